"""The scalar gear kinds run without numpy and without rich (issue 5: start-up time),
and their pure-Python paths agree with the numpy ones."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from mechcli.core.gear.spur import spur_gear
from mechcli.core.gear.involute import (involute_function, involute_point, involute_table,
                                   involute_table_rows, inverse_involute,
                                   inverse_involute_scalar)
from mechcli.report.files import OutputError
from mechcli.report.gear import csv_text
from tests.conftest import CONFIGS

PROBE = """
import json, sys
from mechcli.cli import main
sys.argv = ["mechcli", "gear", sys.argv[1], "--no-plot", sys.argv[2], "--out", sys.argv[3]]
try:
    main()
except SystemExit:
    pass
print(json.dumps({"numpy": "numpy" in sys.modules, "rich": "rich" in sys.modules}),
      file=sys.stderr)
"""


@pytest.mark.parametrize("name, flag", [("ex5-4", "-q"), ("ex5-1", "--json"),
                                        ("ex5-2", "-q"), ("exercise5-3", "--json"),
                                        ("exercise5-7", "-q")])
def test_scalar_kinds_import_neither_numpy_nor_rich(tmp_path, name, flag):
    proc = subprocess.run([sys.executable, "-c", PROBE, str(CONFIGS / "ch5" / f"{name}.toml"),
                           flag, str(tmp_path)], capture_output=True, text=True, timeout=60)
    loaded = json.loads(proc.stderr.strip().splitlines()[-1])
    assert loaded == {"numpy": False, "rich": False}, proc.stderr
    assert (tmp_path / "report.txt").exists()


def test_csv_text_follows_write_csv_rules(tmp_path):
    from mechcli.report.files import write_csv
    cols = [("a", [1, 0.1, 1 / 3, -2.5e-300]), ("b", [1e20, 123456789.123, 0.0, 7])]
    write_csv(tmp_path / "ref.csv", cols)
    assert csv_text(cols) == (tmp_path / "ref.csv").read_text()
    with pytest.raises(OutputError, match="non-finite b in row 2"):
        csv_text([("a", [1.0, 2.0]), ("b", [0.0, math.inf])])
    with pytest.raises(OutputError, match="non-finite"):
        csv_text([("a", [math.nan])])
    with pytest.raises(OutputError, match="expected 2"):
        csv_text([("a", [1.0, 2.0]), ("b", [0.0])])


def test_scalar_inverse_involute_matches_array_path():
    theta = np.concatenate([np.logspace(-12, 0, 301), [0.0, 1e-300, 1e6, 1e300]])
    arr = inverse_involute(theta)
    scal = [inverse_involute_scalar(float(t)) for t in theta]
    np.testing.assert_allclose([s[0] for s in scal], arr.alpha, rtol=5e-16, atol=0)
    assert max(s[1] for s in scal) <= 4
    book = inverse_involute(theta[:301], method="book")
    sb = [inverse_involute_scalar(float(t), "book") for t in theta[:301]]
    np.testing.assert_allclose([s[0] for s in sb], book.alpha, rtol=2e-15, atol=0)
    assert [s[1] for s in sb] == book.iterations.tolist()
    assert inverse_involute_scalar(0.02, "book")[:2] == (pytest.approx(0.3836426, abs=5e-8), 7)


def test_scalar_involute_paths_match_array_paths():
    a = np.linspace(0.0, 1.5, 301)
    np.testing.assert_allclose([involute_function(float(x)) for x in a], involute_function(a),
                               rtol=4e-15, atol=0)
    rows, ang, inv = involute_table()
    r2, a2, i2 = involute_table_rows()
    assert rows.tolist() == r2 and ang.tolist() == a2 and inv.tolist() == i2
    r, th, x, y = involute_point(0.05, 0.7)
    assert r == pytest.approx(0.05 / math.cos(0.7), rel=1e-15)
    assert (x, y) == pytest.approx((r * math.sin(th), r * math.cos(th)), rel=1e-15)
    g = spur_gear(17, 2e-3, math.radians(20), x=0.3)
    radii = np.linspace(g.rb, g.ra, 11)
    np.testing.assert_allclose([g.tooth_thickness(float(q)) for q in radii],
                               g.tooth_thickness(radii), rtol=1e-13, atol=1e-16)
    np.testing.assert_allclose([g.half_tooth_angle(float(q)) for q in radii],
                               g.half_tooth_angle(radii), rtol=1e-13, atol=1e-16)
