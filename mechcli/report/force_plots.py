"""Pictures of ``mechcli force``: pair reactions and the balancing torque against the
input (图 2-5, 2-7, 2-9, 2-11), hodographs of the pin forces, the shaking force and
moment transmitted to the frame, and the GIF of the mechanism with its reactions.

Imports matplotlib: import this module only when a PNG or GIF is written.
"""

from __future__ import annotations

import math

import numpy as np

from mechcli.core.linkage.force_analysis import balancing_symbol
from mechcli.report import plotting, words
from mechcli.report.force import input_factor
from mechcli.report.kin_plots import Drawing, broken, extent, limits

_TEXT = {lang: words.table(lang, "force_plots") for lang in words.LANGUAGES}


def _t(t, key, **kw):
    return plotting.text(t[key].format(**kw))


def _input_label(spec, t):
    n = spec.input.driver
    if spec.input.rotary:
        return _t(t, "crank", n=n).replace(f"θ{n}", plotting.symbol(f"theta{n}"))
    return _t(t, "slide", n=n, u=spec.header.unit)


def _grid(n, ncols):
    from mechcli.report.plotting import plt

    rows = max(1, math.ceil(n / ncols))
    fig, axs = plt.subplots(rows, ncols, figsize=(5.5 * ncols, 3.4 * rows), squeeze=False)
    for ax in axs.flat[n:]:
        ax.set_visible(False)
    return fig, list(axs.flat[:n])


def _shade_loads(ax, spec, result, t):
    """Shade the input intervals where a conditional load acts."""
    fin = input_factor(spec)
    for k, (name, intervals) in enumerate(result.active.items()):
        for m, (a, b) in enumerate(intervals):
            ax.axvspan(a * fin, b * fin, color=f"C{(k + 4) % 10}", alpha=0.15, lw=0,
                       label=_t(t, "active", name=name) if m == 0 else None)


def plot_reactions(spec, result, outputs, t):
    """``force.png``: one panel per pair (x solid, y dashed) and per balancing quantity."""
    fin = input_factor(spec)
    kin = result.kin
    x = broken(kin, result.q * fin)
    xlabel = _input_label(spec, t)
    pairs = result.forces.pairs
    drivers = [d.link for d in spec.linkage.drivers]
    fig, axs = _grid(len(pairs) + len(drivers), 2)
    for ax, pf in zip(axs, pairs):
        lab = pf.pair.label
        ax.plot(x, broken(kin, pf.fx), "-", color="C0", lw=1.3,
                label=plotting.symbol(f"FR{lab}x"))
        ax.plot(x, broken(kin, pf.fy), "--", color="C3", lw=1.3,
                label=plotting.symbol(f"FR{lab}y"))
        ax.axhline(0, color="0.5", lw=0.6)
        ax.set_ylabel(f"{plotting.symbol(f'FR{lab}')} / N")
        handles, labels = ax.get_legend_handles_labels()
        if pf.pair.kind == "P":
            msym = plotting.symbol(f"MR{lab}")
            if plotting.is_constant(pf.couple):   # no second axis for a constant couple
                from matplotlib.lines import Line2D
                c = np.asarray(pf.couple, dtype=float)
                c = c[np.isfinite(c)]
                handles.append(Line2D([], [], ls="none"))
                labels.append(f"{msym} ≡ {float(c[0]) if c.size else 0.0:.4g} N·m")
            else:
                tw = ax.twinx()
                tw.grid(False)
                h, = tw.plot(x, broken(kin, pf.couple), ":", color="C2", lw=1.3, label=msym)
                tw.set_ylabel(f"{msym} / N·m")
                plotting.tie_axis(tw, "C2", "right")
                handles.append(h)
                labels.append(h.get_label())
        plotting.legend_above(ax, handles, labels, fontsize=7)
        ax.set_title(_t(t, "pair", lab="") .replace("F_R", plotting.symbol(f"FR{lab}"))
                     + f"  ({pf.pair.kind}, {pf.pair.point})", fontsize=10, pad=16)
        ax.set_xlabel(xlabel)
    for ax, link in zip(axs[len(pairs):], drivers):
        sym = balancing_symbol(spec.linkage, link)
        v = result.forces.balancing[link]
        msym = plotting.symbol(sym)
        ax.plot(x, broken(kin, v), "-", color="C1", lw=1.5, label=msym)
        ax.axhline(0, color="0.5", lw=0.6)
        _shade_loads(ax, spec, result, t)
        key = "Mb" if sym.startswith("Mb") else "Fb"
        ax.set_title(_t(t, key, sym=msym), fontsize=10, pad=16)   # above the legend's row
        ax.set_ylabel(f"{msym} / " + ("N·m" if key == "Mb" else "N"))
        ax.set_xlabel(xlabel)
        plotting.legend_above(ax, fontsize=7)
    fig.suptitle(plotting.title(spec.header.title), wrap=True)
    plotting.save_png(fig, outputs, "force.png")


def _jumps(result):
    """Indices i where a conditional load switches between positions i and i+1."""
    idx = set()
    for mask in getattr(result, "active_mask", {}).values():
        m = np.asarray(mask, dtype=bool)
        if m.ndim == 1 and m.size > 1:
            idx.update(np.flatnonzero(m[1:] != m[:-1]).tolist())
    return sorted(idx)


def broken_at_jumps(result, v):
    """Values with a NaN wherever a load switches on or off (a hodograph jumps
    there: its tip must not be joined across the jump), and between runs."""
    v = np.asarray(v, dtype=float)
    cuts = _jumps(result)
    if cuts:
        v = np.insert(v, np.asarray(cuts) + 1, np.nan)
        kin = result.kin
        if len(kin.runs) > 1:   # keep the runs' gaps too: shift them past the inserted NaN
            runs = [(a + int(np.searchsorted(cuts, a, side="left")),
                     b + int(np.searchsorted(cuts, b - 1, side="left")))
                    for a, b in kin.runs]
            parts = []
            for i0, i1 in runs:
                parts += [v[i0:i1], [np.nan]]
            return np.concatenate(parts[:-1])
        return v
    return broken(result.kin, v)


def plot_hodographs(spec, result, outputs, t):
    """``hodograph.png``: the path of the tip of each revolute pair's force vector,
    broken where a conditional load jumps on or off."""
    pins = [pf for pf in result.forces.pairs if pf.pair.kind == "R"]
    if not pins:
        return
    ncols = min(3, len(pins))
    fig, axs = _grid(len(pins), ncols)
    fig.set_size_inches(4.2 * ncols, 4.0 * math.ceil(len(pins) / ncols))
    for k, (ax, pf) in enumerate(zip(axs, pins)):
        lab = pf.pair.label
        ax.plot(broken_at_jumps(result, pf.fx), broken_at_jumps(result, pf.fy), "-",
                color=f"C{k % 10}", lw=1.2, label=plotting.symbol(f"FR{lab}"))
        ax.plot([pf.fx[0]], [pf.fy[0]], "o", color=f"C{k % 10}", ms=4, label=t["start"])
        ax.plot([0], [0], "+", color="k", ms=10, mew=1.5, label=t["origin"])
        ax.axhline(0, color="0.6", lw=0.5)
        ax.axvline(0, color="0.6", lw=0.5)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(_t(t, "hodo", lab="").replace("F_R", plotting.symbol(f"FR{lab}"))
                     + f"  ({pf.pair.point})", fontsize=10, pad=16)
        ax.set_xlabel(f"{plotting.symbol(f'FR{lab}x')} / N")
        ax.set_ylabel(f"{plotting.symbol(f'FR{lab}y')} / N")
        plotting.legend_above(ax, fontsize=7)
    fig.suptitle(plotting.title(spec.header.title), wrap=True)
    plotting.save_png(fig, outputs, "hodograph.png")


def plot_frame(spec, result, outputs, t):
    """``frame.png``: shaking force (x, y, magnitude), shaking moment and input power."""
    from mechcli.report.plotting import plt

    fin = input_factor(spec)
    kin, s = result.kin, result.series
    x = broken(kin, result.q * fin)
    fig, axs = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    ax = axs[0]
    ax.plot(x, broken(kin, s["Fshx"]), "-", color="C0", lw=1.2, label=r"$F_{\mathrm{sh}x}$")
    ax.plot(x, broken(kin, s["Fshy"]), "--", color="C3", lw=1.2, label=r"$F_{\mathrm{sh}y}$")
    ax.plot(x, broken(kin, s["Fsh"]), "-", color="k", lw=1.6, label=r"$|F_{\mathrm{sh}}|$")
    ax.set_ylabel("F / N")
    ax.set_title(_t(t, "shake_f"), fontsize=10)
    plotting.legend_outside(ax, fontsize=7)
    ax = axs[1]
    ax.plot(x, broken(kin, s["Msh"]), "-", color="C2", lw=1.4, label=plotting.symbol("Msh"))
    ax.set_ylabel(f"{plotting.symbol('Msh')} / N·m")
    plotting.legend_outside(ax, fontsize=7)
    ax.set_title(_t(t, "shake_m"), fontsize=10)
    ax = axs[2]
    ax.plot(x, broken(kin, s["P"]), "-", color="C1", lw=1.4, label="P")
    _shade_loads(ax, spec, result, t)
    plotting.legend_outside(ax, fontsize=7)
    ax.set_ylabel("$P$ / W")
    ax.set_title(_t(t, "power"), fontsize=10)
    ax.set_xlabel(_input_label(spec, t))
    for ax in axs:
        ax.axhline(0, color="0.5", lw=0.6)
    fig.suptitle(plotting.title(spec.header.title), wrap=True)
    plotting.save_png(fig, outputs, "frame.png")


def plot_engine(spec, result, engine, outputs, t):
    """``engine.png``: FL, FI, FP; FQ, FN, FT, Frad; and the turning moment T (the
    turning-moment diagram of the engine books) against the input."""
    from mechcli.report.plotting import plt

    fin = input_factor(spec)
    kin, s = result.kin, engine.series
    x = broken(kin, result.q * fin)
    fig, axs = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    groups = ((axs[0], ("FL", "FI", "FP"), "piston", "F / N"),
              (axs[1], ("FQ", "FN", "FT", "Frad"), "rod", "F / N"))
    for ax, syms, key, ylabel in groups:
        for k, sym in enumerate(syms):
            ax.plot(x, broken(kin, s[sym]), "-", color=f"C{k}", lw=1.3,
                    label=plotting.symbol(sym))
        ax.set_ylabel(ylabel)
        ax.set_title(_t(t, key), fontsize=10)
        plotting.legend_outside(ax, fontsize=7)
    ax = axs[2]
    T = s["T"]
    q = result.q
    # the trapezoidal mean over the sweep (the report's mean Mb is Gauss-Legendre exact)
    mean = (float(np.sum(0.5 * (T[1:] + T[:-1]) * np.diff(q)) / (q[-1] - q[0]))
            if q.size > 1 and q[-1] > q[0] else float(np.mean(T)))
    ax.plot(x, broken(kin, T), "-", color="k", lw=1.5, label="T")
    ax.axhline(mean, color="C3", lw=0.9, ls="--")
    ax.set_ylabel("T / N·m")
    ax.set_title(_t(t, "torque", m=mean), fontsize=10)
    ax.set_xlabel(_input_label(spec, t))
    for ax in axs:
        ax.axhline(0, color="0.5", lw=0.6)
    fig.suptitle(plotting.title(spec.header.title), wrap=True)
    plotting.save_png(fig, outputs, "engine.png")


def _frame_indices(result, frames, periodic):
    """``frames`` indices spread over the analysed positions (no repeated closing
    position of a full turn), keeping only positions with finite forces."""
    q = result.q
    n = q.size
    if periodic and n > 1 and math.isclose(q[-1] - q[0], 2 * math.pi, rel_tol=1e-9):
        n -= 1
    idx = np.unique(np.round(np.linspace(0, n - 1, max(1, min(frames, n)))).astype(int))
    ok = np.ones(q.size, dtype=bool)
    for pf in result.forces.pairs:
        ok &= np.isfinite(pf.fx) & np.isfinite(pf.fy)
    for pm in result.kin.motion.points.values():
        ok &= np.isfinite(pm.p)
    return idx[ok[idx]]


def animate_reactions(spec, result, sweep, outputs, t):
    """``force.gif``: the mechanism with the pair reactions F_Rij (force of link i on
    link j) drawn as arrows at the pair points, scaled to the largest magnitude."""
    from matplotlib.lines import Line2D

    from mechcli.report.plotting import plt

    motion = result.kin.motion
    k = 1 / spec.header.scale
    idx = _frame_indices(result, spec.output.frames, sweep.periodic)
    if idx.size == 0:
        return ["force.gif not written: no position with finite reactions"]
    pairs = result.forces.pairs
    fx = np.array([pf.fx[idx] for pf in pairs])
    fy = np.array([pf.fy[idx] for pf in pairs])
    peak = float(np.max(np.hypot(fx, fy))) if fx.size else 0.0
    length = 0.25 * extent(motion) * k
    f = length / peak if peak > 0 else 0.0

    fig, ax = plt.subplots(figsize=(7.6, 5.6), dpi=plotting.GIF_DPI)
    d = Drawing(ax, spec.linkage, motion, spec.header.scale, spec.guide_length)
    for tr in spec.tracers:
        p = broken(result.kin, motion.points[tr.name].p * k)
        ax.plot(p.real, p.imag, ":", lw=1, color="C3")
    limits(ax, motion, k, pad=0.3)
    ax.set_title(_t(t, "anim") + "\n" + plotting.title(spec.header.title), fontsize=10)
    ax.set_xlabel(f"x / {spec.header.unit}")
    ax.set_ylabel(f"y / {spec.header.unit}")
    colors = [f"C{(j + 1) % 10}" for j in range(len(pairs))]
    p0 = np.array([motion.points[pf.pair.point].p[idx[0]] * k for pf in pairs])
    quiv = ax.quiver(p0.real, p0.imag, np.zeros(len(pairs)), np.zeros(len(pairs)),
                     color=colors, angles="xy", scale_units="xy", scale=1, width=0.006,
                     zorder=5)
    handles = [Line2D([], [], color=c, lw=2, label=plotting.symbol(f"FR{pf.pair.label}"))
               for c, pf in zip(colors, pairs)]
    plotting.legend_outside(ax, handles, fontsize=8,
                            title=f"{length:.3g} {spec.header.unit} : {peak:.4g} N",
                            title_fontsize=8)
    label = plotting.readout(ax)
    plotting.tight(fig)
    frames = plotting.Frames(fig, d.artists + [quiv, label])
    n_in = spec.input.driver
    fin = input_factor(spec)
    sym = plotting.plain_symbol(f"theta{n_in}" if spec.input.rotary else f"s{n_in}")
    for j, i in enumerate(idx):
        d.update(motion, i)
        pts = np.array([motion.points[pf.pair.point].p[i] * k for pf in pairs])
        quiv.set_offsets(np.column_stack([pts.real, pts.imag]))
        quiv.set_UVC(fx[:, j] * f, fy[:, j] * f)
        v = result.q[i] * fin
        label.set_text(f"{sym} = {v:.0f}°" if spec.input.rotary else
                       f"{sym} = {v:.4g} {spec.header.unit}")
        frames.grab()
    frames.save(outputs, "force.gif")
    return []


def with_switch_rows(spec, result, switches, engine=None):
    """The sweep and the engine's series with the rows of both sides of every load
    switch (:class:`~mechcli.core.linkage.load_switches.SwitchRows`), as the plots
    read them: the two rows at one input make a curve jump vertically, and the
    hodographs break between them.  Returns ``(result, engine)`` unchanged without
    switches."""
    import types

    from mechcli.report.force_rows import merge, merged_order

    if switches is None or not len(switches):
        return result, engine
    keep, order = merged_order(result.q, switches)

    def m(v, sym):
        return merge(v, switches.series[sym], keep, order)

    q = merge(result.q, switches.q, keep, order)
    pairs = []
    for pf in result.forces.pairs:
        lab = pf.pair.label
        couple = (m(pf.couple, f"MR{lab}") if pf.pair.kind == "P"
                  else np.zeros(q.size))
        pairs.append(types.SimpleNamespace(pair=pf.pair, fx=m(pf.fx, f"FR{lab}x"),
                                           fy=m(pf.fy, f"FR{lab}y"), couple=couple))
    balancing = {link: m(v, balancing_symbol(spec.linkage, link))
                 for link, v in result.forces.balancing.items()}
    # a load without conditions acts everywhere
    masks = {name: merge(on, switches.active.get(name, np.ones(len(switches), dtype=bool)),
                         keep, order) for name, on in result.active_mask.items()}
    runs = [(int(np.searchsorted(q, result.q[a], side="left")),
             int(np.searchsorted(q, result.q[b - 1], side="right"))) for a, b in result.kin.runs]
    view = types.SimpleNamespace(
        q=q, kin=types.SimpleNamespace(runs=runs), active=result.active, active_mask=masks,
        series={sym: m(v, sym) for sym, v in result.series.items()},
        forces=types.SimpleNamespace(pairs=pairs, balancing=balancing))
    if engine is not None:
        engine = types.SimpleNamespace(series={sym: merge(v, switches.extra[sym], keep, order)
                                               for sym, v in engine.series.items()})
    return view, engine


def write(spec, result, sweep, outputs, lang, plots=True, animate=False, engine=None,
          switches=None):
    """Write ``force.png``, ``hodograph.png``, ``frame.png``, with an engine load
    ``engine.png`` (``engine``: core.linkage.piston.EngineSweep) and, if asked,
    ``force.gif``.

    Parameters
    ----------
    spec : ForceSpec
    result : ForceSweep
        Forces in N, torques in N·m, power in W (SI); drawn in those units against
        the input in degrees (crank) or spec length units (slider driver).
    sweep : Sweep
    outputs : Outputs
    lang : {"en", "zh"}
    switches : SwitchRows or None
        Both sides of every load switch: the diagrams draw the jumps vertically
        (:func:`with_switch_rows`); the animation shows the sweep's positions.

    Returns
    -------
    list of str
        Warnings (no CJK font for ``--lang zh``, no drawable position).
    """
    warnings = []
    used = plotting.setup(lang)
    if used != lang:
        warnings.append("no CJK font installed: plot labels are in English")
    t = _TEXT[used]
    if plots:
        view, eng = with_switch_rows(spec, result, switches, engine)
        plot_reactions(spec, view, outputs, t)
        plot_hodographs(spec, view, outputs, t)
        plot_frame(spec, view, outputs, t)
        if engine is not None:
            plot_engine(spec, view, eng, outputs, t)
    if animate:
        warnings += animate_reactions(spec, result, sweep, outputs, t)
    return warnings
