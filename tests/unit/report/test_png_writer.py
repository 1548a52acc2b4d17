"""mechcli's PNG writer (``report.plotting.png_bytes``, issue 17 pictures) writes the
pixels exactly: the reference is the picture itself, read back by an independent
decoder (Pillow's), and the resolution Pillow reads from the ``pHYs`` chunk."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from mechcli.report import plotting


#: PNG stores whole pixels per metre: a resolution reads back within half of one,
#: 0.5 * 0.0254 dpi (as from Pillow's own writer)
DPI_TOL = 0.5 * 0.0254 + 1e-9


def _decode(data):
    with Image.open(io.BytesIO(data)) as im:
        im.load()
        return im.mode, np.asarray(im), im.info


def _canvas(h=61, w=47, seed=3):
    """An RGBA canvas: random pixels (every byte value, so the Up filter wraps modulo
    256 both ways), a white band and an opaque alpha, as the Agg canvas has."""
    rng = np.random.default_rng(seed)
    rgba = rng.integers(0, 256, size=(h, w, 4), dtype=np.uint8)
    rgba[10:20] = 255
    rgba[..., 3] = 255
    return rgba


@pytest.mark.parametrize("box", [(0, 61, 0, 47), (5, 54, 3, 45), (0, 1, 0, 1), (60, 61, 2, 47)])
def test_cropped_canvas_round_trips_exactly(box):
    rgba = _canvas()
    r0, r1, c0, c1 = box
    mode, px, info = _decode(plotting.png_bytes(plotting._rgb(rgba, box), 200))
    assert mode == "RGB"
    assert np.array_equal(px, rgba[r0:r1, c0:c1, :3])
    # 200 dpi = 7874 pixels per metre (rounded), which reads back as 199.9996 dpi
    assert info["dpi"] == pytest.approx((200, 200), abs=DPI_TOL)


def test_any_strides_and_no_resolution():
    rgba = _canvas()
    flipped = rgba[::-1, ::-1]          # negative strides: copied first
    mode, px, info = _decode(plotting.png_bytes(plotting._rgb(flipped, (2, 40, 1, 30))))
    assert np.array_equal(px, flipped[2:40, 1:30, :3])
    assert "dpi" not in info


def test_a_drawn_figure_is_saved_as_drawn(tmp_path):
    # save_png crops the canvas to its ink and writes it; decoding the file gives back
    # the canvas' own pixels inside the crop
    from mechcli.report.files import Outputs

    fig, ax = plotting.subplots(figsize=(3, 2))
    ax.plot([0, 1, 2], [0, 1, 0], "-o")
    ax.set_title(plotting.symbol("theta3"))
    fig.set_dpi(80)
    fig.canvas.draw()
    rgba = np.asarray(fig.canvas.buffer_rgba()).copy()
    box = plotting._ink_box(rgba, (255, 255, 255), int(round(plotting._MARGIN_IN * 80)))
    path = plotting.save_png(fig, Outputs(tmp_path), "fig.png", dpi=80, layout=False)
    mode, px, info = _decode(path.read_bytes())
    r0, r1, c0, c1 = box
    assert mode == "RGB" and np.array_equal(px, rgba[r0:r1, c0:c1, :3])
    assert info["dpi"] == pytest.approx((80, 80), abs=DPI_TOL)   # 3150 px/m: 80.01 dpi
