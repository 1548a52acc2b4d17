"""The structure of a linkage's kinetostatic system, worked out once per topology.

:func:`plan` gives the :class:`Plan` of a :class:`~.force_model.Topology` (cached on
it): the unknowns, which equations each one enters and how its coefficient is
computed, and, per element block in the reverse solving order, where each
coefficient goes in the block's matrix, which solved unknowns of later blocks enter
its right-hand side, and the block's closed-form layout (:func:`.dyad_statics.layout`).
:func:`~.kinetostatics.solve_forces` then only computes the coefficients and solves.

A coefficient is described by a small record, computed per call from the motion:

* :class:`Constant`: the same at every position (the +-1 of a force component in
  its own force equation, of a couple or a balancing torque in the moment one);
* :class:`Arm`: the moment about the link's reference point of a unit force
  component at a point (the moment arm, scaled by the length L);
* :class:`Along`: a unit force along a :class:`PairNormal` (a prismatic pair's
  guide normal) or a :class:`DriverLine` (a slider driver's line), in one of the
  link's three equations.

Unknowns are solved scaled: forces as they are, couples and balancing torques
divided by the length scale L (the moment rows are divided by L), so every
coefficient is dimensionless.  The link equations are ΣFx, ΣFy, ΣM in rows
``3 i``, ``3 i + 1``, ``3 i + 2`` of the i-th moving link (``Plan.eq_of``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mechcli.core.linkage import dyad_statics
from mechcli.core.linkage.elements import Element
from mechcli.core.linkage.force_model import ForceModelError
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:

    from mechcli.core.linkage.force_model import Topology

__all__ = ["Constant", "Arm", "Along", "PairNormal", "PairLine", "DriverLine", "Plan",
           "plan", "actuated_pair"]

#: the rows of a link's equations: ΣFx, ΣFy, ΣM (offsets from ``Plan.eq_of[link]``)
FX, FY, M = 0, 1, 2


@record
class Constant:
    """A coefficient that is ``value`` at every position (+-1)."""

    value: float


@record
class Arm:
    """The moment about ``link``'s reference point of a unit force component at
    ``point``, times ``sign``: ``-sign dy / L`` for the x component (``axis`` 0),
    ``sign dx / L`` for the y component (``axis`` 1), with ``(dx, dy)`` the lever
    from the reference point to ``point``."""

    link: int
    point: str
    sign: float
    axis: int


@record(eq=False)
class PairNormal:
    """The left normal of the guide of ``topo.pairs[pair]`` (a prismatic pair).

    A direction is compared and hashed by identity (the plan makes one per pair,
    ``Plan.normal``, or per slider driver): a call caches the direction's cosine
    and sine by it at the cost of a pointer's hash."""

    pair: int


@record(eq=False)
class DriverLine:
    """The line of the slider driver of ``link`` (compared by identity, as
    :class:`PairNormal`)."""

    link: int


@record(eq=False)
class PairLine:
    """The line of sliding of ``topo.pairs[pair]`` (a prismatic pair driven by an
    actuator), in the direction its slide ``s`` grows (compared by identity, as
    :class:`PairNormal`)."""

    pair: int


@record
class Along:
    """A unit force along ``direction`` (a :class:`PairNormal` or a
    :class:`DriverLine`) at ``point`` of ``link``, times ``sign``, in the link's
    equation ``row`` (:data:`FX`, :data:`FY`: its components; :data:`M`: its
    moment about the link's reference point, scaled by L)."""

    link: int
    point: str
    direction: object
    sign: float
    row: int


class Plan:
    """The structure of a linkage's kinetostatic system (see the module notes).

    Attributes
    ----------
    eq_of : dict
        ``{link: first row}`` of each moving link's three equations.
    columns : list
        Per unknown, ``[(row, coefficient record), ...]``.
    pair_cols, driver_cols : list, dict
        The two unknowns of each pair (its force components; a prismatic pair's
        normal force and couple), the unknown of each driver (by link).
    normal : dict
        ``{pair index: PairNormal}`` of every prismatic pair.
    is_couple : list of bool
        Per unknown, whether it is a couple or torque (solved divided by L).
    nrows : int
        Rows of the whole system (three per moving link).
    blocks : list
        Per element block, from the last element back to the drivers, a tuple
        ``(unknowns, rows, entries, known, layout)``: its unknowns and rows,
        ``(local row, local column, coefficient)`` of its matrix, ``(local row,
        unknown, coefficient)`` of the solved unknowns on its right-hand side,
        and its closed-form layout (None: the general elimination).
    ref_point : dict
        ``{link: point}``: the outer pair's point of each link of a closed-form
        block, about which the link may take its moments (the same solution; that
        pair then drops out of the moment equation with no pass over memory).
    all_closed : bool
        Every block has a closed-form layout.
    direction_of : dict
        ``{link: element}``: the element that makes the link, where it can give
        the cosine and sine of the link's angle from its points
        (:meth:`~mechcli.core.linkage.elements.Element.direction`).
    """

    def __init__(self, topo):
        linkage = topo.linkage
        self.eq_of = {link: 3 * i for i, link in enumerate(topo.links)}
        self.columns, self.is_couple = [], []
        self.pair_cols, self.driver_cols, self.normal = [], {}, {}
        for pi, pr in enumerate(topo.pairs):
            self.pair_cols.append((len(self.columns), len(self.columns) + 1))
            if pr.kind == "R":
                self._unknowns(*self._revolute(pr, linkage.frame), couple=False)
            else:
                normal, couple = self._prismatic(pi, pr, linkage.frame)
                self._unknowns(normal, couple=False)
                self._unknowns(couple, couple=True)
        self.actuated = {}
        for d in linkage.drivers:
            self.driver_cols[d.link] = len(self.columns)
            e = self.eq_of[d.link]
            act = getattr(d, "actuator", None)
            if act is not None:  # a force along an actuated slide, on its two links
                pi = self.actuated[d.link] = actuated_pair(topo, act)
                pr, cols = topo.pairs[pi], []
                for link, sign in ((pr.block, 1.0), (pr.guide, -1.0)):
                    if link != linkage.frame:
                        cols += self._along(link, sign, pr.point, PairLine(pi))
                self._unknowns(cols, couple=False)
            elif d.rotary:  # the torque (scaled)
                self._unknowns([(e + M, Constant(1.0))], couple=True)
            else:
                self._unknowns(self._along(d.link, 1.0, d.point, DriverLine(d.link)),
                               couple=False)
        self.nrows = 3 * len(topo.links)
        self.blocks, self.ref_point = [], {}
        solved = []
        for idx, new_links, pidx in reversed(topo.blocks):
            block = self._block(topo, idx, new_links, pidx, solved)
            self.blocks.append(block)
            solved += block[0]
            self._reference_points(topo, new_links, pidx, block[-1])
        if self.actuated:
            # the effort enters at a slide, not at the driver whose angle is given: the
            # driver's block lacks an unknown and the slide's has one more, so the
            # system is no longer block-triangular; solved whole (the general elimination)
            unk = list(range(len(self.columns)))
            entries = [(r, u, spec) for u in unk for r, spec in self.columns[u]]
            if len(unk) != self.nrows:  # pragma: no cover - a determinate linkage
                raise ForceModelError("the actuated linkage is not statically determinate")
            self.blocks, self.ref_point = [(unk, list(range(self.nrows)), entries, [], None)], {}
        self.all_closed = all(blk[-1] is not None for blk in self.blocks)
        self.direction_of = {ln: el for el in linkage.elements for ln in el.makes()[1]
                             if type(el).direction is not Element.direction}

    def _unknowns(self, *columns: Any, couple: FloatOrArray) -> None:
        for col in columns:
            self.columns.append(col)
            self.is_couple.append(couple)

    def _revolute(self, pr: Any, frame: int):
        """The x and y columns of a revolute pair's reaction (of i on j: + on j,
        - on i; the frame has no equations)."""
        cx, cy = [], []
        for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
            if link == frame:
                continue
            e = self.eq_of[link]
            cx += [(e + FX, Constant(sign)), (e + M, Arm(link, pr.point, sign, 0))]
            cy += [(e + FY, Constant(sign)), (e + M, Arm(link, pr.point, sign, 1))]
        return cx, cy

    def _prismatic(self, pi: int, pr: Any, frame: int):
        """The normal-force and couple columns of a prismatic pair."""
        cn, cm = [], []
        normal = self.normal[pi] = PairNormal(pi)
        for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
            if link == frame:
                continue
            cn += self._along(link, sign, pr.point, normal)
            cm.append((self.eq_of[link] + M, Constant(sign)))  # the couple (scaled)
        return cn, cm

    def _along(self, link: int, sign: Any, point: str, direction: Any):
        e = self.eq_of[link]
        return [(e + row, Along(link, point, direction, sign, row)) for row in (FX, FY, M)]

    def _block(self, topo, idx, new_links, pidx,
               solved):
        """One element block ``(unknowns, rows, entries, known, layout)``."""
        el = topo.linkage.elements[idx]
        unk = [u for pi in pidx for u in self.pair_cols[pi]]
        if el.is_driver:
            unk.append(self.driver_cols[el.link])
        rows = [self.eq_of[ln] + c for ln in new_links for c in range(3)]
        if len(unk) != len(rows):  # pragma: no cover - every engine element is determinate
            raise ForceModelError(f"element {idx} is not statically determinate")
        row_pos = {r: i for i, r in enumerate(rows)}
        entries = [(row_pos[r], jc, spec) for jc, u in enumerate(unk)
                   for r, spec in self.columns[u] if r in row_pos]
        known = [(row_pos[r], u, spec) for u in solved for r, spec in self.columns[u]
                 if r in row_pos]
        # the closed-form layout of the block (a driver or a dyad), if it has one
        cols_of_rows = [{} for _ in unk]
        for i, jc, spec in entries:
            cols_of_rows[jc][i] = type(spec) is Constant
        kind_of = [(topo.pairs[pi].kind,
                    tuple(k for k, ln in enumerate(new_links)
                          if ln in (topo.pairs[pi].i, topo.pairs[pi].j)))
                   for pi in pidx]
        lay = dyad_statics.layout(kind_of, cols_of_rows, len(rows))
        return unk, rows, entries, known, lay

    def _reference_points(self, topo, new_links, pidx,
                          lay):
        """A closed-form block's links may take their moments about their outer
        pair's point instead of the centre of mass (the same solution): that pair
        then drops out of the moment equation with no pass over memory."""
        if type(lay) is dyad_statics.DyadLayout:
            for ln, outer in zip(new_links, (lay.a, lay.b)):
                self.ref_point[ln] = topo.pairs[pidx[outer.cols[0] // 2]].point
        elif lay is not None and len(pidx) == 1 and len(new_links) == 1:
            self.ref_point[new_links[0]] = topo.pairs[pidx[0]].point


def plan(topo: Topology) -> Plan:
    """The :class:`Plan` of ``topo``, built on first use and cached on it."""
    p = topo.__dict__.get("_force_plan")
    if p is None:
        p = Plan(topo)
        object.__setattr__(topo, "_force_plan", p)
    return p


def actuated_pair(topo: Topology, name: str):
    """The index in ``topo.pairs`` of the prismatic pair of the RPR dyad whose slide is
    called ``name`` (an actuator: a cylinder between two pivots).

    Raises
    ------
    ForceModelError
        No RPR dyad's slide has that name.
    """
    from mechcli.core.linkage.elements import RPR

    frame = topo.linkage.frame
    for pi, pr in enumerate(topo.pairs):
        el = topo.linkage.elements[pr.element]
        if pr.kind == "P" and type(el) is RPR and el.slide_names(frame)[0] == name:
            return pi
    raise ForceModelError(f"no RPR dyad's slide is called '{name}' (an actuator is the "
                          f"slide of a cylinder between two pivots)", ("slide", name))
