#!/usr/bin/python3
"""rock_ref.py - an independent integrator of the rocking block of
docs/model.md, "Rocking" (Housner 1963), for tests/cli/test_rock.sh.

It shares nothing with seislide but the model as the docs state it:
  theta'' = -p^2 [(1 + a_v/g) sin(s alpha - theta) + (a_h/g) cos(s alpha - theta)]
(s the corner, +1 for theta > 0), a_h and a_v piecewise linear between
samples and zero after the last; uplift from rest at the first instant with
|a_h| > (g + a_v) tan(alpha) (theta > 0 when a_h < 0); impact at theta = 0:
theta' <- r theta' on the other corner, then the rest rule (at rest when the
net acceleration back toward theta = 0, a_r, is positive and the rebound
theta'^2 / (2 a_r) is below 1e-6 alpha, or theta' = 0); tipped at |theta| =
alpha, overturned at pi/2 (the run stops); after the record the block rocks
on to its first peak below alpha (all later peaks are lower), a rest or the
overturn.

Integration: scipy's solve_ivp, DOP853, rtol 1e-10, atol 1e-13, max_step
dt (one kink of the piecewise-linear input per step), events located by its
dense output.

usage: rock_ref.py --h1 FILE.AT2 [--v FILE.AT2] --base-m B --cg-height-m H
                   [--restitution R] [--scale-pga G]
Prints key=value lines: peak_theta_rad, t_peak_s, tipped, overturned,
impacts, uplifts, t_uplift_s, first_peak_rad, t_first_peak_s.
"""
import argparse
import math
import re
import sys

import numpy as np
from scipy.integrate import solve_ivp

G = 9.80665
REST_FRACTION = 1e-6


def read_at2(path):
    """A PEER .AT2 file in g: (samples in m/s^2, dt)."""
    with open(path) as f:
        lines = f.read().splitlines()
    m = re.search(r"NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([0-9.Ee+-]+)", lines[3])
    if not m or "UNITS OF G" not in lines[2].upper():
        sys.exit("rock_ref.py: %s: not a PEER .AT2 file in g" % path)
    n, dt = int(m.group(1)), float(m.group(2))
    vals = np.array(" ".join(lines[4:]).split(), dtype=float)[:n]
    return vals * G, dt


class Block:
    def __init__(self, b, h, r, ah, av, dt):
        self.alpha = math.atan2(b, h)
        self.ta = b / h
        self.p2 = 3 * G / (4 * math.hypot(b, h))
        self.r = r
        self.ah, self.av, self.dt = ah, av, dt
        self.n = len(ah)
        self.t_end = (self.n - 1) * dt

    def forcing(self, t):
        """a_h, a_v at t (linear between samples, zero after the record)."""
        if t > self.t_end:
            return 0.0, 0.0
        i = min(int(t / self.dt), self.n - 2)
        f = (t - i * self.dt) / self.dt
        ah = self.ah[i] + (self.ah[i + 1] - self.ah[i]) * f
        av = self.av[i] + (self.av[i + 1] - self.av[i]) * f
        return ah, av

    def rhs(self, s, t, y):
        ah, av = self.forcing(t)
        a = s * self.alpha - y[0]
        return [y[1], -self.p2 * ((1 + av / G) * math.sin(a) + ah / G * math.cos(a))]

    def uplift_after(self, t0):
        """The first instant >= t0 with (K3), and the corner; None past the record."""
        dt, n = self.dt, self.n
        i = int(t0 / dt)
        if i >= n - 1:
            return None
        T = (G + self.av) * self.ta
        hit = np.nonzero(np.abs(self.ah[i + 1:]) > T[i + 1:])[0]
        j = i + 1 + hit[0] if len(hit) else None
        # within sample i from t0, then sample j - 1 (K3 false at its start)
        for k, ta in ((i, t0), (j - 1 if j is not None else None, None)):
            if k is None:
                continue
            ta = k * dt if ta is None else ta
            x0, y0 = self.forcing(ta)
            x1, y1 = self.ah[k + 1], self.av[k + 1]
            T0, T1 = (G + y0) * self.ta, (G + y1) * self.ta
            best = None
            for side, f0, f1 in ((1, -x0 - T0, -x1 - T1), (-1, x0 - T0, x1 - T1)):
                if f0 > 0:
                    tu = ta
                elif f1 > 0:
                    tu = ta + ((k + 1) * dt - ta) * (-f0 / (f1 - f0))
                else:
                    continue
                if best is None or tu < best[0]:
                    best = (tu, side)
            if best:
                return best
        return None


def run(blk):
    res = dict(peak_theta_rad=0.0, t_peak_s=0.0, tipped=0, overturned=0, impacts=0, uplifts=0,
               t_uplift_s=float("nan"), first_peak_rad=float("nan"),
               t_first_peak_s=float("nan"))
    t, th, om, s, rest = 0.0, 0.0, 0.0, 1, True
    alpha = blk.alpha

    def note_peak(tp, u):
        if math.isnan(res["first_peak_rad"]):
            res["first_peak_rad"], res["t_first_peak_s"] = u, tp
        if u > res["peak_theta_rad"]:
            res["peak_theta_rad"], res["t_peak_s"] = u, tp

    while True:
        if rest:
            up = blk.uplift_after(t)
            if up is None:
                return res
            t, s = up
            th = om = 0.0
            rest = False
            res["uplifts"] += 1
            if res["uplifts"] == 1:
                res["t_uplift_s"] = t
        tail = t >= blk.t_end
        t_stop = t + 1e4 / math.sqrt(blk.p2) if tail else blk.t_end

        def ev_impact(tt, y, s=s):
            return s * y[0]
        ev_impact.terminal, ev_impact.direction = True, -1

        def ev_over(tt, y, s=s):
            return s * y[0] - math.pi / 2
        ev_over.terminal, ev_over.direction = True, 1

        def ev_tip(tt, y, s=s):
            return s * y[0] - alpha
        ev_tip.direction = 1

        def ev_peak(tt, y, s=s):
            return s * y[1]
        ev_peak.direction = -1
        ev_peak.terminal = tail

        sol = solve_ivp(lambda tt, y: blk.rhs(s, tt, y), (t, t_stop), [th, om], method="DOP853",
                        rtol=1e-10, atol=1e-13, max_step=blk.dt if not tail else np.inf,
                        events=[ev_impact, ev_over, ev_tip, ev_peak])
        if sol.status < 0:
            sys.exit("rock_ref.py: solve_ivp failed: " + sol.message)
        for tp, yp in zip(sol.t_events[3], sol.y_events[3]):
            note_peak(tp, abs(yp[0]))
        if len(sol.t_events[2]) and not res["tipped"]:
            res["tipped"], res["t_tip_s"] = 1, sol.t_events[2][0]
        if len(sol.t_events[1]):
            res["overturned"] = 1
            res["tipped"] = 1
            res["peak_theta_rad"], res["t_peak_s"] = math.pi / 2, sol.t_events[1][0]
            return res
        if len(sol.t_events[0]):
            t = sol.t_events[0][0]
            om = blk.r * sol.y_events[0][0][1]
            res["impacts"] += 1
            s = -s
            th = 0.0
            ah, av = blk.forcing(t)
            a_r = blk.p2 * ((1 + av / G) * math.sin(alpha) + s * ah / G * math.cos(alpha))
            if om == 0 or (a_r > 0 and om * om < 2 * a_r * REST_FRACTION * alpha):
                om = 0.0
                rest = True
            continue
        if tail:  # the first peak after the record, below alpha
            return res
        t, th, om = sol.t[-1], sol.y[0][-1], sol.y[1][-1]
        note_peak(t, abs(th))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--h1", required=True)
    ap.add_argument("--v")
    ap.add_argument("--base-m", type=float, required=True)
    ap.add_argument("--cg-height-m", type=float, required=True)
    ap.add_argument("--restitution", type=float)
    ap.add_argument("--scale-pga", type=float)
    a = ap.parse_args()
    ah, dt = read_at2(a.h1)
    av = np.zeros_like(ah)
    if a.v:
        av, dtv = read_at2(a.v)
        n = min(len(ah), len(av))
        ah, av = ah[:n], av[:n]
    if a.scale_pga:
        k = a.scale_pga * G / np.max(np.abs(ah))
        ah, av = ah * k, av * k
    b, h = a.base_m / 2, a.cg_height_m
    r = a.restitution if a.restitution is not None else max(0.0, 1 - 1.5 * b * b / (b * b + h * h))
    res = run(Block(b, h, r, ah, av, dt))
    for k in ("peak_theta_rad", "t_peak_s", "tipped", "overturned", "impacts", "uplifts",
              "t_uplift_s", "first_peak_rad", "t_first_peak_s"):
        print("%s=%.12g" % (k, res[k]))


if __name__ == "__main__":
    main()
