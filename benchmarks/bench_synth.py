"""Speed and accuracy-vs-cost of the rigid-body guidance synthesis (`mechcli synth`).

Prints `name: value unit` lines.  Compare ratios within one run: machines are
shared and noisy.  The baseline is a plain numpy 2x2 solve (`np.linalg.solve`
of one circumcentre's two bisector equations) timed in the same run.

* 【例 3-4】 by the displacement matrix and by the nonlinear solve (【例 3-5】):
  time per design, as multiples of the baseline and of each other, and the
  difference between the two designs; the nonlinear solve's `tol` against its
  iterations, time and error (the error-vs-cost table of the `tol` key).
* Burmester points of five poses (target: <= 50 ms per solve), and the curves
  of four poses at the default resolution and at `samples` = 4001.

Usage: python benchmarks/bench_synth.py [--quick] [--json]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

from mechcli.core.linkage import DriverMotion, solve  # noqa: E402
from mechcli.core.synth.design import four_bar_design  # noqa: E402
from mechcli.core.synth.guidance import (burmester_curves, burmester_points,  # noqa: E402
                                         coupler_poses)

MM = 1e-3
EX34_M = [(10 * MM, 32 * MM), (36 * MM, 39 * MM), (45 * MM, 24 * MM)]
EX34_PHI = np.radians([52.0, 29.0, 0.0])
EX34_A, EX34_D = (0.0, 0.0), (63 * MM, 0.0)


def per_call(fn, number, repeat):
    """Best time of one call [s] over ``repeat`` runs of ``number`` calls."""
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t) / number)
    return best


def baseline():
    """One circumcentre as a plain numpy 2x2 solve of the bisector equations."""
    z = np.array([0.0 + 1.0j, 1.0 + 2.0j, 3.0 + 2.0j])
    a, b = z[1] - z[0], z[2] - z[0]
    A = np.array([[a.real, a.imag], [b.real, b.imag]])
    rhs = np.array([abs(a) ** 2, abs(b) ** 2]) / 2
    return lambda: np.linalg.solve(A, rhs)


def five_poses():
    """Five coupler poses of a four-bar moved on the engine."""
    d = four_bar_design((0.0, 0.0), (0.3, 0.05), (0.05, 0.09), (0.28, 0.22),
                        coupler_point=(0.2, 0.3))
    th = np.radians([0.0, 25.0, 50.0, 90.0, 140.0]) + np.angle(0.05 + 0.09j)
    m = solve(d.linkage, {1: DriverMotion(th)}, order=0)
    return list(zip(m.points["M"].x, m.points["M"].y)), m.links[2].theta


def main():
    quick = "--quick" in sys.argv
    number, repeat = (200, 3) if quick else (1000, 5)
    t_base = per_call(baseline(), number * 10, repeat)
    print(f"baseline_numpy_2x2_solve: {t_base * 1e6:.2f} us")

    def matrix():
        return coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method="matrix")

    def nonlinear(tol=1e-12):
        return coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method="nonlinear", tol=tol)

    t_mat = per_call(matrix, number // 5, repeat)
    t_non = per_call(nonlinear, number // 10, repeat)
    a, b = matrix(), nonlinear()
    diff = max(abs(complex(*a.pivots[k]) - complex(*b.pivots[k])) for k in ("B1", "C1")) / a.size
    print(f"ex3-4_matrix: {t_mat * 1e6:.0f} us")
    print(f"ex3-4_matrix_over_baseline: {t_mat / t_base:.0f} x")
    print(f"ex3-5_nonlinear: {t_non * 1e6:.0f} us")
    print(f"ex3-5_nonlinear_over_baseline: {t_non / t_base:.0f} x")
    print(f"ex3-5_nonlinear_over_matrix: {t_non / t_mat:.1f} x")
    print(f"ex3-5_nonlinear_minus_matrix: {diff:.1e} 1 (relative to the size)")
    for tol in (1e-3, 1e-6, 1e-9, 1e-12, 1e-15):
        d = nonlinear(tol)
        err = max(abs(complex(*a.pivots[k]) - complex(*d.pivots[k])) for k in ("B1", "C1"))
        t = per_call(lambda: nonlinear(tol), number // 20, repeat)
        print(f"ex3-5_tol_{tol:.0e}_iterations: {d.values['iterations']} 1")
        print(f"ex3-5_tol_{tol:.0e}_over_matrix: {t / t_mat:.1f} x")
        print(f"ex3-5_tol_{tol:.0e}_error: {err / a.size:.1e} 1 (relative to the size)")
        print(f"ex3-5_tol_{tol:.0e}_residual: {d.values['residual']:.1e} 1")

    M, phi = five_poses()
    t_five = per_call(lambda: burmester_points(M, phi), max(number // 50, 5), repeat)
    pairs = burmester_points(M, phi)
    print(f"burmester_five_poses: {t_five * 1e3:.2f} ms (target 50 ms), {len(pairs)} pairs")
    print(f"burmester_five_poses_over_baseline: {t_five / t_base:.0f} x")
    print(f"burmester_five_poses_over_matrix: {t_five / t_mat:.0f} x")
    for n in (721, 4001):
        t = per_call(lambda: burmester_curves(M[:4], phi[:4], n=n), max(number // 100, 3),
                     repeat)
        cv = burmester_curves(M[:4], phi[:4], n=n)
        pts = sum(len(c) for c in cv.centre)
        print(f"burmester_curves_n{n}: {t * 1e3:.2f} ms, {pts} points in "
              f"{len(cv.centre)} branches, {t / t_base:.0f} x baseline")

    structural_error_samples(t_base)


def structural_error_samples(t_base):
    """The ``samples`` knob of function generation: the largest structural error of
    【例 3-7】 (y = lg x, Chebyshev) read on n samples, against 1,000,001 samples."""
    import math

    from mechcli.core.synth.function import function_generator
    from mechcli.core.synth.targets import make_function

    f = make_function("log10")

    def run(n):
        return function_generator(f, 1.0, 2.0, alpha_m=math.radians(60), phi_m=math.radians(90),
                                  alpha0=math.radians(86), phi0=math.radians(23.5),
                                  method="chebyshev", n=3, samples=n)

    def interior_peak(v):
        """The largest |Δy| at an interior local maximum (the ends are always sampled)."""
        import numpy as np
        e = np.abs(np.asarray(v["error_y"], dtype=float))
        inner = (e[1:-1] >= e[:-2]) & (e[1:-1] >= e[2:])
        return float(e[1:-1][inner].max()) if inner.any() else 0.0

    ref = run(1_000_001).values
    print(f"ex3-7_largest_error_at_x: {ref['error_x'][int(abs(ref['error_y']).argmax())]:g} "
          "(an end of the interval: every sample count has it exactly)")
    for n in (11, 101, 1001, 10001, 100001):
        t = per_call(lambda: run(n), number=3, repeat=3)
        v = run(n).values
        print(f"ex3-7_samples_{n}: {t * 1e3:.2f} ms ({t / t_base:.0f} x baseline), "
              f"error_y_max off by {abs(v['error_y_max'] - ref['error_y_max']):.1e}, "
              f"largest interior peak off by "
              f"{abs(interior_peak(v) - interior_peak(ref)) / interior_peak(ref):.1e} (relative)")


if __name__ == "__main__":
    run(main)
