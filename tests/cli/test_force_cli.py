"""``mechcli force`` through the CLI: outputs, JSON, languages, bad specs."""

import csv
import json
import math

import pytest

from tests.conftest import CONFIGS, one_line_error, run_cli, write_spec

FOUR_BAR = """
command = "force"
title = "four-bar"
[mechanism]
type = "four_bar"
l1 = 400
l2 = 1000
l3 = 700
l4 = 1200
[input]
omega1 = 10
step = 1
[[link]]
number = 2
mass = 3
J = 0.25
[[load]]
name = "Mr"
link = 3
torque = -100
"""


def test_outputs_csv_report_json(tmp_path):
    proc = run_cli("force", CONFIGS / "ch2" / "ex2-4.toml", "--json", "--no-plot", "--out",
                   tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    res = doc["results"]
    assert res["positions"] == 361
    assert res["power_balance_residual"] < 1e-9
    assert res["active_cutting_deg"][0][0] == pytest.approx(0.0138673834, abs=1e-8)
    assert res["band_cutting_m"] == pytest.approx([-0.389865105464, 0.101043985445], abs=1e-9)
    with open(tmp_path / "force.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    assert head[:5] == ["theta1_deg", "Mb_N_m", "FR16x_N", "FR16y_N", "FR16_N"]
    for col in ("FR23x_N", "MR23_N_m", "FR56_N", "MR56_N_m", "Fsh_N", "Msh_N_m", "P_W",
                "cond", "active_cutting"):
        assert col in head
    assert len(rows) == 362
    assert all(math.isfinite(float(x)) for r in rows[1:] for x in r)
    report = (tmp_path / "report.txt").read_text()
    assert "例 2-4" in report and "cutting" in report and "Extremes" in report


def test_chinese_report(tmp_path):
    proc = run_cli("force", CONFIGS / "ch2" / "ex2-1.toml", "--lang", "zh", "--no-plot",
                   "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text()
    assert "运动副反力" in text and "平衡力矩" in text and "曲柄转角" in text


def test_omega_zero_is_statics(tmp_path):
    spec = write_spec(tmp_path, FOUR_BAR.replace("omega1 = 10", "omega1 = 0"))
    proc = run_cli("force", spec, "--json", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert res["power_balance_residual"] < 1e-9
    assert res["Mb_max_N_m"] > 1.0  # the torque still needs balancing


@pytest.mark.parametrize("edit, key", [
    (("mass = 3", "mass = 0"), "[link.0] mass"),
    (("mass = 3", "mass = -2"), "[link.0] mass"),
    (("number = 2", "number = 9"), "[link.0] number"),
    (("number = 2", "number = 4"), "[link.0] number"),
    (("torque = -100", "force = [1, 0]\nat = \"Q\""), "[load.0] at"),
    (("torque = -100", "torque = -100\nwhen = { velocity = \"vZ\", sign = \"positive\" }"),
     "[load.0.when] velocity"),
    (("torque = -100", "torque = -100\nwhen = { band = [0.1, 0.9] }"), "[load.0.when] slide"),
    (("torque = -100", "torque = -100\nwhen = { velocity = \"omega3\", sign = \"up\" }"),
     "[load.0.when] sign"),
    (("J = 0.25", "J = -1"), "[link.0] J"),
    (("link = 3", "link = 7"), "[load.0] link"),
])
def test_bad_specs_exit_2(tmp_path, edit, key):
    spec = write_spec(tmp_path, FOUR_BAR.replace(*edit))
    proc = run_cli("force", spec, "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert key in line and "spec.toml" in line
    assert "Traceback" not in proc.stderr


def test_unassemblable_exit_3(tmp_path):
    spec = write_spec(tmp_path, FOUR_BAR.replace("l4 = 1200", "l4 = 2500"))
    proc = run_cli("force", spec, "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3
    assert "cannot" in one_line_error(proc)
    assert not (tmp_path / "o" / "force.csv").exists()
