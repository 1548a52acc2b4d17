"""Pictures of ``mechcli optimize``: convergence.png, surface.png (two variables),
target.png (function or path goal) and optimize.gif, for 【例 7-1】 and a path problem."""

import json

import numpy as np
import pytest

from tests.conftest import CONFIGS, run_inprocess, write_spec

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
EX7_1 = CONFIGS / "ch7" / "ex7-1.toml"

# A general-form four-bar whose coupler point M should pass through eight points:
# the points are M's positions at crank angles 0, 45, ..., 315 deg of the design
# along = 50, normal = 20, D = (80, 0) (so the optimum is known and f* ~ 0).
PATH = """\
command = "optimize"
title = "path generation: coupler point M through eight points"
units = "mm"
problem = "kin"

[mechanism]
type = "general"
frame = 4

[mechanism.ground]
A = [0, 0]
D = [80, 0]

[[mechanism.driver]]
type = "crank"
link = 1
pivot = "A"
point = "B"
length = 40

[[mechanism.dyad]]
type = "RRR"
joint = "C"
points = ["B", "D"]
links = [2, 3]
lengths = [120, 100]
branch = "left"

[[mechanism.point]]
name = "M"
link = 2
from = "B"
along = 50
normal = 20

[input]
omega1 = 1
step = 5

[[variable]]
key = "mechanism.point.0.along"
lo = 20
hi = 100
start = 70

[[variable]]
key = "mechanism.point.0.normal"
lo = -30
hi = 50
start = 0

[[variable]]
key = "mechanism.ground.D.0"
lo = 70
hi = 95
start = 85

[objective]
kind = "path"
point = "M"
x = [55.638, 63.398, 34.651, 0.171, -22.512, -25.823, -12.188, 12.851]
y = [51.531, 69.113, 81.223, 74.004, 50.933, 25.511, 12.454, 23.309]

[[constraint]]
kind = "assembly"

[method]
name = "differential_evolution"
maxiter = 30
seed = 3
"""


def _check_png(path, min_side=300):
    from PIL import Image

    assert path.is_file(), path
    assert path.read_bytes()[:8] == PNG_MAGIC
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        w, h = im.size
        assert w > min_side and h > min_side, (path.name, im.size)
        # not a blank canvas: a real figure has many colours
        assert len(im.convert("RGB").getcolors(maxcolors=1 << 20) or ()) > 50


def _check_gif(path, min_frames=10):
    from PIL import Image

    assert path.read_bytes()[:6] in (b"GIF87a", b"GIF89a")
    with Image.open(path) as im:
        assert im.is_animated and im.n_frames >= min_frames


@pytest.fixture
def captured(monkeypatch):
    """What the command hands to optimize_plots.write (the grid, the poses)."""
    from mechcli.report import optimize_plots
    seen = {}
    original = optimize_plots.write

    def spy(*args, **kwargs):
        seen["args"], seen["kwargs"] = args, kwargs
        return original(*args, **kwargs)

    monkeypatch.setattr(optimize_plots, "write", spy)
    return seen


def _run(*args):
    proc = run_inprocess("optimize", *args, "--json")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_ex7_1_pictures_and_animation(tmp_path, captured):
    out = tmp_path / "out"
    doc = _run(EX7_1, "--out", out, "--animate")
    names = {f.split("/")[-1] for f in doc["files"]}
    assert {"convergence.png", "surface.png", "target.png", "optimize.gif"} <= names
    for name in ("convergence.png", "surface.png", "target.png"):
        _check_png(out / name)
    _check_gif(out / "optimize.gif", min_frames=60)    # a crank: the whole revolution

    # the surface the command computed: a box around start and optimum (the bounds
    # 1 ... 20 are far wider, as in the book's crankobjfun_VR), whose best feasible
    # cell lies next to the optimum and is not below f* (x* is the constrained minimum)
    spec, problem, result = captured["args"][:3]
    u, v, F, feas = captured["kwargs"]["surface"]
    assert F.shape == feas.shape == (v.size, u.size) == (41, 41)
    x = result.x
    assert x == pytest.approx([4.1289, 2.3224], abs=1e-3)
    assert u[0] < x[0] < u[-1] and v[0] < x[1] < v[-1]
    assert u[0] < 6 < u[-1] and v[0] < 2.5 < v[-1]          # the book's start x0
    # the box covers what the method visited (SLSQP's first step goes out to l3 = 13)
    for rec in result.history:
        assert u[0] <= rec.x[0] <= u[-1] and v[0] <= rec.x[1] <= v[-1]
    Ff = np.where(feas, F, np.inf)
    i, j = np.unravel_index(np.argmin(Ff), F.shape)
    du, dv = u[1] - u[0], v[1] - v[0]
    assert abs(u[j] - x[0]) <= 1.5 * du and abs(v[i] - x[1]) <= 1.5 * dv
    assert Ff[i, j] >= result.f * (1 - 1e-6)
    assert Ff[i, j] < 2 * result.f
    # infeasible cells exist (g7/g8 cut the box) and the free minimum lies among them
    assert (~feas).any() and np.nanmin(F) < result.f
    # the poses: the optimum moved over the revolution, with the function goal's data
    poses = captured["kwargs"]["poses"]
    assert poses["rotary"] and poses["motion"].feasible.all()
    assert poses["at"] is None


def test_no_plot_with_animate_writes_only_the_gif(tmp_path, captured):
    out = tmp_path / "out"
    doc = _run(write_spec(tmp_path, PATH), "--out", out, "--animate", "--no-plot")
    names = {f.split("/")[-1] for f in doc["files"]}
    assert "optimize.gif" in names
    assert not any(n.endswith(".png") for n in names)
    assert captured["kwargs"]["surface"] is None
    _check_gif(out / "optimize.gif", min_frames=60)    # a crank: the whole revolution


def test_no_surface_when_switched_off(tmp_path, captured):
    out = tmp_path / "out"
    doc = _run(EX7_1, "--out", out, "--set", "method.surface=false")
    names = {f.split("/")[-1] for f in doc["files"]}
    assert {"convergence.png", "target.png"} <= names and "surface.png" not in names
    assert captured["kwargs"]["surface"] is None


def test_path_problem_pictures(tmp_path, captured):
    spec = write_spec(tmp_path, PATH)
    out = tmp_path / "out"
    doc = _run(spec, "--out", out, "--animate")
    names = {f.split("/")[-1] for f in doc["files"]}
    assert {"convergence.png", "target.png", "optimize.gif"} <= names
    assert "surface.png" not in names                   # three variables
    _check_png(out / "convergence.png")
    _check_png(out / "target.png")
    _check_gif(out / "optimize.gif")
    # the coupler curve drawn in target.png passes through the eight targets
    poses = captured["kwargs"]["poses"]
    m = poses["motion"]
    assert m.feasible.all()
    curve = m.points["M"].p * 1e3                       # m -> mm
    spec_obj = captured["args"][0].objective
    targets = spec_obj["targets"][:, 0] * 1e3 + 1j * spec_obj["targets"][:, 1] * 1e3
    gap = np.abs(targets[:, None] - curve[None, :]).min(axis=1)
    assert gap.max() < 1.5      # the samples are 1 deg apart on a ~300 mm curve
    assert doc["results"]["distance_max"] < 0.5


def test_path_with_prescribed_angles_marks_the_timed_points(tmp_path, captured):
    text = PATH.replace('point = "M"\n', 'point = "M"\nangles = [0, 45, 90, 135, 180, 225, '
                        '270, 315]\ntheta0 = 5\n')
    text = text.replace("[objective]", '[[variable]]\nkey = "objective.theta0"\nlo = -20\n'
                        'hi = 20\n\n[objective]')
    spec = write_spec(tmp_path, text)
    out = tmp_path / "out"
    doc = _run(spec, "--out", out, "--lang", "zh")
    _check_png(out / "target.png")
    at = captured["kwargs"]["poses"]["at"]
    assert at is not None and at.feasible.all()
    # the timed points the picture joins to the targets are the targets themselves
    obj = captured["args"][0].objective
    got = at.points["M"].p * 1e3
    want = obj["targets"][:, 0] * 1e3 + 1j * obj["targets"][:, 1] * 1e3
    assert np.abs(got - want).max() < 1.0
    assert abs(doc["results"]["x"]["objective.theta0"]) < 1.0
