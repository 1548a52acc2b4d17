"""configs/ch1/fivebar.toml's [expected] table matches its independent reference.

The reference numbers come from tests/reference/independent_fivebar.py (closed-form
circle intersection, hand-differentiated loop closure, brentq-refined extremes; it
imports nothing from mechcli).  This test reruns that script and compares it with
the config's [expected] table under the same tolerance rule ``mechcli check`` uses,
so a change to either one without the other fails here.
"""

import ast
import importlib.util

from mechcli.spec.expected import evaluate
from tests.conftest import CONFIGS, ROOT

SCRIPT = ROOT / "tests" / "reference" / "independent_fivebar.py"
CONFIG = CONFIGS / "ch1" / "fivebar.toml"


def _reference_module():
    spec = importlib.util.spec_from_file_location("independent_fivebar", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_reference_imports_nothing_from_mechcli():
    tree = ast.parse(SCRIPT.read_text(encoding="utf-8"))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert names and not [m for m in names if m.split(".")[0] == "mechcli"], names


def test_analytic_velocities_agree_with_finite_differences():
    # the script's own cross-check: 8th-order central difference, h = 0.005 rad
    diffs = _reference_module().fd_check()
    assert max(diffs.values()) < 1e-8, diffs


def test_config_expected_matches_independent_reference():
    results = _reference_module().reference()
    checks = evaluate(CONFIG, (), results)
    assert len(checks) >= 8
    failed = [c.as_dict() for c in checks if not c.held]
    assert not failed, failed
