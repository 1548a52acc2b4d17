"""The generating profile-shift coefficient x_E of gears with a tooth-thickness allowance
(issue 29 §4): ISO 21771's sin form ``x_E<i>`` and the tan form ``x_E_tan<i>``.

Where each number comes from:
* hand derivations in the comments (习题 5-3's config with a backlash asked for; a spur gear);
* the identities each form is defined by: a rack at the shift x_E m cuts the reference
  thickness m (pi/2 + 2 x_E tan a) = s - E (tan form), and the span of the thinned tooth is
  the nominal span formula with x_E, W_k = m cos a [pi (k - 0.5) + z inv a] + 2 x_E m sin a
  (sin form); ISO 21771:2007 eq. (63) for a pair, x_E1 + x_E2 = sum x (zero backlash at a')
  - j_bn / (2 m_n sin a_n);
* the independent rack sweep of ``tests/reference/independent_rack_thickness.py`` (imports
  nothing from mechcli);
* a published spreadsheet of ISO 21771:2007 eq. (62)/(63) ("Gear Generating Profile Shift
  Calculations", S. Shelar, scribd.com/document/376176518): z = 31/30, m_n = 3.5 mm,
  a_n = 20 deg, beta = 21 deg, a' = 116.5 mm, x1 = 0.291, normal backlash j_n = 0.03 mm:
  sum x = 0.651877131252 (eq. 62), sum x_E = 0.639346541 (eq. 63, the sin form) and, "using
  the formulae", sum x_E = 0.6401022280 with x_E1 = 0.2851125484 (the tan form given j_n).
"""

import json
import math

import pytest

from mechcli.core.gear.measurement import ToothForm, generating_shift
from tests.conftest import run_inprocess
from tests.reference.independent_rack_thickness import rack_cut_thickness

A20 = math.radians(20)
CONFIG_5_3 = "configs/ch5/exercise5-3.toml"


def _inv(a):
    return math.tan(a) - a


def _spec(tmp_path, body):
    path = tmp_path / "g.toml"
    path.write_text('command = "gear"\nunits = "mm"\n' + body, encoding="utf-8")
    return path


def _results(tmp_path, spec, *sets):
    args = [a for s in sets for a in ("--set", s)]
    proc = run_inprocess("gear", spec, *args, "--json", "--no-plot", "-q",
                         "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)["results"]


# -- 习题 5-3 (an existing config) with a backlash asked for ------------------------------
def test_exercise_5_3_with_backlash_by_hand(tmp_path):
    # Hand derivation.  习题 5-3: m = 10 mm, a = 20 deg, z = 10/12, x = 0.45/0.31, mounted at
    # zero backlash: inv a' = 2 tan 20 (0.76)/22 + inv 20 = 0.0400514, a' = 27.38311 deg.
    # A backlash j = 0.2 mm on the operating pitch circle (the nominal teeth have none) asks
    # E1 + E2 = j cos a' / cos a = 0.2 * 0.887958 / 0.939693 = 0.1889875 mm, E = 0.0944938
    # each (share 0.5).  x_E = x - E/(2 m tan a) = x - 0.0944938/7.279404 = x - 0.0129810:
    # x_E1 = 0.4370190, x_E2 = 0.2970190.
    r = _results(tmp_path, CONFIG_5_3, "pair.backlash=0.2")
    assert (r["allowance1"], r["allowance2"]) == pytest.approx((0.0944938, 0.0944938),
                                                               abs=1e-7)
    for key, hand in (("x_E1", 0.4370190), ("x_E2", 0.2970190)):
        assert r[key] == pytest.approx(hand, abs=1e-7)
        assert r[key.replace("_E", "_E_tan")] == pytest.approx(hand, abs=1e-7)
    m, z1, x1 = 10.0, 10, 0.45
    # tan form: the rack at x_E m cuts the reference thickness s - E (the reported s_n1)
    assert m * (math.pi / 2 + 2 * r["x_E_tan1"] * math.tan(A20)) == pytest.approx(
        m * (math.pi / 2 + 2 * x1 * math.tan(A20)) - r["allowance1"], rel=1e-13)
    assert r["s_n1"] == pytest.approx(m * (math.pi / 2 + 2 * r["x_E_tan1"] * math.tan(A20)),
                                      rel=1e-13)
    # sin form (ISO): the thinned tooth's span is the nominal span formula with x_E
    k = r["k1"]
    assert r["W1"] == pytest.approx(
        m * math.cos(A20) * (math.pi * (k - 0.5) + z1 * _inv(A20))
        + 2 * r["x_E1"] * m * math.sin(A20), rel=1e-13)
    # ISO 21771:2007 eq. (63): x_E1 + x_E2 = sum x for a' - j_bn / (2 m sin a), sum x for
    # a' from the reported a' (the inverse of 习题 5-3's formula); 0.7340381 by hand
    aw = math.radians(r["alpha_w_deg"])
    x_sum = (10 + 12) * (_inv(aw) - _inv(A20)) / (2 * math.tan(A20))
    assert r["x_E1"] + r["x_E2"] == pytest.approx(
        x_sum - r["backlash_n"] / (2 * m * math.sin(A20)), abs=1e-12)
    assert r["x_E1"] + r["x_E2"] == pytest.approx(0.7340381, abs=1e-7)


def test_exercise_5_3_rack_at_x_E_cuts_the_thinned_tooth(tmp_path):
    # the independent rack sweep at the shift x_E1 m cuts the reference thickness s1 - E1,
    # and (involute: the base thickness 2 rb (psi_r + inv a)) the thinned base thickness
    r = _results(tmp_path, CONFIG_5_3, "pair.backlash=0.2")
    m, z1, x1 = 10.0, 10, 0.45
    s_thin = m * (math.pi / 2 + 2 * x1 * math.tan(A20)) - r["allowance1"]
    cut = rack_cut_thickness(z1, m, A20, r["x_E1"] * m, z1 * m / 2)
    assert cut == pytest.approx(s_thin, rel=1e-12)
    rb = z1 * m * math.cos(A20) / 2
    s_b = 2 * rb * (cut / (z1 * m) + _inv(A20))
    nominal_s_b = 2 * rb * ((s_thin + r["allowance1"]) / (z1 * m) + _inv(A20))
    # the base thickness (and the span) lost E cos a: what the sin form divides by 2 m sin a
    assert nominal_s_b - s_b == pytest.approx(r["allowance1"] * math.cos(A20), rel=1e-10)
    assert (x1 - r["x_E1"]) * 2 * m * math.sin(A20) == pytest.approx(nominal_s_b - s_b,
                                                                   rel=1e-10)


# -- a spur gear with an allowance ----------------------------------------------------------
def test_spur_gear_with_an_allowance(tmp_path):
    # Hand derivation: z = 20, m = 2 mm, x = 0.2, E = 0.05 mm: x_E = 0.2 - 0.05/(4 tan 20)
    # = 0.2 - 0.0343435 = 0.1656565; the rack sweep at x_E m cuts s - E = 3.4327688 - 0.05.
    body = "[spur]\nz = 20\nm = 2\nx = 0.2\nthickness_allowance = 0.05\n"
    spec = _spec(tmp_path, body)
    r = _results(tmp_path, spec)
    assert r["x_E"] == pytest.approx(0.1656565, abs=1e-7)
    assert r["x_E_tan"] == pytest.approx(0.1656565, abs=1e-7)
    assert rack_cut_thickness(20, 2.0, A20, r["x_E"] * 2, 20.0) == pytest.approx(
        3.4327688 - 0.05, abs=1e-7)
    report = (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")
    assert "x → x_E = 0.2000 → 0.1657, 0.1657" in report


def test_no_allowance_no_generating_shift(tmp_path):
    # model only what a spec asks for: no allowance, no x_E (and 【例 5-4】's listing unchanged)
    r = _results(tmp_path, _spec(tmp_path, "[spur]\nz = 20\nm = 2\nx = 0.2\n"))
    assert not any("_E" in k for k in r)
    r = _results(tmp_path, "configs/ch5/ex5-4.toml")
    assert not any("_E" in k for k in r)
    # one gear's allowance: that gear's x_E only
    body = "[pair]\nz1 = 20\nz2 = 50\nm = 2\nx1 = 0.3\nthickness_allowance1 = 0.04\n"
    r = _results(tmp_path, _spec(tmp_path, body))
    assert r["x_E1"] == pytest.approx(0.3 - 0.04 / (4 * math.tan(A20)), rel=1e-13)
    assert "x_E2" not in r and "x_E_tan2" not in r
    csv = (tmp_path / "o" / "gear.csv").read_text(encoding="utf-8").splitlines()[0]
    assert ",x_E1,x_E_tan1," in csv


def test_backlash_gives_both_gears_even_a_zero_share(tmp_path):
    # with backlash the allowances of both gears are found: share 1 leaves E2 = 0, x_E2 = x2.
    # Standard gears at a' = a (no nominal backlash, a' = a): E1 = j = 0.1 mm,
    # x_E1 = -0.1 / (2 * 2 tan 20) = -0.0686870
    body = ("[pair]\nz1 = 20\nz2 = 50\nm = 2\na_w = 70.0\nbacklash = 0.1\n"
            "backlash_share1 = 1.0\n")
    r = _results(tmp_path, _spec(tmp_path, body))
    assert r["allowance1"] == pytest.approx(0.1, rel=1e-12) and r["allowance2"] == 0
    assert r["x_E2"] == r["x_E_tan2"] == 0
    assert r["x_E1"] == pytest.approx(-0.0686870, abs=1e-7)


# -- a helical gear: normal module and normal pressure angle, as ISO ----------------------
def test_helical_against_the_published_iso_spreadsheet(tmp_path):
    # The spreadsheet's pair (module docstring) with x1 = 0.291 given and x2 designed for a'.
    body = ("[helical]\nz1 = 31\nz2 = 30\nmn = 3.5\nalpha_n_deg = 20\nbeta_deg = 21\n"
            "a_w = 116.5\nx_split = \"x1\"\nxn1 = 0.291\n")
    spec = _spec(tmp_path, body)
    r = _results(tmp_path, spec)
    assert r["xn_sum"] == pytest.approx(0.651877131252, abs=1e-9)   # eq. (62)
    assert not any("_E" in k for k in r)
    # ISO eq. (63), the sin form: the normal backlash j_bn = 0.03 mm from both gears thinned
    # alike, j_bn = (E1 + E2) cos a_n: E1 = 0.015 / cos 20 mm gives gear 1 half the drop,
    # x_E1 = 0.291 - (0.651877131252 - 0.639346541) / 2 = 0.2847347
    e_iso = 0.015 / math.cos(A20)
    r = _results(tmp_path, spec, f"helical.thickness_allowance1={e_iso!r}")
    assert r["xn_E1"] == pytest.approx(0.291 - (0.651877131252 - 0.639346541) / 2, abs=1e-9)
    assert r["xn_E_tan1"] == pytest.approx(r["xn_E1"], abs=1e-15)
    # "using the formulae": the tan form given j_n / 2 = 0.015 mm as if it were the
    # reference allowance (what makes the two forms differ, by cos a_n): 0.2851125484
    r = _results(tmp_path, spec, "helical.thickness_allowance1=0.015")
    assert r["xn_E_tan1"] == pytest.approx(0.2851125484, abs=1e-10)
    # the normal plane: s_n with the allowance and the normal span carry x_E (ISO)
    mn, an = 3.5, A20
    assert r["s_n1"] == pytest.approx(mn * (math.pi / 2 + 2 * r["xn_E_tan1"] * math.tan(an)),
                                      rel=1e-13)
    at = math.atan(math.tan(an) / math.cos(math.radians(21)))
    assert r["W1"] == pytest.approx(
        mn * math.cos(an) * (math.pi * (r["k1"] - 0.5) + 31 * _inv(at))
        + 2 * r["xn_E1"] * mn * math.sin(an), rel=1e-13)


def test_both_forms_agree_for_helical_gears():
    # the sin form takes the base-normal allowance E cos(at) cos(beta_b) / cos(beta), the
    # tan form E itself: equal because cos(at) cos(beta_b) = cos(an) cos(beta); and the
    # transverse tan form (E/cos beta, m_t, a_t) gives x_E cos(beta), the same radial shift
    for beta_deg in (0.0, 15.0, 30.0, 45.0):
        beta = math.radians(beta_deg)
        g = ToothForm(23, 0.004, A20, 0.35, beta, allowance=3e-5)
        gs = generating_shift(g)
        assert gs.E_bn == pytest.approx(-3e-5 * math.cos(A20), rel=1e-14)
        assert gs.x_E == pytest.approx(gs.x_E_tan, rel=1e-14)
        at = math.atan(math.tan(A20) / math.cos(beta))
        mt = 0.004 / math.cos(beta)
        x_t = 0.35 * math.cos(beta) - 3e-5 / math.cos(beta) / (2 * mt * math.tan(at))
        assert x_t * mt == pytest.approx(gs.x_E * 0.004, rel=1e-14)


def test_ring_gear_follows_iso_sign_of_x(tmp_path):
    # a ring thinned through the backlash: positive x thickens a ring's teeth (ISO 21771),
    # so x_E2 = x2 - E2 / (2 m tan a) again gives s2 - E2 = m (pi/2 + 2 x_E2 tan a)
    body = ("[pair]\nz1 = 20\nz2 = 60\nm = 4\ninternal = true\nx2 = 0.3\na_w = 78\n"
            "backlash = 0.5\n")
    r = _results(tmp_path, _spec(tmp_path, body))
    e2 = r["allowance1"]   # share 0.5: E2 = E1 (a ring reports no measurements)
    assert 4 * (math.pi / 2 + 2 * r["x_E2"] * math.tan(A20)) == pytest.approx(
        4 * (math.pi / 2 + 2 * 0.3 * math.tan(A20)) - e2, rel=1e-13)
    assert r["x_E_tan2"] == pytest.approx(r["x_E2"], abs=1e-15)
