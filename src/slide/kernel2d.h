/*
 * kernel2d.h - the 2-D (+ vertical) Coulomb kernel of the engine
 * (library-internal; engine.c drives it). All friction coefficients of one
 * motion advance together; docs/integrators.md has the method, its order
 * and the error estimator.
 *
 * Equation (slide.h eq. 1): u'' = -a_h(t) - mu N(t) u'/|u'|, N = max(g + a_v, 0),
 * a_h and a_v piecewise linear between samples.
 */
#ifndef SL_KERNEL2D_H
#define SL_KERNEL2D_H

#include <stddef.h>

#include "slide/model.h"

/* The motion as the kernel sees it (SI). ay may be NULL (then 0), av NULL
 * (then N = g). sign = -1 inverts both horizontals. */
typedef struct sl_k2_motion {
    size_t n;
    double dt_s, g_ms2, sign;
    const double *ax, *ay, *av;
} sl_k2_motion;

/* Accuracy control. substeps > 0: that many equal sub-steps per sample and
 * no estimate (err_m = NAN). substeps == 0: per sample and per block, one
 * step against two half steps (step doubling), halving further until the
 * local difference |du| + SL_K2_TV |dv| <= eta_k * max(rtol peak_k, atol);
 * the differences accumulate into err_m (docs/integrators.md). */
typedef struct sl_k2_opts {
    unsigned substeps;
    double rtol, atol_m;
} sl_k2_opts;

/* Per block, at the end of the record (before the closed-form tail). */
typedef struct sl_k2_out {
    double ux, uy, vx, vy;  /* displacement m, velocity m/s */
    double peak_m, t_peak_s, peak_x_m, peak_y_m, path_m, max_speed_ms;
    double t_stop_s, slide_time_s;
    double err_m;     /* estimated error of peak_m, m (NAN with fixed sub-steps) */
    double err_end_m; /* estimated error of the final displacement, m */
    double err_v_ms;  /* estimated error of the final velocity, m/s (for the tail) */
    long episodes;
    long refined;    /* samples on which the block was sub-stepped below dt/2 */
} sl_k2_out;

/* Run m blocks with friction mu[k] (eta[k] > 0: the share of the tolerance
 * per sample, NULL = the default; scale_m[k]: an a-priori estimate of the
 * peak, m, the tolerance uses the larger of it and the peak so far, NULL =
 * none) over the motion; out[k] receives block k.
 * hist (may be NULL; then m must be 1) receives the samples 1..n-1 of block
 * 0, with room already reserved. Returns 0, or -1 when out of memory. */
int sl_kernel2d_run(const sl_k2_motion *in, const double *mu, const double *eta,
                    const double *scale_m, size_t m,
                    const sl_k2_opts *o, sl_k2_out *out, sl_history *hist);

/* The vector passes' instances (kernel2d.c): built by GCC for x86-64 there
 * are two, on AVX2 vectors (4 doubles), run when the CPU has AVX2, and the
 * baseline (SSE2, 2 doubles); elsewhere only the baseline. Both give the same
 * bits. sl_kernel2d_avx2() is 1 when the AVX2 instance runs;
 * sl_kernel2d_baseline(1) makes later runs use the baseline (tests; not
 * while runs go on in other threads), 0 restores the choice by CPU. Returns
 * the previous setting. */
int sl_kernel2d_avx2(void);
int sl_kernel2d_baseline(int on);

/* Default per-sample share of the tolerance, and the time a local velocity
 * difference is charged for in the acceptance test, s. */
#define SL_K2_ETA 0.05
#define SL_K2_TV 0.1
/* Step doubling on a smooth step of local order 3: the error of the two
 * half steps is the difference from the full step over 2^3/2 - 1 = 3. */
#define SL_K2_RICHARDSON 3.0
/* Sub-steps a sliding block starts its refinement with (against twice as
 * many) when it can stop inside the sample: when a lower bound of its speed,
 * from its speed and direction at the start and the largest deceleration
 * along that direction, reaches zero (kernel2d.c (6)). A stop and restart
 * inside one step can look alike at 1 and 2 (from 4 a peak left the
 * tolerance by 1.45 x, docs/integrators.md). */
#define SL_K2_NEAR_STOP_SUB 8u
/* Sub-steps a block at rest starts the refinement of its onset with (against
 * twice as many), on its own grid from the exact onset instant: from 2 a
 * peak missed the tolerance at rtol 3e-4 by 0.3 % (docs/integrators.md),
 * from 4 the answers are as accurate as from 8. */
#define SL_K2_ONSET_SUB 4u
/* In the split step (5) the block is taken to stop at tau only when the
 * speed left across the old direction is at most this fraction of the speed
 * before the step (else it is turning). */
#define SL_K2_STOP_REMNANT 0.25

#endif
