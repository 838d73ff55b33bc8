/* spectrum.c - Nigam-Jennings response spectra (see spectrum.h). */
#include "signal/spectrum.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* Largest number of Taylor terms for the series coefficients; with
 * |Z| <= 3 x SL_SPECTRUM_SERIES_WH the terms fall below 1e-18 after ~16. */
#define SERIES_MAX_TERMS 60
/* Stop the series when a term's size is below this (relative to 1, the size
 * of phi0). */
#define SERIES_TOL 1e-18
/* Relative tolerance for deciding that two grid frequencies coincide. */
#define GRID_REL_TOL 1e-12

enum { C11, C12, C21, C22, BU0, BU1, BV0, BV1, NCOEF };

sl_spectrum *sl_spectrum_alloc(size_t n, double damping)
{
    if (n == 0)
        return NULL;
    sl_spectrum *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->f_hz = calloc(n, sizeof *s->f_hz);
    s->sa_ms2 = calloc(n, sizeof *s->sa_ms2);
    if (!s->f_hz || !s->sa_ms2) {
        sl_spectrum_free(s);
        return NULL;
    }
    s->n = n;
    s->damping = damping;
    return s;
}

void sl_spectrum_clear(sl_spectrum *s)
{
    if (!s)
        return;
    free(s->f_hz);
    free(s->sa_ms2);
    s->f_hz = NULL;
    s->sa_ms2 = NULL;
    s->n = 0;
}

void sl_spectrum_free(sl_spectrum *s)
{
    if (!s)
        return;
    sl_spectrum_clear(s);
    free(s);
}

double sl_spectrum_interp(const sl_spectrum *s, double f_hz)
{
    if (!s || s->n == 0 || !(f_hz >= s->f_hz[0]) || !(f_hz <= s->f_hz[s->n - 1]))
        return NAN;
    size_t lo = 0, hi = s->n - 1;
    if (f_hz == s->f_hz[hi])
        return s->sa_ms2[hi];
    while (hi - lo > 1) { /* f_hz[lo] <= f < f_hz[hi] */
        size_t mid = lo + (hi - lo) / 2;
        if (s->f_hz[mid] <= f_hz)
            lo = mid;
        else
            hi = mid;
    }
    if (f_hz == s->f_hz[lo])
        return s->sa_ms2[lo];
    double p = log(s->sa_ms2[hi] / s->sa_ms2[lo]) / log(s->f_hz[hi] / s->f_hz[lo]);
    return s->sa_ms2[lo] * pow(f_hz / s->f_hz[lo], p);
}

void sl_spectrum_opts_default(sl_spectrum_opts *o)
{
    o->steps_per_period = SL_SPECTRUM_STEPS_PER_PERIOD;
    o->free_vibration = 1;
}

double *sl_spectrum_grid(double fmin_hz, double fmax_hz, double per_decade, size_t *n)
{
    *n = 0;
    if (!(fmin_hz > 0) || !isfinite(fmin_hz) || !isfinite(fmax_hz) || fmax_hz < fmin_hz ||
        !(per_decade > 0) || !isfinite(per_decade))
        return NULL;
    double decades = log10(fmax_hz / fmin_hz);
    double k = ceil(per_decade * decades - GRID_REL_TOL * per_decade);
    if (k < 0)
        k = 0;
    if (k > 1e7)
        return NULL;
    size_t m = (size_t)k + 1;
    double *f = malloc(m * sizeof *f);
    if (!f)
        return NULL;
    f[0] = fmin_hz;
    for (size_t i = 1; i + 1 < m; i++)
        f[i] = fmin_hz * pow(10.0, decades * (double)i / k);
    if (m > 1)
        f[m - 1] = fmax_hz;
    *n = m;
    return f;
}

/* ---- recurrence coefficients ---------------------------------------- */

static void coefs_closed(double w, double z, double h, double c[NCOEF])
{
    double sq = sqrt(1.0 - z * z);
    double wd = w * sq;
    double e = exp(-z * w * h);
    double sn = sin(wd * h), cs = cos(wd * h);
    double q = z / sq;
    double w2 = w * w;
    c[C11] = e * (cs + q * sn);
    c[C12] = e * sn / wd;
    c[C21] = -w2 * c[C12];
    c[C22] = e * (cs - q * sn);
    /* x1 = x_p(h) + A (x0 - x_p(0)), u_p = -a/w^2 + 2 z a'/w^3, v_p = -a'/w^2,
     * a' = (a1 - a0)/h. Collect the a0 and a1 terms. */
    double ku = (2.0 * z * (1.0 - c[C11]) / w + c[C12]) / w2;
    double kv = (-2.0 * z * c[C21] / w + c[C22] - 1.0) / w2;
    c[BU0] = c[C11] / w2 - ku / h;
    c[BU1] = -1.0 / w2 + ku / h;
    c[BV0] = c[C21] / w2 - kv / h;
    c[BV1] = kv / h;
}

/* 2x2 row-major product r = a b (r may not alias). */
static void mat2_mul(const double a[4], const double b[4], double r[4])
{
    r[0] = a[0] * b[0] + a[1] * b[2];
    r[1] = a[0] * b[1] + a[1] * b[3];
    r[2] = a[2] * b[0] + a[3] * b[2];
    r[3] = a[2] * b[1] + a[3] * b[3];
}

static void coefs_series(double w, double z, double h, double c[NCOEF])
{
    double x = w * h;
    const double zb[4] = {0.0, x, -x, -2.0 * z * x}; /* balanced w h [0 1; -1 -2z] */
    double p[4] = {1.0, 0.0, 0.0, 1.0};              /* Z^j */
    double phi0[4] = {0}, phi1[4] = {0}, phi2[4] = {0};
    double fj = 1.0; /* j! */
    for (int j = 0; j < SERIES_MAX_TERMS; j++) {
        double f1 = fj * (double)(j + 1), f2 = f1 * (double)(j + 2);
        for (int k = 0; k < 4; k++) {
            phi0[k] += p[k] / fj;
            phi1[k] += p[k] / f1;
            phi2[k] += p[k] / f2;
        }
        double size = fabs(p[0]) + fabs(p[1]) + fabs(p[2]) + fabs(p[3]);
        if (size / fj < SERIES_TOL)
            break;
        double t[4];
        mat2_mul(p, zb, t);
        memcpy(p, t, sizeof t);
        fj *= (double)(j + 1);
    }
    /* Undo the balancing D = diag(w, 1): X = D^-1 X' D. */
    c[C11] = phi0[0];
    c[C12] = phi0[1] / w;
    c[C21] = phi0[2] * w;
    c[C22] = phi0[3];
    c[BU0] = -h * (phi1[1] - phi2[1]) / w;
    c[BU1] = -h * phi2[1] / w;
    c[BV0] = -h * (phi1[3] - phi2[3]);
    c[BV1] = -h * phi2[3];
}

static void coefs_auto(double w, double z, double h, double c[NCOEF])
{
    if (w * h < SL_SPECTRUM_SERIES_WH)
        coefs_series(w, z, h, c);
    else
        coefs_closed(w, z, h, c);
}

sl_status sl_spectrum_coefs(double f_hz, double zeta, double h_s,
                            sl_spectrum_method method, double c[8], sl_error *err)
{
    if (!(f_hz > 0) || !isfinite(f_hz) || !(h_s > 0) || !isfinite(h_s))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: frequency %g Hz and step %g s must be positive",
                            f_hz, h_s);
    if (!(zeta >= 0 && zeta < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: damping %g outside [0, 1)", zeta);
    double w = 2.0 * SL_PI * f_hz;
    switch (method) {
    case SL_SPECTRUM_CLOSED: coefs_closed(w, zeta, h_s, c); break;
    case SL_SPECTRUM_SERIES: coefs_series(w, zeta, h_s, c); break;
    default: coefs_auto(w, zeta, h_s, c); break;
    }
    return SL_OK;
}

/* ---- the stepping kernel -------------------------------------------- */

static sl_status check_args(const double *acc, size_t n, double dt, const double *f,
                            size_t nf, double zeta, const sl_spectrum_opts *o,
                            sl_error *err)
{
    if (!acc || n == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: empty record");
    if (!(dt > 0) || !isfinite(dt))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: time step %g s must be positive",
                            dt);
    if (!(zeta >= 0 && zeta < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: damping %g outside [0, 1)", zeta);
    if (!(o->steps_per_period >= 1) || !isfinite(o->steps_per_period))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: steps per period %g must be at least 1",
                            o->steps_per_period);
    for (size_t j = 0; j < nf; j++) {
        if (!(f[j] > 0) || !isfinite(f[j]))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "spectrum: frequency %g Hz must be positive and finite", f[j]);
        if (!(dt * f[j] * o->steps_per_period <= SL_SPECTRUM_MAX_SUBSTEPS))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "spectrum: %g Hz at dt %g s needs more than %g sub-steps per "
                                "sample",
                                f[j], dt, SL_SPECTRUM_MAX_SUBSTEPS);
    }
    for (size_t i = 0; i < n; i++)
        if (!isfinite(acc[i]))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "spectrum: sample %zu is not finite", i);
    return SL_OK;
}

/* Sub-steps per input step for one frequency. */
static size_t substeps_for(double f, double dt, double spp)
{
    double m = ceil(dt * f * spp);
    return m < 1 ? 1 : (size_t)m;
}

/* Free-vibration sub-steps needed to reach the first extremum: T_d/2. */
static size_t free_steps_for(double f, double zeta, double h)
{
    double td = 1.0 / (f * sqrt(1.0 - zeta * zeta));
    return (size_t)ceil(0.5 * td / h) + 1;
}

/* Workspace: one block of SoA arrays, frequencies permuted so that groups of
 * equal sub-step count are contiguous. */
typedef struct work {
    size_t nf;
    size_t *perm;   /* position -> index into the caller's f_hz */
    size_t *m;      /* sub-steps per input step, per position */
    double *block;
    double *c[NCOEF];
    double *w2, *tzw;          /* follow the coefficients in block */
    double *state;             /* u, v, umax, amax (after w2, tzw) */
    double *u, *v, *umax, *amax;
} work;

static void work_free(work *wk)
{
    free(wk->perm);
    free(wk->m);
    free(wk->block);
}

/* Insertion sort of indices by m (stable, no global state: qsort's comparator
 * would need one, and this must be thread-safe). nf is a few hundred. */
static void sort_by_m(size_t *perm, const size_t *m_of, size_t nf)
{
    for (size_t i = 1; i < nf; i++) {
        size_t key = perm[i];
        size_t j = i;
        while (j > 0 && m_of[perm[j - 1]] > m_of[key]) {
            perm[j] = perm[j - 1];
            j--;
        }
        perm[j] = key;
    }
}

static sl_status work_init(work *wk, const double *f, size_t nf, double dt, double zeta,
                           double spp, sl_error *err)
{
    memset(wk, 0, sizeof *wk);
    wk->nf = nf;
    enum { NARR = NCOEF + 6 };
    size_t *m_of = malloc(nf * sizeof *m_of);
    wk->perm = malloc(nf * sizeof *wk->perm);
    wk->m = malloc(nf * sizeof *wk->m);
    wk->block = malloc((size_t)NARR * nf * sizeof *wk->block);
    if (!m_of || !wk->perm || !wk->m || !wk->block) {
        free(m_of);
        work_free(wk);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
    }
    for (int k = 0; k < NCOEF; k++)
        wk->c[k] = wk->block + (size_t)k * nf;
    wk->w2 = wk->block + (size_t)NCOEF * nf;
    wk->tzw = wk->w2 + nf;
    wk->state = wk->tzw + nf;
    wk->u = wk->state;
    wk->v = wk->state + nf;
    wk->umax = wk->state + 2 * nf;
    wk->amax = wk->state + 3 * nf;
    for (size_t j = 0; j < nf; j++) {
        m_of[j] = substeps_for(f[j], dt, spp);
        wk->perm[j] = j;
    }
    sort_by_m(wk->perm, m_of, nf);
    for (size_t p = 0; p < nf; p++) {
        size_t j = wk->perm[p];
        double w = 2.0 * SL_PI * f[j];
        double h = dt / (double)m_of[j];
        double c[NCOEF];
        coefs_auto(w, zeta, h, c);
        for (int k = 0; k < NCOEF; k++)
            wk->c[k][p] = c[k];
        wk->m[p] = m_of[j];
        wk->u[p] = wk->v[p] = wk->umax[p] = wk->amax[p] = 0.0;
        wk->w2[p] = w * w;
        wk->tzw[p] = 2.0 * zeta * w;
    }
    free(m_of);
    return SL_OK;
}

/* One sub-step for positions [p0, p1) with input a0 -> a1. `co` holds the
 * NCOEF coefficient arrays then w^2 and 2 z w (stride nf); `st` holds u, v,
 * max|u| and max|u''+a| (stride nf). Separate restrict arguments let the
 * compiler vectorise the loop over frequencies. */
static void step_group(size_t p0, size_t p1, size_t nf, double a0, double a1,
                       const double *restrict co, double *restrict st)
{
    const double *c11 = co + C11 * nf, *c12 = co + C12 * nf, *c21 = co + C21 * nf;
    const double *c22 = co + C22 * nf, *bu0 = co + BU0 * nf, *bu1 = co + BU1 * nf;
    const double *bv0 = co + BV0 * nf, *bv1 = co + BV1 * nf;
    const double *w2 = co + NCOEF * nf, *tzw = co + (NCOEF + 1) * nf;
    double *u = st, *v = st + nf, *umax = st + 2 * nf, *amax = st + 3 * nf;
    for (size_t p = p0; p < p1; p++) {
        double un = c11[p] * u[p] + c12[p] * v[p] + bu0[p] * a0 + bu1[p] * a1;
        double vn = c21[p] * u[p] + c22[p] * v[p] + bv0[p] * a0 + bv1[p] * a1;
        u[p] = un;
        v[p] = vn;
        double au = fabs(un);
        double aa = fabs(w2[p] * un + tzw[p] * vn);
        umax[p] = au > umax[p] ? au : umax[p];
        amax[p] = aa > amax[p] ? aa : amax[p];
    }
}

static void run_groups(work *wk, const double *acc, size_t n, const double *f, double dt,
                       double zeta, int free_vib)
{
    size_t nf = wk->nf;
    for (size_t p0 = 0; p0 < nf;) {
        size_t m = wk->m[p0];
        size_t p1 = p0 + 1;
        while (p1 < nf && wk->m[p1] == m)
            p1++;
        double inv_m = 1.0 / (double)m;
        for (size_t i = 0; i + 1 < n; i++) {
            double a0 = acc[i], da = acc[i + 1] - acc[i];
            double as = a0;
            for (size_t s = 1; s <= m; s++) {
                /* linear interpolation, endpoint exact */
                double as1 = s == m ? acc[i + 1] : a0 + da * ((double)s * inv_m);
                step_group(p0, p1, nf, as, as1, wk->block, wk->state);
                as = as1;
            }
        }
        if (free_vib) {
            double h = dt * inv_m;
            size_t nfree = 0;
            for (size_t p = p0; p < p1; p++) {
                size_t k = free_steps_for(f[wk->perm[p]], zeta, h);
                nfree = k > nfree ? k : nfree;
            }
            for (size_t k = 0; k < nfree; k++)
                step_group(p0, p1, nf, 0.0, 0.0, wk->block, wk->state);
        }
        p0 = p1;
    }
}

sl_status sl_spectrum_compute_opts(const double *acc_ms2, size_t n, double dt_s,
                                   const double *f_hz, size_t nf, double zeta,
                                   const sl_spectrum_opts *opts, double *psa_ms2,
                                   double *sd_m, double *sa_abs_ms2, sl_error *err)
{
    sl_spectrum_opts o;
    if (opts)
        o = *opts;
    else
        sl_spectrum_opts_default(&o);
    if (nf == 0)
        return SL_OK;
    if (!f_hz)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: no frequencies");
    sl_status st = check_args(acc_ms2, n, dt_s, f_hz, nf, zeta, &o, err);
    if (st)
        return st;
    work wk;
    st = work_init(&wk, f_hz, nf, dt_s, zeta, o.steps_per_period, err);
    if (st)
        return st;
    run_groups(&wk, acc_ms2, n, f_hz, dt_s, zeta, o.free_vibration);
    for (size_t p = 0; p < nf; p++) {
        size_t j = wk.perm[p];
        if (sd_m)
            sd_m[j] = wk.umax[p];
        if (psa_ms2)
            psa_ms2[j] = wk.w2[p] * wk.umax[p];
        if (sa_abs_ms2)
            sa_abs_ms2[j] = wk.amax[p];
    }
    work_free(&wk);
    return SL_OK;
}

sl_status sl_spectrum_compute(const double *acc_ms2, size_t n, double dt_s,
                              const double *f_hz, size_t nf, double zeta,
                              double *psa_ms2, double *sd_m, double *sa_abs_ms2,
                              sl_error *err)
{
    return sl_spectrum_compute_opts(acc_ms2, n, dt_s, f_hz, nf, zeta, NULL, psa_ms2, sd_m,
                                    sa_abs_ms2, err);
}

sl_status sl_spectrum_batch(const sl_motion *const *motions, size_t nm,
                            const double *f_hz, size_t nf, double zeta,
                            const sl_spectrum_opts *opts, double *psa_ms2,
                            double *sd_m, double *sa_abs_ms2, sl_error *err)
{
    if (nm == 0)
        return SL_OK;
    if (!motions)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "spectrum: no motions");
    sl_status *st = calloc(nm, sizeof *st);
    sl_error *errs = calloc(nm, sizeof *errs);
    if (!st || !errs) {
        free(st);
        free(errs);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "spectrum: out of memory");
    }
    long long nm_ll = (long long)nm;
#pragma omp parallel for schedule(dynamic, 1)
    for (long long i = 0; i < nm_ll; i++) {
        size_t k = (size_t)i;
        const sl_motion *m = motions[k];
        if (!m) {
            st[k] = sl_error_set(&errs[k], SL_EINVAL, NULL, 0, "spectrum: missing motion");
            continue;
        }
        st[k] = sl_spectrum_compute_opts(m->acc_ms2, m->n, m->dt_s, f_hz, nf, zeta, opts,
                                         psa_ms2 ? psa_ms2 + k * nf : NULL,
                                         sd_m ? sd_m + k * nf : NULL,
                                         sa_abs_ms2 ? sa_abs_ms2 + k * nf : NULL, &errs[k]);
    }
    sl_status ret = SL_OK;
    for (size_t k = 0; k < nm; k++) {
        if (st[k]) {
            const char *path = motions[k] && motions[k]->path ? motions[k]->path : NULL;
            ret = sl_error_set(err, st[k], path && *path ? path : NULL, 0, "%s", errs[k].msg);
            break;
        }
    }
    free(st);
    free(errs);
    return ret;
}

sl_status sl_spectrum_history(const double *acc_ms2, size_t n, double dt_s,
                              double f_hz, double zeta, const sl_spectrum_opts *opts,
                              double *u_m, double *v_ms, sl_error *err)
{
    sl_spectrum_opts o;
    if (opts)
        o = *opts;
    else
        sl_spectrum_opts_default(&o);
    sl_status st = check_args(acc_ms2, n, dt_s, &f_hz, 1, zeta, &o, err);
    if (st)
        return st;
    size_t m = substeps_for(f_hz, dt_s, o.steps_per_period);
    double c[NCOEF];
    coefs_auto(2.0 * SL_PI * f_hz, zeta, dt_s / (double)m, c);
    double u = 0.0, v = 0.0, inv_m = 1.0 / (double)m;
    for (size_t i = 0; i < n; i++) {
        if (u_m)
            u_m[i] = u;
        if (v_ms)
            v_ms[i] = v;
        if (i + 1 == n)
            break;
        double a0 = acc_ms2[i], da = acc_ms2[i + 1] - acc_ms2[i], as = a0;
        for (size_t s = 1; s <= m; s++) {
            double as1 = s == m ? acc_ms2[i + 1] : a0 + da * ((double)s * inv_m);
            double un = c[C11] * u + c[C12] * v + c[BU0] * as + c[BU1] * as1;
            double vn = c[C21] * u + c[C22] * v + c[BV0] * as + c[BV1] * as1;
            u = un;
            v = vn;
            as = as1;
        }
    }
    return SL_OK;
}
