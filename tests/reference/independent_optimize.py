#!/usr/bin/env python3
"""Independent reference optima for the chapter-7 optimize configs (configs/ch7).

Deliberately self-contained: imports nothing from mechcli (only numpy/scipy).
Every problem is written here from the book's model and the configs' text, with
its own closed-form kinematics, and solved by LONG runs (many-start SLSQP,
differential evolution with a big population, each polished):

* ``psi_book``: the rocker angle of 式 7-4 … 7-7 (A = (0, 0), D = (l4, 0), open
  branch: psi = pi - alpha -/+ beta), the right limit position phi0/psi0 of 式 7-1;
* transmission angle of a crank-rocker: its extremes at the crank's two
  positions in line with the frame (式 7-12, 7-13), exact;
* a general four-bar (A, D anywhere): circle intersection, C to the left of
  B->D; the coupler point M = B + (along + i normal) e^{i theta2};
* the path error of 习题 7-3: the distance of each target to the TRUE coupler
  curve (dense scan of the crank angle, refined by a bounded scalar search);
* 例 2-1's balancing torque by virtual work (power balance), analytic
  velocities and accelerations of the four-bar (no force system solved).

Run:  python3 tests/reference/independent_optimize.py [name ...]   (prints JSON)
"""
import json
import math
import sys
import time

import numpy as np
from scipy import optimize

DEG = math.pi / 180.0
TWO_PI = 2.0 * math.pi


def wrap(a):
    return (a + math.pi) % TWO_PI - math.pi


# ----------------------------------------------------------------------------- book closed form
def psi_book(l1, l2, l3, l4, phi):
    """Rocker angle of the open four-bar by 式 7-4 … 7-7 (NaN where it does not
    assemble)."""
    phi = np.asarray(phi, dtype=float)
    r = np.sqrt(l1 * l1 + l4 * l4 - 2 * l1 * l4 * np.cos(phi))
    with np.errstate(invalid="ignore"):
        alpha = np.arccos((r * r + l3 * l3 - l2 * l2) / (2 * r * l3))
        beta = np.arccos((r * r + l4 * l4 - l1 * l1) / (2 * r * l4))
    upper = np.mod(phi, TWO_PI) <= math.pi
    return np.where(upper, math.pi - alpha - beta, math.pi - alpha + beta)


def limit_position(l1, l2, l3, l4):
    """(phi0, psi0) of 式 7-1: crank and coupler extended in line (the right limit)."""
    phi0 = math.acos(((l1 + l2) ** 2 + l4 ** 2 - l3 ** 2) / (2 * (l1 + l2) * l4))
    psi0 = math.acos(((l1 + l2) ** 2 - l4 ** 2 - l3 ** 2) / (2 * l3 * l4))
    return phi0, psi0


def crank_g(l1, l2, l3, l4):
    """The book's g1 … g6 (<= 0)."""
    return np.array([l1 - l2, l1 - l3, l1 - l4, l1 + l4 - l2 - l3, l1 + l2 - l3 - l4,
                     l1 + l3 - l2 - l4])


def mu_range(l1, l2, l3, l4):
    """(least, greatest) angle BCD of a crank-rocker: 式 7-12, 7-13."""
    c_min = (l2 * l2 + l3 * l3 - (l4 - l1) ** 2) / (2 * l2 * l3)
    c_max = (l2 * l2 + l3 * l3 - (l4 + l1) ** 2) / (2 * l2 * l3)
    return math.acos(min(1.0, max(-1.0, c_min))), math.acos(min(1.0, max(-1.0, c_max)))


def function_dev(l, dphi, dpsi):
    """Deviations of 例 7-1's model: l = (l1, l2, l3, l4), origin the right limit
    position, psi - psi0 against the target increments."""
    l1, l2, l3, l4 = l
    phi0, psi0 = limit_position(l1, l2, l3, l4)
    psi = psi_book(l1, l2, l3, l4, phi0 + np.asarray(dphi))
    return wrap(psi - psi0) - np.asarray(dpsi)


def local_multistart(fun, cons, bounds, starts, ftol=1e-14, maxiter=500):
    """Best feasible SLSQP end over the starts."""
    best = None
    for x0 in starts:
        try:
            r = optimize.minimize(fun, x0, method="SLSQP", bounds=bounds, constraints=cons,
                                  options={"ftol": ftol, "maxiter": maxiter})
        except (ValueError, ArithmeticError):
            continue
        x = r.x
        if not np.isfinite(r.fun):
            continue
        if cons and min(np.min(np.atleast_1d(c["fun"](x))) for c in cons) < -1e-9:
            continue
        if best is None or r.fun < best[1]:
            best = (x, float(r.fun))
    return best


def lhs(n, bounds, seed):
    rng = np.random.default_rng(seed)
    lo, hi = np.array(bounds, dtype=float).T
    u = (rng.permuted(np.tile(np.arange(n), (len(lo), 1)), axis=1).T + rng.random((n, len(lo))))
    return lo + u / n * (hi - lo)


# ----------------------------------------------------------------------------- 例 7-1
EX71_N = 30


def ex7_1(mu_lo=45.00845, mu_hi=134.99155, starts=20, seed=0):
    """例 7-1: l1 = 1, l4 = 5, x = (l2, l3); target psi - psi0 = 2/(3 pi) dphi^2 on 30 steps
    of 90 deg; crank g1..g6 and 45 <= mu <= 135 (the book's 1.414 rounding by default)."""
    dphi = (math.pi / 2) * np.arange(1, EX71_N + 1) / EX71_N
    dpsi = 2 / (3 * math.pi) * dphi ** 2

    def f(x):
        d = function_dev((1.0, x[0], x[1], 5.0), dphi, dpsi)
        return float(np.sum(d * d)) if np.all(np.isfinite(d)) else 1e3

    def g(x):                       # >= 0 feasible
        l = (1.0, x[0], x[1], 5.0)
        lo, hi = mu_range(*l)
        return np.concatenate([-crank_g(*l), [lo - mu_lo * DEG, mu_hi * DEG - hi]])

    cons = [{"type": "ineq", "fun": g}]
    bounds = [(1, 20), (1, 20)]
    pts = [np.array([6.0, 2.5])] + list(lhs(starts - 1, bounds, seed))
    x, fx = local_multistart(f, cons, bounds, pts)
    return {"x.mechanism.l2": x[0], "x.mechanism.l3": x[1], "f": fx}


# ----------------------------------------------------------------------------- 习题 7-1, 7-2
def lg_targets(n=30, phi_m=90.0, psi_m=60.0):
    """y = lg x, 1 <= x <= 10: x = 1 + 9 i/n (i = 1..n) mapped linearly onto the
    input swing phi_m, y onto the output swing psi_m (lg 1 = 0, lg 10 = 1)."""
    i = np.arange(1, n + 1)
    x = 1 + 9 * i / n
    return phi_m * DEG * i / n, psi_m * DEG * np.log10(x)


def r2_range(l4, q_a, q_b):
    """Least and greatest BD^2 = 1 + l4^2 - 2 l4 cos q (l1 = 1) for q between q_a and
    q_b: the ends, and q = 0 or pi (mod 2 pi) where they fall inside (exact)."""
    a, b = min(q_a, q_b), max(q_a, q_b)
    qs = [a, b]
    k = math.ceil(a / math.pi)
    while k * math.pi < b:
        qs.append(k * math.pi)
        k += 1
    r2 = [1 + l4 * l4 - 2 * l4 * math.cos(q) for q in qs]
    return min(r2), max(r2)


def range_g(l2, l3, l4, q_a, q_b, mu_min):
    """>= 0 feasible: assembly and mu_min <= angle BCD <= 180 - mu_min for every input
    between q_a and q_b (the extremes of BD, exact)."""
    lo, hi = r2_range(l4, q_a, q_b)
    c_lo = (l2 * l2 + l3 * l3 - lo) / (2 * l2 * l3)    # largest cos: least angle
    c_hi = (l2 * l2 + l3 * l3 - hi) / (2 * l2 * l3)
    cm = math.cos(mu_min * DEG)
    return np.array([cm - c_lo, c_hi + cm])


def crank_rocker_g(x, mu_min):
    """>= 0 feasible: g1 ... g6 and mu_min <= angle BCD <= 180 - mu_min over the
    revolution (式 7-12, 7-13), l1 = 1."""
    l = (1.0, x[0], x[1], x[2])
    g = -crank_g(*l)
    if np.any(g < 0):
        return np.concatenate([g, [0.0, 0.0]])
    lo, hi = mu_range(*l)
    return np.concatenate([g, [lo - mu_min * DEG, (180 - mu_min) * DEG - hi]])


def rocker_dev(x, dphi, dpsi, psi0=None):
    """Deviations (psi(phi0 + dphi) - psi0) - dpsi, l1 = 1; x = (l2, l3, l4, phi0 deg
    [, psi0 deg]); psi0 the rocker's own angle at phi0 when not a variable."""
    l2, l3, l4, p0 = x[:4]
    q = p0 * DEG + np.asarray(dphi)
    psi = psi_book(1.0, l2, l3, l4, q)
    base = x[4] * DEG if len(x) > 4 else psi_book(1.0, l2, l3, l4, p0 * DEG)
    return wrap(psi - base) - np.asarray(dpsi)


def penalized(parts):
    def pen(x):
        fx, g = parts(x)
        v = float(np.sum(np.maximum(-g, 0)))
        return fx if (fx is not None and v <= 0) else 10 + v
    return pen


def global_run(parts, bounds, popsize, seed, smooth):
    """DE with a big population on the penalized function, then polishes: SLSQP on
    the smooth constraints (sum of squares) or Nelder-Mead restarts (mean |dev|)."""
    pen = penalized(parts)
    r = optimize.differential_evolution(pen, bounds, popsize=popsize, tol=1e-12, seed=seed,
                                        maxiter=4000, polish=False, init="sobol")
    best = r.x, float(r.fun)
    for _ in range(4):
        if smooth:
            n = optimize.minimize(lambda x: parts(x)[0] if parts(x)[0] is not None else 10.0,
                                  best[0], method="SLSQP", bounds=bounds,
                                  constraints=[{"type": "ineq", "fun": lambda x: parts(x)[1]}],
                                  options={"ftol": 1e-16, "maxiter": 1000})
        else:
            n = optimize.minimize(pen, best[0], method="Nelder-Mead", bounds=bounds,
                                  options={"xatol": 1e-12, "fatol": 1e-16, "maxiter": 40000,
                                           "adaptive": True})
        if pen(n.x) <= best[1]:
            best = n.x, pen(n.x)
    return best


def exercise7_1(popsize=80, seed=0):
    """习题 7-1: y = lg x on [1, 10], input swing 90 deg, output 60 deg, 30 steps; x = (l2, l3, l4, phi0, psi0), l1 = 1; mean |dev|; crank-rocker, 45 <= mu <= 135."""
    dphi, dpsi = lg_targets(phi_m=90.0, psi_m=60.0)
    bounds = [(1, 10), (1, 10), (1, 10), (0, 360), (0, 360)]

    def parts(x):
        g = crank_rocker_g(x, 45.0)
        d = rocker_dev(x, dphi, dpsi)
        return (float(np.mean(np.abs(d))) if np.all(np.isfinite(d)) else None), g

    x, f = global_run(parts, bounds, popsize, seed, smooth=False)
    names = ["x.mechanism.l2", "x.mechanism.l3", "x.mechanism.l4", "x.objective.phi0",
             "x.objective.psi0"]
    return dict(zip(names, x), f=f, g_deg=list(parts(x)[1]))


EX72_PHI = -np.radians([0.0, 30, 60, 90, 120])
EX72_PSI = -np.radians([0.0, 17, 36, 59, 88])


def exercise7_2(popsize=80, seed=0, mu_min=30.0):
    """习题 7-2: the five clockwise pairs; x = (l2, l3, l4, phi0), l1 = 1, psi0 the
    rocker's angle at phi0; sum of squares; crank-rocker, mu within [30, 150]."""
    bounds = [(1, 10), (1, 10), (1, 10), (0, 360)]

    def parts(x):
        g = crank_rocker_g(x, mu_min)
        d = rocker_dev(x, EX72_PHI, EX72_PSI)
        return (float(np.sum(d * d)) if np.all(np.isfinite(d)) else None), g

    x, f = global_run(parts, bounds, popsize, seed, smooth=True)
    names = ["x.mechanism.l2", "x.mechanism.l3", "x.mechanism.l4", "x.objective.phi0"]
    return dict(zip(names, x), f=f, g=list(parts(x)[1]))


# ----------------------------------------------------------------------------- 习题 7-3, 7-4
EX73_X = np.array([9.50, 9.00, 7.96, 5.65, 4.36, 3.24, 3.26, 4.79, 6.58, 9.12])
EX73_Y = np.array([8.26, 8.87, 9.51, 9.94, 9.70, 9.00, 8.36, 8.11, 8.0, 7.89])
EX74_X = np.array([26.0, 23, 20, 17, 13, 10, 20, 30])
EX74_Y = np.array([16.0, 17, 17, 16, 15, 11, 6, 12])
EX74_DT = np.radians([0.0, 22, 44, 66, 88, 129, 221, 314])
#: x = (Ax, Ay, Dx, Dy, l1, l2, l3, along, normal[, theta0 deg])
GENERAL_NAMES = ["x.mechanism.ground.A.0", "x.mechanism.ground.A.1", "x.mechanism.ground.D.0",
                 "x.mechanism.ground.D.1", "x.mechanism.driver.0.length",
                 "x.mechanism.dyad.0.lengths.0", "x.mechanism.dyad.0.lengths.1",
                 "x.mechanism.point.0.along", "x.mechanism.point.0.normal"]


def coupler_point(x, theta):
    """M of a general four-bar at crank angles theta (absolute, from +x): x as
    GENERAL_NAMES, arrays broadcast (x[k] of shape (S, 1) with theta (1, N))."""
    ax, ay, dx_, dy_, l1, l2, l3, along, normal = x[:9]
    bx, by = ax + l1 * np.cos(theta), ay + l1 * np.sin(theta)
    ex, ey = dx_ - bx, dy_ - by
    d = np.hypot(ex, ey)
    a = (l2 * l2 - l3 * l3 + d * d) / (2 * d)
    with np.errstate(invalid="ignore"):
        h = np.sqrt(l2 * l2 - a * a)                 # NaN: does not assemble
    cx, cy = bx + (a * ex - h * ey) / d, by + (a * ey + h * ex) / d   # left of B->D
    ux, uy = (cx - bx) / l2, (cy - by) / l2
    return bx + along * ux - normal * uy, by + along * uy + normal * ux


def general_g(x, mu_min=30.0):
    """>= 0 feasible: g1 ... g6 (l4 = |AD|) and mu_min <= angle BCD <= 180 - mu_min."""
    l4 = math.hypot(x[2] - x[0], x[3] - x[1])
    l = (x[4], x[5], x[6], l4)
    g = -crank_g(*l)
    if np.any(g < 0):
        return np.concatenate([g, [0.0, 0.0]])
    lo, hi = mu_range(*l)
    return np.concatenate([g, [lo - mu_min * DEG, (180 - mu_min) * DEG - hi]])


def curve_distances(x, tx, ty, n=720, refine=True):
    """Distance of each target to the TRUE closed coupler curve: nearest of n
    samples, then a bounded scalar search on the exact curve between the
    neighbouring samples."""
    th = np.linspace(0, TWO_PI, n, endpoint=False)
    mx, my = coupler_point(x, th)
    d2 = (mx[:, None] - tx[None, :]) ** 2 + (my[:, None] - ty[None, :]) ** 2
    k = np.argmin(d2, axis=0)
    if not refine:
        return np.sqrt(d2[k, np.arange(len(tx))])
    out = []
    step = TWO_PI / n
    for j, kj in enumerate(k):
        def dist2(t):
            px, py = coupler_point(x, t)
            return (px - tx[j]) ** 2 + (py - ty[j]) ** 2
        r = optimize.minimize_scalar(dist2, bounds=(th[kj] - step, th[kj] + step),
                                     method="bounded", options={"xatol": 1e-12})
        out.append(math.sqrt(min(r.fun, d2[kj, j])))
    return np.array(out)


def _path_population(X, tx, ty, timed):
    """Vectorized penalized objective of a DE population X (n, S)."""
    S = X.shape[1]
    cols = [X[i][:, None] for i in range(9)]
    if timed:
        th = X[9][:, None] * DEG + EX74_DT[None, :]
        mx, my = coupler_point(cols, th)
        d2 = (mx - tx) ** 2 + (my - ty) ** 2
        f = np.sum(d2, axis=1)
    else:
        th = np.linspace(0, TWO_PI, 360, endpoint=False)[None, :]
        mx, my = coupler_point(cols, th)
        d2 = (mx[:, :, None] - tx) ** 2 + (my[:, :, None] - ty) ** 2
        f = np.sum(np.min(d2, axis=1), axis=1)
    out = np.empty(S)
    for s in range(S):
        v = float(np.sum(np.maximum(-general_g(X[:, s]), 0)))
        out[s] = f[s] if (v <= 0 and np.isfinite(f[s])) else 1e3 + v
    return out


def path_run(timed, bounds, popsize, seeds, exact):
    tx, ty = (EX74_X, EX74_Y) if timed else (EX73_X, EX73_Y)
    cons = [{"type": "ineq", "fun": general_g}]
    best = None
    for seed in seeds:
        r = optimize.differential_evolution(
            lambda X: _path_population(np.atleast_2d(X.T).T if X.ndim == 1 else X, tx, ty,
                                       timed),
            bounds, popsize=popsize, tol=1e-10, seed=seed, maxiter=3000, polish=False,
            vectorized=True, init="sobol")
        x = r.x
        for _ in range(3):
            p = optimize.minimize(lambda z: (lambda v: v if np.isfinite(v) else 1e3)(exact(z)), x,
                                  method="SLSQP", bounds=bounds, constraints=cons,
                                  options={"ftol": 1e-15, "maxiter": 1000})
            if np.min(general_g(p.x)) >= -1e-10 and exact(p.x) <= exact(x):
                x = p.x
        fx = exact(x)
        if best is None or fx < best[1]:
            best = (x, fx)
    return best


def exercise7_3(popsize=30, seeds=(0, 1, 2)):
    """习题 7-3: the ten points, no timing; sum of squared distances to the true
    coupler curve; crank, 30 <= mu <= 150."""
    bounds = [(-10, 20)] * 4 + [(0.5, 10), (0.5, 20), (0.5, 20), (-15, 15), (-15, 15)]

    def exact(x):
        return float(np.sum(curve_distances(x, EX73_X, EX73_Y) ** 2))

    x, f = path_run(False, bounds, popsize, seeds, exact)
    d = curve_distances(x, EX73_X, EX73_Y)
    return dict(zip(GENERAL_NAMES, x), f=f, dist_max=float(d.max()), g=list(general_g(x)))


def exercise7_4(popsize=30, seeds=(0, 1, 2)):
    """习题 7-4: the eight points at theta0 + dtheta (counter-clockwise); sum of squared
    distances; crank, 30 <= mu <= 150."""
    bounds = [(-20, 50)] * 4 + [(0.5, 20), (0.5, 40), (0.5, 40), (-30, 30), (-30, 30),
                                 (0, 360)]

    def exact(x):
        mx, my = coupler_point(x, x[9] * DEG + EX74_DT)
        return float(np.sum((mx - EX74_X) ** 2 + (my - EX74_Y) ** 2))

    x, f = path_run(True, bounds, popsize, seeds, exact)
    return dict(zip(GENERAL_NAMES + ["x.objective.theta0"], x), f=f, g=list(general_g(x)))


# ----------------------------------------------------------------------------- 例 2-1, least peak |Mb|
EX21 = dict(l1=0.4, l4=1.2, m=(1.2, 3.0, 2.2), J=(0.016, 0.25, 0.09), g=10.0, M3=-100.0,
            w1=10.0)


def mb_ex2_1(l2, l3, theta):
    """例 2-1's balancing torque [N m] at crank angles theta by virtual work: Mb w1 +
    sum(F . v + M w) = 0 over inertia forces and couples, weights and the rocker's
    torque; centres of mass at mid-links; positions, velocities and accelerations
    of the open four-bar from the loop l1 e1 + l2 e2 = l4 + l3 e3 (analytic)."""
    p = EX21
    l1, l4, w1 = p["l1"], p["l4"], p["w1"]
    e1 = np.exp(1j * theta)
    B = l1 * e1
    d = l4 - B
    dist = np.abs(d)
    a = (l2 * l2 - l3 * l3 + dist ** 2) / (2 * dist)
    h = np.sqrt(l2 * l2 - a * a)
    C = B + d / dist * (a + 1j * h)                  # left of B->D: the open branch
    e2, e3 = (C - B) / l2, (C - l4) / l3
    # l2 w2 (i e2) - l3 w3 (i e3) = -l1 w1 (i e1): real 2x2 in (w2, w3)
    u, v = 1j * e2 * l2, -1j * e3 * l3

    def solve(rhs):
        det = u.real * v.imag - u.imag * v.real
        x = (rhs.real * v.imag - rhs.imag * v.real) / det
        y = (u.real * rhs.imag - u.imag * rhs.real) / det
        return x, y

    w2, w3 = solve(-l1 * w1 * 1j * e1)
    al2, al3 = solve(l1 * w1 ** 2 * e1 + l2 * w2 ** 2 * e2 - l3 * w3 ** 2 * e3)
    vS = [0.5 * l1 * w1 * 1j * e1, l1 * w1 * 1j * e1 + 0.5 * l2 * w2 * 1j * e2,
          0.5 * l3 * w3 * 1j * e3]
    aS = [-0.5 * l1 * w1 ** 2 * e1,
          -l1 * w1 ** 2 * e1 + 0.5 * l2 * (al2 * 1j - w2 ** 2) * e2,
          0.5 * l3 * (al3 * 1j - w3 ** 2) * e3]
    w, al = [w1, w2, w3], [0.0, al2, al3]
    power = p["M3"] * w3
    for k in range(3):
        m, J = p["m"][k], p["J"][k]
        F = -m * aS[k] - 1j * m * p["g"]
        power = power + (F.real * vS[k].real + F.imag * vS[k].imag) - J * al[k] * w[k]
    return -power / w1


def peak_mb(x, n=3600):
    """max |Mb| over the revolution: a 0.1 deg scan refined by a bounded search."""
    th = np.linspace(0, TWO_PI, n, endpoint=False)
    mb = np.abs(mb_ex2_1(x[0], x[1], th))
    k = int(np.argmax(mb))
    r = optimize.minimize_scalar(lambda t: -abs(float(mb_ex2_1(x[0], x[1], np.array(t)))),
                                 bounds=(th[k] - TWO_PI / n, th[k] + TWO_PI / n),
                                 method="bounded", options={"xatol": 1e-12})
    return max(-r.fun, mb[k])


def ex2_1_min_mb(grid=121):
    """Least peak |Mb| of 例 2-1 over l2 (coupler) and l3 (rocker) [m] in
    [0.8, 1.4] x [0.5, 1.1], crank (g1 ... g6) and 40 <= mu <= 140: a grid, then
    Nelder-Mead (the max is not smooth) from the best grid points."""
    bounds = [(0.8, 1.4), (0.5, 1.1)]

    def pen(x):
        g = -crank_g(EX21["l1"], x[0], x[1], EX21["l4"])
        if np.all(g >= 0):
            lo, hi = mu_range(EX21["l1"], x[0], x[1], EX21["l4"])
            g = np.concatenate([g, [lo - 40 * DEG, 140 * DEG - hi]])
        v = float(np.sum(np.maximum(-g, 0)))
        if v > 0 or not (bounds[0][0] <= x[0] <= bounds[0][1]
                         and bounds[1][0] <= x[1] <= bounds[1][1]):
            return 1e3 + v
        return peak_mb(x, 720)

    u = np.linspace(*bounds[0], grid)
    w = np.linspace(*bounds[1], grid)
    vals = sorted((pen((a, b)), a, b) for a in u for b in w)
    best = None
    for f0, a, b in vals[:8]:
        r = optimize.minimize(pen, [a, b], method="Nelder-Mead",
                              options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
        if best is None or r.fun < best[1]:
            best = (r.x, r.fun)
    x = best[0]
    th = np.linspace(0, TWO_PI, 3600, endpoint=False)
    mb = mb_ex2_1(x[0], x[1], th)
    return {"x.mechanism.l2": x[0], "x.mechanism.l3": x[1], "f": peak_mb(x),
            "Mb_max": float(mb.max()), "Mb_min": float(mb.min()),
            "mu_deg": [v / DEG for v in mu_range(EX21["l1"], x[0], x[1], EX21["l4"])],
            "check_ex2_1_peak": peak_mb((1.0, 0.7))}


PROBLEMS = {"ex7-1": ex7_1, "exercise7-1": exercise7_1, "exercise7-2": exercise7_2,
            "exercise7-3": exercise7_3, "exercise7-4": exercise7_4,
            "ex2-1-min-Mb": ex2_1_min_mb}


def main(names):
    out = {}
    for name in names or PROBLEMS:
        t = time.perf_counter()
        res = PROBLEMS[name]()
        res["time_s"] = time.perf_counter() - t
        out[name] = res
        print(name, json.dumps(res, default=float), flush=True)
    return out


if __name__ == "__main__":
    main(sys.argv[1:])
