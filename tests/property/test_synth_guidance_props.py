"""Guidance synthesis inverts the motion of a four-bar.

A random four-bar (pivots and lengths in a sane range, at scales from 1 mm to
1 km) is moved on the engine to three (or five) crank angles; its own positions
of B and C, or its own coupler poses, are fed back to the synthesis, which must
return the same pivots and lengths to 1e-9 relative (the data are exact, so only
round-off, amplified by the conditioning the strategies keep bounded, remains).
"""

import math

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.synth.guidance import (burmester_design, burmester_points, coupler_poses,
                                         moving_pivots, three_positions)

unit = st.floats(0.3, 1.0)
coord = st.floats(-1.0, 1.0)
angle = st.floats(-math.pi, math.pi)
scale = st.sampled_from([1e-3, 1.0, 1e3])
#: a random four-bar assembles at every drawn crank angle about one time in three
#: (and the well-conditioned ones less often): the filtering is expected
FILTERED = dict(deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
#: smallest turn between two positions of each link relative to another [rad]:
#: keeps three points on a circle at least this far apart, so the circumcentre's
#: condition stays below ~1/GAP² = 100
GAP = 0.1


def spread(a):
    """Smallest angular distance between any two of the angles."""
    a = np.asarray(a)
    d = np.abs(np.angle(np.exp(1j * (a[:, None] - a[None, :]))))
    return float(np.min(d[np.triu_indices(len(a), 1)]))


@st.composite
def fourbar_motion(draw, n):
    """(A, D, B, C, M, θ2, scale) of a four-bar at n crank angles: the fixed pivots,
    the positions of B, C and of a coupler point M, the coupler angle."""
    s = draw(scale)
    A = complex(draw(coord), draw(coord)) * s
    l1, l2, l3, l4 = (draw(unit) * s for _ in range(4))
    # not a change-point linkage (s + l = p + q: a rhombus folds, C can sit on A)
    L = sorted((l1, l2, l3, l4))
    assume(abs(L[0] + L[3] - L[1] - L[2]) >= 0.02 * s)
    D = A + l4 * np.exp(1j * draw(angle))
    mrel = complex(draw(coord), draw(coord)) * s          # M in link 2's frame, from B
    th0 = draw(angle)
    steps = [draw(st.floats(0.35, 1.4)) for _ in range(n - 1)]
    th = th0 + np.concatenate([[0.0], np.cumsum(steps)])
    b = A + l1 * np.exp(1j * th)
    # C on the circles about B and D (left of B→D)
    bd = D - b
    dist = np.abs(bd)
    assume(np.all(dist < l2 + l3) and np.all(dist > abs(l2 - l3)))
    x = (l2 ** 2 - l3 ** 2 + dist ** 2) / (2 * dist)
    h = np.sqrt(np.maximum(l2 ** 2 - x ** 2, 0.0))
    c = b + (x + 1j * h) * bd / dist
    # well-conditioned dyads: the triangle B C D not near a toggle, B away from D
    assume(np.all(h >= 0.1 * s) and np.all(dist >= 0.1 * s))
    th2 = np.angle(c - b)
    m = b + mrel * np.exp(1j * th2)
    return A, D, b, c, m, th2, s


def close(p, z, size, rel=1e-9):
    """The design's point p = (x, y) is z to ``rel`` of the scale."""
    return abs(complex(*p) - z) <= rel * size


@settings(max_examples=60, **FILTERED)
@given(fourbar_motion(3))
def test_three_positions_recovers_the_fixed_pivots(mo):
    A, D, b, c, m, th2, s = mo
    # B turns about A, C about D: three positions far enough apart on each circle
    assume(spread(np.angle(b - A)) >= GAP and spread(np.angle(c - D)) >= GAP)
    d = three_positions([(z.real, z.imag) for z in b], [(z.real, z.imag) for z in c])
    assert close(d.pivots["A"], A, s) and close(d.pivots["D"], D, s)
    for key, val in (("l1", abs(b[0] - A)), ("l2", abs(c[0] - b[0])),
                     ("l3", abs(c[0] - D)), ("l4", abs(D - A))):
        assert abs(d.lengths[key] - val) <= 1e-9 * s


@settings(max_examples=60, **FILTERED)
@given(fourbar_motion(3), st.sampled_from(["matrix", "nonlinear", "inversion"]))
def test_coupler_poses_recover_the_moving_pivots(mo, method):
    A, D, b, c, m, th2, s = mo
    # seen from the coupler, A turns about B and D about C: the relative angles
    assume(spread(np.angle(b - A) - th2) >= GAP and spread(np.angle(c - D) - th2) >= GAP)
    M = [(z.real, z.imag) for z in m]
    if method == "inversion":
        d = moving_pivots((A.real, A.imag), (D.real, D.imag),
                          [(x, y, p) for (x, y), p in zip(M, th2)])
    else:
        d = coupler_poses(M, th2, (A.real, A.imag), (D.real, D.imag), method=method)
        assert d.values["residual"] <= 1e-12
    assert close(d.pivots["B1"], b[0], s) and close(d.pivots["C1"], c[0], s)
    assert abs(d.lengths["l2"] - abs(c[0] - b[0])) <= 1e-9 * s
    # and the engine moves the design through the three poses (no branch change:
    # the poses came from one assembly mode)
    mm = solve(d.linkage, {1: DriverMotion(d.inputs)}, order=0)
    got = mm.points["M"].x + 1j * mm.points["M"].y
    assert np.max(np.abs(got - m)) <= 1e-9 * d.size


@settings(max_examples=25, **FILTERED)
@given(fourbar_motion(5))
def test_burmester_points_include_the_linkages_own_dyads(mo):
    A, D, b, c, m, th2, s = mo
    assume(spread(th2) >= 0.05)
    M = [(z.real, z.imag) for z in m]
    pairs = burmester_points(M, th2)
    L = float(np.max(np.abs(m - m[0])))
    alpha = th2 - th2[0]
    for p in pairs:
        if p.at_infinity:
            continue
        # (S-E): W (e^{iβj} - 1) + Z (e^{iαj} - 1) = δj at every pose
        W, Z = p.circle - p.centre, m[0] - p.circle
        Bj = m - Z * np.exp(1j * alpha)
        beta = np.angle((Bj - p.centre) / W)
        F = W * (np.exp(1j * beta) - 1) + Z * (np.exp(1j * alpha) - 1) - (m - m[0])
        assert np.max(np.abs(F)) <= 1e-9 * L
    # five exact poses of the linkage: its dyads AB and DC are two of the pairs
    # (1e-7: two Burmester points may lie close, which costs digits)
    for cen, cir in ((A, b[0]), (D, c[0])):
        assert min(abs(p.centre - cen) + abs(p.circle - cir) for p in pairs
                   if not p.at_infinity) <= 1e-7 * s
    # the design of those two moves through the five poses on the engine
    pa = min(pairs, key=lambda p: abs(p.centre - A) if not p.at_infinity else math.inf)
    pb = min(pairs, key=lambda p: abs(p.centre - D) if not p.at_infinity else math.inf)
    design = burmester_design(M, th2, pa, pb)
    mm = solve(design.linkage, {1: DriverMotion(design.inputs)}, order=0)
    got = mm.points["M"].x + 1j * mm.points["M"].y
    assert np.max(np.abs(got - m)) <= 1e-7 * s
