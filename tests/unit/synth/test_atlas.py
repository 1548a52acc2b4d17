"""The digital Hrones–Nelson atlas (issue 15): pages against the engine and a
closed form, descriptor invariance, build/search/refine, the type chart, ranges,
interrupted builds and corrupt files."""

import json
import math

import numpy as np
import pytest

from mechcli.core.errors import DescribedError
from mechcli.core.grashof.chain import TYPES
from mechcli.core.grashof.fourbar import classify_fourbar
from mechcli.core.linkage import DriverMotion, solve
from mechcli import atlas_store as st
from mechcli.core.synth import atlas as at

SMALL = dict(A_range=(2.0, 3.0, 3), B_range=(2.0, 3.0, 3), C_range=(2.0, 3.0, 3),
             grid=([0.0, 0.5, 1.0, 1.5], [-0.5, 0.5, 1.0]))


def closed_form(A, B, C, gx, gy, theta):
    """An independent four-bar: crank pin on the unit circle, C by two circles
    (open branch: left of crank pin -> follower pivot), P on the coupler."""
    bx, by = np.cos(theta), np.sin(theta)
    dx, dy = C - bx, -by
    d = np.hypot(dx, dy)
    a = (A * A - B * B + d * d) / (2 * d)
    h = np.sqrt(A * A - a * a)
    cx = bx + (a * dx - h * dy) / d
    cy = by + (a * dy + h * dx) / d
    ux, uy = (cx - bx) / A, (cy - by) / A
    return bx + gx * ux - gy * uy, by + gx * uy + gy * ux


@pytest.fixture(scope="module")
def small_atlas(tmp_path_factory):
    d = tmp_path_factory.mktemp("atlas")
    return st.build_atlas(d, chunk=100, **SMALL)


def test_page_against_engine_and_closed_form():
    gx, gy = np.array([0.0, 1.0, 2.5, -0.5]), np.array([0.0, 0.0, 1.5, -1.0])
    page = at.atlas_page(2.5, 2.0, 3.0, gx, gy)
    assert page.kind == "crank-rocker" and page.reason is None and page.ok.all()
    assert page.x.shape == (4, 72) and np.allclose(np.diff(page.theta), math.radians(5))
    lk = at.atlas_linkage(2.5, 2.0, 3.0, gx[:, None], gy[:, None])
    m = solve(lk, {1: DriverMotion(page.theta)}, order=0)
    assert np.max(np.abs(page.x - m.points["P"].x)) < 1e-14
    assert np.max(np.abs(page.y - m.points["P"].y)) < 1e-14
    x, y = closed_form(2.5, 2.0, 3.0, gx[:, None], gy[:, None], page.theta[None, :])
    assert np.max(np.hypot(page.x - x, page.y - y)) < 1e-12
    # the crank pin's point is the unit circle
    assert np.allclose(np.hypot(page.x[0], page.y[0]), 1.0)


def test_page_of_a_linkage_that_cannot_turn():
    page = at.atlas_page(1.5, 2.0, 3.0, [0.0, 1.0], [0.0, 0.0])   # s + l > p + q
    assert not page.ok.any() and page.reason == "not_crank_rocker"
    assert page.kind == "double-rocker"


def test_descriptor_invariance():
    page = at.atlas_page(2.5, 2.0, 3.0, [1.0, 2.0, 0.5], [0.5, -1.0, 1.5])
    z = page.x + 1j * page.y
    d0 = at.descriptors(page.x, page.y)
    moved = np.roll(z, 23, axis=1) * (4.7 * np.exp(0.9j)) + (3 - 8j)
    d1 = at.descriptors(moved.real, moved.imag)
    assert d0.shape == (3, 64) and d0.dtype == np.float32
    assert np.max(np.abs(d0 - d1)) < 1e-6
    # the exact coefficients are the limit of dense arc-length resampling
    _, c, _ = at.polyline_coefficients(page.x[1], page.y[1], 8)
    _, c2, _ = at._resampled_coefficients(page.x[1], page.y[1], 8, 200_000)
    assert np.max(np.abs(c - c2)) < 1e-6
    # a mirror image is another shape
    assert np.max(np.abs(at.descriptors(page.x[1], -page.y[1]) - d0[1])) > 1e-2


def test_build_search_finds_itself(small_atlas):
    info = st.open_atlas(small_atlas.directory, verify=True)
    assert info.complete and info.curves == info.candidates > 0
    planted = (2.5, 3.0, 2.5, 1.0, 0.5)
    assert at.crank_rocker_mask(*planted[:3]).all()
    page = at.atlas_page(*planted[:3], [planted[3]], [planted[4]])
    z = np.roll(page.x[0] + 1j * page.y[0], 11) * (0.03 * np.exp(2.1j)) + (0.4 + 0.1j)
    hits = st.search(info, z.real, z.imag, k=3)
    assert (hits[0].A, hits[0].B, hits[0].C, hits[0].gx, hits[0].gy) == pytest.approx(planted)
    assert hits[0].distance < 1e-5 and hits[1].distance > hits[0].distance
    # reversed travel finds it too
    back = st.search(info, z.real[::-1], z.imag[::-1], k=3)
    assert (back[0].A, back[0].gx) == pytest.approx((2.5, 1.0)) and back[0].reversed


def test_planted_linkage_found_and_refined(small_atlas):
    planted = (2.5, 2.5, 2.5, 0.5, 1.0)
    page = at.atlas_page(*planted[:3], [planted[3]], [planted[4]], step=math.radians(15))
    z = page.x[0] * 1 + 1j * page.y[0]
    z = z * (12.0 * np.exp(-0.4j)) + (100 + 50j)
    hits = st.search(small_atlas, z.real, z.imag, k=3)
    assert any((h.A, h.B, h.C, h.gx, h.gy) == pytest.approx(planted) for h in hits)
    # refine from an off-grid neighbour of the planted linkage's target
    off = (2.62, 2.41, 2.55, 0.63, 0.91)
    page2 = at.atlas_page(*off[:3], [off[3]], [off[4]], step=math.radians(15))
    z2 = (page2.x[0] + 1j * page2.y[0]) * (12.0 * np.exp(-0.4j)) + (100 + 50j)
    hit = st.search(small_atlas, z2.real, z2.imag, k=1)[0]
    r = at.refine(hit, z2.real, z2.imag)
    assert r.error_max < 1e-6 * r.size
    m = solve(r.linkage, {1: DriverMotion(np.linspace(0, 2 * np.pi, 7))}, order=0)
    assert m.feasible.all()


def test_refine_with_timing():
    planted = (2.5, 2.5, 2.5, 0.5, 1.0)
    th = np.radians(np.arange(0, 360, 30))
    x, y = closed_form(*planted, th + 0.3)
    z = (x + 1j * y) * 2.0 + 1.0
    guess = at.Match(0.0, 2.4, 2.6, 2.45, 0.6, 0.9)
    r = at.refine(guess, z.real, z.imag, angles=th)
    assert r.error_max < 1e-6 * r.size


def test_type_chart_against_grashof():
    chart = at.type_chart([2.5, 1.5], (0.2, 5.0), (0.2, 6.0), points=101)
    assert chart.region.shape == (2, 101, 101)
    rng = np.random.default_rng(1)
    lut = {"crank_rocker": at.CRANK_ROCKER, "double_crank": at.DOUBLE_CRANK,
           "double_rocker": at.DOUBLE_ROCKER, "parallelogram": at.DOUBLE_CRANK}
    for _ in range(200):
        i, j, k = rng.integers(2), rng.integers(101), rng.integers(101)
        L = [1.0, chart.A[i], chart.B[k], chart.C[j]]
        t = TYPES[int(classify_fourbar(L).code[0])]
        want = at.CHANGE_POINT if t.startswith("change_point") else lut[t]
        assert chart.region[i, j, k] == want
    # the worked example is inside the crank-rocker region with crank 1
    c = at.type_chart(2.5, [2.0], [3.0])
    assert c.region[0, 0] == at.CRANK_ROCKER and c.crank[0, 0] == 1


def test_admissible_ranges_of_the_seed_example():
    r = at.admissible_ranges(2.5, 2.0, 3.0)
    assert r["C"] == pytest.approx((1.5, 3.5)) and r["B"] == pytest.approx((1.5, 4.5))
    assert r["A"] == pytest.approx((2.0, 4.0))
    with pytest.raises(DescribedError) as e:
        at.admissible_ranges(1.5, 2.0, 3.0)
    assert e.value.reason == "not_crank_rocker"


def test_interrupted_build_resumes_identically(tmp_path):
    class Boom(Exception):
        pass

    def mapper(fn, tasks):
        for n, t in enumerate(tasks):
            if n == 2:
                raise Boom
            yield fn(t)

    with pytest.raises(Boom):
        st.build_atlas(tmp_path / "a", chunk=100, mapper=mapper, **SMALL)
    part = st.open_atlas(tmp_path / "a", verify=True)
    assert len(part.chunks) == 2 and not part.complete
    full = st.build_atlas(tmp_path / "a", chunk=100, **SMALL)
    ref = st.build_atlas(tmp_path / "b", chunk=100, **SMALL)
    assert full.complete and full.curves == ref.curves
    assert [c["sha256"] for c in full.chunks] == [c["sha256"] for c in ref.chunks]
    with pytest.raises(DescribedError) as e:      # another build in the same place
        st.build_atlas(tmp_path / "a", chunk=50, **SMALL)
    assert e.value.reason == "atlas_foreign"


def test_corrupt_and_foreign_files(tmp_path, small_atlas):
    import shutil
    d = tmp_path / "c"
    shutil.copytree(small_atlas.directory, d)
    chunk = d / "chunk-00001.npz"
    data = bytearray(chunk.read_bytes())
    data[200] ^= 0xFF
    chunk.write_bytes(bytes(data))
    with pytest.raises(DescribedError) as e:
        st.search(d, [0, 1, 0], [0, 0, 1])
    assert e.value.reason == "atlas_corrupt"
    chunk.write_bytes(bytes(data[:100]))
    with pytest.raises(DescribedError) as e:
        st.open_atlas(d)
    assert e.value.reason == "atlas_corrupt"
    (d / "manifest.json").write_text("{not json")
    with pytest.raises(DescribedError) as e:
        st.open_atlas(d)
    assert e.value.reason == "atlas_corrupt"
    (d / "manifest.json").write_text(json.dumps({"format": "something else"}))
    with pytest.raises(DescribedError) as e:
        st.open_atlas(d)
    assert e.value.reason == "atlas_foreign"


def test_bad_requests(small_atlas, tmp_path):
    with pytest.raises(DescribedError) as e:
        st.search(small_atlas, [0, 1], [0, 1])
    assert e.value.reason == "too_few_points"
    with pytest.raises(DescribedError) as e:
        st.search(small_atlas, [0, 1, 0, 1], [0, 1, 0, 1])
    assert e.value.reason == "too_few_points"
    with pytest.raises(DescribedError) as e:
        st.build_atlas(tmp_path / "n", (1.0, 1.2, 2), (5.0, 6.0, 2), (1.0, 1.1, 2), ([0], [0]))
    assert e.value.reason == "no_crank_rocker"


def test_default_build_size():
    sets = at.ratio_sets(at.DEFAULT_A_RANGE, at.DEFAULT_B_RANGE, at.DEFAULT_C_RANGE)
    assert len(sets) * len(at.DEFAULT_GRID[0]) * len(at.DEFAULT_GRID[1]) >= 100_000
    # every default ratio set turns fully at every grid point (a sample)
    desc, params, ok = at.build_chunk(at.chunk_params(
        {"A_range": at.DEFAULT_A_RANGE, "B_range": at.DEFAULT_B_RANGE,
         "C_range": at.DEFAULT_C_RANGE, "grid": at.DEFAULT_GRID}, 0, 3000))
    assert ok.all() and desc.shape == (3000, 64)
