/* rock_output.c - the tables and files of `seislide rock`. */
#include "rock_output.h"

#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "io/atomic.h"

const char *rock_status_word(const sl_rock_result *r)
{
    return r->overturned ? "overturns" : r->tipped ? "tips" : r->uplifted ? "rocks" : "stands";
}

static int rank(const sl_rock_result *r) { return r->overturned ? 2 : r->tipped ? 1 : 0; }

int rock_worse(const sl_rock_result *a, const sl_rock_result *b)
{
    if (rank(a) != rank(b))
        return rank(a) > rank(b);
    return a->peak_theta_over_alpha > b->peak_theta_over_alpha;
}

/* A time or an empty field. */
static void put_time(double t, int last)
{
    if (isfinite(t))
        printf("%.9f", t);
    putchar(last ? '\n' : ',');
}

void rock_print_csv(const char *command, const double *orient_deg, const sl_rock_result *res,
                    size_t n)
{
    printf("# program: seislide %s\n", SEISLIDE_VERSION);
    printf("# content: rocking of a rigid block (Housner 1963), one row per orientation of "
           "its weak axis from H1\n");
    printf("# command: %s\n", command);
    printf("orientation_deg,peak_theta_rad,peak_theta_over_alpha,tipped,overturned,impacts,"
           "uplifted,uplifts,t_uplift_s,t_peak_s,t_tip_s,t_overturn_s,excursion_mm,"
           "liftoff_samples,status\n");
    for (size_t k = 0; k < n; k++) {
        const sl_rock_result *r = &res[k];
        printf("%g,%.9g,%.9g,%d,%d,%zu,%d,%zu,", orient_deg[k], r->peak_theta_rad,
               r->peak_theta_over_alpha, r->tipped, r->overturned, r->impacts, r->uplifted,
               r->uplifts);
        put_time(r->t_uplift_s, 0);
        put_time(r->uplifted ? r->t_peak_s : NAN, 0);
        put_time(r->t_tip_s, 0);
        put_time(r->t_overturn_s, 0);
        printf("%.6g,%zu,%s\n", 1e3 * r->excursion_m, r->liftoff_samples, rock_status_word(r));
    }
}

void rock_print_table(const sl_set *set, const char *const path[3], const sl_rock_block *blk,
                      const double *orient_deg, const sl_rock_result *res, size_t n, size_t k)
{
    const sl_rock_result *r0 = &res[0];
    printf("# seislide rock: %s%s%s%s%s, %zu samples at dt = %g s\n", path[0],
           path[1] ? " + " : "", path[1] ? path[1] : "", path[2] ? " + V " : "",
           path[2] ? path[2] : "", set->h1->n, set->h1->dt_s);
    printf("# block: base %g m, centre of mass at %g m: alpha %.4f rad (b/h %.4f), "
           "p %.4f rad/s, r %.4f%s; uplift from rest at %.4f g (without vertical)\n",
           2 * blk->b_m, blk->h_m, r0->alpha_rad, blk->b_m / blk->h_m, r0->p_rad_s,
           r0->restitution, blk->restitution >= 0 ? "" : " (Housner)", blk->b_m / blk->h_m);
    printf("%15s %14s %12s %12s %8s %11s %10s  %s\n", "orientation_deg", "peak_theta_rad",
           "theta/alpha", "excursion_mm", "impacts", "t_uplift_s", "t_peak_s", "status");
    for (size_t i = 0; i < n; i++) {
        const sl_rock_result *r = &res[i];
        printf("%15g %14.6f %12.4f %12.1f %8zu ", orient_deg[i], r->peak_theta_rad,
               r->peak_theta_over_alpha, 1e3 * r->excursion_m, r->impacts);
        cli_put_num("%*.3f", r->t_uplift_s, 11);
        putchar(' ');
        cli_put_num("%*.3f", r->uplifted ? r->t_peak_s : NAN, 10);
        printf("  %s%s\n", rock_status_word(r), r->liftoff_samples ? " (lift-off)" : "");
    }
    const sl_rock_result *w = &res[k];
    const char *verdict = w->overturned ? "overturns" : w->tipped ? "tips" : "stands";
    printf("verdict: %s; worst orientation %g deg: theta/alpha %.4f", verdict, orient_deg[k],
           w->peak_theta_over_alpha);
    if (w->overturned)
        printf(", overturned at %.3f s", w->t_overturn_s);
    else if (w->tipped)
        printf(", tipped at %.3f s", w->t_tip_s);
    else if (w->uplifted)
        printf(" at %.3f s, excursion %.1f mm", w->t_peak_s, 1e3 * w->excursion_m);
    else
        printf(" (never uplifts)");
    printf("\n");
}

int rock_write_history(const char *path, const sl_rock_history *h)
{
    sl_error err;
    sl_error_clear(&err);
    sl_atomic *a = sl_atomic_open(path, &err);
    if (!a) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    FILE *f = sl_atomic_file(a);
    fprintf(f, "t_s,theta_rad,omega_rad_s,event,omega_before_rad_s\n");
    size_t i = 0, e = 0;
    while (i < h->n || e < h->n_events) {
        if (e < h->n_events && (i >= h->n || h->events[e].t_s <= h->t_s[i])) {
            const sl_rock_event *v = &h->events[e++];
            fprintf(f, "%.9f,%.9g,", v->t_s, v->theta_rad);
            if (isfinite(v->omega_rad_s))
                fprintf(f, "%.9g", v->omega_rad_s);
            fprintf(f, ",%s,", sl_rock_event_name(v->kind));
            if (v->kind == SL_ROCK_EV_IMPACT)
                fprintf(f, "%.9g", v->omega_before_rad_s);
            fputc('\n', f);
        } else {
            fprintf(f, "%.9f,%.9g,%.9g,,\n", h->t_s[i], h->theta_rad[i], h->omega_rad_s[i]);
            i++;
        }
    }
    if (sl_atomic_commit(a, &err)) {
        cli_print_error(&err);
        return CLI_EXIT_ERROR;
    }
    return CLI_EXIT_OK;
}
