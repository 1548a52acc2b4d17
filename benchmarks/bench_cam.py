"""Accuracy against cost of the sampled cam profile (``mechcli cam``).

For the book's three cams (例 4-1 offset roller, 例 4-2 flat face, 例 4-3
oscillating roller) and steps from 5° down to 0.01°, prints ``name: value unit``
lines:

* ``chord``: largest distance between the exact working curve and the polyline
  through the samples (what a CNC program or a drawing made from cam.csv gets
  wrong), measured at 16 points inside every sample interval;
* ``alpha_grid``: error of the largest pressure angle read off the samples, and
  ``alpha_refined``: error of the value mechcli reports (a 1° coarse search
  refined on the exact function, whatever the sampling step) against a 0.01°
  coarse search;
* ``rho_grid`` / ``rho_refined``: the same for the smallest radius of curvature;
* ``time``: profile + all checks, median of repeated runs (compute only: no
  spec reading, no files); then everything ``mechcli cam`` computes at the
  default step, and the wall time of a whole command-line run;
* ``peak_rss``: the peak RSS of whole runs at two steps and its growth per profile
  point, the figure behind ``mechcli.spec.cam.MAX_POINTS`` (the 1 GiB budget).

Run: ``python benchmarks/bench_cam.py [--json]``.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

from mechcli.core.cam.motion import build_program  # noqa: E402
from mechcli.core.cam.checks import check_cam  # noqa: E402
from mechcli.core.cam.geometry import Follower, cam_profile  # noqa: E402

RAD = math.radians
MM = 1e-3
STEPS = (5.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01)

CASES = {
    "ex4-1": (Follower("translating", "roller", 40 * MM, 1, e=15 * MM, rr=10 * MM),
              build_program([("rise", RAD(100), "parabolic", 60 * MM),
                             ("dwell", RAD(60), None, 0),
                             ("return", RAD(90), "cosine", 60 * MM),
                             ("dwell", RAD(110), None, 0)], 60 * MM)),
    "ex4-2": (Follower("translating", "flat", 30 * MM, 1),
              build_program([("rise", RAD(120), "cosine", 20 * MM),
                             ("return", RAD(150), "cosine", 20 * MM),
                             ("dwell", RAD(90), None, 0)], 20 * MM)),
    "ex4-3": (Follower("oscillating", "roller", 25 * MM, 1, rr=8 * MM, a=60 * MM, l=50 * MM),
              build_program([("rise", RAD(180), "cosine", RAD(25)),
                             ("return", RAD(180), "sine", RAD(25))], RAD(25), angular=True)),
}


def chord_deviation(fol, prog, delta):
    """Largest distance of the exact working curve from the sample polyline, m."""
    work = cam_profile(fol, prog, delta).work
    a, b = work[:, :-1], work[:, 1:]
    ab = b - a
    L2 = np.maximum(np.sum(ab * ab, axis=0), 1e-300)
    worst = 0.0
    for t in np.linspace(0, 1, 18)[1:-1]:
        q = cam_profile(fol, prog, delta[:-1] + t * np.diff(delta)).work
        u = np.clip(np.sum((q - a) * ab, axis=0) / L2, 0, 1)
        d = np.hypot(*(q - a - u * ab))
        worst = max(worst, float(np.max(d)))
    return worst


def timed(fol, prog, delta, step, repeat=7):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        cam_profile(fol, prog, delta)
        check_cam(fol, prog, RAD(1.0))
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def main():
    for name, (fol, prog) in CASES.items():
        exact = check_cam(fol, prog, RAD(0.01))
        a_ref = max(e.value for e in (exact.alpha_rise, exact.alpha_return) if e is not None)
        r_ref = exact.rho_work_min.value
        for step in STEPS:
            n = int(round(360 / step))
            delta = np.linspace(0, 2 * np.pi, n + 1)
            p = cam_profile(fol, prog, delta)
            ch = check_cam(fol, prog, RAD(1.0))
            a_rep = max(e.value for e in (ch.alpha_rise, ch.alpha_return) if e is not None)
            rho = p.rho_work
            tag = f"{name}_step{step:g}deg"   # {n} points
            print(f"{tag}_chord: {chord_deviation(fol, prog, delta) / MM:.3e} mm")
            print(f"{tag}_alpha_grid: {math.degrees(a_ref - np.max(np.abs(p.alpha))):.3e} deg")
            print(f"{tag}_alpha_refined: {math.degrees(abs(a_rep - a_ref)):.3e} deg")
            print(f"{tag}_rho_grid: {(np.min(rho[rho > 0]) - r_ref) / MM:.3e} mm")
            print(f"{tag}_rho_refined: {abs(ch.rho_work_min.value - r_ref) / MM:.3e} mm")
            print(f"{tag}_time: {timed(fol, prog, delta, RAD(step)) * 1e3:.2f} ms")


def bench_design():
    """Everything ``mechcli cam`` computes for 例 4-1 at the default step, with sizing."""
    from mechcli.core.cam.design import design_cam
    from mechcli.spec.cam import DEFAULT_STEP_DEG

    segs = [(s.kind, s.span, s.law, abs(s.lift)) for s in CASES["ex4-1"][1].segments]
    times = []
    for _ in range(7):
        t0 = time.perf_counter()
        design_cam("translating", "roller", 40 * MM, {"rr": 10 * MM, "e": 15 * MM,
                                                      "rotation": 1},
                   segs, 60 * MM, step=RAD(DEFAULT_STEP_DEG), size_base_radius=True,
                   limit_return=True)
        times.append(time.perf_counter() - t0)
    n = int(round(360 / DEFAULT_STEP_DEG))
    print(f"ex4-1_design_cam_default_step_with_sizing_time: {np.median(times) * 1e3:.2f} ms "
          f"(step {DEFAULT_STEP_DEG:g} deg, {n} points)")


def bench_cli():
    """Wall time of a whole ``mechcli cam`` run (start-up, spec, compute, CSV, report)."""
    import subprocess
    import tempfile

    root = Path(__file__).resolve().parent.parent
    spec = root / "configs" / "ch4" / "ex4-1.toml"
    times, base = [], []
    with tempfile.TemporaryDirectory() as out:
        for _ in range(5):   # round-robin with the baseline: both see the same load
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-c", "import numpy"], check=True, cwd=root)
            base.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "mechcli", "cam", str(spec), "--json",
                            "--no-plot", "--out", out], check=True, capture_output=True,
                           cwd=root)
            times.append(time.perf_counter() - t0)
    print(f"process_import_numpy: {min(base) * 1e3:.0f} ms")
    print(f"ex4-1_cli_no_plot_wall_time: {np.median(times) * 1e3:.0f} ms")
    print(f"ex4-1_cli_no_plot_over_import_numpy: {min(times) / min(base):.2f} x")


def bench_peak_rss():
    """Peak RSS of ``mechcli cam`` (例 4-1, no plots) at 36,000 and 360,000 profile points
    and its growth per point: ``mechcli.spec.cam.MAX_POINTS`` is the 1 GiB budget over
    this growth (plots and animation add a few percent), rounded down."""
    import tempfile

    from benchmarks.bench_kin import _peak_rss_run

    root = Path(__file__).resolve().parent.parent
    spec = str(root / "configs" / "ch4" / "ex4-1.toml")
    rss = {}
    with tempfile.TemporaryDirectory() as out:
        for step, n in (("0.01", 36_000), ("0.001", 360_000)):
            rss[n] = _peak_rss_run(["cam", spec, "--set", f"sampling.step={step}", "--out", out,
                                    "--no-plot", "--quiet"])[1]
            print(f"ex4-1_cam_{n}_points_peak_rss: {rss[n] / 2**20:.0f} MB")
    print(f"cam_peak_rss_per_point: {(rss[360_000] - rss[36_000]) / 324_000:.0f} B")


if __name__ == "__main__":
    def _all():
        main()
        bench_design()
        bench_cli()
        bench_peak_rss()

    run(_all)
