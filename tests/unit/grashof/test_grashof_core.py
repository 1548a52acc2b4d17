"""mechcli.core.grashof.fourbar: book and slides values, and cross-checks against the linkage engine.

The closed forms (limit positions, θ, ψ, K, γ) are checked against an
independent dense sweep of the linkage engine (``mechcli.core.linkage``):
positions solved at 0.001°-spaced input angles, extremes read off the grid
(error O(step²) in the extreme values, well below the tolerances used).
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from mechcli.core.grashof import fourbar as gf
from mechcli.core.linkage import RPR, RRP, RRR, Crank, DriverMotion, Ground, Linkage, solve

DEG = math.pi / 180


# ----------------------------------------------------------------- book 例 3-1
def test_ex3_1_first_set_is_a_double_rocker():
    """例 3-1 prints 最长杆 170.00, 最短杆 100.00, 该机构是双摇杆机构."""
    an = gf.analyse_fourbar([100, 150, 170, 110])
    assert an.klass.types == ["double_rocker"]
    assert not an.klass.grashof[0]
    assert an.lengths[0, an.klass.longest[0] - 1] == 170
    assert an.lengths[0, an.klass.shortest[0] - 1] == 100
    assert [k.types[0] for k in gf.classify_inversions([100, 150, 170, 110])] == \
        ["double_rocker"] * 4


def test_ex3_1_second_set_and_its_inversions():
    """例 3-1 (10, 50, 35, 30): crank-rocker; with the shortest link as frame a double crank."""
    inv = gf.classify_inversions([10, 50, 35, 30])
    assert [k.types[0] for k in inv] == ["double_crank", "crank_rocker", "double_rocker",
                                         "crank_rocker"]
    assert inv[0].cranks() == [2, 4] and inv[3].cranks() == [1] and inv[1].cranks() == [1]


@pytest.mark.parametrize("lengths, gamma1, gamma2", [
    # 例 3-8 计算结果 (lengths as printed, 0.01 mm) -> eq. 3-49 as printed
    ([77.00, 218.44, 290, 276.80], 43.50, 87.00),
    ([77.30, 215.00, 290, 277.30], 43.59, 87.89),
    ([77.12, 217.08, 290, 277.00], 43.54, 87.35),
    ([77.29, 215.09, 290, 277.29], 43.58, 87.87),
])
def test_ex3_8_transmission_angles_and_design_data(lengths, gamma1, gamma2):
    m = gf.analyse_fourbar(lengths).merit
    # printed to 0.01°; the book's unrounded lengths move case 1 by 0.006°
    assert abs(math.degrees(m.gamma0[0]) - gamma1) < 0.0065
    assert abs(math.degrees(m.gamma180[0]) - gamma2) < 0.005
    assert abs(m.K[0] - 1.25) < 1e-4          # design data K = 1.25
    assert abs(math.degrees(m.psi[0]) - 34) < 2e-3  # and psi = 34°


# ----------------------------------------------------------- independent crank test
def _turns_fully(a, b, c, d, n=721):
    """Input link a (frame d, coupler b, output c) assembles at every angle (grid incl. 0, π)."""
    th = np.linspace(0, 2 * np.pi, n)
    bd = np.sqrt(a * a + d * d - 2 * a * d * np.cos(th))
    return bool(np.all((bd >= abs(b - c) - 1e-12) & (bd <= b + c + 1e-12)))


def test_crank_mask_matches_assembly_over_a_full_turn():
    rng = np.random.default_rng(7)
    L = rng.uniform(1, 10, (400, 4))
    L = L[gf.closes(L)]
    for frame in (1, 2, 3, 4):
        kl = gf.classify_fourbar(L, frame=frame)
        f0 = frame - 1
        for i in range(len(L)):
            for inp in ((f0 + 1) % 4, (f0 + 3) % 4):
                out = (f0 + 3) % 4 if inp == (f0 + 1) % 4 else (f0 + 1) % 4
                got = _turns_fully(L[i, inp], L[i, (f0 + 2) % 4], L[i, out], L[i, f0])
                assert kl.crank_mask[i, inp] == got, (L[i], frame, inp + 1)


def test_change_point_and_parallelogram_are_named():
    assert gf.classify_fourbar([10, 40, 10, 40]).types == ["parallelogram"]
    assert gf.classify_fourbar([10, 40, 10, 40], crossed=True).types == ["antiparallelogram"]
    assert gf.classify_fourbar([20, 50, 40, 30]).types == ["change_point_crank_rocker"]
    assert gf.classify_fourbar([20, 50, 40, 30], frame=1).types == ["change_point_double_crank"]
    assert gf.classify_fourbar([20, 50, 40, 30], frame=3).types == ["change_point_double_rocker"]
    # within the relative tolerance, and not beyond it
    assert gf.classify_fourbar([20, 50, 40, 30 * (1 + 1e-12)]).change_point[0]
    assert not gf.classify_fourbar([20, 50, 40, 30.001]).change_point[0]


def test_closure_error_names_the_link():
    with pytest.raises(gf.ClosureError, match="link 2"):
        gf.analyse_fourbar([10, 100, 20, 30])
    assert issubclass(gf.ClosureError, gf.UnsolvableError)


def test_input_must_be_joined_to_the_frame():
    with pytest.raises(ValueError, match="joined to the frame"):
        gf.analyse_fourbar([10, 50, 35, 30], frame=4, input_link=2)


# ------------------------------------------------------------ engine cross-checks
def _fourbar(a, b, c, d):
    return Linkage(frame=4, elements=(
        Ground("A", 0.0, 0.0), Ground("D", d, 0.0),
        Crank(link=1, pivot="A", point="B", length=a),
        RRR(joint="C", point_a="B", link_a=2, length_a=b, point_b="D", link_b=3, length_b=c,
            branch=+1)))


@pytest.mark.parametrize("lengths", [
    [28, 52, 50, 72],              # exercise 3-1
    [10, 50, 35, 30],              # 例 3-1, second set
    [77.12, 217.08, 290, 277.00],  # 例 3-8 (4)
    [1, 2.5, 2, 3],                # Hrones-Nelson example
])
def test_crank_rocker_merit_against_engine_sweep(lengths):
    a, b, c, d = lengths
    m = gf.analyse_fourbar(lengths).merit
    th = np.linspace(0, 2 * np.pi, 360_001)
    mo = solve(_fourbar(a, b, c, d), {1: DriverMotion(th)}, order=0, on_fail="raise")
    th3 = np.unwrap(mo.links[3].theta)
    i_max, i_min = int(np.argmax(th3)), int(np.argmin(th3))
    psi = th3[i_max] - th3[i_min]
    assert_allclose(m.psi[0], psi, atol=1e-8)
    # the crank angles of the two output extremes: theta = |Δθ1| − π
    dth = (th[i_min] - th[i_max]) % (2 * np.pi)
    theta = abs(dth - np.pi)
    assert_allclose(m.theta[0], theta, atol=2 * 2 * np.pi / 360_000)
    assert_allclose(m.K[0], (np.pi + theta) / (np.pi - theta), atol=1e-4)
    # limit positions: the output angles at the extremes (C above AD, the open branch)
    ext = {round(float(np.mod(th3[i], 2 * np.pi)), 6) for i in (i_max, i_min)}
    ours = {round(float(m.theta3_ext[0]), 6), round(float(m.theta3_fold[0]), 6)}
    assert_allclose(sorted(ext), sorted(ours), atol=1e-5)
    # transmission angle: the engine's RRR conditioning, minimum and maximum over the turn
    gam = np.arccos(np.clip(np.abs(np.cos(mo.links[2].theta - mo.links[3].theta)), 0, 1))
    assert_allclose(m.gamma_min[0], gam.min(), atol=1e-8)
    # a 90° maximum is a kink of |cos|: the grid is off by up to one step there
    assert_allclose(m.gamma_max[0], gam.max(), atol=2e-5)
    assert gam.max() <= m.gamma_max[0] + 1e-12
    j = int(np.argmin(gam))
    at = min(th[j], 2 * np.pi - th[j])
    assert_allclose(m.gamma_min_at[0], at, atol=1e-4)


def test_rocker_input_range_against_engine():
    """例 3-1 set 1 (double rocker): the input only rocks; γ = 0 at the end of its range."""
    a, b, c, d = 100, 150, 170, 110
    m = gf.analyse_fourbar([a, b, c, d]).merit
    th = np.linspace(0, np.pi, 180_001)
    mo = solve(_fourbar(a, b, c, d), {1: DriverMotion(th)}, order=0, on_fail="mask")
    ok = th[mo.feasible]
    assert_allclose([m.input_lo[0], m.input_hi[0]], [ok.min(), ok.max()], atol=2e-5)
    assert m.gamma_min[0] == 0.0


def test_dead_points_when_the_rocker_drives_are_the_limit_positions():
    """Crank and coupler in line: the engine's angle B-A vs C-B is 0 or π there."""
    a, b, c, d = 28, 52, 50, 72
    m = gf.analyse_fourbar([a, b, c, d]).merit
    for th1 in (m.theta1_ext[0], m.theta1_fold[0]):
        mo = solve(_fourbar(a, b, c, d), {1: DriverMotion(np.array([th1]))}, order=0)
        cross = np.sin(mo.links[2].theta - th1)
        assert abs(cross[0]) < 1e-9
    assert_allclose(sorted(m.dead_theta3[0]), sorted([m.theta3_ext[0], m.theta3_fold[0]]))


def _slider(a, b, e):
    return Linkage(frame=4, elements=(
        Ground("A", 0.0, 0.0), Ground("O", 0.0, e),
        Crank(link=1, pivot="A", point="B", length=a),
        RRP(joint="C", point="B", link=2, length=b, slider=3, guide_link=4, guide_point="O")))


@pytest.mark.parametrize("a, b, e", [(30, 60, 10), (20, 60, 40), (100, 300, 0), (15, 48, 20),
                                     (15, 48, -20)])
def test_slider_crank_against_engine(a, b, e):
    sc = gf.analyse_slider_crank(a, b, e)
    th = np.linspace(0, 2 * np.pi, 360_001)
    mo = solve(_slider(a, b, e), {1: DriverMotion(th)}, order=0, on_fail="mask")
    assert mo.feasible.all()
    x = mo.points["C"].p.real
    assert_allclose(sc.stroke, x.max() - x.min(), atol=1e-6)
    dth = (th[np.argmin(x)] - th[np.argmax(x)]) % (2 * np.pi)
    assert_allclose(sc.theta, abs(dth - np.pi), atol=3e-5)
    alpha = np.arcsin(np.clip(np.abs(mo.points["B"].p.imag - e) / b, 0, 1))
    assert_allclose(sc.alpha_max, alpha.max(), atol=1e-6)


def test_slider_crank_crank_condition_and_exam1_range():
    """Slides exam 1: b = 60, e = 10 -> a crank iff a <= 50."""
    assert gf.analyse_slider_crank(50, 60, 10).crank_exists
    assert gf.analyse_slider_crank(50, 60, 10).boundary
    assert not gf.analyse_slider_crank(50.01, 60, 10).crank_exists
    with pytest.raises(gf.ClosureError):
        gf.analyse_slider_crank(10, 20, 30)


@pytest.mark.parametrize("a, d, e", [(100, 200, 40), (100, 200, 0), (50, 80, 10)])
def test_guide_bar_swing_and_transmission_against_engine(a, d, e):
    gb = gf.analyse_guide_bar(a, d, e)
    assert gb.kind == "oscillating"
    link = Linkage(frame=4, elements=(
        Ground("A", 0.0, 0.0), Ground("C", d, 0.0),
        Crank(link=1, pivot="A", point="B", length=a),
        RPR(point="B", block=2, pivot="C", guide=3, offset=e)))
    th = np.linspace(0, 2 * np.pi, 360_001)
    mo = solve(link, {1: DriverMotion(th, 1.0)}, order=1, on_fail="raise")
    th3 = np.unwrap(mo.links[3].theta)
    assert_allclose(gb.psi, th3.max() - th3.min(), atol=1e-8)
    dth = (th[np.argmin(th3)] - th[np.argmax(th3)]) % (2 * np.pi)
    assert_allclose(gb.theta, abs(dth - np.pi), atol=3e-5)
    # γ from the velocities: force on the guide normal to it, velocity of its point at B
    B = mo.points["B"].p
    v_guide = 1j * mo.links[3].omega * (B - d)
    normal = np.exp(1j * (mo.links[3].theta + np.pi / 2))
    cos_a = np.abs((v_guide * np.conj(normal)).real) / np.maximum(np.abs(v_guide), 1e-300)
    gamma = np.pi / 2 - np.arccos(np.clip(cos_a, 0, 1))
    assert_allclose(gb.gamma_min, gamma.min(), atol=1e-7)
    assert_allclose(gb.gamma_max, gamma.max(), atol=1e-7)


def test_guide_bar_kinds():
    assert gf.analyse_guide_bar(200, 100).kind == "rotating"
    assert gf.analyse_guide_bar(100, 100).kind == "boundary"
    assert gf.analyse_guide_bar(100, 130, 40).kind == "no_crank"
    # slides fill-in 1: a 30° swing gives K = 1.4
    gb = gf.analyse_guide_bar(100 * math.sin(15 * DEG), 100)
    assert_allclose([gb.psi, gb.K], [30 * DEG, 1.4], rtol=1e-12)


# --------------------------------------------------------------------- ranges
def _text(rs):
    return [(r.type, r.crank, r.lo, r.hi, r.lo_closed, r.hi_closed) for r in rs]


def test_ranges_slides_exam2():
    rs = gf.length_ranges([40, 60, 50, 80], vary=1)
    assert _text(rs) == [("crank_rocker", 1, 0.0, 30.0, False, True),
                         ("double_rocker", None, 30.0, 70.0, False, False),
                         ("crank_rocker", 3, 70.0, 90.0, True, True),
                         ("double_rocker", None, 90.0, 190.0, False, False)]


@pytest.mark.parametrize("vary, lo, hi", [(4, 1.5, 3.5), (3, 1.5, 4.5), (2, 2.0, 4.0)])
def test_ranges_hrones_nelson(vary, lo, hi):
    rs = [r for r in gf.length_ranges([1, 2.5, 2, 3], vary) if r.crank == 1]
    assert [(r.type, r.lo, r.hi, r.lo_closed, r.hi_closed) for r in rs] == \
        [("crank_rocker", lo, hi, True, True)]


def test_ranges_agree_with_pointwise_classification():
    rng = np.random.default_rng(3)
    for _ in range(40):
        L = list(rng.integers(1, 20, 4).astype(float))
        vary = int(rng.integers(1, 5))
        for r in gf.length_ranges(L, vary):
            xs = np.linspace(r.lo, r.hi, 9)[1:-1]
            if r.lo_closed:
                xs = np.append(xs, r.lo)
            if r.hi_closed:
                xs = np.append(xs, r.hi)
            M = np.tile(L, (len(xs), 1))
            M[:, vary - 1] = xs
            kl = gf.classify_fourbar(M)
            for i, t in enumerate(kl.types):
                assert t.removeprefix("change_point_") in (r.type, "parallelogram"), (L, vary, r)


# ------------------------------------------------------------ transmission curves
def test_fourbar_transmission_curve_against_engine():
    """习题 3-1 传动角的变化规律: γ(θ1) equals the coupler-output angle of the engine."""
    a, b, c, d = 28, 52, 50, 72
    th = np.linspace(0, 2 * np.pi, 721)
    curve = gf.fourbar_transmission(a, b, c, d, th)
    mo = solve(_fourbar(a, b, c, d), {1: DriverMotion(th)}, order=0, on_fail="raise")
    gam = np.arccos(np.clip(np.abs(np.cos(mo.links[2].theta - mo.links[3].theta)), 0, 1))
    assert curve.feasible.all()
    assert_allclose(curve.gamma, gam, atol=1e-9)


def test_fourbar_transmission_curve_marks_unassemblable_inputs():
    th = np.linspace(0, 2 * np.pi, 721)
    curve = gf.fourbar_transmission(100, 150, 170, 110, th)
    mo = solve(_fourbar(100, 150, 170, 110), {1: DriverMotion(th)}, order=0, on_fail="mask")
    assert np.array_equal(curve.feasible, mo.feasible)


def test_slider_and_guide_transmission_curves_against_engine():
    th = np.linspace(0, 2 * np.pi, 721)
    a, b, e = 15, 48, 20
    mo = solve(_slider(a, b, e), {1: DriverMotion(th)}, order=0, on_fail="raise")
    rod = mo.points["C"].p - mo.points["B"].p
    gam = np.pi / 2 - np.arcsin(np.abs(rod.imag) / b)
    assert_allclose(gf.slider_transmission(a, b, e, th).gamma, gam, atol=1e-9)
    a, d, e = 100, 200, 40
    link = Linkage(frame=4, elements=(
        Ground("A", 0.0, 0.0), Ground("C", d, 0.0),
        Crank(link=1, pivot="A", point="B", length=a),
        RPR(point="B", block=2, pivot="C", guide=3, offset=e)))
    mo = solve(link, {1: DriverMotion(th, 1.0)}, order=1, on_fail="raise")
    v_guide = 1j * mo.links[3].omega * (mo.points["B"].p - d)
    normal = np.exp(1j * (mo.links[3].theta + np.pi / 2))
    cos_a = np.abs((v_guide * np.conj(normal)).real) / np.abs(v_guide)
    gam = np.pi / 2 - np.arccos(np.clip(cos_a, 0, 1))
    assert_allclose(gf.guide_transmission(a, d, e, th).gamma, gam, atol=1e-9)
