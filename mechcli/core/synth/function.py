"""Function generation (§3.5): a linkage whose input and output angles (or slide)
correspond at precision points, and its structural error.

* :func:`freudenstein`: the four-bar through 3–5 pairs of crank and rocker
  angles, Freudenstein's equation (3-34), 【例 3-6】, 习题 3-11;
* :func:`chebyshev_points`: the precision points of eq. (3-38);
* :func:`function_generator`: the four-bar that reproduces y = f(x) on
  [x0, xm] (precision points, Chebyshev spacing or least squares) with its
  structural error Δy = f(x) − F(x) (3-37), 【例 3-7】, 习题 3-13;
* :func:`slider_crank_function`: crank angle ↔ slider position, 习题 3-12;
* :func:`rocker_slider`: rocker angle ↔ slider position, 习题 3-9.

Conventions: A = (0, 0); the four-bar's frame AD lies on +x, D = (d, 0); the
input is the absolute angle θ1 of A→B, the rocker's angle the absolute angle
θ3 of D→C (the engine's link 3, :class:`~mechcli.core.linkage.elements.RRR`
``link_b``); the slider's guide is the line y = e, its slide ``"3"`` the x of
the slider pin.  SI units and radians.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, cast

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.linkage.engine import DriverMotion, solve
from mechcli.core.records import record
from mechcli.core.synth.design import LinkageDesign, branch_of, four_bar_design, slider_crank_design

if TYPE_CHECKING:
    from mechcli.core.synth.targets import Function
    from mechcli.core.types import FloatOrArray

#: a linear system whose smallest singular value is below this fraction of its
#: largest does not determine the linkage (repeated or dependent points)
SINGULAR_RCOND = 1e-10
#: two precision points closer than this in both angles [rad] are the same point
SAME_POINT = 1e-9
#: Freudenstein's equation (3-34) holds to this at an accepted nonlinear root
#: (the equation's terms are cosines, of order 1)
ROOT_TOL = 1e-10
#: the relative lengths l, m, n of a real four-bar lie in [1/RATIO_MAX, RATIO_MAX]:
#: beyond, a link is a point or at infinity (P0 or P1 = 0 up to round-off)
RATIO_MAX = 1e9
#: the methods of :func:`function_generator`
METHODS = ("precision", "chebyshev", "least_squares")
#: least-squares points when neither ``x`` nor ``n`` is given
LEAST_SQUARES_POINTS = 11


def _wrap(a: FloatOrArray) -> FloatOrArray:
    """Angles wrapped to (−π, π]."""
    return np.angle(np.exp(1j * np.asarray(a, dtype=float)))


def _vector(name: str, v: Any) -> np.ndarray:
    a = np.atleast_1d(np.asarray(v, dtype=float))
    if a.ndim != 1 or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be a finite 1-D sequence, got {v!r}")
    return a


def _positive(name: str, v: float) -> float:
    v = float(v)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be positive and finite, got {v!r}")
    return v


def _solve_linear(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve A P = b (least squares when A is tall); 'singular' if A is rank-deficient."""
    s = np.linalg.svd(A, compute_uv=False)
    rcond = float(s[-1] / s[0]) if s[0] > 0 else 0.0
    if not rcond > SINGULAR_RCOND:
        raise DescribedError("the precision points do not determine the linkage "
                             "(repeated or dependent points)", reason="singular", rcond=rcond)
    if A.shape[0] == A.shape[1]:
        return np.linalg.solve(A, b)
    return np.linalg.lstsq(A, b, rcond=None)[0]


def _check_distinct(q1: np.ndarray, q2: np.ndarray) -> None:
    """'singular' if two points coincide in both coordinates (angles modulo 2π)."""
    d1 = np.abs(_wrap(q1[:, None] - q1[None, :]))
    d2 = np.abs(_wrap(q2[:, None] - q2[None, :]))
    same = (d1 < SAME_POINT) & (d2 < SAME_POINT)
    np.fill_diagonal(same, False)
    if same.any():
        i, j = np.argwhere(same)[0]
        raise DescribedError("two precision points are the same", reason="singular",
                             first=int(i), second=int(j))


# --- Freudenstein's equation -------------------------------------------------------------

def _freudenstein_system(t1: np.ndarray, t3: np.ndarray, a0: FloatOrArray, p0: FloatOrArray
                        ) -> Tuple[np.ndarray, np.ndarray]:
    """Rows of eq. (3-34): [cos(θ3+φ0), cos(θ3+φ0−θ1−α0), 1] · (P0, P1, P2) = cos(θ1+α0)."""
    u, v = t1 + a0, t3 + p0
    A = np.stack([np.cos(v), np.cos(v - u), np.ones_like(u + v)], axis=-1)
    return A, np.cos(u)


def _ratios(P: np.ndarray, a0: float, p0: float) -> Optional[Tuple[float, ...]]:
    """l, m, n and the normalised angle origins from P0, P1, P2 (eq. 3-34).

    P0 = m, P1 = −m/n, P2 = (m² + n² + 1 − l²)/(2n).  A negative n puts D on −x:
    the mechanism turned by π (α0 + π, φ0 + π) has D on +x; a negative m points
    the rocker backwards (φ0 + π).  Returns None when there is no real linkage
    (a ratio outside [1/RATIO_MAX, RATIO_MAX]: m = 0 or P1 = 0 up to round-off,
    or l² <= 0).  At exact precision points l² = |C_i − B_i|² >= 0 by
    construction; l² < 0 can come only from a least-squares fit.
    """
    P0, P1, P2 = (float(p) for p in P)
    if not (math.isfinite(P0 + P1 + P2) and 1.0 / RATIO_MAX <= abs(P0) <= RATIO_MAX
            and abs(P1) * RATIO_MAX > abs(P0)):
        return None
    m = P0
    n = -m / P1
    l2 = m * m + n * n + 1.0 - 2.0 * n * P2
    if not (math.isfinite(l2) and RATIO_MAX ** -2 <= l2 <= RATIO_MAX ** 2
            and abs(n) >= 1.0 / RATIO_MAX):
        return None
    if n < 0.0:
        a0, p0, n = a0 + math.pi, p0 + math.pi, -n
    if m < 0.0:
        p0, m = p0 + math.pi, -m
    return math.sqrt(l2), m, n, float(_wrap(a0)), float(_wrap(p0))


def _pivots(t1: np.ndarray, t3: np.ndarray, l: float, m: float, n: float, a0: float, p0: float,
            crank: float) -> Tuple[np.ndarray, np.ndarray, complex]:
    """B, C at every point and D [m] (complex), eq. (3-33) with a = crank."""
    b = crank * np.exp(1j * (t1 + a0))
    d = complex(crank * n, 0.0)
    c = d + crank * m * np.exp(1j * (t3 + p0))
    return b, c, d


def _branches(t1: np.ndarray, t3: np.ndarray, l: float, m: float, n: float, a0: float, p0: float
             ) -> np.ndarray:
    b, c, d = _pivots(t1, t3, l, m, n, a0, p0, 1.0)
    return np.array([branch_of(bi, ci, d) for bi, ci in zip(b, c)])


def _four_bar(t1: np.ndarray, t3: np.ndarray, P: np.ndarray, ratios: Tuple[float, ...],
              crank: float, values: Any) -> LinkageDesign:
    """The design of a Freudenstein solution (pivots in position 1, link 3 = D→C)."""
    l, m, n, a0, p0 = ratios
    A, rhs = _freudenstein_system(t1, t3, a0, p0)
    P_normalised = np.array([m, -m / n, (m * m + n * n + 1.0 - l * l) / (2.0 * n)])
    b, c, d = _pivots(t1, t3, l, m, n, a0, p0, crank)
    values = dict(values)
    values.update(l=l, m=m, n=n, alpha0=a0, phi0=p0,
                  P0=float(P[0]), P1=float(P[1]), P2=float(P[2]),
                  residual=float(np.max(np.abs(A @ P_normalised - rhs))),
                  branches=_branches(t1, t3, l, m, n, a0, p0))
    return four_bar_design((0.0, 0.0), (d.real, 0.0), b[0], c[0], inputs=t1 + a0,
                           angles={3: cast(np.ndarray, _wrap(t3 + p0))}, values=values)


def _newton_roots(t1: np.ndarray, t3: np.ndarray, a0: Optional[float], p0: Optional[float]
                 ) -> List[Tuple[np.ndarray, Any, int]]:
    """Every root of eq. (3-34) with the origins left None unknown (N = 3 + unknowns).

    Multi-start Newton: from a grid of the unknown origins (72 values of one,
    24 × 24 of two, each with P by least squares at those origins), Newton's
    method on (P0, P1, P2, origins) with the analytic Jacobian, angle steps
    limited to 0.5 rad.  Returns a list of (P, ratios, iterations), the
    distinct real linkages, normalised by :func:`_ratios`.
    """
    free = (a0 is None, p0 is None)
    k = sum(free)
    N = t1.size
    if k == 1:
        grid = np.linspace(-math.pi, math.pi, 72, endpoint=False)[:, None]
    else:
        g = np.linspace(-math.pi, math.pi, 24, endpoint=False)
        grid = np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1).reshape(-1, 2)
    S = grid.shape[0]

    def origins(z: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        cols = iter(range(3, 3 + k))
        aa = z[:, next(cols)] if free[0] else np.full(S, a0)
        pp = z[:, next(cols)] if free[1] else np.full(S, p0)
        return aa, pp

    z = np.zeros((S, 3 + k))
    z[:, 3:] = grid
    aa, pp = origins(z)
    A, rhs = _freudenstein_system(t1[None, :], t3[None, :], aa[:, None], pp[:, None])
    z[:, :3] = np.einsum("sij,sj->si", np.linalg.pinv(A), rhs)
    alive = np.ones(S, dtype=bool)
    iterations = np.zeros(S, dtype=int)
    done = np.zeros(S, dtype=bool)
    for it in range(1, 61):
        aa, pp = origins(z)
        u, v = t1[None, :] + aa[:, None], t3[None, :] + pp[:, None]
        P0, P1, P2 = z[:, 0:1], z[:, 1:2], z[:, 2:3]
        r = P0 * np.cos(v) + P1 * np.cos(v - u) + P2 - np.cos(u)
        cols = [np.cos(v), np.cos(v - u), np.ones((S, N))]
        if free[0]:
            cols.append(P1 * np.sin(v - u) + np.sin(u))
        if free[1]:
            cols.append(-P0 * np.sin(v) - P1 * np.sin(v - u))
        J = np.stack(cols, axis=-1)
        step = -np.einsum("sij,sj->si", np.linalg.pinv(J), r)
        step[:, 3:] = np.clip(step[:, 3:], -0.5, 0.5)
        step[~alive | done] = 0.0
        z = z + step
        iterations += (alive & ~done)
        done |= alive & (np.max(np.abs(r), axis=1) < 1e-14) & (np.max(np.abs(step), axis=1) < 1e-12)
        bad = ~np.all(np.isfinite(z), axis=1) | (np.max(np.abs(z[:, :3]), axis=1) > 1e8)
        alive &= ~bad
        z[bad] = 0.0
        if np.all(done | ~alive):
            break
    aa, pp = origins(z)
    A, rhs = _freudenstein_system(t1[None, :], t3[None, :], aa[:, None], pp[:, None])
    res = np.max(np.abs(np.einsum("sij,sj->si", A, z[:, :3]) - rhs), axis=1)
    roots: List[Tuple[np.ndarray, Any, int]] = []
    for s in np.flatnonzero(alive & (res < ROOT_TOL)):
        ratios = _ratios(z[s, :3], float(aa[s]), float(pp[s]))
        if ratios is None:
            continue
        same = any(np.allclose(ratios[:3], r[1][:3], rtol=1e-7, atol=1e-9)
                   and np.all(np.abs(_wrap(np.subtract(ratios[3:], r[1][3:]))) < 1e-7)
                   for r in roots)
        if not same:
            roots.append((z[s, :3].copy(), ratios, int(iterations[s])))
    return roots


def freudenstein(theta1: np.ndarray, theta3: np.ndarray, *, alpha0: Optional[float] = None,
                 phi0: Optional[float] = None, crank: float = 1.0) -> LinkageDesign:
    """The four-bar whose crank and rocker angles correspond at 3–5 precision points.

    Parameters
    ----------
    theta1, theta3 : sequence of float, length N = 3, 4 or 5
        Crank angles θ1i and rocker angles θ3i [rad], each measured from its
        own origin α0, φ0 (图 3-11): the absolute angles are θ1i + α0 (A→B)
        and θ3i + φ0 (D→C), CCW from A→D.
    alpha0, phi0 : float, optional
        The origins [rad].  N = 3: both chosen (default 0, the book's choice,
        【例 3-6】), the equation is linear.  N = 4: one chosen, the other
        solved (when neither is given α0 = 0 is chosen); both given is an
        over-determined system (use least squares, :func:`function_generator`).
        N = 5: both solved, neither may be given.
    crank : float
        The crank length a [m]; b = l a, c = m a, d = n a.

    Returns
    -------
    LinkageDesign
        ``kind="four_bar"``: A = (0, 0), D = (d, 0), ``inputs`` the absolute
        θ1i + α0, ``angles[3]`` the absolute θ3i + φ0 wrapped to (−π, π] (the
        engine's θ3 of D→C), the RRR branch of position 1.  ``values``:

        ``l, m, n``
            b/a, c/a, d/a (the book's relative lengths).
        ``alpha0, phi0``
            The origins used [rad], in (−π, π].  They differ from the given
            ones by π where the solution had n < 0 (the mechanism is turned by
            π so that D lies on +x) or m < 0 (the rocker points the other way).
        ``P0, P1, P2``
            The solution of eq. (3-34) as solved, before that normalisation.
        ``residual``
            max |eq. (3-34)| at the points with the normalised origins.
        ``branches``
            The RRR branch (+1/−1, :func:`~.design.branch_of`) in which each
            point lies; the design moves on ``branches[0]``, so a point of the
            other branch is a branch defect (reported by ``verify``).
        ``iterations``
            Newton iterations of the chosen root (0 for N = 3).
        ``solutions``
            For N = 4, 5: every distinct real root found, rows
            (l, m, n, α0, φ0).

    Raises
    ------
    ValueError
        N outside 3–5, lengths that differ, a non-positive crank.
    DescribedError
        ``"origins"``: origins given that N solves for, or both given at N = 4
        (values ``points`` N, ``wanted`` the number of origins to give);
        ``"singular"``: repeated points or a singular system (values
        ``rcond`` or ``first, second``); ``"no_solution"``: no real linkage
        (a link of zero or infinite length: a ratio outside
        [1e-9, 1e9], values ``P0, P1, P2``; or no root of the nonlinear system).

    Notes
    -----
    Eq. (3-33) projects the loop a + b = d + c on the axes; squaring and adding
    eliminates θ2 and gives eq. (3-34),
    cos(θ1+α0) = P0 cos(θ3+φ0) + P1 cos(θ3+φ0−θ1−α0) + P2 with
    P0 = m, P1 = −m/n, P2 = (m² + n² + 1 − l²)/(2n), linear in P for known
    origins.  Hence m = P0, n = −m/P1, l = √(m² + n² + 1 − 2nP2).

    With N = 4 or 5 the origins are unknown and (3-34) is nonlinear
    (eq. 3-35: N0 = 5 − N free parameters); it is solved by Newton's method
    from a grid of starting origins (:func:`_newton_roots`).  Among the real
    roots the design is the one whose points all lie on one branch, then the
    most compact (smallest longest/shortest link ratio); every root is in
    ``values["solutions"]``.
    """
    t1, t3 = _vector("theta1", theta1), _vector("theta3", theta3)
    if t1.size != t3.size:
        raise ValueError(f"theta1 and theta3 must have the same length, got {t1.size} and "
                         f"{t3.size}")
    N = t1.size
    if not 3 <= N <= 5:
        raise ValueError(f"Freudenstein's equation takes 3 to 5 precision points, got {N}")
    crank = _positive("crank", crank)
    a0, p0 = _origins(N, alpha0, phi0)
    if N == 3:  # _origins gives both origins at 3 points
        return _linear(t1, t3, cast(float, a0), cast(float, p0), crank,
                       "the precision points give no real four-bar "
                       "(a link would have zero or infinite length)")
    return _nonlinear(t1, t3, a0, p0, crank)


def _origins(N: int, alpha0: Optional[float], phi0: Optional[float]
             ) -> Tuple[Optional[float], Optional[float]]:
    """The origins α0, φ0 of :func:`freudenstein` at N points: the chosen ones, None for
    those the N points solve."""
    given = [v if v is None else float(v) for v in (alpha0, phi0)]
    for name, v in zip(("alpha0", "phi0"), given):
        if v is not None and not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v!r}")
    a0, p0 = given
    if N == 3:
        a0, p0 = (0.0 if a0 is None else a0), (0.0 if p0 is None else p0)
    elif N == 4:
        if a0 is not None and p0 is not None:
            raise DescribedError("4 precision points leave one origin to solve, but both are "
                                 "given", reason="origins", points=4, wanted=1)
        if a0 is None and p0 is None:
            a0 = 0.0
    elif a0 is not None or p0 is not None:
        raise DescribedError("5 precision points determine both origins, but an origin is "
                             "given", reason="origins", points=5, wanted=0)
    return a0, p0


def _nonlinear(t1: np.ndarray, t3: np.ndarray, a0: Optional[float], p0: Optional[float],
               crank: float) -> LinkageDesign:
    """Eq. (3-34) at 4 or 5 points with an origin unknown: the best of Newton's roots."""
    N = t1.size
    _check_distinct(t1, t3)
    roots = _newton_roots(t1, t3, a0, p0)
    if not roots:
        raise DescribedError("the precision points give no real four-bar "
                             "(the nonlinear system has no real root)", reason="no_solution")

    def rank(root: Any) -> Tuple[bool, float]:
        ratios = root[1]
        one_branch = abs(int(np.sum(_branches(t1, t3, *ratios)))) == N
        lengths = (1.0,) + ratios[:3]
        return (not one_branch, max(lengths) / min(lengths))

    P, ratios, iterations = min(roots, key=rank)
    solutions = np.array([r[1] for r in roots])
    return _four_bar(t1, t3, P, ratios, crank,
                     {"iterations": iterations, "solutions": solutions})


# --- function generation -----------------------------------------------------------------

def chebyshev_points(x0: float, xm: float, n: int) -> np.ndarray:
    """The Chebyshev spacing of n precision points on [x0, xm], eq. (3-38).

    x_i = (xm + x0)/2 − (xm − x0)/2 · cos((2i − 1)π / (2n)), i = 1 … n, in
    increasing order for x0 < xm.
    """
    n = int(n)
    if n < 1:
        raise ValueError(f"the number of points must be at least 1, got {n}")
    i = np.arange(1, n + 1)
    return 0.5 * (xm + x0) - 0.5 * (xm - x0) * np.cos((2 * i - 1) * np.pi / (2 * n))


def _linear(t1: np.ndarray, t3: np.ndarray, a0: float, p0: float, crank: float, why: str
           ) -> LinkageDesign:
    """Eq. (3-34) with given origins: solved at 3 points, fitted by linear least squares
    at more; *why* words a solution that is no four-bar."""
    _check_distinct(t1, t3)
    A, rhs = _freudenstein_system(t1, t3, a0, p0)
    P = _solve_linear(A, rhs)
    ratios = _ratios(P, a0, p0)
    if ratios is None:
        raise DescribedError(why, reason="no_solution", P0=float(P[0]), P1=float(P[1]),
                             P2=float(P[2]))
    values: Dict[str, float] = {"iterations": 0}
    if len(t1) > 3:
        values["residual_rms"] = float(np.sqrt(np.mean((A @ P - rhs) ** 2)))
    return _four_bar(t1, t3, P, ratios, crank, values)


def _least_squares(t1: np.ndarray, t3: np.ndarray, a0: float, p0: float, crank: float
                  ) -> LinkageDesign:
    """Eq. (3-34) at N > 3 points with chosen origins, by linear least squares."""
    return _linear(t1, t3, a0, p0, crank, "the least-squares fit gives no real four-bar (the "
                   "coupler's length squared is not positive, or a link is a point)")


def function_generator(f: Function, x0: float, xm: float, *, alpha_m: float, phi_m: float,
                       alpha0: Optional[float] = None, phi0: Optional[float] = None,
                       method: str = "precision", n: Optional[int] = None, x: Any = None,
                       crank: float = 1.0, samples: int = 201) -> LinkageDesign:
    """The four-bar that reproduces y = f(x), x0 <= x <= xm (§3.5 二, 【例 3-7】).

    Parameters
    ----------
    f : Function
        The desired function (:mod:`~mechcli.core.synth.targets`); its
        domain is checked on [x0, xm].
    x0, xm : float
        The range of x, x0 < xm.
    alpha_m, phi_m : float
        The swings of crank and rocker [rad], 0 < |αm|, |φm| < π (the book
        advises < 120°); a negative swing turns clockwise.
    alpha0, phi0 : float, optional
        The origins of the crank and rocker angles [rad] (the book's trial
        values, 【例 3-7】 α0 = 86°, φ0 = 23.5°); as :func:`freudenstein` for
        ``"precision"`` and ``"chebyshev"``, both required for
        ``"least_squares"``.
    method : {"precision", "chebyshev", "least_squares"}
        ``"precision"``: the points ``x`` (3–5; when ``x`` is None and ``f`` is
        a table of 3–5 points, the table's x).  ``"chebyshev"``: n points
        (default 3) of eq. (3-38).  ``"least_squares"``: the points ``x``, or n
        (default 11) equally spaced points from x0 to xm, at least 4; eq.
        (3-34) is solved in the least-squares sense (its residual, not the
        structural error, is minimised).
    n : int, optional
        The number of points (``"chebyshev"``, ``"least_squares"``; with
        ``"precision"`` it must equal ``len(x)``).
    x : sequence of float, optional
        The points, inside [x0, xm].
    crank : float
        The crank length [m].
    samples : int
        Points of the structural-error grid, evenly spaced from x0 to xm; the
        precision points are added to it.

    Returns
    -------
    LinkageDesign
        As :func:`freudenstein`, its prescribed inputs and angles at the
        points; more ``values``:

        ``method``, ``x``, ``y``, ``alpha``, ``phi``
            The points x_i, y_i = f(x_i) and their angles α_i, φ_i [rad]
            measured from the origins.
        ``x0, xm, y0, ym, alpha_m, phi_m, mu_alpha, mu_phi``
            The range and the scales μα = (xm − x0)/αm, μφ = (ym − y0)/φm.
        ``error_x``, ``error_y``, ``error_phi``
            The structural error on the grid: Δy = f(x) − F(x) (3-37) in y's
            units and the rocker angle desired minus reproduced [rad]; NaN
            where the design cannot assemble (``error_feasible`` False).
        ``error_feasible``
            The design assembles at each grid point (on its branch).
        ``error_y_max``, ``error_phi_max``
            max |Δy|, max |Δφ| over the grid where it assembles (NaN if nowhere).

    Raises
    ------
    ValueError
        An unknown method, x0 >= xm, a count of points the method does not
        allow, points outside [x0, xm].
    DescribedError
        ``"origins"``: missing origins for least squares (value ``wanted`` 2);
        ``"points_given"``: points given to the Chebyshev spacing; ``"domain"``
        (f undefined on [x0, xm]); ``"swing"`` (|αm| or |φm| is 0 or >= π;
        values ``alpha_m, phi_m``); ``"flat"`` (f(x0) = f(xm): the rocker's
        scale is undefined; values ``y0, ym``); and those of :func:`freudenstein`.

    Notes
    -----
    The book's mapping (步骤 (2)): α = (x − x0)/(xm − x0) · αm,
    φ = (y − y0)/(ym − y0) · φm, so θ1i = αi and θ3i = φi in eq. (3-34).  The
    structural error is computed by moving the design on the engine
    (:func:`mechcli.core.linkage.solve`) at θ1 = α(x) + α0: F(x) = y0 + φ μφ
    with φ = θ3 − φ0 the rocker angle reproduced.
    """
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; known: {', '.join(METHODS)}")
    scale, samples = _scale(f, x0, xm, alpha_m, phi_m, samples)
    xs = _points(f, method, x, n, scale.x0, scale.xm, alpha0, phi0)
    ys, alpha, phi = scale.angles(xs)
    if method == "least_squares":  # both origins given (_points checked)
        design = _least_squares(alpha, phi, float(cast(float, alpha0)), float(cast(float, phi0)),
                                _positive("crank", crank))
    else:
        design = freudenstein(alpha, phi, alpha0=alpha0, phi0=phi0, crank=crank)
    values = _structural_error(design, scale, samples, method, xs, ys, alpha, phi)
    return LinkageDesign(design.kind, design.linkage, design.lengths, design.pivots,
                         design.inputs, design.points, design.angles, design.slides, values)


@record
class _Scale:
    """The book's mapping of x to α and of y = f(x) to φ (步骤 (2))."""

    f: Any
    x0: float
    xm: float
    y0: float
    ym: float
    alpha_m: float
    phi_m: float

    def angles(self, xv: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """y = f(x) and the angles α, φ from the origins at the points ``xv``."""
        x0, xm, y0, ym = self.x0, self.xm, self.y0, self.ym
        yv = np.asarray(self.f(xv), dtype=float)
        return yv, (xv - x0) / (xm - x0) * self.alpha_m, (yv - y0) / (ym - y0) * self.phi_m


def _scale(f: Any, x0: float, xm: float, alpha_m: float, phi_m: float, samples: int
           ) -> Tuple[_Scale, int]:
    """The checked range, swings and grid size of :func:`function_generator`."""
    x0, xm = float(x0), float(xm)
    if not (math.isfinite(x0) and math.isfinite(xm) and x0 < xm):
        raise ValueError(f"the range must be finite with x0 < xm, got {x0!r}, {xm!r}")
    samples = int(samples)
    if samples < 2:
        raise ValueError(f"samples must be at least 2, got {samples}")
    alpha_m, phi_m = float(alpha_m), float(phi_m)
    if not all(math.isfinite(v) and 0.0 < abs(v) < math.pi for v in (alpha_m, phi_m)):
        raise DescribedError("the swings of crank and rocker must be between 0 and half a turn",
                             reason="swing", alpha_m=alpha_m, phi_m=phi_m)
    check = getattr(f, "check_domain", None)
    if check is not None:
        check(x0, xm)
    y0, ym = float(f(x0)), float(f(xm))
    if not (math.isfinite(y0) and math.isfinite(ym) and y0 != ym):
        raise DescribedError("the function has the same value at both ends of the range, so "
                             "the rocker's scale is undefined", reason="flat", y0=y0, ym=ym)
    return _Scale(f, x0, xm, y0, ym, alpha_m, phi_m), samples


def _points(f: Any, method: str, x: Optional[Sequence[float]], n: Optional[int], x0: float,
            xm: float, alpha0: Optional[float], phi0: Optional[float]) -> np.ndarray:
    """The points x_i of :func:`function_generator`'s method, checked to lie in [x0, xm]."""
    if method == "precision":
        if x is None:
            nodes = getattr(f, "nodes", None)
            if nodes is None or not 3 <= len(nodes[0]) <= 5:
                raise ValueError("precision points need x (or a table of 3 to 5 points)")
            x = nodes[0]
        xs = _vector("x", x)
        if n is not None and int(n) != xs.size:
            raise ValueError(f"n = {n} but {xs.size} points are given")
    elif method == "chebyshev":
        if x is not None:
            raise DescribedError("Chebyshev spacing computes the points, but points are given",
                                 reason="points_given")
        xs = chebyshev_points(x0, xm, 3 if n is None else n)
    else:
        if alpha0 is None or phi0 is None:
            raise DescribedError("least squares needs both origins", reason="origins",
                                 wanted=2)
        if x is not None:
            xs = _vector("x", x)
            if n is not None and int(n) != xs.size:
                raise ValueError(f"n = {n} but {xs.size} points are given")
        else:
            xs = np.linspace(x0, xm, LEAST_SQUARES_POINTS if n is None else int(n))
        if xs.size < 4:
            raise ValueError(f"least squares needs at least 4 points, got {xs.size}")
    if np.any(xs < x0) or np.any(xs > xm):
        raise ValueError(f"the points must lie in [{x0}, {xm}], got {xs.tolist()}")
    return xs


def _structural_error(design: LinkageDesign, scale: _Scale, samples: int, method: str,
                      xs: np.ndarray, ys: np.ndarray, alpha: np.ndarray, phi: np.ndarray
                      ) -> Dict[str, Any]:
    """``design.values`` with the points and the structural error on the grid (the
    ``values`` of :func:`function_generator`)."""
    x0, xm, y0, ym = scale.x0, scale.xm, scale.y0, scale.ym
    alpha_m, phi_m = scale.alpha_m, scale.phi_m
    values = dict(design.values)
    grid = np.union1d(np.linspace(x0, xm, samples), xs)
    yg, ag, pg = scale.angles(grid)
    motion = solve(design.linkage, {1: DriverMotion(ag + values["alpha0"])}, order=0)
    feasible = np.asarray(motion.feasible, dtype=bool)
    error_phi = np.where(feasible, _wrap(pg + values["phi0"] - motion.links[3].theta), np.nan)
    error_y = error_phi * ((ym - y0) / phi_m)
    values.update(method=method, x=xs, y=ys, alpha=alpha, phi=phi, x0=x0, xm=xm, y0=y0, ym=ym,
                  alpha_m=alpha_m, phi_m=phi_m, mu_alpha=(xm - x0) / alpha_m,
                  mu_phi=(ym - y0) / phi_m, error_x=grid, error_y=error_y,
                  error_phi=error_phi, error_feasible=feasible,
                  error_y_max=float(np.max(np.abs(error_y[feasible]))) if feasible.any()
                  else math.nan,
                  error_phi_max=float(np.max(np.abs(error_phi[feasible]))) if feasible.any()
                  else math.nan)
    return values


# --- slider mechanisms -------------------------------------------------------------------

def _slider_branches(b: np.ndarray, s: np.ndarray, e: float) -> np.ndarray:
    """+1 where the slider pin (s, e) lies ahead of B along the guide (+x), else −1."""
    return np.where(s >= b.real, 1, -1)


def slider_crank_function(theta1: Any, s: Any, *, e: Optional[float] = None) -> LinkageDesign:
    """The offset slider-crank whose crank angles and slider positions correspond (习题 3-12).

    Parameters
    ----------
    theta1 : sequence of float
        Crank angles θ1i [rad], absolute: CCW from the guide direction +x.
    s : sequence of float
        Slider positions s_i [m]: the x of the slider pin C on the guide
        y = e, measured from the foot of A's perpendicular on the guide.
    e : float, optional
        The offset [m] (guide y = e).  None: solved, 3 points; given: 2 points.

    Returns
    -------
    LinkageDesign
        :func:`~.design.slider_crank_design`: ``lengths`` l1 (AB), l2 (BC),
        e; ``inputs`` θ1i, ``slides["3"]`` s_i; the RRP branch of position 1
        (+1: C ahead of B along +x).  ``values``: ``e``, ``branches`` (the
        branch of each point), ``residual`` (max |eq.| [m²]).

    Raises
    ------
    ValueError
        A number of points other than 3 (e None) or 2 (e given); lengths
        that differ.
    DescribedError
        ``"singular"`` (repeated or dependent points, value ``rcond``);
        ``"no_solution"``: the crank would point against the given angles
        (l1 <= 0: values ``l1``) or no real rod (l2² <= 0: value ``l2_squared``).

    Notes
    -----
    B = l1 (cos θ1, sin θ1), C = (s, e); |BC|² = l2² gives
    2 l1 (s cos θ1 + e sin θ1) + (l2² − l1² − e²) = s², linear in
    X1 = 2 l1, X2 = 2 l1 e, X3 = l2² − l1² − e² when e is unknown
    (rows [s cos θ1, sin θ1, 1] · X = s²), and in X1, X3 when it is given.
    """
    q, sv = _vector("theta1", theta1), _vector("s", s)
    if q.size != sv.size:
        raise ValueError(f"theta1 and s must have the same length, got {q.size} and {sv.size}")
    need = 3 if e is None else 2
    if q.size != need:
        raise ValueError(f"a slider-crank {'with a given offset ' if e is not None else ''}"
                         f"takes {need} precision points, got {q.size}")
    _check_distinct(q, sv)
    if np.ptp(sv) <= SAME_POINT * max(float(np.max(np.abs(sv))), 1e-300):
        raise DescribedError("the slider positions are all the same: the slider does not move",
                             reason="no_motion")
    if e is None:
        X = _solve_linear(np.stack([sv * np.cos(q), np.sin(q), np.ones_like(q)], axis=-1),
                          sv * sv)
        l1 = 0.5 * X[0]
        ev = X[1] / X[0] if X[0] != 0.0 else 0.0
        l2sq = X[2] + l1 * l1 + ev * ev
    else:
        ev = float(e)
        if not math.isfinite(ev):
            raise ValueError(f"e must be finite, got {e!r}")
        X = _solve_linear(np.stack([sv * np.cos(q) + ev * np.sin(q), np.ones_like(q)], axis=-1),
                          sv * sv)
        l1 = 0.5 * X[0]
        l2sq = X[1] + l1 * l1 + ev * ev
    l1, ev = float(l1), float(ev)
    if not l1 > 0.0:
        raise DescribedError("the crank would point against the given angles", reason="no_solution",
                             l1=l1)
    if not l2sq > 0.0:
        raise DescribedError("the precision points give no real connecting rod",
                             reason="no_solution", l2_squared=float(l2sq))
    l2 = math.sqrt(l2sq)
    b = l1 * np.exp(1j * q)
    residual = float(np.max(np.abs(np.abs(sv + 1j * ev - b) ** 2 - l2sq)))
    branches = _slider_branches(b, sv, ev)
    return slider_crank_design(l1, l2, ev, branch=int(branches[0]), inputs=q,
                               slides={"3": sv},
                               values={"e": ev, "branches": branches, "residual": residual})


def rocker_slider(phi: np.ndarray, s: np.ndarray, *, e: float) -> LinkageDesign:
    """The rocker–slider whose rocker angles and slider positions correspond (习题 3-9).

    The rocker turns about A = (0, 0); the slider's pin on the guide y = e is
    given (the exercise's "铰链点取在 B 点"); the pin C on the rocker, where the
    connecting rod joins it, is found, and with it the rocker's effective
    length (the exercise's 曲柄) and the rod's length.

    Parameters
    ----------
    phi : sequence of 3 floats
        Rocker angles φi [rad]: the absolute angle of a line marked on the
        rocker (the exercise's: vertical in position II), CCW from +x.
    s : sequence of 3 floats
        Slider positions [m]: x of the slider pin on the guide y = e.
    e : float
        The offset of the guide from A [m] (signed: the guide is y = e).

    Returns
    -------
    LinkageDesign
        :func:`~.design.slider_crank_design` with the rocker as link 1:
        ``lengths`` l1 = |AC| (rocker), l2 (rod), e; ``inputs`` φi + δ (the
        absolute angle of A→C on the engine), ``slides["3"]`` s_i.
        ``values``: ``delta`` (δ [rad], the angle of A→C from the marked line,
        in (−π, π]), ``e``, ``branches``, ``residual``.

    Raises
    ------
    ValueError
        Not 3 points, lengths that differ, a non-finite e.
    DescribedError
        ``"singular"``, ``"no_solution"`` (the rocker pin at A, or no real rod).

    Notes
    -----
    The inversion method (the rocker held still, the slider's pins B_i turned
    into its frame; C is their circumcentre) is, in numbers: with
    C_i = r (cos(φi+δ), sin(φi+δ)) and B_i = (s_i, e), |B_i C_i|² = L² gives
    2X1 (s cos φ + e sin φ) + 2X2 (e cos φ − s sin φ) + X3 = s² + e²,
    linear in X1 = r cos δ, X2 = r sin δ, X3 = L² − r².
    """
    q, sv = _vector("phi", phi), _vector("s", s)
    if q.size != sv.size:
        raise ValueError(f"phi and s must have the same length, got {q.size} and {sv.size}")
    if q.size != 3:
        raise ValueError(f"a rocker-slider takes 3 precision points, got {q.size}")
    ev = float(e)
    if not math.isfinite(ev):
        raise ValueError(f"e must be finite, got {e!r}")
    _check_distinct(q, sv)
    if np.ptp(sv) <= SAME_POINT * max(float(np.max(np.abs(sv))), 1e-300):
        raise DescribedError("the slider positions are all the same: the slider does not move",
                             reason="no_motion")
    c, sn = np.cos(q), np.sin(q)
    X = _solve_linear(np.stack([2 * (sv * c + ev * sn), 2 * (ev * c - sv * sn),
                                np.ones_like(q)], axis=-1), sv * sv + ev * ev)
    r = math.hypot(X[0], X[1])
    scale = float(np.max(np.abs(sv + 1j * ev)))
    if not r > 1e-12 * scale:
        raise DescribedError("the rod's pin on the rocker falls on the rocker's pivot",
                             reason="no_solution", l1=r)
    L2 = float(X[2]) + r * r
    if not L2 > 0.0:
        raise DescribedError("the precision points give no real connecting rod",
                             reason="no_solution", l2_squared=L2)
    delta = math.atan2(X[1], X[0])
    inputs = q + delta
    cpin = r * np.exp(1j * inputs)
    residual = float(np.max(np.abs(np.abs(sv + 1j * ev - cpin) ** 2 - L2)))
    branches = _slider_branches(cpin, sv, ev)
    return slider_crank_design(r, math.sqrt(L2), ev, branch=int(branches[0]), inputs=inputs,
                               slides={"3": sv},
                               values={"delta": delta, "e": ev, "branches": branches,
                                       "residual": residual})
