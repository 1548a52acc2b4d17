"""Shared matplotlib set-up: Agg backend, CJK fonts for ``--lang zh``, atomic PNG/GIF.

Import this module only when a picture is written: it imports matplotlib.
"""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import font_manager  # noqa: E402

_CJK_FAMILIES = ("Noto Sans CJK SC", "Noto Sans CJK JP", "Noto Sans SC", "Source Han Sans SC",
                 "WenQuanYi Zen Hei", "WenQuanYi Micro Hei", "SimHei", "Microsoft YaHei",
                 "PingFang SC", "AR PL UMing CN", "Droid Sans Fallback")


def cjk_font():
    """Name of an installed font family with Chinese glyphs, or None."""
    names = {f.name for f in font_manager.fontManager.ttflist}
    for fam in _CJK_FAMILIES:
        if fam in names:
            return fam
    return None


_HAS_CJK = None


def has_cjk_font():
    global _HAS_CJK
    if _HAS_CJK is None:
        _HAS_CJK = cjk_font() is not None
    return _HAS_CJK


def text(s):
    """*s* as it can be drawn: without CJK characters when no CJK font is installed."""
    if has_cjk_font():
        return s
    import re

    kept = "".join(c for c in s if ord(c) < 0x2E80 or ord(c) > 0xFFEF)
    kept = re.sub(r"\(\s*\)", "", " ".join(kept.split()))
    return kept.strip()


def setup(lang="en"):
    """Configure matplotlib for *lang*; return the language actually usable.

    With ``zh`` and no CJK font installed, plots fall back to English labels
    (the caller reports that as a warning).
    """
    plt.rcParams.update({"figure.dpi": 100, "savefig.dpi": 100, "axes.grid": True,
                         "grid.alpha": 0.4, "axes.unicode_minus": False})
    fam = cjk_font()
    if fam is not None:
        plt.rcParams["font.sans-serif"] = ["DejaVu Sans", fam]
        plt.rcParams["font.family"] = "sans-serif"
    elif lang == "zh":
        return "en"
    return lang


def save_png(fig, outputs, name):
    """Render *fig* to PNG in memory, then write it atomically as *name* in ``--out``
    (:meth:`~mechcli.report.files.Outputs.bytes` checks the name)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", bbox_inches="tight")
    plt.close(fig)
    return outputs.bytes(name, buf.getvalue())


def save_gif(frames, outputs, name, fps=12):
    """Write a list of RGB(A) uint8 frames (H×W×3/4 arrays) as a looping GIF *name*
    in ``--out`` (through :meth:`~mechcli.report.files.Outputs.bytes`)."""
    from PIL import Image

    images = [Image.fromarray(f[..., :3]) for f in frames]
    buf = io.BytesIO()
    images[0].save(buf, format="GIF", save_all=True, append_images=images[1:],
                   duration=int(1000 / fps), loop=0, optimize=False)
    return outputs.bytes(name, buf.getvalue())


def canvas_frame(fig):
    """The current RGBA pixels of a figure drawn on the Agg canvas."""
    import numpy as np

    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba()).copy()
