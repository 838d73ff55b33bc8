/*
 * bench_engine.h - work-precision data of the error-controlled engine
 * (`seislide bench`, docs/integrators.md), as measurements:
 *
 *  1. Over EVERY three-component set under shared/records (io/setdir.h) and
 *     the friction values sl_bench_wp_mu (2-D + vertical): for each accuracy
 *     setting (the engine's rtol, or fixed sub-steps without error control),
 *     the time of all sets, the median and worst relative error of the peak
 *     vector displacement against a converged reference (the engine at
 *     SL_BENCH_WP_REF_RTOL / SL_BENCH_WP_REF_ATOL_M), over peaks of at least
 *     SL_BENCH_WP_PEAK_FLOOR_M, and the share of rows whose error estimate
 *     err_est_m bounds the true error.
 *  2. For a few sets and a fine friction grid (SL_BENCH_WP_GRID_N values,
 *     0.05 to 0.80): the time of the default engine against the "arithmetic
 *     floor", a branch-free first-order update of all mu at the native dt
 *     (semi-implicit projection w = v - dt a*, v = w max(0, 1 - dt mu N* / |w|),
 *     u += dt v, peak = max |u|), and their ratio, measured in one run.
 *
 * Timing: best of `repeat` runs, one thread. Units: SI; times in s.
 * Memory: sl_bench_wp_run() fills an sl_bench_wp freed with
 * sl_bench_wp_free().
 */
#ifndef SL_BENCH_ENGINE_H
#define SL_BENCH_ENGINE_H

#include <stddef.h>

#include "core/status.h"

#define SL_BENCH_WP_REF_RTOL 1e-6
#define SL_BENCH_WP_REF_ATOL_M 1e-9
#define SL_BENCH_WP_PEAK_FLOOR_M 1e-3
#define SL_BENCH_WP_NMU 7
extern const double sl_bench_wp_mu[SL_BENCH_WP_NMU]; /* 0.05 ... 0.4 */
#define SL_BENCH_WP_NSET 9                           /* settings of part 1 */
#define SL_BENCH_WP_GRID_N 751                       /* mu of part 2 */
#define SL_BENCH_WP_NFLOOR 3                         /* sets of part 2 */

/* One accuracy setting over all sets. */
typedef struct sl_bench_wp_setting {
    double rtol;        /* > 0: error-controlled at this rtol */
    unsigned substeps;  /* > 0: fixed sub-steps, no estimate */
    double time_s;      /* all sets, best of repeat */
    double median_rel, worst_rel; /* over peaks >= SL_BENCH_WP_PEAK_FLOOR_M */
    double bounded;     /* share of rows with err_est_m >= error (rtol settings) */
    double within;      /* share of rows with error <= max(rtol peak, atol) */
} sl_bench_wp_setting;

/* Part 2 on one set. */
typedef struct sl_bench_wp_floor {
    char name[64];
    size_t n;           /* samples */
    double engine_s, floor_s, ratio;
    double sliding;     /* share of (sample, mu) pairs in which the floor's block moves */
} sl_bench_wp_floor;

typedef struct sl_bench_wp {
    size_t n_sets, n_rows, n_unread;
    double ref_time_s;
    sl_bench_wp_setting set[SL_BENCH_WP_NSET];
    int n_floor;
    sl_bench_wp_floor floor[SL_BENCH_WP_NFLOOR];
} sl_bench_wp;

/* Measure both parts on the records under shared/records. Returns NULL and
 * fills err when the folder has no readable set, a run fails or memory runs
 * out. repeat >= 1. */
sl_bench_wp *sl_bench_wp_run(const char *shared, unsigned long repeat, sl_error *err);
void sl_bench_wp_free(sl_bench_wp *b);

#endif
