"""``mechcli force`` with engine loads, end to end: the configs, the report, the CSV, the
exit codes and one-line messages of bad specs (numbers: tests/unit/linkage/test_engine_loads.py)."""

import json
import math

import pytest

from tests.conftest import ROOT, one_line_error, run_cli, run_inprocess

CH2 = ROOT / "configs" / "ch2"
ENGINE_CONFIGS = ["engine-steam-horizontal.toml", "engine-steam-double-acting.toml",
                  "engine-four-stroke-indicator.toml", "engine-two-stroke-crankcase.toml"]


@pytest.mark.parametrize("name", ENGINE_CONFIGS)
def test_configs_meet_their_expected_values(tmp_path, name):
    proc = run_inprocess("check", CH2 / name, "-j", "1", "-q")
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_report_csv_and_json(tmp_path):
    proc = run_inprocess("force", CH2 / "engine-steam-horizontal.toml", "--out", tmp_path,
                         "--no-plot", "--json")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    res = doc["results"]
    # every number finite (no NaN or inf in an output)
    assert all(math.isfinite(v) for v in res.values() if isinstance(v, float))
    report = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "Engine forces" in report and "Values at θ1 = 60°" in report
    assert "model: approximate" in report
    assert "gas pressure on piston 3" in report
    header = (tmp_path / "force.csv").read_text(encoding="utf-8").splitlines()[0].split(",")
    for col in ("FL_N", "FI_N", "FP_N", "FQ_N", "FN_N", "FT_N", "Frad_N", "T_N_m"):
        assert col in header
    # the refined extremes: T's largest value lies between the grid's neighbours
    assert res["T_max_N_m"] >= res["T_at_60deg_N_m"]
    assert 0 < res["T_max_at_deg"] < 180


def test_chinese_report(tmp_path):
    proc = run_inprocess("force", CH2 / "engine-four-stroke-indicator.toml", "--out", tmp_path,
                         "--no-plot", "--lang", "zh", "-q")
    assert proc.returncode == 0, proc.stderr
    report = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "活塞与曲柄上的力" in report and "时的值" in report


def test_exact_model_has_no_model_keys(tmp_path):
    text = (CH2 / "engine-steam-horizontal.toml").read_text(encoding="utf-8")
    spec = tmp_path / "exact.toml"
    spec.write_text(text.replace('model = "approximate"\n', "").split("[expected]")[0],
                    encoding="utf-8")
    proc = run_inprocess("force", spec, "--out", tmp_path / "o", "--no-plot", "--json")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert "model" not in res and not any(k.startswith("approx_error") for k in res)
    assert "FT_at_60deg_N" in res


def test_a_table_that_does_not_span_the_stroke_is_one_line_exit_2(tmp_path):
    text = (CH2 / "engine-four-stroke-indicator.toml").read_text(encoding="utf-8")
    spec = tmp_path / "bad.toml"
    spec.write_text(text.replace("fraction = [0, 0.1, 0.25, 0.5, 0.75, 1]",
                                 "fraction = [0, 0.1, 0.25, 0.5, 0.75, 0.9]"), encoding="utf-8")
    proc = run_cli("force", str(spec), "--out", str(tmp_path / "o"))
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[load.0.pressure] fraction" in line and "spanning the stroke" in line
    assert not (tmp_path / "o" / "force.csv").exists()


def test_json_error_object_names_the_key(tmp_path):
    text = (CH2 / "engine-steam-horizontal.toml").read_text(encoding="utf-8")
    spec = tmp_path / "bad.toml"
    spec.write_text(text.replace('pressure_unit = "N/mm2"', 'pressure_unit = "atm"'),
                    encoding="utf-8")
    proc = run_inprocess("force", spec, "--out", tmp_path / "o", "--json")
    assert proc.returncode == 2
    assert "pressure_unit" in proc.stdout


def test_zero_forces_and_extremes_on_the_grid(tmp_path):
    """At θ1 = 0 the steam engine's FR34 is exactly zero: written 0 with direction 0° (not
    -0 and ±180° by the sign of its zeros; no cell of the CSV is -0).  FN's maximum lies
    on the grid (θ1 = 90°, by symmetry of the double-acting engine's normal force): the
    grid sample ties the refined value by round-off, and its location keeps the refined
    tolerance (~1.5e-5°; it was half the grid step, 1°, when the grid sample won)."""
    proc = run_inprocess("force", CH2 / "engine-steam-double-acting.toml", "--out", tmp_path,
                         "--no-plot", "--json")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert abs(res["FN_max_at_deg"] - 90.0) < 1e-4
    assert res["FN_max_at_deg_tol"] < 1e-4
    assert abs(res["FN_max_at_deg"] - 90.0) <= res["FN_max_at_deg_tol"]
    lines = (tmp_path / "force.csv").read_text(encoding="utf-8").splitlines()
    header = lines[0].split(",")
    row0 = dict(zip(header, lines[1].split(",")))
    assert row0["theta1_deg"] == "0" and float(row0["FR34_N"]) == 0.0
    assert row0["FR34_dir_deg"] == "0" and row0["FR34x_N"] == "0"
    assert not any(cell == "-0" for line in lines[1:] for cell in line.split(","))
