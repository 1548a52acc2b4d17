"""The equation of motion of the equivalent model, its speed fluctuation and the flywheel.

The machine is reduced to its input link (第二节): an equivalent moment of inertia
``Je(φ)`` with its derivative ``dJe/dφ`` (an *inertia model* of :mod:`.equivalent`: any
object with ``__call__(phi) -> (Je, dJe)``, ``period`` (2π or None), ``constant`` and
``plus(J)``; a plain number is taken as a constant inertia) under an equivalent moment
``Me(φ, ω)`` (:class:`MomentModel`).  Its motion obeys, in the book's three forms,

* the energy differential ``d(Je ω²/2) = Me dφ`` (eq 6-5),
* the moment form ``Je dω/dt + (ω²/2) dJe/dφ = Me`` (eq 6-8),
* the energy integral ``½Je ω² − ½Je0 ω0² = ∫Me dφ`` (eqs 6-10, 6-11, 6-12).

What this module solves:

* :func:`energy_solution` -- Me(φ) only: the exact energy integral (eq 6-12) and the time
  ``t = ∫dφ/ω`` (eq 6-14), 例 6-2;
* :func:`linear_closed_form` -- constant Je and ``Me = a − bω − Mr``: ω(t), φ(t) in closed
  form (eqs 6-16 … 6-20), 例 6-3 and 习题 6-3;
* :func:`integrate` -- the general ``Me(φ, ω)`` with ``Je(φ)`` (eq 6-21): scipy's RK45,
  DOP853 or Radau on the kinetic energy ``E = ½Je ω²`` (eq 6-5, regular where ω → 0), or the
  book's explicit fixed-step scheme (eqs 6-22, 6-23), 例 6-4;
* :func:`steady_state` -- the periodic motion of the stable-running stage, its extremes, the
  mean speeds (eqs 6-26, 6-27), the coefficient of fluctuation δ (eq 6-25) and the largest
  energy swing ΔWmax, 例 6-4 and 例 6-5;
* :func:`flywheel_approx` (eqs 6-29, 6-30) and :func:`flywheel_exact` (the flywheel whose
  steady state with the variable Je meets [δ]); :func:`rim`, :func:`disc`, :func:`width`
  size it.

SI units and radians throughout; no I/O.  A problem without solution raises
:class:`~mechcli.core.errors.DescribedError` with a ``reason`` and numbers:

* ``"stall"`` (``phi``): the machine stops (ω reaches 0) at the angle ``phi``;
* ``"unreachable"`` (``omega_inf``, ``omega_end``): the linear model never reaches
  ``omega_end``;
* ``"no_steady_state"`` (``net_work`` or ``omega0``): no periodic motion;
* ``"no_flywheel_needed"`` (``J_total``, ``Je`` or ``delta``): the machine already meets [δ].

A root finder or the book's repeated period that does not converge raises
:class:`~mechcli.core.errors.ConvergenceError`.
"""

from __future__ import annotations

import bisect
import dataclasses
import math
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Tuple, Type, Union

import numpy as np

from mechcli.core.errors import ConvergenceError, DescribedError
from mechcli.core.numerics import gauss_legendre
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.flywheel.equivalent import InertiaModel
    from mechcli.core.types import FloatOrArray, IntArray

TWO_PI = 2.0 * math.pi

#: integration methods of :func:`integrate`: scipy's solve_ivp names and the book's scheme
METHODS = ("RK45", "DOP853", "Radau", "book")

#: period-map root finders of :func:`steady_state`
ROOTS = ("shooting", "repeat")

#: relative tolerance of "the same angle" (a closed table, contiguous segments)
_ANGLE_RTOL = 1e-9

#: Gauss–Legendre nodes per solver step for t = ∫dφ/ω and the integral mean of ω
_GL_NODES = 8


# --------------------------------------------------------------------------- models


class _ConstantInertia:
    """A constant Je for callers that pass a plain number (same interface as .equivalent)."""

    period = None
    constant = True

    def __init__(self, J: float) -> None:
        self.value = float(J)
        if not self.value > 0:
            raise ValueError("the moment of inertia must be positive")

    def __call__(self, phi: FloatOrArray) -> Any:
        phi = np.asarray(phi, dtype=float)
        return np.full_like(phi, self.value), np.zeros_like(phi)

    def plus(self, J: float) -> _ConstantInertia:
        return _ConstantInertia(self.value + J)


if TYPE_CHECKING:
    #: what the solvers take as Je(φ): a model of :mod:`.equivalent` or a plain number's
    Inertia = Union[InertiaModel, _ConstantInertia]


def _as_inertia(inertia: Union[Inertia, float, np.floating, np.integer]) -> Inertia:
    if isinstance(inertia, (int, float, np.floating, np.integer)):
        return _ConstantInertia(float(inertia))
    return inertia


def _breaks_of(model: Any) -> Optional[Tuple[np.ndarray, float, np.ndarray, float]]:
    """``(periodic_knots, period_base, aperiodic_knots[, period])`` where a model may have
    a kink (the period 2π when the tuple has no fourth item).

    A :class:`MomentModel` declares them; a table inertia (``.phi`` nodes over one turn,
    spline or linear) has them at its nodes; other models have none.
    """
    breaks = getattr(model, "breaks", None)
    if breaks is not None:
        return breaks
    nodes = getattr(model, "phi", None)
    if getattr(model, "period", None) and nodes is not None \
            and getattr(model, "method", "") in ("cubic", "linear"):
        nodes = np.asarray(nodes, dtype=float)
        return nodes, float(nodes[0]), np.empty(0), float(model.period)
    return None


class _Piecewise:
    """Piecewise-linear ``M(φ)`` on segments (jumps allowed), optionally periodic.

    ``starts``, ``ends``, ``m0``, ``m1``: the segments, sorted and not overlapping; zero
    outside them.  Periodic: the segments cover ``[starts[0], starts[0] + period]``
    (``period`` [rad], 2π by default: 4π for a four-stroke engine's cycle).
    """

    def __init__(self, starts: np.ndarray, ends: np.ndarray, m0: np.ndarray, m1: np.ndarray,
                 periodic: bool, period: float = TWO_PI) -> None:
        self.period = float(period)
        self.starts, self.ends = np.asarray(starts, float), np.asarray(ends, float)
        self.m0, self.m1 = np.asarray(m0, float), np.asarray(m1, float)
        self.periodic = periodic
        self.base = float(self.starts[0])
        self.slope = (self.m1 - self.m0) / (self.ends - self.starts)
        # ∫ over each whole segment, and their running sum before each segment
        whole = 0.5 * (self.m0 + self.m1) * (self.ends - self.starts)
        self.before = np.concatenate(([0.0], np.cumsum(whole)))
        self.knots = np.unique(np.concatenate((self.starts, self.ends)))
        self._starts, self._ends = self.starts.tolist(), self.ends.tolist()
        self._m0, self._slopes = self.m0.tolist(), self.slope.tolist()

    def scalar(self, p: float) -> float:
        """``M(p)`` for one float angle (the integrators' fast path)."""
        x = self.base + (p - self.base) % self.period if self.periodic else p
        starts = self._starts
        i = bisect.bisect_right(starts, x) - 1
        if i < 0:
            return 0.0
        if x < self._ends[i] or (self.periodic and i == len(starts) - 1):
            return self._m0[i] + self._slopes[i] * (x - starts[i])
        return 0.0

    def _reduce(self, phi: FloatOrArray) -> Any:
        phi = np.asarray(phi, dtype=float)
        if not self.periodic:
            return phi, np.zeros_like(phi)
        T = self.period
        turns = np.floor((phi - self.base) / T)
        x = phi - T * turns
        # rounding may put x a hair beyond the period end: it belongs to the next turn
        over = x >= self.base + T
        return np.where(over, x - T, x), turns + over

    def _index(self, x: FloatOrArray) -> IntArray:
        return np.clip(np.searchsorted(self.starts, x, side="right") - 1, 0, len(self.starts) - 1)

    def __call__(self, phi: FloatOrArray) -> Any:
        x, _ = self._reduce(phi)
        i = self._index(x)
        d = x - self.starts[i]
        inside = (d >= 0) & (x < self.ends[i])
        if self.periodic:  # the period end closes the last segment
            inside |= x == self.ends[-1]
        return np.where(inside, self.m0[i] + self.slope[i] * d, 0.0)

    def primitive(self, phi: np.ndarray) -> FloatOrArray:
        """``∫_{base}^{φ} M dφ``, exact (periodic: whole turns times the work per turn)."""
        x, turns = self._reduce(phi)
        i = self._index(x)
        d = np.clip(x - self.starts[i], 0.0, self.ends[i] - self.starts[i])
        partial = d * (self.m0[i] + 0.5 * self.slope[i] * d)
        return turns * self.before[-1] + np.where(x >= self.starts[0],
                                                   self.before[i] + partial, 0.0)


class _PeriodicCubic:
    """A periodic cubic spline through a closed table, with its exact primitive."""

    def __init__(self, xp: np.ndarray, fp: np.ndarray, period: float = TWO_PI) -> None:
        from scipy.interpolate import CubicSpline

        self.period = float(period)
        self.base = float(xp[0])
        self.spline = CubicSpline(xp, fp, bc_type="periodic")
        self.anti = self.spline.antiderivative()
        self.per_turn = float(self.anti(self.base + self.period) - self.anti(self.base))
        self.knots = np.asarray(xp, dtype=float)
        self.periodic = True

    def scalar(self, p: float) -> float:
        """``M(p)`` for one float angle."""
        return float(self.spline(self.base + (p - self.base) % self.period))

    def _reduce(self, phi: FloatOrArray) -> Any:
        phi = np.asarray(phi, dtype=float)
        turns = np.floor((phi - self.base) / self.period)
        return phi - self.period * turns, turns

    def __call__(self, phi: FloatOrArray) -> Any:
        x, _ = self._reduce(phi)
        return self.spline(x)

    def primitive(self, phi: np.ndarray) -> FloatOrArray:
        x, turns = self._reduce(phi)
        return turns * self.per_turn + self.anti(x) - self.anti(self.base)


class _PeriodicQuadratic(_PeriodicCubic):
    """Simpson's rule as a model: over each pair of intervals of a closed table the
    parabola through its three nodes (eq. of the composite Simpson rule: the primitive at
    every even node is the Simpson sum, on equal or unequal steps).  The number of
    intervals must be even."""

    def __init__(self, xp: np.ndarray, fp: np.ndarray, period: float = TWO_PI) -> None:
        xp, fp = np.asarray(xp, dtype=float), np.asarray(fp, dtype=float)
        n = xp.size - 1
        if n % 2:
            raise ValueError("Simpson's rule needs an even number of intervals per period")
        self.period, self.base, self.periodic = float(period), float(xp[0]), True
        x0, x1, x2 = xp[0:-1:2], xp[1::2], xp[2::2]
        f0, f1, f2 = fp[0:-1:2], fp[1::2], fp[2::2]
        h1, h2 = x1 - x0, x2 - x0
        # M = f0 + c1 d + c2 d² in d = φ − x0 through (x1, f1) and (x2, f2)
        s1, s2 = (f1 - f0) / h1, (f2 - f0) / h2
        self.c2 = (s2 - s1) / (h2 - h1)
        self.c1 = s1 - self.c2 * h1
        self.c0, self.starts, self.width = f0, x0, h2
        whole = h2 * (f0 + h2 * (0.5 * self.c1 + self.c2 * h2 / 3.0))
        self.before = np.concatenate(([0.0], np.cumsum(whole)))
        self.per_turn = float(self.before[-1])
        self.knots = np.append(x0, xp[-1])
        self._lists = (x0.tolist(), self.c0.tolist(), self.c1.tolist(), self.c2.tolist())

    def _index(self, x: FloatOrArray) -> IntArray:
        return np.clip(np.searchsorted(self.starts, x, side="right") - 1, 0,
                       self.starts.size - 1)

    def scalar(self, p: float) -> float:
        x = self.base + (p - self.base) % self.period
        starts, c0, c1, c2 = self._lists
        i = min(max(bisect.bisect_right(starts, x) - 1, 0), len(starts) - 1)
        d = x - starts[i]
        return c0[i] + d * (c1[i] + c2[i] * d)

    def __call__(self, phi: FloatOrArray) -> Any:
        x, _ = self._reduce(phi)
        i = self._index(x)
        d = x - self.starts[i]
        return self.c0[i] + d * (self.c1[i] + self.c2[i] * d)

    def primitive(self, phi: np.ndarray) -> FloatOrArray:
        x, turns = self._reduce(phi)
        i = self._index(x)
        d = np.clip(x - self.starts[i], 0.0, self.width[i])
        part = d * (self.c0[i] + d * (0.5 * self.c1[i] + self.c2[i] * d / 3.0))
        return turns * self.per_turn + self.before[i] + part


def _closed_table(phi: Any, M: Any, period: float = TWO_PI) -> Tuple[np.ndarray, np.ndarray]:
    """The nodes of a periodic table closed at ``phi[0] + period`` (the wrap node
    appended)."""
    phi = np.asarray(phi, dtype=float).ravel()
    M = np.asarray(M, dtype=float).ravel()
    if phi.size != M.size or phi.size < 2:
        raise ValueError("a moment table needs as many moments as angles, at least two")
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(M))):
        raise ValueError("a moment table must be finite")
    if np.any(np.diff(phi) <= 0):
        raise ValueError("the angles of a moment table must increase")
    span = phi[-1] - phi[0]
    T = float(period)
    close = abs(span - T) <= _ANGLE_RTOL * T
    if span > T and not close:
        raise ValueError("a periodic moment table spans at most one period")
    if close:
        if abs(M[-1] - M[0]) > _ANGLE_RTOL * max(1.0, np.max(np.abs(M))):
            raise ValueError("a periodic moment table must end with the moment it starts with")
        phi = phi.copy()
        phi[-1] = phi[0] + T
        return phi, M
    return np.append(phi, phi[0] + T), np.append(M, M[0])


class MomentModel:
    """The equivalent moment ``Me(φ, ω)`` on the input link (eq 6-2), a sum of terms.

    ``Me(φ, ω) = constant + table(φ) + (a − b ω) + a0 + Σ_k (a_k sin kνφ + b_k cos kνφ)
    + segments(φ)`` with ν = 2π/``period`` (1 for one turn).

    Parameters
    ----------
    table : tuple, optional
        ``(phi, M)`` or ``(phi, M, method)``: a periodic table [rad, N·m] over at most one
        period (a closing node at ``phi[0] + period`` may repeat the first moment; otherwise
        it is added), interpolated by ``method`` ``"linear"`` (default; exact
        piecewise-linear work: the trapezoid rule), ``"cubic"`` (periodic cubic spline) or
        ``"quadratic"`` (a parabola over each pair of intervals: Simpson's rule; an even
        number of intervals).
    linear : (float, float), optional
        ``(a, b)``: the motor characteristic ``a − b ω`` [N·m, N·m·s] (例 6-3, 例 6-4).
    harmonic : tuple, optional
        ``(a0, (a1, a2, ...), (b1, b2, ...))``: ``a0 + Σ a_k sin kνφ + b_k cos kνφ`` [N·m].
    segments : sequence of (float, float, float, float), optional
        ``(phi_from, phi_to, M_from, M_to)``: linear pieces [rad, N·m], zero outside; they
        may not overlap.  Periodic only when they join end to end over exactly one period.
    constant : float, optional
        A constant moment [N·m] (a constant drive, or minus a constant resistance).
    period : float, optional
        The period of every periodic term [rad]: 2π (one turn, the default), 4π for the
        cycle of a four-stroke engine.

    Attributes
    ----------
    depends_on_omega, depends_on_phi : bool
    period : float or None
        ``period`` when a periodic term varies with φ and no aperiodic segment spoils it,
        else None.
    breaks : (ndarray, float, ndarray, float)
        ``(periodic knots, their base angle, aperiodic knots, period)``: the angles where
        ``Me`` or its slope may jump (table nodes, segment ends), for the integrators to
        stop at.
    """

    def __init__(self, *, table: Any = None, linear: Optional[Tuple[float, float]] = None,
                 harmonic: Any = None,
                 segments: Optional[List[Tuple[float, float, float, float]]] = None,
                 constant: float = 0.0, period: float = TWO_PI) -> None:
        T = float(period)
        if not (math.isfinite(T) and T > 0):
            raise ValueError("the period must be positive")
        nu = TWO_PI / T
        self.constant = float(constant)
        if not math.isfinite(self.constant):
            raise ValueError("the constant moment must be finite")
        self.a, self.b = (0.0, 0.0) if linear is None else (float(linear[0]), float(linear[1]))
        if not (math.isfinite(self.a) and math.isfinite(self.b)):
            raise ValueError("the linear moment must be finite")
        self._table: Optional[Union[_Piecewise, _PeriodicCubic]] = None
        if table is not None:
            method = table[2] if len(table) > 2 else "linear"
            xp, fp = _closed_table(table[0], table[1], T)
            if method == "linear":
                self._table = _Piecewise(xp[:-1], xp[1:], fp[:-1], fp[1:], periodic=True,
                                         period=T)
            elif method == "cubic":
                self._table = _PeriodicCubic(xp, fp, T)
            elif method == "quadratic":
                self._table = _PeriodicQuadratic(xp, fp, T)
            else:
                raise ValueError(f"unknown table interpolation {method!r}")
        self._harm = None
        if harmonic is not None:
            a0, ak, bk = harmonic
            ak = np.asarray(ak, dtype=float).ravel()
            bk = np.asarray(bk, dtype=float).ravel()
            n = max(ak.size, bk.size)
            ak, bk = np.pad(ak, (0, n - ak.size)), np.pad(bk, (0, n - bk.size))
            if not (math.isfinite(float(a0)) and np.all(np.isfinite(ak))
                    and np.all(np.isfinite(bk))):
                raise ValueError("the harmonic coefficients must be finite")
            # the angular "frequencies" k ν of the harmonics [1/rad]
            self._harm = (float(a0), ak, bk, nu * np.arange(1, n + 1, dtype=float))
            self._harm_lists = (ak.tolist(), bk.tolist(), self._harm[3].tolist())
        self._seg = None
        if segments:
            seg = np.asarray(segments, dtype=float).reshape(-1, 4)
            if not np.all(np.isfinite(seg)):
                raise ValueError("the moment segments must be finite")
            seg = seg[np.argsort(seg[:, 0])]
            if np.any(seg[:, 1] <= seg[:, 0]):
                raise ValueError("every moment segment must end after it starts")
            gaps = seg[1:, 0] - seg[:-1, 1]
            tol = _ANGLE_RTOL * T
            if np.any(gaps < -tol):
                raise ValueError("moment segments may not overlap")
            periodic = bool(np.all(np.abs(gaps) <= tol)
                            and abs(seg[-1, 1] - seg[0, 0] - T) <= tol)
            if periodic:
                seg[1:, 0] = seg[:-1, 1]
                seg[-1, 1] = seg[0, 0] + T
            self._seg = _Piecewise(seg[:, 0], seg[:, 1], seg[:, 2], seg[:, 3], periodic,
                                   period=T)
        harm_varies = self._harm is not None and bool(np.any(self._harm[1]) or
                                                      np.any(self._harm[2]))
        periodic_varies = self._table is not None or harm_varies or (
            self._seg is not None and self._seg.periodic)
        aperiodic = self._seg is not None and not self._seg.periodic
        self.depends_on_omega = self.b != 0.0
        self.depends_on_phi = periodic_varies or aperiodic
        self.period = T if periodic_varies and not aperiodic else None
        periodic_knots: List[np.ndarray] = []
        base = 0.0
        for part in (self._table, self._seg):
            if part is not None and part.periodic:
                base = part.base
                periodic_knots.append(part.knots)
        if periodic_knots:
            k = np.concatenate(periodic_knots)
            k = base + np.mod(k - base, T)
            knots = np.unique(k)
        else:
            knots = np.empty(0)
        aper = self._seg.knots if aperiodic and self._seg is not None else np.empty(0)
        self.breaks = (knots, base, aper, T)

    def scalar(self, p: float, w: float) -> float:
        """``Me(p, w)`` for one float angle and speed (the integrators' fast path)."""
        m = self.constant + self.a - self.b * w
        if self._table is not None:
            m += self._table.scalar(p)
        if self._harm is not None:
            a0, ak, bk, k = self._harm
            m += a0 + sum(a * math.sin(j * p) + b * math.cos(j * p)
                          for a, b, j in zip(self._harm_lists[0], self._harm_lists[1],
                                             self._harm_lists[2]))
        if self._seg is not None:
            m += self._seg.scalar(p)
        return m

    @property
    def omega_coefficient(self) -> float:
        """``∂Me/∂ω = −b`` [N·m·s] (the model is linear in ω)."""
        return -self.b

    def phi_part(self, phi: FloatOrArray) -> FloatOrArray:
        """The part of ``Me`` that depends on φ only (every term but ``−bω``) [N·m]."""
        phi = np.asarray(phi, dtype=float)
        m = np.full_like(phi, self.constant + self.a)
        if self._table is not None:
            m = m + self._table(phi)
        if self._harm is not None:
            a0, ak, bk, k = self._harm
            kp = np.multiply.outer(phi, k)
            m = m + a0 + np.sin(kp) @ ak + np.cos(kp) @ bk
        if self._seg is not None:
            m = m + self._seg(phi)
        return m

    def __call__(self, phi: FloatOrArray, omega: FloatOrArray) -> FloatOrArray:
        """``Me(φ, ω)`` [N·m]; φ [rad] and ω [rad/s] broadcast together."""
        return self.phi_part(phi) - self.b * np.asarray(omega, dtype=float)

    def _primitive(self, phi: FloatOrArray) -> FloatOrArray:
        phi = np.asarray(phi, dtype=float)
        f = (self.constant + self.a) * phi
        if self._table is not None:
            f = f + self._table.primitive(phi)
        if self._harm is not None:
            a0, ak, bk, k = self._harm
            kp = np.multiply.outer(phi, k)
            f = f + a0 * phi + (-np.cos(kp)) @ (ak / k) + np.sin(kp) @ (bk / k)
        if self._seg is not None:
            f = f + self._seg.primitive(phi)
        return f

    def energy(self, phi0: float, phi: FloatOrArray) -> FloatOrArray:
        """The work ``W(φ) = ∫_{φ0}^{φ} Me dφ`` of the φ-only part, exactly (eq 6-12) [J].

        The term ``−bω`` depends on the motion and is left out; ``a`` is kept.
        """
        return self._primitive(phi) - self._primitive(phi0)

    def breaks_between(self, lo: float, hi: float) -> np.ndarray:
        """The break angles of :attr:`breaks` strictly inside ``(lo, hi)``, increasing."""
        return _breaks_in(self.breaks, lo, hi)


def _breaks_in(breaks: Optional[Tuple[np.ndarray, float, np.ndarray, float]], lo: float, hi: float
              ) -> np.ndarray:
    if breaks is None:
        return np.empty(0)
    knots, base, aper = breaks[:3]
    T = float(breaks[3]) if len(breaks) > 3 else TWO_PI
    out = [np.asarray(aper, dtype=float)]
    knots = np.asarray(knots, dtype=float)
    if knots.size:
        n0 = math.floor((lo - base) / T)
        n1 = math.floor((hi - base) / T)
        turns = np.arange(n0, n1 + 1)
        out.append((base + T * turns[:, None] + knots[None, :]).ravel())
    allk = np.unique(np.concatenate(out))
    tol = _ANGLE_RTOL * max(1.0, abs(lo), abs(hi))
    return allk[(allk > lo + tol) & (allk < hi - tol)]


def _all_breaks(inertia: Inertia, moment: MomentModel, lo: float, hi: float) -> np.ndarray:
    out = [_breaks_in(_breaks_of(moment), lo, hi), _breaks_in(_breaks_of(inertia), lo, hi)]
    return np.unique(np.concatenate(out))


# --------------------------------------------------------------------------- results


@record(eq=False)
class Motion:
    """The motion of the equivalent link on an output grid.

    Attributes
    ----------
    phi, t, omega, alpha : ndarray
        Angle [rad], time [s] (0 at the first angle, eq 6-14), speed [rad/s] and angular
        acceleration [rad/s²] (eq 6-8: ``α = (Me − ½ dJe ω²)/Je``).
    Je, dJe, Me : ndarray
        The equivalent inertia [kg·m²], its slope [kg·m²/rad] and the equivalent moment
        [N·m] at those angles (and speeds).
    method : str
        ``"RK45"``, ``"DOP853"``, ``"Radau"``, ``"book"``, ``"energy"`` (the exact energy
        integral) or ``"closed_form"``.
    nfev : int
        Evaluations of the right-hand side (0 for the closed forms).
    rtol, atol : float or None
        The integrator's tolerances (None when not used).
    step : float or None
        The fixed step of the book's scheme [rad] (None otherwise).
    """

    phi: np.ndarray
    t: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    Je: np.ndarray
    dJe: np.ndarray
    Me: np.ndarray
    method: str
    nfev: int = 0
    rtol: float | None = None
    atol: float | None = None
    step: float | None = None

    @property
    def energy(self) -> np.ndarray:
        """The kinetic energy ``½Je ω²`` [J] (eq 6-5)."""
        return 0.5 * self.Je * self.omega ** 2


@record(eq=False)
class SteadyState:
    """The periodic motion of the stable-running stage (第一节 二.2, 第四节).

    Attributes
    ----------
    motion : Motion
        One period, from ``φ0`` to ``φ0 + 2π``.
    omega0 : float
        The periodic speed at ``φ0`` [rad/s].
    omega_max, omega_min : float
        The extremes of ω over the period [rad/s] (refined between grid points for the
        scipy methods; the grid's for the book's scheme), at ``phi_at_max``,
        ``phi_at_min`` [rad].
    omega_mean : float
        The integral mean ``(1/φT) ∫ω dφ`` (eq 6-26) [rad/s].
    omega_avg : float
        ``(ωmax + ωmin)/2`` (eq 6-27) [rad/s].
    delta : float
        ``(ωmax − ωmin)/ω_mean`` (eq 6-25 with the mean of eq 6-26).
    delta_avg : float
        ``(ωmax − ωmin)/ω_avg`` (eq 6-25 with the mean of eq 6-27, the book's practice).
    dW_max : float
        The largest energy swing ``E_max − E_min`` [J] of the cumulative work
        ``∫Me(φ, ω(φ)) dφ`` over the period (eq 6-29).
    iterations : int
        Period-map evaluations of the root finder, or periods of the repeated loop.
    residual : float
        The periodicity residual ``|ω(φ0 + 2π) − ω0|`` [rad/s] of the final motion.
    root : str
        ``"shooting"``, ``"repeat"`` or ``"mean"`` (Me(φ) only: ω0 chosen for the mean).
    nfev : int
        Right-hand-side evaluations of all the periods integrated.
    history : tuple of (float, float or None)
        Every speed the period map was evaluated at and the speed one period later
        (None: the start stalls), in order: the convergence of the search.
    """

    motion: Motion
    omega0: float
    omega_max: float
    omega_min: float
    phi_at_max: float
    phi_at_min: float
    omega_mean: float
    omega_avg: float
    delta: float
    delta_avg: float
    dW_max: float
    iterations: int
    residual: float
    root: str
    nfev: int = 0
    history: tuple = ()


# --------------------------------------------------------------------------- energy integral


def _grid(phi0: float, phi_end: float, points: Optional[int]) -> np.ndarray:
    if points is None:
        points = max(2, int(math.ceil((phi_end - phi0) / math.radians(1.0) - 1e-9)) + 1)
    if points < 2:
        raise ValueError("an output grid needs at least two points")
    return np.linspace(phi0, phi_end, int(points))


def _time(omega_at: Callable[..., Any], breaks: np.ndarray, n: int = _GL_NODES) -> np.ndarray:
    """``t = ∫dφ/ω`` (eq 6-14) from ``breaks[0]`` to every break, Gauss–Legendre per interval.

    A start from rest (ω = 0 at ``φ0 = breaks[0]``, where ``ω ∝ sqrt(φ − φ0)``) is
    integrated in ``s = sqrt(φ − φ0)``: ``t = ∫ 2s ds / ω(φ0 + s²)``, a regular integrand.
    """
    a = float(breaks[0])
    if float(omega_at(breaks[:1])[0]) == 0.0:
        s, w = gauss_legendre(np.sqrt(breaks - a), n)
        parts = (w * 2.0 * s / omega_at(a + s * s)).reshape(-1, n).sum(axis=1)
    else:
        x, w = gauss_legendre(breaks, n)
        parts = (w / omega_at(x)).reshape(-1, n).sum(axis=1)
    return np.concatenate(([0.0], np.cumsum(parts)))


def _stall_angle(g: Callable[..., Any], lo: float, hi: float) -> float:
    """The first root of the falling ``g`` in ``[lo, hi]`` (g(lo) > 0 >= g(hi))."""
    from scipy.optimize import brentq

    if g(lo) <= 0:
        return float(lo)
    return float(brentq(g, lo, hi, xtol=1e-13 * max(1.0, abs(hi)), rtol=4 * np.finfo(float).eps))


def _check_energy_stall(inertia: Inertia, moment: MomentModel, phi0: float, E0: float,
                        phi_end: float, fine: np.ndarray) -> None:
    """Raise ``"stall"`` where ``E0 + W(φ)`` first reaches 0 on ``[phi0, phi_end]``."""
    from scipy.optimize import minimize_scalar

    def g(p: float) -> float:
        return E0 + float(moment.energy(phi0, p))

    e = E0 + moment.energy(phi0, fine)
    assert isinstance(e, np.ndarray)  # fine is an array
    if E0 <= 0 and float(moment.phi_part(phi0)) <= 0:
        raise DescribedError("the machine does not start", reason="stall", phi=float(phi0))
    bad = np.flatnonzero(e[1:] <= 0)
    first = bad[0] + 1 if bad.size else None
    # a dip between samples: refine every sampled local minimum before the first bad sample
    stop = first if first is not None else e.size - 1
    for i in np.flatnonzero((e[1:stop] <= e[:stop - 1]) & (e[1:stop] <= e[2:stop + 1])) + 1:
        r = minimize_scalar(g, bounds=(fine[i - 1], fine[i + 1]), method="bounded",
                            options={"xatol": 1e-12 * max(1.0, abs(fine[i]))})
        if r.fun <= 0:
            raise DescribedError("the machine stops", reason="stall",
                                 phi=_stall_angle(g, fine[i - 1], float(r.x)))
    if first is not None:
        raise DescribedError("the machine stops", reason="stall",
                             phi=_stall_angle(g, fine[first - 1], fine[first]))


def energy_solution(inertia: Union[Inertia, float], moment: MomentModel, phi0: float,
                    omega0: float, phi: Any) -> Motion:
    """The exact motion under a moment of φ alone by the energy integral (eqs 6-11, 6-12).

    ``ω(φ) = sqrt((Je0 ω0² + 2W(φ)) / Je(φ))`` with ``W = ∫_{φ0}^{φ} Me dφ`` exact
    (:meth:`MomentModel.energy`); ``t = ∫dφ/ω`` (eq 6-14) by 8-point Gauss–Legendre between
    the grid points, the moment's break angles and at most 2π/64 apart; ``α`` by eq 6-8.

    Parameters
    ----------
    inertia : inertia model or float
        ``Je(φ)`` [kg·m²].
    moment : MomentModel
        Must not depend on ω.
    phi0 : float
        Initial angle [rad].
    omega0 : float
        Speed at ``phi0`` [rad/s], ``>= 0``.
    phi : array_like
        Output angles [rad], increasing, from ``phi0`` on.

    Returns
    -------
    Motion
        ``method="energy"``.

    Raises
    ------
    DescribedError
        ``reason="stall"`` with ``phi`` [rad]: ``Je0 ω0² + 2W`` reaches 0 (the machine
        stops) at ``phi``.
    """
    inertia = _as_inertia(inertia)
    if moment.depends_on_omega:
        raise ValueError("the energy integral needs a moment of φ alone")
    phi = np.asarray(phi, dtype=float).ravel()
    phi0, omega0 = float(phi0), float(omega0)
    if phi.size < 1 or np.any(np.diff(phi) <= 0) or phi[0] < phi0:
        raise ValueError("the output angles must increase from the initial angle on")
    if omega0 < 0:
        raise ValueError("the initial speed must not be negative")
    E0 = 0.5 * float(inertia(phi0)[0]) * omega0 ** 2
    lo, hi = phi0, float(phi[-1])
    n = max(1, int(math.ceil((hi - lo) / (TWO_PI / 64))))
    breaks = np.unique(np.concatenate(([lo], phi, np.linspace(lo, hi, n + 1),
                                       _all_breaks(inertia, moment, lo, hi))))
    breaks = breaks[(breaks >= lo) & (breaks <= hi)]
    fine = np.unique(np.concatenate((breaks, np.linspace(lo, hi, 16 * n + 1))))
    if hi > lo:
        _check_energy_stall(inertia, moment, phi0, E0, hi, fine)

    def omega_at(p: np.ndarray) -> np.ndarray:
        Je = inertia(p)[0]
        return np.sqrt(np.maximum(2.0 * (E0 + moment.energy(phi0, p)) / Je, 0.0))

    if hi > lo:
        t_b = _time(omega_at, breaks)
        t = t_b[np.searchsorted(breaks, phi)]  # phi is a subset of the breaks
    else:
        t = np.zeros_like(phi)
    Je, dJe = inertia(phi)
    omega = omega_at(phi)
    Me = moment(phi, omega)
    assert isinstance(Me, np.ndarray)  # phi is an array
    alpha = (Me - 0.5 * dJe * omega ** 2) / Je
    return Motion(phi=phi, t=t, omega=omega, alpha=alpha, Je=np.asarray(Je, float),
                  dJe=np.asarray(dJe, float), Me=Me, method="energy")


# --------------------------------------------------------------------------- closed form


def linear_closed_form(J: float, a: float, b: float, Mr: float, omega0: float, *,
                       omega_end: Optional[float] = None, t: Any = None, points: int = 201
                      ) -> Motion:
    """The closed-form motion of ``J dω/dt = a − bω − Mr`` (eqs 6-16 … 6-20; 例 6-3).

    With ``ω∞ = (a − Mr)/b``:

    * ``ω(t) = ω∞ + (ω0 − ω∞) e^{−bt/J}``,
    * ``φ(t) = ω∞ t + (ω0 − ω∞)(J/b)(1 − e^{−bt/J})``,
    * ``α(t) = −(b/J)(ω0 − ω∞) e^{−bt/J}``,
    * ``t(ω) = (J/b) ln((ω0 − ω∞)/(ω − ω∞))`` (eq 6-19 with the sign of b as here);

    and for ``b = 0`` the uniformly accelerated ``ω = ω0 + (a − Mr) t/J``.  The model holds
    for every t as written (ω may pass through 0; Mr keeps its sign).

    Parameters
    ----------
    J : float
        Constant equivalent inertia [kg·m²], > 0.
    a, b : float
        The drive ``a − bω`` [N·m, N·m·s].
    Mr : float
        The constant resisting moment [N·m].
    omega0 : float
        Speed at t = 0 (φ = 0) [rad/s].
    omega_end : float, optional
        Run until this speed: the grid is ``points`` times from 0 to its time.
    t : array_like, optional
        Output times [s] (overrides ``omega_end``'s grid).  Without both, five time
        constants ``5J/b`` (b > 0).
    points : int, optional
        Grid size for ``omega_end`` or the default span.

    Returns
    -------
    Motion
        ``method="closed_form"``, constant ``Je``.

    Raises
    ------
    DescribedError
        ``reason="unreachable"`` with ``omega_inf`` (``ω∞``, ±inf for b = 0) and
        ``omega_end``: the speed is never reached (for b > 0 it is not strictly between
        ω0 and ω∞; for b < 0 it is not beyond ω0 away from ω∞; for b = 0 it lies against
        the acceleration).
    """
    J, a, b, Mr, omega0 = (float(v) for v in (J, a, b, Mr, omega0))
    if not J > 0:
        raise ValueError("the moment of inertia must be positive")
    c = a - Mr
    w_inf = c / b if b != 0 else (math.copysign(math.inf, c) if c != 0 else omega0)
    if t is None and omega_end is not None:
        we = float(omega_end)
        if b != 0:
            ratio = (omega0 - w_inf) / (we - w_inf) if we != w_inf else -1.0
            ok = ratio > 0 and (ratio > 1 if b > 0 else ratio < 1) and we != omega0
            t_end = J / b * math.log(ratio) if ok else math.nan
        else:
            ok = c != 0 and (we - omega0) / c > 0
            t_end = J * (we - omega0) / c if ok else math.nan
        if not ok:
            raise DescribedError("the speed is never reached", reason="unreachable",
                                 omega_inf=w_inf, omega_end=we)
        t = np.linspace(0.0, t_end, int(points))
    elif t is None:
        if not b > 0:
            raise ValueError("give the times or the final speed")
        t = np.linspace(0.0, 5.0 * J / b, int(points))
    t = np.asarray(t, dtype=float).ravel()
    if b != 0:
        decay = np.exp(-b * t / J)
        omega = w_inf + (omega0 - w_inf) * decay
        phi = w_inf * t + (omega0 - w_inf) * (J / b) * -np.expm1(-b * t / J)
        alpha = -(b / J) * (omega0 - w_inf) * decay
    else:
        omega = omega0 + c * t / J
        phi = omega0 * t + 0.5 * c * t ** 2 / J
        alpha = np.full_like(t, c / J)
    Me = a - b * omega - Mr
    return Motion(phi=phi, t=t, omega=omega, alpha=alpha, Je=np.full_like(t, J),
                  dJe=np.zeros_like(t), Me=Me, method="closed_form")


# --------------------------------------------------------------------------- integration


class _Run:
    """One integration: every solver step's interval and dense output of E."""

    def __init__(self, los: List[float], his: List[float], dense: List[Any], nfev: int,
                 E_end: float) -> None:
        self.los, self.his = np.asarray(los), np.asarray(his)
        self.dense = dense            # one callable per step
        self.steps = np.concatenate((self.los[:1], self.his))  # step boundaries, increasing
        self.nfev = nfev
        self.E_end = E_end

    def E(self, phi: np.ndarray) -> np.ndarray:
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        out = np.empty_like(phi)
        k = np.minimum(np.searchsorted(self.his, phi, side="left"), len(self.dense) - 1)
        order = np.argsort(k, kind="stable")
        ks = k[order]
        cuts = np.flatnonzero(np.diff(ks)) + 1
        for idx in np.split(order, cuts):
            out[idx] = self.dense[k[idx[0]]](phi[idx])[0]
        return out


#: scipy's explicit and implicit integrators by name
def _solver_class(method: str) -> Any:
    from scipy.integrate import DOP853, RK45, Radau

    return {"RK45": RK45, "DOP853": DOP853, "Radau": Radau}[method]


#: steps of one integration at most (each keeps a dense output of ~1 kB): a stiff equation
#: under an explicit method would otherwise run for hours and take gigabytes
MAX_STEPS = 200_000


def _ode(inertia: Inertia, moment: MomentModel,
         phi0: float, omega0: float, phi_end: float, method: str, rtol: float, atol: float) -> _Run:
    """Integrate ``dE/dφ = Me(φ, ω)``, ``ω = sqrt(2E/Je)`` (eq 6-5) piece by piece.

    scipy's solver objects are stepped here (not ``solve_ivp``) so that a stall is found on
    the dense output of the step where E turns ≤ 0, robust to the rounding at the step end.
    Past E = 0 the right-hand side stays finite (ω is clipped to 0), so the step is valid.
    """
    from scipy.optimize import brentq

    E0 = 0.5 * float(inertia(phi0)[0]) * omega0 ** 2
    if E0 <= 0 and float(moment(phi0, 0.0)) <= 0:
        raise DescribedError("the machine does not start", reason="stall", phi=float(phi0))

    scalar = getattr(moment, "scalar", None) or (lambda p, w: float(moment(p, w)))

    def rhs(p: float, y: np.ndarray) -> np.ndarray:
        Je = float(inertia(p)[0])
        return np.array([scalar(p, math.sqrt(max(2.0 * y[0] / Je, 0.0)))])

    cls = _solver_class(method)
    ends = np.concatenate(([phi0], _all_breaks(inertia, moment, phi0, phi_end), [phi_end]))
    los, his, dense, nfev, E = [], [], [], 0, E0
    for lo, hi in zip(ends[:-1], ends[1:]):
        solver = cls(rhs, lo, [E], hi, rtol=rtol, atol=atol)
        while solver.status == "running":
            t_old, y_old = solver.t, float(solver.y[0])
            message = solver.step()
            if solver.status == "failed":
                raise ConvergenceError(f"the integrator failed: {message}")
            d = solver.dense_output()
            if float(solver.y[0]) <= 0.0 and solver.t > t_old:
                def g(p: float) -> float:
                    return float(np.ravel(d(p))[0])
                if y_old <= 0.0:
                    at = t_old
                elif g(solver.t) > 0.0:  # rounding at the step end
                    at = solver.t
                else:
                    at = brentq(g, t_old, solver.t, xtol=1e-14 * max(1.0, abs(solver.t)),
                                rtol=4 * np.finfo(float).eps)
                raise DescribedError("the machine stops", reason="stall", phi=float(at))
            los.append(t_old)
            his.append(solver.t)
            dense.append(d)
            if len(dense) > MAX_STEPS:
                raise DescribedError(
                    f"the integrator needs more than {MAX_STEPS:,} steps per run: the "
                    "equation is stiff (a steep motor line on a light machine) -- use "
                    'method = "Radau", or looser rtol', reason="stiff", steps=len(dense),
                    phi=float(solver.t))
        nfev += solver.nfev
        E = float(solver.y[0])
    his[-1] = phi_end
    return _Run(los, his, dense, nfev, E)


def _omega_of(run: _Run, inertia: Inertia
             ) -> Callable[..., Any]:
    def omega(p: np.ndarray) -> np.ndarray:
        return np.sqrt(np.maximum(2.0 * run.E(p) / inertia(p)[0], 0.0))
    return omega


def _motion_from_run(run: _Run, inertia: Inertia,
                     moment: MomentModel, phi: np.ndarray, method: str, rtol: float, atol: float
                    ) -> Motion:
    omega_at = _omega_of(run, inertia)
    breaks = np.unique(np.concatenate((run.steps, phi)))
    t_b = _time(omega_at, breaks)
    t = t_b[np.searchsorted(breaks, phi)]
    Je, dJe = inertia(phi)
    omega = omega_at(phi)
    Me = moment(phi, omega)
    alpha = (Me - 0.5 * dJe * omega ** 2) / Je
    return Motion(phi=phi, t=t, omega=omega, alpha=alpha, Je=np.asarray(Je, float),
                  dJe=np.asarray(dJe, float), Me=np.asarray(Me, float), method=method,
                  nfev=run.nfev, rtol=rtol, atol=atol)


def _book(inertia: Inertia, moment: MomentModel, phi0: float,
          omega0: float, phi_end: float, step: float) -> Tuple[Any, ...]:
    """The book's explicit scheme (eqs 6-22, 6-23) on the grid ``phi0 + k·Δφ``.

    ``ω_{i+1} = Me(φ_i, ω_i) Δφ / (J_i ω_i) + (3J_i − J_{i+1}) ω_i / (2J_i)``; the step is
    shortened so that a whole number of steps spans ``[phi0, phi_end]``.
    """
    n = max(1, int(math.ceil((phi_end - phi0) / step - 1e-9)))
    phi = np.linspace(phi0, phi_end, n + 1)
    h = (phi_end - phi0) / n
    J, dJ = inertia(phi)
    J = np.broadcast_to(np.asarray(J, dtype=float), phi.shape)
    fast = isinstance(moment, MomentModel)
    Pl: List[float] = []
    if fast:
        P = moment.phi_part(phi)
        assert isinstance(P, np.ndarray)  # phi is an array
        Pl = P.tolist()
        c = moment.omega_coefficient
    omega = np.empty(n + 1)
    omega[0] = w = float(omega0)
    if not w > 0:
        raise ValueError("the book's scheme divides by ω: it cannot start from rest")
    Jl = J.tolist()
    for i in range(n):
        m = Pl[i] + c * w if fast else float(moment(phi[i], w))
        w_next = m * h / (Jl[i] * w) + (3.0 * Jl[i] - Jl[i + 1]) / (2.0 * Jl[i]) * w
        if not w_next > 0:
            raise DescribedError("the machine stops", reason="stall",
                                 phi=float(phi[i] + h * w / (w - w_next)))
        omega[i + 1] = w = w_next
    return phi, omega, np.asarray(dJ, float) * np.ones_like(phi), J, h, n


def _book_motion(inertia: Inertia, moment: MomentModel, phi0: float,
                 omega0: float, phi_end: float, step: float) -> Motion:
    phi, omega, dJ, J, h, n = _book(inertia, moment, phi0, omega0, phi_end, step)
    Me = moment(phi, omega)
    # eq 6-14 with ω linear over each step: Δt = Δφ ln(ω_{i+1}/ω_i)/(ω_{i+1} − ω_i)
    w0, w1 = omega[:-1], omega[1:]
    same = np.isclose(w0, w1, rtol=1e-12, atol=0)
    dt = np.where(same, h / (0.5 * (w0 + w1)),
                  h * np.log(w1 / w0) / np.where(same, 1.0, w1 - w0))
    t = np.concatenate(([0.0], np.cumsum(dt)))
    alpha = (Me - 0.5 * dJ * omega ** 2) / J
    return Motion(phi=phi, t=t, omega=omega, alpha=alpha, Je=np.array(J, dtype=float),
                  dJe=dJ, Me=np.asarray(Me, float), method="book", nfev=n, step=h)


def _check_method(method: str, step: Optional[float]) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}")
    if method == "book" and not (step is not None and step > 0):
        raise ValueError("the book's scheme needs a positive step")


def integrate(inertia: Union[Inertia, float], moment: MomentModel,
              phi0: float, omega0: float, phi_end: float, *, method: str = "DOP853",
              rtol: float = 1e-10, atol: float = 1e-12, step: Optional[float] = None,
              points: Optional[int] = None) -> Motion:
    """The motion under ``Me(φ, ω)`` with ``Je(φ)`` from ``phi0`` to ``phi_end`` (eq 6-21).

    ``Je ω dω/dφ + ½ dJe ω² = Me(φ, ω)`` is integrated in φ as the energy differential
    ``dE/dφ = Me(φ, ω)``, ``E = ½Je ω²`` (eq 6-5), which stays regular where ω → 0, piece by
    piece between the angles where Me or Je may have a kink (table nodes, segment ends);
    ``t = ∫dφ/ω`` (eq 6-14) by Gauss–Legendre on the dense output, α by eq 6-8.

    Parameters
    ----------
    inertia : inertia model or float
        ``Je(φ)`` [kg·m²].
    moment : MomentModel
        ``Me(φ, ω)`` [N·m].
    phi0, phi_end : float
        Start and end angles [rad], ``phi_end > phi0``.
    omega0 : float
        Speed at ``phi0`` [rad/s], ``>= 0``.
    method : {"RK45", "DOP853", "Radau", "book"}
        scipy's integrator of that name (Radau for a stiff model: a steep ``−bω`` against a
        small Je, ``b/(Je ω) >> 1`` per radian), or the book's explicit fixed-step scheme
        (eq 6-23) with ``step`` (first order; it divides by ω, so not from rest).
    rtol, atol : float
        Tolerances of the integrator on E; ``atol`` is in J and must lie well below the
        kinetic energies at stake (near a stall of a speed-dependent moment, where
        ``ω ∝ sqrt(φs − φ)``, it bounds the accuracy of the stall angle).
    step : float, optional
        The book's step Δφ [rad] (shortened to divide the span evenly).
    points : int, optional
        Output grid size for the scipy methods (default: about one point per degree); the
        book's scheme reports its own grid.

    Returns
    -------
    Motion

    Notes
    -----
    The models are evaluated one angle at a time: scalar models only (not a batch of
    designs).

    Raises
    ------
    DescribedError
        ``reason="stall"`` with ``phi`` [rad]: ω reaches 0 there (the root of E on the
        dense output of the step where E turns ≤ 0; for the book's scheme, where ω would
        turn ≤ 0, interpolated linearly).
    ConvergenceError
        The integrator failed.
    """
    inertia = _as_inertia(inertia)
    _check_method(method, step)
    phi0, omega0, phi_end = float(phi0), float(omega0), float(phi_end)
    if not phi_end > phi0:
        raise ValueError("the final angle must follow the initial one")
    if not omega0 >= 0:
        raise ValueError("the initial speed must not be negative")
    if method == "book":
        assert step is not None  # _check_method
        return _book_motion(inertia, moment, phi0, omega0, phi_end, step)
    run = _ode(inertia, moment, phi0, omega0, phi_end, method, rtol, atol)
    return _motion_from_run(run, inertia, moment, _grid(phi0, phi_end, points), method,
                            rtol, atol)


# --------------------------------------------------------------------------- steady state


def cycle(*periods: Optional[float]) -> float:
    """The cycle of models of these periods [rad] (None: constant): the longest, which
    every other must divide (2π and 4π: 4π, a four-stroke engine); 2π when none varies.

    Raises
    ------
    ValueError
        A period that does not divide the longest.
    """
    ps = [float(p) for p in periods if p is not None]
    if not ps:
        return TWO_PI
    T = max(ps)
    for p in ps:
        r = T / p
        if abs(r - round(r)) > 1e-9 * r:
            raise ValueError("the periods of the inertia and the moment must divide the "
                             "longest one")
    return T


def _period(inertia: Inertia, moment: MomentModel) -> float:
    if getattr(inertia, "period", None) is None and not getattr(inertia, "constant", False):
        raise ValueError("the steady state needs a periodic or constant inertia")
    if moment.depends_on_phi and moment.period is None:
        raise ValueError("the steady state needs a periodic moment (or one of ω alone)")
    return cycle(getattr(inertia, "period", None), moment.period)


def _extreme(f: Callable[..., Any], phi: np.ndarray, i: int, sign: float) -> Tuple[float, float]:
    """Refine the grid extreme ``i`` of ``sign·f`` (Brent, bounded, on both neighbours)."""
    from scipy.optimize import minimize_scalar

    lo, hi = phi[max(i - 1, 0)], phi[min(i + 1, phi.size - 1)]
    r = minimize_scalar(lambda p: -sign * float(f(np.array([p]))[0]), bounds=(lo, hi),
                        method="bounded", options={"xatol": 1e-12 * max(1.0, abs(hi))})
    best_x, best = phi[i], sign * float(f(phi[i:i + 1])[0])
    if -r.fun > best:
        best_x, best = float(r.x), -float(r.fun)
    return best_x, sign * best


def _summary(motion: Motion, omega0: float, omega_max: float, omega_min: float, p_max: float,
             p_min: float, mean: float, dW: float, it: int, res: float, root: str, nfev: int
            ) -> SteadyState:
    avg = 0.5 * (omega_max + omega_min)
    return SteadyState(motion=motion, omega0=float(omega0), omega_max=float(omega_max),
                       omega_min=float(omega_min), phi_at_max=float(p_max),
                       phi_at_min=float(p_min), omega_mean=float(mean), omega_avg=float(avg),
                       delta=float((omega_max - omega_min) / mean),
                       delta_avg=float((omega_max - omega_min) / avg), dW_max=float(dW),
                       iterations=int(it), residual=float(res), root=root, nfev=int(nfev))


def _steady_energy(inertia: Inertia,
                   moment: MomentModel, phi0: float, T: float, omega_mean: float, tol: float,
                   max_iter: int, points: int) -> SteadyState:
    """Me(φ) only: every ω0 is periodic when the work per period vanishes; pick the mean."""
    from scipy.optimize import brentq

    net = float(moment.energy(phi0, phi0 + T))
    phi = _grid(phi0, phi0 + T, points)
    # Gauss–Legendre between the grid, every kink of Me or Je and at most 2π/256 apart
    x, w = gauss_legendre(np.unique(np.concatenate((
        phi, np.linspace(phi0, phi0 + T, 257), _all_breaks(inertia, moment, phi0, phi0 + T)))),
        _GL_NODES)
    scale = float(np.dot(w, np.abs(moment.phi_part(x))))
    if abs(net) > 1e-9 * max(scale, 1e-300):
        raise DescribedError("the work per period does not vanish", reason="no_steady_state",
                             net_work=net)
    Je_x = inertia(x)[0]
    W_x = moment.energy(phi0, x)
    Je0 = float(inertia(phi0)[0])
    # the lowest ω0 that does not stall: 2E0 >= max(−2W)
    w_low = math.sqrt(max(0.0, 2.0 * float(np.max(-W_x))) / Je0) if np.max(-W_x) > 0 else 0.0

    def mean_of(w0: float) -> float:
        return float(np.dot(w, np.sqrt(np.maximum(Je0 * w0 * w0 + 2 * W_x, 0) / Je_x))) / T

    if not omega_mean > mean_of(w_low):
        raise DescribedError("no periodic motion has that mean speed", reason="no_steady_state",
                             omega0=w_low)
    hi = max(omega_mean, w_low) * 2 + 1.0
    while mean_of(hi) < omega_mean:
        hi *= 2
    w0, r = brentq(lambda v: mean_of(v) - omega_mean, w_low, hi, xtol=tol * omega_mean,
                   rtol=4 * np.finfo(float).eps, maxiter=max_iter, full_output=True,
                   disp=False)
    if not r.converged:
        raise ConvergenceError("the speed of the given mean was not found")
    m = energy_solution(inertia, moment, phi0, w0, phi)

    def omega_f(p: np.ndarray) -> np.ndarray:
        return np.sqrt(np.maximum((Je0 * w0 * w0 + 2 * moment.energy(phi0, p))
                                  / inertia(p)[0], 0.0))

    def E_f(p: np.ndarray) -> FloatOrArray:
        return moment.energy(phi0, p)

    imax, imin = int(np.argmax(m.omega)), int(np.argmin(m.omega))
    p_max, w_max = _extreme(omega_f, phi, imax, 1.0)
    p_min, w_min = _extreme(omega_f, phi, imin, -1.0)
    mean = float(np.dot(w, omega_f(x))) / T
    W = moment.energy(phi0, phi)
    _, e_max = _extreme(E_f, phi, int(np.argmax(W)), 1.0)
    _, e_min = _extreme(E_f, phi, int(np.argmin(W)), -1.0)
    res = abs(float(omega_f(np.array([phi0 + T]))[0]) - w0)
    return _summary(m, w0, w_max, w_min, p_max, p_min, mean, e_max - e_min, r.iterations,
                    res, "mean", 0)


def steady_state(inertia: Union[Inertia, float], moment: MomentModel, *, omega_guess: float,
                 method: str = "DOP853",
                 rtol: float = 1e-10, atol: float = 1e-12, step: Optional[float] = None,
                 root: str = "shooting", tol: float = 1e-12, max_iter: int = 200,
                 points: int = 361, phi0: float = 0.0) -> SteadyState:
    """The periodic motion of the stable-running stage and its speed fluctuation (例 6-4).

    The period map ``ω0 ↦ ω(φ0 + 2π)`` of :func:`integrate` has a fixed point ω0:

    * ``root="shooting"``: scipy's ``brentq`` on ``F(ω0) = ω(φ0 + 2π) − ω0``, bracketed
      from ``omega_guess`` and its image (a start that stalls counts as ``F > 0``: it needs
      more speed);
    * ``root="repeat"``: the book's loop, restarting each period from the last speed until
      ``|Δω| < tol`` (it converges only where the map contracts).

    A moment of φ alone (``depends_on_omega`` False) makes every ω0 periodic once the work
    per period ``W(φ0 + 2π)`` vanishes; then ``omega_guess`` is the integral mean speed
    (eq 6-26) the motion must have, and the exact energy integral gives it (``root="mean"``).

    From the period: the extremes of ω (refined on the dense output), the integral mean
    ``ωm = (1/φT)∫ω dφ`` (eq 6-26; trapezoidal on the grid of the book's scheme), the
    average ``(ωmax + ωmin)/2`` (eq 6-27), ``δ = (ωmax − ωmin)/ωm`` (eq 6-25, with eq 6-26's
    mean; ``delta_avg`` with eq 6-27's) and ``ΔWmax = E_max − E_min`` of the kinetic energy
    ``E = ½Je ω²``, which is the swing of the cumulative work ``∫Me dφ`` (eq 6-10).

    Parameters
    ----------
    inertia : inertia model or float
        ``Je(φ)``, 2π-periodic or constant [kg·m²].
    moment : MomentModel
        2π-periodic in φ, or of ω alone.
    omega_guess : float
        A guess of ω0 [rad/s] (> 0); for a moment of φ alone, the mean speed.
    method, rtol, atol, step : see :func:`integrate`.
    root : {"shooting", "repeat"}
    tol : float
        Root tolerance on ω0 [rad/s] (shooting: brentq's ``xtol``; repeat: ``|Δω|``).
    max_iter : int
        Most root-finder iterations or repeated periods.
    points : int
        Output grid over the period for the scipy methods.
    phi0 : float
        Start of the period [rad].

    Returns
    -------
    SteadyState

    Raises
    ------
    DescribedError
        ``reason="no_steady_state"`` (``net_work`` [J] for a moment of φ alone whose work
        per period does not vanish; ``omega0`` where no periodic speed was bracketed or the
        mean is too low).
    ConvergenceError
        The root finder or the repeated loop did not converge within ``max_iter``.
    """
    inertia = _as_inertia(inertia)
    _check_method(method, step)
    if root not in ROOTS:
        raise ValueError(f"unknown root finder {root!r}")
    if not omega_guess > 0:
        raise ValueError("the speed guess must be positive")
    T = _period(inertia, moment)
    phi0 = float(phi0)
    if not moment.depends_on_omega:
        return _steady_energy(inertia, moment, phi0, T, float(omega_guess), tol, max_iter,
                              points)
    pm = _PeriodMap(inertia, moment, phi0, T, method, rtol, atol, step)
    g = float(omega_guess)
    if root == "repeat":
        w0, iterations = _repeat_root(pm, g, tol, max_iter)
    else:
        w0, iterations = _shooting_root(pm, g, tol, max_iter)
    pm.advance(w0)
    w_end, run = pm.cache[w0]
    assert w_end is not None  # the root does not stall
    trail = tuple((w, pm.cache[w][0]) for w in pm.history)
    found = (iterations, abs(w_end - w0), root, pm.evaluations)
    if method == "book":
        assert step is not None  # _check_method
        st = _book_period(inertia, moment, phi0, T, w0, step, found)
    else:
        assert run is not None  # the solver's run (not the book's scheme)
        st = _run_period(run, inertia, moment, phi0, T, w0, points, method, rtol, atol, found)
    return dataclasses.replace(st, history=trail)


def _book_period(inertia: Inertia, moment: MomentModel, phi0: float, T: float, w0: float,
                 step: float, found: Tuple[int, float, str, int]) -> SteadyState:
    """The steady period by the book's scheme from ``w0``: its grid's extremes, the
    trapezoidal mean and work swing; *found* is (iterations, residual, root, evaluations)."""
    m = _book_motion(inertia, moment, phi0, w0, phi0 + T, step)
    imax, imin = int(np.argmax(m.omega)), int(np.argmin(m.omega))
    mean = float(np.trapezoid(m.omega, m.phi)) / T
    W = np.concatenate(([0.0], np.cumsum(0.5 * (m.Me[1:] + m.Me[:-1]) * np.diff(m.phi))))
    return _summary(m, w0, m.omega[imax], m.omega[imin], m.phi[imax], m.phi[imin], mean,
                    float(W.max() - W.min()), *found)


def _run_period(run: Any, inertia: Inertia, moment: MomentModel, phi0: float, T: float,
                w0: float, points: int, method: str, rtol: float, atol: float,
                found: Tuple[int, float, str, int]) -> SteadyState:
    """The steady period from a solver's *run*: the extremes of ω and of the energy
    refined on the dense output, the mean by Gauss–Legendre between the steps; *found*
    is (iterations, residual, root, evaluations)."""
    phi = _grid(phi0, phi0 + T, points)
    m = _motion_from_run(run, inertia, moment, phi, method, rtol, atol)
    m = dataclasses.replace(m, nfev=run.nfev)
    omega_f = _omega_of(run, inertia)
    p_max, w_max = _extreme(omega_f, phi, int(np.argmax(m.omega)), 1.0)
    p_min, w_min = _extreme(omega_f, phi, int(np.argmin(m.omega)), -1.0)
    breaks = np.unique(np.concatenate((run.steps, phi)))
    x, w = gauss_legendre(breaks, _GL_NODES)
    mean = float(np.dot(w, omega_f(x))) / T
    E = m.energy
    _, e_max = _extreme(run.E, phi, int(np.argmax(E)), 1.0)
    _, e_min = _extreme(run.E, phi, int(np.argmin(E)), -1.0)
    return _summary(m, w0, w_max, w_min, p_max, p_min, mean, e_max - e_min, *found)


class _PeriodMap:
    """The period map ``ω0 ↦ ω(φ0 + T)`` of :func:`steady_state`, memoised: ``cache[ω0]
    = (ω at the period's end or None on a stall, the run)``, ``calls`` the periods
    integrated, ``evaluations`` the moment evaluations they cost, ``history`` the
    starts in order."""

    def __init__(self, inertia: Inertia, moment: MomentModel,
                 phi0: float, T: float, method: str, rtol: float, atol: float,
                 step: Optional[float]) -> None:
        self.inertia, self.moment, self.phi0, self.T = inertia, moment, phi0, T
        self.method, self.rtol, self.atol, self.step = method, rtol, atol, step
        self.cache: Dict[float, Tuple[Optional[float], Optional[_Run]]] = {}
        self.history: List[float] = []
        self.calls = self.evaluations = 0

    def advance(self, w0: float) -> Optional[float]:
        """ω at the period end (``None`` on a stall)."""
        if w0 in self.cache:
            return self.cache[w0][0]
        self.calls += 1
        self.history.append(w0)
        inertia, moment, phi0, T = self.inertia, self.moment, self.phi0, self.T
        try:
            if self.method == "book":
                assert self.step is not None  # _check_method
                ph, om, *_ = _book(inertia, moment, phi0, w0, phi0 + T, self.step)
                self.evaluations += ph.size - 1
                self.cache[w0] = (float(om[-1]), None)
            else:
                run = _ode(inertia, moment, phi0, w0, phi0 + T, self.method, self.rtol,
                           self.atol)
                self.evaluations += run.nfev
                Je0 = float(inertia(phi0 + T)[0])
                self.cache[w0] = (math.sqrt(max(2.0 * run.E_end / Je0, 0.0)), run)
        except DescribedError as e:
            if e.reason != "stall":
                raise
            self.cache[w0] = (None, None)
        return self.cache[w0][0]

    def F(self, w0: float) -> float:
        """``ω(φ0 + T) − ω0`` (+∞ on a stall: the start needs more speed)."""
        w1 = self.advance(w0)
        return math.inf if w1 is None else w1 - w0


def _repeat_root(pm: _PeriodMap, g: float, tol: float, max_iter: int
                ) -> Tuple[float, int]:
    """The book's loop: each period from the last one's end speed until ``|Δω| < tol``:
    ``(ω0, periods)``."""
    w, it = g, 0
    while True:
        w1 = pm.advance(w)
        it += 1
        if w1 is None:
            raise DescribedError("the machine stops within a period", reason="no_steady_state",
                                 omega0=w)
        if abs(w1 - w) < tol:
            return w, it
        if it >= max_iter or not math.isfinite(w1):
            raise ConvergenceError(f"the repeated period did not settle in {it} periods "
                                   f"(last change {abs(w1 - w):.3g})")
        w = w1


def _shooting_root(pm: _PeriodMap, g: float, tol: float, max_iter: int) -> Tuple[float, int]:
    """brentq on the period map's fixed point, bracketed from ``g`` and its image:
    ``(ω0, periods integrated)``."""
    from scipy.optimize import brentq

    F = pm.F
    f_g = F(g)
    if f_g == 0:
        return g, 1
    lo_hi = _bracket(F, g, f_g, max_iter)
    if lo_hi is None:
        raise DescribedError("no periodic speed was found", reason="no_steady_state",
                             omega0=g)
    (a, fa), (b, fb) = lo_hi
    if fa == 0 or fb == 0:
        w0 = a if fa == 0 else b
    else:
        w0, r = brentq(F, a, b, xtol=tol, rtol=4 * np.finfo(float).eps,
                       maxiter=max_iter, full_output=True, disp=False)
        if not r.converged:
            raise ConvergenceError("the periodic speed was not found")
    f0 = F(w0)
    if not math.isfinite(f0) or abs(f0) > max(1e3 * tol, 1e-6 * w0):
        raise DescribedError("no periodic speed was found", reason="no_steady_state",
                             omega0=w0)
    return w0, pm.calls


def _bracket(F: Callable[..., Any], g: float, f_g: float, max_iter: int
            ) -> Optional[Tuple[Tuple[float, float], Tuple[float, float]]]:
    """Two speeds where ``F`` changes sign, from ``g`` and its image ``g + F(g)``."""
    a, fa = g, f_g
    if math.isinf(f_g):  # the guess stalls: go up
        b = 2.0 * g
    else:
        b = g + f_g + math.copysign(1e-6 * g, f_g)  # one repeated period, a hair beyond
        if not b > 0:
            b = 0.5 * g
    for _ in range(max_iter):
        fb = F(b)
        if fb == 0 or (fa > 0) != (fb > 0):
            return (a, fa), (b, fb)
        step = b - a
        a, fa = b, fb
        b = b + 2.0 * step
        if not b > 0:
            b = 0.5 * a
    return None


# --------------------------------------------------------------------------- flywheel


def flywheel_approx(dW_max: float, omega_m: float, delta: float, Je: float = 0.0) -> float:
    """The flywheel inertia of the constant-Je design formula (eqs 6-29, 6-30).

    ``J_F = ΔWmax / (ωm² [δ]) − Je`` (eq 6-29; ``Je = 0`` gives eq 6-30).

    Parameters
    ----------
    dW_max : float
        The largest energy swing ΔWmax [J], >= 0.
    omega_m : float
        Mean speed ωm [rad/s], > 0.
    delta : float
        Allowed coefficient of fluctuation [δ], > 0.
    Je : float, optional
        The machine's own (constant part of the) equivalent inertia [kg·m²].

    Returns
    -------
    float
        ``J_F`` [kg·m²].

    Raises
    ------
    DescribedError
        ``reason="no_flywheel_needed"`` with ``J_total`` (``ΔWmax/(ωm²[δ])``) and ``Je``:
        the machine's inertia already meets [δ] (J_F <= 0).
    """
    dW_max, omega_m, delta, Je = (float(v) for v in (dW_max, omega_m, delta, Je))
    if not (dW_max >= 0 and omega_m > 0 and delta > 0 and Je >= 0):
        raise ValueError("need ΔWmax >= 0, ωm > 0, [δ] > 0 and Je >= 0")
    total = dW_max / (omega_m ** 2 * delta)
    if not total > Je:
        raise DescribedError("the machine needs no flywheel", reason="no_flywheel_needed",
                             J_total=total, Je=Je)
    return total - Je


def flywheel_exact(inertia: Union[Inertia, float], moment: MomentModel, delta: float, *,
                   omega_guess: float,
                   method: str = "DOP853", rtol: float = 1e-10, atol: float = 1e-12,
                   step: Optional[float] = None, mean: str = "integral", tol: float = 1e-9,
                   max_iter: int = 100, points: int = 361,
                   swing: Optional[Tuple[float, float, float]] = None) -> float:
    """The flywheel ``J_F`` whose steady state with the variable Je meets [δ].

    Solves ``δ(J_F) = [δ]`` where ``δ(J_F)`` is the coefficient of fluctuation (eq 6-25) of
    :func:`steady_state` with ``inertia.plus(J_F)``; brentq on ``1/[δ] − 1/δ(J_F)``
    (nearly linear in J_F, eq 6-29),
    bracketed from the estimate of eq 6-29 (with the period mean of Je).

    Parameters
    ----------
    inertia, moment : see :func:`steady_state`.
    delta : float
        The allowed coefficient [δ], > 0.
    omega_guess : float
        As in :func:`steady_state` (the mean speed for a moment of φ alone).
    method, rtol, atol, step : see :func:`integrate`.
    mean : {"integral", "average"}
        δ with the integral mean (eq 6-26, ``delta``) or ``(ωmax + ωmin)/2`` (eq 6-27,
        ``delta_avg``).
    tol : float
        Relative tolerance on ``J_F``.
    max_iter : int
        Most brentq iterations (and bracket doublings).
    points : int
        Grid of each steady state.
    swing : (float, float, float), optional
        ``(ΔWmax [J], ωm [rad/s], mean Je [kg·m²])`` of the diagram at the mean speed: the
        first estimate (eq 6-29) when the machine has no steady state of its own (Je = 0,
        or too small to carry the swing at that mean speed: it cannot run without its
        flywheel).  Without it such a machine raises as :func:`steady_state` does.

    Returns
    -------
    float
        ``J_F`` [kg·m²].

    Raises
    ------
    DescribedError
        ``reason="no_flywheel_needed"`` with ``delta`` (the machine's own δ <= [δ]).
    ConvergenceError
        No bracket or no convergence.
    """
    inertia = _as_inertia(inertia)
    if mean not in ("integral", "average"):
        raise ValueError(f"unknown mean {mean!r}")
    target = float(delta)
    if not target > 0:
        raise ValueError("[δ] must be positive")
    run = _FlywheelRun(inertia, moment, target, float(omega_guess), mean, swing is not None,
                       dict(method=method, rtol=rtol, atol=atol, step=step, points=points))
    J1, h0 = _first_estimate(run, swing)
    return _secant_flywheel(run.h, h0, J1, tol, max_iter)


class _FlywheelRun:
    """The steady states of :func:`flywheel_exact`'s machine with a trial flywheel ``J_F``
    (the mean-speed guess carried from one to the next when the moment depends on ω)."""

    def __init__(self, inertia: Inertia, moment: MomentModel, target: float, guess: float,
                 mean: str, has_swing: bool, options: Dict[str, Any]) -> None:
        self.inertia, self.moment, self.target = inertia, moment, target
        self.guess, self.mean, self.options = guess, mean, options
        self.fixed_mean = not moment.depends_on_omega
        #: the errors that mean "cannot run at that mean speed" (caught only with a swing)
        self.cannot: Tuple[Type[DescribedError], ...] = (DescribedError,) if has_swing else ()

    def ss(self, JF: float) -> SteadyState:
        s = steady_state(self.inertia.plus(JF) if JF else self.inertia, self.moment,
                         omega_guess=self.guess, **self.options)
        if not self.fixed_mean:
            self.guess = s.omega0
        return s

    def d_of(self, s: SteadyState) -> float:
        return s.delta if self.mean == "integral" else s.delta_avg

    def h(self, JF: float) -> float:
        """``1/[δ] − 1/δ(J_F)``: δ ≈ ΔW/(ωm²(J_F + Je)) makes it nearly linear in J_F."""
        try:
            return 1.0 / self.target - 1.0 / self.d_of(self.ss(JF))
        except self.cannot as e:     # still too light to run at that mean: more J_F
            if e.reason not in ("no_steady_state", "stall"):
                raise
            return 1.0 / self.target


def _first_estimate(run: _FlywheelRun, swing: Optional[Tuple[float, float, float]]
                    ) -> Tuple[float, float]:
    """The first trial ``J_F`` (eq 6-29) and ``h(0)``, from the machine's own steady state
    or, when it has none, from ``swing``."""
    inertia, target, mean = run.inertia, run.target, run.mean
    grid = np.linspace(0.0, TWO_PI, 361)
    s0 = None
    if float(np.max(inertia(grid)[0])) > 0.0:
        try:
            s0 = run.ss(0.0)
        except run.cannot as e:     # the machine cannot run without its flywheel
            if e.reason not in ("no_steady_state", "stall"):
                raise
    if s0 is not None:
        d0 = run.d_of(s0)
        if d0 <= target:
            raise DescribedError("the machine needs no flywheel", reason="no_flywheel_needed",
                                 delta=d0)
        Jm = float(np.mean(s0.motion.Je))
        wm = s0.omega_mean if mean == "integral" else s0.omega_avg
        J1 = max(s0.dW_max / (wm ** 2 * target) - Jm, 1e-6 * Jm)
        h0 = 1.0 / target - 1.0 / d0
    else:
        if swing is None:   # Je = 0 everywhere and no swing given
            raise TypeError("a machine without inertia needs the swing")
        dW, wm, Jm = (float(v) for v in swing)
        J1 = max(dW / (wm ** 2 * target) - Jm, 1e-9 * dW / (wm ** 2 * target))
        h0 = 1.0 / target       # δ(0) unbounded
    return J1, h0


def _secant_flywheel(h: Callable[[float], float], h0: float, J1: float, tol: float,
                     max_iter: int) -> float:
    """The root of ``h`` (``h(0) = h0 > 0``) from ``J1``: a safeguarded secant, with a root
    bracket [lo, hi] once h changes sign and bisection whenever the secant leaves it."""
    lo, h_lo = 0.0, h0
    hi = None
    a, h_a, b = 0.0, h_lo, J1
    for _ in range(max_iter):
        h_b = h(b)
        if h_b == 0.0:
            return float(b)
        if h_b > 0:
            lo, h_lo = b, h_b
        else:
            hi = b
        step = -h_b * (b - a) / (h_b - h_a) if h_b != h_a else math.inf
        a, h_a = b, h_b
        nxt = b + step
        if hi is None:
            if not (math.isfinite(nxt) and nxt > lo):
                nxt = 2.0 * max(lo, J1)
        elif not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if abs(nxt - b) <= tol * max(abs(nxt), 1e-300) or (
                hi is not None and hi - lo <= tol * hi):
            return float(nxt if lo <= nxt <= (hi if hi is not None else math.inf) else b)
        b = nxt
    raise ConvergenceError("the flywheel for [δ] was not found")


def rim(J: float, radius: float) -> float:
    """Mass of a thin-rim flywheel ``m = J/R²`` [kg] (J [kg·m²], mean rim radius R [m])."""
    J, radius = float(J), float(radius)
    if not (J >= 0 and radius > 0):
        raise ValueError("need J >= 0 and R > 0")
    return J / radius ** 2


def disc(J: float, radius: float) -> float:
    """Mass of a solid-disc flywheel ``m = 2J/R²`` [kg] (J [kg·m²], outer radius R [m])."""
    J, radius = float(J), float(radius)
    if not (J >= 0 and radius > 0):
        raise ValueError("need J >= 0 and R > 0")
    return 2.0 * J / radius ** 2


def width(mass: float, density: float, r_outer: float, r_inner: float = 0.0) -> float:
    """Axial width ``b = m / (ρ π (Ro² − Ri²))`` [m] of a disc or rim of that mass.

    Parameters
    ----------
    mass : float
        [kg].
    density : float
        [kg/m³].
    r_outer, r_inner : float
        Outer and inner radii [m], ``0 <= r_inner < r_outer``.
    """
    mass, density, ro, ri = (float(v) for v in (mass, density, r_outer, r_inner))
    if not (mass >= 0 and density > 0 and 0 <= ri < ro):
        raise ValueError("need m >= 0, ρ > 0 and 0 <= Ri < Ro")
    return mass / (density * math.pi * (ro * ro - ri * ri))
