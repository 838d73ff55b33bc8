/*
 * engine.c - the sliding-block engine (NLTHA), see slide.h and docs/model.md.
 *
 * Two kernels advance a vector of friction coefficients together, time in
 * the outer loop and mu in the inner loop, over structure-of-arrays state:
 *
 *  - kernel_1d: exact for piecewise-linear input. On each input step the
 *    floor acceleration a(s) and the normal acceleration N(s) = g + a_v(s)
 *    are linear in the local time s, so while the block slides in direction
 *    d (= +1 or -1) its acceleration r(s) = -a(s) - d mu_d N(s) is linear and
 *    its velocity quadratic. Stop instants are roots of that quadratic, slip
 *    onsets roots of the linear stick conditions, lift-off instants roots of
 *    the linear N(s). Between events the velocity keeps its sign, so |u| is
 *    monotone and its peak lies on an event or a step end.
 *  - kernel_2d: on `substeps` sub-steps h per input step, from rest the
 *    implicit (Moreau-Jean) velocity projection onto the friction disk:
 *        w = v_n - h a*,   v_{n+1} = w (1 - h mu N* / |w|)  if |w| > h mu N*,
 *                          v_{n+1} = 0                     otherwise,       (2)
 *        u_{n+1} = u_n + h (v_n + v_{n+1}) / 2,
 *    with a* and N* the exact means of the piecewise-linear a and max(N, 0)
 *    over the sub-step; while sliding on, the implicit midpoint rule (3)
 *    with the position correction (4); at a stop or reversal inside the
 *    sub-step, the split step (5). Blocks at rest and held cost one compare.
 *
 * After the record the floor is at rest: a block still sliding decelerates
 * at mu g along a straight line, so the rest of the motion is closed-form
 * (stop after |v|/(mu g), a further v|v|/(2 mu g)).
 */
#include "slide/engine.h"
#include "slide/kernel2d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cap on events (stops, onsets) handled inside one input step for one mu in
 * the exact kernel; real records need a handful at most. Past it the step
 * is finished stuck and the result is flagged (never silently). */
#define EVENTS_PER_STEP_MAX 64

/* Most runs of the 2-D kernel for one block: the first, then reruns with a
 * tighter share of the tolerance while the estimate exceeds it. */
#define SL_SLIDE_ROUNDS_MAX 4

/* A rerun cuts the block's share of the tolerance by (target / (2
 * estimate)) to this power: the estimate falls more slowly than the share
 * (after a cut by target / (2 estimate), estimates of 1.1-2.3 x the target
 * on Loma Prieta Capitola at 751 mu, where 0.5 was aimed at), so a cut to
 * the power 1 needed a second rerun for most blocks; 1.5 saves 2-10 % of
 * the instructions on four records (docs/integrators.md). */
#define SL_SLIDE_RERUN_POWER 1.5

/* Share of the one-sub-step peak taken as the a-priori scale of the
 * tolerance (below 1: that peak may be too large). */
#define SL_SLIDE_SCALE_SHARE 0.5

/* A history tail after the record is sampled at dt for at most this long. */
#define TAIL_MAX_SAMPLES 2000000u /* a longer tail is sampled more coarsely, never cut */

/* ---- input view ------------------------------------------------------ */

typedef struct input {
    size_t n;
    double dt;
    const double *ax, *ay, *av; /* ay, av may be NULL */
    double sign;                /* -1 when inverted */
    double g;
} input;

static input input_of(const sl_set *set, const sl_slide_opts *o)
{
    input in = {set->h1->n, set->h1->dt_s, set->h1->acc_ms2,
                set->h2 ? set->h2->acc_ms2 : NULL, set->v ? set->v->acc_ms2 : NULL,
                o->invert ? -1.0 : 1.0, o->g_ms2};
    return in;
}

static double in_ax(const input *in, size_t i) { return in->sign * in->ax[i]; }
static double in_ay(const input *in, size_t i) { return in->ay ? in->sign * in->ay[i] : 0.0; }
static double in_n(const input *in, size_t i) { return in->g + (in->av ? in->av[i] : 0.0); }

static long count_liftoff(const input *in)
{
    long c = 0;
    if (in->av)
        for (size_t i = 0; i < in->n; i++)
            c += (in_n(in, i) <= 0.0);
    return c;
}

/* ---- history ---------------------------------------------------------- */

/* Samples of a tail of duration T: every dt, or, when that would take more
 * than TAIL_MAX_SAMPLES, a coarser step *step so that the whole tail, to
 * rest, is sampled in TAIL_MAX_SAMPLES (docs/model.md: the history runs
 * until rest). */
static size_t tail_samples(double T, double dt, double *step)
{
    *step = dt;
    if (!(T > 0))
        return 0;
    double m = ceil(T / dt);
    if (m > (double)(TAIL_MAX_SAMPLES - 1)) {
        m = (double)(TAIL_MAX_SAMPLES - 1);
        *step = T / m;
    }
    return (size_t)m + 1;
}

/* Closed-form tail of a block sliding at velocity (vx, vy) on a floor at
 * rest: deceleration mu g along the direction of motion. Samples at t0 + k dt
 * into h until rest, growing h as needed. Returns 0 or -1 (out of memory). */
static int history_tail(sl_history *h, double t0, double dt, double ux, double uy,
                        double vx, double vy, double mu_g, double g)
{
    double sp = hypot(vx, vy);
    if (!(sp > 0) || !(mu_g > 0))
        return 0;
    double T = sp / mu_g, ex = vx / sp, ey = vy / sp;
    double step;
    size_t m = tail_samples(T, dt, &step);
    if (sl_history_reserve(h, h->n + m))
        return -1;
    for (size_t k = 1; k < m; k++) {
        double s = fmin((double)k * step, T);
        double d = sp * s - 0.5 * mu_g * s * s, vs = sp - mu_g * s;
        int moving = s < T;
        sl_history_push(h, t0 + (double)k * step, ux + ex * d, uy + ey * d, ex * vs, ey * vs,
                    moving ? -ex * mu_g / g : 0.0, moving ? -ey * mu_g / g : 0.0);
        if (!moving)
            break;
    }
    return 0;
}

/* ---- threshold ------------------------------------------------------- */

/* The friction force per unit mass sample i needs to hold the block. */
static double demand_at(const input *in, size_t i, double up_ratio)
{
    const double ax = in_ax(in, i);
    return in->ay ? hypot(ax, in_ay(in, i)) : fmax(ax, -ax / up_ratio);
}

/* The smallest mu that holds the block throughout. Between two samples with
 * N > 0 the largest demand / N is at a sample (|a| convex, N linear); a
 * sample with N <= 0 holds nothing, and nor does the interval on either side
 * of it unless the demand is 0 at both of its ends (then a = 0 there). */
static double threshold(const input *in, double up_ratio)
{
    double thr = 0.0;
    for (size_t i = 0; i < in->n; i++) {
        const double demand = demand_at(in, i, up_ratio), N = in_n(in, i);
        if (N <= 0.0) {
            if (demand > 0.0 || (i > 0 && demand_at(in, i - 1, up_ratio) > 0.0) ||
                (i + 1 < in->n && demand_at(in, i + 1, up_ratio) > 0.0))
                return INFINITY;
            continue;
        }
        const double r = demand / N;
        if (r > thr)
            thr = r;
    }
    return thr;
}

double sl_engine_threshold(const sl_set *set, const sl_slide_opts *opts)
{
    input in = input_of(set, opts);
    return threshold(&in, opts->up_ratio);
}

/* ---- exact 1-D kernel ------------------------------------------------- */

/* State of the 1-D kernel, structure of arrays over the active mu. */
typedef struct state1d {
    size_t m;
    double *mu_d, *mu_u;     /* friction against -x and against +x */
    double *u, *v;           /* displacement, velocity */
    signed char *dir;        /* 0 stuck, +1 / -1 sliding direction */
    double *peak, *tpeak, *path, *vmax, *tstop, *tslide;
    long *episodes, *overflow;
} state1d;

/* First s in [lo, hi] where the linear c0 + c1 s is > 0 (INFINITY if none). */
static double first_positive(double c0, double c1, double lo, double hi)
{
    if (c0 + c1 * lo > 0.0)
        return lo;
    if (c1 <= 0.0)
        return INFINITY;
    double s = -c0 / c1;
    if (s < lo)
        s = lo;
    return s <= hi ? s : INFINITY;
}

/* Smallest x in (0, L] where A + B x + C x^2 falls to 0, given A >= 0 and,
 * when A == 0, B >= 0 (the block is starting to move in its direction).
 * Returns INFINITY if none. Stable quadratic formula. */
static double first_stop(double A, double B, double C, double L)
{
    double x = INFINITY;
    if (A <= 0.0) { /* from rest: f = x (B + C x) */
        if (C < 0.0)
            x = -B / C;
        else if (B <= 0.0 && C <= 0.0)
            x = 0.0;
    } else if (C == 0.0) {
        if (B < 0.0)
            x = -A / B;
    } else {
        double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            double q = -0.5 * (B + copysign(sqrt(disc), B));
            double x1 = q / C, x2 = (q != 0.0) ? A / q : INFINITY;
            if (x1 > 0.0)
                x = x1;
            if (x2 > 0.0 && x2 < x)
                x = x2;
        }
    }
    return x <= L ? x : INFINITY;
}

/* Advance element k over a sub-interval [0, H] of an input step starting at
 * time t0, on which a(s) = a0 + da s and N(s) = N0 + dN s >= 0 (N == 0 on a
 * lift-off interval, passed as N0 = dN = 0). Exact. */
static void advance_1d(state1d *S, size_t k, double t0, double H, double a0, double da,
                       double N0, double dN)
{
    const int lift = (N0 == 0.0 && dN == 0.0);
    const double mud = lift ? 0.0 : S->mu_d[k];
    const double muu = lift ? 0.0 : S->mu_u[k];
    const int one_way = isinf(muu);
    double s = 0.0, u = S->u[k], v = S->v[k];
    int dir = S->dir[k];
    for (int ev = 0; s < H; ev++) {
        if (ev >= EVENTS_PER_STEP_MAX) { /* give up on this step: stay stuck */
            S->overflow[k]++;
            v = 0.0;
            dir = 0;
            break;
        }
        if (dir > 0 && one_way) { /* infinite resistance: stops at once */
            v = 0.0;
            dir = 0;
        }
        if (dir == 0) {
            /* stuck: slip toward -x when a > mu_d N, toward +x when -a > mu_u N */
            double sd = first_positive(a0 - mud * N0, da - mud * dN, s, H);
            double su = one_way ? INFINITY : first_positive(-a0 - muu * N0, -da - muu * dN, s, H);
            double so = fmin(sd, su);
            if (!(so <= H)) /* stays stuck to the end of the interval */
                break;
            s = so;
            dir = (sd <= su) ? -1 : +1;
            v = 0.0;
            S->episodes[k]++;
            continue;
        }
        /* sliding in direction dir: r(x) = r0 + r1 x, x = time since s */
        double mus = dir > 0 ? muu : mud;
        double r0 = -(a0 + da * s) - dir * mus * (N0 + dN * s);
        double r1 = -da - dir * mus * dN;
        double L = H - s;
        double A = dir * v, B = dir * r0, C = 0.5 * dir * r1;
        if (A <= 0.0 && B < 0.0)
            B = 0.0; /* at onset the net force is zero up to round-off */
        double x = first_stop(A, B, C, L);
        double xe = (x <= L) ? x : L;
        /* fastest instant: r(x) = 0 inside (0, xe) */
        if (r1 != 0.0) {
            double xm = -r0 / r1;
            if (xm > 0.0 && xm < xe) {
                double vm = fabs(v + r0 * xm + 0.5 * r1 * xm * xm);
                if (vm > S->vmax[k])
                    S->vmax[k] = vm;
            }
        }
        double du = v * xe + 0.5 * r0 * xe * xe + r1 * xe * xe * xe / 6.0;
        S->tslide[k] += xe;
        u += du;
        S->path[k] += fabs(du);
        s += xe;
        if (x <= L) {
            v = 0.0;
            dir = 0;
            S->tstop[k] = t0 + s;
        } else {
            v += r0 * xe + 0.5 * r1 * xe * xe;
            if (fabs(v) > S->vmax[k])
                S->vmax[k] = fabs(v);
        }
        if (fabs(u) > S->peak[k]) {
            S->peak[k] = fabs(u);
            S->tpeak[k] = t0 + s;
        }
    }
    S->u[k] = u;
    S->v[k] = v;
    S->dir[k] = (signed char)dir;
}

/* Friction force over weight at the end of a step, for the history. */
static double fw_1d(const state1d *S, size_t k, double a, double N, double g)
{
    if (N <= 0.0)
        return 0.0;
    if (S->dir[k] == 0)
        return a / g; /* stuck: the block moves with the floor */
    double mus = S->dir[k] > 0 ? S->mu_u[k] : S->mu_d[k];
    return -S->dir[k] * mus * N / g;
}

static void kernel_1d(const input *in, state1d *S, sl_history *hist)
{
    const double dt = in->dt, g = in->g;
    for (size_t i = 0; i + 1 < in->n; i++) {
        const double t0 = (double)i * dt;
        const double a0 = in_ax(in, i), a1 = in_ax(in, i + 1);
        const double n0 = in_n(in, i), n1 = in_n(in, i + 1);
        const double da = (a1 - a0) / dt, dn = (n1 - n0) / dt;
        /* split the step where N crosses zero (lift-off begins or ends) */
        double cut = dt;
        if ((n0 > 0.0) != (n1 > 0.0))
            cut = fmin(fmax(-n0 / dn, 0.0), dt);
        for (size_t k = 0; k < S->m; k++) {
            /* fast path: stuck and held at both ends (the stick conditions are
             * linear in time, so holding at both ends holds throughout) */
            if (S->dir[k] == 0 && n0 > 0.0 && n1 > 0.0 && a0 <= S->mu_d[k] * n0 &&
                a1 <= S->mu_d[k] * n1 && -a0 <= S->mu_u[k] * n0 && -a1 <= S->mu_u[k] * n1)
                continue;
            if (cut >= dt) {
                if (n0 > 0.0 || n1 > 0.0)
                    advance_1d(S, k, t0, dt, a0, da, n0, dn);
                else
                    advance_1d(S, k, t0, dt, a0, da, 0.0, 0.0);
            } else {
                if (n0 > 0.0)
                    advance_1d(S, k, t0, cut, a0, da, n0, dn);
                else
                    advance_1d(S, k, t0, cut, a0, da, 0.0, 0.0);
                const double ac = a0 + da * cut, nc = fmax(n0 + dn * cut, 0.0);
                if (n1 > 0.0)
                    advance_1d(S, k, t0 + cut, dt - cut, ac, da, nc, dn);
                else
                    advance_1d(S, k, t0 + cut, dt - cut, ac, da, 0.0, 0.0);
            }
        }
        if (hist)
            sl_history_push(hist, t0 + dt, S->u[0], 0.0, S->v[0], 0.0, fw_1d(S, 0, a1, n1, g), 0.0);
    }
}

static void result_init(sl_slide_result *r, double mu, long liftoff)
{
    memset(r, 0, sizeof *r);
    r->mu = mu;
    r->liftoff_samples = liftoff;
    if (liftoff)
        r->flags |= SL_SLIDE_LIFTOFF;
}

/* Finish a result after the record: closed-form deceleration to rest. */
static void finish(sl_slide_result *r, double t_end, double t_stop, double ux, double uy,
                   double vx, double vy, double mu_stop_g, int keep_going)
{
    double sp = hypot(vx, vy);
    r->t_rest_s = sp > 0.0 ? t_end : t_stop;
    if (sp > 0.0 && keep_going) {
        if (mu_stop_g > 0.0) {
            double T = sp / mu_stop_g, d = 0.5 * sp * T;
            if (isinf(mu_stop_g)) {
                T = 0.0;
                d = 0.0;
            }
            ux += vx / sp * d;
            uy += vy / sp * d;
            r->path_m += d;
            r->slide_time_s += T;
            r->t_rest_s = t_end + T;
        } else {
            r->flags |= SL_SLIDE_NEVER_STOPS;
        }
    } else if (sp > 0.0) {
        r->flags |= SL_SLIDE_NEVER_STOPS;
    }
    double mag = hypot(ux, uy);
    if (mag > r->peak_m) { /* straight-line tail: |u| is convex, peak at its end */
        r->peak_m = mag;
        r->t_peak_s = r->t_rest_s;
    }
    r->peak_x_m = fmax(r->peak_x_m, fabs(ux));
    r->peak_y_m = fmax(r->peak_y_m, fabs(uy));
    r->residual_x_m = ux;
    r->residual_y_m = uy;
    r->residual_m = mag;
}

/* Result of one 2-D block: the closed-form tail after the record, and the
 * error estimate of the peak: the kernel's, plus the tail's share of the
 * velocity error, d(v^2/(2 mu g)) = |v| dv/(mu g), when the peak is there. */
static void fill_2d(sl_slide_result *r, const sl_k2_out *q, double mu_g, double t_end,
                    int keep_going)
{
    r->peak_m = q->peak_m;
    r->t_peak_s = q->t_peak_s;
    r->peak_x_m = q->peak_x_m;
    r->peak_y_m = q->peak_y_m;
    r->path_m = q->path_m;
    r->max_speed_ms = q->max_speed_ms;
    r->slide_time_s = q->slide_time_s;
    r->episodes = q->episodes;
    finish(r, t_end, q->t_stop_s, q->ux, q->uy, q->vx, q->vy, mu_g, keep_going);
    const double sp = hypot(q->vx, q->vy);
    r->err_est_m = q->err_m;
    if (r->peak_m > q->peak_m) /* the peak is at the end of the tail */
        r->err_est_m = q->err_end_m + (mu_g > 0.0 ? sp * q->err_v_ms / mu_g : 0.0);
}

/* The 2-D kernel over the active blocks, then again, with a tighter share
 * of the tolerance, for those whose estimate exceeds max(rtol peak, atol). */
static sl_status run_2d(const input *in, const double *mu, const size_t *act, size_t m,
                        const sl_slide_opts *o, sl_slide_result *res, sl_history *hist,
                        double t_end, sl_error *err)
{
    const sl_k2_motion km = {in->n, in->dt, in->g, in->sign, in->ax, in->ay, in->av};
    const sl_k2_opts ko = {o->substeps, o->rtol, o->atol_m};
    double *mus = malloc(5 * m * sizeof *mus), *eta = mus ? mus + m : NULL,
           *eta_all = mus ? mus + 2 * m : NULL, *scale = mus ? mus + 3 * m : NULL,
           *scale_all = mus ? mus + 4 * m : NULL;
    sl_k2_out *q = malloc(m * sizeof *q);
    size_t *idx = malloc(m * sizeof *idx);
    sl_status st = SL_OK;
    if (!mus || !q || !idx) {
        st = sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
        goto done;
    }
    for (size_t j = 0; j < m; j++) {
        mus[j] = mu[act[j]];
        eta_all[j] = SL_K2_ETA;
        idx[j] = j;
    }
    if (o->substeps == 0) {
        /* the scale of each peak, for the tolerance, from one sub-step per
         * sample (cheap; within a few % on records) */
        const sl_k2_opts k1 = {1, o->rtol, o->atol_m};
        if (sl_kernel2d_run(&km, mus, NULL, NULL, m, &k1, q, NULL)) {
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
            goto done;
        }
        for (size_t j = 0; j < m; j++) {
            sl_slide_result R;
            result_init(&R, mu[act[j]], 0);
            fill_2d(&R, &q[j], mu[act[j]] * in->g, t_end, o->keep_going);
            scale_all[j] = SL_SLIDE_SCALE_SHARE * R.peak_m;
        }
    } else {
        for (size_t j = 0; j < m; j++)
            scale_all[j] = 0.0;
    }
    size_t nr = m;
    for (int round = 0; nr > 0; round++) {
        for (size_t r = 0; r < nr; r++) {
            eta[r] = eta_all[idx[r]];
            scale[r] = scale_all[idx[r]];
            mus[r] = mu[act[idx[r]]];
        }
        if (hist)
            hist->n = 1; /* the history restarts with the run */
        if (sl_kernel2d_run(&km, mus, eta, scale, nr, &ko, q, hist)) {
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
            goto done;
        }
        size_t nn = 0;
        for (size_t r = 0; r < nr; r++) {
            const size_t j = idx[r];
            sl_slide_result *R = &res[act[j]];
            const long liftoff = R->liftoff_samples;
            result_init(R, mu[act[j]], liftoff);
            fill_2d(R, &q[r], mu[act[j]] * in->g, t_end, o->keep_going);
            const double target = fmax(o->rtol * R->peak_m, o->atol_m);
            if (o->substeps == 0 && R->err_est_m > target && round < SL_SLIDE_ROUNDS_MAX) {
                eta_all[j] *= pow(0.5 * target / R->err_est_m, SL_SLIDE_RERUN_POWER);
                scale_all[j] = R->peak_m; /* now known to the tolerance */
                idx[nn++] = j;
            }
        }
        if (hist && nn == 0 &&
            history_tail(hist, t_end, in->dt, q[0].ux, q[0].uy, q[0].vx, q[0].vy,
                         mus[0] * in->g, in->g))
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
        nr = nn;
    }
done:
    free(mus);
    free(q);
    free(idx);
    return st;
}

sl_status sl_engine_run(const sl_set *set, const double *mu, size_t n_mu,
                        const sl_slide_opts *o, sl_slide_result *res, sl_history **hist_out,
                        sl_error *err)
{
    const input inv = input_of(set, o);
    const input *in = &inv;
    const long liftoff = count_liftoff(in);
    const double thr = threshold(in, o->up_ratio);
    const double t_end = (double)(in->n - 1) * in->dt;
    size_t *act = malloc((n_mu ? n_mu : 1) * sizeof *act);
    if (!act)
        return sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
    size_t m = 0;
    for (size_t k = 0; k < n_mu; k++) {
        result_init(&res[k], mu[k], liftoff);
        if (mu[k] >= thr && !hist_out)
            res[k].flags |= SL_SLIDE_SKIPPED; /* cannot slide: nothing to integrate */
        else
            act[m++] = k;
    }
    sl_history *hist = NULL;
    if (hist_out) {
        /* worst case tail: the fastest the block can go, stopping at mu g */
        hist = sl_history_alloc(in->n, in->dt); /* the tail grows it when needed */
        if (!hist) {
            free(act);
            return sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
        }
        sl_history_push(hist, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    }
    sl_status st = SL_OK;
    if (m > 0 && !in->ay) {
        state1d S = {.m = m};
        double *buf = calloc(12 * m, sizeof *buf);
        S.dir = calloc(m, 1);
        S.episodes = calloc(2 * m, sizeof(long));
        if (!buf || !S.dir || !S.episodes) {
            st = sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
        } else {
            S.mu_d = buf;
            S.mu_u = buf + m;
            S.u = buf + 2 * m;
            S.v = buf + 3 * m;
            S.peak = buf + 4 * m;
            S.tpeak = buf + 5 * m;
            S.path = buf + 6 * m;
            S.vmax = buf + 7 * m;
            S.tstop = buf + 8 * m;
            S.tslide = buf + 9 * m;
            S.overflow = S.episodes + m;
            for (size_t j = 0; j < m; j++) {
                S.mu_d[j] = mu[act[j]];
                S.mu_u[j] = isinf(o->up_ratio) ? INFINITY : mu[act[j]] * o->up_ratio;
            }
            kernel_1d(in, &S, hist);
            for (size_t j = 0; j < m; j++) {
                sl_slide_result *r = &res[act[j]];
                r->peak_m = S.peak[j];
                r->t_peak_s = S.tpeak[j];
                r->peak_x_m = S.peak[j];
                r->path_m = S.path[j];
                r->max_speed_ms = S.vmax[j];
                r->slide_time_s = S.tslide[j];
                r->episodes = S.episodes[j];
                double mus = S.v[j] > 0.0 ? S.mu_u[j] : S.mu_d[j];
                finish(r, t_end, S.tstop[j], S.u[j], 0.0, S.v[j], 0.0, mus * in->g, o->keep_going);
                if (S.overflow[j])
                    st = sl_error_set(err, SL_ENOCONV, NULL, 0,
                                      "slide: more than %d stick-slip events in one step "
                                      "at mu = %g",
                                      EVENTS_PER_STEP_MAX, mu[act[j]]);
            }
            if (hist && m == 1 &&
                history_tail(hist, t_end, in->dt, S.u[0], 0.0, S.v[0], 0.0,
                             (S.v[0] > 0.0 ? S.mu_u[0] : S.mu_d[0]) * in->g, in->g))
                st = sl_error_set(err, SL_ENOMEM, NULL, 0, "slide: out of memory");
        }
        free(buf);
        free(S.dir);
        free(S.episodes);
    } else if (m > 0) {
        st = run_2d(in, mu, act, m, o, res, hist, t_end, err);
    }
    free(act);
    if (hist_out) {
        if (st == SL_OK)
            *hist_out = hist;
        else
            sl_history_free(hist);
    }
    return st;
}
