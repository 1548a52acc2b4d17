"""Accuracy and speed of ``mechcli gear`` (issue 5).

Prints ``name: value unit`` lines:

* chordal deviation of the flank polyline from the exact involute against the
  number of profile points per flank (【例 5-3】, z = 35, m = 5 mm) — chooses the
  default ``points = 40``;
* inverse-involute error and iterations across theta = 1e-12 … 1 for the
  ``auto`` start and for the book's start (0.8, |f| < 1e-7, 【例 5-2】), and the
  book start's failure region;
* process CPU time of ``mechcli gear`` for the pair of 【例 5-4】 and the
  210-value table of 【例 5-1】 (and the inverse involute, a helical pair)
  without pictures, with ``--json`` and ``-q``, next to ``python -c "import
  numpy"`` and ``mechcli --version`` (the start-up floor); these scalar kinds
  import neither numpy nor rich.  Then the in-process time of spec -> solve ->
  report.

Run: ``python benchmarks/bench_gear.py [--runs N] [--json]``
"""

from __future__ import annotations

import argparse
import math
import os
import resource
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

from mechcli.core.errors import ConvergenceError  # noqa: E402
from mechcli.core.gear.spur import spur_gear  # noqa: E402
from mechcli.core.gear.profile import flank_chordal_deviation  # noqa: E402
from mechcli.core.gear.involute import inverse_involute  # noqa: E402


def _child_cpu(argv, runs, env=None):
    best = math.inf
    for _ in range(runs):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(argv, cwd=ROOT, check=True, capture_output=True, env=env)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        best = min(best, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime))
    return best


def chordal():
    g = spur_gear(35, 5e-3, math.radians(20))
    for n in (5, 10, 20, 40, 80, 160, 320):
        dev = flank_chordal_deviation(g, g.rb, g.ra, n)
        print(f"chordal_deviation_points_{n}: {dev * 1e6:.4g} um")


def inverse():
    theta = np.logspace(-12, 0, 2401)
    auto = inverse_involute(theta)
    print(f"inverse_auto_max_relative_residual: {auto.relative_residual.max():.3g} 1")
    print(f"inverse_auto_iterations_max: {auto.iterations.max()} 1")
    print(f"inverse_auto_iterations_mean: {auto.iterations.mean():.3g} 1")
    for lo, hi in ((1e-12, 1e-6), (1e-6, 1e-3), (1e-3, 0.1), (0.1, 1.0)):
        m = (theta >= lo) & (theta <= hi)
        print(f"inverse_auto_iterations_{lo:g}_{hi:g}: {auto.iterations[m].max()} 1")
    ok = theta < 1.04
    book = inverse_involute(theta[ok], method="book")
    rel = book.relative_residual
    print(f"inverse_book_iterations_max: {book.iterations.max()} 1")
    for lo, hi in ((1e-12, 1e-9), (1e-9, 1e-6), (1e-6, 1e-4), (1e-4, 1e-2), (1e-2, 1.04)):
        m = (theta[ok] >= lo) & (theta[ok] <= hi)
        print(f"inverse_book_max_relative_residual_{lo:g}_{hi:g}: {rel[m].max():.3g} 1")
    bad = theta[ok][rel > 1e-6]
    print(f"inverse_book_relative_error_above_1e-6_below_theta: {bad.max():.3g} rad")
    limit = math.tan(0.8) - 0.8 + (math.pi / 2 - 0.8) * math.tan(0.8) ** 2
    print(f"inverse_book_diverges_above_theta: {limit:.5g} rad")
    try:
        inverse_involute(limit * 1.001, method="book")
        print("inverse_book_above_limit_converges: 1 bool")
    except ConvergenceError:
        print("inverse_book_above_limit_converges: 0 bool (ConvergenceError)")
    t0 = time.perf_counter()
    for _ in range(20):
        inverse_involute(theta)
    per = (time.perf_counter() - t0) / 20 / theta.size
    print(f"inverse_auto_time_per_value: {per * 1e9:.3g} ns")


def speed(runs):
    with tempfile.TemporaryDirectory() as tmp:
        # an installed package has its bytecode cached; PYTHONDONTWRITEBYTECODE=1 (as in
        # some sandboxes) recompiles every module on every start: measure both
        nocache = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
        t = _child_cpu([sys.executable, "-m", "mechcli", "gear", "configs/ch5/ex5-4.toml",
                        "--no-plot", "-q", "--out", tmp], runs, nocache)
        print(f"process_cpu_ex5-4_no_plot_q_without_bytecode_cache: {t:.3f} s")
        cached = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        cached["PYTHONPYCACHEPREFIX"] = str(Path(tmp) / "pycache")
        os.environ.clear()
        os.environ.update(cached)
        base = _child_cpu([sys.executable, "-c", "import numpy"], runs)
        print(f"process_cpu_import_numpy: {base:.3f} s")
        t = _child_cpu([sys.executable, "-m", "mechcli", "--version"], runs)
        print(f"process_cpu_mechcli_version: {t:.3f} s")
        for name in ("ex5-4", "ex5-1", "ex5-2", "exercise5-7"):
            for flag in ("--json", "-q"):
                t = _child_cpu([sys.executable, "-m", "mechcli", "gear",
                                f"configs/ch5/{name}.toml", "--no-plot", flag, "--out", tmp],
                               runs)
                print(f"process_cpu_{name}_no_plot_{flag.strip('-')}: {t:.3f} s")
        for name in ("ex5-3", "gear-cut"):  # profile kinds: numpy (and scipy) on purpose
            t = _child_cpu([sys.executable, "-m", "mechcli", "gear", f"configs/ch5/{name}.toml",
                            "--no-plot", "-q", "--out", tmp], runs)
            print(f"process_cpu_{name}_no_plot_q: {t:.3f} s")
        from mechcli.options import RunOptions
        from mechcli.report.files import Outputs
        from mechcli.core.gear.problems import solve_gear
        from mechcli.report.gear import PRESENTERS
        from mechcli.spec.gear import read_gear_spec
        for name in ("ex5-4", "ex5-1"):
            run = RunOptions(spec_path=None, out_dir=Path(tmp), json=True, plot=False)
            read_gear_spec(ROOT / f"configs/ch5/{name}.toml")  # warm imports
            t0 = time.process_time()
            for _ in range(20):
                spec = read_gear_spec(ROOT / f"configs/ch5/{name}.toml")
                sol = solve_gear(spec.kind, spec.problem)
                PRESENTERS[spec.kind](spec, sol, run, Outputs(tmp))
            ms = (time.process_time() - t0) / 20 * 1e3
            print(f"in_process_{name}_spec_solve_report: {ms:.3g} ms")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    chordal()
    inverse()
    speed(args.runs)


if __name__ == "__main__":
    run(main)
