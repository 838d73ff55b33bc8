#ifndef SL_SCATTER_H
#define SL_SCATTER_H

#include <stddef.h>
#include <stdint.h>

#include "core/status.h"
#include "io/floor.h"
#include "io/motion.h"
#include "slide/model.h"

/* Record-to-record intensity scatter of synthesized sets
 * (docs/synthesis.md 11, docs/run.md "Intensity scatter").
 *
 * A floor spectrum is the mean of the spectra of the floor motions behind
 * it, and those motions differ in intensity from one input to the next
 * (physical floor motions of 83 records: coefficient of variation of the
 * PGA 0.24-0.31). A set synthesized to match the spectrum motion by motion
 * (SRP 3.7.1) has none of that scatter, and sliding near mu g = ZPA is
 * strongly convex in intensity, so its mean sliding falls short of the
 * real motions' (measured: 0.5 x at mu g/ZPA = 0.7, 0.1 x at 0.9). The
 * horizontals of set k are given an intensity factor
 *
 *     eps = exp(sigma z - sigma^2 / 2),  z ~ N(0, 1)                (R1)
 *
 * (log-normal, log standard deviation sigma, E[eps] = 1: the expected
 * set-mean spectrum stays the target; only the spread is added).
 *
 * No random factor is drawn for the design value: by the block's equation
 * of motion (slide.h (1)), u'' = -eps a_g - mu N s, the peak obeys exactly
 *
 *     u(eps a_g, a_v; mu) = eps u(a_g, a_v; mu / eps)                  (R2)
 *
 * (w = u / eps solves the unscaled equation with mu / eps; the vertical, and
 * so N, is left as synthesized). So each set's expected peak over eps,
 *
 *     Y(mu) = E[eps u(mu / eps)] = sum_j w_j eps_j u(mu / eps_j)       (R3)
 *
 * is computed from one NLTHA of the set on a log-spaced friction grid
 * (SL_SCATTER_PER_DECADE points a decade, covering every mu / eps_j), with
 * u interpolated in ln mu by Steffen's monotone cubic (GSL; no overshoot, so
 * no negative peak and no wiggle at the threshold where sliding stops), and z_j on [-SL_SCATTER_ZMAX, SL_SCATTER_ZMAX] in steps
 * SL_SCATTER_DZ with trapezoid weights w_j proportional to phi(z_j),
 * scaled so that sum_j w_j eps_j = 1 (E[eps] = 1 exactly, whatever the
 * truncation). The sets' Y are independent and identically distributed, so the
 * statistics over sets (stats.h) hold as they are, and the scatter adds no
 * sampling noise of its own.
 *
 * sigma of a floor (docs/run.md, "Intensity scatter"; docs/synthesis.md 11).
 * The floor motions behind a spectrum scatter in
 * intensity because the ground motions behind them do, at the frequencies
 * the building amplifies: records scaled to one PGA differ little in their
 * high-frequency spectra and much in their low-frequency ones. So sigma is
 * read from the floor spectrum as
 *
 *     sigma = min(sqrt(sigma_g(f_c)^2 + sigma_0^2), SL_SCATTER_SIGMA_MAX)   (R4)
 *
 * f_c: the centroid in ln f of the floor's amplification over its ZPA,
 *
 *     ln f_c = sum_H int e_H(f) ln f dln f / sum_H int e_H(f) dln f,
 *     e_H(f) = max(SA_H(f) / ZPA_H - 1, 0)                               (R5)
 *
 * over both horizontals H, SA_H at the damping the synthesis matches
 * (sl_synth_floor_damping: 5 % when given), by the trapezoid rule on
 * SL_SCATTER_FC_PER_DECADE points a decade over the table's range (log-log
 * interpolation). Where no value exceeds the ZPA, f_c is the frequency of
 * the highest SA of either horizontal.
 * sigma_g(f): the log standard deviation of SA(f, 5 %) over the horizontal
 * components of the 83 three-component records of the record collection,
 * each record scaled to one larger horizontal PGA (`tailfloors -g`: 1.11 at
 * 0.1 Hz, 0.68 at 1 Hz, 0.43 at 2.4 Hz, 0.31 at 5.6 Hz, 0.19 at 42 Hz),
 * linear in ln f between its points, constant beyond its ends.
 * sigma_0 = SL_SCATTER_SIGMA_0: what sliding near the threshold needs beyond
 * that (the physical motions at one PGA still differ in how they slide
 * there), fitted to the mean sliding of physical floor motions at mu g/ZPA
 * 0.5-1.0 on 8 buildings and checked on 18 others (docs/synthesis.md 11:
 * 17 of those 18 within 0.85-1.2 in geometric mean). */

#define SL_SCATTER_ZMAX 5.0
#define SL_SCATTER_DZ 0.1
#define SL_SCATTER_PER_DECADE 32
#define SL_SCATTER_SIGMA_MAX 1.0 /* log standard deviation, largest accepted */
#define SL_SCATTER_SIGMA_0 0.13   /* (R4): beyond the ground spectra's scatter */
#define SL_SCATTER_FC_PER_DECADE 100 /* (R5): integration points a decade */

/* sigma of (R4) for a floor: > 0 and at most SL_SCATTER_SIGMA_MAX; NAN when
 * the floor has no horizontal spectrum (not a floor sl_floor_load returns).
 * The one rule of every caller that needs a floor's intensity scatter
 * (the run, the probability of tipping). */
double sl_scatter_sigma_of_floor(const sl_floor *fl);

/* f_c of (R5), Hz, of a floor; NAN as above. */
double sl_scatter_floor_fc_hz(const sl_floor *fl);

/* f_c of (R5), Hz, of two horizontal spectra h[0], h[1] (each at the
 * damping the motions are matched at) with their ZPAs zpa_ms2[] (e.g. the
 * targets of synth.h: spec and zpa); NAN when one is missing, empty or its
 * ZPA not > 0. */
double sl_scatter_fc_hz(const sl_spectrum *const h[2], const double zpa_ms2[2]);

/* sigma of (R4) at a centroid frequency f_hz (> 0; NAN otherwise). */
double sl_scatter_sigma_of_fc(double f_hz);

/* sigma_g(f_hz) of (R4), the records' table (NAN for f_hz <= 0). */
double sl_scatter_sigma_ground(double f_hz);

/* eps of (R1) for set `set` into *eps, z = Phi^-1(u), u from GSL's mt19937
 * seeded with sl_synth_stream_seed(seed ^ "scatter!", set, H1, 0): a random
 * draw for Monte Carlo checks of (R3) (tests, tools); exactly 1 when
 * sigma_ln is 0. Returns SL_OK or SL_ENOMEM (GSL could not allocate its
 * generator; GSL's error handler is off meanwhile, gslerr.h). */
sl_status sl_scatter_factor(uint64_t seed, size_t set, double sigma_ln, double *eps,
                            sl_error *err);

/* out = a copy of in with H1 and H2 scaled by f and V as it is (owned:
 * sl_set_free_motions). Returns SL_OK or SL_ENOMEM (out left empty). */
sl_status sl_set_scaled_h_copy(const sl_set *in, double f, sl_set *out, sl_error *err);

/* The quadrature (R3) for a friction grid mu[n_mu] (each >= 0). */
typedef struct sl_scatter sl_scatter;

/* sigma_ln in (0, SL_SCATTER_SIGMA_MAX]. NULL with err on bad input or no
 * memory. */
sl_scatter *sl_scatter_alloc(double sigma_ln, const double *mu, size_t n_mu, sl_error *err);
void sl_scatter_free(sl_scatter *s);

/* The friction values the NLTHA must be run at (borrowed, increasing). */
const double *sl_scatter_grid(const sl_scatter *s, size_t *n);

/* y[k] = Y(mu[k]) of (R3) from u[q] >= 0, the peaks at
 * sl_scatter_grid()[q]. SL_OK, SL_ENOMEM, or SL_ESOLVER (GSL could not
 * set up the interpolation; its error handler is off meanwhile, gslerr.h). */
sl_status sl_scatter_mean(const sl_scatter *s, const double *u, double *y, sl_error *err);

/* (R3) of n sets from their NLTHA on the grid, res[i * nq + q] for set i
 * at sl_scatter_grid()[q]: y[i * n_mu + k] = Y_i(mu[k]), and err_est (NULL:
 * not wanted) the same quadrature of the error estimates err_est_m. SL_OK,
 * SL_ENOMEM or SL_ESOLVER (sl_scatter_mean). */
sl_status sl_scatter_results(const sl_scatter *s, const sl_slide_result *res, size_t n,
                             double *y, double *err_est, sl_error *err);

/* NLTHA of sets[0..n) on the grid (sl_slide_batch, in parallel) and (R3)
 * per set: y[i * n_mu + k] = Y_i(mu[k]); err_est (NULL: not wanted) gets
 * the same quadrature of the engine's error estimates err_est_m. SL_OK, or
 * the engine's error, or SL_ENOMEM. */
sl_status sl_scatter_slide_batch(const sl_scatter *s, const sl_set *sets, size_t n,
                                 const sl_slide_opts *so, double *y, double *err_est,
                                 sl_error *err);

#endif
