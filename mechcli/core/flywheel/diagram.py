"""The turning-moment diagram read as textbooks read it: the loops between the diagram and
its mean, their excess and deficit energies, and the largest energy swing (第四节).

Over one cycle of a machine in its steady state the equivalent moment ``Me(φ)`` (at the
mean speed when it depends on ω) does no net work.  The angles where it changes sign
split the cycle into loops; each loop's area ``∫Me dφ`` is an excess (+, the machine
speeds up) or a deficit (−) of energy.  The cumulative energy at the loop ends is the
kinetic energy's change from the cycle's start (eq 6-10 at constant Je); the speed is
largest where it peaks and least where it is lowest, and ``ΔWmax = E_max − E_min``
(the ΔWmax of eqs 6-29, 6-30).

SI units and radians; no I/O.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Tuple

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.flywheel.motion import MomentModel
    from mechcli.core.types import FloatOrArray

#: relative size of the net work per cycle, against ∫|Me| dφ, that still counts as none
NET_RTOL = 1e-9
#: samples of the moment per cycle between its break angles (sign changes are then
#: refined by Brent's method on the exact model)
SAMPLES = 7200


@record(eq=False)
class EnergyLoops:
    """The loops of a turning-moment diagram about its mean over one cycle.

    Attributes
    ----------
    bounds : ndarray
        The loop ends [rad], ``n + 1`` increasing angles from the cycle's start to its end:
        the start, every sign change of Me, the end.
    areas : ndarray
        Each loop's energy ``∫Me dφ`` [J]: + an excess (increment), − a deficit.
    cumulative : ndarray
        The energy at each bound since the start [J] (``cumulative[0] = 0``).
    dW_max : float
        ``max(cumulative) − min(cumulative)`` [J], the largest energy swing ΔWmax.
    phi_max, phi_min : float
        Where the cumulative energy, so the speed (at constant Je), is largest and least
        [rad].
    period : float
        The cycle [rad].
    """

    bounds: np.ndarray
    areas: np.ndarray
    cumulative: np.ndarray
    dW_max: float
    phi_max: float
    phi_min: float
    period: float


def energy_loops(moment: MomentModel, phi0: float, period: float, omega_m: float = 0.0
                ) -> EnergyLoops:
    """The loop-energy table of ``Me(φ, ωm)`` over one cycle from ``phi0``.

    Parameters
    ----------
    moment : motion.MomentModel
        The equivalent moment [N·m] (its ``energy`` exact; ``b`` its motor-line slope).
    phi0 : float
        Start of the cycle [rad] (where the table of areas starts, "from one end").
    period : float
        The cycle [rad] (2π, 4π for a four-stroke engine).
    omega_m : float
        The mean speed [rad/s] at which a moment of ω is read (``a − b ωm``).

    Returns
    -------
    EnergyLoops

    Raises
    ------
    DescribedError
        ``reason="no_steady_state"`` with ``net_work`` [J]: the work over the cycle does
        not vanish (the diagram has no loops about its mean: make one term the mean).
    """
    from scipy.optimize import brentq

    phi0, T = float(phi0), float(period)
    b = float(getattr(moment, "b", 0.0))

    def W(p: FloatOrArray) -> FloatOrArray:
        p = np.asarray(p, dtype=float)
        return moment.energy(phi0, p) - b * omega_m * (p - phi0)

    def f(p: np.ndarray) -> np.ndarray:
        m = moment(p, omega_m)
        assert isinstance(m, np.ndarray)  # p is an array
        return m

    grid = np.unique(np.concatenate((np.linspace(phi0, phi0 + T, SAMPLES + 1),
                                     moment.breaks_between(phi0, phi0 + T))))
    v = np.asarray(f(grid), dtype=float)
    # the work's scale: ∫|Me| dφ by the trapezoid rule on the fine grid
    scale = float(np.sum(0.5 * (np.abs(v[1:]) + np.abs(v[:-1])) * np.diff(grid)))
    net = float(W(phi0 + T))
    if abs(net) > NET_RTOL * max(scale, 1e-300):
        raise DescribedError("the work over a cycle does not vanish: the diagram has no "
                             "loops about its mean", reason="no_steady_state", net_work=net)
    zero = 1e-12 * max(float(np.max(np.abs(v))), 1e-300)
    sign = np.where(v > zero, 1, np.where(v < -zero, -1, 0))
    cuts = []
    last = None                     # index of the last sample of nonzero sign
    for j in np.flatnonzero(sign):
        if last is not None and sign[j] != sign[last]:
            if j > last + 1:        # Me = 0 on the samples between: the loop ends there
                cuts.append(float(grid[last + 1]))
            else:
                def g(p: float) -> float:
                    return float(f(np.array([p]))[0])
                cuts.append(float(brentq(g, grid[last], grid[j], xtol=1e-13 * max(1.0, T),
                                         rtol=4 * np.finfo(float).eps)))
        last = j
    tol = 1e-12 * max(1.0, abs(phi0) + T)
    cuts = [c for c in cuts if phi0 + tol < c < phi0 + T - tol]
    bounds = np.array([phi0] + cuts + [phi0 + T])
    cum = np.asarray(W(bounds), dtype=float)
    cum[0], cum[-1] = 0.0, net
    areas = np.diff(cum)
    i_max, i_min = int(np.argmax(cum)), int(np.argmin(cum))
    return EnergyLoops(bounds=bounds, areas=areas, cumulative=cum,
                       dW_max=float(cum[i_max] - cum[i_min]), phi_max=float(bounds[i_max]),
                       phi_min=float(bounds[i_min]), period=T)


def speeds_from_swing(J: float, dW: float, omega_mean: float) -> Tuple[float, float, float]:
    """Eqs 6-28, 6-29 from numbers: δ = ΔWmax/(J ωm²) for the whole inertia J [kg m²],
    ΔWmax [J] and the mean speed ωm [rad/s]; ωmax, ωmin = ωm (1 ± δ/2) [rad/s].

    Returns
    -------
    (float, float, float)
        δ, ωmax, ωmin.
    """
    # divided one factor at a time: J ωm² of a tiny ωm underflows to 0, its quotient is
    # then inf (δ ≥ 2 is refused by the command), never a ZeroDivisionError
    with np.errstate(over="ignore", divide="ignore"):
        delta = float(np.float64(dW) / J / omega_mean / omega_mean)
    return delta, omega_mean * (1 + delta / 2), omega_mean * (1 - delta / 2)


def mean_moment(moment: MomentModel, phi0: float, period: float) -> float:
    """The mean of a moment of φ over a cycle, ``(1/T) ∫Me dφ`` [N·m] (the constant that
    balances it: "the resisting moment is the mean")."""
    return float(moment.energy(float(phi0), float(phi0) + float(period))) / float(period)

