"""Groups with no closed form solved by Newton (mechcli.core.linkage.newton_group, issue 30
§3): a class-IV group, a triad with a slider, a triad hung on two cranks.

References: an independent solution of each drawing (tests/reference/independent_joints.py:
MINPACK on the joints' coordinates, its own continuation, central differences for the
rates), the all-revolute triad's own element on the same drawing, the dead point where the
reference's continuation also ends, and the kinetostatics' power balance.
"""

import math

import numpy as np
import pytest

from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.linkage import drawing as drawing_module
from mechcli.core.linkage.newton_group import NewtonGroup
from mechcli.spec.kin import load_kin_spec
from tests.conftest import CONFIGS, ROOT, load_module, one_line_error, run_inprocess, run_json

REF = load_module(ROOT / "tests" / "reference" / "independent_joints.py")

#: (config, crank angles [deg], the joints the group solves)
CASES = [
    ("class4-group", np.arange(0.0, 360.0, 10.0), "CDEF"),
    ("class3-slider", np.arange(-175.0, 130.0, 10.0), "CEF"),
    ("class3-two-cranks", np.arange(0.0, 360.0, 10.0), "CEF"),
]


def _engine_motion(spec, q):
    omega = spec.input.omega
    ins = {spec.input.driver: DriverMotion(q, omega, 0.0)}
    for k, (ratio, phase) in spec.input.followers.items():
        ins[k] = DriverMotion(ratio * q + phase, ratio * omega, 0.0)
    return solve(spec.linkage, ins)


@pytest.mark.parametrize("name, deg, joints", CASES, ids=[c[0] for c in CASES])
def test_against_the_independent_solution(name, deg, joints):
    path = CONFIGS / "ch1" / f"{name}.toml"
    spec = load_kin_spec(path, ())
    assert any(isinstance(e, NewtonGroup) for e in spec.linkage.elements)
    q = np.radians(deg)
    m = _engine_motion(spec, q)
    assert m.regular.all()
    ref = REF.JointsLinkage(path).motion(q)
    for j in joints:
        p, v, a = ref[j]
        pm = m.points[j]
        got = [np.stack([pm.x, pm.y], -1), np.stack([pm.vx, pm.vy], -1),
               np.stack([pm.ax, pm.ay], -1)]
        # positions: both closed to round-off; rates: the reference's central differences
        # (step 1e-5 rad: ~1e-10 of the peak; Richardson on 1e-3/2e-3 rad: ~1e-8)
        for want, have, tol in zip((p, v, a), got, (1e-12, 1e-7, 1e-6)):
            assert np.max(np.abs(have - want)) <= tol * np.max(np.abs(want)), (j, tol)


def test_newton_group_equals_the_triad_element():
    # configs/ch1/class3-sixbar.toml's triad solved by the general group instead of
    # its own element (Cramer on the ternary link's pose): the same motion to round-off
    from mechcli.spec import joints as spec_joints

    path = CONFIGS / "ch1" / "class3-sixbar.toml"
    triad = load_kin_spec(path, ())
    spec_joints._SOLVED.clear()        # the reader remembers drawings: build it afresh
    mp = pytest.MonkeyPatch()
    mp.setattr(drawing_module._Builder, "_triad", drawing_module._Builder._newton_group)
    try:
        general = load_kin_spec(path, ())
    finally:
        mp.undo()
        spec_joints._SOLVED.clear()
    assert "NewtonGroup" in [type(e).__name__ for e in general.linkage.elements]
    q = np.radians(np.arange(0.0, 360.0, 0.25))
    ma, mb = _engine_motion(triad, q), _engine_motion(general, q)
    for j in "CEFM":
        for f in ("x", "y", "vx", "vy", "ax", "ay"):
            va, vb = getattr(ma.points[j], f), getattr(mb.points[j], f)
            assert np.max(np.abs(va - vb)) <= 1e-11 * np.max(np.abs(va)), (j, f)
    for n in (2, 3, 4, 5):
        for f in ("omega", "alpha"):
            va, vb = getattr(ma.links[n], f), getattr(mb.links[n], f)
            assert np.max(np.abs(va - vb)) <= 1e-11 * np.max(np.abs(va)), (n, f)


def test_extremes_are_the_reference_extremes():
    # configs/ch1/class4-group.toml's θ4 extremes: mechcli locates them where ω4 = 0;
    # the reference by a bounded search on its own continued positions
    path = CONFIGS / "ch1" / "class4-group.toml"
    res = run_json("kin", path, "-q")["results"]
    want = REF.extremes(REF.JointsLinkage(path), 4, np.radians(np.arange(0.0, 360.5, 1.0)))
    assert res["theta4_max_deg"] == pytest.approx(want[0], abs=1e-8)
    assert res["theta4_max_at_deg"] == pytest.approx(want[1], abs=1e-4)
    assert res["theta4_min_deg"] == pytest.approx(want[2], abs=1e-8)
    assert res["theta4_min_at_deg"] == pytest.approx(want[3], abs=1e-4)


def test_structure_of_a_class_iv_linkage():
    res = run_json("kin", CONFIGS / "ch1" / "class4-group.toml", "-q")["results"]
    assert res["mechanism_class"] == 4
    assert res["groups"][1] == {"type": "group", "class": 4, "links": [2, 3, 4, 5],
                                "joints": ["B", "G", "C", "F", "D", "E"]}


def test_a_dead_point_of_the_group_ends_the_sweep_where_the_reference_ends(tmp_path):
    # the slider triad over a whole turn: its drawn assembly ends at a dead point, which
    # is exit 3 naming it; the reference's continuation (MINPACK) reaches just short of
    # that angle and no further
    text = (CONFIGS / "ch1" / "class3-slider.toml").read_text(encoding="utf-8")
    text = text.split("[expected]")[0].replace("start = -175\nstop = 130\n", "")
    spec = tmp_path / "turn.toml"
    spec.write_text(text, encoding="utf-8")
    proc = run_inprocess("kin", spec, "-q", "--no-plot", "-o", tmp_path / "out")
    assert proc.returncode == 3
    line = one_line_error(proc)
    assert "limit of assembly at θ1 = 131.75" in line and "partial" in line
    limit = math.radians(float(line.split("θ1 = ")[1].split("°")[0]))
    ref = REF.JointsLinkage(spec)
    u = ref.sweep([limit - 1e-4])[0]      # the reference continued from the drawing
    with pytest.raises(RuntimeError):
        ref.solve_at(limit + 1e-4, ref.solve_at(limit - 1e-6, u))
    # and with partial = true the feasible range is analysed up to it
    spec.write_text(text.replace("step = 1\n", "step = 1\npartial = true\n"), encoding="utf-8")
    assert run_json("kin", spec, "-q")["results"]["positions"] > 300


FORCES = """
[[link]]
number = 2
mass = 2.0
J = 0.004
[[link]]
number = 3
mass = 1.0
J = 0.001
[[link]]
number = 4
mass = 3.0
J = 0.006
com = [20, 5]
[[link]]
number = 5
mass = 1.0
J = 0.001
[gravity]
g = 9.81
[[load]]
name = "work"
link = 4
force = [0, -200]
at = "E"
"""


@pytest.mark.parametrize("name", ["class4-group", "class3-slider", "class3-two-cranks"])
def test_kinetostatics_passes_the_power_balance(tmp_path, name):
    # masses, gravity and a load on every Newton-solved linkage: the balancing effort
    # from the pair equations equals the one from virtual power (Σ P = 0) to round-off
    text = (CONFIGS / "ch1" / f"{name}.toml").read_text(encoding="utf-8").split("[expected]")[0]
    text = text.replace('command = "kin"', 'command = "force"')
    spec = tmp_path / "f.toml"
    spec.write_text(text + FORCES.replace("number = 4\nmass = 3.0\nJ = 0.006\ncom = [20, 5]",
                                          "number = 4\nmass = 3.0\nJ = 0.006")
                    if name == "class3-slider" else text + FORCES, encoding="utf-8")
    res = run_json("force", spec, "-q")["results"]
    assert res["power_balance_residual"] < 1e-9
    assert res["force_balance_residual"] < 1e-9


def test_designs_of_one_topology_stack_into_one_batch(tmp_path):
    # two drawings of the class-IV linkage (its frame pivot G moved): engine.stack puts
    # the group's pair coordinates in (M, 1) columns and keeps a table per design; the
    # batch solves each design as it solves alone, to round-off
    from mechcli.core.linkage.engine import stack

    text = (CONFIGS / "ch1" / "class4-group.toml").read_text(encoding="utf-8")
    moved = tmp_path / "moved.toml"
    moved.write_text(text.replace("G = [150, 0]", "G = [146, 3]"), encoding="utf-8")
    specs = [load_kin_spec(CONFIGS / "ch1" / "class4-group.toml", ()), load_kin_spec(moved, ())]
    batch = stack([s.linkage for s in specs])
    q = np.radians(np.arange(0.0, 360.0, 2.0))
    mb = solve(batch, {1: DriverMotion(q, 10.0, 0.0)})
    for k, s in enumerate(specs):
        m = _engine_motion(s, q)
        for j in "CDEF":
            for f in ("x", "y", "vx", "vy", "ax", "ay"):
                va, vb = getattr(m.points[j], f), getattr(mb.points[j], f)[k]
                assert np.max(np.abs(va - vb)) <= 1e-12 * np.max(np.abs(va)), (k, j, f)
