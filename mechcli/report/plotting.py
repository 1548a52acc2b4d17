"""Shared matplotlib set-up: Agg backend, CJK fonts, atomic PNG/GIF.

Import this module only when a picture is written: it imports matplotlib.

Chinese text.  matplotlib falls back from one font to the next glyph by glyph only
across the families listed in ``font.family`` (a generic family such as
``sans-serif`` resolves to ONE font), so :func:`setup` lists DejaVu Sans (Latin,
Greek, symbols) and then the installed CJK font.  Without a CJK font,
:func:`text` leaves the Chinese out of what it is given (a spec title
``例 1-1 铰链四杆机构 (four-bar linkage)`` becomes ``ex1-1: four-bar linkage``,
the spec's stem and the English part), and the run says so in ONE warning
(:func:`mechcli.report.run.notice`).  Any glyph still missing when a figure is
rendered becomes that same one-line warning, never one warning per glyph.
"""

from __future__ import annotations

import io
import re
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import font_manager  # noqa: E402

from mechcli.report import run as _run  # noqa: E402

#: families with Chinese glyphs, the most complete first
_CJK_FAMILIES = ("Noto Sans CJK SC", "Noto Sans CJK JP", "Noto Sans SC", "Source Han Sans SC",
                 "Source Han Sans CN", "WenQuanYi Zen Hei", "WenQuanYi Micro Hei", "SimHei",
                 "Microsoft YaHei", "PingFang SC", "Heiti SC", "AR PL UMing CN",
                 "AR PL UKai CN", "Noto Serif CJK SC", "Droid Sans Fallback")
#: the family drawn first: Latin, Greek and the symbols of the book's notation
_BASE_FAMILY = "DejaVu Sans"
#: matplotlib's warning for a character no listed font has
_GLYPH_MISSING = re.compile(r"Glyph (\d+) .*missing from (?:current )?font")

_found = (None, None)   # (number of fonts known to matplotlib, the CJK family or None)


def cjk_font():
    """Name of an installed font family with Chinese glyphs, or None.

    Looked up again whenever matplotlib learns a font (``fontManager.addfont``)."""
    global _found
    fonts = font_manager.fontManager.ttflist
    if _found[0] != len(fonts):
        names = {f.name for f in fonts}
        _found = (len(fonts), next((fam for fam in _CJK_FAMILIES if fam in names), None))
    return _found[1]


def has_cjk_font():
    return cjk_font() is not None


def _is_cjk(c):
    o = ord(c)
    return (0x2E80 <= o <= 0x9FFF or 0xAC00 <= o <= 0xD7AF or 0xF900 <= o <= 0xFAFF
            or 0xFE30 <= o <= 0xFE4F or 0xFF00 <= o <= 0xFFEF or 0x20000 <= o <= 0x3FFFF)


#: the book's label at the head of a title: 例 1-1, 习题 3-14, 【例 5-3】
_BOOK_LABEL = re.compile(r"^\s*[【\[]?\s*(?:例|习题)\s*\d+\s*[-‐–]\s*\d+\s*[】\]]?\s*")


def without_cjk(s):
    """*s* with its Chinese left out and the punctuation that framed it tidied:
    ``铰链四杆机构 (four-bar linkage)`` -> ``four-bar linkage`` (brackets that held
    only Chinese, or all that is left, go too)."""
    kept = "".join(" " if _is_cjk(c) else c for c in s)
    for _ in range(3):   # brackets emptied by the removal, then their separators
        kept = re.sub(r"\(\s*[,;:]*\s*\)|\[\s*\]", " ", kept)
        kept = re.sub(r"\(\s*([,;:]\s*)+", "(", kept)
        kept = re.sub(r"(\s*[,;:])+\s*\)", ")", kept)
    kept = " ".join(kept.split())
    kept = re.sub(r"\s+([,;:)])", r"\1", kept)
    kept = re.sub(r"\(\s+", "(", kept)
    kept = kept.strip(" ,;:")
    if kept.startswith("(") and kept.endswith(")") and kept.count("(") == 1:
        kept = kept[1:-1].strip()
    return kept


def title_without_cjk(s, stem):
    """A title whose Chinese cannot be drawn: the spec's *stem* (it names the book's
    example, ``ex1-1``) plus the English part, ``ex1-1: four-bar linkage``."""
    rest = without_cjk(_BOOK_LABEL.sub("", s))
    if not stem:
        return rest or without_cjk(s)
    return f"{stem}: {rest}" if rest else stem


def text(s):
    """*s* as it can be drawn: unchanged when a CJK font is installed or *s* has no
    Chinese; otherwise without its Chinese (:func:`title_without_cjk`, with the
    spec's stem when the Chinese stood outside quotes, as in a title), and the run
    warns once that no CJK font was found."""
    if not any(_is_cjk(c) for c in s) or has_cjk_font():
        return s
    _run.notice(f"{_run.NO_CJK}: Chinese in figure titles is left out")
    unquoted = re.sub(r"'[^']*'", "", s)
    if any(_is_cjk(c) for c in unquoted):
        return title_without_cjk(s, _run.current_stem())
    return re.sub(r"'([^']*)'", lambda m: repr(without_cjk(m.group(1)) or "?"), s)


def setup(lang="en"):
    """Configure matplotlib for *lang*; return the language actually usable.

    With ``zh`` and no CJK font installed, plots fall back to English labels
    (the caller reports that as a warning).
    """
    plt.rcParams.update({"figure.dpi": 100, "savefig.dpi": 100, "axes.grid": True,
                         "grid.alpha": 0.4, "axes.unicode_minus": False})
    fam = cjk_font()
    # an explicit list: matplotlib takes each glyph from the first family that has it
    plt.rcParams["font.family"] = [_BASE_FAMILY, fam] if fam else [_BASE_FAMILY]
    if fam is None and lang == "zh":
        return "en"
    return lang


def _rendered(draw):
    """Run *draw* (which renders a figure) and turn matplotlib's "Glyph … missing"
    warnings, one per character and figure, into one notice for the run."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = draw()
    missing = []
    for w in caught:
        m = _GLYPH_MISSING.match(str(w.message))
        if m:
            missing.append(chr(int(m.group(1))))
        else:   # anything else is not ours to hide
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    if missing:
        chars = "".join(sorted(set(missing)))
        if any(_is_cjk(c) for c in chars) and not has_cjk_font():
            _run.notice(f"{_run.NO_CJK}: Chinese in figure titles is left out")
        else:
            _run.notice(f"the installed fonts have no glyph for {chars[:20]!r}"
                        f"{' …' if len(chars) > 20 else ''}: drawn as empty boxes")
    return out


def save_png(fig, outputs, name):
    """Render *fig* to PNG in memory, then write it atomically as *name* in ``--out``
    (:meth:`~mechcli.report.files.Outputs.bytes` checks the name)."""
    buf = io.BytesIO()
    try:
        _rendered(lambda: fig.savefig(buf, format="png", bbox_inches="tight"))
    finally:
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

    _rendered(fig.canvas.draw)
    return np.asarray(fig.canvas.buffer_rgba()).copy()
