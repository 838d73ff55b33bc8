/* cmd_run.c - `seislide run`: floor response spectra in, the clearance workbook and CSV
 * tables out (analysis.h; report/deliver.h writes the folder). Options and help: one
 * table (run_opts.h); messages on stderr: run_report.h. */
#include <stddef.h>
#include <stdlib.h>
#include <time.h>

#include "analysis.h"
#include "cli.h"
#include "outdir.h"
#include "report/deliver.h"
#include "run_opts.h"
#include "run_report.h"

#include "core/standards.h"

int cmd_run(int argc, char **argv)
{
    const char *dflt[] = {"floors"};
    char cmdline[8192], date[32], warn[4096];
    static sl_deliver_inputs in; /* large: not on the stack */
    sl_analysis *an[SL_DELIVER_MAX_FLOORS] = {NULL};
    sl_atomic_dir *out = NULL;
    sl_error err;
    sl_error_clear(&err);
    run_args a;
    int rc = run_parse(argc, argv, &a);
    if (rc)
        goto done;
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
    sl_analysis_opts *ao = &a.ao; /* rel_se, rtol, seed, policy: set by the options */
    ao->substeps = (unsigned)a.substeps; /* 0: error-controlled by rtol (docs/integrators.md) */
    ao->n_sets = a.sets; /* 0: adaptive */
    ao->abs_se_m = 1e-3 * a.abs_se_mm;
    ao->max_sets = a.max_sets;
    ao->mu = a.mu.v;
    ao->n_mu = a.mu.n;
    run_progress pc;
    ao->progress = run_progress_cb;
    ao->progress_ctx = &pc;
    if (a.sets > 0 && a.sets < SL_NLTHA_MIN_SETS && !a.quiet)
        cli_msg("run: warning: %lu motion sets per floor; ASCE/SEI 43-05 asks for at least %d",
                a.sets, SL_NLTHA_MIN_SETS);
    for (size_t i = 0; i < in.n; i++) {
        pc = (run_progress){a.quiet, i + 1, in.n, in.floors[i]->name, NULL, -100};
        if (!(an[i] = sl_analysis_run(in.floors[i], ao, &err)))
            goto fail;
        if (!a.quiet)
            run_report_floor(i + 1, in.n, in.floors[i]->name, an[i], ao->n_mu);
        if (run_report_checks(i + 1, in.n, in.floors[i], an[i], a.accept_failed))
            goto done; /* failed motions: message printed, nothing written (rc 1) */
    }
    cli_command_line(cmdline, sizeof cmdline, argc, argv);
    sl_deliver_opts *dop = &a.dop; /* version, write_motions, project: set by run_parse */
    dop->command_line = cmdline;
    dop->created = (time_t)a.created;
    dop->seed = ao->seed;
    dop->substeps = ao->substeps;
    dop->accuracy = ao->rtol;
    if (!dop->project.date && strftime(date, sizeof date, "%Y-%m-%d", gmtime(&dop->created)))
        dop->project.date = date;
    cli_outdir_writing(); /* a signal now is noted, and the fresh folder dropped */
    if (sl_deliver_write(sl_atomic_dir_path(out), in.n, (const sl_floor *const *)in.floors,
                         in.idp, (const sl_analysis *const *)an, dop, &err) ||
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
