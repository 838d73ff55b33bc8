/* rg160.c - Regulatory Guide 1.60 design spectra (see rg160.h). */
#include "signal/rg160.h"
#include "core/compare.h"

#include <math.h>
#include <stdlib.h>

#include "signal/spectrum.h"

/* Two grid frequencies closer than this (relative) are the same point. */
#define RG160_GRID_MERGE_REL 1e-9

static const double dampings[SL_RG160_NDAMPING] = {0.005, 0.02, 0.05, 0.07, 0.10};

double sl_rg160_damping(size_t i)
{
    return i < SL_RG160_NDAMPING ? dampings[i] : NAN;
}

/* Control frequencies D, C, B, A, Hz (RG 1.60 Figures 1 and 2). */
static const double control_f_hz[2][SL_RG160_NCONTROL] = {
    [SL_RG160_HORIZONTAL] = {0.25, 2.5, 9.0, 33.0},
    [SL_RG160_VERTICAL] = {0.25, 3.5, 9.0, 33.0},
};

/* Amplification factors per tabulated damping (RG 1.60 Tables I and II):
 * B and C multiply the PGA, D multiplies 36 in x PGA/g. B is the same for
 * both directions. */
static const double factor_b[2][SL_RG160_NDAMPING] = {
    [SL_RG160_HORIZONTAL] = {4.96, 3.54, 2.61, 2.27, 1.90},
    [SL_RG160_VERTICAL] = {4.96, 3.54, 2.61, 2.27, 1.90},
};
static const double factor_c[2][SL_RG160_NDAMPING] = {
    [SL_RG160_HORIZONTAL] = {5.95, 4.25, 3.13, 2.72, 2.28},
    [SL_RG160_VERTICAL] = {5.67, 4.05, 2.98, 2.59, 2.17},
};
static const double factor_d[2][SL_RG160_NDAMPING] = {
    [SL_RG160_HORIZONTAL] = {3.20, 2.50, 2.05, 1.88, 1.70},
    [SL_RG160_VERTICAL] = {2.13, 1.67, 1.37, 1.25, 1.13},
};

/* Interpolate a tabulated factor linearly in ln(zeta), eq. (1). */
static double interp_ln_zeta(const double tab[SL_RG160_NDAMPING], double zeta)
{
    size_t i = 0;
    while (i + 2 < SL_RG160_NDAMPING && zeta > dampings[i + 1])
        i++;
    double z0 = dampings[i], z1 = dampings[i + 1];
    if (zeta == z0)
        return tab[i];
    if (zeta == z1)
        return tab[i + 1];
    double t = log(zeta / z0) / log(z1 / z0);
    return tab[i] + (tab[i + 1] - tab[i]) * t;
}

static sl_status check_dir_zeta(sl_rg160_dir dir, double zeta, sl_error *err)
{
    if (dir != SL_RG160_HORIZONTAL && dir != SL_RG160_VERTICAL)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rg160: unknown direction");
    if (!(zeta >= SL_RG160_ZETA_MIN && zeta <= SL_RG160_ZETA_MAX))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "rg160: damping %g outside the guide's range [%g, %g]", zeta,
                            SL_RG160_ZETA_MIN, SL_RG160_ZETA_MAX);
    return SL_OK;
}

sl_status sl_rg160_factors(sl_rg160_dir dir, double zeta, double *b, double *c,
                           double *d, sl_error *err)
{
    sl_status st = check_dir_zeta(dir, zeta, err);
    if (st)
        return st;
    if (b)
        *b = interp_ln_zeta(factor_b[dir], zeta);
    if (c)
        *c = interp_ln_zeta(factor_c[dir], zeta);
    if (d)
        *d = interp_ln_zeta(factor_d[dir], zeta);
    return SL_OK;
}

/* Control points of the spectrum per 1 m/s^2 of PGA. */
static void unit_control(sl_rg160_dir dir, double b, double c, double d,
                         double f[SL_RG160_NCONTROL], double sa[SL_RG160_NCONTROL])
{
    for (int k = 0; k < SL_RG160_NCONTROL; k++)
        f[k] = control_f_hz[dir][k];
    double w_d = 2.0 * SL_PI * f[0];
    double sd_d_m = d * SL_RG160_DISP_PER_G_M / SL_G; /* per 1 m/s^2 of PGA */
    sa[0] = w_d * w_d * sd_d_m;
    sa[1] = c;
    sa[2] = b;
    sa[3] = 1.0;
}

sl_status sl_rg160_control(sl_rg160_dir dir, double zeta, double pga_ms2,
                           double f_hz[SL_RG160_NCONTROL],
                           double sa_ms2[SL_RG160_NCONTROL], sl_error *err)
{
    double b, c, d;
    sl_status st = sl_rg160_factors(dir, zeta, &b, &c, &d, err);
    if (st)
        return st;
    if (!(pga_ms2 >= 0) || !isfinite(pga_ms2))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rg160: PGA %g must be >= 0", pga_ms2);
    unit_control(dir, b, c, d, f_hz, sa_ms2);
    for (int k = 0; k < SL_RG160_NCONTROL; k++)
        sa_ms2[k] *= pga_ms2;
    return SL_OK;
}

sl_status sl_rg160_psa(sl_rg160_dir dir, double zeta, double pga_ms2, const double *f_hz,
                       size_t n, double *psa_ms2, sl_error *err)
{
    double b, c, d;
    sl_status st = sl_rg160_factors(dir, zeta, &b, &c, &d, err);
    if (st)
        return st;
    if (!(pga_ms2 >= 0) || !isfinite(pga_ms2))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rg160: PGA %g must be >= 0", pga_ms2);
    double f[SL_RG160_NCONTROL], sa[SL_RG160_NCONTROL];
    unit_control(dir, b, c, d, f, sa);
    for (size_t j = 0; j < n; j++) {
        double x = f_hz[j];
        if (!(x > 0) || !isfinite(x))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "rg160: frequency %g Hz must be positive", x);
        double shape;
        if (x >= f[SL_RG160_NCONTROL - 1]) {
            shape = sa[SL_RG160_NCONTROL - 1];
        } else if (x <= f[0]) {
            shape = sa[0] * (x / f[0]) * (x / f[0]); /* constant SD */
        } else {
            int k = 0;
            while (x > f[k + 1])
                k++;
            if (x == f[k + 1]) {
                shape = sa[k + 1];
            } else {
                double p = log(sa[k + 1] / sa[k]) / log(f[k + 1] / f[k]);
                shape = sa[k] * pow(x / f[k], p);
            }
        }
        psa_ms2[j] = pga_ms2 * shape;
    }
    return SL_OK;
}

double *sl_rg160_grid(sl_rg160_dir dir, double fmin_hz, double fmax_hz, double per_decade,
                      size_t *n)
{
    *n = 0;
    if (dir != SL_RG160_HORIZONTAL && dir != SL_RG160_VERTICAL)
        return NULL;
    size_t m;
    double *g = sl_spectrum_grid(fmin_hz, fmax_hz, per_decade, &m);
    if (!g)
        return NULL;
    double *out = realloc(g, (m + SL_RG160_NCONTROL) * sizeof *out);
    if (!out) {
        free(g);
        return NULL;
    }
    size_t k = m;
    for (int c = 0; c < SL_RG160_NCONTROL; c++) {
        double fc = control_f_hz[dir][c];
        if (fc > fmin_hz && fc < fmax_hz)
            out[k++] = fc;
    }
    qsort(out, k, sizeof *out, sl_cmp_double);
    size_t w = 0;
    for (size_t i = 0; i < k; i++) {
        if (w > 0 && out[i] - out[w - 1] <= RG160_GRID_MERGE_REL * out[i]) {
            /* keep the control frequency exactly when one coincides */
            for (int c = 0; c < SL_RG160_NCONTROL; c++)
                if (out[i] == control_f_hz[dir][c])
                    out[w - 1] = out[i];
            continue;
        }
        out[w++] = out[i];
    }
    *n = w;
    return out;
}
