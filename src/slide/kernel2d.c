/*
 * kernel2d.c - the error-controlled 2-D (+ vertical) Coulomb kernel
 * (kernel2d.h, docs/integrators.md).
 *
 * One step of length h over which the forcing is linear in time, from
 * velocity v_n, with h a* and h N* the exact integrals of a_h and max(N, 0)
 * over the step and f = mu h N*:
 *
 *   from rest, the implicit (Moreau-Jean) projection onto the friction disk
 *     w = -h a*,  v_{n+1} = w (1 - f/|w|) if |w| > f, else 0          (2)
 *   sliding on, the implicit midpoint rule (friction along v_n + v_{n+1}):
 *     y = 2 v_n - h a*,  v_{n+1} = y (1 - f/|y|) - v_n                 (3)
 *   (which is (2) when v_n = 0), kept while v_{n+1} . v_n > 0 and the
 *   speed along e = v_n/|v_n| with friction held along e stays positive,
 *   |v_n| > h a*.e + f (else the block may stop inside the step);
 *   position by the trapezoid plus the exact correction for a linear a and
 *   a constant friction force:
 *     u_{n+1} = u_n + h (v_n + v_{n+1})/2 + h^2/12 (a_1 - a_0)           (4)
 *   at a stop or reversal inside the step, the split step: slide along the
 *   old direction e until the speed along e vanishes at tau; if the speed
 *   left across e is small (a stop, not a turn: |v(tau)| <= c |v_n|, c =
 *   SL_K2_STOP_REMNANT) and friction holds the block there
 *   (|a(tau)| <= mu N(tau)), it is at rest until the
 *   exact onset instant (the root of |a|^2 = (mu N)^2, a quadratic), else
 *   (2) over the rest of the step                                       (5)
 *   a block can stop in a sample only if the lower bound of its speed
 *     g(t) = s0 - int_0^t (a(s).e0 + mu max(N(s), 0)) ds <= |v(t)|
 *   (s0, e0 its speed and direction at the start) reaches 0 on [0, dt]:
 *   friction acts along v, so the speed along e0 falls at most at that
 *   rate; with a linear and max(N, 0) under its chord, g is a quadratic (6)
 *
 * Error control (substeps == 0): on every sample, each sliding block takes
 * one step of dt and two of dt/2 with (3)-(4), all blocks together in
 * branch-free loops over packed arrays (the compiler vectorises them). The
 * difference of the two is the local error estimate (step doubling,
 * Richardson: the error of the two half steps is about a third of it where
 * the solution is smooth, equal to it at a stop). Blocks whose difference
 * |du| + T_V |dv| exceeds their share eta max(rtol peak, atol), whose
 * step needs (5), or that can stop within the sample (6), are redone
 * (refine_all) with 1, 2, 4, ... sub-steps (a block that can stop from
 * SL_K2_NEAR_STOP_SUB; a block sent by the tolerance
 * alone from the vector pass's two half steps, level 2) until two
 * successive levels agree: the sliding ones level by level, every block
 * due at one sub-step count advanced together in one vector pass per
 * sub-step (level_vector, levelrun_pass: (3)-(4) with the bookkeeping of
 * fstep), a block whose sub-step needs (5) finishing that level alone with
 * the full step (2)-(5) (run_from); a block at rest alone from its exact
 * onset (refine_onset). Fixed sub-steps take the same level passes. Per
 * sample, sl_kernel2d_run finds the blocks that can move (find_live: one
 * bisection in mu order and the set of sliding blocks), packs them (pack),
 * takes the vector pass (step), unpacks the accepted (accept), refines the
 * rest (refine_all), updates the sliding set (update_sliding) and records
 * block 0's history (push_history). The accepted differences
 * accumulate into the error estimate of the peak: position differences add,
 * and a velocity difference adds dt per sample until the block stops
 * (friction is monotone, so velocity differences do not grow).
 */
#include "slide/kernel2d.h"
#include "slide/kernel2d_step.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Most sub-steps one sample is cut into by the refinement. */
#define NSUB_MAX 4096u
/* refine_all steps through the levels 1, 2, 4, ... NSUB_MAX: a block must start at one of them */
_Static_assert((SL_K2_NEAR_STOP_SUB & (SL_K2_NEAR_STOP_SUB - 1u)) == 0 &&
                   SL_K2_NEAR_STOP_SUB <= NSUB_MAX,
               "SL_K2_NEAR_STOP_SUB must be a power of two, at most NSUB_MAX");
_Static_assert(SL_K2_ONSET_SUB >= 1u && SL_K2_ONSET_SUB <= NSUB_MAX,
               "SL_K2_ONSET_SUB must lie in 1..NSUB_MAX");

/* The unified step (3)-(4), branch-free: from rest it is (2). bad is set
 * when the step needs the split (5). Inlined into the vector loops. */
VECTOR_PASS static inline void ustep(double *vx, double *vy, double *ux, double *uy, double *bad,
                         double hax, double hay, double f, double cx, double cy, double h)
{
    /* every value is computed on every path and only selected, so the
     * compiler can turn the loop into vector code (no traps to guard) */
    const double vx0 = *vx, vy0 = *vy;
    const double yx = 2.0 * vx0 - hax, yy = 2.0 * vy0 - hay;
    const double yn = sqrt(yx * yx + yy * yy);
    const double s1 = 1.0 - f / (yn > 1e-300 ? yn : 1e-300);
    const double s = yn > f ? s1 : 0.0;
    const double mx = yx * s - vx0, my = yy * s - vy0;
    const double v2 = vx0 * vx0 + vy0 * vy0, L = v2 - (hax * vx0 + hay * vy0);
    /* 1.0/0.0 masks rather than ints and branches: they vectorise */
    const double rest = v2 == 0.0 ? 1.0 : 0.0;
    const double fwd = ((mx * vx0 + my * vy0) > 0.0 ? 1.0 : 0.0) * (L > 0.0 ? 1.0 : 0.0) *
                       (L * L > f * f * v2 ? 1.0 : 0.0);
    const double dux = 0.5 * h * (vx0 + mx) + cx, duy = 0.5 * h * (vy0 + my) + cy;
    const double mv = s > 0.0 ? 1.0 : 0.0;
    *bad = rest + fwd > 0.0 ? *bad : 1.0;
    *ux += mv * dux;
    *uy += mv * duy;
    *vx = mx;
    *vy = my;
}

/* Function multiversioning by hand (GCC, x86-64), as the oscillator bank
 * (signal/spectrum.c): the two vector passes below are written once (K2_BODY,
 * always inlined) and compiled twice, for AVX2 (4 doubles a vector) and for
 * the baseline (SSE2, 2 doubles); the AVX2 instance runs when the CPU has
 * it. Without FMA contraction (-ffp-contract=off) both do the same IEEE
 * operations in the same order: the same bits (tests/test_slide.c
 * test_engine_instances_same_bits). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SL_K2_AVX2 1
#endif
#define K2_BODY VECTOR_PASS static inline __attribute__((always_inline))

/* Set by sl_kernel2d_baseline(): the baseline instance even on an AVX2 CPU. */
static int k2_force_baseline;

int sl_kernel2d_baseline(int on)
{
    const int was = k2_force_baseline;
    k2_force_baseline = on != 0;
    return was;
}

int sl_kernel2d_avx2(void)
{
#ifdef SL_K2_AVX2
    return !k2_force_baseline && __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

/* NAME_pass(a): NAME_body as the AVX2 or the baseline instance, its
 * arguments unpacked from the struct *a of type TYPE by UNPACK (one pointer
 * a call: the 23-31 arguments of a pass cost about 100 instructions a call
 * when passed one by one, more than the pass itself on a few blocks; the
 * body's restrict parameters still tell the compiler the rows are apart). */
#ifdef SL_K2_AVX2
#define K2_INSTANCES(name, type, unpack)                                                         \
    VECTOR_PASS static void name##_base(const type *a) { name##_body unpack; }                    \
    __attribute__((target("avx2"))) VECTOR_PASS static void name##_avx2(const type *a)           \
    {                                                                                             \
        name##_body unpack;                                                                       \
    }                                                                                             \
    static void name##_pass(const type *a)                                                        \
    {                                                                                             \
        if (sl_kernel2d_avx2())                                                                   \
            name##_avx2(a);                                                                       \
        else                                                                                      \
            name##_base(a);                                                                       \
    }
#else
#define K2_INSTANCES(name, type, unpack)                                                         \
    static void name##_pass(const type *a) { name##_body unpack; }
#endif

/* Packed working arrays of the live blocks of one sample. */
enum { P_MU, P_TOL, P_UX, P_UY, P_VX, P_VY, P_CUX, P_CUY, P_CVX, P_CVY, P_BAD, P_PK2, P_D, P_DUX,
       P_DUY, P_DVX, P_DVY, P_NS, P_N };

/* The arguments of doubling_pass: the na packed blocks (rows of m in P),
 * the forcing of the whole sample (Fc) and of its halves (Fa, Fb). */
typedef struct doubling_args {
    size_t na, m;
    const force *Fc, *Fa, *Fb;
    const sample *smp;
    double *P;
} doubling_args;

/* The vector pass over the na packed sliding blocks of one sample: one step
 * (3)-(4) of dt (Fc) against two of dt/2 (Fa, Fb), the local differences,
 * the in-sample peak, and the flag pd (1: redo alone). Separate arrays
 * declared restrict here, so the compiler vectorises both loops. */
#define DOUBLING_PARAMS                                                                           \
    (size_t na, const force *Fc, const force *Fa, const force *Fb, const sample *smp,              \
     const double *restrict pmu, const double *restrict ptol, double *restrict pux,               \
     double *restrict puy, double *restrict pvx, double *restrict pvy, double *restrict cux,      \
     double *restrict cuy, double *restrict cvx, double *restrict cvy, double *restrict pbad,     \
     double *restrict ppk2, double *restrict pd, double *restrict pdux, double *restrict pduy,    \
     double *restrict pdvx, double *restrict pdvy, double *restrict pns)
#define DOUBLING_UNPACK                                                                           \
    (a->na, a->Fc, a->Fa, a->Fb, a->smp, a->P + P_MU * a->m, a->P + P_TOL * a->m,                 \
     a->P + P_UX * a->m, a->P + P_UY * a->m, a->P + P_VX * a->m, a->P + P_VY * a->m,              \
     a->P + P_CUX * a->m, a->P + P_CUY * a->m, a->P + P_CVX * a->m, a->P + P_CVY * a->m,          \
     a->P + P_BAD * a->m, a->P + P_PK2 * a->m, a->P + P_D * a->m, a->P + P_DUX * a->m,            \
     a->P + P_DUY * a->m, a->P + P_DVX * a->m, a->P + P_DVY * a->m, a->P + P_NS * a->m)
K2_BODY void doubling_body DOUBLING_PARAMS
{
    /* one step of dt against two of dt/2, every live block at once */
    const double c_ax = Fc->hax, c_ay = Fc->hay, c_n = Fc->hN, c_cx = Fc->cx, c_cy = Fc->cy,
                 c_h = Fc->h;
    const double a_ax = Fa->hax, a_ay = Fa->hay, a_n = Fa->hN, a_cx = Fa->cx, a_cy = Fa->cy,
                 a_h = Fa->h;
    const double b_ax = Fb->hax, b_ay = Fb->hay, b_n = Fb->hN, b_cx = Fb->cx, b_cy = Fb->cy,
                 b_h = Fb->h;
    const double dt = smp->dt, p0 = smp->n0 > 0.0 ? smp->n0 : 0.0, p1 = smp->n1 > 0.0 ? smp->n1 : 0.0;
    const double ax0 = smp->ax0, ay0 = smp->ay0, ax1 = smp->ax1, ay1 = smp->ay1;
    for (size_t j = 0; j < na; j++) {
        double vx = pvx[j], vy = pvy[j], ux = pux[j], uy = puy[j], bad = 0.0;
        ustep(&vx, &vy, &ux, &uy, &bad, c_ax, c_ay, c_n * pmu[j], c_cx, c_cy, c_h);
        cux[j] = ux;
        cuy[j] = uy;
        cvx[j] = vx;
        cvy[j] = vy;
        pbad[j] = bad;
    }
    for (size_t j = 0; j < na; j++) {
        double vx = pvx[j], vy = pvy[j], ux = pux[j], uy = puy[j], bad = pbad[j];
        const double r0 = ux * ux + uy * uy;
        ustep(&vx, &vy, &ux, &uy, &bad, a_ax, a_ay, a_n * pmu[j], a_cx, a_cy, a_h);
        const double uxm = ux, uym = uy, vxm = vx, vym = vy;
        const double rm = ux * ux + uy * uy;
        ustep(&vx, &vy, &ux, &uy, &bad, b_ax, b_ay, b_n * pmu[j], b_cx, b_cy, b_h);
        const double r1 = ux * ux + uy * uy;
        /* in-step maxima of |u|^2 (track_peak) on both halves */
        const double q0 = pux[j] * pvx[j] + puy[j] * pvy[j], qm = uxm * vxm + uym * vym,
                     q1 = ux * vx + uy * vy;
        const double ha_v = r0 + q0 * a_h * q0 / (q0 - qm > 1e-300 ? q0 - qm : 1e-300);
        const double hb_v = rm + qm * b_h * qm / (qm - q1 > 1e-300 ? qm - q1 : 1e-300);
        const double ha = (q0 > 0.0 ? 1.0 : 0.0) * (qm < 0.0 ? ha_v : 0.0);
        const double hb = (qm > 0.0 ? 1.0 : 0.0) * (q1 < 0.0 ? hb_v : 0.0);
        ppk2[j] = max2(max2(rm, r1), max2(ha, hb));
        const double dux = ux - cux[j], duy = uy - cuy[j];
        const double dvx = vx - cvx[j], dvy = vy - cvy[j];
        const double eu = sqrt(dux * dux + duy * duy), ev = sqrt(dvx * dvx + dvy * dvy);
        pdux[j] = dux;
        pduy[j] = duy;
        pdvx[j] = dvx;
        pdvy[j] = dvy;
        /* can the block stop in the sample (6)? Its speed along its start
         * direction e0 falls at most at the rate c(t) = a(t).e0 + mu max(N, 0)
         * (friction along v, |v^.e0| <= 1), so |v(t)| >= v(t).e0 >= g(t) =
         * s0 - int_0^t c; c is at most linear in t (max(N, 0) lies under the
         * chord of its end values), g is then quadratic, and a stop or a
         * pass through zero speed needs min g <= 0 on [0, dt] ((5) and the
         * halving then find it). From rest (s0 = 0) it is always possible. */
        const double s0 = sqrt(pvx[j] * pvx[j] + pvy[j] * pvy[j]);
        const double is0 = 1.0 / (s0 > 1e-300 ? s0 : 1e-300);
        const double c0 = (ax0 * pvx[j] + ay0 * pvy[j]) * is0 + pmu[j] * p0;
        const double c1 = (ax1 * pvx[j] + ay1 * pvy[j]) * is0 + pmu[j] * p1;
        const double g_end = s0 - 0.5 * dt * (c0 + c1);
        /* g falls while c > 0 (g' = -c): its least value on [0, dt] is at
         * the end, or at tv where c falls through 0 inside the sample (else
         * tv = 0 and g(tv) = s0) */
        const double dip = c0 > 0.0 && c1 < 0.0 ? 1.0 : 0.0;
        const double tv = dip * c0 * dt / (c0 - c1 > 1e-300 ? c0 - c1 : 1e-300);
        const double g_v = s0 - 0.5 * c0 * tv; /* g(tv): c(tv) = 0 makes dc tv / dt = -c0 */
        /* a speed so small that its square underflows has no direction */
        const double near_stop = min2(g_v, g_end) <= 0.0 || s0 < 1e-150 ? 1.0 : 0.0;
        const double within = eu + SL_K2_TV * ev <= ptol[j] ? 1.0 : 0.0;
        pd[j] = within * (near_stop == 0.0 ? 1.0 : 0.0) > 0.0 ? bad : 1.0;
        pns[j] = near_stop;
        pux[j] = ux;
        puy[j] = uy;
        cux[j] = vxm; /* reused: mid-sample velocity, for the path */
        cuy[j] = vym;
        pvx[j] = vx;
        pvy[j] = vy;
    }
}

K2_INSTANCES(doubling, doubling_args, DOUBLING_UNPACK)

/* Signed error estimates of one block: position (ex, ey), velocity (wx, wy)
 * and |position error| when the peak was last raised. */
typedef struct errv {
    double ex, ey, wx, wy, at_peak;
} errv;

/* Add the local differences of one accepted sample: a velocity difference
 * shifts the position by dt per sample until the block stops (friction is
 * monotone: velocity differences do not grow). */
static void err_add(errv *e, double dux, double duy, double dvx, double dvy, double dt,
                    int raised_peak)
{
    e->wx += dvx;
    e->wy += dvy;
    e->ex += dux + e->wx * dt;
    e->ey += duy + e->wy * dt;
    if (raised_peak)
        e->at_peak = sqrt(e->ex * e->ex + e->ey * e->ey);
}

/* The working state of one run: every block, its error estimate, and the
 * packed arrays of the live blocks of the current sample (P_N rows of m). */
/* The rows of the packed state of a level (level_vector): the blk fields
 * but the episodes. */
enum { S_UX, S_UY, S_VX, S_VY, S_SP, S_PK2, S_TPK, S_PX, S_PY, S_PATH, S_VM2, S_TSL, S_TST, S_N };

/* Packed rows of the blocks one level of sub-steps advances together
 * (level_vector): friction, the flag of a block whose sub-step needs the
 * split step (5), then two banks of S_N state rows (each sub-step reads one
 * and writes the other). */
enum { Q_MU, Q_BAD, Q_BANK, Q_N = Q_BANK + 2 * S_N };

/* A sliding block being refined: packed index j, block k, the sub-step
 * count of its next level (0 when done), and the previous level's answer. */
typedef struct rq {
    size_t j, k;
    unsigned lev;
    int has_a;
    double ax, ay, avx, avy;
} rq;

typedef struct k2_work {
    size_t m;
    blk *B;
    errv *E;
    double *P, *Q;
    size_t *live, *redo, *qk, *qs;
    long *refined;
    blk *C;  /* the answers of one level, by refinement entry */
    rq *R;   /* the sliding blocks being refined in this sample */
    /* find_live: the blocks by increasing mu (rank[k] = position of k), and
     * the set of sliding blocks (slpos[k] its slot in sl, or SIZE_MAX) */
    size_t *order, *rank, *sl, *slpos, nsl;
} k2_work;

static void work_free(k2_work *w)
{
    free(w->B);
    free(w->E);
    free(w->P);
    free(w->Q);
    free(w->live);
    free(w->redo);
    free(w->qk);
    free(w->qs);
    free(w->refined);
    free(w->C);
    free(w->R);
    free(w->order);
    free(w->rank);
    free(w->sl);
    free(w->slpos);
}

static int work_alloc(k2_work *w, size_t m)
{
    const size_t m1 = m ? m : 1;
    w->m = m;
    w->B = calloc(m1, sizeof *w->B);
    w->E = calloc(m1, sizeof *w->E);
    w->P = malloc((size_t)P_N * m1 * sizeof *w->P);
    w->live = malloc(m1 * sizeof *w->live);
    w->redo = malloc(m1 * sizeof *w->redo);
    w->refined = calloc(m1, sizeof *w->refined);
    w->Q = malloc((size_t)Q_N * m1 * sizeof *w->Q);
    w->qk = malloc(m1 * sizeof *w->qk);
    w->qs = malloc(m1 * sizeof *w->qs);
    w->C = malloc(m1 * sizeof *w->C);
    w->R = malloc(m1 * sizeof *w->R);
    w->order = malloc(m1 * sizeof *w->order);
    w->rank = malloc(m1 * sizeof *w->rank);
    w->sl = malloc(m1 * sizeof *w->sl);
    w->slpos = malloc(m1 * sizeof *w->slpos);
    w->nsl = 0;
    if (!w->B || !w->E || !w->P || !w->live || !w->redo || !w->refined || !w->Q || !w->qk ||
        !w->qs || !w->C || !w->R || !w->order || !w->rank || !w->sl || !w->slpos) {
        work_free(w);
        return -1;
    }
    return 0;
}

/* Sample i of the motion: the linear forcing between samples i and i + 1. */
static sample sample_at(const sl_k2_motion *in, size_t i)
{
    sample s;
    s.ax0 = in->sign * in->ax[i];
    s.ax1 = in->sign * in->ax[i + 1];
    s.ay0 = in->ay ? in->sign * in->ay[i] : 0.0;
    s.ay1 = in->ay ? in->sign * in->ay[i + 1] : 0.0;
    s.n0 = in->g_ms2 + (in->av ? in->av[i] : 0.0);
    s.n1 = in->g_ms2 + (in->av ? in->av[i + 1] : 0.0);
    s.dt = in->dt_s;
    s.t0 = (double)i * in->dt_s;
    return s;
}

/* One block and its mu, for sorting by mu. */
typedef struct mu_key {
    double mu;
    size_t k;
} mu_key;

static int cmp_mu_key(const void *a, const void *b)
{
    const mu_key *x = a, *y = b;
    return x->mu < y->mu ? -1 : x->mu > y->mu ? 1 : (x->k > y->k) - (x->k < y->k);
}

/* Order the blocks by mu (w->order, w->rank), all at rest. Returns 0 or -1
 * (out of memory). */
static int work_order(k2_work *w, const double *mu)
{
    mu_key *key = malloc((w->m ? w->m : 1) * sizeof *key);
    if (!key)
        return -1;
    for (size_t k = 0; k < w->m; k++) {
        key[k].mu = mu[k];
        key[k].k = k;
        w->slpos[k] = SIZE_MAX;
    }
    qsort(key, w->m, sizeof *key, cmp_mu_key);
    for (size_t i = 0; i < w->m; i++) {
        w->order[i] = key[i].k;
        w->rank[key[i].k] = i;
    }
    free(key);
    return 0;
}

/* The blocks that may move in sample s into w->live; returns how many. A
 * block held at both ends of the sample is held throughout when N > 0 at
 * both ends, since |a| is convex and mu N linear then (one test per sample);
 * when N <= 0 at an end, max(N, 0) has a kink inside the sample and nothing
 * is held by the ends alone unless a = 0 at both (then a = 0 throughout).
 * Held at both ends is monotone in mu, so the blocks that would be held at
 * rest are those from the first such in mu order (a bisection); the live
 * blocks are those before it and the sliding ones after it. */
static size_t find_live(k2_work *w, const sample *s, const double *mu)
{
    /* squares, as the onset (sl_k2_onset) compares them: no hypot call */
    const double a02 = s->ax0 * s->ax0 + s->ay0 * s->ay0, a12 = s->ax1 * s->ax1 + s->ay1 * s->ay1;
    const double p0 = max2(s->n0, 0.0), p1 = max2(s->n1, 0.0);
    const int a_zero = s->ax0 == 0.0 && s->ay0 == 0.0 && s->ax1 == 0.0 && s->ay1 == 0.0;
    const int ends_decide = (s->n0 > 0.0 && s->n1 > 0.0) || a_zero;
    size_t lo = ends_decide ? 0 : w->m, hi = w->m; /* first position in order whose block is held */
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        const double mk = mu[w->order[mid]], f0 = mk * p0, f1 = mk * p1;
        if (a02 <= f0 * f0 && a12 <= f1 * f1)
            hi = mid;
        else
            lo = mid + 1;
    }
    size_t na = 0;
    for (size_t i = 0; i < lo; i++)
        w->live[na++] = w->order[i];
    for (size_t i = 0; i < w->nsl; i++)
        if (w->rank[w->sl[i]] >= lo)
            w->live[na++] = w->sl[i];
    return na;
}

/* After a sample: the live blocks now at rest leave the sliding set (and
 * forget their velocity error), those sliding join it. */
static void update_sliding(k2_work *w, size_t na)
{
    for (size_t li = 0; li < na; li++) {
        const size_t k = w->live[li];
        const int rest = w->B[k].vx == 0.0 && w->B[k].vy == 0.0;
        if (rest) {
            w->E[k].wx = w->E[k].wy = 0.0;
            if (w->slpos[k] != SIZE_MAX) { /* leaves: the last takes its slot */
                const size_t last = w->sl[--w->nsl];
                w->sl[w->slpos[k]] = last;
                w->slpos[last] = w->slpos[k];
                w->slpos[k] = SIZE_MAX;
            }
        } else if (w->slpos[k] == SIZE_MAX) {
            w->slpos[k] = w->nsl;
            w->sl[w->nsl++] = k;
        }
    }
}

/* Pack the na live blocks: friction, tolerance share eta max(rtol peak,
 * atol) (peak at least scale_m), position and velocity. */
static void pack(k2_work *w, size_t na, const double *mu, const double *eta,
                 const double *scale_m, const sl_k2_opts *o)
{
    const size_t m = w->m;
    double *pmu = w->P + P_MU * m, *ptol = w->P + P_TOL * m;
    double *pux = w->P + P_UX * m, *puy = w->P + P_UY * m;
    double *pvx = w->P + P_VX * m, *pvy = w->P + P_VY * m;
    for (size_t li = 0; li < na; li++) {
        const size_t k = w->live[li];
        const blk *b = &w->B[k];
        const double pk = scale_m ? max2(scale_m[k], sqrt(b->peak2)) : sqrt(b->peak2);
        const double sc = max2(o->rtol * pk, o->atol_m);
        pmu[li] = mu[k];
        ptol[li] = (eta ? eta[k] : SL_K2_ETA) * sc;
        pux[li] = b->ux;
        puy[li] = b->uy;
        pvx[li] = b->vx;
        pvy[li] = b->vy;
    }
}

/* The vector pass over the packed blocks of sample s (doubling_pass). */
static void step(k2_work *w, size_t na, const sample *s)
{
    const size_t m = w->m;
    double *P = w->P;
    const force Fc = sl_k2_force_of(s, 0.0, 1.0), Fa = sl_k2_force_of(s, 0.0, 0.5),
                Fb = sl_k2_force_of(s, 0.5, 1.0);
    const doubling_args a = {na, m, &Fc, &Fa, &Fb, s, P};
    doubling_pass(&a);
}

/* Unpack the blocks whose step passed (statistics, peak at t1, error
 * estimate: a smooth step of local order 3 errs about a third of the
 * difference, SL_K2_RICHARDSON); the packed indices of the rest go to
 * w->redo. Returns how many are to be redone. */
static size_t accept(k2_work *w, size_t na, double dt, double t1)
{
    const size_t m = w->m;
    const double *P = w->P;
    const double *pux = P + P_UX * m, *puy = P + P_UY * m, *pvx = P + P_VX * m,
                 *pvy = P + P_VY * m, *cux = P + P_CUX * m, *cuy = P + P_CUY * m,
                 *ppk2 = P + P_PK2 * m, *pd = P + P_D * m, *pdux = P + P_DUX * m,
                 *pduy = P + P_DUY * m, *pdvx = P + P_DVX * m, *pdvy = P + P_DVY * m;
    size_t nr = 0;
    for (size_t j = 0; j < na; j++) {
        const size_t k = w->live[j];
        blk *b = &w->B[k];
        if (pd[j] != 0.0 || (b->vx == 0.0 && b->vy == 0.0)) {
            w->redo[nr++] = j;
            continue;
        }
        const double spm = sqrt(cux[j] * cux[j] + cuy[j] * cuy[j]); /* mid-sample speed */
        const double sp2 = pvx[j] * pvx[j] + pvy[j] * pvy[j], sp = sqrt(sp2);
        b->path += 0.25 * dt * (b->sp + 2.0 * spm + sp);
        b->tslide += dt;
        b->vmax2 = max2(b->vmax2, max2(sp2, spm * spm));
        b->sp = sp;
        b->ux = pux[j];
        b->uy = puy[j];
        b->vx = pvx[j];
        b->vy = pvy[j];
        const int raised = ppk2[j] > b->peak2;
        if (raised) {
            b->peak2 = ppk2[j];
            b->tpeak = t1;
        }
        b->px = max2(b->px, fabs(b->ux));
        b->py = max2(b->py, fabs(b->uy));
        err_add(&w->E[k], pdux[j] / SL_K2_RICHARDSON, pduy[j] / SL_K2_RICHARDSON,
                pdvx[j] / SL_K2_RICHARDSON, pdvy[j] / SL_K2_RICHARDSON, dt, raised);
    }
    return nr;
}

/* One sub-step (3)-(4) of every packed block with the forcing F, ending at
 * tu, from the state rows I to the rows O: the arithmetic of fstep and
 * track_peak on the path without the split step, every value computed and
 * selected (vector code). bad = 1 marks a block whose step needs the split
 * (5) (its O is then meaningless). */
#define SUBSTEP_PARAMS                                                                            \
    (size_t nq, const force *F, double tu, const double *restrict mu, double *restrict bad,        \
     const double *restrict iux, const double *restrict iuy, const double *restrict ivx,          \
     const double *restrict ivy, const double *restrict isp, const double *restrict ipk2,         \
     const double *restrict itpk, const double *restrict ipx, const double *restrict ipy,         \
     const double *restrict ipath, const double *restrict ivm2, const double *restrict itsl,       \
     const double *restrict itst, double *restrict oux, double *restrict ouy,                     \
     double *restrict ovx, double *restrict ovy, double *restrict osp, double *restrict opk2,     \
     double *restrict otpk, double *restrict opx, double *restrict opy, double *restrict opath,    \
     double *restrict ovm2, double *restrict otsl, double *restrict otst)
K2_BODY void substep_body SUBSTEP_PARAMS
{
    const double hax = F->hax, hay = F->hay, hN = F->hN, cx = F->cx, cy = F->cy, h = F->h;
    for (size_t j = 0; j < nq; j++) {
        const double vx0 = ivx[j], vy0 = ivy[j], ux0 = iux[j], uy0 = iuy[j];
        const double f = hN * mu[j];
        const double yx = 2.0 * vx0 - hax, yy = 2.0 * vy0 - hay; /* (3) */
        const double yn = sqrt(yx * yx + yy * yy);
        const double s1 = 1.0 - f / (yn > 1e-300 ? yn : 1e-300);
        const double sm = yn > f ? s1 : 0.0;
        const double mx = yx * sm - vx0, my = yy * sm - vy0;
        const double v2 = vx0 * vx0 + vy0 * vy0, L = v2 - (hax * vx0 + hay * vy0);
        const double ok = (yn > f ? 1.0 : 0.0) * ((mx * vx0 + my * vy0) > 0.0 ? 1.0 : 0.0) *
                          (L > 0.0 ? 1.0 : 0.0) * (L * L > f * f * v2 ? 1.0 : 0.0);
        const double nux = ux0 + (0.5 * h * (vx0 + mx) + cx); /* (4) */
        const double nuy = uy0 + (0.5 * h * (vy0 + my) + cy);
        const double sp2 = mx * mx + my * my, spn = sqrt(sp2);
        /* track_peak: the end, and the parabola when u.v turns inward */
        const double r2 = nux * nux + nuy * nuy;
        const double p0 = ux0 * vx0 + uy0 * vy0, p1 = nux * mx + nuy * my;
        const double turn = (p0 > 0.0 ? 1.0 : 0.0) * (p1 < 0.0 ? 1.0 : 0.0);
        const double par = ux0 * ux0 + uy0 * uy0 + p0 * h * p0 / (turn != 0.0 ? p0 - p1 : 1.0);
        const double c = turn != 0.0 ? max2(r2, par) : r2;
        /* times blended by 0/1 weights (exact for the finite times >= 0):
         * a select would load them conditionally and block the vector code */
        const double pk2 = ipk2[j], up = c > pk2 ? 1.0 : 0.0, zs = sp2 == 0.0 ? 1.0 : 0.0;
        opk2[j] = up != 0.0 ? c : pk2;
        otpk[j] = up * tu + (1.0 - up) * itpk[j];
        opx[j] = max2(ipx[j], fabs(nux));
        opy[j] = max2(ipy[j], fabs(nuy));
        opath[j] = ipath[j] + 0.5 * h * (isp[j] + spn);
        otsl[j] = itsl[j] + h;
        ovm2[j] = max2(ivm2[j], sp2);
        otst[j] = zs * tu + (1.0 - zs) * itst[j];
        osp[j] = spn;
        oux[j] = nux;
        ouy[j] = nuy;
        ovx[j] = mx;
        ovy[j] = my;
        bad[j] = 1.0 - ok;
    }
}

/* Where a run of sub-steps of one level stands (levelrun_pass): the next
 * sub-step j, its start x (fraction of the sample), the state bank cur it
 * reads, and whether it stopped because a block's sub-step j needs the
 * split step (5) (then bank 1 - cur holds sub-step j's output of the rest). */
typedef struct level_pos {
    unsigned j;
    double x;
    int cur, bad;
} level_pos;

/* The arguments of levelrun_pass: nq packed blocks of sample s, sub-steps
 * of width wd, at most jmax of them, friction and flag rows, the two state
 * banks S[0], S[1] (S_N rows each), and the position p (read and updated). */
typedef struct level_args {
    size_t nq;
    const sample *s;
    double wd;
    unsigned jmax;
    const double *mu;
    double *bad;
    double *const *S[2];
    level_pos *p;
} level_args;

/* The sub-steps of one level from a->p on, every packed block together
 * (substep_body, one call per sub-step, inlined: the state banks swap from
 * one sub-step to the next), until the level ends or some block's sub-step
 * needs the split step (5): the loop of the level runs inside the vector
 * instance, so a level of n sub-steps costs one call, not n. The sub-steps
 * and their forcing are those of run_from (the same x, x1 and arithmetic). */
K2_BODY void levelrun_body(const level_args *a)
{
    level_pos *p = a->p;
    const size_t nq = a->nq;
    unsigned j = p->j;
    double x = p->x;
    int cur = p->cur;
    p->bad = 0;
    for (; j < a->jmax && x < 1.0; j++) {
        const double x1 = 1.0 - (x + a->wd) < 1e-12 ? 1.0 : x + a->wd;
        const force F = sl_k2_force_of(a->s, x, x1);
        const double tu = F.t - F.h + F.h * 1.0; /* as fstep */
        double *const *I = a->S[cur], *const *O = a->S[1 - cur];
        substep_body(nq, &F, tu, a->mu, a->bad, I[S_UX], I[S_UY], I[S_VX], I[S_VY], I[S_SP],
                     I[S_PK2], I[S_TPK], I[S_PX], I[S_PY], I[S_PATH], I[S_VM2], I[S_TSL],
                     I[S_TST], O[S_UX], O[S_UY], O[S_VX], O[S_VY], O[S_SP], O[S_PK2], O[S_TPK],
                     O[S_PX], O[S_PY], O[S_PATH], O[S_VM2], O[S_TSL], O[S_TST]);
        int any = 0;
        for (size_t i = 0; i < nq; i++)
            any |= a->bad[i] != 0.0;
        if (any) {
            p->bad = 1;
            break;
        }
        cur = 1 - cur;
        x = x1;
    }
    p->j = j;
    p->x = x;
    p->cur = cur;
}

K2_INSTANCES(levelrun, level_args, (a))

/* Row r of state bank `bank` of w->Q. */
static double *q_row(const k2_work *w, int bank, int r)
{
    return w->Q + (size_t)(Q_BANK + bank * S_N + r) * w->m;
}

/* Pack blocks w->qk[0..nq) (all sliding) into w->Q, state bank 0. */
static void q_pack(k2_work *w, size_t nq, const double *mu)
{
    double *S[S_N];
    for (int r = 0; r < S_N; r++)
        S[r] = q_row(w, 0, r);
    for (size_t i = 0; i < nq; i++) {
        const size_t k = w->qk[i];
        const blk *b = &w->B[k];
        w->Q[Q_MU * w->m + i] = mu[k];
        S[S_UX][i] = b->ux;
        S[S_UY][i] = b->uy;
        S[S_VX][i] = b->vx;
        S[S_VY][i] = b->vy;
        S[S_SP][i] = b->sp;
        S[S_PK2][i] = b->peak2;
        S[S_TPK][i] = b->tpeak;
        S[S_PX][i] = b->px;
        S[S_PY][i] = b->py;
        S[S_PATH][i] = b->path;
        S[S_VM2][i] = b->vmax2;
        S[S_TSL][i] = b->tslide;
        S[S_TST][i] = b->tstop;
    }
}

/* Packed block i of the state rows S as a blk (its episodes from the
 * block's start state: a pass never starts a block from rest). */
static blk q_unpack(const k2_work *w, double *const S[S_N], size_t i)
{
    blk b;
    b.ux = S[S_UX][i];
    b.uy = S[S_UY][i];
    b.vx = S[S_VX][i];
    b.vy = S[S_VY][i];
    b.sp = S[S_SP][i];
    b.peak2 = S[S_PK2][i];
    b.tpeak = S[S_TPK][i];
    b.px = S[S_PX][i];
    b.py = S[S_PY][i];
    b.path = S[S_PATH][i];
    b.vmax2 = S[S_VM2][i];
    b.tslide = S[S_TSL][i];
    b.tstop = S[S_TST][i];
    b.episodes = w->B[w->qk[i]].episodes;
    return b;
}

/* Move packed block `last` into slot i (friction, state rows S). */
static void q_move(k2_work *w, double *const S[S_N], size_t i, size_t last)
{
    double *mu = w->Q + Q_MU * w->m;
    mu[i] = mu[last];
    for (int r = 0; r < S_N; r++)
        S[r][i] = S[r][last];
    w->qk[i] = w->qk[last];
    w->qs[i] = w->qs[last];
}

/* sl_k2_run_level(B[k], s, mu, n, 0) of the nq sliding blocks packed in
 * w->Q, all together: the n sub-steps share their forcing and run as vector code
 * (levelrun_pass); a block whose sub-step needs the split step (5) leaves
 * the pack and finishes the level alone (run_from, the same steps from
 * there). Block i's answer goes to res[w->qs[i]]. */
static void level_vector(k2_work *w, size_t nq, const sample *s, unsigned n, blk *res)
{
    const double *mu = w->Q + Q_MU * w->m;
    double *bad = w->Q + Q_BAD * w->m;
    double *S[2][S_N];
    for (int r = 0; r < S_N; r++) {
        S[0][r] = q_row(w, 0, r);
        S[1][r] = q_row(w, 1, r);
    }
    const double wd = (1.0 - 0.0) / n; /* as run_level */
    const unsigned jmax = 4u * n + 8u;
    level_pos p = {0, 0.0, 0, 0};
    level_args a = {nq, s, wd, jmax, mu, bad, {S[0], S[1]}, &p};
    while (nq > 0) {
        a.nq = nq;
        levelrun_pass(&a);
        if (!p.bad)
            break;
        /* sub-step p.j needs (5) for some: from the top, so the block moved
         * into a freed slot is done */
        double *const *I = S[p.cur], *const *O = S[1 - p.cur];
        for (size_t i = nq; i-- > 0;) {
            if (bad[i] == 0.0)
                continue;
            res[w->qs[i]] = sl_k2_run_from(q_unpack(w, I, i), s, mu[i], wd, p.x, jmax - p.j);
            q_move(w, O, i, --nq);
        }
        const double x1 = 1.0 - (p.x + wd) < 1e-12 ? 1.0 : p.x + wd;
        p.cur = 1 - p.cur;
        p.x = x1;
        p.j++;
    }
    for (size_t i = 0; i < nq; i++)
        res[w->qs[i]] = q_unpack(w, S[p.cur], i);
}

/* The end of the refinement of entry e: block k takes the answer C of n
 * sub-steps, and the difference from the level before (e->a*) goes to its
 * error estimate (as refine). */
static void finish_refined(k2_work *w, const rq *e, const blk *C, unsigned n, double dt)
{
    const size_t m = w->m, k = e->k;
    const double ns = w->P[P_NS * m + e->j], bad = w->P[P_BAD * m + e->j];
    w->refined[k] += (n > 2);
    const int raised = C->peak2 > w->B[k].peak2;
    const blk B0 = w->B[k];
    w->B[k] = *C;
    const double rf = (ns == 0.0 && bad == 0.0 && C->episodes == B0.episodes &&
                       C->tstop == B0.tstop)
                          ? SL_K2_RICHARDSON
                          : 1.0;
    err_add(&w->E[k], (C->ux - e->ax) / rf, (C->uy - e->ay) / rf, (C->vx - e->avx) / rf,
            (C->vy - e->avy) / rf, dt, raised);
}

/* Redo packed block j of sample s, at rest at its start, alone: held until
 * the exact onset instant x0, then n, 2n, 4n, ... sub-steps of [x0, 1] with the
 * full step (2)-(5) (from SL_K2_ONSET_SUB: it can stop again, as (6) says
 * of every block at rest, and a stop and restart inside one step can look
 * alike at 1 and 2 sub-steps) until two
 * successive levels agree within its tolerance. An onset counts in full in
 * the error estimate (no Richardson factor). */
static void refine_onset(k2_work *w, size_t j, const sample *s, const double *mu)
{
    const size_t m = w->m, k = w->live[j];
    const double *P = w->P;
    const double tol = P[P_TOL * m + j];
    const double x0 = sl_k2_onset(s, mu[k], 0.0);
    if (!(x0 < 1.0))
        return;
    unsigned n = SL_K2_ONSET_SUB;
    blk A = sl_k2_run_onset(w->B[k], s, mu[k], n, x0), C;
    for (;;) {
        n *= 2;
        C = sl_k2_run_onset(w->B[k], s, mu[k], n, x0);
        const double eu = sqrt((C.ux - A.ux) * (C.ux - A.ux) + (C.uy - A.uy) * (C.uy - A.uy));
        const double ev = sqrt((C.vx - A.vx) * (C.vx - A.vx) + (C.vy - A.vy) * (C.vy - A.vy));
        if (eu + SL_K2_TV * ev <= tol || n >= NSUB_MAX)
            break;
        A = C;
    }
    w->refined[k] += (n > 2);
    const int raised = C.peak2 > w->B[k].peak2;
    w->B[k] = C;
    err_add(&w->E[k], C.ux - A.ux, C.uy - A.uy, C.vx - A.vx, C.vy - A.vy, s->dt, raised);
}

/* Refine the nr blocks of sample s in w->redo: a block at rest alone
 * (refine_onset: its onset sets its own sub-step grid); the sliding ones
 * level by level, every block due at n sub-steps advanced together
 * (level_vector), 1, 2, 4, ... sub-steps until two successive levels agree
 * within the block's tolerance: a block that can stop from
 * SL_K2_NEAR_STOP_SUB, a block sent by the tolerance alone from the vector
 * pass's two half steps (level 2), any other from 1. */
static void refine_all(k2_work *w, size_t nr, const sample *s, const double *mu)
{
    const size_t m = w->m;
    const double *P = w->P;
    size_t nv = 0;
    for (size_t r = 0; r < nr; r++) {
        const size_t j = w->redo[r], k = w->live[j];
        if (w->B[k].vx == 0.0 && w->B[k].vy == 0.0) {
            refine_onset(w, j, s, mu);
            continue;
        }
        rq *e = &w->R[nv++];
        const double ns = P[P_NS * m + j], bad = P[P_BAD * m + j];
        e->j = j;
        e->k = k;
        e->has_a = ns == 0.0 && bad == 0.0;
        e->lev = e->has_a ? 4u : ns != 0.0 ? SL_K2_NEAR_STOP_SUB : 1u;
        e->ax = P[P_UX * m + j];
        e->ay = P[P_UY * m + j];
        e->avx = P[P_VX * m + j];
        e->avy = P[P_VY * m + j];
    }
    size_t pending = nv;
    for (unsigned n = 1; pending > 0 && n <= NSUB_MAX; n *= 2) {
        size_t nq = 0;
        for (size_t i = 0; i < nv; i++)
            if (w->R[i].lev == n) {
                w->qk[nq] = w->R[i].k;
                w->qs[nq++] = i;
            }
        if (nq == 0)
            continue;
        q_pack(w, nq, mu);
        level_vector(w, nq, s, n, w->C);
        for (size_t i = 0; i < nv; i++) {
            rq *e = &w->R[i];
            if (e->lev != n)
                continue;
            const blk *C = &w->C[i];
            const double eu =
                sqrt((C->ux - e->ax) * (C->ux - e->ax) + (C->uy - e->ay) * (C->uy - e->ay));
            const double ev =
                sqrt((C->vx - e->avx) * (C->vx - e->avx) + (C->vy - e->avy) * (C->vy - e->avy));
            if (e->has_a && (eu + SL_K2_TV * ev <= P[P_TOL * m + e->j] || n >= NSUB_MAX)) {
                finish_refined(w, e, C, n, s->dt);
                e->lev = 0;
                pending--;
                continue;
            }
            e->has_a = 1;
            e->ax = C->ux;
            e->ay = C->uy;
            e->avx = C->vx;
            e->avy = C->vy;
            e->lev = 2 * n;
        }
    }
}

/* Fixed sub-steps: n of them per sample for every live block, the sliding
 * ones together (level_vector), a block at rest alone from its onset. */
static void fixed_level(k2_work *w, size_t na, const sample *s, const double *mu, unsigned n)
{
    size_t nq = 0;
    for (size_t li = 0; li < na; li++) {
        const size_t k = w->live[li];
        if (w->B[k].vx == 0.0 && w->B[k].vy == 0.0) {
            w->B[k] = sl_k2_run_level(w->B[k], s, mu[k], n, 0.0);
        } else {
            w->qk[nq] = k;
            w->qs[nq++] = k;
        }
    }
    if (nq > 0) {
        q_pack(w, nq, mu);
        level_vector(w, nq, s, n, w->B);
    }
}

/* The history of block 0 at the end of sample s: F/W = the absolute block
 * acceleration / g. */
static void push_history(sl_history *hist, const blk *b, const sample *s, double mu, double g)
{
    double fx = 0.0, fy = 0.0;
    const double sp = hypot(b->vx, b->vy);
    if (sp > 0.0 && s->n1 > 0.0) {
        fx = -mu * s->n1 * b->vx / sp / g;
        fy = -mu * s->n1 * b->vy / sp / g;
    } else if (sp == 0.0) {
        fx = s->ax1 / g; /* stuck: moves with the floor */
        fy = s->ay1 / g;
    }
    sl_history_push(hist, s->t0 + s->dt, b->ux, b->uy, b->vx, b->vy, fx, fy);
}

static void write_out(const k2_work *w, int adaptive, sl_k2_out *out)
{
    for (size_t k = 0; k < w->m; k++) {
        const blk *b = &w->B[k];
        const errv *e = &w->E[k];
        sl_k2_out *r = &out[k];
        r->ux = b->ux;
        r->uy = b->uy;
        r->vx = b->vx;
        r->vy = b->vy;
        r->peak_m = sqrt(b->peak2);
        r->t_peak_s = b->tpeak;
        r->peak_x_m = b->px;
        r->peak_y_m = b->py;
        r->path_m = b->path;
        r->max_speed_ms = sqrt(b->vmax2);
        r->t_stop_s = b->tstop;
        r->slide_time_s = b->tslide;
        r->episodes = b->episodes;
        r->err_m = adaptive ? e->at_peak : NAN;
        r->err_end_m = adaptive ? hypot(e->ex, e->ey) : NAN;
        r->err_v_ms = adaptive ? hypot(e->wx, e->wy) : NAN;
        r->refined = w->refined[k];
    }
}

int sl_kernel2d_run(const sl_k2_motion *in, const double *mu, const double *eta,
                    const double *scale_m, size_t m,
                    const sl_k2_opts *o, sl_k2_out *out, sl_history *hist)
{
    k2_work w;
    if (work_alloc(&w, m))
        return -1;
    if (work_order(&w, mu)) {
        work_free(&w);
        return -1;
    }
    const int adaptive = (o->substeps == 0);
    for (size_t i = 0; i + 1 < in->n; i++) {
        const sample s = sample_at(in, i);
        const size_t na = find_live(&w, &s, mu);
        if (!adaptive) {
            fixed_level(&w, na, &s, mu, o->substeps);
        } else if (na > 0) {
            pack(&w, na, mu, eta, scale_m, o);
            step(&w, na, &s);
            refine_all(&w, accept(&w, na, s.dt, s.t0 + s.dt), &s, mu);
        }
        update_sliding(&w, na);
        if (hist)
            push_history(hist, &w.B[0], &s, mu[0], in->g_ms2);
    }
    write_out(&w, adaptive, out);
    work_free(&w);
    return 0;
}
