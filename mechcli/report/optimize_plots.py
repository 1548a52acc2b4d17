"""Pictures of ``mechcli optimize``: the convergence of the method, the objective
surface of a two-variable problem with its infeasible region and the path of the
iterates (the book's ``crankobjfun_VR``), the target against the achieved function
or path, and ``--animate`` the optimized linkage moving.

Nothing here solves anything: the command computes the surface grid
(:func:`mechcli.core.optimize.problem.grid`) and the poses of the optimum
(:func:`mechcli.core.linkage.solve`) and hands them over.  matplotlib is imported
inside the functions only.
"""

from __future__ import annotations

import math

import numpy as np

from mechcli.report import words
from mechcli.report.table import book_title

_T = {lang: words.table(lang, "optimize_plots") for lang in words.LANGUAGES}

#: last parts of a dotted key that hold an angle in degrees (the rest are lengths)
_ANGLE_KEYS = ("start", "stop", "step", "angle", "theta", "theta0", "phi", "phi0", "psi0",
               "alpha", "beta", "delta", "gamma", "offset_angle")


def _var_label(spec, i):
    v = spec.variables[i]
    last = v.key.split(".")[-1]
    unit = "°" if v.goal or last in _ANGLE_KEYS else spec.header.unit
    from mechcli.report import plotting
    # the book's symbol (l2, not the spec path mechanism.l2)
    return plotting.axis_label(plotting.symbol(last), unit)


def _f_unit(funit):
    """The objective's unit as a figure writes it (rad², mm²; the JSON keeps f_unit's rad^2)."""
    return funit.replace("^2", "²")


def surface_span(problem, result, margin=0.5, crowded=3.0):
    """The box of the surface picture: the variables' bounds, or, where the bounds
    are more than ``crowded`` times wider than the region the method visited
    (start, iterates, optimum), that region grown by ``margin`` on each side and
    kept within the bounds (the book's ``crankobjfun_VR`` draws x1 in 4 … 5.3,
    x2 in 1.8 … 4 out of bounds 1 … 20).  Plain arithmetic on numbers: the
    command passes it to :func:`~mechcli.core.optimize.problem.grid`."""
    lo, hi = np.asarray(problem.lo, dtype=float), np.asarray(problem.hi, dtype=float)
    pts = [np.asarray(problem.start, dtype=float), np.asarray(result.x, dtype=float)]
    pts += [np.asarray(r.x, dtype=float) for r in result.history]
    P = np.array([p for p in pts if p.shape == lo.shape and np.all(np.isfinite(p))])
    a, b = P.min(axis=0), P.max(axis=0)
    d = np.maximum(b - a, 0.1 * np.maximum(np.abs(np.asarray(result.x, dtype=float)), 1e-3))
    out = []
    for k in range(lo.size):
        if hi[k] - lo[k] > crowded * (1 + 2 * margin) * d[k]:
            out.append((max(lo[k], a[k] - margin * d[k]), min(hi[k], b[k] + margin * d[k])))
        else:
            out.append((lo[k], hi[k]))
    return tuple(out)


def _history(result):
    h = list(result.history)
    it = np.array([r.iteration for r in h], dtype=float)
    if len(it) and not np.all(np.diff(it) > 0):     # multi-start: iterations restart
        it = np.arange(1, len(h) + 1, dtype=float)
        return it, h, "record"
    return it, h, "iter"


def _convergence_png(spec, problem, result, outputs, t, title):
    from mechcli.report import plotting
    from mechcli.report.optimize import f_scale
    from mechcli.report.plotting import plt
    it, h, xlabel = _history(result)
    factor, funit = f_scale(spec)
    f = np.array([r.f for r in h]) * factor
    v = np.array([r.violation for r in h])
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    fin = f[np.isfinite(f)]
    log_f = fin.size > 0 and fin.min() > 0 and fin.max() / fin.min() > 10
    ax1.plot(it, f, "o-", color="C0", ms=4)
    ax1.axhline(result.f * factor, color="C3", lw=0.8, ls="--",
                label=f"{t['best']} = {result.f * factor:.6g}")
    if log_f:
        ax1.set_yscale("log")
    ax1.set_ylabel(t["f"] if funit == "as the result"
                   else plotting.axis_label(t["f"], _f_unit(funit)))
    ax1.legend(fontsize=8, loc="best")
    pos = v > 0
    if pos.any():
        floor = max(float(v[pos].min()) * 0.1, 1e-300)
        ax2.semilogy(it, np.maximum(v, floor), "s-", color="C1", ms=4)
        ax2.axhline(problem.FEASIBLE_TOL, color="0.4", lw=0.8, ls=":", label=t["tol"])
        ax2.legend(fontsize=8, loc="best")
    else:
        ax2.plot(it, v, "s-", color="C1", ms=4)
        ax2.text(0.5, 0.5, t["all_feasible"], transform=ax2.transAxes, ha="center",
                 color="0.3")
    ax2.set_ylabel(t["viol"])
    ax2.set_xlabel(t[xlabel])
    ax1.set_title(plotting.text(title) + "\n" + t["conv"] + f" ({result.method})", wrap=True)
    plotting.save_png(fig, outputs, "convergence.png")


def _thin_labels(ax, labels, U, V, dx=0.12, dy=0.06):
    """Keep one contour label of those closer than (dx, dy) of the box to each other (the
    closed contours round an optimum put all their labels on one spot)."""
    wu, wv = float(np.ptp(U)) or 1.0, float(np.ptp(V)) or 1.0
    kept = []
    for label in labels:
        x, y = label.get_position()
        if any(abs(x - a) / wu < dx and abs(y - b) / wv < dy for a, b in kept):
            label.remove()
        else:
            kept.append((x, y))


def _surface_png(spec, problem, result, surface, outputs, t, title):
    from matplotlib import colors

    from mechcli.report import plotting
    from mechcli.report.optimize import f_scale
    from mechcli.report.plotting import plt
    u, v, F, feas = surface
    factor, funit = f_scale(spec)
    F = np.asarray(F, dtype=float) * factor
    U, V = np.meshgrid(u, v)
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    fin = F[np.isfinite(F)]
    if fin.size and fin.min() > 0 and fin.max() / fin.min() > 100:
        levels = np.geomspace(fin.min(), fin.max(), 25)
        norm = colors.LogNorm(fin.min(), fin.max())
    elif fin.size and fin.max() > fin.min():
        levels = np.linspace(fin.min(), fin.max(), 25)
        norm = None
    else:
        levels, norm = None, None
    if levels is not None:
        cf = ax.contourf(U, V, F, levels=levels, norm=norm, cmap="viridis", alpha=0.55)
        cs = ax.contour(U, V, F, levels=levels[::3], norm=norm, colors="k", linewidths=0.5)
        _thin_labels(ax, ax.clabel(cs, fontsize=6, fmt="%.3g"), U, V)
        cb = fig.colorbar(cf, ax=ax, ticks=levels[::4], format="%.3g")
        cb.minorticks_off()
        cb.set_label("f" if funit == "as the result" else plotting.axis_label("f", _f_unit(funit)))
    bad = ~np.asarray(feas, dtype=bool)
    if bad.any():
        ax.contourf(U, V, bad.astype(float), levels=[0.5, 1.5], colors=["0.55"], alpha=0.45,
                    hatches=["///"])
        ax.plot([], [], "s", color="0.55", alpha=0.6, ms=9, label=t["infeasible"])
    path = np.array([problem.start] + [r.x for r in result.history] + [result.x])
    ax.plot(path[:, 0], path[:, 1], ".-", color="C3", lw=1, ms=5, label=t["path"])
    ax.plot([problem.start[0]], [problem.start[1]], "s", color="C1", ms=8, mec="k",
            label=f"{t['start']} ({problem.start[0]:.4g}, {problem.start[1]:.4g})")
    ax.plot([result.x[0]], [result.x[1]], "*", color="C3", ms=15, mec="k",
            label=f"{t['opt']} ({result.x[0]:.5g}, {result.x[1]:.5g})")
    ax.set_xlim(u[0], u[-1])
    ax.set_ylim(v[0], v[-1])
    ax.set_xlabel(_var_label(spec, 0))
    ax.set_ylabel(_var_label(spec, 1))
    ax.legend(fontsize=7, loc="best", framealpha=0.85)
    # pad: above the colour bar's top tick label, which stands half a line over the axes
    ax.set_title(plotting.text(title) + "\n" + t["surf"], wrap=True, pad=12)
    plotting.save_png(fig, outputs, "surface.png")


def _function_png(spec, details, goal, rotary, outputs, t, title):
    from mechcli.report import plotting
    from mechcli.report.plotting import plt
    out = spec.objective["output"]
    slide = isinstance(out, str)
    q = np.asarray(details["q"][0], dtype=float)
    psi = np.asarray(details["psi"][0], dtype=float)
    dev = np.asarray(details["dev"][0], dtype=float)
    unit = spec.header.unit
    x = np.degrees(q) if rotary else q / spec.unit
    if slide:
        size = float(getattr(goal, "scale", 1.0))
        got = psi / spec.unit
        err = dev * size / spec.unit
        ylab = plotting.axis_label(f"{t['output_s']} ({out})", unit)
        elab = plotting.axis_label(t["dev"], unit)
    else:
        psi = np.unwrap(psi)
        got = np.degrees(psi)
        err = np.degrees(dev)
        ylab = t["output"].replace(" / ", f" (link {out}) / ")
        elab = plotting.axis_label(t["dev"], "°")
    target = got - err
    phi0 = float(details["phi0"][0])
    x0 = math.degrees(phi0) if rotary else phi0 / spec.unit
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True,
                                   gridspec_kw={"height_ratios": [2, 1]})
    ax1.plot(x, target, "--", color="C3", lw=1.5, label=t["tgt_fn"])
    ax1.plot(x, got, "o-", color="C0", ms=3, lw=1, label=t["got_fn"])
    ax1.axvline(x0, color="0.5", lw=0.8, ls=":")
    ax1.annotate("φ0" if rotary else "s0", (x0, ax1.get_ylim()[0]), textcoords="offset points",
                 xytext=(3, 3), fontsize=8, color="0.3")
    ax1.set_ylabel(ylab)
    ax1.legend(fontsize=8, loc="best")
    ax2.plot(x, err, "o-", color="C1", ms=3, lw=1)
    ax2.axhline(0.0, color="0.3", lw=0.8)
    ax2.set_ylabel(elab)
    ax2.set_xlabel(t["input"] if rotary else plotting.axis_label(t["input_s"], unit))
    ax1.set_title(plotting.text(title) + "\n" + t["target"], wrap=True)
    plotting.save_png(fig, outputs, "target.png")


def _feasible_points(motion, name, k):
    p = np.asarray(motion.points[name].p) * k
    return np.where(np.asarray(motion.feasible, dtype=bool), p, np.nan + 0j)


def _path_png(spec, details, poses, outputs, t, title):
    from mechcli.report import plotting
    from mechcli.report.plotting import plt
    k = 1 / spec.unit
    name = spec.objective["point"]
    T = np.asarray(spec.objective["targets"], dtype=float) * k
    fig, ax = plt.subplots(figsize=(6.5, 5.5))
    allp = [T[:, 0] + 1j * T[:, 1]]
    if poses is not None:
        p = _feasible_points(poses["motion"], name, k)
        ax.plot(p.real, p.imag, "-", color="C0", lw=1.2, label=f"{t['curve']} {name} (x*)")
        allp.append(p[np.isfinite(p)])
        if poses.get("at") is not None:
            pa = _feasible_points(poses["at"], name, k)
            ax.plot(pa.real, pa.imag, "o", color="C0", ms=5, mfc="w", label=t["at"])
            for (tx, ty), z in zip(T, pa):
                if np.isfinite(z):
                    ax.plot([tx, z.real], [ty, z.imag], "-", color="C3", lw=0.8)
    ax.plot(T[:, 0], T[:, 1], "x", color="C3", ms=8, mew=2, label=t["points"])
    for j, (tx, ty) in enumerate(T):
        ax.annotate(str(j + 1), (tx, ty), textcoords="offset points", xytext=(4, 4),
                    fontsize=7, color="C3")
    if "dist" in details:
        d = np.asarray(details["dist"][0]) * k
        ax.text(0.02, 0.02, f"max |d| = {d.max():.4g} {spec.header.unit}",
                transform=ax.transAxes, fontsize=8, color="0.2")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(spec.header.unit)
    ax.set_ylabel(spec.header.unit)
    ax.legend(fontsize=7, loc="best")
    ax.set_title(plotting.text(title) + "\n" + t["target"] + f" ({name})", wrap=True)
    plotting.save_png(fig, outputs, "target.png")


def _output_of(motion, output):
    if isinstance(output, str):
        return np.asarray(motion.slides[output].s), True
    return np.asarray(motion.links[output].theta), False


def _animate(spec, details, poses, outputs, t, title, frames=72):
    from mechcli.report import plotting
    from mechcli.report.kin_plots import Drawing
    from mechcli.report.plotting import plt
    m = poses["motion"]
    feas = np.asarray(m.feasible, dtype=bool)
    keep = np.flatnonzero(feas)
    if keep.size == 0:
        return
    idx = keep[np.unique(np.linspace(0, keep.size - 1, min(frames, keep.size)).round()
                         .astype(int))]
    k = 1 / spec.unit
    obj = spec.objective
    fn = obj["kind"] == "function" and "q" in details
    fig, axs = plt.subplots(1, 2 if fn else 1, figsize=(10.5 if fn else 6.4, 5.0),
                            dpi=plotting.GIF_DPI)
    ax = axs[0] if fn else axs
    d = Drawing(ax, poses["linkage"], m, spec.unit)
    # limits over the feasible poses (and the targets), equal aspect
    pts = [np.asarray(pm.p)[feas] * k for pm in m.points.values()]
    trace = tail = None
    if obj["kind"] == "path":
        T = np.asarray(obj["targets"], dtype=float) * k
        pts.append(T[:, 0] + 1j * T[:, 1])
        ax.plot(T[:, 0], T[:, 1], "x", color="C3", ms=7, mew=2)
        trace = _feasible_points(m, obj["point"], k)
        tail, = ax.plot([], [], "-", color="C2", lw=1.2)
    pts = np.concatenate([p.ravel() for p in pts])
    x0, x1, y0, y1 = pts.real.min(), pts.real.max(), pts.imag.min(), pts.imag.max()
    pad = 0.12 * max(x1 - x0, y1 - y0, 1e-300)
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(f"x / {spec.header.unit}")
    ax.set_ylabel(f"y / {spec.header.unit}")
    cursor = None
    if fn:
        rotary = poses.get("rotary", True)
        q = np.asarray(poses["q"], dtype=float)
        xs = np.degrees(q) if rotary else q / spec.unit
        val, slide = _output_of(m, obj["output"])
        val = np.broadcast_to(val, q.shape)
        if slide:
            y = np.where(feas, val / spec.unit, np.nan)
        else:
            y = np.where(feas, np.degrees(np.unwrap(np.where(feas, val, 0.0))), np.nan)
        # the target on its own range, from details (the same branch of the angle)
        got = np.asarray(details["psi"][0], dtype=float)
        dev = np.asarray(details["dev"][0], dtype=float)
        if slide:
            tgt = (got - dev * poses.get("size", 1.0)) / spec.unit
            gq = got / spec.unit
        else:
            tgt = np.degrees(np.unwrap(got) - dev)
            gq = np.degrees(np.unwrap(got))
        xq = np.degrees(details["q"][0]) if rotary else details["q"][0] / spec.unit
        # put the achieved curve on the same 360° branch as the details
        j = int(np.nanargmin(np.abs(np.mod(xs - xq[0] + 180, 360) - 180))) if rotary else 0
        if not slide and np.isfinite(y[j]):
            y = y + 360.0 * round((gq[0] - y[j]) / 360.0)
        axs[1].plot(xs, y, "-", color="C0", lw=1, label=t["got_fn"])
        axs[1].plot(xq, tgt, "--", color="C3", lw=1.5, label=t["tgt_fn"])
        axs[1].set_xlabel(t["input"] if rotary else f"{t['input_s']} / {spec.header.unit}")
        axs[1].set_ylabel(t["output"] if not slide else f"{t['output_s']} / "
                          f"{spec.header.unit}")
        axs[1].legend(fontsize=7, loc="best")
        cursor, = axs[1].plot([], [], "o", color="C3", ms=7)
    fig.suptitle(plotting.text(title), wrap=True)
    label = plotting.readout(ax)
    plotting.tight(fig)
    frames = plotting.Frames(fig, d.artists + [tail, cursor, label])
    drv = poses["linkage"].drivers[0]
    rotary_in = poses.get("rotary", True)
    sym = plotting.plain_symbol(f"theta{drv.link}" if rotary_in else f"s{drv.link}")
    qin = np.asarray(poses["q"], dtype=float)
    for n, i in enumerate(idx):
        d.update(m, i)
        if tail is not None:
            seg = trace[keep[keep <= i]]
            tail.set_data(seg.real, seg.imag)
        if cursor is not None:
            cursor.set_data([xs[i]], [y[i]])
        label.set_text(f"{sym} = {math.degrees(qin[i]):.0f}°" if rotary_in else
                       f"{sym} = {qin[i] * k:.4g} {spec.header.unit}")
        frames.grab()
    frames.save(outputs, "optimize.gif")


def write(spec, problem, result, details, outputs, lang, plots=True, animate=False,
          surface=None, poses=None, goal=None):
    """Write ``convergence.png``, ``surface.png`` (two variables, when the command
    passes ``surface`` = :func:`~mechcli.core.optimize.problem.grid`'s
    ``(u, v, F, feasible)``), ``target.png`` (a function or path goal) and, with
    ``animate``, ``optimize.gif``.

    ``poses``: the optimum moved by the command, ``{"linkage": its (unbatched)
    linkage, "q": inputs (S,), "motion": its motion at q, "at": its motion at the
    goal's prescribed inputs or None, "rotary": the input is an angle, "size":
    the divisor of a slide output's deviation}``; ``goal``: the evaluator's goal.
    Returns warnings.
    """
    from mechcli.report import plotting
    warnings = []
    used = plotting.setup(lang)
    if used != lang:
        warnings.append("no CJK font installed: plot labels are in English")
    t = _T[used]
    title = book_title(spec.header.title)   # drawn through plotting.text below
    kind = spec.objective["kind"]
    if plots:
        if result.history:
            _convergence_png(spec, problem, result, outputs, t, title)
        if surface is not None:
            _surface_png(spec, problem, result, surface, outputs, t, title)
        if kind == "function" and "q" in details:
            rotary = poses.get("rotary", True) if poses else True
            _function_png(spec, details, goal, rotary, outputs, t, title)
        elif kind == "path":
            _path_png(spec, details, poses, outputs, t, title)
    if animate and poses is not None:
        _animate(spec, details, poses, outputs, t, title)
    return warnings
