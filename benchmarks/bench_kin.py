"""Speed and accuracy-vs-cost of the linkage engine and of `mechcli kin`.

Prints `name: value unit` lines.  Compare ratios within one run: machines are
shared and noisy.  Targets (issue #2): 36,001 four-bar positions with
velocities and accelerations <= 5 ms; 1,000,001 <= 150 ms and <= 400 MB peak;
`mechcli kin ex1-1 --no-plot` <= 0.6 s; with PNGs <= 2 s; with a 72-frame GIF
<= 4 s; `mechcli --version` <= 1.5x `python -c "import numpy"`.  Issue #11: 10,000
four-bars x 361 positions, positions + velocities + accelerations in one
batched call, <= 1.2x a plain numpy closed form of the same batch timed in the
same run.

Issue 17: the same 36,001 positions in a fresh process with no allocator
setting <= 0.6x the numpy closed form timed in that process; peak memory of
1e6 positions at order 2 <= 200 B/position (tracemalloc); a 1e7-row `kin` sweep
streamed to its CSV in bounded memory (peak RSS against the in-memory run at
600,001 rows); the extreme refinement of 例 1-1's sweep (``refine_extremes``, warm)
<= 3 ms.

Issue 30: the class-III six-bar given by its joints (a triad by Newton), 36,001
positions with velocities and accelerations, <= 10x the four-bar in the same run.

Usage: python benchmarks/bench_kin.py [--quick] [--json]
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
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

from mechcli._alloc import keep_heap_warm  # noqa: E402
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities  # noqa: E402
from mechcli.core.linkage import (RRR, Crank, DriverMotion, Ground, Linkage, four_bar,  # noqa: E402
                                  solve)


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


def closed_form_fourbar(l1, l2, l3, l4, th, w1):
    """Plain numpy four-bar (open branch, alpha1 = 0): the baseline of the batched benchmark.

    C from the circles about B and D; omega2, omega3 and alpha2, alpha3 from
    the differentiated loop equation l1 e^(i th1) + l2 e^(i th2) = l4 + l3 e^(i th3).
    """
    bx, by = l1 * np.cos(th), l1 * np.sin(th)
    dx, dy = l4 - bx, -by
    d2 = dx * dx + dy * dy
    d = np.sqrt(d2)
    a = (l2 * l2 - l3 * l3 + d2) / (2 * d)
    h = np.sqrt(np.maximum(l2 * l2 - a * a, 0.0))
    cx = bx + (a * dx - h * dy) / d
    cy = by + (a * dy + h * dx) / d
    th2 = np.arctan2(cy - by, cx - bx)
    th3 = np.arctan2(cy, cx - l4)
    s32 = np.sin(th3 - th2)
    w2 = w1 * l1 * np.sin(th - th3) / (l2 * s32)
    w3 = w1 * l1 * np.sin(th - th2) / (l3 * s32)
    a2 = (-w1 * w1 * l1 * np.cos(th - th3) - w2 * w2 * l2 * np.cos(th2 - th3) + w3 * w3 * l3) \
        / (l2 * np.sin(th2 - th3))
    a3 = (w1 * w1 * l1 * np.cos(th - th2) + w2 * w2 * l2 - w3 * w3 * l3 * np.cos(th3 - th2)) \
        / (l3 * s32)
    return th2, th3, w2, w3, a2, a3


def batched(m_designs, n_positions, repeat):
    """One call of the engine over M four-bars x N positions vs the numpy closed form."""
    rng = np.random.default_rng(11)
    # Grashof crank-rockers around 例 1-1 (l1 shortest, s + l < p + q)
    l1 = rng.uniform(0.08, 0.11, (m_designs, 1))
    l2 = rng.uniform(0.24, 0.27, (m_designs, 1))
    l3 = rng.uniform(0.17, 0.19, (m_designs, 1))
    l4 = rng.uniform(0.29, 0.31, (m_designs, 1))
    th = np.linspace(0, 2 * np.pi, n_positions)
    lk = four_bar(l1, l2, l3, l4)
    inputs = {1: DriverMotion(th, 250.0)}
    t_engine = best_of(lambda: solve(lk, inputs, order=2), repeat)
    t_closed = best_of(lambda: closed_form_fourbar(l1, l2, l3, l4, th, 250.0), repeat)
    m = solve(lk, inputs, order=2)
    ref = closed_form_fourbar(l1, l2, l3, l4, th, 250.0)
    ok = m.regular.all(axis=-1)  # designs that assemble at every position
    err = max(np.max(np.abs(m.links[3].omega - ref[3])[ok]) / np.max(np.abs(ref[3][ok])),
              np.max(np.abs(m.links[3].alpha - ref[5])[ok]) / np.max(np.abs(ref[5][ok])))
    k = 200  # separate solves, extrapolated to M
    t_loop = best_of(lambda: [solve(four_bar(float(l1[i, 0]), float(l2[i, 0]), float(l3[i, 0]),
                                             float(l4[i, 0])), inputs, order=2)
                              for i in range(k)], 1) * m_designs / k
    tag = f"{m_designs}x{n_positions}"
    print(f"batched_fourbar_{tag}_engine: {t_engine * 1e3:.0f} ms")
    print(f"batched_fourbar_{tag}_numpy_closed_form: {t_closed * 1e3:.0f} ms")
    print(f"batched_fourbar_{tag}_engine_over_closed_form: {t_engine / t_closed:.2f} x")
    print(f"batched_fourbar_{tag}_separate_solves_estimate: {t_loop * 1e3:.0f} ms")
    print(f"batched_fourbar_{tag}_max_rel_difference_to_closed_form: {err:.1e} 1")
    print(f"batched_fourbar_{tag}_feasible_designs: {int(m.feasible.all(axis=-1).sum())} of "
          f"{m_designs}")


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


def refinement(repeat):
    """Issue 17: the extreme refinement of one sweep (``refine_extremes`` inside
    ``analyse_sweep``, 例 1-1 as ``mechcli kin`` runs it, 7 quantities, warm) <= 3 ms, with
    the engine solves it makes (the bisection it replaced took 13 ms and ~40 solves)."""
    from mechcli.core.linkage import extremes, kinematics
    from mechcli.spec.kin import load_kin_spec

    spec = load_kin_spec(ROOT / "configs" / "ch1" / "ex1-1.toml")
    qs = default_quantities(spec.linkage, spec.output.order, [t.name for t in spec.tracers])
    spent, solves = [], []
    inner, count = kinematics.refine_extremes, kinematics.solve
    # the solves of the whole analysis: its own and those of the refinement's module

    def timed(*a, **k):
        t = time.perf_counter()
        out = inner(*a, **k)
        spent.append(time.perf_counter() - t)
        return out

    def counted(*a, **k):
        solves[-1] += 1
        return count(*a, **k)

    kinematics.refine_extremes, kinematics.solve, extremes.solve = timed, counted, counted
    try:
        t_all = float("inf")
        for _ in range(repeat):
            solves.append(0)
            t = time.perf_counter()
            analyse_sweep(spec.linkage, spec.input.sweep(), qs, spec.output.order,
                          partial=spec.input.partial)
            t_all = min(t_all, time.perf_counter() - t)
    finally:
        kinematics.refine_extremes, kinematics.solve, extremes.solve = inner, count, count
    print(f"refine_extremes_ex1-1: {min(spent) * 1e3:.2f} ms (goal <= 3)")
    print(f"analyse_sweep_ex1-1_solves: {solves[-1]} 1")
    print(f"analyse_sweep_ex1-1: {t_all * 1e3:.2f} ms")


def plain_process(repeat):
    """Issue 17: the engine in a fresh process with no allocator setting, against
    the numpy closed form timed in the same (child) process."""
    code = (
        "import sys, time; sys.path.insert(0, %r); sys.path.insert(0, %r)\n"
        "import numpy as np\n"
        "from bench_kin import fourbar, closed_form_fourbar, best_of\n"
        "from mechcli.core.linkage import DriverMotion, solve\n"
        "lk = fourbar(); th = np.linspace(0, 2 * np.pi, 36001); inp = {1: DriverMotion(th, 250.0)}\n"
        "te = best_of(lambda: solve(lk, inp, order=2), %d)\n"
        "tc = best_of(lambda: closed_form_fourbar(0.1016, 0.254, 0.1778, 0.3048, th, 250.0), %d)\n"
        "print(te, tc)\n") % (str(ROOT), str(Path(__file__).resolve().parent), repeat, repeat)
    te, tc = map(float, subprocess.run([sys.executable, "-c", code], capture_output=True,
                                       text=True, check=True).stdout.split())
    print(f"plain_process_engine_fourbar_36001_pva: {te * 1e3:.2f} ms")
    print(f"plain_process_numpy_closed_form_36001_pva: {tc * 1e3:.2f} ms")
    print(f"plain_process_engine_over_closed_form: {te / tc:.2f} x")


def _peak_rss_run(args):
    """``(seconds, peak RSS [B])`` of ``mechcli ARGS`` in a fresh process."""
    code = ("import resource, sys\n"
            "from mechcli.cli import main\n"
            "try:\n    main(sys.argv[1:])\nexcept SystemExit:\n    pass\n"
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)\n")
    t = time.perf_counter()
    res = subprocess.run([sys.executable, "-c", code, *args], cwd=ROOT, capture_output=True,
                         text=True, check=True)
    return time.perf_counter() - t, int(res.stderr.strip().splitlines()[-1]) * 1024


def streamed(quick):
    """Issue 17: a sweep past the in-memory limit streams its rows to the CSV in bounded
    memory: peak RSS of `mechcli kin ex1-1` at 1e7 rows (1e6 with --quick) against the
    in-memory run at 600,001 rows (kin's limit), both measured here."""
    cfg = str(ROOT / "configs" / "ch1" / "ex1-1.toml")
    rows, step = (1_000_001, "0.00036") if quick else (10_000_001, "0.000036")
    with tempfile.TemporaryDirectory() as out:
        t_mem, rss_mem = _peak_rss_run(["kin", cfg, "--set", "input.step=0.0006", "--out", out,
                                        "--no-plot", "--quiet"])
        t_str, rss_str = _peak_rss_run(["kin", cfg, "--set", f"input.step={step}", "--out",
                                        out, "--no-plot", "--quiet"])
    tag = f"kin_streamed_{rows}"
    print(f"kin_in_memory_600001_peak_rss: {rss_mem / 2**20:.0f} MB")
    print(f"kin_in_memory_600001_peak_rss_per_position: {rss_mem / 600_001:.0f} B")
    print(f"{tag}_peak_rss: {rss_str / 2**20:.0f} MB")
    print(f"{tag}_peak_rss_per_position: {rss_str / rows:.1f} B")
    print(f"{tag}_peak_rss_over_in_memory_600001: {rss_str / rss_mem:.2f} x")
    print(f"{tag}_time: {t_str:.1f} s ({t_str / rows * 1e6:.2f} us per row, CSV included)")


def class3(repeat):
    """Issue 30: the class-III six-bar of configs/ch1/class3-sixbar.toml (a triad solved
    by batched Newton) at 36,001 positions with velocities and accelerations, against
    the four-bar preset in the same run (goal <= 10x)."""
    import math

    from mechcli.core.linkage.drawing import Drawing, from_drawing

    xy = {"A": (0.0, 0.0), "B": (-19.35, -1.44), "C": (81.65, 53.48), "E": (117.78, 50.71),
          "F": (102.9, 93.53), "G": (188.83, 22.69), "H": (80.08, 150.21)}
    xy = {k: (x / 1000, y / 1000) for k, (x, y) in xy.items()}
    links = {1: ("A", "B"), 2: ("B", "C"), 3: ("C", "E", "F"), 4: ("G", "E"), 5: ("H", "F")}
    t = time.perf_counter()
    lk = from_drawing(Drawing(6, xy, links, (), ((1, "A"),))).linkage
    build = time.perf_counter() - t
    th = np.linspace(0, 2 * math.pi, 36001)
    tri = best_of(lambda: solve(lk, {1: DriverMotion(th, 10.0)}, order=2), repeat)
    fb = engine(36001, repeat)
    print(f"engine_class3_sixbar_36001_pva: {tri * 1e3:.2f} ms")
    print(f"engine_class3_over_fourbar_36001_pva: {tri / fb:.1f} x")
    print(f"joints_class3_sixbar_from_drawing: {build * 1e3:.1f} ms")


def class4(repeat):
    """The class-IV six-bar of configs/ch1/class4-group.toml (a NewtonGroup: 12 pose
    unknowns, a 12 x 12 solve per position and Newton step) at 36,001 positions with
    velocities and accelerations, against the four-bar preset in the same run (no goal:
    the figure says what the general group costs beside the triad's closed Cramer form)."""
    import math

    from mechcli.core.linkage.drawing import Drawing, from_drawing

    xy = {"A": (0, 0), "B": (10, 0), "C": (88, 73), "D": (117, 57), "E": (106, 49),
          "F": (76, 5), "G": (150, 0)}
    xy = {k: (x / 1000, y / 1000) for k, (x, y) in xy.items()}
    links = {1: ("A", "B"), 2: ("B", "C", "F"), 3: ("C", "D"), 4: ("G", "D", "E"),
             5: ("E", "F")}
    t = time.perf_counter()
    lk = from_drawing(Drawing(6, xy, links, (), ((1, "A"),))).linkage
    build = time.perf_counter() - t
    th = np.linspace(0, 2 * math.pi, 36001)
    grp = best_of(lambda: solve(lk, {1: DriverMotion(th, 10.0)}, order=2), repeat)
    fb = engine(36001, repeat)
    print(f"engine_class4_sixbar_36001_pva: {grp * 1e3:.2f} ms")
    print(f"engine_class4_over_fourbar_36001_pva: {grp / fb:.1f} x")
    print(f"joints_class4_sixbar_from_drawing: {build * 1e3:.1f} ms")


def main():
    quick = "--quick" in sys.argv
    class3(5 if quick else 15)
    class4(2 if quick else 5)
    r = 3 if quick else 7
    streamed(quick)
    plain_process(10 if quick else 20)
    n = 1000001
    print(f"engine_fourbar_1000001_peak_memory_per_position: {peak_memory(n) / n:.0f} B")
    print(f"allocator_keeps_heap_warm: {int(keep_heap_warm())} bool")
    print(f"engine_fourbar_36001_pva: {engine(36001, r) * 1e3:.2f} ms")
    print(f"engine_fourbar_1000001_pva: {engine(1000001, 2 if quick else 3) * 1e3:.1f} ms")
    print(f"engine_fourbar_1000001_peak_memory: {peak_memory(1000001) / 2**20:.0f} MB")
    batched(10_000, 361, 2 if quick else 5)
    accuracy_vs_step()
    refinement(20 if quick else 60)
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
    run(main)
