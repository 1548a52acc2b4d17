"""``mechcli force`` at the edges of its input: huge finite masses, periodic factor
tables, upside-down windows, load messages that name the right key, the input column."""

import math

import numpy as np
import pytest

from mechcli.core.linkage.kinetostatics import Load, LoadProgram
from mechcli.spec.errors import SpecError
from mechcli.spec.force import load_force_spec
from tests.conftest import CONFIGS, one_line_error, run_inprocess, write_spec

SLIDER_DRIVEN = """
command = "force"
title = "slider driven"
units = "mm"
[mechanism]
type = "general"
frame = 4
[mechanism.ground]
O = [0, 0]
D = [300, 200]
[[mechanism.driver]]
type = "slider"
link = 3
origin = "O"
point = "B"
[[mechanism.dyad]]
type = "RRR"
joint = "C"
points = ["B", "D"]
links = [2, 1]
lengths = [300, 250]
[input]
v1 = 100
start = 0
stop = 200
step = 1
[[link]]
number = 3
mass = 2
[[link]]
number = 2
mass = 1
J = 0.01
[gravity]
g = 9.8
"""


def _spec_error(tmp_path, text):
    with pytest.raises(SpecError) as exc:
        load_force_spec(write_spec(tmp_path, text))
    return str(exc.value)


def test_huge_finite_mass_is_a_spec_error_not_an_internal_error(tmp_path):
    # mass = 1e300 used to overflow the RMS to inf: internal error, exit 1
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-2.toml", "--no-plot", "--json",
                   "--out", tmp_path, "--set", "link.0.mass=1e300")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert "[link.0] mass" in line and "ex2-2.toml" in line


def test_rotary_factor_table_is_periodic():
    # a table over part of the turn closes on its first point (linear, periodic)
    xs = np.radians([0.0, 90.0, 180.0])
    prog = LoadProgram(Load("F", 1, 1.0, 0.0), table=(xs, np.array([1.0, 0.0, 0.5])))
    f = prog.factor(np.radians([45.0, 270.0, 359.0, 360.0]))
    assert f == pytest.approx([0.5, 0.75, 0.5 + 0.5 * 179 / 180, 1.0])


def test_linear_window_upside_down_is_rejected(tmp_path):
    text = SLIDER_DRIVEN + """
[[load]]
name = "P"
link = 2
torque = 1
when = { window = [150, 50] }
"""
    msg = _spec_error(tmp_path, text)
    assert "[load.0.when] window" in msg


def test_at_from_with_pure_torque_names_at_from(tmp_path):
    text = (CONFIGS / "ch2" / "ex2-2.toml").read_text(encoding="utf-8").replace(
        "force = [-1000, 0]", 'torque = 5\nat_from = "C"')
    msg = _spec_error(tmp_path, text)
    assert "[load.0] at_from" in msg


def test_band_without_any_slide_says_so(tmp_path):
    text = SLIDER_DRIVEN + """
[[load]]
name = "P"
link = 2
torque = 1
when = { band = [0.1, 0.9] }
"""
    msg = _spec_error(tmp_path, text)
    assert "a slide of this linkage: ," not in msg
    assert "RRP or RPR" in msg


def test_report_input_column_names_the_driver(tmp_path):
    from mechcli.core.linkage.force_analysis import analyse_forces
    from mechcli.report.force import build_report, input_column

    spec = load_force_spec(write_spec(tmp_path, SLIDER_DRIVEN))
    inp = spec.input
    sweep = inp.sweep()
    res = analyse_forces(spec.linkage, spec.topology, sweep, spec.bodies, spec.gravity,
                         spec.loads)
    rep = build_report(spec, res)
    assert input_column(spec) == "s3_mm"
    assert rep.blocks[0].headers[0] == "s3/(mm)"
    assert math.isfinite(res.mean["Fb"])
