"""mechcli optimize against tests/reference/independent_optimize.py (which imports
nothing from mechcli): 例 7-1's optimum, and the function deviation of the core
against the book's closed form (式 7-1, 7-4 ... 7-7) at a fixed design."""

import ast
import importlib.util

import numpy as np

from tests.conftest import CONFIGS, ROOT

SCRIPT = ROOT / "tests" / "reference" / "independent_optimize.py"


def _reference():
    spec = importlib.util.spec_from_file_location("independent_optimize", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _problem(name):
    from mechcli.commands.optimize import build_problem
    from mechcli.spec.optimize import read_optimize_spec
    return build_problem(read_optimize_spec(CONFIGS / "ch7" / name))


def test_reference_imports_nothing_from_mechcli():
    tree = ast.parse(SCRIPT.read_text(encoding="utf-8"))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert names and not [m for m in names if m.split(".")[0] == "mechcli"], names


def test_ex7_1_optimum_matches_independent_reference():
    from mechcli.core.optimize.methods import minimize
    ref = _reference().ex7_1()
    problem, _ = _problem("ex7-1.toml")
    res = minimize(problem, "slsqp")
    assert abs(res.x[0] - ref["x.mechanism.l2"]) < 1e-4
    assert abs(res.x[1] - ref["x.mechanism.l3"]) < 1e-4
    assert abs(res.f - ref["f"]) < 1e-4 * ref["f"]


def test_function_deviation_matches_book_closed_form():
    ref = _reference()
    _, evaluator = _problem("ex7-1.toml")
    designs = np.array([[4.1289, 2.3224], [6.0, 2.5], [4.6, 3.1]])
    det = evaluator.details(designs)
    n = ref.EX71_N
    dphi = (np.pi / 2) * np.arange(1, n + 1) / n
    dpsi = 2 / (3 * np.pi) * dphi ** 2
    for k, (l2, l3) in enumerate(designs):
        phi0, _ = ref.limit_position(1.0, l2, l3, 5.0)
        assert abs(det["phi0"][k] - phi0) < 1e-12
        book = ref.function_dev((1.0, l2, l3, 5.0), dphi, dpsi)
        np.testing.assert_allclose(det["dev"][k], book, rtol=0, atol=1e-12)
