"""The atlas kinds of `mechcli synth` from the command line: the seed's page and type
chart, a small build (resumed, in parallel, corrupted), path synthesis of a planted
linkage whose linkage-1.toml `kin` moves through the targets, and bad input."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import one_line_error, run_inprocess, run_json

ROOT = Path(__file__).resolve().parents[2]
ATLAS = ROOT / "configs" / "atlas"


def _coupler_point(A, B, C, gx, gy, theta):
    """Independent closed form: crank pivot (0,0), crank 1, follower pivot (C, 0), the
    coupler joint on the open branch, the point (gx, gy) on the coupler plane."""
    bx, by = np.cos(theta), np.sin(theta)
    dx, dy = C - bx, -by
    d = np.hypot(dx, dy)
    a = (A * A - B * B + d * d) / (2 * d)
    h = np.sqrt(A * A - a * a)
    cx, cy = bx + (a * dx - h * dy) / d, by + (a * dy + h * dx) / d
    ux, uy = (cx - bx) / A, (cy - by) / A
    return bx + gx * ux - gy * uy, by + gx * uy + gy * ux


def test_the_seed_page_has_every_curve_and_the_curves_are_right(tmp_path):
    doc = run_json("synth", ATLAS / "page-seed-example.toml", "--out", tmp_path)
    r = doc["results"]
    assert r["curves"] == 54 and r["type"] == "crank-rocker" and r["positions"] == 72
    rows = (tmp_path / "page.csv").read_text().splitlines()
    head = rows[0].split(",")
    data = np.array([[float(v) for v in row.split(",")] for row in rows[1:]])
    col = {h: data[:, i] for i, h in enumerate(head)}
    assert data.shape[0] == 54 * 72
    x, y = _coupler_point(2.5, 2.0, 3.0, col["gx"], col["gy"], np.radians(col["theta_deg"]))
    # the CSV keeps 10 significant digits
    assert np.max(np.hypot(col["x"] - x, col["y"] - y)) < 1e-8


def test_type_chart_gives_the_seeds_ranges(tmp_path):
    r = run_json("synth", ATLAS / "type-chart-seed-example.toml", "--out", tmp_path)["results"]
    # the seed: C from 1.5 to 3.5, B from 1.5 to 4.5, A from 2 to 4
    assert (r["C_min"], r["C_max"], r["B_min"], r["B_max"], r["A_min"], r["A_max"]) == \
        pytest.approx((1.5, 3.5, 1.5, 4.5, 2.0, 4.0), abs=1e-12)
    # the crank-rocker share of the (B, C) square [0, 6]^2 for A = 2.5: the band
    # |A - B| + 1 < C < A + B - 1 with B, C >= 1 ... (grashof with 1 the shortest) plus
    # B < 1 crank-rockers; computed on the same 301 x 301 grid by hand
    b = np.linspace(0, 6, 301)
    B, C = np.meshgrid(b, b)
    L = np.sort(np.stack([np.ones_like(B), np.full_like(B, 2.5), B, C]), axis=0)
    grashof = L[0] + L[3] < L[1] + L[2] - 1e-12
    # crank-rocker: Grashof with the shortest link beside the frame (link 1 or B)
    shortest_is_1 = (L[0] == 1) & (B > 1) & (C > 1)
    shortest_is_B = (B < 1) & (B > 0)
    share = np.mean(grashof & (shortest_is_1 | shortest_is_B))
    assert r["fractions"]["crank_rocker"] == pytest.approx(share, abs=2e-3)


@pytest.fixture(scope="module")
def small_atlas(tmp_path_factory):
    out = tmp_path_factory.mktemp("atlas")
    doc = run_json("synth", ATLAS / "small-build.toml", "--out", out)
    return out, doc["results"]


def test_small_build_counts_and_resumes(small_atlas, tmp_path):
    out, r = small_atlas
    assert r["curves"] == 3330 and r["complete"] is True and r["chunks"] == 2
    manifest = json.loads((out / "atlas" / "manifest.json").read_text())
    again = run_json("synth", ATLAS / "small-build.toml", "--out", out)["results"]
    assert again["curves"] == 3330
    assert json.loads((out / "atlas" / "manifest.json").read_text())["chunks"] == \
        manifest["chunks"]
    # two worker processes write the same chunks (same checksums)
    two = run_json("synth", ATLAS / "small-build.toml", "--out", tmp_path, "--workers", "2")
    assert two["results"]["curves"] == 3330
    assert [c["sha256"] for c in json.loads(
        (tmp_path / "atlas" / "manifest.json").read_text())["chunks"]] == \
        [c["sha256"] for c in manifest["chunks"]]


def _path_spec(tmp_path, atlas_dir, x, y, extra=""):
    p = tmp_path / "path.toml"
    p.write_text(f'''command = "synth"
title = "a planted path"
units = "mm"

[synthesis]
kind = "path"
atlas = "{atlas_dir}"
x = {list(map(float, x))}
y = {list(map(float, y))}
k = 3
{extra}
''', encoding="utf-8")
    return p


def test_a_planted_linkage_is_found_and_its_kin_spec_passes_the_targets(small_atlas, tmp_path):
    out, _ = small_atlas
    # a linkage of the small build's grid (A = 3, B = 2.5, C = 3.5, point (0.5, 0.5)),
    # its curve rotated by 40 deg, scaled by 7 and moved: 12 points
    th = np.radians(np.arange(0, 360, 30) + 7.0)
    px, py = _coupler_point(3.0, 2.5, 3.5, 0.5, 0.5, th)
    z = 7.0 * np.exp(1j * np.radians(40)) * (px + 1j * py) + (20 + 5j)
    spec = _path_spec(tmp_path, out / "atlas", z.real, z.imag)
    doc = run_json("synth", spec, "--out", tmp_path / "o")
    best = doc["results"]["best"]
    assert best["error_max"] < 1e-6 * 7
    assert best["crank"] == pytest.approx(7.0, rel=1e-6)
    assert (best["A"], best["B"], best["C"]) == pytest.approx((3.0, 2.5, 3.5), rel=1e-6)
    kin = tmp_path / "o" / "linkage-1.toml"
    run_json("kin", kin, "--out", tmp_path / "k", "--set", "input.step=0.1")
    rows = (tmp_path / "k" / "kin.csv").read_text().splitlines()
    head = rows[0].split(",")
    ix, iy = head.index("xP_mm"), head.index("yP_mm")
    pts = np.array([[float(r.split(",")[ix]), float(r.split(",")[iy])] for r in rows[1:]])
    d = np.min(np.hypot(pts[:, None, 0] - z.real, pts[:, None, 1] - z.imag), axis=0)
    # kin's path at 0.1 deg passes every target within the sampling distance
    assert np.max(d) < 7 * 2 * math.pi / 3600


def test_fewer_than_three_points_is_a_spec_error(small_atlas, tmp_path):
    out, _ = small_atlas
    proc = run_inprocess("synth", _path_spec(tmp_path, out / "atlas", [1, 2], [3, 4]),
                         "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 2
    assert "3 to 500 target points" in one_line_error(proc)


def test_a_corrupt_or_foreign_atlas_is_one_line(small_atlas, tmp_path):
    import shutil
    out, _ = small_atlas
    bad = tmp_path / "bad"
    shutil.copytree(out / "atlas", bad)
    chunk = sorted(bad.glob("chunk-*.npz"))[0]
    data = bytearray(chunk.read_bytes())
    data[len(data) // 2] ^= 0xFF
    chunk.write_bytes(bytes(data))
    proc = run_inprocess("synth", _path_spec(tmp_path, bad, [0, 1, 2, 1], [0, 1, 0, -1]),
                         "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 3
    assert "atlas" in one_line_error(proc) and "checksum" in proc.stderr
    empty = tmp_path / "empty"
    empty.mkdir()
    proc = run_inprocess("synth", _path_spec(tmp_path, empty, [0, 1, 2, 1], [0, 1, 0, -1]),
                         "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 3 and "manifest" in one_line_error(proc)


def test_ranges_without_a_crank_rocker(tmp_path):
    spec = tmp_path / "b.toml"
    spec.write_text('command = "synth"\n[synthesis]\nkind = "atlas_build"\n'
                    'A = [5, 6, 2]\nB = [1.1, 1.2, 2]\nC = [1.1, 1.2, 2]\n', encoding="utf-8")
    proc = run_inprocess("synth", spec, "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 3 and "no crank-rocker" in one_line_error(proc)


def test_scheduler_without_dask_or_unreachable(tmp_path):
    proc = run_inprocess("synth", ATLAS / "small-build.toml", "--out", tmp_path,
                         "--scheduler", "tcp://127.0.0.1:9", "--no-plot")
    assert proc.returncode in (2, 3)
    line = one_line_error(proc)
    assert "dask" in line.lower() or "scheduler" in line


def test_a_dask_local_cluster_builds_the_same_atlas(small_atlas, tmp_path):
    """The build through a Dask scheduler (the optional `dask` extra; skipped
    without it): the same chunks as the in-process build."""
    distributed = pytest.importorskip("dask.distributed")
    out, _ = small_atlas
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        doc = run_json("synth", ATLAS / "small-build.toml", "--out", tmp_path,
                       "--scheduler", cluster.scheduler_address)
    assert doc["results"]["curves"] == 3330
    ref = json.loads((out / "atlas" / "manifest.json").read_text())["chunks"]
    got = json.loads((tmp_path / "atlas" / "manifest.json").read_text())["chunks"]
    assert [c["sha256"] for c in got] == [c["sha256"] for c in ref]
