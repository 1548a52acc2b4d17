"""``mechcli optimize``: constrained and global optimization of a linkage
(chapter 7) on the engine, a whole population per engine call."""

from __future__ import annotations

import click

from mechcli.options import RunOptions, common_options, export_option


class ResultTerms:
    """Objective and constraints read from another command's ``--json``
    results, one design at a time (``force``'s max |Mb| …).  Picklable."""

    def __init__(self, spec, objective, bounds):
        from mechcli.spec.optimize import Candidates
        self.spec = spec
        self.keys = Candidates(spec).keys
        self.objective = objective          # (key, sign) or None
        self.bounds = bounds                # [(key, lo, hi)]

    def results(self, x):
        from mechcli.spec.optimize import problem_root, read_problem, with_values
        spec = self.spec
        root = problem_root(spec.problem_file, with_values(spec.problem_data,
                                                           dict(zip(self.keys, x))))
        prob = read_problem(spec.problem, root)
        return problem_results(spec.problem, prob)

    def names(self):
        out = []
        for key, lo, hi in self.bounds:
            if lo is not None:
                out.append(f"{key}>=")
            if hi is not None:
                out.append(f"{key}<=")
        return out

    def __call__(self, X):
        import numpy as np

        from mechcli.core.errors import UnsolvableError
        from mechcli.spec.errors import SpecError
        M = len(X)
        f = np.zeros(M) if self.objective else None
        g = np.zeros((M, len(self.names())))
        ok = np.ones(M, dtype=bool)
        for k, x in enumerate(X):
            try:
                r = self.results(x)
            except (UnsolvableError, SpecError, ArithmeticError):
                ok[k] = False
                continue
            if self.objective:
                key, sign = self.objective
                f[k] = sign * float(r[key])
            j = 0
            for key, lo, hi in self.bounds:
                if lo is not None:
                    g[k, j] = lo - float(r[key])
                    j += 1
                if hi is not None:
                    g[k, j] = float(r[key]) - hi
                    j += 1
        return f, g, ok


def problem_results(problem, prob):
    """The ``--json`` results of ``problem`` (kin or force) on its spec, computed
    in-process without writing anything."""
    if problem == "kin":
        from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
        from mechcli.report import kin as rk
        q = default_quantities(prob.linkage, prob.output.order, [t.name for t in prob.tracers])
        res = analyse_sweep(prob.linkage, prob.input.sweep(), q, prob.output.order,
                            partial=prob.input.partial)
        return rk.scalar_results(prob, q, res)
    from mechcli.commands.force import solve
    from mechcli.report import force as rf
    res, extra, _ = solve(prob, prob.input.sweep())
    return rf.scalar_results(prob, res, None, extra)


def build_problem(spec):
    """The core problem of a spec: the vectorized evaluator on the engine (goal,
    engine constraints) plus, where asked, another command's results."""
    import numpy as np

    from mechcli.core.optimize import linkage_problem as lp
    from mechcli.core.optimize.problem import Problem, Variable
    from mechcli.spec.optimize import Candidates

    if spec.problem == "cam":
        return cam_problem(spec)
    from mechcli.core.errors import DescribedError
    from mechcli.core.optimize import terms
    from mechcli.spec.errors import SpecError
    cands = Candidates(spec)
    base = cands.linkage_of(cands.starts)
    driver = base.drivers[0].link
    followers = cands.followers
    obj = spec.objective
    file = str(spec.path)
    if obj["kind"] in ("function", "path"):
        _check_variables_move(spec, cands)
    goal = None
    if obj["kind"] == "function":
        out = obj["output"]
        names = (base.rotating_links if not isinstance(out, str) else base.slide_names)
        if out not in names:
            raise SpecError(file, "objective.output",
                            "a link whose angle the linkage reports, or a slide: one of "
                            + ", ".join(repr(n) for n in base.rotating_links + base.slide_names),
                            repr(out))
        if "dphi" in obj:
            dphi, dpsi = obj["dphi"], obj["dpsi"]
        else:
            dphi, dpsi = function_targets(spec)
        # a slide's deviation stays in metres (shown in the spec's unit)
        goal = lp.FunctionGoal(obj["output"], obj["phi0"], np.asarray(dphi, dtype=float),
                               np.asarray(dpsi, dtype=float), obj["psi0"], obj["measure"])
    elif obj["kind"] == "path":
        goal = lp.PathGoal(obj["point"], obj["targets"], obj["angles"], obj["theta0"],
                           obj["measure"])
    engine, scales, bounds = [], [], []
    size = float(base.scale())
    for c in spec.constraints:
        if c["kind"] == "transmission":
            rrr = base.transmission_joints
            if not rrr:
                raise SpecError(file, f"{c['path']}.kind", "a linkage with an RRR dyad "
                                "(the transmission angle is the angle at its joint)",
                                "no RRR dyad in the mechanism")
            bad = [j for j in c["joints"] if j not in rrr]
            if bad:
                raise SpecError(file, f"{c['path']}.joints", "joints of RRR dyads: "
                                + ", ".join(rrr), ", ".join(bad))
            engine.append(lp.Transmission(c["min"], c["max"], c["over"], c["joints"]))
            scales += [1.0, 1.0]
        elif c["kind"] == "assembly":
            engine.append(lp.Assembly(c["over"]))
            scales.append(1.0)
        elif c["kind"] == "crank":
            try:
                terms.four_bar_lengths(base)
            except DescribedError:
                raise SpecError(file, f"{c['path']}.kind", "a four-bar (one crank and one RRR "
                                "dyad) for the book's g1 ... g6; use kind = \"assembly\" for "
                                "other linkages", "'crank'") from None
            engine.append(lp.CrankConditions())
            scales += [size] * 6
        else:
            bounds.append((c["key"], c["min"], c["max"]))
    extra, extra_names = None, ()
    if obj["kind"] == "result" or bounds:
        objective = ((obj["key"], -1.0 if obj["goal"] == "maximize" else 1.0)
                     if obj["kind"] == "result" else None)
        extra = ResultTerms(spec, objective, bounds)
        check_result_keys(spec, extra)
        extra_names = extra.names()
        for key, lo, hi in bounds:
            scales += [max(abs(v), 1e-300) if v else 1.0 for v in (lo, hi) if v is not None]
    evaluator = lp.LinkageEvaluator(cands, driver, goal, engine, spec.method.samples, extra,
                                    extra_names, followers=followers)
    variables = [Variable(v.key, v.lo, v.hi, v.start) for v in spec.variables]
    return Problem(variables, evaluator, evaluator.names, scales=scales), evaluator


def _check_variables_move(spec, cands):
    """A variable of the problem's tables must move the linkage (input.omega1 does not
    change a position goal): exit 2 instead of a variable that stays at its start."""
    import numpy as np

    from mechcli.spec.errors import SpecError
    x0 = np.array(cands.starts, dtype=float)
    base = cands.parameters(x0)
    for i, v in enumerate(spec.variables):
        if v.goal:
            continue
        x = x0.copy()
        x[i] = v.hi if v.hi != x0[i] else v.lo
        if np.array_equal(cands.parameters(x), base):
            raise SpecError(str(spec.path), f"variable[{i}].key", "a number that changes the "
                            "linkage (a length, coordinate or angle of [mechanism])",
                            f"'{v.key}', which moves nothing the goal depends on")


def cam_problem(spec):
    """例 7-2: the pressure angle over the cam angle (the one variable, degrees),
    with the cam command's exact refinement of the same maximum beside it."""
    import math

    from mechcli.commands.cam import design_of
    from mechcli.core.optimize.cam_problem import PressureAngle
    from mechcli.core.optimize.problem import Problem, Variable
    from mechcli.spec.optimize import problem_root, read_problem
    cs = read_problem("cam", problem_root(spec.problem_file, spec.problem_data))
    design = design_of(cs)
    ev = PressureAngle(design.follower, design.program, spec.objective["goal"] == "maximize",
                       math.pi / 180)
    v = spec.variables[0]
    ev.exact = design.checks.alpha_rise        # cam's refinement (root of dα/dδ)
    return Problem([Variable(v.key, v.lo, v.hi, v.start)], ev), ev


def function_targets(spec):
    """(dphi, dpsi) [rad] of a named function: x from x0 to xm maps linearly onto
    the input swing phi_m, y onto the output swing psi_m (§3.5's scaling)."""
    import numpy as np

    from mechcli.core.errors import DescribedError
    from mechcli.core.synth.functions import make_function
    from mechcli.spec.errors import SpecError
    obj = spec.objective
    f = make_function(obj["function"], exponent=obj.get("exponent"), coeffs=obj.get("coeffs"))
    try:
        f.check_domain(obj["x0"], obj["xm"])
    except DescribedError as exc:
        raise SpecError(str(spec.path), "objective.x0", "an interval inside the function's "
                        "domain", str(exc)) from None
    n = obj["n"]
    x = obj["x0"] + (obj["xm"] - obj["x0"]) * np.arange(1, n + 1) / n
    y0, ym = float(f(obj["x0"])), float(f(obj["xm"]))
    if not np.isfinite(y0) or not np.isfinite(ym) or y0 == ym:
        raise SpecError(str(spec.path), "objective.xm", "an interval where f(x0) != f(xm)",
                        f"f(x0) = {y0:g}, f(xm) = {ym:g}")
    dphi = obj["phi_m"] * np.arange(1, n + 1) / n
    dpsi = obj["psi_m"] * (f(x) - y0) / (ym - y0)
    return dphi, dpsi


def check_result_keys(spec, terms):
    """Every result key names a numeric result of the problem at the start."""
    import difflib

    from mechcli.core.errors import UnsolvableError
    from mechcli.spec.errors import SpecError
    try:
        r = terms.results(terms.spec and [v.start for v in spec.variables])
    except UnsolvableError as exc:
        raise UnsolvableError(f"the start design cannot be analysed by `{spec.problem}`: "
                              f"{exc}") from None
    wanted = ([("objective.key", spec.objective["key"])] if spec.objective["kind"] == "result"
              else []) + [(f"{c['path']}.key", c["key"]) for c in spec.constraints
                          if c["kind"] == "result"]
    numeric = [k for k, v in r.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    for where, key in wanted:
        if key not in numeric:
            near = difflib.get_close_matches(key, numeric, n=1, cutoff=0.5)
            raise SpecError(str(spec.path), where,
                            f"a numeric result of `mechcli {spec.problem} --json`",
                            f"'{key}'" + (f"; did you mean '{near[0]}'?" if near else ""))


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
    from mechcli.core.errors import ConvergenceError, DescribedError
    from mechcli.core.optimize.methods import minimize
    from mechcli.report import optimize as report
    from mechcli.report.files import Outputs
    from mechcli.report.run import finish
    from mechcli.spec.optimize import read_optimize_spec

    spec = read_optimize_spec(spec_path, run.sets)
    if run.export and spec.problem == "cam":
        from mechcli.spec.errors import SpecError
        raise SpecError(str(spec_path), "--export", "an optimization of a linkage (problem = "
                        "\"kin\" or \"force\"); export a cam with `mechcli cam --export`",
                        "problem = \"cam\"")
    problem, evaluator = build_problem(spec)
    executor = None
    workers = workers or spec.method.workers
    if workers > 1:
        # the population's chunks go to local processes through one map-like function
        from concurrent.futures import ProcessPoolExecutor
        executor = ProcessPoolExecutor(workers)
        problem.mapper = executor.map
        problem.chunk = 64
    m = spec.method
    from mechcli.report.console import Progress
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
            result = minimize(problem, m.name, tol=m.tol, maxiter=m.maxiter,
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
    details = (evaluator.details(result.x[None, :]) if hasattr(evaluator, "details")
               else {"exact": getattr(evaluator, "exact", None)})
    outputs = Outputs(run.out_dir, digits=run.digits)
    outputs.csv("history.csv", report.history_columns(spec, result))
    from mechcli.spec.optimize import with_values
    optimum = with_values(spec.problem_data, {v.key: float(x)
                                              for v, x in zip(spec.variables, result.x)})
    outputs.text("optimum.toml", report.optimum_toml(spec, result, optimum))
    warnings = report.warnings(spec, result, details)
    if run.plot or run.animate or run.export:
        # everything the pictures (and --export) show is solved here; the report only draws
        import math

        import numpy as np

        from mechcli.core.linkage import DriverMotion, solve
        from mechcli.core.optimize.problem import grid
        problem.mapper = map            # the pool (if any) is shut down
        surface = poses = None
        if run.plot and spec.method.surface and problem.n == 2:
            from mechcli.report import optimize_plots
            surface = grid(problem, 0, 1, result.x, count=spec.method.surface_points,
                           span=optimize_plots.surface_span(problem, result))
        goal = getattr(evaluator, "goal", None)
        if "linkage" in details and hasattr(evaluator, "candidates"):
            lk = evaluator.candidates.linkage_of(result.x)
            drv = lk.drivers[0]
            rotary = bool(getattr(drv, "rotary", True))
            if rotary:
                q = np.linspace(0.0, 2 * math.pi, 361)
            else:                       # a slide input: the problem's own sweep
                from mechcli.spec.optimize import problem_root, read_problem
                prob = read_problem(spec.problem, problem_root(spec.problem_file, optimum))
                q = np.linspace(prob.input.start, prob.input.stop, 361)
            poses = {"linkage": lk, "q": q, "rotary": rotary,
                     "motion": solve(lk, {drv.link: DriverMotion(q)}, order=0), "at": None,
                     "size": float(getattr(goal, "scale", 1.0))}
            if getattr(goal, "angles", None) is not None and "theta0" in details:
                qa = float(details["theta0"][0]) + np.asarray(goal.angles, dtype=float)
                poses["at"] = solve(lk, {drv.link: DriverMotion(qa)}, order=0)
        if run.plot or run.animate:
            from mechcli.report import optimize_plots
            warnings += optimize_plots.write(spec, problem, result, details, outputs,
                                             run.lang, plots=run.plot,
                                             animate=bool(run.animate), surface=surface,
                                             poses=poses, goal=goal)
        if run.export:
            warnings += export(spec, optimum, poses, run, outputs)
    finish(run, "optimize", report.build_report(spec, problem, result, details, run.lang),
           report.results(spec, problem, result, details), outputs, warnings)


def export(spec, optimum, poses, run, outputs):
    """``--export``: ``optimize.dxf``/``.svg``, the optimum linkage at its problem's
    ``output.draw_at`` with the paths of its traced points (the problem's and a path
    goal's) over the inputs the pictures move it through (report.cad); returns
    warnings."""
    import numpy as np

    from mechcli.core.linkage import DriverMotion, solve
    from mechcli.core.refine import true_runs
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
