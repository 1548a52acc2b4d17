"""PNG diagrams and GIF animation for ``mechcli kin`` (imports matplotlib)."""

from __future__ import annotations

import math

import numpy as np

from mechcli.core.linkage import Bar, Block, Guide, Pivot, solve
from mechcli.report import plotting
from mechcli.report.kin import factor_of, input_factor, pretty_unit

_TITLES = {
    "en": {"disp": "Displacement", "vel": "Velocity", "acc": "Acceleration",
           "mech": "Mechanism at", "input": "crank angle θ1 / °", "curve": "Path of point",
           "anim": "Motion"},
    "zh": {"disp": "位移线图", "vel": "速度线图", "acc": "加速度线图", "mech": "机构位置",
           "input": "曲柄转角 θ1/°", "curve": "轨迹 点", "anim": "运动仿真"},
}


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


def _plot_group(ax, spec, result, qs, x, lang):
    """Angles/angular quantities on the left axis, linear ones on a twin axis (plotyy)."""
    unit, scale = spec.header.unit, spec.header.scale
    left = [q for q in qs if q.kind in ("angle", "angvel", "angacc")]
    right = [q for q in qs if q not in left]
    axes = [(ax, left)]
    if right:
        axes.append((ax.twinx() if left else ax, right))
    styles = ["-", "--", "-.", ":"]
    handles = []
    for k, (a, group) in enumerate(axes):
        for j, q in enumerate(group):
            f = factor_of(q.kind, scale)
            h, = a.plot(broken(result, x), broken(result, result.values[q.symbol] * f),
                        styles[j % 4],
                        color=f"C{j + 3 * k}", label=q.symbol)
            handles.append(h)
        if group:
            a.set_ylabel(", ".join(q.symbol for q in group) + f" / {pretty_unit(group[0].kind, unit)}")
    ax.legend(handles=handles, fontsize=7, loc="best")


def _link_segments(linkage):
    """The elements' drawing primitives, sorted: bars, blocks, guides, ground points."""
    prims = [p for el in linkage.elements for p in el.sketch(linkage.frame)]
    bars = [(p.a, p.b) for p in prims if isinstance(p, Bar)]
    blocks = [p for p in prims if isinstance(p, Block)]
    guides = [p for p in prims if isinstance(p, Guide)]
    grounds = [p.name for p in prims if isinstance(p, Pivot)]
    return bars, blocks, guides, grounds


class Drawing:
    """Artists for one mechanism drawing, updated frame by frame (any linkage: kin's,
    force's, a synthesized design, a flywheel's machine); ``guide_length`` draws a
    guide bar that long instead of just past its blocks."""

    def __init__(self, ax, linkage, motion, scale, guide_length=None):
        self.ax, self.k = ax, 1 / scale
        self.bars, self.blocks, self.guides, self.grounds = _link_segments(linkage)
        self.bar_lines = [ax.plot([], [], "-", color="C0", lw=2)[0] for _ in self.bars]
        self.guide_lines = [ax.plot([], [], "-", color="0.4", lw=1)[0] for _ in self.guides]
        self.block_lines = [ax.plot([], [], "-", color="C1", lw=1.5)[0] for _ in self.blocks]
        self.joints = ax.plot([], [], "o", color="k", ms=4, mfc="w")[0]
        gx = [motion.points[g].p[0].real * self.k for g in self.grounds]
        gy = [motion.points[g].p[0].imag * self.k for g in self.grounds]
        ax.plot(gx, gy, "^", color="k", ms=9, mfc="0.8")
        for g, x, y in zip(self.grounds, gx, gy):
            ax.annotate(g, (x, y), textcoords="offset points", xytext=(4, -12), fontsize=8)
        # guide length for drawing: longest reach of the blocks on it, plus a margin
        self.reach = {}
        for i, g in enumerate(self.guides):
            if g.ray:
                s = np.abs(motion.slides[g.slide].s)
                self.reach[i] = guide_length or 1.15 * float(np.max(s))
        self.size = 0.06 * extent(motion) * self.k

    def update(self, motion, i):
        P = {n: pm.p[i] * self.k for n, pm in motion.points.items()}
        for line, (a, b) in zip(self.bar_lines, self.bars):
            line.set_data([P[a].real, P[b].real], [P[a].imag, P[b].imag])
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
        for line, b in zip(self.block_lines, self.blocks):
            th = 0.0 if b.link is None else motion.links[b.link].theta[i]
            u = complex(math.cos(th), math.sin(th)) * self.size
            corners = [P[b.point] + z * u for z in (-1.4 - 0.7j, 1.4 - 0.7j, 1.4 + 0.7j,
                                                    -1.4 + 0.7j, -1.4 - 0.7j)]
            line.set_data([c.real for c in corners], [c.imag for c in corners])
        pts = [P[n] for n in P]
        self.joints.set_data([p.real for p in pts], [p.imag for p in pts])


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
    import matplotlib.pyplot as plt

    warnings = []
    used = plotting.setup(lang)
    if used != lang:
        warnings.append("no CJK font installed: plot labels are in English")
    t = _TITLES[used]
    unit, scale = spec.header.unit, spec.header.scale
    x = result.q * input_factor(spec)
    k = 1 / scale
    if plots:
        groups = _groups(quantities)
        fig, axs = plt.subplots(2, 2, figsize=(11, 8))
        for ax, order, title in zip(axs.flat[:3], (0, 1, 2), (t["disp"], t["vel"], t["acc"])):
            ax.set_title(title)
            ax.set_xlabel(t["input"] if spec.input.rotary else f"s1 / {unit}")
            if groups[order]:
                _plot_group(ax, spec, result, groups[order], x, lang)
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
        for tr in spec.tracers:
            p = broken(result, result.motion.points[tr.name].p * k)
            ax.plot(p.real, p.imag, ":", lw=1, label=tr.name)
        limits(ax, result.motion, k)
        ax.set_title(f"{t['mech']} θ1 = {at * input_factor(spec):g}°" if spec.input.rotary
                     else t["mech"])
        ax.set_xlabel(unit)
        ax.set_ylabel(unit)
        fig.suptitle(plotting.text(spec.header.title))
        fig.tight_layout()
        plotting.save_png(fig, outputs, "kin.png")
        for tr in spec.tracers:
            fig, ax = plt.subplots(figsize=(6, 5))
            p = result.motion.points[tr.name].p * k
            ax.plot(p.real[0], p.imag[0], "o", color="C3")
            p = broken(result, p)
            ax.plot(p.real, p.imag, "-", color="C3")
            ax.set_title(f"{t['curve']} {tr.name}")
            ax.set_xlabel(unit)
            ax.set_ylabel(unit)
            ax.set_aspect("equal", adjustable="box")
            plotting.save_png(fig, outputs, f"path_{tr.name}.png")
    if animate:
        _animate(spec, result, sweep, outputs, t, k)
    return warnings


def _animate(spec, result, sweep, outputs, t, k):
    import matplotlib.pyplot as plt

    n = spec.output.frames
    q = result.q
    qs = np.linspace(q[0], q[-1], n + 1)[:-1] if sweep.periodic else np.linspace(q[0], q[-1], n)
    m = solve(spec.linkage, sweep.inputs(qs), order=0)
    keep = np.flatnonzero(m.regular)
    fig, ax = plt.subplots(figsize=(5.5, 4.5), dpi=80)
    d = Drawing(ax, spec.linkage, result.motion, 1 / k, spec.guide_length)
    for tr in spec.tracers:
        p = result.motion.points[tr.name].p * k
        ax.plot(p.real, p.imag, ":", lw=1, color="C3")
    limits(ax, result.motion, k)
    ax.set_title(plotting.text(spec.header.title))
    # blitting: draw the static background once, then only the moving artists
    artists = d.bar_lines + d.guide_lines + d.block_lines + [d.joints]
    for a in artists:
        a.set_animated(True)
    fig.canvas.draw()
    background = fig.canvas.copy_from_bbox(fig.bbox)
    frames = []
    for i in keep:
        d.update(m, i)
        fig.canvas.restore_region(background)
        for a in artists:
            ax.draw_artist(a)
        frames.append(np.asarray(fig.canvas.buffer_rgba()).copy())
    plt.close(fig)
    plotting.save_gif(frames, outputs, "kin.gif")
