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

from typing import Any, ClassVar, Optional, Tuple

import numpy as np

from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

#: the engine's solve state and motion (``engine.SolveState``, ``engine.LinkageMotion``):
#: engine imports this module, so they are untyped here (no import cycle, not even under
#: TYPE_CHECKING: tests/unit/test_layering.py)
_SolveState = Any
_Motion = Any

#: relative size below which a dyad counts as singular (a dead point).  The
#: closed-form positions carry a sqrt of a rounded discriminant, so sin(gamma)
#: at an exact toggle comes out as large as ~sqrt(eps) ~ 1.5e-8: anything below
#: 1e-7 is numerically indistinguishable from the toggle itself.
SINGULAR_TOL = 1e-7
#: relative tolerance for a dyad that just touches its assembly limit
ASSEMBLY_TOL = 1e-10


#: the drawing primitives (:mod:`.sketch`), imported when first drawn
_SKETCH = ("Bar", "Block", "Guide", "Pivot")


def __getattr__(name: str):
    if name in _SKETCH:
        from mechcli.core.linkage import sketch
        return getattr(sketch, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ---------------------------------------------------------------------------
# solver state and helpers
# ---------------------------------------------------------------------------
class Solve2:
    """Cramer's rule for ``X*(c1x, c1y) + Y*(c2x, c2y) = (rx, ry)`` on arrays.

    Positions in ``bad`` (a mask, or None when all are regular) get 0, never
    inf or NaN.
    """

    def __init__(self, c1x: FloatOrArray, c1y: FloatOrArray, c2x: FloatOrArray, c2y: FloatOrArray,
                 bad: Optional[np.ndarray]) -> None:
        det = c1x * c2y - c1y * c2x
        if bad is not None:
            det = np.where(bad, 1.0, det)
        self.inv = 1.0 / det
        self.c = (c1x, c1y, c2x, c2y)
        self.bad = bad

    def __call__(self, rx: FloatOrArray, ry: FloatOrArray):
        c1x, c1y, c2x, c2y = self.c
        x = (rx * c2y - ry * c2x) * self.inv
        y = (c1x * ry - c1y * rx) * self.inv
        if self.bad is not None:
            x = np.where(self.bad, 0.0, x)
            y = np.where(self.bad, 0.0, y)
        return x, y


def _minus(a: FloatOrArray, b: FloatOrArray):
    """``a - b`` of two coordinate arrays; ``a`` itself when ``b`` is a point fixed at
    zero (a stride-0 array of zeros, as the engine gives a ground point)."""
    if type(b) is np.ndarray and b.ndim and not any(b.strides) and not b.reshape(-1)[0]:
        return a
    return np.subtract(a, b)


def _guide_unit(dx: Any, dy: Any, s: Any, e: Any,
                inv: Any, ux: Any, uy: Any, t1: Any,
                t2: Any):
    """An RPR guide's unit vector into ``ux``, ``uy``: ``d = (s + i e) u`` with ``d``
    = point - pivot, so ``u = d (s - i e) / |d|^2`` (``inv`` = 1 / |d|^2; ``t1``,
    ``t2`` scratch of the full shape).  Returns where the offset is zero (there
    ``u = d s / |d|^2``, a unit vector even where d -> 0, the foot of the pivot)."""
    centred = np.equal(e, 0.0)
    if not np.all(centred):
        np.multiply(dx, s, out=ux)
        ux += np.multiply(dy, e, out=t1)
        ux *= inv
        np.multiply(dy, s, out=uy)
        uy -= np.multiply(dx, e, out=t1)
        uy *= inv
    if np.any(centred):
        t = np.multiply(inv, s, out=t1)
        if np.ndim(e):
            np.copyto(ux, np.multiply(dx, t, out=t2), where=centred)
            np.copyto(uy, np.multiply(dy, t, out=t2), where=centred)
        else:
            np.multiply(dx, t, out=ux)
            np.multiply(dy, t, out=uy)
    return centred


class LinkState:
    """A solved link: angle, its cosine and sine, omega, alpha."""

    __slots__ = ("theta", "c", "s", "w", "al")

    def __init__(self, theta: FloatOrArray, c: Optional[FloatOrArray],
                 s: Optional[FloatOrArray], w: Optional[FloatOrArray],
                 al: Optional[FloatOrArray]) -> None:
        self.theta, self.c, self.s, self.w, self.al = theta, c, s, w, al


class PointState:
    """A solved point: x, y and (where computed) vx, vy, ax, ay."""

    __slots__ = ("x", "y", "vx", "vy", "ax", "ay")

    def __init__(self, x: FloatOrArray, y: FloatOrArray, vx: Optional[FloatOrArray] = None,
                 vy: Optional[FloatOrArray] = None, ax: Optional[FloatOrArray] = None,
                 ay: Optional[FloatOrArray] = None) -> None:
        self.x, self.y, self.vx, self.vy, self.ax, self.ay = x, y, vx, vy, ax, ay


def rotate_about(o, link, rx, ry, vel,
                 acc, st=None):
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
    A block on it at slide ``s`` is at ``base + s * u``.  On the frame they
    keep the parameters' own shape; on a moving link they are full arrays in
    scratch buffers ``slot ... slot + 3`` (the direction in fresh arrays when
    ``keep``: a later element reads the block's cosine and sine), and the
    block's angle is an output row.
    """

    def __init__(self, st, link, point, angle,
                 offset, slot, keep):
        self.p, self.g = st.P[point], st.L[link]
        self.moving = link != st.frame
        g, c, s = self.g, np.cos(angle), np.sin(angle)
        if self.moving:
            tmp = st.tmp
            self.ux = np.multiply(g.c, c, out=np.empty(st.shape) if keep else tmp(slot))
            self.ux -= np.multiply(g.s, s, out=tmp(slot + 2))
            self.uy = np.multiply(g.s, c, out=np.empty(st.shape) if keep else tmp(slot + 1))
            self.uy += np.multiply(g.c, s, out=tmp(slot + 2))
            self.bx = np.multiply(self.uy, offset, out=tmp(slot + 2))
            np.subtract(self.p.x, self.bx, out=self.bx)
            self.by = np.multiply(self.ux, offset, out=tmp(slot + 3))
            np.add(self.p.y, self.by, out=self.by)
            self.theta = np.add(g.theta, angle, out=st.out())
        else:
            self.ux, self.uy = g.c * c - g.s * s, g.s * c + g.c * s
            self.bx, self.by = self.p.x - offset * self.uy, self.p.y + offset * self.ux
            self.theta = st.full(angle)
        self.keep = keep or not self.moving

    def carried_velocity(self, rx, ry, ox,
                         oy):
        """Velocity [m/s] of the guide link's point at ``point + (rx, ry)``
        (into ``ox``, ``oy`` when the link moves)."""
        p, w = self.p, self.g.w
        if not self.moving:
            return p.vx, p.vy
        np.multiply(w, ry, out=ox)
        np.subtract(p.vx, ox, out=ox)
        np.multiply(w, rx, out=oy)
        np.add(p.vy, oy, out=oy)
        return ox, oy

    def carried_acceleration(self, rx, ry, sd,
                             ox, oy, t):
        """Acceleration [m/s^2] of the guide link's point at ``point + (rx, ry)``
        plus the Coriolis term ``2 omega x (sd u)`` of a block sliding at ``sd``
        [m/s] (into ``ox``, ``oy`` when the link moves; ``t``: two scratch arrays)."""
        p, g = self.p, self.g
        if not self.moving:
            return p.ax, p.ay
        w2 = np.multiply(g.w, g.w, out=t[0])
        cor = np.multiply(sd, 2.0, out=t[1])
        cor *= g.w
        np.multiply(g.al, ry, out=ox)
        np.subtract(p.ax, ox, out=ox)
        ox -= np.multiply(w2, rx, out=oy)
        ox -= np.multiply(cor, self.uy, out=oy)
        np.multiply(g.al, rx, out=oy)
        np.add(p.ay, oy, out=oy)
        oy -= np.multiply(w2, ry, out=w2)
        oy += np.multiply(cor, self.ux, out=cor)
        return ox, oy

    def block(self, st: _SolveState):
        """State of a block sliding on this line: turned with the guide link."""
        if self.keep:
            return LinkState(self.theta, st.full(self.ux), st.full(self.uy), self.g.w,
                             self.g.al)
        return LinkState(self.theta, None, None, self.g.w, self.g.al)


def _prismatic_solve(hx: Any, hy: Any, rx: Any, ry: Any,
                     ux: Any, uy: Any, k: int, a: Any, b: Any,
                     t: Any, bad: Any) -> None:
    """RRP's 2x2 system ``a (i r) - b u = h``: ``a = (hx uy - hy ux) k``,
    ``b = (rx hx + ry hy) k`` with ``k`` the negated inverse of ``r . u``;
    ``t`` is scratch; 0 where ``bad``."""
    np.multiply(hx, uy, out=a)
    a -= np.multiply(hy, ux, out=t)
    a *= k
    np.multiply(rx, hx, out=b)
    b += np.multiply(ry, hy, out=t)
    b *= k
    if bad is not None:
        np.copyto(a, 0.0, where=bad)
        np.copyto(b, 0.0, where=bad)


def _guide_solve(hx: Any, hy: Any, ux: Any, uy: Any,
                 dx: Any, dy: Any, k: int, t1: Any, t2: Any,
                 bad: Any) -> None:
    """RPR's 2x2 system ``a u + b (i d) = h`` in place of ``hx, hy``:
    ``a = (hx dx + hy dy) k``, ``b = (ux hy - uy hx) k`` with ``k = 1 / (u . d)``;
    ``t1``, ``t2`` are scratch; 0 where ``bad``."""
    np.multiply(uy, hx, out=t1)
    np.multiply(ux, hy, out=t2)
    np.multiply(hx, dx, out=hx)
    hx += np.multiply(hy, dy, out=hy)
    hx *= k
    np.subtract(t2, t1, out=hy)
    hy *= k
    if bad is not None:
        np.copyto(hx, 0.0, where=bad)
        np.copyto(hy, 0.0, where=bad)


def _cross_solve(hx: Any, hy: Any, a: Any, b: Any, k: int,
                 t1: Any, t2: Any, bad: Any) -> None:
    """PRP's 2x2 system ``x u_a - y u_b = h`` in place of ``hx, hy``:
    ``x = (hx b_uy - hy b_ux) k``, ``y = (a_uy hx - a_ux hy) k`` with
    ``k = 1 / (u_a x u_b)``; ``t1``, ``t2`` are scratch; 0 where ``bad``."""
    np.multiply(hy, b.ux, out=t1)
    np.multiply(a.uy, hx, out=t2)
    np.multiply(hx, b.uy, out=hx)
    hx -= t1
    hx *= k
    np.multiply(a.ux, hy, out=hy)
    np.subtract(t2, hy, out=hy)
    hy *= k
    if bad is not None:
        np.copyto(hx, 0.0, where=bad)
        np.copyto(hy, 0.0, where=bad)


def _nonpositive(*lengths: FloatOrArray):
    """Mask of the designs where any of ``lengths`` is <= 0 (None when none is:
    the common case costs one comparison per parameter and changes nothing)."""
    void = None
    for v in lengths:
        if type(v) is float and v > 0.0:   # one design: a plain comparison
            continue
        if np.any(np.less_equal(v, 0.0)):
            m = np.less_equal(v, 0.0)
            void = m if void is None else void | m
    return void


def _flips(branch: int):
    """Does ``branch`` (+1/-1, or an array of them) take -1 anywhere?"""
    if type(branch) is int:
        return branch != 1
    return bool(np.any(np.not_equal(branch, 1)))


def _slide_symbol(name: Optional[str], block: Any, guide: Any, frame: int):
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

    def __post_init__(self) -> None:
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

    def slide_names(self, frame: int) -> Tuple[str, ...]:
        """Symbol suffixes of the slides this element reports (``s3``, ``s23``, ``sE``)."""
        return ()

    def translating_links(self, frame: int):
        """Links made here that only translate (their angle never changes)."""
        return ()

    def reported_links(self, frame: int):
        """Links made here whose angle, omega and alpha are reported."""
        return ()

    def transmission_joint(self) -> Optional[str]:
        """Joint whose transmission angle is reported (RRR dyads)."""
        return None

    def step(self, st: _SolveState):
        """Solve this element on the state ``st`` (see ``engine.solve``)."""
        raise NotImplementedError

    def direction(self, motion: _Motion, link: int):
        """``(cos, sin)`` of the angle of ``link`` (made here) at every position of
        ``motion``, formed from its solved points as :meth:`step` formed them: a few
        passes over memory, where ``np.cos`` and ``np.sin`` of the angle cost ~20 ns
        a position.  None: this element has no such form (take the angle's)."""
        return None

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        """How many output arrays of the full shape ``step`` takes from ``st.out()``
        (the engine preallocates them in one block)."""
        return 0

    def pairs(self, tb: Any):
        """Declare the element's points and kinematic pairs on a topology builder."""
        raise NotImplementedError

    def sketch(self, frame: int):
        """Drawing primitives: a tuple of Bar, Block, Guide, Pivot (``frame``: the
        frame's link number, for the slide names)."""
        return ()


# ---------------------------------------------------------------------------
# elements
# ---------------------------------------------------------------------------
@record
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

    def step(self, st: _SolveState) -> None:
        # kept at the parameters' own shape: broadcast to the full shape only in
        # the results (a batch of designs need not repeat x, y at every position)
        st.P[self.name] = PointState(np.asarray(self.x, dtype=float),
                                     np.asarray(self.y, dtype=float), st.zero, st.zero,
                                     st.zero, st.zero)

    def pairs(self, tb: Any) -> None:
        tb.new_point(self.name, tb.frame)

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Pivot
        return (Pivot(self.name),)


@record
class Crank(Element):
    """Rotary driver: link ``link`` turns about the known point ``pivot``.

    ``point = pivot + length * exp(i*theta)``, where ``theta`` is the driver's
    input angle (the link's absolute angle) [rad]; ``length`` [m].

    ``actuator``: the name of a slide (an RPR dyad's, e.g. a hydraulic cylinder
    between two pivots) that drives the machine while the motion is given as this
    link's angle: the kinetostatics then puts the balancing force along that slide
    (``Fb``, positive in the direction its ``s`` grows) and no torque on this link.
    """

    link: int
    pivot: str
    point: str
    length: float
    actuator: Optional[str] = None

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

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        return 2 + 2 * vel + 2 * acc

    def pairs(self, tb: Any):
        tb.revolute(self.pivot, self.link)
        tb.new_point(self.point, self.link)
        tb.frames[self.link] = [self.pivot, self.point]
        return (self.link,)

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Bar
        return (Bar(self.pivot, self.point),)


@record
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

    def slide_names(self, frame: int):
        return (self.name or str(self.link),)

    def translating_links(self, frame: int):
        return (self.link,)

    def step(self, st: _SolveState) -> None:
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

    def pairs(self, tb: Any):
        if tb.owner.get(self.origin) != tb.frame:
            tb.fail(f"the slider driver of link {self.link} needs its origin '{self.origin}' "
                    "on the frame", ("link", self.link))
        tb.new_point(self.point, self.link)
        tb.prismatic(tb.frame, self.link, self.point)
        tb.frames[self.link] = [self.point, None]
        return (self.link,)

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Block
        return (Block(self.point, None),)


def _rrr_solve(rx: Any, ry: Any, rax: Any, ray: Any,
               rbx: Any, rby: Any, icross: Any, a: Any,
               b: Any, bad: Any):
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


@record
class _RRRPose:
    """The RRR dyad's position (:func:`_rrr_pose`): the joint ``qx, qy``; the link
    vectors ``ra = joint - point_a``, ``rb = joint - point_b``; their ``cross``
    product (a scratch buffer the velocity reuses); the transmission measures
    ``sing, cosj``; where it assembles (``ok``), where its known points coincide on
    a kite (``coincide``); and the lengths used (1 where ``void``)."""

    qx: np.ndarray
    qy: np.ndarray
    rax: np.ndarray
    ray: np.ndarray
    rbx: np.ndarray
    rby: np.ndarray
    cross: np.ndarray
    sing: np.ndarray
    cosj: np.ndarray
    ok: np.ndarray
    coincide: Optional[np.ndarray]
    la: Any
    lb: Any


def _rrr_triangle(st: Any, pa: PointState, pb: PointState, la: Any, lb: Any,
                  branch: Any) -> Tuple[Any, ...]:
    """The joint of the triangle (pa, pb, joint) with sides ``la``, ``lb``: returns
    ``(dx, dy, along, h, inv, qx, qy, ok, coincide)`` with ``(along, h)`` the joint from
    ``pa`` in units of ``(dx, dy) = pb - pa`` (``qx, qy`` are still unset rows)."""
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
    if _flips(branch):
        h *= branch
    along *= inv  # (along, h) / dist: the joint from pa in units of (dx, dy)
    h *= inv
    return dx, dy, along, h, inv, qx, qy, ok, coincide


def _rrr_pose(st: Any, pa: PointState, pb: PointState, la: Any, lb: Any,
              branch: Any) -> _RRRPose:
    """The RRR dyad's joint, link vectors and transmission measures (:class:`_RRRPose`)."""
    out, tmp = st.out, st.tmp
    # a link of zero (or negative) length cannot assemble (its angle is
    # undefined): such designs of a batch are infeasible, never inf/NaN
    void = _nonpositive(la, lb)
    if void is not None:
        la, lb = np.where(void, 1.0, la), np.where(void, 1.0, lb)
    dx, dy, along, h, inv, qx, qy, ok, coincide = _rrr_triangle(st, pa, pb, la, lb, branch)
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
    return _RRRPose(qx, qy, rax, ray, rbx, rby, cross, sing, cosj, ok, coincide, la, lb)


def _rrr_velocity(st: _SolveState, pa: Any, pb: Any, p: Any,
                  bad: Any, q: Any
                  ):
    """The links' angular velocities ``wa, wb`` and the joint's velocity (into ``q``):
    the system wa (i ra) - wb (i rb) = vb - va by Cramer's rule; its determinant is
    -cross, kept as ``icross = 1 / cross`` (returned, for the acceleration)."""
    out = st.out
    cross = p.cross
    if bad is not None:
        np.copyto(cross, 1.0, where=bad)
    icross = np.divide(1.0, cross, out=cross)
    rx = np.subtract(pb.vx, pa.vx, out=out())
    ry = np.subtract(pb.vy, pa.vy, out=out())
    wa, wb = _rrr_solve(rx, ry, p.rax, p.ray, p.rbx, p.rby, icross, out(), out(), bad)
    q.vx = np.multiply(wa, p.ray, out=rx)
    np.subtract(pa.vx, q.vx, out=q.vx)
    q.vy = np.multiply(wa, p.rax, out=ry)
    np.add(pa.vy, q.vy, out=q.vy)
    return wa, wb, icross


def _rrr_acceleration(st: _SolveState, pa: Any, pb: Any, p: Any,
                      bad: Any, q: Any, wa: Any,
                      wb: Any, icross: Any):
    """The links' angular accelerations ``aa, ab`` and the joint's acceleration (into
    ``q``): the velocity's system with the centripetal terms on the right."""
    out, tmp = st.out, st.tmp
    rax, ray, rbx, rby = p.rax, p.ray, p.rbx, p.rby
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
    return aa, ab


@record
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

    def reported_links(self, frame: int):
        return (self.link_a, self.link_b)

    def transmission_joint(self):
        return self.joint

    def step(self, st: _SolveState) -> None:
        # written for few passes over memory: every array of the full shape is an
        # output row (st.out) or one of six scratch buffers (st.tmp) reused in place;
        # the steps: the joint (_rrr_pose), its velocity and acceleration
        # (_rrr_velocity, _rrr_acceleration), then the links' states
        pa, pb = st.P[self.point_a], st.P[self.point_b]
        p = _rrr_pose(st, pa, pb, self.length_a, self.length_b, self.branch)
        st.condition(self, self.joint, p.sing, p.cosj)
        bad = st.mark(p.ok, p.sing, p.coincide)
        q = PointState(p.qx, p.qy)
        wa = wb = aa = ab = None
        if st.vel:
            wa, wb, icross = _rrr_velocity(st, pa, pb, p, bad, q)
            if st.acc:
                aa, ab = _rrr_acceleration(st, pa, pb, p, bad, q, wa, wb, icross)
        st.P[self.joint] = q
        needed = st.needed_links
        la, lb, out = p.la, p.lb, st.out
        rax, ray, rbx, rby = p.rax, p.ray, p.rbx, p.rby
        st.L[self.link_a] = LinkState(np.arctan2(ray, rax, out=out()),
                                      rax * (1 / la) if self.link_a in needed else None,
                                      ray * (1 / la) if self.link_a in needed else None, wa, aa)
        st.L[self.link_b] = LinkState(np.arctan2(rby, rbx, out=out()),
                                      rbx * (1 / lb) if self.link_b in needed else None,
                                      rby * (1 / lb) if self.link_b in needed else None, wb, ab)

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        return 6 + 4 * vel + 4 * acc

    def pairs(self, tb: Any):
        tb.revolute(self.point_a, self.link_a)
        tb.new_point(self.joint, self.link_a)
        tb.joint(self.joint, self.link_a, self.link_b)
        tb.revolute(self.point_b, self.link_b)
        tb.frames[self.link_a] = [self.point_a, self.joint]
        tb.frames[self.link_b] = [self.point_b, self.joint]
        return (self.link_a, self.link_b)

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Bar
        return (Bar(self.point_a, self.joint), Bar(self.point_b, self.joint))


def _rrp_guide(st: Any, g: Any, pg: PointState, angle: float, e: float, moving: bool,
               keep_u: bool) -> Tuple[Any, Any, Any, Any]:
    """The RRP dyad's guide line: its direction ``ux, uy`` and base ``bx, by`` (the
    guide point shifted by the offset ``e`` along the left normal)."""
    tmp = st.tmp
    cphi, sphi = np.cos(angle), np.sin(angle)
    if moving:
        # the guide's direction and base turn with its link: full arrays (kept
        # for a later element that reads the slider's cosine and sine)
        ux = np.multiply(g.c, cphi, out=np.empty(st.shape) if keep_u else tmp(6))
        ux -= np.multiply(g.s, sphi, out=tmp(0))
        uy = np.multiply(g.s, cphi, out=np.empty(st.shape) if keep_u else tmp(7))
        uy += np.multiply(g.c, sphi, out=tmp(0))
        bx = np.multiply(uy, e, out=tmp(4))
        np.subtract(pg.x, bx, out=bx)
        by = np.multiply(ux, e, out=tmp(5))
        np.add(pg.y, by, out=by)
    else:  # a frame guide: direction and base at the parameters' own shape
        ux, uy = g.c * cphi - g.s * sphi, g.s * cphi + g.c * sphi
        bx, by = pg.x - e * uy, pg.y + e * ux
    return ux, uy, bx, by


@record
class _RRPPose:
    """The RRP dyad's position (:func:`_rrp_pose`): the guide direction ``ux, uy`` and
    base ``bx, by``; the slide ``s``; the pin ``qx, qy``; the rod ``r = pin - point``;
    ``dot = r . u`` (the velocity system's determinant, a scratch buffer the velocity
    reuses); ``sing = |dot| / length``, ``ilen = 1 / length``; where it assembles."""

    ux: Any
    uy: Any
    bx: Any
    by: Any
    s: np.ndarray
    qx: np.ndarray
    qy: np.ndarray
    rx: np.ndarray
    ry: np.ndarray
    dot: np.ndarray
    sing: np.ndarray
    ilen: Any
    ok: np.ndarray


def _rrp_pose(st: Any, pp: PointState, ux: Any, uy: Any, bx: Any, by: Any, length: Any,
              branch: Any) -> _RRPPose:
    """The slide ``s`` from ``|base + s u - point| = length``, ``s = -b +- sqrt(b^2 - c)``,
    and the pin (:class:`_RRPPose`)."""
    out, tmp = st.out, st.tmp
    void = _nonpositive(length)  # a rod of zero length: infeasible (see RRR)
    if void is not None:
        length = np.where(void, 1.0, length)
    length2 = length * length
    ilen = 1 / length
    wx = np.subtract(bx, pp.x, out=tmp(0))
    wy = np.subtract(by, pp.y, out=tmp(1))
    b = np.multiply(wx, ux, out=tmp(2))
    b += np.multiply(wy, uy, out=tmp(3))
    c = np.multiply(wx, wx, out=tmp(3))
    c += np.multiply(wy, wy, out=wx)
    c -= length2
    s = np.multiply(b, b, out=out())
    s -= c  # the discriminant
    ok = s >= -4 * ASSEMBLY_TOL * length2
    if void is not None:
        ok &= ~void
    np.maximum(s, 0.0, out=s)
    np.sqrt(s, out=s)
    if _flips(branch):
        s *= branch
    s -= b
    qx = np.multiply(s, ux, out=out())
    qx += bx
    qy = np.multiply(s, uy, out=out())
    qy += by
    rx = np.subtract(qx, pp.x, out=tmp(0))  # rod: point -> pin
    ry = np.subtract(qy, pp.y, out=tmp(1))
    dot = np.multiply(rx, ux, out=tmp(2))  # the velocity system's determinant
    dot += np.multiply(ry, uy, out=tmp(3))
    sing = np.abs(dot, out=out())
    sing *= ilen
    return _RRPPose(ux, uy, bx, by, s, qx, qy, rx, ry, dot, sing, ilen, ok)


def _rrp_velocity(st: _SolveState, pp: Any, pg: Any, g: Any, p: Any,
                  moving: Any, bad: Any, q: Any
                  ):
    """The rod's angular velocity ``wr``, the slide rate ``sd`` and the pin's velocity
    (into ``q``): wr (i r) - sd u = v_base(pin) - v_point by Cramer's rule, with the
    negated inverse of the determinant r . u (``ninv``, returned with ``lever``:
    ``(lx, ly)``, base -> pin from the guide point on a moving guide, for the
    acceleration)."""
    out, tmp = st.out, st.tmp
    rx, ry, ux, uy, s = p.rx, p.ry, p.ux, p.uy, p.s
    if bad is not None:
        np.copyto(p.dot, 1.0, where=bad)
    ninv = np.divide(-1.0, p.dot, out=p.dot)
    hx = np.subtract(pg.vx, pp.vx, out=tmp(3))
    hy = np.subtract(pg.vy, pp.vy, out=tmp(4) if not moving else tmp(8))
    lx = ly = None
    if moving:
        gw = g.w
        lx = np.subtract(p.bx, pg.x, out=tmp(9))  # base -> pin from the guide point
        lx += np.multiply(s, ux, out=tmp(10))
        ly = np.subtract(p.by, pg.y, out=tmp(11))
        ly += np.multiply(s, uy, out=tmp(10))
        hx -= np.multiply(gw, ly, out=tmp(10))
        hy += np.multiply(gw, lx, out=tmp(10))
    wr, sd = out(), out()
    _prismatic_solve(hx, hy, rx, ry, ux, uy, ninv, wr, sd, tmp(5), bad)
    q.vx = np.multiply(wr, ry, out=out())
    np.subtract(pp.vx, q.vx, out=q.vx)
    q.vy = np.multiply(wr, rx, out=out())
    np.add(pp.vy, q.vy, out=q.vy)
    return wr, sd, ninv, (lx, ly)


def _rrp_acceleration(st: _SolveState, pp: Any, pg: Any, g: Any, p: Any,
                      moving: Any, bad: Any, q: Any,
                      wr: Any, sd: Any, ninv: Any, lever: Any
                      ):
    """The rod's angular acceleration ``ar``, the slide's ``sdd`` and the pin's
    acceleration (into ``q``): the velocity's system with the centripetal (and, on a
    moving guide, the guide's and Coriolis) terms on the right."""
    out, tmp = st.out, st.tmp
    rx, ry, ux, uy = p.rx, p.ry, p.ux, p.uy
    wr2 = np.multiply(wr, wr, out=tmp(4) if not moving else tmp(12))
    hx = np.subtract(pg.ax, pp.ax, out=tmp(3))
    hx += np.multiply(wr2, rx, out=tmp(5))
    q.ay = hy = np.subtract(pg.ay, pp.ay, out=out())
    hy += np.multiply(wr2, ry, out=tmp(5))
    if moving:
        gw = g.w
        lx, ly = lever
        w2 = np.multiply(gw, gw, out=tmp(8))
        cor = np.multiply(sd, 2.0, out=tmp(13))
        cor *= gw
        hx -= np.multiply(g.al, ly, out=tmp(5))
        hx -= np.multiply(w2, lx, out=tmp(5))
        hx -= np.multiply(cor, uy, out=tmp(5))
        hy += np.multiply(g.al, lx, out=tmp(5))
        hy -= np.multiply(w2, ly, out=tmp(5))
        hy += np.multiply(cor, ux, out=tmp(5))
    ar, sdd = out(), out()
    _prismatic_solve(hx, hy, rx, ry, ux, uy, ninv, ar, sdd, tmp(5), bad)
    q.ax = np.multiply(ar, ry, out=out())
    np.subtract(pp.ax, q.ax, out=q.ax)
    q.ax -= np.multiply(wr2, rx, out=tmp(5))
    np.multiply(ar, rx, out=q.ay)
    np.add(pp.ay, q.ay, out=q.ay)
    q.ay -= np.multiply(wr2, ry, out=tmp(5))
    return ar, sdd


@record
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

    def translating_links(self, frame: int):
        return (self.slider,) if self.guide_link == frame else ()

    def reported_links(self, frame: int):
        return (self.link,) if self.guide_link == frame else (self.link, self.slider)

    def step(self, st: _SolveState) -> None:
        # written like RRR's: every array of the full shape is an output row
        # (st.out) or a scratch buffer (st.tmp) reused in place; the operations
        # (and so the rounding) are those of the plain closed form.  The steps: the
        # guide line (_rrp_guide), the pin (_rrp_pose), its velocity and acceleration
        # (_rrp_velocity, _rrp_acceleration), then the links' states
        pp, pg, g = st.P[self.point], st.P[self.guide_point], st.L[self.guide_link]
        out = st.out
        moving = self.guide_link != st.frame
        keep_u = self.slider in st.needed_links
        ux, uy, bx, by = _rrp_guide(st, g, pg, self.guide_angle, self.offset, moving, keep_u)
        p = _rrp_pose(st, pp, ux, uy, bx, by, self.length, self.branch)
        st.condition(self, self.joint, p.sing)
        bad = st.mark(p.ok, p.sing)
        q = PointState(p.qx, p.qy)
        theta = np.arctan2(p.ry, p.rx, out=out())
        needed = self.link in st.needed_links
        st.L[self.link] = LinkState(theta, p.rx * p.ilen if needed else None,
                                    p.ry * p.ilen if needed else None, None, None)
        wr = ar = sd = sdd = None
        if st.vel:
            wr, sd, ninv, lever = _rrp_velocity(st, pp, pg, g, p, moving, bad, q)
            if st.acc:
                ar, sdd = _rrp_acceleration(st, pp, pg, g, p, moving, bad, q, wr, sd, ninv,
                                            lever)
            st.L[self.link].w, st.L[self.link].al = wr, ar
        st.P[self.joint] = q
        if moving:
            th_s = np.add(g.theta, self.guide_angle, out=out())
            if not keep_u:
                ux = uy = None  # scratch: never kept past this step
        else:
            th_s = st.full(self.guide_angle)
            ux, uy = st.full(ux), st.full(uy)
        st.L[self.slider] = LinkState(th_s, ux, uy, g.w, g.al)
        st.slide(self.slide_names(st.frame)[0], self.slider, self.guide_link, p.s, sd, sdd)

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        return 5 + (self.guide_link != frame) + 4 * vel + 4 * acc

    def pairs(self, tb: Any):
        tb.revolute(self.point, self.link)
        tb.new_point(self.joint, self.link)
        tb.joint(self.joint, self.link, self.slider)
        tb.prismatic(self.guide_link, self.slider, self.joint)
        tb.frames[self.link] = [self.point, self.joint]
        tb.frames[self.slider] = [self.joint, None]
        return (self.link, self.slider)

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Bar, Block, Guide
        return (Bar(self.point, self.joint), Block(self.joint, self.slider),
                Guide(self.guide_link, self.guide_point, self.guide_angle, self.offset,
                      self.slide_names(frame)[0]))


@record
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

    def slide_names(self, frame: int):
        return (self.name or f"{self.block}{self.guide}",)

    def reported_links(self, frame: int):
        return (self.guide,)  # the block turns with the guide

    def step(self, st: _SolveState) -> None:
        # in place like RRR's (output rows and scratch buffers), with the
        # operations of the plain closed form
        pp, pc = st.P[self.point], st.P[self.pivot]
        out, tmp = st.out, st.tmp
        e = self.offset
        scale = st.scale
        dx = np.subtract(pp.x, pc.x, out=tmp(0))
        dy = np.subtract(pp.y, pc.y, out=tmp(1))
        d2 = np.multiply(dx, dx, out=tmp(2))
        d2 += np.multiply(dy, dy, out=tmp(3))
        s = np.subtract(d2, e * e, out=out())  # the discriminant, then the slide
        ok = s >= -ASSEMBLY_TOL * scale * scale
        np.maximum(s, 0.0, out=s)
        np.sqrt(s, out=s)
        if _flips(self.branch):
            s *= self.branch
        # d = (s + i e) u  =>  u = d (s - i e) / |d|^2
        inv = np.maximum(d2, 1e-300 * scale * scale + 1e-300, out=tmp(3))
        np.divide(1.0, inv, out=inv)
        keep = self.guide in st.needed_links or self.block in st.needed_links
        ux = np.empty(st.shape) if keep else tmp(6)
        uy = np.empty(st.shape) if keep else tmp(7)
        centred = _guide_unit(dx, dy, s, e, inv, ux, uy, tmp(4), tmp(5))
        # det of the velocity system is s: singular when the block passes the
        # foot of the pivot (the guide's direction is then undefined)
        dist = np.sqrt(d2, out=d2)
        np.maximum(dist, scale, out=dist)
        sing = np.abs(s, out=out())
        sing /= dist
        st.condition(self, self.point, sing)
        bad = st.mark(ok, sing, centred & (sing <= SINGULAR_TOL) if np.any(centred) else None)
        wg = ag = sd = sdd = None
        if st.vel:
            # sd u + wg (i d) = v_point - v_pivot by Cramer's rule: det = u . d
            det = np.multiply(ux, dx, out=tmp(2))
            det += np.multiply(uy, dy, out=tmp(3))
            if bad is not None:
                np.copyto(det, 1.0, where=bad)
            idet = np.divide(1.0, det, out=det)
            sd = hx = np.subtract(pp.vx, pc.vx, out=out())
            wg = hy = np.subtract(pp.vy, pc.vy, out=out())
            _guide_solve(hx, hy, ux, uy, dx, dy, idet, tmp(3), tmp(4), bad)
            if st.acc:
                cor = np.multiply(sd, 2.0, out=tmp(3))  # Coriolis: 2 sd wg
                cor *= wg
                w2 = np.multiply(wg, wg, out=tmp(4))
                sdd = hx = np.subtract(pp.ax, pc.ax, out=out())
                hx += np.multiply(cor, uy, out=tmp(5))
                hx += np.multiply(w2, dx, out=tmp(5))
                ag = hy = np.subtract(pp.ay, pc.ay, out=out())
                hy -= np.multiply(cor, ux, out=tmp(5))
                hy += np.multiply(w2, dy, out=tmp(5))
                _guide_solve(hx, hy, ux, uy, dx, dy, idet, tmp(3), tmp(4), bad)
        theta = np.arctan2(uy, ux, out=out())
        if not keep:
            ux = uy = None  # scratch: never kept past this step
        st.L[self.guide] = LinkState(theta, ux, uy, wg, ag)
        st.L[self.block] = st.L[self.guide]
        st.slide(self.slide_names(st.frame)[0], self.block, self.guide, s, sd, sdd)

    def direction(self, motion, link):
        # the guide's unit vector u = d (s - i e) / |d|^2, d = point - pivot, as in step
        # (where |d| -> 0, the foot of the pivot, not a regular position, u -> 0)
        pp, pc = motion.points[self.point], motion.points[self.pivot]
        s = motion.slides[self.slide_names(None)[0]].s
        dx, dy = _minus(pp.x, pc.x), _minus(pp.y, pc.y)
        inv = np.multiply(dx, dx)
        inv += np.multiply(dy, dy)
        np.maximum(inv, 1e-300, out=inv)
        np.divide(1.0, inv, out=inv)
        shape = np.broadcast_shapes(np.shape(dx), np.shape(s))
        ux, uy = np.empty(shape), np.empty(shape)
        _guide_unit(dx, dy, s, self.offset, inv, ux, uy, np.empty(shape), np.empty(shape))
        return ux, uy

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        return 3 + 2 * vel + 2 * acc

    def pairs(self, tb: Any):
        tb.revolute(self.point, self.block)
        tb.prismatic(self.guide, self.block, self.point)
        tb.revolute(self.pivot, self.guide)
        tb.frames[self.block] = [self.point, None]
        tb.frames[self.guide] = [self.pivot, None]
        return (self.block, self.guide)

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Block, Guide
        return (Block(self.point, self.block),
                Guide(self.guide, self.pivot, 0.0, self.offset, self.slide_names(frame)[0], True,
                      self.branch))


@record
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
        # the arm (rx, ry) in scratch buffers 3, 4 (rotate_about takes 5 and output rows)
        k, tmp = st.L[self.link], st.tmp
        rx = np.multiply(self.along, k.c, out=tmp(3))
        ry = np.multiply(self.along, k.s, out=tmp(4))
        if np.ndim(self.normal) or self.normal != 0.0:
            rx -= np.multiply(self.normal, k.s, out=tmp(5))
            ry += np.multiply(self.normal, k.c, out=tmp(5))
        st.P[self.name] = rotate_about(st.P[self.origin], k, rx, ry, st.vel, st.acc, st)

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        return 2 + 2 * vel + 2 * acc

    def pairs(self, tb: Any) -> None:
        if self.link not in tb.members.get(self.origin, ()):
            tb.fail(f"point '{self.name}' is placed from '{self.origin}', which is not on link "
                    f"{self.link}", ("point", self.name))
        tb.new_point(self.name, self.link)
        if tb.frames[self.link][1] is None:
            tb.frames[self.link][1] = self.name

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Bar
        return (Bar(self.origin, self.name),)


@record
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

    def slide_names(self, frame: int):
        return tuple(_slide_symbol(name, sl, gl, frame) for sl, gl, *_, name in self._sides())

    def translating_links(self, frame: int):
        return tuple(sl for sl, gl, *_ in self._sides() if gl == frame)

    def reported_links(self, frame: int):
        return tuple(sl for sl, gl, *_ in self._sides() if gl != frame)

    def step(self, st):
        # in place like RRR's: outputs in st.out rows, intermediates in scratch
        # buffers (0-7 and, for moving guides, 8-19), the plain closed form's operations
        out, tmp = st.out, st.tmp
        a, b = (_GuideLine(st, gl, gp, ang, off, slot, sl in st.needed_links)
                for (sl, gl, gp, ang, off, _), slot in zip(self._sides(), (8, 12)))
        # s_a u_a - s_b u_b = base_b - base_a: its determinant is -(u_a x u_b)
        cross = np.multiply(a.ux, b.uy, out=tmp(2))
        cross -= np.multiply(a.uy, b.ux, out=tmp(3))
        sing = np.abs(cross, out=out())
        st.condition(self, self.joint, sing)
        parallel = sing <= SINGULAR_TOL
        st.mark(True, sing, parallel)
        bad = parallel if parallel.any() else None
        if bad is not None:
            np.copyto(cross, 1.0, where=bad)
        k = np.divide(1.0, cross, out=cross)
        sa = np.subtract(b.bx, a.bx, out=out())
        sb = np.subtract(b.by, a.by, out=out())
        _cross_solve(sa, sb, a, b, k, tmp(3), tmp(4), bad)
        qx = np.multiply(sa, a.ux, out=out())
        qx += a.bx
        qy = np.multiply(sa, a.uy, out=out())
        qy += a.by
        q = PointState(qx, qy)
        sda = sdb = sdda = sddb = None
        if st.vel:
            rax = np.subtract(qx, a.p.x, out=tmp(0))
            ray = np.subtract(qy, a.p.y, out=tmp(1))
            rbx = np.subtract(qx, b.p.x, out=tmp(5))
            rby = np.subtract(qy, b.p.y, out=tmp(6))
            vax, vay = a.carried_velocity(rax, ray, tmp(16), tmp(17))
            vbx, vby = b.carried_velocity(rbx, rby, tmp(18), tmp(19))
            sda = np.subtract(vbx, vax, out=out())
            sdb = np.subtract(vby, vay, out=out())
            _cross_solve(sda, sdb, a, b, k, tmp(3), tmp(4), bad)
            q.vx = np.multiply(sda, a.ux, out=out())
            q.vx += vax
            q.vy = np.multiply(sda, a.uy, out=out())
            q.vy += vay
            if st.acc:
                aax, aay = a.carried_acceleration(rax, ray, sda, tmp(16), tmp(17),
                                                  (tmp(3), tmp(4)))
                abx, aby = b.carried_acceleration(rbx, rby, sdb, tmp(18), tmp(19),
                                                  (tmp(3), tmp(4)))
                sdda = np.subtract(abx, aax, out=out())
                sddb = np.subtract(aby, aay, out=out())
                _cross_solve(sdda, sddb, a, b, k, tmp(3), tmp(4), bad)
                q.ax = np.multiply(sdda, a.ux, out=out())
                q.ax += aax
                q.ay = np.multiply(sdda, a.uy, out=out())
                q.ay += aay
        st.P[self.joint] = q
        for (sl, gl, *_), name, line, s, v, acc in zip(
                self._sides(), self.slide_names(st.frame), (a, b), (sa, sb), (sda, sdb),
                (sdda, sddb)):
            st.L[sl] = line.block(st)
            st.slide(name, sl, gl, s, v, acc)

    def _out_rows(self, vel: bool, acc: bool, frame: Optional[int] = None):
        return (5 + (self.guide_link_a != frame) + (self.guide_link_b != frame)
                + 4 * vel + 4 * acc)

    def pairs(self, tb: Any):
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

    def sketch(self, frame: int):
        from mechcli.core.linkage.sketch import Block, Guide
        return tuple(p for (sl, gl, gp, ang, off, _), name in zip(self._sides(),
                                                                  self.slide_names(frame))
                     for p in (Block(self.joint, sl), Guide(gl, gp, ang, off, name)))
