"""Issue 18 item 6: a curve drawn clipped says so, on the figure and once on stderr
with the spec path; a curve that fits says nothing."""
import csv

import pytest

from tests.conftest import CONFIGS, run_inprocess


def _rho_max(out):
    """The largest |radius of curvature| in cam.csv (pitch and working curve)."""
    with open(out / "cam.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    cols = [c for c in ("rho_pitch_mm", "rho_work_mm") if c in rows[0]]   # flat face: no pitch
    return max(abs(float(r[c])) for r in rows for c in cols)


@pytest.mark.parametrize("name, r0, clipped", [
    ("ex4-1", 40.0, True),     # 【例 4-1】 r0 = 40 mm: its pitch curve flattens (|ρ| grows past 4 r0)
    ("ex4-2", 30.0, False),    # 【例 4-2】 r0 = 30 mm, flat-faced: ρ stays within 4 r0
])
def test_a_clipped_radius_of_curvature_is_announced(tmp_path, name, r0, clipped):
    spec = CONFIGS / "ch4" / f"{name}.toml"
    out = tmp_path / name
    proc = run_inprocess("cam", spec, "--out", out)
    assert proc.returncode == 0, proc.stderr
    # the figure clips at 4 r0 (cam_plots.checks): what the CSV holds decides it
    assert (_rho_max(out) > 4 * r0) is clipped
    notices = [ln for ln in proc.stderr.splitlines() if "clipped" in ln]
    if clipped:
        assert len(notices) == 1, proc.stderr
        assert str(spec) in notices[0] and "±160 mm (4 r0)" in notices[0]
    else:
        assert notices == []
