"""``mechcli gear``: involute function, spur gears and pairs, generation, helical/worm/bevel."""

from pathlib import Path

import click

from mechcli.options import RunOptions, common_options


@click.command("gear")
@click.argument("spec_path", metavar="SPEC.toml", type=click.Path(dir_okay=False, path_type=Path))
@common_options
def gear(spec_path, **opts):
    """Solve the gear problem in SPEC.toml (chapter 5; see docs/gear.md).

    The spec holds one table naming the problem: [involute], [inverse_involute],
    [spur], [pair], [generation], [helical], [worm] or [bevel].
    """
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.core.gear.problems import solve_gear
    from mechcli.core.gear.spur import GearError
    from mechcli.report import gear as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.errors import SpecError
    from mechcli.spec.gear import read_gear_spec

    spec = read_gear_spec(spec_path, run.sets)
    try:
        solution = solve_gear(spec.kind, spec.problem)
    except GearError as exc:
        if exc.reason == "mounting":   # a' that jams the teeth: a bad spec value (exit 2)
            raise SpecError(spec_path, *report.mounting_error(spec, exc)) from None
        exc.args = (report.error_message(exc),)
        raise
    warnings = report.enforce(spec, solution)   # exit 3 on what the spec forbids
    outputs = Outputs(run.out_dir, digits=run.digits)
    rep, results, more = report.present(spec, solution, run, outputs)
    finish(run, "gear", rep, results, outputs, warnings + more)
