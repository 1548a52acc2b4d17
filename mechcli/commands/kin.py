"""``mechcli kin``: positions, velocities and accelerations of a planar linkage."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options


@click.command("kin")
@click.argument("spec_path", metavar="SPEC.toml")
@click.option("--accuracy-warn", "accuracy_warn", type=click.FloatRange(0.0, 16.0),
              default=None, metavar="DIGITS",
              help="Warn where fewer correct significant digits than this remain "
                   "(estimated; default: the spec's output.accuracy_warn, 8).")
@common_options
def kin(spec_path, accuracy_warn=None, **opts):
    """Kinematics of a planar linkage (chapter 1): four-bar, slider-crank,
    guide-bar, shaper or any linkage of drivers and RRR/RRP/RPR/PRP dyads."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.core.errors import AssemblyError
    from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
    from mechcli.report import kin as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.kin import load_kin_spec

    spec = load_kin_spec(spec_path, run.sets)
    inp = spec.input
    sweep = inp.sweep()
    quantities = default_quantities(spec.linkage, spec.output.order,
                                    [t.name for t in spec.tracers])
    try:
        result = analyse_sweep(spec.linkage, sweep, quantities, spec.output.order,
                               partial=inp.partial)
    except AssemblyError as exc:   # worded in the spec's units
        raise AssemblyError(report.assembly_message(spec, exc), exc.intervals) from None
    approx = None
    if spec.mechanism == "slider_crank" and _model(spec_path, run.sets) == "approximate":
        from mechcli.core.linkage import approximate
        result, approx = approximate.apply(spec.linkage, sweep, result)
    outputs = Outputs(run.out_dir, digits=run.digits)
    outputs.csv("kin.csv", report.columns(spec, quantities, result))
    warnings = []
    animate = spec.output.animate if run.animate is None else run.animate
    if (run.plot and spec.output.plots) or animate:
        from mechcli.report import kin_plots
        warnings += kin_plots.write(spec, quantities, result, sweep, outputs, run.lang,
                                    plots=run.plot and spec.output.plots, animate=animate)
    warnings += report.warnings(spec, result, accuracy_warn)
    finish(run, "kin", report.build_report(spec, quantities, result, run.lang, approx),
           report.scalar_results(spec, quantities, result, accuracy_warn, approx), outputs,
           warnings)


def _model(spec_path, sets):
    """``[mechanism] model`` of a slider-crank spec (validated by the spec reader)."""
    from mechcli.spec.reader import load_spec
    mech = load_spec(spec_path, sets).data.get("mechanism", {})
    return mech.get("model", "exact") if isinstance(mech, dict) else "exact"
