"""Public evaluators: kinematic coefficients, sweeps with omega(phi), the force evaluator."""

import numpy as np
import pytest

import mechcli
from mechcli.core.linkage import RRP, Crank, Ground, Linkage
from mechcli.core.linkage.force_analysis import ForceEvaluator
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities
from mechcli.core.linkage.kinetostatics import Body, Load, LoadProgram, topology

#: 例 1-1's four-bar [m]
FOUR_BAR = mechcli.four_bar(0.1016, 0.254, 0.1778, 0.3048)
Q = np.radians(np.arange(0.0, 360.0, 5.0))


def test_coefficients_combine_into_any_speed_and_acceleration():
    """omega_n = w1 dθn/dφ and alpha_n = a1 dθn/dφ + w1² d²θn/dφ², against a direct
    solve at w1 = 7 rad/s, a1 = -3 rad/s²."""
    c = mechcli.kinematic_coefficients(FOUR_BAR, Q)
    m = mechcli.solve(FOUR_BAR, {1: mechcli.DriverMotion(Q, 7.0, -3.0)})
    for n in (2, 3):
        np.testing.assert_allclose(m.links[n].omega, 7.0 * c.links[n].omega, rtol=0, atol=1e-12)
        np.testing.assert_allclose(m.links[n].alpha,
                                   -3.0 * c.links[n].omega + 49.0 * c.links[n].alpha,
                                   rtol=0, atol=1e-10)
    np.testing.assert_allclose(m.points["C"].ay,
                               -3.0 * c.points["C"].vy + 49.0 * c.points["C"].ay, atol=1e-10)


def test_coefficients_are_derivatives_of_the_positions():
    """dθ3/dφ and d²θ3/dφ² against central differences of θ3(φ) (h = 1e-4 rad: error
    ~h² θ''' ≈ 1e-8)."""
    h = 1e-4
    c = mechcli.kinematic_coefficients(FOUR_BAR, Q)
    t = [mechcli.solve(FOUR_BAR, {1: mechcli.DriverMotion(Q + d)}, order=0).links[3].theta
         for d in (-h, 0.0, h)]
    np.testing.assert_allclose(c.links[3].omega, (t[2] - t[0]) / (2 * h), atol=1e-7)
    np.testing.assert_allclose(c.links[3].alpha, (t[2] - 2 * t[1] + t[0]) / h**2, atol=1e-5)


def _omega(q):
    return 10.0 + 2.0 * np.sin(q)            # a speed that fluctuates over the turn


def _alpha(q):
    return 2.0 * np.cos(q) * _omega(q)       # dω/dt = dω/dφ · ω


@pytest.mark.parametrize("rate", ["callable", "array"])
def test_sweep_with_varying_input_speed(rate):
    """A sweep whose ω1, α1 vary with φ: at the grid, α3 = α1 dθ3/dφ + ω1² d²θ3/dφ²
    exactly (both forms of the rate give the grid values exactly)."""
    q = np.radians(np.arange(0.0, 361.0, 1.0))
    dq, ddq = (_omega, _alpha) if rate == "callable" else (_omega(q), _alpha(q))
    sweep = Sweep(1, q, dq, ddq, {}, True)
    quantities = default_quantities(FOUR_BAR, 2)
    res = analyse_sweep(FOUR_BAR, sweep, quantities, 2)
    c = mechcli.kinematic_coefficients(FOUR_BAR, q)
    expect = _alpha(q) * c.links[3].omega + _omega(q) ** 2 * c.links[3].alpha
    np.testing.assert_allclose(res.values["alpha3"], expect, rtol=0, atol=1e-9)
    # the refined max of ω3 is at least the grid's, and (exact rates) a local maximum
    # of ω1(φ) dθ3/dφ: its value beats both neighbours 1e-6 rad away
    hi, _lo = res.extremes["omega3"]
    assert hi.value >= float(np.max(res.values["omega3"])) - 1e-12
    if rate == "callable":
        x = np.array([hi.at - 1e-6, hi.at + 1e-6])
        w3 = _omega(x) * mechcli.kinematic_coefficients(FOUR_BAR, x).links[3].omega
        assert hi.value >= w3.max() - 1e-12


def test_rate_array_interpolates_between_nodes():
    """The array form interpolates ω1 linearly between its nodes: the refined extreme is
    then within the interpolation error (≈ h²/8 ω'' ≈ 3e-4 · 2 rad/s at 1°) of the exact."""
    q = np.radians(np.arange(0.0, 361.0, 1.0))
    quantities = default_quantities(FOUR_BAR, 2)
    exact = analyse_sweep(FOUR_BAR, Sweep(1, q, _omega, _alpha, {}, True), quantities, 2)
    interp = analyse_sweep(FOUR_BAR, Sweep(1, q, _omega(q), _alpha(q), {}, True), quantities, 2)
    for sym in ("omega3", "alpha3"):
        for e, i in zip(exact.extremes[sym], interp.extremes[sym]):
            assert i.value == pytest.approx(e.value, rel=1e-4), sym


def test_sweep_rate_array_must_match_q():
    sweep = Sweep(1, Q, np.ones(3))
    with pytest.raises(ValueError, match="shape of q"):
        sweep.inputs(Q)


def test_force_evaluator_power_balance_with_varying_speed():
    """The public evaluator at ω1(φ), α1(φ): the balancing torque's power balances the
    inertia, gravity and load powers (virtual-power residual at round-off)."""
    slider_crank = Linkage(4, (Ground("A", 0.0, 0.0), Crank(1, "A", "B", 0.1),
                               RRP("C", "B", 2, 0.35, 3, 4, "A", 0.0, 0.02, 1, "3")))
    bodies = {1: Body(1, 2.0, 0.01), 2: Body(2, 3.0, 0.04), 3: Body(3, 5.0, 0.0)}
    programs = [LoadProgram(Load("Fr", 3, fx=-400.0))]
    q = np.radians(np.arange(0.0, 360.0, 10.0))
    ev = ForceEvaluator(slider_crank, topology(slider_crank), Sweep(1, q, _omega, _alpha),
                        bodies, (0.0, -9.8), programs)
    fr, masks, motion = ev(q)
    assert masks["Fr"].all()
    np.testing.assert_allclose(motion.links[1].omega, _omega(q))
    peak = float(np.max(np.abs(fr.balancing[1])))
    assert peak > 10.0
    assert float(np.max(np.abs(fr.power_residual))) <= 1e-9 * peak
    # massless, no gravity: virtual work alone gives Mb ω1 + (-400 N) v3 = 0 at every position
    ev0 = ForceEvaluator(slider_crank, topology(slider_crank), Sweep(1, q, 10.0, 0.0),
                         {}, (0.0, 0.0), programs)
    fr0, _, m0 = ev0(q)
    np.testing.assert_allclose(fr0.balancing[1] * 10.0, 400.0 * m0.slides["3"].v, atol=1e-9)
