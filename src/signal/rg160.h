/*
 * rg160.h - US NRC Regulatory Guide 1.60 design response spectra
 * ("Design Response Spectra for Seismic Design of Nuclear Power Plants",
 * Rev. 1 1973 = Rev. 2 2014 numerically; Tables I and II, Figures 1 and 2).
 *
 * The spectrum is scaled to a peak ground acceleration a. It is given by four
 * control points joined by straight lines in log SA against log f:
 *
 *                      horizontal   vertical
 *     A (ZPA)            33 Hz        33 Hz    SA = a
 *     B                   9 Hz         9 Hz    SA = B(z) a
 *     C                 2.5 Hz       3.5 Hz    SA = C(z) a
 *     D                0.25 Hz      0.25 Hz    SD = D(z) x 36 in x a/g
 *
 * SA = a above 33 Hz; below 0.25 Hz the displacement stays at SD_D, so
 * SA = (2 pi f)^2 SD_D (a line of slope 2). At D, SA_D = (2 pi 0.25)^2 SD_D.
 * The vertical ZPA equals the horizontal PGA.
 *
 * Amplification factors B, C, D are tabulated at 0.5, 2, 5, 7 and 10 %
 * damping (Tables I and II of the guide). Between tabulated dampings each
 * factor is interpolated linearly in ln(damping):
 *
 *     X(z) = X_i + (X_{i+1} - X_i) ln(z/z_i)/ln(z_{i+1}/z_i),           (1)
 *
 * exact at the tabulated dampings. The table itself is linear in ln(z) to
 * its rounding: each interior value is reproduced from its neighbours by (1)
 * within 0.01 (linear in z misses by up to 0.76). Dampings outside
 * [0.5 %, 10 %] are refused (no extrapolation). See docs/spectra.md.
 *
 * Units: SI (Hz, m/s^2); g = SL_G; 1 in = SL_INCH_M.
 */
#ifndef SL_RG160_H
#define SL_RG160_H

#include <stddef.h>

#include "core/api.h"
#include "core/status.h"
#include "core/units.h"

typedef enum sl_rg160_dir {
    SL_RG160_HORIZONTAL = 0,
    SL_RG160_VERTICAL = 1
} sl_rg160_dir;

/* Number of control points and of tabulated dampings. */
#define SL_RG160_NCONTROL 4
#define SL_RG160_NDAMPING 5

/* Range of damping ratios the guide tabulates. */
#define SL_RG160_ZETA_MIN 0.005
#define SL_RG160_ZETA_MAX 0.10

/* Spectral displacement per 1 g of PGA at the control point D: 36 in. */
#define SL_RG160_DISP_PER_G_M (36.0 * SL_INCH_M)

/* The i-th tabulated damping ratio, ascending (0.005 ... 0.10) for
 * i = 0 .. SL_RG160_NDAMPING - 1; NaN for any other i. (A function, not
 * an array: the library exports no data.) */
SL_API double sl_rg160_damping(size_t i);

/* Amplification factors at damping zeta by (1): B and C multiply the PGA,
 * D multiplies 36 in x PGA/g. Returns SL_OK or SL_EINVAL (zeta outside
 * [SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX] or not finite). Any output may be
 * NULL. */
SL_API sl_status sl_rg160_factors(sl_rg160_dir dir, double zeta, double *b, double *c,
                                  double *d, sl_error *err);

/* Control points D, C, B, A (ascending frequency) of the spectrum at
 * damping zeta scaled to pga_ms2 (>= 0): f_hz[4] and sa_ms2[4]
 * (pseudo-spectral acceleration, m/s^2). Returns SL_OK or SL_EINVAL. */
SL_API sl_status sl_rg160_control(sl_rg160_dir dir, double zeta, double pga_ms2,
                                  double f_hz[SL_RG160_NCONTROL],
                                  double sa_ms2[SL_RG160_NCONTROL], sl_error *err);

/* Pseudo-spectral acceleration of the design spectrum at n frequencies
 * f_hz (> 0, any order) into psa_ms2 (caller's array of n). Straight lines
 * in log-log between the control points, SA = PGA above A, constant SD below
 * D (see above). Returns SL_OK or SL_EINVAL (bad damping, pga_ms2 < 0 or not
 * finite, a frequency not positive). */
SL_API sl_status sl_rg160_psa(sl_rg160_dir dir, double zeta, double pga_ms2, const double *f_hz,
                              size_t n, double *psa_ms2, sl_error *err);

/* A frequency grid for the design spectrum: the log grid of
 * sl_spectrum_grid(fmin_hz, fmax_hz, per_decade) with the control
 * frequencies of `dir` that lie strictly inside (fmin, fmax) added, so
 * that log-log interpolation between grid points reproduces the spectrum
 * exactly. Sorted, no duplicates (relative 1e-9). Returns a malloc'd array
 * (caller frees) and its length in *n, or NULL on bad input. */
SL_API double *sl_rg160_grid(sl_rg160_dir dir, double fmin_hz, double fmax_hz, double per_decade,
                             size_t *n);

#endif
