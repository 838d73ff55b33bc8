/* design.c - design sliding spectra, crossover and clearance; see design.h. */
#include "method/design.h"

#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "method/asce.h"
#include "core/units.h"

static const char *const policy_names[] = {"nltha", "asce", "envelope"};

const char *sl_clearance_policy_name(sl_clearance_policy p)
{
    return ((int)p >= 0 && p <= SL_CLEARANCE_ENVELOPE) ? policy_names[p] : "unknown";
}

int sl_clearance_policy_parse(const char *s)
{
    for (int i = 0; i <= SL_CLEARANCE_ENVELOPE; i++)
        if (s && !strcmp(s, policy_names[i]))
            return i;
    return -1;
}

void sl_design_input_default(sl_design_input *in)
{
    memset(in, 0, sizeof *in);
    in->g_ms2 = SL_G;
    in->fs_nltha = SL_NLTHA_FS;
    in->fs_asce = SL_ASCE_FS;
    in->cap_factor = SL_DESIGN_CAP_FACTOR;
    in->policy = SL_CLEARANCE_NLTHA;
}

void sl_design_free(sl_design *d)
{
    if (!d)
        return;
    free(d->rows);
    free(d->ranges);
    free(d);
}

static sl_status check(const sl_design_input *in, sl_error *err)
{
    if (in->n_mu == 0 || in->n_sets == 0 || !in->mu || !in->peak_m || !in->pgd_m)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "design: no friction values or no motion sets");
    if (!(in->zpa_h_ms2 > 0) || !isfinite(in->zpa_h_ms2))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "design: horizontal ZPA %g must be > 0",
                            in->zpa_h_ms2);
    if (!(in->g_ms2 > 0) || !(in->fs_nltha > 0) || !(in->fs_asce > 0) || !(in->cap_factor > 0))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "design: factors and g must be > 0");
    for (size_t k = 0; k < in->n_mu; k++) {
        if (!(in->mu[k] >= 0) || !isfinite(in->mu[k]) || (k > 0 && !(in->mu[k] > in->mu[k - 1])))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "design: friction values must be finite, >= 0 and increasing "
                                "(mu[%zu] = %g)", k, in->mu[k]);
    }
    for (size_t i = 0; i < in->n_mu * in->n_sets; i++)
        if (!(in->peak_m[i] >= 0) || !isfinite(in->peak_m[i]))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "design: peak %g is not a finite "
                                "displacement >= 0", in->peak_m[i]);
    for (size_t s = 0; s < in->n_sets; s++)
        if (!(in->pgd_m[s] >= 0) || !isfinite(in->pgd_m[s]))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "design: peak floor displacement %g of "
                                "set %zu is not finite and >= 0", in->pgd_m[s], s + 1);
    return SL_OK;
}

/* Where D_A - D_N changes sign between rows p and q (linear in mu and x);
 * 0 when ASCE is undefined at either row (no place to interpolate). */
static int sign_change(const sl_design_row *p, const sl_design_row *q, double *mu, double *x)
{
    if (!isfinite(p->asce_design_m) || !isfinite(q->asce_design_m))
        return 0;
    double fp = p->asce_design_m - p->nltha_design_m;
    double fq = q->asce_design_m - q->nltha_design_m;
    if (!(fp != fq))
        return 0;
    double w = fp / (fp - fq);
    *mu = p->mu + w * (q->mu - p->mu);
    *x = p->x + w * (q->x - p->x);
    return 1;
}

sl_design *sl_design_compute(const sl_design_input *in, sl_error *err)
{
    if (check(in, err))
        return NULL;
    sl_design *d = calloc(1, sizeof *d);
    double *col = malloc(in->n_sets * sizeof *col);
    if (!d || !col || !(d->rows = calloc(in->n_mu, sizeof *d->rows)) ||
        !(d->ranges = calloc(in->n_mu, sizeof *d->ranges))) {
        free(col);
        sl_design_free(d);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "design: out of memory");
        return NULL;
    }
    d->n = in->n_mu;
    d->zpa_h_ms2 = in->zpa_h_ms2;
    d->policy = in->policy;
    d->n_sets = in->n_sets;
    d->fs_nltha = in->fs_nltha;
    d->fs_asce = in->fs_asce;
    d->cap_factor = in->cap_factor;
    d->cap_m = in->cap_factor * gsl_stats_mean(in->pgd_m, 1, in->n_sets);
    for (size_t k = 0; k < in->n_mu; k++) {
        sl_design_row *r = &d->rows[k];
        for (size_t s = 0; s < in->n_sets; s++)
            col[s] = in->peak_m[s * in->n_mu + k];
        r->mu = in->mu[k];
        r->x = in->mu[k] * in->g_ms2 / in->zpa_h_ms2;
        r->nltha_mean_m = gsl_stats_mean(col, 1, in->n_sets);
        r->nltha_sd_m = in->n_sets > 1 ? gsl_stats_sd_m(col, 1, in->n_sets, r->nltha_mean_m) : 0.0;
        r->cap_m = d->cap_m;
        if (in->no_slide && in->no_slide[k])
            r->flags |= SL_DESIGN_NO_SLIDING;
        double dn = in->fs_nltha * r->nltha_mean_m;
        if (dn > d->cap_m) {
            dn = d->cap_m;
            r->flags |= SL_DESIGN_NLTHA_CAPPED;
        }
        r->nltha_design_m = dn;
        double best = in->asce_best_m ? in->asce_best_m[k] : NAN;
        r->asce_best_m = best;
        if (isfinite(best)) {
            double da = in->fs_asce * best;
            if (da > d->cap_m) {
                da = d->cap_m;
                r->flags |= SL_DESIGN_ASCE_CAPPED;
            }
            r->asce_design_m = da;
            if (da < dn)
                r->flags |= SL_DESIGN_UNCONSERVATIVE;
        } else {
            r->asce_design_m = NAN;
            r->flags |= SL_DESIGN_ASCE_UNDEFINED;
        }
        switch (in->policy) {
        case SL_CLEARANCE_ASCE: r->clearance_m = r->asce_design_m; break;
        case SL_CLEARANCE_ENVELOPE:
            r->clearance_m = isfinite(r->asce_design_m) ? fmax(dn, r->asce_design_m) : dn;
            break;
        default: r->clearance_m = dn; break;
        }
    }
    free(col);
    /* ranges where ASCE < NLTHA, and the first crossing from below */
    d->crossover_x = d->crossover_mu = NAN;
    for (size_t k = 0; k < d->n; k++) {
        const sl_design_row *r = &d->rows[k];
        if (!(r->flags & SL_DESIGN_UNCONSERVATIVE))
            continue;
        size_t e = k;
        while (e + 1 < d->n && (d->rows[e + 1].flags & SL_DESIGN_UNCONSERVATIVE))
            e++;
        sl_design_range *g = &d->ranges[d->n_ranges++];
        g->x_from = d->rows[k].x;
        g->x_to = d->rows[e].x;
        g->mu_lo = d->rows[k].mu;
        g->x_lo = d->rows[k].x;
        g->open_lo = !(k > 0 && sign_change(&d->rows[k - 1], &d->rows[k], &g->mu_lo, &g->x_lo));
        g->mu_hi = d->rows[e].mu;
        g->x_hi = d->rows[e].x;
        g->open_hi =
            !(e + 1 < d->n && sign_change(&d->rows[e], &d->rows[e + 1], &g->mu_hi, &g->x_hi));
        /* the crossover (the study's sense): the end of an unconservative range
         * that starts at the lowest mu of the grid */
        if (k == 0 && e + 1 < d->n && isfinite(d->rows[e + 1].asce_design_m)) {
            /* D_A - D_N: negative at e, >= 0 at e + 1: linear interpolation in x */
            const sl_design_row *p = &d->rows[e], *q = &d->rows[e + 1];
            double fp = p->asce_design_m - p->nltha_design_m;
            double fq = q->asce_design_m - q->nltha_design_m;
            double w = fp / (fp - fq);
            d->has_crossover = 1;
            d->crossover_x = p->x + w * (q->x - p->x);
            d->crossover_mu = p->mu + w * (q->mu - p->mu);
        }
        k = e;
    }
    return d;
}

double sl_design_clearance_at(const sl_design *d, double mu)
{
    if (!d || d->n == 0 || !(mu >= d->rows[0].mu) || !(mu <= d->rows[d->n - 1].mu))
        return NAN;
    for (size_t k = 0; k + 1 < d->n; k++) {
        const sl_design_row *p = &d->rows[k], *q = &d->rows[k + 1];
        if (mu <= q->mu) {
            double w = (mu - p->mu) / (q->mu - p->mu);
            return p->clearance_m + w * (q->clearance_m - p->clearance_m);
        }
    }
    return d->rows[d->n - 1].clearance_m;
}
