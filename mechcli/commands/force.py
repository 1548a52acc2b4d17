"""``mechcli force``: kinetostatic analysis of a planar linkage (chapter 2)."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options, export_option


@click.command("force")
@click.argument("spec_path", metavar="SPEC.toml")
@click.option("--accuracy-warn", "accuracy_warn", type=click.FloatRange(0.0, 16.0),
              default=None, metavar="DIGITS",
              help="Warn where fewer correct significant digits than this remain "
                   "(estimated; default: the spec's output.accuracy_warn, 8).")
@export_option
@common_options
def force(spec_path, accuracy_warn=None, **opts):
    """Kinetostatics (动态静力分析) of any linkage of `kin`: pair reactions, the
    balancing torque, shaking force and moment, checked by the power balance."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.report import force as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.force import load_force_spec

    spec = load_force_spec(spec_path, run.sets)
    sweep = spec.input.sweep()
    result, extra, (pipe, approx) = solve(spec, sweep)
    outputs = Outputs(run.out_dir, digits=run.digits)
    switches = _switch_rows(spec, sweep, result, pipe, approx)
    from mechcli.report.force_rows import csv_columns  # both sides of every load switch
    outputs.csv("force.csv", csv_columns(spec, result, extra, switches))
    warnings = report.warnings(spec, result, accuracy_warn)
    fin = report.input_factor(spec)
    warnings += [f"output.at = {x * fin:g}: the linkage is not regular there (no values)"
                 for x in spec.output.at if float(x) not in extra.at]
    animate = spec.output.animate if run.animate is None else run.animate
    if (run.plot and spec.output.plots) or animate:
        from mechcli.report import force_plots
        warnings += force_plots.write(spec, result, sweep, outputs, run.lang,
                                      plots=run.plot and spec.output.plots, animate=animate,
                                      engine=extra.engine, switches=switches)
    if run.export:
        from mechcli.commands.kin import export_linkage
        warnings += export_linkage(run, outputs, "force", spec, sweep, result.kin.motion,
                                   result.kin.runs)
    finish(run, "force", report.build_report(spec, result, run.lang, extra),
           report.scalar_results(spec, result, accuracy_warn, extra), outputs, warnings)


def solve(spec, sweep):
    """The force pipeline of a read spec over *sweep*: the analysis (its extremes
    located no closer than round-off allows, its mean split at the loads' kinks) and
    the extra results (engine quantities, values at ``output.at``, the approximate
    model's differences), with the kinetostatics at any input it built once (the loads'
    stroke bands fixed) and the approximate model's terms.  ``optimize``'s
    ``result`` goals call it too, so they see what ``force`` reports."""
    from mechcli.core.errors import AssemblyError
    from mechcli.core.linkage.force_analysis import analyse_forces
    from mechcli.core.linkage.load_switches import split_mean
    from mechcli.report import force as report

    inp = spec.input
    bodies, loads, approx = spec.bodies, spec.loads, None
    if spec.model == "approximate":
        from mechcli.core.linkage import approximate
        bodies, loads, approx = approximate.force_model(spec.piston, bodies, loads,
                                                        spec.gravity, inp.omega, inp.alpha)
    try:
        result = analyse_forces(spec.linkage, spec.topology, sweep, bodies, spec.gravity,
                                loads, partial=inp.partial)
    except AssemblyError as exc:   # worded in the spec's units
        raise AssemblyError(report.assembly_message(spec, exc), exc.intervals) from None
    result = _located(sweep, result)
    pipe = _evaluator(spec, sweep, result, bodies, loads)
    split = split_mean(pipe, result)
    if split is not None:   # the loads' kinks as split points of the mean
        import dataclasses
        result = dataclasses.replace(result, mean=split[0], rms=split[1])
    extra = _extra_results(spec, sweep, result, pipe, approx)
    return result, extra, (pipe, approx)


def _located(sweep, result):
    """The sweep with each extreme's input tolerance no smaller than what the round-off
    of the compared values allows at the curvature there
    (core.linkage.piston.located_within): a flat extreme is located less closely."""
    import dataclasses

    from mechcli.core.linkage.piston import located_within, noise_level
    q = result.q
    if q.size < 3:
        return result
    periodic = bool(sweep.periodic and not result.kin.excluded)
    noise = noise_level({k: v for k, v in result.series.items() if k != "P"})
    ext = {}
    for sym, pair in result.extremes.items():
        ext[sym] = tuple(dataclasses.replace(e, tol=located_within(
            q, result.series[sym], e.at, e.tol, noise, periodic)) if e.tol < 0.5 * float(
                q[1] - q[0]) else e for e in pair)
    return dataclasses.replace(result, extremes=ext)


def _piston_mass(spec):
    """The mass of the piston's link [kg] (0 without a body)."""
    body = spec.bodies.get(spec.piston.link)
    return float(body.mass) if body is not None else 0.0


def _switch_rows(spec, sweep, result, pipe, approx):
    """The forces on both sides of every load switch (core.linkage.load_switches), with
    the engine's named series when there is a piston; None without a switch."""
    from mechcli.core.linkage import piston as engine
    from mechcli.core.linkage.load_switches import switch_rows

    pst = spec.piston
    mass = _piston_mass(spec) if pst is not None else 0.0

    def engine_series(pipe, x):
        return engine.engine_at(pst, spec.topology, pipe, x, mass, approx)[1]
    more = engine_series if pst is not None else None
    periodic = bool(sweep.periodic and not result.kin.excluded)
    return switch_rows(pipe, result, periodic, more)


def _evaluator(spec, sweep, result, bodies, loads):
    """The kinetostatics at any input, with the sweep's stroke bands fixed."""
    import dataclasses

    from mechcli.core.linkage.force_analysis import ForceEvaluator
    progs = tuple(dataclasses.replace(p, band_limits=result.band[p.load.name])
                  if p.load.name in result.band else p for p in loads)
    return ForceEvaluator(spec.linkage, spec.topology, sweep, bodies, spec.gravity, progs)


def _extra_results(spec, sweep, result, pipe, approx):
    """The engine's named results, the values at ``output.at`` and, for the
    approximate model, the exact model's values (see report.force.Extra)."""
    import numpy as np

    from mechcli.core.linkage import piston as engine
    from mechcli.core.linkage.force_analysis import series_of
    from mechcli.report.force import Extra

    pst = spec.piston
    mass = _piston_mass(spec) if pst is not None else 0.0
    periodic = bool(sweep.periodic and not result.kin.excluded)
    eng = None
    if pst is not None:
        eng = engine.analyse_engine(pst, spec.topology, pipe, result.q, result.forces,
                                    result.kin.motion, mass, approx, periodic)
    at = {}
    if spec.output.at:
        x = np.asarray(spec.output.at, dtype=float)
        fr, _m, motion = pipe(x)
        ser = dict(series_of(spec.linkage, fr))
        if pst is not None:
            _fr, es = engine.engine_at(pst, spec.topology, pipe, x, mass, approx)
            ser.update(es)
        ok = np.asarray(motion.regular, dtype=bool)
        at = {float(v): {k: float(np.asarray(s)[i]) for k, s in ser.items()}
              for i, v in enumerate(x) if ok[i]}
    exact = None
    if approx is not None:
        # the exact model at the analysed positions: the largest differences
        ex = _evaluator(spec, sweep, result, spec.bodies, spec.loads)
        fr, _m, motion = ex(result.q)
        exact = dict(series_of(spec.linkage, fr))
        exact.update(engine.engine_series(pst, spec.topology, fr, motion,
                                          engine.gas_force(pst, ex.programs, result.q,
                                                           motion), None, mass))
    return Extra(eng, at, exact)
