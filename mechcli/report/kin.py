"""Tables, CSV and JSON results of ``mechcli kin``."""

from __future__ import annotations

import math

import numpy as np

from mechcli.report.table import Block, Report, book_title
from mechcli.report.words import language, say, table

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

#: the symbols whose quantity has a name in the catalogue (``kin.name_<prefix>``), longest first
_NAMED = tuple(sorted(("theta", "omega", "alpha", "gamma", "s", "v", "a", "x", "y",
                       "vx", "vy", "ax", "ay"), key=len, reverse=True))


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


def header(symbol, unit, name=""):
    """A table header in the book's notation: ``θ1/(°)``, ``ω3/(rad/s)``,
    ``xF/(mm)``; with a (Chinese) *name* before the symbol, ``角速度 ω3/(rad/s)``.
    A dimensionless quantity (unit ``""`` or ``"1"``) has no unit."""
    text = symbol if unit in ("", "1") else f"{symbol}/({unit})"
    return f"{name} {text}" if name else text


#: quantity kind -> the symbol's ASCII spelling and its Greek letter
_GREEK_OF = {"angle": (("theta", "θ"), ("gamma", "γ"), ("phi", "φ"), ("psi", "ψ")),
             "angvel": (("omega", "ω"),), "angacc": (("alpha", "α"),)}


def greek(symbol, kind):
    """``theta3`` -> ``θ3``, ``omega3`` -> ``ω3``, ``gammaC`` -> ``γC`` (by *kind*, so
    that a point named ``lpha`` of an acceleration ``alpha`` is left alone)."""
    for ascii_, letter in _GREEK_OF.get(kind, ()):
        if symbol.startswith(ascii_):
            return letter + symbol[len(ascii_):]
    return symbol


def input_header(spec, lang="en"):
    """The input column's header: ``θ1/(°)`` (``曲柄转角 θ1/(°)``) or ``s1/(mm)``.
    *lang* may also be the older ``zh`` flag (True/False)."""
    n, lang = spec.input.driver, language(lang)
    if spec.input.rotary:
        return header(f"θ{n}", "°", say(lang, "kin.crank_angle"))
    return header(f"s{n}", spec.header.unit, say(lang, "kin.slider_position"))


def input_symbol(spec):
    """The input's symbol in a message: ``θ1`` or ``s1``."""
    return f"{'θ' if spec.input.rotary else 's'}{spec.input.driver}"


def input_value(spec, x):
    """An input position *x* [rad or m] as text in the spec's unit, rounded to what
    a user reads (0.0001°, or a millionth of the input range): ``180°``, never
    ``179.999995°`` or ``5.5e-06°``."""
    f = input_factor(spec)
    v = x * f
    if spec.input.rotary:
        digits = 4
    else:
        span = abs(spec.input.stop - spec.input.start) * f
        digits = max(0, 6 - math.ceil(math.log10(span))) if span > 0 else 6
    return f"{round(v, digits) + 0.0:.10g}{input_suffix(spec)}"


def _dyads(spec):
    """The joints of the linkage's dyads (the elements that can reach a dead point)."""
    out = []
    for el in getattr(getattr(spec, "linkage", None), "elements", ()):
        if getattr(el, "is_driver", False) or el.kind not in ("RRR", "RRP", "RPR", "PRP"):
            continue
        out.append(getattr(el, "joint", None) or getattr(el, "point", None))
    return [j for j in out if j]


def singular_groups(spec, intervals, toggles=(), dead_points=()):
    """The input intervals where the linkage cannot be analysed, as the user reads them.

    *intervals* hold ``(start, stop, reason)`` in core units.  An interval narrower
    than 1e-5 of the range (the bisection's bracket round a dead point) is one
    position; the intervals that meet across the 0°/360° seam of a whole turn are one;
    the dyad is the one whose transmission angle vanishes there (*toggles*, a
    :class:`~mechcli.core.linkage.kinematics.Toggle` list), or the linkage's only dyad.
    A one-position interval is named by its refined dead point (*dead_points*, a
    :class:`~mechcli.core.linkage.kinematics.DeadPoint` list) where there is one, else
    by its middle.

    Returns ``[(reason, joint or None, [(a, b) or (x,) ...])]``: one group per reason
    and dyad, in the order of their first position, each in order of the input.
    """
    inp = spec.input
    span = inp.stop - inp.start
    items = sorted((float(a), float(b), why) for a, b, why in intervals)
    if not items:
        return []
    # touching intervals of the same reason are one
    merged = [list(items[0])]
    for a, b, why in items[1:]:
        if why == merged[-1][2] and a - merged[-1][1] <= 1e-9 * max(1.0, abs(span)):
            merged[-1][1] = max(merged[-1][1], b)
        else:
            merged.append([a, b, why])
    wrap = None   # an interval through the seam: (a, b + span)
    if inp.periodic and len(merged) > 1:
        first, last = merged[0], merged[-1]
        tol = 1e-9 * max(1.0, abs(span))
        if first[2] == last[2] and abs(first[0] - inp.start) <= tol \
                and abs(last[1] - inp.stop) <= tol:
            merged = merged[:-1]
            wrap = (last[0], first[1])
            merged[0] = [last[0] - span, first[1], first[2]]
    point_tol = 1e-5 * abs(span)
    only = _dyads(spec)
    groups = {}
    for a, b, why in merged:
        near = [t for t in toggles
                if a - point_tol <= t.at <= b + point_tol
                or (inp.periodic and a < inp.start
                    and a + span - point_tol <= t.at)]
        if near:
            joint = min(near, key=lambda t: t.sin_gamma).joint
        else:
            joint = only[0] if len(only) == 1 else None
        if b - a <= point_tol:
            x = next((d.at for d in dead_points if a - d.tol <= d.at <= b + d.tol),
                     0.5 * (a + b))
            item = (inp.start if inp.periodic and abs(x - inp.start) <= point_tol else x,)
        elif wrap is not None and a < inp.start:
            item = (wrap[0], wrap[1], "seam")
        else:
            item = (a, b)
        groups.setdefault((why, joint), []).append(item)
    return [(why, joint, pts) for (why, joint), pts in groups.items()]


def _why_words(why, lang):
    """An excluded interval's reason (``cannot assemble``, ``dead point``) in *lang*."""
    return say(lang, f"kin.why_{why.replace(' ', '_')}")


def _one_position_words(why, n, lang="en"):
    """``dead point(s)`` or ``limit(s) of assembly``: a group of *n* single positions (a
    ``cannot assemble`` interval of no width is the sweep ending on a limit of assembly,
    docs/accuracy.md §4)."""
    return say(lang, f"kin.{'many' if n > 1 else 'one'}_{why.replace(' ', '_')}")


def _item_text(spec, item, seam_note=True):
    if len(item) == 1:
        return input_value(spec, item[0])
    text = f"{input_value(spec, item[0])} … {input_value(spec, item[1])}"
    if len(item) == 3 and seam_note:   # through the seam of a whole turn
        text += f" (through {input_value(spec, spec.input.start)})"
    return text


def singular_text(spec, why, joint, items):
    """One group of :func:`singular_groups` in words: ``dead points at θ1 = 0°, 180°
    (dyad C)``, ``cannot assemble for input angle θ1 = 352.1° … 7.9° (through 0°;
    dyad C)``."""
    sym = input_symbol(spec)
    where = ", ".join(_item_text(spec, it, seam_note=False) for it in items)
    notes = [f"through {input_value(spec, spec.input.start)}"] \
        if any(len(it) == 3 for it in items) else []
    notes += [f"dyad {joint}"] if joint else []
    dyad = f" ({'; '.join(notes)})" if notes else ""
    if all(len(it) == 1 for it in items):
        return f"{_one_position_words(why, len(items))} at {sym} = {where}{dyad}"
    what = "input angle" if spec.input.rotary else "input"
    return f"{why} for {what} {sym} = {where}{dyad}"


def excluded_warnings(spec, excluded, toggles=(), dead_points=()):
    """One line per group of input positions left out of the analysis
    (``partial = true``), merged, rounded and in order (:func:`singular_groups`).

    *excluded* holds ``(start, stop, reason)`` in core units (rad or m).
    """
    return [f"{singular_text(spec, *g)}: excluded from the analysis"
            for g in singular_groups(spec, excluded, toggles, dead_points)]


def located(spec, x, tol):
    """An input *x* with its uncertainty *tol* [rad or m], with as many decimals as the
    uncertainty allows (at least those of :func:`input_value`): ``180° ± 1e-11°``."""
    f = input_factor(spec)
    t = abs(tol * f)
    suffix = input_suffix(spec)
    digits = 4 if spec.input.rotary else 6
    if t > 0:
        digits = max(digits, min(15, math.ceil(-math.log10(t))))
    text = f"{round(x * f, digits) + 0.0:.{digits}f}".rstrip("0").rstrip(".")
    return f"{text}{suffix} ± {t:.0e}{suffix}"


def dead_point_results(spec, result):
    """JSON of the refined dead points (:class:`~mechcli.core.linkage.kinematics.DeadPoint`):
    ``dead_points_deg`` and ``dead_points_tol_deg`` (input and its uncertainty, lists in
    order), ``dead_points`` (``{at, tol, joint, dyad, shape}``), and ``excluded_tol_deg``:
    how closely each end of every ``excluded`` interval is located (``[tol_start,
    tol_stop]``; the ends of a ``cannot assemble`` interval are the roots of the dyad's
    discriminant).  ``deg`` is the spec's length unit for a slider input."""
    fin = input_factor(spec)
    at_u = "deg" if spec.input.rotary else spec.header.unit
    deads = getattr(result, "dead_points", []) or []
    return {
        f"dead_points_{at_u}": [d.at * fin for d in deads],
        f"dead_points_tol_{at_u}": [d.tol * fin for d in deads],
        "dead_points": [{"at": d.at * fin, "tol": d.tol * fin, "joint": d.joint,
                         "dyad": d.kind, "shape": d.shape} for d in deads],
        f"excluded_tol_{at_u}": [[a * fin, b * fin]
                                 for a, b in getattr(result, "excluded_tol", []) or []],
    }


def dead_point_note(spec, result, lang="en"):
    """One line naming every refined dead point with its uncertainty, or None."""
    deads = getattr(result, "dead_points", []) or []
    if not deads:
        return None
    sym = input_symbol(spec)
    parts = [f"{sym} = {located(spec, d.at, d.tol)} ({say(lang, 'kin.dyad', joint=d.joint)})"
             for d in deads]
    return say(lang, "kin.dead_points", points=", ".join(parts))


def assembly_message(spec, exc):
    """The user's wording of an :class:`~mechcli.core.errors.AssemblyError`: the
    intervals in the spec's input unit, merged and rounded, and the key that
    analyses the rest."""
    if not exc.intervals:
        return str(exc)
    text = "; ".join(singular_text(spec, *g) for g in singular_groups(spec, exc.intervals))
    if not getattr(spec.input, "partial", False):
        text += " (set input.partial = true to analyse the feasible ranges only)"
    hint = degrees_hint(spec)
    if hint:
        text += f"; {hint}"
    return ("fewer than two input positions can be analysed: " + text) if exc.too_few else text


#: an input range whose ends are all within a turn in radians (2π = 6.2832...)
_RADIAN_LIKE = 2 * math.pi * 1.02


def degrees_hint(spec):
    """A hint when a crank's range looks like radians (``stop = 6.2``), else ''."""
    inp = spec.input
    if not inp.rotary:
        return ""
    start, stop = math.degrees(inp.start), math.degrees(inp.stop)
    if max(abs(start), abs(stop)) > _RADIAN_LIKE:
        return ""
    return (f"the input range is only {stop - start:.4g}° ([input] start = {start:g}, "
            f"stop = {stop:g}): angles are in degrees (a whole turn is stop = "
            f"{start + 360:g})")


def warnings(spec, result, accuracy_warn=None):
    """The warnings of a ``kin`` run: excluded input intervals, extremes that
    grow without bound towards a dead point, and ranges that keep fewer than
    ``accuracy_warn`` (default: the spec's ``output.accuracy_warn``) correct digits."""
    hint = degrees_hint(spec)
    return ([hint] if hint else []) + excluded_warnings(spec, result.excluded, result.toggles,
                                                        result.dead_points) \
        + unbounded_warnings(spec, result.extremes, result.excluded) \
        + accuracy_warnings(spec, result.accuracy, _threshold(spec, accuracy_warn))


def _singular_kind(x, excluded):
    """What an unbounded extreme at input *x* [rad or m] grows towards: the ``dead point``
    or the ``limit of assembly`` (a ``cannot assemble`` interval's end) of the excluded
    interval nearest to it."""
    best = None
    for a, b, why in excluded or ():
        d = min(abs(x - a), abs(x - b))
        if best is None or d < best[0]:
            best = (d, why)
    return "dead point" if best is not None and best[1] == "dead point" else \
        "limit of assembly"


def unbounded_warnings(spec, extremes, excluded=()):
    """One line per set of dead points or limits of assembly that quantities grow without
    bound towards: ``omega2, omega3 grow without bound towards the limits of assembly at
    θ1 = 104.5597°, 255.4403°`` (the quantities that share the same positions merged, in
    order of the input).  *excluded* (the result's ``(start, stop, reason)``) tells a dead
    point (reason ``dead point``) from a limit of assembly (an end of a ``cannot assemble``
    interval: the linkage does not assemble beyond it); without it every position is
    called a limit of assembly."""
    towards = {}
    for sym, pair in extremes.items():
        ats = sorted({(input_value(spec, e.at), _singular_kind(e.at, excluded)): e.at
                      for e in pair if not e.bounded}.items(), key=lambda kv: kv[1])
        for kind in ("dead point", "limit of assembly"):
            these = [(t, x) for (t, k), x in ats if k == kind]
            if these:
                key = (kind, tuple(t for t, _ in these))
                towards.setdefault(key, (these[0][1], []))[1].append(sym)
    out = []
    for (kind, ats), (_first, syms) in sorted(towards.items(),
                                              key=lambda kv: (kv[1][0], -len(kv[0][1]))):
        verb = "grows" if len(syms) == 1 else "grow"
        what = _one_position_words("cannot assemble" if kind != "dead point" else kind,
                                   len(ats))
        out.append(f"{', '.join(syms)} {verb} without bound towards the {what} "
                   f"at {input_symbol(spec)} = {', '.join(ats)}")
    return out


def _threshold(spec, accuracy_warn):
    return spec.output.accuracy_warn if accuracy_warn is None else accuracy_warn


def accuracy_warnings(spec, accuracy, threshold):
    """One line per continuous input range where a class of results (positions,
    velocities, accelerations, forces) keeps fewer than *threshold* correct
    significant digits (estimated; see docs/accuracy.md)."""
    if accuracy is None:
        return []
    out = []
    sym = input_symbol(spec)
    for r in accuracy.ranges(threshold):
        a, b = input_value(spec, r.start), input_value(spec, r.stop)
        if a == b:
            where = f"at {sym} = {input_value(spec, r.at)}"
        else:
            where = f"for {sym} = {a} … {b} (fewest at {input_value(spec, r.at)})"
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


def approx_results(spec, approx):
    """JSON of ``model = "approximate"``: the model and the largest differences of
    the series to the exact slider-crank over the sweep, in the spec's units
    (``approx_error_s_max_mm`` ...) and relative (``..._rel``: s to the exact
    stroke, v and a to the largest exact |v| and |a|)."""
    if approx is None:
        return {}
    out = {"model": "approximate"}
    for key, kind in (("s", "length"), ("v", "velocity"), ("a", "acceleration")):
        diff, rel = approx[key]
        out[f"approx_error_{key}_max_{unit_of(kind, spec.header.unit)}"] = \
            diff * factor_of(kind, spec.header.scale)
        out[f"approx_error_{key}_max_rel"] = rel
    return out


def scalar_results(spec, quantities, result, accuracy_warn=None, approx=None):
    """``--json`` results: extremes (with input angles, the tolerance of the
    refinement and the grid error), strokes, swings, flags, estimated accuracy;
    with *approx* (``model = "approximate"``) the differences to the exact model."""
    unit, scale = spec.header.unit, spec.header.scale
    fin = input_factor(spec)
    at_unit = "deg" if spec.input.rotary else unit
    out = {"positions": int(result.q.size)}
    out.update(approx_results(spec, approx))
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
                if not e.constant:   # a quantity constant to round-off: no location
                    out[f"{q.symbol}_{name}_at_{at_unit}"] = e.at * fin
                    # how closely the refinement located it, and what reading it off
                    # the CSV rows would cost (refined extreme minus best sample)
                    out[f"{q.symbol}_{name}_at_{at_unit}_tol"] = e.tol * fin
                best = np.max(samples) if name == "max" else np.min(samples)
                out[f"{q.symbol}_{name}_grid_error_{u}"] = \
                    0.0 if e.constant else float(e.value - best) * f + 0.0
            else:
                unbounded.append({"quantity": f"{q.symbol}_{name}", "towards": e.at * fin})
        if q.kind == "length" and q.symbol.startswith("s"):
            out[f"{q.symbol}_stroke_{u}"] = (hi.value - lo.value) * f
        if q.kind == "angle" and q.symbol.startswith("theta"):
            out[f"{q.symbol}_swing_deg"] = (hi.value - lo.value) * f
    out.update(slider_results(spec, quantities, result, approx))
    out["unbounded"] = unbounded
    out["excluded"] = [[a * fin, b * fin, why] for a, b, why in result.excluded]
    out.update(dead_point_results(spec, result))
    out["toggles"] = [{"at": t.at * fin, "joint": t.joint, "dyad": t.kind,
                       "gamma_deg": math.degrees(math.asin(min(1.0, t.sin_gamma)))}
                      for t in result.toggles]
    out["accuracy"] = accuracy_results(result.accuracy, _threshold(spec, accuracy_warn))
    if spec.linkage.structure is not None:   # a linkage given by its joints
        from mechcli.report.structure import structure_results
        out.update(structure_results(spec.linkage.structure))
    return out


def _is_slide(q):
    return bool(q.source) and q.source[0] == "slide"


def slider_results(spec, quantities, result, approx=None):
    """Named results of every slider (slide) output: where it moves fastest
    in each direction and where its acceleration is 0.

    * ``<v>_max_forward_<u>``, ``..._at_<deg>``, ``..._at_<deg>_tol``: the greatest
      speed while s grows (the refined ``<v>_max``, when it is > 0);
    * ``<v>_max_backward_<u>`` (a speed, > 0), ``..._at_<deg>``, ``..._tol``: while s
      falls (minus the refined ``<v>_min``, when it is < 0);
    * ``<a>_zero_at_<deg>`` and ``<a>_zero_at_<deg>_tol``: every input where the
      acceleration is 0, in order (not for ``model = "approximate"``, whose series
      acceleration is not the engine's).
    """
    unit, scale = spec.header.unit, spec.header.scale
    fin = input_factor(spec)
    at_unit = "deg" if spec.input.rotary else unit
    zeros = getattr(result, "zeros", {}) or {}
    out = {}
    for q in quantities:
        if not _is_slide(q):
            continue
        u = unit_of(q.kind, unit)
        f = factor_of(q.kind, scale)
        if q.kind == "velocity" and q.symbol in result.extremes:
            hi, lo = result.extremes[q.symbol]
            for name, e, sign in (("forward", hi, 1.0), ("backward", lo, -1.0)):
                if e.bounded and sign * e.value > 0:
                    out[f"{q.symbol}_max_{name}_{u}"] = sign * e.value * f
                    if not e.constant:
                        out[f"{q.symbol}_max_{name}_at_{at_unit}"] = e.at * fin
                        out[f"{q.symbol}_max_{name}_at_{at_unit}_tol"] = e.tol * fin
        if q.kind == "acceleration" and q.symbol in zeros and approx is None:
            out[f"{q.symbol}_zero_at_{at_unit}"] = [a * fin for a, _t in zeros[q.symbol]]
            out[f"{q.symbol}_zero_at_{at_unit}_tol"] = [t * fin for _a, t in zeros[q.symbol]]
    return out


def slider_note(spec, quantities, result, lang="en", approx=None):
    """One line per slider: its greatest speed each way and where its acceleration is 0."""
    res = slider_results(spec, quantities, result, approx)
    unit = spec.header.unit
    sym = input_symbol(spec)
    at_unit = "deg" if spec.input.rotary else unit
    lines = []
    for q in quantities:
        if not (_is_slide(q) and q.kind == "velocity"):
            continue
        u = unit_of(q.kind, unit)
        parts = []
        for name in ("forward", "backward"):
            base = f"{q.symbol}_max_{name}"
            if f"{base}_{u}" in res:
                at = input_value(spec, res[f"{base}_at_{at_unit}"] / input_factor(spec))
                parts.append(say(lang, "kin.slider_speed", value=f"{res[f'{base}_{u}']:.6g}",
                                 unit=pretty_unit(q.kind, unit),
                                 way=say(lang, f"kin.slider_{name}"), sym=sym, at=at))
        acc = "a" + q.symbol[1:]
        zeros = res.get(f"{acc}_zero_at_{at_unit}")
        if not parts and not zeros:
            continue
        text = say(lang, "kin.slider", n=q.symbol[1:], speeds=", ".join(parts))
        if zeros:
            where = ", ".join(input_value(spec, z / input_factor(spec)) for z in zeros)
            text += say(lang, "kin.slider_zero", acc=acc, sym=sym, where=where)
        lines.append(text)
    return lines


def pretty_unit(kind, length_unit):
    u = unit_of(kind, length_unit)
    return _PRETTY_UNIT.get(u, u.replace("_s2", "/s²").replace("_s", "/s"))


def _label(q, unit, lang):
    """The header of quantity *q*: ``θ3/(°)``, ``vxF/(mm/s)``; in Chinese with its
    name first, ``角速度 ω3/(rad/s)``."""
    key = next((k for k in _NAMED if q.symbol.startswith(k)), None)
    name = say(lang, f"kin.name_{key}") if key else ""
    return header(greek(q.symbol, q.kind), pretty_unit(q.kind, unit), name)


#: the table header of a quantity, ``quantity_label(q, "mm", "en")`` (mechcli.notebook's tables)
quantity_label = _label


def table_rows(spec, result, step):
    """Indices of the analysed positions closest to every ``step`` of the input."""
    q = result.q
    targets = np.arange(spec.input.start, spec.input.stop + step * 1e-9, step)
    idx = np.searchsorted(q, targets)
    idx = np.clip(idx, 0, q.size - 1)
    left = np.clip(idx - 1, 0, q.size - 1)
    idx = np.where(np.abs(q[left] - targets) < np.abs(q[idx] - targets), left, idx)
    keep = np.abs(q[idx] - targets) <= 0.5 * step
    # distinct sorted indices; np.unique would import numpy.ma (~7 ms of start-up)
    idx = np.sort(idx[keep])
    return idx[np.concatenate(([True], idx[1:] != idx[:-1]))] if idx.size else idx


def _extreme_tol(result):
    """The largest refinement tolerance of the bounded extremes [rad or m] (of the
    quantities that are not constant to round-off)."""
    tols = [e.tol for pair in result.extremes.values() for e in pair
            if e.bounded and not e.constant]
    return max(tols) if tols else 0.0


def _grid_error_note(spec, quantities, result, lang):
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
                worst, sym = abs(e.value - best) / peak, greek(q.symbol, q.kind)
    if sym is None:
        return None
    step = (result.q[1] - result.q[0]) * input_factor(spec) if result.q.size > 1 else 0.0
    if getattr(spec.input, "count", 0):   # streamed: the CSV has every row, finer than q's
        step = (spec.input.stop - spec.input.start) / (spec.input.count - 1) * input_factor(spec)
    at_u = input_suffix(spec)
    return say(lang, "kin.grid_error", step=f"{step:g}", unit=at_u, error=f"{worst:.1e}", sym=sym)


def build_report(spec, quantities, result, lang="en", approx=None):
    """The book-style text report: table every ``table_step``, extremes, flags;
    with *approx* (``model = "approximate"``) a note of the model and its differences."""
    unit, digits = spec.header.unit, spec.output.digits
    fin = input_factor(spec)
    cols = columns(spec, quantities, result)
    headers = [input_header(spec, lang)] + [_label(q, unit, lang) for q in quantities]
    rows = []
    for i in table_rows(spec, result, spec.output.table_step):
        rows.append([fixed(cols[0][1][i], 2)] + [fixed(c[1][i], digits) for c in cols[1:]])
    report = Report(title=book_title(spec.header.title))
    if spec.linkage.structure is not None:   # given by its joints: the book's 杆组分解 first
        from mechcli.report.structure import structure_block
        report.blocks.append(structure_block(lang, spec.linkage.structure, spec.linkage.frame))
    step_txt = f"{spec.output.table_step * fin:g}"
    report.blocks.append(Block(
        heading=say(lang, "kin.results_rotary" if spec.input.rotary else "kin.results_slider",
                    step=step_txt, unit=unit),
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
            if e.constant:   # constant to round-off: no location
                cells += [fixed(e.value * f, digits), say(lang, "common.constant")]
            elif e.bounded:
                cells += [fixed(e.value * f, digits), fixed(e.at * fin, 4)]
            else:
                cells += [say(lang, "kin.unbounded"), "→ " + fixed(e.at * fin, 4)]
        ext_rows.append(cells)
    if ext_rows:
        report.blocks.append(Block(
            heading=say(lang, "kin.extremes", tol=f"{_extreme_tol(result) * fin:.0e}",
                        unit=input_suffix(spec)),
            headers=[say(lang, "common.quantity"), say(lang, "common.max"),
                     header(say(lang, "common.at"), at_u), say(lang, "common.min"),
                     header(say(lang, "common.at"), at_u)],
            rows=ext_rows))
    report.blocks += flags_blocks(spec, result, lang)
    report.notes.append(say(lang, "common.positions", n=result.q.size)
                        + (f"; ω1 = {spec.input.omega:g} rad/s" if spec.input.rotary else ""))
    if approx is not None:
        report.notes.append(approx_note(spec, approx, lang))
    note = _grid_error_note(spec, quantities, result, lang)
    if note:
        report.notes.append(note)
    if result.accuracy is not None and result.accuracy.digits:
        report.notes.append(accuracy_note(result.accuracy, lang))
    note = dead_point_note(spec, result, lang)
    if note:
        report.notes.append(note)
    report.notes.extend(slider_note(spec, quantities, result, lang, approx))
    return report


def approx_note(spec, approx, lang="en"):
    """One line: the approximate model and its largest differences to the exact one."""
    unit = spec.header.unit
    parts = []
    for key, kind in (("s", "length"), ("v", "velocity"), ("a", "acceleration")):
        diff, rel = approx[key]
        parts.append(f"{key} {diff * factor_of(kind, spec.header.scale):.4g} "
                     f"{pretty_unit(kind, unit)} ({rel:.2%})")
    return say(lang, "kin.approx", diffs=", ".join(parts))


def flags_blocks(spec, result, lang="en"):
    """The ``Flags`` block: the excluded positions merged and grouped by reason and
    dyad (:func:`singular_groups`), then the near-dead positions they do not
    already name, each once and rounded."""
    flags = []
    groups = singular_groups(spec, result.excluded, result.toggles, result.dead_points)
    for why, joint, items in groups:
        if all(len(it) == 1 for it in items):
            label = _one_position_words(why, len(items), lang)
        else:
            label = _why_words(why, lang)
        if joint:
            label += f" ({say(lang, 'kin.dyad', joint=joint)})"
        flags.append([label, ", ".join(_item_text(spec, it) for it in items)])
    span = abs(spec.input.stop - spec.input.start)
    tol = 1e-5 * span
    seen = set()
    for t in result.toggles:
        if any(a - tol <= t.at <= b + tol for a, b, _ in result.excluded):
            continue
        at = input_value(spec, t.at)
        if (t.joint, at) in seen:
            continue
        seen.add((t.joint, at))
        g = math.degrees(math.asin(min(1.0, t.sin_gamma)))
        flags.append([say(lang, "kin.near_dead") + f" ({t.kind} {t.joint})",
                      f"{input_symbol(spec)} = {at}, γ = {g:.4f}°"])
    return [Block(heading=say(lang, "kin.flags"), rows=flags)] if flags else []


def accuracy_note(accuracy, lang="en"):
    """One line: the fewest estimated correct significant digits of each class."""
    words = table(lang, "kin")
    parts = ", ".join(f"{words.get(f'digits_{k}', k)} {v:.1f}"
                      for k, v in accuracy.minimum().items())
    return say(lang, "kin.accuracy", digits=parts)
