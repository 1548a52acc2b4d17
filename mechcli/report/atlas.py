"""Results, tables, CSV and ``linkage-N.toml`` of the atlas kinds of ``mechcli synth``
(``atlas_page``, ``type_chart``, ``atlas_build``, ``path``).  Solves nothing.

Ratios (A, B, C, grid coordinates) are in crank lengths; a path's coordinates in the
spec's unit.
"""

from __future__ import annotations

import math

from mechcli.report.table import Block
from mechcli.report.words import say

KINDS = ("atlas_page", "type_chart", "atlas_build", "path")
REGIONS = ("crank_rocker", "double_crank", "double_rocker", "change_point")


def _f(x, nd=4):
    return f"{x:.{nd}f}"


def case_results(sol, u):
    """The ``--json`` results of one atlas case."""
    import numpy as np
    r = {"kind": sol.kind}
    e = sol.extra
    if sol.kind == "atlas_page":
        r.update(A=e.A, B=e.B, C=e.C, type=e.kind, curves=int(e.ok.sum()),
                 points=int(e.ok.size), positions=int(e.theta.size),
                 step_deg=math.degrees(float(e.theta[1] - e.theta[0])) if e.theta.size > 1
                 else 360.0, drawn=e.reason is None, reason=e.reason)
        if e.reason is None:
            span = [float(np.max(np.hypot(np.diff(x), np.diff(y))))
                    for x, y in zip(e.x[e.ok], e.y[e.ok])]
            r["dash_max"] = max(span) if span else 0.0
    elif sol.kind == "type_chart":
        ch = e.chart
        A = np.atleast_1d(ch.A)
        r["A"] = [float(a) for a in A]
        frac = {}
        for code, name in enumerate(REGIONS):
            frac[name] = float(np.mean(ch.region == code))
        r["fractions"] = frac
        if e.mark is not None:
            r["mark_B"], r["mark_C"] = float(e.mark[0]), float(e.mark[1])
            r["mark_type"] = e.kind[0]
            r["mark_crank_is_link_1"] = bool(e.kind[1])
        if e.ranges is not None:
            for k, (lo, hi) in e.ranges.items():
                r[f"{k}_min"], r[f"{k}_max"] = float(lo), float(hi)
    elif sol.kind == "atlas_build":
        info, seconds = e
        r.update(curves=int(info.curves), candidates=int(info.candidates),
                 chunks=len(info.chunks), complete=bool(info.complete),
                 harmonics=int(info.harmonics), time_s=float(seconds),
                 curves_per_s=float(info.candidates / seconds) if seconds > 0 else 0.0,
                 directory=str(info.directory))
    elif sol.kind == "path":
        res = e
        r.update(atlas_curves=int(res["curves"]), search_s=float(res["search_s"]),
                 refine_s=float(res["refine_s"]), candidates=len(res["candidates"]))
        cands = []
        for c in res["candidates"]:
            ref = c.refined
            x = ref.x_opt
            tx, ty, rot, scale = ref.placement
            cands.append({
                "A": x["A"], "B": x["B"], "C": x["C"], "gx": x["gx"], "gy": x["gy"],
                "crank": scale / u, "pivot_x": tx / u, "pivot_y": ty / u,
                "frame_angle_deg": math.degrees(rot),
                "error_rms": ref.error_rms / u, "error_max": ref.error_max / u,
                "gamma_min_deg": math.degrees(min(c.mu_min, math.pi - c.mu_max)),
                "type": c.kind, "atlas_distance": c.match.distance,
                "reversed": bool(c.match.reversed),
                **({"theta0_deg": math.degrees(x["theta0"])} if "theta0" in x else {})})
        r["best"] = cands[0] if cands else None
        r["candidates_list"] = cands
        if cands:
            r["error_rms"], r["error_max"] = cands[0]["error_rms"], cands[0]["error_max"]
            r["gamma_min_deg"] = cands[0]["gamma_min_deg"]
    return r


def blocks(prob, sol, u, unit, lang, prefix=""):
    r = case_results(sol, u)
    out = []
    if sol.kind == "atlas_page":
        rows = [["A, B, C", f"{r['A']:g}, {r['B']:g}, {r['C']:g}"],
                [say(lang, "atlas.type"), r["type"]],
                [say(lang, "atlas.curves_drawn"), f"{r['curves']} / {r['points']}"],
                [say(lang, "atlas.dashes_per_curve"), str(r["positions"])]]
        if not r["drawn"]:
            rows.append([say(lang, "atlas.not_drawn"), WHY[r["reason"]]])
        out.append(Block(prefix + say(lang, "atlas.page"), rows=rows))
    elif sol.kind == "type_chart":
        rows = [["A", ", ".join(f"{a:g}" for a in r["A"])]]
        rows += [[name.replace("_", "-"), f"{100 * v:.1f} %"] for name, v in
                 r["fractions"].items()]
        if "mark_type" in r:
            rows.append([say(lang, "atlas.marked_point"),
                         f"{r['mark_B']:g}, {r['mark_C']:g}: {r['mark_type']}"])
        for k in ("A", "B", "C"):
            if f"{k}_min" in r:
                rows.append([say(lang, "atlas.may_vary", k=k),
                             f"{r[k + '_min']:g} ... {r[k + '_max']:g}"])
        out.append(Block(prefix + say(lang, "atlas.type_chart"), rows=rows))
    elif sol.kind == "atlas_build":
        rows = [[say(lang, "atlas.curves_kept"), str(r["curves"])],
                [say(lang, "atlas.designs_swept"), str(r["candidates"])],
                [say(lang, "atlas.chunks"), str(r["chunks"])],
                [say(lang, "atlas.complete"), "yes" if r["complete"] else "no"],
                [say(lang, "atlas.time"), f"{r['time_s']:.2f}"],
                [say(lang, "atlas.directory"), r["directory"]]]
        out.append(Block(prefix + say(lang, "atlas.build"), rows=rows))
    elif sol.kind == "path":
        heads = ["#", "A", "B", "C", "gx", "gy", f"crank [{unit}]",
                 f"rms err [{unit}]", f"max err [{unit}]", "γmin [°]", "type"]
        rows = [[str(i + 1), _f(c["A"]), _f(c["B"]), _f(c["C"]), _f(c["gx"]), _f(c["gy"]),
                 _f(c["crank"]), f"{c['error_rms']:.3g}", f"{c['error_max']:.3g}",
                 _f(c["gamma_min_deg"], 2), c["type"]]
                for i, c in enumerate(r["candidates_list"])]
        out.append(Block(prefix + say(lang, "atlas.path"), heads, rows))
        if r["candidates_list"] and "theta0_deg" in r["candidates_list"][0]:
            out.append(Block(prefix + say(lang, "atlas.timing"), rows=[
                [say(lang, "atlas.crank_at_target_1", i=i + 1), _f(c["theta0_deg"], 3)]
                for i, c in enumerate(r["candidates_list"])]))
        out.append(Block(prefix + say(lang, "atlas.cost"), rows=[
            [say(lang, "atlas.curves_searched"), str(r["atlas_curves"])],
            [say(lang, "atlas.search"), f"{r['search_s']:.3f}"],
            [say(lang, "atlas.refinement"), f"{r['refine_s']:.3f}"]]))
    return out


#: why a page draws nothing
WHY = {"not_crank_rocker": "the chain is not a crank-rocker: no curve turns a full crank "
                           "revolution",
       "crank_not_link_1": "a crank-rocker whose crank is the follower B, not link 1",
       "change_point": "a change-point linkage (s + l = p + q): it can fold",
       None: ""}


def warnings(prob, sol):
    if sol.kind == "path" and not sol.extra["closed"]:
        return [f"[{prob.path}] an open path is matched as if closed by its chord: an arc of "
                "less than about 2/3 of a coupler curve is not found reliably (the "
                "refinement measures the targets against the whole curve)"]
    if sol.kind == "atlas_page" and sol.extra.reason is not None:
        return [f"[{prob.path}] no curve drawn: {WHY[sol.extra.reason]}"]
    if sol.kind == "atlas_build" and not sol.extra[0].complete:
        return [f"[{prob.path}] the atlas is incomplete: run again to resume it"]
    return []


def page_columns(page):
    """``page.csv``: every curve point: point index, gx, gy, theta, x, y [crank lengths]."""
    import numpy as np
    P, N = page.x.shape
    keep = np.repeat(page.ok, N)
    idx = np.repeat(np.arange(P), N)[keep]
    return [("point", idx.astype(float)), ("gx", np.repeat(page.gx, N)[keep]),
            ("gy", np.repeat(page.gy, N)[keep]),
            ("theta_deg", np.tile(np.degrees(page.theta), P)[keep]),
            ("x", page.x.ravel()[keep]), ("y", page.y.ravel()[keep])]


def candidate_toml(cand, header, title, u):
    """A `mechcli kin` spec (general form) of a refined candidate, in the spec's unit."""
    from mechcli.report.tomlout import dumps
    x = cand.refined.x_opt
    tx, ty, rot, scale = cand.refined.placement
    C = x["C"]
    dx, dy = tx + scale * C * math.cos(rot), ty + scale * C * math.sin(rot)
    timed = "theta0" in x          # timed targets: counter-clockwise from target 1
    rev = bool(cand.match.reversed) and not timed
    start = round(math.degrees(rot + x["theta0"]), 9) if timed else 0
    data = {
        "command": "kin", "title": title, "units": header.unit,
        "mechanism": {
            "type": "general", "frame": 4,
            "ground": {"A": [tx / u, ty / u], "D": [dx / u, dy / u]},
            "driver": [{"type": "crank", "link": 1, "pivot": "A", "point": "B",
                        "length": scale / u}],
            "dyad": [{"type": "RRR", "joint": "C", "points": ["B", "D"], "links": [2, 3],
                      "lengths": [scale * x["A"] / u, scale * x["B"] / u], "branch": "left"}],
            "point": [{"name": "P", "link": 2, "from": "B", "along": scale * x["gx"] / u,
                       "normal": scale * x["gy"] / u}]},
        # the targets' sense of travel (a match found reversed runs clockwise) and, for
        # a timed path, the crank angle at the first target as the start
        "input": {"omega1": -10 if rev else 10, "start": start,
                  "stop": start + (-360 if rev else 360), "step": 1}}
    return dumps(data, "written by mechcli synth (kind = \"path\"): an atlas match, refined")
