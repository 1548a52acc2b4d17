"""The linkage engine: drivers plus class-II Assur groups (杆组法), vectorized.

A planar linkage is a frame, one or more drivers (a crank turning about a
known point, or a slider moving along a line) and a sequence of class-II Assur
groups (dyads), each of which locates one new joint from two known points:

* :class:`RRR` -- two links joined at a new revolute ``joint``;
* :class:`RRP` -- a link from a known point to a slider pin on a guide line
  carried by a known link (the frame or a moving one);
* :class:`RPR` -- a guide link pivoted at a known point, sliding through a
  block pivoted at another known point (guide-bar, 导杆);
* :class:`PointOnLink` -- any point fixed on a solved link (tracer/coupler
  point, or the next dyad's known point).

Positions are closed-form with an explicit ``branch``; velocities and
accelerations come from the time-differentiated loop equations, each a 2x2
linear system solved by Cramer's rule on whole arrays -- never by differencing
positions.  All inputs may be arrays of any (common, broadcastable) shape: the
whole sweep is solved at once.

Points are complex numbers ``x + iy`` [m]; velocities [m/s] and accelerations
[m/s^2] likewise.  Angles are counter-clockwise from +x [rad].

Notes
-----
This generalises the closed-vector-loop method of chapter 1 of the book
(eq. 1-1 ... 1-36): e.g. the four-bar of 例 1-1 is ``Crank`` + ``RRR``; the
slider-crank of 例 1-2 is ``Crank`` + ``RRP``; the guide-bar of 例 1-3 is
``Crank`` + ``RPR``; the shaper of 例 1-4 is ``Crank`` + ``RPR`` +
``PointOnLink`` + ``RRP``.
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Dict, Optional, Tuple, Union

import numpy as np

#: relative size below which a dyad counts as singular (a dead point).  The
#: closed-form positions carry a sqrt of a rounded discriminant, so sin(gamma)
#: at an exact toggle comes out as large as ~sqrt(eps) ~ 1.5e-8: anything below
#: 1e-7 is numerically indistinguishable from the toggle itself.
SINGULAR_TOL = 1e-7
#: relative tolerance for a dyad that just touches its assembly limit
ASSEMBLY_TOL = 1e-10


class LinkageDefinitionError(ValueError):
    """The elements do not form a solvable linkage (bad topology or reference).

    Attributes
    ----------
    index : int or None
        Index of the offending element in ``Linkage.elements``.
    """

    def __init__(self, message, index=None, field=None):
        super().__init__(message)
        self.index = index
        self.field = field


# ---------------------------------------------------------------------------
# elements
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Ground:
    """A point fixed on the frame at (x, y) [m]."""

    name: str
    x: float
    y: float


@dataclasses.dataclass(frozen=True)
class Crank:
    """Rotary driver: link ``link`` turns about the known point ``pivot``.

    ``point = pivot + length * exp(i*theta)``, where ``theta`` is the driver's
    input angle (the link's absolute angle) [rad]; ``length`` [m].
    """

    link: int
    pivot: str
    point: str
    length: float


@dataclasses.dataclass(frozen=True)
class SliderDriver:
    """Linear driver: link ``link`` translates along a line fixed on the frame.

    ``point = origin + s * exp(i*angle)``; ``s`` is the driver's input [m].
    """

    link: int
    origin: str
    point: str
    angle: float = 0.0
    name: Optional[str] = None


@dataclasses.dataclass(frozen=True)
class RRR:
    """RRR dyad: link ``link_a`` (from ``point_a``, length ``length_a``) and
    link ``link_b`` (from ``point_b``, length ``length_b``) meet at ``joint``.

    ``branch = +1`` puts ``joint`` to the left of the directed line
    point_a -> point_b, ``-1`` to the right.
    """

    joint: str
    point_a: str
    link_a: int
    length_a: float
    point_b: str
    link_b: int
    length_b: float
    branch: int = 1


@dataclasses.dataclass(frozen=True)
class RRP:
    """RRP dyad: link ``link`` of length ``length`` from the known ``point`` to a
    slider pin ``joint`` on block ``slider``, which slides on a guide line of
    link ``guide_link``.

    The guide line passes through ``guide_point`` (a point on the guide link)
    shifted by ``offset`` [m] along the line's left normal, in direction
    ``guide_angle`` [rad] relative to the guide link.  The slide ``s`` is
    measured along the line from that base point.  ``branch = +1`` takes the
    larger ``s`` (pin ahead along the guide direction), ``-1`` the smaller.
    """

    joint: str
    point: str
    link: int
    length: float
    slider: int
    guide_link: int
    guide_point: str
    guide_angle: float = 0.0
    offset: float = 0.0
    branch: int = 1
    name: Optional[str] = None


@dataclasses.dataclass(frozen=True)
class RPR:
    """RPR dyad (guide-bar): guide link ``guide`` pivoted at known ``pivot``
    passes through block ``block`` pivoted at the known point ``point``.

    The guide line runs at perpendicular distance ``offset`` [m] (to its left)
    from the pivot; the guide angle is the line's direction and ``s`` the
    block's position along it from the foot of the pivot.  ``branch = +1``
    takes ``s > 0`` (guide pointing from pivot towards the block).
    """

    point: str
    block: int
    pivot: str
    guide: int
    offset: float = 0.0
    branch: int = 1
    name: Optional[str] = None


@dataclasses.dataclass(frozen=True)
class PointOnLink:
    """A point fixed on link ``link``: ``origin + (along + i*normal) * exp(i*theta_link)``.

    ``along`` is measured along the link's reference direction, ``normal`` to
    its left (counter-clockwise), both [m].
    """

    name: str
    link: int
    origin: str
    along: float = 0.0
    normal: float = 0.0


Element = Union[Ground, Crank, SliderDriver, RRR, RRP, RPR, PointOnLink]


def _needs(el):
    """(points needed, links needed, points made, links made) of an element."""
    if isinstance(el, Ground):
        return (), (), (el.name,), ()
    if isinstance(el, Crank):
        return (el.pivot,), (), (el.point,), (el.link,)
    if isinstance(el, SliderDriver):
        return (el.origin,), (), (el.point,), (el.link,)
    if isinstance(el, RRR):
        return (el.point_a, el.point_b), (), (el.joint,), (el.link_a, el.link_b)
    if isinstance(el, RRP):
        return (el.point, el.guide_point), (el.guide_link,), (el.joint,), (el.link, el.slider)
    if isinstance(el, RPR):
        return (el.point, el.pivot), (), (), (el.guide, el.block)
    if isinstance(el, PointOnLink):
        return (el.origin,), (el.link,), (el.name,), ()
    raise LinkageDefinitionError(f"unknown element {el!r}")


@dataclasses.dataclass(frozen=True)
class Linkage:
    """A planar linkage: the frame's link number and the elements.

    Elements may be listed in any order; ``order`` is the solving order
    (each element after those that define its points and links).
    """

    frame: int
    elements: Tuple[Element, ...]
    order: Tuple[int, ...] = dataclasses.field(default=(), compare=False)

    def __post_init__(self):
        object.__setattr__(self, "elements", tuple(self.elements))
        points, links = set(), {self.frame}
        made_points, made_links = {}, {self.frame: -1}
        for i, el in enumerate(self.elements):
            _, _, mp, ml = _needs(el)
            for p in mp:
                if p in made_points:
                    raise LinkageDefinitionError(
                        f"point '{p}' is defined twice (elements {made_points[p]} and {i})", i)
                made_points[p] = i
            for ln in ml:
                if ln in made_links:
                    raise LinkageDefinitionError(
                        f"link {ln} is positioned twice (elements {made_links[ln]} and {i})"
                        if made_links[ln] >= 0 else f"link {ln} is the frame", i)
                made_links[ln] = i
        order, pending = [], list(range(len(self.elements)))
        while pending:
            progress = False
            for i in list(pending):
                np_, nl, mp, ml = _needs(self.elements[i])
                if all(p in points for p in np_) and all(ln in links for ln in nl):
                    points.update(mp)
                    links.update(ml)
                    order.append(i)
                    pending.remove(i)
                    progress = True
            if not progress:
                # report a root cause (a reference nothing defines) before a cycle
                for i in pending:
                    np_, nl, _, _ = _needs(self.elements[i])
                    for p in np_:
                        if p not in made_points:
                            raise LinkageDefinitionError(
                                f"point '{p}' is not defined by any ground point, driver, dyad "
                                "or point", i, ("point", p))
                    for ln in nl:
                        if ln not in made_links:
                            raise LinkageDefinitionError(
                                f"link {ln} is not the frame and is moved by no driver or dyad",
                                i, ("link", ln))
                exc = LinkageDefinitionError(
                    f"elements {sorted(pending)} depend on each other in a closed loop", pending[0])
                exc.cycle = sorted(pending)
                raise exc
        object.__setattr__(self, "order", tuple(order))

    @property
    def drivers(self):
        return tuple(el for el in self.elements if isinstance(el, (Crank, SliderDriver)))

    @property
    def moving_links(self):
        out = []
        for el in self.elements:
            for ln in _needs(el)[3]:
                if ln not in out:
                    out.append(ln)
        return tuple(out)

    @property
    def translating_links(self):
        """Links that only translate (slider blocks on frame guides, linear drivers)."""
        out = []
        for el in self.elements:
            if isinstance(el, RRP) and el.guide_link == self.frame:
                out.append(el.slider)
            elif isinstance(el, SliderDriver):
                out.append(el.link)
        return tuple(out)

    @property
    def point_names(self):
        names = []
        for el in self.elements:
            names.extend(_needs(el)[2])
        return tuple(names)

    def scale(self):
        """A characteristic length [m]: the largest length or coordinate."""
        vals = [1e-300]
        for el in self.elements:
            for f in ("length", "length_a", "length_b", "offset", "along", "normal", "x", "y"):
                if hasattr(el, f):
                    vals.append(abs(getattr(el, f)))
        return max(vals)


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class PointMotion:
    """Motion of a point: coordinates x, y [m], velocity vx, vy [m/s] and
    acceleration ax, ay [m/s^2] (``None`` where not computed).

    ``p``, ``v``, ``a`` give the same as complex numbers ``x + iy``.
    """

    x: np.ndarray
    y: np.ndarray
    vx: Optional[np.ndarray] = None
    vy: Optional[np.ndarray] = None
    ax: Optional[np.ndarray] = None
    ay: Optional[np.ndarray] = None

    @functools.cached_property
    def p(self):
        return self.x + 1j * self.y

    @functools.cached_property
    def v(self):
        return None if self.vx is None else self.vx + 1j * self.vy

    @functools.cached_property
    def a(self):
        return None if self.ax is None else self.ax + 1j * self.ay


@dataclasses.dataclass(frozen=True)
class LinkMotion:
    """Angle ``theta`` [rad], ``omega`` [rad/s], ``alpha`` [rad/s^2]."""

    theta: np.ndarray
    omega: Optional[np.ndarray] = None
    alpha: Optional[np.ndarray] = None


@dataclasses.dataclass(frozen=True)
class SlideMotion:
    """Relative slide of a prismatic pair: ``s`` [m], ``v`` [m/s], ``a`` [m/s^2].

    ``block`` slides on ``guide``; ``name`` is the output symbol suffix
    (``s3``, ``s23``, ``sE``).
    """

    name: str
    block: int
    guide: int
    s: np.ndarray
    v: Optional[np.ndarray] = None
    a: Optional[np.ndarray] = None


@dataclasses.dataclass(frozen=True)
class DyadCondition:
    """Conditioning of one dyad: ``sin_gamma`` is 0 at a toggle/dead point.

    For an RRR dyad it is |sin| of the angle between its two links at the
    joint and ``cos_joint`` that angle's cosine, so ``gamma`` is the acute
    transmission angle in [0, pi/2]; for RRP |cos| of the angle between rod
    and guide; for RPR |s| over the pivot-block distance (or the linkage
    scale, whichever is larger).
    """

    element: int
    kind: str
    joint: str
    sin_gamma: np.ndarray
    cos_joint: Optional[np.ndarray] = None

    @property
    def gamma(self):
        """Acute transmission angle [rad]."""
        if self.cos_joint is None:
            return np.arcsin(np.minimum(self.sin_gamma, 1.0))
        return np.arctan2(self.sin_gamma, np.abs(self.cos_joint))


@dataclasses.dataclass(frozen=True)
class DriverMotion:
    """Input of one driver: angle [rad] (or slide [m]) with its first two derivatives."""

    q: Union[np.ndarray, float]
    dq: Union[np.ndarray, float] = 0.0
    ddq: Union[np.ndarray, float] = 0.0


@dataclasses.dataclass(frozen=True)
class LinkageMotion:
    """Result of :func:`solve` over all input positions.

    Attributes
    ----------
    order : int
        0 positions, 1 + velocities, 2 + accelerations.
    feasible : ndarray of bool
        The linkage assembles (every dyad's discriminant >= 0).
    regular : ndarray of bool
        Feasible and no dyad's velocity system is singular (only ``order >= 1``;
        equal to ``feasible`` for ``order == 0``).
    points, links, slides, conditions : dict
        Motions by point name, link number, slide name; dyad conditioning.
        Values at positions that are not ``regular`` are meaningless (zero).
    """

    order: int
    feasible: np.ndarray
    regular: np.ndarray
    points: Dict[str, PointMotion]
    links: Dict[int, LinkMotion]
    slides: Dict[str, SlideMotion]
    conditions: Tuple[DyadCondition, ...]


# ---------------------------------------------------------------------------
# solver (contiguous real arrays: x and y components kept apart)
# ---------------------------------------------------------------------------
class _Solve2:
    """Cramer's rule for ``X*(c1x, c1y) + Y*(c2x, c2y) = (rx, ry)`` on arrays.

    Positions in ``bad`` (a mask, or None when all are regular) get 0, never
    inf or NaN.
    """

    def __init__(self, c1x, c1y, c2x, c2y, bad):
        det = c1x * c2y - c1y * c2x
        if bad is not None:
            det = np.where(bad, 1.0, det)
        self.inv = 1.0 / det
        self.c = (c1x, c1y, c2x, c2y)
        self.bad = bad

    def __call__(self, rx, ry):
        c1x, c1y, c2x, c2y = self.c
        x = (rx * c2y - ry * c2x) * self.inv
        y = (c1x * ry - c1y * rx) * self.inv
        if self.bad is not None:
            x = np.where(self.bad, 0.0, x)
            y = np.where(self.bad, 0.0, y)
        return x, y


class _Link:
    """Internal link state: angle, its cosine and sine, omega, alpha."""

    __slots__ = ("theta", "c", "s", "w", "al")

    def __init__(self, theta, c, s, w, al):
        self.theta, self.c, self.s, self.w, self.al = theta, c, s, w, al


class _Pt:
    __slots__ = ("x", "y", "vx", "vy", "ax", "ay")

    def __init__(self, x, y, vx=None, vy=None, ax=None, ay=None):
        self.x, self.y, self.vx, self.vy, self.ax, self.ay = x, y, vx, vy, ax, ay


def solve(linkage: Linkage, inputs, order: int = 2, on_fail: str = "mask") -> LinkageMotion:
    """Solve positions (and velocities, accelerations) of every point and link.

    Parameters
    ----------
    linkage : Linkage
    inputs : dict
        ``{driver link number: DriverMotion}`` for every driver; arrays of a
        common (broadcastable) shape, angles [rad], slides [m].
    order : {0, 1, 2}
        Highest derivative to compute (model only what is asked).
    on_fail : {"mask", "raise"}
        ``"mask"`` returns ``feasible``/``regular`` masks; ``"raise"`` raises
        :class:`~mechcli.core.errors.AssemblyError` if any position is not
        regular.

    Returns
    -------
    LinkageMotion
    """
    from mechcli.core.errors import AssemblyError

    if order not in (0, 1, 2):
        raise ValueError(f"order must be 0, 1 or 2, got {order}")
    for d in linkage.drivers:
        if d.link not in inputs:
            raise LinkageDefinitionError(f"no input given for driver link {d.link}")
    shape = np.broadcast(*[np.asarray(m.q) for m in inputs.values()]).shape
    zero = np.broadcast_to(0.0, shape)  # a view: costs no memory
    feasible = np.ones(shape, dtype=bool)
    regular = np.ones(shape, dtype=bool)
    vel, acc = order >= 1, order >= 2
    scale = linkage.scale()
    frame = linkage.frame

    def full(x):
        x = np.asarray(x, dtype=float)
        if x.shape == shape:
            return x
        return np.broadcast_to(x, shape) if x.ndim == 0 else x + zero

    P: Dict[str, _Pt] = {}
    L: Dict[int, _Link] = {frame: _Link(zero, 1.0, 0.0, zero, zero)}
    S: Dict[str, SlideMotion] = {}
    conds = []

    def mark(ok, sing, position_singular=False):
        """Update the masks; return the 'bad' mask for the 2x2 solves (None if none).

        ``position_singular``: the singularity leaves the position itself
        undefined (RPR: the guide's direction when the block is at its pivot),
        so it makes the position irregular even when only positions are asked.
        """
        nonlocal feasible, regular
        feasible &= ok
        if not vel:
            if position_singular is True:
                regular &= ok & (sing > SINGULAR_TOL)
            elif position_singular is not None and position_singular is not False:
                regular &= ok & ~position_singular
            return None
        good = ok & (sing > SINGULAR_TOL)
        regular &= good
        return None if good.all() else ~good

    for idx in linkage.order:
        el = linkage.elements[idx]
        if isinstance(el, Ground):
            P[el.name] = _Pt(full(el.x), full(el.y), zero, zero, zero, zero)

        elif isinstance(el, Crank):
            m = inputs[el.link]
            th, w, al = full(m.q), full(m.dq), full(m.ddq)
            c, s = np.cos(th), np.sin(th)
            o = P[el.pivot]
            rx, ry = el.length * c, el.length * s
            p = _Pt(o.x + rx, o.y + ry)
            if vel:
                p.vx, p.vy = o.vx - w * ry, o.vy + w * rx
            if acc:
                w2 = w * w
                p.ax = o.ax - al * ry - w2 * rx
                p.ay = o.ay + al * rx - w2 * ry
            P[el.point] = p
            L[el.link] = _Link(th, c, s, w, al)

        elif isinstance(el, SliderDriver):
            m = inputs[el.link]
            s = full(m.q)
            ux, uy = np.cos(el.angle), np.sin(el.angle)
            o = P[el.origin]
            p = _Pt(o.x + s * ux, o.y + s * uy)
            v = full(m.dq) if vel else None
            a = full(m.ddq) if acc else None
            if vel:
                p.vx, p.vy = o.vx + v * ux, o.vy + v * uy
            if acc:
                p.ax, p.ay = o.ax + a * ux, o.ay + a * uy
            P[el.point] = p
            L[el.link] = _Link(full(el.angle), ux, uy, zero, zero)
            name = el.name or str(el.link)
            S[name] = SlideMotion(name, el.link, frame, s, v, a)

        elif isinstance(el, RRR):
            pa, pb = P[el.point_a], P[el.point_b]
            la, lb = el.length_a, el.length_b
            dx, dy = pb.x - pa.x, pb.y - pa.y
            d2 = dx * dx + dy * dy
            dist = np.sqrt(d2)
            ok = dist > ASSEMBLY_TOL * scale
            coincide = None
            if not ok.all():
                # the known points coincide: with equal lengths (a kite's folded
                # position) the joint may be anywhere on the circle -- a dead
                # point, not a failure to assemble
                if abs(la - lb) <= ASSEMBLY_TOL * max(la, lb):
                    coincide = ~ok
                dist = np.where(ok, dist, 1.0)
            inv = 1.0 / dist
            along = (la * la - lb * lb + d2) * (0.5 * inv)
            h2 = la * la - along * along
            ok &= h2 >= -4 * ASSEMBLY_TOL * la * la
            h = np.sqrt(np.maximum(h2, 0.0)) * (el.branch * 1.0)
            ex, ey = dx * inv, dy * inv
            qx = pa.x + along * ex - h * ey
            qy = pa.y + along * ey + h * ex
            rax, ray = qx - pa.x, qy - pa.y
            rbx, rby = qx - pb.x, qy - pb.y
            nab = 1.0 / (la * lb)
            cross = rax * rby - ray * rbx
            sing = np.abs(cross) * nab
            if coincide is not None:
                ok = ok | coincide
                sing = np.where(coincide, 0.0, sing)
            conds.append(DyadCondition(idx, "RRR", el.joint, sing,
                                       (rax * rbx + ray * rby) * nab))
            bad = mark(ok, sing, position_singular=coincide)
            q = _Pt(qx, qy)
            wa = wb = aa = ab = None
            if vel:
                solve2 = _Solve2(-ray, rax, rby, -rbx, bad)
                wa, wb = solve2(pb.vx - pa.vx, pb.vy - pa.vy)
                q.vx, q.vy = pa.vx - wa * ray, pa.vy + wa * rax
                if acc:
                    wa2, wb2 = wa * wa, wb * wb
                    aa, ab = solve2(pb.ax - pa.ax + wa2 * rax - wb2 * rbx,
                                    pb.ay - pa.ay + wa2 * ray - wb2 * rby)
                    q.ax = pa.ax - aa * ray - wa2 * rax
                    q.ay = pa.ay + aa * rax - wa2 * ray
            P[el.joint] = q
            L[el.link_a] = _Link(np.arctan2(ray, rax), rax * (1 / la), ray * (1 / la), wa, aa)
            L[el.link_b] = _Link(np.arctan2(rby, rbx), rbx * (1 / lb), rby * (1 / lb), wb, ab)

        elif isinstance(el, RRP):
            pp, pg, g = P[el.point], P[el.guide_point], L[el.guide_link]
            cphi, sphi = np.cos(el.guide_angle), np.sin(el.guide_angle)
            ux, uy = g.c * cphi - g.s * sphi, g.s * cphi + g.c * sphi
            ux, uy = full(ux), full(uy)
            moving = el.guide_link != frame
            bx, by = pg.x - el.offset * uy, pg.y + el.offset * ux  # base of the slide
            wx, wy = bx - pp.x, by - pp.y
            b = wx * ux + wy * uy
            disc = b * b - (wx * wx + wy * wy - el.length ** 2)
            ok = disc >= -4 * ASSEMBLY_TOL * el.length ** 2
            s = np.sqrt(np.maximum(disc, 0.0)) * (el.branch * 1.0) - b
            qx, qy = bx + s * ux, by + s * uy
            rx, ry = qx - pp.x, qy - pp.y
            sing = np.abs(rx * ux + ry * uy) * (1.0 / el.length)
            conds.append(DyadCondition(idx, "RRP", el.joint, sing))
            bad = mark(ok, sing)
            name = el.name or (str(el.slider) if not moving else f"{el.slider}{el.guide_link}")
            q = _Pt(qx, qy)
            wr = ar = sd = sdd = None
            if vel:
                solve2 = _Solve2(-ry, rx, -ux, -uy, bad)
                rhs_x, rhs_y = pg.vx - pp.vx, pg.vy - pp.vy
                if moving:
                    gx, gy = bx - pg.x, by - pg.y
                    rhs_x = rhs_x - g.w * (gy + s * uy)
                    rhs_y = rhs_y + g.w * (gx + s * ux)
                wr, sd = solve2(rhs_x, rhs_y)
                q.vx, q.vy = pp.vx - wr * ry, pp.vy + wr * rx
                if acc:
                    wr2 = wr * wr
                    rhs_x = pg.ax - pp.ax + wr2 * rx
                    rhs_y = pg.ay - pp.ay + wr2 * ry
                    if moving:
                        w2 = g.w * g.w
                        lx, ly = gx + s * ux, gy + s * uy  # base->pin relative to the guide point
                        rhs_x = rhs_x - g.al * ly - w2 * lx - 2 * sd * g.w * uy
                        rhs_y = rhs_y + g.al * lx - w2 * ly + 2 * sd * g.w * ux
                    ar, sdd = solve2(rhs_x, rhs_y)
                    q.ax = pp.ax - ar * ry - wr2 * rx
                    q.ay = pp.ay + ar * rx - wr2 * ry
            P[el.joint] = q
            L[el.link] = _Link(np.arctan2(ry, rx), rx * (1 / el.length), ry * (1 / el.length),
                               wr, ar)
            L[el.slider] = _Link(g.theta + el.guide_angle if moving else full(el.guide_angle),
                                 ux, uy, g.w, g.al)
            S[name] = SlideMotion(name, el.slider, el.guide_link, s, sd, sdd)

        elif isinstance(el, RPR):
            pp, pc = P[el.point], P[el.pivot]
            e = el.offset
            dx, dy = pp.x - pc.x, pp.y - pc.y
            d2 = dx * dx + dy * dy
            disc = d2 - e * e
            ok = disc >= -ASSEMBLY_TOL * scale * scale
            s = np.sqrt(np.maximum(disc, 0.0)) * (el.branch * 1.0)
            # d = (s + i e) u  =>  u = d (s - i e) / |d|^2
            inv = 1.0 / np.maximum(d2, 1e-300 * scale * scale + 1e-300)
            ux, uy = (dx * s + dy * e) * inv, (dy * s - dx * e) * inv
            if e == 0.0:
                # exact unit vector even where d -> 0 (the foot of the pivot)
                ux, uy = dx * (inv * s), dy * (inv * s)
            # det of the velocity system is s: singular when the block passes the
            # foot of the pivot (the guide's direction is then undefined)
            sing = np.abs(s) / np.maximum(np.sqrt(d2), scale)
            conds.append(DyadCondition(idx, "RPR", el.point, sing))
            bad = mark(ok, sing, position_singular=e == 0.0)
            name = el.name or f"{el.block}{el.guide}"
            wg = ag = sd = sdd = None
            if vel:
                solve2 = _Solve2(ux, uy, -dy, dx, bad)
                sd, wg = solve2(pp.vx - pc.vx, pp.vy - pc.vy)
                if acc:
                    w2 = wg * wg
                    sdd, ag = solve2(pp.ax - pc.ax + 2 * sd * wg * uy + w2 * dx,
                                     pp.ay - pc.ay - 2 * sd * wg * ux + w2 * dy)
            theta = np.arctan2(uy, ux)
            L[el.guide] = _Link(theta, ux, uy, wg, ag)
            L[el.block] = L[el.guide]
            S[name] = SlideMotion(name, el.block, el.guide, s, sd, sdd)

        elif isinstance(el, PointOnLink):
            o, k = P[el.origin], L[el.link]
            rx = el.along * k.c - el.normal * k.s
            ry = el.along * k.s + el.normal * k.c
            p = _Pt(o.x + rx, o.y + ry)
            if vel:
                p.vx, p.vy = o.vx - k.w * ry, o.vy + k.w * rx
            if acc:
                w2 = k.w * k.w
                p.ax = o.ax - k.al * ry - w2 * rx
                p.ay = o.ay + k.al * rx - w2 * ry
            P[el.name] = p

    if not vel:
        regular &= feasible
    if on_fail == "raise" and not np.all(regular):
        bad = int(np.size(regular) - np.count_nonzero(regular))
        raise AssemblyError(f"the linkage cannot be assembled (or is at a dead point) at "
                            f"{bad} of {np.size(regular)} input positions")
    points = {n: PointMotion(p.x, p.y, p.vx, p.vy, p.ax, p.ay) for n, p in P.items()}
    links = {n: LinkMotion(full(k.theta), None if k.w is None or not vel else full(k.w),
                           None if k.al is None or not acc else full(k.al))
             for n, k in L.items()}
    return LinkageMotion(order, feasible, regular, points, links, S, tuple(conds))
