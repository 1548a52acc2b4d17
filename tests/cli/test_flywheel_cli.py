"""mechcli flywheel through the command line: the JSON contract, the CSV, the methods and
the exits of problems without solution."""

import csv
import math

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json, write_spec as write

CH6 = CONFIGS / "ch6"


def _json(*args):
    return run_json("flywheel", *args)


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


@pytest.mark.parametrize("end, method, words", [
    ("phi_end_deg = 360", "closed_form", "not an angle: give omega_end or t_end"),
    ("t_end = 0.1", "RK45", "method RK45 runs to an angle: give phi_end_deg (omega_end and "
     "t_end need the closed form"),
])
def test_an_end_the_method_cannot_reach_names_the_keys(tmp_path, end, method, words):
    """The core says which end its method runs to; the report names the spec's keys."""
    text = (CH6 / "ex6-3.toml").read_text(encoding="utf-8").replace(
        "t_end = 0.1", f'{end}\nmethod = "{method}"')
    spec = write(tmp_path, text)
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3, proc.stderr
    line = one_line_error(proc)
    assert "[motion]: " in line and words in line


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


# -- found by an independent review of the first version --------------------------------
def test_closed_form_to_a_time_writes_the_whole_run(tmp_path):
    """例 6-3 to t = 0.1 s: 201 rows from the start at rest (was one row at t_end, so
    omega_min was the final speed)."""
    doc = _json(CH6 / "ex6-3.toml", "--out", tmp_path)
    r = doc["results"]
    assert r["omega_min_rad_s"] == 0.0 and r["omega_final_rad_s"] == pytest.approx(89.346302,
                                                                                    abs=5e-7)
    with open(tmp_path / "flywheel.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 201 and float(rows[0]["t_s"]) == 0.0


def test_constant_inertia_and_moment_to_an_angle(tmp_path):
    """J = 2, Me = 10 − 4 = 6 N m, ω0 = 10, to 720°: ½·2·ω² = ½·2·100 + 6·4π, by hand
    ω = √(100 + 24π) = 13.0300 rad/s (was exit 1: the closed form was chosen)."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nJ = 2\n[moment]\nconstant = 10\n'
                 'resisting = 4\n[motion]\nomega0 = 10\nphi_end_deg = 720\n')
    r = _json(spec, "--out", tmp_path / "o")["results"]
    assert r["method"] == "energy"
    assert r["omega_final_rad_s"] == pytest.approx(math.sqrt(100 + 24 * math.pi), rel=1e-12)


@pytest.mark.parametrize("body, code, words", [
    # a moment table over a turn whose last value is not its first (was exit 1)
    ('[inertia]\nJ = 1\n[moment.table]\nphi_deg = [0, 180, 360]\nM = [10, -10, 5]\n'
     '[motion]\nomega0 = 10\nphi_end_deg = 90', 2, "[moment.table] M"),
    # overlapping segments (was exit 1)
    ('[inertia]\nJ = 1\n[[moment.segment]]\nphi_deg = [0, 200]\nM = [1, 1]\n'
     '[[moment.segment]]\nphi_deg = [100, 360]\nM = [1, 1]\n[motion]\nomega0 = 10\n'
     'phi_end_deg = 90', 2, "[moment] segment"),
    # a negative start speed (was exit 1)
    ('[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nomega0 = -100\nphi_end_deg = 90',
     2, "[motion] omega0"),
    # a steady state of a moment that is not periodic (was a false message / exit 1)
    ('[inertia]\nJ = 1\n[moment]\nconstant = 75\n[[moment.segment]]\nphi_deg = [0, 180]\n'
     'M = [150, 0]\nresisting = true\n[motion]\nkind = "steady"\nomega0 = 10', 3,
     "the moment is not periodic"),
    # a book step that does not divide the turn (was silently 6.667°)
    ('[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nomega0 = 1\nphi_end_deg = 90\n'
     'method = "book"\nstep_deg = 7', 2, "[motion] step_deg"),
])
def test_more_bad_specs_are_one_line(tmp_path, body, code, words):
    spec = write(tmp_path, f'command = "flywheel"\n{body}\n')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == code, proc.stderr
    assert words in one_line_error(proc)


def test_a_vanishing_inertia_is_exit_3_with_the_angle(tmp_path):
    """A centred slider-crank whose only mass is the slider: Je = m v² is 0 at the dead
    points (0° and 180°): ω would be unbounded (was exit 0 with ω = 5e17)."""
    spec = write(tmp_path, 'command = "flywheel"\n[mechanism]\ntype = "slider_crank"\nl1 = 0.1\n'
                 'l2 = 0.3\n[[link]]\nnumber = 3\nmass = 10\n[moment]\nconstant = 100\n'
                 '[motion]\nomega0 = 10\nphi_end_deg = 360\n')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3, proc.stderr
    line = one_line_error(proc)
    assert "[[link]]" in line and "inertia vanishes" in line


def test_an_ill_conditioned_steady_state_is_flagged(tmp_path):
    """J = 1e12 against a motor line 1000 − ω with a harmonic 500 sin φ: the energy
    balance fixes ωm = 1000 rad/s exactly, which the shooting cannot resolve at the
    default tolerance: a warning names both numbers (it was silent)."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nJ = 1e12\n[moment]\n'
                 'drive = [1000, 1]\n[moment.harmonic]\na = [500]\n[motion]\nkind = "steady"\n'
                 'omega0 = 900\n')
    doc = _json(spec, "--out", tmp_path / "o")
    assert any("ill-conditioned" in w and "1000 rad/s" in w for w in doc["warnings"])


def test_the_approximate_flywheel_uses_the_work_at_the_mean_speed(tmp_path):
    """Eq. 6-29 as taught: ΔWmax of Me(φ, ωm) at the mean speed (913.36 J for the shaper of
    例 6-4), not the swing of the machine's own fluctuating motion: J_F ≈ 549.06 kg m²
    against the exact 504.63 (was 77.27)."""
    r = _json(CH6 / "flywheel-sizing.toml", "--out", tmp_path)["results"]
    assert r["J_F_approx_kg_m2"] == pytest.approx(549.06, abs=0.01)
    assert r["J_F_kg_m2"] == pytest.approx(504.63, abs=0.01)


def test_a_steady_state_on_a_flywheel_alone(tmp_path):
    """No [inertia]: the machine's inertia is the flywheel's J = 30 kg·m² alone (was an
    internal error: the steady state was skipped for a machine of no inertia of its own)."""
    spec = write(tmp_path, """command = "flywheel"
title = "a flywheel alone"
units = "m"
[moment]
drive = [5500, 1000]
[moment.resisting_table]
phi_deg = [0, 90, 180, 270, 360]
M = [789, 100, 700, 100, 789]
method = "linear"
[flywheel]
J = 30
[motion]
kind = "steady"
omega0 = 5
""")
    r = _json(spec, "--out", tmp_path / "o")["results"]
    # ωm by hand: (5500 − mean Mr)/1000, the table's trapezoidal mean
    # ((789 + 100) + (100 + 700) + (700 + 100) + (100 + 789)) / 8 = 422.25 N·m
    assert r["omega_mean_rad_s"] == pytest.approx((5500 - 422.25) / 1000, abs=1e-9)
    assert r["periodicity_residual_rad_s"] < 1e-9
    assert r["omega_final_rad_s"] == pytest.approx(r["omega0_rad_s"], abs=1e-9)
