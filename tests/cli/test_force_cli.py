"""``mechcli force`` through the CLI: outputs, JSON, languages, bad specs."""

import csv
import json
import math

import pytest

from tests.conftest import CONFIGS, one_line_error, run_cli, run_inprocess, write_spec

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


def shaper_sE(theta1=None, theta3=None):
    """Independent closed form of the ram position sE of 例 1-4 / 例 2-4's shaper
    (configs/ch2/ex2-4.toml, metres): C at the origin, A = (0, l6), the guide bar CD through B,
    E on the ram guide y = l6' to the left of D (branch "left")."""
    l1, l3, l4, l6, l6p = 0.125, 0.600, 0.150, 0.275, 0.575
    if theta3 is None:
        theta3 = math.atan2(l6 + l1 * math.sin(theta1), l1 * math.cos(theta1))
    dx, dy = l3 * math.cos(theta3), l3 * math.sin(theta3)
    return dx - math.sqrt(l4 ** 2 - (l6p - dy) ** 2)


def shaper_cutting_band():
    """The cutting band of 例 2-4 (sEmin + 0.05H, sEmax - 0.05H) in closed form: the stroke
    ends are where the guide bar is tangent to the crank circle, theta3 = 90° ∓ asin(l1/l6)
    (sEmax = 0.12832, sEmin = -0.41714, H = 2 l1 l3 / l6 = 6/11 m, as printed in 例 1-4);
    returns [-0.389865105464, 0.101043985445]."""
    phi = math.asin(0.125 / 0.275)
    s_max, s_min = shaper_sE(theta3=math.pi / 2 - phi), shaper_sE(theta3=math.pi / 2 + phi)
    h = s_max - s_min
    return [s_min + 0.05 * h, s_max - 0.05 * h]


def test_outputs_csv_report_json(tmp_path):
    # subprocess smoke test of force (``python -m mechcli`` end to end); the rest run in-process
    proc = run_cli("force", CONFIGS / "ch2" / "ex2-4.toml", "--json", "--no-plot", "--out",
                   tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    res = doc["results"]
    assert res["positions"] == 361                 # step = 1° over 0° … 360°, both ends
    assert res["power_balance_residual"] < 1e-9    # power balance, ~1e4 x machine epsilon
    # the cutting starts where the ram, moving left, enters the band: sE(theta1) = sEmax - 0.05H
    # solved with the closed form above: theta1 = 0.0138673834°
    band = shaper_cutting_band()
    from scipy.optimize import brentq
    start = math.degrees(brentq(lambda q: shaper_sE(q) - band[1], -0.1, 0.3, xtol=1e-15))
    assert res["active_cutting_deg"][0][0] == pytest.approx(start, abs=1e-8)
    # closed form (shaper_cutting_band): [-0.389865105464, 0.101043985445]
    assert res["band_cutting_m"] == pytest.approx(band, abs=1e-9)
    with open(tmp_path / "force.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    assert head[:5] == ["theta1_deg", "Mb_N_m", "FR16x_N", "FR16y_N", "FR16_N"]
    for col in ("FR23x_N", "MR23_N_m", "FR56_N", "MR56_N_m", "Fsh_N", "Msh_N_m", "P_W",
                "cond", "active_cutting"):
        assert col in head
    # header + 361 positions + two rows (without, then with the load, or the reverse) at each
    # of the cutting force's two switches, both between grid angles (0.0138673834° above, and
    # where the ram leaves the band near 176.4°)
    assert len(rows) == 362 + 4
    assert all(math.isfinite(float(x)) for r in rows[1:] for x in r)
    report = (tmp_path / "report.txt").read_text()
    assert "例 2-4" in report and "cutting" in report and "Extremes" in report


def test_chinese_report(tmp_path):
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-1.toml", "--lang", "zh", "--no-plot",
                   "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text()
    assert "运动副反力" in text and "平衡力矩" in text and "曲柄转角" in text


def test_omega_zero_is_statics(tmp_path):
    spec = write_spec(tmp_path, FOUR_BAR.replace("omega1 = 10", "omega1 = 0"))
    proc = run_inprocess("force", spec, "--json", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert res["power_balance_residual"] < 1e-9   # power balance, ~1e4 x machine epsilon
    # statics, by virtual work (no gravity here): Mb = -Mr dtheta3/dtheta1 with |Mr| = 100 N·m;
    # the rocker swings, so dtheta3/dtheta1 reaches O(0.1) and Mb_max is far above 1 N·m
    assert res["Mb_max_N_m"] > 1.0


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
    proc = run_inprocess("force", spec, "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert key in line and "spec.toml" in line
    assert "Traceback" not in proc.stderr


def test_unassemblable_exit_3(tmp_path):
    spec = write_spec(tmp_path, FOUR_BAR.replace("l4 = 1200", "l4 = 2500"))
    proc = run_inprocess("force", spec, "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3
    assert "cannot" in one_line_error(proc)
    assert not (tmp_path / "o" / "force.csv").exists()
