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
    for (size_t i = 0; i < n; i++)
        a[i] = g * ta; /* exactly at the threshold: (K3) is strict */
    CHECK(sl_rock_run(&blk, a, NULL, n, dt, 1, 1, &o, &r, NULL) == SL_OK, "run");
    CHECK(!r.uplifted, "at the threshold: uplifted");
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

int main(void)
{
    RUN(test_free_period_exact);
    RUN(test_free_period_linear);
    RUN(test_energy_r1);
    RUN(test_restitution);
    RUN(test_uplift_threshold);
    return HARNESS_END("test_rock");
}
