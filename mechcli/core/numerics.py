"""Shared numerics of the core: refining what a sampling grid only brackets.

Every solver that samples a function on a grid and then needs the exact
position of a root, an extremum or a switching point, or an exact integral
over the grid, uses these kernels instead of its own copy:

* :func:`bisect` -- vectorised bisection of many brackets at once,
* :func:`bracketed_root` -- the same brackets closed by a safeguarded secant
  (Illinois) on the function's values, a few evaluations instead of ~40,
* :func:`golden_section_max` -- vectorised golden-section search,
* :func:`sign_changes` and :func:`descending_root` -- root bracketing on a
  grid and its refinement,
* :func:`maximize_piecewise` -- the maximum of a piecewise-smooth function
  from its value and slope,
* :func:`true_runs` -- the runs of a boolean mask,
* :func:`sorted_union` -- the sorted distinct values of two grids (``np.union1d``
  without the ~20 ms import of ``numpy.ma`` that ``np.unique`` costs),
* :func:`gauss_legendre` and :func:`mean_rms` -- Gauss–Legendre mean and RMS
  over grid intervals.

Pure numpy; imports nothing of mechcli.  The arguments carry no units: the
caller's variable and values are used as given.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Callable, Optional, Tuple

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from mechcli.core.types import ArrayFunc, FloatOrArray

#: where :func:`bracketed_root` puts its second probe past a secant step, as a fraction
#: of that step's move
GUARD = 0.1

#: (√5 − 1)/2: the golden-section ratio that keeps one interior point per step
GOLDEN = (np.sqrt(5) - 1) / 2


def bisect(lo: Any, hi: Any, keep_lo: Callable[..., Any], rtol: float, iterations: int = 64
          ) -> Tuple[np.ndarray, np.ndarray]:
    """Vectorised bisection of many brackets at once.

    Parameters
    ----------
    lo, hi : array_like
        Bracket ends (same shape), in either order.
    keep_lo : callable
        ``keep_lo(mid) -> bool array``: True where the sought point lies beyond
        ``mid`` (seen from ``lo``), so ``lo`` moves to ``mid``; elsewhere ``hi``
        moves to ``mid``.
    rtol : float
        Stop when every bracket satisfies ``|hi − lo| <= rtol · max(1, |lo|)``.
    iterations : int, optional
        Most halvings.

    Returns
    -------
    lo, hi : ndarray
        The final brackets (``lo`` keeps the side ``keep_lo`` is True on).
    """
    lo = np.asarray(lo, dtype=float).copy()
    hi = np.asarray(hi, dtype=float).copy()
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        go = keep_lo(mid)
        lo = np.where(go, mid, lo)
        hi = np.where(go, hi, mid)
        if np.all(np.abs(hi - lo) <= rtol * np.maximum(1.0, np.abs(lo))):
            break
    return lo, hi


def bracketed_root(lo: ArrayLike, hi: ArrayLike, f: ArrayFunc, rtol: FloatOrArray,
                   iterations: int = 64, f_lo: Optional[ArrayLike] = None,
                   f_hi: Optional[ArrayLike] = None) -> Tuple[np.ndarray, np.ndarray]:
    """Vectorised roots of ``f`` in brackets where its sign changes, by a safeguarded secant.

    Parameters
    ----------
    lo, hi : array_like
        Bracket ends (same shape), in either order, with ``f(lo) > 0 >= f(hi)``:
        the predicate ``f > 0`` plays the part of ``keep_lo`` in :func:`bisect`.
    f : callable
        ``f(x) -> array`` of the values at the inputs ``x`` (one call per step
        for every bracket at once).
    rtol : float or array_like
        Stop when every bracket satisfies ``|hi − lo| <= rtol · max(1, |lo|)``,
        the criterion of :func:`bisect` (one value, or one per bracket).
    iterations : int, optional
        Most halvings, as :func:`bisect`: at most ``2 * iterations`` calls of
        ``f`` after the ends (every other step bisects when the secant is slow).
    f_lo, f_hi : array_like, optional
        ``f`` at the ends when known (saves a call).

    Returns
    -------
    lo, hi : ndarray
        The final brackets (``lo`` on the side where ``f > 0``), as :func:`bisect`.

    Notes
    -----
    Regula falsi with the Illinois modification (the value kept at an end that
    survives twice in a row is halved: superlinear from both sides).  A
    secant step that moves less than the tolerance ends the search at that
    point (``lo = hi``); one that lands within the tolerance of an end closes
    the bracket by probing half a tolerance either side of it; a step that is
    not finite, or two steps that did not halve the bracket, fall back to
    bisection.  Each call probes a second point :data:`GUARD` times the secant's
    last move past it, on the side the root is expected (towards the end the last
    step kept): the secant's error being far smaller than its move, the root most
    often falls between the two and the bracket shrinks to that in one call.  Smooth
    functions take 3–6 calls instead of the ~40 of :func:`bisect`.
    """
    a = np.asarray(lo, dtype=float)
    b = np.asarray(hi, dtype=float)
    if f_lo is None or f_hi is None:
        both = np.asarray(f(np.concatenate([a, b])), dtype=float)
        f_lo, f_hi = both[:a.size], both[a.size:]
    s = _Secant(a, b, f_lo, f_hi)
    for _ in range(2 * iterations):
        tol = rtol * np.maximum(1.0, np.abs(np.where(s.flip, s.right, s.left)))
        step = _secant_step(s, tol)
        if step is None:
            break
        x, p1, p2, done = step
        vals = np.asarray(f(np.concatenate([p1, p2])), dtype=float)
        _narrow(s, x, p1, p2, vals[:a.size], vals[a.size:], done)
    return np.where(s.flip, s.right, s.left), np.where(s.flip, s.left, s.right)


class _Secant:
    """The state of :func:`bracketed_root`'s brackets between two steps (left < right)."""

    __slots__ = ("flip", "left", "right", "fl", "fr", "kept", "x_prev", "w_before",
                 "last_bisect")

    def __init__(self, a: np.ndarray, b: np.ndarray, f_lo: ArrayLike, f_hi: ArrayLike) -> None:
        self.flip = a > b
        self.left, self.right = np.where(self.flip, b, a), np.where(self.flip, a, b)
        self.fl = np.where(self.flip, f_hi, f_lo).astype(float)
        self.fr = np.where(self.flip, f_lo, f_hi).astype(float)
        #: end kept by the last step: -1 left, +1 right
        self.kept = np.zeros(a.shape, dtype=np.int8)
        self.x_prev = np.full(a.shape, np.nan)
        #: widths one and two steps back
        self.w_before = (np.full(a.shape, np.inf), self.right - self.left)
        self.last_bisect = np.zeros(a.shape, dtype=bool)


def _secant_step(s: _Secant, tol: np.ndarray
                 ) -> Optional[Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """The next secant (or bisection) point ``x`` and the two probes ``p1 <= p2`` of
    every bracket, with the mask of the brackets done; None when all are done."""
    left, right, fl, fr = s.left, s.right, s.fl, s.fr
    w = right - left
    done = w <= tol
    if np.all(done):
        return None
    den = fr - fl
    with np.errstate(divide="ignore", invalid="ignore"):
        x = right - fr * w / den
    bad = ~np.isfinite(x)
    x = np.clip(np.where(bad, left, x), left, right)
    # the secant step moved less than the tolerance: converged (also where the
    # derivative is a noisy finite difference and the bracket cannot close)
    conv = ~bad & ~done & (np.abs(x - s.x_prev) <= tol)
    left, right = np.where(conv, x, left), np.where(conv, x, right)
    s.left, s.right = left, right
    done |= conv
    if np.all(done):
        return None
    # converging onto an end: close the bracket around x
    stalled = ~bad & ((x - left <= tol) | (right - x <= tol))
    # the last two steps did not halve the bracket: bisect (at worst every other step)
    slow = (w > 0.5 * s.w_before[0]) & ~s.last_bisect
    bad |= slow
    stalled &= ~slow
    s.w_before = (s.w_before[1], w)
    s.last_bisect = bad
    x = np.where(bad, 0.5 * (left + right), x)
    h = 0.5 * tol
    # a secant step's error is far below its move: a second probe a tenth of the
    # move past it (the first step: of its distance to the nearer end), towards
    # the end the last step kept (the first step: the farther end), most often
    # brackets the root tightly, and the bracket shrinks to that in one call
    guard = ~bad & ~stalled
    first = ~np.isfinite(s.x_prev)
    near, far = np.minimum(x - left, right - x), np.where(x - left > right - x, -1, 1)
    move = np.where(first, near, np.abs(x - np.where(first, x, s.x_prev)))
    reach = np.maximum(h, GUARD * move)
    ahead = np.where(s.kept != 0, s.kept, far)
    g = np.clip(x + ahead * reach, left, right)
    p1 = np.where(stalled, np.maximum(x - h, left), np.where(guard, np.minimum(x, g), x))
    p2 = np.where(stalled, np.minimum(x + h, right), np.where(guard, np.maximum(x, g), x))
    return x, p1, p2, done


def _narrow(s: _Secant, x: np.ndarray, p1: np.ndarray, p2: np.ndarray, f1: np.ndarray,
            f2: np.ndarray, done: np.ndarray) -> None:
    """Shrink every bracket not ``done`` to the part of ``left, p1, p2, right`` where the
    sign changes, from the values ``f1``, ``f2`` at the probes (Illinois on the ends)."""
    left, right, fl, fr, kept = s.left, s.right, s.fl, s.fr, s.kept
    pl, p1_pos, p2_pos = fl > 0, f1 > 0, f2 > 0
    in_first = pl != p1_pos                      # the sign changes in [left, p1]
    in_mid = ~in_first & (p1_pos != p2_pos)      # in [p1, p2]
    in_last = ~in_first & ~in_mid                # in [p2, right]
    # Illinois: halve the value of an end kept twice in a row
    fl = np.where(in_first & (kept == -1), 0.5 * fl, fl)
    fr = np.where(in_last & (kept == 1), 0.5 * fr, fr)
    new_l = np.where(in_first, left, np.where(in_mid, p1, p2))
    new_r = np.where(in_first, p1, np.where(in_mid, p2, right))
    new_fl = np.where(in_first, fl, np.where(in_mid, f1, f2))
    new_fr = np.where(in_first, f1, np.where(in_mid, f2, fr))
    new_kept = np.where(in_first, -1, np.where(in_last, 1, 0)).astype(np.int8)
    s.left, s.right = np.where(done, left, new_l), np.where(done, right, new_r)
    s.fl, s.fr = np.where(done, fl, new_fl), np.where(done, fr, new_fr)
    s.kept = np.where(done, kept, new_kept)
    s.x_prev = x


def golden_section_max(f: Callable[..., Any], lo: np.ndarray, hi: np.ndarray, iterations: int = 48,
                       rtol: float = 1e-10) -> Tuple[np.ndarray, np.ndarray]:
    """Vectorised golden-section search for the maxima of unimodal functions.

    Parameters
    ----------
    f : callable
        ``f(x) -> ndarray``: element ``i`` is the ``i``-th function at ``x[i]``.
    lo, hi : ndarray
        Brackets, ``lo <= hi``, one per function.
    iterations : int, optional
        Most steps (each shrinks every bracket by the factor :data:`GOLDEN`).
    rtol : float, optional
        Stop when every bracket is shorter than ``rtol · max(1, |lo|)``.

    Returns
    -------
    x, fx : ndarray
        The better of the two final interior points of each bracket and its
        value (on a tie, the larger ``x``).

    Notes
    -----
    One evaluation of *f* per step for all brackets together: the interior
    point that survives a step is reused.
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    c = hi - GOLDEN * (hi - lo)
    d = lo + GOLDEN * (hi - lo)
    fc, fd = f(c), f(d)
    for _ in range(iterations):
        left = fc > fd  # the maximum lies in [lo, d]
        hi = np.where(left, d, hi)
        lo = np.where(left, lo, c)
        new_c = hi - GOLDEN * (hi - lo)
        new_d = lo + GOLDEN * (hi - lo)
        fx = f(np.where(left, new_c, new_d))
        c_old, fc_old, d_old, fd_old = c, fc, d, fd
        c = np.where(left, new_c, d_old)
        fc = np.where(left, fx, fd_old)
        d = np.where(left, c_old, new_d)
        fd = np.where(left, fc_old, fx)
        if np.all(np.abs(hi - lo) < rtol * np.maximum(1.0, np.abs(lo))):
            break
    take_d = (fd > fc) | ((fd == fc) & (d > c))
    return np.where(take_d, d, c), np.where(take_d, fd, fc)


def sign_changes(y: np.ndarray, falling_only: bool = False) -> np.ndarray:
    """Grid intervals that bracket a root of sampled values.

    Parameters
    ----------
    y : ndarray, shape (n,)
        Function values on an increasing grid.
    falling_only : bool, optional
        Only the intervals where *y* falls through zero
        (``y[i] > 0 >= y[i + 1]``); otherwise every interval whose ends do not
        have strictly the same sign (a zero at either end counts).

    Returns
    -------
    ndarray of int
        Indices ``i``: the root lies in ``[x[i], x[i + 1]]``.
    """
    y = np.asarray(y)
    if falling_only:
        return np.flatnonzero((y[:-1] > 0) & (y[1:] <= 0))
    return np.flatnonzero(np.sign(y[:-1]) * np.sign(y[1:]) <= 0)


def descending_root(f: Callable[..., Any], lo: float, hi: float, n: int = 64) -> float:
    """Root of *f* in ``[lo, hi]`` where it changes from positive to negative.

    Parameters
    ----------
    f : callable
        ``f(x) -> ndarray`` on an array of points.
    lo, hi : float
        Bracket with ``f(lo) > 0 >= f(hi)``.
    n : int, optional
        Sub-intervals per round.

    Returns
    -------
    float
        The root; *lo* when the bracket does not hold.

    Notes
    -----
    Each round evaluates *f* at n + 1 points and keeps the first sub-interval
    with the sign change (a factor n per round) until the bracket is a few
    doubles wide; the last step is a secant.  At a kink the root is the kink.
    """
    for _ in range(20):
        if hi - lo <= 4e-16 * max(1.0, abs(lo), abs(hi)):
            break
        x = np.linspace(lo, hi, n + 1)
        found = sign_changes(f(x), falling_only=True)
        if not found.size:
            break
        i = int(found[0])
        lo, hi = float(x[i]), float(x[i + 1])
    y = f(np.array([lo, hi]))
    ylo, yhi = float(y[0]), float(y[1])
    if not (ylo > 0 >= yhi) or ylo == yhi:
        return lo
    return lo + (hi - lo) * ylo / (ylo - yhi)


def piece_grid(lo: float, hi: float, step: float, min_points: int = 17) -> np.ndarray:
    """Uniform grid on ``[lo, hi]`` no coarser than *step*, at least *min_points*."""
    n = max(min_points, int(math.ceil((hi - lo) / step)) + 1)
    return np.linspace(lo, hi, n)


#: splitting of the intervals that may hold a narrow peak (see maximize_piecewise): levels,
#: new points per interval, and the most intervals split per level and piece
DENSIFY_LEVELS = 4
DENSIFY_FRACTIONS = np.arange(1, 8) / 8.0
DENSIFY_MAX = 64


def maximize_piecewise(pieces: Any, step: float) -> Optional[Tuple[Optional[float], float]]:
    """Maximum of a piecewise-smooth function from its value and slope.

    Parameters
    ----------
    pieces : sequence of (float, float, callable)
        ``(lo, hi, func)`` per smooth piece; ``func(x) -> (g, dg/dx)`` on
        arrays.
    step : float
        Coarse sampling step (each piece gets at least 17 samples).

    Returns
    -------
    (float, float) or None
        ``(x_at_max, g_max)``, refined to a few doubles of *x*; None if
        *pieces* is empty.

    Notes
    -----
    Intervals whose end values plus half their width times the larger end slope
    exceed the best value so far are split in eight, up to four times (a peak
    narrower than the grid).  A piece is skipped when no point of it can reach
    the best grid value (grid value + step × max |g'| below it).  Each remaining grid maximum is
    bracketed between its grid neighbours and the root of dg/dx found by
    :func:`descending_root`; a maximum at a piece end (one-sided, e.g. a
    kink) is taken as is.
    """
    sampled = []
    for lo, hi, func in pieces:
        grid = piece_grid(lo, hi, step)
        g, dg = func(grid)
        sampled.append((func, grid, g, dg))
    if not sampled:
        return None
    top = max(float(np.max(g)) for _, _, g, _ in sampled)
    # a peak narrower than the grid (a pitch curve near a cusp: found by the cam
    # property test) can hide between two samples: split, a few times, every interval
    # whose ends' values and slopes say it might rise above the best value so far
    for _level in range(DENSIFY_LEVELS):
        split = False
        for k, (func, grid, g, dg) in enumerate(sampled):
            h = np.diff(grid)
            bound = np.maximum(g[:-1], g[1:]) + 0.5 * h * np.maximum(np.abs(dg[:-1]),
                                                                    np.abs(dg[1:]))
            hot = np.flatnonzero((bound > top) & (h > 1e-12 * max(1.0, abs(grid[-1]))))
            if hot.size == 0 or hot.size > DENSIFY_MAX:
                continue
            new = (grid[hot, None] + h[hot, None] * DENSIFY_FRACTIONS[None, :]).ravel()
            gn, dgn = func(new)
            order = np.argsort(np.concatenate([grid, new]), kind="stable")
            sampled[k] = (func, np.concatenate([grid, new])[order],
                          np.concatenate([g, gn])[order], np.concatenate([dg, dgn])[order])
            top = max(top, float(np.max(gn)))
            split = True
        if not split:
            break
    best: Tuple[Optional[float], float] = (None, -math.inf)
    for func, grid, g, dg in sampled:
        h_max = float(np.max(np.diff(grid)))
        # no point of this piece can exceed a grid value by more than h max|g'|
        reach = h_max * float(np.max(np.abs(dg)))
        if float(np.max(g)) + reach < top:
            continue
        inner = np.ones(len(g), dtype=bool)
        inner[1:] &= g[1:] >= g[:-1]
        inner[:-1] &= g[:-1] >= g[1:]
        for i in np.flatnonzero(inner & (g + reach >= top)):
            cand = _refine_grid_max(func, grid, g, dg, int(i))
            if cand[1] > best[1]:
                best = cand
    return best


def _refine_grid_max(func: Callable[..., Any], grid: np.ndarray, g: np.ndarray, dg: np.ndarray,
                     i: int) -> Tuple[float, float]:
    """Refine the grid maximum *i* of one piece by a root of its slope."""

    def slope(x: np.ndarray) -> np.ndarray:
        return func(np.asarray(x, dtype=float))[1]

    x_best, g_best = float(grid[i]), float(g[i])
    if dg[i] > 0 and i < len(grid) - 1:
        lo, hi = x_best, float(grid[i + 1])
        dlo, dhi = float(dg[i]), float(dg[i + 1])
    elif dg[i] < 0 and i > 0:
        lo, hi = float(grid[i - 1]), x_best
        dlo, dhi = float(dg[i - 1]), float(dg[i])
    else:
        return x_best, g_best
    if dlo > 0 > dhi:
        x = descending_root(slope, lo, hi)
        gx = float(func(np.array([x]))[0][0])
        if gx >= g_best:
            return x, gx
    return x_best, g_best


def true_runs(mask: np.ndarray) -> Any:
    """The runs of True of a 1-D boolean array.

    Returns
    -------
    list of (int, int)
        ``(start, stop)`` index pairs, ``mask[start:stop]`` all True, in order.
    """
    m = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(m))
    return list(zip(edges[0::2], edges[1::2]))


def sorted_union(a: Any, b: Any) -> np.ndarray:
    """The sorted distinct values of two arrays of numbers (``np.union1d`` of finite values).

    ``np.union1d`` and ``np.unique`` import ``numpy.ma`` (about 20 ms) the first time
    they run; a sort and a comparison of neighbours do not.

    Parameters
    ----------
    a, b : array_like
        Finite numbers (any shape; flattened).

    Returns
    -------
    ndarray, 1-D
    """
    x = np.sort(np.concatenate((np.ravel(a), np.ravel(b))).astype(float, copy=False))
    keep = np.empty(x.size, dtype=bool)
    keep[:1] = True
    np.not_equal(x[1:], x[:-1], out=keep[1:])
    return x[keep]


def gauss_legendre(breaks: np.ndarray, n: int = 4) -> Tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on every interval of a grid.

    Parameters
    ----------
    breaks : ndarray, shape (m,)
        Increasing interval ends.
    n : int, optional
        Nodes per interval (exact for polynomials of degree 2n − 1).

    Returns
    -------
    x, w : ndarray, shape ((m − 1) n,)
        Nodes and weights: ``w @ f(x)`` is the integral of *f* over
        ``[breaks[0], breaks[-1]]``.
    """
    nodes, weights = np.polynomial.legendre.leggauss(n)
    lo, hi = breaks[:-1], breaks[1:]
    half = 0.5 * (hi - lo)
    mid = 0.5 * (hi + lo)
    return ((mid[:, None] + half[:, None] * nodes[None, :]).ravel(),
            (half[:, None] * weights[None, :]).ravel())


def mean_rms(w: np.ndarray, values: np.ndarray, span: float) -> Tuple[float, float]:
    """Mean and root mean square of *values* at quadrature nodes with weights *w*.

    Parameters
    ----------
    w : ndarray
        Quadrature weights (e.g. from :func:`gauss_legendre`).
    values : ndarray
        The function at the nodes.
    span : float
        Length of the integration domain (> 0).

    Returns
    -------
    (float, float)
        ``∫f / span`` and ``sqrt(∫f² / span)``.
    """
    return (float(np.dot(w, values) / span),
            float(np.sqrt(np.dot(w, values * values) / span)))
