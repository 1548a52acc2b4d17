"""Shared matplotlib set-up: figures on the Agg canvas, CJK fonts, atomic PNG/GIF.

Import this module only when a picture is written: it imports matplotlib, but never
``matplotlib.pyplot`` (pyplot's figure manager and backend machinery cost start-up
time and keep global state): figures are :class:`matplotlib.figure.Figure` objects on
a :class:`~matplotlib.backends.backend_agg.FigureCanvasAgg`, made by :func:`subplots`
or :func:`figure` (``plt`` below offers the same two names for modules written
against pyplot).  A PNG is drawn once and cropped to its ink (:func:`save_png`); a
GIF draws its static background once and then only the artists that move
(:class:`Frames`), mapped onto one palette.

Resolution: :func:`dpi` is ``--dpi`` of the current command (default
:data:`DEFAULT_DPI`, 200), or what :func:`set_dpi` set for a library caller.

Chinese text.  matplotlib falls back from one font to the next glyph by glyph only
across the families listed in ``font.family`` (a generic family such as
``sans-serif`` resolves to ONE font), so :func:`setup` lists DejaVu Sans (Latin,
Greek, symbols) and then the CJK font: the ``cjk`` extra's (``pip install
'mechcli[cjk]'``: Noto Sans SC, SIL OFL 1.1, registered with matplotlib when the first
figure is set up, :func:`packaged_font`), else one the system has.  Without a CJK font,
:func:`text` leaves the Chinese out of what it is given (a spec title
``例 1-1 铰链四杆机构 (four-bar linkage)`` becomes ``ex1-1: four-bar linkage``,
the spec's stem and the English part), and the run says so in ONE warning
(:func:`mechcli.report.run.notice`).  Any glyph still missing when a figure is
rendered becomes that same one-line warning, never one warning per glyph.
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
import io
import re
import warnings
from pathlib import Path

import matplotlib
from matplotlib import font_manager
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from mechcli.report import run as _run
from mechcli.report.words import CJK

#: resolution of a PNG unless ``--dpi`` (or :func:`set_dpi`) says otherwise
DEFAULT_DPI = 200
#: resolution of GIF frames: a 6.4 in wide animation is 640 px, legible on a slide
GIF_DPI = 100
#: white margin kept round the ink of a cropped picture, in inches
_MARGIN_IN = 0.06

_dpi_override = None


def set_dpi(value):
    """Resolution of the PNGs written from now on in this process (None: ``--dpi``
    of the running command, else :data:`DEFAULT_DPI`)."""
    global _dpi_override
    _dpi_override = None if value is None else int(value)


def dpi():
    """Resolution of a PNG: :func:`set_dpi`'s value, else the running command's
    ``--dpi`` (its run options, :func:`mechcli.report.run.begin`), else
    :data:`DEFAULT_DPI`."""
    if _dpi_override is not None:
        return _dpi_override
    value = _run.current_dpi()
    return int(value) if value else DEFAULT_DPI


def figure(figsize=None, dpi=None, **kw):
    """A new :class:`~matplotlib.figure.Figure` on its own Agg canvas (no pyplot)."""
    fig = Figure(figsize=figsize, dpi=dpi or 100, **kw)
    FigureCanvasAgg(fig)
    return fig


def subplots(nrows=1, ncols=1, *, figsize=None, dpi=None, sharex=False, sharey=False,
             squeeze=True, gridspec_kw=None, subplot_kw=None, **kw):
    """``(fig, axes)`` like ``pyplot.subplots``, on a figure of :func:`figure`."""
    fig = figure(figsize=figsize, dpi=dpi, **kw)
    axes = fig.subplots(nrows, ncols, sharex=sharex, sharey=sharey, squeeze=squeeze,
                        gridspec_kw=gridspec_kw, subplot_kw=subplot_kw)
    return fig, axes


def close(fig=None):
    """Let a figure's pixels go: its Agg canvas is replaced by a bare one.  The
    renderer that owns the pixel buffer (~15 MB at 200 dpi) is still referenced by
    the drawn texts, so it is freed with the figure when the garbage collector takes
    it: a loop of runs in one process plateaus (measured: ≤ 5 renderers alive, 226 MiB
    at 200 dpi against 168 MiB with ``fig.clear()``), it does not grow.
    ``fig.clear()`` would rebuild every axis' ticks only to drop them (~40 ms of a
    2x2 figure)."""
    if fig is not None:
        from matplotlib.backend_bases import FigureCanvasBase

        FigureCanvasBase(fig)   # the figure's canvas now; the Agg one is freed


class _Figures:
    """The part of ``pyplot`` the report modules use, without importing pyplot:
    ``plt.subplots``, ``plt.figure``, ``plt.close``, ``plt.rcParams``."""

    subplots = staticmethod(subplots)
    figure = staticmethod(figure)
    close = staticmethod(close)

    @property
    def rcParams(self):   # noqa: N802 (pyplot's name)
        return matplotlib.rcParams


plt = _Figures()


#: families with Chinese glyphs, the most complete first
_CJK_FAMILIES = ("Noto Sans CJK SC", "Noto Sans CJK JP", "Noto Sans SC", "Source Han Sans SC",
                 "Source Han Sans CN", "WenQuanYi Zen Hei", "WenQuanYi Micro Hei", "SimHei",
                 "Microsoft YaHei", "PingFang SC", "Heiti SC", "AR PL UMing CN",
                 "AR PL UKai CN", "Noto Serif CJK SC", "Droid Sans Fallback")
#: the family drawn first: Latin, Greek and the symbols of the book's notation
_BASE_FAMILY = "DejaVu Sans"
#: matplotlib's warning for a character no listed font has
_GLYPH_MISSING = re.compile(r"Glyph (\d+) .*missing from (?:current )?font")

#: the package of the ``cjk`` extra (``pip install 'mechcli[cjk]'``), pylopdf-fonts-zh-cn:
#: Noto Sans SC, the Simplified Chinese subset of Noto Sans CJK (SIL Open Font License
#: 1.1), a static CFF font that every supported matplotlib draws (the variable Noto Sans
#: CJK needs FreeType >= 2.8, which the wheels of matplotlib < 3.11 do not bundle)
_PACKAGED_FONT = "pylopdf_fonts_zh_cn"

_found = (None, None)   # (number of fonts known to matplotlib, the CJK family or None)


@functools.cache
def packaged_font():
    """Path of the ``cjk`` extra's font file (its package's ``sans_path()``), or None
    when the extra is not installed (looked for once per process)."""
    if importlib.util.find_spec(_PACKAGED_FONT) is None:
        return None
    try:
        path = Path(importlib.import_module(_PACKAGED_FONT).sans_path())
    except (ImportError, AttributeError, TypeError):   # a release without that function
        return None
    return path if path.is_file() else None


def _registered(path):
    """The family of the font file *path*, registered with matplotlib if it is not yet;
    None if matplotlib cannot read it."""
    manager = font_manager.fontManager
    fname = str(path)
    entry = next((f for f in manager.ttflist if f.fname == fname), None)
    if entry is None:
        try:
            manager.addfont(fname)
        except (OSError, RuntimeError, ValueError):   # a damaged or unreadable file
            return None
        entry = next((f for f in manager.ttflist if f.fname == fname), None)
    return entry.name if entry is not None else None


def cjk_font():
    """Name of the font family that draws Chinese, or None: the ``cjk`` extra's
    (:func:`packaged_font`, registered with matplotlib on the first call), else the first
    of :data:`_CJK_FAMILIES` that matplotlib knows.

    Looked up again whenever matplotlib learns a font (``fontManager.addfont``)."""
    global _found
    fonts = font_manager.fontManager.ttflist
    if _found[0] != len(fonts):
        path = packaged_font()
        family = _registered(path) if path is not None else None
        if family is None:
            names = {f.name for f in fonts}
            family = next((fam for fam in _CJK_FAMILIES if fam in names), None)
        _found = (len(fonts), family)   # after the registration, which adds to *fonts*
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


def title(s):
    """The spec's title as a figure shows it: the book's label in the book's brackets, as
    in the reports (``例 1-1 …`` -> ``【例 1-1】 …``, :func:`~mechcli.report.table.book_title`),
    and drawable (:func:`text`: without its Chinese where no CJK font is installed)."""
    from mechcli.report.table import book_title
    return text(book_title(s))


def setup(lang="en"):
    """Configure matplotlib for *lang*; return the language actually usable.

    With ``zh`` and no CJK font installed, plots fall back to English labels and
    the run says so in its one warning about fonts (:func:`mechcli.report.run.notice`).
    """
    matplotlib.rcParams.update({"figure.dpi": 100, "savefig.dpi": dpi(), "axes.grid": True,
                                "grid.alpha": 0.4, "axes.unicode_minus": False,
                                "legend.framealpha": 0.85, "mathtext.default": "it"})
    fam = cjk_font()
    # an explicit list: matplotlib takes each glyph from the first family that has it
    matplotlib.rcParams["font.family"] = [_BASE_FAMILY, fam] if fam else [_BASE_FAMILY]
    if fam is None and lang in CJK:   # a language in Chinese characters needs a CJK font
        _run.notice(f"{_run.NO_CJK}: figure labels in English")   # once for the run
        return "en"
    return lang


_MATH = re.compile(r"(?<!\\)\$([^$]+)(?<!\\)\$")
_TEX = {r"\theta": "θ", r"\omega": "ω", r"\alpha": "α", r"\gamma": "γ", r"\varphi": "φ",
        r"\phi": "φ", r"\psi": "ψ", r"\delta": "δ", r"\varepsilon": "ε", r"\epsilon": "ε",
        r"\Delta": "Δ", r"\beta": "β", r"\mu": "μ", r"\rho": "ρ", r"\tau": "τ",
        r"\sigma": "σ", r"\lambda": "λ", r"\pi": "π", r"\cdot": "·"}
_SUB_ALL = str.maketrans("0123456789aehijklmnoprstuvx+-=()", "₀₁₂₃₄₅₆₇₈₉ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ₊₋₌₍₎")
_SUP_ALL = str.maketrans("0123456789+-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻")


def plain_math(s):
    """*s* with every mathtext ``$…$`` in plain Unicode: ``$\\theta_{1}$`` -> θ₁,
    ``$F_{\\mathrm{R16}}$`` -> FR₁₆.  For a text that also holds Chinese: mathtext draws
    a string with a ``$…$`` whole, from fonts without CJK glyphs (empty boxes)."""
    def one(m):
        t = re.sub(r"\\math(?:rm|it|bf|sf)\{([^{}]*)\}", r"\1", m.group(1))
        for tex, uni in _TEX.items():
            t = t.replace(tex, uni)
        t = re.sub(r"_\{([^{}]*)\}|_(\S)",
                   lambda g: (g.group(1) or g.group(2)).translate(_SUB_ALL), t)
        t = re.sub(r"\^\{([^{}]*)\}|\^(\S)",
                   lambda g: (g.group(1) or g.group(2)).translate(_SUP_ALL), t)
        return t.replace("{", "").replace("}", "").replace("\\", "")
    return _MATH.sub(one, s)


def _plain_math_beside_cjk(fig):
    """Every text of *fig* that mixes Chinese and mathtext, in plain Unicode
    (:func:`plain_math`), so that its Chinese is drawn from the CJK font."""
    if not has_cjk_font():
        return
    from matplotlib.text import Text

    for t in fig.findobj(Text):
        s = t.get_text()
        if "$" in s and any(_is_cjk(c) for c in s):
            t.set_text(plain_math(s))


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


def _ink_box(rgba, background, margin):
    """``(r0, r1, c0, c1)``: the rows and columns of the RGBA pixels *rgba* whose
    colour differs from *background* (RGB), grown by *margin* pixels (the whole
    picture if blank)."""
    import numpy as np

    px = np.ascontiguousarray(rgba).view(np.uint32)[..., 0]
    bg = np.array([[*background, 255]], dtype=np.uint8).view(np.uint32)[0, 0]
    ink = px != bg
    rows, cols = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    h, w = ink.shape
    if rows.size == 0:
        return 0, h, 0, w
    return (max(0, rows[0] - margin), min(h, rows[-1] + 1 + margin),
            max(0, cols[0] - margin), min(w, cols[-1] + 1 + margin))


def _background(fig):
    import numpy as np

    return tuple(int(v) for v in np.round(
        np.asarray(matplotlib.colors.to_rgb(fig.get_facecolor())) * 255))


def tight(fig, **kw):
    """``fig.tight_layout`` without its "not applied" UserWarning (a figure it
    cannot lay out keeps its layout)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        fig.tight_layout(**kw)


def draw(fig, res, layout=True):
    """Lay *fig* out and draw it on its canvas at *res* dpi, as :func:`save_png` does:
    mathtext beside Chinese in plain Unicode, then (with *layout*, unless the figure has
    a layout engine) the subplots fitted to the figure (:func:`tight`), then the drawing.

    The layout is made at the picture's resolution: the extents of its texts and their
    mathtext are then measured once and reused by the drawing (laid out at the figure's
    100 dpi and drawn at 200, every label was measured and parsed twice: a fifth of the
    time of a figure of forces)."""
    _plain_math_beside_cjk(fig)
    fig.set_dpi(res)
    if layout and fig.get_layout_engine() is None:
        tight(fig)
        if _moves_with_layout(fig):
            tight(fig)    # a second pass, from where the first left everything
    _rendered(fig.canvas.draw)


def _moves_with_layout(fig):
    """Whether one pass of :func:`tight` may not settle *fig*: an axes of fixed aspect
    shrinks into the room the layout gave it, which moves its labels (a gear's x label
    fell off the bottom edge), and a title that wraps is wrapped to the room round it
    where it stands, so it may take another line once the layout has moved it (a cam's
    two-line title ran off the top)."""
    texts = list(fig.texts)
    for ax in fig.axes:
        if ax.get_aspect() != "auto":
            return True
        texts += [ax.title, ax.xaxis.label, ax.yaxis.label]
    return any(t.get_wrap() and t.get_text() for t in texts)


def save_png(fig, outputs, name, dpi=None, layout=True):
    """Draw *fig* once at *dpi* (default :func:`dpi`), crop it to its ink (no empty
    margins: what ``bbox_inches="tight"`` does, without its second drawing), and
    write it atomically as *name* in ``--out``
    (:meth:`~mechcli.report.files.Outputs.bytes` checks the name).

    With *layout* (default) the subplots are first fitted to the figure
    (:func:`tight`), so nothing sticks out of it; ``layout=False`` keeps the
    figure's own layout (it has room for everything)."""
    import numpy as np

    res = int(dpi or globals()["dpi"]())
    try:
        draw(fig, res, layout)
        rgba = np.asarray(fig.canvas.buffer_rgba())
        box = _ink_box(rgba, _background(fig), int(round(_MARGIN_IN * res)))
        data = png_bytes(_rgb(rgba, box), res)
    finally:
        close(fig)
    return outputs.bytes(name, data)


def _rgb(rgba, box):
    """The RGB pixels of the canvas' RGBA array *rgba* inside *box* ``(r0, r1, c0, c1)``,
    C-contiguous: ``rgba[r0:r1, c0:c1, :3]`` copied as 3-byte items (one item per
    pixel; numpy copies a strided 3-channel slice byte by byte, twice as slowly)."""
    import numpy as np

    r0, r1, c0, c1 = (int(v) for v in box)
    px = np.dtype({"names": ["rgb"], "formats": ["V3"], "offsets": [0], "itemsize": 4})
    crop = np.asarray(rgba[r0:r1, c0:c1], dtype=np.uint8)
    if crop.strides[1:] != (4, 1):   # each pixel's 4 bytes together, as on the canvas
        crop = np.ascontiguousarray(crop)
    try:
        items = crop.view(px)
    except ValueError:   # numpy < 1.23 views only C-contiguous arrays as a wider dtype
        items = np.ascontiguousarray(crop).view(px)
    rgb = np.ascontiguousarray(items[..., 0]["rgb"])
    return rgb.view(np.uint8).reshape(r1 - r0, c1 - c0, 3)


def png_bytes(rgb, res=None, level=3):
    """A PNG file (8-bit RGB) of an H×W×3 ``uint8`` array.

    The pixels are written exactly; what differs from Pillow's writer is only the
    row filter: every row is "Up"-filtered (its difference to the row above, one numpy
    subtraction) instead of choosing per row among PNG's five filters, which cost
    ~60 ms of a 2000×1600 picture (now ~20 ms; the files are 3 % larger in the
    median, 18 % at most, over the configs' pictures).
    *res* [dpi] goes into a ``pHYs`` chunk, as Pillow's ``dpi=`` does."""
    import struct
    import zlib

    import numpy as np

    h, w, _ = rgb.shape
    rows = np.ascontiguousarray(rgb, dtype=np.uint8).reshape(h, 3 * w)
    raw = np.empty((h, 1 + 3 * w), dtype=np.uint8)
    raw[:, 0] = 2                              # filter type Up (the row above: 0 for row 0)
    raw[:1, 1:] = rows[:1]
    np.subtract(rows[1:], rows[:-1], out=raw[1:, 1:])   # modulo 256, as PNG wants

    def chunk(tag, payload):
        return (struct.pack(">I", len(payload)) + tag + payload
                + struct.pack(">I", zlib.crc32(tag + payload) & 0xFFFFFFFF))

    parts = [b"\x89PNG\r\n\x1a\n",
             chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))]
    if res:
        ppm = int(res / 0.0254 + 0.5)          # pixels per metre
        parts.append(chunk(b"pHYs", struct.pack(">IIB", ppm, ppm, 1)))
    parts += [chunk(b"IDAT", zlib.compress(raw, level)), chunk(b"IEND", b"")]
    return b"".join(parts)


def _palette(frames):
    """One 255-colour palette for every frame: from a mosaic of up to 12 frames, so
    the colours of the moving artists are in it."""
    import numpy as np
    from PIL import Image

    pick = frames[:: max(1, len(frames) // 12)][:12]
    mosaic = np.concatenate([f[::2, ::2, :3] for f in pick], axis=0)
    return Image.fromarray(np.ascontiguousarray(mosaic)).quantize(
        colors=255, method=Image.Quantize.FASTOCTREE)


def save_gif(frames, outputs, name, fps=12, crop=True):
    """Write a list of RGB(A) uint8 frames (H×W×3/4 arrays) as a looping GIF *name*
    in ``--out`` (through :meth:`~mechcli.report.files.Outputs.bytes`).

    Every frame is mapped onto one shared palette (no per-frame quantization) and,
    with *crop*, the frames are cut to the ink of all of them (no white margins)."""
    import numpy as np
    from PIL import Image

    if not frames:
        return None
    if crop:   # the ink of a dozen frames spread over the animation
        lo = np.full(frames[0].shape[:2] + (4,), 255, dtype=np.uint8)
        for f in frames[:: max(1, len(frames) // 12)] + frames[-1:]:
            np.minimum(lo[..., :3], f[..., :3], out=lo[..., :3])
        r0, r1, c0, c1 = _ink_box(lo, (255, 255, 255), 4)
        frames = [f[r0:r1, c0:c1, :3] for f in frames]
    pal = _palette(frames)
    images = [Image.fromarray(np.ascontiguousarray(f[..., :3])).quantize(
        palette=pal, dither=Image.Dither.NONE) for f in frames]
    buf = io.BytesIO()
    images[0].save(buf, format="GIF", save_all=True, append_images=images[1:],
                   duration=int(1000 / fps), loop=0, optimize=False)
    return outputs.bytes(name, buf.getvalue())


def canvas_frame(fig):
    """The current RGBA pixels of a figure drawn on the Agg canvas (a full drawing;
    :class:`Frames` draws only what moves)."""
    import numpy as np

    _rendered(fig.canvas.draw)
    return np.asarray(fig.canvas.buffer_rgba()).copy()


class Frames:
    """The frames of an animation of ONE figure, drawn by blitting.

    The figure is drawn once without the *moving* artists (they are marked
    animated); that picture is kept, and each :meth:`grab` restores it and draws
    only the moving artists over it.  :meth:`settle` draws artists that stay from
    then on (a trace, the white cut of a gear blank) into the kept picture.

    Parameters
    ----------
    fig : Figure
        A figure of :func:`subplots`, with everything that does not move drawn
        into it already; its ``dpi`` is the frames' resolution.
    moving : sequence of Artist
        What changes from frame to frame (lines updated with ``set_data``, texts
        with ``set_text``, patches, collections).
    """

    def __init__(self, fig, moving):
        self.fig = fig
        self.moving = sorted((a for a in moving if a is not None), key=lambda a: a.get_zorder())
        for a in self.moving:
            a.set_animated(True)
        _plain_math_beside_cjk(fig)
        _rendered(fig.canvas.draw)
        self.background = fig.canvas.copy_from_bbox(fig.bbox)
        self.frames = []

    def settle(self, artists):
        """Draw *artists* into the kept background (they stay in later frames)."""
        canvas = self.fig.canvas
        canvas.restore_region(self.background)
        for a in artists:
            self.fig.draw_artist(a)
        self.background = canvas.copy_from_bbox(self.fig.bbox)

    def grab(self):
        """Append the current frame: the kept background and the moving artists."""
        import numpy as np

        canvas = self.fig.canvas
        canvas.restore_region(self.background)
        for a in self.moving:
            if a.get_visible():
                self.fig.draw_artist(a)
        self.frames.append(np.asarray(canvas.buffer_rgba())[..., :3].copy())

    def save(self, outputs, name, fps=12):
        """Write the GIF (:func:`save_gif`) and release the figure."""
        close(self.fig)
        return save_gif(self.frames, outputs, name, fps=fps)


_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def plain_symbol(name):
    """A book symbol in plain Unicode, for texts redrawn every frame (mathtext would
    be parsed again each time): ``theta1`` -> ``θ₁``, ``s1`` -> ``s₁``."""
    for word, greek in (("theta", "θ"), ("omega", "ω"), ("alpha", "α"), ("phi", "φ"),
                        ("psi", "ψ"), ("delta", "δ"), ("gamma", "γ")):
        if name.startswith(word):
            return greek + name[len(word):].translate(_SUBSCRIPT)
    return name[:1] + name[1:].translate(_SUBSCRIPT)


def readout(ax, text="", **kw):
    """A text box in the upper-left corner of *ax* for a frame's input value
    (``θ1 = 120°``); animate it with :class:`Frames`."""
    style = dict(transform=ax.transAxes, fontsize=10, va="top", ha="left", zorder=10,
                 bbox=dict(boxstyle="round,pad=0.25", fc="white", ec="0.6", alpha=0.9))
    style.update(kw)
    return ax.text(0.02, 0.98, text, **style)


# -- notation ---------------------------------------------------------------------------

_GREEK = {"theta": r"\theta", "omega": r"\omega", "alpha": r"\alpha", "gamma": r"\gamma",
          "phi": r"\varphi", "psi": r"\psi", "delta": r"\delta", "epsilon": r"\varepsilon"}
_SYMBOL = re.compile(r"^(theta|omega|alpha|gamma|phi|psi|delta|epsilon|FR|MR|Fsh|Msh|Mb|Fb|"
                     r"Je|Me|v[xy](?=[A-Z])|a[xy](?=[A-Z])|[svaxy](?=[A-Z0-9]|$))([A-Za-z0-9]*)$")
#: symbols whose subscript is a word of the book (F_R16, M_b), set upright
_UPRIGHT = ("FR", "MR", "Fsh", "Msh", "Mb", "Fb", "Je", "Me")


def symbol(name):
    """A book symbol in mathtext: ``theta3`` -> θ₃, ``omega3`` -> ω₃, ``FR16`` ->
    F_R16, ``vxF`` -> v_Fx, ``sC`` -> s_C, ``Mb1`` -> M_b1; other names unchanged.

    Names with characters outside ASCII letters and digits are left as they are
    (mathtext has no CJK glyphs)."""
    m = _SYMBOL.match(name)
    if not m:
        return name
    head, sub = m.groups()
    if head in _GREEK:
        base = _GREEK[head]
    elif head in ("FR", "MR"):
        base, sub = head[0], "R" + sub
    elif head in ("Fsh", "Msh", "Mb", "Fb", "Je", "Me"):
        base, sub = head[0], head[1:] + sub
    elif len(head) == 2:     # vxF -> v_Fx
        base, sub = head[0], sub + head[1]
    else:
        base = head
    if not sub:
        return f"${base}$"
    if head in _UPRIGHT:
        return f"${base}_{{\\mathrm{{{sub}}}}}$"
    return f"${base}_{{{sub}}}$"


def axis_label(quantity, unit=""):
    """An axis label in the one style of every mechcli figure: the quantity (a name
    may come first), a spaced slash and the unit, a compound unit in parentheses:
    ``x / mm``, ``crank angle θ1 / °``, ``ω3 / (rad/s)``; a dimensionless quantity
    (unit ``""`` or ``"1"``) alone.  The tables keep the book's ``θ1/(°)``."""
    if unit in ("", "1"):
        return quantity
    if "/" in unit and not (unit.startswith("(") and unit.endswith(")")):
        unit = f"({unit})"
    return f"{quantity} / {unit}"


#: an axis label in that style (the unit after " / ", in parentheses when compound)
AXIS_LABEL = re.compile(r"^\S.*? / (\([^()]+\)|[^\s/()]+)(  \(—\)|  \(- -\))?$")


# -- legends, twin axes and clipping ------------------------------------------------------

def is_constant(values, rel=1e-9):
    """True when the finite *values* do not vary (a zero or constant curve)."""
    import numpy as np

    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return True
    scale = max(float(np.max(np.abs(v))), 1e-300)
    return float(np.ptp(v)) <= rel * scale or float(np.max(np.abs(v))) == 0.0


def legend_above(ax, handles=None, labels=None, fontsize=8, ncol=None):
    """A legend in one row above *ax* (outside it: it covers no curve)."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    if labels is None:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    n = ncol or min(len(handles), 4)
    return ax.legend(handles, labels, fontsize=fontsize, loc="lower left",
                     bbox_to_anchor=(0.0, 1.01, 1.0, 0.1), ncol=n, frameon=False,
                     borderaxespad=0.0, handlelength=2.2, columnspacing=1.2)


def legend_outside(ax, handles=None, labels=None, fontsize=8, **kw):
    """A legend to the right of *ax* (outside it: it covers no curve)."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    if labels is None:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    return ax.legend(handles, labels, fontsize=fontsize, loc="upper left",
                     bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, **kw)


def tie_axis(ax, color, side="left"):
    """Colour *ax*'s y label, ticks and spine on *side* like the one curve it carries."""
    ax.yaxis.label.set_color(color)
    ax.tick_params(axis="y", colors=color)
    ax.spines[side].set_color(color)
    ax.spines[side].set_linewidth(1.2)


def text_notice(message):
    """A one-line notice for the run (shown once, on stderr, with the spec path)."""
    _run.notice(message)


def clip_notice(ax, what, lo, hi, unit=""):
    """Say on *ax* (and once for the run) that *what* is drawn clipped to [lo, hi]."""
    u = f" {unit}" if unit else ""
    ax.text(0.99, 0.02, f"{what} clipped to ±{hi:.4g}{u}" if lo == -hi else
            f"{what} clipped to [{lo:.4g}, {hi:.4g}]{u}", transform=ax.transAxes,
            fontsize=7, ha="right", va="bottom", color="0.25",
            bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="0.7", alpha=0.9))
