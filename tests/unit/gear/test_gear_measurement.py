"""Tooth-thickness measurement and the shifts of a pair for a centre distance (issue 19).

Every number says where it comes from: a published worked example (SDP/SI "Elements of
Metric Gear Technology" section 10; MachineCalcs' span example; the KHK profile-shift
example as tabulated by bolsover.com; easyengcalc's backlash rule), or an independent
second implementation below (``_independent_*``: brute-force geometry on the tooth
outline, importing nothing from mechcli) where no published number was found (over
pins, helical span, balanced sliding, backlash with allowances).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from mechcli.core.gear.measurement import (ToothForm, allowances_for_backlash,
                                           backlash_from_allowances, chordal_at_radius,
                                           chordal_at_reference, ideal_pin_diameter,
                                           over_pins, shift_sum_for_centre_distance, span,
                                           span_teeth, specific_sliding_at_roots,
                                           split_balanced_sliding)
from tests.conftest import run_inprocess

A20 = math.radians(20)


def _inv(a):
    return math.tan(a) - a


# -- independent second implementation: the tooth outline, measured by brute force ------
def _half_angle(r, rb, s_over_d, alpha):
    """Half the angle a tooth subtends at radius r (transverse), from the involute."""
    return s_over_d + _inv(alpha) - _inv(math.acos(rb / r))


def _independent_span(z, m, alpha, x, k, e=0.0):
    """Caliper width over k teeth: the span centred on +y, jaws normal to x, width =
    2 max over the outer flank of x (the minimum over jaw directions is the symmetric
    one); maximised over the flank radius."""
    rb = m * z * math.cos(alpha) / 2
    ra = m * z / 2 + (1 + x) * m
    s_over_d = (m * (math.pi / 2 + 2 * x * math.tan(alpha)) - e) / (m * z)
    centre = (k - 1) * math.pi / z
    f = lambda r: -r * math.sin(centre + _half_angle(r, rb, s_over_d, alpha))  # noqa: E731
    r = np.linspace(rb * (1 + 1e-12), ra, 4001)
    i = int(np.argmin([f(v) for v in r]))
    res = minimize_scalar(f, bounds=(r[max(i - 1, 0)], r[min(i + 1, r.size - 1)]),
                          method="bounded", options={"xatol": 1e-13})
    return -2 * res.fun


def _independent_pins(z, m, alpha, x, dp):
    """Pin centre on the axis of a space, where its distance to the flank is dp/2
    (bisection on the centre radius, nearest flank point by a bounded search)."""
    rb = m * z * math.cos(alpha) / 2
    ra = m * z / 2 + (1 + x) * m
    s_over_d = (math.pi / 2 + 2 * x * math.tan(alpha)) / z
    space = math.pi / z   # the space's axis, the tooth centred at 0

    def flank(r):
        a = _half_angle(r, rb, s_over_d, alpha)
        return np.array([r * math.sin(a), r * math.cos(a)])

    def gap(rc):
        c = rc * np.array([math.sin(space), math.cos(space)])
        d = lambda r: float(np.hypot(*(flank(r) - c)))  # noqa: E731
        rr = np.linspace(rb * (1 + 1e-12), ra * 1.3, 3001)
        i = int(np.argmin([d(v) for v in rr]))
        res = minimize_scalar(d, bounds=(rr[max(i - 1, 0)], rr[min(i + 1, rr.size - 1)]),
                              method="bounded", options={"xatol": 1e-14})
        return res.fun - dp / 2

    rc = brentq(gap, rb, ra * 1.3, xtol=1e-14)
    dm = 2 * rc
    return dm + dp if z % 2 == 0 else dm * math.cos(math.pi / (2 * z)) + dp


# -- chordal thickness (published) ---------------------------------------------------
def test_chordal_thickness_of_a_spur_gear_sdp_table_10_1():
    # SDP/SI "Elements of Metric Gear Technology" Table 10-1: m = 10, z = 12, x = +0.3:
    # s = 17.8918, s_j = 17.8256, h_j = 13.6657 (ha = 13.000)
    g = ToothForm(12, 10.0, A20, 0.3, ra=60 + 13.0)
    assert g.s_n == pytest.approx(17.8918, abs=5e-5)
    s_bar, h_bar = chordal_at_reference(g)
    assert s_bar == pytest.approx(17.8256, abs=5e-5)
    assert h_bar == pytest.approx(13.6657, abs=5e-5)


def test_chordal_thickness_of_a_helical_gear_sdp_table_10_3():
    # SDP/SI Table 10-3: mn = 5, an = 20°, beta = 25°, z = 16, xn = +0.2: ha = 6.0000,
    # sn = 8.5819, zv = 21.4928, s_j = 8.5728, h_j = 6.1712
    g = ToothForm(16, 5.0, A20, 0.2, math.radians(25))
    g = ToothForm(16, 5.0, A20, 0.2, math.radians(25), ra=g.d / 2 + 6.0)
    assert (g.s_n, g.zv) == pytest.approx((8.5819, 21.4928), abs=5e-5)
    assert chordal_at_reference(g) == pytest.approx((8.5728, 6.1712), abs=5e-5)


def test_chordal_at_the_reference_radius_is_the_reference_chordal():
    # closed form: at r = d/2 the chordal thickness at a radius is the reference one
    g = ToothForm(12, 10.0, A20, 0.3, ra=73.0)
    assert chordal_at_radius(g, 60.0) == pytest.approx(chordal_at_reference(g), rel=1e-13)
    # at the tip the chordal height is the sagitta r (1 - cos psi) only
    s_bar, h_bar = chordal_at_radius(g, 73.0)
    psi = math.asin(s_bar / (2 * 73.0))
    assert h_bar == pytest.approx(73.0 * (1 - math.cos(psi)), rel=1e-12)


# -- span (published and independent) --------------------------------------------------
def test_span_of_a_standard_spur_gear_machinecalcs():
    # MachineCalcs worked example: z = 20, m = 2, 20°: k = 3, W = 15.321, d_c = 40.59;
    # over 4 teeth 21.225 (the difference is the base pitch 5.904)
    g = ToothForm(20, 2.0, A20)
    sp = span(g)
    assert (sp.k, sp.W, sp.d_contact) == (3, pytest.approx(15.321, abs=5e-4),
                                         pytest.approx(40.59, abs=5e-3))
    assert span(g, 4).W == pytest.approx(21.225, abs=5e-4)
    assert span(g, 4).W - sp.W == pytest.approx(math.pi * 2 * math.cos(A20), rel=1e-13)


@pytest.mark.parametrize("z", [8, 12, 17, 20, 31, 45, 60, 100, 200])
def test_span_count_unshifted_is_the_textbook_rule(z):
    # the usual rule for unshifted gears: k = round(z alpha/180° + 0.5)
    assert span_teeth(ToothForm(z, 1.0, A20)) == math.floor(z * 20 / 180 + 0.5 + 0.5)


@pytest.mark.parametrize("z, x, e", [(20, 0.0, 0.0), (24, 0.4, 0.0), (12, 0.6, 0.05),
                                     (57, -0.3, 0.1)])
def test_span_against_the_outline(z, x, e):
    # independent: the caliper width over the tooth outline (brute force)
    g = ToothForm(z, 3.0, A20, x, allowance=e)
    sp = span(g)
    assert sp.W == pytest.approx(_independent_span(z, 3.0, A20, x, sp.k, e), rel=1e-9)


def test_span_of_a_helical_gear_is_the_transverse_span_times_cos_beta_b():
    # independent: the transverse section is an involute spur profile of mt, at, xt = xn
    # mn/mt; the normal base tangent length is the transverse one times cos(beta_b)
    beta = math.radians(25)
    g = ToothForm(16, 5.0, A20, 0.2, beta)
    mt, at = 5.0 / math.cos(beta), g.alpha_t
    xt = 0.2 * 5.0 / mt
    sp = span(g)
    wt = _independent_span(16, mt, at, xt, sp.k)
    # the transverse rack has the thickness of the normal one / cos beta: xt as above holds
    assert sp.W == pytest.approx(wt * math.cos(g.beta_b), rel=1e-9)
    assert sp.b_min == pytest.approx(sp.W * math.sin(g.beta_b), rel=1e-15)


def test_allowance_reduces_the_span_by_the_backlash_cut():
    # easyengcalc "Base Tangent Length": cutting each gear deeper by dt = B / (2 sin a)
    # reduces W by exactly B.  A radial infeed dt thins the tooth by E = 2 dt tan a.
    b_cut = 0.1
    dt = b_cut / (2 * math.sin(A20))
    g0, g1 = ToothForm(30, 4.0, A20), ToothForm(30, 4.0, A20, allowance=2 * dt * math.tan(A20))
    assert span(g0).W - span(g1).W == pytest.approx(b_cut, rel=1e-12)


# -- over pins (independent) ---------------------------------------------------------------
@pytest.mark.parametrize("z, x", [(20, 0.0), (21, 0.0), (12, 0.3), (35, -0.2), (9, 0.5)])
def test_over_pins_against_the_outline(z, x):
    g = ToothForm(z, 2.0, A20, x)
    pins = over_pins(g)
    assert pins.M == pytest.approx(_independent_pins(z, 2.0, A20, x, pins.dp), rel=1e-9)


def test_ideal_pin_touches_on_the_measuring_circle():
    # closed form: the default pin touches on d + 2 x m; for x = 0 at 20° it is ~1.72 m,
    # close to the standard 1.728 m (AGMA) and 1.75 m (tandwiel.info) pins
    for z, x in [(20, 0.0), (12, 0.3), (40, -0.4)]:
        g = ToothForm(z, 1.0, A20, x)
        assert over_pins(g).d_contact == pytest.approx(z + 2 * x, rel=1e-12)
    assert ideal_pin_diameter(ToothForm(20, 1.0, A20)) == pytest.approx(1.7244, abs=1e-4)


def test_helical_balls_reduce_to_spur_pins_at_zero_helix():
    g0 = ToothForm(20, 2.0, A20, 0.1, 0.0)
    g1 = ToothForm(20, 2.0, A20, 0.1, 1e-9)
    assert over_pins(g1, 3.5).M == pytest.approx(over_pins(g0, 3.5).M, rel=1e-9)


# -- the shift sum for a centre distance, its split, backlash -------------------------------
def test_shift_sum_for_a_centre_distance_khk_example():
    # KHK example (bolsover.com table): z = 12/24, m = 3, a' = 56.5: sum 0.960,
    # alpha' = 26.0888°
    x_sum, aw = shift_sum_for_centre_distance(12, 24, A20, 54.0, 56.5)
    assert x_sum == pytest.approx(0.960, abs=5e-4)
    assert math.degrees(aw) == pytest.approx(26.0888, abs=5e-5)
    # round trip through the forward formula inv a' = 2 tan a (x1 + x2)/(z1 + z2) + inv a
    assert _inv(aw) == pytest.approx(2 * math.tan(A20) * x_sum / 36 + _inv(A20), rel=1e-13)


def _independent_zeta(z1, z2, m, x1, x2, a_w):
    """Specific sliding at both roots from coordinates: the contact points are where the
    tip circles cut the line of action; zeta from the involute arc lengths rho^2/(2 rb)
    swept per small step of the contact along the line (finite difference)."""
    r1, r2 = m * z1 / 2, m * z2 / 2
    rb1, rb2 = r1 * math.cos(A20), r2 * math.cos(A20)
    ra1, ra2 = r1 + (1 + x1) * m, r2 + (1 + x2) * m
    aw = math.acos((r1 + r2) * math.cos(A20) / a_w)
    n1 = rb1 * np.array([math.sin(aw), math.cos(aw)])
    n2 = np.array([0.0, a_w]) - rb2 * np.array([math.sin(aw), math.cos(aw)])
    length = float(np.linalg.norm(n2 - n1))
    u = (n2 - n1) / length
    t_a = brentq(lambda t: np.linalg.norm(n1 + t * u - [0, a_w]) - ra2, 0, length)
    t_e = brentq(lambda t: np.linalg.norm(n1 + t * u) - ra1, 0, length)

    def zeta(t, h=1e-6):
        arc1 = lambda s: (s ** 2) / (2 * rb1)               # noqa: E731  gear 1 involute arc
        arc2 = lambda s: ((length - s) ** 2) / (2 * rb2)    # noqa: E731
        ds1 = arc1(t + h) - arc1(t - h)
        ds2 = -(arc2(t + h) - arc2(t - h))
        return ds1, ds2

    d1, d2 = zeta(t_a)
    z_root1 = (d1 - d2) / d1
    d1, d2 = zeta(t_e)
    z_root2 = (d2 - d1) / d2
    return z_root1, z_root2


def test_specific_sliding_against_coordinates():
    m, a_w = 3.0, 56.5
    x_sum = shift_sum_for_centre_distance(12, 24, A20, 54.0, a_w)[0]
    aw = math.acos(54 * math.cos(A20) / a_w)
    rb = [m * z * math.cos(A20) / 2 for z in (12, 24)]
    x1, x2 = 0.6, x_sum - 0.6
    ra = [18 + (1 + x1) * m, 36 + (1 + x2) * m]
    mine = specific_sliding_at_roots(rb[0], rb[1], ra[0], ra[1], a_w, aw, 2.0)
    assert mine == pytest.approx(_independent_zeta(12, 24, m, x1, x2, a_w), rel=1e-7)


def test_balanced_sliding_split_balances():
    # balance check: at the split the two root sliding values are equal, and the split
    # lies where the sign of zeta1 - zeta2 changes (independent coordinates)
    m, a_w = 3.0, 56.5
    x_sum, aw = shift_sum_for_centre_distance(12, 24, A20, 54.0, a_w)
    rb = [m * z * math.cos(A20) / 2 for z in (12, 24)]

    def zeta(x1):
        ra = [18 + (1 + x1) * m, 36 + (1 + x_sum - x1) * m]
        return specific_sliding_at_roots(rb[0], rb[1], ra[0], ra[1], a_w, aw, 2.0)

    x1 = split_balanced_sliding(zeta, x_sum)
    z1, z2 = _independent_zeta(12, 24, m, x1, x_sum - x1, a_w)
    assert z1 == pytest.approx(z2, rel=1e-6)
    lo = _independent_zeta(12, 24, m, x1 - 0.01, x_sum - x1 + 0.01, a_w)
    hi = _independent_zeta(12, 24, m, x1 + 0.01, x_sum - x1 - 0.01, a_w)
    assert lo[0] < lo[1] and hi[0] > hi[1]


def test_backlash_from_allowances_against_thicknesses_on_the_pitch_circles():
    # independent: j = 2 pi rw1 / z1 - s1(rw1) - s2(rw2) with the thinned teeth
    z1, z2, m, x1, x2, a_w = 20, 50, 2.0, 0.2, 0.1, 71.0
    e1, e2 = 0.03, 0.05
    aw = math.acos(70 * math.cos(A20) / a_w)

    def thickness(z, x, e, r):
        s = m * (math.pi / 2 + 2 * x * math.tan(A20)) - e
        rb = m * z * math.cos(A20) / 2
        return 2 * r * (s / (m * z) + _inv(A20) - _inv(math.acos(rb / r)))

    rw1, rw2 = [m * z * math.cos(A20) / (2 * math.cos(aw)) for z in (z1, z2)]
    j0 = 2 * math.pi * rw1 / z1 - thickness(z1, x1, 0, rw1) - thickness(z2, x2, 0, rw2)
    j = 2 * math.pi * rw1 / z1 - thickness(z1, x1, e1, rw1) - thickness(z2, x2, e2, rw2)
    assert backlash_from_allowances(j0, A20, aw, 0.0, e1, e2) == pytest.approx(j, rel=1e-12)
    e = allowances_for_backlash(j, j0, A20, aw, 0.0, e1 / (e1 + e2))
    assert e == pytest.approx((e1, e2), rel=1e-12)


# -- through the command ---------------------------------------------------------------------
def _spec(tmp_path, body):
    path = tmp_path / "g.toml"
    path.write_text('command = "gear"\nunits = "mm"\n' + body, encoding="utf-8")
    return path


def _json(proc):
    import json
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)["results"]


def test_pair_with_a_split_backlash(tmp_path):
    body = "[pair]\nz1 = 20\nz2 = 50\nm = 2\na_w = 70\nbacklash = 0.1\nbacklash_share1 = 0.4\n"
    r = _json(run_inprocess("gear", _spec(tmp_path, body), "--json", "--no-plot", "-q",
                            "--out", tmp_path / "o"))
    assert r["backlash"] == pytest.approx(0.1, rel=1e-12)
    # standard gears at a: E1 + E2 = j (alpha' = alpha), split 0.4 : 0.6
    assert (r["allowance1"], r["allowance2"]) == pytest.approx((0.04, 0.06), rel=1e-12)
    assert r["backlash_n"] == pytest.approx(0.1 * math.cos(A20), rel=1e-12)
    assert r["W1"] == pytest.approx(span(ToothForm(20, 2.0, A20)).W - 0.04 * math.cos(A20),
                                    rel=1e-12)


def test_pair_balanced_sliding_and_unequal_addenda(tmp_path):
    body = ("[pair]\nz1 = 12\nz2 = 24\nm = 3\na_w = 56.5\nx_split = \"sliding\"\n"
            "ha_star1 = 1.0\nha_star2 = 0.8\n")
    r = _json(run_inprocess("gear", _spec(tmp_path, body), "--json", "--no-plot", "-q",
                            "--out", tmp_path / "o"))
    assert r["x1"] + r["x2"] == pytest.approx(0.960056, abs=1e-6)
    assert r["zeta1"] == pytest.approx(r["zeta2"], rel=1e-9)
    assert r["ha2"] == pytest.approx((0.8 + r["x2"]) * 3, rel=1e-12)      # own tip
    assert r["hf2"] == pytest.approx((1.25 - r["x2"]) * 3, rel=1e-12)     # the cutter's root


@pytest.mark.parametrize("body, key", [
    ("[pair]\nz1 = 20\nz2 = 50\nm = 2\nthickness_allowance1 = 3.5\n",
     "[pair] thickness_allowance1"),
    ("[pair]\nz1 = 20\nz2 = 50\nm = 2\na_w = 70\nbacklash = 8\n", "[pair] backlash"),
    ("[pair]\nz1 = 20\nz2 = 50\nm = 2\na_w = 72\nbacklash = 0.01\n", "[pair] backlash"),
    ("[pair]\nz1 = 12\nz2 = 24\nm = 3\na_w = 56.5\nx_split = \"x1\"\nx1 = -0.8\n", "[pair] x1"),
    ("[pair]\nz1 = 12\nz2 = 24\nm = 3\na_w = 50\nx_split = \"x1\"\n", "[pair] a_w"),
    ("[spur]\nz = 20\nm = 2\nk = 20\n", "[spur] k"),
    ("[spur]\nz = 20\nm = 2\npin_diameter = 0.1\n", "[spur] pin_diameter"),
])
def test_impossible_measurements_name_the_key(tmp_path, body, key):
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "-q",
                         "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    assert key in proc.stderr and proc.stderr.count("\n") == 1, proc.stderr
