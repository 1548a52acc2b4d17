"""习题 3-5, 3-8 and 6-1: each config's [expected] table matches its independent reference.

The reference numbers come from tests/reference/independent_exercises_ch3_ch6.py (closed
forms for the clamp of 3-5 and the bus door of 3-8; the carrier six-bar of 6-1 with
hand-differentiated kinematics; it imports nothing from mechcli).  These tests rerun that
script and compare it with the configs' [expected] tables under the rule ``mechcli check``
uses, and check that each config's inputs are the reference's (read with tomllib), so a
change to one without the other fails here.  Every number below says where it comes from.
"""

from __future__ import annotations

import ast
import math
import sys

from mechcli.spec.expected import evaluate
from tests.conftest import CONFIGS, ROOT, load_module

if sys.version_info >= (3, 11):
    import tomllib
else:       # pragma: no cover
    import tomli as tomllib

SCRIPT = ROOT / "tests" / "reference" / "independent_exercises_ch3_ch6.py"
CONFIG_3_5 = CONFIGS / "ch3" / "exercise3-5.toml"
CONFIG_3_8 = CONFIGS / "ch3" / "exercise3-8.toml"
CONFIG_6_1 = CONFIGS / "ch6" / "exercise6-1.toml"


REF = load_module(SCRIPT)


def _toml(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


def _held(config, results, at_least):
    checks = evaluate(config, (), results)
    assert len(checks) >= at_least
    failed = [c.as_dict() for c in checks if not c.held]
    assert not failed, failed


def test_reference_imports_nothing_from_mechcli():
    tree = ast.parse(SCRIPT.read_text(encoding="utf-8"))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert names and not [m for m in names if m.split(".")[0] == "mechcli"], names


# ---------------------------------------------------------------- 习题 3-5 ----------

def test_exercise_3_5_inputs_are_the_references():
    # the config's points and lines are the poses P1(0.5, 0.5) 20°, P2(1.5, 1.8) 38° of the
    # exercise with the reading B' = (0, 0), C' = (1, 0) that the reference uses
    syn = _toml(CONFIG_3_5)["synthesis"]
    d = REF.clamp_design()
    for key in ("B", "C"):
        for i in (0, 1):
            got, want = syn[key][i], d[f"{key}{i + 1}"]
            assert math.dist(got, want) < 1e-15, (key, i, got, want)
    a, b, c = syn["A_line"]          # A on the line through B2 and C2 (the dead point)
    for p in (d["B2"], d["C2"], d["A"]):
        assert abs(a * p[0] + b * p[1] - c) < 1e-14
    a, b, c = syn["D_line"]          # D on the vertical through C2
    assert (a, b) == (1, 0) and c == d["C2"][0] == d["D"][0]
    assert syn["driver"] == "CD"


def test_exercise_3_5_design_conditions():
    d = REF.clamp_design()
    A, D = d["A"], d["D"]
    # eqs. 3-7, 3-8: each fixed pivot is equidistant from its moving pivot's two positions
    assert abs(math.dist(A, d["B1"]) - math.dist(A, d["B2"])) < 1e-14
    assert abs(math.dist(D, d["C1"]) - math.dist(D, d["C2"])) < 1e-14
    # the dead point at pose 2: |AC2| = l1 + l2 (B2 between A and C2: t < 0)
    assert d["t"] < 0
    assert abs(math.dist(A, d["C2"]) - (d["l1"] + d["l2"])) < 1e-14
    # C2D vertical
    assert d["C2"][0] == D[0] and d["C2"][1] > D[1]
    # driven by CD from pose 1 (clockwise, 123.34°), the linkage stays assembled up to pose 2,
    # where it reaches the dead point; the other way round it comes apart
    motion = REF.clamp_motion()
    sweep, margin, gap = motion[-1]
    assert abs(sweep - 123.34358640665127) < 1e-9 and margin > 0 and abs(gap) < 1e-12
    assert motion[1][1] < 0


def test_exercise_3_5_expected_matches_reference():
    _held(CONFIG_3_5, REF.exercise_3_5(), 8)


# ---------------------------------------------------------------- 习题 3-8 ----------

def test_exercise_3_8_inputs_are_the_references():
    spec = _toml(CONFIG_3_8)
    mech, inp = spec["mechanism"], spec["input"]
    # l1 is the closed form r = (182500 + 120000 cos 65°)/(300 + 800 cos 65°)
    assert abs(mech["l1"] - REF.door_crank()) < 1e-9
    assert (mech["type"], mech["l2"], mech["e"]) == ("slider_crank", 400, 0)
    # the sweep runs from the closed door (crank angle 0) to the open one
    assert inp["start"] == 0 and abs(inp["stop"] - REF.door_open_angle()) < 1e-9


def test_exercise_3_8_design_by_hand():
    r = REF.door_crank()
    # the cosine law it solves, in the triangle A C2 B2 with 65° at C2
    c65 = math.cos(math.radians(65))
    assert abs(r * r - (400 ** 2 + (r - 150) ** 2 - 2 * 400 * (r - 150) * c65)) < 1e-8
    res = REF.exercise_3_8()
    # γmin = 90° − 65° at the open position; the closed-form grid agrees
    assert res["gamma_min_deg"] == 25.0 and abs(res["gamma_min_grid_deg"] - 25.0) < 1e-9
    # of the four designs with the closed door along the track (the config's FIGURE-READING
    # lists them: l_AB = 365.5, 474.6, 3459, 618.2 mm), only the config's one moves
    readings = REF.door_readings()
    assert [k for k, (_, moves) in readings.items() if moves] == [(65.0, "towards")]
    assert [round(float(v[0]), 1) for v in readings.values()] == [365.5, 474.6, 3459.4, 618.2]


def test_exercise_3_8_expected_matches_reference():
    _held(CONFIG_3_8, REF.exercise_3_8(), 8)


# ---------------------------------------------------------------- 习题 6-1 ----------

def test_exercise_6_1_inputs_are_the_references():
    spec = _toml(CONFIG_6_1)
    mech = spec["mechanism"]
    assert mech["ground"]["A"] == list(REF.A6) and mech["ground"]["D"] == list(REF.D6)
    assert mech["ground"]["G"][0] == REF.X_GUIDE
    assert mech["driver"][0]["length"] == REF.L_AB
    rrr, rrp = mech["dyad"]
    assert rrr["lengths"] == [REF.L_BC, REF.L_CD] and rrp["length"] == REF.L_EF
    assert mech["point"][0]["along"] == -REF.L_DE
    assert spec["link"] == [{"number": 5, "mass": REF.M5}]
    assert spec["load"][0]["force"] == list(REF.F5)
    assert spec["output"]["points"] == 2


def test_exercise_6_1_derivatives_agree_with_finite_differences():
    # the script's own cross-check: 8th-order central difference, h = 1e-3 rad
    worst = REF.fd_check()
    assert max(worst.values()) < 1e-9, worst


def test_exercise_6_1_by_hand():
    res = REF.exercise_6_1()
    # ω2 = 0, ω3 = ω1 l_AB/l_CD = ω1/2, α3 = 0 in the stated position (the config's comments)
    assert abs(res["omega2_per_omega1"]) < 1e-15
    assert abs(res["omega3_per_omega1"] - 0.5) < 1e-15
    assert abs(res["alpha3_per_omega1_sq"]) < 1e-15
    # Je = 20 · (0.1 · 0.1/0.2)² = 0.05 kg m², Me = −1000 · 0.05 = −50 N m
    assert abs(res["Je_max_kg_m2"] - 0.05) < 1e-15 and abs(res["Me_min_N_m"] + 50) < 1e-12


def test_exercise_6_1_expected_matches_reference():
    _held(CONFIG_6_1, REF.exercise_6_1(), 6)
