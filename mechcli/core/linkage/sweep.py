"""A sweep of a linkage's primary input and what its analysis reports: the input
program (:class:`Sweep`), the quantities (:func:`default_quantities`), the extremes,
toggles, dead points and the :class:`SweepResult` of
:func:`~mechcli.core.linkage.kinematics.analyse_sweep`; small helpers the steps share."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.linkage.engine import DriverMotion, Linkage, LinkageMotion
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:  # the annotation of SweepResult.accuracy only
    from mechcli.core.linkage.accuracy import Accuracy

#: sin(gamma) below which an interior minimum is flagged as near a dead point
NEAR_TOGGLE_SIN = 0.05


# Records holding arrays compare by identity (``eq=False``, as the engine's motion
# records): ``==`` cannot compare arrays as a whole.
@record(eq=False)
class Sweep:
    """The input program.

    Attributes
    ----------
    driver : int
        Link number of the primary driver.
    q : ndarray
        Input positions: crank angle [rad] or slide [m].
    dq, ddq : float, array or callable
        Input velocity [rad/s or m/s] and acceleration.  A float is the same
        at every position (the book's ``omega1``, ``alpha1``); an array of
        the shape of ``q`` gives the values at ``q`` (interpolated linearly
        between them, periodically when ``periodic``: e.g. omega(phi) of a
        flywheel run); a callable ``f(q)`` is evaluated wherever the
        analysis needs it (exact).
    followers : dict
        ``{link: (ratio, phase)}`` of secondary drivers.
    periodic : bool
        The sweep covers whole turns of every driver (extremes wrap around).
    """

    driver: int
    q: np.ndarray
    dq: object = 1.0
    ddq: object = 0.0
    followers: Dict[int, Tuple[float, float]] = dataclasses.field(default_factory=dict)
    periodic: bool = False

    def _at(self, value: Any, q: np.ndarray):
        if callable(value):
            return np.asarray(value(q), dtype=float)
        if np.ndim(value) == 0:
            return value
        value = np.asarray(value, dtype=float)
        if value.shape != np.shape(self.q):
            raise ValueError(f"an input rate array must have the shape of q {np.shape(self.q)}, "
                             f"got {value.shape}")
        if q is self.q:
            return value
        nodes = np.asarray(self.q, dtype=float)
        if nodes.ndim != 1:
            raise ValueError(f"an input rate array needs a one-dimensional q, got shape "
                             f"{nodes.shape}")
        if nodes.size > 1 and nodes[-1] < nodes[0]:
            nodes, value = nodes[::-1], value[::-1]  # np.interp needs rising nodes
        if nodes.size > 1 and np.any(np.diff(nodes) <= 0):
            raise ValueError("an input rate array needs q strictly monotonic, to interpolate "
                             "between its values")
        return np.interp(q, nodes, value, period=2 * np.pi if self.periodic else None)

    def speed(self, q: np.ndarray):
        """Input velocity at ``q`` (a float when it is constant)."""
        return self._at(self.dq, q)

    def inputs(self, q: np.ndarray):
        q = np.asarray(q, dtype=float)
        dq, ddq = self._at(self.dq, q), self._at(self.ddq, q)
        out = {self.driver: DriverMotion(q, dq, ddq)}
        for link, (ratio, phase) in self.followers.items():
            out[link] = DriverMotion(phase + ratio * q, ratio * dq, ratio * ddq)
        return out


@record
class Quantity:
    """One output quantity as a function of the solved motion.

    ``kind`` is one of ``angle`` [rad], ``angvel`` [rad/s], ``angacc``
    [rad/s^2], ``length`` [m], ``velocity`` [m/s], ``acceleration`` [m/s^2];
    ``order`` the derivative order it needs; ``rate`` (optional) its exact
    time derivative, which needs ``order + 1`` (used to locate extremes).
    """

    symbol: str
    kind: str
    order: int
    get: Callable[[LinkageMotion], np.ndarray]
    rate: Optional[Callable[[LinkageMotion], np.ndarray]] = None
    #: what it belongs to: ``("link", n)``, ``("slide", name)``, ``("point", name)``
    #: or ``("joint", name)`` (a transmission angle); None: unknown (the accuracy
    #: estimate then takes the worst dyad of the linkage)
    source: Optional[tuple] = None

    @property
    def is_angle(self):
        return self.kind == "angle"


@record
class Extreme:
    """An extreme ``value`` at input ``at`` [rad or m]; ``bounded`` is False for a
    velocity or acceleration found at the edge of a gap (a dead point or an
    assembly limit), where it grows without bound."""

    value: float
    at: float
    bounded: bool = True
    #: half-width of the final bracket of the refinement [rad or m]: the
    #: extreme's input lies within ``at ± tol``
    tol: float = 0.0
    #: the quantity does not vary beyond round-off over the sweep (a coupler's ω that
    #: equals the crank's, an α that is zero in truth): ``value`` holds everywhere and
    #: ``at`` is only where the search stopped, not a location
    constant: bool = False


@record
class Toggle:
    """A dead/toggle position: dyad ``joint`` with sin(gamma) = ``sin_gamma`` at ``at``."""

    at: float
    joint: str
    kind: str
    sin_gamma: float


@record
class DeadPoint:
    """An isolated dead point: the dyad ``joint``'s sin(gamma) reaches 0 at input ``at``
    [rad or m], located to ``at ± tol``.

    ``interval`` is the excluded interval it lies in (``SweepResult.excluded``: the
    inputs where sin(gamma) <= ``SINGULAR_TOL``, whose width that threshold sets).
    ``shape`` says how sin(gamma) reaches 0: ``"touch"`` (it falls to 0 and rises again:
    a change point, the folded kite; located as the minimum of sin^2(gamma), smooth there)
    or ``"limit"`` (the dyad's discriminant crosses 0 and the linkage cannot go on:
    located as that root, e.g. a slider-crank driven by its slider at a stroke end).
    :func:`analyse_sweep` reports a ``"limit"`` as what it is, a limit of assembly (a
    ``cannot assemble`` interval's end), not among its dead points.
    """

    at: float
    tol: float
    joint: str
    kind: str
    interval: Tuple[float, float]
    shape: str = "touch"


@record(eq=False)
class SweepResult:
    """Kinematics over the regular positions of a sweep.

    Attributes
    ----------
    q : ndarray
        Input positions analysed.
    values : dict
        ``symbol -> ndarray`` for every requested quantity (angles unwrapped,
        continuously across 0°/360° where the analysed arc passes it).
    extremes : dict
        ``symbol -> (max Extreme, min Extreme)``.
    excluded : list of (float, float, str)
        Input intervals left out, with the reason (``cannot assemble`` or
        ``dead point``).  The ends of a ``cannot assemble`` interval are the roots of
        the failing dyad's discriminant (:func:`assembly_limits`); those of a ``dead
        point`` interval the last regular inputs (sin(gamma) > ``SINGULAR_TOL``).
    toggles : list of Toggle
        Near-dead positions (refined minima of sin(gamma) below
        ``NEAR_TOGGLE_SIN``) and the refined ends of excluded intervals.
    motion : LinkageMotion
        Engine output at ``q`` (for drawings and animations).
    runs : list of (int, int)
        Index ranges of ``q`` that are continuous arcs of the input.
    """

    q: np.ndarray
    values: Dict[str, np.ndarray]
    extremes: Dict[str, Tuple[Extreme, Extreme]]
    excluded: list
    toggles: list
    motion: LinkageMotion
    runs: list = dataclasses.field(default_factory=list)
    #: estimated correct digits (:class:`Accuracy`); None when not estimated
    accuracy: Optional[Accuracy] = None
    #: per excluded interval, how closely its two ends are located [rad or m]: a
    #: ``cannot assemble`` end is the root of the dyad's discriminant (to the
    #: rounding of the inputs, see :func:`assembly_limits`), a ``dead point`` end the
    #: last regular input (sin(gamma) = ``SINGULAR_TOL``, to 1e-15 relative)
    excluded_tol: list = dataclasses.field(default_factory=list)
    #: isolated dead points, one input each (:class:`DeadPoint`), in order: zeros of a
    #: dyad's sin(gamma) with the linkage assembled on both sides (shape ``"touch"``).  A
    #: limit of assembly (the linkage does not assemble beyond it) is not one: it is the
    #: end of a ``cannot assemble`` interval of ``excluded``, also where the sweep ends
    #: exactly on it (:func:`_limits_are_not_dead_points`)
    dead_points: list = dataclasses.field(default_factory=list)
    #: ``symbol -> [(at, tol), ...]``: the inputs where a slide's acceleration is 0
    #: (its velocity is greatest in either direction there when the input speed is
    #: constant), refined between samples of opposite sign (:func:`zero_crossings`)
    zeros: Dict[str, list] = dataclasses.field(default_factory=dict)


def _gamma_of(joint: str):
    """The getter of the transmission angle at *joint* [rad]."""
    return lambda m: m.condition(joint).gamma


def default_quantities(linkage: Linkage, order: int, tracers: Any = ()):
    """The book's quantities: angles/ω/α of every rotating non-driver link, every
    slide s/v/a, the transmission angle of every RRR dyad, and x, y (vx, vy, ax,
    ay) of every tracer point.
    """
    out = []
    rotating = linkage.rotating_links
    slides = linkage.slide_names
    # (symbol prefix, kind, attribute) per derivative order, for links, slides, points
    table = (
        (("theta", "angle", "theta"), ("s", "length", "s"),
         (("x", "length", "x"), ("y", "length", "y"))),
        (("omega", "angvel", "omega"), ("v", "velocity", "v"),
         (("vx", "velocity", "vx"), ("vy", "velocity", "vy"))),
        (("alpha", "angacc", "alpha"), ("a", "acceleration", "a"),
         (("ax", "acceleration", "ax"), ("ay", "acceleration", "ay"))),
    )

    def getter(group: Any, key: Any, attr: str):
        return lambda m: getattr(getattr(m, group)[key], attr)

    # a linkage given by its joints measures a link's angle from its first joint to its
    # second as drawn: the engine's angle plus a constant (Linkage.angle_offsets)
    offsets = dict(linkage.angle_offsets)

    def angle(n: int):
        off = offsets.get(n, 0.0)
        if not off:
            return getter("links", n, "theta")
        return lambda m: m.links[n].theta + off

    for k in range(order + 1):
        (lp, lkind, lattr), (sp, skind, sattr), pts = table[k]
        nxt = table[k + 1] if k < 2 else None
        for n in rotating:
            get = angle(n) if lattr == "theta" else getter("links", n, lattr)
            out.append(Quantity(f"{lp}{n}", lkind, k, get,
                                getter("links", n, nxt[0][2]) if nxt else None, ("link", n)))
        for name in slides:
            out.append(Quantity(f"{sp}{name}", skind, k, getter("slides", name, sattr),
                                getter("slides", name, nxt[1][2]) if nxt else None,
                                ("slide", name)))
        for tr in tracers:
            for j, (pp, pkind, pattr) in enumerate(pts):
                out.append(Quantity(f"{pp}{tr}", pkind, k, getter("points", tr, pattr),
                                    getter("points", tr, nxt[2][j][2]) if nxt else None,
                                    ("point", tr)))
        if k == 0:
            for joint in linkage.transmission_joints:
                out.append(Quantity(f"gamma{joint}", "angle", 0, _gamma_of(joint),
                                    source=("joint", joint)))
    return out


def _take(motion: LinkageMotion, idx: Any) -> LinkageMotion:
    """Restrict every array of a motion to the positions ``idx``."""
    def cut(x: Any):
        return None if x is None else x[idx]
    pts = {k: type(v)(cut(v.x), cut(v.y), cut(v.vx), cut(v.vy), cut(v.ax), cut(v.ay))
           for k, v in motion.points.items()}
    lks = {k: type(v)(cut(v.theta), cut(v.omega), cut(v.alpha)) for k, v in motion.links.items()}
    sls = {k: dataclasses.replace(v, s=cut(v.s), v=cut(v.v), a=cut(v.a))
           for k, v in motion.slides.items()}
    cds = tuple(dataclasses.replace(c, sin_gamma=cut(c.sin_gamma), cos_joint=cut(c.cos_joint))
                for c in motion.conditions)
    return LinkageMotion(motion.order, motion.feasible[idx], motion.regular[idx], pts, lks,
                         sls, cds)


def _wrap(x: FloatOrArray):
    return (x + np.pi) % (2 * np.pi) - np.pi


def _periodic(x: Any, q0: Any, period: Any):
    """``x`` mapped into [q0, q0 + period), snapping round-off next to q0 onto q0."""
    y = q0 + (x - q0) % period
    if abs(y - q0) < 1e-9 or abs(y - q0 - period) < 1e-9:
        return float(q0)
    return float(y)


def _dedupe(toggles):
    out = []
    for t in toggles:
        if out and abs(out[-1].at - t.at) < 1e-9 and out[-1].joint == t.joint:
            continue
        out.append(t)
    return out


def _unwrap_runs(v: Any, runs: Sequence[Tuple[int, int]], connected: bool):
    out = v.copy()
    for (i0, i1) in runs:
        seg = np.unwrap(v[i0:i1])
        out[i0:i1] = seg - (seg[0] - _wrap(seg[0]))  # first value in (-pi, pi]
    if connected:
        # the last run continues into the first through 360° = 0°: same pose
        i0, i1 = runs[0]
        j0, j1 = runs[-1]
        out[i0:i1] += 2 * np.pi * np.round((out[j1 - 1] - out[i0]) / (2 * np.pi))
    return out
