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


EX11 = fourbar(101.6, 254, 177.8, 304.8)   # 例 1-1 (configs/ch1/ex1-1.toml)


def ex11_theta3_max():
    """Closed form (the hand calculation of configs/ch1/ex1-1.toml): theta3 is largest where
    crank and coupler fold (AC = l2 - l1); the cosine rule in triangle ADC gives
    theta3 = 180° - angle ADC and theta1 = 180° + angle DAC.  Returns (theta3, theta1) in
    degrees: (159.1513487698155, 204.533007117)."""
    l1, l2, l3, l4 = 101.6, 254, 177.8, 304.8
    ac = l2 - l1
    dac = math.degrees(math.acos((ac ** 2 + l4 ** 2 - l3 ** 2) / (2 * ac * l4)))
    adc = math.degrees(math.acos((l3 ** 2 + l4 ** 2 - ac ** 2) / (2 * l3 * l4)))
    return 180 - adc, 180 + dac


def shaper_theta4_extremes():
    """Independent closed form of 例 1-4's shaper (configs/ch1/ex1-4.toml, omega1 = 1):
    C at the origin, A = (0, l6), theta3 = atan2(l6 + l1 sin theta1, l1 cos theta1),
    theta4 = pi - asin((l6' - l3 sin theta3) / l4) (branch "left"); omega4 and alpha4 are
    central differences in theta1 (h = 1e-4 rad: truncation ~h^2 |d3 theta4| / 6 < 1e-8,
    round-off ~1e-16 / h^2 = 1e-8), the extremes refined by Brent's method.
    Returns (max omega4, min alpha4): (0.669357124, -2.81718084)."""
    from scipy.optimize import minimize_scalar

    l1, l3, l4, l6, l6p, h = 0.125, 0.600, 0.150, 0.275, 0.575, 1e-4

    def th4(t):
        th3 = np.arctan2(l6 + l1 * np.sin(t), l1 * np.cos(t))
        return np.pi - np.arcsin((l6p - l3 * np.sin(th3)) / l4)

    def om(t):
        return (th4(t + h) - th4(t - h)) / (2 * h)

    def al(t):
        return (th4(t + h) - 2 * th4(t) + th4(t - h)) / h ** 2

    t = np.linspace(0, 2 * np.pi, 20001)
    i, j = int(np.argmax(om(t))), int(np.argmin(al(t)))
    om_max = -minimize_scalar(lambda x: -om(x), bracket=(t[i - 1], t[i], t[i + 1]),
                              tol=1e-12).fun
    al_min = minimize_scalar(al, bracket=(t[j - 1], t[j], t[j + 1]), tol=1e-12).fun
    return om_max, al_min


def test_extreme_just_inside_the_range_start_is_refined():
    res = run(EX11, 204.1, 300.1, 1.0)
    hi, _ = res.extremes["theta3"]
    theta3_max, at = ex11_theta3_max()   # closed form: 159.1513487698155° at 204.533007117°
    assert math.degrees(hi.value) == pytest.approx(theta3_max, abs=1e-9)
    assert math.degrees(hi.at) == pytest.approx(at, abs=1e-7)


def test_narrow_range_keeps_1e_9_rad():
    res = run(EX11, 204.53, 204.54, 0.001)
    # closed form (ex11_theta3_max): theta1 = 204.533007117°
    assert math.degrees(res.extremes["theta3"][0].at) == pytest.approx(ex11_theta3_max()[1],
                                                                       abs=5e-8)


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
    # independent closed form + finite differences (shaper_theta4_extremes):
    # min alpha4 = -2.8171808 rad/s^2, max omega4 = 0.66935714 rad/s
    om_max, al_min = shaper_theta4_extremes()
    assert res.extremes["alpha4"][1].value == pytest.approx(al_min, abs=1e-6)
    assert res.extremes["omega4"][0].value == pytest.approx(om_max, abs=1e-7)


def test_partial_range_extremes_reach_the_assembly_limit_and_angles_stay_continuous():
    lk = fourbar(150, 100, 80, 120)  # the crank cannot pass theta1 = 180°
    res = run(lk, 0, 360, 1.0, partial=True)
    (a, b, why), = res.excluded
    assert why == "cannot assemble"
    # cosine rule: BD = l2 + l3 = 180 where 180^2 = 150^2 + 120^2 - 2*150*120 cos theta1,
    # cos theta1 = 4500/36000 = 0.125
    assert math.degrees(a) == pytest.approx(math.degrees(math.acos(0.125)), abs=1e-12)
    hi, lo = res.extremes["theta3"]
    # closed form: at the limit C lies on BD, theta3 = arg(B - D) = 124.2288663°; theta3
    # grows like sqrt(theta1 - a) there, so the refined limit (to ~1e-12 rad in theta1) reports
    # 124.228855 (this literal is that refined value, pinned; the exact one is checked below)
    assert math.degrees(hi.value) == pytest.approx(124.228855, abs=1e-5)
    b_lim = 150 * complex(math.cos(a), math.sin(a))
    assert 0 <= math.degrees(math.atan2(b_lim.imag, b_lim.real - 120)) - math.degrees(
        hi.value) < 2e-5
    assert hi.at == pytest.approx(a, abs=1e-12)
    swing2 = res.extremes["theta2"][0].value - res.extremes["theta2"][1].value
    # independent geometry: C = circle(B, l2) ∩ circle(D, l3) left of B→D (branch +1), theta2 =
    # arg(C - B) unwrapped over the feasible arc -a … a, 400001 samples: 268.56977°
    tq = np.linspace(-a, a, 400001)
    bq = 150 * np.exp(1j * tq)
    d = np.abs(120 - bq)
    x = (100 ** 2 - 80 ** 2 + d ** 2) / (2 * d)
    cq = bq + (120 - bq) / d * (x + 1j * np.sqrt(np.maximum(100 ** 2 - x ** 2, 0)))
    th2_ref = np.unwrap(np.angle(cq - bq))
    assert math.degrees(swing2) == pytest.approx(
        math.degrees(th2_ref.max() - th2_ref.min()), abs=1e-4)   # 268.56977°
    th2 = res.values["theta2"]
    assert th2[0] == pytest.approx(th2[-1], abs=1e-12)   # 0° and 360° are one pose
    assert not res.extremes["omega2"][1].bounded          # grows without bound at the limit
    assert res.extremes["omega2"][1].at == pytest.approx(a, abs=1e-9)


def test_gap_between_grid_points_is_found():
    lk = fourbar(100, 250, 149.999, 300)
    with pytest.raises(AssemblyError) as exc:
        run(lk, 0.5, 360.5, 1.0)
    # the gap lies between the grid points 179.5° and 180.5° (the message is worded by the
    # report layer; tests/cli checks that text).  Cosine rule: B is farther than
    # l2 + l3 = 399.999 from D where cos theta1 < (100^2 + 300^2 - 399.999^2)/(2*100*300),
    # i.e. from theta1 = 179.7041° (and symmetrically to 180.2959°)
    (start, stop, why), = exc.value.intervals
    assert why == "cannot assemble"
    assert 179.70 <= math.degrees(start) < 179.71 and 179.71 < math.degrees(stop) < 180.5


def test_parallelogram_change_points_are_dead_points():
    lk = fourbar(100, 300, 100, 300)
    with pytest.raises(AssemblyError) as exc:
        run(lk, 0, 360, 1.0)
    ends = sorted(round(math.degrees(s)) for s, _e, _r in exc.value.intervals)
    # a parallelogram's change points: all four links on the frame line, theta1 = 0° and 180°
    assert ends == [0, 180, 360] and "dead point" in str(exc.value)
    res = run(lk, 0, 360, 1.0, partial=True)
    # no 1e9 spikes next to the change points; 0°..180° is the parallelogram
    # (alpha3 = 0), past 180° the fixed branch continues as the antiparallelogram
    assert np.max(np.abs(res.values["alpha3"])) < 200
    first = res.q < math.pi
    assert np.max(np.abs(res.values["alpha3"][first])) < 1e-6


def test_near_dead_point_at_the_sweep_end_is_flagged_once():
    res = run(fourbar(100, 300, 251, 150), 0, 360, 1.0)
    near = [t for t in res.toggles if math.degrees(math.asin(t.sin_gamma)) < 2.1]  # 2.078°
    assert len(near) == 1 and near[0].at == 0.0
    # closed form: at theta1 = 0, BD = l4 - l1 = 50 and the transmission angle at C is
    # acos((300^2 + 251^2 - 50^2) / (2*300*251)) = 2.0776220005°
    gamma0 = math.degrees(math.acos((300 ** 2 + 251 ** 2 - 50 ** 2) / (2 * 300 * 251)))
    assert math.degrees(math.asin(near[0].sin_gamma)) == pytest.approx(gamma0, abs=1e-8)


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
