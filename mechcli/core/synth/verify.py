"""Every design checked on the linkage engine.

:func:`verify` moves a :class:`~mechcli.core.synth.design.LinkageDesign`
through its prescribed positions with :func:`mechcli.core.linkage.solve` -- the
same engine ``mechcli kin`` uses -- and reports

* the residual at every prescribed position: the distance between the engine's
  point and the prescribed one, and the slide error, divided by the linkage's
  size, and the angle error in radians (round-off for an exact method, the
  approximation error for least squares);
* the Grashof type of the design (:mod:`mechcli.core.grashof`);
* the smallest transmission angle over the motion from position 1 to the last;
* the defects: a **branch** (circuit) defect when the engine, assembled as in
  position 1, reaches a prescribed position only in the other assembly mode; a
  **circuit** defect when the crank cannot move from one position to the next
  without disassembly or a dead point, in either direction; an **order**
  defect when no direction of the crank visits the positions in the
  prescribed order.

A design from the time ratio K has no prescribed positions: its residuals are
the relative errors of K (and ψ, or the stroke H) that the Grashof core
computes from the designed lengths.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple, cast

import numpy as np

from mechcli.core.linkage.engine import DriverMotion, Linkage, solve
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import LinkageMotion
    from mechcli.core.synth.design import LinkageDesign

#: samples of the crank path per radian when looking for gaps and dead points
#: (0.25° apart; a gap narrower than that between two positions can be missed,
#: the positions themselves are always solved)
PATH_DENSITY = 4 * 180 / math.pi
#: a residual above this (relative) is not round-off: the branch test compares
BRANCH_TOL = 1e-6
TWO_PI = 2 * math.pi
#: sin γ at or below this is a dead point (the transmission angle is 0 to round-off)
DEAD_POINT_SIN = 1e-9


@record
class Defect:
    """One defect of a design.

    ``kind`` is ``"assembly"`` (the linkage cannot be assembled at a position
    in either mode), ``"branch"``, ``"circuit"`` or ``"order"``; ``position`` the
    1-based prescribed position where it shows (the second of the pair that
    cannot be joined for a circuit defect; None for order); ``at`` the crank
    angle [rad] of the first gap or dead point met, when there is one.
    """

    kind: str
    position: Optional[int] = None
    at: Optional[float] = None


@record
class Verification:
    """What the engine says of a design.

    Attributes
    ----------
    residuals : ndarray, shape (N,)
        Per prescribed position (or per checked figure for a design from K):
        relative residual (see the module docstring); NaN where the design does
        not assemble in its own mode.
    residual_max : float
        Largest finite residual (0 when there is none).
    grashof_type : str
        The core's type name (``crank_rocker`` …; ``crank``/``no_crank`` for a
        slider-crank; the guide-bar's kind).
    input_turns : bool
        The crank turns fully.
    gamma_min : float or None
        Smallest transmission angle over the checked motion [rad].
    direction : int
        +1 the crank turns counter-clockwise from position 1 to the last, -1
        clockwise, 0 when there is no motion to check or when an input that
        does not turn fully reverses between positions.
    start, stop : float
        The checked input motion (unwrapped: ``stop`` is reached from ``start``
        in ``direction``; when the input reverses, ``stop`` is the last
        position) [rad]; a full turn for a design from K.
    defects : tuple of Defect
    driver : int
        The driving link that was checked (1 the crank AB, 3 the rocker CD).
    cranks : tuple of int
        The links of a four-bar that turn fully relative to the frame.
    linkage, inputs
        The linkage that was moved (the design's own, or driven by its rocker)
        and its input at each prescribed position [rad] (None for a design from K).
    """

    residuals: np.ndarray
    residual_max: float
    grashof_type: str
    input_turns: bool
    gamma_min: Optional[float]
    direction: int
    start: float
    stop: float
    defects: Tuple[Defect, ...]
    driver: int = 1
    linkage: Optional[Linkage] = None
    inputs: Optional[np.ndarray] = None
    cranks: Tuple[int, ...] = ()


def _flipped(linkage: Linkage) -> Linkage:
    """The same linkage in the other assembly mode (every dyad's branch negated)."""
    return Linkage(linkage.frame, tuple(
        # every element with a branch (a dyad) is a record, i.e. a dataclass
        dataclasses.replace(el, branch=-el.branch)  # type: ignore[type-var]
        if hasattr(el, "branch") else el
        for el in linkage.elements))


def _residuals(design: LinkageDesign, m: LinkageMotion) -> np.ndarray:
    """Relative residual at each prescribed position (NaN where infeasible)."""
    size = design.size
    res = np.zeros(len(cast(np.ndarray, design.inputs)))  # a design with positions
    for name, target in design.points.items():
        p = m.points[name]
        res = np.maximum(res, np.abs((p.x + 1j * p.y) - np.asarray(target)) / size)
    for link, target in design.angles.items():
        d = np.angle(np.exp(1j * (m.links[link].theta - np.asarray(target, dtype=float))))
        res = np.maximum(res, np.abs(d))
    for name, target in design.slides.items():
        res = np.maximum(res, np.abs(m.slides[name].s - np.asarray(target, dtype=float)) / size)
    return np.where(m.feasible, res, np.nan)


def _type(design: LinkageDesign, driver: int = 1) -> Any:
    """(type name, the input turns, γmin over a turn or None, figures for a K design)."""
    from mechcli.core.grashof.fourbar import (
        analyse_fourbar,
        analyse_guide_bar,
        analyse_slider_crank,
    )
    L = design.lengths
    if design.kind == "four_bar":
        # crossed: A and C on the same side of the diagonal BD in position 1 (AB and CD
        # cross): a parallelogram's lengths then make an antiparallelogram
        P = design.pivots
        a, b, c, d = (complex(*P[k]) for k in ("A", "B1", "C1", "D"))
        side = (lambda z: ((d - b).conjugate() * (z - b)).imag)
        crossed = side(a) * side(c) > 0
        an = analyse_fourbar([L["l1"], L["l2"], L["l3"], L["l4"]], input_link=driver,
                             crossed=crossed, require_closure=False)
        mt = an.merit
        figures: Dict[str, Any] = {"K": float(mt.K[0]), "psi": float(mt.psi[0]),
                                   "theta": float(mt.theta[0])} if mt.has_limits[0] else {}
        figures["cranks"] = an.klass.cranks(0)
        return an.klass.types[0], bool(mt.input_turns[0]), float(mt.gamma_min[0]), figures
    if design.kind == "slider_crank":
        sc = analyse_slider_crank(L["l1"], L["l2"], L.get("e", 0.0))
        figures = {"K": sc.K, "H": sc.stroke, "theta": sc.theta} if sc.crank_exists else {}
        return ("crank" if sc.crank_exists else "no_crank"), bool(sc.crank_exists), \
            (math.pi / 2 - sc.alpha_max if sc.crank_exists else None), figures
    if design.kind == "guide_bar":
        gb = analyse_guide_bar(L["l1"], L["l4"], L.get("e", 0.0))
        figures = {"K": gb.K, "psi": gb.psi, "theta": gb.theta} \
            if gb.kind == "oscillating" else {}
        return gb.kind, gb.kind in ("oscillating", "rotating"), gb.gamma_min, figures
    raise ValueError(f"unknown design kind {design.kind!r}")


def _orders(q: np.ndarray) -> List[Tuple[int, np.ndarray]]:
    """Directions (+1, -1) that visit the positions in order within one turn,
    with their unwrapped paths; a repeated position is a zero step."""
    out = []
    for sign in (1, -1):
        steps = np.mod(sign * np.diff(q), TWO_PI)
        if len(q) > 2 and steps.sum() >= TWO_PI * (1 - 1e-12):
            continue
        out.append((sign, np.concatenate([[0.0], np.cumsum(steps)])))
    out.sort(key=lambda t: t[1][-1])       # the shorter way round first
    return out


def _path_check(linkage: Linkage, q0: float, sign: int, travel: np.ndarray
               ) -> Tuple[Optional[int], Optional[float], Optional[float]]:
    """Solve along one direction; (index of the first position not reached, angle of the
    first bad sample or None, γmin over the path or None)."""
    total = travel[-1]
    n = max(2, int(math.ceil(total * PATH_DENSITY)) + 1)
    s = np.union1d(np.linspace(0.0, total, n), travel)
    m = solve(linkage, {linkage.drivers[0].link: DriverMotion(q0 + sign * s, 1.0)}, order=1)
    ok = m.regular
    gamma = None
    if m.conditions:
        g = m.conditions[0].gamma
        if ok.any():
            gamma = float(np.min(g[ok]))
    if ok.all():
        return None, None, gamma
    bad = int(np.argmax(~ok))
    reached = int(np.searchsorted(travel, s[bad], side="left"))   # position index after gap
    return reached, float(q0 + sign * s[bad]), gamma


def _crank_path(linkage: Linkage, q: np.ndarray
                ) -> Tuple[int, float, Optional[float], Optional[Defect]]:
    """A crank turns one way: the positions must come in order within one turn."""
    orders = _orders(q)
    if not orders:
        return 0, float(q[0]), None, Defect("order")
    first_fail = None
    for sign, travel in orders:
        reached, at, g = _path_check(linkage, q[0], sign, travel)
        if reached is None:
            return sign, float(q[0] + sign * travel[-1]), g, None
        if first_fail is None:
            first_fail = (reached, at)
    assert first_fail is not None   # orders is not empty and every one failed
    return 0, float(q[0]), None, Defect("circuit", first_fail[0] + 1, first_fail[1])


def _rocker_path(linkage: Linkage, q: np.ndarray
                 ) -> Tuple[int, float, Optional[float], Optional[Defect]]:
    """An input that does not turn fully may reverse: each step from one position to
    the next must be possible one way or the other without disassembly."""
    signs, gammas, stop = [], [], float(q[0])
    for i in range(len(q) - 1):
        fail = None
        for sign, travel in _orders(q[i:i + 2]):
            reached, at, g = _path_check(linkage, q[i], sign, travel)
            if reached is None:
                signs.append(sign)
                stop = float(q[i] + sign * travel[-1])
                if g is not None:
                    gammas.append(g)
                break
            fail = fail or at
        else:
            return 0, float(q[0]), None, Defect("circuit", i + 2, fail)
    direction = signs[0] if all(x == signs[0] for x in signs) else 0
    return direction, stop, (min(gammas) if gammas else None), None


def _driven_by_rocker(design: LinkageDesign, C: np.ndarray) -> LinkageDesign:
    """The four-bar of *design* driven by its rocker CD (link 3) about D: the crank AB
    becomes the dyad's second link.  *C*: the joint C at each prescribed position."""
    from mechcli.core.linkage.elements import RRR, Crank, Ground, PointOnLink
    from mechcli.core.synth.design import branch_of
    L, P = design.lengths, design.pivots
    a, d = complex(*P["A"]), complex(*P["D"])
    b1, c1 = complex(*P["B1"]), complex(C[0])
    elements = [Ground("A", a.real, a.imag), Ground("D", d.real, d.imag),
                Crank(3, "D", "C", L["l3"]), RRR("B", "C", 2, L["l2"], "A", 1, L["l1"],
                                                 branch_of(c1, b1, a))]
    for el in design.linkage.elements:
        if isinstance(el, PointOnLink):   # link 2 now points C -> B: half a turn round
            elements.append(PointOnLink(el.name, el.link, el.origin, -el.along, -el.normal))
    angles = {k: (np.asarray(v, dtype=float) + math.pi if k == 2 else v)
              for k, v in design.angles.items()}
    return dataclasses.replace(design, linkage=Linkage(4, tuple(elements)),
                               inputs=np.angle(np.asarray(C) - d), angles=angles)


def verify(design: LinkageDesign, driver: int = 1) -> Verification:
    """Move a design through its prescribed positions on the engine.

    Parameters
    ----------
    design : LinkageDesign
    driver : {1, 3}
        The driving link of a four-bar: 1 the crank AB (the design's own
        linkage), 3 the rocker CD (the same lengths and pivots, driven at D).

    Returns
    -------
    Verification
    """
    if driver == 3 and design.inputs is not None and len(design.inputs):
        if design.kind != "four_bar":
            raise ValueError("only a four-bar can be driven by its rocker")
        q = np.asarray(design.inputs, dtype=float)
        own = solve(design.linkage, {1: DriverMotion(q)}, order=0)
        alt = solve(_flipped(design.linkage), {1: DriverMotion(q)}, order=0)
        mine, theirs = _residuals(design, own), _residuals(design, alt)
        use_alt = np.isfinite(theirs) & ~(theirs >= np.where(np.isfinite(mine), mine, np.inf))
        C = np.where(use_alt, alt.points["C"].p, own.points["C"].p)
        design = _driven_by_rocker(design, C)
    kind, turns, gamma_turn, figures = _type(design, driver)
    cranks = tuple(figures.pop("cranks", ()))
    if design.inputs is None or len(design.inputs) == 0:
        # a design from K: the core's figures of the designed lengths against the targets
        targets: Dict[str, Any] = {k: design.values[k] for k in ("K", "psi")
                                   if k in design.values}
        if "H" in design.lengths:
            targets["H"] = design.lengths["H"]
        res = np.array([abs(figures[k] - v) / max(abs(v), 1e-300) if k in figures
                        else np.nan for k, v in targets.items()])
        finite = res[np.isfinite(res)]
        dead_points: Tuple[Defect, ...] = ()
        if turns:
            # the crank must turn a full revolution on the engine without a dead point
            # (a slider-crank with a + e = b exactly has one at the crank's top)
            q = np.linspace(0.0, TWO_PI, int(TWO_PI * PATH_DENSITY) + 1)
            m = solve(design.linkage, {design.linkage.drivers[0].link: DriverMotion(q, 1.0)},
                      order=1)
            sing = ~m.regular
            if m.conditions:
                sing |= m.conditions[0].sin_gamma <= DEAD_POINT_SIN
            if sing.any():
                dead_points = (Defect("circuit", None, float(q[int(np.argmax(sing))])),)
        return Verification(res, float(finite.max()) if finite.size else 0.0, kind, turns,
                            gamma_turn, 1, 0.0, TWO_PI, dead_points, driver, design.linkage, None,
                            cranks)
    q = np.asarray(design.inputs, dtype=float)
    link = design.linkage.drivers[0].link
    m = solve(design.linkage, {link: DriverMotion(q)}, order=0)
    res = _residuals(design, m)
    defects = []
    other = solve(_flipped(design.linkage), {link: DriverMotion(q)}, order=0)
    res_other = _residuals(design, other)
    for i in range(len(q)):
        mine, theirs = res[i], res_other[i]
        if not (np.isfinite(mine) or np.isfinite(theirs)):
            defects.append(Defect("assembly", i + 1))
        elif i and (not np.isfinite(mine) or mine > BRANCH_TOL) and np.isfinite(theirs) \
                and (not np.isfinite(mine) or theirs < mine):
            defects.append(Defect("branch", i + 1))
    direction, start, stop, gamma = 0, float(q[0]), float(q[0]), None
    if len(q) >= 2 and not defects:
        if turns:
            direction, stop, gamma, defect = _crank_path(design.linkage, q)
        else:
            direction, stop, gamma, defect = _rocker_path(design.linkage, q)
        if defect is not None:
            defects.append(defect)
    finite = res[np.isfinite(res)]
    return Verification(res, float(finite.max()) if finite.size else 0.0, kind, turns,
                        gamma, direction, start, stop, tuple(defects), driver, design.linkage,
                        q, cranks)
