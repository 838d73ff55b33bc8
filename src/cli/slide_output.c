/* slide_output.c - the tables and files of `seislide slide`. */
#include "slide_output.h"

#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "io/atomic.h"

const char *slide_status_word(const sl_slide_result *r)
{
    if (r->flags & SL_SLIDE_SKIPPED)
        return "no_sliding";
    if (r->flags & SL_SLIDE_NEVER_STOPS)
        return "never_stops";
    if (r->flags & SL_SLIDE_LIFTOFF)
        return "liftoff";
    return "ok";
}

int slide_write_history(const char *path, const sl_history *h)
{
    sl_error err;
    sl_error_clear(&err);
    sl_atomic *a = sl_atomic_open(path, &err);
    if (!a) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    FILE *f = sl_atomic_file(a);
    fprintf(f, "t_s,ux_m,uy_m,vx_m_s,vy_m_s,fx_over_w,fy_over_w\n");
    for (size_t i = 0; i < h->n; i++)
        fprintf(f, "%.6f,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g\n", h->t_s[i], h->ux_m[i], h->uy_m[i],
                h->vx_ms[i], h->vy_ms[i], h->fx_w[i], h->fy_w[i]);
    if (sl_atomic_commit(a, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}

void slide_report_fit(const sl_set *set, const char *const path[3], const sl_set_fit *fit)
{
    static const char *const tag[3] = {"H1", "H2", "V"};
    const sl_motion *m[3] = {set->h1, set->h2, set->v};
    if (!fit->changed)
        return;
    for (int q = 0; q < 3; q++)
        if (m[q] && fit->n_in[q] != fit->n)
            cli_msg("%s %s: %zu samples (to %.6g s) %s to %zu (to %.6g s)", tag[q], path[q],
                    fit->n_in[q], (double)(fit->n_in[q] - 1) * set->h1->dt_s,
                    fit->truncated ? "cut" : "padded with zeros", fit->n,
                    (double)(fit->n - 1) * set->h1->dt_s);
}

void slide_print_csv(const sl_slide_result *res, size_t n)
{
    printf("mu,peak_m,residual_m,peak_x_m,peak_y_m,t_peak_s,residual_x_m,residual_y_m,"
           "path_m,max_speed_m_s,t_rest_s,slide_time_s,episodes,liftoff_samples,err_est_m,"
           "status\n");
    for (size_t k = 0; k < n; k++) {
        const sl_slide_result *r = &res[k];
        char est[32] = "";
        if (!isnan(r->err_est_m))
            snprintf(est, sizeof est, "%.3g", r->err_est_m);
        printf("%.6g,%.9g,%.9g,%.9g,%.9g,%.4f,%.9g,%.9g,%.9g,%.9g,%.4f,%.4f,%ld,%ld,%s,%s\n",
               r->mu, r->peak_m, r->residual_m, r->peak_x_m, r->peak_y_m, r->t_peak_s,
               r->residual_x_m, r->residual_y_m, r->path_m, r->max_speed_ms, r->t_rest_s,
               r->slide_time_s, r->episodes, r->liftoff_samples, est, slide_status_word(r));
    }
}

/* What the table was computed with: the engine (exact in 1-D), or a reference model. */
static const char *model_words(const char *const path[3], const sl_slide_opts *so)
{
    const int two_d = path[1] != NULL;
    switch (so->model) {
    case SL_MODEL_SMOOTH:
        return two_d ? "2-D coupled, smoothed hysteretic reference model"
                     : "1-D, smoothed hysteretic reference model";
    case SL_MODEL_PLASTIC:
        return two_d ? "2-D coupled, elastic-plastic reference model"
                     : "1-D, elastic-plastic reference model";
    case SL_MODEL_EXACT:
    default:
        return two_d ? "2-D coupled" : (so->up_ratio != 1.0 ? "1-D asymmetric" : "1-D exact");
    }
}

void slide_print_table(const sl_set *set, const char *const path[3], const sl_slide_opts *so,
                       double pga_ms2, double mu_thr, const sl_slide_result *res, size_t n)
{
    printf("# seislide slide: %s%s%s%s%s, %zu samples at dt = %g s\n", path[0],
           path[1] ? " + " : "", path[1] ? path[1] : "", path[2] ? " + V " : "",
           path[2] ? path[2] : "", set->h1->n, set->h1->dt_s);
    printf("# %s, peak horizontal acceleration %.4f g, no sliding for mu >= %.4f\n",
           model_words(path, so), pga_ms2 / SL_G, mu_thr);
    printf("%8s %12s %12s %10s %9s %8s  %s\n", "mu", "peak_mm", "residual_mm", "t_peak_s",
           "path_mm", "episodes", "status");
    for (size_t k = 0; k < n; k++) {
        const sl_slide_result *r = &res[k];
        printf("%8.4f %12.3f %12.3f %10.3f %9.1f %8ld  %s\n", r->mu, 1e3 * r->peak_m,
               1e3 * r->residual_m, r->t_peak_s, 1e3 * r->path_m, r->episodes,
               slide_status_word(r));
    }
}
