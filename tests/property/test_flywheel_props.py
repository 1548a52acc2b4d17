"""Flywheel motion at the extremes: the energy balance holds along every solution, and a
machine that runs out of energy stops at the right angle instead of returning garbage.

Every expected number is a balance (eq 6-10: ½Je ω² − ½Je0 ω0² = ∫Me dφ) or a closed form
worked from the model (constant and linear moments, eqs 6-16 … 6-20).
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechcli.core.errors import DescribedError
from mechcli.core.flywheel.equivalent import ConstantInertia, TableInertia
from mechcli.core.flywheel.motion import MomentModel, energy_solution, integrate

SETTINGS = settings(max_examples=20, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])

METHODS = st.sampled_from(["DOP853", "RK45"])


@st.composite
def inertias(draw):
    """A constant Je, or a positive smooth Je table over one turn (cubic or linear)."""
    J0 = draw(st.floats(0.05, 500.0))
    if draw(st.booleans()):
        return ConstantInertia(J0)
    n = draw(st.integers(6, 36))
    phi = np.linspace(0.0, 2 * np.pi, n + 1)
    amp = draw(st.floats(0.0, 0.45))
    k = draw(st.integers(1, 3))
    J = J0 * (1.0 + amp * np.cos(k * phi + draw(st.floats(0, 6.3))))
    J[-1] = J[0]
    return TableInertia(phi, J, method=draw(st.sampled_from(["cubic", "linear"])))


@st.composite
def moments_of_phi(draw):
    """Me(φ): a harmonic series, optionally plus a linear table (kinks) and a constant."""
    scale = draw(st.floats(0.1, 1e4))
    ak = [scale * draw(st.floats(-1, 1)) for _ in range(3)]
    bk = [scale * draw(st.floats(-1, 1)) for _ in range(3)]
    kw = {"harmonic": (scale * draw(st.floats(-0.3, 0.3)), ak, bk)}
    if draw(st.booleans()):
        phi = np.linspace(0.0, 2 * np.pi, draw(st.integers(3, 25)))
        M = scale * np.array([draw(st.floats(-1, 1)) for _ in phi])
        M[-1] = M[0]
        kw["table"] = (phi, M, "linear")
    return MomentModel(**kw)


@SETTINGS
@given(inertia=inertias(), moment=moments_of_phi(), turns=st.floats(0.05, 3.0),
       margin=st.floats(0.01, 100.0), method=METHODS)
def test_energy_balance_along_integrate(inertia, moment, turns, margin, method):
    """½Je ω² − ∫Me dφ stays ½Je0 ω0² along integrate() (eq 6-10), to 1e-9 of the energy."""
    phi_end = 2 * np.pi * turns
    probe = np.linspace(0.0, phi_end, 2001)
    W = moment.energy(0.0, probe)
    # ω0 with enough energy to pass the deepest dip of the work by the margin
    need = max(0.0, -float(W.min()))
    scale = max(need, float(np.max(np.abs(W))), 1e-9)
    Je0 = float(inertia(0.0)[0])
    omega0 = math.sqrt(2.0 * (need + margin * scale) / Je0)
    run = integrate(inertia, moment, 0.0, omega0, phi_end, method=method, points=257)
    balance = run.energy - 0.5 * Je0 * omega0 ** 2 - moment.energy(0.0, run.phi)
    assert np.max(np.abs(balance)) <= 1e-9 * float(np.max(run.energy))
    # and ω agrees with the exact energy integral (eq 6-12) on the same grid
    exact = energy_solution(inertia, moment, 0.0, omega0, run.phi)
    assert np.max(np.abs(run.omega - exact.omega)) <= 1e-9 * float(np.max(exact.omega))


@SETTINGS
@given(J=st.floats(1e-3, 1e4), omega0=st.floats(1e-2, 1e3), c=st.floats(1e-2, 1e5),
       method=METHODS)
def test_constant_resistance_stalls_at_the_spent_energy(J, omega0, c, method):
    """Me = −c, constant J: ω → 0 at φs = Jω0²/(2c); a stall, not a negative speed."""
    phi_s = J * omega0 ** 2 / (2 * c)
    with pytest.raises(DescribedError) as e:
        integrate(ConstantInertia(J), MomentModel(constant=-c), 0.0, omega0, 2.0 * phi_s,
                  method=method)
    assert e.value.reason == "stall"
    assert e.value.values["phi"] == pytest.approx(phi_s, rel=1e-8)


@SETTINGS
@given(J=st.floats(0.01, 100.0), b=st.floats(0.01, 100.0), drive=st.floats(-1e3, -1e-2),
       omega0=st.floats(0.1, 100.0), method=METHODS)
def test_decelerating_motor_stalls_where_the_closed_form_stops(J, b, drive, omega0, method):
    """J dω/dt = (a − Mr) − bω with a − Mr < 0 passes ω = 0 at t0 = (J/b) ln((ω0 − ω∞)/(−ω∞))
    (eq 6-19); integrate() in φ must stall at φ(t0) of eq 6-20, a speed-dependent stall."""
    w_inf = drive / b
    t0 = J / b * math.log((omega0 - w_inf) / (-w_inf))
    phi_s = w_inf * t0 + (omega0 - w_inf) * (J / b) * -math.expm1(-b * t0 / J)
    # near the stall ω ∝ sqrt(φs − φ) feeds back through −bω: E must be resolved far below
    # its own size there, so atol (on E, in J) is well under E0 = ½Jω0² >= 5e-5 J
    with pytest.raises(DescribedError) as e:
        integrate(J, MomentModel(linear=(drive, b)), 0.0, omega0, 2.0 * phi_s, method=method,
                  atol=1e-18)
    assert e.value.reason == "stall"
    assert e.value.values["phi"] == pytest.approx(phi_s, rel=1e-7)


@SETTINGS
@given(J=st.floats(1e-3, 1e3), M=st.floats(1e-2, 1e4), phi_end=st.floats(1e-3, 100.0),
       method=METHODS)
def test_start_from_rest(J, M, phi_end, method):
    """ω0 = 0 under a constant Me = M > 0: ω = sqrt(2Mφ/J), t = sqrt(2Jφ/M) (closed form)."""
    run = integrate(J, MomentModel(constant=M), 0.0, 0.0, phi_end, method=method, points=33)
    assert run.omega == pytest.approx(np.sqrt(2 * M * run.phi / J), rel=1e-9)
    assert run.t == pytest.approx(np.sqrt(2 * J * run.phi / M), rel=1e-9)


@SETTINGS
@given(J=st.floats(0.1, 100.0), b=st.floats(0.01, 100.0), w_inf=st.floats(0.5, 200.0),
       ratio=st.floats(0.05, 20.0), method=METHODS)
def test_linear_motor_in_phi_matches_the_closed_form_in_time(J, b, w_inf, ratio, method):
    """integrate() in φ against linear_closed_form's φ(t), ω(t) (eqs 6-19, 6-20): at the
    times integrate() reports, the closed form must be at the same angle and speed."""
    from mechcli.core.flywheel.motion import linear_closed_form

    omega0 = w_inf * ratio
    # run for one time constant, in angle
    end = linear_closed_form(J, b * w_inf, b, 0.0, omega0, t=[J / b])
    # E0 = ½Jω0² may be 3e-5 J here: atol (on E) well below it, so rtol governs
    run = integrate(J, MomentModel(linear=(b * w_inf, b)), 0.0, omega0, float(end.phi[-1]),
                    method=method, points=33, atol=1e-16)
    ref = linear_closed_form(J, b * w_inf, b, 0.0, omega0, t=run.t)
    assert ref.phi == pytest.approx(run.phi, rel=1e-8, abs=1e-12 * float(end.phi[-1]))
    assert ref.omega == pytest.approx(run.omega, rel=1e-8)


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(inertia=inertias(), rate=st.floats(0.01, 10.0), omega_m=st.floats(1.0, 100.0),
       f=st.lists(st.floats(-0.2, 0.2), min_size=4, max_size=4), method=METHODS)
def test_steady_state_mean_speed_balances_the_work(inertia, rate, omega_m, f, method):
    """Me = bωm − bω + Σ harmonics: over a period ∫Me dφ = 0, so the integral mean of ω
    (eq 6-26) is ωm exactly whatever Je(φ) and the harmonics (a balance, eq 6-10)."""
    from mechcli.core.flywheel.motion import steady_state

    J0 = float(inertia(0.0)[0])
    b = rate * J0 * omega_m  # decay of a disturbance ~ e^{−rate·φ}: not stiff for RK45
    scale = J0 * omega_m ** 2  # harmonics up to 0.2 Jωm² (no stall)
    moment = MomentModel(linear=(b * omega_m, b),
                         harmonic=(0.0, (scale * f[0], scale * f[1]), (scale * f[2], scale * f[3])))
    s = steady_state(inertia, moment, omega_guess=omega_m, method=method)
    assert s.omega_mean == pytest.approx(omega_m, rel=1e-8)
    assert s.residual <= 1e-8 * omega_m
    slack = 1e-12 * omega_m
    assert s.omega_min - slack <= s.omega_mean <= s.omega_max + slack
