"""mechcli kin through the command line: outputs, exit codes, one-line messages."""

import csv
import json

import pytest

from tests.conftest import CONFIGS, one_line_error, run_cli, run_inprocess, write_spec as write

EX11 = CONFIGS / "ch1" / "ex1-1.toml"

GOOD = """\
command = "kin"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 100
l2 = 300
l3 = 250
l4 = 200
[input]
omega1 = 10
step = 5
"""


def test_version_and_help():
    # subprocess: start-up (``--version`` and ``--help`` import no subcommand's dependencies)
    assert run_cli("--version").stdout.startswith("mechcli, version")
    proc = run_cli("kin", "--help")
    assert proc.returncode == 0
    for opt in ("--out", "--json", "--no-plot", "--animate", "--lang", "--quiet", "--traceback",
                "--set"):
        assert opt in proc.stdout


def test_json_csv_and_report_are_written(tmp_path):
    # subprocess smoke test of kin (``python -m mechcli`` end to end); the rest run in-process
    proc = run_cli("kin", EX11, "--json", "--no-plot", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["command"] == "kin"
    assert {p.rsplit("/", 1)[-1] for p in doc["files"]} == {"kin.csv", "report.txt"}
    with open(tmp_path / "kin.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["theta1_deg", "theta2_deg", "theta3_deg", "gammaC_deg", "omega2_rad_s",
                       "omega3_rad_s", "alpha2_rad_s2", "alpha3_rad_s2"]
    assert len(rows) == 362   # header + 0° … 360° by 1° (configs/ch1/ex1-1.toml)
    assert not any("nan" in c.lower() or "inf" in c.lower() for r in rows for c in r)
    assert float(rows[1][2]) == pytest.approx(96.6654, abs=5e-5)  # eq. (1-4) at theta1 = 0


def test_lang_zh_report_uses_the_books_labels(tmp_path):
    proc = run_inprocess("kin", EX11, "--lang", "zh", "--quiet", "--no-plot", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "曲柄转角" in text and "角速度" in text and "计算结果" in text


def test_plots_and_animation(tmp_path):
    proc = run_inprocess("kin", CONFIGS / "ch1" / "exercise1-2.toml", "--animate", "--quiet",
                   "--set", "output.frames=8", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    for name in ("kin.png", "path_F.png", "kin.gif"):
        assert (tmp_path / name).stat().st_size > 1000
    from PIL import Image
    with Image.open(tmp_path / "kin.gif") as im:
        assert im.n_frames == 8


def test_set_overrides_are_applied_and_validated(tmp_path):
    base = json.loads(run_inprocess("kin", EX11, "--json", "--no-plot", "--out", tmp_path).stdout)
    proc = run_inprocess("kin", EX11, "--json", "--no-plot", "--out", tmp_path,
                   "--set", "mechanism.l1=90", "--set", "input.step=0.5")
    doc = json.loads(proc.stdout)
    assert doc["results"]["positions"] == 721   # 360° / 0.5° + 1
    assert doc["results"]["theta3_swing_deg"] != base["results"]["theta3_swing_deg"]
    proc = run_inprocess("kin", EX11, "--set", "mechanism.l1=-5", "--out", tmp_path)
    assert proc.returncode == 2
    assert "[mechanism] l1: expected a positive number, got -5.0" in one_line_error(proc)


@pytest.mark.parametrize("edit, key, fragment", [
    (("l2 = 300", "l22 = 300"), "[mechanism] l22", "did you mean 'l2'"),
    (("l2 = 300", 'l2 = "abc"'), "[mechanism] l2", "expected a positive number, got 'abc'"),
    (("l2 = 300", "l2 = -300"), "[mechanism] l2", "expected a positive number"),
    (("l2 = 300", "l2 = nan"), "[mechanism] l2", "expected a finite positive number, got nan"),
    (("l2 = 300\n", ""), "[mechanism] l2", "it is required"),
    (('type = "four_bar"', 'type = "four_bars"'), "[mechanism] type", "did you mean 'four_bar'"),
    (('units = "mm"', 'units = "km"'), "units", "one of 'mm', 'cm', 'm', 'in'"),
    (("step = 5", "step = 7"), "[input] step", "divides stop - start"),
    (("omega1 = 10", "omega1 = 10\nomga1 = 3"), "[input] omga1", "did you mean 'omega1'"),
    (('command = "kin"', 'command = "cam"'), "command", "mechcli cam"),
])
def test_bad_specs_exit_2_with_one_line_naming_file_and_key(tmp_path, edit, key, fragment):
    spec = write(tmp_path, GOOD.replace(*edit))
    proc = run_inprocess("kin", spec, "--out", tmp_path / "out")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert str(spec) in line and key in line and fragment in line
    assert not (tmp_path / "out").exists()


def test_toml_syntax_error_reports_line_and_column(tmp_path):
    spec = write(tmp_path, GOOD.replace("l3 = 250", "l3 = = 250"))
    proc = run_inprocess("kin", spec)
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "valid TOML" in line and "line 7" in line and "column" in line


def test_missing_file_exit_2(tmp_path):
    proc = run_inprocess("kin", tmp_path / "nope.toml")
    assert proc.returncode == 2 and "no such file" in one_line_error(proc)


def test_unassemblable_linkage_exit_3_with_intervals(tmp_path):
    spec = write(tmp_path, GOOD.replace("l1 = 100", "l1 = 240"))  # crank too long to turn
    proc = run_inprocess("kin", spec, "--out", tmp_path / "out")
    assert proc.returncode == 3
    line = one_line_error(proc)
    assert "cannot assemble for input angle" in line and "partial = true" in line
    assert line.startswith(f"mechcli: error: {spec}: ")
    assert not (tmp_path / "out").exists()
    proc = run_inprocess("kin", spec, "--json", "--out", tmp_path / "out")
    doc = json.loads(proc.stdout)
    assert proc.returncode == 3 and doc["exit_code"] == 3 and "cannot assemble" in doc["error"]


def test_partial_analysis_reports_feasible_ranges(tmp_path):
    spec = write(tmp_path, GOOD.replace("l1 = 100", "l1 = 240"))
    proc = run_inprocess("kin", spec, "--json", "--no-plot", "--set", "input.partial=true",
                   "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    excluded = doc["results"]["excluded"]
    # the crank cannot pass theta1 = 0 (B too far from D): excluded 352.1° … 360° and 0° … 7.9°
    assert [why for *_, why in excluded] == ["cannot assemble"] * 2
    inner = [excluded[0][1], excluded[1][0]]
    assert excluded[0][0] == 0 and excluded[1][1] == 360 and 0 < inner[0] < inner[1] < 360
    # boundaries are where B is |l2 - l3| = 50 or l2 + l3 = 550 from D: cosine rule
    import math
    for ang in inner:
        bd = math.dist((240 * math.cos(math.radians(ang)), 240 * math.sin(math.radians(ang))),
                       (200, 0))
        assert min(abs(bd - 50), abs(bd - 550)) < 1e-7
    assert doc["warnings"] and doc["results"]["toggles"]


def test_unknown_command_suggests(tmp_path):
    proc = run_inprocess("kinn", EX11)
    assert proc.returncode == 2 and "did you mean 'kin'" in proc.stderr


@pytest.mark.parametrize("override, fragment", [
    ("output.draw_at=4e5", "[output] draw_at: expected a number in [-36000, 36000], got 400000"),
    ("mechanism.l1=1e300", "[mechanism] l1: expected a length between 1e-09 m and 1e+06 m"),
    ("input.omega1=1e160", "[input] omega1: expected a number in [-1e+06, 1e+06]"),
    ("input.start=1e9", "[input] start: expected a number in [-36000, 36000]"),
    ("input.stop=-10", "[input] stop: expected a value above start (0), got -10"),
    # kin streams past 600,001 rows (issue 17), up to 100,000,001
    ("input.count=1", "[input] count: expected an integer in [2, 100000001], got 1"),
])
def test_out_of_range_angles_and_counts_exit_2(tmp_path, override, fragment):
    spec = write(tmp_path, GOOD.replace("step = 5\n", ""))
    proc = run_inprocess("kin", spec, "--set", override, "--out", tmp_path / "o")
    assert proc.returncode == 2
    assert fragment in one_line_error(proc)


def test_set_count_replaces_the_files_step(tmp_path):
    proc = run_inprocess("kin", EX11, "--json", "--no-plot", "--set", "input.count=721", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["results"]["positions"] == 721   # the count asked for
    spec = write(tmp_path, GOOD.replace("step = 5", "step = 5\ncount = 10"))
    proc = run_inprocess("kin", spec, "--out", tmp_path)
    assert proc.returncode == 2 and "either step or count, not both" in one_line_error(proc)
