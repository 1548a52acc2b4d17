"""What ``kin`` and ``force`` say about their own accuracy: the ``accuracy`` JSON,
the ``[output] accuracy_warn`` key and ``--accuracy-warn``, and every extreme's
refinement tolerance (``*_tol``) and grid error."""

import json

import pytest

from tests.conftest import run_inprocess

EX1_1 = "configs/ch1/ex1-1.toml"
EX2_1 = "configs/ch2/ex2-1.toml"


def _json(*args):
    proc = run_inprocess(*args, "--json", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_kin_accuracy_far_from_any_singularity(tmp_path):
    doc = _json("kin", EX1_1, "-o", tmp_path)
    acc = doc["results"]["accuracy"]
    # 例 1-1: gamma >= 40°, so no dyad is near a singular position: 14+ digits everywhere
    assert set(acc) >= {"positions", "velocities", "accelerations", "by_quantity", "warn_below"}
    assert min(acc["positions"], acc["velocities"], acc["accelerations"]) > 14
    assert acc["warn_below"] == 8.0
    assert not [w for w in doc["warnings"] if "significant digits" in w]


def test_kin_extremes_carry_tolerance_and_grid_error(tmp_path):
    r = _json("kin", EX1_1, "-o", tmp_path)["results"]
    # the refinement brackets the extreme to ~1e-13 rad (secant on the exact derivative)
    assert 0 < r["theta3_max_at_deg_tol"] < 1e-9
    # the grid error is the refined extreme minus the best 1° row: never of the wrong
    # sign, and as large as reading theta3's peak off a 1° grid costs (~1e-3°)
    assert r["theta3_max_grid_error_deg"] >= 0 >= r["theta3_min_grid_error_deg"]
    assert 1e-5 < r["theta3_max_grid_error_deg"] < 1e-2


def test_force_extremes_carry_tolerance_and_grid_error(tmp_path):
    r = _json("force", EX2_1, "-o", tmp_path)["results"]
    # golden section on values: no better than sqrt(eps) rad (8.5e-7°)
    assert 8e-7 < r["Mb_max_at_deg_tol"] < 1e-4
    assert r["Mb_max_grid_error_N_m"] >= 0 >= r["Mb_min_grid_error_N_m"]
    assert r["accuracy"]["forces"] > 12


@pytest.mark.parametrize("how", ["spec", "option"])
def test_threshold_from_the_spec_or_the_option(tmp_path, how):
    # 例 1-1 keeps ~14.5 digits: a threshold of 15 warns, by the key or the option
    args = ["kin", EX1_1, "-o", tmp_path]
    args += ["--set", "output.accuracy_warn=15"] if how == "spec" else ["--accuracy-warn", "15"]
    doc = _json(*args)
    assert doc["results"]["accuracy"]["warn_below"] == 15.0
    warned = [w for w in doc["warnings"] if "significant digits" in w]
    assert warned and all("fewer than 15" in w for w in warned)


def test_threshold_out_of_range_is_a_spec_error(tmp_path):
    proc = run_inprocess("kin", EX1_1, "--json", "--no-plot", "-o", tmp_path,
                         "--set", "output.accuracy_warn=20")
    assert proc.returncode == 2
    assert "accuracy_warn" in proc.stdout + proc.stderr
