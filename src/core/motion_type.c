/* motion_type.c - the motion as plain data and its intensity measures
 * (see motion_type.h). */
#include "core/motion_type.h"

#include "core/units.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Husid-curve fractions bounding the significant duration D5-75. */
#define SL_MOTION_HUSID_LO 0.05
#define SL_MOTION_HUSID_HI 0.75

sl_motion *sl_motion_new_owned(const char *path, const char *label, size_t label_len,
                               double *acc_owned, size_t n, double dt_s)
{
    sl_motion *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    m->path = strdup(path ? path : "");
    m->label = label ? strndup(label, label_len) : strdup("");
    if (!m->path || !m->label) {
        free(m->path);
        free(m->label);
        free(m);
        return NULL;
    }
    m->n = n;
    m->dt_s = dt_s;
    m->acc_ms2 = acc_owned;
    return m;
}

sl_motion *sl_motion_from_array(const double *acc_ms2, size_t n, double dt_s,
                                const char *label)
{
    if (!acc_ms2 || n == 0 || !(dt_s > 0) || !isfinite(dt_s) || n > SIZE_MAX / sizeof(double))
        return NULL;
    double *a = malloc(n * sizeof *a);
    if (!a)
        return NULL;
    memcpy(a, acc_ms2, n * sizeof *a);
    sl_motion *m = sl_motion_new_owned("", label ? label : "", label ? strlen(label) : 0, a, n, dt_s);
    if (!m)
        free(a);
    return m;
}

sl_motion *sl_motion_copy(const sl_motion *m)
{
    if (!m || !m->acc_ms2 || m->n == 0)
        return NULL;
    sl_motion *c = sl_motion_from_array(m->acc_ms2, m->n, m->dt_s, m->label);
    if (!c)
        return NULL;
    char *p = strdup(m->path ? m->path : "");
    if (!p) {
        sl_motion_free(c);
        return NULL;
    }
    free(c->path);
    c->path = p;
    return c;
}

void sl_motion_free(sl_motion *m)
{
    if (!m)
        return;
    free(m->path);
    free(m->label);
    free(m->acc_ms2);
    free(m);
}

/* ---- derived quantities ---- */

double sl_motion_pga(const sl_motion *m)
{
    double p = 0;
    if (!m)
        return 0;
    for (size_t i = 0; i < m->n; i++) {
        double x = fabs(m->acc_ms2[i]);
        if (x > p)
            p = x;
    }
    return p;
}

/* Exact integration of piecewise-linear acceleration from rest; peaks of
 * |v| and |d| over the samples. Either history pointer may be NULL. */
static void integrate(const sl_motion *m, double *vel, double *disp, double *pgv, double *pgd)
{
    double v = 0, d = 0, pv = 0, pd = 0;
    if (!m || m->n == 0) {
        *pgv = *pgd = 0;
        return;
    }
    const double dt = m->dt_s;
    const double *a = m->acc_ms2;
    if (vel)
        vel[0] = 0;
    if (disp)
        disp[0] = 0;
    for (size_t i = 0; i + 1 < m->n; i++) {
        d += dt * v + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        v += dt * (a[i] + a[i + 1]) / 2;
        if (vel)
            vel[i + 1] = v;
        if (disp)
            disp[i + 1] = d;
        if (fabs(v) > pv)
            pv = fabs(v);
        if (fabs(d) > pd)
            pd = fabs(d);
    }
    *pgv = pv;
    *pgd = pd;
}

double sl_motion_pgv(const sl_motion *m)
{
    double pv, pd;
    integrate(m, NULL, NULL, &pv, &pd);
    return pv;
}

double sl_motion_pgd(const sl_motion *m)
{
    double pv, pd;
    integrate(m, NULL, NULL, &pv, &pd);
    return pd;
}

void sl_motion_integrate(const sl_motion *m, double *vel_ms, double *disp_m)
{
    double pv, pd;
    integrate(m, vel_ms, disp_m, &pv, &pd);
}

/* Integral of a^2 over step i for linear a: dt/3 (a_i^2 + a_i a_{i+1} + a_{i+1}^2). */
static double step_a2(const double *a, size_t i, double dt)
{
    return dt / 3 * (a[i] * a[i] + a[i] * a[i + 1] + a[i + 1] * a[i + 1]);
}

double sl_motion_arias(const sl_motion *m)
{
    if (!m)
        return 0;
    double s = 0;
    for (size_t i = 0; i + 1 < m->n; i++)
        s += step_a2(m->acc_ms2, i, m->dt_s);
    return SL_PI / (2 * SL_G) * s;
}

/* Time at which the Husid curve reaches the fraction p of the total
 * (linear interpolation between samples). */
static double husid_time(const sl_motion *m, double total, double p)
{
    double c = 0, target = p * total;
    for (size_t i = 0; i + 1 < m->n; i++) {
        double inc = step_a2(m->acc_ms2, i, m->dt_s);
        if (c + inc >= target && inc > 0)
            return m->dt_s * ((double)i + (target - c) / inc);
        c += inc;
    }
    return m->dt_s * (double)(m->n - 1);
}

double sl_motion_d5_75(const sl_motion *m)
{
    if (!m || m->n < 2)
        return 0;
    double total = 0;
    for (size_t i = 0; i + 1 < m->n; i++)
        total += step_a2(m->acc_ms2, i, m->dt_s);
    if (!(total > 0))
        return 0;
    return husid_time(m, total, SL_MOTION_HUSID_HI) - husid_time(m, total, SL_MOTION_HUSID_LO);
}

void sl_motion_scale(sl_motion *m, double s)
{
    if (!m)
        return;
    for (size_t i = 0; i < m->n; i++)
        m->acc_ms2[i] *= s;
}
