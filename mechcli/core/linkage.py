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
from typing import Dict, Optional, Tuple, Union

import numpy as np

#: relative size below which a dyad's 2x2 velocity system counts as singular
SINGULAR_TOL = 1e-10
#: relative tolerance for a dyad that just touches its assembly limit
ASSEMBLY_TOL = 1e-10


class LinkageDefinitionError(ValueError):
    """The elements do not form a solvable linkage (bad topology or reference).

    Attributes
    ----------
    index : int or None
        Index of the offending element in ``Linkage.elements``.
    """

    def __init__(self, message, index=None):
        super().__init__(message)
        self.index = index


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
                i = pending[0]
                np_, nl, _, _ = _needs(self.elements[i])
                missing = [f"point '{p}'" for p in np_ if p not in made_points] + \
                          [f"link {ln}" for ln in nl if ln not in made_links]
                what = ", ".join(missing) if missing else "points in a closed loop of elements"
                raise LinkageDefinitionError(f"element {i} needs {what}, which nothing defines", i)
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
    """Position ``p`` [m], velocity ``v`` [m/s], acceleration ``a`` [m/s^2] (complex)."""

    p: np.ndarray
    v: Optional[np.ndarray] = None
    a: Optional[np.ndarray] = None


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
    """Conditioning of one dyad: ``sin_gamma`` = |sin| of the angle between the
    two columns of its 2x2 velocity system (0 at a toggle/dead point).

    For an RRR dyad this is |sin| of the angle between its two links at the
    joint, i.e. the sine of the transmission angle; ``gamma`` [rad] is that
    acute transmission angle in [0, pi/2].
    """

    element: int
    kind: str
    joint: str
    sin_gamma: np.ndarray
    gamma: Optional[np.ndarray] = None


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
# solver
# ---------------------------------------------------------------------------
def _cross(a, b):
    """z-component of a x b for complex-encoded 2-vectors."""
    return a.real * b.imag - a.imag * b.real


def _solve2(c1, c2, rhs, det, ok):
    """Solve ``X*c1 + Y*c2 = rhs`` (complex-encoded 2x2, real X, Y) by Cramer's rule."""
    safe = np.where(ok, det, 1.0)
    x = _cross(rhs, c2) / safe
    y = _cross(c1, rhs) / safe
    return np.where(ok, x, 0.0), np.where(ok, y, 0.0)


def _unit(theta):
    return np.cos(theta) + 1j * np.sin(theta)


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
    zeros = np.zeros(shape)
    feasible = np.ones(shape, dtype=bool)
    regular = np.ones(shape, dtype=bool)
    vel, acc = order >= 1, order >= 2
    scale = linkage.scale()

    P: Dict[str, PointMotion] = {}
    L: Dict[int, LinkMotion] = {linkage.frame: LinkMotion(zeros, zeros, zeros)}
    S: Dict[str, SlideMotion] = {}
    conds = []

    def point_state(name):
        pm = P[name]
        return pm.p, pm.v, pm.a

    def put_link(num, theta, omega=None, alpha=None):
        L[num] = LinkMotion(theta, omega if vel else None, alpha if acc else None)

    def put_point(name, p, v=None, a=None):
        P[name] = PointMotion(p + zeros, (v + zeros) if vel and v is not None else None,
                              (a + zeros) if acc and a is not None else None)

    for idx in linkage.order:
        el = linkage.elements[idx]
        if isinstance(el, Ground):
            c = complex(el.x, el.y)
            put_point(el.name, np.full(shape, c), 0j, 0j)

        elif isinstance(el, Crank):
            m = inputs[el.link]
            th = np.asarray(m.q, dtype=float) + zeros
            w = np.asarray(m.dq, dtype=float) + zeros
            al = np.asarray(m.ddq, dtype=float) + zeros
            p0, v0, a0 = point_state(el.pivot)
            r = el.length * _unit(th)
            put_point(el.point, p0 + r, (v0 + 1j * w * r) if vel else None,
                      (a0 + (1j * al - w * w) * r) if acc else None)
            put_link(el.link, th, w, al)

        elif isinstance(el, SliderDriver):
            m = inputs[el.link]
            s = np.asarray(m.q, dtype=float) + zeros
            u = complex(np.cos(el.angle), np.sin(el.angle))
            p0, v0, a0 = point_state(el.origin)
            put_point(el.point, p0 + s * u, (v0 + np.asarray(m.dq) * u) if vel else None,
                      (a0 + np.asarray(m.ddq) * u) if acc else None)
            put_link(el.link, zeros + el.angle, zeros, zeros)
            name = el.name or str(el.link)
            S[name] = SlideMotion(name, el.link, linkage.frame, s,
                                  (np.asarray(m.dq, dtype=float) + zeros) if vel else None,
                                  (np.asarray(m.ddq, dtype=float) + zeros) if acc else None)

        elif isinstance(el, RRR):
            pa, va, aa = point_state(el.point_a)
            pb, vb, ab = point_state(el.point_b)
            d = pb - pa
            dist2 = d.real ** 2 + d.imag ** 2
            dist = np.sqrt(dist2)
            ok_d = dist > ASSEMBLY_TOL * scale
            sd = np.where(ok_d, dist, 1.0)
            along = (el.length_a ** 2 - el.length_b ** 2 + dist2) / (2 * sd)
            h2 = el.length_a ** 2 - along ** 2
            tol = ASSEMBLY_TOL * el.length_a ** 2 * 4
            ok = ok_d & (h2 >= -tol)
            h = np.sqrt(np.where(ok, np.maximum(h2, 0.0), 0.0))
            q = pa + (along + 1j * el.branch * h) * d / sd
            feasible &= ok
            ra, rb = q - pa, q - pb
            # sin of the angle between the links at the joint
            na = np.abs(ra)
            nb = np.abs(rb)
            cr = _cross(ra, rb)
            sing = np.abs(cr) / np.maximum(na * nb, 1e-300)
            cosj = (ra.real * rb.real + ra.imag * rb.imag) / np.maximum(na * nb, 1e-300)
            gamma = np.arctan2(sing, np.abs(cosj))
            conds.append(DyadCondition(idx, "RRR", el.joint, sing, gamma))
            tha, thb = np.angle(ra), np.angle(rb)
            if vel:
                reg = ok & (sing > SINGULAR_TOL)
                regular &= reg
                c1, c2 = 1j * ra, -1j * rb
                det = _cross(c1, c2)
                wa, wb = _solve2(c1, c2, vb - va, det, reg)
                vq = va + 1j * wa * ra
                if acc:
                    rhs = ab - aa + wa * wa * ra - wb * wb * rb
                    aa_, ab_ = _solve2(c1, c2, rhs, det, reg)
                    aq = aa + (1j * aa_ - wa * wa) * ra
                else:
                    aa_ = ab_ = aq = None
            else:
                wa = wb = aa_ = ab_ = vq = aq = None
            put_point(el.joint, q, vq, aq)
            put_link(el.link_a, tha, wa, aa_)
            put_link(el.link_b, thb, wb, ab_)

        elif isinstance(el, RRP):
            pp, vp, ap = point_state(el.point)
            pg, vg, ag = point_state(el.guide_point)
            g = L[el.guide_link]
            u = _unit(g.theta + el.guide_angle)
            n = 1j * u
            base = pg + el.offset * n
            w = base - pp
            b = w.real * u.real + w.imag * u.imag
            c = w.real ** 2 + w.imag ** 2 - el.length ** 2
            disc = b * b - c
            tol = ASSEMBLY_TOL * el.length ** 2 * 4
            ok = disc >= -tol
            feasible &= ok
            s = -b + el.branch * np.sqrt(np.where(ok, np.maximum(disc, 0.0), 0.0))
            q = base + s * u
            r = q - pp
            nr = np.maximum(np.abs(r), 1e-300)
            sing = np.abs(r.real * u.real + r.imag * u.imag) / nr
            conds.append(DyadCondition(idx, "RRP", el.joint, sing, np.arcsin(np.minimum(sing, 1.0))))
            name = el.name or (str(el.slider) if el.guide_link == linkage.frame
                               else f"{el.slider}{el.guide_link}")
            put_link(el.slider, g.theta + el.guide_angle, g.omega, g.alpha)
            if vel:
                reg = ok & (sing > SINGULAR_TOL)
                regular &= reg
                wg = g.omega
                vbase = vg + 1j * wg * (base - pg)
                c1, c2 = 1j * r, -u
                det = _cross(c1, c2)
                rhs = vbase + 1j * wg * s * u - vp
                wr, sd = _solve2(c1, c2, rhs, det, reg)
                vq = vp + 1j * wr * r
                if acc:
                    ab_ = ag + (1j * g.alpha - wg * wg) * (base - pg)
                    rhs = (ab_ + 2j * sd * wg * u + s * (1j * g.alpha - wg * wg) * u
                           - ap + wr * wr * r)
                    ar, sdd = _solve2(c1, c2, rhs, det, reg)
                    aq = ap + (1j * ar - wr * wr) * r
                else:
                    ar = sdd = aq = None
            else:
                wr = ar = sd = sdd = vq = aq = None
            put_point(el.joint, q, vq, aq)
            put_link(el.link, np.angle(r), wr, ar)
            S[name] = SlideMotion(name, el.slider, el.guide_link, s, sd, sdd)

        elif isinstance(el, RPR):
            pp, vp, ap = point_state(el.point)
            pc, vc, ac = point_state(el.pivot)
            d = pp - pc
            dist2 = d.real ** 2 + d.imag ** 2
            disc = dist2 - el.offset ** 2
            tol = ASSEMBLY_TOL * scale ** 2
            ok = disc >= -tol
            feasible &= ok
            s = el.branch * np.sqrt(np.where(ok, np.maximum(disc, 0.0), 0.0))
            # d = (s + i*offset) * u  =>  u = d / (s + i*offset)
            local = s + 1j * el.offset
            theta = np.angle(d) - np.angle(local)
            u = _unit(theta)
            # det of the velocity system is s: singular when the block passes the
            # foot of the pivot (the guide's direction is then undefined)
            sing = np.abs(s) / np.maximum(np.sqrt(dist2), scale)
            conds.append(DyadCondition(idx, "RPR", el.point, sing, np.arcsin(np.minimum(sing, 1.0))))
            name = el.name or f"{el.block}{el.guide}"
            if vel:
                reg = ok & (sing > SINGULAR_TOL)
                regular &= reg
                c1, c2 = u, 1j * d
                det = _cross(c1, c2)
                sd, wg = _solve2(c1, c2, vp - vc, det, reg)
                if acc:
                    rhs = ap - ac - 2j * sd * wg * u + wg * wg * d
                    sdd, ag = _solve2(c1, c2, rhs, det, reg)
                else:
                    sdd = ag = None
            else:
                sd = wg = sdd = ag = None
            put_link(el.guide, theta, wg, ag)
            put_link(el.block, theta, wg, ag)
            S[name] = SlideMotion(name, el.block, el.guide, s, sd, sdd)

        elif isinstance(el, PointOnLink):
            po, vo, ao = point_state(el.origin)
            k = L[el.link]
            r = complex(el.along, el.normal) * _unit(k.theta)
            put_point(el.name, po + r,
                      (vo + 1j * k.omega * r) if vel else None,
                      (ao + (1j * k.alpha - k.omega * k.omega) * r) if acc else None)

    if not vel:
        regular = feasible.copy()
    if on_fail == "raise" and not np.all(regular):
        bad = int(np.size(regular) - np.count_nonzero(regular))
        raise AssemblyError(f"the linkage cannot be assembled (or is at a dead point) at "
                            f"{bad} of {np.size(regular)} input positions")
    return LinkageMotion(order, feasible, regular if vel else feasible, P, L, S, tuple(conds))
