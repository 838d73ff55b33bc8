/* closed_forms.h - closed forms shared by the verification problems
 * (verify_engine.c) and the tests (tests/oracle.h): integrated here, by
 * hand, and not by the engine they check (library-internal, header only). */
#ifndef SL_VERIFY_CLOSED_FORMS_H
#define SL_VERIFY_CLOSED_FORMS_H

#include <stddef.h>

/* Ground velocity *v and displacement *d at time t of samples a[0..n-1]
 * at step dt read as piecewise linear (the exact integral, segment by
 * segment; after the last sample the ground keeps its velocity). */
static inline void sl_closed_ground_vd(const double *a, size_t n, double dt, double t, double *v,
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
