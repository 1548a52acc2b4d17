"""The class-III triad: a ternary link held by three binary links (Newton).

A triad (三级杆组) is the simplest Assur group that is no dyad: the ternary link
``link`` carries the joints J1, J2, J3; each is pinned to a binary link ``links[k]``
of length ``l_k`` whose other end is a known point K_k.  Four links, six revolute
pairs, no closed form in general.

The ternary link's pose is ``u = (x, y, phi)``: J1 = (x, y), and the link's body
vectors ``d_1 = 0``, ``d_2 = (c, 0)``, ``d_3 = (p, q)`` (measured from J1 along the
direction J1 -> J2 and to its left) turned by phi:  J_k = (x, y) + R(phi) d_k.  The
three closure equations and their derivatives are

    g_k(u)  = (|r_k|^2 - l_k^2) / 2 = 0,                r_k = J_k - K_k
    dg_k    = r_k . (dx, dy) + (r_k . t_k) dphi,         t_k = R(phi + 90°) d_k
    g_k'    = r_k . (J_k' - K_k') = 0                    (velocities)
    g_k''   = |r_k'|^2 + r_k . (J_k'' - K_k'') = 0       (accelerations)

so the positions are Newton's iterates u <- u - A^-1 g with the 3x3 matrix A of
rows ``(r_kx, r_ky, r_k . t_k)``, solved by Cramer's rule on whole arrays of
positions (and designs), and the velocities and accelerations are two more solves
with the same A:

    A (x', y', phi')   = (r_k . K_k')
    A (x'', y'', phi'') = (r_k . K_k'' + phi'^2 r_k . R(phi) d_k - |r_k'|^2)

A vanishing determinant is the triad's dead point (its sine-like measure
``|det A| / (l_1 l_2 l_3 L)``, L the linkage's size, is reported as the condition).

Newton needs a start on the right assembly branch.  The element carries a table of
the ternary link's pose against the primary driver's angle, made by continuation
from the drawing (:func:`continuation_table`, in steps small enough that each
Newton solve starts next to its answer): every position starts from the table
interpolated at its input angle, wherever the sweep or a refinement asks.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar, Tuple

import numpy as np

from mechcli.core.linkage.elements import Element, LinkState, PointState
from mechcli.core.records import record

#: Newton iterations at most per solve, and the residual it must reach (relative to
#: the linkage's size) for a position to count as assembled
MAX_NEWTON = 30
CLOSURE_TOL = 1e-12
#: ... and where Newton stops: the step after the one that met CLOSURE_TOL (quadratic
#: convergence takes 1e-12 to round-off), so that velocities and the refined extremes
#: are computed at a pose closed to round-off
STOP_TOL = 1e-14
#: the continuation table's step [rad of the driver]
TABLE_STEP = math.radians(0.5)


@record
class Triad(Element):
    """Class-III triad: ternary ``link`` (joints ``joint_1, joint_2, joint_3``), each
    joint pinned to binary link ``link_k`` of length ``length_k`` from known point
    ``point_k``.  ``body_c`` = |J1 J2|; ``body_p``, ``body_q``: J3 from J1 along
    J1 -> J2 and to its left [m].  ``driver``: the link whose input angle indexes the
    continuation table ``table = (q, x, y, phi)`` (tuples of floats, q increasing;
    ``period``: 2π when it covers a whole turn, else 0)."""

    link: int
    joint_1: str
    joint_2: str
    joint_3: str
    link_1: int
    link_2: int
    link_3: int
    point_1: str
    point_2: str
    point_3: str
    length_1: float
    length_2: float
    length_3: float
    body_c: float
    body_p: float
    body_q: float
    driver: int
    table: tuple = ()
    period: float = 0.0
    #: a batch of designs (:func:`~.engine.stack`): each design's ``(table, period)``
    batch: tuple = ()

    kind: ClassVar[str] = "triad"
    lengths_: ClassVar[Tuple[str, ...]] = ("length_1", "length_2", "length_3", "body_c",
                                          "body_p", "body_q")

    @property
    def joints(self):
        return (self.joint_1, self.joint_2, self.joint_3)

    @property
    def binaries(self):
        return (self.link_1, self.link_2, self.link_3)

    @property
    def points(self):
        return (self.point_1, self.point_2, self.point_3)

    @property
    def lengths(self):
        return (self.length_1, self.length_2, self.length_3)

    def body(self):
        return ((0.0, 0.0), (self.body_c, 0.0), (self.body_p, self.body_q))

    def needs(self):
        return self.points, ()

    def makes(self):
        return self.joints, (self.link,) + self.binaries

    def reported_links(self, frame: int):
        return (self.link,) + self.binaries

    # -- the solve ---------------------------------------------------------------
    def start(self, q: Any):
        """The table's pose at the driver's angles ``q`` (the Newton start); for a
        batch of designs, each design's rows from its own table."""
        q = np.asarray(q, dtype=float)
        if not self.batch:
            return _from_table(self.table, self.period, q)
        m = len(self.batch)
        qb = np.broadcast_to(q if q.ndim == 2 else q.reshape(1, -1), (m, q.shape[-1]))
        rows = [_from_table(t, per, qb[k]) for k, (t, per) in enumerate(self.batch)]
        return tuple(np.stack([r[i] for r in rows]) for i in range(3))

    @classmethod
    def stack_fields(cls, elements: Any, names: Any):
        """:func:`~.engine.stack`: designs whose triads differ in their continuation
        tables (each drawing has its own) keep them per design."""
        if not set(names) <= {"table", "period"} or any(e.batch for e in elements):
            return None
        return {"table": (), "period": 0.0,
                "batch": tuple((e.table, e.period) for e in elements)}

    def step(self, st: Any):
        K = [st.P[p] for p in self.points]
        q = st.inputs[self.driver].q
        x, y, phi = (st.full(v).copy() for v in self.start(q))
        scale = st.scale
        ok, A, r, t, Rd = _newton(self, K, x, y, phi, scale)
        cof, det = _cofactors(A)
        sing = np.abs(det) / (abs(self.length_1 * self.length_2 * self.length_3) * scale)
        sing = np.where(ok, np.minimum(sing, 1.0), 0.0)
        st.condition(self, self.joint_1, sing)
        bad = st.mark(ok, sing)
        c, s = np.cos(phi), np.sin(phi)
        J = [(x + dx * c - dy * s, y + dx * s + dy * c) for dx, dy in self.body()]
        w = al = None
        wk = [None] * 3
        alk = [None] * 3
        pts = [PointState(jx, jy) for jx, jy in J]
        if st.vel:
            safe = np.where(bad, 1.0, det) if bad is not None else det
            rhs = [r[k][0] * K[k].vx + r[k][1] * K[k].vy for k in range(3)]
            vx, vy, w = _solve(cof, rhs, safe)
            for k, (dx, dy) in enumerate(self.body()):
                p = pts[k]
                p.vx, p.vy = vx + w * t[k][0], vy + w * t[k][1]
                rv = (p.vx - K[k].vx, p.vy - K[k].vy)
                wk[k] = (r[k][0] * rv[1] - r[k][1] * rv[0]) / self.lengths[k] ** 2
            if st.acc:
                rhs = []
                for k in range(3):
                    rv = (pts[k].vx - K[k].vx, pts[k].vy - K[k].vy)
                    rhs.append(r[k][0] * K[k].ax + r[k][1] * K[k].ay
                               + w * w * (r[k][0] * Rd[k][0] + r[k][1] * Rd[k][1])
                               - (rv[0] * rv[0] + rv[1] * rv[1]))
                ax, ay, al = _solve(cof, rhs, safe)
                for k in range(3):
                    p = pts[k]
                    p.ax = ax + al * t[k][0] - w * w * Rd[k][0]
                    p.ay = ay + al * t[k][1] - w * w * Rd[k][1]
                    ra = (p.ax - K[k].ax, p.ay - K[k].ay)
                    alk[k] = (r[k][0] * ra[1] - r[k][1] * ra[0]) / self.lengths[k] ** 2
        for name, p in zip(self.joints, pts):
            st.P[name] = p
        st.L[self.link] = LinkState(phi, c, s, w, al)
        for k, ln in enumerate(self.binaries):
            rx, ry = r[k]
            st.L[ln] = LinkState(np.arctan2(ry, rx), rx / self.lengths[k],
                                 ry / self.lengths[k], wk[k], alk[k])

    def pairs(self, tb: Any):
        for j in self.joints:
            tb.new_point(j, self.link)
        for j, ln, p in zip(self.joints, self.binaries, self.points):
            tb.revolute(p, ln)
            tb.joint(j, self.link, ln)
            tb.frames[ln] = [p, j]
        tb.frames[self.link] = [self.joint_1, self.joint_2]
        return (self.link,) + self.binaries

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Bar
        j1, j2, j3 = self.joints
        return tuple(Bar(p, j) for p, j in zip(self.points, self.joints)) + (
            Bar(j1, j2), Bar(j2, j3), Bar(j3, j1))


def _wrap(a: Any):
    return (a + np.pi) % (2 * np.pi) - np.pi


def _geometry(tri: Any, K: Any, x: Any, y: Any, phi: Any):
    """r_k = J_k - K_k, t_k = dJ_k/dphi and R(phi) d_k at the pose."""
    c, s = np.cos(phi), np.sin(phi)
    r, t, Rd = [], [], []
    for (dx, dy), k in zip(tri.body(), K):
        rdx, rdy = dx * c - dy * s, dx * s + dy * c
        Rd.append((rdx, rdy))
        t.append((-rdy, rdx))
        r.append((x + rdx - k.x, y + rdy - k.y))
    return r, t, Rd


def _matrix(r: Any, t: Any):
    return [(rk[0], rk[1], rk[0] * tk[0] + rk[1] * tk[1]) for rk, tk in zip(r, t)]


def _cofactors(A: Any):
    """The cofactors of the 3x3 matrix A (rows of arrays) and its determinant: the
    solves with one matrix share them (:func:`_solve`)."""
    (a, b, c), (d, e, f), (g, h, i) = A
    c11, c12, c13 = e * i - f * h, f * g - d * i, d * h - e * g
    c21, c22, c23 = c * h - b * i, a * i - c * g, b * g - a * h
    c31, c32, c33 = b * f - c * e, c * d - a * f, a * e - b * d
    det = a * c11 + b * c12 + c * c13
    return ((c11, c12, c13), (c21, c22, c23), (c31, c32, c33)), det


def _solve(cof: Any, rhs: Any, det: Any):
    """A u = rhs from A's cofactors: u = adj(A) rhs / det (Cramer's rule)."""
    (c11, c12, c13), (c21, c22, c23), (c31, c32, c33) = cof
    r1, r2, r3 = rhs
    inv = 1.0 / det
    return ((c11 * r1 + c21 * r2 + c31 * r3) * inv, (c12 * r1 + c22 * r2 + c32 * r3) * inv,
            (c13 * r1 + c23 * r2 + c33 * r3) * inv)


def _cramer(A: Any, rhs: Any, det: Any = None):
    """Solve the 3x3 systems A u = rhs (arrays of positions) by Cramer's rule."""
    cof, d = _cofactors(A)
    return _solve(cof, rhs, d if det is None else det)


def _newton(tri: Any, K: Any, x: Any, y: Any, phi: Any, scale: float):
    """Newton on the closure equations from the pose (x, y, phi), in place; returns
    (converged mask, A, r, t, Rd) at the final pose.  Each iteration first measures
    the closure error |(|r_k| - l_k)| ~ |g_k| / l_k at the current pose and stops when
    every position is within :data:`STOP_TOL` of the linkage's size (a position counts
    as assembled within :data:`CLOSURE_TOL`), so the last pose's geometry serves the
    velocity and acceleration solves as it is."""
    lengths = tri.lengths
    tol, stop = CLOSURE_TOL * scale, STOP_TOL * scale
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(MAX_NEWTON + 1):
            r, t, Rd = _geometry(tri, K, x, y, phi)
            g = [0.5 * (rk[0] * rk[0] + rk[1] * rk[1] - lk * lk) for rk, lk in zip(r, lengths)]
            err = np.maximum.reduce([np.abs(gk) * (1.0 / abs(lk)) for gk, lk in zip(g, lengths)])
            if np.all(err <= stop):
                break
            dx, dy, dp = _cramer(_matrix(r, t), g)
            fine = np.isfinite(dx) & np.isfinite(dy) & np.isfinite(dp) & (err > stop)
            x -= np.where(fine, dx, 0.0)
            y -= np.where(fine, dy, 0.0)
            phi -= np.where(fine, dp, 0.0)
        A = _matrix(r, t)
        ok = np.isfinite(err) & (err <= tol) & np.isfinite(phi)
    return ok, A, r, t, Rd


def continuation_table(tri: Any, known: Any, q0: float, pose0: Any, step: float = TABLE_STEP):
    """The ternary link's pose against the driver's angle, by continuation from the
    drawing: ``known(q)`` gives the known points K_1..K_3 (PointState with x, y) at
    driver angles ``q`` (an array); ``pose0 = (x, y, phi)`` at ``q0``.  The marches and
    the table's window are :func:`~.newton_group.table_from_marches`'.  Returns
    ``(table, period)``."""
    from mechcli.core.linkage.newton_group import table_from_marches

    scale = max([abs(v) for v in pose0[:2]] + [abs(tri.length_1), abs(tri.length_2),
                                                abs(tri.length_3), 1e-300])

    def advance(Kall: Any, i: Any, prev: Any):
        K = [_Pt(p.x[i], p.y[i]) for p in Kall]
        x, y, phi = (np.array(v, dtype=float) for v in prev)
        ok, _A, _r, _t, _Rd = _newton(tri, K, x, y, phi, scale)
        if not bool(ok):
            return None
        return float(x), float(y), float(phi)

    return table_from_marches(known, advance, q0, pose0, scale, step)


def _from_table(table: tuple, period: float, q: Any):
    """The pose ``(x, y, phi)`` interpolated in one continuation table at ``q``."""
    from mechcli.core.linkage.newton_group import _from_table as read

    return tuple(read(table, period, q))


class _Pt:
    __slots__ = ("x", "y")

    def __init__(self, x: Any, y: Any):
        self.x, self.y = x, y
