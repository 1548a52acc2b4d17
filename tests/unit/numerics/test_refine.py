"""The shared numerics of :mod:`mechcli.core.numerics` against analytic references."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from mechcli.core.numerics import (bisect, descending_root, gauss_legendre, golden_section_max,
                                   maximize_piecewise, mean_rms, sign_changes, true_runs)


def test_bisect_finds_square_roots_to_the_stated_tolerance():
    # x² = c on [0, 2] and [0, 3]: the roots are √2 and √3
    c = np.array([2.0, 3.0])
    lo, hi = bisect(np.zeros(2), np.array([2.0, 3.0]), lambda x: x * x < c, 1e-14)
    assert np.all(lo * lo < c) and np.all(hi * hi >= c)
    # the stopping rule: |hi - lo| <= rtol * max(1, |lo|)
    assert np.all(np.abs(hi - lo) <= 1e-14 * np.maximum(1.0, lo))
    assert_allclose(lo, np.sqrt(c), rtol=0, atol=2e-14)


def test_bisect_accepts_reversed_brackets_and_stops_after_the_iterations():
    # lo = 2 > hi = 0: lo still keeps the side where keep_lo is True (x² > 2)
    lo, hi = bisect(2.0, 0.0, lambda x: x * x > 2.0, 0.0, iterations=10)
    # 10 halvings of a bracket of width 2 leave 2 / 2**10
    assert abs(lo - hi) == pytest.approx(2.0 / 2 ** 10, rel=0, abs=1e-15)
    assert hi <= math.sqrt(2) <= lo


def test_golden_section_finds_the_maximum_of_a_parabola_and_a_sine():
    # -(x - 0.3)² peaks at 0.3; sin x peaks at π/2 (value 1)
    def f(x):
        return np.array([-(x[0] - 0.3) ** 2, math.sin(x[1])])

    x, fx = golden_section_max(f, np.array([0.0, 1.0]), np.array([1.0, 2.0]))
    # near a quadratic peak f changes by ~x² of the abscissa error: comparisons of f
    # resolve the abscissa to sqrt(eps) |x| ≈ 1.5e-8 · 1.6, not to the 1e-10 bracket
    assert_allclose(x, [0.3, math.pi / 2], rtol=0, atol=np.sqrt(np.finfo(float).eps) * 1.6)
    assert_allclose(fx, [0.0, 1.0], rtol=0, atol=1e-15)


def test_golden_section_stops_after_the_iterations():
    # each step shrinks the bracket [0, 1] by GOLDEN = 0.618...: after 5 steps the better
    # interior point is within 0.618**5 ≈ 0.09 of the maximum at 0.9, and not yet within
    # the 1e-4 that the 48 default steps easily reach
    x, _ = golden_section_max(lambda x: -(x - 0.9) ** 2, np.array([0.0]), np.array([1.0]),
                              iterations=5)
    assert 1e-4 < abs(x[0] - 0.9) < 0.618 ** 5
    x, _ = golden_section_max(lambda x: -(x - 0.9) ** 2, np.array([0.0]), np.array([1.0]))
    assert abs(x[0] - 0.9) < 1e-4


def test_sign_changes_bracket_the_roots_of_a_cosine():
    # cos x on 0..2π in 9 steps of 2π/9: the roots π/2 (falling) and 3π/2 (rising) lie
    # 2.25 and 6.75 steps from 0, i.e. in the intervals 2 and 6
    x = np.linspace(0, 2 * np.pi, 10)
    y = np.cos(x)
    assert sign_changes(y).tolist() == [2, 6]
    assert sign_changes(y, falling_only=True).tolist() == [2]
    assert x[2] < np.pi / 2 < x[3] and x[6] < 1.5 * np.pi < x[7]


def test_sign_changes_of_a_hand_made_sequence():
    # signs + + - - + 0 +: changes in intervals 1 (+ -), 3 (- +), 4 and 5 (touching 0)
    y = np.array([1.0, 2.0, -1.0, -3.0, 2.0, 0.0, 1.0])
    assert sign_changes(y).tolist() == [1, 3, 4, 5]
    # falling through zero: + - (1) and + 0 (4)
    assert sign_changes(y, falling_only=True).tolist() == [1, 4]


def test_descending_root_of_cosine_is_half_pi_to_a_few_doubles():
    root = descending_root(np.cos, 1.0, 2.0)
    assert root == pytest.approx(math.pi / 2, rel=0, abs=4e-16)


def test_descending_root_at_a_kink_is_the_kink():
    # 0.7 - x for x < 0.7, then -(x - 0.7) * 5: a kink at 0.7 where it crosses zero
    def f(x):
        return np.where(x < 0.7, 0.7 - x, -5 * (x - 0.7))

    assert descending_root(f, 0.0, 1.0) == pytest.approx(0.7, rel=0, abs=1e-15)


def test_descending_root_without_a_falling_bracket_returns_lo():
    assert descending_root(lambda x: x, 0.25, 1.0) == 0.25


def test_maximize_piecewise_refines_an_interior_maximum():
    # sin on [0, 2]: maximum 1 at π/2, between grid points of the 0.1 step
    hit = maximize_piecewise([(0.0, 2.0, lambda x: (np.sin(x), np.cos(x)))], 0.1)
    assert hit[0] == pytest.approx(math.pi / 2, rel=0, abs=1e-15)
    assert hit[1] == pytest.approx(1.0, rel=0, abs=1e-15)


def test_maximize_piecewise_takes_a_kink_and_the_best_piece():
    # piece 1: x on [0, 1] (max 1 at its end, a kink); piece 2: 1.5 - (x - 2)² on [1, 3]
    # (max 1.5 at x = 2, the larger one)
    pieces = [(0.0, 1.0, lambda x: (x, np.ones_like(x))),
              (1.0, 3.0, lambda x: (1.5 - (x - 2.0) ** 2, -2.0 * (x - 2.0)))]
    x, g = maximize_piecewise(pieces, 0.3)
    assert x == pytest.approx(2.0, rel=0, abs=1e-15) and g == pytest.approx(1.5, abs=1e-15)
    x, g = maximize_piecewise(pieces[:1], 0.3)
    assert (x, g) == (1.0, 1.0)


def test_maximize_piecewise_of_nothing_is_none():
    assert maximize_piecewise([], 0.1) is None


@pytest.mark.parametrize("mask, runs", [
    ([], []),
    ([False, False, False], []),
    ([True, True, True], [(0, 3)]),
    ([True, False, False, True], [(0, 1), (3, 4)]),
    ([False, True, True, False, True], [(1, 3), (4, 5)]),
    ([True], [(0, 1)]),
])
def test_true_runs_of_hand_made_masks(mask, runs):
    got = true_runs(np.array(mask, dtype=bool))
    assert [(int(a), int(b)) for a, b in got] == runs


def test_gauss_legendre_four_points_integrate_degree_seven_exactly():
    # ∫₀³ x⁷ dx = 3⁸ / 8 = 820.125, on the uneven grid 0, 0.4, 1.7, 3
    x, w = gauss_legendre(np.array([0.0, 0.4, 1.7, 3.0]))
    assert x.shape == w.shape == (12,)
    assert np.dot(w, x ** 7) == pytest.approx(3 ** 8 / 8, rel=1e-14)
    # degree 8 is not exact any more: ∫₀³ x⁸ dx = 3⁹ / 9 = 2187
    assert abs(np.dot(w, x ** 8) - 3 ** 9 / 9) > 1e-6


def test_mean_and_rms_of_a_sine_over_a_period():
    # over one period: mean of sin = 0, RMS = 1/√2
    x, w = gauss_legendre(np.linspace(0, 2 * np.pi, 73))
    mean, rms = mean_rms(w, np.sin(x), 2 * np.pi)
    assert mean == pytest.approx(0.0, abs=1e-14)
    assert rms == pytest.approx(1 / math.sqrt(2), rel=1e-12)


def test_the_former_name_is_the_same_module():
    """``mechcli.core.refine`` (the name before issue 32 §5) is :mod:`mechcli.core.numerics`
    itself, so a monkeypatch on one is seen through the other."""
    import mechcli.core.numerics
    import mechcli.core.refine
    from mechcli.core.refine import bisect as former
    assert mechcli.core.refine is mechcli.core.numerics
    assert former is bisect
