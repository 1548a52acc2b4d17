"""The involute of a circle, the involute function and its inverse.

Everything is in radians and metres.  ``involute_function`` is accurate to a
few ulps for every angle in [0, pi/2) (a Taylor series replaces the
cancelling difference ``tan a - a`` for small angles), and
``inverse_involute`` converges for every finite theta >= 0 from a starting
value that is already within about 1e-3 of the root, so that Newton's method
needs 2 to 4 steps.  The book's own method (Newton from 0.8 with the absolute
stop |f| < 1e-7, 【例 5-2】) is available as ``method="book"``.

numpy is imported only by the array functions: a Python float goes through
``math`` (``involute_function``, ``inverse_involute_scalar``, ``involute_point``,
``involute_table_rows``), so that the scalar gear geometry starts fast.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, List, Tuple, Union, overload

from mechcli.core.errors import ConvergenceError
from mechcli.core.records import record

if TYPE_CHECKING:  # annotations only: numpy is imported lazily
    import numpy as np
    from numpy.typing import ArrayLike

#: Taylor coefficients c_n of tan(a) - a = sum c_n a^(2n+1), n = 1, 2, ...
#: (c_n = (-1)^n 2^(2n+2) (2^(2n+2) - 1) B_(2n+2) / (2n+2)!).
_TAN_MINUS_X = (
    0.3333333333333333, 0.13333333333333333, 0.05396825396825397,
    0.021869488536155203, 0.008863235529902197, 0.003592128036572481,
    0.0014558343870513183, 0.000590027440945586, 0.00023912911424355248,
    9.691537956929451e-05, 3.927832388331683e-05, 1.5918905069328964e-05,
    6.451689215655431e-06, 2.6147711512907546e-06, 1.0597268320104654e-06,
    4.294911078273806e-07, 1.7406618963571648e-07, 7.054636946400968e-08,
    2.859136662305254e-08, 1.1587644432798853e-08, 4.6962953982309016e-09,
    1.903336833931276e-09)

#: below this angle (rad) the series is used (22 terms: truncation < 1e-19 relative)
_SERIES_LIMIT = 0.5

#: the book's Newton start and tolerance (【例 5-2】)
BOOK_START = 0.8
BOOK_EPSILON = 1e-7


@overload
def involute_function(alpha: float) -> float: ...


@overload
def involute_function(alpha: ArrayLike) -> Union[float, np.ndarray]: ...


def involute_function(alpha: ArrayLike) -> Union[float, np.ndarray]:
    """inv(alpha) = tan(alpha) - alpha, accurate also for tiny angles.

    Parameters
    ----------
    alpha : float or array_like
        Pressure angle in radians, 0 <= alpha < pi/2.

    Returns
    -------
    numpy.ndarray or float
        The involute function (the roll angle theta_K of eq. 5-1), radians.

    Notes
    -----
    Eq. (5-1).  For alpha < 0.5 the difference is summed as its Taylor series
    a^3/3 + 2a^5/15 + ... so that no digits cancel (theta = 1e-12 needs it).
    """
    if isinstance(alpha, (int, float)):
        return _involute_scalar(float(alpha))
    import numpy as np
    a = np.asarray(alpha, dtype=float)
    small = np.abs(a) < _SERIES_LIMIT
    a2 = a * a
    series = np.zeros_like(a)
    for c in _TAN_MINUS_X[::-1]:
        series = series * a2 + c
    series = series * a2 * a
    big = np.where(small, 1.0, a)  # avoid tan of the small ones twice (no warnings)
    out = np.where(small, series, np.tan(big) - big)
    return out if out.ndim else float(out)


def _involute_scalar(a: float) -> float:
    """inv(a) of one float, the same series/difference as the array path (math only)."""
    if abs(a) < _SERIES_LIMIT:
        a2 = a * a
        series = 0.0
        for c in reversed(_TAN_MINUS_X):
            series = series * a2 + c
        return series * a2 * a
    return math.tan(a) - a


#: theta below which the series start is used, above it the fixed-point start
_START_SWITCH = 0.5


def _start(theta: np.ndarray) -> np.ndarray:
    """A starting angle within ~1e-3 relative of inv^-1(theta) for every theta >= 0."""
    import numpy as np
    y = np.cbrt(3.0 * np.minimum(theta, _START_SWITCH))
    y2 = y * y
    # series reversion of y^3 = 3 inv(a): a = y - 2y^3/15 + 3y^5/175 - 2y^7/1575 - ...
    small = y * (1.0 + y2 * (-2.0 / 15.0 + y2 * (3.0 / 175.0 + y2 * (
        -2.0 / 1575.0 + y2 * (-16.0 / 202125.0 + y2 * (362.0 / 9384375.0))))))
    # large theta: tan a = theta + atan(tan a); fixed-point sweeps (contraction 1/(1+t^2))
    t = theta + np.pi / 2.0
    for _ in range(4):
        t = theta + np.arctan(t)
    large = np.arctan(t)
    return np.where(theta < _START_SWITCH, small, large)


#: the real cube root (math.cbrt is Python 3.11's; theta >= 0 here)
_cbrt = getattr(math, "cbrt", None) or (lambda x: math.copysign(abs(x) ** (1.0 / 3.0), x))


def _start_scalar(theta: float) -> float:
    """:func:`_start` for one float (math only)."""
    if theta < _START_SWITCH:
        y = _cbrt(3.0 * theta)
        y2 = y * y
        return y * (1.0 + y2 * (-2.0 / 15.0 + y2 * (3.0 / 175.0 + y2 * (
            -2.0 / 1575.0 + y2 * (-16.0 / 202125.0 + y2 * (362.0 / 9384375.0))))))
    t = theta + math.pi / 2.0
    for _ in range(4):
        t = theta + math.atan(t)
    return math.atan(t)


@record
class InverseInvolute:
    """Result of :func:`inverse_involute`.

    Attributes are numpy arrays from :func:`inverse_involute`; tuples of
    Python numbers when built from :func:`inverse_involute_scalar` values.

    Attributes
    ----------
    theta : numpy.ndarray
        The given involute-function values (rad).
    alpha : numpy.ndarray
        Pressure angles with inv(alpha) = theta (rad).
    iterations : numpy.ndarray of int
        Newton steps taken for each value.
    residual : numpy.ndarray
        inv(alpha) - theta (rad).
    method : str
        ``"auto"`` or ``"book"``.
    start : numpy.ndarray
        The starting angles (rad).
    """

    theta: Union[np.ndarray, tuple]
    alpha: Union[np.ndarray, tuple]
    iterations: Union[np.ndarray, tuple]
    residual: Union[np.ndarray, tuple]
    method: str
    start: Union[np.ndarray, tuple]

    @property
    def relative_residual(self) -> np.ndarray:
        """|inv(alpha) - theta| / theta (0 where theta = 0), an array."""
        import numpy as np
        theta = np.asarray(self.theta, dtype=float)
        den = np.where(theta > 0, theta, 1.0)
        return np.abs(np.asarray(self.residual, dtype=float)) / den


def _left_message(start: float, theta: float) -> str:
    why = ("its first step passes pi/2 for theta > 1.0468" if start == BOOK_START else
           "the start itself is outside" if not 0 < start < math.pi / 2 else
           "a Newton step passed a bound")
    return (f"book Newton start {start:g} left (0, pi/2) for theta = {theta:.6g} ({why}); "
            "use method = \"auto\"")


def inverse_involute(theta: ArrayLike, method: str = "auto", *, start: float = BOOK_START,
                     epsilon: float = BOOK_EPSILON, max_iter: int = 100) -> InverseInvolute:
    """Pressure angle alpha with inv(alpha) = theta (Newton's method, eq. 5-3, 5-4).

    Parameters
    ----------
    theta : float or array_like
        Involute-function values (rad), finite and >= 0.
    method : {"auto", "book"}
        ``auto``: start from a series/asymptotic estimate, iterate until the
        step is below 2 ulp (converges for every finite theta >= 0, 2-4 steps
        for 1e-12 <= theta <= 1).  ``book``: start from *start* (0.8) and stop
        when |theta - tan a + a| < *epsilon* (1e-7), as in 【例 5-2】.
    start : float
        Starting angle of the book method (rad).
    epsilon : float
        Absolute stopping tolerance of the book method (rad).
    max_iter : int
        Iteration limit.

    Returns
    -------
    InverseInvolute

    Raises
    ------
    ConvergenceError
        The book method left (0, pi/2) (theta above 1.0468: its first step
        passes pi/2), or the iteration limit was hit.

    Notes
    -----
    f(a) = inv(a) - theta is increasing and convex on (0, pi/2) (f' = tan^2 a),
    so Newton's iterates approach the root monotonically from above once
    one step has been taken; the ``auto`` start is accurate enough that the
    first step never overshoots far.  The book's absolute stop makes its
    answer wrong for small theta (measured relative residual of inv(alpha):
    4e-5 at theta = 1e-6, 0.86 at 1e-8, 11 at 1e-9, 1.2e4 at 1e-12; see
    ``benchmarks/bench_gear.py``).  Like the book's ``while`` loop, the book
    method takes one more step after the test |f| < epsilon has passed.
    """
    import numpy as np
    th = np.asarray(theta, dtype=float)
    th = np.atleast_1d(th)
    if np.any(~np.isfinite(th)) or np.any(th < 0):
        raise ValueError("inverse_involute needs finite theta >= 0")
    if method == "auto":
        a0 = _start(th)
    elif method == "book":
        a0 = np.full_like(th, float(start))
    else:
        raise ValueError(f"unknown method {method!r}")
    a = a0.copy()
    iters = np.zeros(th.shape, dtype=int)
    active = th > 0
    a[~active] = 0.0
    for _ in range(max_iter):
        if not active.any():
            break
        aa = a[active]
        if method == "book" and np.any((aa <= 0) | (aa >= np.pi / 2)):
            bad = th[active][(aa <= 0) | (aa >= np.pi / 2)]
            raise ConvergenceError(_left_message(start, bad[0]))
        f = involute_function(aa) - th[active]
        tan_a = np.tan(aa)
        df = tan_a * tan_a
        if method == "book":
            done = np.abs(f) < epsilon
        step = f / df
        new = aa - step
        if method == "auto":
            new = np.clip(new, 0.5 * aa, None)  # never jump below half (tiny df guard)
            new = np.minimum(new, np.nextafter(np.pi / 2, 0))
            done = np.abs(new - aa) <= 4.0 * np.spacing(aa)
            iters[active] += 1
            a[active] = new
        else:
            # the book updates once more after testing |f| (its while loop)
            iters[active] += 1
            a[active] = new
        idx = np.flatnonzero(active)
        active[idx[done]] = False
    else:
        if active.any():
            raise ConvergenceError(
                f"inverse involute did not converge in {max_iter} iterations "
                f"(theta = {th[active][0]:.6g}, method {method})")
    res = involute_function(a) - th
    return InverseInvolute(theta=th, alpha=a, iterations=iters, residual=np.asarray(res),
                           method=method, start=a0)


def inverse_involute_scalar(theta: float, method: str = "auto", *, start: float = BOOK_START,
                            epsilon: float = BOOK_EPSILON,
                            max_iter: int = 100) -> Tuple[float, int, float]:
    """:func:`inverse_involute` of one float, with ``math`` only (no numpy import).

    The same start, iteration and stopping rules step for step.

    Returns
    -------
    (float, int, float)
        alpha (rad), Newton steps, and the starting angle (rad).

    Raises
    ------
    ValueError, ConvergenceError
        As :func:`inverse_involute`.
    """
    th = float(theta)
    if not math.isfinite(th) or th < 0:
        raise ValueError("inverse_involute needs finite theta >= 0")
    if method == "auto":
        a0 = _start_scalar(th)
    elif method == "book":
        a0 = float(start)
    else:
        raise ValueError(f"unknown method {method!r}")
    if th == 0:
        return 0.0, 0, a0
    a, top = a0, math.nextafter(math.pi / 2, 0)
    for k in range(1, max_iter + 1):
        if method == "book" and not 0 < a < math.pi / 2:
            raise ConvergenceError(_left_message(start, th))
        f = _involute_scalar(a) - th
        tan_a = math.tan(a)
        new = a - f / (tan_a * tan_a)
        if method == "auto":
            new = min(max(new, 0.5 * a), top)
            done = abs(new - a) <= 4.0 * math.ulp(a)
        else:
            done = abs(f) < epsilon
        a = new
        if done:
            return a, k, a0
    raise ConvergenceError(f"inverse involute did not converge in {max_iter} iterations "
                           f"(theta = {th:.6g}, method {method})")


def involute_point(r_b: float, alpha: float) -> Tuple[float, float, float, float]:
    """:func:`involute_curve` at one pressure angle (floats, math only): (r, theta, x, y)."""
    r = r_b / math.cos(alpha)
    th = _involute_scalar(float(alpha))
    return r, th, r * math.sin(th), r * math.cos(th)


def involute_curve(r_b: float,
                   alpha: ArrayLike) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Points of the involute of a base circle, polar and Cartesian (eq. 5-1, 5-2).

    Parameters
    ----------
    r_b : float
        Base-circle radius (m).
    alpha : array_like
        Pressure angles alpha_K (rad), 0 <= alpha < pi/2.

    Returns
    -------
    r, theta, x, y : numpy.ndarray
        Radius r_K = r_b / cos(alpha_K) (m), roll angle theta_K = inv(alpha_K)
        (rad), and x = r_K sin(theta_K), y = r_K cos(theta_K) (m) with the
        polar axis OA along +y (图 5-1).
    """
    import numpy as np
    a = np.asarray(alpha, dtype=float)
    r = r_b / np.cos(a)
    th = np.asarray(involute_function(a))
    return r, th, r * np.sin(th), r * np.cos(th)


def involute_table(start_deg: float = 10.0, stop_deg: float = 30.0, step_deg: float = 0.1,
                   columns: int = 10) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The involute-function table of 表 5-1 (rows of *columns* values).

    Parameters
    ----------
    start_deg, stop_deg : float
        First and last row label (degrees); the last row is full.
    step_deg : float
        Step between columns (degrees).
    columns : int
        Values per row (the book: 10, i.e. 0.0 ... 0.9 degrees).

    Returns
    -------
    rows_deg : numpy.ndarray, shape (n,)
        Row labels (degrees).
    alpha_deg : numpy.ndarray, shape (n, columns)
        Angles (degrees).
    inv : numpy.ndarray, shape (n, columns)
        inv(alpha) (rad).

    Notes
    -----
    【例 5-1】(2).  Angles are built as row + k * step from integers, so that
    20.3 is the decimal 20.3 and not an accumulated sum.
    """
    import numpy as np
    rows, ang, inv = involute_table_rows(start_deg, stop_deg, step_deg, columns)
    return np.array(rows), np.array(ang), np.array(inv)


def involute_table_rows(start_deg: float = 10.0, stop_deg: float = 30.0, step_deg: float = 0.1,
                        columns: int = 10
                        ) -> Tuple[List[float], List[List[float]], List[List[float]]]:
    """:func:`involute_table` as lists (math only): rows, angles (deg) and values per row."""
    row_step = step_deg * columns
    n = int(round((stop_deg - start_deg) / row_step)) + 1
    rows = [start_deg + row_step * i for i in range(n)]
    ang = [[row + step_deg * k for k in range(columns)] for row in rows]
    return rows, ang, [[_involute_scalar(math.radians(a)) for a in line] for line in ang]


def degrees_minutes_seconds(angle: float, seconds_digits: int = 0,
                            rounding: str = "truncate") -> Tuple[int, int, float]:
    """Split an angle into degrees, minutes and seconds as the book prints it.

    Parameters
    ----------
    angle : float
        Angle (rad), >= 0.
    seconds_digits : int
        Decimals of the seconds.
    rounding : {"truncate", "round"}
        ``truncate`` floors every part like the book's ``floor`` (【例 5-2】:
        21.98110 deg -> 21°58′51″, the exact seconds are 51.97); ``round``
        rounds the seconds (with carry into minutes and degrees).

    Returns
    -------
    (int, int, float)
        Degrees, minutes, seconds.
    """
    total = math.degrees(float(angle)) * 3600.0
    q = 10.0 ** seconds_digits
    if rounding == "truncate":
        total = math.floor(total * q * (1 + 1e-15)) / q
    elif rounding == "round":
        total = round(total * q) / q
    else:
        raise ValueError(f"unknown rounding {rounding!r}")
    deg = int(total // 3600)
    minutes = int((total - deg * 3600) // 60)
    seconds = total - deg * 3600 - minutes * 60
    return deg, minutes, round(seconds, seconds_digits)


def format_dms(angle: float, seconds_digits: int = 0, rounding: str = "truncate") -> str:
    """``21°58′51″`` text for an angle in radians (see :func:`degrees_minutes_seconds`)."""
    d, m, s = degrees_minutes_seconds(angle, seconds_digits, rounding)
    sec = f"{s:.{seconds_digits}f}" if seconds_digits else f"{int(s)}"
    return f"{d}°{m}′{sec}″"
