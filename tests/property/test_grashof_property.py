"""Property tests of the four-bar classification and figures of merit at the extremes."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mechcli.core.grashof import fourbar as gf

length = st.floats(1.0, 100.0, allow_nan=False)
scale = st.sampled_from([1e-3, 1e-1, 1.0, 1e3, 1e6])


def closes(L):
    return max(L) < sum(L) - max(L)


@settings(max_examples=200, deadline=None)
@given(st.lists(length, min_size=4, max_size=4), scale)
def test_type_and_angles_do_not_depend_on_scale(L, s):
    if not closes(L):
        return
    a = gf.analyse_fourbar(L)
    b = gf.analyse_fourbar([x * s for x in L])
    assert a.klass.types == b.klass.types
    for name in ("theta", "psi", "K", "gamma_min", "gamma_max", "gamma0", "gamma180"):
        x, y = getattr(a.merit, name), getattr(b.merit, name)
        assert np.all(np.isfinite(y))
        # at a change point (s + l = p + q) an angle that is 0 or π in exact arithmetic
        # moves by sqrt(round-off of the lengths) ~ 1e-8 rad: the problem's own
        # sensitivity (γ ~ sqrt(δl)), not the formula's
        assert np.allclose(x, y, rtol=1e-9, atol=1e-6), name


@settings(max_examples=200, deadline=None)
@given(st.lists(length, min_size=4, max_size=4))
def test_inversions_of_a_grashof_chain(L):
    if not closes(L):
        return
    types = sorted(k.types[0] for k in gf.classify_inversions(L))
    kl = gf.classify_fourbar(L)
    if kl.change_point[0] or len(set(L)) < 4:
        return
    if kl.grashof[0]:
        assert types == ["crank_rocker", "crank_rocker", "double_crank", "double_rocker"]
    else:
        assert types == ["double_rocker"] * 4


@settings(max_examples=300, deadline=None)
@given(st.lists(length, min_size=4, max_size=4), st.integers(1, 4), st.booleans())
def test_merit_is_finite_and_consistent(L, frame, first):
    if not closes(L):
        return
    inp = (frame % 4) + 1 if first else ((frame + 2) % 4) + 1
    m = gf.analyse_fourbar(L, frame=frame, input_link=inp).merit
    for f in ("theta", "psi", "K", "gamma_min", "gamma_max", "input_lo", "input_hi"):
        assert np.all(np.isfinite(getattr(m, f)))
    assert 0 <= m.gamma_min[0] <= m.gamma_max[0] <= math.pi / 2 + 1e-15
    if m.has_limits[0]:
        assert m.K[0] >= 1.0
        assert math.isclose(m.K[0], (math.pi + m.theta[0]) / (math.pi - m.theta[0]))
        assert 0 < m.psi[0] < math.pi


@settings(max_examples=200, deadline=None)
@given(st.floats(1, 10), st.floats(1, 10), st.floats(1, 10), st.floats(-1e-6, 1e-6))
def test_near_the_change_point_either_side_is_consistent(s, p, q, rel):
    """s + l = p + q (1 + rel): Grashof iff rel <= tol, the merit stays finite."""
    s, p, q = sorted([s, p, q])
    lng = (p + q - s) * (1 + rel)
    if not lng >= q or not closes([s, p, q, lng]):
        return
    L = [s, p, q, lng]
    an = gf.analyse_fourbar(L)
    excess = s + lng - p - q
    assert an.klass.grashof[0] == (excess <= 1e-9 * (s + lng))
    assert np.all(np.isfinite(an.merit.gamma_min)) and np.all(np.isfinite(an.merit.K))


@settings(max_examples=200, deadline=None)
@given(st.floats(1, 100), st.floats(1, 400), st.floats(-100, 100))
def test_slider_crank(a, b, e):
    if abs(e) >= a + b:
        return
    sc = gf.analyse_slider_crank(a, b, e)
    assert sc.crank_exists == (a + abs(e) <= b * (1 + 1e-12) or sc.boundary)
    if sc.crank_exists:
        assert sc.stroke >= 2 * a * (1 - 1e-12)
        assert sc.K >= 1 and math.isfinite(sc.K)
        if e == 0:
            assert math.isclose(sc.stroke, 2 * a) and sc.theta == 0


@settings(max_examples=200, deadline=None)
@given(st.lists(length, min_size=5, max_size=5), st.integers(1, 5), scale)
def test_fivebar_class_follows_the_links_not_their_numbers(L, frame, s):
    """Renumbering the loop so that the frame is link 5 changes nothing but the labels."""
    from mechcli.core.grashof.fivebar import classify_fivebar

    if not closes(L):
        return
    a = classify_fivebar(L, frame=frame)
    shift = frame % 5            # new link k is old link (k + shift - 1) % 5 + 1
    rolled = [L[(k + shift - 1) % 5] * s for k in range(1, 6)]
    b = classify_fivebar(rolled, frame=5)
    assert a.types == b.types and a.klass[0] == b.klass[0]
    assert a.inputs_independent[0] == b.inputs_independent[0]
    relabel = sorted((c - shift - 1) % 5 + 1 for c in a.cranks())
    assert relabel == b.cranks()
