"""Solve one ``mechcli grashof`` problem: the closed forms of :mod:`.chain`,
:mod:`.fivebar` and :mod:`.mobility` chosen by the kind of problem.

One four-bar, slider-crank or guide-bar is solved in pure Python (:mod:`.chain`):
``mechcli grashof --lengths`` does not import numpy.  numpy (:mod:`.fourbar`) is
imported only for a transmission-angle curve, a five-bar or a batch.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Tuple

from mechcli.core.grashof import chain
from mechcli.core.records import record

if TYPE_CHECKING:   # numpy is imported only when a curve is made
    import numpy as np
    from numpy.typing import ArrayLike

    from mechcli.core.grashof.fourbar import FourBarAnalysis, TransmissionCurve

#: kinds of problem :func:`solve_grashof` accepts
KINDS = ("fourbar", "slider_crank", "guide_bar", "fivebar", "rrrrp", "mobility")


@record
class GrashofSolution:
    """Everything the report of one problem shows.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    result : object
        :class:`~.chain.FourBarChain` (``fourbar``, lengths [m]),
        :class:`~.chain.SliderCrank`, :class:`~.chain.GuideBar` or
        :class:`~.fivebar.RRRRPCrank` (lengths in the caller's unit, see
        :func:`solve_grashof`), :class:`~.fivebar.FiveBarClass` (``fivebar``,
        lengths [m]) or :class:`~.mobility.Mobility`.
    inversions : tuple of ChainType
        Four-bar only: the type with link 1, 2, 3, 4 as the frame.
    ranges : dict
        Four-bar only: link number -> list of :class:`~.chain.LengthRange` [m].
    curve : TransmissionCurve or None
        γ(θ1) when a curve step was asked (four-bar, slider-crank, guide-bar).
    """

    kind: str
    result: object
    inversions: tuple = ()
    ranges: dict = dataclasses.field(default_factory=dict)
    curve: TransmissionCurve | None = None


def transmission_curve(kind: str, problem: Any, step: float) -> TransmissionCurve:
    """γ over one turn of the input, every *step* [rad] (lengths [m]).

    Parameters
    ----------
    kind : str
        ``fourbar``, ``slider_crank`` or ``guide_bar``.
    problem : object
        With the attributes of that kind (see :func:`solve_grashof`).
    step : float
        Input-angle step [rad]; the last point is the whole turn.
    """
    import numpy as np

    from mechcli.core.grashof import fourbar as gf

    n = int(round(2 * np.pi / step))
    th = np.linspace(0.0, n * step, n + 1)
    p = problem
    if kind == "fourbar":
        i, c, o = chain.driven_links(p.frame, p.input)
        L = p.lengths
        return gf.fourbar_transmission(L[i - 1], L[c - 1], L[o - 1], L[p.frame - 1], th)
    if kind == "slider_crank":
        return gf.slider_transmission(p.crank, p.coupler, p.offset, th)
    return gf.guide_transmission(p.crank, p.frame, p.offset, th)


def solve_grashof(kind: str, problem: Any, scale: float = 1.0) -> GrashofSolution:
    """Classify the linkage of one problem and compute its figures of merit.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.
    problem : object
        Plain data with the attributes of the spec's problem of that kind
        (``mechcli.spec.grashof``): lengths [m], angles [rad], ``rtol``, and
        per kind ``lengths, frame, input, crossed, vary, curve_step`` (four-bar),
        ``crank, coupler, offset, curve_step`` (slider-crank), ``crank, frame,
        offset, curve_step`` (guide-bar), ``lengths, frame`` (five-bar),
        ``l1, l2, l3, offset`` (RRRRP), ``joints, frame, local_dof,
        redundant`` (mobility; joints with ``kind, links, name``).
    scale : float
        Metres per unit of the lengths as the user wrote them.  Closure is
        decided on lengths / scale (the numbers as written, so that an exact
        equality stays exact), and the slider-crank, guide-bar and RRRRP are
        solved in that unit: their results and :class:`~.fourbar.ClosureError`
        numbers are in it.

    Returns
    -------
    GrashofSolution

    Raises
    ------
    ClosureError
        The chain cannot close (numbers in the user's unit).
    MobilityError
        Joints that do not make a chain with that frame.
    """
    solution = _solve(kind, problem, scale)
    step = getattr(problem, "curve_step", None)
    if step is None:
        return solution
    return dataclasses.replace(solution, curve=transmission_curve(kind, problem, step))


def _solve(kind: str, p: Any, scale: float) -> GrashofSolution:
    if kind in ("fourbar", "fivebar"):
        chain.check_chain_closure([x / scale for x in p.lengths])
    if kind == "fourbar":
        an = chain.analyse_chain(p.lengths, p.frame, p.input, p.crossed, p.rtol)
        invs = chain.chain_inversions(p.lengths, p.rtol, p.crossed)
        ranges = {k: chain.length_ranges(p.lengths, k, p.frame, p.rtol) for k in p.vary}
        return GrashofSolution(kind, an, invs, ranges)
    if kind == "slider_crank":
        sc = chain.analyse_slider_crank(p.crank / scale, p.coupler / scale, p.offset / scale,
                                     p.rtol)
        return GrashofSolution(kind, sc)
    if kind == "guide_bar":
        gb = chain.analyse_guide_bar(p.crank / scale, p.frame / scale, p.offset / scale, p.rtol)
        return GrashofSolution(kind, gb)
    if kind == "fivebar":
        from mechcli.core.grashof.fivebar import classify_fivebar
        return GrashofSolution(kind, classify_fivebar(p.lengths, p.frame, p.rtol))
    if kind == "rrrrp":
        from mechcli.core.grashof.fivebar import rrrrp_crank
        return GrashofSolution(kind, rrrrp_crank(p.l1 / scale, p.l2 / scale, p.l3 / scale,
                                                 p.offset / scale, p.rtol))
    if kind == "mobility":
        from mechcli.core.grashof.mobility import Joint, MobilityError, count_mobility
        joints = [Joint(j.kind, j.links, j.name) for j in p.joints]
        mob = count_mobility(joints, p.frame, p.local_dof, p.redundant)
        drivers = getattr(p, "drivers", ())
        if drivers:
            import dataclasses

            from mechcli.core.grashof.structure import decompose
            if mob.F != len(drivers):
                raise MobilityError(f"F = {mob.F} with {len(drivers)} "
                                    f"driver{'s' if len(drivers) != 1 else ''} "
                                    f"{list(drivers)}")
            mob = dataclasses.replace(mob, structure=decompose(joints, p.frame, drivers))
        return GrashofSolution(kind, mob)
    raise ValueError(f"unknown kind {kind!r}: one of {', '.join(KINDS)}")


def classify_batch(lengths: ArrayLike, frame: ArrayLike,
                   input_link: ArrayLike) -> Tuple[FourBarAnalysis, np.ndarray]:
    """Four-bars of a batch that may hold sets that cannot close.

    Returns
    -------
    analysis : FourBarAnalysis
        All sets (merit meaningless where ``closes`` is False).
    closes : ndarray of bool
        Every link shorter than the sum of the others.
    """
    from mechcli.core.grashof import fourbar as gf

    return (gf.analyse_fourbar(lengths, frame, input_link, require_closure=False),
            gf.closes(lengths))


__all__ = ["KINDS", "GrashofSolution", "classify_batch", "solve_grashof", "transmission_curve"]
