/*
 * slide.h - nonlinear time-history analysis (NLTHA) of a rigid block sliding
 * on a level floor with isotropic Coulomb friction (static = kinetic).
 *
 * Equation of motion (the source study's model; docs/model.md, "Equation
 * of motion"), u = block displacement relative to the floor, a_g =
 * horizontal floor acceleration (1-D or 2-D), a_v = vertical floor
 * acceleration (up positive):
 *
 *     u'' = -a_g(t) - mu N(t) s,   N = max(g + a_v, 0)              (1)
 *     s = u'/|u'| while sliding,   |s| <= 1 while stuck.
 *
 * N <= 0 is lift-off: no friction (the instants are counted). The input is
 * taken as piecewise linear between samples; after the last sample the floor
 * is at rest (a_g = a_v = 0) and the block slides on until it stops, so the
 * peak is never cut off.
 *
 * Integrators (docs/model.md, docs/integrators.md):
 *  - 1-D (H1 only): exact for piecewise-linear input. Within a step the
 *    relative velocity is a quadratic in time; stop, start and lift-off
 *    instants are roots of quadratics or linear functions.
 *  - 2-D (H1 and H2): error-controlled (kernel2d.h). Per sample, a step of
 *    dt against two of dt/2 (implicit midpoint friction, position exact
 *    for linear forcing); where they disagree by more than the block's
 *    share of max(rtol peak, atol), or a stop is near, the sample is redone
 *    with 1, 2, 4, ... sub-steps, with exactly located onsets (roots of
 *    |a|^2 = (mu N)^2) and stops. The differences give err_est_m, the
 *    estimated error of the peak; a block whose estimate exceeds the
 *    tolerance is run again tighter. `substeps` > 0 fixes the sub-steps
 *    instead (no estimate). docs/integrators.md.
 *  - Asymmetric 1-D: friction mu against sliding toward -x ("downslope",
 *    where a positive floor acceleration pushes the block) and mu*up_ratio
 *    toward +x; up_ratio = INFINITY is one-way sliding as in Newmark's
 *    asymmetric case and SLAMMER's rigid-block analysis.
 *
 * Units: SI throughout (m, s, m/s^2); mu dimensionless.
 */
#ifndef SL_SLIDE_H
#define SL_SLIDE_H

#include <stddef.h>

#include "core/api.h"
#include "slide/model.h"


/* The smallest mu at which the block can never slide:
 * max_i |a_h(t_i)| / N(t_i) over samples (INFINITY with lift-off). Exact for
 * piecewise-linear input since |a_h| is convex and N linear on each step.
 * With up_ratio != 1 this is the threshold for the downslope resistance. */
SL_API double sl_slide_mu_threshold(const sl_set *set, const sl_slide_opts *opts);

/* Analyse one checked set for n_mu friction coefficients (each >= 0) at
 * once; res[k] is for mu[k]. mu at or above the threshold is not
 * integrated (flag SL_SLIDE_SKIPPED, zero displacement). Returns SL_OK or an
 * error (bad mu, bad options, solver failure for the reference models). */
SL_API sl_status sl_slide_run(const sl_set *set, const double *mu, size_t n_mu,
                              const sl_slide_opts *opts, sl_slide_result *res,
                              sl_error *err);

/* As sl_slide_run for one mu, also returning the history (*hist, caller
 * frees with sl_history_free). */
SL_API sl_status sl_slide_history(const sl_set *set, double mu, const sl_slide_opts *opts,
                                  sl_slide_result *res, sl_history **hist, sl_error *err);

/* The friction values of one work item of sl_slide_batch (a set's mu are
 * run in chunks of this many; each (set, mu) gives the same bits whatever
 * the chunking, so a caller may run the chunks of a set as it likes). */
#define SL_SLIDE_BATCH_CHUNK 16

/* Many sets: res[i * n_mu + k] for set i and mu[k]; runs the sets in
 * parallel with OpenMP. Results do not depend on the thread count. */
SL_API sl_status sl_slide_batch(const sl_set *sets, size_t n_sets, const double *mu,
                                size_t n_mu, const sl_slide_opts *opts,
                                sl_slide_result *res, sl_error *err);

#endif
