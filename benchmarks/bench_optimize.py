"""Optimization: what each method and tolerance buys, and how fast the engine
evaluates a population (issue 14).

Prints ``name: value unit`` lines (``--json``: one JSON object of them):

* for 【例 7-1】 (and 习题 7-3 when ``configs/ch7/exercise7-3.toml`` exists) and each
  method × tol: the objective reached, its gap to the best known optimum, the
  distance of x to it, evaluations and time -- the speed/accuracy table a user
  chooses from (docs/optimize.md);
* the engine's throughput on a four-bar path objective (coupler point over a
  revolution, distance to 10 targets), in linkage-positions per second, against a
  plain numpy closed form of the same four-bar in the same run (ratio);
* the path objective's sampling error: the distance to the polyline through
  ``samples`` positions against 20,001 positions.

Run: ``python benchmarks/bench_optimize.py [--json] [--quick]``.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from mechcli.commands.optimize import build_problem  # noqa: E402
from mechcli.core.optimize.methods import minimize  # noqa: E402
from mechcli.spec.optimize import read_optimize_spec  # noqa: E402

QUICK = "--quick" in sys.argv


def _run(path, sets, method, tol, maxiter=1000):
    spec = read_optimize_spec(path, [f"method.name={method}", *sets])
    problem, _ = build_problem(spec)
    t = time.perf_counter()
    try:
        r = minimize(problem, method, tol=tol, maxiter=maxiter, popsize=spec.method.popsize,
                     seed=spec.method.seed, starts=spec.method.starts,
                     polish=spec.method.polish, central=spec.method.central)
    except Exception as exc:        # a method that fails is a row of the table too
        return None, time.perf_counter() - t, problem.evaluations, str(exc)[:60]
    return r, time.perf_counter() - t, problem.evaluations, ""


def table(name, path, sets, cases, ref_x=None, ref_f=None):
    rows = []
    for method, tol, extra in cases:
        r, dt, nev, err = _run(path, sets + extra, method, tol)
        rows.append((method, tol, extra, r, dt, nev, err))
    best = [r for *_, r, dt, nev, err in [(a, b, c, d, e, f, g) for a, b, c, d, e, f, g in rows]
            if r is not None]
    if ref_f is None and best:
        ref_f = min(r.f for r in best)
        ref_x = min(best, key=lambda r: r.f).x
    print(f"{name}: reference f* = {ref_f:.12g} at x* = {np.round(ref_x, 8).tolist()}")
    for method, tol, extra, r, dt, nev, err in rows:
        tag = f"{name}.{method}.tol{tol:g}" + ("".join("." + e.split("=")[0].split(".")[-1]
                                                    + e.split("=")[1] for e in extra))
        if r is None:
            print(f"{tag}.failed: 1 ({err})")
            continue
        # negative: a design within the feasibility slack (Problem.FEASIBLE_TOL) of
        # an active constraint, slightly beyond it
        print(f"{tag}.f_gap: {r.f - ref_f:.3e} 1")
        print(f"{tag}.x_error: {float(np.max(np.abs(r.x - ref_x))):.3e} 1")
        print(f"{tag}.evaluations: {nev} designs")
        print(f"{tag}.time: {dt * 1e3:.1f} ms")


def _closed_form_path(l1, l2, l3, l4, along, normal, q):
    """Coupler point of a four-bar (A at 0, D at (l4, 0)), plain numpy."""
    bx, by = l1 * np.cos(q), l1 * np.sin(q)
    dx, dy = l4 - bx, -by
    d2 = dx * dx + dy * dy
    d = np.sqrt(d2)
    a = (l2 * l2 - l3 * l3 + d2) / (2 * d)
    h = np.sqrt(np.maximum(l2 * l2 - a * a, 0.0))
    cx = bx + (a * dx - h * dy) / d
    cy = by + (a * dy + h * dx) / d
    ux, uy = (cx - bx) / l2, (cy - by) / l2
    return bx + along * ux - normal * uy, by + along * uy + normal * ux


def throughput():
    from mechcli.core.linkage import PointOnLink, four_bar
    from mechcli.core.optimize import terms
    rng = np.random.default_rng(1)
    M, S = 256, 360
    l2 = rng.uniform(3.5, 4.5, (M, 1))
    l3 = rng.uniform(3.0, 4.0, (M, 1))
    targets = np.column_stack([rng.uniform(-2, 6, 10), rng.uniform(-1, 5, 10)])
    lk = four_bar(1.0, l2, l3, 4.5).with_elements(PointOnLink("M", 2, "B", 2.0, 1.0))

    def engine():
        pop = terms.Population(lk, 1, S)
        return terms.path_deviation(pop, "M", targets)[0]

    q = np.linspace(0, 2 * np.pi, S, endpoint=False)

    def plain():
        # the same distance as the engine's term (nearest sample, then its two segments),
        # on a closed-form four-bar
        px, py = _closed_form_path(1.0, l2, l3, 4.5, 2.0, 1.0, q)
        tx, ty = targets[:, 0], targets[:, 1]
        j = np.argmin((px[..., None] - tx) ** 2 + (py[..., None] - ty) ** 2, axis=-2)
        best = None
        for a, b in ((-1, 0), (0, 1)):
            ia, ib = (j + a) % S, (j + b) % S
            ax, ay = np.take_along_axis(px, ia, -1), np.take_along_axis(py, ia, -1)
            ex = np.take_along_axis(px, ib, -1) - ax
            ey = np.take_along_axis(py, ib, -1) - ay
            t = np.clip(((tx - ax) * ex + (ty - ay) * ey) / (ex * ex + ey * ey), 0, 1)
            dd = (ax + t * ex - tx) ** 2 + (ay + t * ey - ty) ** 2
            best = dd if best is None else np.minimum(best, dd)
        return np.sqrt(best)

    assert np.allclose(engine(), plain(), atol=1e-12)

    def best(fn, n=7):
        out = []
        for _ in range(n):
            t = time.perf_counter()
            fn()
            out.append(time.perf_counter() - t)
        return min(out)

    te, tp = best(engine), best(plain)
    print(f"path_objective.designs: {M} designs x {S} positions, 10 targets")
    print(f"path_objective.engine_positions_per_s: {M * S / te:.3e} 1/s")
    print(f"path_objective.plain_numpy_positions_per_s: {M * S / tp:.3e} 1/s")
    print(f"path_objective.engine_over_plain_numpy: {te / tp:.2f} x")


def sampling_error():
    from mechcli.core.linkage import PointOnLink, four_bar
    from mechcli.core.optimize import terms
    lk = four_bar(1.0, np.array([[4.0]]), np.array([[3.0]]), 4.5).with_elements(
        PointOnLink("M", 2, "B", 2.0, 1.0))
    targets = np.column_stack([np.linspace(-1, 5, 25), np.linspace(4, 0, 25)])
    ref, _ = terms.path_deviation(terms.Population(lk, 1, 20001), "M", targets)
    for s in (36, 72, 180, 360, 720, 1440):
        d, _ = terms.path_deviation(terms.Population(lk, 1, s), "M", targets)
        print(f"path_samples.{s}.distance_error: {float(np.max(np.abs(d - ref))):.2e} "
              f"(of the linkage size 4.5)")


def ex71_reference():
    """例 7-1's optimum by an independent closed form (式 7-1, 7-4 ... 7-7; g1 ... g8
    with the config's 45.00845 / 134.99155 deg) and SLSQP at ftol 1e-15, from the
    book's start: the f* and x* of the table."""
    from scipy.optimize import minimize as sp_minimize

    def f(x):
        l2, l3 = x
        p0 = np.arccos(((1 + l2) ** 2 - l3 ** 2 + 25) / (10 * (1 + l2)))
        s0 = np.arccos(((1 + l2) ** 2 - l3 ** 2 - 25) / (10 * l3))
        ph = p0 + np.arange(1, 31) * (np.pi / 2) / 30
        r = np.sqrt(26 - 10 * np.cos(ph))
        a = np.arccos((r * r + l3 * l3 - l2 * l2) / (2 * r * l3))
        b = np.arccos((r * r + 24) / (10 * r))
        ps = np.where(ph <= np.pi, np.pi - a - b, np.pi - a + b)
        return float(np.sum((ps - s0 - 2 / (3 * np.pi) * (ph - p0) ** 2) ** 2))

    cmin, cmax = math.cos(math.radians(45.00845)), math.cos(math.radians(134.99155))

    def g(x):       # >= 0 met
        l2, l3 = x
        return -np.array([1 - l2, 1 - l3, 6 - l2 - l3, l2 - l3 - 4, l3 - l2 - 4,
                          l2 * l2 + l3 * l3 - 16 - 2 * l2 * l3 * cmin,
                          36 + 2 * l2 * l3 * cmax - l2 * l2 - l3 * l3])

    r = sp_minimize(f, [6.0, 2.5], method="SLSQP", constraints=[{"type": "ineq", "fun": g}],
                    options={"ftol": 1e-15, "maxiter": 500})
    return r.x, r.fun


def main():
    ex71 = ROOT / "configs/ch7/ex7-1.toml"
    ref_x, ref_f = ex71_reference()
    cases = [("slsqp", t, []) for t in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)]
    cases += [("trust-constr", t, []) for t in (1e-6, 1e-8, 1e-10)]
    cases += [("nelder-mead", t, ["mechanism.l2=4.5", "mechanism.l3=2.5"])
              for t in (1e-4, 1e-6, 1e-8)]
    cases += [("differential_evolution", t, []) for t in (1e-4, 1e-6, 1e-8)]
    cases += [("slsqp", 1e-10, ["method.gradient=forward"]),
              ("slsqp", 1e-10, ["method.starts=8"])]
    if QUICK:
        cases = cases[:3]
    table("ex7-1", ex71, [], cases, ref_x, ref_f)
    ex73 = ROOT / "configs/ch7/exercise7-3.toml"
    if ex73.exists() and not QUICK:
        table("exercise7-3", ex73, [],
              [("differential_evolution", t, []) for t in (1e-3, 1e-5, 1e-8)]
              + [("differential_evolution", 1e-8, [f"method.popsize={p}"]) for p in (8, 30)])
    throughput()
    sampling_error()


if __name__ == "__main__":
    try:
        from _figures import run
    except ImportError:        # the shared --json helper absent: plain text
        main()
    else:
        run(main)
