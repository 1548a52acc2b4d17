"""The extremes of every quantity over a sweep, refined on the exact solution by a
bracketed search to 1e-15 ... 1e-10 rad of input, each with its tolerance
(:func:`refine_extremes`); the zeros of the slides' accelerations
(:func:`zero_crossings`)."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.linkage.accuracy import EPS
from mechcli.core.linkage.engine import solve
from mechcli.core.linkage.sweep import Extreme, _periodic, _wrap
from mechcli.core.numerics import bracketed_root
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    from mechcli.core.linkage.sweep import Sweep

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import Linkage


class _Domain:
    """The analysed input domain: continuous arcs (runs) of the grid ``q``, how
    far each run really extends (refined assembly limits), and whether the
    last run continues into the first one through a whole turn (periodic)."""

    def __init__(self, q: np.ndarray, runs: Sequence[Tuple[int, int]], lo_ext: FloatOrArray,
                 hi_ext: FloatOrArray, connected: bool, period: FloatOrArray,
                 ends: Optional[Tuple[float, float]] = None) -> None:
        self.q, self.runs = q, runs
        self.ends = ends if ends is not None else (q[0], q[-1])
        self.lo_ext, self.hi_ext = lo_ext, hi_ext  # per run: input where it really ends
        self.connected, self.period = connected, period

    def is_gap_edge(self, b: FloatOrArray):
        """Is input ``b`` the refined edge of a gap (not an end of the sweep)?"""
        return self.ends[0] < b < self.ends[1]

    def bracket(self, r, k, wraps=True):
        """Input interval around grid index ``k`` of run ``r`` to search for an extreme.

        ``wraps``: the quantity returns to its value after a whole turn, so the
        search may continue through 360° = 0°.
        """
        q = self.q
        i0, i1 = self.runs[r]
        connected = self.connected and wraps
        if k > i0:
            lo = q[k - 1]
        elif connected and r == 0:
            j0, j1 = self.runs[-1]
            lo = q[j1 - 2] - self.period if j1 - j0 > 1 else q[k]
        else:
            lo = self.lo_ext[r]
        if k < i1 - 1:
            hi = q[k + 1]
        elif connected and r == len(self.runs) - 1:
            j0, j1 = self.runs[0]
            hi = q[j0 + 1] + self.period if j1 - j0 > 1 else q[k]
        else:
            hi = self.hi_ext[r]
        return lo, hi


def _steady(sweep):
    """The sweep with no input acceleration, where its input speed is one constant
    (None otherwise).

    The time rate of a velocity is ``J'(q) dq^2 + J(q) ddq``; its derivative along the
    sweep, ``d(J dq)/dq``, is ``J'(q) dq`` when ``dq`` is one constant, whatever the
    sweep's ``ddq`` (the book's ``alpha1`` is used in the accelerations only, with
    ``omega1`` held at every position).  So with ``ddq = 0`` the rate over ``dq`` is that
    derivative exactly; with ``dq`` varying along the sweep it is not, and a difference
    is taken instead.
    """
    if callable(sweep.dq) or np.ndim(sweep.dq) != 0:
        return None
    if not callable(sweep.ddq) and np.ndim(sweep.ddq) == 0 and sweep.ddq == 0:
        return sweep
    return dataclasses.replace(sweep, ddq=0.0)


def _rate_is_slope(sweep: Sweep, getter: Any, speed: FloatOrArray):
    """Does ``getter``'s exact time rate over ``speed`` give its d/dq (see :func:`_steady`)?
    A position's rate (``J dq``) always does; a velocity's only at a constant input speed."""
    return getter[1] is not None and speed != 0 and (
        getter[3] == 0 or _steady(sweep) is not None)


class _SlopeProbe:
    """Sign-carrying d/dq of fixed targets, called on ``rep`` inputs per target (``x`` of
    size ``rep * len(getters)``, target ``j`` at ``x[j::len(getters)]``); returns
    ``(slopes, motion)``.

    ``getters[j]`` is ``(get, rate, is_angle, order)``: with an exact time rate the
    derivative is ``rate / dq``, solved with no input acceleration (:func:`_steady`; one
    solve); otherwise a central difference with step ``h`` (one-sided where a probe
    leaves the regular domain).  The targets are grouped once by quantity, so that a
    call evaluates every quantity's getter once on the solved motion and indexes it,
    whatever the number of targets.
    """

    def __init__(self, linkage, sweep, order, getters,
                 h):
        self.linkage, self.sweep, self.order, self.h = linkage, sweep, order, h
        self.n = len(getters)
        steady = _steady(sweep)
        # exact where the quantity has a rate usable as d/dq (the input speed != 0 is
        # checked per input, :func:`_rate_is_slope`)
        self.has_rate = np.array([g[1] is not None and (g[3] == 0 or steady is not None)
                                  for g in getters], dtype=bool)
        # only positions' rates are used when the input speed varies: they do not
        # depend on ddq
        self.steady = steady if steady is not None else dataclasses.replace(sweep, ddq=0.0)
        self.rate_groups = self._groups(getters, 1)
        self.get_groups = self._groups(getters, 0)
        self._plans = {}

    @staticmethod
    def _groups(getters, slot):
        """``[(function, is_angle, target indices)]``, one entry per distinct function."""
        seen = {}
        for j, g in enumerate(getters):
            fn = g[slot]
            if fn is None:
                continue
            key = (id(fn), g[2])
            if key not in seen:
                seen[key] = (fn, g[2], [])
            seen[key][2].append(j)
        return [(fn, is_angle, np.array(js)) for fn, is_angle, js in seen.values()]

    def _plan(self, rep: int, exact: Any):
        """Per group, the indices of its targets' inputs among ``rep`` copies, split into
        those taken from the rate (``exact``) and those taken by differences."""
        n = self.n
        out = []
        for groups, keep in ((self.rate_groups, exact), (self.get_groups, ~exact)):
            plan = []
            for fn, is_angle, js in groups:
                at = (js[None, :] + n * np.arange(rep)[:, None]).ravel()
                at = at[keep[at]]
                if at.size:
                    plan.append((fn, is_angle, at))
            out.append(plan)
        return out

    def __call__(self, x):
        x = np.asarray(x, dtype=float)
        sweep = self.sweep
        rep = x.size // self.n
        speed = sweep.speed(x)
        if np.ndim(speed) == 0:   # one input speed: the plan depends on rep only
            key = (rep, speed != 0)
            if key not in self._plans:
                self._plans[key] = self._plan(rep, np.tile(self.has_rate, rep) & (speed != 0))
            rates, diffs = self._plans[key]
        else:
            speed = np.broadcast_to(speed, x.shape)
            rates, diffs = self._plan(rep, np.tile(self.has_rate, rep) & (speed != 0))
        m = m_rate = None
        if diffs:
            probe = np.concatenate([x, x - self.h, x + self.h])
            m = solve(self.linkage, sweep.inputs(probe), order=min(self.order + 1, 2))
        out = np.zeros(x.size)
        if rates:
            m_rate = m if self.steady is sweep and m is not None else \
                solve(self.linkage, self.steady.inputs(x), order=min(self.order + 1, 2))
            for rate, _is_angle, at in rates:
                out[at] = np.asarray(rate(m_rate), dtype=float)[at] / (
                    speed if np.ndim(speed) == 0 else speed[at])
        if diffs:
            N = x.size
            reg = m.regular
            with np.errstate(invalid="ignore", over="ignore"):   # of the sides not taken
                for get, is_angle, at in diffs:
                    f = np.asarray(get(m), dtype=float)
                    f0, fm, fp = f[at], f[N + at], f[2 * N + at]
                    rm, rp = reg[N + at], reg[2 * N + at]
                    d = np.where(rm & rp, fp - fm,
                                 np.where(rp, fp - f0, np.where(rm, f0 - fm, 0.0)))
                    out[at] = _wrap(d) if is_angle else d
        return out, (m if m is not None else m_rate)


def _transmission_measure(joint: str):
    """A smooth function of the motion that rises and falls with the acute transmission
    angle of the dyad at ``joint`` (``DyadCondition.gamma``): ``-cos_joint**2`` (gamma =
    atan2(|sin|, |cos|) of the joint angle, the largest where its cosine is 0), or
    ``sin_gamma**2`` where the dyad gives no cosine (gamma = asin(sin_gamma)).  Gamma
    folds at 90° (a kink, where its difference quotient has one magnitude either side and
    a secant search on it only bisects); this measure has a smooth extremum there."""
    def measure(m: Any):
        c = m.condition(joint)
        if c.cos_joint is None:
            return c.sin_gamma * c.sin_gamma
        return -(c.cos_joint * c.cos_joint)
    return measure


def _transmission_measure_rate(linkage: Linkage, joint: str):
    """The exact time rate of :func:`_transmission_measure` for the RRR dyad whose joint
    is ``joint`` (None for any other dyad).

    With ``ra = J - A`` and ``rb = J - B`` the dyad's two link vectors (A, B its known
    points, J its joint), the joint angle's cosine is ``c = ra.rb / (|ra| |rb|)``; the
    lengths are constant, so ``dc/dt = (dra.rb + ra.drb) / (|ra| |rb|)`` with
    ``dra = vJ - vA``, ``drb = vJ - vB`` (the engine's point velocities, exact), and the
    measure ``-c**2`` has the rate ``-2 c dc/dt``: its extremes are located on an exact
    derivative instead of a central difference (whose O(h**2) bias is 1e-11 rad of input
    on 例 1-1's γC)."""
    el = next((e for e in linkage.elements if e.transmission_joint() == joint), None)
    if el is None or getattr(el, "kind", None) != "RRR":
        return None

    def rate(m):
        c = m.condition(joint).cos_joint
        pj, pa, pb = m.points[el.joint], m.points[el.point_a], m.points[el.point_b]
        rax, ray = pj.x - pa.x, pj.y - pa.y
        rbx, rby = pj.x - pb.x, pj.y - pb.y
        dax, day = pj.vx - pa.vx, pj.vy - pa.vy
        dbx, dby = pj.vx - pb.vx, pj.vy - pb.vy
        dc = (dax * rbx + day * rby + rax * dbx + ray * dby) / (
            np.hypot(rax, ray) * np.hypot(rbx, rby))
        return -2.0 * c * dc
    return rate


def _slope_getters(qt: Any, linkage: Optional[Linkage] = None):
    """``(get, rate, is_angle, order)`` whose slope :class:`_SlopeProbe` takes for the
    extremes of ``qt``: its own, but a transmission angle's smooth measure
    (:func:`_transmission_measure`, same extrema) with its exact rate where the dyad
    gives one (:func:`_transmission_measure_rate`)."""
    if qt.rate is None and qt.source and qt.source[0] == "joint" and qt.is_angle:
        rate = None if linkage is None else _transmission_measure_rate(linkage, qt.source[1])
        return (_transmission_measure(qt.source[1]), rate, False, 0)
    return (qt.get, qt.rate, qt.is_angle, qt.order)


def refine_extremes(linkage: Linkage, sweep: Any, order: int, quantities: Sequence[Any],
                    values: Dict[str, np.ndarray], domain: _Domain, iterations: int = 64,
                    max_candidates: int = 6) -> Dict[str, Tuple[Extreme, Extreme]]:
    """Max and min of every quantity, located to ~1e-10 rad of input.

    Every local extremum of the grid within each run (the run ends included,
    searched out to the refined assembly limits) is a candidate; each is
    refined on the exact derivative (the next-order quantity of the engine),
    or on a central difference (h = 1e-5 rad) for quantities without one: by
    a safeguarded secant where the derivative changes sign across the
    bracket (:func:`~mechcli.core.numerics.bracketed_root`, a few solves), by
    bisection on its sign otherwise; the best refined value wins, reported with the
    input where it was evaluated.  A central difference's bracket closes no further
    than its rounding error (:func:`_difference_tol`); its tolerance adds the bias of the
    difference, measured at the located input (:func:`_truncation_shift`).  A
    transmission angle is refined on a smooth measure with the same extrema
    (:func:`_transmission_measure`: it folds at 90°), on its exact rate for an RRR dyad
    (:func:`_transmission_measure_rate`).  All targets share each solve.

    The steps: the candidates (:func:`_extreme_targets`), their brackets
    (:func:`_target_brackets`), the first bisection step (:func:`_first_halving`), the
    secant search (:func:`_close_brackets`), the best value per quantity and sign
    (:func:`_best_candidates`), the extremes (:func:`_extremes_of`).
    """
    q = domain.q
    span = float(q[-1] - q[0]) if q.size > 1 else 1.0
    rotary = linkage.driver(sweep.driver).rotary
    h = 1e-5 if rotary else 1e-5 * max(abs(span), 1e-12)
    targets = _extreme_targets(quantities, values, domain, max_candidates)
    if not targets:
        return {}
    wraps, lo, hi = _target_brackets(quantities, values, domain, targets)
    by_quantity = {}   # one getter per quantity: a solve evaluates each once
    for qi, *_ in targets:
        if qi not in by_quantity:
            by_quantity[qi] = _slope_getters(quantities[qi], linkage)
    s = _Search(linkage, sweep, order, quantities, values, domain, targets,
                [by_quantity[qi] for qi, *_ in targets], np.array([t[1] for t in targets]), h)
    width0 = np.abs(hi - lo)   # the search brackets, before refinement
    lo, hi, d_lo, d_hi, proper, mid = _first_halving(s, lo, hi)
    if proper.any():
        _close_brackets(s, lo, hi, d_lo, d_hi, proper, mid, iterations)
    best = _best_candidates(s, lo, hi, width0)
    return _extremes_of(s, best, wraps)


@record
class _Search:
    """What the steps of :func:`refine_extremes` share: the problem, the targets
    ``(quantity index, sign, run, grid index)``, their slope ``getters``
    (:func:`_slope_getters`) and ``signs``, and the difference step ``h``."""

    linkage: Any
    sweep: Any
    order: int
    quantities: Sequence[Any]
    values: Dict[str, np.ndarray]
    domain: Any
    targets: List[Tuple[int, float, int, int]]
    getters: List[Any]
    signs: np.ndarray
    h: float

    def slope(self, idx: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
        """Signed derivative of the targets ``idx`` (> 0: the extreme lies further on);
        called with several inputs per target (the probes of :func:`bracketed_root`)."""
        probe = _SlopeProbe(self.linkage, self.sweep, self.order,
                            [self.getters[i] for i in idx], self.h)
        sg = self.signs[idx]

        def f(x: np.ndarray) -> np.ndarray:
            return np.tile(sg, x.size // len(idx)) * probe(x)[0]
        return f


def _extreme_targets(quantities: Sequence[Any], values: Any,
                     domain: Any, max_candidates: Any
                     ):
    """``(quantity index, sign, run, grid index)`` of the best ``max_candidates`` local
    extrema of the grid, per quantity and sign."""
    targets = []  # (symbol index, sign, run, k)
    for qi, qt in enumerate(quantities):
        v = values[qt.symbol]
        for sign in (1.0, -1.0):
            cands = []
            for r, (i0, i1) in enumerate(domain.runs):
                w = sign * v[i0:i1]
                n = w.size
                if n == 1:
                    cands.append((w[0], r, i0))
                    continue
                left = np.concatenate(([-np.inf], w[:-1]))
                right = np.concatenate((w[1:], [-np.inf]))
                for k in np.flatnonzero((w >= left) & (w >= right)):
                    cands.append((w[k], r, i0 + int(k)))
            cands.sort(key=lambda c: -c[0])
            for _val, r, k in cands[:max_candidates]:
                targets.append((qi, sign, r, k))
    return targets


def _target_brackets(quantities: Sequence[Any], values: Dict[str, np.ndarray],
                     domain: _Domain, targets: List[Tuple[int, float, int, int]]
                     ) -> Tuple[Dict[str, Any], np.ndarray, np.ndarray]:
    """symbol -> does the quantity return to its value over the sweep; the search
    bracket ``(lo, hi)`` of every target."""
    lo = np.empty(len(targets))
    hi = np.empty(len(targets))
    wraps = {}
    for qt in quantities:
        v = values[qt.symbol]
        wraps[qt.symbol] = abs(v[-1] - v[0]) <= 1e-9 * max(1.0, float(np.max(np.abs(v))))
    for j, (qi, sign, r, k) in enumerate(targets):
        lo[j], hi[j] = domain.bracket(r, k, wraps[quantities[qi].symbol])
    return wraps, lo, hi


def _first_halving(s: _Search, lo: np.ndarray, hi: np.ndarray
                   ) -> Tuple[np.ndarray, ...]:
    """The first step of a bisection on the sign of the derivative, with the derivative
    at both ends too (one solve): the half that bisection keeps either has a sign
    change (``proper``: closed by a safeguarded secant, a few solves instead of ~40)
    or the derivative has one sign over it, and bisection would close on its far end
    (the end of a run, or no extreme inside): taken directly, as bisection's last
    bracket.  Returns ``(lo, hi, d_lo, d_hi, proper, mid)``."""
    n_t = len(s.targets)
    mid = 0.5 * (lo + hi)
    d = s.slope(np.arange(n_t))(np.concatenate([lo, mid, hi]))
    d_lo, d_mid, d_hi = d[:n_t], d[n_t:2 * n_t], d[2 * n_t:]
    up = d_mid > 0                       # bisection's keep_lo at the midpoint
    lo, d_lo = np.where(up, mid, lo), np.where(up, d_mid, d_lo)
    hi, d_hi = np.where(up, hi, mid), np.where(up, d_hi, d_mid)
    proper = (d_lo > 0) & ~(d_hi > 0)
    tol = 1e-13 * np.maximum(1.0, np.abs(lo))
    to_hi = ~proper & (d_lo > 0)         # rising throughout: bisection closes on hi
    lo = np.where(to_hi, hi - np.copysign(tol, hi - lo), lo)
    hi = np.where(~proper & ~to_hi, lo + np.copysign(tol, hi - lo), hi)
    return lo, hi, d_lo, d_hi, proper, mid


def _close_brackets(s: _Search, lo: np.ndarray, hi: np.ndarray, d_lo: np.ndarray,
                    d_hi: np.ndarray, proper: np.ndarray, mid: np.ndarray,
                    iterations: int) -> None:
    """Close the ``proper`` brackets (in place) by a safeguarded secant on the slope.

    A central difference locates its extreme no closer than its rounding allows
    (:func:`_difference_tol`, the tolerance reported for it): its bracket need not
    close further than that."""
    idx = np.flatnonzero(proper)
    rtol = np.full(idx.size, 1e-13)
    spd0 = np.broadcast_to(s.sweep.speed(mid), mid.shape)
    for i, j in enumerate(idx):
        if not _rate_is_slope(s.sweep, s.getters[j], spd0[j]):
            qi, _sign, r, k = s.targets[j]
            dtol = _difference_tol(s.values[s.quantities[qi].symbol], s.domain.q,
                                   s.domain.runs[r], k, s.h)
            rtol[i] = max(1e-13, dtol / max(1.0, abs(float(lo[j]))))
    lo[idx], hi[idx] = bracketed_root(lo[idx], hi[idx], s.slope(idx), rtol, iterations,
                                      d_lo[idx], d_hi[idx])


def _best_candidates(s: _Search, lo: Any, hi: Any, width0: Any
                     ) -> Dict[Tuple[str, float], Tuple[float, float, float]]:
    """(symbol, sign) -> (value, input, tol) of the best target: the refined value where
    the located input is regular and no worse than its grid value, else the grid's."""
    linkage, sweep, h, n_t = s.linkage, s.sweep, s.h, len(s.targets)
    q, values = s.domain.q, s.values
    at = 0.5 * (lo + hi)
    spd = np.broadcast_to(sweep.speed(at), at.shape)
    by_diff = np.array([not _rate_is_slope(sweep, s.getters[j], spd[j]) for j in range(n_t)],
                       dtype=bool)
    diff = np.flatnonzero(by_diff)
    # the targets located on a central difference are solved at +-h and +-2h as well (in
    # the same solve): the bias of the difference (:func:`_truncation_shift`)
    m = solve(linkage, sweep.inputs(np.concatenate(
        [at] + [at[diff] + sh * h for sh in (-1.0, 1.0, -2.0, 2.0)])), order=s.order)
    shift = _truncation_shift(m, s.getters, diff, n_t, h)
    best: Dict[Tuple[str, float], Tuple[float, float, float]] = {}
    for j, (qi, sign, r, k) in enumerate(s.targets):
        qt = s.quantities[qi]
        vgrid = float(values[qt.symbol][k])
        cand = (vgrid, float(q[k]), 0.5 * float(width0[j]))
        if m.regular[j]:
            val = float(qt.get(m)[j])
            if qt.is_angle:
                val = vgrid + float(_wrap(val - vgrid))
            if sign * val >= sign * vgrid:
                # no closer than a few units in the last place of the location itself
                tol = max(0.5 * abs(float(hi[j] - lo[j])), 4.0 * float(np.spacing(abs(at[j]))))
                if by_diff[j]:
                    dtol = _difference_tol(values[qt.symbol], q, s.domain.runs[r], k, h)
                    tol = max(tol, dtol + TRUNCATION_MARGIN * shift.get(j, 0.0))
                cand = (val, float(at[j]), tol)
        key = (qt.symbol, sign)
        if key not in best or sign * cand[0] > sign * best[key][0]:
            best[key] = cand
    return best


def _extremes_of(s: _Search, best: Dict[Tuple[str, float], Tuple[float, float, float]],
                 wraps: Dict[str, Any]) -> Dict[str, Tuple[Extreme, Extreme]]:
    """symbol -> (max, min) :class:`Extreme`: bounded unless at a gap edge, the input
    wrapped into the period of a periodic sweep."""
    domain = s.domain
    gap_edges = [b for r in range(len(domain.runs))
                 for b in (domain.lo_ext[r], domain.hi_ext[r]) if domain.is_gap_edge(b)]
    out = {}
    for qt in s.quantities:
        ext = []
        for sign in (1.0, -1.0):
            val, pos, tol = best[(qt.symbol, sign)]
            bounded = qt.order == 0 or not any(
                abs(pos - b) <= 1e-7 * max(1.0, abs(b)) for b in gap_edges)
            if s.sweep.periodic and domain.connected and wraps[qt.symbol]:
                pos = _periodic(pos, domain.ends[0], domain.period)
            ext.append(Extreme(val, float(pos), bounded, tol))
        out[qt.symbol] = (ext[0], ext[1])
    return out


#: below this fraction of a function's largest magnitude over the sweep a sample is
#: round-off of zero: no root is sought between two such samples
ZERO_NOISE = 1e-12


def zero_crossings(q, values, runs,
                   f, rtol=1e-15, iterations=64):
    """Every input where a sampled function crosses or touches 0, refined.

    Parameters
    ----------
    q, values : ndarray
        The samples (inputs [rad or m], values).
    runs : list of (int, int)
        Index ranges of ``q`` that are continuous arcs (no root is sought across a gap).
    f : callable
        ``f(x) -> ndarray``, the function at inputs ``x`` (one call for all brackets).
    rtol : float
        Relative bracket width at which the search stops.

    Returns
    -------
    list of (float, float)
        ``(at, tol)`` in order: a sample that is exactly 0 is a root with ``tol = 0``;
        a sign change between neighbours is closed by :func:`bracketed_root` and ``tol``
        is half its final bracket (at least a float spacing).
    """
    out, lo, hi, sgn = [], [], [], []
    every = np.asarray(values, dtype=float)
    # a stretch where the function is zero to round-off (a slider resting at a change
    # point while the crank turns) has no roots to report: its sign is noise
    noise = ZERO_NOISE * (float(np.max(np.abs(every))) if every.size else 0.0)
    for i0, i1 in runs:
        w = np.asarray(values[i0:i1], dtype=float)
        big = np.abs(w) > noise
        near = big.copy()          # a sample counts when it or a neighbour is not noise
        near[1:] |= big[:-1]
        near[:-1] |= big[1:]
        for k in np.flatnonzero((w == 0.0) & near):
            out.append((float(q[i0 + k]), 0.0))
        for k in np.flatnonzero((w[:-1] * w[1:] < 0) & (big[:-1] | big[1:])):
            lo.append(q[i0 + k]); hi.append(q[i0 + k + 1]); sgn.append(np.sign(w[k]))
    if lo:
        lo, hi, sgn = np.array(lo, float), np.array(hi, float), np.array(sgn)
        a, b = bracketed_root(lo, hi, lambda x: np.tile(sgn, x.size // sgn.size) * f(x),
                              rtol, iterations)
        for x0, x1 in zip(a, b):
            at = 0.5 * (x0 + x1)
            out.append((float(at), max(0.5 * abs(float(x1 - x0)), float(np.spacing(abs(at))))))
    return sorted(out)


def _slide_zeros(linkage: Linkage, sweep: Sweep, order: int, quantities: Sequence[Any],
                 values: Dict[str, Any], q: Any, runs: Sequence[Tuple[int, int]],
                 periodic: bool, q0: Any, period: Any):
    """:func:`zero_crossings` of every slide acceleration (``SweepResult.zeros``)."""
    out = {}
    for qt in quantities:
        if qt.kind != "acceleration" or not qt.source or qt.source[0] != "slide" \
                or order < 2:
            continue

        def f(x: Any, qt: Any = qt):
            m = solve(linkage, sweep.inputs(x), order=2)
            return np.where(m.regular, np.asarray(qt.get(m), dtype=float), np.nan)
        roots = zero_crossings(q, values[qt.symbol], runs, f)
        if periodic:   # 0° and 360° of a whole turn are one input
            roots = sorted((_periodic(a, q0, period), t) for a, t in roots)
            roots = [r for i, r in enumerate(roots)
                     if i == 0 or abs(r[0] - roots[i - 1][0]) > max(r[1], roots[i - 1][1])]
        out[qt.symbol] = roots
    return out


#: the estimate of a central difference's bias (:func:`_truncation_shift`) is taken with
#: this margin in a tolerance: its own error is O(h**2) relative (the next term of the
#: series) plus the rounding of its f'' (4 EPS |f| / h**2).  1.25 was measured short on
#: 7 of 529 random four-bars' acceleration extremes (the error up to 2.15x the bias), hence 3
TRUNCATION_MARGIN = 3.0


def _truncation_shift(m, getters, diff, n,
                      h):
    """``{target: |x - x*|}``: how far from the true extreme ``x*`` each target ``j`` of
    ``diff`` (located at ``x``, a root of the central difference of step ``h`` of its
    ``getters[j][0]``) lies, from the motion ``m`` solved at the ``n`` targets' ``x``
    followed by ``x - h``, ``x + h``, ``x - 2h``, ``x + 2h`` of the targets ``diff``.

    The central difference ``D_h = f' + h**2 f'''/6 + O(h**4)`` is biased: its root lies
    ``h**2 f''' / (6 f'')`` from that of ``f'`` (1e-11 rad of input at h = 1e-5 for the
    accelerations of 例 1-1, more than its rounding).  Richardson's combination
    ``(4 D_h - D_2h) / 3 = f' + O(h**4)`` gives ``f'(x)`` itself, and one Newton step
    ``|f'(x) / f''(x)|`` (``f''`` from the same samples) the distance to the extreme.
    It includes the rounding of the differences (``_difference_tol`` bounds it) and the
    bracket's own offset.  A target with a probe that is not regular is left out.
    """
    out = {}
    if diff.size == 0:
        return out
    nd = diff.size
    reg = m.regular
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        for i, j in enumerate(diff):
            at = [j] + [n + s * nd + i for s in range(4)]
            if not np.all(reg[at]):
                continue
            get, _rate, is_angle, _order = getters[j]
            f = np.asarray(get(m), dtype=float)
            f0, fm1, fp1, fm2, fp2 = (float(f[a]) for a in at)

            def dif(a: FloatOrArray, b: FloatOrArray, is_angle: bool = is_angle):
                return float(_wrap(a - b)) if is_angle else a - b
            d1 = dif(fp1, fm1) / (2.0 * h)
            d2 = dif(fp2, fm2) / (4.0 * h)
            f2 = (dif(fp1, f0) - dif(f0, fm1)) / (h * h)
            est = abs((4.0 * d1 - d2) / 3.0 / f2) if f2 != 0.0 else np.inf
            if np.isfinite(est):
                out[int(j)] = est
    return out


def _difference_tol(v: Any, q: Any, run: Tuple[int, int], k: int, h: Any):
    """How closely a central difference of step ``h`` locates the extreme of the samples
    ``v`` near grid index ``k``: its rounding, about 2 EPS |f|, over its slope
    2 h |f''| (f'' from the grid's second difference at ``k``), with a factor 2 of
    margin: ``4 EPS |f| / (h |f''|)``.  0 where the grid cannot tell f''."""
    i0, i1 = run
    if not i0 < k < i1 - 1:
        return 0.0
    d2 = abs(float(v[k - 1] - 2 * v[k] + v[k + 1]))
    dq = 0.5 * float(q[k + 1] - q[k - 1])
    if d2 == 0.0 or dq <= 0.0:
        return 0.0
    f2 = d2 / (dq * dq)
    peak = float(np.max(np.abs(v[i0:i1])))
    return 4.0 * EPS * peak / (h * f2)
