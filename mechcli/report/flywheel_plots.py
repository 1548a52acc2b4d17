"""Pictures of ``mechcli flywheel`` (imports matplotlib): Je and dJe/dφ (图 6-4), Me and
the work ΔW(φ), ω(φ) and ω(t) (图 6-6 … 6-11)."""

from __future__ import annotations

import numpy as np

from mechcli.report import plotting, words
from mechcli.report.table import wrap

_T = {lang: words.table(lang, "flywheel_plots") for lang in words.LANGUAGES}


def write(spec, sol, outputs, lang):
    """Write ``flywheel.png`` (2×2: Je and dJe/dφ; Me and W; ω(φ); ω(t)).  Returns warnings."""
    from mechcli.report.plotting import plt
    warnings = []
    used = plotting.setup(lang)
    if used != lang:
        warnings.append("no CJK font installed: plot labels are in English")
    t = _T[used]
    m = sol.motion
    deg = np.degrees(m.phi)
    if not hasattr(m, "omega"):      # the equivalent model only: 图 6-4
        fig, ax = plt.subplots(figsize=(7, 4.5))
        ax.plot(deg, m.Je, "-", color="C0", label="$J_e$")
        ax.set_title(plotting.title(spec.header.title) + "\n" + t["je"], wrap=True)
        ax.set_xlabel(t["phi"])
        ax.set_ylabel("$J_e$ / kg·m²  (—)")
        if not plotting.is_constant(m.dJe):
            ax2 = ax.twinx()
            ax2.plot(deg, m.dJe, "--", color="C1", label=r"$dJ_e/d\varphi$")
            ax2.grid(False)
            ax2.set_ylabel(r"$dJ_e/d\varphi$ / (kg·m²/rad)  (- -)")
            plotting.tie_axis(ax, "C0", "left")
            plotting.tie_axis(ax2, "C1", "right")
        plotting.save_png(fig, outputs, "flywheel.png")
        return warnings
    fig, axs = plt.subplots(2, 2, figsize=(11, 8))
    ax = axs[0, 0]
    ax.plot(deg, m.Je, "-", color="C0", label="$J_e$")
    ax.set_title(t["je"])
    ax.set_xlabel(t["phi"])
    ax.set_ylabel("$J_e$ / kg·m²")
    if not plotting.is_constant(m.dJe):   # no second axis for a constant inertia's zero slope
        ax2 = ax.twinx()
        ax2.plot(deg, m.dJe, "--", color="C1", label=r"$dJ_e/d\varphi$")
        ax2.grid(False)
        ax2.set_ylabel(r"$dJ_e/d\varphi$ / (kg·m²/rad)  (- -)")
        plotting.tie_axis(ax, "C0", "left")
        plotting.tie_axis(ax2, "C1", "right")
    ax = axs[0, 1]
    E = 0.5 * np.asarray(m.Je) * np.asarray(m.omega) ** 2
    ax.plot(deg, m.Me, "-", color="C2", label="$M_e$")
    ax.set_title(t["me"])
    ax.set_xlabel(t["phi"])
    ax.set_ylabel("$M_e$ / N·m")
    dW = E - E[0]
    if not plotting.is_constant(dW):
        ax2 = ax.twinx()
        ax2.plot(deg, dW, "--", color="C3", label=r"$\Delta W$")
        ax2.grid(False)
        ax2.set_ylabel(r"$\Delta W$ / J  (- -)")
        plotting.tie_axis(ax, "C2", "left")
        plotting.tie_axis(ax2, "C3", "right")
    axs[1, 0].plot(deg, m.omega, "-", color="C0")
    axs[1, 0].set_title(t["w"])
    axs[1, 0].set_xlabel(t["phi"])
    axs[1, 0].set_ylabel("ω / (rad/s)")
    axs[1, 1].plot(m.t, m.omega, "-", color="C4")
    axs[1, 1].set_title(t["w"])
    axs[1, 1].set_xlabel(t["t"])
    axs[1, 1].set_ylabel("ω / (rad/s)")
    fig.suptitle(plotting.title(spec.header.title), wrap=True)
    plotting.save_png(fig, outputs, "flywheel.png")
    if sol.steady is not None and sol.steady.history:
        _convergence(spec, sol, outputs, t)
    return warnings


def _convergence(spec, sol, outputs, t):
    """convergence.png: |ω(T) − ω0| of every period the search integrated."""
    from mechcli.report.plotting import plt
    hist = sol.steady.history
    res = [abs(w1 - w0) if w1 is not None else np.nan for w0, w1 in hist]
    fig, ax = plt.subplots(figsize=(6.5, 4))
    floor = 1e-17
    ax.semilogy(range(1, len(res) + 1), [max(r, floor) for r in res], "o-", color="C0")
    ax.set_xlabel(t["iter"])
    ax.set_ylabel("|ω(φ0 + T) − ω0| / (rad/s)")
    # wrapped by hand, in display columns (a Chinese character takes two): a title
    # wrapped by matplotlib would not leave room for its second line above the axes
    ax.set_title("\n".join(wrap(plotting.title(spec.header.title), 60)) + "\n" + t["conv"]
                 + f" ({sol.steady.root})")
    plotting.save_png(fig, outputs, "convergence.png")


def animate(spec, sol, outputs, lang, frames=72):
    """flywheel.gif: the mechanism (when the spec has one) and the cursor on ω(φ)."""
    from mechcli.core.linkage import DriverMotion, solve
    from mechcli.report.kin_plots import Drawing, limits
    from mechcli.report.plotting import plt
    plotting.setup(lang)
    m = sol.motion
    deg = np.degrees(m.phi)
    idx = np.unique(np.linspace(0, len(m.phi) - 1, frames).round().astype(int))
    has_link = spec.linkage is not None
    fig, axs = plt.subplots(1, 2 if has_link else 1, figsize=(10 if has_link else 6, 4.6),
                            dpi=plotting.GIF_DPI)
    ax_w = axs[-1] if has_link else axs
    ax_w.plot(deg, m.omega, "-", color="C0", label="ω(φ)")
    cursor, = ax_w.plot([], [], "o", color="C3", ms=7)
    ax_w.set_xlabel("φ / °")
    ax_w.set_ylabel("ω / (rad/s)")
    drawing = None
    moving = [cursor]
    if has_link:
        k = 1 / spec.header.scale
        mo = solve(spec.linkage, {1: DriverMotion(np.asarray(m.phi)[idx])}, order=0)
        drawing = Drawing(axs[0], spec.linkage, mo, 1 / k)
        limits(axs[0], mo, k)
        axs[0].set_xlabel(f"x / {spec.header.unit}")
        axs[0].set_ylabel(f"y / {spec.header.unit}")
        moving += drawing.artists
    label = plotting.readout(axs[0] if has_link else ax_w)
    moving.append(label)
    fig.suptitle(plotting.title(spec.header.title), wrap=True)
    plotting.tight(fig)
    frames = plotting.Frames(fig, moving)
    for j, i in enumerate(idx):
        cursor.set_data([deg[i]], [m.omega[i]])
        if drawing is not None and bool(mo.feasible[j]):
            drawing.update(mo, j)
        label.set_text(f"φ = {deg[i]:.0f}°, ω = {m.omega[i]:.4g} rad/s")
        frames.grab()
    frames.save(outputs, "flywheel.gif")
