"""Results, book-format report, CSV and ``linkage.toml`` of ``mechcli synth``.

Turns each case's :class:`~mechcli.core.synth.problems.SynthSolution` into the
``--json`` results (lengths in the spec's unit, angles in degrees, pivots as
``[x, y]`` lists), the tables the book prints (计算结果 1: A、D 坐标 …), the
positions CSV and a ``mechcli kin`` spec of the design.  Solves nothing.
"""

from __future__ import annotations

import math

from mechcli.report.kin import header
from mechcli.report.table import Block, Report, book_title
from mechcli.report.words import say, section

#: design value (core name, SI) -> (result key, how to show it): "deg" an angle,
#: "len" a length, "" a plain number
VALUES = {
    "l": ("l", ""), "m": ("m", ""), "n": ("n", ""),
    "alpha0": ("alpha0_deg", "deg"), "phi0": ("phi0_deg", "deg"),
    "theta": ("theta_deg", "deg"), "psi": ("psi_deg", "deg"), "K": ("K", ""),
    "gamma_1": ("gamma_1_deg", "deg"), "gamma_2": ("gamma_2_deg", "deg"),
    "gamma_ok": ("gamma_ok", ""),
    "method": ("method", ""), "iterations": ("iterations", ""), "tol": ("tol", ""),
    "residual": ("equation_residual", ""),
    "error_y_max": ("error_y_max", ""), "error_phi_max": ("error_phi_max_deg", "deg"),
    "alpha_m": ("alpha_m_deg", "deg"), "phi_m": ("phi_m_deg", "deg"),
    "alpha_max": ("alpha_max_deg", "deg"), "e_max": ("e_max", "len"), "R": ("R", "len"),
    "delta": ("delta_deg", "deg"), "residual_rms": ("residual_rms", ""),
    "limit_angle": ("limit_angle_deg", "deg"),
}
#: link lengths as the book names them
LINK_NAMES = {"four_bar": (("l1", "AB"), ("l2", "BC"), ("l3", "CD"), ("l4", "AD")),
              "slider_crank": (("l1", "AB"), ("l2", "BC"), ("e", "e"), ("H", "H")),
              "guide_bar": (("l1", "AB"), ("l4", "AC"))}
ZH_KINDS = {"two_positions": "连杆两位置设计", "three_positions": "连杆三位置设计",
            "moving_pivots": "已知固定铰链的连杆三位置设计",
            "coupler_poses": "按连杆三位置 (位移矩阵) 设计", "burmester": "Burmester 点",
            "function": "函数生成机构设计", "slider_function": "曲柄滑块函数生成",
            "rocker_slider": "摇杆滑块机构设计", "quick_return": "按行程速比系数 K 设计"}


def _xy(p, u):
    return [float(p[0]) / u, float(p[1]) / u]


def _value(kind, v, u):
    if isinstance(v, (bool, str)) or v is None:
        return v
    if kind == "deg":
        return math.degrees(float(v))
    if kind == "len":
        return float(v) / u
    if isinstance(v, int):
        return v
    return float(v)


def defect_text(d):
    """``branch:3`` (kind and 1-based position), ``order``: the JSON form of a defect."""
    return d.kind if d.position is None else f"{d.kind}:{d.position}"


def case_results(sol, u):
    """The results dict of one solved case, in the spec's unit *u* [m per unit]."""
    from mechcli.report import atlas
    if sol.kind in atlas.KINDS:
        return atlas.case_results(sol, u)
    r = {"kind": sol.kind}
    des, chk = sol.design, sol.check
    if des is None:     # the Burmester curves of four poses: no linkage
        curves = sol.extra
        r["curve_points"] = int(sum(len(c) for c in curves.centre_branches()))
        return r
    r["linkage"] = des.kind
    for key, val in des.lengths.items():
        r[key] = float(val) / u
    for name, p in des.pivots.items():
        r[name] = _xy(p, u)
    for key, val in des.values.items():
        if key in VALUES and not (key == "iterations" and des.values.get("method") == "matrix"):
            name, how = VALUES[key]
            r[name] = _value(how, val, u)
    if des.inputs is not None and len(des.inputs):
        r["theta1_deg"] = [math.degrees(float(q)) for q in des.inputs]
    if chk.driver != 1 or sol.kind in ("two_positions", "three_positions", "moving_pivots",
                                       "coupler_poses", "burmester"):
        r["driver"] = {1: "AB", 3: "CD"}[chk.driver]
    r["type"] = chk.grashof_type
    r["crank_turns"] = chk.input_turns
    if des.kind == "four_bar":
        r["cranks"] = list(chk.cranks)
    # None (JSON null) when not checked: the motion has a defect, so there is no path
    r["gamma_min_deg"] = None if chk.gamma_min is None else math.degrees(chk.gamma_min)
    r["residual_max"] = chk.residual_max
    r["residuals"] = [None if not math.isfinite(x) else float(x) for x in chk.residuals]
    r["direction"] = {1: "ccw", -1: "cw", 0: "reverses" if chk.start != chk.stop
                      else "none"}[chk.direction]
    r["defects"] = [defect_text(d) for d in chk.defects]
    r["defect_count"] = len(chk.defects)
    if sol.kind == "burmester" and sol.extra is not None:
        r["burmester_pairs"] = len(sol.extra)
    return r


def results(spec, solutions):
    """The ``--json`` results: one case's keys, or ``{"cases": [...]}`` for [[case]] specs."""
    u = spec.header.scale
    per = [case_results(s, u) for s in solutions]
    if spec.multi:
        return {"cases": per}
    return per[0]


def warnings(spec, solutions):
    """One line per design defect and per transmission angle below the allowed one."""
    import numpy as np
    out = []
    for i, (prob, sol) in enumerate(zip(spec.cases, solutions)):
        where = f"[{prob.path}] " if spec.multi else ""     # as the errors name a case
        from mechcli.report import atlas
        if sol.kind in atlas.KINDS:
            out += atlas.warnings(prob, sol)
            continue
        chk = sol.check
        if chk is None:
            continue
        for d in chk.defects[:3]:
            out.append(where + defect_message(d))
        if len(chk.defects) > 3:
            out.append(where + f"... and {len(chk.defects) - 3} more defects: "
                       + ", ".join(defect_text(d) for d in chk.defects[3:]))
        alt = sol.other_driver
        if alt is not None and not alt.defects:
            name = {1: "AB", 3: "CD"}[alt.driver]
            out.append(where + f"driven by {name} instead, the design has no defect: "
                       f'set driver = "{name}"')
        feasible = sol.design.values.get("error_feasible")
        if feasible is not None and not bool(np.all(feasible)):
            out.append(where + "the design cannot be assembled over part of [x0, xm]: the "
                       "structural error is shown where it can")
        ok = sol.design.values.get("gamma_ok")
        if ok is False:
            out.append(where + f"the smallest transmission angle "
                       f"{math.degrees(sol.design.values['gamma_min']):.2f} deg is below the "
                       f"allowed {math.degrees(prob.data['gamma_allowed']):.2f} deg")
    return out


def defect_message(d):
    """A defect in words (English: warnings go to stderr and JSON in English)."""
    if d.kind == "assembly":
        return (f"assembly defect: the designed linkage cannot be assembled in position "
                f"{d.position} at all")
    if d.kind == "branch":
        return (f"branch defect: position {d.position} is reached only in the other assembly "
                "mode (the linkage would have to be taken apart on the way)")
    if d.kind == "circuit" and d.position is None:
        return ("circuit defect: the crank cannot turn a full revolution: a dead point at "
                f"theta1 = {math.degrees(d.at):.4g} deg")
    if d.kind == "circuit":
        at = "" if d.at is None else f" (it stops at theta1 = {math.degrees(d.at):.4g} deg)"
        return (f"circuit defect: the crank cannot move to position {d.position} without "
                f"disassembly or a dead point{at}")
    return "order defect: no direction of the crank visits the positions in the given order"


# --------------------------------------------------------------------- the book's tables
def _f(x, nd=2):
    text = f"{x:.{nd}f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text  # no "-0.00"


def _blocks(prob, sol, u, unit, lang, prefix=""):
    from mechcli.report import atlas
    if sol.kind in atlas.KINDS:
        return atlas.blocks(prob, sol, u, unit, lang, prefix)
    blocks = []
    des, chk = sol.design, sol.check
    n = 1
    if des is None:
        c = sol.extra
        blocks.append(Block(prefix + say(lang, "synth.burmester"),
                            rows=[[say(lang, "synth.curve_points"),
                                   str(sum(len(b) for b in c.centre_branches()))]]))
        return blocks
    pivots = [k for k in ("A", "D", "C", "B1", "C1", "B2", "C2", "M1") if k in des.pivots]
    if pivots:
        head = say(lang, "synth.pivots", n=n, unit=unit, names=say(lang, "synth.sep").join(pivots))
        blocks.append(Block(prefix + head, ["", "x", "y"],
                            [[k, _f(des.pivots[k][0] / u), _f(des.pivots[k][1] / u)]
                             for k in pivots]))
        n += 1
    if "l" in des.values:
        rows = [[say(lang, "synth.rel_l"), _f(des.values["l"])],
                [say(lang, "synth.rel_m"), _f(des.values["m"])],
                [say(lang, "synth.rel_n"), _f(des.values["n"])]]
        blocks.append(Block(prefix + say(lang, "synth.relative", n=n), rows=rows))
        n += 1
    names = LINK_NAMES[des.kind]
    rows = [[label, _f(des.lengths[key] / u)] for key, label in names if key in des.lengths]
    blocks.append(Block(prefix + say(lang, "synth.lengths", n=n, unit=unit), rows=rows))
    n += 1
    extra = []
    v = des.values
    for key, angle in (("alpha0", True), ("phi0", True), ("theta", True), ("psi", True),
                       ("K", False), ("gamma_1", True), ("gamma_2", True),
                       ("error_phi_max", True), ("error_y_max", False), ("iterations", False)):
        if key in v and v[key] is not None \
                and not (key == "iterations" and v.get("method") == "matrix"):
            val = v[key]
            text = str(val) if isinstance(val, int) else \
                _f(math.degrees(val) if angle else val,
                   6 if key.startswith("error") else 2)
            extra.append([say(lang, f"synth.v_{key}"), text])
    if extra:
        blocks.append(Block(prefix + say(lang, "synth.figures", n=n), rows=extra))
        n += 1
    if des.inputs is not None and len(des.inputs) and des.points:
        heads = [say(lang, "synth.position"), header("θ1", "°")]
        cols = []
        for name, pts in des.points.items():
            heads += [f"x{name}", f"y{name}"]
            cols.append(pts)
        heads.append(say(lang, "synth.residual"))
        rows = []
        for i, q in enumerate(des.inputs):
            row = [str(i + 1), _f(math.degrees(q))]
            for pts in cols:
                row += [_f(pts[i].real / u), _f(pts[i].imag / u)]
            r = chk.residuals[i]
            row.append(f"{r:.1e}" if math.isfinite(r) else "—")
            rows.append(row)
        blocks.append(Block(prefix + say(lang, "synth.prescribed"), heads, rows))
    forms = section("grashof").get(f"type_{chk.grashof_type}")
    kind_text = (forms.get(lang) or forms["en"]) if forms else chk.grashof_type.replace("_", " ")
    if chk.cranks and des.kind == "four_bar":
        kind_text += say(lang, "synth.crank", links=', '.join(map(str, chk.cranks)))
    rows = [[say(lang, "synth.type"), kind_text],
            [say(lang, "synth.residual_max"),
             f"{chk.residual_max:.2e}"]]
    rows.append([say(lang, "synth.gamma_min"),
                 _f(math.degrees(chk.gamma_min)) if chk.gamma_min is not None
                 else say(lang, "synth.not_checked")])
    rows.append([say(lang, "synth.defects"),
                 ", ".join(say(lang, f"synth.defect_{d.kind}")
                           + ("" if d.position is None else f" @{d.position}")
                           for d in chk.defects) or say(lang, "synth.none")])
    blocks.append(Block(prefix + say(lang, "synth.check"),
                        rows=rows))
    return blocks


def build_report(spec, solutions, lang):
    """The book-format report of every case."""
    u, unit = spec.header.scale, spec.header.unit
    rep = Report(book_title(spec.header.title))
    for i, (prob, sol) in enumerate(zip(spec.cases, solutions)):
        prefix = f"[{i + 1}] " if spec.multi else ""
        rep.blocks += _blocks(prob, sol, u, unit, lang, prefix)
    return rep


# --------------------------------------------------------------------- CSV
def positions_columns(sol, u, lang="en"):
    """Columns of ``synth.csv``: each prescribed position, the crank angle, the
    prescribed points/angles/slides and the residual.  None without positions."""
    des, chk = sol.design, sol.check
    if des is None or des.inputs is None or not len(des.inputs):
        return None
    import numpy as np
    cols = [("position", np.arange(1, len(des.inputs) + 1)),
            ("theta1_deg", np.degrees(des.inputs))]
    for name, pts in des.points.items():
        pts = np.asarray(pts)
        cols += [(f"x{name}_{'u'}", pts.real / u), (f"y{name}_{'u'}", pts.imag / u)]
    for link, ang in des.angles.items():
        cols.append((f"theta{link}_deg", np.degrees(np.asarray(ang, dtype=float))))
    for name, s in des.slides.items():
        cols.append((f"s{name}_u", np.asarray(s, dtype=float) / u))
    res = np.asarray(chk.residuals, dtype=float)
    cols.append(("residual", np.where(np.isfinite(res), res, -1.0)))
    return cols


def unit_columns(cols, unit):
    """Spell the spec's unit in the column names (``xB_mm``)."""
    return [(h[:-2] + "_" + unit if h.endswith("_u") else h, c) for h, c in cols]


def error_columns(sol):
    """Columns of ``error.csv``: the structural error of a function generator."""
    v = sol.design.values if sol.design is not None else {}
    if "error_x" not in v:
        return None
    import numpy as np
    x, ey = np.asarray(v["error_x"], dtype=float), np.asarray(v["error_y"], dtype=float)
    ephi = np.asarray(v["error_phi"], dtype=float)
    ok = np.isfinite(ey) & np.isfinite(ephi)     # where the design assembles
    return [("x", x[ok]), ("error_y", ey[ok]), ("error_phi_deg", np.degrees(ephi[ok]))]


def burmester_columns(curves, u, unit):
    """Columns of ``burmester.csv``: centre-point and circle-point curves, branch by branch."""
    import numpy as np
    rows = []
    for b, (cen, cir) in enumerate(zip(curves.centre_branches(), curves.circle_branches())):
        rows.append(np.column_stack([np.full(len(cen), b + 1), cen.real / u, cen.imag / u,
                                     cir.real / u, cir.imag / u]))
    m = np.vstack(rows) if rows else np.zeros((0, 5))
    return [("branch", m[:, 0]), (f"x_centre_{unit}", m[:, 1]), (f"y_centre_{unit}", m[:, 2]),
            (f"x_circle_{unit}", m[:, 3]), (f"y_circle_{unit}", m[:, 4])]


# --------------------------------------------------------------------- linkage.toml
def _num(x):
    return repr(float(x)) if math.isfinite(float(x)) else "0.0"


def linkage_toml(sol, header, name):
    """A ``mechcli kin`` spec of the design: the general form of its elements and the
    crank turned over the checked motion (a full turn for a design from K)."""
    from mechcli.core.linkage.elements import RPR, RRP, RRR, Crank, Ground, PointOnLink
    des, chk = sol.design, sol.check
    u = header.scale
    linkage = chk.linkage if chk.linkage is not None else des.linkage
    lines = ['command = "kin"',
             f'title = {_toml_str("design of " + header.title)}',
             f'units = "{header.unit}"', "",
             f"# Written by `mechcli synth` from {name}: the designed linkage in the general",
             "# form, its crank turned over the checked motion.", "",
             "[mechanism]", 'type = "general"', f"frame = {linkage.frame}", "",
             "[mechanism.ground]"]
    for el in linkage.elements:
        if isinstance(el, Ground):
            lines.append(f"{el.name} = [{_num(el.x / u)}, {_num(el.y / u)}]")
    for el in linkage.elements:
        if isinstance(el, Crank):
            lines += ["", "[[mechanism.driver]]", 'type = "crank"', f"link = {el.link}",
                      f'pivot = "{el.pivot}"', f'point = "{el.point}"',
                      f"length = {_num(el.length / u)}"]
        elif isinstance(el, RRR):
            lines += ["", "[[mechanism.dyad]]", 'type = "RRR"', f'joint = "{el.joint}"',
                      f'points = ["{el.point_a}", "{el.point_b}"]',
                      f"links = [{el.link_a}, {el.link_b}]",
                      f"lengths = [{_num(el.length_a / u)}, {_num(el.length_b / u)}]",
                      f"branch = {int(el.branch)}"]
        elif isinstance(el, RRP):
            lines += ["", "[[mechanism.dyad]]", 'type = "RRP"', f'joint = "{el.joint}"',
                      f'point = "{el.point}"', f"link = {el.link}",
                      f"length = {_num(el.length / u)}", f"slider = {el.slider}",
                      f"guide_link = {el.guide_link}", f'guide_point = "{el.guide_point}"',
                      f"guide_angle = {_num(math.degrees(el.guide_angle))}",
                      f"offset = {_num(el.offset / u)}", f"branch = {int(el.branch)}"]
            if el.name:
                lines.append(f'name = "{el.name}"')
        elif isinstance(el, RPR):
            lines += ["", "[[mechanism.dyad]]", 'type = "RPR"', f'point = "{el.point}"',
                      f"block = {el.block}", f'pivot = "{el.pivot}"', f"guide = {el.guide}",
                      f"offset = {_num(el.offset / u)}", f"branch = {int(el.branch)}"]
            if el.name:
                lines.append(f'name = "{el.name}"')
        elif isinstance(el, PointOnLink):
            lines += ["", "[[mechanism.point]]", f'name = "{el.name}"', f"link = {el.link}",
                      f'from = "{el.origin}"', f"along = {_num(el.along / u)}",
                      f"normal = {_num(el.normal / u)}"]
    a, b = sorted((math.degrees(chk.start), math.degrees(chk.stop)))
    if b - a < 1e-6:
        a, b = a, a + 360.0
    omega = -1.0 if chk.direction == -1 else 1.0
    lines += ["", "[input]", f"omega1 = {omega:g}   # rad/s of the driving link "
              f"{'AB' if chk.driver == 1 else 'CD'}",
              f"start = {_num(a)}", f"stop = {_num(b)}", f"step = {_num((b - a) / 360)}"]
    if chk.defects:
        lines.append("partial = true   # the design has defects: skip what cannot assemble")
    lines += ["", "[output]", "table_step = " + _num((b - a) / 12)]
    return "\n".join(lines) + "\n"


def _toml_str(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


# --------------------------------------------------------------------- errors
def out_of_range(sol, lo, hi, spec, prob):
    """A message when a designed length or pivot coordinate lies outside [lo, hi] metres
    (the lengths every spec, and so linkage.toml, accepts), else None: such a design
    is degenerate (a pivot practically at infinity, a link of zero length)."""
    des = sol.design
    if des is None:
        return None
    u, unit = spec.header.scale, spec.header.unit
    for key, val in des.lengths.items():
        v = abs(float(val))
        if key.startswith("l") and not lo <= v <= hi:
            return (f"[{prob.path}]: the design has {key} = {v / u:.6g} {unit}: "
                    + ("a pivot practically at infinity (nearly collinear or parallel "
                       "positions?)" if v > hi else "a link of practically zero length")
                    + f"; lengths must lie between {lo:g} m and {hi:g} m")
    for name, (x, y) in des.pivots.items():
        if max(abs(x), abs(y)) > hi:
            return (f"[{prob.path}]: the design puts {name} at ({x / u:.6g}, {y / u:.6g}) "
                    f"{unit}: practically at infinity (coordinates within ±{hi:g} m)")
    return None



#: core reason -> the spec keys it is about, per kind (the first that the problem has)
_REASON_KEYS = {
    "coincident": ("poses", "B", "C"), "not_rigid": ("B", "C"),
    "collinear": ("B", "C", "poses"), "zero_link": ("A", "D", "B", "C", "poses"),
    "not_on_bisector": ("A", "D"),
    "parallel": ("A_line", "D_line", "pivot_line"), "not_on_circle": ("A", "D"),
    "at_infinity": ("poses",), "degenerate": ("poses",), "no_rotation": ("poses",),
    "domain": ("x0",), "flat": ("function", "table_y"), "swing": ("swing", "alpha_m"),
    "singular": ("theta1", "x", "s", "phi", "function"),
    "no_solution": ("theta3", "s", "function"),
    "no_motion": ("s",),
    "origins": ("alpha0", "phi0"), "points_given": ("x",),
    "K": ("K",), "pivot_line_misses": ("pivot_line",), "pivot_line_unusable": ("pivot_line",),
    "crank_range": ("crank",), "coupler_range": ("coupler",), "frame_range": ("frame",),
    "offset": ("e",), "limit_angle": ("limit_angle",), "pairs": ("pairs",),
    "too_few_points": ("x", "points"), "atlas_corrupt": ("atlas",),
    "atlas_foreign": ("atlas", "directory"), "atlas_empty": ("atlas",),
    "no_crank_rocker": ("A", "B", "C"), "not_crank_rocker": ("mark",),
    "angles_shape": ("angles",), "target_shape": ("x", "y"), "range": ("A", "B", "C"),
    "grid": ("grid_x", "grid_y"), "chunk": ("chunk",),
}


def _reason_key(reason, prob):
    """The first key of the problem's table that a core reason is about (None: none)."""
    for k in _REASON_KEYS.get(reason, ()):
        if k in prob.keys:
            return k
    return None


def error_message(exc, spec, prob):
    """The message of a synthesis core error: the table and key it is about, the
    reason in words, and the reachable range in the spec's units when there is one."""
    v, unit, u = exc.values, spec.header.unit, spec.header.scale
    reason = exc.reason
    key = _reason_key(reason, prob)
    where = f"[{prob.path}]" + (f" {key}" if key else "")
    text = str(exc).replace(" (the range is in the error's lo, hi)", "")
    if reason == "domain":
        why = str(exc).split(": ", 1)[-1]
        text = (f"x0 = {v['x0']:g} .. xm = {v['xm']:g} leaves the domain of the function "
                f"at x = {v['x']:g} ({why})")
    elif reason == "origins":
        text = {0: "5 precision points determine both origins: give neither alpha0 nor phi0",
                1: "4 precision points leave one origin to solve: give alpha0 or phi0, not "
                   "both",
                2: "least squares needs both origins alpha0 and phi0"}[v["wanted"]]
    elif reason == "points_given":
        text = "Chebyshev spacing computes the points: give n, not x"
    elif reason == "not_rigid":
        text += (": |BC| = " + ", ".join(f"{x / u:.6g}" for x in v["lengths"]) + f" {unit} "
                 f"differ by more than rigid_tol = {v['tol']:g} of the positions' size")
    elif reason == "K" and "hi" in v:
        if "theta_limit" in v:      # the offset slider-crank
            text = (f"no offset slider-crank has a limit-position angle of "
                    f"{math.degrees(v['theta_limit']):g} degrees or more (K >= {v['hi']:g})")
        elif "psi" in v:            # the crank-rocker of a swing: θ < 90° + ψ/2
            text += " (theta must stay below 90 degrees + swing/2)"
        text += f" (K must lie in ({v['lo']:g}, {v['hi']:.6g}))"
    elif reason in ("crank_range", "coupler_range", "frame_range", "offset") and "hi" in v:
        closed = "]" if reason == "offset" else ")"
        text += f": it must lie in ({v['lo'] / u:.6g}, {v['hi'] / u:.6g}{closed} {unit}"
    elif reason == "pivot_line_misses":
        text += (f": with these a, b the line meets it for c in [{v['lo'] / u:.6g}, "
                 f"{v['hi'] / u:.6g}] {unit}")
    elif reason == "swing" and "hi" in v:
        text = (f"the rocker's swing must lie strictly between {math.degrees(v['lo']):g} and "
                f"{math.degrees(v['hi']):g} degrees")
        text += (f" (it must lie between {math.degrees(v['lo']):g} and "
                 f"{math.degrees(v['hi']):g} deg)")
    return f"{where}: {text}"
