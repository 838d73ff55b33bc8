/* test_rg160.c - Regulatory Guide 1.60 design spectra: control points at
 * every tabulated damping, the REFERENCE.md 3 checkpoints, the shape rules
 * and the damping interpolation. */
#include "harness.h"
#include "signal/rg160.h"
#include "core/units.h"

#define PI 3.14159265358979323846
#define IN_M 0.0254

/* RG 1.60 Tables I and II, typed here independently of rg160.c. */
static const double zt[5] = {0.005, 0.02, 0.05, 0.07, 0.10};
static const double tb[5] = {4.96, 3.54, 2.61, 2.27, 1.90};
static const double tc_h[5] = {5.95, 4.25, 3.13, 2.72, 2.28};
static const double td_h[5] = {3.20, 2.50, 2.05, 1.88, 1.70};
static const double tc_v[5] = {5.67, 4.05, 2.98, 2.59, 2.17};
static const double td_v[5] = {2.13, 1.67, 1.37, 1.25, 1.13};

static double sa_d_g(double d, double pga_g)
{
    double w = 2 * PI * 0.25;
    return w * w * d * 36.0 * IN_M * pga_g / SL_G;
}

static void test_control_points(void)
{
    const double pga_g = 0.37;
    for (int dir = 0; dir < 2; dir++)
        for (int k = 0; k < 5; k++) {
            double f[4], sa[4];
            CHECK(sl_rg160_control((sl_rg160_dir)dir, zt[k], pga_g * SL_G, f, sa, NULL) == SL_OK,
                  "ok");
            const double *tc = dir ? tc_v : tc_h, *td = dir ? td_v : td_h;
            CHECK(f[0] == 0.25 && f[1] == (dir ? 3.5 : 2.5) && f[2] == 9 && f[3] == 33,
                  "frequencies %g %g %g %g", f[0], f[1], f[2], f[3]);
            CHECK_CLOSE(sa[0] / SL_G, sa_d_g(td[k], pga_g), 0, 1e-14);
            CHECK_CLOSE(sa[1] / SL_G, tc[k] * pga_g, 0, 1e-14);
            CHECK_CLOSE(sa[2] / SL_G, tb[k] * pga_g, 0, 1e-14);
            CHECK_CLOSE(sa[3] / SL_G, pga_g, 0, 1e-14);
            /* the spectrum passes through its control points */
            double psa[4];
            sl_rg160_psa((sl_rg160_dir)dir, zt[k], pga_g * SL_G, f, 4, psa, NULL);
            for (int q = 0; q < 4; q++)
                CHECK_CLOSE(psa[q], sa[q], 0, 1e-14);
        }
}

/* REFERENCE.md 3, H, a = 1 g, to the printed precision. */
static void test_checkpoints(void)
{
    double f[3] = {1, 5, 20}, psa[3];
    const double h5[3] = {1.4739, 2.8369, 1.4474}, h10[3] = {1.1305, 2.0658, 1.2807};
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.05, SL_G, f, 3, psa, NULL) == SL_OK, "ok");
    for (int j = 0; j < 3; j++)
        CHECK_CLOSE(psa[j] / SL_G, h5[j], 5e-5, 0);
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.10, SL_G, f, 3, psa, NULL) == SL_OK, "ok");
    for (int j = 0; j < 3; j++)
        CHECK_CLOSE(psa[j] / SL_G, h10[j], 5e-5, 0);
}

/* Shape: ZPA above 33 Hz, constant SD below 0.25 Hz, straight lines in
 * log-log between control points (the log-midpoint is the geometric mean),
 * linear in the PGA. */
static void test_shape(void)
{
    for (int dir = 0; dir < 2; dir++) {
        sl_rg160_dir d = (sl_rg160_dir)dir;
        double f[6] = {33, 40, 100, 0.25, 0.1, 0.05}, psa[6];
        sl_rg160_psa(d, 0.07, 0.5 * SL_G, f, 6, psa, NULL);
        CHECK_CLOSE(psa[1], 0.5 * SL_G, 0, 1e-15);
        CHECK_CLOSE(psa[2], 0.5 * SL_G, 0, 1e-15);
        for (int q = 4; q < 6; q++) { /* SD = SA/(2 pi f)^2 the same as at D */
            double sd = psa[q] / pow(2 * PI * f[q], 2), sd_d = psa[3] / pow(2 * PI * 0.25, 2);
            CHECK_CLOSE(sd, sd_d, 0, 1e-14);
        }
        double cf[4], cs[4];
        sl_rg160_control(d, 0.07, 0.5 * SL_G, cf, cs, NULL);
        for (int k = 0; k < 3; k++) {
            double fm = sqrt(cf[k] * cf[k + 1]), sm;
            sl_rg160_psa(d, 0.07, 0.5 * SL_G, &fm, 1, &sm, NULL);
            CHECK_CLOSE(sm, sqrt(cs[k] * cs[k + 1]), 0, 1e-13);
        }
        double one, two, x = 3.3;
        sl_rg160_psa(d, 0.05, 0.2 * SL_G, &x, 1, &one, NULL);
        sl_rg160_psa(d, 0.05, 0.6 * SL_G, &x, 1, &two, NULL);
        CHECK_CLOSE(two, 3 * one, 0, 1e-14);
    }
    double zero_pga, x = 4.0;
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.05, 0.0, &x, 1, &zero_pga, NULL) == SL_OK &&
              zero_pga == 0.0,
          "PGA 0 gives 0");
}

/* Between tabulated dampings: linear in ln(damping), eq. (1) of rg160.h. */
static void test_damping_interpolation(void)
{
    double b, c, d;
    for (int k = 0; k < 5; k++) {
        CHECK(sl_rg160_factors(SL_RG160_HORIZONTAL, zt[k], &b, &c, &d, NULL) == SL_OK, "ok");
        CHECK(b == tb[k] && c == tc_h[k] && d == td_h[k], "tabulated damping %g", zt[k]);
        CHECK(sl_rg160_factors(SL_RG160_VERTICAL, zt[k], &b, &c, &d, NULL) == SL_OK, "ok");
        CHECK(b == tb[k] && c == tc_v[k] && d == td_v[k], "tabulated damping %g", zt[k]);
    }
    for (int k = 0; k < 4; k++) {
        double z = sqrt(zt[k] * zt[k + 1]); /* log-midpoint: the arithmetic mean of factors */
        sl_rg160_factors(SL_RG160_HORIZONTAL, z, &b, &c, &d, NULL);
        CHECK_CLOSE(b, 0.5 * (tb[k] + tb[k + 1]), 0, 1e-14);
        CHECK_CLOSE(c, 0.5 * (tc_h[k] + tc_h[k + 1]), 0, 1e-14);
        CHECK_CLOSE(d, 0.5 * (td_h[k] + td_h[k + 1]), 0, 1e-14);
    }
    double z = 0.03; /* between 2 and 5 % */
    sl_rg160_factors(SL_RG160_VERTICAL, z, NULL, &c, NULL, NULL);
    CHECK_CLOSE(c, 4.05 + (2.98 - 4.05) * log(0.03 / 0.02) / log(0.05 / 0.02), 0, 1e-14);
    /* the spectrum falls as damping rises, at every frequency */
    double f = 1.0, prev = INFINITY;
    for (int i = 0; i <= 38; i++) {
        double zz = fmin(0.005 + 0.0025 * i, 0.10), s = NAN;
        CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, zz, SL_G, &f, 1, &s, NULL) == SL_OK, "ok");
        CHECK(s < prev, "not decreasing at damping %g", zz);
        prev = s;
    }
}

/* Why ln(damping): interpolating each interior tabulated value linearly in
 * ln z between its two neighbours reproduces it to within the table's
 * rounding (0.01), for every column; linear in z misses by up to 0.76. */
static void test_table_is_linear_in_ln_damping(void)
{
    const double *cols[5] = {tb, tc_h, td_h, tc_v, td_v};
    for (int c = 0; c < 5; c++)
        for (int k = 1; k < 4; k++) {
            double t = log(zt[k] / zt[k - 1]) / log(zt[k + 1] / zt[k - 1]);
            double pred = cols[c][k - 1] + (cols[c][k + 1] - cols[c][k - 1]) * t;
            CHECK_CLOSE(pred, cols[c][k], 0.01, 0);
        }
}

/* The tabulated dampings, in the guide's order; NaN past the table. */
static void test_dampings(void)
{
    for (size_t k = 0; k < 5; k++)
        CHECK(sl_rg160_damping(k) == zt[k], "damping %zu: %g", k, sl_rg160_damping(k));
    CHECK(isnan(sl_rg160_damping(5)), "damping 5 is %g, not NaN", sl_rg160_damping(5));
}

static void test_bad_input(void)
{
    double f = 1.0, s;
    sl_error e;
    sl_error_clear(&e);
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.004, SL_G, &f, 1, &s, &e) == SL_EINVAL, "low z");
    CHECK(strstr(e.msg, "damping") != NULL, "message '%s'", e.msg);
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.11, SL_G, &f, 1, &s, &e) == SL_EINVAL, "high z");
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, NAN, SL_G, &f, 1, &s, &e) == SL_EINVAL, "NaN z");
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.05, -1, &f, 1, &s, &e) == SL_EINVAL, "PGA < 0");
    f = 0;
    CHECK(sl_rg160_psa(SL_RG160_HORIZONTAL, 0.05, SL_G, &f, 1, &s, &e) == SL_EINVAL, "f 0");
    CHECK(sl_rg160_factors((sl_rg160_dir)7, 0.05, NULL, NULL, NULL, &e) == SL_EINVAL, "dir");
}

static void test_grid(void)
{
    size_t n;
    double *f = sl_rg160_grid(SL_RG160_VERTICAL, 0.1, 50, 100, &n);
    CHECK(f != NULL && n == 271 + 4, "n = %zu", n);
    int found[4] = {0};
    const double cf[4] = {0.25, 3.5, 9, 33};
    for (size_t i = 0; i < n; i++) {
        if (i)
            CHECK(f[i] > f[i - 1] * (1 + 1e-9), "increasing at %zu", i);
        for (int k = 0; k < 4; k++)
            found[k] |= f[i] == cf[k];
    }
    CHECK(found[0] && found[1] && found[2] && found[3], "control points on the grid");
    free(f);
    f = sl_rg160_grid(SL_RG160_HORIZONTAL, 1, 10, 10, &n); /* 2.5 and 9 inside */
    CHECK(n == 13 && f[0] == 1 && f[n - 1] == 10, "n %zu", n);
    free(f);
}

int main(void)
{
    RUN(test_control_points);
    RUN(test_checkpoints);
    RUN(test_shape);
    RUN(test_damping_interpolation);
    RUN(test_table_is_linear_in_ln_damping);
    RUN(test_dampings);
    RUN(test_bad_input);
    RUN(test_grid);
    return HARNESS_END("rg160");
}
