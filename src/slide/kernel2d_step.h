/*
 * kernel2d_step.h - one block's step of the 2-D kernel (library-internal:
 * kernel2d.c and kernel2d_step.c only): the sample, the forcing of a
 * sub-step, the block's state, and the scalar steps (2)-(5) with the exact
 * onset (kernel2d_step.c; equations numbered in kernel2d.c).
 */
#ifndef SL_KERNEL2D_STEP_H
#define SL_KERNEL2D_STEP_H

/* The vector pass (doubling_pass and what it inlines) computes every value
 * on every path and only selects; with GCC it is compiled without
 * -ftrapping-math (no FP exception flags are used anywhere) so those selects
 * become vector code. */
#if defined(__GNUC__) && !defined(__clang__)
#define VECTOR_PASS __attribute__((optimize("no-trapping-math")))
#else
#define VECTOR_PASS
#endif

/* max and min of finite values as selects (fmax/fmin may be calls) */
VECTOR_PASS static inline double max2(double a, double b) { return a > b ? a : b; }
VECTOR_PASS static inline double min2(double a, double b) { return a < b ? a : b; }

/* One sample: the linear forcing between its ends. */
typedef struct sample {
    double ax0, ax1, ay0, ay1, n0, n1, dt, t0;
} sample;

/* The forcing integrals of the sub-step [x0, x1] (fractions of the sample):
 * h a*, h N*, the correction h^2/12 (a(x1) - a(x0)) of (4), h, end time. */
typedef struct force {
    double hax, hay, hN, cx, cy, h, t;
    double ax0, ay0, dax, day, n0, dn; /* a and N at the start, their changes over the step */
} force;

/* The state of one block and its running statistics. */
typedef struct blk {
    double ux, uy, vx, vy, sp;
    double peak2, tpeak, px, py, path, vmax2, tstop, tslide;
    long episodes;
} blk;

/* Mean over [0, 1] of max(n0 + (n1 - n0) x, 0): exact for the linear N. */
VECTOR_PASS static inline double sl_k2_mean_positive(double n0, double n1)
{
    if (n0 >= 0.0 && n1 >= 0.0)
        return 0.5 * (n0 + n1);
    if (n0 <= 0.0 && n1 <= 0.0)
        return 0.0;
    double p = n0 > 0.0 ? n0 : n1, q = n0 > 0.0 ? n1 : n0;
    return 0.5 * p * p / (p - q);
}

/* The forcing integrals of the sub-step [x0, x1] of sample s (inline: it
 * is computed for every sub-step of every level, a few blocks at a time). */
VECTOR_PASS static inline force sl_k2_force_of(const sample *s, double x0, double x1)
{
    const double h = (x1 - x0) * s->dt, xm = 0.5 * (x0 + x1), c = h * h / 12.0 * (x1 - x0);
    force F;
    F.h = h;
    F.hax = h * (s->ax0 + (s->ax1 - s->ax0) * xm);
    F.hay = h * (s->ay0 + (s->ay1 - s->ay0) * xm);
    F.hN = h * sl_k2_mean_positive(s->n0 + (s->n1 - s->n0) * x0, s->n0 + (s->n1 - s->n0) * x1);
    F.cx = c * (s->ax1 - s->ax0);
    F.cy = c * (s->ay1 - s->ay0);
    F.t = s->t0 + x1 * s->dt;
    F.ax0 = s->ax0 + (s->ax1 - s->ax0) * x0;
    F.ay0 = s->ay0 + (s->ay1 - s->ay0) * x0;
    F.n0 = s->n0 + (s->n1 - s->n0) * x0;
    F.dax = (s->ax1 - s->ax0) * (x1 - x0);
    F.day = (s->ay1 - s->ay0) * (x1 - x0);
    F.dn = (s->n1 - s->n0) * (x1 - x0);
    return F;
}

/* The first fraction x in [lo_x, 1) after which a block at rest slips, or
 * 1 if it stays held (exact). */
double sl_k2_onset(const sample *s, double mu, double lo_x);

/* Sub-steps of width w from fraction x of sample s to its end, at most
 * jmax of them, with the full step (2)-(5); a block at rest stays held
 * until the exact onset instant. */
blk sl_k2_run_from(blk b, const sample *s, double mu, double w, double x, unsigned jmax);

/* n sub-steps of width (1 - x0)/n over [x0, 1] (sl_k2_run_from). */
blk sl_k2_run_level(blk b, const sample *s, double mu, unsigned n, double x0);
/* The same for a block at rest whose onset instant is x0
 * (sl_k2_onset(s, mu, 0)): it slides from x0 without finding it again. */
blk sl_k2_run_onset(blk b, const sample *s, double mu, unsigned n, double x0);

#endif
