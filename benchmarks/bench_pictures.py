"""Pictures: the PNG run of ``kin`` and the GIF frames, against their baselines.

Prints ``name: value unit`` lines (``--json``: the same figures as JSON,
``benchmarks/_figures.py``):

* ``import_numpy_process`` -- the baseline, ``python -c "import numpy"`` [ms];
* ``kin_ex1-1_png_process`` [ms] and ``kin_ex1-1_png_over_import_numpy`` [x]:
  ``mechcli kin configs/ch1/ex1-1.toml`` (kin.png), a fresh process each time
  (bytecode cached, ``benchmarks/_process.py``), round-robin with the baseline so
  both see the same load, minimum of the runs
  (goal <= 5x); ``kin_ex1-1_png_dpi100_*`` the same at ``--dpi 100`` (the
  default is 200 dpi);
* ``kin_ex1-1_no_plot_process`` [ms]: the same run without pictures, so that
  ``kin_ex1-1_png_cost`` [ms] is what the pictures add;
* ``import_matplotlib_process`` [ms] and ``_over_import_numpy`` [x]: ``python -c "import
  numpy, matplotlib.figure, matplotlib.backends.backend_agg"``, the floor of any run that
  writes a PNG (what ``report.plotting`` imports; no pyplot); ``kin_ex1-1_png_drawing``
  [ms] and ``_over_import_numpy`` [x]: the PNG's cost beyond that import (the figure,
  its drawing, the encoding);
* ``kin_ex1-1_png_over_import_matplotlib`` [x]: the PNG run against that import, both
  measured side by side in this run (issue 33 §4: goal <= 1.4x);
* ``bare_matplotlib_figure_process`` [ms], ``bare_matplotlib_drawing`` [ms]: the figure
  of kin.png drawn the ordinary way with matplotlib (``_BARE``: the same panels, curves
  and mathtext labels, ``savefig``), the process and what it adds to the import: the
  floor of drawing this figure with matplotlib; ``kin_ex1-1_png_drawing_over_bare_matplotlib``
  [x] is mechcli's drawing against it (below 1: cheaper than matplotlib's ordinary way),
  and ``bare_matplotlib_figure_over_import_matplotlib`` [x] the ratio issue 33 §4 asks of
  mechcli's run (<= 1.4x), for matplotlib's own figure;
* ``check_no_plot_s_per_spec_per_core`` [s]: ``mechcli check configs/ -j J`` without
  pictures, the floor of the next figure;
* ``check_plot_s_per_spec_per_core`` [s]: ``mechcli check configs/ --plot -j J`` (every
  config with its pictures, J = the CPU count, at most 2) as wall time x J / specs
  (goal <= 0.25 s; ``--no-check`` leaves it out);
* ``import_numpy_cpu``, ``<case>_cpu`` [ms], ``<case>_cpu_over_import_numpy`` [x]:
  the same with the CPU time of the processes' main thread, which a shared, loaded
  machine disturbs less than the wall time (``benchmarks/_process.py``);
* ``gif_<config>_frames`` [1], ``gif_<config>_ms_per_frame`` [ms/frame]: the
  whole animation of ``mechcli kin CONFIG --animate`` (figure set-up, every
  frame, GIF encoding) divided by its frames, in a fresh process (matplotlib
  imported before the clock starts), minimum of the runs (goal <= 8 ms/frame);
  ``gif_<config>_frame_over_import_numpy`` [x] relates it to the baseline.

Usage: python benchmarks/bench_pictures.py [--runs N] [--no-bytecode-cache] [--no-check] [--json]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402
from _process import bench_env, round_robin  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
EX11 = str(ROOT / "configs" / "ch1" / "ex1-1.toml")
GIF_CONFIGS = {"exercise1-2": ROOT / "configs" / "ch1" / "exercise1-2.toml",
               "ex1-3": ROOT / "configs" / "ch1" / "ex1-3.toml"}

#: run in a fresh process: time kin's animation alone (import and solve excluded)
_GIF_PROBE = r"""
import sys, time, tempfile
import numpy as np
import matplotlib
from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
from mechcli.report import kin_plots
from mechcli.report.files import Outputs
from mechcli.spec.kin import load_kin_spec

spec = load_kin_spec(sys.argv[1], ())
sweep = spec.input.sweep()
qs = default_quantities(spec.linkage, spec.output.order, [t.name for t in spec.tracers])
result = analyse_sweep(spec.linkage, sweep, qs, spec.output.order, partial=spec.input.partial)
with tempfile.TemporaryDirectory() as out:
    outputs = Outputs(out)
    kin_plots.write(spec, qs, result, sweep, outputs, "en", plots=False, animate=True)  # warm
    best = float("inf")
    for _ in range(int(sys.argv[2])):
        t0 = time.perf_counter()
        kin_plots.write(spec, qs, result, sweep, outputs, "en", plots=False, animate=True)
        best = min(best, time.perf_counter() - t0)
    # files are staged beside --out until a commit (report/files.py): read the staged
    # kin.gif, then drop the staging folder
    from PIL import Image
    with Image.open(outputs.path("kin.gif")) as im:
        n = im.n_frames
    outputs.discard()
print(best, n)
"""


#: the figure of kin.png drawn the ordinary way, in a fresh process: a 2x2 Figure (11 x 8.5
#: in), three panels of two curves on twin axes with the same mathtext labels, titles and
#: a legend, a fourth with a mechanism's five bars, ``savefig`` at 200 dpi with
#: ``bbox_inches="tight"``; matplotlib's own cost for this picture, the floor of any
#: library drawing it with matplotlib
_BARE = r"""
import numpy as np
from matplotlib.figure import Figure
from matplotlib.backends.backend_agg import FigureCanvasAgg
x = np.linspace(0.0, 360.0, 361)
t = np.radians(x)
fig = Figure(figsize=(11, 8.5))
FigureCanvasAgg(fig)
axs = fig.subplots(2, 2)
names = ((r"$\theta_{2}$", r"$\theta_{3}$"), (r"$\omega_{2}$", r"$\omega_{3}$"),
         (r"$\alpha_{2}$", r"$\alpha_{3}$"))
for k, (ax, (a, b)) in enumerate(zip(axs.flat[:3], names)):
    h1, = ax.plot(x, 30 * np.sin(t + k), "-", label=a)
    tw = ax.twinx()
    h2, = tw.plot(x, 10 ** (k + 1) * np.cos(2 * t), "--", color="C1", label=b)
    ax.set_xlabel(r"crank angle $\theta_{1}$ / °")
    ax.set_ylabel(a + " / (rad)")
    tw.set_ylabel(b + " / (rad)")
    ax.set_title("Displacement")
    ax.legend([h1, h2], [a, b], loc="upper right", fontsize=7)
ax = axs[1, 1]
ax.plot([0, 0.1, 0.3, 0.35, 0], [0, 0.1, 0.15, 0, 0], "o-", lw=2)
ax.plot(0.1 * np.cos(t), 0.1 * np.sin(t), ":")
ax.set_aspect("equal")
ax.set_title(r"Mechanism at $\theta_{1}$ = 0°")
ax.set_xlabel("x / mm")
ax.set_ylabel("y / mm")
fig.suptitle("ex1-1 four-bar linkage")
fig.savefig(__import__("sys").argv[1], dpi=200, bbox_inches="tight")
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5, help="runs of each case (minimum taken)")
    ap.add_argument("--no-bytecode-cache", action="store_true",
                    help="keep the environment's PYTHONDONTWRITEBYTECODE (if set)")
    ap.add_argument("--no-check", action="store_true",
                    help="leave out `mechcli check configs/ --plot` (~1 min)")
    args = ap.parse_args()
    mech = [sys.executable, "-m", "mechcli"]
    with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as cache:
        env = bench_env(cache, not args.no_bytecode_cache)
        cmds = {"import_numpy": [sys.executable, "-c", "import numpy"],
                # the floor of any PNG: what mechcli imports to draw one (report.plotting)
                "import_matplotlib": [sys.executable, "-c", "import numpy, matplotlib.figure, "
                                      "matplotlib.backends.backend_agg"],
                "bare_matplotlib_figure": [sys.executable, "-c", _BARE,
                                           os.path.join(out, "bare.png")],
                "kin_ex1-1_no_plot": mech + ["kin", EX11, "--no-plot", "-q", "--out", out],
                "kin_ex1-1_png": mech + ["kin", EX11, "-q", "--out", out],
                "kin_ex1-1_png_dpi100": mech + ["kin", EX11, "-q", "--dpi", "100", "--out", out]}
        best, cpu = round_robin(cmds, args.runs, out, env)   # (as bench_startup.py)
    base = best["import_numpy"]
    print(f"import_numpy_process: {base * 1e3:.1f} ms")
    print(f"import_numpy_cpu: {cpu['import_numpy'] * 1e3:.1f} ms")
    for name in ("import_matplotlib", "bare_matplotlib_figure", "kin_ex1-1_no_plot",
                 "kin_ex1-1_png", "kin_ex1-1_png_dpi100"):
        print(f"{name}_process: {best[name] * 1e3:.1f} ms")
        print(f"{name}_over_import_numpy: {best[name] / base:.2f} x")
        print(f"{name}_cpu: {cpu[name] * 1e3:.1f} ms")
        print(f"{name}_cpu_over_import_numpy: {cpu[name] / cpu['import_numpy']:.2f} x")
    print(f"kin_ex1-1_png_cost: {(best['kin_ex1-1_png'] - best['kin_ex1-1_no_plot']) * 1e3:.1f} ms")
    # what the pictures cost beyond importing matplotlib: the figure, its drawing, the PNG
    draw = best["kin_ex1-1_png"] - best["kin_ex1-1_no_plot"] \
        - (best["import_matplotlib"] - best["import_numpy"])
    print(f"kin_ex1-1_png_drawing: {draw * 1e3:.1f} ms")
    print(f"kin_ex1-1_png_drawing_over_import_numpy: {draw / base:.2f} x")
    # matplotlib's own cost of such a figure (the bare script beyond its import), and
    # mechcli's drawing against it: below 1 is less than matplotlib's ordinary way
    bare = best["bare_matplotlib_figure"] - best["import_matplotlib"]
    print(f"bare_matplotlib_drawing: {bare * 1e3:.1f} ms")
    print(f"kin_ex1-1_png_drawing_over_bare_matplotlib: {draw / bare:.2f} x")
    print(f"bare_matplotlib_figure_over_import_matplotlib: "
          f"{best['bare_matplotlib_figure'] / best['import_matplotlib']:.2f} x")
    print(f"bare_matplotlib_figure_cpu_over_import_matplotlib: "
          f"{cpu['bare_matplotlib_figure'] / cpu['import_matplotlib']:.2f} x")
    print(f"kin_ex1-1_png_over_import_matplotlib: "
          f"{best['kin_ex1-1_png'] / best['import_matplotlib']:.2f} x")
    print(f"kin_ex1-1_png_cpu_over_import_matplotlib: "
          f"{cpu['kin_ex1-1_png'] / cpu['import_matplotlib']:.2f} x")
    for name, path in GIF_CONFIGS.items():
        if not path.exists():
            continue
        proc = subprocess.run([sys.executable, "-c", _GIF_PROBE, str(path), str(args.runs)],
                              cwd=ROOT, check=True, capture_output=True, text=True)
        t, n = proc.stdout.split()
        t, n = float(t), int(n)
        print(f"gif_{name}_frames: {n} 1")
        print(f"gif_{name}_ms_per_frame: {t / n * 1e3:.2f} ms/frame")
        print(f"gif_{name}_frame_over_import_numpy: {t / n / base:.3f} x")
    if not args.no_check:
        _check_plot(mech)


def _check_plot(mech):
    """``mechcli check configs/`` with and without ``--plot`` on J processes: wall time x J
    per spec; the run without pictures is the floor of the one with."""
    jobs = max(1, min(2, os.cpu_count() or 1))
    specs = sorted((ROOT / "configs").rglob("*.toml"))
    for name, extra in (("check_no_plot", []), ("check_plot", ["--plot"])):
        with tempfile.TemporaryDirectory() as cwd:   # the pictures go to ./out/check/
            t0 = time.perf_counter()
            cmd = mech + ["check", str(ROOT / "configs"), *extra, "-q", "-j", str(jobs)]
            proc = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True,
                                  env={**os.environ, "PYTHONPATH": str(ROOT)})
            wall = time.perf_counter() - t0
        print(f"{name}_specs: {len(specs)} 1")
        print(f"{name}_exit: {proc.returncode} 1")   # 0: every spec ran and met [expected]
        print(f"{name}_s_per_spec_per_core: {wall * jobs / len(specs):.3f} s")


if __name__ == "__main__":
    run(main)
