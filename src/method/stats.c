/* stats.c - mean, standard errors and bootstrap band; see stats.h. */
#include "method/stats.h"
#include "core/gslerr.h"

#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

sl_status sl_stats_mean_compute(const double *x, size_t n, size_t stride, sl_stats_mean *out,
                                sl_error *err)
{
    if (!x || !out || n == 0 || stride == 0)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "stats: empty sample");
    double sum_l = 0;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        double v = x[i * stride];
        if (!(v >= 0) || !isfinite(v))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "stats: value %g (sample %zu) is not finite and >= 0", v, i + 1);
        if (v > 0) {
            k++;
            sum_l += log(v);
        }
    }
    sl_stats_mean s = {0};
    s.n = n;
    s.n_pos = k;
    /* GSL's running mean and sd, as design.c uses them, so the design
     * value here and in the design table are the same bits */
    s.mean = gsl_stats_mean(x, stride, n);
    double ss_l = 0;
    double ml = k ? sum_l / (double)k : NAN;
    for (size_t i = 0; i < n; i++) {
        double v = x[i * stride];
        if (v > 0)
            ss_l += (log(v) - ml) * (log(v) - ml);
    }
    s.sd = n > 1 ? gsl_stats_sd_m(x, stride, n, s.mean) : 0.0;
    s.se = s.sd / sqrt((double)n);
    s.p_pos = (double)k / (double)n;
    s.ln_mu = s.ln_sigma = NAN;
    if (k == 0) {
        s.ln_mean = s.ln_se = 0.0;
    } else if (k == 1) {
        s.ln_mu = ml;
        s.ln_mean = s.ln_se = NAN;
    } else {
        double s2 = ss_l / (double)(k - 1);
        s.ln_mu = ml;
        s.ln_sigma = sqrt(s2);
        s.ln_mean = s.p_pos * exp(ml + 0.5 * s2); /* (1) */
        double var_ln = (1.0 - s.p_pos) / ((double)n * s.p_pos) + s2 / (double)k +
                        s2 * s2 / (2.0 * (double)(k - 1)); /* (2) */
        s.ln_se = s.ln_mean * sqrt(var_ln);
    }
    *out = s;
    return SL_OK;
}

struct sl_stats_boot {
    gsl_rng *rng;
};

sl_stats_boot *sl_stats_boot_alloc(uint64_t seed, sl_error *err)
{
    sl_stats_boot *b = malloc(sizeof *b);
    if (b) { /* GSL's handler off: an allocation failure is a status (gslerr.h) */
        sl_gsl_quiet_begin();
        b->rng = gsl_rng_alloc(gsl_rng_mt19937);
        sl_gsl_quiet_end();
    }
    if (!b || !b->rng) {
        free(b);
        sl_error_set(err, SL_ENOMEM, NULL, 0, "stats: out of memory");
        return NULL;
    }
    /* mt19937 takes an unsigned long: fold the 64-bit seed */
    gsl_rng_set(b->rng, (unsigned long)((seed ^ (seed >> 32)) & 0xffffffffUL));
    return b;
}

void sl_stats_boot_free(sl_stats_boot *b)
{
    if (!b)
        return;
    gsl_rng_free(b->rng);
    free(b);
}

void sl_stats_boot_draw(sl_stats_boot *b, size_t n, size_t *idx)
{
    for (size_t i = 0; i < n; i++)
        idx[i] = (size_t)gsl_rng_uniform_int(b->rng, (unsigned long)n);
}

void sl_stats_band(double *v, size_t m, double level, double *lo, double *hi)
{
    gsl_sort(v, 1, m);
    *lo = gsl_stats_quantile_from_sorted_data(v, 1, m, 0.5 * (1.0 - level));
    *hi = gsl_stats_quantile_from_sorted_data(v, 1, m, 0.5 * (1.0 + level));
}

sl_status sl_stats_boot_mean_band(const double *x, size_t n, size_t B, double level,
                                  uint64_t seed, double *lo, double *hi, sl_error *err)
{
    if (!x || n == 0 || B == 0 || !(level > 0 && level < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "stats: bootstrap needs n, B >= 1 and a "
                            "level in (0, 1) (level %g)", level);
    size_t *idx = malloc(n * sizeof *idx);
    double *v = malloc(B * sizeof *v);
    sl_stats_boot *b = sl_stats_boot_alloc(seed, err);
    if (!idx || !v || !b) {
        free(idx);
        free(v);
        sl_stats_boot_free(b);
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "stats: out of memory");
    }
    for (size_t r = 0; r < B; r++) {
        sl_stats_boot_draw(b, n, idx);
        double sum = 0;
        for (size_t i = 0; i < n; i++)
            sum += x[idx[i]];
        v[r] = sum / (double)n;
    }
    sl_stats_band(v, B, level, lo, hi);
    free(idx);
    free(v);
    sl_stats_boot_free(b);
    return SL_OK;
}

/* Mean and SE of D = min(fs m, cap) from the sums of one sample (sums over
 * n values: s1 = sum x, s2 = sum x^2 at one mu; p1, p2 the same of pgd, or
 * has_cap 0), SE as sl_stats_design_value. */
/* The sample variance from the sum of squares s2 and the mean m of n > 1
 * values. s2 - n m^2 carries a round-off of up to about (n + 3) eps s2 of
 * either sign, all there is when the values are one value repeated (a
 * bootstrap resample of one set): at or below SL_STATS_VAR_ROUNDOFF times
 * that it is 0, so that such a resample has SE* = 0 on every CPU and libm,
 * never the square root of round-off (1e-8 of the mean). Real scatter
 * (coefficient of variation 0.01 or more) is 1e-4 of s2 and more. */
static double var_from_sums(double s2, double m, double dn)
{
    double q = s2 - dn * m * m;
    return q > SL_STATS_VAR_ROUNDOFF * (dn + 3) * DBL_EPSILON * s2 ? q / (dn - 1) : 0.0;
}

static void design_from_sums(double s1, double s2, double p1, double p2, int has_cap, size_t n,
                             double fs, double cap_factor, double *d, double *se)
{
    double dn = (double)n, m = s1 / dn;
    double v = n > 1 ? var_from_sums(s2, m, dn) : 0.0;
    double dd = fs * m, ss = fs * sqrt(v > 0 ? v / dn : 0.0);
    if (has_cap) {
        double mp = p1 / dn, vp = n > 1 ? var_from_sums(p2, mp, dn) : 0.0;
        double cap = cap_factor * mp;
        if (dd > cap) {
            dd = cap;
            ss = cap_factor * sqrt(vp > 0 ? vp / dn : 0.0);
        }
    }
    *d = dd;
    *se = ss;
}

void sl_stats_design_value(const double *peak, size_t n, size_t n_mu, const double *pgd,
                           double fs, double cap_factor, double *d, double *se)
{
    double p1 = 0, p2 = 0;
    for (size_t i = 0; pgd && i < n; i++) {
        p1 += pgd[i];
        p2 += pgd[i] * pgd[i];
    }
    for (size_t k = 0; k < n_mu; k++) {
        double s1 = 0, s2 = 0, dk, sk;
        for (size_t i = 0; i < n; i++) {
            double x = peak[i * n_mu + k];
            s1 += x;
            s2 += x * x;
        }
        design_from_sums(s1, s2, p1, p2, pgd != NULL, n, fs, cap_factor, &dk, &sk);
        if (d)
            d[k] = dk;
        if (se)
            se[k] = sk;
    }
}

sl_status sl_stats_design_band(const double *peak, size_t n, size_t n_mu, const double *pgd,
                               double fs, double cap_factor, size_t B, double level,
                               uint64_t seed, sl_stats_band_method method, double *lo,
                               double *hi, sl_error *err)
{
    if (!peak || n == 0 || n_mu == 0 || B == 0 || !(level > 0 && level < 1) || !lo || !hi)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "stats: bootstrap needs n, B >= 1 and a "
                            "level in (0, 1) (level %g)", level);
    const int student = method == SL_STATS_BAND_STUDENT;
    size_t *idx = malloc(n * sizeof *idx);
    double *v = malloc(B * n_mu * sizeof *v);             /* D* per mu, B each */
    double *t = student ? malloc(B * n_mu * sizeof *t) : NULL; /* t* per mu */
    double *s = malloc(2 * n_mu * sizeof *s);             /* sums of x and x^2 */
    double *d0 = malloc(2 * n_mu * sizeof *d0);           /* D and SE of the sample */
    sl_stats_boot *b = sl_stats_boot_alloc(seed, err);
    sl_status st = SL_OK;
    if (!idx || !v || (student && !t) || !s || !d0 || !b) {
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "stats: out of memory");
        goto done;
    }
    double *se0 = d0 + n_mu;
    sl_stats_design_value(peak, n, n_mu, pgd, fs, cap_factor, d0, se0);
    for (size_t r = 0; r < B; r++) {
        sl_stats_boot_draw(b, n, idx);
        double p1 = 0, p2 = 0;
        memset(s, 0, 2 * n_mu * sizeof *s);
        for (size_t i = 0; i < n; i++) {
            const double *row = peak + idx[i] * n_mu;
            if (pgd) {
                p1 += pgd[idx[i]];
                p2 += pgd[idx[i]] * pgd[idx[i]];
            }
            for (size_t k = 0; k < n_mu; k++) {
                s[2 * k] += row[k];
                s[2 * k + 1] += row[k] * row[k];
            }
        }
        for (size_t k = 0; k < n_mu; k++) {
            double dk, sk;
            design_from_sums(s[2 * k], s[2 * k + 1], p1, p2, pgd != NULL, n, fs, cap_factor, &dk,
                             &sk);
            v[k * B + r] = dk;
            if (student) /* (3); +-inf where SE* = 0 and D* differs: handled below */
                t[k * B + r] = dk == d0[k] ? 0.0 : (dk - d0[k]) / sk;
        }
    }
    for (size_t k = 0; k < n_mu; k++) {
        sl_stats_band(v + k * B, B, level, &lo[k], &hi[k]);
        if (!student)
            continue;
        if (!(se0[k] > 0)) {
            lo[k] = hi[k] = d0[k];
            continue;
        }
        double tlo, thi;
        sl_stats_band(t + k * B, B, level, &tlo, &thi);
        if (isfinite(thi))
            lo[k] = d0[k] - thi * se0[k];
        if (isfinite(tlo))
            hi[k] = d0[k] - tlo * se0[k];
        if (lo[k] < 0)
            lo[k] = 0;
    }
done:
    free(idx);
    free(v);
    free(t);
    free(s);
    free(d0);
    sl_stats_boot_free(b);
    return st;
}

size_t sl_stats_plan_next(size_t n, double r, double margin, size_t min_batch, double growth,
                          size_t max_sets)
{
    if (!(r > 1) || n >= max_sets)
        return n;
    double w = (double)n * r * r * margin * margin; /* (4) */
    if (w < (double)(n + min_batch))
        w = (double)(n + min_batch);
    if (w > growth * (double)n)
        w = growth * (double)n;
    if (w > (double)max_sets)
        w = (double)max_sets;
    size_t want = (size_t)ceil(w);
    return want > n ? want : n + 1;
}

double sl_stats_step(double se, double min_step, double max_step)
{
    if (!(se > 0) || !isfinite(se))
        return min_step;
    double step = pow(10.0, floor(log10(se) + 1e-12));
    return step < min_step ? min_step : step > max_step ? max_step : step;
}

int sl_stats_step_decimals(double step)
{
    double d = -floor(log10(step) + 1e-12);
    return d > 0 ? (int)d : 0;
}
