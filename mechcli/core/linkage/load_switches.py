"""Both sides of a load switch: where a conditional load (a window of the input, a
velocity sign, a stroke band) switches on or off inside a force sweep, the
kinetostatics at that very input once with the load off and once with it on.

The reactions and the balancing torque jump there; a table of the sweep gives the
two limits as two rows at the same input, the one of the smaller input first,
instead of one value on one side.  Each side is evaluated exactly at
the switch, with every conditional load forced to the state it has on that side
(no nudge of the input).

May import what :mod:`mechcli.core.linkage` may.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Callable, Dict, Optional, Sequence

import numpy as np

from mechcli.core.linkage.force_analysis import ForceEvaluator, series_of
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray


@record
class SwitchRows:
    """The rows a force table gets at the load switches of a sweep.

    Attributes
    ----------
    q : ndarray
        Input of each row [rad or m], increasing; two rows at a switch (the limit from
        the smaller input first), one at a run's first sample (from the larger input)
        and at the last sample of a run that does not go on through a whole turn (from
        the smaller input); see :func:`switch_rows`.
    row : ndarray of int
        Index into the sweep's ``q`` of the sample at the same input (that sample's
        row is replaced), −1 where the switch falls between samples.
    series : dict
        Symbol -> array: :func:`~mechcli.core.linkage.force_analysis.series_of` of the
        rows (SI).
    cond, power_residual, force_residual : ndarray
        Of :class:`~mechcli.core.linkage.force_model.ForceResult`, per row.
    active : dict
        Load name -> bool array: the state each conditional load was evaluated with.
    extra : dict
        Symbol -> array from the *extra* callback of :func:`switch_rows`.
    """

    q: np.ndarray
    row: np.ndarray
    series: Dict[str, np.ndarray]
    cond: np.ndarray
    power_residual: np.ndarray
    force_residual: np.ndarray
    active: Dict[str, np.ndarray]
    extra: Dict[str, np.ndarray]

    def __len__(self):
        return int(self.q.size)


def forced_programs(programs: Sequence[Any], state: Any):
    """The load programs with each conditional load in *state* held on or off.

    Parameters
    ----------
    programs : sequence of LoadProgram
    state : dict
        Load name -> bool.  A load held on keeps its factor and source and loses its
        conditions (window, velocity sign, band); a load held off is left out.  Loads
        not named keep their program.

    Returns
    -------
    tuple of LoadProgram
    """
    out = []
    for p in programs:
        on = state.get(p.load.name)
        if on is None:
            out.append(p)
        elif on:
            out.append(dataclasses.replace(p, window=None, velocity=None, sign=0, band=None,
                                           band_limits=None))
    return tuple(out)


def _snap(x: FloatOrArray, programs: Sequence[Any], q: np.ndarray, tol: FloatOrArray):
    """A switch input moved onto the exact window bound it is within round-off of
    (bisection brackets it to ~1e-14), then onto a sample of *q* within *tol*."""
    for p in programs:
        if p.window is None:
            continue
        for bound in p.window:
            b = bound + (2 * math.pi * round((x - bound) / (2 * math.pi)) if p.rotary else 0.0)
            if abs(x - b) <= 1e-10 * max(1.0, abs(b)):
                x = b
    k = int(np.clip(np.searchsorted(q, x), 0, q.size - 1))
    for j in (k - 1, k):
        if 0 <= j < q.size and abs(q[j] - x) <= tol:
            return float(q[j]), j
    return float(x), -1


def switch_states(result, programs, periodic=False):
    """Where the conditional loads switch, and their states on both sides.

    Parameters
    ----------
    result : ForceSweep
        Its ``active`` intervals (bisected to ~1e-14), ``q`` and ``kin.runs``.
    programs : sequence of LoadProgram
    periodic : bool
        The sweep covers a whole turn with no gap: the side beyond the last sample is
        the one after the first sample.

    Returns
    -------
    list of (float, int, dict or None, dict or None)
        ``(input, sample index or −1, state before, state after)``, increasing input;
        a state maps every conditional load's name to on/off; ``before`` is None at a
        run's first sample, ``after`` None at the last sample of a run that does not
        continue.
    """
    q = np.asarray(result.q, dtype=float)
    names = [p.load.name for p in programs if p.conditional and p.load.name in result.active]
    if not names or q.size < 2 or np.any(np.diff(q) <= 0):
        return []
    runs = list(result.kin.runs) or [(0, q.size)]
    step = float(np.min(np.diff(q)))
    tol = 1e-9 * step + 1e-11 * max(1.0, float(np.max(np.abs(q))))
    ivs = {n: [(_snap(s, programs, q, tol)[0], _snap(t, programs, q, tol)[0])
               for s, t in result.active[n]] for n in names}

    def before(x: FloatOrArray):
        return {n: any(s < x <= t for s, t in ivs[n]) for n in names}

    def after(x: FloatOrArray):
        return {n: any(s <= x < t for s, t in ivs[n]) for n in names}

    first, last = q[runs[0][0]], q[runs[-1][1] - 1]
    grid = {n: np.asarray(result.active_mask[n], dtype=bool) for n in names}

    def sample(k: int):
        return None if k < 0 else {n: bool(grid[n][k]) for n in names}

    cands = {_snap(e, programs, q, tol) for n in names for pair in result.active[n]
             for e in pair}
    cands |= {(float(q[j]), j) for a, b in runs for j in (a, b - 1)}
    out = []
    for x, k in sorted(cands):
        a, b = next(((a, b) for a, b in runs if q[a] <= x <= q[b - 1]), (None, None))
        if a is None:
            continue
        lo = before(x) if x > q[a] else None
        hi = after(x) if x < q[b - 1] else (after(first) if periodic and x == last else None)
        if lo is not None and hi is not None:
            if lo == hi:
                continue
        elif (lo or hi) == sample(k):    # one side only, which the sample already holds
            continue
        out.append((x, k, lo, hi))
    return out


def switch_rows(pipe: ForceEvaluator, result: Any, periodic: bool = False,
                extra: Optional[Callable] = None):
    """The kinetostatics on both sides of every load switch of a force sweep.

    Parameters
    ----------
    pipe : ForceEvaluator
        The sweep's evaluator (its programs with the stroke bands fixed).
    result : ForceSweep
    periodic : bool
        See :func:`switch_states`.
    extra : callable, optional
        ``extra(evaluator, x) -> {symbol: array}``: more series at inputs *x* through an
        evaluator (e.g. the engine's named forces).

    Returns
    -------
    SwitchRows or None
        None when no load switches inside the sweep.

    Notes
    -----
    At a run's first sample only the side after it is given (nothing lies before it in
    the range), at a run's last sample only the side before it, and with *periodic*
    also the side after (the one after the first sample: a whole turn goes on there);
    such a one-sided row is given only where it differs from the sample's.  A state is
    taken from the refined ``active`` intervals, so a switch that falls exactly on a
    sample (a window bound on the grid) replaces that sample's row, whose inclusive
    window gave only one side.  A switch whose sides cannot be evaluated to finite
    numbers (a singular position) keeps the sweep's row.
    """
    states = switch_states(result, pipe.programs, periodic)
    if not states:
        return None
    rows = []
    for x, k, lo, hi in states:
        if lo is not None:
            rows.append((x, k, lo))
        if hi is not None:
            rows.append((x, k, hi))
    groups: Dict[tuple, list] = {}
    for i, (x, k, st) in enumerate(rows):
        groups.setdefault(tuple(sorted(st.items())), []).append(i)
    n = len(rows)
    series: Dict[str, np.ndarray] = {}
    more: Dict[str, np.ndarray] = {}
    cond, pres, fres = np.zeros(n), np.zeros(n), np.zeros(n)
    for key, idx in groups.items():
        sub = ForceEvaluator(pipe.linkage, pipe.topo, pipe.sweep, pipe.bodies, pipe.gravity,
                             forced_programs(pipe.programs, dict(key)))
        x = np.array([rows[i][0] for i in idx])
        fr, _m, _motion = sub(x, condition=True)
        for sym, v in series_of(pipe.linkage, fr).items():
            series.setdefault(sym, np.zeros(n))[idx] = v
        cond[idx], pres[idx], fres[idx] = fr.cond, fr.power_residual, fr.force_residual
        if extra is not None:
            for sym, v in extra(sub, x).items():
                more.setdefault(sym, np.zeros(n))[idx] = v
    # a switch whose sides cannot be evaluated (a singular position) keeps the sweep's row
    ok = np.ones(n, dtype=bool)
    for v in list(series.values()) + list(more.values()) + [cond]:
        ok &= np.isfinite(v)
    at = np.array([r[0] for r in rows])
    bad = np.isin(at, at[~ok])
    keep = ~bad
    if not keep.any():
        return None
    names = list(rows[0][2])
    active = {nm: np.array([st[nm] for _x, _k, st in rows])[keep] for nm in names}
    return SwitchRows(at[keep], np.array([r[1] for r in rows])[keep],
                      {k: v[keep] for k, v in series.items()}, cond[keep], pres[keep],
                      fres[keep], active, {k: v[keep] for k, v in more.items()})


def split_mean(pipe: ForceEvaluator, result: Any):
    """The mean and RMS of the balancing quantities with the loads' own kinks and jumps
    as split points of the quadrature.

    :func:`~mechcli.core.linkage.force_analysis.analyse_forces` integrates by 4-point
    Gauss–Legendre between the points of its grid (≤ 0.5° for a crank), split at the
    switches of the conditional loads; a load tabulated against the input or the stroke
    (a ``factor``, a gas pressure: ``LoadProgram.breaks``) has kinks, and an indicator
    diagram jumps at the dead centres, between those points, where the rule is not
    exact.  Adding them as split points makes the mean of a piecewise-smooth load as
    exact as that of a smooth one (the four-stroke indicator config: the net indicator
    work / 4π to 1e-12).

    Parameters
    ----------
    pipe : ForceEvaluator
        The sweep's evaluator (its programs with the stroke bands fixed).
    result : ForceSweep

    Returns
    -------
    (dict, dict) or None
        ``(mean, rms)`` by balancing symbol, or None when no load has a break inside the
        analysed runs (the sweep's own values stand).
    """
    from mechcli.core.linkage.force_analysis import balancing_symbol
    from mechcli.core.linkage.kinematics import SEARCH_STEP
    from mechcli.core.numerics import gauss_legendre, mean_rms, sorted_union

    q = np.asarray(result.q, dtype=float)
    runs = [(a, b) for a, b in (list(result.kin.runs) or [(0, q.size)]) if b - a >= 2]
    if not runs:
        return None
    rotary = pipe.linkage.driver(pipe.sweep.driver).rotary
    fine = SEARCH_STEP if rotary else (q[-1] - q[0]) / 720
    step = float(np.max(np.diff(q)))
    cuts = [e for iv in result.active.values() for pair in iv for e in pair]
    breaks = [x for p in pipe.programs if hasattr(p, "breaks")
              for x in p.breaks(float(q[runs[0][0]]), float(q[runs[-1][1] - 1]))]
    inside = [x for x in breaks if any(q[a] < x < q[b - 1] for a, b in runs)]
    if not inside:
        return None
    xs, ws, span = [], [], 0.0
    for a, b in runs:
        lo, hi = float(q[a]), float(q[b - 1])
        grid = (np.linspace(lo, hi, max(2, int(np.ceil((hi - lo) / fine)) + 1))
                if step > fine * (1 + 1e-9) else q[a:b])
        extra = [c for c in cuts + inside if lo < c < hi]
        x, w = gauss_legendre(sorted_union(grid, extra))
        xs.append(x)
        ws.append(w)
        span += hi - lo
    if span <= 0:
        return None
    xg, wg = np.concatenate(xs), np.concatenate(ws)
    fr, _m, _motion = pipe(xg)
    ser = series_of(pipe.linkage, fr)
    mean, rms = {}, {}
    for d in pipe.linkage.drivers:
        sym = balancing_symbol(pipe.linkage, d.link)
        mean[sym], rms[sym] = mean_rms(wg, ser[sym], span)
    return mean, rms
