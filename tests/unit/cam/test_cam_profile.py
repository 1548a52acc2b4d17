"""Cam profiles: book equations, exact normals, contact by rotation, pressure angle,
curvature, undercut and sizing, each against an independent reference."""

import dataclasses
import math

import numpy as np
import pytest

from mechcli.core.cam.design import design_cam
from mechcli.core.cam.motion import build_program
from mechcli.core.cam.checks import check_cam, max_pressure_angle
from mechcli.core.cam.geometry import (CamGeometryError, Follower, UndercutError, cam_profile,
                                       curvature_and_rate, pressure_angle_and_rate,
                                       working_outline)
from mechcli.core.cam.sizing import (size_flat_base_radius, size_oscillating_base_radius,
                                     translating_base_radius_min)

RAD = math.radians
MM = 1e-3

EX41 = build_program([("rise", RAD(100), "parabolic", 60 * MM), ("dwell", RAD(60), None, 0),
                      ("return", RAD(90), "cosine", 60 * MM), ("dwell", RAD(110), None, 0)],
                     60 * MM)
EX42 = build_program([("rise", RAD(120), "cosine", 20 * MM), ("return", RAD(150), "cosine",
                                                               20 * MM),
                      ("dwell", RAD(90), None, 0)], 20 * MM)
EX43 = build_program([("rise", RAD(180), "cosine", RAD(25)),
                      ("return", RAD(180), "sine", RAD(25))], RAD(25), angular=True)
SMOOTH = build_program([("rise", RAD(110), "modified-sine", 15 * MM), ("dwell", RAD(40), None, 0),
                        ("return", RAD(130), "poly4567", 15 * MM), ("dwell", RAD(80), None, 0)],
                       15 * MM)

ROLLER41 = Follower("translating", "roller", 40 * MM, 1, e=15 * MM, rr=10 * MM)
FLAT42 = Follower("translating", "flat", 30 * MM, 1)
OSC43 = Follower("oscillating", "roller", 25 * MM, 1, rr=8 * MM, a=60 * MM, l=50 * MM)

DELTA = np.linspace(0, 2 * np.pi, 3601)


def test_eq_4_1_and_4_2_pitch_and_working_curves():
    p = cam_profile(ROLLER41, EX41, DELTA)
    e, r0, rr = 15 * MM, 40 * MM, 10 * MM
    s0 = math.sqrt(r0 ** 2 - e ** 2)
    d = DELTA
    x = (s0 + p.s) * np.sin(d) + e * np.cos(d)
    y = (s0 + p.s) * np.cos(d) - e * np.sin(d)
    np.testing.assert_allclose(p.pitch, [x, y], atol=1e-15)
    # eq. 4-2/4-3 with the derivative of eq. 4-1 (the book's cam1 normal, correct ds/dδ)
    dx = (p.s1 - e) * np.sin(d) + (s0 + p.s) * np.cos(d)
    dy = (p.s1 - e) * np.cos(d) - (s0 + p.s) * np.sin(d)
    n = np.hypot(dx, dy)
    np.testing.assert_allclose(p.work, [x + rr * dy / n, y - rr * dx / n], atol=1e-15)


def test_eq_4_4_flat_faced_profile():
    p = cam_profile(FLAT42, EX42, DELTA)
    d, r0 = DELTA, 30 * MM
    np.testing.assert_allclose(p.work, [(r0 + p.s) * np.sin(d) + p.s1 * np.cos(d),
                                        (r0 + p.s) * np.cos(d) - p.s1 * np.sin(d)], atol=1e-15)


def test_eq_4_5_oscillating_pitch_curve_and_eq_4_6():
    p = cam_profile(OSC43, EX43, DELTA)
    a, l = 60 * MM, 50 * MM
    assert math.degrees(OSC43.phi0) == pytest.approx(24.1468, abs=5e-5)
    th = DELTA + p.s + OSC43.phi0
    np.testing.assert_allclose(p.pitch, [a * np.sin(DELTA) - l * np.sin(th),
                                         a * np.cos(DELTA) - l * np.cos(th)], atol=1e-15)
    # at δ = 0 the roller centre is on the base circle
    assert np.hypot(*p.pitch[:, 0]) == pytest.approx(25 * MM, rel=1e-14)


@pytest.mark.parametrize("fol, prog", [(ROLLER41, EX41), (OSC43, EX43),
                                       (dataclasses.replace(OSC43, rotation=-1), EX43),
                                       (Follower("translating", "roller", 30 * MM, -1,
                                                 e=-8 * MM, rr=6 * MM), SMOOTH)])
def test_working_curve_is_offset_along_exact_normal(fol, prog):
    p = cam_profile(fol, prog, DELTA)
    # distance rr, along the normal
    np.testing.assert_allclose(np.hypot(*(p.pitch - p.work)), fol.rr, rtol=1e-12)
    np.testing.assert_allclose(np.hypot(*p.normal), 1.0, rtol=1e-14)
    # the normal is perpendicular to the pitch curve (central differences of the samples)
    h = 1e-7
    st = DELTA[1:-1]
    fwd = cam_profile(fol, prog, st + h).pitch
    bwd = cam_profile(fol, prog, st - h).pitch
    tangent = (fwd - bwd) / (2 * h)
    cos = np.sum(tangent * p.normal[:, 1:-1], axis=0) / np.hypot(*tangent)
    smooth = np.ones_like(st, dtype=bool)
    for seg in prog.segments:
        for d0, _, _ in seg.pieces():
            smooth &= np.abs(st - d0) > 1e-6
    assert np.max(np.abs(cos[smooth])) < 1e-7


def _contact_distance(fol, prog, delta_probe, n=200001):
    """Independent check: turn the working profile back by the cam angle and measure."""
    dense = np.linspace(0, 2 * np.pi, n)
    work = cam_profile(fol, prog, dense).work
    out = []
    for d in delta_probe:
        c, s = math.cos(fol.rotation * d), math.sin(fol.rotation * d)
        xy = np.array([[c, -s], [s, c]]) @ work  # cam turned by the cam angle
        st = prog.evaluate(np.array([d]))
        if fol.motion == "translating":
            centre = np.array([fol.e, fol.s0 + st.s[0]])
        else:
            th = fol.phi0 + st.s[0]
            centre = np.array([-fol.arm_side * fol.l * math.sin(th),
                               fol.a - fol.l * math.cos(th)])
        out.append(np.min(np.hypot(xy[0] - centre[0], xy[1] - centre[1])))
    return np.array(out)


@pytest.mark.parametrize("fol, prog", [(ROLLER41, EX41), (OSC43, EX43),
                                       (dataclasses.replace(OSC43, rotation=-1), EX43)])
def test_roller_touches_cam_at_prescribed_lift(fol, prog):
    probes = np.radians([13.0, 47.0, 95.0, 171.0, 204.0, 233.0, 300.0])
    dist = _contact_distance(fol, prog, probes)
    # chord error of 2e5 samples is < 1e-9 m; the roller neither cuts in nor lifts off
    np.testing.assert_allclose(dist, fol.rr, atol=2e-8)


@pytest.mark.parametrize("rotation", [1, -1])
def test_flat_face_touches_cam_at_prescribed_lift(rotation):
    fol = dataclasses.replace(FLAT42, rotation=rotation)
    work = cam_profile(fol, EX42, np.linspace(0, 2 * np.pi, 200001)).work
    for d in np.radians([10.0, 60.0, 119.0, 200.0, 300.0]):
        c, s = math.cos(rotation * d), math.sin(rotation * d)
        y = s * work[0] + c * work[1]
        expect = 30 * MM + EX42.evaluate(np.array([d])).s[0]
        assert np.max(y) == pytest.approx(expect, abs=1e-9)


def test_clockwise_cam_is_the_mirror_image():
    ccw = cam_profile(ROLLER41, EX41, DELTA)
    cw = cam_profile(dataclasses.replace(ROLLER41, rotation=-1, e=-15 * MM), EX41, DELTA)
    np.testing.assert_allclose(cw.work, [-ccw.work[0], ccw.work[1]], atol=1e-15)
    np.testing.assert_allclose(cw.alpha, ccw.alpha, atol=1e-15)


def test_pressure_angle_translating_eq_7_14():
    for rot, e in ((1, 15 * MM), (1, -15 * MM), (-1, 15 * MM), (-1, -15 * MM)):
        fol = Follower("translating", "roller", 40 * MM, rot, e=e, rr=10 * MM)
        p = cam_profile(fol, EX41, DELTA)
        # favourable side: the offset is subtracted when sigma*e > 0
        ref = np.arctan2(p.s1 - rot * e, fol.s0 + p.s)
        np.testing.assert_allclose(p.alpha, ref, atol=1e-14)


@pytest.mark.parametrize("rotation", [1, -1])
def test_pressure_angle_oscillating_classical_formula(rotation):
    fol = dataclasses.replace(OSC43, rotation=rotation)
    p = cam_profile(fol, EX43, DELTA)
    a, l = fol.a, fol.l
    th = fol.phi0 + p.s
    ref = np.arctan((l * (1 + p.s1) - a * np.cos(th)) / (a * np.sin(th)))
    np.testing.assert_allclose(p.alpha, ref, atol=1e-13)


def test_curvature_textbook_formula_offset_translating():
    p = cam_profile(ROLLER41, EX41, DELTA)
    e, s0 = 15 * MM, ROLLER41.s0
    A, B = s0 + p.s, p.s1 - e
    rho = (A ** 2 + B ** 2) ** 1.5 / (A * (A - p.s2) + B * (2 * p.s1 - e))
    np.testing.assert_allclose(p.rho_pitch, rho, rtol=1e-11)
    np.testing.assert_allclose(p.rho_work, rho - 10 * MM, rtol=1e-11)


@pytest.mark.parametrize("fol, prog", [(ROLLER41, SMOOTH), (OSC43, EX43),
                                       (dataclasses.replace(OSC43, rotation=-1), EX43)])
def test_rates_match_finite_differences(fol, prog):
    d = np.radians(np.linspace(3, 357, 90))
    h = 1e-6
    fd = []
    for f in (pressure_angle_and_rate, curvature_and_rate):
        val, rate = f(fol, *_state(prog, d))
        vp, _ = f(fol, *_state(prog, d + h))
        vm, _ = f(fol, *_state(prog, d - h))
        fd.append(np.max(np.abs((vp - vm) / (2 * h) - rate)) / (np.max(np.abs(rate)) + 1e-30))
    assert max(fd) < 1e-6


def _state(prog, d):
    st = prog.evaluate(d)
    return st.s, st.s1, st.s2, st.s3


def test_example_7_2_max_pressure_angle():
    prog = build_program([("rise", RAD(90), "cosine", 20 * MM), ("dwell", RAD(90), None, 0),
                          ("return", RAD(90), "cosine", 20 * MM), ("dwell", RAD(90), None, 0)],
                         20 * MM)
    fol = Follower("translating", "knife", 40 * MM, 1)
    for step in (RAD(5), RAD(1), RAD(0.01)):
        ext = max_pressure_angle(fol, prog, "rise", step)
        # 例 7-2 prints 22.2077° at 39.2315°
        assert math.degrees(ext.value) == pytest.approx(22.2077, abs=5e-5)
        assert math.degrees(ext.delta) == pytest.approx(39.2315, abs=5e-5)
        # closed form: cos(pi δ/δ0) = (h/2)/(r0 + h/2) = 0.2, tan α = 20 sin x / 48
        x = math.acos(0.2)
        assert ext.delta == pytest.approx(x / math.pi * RAD(90), abs=1e-9)
        assert ext.value == pytest.approx(math.atan(20 * math.sin(x) / 48), abs=1e-13)


def test_refined_maximum_beats_dense_scan():
    fol = dataclasses.replace(OSC43, rotation=-1)
    ext = max_pressure_angle(fol, EX43, "return")
    d = np.linspace(math.pi, 2 * math.pi, 200_001)
    scan = np.max(np.abs(cam_profile(fol, EX43, d).alpha))
    assert ext.value >= scan - 1e-15
    assert ext.value - scan < 1e-9  # a scan of spacing h misses up to ~|α"| h²/8


def test_flat_face_checks_hand_values():
    ch = check_cam(FLAT42, EX42)
    assert ch.rho_work_min.value == pytest.approx(27.5 * MM, abs=1e-15)
    assert math.degrees(ch.rho_work_min.delta) == pytest.approx(120.0, abs=1e-9)
    assert ch.face_width_min == pytest.approx(30 * MM, abs=1e-15)
    assert size_flat_base_radius(EX42) == pytest.approx(2.5 * MM, abs=1e-15)


def test_sizing_translating_residual():
    """At r0_min the largest rise pressure angle equals [α] (to round-off)."""
    for e, rot in ((0.0, 1), (10 * MM, 1), (-10 * MM, 1), (10 * MM, -1)):
        r0 = translating_base_radius_min(EX41, e, rot, RAD(30), RAD(70))
        fol = Follower("translating", "roller", r0, rot, e=e, rr=5 * MM)
        a_r = max_pressure_angle(fol, EX41, "rise").value
        a_t = max_pressure_angle(fol, EX41, "return").value
        assert max(a_r - RAD(30), a_t - RAD(70)) == pytest.approx(0.0, abs=1e-12)
        assert a_r <= RAD(30) + 1e-12 and a_t <= RAD(70) + 1e-12


def test_sizing_exercise_4_2_closed_form():
    prog = build_program([("rise", RAD(120), "uniform", 20 * MM), ("dwell", RAD(60), None, 0),
                          ("return", RAD(90), "parabolic", 20 * MM),
                          ("dwell", RAD(90), None, 0)], 20 * MM)
    r0 = translating_base_radius_min(prog, 0.0, 1, RAD(30))
    assert r0 == pytest.approx(20 * MM / (RAD(120) * math.tan(RAD(30))), rel=1e-13)


def test_sizing_oscillating_residual():
    r0 = size_oscillating_base_radius(OSC43, EX43, RAD(20))
    fol = dataclasses.replace(OSC43, r0=r0)
    assert max_pressure_angle(fol, EX43, "rise").value == pytest.approx(RAD(20), abs=1e-9)


def test_undercut_detected_and_forbidden():
    # tiny base circle, large lift: the pitch curve is sharper than the roller
    segs = [("rise", RAD(60), "cosine", 30 * MM), ("return", RAD(60), "cosine", 30 * MM),
            ("dwell", RAD(240), None, 0)]
    d = design_cam("translating", "roller", 12 * MM, {"rr": 10 * MM, "e": 0.0, "rotation": 1},
                   segs, 30 * MM, step=RAD(1))
    assert d.checks.undercut
    assert d.checks.rho_pitch_min.value < 10 * MM
    assert d.rr_max == pytest.approx(d.checks.rho_pitch_min.value)
    with pytest.raises(UndercutError, match="undercut"):
        design_cam("translating", "roller", 12 * MM, {"rr": 10 * MM, "e": 0.0, "rotation": 1},
                   segs, 30 * MM, step=RAD(1), forbid_undercut=True)
    # the same with a small roller is fine
    d = design_cam("translating", "roller", 12 * MM, {"rr": 1 * MM, "e": 0.0, "rotation": 1},
                   segs, 30 * MM, step=RAD(1))
    assert not d.checks.undercut


def test_flat_face_cusp_detected():
    prog = build_program([("rise", RAD(40), "cosine", 20 * MM), ("return", RAD(40), "cosine",
                                                              20 * MM),
                          ("dwell", RAD(280), None, 0)], 20 * MM)
    ch = check_cam(Follower("translating", "flat", 10 * MM, 1), prog)
    assert ch.undercut and ch.rho_work_min.value < 0
    r0 = size_flat_base_radius(prog)
    ch = check_cam(Follower("translating", "flat", r0, 1), prog)
    assert ch.rho_work_min.value == pytest.approx(0.0, abs=1e-15)


def test_corners_of_the_uniform_law():
    prog = build_program([("rise", RAD(120), "uniform", 20 * MM), ("dwell", RAD(60), None, 0),
                          ("return", RAD(90), "parabolic", 20 * MM),
                          ("dwell", RAD(90), None, 0)], 20 * MM)
    ch = check_cam(Follower("translating", "roller", 20 * MM, 1, rr=5 * MM), prog)
    # the follower jumps outwards at 0 deg (concave corner) and stops at 120 (convex)
    assert [(round(math.degrees(d), 9), c) for d, c in ch.corners] == [(0.0, False),
                                                                        (120.0, True)]


@pytest.mark.parametrize("step", [1.0, 0.1])
def test_working_outline_at_corners_keeps_the_roller_distance(step):
    """Arc in the concave notch, loop cut at the convex edge: every drawn point is at
    least r_r from the pitch curve, and the notch arc is exactly r_r from the corner."""
    from scipy.spatial import cKDTree

    prog = build_program([("rise", RAD(120), "uniform", 20 * MM), ("dwell", RAD(60), None, 0),
                          ("return", RAD(90), "parabolic", 20 * MM),
                          ("dwell", RAD(90), None, 0)], 20 * MM)
    fol = Follower("translating", "roller", 20 * MM, 1, rr=10 * MM)
    p = cam_profile(fol, prog, np.linspace(0, 2 * np.pi, int(round(360 / step)) + 1))
    ch = check_cam(fol, prog)
    out = working_outline(fol, prog, p, ch.corners)
    dense = cam_profile(fol, prog, np.linspace(0, 2 * np.pi, 200001)).pitch
    tree = cKDTree(dense.T, balanced_tree=False, compact_nodes=False)  # fast on curves
    dist, _ = tree.query(out.T)
    assert np.min(dist) > 10 * MM - 1e-7            # no gouging anywhere
    assert np.max(dist) < 10 * MM + 1e-6            # and touching everywhere
    # the untrimmed samples do gouge at the convex edge (that is why the loop is cut)
    raw, _ = tree.query(p.work.T)
    assert np.min(raw) < 10 * MM - 1e-5
    np.testing.assert_allclose(out[:, 0], out[:, -1])


def test_errata_book_program_cam1_return_slope():
    """# ERRATA: cam1 (例 4-1) divides the return's ds/dδ by δ'0 once too often; with that
    slope in eq. (4-3) the working curve is off by up to 1.705 mm (at δ ≈ 206.7°)."""
    p = cam_profile(ROLLER41, EX41, DELTA)
    d, e, s0, rr = DELTA, 15 * MM, ROLLER41.s0, 10 * MM
    ret = (d > RAD(160)) & (d < RAD(250))
    s1_book = np.where(ret, p.s1 / RAD(90), p.s1)
    dx = (s1_book - e) * np.sin(d) + (s0 + p.s) * np.cos(d)
    dy = (s1_book - e) * np.cos(d) - (s0 + p.s) * np.sin(d)
    n = np.hypot(dx, dy)
    book = np.stack([p.pitch[0] + rr * dy / n, p.pitch[1] - rr * dx / n])
    dev = np.hypot(*(book - p.work))
    assert np.max(dev[~ret]) < 1e-15                     # rise and dwells agree
    assert np.max(dev) == pytest.approx(1.705 * MM, abs=5e-4 * MM)
    assert math.degrees(d[np.argmax(dev)]) == pytest.approx(206.7, abs=0.05)


def test_errata_book_program_cam3_roller_offset():
    """# ERRATA: cam3 (例 4-3) moves the roller along (dy, dx)/|.|, not along the normal
    (dy, -dx)/|.|: its 'working curve' passes within 0.003 mm of the roller-centre path
    (it should stay 8 mm away) and is up to 16 mm (2 r_r) from the exact one."""
    from scipy.spatial import cKDTree

    p = cam_profile(OSC43, EX43, DELTA)
    a, l, d = 60 * MM, 50 * MM, DELTA
    th = d + p.s + OSC43.phi0
    dx = a * np.cos(d) - l * (1 + p.s1) * np.cos(th)
    dy = -a * np.sin(d) + l * (1 + p.s1) * np.sin(th)
    n = np.hypot(dx, dy)
    book = np.stack([p.pitch[0] + 8 * MM * dy / n, p.pitch[1] + 8 * MM * dx / n])
    assert np.max(np.hypot(*(book - p.work))) == pytest.approx(16 * MM, rel=1e-6)
    dense = cam_profile(OSC43, EX43, np.linspace(0, 2 * np.pi, 200001)).pitch
    tree = cKDTree(dense.T, balanced_tree=False, compact_nodes=False)
    assert tree.query(book.T)[0].min() < 0.01 * MM
    assert tree.query(p.work.T)[0].min() == pytest.approx(8 * MM, abs=1e-7)


@pytest.mark.parametrize("rotation, arm, sign", [(1, 1, 1), (-1, -1, 1), (-1, 1, -1),
                                                 (1, -1, -1)])
def test_oscillating_arm_side_classical_formulas(rotation, arm, sign):
    """Arm swinging with the cam: tan α = (l(1 + φ') − a cos θ)/(a sin θ); against it:
    tan α = (l(1 − φ') − a cos θ)/(a sin θ)."""
    fol = dataclasses.replace(OSC43, rotation=rotation, arm=arm)
    p = cam_profile(fol, EX43, DELTA)
    a, l = fol.a, fol.l
    th = fol.phi0 + p.s
    ref = np.arctan((l * (1 + sign * p.s1) - a * np.cos(th)) / (a * np.sin(th)))
    np.testing.assert_allclose(np.abs(p.alpha), np.abs(ref), atol=1e-13)
    dist = _contact_distance(fol, EX43, np.radians([30.0, 150.0, 250.0]), n=100001)
    np.testing.assert_allclose(dist, fol.rr, atol=1e-7)


def test_velocity_jumps_the_follower_cannot_reproduce():
    """Roller at a convex pitch corner (ρ = 0 < r_r) and flat face where ds/dδ drops:
    motion distortion (undercut); a knife edge follows any corner."""
    prog = build_program([("rise", RAD(120), "uniform", 20 * MM), ("dwell", RAD(60), None, 0),
                          ("return", RAD(90), "uniform", 20 * MM),
                          ("dwell", RAD(90), None, 0)], 20 * MM)
    roller = check_cam(Follower("translating", "roller", 40 * MM, 1, rr=5 * MM), prog)
    # convex corners where the pitch curve turns inwards: end of rise, start of return
    assert [round(math.degrees(d), 9) for d in roller.distorted] == [120.0, 180.0]
    assert roller.undercut and roller.rho_pitch_min.value > 5 * MM
    flat = check_cam(Follower("translating", "flat", 40 * MM, 1), prog)
    # ds/dδ drops at the end of the rise and at the start of the return
    assert [round(math.degrees(d), 9) for d in flat.distorted] == [120.0, 180.0]
    knife = check_cam(Follower("translating", "knife", 40 * MM, 1), prog)
    assert knife.distorted == () and not knife.undercut
    d = design_cam("translating", "roller", 40 * MM, {"rr": 5 * MM, "e": 0.0, "rotation": 1},
                   [(s.kind, s.span, s.law, abs(s.lift)) for s in prog.segments], 20 * MM,
                   step=RAD(1))
    assert d.rr_max == 0.0
    with pytest.raises(UndercutError) as info:
        design_cam("translating", "roller", 40 * MM, {"rr": 5 * MM, "e": 0.0, "rotation": 1},
                   [(s.kind, s.span, s.law, abs(s.lift)) for s in prog.segments], 20 * MM,
                   step=RAD(1), forbid_undercut=True)
    assert info.value.reason == "distorted" and info.value.values["contact"] == "roller"
    assert [round(math.degrees(d), 9) for d in info.value.values["at"]] == [120.0, 180.0]


def test_sizing_that_does_not_bound_r0_is_a_clear_error():
    """Long cosine rise and return: s + s'' > 0 everywhere, so any r0 > 0 gives a convex
    flat-faced cam; without r0 there is nothing to draw -> UnsolvableError, not a crash."""
    segs = [("rise", RAD(180), "cosine", 20 * MM), ("return", RAD(180), "cosine", 20 * MM)]
    assert size_flat_base_radius(build_program(segs, 20 * MM)) == 0.0
    with pytest.raises(CamGeometryError, match="do not bound the base radius"):
        design_cam("translating", "flat", None, {"e": 0.0, "rotation": 1}, segs, 20 * MM,
                   step=RAD(1), size_base_radius=True)
    d = design_cam("translating", "flat", None, {"e": 0.0, "rotation": 1}, segs, 20 * MM,
                   step=RAD(1), size_base_radius=True, round_up=5 * MM)
    assert d.follower.r0 == pytest.approx(5 * MM)
