"""Property tests of function generation: a linkage's own corresponding positions,
fed back, give back that linkage (Freudenstein four-bar, slider-crank, rocker-slider)."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechcli.core.linkage import DriverMotion, four_bar, slider_crank, solve
from mechcli.core.synth.function import freudenstein, rocker_slider, slider_crank_function

length = st.floats(0.2, 5.0, allow_nan=False)
scale = st.sampled_from([1e-3, 1.0, 1e3])
angle = st.floats(-math.pi, math.pi, allow_nan=False)
#: two steps between three input angles: distinct points, less than a turn in all
gaps = st.lists(st.floats(0.3, 2.0), min_size=2, max_size=2)


def well_conditioned(t1, t3):
    """Eq. (3-34)'s 3×3 matrix with α0 = φ0 = 0 far from singular, so that the
    recovered ratios carry ~1e-12 relative round-off, well inside 1e-9."""
    A = np.stack([np.cos(t3), np.cos(t3 - t1), np.ones(3)], axis=-1)
    s = np.linalg.svd(A, compute_uv=False)
    return s[-1] > 1e-2 * s[0]


@settings(max_examples=80, deadline=None)
@given(length, length, st.floats(0.05, 0.6), st.floats(0.05, 0.95), scale,
       st.sampled_from([1, -1]), angle, gaps)
def test_four_bar_points_give_back_its_ratios(c, d, frac, t, k, branch, q0, gap):
    # a crank-rocker assembles at every crank angle: the crank a shortest and
    # |d - c| + a < b < c + d - a, which is Grashof's a + longest < sum of the other two
    c, d = c * k, d * k
    a = frac * min(c, d)
    lo, hi = abs(d - c) + a, c + d - a
    b = lo + t * (hi - lo)
    q = q0 + np.cumsum([0.0] + gap)
    m = solve(four_bar(a, b, c, d, branch=branch), {1: DriverMotion(q)}, order=0)
    assume(m.regular.all())
    assume(np.all(m.conditions[-1].sin_gamma > 0.05))    # away from a toggle
    t3 = m.links[3].theta
    assume(well_conditioned(q, t3))
    design = freudenstein(q, t3, crank=a)
    v = design.values
    np.testing.assert_allclose([v["l"], v["m"], v["n"]], np.array([b, c, d]) / a, rtol=1e-9)
    assert (v["alpha0"], v["phi0"]) == (0.0, 0.0)        # the frame already lies on +x
    assert list(v["branches"]) == [branch] * 3
    back = solve(design.linkage, {1: DriverMotion(design.inputs)}, order=0)
    assert back.feasible.all()
    assert np.max(np.abs(np.angle(np.exp(1j * (back.links[3].theta - t3))))) <= 1e-9


@settings(max_examples=80, deadline=None)
@given(length, length, st.floats(-2.0, 2.0), scale, st.sampled_from([1, -1]), angle, gaps)
def test_slider_crank_points_give_back_its_lengths(l1, extra, e, k, branch, q0, gap):
    # a rod longer than crank plus offset: the crank turns fully, no toggle
    l1, l2, e = l1 * k, (l1 + abs(e) + extra) * k, e * k
    q = q0 + np.cumsum([0.0] + gap)
    m = solve(slider_crank(l1, l2, e, branch=branch), {1: DriverMotion(q)}, order=0)
    assume(m.regular.all())
    assume(np.all(m.conditions[-1].sin_gamma > 0.05))    # away from a toggle
    s = m.slides["3"].s
    # the 3×3 system [s cos θ, sin θ, 1] well conditioned (else 1e-9 is not reachable)
    A = np.stack([s * np.cos(q) / k, np.sin(q), np.ones(3)], axis=-1)
    sv = np.linalg.svd(A, compute_uv=False)
    assume(sv[-1] > 1e-2 * sv[0])
    d = slider_crank_function(q, s)
    np.testing.assert_allclose([d.lengths["l1"], d.lengths["l2"]], [l1, l2], rtol=1e-9)
    assert abs(d.lengths["e"] - e) <= 1e-9 * k
    assert list(d.values["branches"]) == [branch] * 3
    back = solve(d.linkage, {1: DriverMotion(d.inputs)}, order=0)
    np.testing.assert_allclose(back.slides["3"].s, s, rtol=0, atol=1e-9 * k)


@settings(max_examples=80, deadline=None)
@given(length, length, st.floats(-2.0, 2.0), angle, scale, st.sampled_from([1, -1]), angle,
       gaps)
def test_rocker_slider_finds_the_pin_on_the_rocker(r, extra, e, delta, k, branch, q0, gap):
    # a slider-crank whose crank is a rocker with its pin at δ from a line marked on it
    # (a rod longer than rocker plus offset: it assembles everywhere)
    r, rod, e = r * k, (r + abs(e) + extra) * k, e * k
    phi = q0 + np.cumsum([0.0] + gap)
    m = solve(slider_crank(r, rod, e, branch=branch), {1: DriverMotion(phi + delta)}, order=0)
    assume(m.regular.all())
    assume(np.all(m.conditions[-1].sin_gamma > 0.05))    # away from a toggle
    s = m.slides["3"].s
    c, sn = np.cos(phi), np.sin(phi)
    A = np.stack([(s * c + e * sn) / k, (e * c - s * sn) / k, np.ones(3)], axis=-1)
    sv = np.linalg.svd(A, compute_uv=False)
    assume(sv[-1] > 1e-2 * sv[0])
    d = rocker_slider(phi, s, e=e)
    np.testing.assert_allclose([d.lengths["l1"], d.lengths["l2"]], [r, rod], rtol=1e-9)
    assert abs(np.angle(np.exp(1j * (d.values["delta"] - delta)))) <= 1e-9
    assert list(d.values["branches"]) == [branch] * 3
