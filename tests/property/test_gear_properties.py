"""Gear geometry at the extremes: z = 5 … 400, x = -1 … 1, alpha = 14.5° … 30°, a' at the edge
of feasibility, and the inverse involute for tiny and large theta.  Every case is either
accurate or a clear UnsolvableError — never NaN."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechcli.core.gear.spur import GearGeometryError, spur_gear
from mechcli.core.gear.pair import MeshError, gear_pair
from mechcli.core.gear.profile import gear_outline, generated_tooth
from mechcli.core.gear.involute import involute_function, inverse_involute

teeth = st.integers(5, 400)
shift = st.floats(-1.0, 1.0)
angle = st.floats(14.5, 30.0).map(math.radians)
SET = settings(max_examples=60, deadline=None)


@SET
@given(st.floats(1e-12, 1.0))
def test_round_trip_relative_1e14(theta):
    res = inverse_involute(theta)
    assert abs(res.residual[0]) <= 1e-14 * theta
    assert res.iterations[0] <= 4


@SET
@given(st.floats(1e-300, 1e-12))
def test_tiny_theta(theta):
    a = inverse_involute(theta).alpha[0]
    # inv(a) = a^3/3 (1 + 2a^2/5 + ...): the cube-root law holds to rounding
    assert math.isclose(a, (3 * theta) ** (1 / 3), rel_tol=1e-8)
    assert math.isclose(involute_function(a), theta, rel_tol=1e-14)


@SET
@given(st.floats(1.0, 1e8))
def test_large_theta(theta):
    res = inverse_involute(theta)
    a = res.alpha[0]
    assert 0 < a < math.pi / 2
    # forward condition number is alpha tan^2(alpha) / theta ~ alpha theta: residual within it
    assert abs(res.residual[0]) <= 8 * np.finfo(float).eps * a * math.tan(a) ** 2 + 1e-15 * theta


@SET
@given(teeth, shift, angle)
def test_spur_gear_is_finite_or_refused(z, x, alpha):
    try:
        g = spur_gear(z, 0.004, alpha, x=x)
        tooth = generated_tooth(g)
    except GearGeometryError:
        return
    assert math.isclose(g.tooth_thickness(g.r), g.s, rel_tol=1e-12)
    assert g.rf < tooth.r_form <= tooth.r_top <= g.ra * (1 + 1e-12)
    assert 0.0 <= tooth.undercut_fraction <= 1.0
    out = gear_outline(tooth, 12)
    assert np.all(np.isfinite(out.x)) and np.all(np.isfinite(out.y))
    r = np.hypot(out.x, out.y)
    assert r.min() >= g.rf * (1 - 1e-12) and r.max() <= g.ra * (1 + 1e-12)
    # generated undercut only where the sharp cutter corner passes the tangent point N
    corner = (g.ha_star + g.c_star - g.x) * g.m
    assert tooth.undercut == (corner > g.r * math.sin(alpha) ** 2)


@SET
@given(teeth, teeth, shift, shift, angle, st.floats(0.0, 1.0))
def test_pair_at_the_edge_of_feasibility(z1, z2, x1, x2, alpha, stretch):
    try:
        g1 = spur_gear(z1, 0.002, alpha, x=x1)
        g2 = spur_gear(z2, 0.002, alpha, x=x2)
        tight = gear_pair(g1, g2)
    except (GearGeometryError, MeshError):
        return
    # zero backlash exactly at the zero-backlash distance; base pitches equal
    assert abs(tight.backlash) <= 1e-12 * g1.p
    assert g1.pb == g2.pb or math.isclose(g1.pb, g2.pb, rel_tol=1e-15)
    # just below it the teeth jam
    try:
        gear_pair(g1, g2, a_w=tight.a_w * (1 - 1e-9))
        raise AssertionError("a' below the zero-backlash distance was accepted")
    except MeshError:
        pass
    # anywhere between tight and the last contact: finite epsilon, or a clear refusal
    a_w = tight.a_w + stretch * (g1.ra + g2.ra - tight.a_w)
    assume(a_w > tight.a_w)
    try:
        pr = gear_pair(g1, g2, a_w=a_w)
    except MeshError as exc:
        assert "no contact" in str(exc)
        return
    assert 0 < pr.epsilon_alpha < 10 and math.isfinite(pr.backlash)
    # the backlash grows from 0 at the tight distance: positive once a' is beyond it by
    # more than the rounding of the involute functions (hypothesis found a' = tight + 1 ulp,
    # where it rounds to 0.0)
    assert pr.backlash >= -1e-12 * g1.p
    if a_w - tight.a_w > 1e-9 * tight.a_w:
        assert pr.backlash > 0


@SET
@given(st.integers(5, 120), st.integers(1, 200), shift, shift, angle, st.floats(0.0, 1.0))
def test_internal_pair_edges(z1, extra, x1, x2, alpha, pull):
    try:
        g1 = spur_gear(z1, 0.002, alpha, x=x1)
        g2 = spur_gear(z1 + extra, 0.002, alpha, x=x2, internal=True)
        tight = gear_pair(g1, g2)
    except (GearGeometryError, MeshError):
        return
    assert abs(tight.backlash) <= 1e-12 * g1.p
    # towards the ring centre the backlash opens; epsilon stays finite or the mesh is refused
    lo = tight.a * math.cos(alpha)
    a_w = tight.a_w - pull * (tight.a_w - lo) * 0.999
    try:
        pr = gear_pair(g1, g2, a_w=a_w)
    except MeshError as exc:
        assert "no contact" in str(exc)
        return
    assert math.isfinite(pr.epsilon_alpha) and pr.backlash >= -1e-12 * g1.p


@SET
@given(st.integers(5, 40), angle, st.floats(-1e-6, 1e-6))
def test_undercut_threshold_is_continuous(z, alpha, dx):
    # the sharp cutter corner passes N exactly at x = ha* + c* - z sin^2(alpha) / 2
    x = 1.25 - z * math.sin(alpha) ** 2 / 2 + dx
    assume(-1.5 <= x <= 1.5)
    try:
        tooth = generated_tooth(spur_gear(z, 0.004, alpha, x=x))
    except GearGeometryError:
        return
    assert tooth.undercut_fraction < 1e-4
    assert abs(tooth.r_form - tooth.gear.rb) < 1e-6 * tooth.gear.rb
