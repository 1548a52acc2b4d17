"""mechcli flywheel through the command line: the JSON contract, the CSV, the methods and
the exits of problems without solution."""

import csv
import json
import math

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, write_spec as write

CH6 = CONFIGS / "ch6"


def _json(*args):
    proc = run_inprocess("flywheel", *args, "--json", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_steady_state_json_and_csv(tmp_path):
    doc = _json(CH6 / "ex6-4.toml", "--out", tmp_path)
    r = doc["results"]
    for key in ("Je_min_kg_m2", "Je_max_kg_m2", "omega_max_rad_s", "omega_min_rad_s",
                "omega_mean_rad_s", "delta", "dW_max_J", "iterations", "method", "t_final_s",
                "phi_final_rad"):
        assert key in r, key
    # ωm exact by hand: (5500 − mean Mer)/1000, the trapezoidal mean of 表 6-2's Mer
    assert r["omega_mean_rad_s"] == pytest.approx(5.1125416667, abs=1e-9)
    assert r["periodicity_residual_rad_s"] < 1e-9
    with open(tmp_path / "flywheel.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == ["phi_deg", "t_s", "Je_kg_m2", "dJe_dphi_kg_m2_rad", "Me_N_m",
                             "W_J", "omega_rad_s", "alpha_rad_s2"]
    # one period: the speed returns, the work W (= ΔE) returns to 0
    assert float(rows[-1]["omega_rad_s"]) == pytest.approx(float(rows[0]["omega_rad_s"]),
                                                           abs=1e-9)
    assert abs(float(rows[-1]["W_J"])) < 1e-6


def test_the_model_only_writes_the_columns_it_has(tmp_path):
    """例 6-1 asks for Je and dJe only: no [motion], no speed columns."""
    _json(CH6 / "ex6-1.toml", "--out", tmp_path)
    with open(tmp_path / "flywheel.csv", encoding="utf-8") as f:
        head = next(csv.reader(f))
    assert head == ["phi_deg", "Je_kg_m2", "dJe_dphi_kg_m2_rad"]


def test_an_unreachable_final_speed_is_exit_3_with_the_asymptote(tmp_path):
    """例 6-3 as stated (Mr = 1100 acting): 100 rad/s is never reached, the speed tends to
    (26500 − 1100)/264 = 96.2121 rad/s."""
    text = (CH6 / "ex6-3.toml").read_text(encoding="utf-8").replace(
        "t_end = 0.1", "omega_end = 100")
    spec = write(tmp_path, text)
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3
    line = one_line_error(proc)
    assert "[motion] omega_end" in line and "96.2121" in line


def test_a_stalling_machine_is_exit_3_with_the_angle(tmp_path):
    """Je = 1, ω0 = 1 rad/s against a resisting 10 N m: ½·1·1² = 10·φ stalls at φ = 0.05 rad
    (2.8648°), by hand."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nJ = 1\n[moment]\nresisting = 10\n'
                 '[motion]\nomega0 = 1\nphi_end_deg = 90\nmethod = "energy"\n')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3, proc.stderr
    line = one_line_error(proc)
    assert "[motion] omega0" in line and "2.86479 deg" in line


@pytest.mark.parametrize("body, key", [
    ('[inertia]\nJ = -1\n[moment]\nconstant = 1\n[motion]\nomega0 = 1\nphi_end_deg = 10',
     "[inertia] J"),
    ('[inertia]\nphi_deg = [0, 180, 360]\nJ = [1, 2, 1.5]\n[moment]\nconstant = 1\n'
     '[motion]\nomega0 = 1\nphi_end_deg = 10', "not_periodic"),
    ('[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nomega0 = 1', "[motion] phi_end_deg"),
    ('[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nomega0 = 1\nphi_end_deg = 10\n'
     'method = "book"', "[motion] step_deg"),
    ('[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nkind = "steady"\nomega0 = 0',
     "[motion] omega0"),
])
def test_bad_specs_are_one_line(tmp_path, body, key):
    spec = write(tmp_path, f'command = "flywheel"\n{body}\n')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode in (2, 3), proc.stderr
    line = one_line_error(proc)
    assert key in line or key == "not_periodic" and "period" in line


def test_pictures(tmp_path):
    proc = run_inprocess("flywheel", CH6 / "ex6-2.toml", "--quiet", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "flywheel.png").stat().st_size > 10_000


def test_steady_state_convergence_plot_and_animation(tmp_path):
    """例 6-4 by shooting: convergence.png of the period-map evaluations (3: the guess 5,
    its image, the root), and --animate a 72-frame GIF of the ω(φ) cursor."""
    from PIL import Image
    proc = run_inprocess("flywheel", CH6 / "ex6-4.toml", "--quiet", "--animate", "--out",
                         tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "convergence.png").stat().st_size > 10_000
    with Image.open(tmp_path / "flywheel.gif") as im:
        assert im.n_frames == 72
