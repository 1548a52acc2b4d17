"""Spur gear, pair and generated-profile geometry against independent checks (ch. 5)."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from mechcli.core.gear.spur import GearGeometryError, spur_gear
from mechcli.core.gear.bevel import bevel_pair
from mechcli.core.gear.generation import (cutter_positions, generation_plan,
                                          swept_half_space)
from mechcli.core.gear.helical import helical_pair
from mechcli.core.gear.pair import (MeshError, check_mountings, design_teeth_from_ratio,
                                    gear_pair, zero_backlash_pressure_angle)
from mechcli.core.gear.profile import (flank_chordal_deviation, gear_outline,
                                       generated_tooth)
from mechcli.core.gear.worm import worm_drive
from mechcli.core.gear.involute import involute_function

A20 = math.radians(20)
MM = 1e-3


def test_example_5_3_circles():
    g = spur_gear(35, 5 * MM, A20)
    assert g.d == pytest.approx(0.175)
    assert g.db == pytest.approx(0.175 * math.cos(A20))
    assert g.da == pytest.approx(0.185)
    assert g.df == pytest.approx(0.1625)
    assert g.s + g.e == pytest.approx(g.p)
    assert g.h == pytest.approx(11.25 * MM)


def test_thickness_identities():
    g = spur_gear(18, 10 * MM, A20, x=0.3)
    # on the reference circle the thickness is s = m (pi/2 + 2 x tan alpha)
    assert g.tooth_thickness(g.r) == pytest.approx(g.s, rel=1e-14)
    # thickness + space = circular pitch at any radius
    r = np.linspace(g.rb, g.ra, 7)
    assert_allclose(g.tooth_thickness(r) + g.space_width(r), 2 * np.pi * r / g.z, rtol=1e-14)
    # zero thickness at the pointed radius
    assert abs(g.tooth_thickness(g.pointed_radius)) < 1e-15


def test_exercise_5_1_by_chord_construction():
    # independent: half tooth angle at the base circle = s/(2r) + inv(alpha)
    g = spur_gear(18, 10 * MM, A20)
    sb = 2 * g.rb * (math.pi / (2 * g.z) + math.tan(A20) - A20)
    assert g.tooth_thickness(g.rb) == pytest.approx(sb, rel=1e-14)
    assert g.tooth_thickness(g.ra) == pytest.approx(6.8166 * MM, abs=5e-8)


def test_z_min_and_x_min():
    g = spur_gear(9, 10 * MM, A20)
    assert g.z_min == pytest.approx(17.097, abs=1e-3)
    assert g.x_min == pytest.approx((17.0972 - 9) / 17.0972, abs=1e-4)
    assert g.undercut
    assert not spur_gear(9, 10 * MM, A20, x=g.x_min).undercut


def test_base_pitch_equal_and_contact_ratio_from_path_of_contact():
    g1 = spur_gear(20, 5 * MM, A20)
    g2 = spur_gear(80, 5 * MM, A20)
    pr = gear_pair(g1, g2, a_w=0.255)
    assert g1.pb == pytest.approx(g2.pb, rel=1e-15)
    assert g1.pb == pytest.approx(2 * math.pi * g1.rb / g1.z, rel=1e-15)
    # independent: B1B2 = sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a' sin(alpha')
    b1b2 = (math.sqrt(g1.ra ** 2 - g1.rb ** 2) + math.sqrt(g2.ra ** 2 - g2.rb ** 2)
            - pr.a_w * math.sin(pr.alpha_w))
    assert pr.epsilon_alpha == pytest.approx(b1b2 / g1.pb, rel=1e-13)
    assert pr.epsilon_alpha == pytest.approx(0.765, abs=5e-4)
    # pitch circles roll: d1' + d2' = 2 a', d2'/d1' = z2/z1
    assert pr.dw1 + pr.dw2 == pytest.approx(2 * pr.a_w, rel=1e-15)
    assert pr.dw2 / pr.dw1 == pytest.approx(4.0, rel=1e-15)


def test_zero_backlash_exercise_5_3():
    g1 = spur_gear(10, 10 * MM, A20, x=0.45)
    g2 = spur_gear(12, 10 * MM, A20, x=0.31)
    pr = gear_pair(g1, g2)
    assert math.degrees(pr.alpha_w) == pytest.approx(27.3831, abs=5e-5)
    assert pr.a_w == pytest.approx(116.4098 * MM, abs=5e-8)
    assert abs(pr.backlash) < 1e-15
    # moving apart opens backlash at the rate 2 tan(alpha') (finite difference)
    h = 1e-7
    far = gear_pair(g1, g2, a_w=pr.a_w + h)
    assert far.backlash / h == pytest.approx(2 * math.tan(pr.alpha_w), rel=1e-5)
    with pytest.raises(MeshError):
        gear_pair(g1, g2, a_w=pr.a_w * (1 - 1e-9))


def test_alpha_w_and_a_w_are_inverse():
    g1, g2 = spur_gear(30, 20 * MM, A20), spur_gear(40, 20 * MM, A20)
    pr = gear_pair(g1, g2, a_w=0.725)
    back = gear_pair(g1, g2, alpha_w=pr.alpha_w)
    assert back.a_w == pytest.approx(0.725, rel=1e-15)
    assert math.degrees(pr.alpha_w) == pytest.approx(24.8666, abs=5e-5)


def test_no_contact_and_zero_backlash_limits():
    g1, g2 = spur_gear(20, 5 * MM, A20), spur_gear(80, 5 * MM, A20)
    with pytest.raises(MeshError, match="no contact"):
        gear_pair(g1, g2, a_w=0.262)
    assert zero_backlash_pressure_angle(g1, g2) == pytest.approx(A20, rel=1e-15)


def test_design_from_ratio_exercise_5_2():
    assert design_teeth_from_ratio(1.6, 0.078, 0.003) == (20, 32)
    with pytest.raises(MeshError, match="not whole"):
        design_teeth_from_ratio(1.7, 0.078, 0.003)
    with pytest.raises(MeshError, match="whole number"):
        design_teeth_from_ratio(1.6, 0.0785, 0.003)


def test_mountings_that_jam_are_refused_by_index_with_their_bound():
    g1, g2 = spur_gear(20, 5 * MM, A20), spur_gear(80, 5 * MM, A20)
    check_mountings(g1, g2, (0.250, 0.255), (A20, math.radians(25)))
    with pytest.raises(MeshError) as err:
        check_mountings(g1, g2, (0.255, 0.245))
    v = err.value.values
    assert err.value.reason == "mounting" and (v["given"], v["index"]) == ("a_w", 1)
    assert v["a0"] == pytest.approx(0.250, rel=1e-12) and not v["internal"] and not v["thin"]
    with pytest.raises(MeshError) as err:   # alpha' = 15 deg: a' = 243.21 mm < a0
        check_mountings(g1, g2, (0.255,), (A20, math.radians(15)))
    v = err.value.values
    assert (v["given"], v["index"], v["alpha_w"]) == ("alpha_w", 1, math.radians(15))
    assert v["a_w"] * 1e3 == pytest.approx(243.21, abs=5e-3)
    ring = spur_gear(60, 4 * MM, A20, internal=True)
    pinion = spur_gear(20, 4 * MM, A20)
    for a in (0.070, 0.081):   # outside (a cos alpha, a0] = (75.18, 80] mm
        with pytest.raises(MeshError) as err:
            check_mountings(pinion, ring, (a,))
        assert err.value.values["lo"] * 1e3 == pytest.approx(75.1754, abs=1e-4)
    thin1, thin2 = spur_gear(12, MM, A20, x=-0.5), spur_gear(30, MM, A20, x=-0.5)
    check_mountings(thin1, thin2, (0.020,))
    with pytest.raises(MeshError) as err:   # no a' jams: the base circles bound a'
        check_mountings(thin1, thin2, (0.0197,))
    assert err.value.values["thin"]


def test_the_spec_reads_a_design_from_the_ratio_without_solving(tmp_path):
    from mechcli.core.gear.problems import solve_pair
    from mechcli.spec.gear import read_gear_spec
    path = tmp_path / "g.toml"
    path.write_text('command = "gear"\nunits = "mm"\n[pair]\nratio = 1.7\na_w = 78\nm = 3\n',
                    encoding="utf-8")
    p = read_gear_spec(path).problem   # 1.7 gives no whole z1: the core says so, not the spec
    assert (p.z1, p.z2, p.ratio, p.designed, p.a_w_keys) == (None, None, 1.7, True,
                                                             ("pair.a_w",))
    with pytest.raises(MeshError, match="not whole"):
        solve_pair(p)


@pytest.mark.parametrize("z, x", [(9, 0.0), (9, 0.75), (35, 0.0), (12, -0.2)])
def test_generated_profile_matches_brute_force_sweep(z, x):
    g = spur_gear(z, 10 * MM, A20, x=x)
    tooth = generated_tooth(g)
    lim = 1.5 * math.sqrt(g.ra ** 2 - g.rf ** 2) / g.r + math.pi / g.z
    phi = np.linspace(-lim, lim, 2000)
    rho = np.linspace(tooth.r_form + 1e-3 * g.m, tooth.r_top, 200)
    eta = swept_half_space(g, rho, phi)
    analytic = math.pi / g.z - tooth.half_tooth(rho)
    # above the form circle: the involute; sampling error falls as (step)^2
    assert np.max(np.abs(eta - analytic) * rho) < 5e-8 * g.m / 0.01
    # and on the fillet too the swept space never exceeds the analytic one
    rho_f = np.linspace(g.rf * (1 + 1e-9), tooth.r_form, 100)
    eta_f = swept_half_space(g, rho_f, phi)
    assert np.all(eta_f <= math.pi / g.z - tooth.half_tooth(rho_f) + 1e-12)
    assert np.max(np.abs(eta_f - (math.pi / g.z - tooth.half_tooth(rho_f)))) < 3e-3


def test_cutter_never_enters_the_finished_tooth():
    g = spur_gear(9, 10 * MM, A20)
    tooth = generated_tooth(g)
    cx, cy = cutter_positions(g, generation_plan(math.radians(126), math.radians(2)).phi)
    f = np.linspace(0, 1, 40)
    x = (cx[:, :-1, None] * (1 - f) + cx[:, 1:, None] * f).ravel()
    y = (cy[:, :-1, None] * (1 - f) + cy[:, 1:, None] * f).ravel()
    rho, ang = np.hypot(x, y), np.arctan2(x, -y)
    pitch = 2 * math.pi / g.z
    rel = (ang - pitch / 2) % pitch
    rel = np.minimum(rel, pitch - rel)
    m = (rho > g.rf * (1 + 1e-9)) & (rho < tooth.r_top)
    assert np.all(rel[m] >= tooth.half_tooth(rho[m]) - 1e-12)


def test_undercut_measure_and_its_cure():
    g = spur_gear(9, 10 * MM, A20)
    t0 = generated_tooth(g)
    assert t0.undercut and t0.r_form > g.rb
    assert 0.04 < t0.undercut_fraction < 0.06
    # the sharp cutter corner sits (ha* + c* - x) m inside r:
    # no undercut once that is <= r sin^2(alpha)
    x_cure = 1.25 - 9 * math.sin(A20) ** 2 / 2
    assert generated_tooth(spur_gear(9, 10 * MM, A20, x=x_cure - 1e-3)).undercut
    t1 = generated_tooth(spur_gear(9, 10 * MM, A20, x=x_cure + 1e-3))
    assert not t1.undercut and t1.undercut_fraction == 0.0


def test_outline_is_closed_and_has_z_fold_symmetry():
    g = spur_gear(35, 5 * MM, A20)
    out = gear_outline(generated_tooth(g), 40)
    assert out.x[0] == out.x[-1] and out.y[0] == out.y[-1]
    assert np.all(np.isfinite(out.x))
    r = np.hypot(out.x, out.y)
    assert r.min() == pytest.approx(g.rf, rel=1e-12)
    assert r.max() == pytest.approx(g.ra, rel=1e-12)
    n = (out.x.size - 1) // g.z
    c, s = math.cos(2 * math.pi / g.z), math.sin(2 * math.pi / g.z)
    assert_allclose(c * out.x[:n] - s * out.y[:n], out.x[n:2 * n], atol=1e-15)


def test_radial_root_is_the_books_construction():
    g = spur_gear(35, 5 * MM, A20)
    out = gear_outline(generated_tooth(g), 10, root="radial")
    assert out.flank_r[0] == pytest.approx(g.rf)
    assert out.flank_r[1] == pytest.approx(g.r - g.m)      # r_w = (z/2 - 1) m, eq. (5-10)
    assert out.flank_psi[0] == out.flank_psi[1]            # radial line WF, eq. (5-15)


def test_chordal_deviation_falls_as_n_squared():
    g = spur_gear(35, 5 * MM, A20)
    d10 = flank_chordal_deviation(g, g.rb, g.ra, 10)
    d40 = flank_chordal_deviation(g, g.rb, g.ra, 40)
    assert 8 < d10 / d40 < 20
    assert d40 < 2.5e-6                                     # 2.3 µm at m = 5 mm


def test_pointed_and_impossible_gears():
    g = spur_gear(10, 10 * MM, A20, x=1.0)
    assert g.tooth_thickness(g.ra) < 0
    assert generated_tooth(g).tip_pointed
    with pytest.raises(GearGeometryError):
        spur_gear(2, 10 * MM, A20, x=-1.0)
    with pytest.raises(GearGeometryError, match="pointed"):
        generated_tooth(spur_gear(20, 10 * MM, math.radians(33), c_star=0.25))


def test_helical_exercises():
    hp = helical_pair(21, 22, 2 * MM, A20, a_w=55 * MM)
    assert math.degrees(hp.beta) == pytest.approx(38.5727, abs=5e-5)
    assert hp.a == pytest.approx(55 * MM, rel=1e-14)
    hp = helical_pair(20, 40, 8 * MM, A20, beta=math.radians(15), b=30 * MM)
    assert hp.d(20) == pytest.approx(165.6442 * MM, abs=5e-8)
    # transverse base pitch equals normal base pitch / cos(beta_b) (independent identity)
    beta_b = math.atan(math.tan(hp.beta) * math.cos(hp.alpha_t))
    pbt = math.pi * hp.mt * math.cos(hp.alpha_t)
    pbn = math.pi * hp.mn * math.cos(hp.alpha_n)
    assert pbt == pytest.approx(pbn / math.cos(beta_b), rel=1e-14)


def test_worm_and_bevel():
    w = worm_drive(1, 40, d2=0.28, q=10)
    assert w.m == pytest.approx(0.007)
    assert w.lead == pytest.approx(math.pi * 0.007)
    assert w.a == pytest.approx(0.175)
    b = bevel_pair(20, 40, 5 * MM, A20)
    assert b.delta1 + b.delta2 == pytest.approx(math.pi / 2)
    # both pitch cones share the cone distance: R = d2 / (2 sin delta2)
    assert b.R == pytest.approx(b.d(40) / (2 * math.sin(b.delta2)), rel=1e-14)


def test_involute_function_consistent_with_gear_thickness():
    g = spur_gear(25, 4 * MM, A20)
    r = 0.051
    a = math.acos(g.rb / r)
    assert g.half_tooth_angle(r) == pytest.approx(
        g.s / g.d + involute_function(A20) - involute_function(a), rel=1e-14)


@pytest.mark.parametrize("x1, x2", [(0.0, 0.0), (0.3, 0.2), (-0.2, 0.5)])
def test_internal_pair_zero_backlash_and_path_of_contact(x1, x2):
    g1 = spur_gear(20, 4 * MM, A20, x=x1)
    g2 = spur_gear(60, 4 * MM, A20, x=x2, internal=True)
    assert g2.da < g2.d < g2.df
    pr = gear_pair(g1, g2)
    # the zero-backlash formula (signed z2) and the thickness formulas agree
    assert abs(pr.backlash) < 1e-15
    # for a ring, moving the pinion outwards closes the backlash: rate -2 tan(alpha')
    h = 1e-7
    closer = gear_pair(g1, g2, a_w=pr.a_w - h)
    assert closer.backlash / h == pytest.approx(2 * math.tan(closer.alpha_w), rel=1e-5)
    with pytest.raises(MeshError, match="jam"):
        gear_pair(g1, g2, a_w=pr.a_w * (1 + 1e-9))
    # epsilon from the path of contact: N1N2 + (pinion tip beyond N1) - (ring tip from N2)
    path = (pr.a_w * math.sin(pr.alpha_w) + math.sqrt(g1.ra ** 2 - g1.rb ** 2)
            - math.sqrt(g2.ra ** 2 - g2.rb ** 2))
    assert pr.epsilon_alpha == pytest.approx(path / g1.pb, rel=1e-13)
    # ring tooth + ring space = pitch, and the ring tooth widens outwards
    r = np.linspace(g2.ra, g2.rf, 5)
    assert_allclose(g2.tooth_thickness(r) + g2.space_width(r), 2 * np.pi * r / g2.z, rtol=1e-14)
    assert np.all(np.diff(g2.tooth_thickness(r)) > 0)


def test_internal_gear_needs_its_tip_outside_the_base_circle():
    with pytest.raises(GearGeometryError, match="inside the base circle"):
        spur_gear(30, 4 * MM, A20, internal=True)
    spur_gear(34, 4 * MM, A20, internal=True)
    with pytest.raises(MeshError, match="ring"):
        gear_pair(spur_gear(40, 4 * MM, A20), spur_gear(40, 4 * MM, A20, internal=True))


def test_ring_outline_radii():
    from mechcli.core.gear.profile import ring_outline
    g = spur_gear(60, 4 * MM, A20, internal=True)
    out = ring_outline(g, 20)
    r = np.hypot(out.x, out.y)
    assert r.min() == pytest.approx(g.ra, rel=1e-12)
    assert r.max() == pytest.approx(g.rf, rel=1e-12)


def test_tip_shortening_restores_the_standard_clearance():
    from mechcli.core.gear.pair import tip_shortened
    g1 = spur_gear(10, 10 * MM, A20, x=0.45)
    g2 = spur_gear(12, 10 * MM, A20, x=0.31)
    pr = gear_pair(g1, g2)
    assert pr.delta_y > 0
    short, dy = tip_shortened(pr)
    assert dy == pytest.approx(pr.delta_y)
    # a' - ra1 - rf2 = c* m once the tips lose delta_y m (independent of the shift values)
    assert_allclose(short.clearances, [g1.c, g1.c], rtol=1e-12)
    assert all(c < g1.c for c in pr.clearances)
    # standard gears at a' = a: nothing to shorten
    std = gear_pair(spur_gear(20, 5 * MM, A20), spur_gear(80, 5 * MM, A20))
    assert tip_shortened(std)[0] is std


def test_bevel_with_a_cone_past_90_degrees_is_refused():
    from mechcli.core.errors import UnsolvableError
    with pytest.raises(UnsolvableError, match="crown or internal"):
        bevel_pair(5, 7, 1 * MM, A20, sigma=math.radians(170))
    b = bevel_pair(20, 40, 5 * MM, A20, sigma=math.radians(60))
    assert b.delta1 + b.delta2 == pytest.approx(math.radians(60))
    assert math.sin(b.delta1) / math.sin(b.delta2) == pytest.approx(20 / 40)


@pytest.mark.parametrize("a_w, eps", [(0.250, 1.6913), (0.255, 0.7650)])
def test_mesh_kinematics_reproduces_the_contact_ratio(a_w, eps):
    # independent of the 表 5-2 formula: turn the gears, count the points of contact
    from mechcli.core.gear.pair import mesh_positions
    g1, g2 = spur_gear(20, 5 * MM, A20), spur_gear(80, 5 * MM, A20)
    pr = gear_pair(g1, g2, a_w=a_w)
    mesh = mesh_positions(pr, np.linspace(0, 2 * math.pi / 20, 2000, endpoint=False))
    counts = mesh.count
    assert counts.mean() == pytest.approx(eps, abs=1e-3)
    assert (counts == 0).any() == (eps < 1)
    # every contact point lies on a pinion flank and on a wheel flank (within 1e-15 m)
    for i in range(0, 2000, 97):
        p1, p2, pts = mesh.phi1[i], mesh.phi2[i], mesh.contact(i)
        for centre, gear, turn, pt in [((0.0, 0.0), g1, p1, q) for q in pts] + \
                                      [((0.0, a_w), g2, p2, q) for q in pts]:
            d = pt - np.array(centre)
            rho = math.hypot(*d)
            rel = (math.atan2(d[1], d[0]) - math.pi / 2 - turn
                   - float(gear.half_tooth_angle(rho))) % (2 * math.pi / gear.z)
            rel = min(rel, 2 * math.pi / gear.z - rel)
            assert rel * rho < 1e-15
