"""Design from the time ratio K (§3.6, 【例 3-8】, 习题 3-14 … 3-16, the slides' K problems).

Book values: 【例 3-8】 prints l1 … l4 (mm) and γ1, γ2 (°) to 2 decimals for each
of its four cases (计算结果 1 and 2): tolerance half a unit of the last digit,
0.005.  The exercises print no answers: each is checked against a hand
calculation written in the test (the numbers in the comments, to the digits
given) and against a second method.  Every design is fed back to the Grashof
core (analyse_fourbar / analyse_slider_crank / analyse_guide_bar), which must
return K, θ, ψ (or the stroke H) to 1e-9 relative, and moved on the engine to
its limit positions.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from mechcli.core.errors import DescribedError
from mechcli.core.grashof.fourbar import (analyse_fourbar, analyse_guide_bar,
                                          analyse_slider_crank)
from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.synth.quick_return import (crank_rocker_from_K,
                                             crank_rocker_from_K_limit_angle,
                                             guide_bar_from_K, limit_angle_from_K,
                                             pivot_circle, slider_crank_from_K,
                                             slider_crank_stroke_from_K, time_ratio)

deg = math.radians
MM = 1e-3
RTOL = 1e-9

# 【例 3-8】: K = 1.25, l3 = 290 mm, φ (swing) = 34°, [γmin] = 40°
K8, L3, PSI8 = 1.25, 290 * MM, deg(34)


def lengths(design):
    L = design.lengths
    return [L["l1"], L["l2"], L["l3"], L["l4"]]


def core_fourbar(design):
    an = analyse_fourbar(lengths(design))
    return an.klass.types[0], an.merit


def engine_C(design):
    """C of the design's linkage on the engine with the crank at A→B1 and A→B2."""
    P = design.pivots
    A = np.array(P["A"])
    q = np.array([math.atan2(P[b][1] - A[1], P[b][0] - A[0]) for b in ("B1", "B2")])
    m = solve(design.linkage, {1: DriverMotion(q)}, order=0)
    assert m.feasible.all()
    return m.points["C"].x + 1j * m.points["C"].y


def assert_reproduces(design, K, psi):
    """The Grashof core gives back K and ψ; the engine puts C at C1 and C2."""
    kind, m = core_fourbar(design)
    assert kind == "crank_rocker"
    assert m.K[0] == pytest.approx(K, rel=RTOL)
    assert m.theta[0] == pytest.approx(limit_angle_from_K(K), rel=RTOL)
    assert m.psi[0] == pytest.approx(psi, rel=RTOL)
    P = design.pivots
    want = np.array([complex(*P["C1"]), complex(*P["C2"])])
    assert np.abs(engine_C(design) - want).max() < 1e-12 * design.size


# ------------------------------------------------------------------ 【例 3-8】
# (condition, printed l1, l2, l4 [mm], printed γ1, γ2 [°]) — 计算结果 1 and 2
EX38 = [
    (dict(pivot_line=(1.0, 1.0, 0.0)), (77.29, 215.09, 277.29), (43.58, 87.87)),   # (1)
    (dict(crank=77 * MM), (77.00, 218.44, 276.80), (43.50, 87.00)),                # (2)
    (dict(coupler=215 * MM), (77.30, 215.00, 277.30), (43.59, 87.89)),             # (3)
    (dict(frame=277 * MM), (77.12, 217.08, 277.00), (43.54, 87.35)),               # (4)
]


@pytest.mark.parametrize("condition,printed,gammas", EX38, ids=["line", "l1", "l2", "l4"])
def test_ex3_8_printed_results(condition, printed, gammas):
    d = crank_rocker_from_K(K8, L3, PSI8, gamma_allowed=deg(40), **condition)
    L = d.lengths
    np.testing.assert_allclose([L["l1"] / MM, L["l2"] / MM, L["l4"] / MM], printed, atol=0.005)
    assert L["l3"] == pytest.approx(L3, rel=1e-12)
    np.testing.assert_allclose([math.degrees(d.values["gamma_1"]),
                                math.degrees(d.values["gamma_2"])], gammas, atol=0.005)
    # the book's check: γmin = γ1 >= [γmin] = 40°
    assert d.values["gamma_min"] == pytest.approx(d.values["gamma_1"], rel=1e-12)
    assert d.values["gamma_ok"] is True
    assert d.values["K"] == K8 and d.values["psi"] == PSI8
    assert d.values["theta"] == pytest.approx(deg(20), rel=1e-12)       # eq. 3-39
    assert d.inputs is None
    assert_reproduces(d, K8, PSI8)


def test_ex3_8_placement_is_the_books():
    """图 3-15: D at the origin, the y axis bisects the swing; A on C1's side (the
    book's program starts fsolve at (-100, 100) and takes l1 = (AC2 - AC1)/2 > 0)."""
    d = crank_rocker_from_K(K8, L3, PSI8, pivot_line=(1, 1, 0))
    P = d.pivots
    assert P["D"] == (0.0, 0.0)
    x_c2, y_c2 = 290 * math.sin(deg(17)), 290 * math.cos(deg(17))
    np.testing.assert_allclose(np.array([P["C1"], P["C2"]]) / MM,
                               [(-x_c2, y_c2), (x_c2, y_c2)], rtol=1e-12)
    ax, ay = P["A"]
    assert ax + ay == pytest.approx(0.0, abs=1e-15)                      # on x + y = 0
    assert ax < 0 and d.values["branch"] == "left"
    # C1 is the folded limit position: B1 on the far side of A, A between B1 and C1
    a, b1, c1 = (np.array(P[k]) for k in ("A", "B1", "C1"))
    assert np.dot(b1 - a, c1 - a) < 0
    assert np.hypot(*(c1 - b1)) == pytest.approx(d.lengths["l2"], rel=1e-12)


def test_ex3_8_gamma_at_frame_positions_is_eq_3_49():
    """γ1, γ2 are eq. (3-49) of the designed lengths (γ2 folded below 90°, as the
    program does), the Grashof core's γ at θ1 = 0 and 180°."""
    for condition, _, _ in EX38:
        d = crank_rocker_from_K(K8, L3, PSI8, **condition)
        l1, l2, l3, l4 = lengths(d)
        g1 = math.acos((l2 ** 2 + l3 ** 2 - (l4 - l1) ** 2) / (2 * l2 * l3))
        g2 = math.pi - math.acos((l2 ** 2 + l3 ** 2 - (l4 + l1) ** 2) / (2 * l2 * l3))
        g2 = math.pi - g2 if g2 > math.pi / 2 else g2
        assert d.values["gamma_1"] == pytest.approx(g1, rel=1e-12)
        assert d.values["gamma_2"] == pytest.approx(g2, rel=1e-12)


def book_l2_l4_from_l1(K, l3, psi, l1):
    """Independent: the book's route for case (2), eqs. 3-44 … 3-46 (β − α)."""
    th = math.pi * (K - 1) / (K + 1)
    xc2 = l3 * math.sin(psi / 2)
    R = xc2 / math.sin(th)
    l2 = math.sqrt(((2 * xc2) ** 2 / 2 - l1 ** 2 * (1 + math.cos(th))) / (1 - math.cos(th)))
    alpha, beta = th - psi / 2, math.acos((l2 - l1) / (2 * R))
    g = beta - alpha
    return l2, math.sqrt((l2 - l1) ** 2 + l3 ** 2 - 2 * (l2 - l1) * l3 * math.cos(g))


def test_ex3_8_cases_2_3_by_the_books_equations():
    d2 = crank_rocker_from_K(K8, L3, PSI8, crank=77 * MM)
    l2, l4 = book_l2_l4_from_l1(K8, L3, PSI8, 77 * MM)
    assert d2.lengths["l2"] == pytest.approx(l2, rel=1e-12)
    assert d2.lengths["l4"] == pytest.approx(l4, rel=1e-12)
    # case (3): eq. 3-47 gives l1 from l2, then eq. 3-46
    th = deg(20)
    c1c2 = 2 * L3 * math.sin(PSI8 / 2)
    l1 = math.sqrt((c1c2 ** 2 / 2 - (215 * MM) ** 2 * (1 - math.cos(th))) / (1 + math.cos(th)))
    d3 = crank_rocker_from_K(K8, L3, PSI8, coupler=215 * MM)
    assert d3.lengths["l1"] == pytest.approx(l1, rel=1e-12)
    assert d3.lengths["l4"] == pytest.approx(book_l2_l4_from_l1(K8, L3, PSI8, l1)[1], rel=1e-12)


def test_ex3_8_case1_by_hand():
    """Independent: x + y = 0 into eq. 3-42: 2x² + 2 y_O x + y_O² − R² = 0 (mm)."""
    th, h = deg(20), deg(17)
    R = 290 * math.sin(h) / math.sin(th)                 # 247.903
    yo = 290 * math.cos(h) - R * math.cos(th)            # 44.376
    x = sorted(np.roots([2, 2 * yo, yo ** 2 - R ** 2]).real)   # -196.07, 151.70
    A = np.array([x[0], -x[0]])
    c1, c2 = np.array([-290 * math.sin(h), 290 * math.cos(h)]), np.array([290 * math.sin(h),
                                                                       290 * math.cos(h)])
    ac1, ac2 = np.hypot(*(A - c1)), np.hypot(*(A - c2))
    d = crank_rocker_from_K(K8, L3, PSI8, pivot_line=(1, 1, 0))
    np.testing.assert_allclose(np.array(d.pivots["A"]) / MM, A, rtol=1e-12)
    np.testing.assert_allclose([d.lengths["l1"] / MM, d.lengths["l2"] / MM, d.lengths["l4"] / MM],
                               [(ac2 - ac1) / 2, (ac1 + ac2) / 2, np.hypot(*A)], rtol=1e-12)


def test_ex3_8_case1_other_intersection():
    """The line's second point, x = 151.70 mm (the other root of the hand
    calculation above), is a usable crank-rocker too (C2 folded; l1 = 27.84,
    l2 = 462.05, l4 = 214.53 mm; γmin = γ1 of eq. 3-49 = arccos((462.05² + 290² −
    186.69²)/(2·462.05·290)) = 11.36°); the book keeps the first, which ``best``
    (the larger γmin) does too."""
    th, h = deg(20), deg(17)
    R = 290 * math.sin(h) / math.sin(th)
    yo = 290 * math.cos(h) - R * math.cos(th)
    x = max(np.roots([2, 2 * yo, yo ** 2 - R ** 2]).real)
    A = np.array([x, -x])
    c1, c2 = np.array([-290 * math.sin(h), 290 * math.cos(h)]), np.array([290 * math.sin(h),
                                                                       290 * math.cos(h)])
    ac1, ac2 = np.hypot(*(A - c1)), np.hypot(*(A - c2))
    right = crank_rocker_from_K(K8, L3, PSI8, pivot_line=(1, 1, 0), branch="right")
    np.testing.assert_allclose(np.array(right.pivots["A"]) / MM, A, rtol=1e-12)
    np.testing.assert_allclose([right.lengths[k] / MM for k in ("l1", "l2", "l4")],
                               [(ac1 - ac2) / 2, (ac1 + ac2) / 2, np.hypot(*A)], rtol=1e-12)
    np.testing.assert_allclose([right.lengths[k] / MM for k in ("l1", "l2", "l4")],
                               (27.84, 462.05, 214.53), atol=0.005)
    assert math.degrees(right.values["gamma_min"]) == pytest.approx(11.36, abs=0.005)
    assert right.values["gamma_ok"] is None                 # no [γmin] given
    assert_reproduces(right, K8, PSI8)
    left = crank_rocker_from_K(K8, L3, PSI8, pivot_line=(1, 1, 0), branch="left")
    best = crank_rocker_from_K(K8, L3, PSI8, pivot_line=(1, 1, 0))
    assert best.pivots["A"] == left.pivots["A"] != right.pivots["A"]


def test_ex3_8_mirror_branch_same_lengths():
    """Cases (2)–(4): the other A is the mirror image about the y axis."""
    for condition, _, _ in EX38[1:]:
        left = crank_rocker_from_K(K8, L3, PSI8, **condition)
        right = crank_rocker_from_K(K8, L3, PSI8, branch="right", **condition)
        np.testing.assert_allclose(lengths(right), lengths(left), rtol=1e-12)
        assert right.pivots["A"][0] == pytest.approx(-left.pivots["A"][0], rel=1e-12)
        assert right.values["branch"] == "right"
        assert_reproduces(right, K8, PSI8)


# ERRATA: eq. (3-41) of the book has cos(θ/2) where the geometry, the book's program
# and its printed results have cos θ.
def test_errata_eq_3_41():
    """ERRATA: eq. (3-41) prints y_O = l3 cos(φ/2) − R cos(θ/2); with it, case (1)'s
    A on x + y = 0 gives l4 = 270.26 mm, not the printed 277.29 (the program and the
    printed results use R cos θ: the chord 2 x_C2 subtends 2θ at O)."""
    th, h = deg(20), deg(17)
    R = 290 * math.sin(h) / math.sin(th)
    yo_printed = 290 * math.cos(h) - R * math.cos(th / 2)
    x = min(np.roots([2, 2 * yo_printed, yo_printed ** 2 - R ** 2]).real)
    l4_printed_eq = math.hypot(x, x)
    assert l4_printed_eq == pytest.approx(270.26, abs=0.005)
    circle = pivot_circle(K8, 290.0, PSI8)
    assert circle.O[1] == pytest.approx(290 * math.cos(h) - R * math.cos(th), rel=1e-12)


def test_the_books_frame_bound_is_not_sufficient():
    """Case (4): the book says L and L' meet when R − |y_O| <= l4 <= R + |y_O|
    (203.5 … 292.3 mm), but only l4 in (205.13, 290) mm is a design: at l4 = 291 mm
    the intersection is above the chord C1C2 and sees it under 180° − θ, and the
    Grashof core finds K = 1.12 and ψ = 25.41°, not 1.25 and 34°."""
    circle = pivot_circle(K8, L3, PSI8)
    R, yo = circle.R / MM, circle.O[1] / MM
    assert R - abs(yo) < 291 < R + abs(yo)
    y = (291 ** 2 + yo ** 2 - R ** 2) / (2 * yo)
    A = np.array([-math.sqrt(291 ** 2 - y ** 2), y])
    assert y > 290 * math.cos(PSI8 / 2)                       # above the chord
    ac1 = np.hypot(*(A - circle.C1 / MM))
    ac2 = np.hypot(*(A - circle.C2 / MM))
    m = analyse_fourbar([abs(ac2 - ac1) / 2, (ac1 + ac2) / 2, 290, 291]).merit
    assert m.K[0] == pytest.approx(1.12, abs=0.005)
    assert math.degrees(m.psi[0]) == pytest.approx(25.41, abs=0.005)
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(K8, L3, PSI8, frame=291 * MM)
    assert err.value.reason == "frame_range"
    assert err.value.values["lo"] / MM == pytest.approx(205.13, abs=0.005)
    assert err.value.values["hi"] == pytest.approx(L3, rel=1e-12)


def test_usable_ranges_end_at_change_points():
    """At the end E of the usable arc the line AD passes through C1 or C2: the
    lengths satisfy s + l = p + q (Grashof's equality); at C1 the crank equals the
    coupler, x_C2 = l3 sin(ψ/2)."""
    circle = pivot_circle(K8, L3, PSI8)
    l1, l2, l4 = circle.lengths_at(circle.E)
    L = sorted([l1, l2, L3, l4])
    assert L[0] + L[3] == pytest.approx(L[1] + L[2], rel=1e-12)
    assert circle.crank == pytest.approx((l1, L3 * math.sin(PSI8 / 2)), rel=1e-12)
    assert circle.coupler == pytest.approx((L3 * math.sin(PSI8 / 2), l2), rel=1e-12)
    # just inside each end, a design; just outside, the range error
    for key, reason, (lo, hi) in (("crank", "crank_range", circle.crank),
                                  ("coupler", "coupler_range", circle.coupler),
                                  ("frame", "frame_range", circle.frame)):
        for x in (lo + 1e-3 * (hi - lo), hi - 1e-3 * (hi - lo)):
            assert_reproduces(crank_rocker_from_K(K8, L3, PSI8, **{key: x}), K8, PSI8)
        for x in (lo * (1 - 1e-9), hi * (1 + 1e-9)):
            with pytest.raises(DescribedError) as err:
                crank_rocker_from_K(K8, L3, PSI8, **{key: x})
            assert err.value.reason == reason
            assert (err.value.values["lo"], err.value.values["hi"]) == (lo, hi)
            assert err.value.values["value"] == x


# -------------------------------------------------------------------- 习题 3-14
def test_exercise_3_14():
    """K = 1.25, l_CD = 290, φ = 32°, l_AB = 75 mm: case (2) of 【例 3-8】.

    Hand calculation: θ = 20°, C1C2 = 580 sin 16° = 159.868; eq. 3-45
    l2² = (159.868²/2 − 75²(1 + cos 20°))/(1 − cos 20°) = 1868.5/0.060307,
    l2 = 176.01; R = 79.934/sin 20° = 233.71, α = 20° − 16° = 4°,
    β = arccos(101.01/467.42) = 77.52°, γ = 73.52°, eq. 3-46
    l4 = √(101.01² + 290² − 2·101.01·290 cos 73.52°) = 278.72; γmin = γ1 (eq. 3-49)
    = arccos((176.01² + 290² − 203.72²)/(2·176.01·290)) = 43.88° >= 40°.
    """
    d = crank_rocker_from_K(1.25, 290 * MM, deg(32), crank=75 * MM, gamma_allowed=deg(40))
    np.testing.assert_allclose([d.lengths["l2"] / MM, d.lengths["l4"] / MM], (176.01, 278.72),
                               atol=0.005)
    assert math.degrees(d.values["gamma_min"]) == pytest.approx(43.88, abs=0.005)
    assert d.values["gamma_ok"] is True
    l2, l4 = book_l2_l4_from_l1(1.25, 290 * MM, deg(32), 75 * MM)
    np.testing.assert_allclose([d.lengths["l2"], d.lengths["l4"]], [l2, l4], rtol=1e-12)
    assert_reproduces(d, 1.25, deg(32))


# -------------------------------------------------------------------- 习题 3-15
def test_exercise_3_15_both_limit_kinds():
    """K = 1.5 (θ = 36°), l_CD = 75, l_AD = 100 mm, ∠ADC1 = 45°.

    Hand calculation: AC1² = 100² + 75² − 2·100·75 cos 45°, AC1 = 70.845 at
    φ1 = atan2(53.033, 46.967) = 48.47° from AD.  The ray from A at
    48.47° − 36° = 12.47° meets the circle (D, 75) at t² − 195.28 t + 4375 = 0,
    t = 25.82 or 169.46 (the ray at 84.47° misses it).
    C1 extended: l1 = (70.845 − 25.817)/2 = 22.51, l2 = (70.845 + 25.817)/2 = 48.33;
    C1 folded:   l1 = (169.464 − 70.845)/2 = 49.31, l2 = 120.15.
    """
    ext = crank_rocker_from_K_limit_angle(1.5, 75 * MM, 100 * MM, deg(45), limit="extended")
    fold = crank_rocker_from_K_limit_angle(1.5, 75 * MM, 100 * MM, deg(45), limit="folded")
    np.testing.assert_allclose([ext.lengths["l1"] / MM, ext.lengths["l2"] / MM],
                               (22.51, 48.33), atol=0.005)
    np.testing.assert_allclose([fold.lengths["l1"] / MM, fold.lengths["l2"] / MM],
                               (49.31, 120.15), atol=0.005)
    for d, kind in ((ext, "extended"), (fold, "folded")):
        assert d.values["limit"] == kind
        an = analyse_fourbar(lengths(d))
        m = an.merit
        assert an.klass.types[0] == "crank_rocker"
        assert m.K[0] == pytest.approx(1.5, rel=RTOL)
        th3 = m.theta3_ext[0] if kind == "extended" else m.theta3_fold[0]
        assert math.pi - th3 == pytest.approx(deg(45), rel=RTOL)        # ∠ADC1
        assert d.values["psi"] == pytest.approx(m.psi[0], rel=1e-12)
        P = d.pivots
        want = np.array([complex(*P["C1"]), complex(*P["C2"])])
        assert np.abs(engine_C(d) - want).max() < 1e-12 * d.size
    # best: the larger γmin (13.94° folded against 13.52° extended)
    best = crank_rocker_from_K_limit_angle(1.5, 75 * MM, 100 * MM, deg(45))
    assert best.values["limit"] == "folded"
    assert math.degrees(ext.values["gamma_min"]) == pytest.approx(13.52, abs=0.005)
    assert math.degrees(fold.values["gamma_min"]) == pytest.approx(13.94, abs=0.005)


def test_exercise_3_15_by_a_root_find():
    """Second method: with C1 folded, b = AC1 + a; solve θ(a) = 36° for a on the
    Grashof core's θ (brentq), independent of the ray construction."""
    s1 = math.sqrt(100 ** 2 + 75 ** 2 - 2 * 100 * 75 * math.cos(deg(45)))

    def err(a):
        return analyse_fourbar([a, s1 + a, 75, 100]).merit.theta[0] - deg(36)

    a = brentq(err, 45, 50, xtol=1e-13)          # θ(45) = 28.6°, θ(50) = 37.7°
    fold = crank_rocker_from_K_limit_angle(1.5, 75.0, 100.0, deg(45), limit="folded")
    assert fold.lengths["l1"] == pytest.approx(a, rel=1e-9)


# -------------------------------------------------------------------- 习题 3-16
def test_exercise_3_16():
    """K = 1.5, H = 50, e = 20 mm.  Hand calculation: θ = 36°,
    a² = H/4 (H − 2e tan 18°) = 12.5 (50 − 12.9968) = 462.54, a = 21.51;
    b² = H/4 (H + 2e cot 18°) = 12.5 (50 + 123.1073) = 2163.84, b = 46.52;
    (2) sin α_max = (a + e)/b = 41.507/46.517, α_max = 63.16° (θ1 = 270°)."""
    d = slider_crank_from_K(1.5, 50 * MM, 20 * MM)
    np.testing.assert_allclose([d.lengths["l1"] / MM, d.lengths["l2"] / MM], (21.51, 46.52),
                               atol=0.005)
    assert d.lengths["e"] == 20 * MM and d.lengths["H"] == 50 * MM
    assert math.degrees(d.values["alpha_max"]) == pytest.approx(63.16, abs=0.005)
    assert d.values["gamma_min"] == pytest.approx(math.pi / 2 - d.values["alpha_max"])
    sc = analyse_slider_crank(d.lengths["l1"], d.lengths["l2"], d.lengths["e"])
    assert sc.crank_exists and not sc.boundary
    assert sc.K == pytest.approx(1.5, rel=RTOL)
    assert sc.theta == pytest.approx(deg(36), rel=RTOL)
    assert sc.stroke == pytest.approx(50 * MM, rel=RTOL)
    assert d.values["e_max"] / MM == pytest.approx(50 / math.tan(deg(36)), rel=1e-12)
    # the engine: the slider at C1, C2 with the crank at A→B1, A→B2
    P = d.pivots
    q = np.array([math.atan2(P[b][1], P[b][0]) for b in ("B1", "B2")])
    m = solve(d.linkage, {1: DriverMotion(q)}, order=0)
    np.testing.assert_allclose(m.slides["3"].s, [P["C1"][0], P["C2"][0]], rtol=1e-12)
    assert P["C2"][0] - P["C1"][0] == pytest.approx(50 * MM, rel=1e-12)


def test_slider_crank_offset_limits():
    """e_max = H cot θ is the crank condition's boundary a + e = b (C1 above A);
    e = 0 is a centred slider-crank, K = 1."""
    H, th = 50 * MM, deg(36)
    e_max = H / math.tan(th)
    d = slider_crank_from_K(1.5, H, e_max)
    assert d.values["boundary"] is True
    assert d.lengths["l2"] - d.lengths["l1"] == pytest.approx(e_max, rel=1e-12)
    assert analyse_slider_crank(d.lengths["l1"], d.lengths["l2"], e_max).K == \
        pytest.approx(1.5, rel=RTOL)
    for e in (0.0, e_max * (1 + 1e-6)):
        with pytest.raises(DescribedError) as err:
            slider_crank_from_K(1.5, H, e)
        assert err.value.reason == "offset"
        assert err.value.values["hi"] == pytest.approx(e_max, rel=1e-12)
        assert err.value.values["lo"] == 0.0
    # a negative offset mirrors the design
    neg = slider_crank_from_K(1.5, H, -20 * MM)
    pos = slider_crank_from_K(1.5, H, 20 * MM)
    assert neg.lengths["l1"] == pytest.approx(pos.lengths["l1"], rel=1e-12)
    assert neg.pivots["C1"][1] == -20 * MM
    with pytest.raises(DescribedError) as err:      # θ = 90°: no offset slider-crank
        slider_crank_from_K(3.0, H, 20 * MM)
    assert err.value.reason == "K" and err.value.values["hi"] == 3.0


# ------------------------------------------------------------- slides exam 3
def test_slides_exam3_stroke():
    """Slides exam 3 (2011): a = 20, b = 60 cm, K = 2: θ = 60°, the printed stroke
    s = √(80² + 40² − 2·80·40 cos 60°) = 69.28; e = 3200 sin 60°/69.282 = 40 = b − a
    (hand, configs/ch3/slides-exam3.toml), the boundary of the crank condition."""
    d = slider_crank_stroke_from_K(2.0, 0.20, 0.60)
    assert d.lengths["H"] / 0.01 == pytest.approx(69.28, abs=0.005)
    assert d.lengths["e"] == 0.60 - 0.20
    assert d.values["boundary"] is True
    assert d.values["gamma_min"] == 0.0          # a + e = b: the rod ⟂ path at θ1 = 270°
    sc = analyse_slider_crank(0.2, 0.6, d.lengths["e"])
    assert sc.K == pytest.approx(2.0, rel=RTOL)
    assert sc.stroke == pytest.approx(d.lengths["H"], rel=RTOL)
    with pytest.raises(DescribedError) as err:
        slider_crank_stroke_from_K(2.01, 0.20, 0.60)
    assert err.value.reason == "K"
    assert err.value.values["hi"] == pytest.approx(2.0, rel=1e-12)   # θmax = arccos(40/80)


def test_slides_exam3_through_the_other_design():
    """The same linkage designed from K, its stroke and its offset gives back a, b."""
    d = slider_crank_stroke_from_K(1.5, 0.02, 0.06)
    back = slider_crank_from_K(1.5, d.lengths["H"], d.lengths["e"])
    np.testing.assert_allclose([back.lengths["l1"], back.lengths["l2"]], [0.02, 0.06], rtol=1e-12)


# ------------------------------------------------------------------- guide-bar
def test_guide_bar_slides():
    """Slides §2-3 一.2 (given the frame d and K): a = d sin(φ/2), φ = θ; slides
    fill-in 1: a swing of 30° has K = 1.4, and d = 100 gives a = 25.8819045103
    (configs/ch3/slides-fill1-guide-bar.toml)."""
    d = guide_bar_from_K(1.4, frame=100 * MM)
    assert d.kind == "guide_bar"
    assert d.lengths["l1"] / MM == pytest.approx(25.8819045103, abs=1e-9)
    assert d.values["theta"] == d.values["psi"] == pytest.approx(deg(30), rel=1e-12)
    gb = analyse_guide_bar(d.lengths["l1"], d.lengths["l4"])
    assert gb.kind == "oscillating"
    assert gb.K == pytest.approx(1.4, rel=RTOL)
    assert gb.psi == pytest.approx(deg(30), rel=RTOL)
    assert d.values["gamma_min"] == pytest.approx(math.pi / 2)
    inv = guide_bar_from_K(1.4, crank=d.lengths["l1"])
    assert inv.lengths["l4"] == pytest.approx(100 * MM, rel=1e-12)
    # the engine: at the limit positions the guide points 75° and 105° (ψ = 30°)
    P = d.pivots
    A = np.array(P["A"])
    q = np.array([math.atan2(P[b][1] - A[1], P[b][0] - A[0]) for b in ("B1", "B2")])
    m = solve(d.linkage, {1: DriverMotion(q)}, order=0)
    np.testing.assert_allclose(m.links[3].theta, [deg(75), deg(105)], rtol=1e-12)
    with pytest.raises(ValueError):
        guide_bar_from_K(1.4)
    with pytest.raises(ValueError):
        guide_bar_from_K(1.4, crank=0.01, frame=0.1)


# ---------------------------------------------------------------------- errors
def test_K_and_swing_errors():
    assert limit_angle_from_K(1.25) == pytest.approx(deg(20), rel=1e-15)
    for K in (1.0, 0.5):
        with pytest.raises(DescribedError) as err:
            crank_rocker_from_K(K, L3, PSI8, crank=0.07)
        assert err.value.reason == "K" and err.value.values["lo"] == 1.0
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(K8, L3, math.pi, crank=0.07)
    assert err.value.reason == "swing" and err.value.values["hi"] == math.pi
    # θ must stay below 90° + ψ/2 = 107°: K_max = (180 + 107)/(180 − 107) = 3.9315
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(4.0, L3, PSI8, crank=0.07)
    assert err.value.reason == "K"
    assert err.value.values["hi"] == pytest.approx(287 / 73, rel=1e-12)
    th = deg(105)
    K = time_ratio(th)
    circle = pivot_circle(K, L3, PSI8)
    mid = sum(circle.crank) / 2
    assert_reproduces(crank_rocker_from_K(K, L3, PSI8, crank=mid), K, PSI8)
    for bad in (dict(), dict(crank=0.07, frame=0.28)):
        with pytest.raises(ValueError):
            crank_rocker_from_K(K8, L3, PSI8, **bad)
    with pytest.raises(ValueError):
        crank_rocker_from_K(K8, L3, PSI8, crank=0.07, branch="up")


def test_pivot_line_errors():
    circle = pivot_circle(K8, L3, PSI8)
    # y = c: the line misses L above the top of the circle
    top = circle.O[1] + circle.R
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(K8, L3, PSI8, pivot_line=(0, 1, top * 1.01))
    assert err.value.reason == "pivot_line_misses"
    assert err.value.values["hi"] == pytest.approx(top, rel=1e-12)
    assert err.value.values["lo"] == pytest.approx(circle.O[1] - circle.R, rel=1e-12)
    # y = 0.28 m: meets L only above the chord (y_C2 = 0.2773): no crank-rocker
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(K8, L3, PSI8, pivot_line=(0, 1, 0.28))
    assert err.value.reason == "pivot_line_unusable"
    assert err.value.values["usable"] == [False, False]
    # x = 0: meets L at the bottom, in the dead arc (l1 = 0), and at the top
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(K8, L3, PSI8, pivot_line=(1, 0, 0))
    assert err.value.reason == "pivot_line_unusable"
    with pytest.raises(ValueError):
        crank_rocker_from_K(K8, L3, PSI8, pivot_line=(0, 0, 1))


def test_limit_angle_error_range():
    """K = 3 with 习题 3-15's rocker, frame and 45°: the error's K_hi is the largest
    K of the family (C1 fixed, a varying), below the asked K, and a K a little
    under it is designed."""
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K_limit_angle(3.0, 75.0, 100.0, deg(45))
    assert err.value.reason == "limit_angle"
    K_hi = err.value.values["K_hi"]
    # independent: bisection on K of "can the design be made" (60 halvings between 1.72
    # and 3, 2026-11-23) gives 1.7369994258271675 -- the grid alone gave 1.7223
    assert K_hi == pytest.approx(1.7369994258271675, rel=1e-9)
    with pytest.raises(DescribedError):        # just above it: no design
        crank_rocker_from_K_limit_angle(K_hi * (1 + 1e-7), 75.0, 100.0, deg(45))
    d = crank_rocker_from_K_limit_angle(1 + 0.98 * (K_hi - 1), 75.0, 100.0, deg(45))
    assert core_fourbar(d)[1].K[0] == pytest.approx(1 + 0.98 * (K_hi - 1), rel=RTOL)
