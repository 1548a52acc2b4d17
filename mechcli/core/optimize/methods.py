"""The methods: every one minimizes a :class:`~.problem.Problem` and returns a
:class:`~.problem.Result`.

* ``slsqp``, ``trust-constr`` (``scipy.optimize.minimize``): constraints as
  they are, gradients by finite differences whose stencil is ONE population
  evaluation (the n + 1 or 2n + 1 designs of the stencil are one engine call);
* ``nelder-mead``: bounds, constraints as an extreme barrier (a design that
  violates one is worse than every feasible design);
* ``differential_evolution``: global, the whole population one vectorized
  evaluation per generation; constraints by the feasibility rule (feasible
  beats infeasible, infeasible ranked by violation); the best design is
  polished by SLSQP;
* ``golden``: the book's golden section on one variable
  (:func:`mechcli.core.numerics.golden_section_max`), ``brent``: bounded Brent
  (``scipy.optimize.minimize_scalar``);
* multi-start: a local method from the given start and ``starts - 1`` more
  points of a Latin hypercube (seeded), keeping the best feasible end.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any, Callable, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.errors import ConvergenceError, DescribedError
from mechcli.core.optimize.problem import Problem, Result

if TYPE_CHECKING:
    from mechcli.core.types import Array

#: method names
METHODS = ("slsqp", "trust-constr", "nelder-mead", "differential_evolution", "golden",
           "brent")
LOCAL = ("slsqp", "trust-constr", "nelder-mead")
SCALAR = ("golden", "brent")

#: an infeasible design's value in the barrier and penalty forms: above every
#: feasible (scaled) value, ordered by violation
_WALL = 1e6


class _Smooth:
    """f, g and their finite-difference gradients at x, from one population
    evaluation of the stencil (cached on x)."""

    def __init__(self, problem: Problem, central: bool = True, size: Optional[Array] = None):
        self.p = problem
        self.central = central
        self.key: Optional[bytes] = None
        span = np.where(np.isfinite(problem.hi - problem.lo), problem.hi - problem.lo, 1.0)
        self.h_floor = 1e-9 * np.maximum(span, 1e-12)
        # each variable's typical size: the steps are relative to it, never to 1 (a
        # length in metres and one in millimetres get the same relative step)
        self.size = np.ones(problem.n) if size is None else np.asarray(size, dtype=float)

    def _at(self, x: Array) -> None:
        x = np.asarray(x, dtype=float)
        key = x.tobytes()
        if key == self.key:
            return
        n = x.size
        # step ~ eps^(1/3) (central) or eps^(1/2) (forward) of the variable's size
        rel = 6e-6 if self.central else 1.5e-8
        h = np.maximum(rel * np.maximum(np.abs(x), self.size), self.h_floor)
        rows = [x]
        for i in range(n):
            e = np.zeros(n)
            e[i] = h[i]
            rows.append(x + e)
            if self.central:
                rows.append(x - e)
        ev = self.p.evaluate(np.array(rows))
        # the method's cost counts designs, the stencil's are its gradient
        f, g, ok = ev.f, ev.g, ev.ok
        self.f0, self.g0, self.ok0 = float(f[0]), g[0].copy(), bool(ok[0])
        df = np.zeros(n)
        dg = np.zeros((g.shape[1], n))
        for i in range(n):
            if self.central:
                jp, jm = 1 + 2 * i, 2 + 2 * i
                if ok[jp] and ok[jm]:
                    df[i] = (f[jp] - f[jm]) / (2 * h[i])
                    dg[:, i] = (g[jp] - g[jm]) / (2 * h[i])
                elif ok[jp] and ok[0]:
                    df[i] = (f[jp] - f[0]) / h[i]
                    dg[:, i] = (g[jp] - g[0]) / h[i]
                elif ok[jm] and ok[0]:
                    df[i] = (f[0] - f[jm]) / h[i]
                    dg[:, i] = (g[0] - g[jm]) / h[i]
            else:
                j = 1 + i
                if ok[j] and ok[0]:
                    df[i] = (f[j] - f[0]) / h[i]
                    dg[:, i] = (g[j] - g[0]) / h[i]
        self.df, self.dg = df, dg
        self.key = key

    def f(self, x: Array) -> float:
        self._at(x)
        return self.f0

    def grad(self, x: Array) -> Array:
        self._at(x)
        return self.df

    def g(self, x: Array) -> Array:
        self._at(x)
        return self.g0

    def jac(self, x: Array) -> Array:
        self._at(x)
        return self.dg


def _finish(problem: Problem, x: Array, method: str, message: str, converged: bool,
            iterations: int, started: float, starts: Sequence[tuple] = (),
            extra: Optional[dict] = None) -> Result:
    f, g, ok = problem.one(x)
    feasible = bool(problem.feasible(g, ok))
    return Result(np.asarray(x, dtype=float), f, g, problem.active(g), feasible,
                  bool(converged and feasible), message, method, int(iterations),
                  problem.evaluations, time.perf_counter() - started, tuple(problem.history),
                  tuple(starts), extra)


def _record(problem: Problem, iteration: int, x: Array, progress: Optional[Callable] = None,
            total: Optional[int] = None) -> None:
    f, g, ok = problem.one(x)
    violation = problem.violation(g, ok)
    problem.record(iteration, x, f, violation, ok)
    if progress is not None:
        progress(int(iteration), total, f=float(f), violation=float(violation),
                 evaluable=bool(ok))


def sizes(problem: Problem, x0: Array) -> Array:
    """Each variable's typical size: |start|, or a tenth of its bounds' span
    when the start is 0 (1 when that is not finite either)."""
    x0 = np.abs(np.asarray(x0, dtype=float))
    span = problem.hi - problem.lo
    alt = np.where(np.isfinite(span) & (span > 0), 0.1 * span, 1.0)
    return np.where(x0 > 0, x0, alt)


def _local(problem: Problem, method: str, x0: Array, tol: float, maxiter: int,
           central: bool = True, progress: Optional[Callable] = None, done: int = 0
           ) -> Tuple[Array, bool, int, str]:
    """A local method on the scaled problem: u = x / size (every variable of
    order 1), F = f / |f(start)|, G = g / scale; so tol means the same whatever
    the unit of the lengths (a four-bar in metres or in millimetres)."""
    from scipy import optimize

    size = sizes(problem, x0)
    f0, _, ok0 = problem.one(x0)
    fref = abs(f0) if ok0 and np.isfinite(f0) and f0 != 0 else 1.0
    sm = _Smooth(problem, central, size)
    cs = problem.scales
    bounds = optimize.Bounds(problem.lo / size, problem.hi / size)
    u0 = np.asarray(x0, dtype=float) / size
    it = [0]

    def F(u: Array) -> float:
        v = sm.f(u * size)
        return v / fref if sm.ok0 else _WALL + float(problem.violation(sm.g0, False))

    def DF(u: Array) -> Array:
        return sm.grad(u * size) * size / fref

    def G(u: Array) -> Array:
        return sm.g(u * size) / cs

    def DG(u: Array) -> Array:
        return sm.jac(u * size) * size[None, :] / cs[:, None]

    def cb(uk: Any, *args: Any):
        it[0] += 1
        # the count goes on over the starts of a multi-start (*done* before this one)
        _record(problem, it[0], np.asarray(getattr(uk, "x", uk)) * size,
                None if progress is None else
                (lambda k, total, **v: progress(done + k, total, **v)))

    k = len(problem.constraint_names)
    if method == "slsqp":
        cons = ([{"type": "ineq", "fun": lambda u: -G(u), "jac": lambda u: -DG(u)}]
                if k else [])
        import warnings
        with warnings.catch_warnings():
            # scipy < 1.16 notes that it clipped a step to the bounds (it does; harmless)
            warnings.filterwarnings("ignore", message="Values in x were outside bounds")
            res = optimize.minimize(F, u0, jac=DF, method="SLSQP", bounds=bounds,
                                    constraints=cons, callback=cb,
                                    options={"ftol": tol, "maxiter": maxiter})
        nit = res.nit
        converged = res.status == 0
        capped = res.status == 9
    elif method == "trust-constr":
        cons = ([optimize.NonlinearConstraint(G, -np.inf, 0.0, jac=DG,
                                              hess=optimize.BFGS())] if k else [])
        res, nit = _trust_constr(F, DF, u0, bounds, cons, tol, maxiter, cb)
        # status 2: the trust region fell below xtol (scipy's success: no step
        # is left to take at this precision); status 1 also needs the duality
        converged = res.status == 2 or (res.status == 1 and res.duality <= tol)
        capped = res.status == 0
        if res.status == 1 and res.duality > tol:
            res.message = (f"stopped with the duality measure {res.duality:.1e} above tol "
                           f"(the design may lie inside an active constraint)")
    else:   # nelder-mead with an extreme barrier
        def barrier(u: Array) -> float:
            f, g, ok = problem.one(u * size)
            if problem.feasible(g, ok):
                return f / fref
            return _WALL * (1.0 + abs(f) / fref if ok else 1.0) + float(
                problem.violation(g, ok))

        res = optimize.minimize(barrier, u0, method="Nelder-Mead", bounds=bounds, callback=cb,
                                options={"xatol": tol, "fatol": tol, "maxiter": maxiter,
                                         "adaptive": problem.n > 3})
        nit = res.nit
        converged = res.status == 0
        capped = res.status in (1, 2)
    message = str(res.message) + (" (maxiter reached)" if capped else "")
    return np.clip(res.x * size, problem.lo, problem.hi), converged, nit, message


#: trust-constr: the factor by which each restart lowers the barrier parameter
#: (scipy's own BARRIER_DECAY_RATIO between its barrier subproblems)
_BARRIER_DECAY = 0.2
#: ... and how many restarts it makes at most (the barrier parameter falls from
#: scipy's 0.1 by 0.2**12 = 4e-9 on the way: each restart's own subproblems lower it too)
_RESTARTS = 12


def _trust_constr(F: Callable[[Array], float], DF: Callable[[Array], Array], u0: Array,
                  bounds: Any, cons: Any, tol: float, maxiter: int,
                  cb: Callable[..., None]) -> Tuple[Any, int]:
    """scipy's trust-constr, continued until its design's duality measure is
    at most ``tol``; returns scipy's last result (``duality`` added) and the
    iterations of all its runs.

    scipy documents ``barrier_tol`` as a bound on the barrier parameter at the
    end, but its ``gtol`` exit asks only that the Lagrangian's gradient, with
    whatever multipliers the current barrier subproblem estimates, and the
    constraints' violation be below ``gtol``.  That holds all along a curve
    through the optimum, so the design may stop well inside an active
    constraint, wherever one release's iterates happen to meet ``gtol``
    (scipy 1.17.1 stopped a test quadratic with ``tol`` = 1e-10 at
    f - f* = 2.6e-4).  So the duality measure at the design,
    sum |multiplier x distance to its bound| / m over the m inequalities
    (bounds included; :func:`_duality`) -- what the barrier parameter is on
    the central path -- is checked, and a run that ends above ``tol`` is
    restarted from its design with the barrier parameter lowered by
    :data:`_BARRIER_DECAY`, at most :data:`_RESTARTS` times and as ``maxiter``
    allows; the run with the least measure is returned.  For a convex problem the measure
    bounds the objective:
    f - f* <= |f(start)| (m duality + gtol |u - u*|) in the scaled variables u.
    """
    import warnings

    from scipy import optimize

    mu, nit, u, best = 0.1, 0, u0, None
    for _ in range(1 + _RESTARTS):
        with warnings.catch_warnings():
            # BFGS's note on a linear constraint (its update is skipped: harmless)
            warnings.filterwarnings("ignore", message="delta_grad == 0.0")
            res = optimize.minimize(F, u, jac=DF, hess=optimize.BFGS(),
                                    method="trust-constr", bounds=bounds, constraints=cons,
                                    callback=lambda xk, state=None: cb(xk),
                                    options={"gtol": tol, "xtol": tol, "barrier_tol": tol,
                                             "maxiter": maxiter - nit,
                                             "initial_barrier_parameter": mu,
                                             "initial_barrier_tolerance": mu})
        nit += res.nit
        res.duality = _duality(res, bounds, cons)
        if best is None or (res.status in (1, 2) and res.duality < best.duality):
            best = res
        if res.status != 1 or res.duality <= tol or nit >= maxiter:
            break
        mu = _BARRIER_DECAY * min(mu, getattr(res, "barrier_parameter", mu))
        u = res.x
    return best, nit


def _duality(res: Any, bounds: Any, cons: Any):
    """The duality measure of a trust-constr result: the mean over its
    inequalities of |multiplier x distance to the nearer bound| (scipy lists
    the constraints' values and multipliers in the order given, the bounds
    last); 0 at a KKT point, where each constraint is either active or
    without force, and the barrier parameter on the central path."""
    limits = [(c.lb, c.ub) for c in cons] + [(bounds.lb, bounds.ub)]
    total, m = 0.0, 0
    for v, c, (lb, ub) in zip(getattr(res, "v", ()), getattr(res, "constr", ()), limits):
        c = np.atleast_1d(c)
        d = np.minimum(np.abs(c - lb), np.abs(ub - c))
        finite = np.isfinite(d)
        # a constraint without a finite bound has no force at a KKT point
        total += float(np.sum(np.abs(v) * np.where(finite, d, 1.0)))
        m += int(np.count_nonzero(finite))
    return total / max(m, 1)


def _check_start(problem: Problem, x0: Array, method: str) -> None:
    f, g, ok = problem.one(x0)
    # SLSQP and trust-constr walk from an infeasible start to the feasible
    # region (the book's 例 7-1 starts at x0 = [6, 2.5], which violates g7);
    # Nelder-Mead's barrier cannot, and no method starts where nothing can
    # be evaluated
    if not ok or (method == "nelder-mead" and not problem.feasible(g, ok)):
        bad = [n for n, v, s in zip(problem.constraint_names, g, problem.scales)
               if v > Problem.FEASIBLE_TOL * s]
        raise DescribedError(
            f"the start is {'not evaluable' if not ok else 'infeasible'} for the local method "
            f"{method}", "infeasible_start", x=np.asarray(x0, dtype=float), violated=bad,
            evaluable=ok, g=g)


def _de(problem: Problem, tol: float, maxiter: int, popsize: int, seed: Optional[int],
        polish: bool, central: bool,
        progress: Optional[Callable] = None) -> Tuple[Array, bool, int, str]:
    from scipy import optimize

    ev0 = problem.evaluate(problem.start[None, :])
    ref = abs(float(ev0.f[0])) if ev0.ok[0] and ev0.f[0] != 0 else 1.0
    it = [0]

    def fun(xt: Array) -> Array:             # xt: (n, S), vectorized
        ev = problem.evaluate(xt.T)
        feas = problem.feasible(ev.g, ev.ok)
        pen = _WALL + problem.violation(ev.g, ev.ok)
        return np.where(feas, ev.f / ref, pen)

    def cb(intermediate_result: Any):
        it[0] += 1
        _record(problem, it[0], intermediate_result.x, progress, maxiter)

    res = optimize.differential_evolution(
        fun, list(zip(problem.lo, problem.hi)), popsize=popsize, tol=tol, maxiter=maxiter,
        seed=seed, polish=False, vectorized=True, updating="deferred", callback=cb,
        init="latinhypercube", x0=problem.start)
    x = res.x
    converged = bool(res.success)
    message = str(res.message) + (" (maxiter reached)" if not converged and res.nit >= maxiter
                                  else "")
    f, g, ok = problem.one(x)
    if polish and problem.feasible(g, ok):
        xp, conv_p, nit_p, msg_p = _local(problem, "slsqp", x, 1e-12, 200, central)
        fp, gp, okp = problem.one(xp)
        if problem.feasible(gp, okp) and fp <= f:
            x = xp
            message += f"; polished by SLSQP ({nit_p} iterations)"
            it[0] += nit_p
            if not converged and conv_p:
                # the generations ran out (maxiter is DE's budget) but the best design
                # is a converged local optimum: a result, with a warning (the report
                # says the global optimum is not guaranteed)
                converged = True
                message += "; DE itself stopped at maxiter"

    return x, converged, it[0], message


def _scalar(problem: Problem, method: str, tol: float, maxiter: int
            ) -> Tuple[Array, bool, int, str]:
    from mechcli.core.numerics import golden_section_max
    lo, hi = float(problem.lo[0]), float(problem.hi[0])
    if method == "golden":
        # the book's golden section (例 7-2): shrink [lo, hi] by 0.618 per step
        # until it is shorter than tol (in the variable's numbers)
        steps = max(1, math.ceil(math.log(max(tol, 1e-15) / (hi - lo)) / math.log(0.6180339887)))
        steps = min(steps, maxiter)

        def neg(x: Array) -> Array:
            ev = problem.evaluate(np.asarray(x, dtype=float).reshape(-1, 1))
            feas = problem.feasible(ev.g, ev.ok)
            # every step evaluates one new point: it is the step's row of the history
            problem.record(len(problem.history), np.ravel(x)[:1], float(ev.f[0]),
                           float(problem.violation(ev.g, ev.ok)[0]), bool(ev.ok[0]))
            return np.where(feas, -ev.f, -(_WALL + problem.violation(ev.g, ev.ok)))

        x, _ = golden_section_max(neg, np.array([lo]), np.array([hi]), iterations=steps,
                                  rtol=0.0)
        _record(problem, len(problem.history), x)
        return np.array([float(x[0])]), True, steps, f"golden section, {steps} steps"
    from scipy import optimize

    def f1(x: float) -> float:
        f, g, ok = problem.one(np.array([x]))
        return f if problem.feasible(g, ok) else _WALL + float(problem.violation(g, ok))

    res = optimize.minimize_scalar(f1, bounds=(lo, hi), method="bounded",
                                   options={"xatol": tol, "maxiter": maxiter})
    _record(problem, res.nit, np.array([res.x]))
    return np.array([res.x]), bool(res.success), res.nit, str(res.message)


def minimize(problem: Problem, method: str = "slsqp", *, tol: float = 1e-10, maxiter: int = 1000,
             popsize: int = 15,
             seed: Optional[int] = None, starts: int = 1, polish: bool = True, central: bool = True,
             progress: Optional[Callable] = None) -> Result:
    """Minimize ``problem`` by ``method`` (one of :data:`METHODS`).

    *progress*, if given, is called as ``progress(done, total, f=, violation=,
    evaluable=)`` after each iteration with its design's objective (a placeholder
    where not evaluable), violation and whether it could be evaluated: for
    differential evolution *done* counts generations of *total* = ``maxiter`` (the
    polish is not counted); for a local method iterations over all the starts, of
    *total* None (they stop when converged); golden and Brent do not call it.

    Raises
    ------
    DescribedError
        ``reason="infeasible_start"`` for a local method whose start violates a
        constraint or cannot be evaluated; ``"infeasible"`` when no feasible
        design was found; ``"scalar"`` for golden/brent with more than one
        variable.
    ConvergenceError
        The method stopped at ``maxiter`` without converging.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    started = time.perf_counter()
    problem.started = started
    x0 = problem.start
    starts_out = []
    if method in SCALAR:
        if problem.n != 1:
            raise DescribedError(f"{method} searches one variable, the problem has {problem.n}",
                                 "scalar", n=problem.n)
        x, converged, nit, message = _scalar(problem, method, tol, maxiter)
    elif method == "differential_evolution":
        x, converged, nit, message = _de(problem, tol, maxiter, popsize, seed, polish, central,
                                         progress)
    else:
        _check_start(problem, x0, method)
        x, converged, nit, message = _local(problem, method, x0, tol, maxiter, central,
                                            progress)
        if starts > 1:
            from scipy.stats import qmc
            more = qmc.scale(qmc.LatinHypercube(d=problem.n, seed=seed).random(starts - 1),
                             problem.lo, problem.hi)
            f, g, ok = problem.one(x)
            starts_out.append((x0, x, f, bool(problem.feasible(g, ok))))
            best = (f if problem.feasible(g, ok) else math.inf, x, converged, nit, message)
            for s in more:
                fs, gs, oks = problem.one(s)
                if not problem.feasible(gs, oks) and method == "nelder-mead":
                    starts_out.append((s, s, fs, False))
                    continue
                xs, cs, ns, ms = _local(problem, method, s, tol, maxiter, central,
                                        progress, nit)
                fe, ge, oke = problem.one(xs)
                feas = bool(problem.feasible(ge, oke))
                starts_out.append((s, xs, fe, feas))
                if feas and fe < best[0]:
                    best = (fe, xs, cs, ns, ms)
                nit += ns
            _, x, converged, _, message = best
            message += f"; best of {starts} starts"
    result = _finish(problem, x, method, message, converged, nit, started, starts_out)
    if not result.feasible:
        if not converged and "maxiter" in message:
            exc = ConvergenceError(f"{method} did not converge within {maxiter} iterations: "
                                   f"{message}")
            exc.result = result
            raise exc
        raise DescribedError(f"{method} found no feasible design ({message})", "infeasible",
                             x=result.x, g=result.g, f=result.f)
    if not converged:
        exc = ConvergenceError(f"{method} did not converge within {maxiter} iterations: "
                               f"{message}" if "maxiter" in message else
                               f"{method} stopped without converging: {message}")
        exc.result = result
        raise exc
        raise DescribedError(f"{method} found no feasible design", "infeasible",
                             x=result.x, g=result.g, f=result.f)
    return result
