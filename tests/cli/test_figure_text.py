"""Clean figures (issue 31 §4): every config's figures, drawn as ``mechcli`` saves them, keep
all their text on the canvas and no two texts on top of each other (a title over a legend, C1
printed over C, tick labels running into each other, contour labels piled at one point).

The check uses matplotlib's own text extents (``Text.get_window_extent`` with the canvas's
renderer) of every text actually drawn, taken where :func:`mechcli.report.plotting.save_png`
would draw the figure (the test replaces it: the same layout, no PNG).  Overlap: two boxes
intersecting by more than :data:`TOL` pixels both ways."""

from __future__ import annotations

import itertools
import sys

import pytest

from mechcli.batch import _read_command
from mechcli.report import plotting
from tests.conftest import CONFIGS, run_inprocess

#: pixels two boxes may share (antialiasing, a descender touching the next line's ascender)
TOL = 2.0
#: the resolution the pictures are written at: at 60 dpi the 2-pixel tolerance hid a gear's
#: x label 6 px off the bottom of the 200-dpi picture, a title over a colour bar's tick label
DPI = plotting.DEFAULT_DPI
SPECS = sorted(CONFIGS.rglob("*.toml"))


def _drawn_texts(monkeypatch):
    """Patch Text.draw to record ``(text, bbox)`` of each visible, non-empty text drawn."""
    import matplotlib.text

    drawn = []
    original = matplotlib.text.Text.draw

    def draw(self, renderer, _original=original):
        _original(self, renderer)
        if self.get_visible() and self.get_text().strip() and renderer is not None:
            drawn.append((self.get_text(), self.get_window_extent(renderer)))

    monkeypatch.setattr(matplotlib.text.Text, "draw", draw)
    return drawn


def _problems(name, fig, texts):
    """Texts off the canvas and overlapping pairs of one drawn figure."""
    width, height = fig.canvas.get_width_height()
    out = []
    for text, box in texts:
        if box.x0 < -TOL or box.y0 < -TOL or box.x1 > width + TOL or box.y1 > height + TOL:
            out.append(f"{name}: {text!r} leaves the canvas ({box.x0:.0f}, {box.y0:.0f}, "
                       f"{box.x1:.0f}, {box.y1:.0f}) of {width}x{height}")
    for (ta, a), (tb, b) in itertools.combinations(texts, 2):
        dx = min(a.x1, b.x1) - max(a.x0, b.x0)
        dy = min(a.y1, b.y1) - max(a.y0, b.y0)
        if dx > TOL and dy > TOL:
            out.append(f"{name}: {ta!r} overlaps {tb!r}")
    return out


@pytest.mark.parametrize("lang", ["en", "zh"])
@pytest.mark.parametrize("spec", SPECS, ids=[str(p.relative_to(CONFIGS)) for p in SPECS])
def test_figure_text_stays_on_the_canvas_and_apart(tmp_path, monkeypatch, spec, lang):
    """Both languages: Chinese labels are taller (a gear's title sat on its legend's row
    in ``--lang zh`` only)."""
    if lang == "zh" and not plotting.has_cjk_font():
        # without a CJK font zh figures fall back to English: the en case already checks them
        if sys.version_info < (3, 10):
            pytest.skip("no CJK font on this machine, and the cjk extra needs Python >= 3.10")
        pytest.fail("no CJK font: pip install -e '.[test]' brings the cjk extra's")
    command, err = _read_command(spec)
    assert command is not None, err          # every config names the command that runs it
    drawn = _drawn_texts(monkeypatch)
    found, figures = [], []

    def save_png(fig, outputs, name, dpi=None, layout=True):
        # draw as save_png does (its own step: CJK fallback, layout at the resolution,
        # drawing), then look at what was drawn
        drawn.clear()
        plotting.draw(fig, DPI, layout)
        figures.append(name)
        found.extend(_problems(name, fig, list(drawn)))
        plotting.close(fig)
        return outputs.bytes(name, b"")     # no second drawing, no PNG encoding: time

    monkeypatch.setattr(plotting, "save_png", save_png)
    animate = [] if command == "grashof" else ["--no-animate"]
    result = run_inprocess(command, spec, "-q", "--lang", lang, *animate, "--out", tmp_path)
    assert result.returncode in (0, 3), result.stderr
    assert not found, "\n".join(found)
