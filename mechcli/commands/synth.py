"""``mechcli synth``: linkage synthesis (chapter 3 §3.2–3.4), every design checked on the engine."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options


@click.command("synth")
@click.argument("spec_path", metavar="SPEC.toml")
@common_options
def synth(spec_path, **opts):
    """Design a linkage: rigid-body guidance (two/three positions, coupler poses,
    Burmester), function generation (Freudenstein, Chebyshev, least squares),
    design from the time ratio K; writes linkage.toml for `mechcli kin`."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.core.errors import DescribedError
    from mechcli.core.synth.problems import solve_synthesis
    from mechcli.report import synth as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.synth import read_synth_spec

    from mechcli.core.errors import ConvergenceError, UnsolvableError
    from mechcli.spec.reader import MAX_LENGTH, MIN_LENGTH

    spec = read_synth_spec(spec_path, run.sets)
    solutions = []
    for prob in spec.cases:
        try:
            sol = solve_synthesis(prob.kind, prob.data)
        except DescribedError as exc:   # worded in the spec's units and keys
            raise DescribedError(report.error_message(exc, spec, prob), exc.reason,
                                 **exc.values) from None
        except ConvergenceError as exc:
            raise ConvergenceError(f"[{prob.path}] max_iter, tol: {exc}") from None
        bad = report.out_of_range(sol, MIN_LENGTH, MAX_LENGTH, spec, prob)
        if bad:     # its linkage.toml would be refused by kin: no design
            raise UnsolvableError(bad)
        solutions.append(sol)
    outputs = Outputs(run.out_dir, digits=run.digits)
    u, unit = spec.header.scale, spec.header.unit
    for i, sol in enumerate(solutions):
        tag = f"-{i + 1}" if spec.multi else ""
        cols = report.positions_columns(sol, u)
        if cols:
            outputs.csv(f"synth{tag}.csv", report.unit_columns(cols, unit))
        err = report.error_columns(sol)
        if err:
            outputs.csv(f"error{tag}.csv", err)
        if sol.kind == "burmester" and sol.design is None:
            outputs.csv(f"burmester{tag}.csv", report.burmester_columns(sol.extra, u, unit))
        if sol.design is not None:
            outputs.text(f"linkage{tag}.toml", report.linkage_toml(sol, spec.header,
                                                                   spec_path))
    warnings = report.warnings(spec, solutions)
    animate = bool(run.animate)
    if (run.plot and spec.draw) or animate:
        from mechcli.report import synth_plots
        warnings += synth_plots.write(spec, solutions, outputs, run.lang,
                                      plots=run.plot and spec.draw, animate=animate)
    finish(run, "synth", report.build_report(spec, solutions, run.lang),
           report.results(spec, solutions), outputs, warnings)
