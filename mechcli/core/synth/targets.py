"""The target functions y = f(x) a function generator may be asked to reproduce (§3.5 二).

A function is chosen by name from :data:`NAMES` (with its exponent or its
coefficients where it has them) or given as a table of points; text is never
evaluated.  Every :class:`Function` is vectorised, knows its derivative and
checks that an interval lies inside its domain
(:meth:`Function.check_domain`), raising
:class:`~mechcli.core.errors.DescribedError` with ``reason="domain"`` when it
does not.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, Optional, Tuple, cast

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.types import FloatOrArray

#: the names :func:`make_function` accepts
NAMES = ("log10", "ln", "sqrt", "power", "sin", "cos", "tan", "exp", "reciprocal",
         "polynomial")

#: what each name computes, for messages and documentation
FORMULAS = {
    "log10": "lg x", "ln": "ln x", "sqrt": "sqrt(x)", "power": "x^p", "sin": "sin x",
    "cos": "cos x", "tan": "tan x", "exp": "e^x", "reciprocal": "1/x",
    "polynomial": "c0 + c1 x + c2 x^2 + ...", "table": "table of points",
}


@record(eq=False)
class Function:
    """A named function y = f(x), or a table of points.

    Attributes
    ----------
    name : str
        One of :data:`NAMES`, or ``"table"``.
    exponent : float or None
        p of ``"power"`` (y = x**p).
    coeffs : tuple of float or None
        c0, c1, ... of ``"polynomial"``, in ascending powers:
        y = c0 + c1 x + c2 x**2 + ...
    nodes : (ndarray, ndarray) or None
        The table's points (x strictly increasing, y) of ``"table"``.
    interpolation : str or None
        ``"cubic"`` or ``"linear"`` for a table (see :func:`table_function`).

    Calling the function, ``f(x)``, and :meth:`derivative` work on arrays.
    Outside its domain (:meth:`check_domain`) the values are undefined; a
    table is extrapolated by its end pieces.
    """

    name: str
    exponent: Optional[float] = None
    coeffs: Optional[Tuple[float, ...]] = None
    nodes: Optional[Tuple[np.ndarray, np.ndarray]] = None
    interpolation: Optional[str] = None
    _table: Any = dataclasses.field(default=None, repr=False, compare=False)

    def __call__(self, x: Any) -> FloatOrArray:
        x = np.asarray(x, dtype=float)
        name = self.name
        if name == "log10":
            return np.log10(x)
        if name == "ln":
            return np.log(x)
        if name == "sqrt":
            return np.sqrt(x)
        if name == "power":
            return np.power(x, cast(float, self.exponent))  # set for "power" (make_function)
        if name == "sin":
            return np.sin(x)
        if name == "cos":
            return np.cos(x)
        if name == "tan":
            return np.tan(x)
        if name == "exp":
            return np.exp(x)
        if name == "reciprocal":
            return 1.0 / x
        if name == "polynomial":  # numpy's stubs: a scalar (an array here)
            return cast("FloatOrArray", np.polynomial.polynomial.polyval(x, self._coeffs()))
        return self._table_value(x, 0)

    def derivative(self, x: Any) -> np.ndarray:
        """dy/dx at ``x`` (vectorised).

        Where the derivative is infinite (sqrt at 0, a power 0 < p < 1 at 0)
        the value is ``inf``, without a warning.
        """
        x = np.asarray(x, dtype=float)
        name = self.name
        with np.errstate(divide="ignore"):
            if name == "log10":
                return 1.0 / (x * math.log(10.0))
            if name == "ln":
                return 1.0 / x
            if name == "sqrt":
                return 0.5 / np.sqrt(x)
            if name == "power":
                p = cast(float, self.exponent)  # set for "power" (make_function)
                return np.zeros_like(x) if p == 0 else p * np.power(x, p - 1.0)
            if name == "sin":
                return np.cos(x)
            if name == "cos":
                return -np.sin(x)
            if name == "tan":
                return 1.0 / np.cos(x) ** 2
            if name == "exp":
                return np.exp(x)
            if name == "reciprocal":
                return -1.0 / (x * x)
            if name == "polynomial":
                return cast(np.ndarray, np.polynomial.polynomial.polyval(
                    x, np.polynomial.polynomial.polyder(self._coeffs())))
        return self._table_value(x, 1)

    def _coeffs(self) -> Tuple[float, ...]:
        """The coefficients of ``"polynomial"`` (set by :func:`make_function`)."""
        return cast(Tuple[float, ...], self.coeffs)

    def _nodes(self) -> Tuple[np.ndarray, np.ndarray]:
        """The points of ``"table"`` (set by :func:`table_function`)."""
        return cast(Tuple[np.ndarray, np.ndarray], self.nodes)

    def _table_value(self, x: np.ndarray, order: int) -> np.ndarray:
        xs, ys = self._nodes()
        if self.interpolation == "linear":
            if order == 0:
                return np.interp(x, xs, ys)
            slopes = np.diff(ys) / np.diff(xs)
            # the slope of the piece to the right of x (the last piece at the end)
            k = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(slopes) - 1)
            return slopes[k]
        spline = self._table
        return spline(x) if order == 0 else spline(x, 1)

    def check_domain(self, x0: float, xm: float) -> None:
        """Check that f is defined (and finite) on the closed interval [x0, xm].

        Parameters
        ----------
        x0, xm : float
            The interval's ends (in either order).

        Raises
        ------
        ValueError
            An end is not finite.
        DescribedError
            ``reason="domain"`` with values ``x0``, ``xm`` (the interval as
            given) and ``x`` (the first point of the interval outside the
            domain: 0, a pole, or the table's end): lg/ln of x <= 0, sqrt of
            x < 0, tan at a pole π/2 + kπ, 1/x at 0, x**p at x < 0 for a
            non-integer p or at 0 for p < 0, a table outside its points.
        """
        x0, xm = float(x0), float(xm)
        if not (math.isfinite(x0) and math.isfinite(xm)):
            raise ValueError(f"the interval's ends must be finite, got {x0!r} and {xm!r}")
        lo, hi = min(x0, xm), max(x0, xm)
        bad, why = None, ""
        name = self.name
        if name in ("log10", "ln") and lo <= 0.0:
            bad, why = lo, "its argument must be positive"
        elif name == "sqrt" and lo < 0.0:
            bad, why = lo, "its argument must not be negative"
        elif name == "reciprocal" and lo <= 0.0 <= hi:
            bad, why = 0.0, "it has a pole at 0"
        elif name == "tan":
            k = math.ceil((lo - 0.5 * math.pi) / math.pi)
            pole = 0.5 * math.pi + k * math.pi
            if pole <= hi:
                bad, why = pole, "it has a pole at π/2 + kπ"
        elif name == "power":
            p = cast(float, self.exponent)  # set for "power" (make_function)
            if p != int(p) and lo < 0.0:
                bad, why = lo, "a non-integer power of a negative number is not real"
            elif p < 0 and lo <= 0.0 <= hi:
                bad, why = 0.0, "a negative power has a pole at 0"
        elif name == "table":
            xs = self._nodes()[0]
            if lo < xs[0] or hi > xs[-1]:
                bad = lo if lo < xs[0] else hi
                why = "the interval leaves the table's points"
        if bad is None:
            # defined everywhere, but it may overflow (exp of 1000) or reach values no
            # swing can scale: the ends and a grid must give finite values
            grid = np.linspace(lo, hi, 1001)
            with np.errstate(all="ignore"):
                y = np.asarray(self(grid), dtype=float)
            big = ~np.isfinite(y) | (np.abs(y) > 1e150)
            if big.any():
                bad, why = float(grid[int(np.argmax(big))]), "its values overflow"
        if bad is not None:
            raise DescribedError(
                f"the function {FORMULAS[name]} is not defined on the whole interval: {why}",
                reason="domain", x0=x0, xm=xm, x=float(bad))


def make_function(name: str, *, exponent: Optional[float] = None, coeffs: Any = None) -> Function:
    """The named function ``name`` (one of :data:`NAMES`).

    Parameters
    ----------
    name : str
        ``"log10"`` (lg x, 【例 3-7】), ``"ln"``, ``"sqrt"`` (习题 3-13),
        ``"power"`` (x**exponent), ``"sin"``, ``"cos"``, ``"tan"``, ``"exp"``,
        ``"reciprocal"`` (1/x), ``"polynomial"`` (Σ coeffs[k] x**k).
    exponent : float
        The power p; only and always with ``"power"``.
    coeffs : sequence of float
        The polynomial's coefficients c0, c1, ... in ascending powers; only
        and always with ``"polynomial"``.

    Raises
    ------
    ValueError
        An unknown name, a parameter the function does not take or a missing
        one, a non-finite parameter.
    """
    if name not in NAMES:
        raise ValueError(f"unknown function {name!r}; known: {', '.join(NAMES)}")
    if name == "power":
        if exponent is None:
            raise ValueError("the function 'power' needs its exponent")
        exponent = float(exponent)
        if not math.isfinite(exponent):
            raise ValueError(f"the exponent must be finite, got {exponent!r}")
    elif exponent is not None:
        raise ValueError(f"the function {name!r} takes no exponent")
    if name == "polynomial":
        if coeffs is None:
            raise ValueError("the function 'polynomial' needs its coefficients")
        coeffs = tuple(float(c) for c in np.atleast_1d(np.asarray(coeffs, dtype=float)))
        if not coeffs or not all(math.isfinite(c) for c in coeffs):
            raise ValueError(f"the coefficients must be finite and at least one, got {coeffs!r}")
    elif coeffs is not None:
        raise ValueError(f"the function {name!r} takes no coefficients")
    return Function(name, exponent=exponent, coeffs=coeffs)


def table_function(x: Any, y: Any, *, interpolation: str = "cubic") -> Function:
    """A function given by a table of points (x_i, y_i).

    Parameters
    ----------
    x, y : sequence of float
        At least two points, ``x`` strictly increasing.
    interpolation : {"cubic", "linear"}
        ``"cubic"`` (default): the cubic spline with not-a-knot ends
        (``scipy.interpolate.CubicSpline``; with 3 points the parabola, with 2
        the line), C² so that the structural error of a function generator
        is smooth between the points, exact for cubics. ``"linear"``:
        straight pieces (the derivative is the slope of the piece to the
        right of x).

    Notes
    -----
    When a synthesis needs as many precision points as the table has, they
    are the table's own points (:func:`mechcli.core.synth.function.function_generator`).
    """
    xs = np.asarray(x, dtype=float).ravel()
    ys = np.asarray(y, dtype=float).ravel()
    if xs.shape != ys.shape or xs.size < 2:
        raise ValueError(f"a table needs as many x as y, at least 2, got {xs.size} and {ys.size}")
    if not (np.all(np.isfinite(xs)) and np.all(np.isfinite(ys))):
        raise ValueError("a table's points must be finite")
    if np.any(np.diff(xs) <= 0.0):
        raise ValueError("a table's x must be strictly increasing")
    if interpolation not in ("cubic", "linear"):
        raise ValueError(f"interpolation must be 'cubic' or 'linear', got {interpolation!r}")
    spline = None
    if interpolation == "cubic":
        from scipy.interpolate import CubicSpline
        spline = CubicSpline(xs, ys, bc_type="not-a-knot")
    xs.setflags(write=False)
    ys.setflags(write=False)
    return Function("table", nodes=(xs, ys), interpolation=interpolation, _table=spline)
