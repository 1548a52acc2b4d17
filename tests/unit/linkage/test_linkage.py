"""Linkage engine cross-checks: the book's closed forms and matrix equations,
finite differences of positions, loop-closure residuals."""

import math

import numpy as np
import pytest

from mechcli.core.linkage import (RPR, RRP, RRR, Crank, DriverMotion, Ground, Linkage,
                                  LinkageDefinitionError, PointOnLink, solve)
from mechcli.spec.kin import load_kin_spec
from tests.conftest import CONFIGS

KIN_CONFIGS = sorted((CONFIGS / "ch1").glob("*.toml"))
TH = np.radians(np.arange(0.0, 360.0, 3.0) + 0.5)


def _motion(spec, q, order=2):
    inp = spec.input
    inputs = {inp.driver: DriverMotion(q, inp.omega, inp.alpha)}
    for link, (ratio, phase) in inp.followers.items():
        inputs[link] = DriverMotion(phase + ratio * q, ratio * inp.omega, ratio * inp.alpha)
    return solve(spec.linkage, inputs, order=order)


def _within_the_sweep(spec):
    """TH, or for a config whose sweep is not a whole turn (习题 1-15: the arc between its
    change points) as many inputs inside its sweep: its claims are over that range."""
    q = np.asarray(spec.input.sweep().q, dtype=float)
    if q[-1] - q[0] >= 2 * math.pi - 1e-9:
        return TH
    return np.linspace(q[0], q[-1], TH.size + 2)[1:-1]


@pytest.mark.parametrize("path", KIN_CONFIGS, ids=[p.stem for p in KIN_CONFIGS])
def test_velocities_and_accelerations_match_central_differences(path):
    spec = load_kin_spec(path)
    w = spec.input.omega
    h = 1e-6
    th = _within_the_sweep(spec)
    m = _motion(spec, th)
    mp, mm = _motion(spec, th + h), _motion(spec, th - h)
    assert m.regular.all()

    def check(x, xp, xm, dx, wrap=False):
        d = xp - xm
        if wrap:
            d = (d + np.pi) % (2 * np.pi) - np.pi
        fd = d / (2 * h) * w
        scale = max(np.max(np.abs(dx)), 1e-12)
        # plus the difference's rounding, eps |x| / h: a rate that is zero to round-off
        # (习题 1-15's α2) is compared with the noise of its quantity's differences
        rounding = 100 * np.finfo(float).eps * np.max(np.abs(x)) * abs(w) / h
        np.testing.assert_allclose(fd, dx, atol=2e-6 * scale + rounding, rtol=0)

    for n, lk in m.links.items():
        if n == spec.linkage.frame:
            continue
        check(lk.theta, mp.links[n].theta, mm.links[n].theta, lk.omega, wrap=True)
        check(lk.omega, mp.links[n].omega, mm.links[n].omega, lk.alpha)
    for name, pt in m.points.items():
        check(pt.p, mp.points[name].p, mm.points[name].p, pt.v)
        check(pt.v, mp.points[name].v, mm.points[name].v, pt.a)
    for name, sl in m.slides.items():
        check(sl.s, mp.slides[name].s, mm.slides[name].s, sl.v)
        check(sl.v, mp.slides[name].v, mm.slides[name].v, sl.a)


@pytest.mark.parametrize("path", KIN_CONFIGS, ids=[p.stem for p in KIN_CONFIGS])
def test_loop_closure_residuals(path):
    spec = load_kin_spec(path)
    lk = spec.linkage
    m = _motion(spec, TH, order=0)
    P = {k: v.p for k, v in m.points.items()}
    scale = lk.scale()
    res = [0.0]
    for el in lk.elements:
        if isinstance(el, Crank):
            res.append(np.max(np.abs(np.abs(P[el.point] - P[el.pivot]) - el.length)))
        elif isinstance(el, RRR):
            res.append(np.max(np.abs(np.abs(P[el.joint] - P[el.point_a]) - el.length_a)))
            res.append(np.max(np.abs(np.abs(P[el.joint] - P[el.point_b]) - el.length_b)))
        elif isinstance(el, RRP):
            res.append(np.max(np.abs(np.abs(P[el.joint] - P[el.point]) - el.length)))
            th = m.links[el.guide_link].theta + el.guide_angle
            u = np.exp(1j * th)
            rel = (P[el.joint] - P[el.guide_point]) * np.conj(u)
            res.append(np.max(np.abs(rel.imag - el.offset)))  # pin on the guide line
        elif isinstance(el, RPR):
            u = np.exp(1j * m.links[el.guide].theta)
            rel = (P[el.point] - P[el.pivot]) * np.conj(u)
            res.append(np.max(np.abs(rel.imag - el.offset)))  # block on the guide line
        elif isinstance(el, PointOnLink):
            d = np.abs(P[el.name] - P[el.origin])
            res.append(np.max(np.abs(d - math.hypot(el.along, el.normal))))
    assert max(res) <= 1e-9 * scale


def _fourbar(l1, l2, l3, l4, branch=1):
    return Linkage(4, (Ground("A", 0, 0), Ground("D", l4, 0), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, branch)))


def test_fourbar_matches_book_eq_1_4_and_matrix_eq_1_7_1_8():
    """例 1-1: eq. (1-4) positions; eq. (1-7)/(1-8) solved with numpy.linalg."""
    l1, l2, l3, l4, w1 = 0.1016, 0.254, 0.1778, 0.3048, 250.0
    m = solve(_fourbar(l1, l2, l3, l4), {1: DriverMotion(TH, w1)})
    L = np.sqrt(l4 ** 2 + l1 ** 2 - 2 * l1 * l4 * np.cos(TH))
    phi = np.arcsin(l1 / L * np.sin(TH))
    beta = np.arccos((-l2 ** 2 + l3 ** 2 + L ** 2) / (2 * l3 * L))
    th3 = np.pi - phi - beta
    th2 = np.arcsin((l3 * np.sin(th3) - l1 * np.sin(TH)) / l2)
    np.testing.assert_allclose(np.exp(1j * m.links[3].theta), np.exp(1j * th3), atol=1e-12)
    np.testing.assert_allclose(np.exp(1j * m.links[2].theta), np.exp(1j * th2), atol=1e-12)
    for i in range(0, TH.size, 7):
        t1, t2, t3 = TH[i], th2[i], th3[i]
        A = np.array([[-l2 * math.sin(t2), l3 * math.sin(t3)], [l2 * math.cos(t2), -l3 * math.cos(t3)]])
        om = np.linalg.solve(A, w1 * np.array([l1 * math.sin(t1), -l1 * math.cos(t1)]))
        assert om == pytest.approx([m.links[2].omega[i], m.links[3].omega[i]], rel=1e-10)
        At = np.array([[-om[0] * l2 * math.cos(t2), om[1] * l3 * math.cos(t3)],
                       [-om[0] * l2 * math.sin(t2), om[1] * l3 * math.sin(t3)]])
        rhs = -At @ om + w1 * np.array([w1 * l1 * math.cos(t1), w1 * l1 * math.sin(t1)])
        al = np.linalg.solve(A, rhs)
        assert al == pytest.approx([m.links[2].alpha[i], m.links[3].alpha[i]], rel=1e-9)


def test_slider_crank_matches_book_eq_1_12_with_offset():
    l1, l2, e = 0.1, 0.3, 0.03
    lk = Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", l1),
                     RRP("C", "B", 2, l2, 3, 4, "A", 0.0, e, 1, "3")))
    m = solve(lk, {1: DriverMotion(TH, 10.0)})
    th2 = np.arcsin((e - l1 * np.sin(TH)) / l2)
    sc = l1 * np.cos(TH) + l2 * np.cos(th2)
    np.testing.assert_allclose(m.links[2].theta, th2, atol=1e-12)
    np.testing.assert_allclose(m.slides["3"].s, sc, atol=1e-14)
    # eq. (1-15): omega2, vC from the book's matrix
    for i in range(0, TH.size, 11):
        A = np.array([[l2 * math.sin(th2[i]), 1.0], [-l2 * math.cos(th2[i]), 0.0]])
        sol = np.linalg.solve(A, 10.0 * np.array([-l1 * math.sin(TH[i]), l1 * math.cos(TH[i])]))
        assert sol == pytest.approx([m.links[2].omega[i], m.slides["3"].v[i]], rel=1e-10, abs=1e-13)


def test_guide_bar_matches_book_eq_1_20_and_1_23():
    l1, l4, w1 = 0.12, 0.38, 1.0
    lk = Linkage(4, (Ground("C", 0, 0), Ground("A", 0, l4), Crank(1, "A", "B", l1),
                     RPR("B", 2, "C", 3, 0.0, 1, "23")))
    m = solve(lk, {1: DriverMotion(TH, w1)})
    sb = np.sqrt((l1 * np.cos(TH)) ** 2 + (l4 + l1 * np.sin(TH)) ** 2)
    th3 = np.arccos(l1 * np.cos(TH) / sb)
    np.testing.assert_allclose(m.slides["23"].s, sb, atol=1e-14)
    np.testing.assert_allclose(m.links[3].theta, th3, atol=1e-12)
    for i in range(0, TH.size, 9):
        c, s = math.cos(th3[i]), math.sin(th3[i])
        A = np.array([[c, -sb[i] * s], [s, sb[i] * c]])
        sol = np.linalg.solve(A, w1 * l1 * np.array([-math.sin(TH[i]), math.cos(TH[i])]))
        assert sol == pytest.approx([m.slides["23"].v[i], m.links[3].omega[i]], rel=1e-10, abs=1e-13)


def test_shaper_matches_book_eq_1_28_and_1_32():
    spec = load_kin_spec(CONFIGS / "ch1" / "ex1-4.toml")
    l1, l3, l4, l6, l6p = 0.125, 0.6, 0.15, 0.275, 0.575
    m = _motion(spec, TH)
    s3 = np.sqrt((l1 * np.cos(TH)) ** 2 + (l6 + l1 * np.sin(TH)) ** 2)
    th3 = np.arccos(l1 * np.cos(TH) / s3)
    th4 = np.pi - np.arcsin((l6p - l3 * np.sin(th3)) / l4)
    se = l3 * np.cos(th3) + l4 * np.cos(th4)
    np.testing.assert_allclose(m.links[3].theta, th3, atol=1e-12)
    np.testing.assert_allclose(np.exp(1j * m.links[4].theta), np.exp(1j * th4), atol=1e-12)
    np.testing.assert_allclose(m.slides["E"].s, se, atol=1e-14)


def test_five_bar_two_drivers_close_the_loop():
    lk = Linkage(5, (Ground("A", 0, 0), Ground("E", 21, 0), Crank(1, "A", "B", 5),
                     Crank(4, "E", "D", 13), RRR("C", "B", 2, 20, "D", 3, 22, 1)))
    t1, t4 = np.meshgrid(np.radians(np.arange(0, 360, 10)), np.radians(np.arange(0, 360, 10)))
    m = solve(lk, {1: DriverMotion(t1, 1.0), 4: DriverMotion(t4, -2.0)})
    assert m.feasible.shape == t1.shape and m.feasible.all()
    C, B, D = m.points["C"].p, m.points["B"].p, m.points["D"].p
    assert np.max(np.abs(np.abs(C - B) - 20)) < 1e-12
    assert np.max(np.abs(np.abs(C - D) - 22)) < 1e-12


def test_infeasible_positions_are_masked_not_nan():
    m = solve(_fourbar(0.1, 0.05, 0.06, 0.3), {1: DriverMotion(TH, 1.0)})
    assert not m.feasible.any()
    for pt in m.points.values():
        assert np.isfinite(pt.p).all() and np.isfinite(pt.v).all() and np.isfinite(pt.a).all()


def test_bad_topology_is_reported_with_the_element():
    with pytest.raises(LinkageDefinitionError, match="point 'X' is not defined") as exc:
        Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", 1.0),
                    RRR("C", "B", 2, 1.0, "X", 3, 1.0)))
    assert exc.value.index == 2 and exc.value.field == ("point", "X")
    with pytest.raises(LinkageDefinitionError, match="link 9 is not the frame") as exc:
        Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", 1.0), PointOnLink("P", 9, "B", 1.0)))
    assert exc.value.index == 2 and exc.value.field == ("link", 9)
    with pytest.raises(LinkageDefinitionError, match="defined twice"):
        Linkage(4, (Ground("A", 0, 0), Ground("A", 1, 0)))


def test_order_zero_computes_no_derivatives():
    m = solve(_fourbar(1, 3, 2.5, 2), {1: DriverMotion(TH, 1.0)}, order=0)
    assert m.points["C"].v is None and m.links[3].omega is None
