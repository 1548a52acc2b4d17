"""Long work and pipes (issue 31 §5): progress on stderr only on a terminal, after
~2 s, never with -q; ``-v`` lines per chunk, generation or spec; the core reports through
optional callbacks with sensible counts; tables as plain text when stdout is not a
terminal; ``NO_COLOR`` honoured on a terminal."""

import contextlib
import csv
import io
import json
import re

import numpy as np
import pytest

from mechcli import atlas_store as st
from mechcli.report import check as check_report
from mechcli.report.console import DELAY, Progress, console
from mechcli.report.table import Block, Report, print_rich
from tests.conftest import CONFIGS, run_inprocess

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"
#: rich's box drawing (U+2500 ... U+257F) and an ANSI escape
BOX = re.compile("[\u2500-\u257f]")
ESC = "\x1b"
#: a small atlas (as tests/unit/synth/test_atlas.py's): 3 chunks of 100 rows
SMALL = dict(A_range=(2.0, 3.0, 3), B_range=(2.0, 3.0, 3), C_range=(2.0, 3.0, 3),
             grid=([0.0, 0.5, 1.0, 1.5], [-0.5, 0.5, 1.0]))


class _Tty(io.StringIO):
    """A stream that says it is a terminal."""

    def isatty(self):
        return True


@pytest.fixture
def colour_terminal(monkeypatch):
    """A terminal rich colours (TERM set, nothing forcing or forbidding colour)."""
    for name in ("NO_COLOR", "FORCE_COLOR", "TTY_COMPATIBLE", "TTY_INTERACTIVE", "COLUMNS"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("TERM", "xterm-256color")


def _run_on_terminal(*args):
    """``mechcli ARGS`` in this process with stdout a terminal (stderr captured)."""
    from mechcli.cli import main

    out, err = _Tty(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            main([str(a) for a in args])
            code = 0
        except SystemExit as exc:
            code = exc.code
    return code, out.getvalue(), err.getvalue()


# -- the progress helper ---------------------------------------------------------------

def test_a_bar_appears_only_on_a_terminal_after_the_delay_and_never_with_quiet():
    now = [0.0]
    tty = _Tty()
    p = Progress("work", file=tty, clock=lambda: now[0])
    step = p.stage("chunks", 10)
    step(1)
    now[0] = DELAY - 0.1                    # short work: nothing at all
    step(2)
    assert tty.getvalue() == "" and p.bar is None
    now[0] = DELAY + 0.1
    step(3)
    assert p.bar is not None and "3/10" in tty.getvalue()     # drawn now, not at close
    p.close()
    assert "work: chunks" in tty.getvalue() and "3/10" in tty.getvalue()
    # a pipe or a file, or -q on a terminal: nothing, however long the work
    for stream, show in ((io.StringIO(), True), (_Tty(), False)):
        now[0] = 0.0
        with Progress("work", file=stream, show=show, clock=lambda: now[0]) as p:
            step = p.stage("chunks", 10)
            for k in range(1, 11):
                now[0] += DELAY
                step(k)
            assert p.bar is None
        assert stream.getvalue() == ""


def test_verbose_lines_go_to_stderr_even_in_a_pipe_and_count_the_steps():
    err = io.StringIO()
    with Progress("atlas", file=err, verbose=True) as p:
        step = p.stage("chunks", 3, detail=lambda done, total, curves: f"{done}/{total}: "
                                                                       f"{curves} curves")
        for k, curves in enumerate((0, 100, 200, 288)):
            step(k, curves=curves)
        assert list(p.track(["a", "b"], "refining")) == ["a", "b"]
    # the stage's start (nothing done) has no line; one per step after it
    assert err.getvalue().splitlines() == [
        "mechcli: atlas: 1/3: 100 curves", "mechcli: atlas: 2/3: 200 curves",
        "mechcli: atlas: 3/3: 288 curves", "mechcli: atlas: refining 1/2",
        "mechcli: atlas: refining 2/2"]


# -- the core's callbacks ---------------------------------------------------------------

def test_the_atlas_build_and_search_report_every_chunk(tmp_path):
    built = []
    info = st.build_atlas(tmp_path / "a", chunk=100, **SMALL,
                          progress=lambda done, total, **v: built.append((done, total, v)))
    n = len(info.chunks)
    assert n == 3 and info.complete
    # once before the first chunk, then after each: chunks done of all, curves so far
    assert [b[:2] for b in built] == [(k, n) for k in range(n + 1)]
    curves = [b[2]["curves"] for b in built]
    assert curves[0] == 0 and curves[-1] == info.curves == 288 and curves == sorted(curves)
    assert {b[2]["resumed"] for b in built} == {0}
    # a resumed build finds every chunk on disk: one call, all done
    again = []
    st.build_atlas(tmp_path / "a", chunk=100, **SMALL,
                   progress=lambda done, total, **v: again.append((done, total, v)))
    assert again == [(n, n, {"curves": 288, "resumed": n})]
    searched = []
    t = np.linspace(0.0, 2 * np.pi, 12, endpoint=False)
    st.search(info, np.cos(t), 0.5 * np.sin(t), k=3,
              progress=lambda done, total, **v: searched.append((done, total, v["curves"])))
    assert [s[:2] for s in searched] == [(k, n) for k in range(1, n + 1)]
    assert searched[-1][2] == info.curves


def test_a_streamed_sweep_reports_the_rows_solved_after_every_chunk():
    import dataclasses

    from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
    from mechcli.core.linkage.streaming import StreamedRows, stream_grid
    from mechcli.spec.kin import load_kin_spec

    # 例 1-1 with a 220 mm crank: the crank cannot turn through 109.7° ... 250.3°, so some
    # chunks keep none of their rows (as tests/unit/linkage/test_speed_streaming.py's gap test)
    spec = load_kin_spec(EX1_1, ["mechanism.l1=220", "input.partial=true",
                                 "input.count=20001"])
    inp, quantities = spec.input, default_quantities(spec.linkage, 2)
    n = 20_001
    sub = dataclasses.replace(inp, q=stream_grid(inp.start, inp.stop, n, analysed=2001))
    result = analyse_sweep(spec.linkage, sub.sweep(), quantities, 2, partial=True)
    calls = []
    rows = StreamedRows(spec.linkage, sub.sweep(), quantities, 2, inp.start, inp.stop, n,
                        result, chunk=4096,
                        progress=lambda done, total, kept: calls.append((done, total, kept)))
    handed = np.cumsum([q.size for q, _v in rows])
    # every chunk of 4096 rows, the last one short: 5 calls, the rows solved so far
    assert [c[0] for c in calls] == [4096, 8192, 12288, 16384, 20001]
    assert {c[1] for c in calls} == {n}
    kept = [c[2] for c in calls]
    assert kept == sorted(kept) and kept[-1] == rows.rows == handed[-1] < n
    assert set(handed) <= set(kept)


def test_differential_evolution_reports_each_generation_and_its_best_design():
    from mechcli.core.optimize.methods import minimize
    from mechcli.core.optimize.problem import Evaluation, Problem, Variable

    def ev(X):   # min |x - (2, 2)|^2 subject to x0 + x1 <= 2 (the optimum (1, 1), f = 2)
        return Evaluation(np.sum((X - 2.0) ** 2, axis=1), X[:, :1] + X[:, 1:2] - 2.0,
                          np.ones(len(X), bool))

    p = Problem([Variable("a", -5, 5, 0.0), Variable("b", -5, 5, 0.0)], ev, ["sum"])
    calls = []
    r = minimize(p, "differential_evolution", maxiter=300, seed=3,
                 progress=lambda done, total, **v: calls.append((done, total, v)))
    gens = [c[0] for c in calls]
    assert gens == list(range(1, len(gens) + 1)) and 1 < len(gens) <= 300
    assert {c[1] for c in calls} == {300}
    # each call is the generation's row of the history (the polish's rows come after)
    for (done, _t, v), rec in zip(calls, r.history):
        assert rec.iteration == done and v["f"] == rec.f and v["violation"] == rec.violation
    # the best design of each generation is never worse than the one before (DE keeps it)
    feasible = [v["f"] for _d, _t, v in calls if v["violation"] == 0]
    assert feasible == sorted(feasible, reverse=True)
    assert r.f == pytest.approx(2.0, abs=1e-7)


# -- the commands ------------------------------------------------------------------------

def test_check_writes_nothing_to_a_non_terminal_stderr_and_a_line_per_spec_with_v():
    specs = [CONFIGS / "ch1" / "ex1-1.toml", CONFIGS / "ch1" / "ex1-2.toml"]
    quiet = run_inprocess("check", *specs, "-j", "1")
    assert quiet.returncode == 0 and quiet.stderr == ""
    loud = run_inprocess("check", *specs, "-j", "1", "-v")
    assert loud.returncode == 0
    lines = loud.stderr.splitlines()
    assert len(lines) == 2
    for k, (line, spec) in enumerate(zip(lines, specs), 1):
        assert line.startswith(f"mechcli: check: {k}/2 {spec}: ok (")
    # 例 1-1's six [expected] values (the config's table)
    assert "(6/6 expected values" in lines[0]


def test_kin_v_prints_a_line_per_streamed_chunk(tmp_path):
    # 600,002 rows: past the in-memory 600,001, streamed in chunks of 65,536 (engine.CHUNK)
    proc = run_inprocess("kin", EX1_1, "--set", "input.count=600002", "-q", "--no-plot",
                         "-v", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.startswith("mechcli: kin: ")]
    solved = [int(re.search(r"kin\.csv: ([\d,]+) of 600,002", ln).group(1).replace(",", ""))
              for ln in lines]
    assert solved == [min(65_536 * k, 600_002) for k in range(1, 11)]
    assert lines[-1].endswith("600,002 of them in the CSV")


def test_optimize_v_prints_each_generation_as_history_csv_records_it(tmp_path):
    # 习题 7-2: differential evolution (maxiter 1000 by default), then the SLSQP polish
    proc = run_inprocess("optimize", CONFIGS / "ch7" / "exercise7-2.toml", "-q", "--no-plot",
                         "-v", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if "generation" in ln]
    found = [re.search(r"generation (\d+)/(\d+), best f = (\S+) rad\^2", ln) for ln in lines]
    assert all(found) and {m.group(2) for m in found} == {"1000"}
    gens = [int(m.group(1)) for m in found]
    assert gens == list(range(1, len(gens) + 1))
    with open(tmp_path / "history.csv", newline="") as fh:
        history = list(csv.DictReader(fh))
    assert len(history) > len(gens)             # the polish's iterations follow
    for m, row in zip(found, history):
        assert int(float(row["iteration"])) == int(m.group(1))
        assert float(m.group(3)) == pytest.approx(float(row["f"]), rel=1e-7)   # 8 digits


def test_synth_v_counts_the_atlas_chunks_and_a_rerun_finds_them_on_disk(tmp_path):
    spec = CONFIGS / "atlas" / "small-build.toml"
    first = run_inprocess("synth", spec, "-q", "--no-plot", "-v", "-o", tmp_path)
    assert first.returncode == 0, first.stderr
    manifest = json.loads((tmp_path / "atlas" / "manifest.json").read_text())
    n, curves = manifest["chunk_count"], manifest["curves"]
    lines = first.stderr.splitlines()
    assert [ln.split(",")[0] for ln in lines] == [
        f"mechcli: synth: atlas: chunk {k}/{n} built" for k in range(1, n + 1)]
    assert lines[-1].endswith(f"{curves:,} curves")
    again = run_inprocess("synth", spec, "-q", "--no-plot", "-v", "-o", tmp_path)
    assert again.stderr.splitlines() == [
        f"mechcli: synth: atlas: chunk {n}/{n} built, {curves:,} curves ({n} found on disk)"]
    silent = run_inprocess("synth", spec, "-q", "--no-plot", "-o", tmp_path / "s")
    assert silent.returncode == 0 and silent.stderr == ""


# -- tables in pipes and NO_COLOR ---------------------------------------------------------

def test_check_in_a_pipe_prints_plain_text_without_box_drawing_or_escapes():
    proc = run_inprocess("check", CONFIGS / "ch1", "-j", "2")
    assert proc.returncode == 0, proc.stderr
    assert not BOX.search(proc.stdout) and ESC not in proc.stdout
    lines = proc.stdout.splitlines()
    assert lines[0] == "mechcli check" and lines[1].split() == [
        "spec", "command", "checks", "worst", "dev/tol", "time", "s"]
    specs = sorted(str(p) for p in (CONFIGS / "ch1").rglob("*.toml"))
    rows = [ln for ln in lines if ln.startswith(str(CONFIGS / "ch1"))]
    # one whole line per spec, its path never cut, in the order run
    assert [r.split()[0] for r in rows] == specs
    assert all(r.split()[1] == "kin" and r.endswith(" ok") for r in rows)


def test_a_command_in_a_pipe_prints_plain_text(tmp_path):
    proc = run_inprocess("kin", EX1_1, "--no-plot", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "θ1/(°)" in proc.stdout and not BOX.search(proc.stdout) and ESC not in proc.stdout


def test_no_color_turns_every_escape_off_on_a_terminal(colour_terminal, monkeypatch,
                                                        tmp_path):
    rep = Report("title", [Block("table", ["a", "b"], [["1", "2"]])])
    results = [{"spec": "x.toml", "command": "kin", "status": "failed", "exit_code": 4,
                "time_s": 0.1, "checks": [{"held": False, "deviation": 2.0}]}]

    def shown():
        plain = io.StringIO()
        console(plain, force_terminal=True).print("[bold red]x[/]")
        table, checked = _Tty(), _Tty()
        print_rich(rep, file=table, width=80)
        check_report.print_table(results, file=checked)
        code, out, _err = _run_on_terminal("kin", EX1_1, "--no-plot", "-o", tmp_path)
        assert code == 0
        return plain.getvalue(), table.getvalue(), checked.getvalue(), out

    coloured = shown()
    assert all(ESC in text for text in coloured)       # the test can fail
    monkeypatch.setenv("NO_COLOR", "1")
    for text in shown():
        assert ESC not in text
    # on a terminal the tables stay rich tables: only the escapes go
    assert all(BOX.search(text) for text in shown()[1:])
