/*
 * test_rock.c - the rocking engine (rock/rock.h) against references that do
 * not come from it: Housner's uplift threshold, the restitution from the
 * angular momentum about the new corner, the free-rocking period (the
 * linearised closed form and a GSL quadrature of the exact equation),
 * energy with r = 1, the rectangular-pulse overturning threshold (closed
 * form of the linearised block, quadrature of the exact one), convergence,
 * invariance and hard cases (docs/model.md, "Rocking"; docs/hard-cases.md).
 * Every input is built here.
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "harness.h"
#include "rock/rock.h"
#include "core/units.h"

static const double g = SL_G;

static double *zeros(size_t n) { return calloc(n, sizeof(double)); }

static sl_rock_opts opts(void)
{
    sl_rock_opts o;
    sl_rock_opts_default(&o);
    return o;
}

/* The block's own constants, computed here from (K1). */
typedef struct blk_c {
    double alpha, R, p;
} blk_c;

static blk_c consts(double b, double h)
{
    blk_c c;
    c.alpha = atan(b / h);
    c.R = sqrt(b * b + h * h);
    c.p = sqrt(3.0 * g / (4.0 * c.R)); /* I_O = (4/3) m R^2: p^2 = m g R / I_O */
    return c;
}

/* The n-th event of a kind in a history, or NULL. */
static const sl_rock_event *event_n(const sl_rock_history *h, sl_rock_event_kind k, size_t nth)
{
    for (size_t i = 0; i < h->n_events; i++)
        if (h->events[i].kind == k && nth-- == 0)
            return &h->events[i];
    return NULL;
}

/* ---- free rocking ------------------------------------------------------- */

/* Quarter period of the exact equation from theta0 at rest (no forcing):
 * energy theta'^2/2 = p^2 (cos(alpha - theta0) - cos(alpha - theta)), and
 * cos(alpha - theta0) - cos(alpha - theta) = 2 sin(alpha - (theta + theta0)/2)
 * sin((theta0 - theta)/2), so t = int_0^theta0 w(theta) (theta0 - theta)^(-1/2)
 * dtheta with a smooth w: GSL's QAWS with the algebraic weight. */
typedef struct qpar {
    double alpha, p, th0;
} qpar;

static double quarter_w(double th, void *vp)
{
    const qpar *q = vp;
    const double d = q->th0 - th;
    const double sinc = d == 0 ? 0.5 : sin(0.5 * d) / d;
    return 1.0 / sqrt(4.0 * q->p * q->p * sin(q->alpha - 0.5 * (th + q->th0)) * sinc);
}

static double quarter_exact(double alpha, double p, double th0)
{
    qpar q = {alpha, p, th0};
    gsl_function F = {quarter_w, &q};
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    gsl_integration_qaws_table *t = gsl_integration_qaws_table_alloc(0.0, -0.5, 0, 0);
    double v = NAN, e;
    gsl_error_handler_t *was = gsl_set_error_handler_off();
    if (gsl_integration_qaws(&F, 0.0, th0, t, 1e-15, 1e-13, 200, w, &v, &e))
        v = NAN;
    gsl_set_error_handler(was);
    gsl_integration_qaws_table_free(t);
    gsl_integration_workspace_free(w);
    return v;
}

/* Free rocking from theta0 at rest, r = 1, on a record of zeros: run with
 * the history; the impacts come at t_q, 3 t_q, 5 t_q, ... */
static int free_run(double b, double h, double th0, double T, double dt, double rtol,
                    sl_rock_result *r, sl_rock_history *hi)
{
    size_t n = (size_t)(T / dt) + 1;
    double *a = zeros(n);
    sl_rock_block blk = {b, h, 1.0};
    sl_rock_opts o = opts();
    o.theta0_rad = th0;
    o.rtol = rtol;
    int st = sl_rock_run_history(&blk, a, NULL, n, dt, 1, 1, &o, r, hi, NULL);
    free(a);
    return st;
}

static void test_free_period_exact(void)
{
    const double b = 0.3, h = 1.0;
    blk_c c = consts(b, h);
    const double fr[] = {0.2, 0.6, 0.95};
    for (int k = 0; k < 3; k++) {
        const double th0 = fr[k] * c.alpha, tq = quarter_exact(c.alpha, c.p, th0);
        sl_rock_result r;
        sl_rock_history hi;
        CHECK(free_run(b, h, th0, 8 * tq + 0.1, 0.005, SL_ROCK_DEFAULT_RTOL, &r, &hi) == SL_OK,
              "run");
        const sl_rock_event *i1 = event_n(&hi, SL_ROCK_EV_IMPACT, 0);
        const sl_rock_event *i3 = event_n(&hi, SL_ROCK_EV_IMPACT, 2);
        CHECK(i1 && i3, "impacts %zu", r.impacts);
        if (i1 && i3) {
            CHECK_CLOSE(i1->t_s, tq, 0, 1e-8);
            CHECK_CLOSE(i3->t_s - i1->t_s, 4 * tq, 0, 1e-8); /* the period */
        }
        CHECK_CLOSE(r.p_rad_s, c.p, 0, 1e-15);
        CHECK_CLOSE(r.alpha_rad, c.alpha, 0, 1e-15);
        sl_rock_history_free(&hi);
    }
}

/* A slender block (alpha 0.01): the linearised theta'' = p^2 (theta - alpha)
 * gives the quarter period (1/p) arccosh(1/(1 - theta0/alpha)); the exact
 * equation differs by O(alpha^2), and the difference shrinks 4 x when
 * alpha halves. */
static void test_free_period_linear(void)
{
    double err[2];
    for (int k = 0; k < 2; k++) {
        const double b = k ? 0.005 : 0.01, h = 1.0;
        blk_c c = consts(b, h);
        const double th0 = 0.5 * c.alpha;
        const double tq_lin = acosh(1.0 / (1.0 - th0 / c.alpha)) / c.p;
        sl_rock_result r;
        sl_rock_history hi;
        CHECK(free_run(b, h, th0, 3 * tq_lin, 0.002, SL_ROCK_DEFAULT_RTOL, &r, &hi) == SL_OK,
              "run");
        const sl_rock_event *i1 = event_n(&hi, SL_ROCK_EV_IMPACT, 0);
        CHECK(i1 != NULL, "no impact");
        err[k] = i1 ? i1->t_s / tq_lin - 1 : NAN;
        CHECK(fabs(err[k]) < c.alpha * c.alpha, "linearised %.3g off, alpha^2 %.3g", err[k],
              c.alpha * c.alpha);
        sl_rock_history_free(&hi);
    }
    CHECK_CLOSE(err[0] / err[1], 4.0, 0, 0.01);
}

/* r = 1, no forcing: the energy E = theta'^2/2 + p^2 cos(alpha - |theta|) of
 * the release is kept at every impact (|theta'| = p sqrt(2 (cos(alpha -
 * theta0) - cos alpha))) and every peak (|theta| = theta0), over 30 cycles. */
static void test_energy_r1(void)
{
    const double b = 0.25, h = 0.8;
    blk_c c = consts(b, h);
    const double th0 = 0.7 * c.alpha, tq = quarter_exact(c.alpha, c.p, th0);
    const double w_imp = c.p * sqrt(2 * (cos(c.alpha - th0) - cos(c.alpha)));
    sl_rock_result r;
    sl_rock_history hi;
    CHECK(free_run(b, h, th0, 120 * tq, 0.01, SL_ROCK_DEFAULT_RTOL, &r, &hi) == SL_OK, "run");
    CHECK(r.impacts >= 59, "impacts %zu", r.impacts);
    double worst_w = 0, worst_th = 0;
    for (size_t i = 0; i < hi.n_events; i++) {
        const sl_rock_event *e = &hi.events[i];
        if (e->kind == SL_ROCK_EV_IMPACT) {
            worst_w = fmax(worst_w, fabs(fabs(e->omega_before_rad_s) / w_imp - 1));
            worst_w = fmax(worst_w, fabs(fabs(e->omega_rad_s) / w_imp - 1));
        } else if (e->kind == SL_ROCK_EV_PEAK) {
            worst_th = fmax(worst_th, fabs(fabs(e->theta_rad) / th0 - 1));
        }
    }
    CHECK(worst_w < 1e-8, "impact speed off by %.3g", worst_w);
    CHECK(worst_th < 1e-8, "peak off by %.3g", worst_th);
    CHECK(!r.tipped && r.uplifts == 0, "tipped %d uplifts %zu", r.tipped, r.uplifts);
    sl_rock_history_free(&hi);
}

/* ---- the restitution --------------------------------------------------- */

/* Angular momentum about the new corner O' just before the impact, for a
 * block rocking about O = (b, 0) at omega (CG at (0, h), velocity
 * omega x (G - O)): H = I_G omega + m (G - O') x v_G, I_G = m (b^2 + h^2)/3;
 * after: I_O omega', I_O = I_G + m R^2 = (4/3) m R^2. */
static double restitution_by_momentum(double b, double h)
{
    const double m = 1.0, w = 1.0, IG = m * (b * b + h * h) / 3.0;
    const double Gx = 0, Gy = h, Ox = b, Oy = 0, Px = -b, Py = 0; /* O' = P */
    /* v_G = w k x (G - O) = w (-(Gy - Oy), Gx - Ox) */
    const double vx = -w * (Gy - Oy), vy = w * (Gx - Ox);
    const double H = IG * w + m * ((Gx - Px) * vy - (Gy - Py) * vx);
    const double IO = IG + m * (b * b + h * h);
    return H / (IO * w);
}

static void test_restitution(void)
{
    const double bs[] = {0.1, 0.3, 0.5}, hs[] = {1.0, 1.2, 0.7};
    for (int k = 0; k < 3; k++) {
        const double rr = restitution_by_momentum(bs[k], hs[k]);
        CHECK_CLOSE(sl_rock_housner_r(bs[k], hs[k]), rr, 1e-15, 1e-14);
        /* the engine applies it once per impact: free rocking, Housner's r */
        blk_c c = consts(bs[k], hs[k]);
        const size_t n = 2001;
        double *a = zeros(n);
        sl_rock_block blk = {bs[k], hs[k], -1};
        sl_rock_opts o = opts();
        o.theta0_rad = 0.8 * c.alpha;
        sl_rock_result r;
        sl_rock_history hi;
        CHECK(sl_rock_run_history(&blk, a, NULL, n, 0.005, 1, 1, &o, &r, &hi, NULL) == SL_OK,
              "run");
        CHECK_CLOSE(r.restitution, rr, 1e-15, 1e-14);
        const sl_rock_event *e = event_n(&hi, SL_ROCK_EV_IMPACT, 0);
        CHECK(e != NULL, "no impact");
        if (e)
            CHECK_CLOSE(e->omega_rad_s / e->omega_before_rad_s, rr, 0, 1e-14);
        /* and the first impact's speed from the energy of the release */
        if (e)
            CHECK_CLOSE(fabs(e->omega_before_rad_s),
                        c.p * sqrt(2 * (cos(c.alpha - o.theta0_rad) - cos(c.alpha))), 0, 1e-8);
        free(a);
        sl_rock_history_free(&hi);
    }
    /* a user's r is applied as given, once */
    const size_t n = 1001;
    double *a = zeros(n);
    sl_rock_block blk = {0.2, 1.0, 0.5};
    sl_rock_opts o = opts();
    o.theta0_rad = 0.1;
    sl_rock_result r;
    sl_rock_history hi;
    CHECK(sl_rock_run_history(&blk, a, NULL, n, 0.005, 1, 1, &o, &r, &hi, NULL) == SL_OK, "run");
    const sl_rock_event *e = event_n(&hi, SL_ROCK_EV_IMPACT, 0);
    CHECK(e && fabs(e->omega_rad_s / e->omega_before_rad_s - 0.5) < 1e-15, "r = 0.5");
    free(a);
    sl_rock_history_free(&hi);
}

/* ---- uplift: Housner's threshold (K3) ------------------------------------ */

static void test_uplift_threshold(void)
{
    const double b = 0.2, h = 1.0, ta = b / h;
    const size_t n = 401;
    const double dt = 0.01;
    double *a = zeros(n), *v = zeros(n);
    sl_rock_block blk = {b, h, -1};
    sl_rock_opts o = opts();
    sl_rock_result r;
    /* constant a_h just below and just above g tan(alpha) */
    for (size_t i = 0; i < n; i++)
        a[i] = g * ta * (1 - 1e-12);
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(!r.uplifted && r.peak_theta_rad == 0 && r.steps == 0, "below: uplifted %d", r.uplifted);
    for (int sg = -1; sg <= 1; sg += 2) {
        for (size_t i = 0; i < n; i++)
            a[i] = sg * g * ta; /* exactly at the threshold, either way: (K3) is strict */
        CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
        CHECK(!r.uplifted, "at the threshold (%+d): uplifted", sg);
        /* and a ramp that touches it at one sample and falls back */
        for (size_t i = 0; i < n; i++)
            a[i] = sg * g * ta * (1.0 - fabs((double)i - 200.0) / 200.0);
        CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
        CHECK(!r.uplifted, "touching the threshold (%+d): uplifted", sg);
    }
    for (size_t i = 0; i < n; i++)
        a[i] = -g * ta * (1 + 1e-9);
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(r.uplifted && r.t_uplift_s == 0, "above: uplifted %d at %g", r.uplifted, r.t_uplift_s);
    /* a ramp a_h = -k t: the uplift instant g tan(alpha) / k, exactly */
    const double k = 3.0;
    for (size_t i = 0; i < n; i++)
        a[i] = -k * (double)i * dt;
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK_CLOSE(r.t_uplift_s, g * ta / k, 0, 1e-14);
    CHECK(r.uplifted && r.uplifts == 1, "uplifts %zu", r.uplifts);
    /* a_h < 0 rocks the block to theta > 0 */
    sl_rock_history hi;
    CHECK(sl_rock_run_history(&blk, a, NULL, 200, dt, 1, 1, &o, &r, &hi, NULL) == SL_OK, "run");
    CHECK(hi.theta_rad[199] > 0, "theta %g", hi.theta_rad[199]);
    sl_rock_history_free(&hi);
    /* with a vertical: constant a_v = c gives (g + c) tan(alpha) / k */
    const double cv[] = {-0.4 * g, 0.3 * g};
    for (int q = 0; q < 2; q++) {
        for (size_t i = 0; i < n; i++)
            v[i] = cv[q];
        CHECK(sl_rock_run(&blk, a, v, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
        CHECK_CLOSE(r.t_uplift_s, (g + cv[q]) * ta / k, 0, 1e-14);
    }
    /* a vertical ramp a_v = -c t against a constant a_h = A: (g - c t) tan(alpha) = A */
    const double A = 0.5 * g * ta, cr = 2.0;
    for (size_t i = 0; i < n; i++) {
        a[i] = A;
        v[i] = -cr * (double)i * dt;
    }
    CHECK(sl_rock_run(&blk, a, v, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK_CLOSE(r.t_uplift_s, (g - A / ta) / cr, 0, 1e-14);
    /* scale_h and scale_v act as the scaled samples */
    for (size_t i = 0; i < n; i++) {
        a[i] = -k * (double)i * dt;
        v[i] = 0.1 * g;
    }
    CHECK(sl_rock_run(&blk, a, v, n, dt, 0.5, 2.0, &o, &r, NULL) == SL_OK, "run");
    CHECK_CLOSE(r.t_uplift_s, (g + 0.2 * g) * ta / (0.5 * k), 0, 1e-14);
    free(a);
    free(v);
}

/* ---- constant forcing and the rectangular pulse ------------------------- */

/* Under a constant a_h = -beta g (no vertical) the block leaves rest at
 * t = 0 and, integrating (K2) once, theta'^2/2 = F(theta) with
 * F = p^2 [cos(alpha) - cos(alpha - theta) + beta (sin(alpha) - sin(alpha - theta))];
 * the time to reach theta1 is int_0^theta1 dtheta / sqrt(2 F), F ~ theta near 0:
 * QAWS with the weight theta^(-1/2). */
typedef struct fpar {
    double alpha, p, beta;
} fpar;

/* F without cancellation: cos(alpha) - cos(alpha - th) = -2 sin(alpha - th/2) sin(th/2),
 * sin(alpha) - sin(alpha - th) = 2 cos(alpha - th/2) sin(th/2). */
static double F_const(const fpar *f, double th)
{
    const double m = f->alpha - 0.5 * th;
    return 2 * f->p * f->p * sin(0.5 * th) * (f->beta * cos(m) - sin(m));
}

static double time_w(double th, void *vp)
{
    const fpar *f = vp;
    const double m = f->alpha - 0.5 * th;
    const double q = th > 0 ? 0.5 * th / sin(0.5 * th) : 1.0; /* (th/2) / sin(th/2) */
    return sqrt(q / (2 * f->p * f->p * (f->beta * cos(m) - sin(m))));
}

static double time_to(double alpha, double p, double beta, double th1)
{
    fpar f = {alpha, p, beta};
    gsl_function F = {time_w, &f};
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_integration_qaws_table *t = gsl_integration_qaws_table_alloc(-0.5, 0.0, 0, 0);
    double v = NAN, e;
    gsl_error_handler_t *was = gsl_set_error_handler_off();
    if (gsl_integration_qaws(&F, 0.0, th1, t, 1e-15, 1e-12, 1000, w, &v, &e))
        v = NAN;
    gsl_set_error_handler(was);
    gsl_integration_qaws_table_free(t);
    gsl_integration_workspace_free(w);
    return v;
}

/* A constant a_h of 2 g tan(alpha) from t = 0: tipping at t(alpha), the
 * overturn at t(pi/2), located to the integrator's accuracy (the sampled
 * record is constant, so piecewise linear is exact). */
static void test_constant_push_times(void)
{
    const double b = 0.25, h = 1.0, beta = 2 * b / h;
    blk_c c = consts(b, h);
    const double dt = 0.01;
    const size_t n = 501;
    double *a = zeros(n);
    for (size_t i = 0; i < n; i++)
        a[i] = -beta * g;
    sl_rock_block blk = {b, h, -1};
    sl_rock_opts o = opts();
    sl_rock_result r;
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(r.tipped && r.overturned && r.impacts == 0, "tipped %d overturned %d", r.tipped,
          r.overturned);
    CHECK_CLOSE(r.t_tip_s, time_to(c.alpha, c.p, beta, c.alpha), 0, 1e-8);
    CHECK_CLOSE(r.t_overturn_s, time_to(c.alpha, c.p, beta, SL_PI / 2), 0, 1e-8);
    CHECK(r.peak_theta_rad == SL_PI / 2 && r.excursion_m == 2 * h, "peak %g excursion %g",
          r.peak_theta_rad, r.excursion_m);
    /* tighter steps move the instants by less than the promise's share */
    o.rtol = 1e-10;
    sl_rock_result r2;
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r2, NULL) == SL_OK, "run");
    CHECK_CLOSE(r2.t_overturn_s, time_to(c.alpha, c.p, beta, SL_PI / 2), 0, 1e-11);
    free(a);
}

/* The pulse's end state (theta1 at t_p under beta) by bisection on
 * time_to, then the free rocking's energy decides: the block overturns
 * when F(theta1) >= p^2 (1 - cos(alpha - theta1)) (enough to reach alpha).
 * Returns that margin (> 0: overturns). */
static double pulse_margin(double alpha, double p, double beta, double tp)
{
    double lo = 0, hi = SL_PI / 2;
    if (time_to(alpha, p, beta, hi) <= tp)
        return 1.0; /* lying on its side before the pulse ends */
    for (int it = 0; it < 200 && hi - lo > 1e-15; it++) {
        const double mid = 0.5 * (lo + hi);
        if (time_to(alpha, p, beta, mid) < tp)
            lo = mid;
        else
            hi = mid;
    }
    const double th1 = 0.5 * (lo + hi);
    fpar f = {alpha, p, beta};
    return F_const(&f, th1) - p * p * (1 - cos(alpha - th1));
}

/* The smallest beta = A/g of a rectangular pulse of duration tp that
 * overturns the exact block (bisection on pulse_margin). */
static double pulse_threshold_exact(double alpha, double p, double tp)
{
    double lo = tan(alpha), hi = 20 * tan(alpha);
    for (int it = 0; it < 100 && hi - lo > 1e-13 * hi; it++) {
        const double mid = 0.5 * (lo + hi);
        if (pulse_margin(alpha, p, mid, tp) > 0)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/* The engine's threshold: bisection on its overturned flag for a sampled
 * pulse of m + 1 samples of -A, then zeros (the last interval ramps A -> 0:
 * a pulse of tp = (m + 1/2) dt to O(dt^2)). */
static double pulse_threshold_engine(double b, double h, double dt, size_t m)
{
    const size_t n = m + 3;
    double *a = zeros(n);
    sl_rock_block blk = {b, h, -1};
    sl_rock_opts o = opts();
    double lo = b / h * g, hi = 20 * b / h * g;
    for (int it = 0; it < 100 && hi - lo > 1e-12 * hi; it++) {
        const double A = 0.5 * (lo + hi);
        for (size_t i = 0; i <= m; i++)
            a[i] = -A;
        sl_rock_result r;
        if (sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) != SL_OK) {
            lo = hi = NAN;
            break;
        }
        if (r.overturned)
            hi = A;
        else
            lo = A;
    }
    free(a);
    return 0.5 * (lo + hi) / g;
}

/* Overturning under a rectangular pulse. For the linearised block (theta'' =
 * p^2 (theta - alpha + beta alpha') with beta' = A/(g alpha)), theta/alpha =
 * (beta' - 1)(cosh(p t) - 1) during the pulse, and the free rocking after it
 * reaches alpha when theta'/p >= alpha - theta at its end, which gives
 *     A_min = g alpha / (1 - exp(-p t_p))                               (derived here)
 * (an impulse A t_p >= g alpha / p for short pulses; A -> g alpha for long
 * ones). The exact block's threshold comes from the quadrature above. */
static void test_pulse_overturn(void)
{
    /* the exact block: engine against the quadrature */
    const double b = 0.2, h = 1.0, dt = 2e-4;
    blk_c c = consts(b, h);
    const size_t ms[] = {999, 2499}; /* t_p = 0.2, 0.5 s */
    for (int k = 0; k < 2; k++) {
        const double tp = ((double)ms[k] + 0.5) * dt;
        const double be = pulse_threshold_engine(b, h, dt, ms[k]);
        const double bx = pulse_threshold_exact(c.alpha, c.p, tp);
        CHECK_CLOSE(be, bx, 0, 1e-6);
        CHECK(be > tan(c.alpha), "threshold %g below uplift", be);
    }
    /* a slender block: the linearised closed form, within O(alpha^2) */
    const double bs = 0.01, hs = 1.0;
    blk_c cs = consts(bs, hs);
    const double tp = (999 + 0.5) * dt;
    const double be = pulse_threshold_engine(bs, hs, dt, 999);
    const double bl = cs.alpha / (1 - exp(-cs.p * tp));
    CHECK_CLOSE(be, bl, 0, 2 * cs.alpha * cs.alpha);
    CHECK_CLOSE(be, pulse_threshold_exact(cs.alpha, cs.p, tp), 0, 1e-6);
}

/* ---- the rest rule ------------------------------------------------------- */

/* Free rocking with r < 1 from theta0: the impact speeds fall as r^k w0
 * (energy is kept between impacts), so the cascade ends at the first
 * impact k whose rebound reaches below rest_fraction alpha, i.e.
 * (r^k w0)^2 < 2 p^2 sin(alpha) rest_fraction alpha: exactly k impacts,
 * one rest, no step-size collapse (a few steps per impact), and at rest
 * from there on. */
static void test_rest_rule(void)
{
    const double b = 0.3, h = 1.0;
    blk_c c = consts(b, h);
    const double r = sl_rock_housner_r(b, h);
    const double fr[] = {SL_ROCK_REST_FRACTION, 1e-3};
    for (int q = 0; q < 2; q++) {
        const double th0 = 0.5 * c.alpha;
        const double w0 = c.p * sqrt(2 * (cos(c.alpha - th0) - cos(c.alpha)));
        size_t K = 1;
        while (pow(r, (double)K) * w0 * pow(r, (double)K) * w0 >=
               2 * c.p * c.p * sin(c.alpha) * fr[q] * c.alpha)
            K++;
        const size_t n = 8001;
        double *a = zeros(n);
        sl_rock_block blk = {b, h, -1};
        sl_rock_opts o = opts();
        o.theta0_rad = th0;
        o.rest_fraction = fr[q];
        sl_rock_result res;
        sl_rock_history hi;
        CHECK(sl_rock_run_history(&blk, a, NULL, n, 0.005, 1, 1, &o, &res, &hi, NULL) == SL_OK,
              "run");
        CHECK(res.impacts == K, "impacts %zu, expected %zu", res.impacts, K);
        CHECK(res.rests == 1, "rests %zu", res.rests);
        CHECK(res.steps < 12 * K + n / 4, "steps %zu for %zu impacts", res.steps, K);
        const sl_rock_event *e = event_n(&hi, SL_ROCK_EV_REST, 0);
        const sl_rock_event *last = event_n(&hi, SL_ROCK_EV_IMPACT, K - 1);
        CHECK(e && last && e->t_s == last->t_s, "rest at the last impact");
        /* at rest after it: the history is zero there */
        size_t i0 = e ? (size_t)(e->t_s / 0.005) + 1 : n;
        int zero = 1;
        for (size_t i = i0; i < n; i++)
            zero &= hi.theta_rad[i] == 0 && hi.omega_rad_s[i] == 0;
        CHECK(zero && i0 < n, "not at rest after the cascade");
        /* the impact speeds fall as r^k w0 */
        const sl_rock_event *ek = event_n(&hi, SL_ROCK_EV_IMPACT, K / 2);
        if (ek)
            CHECK_CLOSE(fabs(ek->omega_before_rad_s), pow(r, (double)(K / 2)) * w0, 0, 1e-6);
        free(a);
        sl_rock_history_free(&hi);
    }
    /* r = 0: the first impact ends the rocking */
    const size_t n = 1001;
    double *a = zeros(n);
    sl_rock_block blk = {b, h, 0.0};
    sl_rock_opts o = opts();
    o.theta0_rad = 0.3 * c.alpha;
    sl_rock_result res;
    CHECK(sl_rock_run(&blk, a, NULL, n, 0.005, 1, 1, &o, &res, NULL) == SL_OK, "run");
    CHECK(res.impacts == 1 && res.rests == 1 && res.t_end_s == (double)(n - 1) * 0.005,
          "r = 0: impacts %zu rests %zu", res.impacts, res.rests);
    free(a);
}

/* ---- invariance and convergence ----------------------------------------- */

/* A pulse-like floor motion: one sine of period T and amplitude A from t0,
 * then a smaller decaying tail, sampled at dt (n samples). */
static double *pulse_motion(double A, double T, double dt, size_t n)
{
    double *a = zeros(n);
    for (size_t i = 0; a && i < n; i++) {
        const double t = (double)i * dt - 0.5;
        if (t > 0 && t < T)
            a[i] = A * sin(2 * SL_PI * t / T);
        else if (t >= T)
            a[i] = 0.3 * A * exp(-(t - T)) * sin(2 * SL_PI * (t - T) / (0.37 * T));
    }
    return a;
}

/* 1 when the run of the reference is insensitive (non-chaotic): inputs
 * scaled by 1 +- 1e-6 and 1 +- 1e-5 move the peak by less than 1e-4 and keep
 * the flags. */
static int non_chaotic(const sl_rock_block *blk, const double *a, size_t n, double dt)
{
    sl_rock_opts o = opts();
    o.rtol = 1e-10;
    sl_rock_result r0, r;
    if (sl_rock_run(blk, a, NULL, n, dt, 1, 1, &o, &r0, NULL))
        return 0;
    const double d[] = {1e-6, -1e-6, 1e-5, -1e-5};
    for (int k = 0; k < 4; k++) {
        if (sl_rock_run(blk, a, NULL, n, dt, 1 + d[k], 1, &o, &r, NULL))
            return 0;
        if (r.tipped != r0.tipped || r.overturned != r0.overturned ||
            !(fabs(r.peak_theta_rad - r0.peak_theta_rad) <= 1e-4 * r0.peak_theta_rad))
            return 0;
    }
    return 1;
}

/* The promise: every non-chaotic case's peak within 0.1 % of a converged
 * reference (rtol 1e-10), and rtol halved gives the same peak within it;
 * over blocks from 0.05 m to 2 m tall and pulses that rock, tip and
 * overturn. */
static void test_convergence(void)
{
    const double dt = 0.01;
    const size_t n = 1201;
    const double hs[] = {0.05, 0.2, 0.5, 1.0, 2.0}, kap[] = {1.3, 2.0, 3.5};
    int cases = 0, checked = 0;
    for (int i = 0; i < 5; i++)
        for (int k = 0; k < 3; k++) {
            const double h = hs[i], b = 0.2 * h;
            sl_rock_block blk = {b, h, -1};
            double *a = pulse_motion(kap[k] * g * b / h, 0.6, dt, n);
            cases++;
            if (!non_chaotic(&blk, a, n, dt)) {
                free(a);
                continue;
            }
            checked++;
            sl_rock_opts o = opts(), oh = opts(), oref = opts();
            oh.rtol = o.rtol / 2;
            oref.rtol = 1e-10;
            sl_rock_result r, rh, rr;
            CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
            CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &oh, &rh, NULL) == SL_OK, "run");
            CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &oref, &rr, NULL) == SL_OK, "run");
            CHECK_CLOSE(r.peak_theta_rad, rr.peak_theta_rad, 0, 1e-3);
            CHECK_CLOSE(rh.peak_theta_rad, r.peak_theta_rad, 0, 1e-3);
            CHECK(r.tipped == rr.tipped && r.overturned == rr.overturned, "h %g k %g flags", h,
                  kap[k]);
            free(a);
        }
    CHECK(checked >= cases / 2, "only %d of %d cases non-chaotic", checked, cases);
}

/* a_h -> -a_h is the mirror image: theta -> -theta at every sample, the same
 * peak and events; an orientation of 180 degrees is -H1 (sl_rock_project),
 * so the same peak as 0 degrees. */
static void test_mirror(void)
{
    const double dt = 0.005;
    const size_t n = 2401;
    double *a = pulse_motion(0.3 * g, 0.5, dt, n), *m = zeros(n), *z = zeros(n);
    sl_rock_block blk = {0.2, 1.0, -1};
    sl_rock_opts o = opts();
    sl_rock_result r1, r2, r3;
    sl_rock_history h1, h2;
    CHECK(sl_rock_run_history(&blk, a, NULL, n, dt, 1, 1, &o, &r1, &h1, NULL) == SL_OK, "run");
    CHECK(sl_rock_run_history(&blk, a, NULL, n, dt, -1, 1, &o, &r2, &h2, NULL) == SL_OK, "run");
    CHECK(r1.uplifted && r1.impacts > 2, "the case should rock: impacts %zu", r1.impacts);
    /* the top corner passes the footprint by 2 h sin(peak) */
    CHECK_CLOSE(r1.excursion_m, 2 * blk.h_m * sin(r1.peak_theta_rad), 0, 1e-15);
    CHECK_CLOSE(r1.peak_theta_over_alpha, r1.peak_theta_rad / atan(blk.b_m / blk.h_m), 0, 1e-15);
    CHECK(r1.peak_theta_rad == r2.peak_theta_rad && r1.impacts == r2.impacts &&
              r1.t_peak_s == r2.t_peak_s,
          "mirror: peak %.17g vs %.17g", r1.peak_theta_rad, r2.peak_theta_rad);
    int same = h1.n == h2.n;
    for (size_t i = 0; same && i < h1.n; i++)
        same = h1.theta_rad[i] == -h2.theta_rad[i] && h1.omega_rad_s[i] == -h2.omega_rad_s[i];
    CHECK(same, "mirror history");
    sl_rock_project(a, z, n, 180.0, m);
    CHECK(sl_rock_run(&blk, m, NULL, n, dt, 1, 1, &o, &r3, NULL) == SL_OK, "run");
    CHECK(r3.peak_theta_rad == r1.peak_theta_rad, "180 deg: %.17g vs %.17g", r3.peak_theta_rad,
          r1.peak_theta_rad);
    /* the projection: 30 degrees is cos 30 H1 + sin 30 H2 */
    sl_rock_project(a, a, n, 30.0, m);
    CHECK_CLOSE(m[700], (cos(SL_PI / 6) + sin(SL_PI / 6)) * a[700], 1e-15, 1e-15);
    sl_rock_project(a, NULL, n, 90.0, m);
    CHECK(m[700] == 0, "90 degrees without H2");
    sl_rock_history_free(&h1);
    sl_rock_history_free(&h2);
    free(a);
    free(m);
    free(z);
}

/* Results do not depend on where the samples fall: a record at a huge dt
 * and the same piecewise-linear function sampled 50 times finer give the
 * same peak, events and times (the input is the same function): within the
 * promise at the default rtol, to 1e-9 at rtol 1e-10. And the floor at rest
 * after the record: zeros appended change nothing. */
static void test_resample_and_tail(void)
{
    const double dtc = 0.1;
    const size_t nc = 41, k = 50, nf = (nc - 1) * k + 1;
    double *ac = zeros(nc), *af = zeros(nf), *ap = zeros(nc + 200);
    for (size_t i = 0; i < nc; i++) /* knots of a pulse, zero at the end */
        ac[i] = i < 12 ? -0.27 * g * sin(SL_PI * (double)i / 6.0) : 0.0;
    for (size_t i = 0; i < nf; i++) {
        const size_t j = i / k;
        const double f = (double)(i % k) / (double)k;
        af[i] = j + 1 < nc ? ac[j] + (ac[j + 1] - ac[j]) * f : ac[nc - 1];
    }
    memcpy(ap, ac, nc * sizeof *ac);
    const double hs[] = {0.1, 1.0}, rtols[] = {SL_ROCK_DEFAULT_RTOL, 1e-10};
    for (int q = 0; q < 2; q++)
        for (int t = 0; t < 2; t++) {
            sl_rock_block blk = {0.25 * hs[q], hs[q], -1};
            sl_rock_opts o = opts();
            o.rtol = rtols[t];
            const double tol = t ? 1e-9 : 1e-4;
            sl_rock_result rc, rf, rp;
            CHECK(sl_rock_run(&blk, ac, NULL, nc, dtc, 1, 1, &o, &rc, NULL) == SL_OK, "run");
            CHECK(sl_rock_run(&blk, af, NULL, nf, dtc / (double)k, 1, 1, &o, &rf, NULL) == SL_OK,
                  "run");
            CHECK(sl_rock_run(&blk, ap, NULL, nc + 200, dtc, 1, 1, &o, &rp, NULL) == SL_OK, "run");
            CHECK(rc.uplifted && !rc.tipped && rc.impacts > 20 && rc.peak_theta_rad > 0,
                  "h %g: should rock: impacts %zu, tipped %d", hs[q], rc.impacts, rc.tipped);
            CHECK_CLOSE(rc.peak_theta_rad, rf.peak_theta_rad, 0, tol);
            CHECK_CLOSE(rc.t_uplift_s, rf.t_uplift_s, 1e-12, 0);
            CHECK_CLOSE(rc.t_peak_s, rf.t_peak_s, tol, 0);
            CHECK(rc.impacts == rf.impacts && rc.tipped == rf.tipped, "impacts %zu vs %zu",
                  rc.impacts, rf.impacts);
            /* zeros after the record: the free rocking after it is the same */
            CHECK_CLOSE(rp.peak_theta_rad, rc.peak_theta_rad, 0, 1e-9);
            CHECK(rp.tipped == rc.tipped && rp.overturned == rc.overturned, "padded flags");
        }
    /* a pulse that overturns both: the same instant */
    for (size_t i = 0; i < nc; i++)
        ac[i] = i < 12 ? -0.45 * g * sin(SL_PI * (double)i / 6.0) : 0.0;
    for (size_t i = 0; i < nf; i++) {
        const size_t j = i / k;
        const double f = (double)(i % k) / (double)k;
        af[i] = j + 1 < nc ? ac[j] + (ac[j + 1] - ac[j]) * f : ac[nc - 1];
    }
    sl_rock_block blk = {0.25, 1.0, -1};
    sl_rock_opts o = opts();
    sl_rock_result rc, rf;
    CHECK(sl_rock_run(&blk, ac, NULL, nc, dtc, 1, 1, &o, &rc, NULL) == SL_OK, "run");
    CHECK(sl_rock_run(&blk, af, NULL, nf, dtc / (double)k, 1, 1, &o, &rf, NULL) == SL_OK, "run");
    CHECK(rc.overturned && rf.overturned, "overturns: %d %d", rc.overturned, rf.overturned);
    CHECK_CLOSE(rc.t_overturn_s, rf.t_overturn_s, 1e-6, 0);
    free(ac);
    free(af);
    free(ap);
}

/* ---- hard cases (docs/hard-cases.md) ------------------------------------- */

/* A huge block (p 0.4 rad/s) and a tiny one (p 38 rad/s, 0.4 rad a sample
 * at dt 0.01: sub-steps by the step rule): the free-rocking period against
 * the quadrature, and r = 1 over many impacts. */
static void test_huge_and_tiny_blocks(void)
{
    const double bs[] = {10.0, 0.001}, hs[] = {50.0, 0.005}, dts[] = {0.05, 0.01};
    for (int k = 0; k < 2; k++) {
        blk_c c = consts(bs[k], hs[k]);
        const double th0 = 0.6 * c.alpha, tq = quarter_exact(c.alpha, c.p, th0);
        sl_rock_result r;
        sl_rock_history hi;
        CHECK(free_run(bs[k], hs[k], th0, 21 * tq, dts[k], SL_ROCK_DEFAULT_RTOL, &r, &hi) ==
                  SL_OK,
              "run");
        const sl_rock_event *i1 = event_n(&hi, SL_ROCK_EV_IMPACT, 0);
        const sl_rock_event *i9 = event_n(&hi, SL_ROCK_EV_IMPACT, 8);
        CHECK(i1 && i9, "impacts %zu", r.impacts);
        if (i1 && i9) {
            CHECK_CLOSE(i1->t_s, tq, 0, 1e-6);
            CHECK_CLOSE(i9->t_s - i1->t_s, 16 * tq, 0, 1e-6);
        }
        CHECK_CLOSE(r.peak_theta_rad, th0, 0, 1e-6);
        sl_rock_history_free(&hi);
    }
}

/* g + a_v < 0 for 51 samples: (K3) holds whatever a_h, so the block leaves
 * rest, and (K2) as written (gravity reversed) drives it away from upright;
 * the samples are counted (liftoff_samples) so that the result is flagged,
 * and every number is finite. */
static void test_liftoff(void)
{
    const double dt = 0.01;
    const size_t n = 601;
    double *a = zeros(n), *v = zeros(n);
    for (size_t i = 0; i < n; i++)
        a[i] = 0.01 * g * sin(0.3 * (double)i);
    for (size_t i = 200; i <= 250; i++)
        v[i] = -1.5 * g;
    sl_rock_block blk = {0.3, 1.0, -1};
    sl_rock_opts o = opts();
    sl_rock_result r;
    CHECK(sl_rock_run(&blk, a, v, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(r.liftoff_samples == 51, "liftoff samples %zu", r.liftoff_samples);
    CHECK(r.uplifted && r.t_uplift_s > 1.99 && r.t_uplift_s < 2.0, "uplift at %g", r.t_uplift_s);
    CHECK(isfinite(r.peak_theta_rad) && isfinite(r.excursion_m) && isfinite(r.t_end_s),
          "finite");
    free(a);
    free(v);
}

/* Grazing: a_h above the threshold by 1e-12 for one sample: a tiny
 * excursion, impacts of tiny speed ended by the rest rule, no step-size
 * collapse, at rest at the end. */
static void test_grazing(void)
{
    const double dt = 0.01, b = 0.2, h = 1.0;
    const size_t n = 301;
    double *a = zeros(n);
    a[100] = -g * b / h * (1 + 1e-12);
    sl_rock_block blk = {b, h, -1};
    sl_rock_opts o = opts();
    sl_rock_result r;
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(r.uplifted && r.uplifts == 1 && r.peak_theta_rad < 1e-12 && r.steps < 500,
          "uplifted %d peak %g steps %zu", r.uplifted, r.peak_theta_rad, r.steps);
    CHECK(r.t_end_s == (double)(n - 1) * dt, "not at rest at the end: t_end %g", r.t_end_s);
    free(a);
}

/* Bad input: SL_EINVAL with a message naming the value. */
static void test_bad_input(void)
{
    double a[4] = {0, 1, NAN, 0};
    sl_rock_block blk = {0.2, 1.0, -1};
    sl_rock_opts o = opts();
    sl_rock_result r;
    sl_error e;
    CHECK(sl_rock_run(&blk, a, NULL, 4, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL &&
              strstr(e.msg, "sample 2"),
          "NaN: %s", e.msg);
    a[2] = INFINITY;
    a[1] = 100;
    CHECK(sl_rock_run(&blk, a, NULL, 4, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL, "inf");
    a[2] = 0;
    CHECK(sl_rock_run(&blk, a, NULL, 1, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL, "n = 1");
    CHECK(sl_rock_run(&blk, a, NULL, 4, 0.0, 1, 1, &o, &r, &e) == SL_EINVAL, "dt 0");
    CHECK(sl_rock_run(&blk, a, NULL, 4, 0.01, NAN, 1, &o, &r, &e) == SL_EINVAL, "scale");
    sl_rock_block bad = {0.0, 1.0, -1};
    CHECK(sl_rock_run(&bad, a, NULL, 4, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL, "b = 0");
    bad = (sl_rock_block){0.2, 1.0, 1.5};
    CHECK(sl_rock_run(&bad, a, NULL, 4, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL, "r = 1.5");
    o.rtol = 1.0;
    CHECK(sl_rock_run(&blk, a, NULL, 4, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL, "rtol");
    o = opts();
    o.theta0_rad = 2.0;
    CHECK(sl_rock_run(&blk, a, NULL, 4, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL, "theta0");
    /* a sample not finite found while at rest, after a long scan */
    double *z = zeros(1000);
    z[777] = NAN;
    o = opts();
    CHECK(sl_rock_run(&blk, z, NULL, 1000, 0.01, 1, 1, &o, &r, &e) == SL_EINVAL &&
              strstr(e.msg, "777"),
          "scan: %s", e.msg);
    free(z);
}

int main(void)
{
    RUN(test_free_period_exact);
    RUN(test_free_period_linear);
    RUN(test_energy_r1);
    RUN(test_restitution);
    RUN(test_uplift_threshold);
    RUN(test_constant_push_times);
    RUN(test_pulse_overturn);
    RUN(test_rest_rule);
    RUN(test_convergence);
    RUN(test_mirror);
    RUN(test_resample_and_tail);
    RUN(test_huge_and_tiny_blocks);
    RUN(test_liftoff);
    RUN(test_grazing);
    RUN(test_bad_input);
    return HARNESS_END("test_rock");
}

