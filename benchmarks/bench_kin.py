"""Speed and accuracy-vs-cost of the linkage engine and of `mechcli kin`.

Prints `name: value unit` lines.  Compare ratios within one run: machines are
shared and noisy.  Targets (issue #2): 36,001 four-bar positions with
velocities and accelerations <= 5 ms; 1,000,001 <= 150 ms and <= 400 MB peak;
`mechcli kin ex1-1 --no-plot` <= 0.6 s; with PNGs <= 2 s; with a 72-frame GIF
<= 4 s; `mechcli --version` <= 1.5x `python -c "import numpy"`.

Usage: python benchmarks/bench_kin.py [--quick]
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from mechcli._alloc import keep_heap_warm  # noqa: E402
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities  # noqa: E402
from mechcli.core.linkage import RRR, Crank, DriverMotion, Ground, Linkage, solve  # noqa: E402


def fourbar():
    return Linkage(4, (Ground("A", 0, 0), Ground("D", 0.3048, 0), Crank(1, "A", "B", 0.1016),
                       RRR("C", "B", 2, 0.254, "D", 3, 0.1778, 1)))


def best_of(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def engine(n, repeat):
    lk = fourbar()
    th = np.linspace(0, 2 * np.pi, n)
    return best_of(lambda: solve(lk, {1: DriverMotion(th, 250.0)}, order=2), repeat)


def peak_memory(n):
    lk = fourbar()
    tracemalloc.start()
    th = np.linspace(0, 2 * np.pi, n)
    solve(lk, {1: DriverMotion(th, 250.0)}, order=2)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def process(args, repeat):
    return best_of(lambda: subprocess.run(args, cwd=ROOT, capture_output=True, check=True), repeat)


def accuracy_vs_step():
    """Error of grid extremes (no refinement) vs the refined ones, per angle step."""
    lk = fourbar()
    qs = default_quantities(lk, 2)
    ref = analyse_sweep(lk, Sweep(1, np.linspace(0, 2 * np.pi, 361), 250.0, 0.0, {}, True), qs, 2)
    for step in (15.0, 5.0, 1.0, 0.1, 0.01):
        q = np.radians(np.arange(0.0, 360.0 + step / 2, step))
        t = time.perf_counter()
        m = solve(lk, {1: DriverMotion(q, 250.0)}, order=2)
        cost = time.perf_counter() - t
        err = 0.0
        for sym in ("omega3", "alpha3"):
            v = qs[[q_.symbol for q_ in qs].index(sym)].get(m)
            exact = ref.extremes[sym][0].value
            err = max(err, abs(v.max() - exact) / abs(exact))
        print(f"grid_extreme_rel_error_step_{step:g}deg: {err:.3e} 1")
        print(f"grid_solve_time_step_{step:g}deg: {cost * 1e3:.2f} ms")
    for step in (15.0, 1.0):
        res = analyse_sweep(lk, Sweep(1, np.radians(np.arange(0, 360 + step / 2, step)), 250.0,
                                      0.0, {}, True), qs, 2)
        at = np.array([e.at for e in res.extremes["theta3"]])
        m = solve(lk, {1: DriverMotion(at, 250.0)}, order=2)
        # distance to the true stationary point: one Newton step |omega3 / alpha3| * omega1
        newton = np.max(np.abs(m.links[3].omega / m.links[3].alpha * 250.0))
        print(f"refined_theta3_extreme_location_error_step_{step:g}deg: {newton:.1e} rad")
    t = time.perf_counter()
    analyse_sweep(lk, Sweep(1, np.radians(np.arange(0, 361, 5.0)), 250.0, 0.0, {}, True), qs, 2)
    print(f"analyse_sweep_with_refined_extremes_step_5deg: {(time.perf_counter() - t) * 1e3:.2f} ms")


def main():
    quick = "--quick" in sys.argv
    print(f"allocator_keeps_heap_warm: {int(keep_heap_warm())} bool")
    r = 3 if quick else 7
    print(f"engine_fourbar_36001_pva: {engine(36001, r) * 1e3:.2f} ms")
    print(f"engine_fourbar_1000001_pva: {engine(1000001, 2 if quick else 3) * 1e3:.1f} ms")
    print(f"engine_fourbar_1000001_peak_memory: {peak_memory(1000001) / 2**20:.0f} MB")
    accuracy_vs_step()
    py = sys.executable
    cfg = str(ROOT / "configs" / "ch1" / "ex1-1.toml")
    with tempfile.TemporaryDirectory() as out:
        numpy_t = process([py, "-c", "import numpy"], r)
        version_t = process([py, "-m", "mechcli", "--version"], r)
        print(f"process_import_numpy: {numpy_t * 1e3:.0f} ms")
        print(f"process_mechcli_version: {version_t * 1e3:.0f} ms")
        print(f"process_version_over_import_numpy: {version_t / numpy_t:.2f} x")
        base = [py, "-m", "mechcli", "kin", cfg, "--quiet", "--out", out]
        print(f"process_kin_ex1-1_no_plot: {process(base + ['--no-plot'], r) * 1e3:.0f} ms")
        print(f"process_kin_ex1-1_plots: {process(base, 2 if quick else 3) * 1e3:.0f} ms")
        print(f"process_kin_ex1-1_plots_gif72: "
              f"{process(base + ['--animate'], 1 if quick else 2) * 1e3:.0f} ms")


if __name__ == "__main__":
    main()
