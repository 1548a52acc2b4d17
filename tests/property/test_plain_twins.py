"""Every element's optimised ``step`` equals its readable twin in
mechcli.core.linkage.plain (issue 32 §2) on random batched inputs: the crank, a point on a
link, the RRR, RRP (on the frame and on a moving guide), RPR and PRP (a moving and a fixed
guide) dyads; positions, velocities and accelerations of points, links and slides."""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechcli.core.linkage import (PRP, RPR, RRP, RRR, Crank, DriverMotion, Ground, Linkage,
                                  PointOnLink, solve)
from mechcli.core.linkage import plain

SET = settings(max_examples=30, deadline=None)


@pytest.fixture(autouse=True)
def _quiet_outside_the_linkage():
    # a twin computes NaN where the linkage does not assemble; only the regular
    # positions are compared
    with np.errstate(invalid="ignore", divide="ignore"):
        yield
Q = np.linspace(0.0, 2 * math.pi, 73)
length = st.floats(0.05, 0.5)


def _pt(m, name):
    p = m.points[name]
    return plain.Pt(p.x + 1j * p.y, p.vx + 1j * p.vy, p.ax + 1j * p.ay)


def _ground(x, y):
    z = np.zeros_like(Q, dtype=complex)
    return plain.Pt(x + 1j * y + z, z, z)


def _same(a, b, ok, scale):
    a, b = np.asarray(a)[ok], np.asarray(b)[ok]
    assert np.allclose(a, b, rtol=1e-9, atol=1e-9 * scale), np.max(np.abs(a - b))


def _same_angle(a, b, ok):
    d = np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))
    assert np.max(np.abs(d[ok])) <= 1e-9


def _same_point(m, name, twin, ok, w, al):
    z = _pt(m, name)
    L = float(np.max(np.abs(twin.p[ok])))
    _same(z.p, twin.p, ok, L)
    _same(z.v, twin.v, ok, L * w)
    _same(z.a, twin.a, ok, L * (w * w + abs(al)))


def _same_link(m, n, twin, ok, w, al):
    _same_angle(m.links[n].theta, twin.theta, ok)
    _same(np.broadcast_to(m.links[n].omega, Q.shape), twin.omega, ok, w)
    _same(np.broadcast_to(m.links[n].alpha, Q.shape), twin.alpha, ok, w * w + abs(al))


def _crank_twin(r, w, al):
    return plain.crank(_ground(0.0, 0.0), r, Q, w + 0 * Q, al + 0 * Q)


@SET
@given(st.floats(0.02, 0.15), length, length, length, st.sampled_from([1, -1]),
       st.floats(0.5, 20.0), st.floats(-5.0, 5.0), st.floats(-0.2, 0.2), st.floats(-0.1, 0.1))
def test_crank_rrr_and_a_coupler_point(r, a, b, d, branch, w, al, along, normal):
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", d, 0.0), Crank(1, "A", "B", r),
                     RRR("C", "B", 2, a, "D", 3, b, branch), PointOnLink("E", 2, "B", along, normal)))
    m = solve(lk, {1: DriverMotion(Q, w, al)}, order=2)
    ok = m.regular & (np.abs(np.broadcast_to(m.conditions[0].sin_gamma, Q.shape)) > 0.05)
    assume(ok.sum() > 5)
    B, l1 = _crank_twin(r, w, al)
    C, l2, l3 = plain.rrr(B, a, _ground(d, 0.0), b, branch)
    E = plain.point_on_link(B, l2, along, normal)
    _same_point(m, "B", B, ok, w, al)
    _same_point(m, "C", C, ok, w, al)
    _same_point(m, "E", E, ok, w, al)
    _same_link(m, 2, l2, ok, w, al)
    _same_link(m, 3, l3, ok, w, al)


@SET
@given(st.floats(0.02, 0.12), st.floats(0.2, 0.5), st.floats(-0.05, 0.05),
       st.floats(-1.0, 1.0), st.sampled_from([1, -1]), st.floats(0.5, 20.0),
       st.floats(-5.0, 5.0))
def test_rrp_on_the_frame(r, l, offset, angle, branch, w, al):
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Crank(1, "A", "B", r),
                     RRP("C", "B", 2, l, 3, 4, "A", angle, offset, branch)))
    m = solve(lk, {1: DriverMotion(Q, w, al)}, order=2)
    ok = m.regular & (np.abs(np.broadcast_to(m.conditions[0].sin_gamma, Q.shape)) > 0.05)
    assume(ok.sum() > 5)
    B, _ = _crank_twin(r, w, al)
    C, rod, (s, sd, sdd) = plain.rrp(B, l, _ground(0.0, 0.0), plain.FRAME, angle, offset,
                                     branch)
    _same_point(m, "C", C, ok, w, al)
    _same_link(m, 2, rod, ok, w, al)
    sl = m.slides[next(iter(m.slides))]
    _same(sl.s, s, ok, l)
    _same(sl.v, sd, ok, l * w)
    _same(sl.a, sdd, ok, l * (w * w + abs(al)))


@SET
@given(st.floats(0.05, 0.15), st.floats(0.25, 0.4), st.floats(-0.03, 0.03),
       st.sampled_from([1, -1]), st.floats(0.5, 20.0), st.floats(-5.0, 5.0),
       st.floats(-0.5, 0.5), st.floats(0.1, 0.3), st.floats(-0.3, 0.3))
def test_rpr_then_rrp_on_the_moving_guide(r, c, offset, branch, w, al, angle, l, goff):
    # a guide-bar (RPR: the guide 3 about C through the block 2 at B), then a rod from B
    # whose pin slides on a line carried by the guide 3 (an RRP on a moving guide)
    lk = Linkage(6, (Ground("A", 0.0, 0.0), Ground("C", 0.0, -c), Crank(1, "A", "B", r),
                     RPR("B", 2, "C", 3, offset, branch, "23"),
                     PointOnLink("G", 3, "C", 0.05, 0.0),
                     RRP("E", "B", 4, l, 5, 3, "G", angle, goff, 1, "53")))
    m = solve(lk, {1: DriverMotion(Q, w, al)}, order=2)
    ok = m.regular & np.all([np.abs(np.broadcast_to(c_.sin_gamma, Q.shape)) > 0.05
                             for c_ in m.conditions], axis=0)
    assume(ok.sum() > 5)
    B, _ = _crank_twin(r, w, al)
    guide, (s, sd, sdd) = plain.rpr(B, _ground(0.0, -c), offset, branch)
    _same_link(m, 3, guide, ok, w, al)
    _same(m.slides["23"].s, s, ok, c)
    _same(m.slides["23"].v, sd, ok, c * w)
    _same(m.slides["23"].a, sdd, ok, c * (w * w + abs(al)))
    G = plain.point_on_link(_ground(0.0, -c), guide, 0.05, 0.0)
    E, rod, (s2, sd2, sdd2) = plain.rrp(B, l, G, guide, angle, goff, 1)
    _same_point(m, "E", E, ok, w, al)
    _same_link(m, 4, rod, ok, w, al)
    _same(m.slides["53"].s, s2, ok, l)
    _same(m.slides["53"].v, sd2, ok, l * w)
    _same(m.slides["53"].a, sdd2, ok, l * (w * w + abs(al)))


@SET
@given(st.floats(0.05, 0.3), st.floats(-0.05, 0.05), st.floats(0.3, 1.2),
       st.floats(-0.05, 0.05), st.floats(0.5, 20.0), st.floats(-5.0, 5.0))
def test_prp_on_a_turning_and_a_fixed_guide(d, off_a, angle_b, off_b, w, al):
    # the tangent mechanism: a slotted crank 1 about A (its slot at offset off_a) and a
    # slider on the frame's line through D at angle_b: their blocks pinned at J
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", d, 0.0), Crank(1, "A", "B", 0.1),
                     PRP("J", 2, 1, "A", 3, 4, "D", 0.0, off_a, angle_b, off_b, "a", "b")))
    m = solve(lk, {1: DriverMotion(Q, w, al)}, order=2)
    ok = m.regular & (np.abs(np.broadcast_to(m.conditions[0].sin_gamma, Q.shape)) > 0.1)
    ok &= np.abs(m.points["J"].x + 1j * m.points["J"].y) < 5.0
    assume(ok.sum() > 5)
    _B, crank = _crank_twin(0.1, w, al)
    J, (sa, sda, sdda), (sb, sdb, sddb) = plain.prp(_ground(0.0, 0.0), crank, 0.0, off_a,
                                                    _ground(d, 0.0), plain.FRAME, angle_b,
                                                    off_b)
    L = float(np.max(np.abs(J.p[ok])))
    _same_point(m, "J", J, ok, w, al)
    for name, (s, sd, sdd) in (("a", (sa, sda, sdda)), ("b", (sb, sdb, sddb))):
        _same(m.slides[name].s, s, ok, L)
        _same(m.slides[name].v, sd, ok, L * w)
        _same(m.slides[name].a, sdd, ok, L * (w * w + abs(al)))
