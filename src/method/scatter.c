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

/* sigma_g of (R4): SA(f, 5 %) of the horizontal components of the 83
 * records (study/physfloor.h rule), each record scaled to a larger
 * horizontal PGA of 0.3 g; f = 0.1 x 10^(j/8) Hz. `tailfloors -g`. */
static const double sigma_g_5[] = {1.107, 1.088, 1.023, 0.921, 0.863, 0.829, 0.775, 0.701,
                                   0.682, 0.574, 0.529, 0.434, 0.396, 0.331, 0.311, 0.322,
                                   0.325, 0.323, 0.280, 0.238, 0.217, 0.193};
#define SIGMA_G_N (sizeof sigma_g_5 / sizeof sigma_g_5[0])
#define SIGMA_G_F0_HZ 0.1
#define SIGMA_G_PER_DECADE 8.0

double sl_scatter_sigma_ground(double f_hz)
{
    if (!(f_hz > 0))
        return NAN;
    double x = SIGMA_G_PER_DECADE * log10(f_hz / SIGMA_G_F0_HZ); /* table index */
    if (x <= 0)
        return sigma_g_5[0];
    if (x >= (double)(SIGMA_G_N - 1))
        return sigma_g_5[SIGMA_G_N - 1];
    size_t j = (size_t)x;
    double t = x - (double)j;
    return (1 - t) * sigma_g_5[j] + t * sigma_g_5[j + 1]; /* linear in ln f */
}

double sl_scatter_sigma_of_fc(double f_hz)
{
    double g = sl_scatter_sigma_ground(f_hz);
    return isnan(g) ? NAN : fmin(hypot(g, SL_SCATTER_SIGMA_0), SL_SCATTER_SIGMA_MAX); /* (R4) */
}

/* The spectrum of floor component c the synthesis matches, or NULL. */
static const sl_spectrum *matched(const sl_floor *fl, sl_floor_comp c)
{
    const sl_floor_component *k = &fl->comp[c];
    if (!k->spec || k->nspec == 0)
        return NULL;
    double z = sl_synth_floor_damping(fl, c);
    for (size_t j = 0; j < k->nspec; j++)
        if (fabs(k->spec[j].damping - z) <= SL_FLOOR_DAMPING_TOL)
            return &k->spec[j];
    return NULL;
}

double sl_scatter_fc_hz(const sl_spectrum *const h[2], const double zpa_ms2[2])
{
    double w = 0, wl = 0, best = -1, f_best = NAN; /* (R5) sums; the highest SA */
    for (int c = 0; c < 2; c++) {
        const sl_spectrum *s = h[c];
        const double zpa = zpa_ms2[c];
        if (!s || s->n < 1 || !(zpa > 0))
            return NAN;
        for (size_t j = 0; j < s->n; j++)
            if (s->sa_ms2[j] > best)
                best = s->sa_ms2[j], f_best = s->f_hz[j];
        if (s->n < 2)
            continue;
        const double l0 = log(s->f_hz[0]), l1 = log(s->f_hz[s->n - 1]);
        const size_t m = (size_t)ceil((l1 - l0) / log(10.0) * SL_SCATTER_FC_PER_DECADE) + 1;
        const double h_ln = (l1 - l0) / (double)(m - 1);
        for (size_t q = 0; q < m; q++) { /* trapezoid rule in ln f */
            const int end = q == 0 || q + 1 == m;
            double lf = q + 1 == m ? l1 : l0 + h_ln * (double)q;
            double f = q == 0 ? s->f_hz[0] : q + 1 == m ? s->f_hz[s->n - 1] : exp(lf);
            double e = fmax(sl_spectrum_interp(s, f) / zpa - 1, 0) * (end ? 0.5 : 1.0);
            w += e;
            wl += e * lf;
        }
    }
    return w > 0 ? exp(wl / w) : f_best;
}

double sl_scatter_floor_fc_hz(const sl_floor *fl)
{
    if (!fl)
        return NAN;
    const sl_spectrum *h[2] = {matched(fl, SL_FLOOR_H1), matched(fl, SL_FLOOR_H2)};
    const double zpa[2] = {fl->comp[SL_FLOOR_H1].zpa_ms2, fl->comp[SL_FLOOR_H2].zpa_ms2};
    return sl_scatter_fc_hz(h, zpa);
}

double sl_scatter_sigma_of_floor(const sl_floor *fl)
{
    return sl_scatter_sigma_of_fc(sl_scatter_floor_fc_hz(fl));
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
