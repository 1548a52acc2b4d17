"""Every config in configs/ runs through the CLI and meets its [expected] values.

A new textbook case is a new TOML file with ``command = "..."`` and an
``[expected]`` table: no new test code.  Tolerances default to half a unit of
the last printed digit (see ``mechcli.spec.common.read_expected``).
"""

import json
import sys

import pytest

from mechcli.spec.common import read_expected
from mechcli.spec.reader import load_spec
from tests.conftest import CONFIGS, run_cli

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ALL = sorted(CONFIGS.rglob("*.toml"))


def _command(path):
    with open(path, "rb") as fh:
        return tomllib.load(fh).get("command")


@pytest.mark.parametrize("path", ALL, ids=[str(p.relative_to(CONFIGS)) for p in ALL])
def test_config_meets_expected(path, tmp_path):
    command = _command(path)
    assert command, f"{path} lacks a top-level command = '...'"
    proc = run_cli(command, path, "--json", "--no-plot", "--no-animate", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    results = doc["results"]
    expected = read_expected(load_spec(path))
    failures = []
    for name, exp in expected.items():
        if name not in results:
            failures.append(f"{name}: missing from results (have {sorted(results)})")
            continue
        got = results[name]
        if isinstance(exp.value, (bool, str)):
            if got != exp.value:
                failures.append(f"{name}: expected {exp.value!r}, got {got!r}")
        elif not abs(got - exp.value) <= exp.tol:
            failures.append(f"{name}: expected {exp.value} ± {exp.tol:.3g}, got {got}")
    assert not failures, "\n".join(failures)
