"""Kinetostatics over a sweep of the input: reactions, balancing torque,
extremes (refined), where the conditional loads act, mean and RMS.

The kinematics (gaps, dead points, excluded intervals) come from
:func:`mechcli.core.linkage.kinematics.analyse_sweep`; the forces from
:func:`mechcli.core.linkage.kinetostatics.solve_forces`.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.linkage.accuracy import EPS, Accuracy, _digits, amplification
from mechcli.core.linkage.engine import solve
from mechcli.core.linkage.kinematics import SEARCH_STEP, Sweep, analyse_sweep
from mechcli.core.linkage.kinetostatics import COND_FLAG, ForceResult, solve_forces
from mechcli.core.numerics import (
    bisect,
    gauss_legendre,
    golden_section_max,
    mean_rms,
    sorted_union,
    true_runs,
)
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import LinkageMotion

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import Linkage
    from mechcli.core.linkage.force_model import Topology


@record
class ForceExtreme:
    value: float
    at: float
    #: the extreme's input lies within ``at ± tol`` [rad or m] (see :func:`_golden_tol`)
    tol: float = 0.0


#: error model of the force solve: the reactions and the balancing torque keep
#: ``-log10(FORCE_C * EPS * cond * kappa)`` digits, with ``cond`` the condition number
#: of the kinetostatic system and kappa the kinematic amplification
#: (:func:`~mechcli.core.linkage.kinematics.amplification`).  Calibrated on 例 2-1 at
#: 1e-2 ... 1e-12 from its change point against a 60-digit mpmath reference
#: (tests/unit/linkage/test_accuracy_estimate.py): within 0.5 digits of the true loss.
FORCE_C = 1.0


@record
class ForceSweep:
    """Result of :func:`analyse_forces`.

    ``q`` the analysed output positions, ``kin`` the kinematic sweep result,
    ``forces`` the :class:`ForceResult` at ``q``; ``series`` every reported
    quantity by symbol (balancing, pair components and magnitudes, frame
    force/moment, power); ``extremes`` symbol -> (max, min) refined;
    ``active`` load name -> list of (start, stop) input intervals; ``mean``,
    ``rms`` of each balancing quantity over the analysed range; ``band``
    load name -> absolute slide limits used.
    """

    q: np.ndarray
    kin: object
    forces: ForceResult
    series: Dict[str, np.ndarray]
    extremes: Dict[str, Tuple[ForceExtreme, ForceExtreme]]
    active: Dict[str, List[Tuple[float, float]]]
    active_mask: Dict[str, np.ndarray]
    mean: Dict[str, float]
    rms: Dict[str, float]
    band: Dict[str, Tuple[float, float]]
    flagged: List[Tuple[float, float]]
    #: estimated correct digits of the forces (class ``forces``); None if not estimated
    accuracy: Optional[Accuracy] = None


def balancing_symbol(linkage: Linkage, link: int):
    d = linkage.driver(link)
    base = "Mb" if d.rotary and getattr(d, "actuator", None) is None else "Fb"
    return base if len(linkage.drivers) == 1 else f"{base}{link}"


def series_of(linkage: Linkage, fr: ForceResult):
    """Every reported quantity by symbol (SI units), in report order."""
    out = {}
    for d in linkage.drivers:
        out[balancing_symbol(linkage, d.link)] = fr.balancing[d.link]
    for pf in fr.pairs:
        lab = pf.pair.label
        out[f"FR{lab}x"] = pf.fx
        out[f"FR{lab}y"] = pf.fy
        out[f"FR{lab}"] = pf.magnitude
        if pf.pair.kind == "P":
            out[f"MR{lab}"] = pf.couple
    fx, fy = fr.frame_force
    out["Fshx"], out["Fshy"], out["Fsh"] = fx, fy, np.hypot(fx, fy)
    out["Msh"] = fr.frame_moment
    out["P"] = fr.input_power
    return out


def extreme_symbols(linkage: Linkage, fr: ForceResult):
    """Symbols whose max (and min, for signed ones) are reported."""
    out = [(balancing_symbol(linkage, d.link), True) for d in linkage.drivers]
    for pf in fr.pairs:
        out.append((f"FR{pf.pair.label}", False))
        if pf.pair.kind == "P":
            out.append((f"MR{pf.pair.label}", True))
    out += [("Fsh", False), ("Msh", True)]
    return out


class ForceEvaluator:
    """Kinematics + loads + kinetostatics at any input positions (the public
    kinetostatic evaluator: ``force`` sweeps with it, flywheel takes the
    equivalent moment from it).

    Parameters
    ----------
    linkage : Linkage
    topo : Topology
        ``topology(linkage)``.
    sweep : Sweep
        The input program (driver, input speed and acceleration, followers);
        its ``q`` is not used here.
    bodies : dict
        ``{link: Body}``: masses, moments of inertia, centres of mass.
    gravity : tuple or None
        ``(gx, gy)`` [m/s^2].
    programs : sequence of LoadProgram
        External loads with their programs over the input.

    Calling it with input positions ``q`` returns ``(ForceResult, masks,
    motion)``: the reactions, the balancing torque (or force) of every driver,
    the power and its residual; ``masks[load name]`` where each load acts; the
    linkage motion at ``q``.
    """

    def __init__(self, linkage: Linkage, topo: Topology, sweep: Sweep, bodies: Dict[int, Any],
                 gravity: Optional[Tuple[float, float]], programs: Sequence[Any]) -> None:
        self.linkage, self.topo, self.sweep = linkage, topo, sweep
        self.bodies, self.gravity, self.programs = bodies, gravity, programs
        self.unit_sweep = dataclasses.replace(sweep, dq=1.0, ddq=0.0)

    def __call__(self, q: np.ndarray, motion: Optional[LinkageMotion] = None,
                 condition: bool = False):
        """Forces at inputs ``q``; ``motion`` (order 2, at ``q``) saves a solve when
        known; ``condition`` also computes each position's condition number."""
        q = np.asarray(q, dtype=float)
        if motion is None:
            motion = solve(self.linkage, self.sweep.inputs(q), order=2)
        unit = solve(self.linkage, self.unit_sweep.inputs(q), order=1)
        loads, masks = [], {}
        for p in self.programs:
            ld, on = p.evaluate(q, motion)
            loads.append(ld)
            masks[p.load.name] = on
        fr = solve_forces(self.topo, motion, self.bodies, loads, self.gravity, unit,
                          condition=condition)
        return fr, masks, motion


def analyse_forces(linkage: Linkage, topo: Topology, sweep: Sweep, bodies: Dict[Any, Any],
                   gravity: Optional[Tuple[float, float]], programs: Sequence[Any],
                   partial: bool = False, iterations: int = 48) -> ForceSweep:
    """Solve the kinetostatics over the sweep and summarise it (see :class:`ForceSweep`).

    The steps: the slide bands (:func:`_band_programs`), the forces on the output
    grid, the search grid (:func:`_search_grid`), the refined extremes
    (:func:`_refined_extremes`), where the conditional loads act
    (:func:`_active_intervals`), mean and RMS (:func:`_balancing_mean_rms`).
    """
    slides = [p.slide for p in programs if p.band is not None]
    kin = analyse_sweep(linkage, sweep, slides, 2, partial=partial, extremes=bool(slides))
    progs, band = _band_programs(kin, programs)
    pipe = ForceEvaluator(linkage, topo, sweep, bodies, gravity, progs)
    q = kin.q
    fr, masks, _ = pipe(q, kin.motion, condition=True)
    series = series_of(linkage, fr)
    grid = _search_grid(linkage, sweep, kin, pipe, series)
    extremes = _refined_extremes(linkage, pipe, extreme_symbols(linkage, fr), grid, iterations)
    active = _active_intervals(linkage, sweep, progs, masks, grid, q)
    mean, rms = _balancing_mean_rms(linkage, pipe, grid, active, series)
    flagged = []
    bad = fr.cond > COND_FLAG
    if bad.any():
        for a, b in true_runs(bad):
            flagged.append((float(q[a]), float(q[b - 1])))
    accuracy = _force_accuracy(linkage, pipe, kin, q, fr)
    return ForceSweep(q, kin, fr, series, extremes, active,
                      {k: v for k, v in masks.items()}, mean, rms, band, flagged, accuracy)


@record
class _Grid:
    """The search grid of :func:`analyse_forces`: positions ``qs`` (the output grid
    itself, or a finer one), its analysed ``runs`` (index ranges), the ``series`` at
    ``qs``, and whether the sweep is ``periodic`` with nothing excluded."""

    qs: np.ndarray
    runs: List[Tuple[int, int]]
    series: Dict[str, np.ndarray]
    periodic: bool


def _band_programs(kin: Any, programs: Sequence[Any]) -> Tuple[List[Any], Dict[str, Any]]:
    """The load programs with their slide bands made absolute (from the kinematic
    extremes of the slide), and load name -> the band limits used."""
    band = {}
    progs = []
    for p in programs:
        if p.band is not None:
            top, bottom = kin.extremes[p.slide.symbol]
            p = p.with_band_limits(bottom.value, top.value)
            band[p.load.name] = p.band_limits
        progs.append(p)
    return progs, band


def _search_grid(linkage: Linkage, sweep: Sweep, kin: Any, pipe: ForceEvaluator,
                 series: Dict[str, np.ndarray]) -> _Grid:
    """The output grid, or a <= 0.5 deg grid inside the analysed runs."""
    q = kin.q
    rotary = linkage.driver(sweep.driver).rotary
    step = float(np.max(np.diff(q))) if q.size > 1 else 0.0
    fine = SEARCH_STEP if rotary else (q[-1] - q[0]) / 720
    periodic = bool(sweep.periodic and len(kin.excluded) == 0)
    if not step > fine * (1 + 1e-9):
        return _Grid(q, kin.runs, series, periodic)
    parts = []
    for a, b in kin.runs:
        lo, hi = q[a], q[b - 1]
        n = max(2, int(np.ceil((hi - lo) / fine)) + 1)
        parts.append(np.linspace(lo, hi, n))
    qs = np.concatenate(parts)
    runs, k0 = [], 0
    for prt in parts:
        runs.append((k0, k0 + prt.size))
        k0 += prt.size
    frs, _m, _ = pipe(qs)
    return _Grid(qs, runs, series_of(linkage, frs), periodic)


def _extreme_targets(syms: List[Tuple[str, bool]], grid: _Grid
                     ) -> Tuple[List[Tuple[str, float, int]], List[float], List[float]]:
    """Each (symbol, sign, grid index of the extreme) to refine, and its bracket."""
    qs, runs = grid.qs, grid.runs
    targets = []
    for sym, signed in syms:
        v = grid.series[sym]
        for which in ((1.0, -1.0) if signed else (1.0,)):
            k = int(np.argmax(which * v))
            targets.append((sym, which, k))
    lo_b: Any = []
    hi_b: Any = []
    for sym, which, k in targets:
        run = next((a, b) for a, b in runs if a <= k < b)
        a = qs[k - 1] if k > run[0] else (qs[k] - (qs[1] - qs[0]) if grid.periodic else qs[k])
        b = qs[k + 1] if k < run[1] - 1 else (qs[k] + (qs[1] - qs[0]) if grid.periodic
                                               else qs[k])
        lo_b.append(a)
        hi_b.append(b)
    return targets, lo_b, hi_b


def _refined_extremes(linkage: Linkage, pipe: ForceEvaluator, syms: List[Tuple[str, bool]],
                      grid: _Grid, iterations: int
                      ) -> Dict[str, Tuple[ForceExtreme, ForceExtreme]]:
    """symbol -> (max, min): golden-section refined around the grid extremes (the
    minimum of an unsigned symbol is the grid minimum)."""
    qs, s_series = grid.qs, grid.series
    targets, lo_b, hi_b = _extreme_targets(syms, grid)
    best = {}
    if targets:
        lo_a, hi_a = np.array(lo_b), np.array(hi_b)
        signs = np.array([t[1] for t in targets])

        def values(x: np.ndarray) -> np.ndarray:
            f, _m, _ = pipe(x)
            ser = series_of(linkage, f)
            return np.array([ser[t[0]][i] for i, t in enumerate(targets)]) * signs

        x_best, f_best = golden_section_max(values, lo_a, hi_a, iterations)
        tols = _golden_tol(lo_a, hi_a, iterations)
        for i, (sym, which, k) in enumerate(targets):
            cand = [(s_series[sym][k] * which, qs[k]), (f_best[i], x_best[i])]
            val, at = max(cand)
            # a grid point that ties or beats the refined value (by round-off, at a
            # maximum on the grid): the extreme is within the refined tolerance of
            # x_best, so within |at - x_best| + that of the grid point
            tol = tols[i] if at == x_best[i] else min(0.5 * float(hi_a[i] - lo_a[i]),
                                                      abs(at - x_best[i]) + tols[i])
            best[(sym, which)] = ForceExtreme(float(val * which), float(at), float(tol))
    extremes = {}
    for sym, signed in syms:
        hi = best[(sym, 1.0)]
        k_lo = int(np.argmin(s_series[sym]))
        lo = best[(sym, -1.0)] if signed else ForceExtreme(
            float(np.min(s_series[sym])), float(qs[k_lo]),
            0.5 * float(qs[min(k_lo + 1, qs.size - 1)] - qs[max(k_lo - 1, 0)]))
        extremes[sym] = (hi, lo)
    return extremes


def _active_intervals(linkage: Linkage, sweep: Sweep, progs: Sequence[Any],
                      masks: Dict[str, np.ndarray], grid: _Grid, q: np.ndarray
                      ) -> Dict[str, List[Tuple[float, float]]]:
    """Where the conditional loads act: grid edges refined by bisection."""
    active = {}
    for p in progs:
        if p.conditional:
            active[p.load.name] = _load_intervals(linkage, sweep, p, masks, grid, q)
    return active


def _load_intervals(linkage: Linkage, sweep: Sweep, p: Any, masks: Dict[str, np.ndarray],
                    grid: _Grid, q: np.ndarray) -> List[Tuple[float, float]]:
    """The (start, stop) input intervals where the conditional load ``p`` acts."""
    qs = grid.qs

    def state(x: np.ndarray) -> np.ndarray:
        m = solve(linkage, sweep.inputs(x), order=2)
        return p.active(x, m)

    mask = state(qs) if qs is not q else masks[p.load.name]
    intervals = []
    for a, b in grid.runs:
        m = mask[a:b]
        if not m.any():
            continue
        edges = np.flatnonzero(np.diff(m.astype(np.int8))) + a
        starts = [qs[a]] if m[0] else []
        stops = []
        for e in edges:
            if mask[e]:   # on -> off between e and e+1
                lo, hi = bisect(qs[e], qs[e + 1], lambda x: state(x), 1e-14)
                stops.append(float(lo))
            else:         # off -> on
                lo, hi = bisect(qs[e], qs[e + 1], lambda x: ~state(x), 1e-14)
                starts.append(float(hi))
        if m[-1]:
            stops.append(qs[b - 1])
        intervals += [(float(s), float(t)) for s, t in zip(starts, stops)]
    return intervals


def _balancing_mean_rms(linkage: Linkage, pipe: ForceEvaluator, grid: _Grid,
                        active: Dict[str, List[Tuple[float, float]]],
                        series: Dict[str, np.ndarray]
                        ) -> Tuple[Dict[str, float], Dict[str, float]]:
    """Mean and RMS of each balancing quantity over the analysed range: 4-point
    Gauss-Legendre on every grid interval, split where a conditional load switches
    (exact for the jumps)."""
    qs = grid.qs
    cuts = [e for iv in active.values() for pair in iv for e in pair]
    xs, ws = [], []
    span = 0.0
    for a, b in grid.runs:
        if b - a < 2:
            continue
        x, w = gauss_legendre(sorted_union(qs[a:b], [c for c in cuts if qs[a] < c < qs[b - 1]]))
        xs.append(x)
        ws.append(w)
        span += qs[b - 1] - qs[a]
    mean, rms = {}, {}
    if xs:
        xg, wg = np.concatenate(xs), np.concatenate(ws)
        fg, _m, _ = pipe(xg)
        gser = series_of(linkage, fg)
    for d in linkage.drivers:
        sym = balancing_symbol(linkage, d.link)
        if xs and span > 0:
            mean[sym], rms[sym] = mean_rms(wg, gser[sym], span)
        else:
            v = series[sym]
            mean[sym] = float(np.mean(v))
            rms[sym] = float(np.sqrt(np.mean(v * v)))
    return mean, rms


def _golden_tol(lo: FloatOrArray, hi: FloatOrArray, iterations: int, rtol: float = 1e-10):
    """How closely :func:`~mechcli.core.numerics.golden_section_max` locates each maximum:
    half its final bracket (the brackets shrink together by ``GOLDEN`` per step until
    every one is shorter than ``rtol · max(1, |lo|)``), but never less than what
    comparing values allows near a smooth maximum, about ``sqrt(EPS) · max(1, |x|)``
    (two inputs closer than that give values equal to round-off)."""
    from mechcli.core.numerics import GOLDEN
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    width = np.abs(hi - lo)
    need = rtol * np.maximum(1.0, np.abs(lo))
    steps = 0
    while steps < iterations and not np.all(width * GOLDEN ** steps < need):
        steps += 1
    return np.maximum(0.5 * width * GOLDEN ** steps,
                      np.sqrt(EPS) * np.maximum(1.0, np.abs(0.5 * (lo + hi))))


def _force_accuracy(linkage: Linkage, pipe: Any, kin: Any, q: np.ndarray, fr: Any):
    """Estimated correct digits of the force solve at the output rows and the refined
    near-dead positions (see :data:`FORCE_C`)."""
    runs = kin.runs or [(0, q.size)]
    segment = np.repeat(np.arange(len(runs)), [b - a for a, b in runs])
    kappa = amplification(linkage, kin.motion)[("all",)]
    cond = np.where(np.isfinite(fr.cond), fr.cond, 1.0 / EPS)
    d = _digits(FORCE_C * EPS * cond * kappa)
    extra = np.array([t.at for t in kin.toggles
                      if q.size and q[0] <= t.at <= q[-1] and not np.any(q == t.at)],
                     dtype=float)
    if extra.size:
        fr_t, _m, m_t = pipe(extra, condition=True)
        ok = m_t.regular
        cond_t = np.where(np.isfinite(fr_t.cond), fr_t.cond, 1.0 / EPS)
        d_t = _digits(FORCE_C * EPS * cond_t * amplification(linkage, m_t)[("all",)])[ok]
        extra = extra[ok]
        seg_t = segment[np.clip(np.searchsorted(q, extra) - 1, 0, max(q.size - 1, 0))]
        q_all = np.concatenate([q, extra])
        sort = np.argsort(q_all, kind="stable")
        q_all, d = q_all[sort], np.concatenate([d, d_t])[sort]
        segment = np.concatenate([segment, seg_t])[sort]
    else:
        q_all = q
    sym = balancing_symbol(linkage, linkage.drivers[0].link)
    return Accuracy(q_all, segment, {"forces": d}, {"forces": np.full(q_all.shape, sym,
                                                                       dtype=object)},
                    {sym: float(np.min(d)) if d.size else float(-np.log10(EPS))})

