"""At every moment --out matches its manifest (issue 34 §2): a run writes into a staged
folder beside --out and swaps it in only at its commit; interrupted (Ctrl-C) at any
point of its write phase, or failing, it leaves the earlier run's folder exactly."""

import json

import pytest

from mechcli.report import files
from tests.conftest import CONFIGS, run_inprocess

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"


def _state(folder):
    """{name: sha256} of every file in *folder*."""
    return {p.name: files.file_sha256(p) for p in sorted(folder.iterdir()) if p.is_file()}


def _matches_manifest(folder):
    listed = json.loads((folder / files.MANIFEST).read_text(encoding="utf-8"))["files"]
    state = _state(folder)
    assert {e["name"]: e["sha256"] for e in listed} == {
        k: v for k, v in state.items() if k not in (files.MANIFEST, "mine.txt")}


def _earlier_run(tmp_path):
    out = tmp_path / "out"
    proc = run_inprocess("kin", EX1_1, "--out", out, "--quiet", "--animate")
    assert proc.returncode == 0, proc.stderr
    (out / "mine.txt").write_text("the user's own file", encoding="utf-8")
    _matches_manifest(out)
    return out, _state(out)


class _Stop(KeyboardInterrupt):
    pass


def _interrupting(monkeypatch, target, name, at):
    """Make ``target.name`` raise Ctrl-C on its call number *at* (1-based)."""
    real = getattr(target, name)
    calls = [0]

    def wrapper(*a, **k):
        calls[0] += 1
        if calls[0] == at:
            raise _Stop()
        return real(*a, **k)
    monkeypatch.setattr(target, name, wrapper)
    return calls


@pytest.mark.parametrize("where,at", [
    ("_atomic", 1), ("_atomic", 2), ("_atomic", 3),       # kin.csv, kin.png, report.txt
    ("_publish", 2), ("_carry", 1), ("Outputs._write_quiet", 1), ("_exchange", 1)])
def test_an_interrupted_rerun_leaves_the_earlier_folder_exactly(tmp_path, monkeypatch, where,
                                                                at):
    out, before = _earlier_run(tmp_path)
    target, name = (files.Outputs, where.split(".")[1]) if "." in where else (files, where)
    calls = _interrupting(monkeypatch, target, name, at)
    # another run into the same folder: other numbers, no GIF (the earlier one is stale)
    proc = run_inprocess("kin", EX1_1, "--out", out, "--quiet", "--set", "input.step=2")
    assert calls[0] >= at, "the interruption was not reached"
    assert proc.returncode == 130, proc.stderr
    assert _state(out) == before
    _matches_manifest(out)
    assert [p.name for p in tmp_path.iterdir()] == ["out"]      # no staged folder left


def test_a_failed_rerun_leaves_the_earlier_folder_and_a_committed_one_replaces_it(tmp_path):
    out, before = _earlier_run(tmp_path)
    # its files written, the run fails at its end: an [expected] key names no result
    proc = run_inprocess("kin", EX1_1, "--out", out, "--quiet", "--set", "expected.zz=1.0")
    assert proc.returncode == 2, proc.stderr
    assert _state(out) == before
    proc = run_inprocess("kin", EX1_1, "--out", out, "--quiet", "--set", "input.step=2",
                         "--no-plot")
    assert proc.returncode == 0, proc.stderr
    _matches_manifest(out)
    state = _state(out)
    assert "kin.gif" not in state and "kin.png" not in state      # stale: removed
    assert state["mine.txt"] == before["mine.txt"]                  # the user's: kept
    assert [p.name for p in tmp_path.iterdir()] == ["out"]
