"""``mechcli grashof``: linkage type, crank conditions, mobility and quick-return figures."""

from __future__ import annotations

import click

from mechcli.commands.cam import FiniteFloat
from mechcli.options import RunOptions, common_options


@click.command("grashof")
@click.argument("spec_path", metavar="[SPEC.toml]", required=False)
@click.option("--lengths", metavar="L1,L2,...", help="Quick form without a file: 4 lengths "
              "(four-bar), 5 (five-bar) or 2 with --offset (slider-crank).")
@click.option("--frame", type=int, help="Frame link number (quick form) [default: 4 or 5].")
@click.option("--input", "input_link", type=int, help="Input link (quick form) [default: 1].")
@click.option("--offset", type=FiniteFloat(), help="Slider offset e (quick form, slider-crank).")
@click.option("--batch", type=click.Path(dir_okay=False), metavar="SETS.csv",
              help="Classify many four-bars: rows l1,l2,l3,l4[,frame[,input]] -> grashof.csv.")
@click.option("--units", type=click.Choice(["mm", "cm", "m", "in"]), default=None,
              help="Length unit of --lengths and --batch [default: mm].")
@common_options
def grashof(spec_path, lengths, frame, input_link, offset, batch, units, **opts):
    """Four-bar type (Grashof) and inversions, θ, ψ, K, transmission angles and
    dead points; slider-crank, guide-bar, 5R/RRRRP five-bars, mobility F.

    --no-plot, --dpi and --set serve the SPEC.toml form only: --lengths and --batch
    write no picture and read no file (--dpi and --set are refused there, exit 2).
    grashof writes no animation.
    """
    given = [x for x in (spec_path, lengths, batch) if x]
    if len(given) != 1:
        raise click.UsageError("give exactly one of SPEC.toml, --lengths or --batch")
    quick = {"--frame": frame, "--input": input_link, "--offset": offset}
    extra = [k for k, v in quick.items() if v is not None and not lengths] + \
        (["--units"] if units and spec_path else [])
    if extra:
        raise click.UsageError(f"{', '.join(extra)}: only with "
                               + ("--lengths" if extra != ["--units"] else "--lengths/--batch"))
    _refuse_idle_options("--lengths" if lengths else "--batch" if batch else None)
    units = units or "mm"
    stem = "grashof-batch" if batch else ("grashof" if lengths else None)
    run = RunOptions.from_click(spec_path or batch, opts, stem=stem)
    from mechcli.report import grashof as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec import grashof as spec_mod

    outputs = Outputs(run.out_dir, digits=run.digits)
    if batch:
        from mechcli.core.grashof.analysis import classify_batch
        bs = spec_mod.read_batch_csv(batch, units)
        an, ok = classify_batch(bs.lengths, bs.frame, bs.input)
        outputs.text("grashof.csv", report.fourbar_csv(an, bs.header.scale, ok, run.digits))
        res = report.batch_results(an, ok)
        warns = [f"{res['cannot_close']} length sets cannot close (type cannot_close)"] \
            if res["cannot_close"] else []
        finish(run, "grashof", report.batch_report(bs.header.title, run.lang, res,
                                                     bs.header.unit), res,
               outputs, warns)
        return
    if lengths:
        spec = spec_mod.quick_spec(lengths, frame, input_link, offset, units)
    else:
        spec = spec_mod.read_grashof_spec(spec_path, run.sets)
    results, rep, csv_text, warnings, solution = build(spec, run.lang, run.digits)
    if csv_text:
        outputs.text("grashof.csv", csv_text)
    if solution.curve is not None:
        outputs.csv("transmission.csv", report.curve_outputs(
            solution.curve, spec.problem.curve_step, run.lang)[0])
        if run.plot:
            warnings += report.write_curve_png(solution.curve, outputs, run.lang,
                                               spec.header.title)
    if run.plot and getattr(spec.problem, "draw", False) and "theta_deg" in results:
        warnings += report.write_limits_png(results, report.driven_lengths(spec, solution),
                                            outputs, run.lang, spec.header.title)
    finish(run, "grashof", rep, results, outputs, warnings)


# grashof writes no animation: --animate/--no-animate (shared by every command) is not offered
# in its --help; given anyway, it is refused with a message (_refuse_idle_options)
for _param in grashof.params:
    if _param.name == "animate":
        _param.hidden = True


#: shared options that ask for what a form of grashof never gives -> (forms, why); the
#: negative flags --no-plot/--no-animate ask for nothing and stay accepted as no-ops
#: (batch runners and Makefiles pass them to every command)
_IDLE_OPTIONS = {
    "dpi": ("--dpi", ("--lengths", "--batch"), "it writes no picture"),
    "animate": ("--animate", ("--lengths", "--batch", None), "grashof writes no animation"),
    "sets": ("--set", ("--lengths", "--batch"), "there is no spec file to override; "
             "give the values themselves"),
}


def _refuse_idle_options(form):
    """Exit 2 on a shared option given on the command line that asks for what this form
    never gives (``grashof --lengths … --dpi 300``, ``--animate``, ``--set``): an option
    is never ignored silently."""
    ctx = click.get_current_context()
    idle = []
    for name, (opt, forms, why) in _IDLE_OPTIONS.items():
        if form not in forms or ctx.get_parameter_source(name) \
                != click.core.ParameterSource.COMMANDLINE:
            continue
        if name == "animate" and not ctx.params.get("animate"):
            continue   # --no-animate: nothing asked
        if name == "dpi" and ctx.params.get("no_plot"):
            continue   # --dpi with --no-plot: no picture asked
        idle.append((opt, why))
    if idle:
        where = f"grashof {form}" if form else "grashof SPEC.toml"
        raise click.UsageError(
            "; ".join(f"{opt} does nothing for {where}: {why}" for opt, why in idle)
            + " (leave it out)")


def build(spec, lang, digits=10):
    """Solve a :class:`~mechcli.spec.grashof.GrashofSpec` with the core and present it.

    Returns
    -------
    results, report, csv_text, warnings
        As :func:`mechcli.report.grashof.present`.
    solution : GrashofSolution
    """
    from mechcli.core.grashof.analysis import solve_grashof
    from mechcli.core.grashof.chain import ClosureError
    from mechcli.core.grashof.mobility import MobilityError
    from mechcli.report import grashof as report
    from mechcli.spec.errors import SpecError

    try:
        solution = solve_grashof(spec.kind, spec.problem, spec.header.scale)
    except ClosureError as exc:   # its numbers are in the spec's unit: say which
        exc.args = (report.closure_message(exc, spec.header.unit),)
        raise
    except MobilityError as exc:  # drivers that do not leave Assur groups: the spec's
        key = "mobility.kin" if spec.problem.source not in ("joints", "links") \
            else "mobility.drivers"
        raise SpecError(spec.path, key,
                        "one driver per freedom, the rest Assur groups", str(exc)) from None
    return (*report.present(spec, solution, lang, digits), solution)
