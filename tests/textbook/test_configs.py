"""Every config in configs/ runs through the CLI and meets its [expected] values.

A new textbook case is a new TOML file with ``command = "..."`` and an
``[expected]`` table: no new test code.  Each config runs exactly as
``mechcli check`` runs it (:func:`mechcli.batch.run_spec`: the command its
``command`` key names, ``--json --no-plot --no-animate``), and "expected" means
what :mod:`mechcli.spec.expected` says: the spec's tolerance, otherwise half a
unit of the last digit as written in the file.
"""

import pytest

from mechcli.batch import run_spec
from mechcli.report.check import error_lines, failure_lines
from tests.conftest import CONFIGS

ALL = sorted(CONFIGS.rglob("*.toml"))


@pytest.mark.parametrize("path", ALL, ids=[str(p.relative_to(CONFIGS)) for p in ALL])
def test_config_meets_expected(path, tmp_path):
    result = run_spec(path, out_dir=tmp_path)
    assert result["command"], result["error"]
    lines = error_lines([result], []) + failure_lines([result])
    assert result["status"] == "passed", "\n".join(lines) + "\n" + result["stderr"]
