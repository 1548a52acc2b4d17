#!/usr/bin/env python3
"""Independent reference numbers for 习题 1-9, 1-10 and 1-11 (``mechcli kin``).

Deliberately self-contained: imports nothing from mechcli (numpy and the standard
library only), and each mechanism is written out here from the exercise text and the
figure reading stated in its config (configs/ch1/exercise1-9.toml, exercise1-10.toml,
exercise1-11.toml), not read through mechcli's spec layer.

Models (lengths in mm, angles CCW from +x, the crank at constant speed, alpha1 = 0)
-------------------------------------------------------------------------------
* 1-9, crank AB with two rods and two sliders: A = (0, 0), AB = 100, omega1 = 10 rad/s.
  Rod 2 (BC = 200) drives slider 3 on the x axis (C to the right of the crank),
  rod 4 (BD = 200) drives slider 5 on the y axis (D above the crank).
  Closed forms: xC = l1 cos t + sqrt(l2^2 - l1^2 sin^2 t),
  yD = l1 sin t + sqrt(l4^2 - l1^2 cos^2 t).
* 1-10, punch press: D = (0, 0) on the slider's guide (the y axis), A = (H_x, H_y) =
  (350, 200); crank AB = 100 (omega1 = 1 rad/s: the exercise gives no speed); four-bar
  ABCD with BC = 400, CD = 125, C to the left of the directed line B -> D; rod CE = 540
  to slider 5 on x = 0 below C (the smaller y root).
* 1-11, six-bar with a swinging block: C = (0, 0), A = (0, 550); crank AB = 150 turning
  clockwise, omega1 = -10 rad/s; rod 2 through B slides in block 3 pivoted at C (the
  guide direction u = (B - C)/|B - C|, theta3 = atan2 u, s23 = |B - C|); D on rod 2
  between B and C, D = B - 80 u; rod DE = 500 to slider 5 on the horizontal line through
  A, E to the right of D (the larger x root); sE = xE.

Method
------
* positions: closed-form geometry (circle-circle and circle-line intersections);
* velocities and accelerations: the loop equations differentiated once and twice by hand,
  in vector form (k x r = the vector r turned +90 degrees):
    crank      vB = w1 k x (B-A),            aB = -w1^2 (B-A)
    RRR  J     vJ = vP + wa k x (J-P) = vQ + wb k x (J-Q)              (2x2, Cramer)
               aJ = aP + al_a k x (J-P) - wa^2 (J-P) = aQ + al_b k x (J-Q) - wb^2 (J-Q)
    RRP  J     J = G + s u:  vP + w k x (J-P) = sd u                    (2x2, Cramer)
               aP + al k x (J-P) - w^2 (J-P) = sdd u
    RPR        B - C = s u:  vB = sd u + s w n  (n = k x u)
               aB = (sdd - s w^2) u + (s al + 2 sd w) n
    point      D = O + r (fixed on a link): vD = vO + w k x r, aD = aO + al k x r - w^2 r;
  checked by ``fd_check`` against 8th-order central differences of the positions (for the
  velocities) and of the velocities (for the accelerations), h = 0.002 rad, and the
  positions by ``loop_check`` (every length and guide condition recomputed);
* extremes over one turn (theta1 in [0, 360]): the sign changes of the derivative on a
  0.05-degree scan, each refined by bisection to 1e-13 rad on the analytic derivative
  (omega for theta, v for s, alpha for omega, a for v) or, for an acceleration, on its
  central difference (h = 1e-5 rad); the sweep's ends are candidates too; the extreme is
  the function at the root.  The transmission angle's minimum is refined on omega2 - omega3;
  1-10's rocker limits are also found in closed form (``rocker_limits``, the cosine law).

Run:  python3 tests/reference/independent_exercises_ch1b.py
"""
from __future__ import annotations

import math

import numpy as np

DEG = math.pi / 180.0
TWO_PI = 2.0 * math.pi
SCAN_N = 7200            # 0.05-degree scan of one turn


# ----------------------------------------------------------------------------- vectors
def _k(v):
    """k x v: the vector v turned +90 degrees (arrays of shape (..., 2))."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _col(x):
    return np.asarray(x, float)[..., None]


def _solve2(c1, c2, rhs):
    """x, y with x c1 + y c2 = rhs (vectors (..., 2)), Cramer's rule."""
    det = _cross(c1, c2)
    return _cross(rhs, c2) / det, _cross(c1, rhs) / det


# ----------------------------------------------------------------------------- elements
def crank(A, length, th, w):
    r = length * np.stack([np.cos(th), np.sin(th)], axis=-1)
    return A + r, w * _k(r), -(w ** 2) * r


def rrr(P, vP, aP, la, Q, vQ, aQ, lb, side):
    """Joint J with |J-P| = la, |J-Q| = lb, left of P -> Q for side = +1.
    Returns J, vJ, aJ, (theta_a, w_a, al_a) of P->J and (theta_b, w_b, al_b) of Q->J."""
    d = Q - P
    L = np.hypot(d[..., 0], d[..., 1])
    a = (la ** 2 - lb ** 2 + L ** 2) / (2.0 * L)
    h2 = la ** 2 - a ** 2
    if np.any(h2 < 0):
        raise ValueError("RRR dyad cannot assemble")
    u = d / L[..., None]
    J = P + _col(a) * u + side * _col(np.sqrt(h2)) * _k(u)
    ra, rb = J - P, J - Q
    # vP + wa k ra = vQ + wb k rb  ->  wa (k ra) + wb (-k rb) = vQ - vP
    wa, wb = _solve2(_k(ra), -_k(rb), vQ - vP)
    vJ = vP + _col(wa) * _k(ra)
    rhs = aQ - aP + _col(wa ** 2) * ra - _col(wb ** 2) * rb
    ala, alb = _solve2(_k(ra), -_k(rb), rhs)
    aJ = aP + _col(ala) * _k(ra) - _col(wa ** 2) * ra
    ang = lambda r: np.arctan2(r[..., 1], r[..., 0])  # noqa: E731
    return J, vJ, aJ, (ang(ra), wa, ala), (ang(rb), wb, alb)


def rrp(P, vP, aP, length, G, u, branch):
    """Slider pin J = G + s u on a fixed line, |J - P| = length; branch +1 the larger s.
    Returns s, sd, sdd, J, vJ, aJ, (theta, w, al) of the rod P->J."""
    G = np.asarray(G, float)
    u = np.asarray(u, float)
    g = P - G
    along = _dot(g, u)
    across = _cross(u, g)
    disc = length ** 2 - across ** 2
    if np.any(disc < 0):
        raise ValueError("RRP dyad cannot assemble")
    s = along + branch * np.sqrt(disc)
    J = G + _col(s) * u
    r = J - P
    ub = np.broadcast_to(u, r.shape)
    # vP + w k r = sd u  ->  w (k r) + sd (-u) = -vP
    w, sd = _solve2(_k(r), -ub, -vP)
    al, sdd = _solve2(_k(r), -ub, -aP + _col(w ** 2) * r)
    vJ = _col(sd) * u
    aJ = _col(sdd) * u
    return s, sd, sdd, J, vJ, aJ, (np.arctan2(r[..., 1], r[..., 0]), w, al)


def rpr(B, vB, aB, C):
    """Guide through fixed pivot C and the block pin B (no offset, s > 0).
    Returns s, sd, sdd, (theta, w, al), u."""
    d = B - np.asarray(C, float)
    s = np.hypot(d[..., 0], d[..., 1])
    u = d / s[..., None]
    n = _k(u)
    sd = _dot(vB, u)
    w = _dot(vB, n) / s
    sdd = _dot(aB, u) + s * w ** 2
    al = (_dot(aB, n) - 2.0 * sd * w) / s
    return s, sd, sdd, (np.arctan2(u[..., 1], u[..., 0]), w, al), u


def point_on(O, vO, aO, r, w, al):
    """A point at O + r on a link turning at w, al (r already rotated with the link)."""
    return O + r, vO + _col(w) * _k(r), aO + _col(al) * _k(r) - _col(w ** 2) * r


def _put(out, name, P, vP, aP):
    out["x" + name], out["y" + name] = P[..., 0], P[..., 1]
    out["vx" + name], out["vy" + name] = vP[..., 0], vP[..., 1]
    out["ax" + name], out["ay" + name] = aP[..., 0], aP[..., 1]


def _link(out, n, tw):
    out[f"theta{n}"], out[f"omega{n}"], out[f"alpha{n}"] = tw


# ----------------------------------------------------------------------------- 习题 1-9
class Exercise1_9:
    name = "exercise1-9"
    omega1 = 10.0
    l1, l2, l4 = 100.0, 200.0, 200.0
    A = np.array([0.0, 0.0])

    def state(self, th):
        th = np.asarray(th, float)
        B, vB, aB = crank(self.A, self.l1, th, self.omega1)
        out = {}
        s, sd, sdd, _, _, _, tw = rrp(B, vB, aB, self.l2, self.A, (1.0, 0.0), +1)
        out["sC"], out["vC"], out["aC"] = s, sd, sdd
        _link(out, 2, tw)
        s, sd, sdd, _, _, _, tw = rrp(B, vB, aB, self.l4, self.A, (0.0, 1.0), +1)
        out["sD"], out["vD"], out["aD"] = s, sd, sdd
        _link(out, 4, tw)
        return out

    def closed_form(self, th):
        """The textbook closed forms of the two centric slider-cranks (a check of rrp)."""
        l1, l2, l4 = self.l1, self.l2, self.l4
        return {"sC": l1 * np.cos(th) + np.sqrt(l2 ** 2 - (l1 * np.sin(th)) ** 2),
                "sD": l1 * np.sin(th) + np.sqrt(l4 ** 2 - (l1 * np.cos(th)) ** 2),
                "theta2": np.arcsin(-l1 * np.sin(th) / l2),
                "theta4": np.arccos(-l1 * np.cos(th) / l4)}

    quantities = ("theta2", "theta4", "sC", "sD", "omega2", "omega4", "vC", "vD",
                  "alpha2", "alpha4", "aC", "aD")
    slides = ("sC", "sD")
    swings = (2, 4)
    gamma = None


# ----------------------------------------------------------------------------- 习题 1-10
class Exercise1_10:
    name = "exercise1-10"
    omega1 = 1.0
    l1, l2, l3, l4 = 100.0, 400.0, 125.0, 540.0
    A = np.array([350.0, 200.0])
    D = np.array([0.0, 0.0])

    def state(self, th):
        th = np.asarray(th, float)
        B, vB, aB = crank(self.A, self.l1, th, self.omega1)
        Dg = np.broadcast_to(self.D, B.shape)
        zero = np.zeros_like(B)
        C, vC, aC, t2, t3 = rrr(B, vB, aB, self.l2, Dg, zero, zero, self.l3, +1)
        out = {}
        _link(out, 2, t2)
        _link(out, 3, t3)
        s, sd, sdd, _, _, _, t4 = rrp(C, vC, aC, self.l4, self.D, (0.0, 1.0), -1)
        _link(out, 4, t4)
        out["sE"], out["vE"], out["aE"] = s, sd, sdd
        # transmission angle at C: the acute angle between BC and DC
        cosmu = np.cos(t2[0] - t3[0])
        out["gammaC"] = np.arccos(np.clip(np.abs(cosmu), 0.0, 1.0))
        out["dgammaC"] = t2[1] - t3[1]
        return out

    quantities = ("theta2", "theta3", "theta4", "sE", "omega2", "omega3", "omega4", "vE",
                  "alpha2", "alpha3", "alpha4", "aE")
    slides = ("sE",)
    swings = (2, 3, 4)
    gamma = "gammaC"

    def rocker_limits(self):
        """theta3 [deg] at the rocker's two limit positions by the cosine law: crank and
        coupler collinear, |AC| = l2 + l1 (extended) or l2 - l1 (folded); C is then the
        intersection of the circles (A, |AC|) and (D, l3) on the branch of the linkage
        (C left of the directed line B -> D)."""
        out = []
        for ac, sgn in ((self.l2 + self.l1, +1.0), (self.l2 - self.l1, -1.0)):
            d = self.D - self.A
            L = math.hypot(*d)
            a = (ac ** 2 - self.l3 ** 2 + L ** 2) / (2 * L)
            h = math.sqrt(ac ** 2 - a ** 2)
            u = d / L
            for side in (+1.0, -1.0):
                C = self.A + a * u + side * h * np.array([-u[1], u[0]])
                B = self.A + sgn * self.l1 * (C - self.A) / ac
                if _cross(self.D - B, C - B) > 0:          # C left of B -> D
                    out.append(math.degrees(math.atan2(*(C - self.D)[::-1])))
        return sorted(out)


# ----------------------------------------------------------------------------- 习题 1-11
class Exercise1_11:
    name = "exercise1-11"
    omega1 = -10.0              # clockwise
    l1, lAC, lBD, l4 = 150.0, 550.0, 80.0, 500.0
    C = np.array([0.0, 0.0])
    A = np.array([0.0, 550.0])

    def state(self, th):
        th = np.asarray(th, float)
        B, vB, aB = crank(self.A, self.l1, th, self.omega1)
        s, sd, sdd, t3, u = rpr(B, vB, aB, self.C)
        out = {"s23": s, "v23": sd, "a23": sdd}
        _link(out, 3, t3)
        D, vD, aD = point_on(B, vB, aB, -self.lBD * u, t3[1], t3[2])
        _put(out, "D", D, vD, aD)
        s, sd, sdd, _, _, _, t4 = rrp(D, vD, aD, self.l4, self.A, (1.0, 0.0), +1)
        _link(out, 4, t4)
        out["sE"], out["vE"], out["aE"] = s, sd, sdd
        return out

    quantities = ("theta3", "theta4", "s23", "sE", "xD", "yD", "omega3", "omega4", "v23",
                  "vE", "vxD", "vyD", "alpha3", "alpha4", "a23", "aE", "axD", "ayD")
    slides = ("s23", "sE")
    swings = (3, 4)
    gamma = None


EXERCISES = (Exercise1_9(), Exercise1_10(), Exercise1_11())

#: quantity prefix -> (derivative prefix (None: a central difference), unit suffix)
_RULES = (("theta", "omega", "deg"), ("omega", "alpha", "rad_s"), ("alpha", None, "rad_s2"),
          ("vx", "ax", "mm_s"), ("vy", "ay", "mm_s"), ("ax", None, "mm_s2"),
          ("ay", None, "mm_s2"), ("x", "vx", "mm"), ("y", "vy", "mm"), ("s", "v", "mm"),
          ("v", "a", "mm_s"), ("a", None, "mm_s2"))


def _rule(q):
    for pre, dpre, unit in _RULES:
        if q.startswith(pre):
            return (dpre + q[len(pre):] if dpre else None), unit
    raise KeyError(q)


def _derivative(ex, q):
    """d q / d theta1 (up to the constant factor omega1) as a function of theta1."""
    dq, _unit = _rule(q)
    if dq is not None:
        return lambda th: ex.state(th)[dq]
    h = 1e-5
    return lambda th: (ex.state(th + h)[q] - ex.state(th - h)[q]) / (2 * h)


def _bisect(f, lo, hi, tol=1e-13):
    """Vectorised bisection of the sign changes of f on [lo, hi] (arrays)."""
    lo, hi = np.array(lo, float), np.array(hi, float)
    flo = f(lo)
    for _ in range(80):
        if np.all(hi - lo <= tol):
            break
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        left = np.sign(fm) == np.sign(flo)
        lo = np.where(left, mid, lo)
        flo = np.where(left, fm, flo)
        hi = np.where(left, hi, mid)
    return 0.5 * (lo + hi)


def extremes(ex, q, dfun=None, kink_max=False):
    """(max, th_at_max, min, th_at_min), th1 in rad in [0, 2 pi].  ``kink_max``: the
    maximum is at a kink (a transmission angle's 90 degrees), not located here."""
    grid = np.linspace(0.0, TWO_PI, SCAN_N + 1)
    f = ex.state(grid)[q]
    dfun = dfun or _derivative(ex, q)
    g = dfun(grid)
    idx = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]
    cands = [(float(f[0]), 0.0), (float(f[-1]), TWO_PI)]
    cands += [(float(f[i]), float(grid[i])) for i in np.nonzero(g == 0.0)[0]]
    if len(idx):
        roots = _bisect(dfun, grid[idx], grid[idx + 1])
        vals = ex.state(roots)[q]
        cands += list(zip(vals.tolist(), roots.tolist()))
    vmax = max(cands, key=lambda c: c[0])
    vmin = min(cands, key=lambda c: c[0])
    # the refined extremes bound the scan
    assert kink_max or vmax[0] >= f.max() - 1e-9 * max(1.0, abs(f.max()))
    assert vmin[0] <= f.min() + 1e-9 * max(1.0, abs(f.min()))
    return vmax[0], vmax[1], vmin[0], vmin[1]


def reference(ex):
    """The reference results of one exercise, named as mechcli's ``--json`` results."""
    grid = np.linspace(0.0, TWO_PI, SCAN_N + 1)
    st = ex.state(grid)
    res = {}
    for q in ex.quantities:
        if q.startswith("theta"):   # no angle jumps across +-180 degrees in these models
            assert np.max(np.abs(np.diff(st[q]))) < 0.1, q
        vmax, tmax, vmin, tmin = extremes(ex, q)
        _dq, unit = _rule(q)
        scale = 1.0 / DEG if unit == "deg" else 1.0
        res[f"{q}_max_{unit}"] = vmax * scale
        res[f"{q}_max_at_deg"] = tmax / DEG
        res[f"{q}_min_{unit}"] = vmin * scale
        res[f"{q}_min_at_deg"] = tmin / DEG
    for n in ex.swings:
        res[f"theta{n}_swing_deg"] = res[f"theta{n}_max_deg"] - res[f"theta{n}_min_deg"]
    for s in ex.slides:
        res[f"{s}_stroke_mm"] = res[f"{s}_max_mm"] - res[f"{s}_min_mm"]
    if ex.gamma:
        _vmax, _tmax, vmin, tmin = extremes(ex, ex.gamma,
                                            dfun=lambda th: ex.state(th)["d" + ex.gamma],
                                            kink_max=True)
        res[f"{ex.gamma}_min_deg"] = vmin / DEG
        res[f"{ex.gamma}_min_at_deg"] = tmin / DEG
    res["positions"] = 361          # [input] step = 1 degree over 0 .. 360, both ends
    return res


def fd_check(ex, h=0.002):
    """Largest relative |analytic - 8th-order central difference| over a 1-degree grid:
    velocities against the differenced positions, accelerations against the differenced
    velocities (d/dt = omega1 d/dtheta1); truncation O(h^8)."""
    c1 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    offs = np.arange(-4, 5)
    th = np.arange(360) * DEG
    s = ex.state(th[:, None] + offs[None, :] * h)
    ref = ex.state(th)
    worst = {}
    for q in ex.quantities:
        dq, _unit = _rule(q)
        if dq is None:
            continue
        fd = (s[q] @ c1) / h * ex.omega1
        worst[dq] = float(np.max(np.abs(fd - ref[dq])) / np.max(np.abs(ref[dq])))
    return worst


def loop_check(ex):
    """Largest loop-closure residual [mm] of the positions over a 1-degree grid."""
    th = np.arange(360) * DEG
    st = ex.state(th)
    if isinstance(ex, Exercise1_9):
        B = ex.l1 * np.stack([np.cos(th), np.sin(th)], -1)
        r = [np.hypot(st["sC"] - B[:, 0], B[:, 1]) - ex.l2,
             np.hypot(B[:, 0], st["sD"] - B[:, 1]) - ex.l4,
             ex.closed_form(th)["sC"] - st["sC"], ex.closed_form(th)["sD"] - st["sD"]]
    elif isinstance(ex, Exercise1_10):
        B = ex.A + ex.l1 * np.stack([np.cos(th), np.sin(th)], -1)
        C = ex.D + ex.l3 * np.stack([np.cos(st["theta3"]), np.sin(st["theta3"])], -1)
        BC = B + ex.l2 * np.stack([np.cos(st["theta2"]), np.sin(st["theta2"])], -1)
        E = C + ex.l4 * np.stack([np.cos(st["theta4"]), np.sin(st["theta4"])], -1)
        r = [np.hypot(*(BC - C).T), E[:, 0], E[:, 1] - st["sE"]]
    else:
        B = ex.A + ex.l1 * np.stack([np.cos(th), np.sin(th)], -1)
        u = np.stack([np.cos(st["theta3"]), np.sin(st["theta3"])], -1)
        D = np.stack([st["xD"], st["yD"]], -1)
        E = D + ex.l4 * np.stack([np.cos(st["theta4"]), np.sin(st["theta4"])], -1)
        r = [np.hypot(*(ex.C + st["s23"][:, None] * u - B).T),
             np.hypot(*(B - ex.lBD * u - D).T), E[:, 1] - ex.A[1], E[:, 0] - st["sE"]]
    return float(max(np.max(np.abs(x)) for x in r))


def main():
    for ex in EXERCISES:
        print(f"== {ex.name}")
        for k, v in reference(ex).items():
            print(f"{k:26s} {v:.10f}" if isinstance(v, float) else f"{k:26s} {v}")
        print("velocity/acceleration vs finite differences, max rel |diff|:",
              {k: f"{v:.1e}" for k, v in fd_check(ex).items()})
        print("loop closure, max |residual| [mm]:", f"{loop_check(ex):.1e}")


if __name__ == "__main__":
    main()
