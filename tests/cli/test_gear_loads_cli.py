"""``mechcli gear`` tooth loads and worm efficiency from the command line: results, report
rows, and one-line errors naming the key for bad power, speed, friction and face width."""

import json
import math

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess

CH5 = CONFIGS / "ch5"

WORM = """
[worm]
z1 = 1
z2 = 40
m = 7
q = 10
"""
BEVEL = """
[bevel]
z1 = 20
z2 = 40
m = 5
"""
PAIR = """
[pair]
z1 = 18
z2 = 36
m = 4
"""


def _spec(tmp_path, body, name="g.toml"):
    path = tmp_path / name
    path.write_text('command = "gear"\nunits = "mm"\n' + body, encoding="utf-8")
    return path


def _json(*args):
    proc = run_inprocess("gear", *args, "--json", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_worm_config_reports_loads_and_efficiency(tmp_path):
    proc = run_inprocess("gear", CH5 / "loads-worm.toml", "--quiet", "--no-plot", "--out",
                         tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    # numbers computed by hand in the config's comment, as the report rounds them
    for line in ("T1, T2 = 26.34 N·m, 684.2 N·m", "Ft1, Fr1, Fa1 = 752.7 N, 1788 N, 4887 N",
                 "η = tanγ/tan(γ+φv) = 0.6494", "η' = tan(γ-φv)/tanγ = 0.4657"):
        assert line in text


def test_worm_efficiency_without_power(tmp_path):
    # friction alone: the efficiencies and self-locking, no forces.  Hand: z1 = 1, q = 18,
    # g = atan(1/18) = 3.1798 deg; an = atan(tan 20 cos g) = 19.9716 deg;
    # phi = atan(0.08/cos an) = 4.8652 deg > g: self-locking
    path = _spec(tmp_path, WORM.replace("q = 10", "q = 18") + "mu = 0.08\n")
    res = _json(path, "--out", tmp_path)["results"]
    assert res["self_locking"] is True
    # the formula tan(g - phi)/tan g = tan(-1.6854 deg)/tan(3.1798 deg) = -0.53 < 0: the
    # wheel cannot drive the worm, its efficiency is reported as 0 (not -0.53)
    assert math.tan(math.radians(3.1798 - 4.8652)) / math.tan(math.radians(3.1798)) < 0
    assert res["efficiency_reverse"] == 0.0
    assert res["friction_angle_deg"] == pytest.approx(4.8652, abs=5e-5)
    assert "Ft1_N" not in res and "T1_N_m" not in res


def test_friction_angle_key_gives_the_same_drive(tmp_path):
    # the friction angle that mu = 0.05 gives, stated instead of mu: the same drive
    mu = _json(CH5 / "loads-worm.toml", "--out", tmp_path / "a")["results"]
    path = _spec(tmp_path, WORM + f"friction_angle_deg = {mu['friction_angle_deg']!r}\n"
                 "power_kW = 4\nn1_rpm = 1450\n")
    res = _json(path, "--out", tmp_path / "c")["results"]
    for key in ("efficiency", "Ft2_N", "Fr1_N", "T2_N_m"):
        assert res[key] == pytest.approx(mu[key], rel=1e-12)


@pytest.mark.parametrize("body,key", [
    (PAIR + "power_kW = -5\nn1_rpm = 1000\n", "[pair] power_kW"),          # negative power
    (PAIR + "power_kW = 0\nn1_rpm = 1000\n", "[pair] power_kW"),
    (PAIR + "power_kW = 5\nn1_rpm = -1000\n", "[pair] n1_rpm"),
    (PAIR + "n1_rpm = 1000\n", "[pair] power_kW"),                         # speed without power
    (PAIR + "power_kW = 5\n", "[pair] n1_rpm"),
    (PAIR + "a_w = [110, 111]\npower_kW = 5\nn1_rpm = 1000\n", "[pair] power_kW"),
    (WORM + "power_kW = 4\nn1_rpm = 1450\n", "[worm] mu"),                 # friction needed
    (WORM + "mu = 0.1\nfriction_angle_deg = 5\n", "[worm] friction_angle_deg"),
    # hand: z1 = 4, q = 2: g = 63.43 deg; phi = 30 deg takes g + phi past 90 deg: the worm
    # cannot drive (efficiency <= 0)
    (WORM.replace("z1 = 1", "z1 = 4").replace("q = 10", "q = 2")
     + "friction_angle_deg = 30\n", "[worm] friction_angle_deg"),
    (WORM.replace("z1 = 1", "z1 = 4").replace("q = 10", "q = 2") + "mu = 0.6\n", "[worm] mu"),
    (WORM + "mu = -0.1\n", "[worm] mu"),
    (BEVEL + "power_kW = 3\nn1_rpm = 960\n", "[bevel] b"),                 # face width needed
    # R = 111.8034 mm (习题 5-9): b must stay below it
    (BEVEL + "b = 112\npower_kW = 3\nn1_rpm = 960\n", "[bevel] b"),
])
def test_bad_load_input_is_one_line_naming_the_key(tmp_path, body, key):
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert key in line


def test_helical_and_bevel_tables_show_the_loads(tmp_path):
    for name in ("loads-helical.toml", "loads-bevel.toml", "loads-spur.toml"):
        out = tmp_path / name
        proc = run_inprocess("gear", CH5 / name, "--quiet", "--no-plot", "--out", out)
        assert proc.returncode == 0, proc.stderr
        text = (out / "report.txt").read_text(encoding="utf-8")
        assert "forces on gear 1: tangential, radial, axial" in text
        assert "torques (input, output)" in text
    zh = run_inprocess("gear", CH5 / "loads-bevel.toml", "--quiet", "--no-plot", "--lang", "zh",
                       "--out", tmp_path / "zh")
    assert zh.returncode == 0
    assert "齿宽中点分度圆直径" in (tmp_path / "zh" / "report.txt").read_text(encoding="utf-8")


HELICAL = """
[helical]
z1 = 17
z2 = 43
mn = 2
alpha_n_deg = 20
beta_deg = 15
"""


@pytest.mark.parametrize("body,key", [
    (HELICAL + 'x_split = "strength"\n', "[helical] a_w"),                  # no a' to design for
    (HELICAL.replace("beta_deg = 15\n", "") + 'a_w = 63\nx_split = "x1"\n', "[helical] beta_deg"),
    # hand: a = 2·60/(2 cos 15°) = 62.117 mm, at = 20.647°, rb1 + rb2 = a cos at = 58.127 mm:
    # no shift sum gives a centre distance at or below it
    (HELICAL + 'a_w = 58\nx_split = "sliding"\n', "[helical] a_w"),
    (HELICAL + 'a_w = 63\nx_split = "strength"\nxn1 = 0.2\n', "[helical] xn1"),
    (HELICAL + 'a_w = 63\nx_split = "x1"\nxn2 = 0.2\n', "[helical] xn2"),
    # xn1 + xn2 = 0.463 for a' = 63 (hand, ISO 21771): xn1 = -1.2 leaves xn2 = 1.66 > 1.5
    (HELICAL + 'a_w = 63\nx_split = "x1"\nxn1 = -1.2\n', "[helical] xn1"),
    (HELICAL + 'a_w = 63\nx_split = "x1"\nk2 = 5\n', "[helical] k2"),
    (HELICAL + 'a_w = 63\nx_split = "equal"\n', "[helical] x_split"),
    # a sum no split can carry: a' = 70 mm needs xn1 + xn2 = 5.24 (hand), beyond 2 x 1.5
    (HELICAL + 'a_w = 70\nx_split = "strength"\n', "[helical] a_w"),
    # the spur pair the same way: a' = 80 mm for z = 17/43, m = 2 needs x1 + x2 = 16.7
    ("[pair]\nz1 = 17\nz2 = 43\nm = 2\na_w = 80\nx_split = \"strength\"\n", "[pair] a_w"),
])
def test_bad_shift_design_is_one_line_naming_the_key(tmp_path, body, key):
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    assert key in one_line_error(proc)


def test_helical_shift_design_reports_the_split(tmp_path):
    path = _spec(tmp_path, HELICAL + 'a_w = 63\nx_split = "strength"\n')
    res = _json(path, "--out", tmp_path / "o")["results"]
    assert res["xn1"] + res["xn2"] == pytest.approx(res["xn_sum"], abs=1e-12)
    assert res["Y_Fa1"] * res["Y_Sa1"] == pytest.approx(res["Y_Fa2"] * res["Y_Sa2"], rel=1e-9)
    assert res["a_w"] == pytest.approx(63.0, rel=1e-12)
    proc = run_inprocess("gear", path, "--quiet", "--no-plot", "--out", tmp_path / "t")
    assert proc.returncode == 0
    assert "normal shifts for a' (equal Y_Fa Y_Sa)" in (tmp_path / "t" / "report.txt").read_text(
        encoding="utf-8")


def test_report_says_which_tip_the_contact_path_uses(tmp_path):
    cfg = CH5 / "pointed-tip-nominal.toml"
    doc = _json(cfg, "--out", tmp_path / "n")
    assert doc["results"]["tip"] == "nominal"
    assert any('tip = "nominal"' in w for w in doc["warnings"])
    eff = _json(cfg, "--set", 'pair.tip="effective"', "--out", tmp_path / "e")
    assert eff["results"]["tip"] == "effective"
    # hand (the config's comment): 1.2128 where the flanks meet, 1.2617 on the tip circle
    assert eff["results"]["epsilon_alpha"] == pytest.approx(1.2128, abs=5e-5)
    proc = run_inprocess("gear", cfg, "--quiet", "--no-plot", "--out", tmp_path / "t")
    text = (tmp_path / "t" / "report.txt").read_text(encoding="utf-8")
    assert "a pointed tooth's contact ends at" in text and "nominal tip circle" in text
    bad = run_inprocess("gear", cfg, "--set", 'pair.tip="tip_circle"', "--no-plot", "--out",
                        tmp_path / "b")
    assert bad.returncode == 2 and "[pair] tip" in one_line_error(bad)


# -- review defects 2-6 -----------------------------------------------------------------
SHIFTED = "[pair]\nz1 = 20\nz2 = 40\nm = 2\n"


def _finite_csv(path):
    """Every number of a CSV is finite and there is no empty cell (no NaN reached a writer)."""
    import csv
    rows = list(csv.reader(path.read_text(encoding="utf-8").splitlines()))
    for row in rows[1:]:
        for cell in row:
            try:
                assert math.isfinite(float(cell)), (path.name, row)
            except ValueError:   # a name, a unit, true/false
                pass
    return rows


@pytest.mark.parametrize("body", [
    SHIFTED + 'a_w = 58\nx_split = "x1"\nx1 = 0\n',
    SHIFTED + 'a_w = 57\nx_split = "x1"\nx1 = 0\n',
    SHIFTED + 'a_w = 56.5\nx_split = "x1"\nx1 = 0\n',
    "[pair]\nz1 = 14\nz2 = 28\nm = 3\na_w = 60\nx_split = \"x1\"\nx1 = 0\n",
])
def test_tip_interference_of_a_shift_design_is_a_warning_with_null_sliding(tmp_path, body):
    # the review's crash (exit 1, "non-finite zeta1"): a tip passing the other gear's end N of
    # the line of action leaves the specific sliding at that root undefined; as for any
    # interfering pair the run warns (naming the gear, the end, by how much) and zeta is null
    doc = _json(_spec(tmp_path, body), "--out", tmp_path / "o")
    res = doc["results"]
    assert res["interference"] is True
    assert res["zeta1"] is None or res["zeta2"] is None
    warn = [w for w in doc["warnings"] if "interference" in w]
    assert len(warn) == 1 and "passes the end N" in warn[0]
    for name in ("gear.csv", "results.csv"):
        _finite_csv(tmp_path / "o" / name)


def test_interference_warning_gives_the_gear_the_end_and_the_excess(tmp_path):
    # z = 20/40, m = 2, a' = 58, x1 = 0: hand, cos a' = 60 cos 20° / 58, x2 = x1 + x2 =
    # 60 (inv a' - inv 20°)/(2 tan 20°) = -0.8553; ra2 = 40 + 2 (1 + x2) = 40.289 mm,
    # rb2 = 40 cos 20° = 37.588 mm: the wheel's tip cuts the line of action
    # sqrt(ra2² - rb2²) = 14.505 mm from N2, past N1 (N1N2 = 58 sin a' = 13.606 mm) by 0.899 mm
    a = math.radians(20)
    aw = math.acos(60 * math.cos(a) / 58)
    x2 = 60 * ((math.tan(aw) - aw) - (math.tan(a) - a)) / (2 * math.tan(a))
    excess = math.sqrt((40 + 2 * (1 + x2)) ** 2 - (40 * math.cos(a)) ** 2) - 58 * math.sin(aw)
    doc = _json(_spec(tmp_path, SHIFTED + 'a_w = 58\nx_split = "x1"\nx1 = 0\n'), "--out",
                tmp_path / "o")
    assert doc["results"]["x2"] == pytest.approx(x2, abs=1e-12)
    assert any(f"the tip of gear 2 passes the end N1 of the line of action by {excess:.4f} mm"
               in w for w in doc["warnings"])
    assert doc["results"]["zeta1"] is None
    # forbidden: exit 3, one line naming it
    proc = run_inprocess("gear", _spec(tmp_path, SHIFTED + 'a_w = 58\nx_split = "x1"\nx1 = 0\n'
                                       "forbid_interference = true\n", "f.toml"),
                         "--no-plot", "--out", tmp_path / "f")
    assert proc.returncode == 3
    assert "the tip of gear 2 passes the end N1" in one_line_error(proc)


@pytest.mark.parametrize("a_w,why", [(58, "interference, the tip of gear 2"),
                                     (57, "gear 1 (z = 20) is undercut"),
                                     (56.5, "gear 1 (z = 20) is undercut")])
def test_strength_split_without_a_usable_pair_is_one_line(tmp_path, a_w, why):
    # the only equal-strength split is no usable pair (tests/unit/gear/test_gear_loads.py checks
    # the numbers): refused like any x_split without solution, naming x_split and why
    proc = run_inprocess("gear", _spec(tmp_path, SHIFTED + f'a_w = {a_w}\nx_split = '
                                       '"strength"\n'), "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[pair] x_split" in line and why in line
    proc = run_inprocess("gear", _spec(tmp_path, "[pair]\nz1 = 14\nz2 = 28\nm = 3\na_w = 60\n"
                                       'x_split = "strength"\n', "b.toml"),
                         "--no-plot", "--out", tmp_path / "b")
    assert proc.returncode == 2 and "[pair] x_split" in one_line_error(proc)


@pytest.mark.parametrize("table", [SHIFTED, HELICAL, BEVEL + "b = 20\n",
                                   WORM + "mu = 0.05\n"])
@pytest.mark.parametrize("drive,key", [
    ("power_kW = 1e6\nn1_rpm = 1e-300\n", "n1_rpm"),      # the review: T1 = inf
    ("power_kW = 1e-300\nn1_rpm = 1000\n", "power_kW"),
    ("power_kW = 1\nn1_rpm = 1e-7\n", "n1_rpm"),          # below 1e-6 rpm
    ("power_kW = 1e-10\nn1_rpm = 1000\n", "power_kW"),    # below 1e-9 kW
    ("power_kW = 1\nn1_rpm = 2e6\n", "n1_rpm"),
])
def test_power_and_speed_outside_their_ranges_are_refused(tmp_path, table, drive, key):
    proc = run_inprocess("gear", _spec(tmp_path, table + drive), "--no-plot", "--out",
                         tmp_path / "o")
    assert proc.returncode == 2
    kind = table.split("]")[0].strip().lstrip("[")
    assert f"[{kind}] {key}" in one_line_error(proc)


@pytest.mark.parametrize("power,n1", [(1e-9, 1e6), (1e6, 1e-6)])
def test_extreme_accepted_drives_give_finite_forces(tmp_path, power, n1):
    # the range's corners: T1 = P/omega, Ft = 2 T1/d1 (d1 = 40 mm), Fr = Ft tan 20°, and
    # Fn = Ft / cos 20° (hand; no underflow to 0 at 1 uW and 1e6 rpm)
    res = _json(_spec(tmp_path, SHIFTED + f"power_kW = {power}\nn1_rpm = {n1}\n"), "--out",
                tmp_path / "o")["results"]
    t1 = power * 1e3 / (n1 * math.pi / 30)
    ft = 2 * t1 / 0.040
    assert res["T1_N_m"] == pytest.approx(t1, rel=1e-12)
    assert res["Fn_N"] == pytest.approx(ft / math.cos(math.radians(20)), rel=1e-12)
    assert res["Fn_N"] > 0


def test_worm_diameter_factor_from_d1_is_limited_like_q(tmp_path):
    # the review: d1 = 100000 mm gave q = 14286 (lead angle 0.004°); d1 = q m with q in
    # [1, 100]: m = 7 -> d1 in [7, 700] mm
    bad = WORM.replace("q = 10", "d1 = 100000")
    proc = run_inprocess("gear", _spec(tmp_path, bad), "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[worm] d1" in line and "[7, 700]" in line
    ok = _json(_spec(tmp_path, WORM.replace("q = 10", "d1 = 700"), "ok.toml"), "--out",
               tmp_path / "k")["results"]
    assert ok["q"] == pytest.approx(100.0, rel=1e-12)


def test_worm_mu_and_friction_angle_admit_the_same_frictions(tmp_path):
    # tan phi = mu / cos an, tan an = tan 20° cos g, g = atan(1/10) (hand): the friction
    # angle's 45° is mu = cos an = 0.94024; the same bound for both keys
    gamma = math.atan(1 / 10)
    an = math.atan(math.tan(math.radians(20)) * math.cos(gamma))
    res = _json(_spec(tmp_path, WORM + "friction_angle_deg = 45\n"), "--out",
                tmp_path / "a")["results"]
    assert res["mu"] == pytest.approx(math.cos(an), rel=1e-12)
    proc = run_inprocess("gear", _spec(tmp_path, WORM + f"mu = {math.cos(an) * 1.001}\n",
                                       "b.toml"), "--no-plot", "--out", tmp_path / "b")
    assert proc.returncode == 2 and "[worm] mu" in one_line_error(proc)
    assert _json(_spec(tmp_path, WORM + f"mu = {math.cos(an) * 0.999}\n", "c.toml"), "--out",
                 tmp_path / "c")["results"]["friction_angle_deg"] < 45


def test_bevel_face_width_is_geometry_without_power(tmp_path):
    # 习题 5-9: z = 20/40, m = 5: d1 = 100, d2 = 200, R = sqrt(50² + 100²) = 111.8034 mm;
    # b = 20: dm = d (1 - 0.5 b/R) = 91.0557, 182.1115 mm (hand)
    r = math.hypot(50, 100)
    out = tmp_path / "o"
    res = _json(_spec(tmp_path, BEVEL + "b = 20\n"), "--out", out)["results"]
    assert res["b_mm"] == 20
    assert res["dm1_mm"] == pytest.approx(100 * (1 - 10 / r), rel=1e-12)
    assert res["dm2_mm"] == pytest.approx(200 * (1 - 10 / r), rel=1e-12)
    assert "T1_N_m" not in res
    rows = {row[0]: row for row in _finite_csv(out / "results.csv")}
    assert float(rows["dm1_mm"][1]) == pytest.approx(91.0557, abs=5e-5)
    assert rows["dm1_mm"][2] == "mm"
    # above R/3 = 37.268 mm: a warning; at or above R: exit 2 with R to tell it from b
    doc = _json(_spec(tmp_path, BEVEL + "b = 40\n", "w.toml"), "--out", tmp_path / "w")
    assert any("above R/3 = 37.2678 mm" in w for w in doc["warnings"])
    proc = run_inprocess("gear", _spec(tmp_path, BEVEL + "b = 111.8034\n", "r.toml"),
                         "--no-plot", "--out", tmp_path / "r")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[bevel] b" in line and "R = 111.803398875" in line and "got 111.8034" in line


def test_loads_keep_the_given_speed_and_print_units(tmp_path):
    # the review: n1_rpm came back as 959.9999999999999 (a round trip through rad/s)
    out = tmp_path / "o"
    res = _json(_spec(tmp_path, PAIR + "power_kW = 3\nn1_rpm = 960\n"), "--out", out)["results"]
    assert res["n1_rpm"] == 960 and res["power_kW"] == 3
    assert res["n2_rpm"] == pytest.approx(480, rel=1e-15)      # 960 · 18/36
    rows = {row[0]: row for row in _finite_csv(out / "results.csv")}
    assert rows["T1_N_m"][2] == "N·m" and rows["v_m_s"][2] == "m/s"
    assert rows["Ft1_N"][2] == "N" and rows["n1_rpm"][1] == "960"


def test_shift_design_line_reads_as_a_sum(tmp_path):
    # z = 80/80 at a' = a = 80 mm: x_sum = 0 exactly (no -0.0), x1 = x2 = 0 (symmetry)
    path = _spec(tmp_path, "[pair]\nz1 = 80\nz2 = 80\nm = 1\na_w = 80\nx_split = \"strength\"\n")
    res = _json(path, "--out", tmp_path / "j")["results"]
    assert math.copysign(1.0, res["x_sum"]) == 1.0 and res["x_sum"] == 0.0
    proc = run_inprocess("gear", path, "--quiet", "--no-plot", "--out", tmp_path / "t")
    text = (tmp_path / "t" / "report.txt").read_text(encoding="utf-8")
    assert "x1 + x2 = 0.0000 = 0.0000 + 0.0000 (" in text and "-0.0000" not in text
    # a negative x2 in parentheses: 20/40, m = 2, a' = 61, x1 = 0.6 -> x2 = x_sum - 0.6
    path = _spec(tmp_path, SHIFTED + 'a_w = 61\nx_split = "x1"\nx1 = 0.6\n', "n.toml")
    res = _json(path, "--out", tmp_path / "n")["results"]
    assert res["x2"] < 0
    run_inprocess("gear", path, "--quiet", "--no-plot", "--out", tmp_path / "m")
    text = (tmp_path / "m" / "report.txt").read_text(encoding="utf-8")
    assert f"x1 + x2 = {res['x_sum']:.4f} = 0.6000 + ({res['x2']:.4f}) (" in text


def test_self_locking_note_in_chinese(tmp_path):
    # z1 = 1, q = 18, mu = 0.08: self-locking (test_worm_efficiency_without_power)
    path = _spec(tmp_path, WORM.replace("q = 10", "q = 18") + "mu = 0.08\n")
    run_inprocess("gear", path, "--quiet", "--no-plot", "--lang", "zh", "--out", tmp_path / "z")
    text = (tmp_path / "z" / "report.txt").read_text(encoding="utf-8")
    assert "自锁" in text and "self-locking" not in text


def test_helical_shift_design_with_interference_warns(tmp_path):
    # z = 17/43, mn = 2, beta = 15°, a' = 60 mm, xn1 = 0 (hand, transverse plane):
    # at = atan(tan 20°/cos 15°), a = 60·2/(2 cos 15°) = 62.117 mm, cos a_wt = a cos at / a',
    # xn2 = 60 (inv a_wt - inv at)/(2 tan 20°); ra2 = d2/2 + (1 + xn2) mn, rb2 = d2 cos at / 2:
    # the wheel's tip passes N1 when sqrt(ra2² - rb2²) > a' sin a_wt
    an, beta = math.radians(20), math.radians(15)
    at = math.atan(math.tan(an) / math.cos(beta))
    awt = math.acos(60 / math.cos(beta) * math.cos(at) / 60)
    inv = lambda t: math.tan(t) - t  # noqa: E731
    xn2 = 60 * (inv(awt) - inv(at)) / (2 * math.tan(an))
    d2 = 43 * 2 / math.cos(beta)
    reach = math.sqrt((d2 / 2 + (1 + xn2) * 2) ** 2 - (d2 * math.cos(at) / 2) ** 2)
    assert reach > 60 * math.sin(awt)
    doc = _json(_spec(tmp_path, HELICAL + 'a_w = 60\nx_split = "x1"\nxn1 = 0\n'), "--out",
                tmp_path / "o")
    assert doc["results"]["xn2"] == pytest.approx(xn2, abs=1e-12)
    assert doc["results"]["zeta1"] is None and doc["results"]["zeta2"] < 0
    assert any("tip of gear 2 passes the end N1" in w for w in doc["warnings"])
    _finite_csv(tmp_path / "o" / "gear.csv")
