"""One problem of ``mechcli flywheel``: its models built and its motion solved.

:func:`solve_flywheel` maps the spec's plain data (duck-typed: ``inertia``,
``moment``, ``motion``, ``flywheel`` parts of SI numbers, as
:mod:`mechcli.spec.flywheel` reads them) onto the models of
:mod:`~.equivalent` and the solvers of :mod:`~.motion`.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.flywheel import equivalent as eq
from mechcli.core.flywheel import motion as mo
from mechcli.core.records import record

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


def build_inertia(part, linkage=None, bodies=None, followers=None):
    """The inertia model of the spec's ``inertia`` part."""
    if part.kind == "linkage":
        return eq.LinkageInertia(linkage, bodies, followers=followers or None,
                                 derivative=part.derivative, step=part.step)
    if part.kind == "table":
        return eq.TableInertia(np.asarray(part.phi), np.asarray(part.values), method=part.method)
    if part.kind == "chain":
        return eq.ChainInertia(part.members, masses=part.masses)
    return eq.ConstantInertia(part.J)


def _tables(part, linkage_moment):
    """The φ-tables of the moment summed into one (phi, M, method)."""
    tabs = []
    if part.table is not None:
        tabs.append((np.asarray(part.table[0]), np.asarray(part.table[1]), part.table[2]))
    if part.resisting_table is not None:
        r = part.resisting_table
        tabs.append((np.asarray(r[0]), -np.asarray(r[1]), r[2]))
    if linkage_moment is not None:
        tabs.append(linkage_moment)
    if not tabs:
        return None
    if len(tabs) == 1:
        return tabs[0]
    if all(np.array_equal(t[0], tabs[0][0]) for t in tabs) \
            and len({t[2] for t in tabs}) == 1:
        return tabs[0][0], sum(t[1] for t in tabs), tabs[0][2]
    # linear tables on other angles: their sum is linear on the union of the angles
    two_pi = 2 * np.pi

    def open_table(phi, M):         # without a closing node one turn after the first
        if np.isclose(phi[-1] - phi[0], two_pi, rtol=0, atol=1e-12):
            return phi[:-1], M[:-1]
        return phi, M

    base = tabs[0][0][0]
    grid = np.unique(np.concatenate([np.mod(open_table(t[0], t[1])[0] - base, two_pi)
                                     for t in tabs])) + base
    total = np.zeros_like(grid)
    for phi, M, _m in tabs:
        xp, fp = open_table(phi, M)
        total += np.interp(grid, xp, fp, period=two_pi)
    return grid, total, "linear"


def build_moment(part, linkage=None, topo=None, bodies=None, gravity=None, loads=(),
                 followers=None):
    """The moment model of the spec's ``moment`` part (and the linkage's loads)."""
    lm = None
    if part.loads and linkage is not None:
        loads = _with_band_limits(linkage, loads, followers)
        phi = np.linspace(0.0, 2 * np.pi, LOAD_SAMPLES, endpoint=False)
        M = eq.linkage_moment(linkage, topo, bodies, gravity, list(loads), phi,
                              followers=followers or None)
        lm = (phi, np.asarray(M, dtype=float), "linear")
    constant = part.constant - part.resisting
    if part.torques:
        constant += eq.chain_moment(part.torques)
    terms = dict(linear=part.drive, harmonic=part.harmonic,
                 segments=list(part.segments) or None, constant=constant)
    model = mo.MomentModel(table=_tables(part, lm), **terms)
    if lm is not None:
        # the loads' Me is smooth between the angles where a load switches on or off: the
        # integrators stop there (and at the user's own knots), not at every sample
        own = mo.MomentModel(table=_tables(part, None), **terms).breaks
        knots = np.concatenate([own[0], _switches(linkage, _with_band_limits(
            linkage, loads, followers), lm[0], followers)])
        model.breaks = (np.unique(knots), own[1] if len(own[0]) else 0.0, own[2])
    return model


def _with_band_limits(linkage, loads, followers):
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


def _switches(linkage, loads, phi, followers):
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


def _auto(kind, inertia, moment, end, omega0):
    """The method for the problem: exact where a closed form or the energy integral
    applies, else DOP853 -- or Radau when the motor's damping b makes the equation stiff
    (b/(Je ω) per radian large: a steep motor line on a light machine)."""
    if kind == "start" and end != "phi":
        return "closed_form"
    if kind == "start" and not moment.depends_on_omega:
        return "energy"
    if moment.depends_on_omega and moment.b > 0:
        Je_min = float(np.min(inertia(np.linspace(0, 2 * np.pi, 361))[0]))
        if moment.b / (Je_min * max(abs(omega0), 1e-300)) > STIFF:
            return "Radau"
    return "DOP853"


#: b/(Je ω) [1/rad] above which the automatic method is the stiff Radau
STIFF = 50.0


def _swing_at_mean(moment, phi0, omega_m, n=7201):
    """ΔWmax of eq. 6-29 as taught: the swing of the work of Me(φ, ωm) at the mean speed
    over a period (the φ-part exactly, minus b ωm φ)."""
    phi = np.linspace(phi0, phi0 + 2 * np.pi, n)
    W = moment.energy(phi0, phi) - moment.b * omega_m * (phi - phi0)
    return float(np.max(W) - np.min(W))


def balance_mean(moment, phi0):
    """The integral mean speed a steady state must have when Me is linear in ω with b > 0:
    the work over a period vanishes, so ωm = (1/2π)∫(Me + bω) dφ / b; None otherwise."""
    if not (moment.depends_on_omega and moment.b > 0):
        return None
    return float(moment.energy(phi0, phi0 + 2 * np.pi)) / (2 * np.pi * moment.b)


def _shape(fly, J_F):
    """The mass and width of a rim (mean radius, radial thickness) or a solid disc."""
    mass = (mo.rim if fly.shape == "rim" else mo.disc)(J_F, fly.radius)
    width = None
    if fly.density and fly.shape == "disc":
        width = mo.width(mass, fly.density, fly.radius)
    elif fly.density and fly.thickness:
        half = fly.thickness / 2
        width = mo.width(mass, fly.density, fly.radius + half, fly.radius - half)
    return {"mass": mass, "width": width}


def speeds_from_swing(J, dW, omega_mean):
    """Eqs. 6-28, 6-29 from numbers: δ = ΔWmax/(J ωm²) for the whole inertia J, and
    ωmax, ωmin = ωm (1 ± δ/2)."""
    delta = dW / (J * omega_mean ** 2)
    return delta, omega_mean * (1 + delta / 2), omega_mean * (1 - delta / 2)


def solve_flywheel(spec):
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
    if fly.J:
        inertia = inertia.plus(fly.J)
    if not inertia.constant and inertia.period is not None:
        grid = np.linspace(0.0, inertia.period, 3601)
        Je = np.asarray(inertia(grid)[0], dtype=float)
        if float(Je.min()) <= 1e-9 * float(Je.max()):
            raise DescribedError("the equivalent inertia vanishes: no link with mass moves "
                                 "there (ω would be unbounded)", reason="inertia_vanishes",
                                 angle=float(grid[int(np.argmin(Je))]))
    moment = None if spec.moment is None else build_moment(
        spec.moment, spec.linkage, spec.topo, spec.bodies, spec.gravity, spec.loads,
        spec.followers)
    if ms.kind == "model":      # the equivalent model only, over one turn (例 6-1)
        phi = np.linspace(ms.phi0, ms.phi0 + 2 * np.pi, ms.points)
        Je, dJe = inertia(phi)
        Me = np.zeros_like(phi) if moment is None else moment(phi, np.zeros_like(phi))
        swing = None
        if fly.dW is not None:  # Je's mean (with the flywheel J) carries the swing
            swing = speeds_from_swing(float(np.mean(Je)), fly.dW, fly.omega_mean)
        return FlywheelSolution(inertia, moment, Model(phi, np.asarray(Je, dtype=float),
                                                       np.asarray(dJe, dtype=float),
                                                       np.asarray(Me, dtype=float)),
                                None, "none", J_F=fly.J or None, swing=swing)
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
        if moment.depends_on_phi and moment.period is None:
            raise DescribedError("the moment is not periodic (segments that do not join end "
                                 "to end over a turn): there is no steady state",
                                 reason="moment_not_periodic")
        if inertia.period is None and moment.period is None:
            raise DescribedError("neither the inertia nor the moment varies with the angle: "
                                 "the steady state is a constant speed", reason="not_periodic")
        st = mo.steady_state(inertia, moment, omega_guess=ms.omega0, method=method,
                             root=ms.root, tol=ms.tol, max_iter=ms.max_iter, points=ms.points,
                             phi0=ms.phi0, **kw)
        sol = dict(inertia=inertia, moment=moment, motion=st.motion, steady=st, method=method,
                   J_F=fly.J or None, omega_balance=balance_mean(moment, ms.phi0))
        if fly.delta is not None:
            Je_mean = float(np.mean(inertia(st.motion.phi)[0]))
            sol["J_F_approx"] = mo.flywheel_approx(
                _swing_at_mean(moment, ms.phi0, st.omega_mean), st.omega_mean, fly.delta,
                Je=Je_mean)
            J_F = mo.flywheel_exact(inertia, moment, fly.delta, omega_guess=ms.omega0,
                                    method=method, points=ms.points, **kw)
            st2 = mo.steady_state(inertia.plus(J_F), moment, omega_guess=ms.omega0,
                                  method=method, root=ms.root, tol=ms.tol,
                                  max_iter=ms.max_iter, points=ms.points, phi0=ms.phi0, **kw)
            sol.update(J_F=J_F, J_F_delta=st2.delta)
        if fly.shape and sol["J_F"]:
            sol.update(_shape(fly, sol["J_F"]))
        return FlywheelSolution(**sol)
    if method == "closed_form":
        if not (inertia.constant and not moment.depends_on_phi):
            raise DescribedError("the closed form needs a constant inertia and a moment "
                                 "a − bω of the speed only", reason="method")
        J = float(inertia(np.array([0.0]))[0][0])
        # Me = a − bω with a every term but −bω (constant here: no φ dependence)
        a, b = float(moment.phi_part(0.0)), moment.b
        times = None if ms.t_end is None else np.linspace(0.0, ms.t_end, ms.points)
        mot = mo.linear_closed_form(J, a, b, 0.0, ms.omega0, omega_end=ms.omega_end,
                                    t=times, points=ms.points)
        if end == "phi":
            raise DescribedError("the closed form runs to a speed or a time, not an angle: "
                                 "give omega_end or t_end", reason="end")
        return FlywheelSolution(inertia, moment, mot, None, method,
                                omega_inf=(a / b) if b else None)
    if end != "phi":
        raise DescribedError(f"method {method} runs to an angle: give phi_end_deg (omega_end "
                             "and t_end need the closed form: a constant inertia and a "
                             "moment of the speed only)", reason="end")
    if method == "energy":
        if moment.depends_on_omega:
            raise DescribedError("the energy integral needs a moment of the angle only",
                                 reason="method")
        phi = np.linspace(ms.phi0, ms.phi_end, ms.points)
        mot = mo.energy_solution(inertia, moment, ms.phi0, ms.omega0, phi)
    else:
        mot = mo.integrate(inertia, moment, ms.phi0, ms.omega0, ms.phi_end, method=method,
                           points=ms.points, **kw)
    extra = _shape(fly, fly.J) if fly.shape and fly.J else {}
    return FlywheelSolution(inertia, moment, mot, None, method, J_F=fly.J or None, **extra)
