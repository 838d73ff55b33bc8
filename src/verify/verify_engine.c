/* verify_engine.c - verification problems of the sliding engine and the
 * reference models against closed forms (verify.h; the derivations in
 * docs/verification.md, "The engine"). Every input is built here. */
#include <math.h>
#include <stdlib.h>

#include "core/units.h"
#include "slide/slide.h"
#include "verify/closed_forms.h"
#include "verify/verify_problems.h"

/* ---- references ---------------------------------------------------------- */

/* The pulse of E01: A on samples 0..m-1, zero after (the last interval
 * ramps A -> 0). The block slides toward -x from t = 0 until the ground
 * velocity V equals muN T; U = D(t_m) + V (T - t_m) - muN T^2/2. */
static double pulse_closed(double A, size_t m, double dt, double muN)
{
    double tm1 = (double)(m - 1) * dt, tm = (double)m * dt;
    double V = A * tm1 + 0.5 * A * dt;
    double Dm = 0.5 * A * tm1 * tm1 + A * tm1 * dt + A * dt * dt / 3.0;
    double T = V / muN;
    return Dm + V * (T - tm) - 0.5 * muN * T * T;
}

/* Half-sine A sin(pi t/T): onset th1 = asin(r), r = mu g/A; with
 * w(t) = (A T/pi)(cos th1 - cos(pi t/T)) - mu g (t - t1) the relative
 * speed, U = int_{t1}^{T} w dt + w(T)^2/(2 mu g) (r < 0.7246: the slide
 * outlasts the pulse). */
static double half_sine_closed(double A, double T, double mu)
{
    const double g = SL_G, r = mu * g / A, th = asin(r), t1 = T * th / M_PI;
    double I = A * T / M_PI * (cos(th) * (T - t1) + T / M_PI * r) - mu * g * (T - t1) * (T - t1) / 2;
    double wT = A * T / M_PI * (cos(th) + 1) - mu * g * (T - t1);
    return I + wT * wT / (2 * mu * g);
}

/* ---- inputs --------------------------------------------------------------- */

#define PULSE_A (0.5 * SL_G)
#define PULSE_MU 0.2
#define PULSE_DT 0.005
#define PULSE_M 40  /* t0 = 0.2 s */
#define PULSE_N 200 /* 1 s: the slide stops at 0.5 s */

static double *zeros(size_t n) { return calloc(n, sizeof(double)); }

static sl_status nomem(sl_error *err) { return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory"); }

/* Peak of one 1-D (+ vertical av, NULL none) run with opts o. */
static sl_status peak_1d(double *a, double *av, size_t n, double dt, double mu,
                         const sl_slide_opts *o, sl_slide_result *r, sl_error *err)
{
    sl_motion mh = {"", "", n, dt, a}, mv = {"", "", n, dt, av};
    sl_set set = {&mh, NULL, av ? &mv : NULL};
    return sl_slide_run(&set, &mu, 1, o, r, err);
}

static sl_status pulse_run(sl_model model, double av_const, sl_verify_value *v, sl_error *err)
{
    double *a = zeros(PULSE_N), *av = av_const != 0 ? zeros(PULSE_N) : NULL;
    if (!a || (av_const != 0 && !av)) {
        free(a);
        free(av);
        return nomem(err);
    }
    for (size_t i = 0; i < PULSE_M; i++)
        a[i] = PULSE_A;
    for (size_t i = 0; av && i < PULSE_N; i++)
        av[i] = av_const;
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    o.model = model;
    o.smooth_uy_m = o.plastic_uy_m = 1e-6;
    o.smooth_eta = 20;
    sl_slide_result r;
    sl_status st = peak_1d(a, av, PULSE_N, PULSE_DT, PULSE_MU, &o, &r, err);
    v->computed = r.peak_m;
    v->reference = pulse_closed(PULSE_A, PULSE_M, PULSE_DT, PULSE_MU * (SL_G + av_const));
    free(a);
    free(av);
    return st;
}

SL_VERIFY_FN(sl_verify_e01_pulse)
{
    (void)ctx;
    v->rel_tol = 1e-12;
    return pulse_run(SL_MODEL_EXACT, 0.0, v, err);
}

SL_VERIFY_FN(sl_verify_e02_newmark)
{
    (void)ctx;
    const double A = 3.0, dt = 0.001, mu = 0.1, t0 = 0.5;
    const size_t p = 500, n = 3000;
    double *a = zeros(n);
    if (!a)
        return nomem(err);
    for (size_t i = 1; i <= p; i++)
        a[i] = A;
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    sl_slide_result r;
    sl_status st = peak_1d(a, NULL, n, dt, mu, &o, &r, err);
    double V = A * t0;
    v->reference = V * V / (2 * mu * SL_G) * (1 - mu * SL_G / A);
    v->computed = r.peak_m;
    v->rel_tol = 2 * dt / t0;
    free(a);
    return st;
}

static sl_status half_sine(double mu, sl_verify_value *v, sl_error *err)
{
    const double A = 5.0, T = 0.5;
    const size_t per = 1000, n = per + 11;
    double *a = zeros(n);
    if (!a)
        return nomem(err);
    for (size_t i = 0; i <= per; i++)
        a[i] = A * sin(M_PI * (double)i / (double)per);
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    sl_slide_result r;
    sl_status st = peak_1d(a, NULL, n, T / (double)per, mu, &o, &r, err);
    v->computed = r.peak_m;
    v->reference = half_sine_closed(A, T, mu);
    v->rel_tol = 1e-5;
    free(a);
    return st;
}

SL_VERIFY_FN(sl_verify_e03_half_sine)
{
    (void)ctx;
    return half_sine(0.2, v, err);
}

SL_VERIFY_FN(sl_verify_e04_half_sine)
{
    (void)ctx;
    return half_sine(0.05, v, err);
}

/* Ramped pulses +A, -A, +A (each 0, A x p, 0), each starting from rest
 * 2 s after the one before. One ramped pulse from rest: onset t_on inside
 * the first ramp (a = mu g), stop at t_s = t_on + (V_end - V_on)/(mu g),
 * U = D(t_s) - D(t_on) - V_on (t_s - t_on) - mu g (t_s - t_on)^2/2. */
SL_VERIFY_FN(sl_verify_e05_one_way)
{
    (void)ctx;
    const double A = 3.0, dt = 0.01, mu = 0.1, g = SL_G;
    const size_t p = 50, gap = 200, n = 3 * gap + 200;
    double *a = zeros(n);
    if (!a)
        return nomem(err);
    for (size_t k = 0; k < 3; k++)
        for (size_t i = 1; i <= p; i++)
            a[k * gap + i] = k == 1 ? -A : A;
    /* one pulse alone, from the reference integral */
    double ton = dt * mu * g / A, Von, Don, Vend, Dend, Vs, Ds;
    sl_closed_ground_vd(a, gap, dt, ton, &Von, &Don);
    sl_closed_ground_vd(a, gap, dt, 1e9, &Vend, &Dend);
    double ts = ton + (Vend - Von) / (mu * g);
    sl_closed_ground_vd(a, gap, dt, ts, &Vs, &Ds);
    double U = Ds - Don - Von * (ts - ton) - mu * g * (ts - ton) * (ts - ton) / 2;
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    o.up_ratio = INFINITY;
    sl_slide_result r;
    sl_status st = peak_1d(a, NULL, n, dt, mu, &o, &r, err);
    v->reference = 2 * U;
    v->computed = r.peak_m;
    v->rel_tol = 1e-10;
    free(a);
    return st;
}

/* A deterministic record: three sines under a smooth envelope (stops,
 * restarts and reversals at mu 0.15). */
static double *wave_record(size_t n, double dt, double scale, double phase)
{
    double *a = zeros(n);
    if (!a)
        return NULL;
    const double T = (double)(n - 1) * dt;
    for (size_t i = 0; i < n; i++) {
        double t = (double)i * dt, e = sin(M_PI * t / T);
        a[i] = scale * e * e *
               (sin(2 * M_PI * 1.1 * t + phase) + 0.7 * sin(2 * M_PI * 2.3 * t + 1.0 + phase) +
                0.5 * sin(2 * M_PI * 0.6 * t + 2.0));
    }
    return a;
}

#define WAVE_N 1001
#define WAVE_DT 0.01
#define WAVE_MU 0.15

/* The record of wave_record along angle th: exact 1-D against the 2-D
 * engine. */
static sl_status along(double th_deg, sl_verify_value *v, sl_error *err)
{
    double *a = wave_record(WAVE_N, WAVE_DT, 4.0, 0.0), *ax = zeros(WAVE_N), *ay = zeros(WAVE_N);
    sl_status st = SL_OK;
    if (!a || !ax || !ay) {
        st = nomem(err);
        goto done;
    }
    const double th = th_deg * M_PI / 180.0;
    for (size_t i = 0; i < WAVE_N; i++) {
        ax[i] = a[i] * cos(th);
        ay[i] = a[i] * sin(th);
    }
    sl_motion m1 = {"", "", WAVE_N, WAVE_DT, a}, mx = {"", "", WAVE_N, WAVE_DT, ax},
              my = {"", "", WAVE_N, WAVE_DT, ay};
    sl_set s1 = {&m1, NULL, NULL}, s2 = {&mx, &my, NULL};
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    sl_slide_result r1, r2;
    const double mu = WAVE_MU;
    if ((st = sl_slide_run(&s1, &mu, 1, &o, &r1, err)) ||
        (st = sl_slide_run(&s2, &mu, 1, &o, &r2, err)))
        goto done;
    v->reference = r1.peak_m;
    v->computed = r2.peak_m;
    v->abs_tol = fmax(o.rtol * r1.peak_m, o.atol_m);
done:
    free(a);
    free(ax);
    free(ay);
    return st;
}

SL_VERIFY_FN(sl_verify_e06_45deg)
{
    (void)ctx;
    return along(45.0, v, err);
}

SL_VERIFY_FN(sl_verify_e07_20deg)
{
    (void)ctx;
    return along(20.0, v, err);
}

SL_VERIFY_FN(sl_verify_e08_rotation)
{
    (void)ctx;
    double *x = wave_record(WAVE_N, WAVE_DT, 3.5, 0.0), *y = wave_record(WAVE_N, WAVE_DT, 2.5, 1.3);
    double *rx = zeros(WAVE_N), *ry = zeros(WAVE_N);
    sl_status st = SL_OK;
    if (!x || !y || !rx || !ry) {
        st = nomem(err);
        goto done;
    }
    const double th = 30.0 * M_PI / 180.0, c = cos(th), s = sin(th);
    for (size_t i = 0; i < WAVE_N; i++) {
        rx[i] = c * x[i] - s * y[i];
        ry[i] = s * x[i] + c * y[i];
    }
    sl_motion mx = {"", "", WAVE_N, WAVE_DT, x}, my = {"", "", WAVE_N, WAVE_DT, y},
              mrx = {"", "", WAVE_N, WAVE_DT, rx}, mry = {"", "", WAVE_N, WAVE_DT, ry};
    sl_set s0 = {&mx, &my, NULL}, s1 = {&mrx, &mry, NULL};
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    sl_slide_result r0, r1;
    const double mu = WAVE_MU;
    if ((st = sl_slide_run(&s0, &mu, 1, &o, &r0, err)) ||
        (st = sl_slide_run(&s1, &mu, 1, &o, &r1, err)))
        goto done;
    v->reference = r0.peak_m;
    v->computed = r1.peak_m;
    v->abs_tol = 2 * fmax(o.rtol * r0.peak_m, o.atol_m);
done:
    free(x);
    free(y);
    free(rx);
    free(ry);
    return st;
}

SL_VERIFY_FN(sl_verify_e09_vertical)
{
    (void)ctx;
    v->rel_tol = 1e-10;
    return pulse_run(SL_MODEL_EXACT, -0.3 * SL_G, v, err);
}

/* a_v = -2 g at every sample: N = 0, no friction; a_h = A from t = 0.
 * Free flight u = -A t^2/2 to the record's end T, then the floor is at rest
 * (a = a_v = 0) and friction mu g stops the relative speed A T. */
SL_VERIFY_FN(sl_verify_e10_liftoff)
{
    (void)ctx;
    const double A = 1.0, dt = 0.01, mu = 0.3;
    const size_t n = 101;
    double *a = zeros(n), *av = zeros(n);
    if (!a || !av) {
        free(a);
        free(av);
        return nomem(err);
    }
    for (size_t i = 0; i < n; i++) {
        a[i] = A;
        av[i] = -2 * SL_G;
    }
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    sl_slide_result r;
    sl_status st = peak_1d(a, av, n, dt, mu, &o, &r, err);
    const double T = (double)(n - 1) * dt;
    v->reference = A * T * T / 2 + (A * T) * (A * T) / (2 * mu * SL_G);
    v->computed = r.peak_m;
    v->rel_tol = 1e-10;
    if (st == SL_OK && r.liftoff_samples != (long)n)
        st = sl_error_set(err, SL_EINVAL, NULL, 0, "lift-off samples %ld, expected %zu",
                          r.liftoff_samples, n);
    free(a);
    free(av);
    return st;
}

SL_VERIFY_FN(sl_verify_e11_threshold)
{
    (void)ctx;
    double *a = wave_record(WAVE_N, WAVE_DT, 4.0, 0.0);
    if (!a)
        return nomem(err);
    double amax = 0;
    for (size_t i = 0; i < WAVE_N; i++)
        amax = fmax(amax, fabs(a[i]));
    sl_motion m = {"", "", WAVE_N, WAVE_DT, a};
    sl_set set = {&m, NULL, NULL};
    sl_slide_opts o;
    sl_slide_opts_default(&o);
    v->computed = sl_slide_mu_threshold(&set, &o);
    v->reference = amax / SL_G;
    v->rel_tol = 1e-15;
    free(a);
    return SL_OK;
}

/* ---- the reference models ------------------------------------------------- */

SL_VERIFY_FN(sl_verify_r01_smooth)
{
    (void)ctx;
    v->rel_tol = 0.01;
    return pulse_run(SL_MODEL_SMOOTH, 0.0, v, err);
}

SL_VERIFY_FN(sl_verify_r02_plastic)
{
    (void)ctx;
    v->rel_tol = 0.01;
    return pulse_run(SL_MODEL_PLASTIC, 0.0, v, err);
}

SL_VERIFY_FN(sl_verify_r03_smooth_vertical)
{
    (void)ctx;
    v->rel_tol = 0.01;
    return pulse_run(SL_MODEL_SMOOTH, -0.3 * SL_G, v, err);
}

SL_VERIFY_FN(sl_verify_r04_plastic_vertical)
{
    (void)ctx;
    v->rel_tol = 0.01;
    return pulse_run(SL_MODEL_PLASTIC, -0.3 * SL_G, v, err);
}
