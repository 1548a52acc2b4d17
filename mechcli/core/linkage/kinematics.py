"""Kinematic analysis of a linkage over a sweep of its primary input.

:func:`analyse_sweep` solves the linkage engine over the sweep, finds where it
cannot assemble (or is at a dead point) and refines those boundaries by
bisection, restricts the analysis to the regular positions when asked, and
refines the extremes of every requested quantity by a bracketed search on the
exact solution (to 1e-15 ... 1e-10 rad of input angle, each with its tolerance); gives
every dead point as one input with its uncertainty (:func:`dead_points`) and the ends of
every gap as the roots of a dyad's discriminant (:func:`assembly_limits`).

Secondary drivers (a 2-DOF five-bar driven by two geared cranks) follow the
primary one linearly: ``q_k = phase_k + ratio_k * q_1``.

The steps live by concern: :mod:`.sweep` (the sweep, its quantities and its result
records), :mod:`.limits` (assembly limits, dead points, gaps), :mod:`.extremes` (the
refined extremes and zeros), :mod:`.accuracy` (the digits-lost estimate); this module
runs them (:func:`analyse_sweep`) and re-exports their public names.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Dict, Sequence, Tuple

import numpy as np

from mechcli.core.errors import AssemblyError
from mechcli.core.linkage.accuracy import (
    ACCURACY_C,
    ACCURACY_CLASSES,
    ACCURACY_WARN,
    EPS,
    FULL_DIGITS,
    NOISE_REL,
    Accuracy,
    AccuracyRange,
    _accuracy_of_sweep,
    amplification,
    estimate_accuracy,
    noise_floor,
)
from mechcli.core.linkage.engine import Linkage, solve
from mechcli.core.linkage.extremes import _Domain, _slide_zeros, refine_extremes, zero_crossings
from mechcli.core.linkage.limits import (
    _bisect_boundaries,
    _describe_exclusions,
    _limits_are_not_dead_points,
    _nearest_boundary,
    _refined_exclusions,
    _scan_gaps,
    assembly_limits,
    dead_points,
)
from mechcli.core.linkage.sweep import (
    NEAR_TOGGLE_SIN,
    DeadPoint,
    Extreme,
    Quantity,
    Sweep,
    SweepResult,
    Toggle,
    _dedupe,
    _periodic,
    _take,
    _unwrap_runs,
    default_quantities,
)
from mechcli.core.numerics import sorted_union, true_runs
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import LinkageMotion

#: the public names of the sweep analysis, whichever module of it holds them
#: (:mod:`.sweep`, :mod:`.limits`, :mod:`.extremes`, :mod:`.accuracy`, this one)
__all__ = ["Sweep", "Quantity", "Extreme", "Toggle", "DeadPoint", "SweepResult",
           "default_quantities", "assembly_limits", "dead_points", "refine_extremes",
           "zero_crossings", "Accuracy", "AccuracyRange", "amplification", "estimate_accuracy",
           "EPS", "FULL_DIGITS", "ACCURACY_C", "ACCURACY_CLASSES", "ACCURACY_WARN",
           "NEAR_TOGGLE_SIN", "SEARCH_STEP", "analyse_sweep"]

#: the extremes and dead points are searched on a grid at least this fine
#: (rotary input [rad]; linear inputs use span / 720), whatever the output step
SEARCH_STEP = np.radians(0.5)


def analyse_sweep(linkage: Linkage, sweep: Sweep, quantities: Sequence[Any], order: int,
                  partial: bool = False, extremes: bool = True) -> SweepResult:
    """Solve the linkage over a sweep and summarise it.

    The analysis runs on the output grid merged with a search grid of at most
    0.5° (``SEARCH_STEP``), so extremes, gaps and dead points do not depend
    on the output step; the output rows are a subset of that grid.

    Parameters
    ----------
    linkage : Linkage
    sweep : Sweep
    quantities : list of Quantity
        What to report (see :func:`default_quantities`).
    order : int
        Highest derivative needed (0, 1, 2).
    partial : bool
        False: any position that cannot assemble (or is a dead point) raises
        :class:`AssemblyError` naming the intervals -- including gaps narrower
        than the grid step, found by refining the minima of every dyad's
        sin(gamma).  True: analyse only the regular positions and report the
        excluded intervals.
    extremes : bool
        Refine max/min of every quantity.

    Returns
    -------
    SweepResult
    """
    if linkage.shape != ():
        raise ValueError(f"analyse_sweep works on one design at a time, got a batch of designs "
                         f"(linkage parameters of shape {linkage.shape}); use solve for a batch")
    q_out = np.asarray(sweep.q, dtype=float)
    if q_out.ndim != 1:
        raise ValueError(f"a sweep's q must be one-dimensional, got shape {q_out.shape}")
    q_all, out_idx = _analysis_grid(linkage, sweep, q_out)
    motion = solve(linkage, sweep.inputs(q_all), order=order)
    good = motion.regular.copy()
    # gaps the grid stepped over: refine near-toggles on the grid's own runs
    toggles, gaps = _scan_gaps(linkage, sweep, order, q_all, motion, true_runs(good))
    for x, k in gaps:
        # mark the grid point at a hidden gap as bad: the boundary search
        # below then starts from its neighbours
        good[k] = False
    ex = _exclusions(linkage, sweep, order, q_all, motion, good, gaps, partial)
    grid = _grid_runs(sweep, q_all, good, out_idx, ex)
    toggles += _boundary_toggles(linkage, sweep, q_all, ex.regular)
    grid_motion = _take(motion, grid.idx) if grid.idx.size < q_all.size else motion
    values = {}
    for qt in quantities:
        v = np.asarray(qt.get(grid_motion), dtype=float)
        if qt.is_angle:
            v = _unwrap_runs(v, grid.runs, grid.connected and len(grid.runs) > 1)
        values[qt.symbol] = v
    q, runs, period = grid.q, grid.runs, grid.period
    domain = _Domain(q, runs, grid.lo_ext, grid.hi_ext, grid.connected, period,
                     (q_all[0], q_all[-1]))
    ext = refine_extremes(linkage, sweep, order, quantities, values, domain) if extremes else {}
    ext = _constant_marked(linkage, sweep, quantities, values, ext, q)
    zeros = _slide_zeros(linkage, sweep, order, quantities, values, q, runs,
                         sweep.periodic and grid.connected, q_all[0], period) if extremes else {}
    keep, out_runs, out_motion, out_values = _output_rows(out_idx, good, grid, grid_motion,
                                                          values)
    if sweep.periodic:
        toggles = [dataclasses.replace(t, at=_periodic(t.at, q_all[0], period))
                   for t in toggles]
    toggles.sort(key=lambda t: t.at)
    toggles = _dedupe(toggles)
    q_rows = q_all[keep]
    accuracy = _accuracy_of_sweep(linkage, sweep, quantities, order, q_rows, out_values, ext,
                                  out_motion, out_runs, toggles)
    deads = _one_per_dead_point(ex.deads, sweep, q_all[0], period)
    return SweepResult(q_rows, out_values, ext, ex.excluded, toggles, out_motion, out_runs,
                       accuracy, ex.tol, deads, zeros)


def _constant_marked(linkage: Linkage, sweep: Sweep, quantities: Sequence[Any],
                     values: Dict[str, np.ndarray], ext: Dict[str, Tuple[Extreme, Extreme]],
                     q: np.ndarray):
    """*ext* with the extremes of every quantity that spreads over the sweep by no more
    than round-off marked ``constant``: :data:`~mechcli.core.linkage.accuracy.NOISE_REL`
    of its largest magnitude or of its kind's natural magnitude
    (:func:`~mechcli.core.linkage.accuracy.noise_floor`), with the mean of its samples as
    both values; one that is zero in truth (all its values below that floor) has 0."""
    out = dict(ext)
    for qt in quantities:
        if qt.symbol not in ext:
            continue
        v = np.asarray(values[qt.symbol], dtype=float)
        v = v[np.isfinite(v)]
        floor = noise_floor(linkage, sweep, q, qt.kind)
        if floor is None or v.size == 0:
            continue
        if float(np.ptp(v)) <= max(floor, NOISE_REL * float(np.max(np.abs(v)))):
            # one value for max and min: the samples' mean (two samples' noise apart, they
            # read 9.9999999999995 and 10.0000000000006); zero in truth: its noise is no value
            zero = float(np.max(np.abs(v))) <= floor
            value = 0.0 if zero else float(np.mean(v))
            hi, lo = (dataclasses.replace(e, constant=True, value=value) for e in ext[qt.symbol])
            out[qt.symbol] = (hi, lo)
    return out


def _analysis_grid(linkage: Linkage, sweep: Sweep, q_out: np.ndarray):
    """Step 1: the output inputs merged with a search grid of at most ``SEARCH_STEP``
    (span / 720 for a linear input): ``(q_all, out_idx)``, the rows' indices in it."""
    rotary = linkage.driver(sweep.driver).rotary
    span = float(q_out[-1] - q_out[0])
    fine_step = SEARCH_STEP if rotary else span / 720
    if q_out.size > 1 and np.max(np.diff(q_out)) > fine_step * (1 + 1e-9):
        n = int(np.ceil(span / fine_step)) + 1
        fine = np.linspace(q_out[0], q_out[-1], n)
        # a fine node that is an output node but for rounding (210.0 of the 0.5° grid and
        # 210.0 of the 10° rows, a bit apart) would be a second, nearly equal sample: an
        # extreme's bracket could then lie beside the extreme instead of round it
        i = np.clip(np.searchsorted(q_out, fine), 1, q_out.size - 1)
        near = np.minimum(np.abs(fine - q_out[i - 1]), np.abs(fine - q_out[i]))
        q_all = sorted_union(q_out, fine[near > 1e-9 * fine_step])
    else:
        q_all = q_out
    return q_all, np.searchsorted(q_all, q_out)


@record(eq=False)
class _Excluded:
    """What a sweep cannot analyse: ``excluded`` the intervals ``(start, stop, reason)``
    refined to the assembly limits and dead points, ``tol`` their uncertainties,
    ``regular`` the intervals as the bisection left them (the analysis extends to their
    regular ends), ``deads`` the dead points."""

    excluded: list
    tol: list
    regular: list
    deads: list


def _exclusions(linkage, sweep, order, q_all,
                motion, good, gaps, partial):
    """Step 2: the grid's runs that are not regular, each bounded by bisection from its
    regular neighbours, then refined to the roots of a dyad's discriminant and to the
    dead points; :class:`AssemblyError` unless ``partial``."""
    bad_runs = true_runs(~good)
    if not bad_runs:
        return _Excluded([], [], [], [])
    excluded, ends = [], []
    goods, bads, where = [], [], []
    hidden = {k: x for x, k in gaps}
    for (i0, i1) in bad_runs:
        inner = [hidden[k] for k in range(i0, i1) if k in hidden]
        first_bad = inner[0] if inner and motion.regular[i0] else q_all[i0]
        last_bad = inner[-1] if inner and motion.regular[i1 - 1] else q_all[i1 - 1]
        if i0 > 0:
            goods.append(q_all[i0 - 1]); bads.append(first_bad); where.append((i0, 0))
        if i1 < q_all.size:
            goods.append(q_all[i1]); bads.append(last_bad); where.append((i1 - 1, 1))
    bounds = {}
    if goods:
        for w, val in zip(where, _bisect_boundaries(linkage, sweep, order, goods, bads)):
            bounds[w] = float(val)
    for (i0, i1) in bad_runs:
        start = bounds.get((i0, 0), float(q_all[i0]))
        stop = bounds.get((i1 - 1, 1), float(q_all[i1 - 1]))
        if start > stop:
            start, stop = stop, start
        mid = solve(linkage, sweep.inputs(np.array([0.5 * (start + stop)])), order=0)
        reason = "cannot assemble" if not mid.feasible[0] or not np.all(
            motion.feasible[i0:i1]) else "dead point"
        excluded.append((start, stop, reason))
        # where assembly is lost, inside the interval: the first and last input that
        # does not assemble (a grid point, or the middle)
        infeasible = np.flatnonzero(~motion.feasible[i0:i1])
        if infeasible.size:
            out_lo, out_hi = q_all[i0 + infeasible[0]], q_all[i0 + infeasible[-1]]
        elif not mid.feasible[0]:
            out_lo = out_hi = 0.5 * (start + stop)
        else:
            out_lo = out_hi = None
        end = ((i0, 0) in bounds and out_lo is not None,
               (i1 - 1, 1) in bounds and out_hi is not None, out_lo, out_hi)
        if bounds.get((i0, 0), float(q_all[i0])) > bounds.get((i1 - 1, 1),
                                                               float(q_all[i1 - 1])):
            end = (end[1], end[0], end[3], end[2])   # start and stop were swapped
        ends.append(end)
    regular = excluded
    excluded, excluded_tol = _refined_exclusions(linkage, sweep, excluded, ends, bounds)
    deads = dead_points(linkage, sweep, excluded)
    excluded, excluded_tol, deads = _limits_are_not_dead_points(excluded, excluded_tol, deads)
    if not partial:
        raise AssemblyError(_describe_exclusions(excluded), excluded)
    return _Excluded(excluded, excluded_tol, regular, deads)


@record(eq=False)
class _Grid:
    """The analysed part of the grid: ``idx`` its indices in the whole grid, ``q`` its
    inputs, ``runs`` its continuous arcs (index ranges of ``q``) with their real extent
    ``lo_ext``/``hi_ext`` (the refined gap edges), ``period`` the sweep's span and
    ``connected`` whether a whole turn joins its ends."""

    idx: np.ndarray
    q: np.ndarray
    runs: list
    lo_ext: list
    hi_ext: list
    period: float
    connected: bool


def _grid_runs(sweep: Sweep, q_all: np.ndarray, good: np.ndarray, out_idx: Any, ex: Any):
    """Step 3: the regular part of the grid and its runs (at least two rows, else
    :class:`AssemblyError`)."""
    idx = np.flatnonzero(good)
    if idx.size < 2 or np.count_nonzero(good[out_idx]) < 2:
        raise AssemblyError("fewer than two input positions can be analysed: "
                            + _describe_exclusions(ex.excluded), ex.excluded, too_few=True)
    q = q_all[idx]
    cuts = np.flatnonzero(np.diff(idx) > 1) + 1
    edges = np.concatenate(([0], cuts, [idx.size]))
    runs = list(zip(edges[:-1].tolist(), edges[1:].tolist()))
    lo_ext = [_nearest_boundary(ex.regular, q[i0], before=True) for i0, _ in runs]
    hi_ext = [_nearest_boundary(ex.regular, q[i1 - 1], before=False) for _, i1 in runs]
    period = float(q_all[-1] - q_all[0])
    connected = bool(sweep.periodic and idx[0] == 0 and idx[-1] == q_all.size - 1)
    return _Grid(idx, q, runs, lo_ext, hi_ext, period, connected)


def _boundary_toggles(linkage: Linkage, sweep: Sweep, q_all: np.ndarray, regular: np.ndarray):
    """Step 4: a toggle at every inner end of an excluded interval (the group whose
    condition is least there)."""
    out = []
    for start, stop, _r in regular:
        for b in (start, stop):
            if q_all[0] < b < q_all[-1]:
                m1 = solve(linkage, sweep.inputs(np.array([b])), order=0)
                c = min(m1.conditions, key=lambda c: float(c.sin_gamma[0]))
                out.append(Toggle(b, c.joint, c.kind, float(c.sin_gamma[0])))
    return out


def _output_rows(out_idx: Any, good: np.ndarray, grid: Any, grid_motion: LinkageMotion,
                 values: Dict[str, np.ndarray]):
    """Step 5: the output rows, the regular output positions as a subset of the grid:
    ``(keep, runs, motion, values)`` (``keep``: their indices in the whole grid)."""
    keep = out_idx[good[out_idx]]
    pos = np.searchsorted(grid.idx, keep)  # positions of the kept rows within the grid's idx
    run_of = np.repeat(np.arange(len(grid.runs)), [b - a for a, b in grid.runs])[pos]
    cut_out = np.flatnonzero((np.diff(pos) > 0) & (np.diff(run_of) != 0)) + 1
    e_out = np.concatenate(([0], cut_out, [pos.size]))
    out_runs = list(zip(e_out[:-1].tolist(), e_out[1:].tolist()))
    out_motion = _take(grid_motion, pos) if pos.size < grid.idx.size else grid_motion
    return keep, out_runs, out_motion, {k: v[pos] for k, v in values.items()}


def _one_per_dead_point(deads, sweep, q0, period):
    """Step 6: the dead points in order, 0° and 360° of a whole turn as one."""
    if sweep.periodic:
        deads = [dataclasses.replace(d, at=_periodic(d.at, q0, period)) for d in deads]
    deads = sorted(deads, key=lambda d: d.at)
    unique = []
    for d in deads:
        if unique and abs(unique[-1].at - d.at) <= max(unique[-1].tol, d.tol) \
                and unique[-1].joint == d.joint:
            if d.tol < unique[-1].tol:
                unique[-1] = d
            continue
        unique.append(d)
    return unique


