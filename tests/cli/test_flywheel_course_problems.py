"""mechcli flywheel for the classic course problems (issue 29 §3): cycles longer than a turn,
sizing from an energy swing, machines without their own inertia, the loop table, speeds in
r/min, inertia as m k², Simpson's rule, and every key a form does not use refused."""

import csv
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json, write_spec as write

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "reference"))
import independent_flywheel as ref  # noqa: E402  (numpy only, nothing from mechcli)

CH6 = CONFIGS / "ch6"


def _results(path, tmp_path):
    return run_json("flywheel", path, "--out", tmp_path)["results"]


def _expected(path):
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    exp = tomllib.loads(path.read_text(encoding="utf-8"))["expected"]
    return {k: (v["value"] if isinstance(v, dict) else v) for k, v in exp.items()}


# -- the configs against the independent reference ------------------------------------------
def test_four_stroke_engine_against_the_reference(tmp_path):
    """720° cycle: the reference's mean, loops and exact flywheel (bisection on its own
    energy integral) equal the config's [expected] and the run's results."""
    t = ref.FOUR_STROKE
    exp = _expected(CH6 / "four-stroke-engine.toml")
    lt = ref.loop_table(t["phi_deg"], t["M"], 720.0)
    wm = 200 * math.pi / 30
    assert ref.mean_moment(t["phi_deg"], t["M"], 720.0) == pytest.approx(exp["Mr_mean_N_m"],
                                                                        abs=5e-6)
    assert lt["dW_max"] == pytest.approx(exp["dE_max_J"], abs=5e-3)
    assert lt["phi_min_deg"] == pytest.approx(exp["phi_E_min_deg"], abs=5e-5)
    assert lt["phi_max_deg"] == pytest.approx(exp["phi_E_max_deg"], abs=5e-5)
    J = ref.flywheel_exact(t["phi_deg"], t["M"], wm, 0.02, 720.0)
    assert J == pytest.approx(exp["J_F_kg_m2"], abs=5e-5)
    r = _results(CH6 / "four-stroke-engine.toml", tmp_path)
    assert r["J_F_kg_m2"] == pytest.approx(J, rel=1e-8)
    assert r["J_F_approx_kg_m2"] == pytest.approx(ref.flywheel_approx(lt["dW_max"], wm, 0.02),
                                                  rel=1e-6)   # the table's 7 printed digits
    # the motion reported carries the flywheel: the machine cannot run without it
    assert r["motion_with_J_F"] is True and r["delta"] == pytest.approx(0.02, abs=1e-9)
    # the loop table on disk: the reference's areas
    with open(tmp_path / "loops.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    np.testing.assert_allclose([float(x["dE_J"]) for x in rows], lt["areas"], rtol=1e-6)


def test_multi_cylinder_loop_table_against_the_reference(tmp_path):
    """The seven loops of the classic problem: areas 10π J per mm² (+52, −124, …), in
    order, and the cumulative energies of the reference."""
    mc = ref.multi_cylinder()
    lt = ref.loop_table(mc["phi_deg"], mc["M"])
    np.testing.assert_allclose(lt["areas"], 10 * math.pi * np.array(
        [52, -124, 92, -140, 85, -72, 107]), rtol=1e-12)      # the problem's areas, by hand
    exp = _expected(CH6 / "multi-cylinder.toml")
    assert lt["dW_max"] == pytest.approx(exp["dE_max_J"], abs=5e-5)
    assert (lt["phi_max_deg"], lt["phi_min_deg"]) == pytest.approx(
        (exp["phi_E_max_deg"], exp["phi_E_min_deg"]), abs=5e-5)
    r = _results(CH6 / "multi-cylinder.toml", tmp_path)
    assert r["J_F_equation"] == "6-30"
    with open(tmp_path / "loops.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    np.testing.assert_allclose([float(x["dE_J"]) for x in rows], lt["areas"], rtol=1e-9)
    np.testing.assert_allclose([float(x["E_J"]) for x in rows], lt["cumulative"][1:],
                               atol=1e-6)
    np.testing.assert_allclose([float(x["phi_to_deg"]) for x in rows], lt["bounds_deg"][1:],
                               atol=1e-7)


def test_shaper_without_own_inertia_against_the_reference(tmp_path):
    sh = ref.shaper_drive_mean()
    exp = _expected(CH6 / "shaper-without-own-inertia.toml")
    lt = ref.loop_table(sh["phi_deg"], sh["M"], mean=0.0)
    assert sh["Md"] == pytest.approx(exp["Md_mean_N_m"], abs=5e-7)
    assert lt["dW_max"] == pytest.approx(exp["dE_max_J"], abs=5e-6)
    assert ref.flywheel_exact(sh["phi_deg"], sh["M"], 5.0, 0.05, mean=0.0) == pytest.approx(
        exp["J_F_kg_m2"], abs=5e-5)
    assert ref.flywheel_approx(lt["dW_max"], 5.0, 0.05) == pytest.approx(
        exp["J_F_approx_kg_m2"], abs=5e-6)


# -- the new forms ----------------------------------------------------------------------------
def test_a_720_degree_harmonic_is_a_half_order(tmp_path):
    """[moment.harmonic] period_deg = 720: a1 sin(φ/2).  J = 10, a1 = 500 against nothing:
    W(φ) = 1000 (1 − cos(φ/2)), so ΔWmax = 2000 J over the 720° cycle (by hand), the
    largest speed at 360°."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nJ = 10\n[moment.harmonic]\n'
                 'a = [500]\nperiod_deg = 720\n[motion]\nkind = "steady"\nomega0 = 50\n')
    r = _results(spec, tmp_path / "o")
    assert r["cycle_deg"] == 720 and r["dW_max_J"] == pytest.approx(2000, rel=1e-9)
    assert r["dE_max_J"] == pytest.approx(2000, rel=1e-9)
    assert r["phi_E_max_deg"] == pytest.approx(360, abs=1e-6)


def test_a_360_degree_inertia_table_within_a_720_degree_cycle(tmp_path):
    """A Je table of one turn and a moment of two: the steady state spans 720° and the
    speed after one turn differs from the start (the moment is not 360°-periodic)."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nphi_deg = [0, 180, 360]\n'
                 'J = [10, 12, 10]\n[moment]\ndrive = [1000, 10]\n[moment.table]\n'
                 'period_deg = 720\nphi_deg = [0, 360, 720]\nM = [0, 400, 0]\n'
                 '[motion]\nkind = "steady"\nomega0 = 100\npoints = 721\n')
    run_json("flywheel", spec, "--out", tmp_path / "o")
    with open(tmp_path / "o" / "flywheel.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert float(rows[-1]["phi_deg"]) == pytest.approx(720)
    w = [float(x["omega_rad_s"]) for x in rows]
    assert w[-1] == pytest.approx(w[0], abs=1e-8)          # periodic over the cycle
    assert abs(w[360] - w[0]) > 1e-3                       # but not over a turn


def test_simpson_reproduces_the_simpson_sum_and_states_the_difference(tmp_path):
    """Me = 100 sin φ tabulated every 90° (0, 100, 0, −100, 0), J = 1: Simpson's rule on
    [0°, 180°] gives (π/2)/3 (0 + 4·100 + 0) = 200π/3 = 209.4395 J (by hand) where the
    trapezoid gives 100·π/2 = 157.0796 J; the swing is that work."""
    body = ('command = "flywheel"\n[inertia]\nJ = 1\n[moment.table]\n'
            'phi_deg = [0, 90, 180, 270, 360]\nM = [0, 100, 0, -100, 0]\n{rule}'
            '[motion]\nkind = "steady"\nomega0 = 100\n')
    doc = run_json("flywheel", write(tmp_path, body.format(
        rule='integration = "simpson"\n')), "--out", tmp_path / "s")
    r = doc["results"]
    assert r["dE_max_J"] == pytest.approx(200 * math.pi / 3, rel=1e-12)
    assert r["dE_max_trapezoid_J"] == pytest.approx(50 * math.pi, rel=1e-12)
    assert any("simpson" in w and "trapezoid" in w for w in doc["warnings"])
    r = run_json("flywheel", write(tmp_path, body.format(rule='integration = "trapezoid"\n'),
                                   "t.toml"), "--out", tmp_path / "t")["results"]
    assert r["dE_max_J"] == pytest.approx(50 * math.pi, rel=1e-12)


def test_speeds_in_rpm_and_inertia_as_mass_and_k(tmp_path):
    """J = m k² = 100 · 0.5² = 25 kg m², a start at 600 r/min (20π rad/s) against a
    constant 10 N m over 90°: ½·25·ω² = ½·25·(20π)² − 10·π/2 (by hand)."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nmass = 100\nk = 0.5\n[moment]\n'
                 'resisting = 10\n[motion]\nn0_rpm = 600\nphi_end_deg = 90\n')
    r = _results(spec, tmp_path / "o")
    assert r["Je_min_kg_m2"] == pytest.approx(25, rel=1e-15)
    assert r["omega_final_rad_s"] == pytest.approx(
        math.sqrt((20 * math.pi) ** 2 - 2 * 10 * (math.pi / 2) / 25), rel=1e-12)


# -- no silent keys -------------------------------------------------------------------------
BASE_START = '[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nomega0 = 10\nphi_end_deg = 90\n'
BASE_STEADY = ('[inertia]\nJ = 1\n[moment]\ndrive = [100, 1]\n[moment.harmonic]\na = [5]\n'
               '[motion]\nkind = "steady"\nomega0 = 100\n')
BASE_MODEL = '[inertia]\nJ = 1\n'


@pytest.mark.parametrize("body, key", [
    # [flywheel] delta and the shape keys without [motion] (ignored before)
    (BASE_MODEL + '[flywheel]\ndelta = 0.05\n', "[flywheel] delta"),
    (BASE_MODEL + '[flywheel]\nshape = "rim"\nradius = 1\n', "[flywheel] shape"),
    (BASE_MODEL + '[flywheel]\ndensity = 7800\n', "[flywheel] density"),
    (BASE_MODEL + '[flywheel]\nradius = 1\n', "[flywheel] radius"),
    # dW / omega_mean with [motion] (ignored before)
    (BASE_START + '[flywheel]\nJ = 1\ndW = 100\nomega_mean = 10\n', "[flywheel] dW"),
    (BASE_STEADY + '[flywheel]\nomega_mean = 10\n', "[flywheel] omega_mean"),
    # delta with a start: a flywheel is sized in the steady state
    (BASE_START + '[flywheel]\ndelta = 0.05\n', "[flywheel] delta"),
    # δ outside (0, 2)
    (BASE_STEADY + '[flywheel]\ndelta = 2\n', "[flywheel] delta"),
    (BASE_STEADY + '[flywheel]\ndelta = 225\n', "[flywheel] delta"),
    # the motion's keys its form does not use
    (BASE_START + 'step_deg = 15\n', "[motion] step_deg"),
    (BASE_START + 'tol = 1e-8\n', "[motion] tol"),
    (BASE_START + 'rtol = 1e-8\n', "[motion] rtol"),
    (BASE_START.replace("[moment]\nconstant = 1", "[moment]\nharmonic.a = [1]")
     .replace("phi_end_deg", "kind = \"steady\"\nroot = \"repeat\"\n#"), "[motion] root"),
    ('[inertia]\nJ = 1\n[moment]\nconstant = 1\n[motion]\nomega0 = 10\nphi_end_deg = 90\n'
     '[output]\npoints = 10\n', "[output] points"),
    ('[mechanism]\ntype = "slider_crank"\nl1 = 0.1\nl2 = 0.3\n[[link]]\nnumber = 1\nmass = 1\n'
     'J = 1\ncom = [0, 0]\n[inertia]\nstep_deg = 0.01\n', "[inertia] step_deg"),
    # both spellings of one quantity
    (BASE_START.replace("omega0 = 10", "omega0 = 10\nn0_rpm = 100"), "[motion] n0_rpm"),
    ('[inertia]\nJ = 1\nmass = 1\nk = 1\n', "[inertia] mass"),
    # a table longer than its period
    ('[inertia]\nJ = 1\n[moment.table]\nphi_deg = [0, 360, 720]\nM = [0, 1, 0]\n[motion]\n'
     'omega0 = 10\nphi_end_deg = 90\n', "period_deg"),
    # periods that do not divide the longest
    ('[inertia]\nJ = 1\n[moment.table]\nperiod_deg = 720\nphi_deg = [0, 360, 720]\n'
     'M = [0, 1, 0]\n[moment.harmonic]\nperiod_deg = 500\na = [1]\n[motion]\nomega0 = 10\n'
     'phi_end_deg = 90\n', "period_deg"),
    # Simpson on an odd number of intervals
    ('[inertia]\nJ = 1\n[moment.table]\nphi_deg = [0, 120, 240, 360]\nM = [0, 1, -1, 0]\n'
     'integration = "simpson"\n[motion]\nomega0 = 10\nphi_end_deg = 90\n',
     "[moment.table] integration"),
    # "mean" with a motor line
    ('[inertia]\nJ = 1\n[moment]\ndrive = [100, 1]\nresisting = "mean"\n[moment.harmonic]\n'
     'a = [1]\n[motion]\nkind = "steady"\nomega0 = 10\n', "[moment] resisting"),
])
def test_every_unused_key_is_exit_2(tmp_path, body, key):
    spec = write(tmp_path, f'command = "flywheel"\n{body}')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    assert key in one_line_error(proc)


def test_a_swing_that_gives_delta_2_is_exit_2(tmp_path):
    """J = 1, ωm = 10: ΔW = 200 J gives δ = 200/(1·100) = 2 (by hand): ωmin would be 0."""
    spec = write(tmp_path, 'command = "flywheel"\n[inertia]\nJ = 1\n[flywheel]\ndW = 200\n'
                 'omega_mean = 10\n')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2 and "[flywheel] dW" in one_line_error(proc)


def test_an_unbalanced_diagram_cannot_be_sized(tmp_path):
    """A diagram with net work per cycle and no "mean" term: exit 3 naming [moment] and
    saying what to do."""
    spec = write(tmp_path, 'command = "flywheel"\n[moment.table]\nphi_deg = [0, 180, 360]\n'
                 'M = [0, 100, 0]\n[flywheel]\nomega_mean = 10\ndelta = 0.1\n')
    proc = run_inprocess("flywheel", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3
    line = one_line_error(proc)
    assert "[moment]" in line and '"mean"' in line
