"""Kinematic analysis of a linkage over a sweep of its primary input.

:func:`analyse_sweep` solves the linkage engine over the sweep, finds where it
cannot assemble (or is at a dead point) and refines those boundaries by
bisection, restricts the analysis to the regular positions when asked, and
refines the extremes of every requested quantity by a bracketed search on the
exact solution (to 1e-15 ... 1e-10 rad of input angle, each with its tolerance); gives
every dead point as one input with its uncertainty (:func:`dead_points`) and the ends of
every gap as the roots of a dyad's discriminant (:func:`assembly_limits`).

Secondary drivers (a 2-DOF five-bar driven by two geared cranks) follow the
primary one linearly: ``q_k = phase_k + ratio_k * q_1``.
"""

from __future__ import annotations

import dataclasses
from typing import Callable, Dict, Optional, Tuple

import numpy as np

from mechcli.core.errors import AssemblyError
from mechcli.core.linkage.engine import DriverMotion, Linkage, LinkageMotion, solve
from mechcli.core.records import record
from mechcli.core.refine import bisect, bracketed_root, sorted_union, true_runs

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

    def _at(self, value, q):
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

    def speed(self, q):
        """Input velocity at ``q`` (a float when it is constant)."""
        return self._at(self.dq, q)

    def inputs(self, q):
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
    accuracy: Optional["Accuracy"] = None
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


def default_quantities(linkage: Linkage, order: int, tracers=()):
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

    def getter(group, key, attr):
        return lambda m: getattr(getattr(m, group)[key], attr)

    # a linkage given by its joints measures a link's angle from its first joint to its
    # second as drawn: the engine's angle plus a constant (Linkage.angle_offsets)
    offsets = dict(linkage.angle_offsets)

    def angle(n):
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
                out.append(Quantity(f"gamma{joint}", "angle", 0,
                                    lambda m, j=joint: m.condition(j).gamma,
                                    source=("joint", joint)))
    return out


def _take(motion: LinkageMotion, idx) -> LinkageMotion:
    """Restrict every array of a motion to the positions ``idx``."""
    def cut(x):
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


def _bisect_boundaries(linkage, sweep, order, good, bad):
    """Refine boundaries between regular inputs ``good`` and irregular ``bad``.

    Returns the last regular input of every pair (to ~1e-15 relative).
    """
    def regular(mid):
        return solve(linkage, sweep.inputs(mid), order=order).regular

    return bisect(good, bad, regular, 1e-15)[0]


def _wrap(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


#: sin(gamma) at or below this is zero to round-off: a dyad's sin(gamma) is the root of
#: its (rounded) discriminant, clipped at 0 where that is negative, and its rounding
#: noise there is a few EPS, so sin(gamma)^2 = 1e-26 is 1e-26 / slope past the root
SIN_ZERO = 1e-13
#: the rounding of a dyad's sin(gamma)^2 (proportional to its discriminant), relative to
#: 1: a few operations on the rounded inputs (a crank's cos/sin, the lengths).  Measured
#: on the four-bar gap of tests/unit/test_gap_boundaries.py against a 40-digit root:
#: 9.4 EPS; about 3.5 times that is taken
ROUNDING = 32 * float(np.finfo(float).eps)


def _assembles(linkage, sweep, x):
    """Does the linkage assemble at inputs ``x`` with every dyad's discriminant > 0?
    Also returns the smallest sin(gamma) of the dyads there."""
    m = solve(linkage, sweep.inputs(np.asarray(x, dtype=float)), order=0)
    low = np.min([c.sin_gamma for c in m.conditions], axis=0) if m.conditions else \
        np.ones(np.shape(x))
    return m.feasible & (low > SIN_ZERO), low


def _input_scale(linkage, sweep):
    """1 rad for a crank, the sweep's span [m] for a slider: what 'relative' input means."""
    if linkage.driver(sweep.driver).rotary:
        return 1.0
    q = np.asarray(sweep.q, dtype=float)
    return max(float(abs(q[-1] - q[0])) if q.size else 0.0, float(np.max(linkage.scale())))


def assembly_limits(linkage, sweep, inside, outside, iterations=80):
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


def _touch_minimum(linkage, sweep, ci, c0, R):
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


class _Domain:
    """The analysed input domain: continuous arcs (runs) of the grid ``q``, how
    far each run really extends (refined assembly limits), and whether the
    last run continues into the first one through a whole turn (periodic)."""

    def __init__(self, q, runs, lo_ext, hi_ext, connected, period, ends=None):
        self.q, self.runs = q, runs
        self.ends = ends if ends is not None else (q[0], q[-1])
        self.lo_ext, self.hi_ext = lo_ext, hi_ext  # per run: input where it really ends
        self.connected, self.period = connected, period

    def is_gap_edge(self, b):
        """Is input ``b`` the refined edge of a gap (not an end of the sweep)?"""
        return self.ends[0] < b < self.ends[1]

    def bracket(self, r, k, wraps=True):
        """Input interval around grid index ``k`` of run ``r`` to search for an extreme.

        ``wraps``: the quantity returns to its value after a whole turn, so the
        search may continue through 360° = 0°.
        """
        q = self.q
        i0, i1 = self.runs[r]
        connected = self.connected and wraps
        if k > i0:
            lo = q[k - 1]
        elif connected and r == 0:
            j0, j1 = self.runs[-1]
            lo = q[j1 - 2] - self.period if j1 - j0 > 1 else q[k]
        else:
            lo = self.lo_ext[r]
        if k < i1 - 1:
            hi = q[k + 1]
        elif connected and r == len(self.runs) - 1:
            j0, j1 = self.runs[0]
            hi = q[j0 + 1] + self.period if j1 - j0 > 1 else q[k]
        else:
            hi = self.hi_ext[r]
        return lo, hi


def _steady(sweep):
    """The sweep with no input acceleration, where its input speed is one constant
    (None otherwise).

    The time rate of a velocity is ``J'(q) dq^2 + J(q) ddq``; its derivative along the
    sweep, ``d(J dq)/dq``, is ``J'(q) dq`` when ``dq`` is one constant, whatever the
    sweep's ``ddq`` (the book's ``alpha1`` is used in the accelerations only, with
    ``omega1`` held at every position).  So with ``ddq = 0`` the rate over ``dq`` is that
    derivative exactly; with ``dq`` varying along the sweep it is not, and a difference
    is taken instead.
    """
    if callable(sweep.dq) or np.ndim(sweep.dq) != 0:
        return None
    if not callable(sweep.ddq) and np.ndim(sweep.ddq) == 0 and sweep.ddq == 0:
        return sweep
    return dataclasses.replace(sweep, ddq=0.0)


def _rate_is_slope(sweep, getter, speed):
    """Does ``getter``'s exact time rate over ``speed`` give its d/dq (see :func:`_steady`)?
    A position's rate (``J dq``) always does; a velocity's only at a constant input speed."""
    return getter[1] is not None and speed != 0 and (
        getter[3] == 0 or _steady(sweep) is not None)


class _SlopeProbe:
    """Sign-carrying d/dq of fixed targets, called on ``rep`` inputs per target (``x`` of
    size ``rep * len(getters)``, target ``j`` at ``x[j::len(getters)]``); returns
    ``(slopes, motion)``.

    ``getters[j]`` is ``(get, rate, is_angle, order)``: with an exact time rate the
    derivative is ``rate / dq``, solved with no input acceleration (:func:`_steady`; one
    solve); otherwise a central difference with step ``h`` (one-sided where a probe
    leaves the regular domain).  The targets are grouped once by quantity, so that a
    call evaluates every quantity's getter once on the solved motion and indexes it,
    whatever the number of targets.
    """

    def __init__(self, linkage, sweep, order, getters, h):
        self.linkage, self.sweep, self.order, self.h = linkage, sweep, order, h
        self.n = len(getters)
        steady = _steady(sweep)
        # exact where the quantity has a rate usable as d/dq (the input speed != 0 is
        # checked per input, :func:`_rate_is_slope`)
        self.has_rate = np.array([g[1] is not None and (g[3] == 0 or steady is not None)
                                  for g in getters], dtype=bool)
        # only positions' rates are used when the input speed varies: they do not
        # depend on ddq
        self.steady = steady if steady is not None else dataclasses.replace(sweep, ddq=0.0)
        self.rate_groups = self._groups(getters, 1)
        self.get_groups = self._groups(getters, 0)
        self._plans = {}

    @staticmethod
    def _groups(getters, slot):
        """``[(function, is_angle, target indices)]``, one entry per distinct function."""
        seen = {}
        for j, g in enumerate(getters):
            fn = g[slot]
            if fn is None:
                continue
            key = (id(fn), g[2])
            if key not in seen:
                seen[key] = (fn, g[2], [])
            seen[key][2].append(j)
        return [(fn, is_angle, np.array(js)) for fn, is_angle, js in seen.values()]

    def _plan(self, rep, exact):
        """Per group, the indices of its targets' inputs among ``rep`` copies, split into
        those taken from the rate (``exact``) and those taken by differences."""
        n = self.n
        out = []
        for groups, keep in ((self.rate_groups, exact), (self.get_groups, ~exact)):
            plan = []
            for fn, is_angle, js in groups:
                at = (js[None, :] + n * np.arange(rep)[:, None]).ravel()
                at = at[keep[at]]
                if at.size:
                    plan.append((fn, is_angle, at))
            out.append(plan)
        return out

    def __call__(self, x):
        x = np.asarray(x, dtype=float)
        sweep = self.sweep
        rep = x.size // self.n
        speed = sweep.speed(x)
        if np.ndim(speed) == 0:   # one input speed: the plan depends on rep only
            key = (rep, speed != 0)
            if key not in self._plans:
                self._plans[key] = self._plan(rep, np.tile(self.has_rate, rep) & (speed != 0))
            rates, diffs = self._plans[key]
        else:
            speed = np.broadcast_to(speed, x.shape)
            rates, diffs = self._plan(rep, np.tile(self.has_rate, rep) & (speed != 0))
        m = m_rate = None
        if diffs:
            probe = np.concatenate([x, x - self.h, x + self.h])
            m = solve(self.linkage, sweep.inputs(probe), order=min(self.order + 1, 2))
        out = np.zeros(x.size)
        if rates:
            m_rate = m if self.steady is sweep and m is not None else \
                solve(self.linkage, self.steady.inputs(x), order=min(self.order + 1, 2))
            for rate, _is_angle, at in rates:
                out[at] = np.asarray(rate(m_rate), dtype=float)[at] / (
                    speed if np.ndim(speed) == 0 else speed[at])
        if diffs:
            N = x.size
            reg = m.regular
            with np.errstate(invalid="ignore", over="ignore"):   # of the sides not taken
                for get, is_angle, at in diffs:
                    f = np.asarray(get(m), dtype=float)
                    f0, fm, fp = f[at], f[N + at], f[2 * N + at]
                    rm, rp = reg[N + at], reg[2 * N + at]
                    d = np.where(rm & rp, fp - fm,
                                 np.where(rp, fp - f0, np.where(rm, f0 - fm, 0.0)))
                    out[at] = _wrap(d) if is_angle else d
        return out, (m if m is not None else m_rate)


def _transmission_measure(joint):
    """A smooth function of the motion that rises and falls with the acute transmission
    angle of the dyad at ``joint`` (``DyadCondition.gamma``): ``-cos_joint**2`` (gamma =
    atan2(|sin|, |cos|) of the joint angle, the largest where its cosine is 0), or
    ``sin_gamma**2`` where the dyad gives no cosine (gamma = asin(sin_gamma)).  Gamma
    folds at 90° (a kink, where its difference quotient has one magnitude either side and
    a secant search on it only bisects); this measure has a smooth extremum there."""
    def measure(m):
        c = m.condition(joint)
        if c.cos_joint is None:
            return c.sin_gamma * c.sin_gamma
        return -(c.cos_joint * c.cos_joint)
    return measure


def _transmission_measure_rate(linkage, joint):
    """The exact time rate of :func:`_transmission_measure` for the RRR dyad whose joint
    is ``joint`` (None for any other dyad).

    With ``ra = J - A`` and ``rb = J - B`` the dyad's two link vectors (A, B its known
    points, J its joint), the joint angle's cosine is ``c = ra.rb / (|ra| |rb|)``; the
    lengths are constant, so ``dc/dt = (dra.rb + ra.drb) / (|ra| |rb|)`` with
    ``dra = vJ - vA``, ``drb = vJ - vB`` (the engine's point velocities, exact), and the
    measure ``-c**2`` has the rate ``-2 c dc/dt``: its extremes are located on an exact
    derivative instead of a central difference (whose O(h**2) bias is 1e-11 rad of input
    on 例 1-1's γC)."""
    el = next((e for e in linkage.elements if e.transmission_joint() == joint), None)
    if el is None or getattr(el, "kind", None) != "RRR":
        return None

    def rate(m):
        c = m.condition(joint).cos_joint
        pj, pa, pb = m.points[el.joint], m.points[el.point_a], m.points[el.point_b]
        rax, ray = pj.x - pa.x, pj.y - pa.y
        rbx, rby = pj.x - pb.x, pj.y - pb.y
        dax, day = pj.vx - pa.vx, pj.vy - pa.vy
        dbx, dby = pj.vx - pb.vx, pj.vy - pb.vy
        dc = (dax * rbx + day * rby + rax * dbx + ray * dby) / (
            np.hypot(rax, ray) * np.hypot(rbx, rby))
        return -2.0 * c * dc
    return rate


def _slope_getters(qt, linkage=None):
    """``(get, rate, is_angle, order)`` whose slope :class:`_SlopeProbe` takes for the
    extremes of ``qt``: its own, but a transmission angle's smooth measure
    (:func:`_transmission_measure`, same extrema) with its exact rate where the dyad
    gives one (:func:`_transmission_measure_rate`)."""
    if qt.rate is None and qt.source and qt.source[0] == "joint" and qt.is_angle:
        rate = None if linkage is None else _transmission_measure_rate(linkage, qt.source[1])
        return (_transmission_measure(qt.source[1]), rate, False, 0)
    return (qt.get, qt.rate, qt.is_angle, qt.order)


def refine_extremes(linkage, sweep, order, quantities, values, domain, iterations=64,
                    max_candidates=6):
    """Max and min of every quantity, located to ~1e-10 rad of input.

    Every local extremum of the grid within each run (the run ends included,
    searched out to the refined assembly limits) is a candidate; each is
    refined on the exact derivative (the next-order quantity of the engine),
    or on a central difference (h = 1e-5 rad) for quantities without one: by
    a safeguarded secant where the derivative changes sign across the
    bracket (:func:`~mechcli.core.refine.bracketed_root`, a few solves), by
    bisection on its sign otherwise; the best refined value wins, reported with the
    input where it was evaluated.  A central difference's bracket closes no further
    than its rounding error (:func:`_difference_tol`); its tolerance adds the bias of the
    difference, measured at the located input (:func:`_truncation_shift`).  A
    transmission angle is refined on a smooth measure with the same extrema
    (:func:`_transmission_measure`: it folds at 90°), on its exact rate for an RRR dyad
    (:func:`_transmission_measure_rate`).  All targets share each solve.
    """
    q = domain.q
    span = float(q[-1] - q[0]) if q.size > 1 else 1.0
    rotary = linkage.driver(sweep.driver).rotary
    h = 1e-5 if rotary else 1e-5 * max(abs(span), 1e-12)
    targets = []  # (symbol index, sign, run, k)
    for qi, qt in enumerate(quantities):
        v = values[qt.symbol]
        for sign in (1.0, -1.0):
            cands = []
            for r, (i0, i1) in enumerate(domain.runs):
                w = sign * v[i0:i1]
                n = w.size
                if n == 1:
                    cands.append((w[0], r, i0))
                    continue
                left = np.concatenate(([-np.inf], w[:-1]))
                right = np.concatenate((w[1:], [-np.inf]))
                for k in np.flatnonzero((w >= left) & (w >= right)):
                    cands.append((w[k], r, i0 + int(k)))
            cands.sort(key=lambda c: -c[0])
            for _val, r, k in cands[:max_candidates]:
                targets.append((qi, sign, r, k))
    if not targets:
        return {}
    lo = np.empty(len(targets))
    hi = np.empty(len(targets))
    wraps = {}
    for qt in quantities:
        v = values[qt.symbol]
        wraps[qt.symbol] = abs(v[-1] - v[0]) <= 1e-9 * max(1.0, float(np.max(np.abs(v))))
    for j, (qi, sign, r, k) in enumerate(targets):
        lo[j], hi[j] = domain.bracket(r, k, wraps[quantities[qi].symbol])
    width0 = np.abs(hi - lo)   # the search brackets, before refinement
    by_quantity = {}   # one getter per quantity: a solve evaluates each once
    for qi, *_ in targets:
        if qi not in by_quantity:
            by_quantity[qi] = _slope_getters(quantities[qi], linkage)
    getters = [by_quantity[qi] for qi, *_ in targets]
    signs = np.array([t[1] for t in targets])

    def slope(idx):
        """Signed derivative of the targets ``idx`` (> 0: the extreme lies further on);
        called with several inputs per target (the probes of :func:`bracketed_root`)."""
        probe, sg = _SlopeProbe(linkage, sweep, order, [getters[i] for i in idx], h), signs[idx]

        def f(x):
            return np.tile(sg, x.size // len(idx)) * probe(x)[0]
        return f

    # The first step of a bisection on the sign of the derivative, with the derivative
    # at both ends too (one solve): the half that bisection keeps either has a sign
    # change (closed by a safeguarded secant: a few solves instead of ~40) or the
    # derivative has one sign over it, and bisection would close on its far end
    # (the end of a run, or no extreme inside): taken directly, as bisection's
    # last bracket.
    n_t = len(targets)
    mid = 0.5 * (lo + hi)
    d = slope(np.arange(n_t))(np.concatenate([lo, mid, hi]))
    d_lo, d_mid, d_hi = d[:n_t], d[n_t:2 * n_t], d[2 * n_t:]
    up = d_mid > 0                       # bisection's keep_lo at the midpoint
    lo, d_lo = np.where(up, mid, lo), np.where(up, d_mid, d_lo)
    hi, d_hi = np.where(up, hi, mid), np.where(up, d_hi, d_mid)
    proper = (d_lo > 0) & ~(d_hi > 0)
    tol = 1e-13 * np.maximum(1.0, np.abs(lo))
    to_hi = ~proper & (d_lo > 0)         # rising throughout: bisection closes on hi
    lo = np.where(to_hi, hi - np.copysign(tol, hi - lo), lo)
    hi = np.where(~proper & ~to_hi, lo + np.copysign(tol, hi - lo), hi)
    if proper.any():
        idx = np.flatnonzero(proper)
        # A central difference locates its extreme no closer than its rounding allows
        # (:func:`_difference_tol`, the tolerance reported for it): its bracket need not
        # close further than that.
        rtol = np.full(idx.size, 1e-13)
        spd0 = np.broadcast_to(sweep.speed(mid), mid.shape)
        for i, j in enumerate(idx):
            if not _rate_is_slope(sweep, getters[j], spd0[j]):
                qi, _sign, r, k = targets[j]
                dtol = _difference_tol(values[quantities[qi].symbol], q, domain.runs[r], k, h)
                rtol[i] = max(1e-13, dtol / max(1.0, abs(float(lo[j]))))
        lo[idx], hi[idx] = bracketed_root(lo[idx], hi[idx], slope(idx), rtol, iterations,
                                          d_lo[idx], d_hi[idx])
    at = 0.5 * (lo + hi)
    spd = np.broadcast_to(sweep.speed(at), at.shape)
    by_diff = np.array([not _rate_is_slope(sweep, getters[j], spd[j]) for j in range(n_t)],
                       dtype=bool)
    diff = np.flatnonzero(by_diff)
    # the targets located on a central difference are solved at +-h and +-2h as well (in
    # the same solve): the bias of the difference (:func:`_truncation_shift`)
    m = solve(linkage, sweep.inputs(np.concatenate(
        [at] + [at[diff] + s * h for s in (-1.0, 1.0, -2.0, 2.0)])), order=order)
    shift = _truncation_shift(m, getters, diff, n_t, h)
    best = {}
    for j, (qi, sign, r, k) in enumerate(targets):
        qt = quantities[qi]
        vgrid = float(values[qt.symbol][k])
        cand = (vgrid, float(q[k]), 0.5 * float(width0[j]))
        if m.regular[j]:
            val = float(qt.get(m)[j])
            if qt.is_angle:
                val = vgrid + float(_wrap(val - vgrid))
            if sign * val >= sign * vgrid:
                # no closer than a few units in the last place of the location itself
                tol = max(0.5 * abs(float(hi[j] - lo[j])), 4.0 * float(np.spacing(abs(at[j]))))
                if by_diff[j]:
                    dtol = _difference_tol(values[qt.symbol], q, domain.runs[r], k, h)
                    tol = max(tol, dtol + TRUNCATION_MARGIN * shift.get(j, 0.0))
                cand = (val, float(at[j]), tol)
        key = (qt.symbol, sign)
        if key not in best or sign * cand[0] > sign * best[key][0]:
            best[key] = cand
    gap_edges = [b for r in range(len(domain.runs))
                 for b in (domain.lo_ext[r], domain.hi_ext[r]) if domain.is_gap_edge(b)]
    out = {}
    for qt in quantities:
        ext = []
        for sign in (1.0, -1.0):
            val, pos, tol = best[(qt.symbol, sign)]
            bounded = qt.order == 0 or not any(
                abs(pos - b) <= 1e-7 * max(1.0, abs(b)) for b in gap_edges)
            if sweep.periodic and domain.connected and wraps[qt.symbol]:
                pos = _periodic(pos, domain.ends[0], domain.period)
            ext.append(Extreme(val, float(pos), bounded, tol))
        out[qt.symbol] = (ext[0], ext[1])
    return out


def zero_crossings(q, values, runs, f, rtol=1e-15, iterations=64):
    """Every input where a sampled function crosses or touches 0, refined.

    Parameters
    ----------
    q, values : ndarray
        The samples (inputs [rad or m], values).
    runs : list of (int, int)
        Index ranges of ``q`` that are continuous arcs (no root is sought across a gap).
    f : callable
        ``f(x) -> ndarray``, the function at inputs ``x`` (one call for all brackets).
    rtol : float
        Relative bracket width at which the search stops.

    Returns
    -------
    list of (float, float)
        ``(at, tol)`` in order: a sample that is exactly 0 is a root with ``tol = 0``;
        a sign change between neighbours is closed by :func:`bracketed_root` and ``tol``
        is half its final bracket (at least a float spacing).
    """
    out, lo, hi, sgn = [], [], [], []
    for i0, i1 in runs:
        w = np.asarray(values[i0:i1], dtype=float)
        for k in np.flatnonzero(w == 0.0):
            out.append((float(q[i0 + k]), 0.0))
        for k in np.flatnonzero(w[:-1] * w[1:] < 0):
            lo.append(q[i0 + k]); hi.append(q[i0 + k + 1]); sgn.append(np.sign(w[k]))
    if lo:
        lo, hi, sgn = np.array(lo, float), np.array(hi, float), np.array(sgn)
        a, b = bracketed_root(lo, hi, lambda x: np.tile(sgn, x.size // sgn.size) * f(x),
                              rtol, iterations)
        for x0, x1 in zip(a, b):
            at = 0.5 * (x0 + x1)
            out.append((float(at), max(0.5 * abs(float(x1 - x0)), float(np.spacing(abs(at))))))
    return sorted(out)


def _slide_zeros(linkage, sweep, order, quantities, values, q, runs, periodic, q0, period):
    """:func:`zero_crossings` of every slide acceleration (``SweepResult.zeros``)."""
    out = {}
    for qt in quantities:
        if qt.kind != "acceleration" or not qt.source or qt.source[0] != "slide" \
                or order < 2:
            continue

        def f(x, qt=qt):
            m = solve(linkage, sweep.inputs(x), order=2)
            return np.where(m.regular, np.asarray(qt.get(m), dtype=float), np.nan)
        roots = zero_crossings(q, values[qt.symbol], runs, f)
        if periodic:   # 0° and 360° of a whole turn are one input
            roots = sorted((_periodic(a, q0, period), t) for a, t in roots)
            roots = [r for i, r in enumerate(roots)
                     if i == 0 or abs(r[0] - roots[i - 1][0]) > max(r[1], roots[i - 1][1])]
        out[qt.symbol] = roots
    return out


#: the estimate of a central difference's bias (:func:`_truncation_shift`) is taken with
#: this margin in a tolerance: its own error is O(h**2) relative (the next term of the
#: series) plus the rounding of its f'' (4 EPS |f| / h**2).  1.25 was measured short on
#: 7 of 529 random four-bars' acceleration extremes (the error up to 2.15x the bias), hence 3
TRUNCATION_MARGIN = 3.0


def _truncation_shift(m, getters, diff, n, h):
    """``{target: |x - x*|}``: how far from the true extreme ``x*`` each target ``j`` of
    ``diff`` (located at ``x``, a root of the central difference of step ``h`` of its
    ``getters[j][0]``) lies, from the motion ``m`` solved at the ``n`` targets' ``x``
    followed by ``x - h``, ``x + h``, ``x - 2h``, ``x + 2h`` of the targets ``diff``.

    The central difference ``D_h = f' + h**2 f'''/6 + O(h**4)`` is biased: its root lies
    ``h**2 f''' / (6 f'')`` from that of ``f'`` (1e-11 rad of input at h = 1e-5 for the
    accelerations of 例 1-1, more than its rounding).  Richardson's combination
    ``(4 D_h - D_2h) / 3 = f' + O(h**4)`` gives ``f'(x)`` itself, and one Newton step
    ``|f'(x) / f''(x)|`` (``f''`` from the same samples) the distance to the extreme.
    It includes the rounding of the differences (``_difference_tol`` bounds it) and the
    bracket's own offset.  A target with a probe that is not regular is left out.
    """
    out = {}
    if diff.size == 0:
        return out
    nd = diff.size
    reg = m.regular
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        for i, j in enumerate(diff):
            at = [j] + [n + s * nd + i for s in range(4)]
            if not np.all(reg[at]):
                continue
            get, _rate, is_angle, _order = getters[j]
            f = np.asarray(get(m), dtype=float)
            f0, fm1, fp1, fm2, fp2 = (float(f[a]) for a in at)

            def dif(a, b, is_angle=is_angle):
                return float(_wrap(a - b)) if is_angle else a - b
            d1 = dif(fp1, fm1) / (2.0 * h)
            d2 = dif(fp2, fm2) / (4.0 * h)
            f2 = (dif(fp1, f0) - dif(f0, fm1)) / (h * h)
            est = abs((4.0 * d1 - d2) / 3.0 / f2) if f2 != 0.0 else np.inf
            if np.isfinite(est):
                out[int(j)] = est
    return out


def _difference_tol(v, q, run, k, h):
    """How closely a central difference of step ``h`` locates the extreme of the samples
    ``v`` near grid index ``k``: its rounding, about 2 EPS |f|, over its slope
    2 h |f''| (f'' from the grid's second difference at ``k``), with a factor 2 of
    margin: ``4 EPS |f| / (h |f''|)``.  0 where the grid cannot tell f''."""
    i0, i1 = run
    if not i0 < k < i1 - 1:
        return 0.0
    d2 = abs(float(v[k - 1] - 2 * v[k] + v[k + 1]))
    dq = 0.5 * float(q[k + 1] - q[k - 1])
    if d2 == 0.0 or dq <= 0.0:
        return 0.0
    f2 = d2 / (dq * dq)
    peak = float(np.max(np.abs(v[i0:i1])))
    return 4.0 * EPS * peak / (h * f2)


def _scan_gaps(linkage, sweep, order, q, motion, runs):
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

    def falling(mid):
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


# ---------------------------------------------------------------------------
# accuracy: how many digits the float64 solution keeps near a singular position
# ---------------------------------------------------------------------------
#: the rounding unit of float64 (2.2e-16): one operation's relative error
EPS = float(np.finfo(float).eps)
#: the most significant digits a float64 result can have, -log10(EPS)
FULL_DIGITS = -np.log10(EPS)
#: the classes the estimate reports, by derivative order (the force solve is "forces")
ACCURACY_CLASSES = ("positions", "velocities", "accelerations")
#: warn when fewer correct significant digits than this remain (``[output] accuracy_warn``)
ACCURACY_WARN = 8.0
#: error model (see docs/accuracy.md): the error of a quantity of derivative order k
#: is ``C[k] * EPS * kappa**(k + 1)`` times its natural scale (1 rad or the linkage's
#: scale L, times omega1**k, with alpha1 added for k = 2), where kappa is the product
#: of 1/sin(gamma) of the dyads it depends on.  C is calibrated against a 60-digit
#: mpmath reference of a four-bar at 1e-3 ... 1e-13 from its change point
#: (tests/unit/test_accuracy_estimate.py): the estimate of the worst position is
#: within 0.2 digits of the true loss there (without C it was 0.6 digits optimistic).
ACCURACY_C = (4.0, 1.0, 3.0)
_ORDER_OF_KIND = {"angle": 0, "length": 0, "angvel": 1, "velocity": 1, "angacc": 2,
                  "acceleration": 2}


@record
class AccuracyRange:
    """A continuous range of inputs where a class keeps fewer digits than asked:
    ``digits`` the fewest there (by ``symbol``, at input ``at``), ``start``/``stop``
    the inputs of the range [rad or m]."""

    quantity: str
    start: float
    stop: float
    digits: float
    symbol: str
    at: float


@record
class Accuracy:
    """Estimated correct significant digits, per position and per quantity.

    The digits count relative to the quantity's largest magnitude over the
    analysed range (so a value passing through zero does not "lose" digits).

    Attributes
    ----------
    q : ndarray
        Inputs where the estimate was made: the output rows and the refined
        near-dead positions (sorted).
    segment : ndarray of int
        Continuous arc (run) of every input; a range never crosses a gap.
    digits : dict
        Class (``positions``, ``velocities``, ``accelerations``, ``forces``) ->
        per-input fewest digits of its quantities.
    worst : dict
        Class -> per-input symbol of the quantity with those fewest digits.
    by_quantity : dict
        Symbol -> fewest digits over the range.
    """

    q: np.ndarray
    segment: np.ndarray
    digits: Dict[str, np.ndarray]
    worst: Dict[str, np.ndarray]
    by_quantity: Dict[str, float]

    def minimum(self):
        """Class -> fewest estimated digits over the range (0 ... 15.7)."""
        return {k: float(np.min(v)) for k, v in self.digits.items() if np.size(v)}

    def ranges(self, threshold=ACCURACY_WARN):
        """Every continuous range of inputs where a class keeps fewer than
        ``threshold`` digits: one :class:`AccuracyRange` per range and class."""
        out = []
        for cls, d in self.digits.items():
            low = d < threshold
            if not low.any():
                continue
            for a, b in true_runs(low):
                # split where the arc changes (an excluded gap in between)
                cuts = [a] + [i for i in range(a + 1, b) if self.segment[i] != self.segment[i - 1]]
                for i0, i1 in zip(cuts, cuts[1:] + [b]):
                    k = i0 + int(np.argmin(d[i0:i1]))
                    out.append(AccuracyRange(cls, float(self.q[i0]), float(self.q[i1 - 1]),
                                             float(d[k]), str(self.worst[cls][k]),
                                             float(self.q[k])))
        return out


def amplification(linkage: Linkage, motion: LinkageMotion):
    """How much each solved thing amplifies the rounding of the inputs.

    Returns ``{("link", n) | ("point", name) | ("slide", name) | ("joint", name)
    | ("all",): kappa}``: kappa is the product of 1/sin(gamma) of the dyads the
    thing depends on (through the solving order), an array over the positions
    (1 far from every singular position).  ``("all",)`` is the worst of them.
    """
    frame = linkage.frame
    own = {}
    for c in motion.conditions:
        own[c.element] = 1.0 / np.maximum(np.asarray(c.sin_gamma, dtype=float), EPS)
    point, link, out = {}, {}, {}
    worst = np.ones(np.shape(motion.feasible))
    for idx in linkage.order:
        el = linkage.elements[idx]
        pts, lks = el.needs()
        amp = 1.0
        for p in pts:
            amp = np.maximum(amp, point.get(p, 1.0))
        for k in lks:
            if k != frame:
                amp = np.maximum(amp, link.get(k, 1.0))
        if idx in own:
            amp = amp * own[idx]
        made_p, made_l = el.makes()
        for p in made_p:
            point[p] = amp
        for k in made_l:
            link[k] = amp
        for name in el.slide_names(frame):
            out[("slide", name)] = amp
        joint = el.transmission_joint()
        if joint is not None:
            out[("joint", joint)] = amp
        worst = np.maximum(worst, amp)
    out.update({("point", p): a for p, a in point.items()})
    out.update({("link", k): a for k, a in link.items()})
    out[("all",)] = worst
    return out


def _digits(err_over_scale):
    """Correct significant digits of a relative error (0 ... FULL_DIGITS)."""
    r = np.maximum(np.asarray(err_over_scale, dtype=float), EPS)
    return np.clip(-np.log10(r), 0.0, FULL_DIGITS)


def estimate_accuracy(linkage, sweep, quantities, values, extremes, q, motion, segment):
    """Digits-lost estimate of every quantity at inputs ``q`` (see :class:`Accuracy`).

    ``values``/``extremes`` give each quantity's largest magnitude over the
    sweep; ``motion`` is the engine's solution at ``q``; ``segment`` the run
    of every input.
    """
    amp = amplification(linkage, motion)
    rotary = linkage.driver(sweep.driver).rotary
    L = float(np.max(linkage.scale()))
    speed = np.abs(np.broadcast_to(np.asarray(sweep.speed(q), dtype=float), q.shape))
    accel = np.abs(np.broadcast_to(np.asarray(sweep._at(sweep.ddq, q), dtype=float), q.shape))
    if not rotary:
        speed, accel = speed / L, accel / L
    natural = (np.ones_like(q), speed, speed * speed + accel)
    digits, worst, by_q = {}, {}, {}
    for qt in quantities:
        k = _ORDER_OF_KIND.get(qt.kind)
        if k is None or k > motion.order:
            continue
        v = np.abs(np.asarray(values[qt.symbol], dtype=float))
        peak = float(np.max(v)) if v.size else 0.0
        if qt.symbol in extremes:
            peak = max([peak] + [abs(e.value) for e in extremes[qt.symbol] if e.bounded])
        length = qt.kind in ("length", "velocity", "acceleration")
        if k == 0:
            # an angle is good to EPS of a radian, a length to EPS of the linkage
            peak = max(peak, L if length else 1.0)
        if peak == 0.0:
            continue   # identically zero (no input speed): exact
        kappa = amp.get(qt.source, amp[("all",)]) if qt.source else amp[("all",)]
        kappa = np.broadcast_to(kappa, q.shape)
        if k == 0:
            # a position near an assembly limit loses at most half its digits (a square root)
            kappa = np.minimum(kappa, 1.0 / np.sqrt(EPS))
        err = ACCURACY_C[k] * EPS * kappa ** (k + 1) * natural[k] * (L if length else 1.0)
        d = _digits(err / peak)
        by_q[qt.symbol] = float(np.min(d))
        cls = ACCURACY_CLASSES[k]
        if cls not in digits:
            digits[cls] = d.copy()
            worst[cls] = np.full(q.shape, qt.symbol, dtype=object)
        else:
            lower = d < digits[cls]
            digits[cls] = np.where(lower, d, digits[cls])
            worst[cls] = np.where(lower, qt.symbol, worst[cls])
    return Accuracy(q, segment, digits, worst, by_q)


def _accuracy_of_sweep(linkage, sweep, quantities, order, q, values, extremes, motion, runs,
                       toggles):
    """:func:`estimate_accuracy` on the output rows and the refined near-dead positions
    (a singular position between two rows is not missed)."""
    segment = np.repeat(np.arange(len(runs)), [b - a for a, b in runs]) if runs else \
        np.zeros(q.size, dtype=int)
    extra = np.array([t.at for t in toggles
                      if q.size and q[0] <= t.at <= q[-1] and not np.any(q == t.at)],
                     dtype=float)
    if extra.size:
        m_extra = solve(linkage, sweep.inputs(extra), order=order)
        keep = m_extra.regular
        extra = extra[keep]
    if extra.size:
        m_extra = _take(m_extra, np.flatnonzero(keep))
        q_all = np.concatenate([q, extra])
        sort = np.argsort(q_all, kind="stable")
        seg_extra = segment[np.clip(np.searchsorted(q, extra) - 1, 0, max(q.size - 1, 0))]
        seg = np.concatenate([segment, seg_extra])[sort]
        motion = _concat_motion(motion, m_extra, sort)
        q_all = q_all[sort]
    else:
        q_all, seg = q, segment
    return estimate_accuracy(linkage, sweep, quantities, values, extremes, q_all, motion, seg)


def _concat_motion(a: LinkageMotion, b: LinkageMotion, sort) -> LinkageMotion:
    """Two motions' positions joined, then reordered by ``sort`` (conditions only:
    what the accuracy estimate reads)."""
    def cat(x, y):
        return None if x is None or y is None else np.concatenate([x, y])[sort]
    cds = tuple(dataclasses.replace(c, sin_gamma=cat(c.sin_gamma, d.sin_gamma),
                                    cos_joint=cat(c.cos_joint, d.cos_joint))
                for c, d in zip(a.conditions, b.conditions))
    return LinkageMotion(a.order, cat(a.feasible, b.feasible), cat(a.regular, b.regular),
                         {}, {}, {}, cds)


#: the extremes and dead points are searched on a grid at least this fine
#: (rotary input [rad]; linear inputs use span / 720), whatever the output step
SEARCH_STEP = np.radians(0.5)


def analyse_sweep(linkage: Linkage, sweep: Sweep, quantities, order: int,
                  partial: bool = False, extremes: bool = True) -> SweepResult:
    """Solve the linkage over a sweep and summarise it.

    The analysis runs on the output grid merged with a search grid of at most
    0.5° (``SEARCH_STEP``), so extremes, gaps and dead points do not depend
    on the output step; the output rows are a subset of that grid.

    Parameters
    ----------
    linkage : Linkage
    sweep : Sweep
    quantities : list of Quantity
        What to report (see :func:`default_quantities`).
    order : int
        Highest derivative needed (0, 1, 2).
    partial : bool
        False: any position that cannot assemble (or is a dead point) raises
        :class:`AssemblyError` naming the intervals -- including gaps narrower
        than the grid step, found by refining the minima of every dyad's
        sin(gamma).  True: analyse only the regular positions and report the
        excluded intervals.
    extremes : bool
        Refine max/min of every quantity.

    Returns
    -------
    SweepResult
    """
    if linkage.shape != ():
        raise ValueError(f"analyse_sweep works on one design at a time, got a batch of designs "
                         f"(linkage parameters of shape {linkage.shape}); use solve for a batch")
    q_out = np.asarray(sweep.q, dtype=float)
    if q_out.ndim != 1:
        raise ValueError(f"a sweep's q must be one-dimensional, got shape {q_out.shape}")
    rotary = linkage.driver(sweep.driver).rotary
    span = float(q_out[-1] - q_out[0])
    fine_step = SEARCH_STEP if rotary else span / 720
    if q_out.size > 1 and np.max(np.diff(q_out)) > fine_step * (1 + 1e-9):
        n = int(np.ceil(span / fine_step)) + 1
        fine = np.linspace(q_out[0], q_out[-1], n)
        # a fine node that is an output node but for rounding (210.0 of the 0.5° grid and
        # 210.0 of the 10° rows, a bit apart) would be a second, nearly equal sample: an
        # extreme's bracket could then lie beside the extreme instead of round it
        i = np.clip(np.searchsorted(q_out, fine), 1, q_out.size - 1)
        near = np.minimum(np.abs(fine - q_out[i - 1]), np.abs(fine - q_out[i]))
        q_all = sorted_union(q_out, fine[near > 1e-9 * fine_step])
    else:
        q_all = q_out
    out_idx = np.searchsorted(q_all, q_out)
    motion = solve(linkage, sweep.inputs(q_all), order=order)
    good = motion.regular.copy()
    # gaps the grid stepped over: refine near-toggles on the grid's own runs
    toggles, gaps = _scan_gaps(linkage, sweep, order, q_all, motion, true_runs(good))
    for x, k in gaps:
        # mark the grid point at a hidden gap as bad: the boundary search
        # below then starts from its neighbours
        good[k] = False
    bad_runs = true_runs(~good)
    excluded, excluded_tol, ends, deads = [], [], [], []
    excluded_reg = excluded   # the regular ends (the analysis extends to them)
    if bad_runs:
        goods, bads, where = [], [], []
        hidden = {k: x for x, k in gaps}
        for (i0, i1) in bad_runs:
            inner = [hidden[k] for k in range(i0, i1) if k in hidden]
            first_bad = inner[0] if inner and motion.regular[i0] else q_all[i0]
            last_bad = inner[-1] if inner and motion.regular[i1 - 1] else q_all[i1 - 1]
            if i0 > 0:
                goods.append(q_all[i0 - 1]); bads.append(first_bad); where.append((i0, 0))
            if i1 < q_all.size:
                goods.append(q_all[i1]); bads.append(last_bad); where.append((i1 - 1, 1))
        bounds = {}
        if goods:
            for w, val in zip(where, _bisect_boundaries(linkage, sweep, order, goods, bads)):
                bounds[w] = float(val)
        for (i0, i1) in bad_runs:
            start = bounds.get((i0, 0), float(q_all[i0]))
            stop = bounds.get((i1 - 1, 1), float(q_all[i1 - 1]))
            if start > stop:
                start, stop = stop, start
            mid = solve(linkage, sweep.inputs(np.array([0.5 * (start + stop)])), order=0)
            reason = "cannot assemble" if not mid.feasible[0] or not np.all(
                motion.feasible[i0:i1]) else "dead point"
            excluded.append((start, stop, reason))
            # where assembly is lost, inside the interval: the first and last input that
            # does not assemble (a grid point, or the middle)
            infeasible = np.flatnonzero(~motion.feasible[i0:i1])
            if infeasible.size:
                out_lo, out_hi = q_all[i0 + infeasible[0]], q_all[i0 + infeasible[-1]]
            elif not mid.feasible[0]:
                out_lo = out_hi = 0.5 * (start + stop)
            else:
                out_lo = out_hi = None
            end = ((i0, 0) in bounds and out_lo is not None,
                   (i1 - 1, 1) in bounds and out_hi is not None, out_lo, out_hi)
            if bounds.get((i0, 0), float(q_all[i0])) > bounds.get((i1 - 1, 1),
                                                                   float(q_all[i1 - 1])):
                end = (end[1], end[0], end[3], end[2])   # start and stop were swapped
            ends.append(end)
        excluded_reg = excluded
        excluded, excluded_tol = _refined_exclusions(linkage, sweep, excluded, ends, bounds)
        deads = dead_points(linkage, sweep, excluded)
        excluded, excluded_tol, deads = _limits_are_not_dead_points(excluded, excluded_tol,
                                                                    deads)
        if not partial:
            raise AssemblyError(_describe_exclusions(excluded), excluded)
    idx = np.flatnonzero(good)
    if idx.size < 2 or np.count_nonzero(good[out_idx]) < 2:
        raise AssemblyError("fewer than two input positions can be analysed: "
                            + _describe_exclusions(excluded), excluded, too_few=True)
    # runs of the analysis grid, and their real extent (refined gap edges)
    q = q_all[idx]
    cuts = np.flatnonzero(np.diff(idx) > 1) + 1
    edges = np.concatenate(([0], cuts, [idx.size]))
    runs = list(zip(edges[:-1].tolist(), edges[1:].tolist()))
    lo_ext = [_nearest_boundary(excluded_reg, q[i0], before=True) for i0, _ in runs]
    hi_ext = [_nearest_boundary(excluded_reg, q[i1 - 1], before=False) for _, i1 in runs]
    period = float(q_all[-1] - q_all[0])
    connected = bool(sweep.periodic and idx[0] == 0 and idx[-1] == q_all.size - 1)
    for start, stop, _r in excluded_reg:
        for b in (start, stop):
            if q_all[0] < b < q_all[-1]:
                m1 = solve(linkage, sweep.inputs(np.array([b])), order=0)
                c = min(m1.conditions, key=lambda c: float(c.sin_gamma[0]))
                toggles.append(Toggle(b, c.joint, c.kind, float(c.sin_gamma[0])))
    grid_motion = _take(motion, idx) if idx.size < q_all.size else motion
    values = {}
    for qt in quantities:
        v = np.asarray(qt.get(grid_motion), dtype=float)
        if qt.is_angle:
            v = _unwrap_runs(v, runs, connected and len(runs) > 1)
        values[qt.symbol] = v
    domain = _Domain(q, runs, lo_ext, hi_ext, connected, period, (q_all[0], q_all[-1]))
    ext = refine_extremes(linkage, sweep, order, quantities, values, domain) if extremes else {}
    zeros = _slide_zeros(linkage, sweep, order, quantities, values, q, runs,
                         sweep.periodic and connected, q_all[0], period) if extremes else {}
    # the output rows: the regular output positions, as a subset of the grid
    keep = out_idx[good[out_idx]]
    pos = np.searchsorted(idx, keep)  # positions of the kept rows within the grid's idx
    run_of = np.repeat(np.arange(len(runs)), [b - a for a, b in runs])[pos]
    cut_out = np.flatnonzero((np.diff(pos) > 0) & (np.diff(run_of) != 0)) + 1
    e_out = np.concatenate(([0], cut_out, [pos.size]))
    out_runs = list(zip(e_out[:-1].tolist(), e_out[1:].tolist()))
    out_motion = _take(grid_motion, pos) if pos.size < idx.size else grid_motion
    out_values = {k: v[pos] for k, v in values.items()}
    if sweep.periodic:
        toggles = [dataclasses.replace(t, at=_periodic(t.at, q_all[0], period))
                   for t in toggles]
    toggles.sort(key=lambda t: t.at)
    toggles = _dedupe(toggles)
    q_rows = q_all[keep]
    accuracy = _accuracy_of_sweep(linkage, sweep, quantities, order, q_rows, out_values, ext,
                                  out_motion, out_runs, toggles)
    if sweep.periodic:
        deads = [dataclasses.replace(d, at=_periodic(d.at, q_all[0], period)) for d in deads]
    deads.sort(key=lambda d: d.at)
    unique = []
    for d in deads:   # 0° and 360° of a whole turn are one dead point
        if unique and abs(unique[-1].at - d.at) <= max(unique[-1].tol, d.tol) \
                and unique[-1].joint == d.joint:
            if d.tol < unique[-1].tol:
                unique[-1] = d
            continue
        unique.append(d)
    return SweepResult(q_rows, out_values, ext, excluded, toggles, out_motion, out_runs,
                       accuracy, excluded_tol, unique, zeros)


def _refined_exclusions(linkage, sweep, excluded, ends, bounds):
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


def _limits_are_not_dead_points(excluded, excluded_tol, deads):
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


def _nearest_boundary(excluded, x, before):
    """The refined edge of the excluded interval adjacent to grid point ``x``
    (``x`` itself where no gap is adjacent: the sweep ends there)."""
    if before:
        stops = [b for _a, b, _r in excluded if b <= x]
        return max(stops) if stops else x
    starts = [a for a, _b, _r in excluded if a >= x]
    return min(starts) if starts else x


def _periodic(x, q0, period):
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


def _unwrap_runs(v, runs, connected):
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


def _describe_exclusions(excluded):
    """Core wording (input in rad or m); the report layer rewords it in the spec's units."""
    return "; ".join(f"{reason} for input {start:.6g} … {stop:.6g}"
                     for start, stop, reason in excluded)
