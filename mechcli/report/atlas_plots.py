"""Pictures of the atlas kinds of ``mechcli synth``: an atlas page (coupler curves as
72 dashes, the grid, the linkage with crank and frame collinear), the type chart
(图 7) and a path synthesis (the candidates' curves over the targets).  Draws only:
everything comes computed from the core."""

from __future__ import annotations

import numpy as np

from mechcli.report import plotting, words

_T = {lang: {**words.table(lang, "atlas_plots"), "regions": tuple(
    words.say(lang, f"atlas_plots.regions_{j}") for j in range(4))} for lang in words.LANGUAGES}


def write(spec, cases, outputs, lang):
    """``page[-N].png``, ``chart[-N].png``, ``path[-N].png`` for the atlas cases
    ``[(index, solution)]``.  Returns warnings."""
    used = plotting.setup(lang)
    t = _T[used]
    for i, sol in cases:
        tag = f"-{i + 1}" if spec.multi else ""
        if sol.kind == "atlas_page":
            _page(sol.extra, outputs, f"page{tag}.png", t)
        elif sol.kind == "type_chart":
            _chart(sol.extra, outputs, f"chart{tag}.png", t)
        elif sol.kind == "path" and sol.extra["candidates"]:
            _path(sol.extra, outputs, f"path{tag}.png", t, spec.header.unit,
                  1.0 / spec.header.scale)
    return []


def _page(page, outputs, name, t):
    from mechcli.report.atlas import WHY
    fig, ax = plotting.subplots(figsize=(8, 7))
    # the grid of coupler points, attached to the coupler in the drawn position
    # (crank along the frame, theta = 0: the first sample)
    x0 = page.x[:, 0] if page.x.size else np.zeros(0)
    for k in range(page.gx.size):
        if not page.ok[k]:
            continue
        xs, ys = page.x[k], page.y[k]
        # 72 dashes: every other 5° step drawn, so a dash's length shows the speed
        segs = np.stack([np.stack([xs[:-1], ys[:-1]], -1), np.stack([xs[1:], ys[1:]], -1)], 1)
        from matplotlib.collections import LineCollection
        ax.add_collection(LineCollection(segs[::2], colors="C0", linewidths=1.0))
        ax.add_collection(LineCollection(segs[1::2], colors="C0", linewidths=0.3, alpha=0.4))
    ax.plot(x0[page.ok], page.y[page.ok, 0] if page.x.size else [], ".", ms=3, color="k")
    if page.reason is None:
        # the linkage at theta = 0: crank pivot (0, 0), crank pin (1, 0), follower pivot (C, 0)
        A, B, C = page.A, page.B, page.C
        bx, by = 1.0, 0.0
        d = C - 1.0
        a = (A * A - B * B + d * d) / (2 * d)
        h = np.sqrt(max(A * A - a * a, 0.0))
        cx, cy = bx + a, by + h
        ax.plot([0, bx, cx, C, 0], [0, by, cy, 0, 0], "-o", color="k", lw=1.5, ms=4)
    else:
        ax.text(0.5, 0.5, t["none"].format(why=WHY[page.reason]), transform=ax.transAxes,
                ha="center", va="center", wrap=True)
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.grid(True, lw=0.3)
    ax.set_xlabel("x / crank")
    ax.set_ylabel("y / crank")
    step = np.degrees(page.theta[1] - page.theta[0]) if page.theta.size > 1 else 360.0
    ax.set_title(plotting.text(t["page"].format(A=page.A, B=page.B, C=page.C, s=step)))
    plotting.save_png(fig, outputs, name)


def _chart(res, outputs, name, t):
    from matplotlib.colors import ListedColormap
    ch = res.chart
    A = np.atleast_1d(ch.A)
    fig, axs = plotting.subplots(1, len(A), figsize=(5.5 * len(A), 5), squeeze=False)
    cmap = ListedColormap(["#9ecae1", "#fdd0a2", "#e5e5e5", "#d62728"])
    for j, a in enumerate(A):
        ax = axs[0, j]
        ax.pcolormesh(ch.B, ch.C, ch.region[j], cmap=cmap, vmin=-0.5, vmax=3.5, shading="auto")
        ax.set_xlabel(plotting.text(t["B"]))
        ax.set_ylabel(plotting.text(t["C"]))
        ax.set_title(plotting.text(f"{t['chart']}: A = {a:g}"))
        ax.set_aspect("equal")
        if res.mark is not None and j == 0:
            b, c = res.mark
            ax.plot([b], [c], "k*", ms=12)
            if res.ranges is not None:
                (clo, chi), (blo, bhi) = res.ranges["C"], res.ranges["B"]
                ax.plot([b, b], [clo, chi], "k-", lw=2)
                ax.plot([blo, bhi], [c, c], "k-", lw=2)
    from matplotlib.patches import Patch
    axs[0, -1].legend(handles=[Patch(color=cmap(i), label=plotting.text(n))
                               for i, n in enumerate(t["regions"])], loc="upper right",
                      fontsize=8)
    plotting.save_png(fig, outputs, name)


def _path(res, outputs, name, t, unit, k):
    fig, ax = plotting.subplots(figsize=(7, 6))
    x, y = (np.asarray(v) * k for v in res["targets"])
    for j, cand in enumerate(res["candidates"][:5]):
        curve = res.get("paths", {}).get(j)
        if curve is None:
            continue
        ax.plot(curve[0] * k, curve[1] * k, "-", lw=1.6 if j == 0 else 0.8,
                label=f"{j + 1}: rms {cand.refined.error_rms * k:.3g} {unit}")
    ax.plot(x, y, "o", color="k", ms=5, label=plotting.text(t["targets"]))
    for i, (px, py) in enumerate(zip(x, y)):
        ax.annotate(str(i + 1), (px, py), textcoords="offset points", xytext=(4, 4),
                    fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(t["x"].format(u=unit))
    ax.set_ylabel(t["y"].format(u=unit))
    ax.set_title(plotting.text(t["path"]))
    ax.legend(fontsize=8, loc="best")
    plotting.save_png(fig, outputs, name)
