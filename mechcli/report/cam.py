"""``mechcli cam`` output: CSV, book-style report, JSON results, warnings.

Pictures are in :mod:`mechcli.report.cam_plots` (imported only when a PNG or
GIF is written).
"""

from __future__ import annotations

import math

import numpy as np

from mechcli.core.cam.geometry import RHO_CAP
from mechcli.core.cam.motion import LAW_ALIASES, POLYNOMIAL_LAWS, PolynomialLaw
from mechcli.report.files import Outputs
from mechcli.report.run import finish
from mechcli.report.table import Block, Report, book_title
from mechcli.report.words import say, table


def _f(x, nd=4):
    text = f"{x:.{nd}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def _rho_text(x, cap):
    """A radius of curvature; ``∞`` where the curve is straight (ρ capped in core)."""
    return ("-∞" if x < 0 else "∞") if abs(x) >= cap * (1 - 1e-12) else _f(x)


def _angle(delta):
    """A cam angle in degrees in [0, 360)."""
    d = math.degrees(delta) % 360.0
    return 0.0 if d > 360.0 - 1e-9 else d


def law_text(law, lang="en", width=60):
    """A segment's law as the report names it: ``(name, formula lines)``; the lines
    (``s/h = 3u² − 2u³``, broken between terms to at most *width* characters) are
    empty for a law that is not a polynomial."""
    if law is None:
        return "", []
    if isinstance(law, PolynomialLaw):
        name, poly = say(lang, "cam.polynomial"), law
    else:
        name = LAW_ALIASES.get(law, law)
        if name not in POLYNOMIAL_LAWS:
            return name, []
        poly = PolynomialLaw(POLYNOMIAL_LAWS[name])
    tokens = str(poly).split(" ")        # "3u²", "−", "2u³": a term, then (sign, term) pairs
    words = [tokens[0]] + [f"{a} {b}" for a, b in zip(tokens[1::2], tokens[2::2])]
    lines, cur = [], "s/h ="
    for word in words:
        if len(cur) + 1 + len(word) > width:
            lines.append(cur)
            cur = "     " + word
        else:
            cur += " " + word
    lines.append(cur)
    return name, lines


def _law_name(law):
    if law is None:
        return None
    return "polynomial" if isinstance(law, PolynomialLaw) else LAW_ALIASES.get(law, law)


def _impact_segments(program, delta):
    """Indices into ``program.segments`` of the segment before and after a jump at
    *delta* (the same index twice for a jump inside a segment)."""
    allp = program.pieces()
    k = min(range(len(allp)), key=lambda j: abs(allp[j][1] - delta))
    return allp[k - 1][0], allp[k][0]


def _jump_text(cs, imp):
    """The size of a jump: of ds/dδ (rigid) or d²s/dδ² (soft), in the table's units,
    right minus left."""
    u, unit = cs.header.scale, cs.header.unit
    y = "ψ" if cs.angular else "s"
    what = f"d{y}/dδ" if imp.kind == "rigid" else f"d²{y}/dδ²"
    if cs.angular:
        value, per = imp.jump, ("" if imp.kind == "rigid" else " 1/rad")
    else:
        value, per = imp.jump / u, f" {unit}/rad" + ("" if imp.kind == "rigid" else "²")
    return f"Δ({what}) = {value:+.4f}{per}"


def _impact_where(design, imp, lang):
    L = table(lang, "cam")
    segs = design.program.segments
    i, j = _impact_segments(design.program, imp.delta)

    def seg(k):
        law = _law_name(segs[k].law)
        return L[segs[k].kind] + (f" ({law})" if law else "")
    return f"{L['inside']} {seg(j)}" if i == j else f"{seg(i)} → {seg(j)}"


def _n_points(p):
    """Grid points per revolution of a profile (its jump samples not counted)."""
    return (len(p.delta) if p.grid is None else int(np.count_nonzero(p.grid))) - 1


def table_rows(p, every):
    """Indices of the report table's rows: every *every*-th grid sample, each preceded by
    the left limit of a jump at its angle (*p* a
    :class:`~mechcli.core.cam.geometry.CamProfile`)."""
    grid = np.arange(len(p.delta)) if p.grid is None else np.flatnonzero(p.grid)
    rows = []
    for i in grid[::every]:
        if p.left is not None and i > 0 and p.left[i - 1]:
            rows.append(i - 1)
        rows.append(int(i))
    return rows


def results_dict(cs, design):
    """Scalar results in the spec's units (angles in degrees) for ``--json``."""
    u = cs.header.scale
    fol, ch = design.follower, design.checks
    deg = math.degrees
    n = _n_points(design.profile)
    r = {"units": cs.header.unit, "r0": fol.r0 / u, "n_points": n, "step_deg": 360.0 / n}
    if cs.angular:
        r.update(psi_deg=deg(cs.stroke), phi0_deg=deg(fol.phi0), a=fol.a / u, l=fol.l / u)
    else:
        r.update(h=cs.stroke / u, e=abs(fol.e) / u,
                 offset_side="right" if fol.e > 0 else "left" if fol.e < 0 else "none")
    if fol.contact == "roller":
        r["rr"] = fol.rr / u
    for key, ext in (("alpha_rise_max", ch.alpha_rise), ("alpha_return_max", ch.alpha_return)):
        if ext is not None:
            r[f"{key}_deg"] = deg(ext.value)
            r[f"{key}_at_deg"] = _angle(ext.delta)
    if ch.rho_pitch_min is not None:
        r["rho_pitch_min"] = ch.rho_pitch_min.value / u
        r["rho_pitch_min_at_deg"] = _angle(ch.rho_pitch_min.delta)
    r["rho_work_min"] = ch.rho_work_min.value / u
    r["rho_work_min_at_deg"] = _angle(ch.rho_work_min.delta)
    if design.rr_max is not None:
        r["rr_max"] = design.rr_max / u
    r["undercut"] = ch.undercut
    r["distorted_at_deg"] = [round(_angle(d), 9) for d in ch.distorted]
    if ch.face_width_min is not None:
        r["face_width_min"] = ch.face_width_min / u
    p = design.profile
    scale = 1.0 if cs.angular else 1.0 / u
    r["ds_max"] = float(np.max(np.abs(p.s1))) * scale
    r["d2s_max"] = float(np.max(np.abs(p.s2))) * scale
    if cs.omega is not None:
        r["v_max"] = r["ds_max"] * cs.omega
        r["a_max"] = r["d2s_max"] * cs.omega ** 2
        r["j_max"] = float(np.max(np.abs(p.s3))) * scale * cs.omega ** 3
    rigid = [round(deg(i.delta), 9) for i in design.impacts if i.kind == "rigid"]
    soft = [round(deg(i.delta), 9) for i in design.impacts if i.kind == "soft"]
    r.update(n_rigid_impacts=len(rigid), n_soft_impacts=len(soft), rigid_impacts_deg=rigid,
             soft_impacts_deg=soft)
    segs = design.program.segments
    scale = 1.0 if cs.angular else 1.0 / u
    impacts = []
    for imp in design.impacts:
        i, j = _impact_segments(design.program, imp.delta)
        impacts.append({"at_deg": round(_angle(imp.delta), 9), "kind": imp.kind,
                        "jump": imp.jump * scale, "before": segs[i].kind,
                        "after": segs[j].kind, "inside_segment": i == j})
    r["impacts"] = impacts
    seg_out = []
    for s in segs:
        item = {"kind": s.kind, "start_deg": deg(s.start), "end_deg": deg(s.end),
                "law": _law_name(s.law)}
        if s.law is not None:
            item["lift"] = deg(abs(s.lift)) if cs.angular else abs(s.lift) / u
            law = s.law if isinstance(s.law, PolynomialLaw) else \
                POLYNOMIAL_LAWS.get(LAW_ALIASES.get(s.law, s.law))
            if law is not None:
                c = law.coefficients if isinstance(law, PolynomialLaw) else law
                item["coefficients"] = [float(x) for x in c]
        seg_out.append(item)
    r["segments"] = seg_out
    sz = design.sizing
    if sz is not None:
        r["r0_min"] = sz.r0_min / u
        if sz.best_side is not None:
            r["r0_min_other_side"] = sz.r0_min_other_side / u
            r["offset_side_best"] = "right" if sz.best_side > 0 else "left"
    return r


def warnings_for(cs, design, lang="en"):
    """One-line warnings: undercut, pressure angle over the limit, rigid impacts."""
    ch, fol = design.checks, design.follower
    u, unit = cs.header.scale, cs.header.unit
    out = []
    deg = math.degrees
    if ch.distorted:
        where = ", ".join(f"{deg(d):.4g}°" for d in ch.distorted)
        if fol.contact == "roller":
            out.append(say(lang, "cam.distorted_roller", where=where))
        else:
            out.append(say(lang, "cam.distorted_flat", where=where))
    rho_cut = ((fol.contact == "flat" and ch.rho_work_min.value <= 0)
               or (fol.contact == "roller" and ch.rho_pitch_min.value <= fol.rr))
    if rho_cut:
        where = deg(ch.rho_work_min.delta)
        if fol.contact == "flat":
            out.append(say(lang, "cam.cusp", where=f"{where:.4g}",
                           rho=f"{ch.rho_work_min.value / u:.4g}", unit=unit))
        else:
            out.append(say(lang, "cam.roller_undercut", rr=f"{fol.rr / u:g}", unit=unit,
                           rho=f"{ch.rho_pitch_min.value / u:.4g}", where=f"{where:.4g}"))
    for name, ext, lim in (("rise", ch.alpha_rise, cs.limits.alpha_rise),
                           ("return", ch.alpha_return, cs.limits.alpha_return)):
        # a sized cam meets [α] with equality: do not warn on round-off (1e-9 rad)
        if ext is not None and ext.value > lim + 1e-9:
            out.append(say(lang, f"cam.alpha_over_{name}", alpha=f"{deg(ext.value):.4f}",
                           limit=f"{deg(lim):g}"))
    rigid = [deg(i.delta) for i in design.impacts if i.kind == "rigid"]
    if rigid:
        where = ", ".join(f"{d:.4g}°" for d in rigid)
        out.append(say(lang, "cam.rigid_at", where=where))
    return out


def error_message(exc, cs):
    """The message of a cam core error (:class:`mechcli.core.cam.geometry.CamError`)
    in the spec's length unit, degrees and spec keys."""
    v, unit, u, deg = exc.values, cs.header.unit, cs.header.scale, math.degrees

    def length(key):
        return f"{v[key] / u:.6g} {unit}"

    reason = exc.reason
    if reason == "pitch_cusp":
        return (f"the pitch curve has a cusp near {deg(v['at']):.4g} deg (the follower point "
                "moves with the cam): no normal, no profile")
    if reason == "no_convex_pitch":
        return "the pitch curve has no convex part (check r0 and e)"
    if reason == "no_base_radius":
        return "no base radius between |a - l| and a + l meets the pressure-angle limit"
    if reason == "rounded_base_radius":
        return (f"the rounded base radius {length('r0')} is outside |a - l| < r0 < a + l "
                f"({v['lo'] / u:.6g} .. {length('hi')}); use a smaller round_up")
    if reason == "unbounded_base_radius":
        return (f"the limits do not bound the base radius from below (any r0 > "
                f"{length('floor')} meets them); give r0, or round_up, or stricter limits")
    if reason == "roller_too_large":
        return (f"the sized base radius {length('r0')} is not larger than the roller radius "
                f"{length('rr')}; give r0 or a smaller roller")
    if reason == "arm_past_centre_line":
        return (f"phi0 + psi = {deg(v['angle']):.6g} deg reaches 180 deg: the arm would pass "
                "the line through the pivot and the cam centre")
    if reason == "distorted":
        where = ", ".join(f"{deg(d):.4g}" for d in v["at"])
        return (f"the follower cannot reproduce the velocity jump at {where} deg: "
                + ("the roller rolls round the cam's sharp edge at the convex corner of the "
                   "pitch curve" if v["contact"] == "roller" else
                   "the flat face would need a cusp (r0 + s + s'' has a negative impulse)")
                + "; use a law without velocity jumps")
    if reason == "undercut":
        return (f"the working profile is undercut (cusp) near {deg(v['at']):.4g} deg: "
                + ("r0 + s + s'' <= 0" if v["contact"] == "flat" else
                   f"roller radius {length('rr')} >= pitch-curve radius of curvature "
                   f"{length('rho')}"))
    return str(exc)


def csv_columns(cs, design):
    """``(header, values)`` columns of ``cam.csv`` (spec units, degrees)."""
    p, unit, u = design.profile, cs.header.unit, cs.header.scale
    cols = [("delta_deg", np.degrees(p.delta))]
    if cs.angular:
        cols += [("psi_deg", np.degrees(p.s)), ("v_rad_rad", p.s1), ("a_rad_rad2", p.s2),
                 ("j_rad_rad3", p.s3)]
        if cs.omega is not None:
            w = cs.omega
            cols += [("omega_rad_s", p.s1 * w), ("alpha_rad_s2", p.s2 * w ** 2),
                     ("jerk_rad_s3", p.s3 * w ** 3)]
    else:
        cols += [(f"s_{unit}", p.s / u), (f"v_{unit}_rad", p.s1 / u),
                 (f"a_{unit}_rad2", p.s2 / u), (f"j_{unit}_rad3", p.s3 / u)]
        if cs.omega is not None:
            w = cs.omega
            cols += [(f"v_{unit}_s", p.s1 * w / u), (f"a_{unit}_s2", p.s2 * w ** 2 / u),
                     (f"j_{unit}_s3", p.s3 * w ** 3 / u)]
    if p.pitch is not None:
        cols += [(f"x_pitch_{unit}", p.pitch[0] / u), (f"y_pitch_{unit}", p.pitch[1] / u)]
    cols += [(f"x_work_{unit}", p.work[0] / u), (f"y_work_{unit}", p.work[1] / u),
             ("pressure_angle_deg", np.degrees(p.alpha))]
    if p.rho_pitch is not None:
        cols.append((f"rho_pitch_{unit}", p.rho_pitch / u))
    cols.append((f"rho_work_{unit}", p.rho_work / u))
    if p.roller_angle is not None:
        cols.append(("roller_angle_deg", np.degrees(p.roller_angle)))
    if p.face_offset is not None:
        cols.append((f"face_offset_{unit}", p.face_offset / u))
    return cols


def build_report(cs, design, lang="en"):
    """The book-style text report (table every ``table_step`` plus results)."""
    L = table(lang, "cam")
    unit, u = cs.header.unit, cs.header.scale
    p, fol, ch = design.profile, design.follower, design.checks
    deg = math.degrees
    rep = Report(book_title(cs.header.title))
    n = _n_points(p)
    every = max(1, int(round(cs.table_step / (2 * math.pi / n))))
    if cs.angular:
        heads = [L["delta"], L["psi"], L["vpsi"], L["apsi"]]
        motion = [np.degrees(p.s), p.s1, p.s2]
    else:
        heads = [L["delta"], L["s"], L["v"], L["a"]]
        motion = [p.s / u, p.s1 / u, p.s2 / u]
    heads += [L["alpha"]]
    geo = []
    if p.pitch is not None:
        heads += [L["x"], L["y"]]
        geo += [p.pitch[0] / u, p.pitch[1] / u]
    if fol.contact != "knife":
        heads += [L["xw"], L["yw"]]
        geo += [p.work[0] / u, p.work[1] / u]
    heads.append(L["rho"])
    cap = RHO_CAP * fol.r0 / u
    rows = []
    for i in table_rows(p, every):    # a jump: two rows (left limit first), unless they read alike
        row = ([_f(deg(p.delta[i]), 1)] + [_f(c[i]) for c in motion]
               + [_f(deg(p.alpha[i]))] + [_f(c[i]) for c in geo]
               + [_rho_text(p.rho_work[i] / u, cap)])
        if not rows or row != rows[-1]:
            rows.append(row)
    rep.blocks.append(Block(L["table"], [h.format(u=unit) for h in heads], rows))
    kv = []
    sz = design.sizing
    kv.append([L["r0_sized"] if cs.r0 is None else L["r0"], f"{fol.r0 / u:.4f} {unit}"])
    if cs.angular:
        kv.append([L["psi_s"], f"{deg(cs.stroke):.4f}°"])
        kv.append([L["phi0"], f"{deg(fol.phi0):.4f}°"])
    else:
        kv.append([L["h"], f"{cs.stroke / u:.4f} {unit}"])
    for key, ext in (("a_rise", ch.alpha_rise), ("a_ret", ch.alpha_return)):
        if ext is not None and fol.contact != "flat":
            kv.append([L[key], f"{deg(ext.value):.4f}°  ({L['at']} {_angle(ext.delta):.4f}°)"])
    if ch.rho_pitch_min is not None:
        kv.append([L["rho_p"], f"{ch.rho_pitch_min.value / u:.4f} {unit}  "
                   f"({L['at']} {_angle(ch.rho_pitch_min.delta):.4f}°)"])
    kv.append([L["rho_w"], f"{ch.rho_work_min.value / u:.4f} {unit}  "
               f"({L['at']} {_angle(ch.rho_work_min.delta):.4f}°)"])
    if design.rr_max is not None:
        kv.append([L["rr_max"], f"{design.rr_max / u:.4f} {unit}"])
    kv.append([L["undercut"], L["yes"] if ch.undercut else L["no"]])
    if ch.face_width_min is not None:
        kv.append([L["face"], f"{ch.face_width_min / u:.4f} {unit}"])
    if sz is not None:
        kv.append([L["r0_min_flat"] if fol.contact == "flat" else L["r0_min"],
                   f"{sz.r0_min / u:.4f} {unit}"])
        if sz.best_side is not None:
            kv.append([L["r0_other"], f"{sz.r0_min_other_side / u:.4f} {unit}"])
            kv.append([L["best_side"], L["right"] if sz.best_side > 0 else L["left"]])
    rep.blocks.append(Block(L["summary"], [], kv))
    prog = []
    for s in design.program.segments:
        text = f"δ = {_f(deg(s.start), 1)}° … {_f(deg(s.end), 1)}°"
        formula = []
        if s.law is not None:
            name, formula = law_text(s.law, lang)
            lift = (f"{deg(abs(s.lift)):.4f}°" if cs.angular else f"{abs(s.lift) / u:.4f} {unit}")
            text += f", {name}, {L['lift']} {lift}"
        # a polynomial's formula on its own lines (80 columns)
        prog += [[L[s.kind], text]] + [["", line] for line in formula]
    rep.blocks.append(Block(L["program"], [], prog))
    # two lines per jump (where, then its size) so that a line fits 80 columns
    imp = [row for i in design.impacts
           for row in ([L[i.kind], f"δ = {deg(i.delta):.4f}°, {_impact_where(design, i, lang)}"],
                       ["", _jump_text(cs, i)])]
    rep.blocks.append(Block(L["impacts"], [], imp or [[L["none"], ""]]))
    return rep


def cam_report(run, cs, design, extra=None):
    """Write cam.csv, the pictures and report.txt; print the table or JSON.
    *extra*: a function of the run's outputs that writes more files (the command's
    ``--export``) before the run is finished."""
    out = Outputs(run.out_dir, digits=run.digits)
    out.csv("cam.csv", csv_columns(cs, design))
    warnings = warnings_for(cs, design, run.lang)
    if extra is not None:
        extra(out)
    animate = cs.animate if run.animate is None else run.animate
    if (run.plot and cs.plot) or animate:
        from mechcli.report import cam_plots, plotting

        used = plotting.setup(run.lang)
        if used != run.lang:
            warnings.append("no CJK font installed: plot labels in English")
        if run.plot and cs.plot:
            cam_plots.plot_all(cs, design, out, used)
        if animate:
            cam_plots.animate(cs, design, out, used, progress=run.show_table)
    finish(run, "cam", build_report(cs, design, run.lang), results_dict(cs, design), out,
           warnings)
