#!/usr/bin/env python3
"""Independent kinetostatic reference numbers for `mechcli force`.

Deliberately self-contained: imports nothing from mechcli (only numpy/scipy).

Method
------
* positions: closed-form geometry (circle intersections, right triangles) derived here;
* velocities / accelerations: 8th-order central differences in the crank angle
  (stencil +-4h, h = 0.005 rad; cross-checked against h = 0.01 rad); angles are
  differenced after wrapping, so branch cuts of atan2 do not matter.  Constant
  crank speed: d/dt = w1 d/dth, d2/dt2 = w1^2 d2/dth2;
* kinetostatics: d'Alembert, 3 equations (Fx, Fy, Mz about the global origin) per
  moving link, one dense square system per position, numpy.linalg.solve;
* power balance checked at every grid point.

Sign conventions (see CONVENTIONS below) follow the brief exactly:
F_Rij = force exerted BY link i ON link j (i < j, frame has its own number),
M_Rij = couple of i on j (prismatic pairs; force placed at the named pin point),
Mb = torque of the frame on crank 1, CCW positive.

Run:  python3 tests/reference/independent_force.py  [-> tests/reference/force_reference.json]
"""
import json
import math
import os
import sys

import numpy as np
from scipy.optimize import brentq, minimize_scalar

DEG = math.pi / 180.0
TWO_PI = 2.0 * math.pi
GRID_N = 36000                      # 0.01 deg grid over one turn
DG = TWO_PI / GRID_N
H_MAIN = 0.005                      # finite-difference step [rad]
H_CHECK = 0.01

# 8th-order central difference coefficients, offsets -4..4
C1 = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
C2 = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560])
OFFS = np.arange(-4, 5)


class AssemblyError(RuntimeError):
    pass


# ----------------------------------------------------------------------------- geometry helpers
def unit(a):
    a = np.asarray(a, dtype=float)
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


def angle_of(v):
    return np.arctan2(v[..., 1], v[..., 0])


def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def norm(v):
    return np.hypot(v[..., 0], v[..., 1])


def circ_int(P0, r0, P1, r1, side):
    """Intersection of circle(P0, r0) and circle(P1, r1).
    side=+1: the point on the LEFT of the directed line P0->P1 (cross(P1-P0, X-P0) > 0),
    side=-1: on the right."""
    P0 = np.asarray(P0, float)
    P1 = np.asarray(P1, float)
    d = P1 - P0
    L = norm(d)
    a = (r0 ** 2 - r1 ** 2 + L ** 2) / (2 * L)
    h2 = r0 ** 2 - a ** 2
    if np.any(h2 < 0):
        raise AssemblyError("circles do not intersect")
    h = np.sqrt(h2)
    u = d / L[..., None]
    perp = np.stack([-u[..., 1], u[..., 0]], axis=-1)
    return P0 + a[..., None] * u + side * h[..., None] * perp


def const_pt(p, th):
    return np.broadcast_to(np.asarray(p, float), th.shape + (2,)).copy()


def wrap(a):
    return (a + math.pi) % TWO_PI - math.pi


# ----------------------------------------------------------------------------- problem definitions
class Problem:
    """name, omega1, g, frame, links {k: (m, J, com_point)}, pairs, geom(th)->(pts, angs)."""

    switch_funcs = ()       # functions kin -> array whose zeros are load-switching edges
    fixed_edges = ()        # switching edges known exactly [rad]

    def condition(self, kin):       # conditional load active?  (bool array)
        return np.zeros(kin["th"].shape, bool)

    def loads(self, kin, active):   # list of (link, F (N,2), point name, couple (N,))
        return []

    def extra(self, out):           # problem-specific extra report items
        return {}


class FourBar(Problem):
    name = "ex2-1"
    omega1, g, frame = 10.0, 10.0, 4
    A, D = np.array([0.0, 0.0]), np.array([1.2, 0.0])
    l1, l2, l3 = 0.4, 1.0, 0.7
    links = {1: (1.2, 0.016, "S1"), 2: (3.0, 0.25, "S2"), 3: (2.2, 0.09, "S3")}
    pairs = [dict(i=1, j=4, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="R", at="C"), dict(i=3, j=4, kind="R", at="D")]
    conventions_extra = ("C on the left of directed line B->D (above the x-axis at th1=0); "
                         "resisting torque -100 N m on link 3 at all positions.")

    def geom(self, th):
        A, D = const_pt(self.A, th), const_pt(self.D, th)
        B = A + self.l1 * unit(th)
        C = circ_int(B, self.l2, D, self.l3, +1)
        pts = dict(A=A, B=B, C=C, D=D, S1=(A + B) / 2, S2=(B + C) / 2, S3=(D + C) / 2)
        angs = {1: th.copy(), 2: angle_of(C - B), 3: angle_of(C - D)}
        return pts, angs

    def loads(self, kin, active):
        n = kin["th"].shape
        return [(3, np.zeros(n + (2,)), "D", np.full(n, -100.0))]

    def extra(self, out):
        pts, _ = self.geom(np.array([0.0]))
        return dict(C_at_th0_m=pts["C"][0].tolist(),
                    C_branch_check="C on the left of B->D; at th1=0 C_y > 0: %s" % bool(pts["C"][0, 1] > 0))


class SliderCrank(Problem):
    name = "ex2-2"
    omega1, g, frame = 10.0, 10.0, 4
    l1, l2 = 0.4, 1.2
    links = {1: (1.2, 0.0, "S1"), 2: (3.6, 0.45, "S2"), 3: (6.0, 0.0, "C")}
    pairs = [dict(i=1, j=4, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="R", at="C"),
             dict(i=3, j=4, kind="P", at="C", guide=lambda p, a: const_pt([1.0, 0.0], a[1]))]
    conventions_extra = ("guide = x-axis, C = larger-x solution; F = (-1000, 0) N at C on the slider "
                         "at all positions; F_R34 = force of slider 3 on frame 4 (vertical), "
                         "M_R34 = couple of 3 on 4 about C.")

    def geom(self, th):
        A = const_pt([0.0, 0.0], th)
        B = self.l1 * unit(th)
        C = np.stack([B[..., 0] + np.sqrt(self.l2 ** 2 - B[..., 1] ** 2), np.zeros_like(th)], axis=-1)
        pts = dict(A=A, B=B, C=C, S1=0.5 * B, S2=B + 0.6 * (C - B) / self.l2)
        angs = {1: th.copy(), 2: angle_of(C - B), 3: np.zeros_like(th)}
        return pts, angs

    def loads(self, kin, active):
        n = kin["th"].shape
        F = np.zeros(n + (2,))
        F[..., 0] = -1000.0
        return [(3, F, "C", np.zeros(n))]


class GuideBar(Problem):
    name = "ex2-3"
    omega1, g, frame = 10.0, 9.8, 4
    A = np.array([0.0, 1.0])
    l1 = 0.4
    links = {1: (1.2, 0.0, "A"), 2: (0.0, 0.0, "B"), 3: (10.0, 2.2, "S3")}
    pairs = [dict(i=1, j=4, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="P", at="B", guide=lambda p, a: unit(a[3])),
             dict(i=3, j=4, kind="R", at="C")]
    working_sign = None      # determined in prepare()

    def geom(self, th):
        A = const_pt(self.A, th)
        C = const_pt([0.0, 0.0], th)
        B = A + self.l1 * unit(th)
        phi3 = angle_of(B - C)
        pts = dict(A=A, B=B, C=C, S3=0.8 * unit(phi3), D=1.6 * unit(phi3))
        angs = {1: th.copy(), 2: phi3, 3: phi3.copy()}
        return pts, angs

    switch_funcs = (lambda kin: kin["om"][3],)

    def prepare(self):
        # extremes of the guide bar: zeros of w3 ; the larger crank arc is the working stroke
        edges = find_roots(self, self.switch_funcs[0])
        assert len(edges) == 2, edges
        e0, e1 = edges
        arc01 = e1 - e0
        mid01 = 0.5 * (e0 + e1)
        mid10 = e1 + 0.5 * (TWO_PI - arc01)
        w01 = kinematics(self, np.array([mid01]))["om"][3][0]
        w10 = kinematics(self, np.array([mid10]))["om"][3][0]
        if arc01 > TWO_PI - arc01:
            self.working_sign = np.sign(w01)
        else:
            self.working_sign = np.sign(w10)
        self.arcs = dict(edges_deg=[e0 / DEG, e1 / DEG], arc_e0_e1_deg=arc01 / DEG, w3_sign_e0_e1=float(np.sign(w01)),
                         arc_e1_e0_deg=(TWO_PI - arc01) / DEG, w3_sign_e1_e0=float(np.sign(w10)))

    def condition(self, kin):
        return np.sign(kin["om"][3]) == self.working_sign

    def loads(self, kin, active):
        n = kin["th"].shape
        M = np.where(active, -100.0 * self.working_sign, 0.0)
        return [(3, np.zeros(n + (2,)), "C", M)]

    @property
    def conventions_extra(self):
        return ("guide-bar direction C->B; block 2 massless (J2=0); link 1 CoM at A, J1=0; "
                "resisting torque = -100*sign(w3) N m on link 3 only while sign(w3) equals the "
                "working-stroke sign (working stroke = larger crank arc between the two guide-bar "
                "extreme positions w3=0); F_R23 = force of block 2 on bar 3 (normal to the bar), "
                "M_R23 = couple of 2 on 3 about B (identically 0, block massless).")

    def extra(self, out):
        d = dict(self.arcs)
        d["working_stroke_w3_sign"] = float(self.working_sign)
        d["working_stroke_note"] = ("working (slow) stroke has w3 %s 0 (guide bar turns %s); "
                                    "torque on link 3 during it = %+.0f N m" %
                                    (">" if self.working_sign > 0 else "<",
                                     "CCW" if self.working_sign > 0 else "CW", -100 * self.working_sign))
        return d


class Shaper(Problem):
    name = "ex2-4"
    omega1, g, frame = 1.0, 9.8, 6
    A = np.array([0.0, 0.275])
    l1, lCD, l4, yguide = 0.125, 0.6, 0.15, 0.575
    links = {1: (0.0, 0.0, "A"), 2: (0.0, 0.0, "B"), 3: (20.0, 0.12, "S3"),
             4: (3.0, 0.00025, "S4"), 5: (62.0, 0.0, "S5")}
    pairs = [dict(i=1, j=6, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="P", at="B", guide=lambda p, a: unit(a[3])),
             dict(i=3, j=6, kind="R", at="C"), dict(i=3, j=4, kind="R", at="D"),
             dict(i=4, j=5, kind="R", at="E"),
             dict(i=5, j=6, kind="P", at="E", guide=lambda p, a: const_pt([1.0, 0.0], a[1]))]
    sE_min = sE_max = None

    def geom(self, th):
        A = const_pt(self.A, th)
        C = const_pt([0.0, 0.0], th)
        B = A + self.l1 * unit(th)
        phi3 = angle_of(B - C)
        D = self.lCD * unit(phi3)
        dy = self.yguide - D[..., 1]
        dx2 = self.l4 ** 2 - dy ** 2
        if np.any(dx2 < 0):
            raise AssemblyError("link 4 cannot reach the ram guide")
        E = np.stack([D[..., 0] - np.sqrt(dx2), np.full_like(th, self.yguide)], axis=-1)
        S5 = E - np.array([0.15, 0.0])
        pts = dict(A=A, B=B, C=C, D=D, E=E, S3=0.5 * D, S4=0.5 * (D + E), S5=S5)
        angs = {1: th.copy(), 2: phi3, 3: phi3.copy(), 4: angle_of(E - D), 5: np.zeros_like(th)}
        return pts, angs

    def prepare(self):
        grid = np.arange(GRID_N) * DG
        xE = self.geom(grid)[0]["E"][:, 0]
        fx = lambda t: self.geom(np.array([t]))[0]["E"][0, 0]
        i_min, i_max = int(np.argmin(xE)), int(np.argmax(xE))
        r = minimize_scalar(fx, bounds=(grid[i_min] - DG, grid[i_min] + DG), method="bounded",
                            options=dict(xatol=1e-12))
        self.sE_min, self.th_sEmin = float(r.fun), float(r.x)
        r = minimize_scalar(lambda t: -fx(t), bounds=(grid[i_max] - DG, grid[i_max] + DG), method="bounded",
                            options=dict(xatol=1e-12))
        self.sE_max, self.th_sEmax = float(-r.fun), float(r.x)
        H = self.sE_max - self.sE_min
        self.H = H
        self.lo = self.sE_min + 0.05 * H
        self.hi = self.sE_max - 0.05 * H
        self.switch_funcs = (lambda kin: kin["vel"]["E"][:, 0],
                             lambda kin: kin["pos"]["E"][:, 0] - self.lo,
                             lambda kin: kin["pos"]["E"][:, 0] - self.hi)

    def condition(self, kin):
        xE = kin["pos"]["E"][:, 0]
        return (kin["vel"]["E"][:, 0] < 0) & (xE >= self.lo) & (xE <= self.hi)

    def loads(self, kin, active):
        n = kin["th"].shape
        F = np.zeros(n + (2,))
        F[..., 0] = np.where(active, 5880.0, 0.0)
        return [(5, F, "S5", np.zeros(n))]

    conventions_extra = ("guide-bar direction C->B; E = smaller-x solution on y=0.575; S5 = E-(0.15,0); "
                         "cutting force (+5880,0) N at S5 on ram 5 while vE<0 and "
                         "sE_min+0.05H <= xE <= sE_max-0.05H (inclusive); links 1,2 massless; "
                         "F_R16, F_R36, F_R56 are forces of the moving link ON the frame 6; "
                         "F_R56 vertical, M_R56 = couple of 5 on 6 about E; M_R23 about B.")

    def extra(self, out):
        return dict(sE_min_m=self.sE_min, sE_min_at_deg=self.th_sEmin / DEG % 360,
                    sE_max_m=self.sE_max, sE_max_at_deg=self.th_sEmax / DEG % 360, H_m=self.H,
                    xE_active_lo_m=self.lo, xE_active_hi_m=self.hi)


class Crusher(Problem):
    name = "exercise2-8"
    omega1, g, frame = 20.0, 9.8, 6
    D = np.array([-0.30, -0.50])
    G = np.array([0.43, 0.21])
    l1, l2, l3, l4, l5 = 0.10, 0.46, 0.25, 0.265, 0.67
    links = {1: (2.0, 0.0015, "A"), 2: (9.0, 0.065, "S2"), 3: (4.5, 0.017, "S3"),
             4: (5.0, 0.03, "S4"), 5: (15.0, 0.5, "S5")}
    pairs = [dict(i=1, j=6, kind="R", at="A"), dict(i=1, j=2, kind="R", at="B"),
             dict(i=2, j=3, kind="R", at="C"), dict(i=2, j=4, kind="R", at="C"),
             dict(i=3, j=6, kind="R", at="D"), dict(i=4, j=5, kind="R", at="F"),
             dict(i=5, j=6, kind="R", at="G")]
    sideC, sideF = -1, +1          # requested: C right of B->D, F left of C->G
    fixed_edges = (90 * DEG, 210 * DEG)

    def prepare(self):
        """Try the requested branches; fall back to the first combination that assembles."""
        grid = np.arange(GRID_N) * DG
        self.branch_log = []
        for sc, sf in ((-1, +1), (-1, -1), (+1, +1), (+1, -1)):
            self.sideC, self.sideF = sc, sf
            try:
                self.geom(grid)
                self.geom(grid + 4 * H_CHECK)
                self.geom(grid - 4 * H_CHECK)
            except AssemblyError:
                B = self.l1 * unit(grid)
                C = circ_int(B, self.l2, const_pt(self.D, grid), self.l3, sc)
                d = norm(self.G - C)
                self.branch_log.append("C %s of B->D, F %s of C->G: does NOT assemble (|CG| in [%.6f, %.6f] m, "
                                       "needs <= l4+l5 = %.3f m)" % ("left" if sc > 0 else "right",
                                                                   "left" if sf > 0 else "right",
                                                                   d.min(), d.max(), self.l4 + self.l5))
                continue
            self.branch_log.append("C %s of B->D, F %s of C->G: assembles for the whole turn -> USED"
                                   % ("left" if sc > 0 else "right", "left" if sf > 0 else "right"))
            return
        raise AssemblyError("no branch assembles")

    def geom(self, th):
        A = const_pt([0.0, 0.0], th)
        D, G = const_pt(self.D, th), const_pt(self.G, th)
        B = self.l1 * unit(th)
        C = circ_int(B, self.l2, D, self.l3, self.sideC)
        F = circ_int(C, self.l4, G, self.l5, self.sideF)
        p2, p3, p4, p5 = angle_of(C - B), angle_of(C - D), angle_of(F - C), angle_of(F - G)
        pts = dict(A=A, B=B, C=C, D=D, F=F, G=G,
                   S2=B + 0.30 * unit(p2 + 30 * DEG), S3=D + 0.11 * unit(p3 + 15 * DEG),
                   S4=C + 0.13 * unit(p4), S5=G + 0.50 * unit(p5))
        angs = {1: th.copy(), 2: p2, 3: p3, 4: p4, 5: p5}
        return pts, angs

    def condition(self, kin):
        d = np.round(kin["th"] / DEG % 360.0, 9)
        return (d >= 90.0) & (d <= 210.0)

    def loads(self, kin, active):
        pos = kin["pos"]
        u = pos["F"] - pos["G"]
        u = u / norm(u)[:, None]
        n = np.stack([-u[:, 1], u[:, 0]], axis=-1)
        s = np.sign(np.einsum("ij,ij->i", n, pos["C"] - pos["G"]))
        F = 300.0 * n * s[:, None] * active[:, None]
        return [(5, F, "S5", np.zeros(kin["th"].shape))]

    @property
    def conventions_extra(self):
        return ("BRANCHES: C %s of B->D, F %s of C->G (the requested C-right-of-B->D branch does not assemble, "
                "|CG| would exceed CF+FG); compound hinge C: pin on link 2, F_R23/F_R24 = forces of link 2 "
                         "on links 3/4; ore force 300 N at S5 normal to FG towards C's side of line GF, "
                         "active for 90<=th1<=210 deg (inclusive; tabulated values at 90 and 210 include it); "
                         "F_R16, F_R36, F_R56 = forces of links 1, 3, 5 ON frame 6.") % (
                    "left" if self.sideC > 0 else "right", "left" if self.sideF > 0 else "right")

    def extra(self, out):
        grid = np.arange(GRID_N) * DG
        pts, _ = self.geom(grid)

        def tangle(P, Q, R):   # transmission angle at Q between QP and QR, folded to [0, 90]
            a, b = P - Q, R - Q
            mu = np.arccos(np.clip(np.einsum("ij,ij->i", a, b) / (norm(a) * norm(b)), -1, 1)) / DEG
            return np.minimum(mu, 180 - mu)

        t1 = tangle(pts["B"], pts["C"], pts["D"])
        t2 = tangle(pts["C"], pts["F"], pts["G"])
        dCG = norm(pts["G"] - pts["C"])
        return dict(
            branches=self.branch_log,
            transmission_angle_BCD_min_deg=float(t1.min()), transmission_angle_BCD_min_at_deg=float(grid[np.argmin(t1)] / DEG),
            transmission_angle_CFG_min_deg=float(t2.min()), transmission_angle_CFG_min_at_deg=float(grid[np.argmin(t2)] / DEG),
            CG_distance_range_m=[float(dCG.min()), float(dCG.max())],
            CG_assembly_limits_m=[abs(self.l5 - self.l4), self.l5 + self.l4],
            note="transmission angles from the 0.01 deg grid, folded to [0,90] deg")


# ----------------------------------------------------------------------------- kinematics
def kinematics(prob, th, h=H_MAIN):
    th = np.asarray(th, float)
    samples = [prob.geom(th + k * h) for k in OFFS]
    pts0, angs0 = samples[4]
    w = prob.omega1
    kin = dict(th=th, pos=pts0, phi=angs0, vel={}, acc={}, om={}, al={})
    for name in pts0:
        stack = np.stack([s[0][name] for s in samples])          # (9, N, 2)
        kin["vel"][name] = w * np.tensordot(C1, stack, axes=1) / h
        kin["acc"][name] = w * w * np.tensordot(C2, stack, axes=1) / h ** 2
    for k in angs0:
        stack = np.stack([wrap(s[1][k] - angs0[k]) for s in samples])  # (9, N)
        kin["om"][k] = w * np.tensordot(C1, stack, axes=1) / h
        kin["al"][k] = w * w * np.tensordot(C2, stack, axes=1) / h ** 2
    return kin


# ----------------------------------------------------------------------------- kinetostatics
def pair_name(p):
    return "%d%d" % (p["i"], p["j"])


def kinetostatics(prob, kin, active):
    th = kin["th"]
    N = th.shape[0]
    moving = sorted(prob.links)
    row = {k: 3 * idx for idx, k in enumerate(moving)}
    n = 3 * len(moving)
    unknowns = 1 + 2 * len(prob.pairs)      # Mb and two per lower pair
    if unknowns != n:
        raise ValueError(f"{prob.name}: {unknowns} unknowns for {n} equations "
                         f"({len(moving)} moving links): not a square system")
    A = np.zeros((N, n, n))
    b = np.zeros((N, n))
    pos, vel, acc = kin["pos"], kin["vel"], kin["acc"]
    A[:, row[1] + 2, 0] = 1.0                                  # Mb on crank
    normals = {}
    for ip, p in enumerate(prob.pairs):
        c = 1 + 2 * ip
        P = pos[p["at"]]
        if p["kind"] == "P":
            u = p["guide"](pos, kin["phi"])
            nv = np.stack([-u[:, 1], u[:, 0]], axis=-1)
            normals[ip] = nv
        for link, sgn in ((p["j"], 1.0), (p["i"], -1.0)):
            if link == prob.frame:
                continue
            r = row[link]
            if p["kind"] == "R":
                A[:, r, c] += sgn
                A[:, r + 1, c + 1] += sgn
                A[:, r + 2, c] += -sgn * P[:, 1]
                A[:, r + 2, c + 1] += sgn * P[:, 0]
            else:
                A[:, r, c] += sgn * nv[:, 0]
                A[:, r + 1, c] += sgn * nv[:, 1]
                A[:, r + 2, c] += sgn * cross(P, nv)
                A[:, r + 2, c + 1] += sgn
    # known loads: gravity + inertia
    power = np.zeros(N)
    power_abs = np.zeros(N)
    for k in moving:
        m, J, s = prob.links[k]
        S, aS, vS = pos[s], acc[s], vel[s]
        F = -m * aS + np.array([0.0, -m * prob.g])
        M = -J * kin["al"][k]
        r = row[k]
        b[:, r:r + 2] -= F
        b[:, r + 2] -= cross(S, F) + M
        terms = [np.einsum("ij,ij->i", F, vS), M * kin["om"][k]]
        for t in terms:
            power += t
            power_abs += np.abs(t)
    for k, F, at, M in prob.loads(kin, active):
        r = row[k]
        P = pos[at]
        b[:, r:r + 2] -= F
        b[:, r + 2] -= cross(P, F) + M
        terms = [np.einsum("ij,ij->i", F, vel[at]), M * kin["om"][k]]
        for t in terms:
            power += t
            power_abs += np.abs(t)
    x = np.linalg.solve(A, b[..., None])[..., 0]
    # the equations are met: residual at round-off of the largest load (a singular or
    # mis-assembled system would leave it large)
    scale = max(1.0, float(np.max(np.abs(b))))
    assert float(np.max(np.abs(np.einsum("nij,nj->ni", A, x) - b))) <= 1e-9 * scale, \
        "kinetostatic equations not met"
    out = dict(Mb=x[:, 0])
    power += x[:, 0] * prob.omega1
    power_abs += np.abs(x[:, 0] * prob.omega1)
    for ip, p in enumerate(prob.pairs):
        c = 1 + 2 * ip
        nm = pair_name(p)
        if p["kind"] == "R":
            F = x[:, c:c + 2]
        else:
            F = x[:, c:c + 1] * normals[ip]
            out["MR" + nm] = x[:, c + 1]
        out["FR%sx" % nm] = F[:, 0]
        out["FR%sy" % nm] = F[:, 1]
        out["FR" + nm] = norm(F)
    out["power_residual_abs"] = np.abs(power)
    out["power_scale"] = power_abs
    return out


def evaluate(prob, th, active=None, h=H_MAIN):
    th = np.atleast_1d(np.asarray(th, float))
    kin = kinematics(prob, th, h)
    if active is None:
        active = prob.condition(kin)
    else:
        active = np.broadcast_to(np.asarray(active, bool), th.shape)
    return kinetostatics(prob, kin, active), kin, active


# ----------------------------------------------------------------------------- switching edges
def find_roots(prob, f):
    grid = np.arange(GRID_N + 1) * DG
    vals = f(kinematics(prob, grid))
    roots = []
    fs = lambda t: f(kinematics(prob, np.array([t])))[0]
    for i in range(GRID_N):
        if vals[i] == 0.0:
            roots.append(grid[i])
        elif vals[i] * vals[i + 1] < 0:
            roots.append(brentq(fs, grid[i], grid[i + 1], xtol=1e-14, rtol=1e-15, maxiter=200))
    return sorted(set(r % TWO_PI for r in roots))


def segments(prob):
    edges = list(prob.fixed_edges)
    for f in prob.switch_funcs:
        edges += find_roots(prob, f)
    edges = sorted(set(e % TWO_PI for e in edges))
    if not edges:
        return edges, [(0.0, TWO_PI, False, True)]
    segs = []
    for k, a in enumerate(edges):
        b = edges[k + 1] if k + 1 < len(edges) else edges[0] + TWO_PI
        mid = 0.5 * (a + b)
        st = bool(prob.condition(kinematics(prob, np.array([mid])))[0])
        segs.append((a, b, st, False))
    return edges, segs


def active_intervals(segs):
    ivs = []
    for a, b, st, _ in segs:
        if not st:
            continue
        a_d, b_d = a / DEG, b / DEG
        if b_d <= 360.0 + 1e-12:
            ivs.append([a_d, min(b_d, 360.0)])
        else:
            ivs.append([a_d, 360.0])
            ivs.append([0.0, b_d - 360.0])
    ivs.sort()
    merged = []
    for iv in ivs:
        if merged and abs(merged[-1][1] - iv[0]) < 1e-9:
            merged[-1][1] = iv[1]
        else:
            merged.append(list(iv))
    return merged


# ----------------------------------------------------------------------------- extremes
def extreme(prob, segs, key, sense):
    """sense=+1 max, -1 min; returns (value, angle_deg).  Piecewise-smooth: each segment with its
    own (constant) load state, segment endpoints evaluated as one-sided limits (supremum side)."""
    best = (-np.inf, None)
    for a, b, st, periodic in segs:
        k0 = int(math.ceil(a / DG))
        k1 = int(math.floor(b / DG))
        ks = np.arange(k0, k1 + 1)
        th = ks * DG
        if not periodic:
            th = th[(th > a) & (th < b)]
        cand = []
        if not periodic:
            for e in (a, b):
                cand.append((sense * evaluate(prob, [e], st)[0][key][0], e))
        if th.size == 0:
            c = max(cand, key=lambda z: z[0])
            if c[0] > best[0]:
                best = c
            continue
        q = sense * evaluate(prob, th, st)[0][key]
        i = int(np.argmax(q))
        t = th[i]
        lo, hi = t - DG, t + DG
        if not periodic:
            lo, hi = max(lo, a), min(hi, b)
        fq = lambda x: -sense * evaluate(prob, [x], st)[0][key][0]
        r = minimize_scalar(fq, bounds=(lo, hi), method="bounded", options=dict(xatol=1e-10))
        cand.append((-r.fun, r.x))
        cand.append((q[i], t))
        c = max(cand, key=lambda z: z[0])
        if c[0] > best[0]:
            best = c
    return sense * best[0], (best[1] / DEG) % 360.0


# ----------------------------------------------------------------------------- driver
def sig(v):
    if isinstance(v, (list, tuple)):
        return [sig(x) for x in v]
    if isinstance(v, dict):
        return {k: sig(x) for k, x in v.items()}
    if isinstance(v, (float, np.floating)):
        return float("%.12g" % float(v))
    if isinstance(v, (np.integer,)):
        return int(v)
    return v


BASE_CONV = ("x right, y up, angles CCW from +x, CCW torques positive, SI units. "
             "F_Rij (i<j) = force exerted BY link i ON link j at the pair point (frame numbered like any link, "
             "so pairs with the frame give the force of the moving link on the frame); prismatic pairs: "
             "force normal to the guide placed at the named pin point plus couple M_Rij of i on j. "
             "Mb = torque of the frame on crank 1 (driving torque). Gravity -y. Constant w1 CCW, alpha1=0. "
             "Velocities/accelerations by 8th-order central differences in th1 (h=0.005 rad). "
             "Mean/RMS: arithmetic mean over the uniform grid th1 = k*0.01 deg, k=0..35999. "
             "Extremes: 0.01 deg grid + bounded minimize_scalar refinement per smooth segment; "
             "at load-switching edges the supremum (one-sided limit) is reported. ")


def run(prob):
    if hasattr(prob, "prepare"):
        prob.prepare()
    res = {}
    res["conventions"] = BASE_CONV + prob.conventions_extra
    pos_deg = list(range(0, 360, 30))
    out, kin, act = evaluate(prob, np.array(pos_deg, float) * DEG)
    res["positions_deg"] = pos_deg
    keys = ["Mb"]
    for p in prob.pairs:
        nm = pair_name(p)
        keys += ["FR%sx" % nm, "FR%sy" % nm, "FR" + nm] + (["MR" + nm] if p["kind"] == "P" else [])
    for k in keys:
        unit_s = "_N_m" if k.startswith(("Mb", "MR")) else "_N"
        res[k + unit_s] = out[k].tolist()
    if prob.switch_funcs or prob.fixed_edges:
        res["load_active_at_positions"] = [bool(a) for a in act]

    # fine grid
    grid = np.arange(GRID_N) * DG
    og, kg, ag = evaluate(prob, grid)
    edges, segs = segments(prob)

    ex = {}
    ex["Mb_max_N_m"], ex["Mb_max_at_deg"] = extreme(prob, segs, "Mb", +1)
    ex["Mb_min_N_m"], ex["Mb_min_at_deg"] = extreme(prob, segs, "Mb", -1)
    ex["Mb_mean_N_m"] = float(og["Mb"].mean())
    ex["Mb_rms_N_m"] = float(np.sqrt((og["Mb"] ** 2).mean()))
    # cross-check of the mean: exact mean of Mb = -(1/2pi w1) * integral of external-load power
    # (inertia and gravity do no net work over a cycle); here: scipy quad per smooth segment
    from scipy.integrate import quad
    tot = 0.0
    for a, b, st, periodic in segs:
        tot += quad(lambda t: evaluate(prob, [t], st)[0]["Mb"][0], a, b, limit=400, epsabs=1e-9, epsrel=1e-11)[0]
    ex["Mb_mean_piecewise_quad_N_m"] = tot / TWO_PI
    for p in prob.pairs:
        nm = "FR" + pair_name(p)
        ex[nm + "_max_N"], ex[nm + "_max_at_deg"] = extreme(prob, segs, nm, +1)
    res["extremes"] = ex
    res["power_residual_max"] = float(og["power_residual_abs"].max() / og["power_scale"].max())
    res["power_residual_note"] = ("max over the 0.01 deg grid of |sum of all powers| divided by the max over "
                                  "the grid of the sum of |individual power terms|; absolute max [W] in "
                                  "power_residual_abs_max_W")
    res["power_residual_abs_max_W"] = float(og["power_residual_abs"].max())
    if prob.switch_funcs or prob.fixed_edges:
        res["active_deg"] = active_intervals(segs)
        res["switch_edges_deg"] = [e / DEG for e in edges]

    # finite-difference accuracy check: h=0.005 vs h=0.01 on the 1-deg grid, fixed load state
    g1 = np.arange(360) * DEG
    st = prob.condition(kinematics(prob, g1))
    oa = evaluate(prob, g1, st, H_MAIN)[0]
    ob = evaluate(prob, g1, st, H_CHECK)[0]
    # scale: largest force magnitude of the problem for forces, largest |Mb| for torques/couples
    fscale = max(np.abs(oa[k]).max() for k in keys if k.startswith("FR"))
    mscale = np.abs(oa["Mb"]).max()
    fd = {}
    for k in keys:
        scale = mscale if k.startswith(("Mb", "MR")) else fscale
        fd[k] = float(np.abs(oa[k] - ob[k]).max() / scale)
    res["fd_step_check_max_rel_diff"] = max(fd.values())
    res["fd_step_check_note"] = ("max |result(h=0.005) - result(h=0.01)| on a 1-deg grid, divided by the "
                                 "largest |Mb| (torques) or largest pair-force magnitude (forces)")
    res.update(prob.extra(out))
    return sig(res)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    target = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "force_reference.json")
    probs = [FourBar(), SliderCrank(), GuideBar(), Shaper(), Crusher()]
    result = {}
    for p in probs:
        print("solving", p.name, file=sys.stderr)
        result[p.name] = run(p)
    with open(target, "w") as fh:
        json.dump(result, fh, indent=1)
        fh.write("\n")
    print("wrote", target, file=sys.stderr)


if __name__ == "__main__":
    main()
