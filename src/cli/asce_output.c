/* asce_output.c - the input description and the rows of `seislide asce`. */
#include "asce_output.h"

#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "io/setdir.h"

/* The method's input from whichever source, its description and the PGV
 * for Newmark's estimates. Returns 0 or -1 (err filled). */
int asce_make_source(const asce_args *a, sl_asce_source *src, sl_floor **fl, sl_motion *m[3],
                       double *pgv_ms, char *what, size_t nw, sl_error *err)
{
    *pgv_ms = NAN;
    if (!isnan(a->rg_pga_g)) {
        if (sl_asce_input_from_rg160(a->rg_pga_g, src, err))
            return -1;
        snprintf(what, nw, "RG 1.60 horizontal at PGA %g g for H1 and H2, A_v = %g g, peak "
                 "displacement %.4f m (1.4 x 36 in x PGA)", a->rg_pga_g, a->rg_pga_g,
                 src->in.pgd_m);
        return 0;
    }
    if (a->floor) {
        if (!(*fl = sl_floor_load(a->floor, err)) || sl_asce_input_from_floor(*fl, NULL, src, err))
            return -1;
        snprintf(what, nw, "floor '%s' (%s)%s, horizontal ZPA %.4f g, A_v = %.4f g (V zpa%s)",
                 (*fl)->name, a->floor, (*fl)->h2_same_as_h1 ? ", H2 declared same as H1" : "",
                 src->in.zpa_h_ms2 / SL_G, src->in.av_ms2 / SL_G,
                 (*fl)->comp[SL_FLOOR_V].zpa_given ? "" : " from the high-frequency end");
        return 0;
    }
    const char *path[3] = {a->h1, a->h2, a->v};
    sl_set set;
    if (sl_set_read_files(path, &a->ro, a->truncate, &set, NULL, err))
        return -1;
    m[0] = set.h1, m[1] = set.h2, m[2] = set.v; /* the caller frees them */
    if (sl_asce_input_from_set(&set, src, err))
        return -1;
    *pgv_ms = fmax(sl_motion_pgv(m[0]), sl_motion_pgv(m[1]));
    snprintf(what, nw, "motions %s + %s + V %s, PGA %.4f g, A_v = %.4f g, peak displacement "
             "%.4f m (100-40)", path[0], path[1], path[2], src->in.zpa_h_ms2 / SL_G,
             src->in.av_ms2 / SL_G, src->in.pgd_m);
    return 0;
}

/* One result row: CSV, or the aligned table. */
void asce_print_row(const sl_asce_result *r, double nm1, double nm2, int csv)
{
    char st[80];
    sl_asce_status_name(r->flags, st, sizeof st);
    if (csv) {
        printf("%.6g,%.6g,", r->mu, r->mu_e);
        const double v[] = {r->cs_ms2 / SL_G, r->fes_hz, r->delta_best_m, r->delta_design_m};
        for (int i = 0; i < 4; i++)
            cli_put_csv(v[i], 0);
        printf("%s,", st);
        cli_put_csv(r->cap_m, 0);
        cli_put_csv(nm1, 0);
        cli_put_csv(nm2, 1);
        return;
    }
    printf("%8.4f %8.4f %8.4f ", r->mu, r->mu_e, r->cs_ms2 / SL_G);
    cli_put_num("%*.4f", r->fes_hz, 9);
    const char *fmt[] = {"%*.3f", "%*.3f", "%*.1f", "%*.3f", "%*.3f"};
    const double v[] = {1e3 * r->delta_best_m, 1e3 * r->delta_design_m, 1e3 * r->cap_m,
                        1e3 * nm1, 1e3 * nm2};
    const int w[] = {12, 14, 9, 13, 14};
    for (int i = 0; i < 5; i++) {
        putchar(' ');
        cli_put_num(fmt[i], v[i], w[i]);
    }
    printf("  %s\n", st);
}

void asce_print_head(int csv, double fs, const char *what, double pgd_opt_m, int capped)
{
    if (csv) {
        printf("mu,mu_e,cs_g,fes_hz,delta_best_m,delta_design_m,status,cap_m,"
               "newmark_sym_m,newmark_asym_m\n");
    } else {
        printf("# seislide asce: ASCE/SEI 43-05 A.1, FS = %g\n# input: %s\n", fs, what);
        if (!isnan(pgd_opt_m))
            printf("# peak input displacement %.4f m from --pgd\n", pgd_opt_m);
        printf("# cap: %s\n", capped ? "1.5 x peak input displacement"
                              : "none (peak input displacement unknown)");
        printf("%8s %8s %8s %9s %12s %14s %9s %13s %14s  %s\n", "mu", "mu_e", "cs_g", "fes_hz",
               "best_mm", "design_mm", "cap_mm", "newmark_s_mm", "newmark_a_mm", "status");
    }
}
