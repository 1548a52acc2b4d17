"""The series moment arm of the piston effort (core.linkage.approximate.moment_arm)
against the textbook formulas written out here with plain ``math`` (hand derivation):
T ≈ F_P r (sin θ + sin 2θ / 2n), θ from the head-end dead centre, and its difference to
the exact arm r sin(θ + φ) / cos φ, r sin θ cos θ (1/n − 1/√(n² − sin²θ))."""

import math

import numpy as np
import pytest

from mechcli.core.linkage import approximate

R, L = 0.1, 0.4
N = L / R
DEGREES = np.arange(0.0, 361.0, 7.5)


def _book(deg):
    t = math.radians(deg)
    return R * (math.sin(t) + math.sin(2 * t) / (2 * N))


@pytest.mark.parametrize("branch, head", [(1, 0.0), (-1, 180.0)])
def test_moment_arm_is_the_books_formula_from_the_head_end(branch, head):
    arm = approximate.moment_arm(np.radians(DEGREES), R, L, branch)
    want = [_book(d - head) for d in DEGREES]
    np.testing.assert_allclose(arm, want, rtol=1e-13, atol=1e-16)
    # hand values (right branch): θ = 30°: 0.1 (0.5 + 0.8660254038/8); 90°: r
    if branch == 1:
        assert approximate.moment_arm(math.radians(30), R, L) == pytest.approx(0.06082531755,
                                                                             abs=1e-11)
        assert approximate.moment_arm(math.radians(90), R, L) == pytest.approx(R, abs=1e-16)


@pytest.mark.parametrize("branch", [1, -1])
def test_difference_to_the_exact_arm(branch):
    """series − exact (the exact arm from the exact closed form's ds/dθ, −b ds/dθ by
    virtual work) equals the difference written in a form of its own."""
    q = np.radians(DEGREES)
    head = 0.0 if branch == 1 else math.pi
    exact = -branch * approximate.exact(q, R, L, branch)[1]
    t = q - head
    s, c = np.sin(t), np.cos(t)
    np.testing.assert_allclose(exact, R * np.sin(t + np.arcsin(s / N)) / np.cos(np.arcsin(s / N)),
                               rtol=1e-13, atol=1e-16)
    diff = R * s * c * (1.0 / N - 1.0 / np.sqrt(N * N - s * s))
    np.testing.assert_allclose(approximate.moment_arm(q, R, L, branch) - exact, diff,
                               rtol=1e-9, atol=1e-16)


def test_series_inertia_hands_the_arm_on_only_when_asked():
    q = np.radians([30.0, 60.0])
    assert approximate.SeriesInertia(R, L, 1, 0.0, 0.0).arm(q) is None
    arm = approximate.SeriesInertia(R, L, 1, 0.0, 0.0, moment_arm="series").arm(q)
    np.testing.assert_allclose(arm, [_book(30.0), _book(60.0)], rtol=1e-13)
