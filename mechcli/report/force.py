"""Tables, CSV and JSON results of ``mechcli force``."""

from __future__ import annotations

import dataclasses
from typing import Optional

import numpy as np

from mechcli.core.linkage.kinetostatics import COND_FLAG
from mechcli.core.records import record
from mechcli.report.kin import (  # noqa: F401
    accuracy_note,
    accuracy_results,
    accuracy_warnings,
    assembly_message,
    book_title,
    dead_point_note,
    dead_point_results,
    degrees_hint,
    excluded_warnings,
    fixed,
    header,
    input_column,
    input_factor,
    input_header,
    input_suffix,
    input_symbol,
    input_value,
    table_rows,
)
from mechcli.report.table import Block, Report
from mechcli.report.words import say, section


@record
class Extra:
    """What a ``force`` run adds to the sweep: ``engine`` the piston's named results
    (core.linkage.piston.EngineSweep or None); ``at`` input [rad or m] -> {symbol:
    value} at ``output.at``; ``exact`` the exact model's series at the analysed
    positions when the approximate model ran (else None)."""

    engine: object = None
    at: dict = dataclasses.field(default_factory=dict)
    exact: Optional[dict] = None


#: the engine's named results, in report order, with their descriptions (their Chinese
#: names in the tables: the catalogue's ``force.head_<symbol>``)
ENGINE_NAMES = {
    "FL": "gas force on the piston (toward the crank)",
    "FI": "inertia force of the reciprocating mass, m·a",
    "FP": "piston effort (piston on the rod, along the stroke)",
    "FQ": "force along the connecting rod (compression +)",
    "FN": "thrust on the cylinder walls",
    "FT": "crank effort (tangential force at the crank pin)",
    "Frad": "radial force on the crank (toward its axis)",
    "T": "turning moment on the crank",
}


def _unit(sym):
    if sym.startswith(("Mb", "MR", "Msh")) or sym == "T":
        return "N_m"
    if sym == "P":
        return "W"
    return "N"


_PRETTY = {"N_m": "N·m", "N": "N", "W": "W"}


def columns(spec, res, extra=None):
    """CSV columns: input, balancing, every pair (x, y, magnitude, direction,
    couple), frame force/moment, input power, the engine's named results,
    condition number, load flags."""
    cols = [(input_column(spec), res.q * input_factor(spec))]
    for sym, v in res.series.items():
        cols.append((f"{sym}_{_unit(sym)}", v))
        if sym.startswith("FR") and not sym.endswith(("x", "y")):
            lab = sym
            # (+ 0.0: a zero force points at 0°, not at ±180° by the sign of its zeros)
            cols.append((f"{lab}_dir_deg", np.degrees(np.arctan2(res.series[lab + "y"] + 0.0,
                                                                 res.series[lab + "x"] + 0.0))))
    if extra is not None and extra.engine is not None:
        for sym, v in extra.engine.series.items():
            cols.append((f"{sym}_{_unit(sym)}", v))
    cols.append(("cond", res.forces.cond))
    for name, on in res.active_mask.items():
        if any(p.load.name == name and p.conditional for p in spec.loads):
            cols.append((f"active_{name}", on.astype(float)))
    return cols


def _threshold(spec, accuracy_warn):
    return spec.output.accuracy_warn if accuracy_warn is None else accuracy_warn


def _at_key(spec, x):
    """``_at_60deg`` (rotary input) or ``_at_12p5mm``: an input as a key part."""
    unit = "deg" if spec.input.rotary else spec.header.unit
    return f"_at_{at_text(x * input_factor(spec))}{unit}"


def at_text(v):
    """An ``output.at`` input (°, or the spec's length unit) as the value part of a result
    name: rounded to 9 decimals (the spec refuses two inputs equal after that rounding),
    trailing zeros dropped, a decimal point written ``p`` and a minus ``m`` (``60``,
    ``12p5``, ``m30``, ``10p0000001``, ``0p000025``)."""
    txt = f"{round(float(v), 9) + 0.0:.9f}".rstrip("0").rstrip(".")
    return txt.replace("-", "m").replace(".", "p")


def _extra_results(spec, extra, out):
    fin = input_factor(spec)
    at_u = "deg" if spec.input.rotary else spec.header.unit
    if extra.engine is not None:
        for sym, (hi, lo) in extra.engine.extremes.items():
            u = _unit(sym)
            for name, (val, at, tol) in (("max", hi), ("min", lo)):
                out[f"{sym}_{name}_{u}"] = val
                if at is not None:   # none for a quantity constant to round-off
                    out[f"{sym}_{name}_at_{at_u}"] = at * fin
                    out[f"{sym}_{name}_at_{at_u}_tol"] = tol * fin
            out[f"{sym}_abs_max_{u}"] = max(abs(hi[0]), abs(lo[0]))
        pst = spec.piston
        out[f"stroke_{spec.header.unit}"] = pst.stroke / spec.header.scale
        out["head_end_at_deg"] = float(np.degrees(pst.theta_head))
        out["crank_end_at_deg"] = float(np.degrees(pst.theta_crank))
    for x, values in extra.at.items():
        key = _at_key(spec, x)
        for sym, v in values.items():
            out[f"{sym}{key}_{_unit(sym)}"] = v + 0.0
    return out


def scalar_results(spec, res, accuracy_warn=None, extra=None):
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
    out.update(dead_point_results(spec, res.kin))
    out["accuracy"] = accuracy_results(res.accuracy, _threshold(spec, accuracy_warn))
    if extra is not None:
        _extra_results(spec, extra, out)
        if extra.exact is not None:
            _approx_results(spec, res, extra, out)
    if spec.linkage.structure is not None:   # a linkage given by its joints
        from mechcli.report.structure import structure_results
        out.update(structure_results(spec.linkage.structure))
    return out


def _approx_results(spec, res, extra, out):
    """The model (and ``moment_arm = "series"`` when T and FT take the series arm) and
    the largest |approximate − exact| of Mb and the engine's results over the analysed
    positions (absolute, and relative to the exact peak)."""
    out["model"] = spec.model
    if spec.piston.moment_arm != "exact":
        out["moment_arm"] = spec.piston.moment_arm
    approx = dict(res.series)
    if extra.engine is not None:
        approx.update(extra.engine.series)
    for sym in [s for s in res.series if s.startswith(("Mb", "Fb"))] + list(ENGINE_NAMES):
        if sym not in approx or sym not in extra.exact or not np.size(approx[sym]):
            continue
        diff = float(np.max(np.abs(np.asarray(approx[sym]) - extra.exact[sym])))
        peak = float(np.max(np.abs(extra.exact[sym])))
        u = _unit(sym)
        out[f"approx_error_{sym}_max_{u}"] = diff
        out[f"approx_error_{sym}_max_rel"] = diff / peak if peak > 0 else 0.0


def warnings(spec, res, accuracy_warn=None):
    """The warnings of a ``force`` run: excluded input intervals, ill-conditioned
    positions, ranges that keep fewer than ``accuracy_warn`` (default: the spec's
    ``output.accuracy_warn``) correct digits, conditional loads that never act."""
    hint = degrees_hint(spec)
    out = ([hint] if hint else []) + excluded_warnings(spec, res.kin.excluded, res.kin.toggles,
                                                        res.kin.dead_points)
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
    out += _cycle_warnings(spec)
    return out


def _cycle_warnings(spec):
    """A four-stroke indicator diagram analysed over less than its two turns: the strokes
    left out (compression and suction, or the expansion) are silently missing from the
    mean of Mb and the extremes."""
    out = []
    span = abs(spec.input.stop - spec.input.start)
    for p in spec.loads:
        g = p.source
        if not hasattr(g, "piston") or not spec.input.rotary:
            continue
        for key, curve in (("pressure", g.head), ("crank_side_pressure", g.crank)):
            if curve is not None and curve.strokes == 4 and span < 4 * np.pi * (1 - 1e-9):
                out.append(f"load '{p.load.name}': {key} is a four-stroke indicator diagram "
                           f"(a cycle of 720°) but the input spans {np.degrees(span):g}°: "
                           "only part of the cycle is analysed (input.stop = input.start + "
                           "720 for the whole cycle)")
    return out


def _head_name(lang, sym):
    """The name before a force table header's symbol (``平衡力矩 Mb``); none in English."""
    return say(lang, f"force.head_{sym}") if f"head_{sym}" in section("force") else ""


def build_report(spec, res, lang="en", extra=None):
    """The book-style report: reactions and Mb every ``table_step``, extremes, loads;
    the engine's named results and the values at ``output.at`` when asked."""
    digits = spec.output.digits
    fin = input_factor(spec)
    at_u = "°" if spec.input.rotary else spec.header.unit
    shown = [s for s in res.series if s not in ("P",) and not s.startswith("Fsh")
             and s != "Msh"]
    headers = [input_header(spec, lang)] + [header(s, _PRETTY[_unit(s)]) for s in shown]
    rows = []
    for i in table_rows(spec, res, spec.output.table_step):
        rows.append([fixed(res.q[i] * fin, 2)] + [fixed(res.series[s][i], digits)
                                                   for s in shown])
    report = Report(title=book_title(spec.header.title))
    if spec.linkage.structure is not None:   # given by its joints: the book's 杆组分解 first
        from mechcli.report.structure import structure_block
        report.blocks.append(structure_block(lang, spec.linkage.structure, spec.linkage.frame))
    step_txt = f"{spec.output.table_step * fin:g}"
    torque = any(s.startswith("Mb") for s in res.series)
    report.blocks.append(Block(
        heading=say(lang, "force.reactions", step=step_txt, unit=at_u,
                    what=say(lang, "force.balancing_torque" if torque
                             else "force.balancing_force")),
        headers=headers, rows=rows))
    ext = []
    flat = _constant(res)
    for sym, (hi, lo) in res.extremes.items():
        u = _PRETTY[_unit(sym)]
        signed = not (sym.startswith("FR") or sym == "Fsh")
        name = sym if not sym.startswith("FR") else f"|{sym}|"
        label = header(name, u, _head_name(lang, sym))
        if sym in flat:     # constant to round-off: no location
            ext.append([label, fixed(hi.value, digits), say(lang, "common.constant"),
                        fixed(lo.value, digits) if signed else "", ""])
            continue
        ext.append([label, fixed(hi.value, digits), fixed(hi.at * fin, 4),
                    fixed(lo.value, digits) if signed else "", fixed(lo.at * fin, 4)
                    if signed else ""])
    report.blocks.append(Block(
        heading=say(lang, "force.extremes", tol=f"{_extreme_tol(res) * fin:.0e}",
                    unit=input_suffix(spec)),
        headers=_extreme_headers(lang, at_u), rows=ext))
    lines = []
    for sym in res.mean:
        u = _PRETTY[_unit(sym)]
        lines.append([say(lang, "force.mean", sym=sym), f"{res.mean[sym]:.{digits + 2}f} {u}"])
        lines.append([say(lang, "force.rms", sym=sym), f"{res.rms[sym]:.{digits + 2}f} {u}"])
    fr = res.forces
    peak = max(float(np.max(np.abs(v))) for v in fr.balancing.values())
    lines.append([say(lang, "force.power_residual"),
                  f"{float(np.max(np.abs(fr.power_residual))) / max(peak, 1e-300):.1e}"])
    k = int(np.argmax(fr.cond))
    lines.append([say(lang, "force.largest_cond"),
                  f"{fr.cond[k]:.3g} at {res.q[k] * fin:.2f}{at_u}"])
    report.blocks.append(Block(heading=say(lang, "common.summary"), rows=lines))
    loads = []
    for p in spec.loads:
        ld = p.load
        what = (f"torque {ld.torque:g} N·m" if not (ld.fx or ld.fy) else
                f"force ({ld.fx:g}, {ld.fy:g}) N" + (" in link axes" if ld.relative else ""))
        if p.conditional:
            iv = res.active.get(ld.name, [])
            where = ", ".join(f"{a * fin:.4f} … {b * fin:.4f}{at_u}" for a, b in iv) or \
                say(lang, "force.never")
        else:
            where = say(lang, "force.always")
        if p.source is not None and hasattr(p.source, "piston"):
            g = p.source
            what = (f"gas pressure on piston {ld.link}, area {g.area:.6g} m²"
                    + (f", crank side {g.area - g.rod_area:.6g} m²" if g.crank is not None
                       else "") + " (toward the crank)")
        elif p.source is not None:
            what = "piston inertia force from the series in 1/n"
        loads.append([f"{ld.name} (link {ld.link}): {what}", where])
    if loads:
        report.blocks.append(Block(heading=say(lang, "force.loads"), rows=loads))
    if extra is not None:
        _engine_blocks(spec, res, extra, report, lang, digits)
    report.notes.append(say(lang, "common.positions", n=res.q.size)
                        + (f"; ω1 = {spec.input.omega:g} rad/s" if spec.input.rotary else ""))
    if res.accuracy is not None:
        report.notes.append(accuracy_note(res.accuracy, lang))
    if dead_point_note(spec, res.kin, lang):
        report.notes.append(dead_point_note(spec, res.kin, lang))
    return report


def _extreme_headers(lang, at_u):
    """The headers of an extremes table: quantity, max, at, min, at."""
    at = header(say(lang, "common.at"), at_u)
    return [say(lang, "common.quantity"), say(lang, "common.max"), at,
            say(lang, "common.min"), at]


def _engine_blocks(spec, res, extra, report, lang, digits):
    fin = input_factor(spec)
    at_u = "°" if spec.input.rotary else spec.header.unit
    eng = extra.engine
    if eng is not None:
        syms = list(eng.series)
        headers = [input_header(spec, lang)] + [header(s, _PRETTY[_unit(s)]) for s in syms]
        rows = [[fixed(res.q[i] * fin, 2)] + [fixed(eng.series[s][i], digits) for s in syms]
                for i in table_rows(spec, res, spec.output.table_step)]
        pst = spec.piston
        report.blocks.append(Block(
            heading=say(lang, "force.engine_forces"),
            headers=headers, rows=rows))
        ext = []
        for sym, (hi, lo) in eng.extremes.items():
            u = _PRETTY[_unit(sym)]
            label = header(sym, u, _head_name(lang, sym))
            if hi[1] is None:
                ext.append([label, fixed(hi[0], digits), say(lang, "common.constant"),
                            fixed(lo[0], digits), ""])
            else:
                ext.append([label, fixed(hi[0], digits), fixed(hi[1] * fin, 4),
                            fixed(lo[0], digits), fixed(lo[1] * fin, 4)])
        tols = [e[2] for pair in eng.extremes.values() for e in pair if e[1] is not None]
        report.blocks.append(Block(
            heading=say(lang, "force.engine_extremes_located", tol=f"{max(tols) * fin:.0e}",
                        unit=input_suffix(spec)) if tols else
            say(lang, "force.engine_extremes"),
            headers=_extreme_headers(lang, at_u), rows=ext))
        report.notes.append(say(lang, "force.piston", link=pst.link,
                                stroke=f"{pst.stroke / spec.header.scale:.6g}",
                                unit=spec.header.unit, head=f"{np.degrees(pst.theta_head):.4f}",
                                crank=f"{np.degrees(pst.theta_crank):.4f}"))
    for x, values in extra.at.items():
        shown = at_text(x * fin).replace("p", ".").replace("m", "-")
        rows = [[header(sym, _PRETTY[_unit(sym)]), fixed(v, digits)]
                for sym, v in values.items() if not sym.endswith(("x", "y"))
                or sym in ENGINE_NAMES]
        report.blocks.append(Block(
            heading=say(lang, "force.values_at", sym=input_symbol(spec), x=shown, unit=at_u),
            headers=[say(lang, "common.quantity"), say(lang, "common.value")], rows=rows))
    if extra.exact is not None:
        diffs = {}
        _approx_results(spec, res, extra, diffs)
        parts = [f"{k[len('approx_error_'):-len('_max_rel')]} {v:.2%}"
                 for k, v in diffs.items() if k.endswith("_max_rel")]
        key = "force.approx_arm" if spec.piston.moment_arm == "series" else "force.approx"
        report.notes.append(say(lang, key, diffs=", ".join(parts)))


def _constant(res):
    """The symbols of the extremes whose quantity is constant to round-off (the shaking
    moment of a linkage without a moment on the frame, ~1e-12 N·m): no location."""
    from mechcli.core.linkage.piston import is_constant, noise_level
    noise = noise_level({k: v for k, v in res.series.items() if k != "P"})
    return {sym for sym in res.extremes if is_constant(res.series[sym], noise)}


def _extreme_tol(res):
    """The largest refinement tolerance of the extremes [rad or m] (of the quantities
    that are not constant to round-off)."""
    flat = _constant(res)
    tols = [e.tol for sym, (hi, lo) in res.extremes.items() if sym not in flat
            for e in ((hi, lo) if not (sym.startswith("FR") or sym == "Fsh") else (hi,))]
    return max(tols) if tols else 0.0


__all__ = ["columns", "scalar_results", "build_report", "warnings", "input_column"]
