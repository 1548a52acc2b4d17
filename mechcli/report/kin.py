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


def warnings(spec, result):
    """The warnings of a ``kin`` run: excluded input intervals, and extremes
    that grow without bound towards a dead point."""
    f, unit = input_factor(spec), input_suffix(spec)
    return excluded_warnings(spec, result.excluded) + [
        f"{sym} grows without bound towards the dead point at {e.at * f:.6g}{unit}"
        for sym, pair in result.extremes.items() for e in pair if not e.bounded]


def columns(spec, quantities, result):
    """CSV columns: the input, then every quantity in the spec's units."""
    cols = [(input_column(spec), result.q * input_factor(spec))]
    for q in quantities:
        cols.append((column_name(q, spec.header.unit),
                     result.values[q.symbol] * factor_of(q.kind, spec.header.scale)))
    return cols


def scalar_results(spec, quantities, result):
    """``--json`` results: extremes (with input angles), strokes, swings, flags."""
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
        for name, e in (("max", hi), ("min", lo)):
            if e.bounded:
                out[f"{q.symbol}_{name}_{u}"] = e.value * f
                out[f"{q.symbol}_{name}_at_{at_unit}"] = e.at * fin
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
            heading="极值 (精确到 1e-9 rad)" if zh else "Extremes (refined to 1e-9 rad)",
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
    return report
