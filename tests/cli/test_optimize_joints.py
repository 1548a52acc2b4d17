"""`optimize` over the joint coordinates of a linkage given by its joints (issue 30 §1):
the class-III six-bar's frame pivot H as the design variables; each design is a new
drawing (its links' lengths and its triad's continuation come from it)."""

import json

from tests.conftest import CONFIGS, run_inprocess, write_spec

SPEC = (CONFIGS / "ch1" / "class3-sixbar.toml").read_text(encoding="utf-8").split("[expected]")[0]
SPEC = SPEC.replace('command = "kin"', 'command = "optimize"\nproblem = "kin"')
SPEC = SPEC.replace("[output]\ntable_step = 30\n", "") + """
[[variable]]
key = "mechanism.joints.H.0"
lo = 60
hi = 100
[[variable]]
key = "mechanism.joints.H.1"
lo = 130
hi = 170

[objective]
kind = "function"
output = 4
phi0 = "output_min"
function = "power"
exponent = 1
x0 = 0
xm = 1
phi_m = 90
psi_m = 20
n = 10
measure = "sum_squares"
"""


def test_optimize_moves_a_joint_of_a_class3_drawing(tmp_path):
    proc = run_inprocess("optimize", write_spec(tmp_path, SPEC), "--out", tmp_path / "o",
                         "--json", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    r = json.loads(proc.stdout)["results"]
    # the objective at the drawing's H (the start), by the same program on one design
    start = run_inprocess("optimize", write_spec(tmp_path, SPEC.replace(
        "lo = 60\nhi = 100", "lo = 80.08\nhi = 80.0800001").replace(
        "lo = 130\nhi = 170", "lo = 150.21\nhi = 150.2100001"), name="s.toml"),
        "--out", tmp_path / "s", "--json", "--no-plot")
    assert start.returncode == 0, start.stderr
    f0 = json.loads(start.stdout)["results"]["f"]
    assert r["success"] and r["f"] < 0.5 * f0
    # the optimum is a spec that kin runs: the moved drawing closes
    opt = tmp_path / "o" / "optimum.toml"
    assert 'type = "joints"' in opt.read_text(encoding="utf-8")
    kin = run_inprocess("kin", opt, "--out", tmp_path / "k", "--json", "--no-plot")
    assert kin.returncode == 0, kin.stderr
    assert json.loads(kin.stdout)["results"]["mechanism_class"] == 3
