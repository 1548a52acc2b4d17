"""Commands start without the libraries they do not need (issue 17, start-up).

``mechcli grashof --lengths`` classifies a handful of numbers: numpy alone costs
about as much as everything else it does.  ``mechcli kin --no-plot`` needs numpy,
but no picture library (matplotlib, PIL), no scipy, no rich in a pipe and not
``numpy.ma`` (``np.unique`` imports it).  ``mechcli --version`` and every run's
``outputs.json`` name the library versions without :mod:`importlib.metadata`
(~15 ms).  Each test runs the real command in a fresh ``python -X importtime``
process and reads, from the import log on stderr, which modules were imported;
it also checks the numbers the command printed, so a run that fails early cannot
pass.
"""

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("numpy", "scipy", "matplotlib", "PIL", "rich")

_IMPORT = re.compile(r"^import time:\s*\d+ \|\s*\d+ \|( *)([\w.]+)\s*$")


def imported_modules(stderr):
    """Full names of every module in a ``-X importtime`` log."""
    return {m.group(2) for m in map(_IMPORT.match, stderr.splitlines()) if m}


def imported_packages(stderr):
    """Top-level names of every module in a ``-X importtime`` log."""
    return {name.split(".")[0] for name in imported_modules(stderr)}


def run_importtime(*args, cwd):
    proc = subprocess.run([sys.executable, "-X", "importtime", "-m", "mechcli", *args],
                          capture_output=True, text=True, cwd=cwd, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc, imported_packages(proc.stderr)


#: what reading the versions of numpy, scipy and matplotlib must not cost (~15 ms)
SLOW_VERSIONS = ("importlib.metadata",)


def test_the_import_log_is_read():
    # the parser must see what a numpy import logs, or the tests below prove nothing
    proc = subprocess.run([sys.executable, "-X", "importtime", "-c",
                           "import numpy, numpy.ma, importlib.metadata"],
                          capture_output=True, text=True, timeout=120)
    names = imported_packages(proc.stderr)
    assert "numpy" in names and "json" not in names
    assert {"numpy.ma", "importlib.metadata"} <= imported_modules(proc.stderr)


def test_fourbar_text_form_imports_no_heavy_library(tmp_path):
    # stdout is a pipe here, as in a Makefile or CI: the table is plain text, without rich
    proc, names = run_importtime("grashof", "--lengths", "40,90,70,100", "--no-plot",
                                 "--out", str(tmp_path), cwd=tmp_path)
    assert "mechcli" in names
    assert sorted(set(HEAVY) & names) == []
    # outputs.json names the library versions (below) without importlib.metadata; no
    # spec file to read, so no TOML parser either
    assert sorted(set(SLOW_VERSIONS + ("tomllib",)) & imported_modules(proc.stderr)) == []
    versions = json.loads((tmp_path / "outputs.json").read_text())["versions"]
    assert versions["numpy"] == _installed("numpy") and versions["python"] == _python()
    # the crank-rocker of the quick form: K = 1.0971 (law of cosines, see
    # tests/unit/grashof/test_speed_grashof_scalar.py::test_example_3_1_crank_rocker)
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


def _installed(lib):
    """The installed version as the standard library reads it (the reference)."""
    import importlib.metadata
    return importlib.metadata.version(lib)


def _python():
    import platform
    return platform.python_version()


def test_version_reads_versions_without_importlib_metadata(tmp_path):
    proc = subprocess.run([sys.executable, "-X", "importtime", "-m", "mechcli", "--version"],
                          capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    mods = imported_modules(proc.stderr)
    assert sorted(set(SLOW_VERSIONS) & mods) == []
    assert sorted(set(HEAVY) & {m.split(".")[0] for m in mods}) == []
    line = proc.stdout.splitlines()[1]
    assert line == ", ".join([f"python {_python()}"] + [f"{lib} {_installed(lib)}" for lib in
                                                        ("numpy", "scipy", "matplotlib")])


def _theta3_at_0(l1, l2, l3, l4):
    """θ3 [°] of the open four-bar at θ1 = 0, by hand: B lies on the frame line, so
    BD = l4 - l1, and the cosine rule in triangle BCD gives the angle at D; the open
    branch has C above the frame: θ3 = 180° - angle BDC."""
    bd = l4 - l1
    return 180.0 - math.degrees(math.acos((l3 ** 2 + bd ** 2 - l2 ** 2) / (2 * l3 * bd)))


#: modules of the linkage engine that ``kin --no-plot`` has no use for
LINKAGE_NOT_FOR_KIN = tuple(f"mechcli.core.linkage.{m}" for m in (
    "sketch", "kinetostatics", "force_analysis", "force_model", "loads", "piston",
    "streaming", "approximate"))


def test_the_linkage_modules_named_exist():
    # a renamed module would make the check of kin --no-plot's imports pass vacuously
    import importlib.util

    for name in LINKAGE_NOT_FOR_KIN:   # the installed package's (CI tests the wheel)
        assert importlib.util.find_spec(name) is not None, name


@pytest.mark.parametrize("extra", [[], ["--json"]])
def test_kin_without_pictures_imports_no_picture_library(tmp_path, extra):
    proc, names = run_importtime("kin", str(ROOT / "configs" / "ch1" / "ex1-1.toml"),
                                 "--no-plot", "--out", str(tmp_path), *extra, cwd=tmp_path)
    mods = imported_modules(proc.stderr)
    assert "numpy" in names and "mechcli" in names
    assert sorted({"scipy", "matplotlib", "PIL", "rich"} & names) == []
    assert sorted({"numpy.ma", *SLOW_VERSIONS} & mods) == []
    # nothing of the force analysis, and not the drawing primitives' classes (built
    # only when a picture is drawn: mechcli.core.linkage.sketch)
    assert sorted(set(LINKAGE_NOT_FOR_KIN) & mods) == []
    assert "mechcli.core.linkage.kinematics" in mods   # the list above is of real names
    assert not list(tmp_path.glob("*.png"))
    # 例 1-1 (l1 = 101.6, l2 = 254, l3 = 177.8, l4 = 304.8 mm): θ3 at θ1 = 0 against
    # the cosine rule (_theta3_at_0, 96.6654°); the CSV has 10 significant digits
    head, row = (tmp_path / "kin.csv").read_text().splitlines()[:2]
    cells = dict(zip(head.split(","), row.split(",")))
    assert float(cells["theta1_deg"]) == 0.0
    assert float(cells["theta3_deg"]) == pytest.approx(_theta3_at_0(101.6, 254, 177.8, 304.8),
                                                       abs=1e-7)
    if extra:
        # the rocker's largest angle, 159.1513° (configs/ch1/ex1-1.toml: cosine rule with
        # crank and coupler stretched in line, AC = l1 + l2), printed to 4 decimals
        doc = json.loads(proc.stdout)
        assert doc["results"]["theta3_max_deg"] == pytest.approx(159.1513, abs=5e-5)
