"""``mechcli force``: kinetostatic analysis of a planar linkage (chapter 2)."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options


@click.command("force")
@click.argument("spec_path", metavar="SPEC.toml")
@click.option("--accuracy-warn", "accuracy_warn", type=click.FloatRange(0.0, 16.0),
              default=None, metavar="DIGITS",
              help="Warn where fewer correct significant digits than this remain "
                   "(estimated; default: the spec's output.accuracy_warn, 8).")
@common_options
def force(spec_path, accuracy_warn=None, **opts):
    """Kinetostatics (动态静力分析) of any linkage of `kin`: pair reactions, the
    balancing torque, shaking force and moment, checked by the power balance."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.core.errors import AssemblyError
    from mechcli.core.linkage.force_analysis import analyse_forces
    from mechcli.report import force as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.force import load_force_spec

    spec = load_force_spec(spec_path, run.sets)
    inp = spec.input
    sweep = inp.sweep()
    try:
        result = analyse_forces(spec.linkage, spec.topology, sweep, spec.bodies, spec.gravity,
                                spec.loads, partial=inp.partial)
    except AssemblyError as exc:   # worded in the spec's units
        raise AssemblyError(report.assembly_message(spec, exc), exc.intervals) from None
    outputs = Outputs(run.out_dir, digits=run.digits)
    outputs.csv("force.csv", report.columns(spec, result))
    warnings = report.warnings(spec, result, accuracy_warn)
    animate = spec.output.animate if run.animate is None else run.animate
    if (run.plot and spec.output.plots) or animate:
        from mechcli.report import force_plots
        warnings += force_plots.write(spec, result, sweep, outputs, run.lang,
                                      plots=run.plot and spec.output.plots, animate=animate)
    finish(run, "force", report.build_report(spec, result, run.lang),
           report.scalar_results(spec, result, accuracy_warn), outputs, warnings)
