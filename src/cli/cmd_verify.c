/* cmd_verify.c - `seislide verify`: the verification problems of
 * verify/verify.h run inside the installed program, one line each, and the
 * record an engineer signs (verify_output.c; docs/verification.md). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "outdir.h"
#include "signal/spectrum.h"
#include "signal/spectrum_kernel.h"
#include "slide/kernel2d.h"
#include "verify/verify.h"
#include "verify_output.h"

/* The flags the program was compiled with (Makefile: FP, OPT, CFLAGS). */
#ifndef SL_BUILD_FLAGS
#define SL_BUILD_FLAGS "unknown (built outside the Makefile)"
#endif

static const char verify_head[] =
    "usage: seislide verify [-o DIR] [--checked-by NAME] [--quick] [--baseline]\n"
    "\n"
    "Verification of this installed program on this machine: a fixed set of\n"
    "problems (the engine, the reference models, response spectra, RG 1.60,\n"
    "ASCE/SEI 43-05, synthesis, statistics, input reading, the workbook's\n"
    "Lookup), each against a reference that does not come from the program: a\n"
    "closed form, a value of a guide's table, a hand calculation\n"
    "(docs/verification.md). No source tree, network or recorded motion is\n"
    "needed. One line per problem, then 'N passed, M failed'.\n"
    "\n";

static const char verify_tail[] =
    "\n"
    "With -o, DIR/verification.csv (columns area, problem, checks, reference,\n"
    "reference_source, computed, error, tolerance, tolerance_basis, verdict) and\n"
    "DIR/verification.xlsx, a printable record with the program version, the\n"
    "build, the vector instances, the host, the date, the checker and signature\n"
    "lines. DIR is created when absent; other files in it are left alone.\n"
    "Exit status: 0 every problem passed, 1 a problem failed or the record could\n"
    "not be written, 2 usage error.\n";

enum { OPT_CHECKED = CLI_OPT_ID, OPT_QUICK, OPT_BASELINE };

typedef struct verify_args {
    const char *out, *checked_by;
    int quick, baseline;
} verify_args;

#define A(f) .off = offsetof(verify_args, f)
static const cli_opt verify_opts[] = {
    {"output", 'o', "DIR", "write the record into DIR (created when absent)", .kind = CLI_STRING,
     A(out)},
    {"checked-by", OPT_CHECKED, "NAME", "the engineer who runs the check, for the record",
     .kind = CLI_STRING, A(checked_by)},
    {"quick", OPT_QUICK, NULL, "the quick subset (one problem or more per area)",
     .kind = CLI_FLAG, A(quick)},
    {"baseline", OPT_BASELINE, NULL,
     "use the baseline vector instances (SSE2) of the engine and the\n"
     "spectra even where the CPU has AVX2: both must give the same verdicts",
     .kind = CLI_FLAG, A(baseline)},
};

static const cli_command verify_cmd = {"verify", verify_head, verify_tail, verify_opts,
                                       CLI_NOPTS(verify_opts), 22, NULL, NULL, 0};

static void on_done(void *ctx, const sl_verify_result *r, size_t k, size_t total)
{
    (void)ctx;
    (void)k;
    (void)total;
    const sl_verify_problem *p = r->problem;
    printf("%s %-8s %-4s %s: computed %s, reference %s, error %s, tolerance %s%s%s\n",
           r->pass ? "pass" : "FAIL", p->area, p->id, p->checks, r->computed, r->reference,
           r->error_text, r->tolerance_text, r->status != SL_OK ? "; not computed: " : "",
           r->status != SL_OK ? r->msg : "");
    fflush(stdout);
}

/* "gcc 14.2.0" or the compiler's own version string. */
static void compiler_text(char *buf, size_t n)
{
#if defined(__clang__)
    snprintf(buf, n, "clang %s", __clang_version__);
#elif defined(__GNUC__)
    snprintf(buf, n, "gcc %s", __VERSION__);
#else
    snprintf(buf, n, "unknown compiler");
#endif
}

/* "NAME (Linux 6.1, x86_64, CPU model)". */
static void host_text(char *buf, size_t n)
{
    struct utsname u;
    char cpu[256] = "";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[512];
        while (fgets(line, sizeof line, f))
            if (!strncmp(line, "model name", 10)) {
                const char *c = strchr(line, ':');
                if (c) {
                    snprintf(cpu, sizeof cpu, ", %s", c + 2);
                    cpu[strcspn(cpu, "\n")] = '\0';
                }
                break;
            }
        fclose(f);
    }
    if (uname(&u) == 0)
        snprintf(buf, n, "%s (%s %s, %s%s)", u.nodename, u.sysname, u.release, u.machine, cpu);
    else
        snprintf(buf, n, "unknown host%s", cpu);
}

/* The scratch folder the input problems write into: TMPDIR or /tmp. */
static char *scratch_make(void)
{
    const char *t = getenv("TMPDIR");
    char tmpl[1100];
    snprintf(tmpl, sizeof tmpl, "%s/seislide-verify-XXXXXX", t && *t ? t : "/tmp");
    char *d = mkdtemp(tmpl);
    return d ? strdup(d) : NULL;
}

int cmd_verify(int argc, char **argv)
{
    verify_args a = {NULL, NULL, 0, 0};
    int rc = cli_command_parse(&verify_cmd, argc, argv, &a);
    if (rc)
        return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
    /* the record's folder: made and marked as every output folder (outdir.h) */
    sl_error err;
    sl_error_clear(&err);
    sl_atomic_dir *outd = NULL;
    if (a.out && !(outd = cli_outdir_open(a.out, sl_build_id(), NULL, &err))) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    if (a.baseline)
        cli_kernels_baseline();
    size_t n = 0, n_run = 0, n_pass = 0, n_fail = 0;
    const sl_verify_problem *tab = sl_verify_problems(&n);
    sl_verify_result *res = calloc(n, sizeof *res);
    char *scratch = scratch_make();
    if (!res || !scratch) {
        cli_msg(!res ? "out of memory" : "cannot create a scratch folder in TMPDIR or /tmp");
        free(res);
        free(scratch);
        cli_outdir_finish(outd);
        return CLI_EXIT_ERROR;
    }
    verify_info info;
    memset(&info, 0, sizeof info);
    snprintf(info.version, sizeof info.version, "%s", sl_build_id());
    compiler_text(info.compiler, sizeof info.compiler);
    snprintf(info.flags, sizeof info.flags, "%s", SL_BUILD_FLAGS);
    snprintf(info.vector, sizeof info.vector, "engine %s, spectra %s%s",
             sl_kernel2d_avx2() ? "AVX2" : "baseline",
             sl_spectrum_kernel_avx2() ? "AVX2" : "baseline",
             a.baseline ? " (--baseline)" : "");
    host_text(info.host, sizeof info.host);
    time_t now = time(NULL);
    strftime(info.date, sizeof info.date, "%Y-%m-%d %H:%M:%S UTC", gmtime(&now));
    info.created = now;
    verify_docs_path(info.docs, sizeof info.docs);
    snprintf(info.checked_by, sizeof info.checked_by, "%s",
             a.checked_by ? a.checked_by : "not given");
    cli_command_line(info.command, sizeof info.command, argc, argv);
    info.quick = a.quick;
    cli_msg("verify%s: %s, %s; %s %s; %s; %s", a.quick ? " --quick" : "", info.version,
            info.date, info.compiler, info.flags, info.vector, info.host);
    sl_verify_ctx ctx = {scratch};
    sl_status st = sl_verify_run(tab, n, a.quick, &ctx, res, &n_run, &n_pass, &n_fail, on_done,
                                 NULL);
    rmdir(scratch);
    free(scratch);
    printf("%zu passed, %zu failed\n", n_pass, n_fail);
    rc = st == SL_OK ? CLI_EXIT_OK : CLI_EXIT_ERROR;
    if (outd) {
        info.n_pass = n_pass;
        info.n_fail = n_fail;
        cli_outdir_writing();
        if (verify_write_record(sl_atomic_dir_path(outd), &info, res, n_run, &err) != SL_OK ||
            cli_outdir_commit(&outd, &err) != SL_OK) {
            cli_print_error(&err);
            rc = CLI_EXIT_ERROR;
        } else {
            cli_msg("verify: wrote %s/verification.csv and %s/verification.xlsx", a.out, a.out);
        }
    }
    free(res);
    cli_outdir_finish(outd);
    if (cli_stdout_done() != CLI_EXIT_OK)
        rc = CLI_EXIT_ERROR;
    return rc;
}
