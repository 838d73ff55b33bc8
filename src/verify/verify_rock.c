/* verify_rock.c - verification problems of the rocking engine (rock/rock.h)
 * against closed forms, an impact balance and quadratures of the exact
 * equation (verify.h; the derivations in docs/verification.md, "Rocking").
 * Every input is built here; the quadratures are GSL's (QAWS, the
 * algebraic end-point weight), under the library's quiet GSL handler. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "core/gslerr.h"
#include "core/units.h"
#include "rock/rock.h"
#include "verify/verify_problems.h"

/* ---- references ------------------------------------------------------------ */

/* (K1) by hand: alpha, p. */
static void block_consts(double b, double h, double *alpha, double *p)
{
    *alpha = atan(b / h);
    *p = sqrt(3.0 * SL_G / (4.0 * sqrt(b * b + h * h)));
}

typedef struct qpar {
    double alpha, p, a;  /* a: theta0 (free rocking) or beta = A/g (constant push) */
} qpar;

/* Free rocking from theta0 at rest: theta'^2/2 = p^2 (cos(alpha - theta0) -
 * cos(alpha - theta)) = 2 p^2 sin(alpha - (theta + theta0)/2) sin((theta0 -
 * theta)/2); the quarter period int_0^theta0 dtheta / theta' with the
 * weight (theta0 - theta)^(-1/2) taken out. */
static double free_w(double th, void *vp)
{
    const qpar *q = vp;
    const double d = q->a - th;
    const double sinc = d > 0 ? sin(0.5 * d) / d : 0.5;
    return 1.0 / sqrt(4.0 * q->p * q->p * sin(q->alpha - 0.5 * (th + q->a)) * sinc);
}

/* Under a constant a_h = -beta g from rest: theta'^2/2 = 2 p^2 sin(theta/2)
 * (beta cos(alpha - theta/2) - sin(alpha - theta/2)); the time to theta1 with
 * the weight theta^(-1/2) taken out. */
static double push_w(double th, void *vp)
{
    const qpar *q = vp;
    const double m = q->alpha - 0.5 * th;
    const double s = th > 0 ? 0.5 * th / sin(0.5 * th) : 1.0;
    return sqrt(s / (2.0 * q->p * q->p * (q->a * cos(m) - sin(m))));
}

/* int_0^x f(theta) w(theta) dtheta, w = (x - theta)^(-1/2) (right) or
 * theta^(-1/2) (left). NAN when GSL fails. */
static double qaws(double (*f)(double, void *), qpar *q, double x, int right)
{
    gsl_function F = {f, q};
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_integration_qaws_table *t =
        gsl_integration_qaws_table_alloc(right ? 0.0 : -0.5, right ? -0.5 : 0.0, 0, 0);
    double v = NAN, e;
    sl_gsl_quiet_begin();
    if (!w || !t || gsl_integration_qaws(&F, 0.0, x, t, 1e-15, 1e-12, 1000, w, &v, &e))
        v = NAN;
    sl_gsl_quiet_end();
    if (t)
        gsl_integration_qaws_table_free(t);
    if (w)
        gsl_integration_workspace_free(w);
    return v;
}

/* The smallest beta = A/g of a rectangular pulse of tp that overturns the
 * block: the end state theta1 of the pulse by bisection on push time, and
 * the free rocking after it reaches alpha iff theta'^2/2 >= p^2 (1 -
 * cos(alpha - theta1)); bisection on beta. */
static double pulse_margin(double alpha, double p, double beta, double tp)
{
    qpar q = {alpha, p, beta};
    double lo = 0, hi = SL_PI / 2;
    if (qaws(push_w, &q, hi, 0) <= tp)
        return 1.0;
    for (int it = 0; it < 60 && hi - lo > 1e-14; it++) {
        const double mid = 0.5 * (lo + hi);
        if (qaws(push_w, &q, mid, 0) < tp)
            lo = mid;
        else
            hi = mid;
    }
    const double th = 0.5 * (lo + hi), m = alpha - 0.5 * th;
    const double F = 2 * p * p * sin(0.5 * th) * (beta * cos(m) - sin(m));
    return F - p * p * (1 - cos(alpha - th));
}

static double pulse_exact(double alpha, double p, double tp)
{
    double lo = tan(alpha), hi = 20 * tan(alpha);
    for (int it = 0; it < 45 && hi - lo > 1e-11 * hi; it++) {
        const double mid = 0.5 * (lo + hi);
        if (pulse_margin(alpha, p, mid, tp) > 0)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/* ---- runs -------------------------------------------------------------------- */

static sl_status nomem(sl_error *err) { return sl_error_set(err, SL_ENOMEM, NULL, 0, "out of memory"); }

/* The uplift instant of the block b = 0.2, h = 1 under a_h = -k t, k = 3
 * m/s^3 (and a constant a_v). */
static sl_status uplift_run(double av_const, sl_verify_value *v, sl_error *err)
{
    const double b = 0.2, h = 1.0, k = 3.0, dt = 0.01;
    const size_t n = 201;
    double *a = calloc(n, sizeof *a), *av = calloc(n, sizeof *av);
    if (!a || !av) {
        free(a);
        free(av);
        return nomem(err);
    }
    for (size_t i = 0; i < n; i++) {
        a[i] = -k * (double)i * dt;
        av[i] = av_const;
    }
    sl_rock_block blk = {b, h, -1};
    sl_rock_result r;
    sl_status st = sl_rock_run(&blk, a, av_const != 0 ? av : NULL, n, dt, 1, 1, NULL, &r, err);
    v->computed = r.t_uplift_s;
    v->reference = (SL_G + av_const) * (b / h) / k;
    v->rel_tol = 1e-14;
    free(a);
    free(av);
    return st;
}

SL_VERIFY_FN(sl_verify_h01_uplift)
{
    (void)ctx;
    return uplift_run(0.0, v, err);
}

SL_VERIFY_FN(sl_verify_h02_uplift_vertical)
{
    (void)ctx;
    return uplift_run(-0.3 * SL_G, v, err);
}

/* Free rocking from theta0 on a record of zeros, with the history. */
static sl_status free_run(double b, double h, double r_imp, double th0, double T, double dt,
                          sl_rock_history *hi, sl_error *err)
{
    const size_t n = (size_t)(T / dt) + 1;
    double *a = calloc(n, sizeof *a);
    if (!a)
        return nomem(err);
    sl_rock_block blk = {b, h, r_imp};
    sl_rock_opts o;
    sl_rock_opts_default(&o);
    o.theta0_rad = th0;
    sl_rock_result r;
    sl_status st = sl_rock_run_history(&blk, a, NULL, n, dt, 1, 1, &o, &r, hi, err);
    free(a);
    return st;
}

/* The k-th impact of a history (0-based), or NULL. */
static const sl_rock_event *impact_k(const sl_rock_history *hi, size_t k)
{
    for (size_t i = 0; i < hi->n_events; i++)
        if (hi->events[i].kind == SL_ROCK_EV_IMPACT && k-- == 0)
            return &hi->events[i];
    return NULL;
}

static sl_status no_impact(sl_error *err)
{
    return sl_error_set(err, SL_ENOCONV, NULL, 0, "rock: the block did not reach theta = 0");
}

/* The ratio theta'(after)/theta'(before) at the first impact of a block
 * b = 0.3, h = 1 against the angular momentum about the new corner:
 * (I_G + m (h^2 - b^2)) / I_O with I_G = m R^2/3, I_O = 4 m R^2/3. */
SL_VERIFY_FN(sl_verify_h03_restitution)
{
    (void)ctx;
    const double b = 0.3, h = 1.0, R2 = b * b + h * h;
    sl_rock_history hi;
    sl_status st = free_run(b, h, -1, 0.1, 3.0, 0.005, &hi, err);
    if (st)
        return st;
    const sl_rock_event *e = impact_k(&hi, 0);
    v->reference = (R2 / 3 + h * h - b * b) / (4 * R2 / 3);
    v->computed = e ? e->omega_rad_s / e->omega_before_rad_s : NAN;
    v->rel_tol = 1e-14;
    sl_rock_history_free(&hi);
    return e ? SL_OK : no_impact(err);
}

/* The first impact of a slender block (b/h = 0.01) released at rest from
 * alpha/2: the linearised quarter period (1/p) arccosh(1/(1 - theta0/alpha)). */
SL_VERIFY_FN(sl_verify_h04_period_linear)
{
    (void)ctx;
    const double b = 0.01, h = 1.0;
    double alpha, p;
    block_consts(b, h, &alpha, &p);
    sl_rock_history hi;
    sl_status st = free_run(b, h, 1.0, 0.5 * alpha, 2.0, 0.002, &hi, err);
    if (st)
        return st;
    const sl_rock_event *e = impact_k(&hi, 0);
    v->reference = acosh(2.0) / p;
    v->computed = e ? e->t_s : NAN;
    v->rel_tol = 2 * alpha * alpha;
    sl_rock_history_free(&hi);
    return e ? SL_OK : no_impact(err);
}

/* The period of the exact equation, b = 0.3, h = 1, from 0.6 alpha, r = 1:
 * four quarter periods by quadrature against the time between the first and
 * the third impact. */
SL_VERIFY_FN(sl_verify_h05_period_exact)
{
    (void)ctx;
    const double b = 0.3, h = 1.0;
    double alpha, p;
    block_consts(b, h, &alpha, &p);
    qpar q = {alpha, p, 0.6 * alpha};
    const double tq = qaws(free_w, &q, q.a, 1);
    sl_rock_history hi;
    sl_status st = free_run(b, h, 1.0, q.a, 6 * tq, 0.005, &hi, err);
    if (st)
        return st;
    const sl_rock_event *e1 = impact_k(&hi, 0), *e3 = impact_k(&hi, 2);
    v->reference = 4 * tq;
    v->computed = e1 && e3 ? e3->t_s - e1->t_s : NAN;
    v->rel_tol = 1e-8;
    sl_rock_history_free(&hi);
    return e1 && e3 ? SL_OK : no_impact(err);
}

/* r = 1: the energy of the release kept; the impact speed after 20 cycles,
 * p sqrt(2 (cos(alpha - theta0) - cos(alpha))). */
SL_VERIFY_FN(sl_verify_h06_energy)
{
    (void)ctx;
    const double b = 0.25, h = 0.8, dt = 0.01;
    double alpha, p;
    block_consts(b, h, &alpha, &p);
    const double th0 = 0.7 * alpha;
    qpar q = {alpha, p, th0};
    const double tq = qaws(free_w, &q, th0, 1);
    sl_rock_history hi;
    sl_status st = free_run(b, h, 1.0, th0, 82 * tq, dt, &hi, err);
    if (st)
        return st;
    const sl_rock_event *e = impact_k(&hi, 40);
    v->reference = p * sqrt(2 * (cos(alpha - th0) - cos(alpha)));
    v->computed = e ? fabs(e->omega_before_rad_s) : NAN;
    v->rel_tol = 1e-8;
    sl_rock_history_free(&hi);
    return e ? SL_OK : no_impact(err);
}

/* The engine's overturning threshold beta = A/g of a rectangular pulse of
 * m + 1 samples of -A at dt then zeros (t_p = (m + 1/2) dt to O(dt^2)):
 * bisection on the overturned flag. */
static sl_status pulse_engine(double b, double h, double dt, size_t m, double *beta,
                              sl_error *err)
{
    const size_t n = m + 3;
    double *a = calloc(n, sizeof *a);
    if (!a)
        return nomem(err);
    sl_rock_block blk = {b, h, -1};
    double lo = b / h * SL_G, hi = 20 * b / h * SL_G;
    sl_status st = SL_OK;
    for (int it = 0; it < 60 && hi - lo > 1e-11 * hi && !st; it++) {
        const double A = 0.5 * (lo + hi);
        for (size_t i = 0; i <= m; i++)
            a[i] = -A;
        sl_rock_result r;
        if ((st = sl_rock_run(&blk, a, NULL, n, dt, 1, 1, NULL, &r, err)))
            break;
        if (r.overturned)
            hi = A;
        else
            lo = A;
    }
    *beta = 0.5 * (lo + hi) / SL_G;
    free(a);
    return st;
}

/* A slender block (b/h = 0.01) and a pulse of 0.2 s: the linearised block's
 * closed form A_min = g alpha / (1 - exp(-p t_p)) (docs/verification.md). */
SL_VERIFY_FN(sl_verify_h07_pulse_linear)
{
    (void)ctx;
    const double b = 0.01, h = 1.0, dt = 2e-4;
    const size_t m = 999;
    double alpha, p;
    block_consts(b, h, &alpha, &p);
    const double tp = ((double)m + 0.5) * dt;
    v->reference = alpha / (1 - exp(-p * tp));
    v->rel_tol = 2 * alpha * alpha;
    return pulse_engine(b, h, dt, m, &v->computed, err);
}

/* b/h = 0.2 and a pulse of 0.2 s: the exact block's threshold by quadrature. */
SL_VERIFY_FN(sl_verify_h08_pulse_exact)
{
    (void)ctx;
    const double b = 0.2, h = 1.0, dt = 2e-4;
    const size_t m = 999;
    double alpha, p;
    block_consts(b, h, &alpha, &p);
    v->reference = pulse_exact(alpha, p, ((double)m + 0.5) * dt);
    v->rel_tol = 1e-6;
    return pulse_engine(b, h, dt, m, &v->computed, err);
}
