"""``mechcli gear``: involute function, spur gears and pairs, generation, helical/worm/bevel."""

from pathlib import Path

import click

from mechcli.options import RunOptions, common_options, export_option

#: the gear problems that draw geometry, and so can ``--export`` it
CAD_KINDS = ("involute", "spur", "pair", "generation")
#: involute points per flank of a pair's outlines in its CAD files (a [spur] gear's
#: default ``points``)
PAIR_POINTS = 40


@click.command("gear")
@click.argument("spec_path", metavar="SPEC.toml", type=click.Path(dir_okay=False, path_type=Path))
@export_option
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
    if run.export and spec.kind not in CAD_KINDS:
        raise SpecError(str(spec_path), "--export", "a gear problem that draws geometry ("
                        + ", ".join(f"[{k}]" for k in CAD_KINDS) + ")", f"[{spec.kind}]")
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
    if run.export:
        export(spec, solution, run, outputs)
    finish(run, "gear", rep, results, outputs, warnings + more)


def export(spec, kind_solution, run, outputs):
    """``--export``: the outlines the pictures draw, as CAD files (report.cad):
    involute.*; gear.* (one spur gear; ``gear-N.*`` per shift of a generation);
    gear1.*, gear2.* and pair.* (``pair-N.*`` per mounting) of a pair."""
    from mechcli.report import cad
    fmt, sol = run.export, kind_solution
    if spec.kind == "involute":
        cad.write(outputs, "involute", cad.involute_sketch(sol, spec), fmt)
    elif spec.kind == "spur":
        cad.write(outputs, "gear", cad.gear_sketch(sol["gear"], sol["outline"], spec), fmt)
    elif spec.kind == "generation":
        many = len(sol["outlines"]) > 1
        for k, (tooth, out) in enumerate(zip(sol["teeth"], sol["outlines"])):
            cad.write(outputs, f"gear-{k + 1}" if many else "gear",
                      cad.gear_sketch(tooth.gear, out, spec), fmt)
    elif spec.kind == "pair":
        import math

        from mechcli.core.gear.pair import mesh_positions
        from mechcli.core.gear.profile import gear_outline, generated_tooth, ring_outline
        for k, pr in enumerate(sol):
            g1, g2 = pr.g1, pr.g2
            o1 = gear_outline(generated_tooth(g1), PAIR_POINTS)
            o2 = (ring_outline(g2, PAIR_POINTS) if g2.internal
                  else gear_outline(generated_tooth(g2), PAIR_POINTS))
            if k == 0:
                cad.write(outputs, "gear1", cad.gear_sketch(g1, o1, spec), fmt)
                cad.write(outputs, "gear2", cad.gear_sketch(g2, o2, spec), fmt)
            # the wheel turned into mesh as pair.png draws it
            rot = (math.pi / g2.z if g2.internal
                   else float(mesh_positions(pr, [0.0]).phi2[0]))
            cad.write(outputs, f"pair-{k + 1}" if len(sol) > 1 else "pair",
                      cad.pair_sketch(pr, (o1, o2), rot, spec), fmt)
