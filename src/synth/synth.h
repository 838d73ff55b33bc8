/*
 * synth.h - spectrum-compatible acceleration histories made with FFTW: a
 * seeded random sum of wave packets under an intensity envelope, then
 * iterative correction of the Fourier amplitudes by the ratio target /
 * computed spectrum, with a soft order-preserving compression of the largest
 * half-cycles; no clipping and no pinning of the peak (the PGA comes out of
 * matching the spectrum's high-frequency end). The same iteration modifies a
 * recorded motion to match a target while keeping its Fourier phases.
 * Method, defaults and measured results: docs/synthesis.md.
 *
 * Start (iteration 0). Synthetic: K Gabor wavelets (docs/synthesis.md 3.1)
 *     a(t) = sum_q A_q exp(-(t - t_q)^2/(2 s_q^2)) cos(2 pi f_q (t - t_q) + phi_q),
 * s_q = cycles/(2 f_q), f_q log-uniform over [f0, f1] of the target, t_q
 * with density E(t)^2, phi_q uniform (GSL mt19937), A_q = T(f_q) sqrt(f_q).
 * Recorded: a = the record. Either is high-passed (H below) and scaled by
 * one gain so that its spectrum is aim x T on average (log mean), then made
 * admissible (below). Records with match_margin > 0: r = 1 where S/T is in
 * the dead band [1 + margin, 1 + tol_above - margin].
 *
 * Iteration i -> i + 1, on the N-point DFT grid f_k = k/(N dt), N >= n + pad
 * (pad = one period of the lowest checked frequency):
 *     r_m   = (aim T_m / S_m)^1.6 at grid frequency f_m, clamped to [1/4, 4]
 *     X_k   = DFT of the zero-padded a_i (FFTW r2c, unnormalised)
 *     X_k  *= r(f_k) H(f_k)   (r: mean of ln r over the grid points within
 *                       f_k +- df/2, else log-log interpolation; fading to 1
 *                       one octave outside the checked range; H: zero-phase
 *                       Butterworth high-pass, 1/sqrt(1 + (fc/f)^(2 order)),
 *                       fc = hp_frac x the lowest checked frequency)
 *     a     = first n samples of (1/N) c2r(X)
 * then admissible:
 *     a    *= w(t)  half-cosine taper over taper_s at each end (rest at ends)
 *     soft compression: when max|a| = P > L = aim ZPA, the part of a above
 *           f_c (half the frequency of the target's largest SA) is scaled in
 *           each half-cycle whose peak x > K = knee L by y(x)/x,
 *           y = K + (x - K)(L - K)/(P - K)        (order-preserving, no flat tops)
 *           and, for synthetic motions of a target whose SA at its last
 *           frequency is within 1.1 of its ZPA, when P < L the same map with
 *           K = knee P raises the peak to about L (expansion; docs 3.3 C2)
 *     a    -= (c0 + c1 t/T) (t/T)(1 - t/T)            baseline: v(T) = d(T) = 0
 *     S_m   = PSA of a at f_m, at the target's damping  (spectrum.h)
 * A coarse phase first evaluates S at every 3rd grid point on 6 sub-steps
 * per period; the final iterations use every point at full accuracy.
 *
 * Envelope (Jennings, Housner and Tsai 1968), T = (n - 1) dt:
 *     E(t) = (t/t1)^2 for t < t1;  1 for t1 <= t <= t2;
 *     E(t) = exp(-c (t - t2)) after, c = ln(1/e_end)/(T - t2), so E(T) = e_end,
 * with t1 = rise_frac T and t2 = hold_frac T.
 *
 * Acceptance checks (US NRC SRP 3.7.1, Option 1 Approach 2), each
 * a field of sl_synth_params with that default, computed per motion on the
 * grid of sl_spectrum_grid(fmin_hz, fmax_hz, per_decade) restricted to the
 * target's frequency range, at the target's damping:
 *     S/T >= 1 - tol_below            (no point more than 10 % below)
 *     S/T <= 1 + tol_above            (no point more than 30 % above)
 *     run of consecutive S < T points <= max_run_below (9)
 *     D5-75 (sl_motion_d5_75)         >= min_d5_75_s (6 s)
 *     duration (n - 1) dt             >= min_duration_s (20 s)
 *     |v(T)| <= end_vel_frac PGV, |d(T)| <= end_disp_frac PGD (1 %)
 *     PGA/ZPA <= 1 + tol_above, and >= 1 - pga_tol_below when the
 *         target is rigid at its end                 (ok_pga)
 *     peaks of |a| above 0.9 PGA <= max_peaks for targets with
 *         max SA/ZPA <= SL_SYNTH_PEAKS_MAX_AMP          (ok_peaks)
 *     App. B minimum PSD (realism.h) when psd_frac > 0 (ok_psd; else reported)
 *     |rho| of each pair of the set <= max_corr (0.16), rho the Pearson
 *     correlation coefficient of the accelerations at zero lag.
 * The iteration stops when the spectral checks pass; it keeps the best
 * iterate (smallest violation). A motion that fails any check is reported as
 * failed (pass = 0) and the set functions return SL_ENOCONV.
 *
 * Reproducibility. The random stream of a motion is GSL's mt19937 seeded with
 * the low 32 bits of a SplitMix64 hash of (seed, set index, component,
 * attempt) (sl_synth_stream_seed). FFTW plans are made with FFTW_ESTIMATE
 * (no timing, the same algorithm every run) and executed on fftw_malloc'd
 * arrays, so the same seed gives the same bits whatever the thread count.
 * Two caveats: FFTW uses wisdom of equal or greater rigour when it has it, so
 * code in the same process must not import wisdom or plan these lengths with
 * FFTW_MEASURE; and FFTW_ESTIMATE picks codelets by the CPU's SIMD support,
 * so another CPU type may differ in the last bits.
 *
 * Threads. An sl_synth plan is read-only after sl_synth_alloc() and may be
 * shared by threads, each with its own sl_synth_motion. sl_synth_alloc()
 * and sl_synth_free() may run in several threads at once: the library makes
 * FFTW's planner thread-safe (fftw_make_planner_thread_safe) before its
 * first plan, which covers the caller's own FFTW plans as well.
 *
 * Units: SI (s, Hz, m, m/s, m/s^2). Damping as a ratio of critical.
 */
#ifndef SL_SYNTH_H
#define SL_SYNTH_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "core/api.h"
#include "io/floor.h"
#include "io/motion.h"
#include "signal/realism.h"
#include "signal/spectrum.h"
#include "core/status.h"

/* ---- Defaults of the acceptance checks (SRP 3.7.1) -------------------- */
#define SL_SYNTH_TOL_BELOW 0.10      /* no point more than 10 % below the target */
#define SL_SYNTH_TOL_ABOVE 0.30      /* no point more than 30 % above the target */
#define SL_SYNTH_MAX_RUN_BELOW 9     /* most consecutive grid points below the target */
#define SL_SYNTH_MIN_D5_75_S 6.0     /* strong-motion duration (5-75 % Arias), s */
#define SL_SYNTH_MIN_DURATION_S 20.0 /* total duration, s */
#define SL_SYNTH_MAX_CORR 0.16       /* |correlation coefficient| of two components */
#define SL_SYNTH_MAX_DT_S 0.01       /* largest time step (Nyquist >= 50 Hz), s */
/* "Velocity and displacement end near zero": |v(T)| and |d(T)| at most this
 * fraction of the motion's own PGV and PGD. */
#define SL_SYNTH_END_VEL_FRAC 0.01
#define SL_SYNTH_END_DISP_FRAC 0.01
/* An end velocity or displacement at most this fraction of its peak (PGV,
 * PGD) is round-off of the integration, not data: sl_synth_end_residual()
 * makes it 0 for printing. The integration sums n (<= 1e5) terms of at most
 * the peak each, so its round-off is at most about n x 2.2e-16 = 2e-11 of
 * the peak; the baseline-corrected motions of the example floors end at up
 * to 2e-12 of it. 1e-9 is far above both and 1e-7 of the 1 % check. */
#define SL_SYNTH_END_ROUNDOFF 1e-9
/* PGA/ZPA at least 1 - this (at most 1 + tol_above): the PGA is not pinned
 * but must agree with the target's ZPA. */
#define SL_SYNTH_PGA_TOL_BELOW 0.25
/* Realism (docs/synthesis.md 4): at most this many local maxima of |a|
 * above 0.9 PGA per component (real horizontal records: median 1, 90th
 * percentile 3, maximum 7). */
#define SL_SYNTH_MAX_PEAKS 5
/* The peak count is a check only for targets whose largest SA/ZPA is at
 * most this (ground-like; RG 1.60 at 5 %: 3.13). Above it the count is
 * reported, and the crest reservation of synth_sharp.c holds it at 2-3 on
 * average, at most 4-5 (docs/synthesis.md 4, "Limit: very sharp floors"). */
#define SL_SYNTH_PEAKS_MAX_AMP 4.0

/* ---- Defaults of the method ---- */
#define SL_SYNTH_DAMPING 0.05        /* damping matched (SRP practice: 5 %) */
#define SL_SYNTH_DT_S 0.005          /* time step of synthetic motions, s (200/s) */
#define SL_SYNTH_DURATION_S 20.0     /* duration of synthetic motions, s */
#define SL_SYNTH_MAX_ITER 30         /* correction iterations per attempt */
#define SL_SYNTH_MAX_ATTEMPTS 30     /* phase sets tried per synthetic component
                                      (docs/synthesis.md 3.4: a cap that changes
                                      only the motions that fail every attempt below it) */
/* The correction aims at aim x target: 1.03 puts the set mean spectrum at
 * 1.01-1.07 x the target (unbiased within the 0.98-1.08; 1.04 gave
 * 1.08 at some frequencies). A deliberately conservative set: aim 1.10 (the
 * old default, mean 10-17 % above the target). docs/synthesis.md 3.2. */
#define SL_SYNTH_AIM 1.03
/* Start of a synthetic motion: a sum of Gabor wavelets (docs/synthesis.md
 * 3.1), this many per second of strong motion per octave, each of this
 * many cycles within +-1 standard deviation of its Gaussian window;
 * wavelet_rate = 0 gives the stationary random-phase start (SIMQKE).
 * Coherent wave packets let a 5 %-damped oscillator reach SA/PGA = 3
 * (RG 1.60) without peak limiting. 2 cycles: the width of the tapered
 * cosine wavelet of Al Atik and Abrahamson (2010), gamma = 1.178 f^-0.93 s,
 * is 1.4-2.2 cycles on this measure over 0.1-50 Hz; against 4 cycles the
 * packets' PGA half-cycles and sliding thresholds come closer to those of
 * physical floor motions and the synthesized floor sets' sliding with them
 * (docs/synthesis.md 12). */
#define SL_SYNTH_WAVELET_RATE 0.5
#define SL_SYNTH_WAVELET_CYCLES 2.0
/* Spread start (docs/synthesis.md 3.1, eq. 1a): on a narrow-band floor
 * target, packets drawn more densely and weaker in proportion where a
 * log-uniform packet would carry more than 1/N of the start's expected
 * energy, so that the expected start spectrum is unchanged and the peak
 * band holds many packets. Default 0 (the log-uniform start): N = 32 cut
 * the extra attempts on narrow floors by up to 2.2 a set (D5-75 failures
 * 0.17-2.2 -> 0.04-0.22) but raised the mean sliding at mu g/ZPA 0.5 by up
 * to 5.4 standard errors, the example facility's design values by up to 5.7
 * and the broadened physical-floor ratios above 1.33 (docs/synthesis.md
 * 3.4); SL_SYNTH_WAVELET_SPREAD_TRIED is that N. */
#define SL_SYNTH_WAVELET_SPREAD 0.0
#define SL_SYNTH_WAVELET_SPREAD_TRIED 32.0
/* Log standard deviation of the peak level of synthetic motions (synth.c
 * peak_level): each motion's compression level drawn around aim x ZPA.
 * Default 0 (level aim x ZPA): 0.10-0.25 did not move the sliding of
 * synthesized floor sets at mu g/ZPA >= 0.7 (docs/synthesis.md 10). */
#define SL_SYNTH_PGA_SIGMA 0.0
/* Knee of the soft peak compression (synth.c compress_peaks): half-cycles
 * above SL_SYNTH_KNEE x aim x ZPA are mapped linearly onto [knee, 1] x aim x
 * ZPA when the peak exceeds aim x ZPA. */
#define SL_SYNTH_KNEE 0.9
/* The knee for recorded motions (--match): lower, so that the record's own
 * peaks keep their spacing (Taft 021: 3 peaks above 0.9 PGA before and
 * after matching; 8 with the knee at 0.9). */
#define SL_SYNTH_KNEE_RECORD 0.6
/* Record matching that keeps more of the record (docs/synthesis.md 3.6):
 * with match_margin X > 0, grid points where the record's S/T is already
 * inside the dead band [1 + X, 1 + tol_above - X] get no correction (r = 1),
 * so frequencies that comply are left as recorded. 0 (the default): every
 * point is corrected towards aim x T, as synthesis does; the dead band
 * biases a matched set's mean spectrum up (up to 1 + tol_above - X inside
 * the band), which the study's sets (means) must not have. */
#define SL_SYNTH_MATCH_MARGIN 0.0
/* ... applied to the content above fc = this x the frequency of the
 * target's largest SA only (the long-period content is left alone). */
#define SL_SYNTH_COMPRESS_FC_FRAC 0.5
/* Zero-phase high-pass below the lowest checked frequency f_lo of the
 * target (docs/synthesis.md 3.2): every DFT step multiplies bin f_k by the
 * Butterworth magnitude H(f) = 1/sqrt(1 + (f_c/f)^(2 order)),
 * f_c = hp_frac x f_lo, as record processing does (PEER corners
 * 0.03-0.1 Hz). Content below f_lo is not checked, hardly changes SA at
 * f >= f_lo, and is what makes ground displacement (D ~ A/(2 pi f)^2). */
#define SL_SYNTH_HP_FRAC 0.7
#define SL_SYNTH_HP_ORDER 4.0
/* Lowest frequency of the start wavelets, as a fraction of f_lo. */
#define SL_SYNTH_WAVELET_FLO_FRAC 1.0
/* Outside the checked frequency range the correction fades to none over
 * this many octaves. */
#define SL_SYNTH_EDGE_OCTAVES 1.0
/* A correction factor per iteration is clamped to [1/CLAMP, CLAMP]. */
#define SL_SYNTH_RATIO_CLAMP 4.0
/* Envelope: rise to 10 % of T, hold to 55 % of T, then exponential decay to
 * 5 % amplitude at T (D5-75 of E^2 alone: 0.38 T, 7.6 s for 20 s; the
 * matched motions measure 7.1 s and more). */
#define SL_SYNTH_RISE_FRAC 0.10
#define SL_SYNTH_HOLD_FRAC 0.55
#define SL_SYNTH_END_AMP 0.05

/* Half-cosine taper at each end of every iterate, s: the spectral step
 * spreads content to the ends (circular DFT); the floor starts and ends at
 * rest. */
#define SL_SYNTH_TAPER_S 0.5

/* Components of a set, in file and report order. */
typedef enum sl_synth_comp {
    SL_SYNTH_H1 = 0,
    SL_SYNTH_H2,
    SL_SYNTH_V,
    SL_SYNTH_NCOMP
} sl_synth_comp;

/* Pairs of a set for the correlation check: (H1,H2), (H1,V), (H2,V). */
#define SL_SYNTH_NPAIR 3

/* Every limit and knob. Fill with sl_synth_params_default(), then change. */
typedef struct sl_synth_params {
    /* check (and correction) grid, Hz; points per decade */
    double fmin_hz, fmax_hz, per_decade;
    /* acceptance limits */
    double tol_below;       /* fraction, SL_SYNTH_TOL_BELOW */
    double tol_above;       /* fraction, SL_SYNTH_TOL_ABOVE */
    size_t max_run_below;   /* points, SL_SYNTH_MAX_RUN_BELOW */
    double min_d5_75_s;     /* s, SL_SYNTH_MIN_D5_75_S */
    double min_duration_s;  /* s, SL_SYNTH_MIN_DURATION_S */
    double max_corr;        /* SL_SYNTH_MAX_CORR */
    double end_vel_frac;    /* of PGV, SL_SYNTH_END_VEL_FRAC */
    double end_disp_frac;   /* of PGD, SL_SYNTH_END_DISP_FRAC */
    size_t max_peaks;       /* peaks above 0.9 PGA, SL_SYNTH_MAX_PEAKS (ground-like
                               targets only: SL_SYNTH_PEAKS_MAX_AMP) */
    double pga_tol_below;   /* PGA/ZPA >= 1 - this, SL_SYNTH_PGA_TOL_BELOW */
    double psd_frac;        /* SRP 3.7.1 App. B: PSD >= psd_frac target PSD
                               (SL_PSD_FRAC, realism.h); 0 = not checked */
    /* iteration */
    unsigned max_iter;      /* >= 0; 0 = the initial motion only */
    unsigned max_attempts;  /* >= 1 */
    double aim;             /* > 0, SL_SYNTH_AIM */
    double wavelet_rate;    /* >= 0, SL_SYNTH_WAVELET_RATE (0: random phases) */
    double pga_sigma;       /* >= 0, SL_SYNTH_PGA_SIGMA */
    double wavelet_cycles;  /* > 0, SL_SYNTH_WAVELET_CYCLES */
    double wavelet_spread;  /* >= 0, SL_SYNTH_WAVELET_SPREAD (0: log-uniform) */
    /* envelope (fractions of the duration; end amplitude) */
    double rise_frac, hold_frac, end_amp;
    /* each end is multiplied by a half-cosine taper over this time, s, so
     * the motion starts and ends at rest (SL_SYNTH_TAPER_S) */
    double taper_s;
    /* zero-phase Butterworth high-pass at hp_frac x the target's lowest
     * checked frequency, of order hp_order (SL_SYNTH_HP_FRAC,
     * SL_SYNTH_HP_ORDER); hp_frac = 0: none */
    double hp_frac, hp_order;
    /* records: when > 0, no correction where S/T is in [1 + match_margin,
     * 1 + tol_above - match_margin] (SL_SYNTH_MATCH_MARGIN; 0: none) */
    double match_margin;
    /* 1 (default): the App. B PSD of every motion kept is computed and
     * reported (sl_synth_check.psd_min_ratio) even when psd_frac = 0; 0: it
     * is computed only when psd_frac > 0 (else those fields are NAN and
     * ok_psd is 1), as `seislide run` does, which shows it nowhere */
    int psd_report;
} sl_synth_params;

/* Fill p with the defaults above (grid: SL_SPECTRUM_FMIN_HZ..FMAX_HZ at
 * SL_SPECTRUM_PER_DECADE, 271 points). */
SL_API void sl_synth_params_default(sl_synth_params *p);

/* Check a parameter set: SL_OK or SL_EINVAL naming the bad field. */
SL_API sl_status sl_synth_params_check(const sl_synth_params *p, sl_error *err);

/* A target: a spectrum (borrowed; values > 0, damping in (0, 1)) and the
 * zero-period acceleration the motion's peak is scaled to, m/s^2. */
typedef struct sl_synth_target {
    const sl_spectrum *spec;
    double zpa_ms2;
} sl_synth_target;

/* ------------------------------------------------------------------ */
/* Targets                                                             */
/* ------------------------------------------------------------------ */

/* The RG 1.60 targets at PGA pga_ms2 (> 0) and damping zeta (in the guide's
 * range): H1 and H2 the horizontal spectrum, V the vertical (rg160.h), each
 * on sl_rg160_grid(dir, p->fmin_hz, p->fmax_hz, p->per_decade) so the
 * log-log interpolation is exact; zpa = PGA for all three. spec[c] are
 * allocated (free each with sl_spectrum_free). Returns SL_OK, SL_EINVAL,
 * SL_ENOMEM; on failure nothing is left allocated. */
SL_API sl_status sl_synth_targets_rg160(double pga_ms2, double zeta, const sl_synth_params *p,
                                        sl_spectrum *spec[SL_SYNTH_NCOMP],
                                        sl_synth_target tgt[SL_SYNTH_NCOMP], sl_error *err);

/* The damping a floor component is matched at: SL_SYNTH_DAMPING (5 %) when
 * the file gives it, else the lowest damping given (SRP practice matches
 * the 5 % spectrum). Returns the damping ratio (> 0). */
SL_API double sl_synth_floor_damping(const sl_floor *fl, sl_floor_comp c);

/* The targets of a floor: component c's spectrum at zeta (> 0, must be given
 * in the file) or, when zeta <= 0, at sl_synth_floor_damping(); zpa from
 * comp[c].zpa_ms2. Borrowed pointers into fl. Returns SL_OK or SL_EINVAL
 * (damping not given; err names the file and component). */
SL_API sl_status sl_synth_targets_floor(const sl_floor *fl, double zeta,
                                        sl_synth_target tgt[SL_SYNTH_NCOMP], sl_error *err);

/* ------------------------------------------------------------------ */
/* The plan: FFTW plans, buffers and tables for one length             */
/* ------------------------------------------------------------------ */

typedef struct sl_synth sl_synth;

/* A plan for motions of n samples (>= 16) at dt_s (> 0), with parameters p
 * (copied; NULL = defaults). Makes the FFTW r2c and c2r plans of length
 * N = the smallest 2^a 3^b 5^c 7^d >= n + ceil(1/(fmin dt)) (FFTW_ESTIMATE,
 * under the planner lock), the check grid, the bin-to-grid interpolation
 * table, the envelope and the baseline shapes. Returns NULL and fills err
 * (SL_EINVAL, SL_ENOMEM, SL_ESOLVER) on failure. Free with sl_synth_free. */
SL_API sl_synth *sl_synth_alloc(size_t n, double dt_s, const sl_synth_params *p, sl_error *err);

/* Free a plan; harmless on NULL. Every sl_synth_motion of it must be freed
 * first. */
SL_API void sl_synth_free(sl_synth *s);

SL_API size_t sl_synth_n(const sl_synth *s);        /* motion samples */
SL_API double sl_synth_dt(const sl_synth *s);       /* s */
SL_API size_t sl_synth_nfft(const sl_synth *s);     /* FFT length N */
SL_API const sl_synth_params *sl_synth_params_of(const sl_synth *s);
/* The check grid: *nf points, Hz, borrowed from the plan. */
SL_API const double *sl_synth_grid(const sl_synth *s, size_t *nf);
/* The envelope E(t_j), n values, borrowed. */
SL_API const double *sl_synth_envelope(const sl_synth *s);

/* SplitMix64 hash of (seed, set, comp, attempt), low 32 bits: the seed of
 * the motion's mt19937 stream. Pure function. */
SL_API unsigned long sl_synth_stream_seed(uint64_t seed, size_t set, sl_synth_comp comp,
                                          unsigned attempt);

/* ------------------------------------------------------------------ */
/* One motion: set / iterate / test                                    */
/* ------------------------------------------------------------------ */

/* Every other damping a floor file gives (docs/synthesis.md 4): the
 * motion's own spectrum at that damping against the file's table. */
#define SL_SYNTH_MAX_OTHER 8
typedef struct sl_synth_other {
    double damping;              /* the table's damping ratio */
    double min_ratio, max_ratio; /* this motion: lowest and highest S/T over the grid */
    double set_min, set_max;     /* the mean S/T of the sets checked together:
                                    lowest and highest over the grid */
    double f_set_min_hz, f_set_max_hz; /* where */
    int ok_set;                  /* set mean within [1 - tol_below, 1 + tol_above] */
} sl_synth_other;

/* Result of the checks of one motion. Ratios are computed / target PSA. */
typedef struct sl_synth_check {
    double damping;          /* damping matched */
    double f_lo_hz, f_hi_hz; /* grid range checked (grid inside the target's range) */
    size_t npoints;          /* grid points checked */
    double min_ratio, f_min_ratio_hz;  /* lowest S/T and where */
    double max_ratio, f_max_ratio_hz;  /* highest S/T and where */
    size_t run_below;        /* longest run of consecutive points with S < T */
    size_t n_below;          /* points with S < T */
    double d5_75_s;          /* strong-motion duration, s */
    double duration_s;       /* (n - 1) dt, s */
    double pga_ms2, zpa_ms2; /* peak |a| and the target ZPA, m/s^2 */
    double pgv_ms, pgd_m;    /* peaks of velocity and displacement */
    double v_end_ms, d_end_m;/* velocity and displacement at the end */
    double max_corr;         /* largest |rho| with the other components (NAN alone) */
    unsigned iterations;     /* correction iterations done (of the best iterate) */
    unsigned attempt;        /* phase set used (0 = first; records: 0) */
    /* realism (realism.h): reported; peaks and PSD are also checks */
    double pga_zpa;          /* PGA / target ZPA (emerges from the matching) */
    size_t peaks;            /* local maxima of |a| above 0.9 PGA */
    double va_s, adv2;       /* PGV/PGA (s) and PGA PGD/PGV^2 */
    double va_expect_s, adv2_expect; /* expected from the target (realism.h) */
    double psd_min_ratio, f_psd_min_hz; /* App. B: lowest PSD/target PSD, where */
    double corr_record;      /* records: correlation with the original (NAN) */
    double peaks_record;     /* records: the original's peaks above 0.9 PGA (NAN) */
    int ok_below, ok_above, ok_run, ok_d5_75, ok_duration, ok_end, ok_pga, ok_corr;
    int ok_peaks, ok_psd;
    int pass;                /* all of the above */
    /* other dampings of a floor file (sl_synth_check_dampings; 0 = none);
     * reported, not part of pass: the check is on the set mean */
    size_t n_other;
    sl_synth_other other[SL_SYNTH_MAX_OTHER];
} sl_synth_check;

typedef struct sl_synth_motion sl_synth_motion;

/* A workspace for one motion at a time, for plan s (borrowed: keep s alive).
 * Buffers are fftw_malloc'd once here and reused by every set/iterate.
 * Returns NULL (err filled, SL_ENOMEM) on failure. */
SL_API sl_synth_motion *sl_synth_motion_alloc(const sl_synth *s, sl_error *err);

/* Free a workspace; harmless on NULL. */
SL_API void sl_synth_motion_free(sl_synth_motion *m);

/* Start a synthetic motion for target t: random phases from the stream
 * sl_synth_stream_seed(seed, set, comp, attempt), amplitudes T(f)/sqrt(f)
 * (T extended below its range at constant SD, above at its last value),
 * times the envelope; makes iteration 0 (motion and spectrum). Returns
 * SL_OK, SL_EINVAL (bad target), SL_ENOMEM, SL_ESOLVER. */
SL_API sl_status sl_synth_set_random(sl_synth_motion *m, const sl_synth_target *t, uint64_t seed,
                                     size_t set, sl_synth_comp comp, unsigned attempt,
                                     sl_error *err);

/* Start from a recorded motion acc_ms2[0..n-1] (n <= the plan's n, sampled
 * at the plan's dt; zero-extended to it), no envelope; makes iteration 0.
 * Returns SL_OK, SL_EINVAL (n == 0, too long, non-finite or all-zero
 * samples, bad target), SL_ENOMEM, SL_ESOLVER. */
SL_API sl_status sl_synth_set_record(sl_synth_motion *m, const sl_synth_target *t,
                                     const double *acc_ms2, size_t n, sl_error *err);

/* One iteration (see above): spectral correction of the current iterate,
 * peak limiting, baseline, scaling, spectrum. Keeps the best iterate.
 * Returns SL_OK, SL_EINVAL (no successful set_* before), SL_ESOLVER
 * (non-finite values). */
SL_API sl_status sl_synth_iterate(sl_synth_motion *m, sl_error *err);

/* 1 when the spectral checks (below, above, run) pass for the best iterate,
 * else 0. */
SL_API int sl_synth_test(const sl_synth_motion *m);

/* Iterations done since the last set_*. */
SL_API unsigned sl_synth_iterations(const sl_synth_motion *m);

/* The best iterate so far (n samples, m/s^2) and its spectrum on the grid
 * (NAN outside the target's range); borrowed, valid until the next call on
 * m. */
SL_API const double *sl_synth_acc(const sl_synth_motion *m);
SL_API const double *sl_synth_psa(const sl_synth_motion *m);
/* The target on the grid (NAN outside its range); borrowed. */
SL_API const double *sl_synth_target_psa(const sl_synth_motion *m);

/* An end residual x (v_end_ms or d_end_m) as printed: 0 when |x| is at
 * most SL_SYNTH_END_ROUNDOFF x peak (its PGV or PGD), else x. Round-off
 * differs with the libm routines a CPU selects (FMA or not); printed, it
 * would make outputs differ across machines. */
SL_API double sl_synth_end_residual(double x, double peak);

/* Every check of the best iterate except the correlation (max_corr = NAN,
 * ok_corr = 1), into *out. */
SL_API void sl_synth_check_motion(const sl_synth_motion *m, sl_synth_check *out);

/* Pearson correlation coefficient of a and b over n samples (means
 * removed): sum (a - ma)(b - mb) / sqrt(sum (a - ma)^2 sum (b - mb)^2).
 * 0 when either is constant. */
SL_API double sl_synth_corr(const double *a, const double *b, size_t n);

/* ------------------------------------------------------------------ */
/* Whole sets                                                          */
/* ------------------------------------------------------------------ */

/* One three-component set and its checks. Motions are owned (free with
 * sl_synth_set_clear); absent components (records) are NULL. */
typedef struct sl_synth_set {
    sl_set set;                    /* the project's set type (motion.h): h1, h2, v,
                                      owned here; NULL when absent (records) */
    sl_synth_check check[SL_SYNTH_NCOMP];
    double corr[SL_SYNTH_NPAIR];   /* (H1,H2), (H1,V), (H2,V); NAN if absent */
    int pass;                      /* every check of every present component */
} sl_synth_set;

/* Component c of a set: set.h1, set.h2 or set.v (NULL when absent). */
SL_API sl_motion *sl_synth_set_motion(const sl_synth_set *s, sl_synth_comp c);

/* Free the motions of a set and zero it; harmless on NULL. */
SL_API void sl_synth_set_clear(sl_synth_set *set);

/* Progress callback: `done` of `total` motion runs finished. Called from one
 * thread at a time (inside an OpenMP critical section). */
typedef void (*sl_synth_progress)(void *ctx, size_t done, size_t total);

/* Synthesize `count` sets (indices first_set .. first_set + count - 1) for
 * targets tgt[H1, H2, V] with plan s: for each component, set_random, then
 * iterate until test passes or p->max_iter; a component that fails its
 * spectral checks is redone with the next attempt (new phases), and so is
 * the later component of a pair whose |rho| > max_corr, up to max_attempts.
 * Runs motions in parallel with OpenMP; the results do not depend on the
 * thread count. out[0..count-1] are filled (motions owned by out; label
 * "setNN_h1" etc.). Returns SL_OK when every check passed, SL_ENOCONV when
 * some motion failed a check (out complete; see pass flags), or SL_EINVAL,
 * SL_ENOMEM, SL_ESOLVER (out cleared). progress may be NULL. */
SL_API sl_status sl_synth_make_sets(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                                    uint64_t seed, size_t first_set, size_t count,
                                    sl_synth_set *out, sl_synth_progress progress, void *ctx,
                                    sl_error *err);

/* Called by sl_synth_make_sets_then once for each set, as soon as that set
 * is final: k is its index in the call (out[k] filled, its pass flags set;
 * its index in the run is first_set + k). Called inside the call's OpenMP
 * parallel region, from a task, on any thread, for sets in any order and
 * concurrently with other sets' synthesis: it must touch only what is set
 * k's own, and may spawn OpenMP tasks (the call returns after them). A
 * non-zero return (err filled) stops the call, which then returns it. */
typedef sl_status (*sl_synth_ready)(void *ctx, size_t k, sl_error *err);

/* sl_synth_make_sets with ready(ready_ctx, k, err) for each set as it
 * becomes final (ready may be NULL). The sets are made as a flow of OpenMP
 * tasks, a task per component attempt: when the last running component of
 * a set ends, its thread makes the set's redo decisions (functions of that
 * set's results only) and spawns the redone components, so no thread waits
 * for other sets. out[k] are the same bits as sl_synth_make_sets gives, for
 * any thread count. Same returns; on a failure other than SL_ENOCONV out is
 * cleared, and ready may have been called for some sets. */
SL_API sl_status sl_synth_make_sets_then(const sl_synth *s,
                                         const sl_synth_target tgt[SL_SYNTH_NCOMP],
                                         uint64_t seed, size_t first_set, size_t count,
                                         sl_synth_set *out, sl_synth_progress progress,
                                         void *ctx, sl_synth_ready ready, void *ready_ctx,
                                         sl_error *err);

/* One set (set index `set`; its three components in parallel): the unit
 * timed by the benchmark. Equal, bit for bit, to set `set` of a
 * sl_synth_make_sets() batch with the same seed. Same returns as
 * sl_synth_make_sets. */
SL_API sl_status sl_synth_make_set(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                                   uint64_t seed, size_t set, sl_synth_set *out, sl_error *err);

/* Match recorded components rec[H1, H2, V] (any may be NULL, at least one
 * present; all at the plan's dt, each n <= the plan's n) to tgt: the same
 * iteration from the records' Fourier phases. out filled as above (labels
 * "match_h1" etc.). Same returns as sl_synth_make_sets. */
SL_API sl_status sl_synth_match_set(const sl_synth *s, const sl_synth_target tgt[SL_SYNTH_NCOMP],
                                    const sl_motion *const rec[SL_SYNTH_NCOMP], sl_synth_set *out,
                                    sl_error *err);

/* Every other damping of a floor file, checked on the motions' own spectra
 * (the ASCE method reads e.g. the 10 % table while the NLTHA sees the
 * motions matched at 5 %): for each component c of sets[0..nsets-1] and
 * each spectrum fl gives for c at a damping other than check[c].damping
 * (at most SL_SYNTH_MAX_OTHER), the motion's PSA at that damping on the
 * plan's grid inside the table's frequency range, S/T per motion (min,
 * max) and the mean of S/T over the nsets sets (lowest and highest over
 * the grid, ok_set when inside [1 - tol_below, 1 + tol_above] of the plan's
 * parameters). Fills check[c].n_other and other[] (0 for a component
 * absent from some set, as with records). Returns SL_OK, SL_EINVAL (no
 * sets), SL_ENOMEM, SL_ESOLVER. */
SL_API sl_status sl_synth_check_dampings(const sl_synth *s, const sl_floor *fl, sl_synth_set *sets,
                                         size_t nsets, sl_error *err);

/* 1 when every set-mean check of the other dampings passed (or there are
 * none) for sets[0..nsets-1] after sl_synth_check_dampings. */
SL_API int sl_synth_dampings_ok(const sl_synth_set *sets, size_t nsets);

/* ------------------------------------------------------------------ */
/* Input and output helpers                                            */
/* ------------------------------------------------------------------ */

/* Resample acc_ms2 (n samples at dt_s) to dt_new_s by linear interpolation
 * (exact for the piecewise-linear reading of the record), over the same
 * duration: floor((n - 1) dt/dt_new) + 1 samples, returned in *n_new.
 * Returns a malloc'd array (caller frees) or NULL on bad input. */
SL_API double *sl_synth_resample(const double *acc_ms2, size_t n, double dt_s, double dt_new_s,
                                 size_t *n_new);

/* The step record matching uses for a record sampled at dt_s: the largest
 * dt_s/k <= SL_SYNTH_MAX_DT_S, k whole (dt_s itself when it is fine enough),
 * so every record sample stays a sample. */
SL_API double sl_synth_match_dt(double dt_s);

/* m resampled to dt_s by sl_synth_resample (a plain copy when m is already
 * at dt_s within 1e-9 relative), keeping its path and label. Returns NULL on
 * bad input or allocation failure; free with sl_motion_free. */
SL_API sl_motion *sl_synth_resample_motion(const sl_motion *m, double dt_s);

/* Write a motion as a PEER-style AT2 file readable by sl_motion_read():
 * line 1 "SEISLIDE SYNTHETIC MOTION", line 2 the title, line 3
 * "ACCELERATION TIME SERIES IN UNITS OF G", line 4 "NPTS= n, DT= dt SEC",
 * then 5 values a line in g, %.9E (a relative rounding of 5e-10). Written
 * atomically (atomic.h). Returns SL_OK or SL_EIO/SL_ENOMEM (err names the
 * path). */
SL_API sl_status sl_synth_write_at2(const char *path, const sl_motion *m, const char *title,
                                    sl_error *err);

/* Short name of a component: "h1", "h2", "v". */
SL_API const char *sl_synth_comp_name(sl_synth_comp c);

#endif
