"""One problem of ``mechcli flywheel``: its models built and its motion solved.

:func:`solve_flywheel` maps the spec's plain data (duck-typed: ``inertia``,
``moment``, ``motion``, ``flywheel`` parts of SI numbers, as
:mod:`mechcli.spec.flywheel` reads them) onto the models of
:mod:`~.equivalent` and the solvers of :mod:`~.motion`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple, Union

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.flywheel import diagram as dg
from mechcli.core.flywheel import equivalent as eq
from mechcli.core.flywheel import motion as mo
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.flywheel.equivalent import (
        ConstantInertia,
        LinkageInertia,
        TableInertia,
        ZeroInertia,
    )
    from mechcli.core.flywheel.motion import MomentModel
    from mechcli.core.linkage.engine import Linkage
    from mechcli.core.linkage.force_model import Topology

#: the grid the loads of a linkage are sampled on for the moment table [points per turn]
LOAD_SAMPLES = 3600


@record
class Model:
    """The equivalent model on a grid, without a motion (Me at ω = 0 when it depends on ω)."""

    phi: np.ndarray
    Je: np.ndarray
    dJe: np.ndarray
    Me: np.ndarray


@record(eq=False)
class FlywheelSolution:
    """Everything a flywheel problem gives.

    Attributes
    ----------
    inertia, moment : the models (``inertia`` with any flywheel added)
    motion : motion.Motion
        The solved motion (one period for a steady state).
    steady : motion.SteadyState or None
    method : str
        The method that solved it (``"auto"`` resolved).
    J_F : float or None
        A flywheel added (given) or sized for [δ] (exact, with the variable Je).
    J_F_approx : float or None
        The approximate flywheel of eq 6-29 for [δ].
    J_F_delta : float or None
        δ of the steady state with the sized flywheel.
    omega_inf : float or None
        The asymptotic speed of a motor line with constant Je.
    """

    inertia: Any
    moment: Any
    motion: Any
    steady: Optional[Any]
    method: str
    J_F: Optional[float] = None
    J_F_approx: Optional[float] = None
    J_F_delta: Optional[float] = None
    omega_inf: Optional[float] = None
    mass: Optional[float] = None        # the flywheel's mass [kg] (rim or disc)
    width: Optional[float] = None       # its width along the shaft [m]
    swing: Optional[tuple] = None       # (δ, ωmax, ωmin) from a given ΔWmax (eq. 6-28)
    omega_balance: Optional[float] = None   # ωm by the energy balance (Me linear in ω)
    period: float = 2 * np.pi           # the cycle [rad]
    loops: Optional[Any] = None         # diagram.EnergyLoops at the mean speed
    dW_trapezoid: Optional[float] = None    # ΔWmax with the Simpson tables read linearly
    mean_term: Optional[tuple] = None   # ("constant" | "resisting", its value [N m])
    work_per_cycle: Optional[float] = None  # the driving work over a cycle [J]
    omega_m: Optional[float] = None     # the mean speed the figures of a cycle use [rad/s]
    equation: Optional[str] = None      # "6-29" | "6-30": J_F from ΔWmax (no [motion])
    mass_approx: Optional[float] = None     # the mass of J_F_approx [kg]
    motion_with_J_F: bool = False       # the motion reported carries the sized J_F


def build_inertia(part: Any, linkage: Optional[Linkage] = None, bodies: Any = None,
                  followers: Optional[Dict[Any, Any]] = None) -> Any:
    """The inertia model of the spec's ``inertia`` part."""
    if part.kind == "linkage":
        # (the spec gives the linkage with an inertia of kind "linkage")
        return eq.LinkageInertia(linkage, bodies, followers=followers or None,  # type: ignore[arg-type]
                                 derivative=part.derivative, step=part.step)
    if part.kind == "table":
        return eq.TableInertia(np.asarray(part.phi), np.asarray(part.values), method=part.method,
                               period=part.period)
    if part.kind == "none":
        return eq.ZeroInertia()
    if part.kind == "chain":
        return eq.ChainInertia(part.members, masses=part.masses)
    return eq.ConstantInertia(part.J)


def _repeat_table(phi: np.ndarray, M: np.ndarray, period: float, cycle: float
                 ) -> Tuple[np.ndarray, np.ndarray]:
    """A table of ``period`` repeated over ``cycle`` (a whole multiple): the same periodic
    interpolant (linear, cubic spline, Simpson parabolas) on the longer cycle."""
    xp, fp = mo._closed_table(phi, M, period)
    m = int(round(cycle / period))
    if m == 1:
        return xp, fp
    shift = period * np.arange(m)[:, None]
    return (np.append((xp[:-1] + shift).ravel(), xp[0] + cycle),
            np.append(np.tile(fp[:-1], m), fp[0]))


def _tables(part: Any, linkage_moment: Optional[Any], cycle: float, only: Optional[str] = None
           ) -> Optional[Tuple[np.ndarray, np.ndarray, str]]:
    """The φ-tables of the moment summed into one (phi, M, method) over ``cycle``.
    ``only``: "table" or "resisting_table" alone (no loads), for the work of one term."""
    tabs = []
    names = ("table", "resisting_table") if only is None else (only,)
    for name, sign in (("table", 1.0), ("resisting_table", -1.0)):
        t = getattr(part, name)
        if t is not None and name in names:
            phi, M = _repeat_table(np.asarray(t[0]), sign * np.asarray(t[1]), t[3], cycle)
            tabs.append((phi, M, t[2]))
    if linkage_moment is not None and only is None:
        phi, M = _repeat_table(linkage_moment[0], linkage_moment[1], 2 * np.pi, cycle)
        tabs.append((phi, M, "linear"))
    if not tabs:
        return None
    if len(tabs) == 1:
        return tabs[0]
    if all(np.array_equal(t[0], tabs[0][0]) for t in tabs) \
            and len({t[2] for t in tabs}) == 1:
        # (a sum of two or more arrays: an array, never sum's start 0)
        return tabs[0][0], sum(t[1] for t in tabs), tabs[0][2]  # type: ignore[return-value]
    # linear tables on other angles: their sum is linear on the union of the angles
    base = tabs[0][0][0]
    grid = np.unique(np.concatenate([np.mod(t[0][:-1] - base, cycle) for t in tabs])) + base
    total = np.zeros_like(grid)
    for phi, M, _m in tabs:
        total += np.interp(grid, phi[:-1], M[:-1], period=cycle)
    return grid, total, "linear"


def _harmonic(h: Tuple[float, Tuple[float, ...], Tuple[float, ...], float], cycle: float
             ) -> Tuple[float, Tuple[float, ...], Tuple[float, ...]]:
    """``(a0, a, b)`` of a series of period ``h[3]`` as harmonics of the cycle."""
    a0, a, b, period = h
    m = int(round(cycle / period))
    if m == 1:
        return a0, a, b
    out = []
    for c in (a, b):
        full = np.zeros(m * len(c))
        full[m - 1::m] = c
        out.append(tuple(full))
    return (a0,) + tuple(out)  # type: ignore[return-value]  # (out holds a and b)


def _segments(part: Any, cycle: float) -> Optional[List[Tuple[float, float, float, float]]]:
    """The segments over the cycle: repeated when they cover their period end to end."""
    segs = list(part.segments)
    if not segs:
        return None
    T = part.period
    m = int(round(cycle / T))
    lo, hi = min(x[0] for x in segs), max(x[1] for x in segs)
    covers = abs(hi - lo - T) <= 1e-9 * T
    if m == 1 or not covers:
        return segs
    return [(a + k * T, b + k * T, c, d) for k in range(m) for a, b, c, d in segs]


def moment_cycle(part: Any) -> float:
    """The period [rad] of the moment's φ-terms: the longest of theirs (the spec checks
    that the others divide it); 2π for the loads of a linkage."""
    periods = [2 * np.pi] if part.loads else []
    for t in (part.table, part.resisting_table):
        if t is not None:
            periods.append(t[3])
    if part.harmonic is not None:
        periods.append(part.harmonic[3])
    if part.segments:
        periods.append(part.period)
    return mo.cycle(*periods)


def build_moment(part: Any, linkage: Optional[Linkage] = None, topo: Optional[Topology] = None,
                 bodies: Any = None, gravity: Optional[Tuple[float, float]] = None,
                 loads: Tuple[Any, ...] = (), followers: Optional[Dict[Any, Any]] = None,
                 shift: float = 0.0
                 ) -> Tuple[MomentModel, Optional[Tuple[np.ndarray, np.ndarray, str]]]:
    """The moment model of the spec's ``moment`` part (and the linkage's loads), over its
    cycle; ``shift`` [N m] is added to the constant (the balancing mean)."""
    cycle = moment_cycle(part)
    lm = None
    if part.loads and linkage is not None:
        loads = _with_band_limits(linkage, loads, followers)
        phi = np.linspace(0.0, 2 * np.pi, LOAD_SAMPLES, endpoint=False)
        # (the spec gives the topology with the linkage)
        M = eq.linkage_moment(linkage, topo, bodies, gravity, list(loads), phi,  # type: ignore[arg-type]
                              followers=followers or None)
        lm = (phi, np.asarray(M, dtype=float), "linear")
    constant = part.constant - part.resisting + shift
    if part.torques:
        constant += eq.chain_moment(part.torques)
    harmonic = None if part.harmonic is None else _harmonic(part.harmonic, cycle)
    terms = dict(linear=part.drive, harmonic=harmonic, segments=_segments(part, cycle),
                 constant=constant, period=cycle)
    model = mo.MomentModel(table=_tables(part, lm, cycle), **terms)
    if lm is not None:
        # the loads' Me is smooth between the angles where a load switches on or off: the
        # integrators stop there (and at the user's own knots), not at every sample
        own = mo.MomentModel(table=_tables(part, None, cycle), **terms).breaks
        # (lm is set only with a linkage)
        switches = _switches(linkage, _with_band_limits(linkage, loads, followers), lm[0],  # type: ignore[arg-type]
                             followers)
        switches = (switches[:, None] + 2 * np.pi * np.arange(
            int(round(cycle / (2 * np.pi))))[None, :]).ravel()
        knots = np.concatenate([own[0], switches])
        model.breaks = (np.unique(knots), own[1] if len(own[0]) else 0.0, own[2], cycle)
    return model, lm


def _term_works(part: Any, lm: Optional[Any], cycle: float, omega_m: float
                ) -> Optional[List[float]]:
    """The work over a cycle of each term of the moment [J] (None for a motor line without
    a mean speed): the driving ones positive, the resisting ones negative."""
    T = cycle
    works = [part.constant * T, -part.resisting * T]
    if part.torques:
        works.append(eq.chain_moment(part.torques) * T)
    if part.drive is not None:
        if omega_m is None and part.drive[1] != 0:
            return None
        a, b = part.drive
        works.append((a - b * (omega_m or 0.0)) * T)
    for name in ("table", "resisting_table"):
        t = _tables(part, None, cycle, only=name)
        if t is not None:
            works.append(float(mo.MomentModel(table=t, period=cycle).energy(t[0][0],
                                                                           t[0][0] + T)))
    if part.harmonic is not None:
        works.append(part.harmonic[0] * T)
    for a, b, c, d in _segments(part, cycle) or ():
        works.append(0.5 * (c + d) * (b - a))
    if lm is not None:
        phi, M = _repeat_table(lm[0], lm[1], 2 * np.pi, cycle)
        works.append(float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(phi))))
    return works


def _with_band_limits(linkage: Linkage, loads: Any, followers: Optional[Dict[Any, Any]]):
    """Loads acting over a band of a slide's stroke (例 2-4's cutting force) get the
    stroke's absolute limits, refined on the exact solution as ``force`` does."""
    if not any(p.band is not None for p in loads):
        return loads
    from mechcli.core.linkage.kinematics import Sweep, analyse_sweep
    q = np.linspace(0.0, 2 * np.pi, 721)
    slides = [p.slide for p in loads if p.band is not None]
    kin = analyse_sweep(linkage, Sweep(linkage.drivers[0].link, q, 1.0, 0.0,
                                       followers or {}), slides, 1, extremes=True)
    out = []
    for p in loads:
        if p.band is not None:
            hi, lo = kin.extremes[p.slide.symbol]
            p = p.with_band_limits(lo.value, hi.value)
        out.append(p)
    return out


def _switches(linkage: Linkage, loads: Any, phi: np.ndarray, followers: Optional[Dict[Any, Any]]
              ) -> np.ndarray:
    """The sample angles at which a load's program switches (its window, velocity sign or
    stroke band): where the loads' Me may jump."""
    from mechcli.core.linkage.kinematics import Sweep
    if not any(p.conditional for p in loads):
        return np.empty(0)
    sweep = Sweep(linkage.drivers[0].link, phi, 1.0, 0.0, followers or {})
    from mechcli.core.linkage.engine import solve
    m = solve(linkage, sweep.inputs(phi), order=1)
    out = []
    for p in loads:
        if p.conditional:
            on = np.asarray(p.active(phi, m), dtype=bool)
            change = np.flatnonzero(on != np.roll(on, 1))
            out.append(phi[change])
    return np.concatenate(out) if out else np.empty(0)


def _auto(kind: str, inertia: mo.Inertia, moment: MomentModel, end: str, omega0: float) -> str:
    """The method for the problem: exact where a closed form or the energy integral
    applies, else DOP853 -- or Radau when the motor's damping b makes the equation stiff
    (b/(Je ω) per radian large: a steep motor line on a light machine)."""
    if kind == "start" and end != "phi":
        return "closed_form"
    if kind == "start" and not moment.depends_on_omega:
        return "energy"
    if moment.depends_on_omega and moment.b > 0:
        Je_min = float(np.min(inertia(np.linspace(0, 2 * np.pi, 361))[0]))
        if Je_min * max(abs(omega0), 1e-300) * STIFF < moment.b:
            return "Radau"
    return "DOP853"


#: b/(Je ω) [1/rad] above which the automatic method is the stiff Radau
STIFF = 50.0


def _swing_at_mean(moment: MomentModel, phi0: float, omega_m: float, period: float,
                   n: int = 7201) -> float:
    """ΔWmax of eq. 6-29 as taught: the swing of the work of Me(φ, ωm) at the mean speed
    over a cycle (the φ-part exactly, minus b ωm φ)."""
    phi = np.linspace(phi0, phi0 + period, n)
    W = moment.energy(phi0, phi) - moment.b * omega_m * (phi - phi0)
    return float(np.max(W) - np.min(W))


def balance_mean(moment: MomentModel, phi0: float, period: float = 2 * np.pi) -> Optional[float]:
    """The integral mean speed a steady state must have when Me is linear in ω with b > 0:
    the work over a cycle vanishes, so ωm = (1/T)∫(Me + bω) dφ / b; None otherwise."""
    if not (moment.depends_on_omega and moment.b > 0):
        return None
    return float(moment.energy(phi0, phi0 + period)) / (period * moment.b)


def _shape(fly: Any, J_F: float) -> Any:
    """The mass and width of a rim (mean radius, radial thickness) or a solid disc, or
    the mass J/k² for a radius of gyration k; {} without a shape."""
    if fly.k:
        return {"mass": J_F / fly.k ** 2}
    if not fly.shape:
        return {}
    mass = (mo.rim if fly.shape == "rim" else mo.disc)(J_F, fly.radius)
    width = None
    if fly.density and fly.shape == "disc":
        width = mo.width(mass, fly.density, fly.radius)
    elif fly.density and fly.thickness:
        half = fly.thickness / 2
        width = mo.width(mass, fly.density, fly.radius + half, fly.radius - half)
    return {"mass": mass, "width": width}


speeds_from_swing = dg.speeds_from_swing


def _balanced(spec: Any, cycle: float) -> Any:
    """The moment part with its "mean" term resolved: (part, shift [N m], mean term)."""
    part = spec.moment
    if part is None or part.mean is None:
        return 0.0, None
    trial, _lm = build_moment(part, spec.linkage, spec.topo, spec.bodies, spec.gravity,
                              spec.loads, spec.followers)
    mean = dg.mean_moment(trial, 0.0, cycle)
    value = mean if part.mean == "resisting" else -mean
    return -mean, (part.mean, value)


def _figures(spec: Any, moment: Optional[MomentModel], lm: Optional[Any], cycle: float,
             phi0: float, omega_m: Optional[float], sol: Any) -> None:
    """The numbers of a cycle textbooks print: the loop table, the work per cycle (the mean
    moment follows), and with Simpson tables ΔWmax with them read linearly."""
    if moment is None or moment.period is None or omega_m is None:
        return
    try:
        sol["loops"] = dg.energy_loops(moment, phi0, cycle, omega_m)
    except DescribedError:      # the diagram does not balance: no loops to tabulate
        return
    sol["omega_m"] = omega_m
    works = _term_works(spec.moment, lm, cycle, omega_m)
    if works is not None and sol.get("mean_term") is not None:
        name, value = sol["mean_term"]      # the balancing term: a drive or a resistance
        works.append((value if name == "constant" else -value) * cycle)
    if works is not None:
        w = float(sum(x for x in works if x > 0))
        if w > 0:
            sol["work_per_cycle"] = w
    tabs = [t for t in (spec.moment.table, spec.moment.resisting_table) if t is not None]
    if any(t[4] == "simpson" for t in tabs):
        import dataclasses

        def linear(t: Optional[Tuple[Any, ...]]) -> Optional[Tuple[Any, ...]]:
            return None if t is None else (t[0], t[1], "linear", t[3], "trapezoid")
        alt = dataclasses.replace(spec.moment, table=linear(spec.moment.table),
                                  resisting_table=linear(spec.moment.resisting_table))
        shift = sol.get("mean_term")
        cut = 0.0
        if shift is not None:
            trial, _ = build_moment(alt, spec.linkage, spec.topo, spec.bodies, spec.gravity,
                                    spec.loads, spec.followers)
            cut = -dg.mean_moment(trial, 0.0, cycle)
        m2, _ = build_moment(alt, spec.linkage, spec.topo, spec.bodies, spec.gravity,
                             spec.loads, spec.followers, shift=cut)
        sol["dW_trapezoid"] = dg.energy_loops(m2, phi0, cycle, omega_m).dW_max


def solve_flywheel(spec: Any) -> FlywheelSolution:
    """Build the models of a flywheel spec and solve its motion.

    Raises
    ------
    DescribedError
        ``stall``, ``unreachable``, ``no_steady_state``, ``not_periodic`` …
        (see the models and solvers), and ``end`` when the chosen method cannot
        stop at the requested end.
    """
    ms, fly = spec.motion, spec.flywheel
    inertia = build_inertia(spec.inertia, spec.linkage, spec.bodies, spec.followers)
    zero = isinstance(inertia, eq.ZeroInertia)
    if fly.J:
        inertia = inertia.plus(fly.J)
    if not inertia.constant and inertia.period is not None:
        grid = np.linspace(0.0, inertia.period, 3601)
        Je = np.asarray(inertia(grid)[0], dtype=float)
        if float(Je.min()) <= 1e-9 * float(Je.max()):
            raise DescribedError("the equivalent inertia vanishes: no link with mass moves "
                                 "there (ω would be unbounded)", reason="inertia_vanishes",
                                 angle=float(grid[int(np.argmin(Je))]))
    moment: Any = None      # a MomentModel: None only for a model without [moment]
    lm = None
    sol = {}
    if spec.moment is not None:
        mcycle = moment_cycle(spec.moment)
        shift, mean_term = _balanced(spec, mcycle)
        moment, lm = build_moment(spec.moment, spec.linkage, spec.topo, spec.bodies,
                                  spec.gravity, spec.loads, spec.followers, shift=shift)
        if mean_term is not None:
            sol["mean_term"] = mean_term
    cycle = mo.cycle(inertia.period, None if moment is None else moment.period)
    sol["period"] = cycle
    if ms.kind == "model":      # the equivalent model only, over one cycle (例 6-1)
        return _model(spec, inertia, zero, moment, lm, cycle, sol)
    end = "phi" if ms.phi_end is not None else "omega" if ms.omega_end is not None else "t"
    method = _auto(ms.kind, inertia, moment, end, ms.omega0) if ms.method == "auto" \
        else ms.method
    if isinstance(inertia, eq.LinkageInertia) and inertia.period is not None \
            and method not in ("energy", "closed_form"):
        # the integrators call Je tens of thousands of times: sample the linkage once
        # (every 0.1° by default, exact Je and dJe there) and interpolate by cubic
        # Hermite; the energy integral evaluates the exact model on its grid
        inertia = eq.SampledInertia(inertia, spec.inertia.samples)
    kw = dict(rtol=ms.rtol, atol=ms.atol, step=ms.step)
    if ms.kind == "steady":
        return _steady(spec, inertia, zero, moment, lm, cycle, method, kw, sol)
    if method == "closed_form":
        if not (inertia.constant and not moment.depends_on_phi):
            raise DescribedError("the closed form needs a constant inertia and a moment "
                                 "a − bω of the speed only", reason="method")
        J = float(inertia(np.array([0.0]))[0][0])
        # Me = a − bω with a every term but −bω (constant here: no φ dependence)
        a, b = float(moment.phi_part(0.0)), moment.b
        times = None if ms.t_end is None else np.linspace(0.0, ms.t_end, ms.points)
        if end == "phi":
            raise DescribedError("the closed form runs to a speed or a time, not an angle",
                                 reason="end", to_angle=False)
        mot = mo.linear_closed_form(J, a, b, 0.0, ms.omega0, omega_end=ms.omega_end,
                                    t=times, points=ms.points)
        if ms.phi0:             # the closed form counts φ from 0: start at phi0_deg
            import dataclasses
            mot = dataclasses.replace(mot, phi=mot.phi + ms.phi0)
        return FlywheelSolution(inertia, moment, mot, None, method,
                                omega_inf=(a / b) if b else None, **sol)
    if end != "phi":
        raise DescribedError(f"method {method} runs to an angle", reason="end", to_angle=True)
    if method == "energy":
        if moment.depends_on_omega:
            raise DescribedError("the energy integral needs a moment of the angle only",
                                 reason="method")
        phi = np.linspace(ms.phi0, ms.phi_end, ms.points)
        mot = mo.energy_solution(inertia, moment, ms.phi0, ms.omega0, phi)
    else:
        mot = mo.integrate(inertia, moment, ms.phi0, ms.omega0, ms.phi_end, method=method,
                           points=ms.points, **kw)
    extra = _shape(fly, fly.J) if fly.J else {}
    return FlywheelSolution(inertia, moment, mot, None, method, J_F=fly.J or None, **extra,
                            **sol)


def _model(spec: Any, inertia: Union[ConstantInertia, LinkageInertia, ZeroInertia], zero: bool,
           moment: Optional[MomentModel], lm: Optional[Any], cycle: float, sol: Any
          ) -> FlywheelSolution:
    """No [motion]: Je (and Me) over one cycle; the energy-swing forms (eqs 6-28 … 6-30)."""
    ms, fly = spec.motion, spec.flywheel
    phi = np.linspace(ms.phi0, ms.phi0 + cycle, ms.points)
    if zero and not fly.J:      # the flywheel is still to size: the machine's Je is 0
        Je, dJe = np.zeros_like(phi), np.zeros_like(phi)
    else:
        Je, dJe = inertia(phi)
    Je = np.asarray(Je, dtype=float) + np.zeros_like(phi)
    Me = np.zeros_like(phi) if moment is None else moment(phi, np.zeros_like(phi))
    _figures(spec, moment, lm, cycle, ms.phi0, fly.omega_mean, sol)
    dW = fly.dW
    if dW is None and fly.omega_mean is not None:
        if sol.get("loops") is None:
            net = 0.0 if moment is None else float(moment.energy(ms.phi0, ms.phi0 + cycle))
            raise DescribedError("the diagram's work over a cycle does not vanish: it has no "
                                 "energy swing about its mean", reason="no_loops",
                                 net_work=net)
        dW = sol["loops"].dW_max
    Je_mean = float(np.mean(Je[:-1])) if Je.size > 1 else float(Je[0])
    J_F = fly.J or None
    if fly.delta is not None:
        own = Je_mean - (fly.J or 0.0)
        J_F = mo.flywheel_approx(dW, fly.omega_mean, fly.delta, Je=max(own, 0.0))
        sol["equation"] = "6-29" if own > 0 else "6-30"
        Je = Je + J_F
        Je_mean += J_F
    swing = None
    if dW is not None and fly.omega_mean is not None and fly.delta is None:
        swing = speeds_from_swing(Je_mean, dW, fly.omega_mean)
    if J_F:
        sol.update(_shape(fly, J_F))
    return FlywheelSolution(inertia, moment, Model(phi, Je, np.asarray(dJe, dtype=float)
                                                   + np.zeros_like(phi),
                                                   np.asarray(Me, dtype=float)),
                            None, "none", J_F=J_F, swing=swing, **sol)


def _steady(spec: Any, inertia: Union[ConstantInertia, TableInertia, ZeroInertia], zero: bool,
            moment: MomentModel, lm: Optional[Any], cycle: float, method: str,
            kw: Dict[str, Optional[float]], sol: Any) -> FlywheelSolution:
    """The periodic steady state; with ``delta`` the flywheel sized for it exactly (and by
    eq 6-29).  A machine that cannot run at its mean speed without the flywheel (Je = 0,
    or too light for the swing) reports the motion with the sized flywheel."""
    ms, fly = spec.motion, spec.flywheel
    if moment.depends_on_phi and moment.period is None:
        raise DescribedError("the moment is not periodic (segments that do not join end "
                             "to end over a cycle): there is no steady state",
                             reason="moment_not_periodic")
    if inertia.period is None and moment.period is None:
        raise DescribedError("neither the inertia nor the moment varies with the angle: "
                             "the steady state is a constant speed", reason="not_periodic")
    steady = dict(omega_guess=ms.omega0, method=method, root=ms.root, tol=ms.tol,
                  max_iter=ms.max_iter, points=ms.points, phi0=ms.phi0, **kw)
    st = None
    if not zero or fly.J:   # a machine of no inertia of its own runs on a given flywheel
        try:
            st = mo.steady_state(inertia, moment, **steady)
        except DescribedError as e:
            if fly.delta is None or e.reason not in ("no_steady_state", "stall"):
                raise
    sol["omega_balance"] = balance_mean(moment, ms.phi0, cycle)
    if st is not None:
        omega_m = st.omega_mean
    elif moment.depends_on_omega:
        omega_m = sol["omega_balance"]
    else:
        omega_m = ms.omega0
    _figures(spec, moment, lm, cycle, ms.phi0, omega_m, sol)
    if fly.delta is None:
        if st is None:   # no inertia at all: nothing bounds the speed's change
            raise DescribedError("the machine has no inertia and no flywheel is given: its "
                                 "speed is not determined", reason="no_inertia")
        sol.update(_shape(fly, fly.J) if fly.J else {})
        return FlywheelSolution(inertia, moment, st.motion, st, method, J_F=fly.J or None,
                                **sol)
    grid = np.linspace(ms.phi0, ms.phi0 + cycle, 3601)[:-1]
    Je_mean = 0.0 if zero else float(np.mean(inertia(grid)[0]))
    loops = sol.get("loops")
    dW = loops.dW_max if loops is not None else _swing_at_mean(moment, ms.phi0, omega_m,
                                                                 cycle)
    try:
        sol["J_F_approx"] = mo.flywheel_approx(dW, omega_m, fly.delta, Je=Je_mean)
    except DescribedError:
        if st is None:
            raise
    J_F = mo.flywheel_exact(inertia, moment, fly.delta, omega_guess=ms.omega0, method=method,
                            points=ms.points, swing=(dW, omega_m, Je_mean),
                            **kw)  # type: ignore[arg-type]  # (kw: rtol, atol, step)
    st2 = mo.steady_state(inertia.plus(J_F), moment, **steady)
    if st is None:
        st, sol["motion_with_J_F"] = st2, True
        inertia = inertia.plus(J_F)
    sol.update(J_F=J_F, J_F_delta=st2.delta)
    sol.update(_shape(fly, J_F))
    if "J_F_approx" in sol and sol.get("mass") is not None:
        sol["mass_approx"] = _shape(fly, sol["J_F_approx"])["mass"]
    return FlywheelSolution(inertia, moment, st.motion, st, method, **sol)
