"""Property tests of the designs from the time ratio K (mechcli.core.synth.quick_return).

Every random feasible problem is designed, and the Grashof core, fed the
designed lengths, must give back K and ψ (or the stroke H) to 1e-9 relative,
and the condition that fixed the design.  Round trips start from a random
crank-rocker: its K and ψ (and one length, or one limit position) must design
it again.
"""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechcli.core.errors import DescribedError
from mechcli.core.grashof.fourbar import (analyse_fourbar, analyse_guide_bar,
                                          analyse_slider_crank)
from mechcli.core.synth.quick_return import (crank_rocker_from_K,
                                             crank_rocker_from_K_limit_angle,
                                             guide_bar_from_K, pivot_circle,
                                             slider_crank_from_K, slider_crank_stroke_from_K,
                                             time_ratio)

RTOL = 1e-9
unit = st.floats(0.0, 1.0)
inner = st.floats(0.05, 0.95)          # away from the change points at the ends of a range
scale = st.sampled_from([1e-3, 0.29, 1.0, 1e3])


def core(design):
    L = design.lengths
    an = analyse_fourbar([L["l1"], L["l2"], L["l3"], L["l4"]])
    return an.klass.types[0], an.merit


@st.composite
def crank_rocker_problem(draw):
    """ψ in [5°, 170°], θ in (1°, 90° + ψ/2 − 2°): a feasible K (pivot_circle)."""
    psi = math.radians(draw(st.floats(5.0, 170.0)))
    th_max = math.pi / 2 + psi / 2 - math.radians(2)
    theta = math.radians(1.0) + draw(unit) * (min(th_max, math.radians(170)) - math.radians(1))
    return time_ratio(theta), draw(scale), psi


@settings(max_examples=150, deadline=None)
@given(crank_rocker_problem(), st.sampled_from(["crank", "coupler", "frame"]), inner,
       st.sampled_from(["best", "left", "right"]))
def test_length_condition_reproduces_K_psi(problem, key, f, branch):
    K, l3, psi = problem
    circle = pivot_circle(K, l3, psi)
    lo, hi = getattr(circle, key)
    value = lo + f * (hi - lo)
    d = crank_rocker_from_K(K, l3, psi, branch=branch, **{key: value})
    kind, m = core(d)
    assert kind == "crank_rocker"
    assert m.K[0] == pytest.approx(K, rel=RTOL)
    assert m.psi[0] == pytest.approx(psi, rel=RTOL)
    assert d.lengths[{"crank": "l1", "coupler": "l2", "frame": "l4"}[key]] == \
        pytest.approx(value, rel=1e-9)
    assert d.values["gamma_min"] == pytest.approx(float(m.gamma_min[0]), rel=1e-12)
    # A sees C1C2 under θ and lies on L
    A, C1, C2 = (np.array(d.pivots[k]) for k in ("A", "C1", "C2"))
    u, v = C1 - A, C2 - A
    ang = math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u @ v)
    assert ang == pytest.approx(d.values["theta"], rel=1e-9)


@settings(max_examples=100, deadline=None)
@given(crank_rocker_problem(), inner, st.floats(0.0, math.pi))
def test_pivot_line_through_a_usable_point(problem, f, direction):
    """A line through a point of the usable arc: the design puts A on the line."""
    K, l3, psi = problem
    circle = pivot_circle(K, l3, psi)
    lo, hi = circle.crank
    delta = math.asin((lo + f * (hi - lo)) / (2 * circle.R * math.sin(circle.theta / 2)))
    P = circle.from_delta(delta)
    n = np.array([math.cos(direction), math.sin(direction)])
    line = (n[0], n[1], float(n @ P))
    d = crank_rocker_from_K(K, l3, psi, pivot_line=line)
    A = np.array(d.pivots["A"])
    assert abs(n @ A - line[2]) <= 1e-9 * l3
    kind, m = core(d)
    assert kind in ("crank_rocker", "change_point_crank_rocker")
    # the other intersection may be near a change point: K and ψ stay exact
    assert m.K[0] == pytest.approx(K, rel=RTOL)
    assert m.psi[0] == pytest.approx(psi, rel=RTOL)


@settings(max_examples=150, deadline=None)
@given(st.floats(0.05, 0.9), st.floats(1.1, 3.0), st.floats(1.1, 3.0), scale)
def test_round_trip_from_a_crank_rocker(a_rel, b_rel, c_rel, s):
    """A random crank-rocker (crank shortest, Grashof with a margin): its K, ψ and
    one length design it again (the other lengths to 1e-7)."""
    a, b, c = a_rel, b_rel, c_rel
    # frame d with a + max <= others − margin, any order of b, c, d
    d_lo = max(abs(b - c) + a, a) + 0.05
    d_hi = b + c - a - 0.05
    assume(d_lo < d_hi)
    d = (d_lo + d_hi) / 2
    # l4 = l3 puts D at the centre of L: every A is l3 from D and the frame fixes none
    assume(abs(d - c) > 0.02 * c)
    L = np.array([a, b, c, d]) * s
    an = analyse_fourbar(L)
    assume(an.klass.types[0] == "crank_rocker")
    m = an.merit
    K, psi = float(m.K[0]), float(m.psi[0])
    assume(K > 1 + 1e-6 and psi > 1e-3)
    for key, i in (("crank", 0), ("coupler", 1), ("frame", 3)):
        des = crank_rocker_from_K(K, L[2], psi, **{key: L[i]})
        got = [des.lengths[k] for k in ("l1", "l2", "l3", "l4")]
        np.testing.assert_allclose(got, L, rtol=1e-7)


@settings(max_examples=150, deadline=None)
@given(st.floats(0.05, 0.9), st.floats(1.1, 3.0), st.floats(1.1, 3.0), scale,
       st.sampled_from(["extended", "folded"]))
def test_round_trip_limit_angle(a_rel, b_rel, c_rel, s, limit):
    """习题 3-15's design: a random crank-rocker's K, frame, rocker and the angle of
    one limit position design a crank-rocker with that K and limit position (the
    same one, or the other of the family)."""
    a, b, c = a_rel, b_rel, c_rel
    d_lo = max(abs(b - c) + a, a) + 0.05
    d_hi = b + c - a - 0.05
    assume(d_lo < d_hi)
    L = np.array([a, b, c, (d_lo + d_hi) / 2]) * s
    an = analyse_fourbar(L)
    assume(an.klass.types[0] == "crank_rocker")
    m = an.merit
    K = float(m.K[0])
    assume(K > 1 + 1e-6)
    th3 = float(m.theta3_ext[0] if limit == "extended" else m.theta3_fold[0])
    des = crank_rocker_from_K_limit_angle(K, L[2], L[3], math.pi - th3, limit=limit)
    kind, m2 = core(des)
    assert kind == "crank_rocker"
    assert m2.K[0] == pytest.approx(K, rel=RTOL)
    got = m2.theta3_ext[0] if limit == "extended" else m2.theta3_fold[0]
    assert got == pytest.approx(th3, rel=1e-9)
    assert des.lengths["l3"] == pytest.approx(L[2]) and des.lengths["l4"] == L[3]


@settings(max_examples=150, deadline=None)
@given(st.floats(0.5, 89.0), scale, st.floats(0.01, 0.99), st.booleans())
def test_slider_crank_reproduces_K_and_H(theta_deg, H, f, negative):
    """e up to 0.99 e_max: at e_max (a + e = b) the folded position has
    x = sqrt((b − a)² − e²) = 0, where θ moves by sqrt(round-off) ~ 1e-8."""
    theta = math.radians(theta_deg)
    K = time_ratio(theta)
    e = f * H / math.tan(theta) * (-1 if negative else 1)
    d = slider_crank_from_K(K, H, e)
    sc = analyse_slider_crank(d.lengths["l1"], d.lengths["l2"], d.lengths["e"])
    assert sc.crank_exists
    assert sc.K == pytest.approx(K, rel=RTOL)
    assert sc.stroke == pytest.approx(H, rel=RTOL)
    # the other design, from the crank and the coupler, gives back H and e
    back = slider_crank_stroke_from_K(K, d.lengths["l1"], d.lengths["l2"])
    assert back.lengths["H"] == pytest.approx(H, rel=1e-9)
    assert back.lengths["e"] == pytest.approx(abs(e), rel=1e-7)


@settings(max_examples=100, deadline=None)
@given(st.floats(0.5, 89.0), scale, st.floats(1.001, 1.5))
def test_slider_crank_offset_beyond_e_max_fails(theta_deg, H, f):
    theta = math.radians(theta_deg)
    e_max = H / math.tan(theta)
    with pytest.raises(DescribedError) as err:
        slider_crank_from_K(time_ratio(theta), H, f * e_max)
    assert err.value.reason == "offset"
    assert err.value.values["hi"] == pytest.approx(e_max, rel=1e-12)


@settings(max_examples=100, deadline=None)
@given(st.floats(1.01, 50.0), scale, st.booleans())
def test_guide_bar_reproduces_K_psi(K, s, by_frame):
    d = guide_bar_from_K(K, frame=s) if by_frame else guide_bar_from_K(K, crank=s)
    gb = analyse_guide_bar(d.lengths["l1"], d.lengths["l4"])
    assert gb.kind == "oscillating"
    assert gb.K == pytest.approx(K, rel=RTOL)
    assert gb.psi == pytest.approx(d.values["psi"], rel=RTOL)


@settings(max_examples=100, deadline=None)
@given(crank_rocker_problem(), st.sampled_from(["crank", "coupler", "frame"]),
       st.floats(0.05, 2.0), st.booleans())
def test_outside_the_range_fails_with_the_range(problem, key, f, below):
    K, l3, psi = problem
    circle = pivot_circle(K, l3, psi)
    lo, hi = getattr(circle, key)
    value = lo * (1 - f / 2.1) if below else hi * (1 + f)
    with pytest.raises(DescribedError) as err:
        crank_rocker_from_K(K, l3, psi, **{key: value})
    assert err.value.reason == f"{key}_range"
    assert (err.value.values["lo"], err.value.values["hi"]) == (lo, hi)
