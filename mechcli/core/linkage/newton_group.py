"""Any Assur group by Newton: the groups with no closed form (class III with sliders,
class IV and up, an RPP dyad, a triad under two drivers).

The group's n links are rigid bodies with unknown poses ``u_i = (x_i, y_i, phi_i)``:
the body's origin and the angle of its reference direction.  A point fixed on body i
at local coordinates ``d`` is ``P = (x_i, y_i) + R(phi_i) d``.  Its pairs give 3n
equations (an Assur group has 3n = 2p):

* a revolute pair joins a point of body a to a point of body b, or to a known point
  K::

      g = P_a - P_b  (2 equations)
* a prismatic pair keeps body a's point P_a on a line fixed in body b (through P_b,
  direction ``t = R(phi_b + beta) e_x``, left normal ``n``) at its drawn offset h0,
  and the two bodies' angles at their drawn difference c0::

      g = (L (phi_a - phi_b - c0),  n . (P_a - P_b) - h0)

  (L, the linkage's size, makes every equation a length).  A side that is a known
  link (the frame, a driver, an earlier group) has its pose from the solved points
  and links.

Positions are Newton's iterates ``u <- u - J^-1 g`` with the analytic Jacobian J,
solved for whole arrays of positions at once (``numpy.linalg.solve`` on stacked
3n x 3n matrices).  Velocities and accelerations are linear solves with the same J:
``g' = J u' + g'_known = 0`` and ``g'' = J u'' + g''_rest = 0``, where the known part
is g's time derivative with the unknown rates set to zero (the point rules
``P' = v + w R(90°) R d``, ``P'' = a + al R(90°) R d - w^2 R d``, and for the line
``n' = -w_b t``).  The conditioning is the reciprocal 1-norm condition number 1/κ₁ of J
with its angle columns divided by L, relative to its best over the table (times
:data:`MARGIN`), reported like a dyad's sine; near zero is the group's dead point.

Newton needs a start on the right assembly branch: as for the all-revolute triad
(:mod:`.triad`), the element carries a table of its poses against the primary
driver's angle, made by continuation from the drawing (secondary drivers follow the
primary as the spec's ``ratio`` and ``phase`` say), and each position starts from the
table interpolated at its input angle.
"""

from __future__ import annotations

import math
from typing import Any, Callable, ClassVar, List, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.linkage.elements import Element, LinkState, PointState
from mechcli.core.records import record

#: Newton iterations at most, and the closure it must reach (relative to the linkage's
#: size) for a position to count as assembled; it stops at STOP_TOL (one step past)
MAX_NEWTON = 30
CLOSURE_TOL = 1e-12
STOP_TOL = 1e-14
#: the continuation table's step [rad of the primary driver]
TABLE_STEP = math.radians(0.5)
#: the reported condition is 1/κ₁ relative to the table's best, times this margin:
#: the digits-lost estimate (the dyads' model, docs/accuracy.md) then stays within about
#: a digit of the truth on the optimistic side near a singular position (measured against
#: 60-digit solutions, tests/unit/linkage/test_triad_accuracy.py: +1.0 … −2.9 digits)
MARGIN = 1.0 / 3.0
#: where the branch ends (a dead point) the continuation closes in on it to this [rad]
FOLD_TOL = 1e-11
#: a branch that reaches over a turn without closing is read in a window this much
#: shorter than a turn [rad]: the positions in the gap are reported as not assembled
WINDOW_GAP = 1e-6

Arr = Any   # a float or an array of positions (and designs)


@record
class NewtonGroup(Element):
    """An Assur group solved by Newton on its pairs' closure equations.

    ``links``: the group's links (its bodies, in order); each body's origin and
    reference angle are those of the drawing (``frames``: one ``(x0, y0, phi0)`` per
    body, for the table's start only).

    ``pins``: revolute pairs ``(joint, a, ax, ay, b, bx, by)``: the point (ax, ay) of
    body ``a`` (an index into ``links``) is the point (bx, by) of body ``b``, or, when
    ``b`` is -1, the known point ``joint``.

    ``slides``: prismatic pairs ``(name, point, a, ax, ay, b, bx, by, beta, h0, c0,
    block, guide)``: body a's point (ax, ay) (the named ``point``) stays at the offset
    h0 from the line through body b's point (bx, by) at angle beta in b's frame, their
    angles differ by c0; an index -1 - k is the known link ``known[k] = (link,
    origin)`` (``origin`` a known point on it, "" for the frame's origin).  ``block``
    and ``guide`` are the links the statics sees: the block's angle is the line's.

    ``ends``: per body, its first two joints as drawn (``(origin, second)``, second ""
    for a link with one): the statics' frame of the link (its default centre of mass,
    the origin of a ``com = [along, normal]``).

    ``well``: the best conditioning (1/κ₁) over the continuation table; the
    reported condition is the conditioning relative to it (times :data:`MARGIN`; → 0 at
    a dead point), so that it reads like a dyad's sine whatever the group's size and
    formulation.

    ``driver``: the primary driver (the table's input); ``table = (q, u_1 … u_3n)``,
    ``period`` 2π when it covers a whole turn; ``batch``: per design ``(table,
    period)`` (:func:`~.engine.stack`).
    """

    links: tuple
    pins: tuple
    slides: tuple
    known: tuple
    driver: int
    ends: tuple = ()
    group: str = "group"
    well: Any = 1.0
    table: tuple = ()
    period: float = 0.0
    batch: tuple = ()

    kind: ClassVar[str] = "group"

    # -- what it needs and makes -------------------------------------------------
    @property
    def inner_joints(self) -> Tuple[str, ...]:
        out: List[str] = []
        for j, _a, _ax, _ay, b, _bx, _by in self.pins:
            if b >= 0 and j not in out:
                out.append(j)
        return tuple(out)

    @property
    def outer_points(self) -> Tuple[str, ...]:
        out = [j for j, _a, _ax, _ay, b, _bx, _by in self.pins if b < 0]
        out += [o for _l, o in self.known if o]
        return tuple(dict.fromkeys(out))

    def needs(self) -> Tuple[Tuple[str, ...], Tuple[int, ...]]:
        return self.outer_points, tuple(ln for ln, _o in self.known)

    def makes(self) -> Tuple[Tuple[str, ...], Tuple[int, ...]]:
        return self.inner_joints, tuple(self.links)

    def slide_names(self, frame: Any) -> Tuple[str, ...]:
        return tuple(s[0] for s in self.slides)

    def translating_links(self, frame: int) -> Tuple[int, ...]:
        return tuple(self.links[s[2]] for s in self.slides
                     if s[2] >= 0 and s[5] < 0 and self.known[-1 - s[5]][0] == frame) + tuple(
            self.links[s[5]] for s in self.slides
            if s[5] >= 0 and s[2] < 0 and self.known[-1 - s[2]][0] == frame)

    def reported_links(self, frame: int) -> Tuple[int, ...]:
        fixed = set(self.translating_links(frame))
        return tuple(ln for ln in self.links if ln not in fixed)

    @classmethod
    def stack_fields(cls, elements: Sequence[NewtonGroup], names: Any) -> Any:
        """:func:`~.engine.stack`: designs of one topology (the same links, joints and
        known links) whose drawings differ: each keeps its continuation table, and the
        pairs' numbers become columns of the designs, ``(M, 1)`` arrays that broadcast
        over the positions like every other element's batched lengths."""
        if not set(names) <= {"table", "period", "pins", "slides", "well"} or any(
                e.batch for e in elements):
            return None
        out: dict = {"table": (), "period": 0.0,
                     "batch": tuple((e.table, e.period) for e in elements),
                     "well": np.asarray([e.well for e in elements], dtype=float)[:, None]}
        for name in ("pins", "slides"):
            rows = [getattr(e, name) for e in elements]
            if any(len(r) != len(rows[0]) for r in rows):
                return None
            stacked = []
            for k, first in enumerate(rows[0]):
                entry: list = []
                for f, v in enumerate(first):
                    column = [r[k][f] for r in rows]
                    if isinstance(v, (str, int)) and not isinstance(v, bool) \
                            and type(v) is not float:
                        if any(c != v for c in column):
                            return None
                        entry.append(v)
                    else:
                        entry.append(np.asarray(column, dtype=float)[:, None])
                stacked.append(tuple(entry))
            out[name] = tuple(stacked)
        return out

    # -- the solve ----------------------------------------------------------------
    def start(self, q: Arr) -> List[Arr]:
        """The table's poses at the primary driver's angles ``q`` (Newton's start)."""
        q = np.asarray(q, dtype=float)
        if not self.batch:
            return _from_table(self.table, self.period, q)
        m = len(self.batch)
        qb = np.broadcast_to(q if q.ndim == 2 else q.reshape(1, -1), (m, q.shape[-1]))
        rows = [_from_table(t, per, qb[k]) for k, (t, per) in enumerate(self.batch)]
        return [np.stack([r[i] for r in rows]) for i in range(len(rows[0]))]

    def step(self, st: Any) -> None:
        u0 = self.start(st.inputs[self.driver].q)
        u = [st.full(v).copy() for v in u0]
        sys = _System(self, st.P, st.L, st.frame, st.scale)
        ok, J = sys.newton(u)
        ok &= ~_left_branch(u0, u, st.scale)
        sing = np.where(ok, np.minimum(sys.conditioning(J) / self.well, 1.0) * MARGIN, 0.0)
        st.condition(self, (self.inner_joints or self.outer_points)[0], sing)
        bad = st.mark(ok, sing)
        vel = acc = None
        if st.vel:
            Js = J if bad is None else _regularised(J, bad)
            vel = _solve(Js, [-r for r in sys.rates(u, None, None)])
            if st.acc:
                acc = _solve(Js, [-r for r in sys.rates(u, vel, None)])
        sys.write(st, u, vel, acc)

    # -- statics and drawing ---------------------------------------------------------
    def pairs(self, tb: Any) -> Tuple[int, ...]:
        made = set()
        for j, a, _ax, _ay, b, _bx, _by in self.pins:
            la = self.links[a]
            if b < 0:
                tb.revolute(j, la)
            elif j not in made:
                made.add(j)
                tb.new_point(j, la)
                tb.joint(j, la, self.links[b])
            else:
                tb.joint(j, tb.owner[j], self.links[b])
        for s in self.slides:
            tb.prismatic(s[12], s[11], s[1])
        for ln, (first, second) in zip(self.links, self.ends):
            tb.frames[ln] = [first, second or None]
        return tuple(self.links)

    def sketch(self, frame: int) -> Tuple[Any, ...]:
        from mechcli.core.linkage.sketch import Bar, Block
        out: List[Any] = []
        for i, ln in enumerate(self.links):
            on = [j for j, a, _ax, _ay, b, _bx, _by in self.pins if i in (a, b)]
            on = list(dict.fromkeys(on))
            out += [Bar(p, q) for p, q in zip(on, on[1:])]
            if len(on) > 2:
                out.append(Bar(on[-1], on[0]))
        out += [Block(s[1], s[11]) for s in self.slides]
        return tuple(out)


class _Body:
    """A body's pose and rates at the positions: (x, y, phi) with cos, sin; (vx, vy, w)
    and (ax, ay, al), None where not (yet) known."""

    __slots__ = ("x", "y", "phi", "c", "s", "v", "a")

    def __init__(self, x: Arr, y: Arr, phi: Arr, v: Any = None, a: Any = None) -> None:
        self.x, self.y, self.phi = x, y, phi
        self.c, self.s = np.cos(phi), np.sin(phi)
        self.v, self.a = v, a

    def point(self, lx: float, ly: float) -> Tuple[Arr, Arr, Arr, Arr]:
        """The point fixed at (lx, ly): its position and R(phi) d."""
        rx, ry = self.c * lx - self.s * ly, self.s * lx + self.c * ly
        return self.x + rx, self.y + ry, rx, ry

    def point_rates(self, rx: Arr, ry: Arr) -> Tuple[Tuple[Arr, Arr], Tuple[Arr, Arr]]:
        """Velocity and acceleration of the point at R(phi) d = (rx, ry) (zero rates
        where the body's are unknown)."""
        vx, vy, w = self.v if self.v is not None else (0.0, 0.0, 0.0)
        ax, ay, al = self.a if self.a is not None else (0.0, 0.0, 0.0)
        return ((vx - w * ry, vy + w * rx),
                (ax - al * ry - w * w * rx, ay + al * rx - w * w * ry))


_ZERO = (0.0, 0.0, 0.0)


class _System:
    """The group's equations on one state: the known bodies and points from ``P`` and
    ``L`` (the engine's solve state, or a solved motion for the continuation)."""

    def __init__(self, el: NewtonGroup, P: Any, L: Any, frame: int, scale: Arr) -> None:
        self.el, self.P, self.scale = el, P, scale   # an (M, 1) array for a batch
        self.n = len(el.links)
        self.m = 3 * self.n
        self.kb = [self._known_body(P, L, frame, ln, o) for ln, o in el.known]

    @staticmethod
    def _known_body(P: Any, L: Any, frame: int, link: int, origin: str) -> _Body:
        if origin:
            p = P[origin]
            x, y = p.x, p.y
            v = None if getattr(p, "vx", None) is None else (p.vx, p.vy)
            a = None if getattr(p, "ax", None) is None else (p.ax, p.ay)
        else:
            x = y = 0.0
            v = a = (0.0, 0.0)
        phi: Arr
        w: Optional[Arr]
        al: Optional[Arr]
        if link == frame:
            phi, w, al = 0.0, 0.0, 0.0
        else:
            ls = L[link]
            phi = ls.theta
            w, al = getattr(ls, "w", None), getattr(ls, "al", None)
        body = _Body(x, y, phi)
        body.v = None if v is None or w is None else (v[0], v[1], w)
        body.a = None if a is None or al is None else (a[0], a[1], al)
        return body

    def bodies(self, u: Sequence[Arr], vel: Any = None, acc: Any = None) -> List[_Body]:
        out = []
        for i in range(self.n):
            b = _Body(u[3 * i], u[3 * i + 1], u[3 * i + 2])
            b.v = None if vel is None else tuple(vel[3 * i:3 * i + 3])
            b.a = None if acc is None else tuple(acc[3 * i:3 * i + 3])
            out.append(b)
        return out

    def _end(self, bodies: List[_Body], k: int) -> _Body:
        return bodies[k] if k >= 0 else self.kb[-1 - k]

    def _known_point(self, name: str) -> Tuple[Arr, Arr]:
        p = self.P[name]
        return p.x, p.y

    # -- residuals and Jacobian ---------------------------------------------------------
    def residual(self, u: Sequence[Arr]) -> Tuple[List[Arr], np.ndarray]:
        """g(u) and J(u): a list of m arrays and an array (..., m, m)."""
        el, L = self.el, self.scale
        B = self.bodies(u)
        shape = np.broadcast_shapes(*(np.shape(v) for v in u))
        J = np.zeros(shape + (self.m, self.m))
        g: List[Arr] = []
        r = 0
        for j, a, ax, ay, b, bx, by in el.pins:
            pa = B[a].point(ax, ay)
            J[..., r, 3 * a] = 1.0
            J[..., r + 1, 3 * a + 1] = 1.0
            J[..., r, 3 * a + 2] = -pa[3]
            J[..., r + 1, 3 * a + 2] = pa[2]
            if b < 0:
                kx, ky = self._known_point(j)
                g += [pa[0] - kx, pa[1] - ky]
            else:
                pb = B[b].point(bx, by)
                g += [pa[0] - pb[0], pa[1] - pb[1]]
                J[..., r, 3 * b] = -1.0
                J[..., r + 1, 3 * b + 1] = -1.0
                J[..., r, 3 * b + 2] = pb[3]
                J[..., r + 1, 3 * b + 2] = -pb[2]
            r += 2
        for (_name, _pt, a, ax, ay, b, bx, by, beta, h0, c0, _blk, _gd) in el.slides:
            ea, eb = self._end(B, a), self._end(B, b)
            pa, pb = ea.point(ax, ay), eb.point(bx, by)
            tx, ty = np.cos(eb.phi + beta), np.sin(eb.phi + beta)
            dx, dy = pa[0] - pb[0], pa[1] - pb[1]
            # the angle difference wrapped: a known link's angle may jump by a turn
            g += [L * _wrap(ea.phi - eb.phi - c0), -ty * dx + tx * dy - h0]
            if a >= 0:
                J[..., r, 3 * a + 2] = L
                J[..., r + 1, 3 * a] = -ty
                J[..., r + 1, 3 * a + 1] = tx
                J[..., r + 1, 3 * a + 2] = ty * pa[3] + tx * pa[2]
            if b >= 0:
                J[..., r, 3 * b + 2] = -L
                J[..., r + 1, 3 * b] = ty
                J[..., r + 1, 3 * b + 1] = -tx
                J[..., r + 1, 3 * b + 2] = -(tx * dx + ty * dy) - (ty * pb[3] + tx * pb[2])
            r += 2
        return g, J

    def rates(self, u: Sequence[Arr], vel: Any, acc: Any) -> List[Arr]:
        """g's first time derivative with the unknown rates zero (``vel`` None), or its
        second with the unknown accelerations zero (``vel`` given): the right-hand
        sides' negatives."""
        el, L = self.el, self.scale
        second = vel is not None
        B = self.bodies(u, vel, None)
        out: List[Arr] = []
        for j, a, ax, ay, b, bx, by in el.pins:
            pa = B[a].point(ax, ay)
            va, aa = B[a].point_rates(pa[2], pa[3])
            if b < 0:
                p = self.P[j]
                vb, ab = (p.vx, p.vy), (p.ax, p.ay)
            else:
                pb = B[b].point(bx, by)
                vb, ab = B[b].point_rates(pb[2], pb[3])
            d = (aa, ab) if second else (va, vb)
            out += [d[0][0] - d[1][0], d[0][1] - d[1][1]]
        for (_name, _pt, a, ax, ay, b, bx, by, beta, _h0, _c0, _blk, _gd) in el.slides:
            ea, eb = self._end(B, a), self._end(B, b)
            pa, pb = ea.point(ax, ay), eb.point(bx, by)
            va, aa = ea.point_rates(pa[2], pa[3])
            vb, ab = eb.point_rates(pb[2], pb[3])
            wa = (ea.v or _ZERO)[2]
            wb = (eb.v or _ZERO)[2]
            ala = (ea.a or _ZERO)[2]
            alb = (eb.a or _ZERO)[2]
            tx, ty = np.cos(eb.phi + beta), np.sin(eb.phi + beta)
            dx, dy = pa[0] - pb[0], pa[1] - pb[1]
            ddx, ddy = va[0] - vb[0], va[1] - vb[1]
            if not second:
                out += [L * (wa - wb), -wb * (tx * dx + ty * dy) + (-ty * ddx + tx * ddy)]
            else:
                adx, ady = aa[0] - ab[0], aa[1] - ab[1]
                out += [L * (ala - alb),
                        -alb * (tx * dx + ty * dy) - wb * wb * (-ty * dx + tx * dy)
                        - 2.0 * wb * (tx * ddx + ty * ddy) + (-ty * adx + tx * ady)]
        return out

    # -- Newton -------------------------------------------------------------------------
    def newton(self, u: List[Arr]) -> Tuple[Arr, np.ndarray]:
        """Newton from the poses ``u`` (a list of 3n arrays, updated in place); returns
        (assembled mask, J at the final poses)."""
        tol, stop = CLOSURE_TOL * self.scale, STOP_TOL * self.scale
        with np.errstate(all="ignore"):
            for _ in range(MAX_NEWTON + 1):
                g, J = self.residual(u)
                err = np.maximum.reduce([np.abs(gk) for gk in g])
                if np.all(err <= stop):
                    break
                du = _solve(_regularised(J, ~np.isfinite(err)), g)
                fine = err > stop
                for k in range(self.m):
                    ok_k = fine & np.isfinite(du[k])
                    u[k] -= np.where(ok_k, du[k], 0.0)
            ok = np.isfinite(err) & (err <= tol)
            for v in u:
                ok &= np.isfinite(v)
        return ok, J

    def conditioning(self, J: np.ndarray) -> Arr:
        """1 / (‖J‖₁ ‖J⁻¹‖₁) of J with its angle columns made lengths (the reciprocal of
        its 1-norm condition number: an inverse per position, a fifth of an SVD's cost)."""
        Jn = J.copy()
        Jn[..., 2::3] /= np.asarray(self.scale, dtype=float)[..., None, None]
        with np.errstate(all="ignore"):
            bad = ~np.isfinite(Jn).all(axis=(-2, -1))
            try:
                inv = np.linalg.inv(_regularised(Jn, bad))
            except np.linalg.LinAlgError:
                det = np.linalg.det(_regularised(Jn, bad))
                bad = bad | ~np.isfinite(det) | (det == 0.0)
                inv = np.linalg.inv(_regularised(Jn, bad))
            norm = np.abs(Jn).sum(axis=-2).max(axis=-1) * np.abs(inv).sum(axis=-2).max(axis=-1)
            return np.where(bad | ~np.isfinite(norm), 0.0, 1.0 / norm)

    # -- results --------------------------------------------------------------------------
    def write(self, st: Any, u: Sequence[Arr], vel: Any, acc: Any) -> None:
        el = self.el
        B = self.bodies(u, vel, acc)
        done = set()
        for j, a, ax, ay, b, _bx, _by in el.pins:
            if b < 0 or j in done:
                continue
            done.add(j)
            x, y, rx, ry = B[a].point(ax, ay)
            p = PointState(x, y)
            if vel is not None:
                (p.vx, p.vy), (p.ax, p.ay) = B[a].point_rates(rx, ry)
                if acc is None:
                    p.ax = p.ay = None
            st.P[j] = p
        for i, ln in enumerate(el.links):
            b = B[i]
            w = None if vel is None else vel[3 * i + 2]
            al = None if acc is None else acc[3 * i + 2]
            st.L[ln] = LinkState(b.phi, b.c, b.s, w, al)
        for (name, _pt, a, ax, ay, bi, bx, by, beta, _h0, _c0, blk, gd) in el.slides:
            ea, eb = self._end(B, a), self._end(B, bi)
            pa, pb = ea.point(ax, ay), eb.point(bx, by)
            tx, ty = np.cos(eb.phi + beta), np.sin(eb.phi + beta)
            dx, dy = pa[0] - pb[0], pa[1] - pb[1]
            s = tx * dx + ty * dy
            v = acc_s = None
            if vel is not None:
                va, aa = ea.point_rates(pa[2], pa[3])
                vb, ab = eb.point_rates(pb[2], pb[3])
                wb = (eb.v or _ZERO)[2]
                ddx, ddy = va[0] - vb[0], va[1] - vb[1]
                nd = -ty * dx + tx * dy
                v = wb * nd + tx * ddx + ty * ddy
                if acc is not None:
                    alb = (eb.a or _ZERO)[2]
                    acc_s = (alb * nd - wb * wb * s + 2.0 * wb * (-ty * ddx + tx * ddy)
                             + tx * (aa[0] - ab[0]) + ty * (aa[1] - ab[1]))
            st.slide(name, self._slide_link(a, blk), self._slide_link(bi, gd), s, v, acc_s)

    def _slide_link(self, k: int, fallback: int) -> int:
        return self.el.links[k] if k >= 0 else self.el.known[-1 - k][0]


def _regularised(J: np.ndarray, bad: Any) -> np.ndarray:
    """J with the matrices at ``bad`` positions replaced by the identity (their
    solution is discarded), so a batched solve never meets a singular one."""
    if bad is None or not np.any(bad):
        return J
    J = J.copy()
    J[np.broadcast_to(bad, J.shape[:-2])] = np.eye(J.shape[-1])
    return J


def _solve(J, rhs: Sequence[Arr]) -> List[Arr]:
    """J x = rhs for every position (rhs: m arrays), x as m arrays; NaN where J is
    singular."""
    shape = J.shape[:-2]
    if not shape:     # one position (the continuation's steps)
        R = np.array([float(r) for r in rhs])
    else:
        R = np.stack([np.broadcast_to(np.asarray(r, dtype=float), shape) for r in rhs], -1)
    with np.errstate(all="ignore"):
        try:
            x = np.linalg.solve(J, R[..., None])[..., 0]
        except np.linalg.LinAlgError:
            det = np.linalg.det(J)
            bad = ~np.isfinite(det) | (det == 0.0)
            x = np.linalg.solve(_regularised(J, bad), R[..., None])[..., 0]
            x[bad] = np.nan
    return [x[..., k] for k in range(J.shape[-1])]


# ---------------------------------------------------------------------------------
# continuation from the drawing
# ---------------------------------------------------------------------------------
def continuation_table(group: NewtonGroup, known: Callable, q0: float, pose0: Sequence[float],
                       scale: float, frame: int, step: float = TABLE_STEP):
    """The group's poses against the primary driver's angle, by continuation from the
    drawing: ``known(q)`` is a solved motion (``.points``, ``.links``) of the known
    part at driver angles ``q``; ``pose0`` the 3n pose values at ``q0``.  A turn each
    way from the drawing, each step's Newton started from the previous pose
    (:func:`table_from_marches`).  Returns ``(table, period)``."""
    def advance(m: Any, i: int, prev: Sequence[float]) -> Any:
        P = {k: _Pt(p.x[i], p.y[i]) for k, p in m.points.items()}
        L = {k: _Ln(lm.theta[i]) for k, lm in m.links.items()}
        u = [np.array(v, dtype=float) for v in prev]
        ok, _J = _System(group, P, L, frame, scale).newton(u)
        return tuple(float(v) for v in u) if bool(ok) else None

    return table_from_marches(known, advance, q0, pose0, scale, step)


def best_conditioning(group: NewtonGroup, motion: Any, table: tuple, scale: float,
                      frame: int) -> float:
    """The largest 1/κ₁ over the table's poses (``motion``: the known part solved
    at the table's angles): :attr:`NewtonGroup.well`."""
    sys = _System(group, motion.points, motion.links, frame, scale)
    u = [np.asarray(c, dtype=float) for c in table[1:]]
    _g, J = sys.residual(u)
    best = float(np.max(sys.conditioning(J)))
    return best if best > 0.0 else 1.0


def drawn_conditioning(group: NewtonGroup, motion: Any, pose: Sequence[float], scale: float,
                       frame: int) -> float:
    """1/κ₁ at one pose (``motion``: the known part solved at its angle, one position):
    the drawing's, whose dead point fixes no branch."""
    P = {k: _Pt(p.x[0], p.y[0]) for k, p in motion.points.items()}
    L = {k: _Ln(lm.theta[0]) for k, lm in motion.links.items()}
    sys = _System(group, P, L, frame, scale)
    _g, J = sys.residual([np.asarray(v, dtype=float) for v in pose])
    return float(sys.conditioning(J))


def table_from_marches(known: Callable, advance: Callable, q0: float,
                       pose0: Sequence[float], scale: float, step: float = TABLE_STEP,
                       predict: bool = False):
    """A continuation table ``(q, pose columns…)`` and its period from marches of up to
    a turn each way from the drawing's ``q0`` (``advance(motion, i, pose)``: the pose at
    the march's i-th angle from the previous one, None where Newton fails;
    ``predict``: start it from the secant through the previous two poses instead).

    A branch that comes back to the drawn pose after a turn is periodic (period 2π) and
    read modulo a turn.  Otherwise the table is one window of less than a turn, read
    at the input moved by whole turns into it; angles outside it are not reached (the
    engine reports them as beyond an assembly limit).  The window ends where the branch
    does (a dead point, where the input cannot go on), so that a sweep never jumps from
    one end of the branch to the other unreported: where it reaches over a turn, the
    window is cut one step short of a turn, at a dead point if the branch has one."""
    n = int(round(2 * math.pi / step))

    def solve_at(q: float, prev: Sequence[float]) -> Any:
        nxt = advance(known(np.array([q])), 0, prev)
        return None if nxt is None or _jumped(prev, nxt, scale) else nxt

    def march(sign: int) -> Tuple[List[float], List[Any], bool]:
        grid = q0 + sign * step * np.arange(n + 1)
        m = known(grid)
        qs, poses = [float(q0)], [tuple(float(v) for v in pose0)]
        for i in range(1, n + 1):
            # Newton starts from the previous pose (or, with predict, the secant through
            # the last two: fewer iterations, but near a passage where two branches
            # come close it can land on the other, so not by default)
            guess = poses[-1] if len(poses) < 2 or not predict else tuple(
                2.0 * a - b for a, b in zip(poses[-1], poses[-2]))
            nxt = advance(m, i, guess)
            if nxt is not None and not _jumped(poses[-1], nxt, scale):
                qs.append(float(grid[i]))
                poses.append(nxt)
                continue
            # a fast passage or the branch's end: shorter steps to this grid angle,
            # halved where they fail and doubled back where they pass; a step that
            # fails at FOLD_TOL is a dead point (the input cannot go on)
            h = step / 2
            while sign * (grid[i] - qs[-1]) > FOLD_TOL:
                hh = min(h, sign * (float(grid[i]) - qs[-1]))
                nxt = solve_at(qs[-1] + sign * hh, poses[-1])
                if nxt is None:
                    h = hh / 2
                    if h < FOLD_TOL:
                        return qs, poses, True
                    continue
                qs.append(qs[-1] + sign * hh)
                poses.append(nxt)
                h = min(2 * hh, step)
            qs[-1] = float(grid[i])
        return qs, poses, False

    qf, fwd, stopped_f = march(1)
    width = len(pose0)
    # periodic: after the turn every body is back where it was drawn (angles and origins)
    if not stopped_f and not _moved(fwd[0], _unturned(fwd[-1], fwd[0]), 1e-6, 1e-6 * scale):
        return _columns(qf[:-1], fwd[:-1], width), 2 * math.pi   # all but q0 + 2π
    qb, bwd, stopped_b = march(-1)
    qs = qb[1:][::-1] + qf
    rows = bwd[1:][::-1] + fwd
    span = 2 * math.pi - WINDOW_GAP
    if qs[-1] - qs[0] > span + 1e-12:
        if stopped_f or not stopped_b:
            lo = qs[-1] - span if stopped_f else q0 - span / 2
            i = next(k for k, q in enumerate(qs) if q > lo)
            end = solve_at(lo, rows[i])
            qs, rows = [lo] + qs[i:], [end] + rows[i:]
        if qs[-1] - qs[0] > span + 1e-12:
            hi = qs[0] + span
            i = max(k for k, q in enumerate(qs) if q < hi)
            end = solve_at(hi, rows[i])
            qs, rows = qs[:i + 1] + [hi], rows[:i + 1] + [end]
        if any(r is None for r in rows):  # pragma: no cover - a solved neighbour's step
            raise ValueError("the continuation could not solve its window's end")
    return _columns(qs, rows, width), 0.0


def _columns(qs: Sequence[float], rows: Sequence[Any], width: int) -> tuple:
    return (tuple(map(float, qs)),) + tuple(tuple(r[k] for r in rows) for k in range(width))


def _unturned(pose: Sequence[float], ref: Sequence[float]) -> Tuple[float, ...]:
    """``pose`` with its angles moved by whole turns next to ``ref``'s."""
    out = list(pose)
    for k in range(2, len(out), 3):
        out[k] = ref[k] + float(_wrap(out[k] - ref[k]))
    return tuple(out)


def _moved(a: Sequence[Arr], b: Sequence[Arr], angle: float, length: Arr) -> Arr:
    """Where the poses ``b`` are over ``angle`` [rad] (a body's turn) or ``length`` (a
    body's origin) from the poses ``a``: per position for arrays, a bool for floats."""
    far = np.zeros(np.shape(a[0]), dtype=bool)
    with np.errstate(invalid="ignore"):
        for k in range(0, len(a), 3):
            far |= np.abs(np.subtract(b[k + 2], a[k + 2])) > angle
            far |= np.hypot(np.subtract(b[k], a[k]), np.subtract(b[k + 1], a[k + 1])) > length
    return far


def _jumped(prev: Sequence[float], nxt: Sequence[float], scale: float) -> bool:
    """A continuation step that left the branch: an angle turned by over 0.5 rad or a
    body moved by over a fifth of the linkage's size in one step."""
    return bool(_moved(prev, nxt, 0.5, 0.2 * scale))


def _left_branch(u0: Sequence[Arr], u: Sequence[Arr], scale: Arr) -> Arr:
    """Positions where Newton ended far from its start (an angle by over 0.25 rad, a
    body by over a tenth of the linkage's size): on another assembly branch, which the
    table (made in 0.5° steps) would have started next to."""
    return _moved(u0, u, 0.25, 0.1 * scale)


def _wrap(a: Arr) -> Arr:
    return (a + np.pi) % (2 * np.pi) - np.pi


def _from_table(table: tuple, period: float, q: Arr) -> List[Arr]:
    """The poses interpolated in one continuation table at ``q``.  A table that does not
    cover a whole turn (the branch ends at dead points) is read at ``q`` moved by whole
    turns into its range; where it is not there, NaN (the branch does not reach it)."""
    tq = np.asarray(table[0], dtype=float)
    cols = [np.asarray(t, dtype=float) for t in table[1:]]
    q = tq[0] + np.mod(np.asarray(q, dtype=float) - tq[0], 2 * np.pi)
    if period:
        tq = np.append(tq, tq[0] + period)
        closed = []
        for k, c in enumerate(cols):
            if k % 3 == 2:   # an angle: continue it by its turn over the period
                closed.append(np.append(c, c[0] + (c[-1] - c[0] + _wrap(c[0] - c[-1]))))
            else:
                closed.append(np.append(c, c[0]))
        return [np.interp(q, tq, c) for c in closed]
    out = np.greater(q, tq[-1])
    return [np.where(out, np.nan, np.interp(q, tq, c)) for c in cols]


class _Pt:
    __slots__ = ("x", "y", "vx", "vy", "ax", "ay")

    def __init__(self, x: Arr, y: Arr) -> None:
        self.x, self.y = x, y
        self.vx = self.vy = self.ax = self.ay = None


class _Ln:
    __slots__ = ("theta", "w", "al")

    def __init__(self, theta: Arr) -> None:
        self.theta, self.w, self.al = theta, None, None


def local(origin: Tuple[float, float], angle: float, p: Sequence[float]) -> Tuple[float, float]:
    """The coordinates of the drawn point ``p`` in a body frame at ``origin`` turned by
    ``angle``."""
    dx, dy = p[0] - origin[0], p[1] - origin[1]
    c, s = math.cos(angle), math.sin(angle)
    return float(c * dx + s * dy), float(-s * dx + c * dy)


__all__ = ["NewtonGroup", "continuation_table", "local"]
