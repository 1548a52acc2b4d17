"""Results, book-format report and ``grashof.csv`` of ``mechcli grashof``.

Turns the :class:`~mechcli.core.grashof.analysis.GrashofSolution` of a spec
into results, tables, CSV text and pictures; solves nothing (from the core it
imports only result types and constants).  Lengths are shown in the spec's unit, angles
in degrees.  ``results`` dicts hold only finite numbers, strings, booleans, None and lists
of those.
"""

from __future__ import annotations

import math
import re

from mechcli.report.files import DEFAULT_DIGITS
from mechcli.report.table import Block, Report, book_title
from mechcli.report.words import CJK, say, section, table


def __getattr__(name):
    """``ZH_TYPES`` (synth's atlas): the linkage types' Chinese names, from the catalogue."""
    if name == "ZH_TYPES":
        return {k[len("type_"):]: v for k, v in table("zh", "grashof").items()
                if k.startswith("type_")}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _deg(x):
    return math.degrees(float(x))


def _f(x, nd=2):
    return f"{x:.{nd}f}"


def _g(x):
    return f"{x:.6g}"


def _type_text(lang, t):
    """A linkage type in words: ``crank rocker``, ``曲柄摇杆机构``."""
    if f"type_{t}" in section("grashof"):
        return say(lang, f"grashof.type_{t}")
    return t.replace("_", " ")


def interval_text(ranges):
    """``(0, 30] ∪ [70, 90]`` from a list of ``(lo, hi, lo_closed, hi_closed)`` in display units."""
    parts = []
    for lo, hi, lc, hc in ranges:
        if lo == hi:
            parts.append(f"{{{_g(lo)}}}")
        else:
            parts.append(f"{'[' if lc else '('}{_g(lo)}, {_g(hi)}{']' if hc else ')'}")
    return " ∪ ".join(parts) if parts else "∅"


# --------------------------------------------------------------------- four-bar
def fourbar_results(prob, an, inversions, ranges, scale):
    """Results dict of one four-bar (a :class:`~mechcli.core.grashof.chain.FourBarChain`)."""
    kl, m = an.klass, an.merit
    L = [x / scale for x in an.lengths]
    t = kl.type
    cranks = list(kl.cranks)
    if t.endswith("crank_rocker"):
        crank = cranks[0]
    elif cranks:
        crank = an.input if an.input in cranks else cranks[0]
    else:
        crank = None
    r = {
        "type": t, "crank": crank, "cranks": cranks, "grashof": kl.grashof,
        "change_point": kl.change_point,
        "longest": max(L), "shortest": min(L),
        "longest_link": kl.longest, "shortest_link": kl.shortest,
        "excess": kl.excess / scale,
        "frame": an.frame, "input": an.input, "coupler": an.coupler, "output": an.output,
        "input_turns": m.input_turns, "output_turns": m.output_turns,
    }
    if m.has_limits:
        r.update(theta_deg=_deg(m.theta), psi_deg=_deg(m.psi), K=m.K,
                 theta1_ext_deg=_deg(m.theta1_ext), theta1_fold_deg=_deg(m.theta1_fold),
                 theta3_ext_deg=_deg(m.theta3_ext), theta3_fold_deg=_deg(m.theta3_fold))
    if not m.input_turns:
        r.update(input_min_deg=_deg(m.input_lo), input_max_deg=_deg(m.input_hi))
    r.update(gamma_min_deg=_deg(m.gamma_min), gamma_min_at_deg=_deg(m.gamma_min_at),
             gamma_max_deg=_deg(m.gamma_max), gamma_max_at_deg=_deg(m.gamma_max_at))
    if m.has_gamma0:
        r["gamma_at_0_deg"] = _deg(m.gamma0)
    if m.has_gamma180:
        r["gamma_at_180_deg"] = _deg(m.gamma180)
    r["dead_points_output_driving_deg"] = [
        _deg(m.dead_theta3[j]) for j in (0, 1) if m.dead_output[j]]
    # the name without its unit, kept as an alias for one release
    r["dead_points_output_driving"] = r["dead_points_output_driving_deg"]
    for k, inv in enumerate(inversions, start=1):
        r[f"inversion_frame{k}"] = inv.type
        r[f"inversion_frame{k}_cranks"] = list(inv.cranks)
    for link, rs in ranges.items():
        by_type = {}
        for x in rs:
            by_type.setdefault(x.type, []).append(x)
            if x.type == "crank_rocker":
                by_type.setdefault(f"crank_rocker_crank{x.crank}", []).append(x)
        for name, xs in by_type.items():
            r[f"l{link}_{name}"] = interval_text(
                [(x.lo / scale, x.hi / scale, x.lo_closed, x.hi_closed) for x in xs])
    return r


def fourbar_report(title, lang, r, unit, ranges_present):
    rep = Report(title)
    # the two lines 【例 3-1】 prints, as printed ("最长杆 170.00")
    rows = [[say(lang, "grashof.longest_link"), _f(r["longest"])],
            [say(lang, "grashof.shortest_link"), _f(r["shortest"])]]
    rep.blocks.append(Block("", rows=rows))
    if r["crank"] is None:
        statement = say(lang, "grashof.statement", type=_type_text(lang, r["type"]))
    else:
        statement = say(lang, "grashof.statement_crank", type=_type_text(lang, r["type"]),
                        crank=str(r["crank"]))
    facts = [
        [say(lang, "grashof.grashof_condition"),
         say(lang, "common.yes" if r["grashof"] else "common.no")],
        [say(lang, "grashof.grashof_margin", unit=unit),
         _f(r["excess"])],
        [say(lang, "grashof.frame_input_output"),
         f"{r['frame']} / {r['input']} / {r['output']}"],
        [say(lang, "grashof.cranks"), ", ".join(map(str, r["cranks"])) or "-"],
    ]
    rep.blocks.append(Block(statement, rows=facts))
    merit = []
    if "theta_deg" in r:
        merit += [
            [say(lang, "grashof.limit_position_angle"), _f(r["theta_deg"])],
            [say(lang, "grashof.output_swing"), _f(r["psi_deg"])],
            [say(lang, "grashof.time_ratio_k"), f"{r['K']:.4f}"],
            [say(lang, "grashof.limit_positions_1"),
             f"{_f(r['theta1_ext_deg'])}, {_f(r['theta1_fold_deg'])}"],
            [say(lang, "grashof.limit_positions_3"),
             f"{_f(r['theta3_ext_deg'])}, {_f(r['theta3_fold_deg'])}"],
        ]
    if "input_min_deg" in r:
        lo, hi = r["input_min_deg"], r["input_max_deg"]
        if hi >= 180 - 1e-9:
            span = f"[{_f(lo)}, {_f(360 - lo)}]"
        elif lo <= 1e-9:
            span = f"[{_f(-hi)}, {_f(hi)}]"
        else:
            span = f"[{_f(lo)}, {_f(hi)}] | [{_f(-hi)}, {_f(-lo)}]"
        merit.append([say(lang, "grashof.input_range_1"), span])
    merit += [
        [say(lang, "grashof.gamma_min"),
         f"{_f(r['gamma_min_deg'])} (θ1 = {_f(r['gamma_min_at_deg'])})"],
        [say(lang, "grashof.gamma_max"),
         f"{_f(r['gamma_max_deg'])} (θ1 = {_f(r['gamma_max_at_deg'])})"],
    ]
    if "gamma_at_0_deg" in r:
        merit.append([say(lang, "grashof.gamma1_at_0"),
                      _f(r["gamma_at_0_deg"])])
    if "gamma_at_180_deg" in r:
        merit.append([say(lang, "grashof.gamma2_at_180"),
                      _f(r["gamma_at_180_deg"])])
    dead = r["dead_points_output_driving"]
    merit.append([say(lang, "grashof.dead_points_output"),
                  ", ".join(_f(x) for x in dead) if dead else say(lang, "grashof.none")])
    rep.blocks.append(Block(say(lang, "grashof.figures_of_merit"), rows=merit))
    inv_rows = [[str(k), _type_text(lang, r[f"inversion_frame{k}"]),
                 ", ".join(map(str, r[f"inversion_frame{k}_cranks"])) or "-"]
                for k in (1, 2, 3, 4)]
    rep.blocks.append(Block(say(lang, "grashof.inversions"),
                            headers=[say(lang, "grashof.frame"), say(lang, "grashof.type"),
                                     say(lang, "grashof.cranks")], rows=inv_rows))
    if ranges_present:
        rows = []
        for k, v in r.items():
            if not (k[:1] == "l" and k[1:2].isdigit() and "_" in k):
                continue
            link, name = k.split("_", 1)
            m = re.fullmatch(r"(.+)_crank(\d+)", name)   # crank_rocker_crank1, not double_crank
            base, crank = (m.group(1), m.group(2)) if m else (name, "")
            text = _type_text(lang, base)
            if crank:
                text += say(lang, "grashof.crank", crank=crank)
            rows.append([link, text, v])
        rows.sort(key=lambda row: (row[0], row[1]))
        rep.blocks.append(Block(say(lang, "grashof.length_ranges"),
                                headers=[say(lang, "grashof.link"), say(lang, "grashof.type"),
                                         say(lang, "grashof.range", unit=unit)],
                                rows=rows))
    return rep


# ------------------------------------------------------------------- batch CSV
CSV_HEADER = ("l1,l2,l3,l4,frame,input,type,crank,grashof,theta_deg,psi_deg,K,"
              "gamma_min_deg,gamma_min_at_deg,gamma_max_deg")


def fourbar_csv(an, scale, closes_mask=None, digits=DEFAULT_DIGITS):
    """``grashof.csv`` text, one row per length set (empty cells: does not exist);
    numbers with *digits* significant digits (``--digits``)."""
    import numpy as np

    kl, m = an.klass, an.merit
    n = an.lengths.shape[0]
    ok = np.ones(n, dtype=bool) if closes_mask is None else closes_mask
    L = an.lengths / scale
    types = np.array(kl.code)
    from mechcli.core.grashof.fourbar import TYPES
    tnames = np.array(TYPES + ("cannot_close",))
    types = np.where(ok, types, len(TYPES))
    cm = kl.crank_mask
    rows_i = np.arange(n)
    in_crank = cm[rows_i, an.input - 1]
    first = np.argmax(cm, axis=1) + 1
    crank = np.where(in_crank, an.input, np.where(cm.any(axis=1), first, 0))
    deg = 180.0 / np.pi
    lim = m.has_limits & ok

    def col(x, mask, fmt=f"{{:.{digits}g}}"):
        f = fmt.format
        return [f(v) if k else "" for v, k in zip(x.tolist(), np.broadcast_to(mask, (n,)).tolist())]

    always = np.ones(n, dtype=bool)
    cols = [col(L[:, k], always) for k in range(4)]
    cols += [list(map(str, an.frame.tolist())), list(map(str, an.input.tolist())),
             tnames[types].tolist(), col(crank, (crank > 0) & ok, "{:d}"),
             [("true" if g else "false") if k else "" for g, k in
              zip(kl.grashof.tolist(), ok.tolist())],
             col(m.theta * deg, lim), col(m.psi * deg, lim), col(m.K, lim),
             col(m.gamma_min * deg, ok), col(m.gamma_min_at * deg, ok),
             col(m.gamma_max * deg, ok)]
    return CSV_HEADER + "\n" + "\n".join(map(",".join, zip(*cols))) + "\n"


def chain_csv(an, scale, digits=DEFAULT_DIGITS):
    """``grashof.csv`` text of one four-bar (a :class:`~mechcli.core.grashof.chain.FourBarChain`):
    the row :func:`fourbar_csv` writes for it, made without numpy."""
    kl, m = an.klass, an.merit
    num = f"{{:.{digits}g}}".format
    deg = 180.0 / math.pi
    crank = an.input if an.input in kl.cranks else (kl.cranks[0] if kl.cranks else 0)

    def lim(x):
        return num(x) if m.has_limits else ""

    row = [num(x / scale) for x in an.lengths]
    row += [str(an.frame), str(an.input), kl.type, f"{crank:d}" if crank > 0 else "",
            "true" if kl.grashof else "false", lim(m.theta * deg), lim(m.psi * deg), lim(m.K),
            num(m.gamma_min * deg), num(m.gamma_min_at * deg), num(m.gamma_max * deg)]
    return CSV_HEADER + "\n" + ",".join(row) + "\n"


def batch_results(an, closes_mask):
    import numpy as np

    from mechcli.core.grashof.fourbar import TYPES
    counts = {}
    codes = an.klass.code[closes_mask]
    for i, name in enumerate(TYPES):
        c = int(np.count_nonzero(codes == i))
        if c:
            counts[name] = c
    n_bad = int(np.count_nonzero(~closes_mask))
    res = {"sets": int(an.lengths.shape[0]), "counts": counts, "cannot_close": n_bad}
    return res


def batch_report(title, lang, res, unit=None):
    """The report of a ``--batch`` run; with *unit*, a note on the unit of the lengths
    ``l1…l4`` of ``grashof.csv`` (named as the input's columns, see docs/grashof.md)."""
    rep = Report(title)
    if unit:
        rep.notes.append(say(lang, "grashof.csv_note", unit=unit))
    rows = [[_type_text(lang, k), str(v)] for k, v in res["counts"].items()]
    if res["cannot_close"]:
        rows.append([say(lang, "grashof.cannot_close"), str(res["cannot_close"])])
    rep.blocks.append(Block(say(lang, "grashof.length_sets", n=res['sets']),
                            headers=[say(lang, "grashof.type"), say(lang, "grashof.count")],
                            rows=rows))
    return rep


# -------------------------------------------------------------- slider, guide
def slider_results(sc, scale):
    if not sc.crank_exists:
        return {"type": "rocker_slider", "crank": None, "crank_exists": False,
                "boundary": False}
    return {"type": "crank_slider_boundary" if sc.boundary else "crank_slider", "crank": 1,
            "crank_exists": True, "boundary": sc.boundary, "stroke": sc.stroke / scale,
            "theta_deg": _deg(sc.theta), "K": sc.K,
            "pressure_angle_max_deg": _deg(sc.alpha_max),
            "pressure_angle_max_at_deg": _deg(sc.alpha_max_at),
            "theta1_ext_deg": _deg(sc.theta1_ext), "theta1_fold_deg": _deg(sc.theta1_fold),
            "x_ext": sc.x_ext / scale, "x_fold": sc.x_fold / scale,
            "dead_points_slider_driving": [sc.x_ext / scale, sc.x_fold / scale]}


def slider_report(title, lang, r, unit):
    rep = Report(title)
    rows = [[say(lang, "grashof.crank_exists"),
             say(lang, "common.yes" if r["crank_exists"] else "common.no")]]
    if r["crank_exists"]:
        rows += [
            [say(lang, "grashof.stroke_h", unit=unit), _f(r["stroke"])],
            [say(lang, "grashof.limit_position_angle"), _f(r["theta_deg"])],
            [say(lang, "grashof.time_ratio_k"), f"{r['K']:.4f}"],
            [say(lang, "grashof.alpha_max_slider"),
             f"{_f(r['pressure_angle_max_deg'])} (θ1 = {_f(r['pressure_angle_max_at_deg'])})"],
            [say(lang, "grashof.dead_points_slider", unit=unit),
             ", ".join(_f(x) for x in r["dead_points_slider_driving"])],
        ]
    rep.blocks.append(Block(_type_text(lang, r["type"]), rows=rows))
    if r.get("boundary"):
        rep.notes.append(say(lang, "grashof.coupler_normal"))
    return rep


def guide_results(gb, scale):
    r = {"type": gb.kind, "crank": 1 if gb.kind != "no_crank" else None}
    if gb.kind in ("oscillating", "boundary") and gb.theta > 0:
        r.update(theta_deg=_deg(gb.theta), psi_deg=_deg(gb.psi))
        if gb.K > 0:
            r["K"] = gb.K
    if gb.kind != "no_crank":
        r.update(gamma_min_deg=_deg(gb.gamma_min), gamma_max_deg=_deg(gb.gamma_max))
    return r


def guide_report(title, lang, r):
    rep = Report(title)
    rows = []
    if "theta_deg" in r:
        rows += [[say(lang, "grashof.theta_psi"), _f(r["theta_deg"])],
                 [say(lang, "grashof.time_ratio_k"),
                  f"{r['K']:.4f}" if "K" in r else "∞"]]
    if "gamma_min_deg" in r:
        rows += [[say(lang, "grashof.gamma_min_short"), _f(r["gamma_min_deg"])],
                 [say(lang, "grashof.gamma_max_short"), _f(r["gamma_max_deg"])]]
    rep.blocks.append(Block(_type_text(lang, r["type"]), rows=rows))
    return rep


# --------------------------------------------------------------- five-bar etc.
def fivebar_results(prob, kl, scale):
    import numpy as np

    L = np.asarray(prob.lengths) / scale
    return {"class": "I" if kl.klass[0] == 1 else "II", "class_boundary": bool(kl.boundary[0]),
            "type": kl.types[0], "cranks": kl.cranks(0), "frame": prob.frame,
            "inputs": list(prob.inputs), "shortest": [int(kl.short1[0]), int(kl.short2[0])],
            "longest": float(L.max()), "excess": float(kl.excess[0] / scale),
            "inputs_independent": bool(kl.inputs_independent[0])}


def fivebar_report(title, lang, r):
    rep = Report(title)
    rows = [
        [say(lang, "grashof.fivebar_class"),
         say(lang, f"grashof.class_{r['class']}")],
        [say(lang, "grashof.frame_inputs"),
         f"{r['frame']} / {r['inputs'][0]}, {r['inputs'][1]}"],
        [say(lang, "grashof.shortest_links"),
         f"{r['shortest'][0]}, {r['shortest'][1]}"],
        [say(lang, "grashof.cranks"), ", ".join(map(str, r["cranks"])) or "-"],
        [say(lang, "grashof.inputs_independent"),
         say(lang, "common.yes" if r["inputs_independent"] else "common.no")],
    ]
    rep.blocks.append(Block(_type_text(lang, r["type"]), rows=rows))
    return rep


def rrrrp_results(rc, scale):
    r = {"crank": 1 if rc.crank_any_fold else None, "crank_any_fold": rc.crank_any_fold,
         "boundary": rc.boundary, "slider_lo": rc.slider_lo / scale,
         "slider_hi": rc.slider_hi / scale}
    if rc.has_inner:
        r["slider_inner_hi"] = rc.slider_inner_hi / scale
    return r


def rrrrp_report(title, lang, r, unit):
    rep = Report(title)
    rows = [[say(lang, "grashof.rrrrp_condition"),
             say(lang, "common.yes" if r["crank_any_fold"] else "common.no")],
            [say(lang, "grashof.slider_positions_crank", unit=unit),
             f"±[{_f(r['slider_lo'])}, {_f(r['slider_hi'])}]" if r["slider_hi"] > 0 else "-"]]
    if "slider_inner_hi" in r:
        rows.append([say(lang, "grashof.slider_inside_crank_circle", unit=unit),
                     f"[{_f(-r['slider_inner_hi'])}, {_f(r['slider_inner_hi'])}]"])
    rep.blocks.append(Block("RRRRP", rows=rows))
    return rep


def mobility_results(mob):
    r = {"F": mob.F, "n": mob.n, "P_L": mob.P_L, "P_H": mob.P_H,
         "local_dof": mob.local_dof, "redundant": mob.redundant,
         "moving_links": list(mob.moving), "frame": mob.frame,
         "joints": [{"name": j.name, "kind": j.kind, "links": list(j.links),
                     "pairs": j.pairs} for j in mob.joints]}
    if mob.structure is not None:
        from mechcli.report.structure import structure_results
        r.update(structure_results(mob.structure))
    return r


def mobility_report(title, lang, mob):
    rep = Report(title)
    rows = []
    for j in mob.joints:
        kind = {"R": say(lang, "grashof.revolute"), "P": say(lang, "grashof.prismatic"),
                "H": say(lang, "grashof.higher_pair")}[j.kind]
        why = ""
        if j.kind == "R" and len(j.links) > 2:
            why = say(lang, "grashof.compound_hinge_of_links", n=len(j.links))
        rows.append([j.name or "-", kind, ", ".join(map(str, j.links)), str(j.pairs), why])
    rep.blocks.append(Block(say(lang, "grashof.pairs"),
                            headers=[say(lang, "grashof.joint"), say(lang, "grashof.kind"),
                                     say(lang, "grashof.links"), say(lang, "grashof.pair_count"),
                                     ""], rows=rows))
    expl = [
        [say(lang, "grashof.moving_links_n"),
         f"{mob.n} ({', '.join(map(str, mob.moving))}; frame {mob.frame})"],
        [say(lang, "grashof.lower_pairs"), str(mob.P_L)],
        [say(lang, "grashof.higher_pairs"), str(mob.P_H)],
        [say(lang, "grashof.local_dof"), str(mob.local_dof)],
        [say(lang, "grashof.redundant"), str(mob.redundant)],
        ["F", f"3×{mob.n} − 2×{mob.P_L} − {mob.P_H} − {mob.local_dof} + {mob.redundant}"
              f" = {mob.F}"],
    ]
    rep.blocks.append(Block(say(lang, "grashof.mobility"), rows=expl))
    if mob.structure is not None:
        from mechcli.report.structure import structure_block
        rep.blocks.append(structure_block(lang, mob.structure, mob.frame))
    return rep


# ------------------------------------------------------- transmission curve
def curve_outputs(curve, step, lang):
    """``transmission.csv`` columns and a report block of γ every 30° (or every step)."""
    import numpy as np

    ok = curve.feasible
    cols = [("theta1_deg", np.degrees(curve.theta1[ok])),
            ("gamma_deg", np.degrees(curve.gamma[ok]))]
    every = max(1, int(round(np.radians(30.0) / step)))
    rows = [[_f(np.degrees(t)), _f(np.degrees(g)) if k else "-"]
            for t, g, k in zip(curve.theta1[::every], curve.gamma[::every], ok[::every])]
    block = Block(say(lang, "grashof.gamma_curve"),
                  headers=[say(lang, "grashof.input_angle"),
                           say(lang, "grashof.gamma")],
                  rows=rows)
    return cols, block


def write_curve_png(curve, outputs, lang, title):
    """``transmission.png`` (imports matplotlib: call only when a picture is wanted)."""
    import numpy as np

    from mechcli.report import plotting

    used = plotting.setup(lang)
    fig, ax = plotting.plt.subplots(figsize=(7, 4))
    th = np.degrees(curve.theta1)
    g = np.where(curve.feasible, np.degrees(curve.gamma), np.nan)
    ax.plot(th, g)
    ax.set_xlabel(say(used, "grashof.plot_input_angle"))
    ax.set_ylabel(say(used, "grashof.plot_gamma"))
    if used in CJK or title.isascii():   # no tofu boxes without a CJK font
        ax.set_title(title)
    ax.set_xlim(th.min(), th.max())
    plotting.save_png(fig, outputs, "transmission.png")
    return [] if used == lang else ["no CJK font installed: plot labels in English"]


def write_limits_png(r, scale_unit, outputs, lang, title):
    """``limits.png``: the four-bar at its two limit positions (imports matplotlib).

    Parameters
    ----------
    r : dict
        Four-bar results (spec units, degrees) with the limit positions.
    scale_unit : tuple of (lengths a, b, c, d in spec units, unit name)
    """
    import numpy as np

    from mechcli.report import plotting

    (a, b, c, d), unit = scale_unit
    used = plotting.setup(lang)
    fig, ax = plotting.plt.subplots(figsize=(7, 5))
    A, D = 0j, complex(d, 0)
    for name, style in (("ext", "-"), ("fold", "--")):
        t1 = np.radians(r[f"theta1_{name}_deg"])
        t3 = np.radians(r[f"theta3_{name}_deg"])
        B = a * np.exp(1j * t1)
        C = D + c * np.exp(1j * t3)
        pts = np.array([A, B, C, D])
        label = say(used, f"grashof.limit_{name}")
        ax.plot(pts.real, pts.imag, style, marker="o", label=label)
        ax.annotate("C1" if name == "ext" else "C2", (C.real, C.imag),
                    textcoords="offset points", xytext=(4, 4))
    ax.plot([0, d], [0, 0], "k-", lw=3)
    ax.annotate("A", (0, 0), textcoords="offset points", xytext=(-10, -12))
    ax.annotate("D", (d, 0), textcoords="offset points", xytext=(4, -12))
    ax.set_aspect("equal")
    ax.set_xlabel(plotting.axis_label("x", unit))
    ax.set_ylabel(plotting.axis_label("y", unit))
    ax.legend(title=f"θ = {r['theta_deg']:.2f}°, ψ = {r['psi_deg']:.2f}°, K = {r['K']:.4f}")
    if used in CJK or title.isascii():
        ax.set_title(title)
    plotting.save_png(fig, outputs, "limits.png")
    return [] if used == lang else ["no CJK font installed: plot labels in English"]


def driven_lengths(spec, solution):
    """((a, b, c, d) in spec units, unit) of a solved four-bar: input, coupler, output, frame."""
    m, sc = solution.result.merit, spec.header.scale
    return tuple(x / sc for x in (m.a, m.b, m.c, m.d)), spec.header.unit


def closure_message(exc, unit):
    """The user's text of a :class:`~mechcli.core.grashof.chain.ClosureError` (its numbers
    are in the spec's unit, see :func:`~mechcli.core.grashof.analysis.solve_grashof`)."""
    u = f" {unit}" if unit else ""
    length, limit = f"{exc.length:.6g}{u}", f"{exc.limit:.6g}{u}"
    if exc.chain == "slider-crank":
        return (f"the slider-crank cannot close: offset |e| = {length} is not shorter than "
                f"crank + coupler = {limit}")
    if exc.chain == "guide-bar":
        return (f"the guide-bar cannot close: guide offset {length} is not shorter than "
                f"crank + frame = {limit} (the guide never reaches B)")
    if exc.chain == "RRRRP":
        return (f"the RRRRP chain cannot reach its slider path: offset {length} >= "
                f"l1 + l2 + l3 = {limit}")
    return (f"the chain cannot close: link {exc.link} ({length}) is not shorter than the sum "
            f"of the other links ({limit})"
            + (f" (length set {exc.set_index})" if exc.set_index is not None else ""))


# ------------------------------------------------------------------ dispatch
def present(spec, solution, lang, digits=DEFAULT_DIGITS):
    """Results, report and ``grashof.csv`` of a solved
    :class:`~mechcli.spec.grashof.GrashofSpec`.

    Returns
    -------
    results : dict
    report : Report
    csv_text : str or None
        ``grashof.csv`` content (four-bar only), numbers with *digits* significant digits.
    warnings : list of str
    """
    r, rep, csv_text, warnings = _present(spec, solution, lang, digits)
    if solution.curve is not None:
        rep.blocks.append(curve_outputs(solution.curve, spec.problem.curve_step, lang)[1])
    rep.title = book_title(rep.title)
    return with_units(r, spec.header.unit, spec.kind), rep, csv_text, warnings


#: results that are lengths in the spec's unit, by kind: their names carry the unit
#: (``longest`` -> ``longest_mm``); the bare names stay as aliases for one release.
#: A five-bar's ``shortest`` is two link numbers, not a length.
LENGTH_RESULTS = {
    "fourbar": frozenset(("longest", "shortest", "excess")),
    "slider_crank": frozenset(("stroke", "x_ext", "x_fold", "dead_points_slider_driving")),
    "fivebar": frozenset(("longest", "excess")),
    "rrrrp": frozenset(("slider_lo", "slider_hi", "slider_inner_hi")),
}
#: the length ranges of a four-bar's link for a type: ``l1_crank_rocker`` (interval text)
_RANGE = re.compile(r"l\d+_\w+")


def unit_name(key, unit, kind):
    """*key* with the unit of a length result of *kind* (``excess`` -> ``excess_mm``), else
    *key*."""
    lengths = LENGTH_RESULTS.get(kind, ())
    if key in lengths or (kind == "fourbar" and _RANGE.fullmatch(key)):
        return f"{key}_{unit}"
    return key


def with_units(results, unit, kind):
    """*results* with every length under its name with the unit, in order, then the old
    bare names (``longest``, ``stroke``, ``l1_crank_rocker`` …) as aliases of the same
    values, kept for one release."""
    named, aliases = {}, {}
    for key, value in results.items():
        new = unit_name(key, unit, kind)
        if new != key:
            aliases[key] = value
        named[new] = value
    return {**named, **aliases}


def _present(spec, sol, lang, digits=DEFAULT_DIGITS):
    p, unit, scale, title = spec.problem, spec.header.unit, spec.header.scale, spec.header.title
    res = sol.result
    warnings = []
    if spec.kind == "fourbar":
        r = fourbar_results(p, res, sol.inversions, sol.ranges, scale)
        if r["change_point"]:
            warnings.append("s + l = p + q: a change-point linkage (it can fold flat; "
                            "the motion branch is undetermined there)")
        return (r, fourbar_report(title, lang, r, unit, bool(sol.ranges)),
                chain_csv(res, scale, digits=digits), warnings)
    if spec.kind == "slider_crank":   # solved in the spec's unit
        r = slider_results(res, 1.0)
        if res.boundary:
            warnings.append("a + |e| = b: the crank just exists (pressure angle reaches 90°)")
        return r, slider_report(title, lang, r, unit), None, warnings
    if spec.kind == "guide_bar":
        r = guide_results(res, 1.0)
        return r, guide_report(title, lang, r), None, warnings
    if spec.kind == "fivebar":
        r = fivebar_results(p, res, scale)
        return r, fivebar_report(title, lang, r), None, warnings
    if spec.kind == "rrrrp":
        r = rrrrp_results(res, 1.0)
        return r, rrrrp_report(title, lang, r, unit), None, warnings
    return mobility_results(res), mobility_report(title, lang, res), None, warnings
