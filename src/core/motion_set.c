/* motion_set.c - checks and combinations of a three-component set (see
 * motion_set.h). */
#include "core/motion_set.h"

#include "core/standards.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *comp_name(const sl_motion *m)
{
    if (m->path && m->path[0])
        return m->path;
    if (m->label && m->label[0])
        return m->label;
    return "(unnamed)";
}

sl_status sl_set_check_fit(sl_set *set, int truncate, sl_set_fit *fit, sl_error *err)
{
    sl_error_clear(err);
    if (fit)
        memset(fit, 0, sizeof *fit);
    if (!set || !set->h1)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "component H1 missing");
    sl_motion *c[3] = {set->h1, set->h2, set->v};
    static const char *const tag[3] = {"H1", "H2", "V"};
    size_t nmin = SIZE_MAX, nmax = 0;
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        if (!c[k]->acc_ms2 || c[k]->n == 0)
            return sl_error_set(err, SL_EINVAL, c[k]->path, 0, "%s '%s' has no samples",
                                tag[k], comp_name(c[k]));
        if (!(c[k]->dt_s > 0) || !isfinite(c[k]->dt_s))
            return sl_error_set(err, SL_EINVAL, c[k]->path, 0, "%s '%s': dt %g must be > 0",
                                tag[k], comp_name(c[k]), c[k]->dt_s);
        if (c[k]->n < nmin)
            nmin = c[k]->n;
        if (c[k]->n > nmax)
            nmax = c[k]->n;
    }
    for (int k = 1; k < 3; k++) {
        if (!c[k])
            continue;
        double d0 = c[0]->dt_s, dk = c[k]->dt_s;
        if (fabs(dk - d0) > SL_MOTION_DT_REL_TOL * fmax(d0, dk))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "components have different dt: H1 '%s' dt %.9g s, "
                                "%s '%s' dt %.9g s (must agree within %g relative)",
                                comp_name(c[0]), d0, tag[k], comp_name(c[k]), dk,
                                SL_MOTION_DT_REL_TOL);
    }
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        for (size_t i = 0; i < c[k]->n; i++) {
            if (!isfinite(c[k]->acc_ms2[i]))
                return sl_error_set(err, SL_EINVAL, c[k]->path, 0,
                                    "%s '%s': sample %zu (t = %.9g s) is not finite", tag[k],
                                    comp_name(c[k]), i + 1, (double)i * c[k]->dt_s);
        }
    }
    const size_t n = truncate ? nmin : nmax;
    /* pad: grow every short component first, so a failure leaves the set as it was */
    for (int k = 0; k < 3 && !truncate; k++) {
        if (!c[k] || c[k]->n == n)
            continue;
        double *p = realloc(c[k]->acc_ms2, n * sizeof *p);
        if (!p)
            return sl_error_set(err, SL_ENOMEM, c[k]->path, 0, "%s '%s': out of memory padding",
                                tag[k], comp_name(c[k]));
        c[k]->acc_ms2 = p;
    }
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        if (fit) {
            fit->n_in[k] = c[k]->n;
            fit->changed |= (c[k]->n != n);
        }
        for (size_t i = c[k]->n; i < n; i++)
            c[k]->acc_ms2[i] = 0.0; /* the ground at rest after its record */
        c[k]->n = n;
        c[k]->dt_s = c[0]->dt_s;
    }
    if (fit) {
        fit->n = n;
        fit->truncated = truncate != 0;
    }
    return SL_OK;
}

sl_status sl_set_check(sl_set *set, int truncate, sl_error *err)
{
    return sl_set_check_fit(set, truncate, NULL, err);
}

double sl_set_pga_h(const sl_set *set)
{
    if (!set)
        return 0;
    return fmax(sl_motion_pga(set->h1), sl_motion_pga(set->h2));
}

double sl_set_scale_pga_h(sl_set *set, double pga_ms2)
{
    double pga = sl_set_pga_h(set);
    if (!(pga > 0))
        return 0;
    double s = pga_ms2 / pga;
    sl_motion *m[3] = {set->h1, set->h2, set->v};
    for (int q = 0; q < 3; q++)
        if (m[q])
            sl_motion_scale(m[q], s);
    return s;
}

double sl_set_pgd_100_40(const sl_set *set)
{
    if (!set || !set->h1)
        return 0;
    double p1 = sl_motion_pgd(set->h1);
    if (!set->h2)
        return p1;
    double p2 = sl_motion_pgd(set->h2);
    return fmax(p1 + SL_COMB_100_40 * p2, p2 + SL_COMB_100_40 * p1);
}
