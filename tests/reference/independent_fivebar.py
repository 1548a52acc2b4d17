#!/usr/bin/env python3
"""Independent reference numbers for ``configs/ch1/fivebar.toml`` (``mechcli kin``).

Deliberately self-contained: imports nothing from mechcli (only numpy/scipy), and
the mechanism is written out here rather than read through mechcli's spec layer.

Mechanism (李辉 et al. 2002, 实例 2): A = (0, 0), E = (21, 0); crank AB = 5 turns
with theta1 at omega1 = 10 rad/s (CCW, constant); crank ED = 13 is geared to it,
theta4 = 90° - theta1 (phase 90°, ratio -1), so omega4 = -omega1; BC = 20, CD = 22.
Joint C on branch +1: to the LEFT of the directed line B -> D.

Method
------
* position: C = B + a*u + h*n, the intersection of the circles |C-B| = 20 and
  |C-D| = 22 (u = unit vector B->D, n = u turned +90°, a = (L2²-L3²+|BD|²)/(2|BD|),
  h = +sqrt(L2²-a²)); theta2 = atan2(C-B), theta3 = atan2(C-D) (link 3 points from
  its ground-crank end D to C), CCW from +x, wrapped to [0, 360);
* velocity / acceleration: the loop B + L2 e2 = D + L3 e3 differentiated once and
  twice by hand, each a 2x2 linear system in (omega2, omega3) / (alpha2, alpha3)
  solved exactly (Cramer);  cross-checked against an 8th-order central difference
  of the positions (h = 0.005 rad), see ``fd_check``;
* transmission angle at C: gamma = arccos|e2 . e3| (acute angle between BC and CD);
* extremes: a scan of 36000 points (0.01°) over one turn locates the sign changes of
  the analytic derivative (omega for theta, vx/vy for x/y, alpha for omega,
  omega3 - omega2 for gamma), each refined by brentq (xtol 1e-13 rad) on that
  derivative; the extreme value is the function at the root.

Run:  python3 tests/reference/independent_fivebar.py
"""
import math

import numpy as np
from scipy.optimize import brentq

DEG = math.pi / 180.0
TWO_PI = 2.0 * math.pi

A = np.array([0.0, 0.0])
E = np.array([21.0, 0.0])
L1, L2, L3, L4 = 5.0, 20.0, 22.0, 13.0
PHASE = 90.0 * DEG      # theta4 = PHASE + RATIO * theta1
RATIO = -1.0
OMEGA1 = 10.0           # rad/s
BRANCH = +1             # C to the left of B -> D
SCAN_N = 36000          # 0.01° scan


def _perp(v):
    """v turned +90° (works on (..., 2) arrays)."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def state(th1):
    """Everything at crank angle(s) th1 [rad]: a dict of numpy arrays."""
    th1 = np.asarray(th1, dtype=float)
    w1 = OMEGA1
    th4 = PHASE + RATIO * th1
    w4 = RATIO * w1
    e1 = np.stack([np.cos(th1), np.sin(th1)], axis=-1)
    e4 = np.stack([np.cos(th4), np.sin(th4)], axis=-1)
    B = A + L1 * e1
    D = E + L4 * e4
    vB = L1 * w1 * _perp(e1)
    vD = L4 * w4 * _perp(e4)
    aB = -L1 * w1 ** 2 * e1            # constant crank speeds
    aD = -L4 * w4 ** 2 * e4

    # position: intersection of the two circles
    d = D - B
    r = np.hypot(d[..., 0], d[..., 1])
    u = d / r[..., None]
    a = (L2 ** 2 - L3 ** 2 + r ** 2) / (2.0 * r)
    h2 = L2 ** 2 - a ** 2
    if np.any(h2 < 0):
        raise ValueError("the five-bar does not assemble")
    h = np.sqrt(h2)
    C = B + a[..., None] * u + BRANCH * h[..., None] * _perp(u)
    e2 = (C - B) / L2
    e3 = (C - D) / L3
    th2 = np.arctan2(e2[..., 1], e2[..., 0])
    th3 = np.arctan2(e3[..., 1], e3[..., 0])

    # velocity: vB + L2 w2 perp(e2) = vD + L3 w3 perp(e3)
    #   => w2 (L2 perp e2) + w3 (-L3 perp e3) = vD - vB
    p2 = L2 * _perp(e2)
    p3 = -L3 * _perp(e3)
    det = p2[..., 0] * p3[..., 1] - p2[..., 1] * p3[..., 0]

    def solve(rhs):
        x = (rhs[..., 0] * p3[..., 1] - rhs[..., 1] * p3[..., 0]) / det
        y = (p2[..., 0] * rhs[..., 1] - p2[..., 1] * rhs[..., 0]) / det
        return x, y

    w2, w3 = solve(vD - vB)
    vC = vB + w2[..., None] * p2
    # acceleration: aB + L2 al2 perp e2 - L2 w2² e2 = aD + L3 al3 perp e3 - L3 w3² e3
    rhs = aD - aB + L2 * (w2 ** 2)[..., None] * e2 - L3 * (w3 ** 2)[..., None] * e3
    al2, al3 = solve(rhs)
    aC = aB + al2[..., None] * p2 - L2 * (w2 ** 2)[..., None] * e2

    cosmu = np.sum(e2 * e3, axis=-1)
    gamma = np.arccos(np.clip(np.abs(cosmu), 0.0, 1.0))
    return dict(theta2=np.mod(th2, TWO_PI), theta3=np.mod(th3, TWO_PI),
                omega2=w2, omega3=w3, alpha2=al2, alpha3=al3,
                xC=C[..., 0], yC=C[..., 1], vxC=vC[..., 0], vyC=vC[..., 1],
                axC=aC[..., 0], ayC=aC[..., 1], gamma=gamma,
                dgamma_sign=w3 - w2)


# quantity -> the derivative (per unit time) whose zeros are its interior extremes
DERIV = {"theta2": "omega2", "theta3": "omega3", "xC": "vxC", "yC": "vyC",
         "omega2": "alpha2", "omega3": "alpha3", "gamma": "dgamma_sign"}


def _scalar(th, key):
    return float(state(np.array([th]))[key][0])


def extremes(key):
    """(max, th1_at_max, min, th1_at_min) of quantity *key*, th1 in rad in [0, 2pi)."""
    grid = np.linspace(0.0, TWO_PI, SCAN_N + 1)
    s = state(grid)
    f, g = s[key], s[DERIV[key]]
    cands = []
    for i in np.nonzero(np.sign(g[:-1]) != np.sign(g[1:]))[0]:
        root = brentq(lambda t: _scalar(t, DERIV[key]), grid[i], grid[i + 1], xtol=1e-13)
        cands.append((_scalar(root, key), root % TWO_PI))
    # the grid maximum / minimum must be next to one of the roots (no endpoint extremes
    # on a closed cycle, and no kinks: gamma stays below 90° at its minimum; its
    # maximum, 90° at a kink of arccos|.|, is not located this way and not reported)
    vmax = max(cands)
    vmin = min(cands)
    assert vmin[0] <= f.min() + 1e-9
    assert key == "gamma" or vmax[0] >= f.max() - 1e-9
    return vmax[0], vmax[1], vmin[0], vmin[1]


def fd_check(h=0.005):
    """Largest |analytic - 8th-order central difference| of omega2, omega3 [rad/s] and
    vxC, vyC [mm/s] over a 1° grid (the truncation error is O(h^8))."""
    c1 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    offs = np.arange(-4, 5)
    th = np.arange(360) * DEG
    s = state(th[:, None] + offs[None, :] * h)
    ref = state(th)
    out = {}
    for q, v in (("theta2", "omega2"), ("theta3", "omega3"), ("xC", "vxC"), ("yC", "vyC")):
        x = np.unwrap(s[q], axis=1) if q.startswith("theta") else s[q]
        fd = (x @ c1) / h * OMEGA1
        out[v] = float(np.max(np.abs(fd - ref[v])))
    return out


def reference():
    """The reference results, named as mechcli's ``--json`` results (angles in deg)."""
    res = {}
    for key, name, scale, unit in (("theta2", "theta2", 1 / DEG, "deg"),
                                   ("theta3", "theta3", 1 / DEG, "deg"),
                                   ("xC", "xC2", 1.0, "mm"),
                                   ("yC", "yC2", 1.0, "mm"),
                                   ("omega2", "omega2", 1.0, "rad_s"),
                                   ("omega3", "omega3", 1.0, "rad_s"),
                                   ("gamma", "gammaC", 1 / DEG, "deg")):
        vmax, tmax, vmin, tmin = extremes(key)
        if key != "gamma":
            res[f"{name}_max_{unit}"] = vmax * scale
            res[f"{name}_max_at_deg"] = tmax / DEG
        res[f"{name}_min_{unit}"] = vmin * scale
        res[f"{name}_min_at_deg"] = tmin / DEG
    res["theta2_swing_deg"] = res["theta2_max_deg"] - res["theta2_min_deg"]
    res["theta3_swing_deg"] = res["theta3_max_deg"] - res["theta3_min_deg"]
    res["positions"] = 361          # [input] step = 1° over 0..360°, both ends included
    return res


def main():
    for k, v in reference().items():
        print(f"{k:22s} {v:.10f}" if isinstance(v, float) else f"{k:22s} {v}")
    print("analytic vs finite-difference velocity, max |diff|:",
          {k: f"{v:.1e}" for k, v in fd_check().items()})


if __name__ == "__main__":
    main()
