"""`mechcli optimize` from the command line: the book's 例 7-1 through every
method, the JSON names of the issue, optimum.toml runnable by `kin`, and every
kind of bad input as one line with exit 2 or 3."""

import json
import math
try:
    import tomllib
except ImportError:      # Python < 3.11
    import tomli as tomllib
from pathlib import Path

import pytest

from tests.conftest import one_line_error, run_inprocess, run_json

ROOT = Path(__file__).resolve().parents[2]
EX71 = ROOT / "configs" / "ch7" / "ex7-1.toml"
# 例 7-1 prints x = [4.1289, 2.3224], f = 0.0076 (four decimals: tolerance half a unit
# of the last digit)
BOOK_X = (4.1289, 2.3224)
BOOK_F = 0.0076


def _x(doc):
    x = doc["results"]["x"]
    return x["mechanism.l2"], x["mechanism.l3"]


def test_ex7_1_json_names_and_book_values(tmp_path):
    doc = run_json("optimize", EX71, "--out", tmp_path)
    r = doc["results"]
    for key in ("x", "f", "constraints", "iterations", "evaluations", "time_s", "method",
                "success"):
        assert key in r
    assert r["method"] == "slsqp" and r["success"] is True
    assert _x(doc) == pytest.approx(BOOK_X, abs=5e-5)
    assert r["f"] == pytest.approx(BOOK_F, abs=5e-5)
    # g8 (the angle BCD at most 134.99155 deg) is the active constraint of the book's optimum
    assert r["constraints"]["gamma_max"]["active"] is True
    assert abs(r["constraints"]["gamma_max"]["value"]) < 1e-6
    assert r["constraints"]["gamma_min"]["active"] is False
    assert r["constraints"]["gamma_min"]["value"] < -20      # γmin ≈ 70.4° >> 45°
    assert all(not r["constraints"][f"g{i}"]["active"] for i in range(1, 7))
    # the history's last f is the optimum's
    rows = (tmp_path / "history.csv").read_text().splitlines()
    head = rows[0].split(",")
    last = dict(zip(head, rows[-1].split(",")))
    assert float(last["f"]) == pytest.approx(r["f"], rel=1e-6)
    assert float(last["x_mechanism_l2"]) == pytest.approx(BOOK_X[0], abs=5e-5)


def test_optimum_toml_runs_through_kin_and_keeps_the_design(tmp_path):
    doc = run_json("optimize", EX71, "--out", tmp_path / "o")
    opt = tmp_path / "o" / "optimum.toml"
    data = tomllib.loads(opt.read_text(encoding="utf-8"))
    assert data["command"] == "kin"
    assert data["mechanism"]["l2"] == doc["results"]["x"]["mechanism.l2"]
    kin = run_json("kin", opt, "--out", tmp_path / "k")
    # independent check of the design: the rocker's smallest angle is at the extended
    # dead point, theta3 = acos(((l1+l2)^2 - l3^2 - l4^2) / (2 l3 l4)) (式 7-1's psi0)
    l2, l3 = _x(doc)
    psi0 = math.degrees(math.acos(((1 + l2) ** 2 - l3 ** 2 - 25) / (10 * l3)))
    assert kin["results"]["theta3_min_deg"] == pytest.approx(psi0, abs=1e-6)


@pytest.mark.parametrize("sets,tol", [
    (["method.name=trust-constr"], 5e-5),
    (["method.name=differential_evolution"], 1e-4),
    (["method.starts=3"], 5e-5),
    # Nelder-Mead needs a feasible start: l2 = 4.5, l3 = 2.5 meets g1 ... g8
    (["method.name=nelder-mead", "mechanism.l2=4.5", "mechanism.l3=2.5"], 2e-3),
])
def test_every_method_reaches_the_book_optimum(tmp_path, sets, tol):
    args = [a for s in sets for a in ("--set", s)]
    doc = run_json("optimize", EX71, "--out", tmp_path, *args)
    assert _x(doc) == pytest.approx(BOOK_X, abs=tol)
    assert doc["results"]["f"] == pytest.approx(BOOK_F, abs=5e-5)


def _fails(tmp_path, *sets, code=2):
    args = [a for s in sets for a in ("--set", s)]
    proc = run_inprocess("optimize", EX71, "--out", tmp_path, "--no-plot", *args)
    assert proc.returncode == code, proc.stderr
    return one_line_error(proc)


def test_unknown_variable_path_names_the_key_with_a_suggestion(tmp_path):
    line = _fails(tmp_path, 'variable.0.key="mechanism.l22"')
    assert "variable[0].key" in line or "variable.0" in line
    assert "mechanism.l2" in line and "did you mean" in line


def test_variable_that_is_not_a_number(tmp_path):
    line = _fails(tmp_path, 'variable.0.key="mechanism.type"')
    assert "the path of a number" in line and "four_bar" in line


def test_bounds_crossing_and_start_outside(tmp_path):
    assert "above lo" in _fails(tmp_path, "variable.0.hi=0.5")
    assert "within [lo, hi]" in _fails(tmp_path, "variable.0.start=30")


def test_a_bound_the_problem_rejects_is_named(tmp_path):
    line = _fails(tmp_path, "variable.0.lo=-1")
    assert "lo" in line and "mechanism.l2" in line


def test_golden_with_two_variables_is_a_spec_error(tmp_path):
    line = _fails(tmp_path, "method.name=golden")
    assert "golden" in line and "2 variables" in line


def test_infeasible_start_for_nelder_mead_is_exit_3(tmp_path):
    # the book's start [6, 2.5] violates g7 (angle BCD 29.6° < 45° at the folded position)
    line = _fails(tmp_path, "method.name=nelder-mead", code=3)
    assert "start" in line and "gamma_min" in line


def test_no_feasible_design_is_exit_3(tmp_path):
    # an angle BCD within 80...100 deg over a whole revolution: no crank-rocker with
    # l1 = 1, l4 = 5 has a swing that small (g7/g8 conflict)
    line = _fails(tmp_path, "constraint.1.min=80", "constraint.1.max=100", code=3)
    assert "no feasible design" in line


def test_maxiter_reached_is_exit_3_with_the_best_so_far(tmp_path):
    line = _fails(tmp_path, "method.maxiter=2", code=3)
    assert "maxiter = 2" in line and "best so far" in line


def test_result_key_unknown_names_a_near_result(tmp_path):
    spec = tmp_path / "r.toml"
    text = EX71.read_text(encoding="utf-8")
    head, _, _ = text.partition("[objective]")
    spec.write_text(head + '[objective]\nkind = "result"\nkey = "theta3_maxx_deg"\n'
                    '[method]\nname = "slsqp"\n', encoding="utf-8")
    proc = run_inprocess("optimize", spec, "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert "[objective] key" in line and "did you mean 'theta3_max_deg'" in line


def test_workers_give_the_same_answer(tmp_path):
    one = run_json("optimize", EX71, "--out", tmp_path / "a",
                   "--set", "method.name=differential_evolution")
    two = run_json("optimize", EX71, "--out", tmp_path / "b", "--workers", "2",
                   "--set", "method.name=differential_evolution")
    assert _x(one) == _x(two)
    assert one["results"]["evaluations"] == two["results"]["evaluations"]


# -- regressions from the independent review -------------------------------------------
def _spec(tmp_path, old_new, name="s.toml"):
    text = EX71.read_text(encoding="utf-8").split("[expected]")[0]
    for old, new in old_new:
        assert old in text, old
        text = text.replace(old, new)
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_the_answer_does_not_depend_on_the_unit_of_the_lengths(tmp_path):
    # 例 7-1 is dimensionless: every length x 1e4 gives x* x 1e4 and the same f (the
    # variables and f are scaled inside the local method)
    big = _spec(tmp_path, [("l1 = 1\n", "l1 = 10000\n"), ("l2 = 6 ", "l2 = 60000 "),
                           ("l3 = 2.5\n", "l3 = 25000\n"), ("l4 = 5\n", "l4 = 50000\n"),
                           ("lo = 1\nhi = 20", "lo = 10000\nhi = 200000")])
    doc = run_json("optimize", big, "--out", tmp_path / "o")
    x = doc["results"]["x"]
    assert x["mechanism.l2"] == pytest.approx(1e4 * BOOK_X[0], abs=1e4 * 5e-5)
    assert x["mechanism.l3"] == pytest.approx(1e4 * BOOK_X[1], abs=1e4 * 5e-5)
    assert doc["results"]["f"] == pytest.approx(BOOK_F, abs=5e-5)


def test_a_variable_that_moves_nothing_is_refused(tmp_path):
    line = _fails(tmp_path, 'variable.0.key="input.omega1"')
    assert "moves nothing" in line and "input.omega1" in line


def test_discrete_keys_are_not_variables(tmp_path):
    line = _fails(tmp_path, 'variable.0.key="mechanism.l1"', 'variable.1.key="input.step"')
    assert "input.step" in line and "not design variables" in line


def test_a_goal_variable_the_goal_does_not_use_is_refused(tmp_path):
    spec = _spec(tmp_path, [('key = "mechanism.l3"\nlo = 1\nhi = 20',
                             'key = "objective.phi0"\nlo = 0\nhi = 90\nstart = 30')])
    proc = run_inprocess("optimize", spec, "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 2
    assert "objective.phi0" in one_line_error(proc) and "output_min" in proc.stderr


def test_transmission_joint_that_is_not_an_rrr_joint(tmp_path):
    line = _fails(tmp_path, 'constraint.1.joints=["Q"]')
    assert "joints" in line and "C" in line


def test_two_transmission_constraints_keep_both_in_the_json(tmp_path):
    spec = _spec(tmp_path, [("[method]", '[[constraint]]\nkind = "transmission"\nmin = 30\n'
                             "over = \"range\"\n\n[method]")])
    r = run_json("optimize", spec, "--out", tmp_path / "o")["results"]["constraints"]
    assert {"gamma_min", "gamma_max", "gamma_min_2", "gamma_max_2"} <= set(r)
    assert r["gamma_min"]["value"] != r["gamma_min_2"]["value"]


def test_history_marks_designs_that_could_not_be_evaluated(tmp_path):
    # SLSQP's first step from the book's start leaves the crank-rockers (l3 = 13)
    run_json("optimize", EX71, "--out", tmp_path)
    rows = [dict(zip(*(line.split(",") for line in pair)))
            for pair in [((tmp_path / "history.csv").read_text().splitlines()[0], row)
                         for row in (tmp_path / "history.csv").read_text().splitlines()[1:]]]
    assert {float(r["evaluable"]) for r in rows} <= {0.0, 1.0}
    assert float(rows[-1]["evaluable"]) == 1.0
    for r in rows:
        if float(r["evaluable"]) == 0.0:
            assert float(r["violation"]) >= 1.0
