"""Every user error is one line and an exit code: usage errors, deep TOML, results out of
floating-point range, Ctrl-C (issue 21 items 5, 7, 9, 10)."""

import json
import signal
import subprocess
import sys
import time

import pytest

from tests.conftest import CONFIGS, ROOT, one_line_error, run_inprocess, write_spec


@pytest.mark.parametrize("args, words", [
    (["kin", CONFIGS / "ch1" / "ex1-1.toml", "--lang", "xx"], "'--lang'"),
    (["kin"], "Missing argument 'SPEC.toml'"),
    (["cam", CONFIGS / "ch4" / "ex4-1.toml", "--bogus"], "No such option '--bogus'"),
    (["kinn", "x.toml"], "did you mean 'kin'"),
    (["kin", CONFIGS / "ch1" / "ex1-1.toml", "--digits", "0"], "'--digits'"),
])
def test_usage_error_is_one_line_and_a_json_object(args, words):
    proc = run_inprocess(*args)
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert line.startswith("mechcli: error: ") and words in line
    assert "Usage:" not in proc.stderr
    proc = run_inprocess(*args, "--json")
    assert proc.returncode == 2
    doc = json.loads(proc.stdout)
    assert doc["exit_code"] == 2 and words in doc["error"]


def test_deeply_nested_toml_is_a_spec_error(tmp_path):
    """tomllib recurses once per level: 1,000 nested arrays raise RecursionError (was exit 1)."""
    spec = write_spec(tmp_path, 'command = "kin"\nx = ' + "[" * 1000 + "]" * 1000 + "\n")
    proc = run_inprocess("kin", spec, "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 2
    assert "nesting too deep" in one_line_error(proc)


def test_result_out_of_float_range_is_exit_3_and_writes_nothing(tmp_path):
    """例 5-2 with θ = 1e-320 (a subnormal): the relative residual overflows to inf. The run
    exits 3 naming the result, and none of its files is kept (was: CSV and report written, then
    exit 1 from the JSON writer)."""
    out = tmp_path / "o"
    proc = run_inprocess("gear", CONFIGS / "ch5" / "ex5-2.toml", "--set",
                         "inverse_involute.theta=1e-320", "--json", "--no-plot", "--out", out)
    assert proc.returncode == 3
    assert "out of the range of floating-point numbers" in json.loads(proc.stdout)["error"]
    assert not out.exists() or not any(out.iterdir())


def test_ctrl_c_exits_130_without_traceback(tmp_path):
    """SIGINT during a long run (2,000,001 positions): exit 130 "interrupted" (was exit 1
    "aborted": click turns KeyboardInterrupt into Abort)."""
    proc = subprocess.Popen([sys.executable, "-m", "mechcli", "kin",
                             str(CONFIGS / "ch1" / "ex1-1.toml"), "--set", "input.count=2000001",
                             "--no-plot", "--quiet", "--out", str(tmp_path / "o")],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    if proc.poll() is not None:  # pragma: no cover - a machine fast enough to finish first
        pytest.skip("the run finished before the interrupt")
    proc.send_signal(signal.SIGINT)
    _out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
