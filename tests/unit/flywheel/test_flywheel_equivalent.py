"""The equivalent dynamic model (chapter 6, 第二节): Je and dJe/dφ (eq 6-4) of a linkage,
a table, a constant and a gear train, and the equivalent moment Me (eq 6-2).

Where the numbers come from:

* 【例 6-1】 (slider-crank; OCR line 6084): tests/reference/independent_slider_crank_inertia.py,
  hand-differentiated closed forms that import nothing from mechcli, plus values by hand;
* 表 6-2 (例 6-4's shaper, OCR line 6470): the table itself, finite differences with their
  truncation bounds, and trigonometric polynomials that interpolation must reproduce;
* 习题 6-2 (OCR line 6615): by hand below;
* Me: virtual power against the kinetostatics (ForceEvaluator), which shares no code
  with the energy route.

习题 6-1 (the carrier mechanism 搬运器) is not tested: its figure is lost in the OCR text, and
the data given (l_AB = l_ED = 100 mm, l_BC = l_CD = l_EF = 200 mm, φ1 = φ2 = φ3 = 90°, m = 20
kg, F5 = 1 kN) do not fix which points the links join nor where the slider's guide lies.

Speed (not timed here, the machines are shared): Je and dJe of 例 6-1 over 36,001 crank
angles take about 6.5 ms on the development machine (the engine's order-2 solve about 5 ms
of it); the issue's target is <= 10 ms.
"""

import ast
import importlib.util

import numpy as np
import pytest

from mechcli.core.errors import DescribedError
from mechcli.core.flywheel.equivalent import (ChainInertia, ConstantInertia, LinkageInertia,
                                              TableInertia, chain_moment, linkage_moment)
from mechcli.core.linkage import slider_crank
from mechcli.core.linkage.force_analysis import ForceEvaluator
from mechcli.core.linkage.force_model import Body, ForceModelError, Load, topology
from mechcli.core.linkage.kinematics import Sweep
from mechcli.core.linkage.loads import LoadProgram
from tests.conftest import ROOT

SCRIPT = ROOT / "tests" / "reference" / "independent_slider_crank_inertia.py"
DEG = np.pi / 180.0


def _reference():
    spec = importlib.util.spec_from_file_location("independent_slider_crank_inertia", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


REF = _reference()


def _example_6_1(a=0.2, **kw):
    """【例 6-1】: l1 = 0.2, l2 = 0.5, e = 0.05 m; m1 = 1.2, m2 = 5, m3 = 10 kg; J1 = 3 kg m²
    about A (so the crank's body sits at A: its m1 |v_A|² is zero); J_S2 = 0.15 kg m²;
    S2 at l_BS2 = ``a`` from B."""
    lk = slider_crank(0.2, 0.5, 0.05)
    bodies = {1: Body(1, 1.2, 3.0, origin="A"),
              2: Body(2, 5.0, 0.15, origin="B", along=a),
              3: Body(3, 10.0)}
    return lk, bodies, LinkageInertia(lk, bodies, **kw)


PHI = np.linspace(0.0, 2 * np.pi, 36001)  # every 0.01° of one turn


# ---------------------------------------------------------------------------
# the independent reference itself
# ---------------------------------------------------------------------------
def test_reference_imports_nothing_from_mechcli():
    tree = ast.parse(SCRIPT.read_text(encoding="utf-8"))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert names and not [m for m in names if m.split(".")[0] == "mechcli"], names


def test_reference_derivative_agrees_with_its_finite_difference():
    # 8th-order central difference, h = 0.01 rad: truncation ~1e-16 |Je^(9)|, round-off
    # ~1e-16 Je / h ~ 1e-13 kg m²/rad; a wrong hand derivative would be off by >= 1e-3
    assert REF.fd_check() < 1e-11


# ---------------------------------------------------------------------------
# 【例 6-1】 on the engine
# ---------------------------------------------------------------------------
def test_example_6_1_by_hand():
    # φ = 90°: θ2' = -l1 cos φ / (l2 cos θ2) = 0, so S2 and C move with B's velocity
    # (-l1, 0) per rad: Je = J1 + m2 l1² + m3 l1² = 3 + 5·0.04 + 10·0.04 = 3.6 kg m².
    # φ = 0°: sin θ2 = e/l2 = 0.1, cos θ2 θ2' = -l1/l2 = -0.4, θ2'² = 0.16/0.99 = 16/99;
    # J_S2 θ2'² = 2.4/99; m3 s'² = m3 (l2 sin θ2 θ2')² = 10·0.0025·16/99 = 0.4/99;
    # m2 |v_S2|² = 5 [(0.2·0.1)² 16/99 + (0.2 - 0.2·0.4)²] = 7.16/99: Je = 3 + 9.96/99.
    _, _, model = _example_6_1()
    Je, _ = model(np.array([90.0, 0.0, 360.0]) * DEG)
    assert Je == pytest.approx([3.6, 3 + 9.96 / 99, 3 + 9.96 / 99], rel=1e-14)


def test_example_6_1_matches_independent_closed_form():
    _, _, model = _example_6_1()
    Je, dJe = model(PHI)
    ref, dref = REF.inertia(PHI, **REF.EXAMPLE_6_1)
    assert Je.shape == dJe.shape == PHI.shape
    assert np.max(np.abs(Je - ref) / ref) <= 1e-12
    # dJe/dφ crosses zero: relative to its largest magnitude (≈ 0.84 kg m²/rad)
    assert np.max(np.abs(dJe - dref)) <= 1e-12 * np.max(np.abs(dref))


@pytest.mark.parametrize("a", [0.2, 0.25])
def test_centre_of_mass_of_the_coupler(a):
    # ERRATA: the book's programs ch6_1/ch6_2 put S2 at l2/2 = 0.25 m (the factor 1/2 on
    # omega2 in v2x, v2y) although 例 6-1 states l_BS2 = 0.2 m.  The engine follows the
    # statement; both agree with the closed form, and they differ by up to 0.022 kg m²
    # (0.71 % of Je, near φ = 188°) and 0.034 kg m²/rad in dJe/dφ.
    _, _, model = _example_6_1(a=a)
    params = dict(REF.EXAMPLE_6_1, a=a)
    Je, dJe = model(PHI)
    ref, dref = REF.inertia(PHI, **params)
    assert np.max(np.abs(Je - ref) / ref) <= 1e-12
    assert np.max(np.abs(dJe - dref)) <= 1e-12 * np.max(np.abs(dref))


def test_exact_derivative_matches_high_order_finite_difference():
    # the engine's own Je differenced with the 8th-order stencil (h = 0.01 rad): truncation
    # (h^8/630)|Je^(9)| ~ 1e-16·|Je^(9)|, round-off ~1e-13 kg m²/rad
    _, _, model = _example_6_1()
    c = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    h = 0.01
    phi = np.arange(360) * DEG
    Je, _ = model(phi[:, None] + np.arange(-4, 5)[None, :] * h)
    _, dJe = model(phi)
    assert np.max(np.abs(Je @ c / h - dJe)) < 1e-11


def test_difference_derivative_has_the_central_difference_error():
    # derivative="difference": (Je(φ+h) - Je(φ-h)) / 2h = Je' + h² Je'''/6 + O(h⁴).
    # Je''' from the exact dJe by a second central difference (k = 1e-3 rad, error
    # k² |Je^(5)|/12 ~ 1e-7 relative); the measured error must be h² Je'''/6 to 1 %.
    _, _, exact = _example_6_1()
    phi = np.arange(0.0, 360.0, 2.0) * DEG
    _, d = exact(phi)
    k = 1e-3
    third = (exact(phi + k)[1] - 2 * d + exact(phi - k)[1]) / k**2
    errors = {}
    for h in (1e-2, 5e-3):
        _, _, fd = _example_6_1(derivative="difference", step=h)
        err = fd(phi)[1] - d
        predicted = h * h / 6 * third
        assert np.max(np.abs(err - predicted)) <= 0.01 * np.max(np.abs(predicted))
        errors[h] = np.max(np.abs(err))
    assert errors[1e-2] / errors[5e-3] == pytest.approx(4.0, rel=0.01)  # second order
    # the default step 1e-5 rad: truncation ~2e-11·|Je'''| (|Je'''| ≤ 12 kg m²/rad³ here);
    # round-off ~1e-16 Je / h ~ 4e-11 per evaluation
    _, _, fd = _example_6_1(derivative="difference")
    assert np.max(np.abs(fd(phi)[1] - d)) < 1e-9


def test_batch_of_designs_equals_separate_designs():
    # l1 of shape (3, 1) against φ of shape (N,): results (3, N), each row the closed form
    l1 = np.array([0.15, 0.2, 0.25])
    lk = slider_crank(l1[:, None], 0.5, 0.05)
    bodies = {1: Body(1, 1.2, 3.0, origin="A"), 2: Body(2, 5.0, 0.15, origin="B", along=0.2),
              3: Body(3, 10.0)}
    phi = np.arange(0.0, 360.0, 5.0) * DEG
    Je, dJe = LinkageInertia(lk, bodies)(phi)
    assert Je.shape == (3, phi.size)
    for row, length in enumerate(l1):
        ref, dref = REF.inertia(phi, **dict(REF.EXAMPLE_6_1, l1=length))
        assert np.max(np.abs(Je[row] - ref) / ref) <= 1e-12
        assert np.max(np.abs(dJe[row] - dref)) <= 1e-12 * np.max(np.abs(dref))


def test_default_centre_of_mass_is_the_midpoint():
    # Body(2) with no origin: S2 at the midpoint of BC, i.e. the closed form with a = l2/2
    lk = slider_crank(0.2, 0.5, 0.05)
    bodies = {1: Body(1, 1.2, 3.0, origin="A"), 2: Body(2, 5.0, 0.15), 3: Body(3, 10.0)}
    Je, dJe = LinkageInertia(lk, bodies)(PHI[::100])
    ref, dref = REF.inertia(PHI[::100], **dict(REF.EXAMPLE_6_1, a=0.25))
    assert np.max(np.abs(Je - ref) / ref) <= 1e-12
    assert np.max(np.abs(dJe - dref)) <= 1e-12 * np.max(np.abs(dref))


def test_parts_sum_to_the_whole_and_flywheel_adds_a_constant():
    _, _, model = _example_6_1()
    phi = np.arange(0.0, 360.0, 10.0) * DEG
    Je, dJe = model(phi)
    parts = model.parts(phi)
    assert sorted(parts) == [1, 2, 3]
    assert np.allclose(parts[1][0], 3.0, rtol=0, atol=1e-15)  # J1 about A, S1 at A
    assert np.allclose(sum(p[0] for p in parts.values()), Je, rtol=1e-15, atol=0)
    assert np.allclose(sum(p[1] for p in parts.values()), dJe, rtol=0, atol=1e-15)
    # 例 6-5's flywheel J_F = 587.92849 kg m² on the equivalent link
    fly = model.plus(587.92849)
    Jf, dJf = fly(phi)
    assert np.allclose(Jf, Je + 587.92849, rtol=1e-15, atol=0) and np.array_equal(dJf, dJe)
    assert model.added == 0.0 and fly.added == 587.92849 and fly.plus(1.0).added == 588.92849
    assert model.period == pytest.approx(2 * np.pi) and not model.constant


def test_cannot_assemble_names_an_input_where_it_does_not():
    # l2 = 0.1 < l1 = 0.2: the rod reaches the guide y = 0 only while |l1 sin φ| <= l2
    lk = slider_crank(0.2, 0.1, 0.0)
    model = LinkageInertia(lk, {2: Body(2, 1.0, 0.1)})
    phi = np.arange(0.5, 360.0, 1.0) * DEG
    with pytest.raises(DescribedError) as exc:
        model(phi)
    assert exc.value.reason == "cannot_assemble"
    assert exc.value.values["angle"] == pytest.approx(30.5 * DEG, rel=1e-15)  # first > 30°
    with pytest.raises(DescribedError) as exc:
        linkage_moment(lk, topology(lk), {}, (0.0, -9.81), (), phi)
    assert exc.value.reason == "cannot_assemble"
    # at the limit itself, l1 sin 30° = l2, the rod is perpendicular to the guide: the
    # linkage assembles but its velocity coefficients are unbounded
    with pytest.raises(DescribedError) as exc:
        model(PHI)
    assert exc.value.reason == "dead_point"
    assert exc.value.values["angle"] == pytest.approx(30 * DEG, rel=1e-12)


def test_body_on_the_frame_is_rejected():
    lk = slider_crank(0.2, 0.5, 0.05)
    with pytest.raises(ForceModelError):
        LinkageInertia(lk, {4: Body(4, 1.0)})
    with pytest.raises(ForceModelError):
        LinkageInertia(lk, {2: Body(2, 1.0, origin="A")})  # A is not on the coupler


# ---------------------------------------------------------------------------
# Me of a linkage: virtual power against the kinetostatics
# ---------------------------------------------------------------------------
def _programs():
    """A resisting force on the slider during half a turn, a torque on the coupler and a
    force fixed in the coupler's axes at a point off its line (invented loads that
    exercise every term of eq 6-2)."""
    return (LoadProgram(Load("Fr", 3, fx=-1000.0, origin="C"), window=(0.0, np.pi)),
            LoadProgram(Load("M2", 2, torque=25.0)),
            LoadProgram(Load("F2", 2, fx=40.0, fy=-60.0, origin="B", along=0.3, normal=0.05,
                             relative=True)))


def test_moment_is_minus_the_balancing_torque_of_the_massless_linkage():
    # virtual power at unit input speed: Mb + Σ loads · v* = 0, so Mb = -Me (any ω1)
    lk = slider_crank(0.2, 0.5, 0.05)
    topo = topology(lk)
    phi = np.arange(0.5, 360.0, 3.0) * DEG
    Me = linkage_moment(lk, topo, {}, None, _programs(), phi)
    ev = ForceEvaluator(lk, topo, Sweep(1, phi, 10.0, 0.0), {}, (0.0, 0.0), _programs())
    Mb = ev(phi)[0].balancing[1]
    assert np.max(np.abs(Mb + Me)) <= 1e-10 * np.max(np.abs(Me))
    # the window: the slider's force adds F s' on (0, π) only, with the slider's velocity
    # coefficient s' = -l1 sin φ - l2 sin θ2 θ2' (sin θ2 = (e - l1 sin φ)/l2, θ2' as above)
    Me_off = linkage_moment(lk, topo, {}, None, _programs()[1:], phi)
    s2 = (0.05 - 0.2 * np.sin(phi)) / 0.5
    t1 = -0.2 * np.cos(phi) / (0.5 * np.sqrt(1 - s2**2))
    v3 = -0.2 * np.sin(phi) - 0.5 * s2 * t1
    added = np.where(phi < np.pi, -1000.0 * v3, 0.0)
    assert np.max(np.abs(Me - Me_off - added)) <= 1e-12 * np.max(np.abs(Me))


def test_equation_of_motion_closes_the_kinetostatics():
    # eq 6-8 with the balancing torque as the drive: Mb = Je α1 + ½ dJe/dφ ω1² - Me, at
    # ω1 = 10 rad/s, α1 = 3 rad/s², 例 6-1's masses, gravity and the loads above.  The
    # kinetostatics (d'Alembert, per link) shares nothing with the energy route.
    lk, bodies, model = _example_6_1()
    topo = topology(lk)
    phi = np.arange(0.5, 360.0, 3.0) * DEG
    g = (0.0, -9.81)
    Je, dJe = model(phi)
    Me = linkage_moment(lk, topo, bodies, g, _programs(), phi)
    w1, a1 = 10.0, 3.0
    ev = ForceEvaluator(lk, topo, Sweep(1, phi, w1, a1), bodies, g, _programs())
    Mb = ev(phi)[0].balancing[1]
    expected = Je * a1 + 0.5 * dJe * w1**2 - Me
    assert np.max(np.abs(Mb - expected)) <= 1e-10 * np.max(np.abs(Mb))
    # gravity alone: Me = Σ m g·v_S = -g m2 yS2' (the slider moves level, S1 is at A),
    # yS2' = l1 cos φ + a cos θ2 θ2'
    Mg = linkage_moment(lk, topo, bodies, g, (), phi)
    s2 = (0.05 - 0.2 * np.sin(phi)) / 0.5
    t1 = -0.2 * np.cos(phi) / (0.5 * np.sqrt(1 - s2**2))
    vy = 0.2 * np.cos(phi) + 0.2 * np.sqrt(1 - s2**2) * t1
    assert np.max(np.abs(Mg - (-9.81 * 5.0 * vy))) <= 1e-12 * np.max(np.abs(Mg))


def test_band_program_needs_absolute_limits():
    lk = slider_crank(0.2, 0.5, 0.05)
    prog = LoadProgram(Load("F", 3, fx=-10.0), band=(0.2, 0.8))
    with pytest.raises(ValueError, match="with_band_limits"):
        linkage_moment(lk, topology(lk), {}, None, (prog,), PHI[:10])


# ---------------------------------------------------------------------------
# a table over one turn: 表 6-2
# ---------------------------------------------------------------------------
#: 表 6-2 (例 6-4's shaper): Je [kg m²] at φ = 0, 15, ..., 360°
TABLE_6_2 = np.array([34.0, 33.9, 33.6, 33.1, 32.4, 31.8, 31.2, 31.1, 31.6, 33, 35, 37.2, 38.2,
                      37.2, 35, 33, 31.5, 31.1, 31.2, 31.8, 32.4, 33.1, 33.6, 33.9, 34.0])
NODES = np.arange(0.0, 361.0, 15.0) * DEG


@pytest.mark.parametrize("method", ["cubic", "linear", "fourier"])
def test_table_passes_through_its_nodes_and_is_periodic(method):
    model = TableInertia(NODES, TABLE_6_2, method=method)
    Je, _ = model(NODES)
    assert np.max(np.abs(Je - TABLE_6_2)) <= 1e-12
    x = np.linspace(-3.0, 3.0, 601)
    J0, d0 = model(x)
    for turns in (1, -2):
        J1, d1 = model(x + turns * 2 * np.pi)
        assert np.max(np.abs(J1 - J0)) <= 1e-12
        # the linear slope jumps at nodes, where x + 2π may round to the other side
        off_nodes = np.abs(np.mod(x / (15 * DEG) + 0.5, 1.0) - 0.5) > 1e-9
        assert np.max(np.abs(d1 - d0)[off_nodes]) <= 1e-9
    assert model.period == pytest.approx(2 * np.pi) and not model.constant
    assert model.plus(587.92849)(NODES)[0] == pytest.approx(TABLE_6_2 + 587.92849, rel=1e-15)


def test_cubic_table_derivative_is_the_spline_slope():
    # inside an interval the spline is a cubic: the central difference is exactly
    # S' + h² S'''/6, with S''' constant there; h = 1e-4 rad, points >= h from the nodes
    model = TableInertia(NODES, TABLE_6_2)
    x = (np.arange(24) * 15.0 + np.array([[1.0], [7.3], [13.9]])).ravel() * DEG
    h = 1e-4
    _, d = model(x)
    fd = (model(x + h)[0] - model(x - h)[0]) / (2 * h)
    third = model._spline.derivative(3)(x)
    assert np.max(np.abs(fd - d - h * h / 6 * third)) <= 1e-9  # round-off 38·1e-16/h
    # C¹ across the seam 0/2π: one-sided slopes agree to |S''|·2δ
    delta = 1e-7
    left, right = model(-delta)[1], model(delta)[1]
    assert abs(left - right) <= 2 * delta * np.max(np.abs(model._spline.derivative(2)(NODES)))


def test_linear_table_slope_is_the_interval_slope():
    model = TableInertia(NODES, TABLE_6_2, method="linear")
    mid = (np.arange(24) * 15.0 + 7.5) * DEG
    Je, dJe = model(mid)
    assert np.allclose(Je, 0.5 * (TABLE_6_2[:-1] + TABLE_6_2[1:]), rtol=0, atol=1e-12)
    assert np.allclose(dJe, np.diff(TABLE_6_2) / (15 * DEG), rtol=1e-12, atol=0)
    # e.g. 0..15°: (33.9 - 34.0) / (π/12) = -0.38197 kg m²/rad
    assert dJe[0] == pytest.approx(-0.1 / (np.pi / 12), rel=1e-12)


def test_fourier_table_reproduces_a_trigonometric_polynomial():
    # J = 3 + 0.5 cos φ + 0.2 sin 3φ + 0.1 cos 12φ has degree <= N/2 = 12, with the
    # Nyquist term a cosine: trigonometric interpolation through 24 nodes reproduces it
    # and its derivative everywhere
    def f(x):
        return 3 + 0.5 * np.cos(x) + 0.2 * np.sin(3 * x) + 0.1 * np.cos(12 * x)

    def df(x):
        return -0.5 * np.sin(x) + 0.6 * np.cos(3 * x) - 1.2 * np.sin(12 * x)

    model = TableInertia(NODES, f(NODES), method="fourier")
    x = np.linspace(-1.0, 8.0, 2001)
    Je, dJe = model(x)
    assert np.max(np.abs(Je - f(x))) <= 1e-13
    assert np.max(np.abs(dJe - df(x))) <= 1e-12


@pytest.mark.parametrize("change, reason, values", [
    (lambda p, J: (p, np.append(J[:-1], 34.1)), "not_periodic", {"first": 34.0, "last": 34.1}),
    (lambda p, J: (p[:-1], J[:-1]), "not_one_period", {"span": 345 * DEG}),
    (lambda p, J: (p[:2], J[:2]), "too_few", {"count": 2}),
    (lambda p, J: (np.where(np.arange(p.size) == 3, p[2], p), J), "not_increasing",
     {"angle": 30 * DEG}),
    (lambda p, J: (p, np.where(np.arange(J.size) == 5, -1.0, J)), "not_positive",
     {"value": -1.0}),
])
def test_table_errors(change, reason, values):
    phi, J = change(NODES, TABLE_6_2)
    with pytest.raises(DescribedError) as exc:
        TableInertia(phi, J)
    assert exc.value.reason == reason
    for key, value in values.items():
        assert exc.value.values[key] == pytest.approx(value, rel=1e-12)


def test_fourier_table_needs_equal_steps():
    phi = NODES.copy()
    phi[5] += 1 * DEG
    with pytest.raises(DescribedError) as exc:
        TableInertia(phi, TABLE_6_2, method="fourier")
    assert exc.value.reason == "not_uniform"
    assert TableInertia(phi, TABLE_6_2, method="cubic")(phi)[0] == pytest.approx(TABLE_6_2)


# ---------------------------------------------------------------------------
# constant ratios: 习题 6-2
# ---------------------------------------------------------------------------
def test_exercise_6_2_gear_train():
    # 习题 6-2: z1 = z2' = 20, z2 = z3 = 40 (the OCR prints "z1 = z2 = 20, z2 = z3 = 40",
    # its primes lost); J1 = J2' = 0.01, J2 = J3 = 0.04 kg m²; M3 = 40 N m resisting on O3.
    # ω2/ω1 = z1/z2 = 1/2 (gears 2 and 2' on one shaft), ω3/ω1 = (z1 z2')/(z2 z3) = 1/4.
    # Je = J1 + (J2 + J2')(1/2)² + J3 (1/4)² = 0.01 + 0.0125 + 0.0025 = 0.025 kg m²;
    # Me = -M3 · 1/4 = -10 N m (resisting: against ω3).
    model = ChainInertia([(0.01, 1.0), (0.04, -0.5), (0.01, -0.5), (0.04, 0.25)])
    Je, dJe = model(NODES)
    assert np.allclose(Je, 0.025, rtol=1e-15) and not np.any(dJe)
    assert model.terms == pytest.approx((0.01, 0.01, 0.0025, 0.0025), rel=1e-15)
    assert model.constant and model.period is None
    assert chain_moment([(-40.0, 0.25)]) == pytest.approx(-10.0, rel=1e-15)
    # a mass moving at v/ω1 = 0.05 m/rad adds m (v/ω1)² = 2·0.0025 kg m²; a force F cos α
    # = -100 N on it adds -100·0.05 N m
    assert ChainInertia([(0.01, 1.0)], masses=[(2.0, 0.05)]).value == pytest.approx(0.015)
    assert chain_moment([(-40.0, 0.25)], forces=[(-100.0, 0.05)]) == pytest.approx(-15.0)


def test_constant_inertia():
    # 例 6-3: Je = 10 kg m²; 例 6-5 adds J_F = 587.92849 kg m²
    model = ConstantInertia(10.0)
    Je, dJe = model(np.zeros((2, 3)))
    assert Je.shape == (2, 3) and np.all(Je == 10.0) and not np.any(dJe)
    assert model.plus(587.92849)(0.0)[0] == pytest.approx(597.92849, rel=1e-15)
    with pytest.raises(DescribedError) as exc:
        ConstantInertia(0.0)
    assert exc.value.reason == "not_positive"


def test_sampled_inertia_is_the_exact_model_within_its_interpolation_error():
    """SampledInertia (what the integrators use for a linkage) against the exact model of
    例 6-1 at 2,001 angles between its samples: cubic Hermite on 0.1° samples errs by
    about h⁴/384·max|Je⁗| in Je and h³/72·max|Je⁗| in dJe (h = 1.745e-3 rad; |Je⁗| of
    order 10 kg m² here), and the error falls by 16 when the step is halved."""
    from mechcli.core.flywheel.equivalent import SampledInertia
    exact = _example_6_1()[2]
    phi = np.random.default_rng(7).uniform(0, 2 * np.pi, 2001)
    J0, dJ0 = exact(phi)
    errs = []
    for n in (3600, 7200):
        J, dJ = SampledInertia(exact, n)(phi)
        errs.append(np.max(np.abs(J - J0)))
        assert np.max(np.abs(dJ - dJ0)) < 1e-6 * np.max(np.abs(dJ0))
    assert errs[0] < 1e-10 * np.max(J0)
    assert 8 < errs[0] / errs[1] < 32          # fourth order
    # a flywheel added before or after sampling is the same
    a, _ = SampledInertia(exact.plus(5.0), 360)(phi)
    b, _ = SampledInertia(exact, 360).plus(5.0)(phi)
    assert np.allclose(a, b, rtol=0, atol=1e-12)
