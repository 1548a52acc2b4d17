"""Results, book-format report, ``history.csv`` and ``optimum.toml`` of
``mechcli optimize``.  Solves nothing.

Numbers are shown in the problem's own numbers: design variables as the
spec writes them (its length unit, degrees), constraint values ``g`` (<= 0
satisfied) in degrees for angles and in the length unit for lengths, the
objective ``f`` in rad (rad² for a sum of squares) for function generation and
in the length unit (squared) for paths, as the book prints 例 7-1's f = 0.0076.
"""

from __future__ import annotations

import math

from mechcli.report.table import Block, Report, book_title
from mechcli.report.words import say


def _unit_name(spec):
    return spec.header.unit


def f_scale(spec):
    """(factor, unit text): f in the core's SI numbers times factor = f shown."""
    obj = spec.objective
    sq = obj.get("measure") == "sum_squares"
    if obj["kind"] == "path":
        k = 1.0 / spec.unit
        return (k * k if sq else k), (f"{_unit_name(spec)}^2" if sq else _unit_name(spec))
    if obj["kind"] == "pressure_angle":
        return (-180 / math.pi if obj["goal"] == "maximize" else 180 / math.pi), "deg"
    if obj["kind"] == "function":
        if isinstance(obj["output"], str):      # a slide's deviations [m] in the length unit
            k = 1.0 / spec.unit
            return (k * k if sq else k), (f"{_unit_name(spec)}^2" if sq else _unit_name(spec))
        return 1.0, ("rad^2" if sq else "rad")
    return (-1.0 if obj["goal"] == "maximize" else 1.0), "as the result"


def _g_shown(spec, problem, g):
    """Constraint values in display units (deg for angles, the length unit)."""
    out = []
    for name, v in zip(problem.constraint_names, g):
        if name.startswith("gamma"):
            out.append(math.degrees(float(v)))
        elif name in ("g1", "g2", "g3", "g4", "g5", "g6"):
            out.append(float(v) / spec.unit)
        else:
            out.append(float(v))
    return out


def results(spec, problem, result, details):
    """The JSON results (names from the issue; stable)."""
    k, unit = f_scale(spec)
    r = {"x": {v.name: float(x) for v, x in zip(problem.variables, result.x)},
         "f": float(result.f) * k, "f_unit": unit,
         "constraints": {name: {"value": val, "active": bool(act)}
                         for name, val, act in zip(problem.constraint_names,
                                                   _g_shown(spec, problem, result.g),
                                                   result.active)},
         "iterations": int(result.iterations), "evaluations": int(result.evaluations),
         "time_s": float(result.time_s), "method": result.method,
         "success": bool(result.success), "feasible": bool(result.feasible),
         "message": result.message}
    if "dev" in details:
        dev = details["dev"][0]
        angle = not isinstance(spec.objective["output"], str)
        r["deviation_max_deg" if angle else "deviation_max"] = float(
            max(abs(float(d)) for d in dev) * (180 / math.pi if angle else 1.0 / spec.unit))
        r["phi0_deg"] = math.degrees(float(details["phi0"][0]))
    if "dist" in details:
        r["distance_max"] = float(details["dist"][0].max()) / spec.unit
        r["distance_rms"] = float((details["dist"][0] ** 2).mean() ** 0.5) / spec.unit
    if details.get("exact") is not None:
        # 例 7-2: the golden section's maximum beside cam's exact refinement
        ex = details["exact"]
        r["alpha_max_deg"] = r["f"]
        r["delta_deg"] = float(result.x[0])
        r["alpha_exact_deg"] = math.degrees(ex.value)
        r["delta_exact_deg"] = math.degrees(ex.delta)
        r["delta_error_deg"] = float(result.x[0]) - math.degrees(ex.delta)
        r["alpha_error_deg"] = r["f"] - math.degrees(ex.value)
    if result.starts:
        r["starts"] = len(result.starts)
    return r


def history_columns(spec, result):
    import numpy as np
    h = result.history
    k, _ = f_scale(spec)
    cols = [("iteration", np.array([r.iteration for r in h], dtype=float)),
            ("evaluations", np.array([r.evaluations for r in h], dtype=float)),
            ("time_s", np.array([r.time_s for r in h])),
            ("f", np.array([r.f * k for r in h])),
            ("violation", np.array([r.violation for r in h])),
            # 0: the design could not be evaluated (its f is a placeholder 0)
            ("evaluable", np.array([1.0 if r.evaluable else 0.0 for r in h]))]
    for i, v in enumerate(spec.variables):
        cols.append((_column_name(v.key), np.array([r.x[i] for r in h])))
    return cols


def _column_name(key):
    return "x_" + key.replace(".", "_")


def optimum_toml(spec, result, data):
    """The problem's spec at the optimum (its tables ``data`` with the design's
    values set), runnable by its own command."""
    from mechcli.report.tomlout import dumps
    values = {v.key: float(x) for v, x in zip(spec.variables, result.x)}
    data = {"command": spec.problem, "title": f"{spec.header.title} (optimum)",
            **{k: v for k, v in data.items() if k not in ("command", "title")}}
    goal = [f"{k} = {v!r}" for k, v in values.items() if k.startswith("objective.")]
    note = (f"written by mechcli optimize from {spec.path.name}: {result.method}, "
            f"f = {result.f:.10g}" + (f"\n{', '.join(goal)} (the goal's origin)" if goal else ""))
    return dumps(data, note)


def warnings(spec, result, details=None):
    out = []
    if "DE itself stopped at maxiter" in result.message:
        out.append(f"differential evolution used all {spec.method.maxiter} generations "
                   f"without meeting tol = {spec.method.tol:g}; its best design was polished "
                   f"to a local optimum by SLSQP: a better optimum may exist (raise maxiter "
                   f"or popsize, or try other seeds)")
    ex = (details or {}).get("exact")
    if ex is not None:
        k, _ = f_scale(spec)
        found = float(result.f) * k
        exact = math.degrees(ex.value)
        if abs(found - exact) > 1e-6 * max(1.0, abs(exact)):
            out.append(f"the search found a local maximum {found:.6g} deg at "
                       f"{float(result.x[0]):.6g} deg; `mechcli cam` finds the largest, "
                       f"{exact:.6g} deg at {math.degrees(ex.delta):.6g} deg (narrow lo/hi "
                       f"around one maximum, or trust cam's refinement)")
    lo = [v for v, x in zip(spec.variables, result.x) if x <= v.lo + 1e-9 * max(1, abs(v.lo))]
    hi = [v for v, x in zip(spec.variables, result.x) if x >= v.hi - 1e-9 * max(1, abs(v.hi))]
    for v in lo:
        out.append(f"{v.key} ends at its lower bound {v.lo:g}: the optimum may lie beyond it")
    for v in hi:
        out.append(f"{v.key} ends at its upper bound {v.hi:g}: the optimum may lie beyond it")
    return out


def build_report(spec, problem, result, details, lang):
    rep = Report(book_title(spec.header.title))
    rows = [[v.key, f"{v.start:.6g}", f"{v.lo:.6g}", f"{v.hi:.6g}", f"{x:.6f}"]
            for v, x in zip(spec.variables, result.x)]
    rep.blocks.append(Block(say(lang, "optimize.variables"),
                            [say(lang, "optimize.variable"), say(lang, "optimize.start"),
                             say(lang, "optimize.lower"), say(lang, "optimize.upper"),
                             "x*"], rows))
    if problem.constraint_names:
        crow = [[n.replace("gamma_", "γ"), f"{g:.6g}", say(lang, "optimize.active") if a else ""]
                for n, g, a in zip(problem.constraint_names, _g_shown(spec, problem, result.g),
                                   result.active)]
        rep.blocks.append(Block(say(lang, "optimize.constraints"),
                                [say(lang, "optimize.constraint"), "g(x*)", ""], crow))
    r = results(spec, problem, result, details)
    kv = [[say(lang, "optimize.objective"), f"{r['f']:.6g} {r['f_unit'].replace('^2', '²')}"],
          [say(lang, "optimize.method"), result.method],
          [say(lang, "optimize.iterations"), str(result.iterations)],
          [say(lang, "optimize.evaluations"), str(result.evaluations)],
          [say(lang, "optimize.time"), f"{result.time_s:.3f}"],
          [say(lang, "optimize.converged"),
           say(lang, "optimize.yes" if result.success else "optimize.no")]]
    if "deviation_max_deg" in r:
        kv.append([say(lang, "optimize.deviation_max"),
                   f"{r['deviation_max_deg']:.4f}"])
        kv.append([say(lang, "optimize.phi0"), f"{r['phi0_deg']:.4f}"])
    if "alpha_exact_deg" in r:
        kv.append([say(lang, "optimize.alpha_exact"),
                   f"{r['alpha_exact_deg']:.6f} at {r['delta_exact_deg']:.6f}"])
        kv.append([say(lang, "optimize.delta_error"),
                   f"{r['delta_error_deg']:.2e}"])
    if "distance_max" in r:
        kv.append([say(lang, "optimize.distance_max", u=spec.header.unit),
                   f"{r['distance_max']:.6g}"])
    rep.blocks.append(Block(say(lang, "optimize.optimum"), rows=kv))
    return rep


def error_message(exc, spec, problem):
    """A core error of the optimization in words of the spec."""
    v, reason = exc.values, exc.reason
    if reason == "infeasible_start":
        what = ("cannot be evaluated (the linkage does not assemble over its range)"
                if not v.get("evaluable", True) else
                "violates " + ", ".join(v.get("violated", [])))
        return (f"[[variable]] start: the start {what}; {spec.method.name} needs "
                f"a feasible start: change the starts, or use name = \"differential_evolution\"")
    if reason == "infeasible":
        g = v.get("g")
        bad = ([f"{n} by {val:.3g}" for n, val, s in zip(problem.constraint_names,
                                                         _g_shown(spec, problem, g),
                                                         problem.scales)
                if val > 0] if g is not None else [])
        best = ", ".join(f"{var.name} = {x:.6g}" for var, x in zip(problem.variables,
                                                                 v.get("x", [])))
        other = ("" if spec.method.name == "differential_evolution"
                 else ", or try differential_evolution")
        return (f"[method] {spec.method.name} found no feasible design within the bounds "
                f"(the best, {best}, violates {', '.join(bad) or 'the constraints'}); widen "
                f"the bounds or relax the constraints{other}")
    if reason == "scalar":
        return (f"[method] name: {spec.method.name} searches one variable, the "
                f"spec has {v.get('n')}")
    if reason == "not_four_bar":
        return ("[[constraint]] kind = \"crank\": the book's g1...g6 need a "
                "four-bar (one crank and one RRR dyad)")
    return str(exc)


def convergence_message(exc, spec, problem):
    res = getattr(exc, "result", None)
    best = ""
    if res is not None:
        best = " (best so far: " + ", ".join(
            f"{v.name} = {x:.6g}" for v, x in zip(problem.variables, res.x)) + \
            f"; f = {res.f:.6g})"
    if "maxiter" in str(exc):
        return (f"[method] maxiter = {spec.method.maxiter}: {exc}{best}; raise "
                f"maxiter or loosen tol")
    return (f"[method] name = \"{spec.method.name}\": {exc}{best}; try another start, "
            f"method or tol")
