"""The equivalent dynamic model of a machine reduced to its input link (第二节, 图 6-2).

A one-degree-of-freedom machine moves like one rotating link, the equivalent link, when that
link carries

* the equivalent moment of inertia (kinetic energy equal to the machine's, eq 6-4)

  .. math:: J_e(\\varphi) = \\sum_i m_i \\left(\\frac{v_{Si}}{\\omega}\\right)^2
            + J_{Si} \\left(\\frac{\\omega_i}{\\omega}\\right)^2

* the equivalent moment (power equal to that of the external forces, eq 6-2)

  .. math:: M_e(\\varphi) = \\sum_i F_i \\cos\\alpha_i \\frac{v_i}{\\omega}
            \\pm M_i \\frac{\\omega_i}{\\omega}

with every ratio v/ω, ω_i/ω a function of the position only: the velocity coefficients
(类速度) of :func:`mechcli.core.linkage.kinematic_coefficients`.  The equation of motion
(eq 6-8, :mod:`.motion`) also needs dJe/dφ; for a linkage it is computed exactly from the
acceleration coefficients (d²θ/dφ²), where the book differences Je.

Inertia models (what :mod:`.motion` integrates with) share one interface:

* ``model(phi) -> (Je, dJe)``: arrays like ``phi`` [kg m², kg m²/rad];
* ``model.period``: 2π, or None when the model is not periodic in φ (a constant, or a
  linkage whose primary driver is linear or whose followers turn at a non-integer ratio);
* ``model.constant``: Je does not depend on φ;
* ``model.plus(J)``: the same model with a constant J [kg m²] added (a flywheel on the
  equivalent link, eq 6-29); ``model.added`` is the total added so far.

:class:`ConstantInertia`, :class:`ChainInertia` (a gear train, constant ratios),
:class:`TableInertia` (Je tabulated over one turn, 表 6-2) and :class:`LinkageInertia` (a
linkage of the engine with its bodies, 【例 6-1】).  :func:`chain_moment` and
:func:`linkage_moment` give Me (eq 6-2).

Units SI, angles in radians; the input is assumed to turn forward (ω1 > 0) wherever a
load's program depends on the sign of a velocity.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.linkage.engine import kinematic_coefficients
from mechcli.core.linkage.force_model import Body, ForceModelError, com_of, topology

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import Linkage, LinkageMotion
    from mechcli.core.linkage.force_model import Topology
    from mechcli.core.types import FloatOrArray

TWO_PI = 2.0 * np.pi

#: relative mismatch of a table's last value against its first that still closes the
#: period (the brief; tables are printed to 3-4 digits, so a real mismatch is >= 1e-4)
PERIODIC_RTOL = 1e-9

#: relative mismatch of a table's span against 2π, and of a Fourier table's steps
#: against 2π/N (angles converted from printed degrees are exact to ~1e-16)
SPAN_RTOL = 1e-9

#: rows × terms of one block of the Fourier evaluation (bounds its memory to ~64 MB)
_FOURIER_BLOCK = 4_000_000


# ---------------------------------------------------------------------------
# the interface
# ---------------------------------------------------------------------------
class InertiaModel:
    """Base of the inertia models: ``added`` constant, ``plus``, ``__call__``.

    Subclasses implement ``_evaluate(phi) -> (Je, dJe)`` on a float array and set
    ``period`` and ``constant``.
    """

    period: Optional[float] = None
    constant: bool = False
    added = 0.0

    def __call__(self, phi: FloatOrArray) -> Any:
        """``(Je, dJe)`` at the input angles ``phi`` [rad]: arrays of ``phi``'s shape
        (broadcast with the model's own batch shape, if any) [kg m², kg m²/rad]."""
        phi = np.asarray(phi, dtype=float)
        Je, dJe = self._evaluate(phi)
        return Je + self.added, dJe

    def plus(self, J: float) -> Any:
        """The same model with the constant moment of inertia ``J`` [kg m²] added: a
        flywheel on the equivalent link (eq 6-29 adds J_F to Je)."""
        new = copy.copy(self)
        new.added = self.added + J
        return new

    def _evaluate(self, phi: np.ndarray) -> Any:  # pragma: no cover - every model overrides it
        raise NotImplementedError


def _positive(J: FloatOrArray, what: str) -> None:
    J = np.asarray(J, dtype=float)
    if not np.all(np.isfinite(J)) or np.any(J <= 0.0):
        bad = J[~(np.isfinite(J) & (J > 0.0))] if J.ndim else J
        raise DescribedError(f"the {what} must be positive", reason="not_positive",
                             value=float(np.ravel(bad)[0]))


# ---------------------------------------------------------------------------
# constant models
# ---------------------------------------------------------------------------
class ConstantInertia(InertiaModel):
    """A constant equivalent moment of inertia (例 6-3: an electric drive, Je = 10 kg m²).

    Parameters
    ----------
    J : float or array
        Je [kg m²], positive (an array: a batch of designs).

    Raises
    ------
    DescribedError
        ``reason="not_positive"`` (``value``) when J is not positive.
    """

    period = None
    constant = True

    def __init__(self, J: float) -> None:
        _positive(J, "equivalent moment of inertia")
        self.value = J

    def _evaluate(self, phi: np.ndarray) -> Any:
        Je = self.value + np.zeros_like(phi)
        return Je, np.zeros_like(Je)


class ZeroInertia(InertiaModel):
    """No inertia of the machine's own (Je = 0): the textbook's machine whose flywheel
    carries all of it (eq 6-30).  Only useful with a flywheel added (``plus``)."""

    period = None
    constant = True

    def _evaluate(self, phi: np.ndarray) -> Any:
        Je = np.zeros_like(phi)
        return Je, np.zeros_like(Je)


class ChainInertia(ConstantInertia):
    """Je of members turning (or sliding) at constant ratios to the input: a gear train
    (eq 6-4 with constant ratios; the book's note (2) after eq 6-4: Je is then constant).

    Parameters
    ----------
    members : sequence of (J_i, ratio_i)
        Moment of inertia of each rotating member about its axis [kg m²] and its speed
        ratio ω_i/ω1 (the sign does not matter: Je has the ratio squared).
    masses : sequence of (m_i, v_ratio_i), optional
        Translating members: mass [kg] and speed ratio v_i/ω1 [m/rad].

    Attributes
    ----------
    value : float
        Je = Σ J_i (ω_i/ω1)² + Σ m_i (v_i/ω1)² [kg m²].
    terms : tuple of float
        Each member's share, members first, then masses, in the order given.
    """

    def __init__(self, members: List[Tuple[float, float]], *, masses: Any = ()) -> None:
        terms = tuple(float(J) * float(r) ** 2 for J, r in members)
        terms += tuple(float(m) * float(v) ** 2 for m, v in masses)
        if any(t < 0.0 for t in terms):
            raise DescribedError("a member's moment of inertia or mass is negative",
                                 reason="not_positive", value=min(terms))
        super().__init__(float(sum(terms)))
        self.terms = terms


def chain_moment(torques: List[Tuple[float, float]], forces: Any = ()) -> float:
    """Me of loads on members at constant ratios to the input (eq 6-2).

    Parameters
    ----------
    torques : sequence of (M_i, ratio_i)
        Torque on each member [N m] and its speed ratio ω_i/ω1, both signed in one sense
        of rotation: a torque turning with its member counts positive (the book's +),
        against it negative (−, a resisting torque).
    forces : sequence of (F_i, v_ratio_i), optional
        Force on a translating member along its velocity, F_i cos α_i [N], with the speed
        ratio v_i/ω1 [m/rad], signed alike.

    Returns
    -------
    float
        Me = Σ M_i ω_i/ω1 + Σ F_i cos α_i v_i/ω1 [N m].
    """
    return float(sum(float(M) * float(r) for M, r in torques)
                 + sum(float(F) * float(v) for F, v in forces))


# ---------------------------------------------------------------------------
# a table over one turn
# ---------------------------------------------------------------------------
class TableInertia(InertiaModel):
    """Je tabulated over exactly one period of the input (表 6-2, 例 6-4: one turn),
    interpolated periodically.

    Parameters
    ----------
    phi : array
        Input angles [rad], strictly increasing, ``phi[-1] - phi[0]`` = ``period`` (the
        last node closes the period, as 表 6-2's 0° ... 360°).
    J : array
        Je at ``phi`` [kg m²], positive; ``J[-1]`` equals ``J[0]`` to ``PERIODIC_RTOL``.
    method : {"cubic", "linear", "fourier"}
        * ``"cubic"``: periodic cubic spline (``scipy.interpolate.CubicSpline``,
          ``bc_type="periodic"``); Je and dJe continuous (C², also across 0/2π); dJe is
          the spline's exact derivative.  The default.
        * ``"linear"``: periodic piecewise linear; Je continuous, dJe piecewise constant
          (the slope of the interval [φ_k, φ_k+1) that contains φ), with jumps at the
          nodes.
        * ``"fourier"``: trigonometric interpolation through the N = len(phi) - 1 nodes
          (needs equal steps); Je and dJe smooth (analytic), but it may overshoot between
          nodes where the table has a kink.  Costs N/2 terms per evaluated angle.
    period : float
        The period [rad]: 2π (one turn, the default), 4π for a four-stroke cycle.

    Raises
    ------
    DescribedError
        ``reason`` ``"too_few"`` (``count``), ``"not_increasing"`` (``angle``: the first
        node not above its predecessor), ``"not_one_period"`` (``span`` [rad]),
        ``"not_periodic"`` (``first``, ``last`` [kg m²]), ``"not_uniform"`` (``step``,
        ``expected`` [rad], for ``"fourier"``), ``"not_positive"`` (``value``).
    """

    constant = False
    period: float
    METHODS = ("cubic", "linear", "fourier")

    def __init__(self, phi: np.ndarray, J: np.ndarray, *, method: str = "cubic",
                 period: float = TWO_PI) -> None:
        self.period = T = float(period)
        phi = np.asarray(phi, dtype=float).ravel()
        J = np.asarray(J, dtype=float).ravel()
        if method not in self.METHODS:
            raise ValueError(f"method must be one of {self.METHODS}, got {method!r}")
        if phi.size != J.size:
            raise ValueError(f"phi has {phi.size} values and J {J.size}")
        if phi.size < 3:
            raise DescribedError("a table over one turn needs at least three nodes",
                                 reason="too_few", count=int(phi.size))
        steps = np.diff(phi)
        if not np.all(steps > 0.0):
            k = int(np.argmax(~(steps > 0.0))) + 1
            raise DescribedError("the table's angles must increase", reason="not_increasing",
                                 angle=float(phi[k]))
        span = float(phi[-1] - phi[0])
        if abs(span - T) > SPAN_RTOL * T:
            raise DescribedError("the table must span exactly one period of the input",
                                 reason="not_one_period", span=span)
        _positive(J, "equivalent moment of inertia")
        if abs(J[-1] - J[0]) > PERIODIC_RTOL * float(np.max(np.abs(J))):
            raise DescribedError("the table's last value must repeat its first (one period)",
                                 reason="not_periodic", first=float(J[0]), last=float(J[-1]))
        J = J.copy()
        J[-1] = J[0]
        self.phi, self.J, self.method = phi, J, method
        if method == "cubic":
            from scipy.interpolate import CubicSpline

            self._spline = CubicSpline(phi, J, bc_type="periodic")
            self._slope = self._spline.derivative()
        elif method == "linear":
            self._slopes = np.diff(J) / steps
        else:
            n = phi.size - 1
            if np.max(np.abs(steps - T / n)) > SPAN_RTOL * T:
                k = int(np.argmax(np.abs(steps - T / n)))
                raise DescribedError("Fourier interpolation needs equal steps",
                                     reason="not_uniform", step=float(steps[k]),
                                     expected=T / n)
            c = np.fft.rfft(J[:-1]) / n
            weight = np.full(c.size, 2.0)
            weight[0] = 1.0
            if n % 2 == 0:
                weight[-1] = 1.0  # the Nyquist term cos(n/2 (φ - φ0)) taken once
            self._coef = weight * c
            self._k = np.arange(c.size, dtype=float) * (TWO_PI / T)

    def _evaluate(self, phi: np.ndarray) -> Any:
        x0 = self.phi[0]
        t = np.mod(phi - x0, self.period)
        if self.method == "cubic":
            x = x0 + t
            return self._spline(x), self._slope(x)
        if self.method == "linear":
            x = x0 + t
            k = np.clip(np.searchsorted(self.phi, x, side="right") - 1, 0,
                        self._slopes.size - 1)
            return np.interp(x, self.phi, self.J), self._slopes[k]
        flat = t.ravel()
        Je, dJe = np.empty_like(flat), np.empty_like(flat)
        rows = max(1, _FOURIER_BLOCK // self._k.size)
        for a in range(0, flat.size, rows):
            e = np.exp(1j * np.multiply.outer(flat[a:a + rows], self._k)) * self._coef
            Je[a:a + rows] = e.real.sum(axis=-1)
            dJe[a:a + rows] = -(e.imag * self._k).sum(axis=-1)
        return Je.reshape(t.shape), dJe.reshape(t.shape)


# ---------------------------------------------------------------------------
# a linkage of the engine
# ---------------------------------------------------------------------------
def _point_motion(m: LinkageMotion, topo: Topology, link: int, origin: str, along: Optional[float],
                  normal: Optional[float], acc: bool) -> Any:
    """Velocity (and acceleration) coefficients of a point fixed on ``link``: ``origin +
    (along + i normal) e^{iθ}``, or the midpoint of the link's two points when ``along``
    is None (:func:`~mechcli.core.linkage.force_model.com_of`'s convention)."""
    # (ignored below: m is solved to order 1, 2 with acc, so its velocities and accelerations
    # are not None; along is None only for a link with a second point, com_of's midpoint)
    o = m.points[origin]
    if along is None:
        p = m.points[topo.frames[link][1]]  # type: ignore[index]
        v = (0.5 * (o.vx + p.vx), 0.5 * (o.vy + p.vy))  # type: ignore[operator]
        return v + ((0.5 * (o.ax + p.ax), 0.5 * (o.ay + p.ay)) if acc else (None, None))  # type: ignore[operator]
    if not (np.any(along) or np.any(normal)):
        return (o.vx, o.vy) + ((o.ax, o.ay) if acc else (None, None))
    k = m.links[link]
    c, s = np.cos(k.theta), np.sin(k.theta)
    rx, ry = along * c - normal * s, along * s + normal * c
    vx, vy = o.vx - k.omega * ry, o.vy + k.omega * rx
    if not acc:
        return vx, vy, None, None
    w2 = k.omega * k.omega  # type: ignore[operator]
    return vx, vy, o.ax - k.alpha * ry - w2 * rx, o.ay + k.alpha * rx - w2 * ry


def _check_regular(m: LinkageMotion, phi: np.ndarray) -> None:
    """Raise when the linkage does not assemble (or is at a dead point) at some input."""
    if np.all(m.regular):
        return
    bad = ~np.asarray(m.regular)
    idx = np.unravel_index(int(np.argmax(bad)), bad.shape)
    angle = float(np.broadcast_to(phi, bad.shape)[idx])
    if not np.asarray(m.feasible)[idx]:
        raise DescribedError("the linkage does not assemble at an input position",
                             reason="cannot_assemble", angle=angle)
    raise DescribedError("the linkage is at a dead point at an input position (its velocity "
                         "coefficients are unbounded)", reason="dead_point", angle=angle)


def _period(linkage: Linkage, followers: Optional[Any]) -> Optional[float]:
    rotary = linkage.drivers[0].rotary
    ratios = [float(r) for r, _ in (followers or {}).values()]
    return TWO_PI if rotary and all(r == round(r) for r in ratios) else None


class LinkageInertia(InertiaModel):
    """Je(φ) of a linkage of the engine reduced to its primary driver (eq 6-4, 【例 6-1】).

    .. math:: J_e = \\sum_i m_i |v_{Si}/\\omega_1|^2 + J_{Si} (\\omega_i/\\omega_1)^2

    with the velocity coefficients of :func:`~mechcli.core.linkage.kinematic_coefficients`
    (the linkage solved at unit input speed).  The exact derivative differentiates each
    term once more: with the acceleration coefficients (unit speed, zero input
    acceleration) a_S = d²r_S/dφ², α_i = d²θ_i/dφ², so

    .. math:: \\frac{dJ_e}{d\\varphi} = 2 \\sum_i m_i\\, v_{Si}\\cdot a_{Si}
              + J_{Si}\\, \\omega_i \\alpha_i

    For a linear primary driver the same sums are the equivalent mass m_e (eq 6-3) and its
    derivative dm_e/ds.

    Parameters
    ----------
    linkage : Linkage
        One design, or a batch (element parameters of shape ``(M, 1)``: results ``(M, N)``).
    bodies : dict
        ``{link: Body}`` (:class:`~mechcli.core.linkage.force_model.Body`): mass [kg],
        moment of inertia J_S about the centre of mass [kg m²], and the centre of mass
        ``origin + (along + i normal) e^{iθ}`` (``origin`` None: the midpoint of the
        link's two points, or its only point, as the kinetostatics).  A body on the driver
        counts like any other, J_S plus m |v_S|²: a crank given by its J about the pivot
        (例 6-1's J1) is ``Body(1, mass, J1, origin=pivot)``.  Masses and inertias may be
        arrays of the batch's shape.
    followers : dict, optional
        ``{link: (ratio, phase)}`` of secondary drivers (see ``kinematic_coefficients``).
    derivative : {"exact", "difference"}
        ``"exact"``: from the acceleration coefficients (one solve of order 2).
        ``"difference"``: the central difference (Je(φ+h) − Je(φ−h)) / 2h with h =
        ``step`` [rad], the book's way (it differences Je over 1°); truncation error
        h² |Je'''| / 6 plus round-off ≈ 1e-16 Je / h (three solves of order 1).
    step : float
        h of ``"difference"`` [rad (m for a linear driver)], positive.

    Raises
    ------
    DescribedError
        When called: ``reason="cannot_assemble"`` (``angle``: the first input where the
        linkage does not assemble) or ``"dead_point"`` (``angle``: where it assembles
        but its velocity coefficients are unbounded).
    ForceModelError
        A body on a link that does not move, or at a point not on its link.
    """

    constant = False

    def __init__(self, linkage: Linkage, bodies: Dict[int, Body], *,
                 followers: Optional[Any] = None, derivative: str = "exact", step: float = 1e-5
                ) -> None:
        if derivative not in ("exact", "difference"):
            raise ValueError(f"derivative must be 'exact' or 'difference', got {derivative!r}")
        if not step > 0.0:
            raise ValueError(f"step must be positive, got {step!r}")
        self.linkage, self.followers = linkage, dict(followers or {})
        self.derivative, self.step = derivative, float(step)
        self.topo = topology(linkage)
        self.bodies = dict(bodies)
        self._terms = []
        for link, b in self.bodies.items():
            _check_on_link(self.topo, link, b.origin, f"the body of link {link}")
            if np.any(b.mass) or np.any(b.inertia):
                self._terms.append((link, b.mass, b.inertia) + com_of(self.topo, b, link))
        self.period = _period(linkage, followers)

    def _solve(self, phi: np.ndarray, order: int) -> LinkageMotion:
        m = kinematic_coefficients(self.linkage, phi, self.followers or None, order=order)
        _check_regular(m, phi)
        return m

    def parts(self, phi: np.ndarray) -> Dict[int, Tuple[np.ndarray, np.ndarray]]:
        """Each body's share of Je and its exact derivative: ``{link: (Je_i, dJe_i)}``
        (before ``added``)."""
        phi = np.asarray(phi, dtype=float)
        m = self._solve(phi, 2)
        shape = np.shape(m.feasible)
        return {link: (np.array(np.broadcast_to(Je, shape)), np.array(np.broadcast_to(dJe, shape)))
                for link, (Je, dJe) in self._shares(m).items()}

    def _shares(self, m: LinkageMotion) -> Any:
        out = {}
        for link, mass, J, origin, along, normal in self._terms:
            vx, vy, ax, ay = _point_motion(m, self.topo, link, origin, along, normal, True)
            k = m.links[link]
            Je = mass * (vx * vx + vy * vy) + J * k.omega * k.omega
            dJe = 2.0 * (mass * (vx * ax + vy * ay) + J * k.omega * k.alpha)
            out[link] = (Je, dJe)
        return out

    def _je(self, m: LinkageMotion) -> np.ndarray:
        Je = np.zeros(np.shape(m.feasible))
        for link, mass, J, origin, along, normal in self._terms:
            vx, vy, _ax, _ay = _point_motion(m, self.topo, link, origin, along, normal, False)
            w = m.links[link].omega
            Je = Je + mass * (vx * vx + vy * vy) + J * w * w
        return Je

    def _evaluate(self, phi: np.ndarray) -> Any:
        if self.derivative == "exact":
            m = self._solve(phi, 2)
            Je, dJe = np.zeros(np.shape(m.feasible)), np.zeros(np.shape(m.feasible))
            for Je_i, dJe_i in self._shares(m).values():
                Je, dJe = Je + Je_i, dJe + dJe_i
            return Je, dJe
        h = self.step
        Je = self._je(self._solve(phi, 1))
        dJe = (self._je(self._solve(phi + h, 1)) - self._je(self._solve(phi - h, 1))) / (2 * h)
        return Je, dJe


def _check_on_link(topo: Topology, link: int, origin: Optional[str], what: str) -> None:
    if link not in topo.links:
        raise ForceModelError(f"{what}: link {link} does not move", ("link", link))
    if origin is not None and link not in topo.members.get(origin, ()):
        raise ForceModelError(f"{what}: point '{origin}' is not on link {link}",
                              ("point", origin))


# ---------------------------------------------------------------------------
# the equivalent moment of a linkage's loads
# ---------------------------------------------------------------------------
def linkage_moment(linkage: Linkage, topo: Topology, bodies: Any,
                   gravity: Optional[Tuple[float, float]], programs: Any, phi: np.ndarray, *,
                   followers: Optional[Any] = None) -> np.ndarray:
    """Me(φ) of the external loads and gravity on a linkage (eq 6-2).

    The power of every load at unit input speed (the velocity coefficients):

    .. math:: M_e = \\sum_{loads} (F \\cdot v_P + M\\, \\omega_i)/\\omega_1
              + \\sum_{bodies} m_i\\, g \\cdot v_{Si}/\\omega_1

    with P the load's point (its link's centre of mass by default) and ω_i the angular
    velocity of the link it acts on.  By virtual power, the kinetostatic balancing torque
    of the massless linkage under the same loads is −Me; with masses it is
    Je α1 + ½ dJe/dφ ω1² − Me (eq 6-8).

    Parameters
    ----------
    linkage : Linkage
    topo : Topology
        ``topology(linkage)``.
    bodies : dict
        ``{link: Body}``: masses for gravity and the centres of mass (where a load with no
        point acts).
    gravity : (gx, gy) or None
        [m/s²].
    programs : sequence of LoadProgram
        The loads with their programs over the input (``LoadProgram.evaluate``): windows
        and tables in φ; a velocity-sign condition is read at unit input speed, i.e. for
        ω1 > 0; a stroke band must already be fixed to absolute limits
        (``with_band_limits``).
    phi : array
        Input positions [rad].
    followers : dict, optional
        ``{link: (ratio, phase)}`` of secondary drivers.

    Returns
    -------
    ndarray
        Me [N m] (an equivalent force [N], eq 6-1, for a linear primary driver), of the
        broadcast shape of ``phi`` and the linkage.

    Raises
    ------
    DescribedError
        ``reason="cannot_assemble"`` or ``"dead_point"`` (``angle``), as
        :class:`LinkageInertia`.
    ForceModelError
        A load or body on a link that does not move, or at a point not on its link.
    ValueError
        A stroke-band program without absolute limits.
    """
    phi = np.asarray(phi, dtype=float)
    m = kinematic_coefficients(linkage, phi, followers or None, order=2)
    _check_regular(m, phi)
    shape = np.shape(m.feasible)
    Me = np.zeros(shape)
    if gravity is not None:
        gx, gy = gravity
        for link, b in bodies.items():
            _check_on_link(topo, link, b.origin, f"the body of link {link}")
            if not np.any(b.mass) or not (gx or gy):
                continue
            where: Tuple[str, Optional[float], Optional[float]] = com_of(topo, b, link)
            vx, vy, _ax, _ay = _point_motion(m, topo, link, *where, False)
            Me = Me + b.mass * (gx * vx + gy * vy)
    for p in programs:
        if p.band is not None and p.band_limits is None:
            raise ValueError(f"load '{p.load.name}': fix its stroke band to absolute limits "
                             "first (LoadProgram.with_band_limits)")
        ld, _on = p.evaluate(phi, m)
        link = ld.link
        _check_on_link(topo, link, ld.origin, f"load '{ld.name}'")
        k = m.links[link]
        fx, fy = ld.fx, ld.fy
        if ld.relative:
            c, s = np.cos(k.theta), np.sin(k.theta)
            fx, fy = fx * c - fy * s, fx * s + fy * c
        if np.any(fx) or np.any(fy):
            if ld.origin is None:
                where = com_of(topo, bodies.get(link) or Body(link), link)
            else:
                where = (ld.origin, ld.along, ld.normal)
            vx, vy, _ax, _ay = _point_motion(m, topo, link, *where, False)
            Me = Me + fx * vx + fy * vy
        if np.any(ld.torque):
            Me = Me + ld.torque * k.omega
    return np.array(np.broadcast_to(Me, shape))


class SampledInertia(InertiaModel):
    """A periodic inertia model sampled once, then interpolated by cubic Hermite.

    The equation of motion evaluates Je and dJe/dφ tens of thousands of times; a
    :class:`LinkageInertia` costs an engine solve each time.  This samples the model's
    exact ``(Je, dJe)`` at ``samples`` equally spaced angles over its period and
    interpolates: Je by the cubic Hermite of the values and slopes (error about
    h⁴/384·max|Je⁗| for the step h), dJe/dφ by that cubic's derivative (error about
    h³/72·max|Je⁗|), so the pair stays consistent.

    Parameters
    ----------
    model : InertiaModel
        A periodic model (``model.period`` not None).
    samples : int
        Angles per period (3600: every 0.1°).
    """

    period: float

    def __init__(self, model: LinkageInertia, samples: int = 3600) -> None:
        if model.period is None:
            raise ValueError("only a periodic inertia model can be sampled")
        self.period, self.constant, self.samples = model.period, False, int(samples)
        self.h = self.period / self.samples
        grid = np.arange(self.samples) * self.h
        J, dJ = model(grid)
        self._J, self._dJ = np.asarray(J, dtype=float), np.asarray(dJ, dtype=float)
        self.added = 0.0        # model(grid) already holds model.added

    def _evaluate(self, phi: np.ndarray) -> Any:
        u = np.mod(phi, self.period) / self.h
        i = np.minimum(np.floor(u).astype(int), self.samples - 1)
        t = u - i
        j = (i + 1) % self.samples
        y0, y1 = self._J[i], self._J[j]
        m0, m1 = self._dJ[i] * self.h, self._dJ[j] * self.h
        t2, t3 = t * t, t * t * t
        J = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * m0 \
            + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * m1
        dJ = ((6 * t2 - 6 * t) * y0 + (3 * t2 - 4 * t + 1) * m0
              + (-6 * t2 + 6 * t) * y1 + (3 * t2 - 2 * t) * m1) / self.h
        return J, dJ
