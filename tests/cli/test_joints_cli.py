"""`[mechanism] type = "joints"` through the commands (issue 30): the structural
analysis in the JSON and the report, a linkage by joints equal to its preset, and
one-line exit-2 messages that name the key of a bad drawing."""

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json, write_spec

CLASS3 = CONFIGS / "ch1" / "class3-sixbar.toml"

#: 例 1-1's four-bar drawn at θ1 = 60° (positions from the preset's own solve) [mm]
FOUR_BAR = """
command = "kin"
units = "mm"
[mechanism]
type = "joints"
frame = 4
[mechanism.joints]
A = [0, 0]
B = [50.80000000000001, 87.98818102449896]
C = [288.66767665319665, 177.06662063594647]
D = [304.8, 0]
[[mechanism.link]]
number = 1
joints = ["A", "B"]
[[mechanism.link]]
number = 2
joints = ["B", "C"]
[[mechanism.link]]
number = 3
joints = ["D", "C"]
[[mechanism.driver]]
type = "crank"
link = 1
pivot = "A"
[input]
omega1 = 250
"""


def test_the_class3_config_reports_its_triad(tmp_path):
    r = run_json("kin", CLASS3, "--out", tmp_path)["results"]
    assert r["mechanism_class"] == 3
    assert [(g["type"], g["class"], g["links"]) for g in r["groups"]] == [
        ("driver", 1, [1]), ("triad", 3, [2, 3, 4, 5])]
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "a class III mechanism" in text and "triad (class III)" in text


def test_a_four_bar_by_joints_gives_the_presets_numbers(tmp_path):
    spec = write_spec(tmp_path, FOUR_BAR)
    by_joints = run_json("kin", spec, "--out", tmp_path / "j")["results"]
    preset = run_json("kin", CONFIGS / "ch1" / "ex1-1.toml", "--out", tmp_path / "p")["results"]
    for key in ("theta2_max_deg", "theta3_min_deg", "theta3_min_at_deg", "omega3_max_rad_s",
                "alpha3_max_rad_s2", "gammaC_min_deg"):
        assert by_joints[key] == pytest.approx(preset[key], rel=1e-12, abs=1e-12), key
    assert by_joints["mechanism_class"] == 2


def test_a_point_on_a_link_is_measured_from_its_drawn_direction(tmp_path):
    # link 3 listed C -> D: a point 50 mm along it from C lies on CD, 50 from C, whichever
    # way the engine measures link 3 (the distance to D is then 177.8 - 50 = 127.8)
    text = FOUR_BAR.replace('joints = ["D", "C"]', 'joints = ["C", "D"]') + """
[[mechanism.point]]
name = "P"
link = 3
from = "C"
along = 50
"""
    spec = write_spec(tmp_path, text)
    proc = run_inprocess("kin", spec, "--out", tmp_path / "o", "--no-plot", "--digits", "17")
    assert proc.returncode == 0, proc.stderr
    import csv
    with (tmp_path / "o" / "kin.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    for row in rows[::45]:
        x, y = float(row["xP_mm"]), float(row["yP_mm"])
        assert ((x - 304.8) ** 2 + y ** 2) ** 0.5 == pytest.approx(127.8, abs=1e-9)


@pytest.mark.parametrize("edit,key,words", [
    (('joints = ["B", "C"]', 'joints = ["B", "X"]'), "[mechanism.link.1] joints[1]",
     "a joint of [mechanism.joints]"),
    (("pivot = \"A\"", "pivot = \"A\"\n[[mechanism.driver]]\ntype = \"crank\"\nlink = 3\n"
                       "pivot = \"D\""), "[mechanism] driver", "= 1, but 2 drivers"),
    (("C = [288.66767665319665, 177.06662063594647]", "C = [177.8, 43.99409051224948]"),
     "[mechanism.joints] C", "dead point"),
    (("frame = 4", "frame = 4\nzz = 1"), "[mechanism] zz", "unknown key"),
])
def test_a_bad_drawing_is_one_line_naming_the_key(tmp_path, edit, key, words):
    spec = write_spec(tmp_path, FOUR_BAR.replace(*edit))
    proc = run_inprocess("kin", spec, "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert key in line and words in line, line


def test_forces_on_a_triad_pass_the_power_balance(tmp_path):
    # the class-III six-bar with masses on every moving link: the general elimination
    # solves the triad's pairs; Mb ω1 + Σ(F·v + M·ω) = 0 to round-off of its terms
    text = CLASS3.read_text(encoding="utf-8").replace('command = "kin"', 'command = "force"')
    text = text.split("[expected]")[0].replace("[output]\ntable_step = 30\n", "")
    for n, com in ((2, '"mid"'), (3, '"E"'), (4, '"mid"'), (5, '"mid"')):
        text += f"\n[[link]]\nnumber = {n}\nmass = {n * 0.5}\nJ = 0.002\ncom = {com}\n"
    spec = write_spec(tmp_path, text)
    r = run_json("force", spec, "--out", tmp_path / "o")["results"]
    assert r["mechanism_class"] == 3
    assert abs(r["power_balance_residual"]) < 1e-12
    assert r["Mb_max_N_m"] > 0.01          # the inertia loads are not negligible


def test_exercise2_8_by_joints_equals_its_dyad_form(tmp_path):
    # 习题 2-8 drawn by its joints (at θ1 = 90°) against the dyad form: the same forces at
    # every reported extreme, to round-off of the drawing's digits; and its structure
    gen = run_json("force", CONFIGS / "ch2" / "exercise2-8.toml", "--out", tmp_path / "g")
    jts = run_json("force", CONFIGS / "ch2" / "exercise2-8-joints.toml", "--out", tmp_path / "j")
    g, j = gen["results"], jts["results"]
    assert j["mechanism_class"] == 2
    assert [grp["type"] for grp in j["groups"]] == ["driver", "RRR", "RRR"]
    keys = [k for k, v in g.items() if isinstance(v, float) and k.endswith(("_N", "_N_m"))]
    assert len(keys) > 20
    for k in keys:
        assert j[k] == pytest.approx(g[k], rel=1e-9, abs=1e-9), k
