/*
 * realism.h - measures of whether an acceleration history looks like a real
 * earthquake motion, beyond the spectral checks (US NRC SRP 3.7.1: motions
 * consistent with the characteristic values of real ones; docs/synthesis.md
 * section 4).
 *
 *  - Peaks near the PGA: the number of local maxima of |a| (sample i with
 *    |a_i| > |a_{i-1}| and |a_i| >= |a_{i+1}|) above frac x PGA. Real
 *    horizontal records (338 PEER NGA-West2, USGS and CWA components): median 1, 90th
 *    percentile 3, maximum 7 at frac = 0.9. Clipping makes dozens.
 *  - Characteristic ratios (SRP 3.7.1, "consistent with characteristic
 *    values"): V/A = PGV/PGA and AD/V^2 = PGA PGD/PGV^2. RG 1.60 rests on
 *    Newmark-Hall: V/A = 48 in/s per g (1.219 m/s per g), D/A = 36 in per g
 *    (0.914 m per g), so AD/V^2 = 386.09 x 36/48^2 = 6.03.
 *  - Expected ratios of any spectrum (floors): a stationary motion whose
 *    one-sided PSD G(f) is compatible with a PSA spectrum S(f) has, to first
 *    order, G(f) ~ S(f)^2/f (G = 4 zeta S^2/(pi p^2 f), eq. R1 below, with
 *    a slowly varying peak factor p). Its spectral moment ratios give
 *        V/A ~ sqrt(int G/(2 pi f)^2 df / int G df),
 *        D/A ~ sqrt(int G/(2 pi f)^4 df / int G df),
 *    over the spectrum's range. The peak factors of a, v and d differ, so
 *    the moment ratios are calibrated once on RG 1.60 (5 %, horizontal):
 *    expected = moment ratio x (Newmark-Hall value / moment ratio of
 *    RG 1.60). RG 1.60 thus gets 48 in/s and 36 in per g exactly, and a
 *    floor spectrum narrow-banded at f0 gets V/A -> 1/(2 pi f0).
 *  - Minimum power spectral density (SRP 3.7.1 Appendix B, as commonly
 *    applied, e.g. Montejo 2025): the one-sided PSD of the motion over its
 *    strong-motion window [t5, t75] (5 % and 75 % of Arias intensity),
 *        G_k = 2 dt^2 |X_k|^2 / T_s,  X = DFT of a(t5..t75),   (R2)
 *    averaged over f +- 20 %, must be at least psd_frac (0.7) of the
 *    target PSD at every frequency of 0.3-24 Hz. The target PSD is the one
 *    compatible with the target spectrum for that strong-motion duration
 *    T_s (random vibration, Vanmarcke 1976):
 *        G(f) = 4 zeta S(f)^2 / (pi p^2 f),                     (R1)
 *        p = sqrt(2 ln(2 f T_s)) + 0.5772/sqrt(2 ln(2 f T_s))   (Davenport)
 *    (from sigma_u^2 = G/(8 zeta w^3) of a white-noise-driven oscillator
 *    and S = w^2 p sigma_u).
 *
 * Units: SI (s, Hz, m, m/s, m/s^2). Library code: no printing.
 */
#ifndef SL_REALISM_H
#define SL_REALISM_H

#include <stddef.h>

#include "core/api.h"
#include "core/status.h"
#include "signal/spectrum.h"

/* Newmark-Hall characteristic values behind RG 1.60 (per g of PGA). */
#define SL_NH_V_PER_G_MS 1.2192   /* 48 in/s */
#define SL_NH_D_PER_G_M 0.9144    /* 36 in */
/* Peaks above this fraction of the PGA are counted. */
#define SL_REALISM_PEAK_FRAC 0.9
/* SRP 3.7.1 Appendix B: the motion's PSD at least this fraction of the
 * target PSD over [SL_PSD_FMIN_HZ, SL_PSD_FMAX_HZ], averaged over f +- 20 %. */
#define SL_PSD_FRAC 0.7
#define SL_PSD_FMIN_HZ 0.3
#define SL_PSD_FMAX_HZ 24.0
#define SL_PSD_WINDOW 0.20

/* Local maxima of |a| above frac x max|a| (definition above). 0 for n < 1
 * or an all-zero motion. */
SL_API size_t sl_realism_peaks_above(const double *acc, size_t n, double frac);

/* Characteristic ratios of a motion from its peaks: *va_s = PGV/PGA (s),
 * *adv2 = PGA PGD / PGV^2 (dimensionless). NAN when a peak is zero. */
SL_API void sl_realism_ratios(double pga_ms2, double pgv_ms, double pgd_m, double *va_s,
                              double *adv2);

/* Expected V/A (s) and D/A (s^2) of a spectrum (any damping, log-log
 * interpolated; values > 0) by the calibrated moment ratios above, and
 * AD/V^2 = (D/A)/(V/A)^2. Integrals by the trapezoid rule in ln f on
 * 100 points per decade over the spectrum's range. Returns SL_OK or
 * SL_EINVAL (fewer than 2 points). */
SL_API sl_status sl_realism_expected(const sl_spectrum *s, double *va_s, double *da_s2,
                                     double *adv2, sl_error *err);

/* Result of the minimum-PSD check of one motion. */
typedef struct sl_psd_check {
    double t5_s, t75_s;      /* strong-motion window, s */
    double min_ratio;        /* lowest averaged PSD / target PSD over the band */
    double f_min_ratio_hz;   /* where */
    int ok;                  /* min_ratio >= frac */
} sl_psd_check;

/* The Appendix B check of acc (n samples at dt_s) against target spectrum
 * `target` (PSA, its own damping) with limit frac over [fmin_hz, fmax_hz]
 * (clipped to the target's range). Uses FFTW (FFTW_ESTIMATE, under the
 * planner lock). Returns SL_OK, SL_EINVAL, SL_ENOMEM. */
SL_API sl_status sl_psd_check_motion(const double *acc, size_t n, double dt_s,
                                     const sl_spectrum *target, double frac, double fmin_hz,
                                     double fmax_hz, sl_psd_check *out, sl_error *err);

#endif
