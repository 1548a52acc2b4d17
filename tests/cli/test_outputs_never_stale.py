"""Outputs are never stale or clobbered (issue 18, item 4): ``outputs.json`` records each
run; files an earlier run wrote and this one did not are removed (only those); ``--set``
and file-less runs get their own default folder."""

import hashlib
import json

import pytest

from mechcli.options import default_dir_name
from tests.conftest import CONFIGS, run_inprocess

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"
EX1_2 = CONFIGS / "ch1" / "exercise1-2.toml"   # traces the coupler point F


def _run(*args):
    proc = run_inprocess(*map(str, args))
    assert proc.returncode == 0, proc.stderr
    return proc


def _manifest(out):
    return json.loads((out / "outputs.json").read_text(encoding="utf-8"))


def test_manifest_records_the_run(tmp_path):
    out = tmp_path / "o"
    doc = json.loads(_run("kin", EX1_1, "--json", "--no-plot", "--set", "mechanism.l1=100",
                          "-o", out).stdout)
    m = _manifest(out)
    import numpy
    import scipy

    import mechcli
    assert m["generator"] == "mechcli" and m["command"] == "kin"
    assert m["spec"] == str(EX1_1)
    assert m["spec_sha256"] == hashlib.sha256(EX1_1.read_bytes()).hexdigest()
    assert m["sets"] == ["mechanism.l1=100"]
    assert m["options"] == {"lang": "en", "plot": False, "animate": None, "digits": 10}
    assert m["versions"]["mechcli"] == mechcli.__version__
    assert m["versions"]["numpy"] == numpy.__version__
    assert m["versions"]["scipy"] == scipy.__version__
    assert m["versions"]["matplotlib"]
    assert [e["name"] for e in m["files"]] == ["kin.csv", "report.txt"]
    for e in m["files"]:
        data = (out / e["name"]).read_bytes()
        assert e["bytes"] == len(data) and e["sha256"] == hashlib.sha256(data).hexdigest()
    assert doc["manifest"] == str(out / "outputs.json") and doc["removed"] == []
    assert [p.rsplit("/", 1)[-1] for p in doc["files"]] == ["kin.csv", "report.txt"]


def test_a_rerun_removes_what_it_no_longer_writes_and_nothing_else(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    (out / "mine.txt").write_text("the user's own file\n")
    (out / "kin.svg").write_text("not listed in any manifest\n")
    _run("kin", EX1_2, "-q", "--animate", "-o", out)
    first = {p.name for p in out.iterdir()}
    assert first == {"kin.csv", "kin.png", "path_F.png", "kin.gif", "report.txt",
                     "outputs.json", "mine.txt", "kin.svg"}
    # another problem (other --set values): the earlier figures are stale (issue 31 §2:
    # the same spec and --set values would keep them, tests/cli/test_outputs_stay.py)
    doc = json.loads(_run("kin", EX1_2, "--json", "--no-plot", "--set", "input.omega1=20",
                          "-o", out).stdout)
    assert sorted(doc["removed"]) == ["kin.gif", "kin.png", "path_F.png"]
    assert {p.name for p in out.iterdir()} == {"kin.csv", "report.txt", "outputs.json",
                                               "mine.txt", "kin.svg"}
    assert (out / "mine.txt").read_text() == "the user's own file\n"


def test_a_stale_file_changed_since_is_kept_with_a_warning(tmp_path):
    out = tmp_path / "o"
    _run("kin", EX1_2, "-q", "-o", out)
    (out / "path_F.png").write_bytes(b"edited by hand")
    doc = json.loads(_run("kin", EX1_2, "--json", "--no-plot", "--set", "input.omega1=20",
                          "-o", out).stdout)
    assert doc["removed"] == ["kin.png"]
    assert (out / "path_F.png").read_bytes() == b"edited by hand"
    assert any(w.startswith("kept path_F.png in ") for w in doc["warnings"]), doc["warnings"]


def test_a_manifest_naming_files_outside_the_folder_removes_none_of_them(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("x")
    digest = hashlib.sha256(b"x").hexdigest()
    (out / "outputs.json").write_text(json.dumps({
        "generator": "mechcli", "format": 1,
        "files": [{"name": n, "sha256": digest} for n in
                  ("../victim.txt", str(victim), "..", "sub/x", 7)]}))
    doc = json.loads(_run("kin", EX1_1, "--json", "--no-plot", "-o", out).stdout)
    assert doc["removed"] == [] and victim.read_text() == "x"


def test_a_foreign_outputs_json_is_not_a_manifest(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    (out / "kin.png").write_bytes(b"x")
    (out / "outputs.json").write_text(json.dumps(
        {"files": [{"name": "kin.png", "sha256": hashlib.sha256(b"x").hexdigest()}]}))
    _run("kin", EX1_1, "-q", "--no-plot", "-o", out)
    assert (out / "kin.png").read_bytes() == b"x"


def test_set_runs_get_their_own_default_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _run("kin", EX1_1, "-q", "--no-plot")
    base = (tmp_path / "out" / "ex1-1" / "kin.csv").read_bytes()
    _run("kin", EX1_1, "-q", "--no-plot", "--set", "mechanism.l1=100")
    _run("kin", EX1_1, "-q", "--no-plot", "--set", "mechanism.l1=90")
    _run("kin", EX1_1, "-q", "--no-plot", "--set", " mechanism.l1=90 ")
    a = default_dir_name("ex1-1", ["mechanism.l1=100"])
    b = default_dir_name("ex1-1", ["mechanism.l1=90"])
    assert a == "ex1-1+" + hashlib.sha256(b"mechanism.l1=100").hexdigest()[:8]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(["ex1-1", a, b])
    assert (tmp_path / "out" / "ex1-1" / "kin.csv").read_bytes() == base   # not clobbered
    assert _manifest(tmp_path / "out" / b)["sets"] == ["mechanism.l1=90"]
    assert (tmp_path / "out" / a / "kin.csv").read_bytes() != base


def test_grashof_lengths_get_a_folder_named_after_them(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _run("grashof", "--lengths", "28,52,50,72", "-q")
    _run("grashof", "--lengths", "28, 52, 50, 60", "-q")
    _run("grashof", "--lengths", "28,52,50,72", "--frame", "2", "-q")
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "grashof-28_52_50_60", "grashof-28_52_50_72", "grashof-28_52_50_72-frame2"]
    assert _manifest(tmp_path / "out" / "grashof-28_52_50_72")["spec"] is None


def test_a_long_quick_form_is_hashed():
    name = default_dir_name("grashof", (), [("lengths", ",".join(["123.456"] * 20))])
    assert name.startswith("grashof-") and len(name) == len("grashof-") + 8


@pytest.mark.parametrize("sets", [["a.b=1", "c=2"], ["c=2", "a.b=1"]])
def test_set_hash_follows_the_overrides_in_order(sets):
    assert default_dir_name("s", sets) == "s+" + hashlib.sha256(
        "\0".join(sets).encode()).hexdigest()[:8]
