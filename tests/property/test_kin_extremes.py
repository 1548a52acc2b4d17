"""Property tests at the extremes: every result is finite and accurate, or a clear error."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechcli.core.errors import AssemblyError
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities
from mechcli.core.linkage import RPR, RRR, Crank, DriverMotion, Ground, Linkage, solve

SETTINGS = settings(max_examples=40, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])
Q = np.radians(np.linspace(0.0, 360.0, 361))


def fourbar(l1, l2, l3, l4, branch=1):
    return Linkage(4, (Ground("A", 0, 0), Ground("D", l4, 0), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, branch)))


def analyse(lk, q=Q, partial=False, omega=1.0):
    qs = default_quantities(lk, 2)
    return analyse_sweep(lk, Sweep(1, q, omega, 0.0, {}, True), qs, 2, partial=partial), qs


def all_finite(res):
    vals = [v for v in res.values.values()] + [res.q]
    ext = [e.value for pair in res.extremes.values() for e in pair]
    return all(np.isfinite(v).all() for v in vals) and np.isfinite(ext).all()


@SETTINGS
@given(scale=st.floats(1e-6, 1e3),  # metres: 1e-3 mm ... 1e6 mm
       ratios=st.tuples(st.floats(2.2, 4.0), st.floats(2.0, 4.0), st.floats(2.5, 4.0)))
def test_crank_rocker_at_any_scale_is_finite_and_closes(scale, ratios):
    b, c, d = ratios
    l1, l2, l3, l4 = scale, b * scale, c * scale, d * scale
    if not (l1 + max(l2, l3, l4) < (sum((l2, l3, l4)) - max(l2, l3, l4)) * (1 - 1e-9)):
        # not Grashof with the crank shortest -- or a change point to round-off (e.g. ratios
        # 4, 2.5, 2.5: s + l = p + q, dead points at 0°, a clear error by design)
        return
    res, _ = analyse(fourbar(l1, l2, l3, l4))
    assert all_finite(res)
    C, B = res.motion.points["C"].p, res.motion.points["B"].p
    assert np.max(np.abs(np.abs(C - B) - l2)) <= 1e-9 * l4 * 4
    # the refined extremes bound the sampled values and sit where omega3 = 0
    hi, lo = res.extremes["theta3"]
    assert hi.value >= res.values["theta3"].max() - 1e-12
    assert lo.value <= res.values["theta3"].min() + 1e-12
    m = solve(fourbar(l1, l2, l3, l4), {1: DriverMotion(np.array([hi.at, lo.at]), 1.0)}, order=1)
    assert np.max(np.abs(m.links[3].omega)) <= 1e-6 * max(1.0, np.max(np.abs(res.values["omega3"])))


@SETTINGS
@given(delta=st.floats(-1e-3, 1e-3), frac=st.floats(0.1, 0.9))
def test_near_change_point_is_finite_or_a_clear_error(delta, frac):
    # s + l = p + q (1 + delta): the Grashof boundary, with a singular position at delta = 0
    l1, l4 = 1.0, 3.0
    rest = (l1 + l4) * (1 + delta)
    l2, l3 = frac * rest, (1 - frac) * rest
    if min(l2, l3) <= l1 or max(l2, l3) >= l4:
        l2, l3 = 2.0 * (1 + delta), 2.0 * (1 + delta)
    try:
        res, _ = analyse(fourbar(l1, l2, l3, l4))
    except AssemblyError as exc:
        assert exc.intervals and {r for _a, _b, r in exc.intervals} <= {"dead point",
                                                                         "cannot assemble"}
        assert all(np.isfinite([a, b]).all() for a, b, _ in exc.intervals)
        return
    assert all_finite(res)


@SETTINGS
@given(gap=st.floats(1e-9, 0.2))
def test_near_toggle_partial_range_reports_refined_dead_points(gap):
    # a double rocker driven by link 1: the crank cannot turn fully
    lk = fourbar(2.0, 1.0, 2.5 - gap, 2.2)
    with pytest.raises(AssemblyError) as exc:
        analyse(lk)
    assert exc.value.intervals
    res, _ = analyse(lk, partial=True)
    assert all_finite(res)
    # at every refined boundary the dyad is (numerically) at its toggle: links collinear
    for start, stop, _ in res.excluded:
        for b in (start, stop):
            if 1e-9 < b < 2 * math.pi - 1e-9:
                m = solve(lk, {1: DriverMotion(np.array([b]), 1.0)}, order=0)
                assert m.feasible[0]
                assert m.conditions[0].sin_gamma[0] < 1e-5


@SETTINGS
@given(rel=st.floats(-0.05, 0.05))
def test_guide_bar_oscillating_rotating_boundary(rel):
    l4 = 1.0
    l1 = l4 * (1 + rel)
    lk = Linkage(4, (Ground("C", 0, 0), Ground("A", 0, l4), Crank(1, "A", "B", l1),
                     RPR("B", 2, "C", 3)))
    try:
        res, _ = analyse(lk)
    except AssemblyError as exc:
        # only a dead point (B through C) can stop it, and only at l1 == l4
        assert "dead point" in str(exc)
        return
    assert all_finite(res)
    swing = res.extremes["theta3"][0].value - res.extremes["theta3"][1].value
    if rel < -1e-6:      # oscillating: psi = 2 asin(l1/l4)
        assert swing == pytest.approx(2 * math.asin(l1 / l4), rel=1e-6)
    elif rel > 1e-6:     # rotating guide: it turns a full revolution
        assert swing == pytest.approx(2 * math.pi, rel=1e-6)


def test_exactly_at_the_guide_bar_boundary_is_a_clear_error():
    lk = Linkage(4, (Ground("C", 0, 0), Ground("A", 0, 1.0), Crank(1, "A", "B", 1.0),
                     RPR("B", 2, "C", 3)))
    with pytest.raises(AssemblyError) as exc:
        analyse(lk)
    # the block passes the guide's pivot at θ1 = 270°: a dead point there
    assert any(r == "dead point" and math.degrees(a) <= 270.0 + 1e-6 and
               math.degrees(b) >= 270.0 - 1e-6 for a, b, r in exc.value.intervals)
