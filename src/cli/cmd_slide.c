/* cmd_slide.c - `seislide slide`: one motion set, many friction coefficients.
 * Parses (slide_opts.h: one option table), reads the set (io/setdir.h),
 * calls slide/slide.h, prints (slide_output.h). */
#include <stdlib.h>

#include "cli.h"
#include "outdir.h"
#include "io/setdir.h"
#include "slide/slide.h"
#include "slide_opts.h"
#include "slide_output.h"

int cmd_slide(int argc, char **argv)
{
    slide_args a;
    sl_set set = {NULL, NULL, NULL};
    sl_set_fit fit;
    sl_slide_result *res = NULL;
    sl_history *hist = NULL;
    sl_error err;
    sl_error_clear(&err);
    int rc = slide_parse(argc, argv, &a);
    if (rc || (a.history && (rc = cli_outdir_apart("slide", "--history", a.history, a.path, 3))))
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
    if (!(res = calloc(a.mu.n, sizeof *res))) {
        cli_msg("out of memory");
        goto done;
    }
    if (a.history ? sl_slide_history(&set, a.mu.v[0], &a.so, res, &hist, &err)
                  : sl_slide_batch(&set, 1, a.mu.v, a.mu.n, &a.so, res, &err)) {
        cli_print_error(&err);
        goto done;
    }
    if (a.history && slide_write_history(a.history, hist) != CLI_EXIT_OK)
        goto done;
    if (a.csv)
        slide_print_csv(res, a.mu.n);
    else
        slide_print_table(&set, a.path, &a.so, sl_set_pga_h(&set),
                          sl_slide_mu_threshold(&set, &a.so), res, a.mu.n);
    rc = CLI_EXIT_OK;
done:
    free(a.mu.v);
    free(res);
    sl_history_free(hist);
    sl_set_free_motions(&set);
    return rc == CLI_OPT_HELP ? CLI_EXIT_OK : rc;
}
