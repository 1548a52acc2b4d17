"""Tooth loads from power and speed (``mechcli.core.gear.loads``).

Every case is checked twice: against numbers computed by hand in the config comments of
configs/ch5/loads-*.toml (no published worked example with printed force values was
found; the problem data are cited there), and against an independent model written here
(power balance, the normal force in the base tangent plane, a 3-D vector model of the
worm's flank with its friction force, the bevel's separating force in the plane of the
axes).
"""

import math

import numpy as np
import pytest

from mechcli.core.gear import loads as ld
from mechcli.core.gear.helical import helical_pair
from mechcli.core.gear.problems import solve_bevel, solve_helical, solve_pair, solve_worm
from mechcli.spec.gear import read_gear_spec
from tests.conftest import CONFIGS

CH5 = CONFIGS / "ch5"
RPM = math.pi / 30


def _solve(name):
    spec = read_gear_spec(CH5 / name)
    solver = {"pair": solve_pair, "helical": solve_helical, "worm": solve_worm,
              "bevel": solve_bevel}[spec.kind]
    return spec, solver(spec.problem)


# -- the configs' hand-computed numbers (tolerance: half a unit of the last printed digit) --
def test_helical_loads_of_the_exam_problem():
    # configs/ch5/loads-helical.toml, computed by hand there
    _, sol = _solve("loads-helical.toml")
    f = sol.loads
    assert f.v == pytest.approx(8.37758, abs=5e-6)
    assert f.T1 == pytest.approx(397.887, abs=5e-4)
    assert f.Ft1 == pytest.approx(5968.31, abs=5e-3)
    assert f.Fr1 == pytest.approx(2413.65, abs=5e-3)
    assert f.Fa1 == pytest.approx(2890.58, abs=5e-3)
    assert f.Fn == pytest.approx(7057.05, abs=5e-3)
    assert f.T2 == pytest.approx(795.775, abs=5e-4)


def test_spur_loads_of_the_half_horsepower_pair():
    # configs/ch5/loads-spur.toml: Wt = 33000 hp / v = 11.671 lbf (hand), 1 lbf = 4.4482216 N
    _, sol = _solve("loads-spur.toml")
    f = sol.loads
    assert f.Ft1 / 4.4482216152605 == pytest.approx(11.671, abs=5e-4)
    assert f.Fr1 == pytest.approx(18.8962, abs=5e-5)
    assert f.Fa1 == 0.0
    assert f.T2 == pytest.approx(3.95606, abs=5e-6)


def test_bevel_loads_of_exercise_5_9_geometry():
    # configs/ch5/loads-bevel.toml, computed by hand there
    _, sol = _solve("loads-bevel.toml")
    f = sol.loads
    assert f.d_force1 == pytest.approx(86.5836e-3, abs=5e-8)
    assert f.Ft1 == pytest.approx(689.312, abs=5e-4)
    assert (f.Fr1, f.Fa1) == pytest.approx((224.402, 112.201), abs=5e-4)
    assert (f.Fr2, f.Fa2) == pytest.approx((112.201, 224.402), abs=5e-4)


def test_worm_loads_and_efficiency_of_exercise_5_8_geometry():
    # configs/ch5/loads-worm.toml, computed by hand there
    _, sol = _solve("loads-worm.toml")
    f = sol.loads
    assert math.degrees(f.friction_angle) == pytest.approx(3.0440, abs=5e-5)
    assert f.efficiency == pytest.approx(0.64936, abs=5e-6)
    assert f.efficiency_reverse == pytest.approx(0.46574, abs=5e-6)
    assert f.self_locking is False
    assert f.Ft1 == pytest.approx(752.654, abs=5e-4)
    assert f.Ft2 == pytest.approx(4887.46, abs=5e-3)
    assert f.Fr1 == pytest.approx(1788.40, abs=5e-3)
    assert f.T2 == pytest.approx(684.244, abs=5e-4)


# -- independent checks -------------------------------------------------------------------
@pytest.mark.parametrize("name", ["loads-helical.toml", "loads-spur.toml", "loads-bevel.toml",
                                  "loads-worm.toml"])
def test_power_balance(name):
    # the tangential force at the pitch point times its speed is the input power, and the
    # output power is eta times it (no friction but the worm's: eta = 1 otherwise)
    spec, sol = _solve(name)
    f = sol.loads
    p = spec.problem.drive
    assert f.Ft1 * f.v == pytest.approx(p.power, rel=1e-12)
    assert f.T1 * f.omega1 == pytest.approx(p.power, rel=1e-12)
    assert f.T2 * f.omega2 == pytest.approx(f.efficiency * p.power, rel=1e-12)
    assert f.omega1 / f.omega2 == pytest.approx(sol.z2 / sol.z1 if name != "loads-spur.toml"
                                                else 2.0, rel=1e-12)


@pytest.mark.parametrize("xn", [(0.0, 0.0), (0.4, 0.3), (-0.2, 0.1)])
@pytest.mark.parametrize("beta_deg", [0.0, 12.0, 30.0])
def test_helical_normal_force_lies_in_the_base_tangent_plane(beta_deg, xn):
    # Independent: the normal force of a helical (or spur) pair acts in the plane tangent to
    # both base cylinders at the base helix angle beta_b (sin beta_b = sin beta cos an), so
    # Fn = T1 / (rb1 cos beta_b) and its axial part Fa = Fn sin beta_b, whatever the shift
    # (the pitch point moves, the base cylinders do not).
    an, mn, z1, z2 = math.radians(20), 4e-3, 19, 47
    power, omega = 7.5e3, 1440 * RPM
    if beta_deg:
        hp = helical_pair(z1, z2, mn, an, beta=math.radians(beta_deg), xn1=xn[0], xn2=xn[1])
        beta, at, awt, a, aw = hp.beta, hp.alpha_t, hp.alpha_wt, hp.a, hp.a_w
    else:
        at = an
        beta = 0.0
        theta = 2 * math.tan(an) * sum(xn) / (z1 + z2) + math.tan(an) - an
        # inverse involute by bisection (independent of mechcli's)
        lo, hi = 0.0, 1.5
        for _ in range(200):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if math.tan(mid) - mid < theta else (lo, mid)
        awt = (lo + hi) / 2
        a = mn * (z1 + z2) / 2
        aw = a * math.cos(an) / math.cos(awt)
    d1, d2 = z1 * mn / math.cos(beta), z2 * mn / math.cos(beta)
    f = ld.parallel_loads(power, omega, z1, z2, d1, d2, d1 * aw / a, d2 * aw / a, awt, beta)
    rb1 = d1 * math.cos(at) / 2
    beta_b = math.asin(math.sin(beta) * math.cos(an))
    t1 = power / omega
    fn = t1 / (rb1 * math.cos(beta_b))
    assert f.Fn == pytest.approx(fn, rel=1e-12)
    assert f.Fa1 == pytest.approx(fn * math.sin(beta_b), rel=1e-12, abs=1e-9)
    assert f.T2 / f.T1 == pytest.approx(z2 / z1, rel=1e-14)


def _worm_flank_force(gamma, alpha_n, mu, worm_drives=True):
    """Independent 3-D model of the worm's flank at the pitch point.

    Unit vectors at the contact: t along the worm's surface velocity, a along the worm's
    axis, r radially out of the worm.  The thread (h = cos g t + sin g a) is the direction
    of the worm's sliding on the wheel; the wheel's surface moves along -a at v1 tan g.
    The flank normal has the normal pressure angle an to the tangent plane.  Returns the
    force of the worm on the wheel for a unit normal force, and the powers (per unit v1)
    into the wheel and out of the worm (worm driving) or the reverse.
    """
    t, a, r = np.eye(3)
    h = math.cos(gamma) * t + math.sin(gamma) * a
    normal = math.cos(alpha_n) * (math.sin(gamma) * t - math.cos(gamma) * a) \
        + math.sin(alpha_n) * r
    u2 = -math.tan(gamma) * a       # wheel's pitch-point velocity for v1 = 1
    u1 = t
    if worm_drives:
        force = normal + mu * h      # worm pushes the wheel, friction drags it along h
        return force, force @ u1, force @ u2
    force = -normal + mu * h         # the wheel pushes the worm: the worm resists
    return force, -force @ u2, -force @ u1


@pytest.mark.parametrize("z1,q,mu", [(1, 10, 0.05), (2, 8, 0.08), (4, 10, 0.02),
                                     (1, 18, 0.12)])
def test_worm_efficiency_from_the_force_vectors(z1, q, mu):
    # Independent: eta = power into the wheel / power out of the worm from the 3-D flank
    # force with its friction; the components of that force scaled to Ft1 = 2 T1/d1 are the
    # worm's tangential, axial (= wheel tangential) and radial forces.
    m, z2, ax = 5e-3, 40, math.radians(20)
    gamma = math.atan(z1 / q)
    alpha_n = math.atan(math.tan(ax) * math.cos(gamma))
    force, p_worm, p_wheel = _worm_flank_force(gamma, alpha_n, mu)
    f = ld.worm_loads(3e3, 960 * RPM, z1, z2, q * m, z2 * m, gamma, ax, mu)
    assert f.efficiency == pytest.approx(p_wheel / p_worm, rel=1e-12)
    scale = f.Ft1 / force[0]
    assert f.Ft2 == pytest.approx(-force[1] * scale, rel=1e-12)   # wheel's tangential
    assert f.Fa1 == pytest.approx(-force[1] * scale, rel=1e-12)
    assert f.Fr1 == pytest.approx(force[2] * scale, rel=1e-12)
    assert f.Fn == pytest.approx(scale, rel=1e-12)                 # the unit normal force
    # the same efficiency from the force components: Ft2 v2 / (Ft1 v1), v2/v1 = tan g
    assert f.efficiency == pytest.approx(f.Ft2 * math.tan(gamma) / f.Ft1, rel=1e-12)
    # and the closed form tan g / tan(g + phi)
    assert f.efficiency == pytest.approx(math.tan(gamma) / math.tan(gamma + f.friction_angle),
                                         rel=1e-12)
    # wheel driving: the reverse efficiency of the same vector model
    _, p_in, p_out = _worm_flank_force(gamma, alpha_n, mu, worm_drives=False)
    assert f.efficiency_reverse == pytest.approx(p_out / p_in, rel=1e-12)
    assert f.self_locking == (p_out <= 0)


def test_worm_self_locks_when_the_lead_angle_is_below_the_friction_angle():
    # hand: z1 = 1, q = 18: g = atan(1/18) = 3.1798 deg; mu = 0.08 -> phi ~ 4.87 deg > g
    gamma = math.atan(1 / 18)
    an = ld.worm_normal_pressure_angle(math.radians(20), gamma)
    eta, eta_rev, phi = ld.worm_efficiency(gamma, an, 0.08)
    assert phi > gamma and eta_rev < 0 and 0 < eta < 0.5
    # at mu = 0 nothing is lost either way
    assert ld.worm_efficiency(gamma, an, 0.0)[:2] == pytest.approx((1.0, 1.0), rel=1e-15)


def test_worm_that_cannot_drive_is_refused():
    gamma = math.radians(50)
    with pytest.raises(ld.LoadError) as exc:
        ld.worm_loads(1e3, 100.0, 8, 40, 0.05, 0.2, gamma, math.radians(20), 1.0)
    assert exc.value.reason == "no_drive"


@pytest.mark.parametrize("sigma_deg", [90.0, 70.0, 100.0])
def test_bevel_separating_force_in_the_plane_of_the_axes(sigma_deg):
    # Independent: the separating force Ft tan(alpha) is perpendicular to the common cone
    # element g = (cos d1, sin d1, 0) in the plane of the axes e1 = x and
    # e2 = (cos S, sin S, 0); its components along and across each axis are the axial and
    # radial forces of that gear (equal and opposite on the two gears).
    from mechcli.core.gear.bevel import bevel_pair
    b = bevel_pair(17, 43, 4e-3, math.radians(20), sigma=math.radians(sigma_deg))
    f = ld.bevel_loads(2.2e3, 1450 * RPM, b.z1, b.z2, b.d(b.z1), b.d(b.z2), b.R, 0.25 * b.R,
                       b.alpha, b.delta1, b.delta2)
    s = math.radians(sigma_deg)
    sep = f.Ft1 * math.tan(b.alpha) * np.array([math.sin(b.delta1), -math.cos(b.delta1), 0])
    e1, e2 = np.array([1.0, 0, 0]), np.array([math.cos(s), math.sin(s), 0])
    assert f.Fa1 == pytest.approx(abs(sep @ e1), rel=1e-12)
    assert f.Fr1 == pytest.approx(math.sqrt(sep @ sep - (sep @ e1) ** 2), rel=1e-12)
    assert f.Fa2 == pytest.approx(abs(sep @ e2), rel=1e-12)
    assert f.Fr2 == pytest.approx(math.sqrt(sep @ sep - (sep @ e2) ** 2), rel=1e-12)
    assert f.Fn == pytest.approx(math.hypot(f.Ft1, np.linalg.norm(sep)), rel=1e-12)
    # the mean cone: Ft dm1 / 2 = T1
    assert f.Ft1 * f.d_force1 / 2 == pytest.approx(f.T1, rel=1e-14)
    assert f.d_force1 == pytest.approx(b.d(b.z1) * (1 - 0.125), rel=1e-14)


def test_bevel_face_width_not_below_the_cone_distance_is_refused():
    with pytest.raises(ld.LoadError) as exc:
        ld.bevel_loads(1e3, 100.0, 20, 40, 0.1, 0.2, 0.11, 0.11, math.radians(20), 0.46, 1.1)
    assert exc.value.reason == "bevel_face"


# -- profile shifts for a centre distance: helical pairs, equal-strength split -------------
from mechcli.core.gear import measurement as ms  # noqa: E402
from mechcli.core.gear import strength as st  # noqa: E402
from tests.reference.independent_root_factors import independent_root_factors  # noqa: E402

#: 齿形系数 Y_Fa 及应力校正系数 Y_Sa (china-reducers.com, 机械设计 课程内容 6/21): alpha = 20 deg,
#: rho = 0.38 m, unshifted gears.  The table is read off the ISO chart to two decimals and
#: its own rows scatter by up to 0.017 about the closed form (z = 27 ... 29), so Y_Fa is
#: checked to 0.02 and Y_Sa to 0.01 rather than to half a printed digit.
ROOT_TABLE = {17: (2.97, 1.52), 18: (2.91, 1.53), 19: (2.85, 1.54), 20: (2.80, 1.55),
              21: (2.76, 1.56), 22: (2.72, 1.57), 23: (2.69, 1.575), 24: (2.65, 1.58),
              25: (2.62, 1.59), 26: (2.60, 1.595), 27: (2.57, 1.60), 28: (2.55, 1.61),
              29: (2.53, 1.62), 30: (2.52, 1.625), 35: (2.45, 1.65), 40: (2.40, 1.67),
              45: (2.35, 1.68), 50: (2.32, 1.70), 60: (2.28, 1.73), 70: (2.24, 1.75),
              80: (2.22, 1.77), 90: (2.20, 1.78), 100: (2.18, 1.79), 150: (2.14, 1.83),
              200: (2.12, 1.865), 100000: (2.06, 1.97)}   # the table's z = infinity


@pytest.mark.parametrize("z", sorted(ROOT_TABLE))
def test_root_factors_match_the_published_table(z):
    y_fa, y_sa = ROOT_TABLE[z]
    r = st.root_factors(z, 1e-3, math.radians(20), 0.0, (z + 2) * 1e-3)
    assert r.Y_Fa == pytest.approx(y_fa, abs=0.02)
    assert r.Y_Sa == pytest.approx(y_sa, abs=0.01)


@pytest.mark.parametrize("z,x", [(20, 0.0), (17, 0.3), (40, -0.2), (25, 0.6), (60, 0.0),
                                 (13.7, 0.45)])
def test_root_factors_match_a_generated_fillet(z, x):
    # tests/reference/independent_root_factors.py generates the fillet numerically; the
    # closed forms agree to the finite differences of its curvature (about 1e-6)
    a, m = math.radians(20), 2e-3
    da = (z + 2 * (1 + x)) * m
    y_fa, y_sa, s_fn, h_fa, rho_f = independent_root_factors(z, m, a, x, da, 1.25 * m,
                                                             0.38 * m)
    r = st.root_factors(z, m, a, x, da, h_fP=1.25 * m, rho_fP=0.38 * m)
    assert (r.s_Fn, r.h_Fa) == pytest.approx((s_fn, h_fa), rel=1e-8)
    assert r.rho_F == pytest.approx(rho_f, rel=1e-5)
    assert r.Y_Fa == pytest.approx(y_fa, rel=1e-8)
    assert r.Y_Sa == pytest.approx(y_sa, rel=1e-5)


def test_helical_root_factors_are_those_of_the_virtual_spur_gear():
    # zn = z / (cos^2 beta_b cos beta), tip d_an = d_n + da - d (ISO 6336-3), checked on the
    # generated fillet of that virtual gear
    a, m, z, x, beta = math.radians(20), 3e-3, 19, 0.25, math.radians(18)
    d = z * m / math.cos(beta)
    da = d + 2 * (1 + x) * m
    r = st.root_factors(z, m, a, x, da, beta, h_fP=1.25 * m, rho_fP=0.38 * m)
    beta_b = math.asin(math.sin(beta) * math.cos(a))
    zn = z / (math.cos(beta_b) ** 2 * math.cos(beta))
    y_fa, y_sa, *_ = independent_root_factors(zn, m, a, x, zn * m + da - d, 1.25 * m,
                                              0.38 * m)
    assert r.zn == pytest.approx(zn, rel=1e-14)
    assert (r.Y_Fa, r.Y_Sa) == pytest.approx((y_fa, y_sa), rel=1e-5)


def _zero_backlash_residual(z1, z2, mn, an, beta, xn1, xn2, a_w):
    """Independent: transverse tooth thicknesses on the operating pitch circles of a pair at
    a' fill one transverse pitch there: s'1 + s'2 - p' (m)."""
    at = math.atan(math.tan(an) / math.cos(beta))
    a = mn * (z1 + z2) / (2 * math.cos(beta))
    awt = math.acos(a * math.cos(at) / a_w)
    inv = lambda v: math.tan(v) - v  # noqa: E731
    total = 0.0
    for z, x in ((z1, xn1), (z2, xn2)):
        d = z * mn / math.cos(beta)
        st_ = (math.pi / 2 + 2 * x * math.tan(an)) * mn / math.cos(beta)
        dw = d * math.cos(at) / math.cos(awt)
        total += dw * (st_ / d + inv(at) - inv(awt))
    return total - math.pi * (z1 * mn / math.cos(beta)) * math.cos(at) / math.cos(awt) / z1


def test_helical_shift_sum_of_the_khk_example():
    # configs/ch5/shift-helical-centre-distance.toml: KHK (bolsover.com table) mn = 3,
    # beta = 30 deg, z = 12/60, a' = 125: xn1 + xn2 = 0.09809, a_wt = 23.1126 deg
    an, beta = math.radians(20), math.radians(30)
    x_sum, awt = ms.normal_shift_sum_for_centre_distance(12, 60, 3e-3, an, beta, 0.125)
    assert x_sum == pytest.approx(0.09809, abs=5e-6)
    assert math.degrees(awt) == pytest.approx(23.1126, abs=5e-5)
    assert _zero_backlash_residual(12, 60, 3e-3, an, beta, x_sum, 0.0, 0.125) == \
        pytest.approx(0.0, abs=1e-15)
    _, sol = _solve("shift-helical-centre-distance.toml")
    assert sol.a_w == pytest.approx(0.125, rel=1e-13)   # the forward mesh: back to a'


@pytest.mark.parametrize("delta_mm", [-0.5, 1.0, 3.0])
@pytest.mark.parametrize("beta_deg", [0.0, 10.0, 25.0])
def test_shift_sum_gives_a_zero_backlash_mesh(beta_deg, delta_mm):
    an, beta, mn = math.radians(20), math.radians(beta_deg), 2e-3
    a_w = mn * 60 / (2 * math.cos(beta)) + delta_mm * 1e-3
    x_sum, _ = ms.normal_shift_sum_for_centre_distance(17, 43, mn, an, beta, a_w)
    assert (x_sum < 0) == (delta_mm < 0)
    for x1 in (0.0, 0.3, x_sum / 2):
        res = _zero_backlash_residual(17, 43, mn, an, beta, x1, x_sum - x1, a_w)
        assert res == pytest.approx(0.0, abs=1e-15)


def _helical_problem(**kw):
    from mechcli.spec.gear import HelicalProblem
    base = dict(z1=17, z2=43, mn=2e-3, alpha_n=math.radians(20), han_star=1.0, cn_star=0.25,
                beta=math.radians(15), a_w=0.0630, b=None)
    base.update(kw)
    return HelicalProblem(**base)


def test_equal_strength_split_equalises_the_root_stress():
    sol = solve_helical(_helical_problem(x_split="strength"))
    sh = sol.shift
    f1, f2 = sh.factors
    assert f1.Y_FaSa == pytest.approx(f2.Y_FaSa, rel=1e-9)
    assert sh.x1 + sh.x2 == pytest.approx(sh.x_sum, abs=1e-15)
    # a moderate sum (a = 62.117 mm, a' = 63 mm): the pinion, with fewer teeth and the
    # steeper Y_Fa Y_Sa, gets the larger shift
    assert 0.3 < sh.x_sum < 0.6 and sh.x1 > sh.x2
    assert sol.a_w == pytest.approx(0.0630, rel=1e-12)
    # the same factors computed afresh for the designed gears
    an, beta, mn = math.radians(20), math.radians(15), 2e-3
    rho = 0.25 / (1 - math.sin(an)) * mn    # the rack's full tip round (0.380 mn)
    for f, z, x in ((f1, 17, sh.x1), (f2, 43, sh.x2)):
        d = z * mn / math.cos(beta)
        g = st.root_factors(z, mn, an, x, d + 2 * (1 + x) * mn, beta, h_fP=1.25 * mn,
                            rho_fP=rho)
        assert g.Y_FaSa == pytest.approx(f.Y_FaSa, rel=1e-12)


def test_equal_teeth_split_equally():
    # by symmetry (hand): z1 = z2 splits any sum in halves, for every rule
    for rule in ("strength", "sliding"):
        sol = solve_helical(_helical_problem(z1=30, z2=30, a_w=0.0630, x_split=rule))
        assert sol.shift.x1 == pytest.approx(sol.shift.x_sum / 2, abs=1e-9)


def test_helical_sliding_split_balances_the_specific_sliding():
    sol = solve_helical(_helical_problem(x_split="sliding"))
    assert sol.shift.zeta1 == pytest.approx(sol.shift.zeta2, abs=1e-9)
    x1_given = solve_helical(_helical_problem(x_split="x1", xn1=0.2))
    assert (x1_given.xn1, x1_given.xn2) == pytest.approx((0.2, x1_given.shift.x_sum - 0.2))


def test_spur_strength_split_of_the_config():
    # configs/ch5/shift-equal-strength.toml: z = 20/20 at a = 40 -> x1 = x2 = 0 (hand), and
    # the table's Y_Fa = 2.80, Y_Sa = 1.55 at z = 20
    _, sol = _solve("shift-equal-strength.toml")
    sh = sol.shift
    assert (sh.x1, sh.x2) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert sh.factors[0].Y_Fa == pytest.approx(2.80, abs=0.005)
    assert sh.factors[0].Y_Sa == pytest.approx(1.55, abs=0.005)


# -- a pointed tooth: the contact path on the nominal tip circle (tip = "nominal") --------
def test_pointed_pinion_contact_ratio_on_the_nominal_tip_circle():
    # configs/ch5/pointed-tip-nominal.toml, computed by hand there: eps = 1.2617 on the
    # nominal tip circles, 1.2128 where the pinion's flanks meet (the default)
    import dataclasses
    spec, sol = _solve("pointed-tip-nominal.toml")
    pr = sol[0]
    assert pr.g1.nominal_tip and pr.g2.nominal_tip
    assert pr.epsilon_alpha == pytest.approx(1.2617, abs=5e-5)
    assert pr.g1.tooth_thickness(pr.g1.ra) < 0          # really pointed
    effective = solve_pair(dataclasses.replace(spec.problem, tip="effective"))[0]
    assert effective.epsilon_alpha == pytest.approx(1.2128, abs=5e-5)
    assert effective.g1.r_tip_effective == pytest.approx(20.3854e-3, abs=5e-8)
    assert pr.g1.r_tip_effective == pr.g1.ra


@pytest.mark.parametrize("tip", ["nominal", "effective"])
def test_mesh_kinematics_count_the_chosen_contact_path(tip):
    # Independent: turning the pair through one base pitch, the mean number of contact
    # points of the mesh kinematics (pair.mesh_positions) is the contact ratio of the
    # chosen tip model
    import dataclasses

    from mechcli.core.gear.pair import mesh_positions
    spec, _ = _solve("pointed-tip-nominal.toml")
    pr = solve_pair(dataclasses.replace(spec.problem, tip=tip))[0]
    n = 20000
    phi = np.arange(n) * (2 * math.pi / pr.g1.z) / n
    mean = mesh_positions(pr, phi).in_contact.sum(axis=1).mean()
    assert mean == pytest.approx(pr.epsilon_alpha, abs=2e-4)


# -- the equal-strength split when Y_Fa Y_Sa is not monotonic (review defect 1) ------------
def _pair_spec(tmp_path, body, name="p.toml"):
    path = tmp_path / name
    path.write_text('command = "gear"\nunits = "mm"\n[pair]\n' + body, encoding="utf-8")
    return read_gear_spec(path)


def _strength_split(tmp_path, z1, z2, m, a_w):
    spec = _pair_spec(tmp_path, f'z1 = {z1}\nz2 = {z2}\nm = {m}\na_w = {a_w}\n'
                      'x_split = "strength"\n')
    return solve_pair(spec.problem).shift


def _fillet_y(z, x):
    """Y_Fa Y_Sa of a gear (m = 1, standard rack, tip d + 2 (1 + x) m) from the numerically
    generated fillet of tests/reference (independent of mechcli's closed forms; its
    finite-difference fillet radius drifts by up to 1 % where the rack round's centre
    nears the rolling line, x ~ 0.87, so it is used away from there)."""
    m, a = 1.0, math.radians(20)
    rho = 0.25 / (1 - math.sin(a)) * m       # the rack's full tip round, c* m/(1 - sin a)
    y_fa, y_sa, *_ = independent_root_factors(z, m, a, x, (z + 2 * (1 + x)) * m, 1.25 * m,
                                              rho)
    return y_fa * y_sa


def _model_y(z, x):
    """Y_Fa Y_Sa of the same gear from mechcli's closed forms (checked against the published
    table and the generated fillet above)."""
    a = math.radians(20)
    return st.root_factors(z, 1.0, a, x, z + 2 * (1 + x), h_fP=1.25,
                           rho_fP=0.25 / (1 - math.sin(a))).Y_FaSa


def _equal_splits(y, z1, z2, x_sum, lo=-1.5, hi=1.5, step=0.05):
    """Independent scan: every x1 with y(z1, x1) = y(z2, x_sum - x1), by brentq on each sign
    change of a grid of *step*; returns [(x1, common y)]."""
    from scipy.optimize import brentq

    def diff(x1):
        return y(z1, x1) - y(z2, x_sum - x1)

    n = int(round((hi - lo) / step))
    grid = [lo + (hi - lo) * i / n for i in range(n + 1)]
    vals = [diff(x) for x in grid]
    roots = [brentq(diff, u, v, xtol=1e-12) for u, v, fu, fv in
             zip(grid, grid[1:], vals, vals[1:]) if fu * fv < 0]
    roots += [x for x, f in zip(grid, vals) if f == 0]   # a grid point on a root (symmetry)
    return [(r, y(z1, r)) for r in sorted(roots)]


@pytest.mark.parametrize("z,a_w", [(80, 80), (100, 100)])
def test_strength_split_of_a_symmetric_pair_with_many_teeth_is_symmetric(tmp_path, z, a_w):
    # z1 = z2 at a' = a: x_sum = 0; by symmetry x1 = x2 = 0 equalises Y_Fa Y_Sa.  The review
    # found the old bisection returning x1 = -0.516 (80/80) and -0.853 (100/100): the mirror
    # splits (x1, -x1) are also equal but weaker (larger common Y_Fa Y_Sa)
    sh = _strength_split(tmp_path, z, z, 1, a_w)
    assert (sh.x_sum, sh.x1, sh.x2) == (0.0, 0.0, 0.0)
    splits = _equal_splits(_model_y, z, z, 0.0)
    assert [r for r, _ in splits] == pytest.approx(
        {80: [-0.516, 0.0, 0.516], 100: [-0.8525, 0.0, 0.8525]}[z], abs=5e-4)   # review
    assert min(splits, key=lambda s: s[1])[0] == pytest.approx(0.0, abs=1e-9)
    assert sh.factors[0].Y_FaSa == pytest.approx(_fillet_y(z, 0.0), rel=1e-5)


def test_strength_split_of_eighty_teeth_mirror_split_is_weaker_on_the_fillet():
    # the generated fillet confirms the mirror splits of 80/80 are equal and weaker:
    # Y(80, 0.516) = Y(80, -0.516) = 3.957 > Y(80, 0) = 3.939
    y0, y_plus, y_minus = _fillet_y(80, 0.0), _fillet_y(80, 0.516), _fillet_y(80, -0.516)
    assert y_plus == pytest.approx(y_minus, abs=5e-4)
    assert (y0, y_plus) == pytest.approx((3.939, 3.957), abs=5e-4)


def test_strength_split_takes_the_strongest_of_several_equal_splits(tmp_path):
    # z = 60/150, m = 1, a' = a = 105: the review's roots x1 = -0.230, 0.020, 0.905 with the
    # common Y_Fa Y_Sa 3.978, 3.951, 3.872 (found again by the independent scan); none is
    # undercut (x_min = 1 - z sin^2(20 deg)/2 = -2.51 and -7.77), pointed or interfering:
    # the strongest (smallest common value) is the last
    splits = _equal_splits(_model_y, 60, 150, 0.0)
    assert [r for r, _ in splits] == pytest.approx([-0.230, 0.020, 0.905], abs=5e-4)
    assert [c for _, c in splits] == pytest.approx([3.978, 3.951, 3.872], abs=5e-4)
    sh = _strength_split(tmp_path, 60, 150, 1, 105)
    assert sh.x1 == pytest.approx(splits[2][0], abs=1e-9)
    assert sh.x2 == pytest.approx(-splits[2][0], abs=1e-9)
    assert sh.factors[0].Y_FaSa == pytest.approx(sh.factors[1].Y_FaSa, rel=1e-9)
    # the first two lie where the generated fillet is accurate: it finds them too
    fillet = _equal_splits(_fillet_y, 60, 150, 0.0, -0.5, 0.5, 0.25)
    assert [r for r, _ in fillet] == pytest.approx([-0.230, 0.020], abs=2e-3)


def test_strength_split_of_few_teeth_has_one_root(tmp_path):
    # z = 14/28, m = 3, a' = 64 (a = 63): x_sum = 0.3523 (inv a' - inv a formula); the
    # difference is monotonic (one sign change on the generated fillet's 0.1 grid)
    from scipy.optimize import brentq
    a = math.radians(20)
    aw = math.acos(63 * math.cos(a) / 64)
    x_sum = 42 * ((math.tan(aw) - aw) - (math.tan(a) - a)) / (2 * math.tan(a))

    def diff(x1):
        return _fillet_y(14, x1) - _fillet_y(28, x_sum - x1)

    grid = [0.2 + i / 10 for i in range(0, 12)]   # above x_min(14) = 1 - 7 sin^2 a = 0.181
    vals = [diff(x) for x in grid]
    assert sum(fu * fv < 0 for fu, fv in zip(vals, vals[1:])) == 1
    x1 = brentq(diff, 0.2, 1.3, xtol=1e-8)
    sh = _strength_split(tmp_path, 14, 28, 3, 64)
    assert sh.x_sum == pytest.approx(x_sum, abs=1e-12)
    assert sh.x1 == pytest.approx(x1, abs=1e-6)
    assert sh.x1 > 1 - 14 * math.sin(a) ** 2 / 2          # not undercut


def test_strength_split_of_thirty_teeth_halves_the_sum(tmp_path):
    # z = 30/30, m = 1, a' = 30.5: one root, by symmetry x1 = x2 = x_sum / 2
    sh = _strength_split(tmp_path, 30, 30, 1, 30.5)
    a = math.radians(20)
    aw = math.acos(30 * math.cos(a) / 30.5)
    x_sum = 60 * ((math.tan(aw) - aw) - (math.tan(a) - a)) / (2 * math.tan(a))
    assert (sh.x1, sh.x2) == pytest.approx((x_sum / 2, x_sum / 2), abs=1e-9)
    assert sh.factors[0].Y_FaSa == pytest.approx(_fillet_y(30, x_sum / 2), rel=1e-5)


def test_strength_split_refuses_an_interfering_or_undercut_pair(tmp_path):
    # z = 20/40, m = 2: at a' = 58 the only equal split, x1 = -0.125, lets the wheel's tip
    # pass N1 (hand below); at a' = 57 the only one, x1 = -0.2475, undercuts the pinion
    # (x_min = 1 - 20 sin^2(20 deg)/2 = -0.1698)
    from mechcli.core.gear.pair import MeshError
    a = math.radians(20)
    with pytest.raises(MeshError) as exc:
        _strength_split(tmp_path, 20, 40, 2, 58)
    v = exc.value.values
    assert v["what"] == "strength_rejected" and len(v["splits"]) == 1
    x1, why = v["splits"][0]
    assert why["what"] == "interference" and why["gear"] == 2
    # hand: x_sum from the inv formula, x2 = x_sum - x1, ra2 = 40 + 2 (1 + x2), rb2 = 40 cos a,
    # N1N2 = a' sin a'; the tip passes N1 by sqrt(ra2^2 - rb2^2) - N1N2 (mm)
    aw = math.acos(60 * math.cos(a) / 58)
    x_sum = 60 * ((math.tan(aw) - aw) - (math.tan(a) - a)) / (2 * math.tan(a))
    ra2, rb2 = 40 + 2 * (1 + x_sum - x1), 40 * math.cos(a)
    assert why["excess"] == pytest.approx((math.sqrt(ra2 ** 2 - rb2 ** 2) - 58 * math.sin(aw))
                                          * 1e-3, rel=1e-9)
    assert why["excess"] > 1.5e-3
    with pytest.raises(MeshError) as exc:
        _strength_split(tmp_path, 20, 40, 2, 57)
    (x1, why), = exc.value.values["splits"]
    assert why["what"] == "undercut" and why["gear"] == 1
    assert why["x_min"] == pytest.approx(1 - 20 * math.sin(a) ** 2 / 2, abs=1e-12)
    assert x1 < why["x_min"]


def test_given_x1_with_interference_leaves_the_sliding_there_undefined(tmp_path):
    # z = 20/40, m = 2, a' = 58, x1 = 0: x2 = x_sum = -0.8553; the wheel's tip passes N1
    # (the contact would start below the pinion's base circle): zeta1 is None, not -inf;
    # zeta2 as the hand formula 1 - u rho1/rho2 at the pinion's tip (u = 2)
    spec = _pair_spec(tmp_path, 'z1 = 20\nz2 = 40\nm = 2\na_w = 58\nx_split = "x1"\nx1 = 0\n')
    sol = solve_pair(spec.problem)
    a = math.radians(20)
    aw = math.acos(60 * math.cos(a) / 58)
    n = 58 * math.sin(aw)
    rho1 = math.sqrt(22 ** 2 - (20 * math.cos(a)) ** 2)     # ra1 = 20 + 2 = 22 mm
    assert sol.shift.zeta1 is None
    assert sol.shift.zeta2 == pytest.approx(1 - 2 * rho1 / (n - rho1), rel=1e-9)
    assert sol[0].interference
