"""Sweep analysis: extremes, gaps and dead points, independent of the output step.

Each case reproduces a defect found in review (an independent 50-digit
Newton solver and dense sweeps were the references).
"""

import math

import numpy as np
import pytest

from mechcli.core.errors import AssemblyError
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities
from mechcli.core.linkage import RRR, Crank, DriverMotion, Ground, Linkage, solve
from mechcli.spec.kin import load_kin_spec
from tests.conftest import CONFIGS


def fourbar(l1, l2, l3, l4):
    return Linkage(4, (Ground("A", 0, 0), Ground("D", l4, 0), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, 1)))


def run(lk, start, stop, step, partial=False, order=2, omega=10.0):
    q = np.radians(np.arange(start, stop + step / 2, step))
    periodic = abs(stop - start - 360) < 1e-9
    qs = default_quantities(lk, order)
    return analyse_sweep(lk, Sweep(1, q, omega, 0.0, {}, periodic), qs, order, partial=partial)


def dense_extremes(lk, sym, start=0.0, stop=360.0, order=2):
    q = np.radians(np.linspace(start, stop, 720001))
    m = solve(lk, {1: DriverMotion(q, 10.0)}, order=order)
    v = {q_.symbol: q_ for q_ in default_quantities(lk, order)}[sym].get(m)
    v = np.unwrap(v) if sym.startswith(("theta", "gamma")) else v
    return float(v[m.regular].max()), float(v[m.regular].min())


EX11 = fourbar(101.6, 254, 177.8, 304.8)


def test_extreme_just_inside_the_range_start_is_refined():
    res = run(EX11, 204.1, 300.1, 1.0)
    hi, _ = res.extremes["theta3"]
    assert math.degrees(hi.value) == pytest.approx(159.1513487698155, abs=1e-9)
    assert math.degrees(hi.at) == pytest.approx(204.533007117, abs=1e-7)


def test_narrow_range_keeps_1e_9_rad():
    res = run(EX11, 204.53, 204.54, 0.001)
    assert math.degrees(res.extremes["theta3"][0].at) == pytest.approx(204.533007117, abs=5e-8)


@pytest.mark.parametrize("step", [15.0, 60.0, 120.0])
def test_extremes_do_not_depend_on_the_output_step(step):
    spec = load_kin_spec(CONFIGS / "ch1" / "ex1-4.toml")
    inp = spec.input
    qs = default_quantities(spec.linkage, 2)
    ref = analyse_sweep(spec.linkage, Sweep(1, inp.q, 1.0, 0.0, {}, True), qs, 2)
    q = np.radians(np.arange(0.0, 360.0 + step / 2, step))
    res = analyse_sweep(spec.linkage, Sweep(1, q, 1.0, 0.0, {}, True), qs, 2)
    for sym in ("alpha4", "omega4", "aE", "sE"):
        for a, b in zip(res.extremes[sym], ref.extremes[sym]):
            assert a.value == pytest.approx(b.value, rel=1e-9, abs=1e-12)
            # the reported value is the value at the reported angle
            m = solve(spec.linkage, {1: DriverMotion(np.array([a.at]), 1.0)}, order=2)
            got = {q_.symbol: q_ for q_ in qs}[sym].get(m)[0]
            assert got == pytest.approx(a.value, rel=1e-9, abs=1e-12)
    assert res.extremes["alpha4"][1].value == pytest.approx(-2.8171808, abs=1e-6)
    assert res.extremes["omega4"][0].value == pytest.approx(0.66935714, abs=1e-7)


def test_partial_range_extremes_reach_the_assembly_limit_and_angles_stay_continuous():
    lk = fourbar(150, 100, 80, 120)  # the crank cannot pass theta1 = 180°
    res = run(lk, 0, 360, 1.0, partial=True)
    (a, b, why), = res.excluded
    assert why == "cannot assemble"
    assert math.degrees(a) == pytest.approx(math.degrees(math.acos(0.125)), abs=1e-12)
    hi, lo = res.extremes["theta3"]
    assert math.degrees(hi.value) == pytest.approx(124.228855, abs=1e-5)
    assert hi.at == pytest.approx(a, abs=1e-12)
    swing2 = res.extremes["theta2"][0].value - res.extremes["theta2"][1].value
    assert math.degrees(swing2) == pytest.approx(268.56977, abs=1e-4)
    th2 = res.values["theta2"]
    assert th2[0] == pytest.approx(th2[-1], abs=1e-12)   # 0° and 360° are one pose
    assert not res.extremes["omega2"][1].bounded          # grows without bound at the limit
    assert res.extremes["omega2"][1].at == pytest.approx(a, abs=1e-9)


def test_gap_between_grid_points_is_found():
    lk = fourbar(100, 250, 149.999, 300)
    with pytest.raises(AssemblyError) as exc:
        run(lk, 0.5, 360.5, 1.0)
    # the gap lies between the grid points 179.5° and 180.5° (the message is worded by the
    # report layer; tests/cli checks that text)
    (start, stop, why), = exc.value.intervals
    assert why == "cannot assemble"
    assert 179.70 <= math.degrees(start) < 179.71 and 179.71 < math.degrees(stop) < 180.5


def test_parallelogram_change_points_are_dead_points():
    lk = fourbar(100, 300, 100, 300)
    with pytest.raises(AssemblyError) as exc:
        run(lk, 0, 360, 1.0)
    ends = sorted(round(math.degrees(s)) for s, _e, _r in exc.value.intervals)
    assert ends == [0, 180, 360] and "dead point" in str(exc.value)
    res = run(lk, 0, 360, 1.0, partial=True)
    # no 1e9 spikes next to the change points; 0°..180° is the parallelogram
    # (alpha3 = 0), past 180° the fixed branch continues as the antiparallelogram
    assert np.max(np.abs(res.values["alpha3"])) < 200
    first = res.q < math.pi
    assert np.max(np.abs(res.values["alpha3"][first])) < 1e-6


def test_near_dead_point_at_the_sweep_end_is_flagged_once():
    res = run(fourbar(100, 300, 251, 150), 0, 360, 1.0)
    near = [t for t in res.toggles if math.degrees(math.asin(t.sin_gamma)) < 2.1]
    assert len(near) == 1 and near[0].at == 0.0
    assert math.degrees(math.asin(near[0].sin_gamma)) == pytest.approx(2.0776220005, abs=1e-8)


def test_rotating_link_extremes_are_the_sweep_ends():
    res = run(fourbar(100, 300, 250, 200), 0, 360, 5.0, order=0)
    lo_hi = dense_extremes(fourbar(100, 300, 250, 200), "theta3", order=0)
    assert res.extremes["theta3"][0].value == pytest.approx(lo_hi[0], abs=1e-9)


def test_kite_folded_position_is_a_dead_point_not_an_assembly_failure():
    # l1 = l4, l2 = l3: at theta1 = 0, B lands on D and C is indeterminate
    lk = fourbar(100, 150, 150, 100)
    for order in (0, 2):
        m = solve(lk, {1: DriverMotion(np.array([0.0, 0.1]), 1.0)}, order=order)
        assert m.feasible.all() and list(m.regular) == [False, True]
    with pytest.raises(AssemblyError) as exc:
        run(lk, 0, 360, 1.0)
    assert exc.value.intervals[0][2] == "dead point"
    assert exc.value.intervals[0][0] == pytest.approx(0.0, abs=1e-9)
