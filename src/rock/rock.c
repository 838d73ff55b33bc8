/*
 * rock.c - the rocking block of rock.h: (K1)-(K4), events located on the
 * integrator itself, the rest rule, the free rocking after the record.
 *
 * The state is (theta, omega = theta', s) with s = +1 or -1 the corner the
 * block rocks about (theta has the sign of s, or is 0 at an uplift or an
 * impact). Within a sample the floor's accelerations are linear in the
 * time tau since the sample, so (K2) is smooth between events:
 *
 *   theta'' = (A0 + Ak tau) sin(s alpha - theta) + (B0 + Bk tau) cos(s alpha - theta)
 *
 * with A = -p^2 (1 + a_v/g) and B = -p^2 a_h/g. It is integrated by the
 * three-stage fourth-order Runge-Kutta-Nystrom method for y'' = f(t, y)
 * (Hairer, Norsett and Wanner, Solving ODEs I, II.14: c = 0, 1/2, 1;
 * a21 = 1/8, a32 = 1/2; b = 1/6, 1/3, 0; b' = 1/6, 2/3, 1/6): three
 * evaluations of the right-hand side (one sin and one cos each) per step,
 * on sub-steps aligned with the samples, each at most H(rtol)/omega_s long
 * (rock.h, sl_rock_opts).
 *
 * Events. A step whose end shows that |theta| turned (theta' changed
 * sign), reached 0 (an impact), alpha (tipping) or pi/2 (overturning) is
 * shortened to the event: the step size h at which the step's own result
 * satisfies the event is found by Newton's method on h (the derivative of
 * theta(h) is omega(h), that of omega(h) the last stage's acceleration),
 * kept inside a bracket (bisection when Newton leaves it), to
 * SL_ROCK_LOCATE_REL of the time within the sample: round-off. Turning
 * points are located first, so that a step is monotone in |theta| when
 * it is tested for 0, alpha and pi/2.
 *
 * Uplift from rest: (K3) at a sample's ends, |a_h| > (g + a_v) tan(alpha);
 * |a_h| - (g + a_v) tan(alpha) is convex within a sample, so a sample
 * whose ends hold holds throughout, and the instant of an uplift is the
 * root of a linear function (exact). While the block is at rest that test
 * per sample is all the work.
 *
 * Impact: theta' <- r theta', the other corner (K4). The rest rule: after
 * an impact, when the net acceleration at theta = 0 pushes the block back
 * (a_r > 0) and the rebound's reach w^2 / (2 a_r) is below rest_fraction
 * alpha, the cascade of impacts (whose times converge geometrically) is
 * ended at rest; r = 0 rests at once. (K3) then decides the next uplift.
 *
 * After the record the floor is at rest: the energy
 * E = theta'^2/2 + p^2 cos(alpha - |theta|) is conserved between impacts
 * and lost at them (r <= 1), so every peak after the first peak of the
 * free rocking is lower. The integration stops there, at a rest, or at the
 * overturn.
 */
#include "rock/rock.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/units.h"

/* Newton's iteration on the step size stops when it moves h by less than
 * this share of the time since the sample's start (about 64 ulp), or after
 * SL_ROCK_LOCATE_MAX iterations (bisection keeps it bracketed). */
#define SL_ROCK_LOCATE_REL (64 * DBL_EPSILON)
#define SL_ROCK_LOCATE_MAX 60
/* Steps of the free rocking after the record, at most (with the time cap). */
#define SL_ROCK_TAIL_MAX_STEPS 10000000ul

static const char *const event_names[SL_ROCK_EV_COUNT] = {
    "uplift", "impact", "peak", "tip", "overturn", "rest", "end"};

const char *sl_rock_event_name(sl_rock_event_kind k)
{
    return (unsigned)k < SL_ROCK_EV_COUNT ? event_names[k] : "?";
}

void sl_rock_opts_default(sl_rock_opts *o)
{
    o->rtol = SL_ROCK_DEFAULT_RTOL;
    o->substeps = 0;
    o->rest_fraction = SL_ROCK_REST_FRACTION;
    o->theta0_rad = 0.0;
    o->omega0_rad_s = 0.0;
}

/* (K4): r = 1 - (3/2) sin^2(alpha), at least 0 (a block wider than about
 * 1.4 times its height would not rebound at all; it slides first anyway). */
double sl_rock_housner_r(double b_m, double h_m)
{
    const double s2 = b_m * b_m / (b_m * b_m + h_m * h_m); /* sin^2(alpha) */
    const double r = 1.0 - 1.5 * s2;
    return r > 0.0 ? r : 0.0;
}

void sl_rock_project(const double *h1, const double *h2, size_t n, double phi_deg, double *out)
{
    /* phi = 90 k + r, r in [0, 90): the quarter turns exact (180 degrees is -H1 to the
     * bit), and cos, sin of r taken so that r and 90 - r swap them bit for bit (cos r
     * is computed as sin(90 - r) above 45 degrees, and both are sqrt(1/2) at 45): H1
     * and H2 exchanged give the same projections at the mirrored angles */
    double q = floor(phi_deg / 90.0), r = phi_deg - 90.0 * q, c0, s0, c, s;
    if (r >= 90.0) { /* round-off of the division */
        r -= 90.0;
        q += 1.0;
    }
    if (r == 45.0) {
        c0 = s0 = sqrt(0.5);
    } else if (r < 45.0) {
        c0 = cos(r * (SL_PI / 180.0));
        s0 = sin(r * (SL_PI / 180.0));
    } else {
        c0 = sin((90.0 - r) * (SL_PI / 180.0));
        s0 = cos((90.0 - r) * (SL_PI / 180.0));
    }
    long k = (long)fmod(q, 4.0);
    k = (k + 4) % 4;
    c = k == 0 ? c0 : k == 1 ? -s0 : k == 2 ? -c0 : s0;
    s = k == 0 ? s0 : k == 1 ? c0 : k == 2 ? -s0 : -c0;
    for (size_t i = 0; i < n; i++)
        out[i] = h2 ? c * h1[i] + s * h2[i] : c * h1[i];
}

/* ---- the history (sl_rock_run_history only) ---------------------------- */

typedef struct rk_hist {
    sl_rock_history *h;
    size_t cap, ecap;
    int failed; /* out of memory */
} rk_hist;

static void hist_row(rk_hist *H, double t, double th, double om)
{
    sl_rock_history *h = H->h;
    if (H->failed)
        return;
    if (h->n == H->cap) {
        size_t cap = H->cap ? 2 * H->cap : 1024;
        double *a = realloc(h->t_s, cap * sizeof *a);
        if (a)
            h->t_s = a;
        double *b = a ? realloc(h->theta_rad, cap * sizeof *b) : NULL;
        if (b)
            h->theta_rad = b;
        double *c = b ? realloc(h->omega_rad_s, cap * sizeof *c) : NULL;
        if (!c) {
            H->failed = 1;
            return;
        }
        h->omega_rad_s = c;
        H->cap = cap;
    }
    h->t_s[h->n] = t;
    h->theta_rad[h->n] = th;
    h->omega_rad_s[h->n] = om;
    h->n++;
}

static void hist_event(rk_hist *H, sl_rock_event_kind k, double t, double th, double om,
                       double om_before)
{
    sl_rock_history *h = H->h;
    if (H->failed)
        return;
    if (h->n_events == H->ecap) {
        size_t cap = H->ecap ? 2 * H->ecap : 64;
        sl_rock_event *e = realloc(h->events, cap * sizeof *e);
        if (!e) {
            H->failed = 1;
            return;
        }
        h->events = e;
        H->ecap = cap;
    }
    h->events[h->n_events++] = (sl_rock_event){k, t, th, om, om_before};
}

void sl_rock_history_free(sl_rock_history *h)
{
    if (!h)
        return;
    free(h->t_s);
    free(h->theta_rad);
    free(h->omega_rad_s);
    free(h->events);
    memset(h, 0, sizeof *h);
}

/* ---- the integrator ------------------------------------------------------ */

typedef struct rk {
    /* block and settings */
    double alpha, ta, sin_a, cos_a, p2, r, H, rest_frac, hmax_fixed;
    /* input: x = scale_h a_h, y = scale_v a_v (m/s^2) */
    const double *ah, *av;
    size_t n;
    double dt, sh, sv, gta; /* gta = g tan(alpha) */
    /* the current piece: theta'' = (A0 + Ak tau) sin(sa - th) + (B0 + Bk tau) cos(sa - th) */
    double A0, Ak, B0, Bk, hmax;
    double xa, xb, ya, yb; /* accelerations at the piece's sample ends, m/s^2 */
    double ti;             /* start of the piece's sample, s */
    /* state */
    double th, om, sa;
    int s;
    /* output */
    sl_rock_result *res;
    rk_hist *hist;
} rk;

/* A step's origin: the state at tau, sin and cos of (s alpha - theta) there
 * (libm) and theta'' there (K2). */
typedef struct rk_org {
    double tau, th, om, S, C, k1;
} rk_org;

static inline void org_set(const rk *c, rk_org *o, double tau, double th, double om)
{
    const double a = c->sa - th;
    o->tau = tau;
    o->th = th;
    o->om = om;
    o->S = sin(a);
    o->C = cos(a);
    o->k1 = (c->A0 + c->Ak * tau) * o->S + (c->B0 + c->Bk * tau) * o->C;
}

/* theta'' at tau and theta = o->th + d (K2). sin and cos of (s alpha -
 * theta) by the angle-difference formulas from the origin's, with sin d and
 * cos d from their Taylor series: to d^7 and d^8 for |d| <= 2^-7 and to d^11
 * and d^12 for |d| <= 1/8 (the first term left out is below 1e-20 relative,
 * under the rounding of the formulas); libm for a larger d. */
static inline double acc_d(const rk *c, const rk_org *o, double tau, double d)
{
    /* Taylor coefficients: (-1)^k / (2k + 1)! and (-1)^k / (2k)! */
    static const double s3 = -1.0 / 6, s5 = 1.0 / 120, s7 = -1.0 / 5040, s9 = 1.0 / 362880,
                        s11 = -1.0 / 39916800;
    static const double c2 = -0.5, c4 = 1.0 / 24, c6 = -1.0 / 720, c8 = 1.0 / 40320,
                        c10 = -1.0 / 3628800, c12 = 1.0 / 479001600;
    const double z = d * d;
    double sd, cd;
    if (z <= 0x1p-14) {
        sd = d + d * z * (s3 + z * (s5 + z * s7));
        cd = 1 + z * (c2 + z * (c4 + z * (c6 + z * c8)));
    } else if (z <= 0x1p-6) {
        sd = d + d * z * (s3 + z * (s5 + z * (s7 + z * (s9 + z * s11))));
        cd = 1 + z * (c2 + z * (c4 + z * (c6 + z * (c8 + z * (c10 + z * c12)))));
    } else {
        const double a = c->sa - (o->th + d);
        return (c->A0 + c->Ak * tau) * sin(a) + (c->B0 + c->Bk * tau) * cos(a);
    }
    const double S = o->S * cd - o->C * sd; /* sin(a - d) */
    const double C = o->C * cd + o->S * sd; /* cos(a - d) */
    return (c->A0 + c->Ak * tau) * S + (c->B0 + c->Bk * tau) * C;
}

/* One Runge-Kutta-Nystrom step of size h from the origin o: the state at
 * o->tau + h and the last stage's acceleration (about theta'' there). */
static inline void rkn(const rk *c, const rk_org *o, double h, double *th1, double *om1,
                       double *a1)
{
    const double tau = o->tau, om = o->om, k1 = o->k1;
    const double k2 = acc_d(c, o, tau + 0.5 * h, 0.5 * h * om + 0.125 * h * h * k1);
    const double k3 = acc_d(c, o, tau + h, h * om + 0.5 * h * h * k2);
    *th1 = o->th + h * om + h * h * (k1 + 2.0 * k2) / 6.0;
    *om1 = om + h * (k1 + 4.0 * k2 + k3) / 6.0;
    *a1 = k3;
}

/* Set the piece of sample i (i <= n - 2: the record; else the floor at rest). */
static void set_piece(rk *c, size_t i)
{
    const double g = SL_G;
    c->ti = (double)i * c->dt;
    if (i + 1 < c->n) {
        c->xa = c->sh * c->ah[i];
        c->xb = c->sh * c->ah[i + 1];
        c->ya = c->av ? c->sv * c->av[i] : 0.0;
        c->yb = c->av ? c->sv * c->av[i + 1] : 0.0;
    } else {
        c->xa = c->xb = c->ya = c->yb = 0.0;
    }
    c->A0 = -c->p2 * (1.0 + c->ya / g);
    c->Ak = -c->p2 * (c->yb - c->ya) / (g * c->dt);
    c->B0 = -c->p2 * c->xa / g;
    c->Bk = -c->p2 * (c->xb - c->xa) / (g * c->dt);
    if (c->hmax_fixed > 0) {
        c->hmax = c->hmax_fixed;
    } else {
        /* omega_s^4 = p^4 ((1 + a_v/g)^2 + (a_h/g)^2), the larger of the ends */
        const double za = 1.0 + c->ya / g, zb = 1.0 + c->yb / g;
        const double qa = za * za + c->xa * c->xa / (g * g), qb = zb * zb + c->xb * c->xb / (g * g);
        const double w4 = c->p2 * c->p2 * (qa > qb ? qa : qb);
        c->hmax = w4 > 0 ? c->H / sqrt(sqrt(w4)) : c->dt;
    }
}

static void set_side(rk *c, int s)
{
    c->s = s;
    c->sa = s > 0 ? c->alpha : -c->alpha;
}

enum { Q_THETA, Q_OMEGA };

/* The step size in (0, hb] at which a step from the origin o meets
 * q = s theta - level (Q_THETA) or q = s omega (Q_OMEGA), given that q at
 * h = 0 (q0) and at hb (qb) lie on the two sides of 0 (qb may be 0). Newton
 * on the step's own result, bracketed. The state there in *th1, *om1. */
static double locate(const rk *c, const rk_org *o, double hb, double q0, double qb, int kind,
                     double level, double *th1, double *om1)
{
    const double s = c->s, tau = o->tau;
    double lo = 0.0, hi = hb, qlo = q0;
    double h = q0 != qb ? hb * q0 / (q0 - qb) : hb; /* regula falsi */
    double t1 = 0, o1 = 0, a1 = 0;
    for (int it = 0; it < SL_ROCK_LOCATE_MAX; it++) {
        if (!(h > lo && h < hi))
            h = 0.5 * (lo + hi);
        rkn(c, o, h, &t1, &o1, &a1);
        c->res->steps++;
        const double q = kind == Q_THETA ? s * t1 - level : s * o1;
        const double dq = kind == Q_THETA ? s * o1 : s * a1;
        if (q == 0.0)
            break;
        if ((q > 0) == (qlo > 0)) {
            lo = h;
            qlo = q;
        } else {
            hi = h;
        }
        const double tol = SL_ROCK_LOCATE_REL * (tau + h);
        double hn = dq != 0.0 ? h - q / dq : 0.5 * (lo + hi);
        if (!(hn > lo && hn < hi))
            hn = 0.5 * (lo + hi);
        if (fabs(hn - h) <= tol || hi - lo <= tol) {
            if (fabs(hn - h) <= tol && hn != h) {
                h = hn;
                rkn(c, o, h, &t1, &o1, &a1);
                c->res->steps++;
            }
            break;
        }
        h = hn;
    }
    *th1 = t1;
    *om1 = o1;
    return h;
}

/* ---- events ---------------------------------------------------------------- */

static void note_peak(rk *c, double t, double u)
{
    if (u > c->res->peak_theta_rad) {
        c->res->peak_theta_rad = u;
        c->res->t_peak_s = t;
    }
}

static void ev(rk *c, sl_rock_event_kind k, double t, double om_before)
{
    if (c->hist)
        hist_event(c->hist, k, t, c->th, c->om, om_before);
}

static void tip(rk *c, double t)
{
    if (!c->res->tipped) {
        c->res->tipped = 1;
        c->res->t_tip_s = t;
        if (c->hist) /* the state at the tip instant is not kept: theta = s alpha */
            hist_event(c->hist, SL_ROCK_EV_TIP, t, c->sa, NAN, NAN);
    }
}

static void overturn(rk *c, double t)
{
    c->res->overturned = 1;
    c->res->t_overturn_s = t;
    c->th = c->s * (SL_PI / 2);
    c->om = 0.0;
    c->res->peak_theta_rad = SL_PI / 2;
    c->res->t_peak_s = t;
    ev(c, SL_ROCK_EV_OVERTURN, t, 0.0);
}

/* The results of one piece. */
enum { P_DONE, P_REST, P_OVER, P_STOP };

/* An impact at tau (theta = 0, omega = om_minus): the other corner, r omega,
 * then the rest rule. Returns P_REST or P_DONE (rocks on). */
static int impact(rk *c, double tau, double om_minus)
{
    const double t = c->ti + tau;
    c->res->impacts++;
    set_side(c, -c->s);
    c->th = 0.0;
    c->om = c->r * om_minus;
    ev(c, SL_ROCK_EV_IMPACT, t, om_minus);
    /* a_r: the net acceleration back toward theta = 0 on the new side */
    const double A = c->A0 + c->Ak * tau, B = c->B0 + c->Bk * tau;
    const double a_r = -(A * c->sin_a + c->s * B * c->cos_a);
    const double w = c->om;
    if (w == 0.0 || (a_r > 0.0 && w * w < 2.0 * a_r * c->rest_frac * c->alpha)) {
        c->om = 0.0;
        c->res->rests++;
        ev(c, SL_ROCK_EV_REST, t, w);
        return P_REST;
    }
    return P_DONE;
}

/* Rock through the piece from *ptau to tend (tail: the free rocking after
 * the record, which stops at its first peak below alpha). */
static int rock_piece(rk *c, double *ptau, double tend, int tail)
{
    double tau = *ptau;
    int rc = P_DONE;
    while (tau < tend) {
        const double rem = tend - tau;
        const double hs = rem <= c->hmax * (1 + 1e-12) ? rem : rem / ceil(rem / c->hmax);
        const double s = c->s, th = c->th, om = c->om;
        rk_org o;
        org_set(c, &o, tau, th, om);
        double th1, om1, a1;
        rkn(c, &o, hs, &th1, &om1, &a1);
        c->res->steps++;
        const double u0 = s * th, v0 = s * om, u1 = s * th1, v1 = s * om1;
        double h, te, tq, oq;
        if (v0 > 0 && v1 <= 0) {
            /* |theta| turns: a peak inside; tipping or overturning may come first */
            h = v1 == 0 ? hs : locate(c, &o, hs, v0, v1, Q_OMEGA, 0, &tq, &oq);
            if (v1 == 0) {
                tq = th1;
            }
            const double up = s * tq;
            if (up >= SL_PI / 2) {
                te = locate(c, &o, h, u0 - SL_PI / 2, up - SL_PI / 2, Q_THETA,
                            SL_PI / 2, &tq, &oq);
                overturn(c, c->ti + tau + te);
                rc = P_OVER;
                break;
            }
            if (up >= c->alpha && !c->res->tipped) {
                te = locate(c, &o, h, u0 - c->alpha, up - c->alpha, Q_THETA,
                            c->alpha, &th1, &om1);
                tip(c, c->ti + tau + te);
            }
            tau += h;
            c->th = tq;
            c->om = 0.0;
            note_peak(c, c->ti + tau, up);
            ev(c, SL_ROCK_EV_PEAK, c->ti + tau, 0.0);
            if (tail && up < c->alpha) {
                rc = P_STOP;
                break;
            }
            continue;
        }
        if (v0 < 0 && v1 > 0) {
            /* |theta| turns back out: an impact may come before */
            h = locate(c, &o, hs, v0, v1, Q_OMEGA, 0, &tq, &oq);
            if (s * tq <= 0) {
                te = locate(c, &o, h, u0, s * tq, Q_THETA, 0, &tq, &oq);
                tau += te;
                if ((rc = impact(c, tau, oq)) == P_REST)
                    break;
                continue;
            }
            tau += h;
            c->th = tq;
            c->om = 0.0;
            continue;
        }
        if (v1 > 0 || (v1 == 0 && v0 >= 0 && u1 > 0)) {
            /* |theta| grows */
            if (u1 >= SL_PI / 2) {
                te = locate(c, &o, hs, u0 - SL_PI / 2, u1 - SL_PI / 2, Q_THETA,
                            SL_PI / 2, &tq, &oq);
                overturn(c, c->ti + tau + te);
                rc = P_OVER;
                break;
            }
            if (u1 >= c->alpha && !c->res->tipped) {
                te = locate(c, &o, hs, u0 - c->alpha, u1 - c->alpha, Q_THETA,
                            c->alpha, &tq, &oq);
                tip(c, c->ti + tau + te);
            }
        } else if (u1 <= 0) {
            /* |theta| falls to 0 */
            if (u0 == 0.0 && v0 == 0.0) {
                /* left rest by round-off only (a step from an uplift that
                 * does not rise): at rest through this step */
                c->th = c->om = 0.0;
                *ptau = tau + hs;
                return P_REST;
            }
            te = locate(c, &o, hs, u0, u1, Q_THETA, 0, &tq, &oq);
            tau += te;
            if ((rc = impact(c, tau, oq)) == P_REST)
                break;
            continue;
        }
        /* no event: take the whole step */
        tau = hs == rem ? tend : tau + hs;
        c->th = th1;
        c->om = om1;
        note_peak(c, c->ti + tau, fabs(th1));
    }
    *ptau = tau;
    return rc;
}

/* The first instant in [tau, dt] of the current piece at which (K3) holds,
 * or -1; *side the corner. The ends of the sample are tested exactly as the
 * scan tests the samples (uplift_at). */
static double uplift_in_piece(const rk *c, double tau, int *side)
{
    const double f = tau / c->dt;
    const double x0 = tau == 0 ? c->xa : c->xa + (c->xb - c->xa) * f;
    const double y0 = tau == 0 ? c->ya : c->ya + (c->yb - c->ya) * f;
    const double T0 = (SL_G + y0) * c->ta, T1 = (SL_G + c->yb) * c->ta;
    /* side +1 (theta > 0) when -a_h > (g + a_v) tan(alpha), side -1 when a_h > ... */
    const double fp0 = -x0 - T0, fp1 = -c->xb - T1, fm0 = x0 - T0, fm1 = c->xb - T1;
    double tp = -1, tm = -1;
    if (fp0 > 0)
        tp = tau;
    else if (fp1 > 0)
        tp = tau + (c->dt - tau) * (-fp0 / (fp1 - fp0));
    if (fm0 > 0)
        tm = tau;
    else if (fm1 > 0)
        tm = tau + (c->dt - tau) * (-fm0 / (fm1 - fm0));
    if (tp < 0 && tm < 0)
        return -1;
    if (tm < 0 || (tp >= 0 && tp < tm) || (tp == tm && x0 <= 0)) {
        *side = 1;
        return tp;
    }
    *side = -1;
    return tm;
}

/* The first sample j >= from whose point holds (K3), or n (or the first
 * sample that is not finite: the caller checks). The work of a block at
 * rest: one multiply, one mask and one unordered compare per sample, two
 * samples at a time (GCC's and Clang's vector extensions: SSE2 on x86-64,
 * plain scalar code elsewhere), 16 samples between branches; a NaN stops
 * the scan as an uplift would (!(|x| <= T)). */
typedef double rk_v2d __attribute__((vector_size(16)));
typedef long long rk_v2l __attribute__((vector_size(16)));
#define RK_SCAN_BLOCK 16

/* |x|, a lane at a time (the sign bit cleared). */
static inline rk_v2d v2_abs(rk_v2d x)
{
    const rk_v2l mask = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL};
    rk_v2l b;
    memcpy(&b, &x, sizeof b);
    b &= mask;
    memcpy(&x, &b, sizeof x);
    return x;
}

static size_t uplift_scan(const rk *c, size_t from)
{
    const double *ah = c->ah, *av = c->av, sh = c->sh, sv = c->sv, ta = c->ta, gta = c->gta;
    const size_t n = c->n;
    const rk_v2d vsh = {sh, sh}, vgta = {gta, gta}, vsv = {sv, sv}, vta = {ta, ta},
                 vg = {SL_G, SL_G};
    size_t j = from;
    if (!av) {
        for (; j + RK_SCAN_BLOCK <= n; j += RK_SCAN_BLOCK) {
            rk_v2l hit = {0, 0};
            for (size_t k = 0; k < RK_SCAN_BLOCK; k += 2) {
                rk_v2d x;
                memcpy(&x, ah + j + k, sizeof x);
                hit |= ~(v2_abs(vsh * x) <= vgta);
            }
            if ((hit[0] | hit[1]) != 0)
                break;
        }
    } else {
        for (; j + RK_SCAN_BLOCK <= n; j += RK_SCAN_BLOCK) {
            rk_v2l hit = {0, 0};
            for (size_t k = 0; k < RK_SCAN_BLOCK; k += 2) {
                rk_v2d x, y;
                memcpy(&x, ah + j + k, sizeof x);
                memcpy(&y, av + j + k, sizeof y);
                /* (g + sv a_v) tan(alpha), the same operations as below */
                hit |= ~(v2_abs(vsh * x) <= (vg + vsv * y) * vta);
            }
            if ((hit[0] | hit[1]) != 0)
                break;
        }
    }
    for (; j < n; j++) {
        const double T = av ? (SL_G + sv * av[j]) * ta : gta;
        if (!(fabs(sh * ah[j]) <= T))
            break;
    }
    return j;
}

static sl_status check_input(const sl_rock_block *blk, const double *ah, size_t n, double dt,
                             double sh, double sv, const sl_rock_opts *o, sl_error *err)
{
    if (!blk || !(blk->b_m > 0) || !(blk->h_m > 0) || !isfinite(blk->b_m) || !isfinite(blk->h_m))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "rock: base half-width %g m and centre-of-mass height %g m must be "
                            "finite and > 0", blk ? blk->b_m : NAN, blk ? blk->h_m : NAN);
    if (!(blk->restitution <= 1.0) && !isnan(blk->restitution))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: restitution %g must be in [0, 1]",
                            blk->restitution);
    if (!ah || n < 2)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: a motion needs 2 samples or more");
    if (!(dt > 0) || !isfinite(dt))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: dt %g s must be > 0", dt);
    if (!isfinite(sh) || !isfinite(sv))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: scales %g, %g must be finite", sh,
                            sv);
    if (!(o->rtol >= SL_ROCK_RTOL_MIN && o->rtol <= SL_ROCK_RTOL_MAX))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: rtol %g must be in [%g, %g]",
                            o->rtol, SL_ROCK_RTOL_MIN, SL_ROCK_RTOL_MAX);
    if (o->substeps > SL_ROCK_SUBSTEPS_MAX)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: substeps %u above %u", o->substeps,
                            SL_ROCK_SUBSTEPS_MAX);
    if (!(o->rest_fraction >= 0 && o->rest_fraction < 1))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: rest fraction %g must be in [0, 1)",
                            o->rest_fraction);
    if (!(fabs(o->theta0_rad) < SL_PI / 2) || !isfinite(o->omega0_rad_s))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "rock: initial state %g rad, %g rad/s: |theta0| must be < pi/2",
                            o->theta0_rad, o->omega0_rad_s);
    return SL_OK;
}

static sl_status not_finite(const rk *c, size_t j, sl_error *err)
{
    const int h_bad = !isfinite(c->ah[j]);
    return sl_error_set(err, SL_EINVAL, NULL, 0, "rock: sample %zu of %s is %g (not finite)", j,
                        h_bad ? "a_h" : "a_v", h_bad ? c->ah[j] : c->av[j]);
}

/* Rows of the history for the samples up to i (the block's state th, om). */
static void hist_upto(rk *c, size_t *next_row, size_t i, double th, double om)
{
    if (!c->hist)
        return;
    for (; *next_row <= i; (*next_row)++)
        hist_row(c->hist, (double)*next_row * c->dt, th, om);
}

static sl_status run(const sl_rock_block *blk, const double *ah, const double *av, size_t n,
                     double dt, double sh, double sv, const sl_rock_opts *o,
                     sl_rock_result *out, rk_hist *hist, sl_error *err)
{
    sl_rock_opts def;
    if (!o) {
        sl_rock_opts_default(&def);
        o = &def;
    }
    sl_status st = check_input(blk, ah, n, dt, sh, sv, o, err);
    if (st)
        return st;
    rk c;
    memset(&c, 0, sizeof c);
    const double b = blk->b_m, hc = blk->h_m, R = sqrt(b * b + hc * hc);
    c.alpha = atan2(b, hc);
    c.sin_a = b / R;
    c.cos_a = hc / R;
    c.ta = b / hc;
    c.gta = SL_G * c.ta;
    c.p2 = 3.0 * SL_G / (4.0 * R); /* (K1) */
    c.r = blk->restitution >= 0 ? blk->restitution : sl_rock_housner_r(b, hc);
    c.H = SL_ROCK_H_COEF * sqrt(sqrt(o->rtol));
    c.rest_frac = o->rest_fraction;
    c.hmax_fixed = o->substeps ? dt / o->substeps : 0.0;
    c.ah = ah;
    c.av = av;
    c.n = n;
    c.dt = dt;
    c.sh = sh;
    c.sv = sv;
    c.hist = hist;
    sl_rock_result *res = out;
    *res = (sl_rock_result){.alpha_rad = c.alpha, .p_rad_s = sqrt(c.p2), .restitution = c.r,
                            .t_peak_s = 0.0, .t_uplift_s = NAN, .t_tip_s = NAN,
                            .t_overturn_s = NAN};
    c.res = res;
    size_t row = 0; /* next history row */

    /* the initial state */
    int rocking = o->theta0_rad != 0 || o->omega0_rad_s != 0;
    c.th = o->theta0_rad;
    c.om = o->omega0_rad_s;
    set_side(&c, o->theta0_rad > 0 || (o->theta0_rad == 0 && o->omega0_rad_s > 0) ? 1 : -1);
    res->peak_theta_rad = fabs(c.th);
    if (fabs(c.th) >= c.alpha)
        tip(&c, 0.0);
    for (size_t j = 0; j < 2; j++)
        if (!isfinite(ah[j]) || (av && !isfinite(av[j])))
            return not_finite(&c, j, err);
    if (av && SL_G + sv * av[0] < 0)
        res->liftoff_samples++;
    hist_upto(&c, &row, 0, c.th, c.om);

    size_t i = 0;
    double tau = 0.0;
    set_piece(&c, 0);
    /* invariant: the points up to i + 1 are finite, the piece of sample i is set */
    while (i + 1 < n) {
        if (!rocking) {
            int side = 1;
            double tu = uplift_in_piece(&c, tau, &side);
            if (tu < 0) {
                /* at rest to the end of this sample: scan on (a sample that is
                 * not finite stops the scan as an uplift would) */
                size_t j = uplift_scan(&c, i + 2);
                if (j < n && (!isfinite(ah[j]) || (av && !isfinite(av[j]))))
                    return not_finite(&c, j, err);
                hist_upto(&c, &row, j - 1, 0.0, 0.0);
                if (j >= n) {
                    i = n - 1;
                    break;
                }
                i = j - 1;
                tau = 0.0;
                if (!isfinite(ah[j - 1]) || (av && !isfinite(av[j - 1])))
                    return not_finite(&c, j - 1, err);
                set_piece(&c, i);
                tu = uplift_in_piece(&c, 0.0, &side);
                if (tu < 0) /* cannot be: the scan found (K3) at the end */
                    tu = dt;
            }
            tau = tu;
            set_side(&c, side);
            c.th = c.om = 0.0;
            rocking = 1;
            res->uplifts++;
            if (!res->uplifted) {
                res->uplifted = 1;
                res->t_uplift_s = c.ti + tau;
            }
            ev(&c, SL_ROCK_EV_UPLIFT, c.ti + tau, 0.0);
        }
        int pr = rock_piece(&c, &tau, dt, 0);
        if (pr == P_OVER) {
            hist_upto(&c, &row, i, c.th, c.om);
            hist_upto(&c, &row, n - 1, c.th, 0.0);
            res->t_end_s = res->t_overturn_s;
            goto done;
        }
        if (pr == P_REST) {
            rocking = 0;
            c.th = c.om = 0.0;
            if (tau < dt)
                continue; /* the uplift test from tau within this sample */
        }
        /* the end of sample i: the next point */
        hist_upto(&c, &row, i + 1, c.th, c.om);
        i++;
        tau = 0.0;
        if (i + 1 < n && (!isfinite(ah[i + 1]) || (av && !isfinite(av[i + 1]))))
            return not_finite(&c, i + 1, err);
        if (av && SL_G + sv * av[i] < 0)
            res->liftoff_samples++;
        set_piece(&c, i);
    }
    hist_upto(&c, &row, n - 1, c.th, c.om);
    res->t_end_s = (double)(n - 1) * dt;
    if (rocking) {
        /* the free rocking after the record: to its first peak (or a rest, the overturn) */
        const double t_cap = res->t_end_s + SL_ROCK_TAIL_MAX_P / res->p_rad_s;
        const size_t steps0 = res->steps;
        for (i = n - 1;; i++) {
            set_piece(&c, i);
            tau = 0.0;
            int pr = rock_piece(&c, &tau, dt, 1);
            if (pr != P_DONE) {
                res->t_end_s = pr == P_OVER ? res->t_overturn_s : c.ti + tau;
                if (pr != P_OVER && c.hist)
                    hist_row(c.hist, res->t_end_s, c.th, c.om);
                break;
            }
            hist_upto(&c, &row, i + 1, c.th, c.om);
            if (c.ti + dt > t_cap || res->steps - steps0 > SL_ROCK_TAIL_MAX_STEPS)
                return sl_error_set(err, SL_ENOCONV, NULL, 0,
                                    "rock: the free rocking after the record did not end "
                                    "within %g s", t_cap - (double)(n - 1) * dt);
        }
    }
done:
    if (!res->overturned)
        ev(&c, SL_ROCK_EV_END, res->t_end_s, c.om);
    res->peak_theta_over_alpha = res->peak_theta_rad / c.alpha;
    res->excursion_m = res->overturned ? 2.0 * hc : 2.0 * hc * sin(res->peak_theta_rad);
    if (hist && hist->failed)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "rock: out of memory for the history");
    return SL_OK;
}

sl_status sl_rock_run(const sl_rock_block *blk, const double *a_h_ms2, const double *a_v_ms2,
                      size_t n, double dt_s, double scale_h, double scale_v,
                      const sl_rock_opts *o, sl_rock_result *out, sl_error *err)
{
    return run(blk, a_h_ms2, a_v_ms2, n, dt_s, scale_h, scale_v, o, out, NULL, err);
}

sl_status sl_rock_run_history(const sl_rock_block *blk, const double *a_h_ms2,
                              const double *a_v_ms2, size_t n, double dt_s, double scale_h,
                              double scale_v, const sl_rock_opts *o, sl_rock_result *out,
                              sl_rock_history *h, sl_error *err)
{
    memset(h, 0, sizeof *h);
    rk_hist H = {h, 0, 0, 0};
    sl_status st = run(blk, a_h_ms2, a_v_ms2, n, dt_s, scale_h, scale_v, o, out, &H, err);
    if (st)
        sl_rock_history_free(h);
    return st;
}
