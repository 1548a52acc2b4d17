"""``mechcli optimize``: constrained and global optimization of a linkage
(chapter 7) on the engine, a whole population per engine call."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options, export_option


def build_problem(spec):
    """The core problem of a spec: the vectorized evaluator on the engine (goal,
    engine constraints) plus, where asked, another command's results."""
    if spec.problem == "cam":
        return cam_problem(spec)
    from mechcli.core.optimize.build import function_goal, linkage_problem, path_goal
    from mechcli.core.optimize.problem import Variable
    from mechcli.runner.results import ResultTerms
    from mechcli.spec import optimize as so
    cands = so.Candidates(spec)
    targets = so.check_linkage_problem(spec, cands)     # exit 2 before anything is built
    obj = spec.objective
    goal = (function_goal(obj, *targets) if targets is not None
            else path_goal(obj) if obj["kind"] == "path" else None)
    bounds = so.result_bounds(spec)
    extra, extra_names = None, ()
    if obj["kind"] == "result" or bounds:
        extra = ResultTerms(spec, so.result_objective(spec), bounds)
        so.check_result_keys(spec, extra.at_start())
        extra_names = extra.names()
    variables = [Variable(v.key, v.lo, v.hi, v.start) for v in spec.variables]
    return linkage_problem(cands, variables, goal, spec.constraints, spec.method.samples,
                           extra, extra_names, bounds)


def cam_problem(spec):
    """例 7-2: the pressure angle over the cam angle, on the cam command's design."""
    from mechcli.commands.cam import design_of
    from mechcli.core.optimize import build
    from mechcli.core.optimize.problem import Variable
    from mechcli.spec.optimize import problem_root, read_problem
    design = design_of(read_problem("cam", problem_root(spec.problem_file, spec.problem_data)))
    v = spec.variables[0]
    return build.cam_problem(design, spec.objective["goal"] == "maximize",
                             Variable(v.key, v.lo, v.hi, v.start))


@click.command("optimize")
@click.argument("spec_path", metavar="SPEC.toml")
@click.option("--workers", type=click.IntRange(1, 256), default=None,
              help="Local processes evaluating the population (overrides [method] workers).")
@export_option
@common_options
def optimize(spec_path, workers=None, **opts):
    """Optimization of a linkage (chapter 7): function or path generation, or any
    scalar result of kin/force, under transmission-angle, crank and assembly
    constraints, by SLSQP, trust-constr, Nelder-Mead, differential evolution,
    golden section or Brent."""
    run = RunOptions.from_click(spec_path, opts)
    from mechcli.report import optimize as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.optimize import read_optimize_spec, with_values

    spec = read_optimize_spec(spec_path, run.sets)
    if run.export and spec.problem == "cam":
        from mechcli.spec.errors import SpecError
        raise SpecError(str(spec_path), "--export", "an optimization of a linkage (problem = "
                        "\"kin\" or \"force\"); export a cam with `mechcli cam --export`",
                        "problem = \"cam\"")
    problem, evaluator = build_problem(spec)
    result = _minimize(spec, problem, run, workers or spec.method.workers)
    details = (evaluator.details(result.x[None, :]) if hasattr(evaluator, "details")
               else {"exact": getattr(evaluator, "exact", None)})
    outputs = Outputs(run.out_dir, digits=run.digits)
    outputs.csv("history.csv", report.history_columns(spec, result))
    optimum = with_values(spec.problem_data, {v.key: float(x)
                                              for v, x in zip(spec.variables, result.x)})
    outputs.text("optimum.toml", report.optimum_toml(spec, result, optimum))
    warnings = report.warnings(spec, result, details)
    if run.plot or run.animate or run.export:
        # everything the pictures (and --export) show is solved here; the report only draws
        problem.mapper = map            # the pool (if any) is shut down
        poses = _poses(spec, evaluator, result, details, optimum)
        if run.plot or run.animate:
            warnings += _pictures(spec, problem, evaluator, result, details, poses, run,
                                  outputs)
        if run.export:
            warnings += export(spec, optimum, poses, run, outputs)
    finish(run, "optimize", report.build_report(spec, problem, result, details, run.lang),
           report.results(spec, problem, result, details), outputs, warnings)


def _minimize(spec, problem, run, workers):
    """The search, with its progress line, on a pool of *workers* processes (>1);
    its errors worded with the spec's keys."""
    from mechcli.core.errors import ConvergenceError, DescribedError
    from mechcli.core.optimize.methods import minimize
    from mechcli.report import optimize as report
    from mechcli.report.console import Progress
    executor = None
    if workers > 1:
        # the population's chunks go to local processes through one map-like function
        from concurrent.futures import ProcessPoolExecutor
        executor = ProcessPoolExecutor(workers)
        problem.mapper = executor.map
        problem.chunk = 64
    m = spec.method
    progress = Progress("optimize", show=not run.quiet, verbose=run.verbose)
    stage = ("generations of differential evolution" if m.name == "differential_evolution"
             else f"{m.name} iterations")
    k, unit = report.f_scale(spec)      # f as the report shows it

    def step_line(done, total, f, violation, evaluable):
        where = f"generation {done}/{total}, best" if total else f"iteration {done},"
        shown = (f"f = {f * k:.8g}" + (f" {unit}" if unit != "as the result" else "")
                 if evaluable else "the design cannot be evaluated")
        return (f"{m.name}: {where} {shown}"
                + (f", constraint violation {violation:.3g}" if violation > 0 else ""))

    try:
        with progress:
            return minimize(problem, m.name, tol=m.tol, maxiter=m.maxiter,
                            popsize=m.popsize, seed=m.seed, starts=m.starts,
                            polish=m.polish, central=m.central,
                            progress=progress.stage(stage, detail=step_line))
    except DescribedError as exc:       # worded with the spec's keys
        raise DescribedError(report.error_message(exc, spec, problem), exc.reason,
                             **exc.values) from None
    except ConvergenceError as exc:
        raise ConvergenceError(report.convergence_message(exc, spec, problem)) from None
    finally:
        if executor is not None:
            executor.shutdown()


def _poses(spec, evaluator, result, details, optimum):
    """The optimum linkage moved through its inputs (a slide: its problem's sweep)
    for the pictures and ``--export``; None when the optimum is no linkage."""
    if "linkage" not in details or not hasattr(evaluator, "candidates"):
        return None
    import math

    import numpy as np

    from mechcli.core.optimize.build import optimum_poses
    from mechcli.spec.optimize import problem_root, read_problem
    lk = evaluator.candidates.linkage_of(result.x)
    rotary = bool(getattr(lk.drivers[0], "rotary", True))
    if rotary:
        q = np.linspace(0.0, 2 * math.pi, 361)
    else:
        prob = read_problem(spec.problem, problem_root(spec.problem_file, optimum))
        q = np.linspace(prob.input.start, prob.input.stop, 361)
    return optimum_poses(lk, q, rotary, getattr(evaluator, "goal", None), details)


def _pictures(spec, problem, evaluator, result, details, poses, run, outputs):
    """The plots and animation (with a two-variable problem's surface); warnings."""
    from mechcli.core.optimize.problem import grid
    from mechcli.report import optimize_plots
    surface = None
    if run.plot and spec.method.surface and problem.n == 2:
        surface = grid(problem, 0, 1, result.x, count=spec.method.surface_points,
                       span=optimize_plots.surface_span(problem, result))
    return optimize_plots.write(spec, problem, result, details, outputs, run.lang,
                                plots=run.plot, animate=bool(run.animate), surface=surface,
                                poses=poses, goal=getattr(evaluator, "goal", None))


def export(spec, optimum, poses, run, outputs):
    """``--export``: ``optimize.dxf``/``.svg`` (report.cad), the optimum linkage at
    ``output.draw_at`` with its traced points' paths (and a path goal's); warnings."""
    import numpy as np

    from mechcli.core.linkage import DriverMotion, solve
    from mechcli.core.numerics import true_runs
    from mechcli.report import cad
    from mechcli.spec.optimize import problem_root, read_problem
    if poses is None:
        return ["--export: the optimum is not a linkage the engine moves (nothing exported)"]
    prob = read_problem(spec.problem, problem_root(spec.problem_file, optimum))
    lk, m = poses["linkage"], poses["motion"]
    ok = np.broadcast_to(np.asarray(m.feasible, dtype=bool), np.shape(poses["q"]))
    names = [t.name for t in prob.tracers]
    if spec.objective["kind"] == "path":
        names.append(spec.objective["point"])
    curves = [c for n in dict.fromkeys(names) if n in m.points
              for c in cad.runs_of(m.points[n].p, true_runs(ok))]
    pose = solve(lk, {lk.drivers[0].link: DriverMotion(np.array([prob.output.draw_at]))},
                 order=0)
    warnings = []
    if not bool(pose.feasible[0]):
        pose = None
        warnings.append("--export: the optimum cannot be assembled at draw_at: only the "
                        "traced paths are exported")
    sk = cad.linkage_sketch(lk, pose, m, spec.header.scale, spec.header.unit,
                            spec.header.title, curves, prob.guide_length, feasible=ok)
    cad.write(outputs, "optimize", sk, run.export)
    return warnings
