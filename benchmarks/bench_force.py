"""Speed and accuracy-vs-cost of the kinetostatics (`mechcli force`).

Prints `name: value unit` lines.  Compare ratios within one run: machines are
shared and noisy.  Target (issue #6): 36,001 positions of 例 2-4 (the shaper
six-bar, 15 unknowns) solved in <= 50 ms of compute.

Usage: python benchmarks/bench_force.py [--quick] [--json]
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

from benchmarks.bench_kin import best_of  # noqa: E402
from mechcli._alloc import keep_heap_warm  # noqa: E402
from mechcli.core.linkage.force_analysis import ForceEvaluator, analyse_forces  # noqa: E402
from mechcli.core.linkage.kinematics import Sweep  # noqa: E402
from mechcli.core.linkage.kinetostatics import solve_forces  # noqa: E402
from mechcli.core.linkage import solve  # noqa: E402
from mechcli.spec.force import load_force_spec  # noqa: E402


def main(quick=False):
    keep_heap_warm()
    spec = load_force_spec(ROOT / "configs" / "ch2" / "ex2-4.toml")
    inp = spec.input
    rep = 3 if quick else 7
    n = 36001
    q = np.linspace(0, 2 * np.pi, n)
    sweep = Sweep(inp.driver, q, inp.omega, inp.alpha, inp.followers, True)
    unit = Sweep(inp.driver, q, 1.0, 0.0, inp.followers, True)
    motion = solve(spec.linkage, sweep.inputs(q), 2)
    umotion = solve(spec.linkage, unit.inputs(q), 1)
    progs = [p.with_band_limits(-0.417137832736, 0.128316712718) for p in spec.loads]
    loads = [p.evaluate(q, motion)[0] for p in progs]
    nunk = sum(2 for _ in spec.topology.pairs) + len(spec.linkage.drivers)
    print(f"ex2-4 unknowns: {nunk}")

    def force_only():
        solve_forces(spec.topology, motion, spec.bodies, loads, spec.gravity, umotion,
                     condition=False)

    def force_cond():
        solve_forces(spec.topology, motion, spec.bodies, loads, spec.gravity, umotion,
                     condition=True)

    pipe = ForceEvaluator(spec.linkage, spec.topology, sweep, spec.bodies, spec.gravity, progs)
    t = best_of(force_only, rep)
    print(f"ex2-4_forces_36001_given_motion: {t * 1e3:.1f} ms (target <= 50)")
    print(f"ex2-4_forces_36001_given_motion_with_condition: "
          f"{best_of(force_cond, rep) * 1e3:.1f} ms")
    print(f"ex2-4_pipeline_36001: {best_of(lambda: pipe(q), rep) * 1e3:.1f} ms "
          "(kinematics + loads + kinetostatics)")
    # the fixed cost of one call (issue 17: <= 0.5 ms), against one position solve
    q1 = q[:1]
    m1 = solve(spec.linkage, sweep.inputs(q1), 2)
    u1 = solve(spec.linkage, unit.inputs(q1), 1)
    l1 = [p.evaluate(q1, m1)[0] for p in progs]
    t_pos = best_of(lambda: solve(spec.linkage, sweep.inputs(q1), 2), 50)
    t_one = best_of(lambda: solve_forces(spec.topology, m1, spec.bodies, l1, spec.gravity, u1,
                                         condition=False), 50)
    t_one_c = best_of(lambda: solve_forces(spec.topology, m1, spec.bodies, l1, spec.gravity,
                                           u1, condition=True), 50)
    t_pipe1 = best_of(lambda: pipe(q1, condition=True), 50)
    print(f"position_solve_1_position: {t_pos * 1e3:.3f} ms")
    print(f"ex2-4_forces_1_position: {t_one * 1e3:.3f} ms")
    print(f"ex2-4_forces_1_position_over_position_solve: {t_one / t_pos:.2f} x")
    print(f"ex2-4_forces_1_position_with_condition: {t_one_c * 1e3:.3f} ms")
    print(f"ex2-4_pipeline_1_position: {t_pipe1 * 1e3:.3f} ms")
    print(f"ex2-4_pipeline_1_position_over_position_solve: {t_pipe1 / t_pos:.2f} x")
    # accuracy vs cost: the mean and the extremes against the step of the sweep
    ref = None
    for step in (0.01, 0.1, 0.5, 1.0, 5.0, 10.0):
        qq = np.radians(np.arange(0.0, 360.0 + step / 2, step))
        sw = Sweep(inp.driver, qq, inp.omega, inp.alpha, inp.followers, True)
        t0 = time.perf_counter()
        res = analyse_forces(spec.linkage, spec.topology, sw, spec.bodies, spec.gravity,
                             spec.loads)
        dt = time.perf_counter() - t0
        mean, mx = res.mean["Mb"], res.extremes["Mb"][0].value
        if ref is None:
            ref = (mean, mx)
        tag = f"ex2-4_step_{step:g}deg"
        print(f"{tag}_analyse: {dt * 1e3:.1f} ms")
        print(f"{tag}_mean_Mb: {mean:.9f} N_m")
        print(f"{tag}_mean_Mb_diff: {abs(mean - ref[0]):.1e} N_m (to the 0.01 deg step)")
        print(f"{tag}_max_Mb: {mx:.9f} N_m")
        print(f"{tag}_max_Mb_diff: {abs(mx - ref[1]):.1e} N_m (to the 0.01 deg step)")
    with tempfile.TemporaryDirectory() as tmp:
        base = best_of(lambda: subprocess.run([sys.executable, "-c", "import numpy"],
                                              check=True), 1 if quick else 3)
        print(f"process_import_numpy: {base:.3f} s")
        for args, label in (([], "png"), (["--no-plot"], "no_plot"),
                            (["--animate"], "png_gif72")):
            cmd = [sys.executable, "-m", "mechcli", "force",
                   str(ROOT / "configs" / "ch2" / "ex2-4.toml"), "--out", tmp, "-q", *args]
            t = best_of(lambda: subprocess.run(cmd, check=True), 1 if quick else 3)
            print(f"process_force_ex2-4_{label}: {t:.2f} s")
            print(f"process_force_ex2-4_{label}_over_import_numpy: {t / base:.1f} x")


if __name__ == "__main__":
    def _all():
        main("--quick" in sys.argv)

    run(_all)
