/* test_design.c - design spectra, cap, crossover, ranges, clearance policy. */
#include <math.h>
#include <stdlib.h>

#include "method/design.h"
#include "harness.h"
#include "oracle.h"
#include "core/units.h"

/* Two sets, five mu. Hand values: means, sample sd, the 3.0 / 2.0 factors,
 * the cap 1.5 x mean PGD, and a crossover where the two design curves, each
 * linear between grid points, meet. */
static void test_hand_example(void)
{
    const double mu[5] = {0.1, 0.2, 0.3, 0.4, 0.5};
    /* set 1 and set 2 peaks, m */
    const double peak[10] = {0.30, 0.10, 0.04, 0.01, 0.0,
                             0.50, 0.14, 0.06, 0.01, 0.0};
    const int no_slide[5] = {0, 0, 0, 0, 1};
    const double asce[5] = {0.20, 0.15, 0.06, 0.01, 0.0};
    const double pgd[2] = {0.5, 0.7};
    sl_design_input in = oracle_design_input(5, 2, mu, peak, asce, pgd, 0.5 * SL_G);
    in.no_slide = no_slide;
    sl_error e;
    sl_design *d = sl_design_compute(&in, &e);
    CHECK(d != NULL, "compute: %s", e.msg);
    if (!d)
        return;
    CHECK_CLOSE(d->cap_m, 1.5 * 0.6, 0, 1e-15);
    CHECK_CLOSE(d->rows[0].x, 0.2, 0, 1e-15);
    CHECK_CLOSE(d->rows[0].nltha_mean_m, 0.40, 0, 1e-15);
    CHECK_CLOSE(d->rows[0].nltha_sd_m, sqrt(0.02), 0, 1e-12); /* (0.1^2 + 0.1^2)/(2 - 1) */
    /* row 0: 3 x 0.4 = 1.2 > cap 0.9 -> capped; ASCE 2 x 0.2 = 0.4 < 0.9 */
    CHECK_CLOSE(d->rows[0].nltha_design_m, 0.9, 0, 1e-15);
    CHECK(d->rows[0].flags & SL_DESIGN_NLTHA_CAPPED, "capped flag");
    CHECK_CLOSE(d->rows[0].asce_design_m, 0.4, 0, 1e-15);
    CHECK(d->rows[0].flags & SL_DESIGN_UNCONSERVATIVE, "0.4 < 0.9 is unconservative");
    /* row 1: N = 3 x 0.12 = 0.36; A = 0.30 -> unconservative
     * row 2: N = 3 x 0.05 = 0.15; A = 0.12 -> unconservative
     * row 3: N = 0.03; A = 0.02 -> unconservative; row 4: both 0 -> not */
    CHECK_CLOSE(d->rows[1].nltha_design_m, 0.36, 0, 1e-12);
    CHECK(d->rows[3].flags & SL_DESIGN_UNCONSERVATIVE, "row 3");
    CHECK(!(d->rows[4].flags & SL_DESIGN_UNCONSERVATIVE), "row 4: equal zero is not unconservative");
    CHECK(d->rows[4].flags & SL_DESIGN_NO_SLIDING, "row 4 no sliding");
    CHECK(d->n_ranges == 1, "ranges %zu", d->n_ranges);
    CHECK_CLOSE(d->ranges[0].x_from, 0.2, 0, 1e-12);
    CHECK_CLOSE(d->ranges[0].x_to, 0.8, 0, 1e-12);
    /* crossing between rows 3 and 4: f = A - N = -0.01 at x 0.8, 0 at x 1.0 -> x = 1.0 */
    CHECK(d->has_crossover, "crossover");
    CHECK_CLOSE(d->crossover_x, 1.0, 0, 1e-12);
    /* the same range with interpolated ends: it starts at the grid's first row
     * (open there) and ends where A - N reaches 0, at row 4 (mu 0.5) */
    CHECK(d->ranges[0].open_lo == 1 && d->ranges[0].open_hi == 0, "open ends %d %d",
          d->ranges[0].open_lo, d->ranges[0].open_hi);
    CHECK_CLOSE(d->ranges[0].mu_lo, 0.1, 0, 1e-12);
    CHECK_CLOSE(d->ranges[0].mu_hi, 0.5, 0, 1e-12);
    CHECK(d->n_sets == 2 && d->fs_nltha == SL_NLTHA_FS && d->cap_factor == SL_DESIGN_CAP_FACTOR,
          "factors recorded");
    /* default policy: clearance = NLTHA design; interpolation between rows */
    CHECK_CLOSE(d->rows[2].clearance_m, d->rows[2].nltha_design_m, 0, 0);
    CHECK_CLOSE(sl_design_clearance_at(d, 0.25), 0.5 * (0.36 + 0.15), 0, 1e-12);
    CHECK(isnan(sl_design_clearance_at(d, 0.05)), "outside the grid: NAN");
    sl_design_free(d);
}

/* A range inside the grid: N = 3 x 0.1 = 0.3 everywhere (one set, cap far
 * above), A = 2 x best = 0.5, 0.2, 0.2, 0.4: A - N = 0.2, -0.1, -0.1, 0.1.
 * By hand: the range starts at mu 0.1 + 0.2/0.3 x 0.1 = 0.16667 and ends at
 * 0.3 + 0.1/0.2 x 0.1 = 0.35; no crossover (ASCE conservative at the lowest
 * mu), both ends closed. */
static void test_inner_range(void)
{
    const double mu[4] = {0.1, 0.2, 0.3, 0.4};
    const double peak[4] = {0.1, 0.1, 0.1, 0.1};
    const double asce[4] = {0.25, 0.1, 0.1, 0.2};
    const double pgd[1] = {10.0};
    sl_design_input in = oracle_design_input(4, 1, mu, peak, asce, pgd, 0.4 * SL_G);
    sl_error e;
    sl_design *d = sl_design_compute(&in, &e);
    CHECK(d != NULL, "compute: %s", e.msg);
    if (!d)
        return;
    CHECK(d->n_ranges == 1 && !d->has_crossover, "ranges %zu crossover %d", d->n_ranges,
          d->has_crossover);
    if (d->n_ranges == 1) {
        CHECK_CLOSE(d->ranges[0].mu_lo, 0.1 + 0.2 / 0.3 * 0.1, 0, 1e-12);
        CHECK_CLOSE(d->ranges[0].mu_hi, 0.35, 0, 1e-12);
        CHECK_CLOSE(d->ranges[0].x_lo, (0.1 + 0.2 / 0.3 * 0.1) / 0.4, 0, 1e-12);
        CHECK(!d->ranges[0].open_lo && !d->ranges[0].open_hi, "closed ends");
    }
    /* clearance at mu: the rows' 0.3 at and between grid points */
    CHECK_CLOSE(sl_design_clearance_at(d, 0.1), 0.3, 0, 1e-15);
    CHECK_CLOSE(sl_design_clearance_at(d, 0.4), 0.3, 0, 1e-15);
    CHECK(isnan(sl_design_clearance_at(d, NAN)), "NAN mu");
    sl_design_free(d);
}

/* The crossover lies where the two interpolated curves cross: D_A - D_N,
 * interpolated linearly in x, is zero there. */
static void test_crossover_on_curves(void)
{
    enum { N = 40 };
    double mu[N], peak[N], asce[N], pgd[1] = {10.0};
    for (int k = 0; k < N; k++) {
        mu[k] = 0.02 * (k + 1);
        peak[k] = 0.05 * exp(-8 * mu[k]);             /* NLTHA mean */
        asce[k] = 0.02 * exp(-4 * mu[k]);              /* below at low mu, above at high */
    }
    sl_design_input in = oracle_design_input(N, 1, mu, peak, asce, pgd, 0.3 * SL_G);
    sl_design *d = sl_design_compute(&in, NULL);
    CHECK(d && d->has_crossover, "crossover expected");
    if (!d || !d->has_crossover) {
        sl_design_free(d);
        return;
    }
    size_t k = 0;
    while (k + 1 < d->n && d->rows[k + 1].x < d->crossover_x)
        k++;
    const sl_design_row *p = &d->rows[k], *q = &d->rows[k + 1];
    double w = (d->crossover_x - p->x) / (q->x - p->x);
    double dn = p->nltha_design_m + w * (q->nltha_design_m - p->nltha_design_m);
    double da = p->asce_design_m + w * (q->asce_design_m - p->asce_design_m);
    CHECK_CLOSE(da, dn, 1e-15, 1e-12);
    CHECK(p->asce_design_m < p->nltha_design_m && q->asce_design_m >= q->nltha_design_m,
          "the crossing is bracketed");
    CHECK_CLOSE(d->crossover_mu, d->crossover_x * 0.3, 0, 1e-12);
    sl_design_free(d);
}

/* ASCE conservative at the lowest mu: no crossover, even if an
 * unconservative range follows; the range is still listed. */
static void test_no_crossover_when_conservative_low(void)
{
    const double mu[4] = {0.1, 0.2, 0.3, 0.4}, peak[4] = {0.1, 0.05, 0.01, 0.0};
    const double asce[4] = {0.2, 0.01, 0.0, 0.0}, pgd[1] = {10};
    sl_design_input in = oracle_design_input(4, 1, mu, peak, asce, pgd, SL_G);
    sl_design *d = sl_design_compute(&in, NULL);
    CHECK(d && !d->has_crossover && isnan(d->crossover_x), "no crossover expected");
    CHECK(d && d->n_ranges == 1, "one unconservative range");
    if (d)
        CHECK_CLOSE(d->ranges[0].x_from, 0.2, 0, 1e-12);
    sl_design_free(d);
}

static void test_policies(void)
{
    const double mu[2] = {0.1, 0.2}, peak[2] = {0.1, 0.01}, asce[2] = {0.01, NAN}, pgd[1] = {1};
    sl_design_input in = oracle_design_input(2, 1, mu, peak, asce, pgd, SL_G);
    for (int p = 0; p < 3; p++) {
        in.policy = (sl_clearance_policy)p;
        sl_design *d = sl_design_compute(&in, NULL);
        CHECK(d != NULL, "compute");
        if (!d)
            continue;
        double expect = p == SL_CLEARANCE_ASCE ? 0.02 : 0.3;
        CHECK_CLOSE(d->rows[0].clearance_m, expect, 0, 1e-12);
        CHECK(d->rows[1].flags & SL_DESIGN_ASCE_UNDEFINED, "undefined ASCE flagged");
        CHECK(sl_clearance_policy_parse(sl_clearance_policy_name((sl_clearance_policy)p)) == p,
              "name round trip");
        sl_design_free(d);
    }
    CHECK(sl_clearance_policy_parse("bogus") == -1, "unknown policy");
}

static void test_bad_input(void)
{
    const double mu[2] = {0.2, 0.1}, peak[2] = {0.1, 0.01}, pgd[1] = {1};
    sl_design_input in = oracle_design_input(2, 1, mu, peak, NULL, pgd, SL_G);
    sl_error e;
    CHECK(sl_design_compute(&in, &e) == NULL && e.code == SL_EINVAL, "decreasing mu");
    const double mu2[2] = {0.1, 0.2}, badpk[2] = {NAN, 0};
    in.mu = mu2;
    in.peak_m = badpk;
    CHECK(sl_design_compute(&in, &e) == NULL, "NaN peak");
    in.peak_m = peak;
    in.zpa_h_ms2 = 0;
    CHECK(sl_design_compute(&in, &e) == NULL, "zero ZPA");
}

int main(void)
{
    RUN(test_hand_example);
    RUN(test_inner_range);
    RUN(test_crossover_on_curves);
    RUN(test_no_crossover_when_conservative_low);
    RUN(test_policies);
    RUN(test_bad_input);
    return HARNESS_END("design");
}
