"""The digital Hrones–Nelson atlas (issue 15): build rate, search time, scaling, quality.

Prints ``name: value unit`` lines.  Targets: build >= 50 000 curves of 72 points
per second per core (one engine call per chunk + exact Fourier descriptors),
against a plain numpy closed-form four-bar (curves only, no descriptors) in the
same run; search <= 0.2 s for 1e5 curves and <= 2 s for 1e6 curves; scaling from
1 to 2 worker processes; the path error after refinement against the atlas size.

The 1e5 search runs on the real default build (151 690 curves, built here); the
1e6 search on synthesized chunks (the default build's descriptors repeated with
noise, same file format and manifest), since building 1e6 curves takes minutes.

Run: ``python benchmarks/bench_atlas.py [--quick] [--json]``
"""

from __future__ import annotations

import argparse
import concurrent.futures
import io
import json
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from _figures import run  # noqa: E402

from mechcli import atlas_store as st
from mechcli.core.synth import atlas as at  # noqa: E402


def closed_form(P, theta):
    A, B, C, gx, gy = (P[:, j:j + 1] for j in range(5))
    bx, by = np.cos(theta), np.sin(theta)
    dx, dy = C - bx, -by
    d = np.hypot(dx, dy)
    a = (A * A - B * B + d * d) / (2 * d)
    h = np.sqrt(A * A - a * a)
    cx = bx + (a * dx - h * dy) / d
    cy = by + (a * dy + h * dx) / d
    ux, uy = (cx - bx) / A, (cy - by) / A
    return bx + gx * ux - gy * uy, by + gx * uy + gy * ux


def _best(fn, repeat):
    out = []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        out.append((time.perf_counter() - t0, time.process_time() - c0))
    return min(o[0] for o in out), min(o[1] for o in out)


def _synthesize(directory, base_desc, base_params, total, chunk, rng):
    directory.mkdir(parents=True, exist_ok=True)
    params = {"A_range": [0, 0, 1], "B_range": [0, 0, 1], "C_range": [0, 0, 1],
              "grid": [[0.0], [0.0]], "chunk": chunk, "harmonics": 16, "step": at.STEP,
              "positions": at.POSITIONS, "branch": 1, "synthesized": True}
    entries = []
    for i in range(-(-total // chunk)):
        n = min(chunk, total - i * chunk)
        j = rng.integers(0, base_desc.shape[0], n)
        desc = (base_desc[j] + rng.normal(0, 1e-3, (n, base_desc.shape[1]))).astype(np.float32)
        buf = io.BytesIO()
        np.savez(buf, desc=desc, params=base_params[j])
        data = buf.getvalue()
        st._atomic_write(directory / st.chunk_name(i), data)
        import hashlib
        entries.append({"index": i, "file": st.chunk_name(i), "count": n, "candidates": n,
                        "bytes": len(data), "sha256": hashlib.sha256(data).hexdigest()})
    m = st._manifest(params, entries, total, len(entries))
    st._atomic_write(directory / at.MANIFEST, json.dumps(m).encode())
    return st.open_atlas(directory)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="smaller sizes (a smoke run)")
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    defaults = {"A_range": at.DEFAULT_A_RANGE, "B_range": at.DEFAULT_B_RANGE,
                "C_range": at.DEFAULT_C_RANGE, "grid": at.DEFAULT_GRID}

    # --- build rate: one chunk of 20 000 default rows, engine + descriptors
    P = at.chunk_params(defaults, 0, 20000)
    theta = np.arange(72) * at.STEP
    w_b, c_b = _best(lambda: at.build_chunk(P), 3)
    w_n, c_n = _best(lambda: closed_form(P, theta), 3)
    w_e, c_e = _best(lambda: at._curves(P), 3)
    print(f"build_curves_per_s: {P.shape[0] / w_b:.0f} curves/s (wall, 72 points per curve, "
          f"engine + descriptors)")
    print(f"build_curves_per_cpu_s: {P.shape[0] / c_b:.0f} curves/s (process time: one core)")
    print(f"engine_curves_per_s: {P.shape[0] / w_e:.0f} curves/s (engine call only)")
    print(f"closed_form_curves_per_s: {P.shape[0] / w_n:.0f} curves/s (plain numpy four-bar, "
          f"no descriptors)")
    print(f"build_over_closed_form: {w_n / w_b:.3f} x")
    print(f"engine_over_closed_form: {w_n / w_e:.3f} x")

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # --- the default build (1.5e5 curves) and its search
        t0 = time.perf_counter()
        info = st.build_atlas(tmp / "default")
        dt = time.perf_counter() - t0
        print(f"default_build_curves: {info.curves} curves")
        print(f"default_build_s: {dt:.2f} s ({info.curves / dt:.0f} curves/s, in process)")
        page = at.atlas_page(2.5, 2.0, 3.0, [1.2], [0.7])
        tx, ty = page.x[0], page.y[0]
        w_s, _ = _best(lambda: st.search(info, tx, ty, k=10), 3)
        print(f"search_1e5_s: {w_s:.3f} s ({info.curves} curves, sha256 verified)")
        w_s, _ = _best(lambda: st.search(info, tx, ty, k=10, verify=False), 3)
        print(f"search_1e5_noverify_s: {w_s:.3f} s")

        # --- 1e6 synthesized
        desc, params = [], []
        for c in info.chunks:
            d_, p_ = st._load_chunk(info.directory, c)
            desc.append(d_)
            params.append(p_)
        desc, params = np.concatenate(desc), np.concatenate(params)
        n6 = 200_000 if args.quick else 1_000_000
        big = _synthesize(tmp / "big", desc, params, n6, 100_000, rng)
        w_s, _ = _best(lambda: st.search(big, tx, ty, k=10), 2)
        print(f"search_1e6_s: {w_s:.3f} s ({big.curves} synthesized curves, sha256 verified)")
        w_s, _ = _best(lambda: st.search(big, tx, ty, k=10, verify=False), 2)
        print(f"search_1e6_noverify_s: {w_s:.3f} s")
        with concurrent.futures.ProcessPoolExecutor(2) as ex:
            list(ex.map(abs, [1, 2]))
            w_s2, _ = _best(lambda: st.search(big, tx, ty, k=10, mapper=ex.map), 2)
        print(f"search_1e6_2_workers_s: {w_s2:.3f} s")
        del desc, params

        # --- scaling 1 vs 2 workers (build of 8 chunks of 10 000)
        part = dict(defaults, A_range=(1.25, 2.25, 5))
        t0 = time.perf_counter()
        one = st.build_atlas(tmp / "w1", chunk=10000, **part)
        t1 = time.perf_counter() - t0
        with concurrent.futures.ProcessPoolExecutor(2) as ex:
            list(ex.map(abs, [1, 2]))
            t0 = time.perf_counter()
            two = st.build_atlas(tmp / "w2", chunk=10000, mapper=ex.map, **part)
            t2 = time.perf_counter() - t0
        assert [c["sha256"] for c in one.chunks] == [c["sha256"] for c in two.chunks]
        print(f"build_1_worker_curves_per_s: {one.curves / t1:.0f} curves/s")
        print(f"build_2_workers_curves_per_s: {two.curves / t2:.0f} curves/s")
        print(f"build_2_over_1_workers: {t1 / t2:.2f} x (cpus: {os.cpu_count()})")

        # --- quality: path error after refinement against the atlas size
        targets = []
        trng = np.random.default_rng(7)
        while len(targets) < (3 if args.quick else 6):
            p = trng.uniform([1.6, 1.6, 1.6, -0.5, -1.0], [3.9, 3.9, 3.9, 2.5, 1.8])
            if at.crank_rocker_mask(*p[:3]).all():
                pg = at.atlas_page(*p[:3], [p[3]], [p[4]], step=math.radians(10))
                targets.append((pg.x[0] + 1j * pg.y[0]) * 20 * np.exp(0.3j) + 5)
        for counts, grid_step in ((4, 1.0), (7, 0.5), (14, 0.5)):
            rngs = {k: (1.25, 4.5, counts) for k in ("A_range", "B_range", "C_range")}
            gx = np.arange(-1.5, 3.51, grid_step)
            gy = np.arange(-2.0, 2.51, grid_step)
            a = (info if counts == 14 else
                 st.build_atlas(tmp / f"q{counts}", grid=(gx, gy), **rngs))
            errs, errs_slsqp, t_ref = [], [], 0.0
            for z in targets:
                hit = st.search(a, z.real, z.imag, k=3)
                t0 = time.perf_counter()
                rs = [at.refine(h, z.real, z.imag) for h in hit]
                t_ref += time.perf_counter() - t0
                best = min(rs, key=lambda r: r.error_rms)
                errs.append(best.error_max / best.size)
                r0 = at.refine(hit[0], z.real, z.imag, polish=False)
                errs_slsqp.append(r0.error_max / r0.size)
            print(f"quality_{a.curves}_curves_median_rel_error: {np.median(errs):.2e} 1 "
                  f"(top 3 refined, best; worst {np.max(errs):.1e})")
            print(f"quality_{a.curves}_curves_slsqp_top1_median_rel_error: "
                  f"{np.median(errs_slsqp):.2e} 1 (SLSQP only, top 1)")
            print(f"quality_{a.curves}_curves_refine_s: {t_ref / len(targets):.2f} s per target")


if __name__ == "__main__":
    run(main)
