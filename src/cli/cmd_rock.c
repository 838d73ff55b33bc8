/* cmd_rock.c - `seislide rock`: one motion set, one block, the 12
 * orientations of its weak axis (or one). Parses (rock_opts.h), reads the
 * set as `slide` does (io/setdir.h, slide_output.h's note on padded or cut
 * components), calls rock/rock.h, prints (rock_output.h). */
#include <stdlib.h>

#include "cli.h"
#include "io/setdir.h"
#include "outdir.h"
#include "rock/rock.h"
#include "rock_opts.h"
#include "rock_output.h"
#include "slide_output.h"

int cmd_rock(int argc, char **argv)
{
    rock_args a;
    sl_set set = {NULL, NULL, NULL};
    sl_set_fit fit;
    sl_rock_history hist = {0};
    double *ah = NULL;
    sl_error err;
    sl_error_clear(&err);
    int rc = rock_parse(argc, argv, &a);
    if (rc || (a.history && (rc = cli_outdir_apart("rock", "--history", a.history, a.path, 3))))
        goto done;
    rc = CLI_EXIT_ERROR;
    if (sl_set_read_files(a.path, &a.ro, a.truncate, &set, &fit, &err)) {
        cli_print_error(&err);
        goto done;
    }
    slide_report_fit(&set, a.path, &fit);
    if (a.scale_g > 0 && !sl_set_scale_pga_h(&set, a.scale_g * SL_G)) {
        cli_msg("%s: cannot scale an all-zero motion to %g g", a.path[0], a.scale_g);
        goto done;
    }
    const size_t n = set.h1->n;
    const sl_rock_block blk = {0.5 * a.base_m, a.cg_m, a.has_restitution ? a.restitution : -1.0};
    double orient[ROCK_N_ORIENT];
    sl_rock_result res[ROCK_N_ORIENT];
    const size_t no = a.has_orientation ? 1 : ROCK_N_ORIENT;
    for (size_t k = 0; k < no; k++)
        orient[k] = a.has_orientation ? a.orientation_deg : ROCK_ORIENT_STEP_DEG * (double)k;
    if (!(ah = malloc(n * sizeof *ah))) {
        cli_msg("out of memory");
        goto done;
    }
    const double *av = set.v ? set.v->acc_ms2 : NULL;
    size_t worst = 0;
    for (size_t k = 0; k < no; k++) {
        sl_rock_project(set.h1->acc_ms2, set.h2 ? set.h2->acc_ms2 : NULL, n, orient[k], ah);
        if (sl_rock_run(&blk, ah, av, n, set.h1->dt_s, 1.0, 1.0, &a.o, &res[k], &err)) {
            cli_print_error(&err);
            goto done;
        }
        if (k && rock_worse(&res[k], &res[worst]))
            worst = k;
    }
    size_t liftoff = 0;
    for (size_t k = 0; k < no; k++)
        liftoff = res[k].liftoff_samples > liftoff ? res[k].liftoff_samples : liftoff;
    if (liftoff)
        cli_msg("warning: g + a_v < 0 at %zu samples: the block would leave the floor, which "
                "the rocking model does not describe (docs/model.md, \"Rocking\")", liftoff);
    if (a.history) {
        sl_rock_project(set.h1->acc_ms2, set.h2 ? set.h2->acc_ms2 : NULL, n, orient[worst], ah);
        sl_rock_result r;
        if (sl_rock_run_history(&blk, ah, av, n, set.h1->dt_s, 1.0, 1.0, &a.o, &r, &hist, &err)) {
            cli_print_error(&err);
            goto done;
        }
        if (rock_write_history(a.history, &hist) != CLI_EXIT_OK)
            goto done;
    }
    if (a.csv) {
        char cmdline[2048];
        cli_command_line(cmdline, sizeof cmdline, argc, argv);
        rock_print_csv(cmdline, orient, res, no);
    } else {
        rock_print_table(&set, a.path, &blk, orient, res, no, worst);
    }
    rc = cli_stdout_done();
done:
    free(ah);
    sl_rock_history_free(&hist);
    sl_set_free_motions(&set);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
