"""Tables, CSV and JSON results of ``mechcli kin``."""

from __future__ import annotations

import math

import numpy as np

from mechcli.report.table import Block, Report

# kind -> (unit suffix template, factor template); {u} = spec length unit
_UNITS = {
    "angle": ("deg", lambda s: 180 / math.pi),
    "angvel": ("rad_s", lambda s: 1.0),
    "angacc": ("rad_s2", lambda s: 1.0),
    "length": ("{u}", lambda s: 1 / s),
    "velocity": ("{u}_s", lambda s: 1 / s),
    "acceleration": ("{u}_s2", lambda s: 1 / s),
    "ratio": ("1", lambda s: 1.0),
}
_PRETTY_UNIT = {"deg": "°", "rad_s": "rad/s", "rad_s2": "rad/s²"}

_ZH = {
    "theta": "角位移", "omega": "角速度", "alpha": "角加速度", "gamma": "传动角",
    "s": "位移", "v": "速度", "a": "加速度", "x": "x 坐标", "y": "y 坐标",
    "vx": "x 向速度", "vy": "y 向速度", "ax": "x 向加速度", "ay": "y 向加速度",
}


def unit_of(kind, length_unit):
    return _UNITS[kind][0].format(u=length_unit)


def factor_of(kind, scale):
    return _UNITS[kind][1](scale)


def column_name(q, length_unit):
    return f"{q.symbol}_{unit_of(q.kind, length_unit)}"


def input_column(spec):
    n = spec.input.driver
    return f"theta{n}_deg" if spec.input.rotary else f"s{n}_{spec.header.unit}"


def fixed(x, digits):
    """``x`` with ``digits`` decimals, never a negative zero."""
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text


def input_factor(spec):
    return 180 / math.pi if spec.input.rotary else 1 / spec.header.scale


def input_suffix(spec):
    """Unit text after an input value in a message: ``°`` or `` mm``."""
    return "°" if spec.input.rotary else f" {spec.header.unit}"


def excluded_warnings(spec, excluded):
    """One line per input interval left out of the analysis (``partial = true``).

    *excluded* holds ``(start, stop, reason)`` in core units (rad or m).
    """
    f, unit = input_factor(spec), input_suffix(spec)
    return [f"{why} for input {a * f:.6g}{unit} … {b * f:.6g}{unit} (excluded)"
            for a, b, why in excluded]


def assembly_message(spec, exc):
    """The user's wording of an :class:`~mechcli.core.errors.AssemblyError`: the
    intervals in the spec's input unit, and the key that analyses the rest."""
    if not exc.intervals:
        return str(exc)
    f, unit = input_factor(spec), input_suffix(spec)
    what = "input angle" if spec.input.rotary else "input"
    text = "; ".join(f"{why} for {what} {a * f:.6g}{unit} … {b * f:.6g}{unit}"
                     for a, b, why in exc.intervals)
    text += " (set input.partial = true to analyse the feasible ranges only)"
    return ("fewer than two input positions can be analysed: " + text) if exc.too_few else text


def warnings(spec, result, accuracy_warn=None):
    """The warnings of a ``kin`` run: excluded input intervals, extremes that
    grow without bound towards a dead point, and ranges that keep fewer than
    ``accuracy_warn`` (default: the spec's ``output.accuracy_warn``) correct digits."""
    f, unit = input_factor(spec), input_suffix(spec)
    return excluded_warnings(spec, result.excluded) + [
        f"{sym} grows without bound towards the dead point at {e.at * f:.6g}{unit}"
        for sym, pair in result.extremes.items() for e in pair if not e.bounded] + \
        accuracy_warnings(spec, result.accuracy, _threshold(spec, accuracy_warn))


def _threshold(spec, accuracy_warn):
    return spec.output.accuracy_warn if accuracy_warn is None else accuracy_warn


def accuracy_warnings(spec, accuracy, threshold):
    """One line per continuous input range where a class of results (positions,
    velocities, accelerations, forces) keeps fewer than *threshold* correct
    significant digits (estimated; see docs/accuracy.md)."""
    if accuracy is None:
        return []
    f, unit = input_factor(spec), input_suffix(spec)
    out = []
    for r in accuracy.ranges(threshold):
        if f"{r.start * f:.6g}" == f"{r.stop * f:.6g}":
            where = f"at input {r.at * f:.6g}{unit}"
        else:
            where = (f"for input {r.start * f:.6g}{unit} … {r.stop * f:.6g}{unit} "
                     f"(fewest at {r.at * f:.6g}{unit})")
        out.append(f"{r.quantity} lose digits near a singular position: {r.symbol} keeps about "
                   f"{r.digits:.1f} correct significant digits (estimated; fewer than "
                   f"{threshold:g}) {where}")
    return out


def accuracy_results(accuracy, threshold):
    """JSON ``accuracy``: the fewest estimated correct significant digits of each
    class over the range, of each quantity, and the warning threshold."""
    if accuracy is None:
        return {}
    out = {k: round(v, 1) for k, v in accuracy.minimum().items()}
    out["by_quantity"] = {k: round(v, 1) for k, v in accuracy.by_quantity.items()}
    out["warn_below"] = float(threshold)
    return out


def columns(spec, quantities, result):
    """CSV columns: the input, then every quantity in the spec's units."""
    cols = [(input_column(spec), result.q * input_factor(spec))]
    for q in quantities:
        cols.append((column_name(q, spec.header.unit),
                     result.values[q.symbol] * factor_of(q.kind, spec.header.scale)))
    return cols


def scalar_results(spec, quantities, result, accuracy_warn=None):
    """``--json`` results: extremes (with input angles, the tolerance of the
    refinement and the grid error), strokes, swings, flags, estimated accuracy."""
    unit, scale = spec.header.unit, spec.header.scale
    fin = input_factor(spec)
    at_unit = "deg" if spec.input.rotary else unit
    out = {"positions": int(result.q.size)}
    unbounded = []
    for q in quantities:
        if q.symbol not in result.extremes:
            continue
        hi, lo = result.extremes[q.symbol]
        u = unit_of(q.kind, unit)
        f = factor_of(q.kind, scale)
        samples = result.values[q.symbol]
        for name, e in (("max", hi), ("min", lo)):
            if e.bounded:
                out[f"{q.symbol}_{name}_{u}"] = e.value * f
                out[f"{q.symbol}_{name}_at_{at_unit}"] = e.at * fin
                # how closely the refinement located it, and what reading it off
                # the CSV rows would cost (refined extreme minus best sample)
                out[f"{q.symbol}_{name}_at_{at_unit}_tol"] = e.tol * fin
                best = np.max(samples) if name == "max" else np.min(samples)
                out[f"{q.symbol}_{name}_grid_error_{u}"] = float(e.value - best) * f + 0.0
            else:
                unbounded.append({"quantity": f"{q.symbol}_{name}", "towards": e.at * fin})
        if q.kind == "length" and q.symbol.startswith("s"):
            out[f"{q.symbol}_stroke_{u}"] = (hi.value - lo.value) * f
        if q.kind == "angle" and q.symbol.startswith("theta"):
            out[f"{q.symbol}_swing_deg"] = (hi.value - lo.value) * f
    out["unbounded"] = unbounded
    out["excluded"] = [[a * fin, b * fin, why] for a, b, why in result.excluded]
    out["toggles"] = [{"at": t.at * fin, "joint": t.joint, "dyad": t.kind,
                       "gamma_deg": math.degrees(math.asin(min(1.0, t.sin_gamma)))}
                      for t in result.toggles]
    out["accuracy"] = accuracy_results(result.accuracy, _threshold(spec, accuracy_warn))
    return out


def pretty_unit(kind, length_unit):
    u = unit_of(kind, length_unit)
    return _PRETTY_UNIT.get(u, u.replace("_s2", "/s²").replace("_s", "/s"))


def _label(q, unit, lang):
    pretty = pretty_unit(q.kind, unit)
    if lang == "zh":
        base = q.symbol.rstrip("0123456789")
        for key in sorted(_ZH, key=len, reverse=True):
            if q.symbol.startswith(key):
                base = key
                break
        return f"{q.symbol} {_ZH.get(base, '')}/{pretty}".replace(" /", "/")
    return f"{q.symbol}/{pretty}"


def table_rows(spec, result, step):
    """Indices of the analysed positions closest to every ``step`` of the input."""
    q = result.q
    targets = np.arange(spec.input.start, spec.input.stop + step * 1e-9, step)
    idx = np.searchsorted(q, targets)
    idx = np.clip(idx, 0, q.size - 1)
    left = np.clip(idx - 1, 0, q.size - 1)
    idx = np.where(np.abs(q[left] - targets) < np.abs(q[idx] - targets), left, idx)
    keep = np.abs(q[idx] - targets) <= 0.5 * step
    return np.unique(idx[keep])


def _extreme_tol(result):
    """The largest refinement tolerance of the bounded extremes [rad or m]."""
    tols = [e.tol for pair in result.extremes.values() for e in pair if e.bounded]
    return max(tols) if tols else 0.0


def _grid_error_note(spec, quantities, result, zh):
    """The largest relative grid error of the CSV rows' peaks, with its quantity."""
    worst, sym = 0.0, None
    for q in quantities:
        if q.symbol not in result.extremes:
            continue
        v = result.values[q.symbol]
        hi, lo = result.extremes[q.symbol]
        peak = max(abs(hi.value), abs(lo.value))
        if peak == 0:
            continue
        for e, best in ((hi, np.max(v)), (lo, np.min(v))):
            if e.bounded and abs(e.value - best) / peak > worst:
                worst, sym = abs(e.value - best) / peak, q.symbol
    if sym is None:
        return None
    step = (result.q[1] - result.q[0]) * input_factor(spec) if result.q.size > 1 else 0.0
    at_u = input_suffix(spec)
    if zh:
        return f"{step:g}{at_u} CSV 行上的峰值误差 ≤ 峰值的 {worst:.1e} ({sym})"
    return f"peaks of the {step:g}{at_u} CSV rows are off by ≤ {worst:.1e} of the peak ({sym})"


def build_report(spec, quantities, result, lang="en"):
    """The book-style text report: table every ``table_step``, extremes, flags."""
    zh = lang == "zh"
    unit, digits = spec.header.unit, spec.output.digits
    fin = input_factor(spec)
    cols = columns(spec, quantities, result)
    in_label = ("曲柄转角 θ1/°" if zh else "theta1/°") if spec.input.rotary else f"s1/{unit}"
    headers = [in_label] + [_label(q, unit, lang) for q in quantities]
    rows = []
    for i in table_rows(spec, result, spec.output.table_step):
        rows.append([fixed(cols[0][1][i], 2)] + [fixed(c[1][i], digits) for c in cols[1:]])
    report = Report(title=spec.header.title)
    step_txt = f"{spec.output.table_step * fin:g}"
    report.blocks.append(Block(
        heading=(f"计算结果 (每 {step_txt}° 一行，长度单位 {unit})" if zh else
                 f"Results (every {step_txt}{'°' if spec.input.rotary else ' ' + unit}, "
                 f"lengths in {unit})"),
        headers=headers, rows=rows))
    ext_rows = []
    at_u = "°" if spec.input.rotary else unit
    for q in quantities:
        if q.symbol not in result.extremes:
            continue
        hi, lo = result.extremes[q.symbol]
        f = factor_of(q.kind, spec.header.scale)
        cells = [_label(q, unit, lang)]
        for e in (hi, lo):
            if e.bounded:
                cells += [fixed(e.value * f, digits), fixed(e.at * fin, 4)]
            else:
                cells += ["无界" if zh else "unbounded", "→ " + fixed(e.at * fin, 4)]
        ext_rows.append(cells)
    if ext_rows:
        report.blocks.append(Block(
            heading=(f"极值 (位置精确到 ±{_extreme_tol(result) * fin:.0e}{input_suffix(spec)})"
                     if zh else f"Extremes (input located to "
                                f"±{_extreme_tol(result) * fin:.0e}{input_suffix(spec)})"),
            headers=["量" if zh else "quantity", "最大值" if zh else "max",
                     f"位置/{at_u}" if zh else f"at/{at_u}", "最小值" if zh else "min",
                     f"位置/{at_u}" if zh else f"at/{at_u}"],
            rows=ext_rows))
    flags = []
    for a, b, why in result.excluded:
        why_t = {"cannot assemble": "无法装配", "dead point": "死点"}[why] if zh else why
        flags.append([why_t, f"{a * fin:.6f} … {b * fin:.6f} {at_u}"])
    for t in result.toggles:
        g = math.degrees(math.asin(min(1.0, t.sin_gamma)))
        flags.append([("接近死点" if zh else "near dead point") + f" ({t.kind} {t.joint})",
                      f"{t.at * fin:.6f} {at_u}, γ = {g:.4f}°"])
    if flags:
        report.blocks.append(Block(heading="标记" if zh else "Flags", rows=flags))
    n = result.q.size
    report.notes.append((f"共 {n} 个位置" if zh else f"{n} positions analysed")
                        + (f"; ω1 = {spec.input.omega:g} rad/s" if spec.input.rotary else ""))
    note = _grid_error_note(spec, quantities, result, zh)
    if note:
        report.notes.append(note)
    if result.accuracy is not None and result.accuracy.digits:
        report.notes.append(accuracy_note(result.accuracy, zh))
    return report


_ZH_CLASS = {"positions": "位置", "velocities": "速度", "accelerations": "加速度",
             "forces": "力"}


def accuracy_note(accuracy, zh=False):
    """One line: the fewest estimated correct significant digits of each class."""
    parts = ", ".join(f"{_ZH_CLASS.get(k, k) if zh else k} {v:.1f}"
                      for k, v in accuracy.minimum().items())
    return f"估计有效数字 (最少): {parts}" if zh else f"estimated correct digits: {parts}"
