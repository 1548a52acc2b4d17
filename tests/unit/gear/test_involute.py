"""The involute function, its inverse and the DMS output (eq. 5-1 … 5-4, 【例 5-1】, 【例 5-2】)."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from mechcli.core.errors import ConvergenceError
from mechcli.core.gear.involute import (degrees_minutes_seconds, format_dms, involute_curve,
                                   involute_function, involute_table, inverse_involute)


def _inv_longdouble(alpha):
    a = np.asarray(alpha, dtype=np.longdouble)
    return np.tan(a) - a


def test_exact_values():
    assert involute_function(math.pi / 4) == pytest.approx(1 - math.pi / 4, rel=1e-15)
    assert involute_function(math.pi / 3) == pytest.approx(math.sqrt(3) - math.pi / 3, rel=1e-15)
    assert involute_function(0.0) == 0.0


def test_against_extended_precision():
    # long double has 64 mantissa bits: tan(a) - a keeps ~1e-16 relative for a >= 0.05
    a = np.linspace(0.05, 1.5, 3001)
    ref = _inv_longdouble(a).astype(float)
    assert_allclose(involute_function(a), ref, rtol=2e-15, atol=0)  # tan(a) - a cancels above 0.5


def test_tiny_angles_against_series():
    # independent: three terms of tan(a) - a, truncation below 1e-19 relative for a <= 1e-3
    a = np.logspace(-8, -3, 200)
    ref = a ** 3 / 3 + 2 * a ** 5 / 15 + 17 * a ** 7 / 315
    assert_allclose(involute_function(a), ref, rtol=1e-15, atol=0)


def test_series_switch_is_seamless():
    a = np.array([0.5 - 1e-12, 0.5, 0.5 + 1e-12])
    v = involute_function(a)
    assert np.all(np.diff(v) > 0)
    assert_allclose(v, _inv_longdouble(a).astype(float), rtol=2e-15)


def test_table_5_1_layout_and_values():
    rows, ang, inv = involute_table(10, 30, 0.1, 10)
    assert inv.shape == (21, 10)
    assert_allclose(rows, np.arange(10, 31))
    assert ang[10, 3] == pytest.approx(20.3, abs=1e-12)
    # a few printed values of 表 5-1 (4 decimals)
    assert round(inv[0, 0], 4) == 0.0018
    assert round(inv[10, 0], 4) == 0.0149
    assert round(inv[20, 9], 4) == 0.0592


def test_curve_polar_and_cartesian():
    rb = 0.05
    alpha = np.radians([0.0, 20.0, 40.0])
    r, th, x, y = involute_curve(rb, alpha)
    assert_allclose(r, rb / np.cos(alpha))
    assert_allclose(np.hypot(x, y), r)
    assert_allclose(np.arctan2(x, y), th, atol=1e-16)
    # the involute's defining property: arc length of the unwrapped string = rb * roll angle
    assert_allclose(np.sqrt(r ** 2 - rb ** 2), rb * (th + alpha), rtol=1e-14)


def test_example_5_2_auto_and_book():
    auto = inverse_involute(0.02)
    book = inverse_involute(0.02, method="book")
    assert round(float(auto.alpha[0]), 7) == 0.3836426
    assert round(float(book.alpha[0]), 7) == 0.3836426
    assert auto.iterations[0] <= 4
    assert format_dms(auto.alpha[0]) == "21°58′51″"           # the book floors the seconds
    assert format_dms(auto.alpha[0], rounding="round") == "21°58′52″"
    d, m, s = degrees_minutes_seconds(auto.alpha[0], 2)
    assert (d, m, s) == (21, 58, 51.96)


def test_dms_round_carries():
    assert format_dms(math.radians(29.99999999), rounding="round") == "30°0′0″"


# Newton steps after the series/asymptotic start of method "auto" (docstring: at most 4),
# measured 2026-11-23: one step for small θ where the series start is already close
@pytest.mark.parametrize("theta, steps", [(1e-12, 1), (1e-9, 1), (1e-6, 1), (1e-3, 1),
                                          (0.02, 2), (0.3, 3), (0.5, 4), (1.0, 3)])
def test_inverse_accuracy(theta, steps):
    res = inverse_involute(theta)
    assert abs(res.residual[0]) <= 1e-14 * theta
    # the independent forward function reproduces theta from the returned angle
    assert involute_function(res.alpha[0]) == pytest.approx(theta, rel=1e-13)
    assert res.iterations[0] == steps


def test_round_trip_whole_range():
    theta = np.logspace(-12, 0, 4001)
    res = inverse_involute(theta)
    assert np.max(res.relative_residual) < 1e-14
    assert res.iterations.max() <= 4


def test_inverse_recovers_angle():
    alpha = np.linspace(0.02, 1.3, 500)
    theta = _inv_longdouble(alpha).astype(float)
    # condition number theta / (alpha tan^2 alpha) < 1/3: alpha errs no more than theta's rounding
    assert_allclose(inverse_involute(theta).alpha, alpha, rtol=5e-16)


def test_extremes_stay_finite():
    res = inverse_involute([0.0, 5e-324, 1e-300, 1e6, 1e300])
    assert np.all(np.isfinite(res.alpha))
    assert res.alpha[0] == 0.0
    assert 0 < res.alpha[2] < 1e-99
    assert res.alpha[3] == pytest.approx(math.atan(1e6 + math.pi / 2 - 1e-6), abs=1e-15)
    assert res.alpha[4] < math.pi / 2


def test_book_method_failure_region():
    # first step passes pi/2 above theta = inv(0.8) + (pi/2 - 0.8) tan^2(0.8) = 1.0467
    limit = involute_function(0.8) + (math.pi / 2 - 0.8) * math.tan(0.8) ** 2
    assert limit == pytest.approx(1.0468, abs=1e-4)
    inverse_involute(limit - 1e-3, method="book")
    with pytest.raises(ConvergenceError):
        inverse_involute(limit + 1e-3, method="book")
    # the absolute stop |f| < 1e-7 is useless for small theta
    assert inverse_involute(1e-9, method="book").relative_residual[0] > 1
    assert inverse_involute(1e-6, method="book").relative_residual[0] > 1e-5
    assert inverse_involute(1e-3, method="book").relative_residual[0] < 1e-12


def test_bad_input():
    with pytest.raises(ValueError):
        inverse_involute(-1e-3)
    with pytest.raises(ValueError):
        inverse_involute(float("nan"))
