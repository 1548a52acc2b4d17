"""Tables, CSV and JSON results of ``mechcli force``."""

from __future__ import annotations

import numpy as np

from mechcli.core.linkage.kinetostatics import COND_FLAG
from mechcli.report.kin import (accuracy_note, accuracy_results, accuracy_warnings,  # noqa: F401
                                assembly_message, book_title, degrees_hint,
                                excluded_warnings, fixed, header, input_column, input_factor,
                                input_header, input_suffix, input_symbol, input_value,
                                table_rows)
from mechcli.report.table import Block, Report


def _unit(sym):
    if sym.startswith(("Mb", "MR", "Msh")):
        return "N_m"
    if sym == "P":
        return "W"
    return "N"


_PRETTY = {"N_m": "N·m", "N": "N", "W": "W"}


def columns(spec, res):
    """CSV columns: input, balancing, every pair (x, y, magnitude, direction,
    couple), frame force/moment, input power, condition number, load flags."""
    cols = [(input_column(spec), res.q * input_factor(spec))]
    for sym, v in res.series.items():
        cols.append((f"{sym}_{_unit(sym)}", v))
        if sym.startswith("FR") and not sym.endswith(("x", "y")):
            lab = sym
            cols.append((f"{lab}_dir_deg", np.degrees(np.arctan2(res.series[lab + "y"],
                                                                 res.series[lab + "x"]))))
    cols.append(("cond", res.forces.cond))
    for name, on in res.active_mask.items():
        if any(p.load.name == name and p.conditional for p in spec.loads):
            cols.append((f"active_{name}", on.astype(float)))
    return cols


def _threshold(spec, accuracy_warn):
    return spec.output.accuracy_warn if accuracy_warn is None else accuracy_warn


def scalar_results(spec, res, accuracy_warn=None):
    """``--json`` results: extremes with input angles (with the tolerance of the
    refinement and the grid error), mean/RMS, checks, loads, estimated accuracy."""
    fin = input_factor(spec)
    at_u = "deg" if spec.input.rotary else spec.header.unit
    out = {"positions": int(res.q.size)}
    for sym, (hi, lo) in res.extremes.items():
        u = _unit(sym)
        samples = res.series[sym]
        out[f"{sym}_max_{u}"] = hi.value + 0.0  # never -0.0
        out[f"{sym}_max_at_{at_u}"] = hi.at * fin
        out[f"{sym}_max_at_{at_u}_tol"] = hi.tol * fin
        # refined extreme minus the best CSV row
        out[f"{sym}_max_grid_error_{u}"] = float(hi.value - np.max(samples)) + 0.0
        if not sym.startswith("FR") and sym != "Fsh":
            out[f"{sym}_min_{u}"] = lo.value + 0.0
            out[f"{sym}_min_at_{at_u}"] = lo.at * fin
            out[f"{sym}_min_at_{at_u}_tol"] = lo.tol * fin
            out[f"{sym}_min_grid_error_{u}"] = float(lo.value - np.min(samples)) + 0.0
            # the peak magnitude (optimize's "max |Mb|" goal)
            out[f"{sym}_abs_max_{u}"] = max(abs(hi.value), abs(lo.value))
    for sym in res.mean:
        u = _unit(sym)
        out[f"{sym}_mean_{u}"] = res.mean[sym]
        out[f"{sym}_rms_{u}"] = res.rms[sym]
    fr = res.forces
    peak = max(float(np.max(np.abs(v))) for v in fr.balancing.values())
    out["power_balance_residual"] = float(np.max(np.abs(fr.power_residual))) / max(peak, 1e-300)
    mass_force = max(1e-300, float(np.max(res.series["Fsh"])), peak)
    out["force_balance_residual"] = float(np.max(fr.force_residual)) / mass_force
    k = int(np.argmax(fr.cond))
    out["cond_max"] = float(fr.cond[k])
    out["cond_max_at_" + at_u] = float(res.q[k] * fin)
    out["ill_conditioned"] = [[a * fin, b * fin] for a, b in res.flagged]
    for name, iv in res.active.items():
        out[f"active_{name}_{at_u}"] = [[a * fin, b * fin] for a, b in iv]
    for name, (lo, hi) in res.band.items():
        out[f"band_{name}_{spec.header.unit}"] = [lo / spec.header.scale, hi / spec.header.scale]
    out["excluded"] = [[a * fin, b * fin, why] for a, b, why in res.kin.excluded]
    out["accuracy"] = accuracy_results(res.accuracy, _threshold(spec, accuracy_warn))
    return out


def warnings(spec, res, accuracy_warn=None):
    """The warnings of a ``force`` run: excluded input intervals, ill-conditioned
    positions, ranges that keep fewer than ``accuracy_warn`` (default: the spec's
    ``output.accuracy_warn``) correct digits, conditional loads that never act."""
    hint = degrees_hint(spec)
    out = ([hint] if hint else []) + excluded_warnings(spec, res.kin.excluded, res.kin.toggles)
    out += accuracy_warnings(spec, res.accuracy, _threshold(spec, accuracy_warn))
    if res.flagged:
        where = []
        for a, b in sorted(res.flagged):
            ta, tb = input_value(spec, a), input_value(spec, b)
            where.append(ta if ta == tb else f"{ta} … {tb}")
        out.append(f"ill-conditioned (condition number > {COND_FLAG:.0e}) at "
                   f"{input_symbol(spec)} = {', '.join(where)}: reactions lose digits near "
                   "a dead point")
    for p in spec.loads:
        if p.conditional and not res.active.get(p.load.name):
            out.append(f"load '{p.load.name}' is never active over the analysed range")
    return out


_ZH_HEAD = {"Mb": "平衡力矩", "Fb": "平衡力", "Fsh": "机架总反力", "Msh": "机架总力矩"}


def build_report(spec, res, lang="en"):
    """The book-style report: reactions and Mb every ``table_step``, extremes, loads."""
    zh = lang == "zh"
    digits = spec.output.digits
    fin = input_factor(spec)
    at_u = "°" if spec.input.rotary else spec.header.unit
    shown = [s for s in res.series if s not in ("P",) and not s.startswith("Fsh")
             and s != "Msh"]
    headers = [input_header(spec, zh)] + [header(s, _PRETTY[_unit(s)]) for s in shown]
    rows = []
    for i in table_rows(spec, res, spec.output.table_step):
        rows.append([fixed(res.q[i] * fin, 2)] + [fixed(res.series[s][i], digits)
                                                   for s in shown])
    report = Report(title=book_title(spec.header.title))
    step_txt = f"{spec.output.table_step * fin:g}"
    report.blocks.append(Block(
        heading=(f"运动副反力与平衡力矩 (每 {step_txt}{at_u} 一行; F_Rij 为构件 i 对构件 j "
                 "的作用力)" if zh else
                 f"Pair reactions and balancing torque (every {step_txt}{at_u}; F_Rij = "
                 "force of link i on link j)"),
        headers=headers, rows=rows))
    ext = []
    for sym, (hi, lo) in res.extremes.items():
        u = _PRETTY[_unit(sym)]
        signed = not (sym.startswith("FR") or sym == "Fsh")
        name = sym if not sym.startswith("FR") else f"|{sym}|"
        label = header(name, u, _ZH_HEAD.get(sym, "") if zh else "")
        ext.append([label, fixed(hi.value, digits), fixed(hi.at * fin, 4),
                    fixed(lo.value, digits) if signed else "", fixed(lo.at * fin, 4)
                    if signed else ""])
    report.blocks.append(Block(
        heading=(f"极值 (位置精确到 ±{_extreme_tol(res) * fin:.0e}{input_suffix(spec)})" if zh
                 else f"Extremes (refined by golden-section search, input located to "
                      f"±{_extreme_tol(res) * fin:.0e}{input_suffix(spec)})"),
        headers=["量" if zh else "quantity", "最大值" if zh else "max",
                 header("位置" if zh else "at", at_u), "最小值" if zh else "min",
                 header("位置" if zh else "at", at_u)],
        rows=ext))
    lines = []
    for sym in res.mean:
        u = _PRETTY[_unit(sym)]
        lines.append([("平均 " if zh else "mean ") + sym, f"{res.mean[sym]:.{digits + 2}f} {u}"])
        lines.append([("均方根 " if zh else "RMS ") + sym, f"{res.rms[sym]:.{digits + 2}f} {u}"])
    fr = res.forces
    peak = max(float(np.max(np.abs(v))) for v in fr.balancing.values())
    lines.append(["功率平衡残差 (相对)" if zh else "power balance residual (relative)",
                  f"{float(np.max(np.abs(fr.power_residual))) / max(peak, 1e-300):.1e}"])
    k = int(np.argmax(fr.cond))
    lines.append(["最大条件数" if zh else "largest condition number",
                  f"{fr.cond[k]:.3g} at {res.q[k] * fin:.2f}{at_u}"])
    report.blocks.append(Block(heading="汇总" if zh else "Summary", rows=lines))
    loads = []
    for p in spec.loads:
        ld = p.load
        what = (f"torque {ld.torque:g} N·m" if not (ld.fx or ld.fy) else
                f"force ({ld.fx:g}, {ld.fy:g}) N" + (" in link axes" if ld.relative else ""))
        if p.conditional:
            iv = res.active.get(ld.name, [])
            where = ", ".join(f"{a * fin:.4f} … {b * fin:.4f}{at_u}" for a, b in iv) or \
                ("从不" if zh else "never")
        else:
            where = "全程" if zh else "always"
        loads.append([f"{ld.name} (link {ld.link}): {what}", where])
    if loads:
        report.blocks.append(Block(heading="外载荷作用区间" if zh else "Loads and where they act",
                                   rows=loads))
    n = res.q.size
    report.notes.append((f"共 {n} 个位置" if zh else f"{n} positions analysed")
                        + (f"; ω1 = {spec.input.omega:g} rad/s" if spec.input.rotary else ""))
    if res.accuracy is not None:
        report.notes.append(accuracy_note(res.accuracy, zh))
    return report


def _extreme_tol(res):
    """The largest refinement tolerance of the extremes [rad or m]."""
    tols = [e.tol for pair in res.extremes.values() for e in pair]
    return max(tols) if tols else 0.0


__all__ = ["columns", "scalar_results", "build_report", "warnings", "input_column"]
