"""Pictures of ``mechcli gear``: involute curve, gear drawing, pair in mesh,
rack-cutter generation (PNG) and its animation (GIF).

Imports matplotlib: import this module only when a picture is written.
"""

from __future__ import annotations

import math

import numpy as np

from mechcli.report import plotting, words
from mechcli.report.plotting import plt


def _circle(ax, r, style, label=None, lw=0.8, centre=(0.0, 0.0)):
    t = np.linspace(0, 2 * np.pi, 361)
    ax.plot(centre[0] + r * np.cos(t), centre[1] + r * np.sin(t), style, lw=lw, label=label)


def plot_involute(sol, spec, run, outputs):
    """involute.png: the involute of 【例 5-1】 (图 5-2) with its base circle."""
    lang = plotting.setup(run.lang)
    sc, u = spec.header.scale, spec.header.unit
    _, _, x, y = sol["curve"]
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(x / sc, y / sc, "b-", lw=1.5, label=words.say(lang, "gear_plots.involute"))
    _circle(ax, spec.problem.rb / sc, "c--", words.say(lang, "gear_plots.base"))
    ax.set_aspect("equal")
    ax.set_xlabel(plotting.axis_label("x", u))
    ax.set_ylabel(plotting.axis_label("y", u))
    # the legend in a row above the axes (it covers no curve), the title above it
    ax.set_title(words.say(lang, "gear_plots.involute_curve"), pad=16)
    plotting.legend_above(ax, fontsize=7)
    plotting.save_png(fig, outputs, "involute.png")


def _gear_axes(ax, g, sc, lang, centre=(0.0, 0.0), legend=True):
    for r, style, key in ((g.ra, "r:", "tip"), (g.r, "g-.", "reference"), (g.rb, "c--", "base"),
                          (g.rf, "b:", "root")):
        _circle(ax, r / sc, style, words.say(lang, f"gear_plots.{key}") if legend else None,
                centre=centre)


def plot_gear(sol, spec, run, outputs):
    """gear.png: the whole gear (【例 5-3】, 图 5-7) with its circles, and one tooth enlarged."""
    lang = plotting.setup(run.lang)
    sc, u = spec.header.scale, spec.header.unit
    g, out, tooth = sol["gear"], sol["outline"], sol["tooth"]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 6))
    for a in (ax, bx):
        a.plot(out.x / sc, out.y / sc, "k-", lw=1.0)
        _gear_axes(a, g, sc, lang, legend=a is ax)
        a.set_aspect("equal")
        a.set_xlabel(plotting.axis_label("x", u))
        a.set_ylabel(plotting.axis_label("y", u))
    plotting.legend_above(ax, fontsize=7, ncol=4)   # above the axes: it covers no tooth
    ax.set_title(words.say(lang, "gear_plots.gear", m=g.m / sc, z=g.z, x=g.x), pad=20)
    half = 1.6 * math.pi / g.z
    r0, r1 = g.rf / sc * 0.97, g.ra / sc * 1.02
    bx.set_xlim(-r1 * math.sin(half), r1 * math.sin(half))
    bx.set_ylim(r0 * math.cos(half), r1)
    _circle(bx, tooth.r_form / sc, "m-", lw=0.6)
    bx.set_title(words.say(lang, "gear_plots.tooth", r=tooth.r_form / sc, u=u), pad=16)
    plotting.save_png(fig, outputs, "gear.png")


def plot_pair(pair, spec, run, outputs):
    """pair.png: both gears in mesh at a' with pitch and base circles and the line of action.

    The pinion is centred at the origin with a tooth on +y; the pitch point is
    (0, r1'); the wheel's centre is (0, a') — (0, -a') for a ring gear.
    """
    from mechcli.core.gear.profile import gear_outline, generated_tooth, ring_outline

    lang = plotting.setup(run.lang)
    sc, u = spec.header.scale, spec.header.unit
    g1, g2 = pair.g1, pair.g2
    fig, ax = plt.subplots(figsize=(8, 8))
    o1 = gear_outline(generated_tooth(g1), 30)
    ax.fill(o1.x / sc, o1.y / sc, color="#c6dbef", zorder=0)
    ax.plot(o1.x / sc, o1.y / sc, "b-", lw=0.8)
    contact = np.zeros((0, 2))
    if g2.internal:
        o2, c2, rot = ring_outline(g2, 30), -pair.a_w, math.pi / g2.z
    else:
        from mechcli.core.gear.pair import mesh_positions
        mesh = mesh_positions(pair, [0.0])
        o2, c2, rot = gear_outline(generated_tooth(g2), 30), pair.a_w, float(mesh.phi2[0])
        contact = mesh.contact(0)
    c, s = math.cos(rot), math.sin(rot)
    x2, y2 = (c * o2.x - s * o2.y) / sc, (s * o2.x + c * o2.y + c2) / sc
    if g2.internal:   # ring material between the outline and an outer rim
        t = math.atan2(y2[0] - c2 / sc, x2[0]) - np.linspace(0, 2 * np.pi, 361)
        rim = (g2.rf + 2 * g2.m) / sc
        ax.fill(np.concatenate([x2, rim * np.cos(t)]),
                np.concatenate([y2, c2 / sc + rim * np.sin(t)]), color="#fcbba1", zorder=0)
    else:
        ax.fill(x2, y2, color="#fcbba1", zorder=0)
    ax.plot(x2, y2, "r-", lw=0.8)
    _circle(ax, pair.dw1 / 2 / sc, "g-.", words.say(lang, "gear_plots.pitch_w"))
    _circle(ax, pair.dw2 / 2 / sc, "g-.", centre=(0, c2 / sc))
    _circle(ax, g1.rb / sc, "c--", words.say(lang, "gear_plots.bases"))
    _circle(ax, g2.rb / sc, "c--", centre=(0, c2 / sc))
    # line of action N1N2 through the pitch point at alpha' to the common tangent
    aw = pair.alpha_w
    foot = np.array([math.sin(aw), math.cos(aw)])
    n1 = g1.rb * foot
    n2 = np.array([0.0, c2]) + g2.rb * (foot if g2.internal else -foot)
    ax.plot([n1[0] / sc, n2[0] / sc], [n1[1] / sc, n2[1] / sc], "m-", lw=1.0,
            label=words.say(lang, "gear_plots.line"))
    ax.plot([n1[0] / sc, n2[0] / sc], [n1[1] / sc, n2[1] / sc], "mo", ms=3)
    if contact.size:
        ax.plot(contact[:, 0] / sc, contact[:, 1] / sc, "ko", ms=5,
                label=words.say(lang, "gear_plots.contact"))
    rw1 = pair.dw1 / 2
    span = max(4 * g1.p, 1.2 * pair.line_of_action)
    ax.set_xlim(-span / sc, span / sc)
    ax.set_ylim((rw1 - span) / sc, (rw1 + span) / sc)
    ax.set_aspect("equal")
    plotting.legend_above(ax, fontsize=7, ncol=4)   # above the axes: it covers no tooth
    ax.set_xlabel(plotting.axis_label("x", u))
    ax.set_ylabel(plotting.axis_label("y", u))
    key = "gear_plots.pair_internal" if g2.internal else "gear_plots.pair"
    # above the legend's row (legend_above)
    ax.set_title(words.say(lang, key, z1=g1.z, z2=g2.z, a=pair.a_w / sc, u=u,
                           eps=pair.epsilon_alpha), pad=24)
    plotting.save_png(fig, outputs, "pair.png")


def animate_pair(pair, spec, run, outputs, frames_per_pitch=20, pitches=2):
    """pair.gif: an external pair turning through *pitches* base pitches.

    The pinion drives counter-clockwise; the points of contact (black) run
    along N1N2.  With epsilon_alpha < 1 some frames have none and say so.
    """
    from mechcli.core.gear.pair import mesh_positions
    from mechcli.core.gear.profile import gear_outline, generated_tooth

    lang = plotting.setup(run.lang)
    sc = spec.header.scale
    g1, g2 = pair.g1, pair.g2
    n = frames_per_pitch * pitches
    mesh = mesh_positions(pair, np.arange(n) * (2 * math.pi / g1.z) / frames_per_pitch)
    o1 = gear_outline(generated_tooth(g1), 30)
    o2 = gear_outline(generated_tooth(g2), 30)
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    rw1 = pair.dw1 / 2
    span = max(2.5 * g1.p, 0.8 * pair.contact_length)
    ax.set_xlim(-span / sc, span / sc)
    ax.set_ylim((rw1 - span) / sc, (rw1 + span) / sc)
    ax.set_aspect("equal")
    ax.plot([mesh.n1[0] / sc, mesh.n2[0] / sc], [mesh.n1[1] / sc, mesh.n2[1] / sc], "m-", lw=1)
    p1, = ax.fill([0], [0], facecolor="#c6dbef", edgecolor="b", lw=0.8)
    p2, = ax.fill([0], [0], facecolor="#fcbba1", edgecolor="r", lw=0.8)
    dots, = ax.plot([], [], "ko", ms=5)
    u = spec.header.unit
    ax.set_xlabel(plotting.axis_label("x", u))
    ax.set_ylabel(plotting.axis_label("y", u))
    title = ax.set_title(" ")
    label = plotting.readout(ax)
    plotting.tight(fig)
    frames = plotting.Frames(fig, [p1, p2, dots, title, label])
    for k in range(n):
        for poly, out, ang, centre in ((p1, o1, mesh.phi1[k], 0.0),
                                       (p2, o2, mesh.phi2[k], pair.a_w)):
            c, s = math.cos(ang), math.sin(ang)
            poly.set_xy(np.column_stack([c * out.x - s * out.y,
                                         s * out.x + c * out.y + centre]) / sc)
        pts = mesh.contact(k)
        dots.set_data(pts[:, 0] / sc, pts[:, 1] / sc)
        count = len(pts)
        title.set_text(words.say(lang, "gear_plots.in_contact", eps=pair.epsilon_alpha, n=count)
                       + (words.say(lang, "gear_plots.no_contact") if count == 0 else ""))
        title.set_color("red" if count == 0 else "black")
        label.set_text(f"φ₁ = {math.degrees(mesh.phi1[k] - mesh.phi1[0]):.1f}°")
        frames.grab()
    frames.save(outputs, "pair.gif", fps=10)


def _generation_axes(ax, tooth, phi, spec, lang, teeth, cutter=True):
    from mechcli.core.gear.generation import cutter_positions
    from mechcli.core.gear.profile import gear_outline

    sc, u = spec.header.scale, spec.header.unit
    g = tooth.gear
    if cutter:
        # the blank, every cutter position painted over it (the swept space), the outlines
        t = np.linspace(0, 2 * np.pi, 361)
        ax.fill(g.ra / sc * np.cos(t), g.ra / sc * np.sin(t), color="#9ecae1", zorder=0)
        bx, by = cutter_positions(g, phi, teeth, body=True)
        for k in range(bx.shape[0]):
            ax.fill(bx[k] / sc, by[k] / sc, color="white", zorder=0.5)
        cx, cy = cutter_positions(g, phi, teeth)
        ax.plot(cx.T / sc, cy.T / sc, "-", color="0.55", lw=0.4)
    out = gear_outline(tooth, spec.problem.points)
    rot = -math.pi - math.pi / g.z   # a tooth space to -y, where the cutter is
    c, s = math.cos(rot), math.sin(rot)
    ax.plot((c * out.x - s * out.y) / sc, (s * out.x + c * out.y) / sc, "k-", lw=1.3)
    _gear_axes(ax, g, sc, lang)
    if tooth.undercut:
        _circle(ax, tooth.r_form / sc, "m-", words.say(lang, "gear_plots.form"), lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel(plotting.axis_label("x", u))
    ax.set_ylabel(plotting.axis_label("y", u))
    # the verdict on a second line: the panels' titles stay apart
    key = "gear_plots.undercut" if g.undercut else "gear_plots.no_undercut"
    ax.set_title(words.say(lang, "gear_plots.cut", m=g.m / sc, z=g.z, alpha=math.degrees(g.alpha),
                           x=g.x) + "\n" + words.say(lang, key)
                 + (words.say(lang, "gear_plots.cuts", pct=100 * tooth.undercut_fraction)
                    if tooth.undercut else ""), fontsize=9)
    lim = g.ra * 1.25 / sc
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-(g.r + (g.x + 2) * g.m) / sc * 1.05, lim)
    ax.legend(loc="upper right", fontsize=7)


def plot_generation(sol, spec, run, outputs):
    """generation.png: cutter positions and the generated gear, one panel per shift (图 5-10)."""
    lang = plotting.setup(run.lang)
    teeth = sol["teeth"]
    phi = sol["plan"].phi
    fig, axes = plt.subplots(1, len(teeth), figsize=(6.5 * len(teeth), 7.5), squeeze=False)
    for ax, tooth in zip(axes[0], teeth):
        _generation_axes(ax, tooth, phi, spec, lang, spec.problem.cutter_teeth)
    fig.suptitle(words.say(lang, "gear_plots.generation"))
    plotting.save_png(fig, outputs, "generation.png")


def animate_generation(sol, spec, run, outputs):
    """generation.gif: the cutter (filled) rolling round the blank of the first shift.

    Every cutter position is painted over the blank, so the frames show the
    gear being cut; the last frame is the finished gear with the analytic
    outline (black) drawn on top.
    """
    from mechcli.core.gear.generation import cutter_positions

    lang = plotting.setup(run.lang)
    tooth = sol["teeth"][0]
    g, sc = tooth.gear, spec.header.scale
    phi = np.sort(sol["plan"].phi, kind="stable")
    cx, cy = cutter_positions(g, phi, spec.problem.cutter_teeth, body=True)
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    t = np.linspace(0, 2 * np.pi, 361)
    ax.fill(g.ra / sc * np.cos(t), g.ra / sc * np.sin(t), color="#9ecae1", zorder=1)
    _generation_axes(ax, tooth, phi[:0], spec, lang, spec.problem.cutter_teeth, cutter=False)
    for line in ax.lines:
        line.set_zorder(4)
    current, = ax.fill([0], [0], facecolor="none", edgecolor="r", lw=1.2, zorder=5)
    label = plotting.readout(ax)
    # the outline and circles stay on top of the cut: they move with the frames
    on_top = [line for line in ax.lines] + [ax.get_legend()]
    frames = plotting.Frames(fig, on_top + [current, label])
    for k in range(phi.size):
        cut, = ax.fill(cx[k] / sc, cy[k] / sc, color="white", zorder=2)
        frames.settle([cut])
        current.set_xy(np.column_stack([cx[k], cy[k]]) / sc)
        label.set_text(f"φ = {math.degrees(phi[k]):.1f}°")
        frames.grab()
    current.set_visible(False)
    frames.grab()
    frames.save(outputs, "generation.gif", fps=8)
