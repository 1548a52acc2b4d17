"""Review regressions for ``mechcli cam`` (each failed before its fix)."""

import math

import pytest

from mechcli.core.cam_motion import build_program
from mechcli.core.cam_profile import translating_base_radius_min
from tests.conftest import run_cli

SIZED = """command = "cam"
[follower]
contact = "roller"
rr = 5
[motion]
h = 20
segments = [
  { kind = "rise", angle = 180, law = "sine" },
  { kind = "return", angle = 180, law = "sine" },
]
[sizing]
base_radius = true
"""


@pytest.mark.parametrize("key", ["alpha_rise", "alpha_return"])
def test_zero_allowed_pressure_angle_is_a_spec_error(tmp_path, key):
    # [alpha] = 0 used to divide by tan 0 in the sizing (RuntimeWarning, NaN) and report a
    # meaningless "sized base radius 0.628 mm" with exit 3
    spec = tmp_path / "spec.toml"
    spec.write_text(SIZED + f"[limits]\n{key} = 0\n", encoding="utf-8")
    proc = run_cli("cam", spec, "--no-plot", "--out", tmp_path)
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr.strip()
    assert len(err.splitlines()) == 1 and key in err and "Warning" not in err, err


def test_sizing_core_rejects_a_zero_limit():
    prog = build_program([("rise", math.pi, "sine", 0.02), ("return", math.pi, "sine", 0.02)],
                         0.02)
    with pytest.raises(ValueError, match="allowed pressure angle"):
        translating_base_radius_min(prog, 0.0, 1, 0.0)
    with pytest.raises(ValueError, match="allowed pressure angle"):
        translating_base_radius_min(prog, 0.0, 1, math.radians(30), 0.0)
