"""The kinetostatic model of a linkage: bodies, loads, pairs and results.

:func:`topology` derives the kinematic pairs of a linkage from its elements
(each element declares its own, :meth:`~mechcli.core.linkage.elements.Element.pairs`);
:class:`Body` and :class:`Load` describe the masses and the external loads;
:class:`ForceResult` is what :func:`~mechcli.core.linkage.kinetostatics.solve_forces`
returns.  Conventions: see :mod:`mechcli.core.linkage.kinetostatics`.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Dict, Optional, Tuple

import numpy as np

from mechcli.core.linkage.engine import Linkage
from mechcli.core.records import record

#: condition number of an element block above which a position is flagged
#: (reactions then carry ~cond * 1e-16 relative error)
COND_FLAG = 1e8


class ForceModelError(ValueError):
    """The linkage, bodies or loads cannot be modelled (bad point or link)."""

    def __init__(self, message: str, what: Any = None) -> None:
        super().__init__(message)
        self.what = what


# ---------------------------------------------------------------------------
# model description
# ---------------------------------------------------------------------------
@record
class Body:
    """Inertia of one moving link.

    The centre of mass is ``origin + (along + i*normal) * exp(i*theta_link)``
    (as :class:`~mechcli.core.linkage.PointOnLink`); ``mass`` [kg] and
    ``inertia`` J_S about the centre of mass [kg m^2].
    """

    link: int
    mass: float = 0.0
    inertia: float = 0.0
    origin: Optional[str] = None
    along: float = 0.0
    normal: float = 0.0


@record
class Load:
    """An external force (at a point of a link) or torque on a link.

    ``fx``, ``fy`` [N] (a force) or ``torque`` [N m]: scalars or arrays over
    the positions (already multiplied by any table factor and active mask).
    The force acts at ``origin + (along + i*normal) * exp(i*theta_link)``
    (default: the link's centre of mass).  With ``relative`` the force's
    components are in the link's own axes (along, left normal).
    """

    name: str
    link: int
    fx: object = 0.0
    fy: object = 0.0
    torque: object = 0.0
    origin: Optional[str] = None
    along: float = 0.0
    normal: float = 0.0
    relative: bool = False


@record
class Pair:
    """A kinematic pair between links ``i < j`` at point ``point``.

    ``kind`` is ``"R"`` (revolute) or ``"P"`` (prismatic; ``guide`` is the
    link that carries the guide line, ``block`` the sliding one).
    """

    i: int
    j: int
    kind: str
    point: str
    element: int
    guide: Optional[int] = None
    block: Optional[int] = None

    @property
    def label(self):
        sep = "_" if self.i >= 10 or self.j >= 10 else ""
        return f"{self.i}{sep}{self.j}"


@record
class Topology:
    """Pairs, drivers and link reference points of a linkage.

    ``frames[link] = (origin, second)``: the point the link's local
    coordinates start from and the second point that fixes its length (None
    for a block or a guide with no point on it); the default centre of mass is
    their midpoint (or the origin).
    """

    linkage: Linkage
    links: Tuple[int, ...]
    pairs: Tuple[Pair, ...]
    members: Dict[str, frozenset]
    owner: Dict[str, int]
    frames: Dict[int, Tuple[str, Optional[str]]]
    blocks: Tuple[Tuple[int, Tuple[int, ...], Tuple[int, ...]], ...]
    #: links meeting at each point, the point's owner first, then in the order they join
    links_at: Dict[str, Tuple[int, ...]] = dataclasses.field(default_factory=dict)


class _TopologyBuilder:
    """What an element's ``pairs`` method declares its points and pairs on.

    A point belongs to the link that defines it (``owner``); ``members`` are
    all the links that meet at a point; ``frames[link]`` the link's reference
    points (see :class:`Topology`).
    """

    def __init__(self, frame):
        self.frame = frame
        self.owner: Dict[str, int] = {}
        self.members: Dict[str, list] = {}
        self.frames: Dict[int, list] = {}
        self.pairs = []
        self.index = None

    def put(self, point: str, link: int) -> None:
        links = self.members.setdefault(point, [])
        if link not in links:
            links.append(link)

    def new_point(self, point: str, link: int) -> None:
        """``point`` is made by (fixed on) ``link``."""
        self.owner[point] = link
        self.put(point, link)

    def revolute(self, point, link):
        """``link`` is pinned at the known ``point`` to the link that owns it."""
        a = self.owner[point]
        self.put(point, link)
        self.pairs.append(Pair(min(a, link), max(a, link), "R", point, self.index))

    def joint(self, point, a, b):
        """A revolute pair between links ``a`` and ``b`` at ``point`` (already on ``a``)."""
        self.put(point, b)
        self.pairs.append(Pair(min(a, b), max(a, b), "R", point, self.index))

    def prismatic(self, guide, block, point):
        """``block`` slides on a guide carried by ``guide``; ``point`` is the block's pin."""
        self.pairs.append(Pair(min(guide, block), max(guide, block), "P", point, self.index,
                               guide, block))

    def fail(self, message: str, what: Any):
        raise ForceModelError(message, what)


def topology(linkage):
    """Derive the pairs of a linkage from its elements (see the module notes)."""
    tb = _TopologyBuilder(linkage.frame)
    blocks = []
    for idx in linkage.order:
        el = linkage.elements[idx]
        tb.index = idx
        start = len(tb.pairs)
        new_links = el.pairs(tb)
        if new_links:
            blocks.append((idx, tuple(new_links), tuple(range(start, len(tb.pairs)))))
    links = tuple(ln for _, nl, _ in blocks for ln in nl)
    return Topology(linkage, links, tuple(tb.pairs),
                    {k: frozenset(v) for k, v in tb.members.items()}, tb.owner,
                    {k: (v[0], v[1]) for k, v in tb.frames.items()}, tuple(blocks),
                    {k: tuple(v) for k, v in tb.members.items()})


def com_of(topo: Topology, body: Optional[Body], link: int):
    """``(origin, along, normal)`` of a link's centre of mass; ``along is None``
    means the midpoint of the link's two points (the default)."""
    if body is not None and body.origin is not None:
        return body.origin, body.along, body.normal
    origin, second = topo.frames[link]
    return (origin, 0.0, 0.0) if second is None else (origin, None, None)


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------
@record
class PairForce:
    """Reaction of a pair over the positions: force of ``i`` on ``j`` (fx, fy) [N]
    and, for a prismatic pair, the couple of ``i`` on ``j`` [N m] about the
    pair's point (zero for a revolute pair)."""

    pair: Pair
    fx: np.ndarray
    fy: np.ndarray
    couple: np.ndarray

    @property
    def magnitude(self):
        return np.hypot(self.fx, self.fy)


@record
class ForceResult:
    """Kinetostatics over the positions of a motion.

    Attributes
    ----------
    balancing : dict
        ``{driver link: array}``: torque [N m] on a crank, force [N] along a
        slider driver's line.
    pairs : list of PairForce
        In the order of the topology's pairs.
    frame_force : (ndarray, ndarray)
        Force transmitted to the frame (through its pairs and the drives) [N].
    frame_moment : ndarray
        Moment transmitted to the frame about the origin (0, 0) [N m].
    input_power : ndarray
        Σ balancing · driver speed [W].
    cond : ndarray
        Largest 1-norm condition number of the (scaled) element blocks.
    power_residual : ndarray
        Virtual-power balance Σ balancing·ω* + Σ known loads·v* (ω*, v* per unit
        primary input speed): zero up to round-off (a second route to Mb).
    force_residual : ndarray
        |Σ external + gravity + frame reactions − Σ m a_S| over the mechanism [N].
    active : dict
        ``{load name: bool array}`` (only for conditional loads; set by callers).
    """

    balancing: Dict[int, np.ndarray]
    pairs: list
    frame_force: Tuple[np.ndarray, np.ndarray]
    frame_moment: np.ndarray
    input_power: np.ndarray
    cond: np.ndarray
    power_residual: np.ndarray
    force_residual: np.ndarray
    com: Dict[int, Tuple[np.ndarray, np.ndarray]]
