"""The optimize core against independent references: the book's closed forms
(式 7-1, 7-12, 7-13), brute-force distances, finite-difference-free checks of
the methods on problems with known optima, and the population plumbing
(chunks through a mapper, no NaN for designs that do not assemble)."""

import math

import numpy as np
import pytest

from mechcli.core.errors import DescribedError
from mechcli.core.linkage import (RRR, Crank, DriverMotion, Ground, Linkage, PointOnLink,
                                  four_bar, solve, stack)
from mechcli.core.optimize import linkage_problem as lp
from mechcli.core.optimize import terms
from mechcli.core.optimize.methods import minimize
from mechcli.core.optimize.problem import Evaluation, Problem, Variable, grid


def _pop(l2, l3, l1=1.0, l4=5.0, samples=360):
    lk = four_bar(l1, np.asarray(l2, float).reshape(-1, 1), np.asarray(l3, float).reshape(-1, 1),
                  l4)
    return terms.Population(lk, 1, samples)


def test_input_limit_is_the_books_phi0():
    # 式 7-1: phi0 = acos(((l1 + l2)^2 + l4^2 - l3^2) / (2 (l1 + l2) l4))
    l2 = np.array([4.1289, 3.0, 5.5])
    l3 = np.array([2.3224, 3.5, 2.0])
    phi0, ok = terms.input_limit(_pop(l2, l3), 3, "min")
    book = np.arccos(((1 + l2) ** 2 + 25 - l3 ** 2) / (10 * (1 + l2)))
    assert ok.all()
    assert phi0 == pytest.approx(book, abs=1e-12)


def test_transmission_range_is_the_books_g7_g8():
    # 式 7-12/7-13: the angle BCD is extreme with the crank along the frame:
    # acos((l2^2 + l3^2 - (l4 -+ l1)^2) / (2 l2 l3)); 0 and 180 deg are samples
    l2 = np.array([4.1289, 3.0])
    l3 = np.array([2.3224, 3.5])
    lo, hi, ok = terms.transmission_range(_pop(l2, l3).revolution(1), ["C"])
    assert ok.all()
    assert lo == pytest.approx(np.arccos((l2 ** 2 + l3 ** 2 - 16) / (2 * l2 * l3)), abs=1e-12)
    assert hi == pytest.approx(np.arccos((l2 ** 2 + l3 ** 2 - 36) / (2 * l2 * l3)), abs=1e-12)


def test_transmission_refinement_between_samples():
    # a frame tilted by 7.3 deg: the extremes fall between the 1-degree samples; the
    # parabola through three samples brings them within 1e-6 rad of the closed form
    tilt = math.radians(7.3)
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", 5 * math.cos(tilt), 5 * math.sin(tilt)),
                     Crank(1, "A", "B", 1.0), RRR("C", "B", 2, 4.0, "D", 3, 2.5, 1)))
    lo, hi, ok = terms.transmission_range(terms.Population(lk, 1).revolution(1), ["C"])
    assert lo[0] == pytest.approx(math.acos((16 + 6.25 - 16) / 20), abs=1e-6)
    assert hi[0] == pytest.approx(math.acos((16 + 6.25 - 36) / 20), abs=1e-6)


def test_function_deviation_against_the_books_formulas():
    # 式 7-4 ... 7-7: psi = pi - alpha - beta for 0 < phi <= pi, pi - alpha + beta beyond
    l2, l3 = 4.0, 2.5
    pop = _pop([l2], [l3])
    phi0 = np.array([0.3])
    dphi = np.linspace(0.1, 4.0, 40)
    dev, psi, q, ok = terms.function_deviation(pop, 3, phi0, dphi, np.zeros_like(dphi),
                                               psi0=0.0)
    phi = phi0[0] + dphi
    r = np.sqrt(26 - 10 * np.cos(phi))
    alpha = np.arccos((r * r + l3 * l3 - l2 * l2) / (2 * r * l3))
    beta = np.arccos((r * r + 24) / (10 * r))
    book = np.where(phi <= np.pi, np.pi - alpha - beta, np.pi - alpha + beta)
    assert ok.all()
    assert psi[0] == pytest.approx(book, abs=1e-12)
    assert dev[0] == pytest.approx(book, abs=1e-12)     # psi0 = 0: the deviation is psi


def test_path_deviation_is_the_distance_to_the_sampled_curve():
    lk = four_bar(1.0, np.array([[4.0]]), np.array([[3.0]]), 4.5).with_elements(
        PointOnLink("M", 2, "B", 2.0, 1.0))
    pop = terms.Population(lk, 1, 720)
    m = solve(lk, {1: DriverMotion(np.linspace(0, 2 * np.pi, 20001), 1.0, 0.0)}, order=0)
    px, py = m.points["M"].x.ravel(), m.points["M"].y.ravel()
    targets = np.array([[2.0, 3.0], [3.5, 2.5], [0.0, 0.0]])
    d, ok = terms.path_deviation(pop, "M", targets)
    brute = np.min(np.hypot(px[:, None] - targets[:, 0], py[:, None] - targets[:, 1]), axis=0)
    assert ok.all()
    # the polyline through 720 samples is within O(h^2 curvature) of the curve
    assert d[0] == pytest.approx(brute, abs=2e-5)
    # with prescribed angles the distance is to the point at those angles exactly
    d2, _ = terms.path_deviation(pop, "M", targets[:1], np.array([0.0]), np.array([1.0]))
    m1 = solve(lk, {1: DriverMotion(np.array([1.0]), 1.0, 0.0)}, order=0)
    assert d2[0, 0] == pytest.approx(math.hypot(float(m1.points["M"].x.ravel()[0]) - 2.0,
                                                float(m1.points["M"].y.ravel()[0]) - 3.0),
                                     abs=1e-14)


def test_designs_that_do_not_assemble_are_infeasible_never_nan():
    # l2 = 1.2, l3 = 1.2 with l4 = 5: C cannot close at any crank angle
    ev = lp.LinkageEvaluator(
        lambda X: (four_bar(1.0, X[:, :1], X[:, 1:], 5.0), np.ones(len(X), bool), {}), 1,
        lp.FunctionGoal(3, "output_min", np.array([0.5, 1.0]), np.array([0.1, 0.2])),
        [lp.Transmission(0.5, 2.5), lp.Assembly(), lp.CrankConditions()])
    out = ev(np.array([[1.2, 1.2], [4.0, 2.5]]))
    assert out.ok.tolist() == [False, True]
    assert np.isfinite(out.f).all() and np.isfinite(out.g).all()
    assert out.g[0, 2] == pytest.approx(1.0)         # assembly: every position failed
    assert out.g[1, 2] == 0.0


def test_crank_conditions_are_the_books_g1_to_g6():
    g = terms.crank_conditions(1.0, 4.1289, 2.3224, 5.0)
    assert g == pytest.approx([1 - 4.1289, 1 - 2.3224, 1 - 5, 6 - 6.4513, 5.1289 - 7.3224,
                               3.3224 - 9.1289])
    with pytest.raises(DescribedError):
        terms.four_bar_lengths(Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", 1.0))))


def _quadratic(center, constraint=None):
    def ev(X):
        f = np.sum((X - center) ** 2, axis=1)
        g = (np.zeros((len(X), 0)) if constraint is None
             else (X[:, :1] + X[:, 1:2] - constraint))       # x0 + x1 <= c
        return Evaluation(f, g, np.ones(len(X), bool))
    return ev


@pytest.mark.parametrize("method", ["slsqp", "trust-constr", "differential_evolution"])
def test_methods_find_the_constrained_minimum_of_a_quadratic(method):
    # min |x - (2, 2)|^2 subject to x0 + x1 <= 2: the KKT point is (1, 1), f = 2
    p = Problem([Variable("a", -5, 5, 0.0), Variable("b", -5, 5, 0.0)],
                _quadratic(np.array([2.0, 2.0]), 2.0), ["sum"])
    r = minimize(p, method, tol=1e-10, maxiter=2000, seed=3)
    # What trust-constr promises at tol = 1e-10 (mechcli's continuation of it, methods.
    # _trust_constr): on the scaled problem F = f / f(start) = f / 8, u = x (a zero start's
    # size is a tenth of the span 10), the Lagrangian's gradient below tol (inf-norm) and
    # the duality measure below tol over m = 5 inequalities (the constraint, 4 bounds).
    # This problem is convex, so f - f* <= 8 (5 tol + tol |u - u*|) < 4.1e-9; along the
    # constraint the gradient bound gives |x0 - x1| <= 8 sqrt(2) tol / sqrt(2) = 8e-10,
    # across it f - f* >= lambda |g| = 2 |x0 + x1 - 2|: both x within 2.1e-9 of (1, 1).
    # (scipy 1.17.1's own gtol exit, taken as it is, stopped at f = 2.000258: its test
    # ignores complementarity.)  SLSQP, and DE polished by it, promise f: ftol = 1e-10 on
    # its relative change, f - f* well below 1e-7; then |x - x*|^2 <= f - f* (f is strongly
    # convex with modulus 1 about x*, where grad f . (x - x*) = -2 g(x) >= 0) leaves x
    # within 3.2e-4, measured 1e-6 along the constraint: 1e-5 checks it with margin.
    x_tol, f_tol = (2.1e-9, 4.1e-9) if method == "trust-constr" else (1e-5, 1e-7)
    assert r.x == pytest.approx([1.0, 1.0], abs=x_tol)
    assert r.f == pytest.approx(2.0, abs=f_tol)
    assert r.success and r.active.tolist() == [True]


def test_nelder_mead_and_multistart_without_constraints():
    p = Problem([Variable("a", -5, 5, 4.0), Variable("b", -5, 5, -4.0)],
                _quadratic(np.array([1.5, -0.5])))
    r = minimize(p, "nelder-mead", tol=1e-10, maxiter=5000)
    assert r.x == pytest.approx([1.5, -0.5], abs=1e-7)
    p.history.clear()
    r = minimize(p, "slsqp", tol=1e-12, starts=4, seed=0)
    assert len(r.starts) == 4 and r.x == pytest.approx([1.5, -0.5], abs=1e-7)


@pytest.mark.parametrize("method", ["golden", "brent"])
def test_scalar_methods(method):
    # min (x - 0.3)^2 on [0, 1]: golden section shrinks to tol = 1e-8
    p = Problem([Variable("x", 0.0, 1.0, 0.5)], _quadratic(np.array([0.3])))
    r = minimize(p, method, tol=1e-8, maxiter=500)
    assert r.x[0] == pytest.approx(0.3, abs=1e-7)


def test_population_goes_through_the_mapper_in_chunks():
    seen = []

    def mapper(fn, chunks):
        chunks = list(chunks)
        seen.append([len(c) for c in chunks])
        return map(fn, chunks)

    p = Problem([Variable("a", 0, 1, 0.5)], _quadratic(np.array([0.2])), mapper=mapper, chunk=4)
    ev = p.evaluate(np.linspace(0, 1, 10)[:, None])
    assert seen == [[4, 4, 2]]
    assert ev.f == pytest.approx((np.linspace(0, 1, 10) - 0.2) ** 2)
    assert p.evaluations == 10


def test_grid_counts_no_evaluations_and_marks_infeasible():
    p = Problem([Variable("a", -2, 2, 0.0), Variable("b", -2, 2, 0.0)],
                _quadratic(np.array([0.0, 0.0]), 1.0), ["sum"])
    u, v, F, feas = grid(p, 0, 1, np.zeros(2), count=5)
    assert p.evaluations == 0
    assert F[2, 2] == 0.0 and feas[2, 2] and not feas[4, 4]    # (2, 2): 4 > 1


def test_stack_refuses_linkages_of_different_structure():
    from mechcli.core.linkage import slider_crank
    with pytest.raises(ValueError, match="differs"):
        stack([four_bar(1, 4, 3, 5), slider_crank(1, 4)])
    # numbers (the branch included) may differ: one batched solve moves both
    lk = stack([four_bar(1, 4, 3, 5), four_bar(1, 4.5, 3, 5, branch=-1)])
    assert lk.shape == (2, 1)
    m = solve(lk, {1: DriverMotion(np.array([0.7]), 1.0, 0.0)}, order=0)
    for k, single in enumerate([four_bar(1, 4, 3, 5), four_bar(1, 4.5, 3, 5, branch=-1)]):
        ms = solve(single, {1: DriverMotion(np.array([0.7]), 1.0, 0.0)}, order=0)
        assert m.links[3].theta[k, 0] == ms.links[3].theta[0]


def test_slide_goal_deviation_is_in_one_unit():
    # a slider-crank's slide moved by exactly the target: zero deviation; 1 mm more
    # target: -1 mm over the linkage's size (scale)
    from mechcli.core.linkage import slider_crank
    lk = slider_crank(np.array([[0.05]]), np.array([[0.2]]))
    pop = terms.Population(lk, 1)
    dphi = np.radians([30.0, 60.0, 90.0])
    m = solve(lk, {1: DriverMotion(np.concatenate([[0.0], dphi]), 1.0, 0.0)}, order=0)
    s = m.slides["3"].s.ravel()
    moved = s[1:] - s[0]
    dev, *_ = terms.function_deviation(pop, "3", np.array([0.0]), dphi, moved, scale=0.2)
    assert dev[0] == pytest.approx(0.0, abs=1e-15)
    dev, *_ = terms.function_deviation(pop, "3", np.array([0.0]), dphi, moved + 0.001,
                                       scale=0.2)
    assert dev[0] == pytest.approx(np.full(3, -0.001 / 0.2), abs=1e-14)
