#!/usr/bin/env python3
"""Independent reference numbers for 习题 1-4 … 1-8 (``configs/ch1/exercise1-4.toml`` …
``exercise1-8.toml``, ``mechcli kin``).

Self-contained: numpy only, nothing from mechcli.  Every mechanism is written out here in the
reading its config states (the figures are lost; see the ``# FIGURE-READING`` comments there).
Lengths in mm, angles CCW from +x, the input angle theta1 of link 1 CCW from +x, constant
input speed (alpha1 = 0).  ``J v`` is v turned +90°.

Models and their hand-differentiated equations
-----------------------------------------------
1-4 (swinging guide bar with an offset guide): C = (0, 0), A = (0, 300), crank AB = 100,
    omega1 = 10.  The guide line of bar 3 runs at e = CK = 40 to the left of its direction
    u = e^(i theta3) from C:  B = s u + e n  (n = J u), i.e. B = (s + i e) u, so
    s = sqrt(|B|² - e²) > 0 and theta3 = arg B - atan2(e, s).  Differentiating in the turning
    frame (u' = omega3 n, n' = -omega3 u):
        vB = (s' - omega3 e) u + omega3 s n
        aB = (s'' - alpha3 e - omega3² s) u + (alpha3 s + 2 omega3 s' - omega3² e) n
    so omega3 = vB.n / s, s' = vB.u + omega3 e, alpha3 = (aB.n - 2 omega3 s' + omega3² e)/s,
    s'' = aB.u + alpha3 e + omega3² s.
1-5 (rotating guide bar driven by the guide): C = (0, 0), A = (0, 50) (y along CA); guide 1
    turns about A at theta1 = phi1 + 90° (phi1 from +y), omega1 = 20; block 2 at B on it,
    B = A + S u1 with S > 0 and |B - C| = l3 = 100; D on CB produced, CD = 120.  With
    delta = theta3 - theta1 (theta3 the direction C -> B):
        S = -u1.(A - C) + sqrt((u1.(A - C))² - |A - C|² + l3²)
        omega3 = S omega1 / (l3 cos delta),  S' = -S omega1 tan delta
        alpha3 = (2 S' omega1 + l3 omega3² sin delta) / (l3 cos delta)
        S''    = S omega1² - l3 alpha3 sin delta - l3 omega3² cos delta
    (the components along u1 and n1 of  S'' u1 - S omega1² u1 + 2 S' omega1 n1 =
    l3 alpha3 n3 - l3 omega3² u3);  vD = 120 omega3 n3, aD = 120 (alpha3 n3 - omega3² u3).
1-6 (crank and rocking block): A = (0, 0), C = (-100, 0), crank AB = 30, omega1 = 10; bar 2
    from B through the block 3 pivoted at C: C - B = L u2.  Differentiating,
        -vB = L' u2 + L omega2 n2,   -aB = (L'' - L omega2²) u2 + (L alpha2 + 2 L' omega2) n2
    so omega2 = -vB.n2 / L, L' = -vB.u2, alpha2 = (-aB.n2 - 2 L' omega2)/L,
    L'' = -aB.u2 + L omega2².  D = B + 50 u2, E = D + 40 n2 (E to the left of B -> C).
1-7 (six-bar with piston 5): A = (0, 0), D = (225, 80); four-bar AB = 60, BC = 180, DC = 120
    with C to the left of B -> D; straight lever C-D-E, DE = 200 (E = D - 200 u3,
    u3 = (C - D)/120); rod EF = 300; piston 5 on the vertical line x = 310 (85 to the right
    of D), F above E: sF = yF.  omega1 = 100.
1-8 (swinging feed mechanism): A = (0, 0), D = (-90, 170); four-bar AB = 80, BC = 260,
    DC = 300 with C to the left of B -> D; E on DC produced, DE = 400; rod EF = 300;
    slider 5 on the horizontal line y = 0 through A, F to the left of E: sF = xF.
    omega1 = 400 r/min = 40 pi / 3 rad/s.
Four-bar loop (1-7, 1-8): B + l2 e2 = D + l3 e3 (C by circle intersection).  Its derivatives,
dotted with e3 and with e2 (J e2.e3 = sin(theta3 - theta2)):
    omega2 = -vB.e3 / (l2 Je2.e3),   omega3 = vB.e2 / (l3 Je3.e2)
    alpha2 = (-l3 omega3² - aB.e3 + l2 omega2² e2.e3) / (l2 Je2.e3)
    alpha3 = (aB.e2 - l2 omega2² + l3 omega3² e3.e2) / (l3 Je3.e2)
Rod and slider (RRP, 1-7, 1-8): F = G + s g = E + l4 e4 on a frame line through G with
direction g.  Dotted with J g and with g:
    omega4 = -vE.Jg / (l4 e4.g),           s'  = vE.g + l4 omega4 Je4.g
    alpha4 = (-aE.Jg + l4 omega4² e4.Jg) / (l4 e4.g),
    s''    = aE.g + l4 alpha4 Je4.g - l4 omega4² e4.g
A point P = O + a u + b n fixed on a link (angle theta, u = e^(i theta), n = J u):
    vP = vO + omega (a n - b u),  aP = aO + alpha (a n - b u) - omega² (a u + b n).

Extremes
--------
Each quantity is scanned over the input range at 0.05° and every sign change of its
theta1-derivative is refined by bisection (to the round-off of theta1); the range's ends are
candidates too (1-4 runs over phi1 = 1° … 360° as its statement asks); where an extreme is
reached at two positions (a symmetric pair, or both ends of a cycle) its angle is left out.
An oscillating link's angle is reported on its continuous branch through its value at the
start, taken in [-180°, 180°); a fully turning link's only as a swing of 360°.  The derivative is
exact where the model has it: omega/omega1 for an angle, v for a slide or a coordinate, alpha
or a (the next order) for a velocity (omega1 is constant).  For an acceleration it is an
8th-order central difference of the exact acceleration with h = 1e-3 rad (truncation
~h^8 f^(9), far below the round-off of ~1e-13 relative); its zero is located to ~1e-10 rad,
and the extreme's value, flat there, to round-off.  ``fd_check`` compares every analytic
velocity and acceleration with an 8th-order central difference of the next-lower quantity.

Run:  python3 tests/reference/independent_exercises_ch1a.py
"""
from __future__ import annotations

import math

import numpy as np

DEG = math.pi / 180.0
SCAN_STEP_DEG = 0.05
FD_H = 1e-3                      # rad, the step of the acceleration's derivative
C8 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
OFFS = np.arange(-4, 5)


# ---------------------------------------------------------------------------
# small vector helpers on (..., 2) arrays
# ---------------------------------------------------------------------------
def _J(v):
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _unit(th):
    return np.stack([np.cos(th), np.sin(th)], axis=-1)


def _col(x):
    return np.asarray(x)[..., None]


def _deg360(v):
    """Direction of v in degrees, in [0, 360)."""
    return np.mod(np.degrees(np.arctan2(v[..., 1], v[..., 0])), 360.0)


def _crank(A, l1, th1, w1):
    e1 = _unit(th1)
    B = A + l1 * e1
    return B, l1 * w1 * _J(e1), -l1 * w1 ** 2 * e1


def _point(O, vO, aO, u, w, al, a, b):
    """P = O + a u + b n on a link of direction u, angular velocity w, acceleration al."""
    n = _J(u)
    r = a * u + b * n
    Jr = a * n - b * u
    return O + r, vO + _col(w) * Jr, aO + _col(al) * Jr - _col(w ** 2) * r


def _four_bar(B, vB, aB, D, l2, l3, side):
    """C with |C - B| = l2, |C - D| = l3, on the ``side`` (+1 left, -1 right) of B -> D."""
    d = D - B
    r = np.hypot(d[..., 0], d[..., 1])
    u = d / _col(r)
    a = (l2 ** 2 - l3 ** 2 + r ** 2) / (2 * r)
    h2 = l2 ** 2 - a ** 2
    if np.any(h2 <= 0):
        raise ValueError("the four-bar does not assemble")
    C = B + _col(a) * u + side * _col(np.sqrt(h2)) * _J(u)
    e2, e3 = (C - B) / l2, (C - D) / l3
    s23 = _dot(_J(e2), e3)                       # sin(theta3 - theta2)
    s32 = _dot(_J(e3), e2)                       # sin(theta2 - theta3)
    c23 = _dot(e2, e3)
    w2 = -_dot(vB, e3) / (l2 * s23)
    w3 = _dot(vB, e2) / (l3 * s32)
    al2 = (-l3 * w3 ** 2 - _dot(aB, e3) + l2 * w2 ** 2 * c23) / (l2 * s23)
    al3 = (_dot(aB, e2) - l2 * w2 ** 2 + l3 * w3 ** 2 * c23) / (l3 * s32)
    return C, e2, e3, w2, w3, al2, al3


def _rod_slider(E, vE, aE, G, g, l4, branch):
    """F = G + s g with |F - E| = l4; branch +1 the larger s."""
    Jg = _J(g)
    p = _dot(E - G, g)
    q = _dot(E - G, Jg)
    rad = l4 ** 2 - q ** 2
    if np.any(rad <= 0):
        raise ValueError("the rod cannot reach the slider's guide")
    s = p + branch * np.sqrt(rad)
    F = G + _col(s) * g
    e4 = (F - E) / l4
    c = _dot(e4, g)
    w4 = -_dot(vE, Jg) / (l4 * c)
    sd = _dot(vE, g) + l4 * w4 * _dot(_J(e4), g)
    al4 = (-_dot(aE, Jg) + l4 * w4 ** 2 * _dot(e4, Jg)) / (l4 * c)
    sdd = _dot(aE, g) + l4 * al4 * _dot(_J(e4), g) - l4 * w4 ** 2 * c
    return F, e4, s, sd, sdd, w4, al4


# ---------------------------------------------------------------------------
# the five exercises: state(th1 [rad]) -> dict of arrays (mm, deg, rad/s, ...)
# ---------------------------------------------------------------------------
class Ex14:
    """习题 1-4: swinging guide bar, guide line offset CK = 40 from its pivot C."""
    name = "exercise1-4"
    l1, l4, e, w1 = 100.0, 300.0, 40.0, 10.0
    lo_deg, hi_deg = 1.0, 360.0
    deriv = {"theta3": "omega3", "omega3": "alpha3", "alpha3": None,
             "s23": "v23", "v23": "a23", "a23": None}
    units = {"theta3": "deg", "omega3": "rad_s", "alpha3": "rad_s2",
             "s23": "mm", "v23": "mm_s", "a23": "mm_s2"}

    def state(self, th1):
        th1 = np.asarray(th1, float)
        A = np.array([0.0, self.l4])
        B, vB, aB = _crank(A, self.l1, th1, self.w1)
        e = self.e
        s = np.sqrt(_dot(B, B) - e * e)
        th3 = np.arctan2(B[..., 1], B[..., 0]) - np.arctan2(e, s)
        u = _unit(th3)
        n = _J(u)
        w3 = _dot(vB, n) / s
        sd = _dot(vB, u) + w3 * e
        al3 = (_dot(aB, n) - 2 * w3 * sd + w3 ** 2 * e) / s
        sdd = _dot(aB, u) + al3 * e + w3 ** 2 * s
        return {"theta3": np.mod(np.degrees(th3), 360.0), "omega3": w3, "alpha3": al3,
                "s23": s, "v23": sd, "a23": sdd,
                "_u3": u, "_B": B, "_vB": vB, "_aB": aB}

    def fd_pairs(self):
        return (("theta3", "omega3"), ("omega3", "alpha3"), ("s23", "v23"), ("v23", "a23"))


class Ex15:
    """习题 1-5: rotating guide bar, the guide 1 driving, D on CB produced (BD = 20)."""
    name = "exercise1-5"
    lAC, l3, lCD, w1 = 50.0, 100.0, 120.0, 20.0
    lo_deg, hi_deg = 90.0, 450.0                 # theta1 = phi1 + 90°, phi1 = 0 … 360°
    turning = ("theta3",)                        # link 3 turns fully (AC < BC)
    deriv = {"theta3": "omega3", "omega3": "alpha3", "alpha3": None,
             "s21": "v21", "v21": "a21", "a21": None,
             "xD": "vxD", "yD": "vyD", "vxD": "axD", "vyD": "ayD", "axD": None, "ayD": None}
    units = {"theta3": "deg", "omega3": "rad_s", "alpha3": "rad_s2",
             "s21": "mm", "v21": "mm_s", "a21": "mm_s2",
             "xD": "mm", "yD": "mm", "vxD": "mm_s", "vyD": "mm_s", "axD": "mm_s2",
             "ayD": "mm_s2"}

    def state(self, th1):
        th1 = np.asarray(th1, float)
        w1 = self.w1
        C = np.array([0.0, 0.0])
        A = np.array([0.0, self.lAC])
        u1 = _unit(th1)
        p = _dot(u1, A - C)
        S = -p + np.sqrt(p ** 2 - self.lAC ** 2 + self.l3 ** 2)
        B = A + _col(S) * u1
        u3 = (B - C) / self.l3
        th3 = np.arctan2(u3[..., 1], u3[..., 0])
        delta = th3 - th1
        cd, sdl = np.cos(delta), np.sin(delta)
        w3 = S * w1 / (self.l3 * cd)
        Sd = -S * w1 * sdl / cd
        al3 = (2 * Sd * w1 + self.l3 * w3 ** 2 * sdl) / (self.l3 * cd)
        Sdd = S * w1 ** 2 - self.l3 * al3 * sdl - self.l3 * w3 ** 2 * cd
        zero = np.zeros(th1.shape + (2,))
        D, vD, aD = _point(C + zero, zero, zero, u3, w3, al3, self.lCD, 0.0)
        return {"theta3": np.mod(np.degrees(th3), 360.0), "omega3": w3, "alpha3": al3,
                "s21": S, "v21": Sd, "a21": Sdd,
                "xD": D[..., 0], "yD": D[..., 1], "vxD": vD[..., 0], "vyD": vD[..., 1],
                "axD": aD[..., 0], "ayD": aD[..., 1], "_u3": u3, "_B": B}

    def fd_pairs(self):
        return (("theta3", "omega3"), ("omega3", "alpha3"), ("s21", "v21"), ("v21", "a21"),
                ("xD", "vxD"), ("yD", "vyD"), ("vxD", "axD"), ("vyD", "ayD"))


class Ex16:
    """习题 1-6: crank and rocking block, D on bar 2 (BD = 50), E with DE = 40 ⊥ BD."""
    name = "exercise1-6"
    l1, lAC, lBD, lDE, w1 = 30.0, 100.0, 50.0, 40.0, 10.0
    e_side = +1.0                                # E to the left of B -> C
    lo_deg, hi_deg = 0.0, 360.0
    deriv = {"theta2": "omega2", "omega2": "alpha2", "alpha2": None,
             "s32": "v32", "v32": "a32", "a32": None}
    units = {"theta2": "deg", "omega2": "rad_s", "alpha2": "rad_s2",
             "s32": "mm", "v32": "mm_s", "a32": "mm_s2"}
    for _p in "DE":
        for _q, _d in (("x", "vx"), ("y", "vy"), ("vx", "ax"), ("vy", "ay"), ("ax", None),
                       ("ay", None)):
            deriv[_q + _p] = None if _d is None else _d + _p
            units[_q + _p] = {"x": "mm", "y": "mm", "vx": "mm_s", "vy": "mm_s",
                              "ax": "mm_s2", "ay": "mm_s2"}[_q]
    del _p, _q, _d

    def state(self, th1):
        th1 = np.asarray(th1, float)
        A = np.array([0.0, 0.0])
        C = np.array([-self.lAC, 0.0])
        B, vB, aB = _crank(A, self.l1, th1, self.w1)
        d = C - B
        L = np.hypot(d[..., 0], d[..., 1])
        u2 = d / _col(L)
        n2 = _J(u2)
        w2 = -_dot(vB, n2) / L
        Ld = -_dot(vB, u2)
        al2 = (-_dot(aB, n2) - 2 * Ld * w2) / L
        Ldd = -_dot(aB, u2) + L * w2 ** 2
        out = {"theta2": _deg360(u2), "omega2": w2, "alpha2": al2,
               "s32": L, "v32": Ld, "a32": Ldd, "_u2": u2, "_B": B}
        for P, b in (("D", 0.0), ("E", self.e_side * self.lDE)):
            X, vX, aX = _point(B, vB, aB, u2, w2, al2, self.lBD, b)
            out.update({"x" + P: X[..., 0], "y" + P: X[..., 1], "vx" + P: vX[..., 0],
                        "vy" + P: vX[..., 1], "ax" + P: aX[..., 0], "ay" + P: aX[..., 1]})
        return out

    def fd_pairs(self):
        pairs = [("theta2", "omega2"), ("omega2", "alpha2"), ("s32", "v32"), ("v32", "a32")]
        for P in "DE":
            pairs += [("x" + P, "vx" + P), ("y" + P, "vy" + P), ("vx" + P, "ax" + P),
                      ("vy" + P, "ay" + P)]
        return tuple(pairs)


class _SixBar:
    """Four-bar ABCD + point E on the rocker + rod EF + slider 5 on a frame line."""
    lo_deg, hi_deg = 0.0, 360.0
    deriv = {"theta2": "omega2", "theta3": "omega3", "theta4": "omega4",
             "omega2": "alpha2", "omega3": "alpha3", "omega4": "alpha4",
             "alpha2": None, "alpha3": None, "alpha4": None,
             "sF": "vF", "vF": "aF", "aF": None}
    units = {"theta2": "deg", "theta3": "deg", "theta4": "deg",
             "omega2": "rad_s", "omega3": "rad_s", "omega4": "rad_s",
             "alpha2": "rad_s2", "alpha3": "rad_s2", "alpha4": "rad_s2",
             "sF": "mm", "vF": "mm_s", "aF": "mm_s2"}

    def state(self, th1):
        th1 = np.asarray(th1, float)
        B, vB, aB = _crank(self.A, self.l1, th1, self.w1)
        C, e2, e3, w2, w3, al2, al3 = _four_bar(B, vB, aB, self.D, self.l2, self.l3,
                                                self.side)
        zero = np.zeros(th1.shape + (2,))
        E, vE, aE = _point(self.D + zero, zero, zero, e3, w3, al3, self.DE_along, 0.0)
        F, e4, s, sd, sdd, w4, al4 = _rod_slider(E, vE, aE, self.G, self.g, self.l4,
                                                 self.branch)
        return {"theta2": _deg360(e2), "theta3": _deg360(e3), "theta4": _deg360(e4),
                "omega2": w2, "omega3": w3, "omega4": w4,
                "alpha2": al2, "alpha3": al3, "alpha4": al4,
                "sF": s, "vF": sd, "aF": sdd, "_C": C, "_E": E, "_F": F}

    def fd_pairs(self):
        return (("theta2", "omega2"), ("theta3", "omega3"), ("theta4", "omega4"),
                ("omega2", "alpha2"), ("omega3", "alpha3"), ("omega4", "alpha4"),
                ("sF", "vF"), ("vF", "aF"))


class Ex17(_SixBar):
    """习题 1-7: six-bar with piston 5 (reading: D = (h2, h), axis h1 right of D)."""
    name = "exercise1-7"
    A = np.array([0.0, 0.0])
    D = np.array([225.0, 80.0])
    l1, l2, l3, l4 = 60.0, 180.0, 120.0, 300.0
    DE_along = -200.0                            # E = D - 200 e3: the lever C-D-E
    side = +1                                    # C left of B -> D
    G = np.array([310.0, 0.0])                   # piston axis x = 225 + 85
    g = np.array([0.0, 1.0])
    branch = +1                                  # F above E
    w1 = 100.0


class Ex18(_SixBar):
    """习题 1-8: swinging feed mechanism (D = (-a, b), DC = DE - CE = 300, guide y = 0)."""
    name = "exercise1-8"
    A = np.array([0.0, 0.0])
    D = np.array([-90.0, 170.0])
    l1, l2, l3, l4 = 80.0, 260.0, 300.0, 300.0
    DE_along = 400.0                             # E on DC produced
    side = +1                                    # C left of B -> D
    G = np.array([0.0, 0.0])                     # slider guide: the horizontal through A
    g = np.array([1.0, 0.0])
    branch = -1                                  # F left of E
    w1 = 400.0 * 2.0 * math.pi / 60.0


EXERCISES = (Ex14(), Ex15(), Ex16(), Ex17(), Ex18())


# ---------------------------------------------------------------------------
# extremes
# ---------------------------------------------------------------------------
def _derivatives(model, keys, th):
    """{key: an array proportional (with a fixed sign) to d key / d theta1 at th [rad]}."""
    st = model.state(th)
    out = {k: st[model.deriv[k]] for k in keys if model.deriv[k] is not None}
    fd = [k for k in keys if model.deriv[k] is None]
    if fd:
        sf = model.state(th[..., None] + OFFS * FD_H)
        out.update({k: sf[k] @ C8 / FD_H for k in fd})
    return out


def extremes(model, keys):
    """{key: (max, theta1_at_max_deg, min, theta1_at_min_deg)} over [lo_deg, hi_deg]; an
    angle is None where the extreme is reached at two positions (a tie).  The brackets of
    every key are bisected together."""
    lo, hi = model.lo_deg * DEG, model.hi_deg * DEG
    n = int(round((model.hi_deg - model.lo_deg) / SCAN_STEP_DEG))
    grid = np.linspace(lo, hi, n + 1)
    g = _derivatives(model, keys, grid)
    seg, a, b, ga, start = {}, [], [], [], 0
    for k in keys:
        idx = np.nonzero(np.sign(g[k][:-1]) * np.sign(g[k][1:]) < 0)[0]
        seg[k] = slice(start, start + len(idx))
        start += len(idx)
        a.append(grid[idx])
        b.append(grid[idx + 1])
        ga.append(g[k][idx])
    a, b, ga = np.concatenate(a), np.concatenate(b), np.concatenate(ga)
    for _ in range(64):                          # bisection on the sign of the derivative
        m = 0.5 * (a + b)
        gmk = _derivatives(model, keys, m)
        gm = np.empty_like(m)
        for k in keys:
            gm[seg[k]] = gmk[k][seg[k]]
        left = np.sign(gm) == np.sign(ga)
        a = np.where(left, m, a)
        ga = np.where(left, gm, ga)
        b = np.where(left, b, m)
    found = 0.5 * (a + b)
    fgrid = model.state(grid)
    out = {}
    for k in keys:
        roots = np.concatenate([found[seg[k]], [lo, hi]])
        vals = model.state(roots)[k]
        f = fgrid[k]
        if k.startswith("theta"):
            # a link's angle is reported on its continuous branch through its value at the
            # range's start (an oscillating link: within 180° of it)
            c = np.mod(f[0] + 180.0, 360.0) - 180.0
            vals = c + np.mod(vals - c + 180.0, 360.0) - 180.0
            f = c + np.mod(f - c + 180.0, 360.0) - 180.0
        i_max, i_min = int(np.argmax(vals)), int(np.argmin(vals))
        assert vals[i_max] >= f.max() - 1e-9 * max(1.0, abs(f.max()))
        assert vals[i_min] <= f.min() + 1e-9 * max(1.0, abs(f.min()))

        def where(i, vals=vals, roots=roots):
            # None where another position (the two ends of a cycle included) gives the
            # same value: a tie, whose reported angle depends on the search order
            tie = np.abs(vals - vals[i]) <= 1e-10 * max(1.0, abs(vals[i]))
            tie &= np.abs(roots - roots[i]) > 1e-6 * DEG
            return None if np.any(tie) else float(roots[i] / DEG)

        out[k] = float(vals[i_max]), where(i_max), float(vals[i_min]), where(i_min)
    return out


def reference_for(model):
    """The reference results of one exercise, named as mechcli's ``--json`` results."""
    res = {"positions": int(round(model.hi_deg - model.lo_deg)) + 1}     # 1° steps, both ends
    turning = getattr(model, "turning", ())
    ext = extremes(model, [k for k in model.units if k not in turning])
    for key, unit in model.units.items():
        if key in turning:
            res[f"{key}_swing_deg"] = 360.0      # a fully turning link: no extremes
            continue
        vmax, tmax, vmin, tmin = ext[key]
        res[f"{key}_max_{unit}"] = vmax
        res[f"{key}_min_{unit}"] = vmin
        if tmax is not None:
            res[f"{key}_max_at_deg"] = tmax
        if tmin is not None:
            res[f"{key}_min_at_deg"] = tmin
        if key.startswith("theta"):
            res[f"{key}_swing_deg"] = vmax - vmin
        if model.deriv.get(key) and key.startswith("s") and unit == "mm":
            res[f"{key}_stroke_mm"] = vmax - vmin
    return res


def reference():
    """{config stem: results} for every exercise."""
    return {m.name: reference_for(m) for m in EXERCISES}


# ---------------------------------------------------------------------------
# closed forms (the hand derivations written in the configs' comments)
# ---------------------------------------------------------------------------
def _acosd(x):
    return math.degrees(math.acos(x))


def closed_forms():
    """{config stem: {result: value}} from the limit-position formulas alone."""
    out = {}
    m = Ex14()
    # omega3 = 0 <=> AB normal to the guide: B = A -+ l1 n with n.B = e, n.A = l4 cos theta3
    t_max = _acosd((m.e - m.l1) / m.l4)          # B = A + l1 n, theta1 = theta3 + 90°
    t_min = _acosd((m.e + m.l1) / m.l4)          # B = A - l1 n, theta1 = theta3 - 90°
    out[m.name] = {"theta3_max_deg": t_max, "theta3_max_at_deg": t_max + 90.0,
                   "theta3_min_deg": t_min, "theta3_min_at_deg": t_min - 90.0 + 360.0,
                   "theta3_swing_deg": t_max - t_min,
                   "s23_max_mm": math.sqrt((m.l4 + m.l1) ** 2 - m.e ** 2),
                   "s23_max_at_deg": 90.0,
                   "s23_min_mm": math.sqrt((m.l4 - m.l1) ** 2 - m.e ** 2),
                   "s23_min_at_deg": 270.0}
    m = Ex15()
    # phi1 = 0 (theta1 = 90°, 450°): S = l3 - AC, delta = 0; phi1 = 180°: S = l3 + AC;
    # phi1 = 90° (theta1 = 180°): S = sqrt(l3² - AC²), theta3 = 150°, delta = -30°
    w1, l3, ac = m.w1, m.l3, m.lAC
    S90 = math.sqrt(l3 ** 2 - ac ** 2)
    d90 = math.atan2(ac, -S90) - math.pi       # theta3 - theta1
    w3_90 = S90 * w1 / (l3 * math.cos(d90))
    Sd90 = -S90 * w1 * math.tan(d90)
    al3_90 = (2 * Sd90 * w1 + l3 * w3_90 ** 2 * math.sin(d90)) / (l3 * math.cos(d90))
    th3_90 = math.atan2(ac, -S90)
    w3_180 = (l3 + ac) * w1 / l3
    out[m.name] = {"omega3_max_rad_s": w3_180, "omega3_max_at_deg": 270.0,
                   "omega3_min_rad_s": (l3 - ac) * w1 / l3,
                   "alpha3_max_rad_s2": al3_90, "alpha3_max_at_deg": 180.0,
                   "alpha3_min_rad_s2": -al3_90, "alpha3_min_at_deg": 360.0,
                   "s21_max_mm": l3 + ac, "s21_max_at_deg": 270.0, "s21_min_mm": l3 - ac,
                   "a21_min_mm_s2": (l3 + ac) * w1 ** 2 - l3 * w3_180 ** 2,
                   "a21_min_at_deg": 270.0,
                   "vxD_max_mm_s": m.lCD * w3_180, "vxD_max_at_deg": 270.0,
                   "ayD_max_mm_s2": m.lCD * w3_180 ** 2, "ayD_max_at_deg": 270.0,
                   "ayD_min_mm_s2": m.lCD * (al3_90 * math.cos(th3_90)
                                             - w3_90 ** 2 * math.sin(th3_90)),
                   "ayD_min_at_deg": 180.0,
                   "theta3_swing_deg": 360.0}
    m = Ex16()
    # B on the line AC: theta1 = 0 (BC = AC + l1) and 180° (BC = AC - l1); the bar's
    # limits where it is tangent to the crank circle: half-swing asin(l1/AC), the
    # sliding speed there l1 omega1
    out[m.name] = {"omega2_max_rad_s": m.l1 * m.w1 / (m.lAC + m.l1),
                   "omega2_max_at_deg": 0.0,
                   "omega2_min_rad_s": -m.l1 * m.w1 / (m.lAC - m.l1),
                   "omega2_min_at_deg": 180.0,
                   "theta2_swing_deg": 2.0 * math.degrees(math.asin(m.l1 / m.lAC)),
                   "s32_max_mm": m.lAC + m.l1, "s32_min_mm": m.lAC - m.l1,
                   "v32_max_mm_s": m.l1 * m.w1}
    for m in (Ex17(), Ex18()):
        AD = math.hypot(*(m.D - m.A))
        dA = math.degrees(math.atan2(*(m.A - m.D)[::-1]))     # direction D -> A
        res = {}
        # the rocker's limits: B on the line AC, AC = l2 + l1 (extended) or l2 - l1
        # (folded); angle at D of triangle ADC by the cosine law, C on the model's side
        lim = {}
        for which, AC in (("ext", m.l2 + m.l1), ("fold", m.l2 - m.l1)):
            psi = _acosd((AD ** 2 + m.l3 ** 2 - AC ** 2) / (2 * AD * m.l3))
            th3 = dA - m.side * psi
            C = m.D + m.l3 * np.array([math.cos(math.radians(th3)),
                                        math.sin(math.radians(th3))])
            th1 = math.degrees(math.atan2(*(C - m.A)[::-1]))
            if which == "fold":
                th1 += 180.0
            E = m.D + m.DE_along * (C - m.D) / m.l3
            p, q = float(np.dot(E - m.G, m.g)), float(np.dot(E - m.G, _J(m.g)))
            sF = p + m.branch * math.sqrt(m.l4 ** 2 - q ** 2)
            lim[which] = (th3, th1 % 360.0, sF)
        # reported on the branch through the rocker's angle at the start (theta1 = 0)
        c = float(np.mod(m.state(np.array([0.0]))["theta3"][0] + 180.0, 360.0) - 180.0)
        lim = {k: (c + (v[0] - c + 180.0) % 360.0 - 180.0,) + v[1:] for k, v in lim.items()}
        hi, lo = sorted(lim.values(), key=lambda t: -t[0])
        res.update({"theta3_max_deg": hi[0], "theta3_max_at_deg": hi[1],
                    "theta3_min_deg": lo[0], "theta3_min_at_deg": lo[1],
                    "theta3_swing_deg": hi[0] - lo[0]})
        sf = sorted(lim.values(), key=lambda t: -t[2])
        res.update({"sF_max_mm": sf[0][2], "sF_max_at_deg": sf[0][1],
                    "sF_min_mm": sf[1][2], "sF_min_at_deg": sf[1][1],
                    "sF_stroke_mm": sf[0][2] - sf[1][2]})
        # least transmission angle at C: at one of the extremes of BD, AD + l1 (B on DA
        # produced beyond A) or AD - l1 (B on AD); the angle BCD by the cosine law
        cands = []
        for BD, at in ((AD + m.l1, dA), (AD - m.l1, dA + 180.0)):
            mu = _acosd((m.l2 ** 2 + m.l3 ** 2 - BD ** 2) / (2 * m.l2 * m.l3))
            cands.append((min(mu, 180.0 - mu), at % 360.0))
        res["gammaC_min_deg"], res["gammaC_min_at_deg"] = min(cands)
        out[m.name] = res
    return out


def gamma_min_grid(model, step_deg=0.01):
    """The least transmission angle at C [deg] on a grid (a check of the closed form)."""
    st = model.state(np.radians(np.arange(0.0, 360.0, step_deg)))
    e2 = np.stack([np.cos(np.radians(st["theta2"])), np.sin(np.radians(st["theta2"]))], -1)
    e3 = np.stack([np.cos(np.radians(st["theta3"])), np.sin(np.radians(st["theta3"]))], -1)
    return float(np.degrees(np.min(np.arccos(np.abs(_dot(e2, e3))))))


# ---------------------------------------------------------------------------
# self-checks
# ---------------------------------------------------------------------------
def fd_check(h=2e-3):
    """{exercise: largest relative |analytic - 8th-order central difference|} over a 1° grid:
    every velocity against the difference of its position, every acceleration against the
    difference of its velocity (angles differenced unwrapped)."""
    out = {}
    for m in EXERCISES:
        th = np.arange(int(m.lo_deg), int(m.hi_deg)) * DEG + 0.5 * DEG
        st = m.state(th[:, None] + OFFS[None, :] * h)
        ref = m.state(th)
        worst = 0.0
        for q, dq in m.fd_pairs():
            x = st[q]
            if q.startswith("theta"):
                x = np.unwrap(np.radians(x), axis=1)
            fd = (x @ C8) / h * m.w1
            scale = np.max(np.abs(ref[dq]))
            worst = max(worst, float(np.max(np.abs(fd - ref[dq])) / scale))
        out[m.name] = worst
    return out


def loop_check():
    """{exercise: largest loop-closure residual [mm]} over a 1° grid (every joint distance
    of the model against its link length)."""
    out = {}
    for m in EXERCISES:
        th = np.arange(0, 360) * DEG
        st = m.state(th)
        if isinstance(m, Ex14):
            A = np.array([0.0, m.l4])
            # B on the guide line: its distance from the line through C is e
            r = [np.abs(_dot(st["_B"], _J(st["_u3"])) - m.e),
                 np.abs(np.hypot(*(st["_B"] - A).T) - m.l1)]
        elif isinstance(m, Ex15):
            A = np.array([0.0, m.lAC])
            r = [np.abs(np.hypot(*st["_B"].T) - m.l3),
                 np.abs(_cross(st["_B"] - A, _unit(th)))]
        elif isinstance(m, Ex16):
            C = np.array([-m.lAC, 0.0])
            r = [np.abs(_cross(C - st["_B"], st["_u2"])),
                 np.abs(np.hypot(*st["_B"].T) - m.l1)]
        else:
            B = m.A + m.l1 * _unit(th)
            r = [np.abs(np.hypot(*(st["_C"] - B).T) - m.l2),
                 np.abs(np.hypot(*(st["_C"] - m.D).T) - m.l3),
                 np.abs(np.hypot(*(st["_E"] - m.D).T) - abs(m.DE_along)),
                 np.abs(np.hypot(*(st["_F"] - st["_E"]).T) - m.l4),
                 np.abs(_dot(st["_F"] - m.G, _J(m.g)))]
        out[m.name] = float(max(np.max(x) for x in r))
    return out


def main():
    for name, res in reference().items():
        print(f"[{name}]")
        for k, v in res.items():
            print(f"  {k:26s} {v:.10f}" if isinstance(v, float) else f"  {k:26s} {v}")
    print("analytic vs finite difference, max relative |diff|:",
          {k: f"{v:.1e}" for k, v in fd_check().items()})
    print("loop closure, max |residual| [mm]:", {k: f"{v:.1e}" for k, v in loop_check().items()})
    for name, res in closed_forms().items():
        print(f"[{name}] closed forms")
        for k, v in res.items():
            print(f"  {k:26s} {v:.10f}")


if __name__ == "__main__":
    main()
