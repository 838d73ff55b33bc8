/*
 * test_slide.c - the sliding engine against closed forms and invariants
 * (../shared/docs/REFERENCE.md section 4). Every input is built here.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "oracle.h"
#include "slide/kernel2d.h"
#include "slide/kernel2d_step.h"
#include "slide/slide.h"

static const double g = SL_G;


static double *alloc_n(size_t n) { return calloc(n, sizeof(double)); }

static sl_slide_opts opts_default(void)
{
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    return o;
}


/* Rectangular pulse as samples: 0, A x p, 0 ... (ramps of one dt). The block
 * slides one way from the onset t_on (a = mu g on the first ramp) until
 * V_g(t) - V_g(t_on) = mu g (t - t_on); the slide is
 *   U = D_g(t_s) - D_g(t_on) - V_g(t_on)(t_s - t_on) - mu g (t_s - t_on)^2/2. */
static void test_rect_pulse_exact(void)
{
    const double A = 3.0, dt = 0.01, mu = 0.1;
    const size_t p = 50, n = 400;
    double *a = alloc_n(n);
    for (size_t i = 1; i <= p; i++)
        a[i] = A;
    sl_motion m = oracle_motion(a, n, dt);
    sl_set set = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    CHECK(sl_slide_run(&set, &mu, 1, &o, &r, NULL) == SL_OK, "run");
    double ton = dt * mu * g / A, Von, Don, V, D;
    oracle_ground_vd(a, n, dt, ton, &Von, &Don);
    oracle_ground_vd(a, n, dt, 1e9, &V, &D);
    double ts = ton + (V - Von) / (mu * g);
    double Vs, Ds;
    oracle_ground_vd(a, n, dt, ts, &Vs, &Ds);
    double U = Ds - Don - Von * (ts - ton) - mu * g * (ts - ton) * (ts - ton) / 2;
    CHECK_CLOSE(r.peak_m, U, 0, 1e-12);
    CHECK_CLOSE(r.residual_x_m, -U, 0, 1e-12);
    CHECK_CLOSE(r.t_rest_s, ts, 1e-12, 1e-12);
    CHECK_CLOSE(r.path_m, U, 0, 1e-12);
    CHECK(r.episodes == 1, "episodes %ld", r.episodes);
    /* and the textbook rectangle V^2/(2 mu g)(1 - mu g/A) with V = A t0, which
     * the ramps change by O(dt/t0) */
    double t0 = (double)p * dt, Vr = A * t0;
    double Ur = Vr * Vr / (2 * mu * g) * (1 - mu * g / A);
    CHECK_CLOSE(r.peak_m, Ur, 0, 2.0 * dt / t0);
    free(a);
}

/* Half-sine pulse A sin(pi t/T): onset theta1 = asin(r); for r < 0.7246 the
 * slide outlasts the pulse. With w(t) = (A T/pi)(cos th1 - cos(pi t/T)) -
 * mu g (t - t1): U = int_{t1}^{T} w + w(T)^2/(2 mu g). Sampled input is
 * piecewise linear, so the error is O(dt^2): check it and its order. */
static double half_sine_closed(double A, double T, double mu)
{
    double r = mu * g / A, th = asin(r), t1 = T * th / M_PI;
    double I = A * T / M_PI * (cos(th) * (T - t1) + T / M_PI * r) - mu * g * (T - t1) * (T - t1) / 2;
    double wT = A * T / M_PI * (cos(th) + 1) - mu * g * (T - t1);
    return I + wT * wT / (2 * mu * g);
}

static double half_sine_run(double A, double T, double mu, size_t per_pulse)
{
    double dt = T / (double)per_pulse;
    size_t n = per_pulse + 1 + 10;
    double *a = alloc_n(n);
    for (size_t i = 0; i <= per_pulse; i++)
        a[i] = A * sin(M_PI * (double)i / (double)per_pulse);
    sl_motion m = oracle_motion(a, n, dt);
    sl_set set = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    sl_slide_run(&set, &mu, 1, &o, &r, NULL);
    free(a);
    return r.peak_m;
}

static void test_half_sine(void)
{
    const double A = 5.0, T = 0.5;
    const double mus[] = {0.05, 0.2, 0.35};
    for (int q = 0; q < 3; q++) {
        double U = half_sine_closed(A, T, mus[q]);
        double e1 = fabs(half_sine_run(A, T, mus[q], 500) / U - 1);
        double e2 = fabs(half_sine_run(A, T, mus[q], 1000) / U - 1);
        CHECK(e2 < 1e-5, "mu %g: relative error %.3g at T/1000", mus[q], e2);
        /* second order in dt: halving dt divides the error by about 4 */
        CHECK(e1 / e2 > 3.5 && e1 / e2 < 4.5, "mu %g: error ratio %.3f (expect 4)", mus[q], e1 / e2);
    }
}

/* Two-way harmonic steady state a = A sin(w t), r < 0.537: amplitude
 * X = (A/w^2) sqrt(1 - (pi r/2)^2) (Den Hartog). Measured as half the
 * peak-to-peak of u over the last cycles. */
static void test_harmonic_steady_state(void)
{
    const double A = 2.0, f = 2.0, w = 2 * M_PI * f;
    /* the start-up transient of the mean drift dies out within ~60 cycles at
     * r = 0.1; the piecewise-linear sine is off by (w dt)^2/12 = 1.3e-5 */
    const size_t per = 500, cycles = 100, n = per * cycles + 1;
    const double dt = 1.0 / (f * (double)per);
    double *a = alloc_n(n);
    for (size_t i = 0; i < n; i++)
        a[i] = A * sin(w * (double)i * dt);
    sl_motion m = oracle_motion(a, n, dt);
    sl_set set = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    const double rs[] = {0.1, 0.3, 0.5};
    for (int q = 0; q < 3; q++) {
        double mu = rs[q] * A / g;
        sl_slide_result r;
        sl_history *h = NULL;
        CHECK(sl_slide_history(&set, mu, &o, &r, &h, NULL) == SL_OK, "history");
        if (!h)
            continue;
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = n - 1 - per; i < n; i++) {
            lo = fmin(lo, h->ux_m[i]);
            hi = fmax(hi, h->ux_m[i]);
        }
        double X = A / (w * w) * sqrt(1 - pow(M_PI * rs[q] / 2, 2));
        CHECK_CLOSE((hi - lo) / 2, X, 0, 1e-4);
        sl_history_free(h);
    }
    free(a);
}

/* Circular base motion a = A (cos wt, sin wt): steady relative speed
 * V = (A/w) sqrt(1 - r^2) on a circle of radius V/w. Projection 2-D kernel:
 * first order, so the error falls with the sub-steps. */
static void test_circular(void)
{
    const double A = 3.0, f = 1.0, w = 2 * M_PI * f, r = 0.4, mu = r * A / g;
    const size_t per = 200, cycles = 20, n = per * cycles + 1;
    const double dt = 1.0 / (f * (double)per);
    double *ax = alloc_n(n), *ay = alloc_n(n);
    for (size_t i = 0; i < n; i++) {
        ax[i] = A * cos(w * (double)i * dt);
        ay[i] = A * sin(w * (double)i * dt);
    }
    sl_motion mx = oracle_motion(ax, n, dt), my = oracle_motion(ay, n, dt);
    sl_set set = {&mx, &my, NULL};
    const double V = A / w * sqrt(1 - r * r);
    double prev_err = INFINITY;
    const unsigned subs[] = {1, 4, 16};
    for (int q = 0; q < 3; q++) {
        sl_slide_opts o = opts_default();
        o.substeps = subs[q];
        sl_slide_result res;
        sl_history *h = NULL;
        CHECK(sl_slide_history(&set, mu, &o, &res, &h, NULL) == SL_OK, "history");
        if (!h)
            continue;
        /* speed and orbit radius over the last cycle */
        double cx = 0, cy = 0, sp = 0;
        size_t i0 = n - 1 - per;
        for (size_t i = i0; i < n - 1; i++) {
            cx += h->ux_m[i];
            cy += h->uy_m[i];
            sp += hypot(h->vx_ms[i], h->vy_ms[i]);
        }
        cx /= (double)per;
        cy /= (double)per;
        sp /= (double)per;
        double rad = 0;
        for (size_t i = i0; i < n - 1; i++)
            rad += hypot(h->ux_m[i] - cx, h->uy_m[i] - cy) / (double)per;
        double err = fabs(sp / V - 1) + fabs(rad / (V / w) - 1);
        CHECK(err < prev_err, "substeps %u: error %.3g not below %.3g", subs[q], err, prev_err);
        prev_err = err;
        if (subs[q] == 16) {
            CHECK_CLOSE(sp, V, 0, 2e-3);
            CHECK_CLOSE(rad, V / w, 0, 2e-3);
        }
        sl_history_free(h);
    }
    free(ax);
    free(ay);
}

/* A synthetic broadband record, deterministic. */
static double *noise_record(size_t n, double dt, double amp, unsigned seed)
{
    double *a = alloc_n(n);
    unsigned s = seed;
    for (size_t i = 0; i < n; i++) {
        double t = (double)i * dt, env = sin(M_PI * t / ((double)(n - 1) * dt));
        double x = 0;
        for (int k = 0; k < 6; k++) {
            s = s * 1103515245u + 12345u;
            x += (double)((s >> 8) & 0xffff) / 65535.0 - 0.5;
        }
        a[i] = amp * env * env * x;
    }
    /* a little smoothing: 3-point moving average */
    for (size_t i = 1; i + 1 < n; i++)
        a[i] = (a[i - 1] + 2 * a[i] + a[i + 1]) / 4;
    a[0] = a[n - 1] = 0;
    return a;
}

/* A 1-D record along 45 degrees through the 2-D kernel reproduces the exact
 * 1-D answer, converging with the sub-steps. */
static void test_rotation_45(void)
{
    const size_t n = 2000;
    const double dt = 0.01, mu = 0.15;
    double *a = noise_record(n, dt, 8.0, 7u), *ax = alloc_n(n), *ay = alloc_n(n);
    for (size_t i = 0; i < n; i++) {
        ax[i] = a[i] * M_SQRT1_2;
        ay[i] = a[i] * M_SQRT1_2;
    }
    sl_motion m1 = oracle_motion(a, n, dt), mx = oracle_motion(ax, n, dt), my = oracle_motion(ay, n, dt);
    sl_set s1 = {&m1, NULL, NULL}, s2 = {&mx, &my, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r1, r2;
    sl_slide_run(&s1, &mu, 1, &o, &r1, NULL);
    CHECK(r1.peak_m > 0.01, "record must slide: %g", r1.peak_m);
    double prev = INFINITY;
    const unsigned subs[] = {4, 32, 256};
    for (int q = 0; q < 3; q++) {
        o.substeps = subs[q];
        sl_slide_run(&s2, &mu, 1, &o, &r2, NULL);
        double e = fabs(r2.peak_m / r1.peak_m - 1);
        CHECK(e < prev || e < 1e-6, "substeps %u: error %.3g", subs[q], e);
        prev = e;
        /* the path stays on the 45-degree line */
        CHECK_CLOSE(r2.residual_x_m, r2.residual_y_m, 1e-12, 1e-9);
    }
    CHECK(prev < 1e-3, "2-D along 45 deg vs exact 1-D at 256 substeps: %.3g", prev);
    free(a);
    free(ax);
    free(ay);
}

/* Constant vertical acceleration c: every answer equals the one with
 * mu (g + c)/g and no vertical. */
static void test_constant_vertical(void)
{
    const size_t n = 1500;
    const double dt = 0.01, mu = 0.2, c = -2.5;
    double *a = noise_record(n, dt, 9.0, 3u), *v = alloc_n(n);
    for (size_t i = 0; i < n; i++)
        v[i] = c;
    sl_motion mh = oracle_motion(a, n, dt), mv = oracle_motion(v, n, dt);
    sl_set sv = {&mh, NULL, &mv}, s0 = {&mh, NULL, NULL};
    sl_slide_opts o = opts_default();
    o.keep_going = 0; /* after the record the vertical is zero: compare within it */
    double mu_eq = mu * (g + c) / g;
    sl_slide_result r1, r2;
    sl_slide_run(&sv, &mu, 1, &o, &r1, NULL);
    sl_slide_run(&s0, &mu_eq, 1, &o, &r2, NULL);
    CHECK(r2.peak_m > 0.005, "must slide: %g", r2.peak_m);
    CHECK_CLOSE(r1.peak_m, r2.peak_m, 1e-15, 1e-9);
    CHECK_CLOSE(r1.path_m, r2.path_m, 1e-15, 1e-9);
    free(a);
    free(v);
}

/* Invariants: -a gives -u; (lambda a, lambda mu) gives lambda u; mu = 0
 * gives u = -ground displacement; mu g >= max|a| gives no sliding. */
static void test_invariants(void)
{
    const size_t n = 1200;
    const double dt = 0.005, mu = 0.1, lam = 2.5;
    double *a = noise_record(n, dt, 6.0, 11u), *an = alloc_n(n), *as = alloc_n(n);
    double *b = noise_record(n, dt, 6.0, 12u), *bn = alloc_n(n), *bs = alloc_n(n);
    for (size_t i = 0; i < n; i++) {
        an[i] = -a[i];
        as[i] = lam * a[i];
        bn[i] = -b[i];
        bs[i] = lam * b[i];
    }
    sl_motion ma = oracle_motion(a, n, dt), man = oracle_motion(an, n, dt), mas = oracle_motion(as, n, dt);
    sl_motion mb = oracle_motion(b, n, dt), mbn = oracle_motion(bn, n, dt), mbs = oracle_motion(bs, n, dt);
    sl_slide_opts o = opts_default();
    sl_slide_result r, rn, rs;
    /* 1-D and 2-D */
    for (int d = 1; d <= 2; d++) {
        sl_set s = {&ma, d == 2 ? &mb : NULL, NULL};
        sl_set sn = {&man, d == 2 ? &mbn : NULL, NULL};
        sl_set ss = {&mas, d == 2 ? &mbs : NULL, NULL};
        double mus = lam * mu;
        sl_slide_run(&s, &mu, 1, &o, &r, NULL);
        sl_slide_run(&sn, &mu, 1, &o, &rn, NULL);
        sl_slide_opts os = o; /* the absolute tolerance is a length: it scales too */
        os.atol_m = lam * o.atol_m;
        sl_slide_run(&ss, &mus, 1, &os, &rs, NULL);
        CHECK(r.peak_m > 1e-3, "%d-D must slide", d);
        CHECK_CLOSE(rn.peak_m, r.peak_m, 0, 1e-12);
        CHECK_CLOSE(rn.residual_x_m, -r.residual_x_m, 1e-15, 1e-12);
        CHECK_CLOSE(rn.residual_y_m, -r.residual_y_m, 1e-15, 1e-12);
        CHECK_CLOSE(rs.peak_m, lam * r.peak_m, 0, 1e-12);
        CHECK_CLOSE(rs.path_m, lam * r.path_m, 0, 1e-12);
        CHECK(rs.episodes == r.episodes, "episodes %ld vs %ld", rs.episodes, r.episodes);
    }
    /* mu = 0: u = -D_g over the record */
    {
        sl_set s = {&ma, NULL, NULL};
        double z = 0.0, V, D;
        sl_slide_run(&s, &z, 1, &o, &r, NULL);
        oracle_ground_vd(a, n, dt, (double)(n - 1) * dt, &V, &D);
        CHECK_CLOSE(r.residual_x_m, -D, 1e-12, 1e-10);
        CHECK(r.flags & SL_SLIDE_NEVER_STOPS, "mu = 0 must be flagged never_stops");
        sl_set s2 = {&ma, &mb, NULL};
        double Vb, Db;
        sl_slide_run(&s2, &z, 1, &o, &r, NULL);
        oracle_ground_vd(b, n, dt, (double)(n - 1) * dt, &Vb, &Db);
        CHECK_CLOSE(r.residual_x_m, -D, 1e-12, 1e-10);
        CHECK_CLOSE(r.residual_y_m, -Db, 1e-12, 1e-10);
    }
    /* mu g >= max |a|: no sliding; just below: slides */
    {
        sl_set s = {&ma, NULL, NULL};
        double thr = sl_slide_mu_threshold(&s, &o), amax = 0;
        for (size_t i = 0; i < n; i++)
            amax = fmax(amax, fabs(a[i]));
        CHECK_CLOSE(thr, amax / g, 0, 1e-15);
        double mus[2] = {thr, thr * (1 - 1e-6)};
        sl_slide_result rr[2];
        sl_slide_run(&s, mus, 2, &o, rr, NULL);
        CHECK(rr[0].peak_m == 0.0 && (rr[0].flags & SL_SLIDE_SKIPPED), "at threshold: %g", rr[0].peak_m);
        CHECK(rr[1].peak_m > 0.0 && !(rr[1].flags & SL_SLIDE_SKIPPED), "below threshold must slide");
        /* the skip is not a shortcut that changes answers: force integration */
        o.keep_going = 1;
        sl_history *h = NULL;
        sl_slide_history(&s, thr * 1.5, &o, &rr[0], &h, NULL);
        CHECK(rr[0].peak_m == 0.0, "integrated at 1.5 x threshold: %g", rr[0].peak_m);
        sl_history_free(h);
    }
    free(a); free(an); free(as); free(b); free(bn); free(bs);
}

/* Energy: the work of the inertia force -int a_g u' dt equals the friction
 * dissipation mu g * path when the block ends at rest (1-D exact: checked on
 * a fine history, trapezoid error O(dt^2)). */
static void test_energy_balance(void)
{
    /* smooth input so that the trapezoid rule on the history is accurate:
     * its error is O(dt^2), measured 1.2e-5 at this dt and 5e-5 at 2 dt */
    const size_t n = 8000;
    const double dt = 10.0 / (double)n, mu = 0.12;
    double *a = alloc_n(n);
    for (size_t i = 1; i < n; i++) {
        double t = (double)i * dt;
        a[i] = 7 * sin(2 * M_PI * 1.3 * t) * sin(M_PI * t / 10) + 3 * sin(2 * M_PI * 4.1 * t);
    }
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    sl_history *h = NULL;
    sl_slide_history(&s, mu, &o, &r, &h, NULL);
    CHECK(h != NULL && r.path_m > 0.01, "slides");
    if (h) {
        double W = 0;
        for (size_t i = 0; i + 1 < n; i++)
            W -= 0.5 * dt * (a[i] * h->vx_ms[i] + a[i + 1] * h->vx_ms[i + 1]);
        /* after the record a = 0: the tail dissipates v_end^2/2, which the
         * path already holds */
        CHECK(fabs(h->vx_ms[n - 1]) > 0.01, "ends sliding: the tail is exercised");
        CHECK_CLOSE(W, mu * g * r.path_m, 0, 1e-4);
        sl_history_free(h);
    }
    free(a);
}

/* Asymmetric resistance: one-way sliding under a symmetric sine never
 * moves upslope; a huge up_ratio converges to one-way; up_ratio 1 is the
 * symmetric answer. Newmark (1965) asymmetric rectangular pulse: same slide
 * as symmetric for a single pulse in the downslope direction. */
static void test_asymmetric(void)
{
    const size_t n = 3001;
    const double dt = 0.002, A = 3.0, f = 2.0, mu = 0.1;
    double *a = alloc_n(n);
    for (size_t i = 0; i < n; i++)
        a[i] = A * sin(2 * M_PI * f * (double)i * dt);
    sl_motion m = oracle_motion(a, n, dt);
    sl_set s = {&m, NULL, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r1, rw, rb;
    sl_history *h = NULL;
    o.up_ratio = INFINITY;
    CHECK(sl_slide_history(&s, mu, &o, &rw, &h, NULL) == SL_OK, "one-way");
    if (h) {
        int mono = 1;
        for (size_t i = 1; i < h->n; i++)
            mono &= h->ux_m[i] <= h->ux_m[i - 1] + 1e-15;
        CHECK(mono, "one-way: u must never increase");
        sl_history_free(h);
    }
    CHECK(rw.residual_x_m < 0 && rw.peak_m == -rw.residual_x_m, "downslope is -x");
    o.up_ratio = 1e6;
    sl_slide_run(&s, &mu, 1, &o, &rb, NULL);
    CHECK_CLOSE(rb.peak_m, rw.peak_m, 0, 1e-5);
    o.up_ratio = 1.0;
    sl_slide_run(&s, &mu, 1, &o, &r1, NULL);
    CHECK(rw.peak_m > r1.peak_m, "one-way accumulates more than two-way: %g vs %g", rw.peak_m, r1.peak_m);
    /* invert: the one-way slide then comes from the negative half cycles */
    o.up_ratio = INFINITY;
    o.invert = 1;
    sl_slide_result ri;
    sl_slide_run(&s, &mu, 1, &o, &ri, NULL);
    CHECK(ri.peak_m > 0 && ri.residual_x_m < 0, "inverted one-way slides downslope too");
    free(a);
}

/* Lift-off: a_v <= -g means no friction: the block moves with u'' = -a_g. */
static void test_liftoff(void)
{
    const size_t n = 200;
    const double dt = 0.01, mu = 0.5;
    double *a = alloc_n(n), *v = alloc_n(n);
    for (size_t i = 0; i < n; i++) {
        a[i] = 1.0; /* 0.1 g, far below mu g: no sliding without lift-off */
        v[i] = (i >= 50 && i < 100) ? -1.5 * g : 0.0;
    }
    a[0] = 0.0;
    sl_motion mh = oracle_motion(a, n, dt), mv = oracle_motion(v, n, dt);
    sl_set s = {&mh, NULL, &mv};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(r.liftoff_samples == 50, "lift-off samples %ld", r.liftoff_samples);
    CHECK(r.flags & SL_SLIDE_LIFTOFF, "flag");
    CHECK(r.peak_m > 0, "slides during lift-off");
    /* the 2-D kernel agrees (same vertical, H2 = 0) */
    double *z = alloc_n(n);
    sl_motion mz = oracle_motion(z, n, dt);
    sl_set s2 = {&mh, &mz, &mv};
    sl_slide_result r2;
    o.substeps = 64;
    sl_slide_run(&s2, &mu, 1, &o, &r2, NULL);
    CHECK_CLOSE(r2.peak_m, r.peak_m, 0, 2e-2);
    free(a);
    free(v);
    free(z);
}

/* Many mu at once give the same answers as one at a time; the batch is
 * the same whatever the thread count. */
static void test_vector_and_batch(void)
{
    const size_t n = 1500, nm = 37;
    const double dt = 0.01;
    double *a = noise_record(n, dt, 7.0, 21u), *b = noise_record(n, dt, 5.0, 22u);
    sl_motion ma = oracle_motion(a, n, dt), mb = oracle_motion(b, n, dt);
    double mu[37];
    for (size_t k = 0; k < nm; k++)
        mu[k] = 0.02 * (double)(k + 1);
    sl_slide_opts o = opts_default();
    for (int d = 1; d <= 2; d++) {
        sl_set s = {&ma, d == 2 ? &mb : NULL, NULL};
        sl_slide_result all[37], one;
        sl_slide_run(&s, mu, nm, &o, all, NULL);
        int same = 1;
        for (size_t k = 0; k < nm; k++) {
            sl_slide_run(&s, &mu[k], 1, &o, &one, NULL);
            same &= (one.peak_m == all[k].peak_m && one.residual_x_m == all[k].residual_x_m);
        }
        CHECK(same, "%d-D: vector of mu differs from one at a time", d);
        sl_set sets[3] = {s, s, s};
        sl_slide_result bt[3 * 37];
        CHECK(sl_slide_batch(sets, 3, mu, nm, &o, bt, NULL) == SL_OK, "batch");
        same = 1;
        for (size_t k = 0; k < 3 * nm; k++)
            same &= (bt[k].peak_m == all[k % nm].peak_m);
        CHECK(same, "%d-D: batch differs from single runs", d);
    }
    free(a);
    free(b);
}

/* Issue 11 (a): the 2-D "no sliding" threshold is the vector magnitude
 * |a_h| / N. A half-sine pulse of peak A = g along 45 degrees has components
 * of only g/sqrt(2) each, yet at mu = 0.95 < A/g the block must slide the
 * closed-form distance of the 1-D pulse; a threshold from max(|ax|, |ay|)
 * would skip it (0 mm). At r = mu g/A > 0.7246 the slide ends inside the
 * pulse: from the onset t1 = T asin(r)/pi the relative speed is
 *   w(t) = (A T/pi)(cos th1 - cos(pi t/T)) - mu g (t - t1)
 * until w(ts) = 0 (found by bisection here), and
 *   U = (A T/pi)(cos th1 (ts - t1) - (T/pi)(sin(pi ts/T) - r)) - mu g (ts - t1)^2/2.
 * The sampled (piecewise-linear) input differs by O(dt^2). */
static double half_sine_short(double A, double T, double mu)
{
    const double r = mu * g / A, th = asin(r), t1 = T * th / M_PI, k = A * T / M_PI;
    double lo = T / 2, hi = T; /* w > 0 at T/2 (w' = a - mu g > 0 before), w(T) < 0 */
    for (int it = 0; it < 200; it++) {
        double t = 0.5 * (lo + hi);
        double w = k * (cos(th) - cos(M_PI * t / T)) - mu * g * (t - t1);
        if (w > 0)
            lo = t;
        else
            hi = t;
    }
    double ts = 0.5 * (lo + hi);
    return k * (cos(th) * (ts - t1) - T / M_PI * (sin(M_PI * ts / T) - r)) -
           mu * g * (ts - t1) * (ts - t1) / 2;
}

static void test_threshold_vector(void)
{
    const double A = g, T = 0.5, mu = 0.95;
    const size_t per = 2000, n = per + 11;
    double *ax = alloc_n(n), *ay = alloc_n(n);
    for (size_t i = 0; i <= per; i++) {
        ax[i] = A * sin(M_PI * (double)i / (double)per) * M_SQRT1_2;
        ay[i] = ax[i];
    }
    sl_motion mx = oracle_motion(ax, n, T / (double)per), my = oracle_motion(ay, n, T / (double)per);
    sl_set set = {&mx, &my, NULL};
    sl_slide_opts o = opts_default();
    CHECK_CLOSE(sl_slide_mu_threshold(&set, &o), A / g, 0, 1e-12);
    sl_slide_result r;
    CHECK(sl_slide_run(&set, &mu, 1, &o, &r, NULL) == SL_OK, "run");
    double U = half_sine_short(A, T, mu);
    CHECK(U > 5e-4, "closed form must slide: %g", U);
    CHECK_CLOSE(r.peak_m, U, 0, 2e-3);
    CHECK(!(r.flags & SL_SLIDE_SKIPPED), "flags %d", r.flags);
    free(ax);
    free(ay);
}

/* Issue 11 (b): the position update of the 2-D step while sliding on is
 * exact for forcing linear in time, trapezoid + h^2/12 (a_1 - a_0) (eq. 4).
 * A ramp a(t) = -(c0 + c1 t) along 45 degrees (c0 > mu g) drives the block
 * from rest without stopping: u(t) = (c0 - mu g) t^2/2 + c1 t^3/6 along the
 * diagonal. One sub-step of 0.05 s; the only error is the first (onset)
 * step's c1 h^3/12. Without the correction the error grows as t c1 h^2/12
 * (4e-4 m at 2 s). */
static void test_ramp_position(void)
{
    const double dt = 0.05, c0 = 3.0, c1 = 1.5, mu = 0.2;
    const size_t n = 41;
    double *ax = alloc_n(n), *ay = alloc_n(n);
    for (size_t i = 0; i < n; i++)
        ax[i] = ay[i] = -(c0 + c1 * (double)i * dt) * M_SQRT1_2;
    sl_motion mx = oracle_motion(ax, n, dt), my = oracle_motion(ay, n, dt);
    sl_set set = {&mx, &my, NULL};
    sl_slide_opts o = opts_default();
    o.substeps = 1;
    o.keep_going = 0;
    sl_slide_result r;
    sl_history *h = NULL;
    CHECK(sl_slide_history(&set, mu, &o, &r, &h, NULL) == SL_OK, "history");
    if (h) {
        const double tol = c1 * dt * dt * dt / 12 * 1.01 + 1e-12;
        for (size_t i = 1; i < n; i++) {
            double t = (double)i * dt;
            double u = (c0 - mu * g) * t * t / 2 + c1 * t * t * t / 6;
            CHECK_CLOSE(hypot(h->ux_m[i], h->uy_m[i]), u, tol, 0);
            CHECK_CLOSE(h->ux_m[i], h->uy_m[i], 1e-14, 1e-12);
        }
        sl_history_free(h);
    }
    free(ax);
    free(ay);
}

/* Error control (issue 14) on synthetic 2-D + vertical motions (no files
 * needed): the default run is within max(rtol peak, atol) of the engine at
 * a 1000 x tighter tolerance, and its estimate err_est_m bounds that error;
 * the tight run is checked against the exact 1-D kernel on the same record
 * along 30 degrees (an independent method), vertical included. */
static void test_error_control(void)
{
    const size_t n = 3000;
    const double dt = 0.01, mus[] = {0.08, 0.15, 0.25, 0.35};
    const size_t nm = sizeof mus / sizeof mus[0];
    int rows = 0, bounded = 0;
    for (unsigned seed = 11; seed <= 12; seed++) {
        double *ax = noise_record(n, dt, 9.0, seed), *ay = noise_record(n, dt, 7.0, seed + 100);
        double *av = noise_record(n, dt, 6.0, seed + 200);
        sl_motion mx = oracle_motion(ax, n, dt), my = oracle_motion(ay, n, dt),
                  mv = oracle_motion(av, n, dt);
        sl_set set = {&mx, &my, &mv};
        sl_slide_opts o = opts_default(), ot = opts_default();
        ot.rtol = 1e-6;
        ot.atol_m = 1e-9;
        sl_slide_result a[4], r[4];
        CHECK(sl_slide_run(&set, mus, nm, &o, a, NULL) == SL_OK, "default");
        CHECK(sl_slide_run(&set, mus, nm, &ot, r, NULL) == SL_OK, "tight");
        for (size_t k = 0; k < nm; k++) {
            const double err = fabs(a[k].peak_m - r[k].peak_m);
            CHECK(r[k].peak_m > 1e-3, "seed %u mu %g must slide: %g", seed, mus[k], r[k].peak_m);
            CHECK(err <= fmax(o.rtol * r[k].peak_m, o.atol_m), "seed %u mu %g: error %.3g of %.9g",
                  seed, mus[k], err, r[k].peak_m);
            CHECK(a[k].err_est_m > 0 && a[k].err_est_m <= fmax(o.rtol * a[k].peak_m, o.atol_m),
                  "estimate %g within the tolerance", a[k].err_est_m);
            rows++;
            bounded += a[k].err_est_m >= err;
        }
        /* the tight run against the exact 1-D answer along 30 degrees */
        double *b = alloc_n(n), *bx = alloc_n(n), *by = alloc_n(n);
        for (size_t i = 0; i < n; i++) {
            b[i] = ax[i];
            bx[i] = ax[i] * cos(M_PI / 6);
            by[i] = ax[i] * sin(M_PI / 6);
        }
        sl_motion m1 = oracle_motion(b, n, dt), m2x = oracle_motion(bx, n, dt),
                  m2y = oracle_motion(by, n, dt);
        sl_set s1 = {&m1, NULL, &mv}, s2 = {&m2x, &m2y, &mv};
        sl_slide_result e1[4], e2[4];
        sl_slide_run(&s1, mus, nm, &o, e1, NULL);
        sl_slide_run(&s2, mus, nm, &ot, e2, NULL);
        for (size_t k = 0; k < nm; k++) {
            CHECK(e1[k].err_est_m == 0.0, "1-D exact: estimate %g", e1[k].err_est_m);
            CHECK_CLOSE(e2[k].peak_m, e1[k].peak_m, 1e-8, 1e-6);
        }
        free(ax);
        free(ay);
        free(av);
        free(b);
        free(bx);
        free(by);
    }
    CHECK(bounded == rows, "the estimate bounds the error in %d of %d rows", bounded, rows);
    /* a record that stops in strong shaking: the block slides on after it
     * and the peak is at the end of the tail, d = v^2/(2 mu g); its
     * estimate carries the velocity error, |v| dv/(mu g) */
    {
        const size_t nc = 1200;
        double *ax = noise_record(2 * nc, dt, 9.0, 21u), *ay = noise_record(2 * nc, dt, 9.0, 22u);
        sl_motion mx = oracle_motion(ax, nc, dt), my = oracle_motion(ay, nc, dt);
        sl_set set = {&mx, &my, NULL};
        const double mu = 0.05;
        sl_slide_opts o = opts_default(), ot = opts_default();
        ot.rtol = 1e-6;
        ot.atol_m = 1e-9;
        sl_slide_result a, r;
        sl_slide_run(&set, &mu, 1, &o, &a, NULL);
        sl_slide_run(&set, &mu, 1, &ot, &r, NULL);
        CHECK(r.t_peak_s > (double)(nc - 1) * dt, "peak in the tail: t %g", r.t_peak_s);
        CHECK(a.err_est_m >= fabs(a.peak_m - r.peak_m), "tail: estimate %.3g, error %.3g",
              a.err_est_m, fabs(a.peak_m - r.peak_m));
        free(ax);
        free(ay);
    }
}

/* Stop-heavy sliding: a 1-D record with a vertical along 20 degrees, at mu
 * from 0.1 to 0.55 of the threshold (short slides, many stops and
 * restarts inside samples). The default 2-D run against the exact 1-D
 * kernel (an independent method): every peak and residual within
 * max(rtol peak, atol), the estimate bounding any error above a tenth of
 * that. */
/* The 1-D record a (with vertical av) and the same record along th from the
 * x axis as two horizontals: s1 the 1-D set, s2 the 2-D one. The motions
 * point into a, av and the freshly allocated *ax, *ay (freed by the caller). */
static void along_direction(double *a, double *av, size_t n, double dt, double th, double **ax,
                            double **ay, sl_motion m[4], sl_set *s1, sl_set *s2)
{
    *ax = alloc_n(n);
    *ay = alloc_n(n);
    for (size_t i = 0; i < n; i++) {
        (*ax)[i] = a[i] * cos(th);
        (*ay)[i] = a[i] * sin(th);
    }
    m[0] = oracle_motion(a, n, dt);
    m[1] = oracle_motion(*ax, n, dt);
    m[2] = oracle_motion(*ay, n, dt);
    m[3] = oracle_motion(av, n, dt);
    *s1 = (sl_set){&m[0], NULL, &m[3]};
    *s2 = (sl_set){&m[1], &m[2], &m[3]};
}

static void test_stop_heavy(void)
{
    const size_t n = 3000;
    const double dt = 0.01, th = 20.0 * M_PI / 180.0;
    double *a = noise_record(n, dt, 6.0, 31u), *av = noise_record(n, dt, 4.0, 32u), *ax, *ay;
    sl_motion m[4];
    sl_set s1, s2;
    along_direction(a, av, n, dt, th, &ax, &ay, m, &s1, &s2);
    sl_slide_opts o = opts_default();
    const double thr = sl_slide_mu_threshold(&s1, &o);
    enum { NM = 10 };
    double mus[NM];
    for (int k = 0; k < NM; k++)
        mus[k] = thr * (0.1 + 0.05 * k);
    sl_slide_result r1[NM], r2[NM];
    CHECK(sl_slide_run(&s1, mus, NM, &o, r1, NULL) == SL_OK, "exact 1-D");
    CHECK(sl_slide_run(&s2, mus, NM, &o, r2, NULL) == SL_OK, "2-D along 20 degrees");
    long episodes = 0;
    for (int k = 0; k < NM; k++) {
        const double tol = fmax(o.rtol * r1[k].peak_m, o.atol_m);
        const double err = fabs(r2[k].peak_m - r1[k].peak_m);
        CHECK(err <= tol, "mu %.4g: peak %.9g vs exact %.9g (error %.3g > %.3g)", mus[k],
              r2[k].peak_m, r1[k].peak_m, err, tol);
        CHECK(fabs(r2[k].residual_m - r1[k].residual_m) <= tol, "mu %.4g: residual %.9g vs %.9g",
              mus[k], r2[k].residual_m, r1[k].residual_m);
        CHECK(err <= fmax(r2[k].err_est_m, 0.1 * tol),
              "mu %.4g: estimate %.3g below the error %.3g", mus[k], r2[k].err_est_m, err);
        episodes += r1[k].episodes;
        if (getenv("SEISLIDE_TEST_VERBOSE"))
            fprintf(stderr, "  mu %.4f peak %.6g err %.3g est %.3g tol %.3g episodes %ld\n",
                    mus[k], r1[k].peak_m, err, r2[k].err_est_m, tol, r1[k].episodes);
    }
    CHECK(episodes >= 20 * NM, "stop-heavy: %ld episodes over %d mu", episodes, NM);
    free(a);
    free(av);
    free(ax);
    free(ay);
}

/* Lift-off inside a sample: N = g + a_v goes from -g to +g over the first
 * sample while a rises from 0 to 1 m/s^2, so max(N, 0) has a kink inside it
 * and the block, held (|a| <= mu N) at both ends of that sample, slips in
 * between while N is still small (8.5 um). Neither the friction threshold
 * (engine.c) nor the 2-D engine's held test (kernel2d.c find_live) may take
 * the ends of that sample for the whole of it: the exact 1-D kernel must
 * slide, and the 2-D engine along 30 degrees must agree with it. */
static void test_liftoff_inside_sample(void)
{
    const size_t n = 40;
    const double dt = 0.01, th = 30.0 * M_PI / 180.0, mu = 0.2;
    double *a = alloc_n(n), *av = alloc_n(n), *ax, *ay;
    for (size_t i = 0; i < n; i++) {
        a[i] = i <= 10 ? 0.0 : 1.0;
        av[i] = i == 10 ? -2.0 * SL_G : 0.0;
    }
    sl_motion m[4];
    sl_set s1, s2;
    along_direction(a, av, n, dt, th, &ax, &ay, m, &s1, &s2);
    sl_slide_opts o = opts_default();
    sl_slide_result r1, r2;
    CHECK(sl_slide_run(&s1, &mu, 1, &o, &r1, NULL) == SL_OK, "exact 1-D");
    CHECK(sl_slide_run(&s2, &mu, 1, &o, &r2, NULL) == SL_OK, "2-D along 30 degrees");
    if (getenv("SEISLIDE_TEST_VERBOSE"))
        fprintf(stderr, "  1-D %.9g m (%ld episodes), 2-D %.9g m (%ld)\n", r1.peak_m, r1.episodes,
                r2.peak_m, r2.episodes);
    CHECK(r1.peak_m > 0 && r1.episodes >= 1, "1-D: the block slips while N is small: peak %g m, %ld episodes",
          r1.peak_m, r1.episodes);
    const double tol = fmax(o.rtol * r1.peak_m, o.atol_m);
    CHECK(fabs(r2.peak_m - r1.peak_m) <= tol, "2-D peak %.9g vs exact 1-D %.9g (tolerance %.3g)",
          r2.peak_m, r1.peak_m, tol);
    free(a);
    free(ax);
    free(ay);
    free(av);
}

/* The AVX2 and baseline instances of the engine's vector passes
 * (kernel2d.c) give the same bits: every field of every result on
 * independent 2-D + vertical noise (stops, onsets, turns; no lift-off) at
 * 40 mu, error-controlled and at 8 fixed sub-steps. Skipped where only the
 * baseline runs (a CPU without AVX2, or a build other than GCC on x86-64). */
static void same_results(const sl_slide_result *a, const sl_slide_result *b, size_t n,
                         const char *what)
{
    size_t bad = 0;
    for (size_t k = 0; k < n; k++) {
        const double x[] = {a[k].peak_m, a[k].peak_x_m, a[k].peak_y_m, a[k].t_peak_s,
                            a[k].residual_m, a[k].residual_x_m, a[k].residual_y_m,
                            a[k].path_m, a[k].max_speed_ms, a[k].t_rest_s, a[k].err_est_m,
                            a[k].slide_time_s};
        const double y[] = {b[k].peak_m, b[k].peak_x_m, b[k].peak_y_m, b[k].t_peak_s,
                            b[k].residual_m, b[k].residual_x_m, b[k].residual_y_m,
                            b[k].path_m, b[k].max_speed_ms, b[k].t_rest_s, b[k].err_est_m,
                            b[k].slide_time_s};
        bad += memcmp(x, y, sizeof x) != 0 || a[k].episodes != b[k].episodes ||
               a[k].flags != b[k].flags;
    }
    CHECK(bad == 0, "%s: %zu of %zu results differ between the instances", what, bad, n);
}

static void test_engine_instances_same_bits(void)
{
    if (!sl_kernel2d_avx2()) {
        SKIP("no AVX2 instance here (CPU without AVX2, or not built: GCC on x86-64 only)");
    }
    const size_t n = 3000;
    const double dt = 0.01;
    double *ax = noise_record(n, dt, 6.0, 41u), *ay = noise_record(n, dt, 5.0, 42u),
           *av = noise_record(n, dt, 4.0, 43u);
    sl_motion m[3] = {oracle_motion(ax, n, dt), oracle_motion(ay, n, dt), oracle_motion(av, n, dt)};
    const sl_set set = {&m[0], &m[1], &m[2]};
    enum { NM = 40 };
    double mus[NM];
    for (int k = 0; k < NM; k++)
        mus[k] = 0.02 + 0.015 * k;
    sl_slide_result r[2][NM];
    for (int fixed = 0; fixed < 2; fixed++) {
        sl_slide_opts o = opts_default();
        o.substeps = fixed ? 8 : 0;
        int was = 0;
        for (int k = 0; k < 2; k++) {
            const int before = sl_kernel2d_baseline(k);
            if (k == 0)
                was = before;
            CHECK(sl_kernel2d_avx2() == !k, "instance %d", k);
            CHECK(sl_slide_run(&set, mus, NM, &o, r[k], NULL) == SL_OK, "run");
        }
        sl_kernel2d_baseline(was);
        same_results(r[0], r[1], NM, fixed ? "8 fixed sub-steps" : "error-controlled");
    }
    long episodes = 0;
    for (int k = 0; k < NM; k++)
        episodes += r[0][k].episodes;
    CHECK(episodes >= 10 * NM, "a run with stops and onsets: %ld episodes", episodes);
    free(ax);
    free(ay);
    free(av);
}

/* The Coulomb step (3)-(4) is written twice: the scalar step with its
 * split (5) (kernel2d_step.c fstep, through sl_k2_run_level) and the
 * vector sub-step pass (kernel2d.c substep_body, through the level runs
 * of fixed sub-steps, levelrun_pass), which hands a block to the scalar
 * step only for a split. On 2-D + vertical noise at 30 mu and 1, 2, 4 and
 * 16 sub-steps, every
 * block's state and statistics from sl_kernel2d_run must be the scalar
 * step's to the bit. */
static void test_step_forms_agree(void)
{
    const size_t n = 1500;
    const double dt = 0.01;
    double *ax = noise_record(n, dt, 6.0, 51u), *ay = noise_record(n, dt, 5.0, 52u),
           *av = noise_record(n, dt, 4.0, 53u);
    const sl_k2_motion km = {n, dt, SL_G, 1.0, ax, ay, av};
    enum { NM = 30 };
    double mus[NM];
    for (int k = 0; k < NM; k++)
        mus[k] = 0.03 + 0.02 * k;
    sl_k2_out out[NM];
    /* 16: long levels, in which the vector run of a level stops at a block's
     * split step and resumes after it (kernel2d.c levelrun_pass) many times */
    static const unsigned subs[4] = {1, 2, 4, 16};
    for (int q = 0; q < 4; q++) {
        const sl_k2_opts ko = {subs[q], 1e-3, 1e-6};
        CHECK(sl_kernel2d_run(&km, mus, NULL, NULL, NM, &ko, out, NULL) == 0, "run");
        size_t bad = 0;
        long episodes = 0;
        for (int k = 0; k < NM; k++) {
            blk b;
            memset(&b, 0, sizeof b);
            for (size_t i = 0; i + 1 < n; i++) {
                const sample sm = {ax[i], ax[i + 1], ay[i], ay[i + 1], SL_G + av[i],
                                   SL_G + av[i + 1], dt, (double)i * dt};
                b = sl_k2_run_level(b, &sm, mus[k], subs[q], 0.0);
            }
            const double x[] = {b.ux, b.uy, b.vx, b.vy, sqrt(b.peak2), b.tpeak, b.px, b.py,
                                b.path, sqrt(b.vmax2), b.tstop, b.tslide};
            const double y[] = {out[k].ux, out[k].uy, out[k].vx, out[k].vy, out[k].peak_m,
                                out[k].t_peak_s, out[k].peak_x_m, out[k].peak_y_m,
                                out[k].path_m, out[k].max_speed_ms, out[k].t_stop_s,
                                out[k].slide_time_s};
            bad += memcmp(x, y, sizeof x) != 0 || b.episodes != out[k].episodes;
            episodes += b.episodes;
        }
        CHECK(bad == 0, "%u sub-steps: %zu of %d blocks differ between the vector and the scalar step",
              subs[q], bad, NM);
        CHECK(episodes >= 5 * NM, "a run with stops and onsets: %ld episodes", episodes);
    }
    free(ax);
    free(ay);
    free(av);
}

/* Bad options are errors, never silent. */
static void test_bad_options(void)
{
    double a[4] = {0, 1, 2, 0};
    sl_motion m = oracle_motion(a, 4, 0.01);
    sl_set s = {&m, &m, NULL};
    sl_slide_opts o = opts_default();
    sl_slide_result r;
    sl_error e;
    double mu = -0.1;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, &e) == SL_EINVAL, "negative mu");
    mu = NAN;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, &e) == SL_EINVAL, "NaN mu");
    mu = 0.1;
    o.up_ratio = INFINITY;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, &e) == SL_EINVAL, "one-way in 2-D");
    CHECK(strstr(e.msg, "1-D") != NULL, "message: %s", e.msg);
    o = opts_default();
    o.rtol = 0.0;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, &e) == SL_EINVAL, "rtol 0");
    o = opts_default();
    o.atol_m = -1e-6;
    CHECK(sl_slide_run(&s, &mu, 1, &o, &r, &e) == SL_EINVAL, "atol < 0");
}

/* sl_slide_opts_set_tol: the engine's tolerances for the exact and plastic
 * models, the ODE solver's for the smooth one; <= 0 keeps; an engine rtol
 * outside [1e-9, 0.1] is refused with nothing changed. */
static void test_set_tol(void)
{
    sl_slide_opts o = opts_default(), d = o;
    sl_error e;
    CHECK(sl_slide_opts_set_tol(&o, 1e-4, 2e-8, &e) == SL_OK && o.rtol == 1e-4 &&
              o.atol_m == 2e-8 && o.smooth_rtol == d.smooth_rtol && o.smooth_atol == d.smooth_atol,
          "exact: rtol %g atol %g smooth %g %g", o.rtol, o.atol_m, o.smooth_rtol, o.smooth_atol);
    o = d;
    o.model = SL_MODEL_SMOOTH;
    CHECK(sl_slide_opts_set_tol(&o, 1e-5, 3e-10, &e) == SL_OK && o.smooth_rtol == 1e-5 &&
              o.smooth_atol == 3e-10 && o.rtol == d.rtol && o.atol_m == d.atol_m,
          "smooth: %g %g, engine %g %g", o.smooth_rtol, o.smooth_atol, o.rtol, o.atol_m);
    o = d;
    CHECK(sl_slide_opts_set_tol(&o, 0, -1, &e) == SL_OK && !memcmp(&o, &d, sizeof o),
          "<= 0 keeps the defaults");
    o.model = d.model = SL_MODEL_PLASTIC;
    CHECK(sl_slide_opts_set_tol(&o, 0.5, 1e-3, &e) == SL_EINVAL && !memcmp(&o, &d, sizeof o) &&
              strstr(e.msg, "0.5") != NULL,
          "rtol 0.5 refused, nothing changed: %s", e.msg);
    CHECK(sl_slide_opts_set_tol(&o, 1e-12, 0, &e) == SL_EINVAL, "rtol 1e-12 refused");
    CHECK(sl_slide_opts_set_tol(&o, 0.1, 0, &e) == SL_OK && o.rtol == 0.1, "rtol 0.1 taken");
}

int main(void)
{
    RUN(test_rect_pulse_exact);
    RUN(test_half_sine);
    RUN(test_harmonic_steady_state);
    RUN(test_circular);
    RUN(test_rotation_45);
    RUN(test_constant_vertical);
    RUN(test_invariants);
    RUN(test_energy_balance);
    RUN(test_asymmetric);
    RUN(test_liftoff);
    RUN(test_vector_and_batch);
    RUN(test_threshold_vector);
    RUN(test_ramp_position);
    RUN(test_error_control);
    RUN(test_stop_heavy);
    RUN(test_liftoff_inside_sample);
    RUN(test_engine_instances_same_bits);
    RUN(test_step_forms_agree);
    RUN(test_bad_options);
    RUN(test_set_tol);
    return HARNESS_END("slide");
}
