"""``mechcli kin``: positions, velocities and accelerations of a planar linkage."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options, export_option


@click.command("kin")
@click.argument("spec_path", metavar="SPEC.toml")
@click.option("--accuracy-warn", "accuracy_warn", type=click.FloatRange(0.0, 16.0),
              default=None, metavar="DIGITS",
              help="Warn where fewer correct significant digits than this remain "
                   "(estimated; default: the spec's output.accuracy_warn, 8).")
@export_option
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

    spec = load_kin_spec(spec_path, run.sets, stream=True)
    streamed = spec.input.count > 0   # past the in-memory limit: rows streamed to the CSV
    if streamed:
        spec = _analysed_rows(spec)
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
    if spec.mechanism == "slider_crank" and spec.model == "approximate":
        if streamed:
            from mechcli.spec.errors import SpecError
            from mechcli.spec.kin import MAX_POSITIONS
            raise SpecError(spec_path, "input.step", f"at most {MAX_POSITIONS:,} positions "
                            "with [mechanism] model = \"approximate\"",
                            f"{inp.count:,} positions")
        from mechcli.core.linkage import approximate
        result, approx = approximate.apply(spec.linkage, sweep, result)
    outputs = Outputs(run.out_dir, digits=run.digits)
    warnings = []
    if streamed:
        rows = _stream_csv(spec, sweep, quantities, result, outputs, report, run)
        warnings += _streamed_warnings(spec, quantities, result, rows, report)
    else:
        outputs.csv("kin.csv", report.columns(spec, quantities, result))
    animate = spec.output.animate if run.animate is None else run.animate
    if (run.plot and spec.output.plots) or animate:
        from mechcli.report import kin_plots
        warnings += kin_plots.write(spec, quantities, result, sweep, outputs, run.lang,
                                    plots=run.plot and spec.output.plots, animate=animate)
    if run.export:
        warnings += export_linkage(run, outputs, "kin", spec, sweep, result.motion, result.runs)
    warnings += report.warnings(spec, result, accuracy_warn)
    results = report.scalar_results(spec, quantities, result, accuracy_warn, approx)
    if streamed:   # the CSV's rows; the analysis, table and plots ran on a subset of them
        results["positions"] = rows.rows
        results["positions_analysed"] = int(result.q.size)
        _streamed_grid_errors(spec, quantities, result, rows, results, report)
    finish(run, "kin", report.build_report(spec, quantities, result, run.lang, approx),
           results, outputs, warnings)


def export_linkage(run, outputs, stem, spec, sweep, motion, runs):
    """``--export``: ``<stem>.dxf``/``.svg`` of the linkage at ``output.draw_at`` with
    the traced points' paths over the sweep (*motion*, split at *runs*), for kin and
    force (report.cad); returns warnings."""
    import numpy as np

    from mechcli.core.linkage import solve
    from mechcli.report import cad
    from mechcli.report.kin import input_factor

    at = spec.output.draw_at
    pose = solve(spec.linkage, sweep.inputs(np.array([at])), order=0)
    curves = [c for tr in spec.tracers for c in cad.runs_of(motion.points[tr.name].p, runs)]
    warnings = []
    if not bool(pose.regular[0]):
        pose = None
        warnings.append(f"{stem}.{run.export[0]}: the mechanism cannot be assembled at "
                        f"draw_at = {at * input_factor(spec):g}: only the traced paths "
                        "are exported")
    sk = cad.linkage_sketch(spec.linkage, pose, motion, spec.header.scale, spec.header.unit,
                            spec.header.title, curves, spec.guide_length)
    cad.write(outputs, stem, sk, run.export)
    return warnings


def _analysed_rows(spec):
    """A streamed spec with ``input.q``: the analysed rows, every table row among them."""
    import dataclasses

    import numpy as np

    from mechcli.core.linkage.streaming import stream_grid

    inp, step = spec.input, spec.output.table_step
    targets = np.arange(inp.start, inp.stop + step * 1e-9, step)
    q = stream_grid(inp.start, inp.stop, inp.count, targets)
    return dataclasses.replace(spec, input=dataclasses.replace(inp, q=q))


def _stream_csv(spec, sweep, quantities, result, outputs, report, run):
    """Solve every row of a streamed sweep chunk by chunk into ``kin.csv``; the CSV
    is written to a temporary file and renamed at the end (none if a row fails).
    A terminal shows the rows solved (after 2 s, not with -q); -v a line per chunk."""
    import types

    from mechcli.core.errors import AssemblyError
    from mechcli.core.linkage.streaming import StreamedRows
    from mechcli.report.console import Progress

    inp = spec.input
    progress = Progress("kin", show=not run.quiet, verbose=run.verbose)

    def chunk_line(done, total, kept):
        return f"kin.csv: {done:,} of {total:,} rows solved, {kept:,} of them in the CSV"

    rows = StreamedRows(spec.linkage, sweep, quantities, spec.output.order, inp.start,
                        inp.stop, inp.count, result,
                        progress=progress.stage("rows of kin.csv", inp.count, chunk_line))
    headers = [h for h, _col in report.columns(spec, quantities, result)]

    def chunks():
        for q, values in rows:
            if rows.irregular is not None and not inp.partial:
                # a gap narrower than the analysed rows' step: refused like any other
                lo, hi = rows.irregular
                exc = AssemblyError("", [(lo, hi, "dead point")])
                raise AssemblyError(report.assembly_message(spec, exc), exc.intervals)
            chunk = types.SimpleNamespace(q=q, values=values)
            yield [col for _h, col in report.columns(spec, quantities, chunk)]

    with progress:
        outputs.csv_stream("kin.csv", headers, chunks())
    return rows


def _streamed_grid_errors(spec, quantities, result, rows, results, report):
    """``*_grid_error_*``: refined extreme minus the best of the CSV's rows (all of them,
    as the stream saw them; not only the analysed ones)."""
    for q in quantities:
        if q.symbol not in result.extremes or q.symbol not in rows.peaks:
            continue
        u, f = report.unit_of(q.kind, spec.header.unit), report.factor_of(q.kind,
                                                                            spec.header.scale)
        top, _at, bottom, _at2 = rows.peaks[q.symbol]
        for name, e, best in zip(("max", "min"), result.extremes[q.symbol], (top, bottom)):
            key = f"{q.symbol}_{name}_grid_error_{u}"
            if key in results and not e.constant:   # a constant's rows differ by noise
                results[key] = float(e.value - best) * f + 0.0


def _streamed_warnings(spec, quantities, result, rows, report):
    """Warnings of a streamed sweep: rows left out that the analysis did not see (a
    gap narrower than its step), a row past a refined extreme (never expected: the
    extremes are refined on the exact solution)."""
    out = []
    if rows.irregular is not None:
        lo, hi = rows.irregular
        f = report.input_factor(spec)
        unit = "°" if spec.input.rotary else f" {spec.header.unit}"
        out.append(f"rows between input {lo * f:.6g}{unit} and {hi * f:.6g}{unit} are not "
                   "regular and were left out (a gap narrower than the analysed rows' step)")
    for q in quantities:
        if q.symbol not in result.extremes or q.symbol not in rows.peaks:
            continue
        hi, lo = result.extremes[q.symbol]
        if hi.constant:   # constant to round-off: its rows differ from it by noise only
            continue
        top, at_top, bottom, at_bottom = rows.peaks[q.symbol]
        slack = 1e-9 * max(abs(hi.value), abs(lo.value), 1e-300)
        if (hi.bounded and top > hi.value + slack) or (lo.bounded and bottom < lo.value - slack):
            out.append(f"{q.symbol}: a streamed row lies beyond the refined extreme "
                       f"(the analysed rows may miss a narrow peak; use a larger step)")
    return out

