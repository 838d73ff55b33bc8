/* cmd_run.c - `seislide run`: floor response spectra in, the clearance workbook and CSV
 * tables out (analysis.h; report/deliver.h writes the folder). Options and help: one table. */
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "analysis.h"
#include "cli.h"
#include "outdir.h"
#include "run_report.h"
#include "report/deliver.h"

#include "core/standards.h"

/* Everything the options set (cli.h: one table, parsed and documented from it). */
typedef struct run_args {
    const char *out;
    int quiet, motions, force;
    unsigned long sets, substeps, max_sets;
    double rel_se, abs_se_mm;
    cli_mu mu;
    double accuracy, created;
    uint64_t seed;
    sl_clearance_policy policy;
    sl_report_project project;
} run_args;
#define A(f) .off = offsetof(run_args, f)
enum { O_SETS = CLI_OPT_ID, O_SEED, O_MU_RANGE, O_MU, O_POLICY, O_ACC, O_SUB, O_MOTIONS,
       O_CREATED, O_FORCE, O_PROJECT, O_DOCUMENT, O_REVISION, O_PREPARED, O_CHECKED, O_DATE,
       O_REL_SE, O_ABS_SE, O_MAX_SETS };
static const cli_opt opts[] = {
    {"output", 'o', "DIR", "output folder (default output/); the run writes a fresh folder and\n"
     "swaps it in: DIR must be new, empty or hold only seislide outputs", .kind = CLI_STRING,
     A(out)},
    {"quiet", 'q', NULL, "no progress on stderr", .kind = CLI_FLAG, A(quiet)},
    {"sets", O_SETS, "N", "a fixed number of motion sets per floor (ASCE 43-05: >= %g);\n"
     "default: sets are added until converged (docs/run.md, Convergence):",
     {SL_NLTHA_MIN_SETS}, .kind = CLI_COUNT1, A(sets)},
    {"rel-se", O_REL_SE, "R", "target standard error of the design value, relative (default %g),",
     {SL_ANALYSIS_REL_SE}, .kind = CLI_NONNEG, A(rel_se)},
    {"abs-se", O_ABS_SE, "MM", "or absolute, mm (default %g), whichever is larger, at every mu",
     {1e3 * SL_ANALYSIS_ABS_SE_M}, .kind = CLI_NONNEG, A(abs_se_mm)},
    {"max-sets", O_MAX_SETS, "N", "stop there when not converged; the floor is flagged (default %g)",
     {SL_ANALYSIS_MAX_SETS}, .kind = CLI_COUNT1, A(max_sets)},
    {"seed", O_SEED, "S", "random seed (default 1); a floor's seed also depends on its\n"
     "spectra's numbers (or its 'seed ='), never on its name or the other floors",
     .kind = CLI_CALL},
    {"mu-range", O_MU_RANGE, "A:B:S", "friction grid (default " SL_MU_GRID_TEXT ")",
     .kind = CLI_MU_RANGE, A(mu)},
    {"mu", O_MU, "LIST", "explicit friction values, increasing", .kind = CLI_MU_LIST, A(mu)},
    {"policy", O_POLICY, "P", "required clearance: nltha (default), asce or envelope",
     .kind = CLI_CALL},
    {"accuracy", O_ACC, "E", "relative error of every NLTHA peak the 2-D engine aims at (its\n"
     "rtol, default 0.001, at most 0.1; docs/integrators.md)", .kind = CLI_POSITIVE, A(accuracy)},
    {"substeps", O_SUB, "N", "expert: N fixed 2-D sub-steps per sample, no error control",
     .kind = CLI_COUNT1, A(substeps)},
    {"motions", O_MOTIONS, NULL, "also write every motion to DIR/motions/<floor id>/*.AT2",
     .kind = CLI_FLAG, A(motions)},
    {"created", O_CREATED, "EPOCH", "workbook date, s since 1970 (default SOURCE_DATE_EPOCH,\nelse now)",
     .kind = CLI_CALL},
    {"force", O_FORCE, NULL, "run a floor whose horizontal ZPA is outside %g-%g g (warning)",
     {SL_FLOOR_ZPA_MIN_G, SL_FLOOR_ZPA_MAX_G}, .kind = CLI_FLAG, A(force)},
    {.head = "title block of the workbook (Lookup, Summary, page headers, CSV comments):"},
    {"project", O_PROJECT, "TEXT", "project", .kind = CLI_STRING, A(project.project)},
    {"document", O_DOCUMENT, "TEXT", "document number", .kind = CLI_STRING, A(project.document)},
    {"revision", O_REVISION, "TEXT", "revision", .kind = CLI_STRING, A(project.revision)},
    {"prepared", O_PREPARED, "TEXT", "prepared by", .kind = CLI_STRING, A(project.prepared)},
    {"checked", O_CHECKED, "TEXT", "checked by", .kind = CLI_STRING, A(project.checked)},
    {"date", O_DATE, "TEXT", "date (default: the workbook date)", .kind = CLI_STRING,
     A(project.date)}};

/* The options that need more than their kind. */
static int take(void *dst, int key, const char *v)
{
    run_args *a = dst;
    unsigned long ul = 0;
    int p = key == O_POLICY ? sl_clearance_policy_parse(v) : 0;
    int bad = key == O_SEED ? cli_parse_ulong(v, &ul) : key == O_POLICY ? p < 0
              : cli_parse_double(v, &a->created) || a->created < 0 || a->created > 4e12;
    if (bad)
        return cli_usage("run", "bad value '%s' for --%s", v, key == O_SEED ? "seed"
                         : key == O_POLICY ? "policy (nltha, asce, envelope)" : "created");
    if (key == O_SEED)
        a->seed = ul;
    if (key == O_POLICY)
        a->policy = (sl_clearance_policy)p;
    return CLI_EXIT_OK;
}

static void help(void)
{
    puts("usage: seislide run [FLOOR.ini ... | DIR] [options]\n\nThe main job: for every floor "
         "response spectrum file (default: every *.ini in floors/),\nsynthesize motion sets, "
         "compute the peak vector sliding displacement of each by\nNLTHA over the friction grid "
         "and the ASCE/SEI 43-05 estimate, the design sliding\nspectra, every range where ASCE "
         "is below NLTHA, and the required clearance; write\nDIR/" SL_DELIVER_WORKBOOK " and "
         "the CSV files (docs/run.md).\n\noptions:");
    cli_help_options(stdout, opts, CLI_NOPTS(opts), 22);
    puts("\nExit status: 0 success, 1 bad input or failed run (the output folder unchanged),\n"
         "2 usage error.");
}

int cmd_run(int argc, char **argv)
{
    const char *sde = getenv("SOURCE_DATE_EPOCH"), *dflt[] = {"floors"};
    double v;
    run_args a = {.out = "output", .sets = 0, .accuracy = 1e-3, .seed = 1,
                  .rel_se = SL_ANALYSIS_REL_SE, .abs_se_mm = 1e3 * SL_ANALYSIS_ABS_SE_M,
                  .max_sets = SL_ANALYSIS_MAX_SETS,
                  .created = (sde && !cli_parse_double(sde, &v) && v >= 0) ? v : (double)time(NULL)};
    char cmdline[8192] = "seislide", date[32], warn[4096];
    static sl_deliver_inputs in; /* large: not on the stack */
    sl_analysis *an[SL_DELIVER_MAX_FLOORS] = {NULL};
    sl_atomic_dir *out = NULL;
    sl_error err;
    sl_error_clear(&err);
    int rc = cli_parse("run", opts, CLI_NOPTS(opts), argc, argv, &a, take);
    if (rc == CLI_OPT_HELP)
        help();
    if (rc || (!a.mu.v && cli_parse_range(SL_MU_GRID_TEXT, &a.mu.v, &a.mu.n)))
        goto done;
    if (!(a.rel_se < 1) || !(a.rel_se > 0 || a.abs_se_mm > 0) || !isfinite(a.abs_se_mm) ||
        a.max_sets < 2 || a.max_sets > 10000) {
        rc = cli_usage("run", "--rel-se must be below 1, --rel-se and --abs-se not both 0, "
                       "--max-sets from 2 to 10000");
        goto done;
    }
    rc = CLI_EXIT_ERROR;
    /* every floor read and checked, and the output folder made, before any long work */
    int nargs = optind < argc ? argc - optind : 1;
    if (sl_deliver_inputs_load(&in, optind < argc ? (const char *const *)argv + optind : dflt,
                               (size_t)nargs, a.force, warn, sizeof warn, &err))
        goto fail;
    if (warn[0])
        cli_msg("run: warning (--force): %s", warn);
    if (!(out = cli_outdir_open(a.out, sl_report_owns_name, &err)))
        goto fail;
    sl_analysis_opts ao;
    sl_analysis_opts_default(&ao);
    ao.substeps = (unsigned)a.substeps; /* 0: error-controlled by rtol (docs/integrators.md) */
    ao.rtol = a.accuracy;
    ao.n_sets = a.sets; /* 0: adaptive */
    ao.rel_se = a.rel_se;
    ao.abs_se_m = 1e-3 * a.abs_se_mm;
    ao.max_sets = a.max_sets;
    ao.seed = a.seed;
    ao.mu = a.mu.v;
    ao.n_mu = a.mu.n;
    ao.policy = a.policy;
    run_progress pc;
    ao.progress = run_progress_cb;
    ao.progress_ctx = &pc;
    if (a.sets > 0 && a.sets < SL_NLTHA_MIN_SETS && !a.quiet)
        cli_msg("run: warning: %lu motion sets per floor; ASCE/SEI 43-05 asks for at least %d",
                a.sets, SL_NLTHA_MIN_SETS);
    for (size_t i = 0; i < in.n; i++) {
        pc = (run_progress){a.quiet, i + 1, in.n, in.floors[i]->name, NULL, -100};
        if (!(an[i] = sl_analysis_run(in.floors[i], &ao, &err)))
            goto fail;
        if (!a.quiet)
            run_report_floor(i + 1, in.n, in.floors[i]->name, an[i], ao.n_mu);
    }
    for (int i = 0; i < argc && strlen(cmdline) + strlen(argv[i]) + 2 < sizeof cmdline; i++)
        strcat(strcat(cmdline, " "), argv[i]);
    sl_deliver_opts dop = {.version = "seislide " SEISLIDE_VERSION, .command_line = cmdline,
                           .created = (time_t)a.created, .project = a.project, .seed = a.seed,
                           .substeps = ao.substeps, .accuracy = a.accuracy,
                           .write_motions = a.motions};
    if (!dop.project.date && strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop.created)))
        dop.project.date = date;
    cli_outdir_writing(); /* a signal now is noted, and the fresh folder dropped */
    if (sl_deliver_write(sl_atomic_dir_path(out), in.n, (const sl_floor *const *)in.floors,
                         in.idp, (const sl_analysis *const *)an, &dop, &err) ||
        cli_outdir_commit(&out, &err))
        goto fail;
    if (!a.quiet)
        cli_msg("run: wrote %s/%s and the CSV files", a.out, SL_DELIVER_WORKBOOK);
    rc = CLI_EXIT_OK;
    goto done;
fail:
    if (!cli_outdir_interrupted())
        cli_print_error(&err);
done:
    free(a.mu.v);
    for (size_t i = 0; i < in.n; i++)
        sl_analysis_free(an[i]);
    sl_deliver_inputs_free(&in);
    cli_outdir_finish(out);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
