/*
 * refmodel.c - the reference models of the sliding block (refmodel.h,
 * docs/refmodels.md). Same equation as the engine (slide.h, eq. 1),
 *
 *     u'' = -a_g(t) - mu N(t) Z,   N = max(g + a_v, 0),   |Z| <= 1,
 *
 * with the rigid-plastic friction direction s replaced by a hysteretic
 * variable Z that has an elastic range of displacement U_y. Both models tend
 * to the Coulomb block as U_y -> 0, but not uniformly at first order: the
 * elastic displacement U_y Z is an O(U_y) offset, while each reversal or
 * jump of the friction force takes a time ~ sqrt(U_y / a) to load the
 * spring, losing an impulse ~ mu N sqrt(U_y / a): peaks of records with
 * stick-slip or reversals converge like sqrt(U_y) (docs/refmodels.md).
 *
 * SL_MODEL_SMOOTH - biaxial Bouc-Wen model in the Park, Wen & Ang (1986)
 * coupling ("Random vibration of hysteretic systems in bidirectional
 * motions", J. Eng. Mech. 112(8)), as used for sliding bearings by
 * Nagarajaiah, Reinhorn & Constantinou (1991) "Nonlinear dynamic analysis
 * of 3-D-base-isolated structures", J. Struct. Eng. 117(7), and in
 * 3D-BASIS and OpenSees' LeadRubberX (SRC/element/elastomericBearing),
 * generalised to an exponent eta:
 *
 *     U_y Z' = A u' - |Z|^(eta-2) Z S,                                  (R1)
 *     S = sum_j ( beta |u'_j Z_j| + gamma u'_j Z_j ),   j = x, y.
 *
 * Component by component this is Nagarajaiah's matrix form
 *     U_y Z_x' = [A - Z_x^2 (gamma' sgn(u_x' Z_x) + beta')] u_x'
 *                - Z_x Z_y (gamma' sgn(u_y' Z_y) + beta') u_y'   (and x<->y)
 * with his beta' = our gamma and his gamma' = our beta (the two papers
 * swap the names; with beta = gamma = 0.5 they coincide). For eta = 2 it is
 * Park-Wen-Ang exactly; in 1-D it is Wen's uniaxial law
 *     U_y Z' = A u' - beta |u'| |Z|^(eta-1) Z - gamma u' |Z|^eta,
 * i.e. Z' = u' (A - |Z|^eta (beta sgn(u' Z) + gamma)) / U_y (slide.h).
 * A = 1, beta = gamma = 0.5 (the source study): |Z| = 1 is the yield
 * surface (beta + gamma = A) and Z Z' <= 0 there while loading.
 * The right-hand side is continuous (|.| has a kink, no jump), so it is not
 * smoothed; its Jacobian jumps where u'_j Z_j changes sign, which only costs
 * the stiff solvers a rejected step. State y = (u, u', Z, p) with p the slip
 * path (a quadrature, see below): 4 values in 1-D, 7 in 2-D.
 *
 * SL_MODEL_PLASTIC - elastic-perfectly-plastic spring, isotropic (circular
 * yield surface |F| <= mu N), stiffness k = mu N / U_y per unit mass so that
 * F = mu N Z with Z = (u - u_p) / U_y (the eta -> infinity limit of R1),
 * integrated with Newmark's average acceleration (gamma 1/2, beta 1/4) on
 * `plastic_substeps` sub-steps per sample. Each sub-step solves the implicit
 * equation (4/h^2) du + mu N Z(du) = r with the radial return map; for a
 * circular surface and isotropic elastic stiffness this has a closed form
 * (below), which is the converged value of the Newton iteration OpenSees'
 * flatSliderBearing runs with a Coulomb friction model.
 *
 * Shared conventions (docs/refmodels.md):
 *  - Floor input piecewise linear between samples; zero after the record
 *    (a_g = a_v = 0 from t_{n-1} on).
 *  - Slip: the part of the relative motion not stored in the spring,
 *    u_p' = u' - U_y Z' / A (smooth) or du_p (plastic). path_m integrates
 *    |u_p'|; a slip interval is where |u_p'| > SL_REF_SLIP_SPEED_MS (a turn
 *    of u_p' by more than 90 degrees between two points also starts a new
 *    one), and counts as an episode once it has slipped
 *    SL_REF_EPISODE_SLIP_UY U_y; t_rest_s is the last instant of a counted
 *    interval. These tend to the
 *    rigid-plastic path, episodes and stop time as U_y -> 0, while |u'|
 *    also carries the elastic ringing of speed up to sqrt(mu N U_y).
 *  - Rest (keep_going): the floor is at rest (N = g) and the elastic orbit
 *    of the block no longer reaches the friction limit: with q = U_y Z and
 *    w^2 = mu g / U_y the unslipping block is an isotropic oscillator whose
 *    largest |Z| follows from its energy and angular momentum (at_rest).
 *    In 1-D this reads |u'|^2 / 2 + mu g U_y Z^2 / 2 <= mu g U_y / 2: the
 *    speed is below sqrt(mu g U_y (1 - Z^2)) and the spring holds. Checked
 *    at each sample; the extension is capped at SL_REF_EXTEND_S + |u'| /
 *    (mu g) after the record (flag SL_SLIDE_NEVER_STOPS when reached).
 */
#include "slide/refmodel.h"
#include "core/gslerr.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- named parameters ------------------------------------------------ */

/* Bouc-Wen shape parameters of the source study (dimensionless). */
#define SL_REF_SMOOTH_A 1.0
#define SL_REF_SMOOTH_BETA 0.5
#define SL_REF_SMOOTH_GAMMA 0.5
/* Accepted exponent range (the study used 20 and 5). */
#define SL_REF_ETA_MIN 2.0
#define SL_REF_ETA_MAX 20.0
/* Accepted yield displacements, m (the study used 1e-7). */
#define SL_REF_UY_MIN_M 1e-9
#define SL_REF_UY_MAX_M 1.0
/* Accepted solver relative tolerance range. */
#define SL_REF_RTOL_MIN 1e-12
#define SL_REF_RTOL_MAX 1e-2
/* |Z| used inside |Z|^(eta-2) is capped here: the physical range is
 * |Z| <= 1; a trial stage of the solver may overshoot, and with the cap
 * the factor stays below 2^18 for eta = 20 (no overflow, still restoring). */
#define SL_REF_SMOOTH_RHO_CAP 2.0
/* First trial step of the ODE solver, s. */
#define SL_REF_SMOOTH_HSTART_S 1e-6
/* Internal solver steps allowed inside one input sample interval; past it
 * the run fails with SL_ESOLVER (an explicit method on a stiff case). */
#define SL_REF_SMOOTH_MAX_STEPS_PER_SAMPLE 200000UL
/* Sub-steps per sample accepted for the plastic model. */
#define SL_REF_PLASTIC_SUBSTEPS_MAX 100000u
/* Slip speed above which the block counts as sliding, m/s (episodes,
 * t_rest_s). Measured against the exact engine on a 20 s 2-D record at
 * U_y = 1e-7: 1e-4 reproduces its episodes within 1-3 and its stop time
 * within 0.05 s; 1e-5 and below count solver chatter as episodes. */
#define SL_REF_SLIP_SPEED_MS 1e-4
/* A slip interval counts as an episode once it has slipped this many U_y:
 * the elastic rebound of a block that has just stopped touches the yield
 * surface and slips by a small fraction of U_y in the smooth model. */
#define SL_REF_EPISODE_SLIP_UY 0.5
/* Rest test (at_rest): margin on the squared largest |Z| of the elastic
 * orbit, and the speed, m/s, below which a block with no friction (mu = 0)
 * counts as at rest. */
#define SL_REF_REST_ORBIT_TOL 1e-3
#define SL_REF_REST_SPEED_MS 1e-9
/* Extension after the record (keep_going): this long plus the time to stop
 * from the end speed at mu g, s. */
#define SL_REF_EXTEND_S 60.0

/* ---- input ------------------------------------------------------------ */

typedef struct feed {
    size_t n;
    double dt, g, sign;
    const double *ax, *ay, *av; /* ay, av may be NULL */
    int d;                      /* 1 or 2 horizontal axes */
} feed;

/* One interval [t0, t0 + dt]: a_x = ax0 + ax1 (t - t0), ..., and the raw
 * normal acceleration g + a_v = nv0 + nv1 (t - t0) (clipped at 0 in use). */
typedef struct seg {
    double t0, ax0, ax1, ay0, ay1, nv0, nv1;
} seg;

static double feed_t(const feed *f, size_t i) { return (double)i * f->dt; }

static double feed_n_at(const feed *f, size_t i)
{
    if (i >= f->n)
        return f->g;
    return fmax(f->g + (f->av ? f->av[i] : 0.0), 0.0);
}

static void feed_seg(const feed *f, size_t i, seg *s)
{
    memset(s, 0, sizeof *s);
    s->t0 = feed_t(f, i);
    s->nv0 = f->g;
    if (i + 1 >= f->n) /* past the record: floor at rest */
        return;
    const double r = 1.0 / f->dt;
    s->ax0 = f->sign * f->ax[i];
    s->ax1 = f->sign * (f->ax[i + 1] - f->ax[i]) * r;
    if (f->ay) {
        s->ay0 = f->sign * f->ay[i];
        s->ay1 = f->sign * (f->ay[i + 1] - f->ay[i]) * r;
    }
    if (f->av) {
        s->nv0 = f->g + f->av[i];
        s->nv1 = (f->av[i + 1] - f->av[i]) * r;
    }
}

/* ---- result tracking ---------------------------------------------------- */

typedef struct track {
    double peak2, t_peak, px, py, vmax2, t_slip;
    double t_prev, t_sliding; /* time of the previous point; time spent slipping */
    double min_slip_m;  /* SL_REF_EPISODE_SLIP_UY * U_y */
    double slip0;       /* slip path when the current slip interval began */
    double w[2];        /* slip velocity at the previous point */
    long episodes;
    int slipping, counted;
} track;

/* Record one (sub)step end: time, displacement u, velocity v, slip velocity
 * w and accumulated slip path. A slip interval begins when |w| rises above
 * SL_REF_SLIP_SPEED_MS, or when w turns by more than 90 degrees from one
 * point to the next (a reversal, i.e. a stop, passed inside the step); it
 * counts as an episode once it has slipped min_slip_m, and t_slip is the
 * last instant of a counted interval. */
static void track_point(track *k, double t, const double u[2], const double v[2],
                        const double w[2], double path)
{
    double m2 = u[0] * u[0] + u[1] * u[1];
    if (m2 > k->peak2) {
        k->peak2 = m2;
        k->t_peak = t;
    }
    k->px = fmax(k->px, fabs(u[0]));
    k->py = fmax(k->py, fabs(u[1]));
    k->vmax2 = fmax(k->vmax2, v[0] * v[0] + v[1] * v[1]);
    int now = hypot(w[0], w[1]) > SL_REF_SLIP_SPEED_MS;
    if (now && k->slipping)
        k->t_sliding += t - k->t_prev;
    k->t_prev = t;
    int reversed = k->slipping && now && w[0] * k->w[0] + w[1] * k->w[1] < 0.0;
    if (now && (!k->slipping || reversed)) { /* a slip interval begins */
        k->slip0 = path;
        k->counted = 0;
    }
    if (now && !k->counted && path - k->slip0 >= k->min_slip_m) {
        k->episodes++;
        k->counted = 1;
    }
    if (now && k->counted)
        k->t_slip = t;
    k->slipping = now;
    k->w[0] = w[0];
    k->w[1] = w[1];
}

/* ---- the models' common state ------------------------------------------ */

typedef struct smooth_par {
    int d;
    double mu, uy, eta;
    seg s; /* the current input interval */
} smooth_par;

typedef struct model {
    sl_model kind;
    int d;
    double mu, uy, g;
    /* current state, both models */
    double t, u[2], v[2], z[2], path;
    /* smooth */
    smooth_par par;
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *drv;
    double y[7], h;
    /* plastic */
    unsigned sub;
    double a[2]; /* relative acceleration at t (Newmark) */
} model;

/* ---- smooth model: right-hand side and Jacobian ------------------------- */

/* P = |Z|^(eta-2) (|Z| capped at SL_REF_SMOOTH_RHO_CAP), S of (R1) and
 * |Z|^2. w = P Z S is the slip velocity u' - U_y Z' / A (A = 1). */
static void smooth_terms(const smooth_par *p, const double *v, const double *z, double *P,
                         double *S, double *rho2)
{
    double r2 = 0.0, s = 0.0;
    for (int j = 0; j < p->d; j++) {
        double q = v[j] * z[j];
        r2 += z[j] * z[j];
        s += SL_REF_SMOOTH_BETA * fabs(q) + SL_REF_SMOOTH_GAMMA * q;
    }
    double pw = 1.0;
    if (p->eta != 2.0) {
        double r2c = fmin(r2, SL_REF_SMOOTH_RHO_CAP * SL_REF_SMOOTH_RHO_CAP);
        pw = r2c > 0.0 ? exp(0.5 * (p->eta - 2.0) * log(r2c)) : 0.0;
    }
    *P = pw;
    *S = s;
    *rho2 = r2;
}

static int smooth_rhs(double t, const double y[], double f[], void *params)
{
    const smooth_par *p = params;
    const int d = p->d;
    const double *v = y + d, *z = y + 2 * d;
    const double x = t - p->s.t0;
    const double ag[2] = {p->s.ax0 + p->s.ax1 * x, p->s.ay0 + p->s.ay1 * x};
    const double muN = p->mu * fmax(p->s.nv0 + p->s.nv1 * x, 0.0);
    double P, S, r2;
    smooth_terms(p, v, z, &P, &S, &r2);
    double w2 = 0.0;
    for (int i = 0; i < d; i++) {
        double w = P * z[i] * S;
        f[i] = v[i];
        f[d + i] = -ag[i] - muN * z[i];
        f[2 * d + i] = (SL_REF_SMOOTH_A * v[i] - w) / p->uy;
        w2 += w * w;
    }
    f[3 * d] = sqrt(w2);
    for (int i = 0; i <= 3 * d; i++)
        if (!isfinite(f[i]))
            return GSL_EBADFUNC;
    return GSL_SUCCESS;
}

/* Analytic Jacobian of smooth_rhs (row-major, n = 3d + 1) and df/dt. */
static int smooth_jac(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
    const smooth_par *p = params;
    const int d = p->d, n = 3 * d + 1;
    const double *v = y + d, *z = y + 2 * d;
    const double x = t - p->s.t0;
    const double nraw = p->s.nv0 + p->s.nv1 * x;
    const double muN = p->mu * fmax(nraw, 0.0);
    const double dmuN = nraw > 0.0 ? p->mu * p->s.nv1 : 0.0;
    const double ag1[2] = {p->s.ax1, p->s.ay1};
    double P, S, r2;
    smooth_terms(p, v, z, &P, &S, &r2);
    /* dP/dZ_j = (eta - 2) P Z_j / |Z|^2 inside the cap, 0 outside */
    double dPf = 0.0;
    if (p->eta != 2.0 && r2 > 0.0 &&
        r2 < SL_REF_SMOOTH_RHO_CAP * SL_REF_SMOOTH_RHO_CAP)
        dPf = (p->eta - 2.0) * P / r2;
    double c[2]; /* dS/dv_j = Z_j c_j, dS/dZ_j = v_j c_j */
    double w[2], dw_dv[2][2], dw_dz[2][2];
    for (int j = 0; j < d; j++) {
        double q = v[j] * z[j];
        c[j] = SL_REF_SMOOTH_BETA * (q > 0.0 ? 1.0 : q < 0.0 ? -1.0 : 0.0) + SL_REF_SMOOTH_GAMMA;
    }
    for (int i = 0; i < d; i++) {
        w[i] = P * z[i] * S;
        for (int j = 0; j < d; j++) {
            dw_dv[i][j] = P * z[i] * z[j] * c[j];
            dw_dz[i][j] = P * z[i] * v[j] * c[j] + dPf * z[j] * z[i] * S + (i == j ? P * S : 0.0);
        }
    }
    memset(dfdy, 0, (size_t)(n * n) * sizeof *dfdy);
    memset(dfdt, 0, (size_t)n * sizeof *dfdt);
    double wn = 0.0;
    for (int i = 0; i < d; i++)
        wn += w[i] * w[i];
    wn = sqrt(wn);
    for (int i = 0; i < d; i++) {
        dfdy[i * n + d + i] = 1.0;                  /* u' = v */
        dfdy[(d + i) * n + 2 * d + i] = -muN;        /* v' = -a_g - mu N Z */
        dfdt[d + i] = -ag1[i] - dmuN * z[i];
        for (int j = 0; j < d; j++) {
            dfdy[(2 * d + i) * n + d + j] =
                ((i == j ? SL_REF_SMOOTH_A : 0.0) - dw_dv[i][j]) / p->uy;
            dfdy[(2 * d + i) * n + 2 * d + j] = -dw_dz[i][j] / p->uy;
            if (wn > 0.0) { /* path' = |w| */
                dfdy[3 * d * n + d + j] += w[i] * dw_dv[i][j] / wn;
                dfdy[3 * d * n + 2 * d + j] += w[i] * dw_dz[i][j] / wn;
            }
        }
    }
    return GSL_SUCCESS;
}

static const gsl_odeiv2_step_type *smooth_step_type(int solver)
{
    switch (solver) {
    case 0: return gsl_odeiv2_step_msbdf;
    case 1: return gsl_odeiv2_step_rk4imp;
    case 2: return gsl_odeiv2_step_bsimp;
    case 3: return gsl_odeiv2_step_rkf45;
    default: return NULL;
    }
}

static void smooth_unpack(model *m)
{
    const int d = m->d;
    for (int i = 0; i < d; i++) {
        m->u[i] = m->y[i];
        m->v[i] = m->y[d + i];
        m->z[i] = m->y[2 * d + i];
    }
    m->path = m->y[3 * d];
}

/* Slip velocity w = P Z S of the current smooth state. */
static void smooth_slip(const model *m, double w[2])
{
    double P, S, r2;
    smooth_terms(&m->par, m->v, m->z, &P, &S, &r2);
    w[0] = P * S * m->z[0];
    w[1] = P * S * m->z[1];
}

static sl_status smooth_init(model *m, const sl_slide_opts *o, sl_error *err)
{
    const int d = m->d, n = 3 * d + 1;
    m->par.d = d;
    m->par.mu = m->mu;
    m->par.uy = m->uy;
    m->par.eta = o->smooth_eta;
    m->sys.function = smooth_rhs;
    m->sys.jacobian = smooth_jac;
    m->sys.dimension = (size_t)n;
    m->sys.params = &m->par;
    /* Absolute tolerance per component: atol (m) on u, atol (m/s) on u',
     * min(atol / U_y, rtol) on Z (atol on the elastic displacement U_y Z,
     * but never looser than rtol on the friction force mu N Z), atol (m) on
     * the path; smooth_rtol relative to |y| on all of them. */
    double scale[7];
    const double ztol = fmin(o->smooth_atol / m->uy, o->smooth_rtol);
    for (int i = 0; i < d; i++) {
        scale[i] = 1.0;
        scale[d + i] = 1.0;
        scale[2 * d + i] = ztol / o->smooth_atol;
    }
    scale[3 * d] = 1.0;
    m->drv = gsl_odeiv2_driver_alloc_scaled_new(&m->sys, smooth_step_type(o->smooth_solver),
                                                SL_REF_SMOOTH_HSTART_S, o->smooth_atol,
                                                o->smooth_rtol, 1.0, 0.0, scale);
    if (!m->drv)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "smooth model: cannot allocate the GSL %s driver",
                            smooth_step_type(o->smooth_solver)->name);
    memset(m->y, 0, sizeof m->y);
    m->h = SL_REF_SMOOTH_HSTART_S;
    return SL_OK;
}

/* Integrate the smooth model over input interval i ([t_i, t_{i+1}]). */
static sl_status smooth_advance(model *m, const feed *f, size_t i, track *k, sl_error *err)
{
    gsl_odeiv2_driver *dr = m->drv;
    feed_seg(f, i, &m->par.s);
    if (i + 1 == f->n && i > 0) {
        /* the input jumps to zero at the record end: restart the multistep
         * history instead of carrying it across the discontinuity */
        int rs = gsl_odeiv2_driver_reset(dr);
        if (rs != GSL_SUCCESS)
            return sl_error_set(err, SL_ESOLVER, NULL, 0,
                                "smooth model: GSL %s reset failed at t = %.6g s: %s",
                                gsl_odeiv2_step_name(dr->s), m->t, gsl_strerror(rs));
    }
    const double t1 = feed_t(f, i + 1);
    if (!(m->h > 0.0) || m->h > f->dt)
        m->h = f->dt;
    unsigned long steps = 0;
    while (m->t < t1) {
        int st = gsl_odeiv2_evolve_apply(dr->e, dr->c, dr->s, &m->sys, &m->t, t1, &m->h, m->y);
        if (st == GSL_SUCCESS && ++steps > SL_REF_SMOOTH_MAX_STEPS_PER_SAMPLE)
            st = GSL_EMAXITER;
        if (st != GSL_SUCCESS)
            return sl_error_set(
                err, SL_ESOLVER, NULL, 0,
                "smooth model: GSL %s failed at t = %.6g s (sample %zu), mu = %g: %s "
                "(step %.3g s, %lu steps in this sample; U_y = %g m, eta = %g)",
                gsl_odeiv2_step_name(dr->s), m->t, i + 1, m->mu,
                st == GSL_EMAXITER ? "too many steps (problem too stiff for this solver?)"
                                   : gsl_strerror(st),
                m->h, steps, m->uy, m->par.eta);
        smooth_unpack(m);
        for (int q = 0; q < 3 * m->d + 1; q++)
            if (!isfinite(m->y[q]))
                return sl_error_set(err, SL_ESOLVER, NULL, 0,
                                    "smooth model: GSL %s produced a non-finite state at "
                                    "t = %.6g s (sample %zu), mu = %g",
                                    gsl_odeiv2_step_name(dr->s), m->t, i + 1, m->mu);
        double w[2];
        smooth_slip(m, w);
        track_point(k, m->t, m->u, m->v, w, m->path);
    }
    m->t = t1;
    return SL_OK;
}

/* ---- plastic model ------------------------------------------------------ */

/* One Newmark average-acceleration step of length h to time t with floor
 * acceleration ag and normal acceleration N (>= 0) at t. Unknown du solves
 *   (4/h^2) du + mu N Z(du) = r,   r = (4/h) v + a - ag,
 * Z(du) = radial return of the trial Z + du / U_y onto |Z| <= 1. With
 * c = 4 U_y / h^2 and w = r + c Z:
 *   |w| <= c + mu N:  elastic, Z' = w / (c + mu N);
 *   otherwise:        Z' = w / |w|, trial length lambda = (|w| - mu N) / c,
 *                     slip du_p = U_y (lambda - 1) Z'.
 * Stores the slip du_p in dup. */
static void plastic_step(model *m, double h, const double ag[2], double N, double dup[2])
{
    const int d = m->d;
    const double c = 4.0 * m->uy / (h * h), muN = m->mu * N;
    double w[2] = {0.0, 0.0}, wn = 0.0, znew[2] = {0.0, 0.0}, slip = 0.0;
    dup[0] = dup[1] = 0.0;
    for (int i = 0; i < d; i++) {
        double r = 4.0 / h * m->v[i] + m->a[i] - ag[i];
        w[i] = r + c * m->z[i];
        wn += w[i] * w[i];
    }
    wn = sqrt(wn);
    if (wn <= c + muN) {
        for (int i = 0; i < d; i++)
            znew[i] = w[i] / (c + muN);
    } else {
        double lam = (wn - muN) / c;
        for (int i = 0; i < d; i++)
            znew[i] = w[i] / wn;
        slip = m->uy * (lam - 1.0);
        for (int i = 0; i < d; i++) {
            m->u[i] += m->uy * (lam * znew[i] - m->z[i]);
            dup[i] = slip * znew[i];
        }
    }
    for (int i = 0; i < d; i++) {
        if (wn <= c + muN)
            m->u[i] += m->uy * (znew[i] - m->z[i]);
        double anew = -ag[i] - muN * znew[i];
        m->v[i] += 0.5 * h * (m->a[i] + anew);
        m->a[i] = anew;
        m->z[i] = znew[i];
    }
    m->path += slip;
}

/* Acceleration consistent with the input at the start of interval i (the
 * input is continuous inside the record, jumps to zero at its end). */
static void plastic_sync_accel(model *m, const seg *s)
{
    const double muN = m->mu * fmax(s->nv0, 0.0);
    const double ag[2] = {s->ax0, s->ay0};
    for (int j = 0; j < m->d; j++)
        m->a[j] = -ag[j] - muN * m->z[j];
}

static sl_status plastic_advance(model *m, const feed *f, size_t i, track *k, sl_error *err)
{
    seg s;
    feed_seg(f, i, &s);
    if (i == 0 || i + 1 == f->n)
        plastic_sync_accel(m, &s);
    const double t0 = feed_t(f, i), h = f->dt / (double)m->sub;
    for (unsigned q = 1; q <= m->sub; q++) {
        double x = (double)q * h;
        double ag[2] = {s.ax0 + s.ax1 * x, s.ay0 + s.ay1 * x};
        double N = fmax(s.nv0 + s.nv1 * x, 0.0);
        double dup[2];
        plastic_step(m, h, ag, N, dup);
        m->t = (q == m->sub) ? feed_t(f, i + 1) : t0 + x;
        const double w[2] = {dup[0] / h, dup[1] / h};
        track_point(k, m->t, m->u, m->v, w, m->path);
    }
    for (int j = 0; j < m->d; j++)
        if (!isfinite(m->u[j]) || !isfinite(m->v[j]))
            return sl_error_set(err, SL_ESOLVER, NULL, 0,
                                "plastic model: non-finite state at t = %.6g s (sample %zu), "
                                "mu = %g",
                                m->t, i + 1, m->mu);
    return SL_OK;
}

/* ---- driver ---------------------------------------------------------------- */

/* Rest on a floor at rest (N = g), see the file comment. Without slip the
 * block is an isotropic oscillator in q = U_y Z with w^2 = mu g / U_y; its
 * orbit is an ellipse whose largest |Z|, r, follows from the energy and the
 * angular momentum (in units of Z):
 *   E = (|Z'|^2 / w^2 + |Z|^2) / 2,  L = (Z x Z') / w,  r^2 = E + sqrt(E^2 - L^2).
 * r <= 1 means the spring never reaches the friction limit again: at rest.
 * (In 1-D, L = 0 and this is E <= the depth of the elastic well.) The
 * trapezoidal rule of the plastic model conserves E, L and the orbit
 * exactly; the smooth model only dissipates. */
static int at_rest(const model *m)
{
    const double w2 = m->mu * m->g / m->uy;
    if (!(w2 > 0.0)) /* no friction: at rest only if not moving */
        return hypot(m->v[0], m->v[1]) <= SL_REF_REST_SPEED_MS;
    const double zd[2] = {m->v[0] / m->uy, m->v[1] / m->uy};
    const double E = 0.5 * ((zd[0] * zd[0] + zd[1] * zd[1]) / w2 +
                            m->z[0] * m->z[0] + m->z[1] * m->z[1]);
    const double L = (m->z[0] * zd[1] - m->z[1] * zd[0]) / sqrt(w2);
    const double r2 = E + sqrt(fmax(E * E - L * L, 0.0));
    return r2 <= 1.0 + SL_REF_REST_ORBIT_TOL;
}

static void hist_put(sl_history *h, const model *m, double N)
{
    size_t i = h->n++;
    double fw = -m->mu * N / m->g; /* F/W = (u'' + a_g) / g = -mu N Z / g */
    h->t_s[i] = m->t;
    h->ux_m[i] = m->u[0];
    h->uy_m[i] = m->u[1];
    h->vx_ms[i] = m->v[0];
    h->vy_ms[i] = m->v[1];
    h->fx_w[i] = fw * m->z[0];
    h->fy_w[i] = fw * m->z[1];
}

static sl_status check_inputs(const sl_set *set, double mu, const sl_slide_opts *o,
                              const sl_slide_result *res, sl_error *err)
{
    if (!set || !set->h1 || !set->h1->acc_ms2 || set->h1->n < 1)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "reference model: no H1 motion");
    if (!o || !res)
        return sl_error_set(err, SL_EINVAL, NULL, 0, "reference model: options and result required");
    const size_t n = set->h1->n;
    const double dt = set->h1->dt_s;
    if (!(dt > 0.0) || !isfinite(dt))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "reference model: dt %g must be > 0", dt);
    const sl_motion *c[3] = {set->h1, set->h2, set->v};
    for (int k = 0; k < 3; k++) {
        if (!c[k])
            continue;
        if (!c[k]->acc_ms2 || c[k]->n != n || fabs(c[k]->dt_s - dt) > 1e-6 * dt)
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "reference model: components differ in length or dt "
                                "(check the set first)");
        for (size_t i = 0; i < n; i++)
            if (!isfinite(c[k]->acc_ms2[i]))
                return sl_error_set(err, SL_EINVAL, NULL, 0,
                                    "reference model: non-finite acceleration at sample %zu", i);
    }
    if (!(mu >= 0.0) || !isfinite(mu))
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "reference model: friction coefficient %g must be finite and >= 0", mu);
    if (!(o->g_ms2 > 0.0) || !isfinite(o->g_ms2))
        return sl_error_set(err, SL_EINVAL, NULL, 0, "reference model: gravity %g must be > 0",
                            o->g_ms2);
    if (o->up_ratio != 1.0)
        return sl_error_set(err, SL_EUNSUPPORTED, NULL, 0,
                            "reference models are symmetric: up_ratio must be 1 (got %g)",
                            o->up_ratio);
    if (o->model == SL_MODEL_SMOOTH) {
        if (!(o->smooth_eta >= SL_REF_ETA_MIN && o->smooth_eta <= SL_REF_ETA_MAX))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "smooth model: eta %g outside [%g, %g]", o->smooth_eta,
                                SL_REF_ETA_MIN, SL_REF_ETA_MAX);
        if (!(o->smooth_uy_m >= SL_REF_UY_MIN_M && o->smooth_uy_m <= SL_REF_UY_MAX_M))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "smooth model: yield displacement %g m outside [%g, %g] m",
                                o->smooth_uy_m, SL_REF_UY_MIN_M, SL_REF_UY_MAX_M);
        if (!(o->smooth_rtol >= SL_REF_RTOL_MIN && o->smooth_rtol <= SL_REF_RTOL_MAX))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "smooth model: rtol %g outside [%g, %g]", o->smooth_rtol,
                                SL_REF_RTOL_MIN, SL_REF_RTOL_MAX);
        if (!(o->smooth_atol > 0.0) || !isfinite(o->smooth_atol))
            return sl_error_set(err, SL_EINVAL, NULL, 0, "smooth model: atol %g must be > 0 (m)",
                                o->smooth_atol);
        if (!smooth_step_type(o->smooth_solver))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "smooth model: solver %d unknown (0 msbdf, 1 rk4imp, 2 bsimp, "
                                "3 rkf45)",
                                o->smooth_solver);
    } else if (o->model == SL_MODEL_PLASTIC) {
        if (!(o->plastic_uy_m >= SL_REF_UY_MIN_M && o->plastic_uy_m <= SL_REF_UY_MAX_M))
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "plastic model: yield displacement %g m outside [%g, %g] m",
                                o->plastic_uy_m, SL_REF_UY_MIN_M, SL_REF_UY_MAX_M);
        if (o->plastic_substeps < 1 || o->plastic_substeps > SL_REF_PLASTIC_SUBSTEPS_MAX)
            return sl_error_set(err, SL_EINVAL, NULL, 0,
                                "plastic model: substeps %u outside [1, %u]",
                                o->plastic_substeps, SL_REF_PLASTIC_SUBSTEPS_MAX);
    } else {
        return sl_error_set(err, SL_EINVAL, NULL, 0,
                            "reference model: model %d is not SMOOTH or PLASTIC", (int)o->model);
    }
    return SL_OK;
}

static sl_status refmodel_run(const sl_set *set, double mu, const sl_slide_opts *opts,
                              sl_slide_result *res, sl_history **hist, sl_error *err)
{
    if (hist)
        *hist = NULL;
    sl_status st = check_inputs(set, mu, opts, res, err);
    if (st)
        return st;

    feed f = {set->h1->n, set->h1->dt_s, opts->g_ms2, opts->invert ? -1.0 : 1.0,
              set->h1->acc_ms2, set->h2 ? set->h2->acc_ms2 : NULL,
              set->v ? set->v->acc_ms2 : NULL, set->h2 ? 2 : 1};
    const int smooth = opts->model == SL_MODEL_SMOOTH;
    model m;
    memset(&m, 0, sizeof m);
    m.kind = opts->model;
    m.d = f.d;
    m.mu = mu;
    m.g = opts->g_ms2;
    m.uy = smooth ? opts->smooth_uy_m : opts->plastic_uy_m;
    m.sub = opts->plastic_substeps;

    memset(res, 0, sizeof *res);
    res->mu = mu;
    if (f.av)
        for (size_t i = 0; i < f.n; i++)
            res->liftoff_samples += (f.g + f.av[i] <= 0.0);
    if (res->liftoff_samples)
        res->flags |= SL_SLIDE_LIFTOFF;

    sl_history *H = NULL;
    if (hist && !(H = sl_history_alloc(f.n, f.dt)))
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "reference model: out of memory (history)");
    if (smooth && (st = smooth_init(&m, opts, err)) != SL_OK) {
        sl_history_free(H);
        return st;
    }

    track k;
    memset(&k, 0, sizeof k);
    k.min_slip_m = SL_REF_EPISODE_SLIP_UY * m.uy;
    const double zero[2] = {0.0, 0.0};
    track_point(&k, 0.0, zero, zero, zero, 0.0);
    if (H)
        hist_put(H, &m, feed_n_at(&f, 0));

    /* Record: intervals 0 .. n-2; then, with keep_going, zero input until
     * rest or the cap. */
    size_t i_end = f.n - 1, i = 0;
    int rest = 0;
    for (;;) {
        if (i >= f.n - 1) { /* at or past the record end: t = t_i */
            if (i == f.n - 1) {
                rest = at_rest(&m);
                if (!rest && opts->keep_going && mu > 0.0) {
                    double sp = hypot(m.v[0], m.v[1]);
                    double T = SL_REF_EXTEND_S + sp / (mu * f.g);
                    i_end = f.n - 1 + (size_t)ceil(T / f.dt);
                    if (H && sl_history_reserve(H, i_end + 1)) {
                        st = sl_error_set(err, SL_ENOMEM, NULL, 0,
                                          "reference model: out of memory (history)");
                        break;
                    }
                }
            } else {
                rest = at_rest(&m);
            }
            if (rest || i >= i_end)
                break;
        }
        st = smooth ? smooth_advance(&m, &f, i, &k, err) : plastic_advance(&m, &f, i, &k, err);
        if (st)
            break;
        i++;
        if (H)
            hist_put(H, &m, feed_n_at(&f, i));
    }
    if (m.drv)
        gsl_odeiv2_driver_free(m.drv);
    if (st) {
        sl_history_free(H);
        return st;
    }
    if (!rest)
        res->flags |= SL_SLIDE_NEVER_STOPS;

    res->peak_m = sqrt(k.peak2);
    res->peak_x_m = k.px;
    res->peak_y_m = k.py;
    res->t_peak_s = k.t_peak;
    res->residual_x_m = m.u[0];
    res->residual_y_m = m.u[1];
    res->residual_m = hypot(m.u[0], m.u[1]);
    res->path_m = m.path;
    res->max_speed_ms = sqrt(k.vmax2);
    res->t_rest_s = rest ? k.t_slip : m.t;
    res->episodes = k.episodes;
    res->slide_time_s = k.t_sliding;
    if (hist)
        *hist = H;
    return SL_OK;
}

/* GSL's error handler is off while the model runs (every GSL return code is
 * checked here) and the caller's is back on return (core/gslerr.h). */
sl_status sl_refmodel_run(const sl_set *set, double mu, const sl_slide_opts *opts,
                          sl_slide_result *res, sl_history **hist, sl_error *err)
{
    sl_gsl_quiet_begin();
    sl_status st = refmodel_run(set, mu, opts, res, hist, err);
    sl_gsl_quiet_end();
    return st;
}
