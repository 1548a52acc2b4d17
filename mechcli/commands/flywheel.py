"""``mechcli flywheel``: the equivalent model, the equation of motion, the steady state and
the flywheel (chapter 6)."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options


@click.command("flywheel")
@click.argument("spec_path", metavar="SPEC.toml")
@common_options
def flywheel(spec_path, **opts):
    """Machine dynamics on the equivalent link: Je and Me from a linkage, a table or
    constants; the motion from a start or the periodic steady state (δ, ΔWmax);
    a flywheel added or sized for an allowed δ."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.core.errors import DescribedError
    from mechcli.core.flywheel.problems import solve_flywheel
    from mechcli.report import flywheel as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.flywheel import read_flywheel_spec

    spec = read_flywheel_spec(spec_path, run.sets)
    try:
        sol = solve_flywheel(spec)
    except DescribedError as exc:       # worded with the spec's keys
        raise DescribedError(report.error_message(exc, spec), exc.reason,
                             **exc.values) from None
    from mechcli.core.errors import UnsolvableError
    bad = report.non_finite(sol)
    if bad:     # an extreme spec: the motion overflows; nothing is written
        raise UnsolvableError(bad)
    if sol.swing is not None and not sol.swing[0] < 2.0:
        from mechcli.spec.errors import SpecError
        key = "flywheel.dW" if spec.flywheel.dW is not None else "moment"
        wm = getattr(spec.flywheel, "omega_mean", None)
        raise SpecError(spec_path, key, "an energy swing below 2 J ωm² (δ = "
                        "ΔWmax/(J ωm²) < 2: the least speed stays positive)",
                        f"δ = {sol.swing[0]:.6g}"
                        + (f" with ωm = {wm:.6g} rad/s" if wm is not None else ""))
    outputs = Outputs(run.out_dir, digits=run.digits)
    outputs.csv("flywheel.csv", report.columns(sol))
    if sol.loops is not None:
        outputs.csv("loops.csv", report.loop_rows(sol))
    warnings = report.warnings(spec, sol)
    if run.animate and not hasattr(sol.motion, "omega"):
        warnings.append("no animation: the spec asks for no motion (no [motion] table)")
    if run.plot and spec.plots:
        from mechcli.report import flywheel_plots
        warnings += flywheel_plots.write(spec, sol, outputs, run.lang)
    if run.animate and hasattr(sol.motion, "omega"):
        from mechcli.report import flywheel_plots
        flywheel_plots.animate(spec, sol, outputs, run.lang)
    finish(run, "flywheel", report.build_report(spec, sol, run.lang),
           report.results(spec, sol), outputs, warnings)
