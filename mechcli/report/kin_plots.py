"""PNG diagrams and GIF animation for ``mechcli kin`` (imports matplotlib)."""

from __future__ import annotations

import math

import numpy as np

from mechcli.core.linkage import Bar, Block, Guide, Pivot, solve
from mechcli.report import plotting, words
from mechcli.report.kin import factor_of, input_factor, pretty_unit

_TITLES = {lang: words.table(lang, "kin_plots") for lang in words.LANGUAGES}


def _groups(quantities):
    groups = {0: [], 1: [], 2: []}
    for q in quantities:
        if q.symbol.startswith("gamma"):
            continue
        groups[q.order].append(q)
    return groups


def broken(result, v):
    """Values with a NaN between runs, so a curve is not drawn across a gap.
    (NaN only goes to matplotlib, never to an output file.)"""
    if len(result.runs) <= 1:
        return v
    parts = []
    for i0, i1 in result.runs:
        parts += [v[i0:i1], [np.nan]]
    return np.concatenate(parts[:-1])


def input_label(spec, t):
    """The x label of a diagram against the input: ``crank angle θ1 / °`` or ``s1 / mm``."""
    n = spec.input.driver
    if spec.input.rotary:
        return plotting.text(t["input"].format(sym=plotting.symbol(f"theta{n}")))
    return f"{plotting.symbol(f's{n}')} / {spec.header.unit}"


def _plot_group(ax, spec, result, qs, x, t):
    """Angular quantities on the left axis, linear ones on a twin axis (plotyy).

    A curve that does not vary (zero or constant) gets no axis of its own: it is
    named with its value in the legend.  Each axis is tied to its curves: the left
    one's curves are solid, the twin's dashed, and an axis with one curve takes its
    colour.  The legend sits above the panel, outside the curves."""
    from matplotlib.lines import Line2D

    unit, scale = spec.header.unit, spec.header.scale
    handles, constant = [], []
    drawn = []
    for q in qs:
        f = factor_of(q.kind, scale)
        v = result.values[q.symbol] * f
        ext = (getattr(result, "extremes", None) or {}).get(q.symbol)
        if ext is not None and ext[0].constant:   # constant to round-off (the engine says)
            constant.append(Line2D([], [], ls="none", label=t["const"].format(
                sym=plotting.symbol(q.symbol), v=ext[0].value * f + 0.0,
                u=pretty_unit(q.kind, unit))))
        elif plotting.is_constant(v):
            finite = v[np.isfinite(v)]
            val = float(finite[0]) if finite.size else 0.0
            constant.append(Line2D([], [], ls="none", label=t["const"].format(
                sym=plotting.symbol(q.symbol), v=val + 0.0, u=pretty_unit(q.kind, unit))))
        else:
            drawn.append((q, v))
    left = [(q, v) for q, v in drawn if q.kind in ("angle", "angvel", "angacc")]
    right = [(q, v) for q, v in drawn if (q, v) not in left]
    axes = []
    if left:
        axes.append((ax, left, "-", "left"))
    if right:
        tw = ax.twinx() if left else ax
        if tw is not ax:
            tw.grid(False)
        axes.append((tw, right, "--" if left else "-", "right" if left else "left"))
    color = 0
    for a, group, style, side in axes:
        colors = []
        for q, v in group:
            c = f"C{color % 10}"
            color += 1
            colors.append(c)
            h, = a.plot(broken(result, x), broken(result, v), style, color=c, lw=1.4,
                        label=plotting.symbol(q.symbol))
            handles.append(h)
        mark = "" if len(axes) == 1 else ("  (—)" if style == "-" else "  (- -)")
        a.set_ylabel(plotting.axis_label(
            ", ".join(plotting.symbol(q.symbol) for q, _ in group),
            pretty_unit(group[0][0].kind, unit)) + mark)
        if len(axes) > 1 and len(group) == 1:
            plotting.tie_axis(a, colors[0], side)
    if not axes:
        ax.set_yticks([])
    plotting.legend_above(ax, handles + constant, ncol=min(len(handles + constant), 4))


def _element_links(el, frame):
    """``[(Bar, link number)]`` of an element's bars (the link a bar is part of)."""
    out = []
    for p in el.sketch(frame):
        if not isinstance(p, Bar):
            continue
        if hasattr(el, "link_a") and p.a == getattr(el, "point_a", None):
            out.append((p, el.link_a))
        elif hasattr(el, "link_b") and p.a == getattr(el, "point_b", None):
            out.append((p, el.link_b))
        else:
            out.append((p, getattr(el, "link", None)))
    return out


def _link_segments(linkage):
    """The elements' drawing primitives, sorted: bars, blocks, guides, ground points."""
    prims = [p for el in linkage.elements for p in el.sketch(linkage.frame)]
    bars = [(p.a, p.b) for p in prims if isinstance(p, Bar)]
    blocks = [p for p in prims if isinstance(p, Block)]
    guides = [p for p in prims if isinstance(p, Guide)]
    grounds = [p.name for p in prims if isinstance(p, Pivot)]
    return bars, blocks, guides, grounds


def _bodies(linkage):
    """``{link: [points]}`` of every moving link drawn by bars, in the order met."""
    bodies = {}
    for el in linkage.elements:
        for bar, link in _element_links(el, linkage.frame):
            if link is None or link == linkage.frame:
                continue
            pts = bodies.setdefault(link, [])
            for n in (bar.a, bar.b):
                if n not in pts:
                    pts.append(n)
    return bodies


_GLYPHS = {}


def _glyph(text, base=7):
    """``{marker, ms}`` drawing *text* as a marker: the outline of its glyphs in the
    figure's font, centred on their box, made once per text and drawn as one path in
    every frame, about the height of an 8-pt label (:func:`_glyph_size`).

    A plain text path, not a mathtext marker (``$\\mathrm{A}$`` gives the same DejaVu
    Sans glyphs -- the same pixels for names of 1-3 characters, within a few levels on
    the antialiased edges of longer ones -- but its parser's grammar costs ~30 ms when
    first used and ~2 ms a name after).  matplotlib scales a path marker by its farthest
    vertex, a mathtext one by its box: the curves' control points lie outside the box, so
    the size is corrected to draw the glyphs as large as before."""
    import matplotlib

    if not text.strip():   # (names are never blank; no glyphs to draw)
        return {"marker": "None", "ms": 0}
    # the glyphs of the fonts set now (plotting.setup lists DejaVu Sans, then a CJK font)
    key = (text, tuple(matplotlib.rcParams["font.family"]),
           tuple(matplotlib.rcParams["font.sans-serif"]))
    got = _GLYPHS.get(key)
    if got is None:
        from matplotlib.path import Path
        from matplotlib.textpath import TextPath

        glyphs = TextPath((0, 0), text)
        box = glyphs.get_extents()
        v = glyphs.vertices - ((box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2)
        reach = float(abs(v).max()) if len(v) else 0.0
        span = max(box.width, box.height)
        got = _GLYPHS[key] = (Path(v, glyphs.codes), 2 * reach / span if span else 1.0)
    path, grow = got
    return {"marker": path, "ms": _glyph_size(text, base) * grow}


def _glyph_size(text, base=7):
    """Marker size that gives the glyphs of *text* about the height of an 8-pt label."""
    return base * max(1, len(text)) ** 0.9 + 1


class Drawing:
    """Artists for one mechanism drawing, updated frame by frame (any linkage: kin's,
    force's, a synthesized design, a flywheel's machine); ``guide_length`` draws a
    guide bar that long instead of just past its blocks.

    Every joint is named beside it and every link carries its number (the frame's
    by its first pivot); a link with three or more points (the coupler BCF of a
    four-bar with a coupler point) is drawn as the rigid body it is, a filled
    polygon.  ``labels=False`` leaves the names out (several poses on one axes)."""

    def __init__(self, ax, linkage, motion, scale, guide_length=None, labels=True):
        from matplotlib.patches import Polygon

        self.ax, self.k = ax, 1 / scale
        self.bars, self.blocks, self.guides, self.grounds = _link_segments(linkage)
        self.bar_lines = [ax.plot([], [], "-", color="C0", lw=2, solid_capstyle="round")[0]
                          for _ in self.bars]
        self.guide_lines = [ax.plot([], [], "-", color="0.4", lw=1)[0] for _ in self.guides]
        self.block_lines = [ax.plot([], [], "-", color="C1", lw=1.5)[0] for _ in self.blocks]
        self.bodies = {ln: pts for ln, pts in _bodies(linkage).items() if len(pts) >= 3}
        self.body_patches = {ln: ax.add_patch(Polygon(np.zeros((3, 2)), closed=True,
                                                      fc="C0", alpha=0.18, ec="C0", lw=1.0))
                             for ln in self.bodies}
        self.joints = ax.plot([], [], "o", color="k", ms=4, mfc="w", zorder=4)[0]
        gx = [motion.points[g].p[0].real * self.k for g in self.grounds]
        gy = [motion.points[g].p[0].imag * self.k for g in self.grounds]
        ax.plot(gx, gy, "^", color="k", ms=9, mfc="0.8", zorder=3)
        self.size = 0.06 * extent(motion) * self.k
        self.names, self.link_names, self.link_rings = {}, {}, {}
        self.offset = 0.45 * self.size * (1 + 0.8j)
        if labels:
            # names as marker glyphs: a path made once, drawn fast in every frame
            self.names = {n: ax.plot([], [], ls="none", **_glyph(n), color="k", mew=0,
                                     zorder=6)[0] for n in motion.points}
            links = sorted({ln for el in linkage.elements
                            for _, ln in _element_links(el, linkage.frame)
                            if ln is not None and ln != linkage.frame}
                           | {b.link for b in self.blocks if b.link is not None}
                           | {g.link for g in self.guides if g.link != linkage.frame})
            for ln in links:
                self.link_rings[ln] = ax.plot([], [], ls="none", marker="o", ms=11, mfc="w",
                                              mec="0.45", mew=0.7, zorder=6)[0]
                self.link_names[ln] = ax.plot([], [], ls="none", **_glyph(str(ln), 6),
                                              color="0.15", mew=0, zorder=7)[0]
            if self.grounds:
                z = complex(gx[0], gy[0]) - 1.4 * self.size * (0.6 + 1j)
                ax.plot([z.real], [z.imag], ls="none", marker="o", ms=11, mfc="w", mec="0.45",
                        mew=0.7, zorder=6)
                ax.plot([z.real], [z.imag], ls="none", **_glyph(str(linkage.frame), 6),
                        color="0.15", mew=0, zorder=7)
        self._bar_link = [ln for el in linkage.elements
                          for _, ln in _element_links(el, linkage.frame)]
        # guide length for drawing: longest reach of the blocks on it, plus a margin
        self.reach = {}
        for i, g in enumerate(self.guides):
            if g.ray:
                s = np.abs(motion.slides[g.slide].s)
                self.reach[i] = guide_length or 1.15 * float(np.max(s))

    @property
    def artists(self):
        """Every artist that moves with the mechanism (for blitting)."""
        return (self.bar_lines + self.guide_lines + self.block_lines
                + list(self.body_patches.values()) + [self.joints]
                + list(self.names.values()) + list(self.link_rings.values())
                + list(self.link_names.values()))

    def update(self, motion, i):
        P = {n: pm.p[i] * self.k for n, pm in motion.points.items()}
        for line, (a, b) in zip(self.bar_lines, self.bars):
            line.set_data([P[a].real, P[b].real], [P[a].imag, P[b].imag])
        mids = {}
        for (a, b), ln in zip(self.bars, self._bar_link):
            if ln is not None:
                mids.setdefault(ln, []).append(0.5 * (P[a] + P[b]))
        for ln, pts in self.bodies.items():
            z = np.array([P[n] for n in pts])
            c = z.mean()
            z = z[np.argsort(np.angle(z - c))]
            self.body_patches[ln].set_xy(np.column_stack([z.real, z.imag]))
            mids[ln] = [c]
        for j, (line, g) in enumerate(zip(self.guide_lines, self.guides)):
            th = motion.links[g.link].theta[i] + g.angle
            u = complex(math.cos(th), math.sin(th))
            c = P[g.point] + g.offset * self.k * 1j * u
            if g.ray:
                ends = [c, c + self.reach[j] * self.k * u * g.branch]
            else:
                s = motion.slides[g.slide].s if g.slide in motion.slides else None
                span = self.size * 8
                if s is not None:
                    lo, hi = float(np.min(s)) * self.k - span, float(np.max(s)) * self.k + span
                else:
                    lo, hi = -span, span
                ends = [c + lo * u, c + hi * u]
            line.set_data([e.real for e in ends], [e.imag for e in ends])
            if g.link not in mids:
                mids[g.link] = [ends[0] + 0.75 * (ends[1] - ends[0])]
        for line, b in zip(self.block_lines, self.blocks):
            th = 0.0 if b.link is None else motion.links[b.link].theta[i]
            u = complex(math.cos(th), math.sin(th)) * self.size
            corners = [P[b.point] + z * u for z in (-1.4 - 0.7j, 1.4 - 0.7j, 1.4 + 0.7j,
                                                    -1.4 + 0.7j, -1.4 - 0.7j)]
            line.set_data([c.real for c in corners], [c.imag for c in corners])
            if b.link is not None:
                mids[b.link] = [P[b.point] + u * (0.0 + 1.5j)]
        pts = [P[n] for n in P]
        self.joints.set_data([p.real for p in pts], [p.imag for p in pts])
        for n, mark in self.names.items():
            z = P[n] + self.offset
            mark.set_data([z.real], [z.imag])
        for ln, mark in self.link_names.items():
            if ln in mids:
                z = mids[ln][0]
                mark.set_data([z.real], [z.imag])
                self.link_rings[ln].set_data([z.real], [z.imag])


def extent(motion):
    pts = np.concatenate([pm.p for pm in motion.points.values()])
    return max(float(np.ptp(pts.real)), float(np.ptp(pts.imag)), 1e-300)


def limits(ax, motion, k, pad=0.12):
    pts = np.concatenate([pm.p for pm in motion.points.values()]) * k
    x0, x1, y0, y1 = pts.real.min(), pts.real.max(), pts.imag.min(), pts.imag.max()
    d = pad * max(x1 - x0, y1 - y0, 1e-300)
    ax.set_xlim(x0 - d, x1 + d)
    ax.set_ylim(y0 - d, y1 + d)
    ax.set_aspect("equal", adjustable="box")


def write(spec, quantities, result, sweep, outputs, lang, plots=True, animate=False):
    """Write ``kin.png`` (the book's 2x2 figure), coupler-curve PNGs and ``kin.gif``.

    Returns a list of warnings (e.g. no CJK font for ``--lang zh``).
    """
    warnings = []
    used = plotting.setup(lang)
    if used != lang:
        warnings.append("no CJK font installed: plot labels are in English")
    t = _TITLES[used]
    unit, scale = spec.header.unit, spec.header.scale
    x = result.q * input_factor(spec)
    k = 1 / scale
    n_in = spec.input.driver
    if plots:
        groups = _groups(quantities)
        fig, axs = plotting.subplots(2, 2, figsize=(11, 8.5))
        for ax, order, title in zip(axs.flat[:3], (0, 1, 2), (t["disp"], t["vel"], t["acc"])):
            # y=1.0: the title stays where matplotlib's automatic placement puts it
            # (22 pt above the axes clears the y offset text), without the tick-label
            # layout of every twin axis that the automatic placement costs at each draw
            ax.set_title(title, pad=22, y=1.0)
            ax.set_xlabel(input_label(spec, t))
            if groups[order]:
                _plot_group(ax, spec, result, groups[order], x, t)
                legend = ax.get_legend()
                rows = -(-len(legend.texts) // 4) if legend is not None else 1
                if rows > 1:   # the title above every row of the legend
                    ax.set_title(title, pad=22 + 11 * (rows - 1), y=1.0)
                ax.set_xlim(float(np.nanmin(x)), float(np.nanmax(x)))
            else:
                ax.set_visible(False)
        ax = axs[1, 1]
        at = spec.output.draw_at
        m1 = solve(spec.linkage, sweep.inputs(np.array([at])), order=0)
        if bool(m1.regular[0]):
            d = Drawing(ax, spec.linkage, result.motion, scale, spec.guide_length)
            d.update(m1, 0)
        else:
            warnings.append(f"mechanism not drawn: it cannot be assembled at draw_at = "
                            f"{at * input_factor(spec):g}")
        for j, tr in enumerate(spec.tracers):
            p = broken(result, result.motion.points[tr.name].p * k)
            ax.plot(p.real, p.imag, ":", lw=1.2, color=f"C{(3 + j) % 10}",
                    label=t["path"].format(name=tr.name))
        limits(ax, result.motion, k)
        if spec.tracers:
            ax.legend(fontsize=7, loc="best")
        sym = plotting.symbol(f"theta{n_in}")
        ax.set_title(f"{t['mech']} {sym} = {at * input_factor(spec):g}°" if spec.input.rotary
                     else t["mech"], pad=22, y=1.0)
        ax.set_xlabel(f"x / {unit}")
        ax.set_ylabel(f"y / {unit}")
        fig.suptitle(plotting.title(spec.header.title), wrap=True)
        # a fixed layout with room for twin axes' labels (tight_layout would lay out
        # every text once more before the drawing); save_png crops the margins
        fig.subplots_adjust(left=0.08, right=0.92, bottom=0.07, top=0.885, wspace=0.5,
                            hspace=0.45)
        plotting.save_png(fig, outputs, "kin.png", layout=False)
        for tr in spec.tracers:
            fig, ax = plotting.subplots(figsize=(6, 5))
            p = result.motion.points[tr.name].p * k
            ax.plot(p.real[0], p.imag[0], "o", color="C3",
                    label=f"{sym} = {result.q[0] * input_factor(spec):g}°"
                    if spec.input.rotary else "start")
            p = broken(result, p)
            ax.plot(p.real, p.imag, "-", color="C3", label=t["path"].format(name=tr.name))
            ax.set_title(f"{t['curve']} {tr.name}")
            ax.set_xlabel(f"{plotting.symbol('x' + tr.name)} / {unit}")
            ax.set_ylabel(f"{plotting.symbol('y' + tr.name)} / {unit}")
            ax.set_aspect("equal", adjustable="datalim")
            ax.legend(fontsize=7, loc="best")
            plotting.save_png(fig, outputs, f"path_{tr.name}.png")
    if animate:
        _animate(spec, result, sweep, outputs, t, k)
    return warnings


def angle_readout(spec, value):
    """The text of a frame's input: ``θ1 = 120°`` or ``s1 = 35.2 mm`` (value in
    degrees or spec units)."""
    n = spec.input.driver
    if spec.input.rotary:
        return f"{plotting.plain_symbol(f'theta{n}')} = {value:.0f}°"
    return f"{plotting.plain_symbol(f's{n}')} = {value:.4g} {spec.header.unit}"


def _animate(spec, result, sweep, outputs, t, k):
    n = spec.output.frames
    q = result.q
    qs = np.linspace(q[0], q[-1], n + 1)[:-1] if sweep.periodic else np.linspace(q[0], q[-1], n)
    m = solve(spec.linkage, sweep.inputs(qs), order=0)
    keep = np.flatnonzero(m.regular)
    if keep.size == 0:
        return
    fig, ax = plotting.subplots(figsize=(6.4, 5.2), dpi=plotting.GIF_DPI)
    d = Drawing(ax, spec.linkage, result.motion, 1 / k, spec.guide_length)
    for j, tr in enumerate(spec.tracers):
        p = broken(result, result.motion.points[tr.name].p * k)
        ax.plot(p.real, p.imag, ":", lw=1.2, color=f"C{(3 + j) % 10}",
                label=t["path"].format(name=tr.name))
    limits(ax, result.motion, k)
    ax.set_title(plotting.title(spec.header.title), fontsize=10)
    ax.set_xlabel(f"x / {spec.header.unit}")
    ax.set_ylabel(f"y / {spec.header.unit}")
    if spec.tracers:
        ax.legend(fontsize=8, loc="lower right")
    label = plotting.readout(ax)
    plotting.tight(fig)
    frames = plotting.Frames(fig, d.artists + [label])
    fin = input_factor(spec)
    for i in keep:
        d.update(m, i)
        label.set_text(angle_readout(spec, qs[i] * fin))
        frames.grab()
    frames.save(outputs, "kin.gif")
