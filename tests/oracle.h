/*
 * oracle.h - independent references shared by the tests: the ground
 * velocity and displacement of a piecewise-linear record, integrated by
 * hand (src/verify/closed_forms.h) and not by the library, a motion over a
 * caller-owned array, and a design input over hand-chosen numbers (the
 * tests give the expected design values).
 */
#ifndef SL_TEST_ORACLE_H
#define SL_TEST_ORACLE_H

#include <stddef.h>

#include "io/motion.h"
#include "method/design.h"
#include "verify/closed_forms.h"

/* A motion over a caller-owned array (no file, nothing to free). */
static inline sl_motion oracle_motion(double *a, size_t n, double dt)
{
    sl_motion m = {NULL, NULL, n, dt, a};
    return m;
}

/* Ground velocity *v and displacement *d at time t of the samples a (taken
 * as piecewise linear; after the last sample the ground keeps its velocity):
 * the closed form of src/verify/closed_forms.h, which the verification
 * problems use too. */
static inline void oracle_ground_vd(const double *a, size_t n, double dt, double t, double *v,
                                    double *d)
{
    sl_closed_ground_vd(a, n, dt, t, v, d);
}

/* A design input over caller-owned arrays: n_mu friction values mu, the
 * peaks of n_sets sets (peak[s * n_mu + k], m), the ASCE best estimates
 * (asce, m; NULL: none), each set's peak ground displacement (pgd, m) and
 * the larger horizontal ZPA (m/s^2); everything else as
 * sl_design_input_default() sets it. */
static inline sl_design_input oracle_design_input(size_t n_mu, size_t n_sets, const double *mu,
                                                  const double *peak, const double *asce,
                                                  const double *pgd, double zpa_h_ms2)
{
    sl_design_input in;
    sl_design_input_default(&in);
    in.n_mu = n_mu;
    in.n_sets = n_sets;
    in.mu = mu;
    in.peak_m = peak;
    in.asce_best_m = asce;
    in.pgd_m = pgd;
    in.zpa_h_ms2 = zpa_h_ms2;
    return in;
}

#endif
