"""A sweep past the in-memory limit is streamed to the CSV (issue 17): the same bytes
as the rows solved all at once, in bounded memory (tracemalloc, not time), with the
extremes of the analysis.

References: the unstreamed CSV is written here from one engine call over every row
(``solve``, the quantities, ``np.unwrap`` shifted into (-180°, 180°] as
``analyse_sweep`` does for a sweep without gaps) through ``report.columns`` and
``write_csv``; the extremes are 【例 1-1】's, refined on the exact solution by a
normal (in-memory) run.
"""

import json
import tracemalloc
import types
from pathlib import Path

import numpy as np
import pytest

from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.linkage.kinematics import default_quantities
from mechcli.core.linkage.sweep import _wrap
from mechcli.core.linkage.streaming import StreamedRows, rows_at, stream_grid
from mechcli.report import kin as report
from mechcli.report.files import write_csv, write_csv_stream
from mechcli.spec.kin import MAX_POSITIONS, MAX_STREAMED, load_kin_spec
from tests.conftest import run_inprocess

EX1_1 = Path(__file__).resolve().parents[3] / "configs" / "ch1" / "ex1-1.toml"
#: 360° / 0.00036° = 1e6 steps: 1,000,001 rows, past kin's in-memory 600,001
STEP = "input.step=0.00036"
ROWS = 1_000_001


def test_rows_are_linspace_bit_for_bit():
    for start, stop, count in ((0.0, 2 * np.pi, ROWS), (-0.3, 7.1, 1_234_567)):
        full = np.linspace(start, stop, count)
        assert np.array_equal(rows_at(start, stop, count, np.arange(count)), full)
        assert np.array_equal(rows_at(start, stop, count, np.arange(70_000, 140_001)),
                              full[70_000:140_001])
        grid = stream_grid(start, stop, count, extra=[start + 0.5])
        assert np.isin(grid, full).all() and grid[0] == start and grid[-1] == stop
        assert grid.size <= 36_002 and np.all(np.diff(grid) > 0)


def test_unwrap_across_chunks_is_numpy_unwrap():
    # an angle that turns several times, cut into chunks at arbitrary rows
    rng = np.random.default_rng(3)
    raw = _wrap(np.cumsum(rng.uniform(-3.0, 3.0, 5000)))
    from mechcli.core.linkage.streaming import _Unwrap
    u = _Unwrap()
    u.start(raw[0] - _wrap(raw[0]))
    cuts = [0, 1, 2, 700, 701, 3000, 5000]
    got = np.concatenate([u(raw[a:b]) for a, b in zip(cuts[:-1], cuts[1:])])
    seg = np.unwrap(raw)
    assert np.array_equal(got, seg - (seg[0] - _wrap(seg[0])))


def _unstreamed_csv(spec, path):
    """The CSV of every row solved in one engine call (the reference)."""
    inp = spec.input
    q = np.linspace(inp.start, inp.stop, inp.count)
    quantities = default_quantities(spec.linkage, spec.output.order)
    m = solve(spec.linkage, {inp.driver: DriverMotion(q, inp.omega, inp.alpha)},
              order=spec.output.order)
    assert m.regular.all()
    values = {}
    for qt in quantities:
        v = np.asarray(qt.get(m), dtype=float)
        if qt.is_angle:
            v = np.unwrap(v)
            v = v - (v[0] - _wrap(v[0]))
        values[qt.symbol] = v
    write_csv(path, report.columns(spec, quantities, types.SimpleNamespace(q=q, values=values)))


def test_streamed_csv_equals_unstreamed(tmp_path):
    out = tmp_path / "streamed"
    res = run_inprocess("kin", EX1_1, "--set", STEP, "--out", out, "--no-plot", "--json")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)["results"]
    # the analysis ran on ~36,000 of the rows (every 28th and the table's)
    assert doc["positions"] == ROWS and doc["positions_analysed"] <= 36_100
    spec = load_kin_spec(EX1_1, [STEP], stream=True)
    assert spec.input.count == ROWS
    ref = tmp_path / "ref.csv"
    _unstreamed_csv(spec, ref)
    assert (out / "kin.csv").read_bytes() == ref.read_bytes()
    # the extremes are those of the in-memory run at the book's step (refined on the
    # exact solution, so independent of the step), to their tolerance
    base = json.loads(run_inprocess("kin", EX1_1, "--out", tmp_path / "base", "--no-plot",
                                    "--json").stdout)["results"]
    for key in ("theta3_max_deg", "theta3_min_deg", "omega3_max_rad_s", "alpha3_max_rad_s2",
                "gammaC_min_deg"):
        assert doc[key] == pytest.approx(base[key], rel=1e-9, abs=1e-9), key


def _stream_peak(spec, quantities, sweep, result, count, path, chunk):
    """Peak traced memory [B] of streaming *count* rows of *spec*'s sweep to *path*."""
    tracemalloc.start()
    try:
        rows = StreamedRows(spec.linkage, sweep, quantities, 2, spec.input.start,
                            spec.input.stop, count, result, chunk=chunk)
        headers = [h for h, _c in report.columns(spec, quantities, result)]
        write_csv_stream(path, headers, (
            [c for _h, c in report.columns(spec, quantities, types.SimpleNamespace(q=q, values=v))]
            for q, v in rows))
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_stream_memory_does_not_grow_with_the_rows(tmp_path):
    from mechcli.core.linkage.kinematics import analyse_sweep
    spec = load_kin_spec(EX1_1, [])
    quantities = default_quantities(spec.linkage, 2)
    sweep = spec.input.sweep()
    result = analyse_sweep(spec.linkage, sweep, quantities, 2)
    # chunks of 4,096 rows (the CLI streams 65,536 at a time: 34 MB traced at 720,001
    # and at 2,000,001 rows, measured 2026-11-25); tracemalloc slows the CSV's text ~7x,
    # so few rows here
    small = _stream_peak(spec, quantities, sweep, result, 20_001, tmp_path / "a.csv", 4096)
    large = _stream_peak(spec, quantities, sweep, result, 100_001, tmp_path / "b.csv", 4096)
    # one chunk whatever the rows: the 100,001 rows' eight columns alone would be 6.4 MB
    # as arrays, their CSV text 8 MB
    assert large < small + 0.5e6 and large < 6e6, (small, large)  # 4.4 MB both, measured
    with open(tmp_path / "b.csv", "rb") as fh:
        assert sum(1 for _ in fh) == 100_002


def test_streamed_rows_never_pass_the_refined_extremes(tmp_path):
    spec = load_kin_spec(EX1_1, ["input.step=0.0005"], stream=True)   # 720,001 rows
    from mechcli.core.linkage.kinematics import analyse_sweep
    quantities = default_quantities(spec.linkage, 2)
    sweep = spec.input.sweep()
    result = analyse_sweep(spec.linkage, sweep, quantities, 2)
    rows = StreamedRows(spec.linkage, sweep, quantities, 2, spec.input.start, spec.input.stop,
                        spec.input.count, result)
    n = sum(q.size for q, _v in rows)
    assert n == spec.input.count == rows.rows and rows.irregular is None
    for sym, (hi, lo) in result.extremes.items():
        top, _a, bottom, _b = rows.peaks[sym]
        slack = 1e-12 * max(abs(hi.value), abs(lo.value))
        assert bottom >= lo.value - slack and top <= hi.value + slack, sym


def test_a_failing_stream_leaves_no_csv(tmp_path):
    def chunks():
        yield [np.arange(3.0), np.ones(3)]
        yield [np.array([1.0]), np.array([np.nan])]

    target = tmp_path / "k.csv"
    from mechcli.report.files import OutputError
    with pytest.raises(OutputError, match="row 4"):
        write_csv_stream(target, ["a", "b"], chunks())
    assert list(tmp_path.iterdir()) == []


def test_kin_limits_in_memory_and_streamed():
    assert MAX_POSITIONS == 600_001 and MAX_STREAMED == 100_000_001
    assert load_kin_spec(EX1_1, ["input.count=600001"]).input.count == 0
    assert load_kin_spec(EX1_1, ["input.count=600002"], stream=True).input.count == 600_002
    res = run_inprocess("kin", EX1_1, "--set", f"input.count={MAX_STREAMED + 1}", "--json")
    assert res.returncode == 2 and "at most 100,000,001 positions" in res.stdout + res.stderr


def test_a_streamed_sweep_with_gaps_matches_the_in_memory_one():
    # 例 1-1 with a 220 mm crank: a non-Grashof chain whose crank cannot turn through
    # 109.7° ... 250.3° (computed here by the in-memory analysis of every row)
    import dataclasses

    from mechcli.core.linkage.kinematics import analyse_sweep
    spec = load_kin_spec(EX1_1, ["mechanism.l1=220", "input.partial=true",
                                 "input.count=20001"])
    inp, quantities = spec.input, default_quantities(spec.linkage, 2)
    whole = analyse_sweep(spec.linkage, inp.sweep(), quantities, 2, partial=True)
    assert len(whole.excluded) == 1
    n = 20_001   # in memory here (inp.count is 0): streamed below as if it were long
    sub = dataclasses.replace(inp, q=stream_grid(inp.start, inp.stop, n, analysed=2001))
    result = analyse_sweep(spec.linkage, sub.sweep(), quantities, 2, partial=True)
    rows = StreamedRows(spec.linkage, sub.sweep(), quantities, 2, inp.start, inp.stop, n,
                        result, chunk=4096)
    got = list(rows)
    q = np.concatenate([c[0] for c in got])
    assert np.array_equal(q, whole.q) and rows.irregular is None
    for qt in quantities:
        v = np.concatenate([c[1][qt.symbol] for c in got])
        ref = whole.values[qt.symbol]
        # the same rows, solved alike; the angles' runs placed on the same turn
        np.testing.assert_allclose(v, ref, rtol=1e-12, atol=1e-12 * np.max(np.abs(ref)),
                                   err_msg=qt.symbol)


def test_sigterm_while_streaming_leaves_no_temporary_file(tmp_path):
    """A streamed CSV takes seconds to write: `kill` (SIGTERM, a CI timeout) midway
    must leave neither the CSV nor its hidden temporary file (review of issue 17)."""
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "mechcli", "kin", str(EX1_1),
         "--set", "input.step=0.00003", "--no-plot", "--out", str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    def streaming():   # the run writes into its staged folder beside --out
        return any(p.name.endswith(".tmp") for d in tmp_path.glob(".out.mechcli-*")
                   for p in d.iterdir())

    while time.monotonic() < deadline:          # wait until the stream has begun
        if streaming() or proc.poll() is not None:
            break
        time.sleep(0.05)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=60)
    assert proc.returncode == 128 + signal.SIGTERM
    # neither the CSV, nor its temporary file, nor the staged folder is left
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_manifest_checksums_are_sha256(tmp_path):
    """outputs.json's checksums (files._sha256: CPython's built-in SHA-256 for up to 1 MB,
    hashlib's beyond) are hashlib.sha256's: in-memory bytes small and large, a file written
    by a function (hashed back through its descriptor), a CSV from memory, a stream."""
    import hashlib

    from mechcli.report import files

    small, large = tmp_path / "a.txt", tmp_path / "big.bin"
    files.write_text(small, "θ1 = 30°\n" * 1000)
    files.write_bytes(large, bytes(range(256)) * 9000)                  # 2.3 MB
    by_function = tmp_path / "f.bin"
    files._atomic(by_function, lambda fh: [fh.write(b"%d," % i) for i in range(300_000)])
    csv_path, streamed = tmp_path / "c.csv", tmp_path / "s.csv"
    write_csv(csv_path, [("x", np.arange(100.0)), ("y", np.ones(100))])
    write_csv_stream(streamed, ["x", "y"], ([np.arange(5.0) + k, np.ones(5)] for k in range(3)))
    for path in (small, large, by_function, csv_path, streamed):
        data = path.read_bytes()
        want = hashlib.sha256(data).hexdigest()
        assert files._WRITTEN[str(path)] == (len(data), want), path.name
        assert files.file_sha256(path) == want
        assert oct(path.stat().st_mode & 0o777) == oct(0o666 & ~files._UMASK)
    assert large.stat().st_size > files._BUILTIN_HASH_MAX > small.stat().st_size


def test_csv_guard_and_early_errors(tmp_path, monkeypatch):
    """A CSV from memory of more than _GUARD_CELLS cells is guarded against SIGTERM like a
    stream, a small one is not; a stream refused before its first row leaves no file."""
    from mechcli.report import files

    guarded = []
    monkeypatch.setattr(files, "_terminate_as_exit", lambda: guarded.append(1) or files._nothing)
    write_csv(tmp_path / "small.csv", [("x", np.arange(10.0))])
    assert guarded == []
    monkeypatch.setattr(files, "_GUARD_CELLS", 5)
    write_csv(tmp_path / "big.csv", [("x", np.arange(10.0))])
    assert guarded == [1]
    with pytest.raises(TypeError):
        write_csv_stream(tmp_path / "bad.csv", iter(["x"]), [[[1.0]]])   # no len()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.csv", "small.csv"]
