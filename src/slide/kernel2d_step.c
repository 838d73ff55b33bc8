/*
 * kernel2d_step.c - the scalar step of one block of the 2-D kernel
 * (kernel2d_step.h): the forcing of a sub-step, the full step (2)-(5)
 * with its peak bookkeeping, the exact onset from rest, and runs of equal
 * sub-steps. Equations numbered in kernel2d.c.
 */
#include "slide/kernel2d_step.h"
#include "slide/kernel2d.h"

#include <math.h>

/* Peak bookkeeping after a step from (u0, v0) to the block's new state over
 * h ending at t: |u|^2 at the end, and inside the step when the radial
 * speed u.v turns from outward to inward, the maximum of the parabola with
 * the end slopes d|u|^2/dt = 2 u.v (third-order accurate). */
static void track_peak(blk *b, double ux0, double uy0, double vx0, double vy0, double h, double t)
{
    const double r2 = b->ux * b->ux + b->uy * b->uy;
    const double p0 = ux0 * vx0 + uy0 * vy0, p1 = b->ux * b->vx + b->uy * b->vy;
    double c = r2;
    if (p0 > 0.0 && p1 < 0.0)
        c = max2(c, ux0 * ux0 + uy0 * uy0 + p0 * h * p0 / (p0 - p1));
    if (c > b->peak2) {
        b->peak2 = c;
        b->tpeak = t;
    }
    b->px = max2(b->px, fabs(b->ux));
    b->py = max2(b->py, fabs(b->uy));
}

/* The full step (2)-(5) of one block. Returns the fraction of the step
 * used: 1, or tau/h when the block stopped at tau and friction holds it
 * there (|a(tau)| <= mu N(tau)); the caller then finds the next onset. */
static double fstep(blk *b, const force *F, double mu)
{
    double used = 1.0;
    const double h = F->h, f = F->hN * mu, hax = F->hax, hay = F->hay;
    const double vx0 = b->vx, vy0 = b->vy, ux0 = b->ux, uy0 = b->uy;
    double nvx, nvy, dux, duy;
    if (vx0 == 0.0 && vy0 == 0.0) {
        const double w2 = hax * hax + hay * hay;
        if (w2 <= f * f)
            return 1.0; /* (2): stays stuck, nothing moves */
        const double sc = 1.0 - f / sqrt(w2);
        nvx = -hax * sc;
        nvy = -hay * sc;
        dux = 0.5 * h * nvx + F->cx;
        duy = 0.5 * h * nvy + F->cy;
        b->episodes++;
    } else {
        const double yx = 2.0 * vx0 - hax, yy = 2.0 * vy0 - hay; /* (3) */
        const double yn = sqrt(yx * yx + yy * yy);
        const double sm = yn > f ? 1.0 - f / yn : 0.0;
        const double mx = yx * sm - vx0, my = yy * sm - vy0;
        /* sliding on only if, with friction held along e = v_n/|v_n|, the
         * speed along e stays positive over the step: |v_n| > h a*.e + f */
        const double v2 = vx0 * vx0 + vy0 * vy0, L = v2 - (hax * vx0 + hay * vy0);
        if (yn > f && mx * vx0 + my * vy0 > 0.0 && L > 0.0 && L * L > f * f * v2) {
            nvx = mx;
            nvy = my;
            dux = 0.5 * h * (vx0 + nvx) + F->cx; /* (4) */
            duy = 0.5 * h * (vy0 + nvy) + F->cy;
        } else { /* (5) */
            const double vn = sqrt(vx0 * vx0 + vy0 * vy0);
            const double ex = vx0 / vn, ey = vy0 / vn;
            const double dec = (hax * ex + hay * ey + f) / h;
            const double tau = dec > 0.0 ? min2(vn / dec, h) : h;
            const double q = tau / h, rest = 1.0 - q;
            const double tx = vx0 - q * (hax + f * ex), ty = vy0 - q * (hay + f * ey);
            const double atx = F->ax0 + F->dax * q, aty = F->ay0 + F->day * q;
            const double Nt = F->n0 + F->dn * q;
            /* a stop, not a turn: the speed across e left at tau is small */
            if (q < 1.0 && atx * atx + aty * aty <= mu * mu * max2(Nt, 0.0) * max2(Nt, 0.0) &&
                tx * tx + ty * ty <= SL_K2_STOP_REMNANT * SL_K2_STOP_REMNANT * vn * vn) {
                /* stopped at tau and held there: at rest until the next onset */
                nvx = nvy = 0.0;
                dux = 0.5 * tau * (vx0 + tx);
                duy = 0.5 * tau * (vy0 + ty);
                used = q;
            } else {
                const double w2x = tx - rest * hax, w2y = ty - rest * hay;
                const double w2n = sqrt(w2x * w2x + w2y * w2y);
                const double s2 = w2n > rest * f ? 1.0 - rest * f / w2n : 0.0;
                nvx = w2x * s2;
                nvy = w2y * s2;
                dux = 0.5 * (tau * (vx0 + tx) + (h - tau) * (tx + nvx));
                duy = 0.5 * (tau * (vy0 + ty) + (h - tau) * (ty + nvy));
            }
        }
    }
    b->ux += dux;
    b->uy += duy;
    b->vx = nvx;
    b->vy = nvy;
    const double sp2 = nvx * nvx + nvy * nvy, sp = sqrt(sp2);
    const double hu = h * used, tu = F->t - h + hu;
    b->path += 0.5 * hu * (b->sp + sp);
    b->sp = sp;
    b->tslide += hu;
    b->vmax2 = max2(b->vmax2, sp2);
    if (sp2 == 0.0)
        b->tstop = tu;
    track_peak(b, ux0, uy0, vx0, vy0, hu, tu);
    return used;
}

/* Does a block at rest slip at fraction x of the sample: |a(x)| > mu N(x)
 * (any |a| > 0 when N <= 0)? */
static int slips_at(const sample *s, double mu, double x)
{
    const double ax = s->ax0 + (s->ax1 - s->ax0) * x, ay = s->ay0 + (s->ay1 - s->ay0) * x;
    const double N = s->n0 + (s->n1 - s->n0) * x;
    return ax * ax + ay * ay > mu * mu * max2(N, 0.0) * max2(N, 0.0);
}

/* The first fraction x in [lo, 1) after which a block at rest slips, or 1
 * if it stays held. With a and N linear in x, |a|^2 - (mu N)^2 is a quadratic
 * q2 x^2 + q1 x + q0; the slip condition keeps its truth value between its
 * roots and the zero of N, so testing one point between consecutive
 * candidates is exact. */
double sl_k2_onset(const sample *s, double mu, double lo_x)
{
    const double dax = s->ax1 - s->ax0, day = s->ay1 - s->ay0, dn = s->n1 - s->n0;
    const double q2 = dax * dax + day * day - mu * mu * dn * dn;
    const double q1 = 2.0 * (s->ax0 * dax + s->ay0 * day - mu * mu * s->n0 * dn);
    const double q0 = s->ax0 * s->ax0 + s->ay0 * s->ay0 - mu * mu * s->n0 * s->n0;
    double c[5] = {lo_x, 1.0, 1.0, 1.0, 1.0};
    int nc = 1;
    if (q2 != 0.0) {
        const double disc = q1 * q1 - 4.0 * q2 * q0;
        if (disc >= 0.0) {
            const double qq = -0.5 * (q1 + copysign(sqrt(disc), q1));
            if (qq != 0.0)
                c[nc++] = q0 / qq;
            c[nc++] = qq / q2;
        }
    } else if (q1 != 0.0) {
        c[nc++] = -q0 / q1;
    }
    if (dn != 0.0)
        c[nc++] = -s->n0 / dn;
    for (int i = 1; i < nc; i++) /* sort the few candidates */
        for (int j = i; j > 0 && c[j] < c[j - 1]; j--) {
            const double t = c[j];
            c[j] = c[j - 1];
            c[j - 1] = t;
        }
    for (int i = 0; i < nc; i++) {
        const double lo = fmax(c[i], lo_x), hi = i + 1 < nc ? fmin(c[i + 1], 1.0) : 1.0;
        if (!(lo < 1.0) || !(hi > lo))
            continue;
        if (slips_at(s, mu, 0.5 * (lo + hi)))
            return lo;
    }
    return 1.0;
}

/* Sub-steps of width w from fraction x of one sample to its end, at most
 * jmax of them; a block at rest stays held until the exact onset instant
 * (onset_at_x: x is that instant already). */
static blk run_from(blk b, const sample *s, double mu, double w, double x, unsigned jmax,
                    int onset_at_x)
{
    for (unsigned j = 0; j < jmax && x < 1.0; j++) {
        if (b.vx == 0.0 && b.vy == 0.0 && !(j == 0 && onset_at_x)) {
            x = sl_k2_onset(s, mu, x);
            if (!(x < 1.0))
                break;
        }
        const double x1 = 1.0 - (x + w) < 1e-12 ? 1.0 : x + w;
        force F = sl_k2_force_of(s, x, x1);
        const double used = fstep(&b, &F, mu);
        x = used < 1.0 ? x + (x1 - x) * used : x1;
    }
    return b;
}

blk sl_k2_run_from(blk b, const sample *s, double mu, double w, double x, unsigned jmax)
{
    return run_from(b, s, mu, w, x, jmax, 0);
}

/* Sub-steps of width (1 - x0)/n over the part [x0, 1] of one sample from
 * b (run_from). */
blk sl_k2_run_level(blk b, const sample *s, double mu, unsigned n, double x0)
{
    return run_from(b, s, mu, (1.0 - x0) / n, x0, 4u * n + 8u, 0);
}

blk sl_k2_run_onset(blk b, const sample *s, double mu, unsigned n, double x0)
{
    return run_from(b, s, mu, (1.0 - x0) / n, x0, 4u * n + 8u, 1);
}
