"""``mechcli grashof --lengths`` starts without the heavy libraries.

The quick form classifies a handful of numbers: numpy alone costs about as much
as everything else it does (issue 17, start-up).  Each test runs the real
command in a fresh ``python -X importtime`` process and reads, from the import
log on stderr, which top-level packages were imported; it also checks the
numbers the command printed, so a run that fails early cannot pass.
"""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("numpy", "scipy", "matplotlib", "PIL", "rich")

_IMPORT = re.compile(r"^import time:\s*\d+ \|\s*\d+ \|( *)([\w.]+)\s*$")


def imported_packages(stderr):
    """Top-level names of every module in a ``-X importtime`` log."""
    names = set()
    for line in stderr.splitlines():
        m = _IMPORT.match(line)
        if m:
            names.add(m.group(2).split(".")[0])
    return names


def run_importtime(*args, cwd):
    proc = subprocess.run([sys.executable, "-X", "importtime", "-m", "mechcli", *args],
                          capture_output=True, text=True, cwd=cwd, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc, imported_packages(proc.stderr)


def test_the_import_log_is_read():
    # the parser must see what a numpy import logs, or the tests below prove nothing
    proc = subprocess.run([sys.executable, "-X", "importtime", "-c", "import numpy"],
                          capture_output=True, text=True, timeout=120)
    names = imported_packages(proc.stderr)
    assert "numpy" in names and "json" not in names


def test_fourbar_text_form_imports_no_heavy_library(tmp_path):
    # stdout is a pipe here, as in a Makefile or CI: the table is plain text, without rich
    proc, names = run_importtime("grashof", "--lengths", "40,90,70,100", "--no-plot",
                                 "--out", str(tmp_path), cwd=tmp_path)
    assert "mechcli" in names
    assert sorted(set(HEAVY) & names) == []
    # the crank-rocker of the quick form: K = 1.0971 (law of cosines, see
    # tests/unit/test_speed_grashof_scalar.py::test_example_3_1_crank_rocker)
    assert "crank rocker" in proc.stdout and "1.0971" in proc.stdout
    row = (tmp_path / "grashof.csv").read_text().splitlines()[1].split(",")
    assert row[6] == "crank_rocker" and float(row[11]) == pytest.approx(1.0970658942, abs=1e-9)


@pytest.mark.parametrize("args, key, value", [
    (["--lengths", "40,90,70,100"], "K", 1.0970658942),   # law of cosines, see above
    (["--lengths", "40,90,70,100", "--frame", "1", "--input", "2"], "type", "double_crank"),
    # slider-crank a = 20, b = 60, e = 40: the boundary case of the slides' exam problem 3
    (["--lengths", "20,60", "--offset", "40"], "stroke", 69.2820323028),   # 40 √3
])
def test_json_form_imports_no_heavy_library(tmp_path, args, key, value):
    proc, names = run_importtime("grashof", *args, "--json", "--out", str(tmp_path),
                                 cwd=tmp_path)
    assert sorted(set(HEAVY) & names) == []
    got = json.loads(proc.stdout)["results"][key]
    assert got == (pytest.approx(value, abs=1e-9) if isinstance(value, float) else value)
