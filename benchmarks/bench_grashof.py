"""Speed of ``mechcli grashof``: start-up of the quick form and vectorized batch throughput.

Prints ``name: value unit`` lines.  Targets (issue 3): the quick form's process
time within 1.5x ``python -c "import numpy"``; 100 000 length sets classified
(type, cranks, θ, ψ, K, γ) in under 1 s of compute.

Run: ``python benchmarks/bench_grashof.py [--runs N] [--json]``
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)


def _process_time(argv, runs):
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(argv, cwd=ROOT, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--sets", type=int, default=100_000)
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        base = _process_time([sys.executable, "-c", "import numpy"], args.runs)
        quick = _process_time([sys.executable, "-m", "mechcli", "grashof", "--lengths",
                               "100,150,170,110", "-q", "--out", tmp], args.runs)
        table = _process_time([sys.executable, "-m", "mechcli", "grashof", "--lengths",
                               "100,150,170,110", "--out", tmp], args.runs)
    print(f"import_numpy_process: {base * 1e3:.1f} ms")
    print(f"quick_form_quiet_process: {quick * 1e3:.1f} ms")
    print(f"quick_form_table_process: {table * 1e3:.1f} ms")
    print(f"quick_form_quiet_ratio: {quick / base:.2f} x")
    print(f"quick_form_table_ratio: {table / base:.2f} x")

    import numpy as np

    from mechcli.core.grashof.fourbar import analyse_fourbar, closes
    from mechcli.report.grashof import fourbar_csv

    rng = np.random.default_rng(0)
    L = rng.uniform(1.0, 100.0, (args.sets, 4))
    frame = rng.integers(1, 5, args.sets)
    inp = np.where(rng.random(args.sets) < 0.5, frame % 4 + 1, (frame + 2) % 4 + 1)
    best = float("inf")
    for _ in range(5):
        t0 = time.perf_counter()
        ok = closes(L)
        an = analyse_fourbar(L, frame, inp, require_closure=False)
        best = min(best, time.perf_counter() - t0)
    print(f"batch_sets: {args.sets} sets")
    print(f"batch_classify_and_merit: {best * 1e3:.1f} ms")
    print(f"batch_throughput: {args.sets / best / 1e6:.2f} Msets/s")
    t0 = time.perf_counter()
    text = fourbar_csv(an, 1.0, ok)
    print(f"batch_csv_format: {(time.perf_counter() - t0) * 1e3:.1f} ms")
    print(f"batch_csv_size: {len(text) / 1e6:.1f} MB")


if __name__ == "__main__":
    run(main)
