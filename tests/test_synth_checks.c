/*
 * test_synth_checks.c - the verdicts of sl_synth_check_motion must fail when
 * a motion breaks a rule, not only pass when it meets it.
 *
 * End at rest (synth.h, SRP 3.7.1; docs/synthesis.md §4):
 *     ok_end = |v(T)| <= end_vel_frac PGV  and  |d(T)| <= end_disp_frac PGD.
 * Every motion synth makes is baseline-corrected so that v(T) = d(T) = 0 up
 * to rounding, so a motion that breaks the default 1 % rule cannot be made
 * through the public API. What can be made is a motion whose end values,
 * reported by the check itself (v_end_ms, d_end_m, pgv_ms, pgd_m), are put
 * on either side of the limit by the limit: the same motion (same seed: the
 * end fractions take no part in making it) is checked under plans whose
 * end_disp_frac is half and twice |d(T)|/PGD, the velocity limit generous,
 * and the other way round. The verdict must fail at half and pass at twice,
 * for each half of the rule on its own: a verdict that dropped either half,
 * reversed a comparison or scaled a limit fails here. The end values are
 * recomputed independently (trapezoid velocity, exact piecewise-linear
 * displacement, SRP's definition of "at rest") from sl_synth_acc.
 */
#include <math.h>
#include <stdint.h>

#include "harness.h"
#include "synth/synth.h"

#define T_N 4001
#define T_DT 0.005
#define T_PGA_MS2 (0.3 * 9.80665)

static int verbose(void) { return getenv("SEISLIDE_TEST_VERBOSE") != NULL; }

/* v(T), d(T), PGV, PGD of a[0..n-1] at step dt, piecewise-linear a:
 * v_{i+1} = v_i + dt (a_i + a_{i+1})/2,
 * d_{i+1} = d_i + dt v_i + dt^2 (2 a_i + a_{i+1})/6 (exact for linear a). */
static void end_values(const double *a, size_t n, double dt, double *v, double *d, double *pv,
                       double *pd)
{
    double vv = 0, dd = 0, mv = 0, md = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        dd += dt * vv + dt * dt * (2 * a[i] + a[i + 1]) / 6;
        vv += dt * (a[i] + a[i + 1]) / 2;
        mv = fabs(vv) > mv ? fabs(vv) : mv;
        md = fabs(dd) > md ? fabs(dd) : md;
    }
    *v = vv, *d = dd, *pv = mv, *pd = md;
}

/* Make motion (seed, H1, attempt 0) of RG 1.60 at 0.3 g, 3 iterations, under
 * end limits (fv, fd), and check it. Returns 0 on success. */
static int make_and_check(double fv, double fd, uint64_t seed, sl_synth_check *k, double *acc0,
                          size_t n)
{
    sl_error e;
    sl_synth_params p;
    sl_synth_params_default(&p);
    p.end_vel_frac = fv;
    p.end_disp_frac = fd;
    sl_synth *s = sl_synth_alloc(T_N, T_DT, &p, &e);
    CHECK(s, "plan: %s", e.msg);
    if (!s)
        return 1;
    sl_spectrum *sp[SL_SYNTH_NCOMP];
    sl_synth_target tgt[SL_SYNTH_NCOMP];
    int bad = 1;
    if (sl_synth_targets_rg160(T_PGA_MS2, 0.05, &p, sp, tgt, &e) != SL_OK) {
        CHECK(0, "targets: %s", e.msg);
        sl_synth_free(s);
        return 1;
    }
    sl_synth_motion *m = sl_synth_motion_alloc(s, &e);
    CHECK(m, "motion: %s", e.msg);
    if (m && sl_synth_set_random(m, &tgt[SL_SYNTH_H1], seed, 0, SL_SYNTH_H1, 0, &e) == SL_OK) {
        bad = 0;
        for (int it = 0; it < 3 && !bad; it++)
            bad = sl_synth_iterate(m, &e) != SL_OK;
        CHECK(!bad, "iterate: %s", e.msg);
        if (!bad) {
            sl_synth_check_motion(m, k);
            for (size_t i = 0; i < n; i++)
                acc0[i] = sl_synth_acc(m)[i];
        }
    } else {
        CHECK(0, "set_random: %s", e.msg);
    }
    sl_synth_motion_free(m);
    for (int c = 0; c < SL_SYNTH_NCOMP; c++)
        sl_spectrum_free(sp[c]);
    sl_synth_free(s);
    return bad;
}

static void test_end_at_rest_verdict(void)
{
    static double a[T_N], b[T_N];
    sl_synth_check k0, k;
    /* a seed whose motion has both end values non-zero in floating point
     * (the baseline leaves rounding: |d(T)|/PGD about 1e-13); the first
     * one does, the loop only guards against an exact zero */
    uint64_t seed = 0;
    for (uint64_t s = 7; s < 12 && !seed; s++) {
        if (make_and_check(SL_SYNTH_END_VEL_FRAC, SL_SYNTH_END_DISP_FRAC, s, &k0, a, T_N))
            return;
        if (k0.v_end_ms != 0 && k0.d_end_m != 0)
            seed = s;
    }
    CHECK(seed, "no seed among 7-11 leaves non-zero end values");
    if (!seed)
        return;
    /* the default rule holds (baseline correction) */
    CHECK(k0.ok_end, "default 1 %% rule fails: v %g of PGV %g, d %g of PGD %g", k0.v_end_ms,
          k0.pgv_ms, k0.d_end_m, k0.pgd_m);
    /* the reported end values are the motion's own */
    double v, d, pv, pd;
    end_values(a, T_N, T_DT, &v, &d, &pv, &pd);
    CHECK_CLOSE(k0.pgv_ms, pv, 0, 1e-9);
    CHECK_CLOSE(k0.pgd_m, pd, 0, 1e-9);
    CHECK(fabs(k0.v_end_ms - v) <= 1e-9 * pv && fabs(k0.d_end_m - d) <= 1e-9 * pd,
          "end values %g %g, recomputed %g %g", k0.v_end_ms, k0.d_end_m, v, d);
    const double rv = fabs(k0.v_end_ms) / k0.pgv_ms, rd = fabs(k0.d_end_m) / k0.pgd_m;
    if (verbose())
        fprintf(stderr, "  seed %llu: |v(T)|/PGV %.3g, |d(T)|/PGD %.3g\n",
                (unsigned long long)seed, rv, rd);
    struct {
        double fv, fd;
        int ok;
        const char *what;
    } cases[] = {
        {2 * rv, 0.5 * rd, 0, "end displacement above its limit, velocity within"},
        {0.5 * rv, 2 * rd, 0, "end velocity above its limit, displacement within"},
        {0.5 * rv, 0.5 * rd, 0, "both above"},
        {2 * rv, 2 * rd, 1, "both within"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (make_and_check(cases[c].fv, cases[c].fd, seed, &k, b, T_N))
            return;
        /* the same motion: the end limits take no part in making it */
        CHECK(memcmp(a, b, sizeof a) == 0, "%s: the motion changed with the end limits",
              cases[c].what);
        CHECK(k.ok_end == cases[c].ok, "%s: ok_end %d (|v(T)|/PGV %.3g, limit %.3g; "
              "|d(T)|/PGD %.3g, limit %.3g)", cases[c].what, k.ok_end, rv, cases[c].fv, rd,
              cases[c].fd);
        /* a failed end check fails the motion */
        if (!cases[c].ok)
            CHECK(!k.pass, "%s: the motion passes", cases[c].what);
    }
}

int main(void)
{
    RUN(test_end_at_rest_verdict);
    return HARNESS_END("synth_checks");
}
