/*
 * cmd_bench.c - `seislide bench`: speed against error. study/bench.h
 * measures; bench_report.c prints the tables to stdout and
 * docs/performance.md (--out) at once.
 */
#include <stddef.h>
#include <string.h>

#include "bench_report.h"
#include "cli.h"
#include "io/atomic.h"
#include "study/bench.h"
#include "study/bench_engine.h"
#include "study/bench_rock.h"
#include "study/bench_rockf.h"

static const char bench_help[] =
    "usage: seislide bench [--shared DIR] [--repeat N] [--out FILE] [--quick]\n"
    "\n"
    "Speed against error: the engine, the reference models (smoothed Park-Wen with\n"
    "GSL stiff solvers; elastic-plastic Newmark), response spectra and the rocking\n"
    "engine (cost per run against its error), on the\n"
    "three-component records in DIR/records (default ../shared; synthesized motions\n"
    "when absent). Errors of the peak vector sliding displacement are against the\n"
    "converged Coulomb solution (engine at %u sub-steps, checked against %u).\n"
    "Prints the tables and writes them to FILE (default docs/performance.md).\n"
    "--quick skips the slowest reference-model settings.\n";

typedef struct bench_args {
    const char *shared, *out;
    unsigned long repeat;
    int quick;
} bench_args;

#define A(f) .off = offsetof(bench_args, f)
static const cli_opt bench_opts[] = {
    {"shared", CLI_OPT_ID, "DIR", NULL, .kind = CLI_STRING, A(shared)},
    {"repeat", CLI_OPT_ID + 1, "N", NULL, .kind = CLI_COUNT1, A(repeat)},
    {"out", CLI_OPT_ID + 2, "FILE", NULL, .kind = CLI_STRING, A(out)},
    {"quick", CLI_OPT_ID + 3, NULL, NULL, .kind = CLI_FLAG, A(quick)},
};

static void progress(void *ctx, const char *msg)
{
    (void)ctx;
    fprintf(stderr, "seislide: bench: %s\n", msg);
}

int cmd_bench(int argc, char **argv)
{
    bench_args a = {"../shared", "docs/performance.md", 3, 0};
    int rc = cli_parse("bench", bench_opts, CLI_NOPTS(bench_opts), argc, argv, &a, NULL);
    if (rc == CLI_OPT_HELP) {
        printf(bench_help, SL_BENCH_REF_SUBSTEPS, SL_BENCH_REF_CHECK_SUBSTEPS);
        return CLI_EXIT_OK;
    }
    if (rc || (rc = cli_no_operands("bench", argc, argv)))
        return rc;
    sl_error err;
    sl_error_clear(&err);
    sl_atomic *af = sl_atomic_open(a.out, &err); /* fail before the long runs */
    sl_bench_opts bo = {a.shared, a.repeat, a.quick, progress, NULL};
    sl_bench *b = af ? sl_bench_run(&bo, &err) : NULL;
    if (!b) {
        sl_atomic_abort(af);
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    bench_report(sl_atomic_file(af), b, a.repeat);
    sl_bench_free(b);
    progress(NULL, "rocking engine: cost per run against its error");
    sl_bench_rock br;
    if (sl_bench_rock_run(a.repeat, &br, &err)) {
        sl_atomic_abort(af);
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    bench_report_rock(sl_atomic_file(af), &br);
    progress(NULL, "rocking on a floor: cost per item and of the lookup");
    sl_bench_rockf bf;
    if (sl_bench_rockf_run(&bf, &err)) {
        sl_atomic_abort(af);
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    bench_report_rockf(sl_atomic_file(af), &bf);
    progress(NULL, "engine: work-precision on every record set, ratio to the floor");
    sl_bench_wp *w = sl_bench_wp_run(a.shared, a.repeat, &err);
    if (!w) {
        sl_atomic_abort(af);
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    bench_report_engine_wp(sl_atomic_file(af), w);
    sl_bench_wp_free(w);
    if (sl_atomic_commit(af, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    fprintf(stderr, "seislide: bench: wrote %s\n", a.out);
    return CLI_EXIT_OK;
}
