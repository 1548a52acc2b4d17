"""Speed and accuracy-vs-cost of the kinetostatics (`mechcli force`).

Prints `name: value unit` lines.  Compare ratios within one run: machines are
shared and noisy.  Target (issue #6): 36,001 positions of 例 2-4 (the shaper
six-bar, 15 unknowns) solved in <= 50 ms of compute.

Usage: python benchmarks/bench_force.py [--quick]
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
    print(f"kinetostatics, 36,001 positions (given the motion): {t * 1e3:.1f} ms  (target <= 50)")
    print(f"  with condition numbers of every block: {best_of(force_cond, rep) * 1e3:.1f} ms")
    print(f"kinematics + loads + kinetostatics, 36,001 positions: "
          f"{best_of(lambda: pipe(q), rep) * 1e3:.1f} ms")
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
        print(f"step {step:5.2f} deg: analyse {dt * 1e3:7.1f} ms, mean Mb {mean:.9f} "
              f"(diff {abs(mean - ref[0]):.1e}), max Mb {mx:.9f} (diff {abs(mx - ref[1]):.1e})")
    with tempfile.TemporaryDirectory() as tmp:
        for args, label in (([], "with PNGs"), (["--no-plot"], "--no-plot"),
                            (["--animate"], "with PNGs and 72-frame GIF")):
            cmd = [sys.executable, "-m", "mechcli", "force",
                   str(ROOT / "configs" / "ch2" / "ex2-4.toml"), "--out", tmp, "-q", *args]
            t = best_of(lambda: subprocess.run(cmd, check=True), 1 if quick else 3)
            print(f"mechcli force ex2-4 {label}: {t:.2f} s")


if __name__ == "__main__":
    main("--quick" in sys.argv)
