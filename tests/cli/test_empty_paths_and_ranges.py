"""Where a run may write and what a reader refuses (issue 34 §3, §4, §6): an empty
--out, --junit or --scheduler is exit 2 (an empty --out used to write into the working
folder); values a reader must refuse are exit 2, never an internal error; usage errors
and bare `mechcli` are one line or the help."""

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess

EXAMPLES = [("kin", CONFIGS / "ch1" / "ex1-1.toml"), ("force", CONFIGS / "ch2" / "ex2-1.toml"),
            ("grashof", CONFIGS / "ch3" / "ex3-1.toml"), ("synth", CONFIGS / "ch3" / "ex3-2.toml"),
            ("cam", CONFIGS / "ch4" / "ex4-1.toml"), ("gear", CONFIGS / "ch5" / "ex5-3.toml"),
            ("flywheel", CONFIGS / "ch6" / "ex6-1.toml"),
            ("optimize", CONFIGS / "ch7" / "ex7-2.toml")]


@pytest.mark.parametrize("command,spec", EXAMPLES, ids=[c for c, _ in EXAMPLES])
def test_an_empty_out_is_exit_2_and_writes_nothing(command, spec, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    proc = run_inprocess(command, spec, "--out", "", "--no-plot")
    assert proc.returncode == 2
    assert "--out" in one_line_error(proc) and "empty path" in proc.stderr
    assert list(tmp_path.iterdir()) == []


def test_an_empty_junit_or_scheduler_is_exit_2(tmp_path):
    proc = run_inprocess("check", CONFIGS / "ch1" / "ex1-1.toml", "--junit", "")
    assert proc.returncode == 2 and "--junit" in one_line_error(proc)
    proc = run_inprocess("synth", CONFIGS / "atlas" / "small-build.toml", "--scheduler", "",
                         "--out", tmp_path)
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "--scheduler: expected a Dask scheduler address" in line
    assert "--scheduler: --scheduler" not in line


@pytest.mark.parametrize("command,spec,setting,words", [
    ("optimize", CONFIGS / "ch7" / "ex7-1.toml", 'units="furlong"', "units: expected one of"),
    ("flywheel", CONFIGS / "ch6" / "speed-from-energy.toml", "flywheel.omega_mean=1e-300",
     "δ = inf with ωm = 1e-300"),
    ("kin", CONFIGS / "ch1" / "fivebar.toml", "mechanism.driver.1.ratio=1e300",
     "ratio: expected a number in [-10000, 10000]"),
])
def test_values_a_reader_refuses_are_exit_2(command, spec, setting, words, tmp_path):
    proc = run_inprocess(command, spec, "--set", setting, "--out", tmp_path, "--no-plot")
    assert proc.returncode == 2, proc.stderr
    assert words in one_line_error(proc)


def test_usage_errors_are_one_line_and_bare_mechcli_is_the_help():
    proc = run_inprocess("new")
    assert proc.returncode == 2
    assert "Missing argument 'COMMAND'. Choose from: kin, force" in one_line_error(proc)
    proc = run_inprocess()
    assert proc.returncode == 0 and proc.stderr == ""
    assert proc.stdout.startswith("Usage: mechcli") and "Commands:" in proc.stdout
