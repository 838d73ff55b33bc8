/*
 * oracle.h - independent references shared by the sliding tests: the ground
 * velocity and displacement of a piecewise-linear record, integrated here
 * and not by the library, and a motion over a caller-owned array.
 */
#ifndef SL_TEST_ORACLE_H
#define SL_TEST_ORACLE_H

#include <stddef.h>

#include "io/motion.h"

/* A motion over a caller-owned array (no file, nothing to free). */
static inline sl_motion oracle_motion(double *a, size_t n, double dt)
{
    sl_motion m = {NULL, NULL, n, dt, a};
    return m;
}

/* Ground velocity *v and displacement *d at time t of the samples a (taken
 * as piecewise linear; after the last sample the ground keeps its velocity). */
static inline void oracle_ground_vd(const double *a, size_t n, double dt, double t, double *v,
                                    double *d)
{
    double V = 0, D = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        double t0 = (double)i * dt;
        if (t <= t0)
            break;
        double h = t - t0 < dt ? t - t0 : dt, s = (a[i + 1] - a[i]) / dt;
        D += V * h + a[i] * h * h / 2 + s * h * h * h / 6;
        V += a[i] * h + s * h * h / 2;
    }
    double tend = (double)(n - 1) * dt;
    if (t > tend)
        D += V * (t - tend);
    *v = V;
    *d = D;
}

#endif
