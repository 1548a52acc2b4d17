"""configs/ch1/exercise1-4 … exercise1-8.toml: their [expected] tables match the independent
reference tests/reference/independent_exercises_ch1a.py.

The reference (numpy only, nothing from mechcli) writes each exercise's mechanism out in the
reading its config states, differentiates the loop equations by hand and refines the extremes
on the exact derivative; its closed forms are the limit-position formulas the configs'
comments derive by hand.  Here it is rerun and compared with each config's [expected] table,
read with tomllib, under the rule ``mechcli check`` uses (half a unit of the last digit as
written, unless the entry gives ``tol`` or ``rtol``), so a change to either side alone fails.
The numbers in the self-checks are round-off bounds: the reference's own measured residuals
are 1e-12 relative (finite differences) and 2e-13 mm (loop closure).
"""

from __future__ import annotations

import ast
import re
import sys
from decimal import Decimal

import pytest

from tests.conftest import CONFIGS, ROOT, load_module

if sys.version_info >= (3, 11):
    import tomllib
else:                                   # pragma: no cover - Python < 3.11
    import tomli as tomllib

SCRIPT = ROOT / "tests" / "reference" / "independent_exercises_ch1a.py"
NAMES = ("exercise1-4", "exercise1-5", "exercise1-6", "exercise1-7", "exercise1-8")


@pytest.fixture(scope="module")
def ref():
    return load_module(SCRIPT)


@pytest.fixture(scope="module")
def results(ref):
    return ref.reference(), ref.closed_forms()


def _literal_tolerances(text):
    """{key: tol} of the plain numbers of the [expected] table, from their written digits."""
    tols, inside = {}, False
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("["):
            inside = stripped == "[expected]"
            continue
        m = re.match(r"([A-Za-z0-9_]+)\s*=\s*([-+]?[0-9][0-9_.eE+-]*)\s*(#.*)?$", stripped)
        if inside and m:
            lit = Decimal(m.group(2).replace("_", ""))
            tols[m.group(1)] = 0.5 * 10.0 ** lit.as_tuple().exponent
    return tols


def test_reference_imports_nothing_from_mechcli():
    tree = ast.parse(SCRIPT.read_text(encoding="utf-8"))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert names and not [m for m in names if m.split(".")[0] == "mechcli"], names


def test_analytic_derivatives_agree_with_finite_differences(ref):
    # 8th-order central differences (h = 2e-3 rad: truncation ~1e-18) of every position and
    # velocity against the hand-derived velocity and acceleration; measured 6e-13 ... 4e-12
    worst = ref.fd_check()
    assert set(worst) == set(NAMES)
    assert max(worst.values()) < 1e-10, worst


def test_loop_closure(ref):
    # every joint distance of each model against its link length; measured <= 2e-13 mm
    worst = ref.loop_check()
    assert max(worst.values()) < 1e-9, worst


def test_closed_forms_agree_with_the_numeric_extremes(ref, results):
    numeric, closed = results
    for name in NAMES:
        shared = set(closed[name]) & set(numeric[name])
        assert len(shared) >= 5, (name, shared)
        for key in shared:
            a, b = closed[name][key], numeric[name][key]
            assert abs(a - b) <= 1e-9 * max(1.0, abs(a)), (name, key, a, b)
    # the least transmission angle: the cosine law at BD = AD -+ l1 against a 0.01° grid
    for model in (ref.Ex17(), ref.Ex18()):
        grid_min = ref.gamma_min_grid(model)
        exact = closed[model.name]["gammaC_min_deg"]
        assert exact <= grid_min + 1e-9 and grid_min - exact < 1e-4, (model.name, exact,
                                                                       grid_min)


@pytest.mark.parametrize("name", NAMES)
def test_config_expected_matches_reference(name, results):
    numeric, closed = results
    path = CONFIGS / "ch1" / f"{name}.toml"
    text = path.read_text(encoding="utf-8")
    spec = tomllib.loads(text)
    assert spec["command"] == "kin"
    assert spec["title"].startswith("习题 " + name[len("exercise"):] + " ")
    expected = spec["expected"]
    tols = _literal_tolerances(text)
    assert len(expected) >= 15
    failed = []
    for key, entry in expected.items():
        if isinstance(entry, dict):
            value = entry["value"]
            tol = entry["tol"] if "tol" in entry else entry["rtol"] * abs(value)
        else:
            value, tol = entry, tols[key]
        got = numeric[name].get(key, closed[name].get(key))
        assert got is not None, f"{name}: no reference value for [expected] {key}"
        if abs(got - value) > tol * (1 + 1e-9):
            failed.append((key, value, got, tol))
    assert not failed, failed
