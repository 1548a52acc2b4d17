"""Where a linkage cannot assemble or is at a dead point: the ends of every gap as
the roots of a dyad's discriminant (:func:`assembly_limits`), every dead point as one
input with its uncertainty (:func:`dead_points`), the toggles a grid passes near
(:func:`_scan_gaps`), and the wording-free description of the excluded ranges."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from mechcli.core.linkage.engine import solve
from mechcli.core.linkage.sweep import NEAR_TOGGLE_SIN, DeadPoint, Toggle
from mechcli.core.numerics import bisect
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    pass

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import Linkage
    from mechcli.core.linkage.sweep import Sweep


def _bisect_boundaries(linkage: Linkage, sweep: Sweep, order: int, good: np.ndarray,
                       bad: Optional[np.ndarray]):
    """Refine boundaries between regular inputs ``good`` and irregular ``bad``.

    Returns the last regular input of every pair (to ~1e-15 relative).
    """
    def regular(mid: Any):
        return solve(linkage, sweep.inputs(mid), order=order).regular

    return bisect(good, bad, regular, 1e-15)[0]


#: sin(gamma) at or below this is zero to round-off: a dyad's sin(gamma) is the root of
#: its (rounded) discriminant, clipped at 0 where that is negative, and its rounding
#: noise there is a few EPS, so sin(gamma)^2 = 1e-26 is 1e-26 / slope past the root
SIN_ZERO = 1e-13
#: the rounding of a dyad's sin(gamma)^2 (proportional to its discriminant), relative to
#: 1: a few operations on the rounded inputs (a crank's cos/sin, the lengths).  Measured
#: on the four-bar gap of tests/unit/linkage/test_gap_boundaries.py against a 40-digit root:
#: 9.4 EPS; about 3.5 times that is taken
ROUNDING = 32 * float(np.finfo(float).eps)


def _assembles(linkage: Linkage, sweep: Sweep, x: FloatOrArray):
    """Does the linkage assemble at inputs ``x`` with every dyad's discriminant > 0?
    Also returns the smallest sin(gamma) of the dyads there."""
    m = solve(linkage, sweep.inputs(np.asarray(x, dtype=float)), order=0)
    low = np.min([c.sin_gamma for c in m.conditions], axis=0) if m.conditions else \
        np.ones(np.shape(x))
    return m.feasible & (low > SIN_ZERO), low


def _input_scale(linkage: Linkage, sweep: Sweep):
    """1 rad for a crank, the sweep's span [m] for a slider: what 'relative' input means."""
    if linkage.driver(sweep.driver).rotary:
        return 1.0
    q = np.asarray(sweep.q, dtype=float)
    return max(float(abs(q[-1] - q[0])) if q.size else 0.0, float(np.max(linkage.scale())))


def assembly_limits(linkage: Linkage, sweep: Sweep, inside: FloatOrArray, outside: FloatOrArray,
                    iterations: int = 80):
    """The inputs where the linkage stops assembling, between ``inside`` (assembles) and
    ``outside`` (does not), and how closely each is located.

    The limit is where a dyad's discriminant crosses 0 (for an RRR dyad between
    points P and Q: PQ = l_a + l_b or |l_a - l_b|; sin(gamma)^2 is proportional
    to the discriminant).  Bisection on the sign of the discriminant as the engine
    rounds it (sin(gamma) > ``SIN_ZERO``) closes on its root to a float spacing; the
    root itself is known only as well as the rounded discriminant allows, about
    ``ROUNDING / k`` with k = d(sin^2 gamma)/dq there, which ``tol`` includes.

    Returns
    -------
    at, tol : ndarray
        The last input that assembles, and the half-width of the uncertainty [rad or m].
    """
    inside = np.asarray(inside, dtype=float)
    outside = np.asarray(outside, dtype=float)
    if inside.size == 0:
        return inside.copy(), inside.copy()
    lo, hi = bisect(inside, outside, lambda x: _assembles(linkage, sweep, x)[0], 0.0,
                    iterations)
    # the slope of sin^2(gamma) just inside the limit: k = s^2 / delta
    delta = 1e-6 * _input_scale(linkage, sweep) * np.sign(inside - outside)
    probe = lo + delta
    ok, low = _assembles(linkage, sweep, probe)
    k = np.where(ok, low * low / np.abs(delta), 0.0)
    with np.errstate(divide="ignore"):
        noise = np.where(k > 0, ROUNDING / np.where(k > 0, k, 1.0), np.abs(delta))
    tol = np.maximum.reduce([0.5 * np.abs(hi - lo), np.minimum(noise, np.abs(delta)),
                             np.spacing(np.abs(lo))])
    return lo, tol


def _touch_minimum(linkage: Linkage, sweep: Sweep, ci: int, c0: int, R: FloatOrArray):
    """The minimum of sin^2(gamma) of condition ``ci`` near ``c0``, from the 6-point
    stencil c0 ± R, ± 2R, ± 3R (a degree-5 interpolant; sin^2(gamma) is smooth through
    a touching zero, sin(gamma) is not).  Returns ``(t, noise)`` in input units, or
    None where a stencil point does not assemble."""
    t = np.array([-3.0, -2.0, -1.0, 1.0, 2.0, 3.0])
    m = solve(linkage, sweep.inputs(c0 + R * t), order=0)
    if not m.feasible.all():
        return None
    g = m.conditions[ci].sin_gamma ** 2
    p = np.polynomial.Polynomial.fit(t, g, 5, domain=[-1, 1], window=[-1, 1])
    dp, ddp = p.deriv(), p.deriv(2)
    roots = dp.roots()
    roots = roots[np.abs(roots.imag) < 1e-9].real
    roots = roots[(np.abs(roots) <= 1.5) & (ddp(roots) > 0)]
    if roots.size == 0:
        return None
    r = roots[np.argmin(np.abs(roots))]
    # rounding: sin^2(gamma) carries about ROUNDING; p'(0) weighs the samples by
    # (45, 9, 1) / 60 per side, so p' is off by ~1.83 ROUNDING (per R), and t by that / p''
    noise = 1.83 * ROUNDING / max(float(ddp(r)), 1e-300)
    return float(r) * R, noise * R


def dead_points(linkage, sweep, excluded):
    """One input, with its uncertainty, for every ``dead point`` interval of ``excluded``
    that holds an isolated zero of a dyad's sin(gamma) (see :class:`DeadPoint`).

    The dyad is the one with the smallest sin(gamma) at the interval's middle.  Where
    sin(gamma) falls to 0 and rises again (a touch), the dead point is the minimum of
    sin^2(gamma) -- smooth there, ~ k (q - q0)^2 -- from a 6-point stencil at a radius R
    where sin(gamma) is >= 1e-3 (so its rounding, a few EPS / sin(gamma), hardly
    matters), applied twice; the uncertainty is the second correction plus the rounding
    of the stencil (about 2 ``ROUNDING`` / (k R)).  Where sin(gamma) reaches 0 at a limit of
    assembly (no assembly on one side), the dead point is that limit
    (:func:`assembly_limits`).  An interval where sin(gamma) stays 0 (two parallel guides)
    has no single dead point and gives none.
    """
    scale = _input_scale(linkage, sweep)
    out = []
    for a, b, why in excluded:
        if why != "dead point":
            continue
        c0 = 0.5 * (a + b)
        m0 = solve(linkage, sweep.inputs(np.array([c0])), order=0)
        if not m0.conditions:
            continue
        ci = int(np.argmin([float(c.sin_gamma[0]) for c in m0.conditions]))
        cond = m0.conditions[ci]
        # a ladder of radii: the smallest where both sides have sin(gamma) >= 1e-3
        radii = max(4.0 * (b - a), 1e-9 * scale) * 4.0 ** np.arange(16)
        radii = radii[radii <= 0.05 * scale]
        if radii.size == 0:
            continue
        m = solve(linkage, sweep.inputs(np.concatenate([c0 - radii, c0 + radii])), order=0)
        s = m.conditions[ci].sin_gamma
        n = radii.size
        left_ok = m.feasible[:n] & (s[:n] > SIN_ZERO)
        right_ok = m.feasible[n:] & (s[n:] > SIN_ZERO)
        both = left_ok & right_ok & (np.minimum(s[:n], s[n:]) >= 1e-3)
        found = None
        if both.any():
            R = float(radii[np.argmax(both)]) / 3.0
            first = _touch_minimum(linkage, sweep, ci, c0, R)
            if first is not None:
                c1 = c0 + first[0]
                second = _touch_minimum(linkage, sweep, ci, c1, R)
                if second is not None:
                    at = c1 + second[0]
                    tol = max(abs(second[0]), 2.0 * second[1], float(np.spacing(abs(at))))
                    found = (at, tol, "touch")
        elif left_ok.any() != right_ok.any():
            # assembles on one side only: the dead point is the limit of assembly
            side = left_ok if left_ok.any() else right_ok
            sign = -1.0 if left_ok.any() else 1.0
            inside = c0 + sign * float(radii[np.argmax(side)])
            outside = c0 - sign * float(radii[0])
            if not _assembles(linkage, sweep, [outside])[0][0]:
                at, tol = assembly_limits(linkage, sweep, [inside], [outside])
                found = (float(at[0]), float(tol[0]), "limit")
        if found is not None:
            out.append(DeadPoint(found[0], found[1], cond.joint, cond.kind, (a, b), found[2]))
    return out


def _scan_gaps(linkage, sweep, order, q, motion,
               runs):
    """Find dead points and assembly gaps the grid stepped over, and near-toggles.

    Every grid minimum of a dyad's sin(gamma) below ``NEAR_TOGGLE_SIN``
    (run ends included) is refined by bisection on the sign of its central
    difference.  Returns ``(toggles, gaps)``: refined near-dead positions that
    are regular, and ``(input, grid index)`` of refined minima that turned out
    not to be regular (a gap or dead point between grid points).
    """
    targets = []
    for ci, c in enumerate(motion.conditions):
        s = c.sin_gamma
        for (i0, i1) in runs:
            w = s[i0:i1]
            if w.size < 2:
                continue
            left = np.concatenate(([np.inf], w[:-1]))
            right = np.concatenate((w[1:], [np.inf]))
            cand = (w <= left) & (w <= right) & (w < NEAR_TOGGLE_SIN)
            # a run end next to a gap is not a toggle of its own: the gap's
            # refined edges are reported instead
            if i0 > 0:
                cand[0] = False
            if i1 < q.size:
                cand[-1] = False
            for k in np.flatnonzero(cand):
                k = i0 + int(k)
                targets.append((ci, k, q[max(k - 1, i0)], q[min(k + 1, i1 - 1)]))
    if not targets:
        return [], []
    lo = np.array([t[2] for t in targets], dtype=float)
    hi = np.array([t[3] for t in targets], dtype=float)
    h = 1e-7 * max(1.0, float(np.max(np.abs(q))))
    T = len(targets)

    def falling(mid: FloatOrArray):
        m = solve(linkage, sweep.inputs(np.concatenate([mid - h, mid + h])), order=0)
        return np.array([m.conditions[ci].sin_gamma[T + j] - m.conditions[ci].sin_gamma[j]
                         for j, (ci, *_r) in enumerate(targets)]) < 0

    lo, hi = bisect(lo, hi, falling, 1e-14, 60)
    at = 0.5 * (lo + hi)
    m = solve(linkage, sweep.inputs(at), order=order)
    toggles, gaps = [], []
    for j, (ci, k, _lo, _hi) in enumerate(targets):
        c = m.conditions[ci]
        if m.regular[j]:
            toggles.append(Toggle(float(at[j]), c.joint, c.kind, float(c.sin_gamma[j])))
        else:
            gaps.append((float(at[j]), k))
    return toggles, gaps


def _refined_exclusions(linkage, sweep, excluded, ends,
                        bounds):
    """The excluded intervals with every ``cannot assemble`` end that lies between a
    regular input and one that does not assemble moved onto the root of the dyad's
    discriminant (:func:`assembly_limits`); the other ends stay the last regular input.
    Returns ``(excluded, tol)``: ``tol`` holds ``(tol_start, tol_stop)`` per interval."""
    inside, outside, where = [], [], []
    for j, ((start, stop, why), (do_lo, do_hi, out_lo, out_hi)) in enumerate(zip(excluded,
                                                                                ends)):
        if why != "cannot assemble":
            continue
        if do_lo:
            inside.append(start); outside.append(out_lo); where.append((j, 0))
        if do_hi:
            inside.append(stop); outside.append(out_hi); where.append((j, 1))
    out = [list(e) for e in excluded]
    # an end the bisection placed is good to its bracket (~1e-15 relative); a sweep end is exact
    tol = [[1e-15 * max(1.0, abs(a)) if a in bounds.values() else 0.0,
            1e-15 * max(1.0, abs(b)) if b in bounds.values() else 0.0]
           for a, b, _w in excluded]
    if inside:
        at, t = assembly_limits(linkage, sweep, inside, outside)
        for (j, side), x, tx in zip(where, at, t):
            out[j][side] = float(x)
            tol[j][side] = float(tx)
    return [tuple(e) for e in out], [tuple(t) for t in tol]


def _limits_are_not_dead_points(excluded: Any, excluded_tol: Any, deads: Any):
    """A ``dead point`` interval whose zero of sin(gamma) is a limit of assembly (the
    sweep ends on it: a :class:`DeadPoint` of shape ``"limit"``) is what a gap's end is,
    a limit of assembly, not a dead point: it becomes a ``cannot assemble`` interval that
    starts (or stops) at that limit, with its uncertainty, and leaves the dead points.
    A dead point is a zero of sin(gamma) with the linkage assembled on both sides of it
    (shape ``"touch"``).  Returns ``(excluded, excluded_tol, dead points)``."""
    excluded, excluded_tol = list(excluded), list(excluded_tol)
    spans = [tuple(e[:2]) for e in excluded]
    keep = []
    for d in deads:
        if d.shape != "limit" or tuple(d.interval) not in spans:
            keep.append(d)
            continue
        j = spans.index(tuple(d.interval))
        a, b, _why = excluded[j]
        ta, tb = excluded_tol[j] if j < len(excluded_tol) else (0.0, 0.0)
        # the limit lies at the end of the sweep the interval reaches: from it to that end
        if abs(d.at - a) <= abs(d.at - b):   # the sweep starts on it
            excluded[j], excluded_tol[j] = (a, max(d.at, a), "cannot assemble"), (ta, d.tol)
        else:
            excluded[j], excluded_tol[j] = (min(d.at, b), b, "cannot assemble"), (d.tol, tb)
    return excluded, excluded_tol, keep


def _nearest_boundary(excluded: Any, x: FloatOrArray, before: FloatOrArray):
    """The refined edge of the excluded interval adjacent to grid point ``x``
    (``x`` itself where no gap is adjacent: the sweep ends there)."""
    if before:
        stops = [b for _a, b, _r in excluded if b <= x]
        return max(stops) if stops else x
    starts = [a for a, _b, _r in excluded if a >= x]
    return min(starts) if starts else x


def _describe_exclusions(excluded: Any):
    """Core wording (input in rad or m); the report layer rewords it in the spec's units."""
    return "; ".join(f"{reason} for input {start:.6g} … {stop:.6g}"
                     for start, stop, reason in excluded)
