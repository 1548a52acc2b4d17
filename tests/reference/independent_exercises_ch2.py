#!/usr/bin/env python3
"""Independent reference numbers for the chapter-2 exercises (习题 2-1, 2-5) of
李滨城, 徐超《机械原理 MATLAB 辅助分析》, written for configs/ch2/exercise2-1.toml and
configs/ch2/exercise2-5.toml.

Self-contained: imports nothing from mechcli.  It reuses the dense kinetostatic solver of
the project's other independent reference, tests/reference/independent_force.py (which
imports nothing from mechcli either), but not its finite-difference kinematics: the
velocities and accelerations here are differentiated by hand, and `fd_check` compares them
with an 8th-order central difference of the positions.

Conventions (those of independent_force.py and of the book, 第二章第一节): x right, y up,
angles counter-clockwise from +x, SI units; F_Rij (i < j) is the force of link i on link j
(the frame numbered like any link, so F_R14 is the force of crank 1 on the frame 4); a
prismatic pair carries a force normal to its guide, placed at the named pin, and a couple
M_Rij of i on j about that pin; Mb is the torque of the frame on crank 1, counter-clockwise
positive.  Each moving link is in d'Alembert equilibrium (3 equations: Fx, Fy, Mz about the
origin) under its pair reactions, its weight m g (-y), its inertia force -m a_S and couple
-J_S alpha, and the external loads; one dense square system per position (numpy.linalg.solve).
Derivatives are taken with respect to the crank angle th (a prime below); with a constant
crank speed w1:  v = w1 X',  a = w1^2 X''.

习题 2-1 (crank and rocking block, 曲柄摇块机构)
-----------------------------------------------
A = (0, 0), C = (l_AC, 0) = (0.2, 0) m, crank AB = r = 0.1 m, w1 = 40 rad/s (CCW).
Rod 2 is pinned to the crank at B and slides through block 3, which turns about C.
    B  = r (cos th, sin th),   B' = r (-sin th, cos th),   B'' = -B
    w  = C - B (from B to C),  s = |w|,  phi2 = atan2(w_y, w_x)   (block 3 turns with it)
    w' = -B',  w'' = -B'' = B
    phi2'  = (w x w') / s^2,   s' = (w . w') / s
    phi2'' = (w x w'') / s^2 - 2 phi2' s' / s
    S2 = B + l_BS2 u,  u = (cos phi2, sin phi2),  n = (-sin phi2, cos phi2)
    S2' = B' + l_BS2 phi2' n,  S2'' = B'' + l_BS2 (phi2'' n - phi2'^2 u)
m2 = 20 kg, J_S2 = 0.074 kg m^2, l_BS2 = 0.086 m; crank and block massless; g = 9.8 m/s^2.
Pairs: 1-4 (R, A), 1-2 (R, B), 2-3 (P, at C, guide along u), 3-4 (R, C): 9 unknowns with Mb.

习题 2-5 (swinging feed mechanism, 摇摆送进机构)
-----------------------------------------------
A = (0, 0), D = (-a, b) = (-0.09, 0.17) m; crank AB = 0.08, coupler BC = 0.26, rocker
D-C-E with DC = DE - CE = 0.30 and DE = 0.40, rod EF = 0.46, slider 5 on the horizontal
guide through A (y = 0); C to the left of the directed line B->D (the rocker hangs down
and to the left from D), F to the left of E.  n1 = 400 r/min (w1 = 400 * 2 pi / 60, CCW).
    B + l2 e2 = D + l3 e3                    (e_k = (cos phi_k, sin phi_k), n_k = e_k rotated +90°)
    l2 phi2' n2 - l3 phi3' n3 = -B'                                              (2x2, solved)
    l2 phi2'' n2 - l3 phi3'' n3 = -B'' + l2 phi2'^2 e2 - l3 phi3'^2 e3           (2x2, solved)
    E = D + DE e3,  E' = DE phi3' n3,  E'' = DE (phi3'' n3 - phi3'^2 e3)
    F = E + EF e4 with F_y = 0:  sin phi4 = -E_y / EF,  cos phi4 < 0
    phi4'  = -E_y' / (EF cos phi4),   F_x' = E_x' - EF sin phi4 phi4'
    phi4'' = (-E_y'' + EF sin phi4 phi4'^2) / (EF cos phi4)
    F_x''  = E_x'' - EF (sin phi4 phi4'' + cos phi4 phi4'^2)
Centres of mass: S1 = A, S2 = (B + C)/2, S3 = C, S4 = (E + F)/2, S5 = F; masses m = G/g with
G1..G4 = 36, 60, 72, 85 N and g = 9.8 m/s^2 (so the weights are exactly the book's G);
J1..J4 = 0.3, 0.08, 0.1, 0.12 kg m^2; slider 5 massless (the book gives no G5).  The
production resistance P_r = 4000 N acts on the slider at F, horizontal, opposing the
slider's velocity.  Pairs: 1-6 (A), 1-2 (B), 2-3 (C), 3-6 (D), 3-4 (E), 4-5 (F), all R, and
5-6 (P, at F, guide along +x): 15 unknowns with Mb.

Results (named as `mechcli force --json` names them, so the test can compare them with the
configs' [expected] tables): extremes over a turn from a 0.5° grid refined by a bounded
Brent search (xatol 1e-9°); mean and RMS of Mb by the trapezoid rule on 3600 points (exact
to round-off for a smooth periodic function); values at given crank angles; and the
virtual-power and force-balance residuals of the solution (`balance_residuals`), each
relative to its largest term.

Run:  python3 tests/reference/independent_exercises_ch2.py   (prints both result sets)
"""
import importlib.util
import json
import math
import os

import numpy as np
from scipy.optimize import minimize_scalar

_HERE = os.path.dirname(os.path.abspath(__file__))


def _load_independent_force():
    path = os.path.join(_HERE, "independent_force.py")
    spec = importlib.util.spec_from_file_location("independent_force_for_ch2", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


IF = _load_independent_force()
kinetostatics = IF.kinetostatics

DEG = math.pi / 180.0
TWO_PI = 2.0 * math.pi


def _e(phi):
    return np.stack([np.cos(phi), np.sin(phi)], axis=-1)


def _n(phi):
    return np.stack([-np.sin(phi), np.cos(phi)], axis=-1)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _const(p, th):
    return np.broadcast_to(np.asarray(p, float), th.shape + (2,)).copy()


def _wrap(a):
    return (a + math.pi) % TWO_PI - math.pi


# ----------------------------------------------------------------------------- problems
class CrankRockingBlock(IF.Problem):
    """习题 2-1: the crank and rocking block (see the module docstring)."""

    name = "exercise2-1"
    omega1, g, frame = 40.0, 9.8, 4
    r, d, l_bs2 = 0.100, 0.200, 0.086
    links = {1: (0.0, 0.0, "A"), 2: (20.0, 0.074, "S2"), 3: (0.0, 0.0, "C")}
    pairs = [dict(i=1, j=4, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="P", at="C", guide=lambda p, a: _e(a[2])),
             dict(i=3, j=4, kind="R", at="C")]

    def positions(self, th):
        """Positions only (for the finite-difference check)."""
        th = np.asarray(th, float)
        B = self.r * _e(th)
        C = _const([self.d, 0.0], th)
        phi2 = np.arctan2(C[..., 1] - B[..., 1], C[..., 0] - B[..., 0])
        S2 = B + self.l_bs2 * _e(phi2)
        return dict(A=_const([0.0, 0.0], th), B=B, C=C, S2=S2), {1: th.copy(), 2: phi2, 3: phi2.copy()}

    def derivatives(self, th):
        """Positions, first and second derivatives with respect to th, by hand."""
        th = np.asarray(th, float)
        pts, angs = self.positions(th)
        B = pts["B"]
        B1, B2 = self.r * _n(th), -B
        w = pts["C"] - B
        w1, w2 = -B1, -B2
        s = np.hypot(w[..., 0], w[..., 1])
        p1 = _cross(w, w1) / s ** 2
        s1 = _dot(w, w1) / s
        p2 = _cross(w, w2) / s ** 2 - 2.0 * p1 * s1 / s
        phi2 = angs[2]
        u, n = _e(phi2), _n(phi2)
        zero = np.zeros_like(B)
        d1 = dict(A=zero, B=B1, C=zero, S2=B1 + self.l_bs2 * p1[..., None] * n)
        d2 = dict(A=zero, B=B2, C=zero,
                  S2=B2 + self.l_bs2 * (p2[..., None] * n - (p1 ** 2)[..., None] * u))
        one, nil = np.ones_like(th), np.zeros_like(th)
        a1 = {1: one, 2: p1, 3: p1.copy()}
        a2 = {1: nil, 2: p2, 3: p2.copy()}
        return pts, angs, d1, d2, a1, a2

    def loads(self, kin, active):
        return []


class SwingingFeed(IF.Problem):
    """习题 2-5: the swinging feed mechanism (see the module docstring)."""

    name = "exercise2-5"
    omega1 = 400.0 * TWO_PI / 60.0
    g, frame = 9.8, 6
    D = np.array([-0.090, 0.170])
    l1, l2, l3, lDE, l4 = 0.080, 0.260, 0.300, 0.400, 0.460
    Pr = 4000.0
    links = {1: (36.0 / 9.8, 0.3, "A"), 2: (60.0 / 9.8, 0.08, "S2"), 3: (72.0 / 9.8, 0.1, "C"),
             4: (85.0 / 9.8, 0.12, "S4"), 5: (0.0, 0.0, "F")}
    pairs = [dict(i=1, j=6, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="R", at="C"), dict(i=3, j=6, kind="R", at="D"),
             dict(i=3, j=4, kind="R", at="E"), dict(i=4, j=5, kind="R", at="F"),
             dict(i=5, j=6, kind="P", at="F", guide=lambda p, a: _const([1.0, 0.0], a[1]))]

    def positions(self, th):
        th = np.asarray(th, float)
        A, D = _const([0.0, 0.0], th), _const(self.D, th)
        B = self.l1 * _e(th)
        # C: left of the directed line B -> D (circle intersection)
        C = IF.circ_int(B, self.l2, D, self.l3, +1)
        phi2 = np.arctan2(C[..., 1] - B[..., 1], C[..., 0] - B[..., 0])
        phi3 = np.arctan2(C[..., 1] - D[..., 1], C[..., 0] - D[..., 0])
        E = D + self.lDE * _e(phi3)
        sin4 = (0.0 - E[..., 1]) / self.l4            # the guide is the line y = 0
        if np.any(np.abs(sin4) >= 1.0):
            raise IF.AssemblyError("rod EF cannot reach the slider's guide")
        phi4 = math.pi - np.arcsin(sin4)              # cos phi4 < 0: F to the left of E
        F = E + self.l4 * _e(phi4)
        pts = dict(A=A, B=B, C=C, D=D, E=E, F=F, S2=0.5 * (B + C), S4=0.5 * (E + F))
        angs = {1: th.copy(), 2: phi2, 3: phi3, 4: phi4, 5: np.zeros_like(th)}
        return pts, angs

    def derivatives(self, th):
        th = np.asarray(th, float)
        pts, angs = self.positions(th)
        B = pts["B"]
        B1, B2 = self.l1 * _n(th), -B
        e2, n2, e3, n3 = _e(angs[2]), _n(angs[2]), _e(angs[3]), _n(angs[3])
        # [l2 n2, -l3 n3] [phi2', phi3']^T = rhs
        M = np.stack([self.l2 * n2, -self.l3 * n3], axis=-1)          # (N, 2, 2)
        q1 = np.linalg.solve(M, (-B1)[..., None])[..., 0]
        p21, p31 = q1[..., 0], q1[..., 1]
        rhs2 = -B2 + self.l2 * (p21 ** 2)[..., None] * e2 - self.l3 * (p31 ** 2)[..., None] * e3
        q2 = np.linalg.solve(M, rhs2[..., None])[..., 0]
        p22, p32 = q2[..., 0], q2[..., 1]
        C1 = self.l3 * p31[..., None] * n3
        C2 = self.l3 * (p32[..., None] * n3 - (p31 ** 2)[..., None] * e3)
        E1 = self.lDE * p31[..., None] * n3
        E2 = self.lDE * (p32[..., None] * n3 - (p31 ** 2)[..., None] * e3)
        phi4 = angs[4]
        c4, s4 = np.cos(phi4), np.sin(phi4)
        p41 = -E1[..., 1] / (self.l4 * c4)
        p42 = (-E2[..., 1] + self.l4 * s4 * p41 ** 2) / (self.l4 * c4)
        F1 = np.stack([E1[..., 0] - self.l4 * s4 * p41, np.zeros_like(th)], axis=-1)
        F2 = np.stack([E2[..., 0] - self.l4 * (s4 * p42 + c4 * p41 ** 2), np.zeros_like(th)], axis=-1)
        zero = np.zeros_like(B)
        d1 = dict(A=zero, B=B1, C=C1, D=zero, E=E1, F=F1, S2=0.5 * (B1 + C1), S4=0.5 * (E1 + F1))
        d2 = dict(A=zero, B=B2, C=C2, D=zero, E=E2, F=F2, S2=0.5 * (B2 + C2), S4=0.5 * (E2 + F2))
        nil = np.zeros_like(th)
        a1 = {1: np.ones_like(th), 2: p21, 3: p31, 4: p41, 5: nil}
        a2 = {1: nil, 2: p22, 3: p32, 4: p42, 5: nil.copy()}
        return pts, angs, d1, d2, a1, a2

    def condition(self, kin):
        # the resistance opposes the slider's motion: +x force while F moves to -x
        return kin["vel"]["F"][..., 0] < 0.0

    def loads(self, kin, active):
        n = kin["th"].shape
        Fx = np.where(active, self.Pr, -self.Pr)
        F = np.stack([Fx, np.zeros(n)], axis=-1)
        return [(5, F, "F", np.zeros(n))]


# ----------------------------------------------------------------------------- kinematics
def kinematics(prob, th):
    """The kin dict of independent_force.kinetostatics, from the hand derivatives."""
    th = np.atleast_1d(np.asarray(th, float))
    pts, angs, d1, d2, a1, a2 = prob.derivatives(th)
    w = prob.omega1
    return dict(th=th, pos=pts, phi=angs,
                vel={k: w * v for k, v in d1.items()}, acc={k: w * w * v for k, v in d2.items()},
                om={k: w * v for k, v in a1.items()}, al={k: w * w * v for k, v in a2.items()})


def fd_check(prob, h=1e-3):
    """Largest difference, relative to each quantity's scale, between the hand derivatives
    and an 8th-order central difference of the positions (stencil +-4h) at 0, 10, ..., 350°."""
    th = np.arange(0.0, 360.0, 10.0) * DEG
    pts, angs, d1, d2, a1, a2 = prob.derivatives(th)
    samples = [prob.positions(th + k * h) for k in IF.OFFS]
    worst = {}
    # a fixed point's derivatives are 0: measure it against the linkage's largest rate
    floor1 = max(float(np.abs(v).max()) for v in d1.values())
    floor2 = max(float(np.abs(v).max()) for v in d2.values())
    for name in pts:
        st = np.stack([s[0][name] for s in samples])
        fd1 = np.tensordot(IF.C1, st, axes=1) / h
        fd2 = np.tensordot(IF.C2, st, axes=1) / h ** 2
        sc1 = max(floor1, float(np.abs(d1[name]).max()))
        sc2 = max(floor2, float(np.abs(d2[name]).max()))
        worst["d" + name] = float(np.abs(fd1 - d1[name]).max() / sc1)
        worst["dd" + name] = float(np.abs(fd2 - d2[name]).max() / sc2)
    for k in angs:
        st = np.stack([_wrap(s[1][k] - angs[k]) for s in samples])
        fd1 = np.tensordot(IF.C1, st, axes=1) / h
        fd2 = np.tensordot(IF.C2, st, axes=1) / h ** 2
        sc1 = max(1.0, float(np.abs(a1[k]).max()))       # per radian of crank angle
        sc2 = max(1.0, float(np.abs(a2[k]).max()))
        worst["dphi%d" % k] = float(np.abs(fd1 - a1[k]).max() / sc1)
        worst["ddphi%d" % k] = float(np.abs(fd2 - a2[k]).max() / sc2)
    return worst


def solve(prob, th_deg, active=None):
    """Reactions, Mb and the power-balance terms at crank angles th_deg (degrees)."""
    th = np.atleast_1d(np.asarray(th_deg, float)) * DEG
    kin = kinematics(prob, th)
    if active is None:
        active = prob.condition(kin)
    out = kinetostatics(prob, kin, active)
    return out, kin


# ----------------------------------------------------------------------------- extremes
def _extreme(prob, key, sense, step_deg=0.5):
    """(value, angle in degrees) of the largest sense*key over one turn: a grid, then a
    bounded Brent search within one grid step of the best sample.  For a problem without
    switching loads only (习题 2-1)."""
    grid = np.arange(0.0, 360.0, step_deg)
    q = sense * solve(prob, grid)[0][key]
    i = int(np.argmax(q))
    f = lambda t: -sense * solve(prob, [t])[0][key][0]
    r = minimize_scalar(f, bounds=(grid[i] - step_deg, grid[i] + step_deg), method="bounded",
                        options=dict(xatol=1e-9))
    return sense * float(-r.fun), float(r.x % 360.0)


def exercise_2_1():
    """习题 2-1: the results named as `mechcli force --json` names them."""
    prob = CrankRockingBlock()
    res = {}
    for sense, word in ((1, "max"), (-1, "min")):
        v, at = _extreme(prob, "Mb", sense)
        res["Mb_%s_N_m" % word] = v
        res["Mb_%s_at_deg" % word] = at
    for pair in ("FR14", "FR12", "FR23", "FR34"):
        v, at = _extreme(prob, pair, 1)
        res[pair + "_max_N"] = v
        res[pair + "_max_at_deg"] = at
    # mean and RMS over the turn: the trapezoid rule on a periodic smooth function
    # converges geometrically; 3600 points are exact to round-off here
    grid = np.arange(3600) * 0.1
    mb = solve(prob, grid)[0]["Mb"]
    res["Mb_mean_N_m"] = float(mb.mean())
    res["Mb_rms_N_m"] = float(np.sqrt((mb ** 2).mean()))
    res["power_balance_residual"], res["force_balance_residual"] = balance_residuals(prob, grid)
    at = [0.0, 90.0, 180.0]
    out = solve(prob, at)[0]
    for k, a in enumerate(at):
        tag = "_at_%ddeg" % a
        res["Mb" + tag + "_N_m"] = float(out["Mb"][k])
        for pair in ("FR14", "FR12", "FR23", "FR34"):
            for c in ("x", "y", ""):
                res[pair + c + tag + "_N"] = float(out[pair + c][k])
        res["MR23" + tag + "_N_m"] = float(out["MR23"][k])
    return res


def exercise_2_5():
    """习题 2-5 at φ1 = 90°: the results named as `mechcli force --json` names them."""
    prob = SwingingFeed()
    out, kin = solve(prob, [90.0])
    tag = "_at_90deg"
    res = {"Mb" + tag + "_N_m": float(out["Mb"][0]), "MR56" + tag + "_N_m": float(out["MR56"][0])}
    for p in prob.pairs:
        nm = "FR%d%d" % (p["i"], p["j"])
        for c in ("x", "y", ""):
            res[nm + c + tag + "_N"] = float(out[nm + c][0])
    res["vF" + tag + "_m_s"] = float(kin["vel"]["F"][0, 0])
    res["power_balance_residual"], res["force_balance_residual"] = balance_residuals(prob, [90.0])
    return res


def fire_ladder(phi_deg):
    """习题 2-2 (configs/ch2/exercise2-2.toml's reading): the balancing force Fb on the
    cylinder's piston by virtual work, and the pair reactions by hand statics.

    A = (0, 0.8), C = (0.8, 0); the ladder's axis u = (cos φ, sin φ), its left normal n;
    the rod's pin B = A + 0.4 u − 0.2 n; Q = 3000 N down at S2 = A + 1.5 u; massless
    links.  Fb ds/dφ = Q dy_S2/dφ with s = |CB|; the cylinder (3 and 4, massless, pinned
    at both ends) is a two-force member, so every force in it is along C -> B."""
    phi = math.radians(phi_deg)
    A, C = np.array([0.0, 0.8]), np.array([0.8, 0.0])
    u, n = _e(phi), _n(phi)
    B = A + 0.4 * u - 0.2 * n
    d = B - C
    s = math.hypot(*d)
    ds = _dot(d, 0.4 * n + 0.2 * u) / s
    fb = 3000.0 * 1.5 * math.cos(phi) / ds
    f = fb * d / s                      # the rod's push on the ladder, along C -> B
    out = {"Fb": fb}
    for name, v in (("FR12", -f - np.array([0.0, -3000.0])),   # frame on ladder at A
                    ("FR24", -f), ("FR34", f), ("FR13", f)):
        out[name + "x"], out[name + "y"], out[name] = float(v[0]), float(v[1]), math.hypot(*v)
    return out


def exercise_2_2():
    """习题 2-2 at φ = 0°, 20°, …, 80°: the results named as `mechcli force --json`."""
    res = {}
    for a in (0, 20, 40, 60, 80):
        for k, v in fire_ladder(a).items():
            res[f"{k}_at_{a}deg_N"] = v
    return res


def balance_residuals(prob, th_deg):
    """(power, force) residuals over th_deg, each relative to its largest term:
    power: max |Mb w1 + Σ (F.v + M w)| / max Σ |terms| (the virtual-power balance);
    force: max |Σ F_R(link -> frame) - Σ (loads + m g - m a_S)| / max |term| (the frame
    takes what the moving links do not balance)."""
    out, kin = solve(prob, th_deg)
    power = float(out["power_residual_abs"].max() / out["power_scale"].max())
    n = kin["th"].shape[0]
    to_frame = np.zeros((n, 2))
    for p in prob.pairs:
        if p["j"] == prob.frame:
            nm = "FR%d%d" % (p["i"], p["j"])
            to_frame += np.stack([out[nm + "x"], out[nm + "y"]], axis=-1)
    known = np.zeros((n, 2))
    scale = float(np.abs(to_frame).max())
    for k, (m, _J, s) in prob.links.items():
        f = -m * kin["acc"][s] + np.array([0.0, -m * prob.g])
        known += f
        scale = max(scale, float(np.abs(f).max()))
    active = prob.condition(kin)
    for _k, F, _at, _M in prob.loads(kin, active):
        known += F
        scale = max(scale, float(np.abs(F).max()))
    force = float(np.abs(to_frame - known).max() / scale)
    return power, force


def power_residuals(prob, th_deg):
    """|Σ power| / Σ|power terms| at th_deg: Mb w1 + Σ (F.v + M w) over the inertia forces,
    weights, loads = 0 (virtual power with the hand velocities; independent of the
    reaction equations, which carry no power)."""
    out, _ = solve(prob, th_deg)
    return out["power_residual_abs"] / out["power_scale"]


if __name__ == "__main__":
    for p in (CrankRockingBlock(), SwingingFeed()):
        print(p.name, "fd_check max", max(fd_check(p).values()))
    print(json.dumps(dict(exercise2_1=exercise_2_1(), exercise2_2=exercise_2_2(),
                          exercise2_5=exercise_2_5()), indent=1))
