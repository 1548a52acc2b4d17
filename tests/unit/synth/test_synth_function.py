"""Function generation (§3.5): Freudenstein's equation, Chebyshev spacing, least
squares, the slider mechanisms, the structural error, and the named functions.

Book values: 【例 3-6】 prints l, m, n and a, b, c, d to 2 decimals (tolerance
±0.005).  【例 3-7】's program prints l, m, n, but the results are not in the
book's text (the section ends after the listing): its design is checked against
an independent solution instead.  The exercises (习题 3-9, 3-11, 3-12, 3-13) print
no answers: each is checked against a second calculation written here (a
nonlinear solve of the loop, the inversion method, a closed-form position).
"""

import math

import numpy as np
import pytest
from scipy.optimize import root

from mechcli.core.errors import DescribedError
from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.synth.function import (chebyshev_points, freudenstein, function_generator,
                                         rocker_slider, slider_crank_function)
from mechcli.core.synth.targets import NAMES, make_function, table_function

deg = np.radians


def wrap(a):
    return np.angle(np.exp(1j * np.asarray(a)))


def engine_theta3(design):
    """θ3 of the design moved on the engine to its prescribed inputs."""
    m = solve(design.linkage, {1: DriverMotion(design.inputs)}, order=0)
    assert m.feasible.all()
    return m.links[3].theta


def engine_slide(design):
    m = solve(design.linkage, {1: DriverMotion(design.inputs)}, order=0)
    assert m.feasible.all()
    return m.slides["3"].s


def loop_closure_ratios(t1, t3, a0, p0, guess):
    """Independent: eq. (3-33) itself, θ2i unknown, solved by scipy's root for (l, m, n, θ2i)."""
    def residual(z):
        l, m, n, th2 = z[0], z[1], z[2], z[3:]
        return np.concatenate([l * np.cos(th2) - (n + m * np.cos(t3 + p0) - np.cos(t1 + a0)),
                               l * np.sin(th2) - (m * np.sin(t3 + p0) - np.sin(t1 + a0))])
    z = root(residual, guess, method="hybr", tol=1e-14).x
    assert np.max(np.abs(residual(z))) < 1e-12
    return abs(z[0]), z[1], z[2]


def rocker_angle(l, m, n, u, branch):
    """Independent closed form of the four-bar (a = 1, b = l, c = m, d = n): the
    angle of D→C at crank angle u, C on the side ``branch`` of B→D (+1 left)."""
    b = np.exp(1j * u)
    d = n + 0j
    bd = d - b
    dist = np.abs(bd)
    along = (l * l - m * m + dist * dist) / (2 * dist)
    h = np.sqrt(l * l - along * along)
    c = b + bd / dist * (along + 1j * branch * h)
    return np.angle(c - d)


# --- 【例 3-6】 --------------------------------------------------------------------------

T1_36, T3_36 = deg([45.0, 90.0, 135.0]), deg([50.0, 80.0, 110.0])   # 【例 3-6】 θ1i, θ3i


def test_example_3_6_relative_and_absolute_lengths():
    # ERRATA: the listing of link_design builds the 2nd column as
    # cos(theta_3+phi_0)-theta_1-alpha_0 (a misplaced parenthesis); taken literally
    # it gives l² = -0.018 (no linkage).  The printed results are those of
    # eq. (3-34), cos(θ3+φ0-θ1-α0), which is what is implemented and tested.
    d = freudenstein(T1_36, T3_36, crank=0.100)              # a = 100 mm (the example's a)
    v = d.values
    # 【例 3-6】 计算结果 1, printed to 2 decimals
    assert v["l"] == pytest.approx(1.78, abs=0.005)
    assert v["m"] == pytest.approx(1.53, abs=0.005)
    assert v["n"] == pytest.approx(1.44, abs=0.005)
    # 计算结果 2 [mm], printed to 2 decimals
    mm = {k: d.lengths[k] * 1e3 for k in ("l1", "l2", "l3", "l4")}
    assert mm["l1"] == pytest.approx(100.00, abs=0.005)
    assert mm["l2"] == pytest.approx(178.30, abs=0.005)
    assert mm["l3"] == pytest.approx(153.30, abs=0.005)
    assert mm["l4"] == pytest.approx(144.24, abs=0.005)
    assert v["alpha0"] == 0.0 and v["phi0"] == 0.0 and v["iterations"] == 0   # the book's choice
    assert d.pivots["A"] == (0.0, 0.0) and d.pivots["D"][1] == 0.0 and d.pivots["D"][0] > 0


def test_example_3_6_matches_the_loop_closure_solved_directly():
    d = freudenstein(T1_36, T3_36)
    l, m, n = loop_closure_ratios(T1_36, T3_36, 0.0, 0.0, [1.5, 1.2, 1.2, 0.3, 0.3, 0.3])
    assert (d.values["l"], d.values["m"], d.values["n"]) == pytest.approx((l, m, n), rel=1e-10)
    assert d.values["residual"] < 1e-14   # eq. (3-34) at the points, round-off


def test_example_3_6_design_reproduces_its_points_on_the_engine():
    d = freudenstein(T1_36, T3_36, crank=0.1)
    np.testing.assert_allclose(d.inputs, T1_36, atol=0)            # α0 = 0: inputs as given
    np.testing.assert_allclose(d.angles[3], T3_36, atol=1e-15)
    assert np.max(np.abs(wrap(engine_theta3(d) - d.angles[3]))) <= 1e-9
    assert list(d.values["branches"]) == [1, 1, 1]


# --- 习题 3-11 ----------------------------------------------------------------------------

def test_exercise_3_11_against_the_loop_closure():
    # 习题 3-11: α1..3 = 35°, 80°, 125°; φ1..3 = 50°, 75°, 105°; origins 0 as in 【例 3-6】
    t1, t3 = deg([35.0, 80.0, 125.0]), deg([50.0, 75.0, 105.0])
    d = freudenstein(t1, t3)
    expected = loop_closure_ratios(t1, t3, 0.0, 0.0, [1.5, 1.5, 1.2, 0.3, 0.3, 0.3])
    assert (d.values["l"], d.values["m"], d.values["n"]) == pytest.approx(expected, rel=1e-10)
    # the same numbers to 4 digits by hand (Cramer's rule on the 3×3 system): l = 1.5829,
    # m = 1.5815, n = 1.2512
    assert (d.values["l"], d.values["m"], d.values["n"]) == pytest.approx(
        (1.5829, 1.5815, 1.2512), abs=5e-5)
    assert np.max(np.abs(wrap(engine_theta3(d) - d.angles[3]))) <= 1e-9


# --- 4 and 5 precision points -------------------------------------------------------------

def known_four_bar_points(t1_abs):
    """The points of 【例 3-6】's design (a = 1) turned so that α0 = 0.3, φ0 = -0.2:
    its engine θ3 at the absolute crank angles t1_abs, as relative angles."""
    l, m, n = 1.7830234404270604, 1.533039584971189, 1.4423946579721596   # 【例 3-6】 to 16 digits
    theta3 = rocker_angle(l, m, n, t1_abs, +1)
    return (l, m, n), t1_abs - 0.3, theta3 + 0.2


def test_five_points_recover_both_origins():
    ratios, t1, t3 = known_four_bar_points(deg([30.0, 55.0, 80.0, 105.0, 130.0]))
    d = freudenstein(t1, t3)
    v = d.values
    assert (v["l"], v["m"], v["n"]) == pytest.approx(ratios, rel=1e-9)
    assert (v["alpha0"], v["phi0"]) == pytest.approx((0.3, -0.2), abs=1e-9)
    assert v["iterations"] > 0 and len(v["solutions"]) >= 1
    assert np.max(np.abs(wrap(engine_theta3(d) - d.angles[3]))) <= 1e-9


@pytest.mark.parametrize("given", ["alpha0", "phi0"])
def test_four_points_solve_the_other_origin(given):
    ratios, t1, t3 = known_four_bar_points(deg([30.0, 60.0, 90.0, 120.0]))
    d = freudenstein(t1, t3, **{given: 0.3 if given == "alpha0" else -0.2})
    v = d.values
    # one free parameter (eq. 3-35: N0 = 1) gives several real roots; the known one is among
    # them, and the chosen one reproduces the points whatever it is
    assert any(np.allclose(row, (*ratios, 0.3, -0.2), atol=1e-9) for row in v["solutions"])
    assert v["residual"] < 1e-12
    assert np.max(np.abs(wrap(engine_theta3(d) - d.angles[3]))) <= 1e-9


# --- 【例 3-7】 Chebyshev spacing -----------------------------------------------------------

EX37 = dict(alpha_m=deg(60.0), phi_m=deg(90.0), alpha0=deg(86.0), phi0=deg(23.5))   # 【例 3-7】


def test_chebyshev_points_eq_3_38():
    # m = 3 on [1, 2]: 1.5 -/+ (1/2) cos(π/6) = 1.5 -/+ √3/4, and the midpoint
    np.testing.assert_allclose(chebyshev_points(1.0, 2.0, 3),
                               [1.5 - math.sqrt(3) / 4, 1.5, 1.5 + math.sqrt(3) / 4], rtol=1e-15)
    # the nodes of cos(nθ) scaled to [x0, xm] are symmetric about the midpoint
    x = chebyshev_points(-3.0, 7.0, 5)
    np.testing.assert_allclose(x + x[::-1], 4.0, rtol=1e-15)


def test_example_3_7_against_an_independent_solution():
    d = function_generator(make_function("log10"), 1.0, 2.0, method="chebyshev", n=3, **EX37)
    v = d.values
    x = np.array([1.5 - math.sqrt(3) / 4, 1.5, 1.5 + math.sqrt(3) / 4])   # eq. (3-38), m = 3
    alpha = (x - 1.0) * deg(60.0)                       # step (2): α = (x - x0)/μα
    phi = np.log10(x) / math.log10(2.0) * deg(90.0)     # φ = (y - y0)/μφ, y0 = 0, ym = lg 2
    np.testing.assert_allclose(v["x"], x, rtol=1e-15)
    np.testing.assert_allclose(v["alpha"], alpha, rtol=1e-14)
    np.testing.assert_allclose(v["phi"], phi, rtol=1e-14)
    expected = loop_closure_ratios(alpha, phi, deg(86.0), deg(23.5), [2.0, 0.5, 1.5, 0.3, 0.3, 0.3])
    assert (v["l"], v["m"], v["n"]) == pytest.approx(expected, rel=1e-10)
    # the program prints 2 decimals; these are the values it would print (not in the text)
    assert (round(v["l"], 2), round(v["m"], 2), round(v["n"], 2)) == (2.09, 0.57, 1.48)
    assert (v["alpha0"], v["phi0"]) == pytest.approx((deg(86.0), deg(23.5)), abs=1e-15)
    assert v["mu_alpha"] == pytest.approx(1.0 / deg(60.0), rel=1e-15)   # μα = (xm - x0)/αm


def test_example_3_7_structural_error_by_a_closed_form():
    d = function_generator(make_function("log10"), 1.0, 2.0, method="chebyshev", samples=101,
                           **EX37)
    v = d.values
    x = v["error_x"]
    assert v["error_feasible"].all() and list(v["branches"]) == [1, 1, 1]
    u = (x - 1.0) * deg(60.0) + deg(86.0)
    phi_real = wrap(rocker_angle(v["l"], v["m"], v["n"], u, +1) - deg(23.5))
    y_real = phi_real / deg(90.0) * math.log10(2.0)     # F(x) = y0 + φ μφ
    np.testing.assert_allclose(v["error_y"], np.log10(x) - y_real, atol=1e-12)   # Δy (3-37)
    np.testing.assert_allclose(v["error_phi"],
                               np.log10(x) / math.log10(2) * deg(90.0) - phi_real, atol=1e-12)
    assert v["error_y_max"] == pytest.approx(np.max(np.abs(np.log10(x) - y_real)), rel=1e-9)


def sign_changes(e):
    e = e[np.abs(e) > 1e-9 * np.max(np.abs(e))]
    return int(np.count_nonzero(np.sign(e[1:]) != np.sign(e[:-1])))


def test_example_3_7_structural_error_vanishes_at_the_nodes_and_crosses_there():
    d = function_generator(make_function("log10"), 1.0, 2.0, method="chebyshev", **EX37)
    v = d.values
    x, e = v["error_x"], v["error_y"]
    at = np.isin(x, v["x"])
    assert at.sum() == 3 and np.max(np.abs(e[at])) <= 1e-9
    for i in np.flatnonzero(at):              # a simple zero: the sign changes across each node
        assert e[i - 1] * e[i + 1] < 0
    # the book's trial origins (α0 = 86°, φ0 = 23.5°) are not the minimax ones: one more
    # crossing near x = 1.7, and the largest error at the end x0 (1.95e-3)
    assert sign_changes(e) >= 3
    assert np.argmax(np.abs(e)) == 0


def test_five_chebyshev_nodes_with_solved_origins_equi_oscillate_roughly():
    d = function_generator(make_function("log10"), 1.0, 2.0, method="chebyshev", n=5,
                           alpha_m=deg(60.0), phi_m=deg(90.0))
    v = d.values
    x, e = v["error_x"], v["error_y"]
    assert np.max(np.abs(e[np.isin(x, v["x"])])) <= 1e-9
    assert sign_changes(e) == 5
    # one extreme in each of the 6 intervals (ends and between nodes).  Chebyshev spacing
    # equalises the interpolation error's node polynomial; what is left is the variation of
    # the 5th derivative, ∝ x⁻⁵ for lg x: a factor 2⁵ = 32 over [1, 2] (measured: 16)
    edges = np.concatenate([[1.0], v["x"], [2.0]])
    peaks = [np.max(np.abs(e[(x >= lo) & (x <= hi)])) for lo, hi in zip(edges[:-1], edges[1:])]
    assert max(peaks) < 32 * min(peaks)
    assert v["error_y_max"] < 1e-3 * math.log10(2)     # far better than 3 nodes' 2e-3


def test_precision_points_given_by_x():
    x = [1.1, 1.5, 1.9]
    d = function_generator(make_function("log10"), 1.0, 2.0, x=x, **EX37)
    e = d.values["error_y"][np.isin(d.values["error_x"], x)]
    assert np.max(np.abs(e)) <= 1e-9
    assert np.max(np.abs(wrap(engine_theta3(d) - d.angles[3]))) <= 1e-9


def test_a_table_with_as_many_points_as_needed_gives_the_precision_points():
    x = chebyshev_points(1.0, 2.0, 3)
    table = table_function(x, np.log10(x))
    # the table's end points are the nodes, so the range is theirs
    via_table = function_generator(table, x[0], x[-1], **EX37)
    via_name = function_generator(make_function("log10"), x[0], x[-1], x=x, **EX37)
    for k in ("l", "m", "n"):
        assert via_table.values[k] == pytest.approx(via_name.values[k], rel=1e-12)


# --- 习题 3-13 least squares ---------------------------------------------------------------

def test_exercise_3_13_least_squares_is_optimal_and_moves_through_the_range():
    # 习题 3-13 gives only y = √x, 1 <= x <= 10; αm = 60°, φm = 90° (the book's 【例 3-7】 swings)
    # and α0 = 240°, φ0 = 340° (a 10° search for the smallest Δy with one branch) are ours
    d = function_generator(make_function("sqrt"), 1.0, 10.0, method="least_squares", n=11,
                           alpha_m=deg(60.0), phi_m=deg(90.0), alpha0=deg(240.0),
                           phi0=deg(340.0))
    v = d.values
    t1, t3 = v["alpha"] + v["alpha0"], v["phi"] + v["phi0"]
    A = np.stack([np.cos(t3), np.cos(t3 - t1), np.ones(11)], axis=-1)
    P = np.array([v["m"], -v["m"] / v["n"], (v["m"] ** 2 + v["n"] ** 2 + 1 - v["l"] ** 2)
                  / (2 * v["n"])])
    r = A @ P - np.cos(t1)
    # the normal equations Aᵀr = 0: the residual of (3-34) is least (a perturbed P is worse)
    assert np.max(np.abs(A.T @ r)) < 1e-13
    assert v["residual_rms"] == pytest.approx(np.sqrt(np.mean(r ** 2)), rel=1e-9)
    assert v["residual_rms"] > 1e-6                     # 11 points: not exact
    assert v["error_feasible"].all() and abs(int(v["branches"].sum())) == 11
    assert 0 < v["error_y_max"] < 0.01 * (math.sqrt(10) - 1)


# --- slider mechanisms --------------------------------------------------------------------

def test_exercise_3_12_slider_crank():
    # 习题 3-12: φ = 60°, 85°, 120°; s = 36, 28, 19 mm; offset unknown (guide y = e)
    q, s = deg([60.0, 85.0, 120.0]), np.array([36.0, 28.0, 19.0]) * 1e-3
    d = slider_crank_function(q, s)

    def closure(z):     # independent: |BC| = l2 at the three positions, scipy root
        l1, l2, e = z
        return np.hypot(s - l1 * np.cos(q), e - l1 * np.sin(q)) - l2
    l1, l2, e = root(closure, [0.02, 0.03, 0.0], method="hybr", tol=1e-14).x
    assert np.max(np.abs(closure([l1, l2, e]))) < 1e-15
    assert (d.lengths["l1"], d.lengths["l2"], d.lengths["e"]) == pytest.approx((l1, l2, e),
                                                                                 rel=1e-9)
    # the crank comes out 17.000 mm: round, as an exercise's data are made from it
    assert d.lengths["l1"] * 1e3 == pytest.approx(17.0, abs=1e-9)
    assert d.lengths["l2"] * 1e3 == pytest.approx(29.572, abs=5e-4)
    assert d.lengths["e"] * 1e3 == pytest.approx(3.847, abs=5e-4)
    np.testing.assert_allclose(engine_slide(d), s, atol=1e-12)


def test_slider_crank_with_given_offset_takes_two_points():
    # two points of the 习题 3-12 design (l1 = 17, e as solved): the same crank and rod
    q, s = deg([60.0, 85.0, 120.0]), np.array([36.0, 28.0, 19.0])
    full = slider_crank_function(q, s)
    d = slider_crank_function(q[:2], s[:2], e=full.lengths["e"])
    assert d.lengths["l1"] == pytest.approx(full.lengths["l1"], rel=1e-9)
    assert d.lengths["l2"] == pytest.approx(full.lengths["l2"], rel=1e-9)
    with pytest.raises(ValueError):
        slider_crank_function(q, s, e=1.0)


def test_exercise_3_9_rocker_slider_by_the_inversion_method():
    # 习题 3-9: S1 = 36, S12 = 8, S23 = 9 mm; φ12 = 25°, φ23 = 35°; position II vertical;
    # e = 28 mm.  The figure is not in the text; assumed: A = (0, 0), guide y = -28 mm,
    # the slider moving towards A's foot (s = 36, 28, 19), the rocker's line pointing
    # down in position II and turning clockwise (φ = -65°, -90°, -125°)
    phi = deg([-65.0, -90.0, -125.0])
    s = np.array([36.0, 28.0, 19.0])
    d = rocker_slider(phi, s, e=-28.0)
    # the inversion method: the rocker held in position II, the pins B_i turned by φ2 - φi
    b = (s - 28.0j) * np.exp(1j * (phi[1] - phi))
    (p, q, r) = b
    den = 2 * (p.real * (q.imag - r.imag) + q.real * (r.imag - p.imag) + r.real * (p.imag - q.imag))
    c2 = complex((abs(p) ** 2 * (q.imag - r.imag) + abs(q) ** 2 * (r.imag - p.imag)
                  + abs(r) ** 2 * (p.imag - q.imag)) / den,
                 (abs(p) ** 2 * (r.real - q.real) + abs(q) ** 2 * (p.real - r.real)
                  + abs(r) ** 2 * (q.real - p.real)) / den)          # circumcentre of B1', B2, B3'
    assert d.lengths["l1"] == pytest.approx(abs(c2), rel=1e-12)      # the rocker A→C
    assert d.lengths["l2"] == pytest.approx(abs(c2 - q), rel=1e-12)  # the rod C→B
    assert d.lengths["l1"] == pytest.approx(22.237, abs=5e-4)        # the same, 3 decimals
    assert d.lengths["l2"] == pytest.approx(52.247, abs=5e-4)
    assert d.values["delta"] == pytest.approx(wrap(np.angle(c2) - phi[1]), abs=1e-12)
    np.testing.assert_allclose(engine_slide(d), s, atol=1e-9)


# --- errors -------------------------------------------------------------------------------

@pytest.mark.parametrize("n", [2, 6])
def test_freudenstein_takes_three_to_five_points(n):
    with pytest.raises(ValueError):
        freudenstein(np.linspace(0.1, 1.0, n), np.linspace(0.2, 1.1, n))


def test_origins_that_the_points_determine_may_not_be_given():
    t = np.linspace(0.1, 1.0, 5)
    with pytest.raises(ValueError):
        freudenstein(t[:4], t[:4] ** 2, alpha0=0.0, phi0=0.0)
    with pytest.raises(ValueError):
        freudenstein(t, t ** 2, phi0=0.0)


def test_repeated_points_are_singular():
    with pytest.raises(DescribedError) as e:
        freudenstein(deg([45.0, 45.0, 135.0]), deg([50.0, 50.0, 110.0]))
    assert e.value.reason == "singular"
    with pytest.raises(DescribedError) as e:      # the same point a turn apart
        freudenstein(deg([45.0, 90.0, 405.0]), deg([50.0, 80.0, 50.0]))
    assert e.value.reason == "singular"
    with pytest.raises(DescribedError) as e:
        slider_crank_function(deg([60.0, 60.0, 120.0]), [36.0, 36.0, 19.0])
    assert e.value.reason == "singular"


def test_no_real_four_bar():
    # cos θ1 is 1/2 at all three points: eq. (3-34) gives P = (0, 0, 1/2), a rocker of
    # zero length
    with pytest.raises(DescribedError) as e:
        freudenstein(deg([60.0, -60.0, 60.0]), deg([10.0, 40.0, 80.0]))
    assert e.value.reason == "no_solution"
    assert abs(e.value.values["P0"]) < 1e-12


def test_slider_crank_against_its_angles_has_no_solution():
    # 习题 3-12's angles turned by π: the crank would have to be -17 mm
    with pytest.raises(DescribedError) as e:
        slider_crank_function(deg([240.0, 265.0, 300.0]), [36.0, 28.0, 19.0])
    assert e.value.reason == "no_solution"
    assert e.value.values["l1"] == pytest.approx(-17.0, abs=1e-9)


@pytest.mark.parametrize("swing", [{"alpha_m": math.pi}, {"phi_m": deg(200.0)},
                                   {"alpha_m": 0.0}])
def test_a_swing_of_half_a_turn_or_more_is_refused(swing):
    kw = {**EX37, **swing}
    with pytest.raises(DescribedError) as e:
        function_generator(make_function("log10"), 1.0, 2.0, method="chebyshev", **kw)
    assert e.value.reason == "swing"


def test_function_generator_arguments():
    f = make_function("log10")
    with pytest.raises(ValueError):
        function_generator(f, 1.0, 2.0, method="simplex", **EX37)
    with pytest.raises(ValueError):
        function_generator(f, 2.0, 1.0, method="chebyshev", **EX37)
    with pytest.raises(ValueError):                      # precision points need x
        function_generator(f, 1.0, 2.0, **EX37)
    with pytest.raises(ValueError):                      # a point outside the range
        function_generator(f, 1.0, 2.0, x=[1.1, 1.5, 2.5], **EX37)
    with pytest.raises(ValueError):                      # Chebyshev computes its points
        function_generator(f, 1.0, 2.0, method="chebyshev", x=[1.1, 1.5, 1.9], **EX37)
    with pytest.raises(ValueError):
        function_generator(f, 1.0, 2.0, method="chebyshev", n=6, **EX37)
    with pytest.raises(ValueError):                      # least squares needs 4 points or more
        function_generator(f, 1.0, 2.0, method="least_squares", n=3, **EX37)
    with pytest.raises(ValueError):                      # ... and both origins
        function_generator(f, 1.0, 2.0, method="least_squares", alpha_m=deg(60),
                           phi_m=deg(90), alpha0=0.0)
    with pytest.raises(DescribedError) as e:             # lg x at x = 0
        function_generator(f, 0.0, 2.0, method="chebyshev", **EX37)
    assert e.value.reason == "domain"
    with pytest.raises(DescribedError) as e:             # cos 0 = cos 2π: no scale
        function_generator(make_function("cos"), 0.0, 2 * math.pi, method="chebyshev", **EX37)
    assert e.value.reason == "flat"


# --- the named functions ------------------------------------------------------------------

SAMPLES = {   # name -> (kwargs, x inside the domain, f(x) by hand)
    "log10": ({}, 100.0, 2.0), "ln": ({}, math.e, 1.0), "sqrt": ({}, 9.0, 3.0),
    "power": ({"exponent": 1.5}, 4.0, 8.0), "sin": ({}, math.pi / 6, 0.5),
    "cos": ({}, math.pi / 3, 0.5), "tan": ({}, math.pi / 4, 1.0), "exp": ({}, 0.0, 1.0),
    "reciprocal": ({}, 4.0, 0.25), "polynomial": ({"coeffs": [1.0, -2.0, 3.0]}, 2.0, 9.0),
}


@pytest.mark.parametrize("name", NAMES)
def test_named_function_value_and_derivative(name):
    kw, x, y = SAMPLES[name]
    f = make_function(name, **kw)
    assert f.name == name
    assert float(f(x)) == pytest.approx(y, rel=1e-14)
    xs = np.array([x, x * 1.1 + 0.1])
    np.testing.assert_allclose(f(xs)[0], y, rtol=1e-14)                 # vectorised
    h = 1e-5 * max(1.0, abs(x))
    fd = (f(xs + h) - f(xs - h)) / (2 * h)      # central difference: O(h²) + eps/h ~ 1e-10
    np.testing.assert_allclose(f.derivative(xs), fd, rtol=1e-7)


@pytest.mark.parametrize("name, kw, x0, xm, bad", [
    ("log10", {}, 0.0, 2.0, 0.0), ("ln", {}, -1.0, 2.0, -1.0), ("sqrt", {}, -0.5, 2.0, -0.5),
    ("tan", {}, 1.0, 2.0, math.pi / 2), ("tan", {}, -5.0, -4.0, -1.5 * math.pi),
    ("reciprocal", {}, -1.0, 1.0, 0.0), ("power", {"exponent": 0.5}, -1.0, 1.0, -1.0),
    ("power", {"exponent": -2.0}, 0.0, 1.0, 0.0),
])
def test_domain_errors(name, kw, x0, xm, bad):
    f = make_function(name, **kw)
    with pytest.raises(DescribedError) as e:
        f.check_domain(x0, xm)
    assert e.value.reason == "domain"
    assert e.value.values["x"] == pytest.approx(bad, abs=1e-15)
    assert (e.value.values["x0"], e.value.values["xm"]) == (x0, xm)


@pytest.mark.parametrize("name, kw, x0, xm", [
    ("log10", {}, 0.5, 2.0), ("sqrt", {}, 0.0, 2.0), ("tan", {}, -1.5, 1.5),
    ("reciprocal", {}, 0.1, 1.0), ("power", {"exponent": 2.0}, -3.0, 1.0),
    ("power", {"exponent": 0.5}, 0.0, 1.0), ("exp", {}, -50.0, 50.0),
])
def test_domain_accepted(name, kw, x0, xm):
    make_function(name, **kw).check_domain(x0, xm)    # raises if refused


def test_make_function_refuses_what_it_does_not_take():
    with pytest.raises(ValueError):
        make_function("lg")                           # not a name
    with pytest.raises(ValueError):
        make_function("sqrt", exponent=2)
    with pytest.raises(ValueError):
        make_function("power")
    with pytest.raises(ValueError):
        make_function("polynomial")
    with pytest.raises(ValueError):
        make_function("log10", coeffs=[1, 2])


def test_cubic_table_is_exact_for_a_cubic_and_linear_table_for_a_line():
    x = np.array([0.0, 0.5, 1.5, 2.0, 3.0])
    cubic = table_function(x, x ** 3 - 2 * x)          # not-a-knot reproduces a cubic
    xi = np.linspace(0.0, 3.0, 31)
    np.testing.assert_allclose(cubic(xi), xi ** 3 - 2 * xi, atol=1e-12)
    np.testing.assert_allclose(cubic.derivative(xi), 3 * xi ** 2 - 2, atol=1e-11)
    line = table_function([1.0, 2.0, 4.0], [0.0, 1.0, 1.0], interpolation="linear")
    np.testing.assert_allclose(line([1.5, 3.0]), [0.5, 1.0], atol=0)
    np.testing.assert_allclose(line.derivative([1.5, 3.0]), [1.0, 0.0], atol=0)
    with pytest.raises(DescribedError) as e:
        cubic.check_domain(-0.1, 1.0)
    assert e.value.reason == "domain" and e.value.values["x"] == -0.1
    with pytest.raises(ValueError):
        table_function([1.0, 1.0, 2.0], [0.0, 1.0, 2.0])    # x not increasing


def test_the_former_name_of_the_target_functions_is_the_same_module():
    """``mechcli.core.synth.functions`` (the name before issue 32 §5) is
    :mod:`mechcli.core.synth.targets` itself."""
    import mechcli.core.synth.functions
    import mechcli.core.synth.targets
    from mechcli.core.synth.functions import make_function as former
    assert mechcli.core.synth.functions is mechcli.core.synth.targets
    assert former is make_function
