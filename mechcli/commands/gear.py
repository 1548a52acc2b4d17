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
    from mechcli.report.files import Outputs
    from mechcli.report.gear import PRESENTERS
    from mechcli.report.run import finish
    from mechcli.spec.gear import enforce, read_gear_spec

    spec = read_gear_spec(spec_path, run.sets)
    solution = spec.problem.solve()
    warnings = enforce(spec, solution)          # exit 3 on what the spec forbids
    outputs = Outputs(run.out_dir)
    report, results, more = PRESENTERS[spec.kind](spec, solution, run, outputs)
    results = {"kind": spec.kind, **results}
    finish(run, "gear", report, results, outputs, warnings + more)
