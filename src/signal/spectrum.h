/*
 * spectrum.h - linear elastic response spectra of acceleration records by
 * the exact piecewise-linear recurrence of Nigam and Jennings (1969).
 *
 * The oscillator (natural frequency f, circular frequency w = 2 pi f,
 * damping ratio z, relative displacement u) obeys
 *
 *     u'' + 2 z w u' + w^2 u = -a(t),                                   (1)
 *
 * with a(t) the ground (floor) acceleration taken as piecewise linear
 * between samples. Over a step h the exact solution is a linear map
 *
 *     [u1]   [a11 a12] [u0]   [bu0 bu1] [a0]
 *     [v1] = [a21 a22] [v0] + [bv0 bv1] [a1],                           (2)
 *
 * (Nigam and Jennings 1969, "Calculation of response spectra from
 * strong-motion earthquake records", BSSA 59(2), eq. 4-6). The oscillator
 * starts at rest. Quantities returned, all peaks over time of absolute
 * values:
 *     SD     = max |u|                      spectral displacement, m
 *     PSA    = w^2 SD                       pseudo-spectral acceleration, m/s^2
 *     SA_abs = max |u'' + a| = max |2 z w u' + w^2 u|
 *                                           absolute acceleration, m/s^2
 *
 * Sampled peak. A peak taken over samples spaced h underestimates the true
 * peak of an oscillation of period T by up to 1 - cos(pi h/T). Each
 * frequency therefore runs on sub-steps h = dt/m with m = ceil(dt f N) and
 * N = SL_SPECTRUM_STEPS_PER_PERIOD (20): h <= T/20, error <= 1.2 %. The
 * sub-step input is the linear interpolation of the samples, which is exact
 * for the piecewise-linear reading of the record, so resampling changes
 * nothing but where the peak is sampled.
 *
 * End of record. As in slide.h, the input ends at the last sample and the
 * floor is at rest afterwards (a = 0). The oscillator then vibrates freely;
 * the largest |u| (and |u''|) of a free damped vibration occurs at its first
 * extremum, within half a damped period T_d/2 = T/(2 sqrt(1 - z^2)), since
 * later extrema decay. The run therefore continues for ceil(T_d/(2 h)) + 1
 * free sub-steps, so a peak after the record end is never cut off. A block
 * of oscillators skips those free sub-steps when, for each of them, the
 * amplitude of the free vibration from its state at the last sample is
 * below its peak over the record (spectrum.c eq. F1-F2): they could not
 * raise it, and the result is the same bits.
 *
 * Speed. Coefficients are computed once per (frequency, sub-step) (once
 * per plan, below); the frequencies are grouped by m and each group is
 * stepped in blocks of up to 16 oscillators with time as the inner loop: a
 * block's state stays in registers and its independent lanes hide the
 * latency of the recurrence. A group with m > 1 interpolates its sub-step
 * input once for all its blocks.
 * sl_spectrum_batch() runs motions in parallel with OpenMP.
 *
 * Units: SI (s, Hz, m, m/s^2). Damping as a ratio of critical, in [0, 1).
 */
#ifndef SL_SPECTRUM_H
#define SL_SPECTRUM_H

#include <stddef.h>

#include "core/api.h"
#include "core/motion_type.h"
#include "core/spectrum_type.h"
#include "core/status.h"

/* Sub-steps per natural period for the sampled peak (the peak over samples
 * underestimates by up to 1 - cos(pi h/T): h <= T/20, error <= 1 - cos(pi/20) = 1.23 %). */
#define SL_SPECTRUM_STEPS_PER_PERIOD 20.0

/* Default frequency grid (US NRC SRP 3.7.1): 100 log-spaced points per
 * decade from 0.1 to 50 Hz. */
#define SL_SPECTRUM_FMIN_HZ 0.1
#define SL_SPECTRUM_FMAX_HZ 50.0
#define SL_SPECTRUM_PER_DECADE 100.0

/* Below this w h the recurrence coefficients come from the Taylor series of
 * the matrix exponential and phi functions (no cancellation); at and above
 * it from the closed form. Both are the same exact map (2). */
#define SL_SPECTRUM_SERIES_WH 0.2

/* Most sub-steps per input step (a guard against absurd options): a
 * frequency needing more is refused with SL_EINVAL. */
#define SL_SPECTRUM_MAX_SUBSTEPS 1e6

/* Options of a spectrum computation. */
typedef struct sl_spectrum_opts {
    double steps_per_period; /* sub-steps per natural period, >= 1
                                (SL_SPECTRUM_STEPS_PER_PERIOD) */
    int free_vibration;      /* 1 (default): continue after the record until
                                the first free-vibration extremum; 0: stop at
                                the last sample */
} sl_spectrum_opts;

/* Fill defaults (steps_per_period = 20, free_vibration = 1). */
SL_API void sl_spectrum_opts_default(sl_spectrum_opts *o);

/* Log-spaced frequency grid from fmin_hz to fmax_hz inclusive with at least
 * per_decade points per decade: k = ceil(per_decade log10(fmax/fmin))
 * intervals of equal log width, k + 1 points (271 for the default 0.1-50 Hz
 * at 100 per decade). fmin == fmax gives one point. Returns a malloc'd array
 * the caller frees, and its length in *n; NULL (and *n = 0) on bad input
 * (non-positive, non-finite, fmax < fmin, per_decade <= 0) or allocation
 * failure. */
SL_API double *sl_spectrum_grid(double fmin_hz, double fmax_hz, double per_decade, size_t *n);

/* Spectrum of one record at one damping, default options.
 *   acc_ms2, n, dt_s : the record (n >= 1 samples, dt_s > 0), m/s^2, s
 *   f_hz, nf         : frequencies (> 0, any order), Hz
 *   zeta             : damping ratio in [0, 1)
 *   psa_ms2, sd_m, sa_abs_ms2 : outputs of nf values each (any may be NULL)
 * Returns SL_OK; SL_EINVAL for bad arguments or a non-finite sample;
 * SL_ENOMEM. Equation (1)-(2); peak definitions above. Thread-safe. */
SL_API sl_status sl_spectrum_compute(const double *acc_ms2, size_t n, double dt_s,
                                     const double *f_hz, size_t nf, double zeta,
                                     double *psa_ms2, double *sd_m, double *sa_abs_ms2,
                                     sl_error *err);

/* As sl_spectrum_compute() with explicit options (NULL = defaults). */
SL_API sl_status sl_spectrum_compute_opts(const double *acc_ms2, size_t n, double dt_s,
                                          const double *f_hz, size_t nf, double zeta,
                                          const sl_spectrum_opts *opts, double *psa_ms2,
                                          double *sd_m, double *sa_abs_ms2, sl_error *err);

/* Spectra of nm motions at one damping, in parallel over motions (OpenMP).
 * Outputs are row-major nm x nf: psa_ms2[i * nf + j] is motion i at
 * f_hz[j]; any output may be NULL. opts may be NULL. On failure returns the
 * status of the first failing motion (in index order) with its message and
 * the motion's path as the error's file. Results do not depend on the
 * thread count. Memory: the caller owns every array. */
SL_API sl_status sl_spectrum_batch(const sl_motion *const *motions, size_t nm,
                                   const double *f_hz, size_t nf, double zeta,
                                   const sl_spectrum_opts *opts, double *psa_ms2,
                                   double *sd_m, double *sa_abs_ms2, sl_error *err);

/* Response history of one oscillator, at the record's samples: u_m[i] and
 * v_ms[i] (relative displacement, m, and velocity, m/s) at t = i dt_s,
 * i = 0..n-1, from rest, on sub-steps h <= T/steps_per_period (opts may be
 * NULL). Either output may be NULL. Returns SL_OK, SL_EINVAL. For tests and
 * plots; the spectrum functions do not store histories. */
SL_API sl_status sl_spectrum_history(const double *acc_ms2, size_t n, double dt_s,
                                     double f_hz, double zeta, const sl_spectrum_opts *opts,
                                     double *u_m, double *v_ms, sl_error *err);

/* How to compute the recurrence coefficients. */
typedef enum sl_spectrum_method {
    SL_SPECTRUM_AUTO = 0, /* series below SL_SPECTRUM_SERIES_WH, else closed form */
    SL_SPECTRUM_CLOSED,   /* closed form (trigonometric), needs zeta < 1 */
    SL_SPECTRUM_SERIES    /* Taylor series of exp and phi functions */
} sl_spectrum_method;

/* Coefficients of map (2) for one oscillator and one step h_s:
 * c[0..7] = a11, a12, a21, a22, bu0, bu1, bv0, bv1.
 * Closed form: with wd = w sqrt(1-z^2), E = exp(-z w h), q = z/sqrt(1-z^2),
 *   a11 = E (cos wd h + q sin wd h),  a12 = E sin(wd h)/wd,
 *   a21 = -w^2 a12,                   a22 = E (cos wd h - q sin wd h),
 * and the load terms from the particular solution of (1) for linear a,
 * u_p = -a/w^2 + 2 z a'/w^3, v_p = -a'/w^2:  x1 = x_p(h) + A (x0 - x_p(0)).
 * Series: x1 = phi0(Mh) x0 - h (phi1 - phi2)(Mh) e a0 - h phi2(Mh) e a1,
 * M = [0 1; -w^2 -2zw], e = [0 1]^T, phi_k(Z) = sum_j Z^j/(j+k)!, evaluated
 * on the balanced matrix w h [0 1; -1 -2z].
 * Returns SL_OK, or SL_EINVAL (f <= 0, h <= 0, zeta outside [0, 1)). */
SL_API sl_status sl_spectrum_coefs(double f_hz, double zeta, double h_s,
                                   sl_spectrum_method method, double c[8], sl_error *err);

/* ---- plans: coefficients made once; optional multirate ---------------
 *
 * A plan holds the recurrence coefficients of one set of oscillators for one
 * record length, step and damping, so repeated spectra of same-length motions
 * (the synthesis iteration) skip that set-up. With ratio = 0 a plan computes
 * exactly sl_spectrum_compute_opts() (the same bits).
 *
 * Multirate (ratio R > 0). An oscillator at f whose response is dominated by
 * content near f does not need the full sampling rate fs. Each oscillator
 * runs at the rate fs_l = fs/2^l of the largest l with
 *
 *     fs_l >= R f                                                       (M1)
 *
 * on a band-limited copy of the record: with X_k the DFT of the record
 * zero-padded to N (a multiple of 2^l), the copy is the inverse DFT of length
 * N/2^l of
 *
 *     X_k sinc^2(f_k/fs) / sinc^2(f_k/fs_l),   f_k < fs_l/2,  0 above,   (M2)
 *
 * sampled at step 2^l dt (an exact band-limited resample; the sinc^2 ratio
 * makes the piecewise-linear reading at fs_l have the baseband spectrum of
 * the piecewise-linear reading at fs). What is lost is the content above
 * fs_l/2 >= R f/2, to which the oscillator responds with a gain below
 * 1/((R/2)^2 - 1) of the static one (1 % at R = 20), and the images of the
 * linear interpolation, which (M2) does not undo. Measured against the full
 * computation over the default grid at 5 % (tests/test_spectrum.c,
 * docs/synthesis.md 8), worst / mean relative error of PSA: four records,
 * R = 20: 10 % / 0.5 %, R = 40: 3.2 % / 0.12 %, R = 64: 0.7 % / 0.03 %;
 * synthesized motions, R = 20: 3.5 % / 0.2 %; worst at the lowest
 * frequencies, where the content above the cutoff is large against the
 * oscillator's own. So it is an estimate for steering an iteration, not for
 * checks. Oscillators with fs < R f run at the full rate exactly as without
 * a plan. A multirate plan gives PSA and SD only. */
typedef struct sl_spectrum_plan sl_spectrum_plan;

/* Smallest multirate ratio accepted: fs_l >= 8 f keeps the cutoff fs_l/2 at
 * 4 f or more. */
#define SL_SPECTRUM_MIN_RATIO 8.0

/* Plan for records of n samples at dt_s, frequencies f_hz[0..nf-1] (any
 * order), damping zeta, options opts (NULL = defaults), multirate ratio
 * (0 = none, else >= SL_SPECTRUM_MIN_RATIO). NULL on bad arguments (err
 * says which) or allocation failure. Makes FFTW plans when multirate (from
 * any thread: the planner is made thread-safe). Free with
 * sl_spectrum_plan_free(). */
SL_API sl_spectrum_plan *sl_spectrum_plan_alloc(size_t n, double dt_s, const double *f_hz, size_t nf,
                                                double zeta, const sl_spectrum_opts *opts,
                                                double ratio, sl_error *err);

/* Free a plan; harmless on NULL. */
SL_API void sl_spectrum_plan_free(sl_spectrum_plan *p);

/* Number of rates the plan uses (1 without multirate). */
SL_API size_t sl_spectrum_plan_levels(const sl_spectrum_plan *p);

/* Spectrum of one record of the plan's length: outputs as in
 * sl_spectrum_compute() (sa_abs_ms2 must be NULL for a multirate plan).
 * The plan is only read: one plan may serve several threads at once.
 * Returns SL_OK, SL_EINVAL (non-finite sample), SL_ENOMEM. */
SL_API sl_status sl_spectrum_plan_compute(const sl_spectrum_plan *p, const double *acc_ms2,
                                          double *psa_ms2, double *sd_m, double *sa_abs_ms2,
                                          sl_error *err);

#endif
