/*
 * stats.h - the mean of a skewed, non-negative quantity (peak sliding
 * displacements over motion sets, with zeros where a set does not slide),
 * its standard error and a bootstrap confidence band.
 *
 * Estimators, for a sample x_1..x_n >= 0 (docs/run.md, "Convergence"):
 *
 *  - Sample mean  m = sum x_i / n, sample sd s (n - 1 in the denominator),
 *    standard error SE = s / sqrt(n). m is what ASCE/SEI 43-05 A.1 asks for
 *    (the mean of the analyses) and is unbiased whatever the distribution.
 *
 *  - Zero-inflated log-normal fit (the model the field uses for sliding,
 *    e.g. Bray and Travasarou 2007: a probability of sliding times a
 *    log-normal of the non-zero displacement). With k = #{x_i > 0},
 *    p = k / n, and y_i = ln x_i over the positive values with mean mu_l and
 *    sd sigma_l (k - 1 in the denominator):
 *        M  = p exp(mu_l + sigma_l^2 / 2)                               (1)
 *        Var(ln M) = (1 - p)/(n p) + sigma_l^2/k + sigma_l^4/(2 (k - 1)) (2)
 *    ((2) is the delta method: binomial p, normal mean and chi-square
 *    variance of the logs), SE(M) = M sqrt(Var(ln M)). Needs k >= 2.
 *    Reported beside the sample mean as a check of the distribution, not
 *    used for the design value: near the friction value where sliding stops
 *    the positive peaks span decades (from numerical traces of 1e-9 m to
 *    millimetres), sigma_l is large and exp(sigma_l^2 / 2) makes M and its
 *    SE meaningless, while the sample mean stays unbiased.
 *
 *  - Percentile bootstrap (Efron and Tibshirani 1993, ch. 13): resample the
 *    n indices with replacement B times, recompute the statistic, take its
 *    (1 - level)/2 and (1 + level)/2 quantiles. The resampler is GSL's
 *    mt19937 with a given seed, so the band is reproducible. On skewed
 *    samples it is too narrow and sits on the wrong side (the mean of a
 *    right-skewed sample is low exactly when its SE is low).
 *
 *  - Bootstrap-t (studentized; Efron and Tibshirani 1993, ch. 12.5): per
 *    resample t* = (D* - D) / SE*, with SE* computed from the resample as SE
 *    is from the sample; with t_a the a-quantile of t*:
 *        band = [D - t_(1+level)/2 SE,  D - t_(1-level)/2 SE]             (3)
 *    Second-order accurate for a mean: it widens the side towards which
 *    the sample is skewed and allows for the error of SE itself.
 *
 * Units: whatever the caller's values carry. No allocation except where a
 * function says so; no printing.
 */
#ifndef SL_STATS_H
#define SL_STATS_H

#include <stddef.h>
#include <stdint.h>

#include "core/api.h"
#include "core/status.h"

/* The statistics of a design value D = min(FS mean, cap) at one friction
 * value (units m), as analysis.c fills them (analysis.h, "Convergence"). */
typedef struct sl_stats_conv {
    size_t n_sets;              /* sets used */
    double mean_m, se_m;        /* sample mean of the peaks and its SE */
    double lognormal_mean_m;    /* zero-inflated log-normal mean (stats.h (1); NAN if < 2
                                   sets slide) */
    double p_slide;             /* fraction of sets that slide */
    double design_m;            /* min(FS mean, cap) = the design row's nltha_design_m */
    double design_se_m;         /* its SE: FS se_m, or the cap's SE when capped */
    double design_lo_m, design_hi_m; /* bootstrap band (band_level) */
    double target_se_m;         /* max(rel_se design, abs_se_m) */
    int converged;              /* design_se_m <= target_se_m */
} sl_stats_conv;

/* Default number of bootstrap resamples and level of the band. */
#define SL_STATS_BOOT_RESAMPLES 1000
#define SL_STATS_BAND_LEVEL 0.90
/* A sample variance within this many times the round-off of its sums,
 * (n + 3) DBL_EPSILON x the sum of squares, is 0 (stats.c var_from_sums):
 * n copies of one value have no scatter on any CPU. */
#define SL_STATS_VAR_ROUNDOFF 4.0

/* Summary of a sample (see the header comment for the formulas). */
typedef struct sl_stats_mean {
    size_t n;          /* sample size */
    size_t n_pos;      /* values > 0 */
    double mean;       /* sample mean */
    double sd;         /* sample standard deviation (0 when n < 2) */
    double se;         /* sd / sqrt(n) */
    double p_pos;      /* n_pos / n */
    double ln_mu, ln_sigma; /* mean and sd of ln x over x > 0 (NAN when n_pos < 2) */
    double ln_mean;    /* (1): the zero-inflated log-normal mean (0 when n_pos = 0,
                          NAN when n_pos = 1) */
    double ln_se;      /* (2): its standard error (0 when n_pos = 0, NAN when n_pos = 1) */
} sl_stats_mean;

/* Summarise x[0], x[stride], ..., x[(n - 1) stride] (n >= 1, values finite
 * and >= 0). Returns SL_OK, or SL_EINVAL on n = 0, stride = 0 or a bad
 * value. */
SL_API sl_status sl_stats_mean_compute(const double *x, size_t n, size_t stride, sl_stats_mean *out,
                                       sl_error *err);

/* A bootstrap resampler: idx[0..n-1] drawn uniformly from 0..n-1 with
 * replacement, from a stream seeded with `seed`. */
typedef struct sl_stats_boot sl_stats_boot;

SL_API sl_stats_boot *sl_stats_boot_alloc(uint64_t seed, sl_error *err);
SL_API void sl_stats_boot_free(sl_stats_boot *b);
/* Fill idx with one resample of 0..n-1 (n >= 1). */
SL_API void sl_stats_boot_draw(sl_stats_boot *b, size_t n, size_t *idx);

/* The (1 - level)/2 and (1 + level)/2 quantiles of v[0..m-1] (sorted in
 * place; m >= 1, 0 < level < 1), linear interpolation between order
 * statistics (gsl_stats_quantile_from_sorted_data). */
SL_API void sl_stats_band(double *v, size_t m, double level, double *lo, double *hi);

/* Percentile bootstrap band of the sample mean of x[0..n-1] (stride 1):
 * B resamples from `seed`. Allocates its own work space. Returns SL_OK or
 * SL_EINVAL / SL_ENOMEM. */
SL_API sl_status sl_stats_boot_mean_band(const double *x, size_t n, size_t B, double level,
                                         uint64_t seed, double *lo, double *hi, sl_error *err);

/* How sl_stats_design_band builds the band. */
typedef enum sl_stats_band_method {
    SL_STATS_BAND_PERCENTILE = 0, /* percentile bootstrap */
    SL_STATS_BAND_STUDENT         /* bootstrap-t, (3) (the default of the run) */
} sl_stats_band_method;

/* The design value D_k = min(fs m_k, cap) at each of n_mu friction values
 * and its SE (stats.h; analysis.h, "Convergence"): m_k the mean of
 * peak[i n_mu + k] over the sets i < n, cap = cap_factor x the mean of
 * pgd[0..n-1] (pgd NULL: no cap), SE = fs s_k / sqrt(n) below the cap and
 * cap_factor s_pgd / sqrt(n) where the cap governs. Writes d[k] and se[k]
 * (either may be NULL). */
SL_API void sl_stats_design_value(const double *peak, size_t n, size_t n_mu, const double *pgd,
                                  double fs, double cap_factor, double *d, double *se);

/* Bootstrap band at `level` of D_k (as sl_stats_design_value) at every k:
 * B resamples of the n sets from `seed`, each set's peaks and pgd drawn
 * together (so the cap moves with them). Percentile: the quantiles of D*.
 * Student: (3); where SE is 0 (every set alike) the band is [D, D]; where a
 * quantile of t* is not finite (resamples with SE* = 0, e.g. none of the
 * few sliding sets drawn) that end falls back to the percentile end; the
 * low end is at least 0. Writes lo[k] <= hi[k]. Allocates its own work
 * space (B n_mu doubles). Returns SL_OK, SL_EINVAL or SL_ENOMEM. */
SL_API sl_status sl_stats_design_band(const double *peak, size_t n, size_t n_mu, const double *pgd,
                                      double fs, double cap_factor, size_t B, double level,
                                      uint64_t seed, sl_stats_band_method method, double *lo,
                                      double *hi, sl_error *err);

/* The next motion count of a sequential run (docs/run.md, "Stopping
 * rule"): after n sets, with r the largest SE / target over the friction
 * values, stop (return n) when r <= 1 or n >= max_sets; else aim at
 *     n r^2 margin^2                                                     (4)
 * sets (SE falls as 1/sqrt(n): (4) puts the expected SE at target/margin,
 * so that the next look passes whatever the noise of this SE, instead of
 * looking again and again at a SE hovering at the target and stopping on a
 * low fluctuation), at least n + min_batch, at most growth x n, at most
 * max_sets. */
SL_API size_t sl_stats_plan_next(size_t n, double r, double margin, size_t min_batch, double growth,
                                 size_t max_sets);

/* Showing a design value at the precision its uncertainty supports:
 * the display step is the power of ten at the place of the SE's leading
 * digit (se 26 -> 10, 5.2 -> 1, 0.3 -> 0.1), clamped to [min_step,
 * max_step]; min_step when se is 0 or not finite. */
SL_API double sl_stats_step(double se, double min_step, double max_step);

/* Decimals needed to print multiples of step exactly: max(0, -log10 step),
 * rounded. */
SL_API int sl_stats_step_decimals(double step);

#endif
