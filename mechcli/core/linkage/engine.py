"""The linkage engine: a :class:`Linkage` of elements, solved by :func:`solve`.

The elements (drivers, dyads, points; :mod:`mechcli.core.linkage.elements`)
each own their solving step; this module orders them, runs them over whole
arrays at once and gathers the results.  Inputs and every element parameter
may be arrays of any common (broadcastable) shape: ``solve`` over lengths of
shape ``(M, 1)`` and input angles of shape ``(N,)`` solves M candidate linkages
at N positions each, with results of shape ``(M, N)``.

Points are complex numbers ``x + iy`` [m] (kept as separate real arrays);
velocities [m/s] and accelerations [m/s^2] likewise.  Angles are
counter-clockwise from +x [rad].
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import sys
import threading
from typing import Any, Dict, Optional, Tuple, Union

import numpy as np

from mechcli.core.linkage.elements import SINGULAR_TOL, Element, LinkState, PointState
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray


class LinkageDefinitionError(ValueError):
    """The elements do not form a solvable linkage (bad topology or reference).

    Attributes
    ----------
    index : int or None
        Index of the offending element in ``Linkage.elements``.
    field : tuple or None
        ``("point", name)`` or ``("link", number)``: the reference at fault.
    """

    def __init__(self, message: str, index: Optional[int] = None,
                 field: Optional[Tuple[str, Any]] = None) -> None:
        super().__init__(message)
        self.index = index
        self.field = field


@record(eq=False)
class Linkage:
    """A planar linkage: the frame's link number and the elements.

    Elements may be listed in any order; ``order`` is the solving order
    (each element after those that define its points and links).  Element
    parameters may be arrays (a batch of designs; see :func:`solve`).
    """

    frame: int
    elements: Tuple[Element, ...]
    order: Tuple[int, ...] = dataclasses.field(default=(), compare=False)
    #: ``((link, offset), ...)``: a linkage given by its joints (:mod:`.drawing`) measures
    #: a link's angle from its first joint to its second as drawn; where the engine
    #: measures it from other points, ``offset`` = that angle − the engine's [rad],
    #: constant on a rigid link, is what the reports add (the engine's own results,
    #: ``LinkageMotion.links``, are its angles); empty otherwise
    angle_offsets: Tuple[Tuple[int, float], ...] = dataclasses.field(default=(),
                                                                     compare=False)
    #: the drivers and Assur groups (:class:`mechcli.core.grashof.structure.Structure`)
    #: where the linkage was given by its joints; None otherwise
    structure: object = dataclasses.field(default=None, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "elements", tuple(self.elements))
        for i, el in enumerate(self.elements):
            if not isinstance(el, Element):
                raise LinkageDefinitionError(f"unknown element {el!r}", i)
        points, links = set(), {self.frame}
        made_points, made_links = {}, {self.frame: -1}
        for i, el in enumerate(self.elements):
            mp, ml = el.makes()
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
                (np_, nl), (mp, ml) = self.elements[i].needs(), self.elements[i].makes()
                if all(p in points for p in np_) and all(ln in links for ln in nl):
                    points.update(mp)
                    links.update(ml)
                    order.append(i)
                    pending.remove(i)
                    progress = True
            if not progress:
                # report a root cause (a reference nothing defines) before a cycle
                for i in pending:
                    np_, nl = self.elements[i].needs()
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

    def with_elements(self, *extra: Any) -> Linkage:
        """The same linkage with more elements (e.g. coupler points) added."""
        return Linkage(self.frame, self.elements + tuple(extra),
                       angle_offsets=self.angle_offsets, structure=self.structure)

    @property
    def drivers(self):
        """The driver elements, the primary (input) one first."""
        return tuple(el for el in self.elements if el.is_driver)

    def driver(self, link: int):
        """The driver element of link ``link``."""
        for d in self.drivers:
            if d.link == link:
                return d
        raise KeyError(link)

    @property
    def translating_links(self):
        """Links that only translate (slider blocks on frame guides, linear drivers)."""
        return tuple(ln for el in self.elements for ln in el.translating_links(self.frame))

    @property
    def rotating_links(self):
        """Links whose angle, omega and alpha are reported (not drivers, not translating)."""
        out = []
        for el in self.elements:
            if not el.is_driver:
                out += [ln for ln in el.reported_links(self.frame) if ln not in out]
        return tuple(sorted(out))

    @property
    def slide_names(self):
        """Names of the slides (prismatic pairs reported as s/v/a), in element order."""
        return tuple(n for el in self.elements if not el.is_driver
                     for n in el.slide_names(self.frame))

    @property
    def transmission_joints(self):
        """Joints whose transmission angle is reported (RRR dyads), in element order."""
        return tuple(j for el in self.elements for j in [el.transmission_joint()]
                     if j is not None)

    @property
    def point_names(self):
        return tuple(n for el in self.elements for n in el.makes()[0])

    @property
    def shape(self):
        """Broadcast shape of the element parameters: () for one linkage,
        e.g. ``(M, 1)`` for a batch of M designs."""
        shapes = [np.shape(p) for el in self.elements for p in el.parameters()]
        try:
            return np.broadcast_shapes(*shapes)
        except ValueError:
            named = ", ".join(f"element {i} ({el.kind}) {f} {np.shape(getattr(el, f))}"
                              for i, el in enumerate(self.elements) for f in _fields(el)
                              if np.ndim(getattr(el, f)))
            raise ValueError("the element parameters do not broadcast to one batch shape: "
                             + named) from None

    def scale(self):
        """A characteristic length [m]: the largest length or coordinate
        (an array of shape :attr:`shape` for a batch of designs)."""
        sizes = [s for el in self.elements for s in el.sizes()]
        if all(np.ndim(s) == 0 for s in sizes):
            return max([1e-300] + [float(s) for s in sizes])
        return functools.reduce(np.maximum, sizes, 1e-300)


def stack(linkages):
    """One batched linkage from M linkages of the same structure.

    Every numeric parameter (lengths, coordinates, angles, branch) becomes an
    array of shape ``(M, 1)``, so :func:`solve` against inputs of shape
    ``(N,)`` or ``(M, N)`` moves all M designs at once (results ``(M, N)``).
    The linkages must have the same elements in the same order, with the same
    points, links and names; only their numbers may differ.  This is how a
    population of candidate designs (``optimize``, the atlas) is one engine
    call.

    Raises
    ------
    ValueError
        If the list is empty, a parameter is already an array, or two
        linkages differ in anything but numbers.
    """
    linkages = list(linkages)
    if not linkages:
        raise ValueError("stack needs at least one linkage")
    first = linkages[0]
    for k, lk in enumerate(linkages[1:], 1):
        if lk.frame != first.frame or len(lk.elements) != len(first.elements):
            raise ValueError(f"linkage {k} differs in structure from linkage 0")
    elements = []
    for i, el in enumerate(first.elements):
        numeric = _fields(el)
        differ: set = set()
        for k, lk in enumerate(linkages):
            other = lk.elements[i]
            if type(other) is not type(el):
                raise ValueError(f"element {i} ({el.kind}) of linkage {k} differs from linkage "
                                 "0 in more than its numbers")
            differ.update(f.name for f in dataclasses.fields(el) if f.name not in numeric
                          and getattr(other, f.name) != getattr(el, f.name))
        values: dict = {}
        if differ:  # an element may batch what else differs (a triad's tables)
            hook = getattr(type(el), "stack_fields", None)
            got = hook([lk.elements[i] for lk in linkages], sorted(differ)) \
                if hook is not None else None
            if got is None:
                raise ValueError(f"element {i} ({el.kind}) of the linkages differs in more "
                                 f"than its numbers ({', '.join(sorted(differ))})")
            values = dict(got)
        for f in numeric:
            column = [getattr(lk.elements[i], f) for lk in linkages]
            if any(np.ndim(v) for v in column):
                raise ValueError(f"element {i} ({el.kind}) {f} is already an array")
            values[f] = np.asarray(column, dtype=float)[:, None]
        elements.append(dataclasses.replace(el, **values))
    return Linkage(first.frame, tuple(elements), angle_offsets=first.angle_offsets,
                   structure=first.structure)


def _fields(el: Any):
    return [f for f in el.lengths_ + el.angles_ + ("branch",) if hasattr(el, f)]


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------
# The motion records hold arrays, which ``==`` cannot compare as a whole: they compare
# (and hash) by identity, ``eq=False``, which also spares the generated ``__eq__`` and
# ``__hash__`` at start-up.
@record(eq=False)
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


@record(eq=False)
class LinkMotion:
    """Angle ``theta`` [rad], ``omega`` [rad/s], ``alpha`` [rad/s^2]."""

    theta: np.ndarray
    omega: Optional[np.ndarray] = None
    alpha: Optional[np.ndarray] = None


@record(eq=False)
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


@record(eq=False)
class DyadCondition:
    """Conditioning of one dyad: ``sin_gamma`` is 0 at a toggle/dead point.

    For an RRR dyad it is |sin| of the angle between its two links at the
    joint and ``cos_joint`` that angle's cosine, so ``gamma`` is the acute
    transmission angle in [0, pi/2]; for RRP |cos| of the angle between rod
    and guide; for RPR |s| over the pivot-block distance (or the linkage
    scale, whichever is larger); for PRP |sin| of the angle between the two
    guides.  Each element class documents its own (``Element.step``).
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


@record(eq=False)
class DriverMotion:
    """Input of one driver: angle [rad] (or slide [m]) with its first two derivatives."""

    q: Union[np.ndarray, float]
    dq: Union[np.ndarray, float] = 0.0
    ddq: Union[np.ndarray, float] = 0.0


class Slides(dict):
    """``LinkageMotion.slides``: slide name -> :class:`SlideMotion`, keyed by the slide's
    name (``"3"``, ``"23"``, ``"E"``); a lookup by its symbol as the reports and CSVs
    write it (``"s3"``, ``"s23"``, ``"sE"``) finds the same slide.  Iteration and
    ``keys()`` give the names only."""

    __slots__ = ()

    def __missing__(self, key: Any):
        if isinstance(key, str) and key.startswith("s") and dict.__contains__(self, key[1:]):
            return self[key[1:]]
        raise KeyError(key)

    def __contains__(self, key: Any):
        return dict.__contains__(self, key) or (
            isinstance(key, str) and key.startswith("s") and dict.__contains__(self, key[1:]))

    def get(self, key: Any, default: Any = None):
        return self[key] if key in self else default


@record(eq=False)
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

    def __post_init__(self) -> None:
        if type(self.slides) is not Slides:
            object.__setattr__(self, "slides", Slides(self.slides))

    def condition(self, joint: str) -> DyadCondition:
        """The conditioning of the dyad whose joint (or block point) is ``joint``:
        ``m.condition("C").gamma`` is the transmission angle at C [rad]."""
        for c in self.conditions:
            if c.joint == joint:
                return c
        raise KeyError(f"no dyad has the joint {joint!r}; the dyads' joints are "
                       f"{[c.joint for c in self.conditions]}")


# ---------------------------------------------------------------------------
# solver
# ---------------------------------------------------------------------------
class SolveState:
    """What the elements read and write while a linkage is solved.

    ``P``/``L`` hold the solved points and links; ``vel``/``acc`` say which
    derivatives are asked; ``full(x)`` broadcasts a parameter to the result
    shape; ``mark`` updates the feasibility masks; ``condition`` and ``slide``
    record a dyad's conditioning and a prismatic pair's slide.
    """

    def __init__(self, linkage, inputs, shape, order,
                 arena=None):
        self.inputs = inputs
        self.shape = shape
        self.zero = np.broadcast_to(0.0, shape)  # a view: costs no memory
        self.feasible = np.ones(shape, dtype=bool)
        self.regular = np.ones(shape, dtype=bool)
        self.vel, self.acc = order >= 1, order >= 2
        facts = _facts(linkage)
        self.scale = facts.scale
        self.frame = linkage.frame
        self.P = {}
        self.L = {self.frame: LinkState(self.zero, 1.0, 0.0, self.zero, self.zero)}
        self.S = {}
        self.conds = []
        self.index = None
        #: links some element reads (their cosine and sine are kept for it)
        self.needed_links = facts.needed_links
        self._rows = facts.rows[order]
        self._arena = arena  # (rows, *shape): the outputs, allocated in one block
        self._next = 0
        self._tmp = {}
        self.given = []  # the output rows handed out, in order

    def out(self):
        """A fresh output array of the full shape (uninitialised): the next row
        of one block preallocated for every element's outputs."""
        if self._arena is None:
            self._arena = _output_block((self._rows,) + self.shape)
        if self._next < len(self._arena):
            self._next += 1
            row = self._arena[self._next - 1, ...]
            self.given.append(row)
            return row
        return np.empty(self.shape)

    def tmp(self, i: int):
        """Scratch buffer ``i`` (0-7) of the full shape: shared by the elements,
        valid only inside one element's step (never stored in the results)."""
        t = self._tmp.get(i)
        if t is None:
            t = self._tmp[i] = _scratch(i, self.shape)
        return t

    def full(self, x: FloatOrArray):
        x = np.asarray(x, dtype=float)
        if x.shape == self.shape:
            return x
        return np.broadcast_to(x, self.shape) if x.ndim == 0 else x + self.zero

    def mark(self, ok: np.ndarray, sing: FloatOrArray,
             position_singular: Optional[np.ndarray] = None):
        """Update the masks; return the 'bad' mask for the 2x2 solves (None if none).

        ``position_singular``: a mask of positions where the singularity
        leaves the position itself undefined (RPR: the guide's direction when
        the block is at its pivot), so they are irregular even when only
        positions are asked.
        """
        self.feasible &= ok
        if not self.vel:
            if position_singular is not None:
                self.regular &= ok & ~position_singular
            return None
        good = ok & (sing > SINGULAR_TOL)
        self.regular &= good
        return None if good.all() else ~good

    def condition(self, element, joint, sin_gamma,
                  cos_joint=None):
        self.conds.append(DyadCondition(self.index, element.kind, joint, sin_gamma, cos_joint))

    def slide(self, name: str, block: Any, guide: Any, s: Any, v: Any,
              a: Any) -> None:
        self.S[name] = SlideMotion(name, block, guide, s, v, a)


#: positions per chunk of a long one-dimensional sweep (bounded scratch memory)
CHUNK = 1 << 16
_SCRATCH_ROWS = 8
_POOL_SIZE = 1 << 16  # per-thread scratch kept between solves: 8 x 512 KiB
_POOL = threading.local()


def _scratch(i: int, shape: Tuple[int, ...]):
    """Scratch row ``i``: from a per-thread pool reused across solves (so a
    solve does not pay fresh pages for its temporaries) when it is small
    enough, else a new array."""
    size = int(np.prod(shape, dtype=np.int64))
    if i >= _SCRATCH_ROWS or size > _POOL_SIZE:
        return np.empty(shape)
    pool = getattr(_POOL, "block", None)
    if pool is None:
        pool = _POOL.block = np.empty((_SCRATCH_ROWS, _POOL_SIZE))
    return pool[i, :size].reshape(shape)


#: output blocks of up to this many float64 (8 MiB) are kept per thread for reuse
_KEEP_BLOCK = 1 << 20


def _free_refs():
    """What ``sys.getrefcount`` says of an array that only a list holds (measured, as
    interpreters count differently); None where there is no reference count."""
    if not hasattr(sys, "getrefcount"):
        return None
    probe = [np.empty(1)]
    free = sys.getrefcount(probe[0])
    holder = probe[0][:]   # a view holds its base: the count must rise by exactly one
    held = sys.getrefcount(probe[0])
    del holder
    # an interpreter whose count does not see a holder gets no reuse at all
    return free if held == free + 1 and sys.getrefcount(probe[0]) == free else None


_FREE_REFS = _free_refs()


def _output_block(shape: Tuple[int, ...]):
    """A block for a solve's outputs: one of the last two handed out on this
    thread if nothing references it any more (its results were dropped: its
    pages are mapped already, so the next solve pays no page faults), else a
    new one.  A result still held anywhere (any view of the block) keeps its
    block out of reuse, so results are never overwritten."""
    kept = getattr(_POOL, "blocks", None)
    if kept is None:
        kept = _POOL.blocks = []
    if _FREE_REFS is not None:
        for i in range(len(kept)):
            # as many references as a block in a list that nothing else holds
            if kept[i].shape == shape and sys.getrefcount(kept[i]) == _FREE_REFS:
                return kept[i]
    block = np.empty(shape)
    if block.size <= _KEEP_BLOCK:
        kept.insert(0, block)
        del kept[2:]
    return block


class _Facts:
    """What a solve needs to know of a linkage beyond its elements' steps,
    worked out once per linkage (a ``Linkage`` is frozen): the parameters'
    broadcast shape, the designs with finite parameters, the scale, the links
    some element reads and the output rows per order."""

    __slots__ = ("shape", "finite", "scale", "needed_links", "rows", "drivers")

    def __getstate__(self):    # pickle protocols 0 and 1 need it with __slots__
        return {k: getattr(self, k) for k in self.__slots__}

    def __setstate__(self, state: Any) -> None:
        for k, v in state.items():
            setattr(self, k, v)

    def __init__(self, linkage: Linkage) -> None:
        self.shape = linkage.shape
        self.finite = _finite_designs(linkage)
        self.scale = linkage.scale()
        self.needed_links = frozenset(ln for el in linkage.elements for ln in el.needs()[1])
        self.drivers = frozenset(d.link for d in linkage.drivers)
        self.rows = tuple(sum(el._out_rows(order >= 1, order >= 2, linkage.frame)
                              for el in linkage.elements) for order in (0, 1, 2))


def _facts(linkage: Linkage):
    facts = linkage.__dict__.get("_facts")
    if facts is None:
        facts = _Facts(linkage)
        object.__setattr__(linkage, "_facts", facts)
    return facts


def _needed_links(linkage: Linkage):
    return _facts(linkage).needed_links


def _out_rows(linkage: Linkage, order: int):
    return _facts(linkage).rows[order]


def solve(linkage, inputs, order=2,
          on_fail="mask"):
    """Solve positions (and velocities, accelerations) of every point and link.

    Parameters
    ----------
    linkage : Linkage
        Its element parameters may be arrays (a batch of designs), e.g. of
        shape ``(M, 1)`` against inputs of shape ``(N,)``.
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
        Every array has the broadcast shape of the inputs and the parameters.

    Examples
    --------
    >>> import numpy as np
    >>> from mechcli.core.linkage import DriverMotion, four_bar, solve
    >>> m = solve(four_bar(0.1, 0.25, 0.2, 0.3), {1: DriverMotion(np.radians([0, 90]), 10.0)})
    >>> m.links[3].omega.shape
    (2,)
    """
    from mechcli.core.errors import AssemblyError

    if order not in (0, 1, 2):
        raise ValueError(f"order must be 0, 1 or 2, got {order}")
    if on_fail not in ("mask", "raise"):
        raise ValueError(f"on_fail must be 'mask' or 'raise', got {on_fail!r}")
    facts = _facts(linkage)
    shape = _input_shape(linkage, inputs, order, facts.shape)
    finite = facts.finite
    if finite is None and len(shape) == 1 and shape[0] > CHUNK and facts.shape == ():
        st = _solve_chunked(linkage, inputs, shape, order)
    else:
        st = SolveState(linkage, inputs, shape, order)
        with np.errstate(invalid="ignore", over="ignore") if finite is not None else _NO_CONTEXT:
            for idx in linkage.order:
                st.index = idx
                linkage.elements[idx].step(st)
    vel, acc = st.vel, st.acc
    regular, feasible = st.regular, st.feasible
    if finite is not None:
        # a design with an inf/NaN parameter does not assemble (and, above, did
        # not warn): it never poisons the masks of the other designs
        feasible &= finite
        regular &= finite
    if not vel:
        regular &= feasible
    if on_fail == "raise" and not np.all(regular):
        bad = int(np.size(regular) - np.count_nonzero(regular))
        raise AssemblyError(f"the linkage cannot be assembled (or is at a dead point) at "
                            f"{bad} of {np.size(regular)} input positions")
    full = st.full
    points = {n: PointMotion(full(p.x), full(p.y), p.vx, p.vy, p.ax, p.ay)
              for n, p in st.P.items()}
    links = {n: LinkMotion(full(k.theta), None if k.w is None or not vel else full(k.w),
                           None if k.al is None or not acc else full(k.al))
             for n, k in st.L.items()}
    return LinkageMotion(order, feasible, regular, points, links, st.S, tuple(st.conds))


_NO_CONTEXT = contextlib.nullcontext()


def _solve_chunked(linkage, inputs, shape, order):
    """Solve a long sweep (one linkage, 1-D inputs) chunk by chunk: the outputs
    are preallocated at the full length and every chunk's elements write into
    their slices, so the scratch memory is bounded by the chunk size.  Returns
    a :class:`SolveState` holding the full-length results."""
    n = shape[0]
    whole = SolveState(linkage, inputs, shape, order)
    arena = whole._arena = np.empty((whole._rows, n))
    bounds = np.linspace(0, n, -(-n // CHUNK) + 1).astype(int)  # chunks of >= CHUNK/2
    copies = {}
    for a, b in zip(bounds[:-1], bounds[1:]):
        sub = {k: DriverMotion(*(v[a:b] if np.ndim(v) else v for v in (m.q, m.dq, m.ddq)))
               for k, m in inputs.items()}
        st = SolveState(linkage, sub, (b - a,), order, arena[:, a:b])
        for idx in linkage.order:
            st.index = idx
            linkage.elements[idx].step(st)
        whole.feasible[a:b] = st.feasible
        whole.regular[a:b] = st.regular
        seen = {id(row): arena[r] for r, row in enumerate(st.given)}
        for k, m in sub.items():
            if isinstance(m.q, np.ndarray) and np.ndim(inputs[k].q) == 1:
                seen.setdefault(id(m.q), np.asarray(inputs[k].q))

        def full(v, key, a=a, b=b,
                 seen=seen):
            if not isinstance(v, np.ndarray) or v.shape != (b - a,):
                return v
            if id(v) in seen:
                return seen[id(v)]
            if v.strides[0] == 0:  # a constant broadcast over the chunk
                res = np.broadcast_to(v[:1], shape)
            else:
                res = copies.get(key)
                if res is None:
                    res = copies[key] = np.empty(shape, dtype=v.dtype)
                res[a:b] = v
            seen[id(v)] = res
            return res

        P = {nm: PointState(*(full(getattr(p, f), ("P", nm, f)) for f in PointState.__slots__))
             for nm, p in st.P.items()}
        L = {ln: LinkState(*(full(getattr(k, f), ("L", ln, f)) if f in ("theta", "w", "al")
                             else None for f in LinkState.__slots__))
             for ln, k in st.L.items()}
        S = {nm: dataclasses.replace(sl, **{f: full(getattr(sl, f), ("S", nm, f))
                                            for f in ("s", "v", "a")})
             for nm, sl in st.S.items()}
        conds = [dataclasses.replace(c, sin_gamma=full(c.sin_gamma, ("C", i, "sin")),
                                     cos_joint=full(c.cos_joint, ("C", i, "cos")))
                 for i, c in enumerate(st.conds)]
    whole.P, whole.L, whole.S, whole.conds = P, L, S, conds
    return whole


def _input_shape(linkage: Linkage, inputs: Dict[int, Any], order: int,
                 params_shape: Optional[Tuple[int, ...]] = None):
    """Broadcast shape of the inputs (the rates that ``order`` uses) and the
    linkage parameters; a clear ValueError naming every shape when they do not
    broadcast, or when a driver has no input or an input has no driver."""
    if params_shape is None:
        params_shape = linkage.shape
    drivers = _facts(linkage).drivers
    if len(inputs) != len(drivers) or any(d not in inputs for d in drivers):
        for d in sorted(drivers):
            if d not in inputs:
                raise LinkageDefinitionError(f"no input given for driver link {d} (inputs "
                                             f"are needed for links {sorted(drivers)})")
    for link, m in inputs.items():
        if link not in drivers:
            raise LinkageDefinitionError(f"an input is given for link {link!r}, which is not "
                                         f"driven (drivers: links {sorted(drivers)})")
        if not isinstance(m, DriverMotion):
            raise TypeError(f"the input of driver link {link} must be a DriverMotion(q, dq, ddq),"
                            f" got {type(m).__name__}")
    shapes = [np.shape(v) for m in inputs.values() for v in (m.q, m.dq, m.ddq)]
    distinct = set(shapes)
    distinct.add(params_shape)
    distinct.discard(())
    if len(distinct) <= 1:  # the common case: one shape, or scalars beside it
        used = {sh for i, sh in enumerate(shapes) if i % 3 <= order and sh}
        return distinct.pop() if used or params_shape else ()
    try:
        np.broadcast_shapes(*shapes, params_shape)
        return np.broadcast_shapes(*(sh for i, sh in enumerate(shapes) if i % 3 <= order),
                                   params_shape)
    except ValueError:
        named = ", ".join(f"{attr} of link {k} {np.shape(getattr(m, attr))}"
                          for k, m in inputs.items() for attr in ("q", "dq", "ddq"))
        raise ValueError("the driver inputs and the linkage parameters do not broadcast "
                         f"together: {named}, linkage parameters {params_shape}") from None


def _finite_designs(linkage: Linkage):
    """Mask (of the parameters' shape) of the designs whose parameters are all
    finite; None when every one is (the common case)."""
    params = [p for el in linkage.elements for p in el.parameters()]
    if all(np.isfinite(p).all() for p in params):
        return None
    return functools.reduce(np.logical_and, (np.isfinite(p) for p in params), True)


def kinematic_coefficients(linkage: Linkage, q: np.ndarray,
                           followers: Optional[Dict[int, Any]] = None,
                           order: int = 2) -> LinkageMotion:
    """Velocity and acceleration coefficients (类速度, 类加速度) at input positions ``q``.

    The linkage is solved at unit input speed and zero input acceleration, so
    every velocity is a first derivative with respect to the input
    (``links[n].omega`` = dθn/dφ, ``points[P].vx`` = dxP/dφ [m/rad]) and every
    acceleration a second derivative (``links[n].alpha`` = d²θn/dφ²).  At any
    input speed ω1 and acceleration α1 the motion follows as
    ``ω_n = ω1 dθn/dφ`` and ``α_n = α1 dθn/dφ + ω1² d²θn/dφ²``: what the
    equivalent inertia Je(φ) = Σ m (v_S/ω1)² + J (ω/ω1)², its exact derivative
    dJe/dφ and the equivalent moment need (chapter 6).

    Parameters
    ----------
    linkage : Linkage
    q : array
        Positions of the primary (first) driver [rad or m].
    followers : dict, optional
        ``{link: (ratio, phase)}`` of secondary drivers: q_k = phase + ratio q.
    order : {1, 2}
    """
    q = np.asarray(q, dtype=float)
    drivers = linkage.drivers
    missing = [d.link for d in drivers[1:] if d.link not in (followers or {})]
    if missing:
        raise LinkageDefinitionError(
            f"links {missing} are secondary drivers: give followers={{link: (ratio, phase)}} "
            f"for each (q_k = phase + ratio * q of link {drivers[0].link})")
    inputs = {drivers[0].link: DriverMotion(q, 1.0, 0.0)}
    for link, (ratio, phase) in (followers or {}).items():
        inputs[link] = DriverMotion(phase + ratio * q, ratio, 0.0)
    return solve(linkage, inputs, order=order)
