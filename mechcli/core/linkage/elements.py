"""The elements of a linkage: each one class that owns everything about it.

A planar linkage is a frame, one or more drivers and a sequence of class-II
Assur groups (dyads) solved in order (杆组法).  Every element class here owns

* what it needs and what it makes (:meth:`Element.needs`, :meth:`Element.makes`),
* its position / velocity / acceleration step (:meth:`Element.step`),
* its kinematic pairs for kinetostatics (:meth:`Element.pairs`),
* the names of the slides it reports (:meth:`Element.slide_names`) and which of
  its links are reported as rotating (:meth:`Element.reported_links`),
* how it is drawn (:meth:`Element.sketch`, plain data: the report layer turns
  :class:`Bar`, :class:`Block`, :class:`Guide` and :class:`Pivot` into
  pictures).

Adding a dyad type (PRP, RPP, ...) is one new class here plus its tests; the
engine, the sweep analysis, kinetostatics, the mobility count and the drawings
use only these methods.

Points are complex numbers ``x + iy`` kept as separate real arrays [m];
velocities [m/s] and accelerations [m/s^2] likewise; angles are
counter-clockwise from +x [rad].  Every length, offset, coordinate and angle of
an element may be an array that broadcasts against the input positions: one
solve then covers many candidate linkages (designs) at once.

Notes
-----
This generalises the closed-vector-loop method of chapter 1 of the book
(eq. 1-1 ... 1-36): the four-bar of 例 1-1 is ``Crank`` + ``RRR``; the
slider-crank of 例 1-2 is ``Crank`` + ``RRP``; the guide-bar of 例 1-3 is
``Crank`` + ``RPR``; the shaper of 例 1-4 is ``Crank`` + ``RPR`` +
``PointOnLink`` + ``RRP``.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar, Optional, Tuple

import numpy as np

#: relative size below which a dyad counts as singular (a dead point).  The
#: closed-form positions carry a sqrt of a rounded discriminant, so sin(gamma)
#: at an exact toggle comes out as large as ~sqrt(eps) ~ 1.5e-8: anything below
#: 1e-7 is numerically indistinguishable from the toggle itself.
SINGULAR_TOL = 1e-7
#: relative tolerance for a dyad that just touches its assembly limit
ASSEMBLY_TOL = 1e-10


# ---------------------------------------------------------------------------
# drawing primitives (data only; report/kin_plots.py draws them)
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Bar:
    """A bar drawn between two points."""

    a: str
    b: str


@dataclasses.dataclass(frozen=True)
class Block:
    """A slider block at ``point``, turned with link ``link`` (``None``: not turned)."""

    point: str
    link: Optional[int] = None


@dataclasses.dataclass(frozen=True)
class Guide:
    """A guide line carried by link ``link``.

    It passes through ``point`` shifted by ``offset`` [m] to the left of its
    direction, which is ``angle`` [rad] relative to the link.  ``ray``: drawn
    from that point along ``branch`` times the direction (a guide bar pivoted
    at ``point``); otherwise a line spanning the range of slide ``slide``.
    """

    link: int
    point: str
    angle: float
    offset: float
    slide: str
    ray: bool = False
    branch: int = 1


@dataclasses.dataclass(frozen=True)
class Pivot:
    """A point fixed on the frame, drawn as a ground symbol."""

    name: str


# ---------------------------------------------------------------------------
# solver state and helpers
# ---------------------------------------------------------------------------
class Solve2:
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


class LinkState:
    """A solved link: angle, its cosine and sine, omega, alpha."""

    __slots__ = ("theta", "c", "s", "w", "al")

    def __init__(self, theta, c, s, w, al):
        self.theta, self.c, self.s, self.w, self.al = theta, c, s, w, al


class PointState:
    """A solved point: x, y and (where computed) vx, vy, ax, ay."""

    __slots__ = ("x", "y", "vx", "vy", "ax", "ay")

    def __init__(self, x, y, vx=None, vy=None, ax=None, ay=None):
        self.x, self.y, self.vx, self.vy, self.ax, self.ay = x, y, vx, vy, ax, ay


def rotate_about(o: PointState, link: LinkState, rx, ry, vel, acc, st=None) -> PointState:
    """The point ``o + (rx, ry)`` fixed on ``link``, with its velocity and acceleration.

    With ``st`` (the solve state) the results are written into its preallocated
    output rows (``st.out()``) with no temporaries of the full shape.
    """
    if st is None:
        p = PointState(o.x + rx, o.y + ry)
        if vel:
            p.vx, p.vy = o.vx - link.w * ry, o.vy + link.w * rx
        if acc:
            w2 = link.w * link.w
            p.ax = o.ax - link.al * ry - w2 * rx
            p.ay = o.ay + link.al * rx - w2 * ry
        return p
    out = st.out
    p = PointState(np.add(o.x, rx, out=out()), np.add(o.y, ry, out=out()))
    if vel:
        w = link.w
        p.vx = np.multiply(w, ry, out=out())
        np.subtract(o.vx, p.vx, out=p.vx)
        p.vy = np.multiply(w, rx, out=out())
        np.add(o.vy, p.vy, out=p.vy)
    if acc:
        w2, al, t = link.w * link.w, link.al, st.tmp(5)
        p.ax = np.multiply(al, ry, out=out())
        np.subtract(o.ax, p.ax, out=p.ax)
        p.ax -= np.multiply(w2, rx, out=t)
        p.ay = np.multiply(al, rx, out=out())
        np.add(o.ay, p.ay, out=p.ay)
        p.ay -= np.multiply(w2, ry, out=t)
    return p


class _GuideLine:
    """A guide line carried by link ``link`` (solved), as a dyad sees it.

    The line passes through the known point ``point`` of that link, shifted
    by ``offset`` [m] along its left normal, in direction ``angle`` [rad]
    relative to the link: unit direction ``(ux, uy)``, base ``(bx, by)``.
    A block on it at slide ``s`` is at ``base + s * u``.
    """

    def __init__(self, st, link, point, angle, offset):
        self.p, self.g = st.P[point], st.L[link]
        self.moving = link != st.frame
        g, c, s = self.g, np.cos(angle), np.sin(angle)
        self.ux, self.uy = st.full(g.c * c - g.s * s), st.full(g.s * c + g.c * s)
        self.bx, self.by = self.p.x - offset * self.uy, self.p.y + offset * self.ux
        self.theta = st.full(g.theta + angle)

    def carried_velocity(self, rx, ry):
        """Velocity [m/s] of the guide link's point at ``point + (rx, ry)``."""
        p, w = self.p, self.g.w
        if not self.moving:
            return p.vx, p.vy
        return p.vx - w * ry, p.vy + w * rx

    def carried_acceleration(self, rx, ry, sd):
        """Acceleration [m/s^2] of the guide link's point at ``point + (rx, ry)``
        plus the Coriolis term ``2 omega x (sd u)`` of a block sliding at ``sd`` [m/s]."""
        p, g = self.p, self.g
        if not self.moving:
            return p.ax, p.ay
        w2, cor = g.w * g.w, 2 * sd * g.w
        return (p.ax - g.al * ry - w2 * rx - cor * self.uy,
                p.ay + g.al * rx - w2 * ry + cor * self.ux)

    def block(self):
        """State of a block sliding on this line: turned with the guide link."""
        return LinkState(self.theta, self.ux, self.uy, self.g.w, self.g.al)


def _nonpositive(*lengths):
    """Mask of the designs where any of ``lengths`` is <= 0 (None when none is:
    the common case costs one comparison per parameter and changes nothing)."""
    void = None
    for v in lengths:
        if np.any(np.less_equal(v, 0.0)):
            m = np.less_equal(v, 0.0)
            void = m if void is None else void | m
    return void


def _slide_symbol(name, block, guide, frame):
    """Slide symbol suffix: ``name`` if given, else ``<block>`` on a frame
    guide, ``<block><guide>`` on a moving one (RRP's rule)."""
    if name:
        return name
    return str(block) if guide == frame else f"{block}{guide}"


class Element:
    """Base of every element.  Subclasses are frozen dataclasses.

    Class attributes
    ----------------
    kind : str
        Short name (``"crank"``, ``"RRR"`` ...).
    is_driver : bool
        A driver takes an input motion (``inputs[link]``).
    rotary : bool
        For a driver: its input is an angle (else a slide).
    lengths_ : tuple of str
        Fields that are lengths or coordinates [m] (the linkage's scale).
    angles_ : tuple of str
        Fields that are angles [rad].
    """

    kind: ClassVar[str] = ""
    is_driver: ClassVar[bool] = False
    rotary: ClassVar[bool] = False
    lengths_: ClassVar[Tuple[str, ...]] = ()
    angles_: ClassVar[Tuple[str, ...]] = ()

    def __post_init__(self):
        # numeric parameters given as lists/tuples become arrays (a batch of
        # designs); a branch must be +1 or -1 (0 or 2 would solve silently wrong)
        for f in self.lengths_ + self.angles_ + ("branch",):
            v = getattr(self, f, None)
            if isinstance(v, (list, tuple)):
                v = np.asarray(v, dtype=float)
                object.__setattr__(self, f, v)
        if hasattr(self, "branch"):
            b = np.asarray(self.branch)
            if b.dtype.kind not in "biuf" or not np.all(np.abs(b) == 1):
                raise ValueError(f"{self.kind} dyad: branch must be +1 or -1 (or an array of "
                                 f"them), got {self.branch!r}")

    def needs(self):
        """(points, links) that must be known before this element is solved."""
        raise NotImplementedError

    def makes(self):
        """(points, links) this element positions."""
        raise NotImplementedError

    def parameters(self):
        """Every numeric parameter (lengths, coordinates, angles, branch)."""
        return tuple(getattr(self, f) for f in self.lengths_ + self.angles_ + ("branch",)
                     if hasattr(self, f))

    def sizes(self):
        """Absolute values of the length-like parameters [m]."""
        return tuple(np.abs(getattr(self, f)) for f in self.lengths_)

    def slide_names(self, frame) -> Tuple[str, ...]:
        """Symbol suffixes of the slides this element reports (``s3``, ``s23``, ``sE``)."""
        return ()

    def translating_links(self, frame):
        """Links made here that only translate (their angle never changes)."""
        return ()

    def reported_links(self, frame):
        """Links made here whose angle, omega and alpha are reported."""
        return ()

    def transmission_joint(self) -> Optional[str]:
        """Joint whose transmission angle is reported (RRR dyads)."""
        return None

    def step(self, st):
        """Solve this element on the state ``st`` (see ``engine.solve``)."""
        raise NotImplementedError

    def _out_rows(self, vel, acc):
        """How many output arrays of the full shape ``step`` takes from ``st.out()``
        (the engine preallocates them in one block)."""
        return 0

    def pairs(self, tb):
        """Declare the element's points and kinematic pairs on a topology builder."""
        raise NotImplementedError

    def sketch(self, frame):
        """Drawing primitives: a tuple of Bar, Block, Guide, Pivot (``frame``: the
        frame's link number, for the slide names)."""
        return ()


# ---------------------------------------------------------------------------
# elements
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Ground(Element):
    """A point fixed on the frame at (x, y) [m]."""

    name: str
    x: float
    y: float

    kind: ClassVar[str] = "ground"
    lengths_: ClassVar[Tuple[str, ...]] = ("x", "y")

    def needs(self):
        return (), ()

    def makes(self):
        return (self.name,), ()

    def step(self, st):
        # kept at the parameters' own shape: broadcast to the full shape only in
        # the results (a batch of designs need not repeat x, y at every position)
        st.P[self.name] = PointState(np.asarray(self.x, dtype=float),
                                     np.asarray(self.y, dtype=float), st.zero, st.zero,
                                     st.zero, st.zero)

    def pairs(self, tb):
        tb.new_point(self.name, tb.frame)

    def sketch(self, frame):
        return (Pivot(self.name),)


@dataclasses.dataclass(frozen=True)
class Crank(Element):
    """Rotary driver: link ``link`` turns about the known point ``pivot``.

    ``point = pivot + length * exp(i*theta)``, where ``theta`` is the driver's
    input angle (the link's absolute angle) [rad]; ``length`` [m].
    """

    link: int
    pivot: str
    point: str
    length: float

    kind: ClassVar[str] = "crank"
    is_driver: ClassVar[bool] = True
    rotary: ClassVar[bool] = True
    lengths_: ClassVar[Tuple[str, ...]] = ("length",)

    def needs(self):
        return (self.pivot,), ()

    def makes(self):
        return (self.point,), (self.link,)

    def step(self, st):
        m = st.inputs[self.link]
        # the angle at its own shape (cos and sin once per input, not per design);
        # omega and alpha stay scalars when given as scalars (no full-shape copies)
        th = np.asarray(m.q, dtype=float)
        w, al = np.asarray(m.dq, dtype=float), np.asarray(m.ddq, dtype=float)
        if np.shape(th) != st.shape or self.link in st.needed_links:
            c, s = np.cos(th), np.sin(th)
            rx, ry = self.length * c, self.length * s
        else:  # cos and sin only as scratch: scaled in place into the arm
            rx, ry = np.cos(th, out=st.tmp(0)), np.sin(th, out=st.tmp(1))
            rx *= self.length
            ry *= self.length
            c = s = None
        link = LinkState(th, c, s, w if w.ndim == 0 else st.full(w),
                         al if al.ndim == 0 else st.full(al))
        st.P[self.point] = rotate_about(st.P[self.pivot], link, rx, ry, st.vel, st.acc, st)
        st.L[self.link] = link

    def _out_rows(self, vel, acc):
        return 2 + 2 * vel + 2 * acc

    def pairs(self, tb):
        tb.revolute(self.pivot, self.link)
        tb.new_point(self.point, self.link)
        tb.frames[self.link] = [self.pivot, self.point]
        return (self.link,)

    def sketch(self, frame):
        return (Bar(self.pivot, self.point),)


@dataclasses.dataclass(frozen=True)
class SliderDriver(Element):
    """Linear driver: link ``link`` translates along a line fixed on the frame.

    ``point = origin + s * exp(i*angle)``; ``s`` is the driver's input [m].
    """

    link: int
    origin: str
    point: str
    angle: float = 0.0
    name: Optional[str] = None

    kind: ClassVar[str] = "slider"
    is_driver: ClassVar[bool] = True
    angles_: ClassVar[Tuple[str, ...]] = ("angle",)

    def needs(self):
        return (self.origin,), ()

    def makes(self):
        return (self.point,), (self.link,)

    def slide_names(self, frame):
        return (self.name or str(self.link),)

    def translating_links(self, frame):
        return (self.link,)

    def step(self, st):
        m = st.inputs[self.link]
        s = st.full(m.q)
        ux, uy = np.cos(self.angle), np.sin(self.angle)
        o = st.P[self.origin]
        p = PointState(o.x + s * ux, o.y + s * uy)
        v = st.full(m.dq) if st.vel else None
        a = st.full(m.ddq) if st.acc else None
        if st.vel:
            p.vx, p.vy = o.vx + v * ux, o.vy + v * uy
        if st.acc:
            p.ax, p.ay = o.ax + a * ux, o.ay + a * uy
        st.P[self.point] = p
        st.L[self.link] = LinkState(st.full(self.angle), ux, uy, st.zero, st.zero)
        st.slide(self.slide_names(st.frame)[0], self.link, st.frame, s, v, a)

    def pairs(self, tb):
        if tb.owner.get(self.origin) != tb.frame:
            tb.fail(f"the slider driver of link {self.link} needs its origin '{self.origin}' "
                    "on the frame", ("link", self.link))
        tb.new_point(self.point, self.link)
        tb.prismatic(tb.frame, self.link, self.point)
        tb.frames[self.link] = [self.point, None]
        return (self.link,)

    def sketch(self, frame):
        return (Block(self.point, None),)


def _rrr_solve(rx, ry, rax, ray, rbx, rby, icross, a, b, bad):
    """The RRR dyad's 2x2 system for the rates of its links (velocities, or
    accelerations with the centripetal terms moved into ``rx, ry``), by Cramer's
    rule into ``a`` and ``b`` (``ry`` is used as scratch); 0 where ``bad``."""
    np.multiply(rx, rbx, out=a)
    a += np.multiply(ry, rby, out=b)
    a *= icross
    np.multiply(rax, rx, out=b)
    b += np.multiply(ray, ry, out=ry)
    b *= icross
    if bad is not None:
        np.copyto(a, 0.0, where=bad)
        np.copyto(b, 0.0, where=bad)
    return a, b


@dataclasses.dataclass(frozen=True)
class RRR(Element):
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

    kind: ClassVar[str] = "RRR"
    lengths_: ClassVar[Tuple[str, ...]] = ("length_a", "length_b")

    def needs(self):
        return (self.point_a, self.point_b), ()

    def makes(self):
        return (self.joint,), (self.link_a, self.link_b)

    def reported_links(self, frame):
        return (self.link_a, self.link_b)

    def transmission_joint(self):
        return self.joint

    def step(self, st):
        # written for few passes over memory: every array of the full shape is an
        # output row (st.out) or one of six scratch buffers (st.tmp) reused in place
        pa, pb = st.P[self.point_a], st.P[self.point_b]
        la, lb = self.length_a, self.length_b
        # a link of zero (or negative) length cannot assemble (its angle is
        # undefined): such designs of a batch are infeasible, never inf/NaN
        void = _nonpositive(la, lb)
        if void is not None:
            la, lb = np.where(void, 1.0, la), np.where(void, 1.0, lb)
        out, tmp = st.out, st.tmp
        qx, qy = out(), out()
        dx = np.subtract(pb.x, pa.x, out=tmp(0))
        dy = np.subtract(pb.y, pa.y, out=tmp(1))
        d2 = np.multiply(dx, dx, out=tmp(2))
        d2 += np.multiply(dy, dy, out=qx)
        dist = np.sqrt(d2, out=tmp(3))
        ok = dist > ASSEMBLY_TOL * st.scale
        coincide = None
        if not ok.all():
            # the known points coincide: with equal lengths (a kite's folded
            # position) the joint may be anywhere on the circle -- a dead
            # point, not a failure to assemble
            kite = np.abs(la - lb) <= ASSEMBLY_TOL * np.maximum(la, lb)
            if np.any(kite):
                coincide = ~ok & kite
            np.copyto(dist, 1.0, where=~ok)
        inv = np.divide(1.0, dist, out=dist)
        la2 = la * la
        along = d2
        along += la2 - lb * lb
        along *= inv
        along *= 0.5
        h = np.multiply(along, along, out=tmp(4))
        np.subtract(la2, h, out=h)
        ok &= h >= -4 * ASSEMBLY_TOL * la2
        np.maximum(h, 0.0, out=h)
        np.sqrt(h, out=h)
        if np.any(np.not_equal(self.branch, 1)):
            h *= self.branch
        along *= inv  # (along, h) / dist: the joint from pa in units of (dx, dy)
        h *= inv
        # ra = along * e + h * (i e), e = (dx, dy) / dist
        rax = np.multiply(along, dx, out=inv)
        rax -= np.multiply(h, dy, out=qx)
        ray = np.multiply(along, dy, out=along)
        ray += np.multiply(h, dx, out=qy)
        np.add(pa.x, rax, out=qx)
        np.add(pa.y, ray, out=qy)
        rbx = np.subtract(rax, dx, out=dx)
        rby = np.subtract(ray, dy, out=dy)
        nab = 1.0 / (la * lb)
        sing, cosj = out(), out()
        cross = np.multiply(rax, rby, out=h)
        cross -= np.multiply(ray, rbx, out=sing)
        np.abs(cross, out=sing)
        sing *= nab
        np.multiply(rax, rbx, out=cosj)
        cosj += np.multiply(ray, rby, out=tmp(5))
        cosj *= nab
        if coincide is not None:
            ok = ok | coincide
            np.copyto(sing, 0.0, where=coincide)
        if void is not None:
            ok = ok & ~void
        st.condition(self, self.joint, sing, cosj)
        bad = st.mark(ok, sing, coincide)
        q = PointState(qx, qy)
        wa = wb = aa = ab = None
        if st.vel:
            # the velocity system wa (i ra) - wb (i rb) = vb - va by Cramer's rule:
            # its determinant is -cross; kept as 1 / cross
            if bad is not None:
                np.copyto(cross, 1.0, where=bad)
            icross = np.divide(1.0, cross, out=cross)
            rx = np.subtract(pb.vx, pa.vx, out=out())
            ry = np.subtract(pb.vy, pa.vy, out=out())
            wa, wb = _rrr_solve(rx, ry, rax, ray, rbx, rby, icross, out(), out(), bad)
            q.vx = np.multiply(wa, ray, out=rx)
            np.subtract(pa.vx, q.vx, out=q.vx)
            q.vy = np.multiply(wa, rax, out=ry)
            np.add(pa.vy, q.vy, out=q.vy)
            if st.acc:
                wa2 = np.multiply(wa, wa, out=tmp(5))
                aa, ab = out(), out()
                wb2 = np.multiply(wb, wb, out=ab)
                rx = np.subtract(pb.ax, pa.ax, out=out())
                rx += np.multiply(wa2, rax, out=aa)
                rx -= np.multiply(wb2, rbx, out=aa)
                ry = np.subtract(pb.ay, pa.ay, out=out())
                ry += np.multiply(wa2, ray, out=aa)
                ry -= np.multiply(wb2, rby, out=aa)
                _rrr_solve(rx, ry, rax, ray, rbx, rby, icross, aa, ab, bad)
                q.ax = np.multiply(aa, ray, out=rx)
                np.subtract(pa.ax, q.ax, out=q.ax)
                q.ax -= np.multiply(wa2, rax, out=ry)
                q.ay = np.multiply(aa, rax, out=ry)
                np.add(pa.ay, q.ay, out=q.ay)
                q.ay -= np.multiply(wa2, ray, out=wa2)
        st.P[self.joint] = q
        needed = st.needed_links
        st.L[self.link_a] = LinkState(np.arctan2(ray, rax, out=out()),
                                      rax * (1 / la) if self.link_a in needed else None,
                                      ray * (1 / la) if self.link_a in needed else None, wa, aa)
        st.L[self.link_b] = LinkState(np.arctan2(rby, rbx, out=out()),
                                      rbx * (1 / lb) if self.link_b in needed else None,
                                      rby * (1 / lb) if self.link_b in needed else None, wb, ab)

    def _out_rows(self, vel, acc):
        return 6 + 4 * vel + 4 * acc

    def pairs(self, tb):
        tb.revolute(self.point_a, self.link_a)
        tb.new_point(self.joint, self.link_a)
        tb.joint(self.joint, self.link_a, self.link_b)
        tb.revolute(self.point_b, self.link_b)
        tb.frames[self.link_a] = [self.point_a, self.joint]
        tb.frames[self.link_b] = [self.point_b, self.joint]
        return (self.link_a, self.link_b)

    def sketch(self, frame):
        return (Bar(self.point_a, self.joint), Bar(self.point_b, self.joint))


@dataclasses.dataclass(frozen=True)
class RRP(Element):
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

    kind: ClassVar[str] = "RRP"
    lengths_: ClassVar[Tuple[str, ...]] = ("length", "offset")
    angles_: ClassVar[Tuple[str, ...]] = ("guide_angle",)

    def needs(self):
        return (self.point, self.guide_point), (self.guide_link,)

    def makes(self):
        return (self.joint,), (self.link, self.slider)

    def slide_names(self, frame):
        return (_slide_symbol(self.name, self.slider, self.guide_link, frame),)

    def translating_links(self, frame):
        return (self.slider,) if self.guide_link == frame else ()

    def reported_links(self, frame):
        return (self.link,) if self.guide_link == frame else (self.link, self.slider)

    def step(self, st):
        pp, pg, g = st.P[self.point], st.P[self.guide_point], st.L[self.guide_link]
        cphi, sphi = np.cos(self.guide_angle), np.sin(self.guide_angle)
        ux, uy = st.full(g.c * cphi - g.s * sphi), st.full(g.s * cphi + g.c * sphi)
        moving = self.guide_link != st.frame
        e = self.offset
        bx, by = pg.x - e * uy, pg.y + e * ux  # base of the slide
        wx, wy = bx - pp.x, by - pp.y
        b = wx * ux + wy * uy
        length = self.length
        void = _nonpositive(length)  # a rod of zero length: infeasible (see RRR)
        if void is not None:
            length = np.where(void, 1.0, length)
        length2 = length * length
        disc = b * b - (wx * wx + wy * wy - length2)
        ok = disc >= -4 * ASSEMBLY_TOL * length2
        if void is not None:
            ok = ok & ~void
        s = np.sqrt(np.maximum(disc, 0.0)) * (self.branch * 1.0) - b
        qx, qy = bx + s * ux, by + s * uy
        rx, ry = qx - pp.x, qy - pp.y
        sing = np.abs(rx * ux + ry * uy) * (1.0 / length)
        st.condition(self, self.joint, sing)
        bad = st.mark(ok, sing)
        q = PointState(qx, qy)
        wr = ar = sd = sdd = None
        if st.vel:
            solve2 = Solve2(-ry, rx, -ux, -uy, bad)
            rhs_x, rhs_y = pg.vx - pp.vx, pg.vy - pp.vy
            if moving:
                gx, gy = bx - pg.x, by - pg.y
                rhs_x = rhs_x - g.w * (gy + s * uy)
                rhs_y = rhs_y + g.w * (gx + s * ux)
            wr, sd = solve2(rhs_x, rhs_y)
            q.vx, q.vy = pp.vx - wr * ry, pp.vy + wr * rx
            if st.acc:
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
        st.P[self.joint] = q
        st.L[self.link] = LinkState(np.arctan2(ry, rx), rx * (1 / length),
                                    ry * (1 / length), wr, ar)
        st.L[self.slider] = LinkState(g.theta + self.guide_angle if moving
                                      else st.full(self.guide_angle), ux, uy, g.w, g.al)
        st.slide(self.slide_names(st.frame)[0], self.slider, self.guide_link, s, sd, sdd)

    def pairs(self, tb):
        tb.revolute(self.point, self.link)
        tb.new_point(self.joint, self.link)
        tb.joint(self.joint, self.link, self.slider)
        tb.prismatic(self.guide_link, self.slider, self.joint)
        tb.frames[self.link] = [self.point, self.joint]
        tb.frames[self.slider] = [self.joint, None]
        return (self.link, self.slider)

    def sketch(self, frame):
        return (Bar(self.point, self.joint), Block(self.joint, self.slider),
                Guide(self.guide_link, self.guide_point, self.guide_angle, self.offset,
                      self.slide_names(frame)[0]))


@dataclasses.dataclass(frozen=True)
class RPR(Element):
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

    kind: ClassVar[str] = "RPR"
    lengths_: ClassVar[Tuple[str, ...]] = ("offset",)

    def needs(self):
        return (self.point, self.pivot), ()

    def makes(self):
        return (), (self.guide, self.block)

    def slide_names(self, frame):
        return (self.name or f"{self.block}{self.guide}",)

    def reported_links(self, frame):
        return (self.guide,)  # the block turns with the guide

    def step(self, st):
        pp, pc = st.P[self.point], st.P[self.pivot]
        e = self.offset
        scale = st.scale
        dx, dy = pp.x - pc.x, pp.y - pc.y
        d2 = dx * dx + dy * dy
        disc = d2 - e * e
        ok = disc >= -ASSEMBLY_TOL * scale * scale
        s = np.sqrt(np.maximum(disc, 0.0)) * (self.branch * 1.0)
        # d = (s + i e) u  =>  u = d (s - i e) / |d|^2
        inv = 1.0 / np.maximum(d2, 1e-300 * scale * scale + 1e-300)
        ux, uy = (dx * s + dy * e) * inv, (dy * s - dx * e) * inv
        centred = np.equal(e, 0.0)
        if np.any(centred):
            # exact unit vector even where d -> 0 (the foot of the pivot)
            ux = np.where(centred, dx * (inv * s), ux) if np.ndim(e) else dx * (inv * s)
            uy = np.where(centred, dy * (inv * s), uy) if np.ndim(e) else dy * (inv * s)
        # det of the velocity system is s: singular when the block passes the
        # foot of the pivot (the guide's direction is then undefined)
        sing = np.abs(s) / np.maximum(np.sqrt(d2), scale)
        st.condition(self, self.point, sing)
        bad = st.mark(ok, sing, centred & (sing <= SINGULAR_TOL) if np.any(centred) else None)
        wg = ag = sd = sdd = None
        if st.vel:
            solve2 = Solve2(ux, uy, -dy, dx, bad)
            sd, wg = solve2(pp.vx - pc.vx, pp.vy - pc.vy)
            if st.acc:
                w2 = wg * wg
                sdd, ag = solve2(pp.ax - pc.ax + 2 * sd * wg * uy + w2 * dx,
                                 pp.ay - pc.ay - 2 * sd * wg * ux + w2 * dy)
        st.L[self.guide] = LinkState(np.arctan2(uy, ux), ux, uy, wg, ag)
        st.L[self.block] = st.L[self.guide]
        st.slide(self.slide_names(st.frame)[0], self.block, self.guide, s, sd, sdd)

    def pairs(self, tb):
        tb.revolute(self.point, self.block)
        tb.prismatic(self.guide, self.block, self.point)
        tb.revolute(self.pivot, self.guide)
        tb.frames[self.block] = [self.point, None]
        tb.frames[self.guide] = [self.pivot, None]
        return (self.block, self.guide)

    def sketch(self, frame):
        return (Block(self.point, self.block),
                Guide(self.guide, self.pivot, 0.0, self.offset, self.slide_names(frame)[0], True,
                      self.branch))


@dataclasses.dataclass(frozen=True)
class PointOnLink(Element):
    """A point fixed on link ``link``: ``origin + (along + i*normal) * exp(i*theta_link)``.

    ``along`` is measured along the link's reference direction, ``normal`` to
    its left (counter-clockwise), both [m].
    """

    name: str
    link: int
    origin: str
    along: float = 0.0
    normal: float = 0.0

    kind: ClassVar[str] = "point"
    lengths_: ClassVar[Tuple[str, ...]] = ("along", "normal")

    def needs(self):
        return (self.origin,), (self.link,)

    def makes(self):
        return (self.name,), ()

    def step(self, st):
        k = st.L[self.link]
        rx = self.along * k.c - self.normal * k.s
        ry = self.along * k.s + self.normal * k.c
        st.P[self.name] = rotate_about(st.P[self.origin], k, rx, ry, st.vel, st.acc, st)

    def _out_rows(self, vel, acc):
        return 2 + 2 * vel + 2 * acc

    def pairs(self, tb):
        if self.link not in tb.members.get(self.origin, ()):
            tb.fail(f"point '{self.name}' is placed from '{self.origin}', which is not on link "
                    f"{self.link}", ("point", self.name))
        tb.new_point(self.name, self.link)
        if tb.frames[self.link][1] is None:
            tb.frames[self.link][1] = self.name

    def sketch(self, frame):
        return (Bar(self.origin, self.name),)


@dataclasses.dataclass(frozen=True)
class PRP(Element):
    """PRP dyad: two slider blocks pinned together at a new ``joint``.

    Block ``slider_a`` slides on a guide line carried by link
    ``guide_link_a``: through that link's known point ``guide_point_a``,
    shifted by ``offset_a`` [m] along the line's left normal, in direction
    ``guide_angle_a`` [rad] relative to the guide link (the frame or a moving
    link).  Block ``slider_b`` likewise on ``guide_link_b``.  The joint is the
    intersection of the two lines,

        joint = base_a + s_a u_a = base_b + s_b u_b,

    with the slides ``s_a``, ``s_b`` [m] measured along each line from its
    base point.  The intersection is unique: there is no branch.  It is
    singular when the guides are parallel: the conditioning ``sin_gamma`` is
    |sin| of the angle between them (a dead point at ``sin_gamma -> 0``,
    where the position itself is undefined and the slides are set to 0).

    Both slides are reported (:meth:`slide_names`), named ``name_a`` /
    ``name_b`` or by RRP's rule (``s<slider>`` on the frame,
    ``s<slider><guide>`` on a moving link).  Each block turns with its guide
    link.

    Notes
    -----
    The pin of a cross-slide, of the tangent mechanism (正切机构: slotted
    crank + slider on a fixed line, y = d tan θ) and of the Oldham coupling's
    inversion of the elliptic trammel (two slotted cranks).  Velocities and
    accelerations follow from differentiating the loop twice: the point of a
    moving guide link under the joint, plus the slide along the guide, plus
    the Coriolis term ``2 ω × (ṡ u)``, as in :class:`RRP`.
    """

    joint: str
    slider_a: int
    guide_link_a: int
    guide_point_a: str
    slider_b: int
    guide_link_b: int
    guide_point_b: str
    guide_angle_a: float = 0.0
    offset_a: float = 0.0
    guide_angle_b: float = 0.0
    offset_b: float = 0.0
    name_a: Optional[str] = None
    name_b: Optional[str] = None

    kind: ClassVar[str] = "PRP"
    lengths_: ClassVar[Tuple[str, ...]] = ("offset_a", "offset_b")
    angles_: ClassVar[Tuple[str, ...]] = ("guide_angle_a", "guide_angle_b")

    def _sides(self):
        return ((self.slider_a, self.guide_link_a, self.guide_point_a, self.guide_angle_a,
                 self.offset_a, self.name_a),
                (self.slider_b, self.guide_link_b, self.guide_point_b, self.guide_angle_b,
                 self.offset_b, self.name_b))

    def needs(self):
        return (self.guide_point_a, self.guide_point_b), (self.guide_link_a, self.guide_link_b)

    def makes(self):
        return (self.joint,), (self.slider_a, self.slider_b)

    def slide_names(self, frame):
        return tuple(_slide_symbol(name, sl, gl, frame) for sl, gl, *_, name in self._sides())

    def translating_links(self, frame):
        return tuple(sl for sl, gl, *_ in self._sides() if gl == frame)

    def reported_links(self, frame):
        return tuple(sl for sl, gl, *_ in self._sides() if gl != frame)

    def step(self, st):
        a, b = (_GuideLine(st, gl, gp, ang, off) for _, gl, gp, ang, off, _ in self._sides())
        # s_a u_a - s_b u_b = base_b - base_a: its determinant is -(u_a x u_b)
        sing = np.abs(a.ux * b.uy - a.uy * b.ux)
        st.condition(self, self.joint, sing)
        parallel = sing <= SINGULAR_TOL
        st.mark(True, sing, parallel)
        solve2 = Solve2(a.ux, a.uy, -b.ux, -b.uy, parallel if parallel.any() else None)
        sa, sb = solve2(b.bx - a.bx, b.by - a.by)
        q = PointState(a.bx + sa * a.ux, a.by + sa * a.uy)
        sda = sdb = sdda = sddb = None
        if st.vel:
            rax, ray = q.x - a.p.x, q.y - a.p.y
            rbx, rby = q.x - b.p.x, q.y - b.p.y
            (vax, vay), (vbx, vby) = a.carried_velocity(rax, ray), b.carried_velocity(rbx, rby)
            sda, sdb = solve2(vbx - vax, vby - vay)
            q.vx, q.vy = vax + sda * a.ux, vay + sda * a.uy
            if st.acc:
                aax, aay = a.carried_acceleration(rax, ray, sda)
                abx, aby = b.carried_acceleration(rbx, rby, sdb)
                sdda, sddb = solve2(abx - aax, aby - aay)
                q.ax, q.ay = aax + sdda * a.ux, aay + sdda * a.uy
        st.P[self.joint] = q
        for (sl, gl, *_), name, line, s, v, acc in zip(
                self._sides(), self.slide_names(st.frame), (a, b), (sa, sb), (sda, sdb),
                (sdda, sddb)):
            st.L[sl] = line.block()
            st.slide(name, sl, gl, s, v, acc)

    def pairs(self, tb):
        for sl, gl, gp, *_ in self._sides():
            if gl not in tb.members.get(gp, ()):
                tb.fail(f"the guide of slider {sl} passes through '{gp}', which is not on "
                        f"link {gl}", ("point", gp))
        tb.new_point(self.joint, self.slider_a)
        tb.prismatic(self.guide_link_a, self.slider_a, self.joint)
        tb.joint(self.joint, self.slider_a, self.slider_b)
        tb.prismatic(self.guide_link_b, self.slider_b, self.joint)
        tb.frames[self.slider_a] = [self.joint, None]
        tb.frames[self.slider_b] = [self.joint, None]
        return (self.slider_a, self.slider_b)

    def sketch(self, frame):
        return tuple(p for (sl, gl, gp, ang, off, _), name in zip(self._sides(),
                                                                  self.slide_names(frame))
                     for p in (Block(self.joint, sl), Guide(gl, gp, ang, off, name)))
