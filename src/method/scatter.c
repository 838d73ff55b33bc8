#include "method/scatter.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_interp.h>
#include <gsl/gsl_rng.h>

#include "core/gslerr.h"
#include "core/units.h"
#include "io/setdir.h"
#include "slide/slide.h"
#include "synth/synth.h"

#define SCATTER_STREAM 0x7363617474657221ULL /* "scatter!" */

double sl_scatter_sigma_of_floor(const sl_floor *fl)
{
    (void)fl;
    return 0.30;
}

sl_status sl_scatter_factor(uint64_t seed, size_t set, double sigma_ln, double *eps,
                            sl_error *err)
{
    *eps = 1.0;
    if (!(sigma_ln > 0))
        return SL_OK;
    sl_gsl_quiet_begin();
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (rng) {
        gsl_rng_set(rng, sl_synth_stream_seed(seed ^ SCATTER_STREAM, set, SL_SYNTH_H1, 0));
        double z = gsl_cdf_ugaussian_Pinv(gsl_rng_uniform_pos(rng));
        *eps = exp(sigma_ln * z - 0.5 * sigma_ln * sigma_ln); /* (R1) */
    }
    gsl_rng_free(rng);
    sl_gsl_quiet_end(); /* the caller's handler back */
    return rng ? SL_OK
               : sl_error_set(err, SL_ENOMEM, NULL, 0, "scatter: out of memory (GSL's generator)");
}

sl_status sl_set_scaled_h_copy(const sl_set *in, double f, sl_set *out, sl_error *err)
{
    memset(out, 0, sizeof *out);
    int bad = 0;
    const sl_motion *src[3] = {in->h1, in->h2, in->v};
    sl_motion **dst[3] = {&out->h1, &out->h2, &out->v};
    for (int c = 0; c < 3; c++) {
        if (!src[c])
            continue;
        if (!(*dst[c] = sl_motion_copy(src[c])))
            bad = 1;
        else if (c < 2)
            sl_motion_scale(*dst[c], f);
    }
    if (bad) {
        sl_set_free_motions(out);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "scatter: out of memory");
    }
    return SL_OK;
}

struct sl_scatter {
    size_t n_mu, nz, nq, off; /* off = 1 when grid[0] = 0 */
    double *grid;             /* nq friction values */
    double *lng;              /* ln grid[off..nq) */
    double *weps;             /* nz node weights of (R3), w_j eps_j */
    double *x;                /* n_mu x nz: ln(mu_k / eps_j) on the grid; NAN for mu_k = 0 */
};

void sl_scatter_free(sl_scatter *s)
{
    if (!s)
        return;
    free(s->grid);
    free(s->lng);
    free(s->weps);
    free(s->x);
    free(s);
}

sl_scatter *sl_scatter_alloc(double sigma_ln, const double *mu, size_t n_mu, sl_error *err)
{
    if (!(sigma_ln > 0 && sigma_ln <= SL_SCATTER_SIGMA_MAX)) {
        sl_error_set(err, SL_EINVAL, NULL, 0,
                     "scatter: log standard deviation %g outside (0, %g]", sigma_ln,
                     SL_SCATTER_SIGMA_MAX);
        return NULL;
    }
    double lo = INFINITY, hi = 0;
    int has_zero = 0;
    for (size_t k = 0; k < n_mu; k++) {
        if (!(mu[k] >= 0 && isfinite(mu[k]))) {
            sl_error_set(err, SL_EINVAL, NULL, 0, "scatter: friction coefficient %g", mu[k]);
            return NULL;
        }
        if (mu[k] == 0)
            has_zero = 1;
        else
            lo = fmin(lo, mu[k]), hi = fmax(hi, mu[k]);
    }
    const size_t nz = (size_t)lround(2 * SL_SCATTER_ZMAX / SL_SCATTER_DZ) + 1;
    sl_scatter *s = calloc(1, sizeof *s);
    double *eps = malloc(nz * sizeof *eps), *w = malloc(nz * sizeof *w);
    if (!s || !eps || !w)
        goto nomem;
    s->n_mu = n_mu;
    s->nz = nz;
    double wsum = 0; /* sum w eps: E[eps] = 1 exactly */
    for (size_t j = 0; j < nz; j++) {
        double z = -SL_SCATTER_ZMAX + SL_SCATTER_DZ * (double)j;
        eps[j] = exp(sigma_ln * z - 0.5 * sigma_ln * sigma_ln); /* (R1) */
        w[j] = exp(-0.5 * z * z) * (j == 0 || j + 1 == nz ? 0.5 : 1.0);
        wsum += w[j] * eps[j];
    }
    /* log grid from lo / eps_max to hi / eps_min, whole steps of a decade / N */
    size_t nlog = 0;
    const double step = 1.0 / SL_SCATTER_PER_DECADE;
    double l0 = 0;
    if (hi > 0) {
        l0 = floor(log10(lo / eps[nz - 1]) / step) * step;
        double l1 = ceil(log10(hi / eps[0]) / step) * step;
        /* Steffen's interpolation needs a few points (a small sigma and one
         * mu give fewer): widen by a step on both sides until it has them */
        while ((nlog = (size_t)lround((l1 - l0) / step) + 1) <
               gsl_interp_type_min_size(gsl_interp_steffen)) {
            l0 -= step;
            l1 += step;
        }
    }
    s->off = (size_t)has_zero;
    s->nq = nlog + s->off;
    s->grid = malloc((s->nq ? s->nq : 1) * sizeof *s->grid);
    s->lng = malloc((nlog ? nlog : 1) * sizeof *s->lng);
    s->weps = malloc(nz * sizeof *s->weps);
    s->x = malloc((n_mu > 0 ? n_mu * nz : 1) * sizeof *s->x);
    if (!s->grid || !s->lng || !s->weps || !s->x)
        goto nomem;
    if (has_zero)
        s->grid[0] = 0;
    for (size_t q = 0; q < nlog; q++) {
        s->grid[s->off + q] = pow(10.0, l0 + step * (double)q);
        s->lng[q] = log(s->grid[s->off + q]);
    }
    for (size_t j = 0; j < nz; j++)
        s->weps[j] = w[j] / wsum * eps[j];
    for (size_t k = 0; k < n_mu; k++) /* mu = 0: (R2) gives u(eps a) = eps u(0) */
        for (size_t j = 0; j < nz; j++)
            s->x[k * nz + j] = mu[k] == 0 ? NAN
                                          : fmin(fmax(log(mu[k] / eps[j]), s->lng[0]),
                                                 s->lng[nlog - 1]);
    free(eps);
    free(w);
    return s;
nomem:
    free(eps);
    free(w);
    sl_scatter_free(s);
    sl_error_set(err, SL_ENOMEM, NULL, 0, "scatter: out of memory");
    return NULL;
}

const double *sl_scatter_grid(const sl_scatter *s, size_t *n)
{
    *n = s->nq;
    return s->grid;
}

sl_status sl_scatter_mean(const sl_scatter *s, const double *u, double *y, sl_error *err)
{
    const size_t nlog = s->nq - s->off;
    gsl_interp *ip = NULL;
    gsl_interp_accel *acc = NULL;
    sl_status st = SL_OK;
    /* GSL's handler off around its calls (gslerr.h): a failure is a status */
    sl_gsl_quiet_begin();
    if (nlog > 0) { /* u between grid points: Steffen's monotone cubic in ln mu */
        ip = gsl_interp_alloc(gsl_interp_steffen, nlog);
        acc = gsl_interp_accel_alloc();
        if (!ip || !acc)
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "scatter: out of memory");
        else if (gsl_interp_init(ip, s->lng, u + s->off, nlog))
            st = sl_error_set(err, SL_ESOLVER, NULL, 0,
                              "scatter: peaks cannot be interpolated on the friction grid");
    }
    for (size_t k = 0; st == SL_OK && k < s->n_mu; k++) {
        const double *xk = s->x + k * s->nz;
        double sum = 0;
        for (size_t j = 0; j < s->nz; j++) {
            double uk = isnan(xk[j]) ? u[0] : gsl_interp_eval(ip, s->lng, u + s->off, xk[j], acc);
            sum += s->weps[j] * (uk < 0 ? 0.0 : uk); /* (R3); a NaN peak stays NaN */
        }
        y[k] = sum;
    }
    gsl_interp_free(ip);
    gsl_interp_accel_free(acc);
    sl_gsl_quiet_end();
    return st;
}

sl_status sl_scatter_results(const sl_scatter *s, const sl_slide_result *res, size_t n,
                             double *y, double *err_est, sl_error *err)
{
    double *u = malloc(2 * s->nq * sizeof *u);
    sl_status st = u ? SL_OK : sl_error_set(err, SL_ENOMEM, NULL, 0, "scatter: out of memory");
    for (size_t i = 0; i < n && !st; i++) {
        const sl_slide_result *r = res + i * s->nq;
        double *e = u + s->nq;
        for (size_t q = 0; q < s->nq; q++) {
            u[q] = r[q].peak_m;
            e[q] = r[q].err_est_m;
        }
        st = sl_scatter_mean(s, u, y + i * s->n_mu, err);
        if (!st && err_est)
            st = sl_scatter_mean(s, e, err_est + i * s->n_mu, err);
    }
    free(u);
    return st;
}

sl_status sl_scatter_slide_batch(const sl_scatter *s, const sl_set *sets, size_t n,
                                 const sl_slide_opts *so, double *y, double *err_est,
                                 sl_error *err)
{
    if (n == 0)
        return SL_OK;
    sl_slide_result *res = calloc(n * s->nq, sizeof *res);
    sl_status st = !res ? sl_error_set(err, SL_ENOMEM, NULL, 0, "scatter: out of memory")
                        : sl_slide_batch(sets, n, s->grid, s->nq, so, res, err);
    if (!st)
        st = sl_scatter_results(s, res, n, y, err_est, err);
    free(res);
    return st;
}
