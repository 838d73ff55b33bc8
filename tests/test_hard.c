/*
 * test_hard.c - numerical stability on hard cases (issue "Speed against
 * error"): finite, stable and physically right, each against a closed form
 * or an invariant. docs/hard-cases.md records what these found.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "harness.h"
#include "oracle.h"
#include "slide/refmodel.h"
#include "slide/slide.h"

static const double g = SL_G;


static sl_slide_opts opts_default(void)
{
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    return o;
}

static int finite_result(const sl_slide_result *r)
{
    return isfinite(r->peak_m) && isfinite(r->residual_m) && isfinite(r->path_m) &&
           isfinite(r->t_rest_s) && isfinite(r->max_speed_ms) && r->peak_m >= 0;
}


static double *sine_record(size_t n, double dt, double A, double f)
{
    double *a = calloc(n, sizeof *a);
    for (size_t i = 0; i < n; i++)
        a[i] = A * sin(2 * M_PI * f * (double)i * dt);
    return a;
}

/* mu = 1e-4: the block nearly floats. Over the record u ~ -D_g; after it the
 * block coasts at the ground's final velocity V and stops after V/(mu g),
 * sliding a further V^2/(2 mu g): closed form. */
static void test_tiny_mu(void)
{
    const size_t n = 2001;
    const double dt = 0.005, mu = 1e-4;
    double *a = calloc(n, sizeof *a);
    for (size_t i = 0; i < n; i++) {
        double t = (double)i * dt;
        a[i] = 3.0 * sin(2 * M_PI * 0.7 * t) * exp(-0.3 * t) + 0.1; /* ends with V != 0 */
    }
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r, r0;
    double z = 0.0;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, NULL) == SL_OK, "run");
    sl_slide_run(&s, &z, 1, &o, &r0, NULL);
    CHECK(finite_result(&r), "finite");
    double V, D, tend = (double)(n - 1) * dt;
    oracle_ground_vd(a, n, dt, tend, &V, &D);
    /* the relative velocity at the end is -V + mu g (duration of sliding): */
    double vend = -V + mu * g * tend * (V > 0 ? 1 : -1);
    CHECK_CLOSE(r.t_rest_s, tend + fabs(vend) / (mu * g), 0, 1e-3);
    CHECK_CLOSE(r.residual_x_m, r0.residual_x_m + vend * fabs(vend) / (2 * mu * g), 0, 2e-3);
    /* the 2-D kernel agrees along the x axis */
    double *zero = calloc(n, sizeof *zero);
    sl_motion mz = oracle_motion(zero, n, dt);
    sl_set s2 = {&m, &mz, NULL};
    sl_slide_result r2;
    sl_slide_run(&s2, &mu, 1, &o, &r2, NULL);
    CHECK(finite_result(&r2), "2-D finite");
    CHECK_CLOSE(r2.residual_x_m, r.residual_x_m, 1e-6, 1e-6);
    free(a);
    free(zero);
}

/* mu just below the threshold: sliding barely starts. The slide is tiny,
 * positive, finite, and shrinks to zero as mu approaches the threshold
 * (for a smooth peak the slide is O((1 - mu/mu_t)^2)... just check
 * monotone decrease to zero and one episode). */
static void test_threshold_mu(void)
{
    const size_t n = 1001;
    const double dt = 0.01;
    double *a = sine_record(n, dt, 2.0, 1.3);
    for (size_t i = 0; i < n; i++)
        a[i] *= sin(M_PI * (double)i / (double)(n - 1));
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    double thr = sl_slide_mu_threshold(&s, &o);
    const double eps[] = {1e-2, 1e-4, 1e-6, 1e-9, 1e-12};
    double prev = INFINITY;
    for (int q = 0; q < 5; q++) {
        double mu = thr * (1 - eps[q]);
        sl_slide_result r;
        CHECK(sl_slide_run(&s, &mu, 1, &o, &r, NULL) == SL_OK, "run");
        CHECK(finite_result(&r) && r.peak_m > 0 && r.peak_m < prev,
              "eps %g: peak %.3g (previous %.3g)", eps[q], r.peak_m, prev);
        CHECK(r.episodes >= 1 && r.episodes <= 2, "eps %g: %ld episodes", eps[q], r.episodes);
        prev = r.peak_m;
    }
    CHECK(prev < 1e-12, "at 1e-12 below the threshold the slide must be negligible: %g", prev);
    /* 2-D the same */
    double *z = calloc(n, sizeof *z);
    sl_motion mz = oracle_motion(z, n, dt);
    sl_set s2 = {&mz, &m, NULL};
    double mu = thr * (1 - 1e-9);
    sl_slide_result r2;
    sl_slide_run(&s2, &mu, 1, &o, &r2, NULL);
    CHECK(finite_result(&r2) && r2.peak_m < 1e-9, "2-D near threshold: %g", r2.peak_m);
    free(a);
    free(z);
}

/* Vertical below -g for 500 steps: no friction, so during that window the
 * block follows u'' = -a_g exactly (compared with mu = 0 started from the
 * same state: the velocity change over the window equals -(ground velocity
 * change)). Counted, finite, in 1-D and 2-D. */
static void test_long_liftoff(void)
{
    const size_t n = 1500, i0 = 400, i1 = 900;
    const double dt = 0.01, mu = 0.4;
    double *a = calloc(n, sizeof *a), *v = calloc(n, sizeof *v);
    for (size_t i = 0; i < n; i++) {
        a[i] = 0.8 * sin(2 * M_PI * 1.1 * (double)i * dt); /* far below mu g */
        v[i] = (i >= i0 && i < i1) ? -1.3 * g : 0.0;
    }
    sl_motion mh = oracle_motion(a, n, dt), mv = oracle_motion(v, n, dt);
    sl_set s = {&mh, NULL, &mv};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    sl_history *h = NULL;
    CHECK(sl_slide_history(&s, mu, &o, &r, &h, NULL) == SL_OK, "run");
    CHECK(finite_result(&r), "finite");
    CHECK(r.liftoff_samples == (long)(i1 - i0), "counted %ld", r.liftoff_samples);
    if (h) {
        /* inside the window (away from the ramps at its ends) the relative
         * velocity changes exactly by minus the ground velocity change */
        size_t j0 = i0 + 1, j1 = i1 - 2;
        double V0, V1, D;
        oracle_ground_vd(a, n, dt, (double)j0 * dt, &V0, &D);
        oracle_ground_vd(a, n, dt, (double)j1 * dt, &V1, &D);
        CHECK_CLOSE(h->vx_ms[j1] - h->vx_ms[j0], -(V1 - V0), 1e-12, 1e-9);
        sl_history_free(h);
    }
    double *z = calloc(n, sizeof *z);
    sl_motion mz = oracle_motion(z, n, dt);
    sl_set s2 = {&mh, &mz, &mv};
    sl_slide_result r2;
    sl_slide_run(&s2, &mu, 1, &o, &r2, NULL);
    CHECK(finite_result(&r2), "2-D finite");
    CHECK_CLOSE(r2.peak_m, r.peak_m, 0, 1e-3);
    free(a);
    free(v);
    free(z);
}

static long maxrss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* A 60-minute record at 0.001 s (3.6 million samples): harmonic, two-way
 * continuous sliding. No blow-up; no drift: the amplitude over the last
 * cycle is Den Hartog's and the mean position over the last cycle equals
 * that over a cycle at minute 10; memory grows by no more than the input. */
static void test_sixty_minutes(void)
{
    const double dt = 0.001, T = 3600.0, A = 2.0, f = 2.0, r = 0.3, mu = r * A / g;
    const size_t n = (size_t)(T / dt) + 1;
    const size_t per = (size_t)(1.0 / (f * dt));
    long rss0 = maxrss_kb();
    double *a = sine_record(n, dt, A, f);
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result res;
    sl_history *h = NULL;
    CHECK(sl_slide_history(&s, mu, &o, &res, &h, NULL) == SL_OK, "run");
    CHECK(finite_result(&res), "finite");
    if (h) {
        double lo = INFINITY, hi = -INFINITY, m1 = 0, m2 = 0;
        for (size_t i = n - 1 - per; i < n - 1; i++) {
            lo = fmin(lo, h->ux_m[i]);
            hi = fmax(hi, h->ux_m[i]);
            m1 += h->ux_m[i] / (double)per;
        }
        size_t k0 = (size_t)(600.0 / dt);
        for (size_t i = k0; i < k0 + per; i++)
            m2 += h->ux_m[i] / (double)per;
        double w = 2 * M_PI * f, X = A / (w * w) * sqrt(1 - pow(M_PI * r / 2, 2));
        CHECK_CLOSE((hi - lo) / 2, X, 0, 1e-4);
        CHECK_CLOSE(m1, m2, 1e-9, 0); /* no drift over 50 minutes, to a nanometre */
        sl_history_free(h);
    }
    /* without a history the engine's memory does not grow with the record */
    long rss1 = maxrss_kb();
    double mus[8] = {0.02, 0.04, 0.06, 0.08, 0.1, 0.12, 0.15, 0.2};
    sl_slide_result rr[8];
    CHECK(sl_slide_run(&s, mus, 8, &o, rr, NULL) == SL_OK, "vector run");
    long rss2 = maxrss_kb();
    CHECK(rss2 - rss1 < 1024, "memory grew by %ld kB for a run without history", rss2 - rss1);
    for (int k = 0; k < 8; k++)
        CHECK(finite_result(&rr[k]), "mu %g finite", mus[k]);
    (void)rss0;
    free(a);
}

/* An all-zero record: nothing moves, for every mu including 0. */
static void test_all_zero(void)
{
    const size_t n = 500;
    double *a = calloc(n, sizeof *a);
    sl_motion m = oracle_motion(a, n, 0.01);
    sl_set s1 = {&m, NULL, NULL}, s2 = {&m, &m, &m};
    sl_slide_opts o = opts_default();
    double mus[3] = {0.0, 0.1, 1.0};
    sl_slide_result r[3];
    for (int d = 0; d < 2; d++) {
        CHECK(sl_slide_run(d ? &s2 : &s1, mus, 3, &o, r, NULL) == SL_OK, "run");
        for (int k = 0; k < 3; k++)
            CHECK(r[k].peak_m == 0 && r[k].path_m == 0 && r[k].episodes == 0 && finite_result(&r[k]),
                  "%d-D mu %g: peak %g", d + 1, mus[k], r[k].peak_m);
    }
    free(a);
}

/* One huge spike (1000 g in one sample) in an otherwise quiet record: the
 * slide matches the exact answer for the triangular pulse (onset on the
 * rising ramp at t_on = dt mu g/A, stop where V_g(t) - V_g(t_on) =
 * mu g (t - t_on)); in 2-D along 30 degrees the same magnitude and
 * direction. */
static void test_huge_spike(void)
{
    const size_t n = 4000, k = 100;
    const double dt = 0.005, mu = 0.2, A = 1000 * g;
    double *a = calloc(n, sizeof *a);
    a[k] = A;
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, NULL) == SL_OK, "run");
    double ton = (double)(k - 1) * dt + dt * mu * g / A, Von, Don, V, D;
    oracle_ground_vd(a, n, dt, ton, &Von, &Don);
    oracle_ground_vd(a, n, dt, 1e9, &V, &D);
    double ts = ton + (V - Von) / (mu * g), Vs, Ds;
    oracle_ground_vd(a, n, dt, ts, &Vs, &Ds);
    double U = Ds - Don - Von * (ts - ton) - mu * g * (ts - ton) * (ts - ton) / 2;
    CHECK_CLOSE(r.peak_m, U, 0, 1e-10);
    CHECK(r.episodes == 1, "episodes %ld", r.episodes);
    double c = cos(M_PI / 6), sn = sin(M_PI / 6);
    double *ax = calloc(n, sizeof *ax), *ay = calloc(n, sizeof *ay);
    ax[k] = A * c;
    ay[k] = A * sn;
    sl_motion mx = oracle_motion(ax, n, dt), my = oracle_motion(ay, n, dt);
    sl_set s2 = {&mx, &my, NULL};
    sl_slide_result r2;
    CHECK(sl_slide_run(&s2, &mu, 1, &o, &r2, NULL) == SL_OK, "2-D run");
    CHECK_CLOSE(r2.peak_m, U, 0, 1e-3);
    CHECK_CLOSE(atan2(r2.residual_y_m, r2.residual_x_m), atan2(-sn, -c), 1e-9, 0);
    free(a);
    free(ax);
    free(ay);
}

/* The smoothed model at U_y = 1e-7 m and eta = 20: finite and close to the
 * exact engine, or a solver error with context, never NaN. */
static void test_smooth_extreme(void)
{
    const size_t n = 400;
    const double dt = 0.01, mu = 0.2;
    double *a = sine_record(n, dt, 4.0, 1.5);
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result re, rs;
    sl_slide_run(&s, &mu, 1, &o, &re, NULL);
    o.model = SL_MODEL_SMOOTH;
    o.smooth_uy_m = 1e-7;
    o.smooth_eta = 20;
    sl_error e;
    sl_error_clear(&e);
    sl_status st = sl_slide_run(&s, &mu, 1, &o, &rs, &e);
    if (st == SL_OK) {
        CHECK(finite_result(&rs), "finite");
        /* error ~ sqrt(U_y / slide) at reversals: 1e-7 m against ~0.1 m */
        CHECK_CLOSE(rs.peak_m, re.peak_m, 0, 1e-2);
    } else {
        CHECK(st == SL_ESOLVER && strlen(e.msg) > 10, "failure must be a solver error with context");
    }
    free(a);
}

/* Pulse-like motion with a large velocity: a half-sine of 2 g over 1 s
 * (ground velocity 12.5 m/s). Closed form (REFERENCE 4): onset at
 * asin(r); U = int_{t1}^{T} w + w(T)^2/(2 mu g); the 2-D kernel along 60
 * degrees agrees, and energy is conserved (-int a u' = mu g path). */
static void test_large_velocity_pulse(void)
{
    const double A = 2 * g, T = 1.0, mu = 0.3;
    const size_t per = 2000, n = per + 1 + 10;
    const double dt = T / (double)per;
    double *a = calloc(n, sizeof *a);
    for (size_t i = 0; i <= per; i++)
        a[i] = A * sin(M_PI * (double)i / (double)per);
    double rr = mu * g / A, th = asin(rr), t1 = T * th / M_PI;
    double I = A * T / M_PI * (cos(th) * (T - t1) + T / M_PI * rr) - mu * g * (T - t1) * (T - t1) / 2;
    double wT = A * T / M_PI * (cos(th) + 1) - mu * g * (T - t1);
    double U = I + wT * wT / (2 * mu * g);
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    sl_slide_run(&s, &mu, 1, &o, &r, NULL);
    CHECK_CLOSE(r.peak_m, U, 0, 1e-6);
    CHECK(r.max_speed_ms > 5.0, "large velocity: %g m/s", r.max_speed_ms);
    double c = cos(M_PI / 3), sn = sin(M_PI / 3);
    double *ax = calloc(n, sizeof *ax), *ay = calloc(n, sizeof *ay);
    for (size_t i = 0; i < n; i++) {
        ax[i] = a[i] * c;
        ay[i] = a[i] * sn;
    }
    sl_motion mx = oracle_motion(ax, n, dt), my = oracle_motion(ay, n, dt);
    sl_set s2 = {&mx, &my, NULL};
    sl_slide_result r2;
    sl_slide_run(&s2, &mu, 1, &o, &r2, NULL);
    CHECK_CLOSE(r2.peak_m, U, 0, 1e-5);
    CHECK_CLOSE(r2.path_m, r.path_m, 0, 1e-5);
    free(a);
    free(ax);
    free(ay);
}

/* The history runs to rest, however long the tail (docs/model.md): a
 * rectangular pulse A for t0 at mu = 1e-4 leaves the block coasting for
 * (A - mu g) t0 / (mu g) = 1019 s after the pulse; its last sample is at rest
 * at U = V^2/(2 mu g) (1 - mu g/A), V = A t0 (REFERENCE 4). */
static void test_history_whole_tail(void)
{
    const double A = 1.0, t0 = 1.0, dt = 0.01, mu = 1e-4;
    const size_t n = (size_t)(t0 / dt) + 3;
    double *a = calloc(n, sizeof *a);
    for (size_t i = 0; i <= (size_t)(t0 / dt); i++)
        a[i] = A;
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    sl_history *h = NULL;
    CHECK(sl_slide_history(&s, mu, &o, &r, &h, NULL) == SL_OK && h, "run");
    /* piecewise-linear input: the pulse ends with a ramp over one dt (V = A (t0 + dt/2)); the friction
     * during the pulse changes U by a relative O(mu g / A) already in the formula */
    double V = A * (t0 + dt / 2), U = V * V / (2 * mu * g) * (1 - mu * g / A);
    if (h) {
        size_t e = h->n - 1;
        CHECK(h->t_s[e] > 1000.0, "history ends at %g s", h->t_s[e]);
        CHECK(h->vx_ms[e] == 0.0, "at rest: v %g", h->vx_ms[e]);
        CHECK_CLOSE(fabs(h->ux_m[e]), r.residual_m, 0, 1e-9);
        CHECK_CLOSE(fabs(h->ux_m[e]), U, 0, 1e-3);
        sl_history_free(h);
    }
    free(a);
}

int main(void)
{
    RUN(test_tiny_mu);
    RUN(test_threshold_mu);
    RUN(test_long_liftoff);
    RUN(test_sixty_minutes);
    RUN(test_all_zero);
    RUN(test_huge_spike);
    RUN(test_smooth_extreme);
    RUN(test_large_velocity_pulse);
    RUN(test_history_whole_tail);
    return HARNESS_END("hard");
}
