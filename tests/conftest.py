import os
import subprocess
import sys
from pathlib import Path

import pytest

try:        # CI runs the property tests on fixed examples: a red CI is a real defect
    from hypothesis import settings as _hsettings
    _hsettings.register_profile("ci", derandomize=True, print_blob=True)
    if os.environ.get("CI"):
        _hsettings.load_profile("ci")
except ImportError:     # hypothesis is a test extra
    pass

ROOT = Path(__file__).resolve().parent.parent
CONFIGS = ROOT / "configs"

os.environ.setdefault("MPLBACKEND", "Agg")


def run_cli(*args, cwd=None):
    """Run ``python -m mechcli ARGS`` in a subprocess; return CompletedProcess."""
    return subprocess.run([sys.executable, "-m", "mechcli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd or ROOT, timeout=300)


def load_module(path):
    """The Python file *path* (a ``tests/reference`` script, a ``docs`` generator) as a
    module, without it being a package: what the tests of those scripts import."""
    import importlib.util

    path = Path(path)
    spec = importlib.util.spec_from_file_location(path.stem, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def write_spec(tmp_path, text, name="spec.toml", encoding="utf-8"):
    """Write a spec file for a test and return its path."""
    p = tmp_path / name
    p.write_text(text, encoding=encoding)
    return p


def one_line_error(proc):
    """The single stderr line of a failed run (no traceback, nothing else)."""
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, proc.stderr
    assert "Traceback" not in proc.stderr
    return lines[0]


@pytest.fixture
def cli():
    return run_cli


def run_inprocess(*args):
    """Run ``mechcli ARGS`` in this process (``mechcli.cli.main``), much faster
    than :func:`run_cli`; return a CompletedProcess (exit code, stdout, stderr).

    Use it for runs that print no rich table (``--quiet`` or ``--json``).
    """
    import contextlib
    import io

    from mechcli.cli import main

    argv = [str(a) for a in args]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            main(argv)
            code = 0
        except SystemExit as exc:
            code = exc.code
    return subprocess.CompletedProcess(["mechcli", *argv], code, out.getvalue(), err.getvalue())


def run_json(command, *args):
    """``mechcli COMMAND ARGS --json --no-plot`` in this process; the JSON document of a
    run that must succeed (exit 0)."""
    import json

    proc = run_inprocess(command, *args, "--json", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.fixture(autouse=True)
def _close_figures():
    """In-process runs share one matplotlib state: close every figure a test left open
    (a run that fails half-way may not reach ``plt.close``), so no test meets the
    "More than 20 figures" RuntimeWarning (an error under ``filterwarnings = error``)."""
    yield
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")


#: the modules whose tests take most of the suite's time (figures, the fuzzer, every
#: config through every reader, schema learning, the optimizer, streams past memory):
#: marked ``slow`` so that ``pytest -m "not slow"`` is a quick inner loop (README's test
#: command still runs everything).  Measured with ``pytest --durations=0``.
SLOW_MODULES = {
    "test_figure_text",
    "test_fuzz_configs", "test_force_plots", "test_configs", "test_schema", "test_new_types",
    "test_axis_label_style", "test_unknown_keys", "test_tables_fit_the_page",
    "test_flywheel_course_problems", "test_chinese_figures", "test_pictures_figures",
    "test_speed_streaming", "test_interrupted_runs", "test_cjk_extra", "test_batches",
    "test_triad_accuracy", "test_flywheel_cli", "test_optimize_joints", "test_gear_loads",
    "test_cam_properties", "test_optimize_plots", "test_joints_properties", "test_atlas_cli",
    "test_optimize_cli", "test_cad_export", "test_accuracy_estimate", "test_kin_plots",
    "test_cam_plots", "test_gear_plots", "test_synth_plots", "test_flywheel_plots",
    "test_plain_twins", "test_kin_extremes", "test_flywheel_props", "test_atlas",
    "test_progress_and_pipes", "test_check", "test_flywheel_motion", "test_outputs_never_stale",
    "test_engine_loads", "test_grashof_property", "test_notebook", "test_clipped_curve_notice",
    "test_synth_quick_return_props", "test_outputs_stay", "test_own_problem_doc",
    "test_newton_group_cases", "test_newton_group",
}


def pytest_collection_modifyitems(config, items):
    slow = pytest.mark.slow
    for item in items:
        if item.module.__name__.rsplit(".", 1)[-1] in SLOW_MODULES:
            item.add_marker(slow)
