"""The PRP dyad (two slider blocks pinned together): loop closure, finite
differences, the tangent mechanism and the Oldham-coupling inversion of the
elliptic trammel in closed form, kinetostatic power balance, a ``kin`` run,
the parallel-guides dead point and a batch of designs.

It is also the proof of the engine's extension point: the class in
``elements.py``, its spec reader and these tests are all it took.
"""

import csv
import math

import numpy as np
import pytest

from mechcli.core.linkage import PRP, Crank, DriverMotion, Ground, Linkage, solve
from mechcli.core.linkage.kinetostatics import Body, ForceModelError, Load, solve_forces, topology
from tests.conftest import run_inprocess, write_spec
from tests.unit.linkage.test_kinetostatics import _equilibrium_residual

EPS = np.finfo(float).eps
D = 0.2  # [m] distance of the tangent mechanism's slider line from the crank pivot


def tangent_mechanism(d=D):
    """The tangent mechanism (正切机构): link 1 turns about A = (0, 0) and carries
    a slot along itself (guide a through A); block 2 slides in it, pinned at C
    to block 3, which slides on the frame's vertical line x = d (guide b through
    G = (d, 0) at 90°).  Frame 4.  y_C = s3 = d tan θ1."""
    return Linkage(4, (Ground("A", 0.0, 0.0), Ground("G", d, 0.0), Crank(1, "A", "B", 0.1),
                       PRP("C", 2, 1, "A", 3, 4, "G", guide_angle_b=math.pi / 2)))


def oldham(d=D):
    """Oldham coupling (the elliptic trammel's inversion with the slotted
    cranks as drivers): crank 1 about A = (0, 0) with a slot along itself,
    crank 4 about E = (d, 0) with a slot at 90° to itself, both at θ (link 4
    follows link 1, ratio 1).  Frame 5.  The cross's centre C is the foot of
    the perpendicular from E on crank 1's slot (Thales), so the slide along
    crank 1 is s21 = d cos θ and along crank 4 is s34 = d sin θ: the Scotch-yoke
    law x = r cos θ with r = d, and C runs on the circle of diameter AE at 2ω."""
    return Linkage(5, (Ground("A", 0.0, 0.0), Ground("E", d, 0.0), Crank(1, "A", "B", 0.05),
                       Crank(4, "E", "F", 0.05),
                       PRP("C", 2, 1, "A", 3, 4, "E", guide_angle_b=math.pi / 2)))


# general PRPs for the finite-difference checks (angles [rad], lengths [m]):
# guide a on the crank through its pin B, turned 0.6 rad and offset 0.03 m;
# guide b on the frame through G at 1.9 rad, offset -0.02 m ...
CRANK_AND_FRAME = Linkage(4, (Ground("A", 0.0, 0.0), Ground("G", 0.25, -0.05),
                              Crank(1, "A", "B", 0.1),
                              PRP("C", 2, 1, "B", 3, 4, "G", 0.6, 0.03, 1.9, -0.02)))
# ... and both guides moving: guide b on a second crank 5 (about E, pin D), which
# turns at its own speed and acceleration
BOTH_MOVING = Linkage(6, (Ground("A", 0.0, 0.0), Ground("E", 0.3, 0.05),
                          Crank(1, "A", "B", 0.1), Crank(5, "E", "D", 0.08),
                          PRP("C", 2, 1, "B", 3, 5, "D", 0.4, 0.01, -1.1, -0.015)))


def _lines(linkage, motion):
    """Per side of the PRP: (guide base point, unit direction, slide) rebuilt
    from the solved guide links' angles and points, as complex numbers."""
    prp = linkage.elements[-1]
    out = []
    for sl, gl, gp, ang, off, _ in prp._sides():
        u = np.exp(1j * (motion.links[gl].theta + ang))
        base = motion.points[gp].p + off * 1j * u
        slide = next(s for s in motion.slides.values() if s.block == sl and s.guide == gl)
        out.append((base, u, slide.s))
    return out


def _inputs(linkage, t, q0, w, al):
    """Every driver at time t [s]: q = q0 + w t + al t²/2 (constant acceleration)."""
    return {d.link: DriverMotion(q0[d.link] + w[d.link] * t + 0.5 * al[d.link] * t * t,
                                 w[d.link] + al[d.link] * t, al[d.link])
            for d in linkage.drivers}


@pytest.mark.parametrize("linkage, q0, w, al", [
    (CRANK_AND_FRAME, {1: np.radians(np.arange(-150.0, 60.0, 7.0))}, {1: 2.5}, {1: -1.5}),
    (BOTH_MOVING, {1: np.radians(np.arange(0.0, 360.0, 9.0)),
                   5: np.radians(200.0 - 0.7 * np.arange(0.0, 360.0, 9.0))},
     {1: 2.5, 5: -1.75}, {1: 1.2, 5: 3.0}),
], ids=["crank_and_frame", "both_guides_moving"])
def test_loop_closure_and_finite_differences(linkage, q0, w, al):
    """The joint lies on both guide lines (to round-off), and the exact
    velocities and accelerations (joint and both slides) match central
    differences in time of the positions.

    Step h = 1e-5 s.  Central differences carry a truncation error of
    h²/6 |p'''| (first) and h²/12 |p''''| (second derivative): measured 1.2e-6
    of the peaks at h = 1e-4 s and 100x less at 1e-5 s (it is O(h²)), so ~1e-8;
    and a round-off of ~eps |p| / h (~1e-11) and ~eps |p| / h² (measured up to
    9e-8 of the peak acceleration).  Asserted: velocities to 1e-7 and
    accelerations to 1e-6 of each quantity's peak.  Positions within ~17° of
    parallel guides (sin_gamma < 0.3: the joint far out, derivatives growing
    as 1/sin³ and the truncation error with them) are left out.
    """
    m = solve(linkage, _inputs(linkage, 0.0, q0, w, al), order=2)
    keep = m.conditions[0].sin_gamma >= 0.3
    assert keep.sum() >= 20
    q0 = {k: v[keep] for k, v in q0.items()}
    m = solve(linkage, _inputs(linkage, 0.0, q0, w, al), order=2)
    assert m.regular.all()
    scale = max(linkage.scale(), np.max(np.abs(m.points["C"].p)))
    (ba, ua, sa), (bb, ub, sb) = _lines(linkage, m)
    c = m.points["C"].p
    # on both lines: (C - base) x u = 0, and C = base + s u, to a few ulps
    for base, u, s in ((ba, ua, sa), (bb, ub, sb)):
        assert np.max(np.abs(((c - base) * np.conj(u)).imag)) <= 8 * EPS * scale
        assert np.max(np.abs(base + s * u - c)) <= 8 * EPS * scale

    # each block turns with its guide link
    prp = linkage.elements[-1]
    for sl, gl, _, ang, *_ in prp._sides():
        k, g = m.links[sl], m.links[gl]
        assert np.allclose(np.exp(1j * k.theta), np.exp(1j * (g.theta + ang)), rtol=0,
                           atol=4 * EPS)
        assert np.array_equal(k.omega, g.omega) and np.array_equal(k.alpha, g.alpha)

    h = 1e-5
    mp, mm = (solve(linkage, _inputs(linkage, t, q0, w, al), order=0) for t in (h, -h))
    series = {"xC": lambda k: k.points["C"].x, "yC": lambda k: k.points["C"].y}
    exact = {"xC": (m.points["C"].vx, m.points["C"].ax),
             "yC": (m.points["C"].vy, m.points["C"].ay)}
    for name, sl in m.slides.items():
        series[name] = lambda k, n=name: k.slides[n].s
        exact[name] = (sl.v, sl.a)
    assert len(m.slides) == 2
    for name, f in series.items():
        p0, pp, pm = f(m), f(mp), f(mm)
        v_fd = (pp - pm) / (2 * h)
        a_fd = (pp - 2 * p0 + pm) / (h * h)
        v, a = exact[name]
        peak_v = max(np.max(np.abs(v)), 1e-3 * scale)
        peak_a = max(np.max(np.abs(a)), 1e-3 * scale)
        assert np.max(np.abs(v - v_fd)) <= 1e-7 * peak_v, name
        assert np.max(np.abs(a - a_fd)) <= 1e-6 * peak_a, name


def test_tangent_mechanism_closed_form():
    """Tangent mechanism: y_C = d tan θ, v_C = d ω / cos²θ,
    a_C = d (α + 2 ω² tan θ) / cos²θ; block 2 is at d / cos θ along the crank,
    turns with it, and block 3 translates."""
    th = np.radians(np.arange(-80.0, 81.0, 5.0))
    w, al = 3.0, -2.0
    lk = tangent_mechanism()
    m = solve(lk, {1: DriverMotion(th, w, al)}, order=2)
    sec2 = 1 / np.cos(th) ** 2
    c = m.points["C"]
    tol = 1e-13 * D * sec2  # a few ulps of the largest quantity at each angle
    assert np.allclose(c.x, D, rtol=0, atol=1e-15)
    assert np.all(np.abs(c.y - D * np.tan(th)) <= tol)
    s3 = m.slides["3"]  # block 3 on the frame: slide symbol s3 (RRP's rule)
    assert np.all(np.abs(s3.s - D * np.tan(th)) <= tol)
    assert np.all(np.abs(s3.v - D * w * sec2) <= tol * w * sec2)
    assert np.all(np.abs(s3.a - D * (al + 2 * w * w * np.tan(th)) * sec2)
                  <= tol * w * w * 4 * sec2)
    s21 = m.slides["21"]  # block 2 on the moving guide of link 1: s21
    assert np.all(np.abs(s21.s - D / np.cos(th)) <= tol)
    assert np.allclose(m.links[2].theta, th, rtol=0, atol=1e-15)
    assert np.allclose(m.links[2].omega, w) and np.allclose(m.links[2].alpha, al)
    # what kin reports: block 2's angle (it turns with the crank), both slides
    assert lk.slide_names == ("21", "3")
    assert lk.rotating_links == (2,) and lk.translating_links == (3,)


def test_oldham_inversion_scotch_yoke_law():
    """Both guides moving (Oldham coupling): s21 = d cos θ, v21 = -d ω sin θ,
    a21 = -d ω² cos θ (the Scotch-yoke law, r = d) and s34 = d sin θ; the
    cross's centre is on the circle of diameter AE, at angle 2θ from its centre."""
    th = np.radians(np.arange(0.0, 360.0, 5.0))
    w = 4.0
    lk = oldham()
    m = solve(lk, {1: DriverMotion(th, w), 4: DriverMotion(th, w)}, order=2)
    assert m.regular.all()  # the slots stay at 90°: never singular
    tol = 1e-15 * 8 * D
    s21, s34 = m.slides["21"], m.slides["34"]
    assert np.max(np.abs(s21.s - D * np.cos(th))) <= tol
    assert np.max(np.abs(s21.v + D * w * np.sin(th))) <= tol * w
    assert np.max(np.abs(s21.a + D * w * w * np.cos(th))) <= tol * w * w
    assert np.max(np.abs(s34.s - D * np.sin(th))) <= tol
    assert np.max(np.abs(s34.v - D * w * np.cos(th))) <= tol * w
    c = m.points["C"]
    assert np.max(np.abs(c.p - 0.5 * D * (1 + np.exp(2j * th)))) <= tol
    assert np.max(np.abs(c.v - 0.5 * D * 2j * w * np.exp(2j * th))) <= tol * w
    assert np.max(np.abs(c.a + 0.5 * D * 4 * w * w * np.exp(2j * th))) <= tol * w * w
    cond = m.conditions[0]
    assert cond.kind == "PRP" and cond.joint == "C" and np.allclose(cond.sin_gamma, 1.0)


def _forces(linkage, q, w, bodies, loads, gravity, alpha=0.0):
    motion = solve(linkage, {1: DriverMotion(q, w, alpha)}, order=2)
    unit = solve(linkage, {1: DriverMotion(q, 1.0, 0.0)}, order=1)
    topo = topology(linkage)
    return topo, motion, solve_forces(topo, motion, bodies, loads, gravity, unit)


def test_kinetostatics_power_balance():
    """Massless blocks, a force P down on block 3: by virtual work the crank
    needs Mb = P d / cos²θ (Mb ω = P v_C).  With masses, inertia, gravity and a
    load: every link in equilibrium and the virtual-power residual at round-off
    (asserted 1e-10 of the peak Mb; measured 1.3e-16)."""
    lk = tangent_mechanism()
    q = np.radians(np.arange(-70.0, 71.0, 5.0))
    P = 250.0
    topo, motion, fr = _forces(lk, q, 6.0, {}, [Load("P", 3, 0.0, -P, 0.0, "C")], (0.0, 0.0))
    assert np.allclose(fr.balancing[1], P * D / np.cos(q) ** 2, rtol=1e-12, atol=0)
    # the pairs: the crank's pivot; P crank-block 2, R at C, P block 3-frame
    assert [(p.pair.kind, p.pair.label) for p in fr.pairs] == [
        ("R", "14"), ("P", "12"), ("R", "23"), ("P", "34")]
    bodies = {1: Body(1, 2.0, 0.004, "A", 0.05, 0.0), 2: Body(2, 0.6, 0.0003, "C", 0.01, 0.005),
              3: Body(3, 1.5, 0.001, "C", 0.0, -0.03)}
    loads = [Load("F", 3, 40.0, -P, 0.0, "C", 0.02, 0.01), Load("T", 2, torque=3.0)]
    topo, motion, fr = _forces(lk, q, 6.0, bodies, loads, (0.0, -9.81), alpha=2.0)
    peak = np.max(np.abs(fr.balancing[1]))
    assert np.max(np.abs(fr.power_residual)) <= 1e-10 * peak
    assert np.max(fr.force_residual) <= 1e-11 * np.max(np.hypot(*fr.frame_force))
    forces = max(np.max(pf.magnitude) for pf in fr.pairs)
    assert _equilibrium_residual(topo, motion, fr, bodies, loads, (0.0, -9.81)) <= 1e-10 * forces


def test_guide_point_must_be_on_its_guide_link():
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Ground("G", D, 0.0), Crank(1, "A", "B", 0.1),
                     PRP("C", 2, 1, "G", 3, 4, "G", guide_angle_b=math.pi / 2)))
    with pytest.raises(ForceModelError, match="'G', which is not on link 1"):
        topology(lk)


SPEC = """\
command = "kin"
units = "mm"
[mechanism]
type = "general"
frame = 4
[mechanism.ground]
A = [0, 0]
G = [200, 0]
[[mechanism.driver]]
type = "crank"
link = 1
pivot = "A"
point = "B"
length = 100
[[mechanism.dyad]]
type = "PRP"
joint = "C"
slider_a = 2
guide_link_a = 1
guide_point_a = "A"
slider_b = 3
guide_link_b = 4
guide_point_b = "G"
guide_angle_b = 90
name_b = "C"
[input]
omega1 = 2
start = -60
stop = 60
step = 1
"""


def test_kin_run_of_a_prp_spec(tmp_path):
    """``mechcli kin`` on the tangent mechanism (d = 200 mm, ω1 = 2 rad/s):
    sC = 200 tan θ mm, vC = 400 / cos²θ mm/s, aC = 1600 tan θ / cos²θ mm/s²,
    to the CSV's 10 significant digits."""
    spec = write_spec(tmp_path, SPEC)
    proc = run_inprocess("kin", spec, "--no-plot", "--quiet", "--out", tmp_path / "out")
    assert proc.returncode == 0, proc.stderr
    with open(tmp_path / "out" / "kin.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    # both slides are reported: s21 (block 2 along the slot of crank 1), then sC
    assert rows[0] == ["theta1_deg", "theta2_deg", "s21_mm", "sC_mm", "omega2_rad_s",
                       "v21_mm_s", "vC_mm_s", "alpha2_rad_s2", "a21_mm_s2", "aC_mm_s2"]
    cols = np.array(rows[1:], dtype=float).T
    th = np.radians(cols[0])
    assert len(th) == 121
    for col, want in ((cols[2], 200 / np.cos(th)), (cols[3], 200 * np.tan(th)),
                      (cols[6], 400 / np.cos(th) ** 2),
                      (cols[9], 1600 * np.tan(th) / np.cos(th) ** 2)):
        assert np.allclose(col, want, rtol=1e-9, atol=1e-9 * np.max(np.abs(want)))


def test_kin_spec_rejects_a_branch(tmp_path):
    """A PRP has one assembly: a ``branch`` key is an error, not ignored."""
    spec = write_spec(tmp_path, SPEC.replace('name_b = "C"', 'name_b = "C"\nbranch = 1'))
    proc = run_inprocess("kin", spec, "--no-plot", "--quiet", "--out", tmp_path / "out")
    assert proc.returncode == 2
    assert "branch" in proc.stderr and "no branch" in proc.stderr


@pytest.mark.parametrize("order", [0, 1, 2])
def test_parallel_guides_are_a_flagged_dead_point(order):
    """At θ = 90° and 270° the crank's slot is parallel to the slider line: the
    positions are flagged (regular False, sin_gamma ~ cos 90° = 6e-17), every
    value stays finite; 1e-3 rad away the linkage is regular again."""
    th = np.radians([0.0, 90.0, 180.0, 270.0]) + np.array([0.0, 0.0, 1e-3, 0.0])
    th = np.append(th, np.radians(90.0) - 1e-3)
    m = solve(tangent_mechanism(), {1: DriverMotion(th, 2.0, 1.0)}, order=order)
    assert m.feasible.all()
    assert m.regular.tolist() == [True, False, True, False, True]
    assert m.conditions[0].kind == "PRP"
    assert np.all(m.conditions[0].sin_gamma[[1, 3]] < 1e-15)
    values = [m.points["C"].x, m.points["C"].y] + [s.s for s in m.slides.values()]
    if order:
        values += [m.points["C"].vx, m.points["C"].vy] + [s.v for s in m.slides.values()]
    if order == 2:
        values += [m.points["C"].ax, m.points["C"].ay] + [s.a for s in m.slides.values()]
    assert all(np.all(np.isfinite(v)) for v in values)
    # both guides on the frame and parallel: a dead point at every position
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Ground("G", 0.0, 0.1), Crank(1, "A", "B", 0.1),
                     PRP("C", 2, 4, "A", 3, 4, "G", 0.3, 0.0, 0.3 + math.pi, 0.0)))
    m = solve(lk, {1: DriverMotion(th, 2.0)}, order=order)
    assert not m.regular.any() and np.all(np.isfinite(m.points["C"].x))


def test_batch_of_designs_equals_separate_solves():
    """Slider-line distance d, guide angle and offsets of shape (M, 1) against
    θ of shape (N,): one call gives (M, N) equal to M separate solves."""
    M = 5
    d = np.linspace(0.1, 0.5, M)[:, None]
    ang = np.radians(np.linspace(70.0, 110.0, M))[:, None]
    off_a = np.linspace(-0.02, 0.02, M)[:, None]
    off_b = np.linspace(0.03, -0.01, M)[:, None]
    th = np.radians(np.arange(-60.0, 61.0, 4.0))

    def build(d, ang, off_a, off_b):
        return Linkage(4, (Ground("A", 0.0, 0.0), Ground("G", d, 0.0), Crank(1, "A", "B", 0.1),
                           PRP("C", 2, 1, "A", 3, 4, "G", 0.0, off_a, ang, off_b)))

    inputs = {1: DriverMotion(th, 3.0, -1.0)}
    batch = solve(build(d, ang, off_a, off_b), inputs, order=2)
    assert batch.points["C"].ax.shape == (M, len(th)) and batch.regular.all()
    for i in range(M):
        one = solve(build(float(d[i, 0]), float(ang[i, 0]), float(off_a[i, 0]),
                          float(off_b[i, 0])), inputs, order=2)
        for got, want in ((batch.points["C"], one.points["C"]),):
            for f in ("x", "y", "vx", "vy", "ax", "ay"):
                assert np.allclose(getattr(got, f)[i], getattr(want, f), rtol=1e-14,
                                   atol=1e-15), f
        for name in ("3", "21"):
            for f in ("s", "v", "a"):
                assert np.allclose(getattr(batch.slides[name], f)[i],
                                   getattr(one.slides[name], f), rtol=1e-14, atol=1e-15)
        assert np.array_equal(batch.regular[i], one.regular)


def test_kin_spec_names_an_undefined_guide_point(tmp_path):
    """A guide point nothing defines is reported at its own key, ``guide_point_b``."""
    spec = write_spec(tmp_path, SPEC.replace('guide_point_b = "G"', 'guide_point_b = "H"'))
    proc = run_inprocess("kin", spec, "--no-plot", "--quiet", "--out", tmp_path / "out")
    assert proc.returncode == 2
    assert "[mechanism.dyad.0] guide_point_b:" in proc.stderr, proc.stderr
    assert "'H'" in proc.stderr
