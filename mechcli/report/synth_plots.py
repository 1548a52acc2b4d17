"""Pictures of ``mechcli synth`` (imports matplotlib): the design drawn in every
prescribed position (the book's 图 3-5 …), the structural error of a function
generator, the Burmester curves, and ``--animate`` a GIF of the design moving."""

from __future__ import annotations

import math

import numpy as np

from mechcli.core.linkage import DriverMotion, solve
from mechcli.report import plotting, words
from mechcli.report.kin_plots import Drawing, limits
from mechcli.report.table import book_title

_T = {lang: words.table(lang, "synth_plots") for lang in words.LANGUAGES}


def _drive(chk, q):
    """Solve the checked linkage at inputs *q* of its driver."""
    return solve(chk.linkage, {chk.linkage.drivers[0].link: DriverMotion(q)}, order=0)


def _limit_inputs(sol):
    """The crank angles of a design from K at its two limit positions (B1, B2), or None."""
    des = sol.design
    crank = des.linkage.drivers[0]
    piv = next((el for el in des.linkage.elements
                if getattr(el, "name", None) == crank.pivot and hasattr(el, "x")), None)
    if piv is None or "B1" not in des.pivots or "B2" not in des.pivots:
        return None
    a = complex(piv.x, piv.y)
    return np.array([np.angle(complex(*des.pivots[b]) - a) for b in ("B1", "B2")])


def _pose_label(ax, points, feasible, i, text):
    """*text* beside ``points[i]``, pushed away from the other poses' points (C1 and C2 of
    two near poses apart)."""
    p = points[i]
    others = points[feasible]
    away = p - others.mean() if len(others) > 1 else 0
    # coincident points (a pose repeated): the labels go round the point, one per quadrant
    step = away if abs(away) > 1e-6 * max(1.0, abs(p)) else np.exp(1j * math.pi * (0.25 + i / 2))
    off = 9 * step / abs(step)
    ax.annotate(text, (p.real, p.imag), textcoords="offset points", xytext=(off.real, off.imag),
                fontsize=8, color=f"C{i % 10}", ha="left" if off.real >= 0 else "right",
                va="bottom" if off.imag >= 0 else "top")


def _positions_png(sol, outputs, name, title, unit, k, t, q=None):
    from mechcli.report.plotting import plt
    des, chk = sol.design, sol.check
    limits_only = q is not None
    q = np.asarray(chk.inputs if q is None else q, dtype=float)
    m = _drive(chk, q)
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    named = des.points or (["C"] if "C" in m.points else [])
    # the joints' names once (the first pose); the named points of every pose as C1, C2, …
    first = int(np.argmax(m.feasible)) if m.feasible.any() else -1
    for i in range(len(q)):
        if not m.feasible[i]:
            continue
        d = Drawing(ax, chk.linkage, m, 1 / k, labels=i == first and not named)
        d.update(m, i)
        for line in d.bar_lines + d.block_lines:
            line.set_color(f"C{i % 10}")
        for pname in named:
            _pose_label(ax, m.points[pname].p * k, m.feasible, i, f"{pname}{i + 1}")
    for pname, pts in des.points.items():
        pts = np.asarray(pts) * k
        ax.plot(pts.real, pts.imag, "x", color="k", ms=7)
    path = np.linspace(chk.start, chk.stop, 361) if chk.start != chk.stop else q
    mp = _drive(chk, path)
    for pname in ("C", "M"):
        if pname in mp.points and mp.feasible.any():
            p = mp.points[pname].p * k
            p = np.where(mp.feasible, p, np.nan)
            ax.plot(p.real, p.imag, ":", lw=1, color="0.4")
    limits(ax, m, k)
    ax.set_title(plotting.text(title) + "\n" + (t["lim"] if limits_only else t["pos"]), wrap=True)
    ax.set_xlabel(plotting.axis_label("x", unit))
    ax.set_ylabel(plotting.axis_label("y", unit))
    plotting.save_png(fig, outputs, name)


def _error_png(sol, outputs, name, title, t):
    from mechcli.report.plotting import plt
    v = sol.design.values
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.plot(v["error_x"], np.degrees(v["error_phi"]), "-", color="C0", label=t["ephi"])
    ax.axhline(0.0, color="0.3", lw=0.8)
    ax.set_xlabel(t["x"])
    ax.set_ylabel(t["ephi"])
    ax2 = ax.twinx()
    ax2.plot(v["error_x"], v["error_y"], "--", color="C1", label=t["ey"])
    ax2.set_ylabel(t["ey"] + "  (- -)")
    ax2.grid(False)
    plotting.tie_axis(ax, "C0", "left")
    plotting.tie_axis(ax2, "C1", "right")
    ax.set_title(plotting.text(title) + "\n" + t["err"], wrap=True)
    plotting.save_png(fig, outputs, name)


def _burmester_png(sol, prob, outputs, name, title, unit, k, t):
    from mechcli.report.plotting import plt
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    M = np.array([complex(x, y) for x, y in prob.data["M"]]) * k
    phi = np.asarray(prob.data["phi"])
    ax.plot(M.real, M.imag, "o", color="k", ms=4, label=t["poses"])
    span = max(float(np.ptp(M.real)), float(np.ptp(M.imag)), 1e-300)
    for z, p in zip(M, phi):
        ax.annotate("", (z.real + 0.15 * span * math.cos(p), z.imag + 0.15 * span * math.sin(p)),
                    (z.real, z.imag), arrowprops=dict(arrowstyle="->", lw=0.8))
    if sol.design is None:
        c = sol.extra
        for j, (cen, cir) in enumerate(zip(c.centre_branches(), c.circle_branches())):
            ax.plot(cen.real * k, cen.imag * k, "-", color="C0", lw=1,
                    label=t["centre"] if j == 0 else None)
            ax.plot(cir.real * k, cir.imag * k, "--", color="C3", lw=1,
                    label=t["circle"] if j == 0 else None)
        allp = np.concatenate([M] + [b * k for b in c.centre_branches()])
        lo, hi = np.percentile(allp.real, [2, 98]), np.percentile(allp.imag, [2, 98])
        ax.set_xlim(lo[0] - 0.2 * span, lo[1] + 0.2 * span)
        ax.set_ylim(hi[0] - 0.2 * span, hi[1] + 0.2 * span)
    else:
        for j, pr in enumerate(sol.extra):
            ax.plot([pr.centre.real * k], [pr.centre.imag * k], "^", color=f"C{j}", ms=8)
            if not pr.at_infinity:
                ax.plot([pr.circle.real * k], [pr.circle.imag * k], "o", color=f"C{j}", ms=6)
                ax.plot([pr.centre.real * k, pr.circle.real * k],
                        [pr.centre.imag * k, pr.circle.imag * k], "-", color=f"C{j}", lw=1,
                        label=f"pair {j + 1}")
    ax.set_aspect("equal", adjustable="box")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(plotting.text(title) + "\n" + (t["burm"] if sol.design is None else t["bpts"]),
                 wrap=True)
    ax.set_xlabel(plotting.axis_label("x", unit))
    ax.set_ylabel(plotting.axis_label("y", unit))
    plotting.save_png(fig, outputs, name)


def _animate(sol, outputs, name, title, k, frames=72, unit=""):
    from mechcli.report.plotting import plt
    chk = sol.check
    a, b = chk.start, chk.stop
    if a == b:
        a, b = 0.0, 2 * math.pi
    q = np.linspace(a, b, frames)
    m = _drive(chk, q)
    keep = np.flatnonzero(m.feasible)
    if keep.size == 0:
        return
    fig, ax = plt.subplots(figsize=(6.4, 5.2), dpi=plotting.GIF_DPI)
    d = Drawing(ax, chk.linkage, m, 1 / k)
    limits(ax, m, k)
    ax.set_title(plotting.text(title), fontsize=10, wrap=True)
    ax.set_xlabel(f"x / {unit}")
    ax.set_ylabel(f"y / {unit}")
    label = plotting.readout(ax)
    plotting.tight(fig)
    frames = plotting.Frames(fig, d.artists + [label])
    drv = chk.linkage.drivers[0]
    rotary = getattr(drv, "rotary", True)
    sym = plotting.plain_symbol(f"theta{drv.link}" if rotary else f"s{drv.link}")
    for i in keep:
        d.update(m, i)
        label.set_text(f"{sym} = {math.degrees(q[i]):.0f}°" if rotary else
                       f"{sym} = {q[i] * k:.4g} {unit}")
        frames.grab()
    frames.save(outputs, name)


def write(spec, solutions, outputs, lang, plots=True, animate=False):
    """Write ``positions.png``, ``error.png``, ``burmester.png`` and ``synth.gif``
    (suffixed ``-N`` per case of a [[case]] spec).  Returns warnings."""
    warnings = []
    used = plotting.setup(lang)
    if used != lang:
        warnings.append("no CJK font installed: plot labels are in English")
    t = _T[used]
    unit, k = spec.header.unit, 1 / spec.header.scale
    for i, (prob, sol) in enumerate(zip(spec.cases, solutions)):
        tag = f"-{i + 1}" if spec.multi else ""
        title = book_title(spec.header.title) + (f" [{i + 1}]" if spec.multi else "")
        des = sol.design
        if plots:
            if des is not None and sol.check.inputs is not None and len(sol.check.inputs):
                _positions_png(sol, outputs, f"positions{tag}.png", title, unit, k, t)
            elif des is not None and _limit_inputs(sol) is not None:
                _positions_png(sol, outputs, f"positions{tag}.png", title, unit, k, t,
                               _limit_inputs(sol))
            if des is not None and "error_x" in des.values:
                _error_png(sol, outputs, f"error{tag}.png", title, t)
            if sol.kind == "burmester":
                _burmester_png(sol, prob, outputs, f"burmester{tag}.png", title, unit, k, t)
        if animate and des is not None:
            _animate(sol, outputs, f"synth{tag}.gif", title, k, unit=unit)
    return warnings
