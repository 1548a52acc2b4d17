"""Process start-up of the commands users run from Makefiles and CI (issue 17).

Each command is run as a fresh process (stdout a pipe, bytecode cached by a
warm-up run, see ``benchmarks/_process.py``), round-robin with the baseline
``python -c "import numpy"`` so that both see the same load; the figure is the
minimum over the runs.  Prints
``name: value unit`` lines, ``--json`` the same figures as JSON
(``benchmarks/_figures.py``):

* ``import_numpy_process`` -- the baseline [ms];
* ``<case>_process`` [ms] and ``<case>_over_import_numpy`` [x] for ``version``
  (``mechcli --version``), ``grashof_quick`` (``mechcli grashof --lengths
  40,90,70,100``), ``kin_ex1-1_no_plot`` and ``kin_ex1-1_png`` (the PNGs of
  ``configs/ch1/ex1-1.toml``);
* ``import_numpy_cpu``, ``<case>_cpu`` [ms] and ``<case>_cpu_over_import_numpy`` [x]:
  the same with the CPU time of the processes' main thread, which a shared, loaded
  machine disturbs less than the wall time (``benchmarks/_process.py``).

Goals (issue 17): grashof quick form <= 1.0x, kin --no-plot <= 1.5x, kin with
PNGs <= 5x ``import numpy``.

``--no-site-hooks`` runs every process (the baseline's too) with ``python -S`` and the site
directories on ``PYTHONPATH``: the ``.pth`` files of the environment then import nothing
into them.  Some sandboxes import certifi, typing, tempfile, pathlib ... into every process
that way, which mechcli would otherwise pay for itself; on this machine the ratio of
``kin --no-plot`` is ~0.1 higher without them.

Usage: python benchmarks/bench_startup.py [--runs N] [--no-bytecode-cache] [--no-site-hooks]
       [--json]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402
from _process import bench_env, interpreter, round_robin  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
EX11 = str(ROOT / "configs" / "ch1" / "ex1-1.toml")


def cases(out, site_hooks=True):
    py = interpreter(site_hooks)
    mech = py + ["-m", "mechcli"]
    return {
        "import_numpy": py + ["-c", "import numpy"],
        "version": mech + ["--version"],
        "grashof_quick": mech + ["grashof", "--lengths", "40,90,70,100", "--out", out],
        "kin_ex1-1_no_plot": mech + ["kin", EX11, "--no-plot", "--out", out],
        "kin_ex1-1_png": mech + ["kin", EX11, "--out", out],
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=7, help="runs of each command (minimum taken)")
    ap.add_argument("--no-bytecode-cache", action="store_true",
                    help="keep the environment's PYTHONDONTWRITEBYTECODE (if set)")
    ap.add_argument("--no-site-hooks", action="store_true",
                    help="python -S with the site directories on PYTHONPATH: the "
                         "environment's .pth files run in no process (a clean installation)")
    args = ap.parse_args()
    hooks = not args.no_site_hooks
    with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as cache:
        env = bench_env(cache, not args.no_bytecode_cache, site_hooks=hooks)
        # run in the output folder: a checkout in the working directory would shadow an
        # installed mechcli (`-c` and `-m` put the working directory first on sys.path)
        best, cpu = round_robin(cases(out, hooks), args.runs, out, env)
    print(f"site_hooks: {int(hooks)} 1")
    base, cpu_base = best.pop("import_numpy"), cpu.pop("import_numpy")
    print(f"import_numpy_process: {base * 1e3:.1f} ms")
    print(f"import_numpy_cpu: {cpu_base * 1e3:.1f} ms")
    for name, t in best.items():
        print(f"{name}_process: {t * 1e3:.1f} ms")
        print(f"{name}_over_import_numpy: {t / base:.2f} x")
        print(f"{name}_cpu: {cpu[name] * 1e3:.1f} ms")
        print(f"{name}_cpu_over_import_numpy: {cpu[name] / cpu_base:.2f} x")


if __name__ == "__main__":
    run(main)
