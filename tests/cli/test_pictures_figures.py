"""Pictures (issues 17 and 18): figures without pyplot, ``--dpi``, cropped PNGs and
GIFs, the input readout in every animation, book symbols in mathtext, no axis for a
constant curve, equal aspect for paths, labelled mechanism drawings."""

from __future__ import annotations

import re
import subprocess
import sys
import types

import numpy as np
import pytest
from PIL import Image

from tests.conftest import CONFIGS, ROOT, run_inprocess

EX11 = CONFIGS / "ch1" / "ex1-1.toml"
EX12 = CONFIGS / "ch1" / "exercise1-2.toml"


def _modules_after(args):
    """``(exit code, sorted matplotlib modules)`` after ``mechcli ARGS`` in a fresh process."""
    code = ("import sys\nfrom mechcli.cli import main\ncode = 0\n"
            f"try:\n    main({[str(a) for a in args]!r})\n"
            "except SystemExit as e:\n    code = e.code\n"
            "print(code, 'matplotlib.pyplot' in sys.modules, 'matplotlib' in sys.modules)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT, timeout=300)
    return proc.stdout.split()


@pytest.mark.parametrize("extra", [[], ["--animate"]])
def test_a_picture_run_never_imports_pyplot(tmp_path, extra):
    code, pyplot, mpl = _modules_after(["kin", EX12, "-q", "--out", tmp_path, *extra])
    assert code == "0"
    assert mpl == "True"          # the pictures were drawn with matplotlib ...
    assert pyplot == "False"      # ... on Figure + Agg canvas, pyplot never imported
    assert (tmp_path / "kin.png").exists() and (tmp_path / "path_F.png").exists()
    if extra:
        assert (tmp_path / "kin.gif").exists()


def _ink_margins(img):
    """Distance in pixels from each edge (top, bottom, left, right) to the first
    non-white pixel."""
    a = np.asarray(img.convert("RGB"))
    ink = np.any(a < 250, axis=2)
    rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    return rows[0], a.shape[0] - 1 - rows[-1], cols[0], a.shape[1] - 1 - cols[-1]


def test_dpi_default_200_and_option(tmp_path):
    assert run_inprocess("kin", EX11, "-q", "--out", tmp_path / "d").returncode == 0
    assert run_inprocess("kin", EX11, "-q", "--dpi", "100", "--out",
                         tmp_path / "h").returncode == 0
    with Image.open(tmp_path / "d" / "kin.png") as big, \
            Image.open(tmp_path / "h" / "kin.png") as small:
        assert round(big.info["dpi"][0]) == 200
        assert round(small.info["dpi"][0]) == 100
        # same figure, twice the resolution (cropping moves the edges by a few pixels)
        assert big.width / small.width == pytest.approx(2.0, rel=0.03)
        assert big.height / small.height == pytest.approx(2.0, rel=0.03)
        # no empty space: the ink reaches within the crop margin (0.06 in) of every edge
        for m in _ink_margins(big):
            assert m <= 0.06 * 200 + 2
    bad = run_inprocess("kin", EX11, "-q", "--dpi", "0", "--out", tmp_path / "x")
    assert bad.returncode == 2


def test_dpi_is_not_part_of_a_quick_form_folder_name(tmp_path):
    from mechcli.options import default_dir_name

    proc = run_inprocess("grashof", "--lengths", "40,90,70,100", "--dpi", "120", "--json",
                         "--no-plot")
    assert proc.returncode == 0, proc.stderr
    assert "dpi" not in proc.stdout.split("out/")[-1].split('"')[0] if "out/" in proc.stdout \
        else True
    assert default_dir_name("grashof", (), [("lengths", "40,90,70,100")]) == \
        "grashof-40_90_70_100"


# -- animations: one readout of the input in every frame, cropped frames --------------------

ANIMATIONS = [
    ("kin", CONFIGS / "ch1" / "exercise1-2.toml", "kin.gif", r"^θ₁ = -?\d+°$"),
    ("kin", CONFIGS / "ch1" / "ex1-3.toml", "kin.gif", r"^θ₁ = -?\d+°$"),
    ("force", CONFIGS / "ch2" / "ex2-4.toml", "force.gif", r"^θ₁ = -?\d+°$"),
    ("synth", CONFIGS / "ch3" / "ex3-5.toml", "synth.gif", r"^θ[₀-₉]+ = -?\d+°$"),
    ("cam", CONFIGS / "ch4" / "ex4-1.toml", "cam.gif", r"^δ = \d+°$"),
    ("gear", CONFIGS / "ch5" / "ex5-4.toml", "pair.gif", r"^φ₁ = -?[\d.]+°$"),
    ("flywheel", CONFIGS / "ch6" / "linkage-motor.toml", "flywheel.gif", r"^φ = -?\d+°"),
    ("optimize", CONFIGS / "ch7" / "ex7-1.toml", "optimize.gif", r"^θ[₀-₉]+ = -?\d+°$"),
]


@pytest.mark.parametrize("command, spec, gif, pattern", ANIMATIONS,
                         ids=[f"{c}-{s.stem}" for c, s, _, _ in ANIMATIONS])
def test_every_animation_shows_the_input_in_every_frame(tmp_path, monkeypatch, command, spec,
                                                        gif, pattern):
    from matplotlib.text import Text

    from mechcli.report import plotting

    texts = []
    grab = plotting.Frames.grab

    def spy(self):
        texts.append([a.get_text() for a in self.moving
                      if isinstance(a, Text) and re.search(pattern, a.get_text())])
        return grab(self)

    monkeypatch.setattr(plotting.Frames, "grab", spy)
    proc = run_inprocess(command, spec, "-q", "--animate", "--no-plot", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    with Image.open(tmp_path / gif) as im:
        n = im.n_frames
        assert max(im.size) >= 450          # legible: not a thumbnail
        for m in _ink_margins(im):
            assert m <= 6                    # cropped to the drawing
    assert len(texts) == n
    assert all(len(t) == 1 for t in texts), texts[:3]   # a readout in every frame
    assert len({t[0] for t in texts}) > n // 2          # ... that follows the input


# -- notation, twin axes, aspect, drawings ---------------------------------------------------

@pytest.mark.parametrize("name, math", [
    ("theta3", r"$\theta_{3}$"), ("omega3", r"$\omega_{3}$"), ("alpha2", r"$\alpha_{2}$"),
    ("FR16", r"$F_{\mathrm{R16}}$"), ("vxF", r"$v_{Fx}$"), ("sC", r"$s_{C}$"),
    ("Mb1", r"$M_{\mathrm{b1}}$"), ("slide", "slide"), ("点F", "点F"),
])
def test_book_symbols_are_mathtext(name, math):
    from matplotlib.mathtext import MathTextParser

    from mechcli.report import plotting

    assert plotting.symbol(name) == math
    if math.startswith("$"):
        MathTextParser("agg").parse(math, dpi=100)   # matplotlib can typeset it


def test_a_constant_curve_gets_no_axis_of_its_own():
    from mechcli.report import kin_plots, plotting

    x = np.linspace(0, 360, 37)
    spec = types.SimpleNamespace(header=types.SimpleNamespace(unit="mm", scale=1e-3))
    result = types.SimpleNamespace(runs=[(0, 37)], values={
        "theta3": np.radians(60 + 20 * np.sin(np.radians(x))), "sC": np.zeros(37)})
    qs = [types.SimpleNamespace(symbol="theta3", kind="angle"),
          types.SimpleNamespace(symbol="sC", kind="length")]
    fig, ax = plotting.subplots()
    kin_plots._plot_group(ax, spec, result, qs, x, kin_plots._TITLES["en"])
    assert len(fig.axes) == 1                       # no twin axis for sC = 0
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[0] == r"$\theta_{3}$"
    assert labels[1].startswith(r"$s_{C}$ ≡ 0")     # named with its value instead
    # both varying: a twin axis, tied to its one curve by colour
    result.values["sC"] = 1e-3 * (100 + x)
    fig, ax = plotting.subplots()
    kin_plots._plot_group(ax, spec, result, qs, x, kin_plots._TITLES["en"])
    assert len(fig.axes) == 2
    twin = fig.axes[1]
    assert twin.yaxis.label.get_color() == twin.lines[0].get_color()


def test_paths_have_equal_aspect_and_drawings_name_every_joint_and_link(tmp_path,
                                                                         monkeypatch):
    from matplotlib.patches import Polygon

    from mechcli.report import kin_plots, plotting

    seen = {}
    save = plotting.save_png

    def spy(fig, outputs, name, *a, **kw):
        seen[name] = [(ax.get_aspect(), ax) for ax in fig.axes]
        seen[name + ":patches"] = [p for ax in fig.axes for p in ax.patches
                                   if isinstance(p, Polygon)]
        seen[name + ":markers"] = [ln.get_marker() for ax in fig.axes for ln in ax.lines]
        return save(fig, outputs, name, *a, **kw)

    monkeypatch.setattr(plotting, "save_png", spy)
    monkeypatch.setattr(kin_plots.plotting, "save_png", spy)
    assert run_inprocess("kin", EX12, "-q", "--out", tmp_path).returncode == 0
    assert seen["path_F.png"][0][0] == 1.0
    assert seen["kin.png"][3][0] == 1.0                      # the mechanism panel
    markers = {id(m) for m in seen["kin.png:markers"]}
    for name in ("A", "B", "C", "D", "F"):                 # every joint named
        assert id(kin_plots._glyph(name)["marker"]) in markers, name
    for link in ("1", "2", "3", "4"):                      # every link numbered
        assert id(kin_plots._glyph(link)["marker"]) in markers, link
    # the coupler carries F: drawn as the rigid triangle BCF
    tri = [p for p in seen["kin.png:patches"] if len(p.get_xy()) in (3, 4)]
    assert tri, "coupler not drawn as a body"


@pytest.mark.parametrize("text", ["A", "C", "12", "g"])
def test_name_glyphs_draw_the_pixels_of_the_mathtext_marker(text):
    """kin_plots._glyph draws a name as a text path (no mathtext parser) exactly as the
    mathtext marker ``$\\mathrm{A}$`` drew it before: same glyph, same size (a wrong
    size or another font changes hundreds of pixels)."""
    from mechcli.report import kin_plots, plotting

    def pixels(**marker):
        fig, ax = plotting.subplots(figsize=(1, 1), dpi=200)
        ax.set_axis_off()
        ax.plot([0.5], [0.5], ls="none", color="k", mew=0, **marker)
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1)
        fig.canvas.draw()
        return np.asarray(fig.canvas.buffer_rgba()).copy()

    new = kin_plots._glyph(text)
    old = pixels(marker=f"$\\mathrm{{{text}}}$", ms=kin_plots._glyph_size(text))
    assert (old[..., 0] < 128).sum() > 20                  # something was drawn
    # single glyphs: the same pixels; two (a link 12): antialiasing may round a few
    # pixels of their edges one level apart (measured: <= 20 pixels, 1/255)
    diff = np.abs(pixels(**new).astype(int) - old)
    assert diff.max() <= 1 and (diff > 0).sum() <= 40
    assert diff.max() == 0 or len(text) > 1
