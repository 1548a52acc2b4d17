"""Batches and files: ``--digits``, round-trip JSON, atomic outputs under concurrent
writers, ``mechcli new`` and the homework Makefile (issue 16, "Batches and files")."""

import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import run_inprocess

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
HOMEWORK = ROOT / "examples" / "homework"
COMMANDS = ("kin", "force", "grashof", "cam", "gear", "synth", "flywheel", "optimize")


def read_rows(path):
    with open(path, newline="") as fh:
        return list(csv.reader(fh))


# -- --digits ----------------------------------------------------------------------------
@pytest.mark.parametrize("command, spec, name", [
    ("kin", CONFIGS / "ch1" / "ex1-1.toml", "kin.csv"),
    ("force", CONFIGS / "ch2" / "ex2-1.toml", "force.csv"),
    ("cam", CONFIGS / "ch4" / "ex4-1.toml", "cam.csv"),
    ("gear", CONFIGS / "ch5" / "ex5-3.toml", "gear.csv"),
    ("gear", CONFIGS / "ch5" / "ex5-4.toml", "gear.csv"),       # a pair: text CSV writer
    ("grashof", CONFIGS / "ch3" / "ex3-1.toml", "grashof.csv"),  # text CSV writer
])
def test_digits_17_is_round_trip_exact_and_keeps_the_columns(tmp_path, command, spec, name):
    files = {}
    for digits in (10, 17):
        out = tmp_path / str(digits)
        proc = run_inprocess(command, spec, "--no-plot", "--quiet", "--digits", digits,
                             "--out", out)
        assert proc.returncode == 0, proc.stderr
        files[digits] = read_rows(out / name)
    lo, hi = files[10], files[17]
    assert lo[0] == hi[0] and len(lo) == len(hi)
    assert all(len(a) == len(b) for a, b in zip(lo, hi))
    longest = {d: 0 for d in (10, 17)}
    differ = 0
    for a_row, b_row in zip(lo[1:], hi[1:]):
        for a, b in zip(a_row, b_row):
            try:
                x, y = float(a), float(b)
            except ValueError:        # a type name or an empty cell: the same in both
                assert a == b
                continue
            # 10 significant digits agree with the exact value to half a unit of the 10th
            assert abs(x - y) <= 5e-10 * abs(y) + 1e-300
            # 17 significant digits: the number as printed by %.17g, which reads back exactly
            assert b == f"{y:.17g}" and float(f"{y:.17g}") == y
            differ += a != b
            for d, cell in ((10, a), (17, b)):
                mant = re.sub(r"e.*", "", cell).replace("-", "").replace(".", "").lstrip("0")
                longest[d] = max(longest[d], len(mant))
    assert longest[10] <= 10 and longest[17] <= 17
    assert differ > 0 or command == "grashof"   # the 17-digit file holds more digits


@pytest.mark.parametrize("value", ["0", "18", "x", "-3"])
def test_bad_digits_is_a_usage_error(tmp_path, value):
    proc = run_inprocess("grashof", "--lengths", "28,52,50,72", "--digits", value,
                         "--out", tmp_path)
    assert proc.returncode == 2
    assert "--digits" in proc.stderr


def test_digits_default_is_10(tmp_path):
    proc = run_inprocess("grashof", "--lengths", "28,52,50,72", "--quiet", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    row = read_rows(tmp_path / "grashof.csv")[1]
    theta = row[9]
    assert theta == f"{float(theta):.10g}" and len(theta.replace(".", "")) == 10


# -- JSON --------------------------------------------------------------------------------
@pytest.mark.parametrize("value", [0.1 + 0.2, 1e-300, 123456789.123456789, 2 / 3, 5e-324,
                                   1.7976931348623157e308, -1.0 / 3.0])
def test_json_numbers_are_round_trip_exact(value):
    import numpy as np

    from mechcli.report.jsonout import dumps
    text = dumps("x", None, {"a": value, "b": np.float64(value), "c": [value]}, [])
    r = json.loads(text)["results"]
    assert r["a"] == value and r["b"] == value and r["c"] == [value]
    literal = re.search(r'"a": ([^,\n]+)', text).group(1)
    assert float(literal) == value


def test_json_of_a_run_is_exact(tmp_path):
    proc = run_inprocess("grashof", "--lengths", "28,52,50,72", "--json", "--out", tmp_path)
    r = json.loads(proc.stdout)["results"]
    # K = (180 + θ)/(180 − θ) of the same run's θ, to the last bit of a double's rounding
    assert math.isclose(r["K"], (180 + r["theta_deg"]) / (180 - r["theta_deg"]), rel_tol=4e-16)


# -- concurrent writers ------------------------------------------------------------------
def test_two_processes_writing_one_out_never_corrupt_a_file(tmp_path):
    """Two runs of different problems into the same --out, three rounds: every file is
    whole (one run's complete file) and no temporary file is left behind."""
    out = tmp_path / "shared"
    specs = [CONFIGS / "ch5" / "ex5-3.toml", CONFIGS / "ch5" / "exercise5-1.toml"]
    expect = {}
    for i, spec in enumerate(specs):   # what each run writes alone
        solo = tmp_path / f"solo{i}"
        assert run_inprocess("gear", spec, "--quiet", "--no-plot", "--out", solo).returncode == 0
        expect[i] = {f.name: f.read_bytes() for f in solo.iterdir()}
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    for _ in range(3):
        procs = [subprocess.Popen([sys.executable, "-m", "mechcli", "gear", str(s), "--quiet",
                                   "--no-plot", "--out", str(out)], env=env,
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE)
                 for s in specs]
        for p in procs:
            _, err = p.communicate(timeout=60)
            assert p.returncode == 0, err.decode()
        names = sorted(f.name for f in out.iterdir())
        assert names == sorted(set(expect[0]) | set(expect[1])), names   # no .tmp left
        for f in out.iterdir():
            data = f.read_bytes()
            assert any(data == e.get(f.name) for e in expect.values()), f.name
            if f.suffix == ".csv":
                rows = read_rows(f)
                assert rows and all(len(r) == len(rows[0]) for r in rows)


def test_parallel_writes_use_distinct_temporary_files(tmp_path, monkeypatch):
    from mechcli.report import files
    seen = []
    real = files._temporary

    def spy(path):
        fd, name = real(path)
        seen.append(name)
        return fd, name
    monkeypatch.setattr(files, "_temporary", spy)
    for _ in range(5):
        files.write_text(tmp_path / "a.txt", "x")
    assert len(set(seen)) == 5 and all(Path(s).parent == tmp_path for s in seen)
    assert all(re.fullmatch(r"\.a\.txt\.[0-9a-f]{12}\.tmp", Path(s).name) for s in seen)
    assert [p.name for p in tmp_path.iterdir()] == ["a.txt"]


def test_temporary_files_are_new_private_and_retried_on_a_clash(tmp_path, monkeypatch):
    """files._temporary does what tempfile.mkstemp did: O_EXCL (never an existing file),
    mode 0600 until the rename gives the umask's mode, another name on a clash."""
    from mechcli.report import files
    target = tmp_path / "kin.csv"
    draws = iter([b"\x01" * 6, b"\x01" * 6, b"\x02" * 6])
    monkeypatch.setattr(files.os, "urandom", lambda n: next(draws))
    fd1, name1 = files._temporary(target)
    fd2, name2 = files._temporary(target)          # the first draw clashes: the next taken
    os.close(fd1)
    os.close(fd2)
    assert Path(name1).name == ".kin.csv.010101010101.tmp"
    assert Path(name2).name == ".kin.csv.020202020202.tmp"
    if os.name == "posix":
        assert Path(name1).stat().st_mode & 0o777 == 0o600


# -- mechcli new -------------------------------------------------------------------------
@pytest.mark.parametrize("command", COMMANDS)
def test_every_template_runs_through_its_command(tmp_path, command):
    spec = tmp_path / f"{command}-start.toml"
    proc = run_inprocess("new", command, "-o", spec)
    assert proc.returncode == 0, proc.stderr
    text = spec.read_text(encoding="utf-8")
    assert f'command = "{command}"' in text
    # documented: a comment on (nearly) every key line, with a default or a unit
    keys = [ln for ln in text.splitlines() if re.match(r"^[a-zA-Z_0-9]+\s*=", ln)]
    assert len(keys) >= 5
    assert sum("#" in ln for ln in keys) >= 0.7 * len(keys)
    # the template itself is the proof that every live key is accepted
    proc = run_inprocess(command, spec, "--no-plot", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert (tmp_path / "o" / "report.txt").exists()


def test_new_prints_to_stdout_and_the_text_runs(tmp_path):
    proc = run_inprocess("new", "kin")
    assert proc.returncode == 0 and proc.stdout.startswith("# mechcli kin")
    from importlib.resources import files
    assert proc.stdout == (files("mechcli") / "templates" / "kin.toml").read_text("utf-8")


@pytest.mark.parametrize("command, example", [
    ("kin", "ex1-4"), ("force", "ex2-3"), ("grashof", "ex3-8-case1"), ("cam", "ex7-2"),
    ("gear", "ex5-4"), ("synth", "ex3-8"), ("flywheel", "ex6-4"), ("optimize", "ex7-1")])
def test_new_from_an_example(tmp_path, command, example):
    spec = tmp_path / "s.toml"
    proc = run_inprocess("new", command, "--from", example, "-o", spec)
    assert proc.returncode == 0, proc.stderr
    proc = run_inprocess(command, spec, "--no-plot", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    listed = run_inprocess("new", command, "--list").stdout.split()
    assert example in listed


def test_every_shipped_example_runs_and_matches_configs(tmp_path):
    from mechcli.commands.new import examples
    known = examples()
    assert {c for c, _ in known.values()} == set(COMMANDS)
    for name, (command, text) in known.items():
        # a copy of the config of the same name (so it keeps matching the book)
        assert [text] == [p.read_text("utf-8") for p in CONFIGS.glob(f"*/{name}.toml")], name


@pytest.mark.parametrize("args, words", [
    (("kin", "--from", "ex1-5"), ["ex1-5", "did you mean 'ex1-4'"]),
    (("kin", "--from", "ex4-1"), ["mechcli cam", "ex1-1"]),
    (("atlas",), ["COMMAND"]),      # not a command
])
def test_new_bad_arguments(args, words):
    proc = run_inprocess("new", *args)
    assert proc.returncode == 2
    for w in words:
        assert w in proc.stderr


def test_new_refuses_to_overwrite_without_force(tmp_path):
    spec = tmp_path / "mine.toml"
    spec.write_text("# my work\n")
    proc = run_inprocess("new", "cam", "-o", spec)
    assert proc.returncode == 2 and "--force" in proc.stderr
    assert spec.read_text() == "# my work\n"
    proc = run_inprocess("new", "cam", "-o", spec, "--force")
    assert proc.returncode == 0 and spec.read_text(encoding="utf-8").startswith("# mechcli cam")


# -- homework Makefile -------------------------------------------------------------------
@pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
def test_homework_makefile_has_one_target_per_spec(tmp_path):
    specs = sorted(p.stem for p in (HOMEWORK / "specs").glob("*.toml"))
    assert len(specs) >= 3
    proc = subprocess.run(["make", "-n", "-C", str(HOMEWORK), f"OUT={tmp_path}/out"],
                          capture_output=True, text=True, check=True)
    runs = re.findall(r"^\S+ \$cmd specs/(\S+)\.toml --out " + re.escape(str(tmp_path)),
                      proc.stdout, re.M)
    assert sorted(runs) == specs
    check = subprocess.run(["make", "-n", "-C", str(HOMEWORK), "test"], capture_output=True,
                           text=True, check=True).stdout
    assert "mechcli check specs/" in check


@pytest.mark.parametrize("spec", sorted((HOMEWORK / "specs").glob("*.toml")), ids=lambda p: p.stem)
def test_homework_specs_run(tmp_path, spec):
    command = re.search(r'^command\s*=\s*"(\w+)"', spec.read_text("utf-8"), re.M).group(1)
    proc = run_inprocess(command, spec, "--no-plot", "--quiet", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr


# -- shell completion --------------------------------------------------------------------
def test_bash_completion_through_the_lazy_group():
    env = {**os.environ, "_MECHCLI_COMPLETE": "bash_complete", "COMP_WORDS": "mechcli kin --dig",
           "COMP_CWORD": "2", "PYTHONWARNINGS": "ignore"}
    proc = subprocess.run([sys.executable, "-m", "mechcli"], env=env, capture_output=True,
                          text=True)
    assert "plain,--digits" in proc.stdout.splitlines(), proc.stdout + proc.stderr
    env.update(COMP_WORDS="mechcli gr", COMP_CWORD="1")
    proc = subprocess.run([sys.executable, "-m", "mechcli"], env=env, capture_output=True,
                          text=True)
    assert proc.stdout.splitlines() == ["plain,grashof"]


@pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
def test_homework_makefile_reads_a_single_quoted_or_indented_command(tmp_path):
    # before: `command = 'grashof'` (a TOML literal string) made the Makefile say
    # "no command" although mechcli check runs the spec
    specs = tmp_path / "specs"
    specs.mkdir()
    body = "[fourbar]\nlengths = [28, 52, 50, 72]\n"
    (specs / "single.toml").write_text("command = 'grashof'\n" + body, encoding="utf-8")
    (specs / "indented.toml").write_text('  command = "grashof"  # x\n' + body,
                                         encoding="utf-8")
    proc = subprocess.run(["make", "-s", "-C", str(HOMEWORK), f"SPECS={specs}",
                           f"OUT={tmp_path}/out", f"MECHCLI={sys.executable} -m mechcli"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "out" / "single" / "report.txt").is_file()
    assert (tmp_path / "out" / "indented" / "report.txt").is_file()
