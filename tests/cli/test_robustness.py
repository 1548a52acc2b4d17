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
    # click's own words ("No such option '--bogus'", "No such option: --bogus" before 8.2)
    (["cam", CONFIGS / "ch4" / "ex4-1.toml", "--bogus"], "No such option"),
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
    """SIGINT during a long run (600,001 positions): exit 130 "interrupted" (was exit 1
    "aborted": click turns KeyboardInterrupt into Abort)."""
    proc = subprocess.Popen([sys.executable, "-m", "mechcli", "kin",
                             str(CONFIGS / "ch1" / "ex1-1.toml"), "--set", "input.count=600001",
                             "--no-plot", "--quiet", "--out", str(tmp_path / "o")],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    # the run takes about 3.5 s here (600,001 positions, measured 2026-11-23): still running
    assert proc.poll() is None, "the run finished before the interrupt"
    proc.send_signal(signal.SIGINT)
    _out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err


@pytest.mark.parametrize("args, key", [
    # a step that underflows to 0 rad (5e-324° × π/180): was ZeroDivisionError, exit 1
    (["kin", CONFIGS / "ch1" / "ex1-2.toml", "--set", "input.step=5e-324"], "[input] step"),
    # force's table step below the sweep over its position limit: was ZeroDivisionError
    (["force", CONFIGS / "ch2" / "exercise2-8.toml", "--set", "output.table_step=5e-324"],
     "[output] table_step"),
    # a module whose metres underflow to 0 (5e-324 mm): was ZeroDivisionError
    (["gear", CONFIGS / "ch5" / "exercise5-2.toml", "--set", "pair.m=5e-324"], "[pair] m"),
    # a rise of 5e-324 deg (0 rad): was ValueError "segment spans must be positive", exit 1
    (["cam", CONFIGS / "ch4" / "ex4-2.toml", "--set", "motion.segments.0.angle=5e-324"],
     "[motion.segments.0] angle"),
    # an allowed pressure angle of 1e-300 deg: the sizing overflowed (OverflowError, exit 1)
    (["cam", CONFIGS / "ch4" / "exercise4-2.toml", "--set", "limits.alpha_rise=1e-300"],
     "[limits] alpha_rise"),
    # a dyad length of 1e300 mm: was a numpy RuntimeWarning (invalid value in subtract)
    (["force", CONFIGS / "ch2" / "exercise2-8.toml", "--set",
      "mechanism.dyad.0.lengths.0=1e300"], "[mechanism.dyad.0] lengths"),
])
def test_extreme_numbers_found_by_the_fuzzer_are_spec_errors(args, key, tmp_path):
    proc = run_inprocess(*args, "--no-plot", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 2
    assert key in one_line_error(proc)


@pytest.mark.parametrize("value", ["a\nb", "a;b\r", "a\u2028b"])
def test_a_value_with_a_line_break_is_echoed_on_one_line(value, tmp_path):
    """units = "a<newline>b" was echoed raw: the one-line error became two lines."""
    spec = write_spec(tmp_path, (CONFIGS / "ch1" / "ex1-1.toml").read_text(encoding="utf-8")
                      .replace('units = "mm"', "units = " + json.dumps(value)))
    proc = run_inprocess("kin", spec, "--no-plot", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 2
    assert "units" in one_line_error(proc)


def test_ratio_design_with_fewer_teeth_than_one_per_gear_is_exit_3(tmp_path):
    """习题 5-2 with m = 1, a' = 1 mm: z1 + z2 = 2 a'/m = 2, z1 = 2/(1 + 1.6) < 1; naming the
    nearest ratios divided by z1 = 0 (ZeroDivisionError, exit 1; found by the fuzzer)."""
    proc = run_inprocess("gear", CONFIGS / "ch5" / "exercise5-2.toml", "--set", "pair.m=1",
                         "--set", "pair.a_w=1", "--no-plot", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 3
    assert "at least one tooth on each gear" in one_line_error(proc)
