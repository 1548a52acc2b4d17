"""The core stays pure; start-up stays light."""

import re
import subprocess
import sys

from tests.conftest import ROOT

FORBIDDEN = re.compile(r"^\s*(import|from)\s+(click|rich|matplotlib|tomllib|tomli)\b", re.M)


def test_core_imports_no_ui_plot_or_toml():
    offenders = [p.name for p in (ROOT / "mechcli" / "core").rglob("*.py")
                 if FORBIDDEN.search(p.read_text(encoding="utf-8"))]
    assert offenders == []


def test_core_does_not_open_files():
    offenders = [p.name for p in (ROOT / "mechcli" / "core").rglob("*.py")
                 if re.search(r"\bopen\(|\bprint\(", p.read_text(encoding="utf-8"))]
    assert offenders == []


def test_version_does_not_import_numpy_or_matplotlib():
    code = ("import sys; from mechcli import cli;"
            "print(sorted(m for m in ('numpy','matplotlib','scipy','rich') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.strip()
    assert out == "[]"
