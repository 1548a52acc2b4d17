"""Pictures of ``mechcli cam``: s-v-a-j diagrams, the cam drawing (图 4-5 … 4-7),
pressure angle and curvature diagrams, and the GIF of the turning cam (运动仿真).

Imports matplotlib: import this module only when a PNG or GIF is written.
"""

from __future__ import annotations

import math

import numpy as np

from mechcli.report import plotting, words
from mechcli.report.plotting import plt

TEXT = {lang: words.table(lang, "cam_plots") for lang in words.LANGUAGES}


def _t(lang, key, unit):
    return TEXT[lang][key].format(u=unit)


#: the phases of the allowed pressure angles' legend, en and zh


def _boundaries(ax, design, label=None):
    for k, seg in enumerate(design.program.segments):
        ax.axvline(math.degrees(seg.start), color="0.6", lw=0.6, ls=":",
                   label=label if k == 0 else None)


def plot_motion(cs, design, out, lang):
    """``motion.png``: displacement, velocity, acceleration, jerk against δ."""
    p, unit, u = design.profile, cs.header.unit, cs.header.scale
    d = np.degrees(p.delta)
    w = cs.omega
    if cs.angular:
        ys = [np.degrees(p.s), p.s1, p.s2, p.s3]
        keys = ["psi", "vpsi", "apsi", "jpsi"] if w is None else ["psi", "vpsit", "apsit",
                                                                   "jpsit"]
    else:
        ys = [p.s / u, p.s1 / u, p.s2 / u, p.s3 / u]
        keys = ["s", "v", "a", "j"] if w is None else ["s", "vt", "at", "jt"]
    if w is not None:
        ys = [ys[0], ys[1] * w, ys[2] * w ** 2, ys[3] * w ** 3]
    fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True)
    for ax, y, key in zip(axes, ys, keys):
        ax.plot(d, y, lw=1.2)
        ax.set_ylabel(_t(lang, key, unit))
        _boundaries(ax, design)
    _boundaries(axes[0], design, words.say(lang, "cam_plots.boundary"))
    seen = set()
    for imp in design.impacts:
        ax = axes[1] if imp.kind == "rigid" else axes[2]
        ax.axvline(math.degrees(imp.delta), color="r" if imp.kind == "rigid" else "orange",
                   lw=1.0, alpha=0.7,
                   label=None if imp.kind in seen else (
                       words.say(lang, f"cam_plots.impact_{imp.kind}")))
        seen.add(imp.kind)
    for ax in axes:
        if ax.get_legend_handles_labels()[0]:
            plotting.legend_outside(ax, fontsize=7)
    axes[-1].set_xlabel(_t(lang, "delta", unit))
    axes[-1].set_xlim(0, 360)
    axes[0].set_title(plotting.title(cs.header.title), wrap=True)
    return plotting.save_png(fig, out, "motion.png")


def _circle(r, cx=0.0, cy=0.0, n=361):
    t = np.linspace(0, 2 * np.pi, n)
    return cx + r * np.cos(t), cy + r * np.sin(t)


def _follower_lines(cs, design, k):
    """Line pieces (list of (x, y) arrays, spec units) of the follower at sample *k*."""
    fol, p, u = design.follower, design.profile, cs.header.scale
    s = p.s[k]
    lines = []
    size = max(fol.r0, cs.stroke if not cs.angular else fol.l) / u
    if fol.motion == "translating":
        if fol.contact == "flat":
            y = (fol.r0 + s) / u
            half = 0.5 * max(design.checks.face_width_min / u * 1.3, 0.4 * size)
            x0 = fol.e / u
            lines.append((np.array([x0 - half, x0 + half]), np.array([y, y])))
            lines.append((np.array([x0, x0]), np.array([y, y + 0.8 * size])))
        else:
            x0, y0 = fol.e / u, (fol.s0 + s) / u
            top = y0 + 0.8 * size
            if fol.contact == "roller":
                lines.extend(_roller(fol.rr / u, x0, y0, p.roller_angle[k]))
            lines.append((np.array([x0, x0]), np.array([y0, top])))
    else:
        th = fol.phi0 + s
        bx = -fol.arm_side * fol.l * math.sin(th) / u
        by = (fol.a - fol.l * math.cos(th)) / u
        lines.append((np.array([0.0, bx]), np.array([fol.a / u, by])))
        if fol.contact == "roller":
            lines.extend(_roller(fol.rr / u, bx, by, p.roller_angle[k]))
    return lines


def _roller(r, cx, cy, angle):
    """Roller circle and a mark turning with it (the book's 滚子圆标线)."""
    mark = (np.array([cx, cx + r * math.cos(-angle)]), np.array([cy, cy + r * math.sin(-angle)]))
    return [_circle(r, cx, cy, 91), mark]


def _outline(design):
    from mechcli.core.cam.geometry import working_outline

    return working_outline(design.follower, design.program, design.profile,
                           design.checks.corners)


def plot_profile(cs, design, out, lang):
    """``profile.png``: base circle, pitch and working curves, follower at δ = 0."""
    p, fol, unit, u = design.profile, design.follower, cs.header.unit, cs.header.scale
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.plot(*_circle(fol.r0 / u), color="g", lw=0.8, label=_t(lang, "base", unit))
    if fol.motion == "translating" and fol.e != 0 and fol.contact != "flat":
        ax.plot(*_circle(abs(fol.e) / u), color="c", lw=0.6, ls="--",
                label=_t(lang, "offset", unit))
    if p.pitch is not None and fol.contact == "roller":
        ax.plot(p.pitch[0] / u, p.pitch[1] / u, "r--", lw=1.0, label=_t(lang, "pitch", unit))
    outline = _outline(design) / u
    ax.plot(outline[0], outline[1], "b", lw=1.5, label=_t(lang, "work", unit))
    for x, y in _follower_lines(cs, design, 0):
        ax.plot(x, y, "k", lw=1.2)
    if fol.motion == "oscillating":
        ax.plot([0], [fol.a / u], "ko", ms=4)
    ax.plot([0], [0], "k+", ms=10)
    ax.set_aspect("equal")
    ax.set_xlabel(_t(lang, "x", unit))
    ax.set_ylabel(_t(lang, "y", unit))
    ax.set_title(plotting.title(cs.header.title), wrap=True)
    plotting.legend_outside(ax, fontsize=8)
    return plotting.save_png(fig, out, "profile.png")


def plot_checks(cs, design, out, lang):
    """``checks.png``: pressure angle and radii of curvature against δ."""
    p, fol, unit, u = design.profile, design.follower, cs.header.unit, cs.header.scale
    d = np.degrees(p.delta)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    a1.plot(d, np.degrees(p.alpha), lw=1.2)
    for j, lim in enumerate((cs.limits.alpha_rise, cs.limits.alpha_return)):
        for sgn in (1, -1):
            a1.axhline(sgn * math.degrees(lim), color="r" if j == 0 else "m", lw=0.6, ls="--",
                       label=(f"[α] {words.say(lang, f'cam_plots.phase_{j}')} = "
                              f"{math.degrees(lim):g}°") if sgn == 1 else None)
    for ext in (design.checks.alpha_rise, design.checks.alpha_return):
        if ext is not None:
            a1.plot([math.degrees(ext.delta)], [math.degrees(ext.value) * np.sign(
                np.interp(ext.delta, p.delta, p.alpha) or 1.0)], "ro", ms=4)
    a1.set_ylabel(_t(lang, "alpha", unit))
    _boundaries(a1, design, words.say(lang, "cam_plots.boundary"))
    plotting.legend_outside(a1, fontsize=7)
    lim = 4 * fol.r0 / u
    clipped = False
    for rho, style, key in ((p.rho_pitch, "r--", "rho_p"), (p.rho_work, "b", "rho_w")):
        if rho is None:
            continue
        r = np.asarray(rho, dtype=float) / u
        clipped |= bool(np.any(np.abs(r[np.isfinite(r)]) > lim))
        a2.plot(d, np.clip(r, -lim, lim), style, lw=1.0 if key == "rho_p" else 1.2,
                label=_t(lang, key, unit))
    a2.axhline(0, color="k", lw=0.6)
    a2.set_ylabel(_t(lang, "rho", unit))
    a2.set_xlabel(_t(lang, "delta", unit))
    a2.set_xlim(0, 360)
    _boundaries(a2, design)
    if clipped:   # say so: an infinite radius (a flat) would leave the picture
        plotting.clip_notice(a2, "ρ", -lim, lim, unit)
        plotting.text_notice(f"checks.png: the radius of curvature is drawn clipped to "
                             f"±{lim:.4g} {unit} (4 r0)")
    plotting.legend_outside(a2, fontsize=7)
    return plotting.save_png(fig, out, "checks.png")


def plot_all(cs, design, out, lang):
    """Write every PNG of a cam run."""
    plot_motion(cs, design, out, lang)
    plot_profile(cs, design, out, lang)
    plot_checks(cs, design, out, lang)


def animate(cs, design, out, lang, fps=12, progress=False):
    """``cam.gif``: the cam turning and the follower moving (the book's 运动仿真).

    With *progress*, a rich progress bar on stderr counts the frames.
    """
    p, fol, unit, u = design.profile, design.follower, cs.header.unit, cs.header.scale
    grid = np.arange(len(p.delta)) if p.grid is None else np.flatnonzero(p.grid)
    n = len(grid) - 1         # frames at grid samples (a jump's left limit is not a frame)
    idx = grid[np.unique(np.round(np.linspace(0, n, cs.frames, endpoint=False)).astype(int))]
    fig, (ax, axs) = plt.subplots(1, 2, figsize=(10, 4.8), dpi=plotting.GIF_DPI,
                                  gridspec_kw={"width_ratios": [1.2, 1]})
    reach = float(np.max(np.hypot(*p.work))) / u
    pts = [np.concatenate([ln[0] for ln in _follower_lines(cs, design, k)]) for k in idx]
    ys = [np.concatenate([ln[1] for ln in _follower_lines(cs, design, k)]) for k in idx]
    xs_all, ys_all = np.concatenate(pts), np.concatenate(ys)
    x0, x1 = min(-reach, xs_all.min()), max(reach, xs_all.max())
    y0, y1 = min(-reach, ys_all.min()), max(reach, ys_all.max())
    pad = 0.06 * max(x1 - x0, y1 - y0)
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal")
    ax.set_title(plotting.title(cs.header.title), fontsize=10, wrap=True)
    ax.set_xlabel(_t(lang, "x", unit))
    ax.set_ylabel(_t(lang, "y", unit))
    cam_line, = ax.plot([], [], "b", lw=1.5)
    base_x, base_y = _circle(fol.r0 / u)
    ax.plot(base_x, base_y, color="g", lw=0.6)
    ax.plot([0], [0], "k+", ms=8)
    marker, = ax.plot([], [], "r.", ms=4)
    foll = [ax.plot([], [], "k", lw=1.2)[0] for _ in range(3)]
    d = np.degrees(p.delta)
    y = np.degrees(p.s) if cs.angular else p.s / u
    axs.plot(d, y, lw=1.2)
    dot, = axs.plot([], [], "ro", ms=5)
    axs.set_xlim(0, 360)
    axs.set_xlabel(_t(lang, "delta", unit))
    axs.set_ylabel(_t(lang, "psi" if cs.angular else "s", unit))
    outline = _outline(design) / u
    label = plotting.readout(ax)
    plotting.tight(fig)
    frames = plotting.Frames(fig, [cam_line, marker, dot, label] + foll)
    steps = idx
    if progress:
        from rich.console import Console
        from rich.progress import track

        steps = track(idx, description="cam.gif", console=Console(stderr=True),
                      transient=True)
    for k in steps:
        ang = fol.rotation * p.delta[k]
        c, s = math.cos(ang), math.sin(ang)
        wx, wy = outline
        cam_line.set_data(c * wx - s * wy, s * wx + c * wy)
        mx, my = wx[0], wy[0]
        marker.set_data([c * mx - s * my], [s * mx + c * my])
        lines = _follower_lines(cs, design, k)
        for art, ln in zip(foll, lines + [(np.array([]), np.array([]))] * 3):
            art.set_data(*ln)
        dot.set_data([d[k]], [y[k]])
        label.set_text(f"δ = {d[k]:.0f}°")
        frames.grab()
    return frames.save(out, "cam.gif", fps=fps)
