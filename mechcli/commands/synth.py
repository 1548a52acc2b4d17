"""``mechcli synth``: linkage synthesis (chapter 3 §3.2–3.4), every design checked on the engine."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options, export_option


@click.command("synth")
@click.argument("spec_path", metavar="SPEC.toml")
@click.option("--workers", type=click.IntRange(1, 256), default=None,
              help="Local processes for an atlas build or search.")
@click.option("--scheduler", default=None, metavar="ADDRESS",
              help="A Dask scheduler for an atlas build or search (the dask extra).")
@click.option("--atlas", "atlas_dir", type=click.Path(file_okay=False), default=None,
              metavar="DIR",
              help="Build the atlas (atlas_build, or a path search's default atlas) in DIR "
                   "instead of inside --out (a spec never chooses where mechcli writes).")
@export_option
@common_options
def synth(spec_path, workers=None, scheduler=None, atlas_dir=None, **opts):
    """Design a linkage: rigid-body guidance (two/three positions, coupler poses,
    Burmester), function generation (Freudenstein, Chebyshev, least squares),
    design from the time ratio K; writes linkage.toml for `mechcli kin`."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.core.errors import ConvergenceError, DescribedError, UnsolvableError
    from mechcli.core.synth.problems import solve_synthesis
    from mechcli.report import synth as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.runner.atlas import atlas_case, atlas_folder, atlas_mapper
    from mechcli.spec.reader import MAX_LENGTH, MIN_LENGTH
    from mechcli.spec.synth import read_synth_spec

    if atlas_dir is not None and not str(atlas_dir).strip():
        raise click.BadParameter("expected a folder, got an empty path", param_hint="--atlas")
    spec = read_synth_spec(spec_path, run.sets)
    solutions, prob_of = [], {}
    mapper = close = None
    outputs = Outputs(run.out_dir, digits=run.digits)
    from mechcli.report.console import Progress
    progress = Progress("synth", show=not run.quiet, verbose=run.verbose)
    try:
        for prob in spec.cases:
            try:
                if prob.kind in ("atlas_build", "path"):
                    if mapper is None:
                        mapper, close = atlas_mapper(workers, scheduler)
                    sol = atlas_case(prob, spec, run, mapper, atlas_dir, outputs, progress)
                else:
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
            prob_of[id(sol)] = prob
    finally:
        progress.close()
        if close is not None:
            close()
    u, unit = spec.header.scale, spec.header.unit
    from mechcli.report import atlas as atlas_report
    for sol in solutions:
        # an atlas built under --out is this run's output: listed in outputs.json,
        # removed with the rest if the run fails (an [expected] typo)
        if sol.kind not in ("atlas_build", "path") or atlas_dir is not None:
            continue
        folder = atlas_folder(prob_of[id(sol)], run, None, outputs)
        if folder.is_dir():
            for f in sorted(folder.iterdir()):
                if f.is_file() and f not in outputs.files:
                    outputs.files.append(f)
    for i, sol in enumerate(solutions):
        tag = f"-{i + 1}" if spec.multi else ""
        if sol.kind == "atlas_page" and sol.extra.reason is None:
            outputs.csv(f"page{tag}.csv", atlas_report.page_columns(sol.extra))
        if sol.kind == "path":
            for j, cand in enumerate(sol.extra["candidates"]):
                outputs.text(f"linkage{tag}-{j + 1}.toml", atlas_report.candidate_toml(
                    cand, spec.header, f"{spec.header.title}: candidate {j + 1}", u))
        if sol.kind in atlas_report.KINDS:
            continue
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
    if run.export:
        warnings += export(spec, solutions, run, outputs)
    animate = bool(run.animate)
    atlas_sols = [(i, s) for i, s in enumerate(solutions) if s.kind in atlas_report.KINDS]
    if atlas_sols and run.plot and spec.draw:
        from mechcli.report import atlas_plots
        warnings += atlas_plots.write(spec, atlas_sols, outputs, run.lang)
    others = [s for s in solutions if s.kind not in atlas_report.KINDS]
    if others and ((run.plot and spec.draw) or animate):
        from mechcli.report import synth_plots
        warnings += synth_plots.write(spec, solutions, outputs, run.lang,
                                      plots=run.plot and spec.draw, animate=animate)
    finish(run, "synth", report.build_report(spec, solutions, run.lang),
           report.results(spec, solutions), outputs, warnings)


def export(spec, solutions, run, outputs):
    """``--export``: ``synth.dxf``/``.svg`` (``synth-N`` per case) of each designed
    linkage, posed by the engine at its first prescribed input (else at the start of
    its checked range), with the path of its coupler point M over that range as
    ``positions.png`` draws it (report.cad); returns warnings."""
    import numpy as np

    from mechcli.core.linkage import DriverMotion, solve
    from mechcli.core.numerics import true_runs
    from mechcli.report import cad
    warnings, written = [], False
    for i, sol in enumerate(solutions):
        tag = f"-{i + 1}" if spec.multi else ""
        if sol.design is None or sol.check is None:
            continue
        chk = sol.check
        lk = chk.linkage
        drv = lk.drivers[0].link
        inputs = np.asarray(chk.inputs if chk.inputs is not None else [], dtype=float)
        q0 = float(inputs[0]) if inputs.size else float(chk.start)
        pose = solve(lk, {drv: DriverMotion(np.array([q0]))}, order=0)
        path = (np.linspace(chk.start, chk.stop, 361) if chk.start != chk.stop
                else np.concatenate([[q0], inputs]))
        ok = np.asarray(solve(lk, {drv: DriverMotion(path)}, order=0).feasible, dtype=bool)
        ok = np.broadcast_to(ok, path.shape)
        if not ok.any():
            continue
        m = solve(lk, {drv: DriverMotion(path[ok])}, order=0)
        at = np.cumsum(ok) - 1            # index of each feasible input among them
        runs = [(int(at[a]), int(at[b - 1]) + 1) for a, b in true_runs(ok)]
        curves = ([c for c in cad.runs_of(m.points["M"].p, runs)]
                  if "M" in m.points and chk.start != chk.stop else [])
        sk = cad.linkage_sketch(lk, pose if bool(pose.feasible[0]) else None, m,
                                spec.header.scale, spec.header.unit, spec.header.title,
                                curves)
        cad.write(outputs, f"synth{tag}", sk, run.export)
        written = True
    if not written:
        warnings.append("--export: no linkage was designed (nothing to export)")
    return warnings
