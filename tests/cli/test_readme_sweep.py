"""The README's "sweep a parameter" line is a real sweep: a shell loop over ``--set``
values printing one JSON result per run (issue 31 §3).  It is run as written, by the
shell, in a folder whose ``configs`` is the checkout's."""

import math
import os
import re
import shutil
import subprocess
import sys

import pytest

from tests.conftest import ROOT


def _sweep():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    lines = readme.splitlines()
    at = next(i for i, ln in enumerate(lines) if "# sweep a parameter" in ln)
    start = at
    while lines[start - 1].endswith("\\"):
        start -= 1
    return "\n".join(lines[start:at + 1])


def _gamma_min(l1, l2=254.0, l3=177.8, l4=304.8):
    """γmin of 例 1-1's four-bar with crank l1, by hand: a crank-rocker's transmission
    angle is extreme where crank and frame are in line, |BD| = l4 ∓ l1 (cosine law)."""
    out = []
    for bd in (l4 - l1, l4 + l1):
        delta = math.degrees(math.acos((l2 ** 2 + l3 ** 2 - bd ** 2) / (2 * l2 * l3)))
        out.append(min(delta, 180 - delta))
    return min(out)


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs a POSIX shell")
def test_the_readme_sweep_prints_one_value_per_run(tmp_path):
    line = _sweep()
    assert line.startswith("for ") and "--set mechanism.l1=$l1" in line and "--json" in line
    (tmp_path / "configs").symlink_to(ROOT / "configs", target_is_directory=True)
    env = dict(os.environ, PATH=os.path.dirname(sys.executable) + os.pathsep
               + os.environ.get("PATH", ""))
    proc = subprocess.run(["bash", "-c", line], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    values = re.search(r"for l1 in ([\d. ]+); do", line).group(1).split()
    rows = [r.split() for r in proc.stdout.strip().splitlines()]
    assert [r[0] for r in rows] == values
    for l1, gamma in rows:
        assert float(gamma) == pytest.approx(_gamma_min(float(l1)), abs=1e-9)
