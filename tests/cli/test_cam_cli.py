"""``mechcli cam`` end to end: outputs, overrides, bad specs (exit 2), undercut (exit 3)."""

import csv
import json
import math

import pytest

from tests.conftest import CONFIGS, run_cli, run_inprocess

BASE = """command = "cam"
title = "test"
units = "mm"

[follower]
motion = "translating"
contact = "roller"
r0 = 40
rr = 10
e = 15

[motion]
h = 60
segments = [
  { kind = "rise", angle = 100, law = "parabolic" },
  { kind = "dwell", angle = 60 },
  { kind = "return", angle = 90, law = "cosine" },
  { kind = "dwell", angle = 110 },
]
"""

OSC = """command = "cam"
[follower]
motion = "oscillating"
contact = "roller"
a = 60
l = 50
r0 = 25
rr = 8
[motion]
psi = 25
segments = [
  { kind = "rise", angle = 180, law = "cosine" },
  { kind = "return", angle = 180, law = "sine" },
]
"""


def _spec(tmp_path, text, name="spec.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _json(proc):
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_outputs_csv_report_and_json(tmp_path):
    spec = _spec(tmp_path, BASE + "[cam]\nomega = 10\n")
    # subprocess smoke test of cam (``python -m mechcli`` end to end)
    doc = _json(run_cli("cam", spec, "--json", "--no-plot", "--out", tmp_path / "o",
                        "--step", "1"))
    assert doc["command"] == "cam"
    res = doc["results"]
    assert res["n_points"] == 360                               # 360° / --step 1
    assert res["v_max"] == pytest.approx(10 * res["ds_max"])   # v = omega ds/ddelta, omega = 10
    with open(tmp_path / "o" / "cam.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    for col in ("delta_deg", "s_mm", "v_mm_rad", "a_mm_rad2", "j_mm_rad3", "v_mm_s",
                "x_pitch_mm", "y_pitch_mm", "x_work_mm", "y_work_mm", "pressure_angle_deg",
                "rho_pitch_mm", "rho_work_mm", "roller_angle_deg"):
        assert col in head
    # header + 0° … 360° by 1° (the closing 360° repeated) + one left-limit row at each of the
    # five acceleration jumps 50° (parabolic midpoint), 100°, 160°, 250° and 360° (≡ 0°)
    assert len(rows) == 362 + 5
    row = dict(zip(head, map(float, rows[51])))    # δ = 50°: s = h/2 = 30 of the parabolic rise
    after = dict(zip(head, map(float, rows[52])))  # the same δ, limit from the right
    assert row["delta_deg"] == after["delta_deg"] == pytest.approx(50.0)
    assert row["s_mm"] == after["s_mm"] == pytest.approx(30.0, abs=1e-9)
    # hand: the parabolic law's d²s/dδ² = ±4h/δ0² = ±4·60/(100π/180)² = ±78.7873524 mm/rad²,
    # + before the midpoint, − after it
    jump = 4 * 60 / math.radians(100) ** 2
    assert (row["a_mm_rad2"], after["a_mm_rad2"]) == pytest.approx((jump, -jump), rel=1e-9)
    report = (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")
    # BASE is 例 4-1 (configs/ch4/ex4-1.toml): hand calculation of the rise's largest pressure
    # angle at the parabolic kink, atan((2h/delta0 - e)/(sqrt(r0^2 - e^2) + h/2)) = 38.7067°
    assert "38.7067" in report and "soft impact" in report


def test_chinese_report_and_plots(tmp_path):
    spec = _spec(tmp_path, OSC)
    proc = run_inprocess("cam", spec, "--lang", "zh", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    report = (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")
    assert "推程最大压力角" in report and "柔性冲击" in report
    for name in ("motion.png", "profile.png", "checks.png"):
        assert (tmp_path / "o" / name).stat().st_size > 1000


def test_animation_written_on_request(tmp_path):
    spec = _spec(tmp_path, BASE + "[output]\nframes = 8\n")
    doc = _json(run_inprocess("cam", spec, "--json", "--no-plot", "--animate", "--out", tmp_path,
                        "--step", "2"))
    gif = [f for f in doc["files"] if f.endswith(".gif")]
    assert gif and (tmp_path / "cam.gif").read_bytes()[:6] in (b"GIF89a", b"GIF87a")


def test_set_override_and_sizing(tmp_path):
    spec = _spec(tmp_path, BASE)
    doc = _json(run_inprocess("cam", spec, "--json", "--no-plot", "--out", tmp_path, "--set",
                        "sizing.base_radius=true", "--set", "follower.side=left"))
    res = doc["results"]
    assert res["offset_side"] == "left"
    assert res["offset_side_best"] == "right"
    assert res["r0_min_other_side"] < res["r0_min"]


def test_undercut_warning_then_exit_3_when_forbidden(tmp_path):
    text = BASE.replace("r0 = 40", "r0 = 12").replace("e = 15", "e = 0").replace(
        "angle = 100, law = \"parabolic\"", "angle = 40, law = \"parabolic\"").replace(
        "{ kind = \"dwell\", angle = 60 }", "{ kind = \"dwell\", angle = 120 }")
    spec = _spec(tmp_path, text)
    doc = _json(run_inprocess("cam", spec, "--json", "--no-plot", "--out", tmp_path))
    assert doc["results"]["undercut"] is True
    assert any("undercut" in w for w in doc["warnings"])
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path, "--set",
                   "limits.forbid_undercut=true")
    assert proc.returncode == 3
    assert "undercut" in proc.stderr and "Traceback" not in proc.stderr


@pytest.mark.parametrize("edit, key, words", [
    (("angle = 110", "angle = 100"), "segments", "360"),
    (("law = \"cosine\"", "law = \"cosin\""), "law", "did you mean 'cosine'"),
    (("law = \"cosine\"", "law = \"bogus\""), "law", "modified-trapezoid"),
    (("{ kind = \"return\", angle = 90, law = \"cosine\" }",
      "{ kind = \"return\", angle = 90, law = \"cosine\", lift = 50 }"), "segments",
     "return lift = rise lift"),
    (("{ kind = \"return\", angle = 90, law = \"cosine\" }",
      "{ kind = \"return\", angle = 90, law = \"cosine\", lift = 70 }"), "lift",
     "return lift = rise lift"),
    (("r0 = 40", "r0 = 15"), "r0", "larger than the offset"),
    (("rr = 10", "rr = 10\nrrr = 3"), "rrr", "did you mean 'rr'"),
    (("h = 60", "h = -60"), "h", "positive"),
    (("contact = \"roller\"", "contact = \"needle\""), "contact", "knife"),
    (("command = \"cam\"", "command = \"kin\""), "command", "mechcli cam"),
])
def test_bad_specs_exit_2_naming_the_key(tmp_path, edit, key, words):
    spec = _spec(tmp_path, BASE.replace(*edit))
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path)
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr.strip()
    assert len(err.splitlines()) == 1 and key in err and words in err, err


@pytest.mark.parametrize("edit, key, words", [
    (("r0 = 25", "r0 = 5"), "r0", "|a - l| < r0 < a + l"),
    (("r0 = 25", "r0 = 120"), "r0", "|a - l| < r0 < a + l"),
    (("psi = 25", "psi = 160"), "psi", "phi0 + psi < 180"),
    (("contact = \"roller\"", "contact = \"flat\""), "contact", "oscillating"),
])
def test_bad_oscillating_specs_exit_2(tmp_path, edit, key, words):
    spec = _spec(tmp_path, OSC.replace(*edit))
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path)
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr.strip()
    assert key in err and words in err, err


def test_swing_just_below_the_geometric_limit(tmp_path):
    phi0 = math.degrees(math.acos((60 ** 2 + 50 ** 2 - 25 ** 2) / (2 * 60 * 50)))
    psi = 180 - phi0 - 1e-3
    spec = _spec(tmp_path, OSC.replace("psi = 25", f"psi = {psi!r}"))
    doc = _json(run_inprocess("cam", spec, "--json", "--no-plot", "--out", tmp_path, "--step", "1"))
    # the arm ends almost on the line pivot–cam centre: the pressure angle reaches ~90°
    assert 85 < doc["results"]["alpha_rise_max_deg"] < 90
    assert any("exceeds" in w for w in doc["warnings"])


def test_ex7_2_config_text_output(tmp_path):
    # subprocess: checks the rich table printed to the (non-terminal) stdout of a real process
    proc = run_cli("cam", CONFIGS / "ch7" / "ex7-2.toml", "--no-plot", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    # 例 7-2 prints alpha_max = 22.2077° at phi = 39.2315° (configs/ch7/ex7-2.toml)
    assert "22.2077°" in proc.stdout and "39.2315°" in proc.stdout


def test_oscillating_sizing_meets_the_limit(tmp_path):
    spec = _spec(tmp_path, OSC.replace("r0 = 25\n", "") + "[limits]\nalpha_rise = 25\n"
                 "[sizing]\nbase_radius = true\n")
    doc = _json(run_inprocess("cam", spec, "--json", "--no-plot", "--out", tmp_path, "--step", "1"))
    res = doc["results"]
    assert 10 < res["r0_min"] < 110 and res["r0"] == pytest.approx(res["r0_min"])
    assert res["alpha_rise_max_deg"] == pytest.approx(25.0, abs=1e-6)


def test_flat_face_cusp_warns_then_exit_3(tmp_path):
    text = """command = "cam"
[follower]
contact = "flat"
r0 = 10
[motion]
h = 20
segments = [
  { kind = "rise", angle = 40, law = "cosine" },
  { kind = "return", angle = 40, law = "cosine" },
  { kind = "dwell", angle = 280 },
]
[sizing]
"""
    spec = _spec(tmp_path, text)
    doc = _json(run_inprocess("cam", spec, "--json", "--no-plot", "--out", tmp_path))
    res = doc["results"]
    assert res["undercut"] is True and res["rho_work_min"] < 0
    # hand calculation: max(-(s + s'')) at the end of the rise = -20 + pi^2*20/(2*(40 deg)^2)
    assert res["r0_min"] == pytest.approx(-20 + math.pi ** 2 * 20 / (2 * math.radians(40) ** 2),
                                          rel=1e-9)
    assert any("cusp" in w for w in doc["warnings"])
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path, "--set",
                   "limits.forbid_undercut=true")
    assert proc.returncode == 3 and "r0 + s + s''" in proc.stderr


def test_units_aliases_partial_lifts_and_points(tmp_path):
    """Same cam in metres: lengths come back in metres, angles unchanged; law aliases,
    partial lifts and sampling.points are accepted."""
    mm = _json(run_inprocess("cam", _spec(tmp_path, BASE, "mm.toml"), "--json", "--no-plot",
                       "--out", tmp_path / "a", "--step", "1"))["results"]
    text = (BASE.replace('units = "mm"', 'units = "m"').replace("r0 = 40", "r0 = 0.04")
            .replace("rr = 10", "rr = 0.01").replace("e = 15", "e = 0.015")
            .replace("h = 60", "h = 0.06").replace('"cosine"', '"harmonic"')
            + "[sampling]\npoints = 360\n")
    m = _json(run_inprocess("cam", _spec(tmp_path, text, "m.toml"), "--json", "--no-plot",
                      "--out", tmp_path / "b"))["results"]
    assert m["n_points"] == 360 and m["units"] == "m"
    assert m["alpha_return_max_deg"] == pytest.approx(mm["alpha_return_max_deg"], abs=1e-9)
    assert m["rho_work_min"] == pytest.approx(mm["rho_work_min"] / 1000, rel=1e-9)
    two_step = BASE.replace(
        '{ kind = "rise", angle = 100, law = "parabolic" },\n  { kind = "dwell", angle = 60 },',
        '{ kind = "rise", angle = 50, law = "cycloidal", lift = 20 },\n'
        '  { kind = "dwell", angle = 20 },\n'
        '  { kind = "rise", angle = 50, law = "3-4-5", lift = 40 },\n'
        '  { kind = "dwell", angle = 40 },')
    res = _json(run_inprocess("cam", _spec(tmp_path, two_step, "two.toml"), "--json", "--no-plot",
                        "--out", tmp_path / "c", "--points", "720"))["results"]
    assert res["n_points"] == 720 and res["n_rigid_impacts"] == 0
    with open(tmp_path / "c" / "cam.csv", newline="") as fh:
        rows = {round(float(r["delta_deg"]), 6): r for r in csv.DictReader(fh)}
    assert float(rows[60.0]["s_mm"]) == pytest.approx(20.0, abs=1e-12)
    assert float(rows[120.0]["s_mm"]) == pytest.approx(60.0, abs=1e-12)


@pytest.mark.parametrize("reason, values, message", [
    ("pitch_cusp", {"at": math.radians(30)},
     "the pitch curve has a cusp near 30 deg (the follower point moves with the cam): "
     "no normal, no profile"),
    ("no_convex_pitch", {}, "the pitch curve has no convex part (check r0 and e)"),
    ("no_base_radius", {"lo": 0.01, "hi": 0.11},
     "no base radius between |a - l| and a + l meets the pressure-angle limit"),
    ("rounded_base_radius", {"r0": 0.2, "lo": 0.01, "hi": 0.11},
     "the rounded base radius 200 mm is outside |a - l| < r0 < a + l (10 .. 110 mm); "
     "use a smaller round_up"),
    ("unbounded_base_radius", {"floor": 0.015},
     "the limits do not bound the base radius from below (any r0 > 15 mm meets them); "
     "give r0, or round_up, or stricter limits"),
    ("roller_too_large", {"r0": 0.0138423, "rr": 0.08},
     "the sized base radius 13.8423 mm is not larger than the roller radius 80 mm; "
     "give r0 or a smaller roller"),
    ("arm_past_centre_line", {"angle": math.radians(185)},
     "phi0 + psi = 185 deg reaches 180 deg: the arm would pass the line through the pivot "
     "and the cam centre"),
    ("distorted", {"at": (math.radians(120), math.radians(180)), "contact": "flat"},
     "the follower cannot reproduce the velocity jump at 120, 180 deg: the flat face would "
     "need a cusp (r0 + s + s'' has a negative impulse); use a law without velocity jumps"),
    ("undercut", {"at": math.radians(40), "contact": "roller", "rr": 0.035, "rho": 0.0141343},
     "the working profile is undercut (cusp) near 40 deg: roller radius 35 mm >= pitch-curve "
     "radius of curvature 14.1343 mm"),
])
def test_cam_core_errors_are_worded_in_spec_units_and_keys(reason, values, message):
    """The core raises numbers (SI, rad); the report words them as the CLI always did
    (the messages of the mm specs these numbers come from, before the wording moved)."""
    from types import SimpleNamespace

    from mechcli.core.cam.geometry import CamGeometryError
    from mechcli.report.cam import error_message

    exc = CamGeometryError("core text", reason, **values)
    assert "mm" not in str(exc) and "deg" not in str(exc)
    cs = SimpleNamespace(header=SimpleNamespace(unit="mm", scale=1e-3))
    assert error_message(exc, cs) == message
    if reason == "roller_too_large":  # a spec in metres gets metres
        metres = SimpleNamespace(header=SimpleNamespace(unit="m", scale=1.0))
        assert "radius 0.0138423 m is not larger than the roller radius 0.08 m" in (
            error_message(exc, metres))


def test_core_error_reaches_the_cli_worded(tmp_path):
    """A forbidden undercut: exit 3 with the report's wording, not the core's."""
    text = BASE.replace("rr = 10", "rr = 35").replace("e = 15", "e = 0") + (
        "[limits]\nforbid_undercut = true\n")
    text = text.replace(
        """segments = [
  { kind = "rise", angle = 100, law = "parabolic" },
  { kind = "dwell", angle = 60 },
  { kind = "return", angle = 90, law = "cosine" },
  { kind = "dwell", angle = 110 },
]""", """segments = [
  { kind = "rise", angle = 40, law = "cosine" },
  { kind = "return", angle = 40, law = "cosine" },
  { kind = "dwell", angle = 280 },
]""")
    proc = run_inprocess("cam", _spec(tmp_path, text), "--no-plot", "--out", tmp_path)
    assert proc.returncode == 3, proc.stderr
    # the message the CLI printed for this spec before the wording left the core
    assert ("the working profile is undercut (cusp) near 40 deg: roller radius 35 mm >= "
            "pitch-curve radius of curvature 14.1343 mm") in proc.stderr
