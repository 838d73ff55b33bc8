/* spectrum_coefs.c - the exact recurrence of a damped oscillator over one
 * step of piecewise-linear input (Nigam and Jennings 1969; spectrum.h): the
 * closed form, and its Taylor series where w h is small. */
#include "signal/spectrum.h"
#include "signal/spectrum_kernel.h"

#include "core/units.h"

#include <math.h>
#include <string.h>

/* Largest number of Taylor terms for the series coefficients; with
 * |Z| <= 3 x SL_SPECTRUM_SERIES_WH the terms fall below 1e-18 after ~16. */
#define SERIES_MAX_TERMS 60
/* Stop the series when a term's size is below this (relative to 1, the size
 * of phi0). */
#define SERIES_TOL 1e-18

static void coefs_closed(double w, double z, double h, double c[NCOEF])
{
    double sq = sqrt(1.0 - z * z);
    double wd = w * sq;
    double e = exp(-z * w * h);
    double sn = sin(wd * h), cs = cos(wd * h);
    double q = z / sq;
    double w2 = w * w;
    c[C11] = e * (cs + q * sn);
    c[C12] = e * sn / wd;
    c[C21] = -w2 * c[C12];
    c[C22] = e * (cs - q * sn);
    /* x1 = x_p(h) + A (x0 - x_p(0)), u_p = -a/w^2 + 2 z a'/w^3, v_p = -a'/w^2,
     * a' = (a1 - a0)/h. Collect the a0 and a1 terms. */
    double ku = (2.0 * z * (1.0 - c[C11]) / w + c[C12]) / w2;
    double kv = (-2.0 * z * c[C21] / w + c[C22] - 1.0) / w2;
    c[BU0] = c[C11] / w2 - ku / h;
    c[BU1] = -1.0 / w2 + ku / h;
    c[BV0] = c[C21] / w2 - kv / h;
    c[BV1] = kv / h;
}

/* 2x2 row-major product r = a b (r may not alias). */
static void mat2_mul(const double a[4], const double b[4], double r[4])
{
    r[0] = a[0] * b[0] + a[1] * b[2];
    r[1] = a[0] * b[1] + a[1] * b[3];
    r[2] = a[2] * b[0] + a[3] * b[2];
    r[3] = a[2] * b[1] + a[3] * b[3];
}

static void coefs_series(double w, double z, double h, double c[NCOEF])
{
    double x = w * h;
    const double zb[4] = {0.0, x, -x, -2.0 * z * x}; /* balanced w h [0 1; -1 -2z] */
    double p[4] = {1.0, 0.0, 0.0, 1.0};              /* Z^j */
    double phi0[4] = {0}, phi1[4] = {0}, phi2[4] = {0};
    double fj = 1.0; /* j! */
    for (int j = 0; j < SERIES_MAX_TERMS; j++) {
        double f1 = fj * (double)(j + 1), f2 = f1 * (double)(j + 2);
        for (int k = 0; k < 4; k++) {
            phi0[k] += p[k] / fj;
            phi1[k] += p[k] / f1;
            phi2[k] += p[k] / f2;
        }
        double size = fabs(p[0]) + fabs(p[1]) + fabs(p[2]) + fabs(p[3]);
        if (size / fj < SERIES_TOL)
            break;
        double t[4];
        mat2_mul(p, zb, t);
        memcpy(p, t, sizeof t);
        fj *= (double)(j + 1);
    }
    /* Undo the balancing D = diag(w, 1): X = D^-1 X' D. */
    c[C11] = phi0[0];
    c[C12] = phi0[1] / w;
    c[C21] = phi0[2] * w;
    c[C22] = phi0[3];
    c[BU0] = -h * (phi1[1] - phi2[1]) / w;
    c[BU1] = -h * phi2[1] / w;
    c[BV0] = -h * (phi1[3] - phi2[3]);
    c[BV1] = -h * phi2[3];
}

void sl_spectrum_coefs_auto(double w, double z, double h, double c[NCOEF])
{
    if (w * h < SL_SPECTRUM_SERIES_WH)
        coefs_series(w, z, h, c);
    else
        coefs_closed(w, z, h, c);
}

sl_status sl_spectrum_coefs(double f_hz, double zeta, double h_s,
                            sl_spectrum_method method, double c[8], sl_error *err)
{
    if (!(f_hz > 0) || !isfinite(f_hz) || !(h_s > 0) || !isfinite(h_s))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: frequency %g Hz and step %g s must be positive",
                            f_hz, h_s);
    if (!(zeta >= 0 && zeta < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "spectrum: damping %g outside [0, 1)", zeta);
    double w = 2.0 * SL_PI * f_hz;
    switch (method) {
    case SL_SPECTRUM_CLOSED: coefs_closed(w, zeta, h_s, c); break;
    case SL_SPECTRUM_SERIES: coefs_series(w, zeta, h_s, c); break;
    default: sl_spectrum_coefs_auto(w, zeta, h_s, c); break;
    }
    return SL_OK;
}
