"""Undercut: one criterion (x < x_min, the standard rack), the sharp-cornered cutter's cut as
its measure, one warning in the same words (issue 20, section 3).

References:

* the textbook criterion z_min = 2 ha* / sin²α, x_min = ha* - z sin²α / 2: computed by hand,
  sin²20° = 0.11697778, z_min = 2 / 0.11697778 = 17.0973, x_min(17) = 1 - 8.5 * 0.11697778 =
  0.00568888, x_min(18) = 1 - 9 * 0.11697778 = -0.0528000 (the "17 teeth" of every textbook);
* the book (seeds, chapter 5): 习题 5-1 takes z = 18 as a standard gear without undercut, and
  gear_cut (图 5-10) cuts z = 9 with x = 0, an undercut gear; the involute of a rack-cut gear
  ends at r_w = (z/2 - 1) m, i.e. the rack's straight flank works down to ha* m;
* independent computations written here, importing nothing of mechcli's gear geometry: the
  line of action and the rack's form line as vectors; a brute-force sweep of the book's
  sharp-cornered cutter and of a standard cutter with a rounded tip, against the involute.
"""

import math

import numpy as np
import pytest

from mechcli.core.gear.profile import generated_tooth
from mechcli.core.gear.spur import spur_gear
from tests.conftest import run_inprocess, write_spec

A20 = math.radians(20)
M5 = 5e-3   # m = 5 mm (the module of 【例 5-3】, 【例 5-4】)
SIN2 = math.sin(A20) ** 2


def _inv(a):
    return np.tan(a) - a


def _undercut_by_line_of_action(z, x, m=1.0, alpha=A20, ha=1.0):
    """Independent: does the end of the rack's straight flank (ha* m below its reference
    line, x m outside the rolling line) pass the tangent point N?  Vectors at the pitch
    point P = (0, -r), gear centre O at the origin, line of action through P at alpha."""
    r = m * z / 2
    O, P = np.array([0.0, 0.0]), np.array([0.0, -r])
    d = np.array([math.cos(alpha), math.sin(alpha)])      # from P towards the gear side
    N = P + np.dot(O - P, d) * d                           # foot of the normal from O
    y_form = -r + (ha - x) * m                             # the form line, towards O
    K = P + (y_form - P[1]) / d[1] * d                     # where it meets the line of action
    return float(np.dot(K - P, d)) > float(np.dot(N - P, d)) * (1 + 1e-12)


def _cutter_sweep(z, x, u, h, m, alpha=A20, ha=1.0, phi=np.linspace(-0.8, 0.8, 8001)):
    """Independent: cutter points (u along the rolling line from the tooth centre, h below
    the cutter's reference line towards the gear) rolled over the gear (the book's eq.
    5-18 … 5-21): their radius R and their angle beta from the space centre, and the
    involute's space half-angle eta(R) there (R >= rb)."""
    r, rb = m * z / 2, m * z / 2 * math.cos(alpha)
    s = m * (math.pi / 2 + 2 * x * math.tan(alpha))
    ph = phi[:, None]
    wx = np.asarray(u)[None, :] + r * ph
    wy = -(r + x * m - np.asarray(h)[None, :])
    X = np.cos(ph) * wx + np.sin(ph) * wy
    Y = -np.sin(ph) * wx + np.cos(ph) * wy
    R = np.hypot(X, Y)
    beta = np.arctan2(X, -Y)
    eta = math.pi / z - (s / (2 * r) + _inv(alpha) - _inv(np.arccos(rb / np.maximum(R, rb))))
    return R, beta, eta, rb


def _sharp_corner_cut(z, x, m=5.0, alpha=A20, ha=1.0, c=0.25):
    """Independent: (r_form - rb, share of the involute's length) cut by the sharp corner
    of the book's cutter, from its sampled path (the last crossing of the involute,
    interpolated)."""
    uc = math.pi * m / 4 - (ha + c) * m * math.tan(alpha)
    R, beta, eta, rb = _cutter_sweep(z, x, [uc], [(ha + c) * m], m, alpha, ha,
                                     np.linspace(-1.5, 1.5, 200001))
    R, f = R[:, 0], np.where(R[:, 0] > rb, (beta - eta)[:, 0], -1.0)
    i = np.nonzero((f[:-1] > 0) != (f[1:] > 0))[0]
    if i.size == 0:
        return 0.0, 0.0
    t = f[i] / (f[i] - f[i + 1])
    r_form = float(np.max(R[i] + t * (R[i + 1] - R[i])))
    ra = m * z / 2 + (ha + x) * m
    return r_form - rb, ((r_form / rb) ** 2 - 1) / ((ra / rb) ** 2 - 1)


def _rounded_rack_cut(z, x, m=5.0, alpha=A20, ha=1.0, c=0.25):
    """Independent: the largest arc (mm) by which a standard cutter cuts past the involute;
    its tip is rounded with rho = c* m / (1 - sin alpha), tangent to the flank and the tip
    line, so its straight flank ends ha* m below its reference line."""
    t, sa, ca = math.tan(alpha), math.sin(alpha), math.cos(alpha)
    H, rho = (ha + c) * m, c * m / (1 - sa)
    hs = H - rho * (1 - sa)
    assert hs == pytest.approx(ha * m, rel=1e-12)
    h1 = np.linspace(0.0, hs, 150)
    u1 = math.pi * m / 4 - h1 * t
    cu, ch = (math.pi * m / 4 - hs * t) - rho * ca, hs - rho * sa
    a = np.linspace(0.0, math.pi / 2 - alpha, 150)
    u = np.concatenate([u1, cu + rho * np.cos(alpha + a)])
    h = np.concatenate([h1, ch + rho * np.sin(alpha + a)])
    R, beta, eta, rb = _cutter_sweep(z, x, u, h, m, alpha, ha)
    ra = m * z / 2 + (ha + x) * m
    ok = (R > rb * (1 + 1e-9)) & (R < ra)
    return float(np.max((R * (beta - eta))[ok]))


# -- the criterion --------------------------------------------------------------------------

@pytest.mark.parametrize("z, x, undercut, x_min", [
    (17, 0.0, True, 0.00568888),     # z < z_min = 17.0973
    (18, 0.0, False, -0.0528000),    # 习题 5-1's standard z = 18
    (9, 0.0, True, 0.4736000),       # gear_cut's z = 9 (图 5-10)
])
def test_criterion_against_the_textbook_numbers(z, x, undercut, x_min):
    g = spur_gear(z, M5, A20, x=x)
    assert g.z_min == pytest.approx(17.0973, abs=5e-5)
    assert g.x_min == pytest.approx(x_min, abs=5e-8 if z != 17 else 5e-9)
    assert g.undercut is undercut
    assert _undercut_by_line_of_action(z, x) is undercut


def test_z17_at_x_min_is_free_of_undercut():
    g = spur_gear(17, M5, A20)
    at = spur_gear(17, M5, A20, x=g.x_min)
    assert not at.undercut
    assert spur_gear(17, M5, A20, x=g.x_min - 1e-6).undercut


@pytest.mark.parametrize("z", range(5, 41))
@pytest.mark.parametrize("x", [-0.3, 0.0, 0.2, 0.5])
def test_criterion_is_the_line_of_action_geometry(z, x):
    g = spur_gear(z, M5, A20, x=x)   # every one of these 144 gears exists (checked)
    assert g.undercut is _undercut_by_line_of_action(z, x)
    # and it is x < x_min of the textbook: z_min = 2 ha* / sin² α, x_min = ha* (z_min - z) / z_min
    z_min = 2.0 / math.sin(A20) ** 2
    assert g.undercut is (x < (z_min - z) / z_min)


def test_a_rounded_standard_cutter_agrees_with_the_criterion():
    # no measurable cut (< 1e-9 mm) where the criterion says none; a cut where it says one
    assert _rounded_rack_cut(18, 0.0) < 1e-9
    assert _rounded_rack_cut(17, spur_gear(17, M5, A20).x_min) < 1e-9
    assert _rounded_rack_cut(15, 0.0) > 1e-4 and spur_gear(15, M5, A20).undercut
    assert _rounded_rack_cut(12, 0.0) > 1e-3 and spur_gear(12, M5, A20).undercut


# -- the sharp-cornered cutter: the measure beside the criterion ----------------------------

@pytest.mark.parametrize("z, x_of, depth_mm, share", [
    # brute force of this file (m = 5 mm): r_form - rb and the share of the involute
    (17, lambda g: 0.0, 0.036944, 0.0044643),
    (18, lambda g: 0.0, 0.021637, 0.0025712),
    (17, lambda g: g.x_min, 0.035435, 0.0042645),
])
def test_sharp_corner_cut_against_a_brute_force_sweep(z, x_of, depth_mm, share):
    x = x_of(spur_gear(z, M5, A20))
    g = spur_gear(z, M5, A20, x=x)
    tooth = generated_tooth(g)
    assert tooth.undercut   # the sharp corner cuts in all three: it is why they disagreed
    d_ind, s_ind = _sharp_corner_cut(z, x)
    assert (tooth.r_form - g.rb) * 1e3 == pytest.approx(d_ind, rel=1e-5)
    assert tooth.undercut_fraction == pytest.approx(s_ind, rel=1e-5)
    assert (tooth.r_form - g.rb) * 1e3 == pytest.approx(depth_mm, abs=5e-7)
    assert tooth.undercut_fraction == pytest.approx(share, abs=5e-8)


def test_sharp_corner_cuts_up_to_z21_for_x0():
    # its straight flank reaches (ha* + c*) m: cut while z < 2.5 / sin²20° = 21.37
    assert generated_tooth(spur_gear(21, M5, A20)).undercut
    assert not generated_tooth(spur_gear(22, M5, A20)).undercut
    assert _sharp_corner_cut(22, 0.0) == (0.0, 0.0)
    assert _sharp_corner_cut(21, 0.0)[0] > 0


# -- what the user sees: one warning, in the same words, from the criterion -----------------

SPUR = 'command = "gear"\nunits = "mm"\n[spur]\nz = {z}\nm = 5\nx = {x!r}\n'
GENERATION = ('command = "gear"\nunits = "mm"\n[generation]\nz = {z}\nm = 5\nx = [{x!r}]\n')


def _run(tmp_path, text, name):
    import json
    spec = write_spec(tmp_path, text, name=name)
    proc = run_inprocess("gear", spec, "--json", "--no-plot", "-o", tmp_path / f"out-{name}")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.mark.parametrize("z, x", [(17, 0.0), (9, 0.0)])
def test_one_warning_in_the_same_words_in_spur_and_generation(tmp_path, z, x):
    spur = _run(tmp_path, SPUR.format(z=z, x=x), "s.toml")
    gen = _run(tmp_path, GENERATION.format(z=z, x=x), "g.toml")
    ws = [w for w in spur["warnings"] if "undercut" in w]
    wg = [w for w in gen["warnings"] if "undercut" in w]
    assert len(ws) == 1 and ws == wg
    g = spur_gear(z, M5, A20, x=x)
    assert ws[0].startswith(f"undercut: z = {z}, x = 0 < x_min = {g.x_min:.4f}")
    assert spur["results"]["undercut"] is True and gen["results"]["undercut"] is True


@pytest.mark.parametrize("kind", ["spur", "generation"])
def test_z18_is_free_of_undercut_and_reports_the_sharp_corner_as_a_measure(tmp_path, kind):
    doc = _run(tmp_path, (SPUR if kind == "spur" else GENERATION).format(z=18, x=0.0),
               f"{kind}.toml")
    r = doc["results"]
    assert not [w for w in doc["warnings"] if "undercut" in w]
    assert r["undercut"] is False and r["undercut_generated"] is True
    assert r["undercut_margin"] == pytest.approx(0.0528000, abs=5e-8)   # x - x_min, by hand
    assert r["undercut_depth_mm"] == pytest.approx(0.021637, abs=5e-7)  # brute force above
    assert r["undercut_fraction"] == pytest.approx(0.0025712, abs=5e-8)


def test_forbid_undercut_follows_the_criterion(tmp_path):
    ok = write_spec(tmp_path, SPUR.format(z=18, x=0.0) + "forbid_undercut = true\n", "ok.toml")
    assert run_inprocess("gear", ok, "--no-plot", "-q", "-o", tmp_path / "a").returncode == 0
    bad = write_spec(tmp_path, SPUR.format(z=17, x=0.0) + "forbid_undercut = true\n", "no.toml")
    proc = run_inprocess("gear", bad, "--no-plot", "-q", "-o", tmp_path / "b")
    assert proc.returncode == 3 and "undercut: z = 17, x = 0 < x_min = 0.0057" in proc.stderr
