"""``mechcli check``: what an expected value means, exit codes, bad input, JSON and JUnit.

Specs are small grashof four-bars (milliseconds each).  The tolerance rule is
docs/check.md's: the spec's tol/rtol, otherwise half a unit of the last digit
as written in the TOML text.
"""

import json
import xml.etree.ElementTree as ET

import pytest

from mechcli.spec.expected import literal_texts, override_texts, tolerance_of_literal
from tests.conftest import CONFIGS, run_inprocess, write_spec

# 例 3-1's four-bar (100, 150, 170, 110): not Grashof, a double rocker, longest 170
FOURBAR = """command = "grashof"
[fourbar]
lengths = [100, 150, 170, 110]
frame = 4
input = 1
"""


def spec(tmp_path, expected, name="s.toml", head=FOURBAR):
    return write_spec(tmp_path, head + "[expected]\n" + expected, name=name)


def check(*args):
    return run_inprocess("check", *args)


def doc(proc):
    return json.loads(proc.stdout)


@pytest.mark.parametrize("text, tol", [
    ("0.5454", 5e-5), ("1.2300", 5e-5), ("1e-3", 5e-4), ("120", 0.5), ("-0.000000", 5e-7),
    ("1.5E+2", 5.0), ("2.50e-3", 5e-6), ("1_000.5", 0.05), ("+7", 0.5)])
def test_tolerance_is_half_a_unit_of_the_last_written_digit(text, tol):
    assert tolerance_of_literal(text) == pytest.approx(tol, rel=1e-12)


def test_literal_texts_come_from_the_expected_table_only():
    text = ('a = 1.0\n[expected]\nK = 1.2300   # book\nL = { value = 2.50, tol = 0.1 }\n'
            'M = [1.0, 2.50]\n"q" = 3.10\n[other]\nK = 9.9\n')
    assert literal_texts(text) == {"K": "1.2300", "L": "2.50", "M": ["1.0", "2.50"], "q": "3.10"}
    assert override_texts(["expected.K=1.20", "fourbar.frame=4"]) == {"K": "1.20"}


def test_trailing_zeros_tighten_the_tolerance(tmp_path):
    # the result is exactly 170; 169.99 is 0.01 away: within ±0.05 (169.9), not ±0.005 (169.99)
    loose = spec(tmp_path, "longest = 169.9\n", "loose.toml")
    strict = spec(tmp_path, "longest = 169.990\n", "strict.toml")
    d = doc(check(loose, strict, "--json", "-j", "1"))
    held = {s["spec"]: s["checks"][0] for s in d["specs"]}
    assert held[str(loose)]["held"] is False and held[str(loose)]["tol"] == pytest.approx(0.05)
    assert held[str(strict)]["held"] is False and held[str(strict)]["tol"] == pytest.approx(5e-4)
    ok = spec(tmp_path, "longest = 170.00\nshortest = 1e2\n", "ok.toml")
    proc = check(ok, "--json")
    assert proc.returncode == 0, proc.stderr
    checks = doc(proc)["specs"][0]["checks"]
    assert [c["tol"] for c in checks] == pytest.approx([5e-3, 50.0])


def test_integer_and_explicit_tolerances(tmp_path):
    p = spec(tmp_path, "longest = 170\nshortest = { value = 100.4, tol = 0.5 }\n"
             "crank = { value = 1, rel = 0.01 }\n".replace("crank", "longest_rel"))
    proc = check(p, "--json")  # longest_rel names no result: exit 2 with the key
    assert proc.returncode == 2 and "longest_rel" in proc.stderr
    p = spec(tmp_path, "longest = 170\nshortest = { value = 100.4, tol = 0.5 }\n"
             "F = { value = 1.02, rtol = 0.05 }\n".replace("F =", "# F ="))
    d = doc(check(p, "--json"))
    assert [c["tol"] for c in d["specs"][0]["checks"]] == pytest.approx([0.5, 0.5])
    p = spec(tmp_path, "longest = { value = 171, rtol = 0.01 }\n")
    c = doc(check(p, "--json"))["specs"][0]["checks"][0]
    assert c["held"] and c["tol"] == pytest.approx(1.71)
    p = spec(tmp_path, "longest = { value = 0, rtol = 0.1 }\n")
    proc = check(p)
    assert proc.returncode == 2 and "[expected.longest] rtol" in proc.stderr


def test_strings_and_booleans_compare_exactly(tmp_path):
    p = spec(tmp_path, 'type = "double_rocker"\ngrashof = false\n')
    assert check(p, "-q").returncode == 0
    p = spec(tmp_path, 'type = "crank_rocker"\ngrashof = true\n')
    proc = check(p)
    assert proc.returncode == 4
    assert "[expected] type: expected 'crank_rocker' exact, got 'double_rocker'" in proc.stdout
    assert "[expected] grashof: expected true exact, got false" in proc.stdout


def test_lists_compare_element_wise(tmp_path):
    from mechcli.spec.expected import Expected, compare
    exp = {"x": Expected("x", [1.0, 2.0, "a"], [0.05, 0.005, None])}
    assert compare(exp, {"x": [1.04, 2.004, "a"]})[0].held
    bad = compare(exp, {"x": [1.04, 2.006, "a"]})[0]
    assert not bad.held and bad.deviation == pytest.approx(1.2)
    assert not compare(exp, {"x": [1.0, 2.0]})[0].held          # length differs
    assert not compare(exp, {"x": [1.0, 2.0, "b"]})[0].held     # a string differs
    # the spec reader gives per-element tolerances from the text
    p = spec(tmp_path, "longest = [170.0]\n")
    d = doc(check(p, "--json"))  # an array against a scalar result: not met
    c = d["specs"][0]["checks"][0]
    assert c["tol"] == pytest.approx([0.05]) and c["held"] is False


def test_failing_key_exits_4_with_expected_got_and_tolerance(tmp_path):
    good = spec(tmp_path, "longest = 170.00\n", "good.toml")
    bad = spec(tmp_path, "shortest = 100.05\n", "bad.toml")
    proc = check(good, bad, "-j", "1")
    assert proc.returncode == 4
    line = next(ln for ln in proc.stdout.splitlines() if "[expected] shortest" in ln)
    assert f"{bad}: [expected] shortest: expected 100.05 ± 0.005, got 100" in line
    assert "1 passed, 1 failed" in proc.stdout


def test_set_gives_the_digits_of_an_overridden_expected_value(tmp_path):
    p = spec(tmp_path, "longest = 170\n")
    d = doc(check(p, "--json", "--set", "expected.longest=170.0000"))
    assert d["specs"][0]["checks"][0]["tol"] == pytest.approx(5e-5)


@pytest.mark.parametrize("body, where", [
    ("longest = 1979-05-27\n", "[expected] longest"),
    ("longest = { value = 170, tol = 0 }\n", "[expected.longest] tol"),
    ("longest = { value = 170, tol = -1 }\n", "[expected.longest] tol"),
    ("longest = []\n", "[expected] longest"),
    ('longest = { value = "a" }\n', "[expected.longest] value"),
])
def test_bad_expected_values_are_spec_errors(tmp_path, body, where):
    p = spec(tmp_path, body)
    proc = check(p)
    assert proc.returncode == 2
    assert where in proc.stderr, proc.stderr


def test_spec_without_command_and_broken_spec_do_not_stop_the_batch(tmp_path):
    spec(tmp_path, "longest = 170.00\n", "a-good.toml")
    (tmp_path / "b-nocommand.toml").write_text(FOURBAR.replace('command = "grashof"\n', ""))
    (tmp_path / "c-broken.toml").write_text("command = \n")
    (tmp_path / "d-binary.toml").write_bytes(b"\xff\xfe\x00")
    spec(tmp_path, "longest = 170.00\n", "e-good.toml")
    proc = check(tmp_path, "--json", "-j", "1")
    assert proc.returncode == 2
    d = doc(proc)
    status = {s["spec"].rpartition("/")[2]: s["status"] for s in d["specs"]}
    assert status == {"a-good.toml": "passed", "b-nocommand.toml": "error",
                      "c-broken.toml": "error", "d-binary.toml": "error",
                      "e-good.toml": "passed"}
    errors = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(errors) == 3 and all(ln.startswith("mechcli: error: ") for ln in errors)
    assert any("b-nocommand.toml: no top-level command" in ln for ln in errors)
    assert "Traceback" not in proc.stderr


def test_folder_without_specs_and_missing_paths(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    good = spec(tmp_path, "longest = 170.00\n")
    proc = check(empty, tmp_path / "nope.toml", str(tmp_path / "x*.toml"), good)
    assert proc.returncode == 2
    assert f"{empty}: a folder with no *.toml specs" in proc.stderr
    assert "nope.toml: no such file or folder" in proc.stderr
    assert "x*.toml: no file matches this pattern" in proc.stderr
    assert "1 passed" in proc.stdout


def test_failures_win_over_specs_that_cannot_run(tmp_path):
    spec(tmp_path, "shortest = 99.9\n", "bad.toml")
    (tmp_path / "nocmd.toml").write_text("[expected]\nx = 1\n")
    assert check(tmp_path, "-q").returncode == 4


def test_junit_xml_parses_back_with_counts(tmp_path):
    spec(tmp_path, "longest = 170.00\n", "a.toml")
    spec(tmp_path, "shortest = 99.9\nlongest = 169\ntype = 'double_rocker'\n", "b.toml")
    (tmp_path / "c.toml").write_text("title = 'no command'\n")
    junit = tmp_path / "out" / "junit.xml"
    proc = check(tmp_path, "--junit", junit, "-q")
    assert proc.returncode == 4
    suite = ET.parse(junit).getroot().find("testsuite")
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("3", "1", "1")
    cases = {c.get("name").rpartition("/")[2]: c for c in suite.iter("testcase")}
    assert len(cases["a.toml"]) == 0
    assert [f.get("message").split(":")[0] for f in cases["b.toml"].iter("failure")] \
        == ["shortest", "longest"]
    assert cases["b.toml"].get("classname") == "mechcli.grashof"
    error = cases["c.toml"].find("error")
    # c.toml has no `command` key: a spec that cannot run is a JUnit error of exit 2, not a failure
    assert error.get("type") == "exit 2"
    assert "no top-level command" in error.get("message")


def test_json_shape_and_parallel_equals_serial(tmp_path):
    for i, body in enumerate(["longest = 170.00\n", "shortest = 99.9\n",
                              "type = 'double_rocker'\n"]):
        spec(tmp_path, body, f"s{i}.toml")
    cfgs = [CONFIGS / "ch3" / "ex3-1.toml", CONFIGS / "ch5" / "ex5-2.toml"]
    serial = check(tmp_path, *cfgs, "--json", "-j", "1")
    parallel = check(tmp_path, *cfgs, "--json", "-j", "2")
    assert serial.returncode == parallel.returncode == 4
    a, b = doc(serial), doc(parallel)
    assert set(a) >= {"command", "spec", "results", "warnings", "files", "specs", "problems"}
    assert a["command"] == "check"
    assert {k: a["results"][k] for k in ("specs", "passed", "failed", "errors", "checks")} \
        == {"specs": 5, "passed": 4, "failed": 1, "errors": 0, "checks": a["results"]["checks"]}
    assert set(a["specs"][0]) >= {"spec", "command", "status", "exit_code", "checks", "time_s",
                                  "worst_deviation"}
    assert set(a["specs"][0]["checks"][0]) == {"key", "held", "expected", "got", "tol",
                                               "deviation"}

    def strip(d):
        return [{k: v for k, v in s.items() if k != "time_s"} for s in d["specs"]]
    assert strip(a) == strip(b)


def test_plot_writes_into_out_check(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    spec(tmp_path, "longest = 170.00\n", "fb.toml")
    proc = check("fb.toml", "-q", "--plot")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "out" / "check" / "fb" / "report.txt").exists()


# -- review of issue 16: regressions -----------------------------------------------------
def test_literal_texts_of_subtables_inline_tables_and_multiline_strings():
    # an [expected.K] table, a top-level `expected = { … }` and a multi-line string that
    # looks like an [expected] table: the digits as written, not the float's repr
    text = ('expected = { A = 1.2300, B = { value = 2.50, tol = 1 }, s = "a,b", C = [1.0, 2.50] }\n'
            'note = """\n[expected]\nA = 9.9\n"""\n[expected.D]\nvalue = 3.000\ntol = 1\n')
    assert literal_texts(text) == {"A": "1.2300", "B": "2.50", "C": ["1.0", "2.50"],
                                   "D": "3.000"}
    assert override_texts(["expected={ A = 1.2300 }"]) == {"A": "1.2300"}


def test_expected_subtable_keeps_its_trailing_zeros(tmp_path):
    # before: [expected.longest] value = 170.000 was checked within ±0.05 (repr "170.0")
    p = spec(tmp_path, "", head=FOURBAR + "[expected.longest]\nvalue = 170.000\n")
    assert doc(check(p, "--json"))["specs"][0]["checks"][0]["tol"] == pytest.approx(5e-4)
    top = write_spec(tmp_path, "expected = { longest = 170.000 }\n" + FOURBAR, name="top.toml")
    assert doc(check(top, "--json"))["specs"][0]["checks"][0]["tol"] == pytest.approx(5e-4)


def _interrupt_check(args, delay):
    import glob
    import os
    import signal
    import subprocess
    import sys
    import time

    # a temporary folder of its own (TMPDIR), so that other tests running beside it (pytest
    # -n) leave nothing there
    tmp = __import__("tempfile").mkdtemp(prefix="interrupt-")
    before = set(glob.glob(os.path.join(tmp, "mechcli-check-*")))
    proc = subprocess.Popen([sys.executable, "-m", "mechcli", "check", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, env=dict(os.environ, TMPDIR=tmp))
    time.sleep(delay)
    os.killpg(proc.pid, signal.SIGINT)       # Ctrl-C: the whole process group
    try:
        out, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:         # the hang this test is about
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail("mechcli check hung after Ctrl-C")
    time.sleep(0.2)
    after = set(glob.glob(os.path.join(tmp, "mechcli-check-*")))
    return proc.returncode, out, err, after - before


@pytest.mark.parametrize("jobs", ["1", "2", "4"])
def test_ctrl_c_stops_the_whole_batch_cleanly(jobs):
    # before: -j 1 ran on after Ctrl-C (only the running spec was "interrupted"), and with
    # -j N the workers caught SIGINT themselves, sometimes leaving the parent waiting for ever
    specs = [str(CONFIGS)]
    for _ in range(3):
        code, out, err, left = _interrupt_check(specs + ["-j", jobs], 0.5)
        if code == 0:
            continue        # the batch finished before the signal (a very fast machine)
        assert code == 130, err
        assert "Traceback" not in err and "interrupted" in err
        assert "mechcli check:" not in out       # no summary: the batch did not run on
        assert not left
        return


def _slow_spec(path, sets=(), plot=False, out_dir=None, tmp_root=None):
    """A stand-in for batch.run_spec (module level: the workers unpickle it by name)."""
    import time
    from pathlib import Path
    time.sleep(0.2)
    Path(str(path) + ".ran").write_text("", encoding="utf-8")
    return {"spec": str(path), "command": "grashof", "status": "passed", "exit_code": 0,
            "time_s": 0.2, "checks": [], "error": None, "warnings": [], "stderr": ""}


def test_run_batch_stops_its_workers_on_keyboard_interrupt(tmp_path, monkeypatch):
    # before: Ctrl-C in the parent waited for every queued spec (and the workers' own
    # SIGINT handling could leave the pool hung); now the queue is cancelled, the workers
    # terminated and the batch's temporary directory removed
    import glob
    import os
    import signal
    import tempfile

    from mechcli import batch

    specs = [tmp_path / f"s{i}.toml" for i in range(20)]
    monkeypatch.setattr(batch, "run_spec", _slow_spec)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))

    def on_done(result):
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        batch.run_batch(specs, jobs=2, on_done=on_done)
    assert len(glob.glob(str(tmp_path / "*.ran"))) < 10
    assert not glob.glob(os.path.join(str(tmp_path), "mechcli-check-*"))
    # the workers leave Ctrl-C to the parent
    old = signal.getsignal(signal.SIGINT)
    try:
        batch._init_worker()
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, old)
