"""Kinematic analysis of a linkage over a sweep of its primary input.

:func:`analyse_sweep` solves the linkage engine over the sweep, finds where it
cannot assemble (or is at a dead point) and refines those boundaries by
bisection, restricts the analysis to the regular positions when asked, and
refines the extremes of every requested quantity by a bracketed search on the
exact solution (to ~1e-10 rad of input angle).

Secondary drivers (a 2-DOF five-bar driven by two geared cranks) follow the
primary one linearly: ``q_k = phase_k + ratio_k * q_1``.
"""

from __future__ import annotations

import dataclasses
from typing import Callable, Dict, Tuple

import numpy as np

from mechcli.core.errors import AssemblyError
from mechcli.core.linkage import (RRR, Crank, DriverMotion, Linkage, LinkageMotion,
                                  SliderDriver, solve)

#: sin(gamma) below which an interior minimum is flagged as near a dead point
NEAR_TOGGLE_SIN = 0.05


@dataclasses.dataclass(frozen=True)
class Sweep:
    """The input program.

    Attributes
    ----------
    driver : int
        Link number of the primary driver.
    q : ndarray
        Input positions: crank angle [rad] or slide [m].
    dq, ddq : float
        Input velocity [rad/s or m/s] and acceleration, the same at every
        position (the book's ``omega1``, ``alpha1``).
    followers : dict
        ``{link: (ratio, phase)}`` of secondary drivers.
    periodic : bool
        The sweep covers whole turns of every driver (extremes wrap around).
    """

    driver: int
    q: np.ndarray
    dq: float = 1.0
    ddq: float = 0.0
    followers: Dict[int, Tuple[float, float]] = dataclasses.field(default_factory=dict)
    periodic: bool = False

    def inputs(self, q):
        q = np.asarray(q, dtype=float)
        out = {self.driver: DriverMotion(q, self.dq, self.ddq)}
        for link, (ratio, phase) in self.followers.items():
            out[link] = DriverMotion(phase + ratio * q, ratio * self.dq, ratio * self.ddq)
        return out


@dataclasses.dataclass(frozen=True)
class Quantity:
    """One output quantity as a function of the solved motion.

    ``kind`` is one of ``angle`` [rad], ``angvel`` [rad/s], ``angacc``
    [rad/s^2], ``length`` [m], ``velocity`` [m/s], ``acceleration`` [m/s^2],
    ``ratio`` [-]; ``order`` the derivative order it needs.
    """

    symbol: str
    kind: str
    order: int
    get: Callable[[LinkageMotion], np.ndarray]

    @property
    def is_angle(self):
        return self.kind == "angle"


@dataclasses.dataclass(frozen=True)
class Extreme:
    value: float
    at: float  # input position [rad or m]


@dataclasses.dataclass(frozen=True)
class Toggle:
    """A dead/toggle position: dyad ``joint`` with sin(gamma) = ``sin_gamma`` at ``at``."""

    at: float
    joint: str
    kind: str
    sin_gamma: float


@dataclasses.dataclass(frozen=True)
class SweepResult:
    """Kinematics over the regular positions of a sweep.

    Attributes
    ----------
    q : ndarray
        Input positions analysed.
    values : dict
        ``symbol -> ndarray`` for every requested quantity (angles unwrapped).
    extremes : dict
        ``symbol -> (max Extreme, min Extreme)``.
    excluded : list of (float, float, str)
        Input intervals left out, with the reason (``cannot assemble`` or
        ``dead point``); boundaries refined by bisection.
    toggles : list of Toggle
        Interior near-dead positions (local minima of sin(gamma) below
        ``NEAR_TOGGLE_SIN``) and the refined ends of excluded intervals.
    motion : LinkageMotion
        Engine output at ``q`` (for drawings and animations).
    """

    q: np.ndarray
    values: Dict[str, np.ndarray]
    extremes: Dict[str, Tuple[Extreme, Extreme]]
    excluded: list
    toggles: list
    motion: LinkageMotion


def default_quantities(linkage: Linkage, order: int, tracers=()):
    """The book's quantities: angles/ω/α of every rotating non-driver link, every
    slide s/v/a, the transmission angle of every RRR dyad, and x, y (vx, vy, ax,
    ay) of every tracer point.
    """
    out = []
    drivers = {d.link for d in linkage.drivers}
    translating = set(linkage.translating_links)
    rotating = []
    for el in linkage.elements:
        if isinstance(el, (Crank, SliderDriver)):
            continue
        for link in _links_of(el):
            if link not in drivers and link not in translating and link not in rotating:
                rotating.append(link)
    # a block of an RPR turns with its guide: report the guide only
    from mechcli.core.linkage import RPR
    blocks = {el.block for el in linkage.elements if isinstance(el, RPR)}
    rotating = [ln for ln in rotating if ln not in blocks]
    slides = _slide_names(linkage)
    # (symbol prefix, kind, attribute) per derivative order, for links, slides, points
    table = (
        (("theta", "angle", "theta"), ("s", "length", "s"),
         (("x", "length", "x"), ("y", "length", "y"))),
        (("omega", "angvel", "omega"), ("v", "velocity", "v"),
         (("vx", "velocity", "vx"), ("vy", "velocity", "vy"))),
        (("alpha", "angacc", "alpha"), ("a", "acceleration", "a"),
         (("ax", "acceleration", "ax"), ("ay", "acceleration", "ay"))),
    )
    for k in range(order + 1):
        (lp, lkind, lattr), (sp, skind, sattr), pts = table[k]
        for n in sorted(rotating):
            out.append(Quantity(f"{lp}{n}", lkind, k,
                                lambda m, n=n, a=lattr: getattr(m.links[n], a)))
        for name in slides:
            out.append(Quantity(f"{sp}{name}", skind, k,
                                lambda m, n=name, a=sattr: getattr(m.slides[n], a)))
        for tr in tracers:
            for pp, pkind, pattr in pts:
                out.append(Quantity(f"{pp}{tr}", pkind, k,
                                    lambda m, n=tr, a=pattr: getattr(m.points[n], a)))
        if k == 0:
            for el in linkage.elements:
                if isinstance(el, RRR):
                    out.append(Quantity(f"gamma{el.joint}", "angle", 0,
                                        lambda m, j=el.joint: _cond(m, j).gamma))
    return out


def _links_of(el):
    from mechcli.core.linkage import _needs
    return _needs(el)[3]


def _slide_names(linkage):
    from mechcli.core.linkage import RPR, RRP
    names = []
    for el in linkage.elements:
        if isinstance(el, RRP):
            names.append(el.name or (str(el.slider) if el.guide_link == linkage.frame
                                     else f"{el.slider}{el.guide_link}"))
        elif isinstance(el, RPR):
            names.append(el.name or f"{el.block}{el.guide}")
    return names


def _cond(m, joint):
    for c in m.conditions:
        if c.joint == joint:
            return c
    raise KeyError(joint)


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


def _runs(mask):
    """(start, stop) index pairs of the True runs of a 1-D boolean array."""
    m = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(m))
    return list(zip(edges[0::2], edges[1::2]))


def _bisect_boundaries(linkage, sweep, order, good_lo, bad_hi, iterations=60):
    """Refine boundaries between a regular input ``good_lo`` and a bad ``bad_hi``."""
    a = np.asarray(good_lo, dtype=float).copy()
    b = np.asarray(bad_hi, dtype=float).copy()
    for _ in range(iterations):
        mid = 0.5 * (a + b)
        ok = solve(linkage, sweep.inputs(mid), order=order).regular
        a = np.where(ok, mid, a)
        b = np.where(ok, b, mid)
        if np.all(np.abs(b - a) <= 1e-15 * np.maximum(1.0, np.abs(a))):
            break
    return a, b


def _wrap(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


def refine_extremes(linkage, sweep, order, quantities, q, values, runs, iterations=48):
    """Refine max and min of every quantity by bisection on its derivative's sign.

    The derivative is a central difference of the exact solution with step
    ``h = 1e-5`` of the input range scale, so the location error is about
    ``h^2 * f'''/f''`` (~1e-10 rad); the value is evaluated exactly there.
    """
    span = float(np.ptp(q)) if q.size > 1 else 1.0
    h = 1e-5 * max(span, 1e-12) / (2 * np.pi) if span > 0 else 1e-7
    targets = []  # (symbol, sign, lo, hi, q_grid, v_grid, lo_bound, hi_bound)
    out = {}
    for qt in quantities:
        v = values[qt.symbol]
        res = []
        for sign in (1.0, -1.0):
            best = None
            for (i0, i1) in runs:
                seg = sign * v[i0:i1]
                k = i0 + int(np.argmax(seg))
                if best is None or sign * v[k] > sign * v[best[0]]:
                    best = (k, i0, i1)
            k, i0, i1 = best
            n = q.size
            # a quantity with a net change over a whole-turn sweep (a fully turning
            # link's unwrapped angle) is not periodic: its extremes are the ends
            returns = abs(v[-1] - v[0]) <= 1e-9 * max(1.0, float(np.max(np.abs(v))))
            whole = sweep.periodic and returns and len(runs) == 1 and i0 == 0 and i1 == n
            if whole:
                lo = q[k - 1] if k > 0 else q[0] - (q[1] - q[0])
                hi = q[k + 1] if k < n - 1 else q[-1] + (q[1] - q[0])
            else:
                if k == i0 or k == i1 - 1:
                    res.append(Extreme(float(v[k]), float(q[k])))
                    continue
                lo, hi = q[k - 1], q[k + 1]
            res.append(None)
            targets.append((qt, sign, lo, hi, float(v[k]), len(res) - 1))
        out[qt.symbol] = res
    if targets:
        lo = np.array([t[2] for t in targets], dtype=float)
        hi = np.array([t[3] for t in targets], dtype=float)
        for _ in range(iterations):
            mid = 0.5 * (lo + hi)
            probe = np.concatenate([mid - h, mid + h])
            m = solve(linkage, sweep.inputs(probe), order=order)
            T = len(targets)
            g = np.empty(T)
            for j, (qt, sign, *_rest) in enumerate(targets):
                arr = qt.get(m)
                dv = arr[T + j] - arr[j]
                if qt.is_angle:
                    dv = _wrap(dv)
                g[j] = sign * dv
            rising = g > 0
            lo = np.where(rising, mid, lo)
            hi = np.where(rising, hi, mid)
            if np.all(hi - lo <= 1e-13):
                break
        at = 0.5 * (lo + hi)
        m = solve(linkage, sweep.inputs(at), order=order)
        for j, (qt, sign, _lo, _hi, vgrid, slot) in enumerate(targets):
            val = float(qt.get(m)[j])
            if qt.is_angle:
                val = vgrid + float(_wrap(val - vgrid))
            # never report a refined extreme worse than the grid's
            if sign * val < sign * vgrid:
                val = vgrid
            pos = float(at[j])
            if sweep.periodic:
                pos = q[0] + (pos - q[0]) % (q[-1] - q[0]) if q[-1] > q[0] else pos
            out[qt.symbol][slot] = Extreme(val, pos)
    return {k: (v[0], v[1]) for k, v in out.items()}


def analyse_sweep(linkage: Linkage, sweep: Sweep, quantities, order: int,
                  partial: bool = False, extremes: bool = True) -> SweepResult:
    """Solve the linkage over a sweep and summarise it.

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
        :class:`AssemblyError` naming the intervals.  True: analyse only the
        regular positions and report the excluded intervals.
    extremes : bool
        Refine max/min of every quantity.

    Returns
    -------
    SweepResult
    """
    q = np.asarray(sweep.q, dtype=float)
    motion = solve(linkage, sweep.inputs(q), order=order)
    good = motion.regular
    excluded, toggles = [], []
    runs = [(0, q.size)]
    if not np.all(good):
        bad_runs = _runs(~good)
        lo_in, hi_in, where = [], [], []
        for (i0, i1) in bad_runs:
            if i0 > 0:
                lo_in.append(q[i0 - 1]); hi_in.append(q[i0]); where.append((i0, "start"))
            if i1 < q.size:
                lo_in.append(q[i1]); hi_in.append(q[i1 - 1]); where.append((i1 - 1, "end"))
        bounds = {}
        if lo_in:
            a, _b = _bisect_boundaries(linkage, sweep, order, lo_in, hi_in)
            for (i, side), val in zip(where, a):
                bounds[(i, side)] = float(val)
        for (i0, i1) in bad_runs:
            start = bounds.get((i0, "start"), float(q[i0]))
            stop = bounds.get((i1 - 1, "end"), float(q[i1 - 1]))
            reason = "cannot assemble" if not np.all(motion.feasible[i0:i1]) else "dead point"
            excluded.append((start, stop, reason))
        if not partial:
            raise AssemblyError(_describe_exclusions(excluded, linkage, sweep), excluded)
        idx = np.flatnonzero(good)
        if idx.size < 2:
            raise AssemblyError("fewer than two input positions can be analysed: "
                                + _describe_exclusions(excluded, linkage, sweep), excluded)
        q = q[idx]
        motion = _take(motion, idx)
        cuts = np.flatnonzero(np.diff(idx) > 1) + 1
        edges = np.concatenate(([0], cuts, [idx.size]))
        runs = list(zip(edges[:-1], edges[1:]))
        for start, stop, _r in excluded:
            for b in (start, stop):
                if b not in (float(sweep.q[0]), float(sweep.q[-1])):
                    m1 = solve(linkage, sweep.inputs(np.array([b])), order=0)
                    c = min(m1.conditions, key=lambda c: float(c.sin_gamma[0]))
                    toggles.append(Toggle(b, c.joint, c.kind, float(c.sin_gamma[0])))
    values = {}
    for qt in quantities:
        v = np.asarray(qt.get(motion), dtype=float)
        if qt.is_angle:
            v = _unwrap_runs(v, runs)
        values[qt.symbol] = v
    toggles.extend(_near_toggles(linkage, sweep, motion, q, runs))
    ext = refine_extremes(linkage, sweep, order, quantities, q, values, runs) if extremes else {}
    return SweepResult(q, values, ext, excluded, toggles, motion)


def _unwrap_runs(v, runs):
    out = v.copy()
    for (i0, i1) in runs:
        seg = np.unwrap(v[i0:i1])
        # first value in (-pi, pi]
        shift = seg[0] - _wrap(seg[0])
        out[i0:i1] = seg - shift
    return out


def _near_toggles(linkage, sweep, motion, q, runs):
    out = []
    for c in motion.conditions:
        s = c.sin_gamma
        if s.size < 3 or np.min(s) >= NEAR_TOGGLE_SIN:
            continue
        interior = (s[1:-1] <= s[:-2]) & (s[1:-1] <= s[2:]) & (s[1:-1] < NEAR_TOGGLE_SIN)
        for k in np.flatnonzero(interior) + 1:
            out.append(Toggle(float(q[k]), c.joint, c.kind, float(s[k])))
    return out


def _describe_exclusions(excluded, linkage, sweep):
    rotary = any(isinstance(d, Crank) and d.link == sweep.driver for d in linkage.drivers)
    parts = []
    for start, stop, reason in excluded:
        if rotary:
            parts.append(f"{reason} for input angle {np.degrees(start):.6g}° … "
                         f"{np.degrees(stop):.6g}°")
        else:
            parts.append(f"{reason} for input {start:.6g} … {stop:.6g} m")
    return ("; ".join(parts) + " (set input.partial = true to analyse the feasible ranges only)")
