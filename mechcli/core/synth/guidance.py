"""Rigid-body guidance (chapter 3 §3.2–3.4 and, beyond the book, Burmester theory).

A coupler BC (link 2) is to be led through prescribed positions; the fixed
pivots A, D and the moving pivots B, C of a four-bar ABCD are sought.

* :func:`two_positions`, :func:`three_positions` -- positions of B and C given:
  A lies on the perpendicular bisector of B1B2 (and B2B3), D on that of C1C2
  (eqs. 3-3…3-21, 【例 3-2】, 【例 3-3】).
* :func:`moving_pivots`, :func:`coupler_poses` -- poses (x, y, φ) of a coupler
  point M and A, D given: B1, C1 by kinematic inversion with the displacement
  matrix (eqs. 3-22…3-27, 【例 3-4】) or by a nonlinear solve of the constant
  crank and rocker lengths (eqs. 3-28…3-32, 【例 3-5】).
* :func:`burmester_curves`, :func:`burmester_points`, :func:`burmester_design`
  -- four poses leave a one-parameter family of dyads (the centre-point and
  circle-point curves), five poses at most four (the Burmester points); a
  four-bar is two of them.  The complex-number (Sandor–Erdman) dyad equation

      W (e^{iβj} - 1) + Z (e^{iαj} - 1) = δj,     j = 2 … n          (S-E)

  with W the crank A→B1, Z the coupler vector B1→M1, αj = φj - φ1 the coupler's
  rotation and δj = Mj - M1 its displacement, βj the crank's rotation.  This is
  eq. 3-31 of the book written for complex numbers: eliminating βj gives
  |Bj - A| = |B1 - A|.

Conventions: points are ``(x, y)`` tuples [m] (complex numbers inside), angles
in radians counter-clockwise from +x.  Every design is a
:class:`~mechcli.core.synth.design.LinkageDesign` whose ``inputs`` are θ1 = the
angle of A→Bj at each prescribed position, so that the engine moves it through
them.  A problem without solution raises
:class:`~mechcli.core.errors.DescribedError` with one of the reasons

``coincident``     two prescribed positions of one point coincide (or every
                   pose shares its coupler point);
``collinear``      three positions of one point are on a line (the fixed
                   pivot would be at infinity);
``not_on_bisector``  a given fixed pivot is not equidistant from the two
                   positions of its moving pivot;
``parallel``       a given line of a fixed pivot is parallel to the bisector;
``not_rigid``      the positions of B and C change the length BC;
``zero_link``      a designed link has zero length (for example A = D);
``no_rotation``    five poses that only translate (Burmester points);
``degenerate``     four or five poses that leave every point or no point a
                   circle point (Burmester);
``at_infinity``    a four-bar asked of a Burmester pair whose centre point is
                   at infinity (a slider);
``not_on_circle``  a dyad that does not keep its circle point on a circle
                   through the poses.

An iterative solve that does not converge raises
:class:`~mechcli.core.errors.ConvergenceError`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, List, Optional, Tuple, cast

import numpy as np

from mechcli.core.errors import ConvergenceError, DescribedError
from mechcli.core.records import record
from mechcli.core.synth.design import LinkageDesign, four_bar_design

if TYPE_CHECKING:
    from mechcli.core.types import FloatOrArray

Point = Tuple[float, float]

#: relative size below which two positions are the same point (round-off)
COINCIDENT_TOL = 1e-12
#: sine of the angle below which three positions are on a line
COLLINEAR_TOL = 1e-12
#: relative tolerance of a given fixed pivot on its bisector
BISECTOR_TOL = 1e-9
#: relative tolerance of the coupler length BC over the prescribed positions
RIGID_TOL = 1e-4   # the book's own check: 1e-2 mm on a coupler of ~100 mm (例 3-3's program)
#: relative residual of the dyad equations above which a Burmester candidate is
#: not a solution (a genuine solution polishes to round-off, ~1e-15)
BURMESTER_TOL = 1e-9
#: a centre point farther than this (in units of the poses' size) is at infinity
INFINITY = 1e8


# --------------------------------------------------------------------- helpers
def _complex(p: Any, what: str) -> complex:
    """(x, y) or complex -> complex; ValueError unless finite."""
    if isinstance(p, complex):
        z = p
    else:
        try:
            x, y = p
        except (TypeError, ValueError):
            raise ValueError(f"{what} must be an (x, y) pair, got {p!r}") from None
        z = complex(float(x), float(y))
    if not (math.isfinite(z.real) and math.isfinite(z.imag)):
        raise ValueError(f"{what} must be finite, got {p!r}")
    return z


def _points(seq: Any, n: int, what: str) -> np.ndarray:
    """A sequence of exactly ``n`` (x, y) points (an int, or a tuple of allowed counts)."""
    pts = list(seq)
    counts = (n,) if isinstance(n, int) else tuple(n)
    if len(pts) not in counts:
        raise ValueError(f"{what} needs {' or '.join(map(str, counts))} points, got {len(pts)}")
    return np.array([_complex(p, f"{what}[{i}]") for i, p in enumerate(pts)], dtype=complex)


def _angles(seq: Any, n: int, what: str) -> np.ndarray:
    a = np.asarray(list(seq), dtype=float)
    if a.shape != (n,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{what} needs {n} finite angles, got {list(seq)!r}")
    return a


def _pt(z: complex) -> Point:
    return (float(z.real), float(z.imag))


def _wrap(a: FloatOrArray) -> FloatOrArray:
    """Angle(s) wrapped into (-π, π]."""
    return np.angle(np.exp(1j * np.asarray(a, dtype=float)))


def _check_rigid(b: np.ndarray, c: np.ndarray, tol: float = RIGID_TOL) -> None:
    """The positions of B and C keep BC (a rigid coupler) within *tol* of the
    positions' size, else ``not_rigid``."""
    lengths = np.abs(c - b)
    size = float(max(np.max(np.abs(np.concatenate([b, c]) - b[0])), lengths.max()))
    if lengths.min() <= COINCIDENT_TOL * size:
        raise DescribedError("B and C coincide in a prescribed position", reason="coincident",
                             lengths=tuple(float(x) for x in lengths))
    if lengths.max() - lengths.min() > tol * size:
        raise DescribedError("the prescribed positions of B and C change the coupler length BC",
                             reason="not_rigid", lengths=tuple(float(x) for x in lengths),
                             tol=tol, size=size)


def _check_distinct(z: np.ndarray, link: int) -> None:
    scale = float(np.max(np.abs(z - z.mean()))) + float(np.max(np.abs(z)))
    for i in range(len(z)):
        for j in range(i + 1, len(z)):
            if abs(z[j] - z[i]) <= COINCIDENT_TOL * scale:
                raise DescribedError(f"positions {i + 1} and {j + 1} of the moving pivot of "
                                     f"link {link} coincide", reason="coincident",
                                     link=link, positions=(i + 1, j + 1))


def _circumcentre(z: np.ndarray, link: int) -> complex:
    """Centre of the circle through three points (eqs. 3-10…3-21: the perpendicular
    bisectors b12 and b23 intersected), ``coincident``/``collinear`` otherwise.

    ``link`` (1 crank, 3 rocker) says whose moving pivot the points are.
    """
    _check_distinct(z, link)
    a, b = z[1] - z[0], z[2] - z[0]
    cross = (a.conjugate() * b).imag
    if abs(cross) <= COLLINEAR_TOL * abs(a) * abs(b):
        raise DescribedError(f"the three positions of the moving pivot of link {link} are on "
                             "a line: its fixed pivot would be at infinity",
                             reason="collinear", link=link, sine=float(cross / abs(a) / abs(b)))
    # Re(conj(a) o) = |a|²/2, Re(conj(b) o) = |b|²/2 for o = centre - z0
    aa, bb = abs(a) ** 2, abs(b) ** 2
    ox = (aa * b.imag - bb * a.imag) / (2 * cross)
    oy = (bb * a.real - aa * b.real) / (2 * cross)
    return complex(z[0] + complex(ox, oy))


def _design(A: complex, D: complex, b: np.ndarray, c: np.ndarray, **kw: Any) -> LinkageDesign:
    """The four-bar with A, D and B, C at the positions ``b``, ``c``; ``zero_link``
    when a link vanishes."""
    lengths = (abs(b[0] - A), abs(c[0] - b[0]), abs(D - c[0]), abs(D - A))
    size = max(lengths)
    if min(lengths) <= COINCIDENT_TOL * size:
        raise DescribedError("a designed link has zero length", reason="zero_link",
                             l1=lengths[0], l2=lengths[1], l3=lengths[2], l4=lengths[3])
    kw.setdefault("angles", {2: _wrap(np.angle(c - b))})
    return four_bar_design(_pt(A), _pt(D), _pt(b[0]), _pt(c[0]), inputs=np.angle(b - A), **kw)


# --------------------------------------------------------------------- §3.2: B and C given
def _pivot_on_bisector(z1: complex, z2: complex, point: Any, line: Any, name: str, link: int
                      ) -> complex:
    """A fixed pivot on the perpendicular bisector of z1 z2 (eqs. 3-3…3-9)."""
    if (point is None) == (line is None):
        raise ValueError(f"give {name} either as a point or as a line, not "
                         f"{'both' if point is not None else 'neither'}")
    _check_distinct(np.array([z1, z2]), link)
    mid, d = (z1 + z2) / 2, z2 - z1
    if point is not None:
        p = _complex(point, name)
        r1, r2 = abs(p - z1), abs(p - z2)
        if abs(r1 - r2) > BISECTOR_TOL * max(r1, r2):
            raise DescribedError(f"the fixed pivot {name} is not equidistant from the two "
                                 f"positions of its moving pivot", reason="not_on_bisector",
                                 link=link, distance_1=r1, distance_2=r2)
        return p
    try:
        a, b, c = (float(v) for v in line)
    except (TypeError, ValueError):
        raise ValueError(f"the line of {name} must be (a, b, c) of a x + b y = c, "
                         f"got {line!r}") from None
    if not all(map(math.isfinite, (a, b, c))) or a == 0.0 and b == 0.0:
        raise ValueError(f"the line of {name} must have finite a, b, c and (a, b) != 0, "
                         f"got {line!r}")
    g, n = complex(a, b), 1j * d           # the line's normal, the bisector's direction
    gn = (g.conjugate() * n).real          # a x + b y = Re(conj(g) p) along mid + s n
    if abs(gn) <= COLLINEAR_TOL * abs(g) * abs(n):
        raise DescribedError(f"the line of the fixed pivot {name} is parallel to the "
                             "perpendicular bisector of its moving pivot's positions",
                             reason="parallel", link=link)
    s = (c - (g.conjugate() * mid).real) / gn
    return mid + s * n


def two_positions(B: Any, C: Any, *, A: Any = None, D: Optional[Tuple[int, int]] = None,
                  line_A: Any = None, line_D: Any = None, rigid_tol: float = RIGID_TOL
                 ) -> LinkageDesign:
    """A four-bar whose coupler BC passes through two prescribed positions.

    Parameters
    ----------
    B, C : sequence of two (x, y)
        B1, B2 and C1, C2, the moving pivots in the two positions [m].
    rigid_tol : float
        How much |BC| may vary between the positions, relative to their size
        (default 1e-4, the book's 1e-2 mm check); more is ``not_rigid``.
    A, D : (x, y), optional
        A fixed pivot given as a point [m]: it must lie on the perpendicular
        bisector of B1B2 (A) or C1C2 (D).
    line_A, line_D : (a, b, c), optional
        A fixed pivot given by a line ``a x + b y = c`` (``c`` in m): the pivot
        is its intersection with the bisector (eq. 3-9).  Each of A, D is given
        either as a point or as a line.

    Returns
    -------
    LinkageDesign
        ``inputs`` θ1 at the two positions; ``points`` ``{"B", "C"}``;
        ``angles`` ``{2: θ2}`` (the angle of B→C).

    Raises
    ------
    DescribedError
        ``coincident`` (B1 = B2, C1 = C2 or B = C), ``not_rigid``,
        ``not_on_bisector``, ``parallel``, ``zero_link``.
    ValueError
        Neither or both of a point and a line for A or D; malformed input.

    Notes
    -----
    A lies on the bisector b12 through the midpoint of B1B2 (eqs. 3-3, 3-5, 3-7),
    D on c12 (eqs. 3-4, 3-6, 3-8); with the line of eq. 3-9 each is one point.
    Written for the bisector as ``mid + s·i(z2 - z1)``, so a vertical or
    horizontal B1B2 needs no special case (the book's slopes do).  【例 3-2】.
    """
    b, c = _points(B, 2, "B"), _points(C, 2, "C")
    _check_rigid(b, c, rigid_tol)
    a = _pivot_on_bisector(b[0], b[1], A, line_A, "A", 1)
    d = _pivot_on_bisector(c[0], c[1], D, line_D, "D", 3)
    return _design(a, d, b, c, points={"B": b, "C": c})


def three_positions(B: Any, C: Any, *, rigid_tol: float = RIGID_TOL) -> LinkageDesign:
    """A four-bar whose coupler BC passes through three prescribed positions.

    Parameters
    ----------
    B, C : sequence of three (x, y)
        B1, B2, B3 and C1, C2, C3 [m].
    rigid_tol : float
        How much |BC| may vary between the positions, relative to their size
        (default 1e-4, the book's 1e-2 mm check); more is ``not_rigid``.

    Returns
    -------
    LinkageDesign
        A = circumcentre of B1B2B3, D = circumcentre of C1C2C3; ``inputs`` θ1 at
        the three positions; ``points`` ``{"B", "C"}``; ``angles`` ``{2: θ2}``.

    Raises
    ------
    DescribedError
        ``coincident``, ``collinear``, ``not_rigid``, ``zero_link``.

    Notes
    -----
    A is the intersection of the bisectors b12 and b23 (eqs. 3-10, 3-11, 3-14,
    3-15, 3-18, 3-19), D of c12 and c23 (eqs. 3-12, 3-13, 3-16, 3-17, 3-20,
    3-21).  【例 3-3】.
    """
    b, c = _points(B, 3, "B"), _points(C, 3, "C")
    _check_rigid(b, c, rigid_tol)
    return _design(_circumcentre(b, 1), _circumcentre(c, 3), b, c, points={"B": b, "C": c})


# --------------------------------------------------------------------- §3.3–3.4: poses given
def displacement_matrix(M_from: Tuple[float, float], phi_from: float, M_to: Tuple[float, float],
                        phi_to: float) -> np.ndarray:
    """The planar displacement matrix [D] of eq. 3-22: a body's pose (M, φ) from -> to.

    Parameters
    ----------
    M_from, M_to : (x, y)
        The reference point M in the two poses [m].
    phi_from, phi_to : float
        The body's angle in the two poses [rad].

    Returns
    -------
    ndarray, shape (3, 3)
        Homogeneous: ``[x', y', 1] = D @ [x, y, 1]`` for any point of the body
        (eq. 3-23).  With ``from`` = pose j and ``to`` = pose 1 it is the matrix
        [D_j1] of eqs. 3-24…3-27.
    """
    m0, m1 = _complex(M_from, "M_from"), _complex(M_to, "M_to")
    t = float(phi_to) - float(phi_from)
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, m1.real - m0.real * c + m0.imag * s],
                     [s, c, m1.imag - m0.real * s - m0.imag * c],
                     [0.0, 0.0, 1.0]])


def _inverted(P: complex, M: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """P seen from the coupler in each pose, carried into pose 1 (eqs. 3-24…3-27):
    the positions of the fixed pivot P on the inverted linkage (coupler fixed)."""
    out = np.empty(len(M), dtype=complex)
    for j in range(len(M)):
        Dj1 = displacement_matrix(_pt(M[j]), phi[j], _pt(M[0]), phi[0])
        x, y, _ = Dj1 @ np.array([P.real, P.imag, 1.0])
        out[j] = complex(x, y)
    return out


def _poses_design(A: complex, D: complex, M: np.ndarray, phi: np.ndarray, b1: complex, c1: complex,
                  values: Any) -> LinkageDesign:
    """The design of moving pivots b1, c1 (pose 1) led through the poses."""
    rot = np.exp(1j * (phi - phi[0]))
    b = M + (b1 - M[0]) * rot          # eq. 3-28
    c = M + (c1 - M[0]) * rot          # eq. 3-29
    return _design(A, D, b, c, points={"M": M.copy()}, angles={2: _wrap(np.angle(c - b))},
                   coupler_point=_pt(M[0]), values=values)


def _equation_residual(A: complex, D: complex, M: np.ndarray, phi: np.ndarray, b1: complex,
                       c1: complex) -> float:
    """Largest |eq. 3-31|, |eq. 3-32| divided by the size² of the design (dimensionless)."""
    rot = np.exp(1j * (phi - phi[0]))
    b, c = M + (b1 - M[0]) * rot, M + (c1 - M[0]) * rot
    rb, rc = np.abs(b - A) ** 2, np.abs(c - D) ** 2
    size = max(abs(b1 - A), abs(c1 - b1), abs(D - c1), abs(D - A))
    return float(max(np.max(np.abs(rb - rb[0])), np.max(np.abs(rc - rc[0]))) / size ** 2)


def moving_pivots(A: Any, D: Any, poses: Any) -> LinkageDesign:
    """The moving pivots B1, C1 for given fixed pivots A, D and three coupler poses.

    Parameters
    ----------
    A, D : (x, y)
        The fixed pivots [m].
    poses : sequence of three (x, y, phi)
        The coupler reference point M [m] and the coupler angle φ [rad] in each
        pose.

    Returns
    -------
    LinkageDesign
        B1 = circumcentre of A's three positions seen from the coupler (carried
        into pose 1), C1 likewise of D's; ``points`` ``{"M"}``, ``angles``
        ``{2: θ2}``, the coupler point M1; ``values`` ``{"residual"}`` (as
        :func:`coupler_poses`).

    Raises
    ------
    DescribedError
        ``coincident`` (two poses put A, or D, at one place relative to the
        coupler: A or D is a pole of the two poses), ``collinear``, ``zero_link``.

    Notes
    -----
    Kinematic inversion (§3.3, 机构倒置): fixing the coupler in pose 1, A and D
    move to A_j = [D_j1] A, D_j = [D_j1] D (eqs. 3-22, 3-24…3-27), and B1, C1 are
    the fixed pivots of that inverted motion (eqs. 3-10…3-21).  The same
    construction as :func:`coupler_poses` ``method="matrix"``; 【例 3-4】.
    """
    rows = list(poses)
    if len(rows) != 3:
        raise ValueError(f"moving_pivots needs three poses (x, y, phi), got {len(rows)}")
    M = _points([r[:2] for r in rows], 3, "poses")
    phi = _angles([r[2] for r in rows], 3, "poses' phi")
    a, d = _complex(A, "A"), _complex(D, "D")
    b1 = _circumcentre(_inverted(a, M, phi), 1)
    c1 = _circumcentre(_inverted(d, M, phi), 3)
    return _poses_design(a, d, M, phi, b1, c1,
                         {"residual": _equation_residual(a, d, M, phi, b1, c1)})


def coupler_poses(M: Any, phi: Any, A: Any, D: Any, *, method: str = "matrix", tol: float = 1e-12,
                  max_iter: int = 100, guess: Optional[List[Tuple[float, float]]] = None
                 ) -> LinkageDesign:
    """A four-bar with given fixed pivots whose coupler takes three poses.

    Parameters
    ----------
    M : sequence of three (x, y)
        The coupler point M in each pose [m].
    phi : sequence of three float
        The coupler angle φ (of a line MN of the coupler) in each pose [rad].
    A, D : (x, y)
        The fixed pivots [m].
    method : {"matrix", "nonlinear"}
        ``"matrix"``: the displacement matrix and circumcentres (§3.3,
        【例 3-4】); ``"nonlinear"``: eqs. 3-31 and 3-32 solved for the moving
        pivots in the coupler frame with :func:`scipy.optimize.root`,
        Levenberg–Marquardt (§3.4, 【例 3-5】; the book uses ``fsolve``).
    tol : float
        The nonlinear solve's tolerances (``xtol``, ``ftol``): relative on the
        unknowns and on the sum of squares of the equations, which are scaled
        by the size of the data; a residual at or below ``tol`` is converged.
    max_iter : int
        The nonlinear solve's largest number of evaluations of the equations.
    guess : (B1, C1), optional
        The nonlinear solve's start: the moving pivots in pose 1, (x, y) [m];
        default M1 for both (the book starts B at the origin of the coupler
        frame, x' = y' = 0).

    Returns
    -------
    LinkageDesign
        ``points`` ``{"M"}``, ``angles`` ``{2: θ2}`` (θ2 = the angle of B→C in
        each pose), coupler point M1; ``values``: ``method``, ``iterations``
        (the solver's iterations, i.e. Jacobian evaluations; 0 for ``"matrix"``),
        ``tol``, ``residual`` (the largest of eqs. 3-31, 3-32 at the design,
        divided by its size squared).

    Raises
    ------
    DescribedError
        ``coincident``, ``collinear``, ``zero_link`` (as :func:`moving_pivots`).
    ConvergenceError
        The nonlinear solve did not converge.
    ValueError
        Unknown method, non-positive tol or max_iter, malformed input.

    Notes
    -----
    Eq. 3-28 places B at ``M_i + e^{iφ_i} (x'_B + i y'_B)``; eq. 3-31 asks
    |B_i - A|² = |B_1 - A|² (i = 2, 3), eq. 3-32 the same of C and D.  With A and
    D given the |x'|² terms cancel and the equations are linear in (x'_B, y'_B)
    (the book's remark after eq. 3-32), so the solve takes one Newton step; the
    two methods agree to round-off.
    """
    Mz = _points(M, 3, "M")
    ph = _angles(phi, 3, "phi")
    a, d = _complex(A, "A"), _complex(D, "D")
    if method not in ("matrix", "nonlinear"):
        raise ValueError(f"method must be 'matrix' or 'nonlinear', got {method!r}")
    if not (tol > 0 and math.isfinite(tol)):
        raise ValueError(f"tol must be positive, got {tol!r}")
    if int(max_iter) != max_iter or max_iter < 1:
        raise ValueError(f"max_iter must be a positive integer, got {max_iter!r}")
    # the inverted positions: the book's construction, and the conditions of a
    # unique solution for both methods (eq. 3-31 is singular exactly when they
    # are collinear)
    inv_a, inv_d = _inverted(a, Mz, ph), _inverted(d, Mz, ph)
    b1, c1 = _circumcentre(inv_a, 1), _circumcentre(inv_d, 3)
    iterations = 0
    if method == "nonlinear":
        b1, c1, iterations = _solve_moving_pivots(a, d, Mz, ph, tol, int(max_iter), guess)
    values = {"method": method, "iterations": int(iterations), "tol": float(tol),
              "residual": _equation_residual(a, d, Mz, ph, b1, c1)}
    return _poses_design(a, d, Mz, ph, b1, c1, values)


def _solve_moving_pivots(a: complex, d: complex, M: np.ndarray, phi: np.ndarray, tol: float,
                         max_iter: int, guess: Optional[List[Tuple[float, float]]]
                        ) -> Tuple[complex, complex, int]:
    """Eqs. 3-31, 3-32 (i = 2, 3) solved for x'_B, y'_B, x'_C, y'_C with scipy.

    Scaled by the size of the data (origin M1), so that ``tol`` is relative.
    """
    from scipy.optimize import root

    scale = float(max(np.max(np.abs(M - M[0])), abs(a - M[0]), abs(d - M[0])))
    m = (M - M[0]) / scale
    fixed = np.array([(a - M[0]) / scale, (d - M[0]) / scale])
    e = np.exp(1j * phi)                               # the coupler frame in each pose
    if guess is None:
        x0 = np.zeros(4)
    else:
        g = _points(guess, 2, "guess")
        local = (g - M[0]) / scale / e[0]              # eqs. 3-28, 3-29 inverted at pose 1
        x0 = np.array([local[0].real, local[0].imag, local[1].real, local[1].imag])

    def fun(x: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        F, J = np.zeros(4), np.zeros((4, 4))
        for k in range(2):                              # k = 0: B about A; 1: C about D
            p = complex(x[2 * k], x[2 * k + 1])
            r = m + p * e - fixed[k]                    # B_i - A (or C_i - D)
            for i in (1, 2):
                F[2 * k + i - 1] = abs(r[i]) ** 2 - abs(r[0]) ** 2
                # d|r_i|²/dx' = 2 Re(conj(r_i) e_i), d/dy' = 2 Re(conj(r_i) i e_i)
                for col, dz in ((0, 1.0), (1, 1j)):
                    J[2 * k + i - 1, 2 * k + col] = 2 * ((r[i].conjugate() * dz * e[i]).real
                                                         - (r[0].conjugate() * dz * e[0]).real)
        return F, J

    # Levenberg–Marquardt (MINPACK lmder): on these linear equations it stops after
    # a step or two; MINPACK's hybrid method (fsolve's) reports "no progress" once
    # the residual is exactly zero, so success is judged on the residual as well
    sol = root(fun, x0, jac=True, method="lm",
               options={"xtol": tol, "ftol": tol, "maxiter": max_iter})
    F, _ = fun(sol.x)
    resid = float(np.max(np.abs(F))) if np.all(np.isfinite(sol.x)) else math.inf
    if not (resid <= max(tol, 1e-13) or (sol.success and resid <= 1e-6)):
        raise ConvergenceError(f"the moving pivots did not converge in {sol.nfev} "
                               f"evaluations ({sol.message})")
    iterations = int(getattr(sol, "njev", None) or sol.nfev)
    b1 = M[0] + scale * complex(sol.x[0], sol.x[1]) * e[0]
    c1 = M[0] + scale * complex(sol.x[2], sol.x[3]) * e[0]
    return b1, c1, iterations


# --------------------------------------------------------------------- Burmester
@record(eq=False)
class BurmesterCurves:
    """The centre-point and circle-point curves of four poses.

    Attributes
    ----------
    centre, circle : list of complex ndarray
        Branch by branch, the fixed pivots (centre points) and the moving
        pivots in pose 1 (circle points) of the dyads that reach the four poses
        [m]; ``circle[k][i]`` is the circle point of ``centre[k][i]``.  Finite,
        NaN-free; a curve is cut where it leaves the disc of radius
        ``extent`` × the poses' size about M1 (its asymptote) and where the
        parameter has no real solution.
    beta2 : list of ndarray
        The crank's rotation β2 from pose 1 to pose 2 at each point [rad].
    """

    centre: List[np.ndarray]
    circle: List[np.ndarray]
    beta2: List[np.ndarray]

    def centre_branches(self) -> List[np.ndarray]:
        """The centre-point curve, one array per branch [m]."""
        return list(self.centre)

    def circle_branches(self) -> List[np.ndarray]:
        """The circle-point curve, one array per branch [m]."""
        return list(self.circle)


@record
class BurmesterPair:
    """A dyad that reaches five poses: a Burmester point pair.

    Attributes
    ----------
    centre : complex
        The fixed pivot (centre point) [m]; when ``at_infinity``, the unit
        vector along the straight line the circle point moves on instead.
    circle : complex
        The moving pivot in pose 1 (circle point) [m].
    at_infinity : bool
        The centre point is at infinity: the circle point's positions are on a
        line, and the dyad is a slider on a guide along ``centre``.
    """

    centre: complex
    circle: complex
    at_infinity: bool = False


def _poses(M: Any, phi: Any, n: int) -> Tuple[np.ndarray, np.ndarray, float, np.ndarray]:
    """Poses scaled about M1: (m_j = (M_j - M_1)/L, E_j = e^{i(φj - φ1)}, L, M as complex)."""
    Mz = _points(M, n, "M")
    ph = _angles(phi, len(Mz), "phi")
    L = float(np.max(np.abs(Mz - Mz[0])))
    if L <= COINCIDENT_TOL * (float(np.max(np.abs(Mz))) + 1.0) or L == 0.0:
        raise DescribedError("every pose has the same coupler point: the coupler turns about "
                             "it, and every point of the coupler is a circle point",
                             reason="coincident")
    for i in range(len(Mz)):
        for j in range(i + 1, len(Mz)):
            # a pose repeated (phi one turn apart is the same pose): one equation short
            if abs(Mz[j] - Mz[i]) <= COINCIDENT_TOL * L \
                    and abs(cast(float, _wrap(ph[j] - ph[i]))) <= COINCIDENT_TOL:
                raise DescribedError(f"poses {i + 1} and {j + 1} are the same pose",
                                     reason="coincident", positions=(i + 1, j + 1))
    return (Mz - Mz[0]) / L, np.exp(1j * (ph - ph[0])), L, Mz


def burmester_curves(M: Any, phi: Any, n: int = 721, *, extent: Optional[float] = None
                    ) -> BurmesterCurves:
    """The centre-point and circle-point curves of four coupler poses.

    Parameters
    ----------
    M : sequence of four (x, y)
        The coupler point in each pose [m].
    phi : sequence of four float
        The coupler angle in each pose [rad].
    n : int
        Samples of the parameter β over a turn (each gives up to two points).
    extent : float, optional
        Points farther from M1 than ``extent`` × max|Mj - M1| are left out (the
        curves go to infinity along an asymptote).  Default: 10, or enough to
        show the six poles Pjk (which are on the centre-point curve) up to 100.

    Returns
    -------
    BurmesterCurves

    Raises
    ------
    DescribedError
        ``coincident``; ``degenerate`` (the poses leave the compatibility
        equation empty: every dyad or none).

    Notes
    -----
    Sandor–Erdman: the equations (S-E) for j = 2, 3, 4 are linear in W, Z, so
    their 3×3 determinant vanishes (the compatibility equation)

        Δ1 + Δ2 e^{iβ2} + Δ3 e^{iβ3} + Δ4 e^{iβ4} = 0,    Δ1 = -(Δ2 + Δ3 + Δ4),

    Δj the cofactors of the column e^{iβj} - 1.  It closes a quadrilateral of
    sides |Δj|: one β (the parameter: the one of the shortest side) is swept
    over a turn, the next follows from the triangle inequality in two ways
    (cos(β + γ) = h/|g|), the last from the closure; then W, Z from two of the
    equations, circle point B1 = M1 - Z, centre point A = B1 - W.  The two ways
    join where h = ±|g|, so each run of the parameter is one closed curve.
    """
    n = int(n)
    if n < 8:
        raise ValueError(f"n must be at least 8, got {n}")
    m, E, L, Mz = _poses(M, phi, 4)
    if extent is None:
        far = [abs(P) for P in _poles(m, E) if abs(P) <= 100]
        extent = max([10.0] + [1.25 * r for r in far])
    if not extent > 0:
        raise ValueError(f"extent must be positive, got {extent!r}")
    comp = _Compatibility(m, E, extent)
    step = 2 * np.pi / n
    grid = step * (np.arange(n) + 0.5)
    ok = comp.triangle(grid)[2]
    out = _Loops(Mz[0], L, extent / 50, n)
    for run in _cyclic_runs(ok):
        beta = np.unwrap(grid[run])
        if len(run) == n:                           # two closed loops
            loop = np.concatenate([beta, beta[:1] + 2 * np.pi])
            _keep(comp, out, loop, np.ones(len(loop)))
            _keep(comp, out, loop, -np.ones(len(loop)))
        else:                                       # one loop: + forward, - back
            lo = _edge(comp, beta[0], beta[0] - step)
            hi = _edge(comp, beta[-1], beta[-1] + step)
            fwd = np.concatenate([[lo], beta, [hi]])
            _keep(comp, out, np.concatenate([fwd, fwd[::-1]]),
                  np.concatenate([np.ones(len(fwd)), -np.ones(len(fwd))]))
    return BurmesterCurves(out.centres, out.circles, out.betas)


class _Compatibility:
    """The compatibility equation of four poses (:func:`burmester_curves`, Notes): its
    cofactors, and its solutions W, Z at values of the parameter."""

    def __init__(self, m: np.ndarray, E: np.ndarray, extent: float) -> None:
        Aj, dj = E[1:] - 1, m[1:]                      # rows j = 2, 3, 4
        cof = np.array([Aj[1] * dj[2] - Aj[2] * dj[1],
                        -(Aj[0] * dj[2] - Aj[2] * dj[0]),
                        Aj[0] * dj[1] - Aj[1] * dj[0]])
        big = float(np.max(np.abs(cof)))
        if big <= 1e-12:
            raise DescribedError("the four poses leave the compatibility equation empty",
                                 reason="degenerate")
        self.Aj, self.dj, self.cof, self.extent = Aj, dj, cof, extent
        self.d1 = -cof.sum()
        # parameter: the shortest side
        self.p, self.q, self.r = (int(i) for i in np.argsort(np.abs(cof)))

    def triangle(self, beta: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(base, |h/g|-clipped spread, ok) of the second angle at parameter values beta."""
        cof, p, q, r = self.cof, self.p, self.q, self.r
        K = self.d1 + cof[p] * np.exp(1j * beta)
        g = K.conjugate() * cof[q]
        h = (abs(cof[r]) ** 2 - abs(cof[q]) ** 2 - np.abs(K) ** 2) / 2
        ok = np.abs(h) <= np.abs(g)
        ratio = np.where(np.abs(g) > 0, h / np.where(np.abs(g) > 0, np.abs(g), 1.0), 2.0)
        return -np.angle(g), np.arccos(np.clip(ratio, -1.0, 1.0)), ok

    def points(self, beta: np.ndarray, sign: np.ndarray
               ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Centre, circle points (scaled), β2 and validity at parameter beta, way sign."""
        cof, p, q, r, Aj, dj = self.cof, self.p, self.q, self.r, self.Aj, self.dj
        base, spread, ok = self.triangle(beta)
        x = np.empty((3, len(beta)), dtype=complex)
        x[p] = np.exp(1j * beta)
        x[q] = np.exp(1j * (base + sign * spread))
        x[r] = -(self.d1 + cof[p] * x[p] + cof[q] * x[q]) / cof[r]
        # W, Z from the best-conditioned two of the three equations
        W = np.zeros(len(beta), dtype=complex)
        Z = np.zeros(len(beta), dtype=complex)
        dets = np.zeros(len(beta))
        for j, k in ((0, 1), (0, 2), (1, 2)):
            det = (x[j] - 1) * Aj[k] - (x[k] - 1) * Aj[j]
            take = np.abs(det) > dets
            safe = np.where(take, det, 1.0)
            W = np.where(take, (dj[j] * Aj[k] - dj[k] * Aj[j]) / safe, W)
            Z = np.where(take, ((x[j] - 1) * dj[k] - (x[k] - 1) * dj[j]) / safe, Z)
            dets = np.where(take, np.abs(det), dets)
        circle = -Z                                # B1 = M1 - Z (M1 at the origin)
        centre = circle - W
        extent = self.extent
        good = ok & (dets > 1e-14) & (np.abs(circle) <= extent) & (np.abs(centre) <= extent)
        return centre, circle, np.angle(x[0]), good


class _Loops:
    """The pieces of the Burmester curves kept so far, in the poses' frame."""

    def __init__(self, origin: complex, scale: float, chord: float, n: int) -> None:
        self.origin, self.scale, self.n = origin, scale, n
        #: longest chord before a sample is added
        self.chord = chord
        self.centres: List[np.ndarray] = []
        self.circles: List[np.ndarray] = []
        self.betas: List[np.ndarray] = []


def _keep(comp: _Compatibility, out: _Loops, beta: np.ndarray, sign: np.ndarray) -> None:
    """Sample one loop (beta unwrapped, increasing where the way is +), adding
    samples where the curve moves fast, then cut it where it leaves the disc."""
    chord = out.chord
    for _ in range(8):
        cen, cir, b2, good = comp.points(beta, sign)
        long = (np.maximum(np.abs(np.diff(cen)), np.abs(np.diff(cir))) > chord) \
            & (sign[1:] == sign[:-1]) & (good[1:] | good[:-1])
        if not long.any() or len(beta) > 8 * out.n:
            break
        at = np.flatnonzero(long) + 1
        beta = np.insert(beta, at, (beta[at - 1] + beta[at]) / 2)
        sign = np.insert(sign, at, sign[at])
    cut = ~good
    # an asymptote crossed between two samples (refinement gave up)
    cut[1:] |= np.maximum(np.abs(np.diff(cen)), np.abs(np.diff(cir))) > 4 * chord
    for seg in _runs(~cut, good):
        if len(seg) >= 2:
            out.centres.append(out.origin + out.scale * cen[seg])
            out.circles.append(out.origin + out.scale * cir[seg])
            out.betas.append(b2[seg])


def _edge(comp: _Compatibility, inside: float, outside: float) -> float:
    """The parameter where the triangle closes (h = ±|g|), by bisection."""
    for _ in range(50):
        mid = (inside + outside) / 2
        inside, outside = (mid, outside) if comp.triangle(np.array([mid]))[2][0] else \
            (inside, mid)
    return inside


def _poles(m: np.ndarray, E: np.ndarray) -> List[complex]:
    """The poles Pjk of the displacements between poses (scaled; finite ones)."""
    out = []
    for j in range(len(m)):
        for k in range(j + 1, len(m)):
            e = E[k] / E[j]
            if abs(1 - e) > 1e-12:
                # P = m_k + e (P - m_j): the point of the body that stays put
                out.append(complex((m[k] - e * m[j]) / (1 - e)))
    return out


def _runs(start_ok: np.ndarray, good: np.ndarray) -> List[np.ndarray]:
    """Runs of ``good`` samples, a new run also where ``start_ok`` is False."""
    runs: List[np.ndarray] = []
    cur: List[int] = []
    for k in range(len(good)):
        if not good[k]:
            if cur:
                runs.append(np.array(cur))
            cur = []
            continue
        if not start_ok[k] and cur:
            runs.append(np.array(cur))
            cur = []
        cur.append(k)
    if cur:
        runs.append(np.array(cur))
    return runs


def _cyclic_runs(mask: np.ndarray) -> List[np.ndarray]:
    """Index runs where ``mask`` holds, the array read as a circle."""
    n = len(mask)
    if mask.all():
        return [np.arange(n)]
    if not mask.any():
        return []
    start = int(np.argmin(mask))                    # a False: runs do not wrap past it
    idx = (np.arange(n) + start) % n
    m = mask[idx]
    runs, k = [], 0
    while k < n:
        if m[k]:
            j = k
            while j < n and m[j]:
                j += 1
            runs.append(idx[k:j])
            k = j
        else:
            k += 1
    return runs


def _rows(m: np.ndarray, E: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """N(c) = N0 + u Nu + v Nv for the circle point c = u + iv (scaled, M1 = 0).

    Row j (poses j = 2…5) of the condition on the centre point (w, ax, ay), the
    homogeneous A = (ax + i ay)/w:  |Bj|² - |B1|² - 2 Re(conj(A)(Bj - B1)) = 0,
    i.e. |Bj - A| = |B1 - A| (eq. 3-31, S-E with βj eliminated), with
    Bj = m_j + c E_j (eq. 3-28).  |Bj|² - |c|² = |m_j|² + 2 Re(conj(m_j) E_j c) is
    affine in c, so every entry is.
    """
    mj, Ej = m[1:], E[1:]
    Aj = Ej - 1
    k = mj.conjugate() * Ej
    N0 = np.column_stack([np.abs(mj) ** 2, -2 * mj.real, -2 * mj.imag])
    Nu = np.column_stack([2 * k.real, -2 * Aj.real, -2 * Aj.imag])
    Nv = np.column_stack([-2 * k.imag, 2 * Aj.imag, -2 * Aj.real])
    return N0, Nu, Nv


def burmester_points(M: Any, phi: Any) -> List[BurmesterPair]:
    """The Burmester point pairs of five coupler poses (real ones, at most four).

    Parameters
    ----------
    M : sequence of five (x, y)
        The coupler point in each pose [m].
    phi : sequence of five float
        The coupler angle in each pose [rad].

    Returns
    -------
    list of BurmesterPair
        Finite pairs sorted by the centre point's x (then y), a slider pair
        (centre point at infinity) last.  Each satisfies (S-E) for j = 2…5 to
        round-off (relative residual ≤ ``BURMESTER_TOL``).  A pair whose
        *circle* point is at infinity (a guide on the coupler through a fixed
        pivot) is not returned.

    Raises
    ------
    DescribedError
        ``coincident``, ``no_rotation`` (the poses only translate).

    Notes
    -----
    Eliminating βj from (S-E) leaves, for the circle point c and the centre
    point A, the 4×3 system N(c) (w, ax, ay)ᵀ = 0 (see :func:`_rows`), affine in
    c: c is a Burmester point where N(c) has rank 2.  Rows j, k, l vanish
    together (a 3×3 determinant, cubic in c) on the circle-point curve of poses
    1, j, k, l, which passes through the pole P1j (where row j is zero).  On the
    line c = P1j + t e^{iθ} each cubic is t·q(t), q quadratic; the curves of
    poses 1234 and 1235 meet on the line where the two quadratics have a common
    root, i.e. where their resultant R(θ) vanishes.  R is a trigonometric
    polynomial of degree 8 in θ (even harmonics only); it is sampled at 16
    angles and its roots found as polynomial roots in e^{2iθ}.  Its real roots
    are the Burmester points and two spurious lines (through P13 and the image
    pole P23); the complex pair is the circular points.  Each candidate is
    polished by Newton's method on N(c) n = 0 and kept when N(c) has rank 2;
    then βj, W, Z follow and are polished on (S-E).
    """
    m, E, L, Mz = _poses(M, phi, 5)
    rot = np.abs(E[1:] - 1)
    if rot.max() <= 1e-9:
        raise DescribedError("the five poses only translate the coupler",
                             reason="no_rotation")
    N0, Nu, Nv = _rows(m, E)
    order = np.argsort(-rot)                       # the pole of the largest rotation first
    N0, Nu, Nv = N0[order], Nu[order], Nv[order]
    k = order[0] + 1
    P = m[k] / (1 - E[k])                          # the pole P1k: B_k = B_1
    X = N0 + P.real * Nu + P.imag * Nv             # N(P); its row 0 is zero
    X[0] = 0.0
    candidates = _line_candidates(P, X, Nu, Nv)
    pairs: List[Tuple[complex, np.ndarray]] = []
    for c0 in candidates:
        found = _polish_circle_point(c0, N0, Nu, Nv)
        if found is None:
            continue
        c, nvec = found
        if any(abs(c - q[0]) <= 1e-7 * (1 + abs(c)) for q in pairs):
            continue
        pairs.append((c, nvec))
    out = _burmester_pairs(pairs, m, E, L, Mz)
    out.sort(key=lambda p: (p.at_infinity, p.centre.real if not p.at_infinity else 0.0,
                            p.centre.imag if not p.at_infinity else 0.0))
    return out


def _quads(X: np.ndarray, Nu: np.ndarray, Nv: np.ndarray, theta: np.ndarray
           ) -> List[Tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """q(t) = a + b t + c t² of the cubics of rows (0,1,2) and (0,1,3) on the lines
    c = P + t e^{iθ} (``X`` = N(P))."""
    ct, st = np.cos(theta)[:, None, None], np.sin(theta)[:, None, None]
    Y = ct * Nu + st * Nv                      # (T, 4, 3)
    Xb = np.broadcast_to(X, Y.shape)
    out = []
    for last in (2, 3):
        def det(r1: np.ndarray, r2: np.ndarray) -> np.ndarray:
            return np.linalg.det(np.stack([Y[:, 0], r1, r2], axis=1))
        a = det(Xb[:, 1], Xb[:, last])
        b = det(Y[:, 1], Xb[:, last]) + det(Xb[:, 1], Y[:, last])
        c = det(Y[:, 1], Y[:, last])
        out.append((a, b, c))
    return out


def _line_candidates(P: complex, X: np.ndarray, Nu: np.ndarray, Nv: np.ndarray
                     ) -> List[complex]:
    """The candidate circle points: the common roots on the lines through the pole P
    at the real roots θ of the resultant R(θ) (:func:`burmester_points`, Notes)."""
    T = 16
    theta = np.pi * np.arange(T) / T
    (a1, b1, c1), (a2, b2, c2) = _quads(X, Nu, Nv, theta)
    R = (a1 * c2 - a2 * c1) ** 2 - (a1 * b2 - a2 * b1) * (b1 * c2 - b2 * c1)
    r = np.fft.fft(R) / T                          # R = Σ r_m e^{2imθ}, m = -4…4
    coeffs = np.array([r[mm % T] for mm in range(4, -5, -1)])
    scale = float(np.max(np.abs(coeffs)))
    coeffs = np.where(np.abs(coeffs) <= 1e-13 * scale, 0.0, coeffs)
    nz = np.flatnonzero(coeffs)
    roots = np.roots(coeffs[nz[0]:nz[-1] + 1]) if len(nz) > 1 else np.zeros(0)
    roots = roots[np.abs(np.abs(roots) - 1) < 1e-3]
    cand_theta = np.angle(roots) / 2
    candidates = []
    if len(cand_theta):
        qs = _quads(X, Nu, Nv, cand_theta)
        for i, th in enumerate(cand_theta):
            for a, b, c in qs:
                for t in np.roots([c[i], b[i], a[i]]) if abs(c[i]) > 0 or abs(b[i]) > 0 else ():
                    if abs(t.imag) <= 1e-3 * (1 + abs(t)):
                        candidates.append(P + t.real * np.exp(1j * th))
    return candidates


def _burmester_pairs(pairs: List[Tuple[complex, np.ndarray]], m: np.ndarray, E: np.ndarray,
                     L: float, Mz: np.ndarray) -> List[BurmesterPair]:
    """The Burmester pairs of the polished circle points and null vectors (w, ax, ay),
    in the poses' frame; those that do not polish are left out."""
    out = []
    for c, (w, ax, ay) in pairs:
        a = complex(ax, ay)
        if abs(w) * INFINITY < abs(a):             # the centre point at infinity: a slider
            guide = 1j * a / abs(a)                # the circle point moves normal to a
            if guide.real < 0 or (guide.real == 0 and guide.imag < 0):
                guide = -guide
            if _slider_residual(c, m, E, guide) <= BURMESTER_TOL:
                out.append(BurmesterPair(complex(guide), complex(Mz[0] + L * c), True))
            continue
        centre = a / w
        polished = _polish_dyad(centre, c, m, E)
        if polished is None:
            continue
        centre, c = polished
        out.append(BurmesterPair(complex(Mz[0] + L * centre), complex(Mz[0] + L * c), False))
    return out


def _polish_circle_point(c0: complex, N0: np.ndarray, Nu: np.ndarray, Nv: np.ndarray,
                         iterations: int = 30) -> Optional[Tuple[complex, np.ndarray]]:
    """Newton on N(c) n = 0, n0·n = 1 (5 equations, unknowns u, v, n); (c, n) or None."""
    c = complex(c0)
    N = N0 + c.real * Nu + c.imag * Nv
    n0 = np.linalg.svd(N)[2][-1]
    x = np.array([c.real, c.imag, *n0])
    with np.errstate(over="ignore", invalid="ignore"):
        # a start that diverges overflows: it is no solution, and is dropped below
        polished = _newton_circle_point(x, n0, N0, Nu, Nv, iterations)
    if polished is None:
        return None
    x = polished
    N = N0 + x[0] * Nu + x[1] * Nv
    s = np.linalg.svd(N, compute_uv=False)
    if s[-1] > 1e-10 * s[0]:
        return None
    nvec = x[2:] / np.linalg.norm(x[2:])
    return complex(x[0], x[1]), nvec


def _newton_circle_point(x: np.ndarray, n0: np.ndarray, N0: np.ndarray, Nu: np.ndarray,
                         Nv: np.ndarray, iterations: int) -> Optional[np.ndarray]:
    """Newton's iterations of :func:`_polish_circle_point`; None when they diverge."""
    for _ in range(iterations):
        N = N0 + x[0] * Nu + x[1] * Nv
        F = np.concatenate([N @ x[2:], [n0 @ x[2:] - 1.0]])
        J = np.zeros((5, 5))
        J[:4, 0], J[:4, 1], J[:4, 2:] = Nu @ x[2:], Nv @ x[2:], N
        J[4, 2:] = n0
        try:
            step = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            return None
        x = x + step
        if not np.all(np.isfinite(x)) or abs(complex(x[0], x[1])) > INFINITY:
            return None
        if np.max(np.abs(step)) <= 1e-15 * (1 + np.max(np.abs(x))):
            break
    return x


def _dyad_residual(centre: complex, circle: complex, m: np.ndarray, E: np.ndarray) -> float:
    """Largest ||Bj - A| - |B1 - A|| (scaled): the circle point on its circle."""
    B = m + circle * E
    r = np.abs(B - centre)
    return float(np.max(np.abs(r - r[0])))


def _slider_residual(circle: complex, m: np.ndarray, E: np.ndarray, guide: complex) -> float:
    """Largest distance of the circle point's positions from its line (scaled)."""
    B = m + circle * E
    return float(np.max(np.abs((np.conj(guide) * (B - B[0])).imag)))


def _polish_dyad(centre: complex, circle: complex, m: np.ndarray, E: np.ndarray,
                 iterations: int = 8) -> Optional[Tuple[complex, complex]]:
    """Newton on (S-E) j = 2…n in W, Z, βj (scaled, M1 = 0); (centre, circle) or None."""
    W, Z = circle - centre, -circle
    B = m + circle * E
    beta = np.angle((B[1:] - centre) / W)
    Aj, dj = E[1:] - 1, m[1:]
    k = len(dj)
    x = np.concatenate([[W.real, W.imag, Z.real, Z.imag], beta])
    # a diverging start overflows: it is no solution, and is dropped below
    with np.errstate(over="ignore", invalid="ignore"):
        for _ in range(iterations):
            W, Z = complex(x[0], x[1]), complex(x[2], x[3])
            eb = np.exp(1j * x[4:])
            F = W * (eb - 1) + Z * Aj - dj
            if np.max(np.abs(F)) <= 1e-15:
                break
            Jc = np.zeros((k, 4 + k), dtype=complex)
            Jc[:, 0], Jc[:, 1], Jc[:, 2], Jc[:, 3] = eb - 1, 1j * (eb - 1), Aj, 1j * Aj
            Jc[np.arange(k), 4 + np.arange(k)] = 1j * W * eb
            J = np.concatenate([Jc.real, Jc.imag])
            Fr = np.concatenate([F.real, F.imag])
            try:
                step = np.linalg.solve(J, -Fr)
            except np.linalg.LinAlgError:
                break
            x = x + step
    if not np.all(np.isfinite(x)):
        return None
    W, Z = complex(x[0], x[1]), complex(x[2], x[3])
    F = W * (np.exp(1j * x[4:]) - 1) + Z * Aj - dj
    if np.max(np.abs(F)) > BURMESTER_TOL:
        return None
    return -Z - W, -Z


def burmester_design(M: List[Tuple[float, float]], phi: np.ndarray, pair_a: BurmesterPair,
                     pair_b: BurmesterPair) -> LinkageDesign:
    """The four-bar of two Burmester pairs: A, B1 of ``pair_a``; D, C1 of ``pair_b``.

    Parameters
    ----------
    M : sequence of (x, y)
        The coupler point in each pose (four or five; any number ≥ 2) [m].
    phi : sequence of float
        The coupler angle in each pose [rad].
    pair_a, pair_b : BurmesterPair
        Two dyads that reach the poses (from :func:`burmester_points`, or
        points of :func:`burmester_curves` as ``BurmesterPair(centre, circle)``).

    Returns
    -------
    LinkageDesign
        ``inputs`` θ1 at each pose, ``points`` ``{"M"}``, ``angles`` ``{2: θ2}``,
        coupler point M1; ``values`` ``{"residual"}``: the largest
        ||Bj - A| - |B1 - A|| (and of C about D) divided by the poses' size.

    Raises
    ------
    DescribedError
        ``at_infinity`` (a slider pair), ``not_on_circle`` (a pair that does not
        reach the poses: relative residual above 1e-6), ``zero_link``.
    """
    npos = len(list(M))
    if npos < 2:
        raise ValueError(f"burmester_design needs at least two poses, got {npos}")
    m, E, L, Mz = _poses(M, phi, npos)
    for name, pair in (("a", pair_a), ("b", pair_b)):
        if pair.at_infinity:
            raise DescribedError(f"Burmester pair {name} has its centre point at infinity "
                                 "(a slider): it makes no four-bar", reason="at_infinity")
    res = []
    for pair in (pair_a, pair_b):
        cen, cir = (_complex(pair.centre, "centre") - Mz[0]) / L, \
                   (_complex(pair.circle, "circle") - Mz[0]) / L
        res.append(_dyad_residual(cen, cir, m, E))
    if max(res) > 1e-6:
        raise DescribedError("a Burmester pair does not keep its circle point on a circle "
                             "through the poses", reason="not_on_circle",
                             residual_a=res[0], residual_b=res[1])
    A, D = complex(pair_a.centre), complex(pair_b.centre)
    b1, c1 = complex(pair_a.circle), complex(pair_b.circle)
    b, c = Mz + (b1 - Mz[0]) * E, Mz + (c1 - Mz[0]) * E
    return _design(A, D, b, c, points={"M": Mz.copy()}, angles={2: _wrap(np.angle(c - b))},
                   coupler_point=_pt(Mz[0]), values={"residual": float(max(res))})


__all__ = ["BurmesterCurves", "BurmesterPair", "burmester_curves", "burmester_design",
           "burmester_points", "coupler_poses", "displacement_matrix", "moving_pivots",
           "three_positions", "two_positions"]
