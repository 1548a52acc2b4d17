"""Pictures of ``mechcli force``: force.png, hodograph.png, frame.png and force.gif."""

import json

import pytest

from tests.conftest import CONFIGS, run_inprocess, write_spec

PNGS = ("force.png", "hodograph.png", "frame.png")
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

# A non-Grashof four-bar driven by its "crank": the input can only swing, so the
# analysed range has a gap (partial = true) and every curve must break across it.
PARTIAL = """\
command = "force"
title = "partial range"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 600
l2 = 500
l3 = 700
l4 = 1000
branch = "open"
[input]
omega1 = 10
step = 2
partial = true
[[link]]
number = 2
mass = 3
J = 0.25
[[link]]
number = 3
mass = 2.2
J = 0.09
[gravity]
g = 10
[[load]]
name = "Mr"
link = 3
torque = -100
[output]
frames = 24
"""


def _check_png(path):
    from PIL import Image

    assert path.read_bytes()[:8] == PNG_MAGIC
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        w, h = im.size
        assert w > 300 and h > 300


def _check_gif(path, frames):
    from PIL import Image

    assert path.read_bytes()[:6] in (b"GIF87a", b"GIF89a")
    with Image.open(path) as im:
        assert im.n_frames == frames
        assert im.is_animated


@pytest.mark.parametrize("config", ["ex2-4", "ex2-1", "exercise2-8"])
def test_force_pictures_and_animation(tmp_path, config):
    out = tmp_path / "out"
    proc = run_inprocess("force", CONFIGS / "ch2" / f"{config}.toml", "--out", out, "--animate",
                   "--json")
    assert proc.returncode == 0, proc.stderr
    files = json.loads(proc.stdout)["files"]
    for name in PNGS:
        assert str(out / name) in files
        _check_png(out / name)
    assert str(out / "force.gif") in files
    _check_gif(out / "force.gif", 72)   # output.frames default, the closing 360° not repeated


def test_no_plot_writes_no_picture(tmp_path):
    out = tmp_path / "out"
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-4.toml", "--out", out, "--no-plot")
    assert proc.returncode == 0, proc.stderr
    assert (out / "force.csv").exists()
    assert not list(out.glob("*.png"))
    assert not list(out.glob("*.gif"))


def test_no_plot_with_animate_writes_only_the_gif(tmp_path):
    out = tmp_path / "out"
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-1.toml", "--out", out, "--no-plot",
                   "--animate")
    assert proc.returncode == 0, proc.stderr
    assert not list(out.glob("*.png"))
    _check_gif(out / "force.gif", 72)


def test_chinese_labels(tmp_path):
    out = tmp_path / "out"
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-4.toml", "--out", out, "--lang", "zh")
    assert proc.returncode == 0, proc.stderr
    for name in PNGS:
        _check_png(out / name)


def test_partial_range_pictures(tmp_path):
    spec = write_spec(tmp_path, PARTIAL)
    out = tmp_path / "out"
    proc = run_inprocess("force", spec, "--out", out, "--animate", "--json")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["results"]["excluded"], "the spec must have a gap"
    for name in PNGS:
        _check_png(out / name)
    _check_gif(out / "force.gif", 24)  # frames = 24, spread over the analysed arcs


def test_runs_break_curves_and_frames_are_finite():
    """In-process: curves get a NaN between runs; the frames avoid non-finite forces."""
    import numpy as np

    from mechcli.report import force_plots
    from mechcli.report.kin_plots import broken

    class Kin:
        runs = [(0, 3), (3, 5)]

    v = broken(Kin, np.arange(5.0))
    assert np.isnan(v[3]) and v.size == 6

    class Pair:
        fx = np.array([1.0, np.nan, 2.0, 3.0])
        fy = np.zeros(4)

    class Points:
        p = np.zeros(4, dtype=complex)

    class Motion:
        points = {"A": Points}

    class Res:
        q = np.linspace(0, 2 * np.pi, 4)
        forces = type("F", (), {"pairs": [Pair]})
        kin = type("K", (), {"motion": Motion})

    idx = force_plots._frame_indices(Res, 72, periodic=True)
    assert list(idx) == [0, 2]
