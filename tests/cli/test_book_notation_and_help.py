"""One notation, messages about singular geometry, spec conveniences, help and setup
(issue 18, items 8 for kin/force/cam, 9, 10 and 11)."""

import importlib.metadata
import json
import math
import re

import pytest

from mechcli.report.kin import book_title
from tests.conftest import CONFIGS, ROOT, one_line_error, run_cli, run_inprocess, write_spec

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"
EX2_1 = CONFIGS / "ch2" / "ex2-1.toml"
EX4_1 = CONFIGS / "ch4" / "ex4-1.toml"
EX4_3 = CONFIGS / "ch4" / "ex4-3.toml"

#: symbol/(unit), the book's notation of a table header
BOOK_HEADER = re.compile(r"^\S+/\(.+\)$")

PARALLELOGRAM = """\
command = "kin"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 100
l2 = 300
l3 = 100
l4 = 300
[input]
omega1 = 10
step = 1
"""

NO_CRANK = """\
command = "kin"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 240
l2 = 300
l3 = 250
l4 = 200
[input]
omega1 = 10
step = 5
"""


def _report(tmp_path, *args):
    proc = run_inprocess(*args, "--no-plot", "-q", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    return (tmp_path / "report.txt").read_text(encoding="utf-8").splitlines()


def _header_row(lines, first):
    return next(ln.split() for ln in lines if ln.split()[:1] == [first])


# -- item 8: one notation (kin, force, cam) ---------------------------------------------------

def test_kin_headers_and_title_in_the_books_notation(tmp_path):
    lines = _report(tmp_path, "kin", EX1_1)
    assert lines[0] == "【例 1-1】 铰链四杆机构 (four-bar linkage)"
    head = _header_row(lines, "θ1/(°)")
    assert head[:4] == ["θ1/(°)", "θ2/(°)", "θ3/(°)", "γC/(°)"]
    assert all(BOOK_HEADER.match(h) for h in head), head
    assert not any("theta" in ln or "/°" in ln for ln in lines if "/(" in ln)
    extremes = _header_row(lines, "quantity")
    assert extremes == ["quantity", "max", "at/(°)", "min", "at/(°)"]
    rows = [ln.split()[0] for ln in lines if ln.strip().startswith(("ω3/", "α3/"))]
    assert "ω3/(rad/s)" in rows and "α3/(rad/s²)" in rows


def test_kin_headers_in_chinese(tmp_path):
    lines = _report(tmp_path, "kin", EX1_1, "--lang", "zh")
    text = "\n".join(lines)
    assert "曲柄转角 θ1/(°)" in text and "角速度 ω3/(rad/s)" in text
    assert "角加速度 α3/(rad/s²)" in text and "位置/(°)" in text
    assert "/°" not in text.replace("/(°)", "")


def test_force_headers_and_title(tmp_path):
    lines = _report(tmp_path, "force", EX2_1)
    assert lines[0].startswith("【例 2-1】 ")
    head = _header_row(lines, "θ1/(°)")
    assert head[:3] == ["θ1/(°)", "Mb/(N·m)", "FR14x/(N)"]
    assert all(BOOK_HEADER.match(h) for h in head), head
    zh = "\n".join(_report(tmp_path / "zh", "force", EX2_1, "--lang", "zh"))
    assert "曲柄转角 θ1/(°)" in zh and "平衡力矩 Mb/(N·m)" in zh


def test_cam_headers_and_title(tmp_path):
    lines = _report(tmp_path, "cam", EX4_1)
    assert lines[0].startswith("【例 4-1】 ")
    head = _header_row(lines, "δ/(°)")
    assert head[:3] == ["δ/(°)", "s/(mm)", "ds/dδ/(mm/rad)"]
    assert all(BOOK_HEADER.match(h) for h in head), head
    zh = "\n".join(_report(tmp_path / "zh", "cam", EX4_3, "--lang", "zh"))
    assert "凸轮转角 δ/(°)" in zh and "摆角 ψ/(°)" in zh


def test_csv_columns_and_json_keys_are_unchanged(tmp_path):
    proc = run_inprocess("kin", EX1_1, "--json", "--no-plot", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    head = (tmp_path / "kin.csv").read_text().splitlines()[0].split(",")
    assert head[:4] == ["theta1_deg", "theta2_deg", "theta3_deg", "gammaC_deg"]
    assert "theta3_max_deg" in json.loads(proc.stdout)["results"]


@pytest.mark.parametrize("title, expected", [
    ("例 1-1 铰链四杆机构", "【例 1-1】 铰链四杆机构"),
    ("例1-2 曲柄滑块机构", "【例 1-2】 曲柄滑块机构"),
    ("例 2-4", "【例 2-4】"),
    ("【例 5-4】 gear pair", "【例 5-4】 gear pair"),
    ("习题 1-1 铰链四杆机构", "习题 1-1 铰链四杆机构"),
    ("four-bar 例 1-1", "four-bar 例 1-1"),
])
def test_book_title(title, expected):
    assert book_title(title) == expected


# -- item 9: messages about singular geometry -------------------------------------------------

def test_dead_points_merged_rounded_and_grouped(tmp_path):
    spec = write_spec(tmp_path, PARALLELOGRAM)
    proc = run_inprocess("kin", spec, "-o", tmp_path / "o")
    assert proc.returncode == 3
    line = one_line_error(proc)
    assert "dead points at θ1 = 0°, 180° (dyad C)" in line
    assert "e-0" not in line and line.count("dead point") == 1
    assert "partial = true" in line
    # the analysis of the rest: one warning line, and one line of flags
    proc = run_inprocess("kin", spec, "--set", "input.partial=true", "--no-plot",
                         "-o", tmp_path / "p")
    assert proc.returncode == 0, proc.stderr
    warn = [ln for ln in proc.stderr.splitlines() if "dead point" in ln]
    assert warn == [f"mechcli: warning: {spec}: dead points at θ1 = 0°, 180° (dyad C): "
                    "excluded from the analysis"]
    report = (tmp_path / "p" / "report.txt").read_text(encoding="utf-8")
    flags = report.split("Flags\n", 1)[1].split("\n\n", 1)[0].splitlines()
    assert [f.split() for f in flags] == [["dead", "points", "(dyad", "C)", "0°,", "180°"]]
    # the JSON keeps every refined interval
    doc = json.loads(run_inprocess("kin", spec, "--set", "input.partial=true", "--json",
                                   "--no-plot", "-o", tmp_path / "j").stdout)
    assert len(doc["results"]["excluded"]) == 3


def test_cannot_assemble_through_zero_is_one_interval(tmp_path):
    spec = write_spec(tmp_path, NO_CRANK)
    line = one_line_error(run_inprocess("kin", spec, "-o", tmp_path / "o"))
    m = re.search(r"cannot assemble for input angle θ1 = ([\d.]+)° … ([\d.]+)° "
                  r"\(through 0°; dyad C\)", line)
    assert m, line
    # the ends are where B is |l2 - l3| = 50 from D (cosine rule), rounded to 0.0001°
    end = math.degrees(math.acos((240 ** 2 + 200 ** 2 - 50 ** 2) / (2 * 240 * 200)))
    assert float(m.group(2)) == pytest.approx(end, abs=6e-5)
    assert float(m.group(1)) == pytest.approx(360 - end, abs=6e-5)
    proc = run_inprocess("kin", spec, "--set", "input.partial=true", "--no-plot", "-q",
                         "-o", tmp_path / "p")
    assert proc.returncode == 0, proc.stderr
    unbounded = [ln for ln in proc.stderr.splitlines() if "without bound" in ln]
    # the quantities that share their limits of assembly (the gap's ends: docs/accuracy.md
    # §4, not dead points) are one line, in order of the input
    assert len(unbounded) == 2
    assert "omega2, omega3 grow without bound towards the limits of assembly at θ1 = " \
        in unbounded[0]


@pytest.mark.parametrize("stop", ["6", "3.14"])
def test_a_range_that_looks_like_radians_gets_a_hint(tmp_path, stop):
    proc = run_inprocess("kin", EX1_1, "--set", f"input.stop={stop}", "--no-plot", "-q",
                         "-o", tmp_path)
    assert proc.returncode in (0, 2)
    assert "angles are in degrees" in proc.stderr
    assert "stop = 360" in proc.stderr


def test_a_step_error_on_a_radian_like_range_says_degrees(tmp_path):
    proc = run_inprocess("kin", EX1_1, "--set", "input.stop=6.2", "-o", tmp_path)
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[input] step" in line and "angles are in degrees" in line


def test_no_hint_for_a_range_in_degrees(tmp_path):
    proc = run_inprocess("kin", EX1_1, "--set", "input.start=60", "--set", "input.stop=66",
                         "--no-plot", "-q", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "degrees" not in proc.stderr


# -- item 10: --set input.n1 replaces omega1 --------------------------------------------------

def test_set_n1_replaces_the_files_omega1(tmp_path):
    base = json.loads(run_inprocess("kin", EX1_1, "--json", "--no-plot", "--set",
                                    f"input.omega1={2 * math.pi!r}", "-o", tmp_path / "w").stdout)
    proc = run_inprocess("kin", EX1_1, "--json", "--no-plot", "--set", "input.n1=60",
                         "-o", tmp_path / "n")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["results"]["omega3_max_rad_s"] == pytest.approx(
        base["results"]["omega3_max_rad_s"], rel=1e-12)


def test_n1_and_omega1_both_in_the_file_or_both_set_is_an_error(tmp_path):
    spec = write_spec(tmp_path, PARALLELOGRAM.replace("omega1 = 10", "omega1 = 10\nn1 = 60"))
    line = one_line_error(run_inprocess("kin", spec, "-o", tmp_path / "o"))
    assert "[input] n1: expected either omega1 or n1, not both" in line
    line = one_line_error(run_inprocess("kin", EX1_1, "--set", "input.n1=60", "--set",
                                        "input.omega1=3", "-o", tmp_path / "o"))
    assert "either omega1 or n1, not both" in line


def test_set_omega1_replaces_the_files_n1(tmp_path):
    spec = write_spec(tmp_path, PARALLELOGRAM.replace("l3 = 100", "l3 = 250").replace(
        "l1 = 100", "l1 = 50").replace("omega1 = 10", "n1 = 60"))
    proc = run_inprocess("kin", spec, "--json", "--no-plot", "--set", "input.omega1=3",
                         "-o", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr


# -- item 11: help, version, README -----------------------------------------------------------

def test_version_names_the_libraries():
    proc = run_cli("--version")
    assert proc.returncode == 0
    first, second = proc.stdout.splitlines()[:2]
    assert first.startswith("mechcli, version")
    for lib in ("numpy", "scipy", "matplotlib"):
        assert f"{lib} {importlib.metadata.version(lib)}" in second


def test_version_reads_metadata_without_importing_numpy():
    import subprocess
    import sys
    code = ("import sys; from mechcli.cli import main\n"
            "try:\n    main(['--version'])\nexcept SystemExit:\n    pass\n"
            "assert 'numpy' not in sys.modules and 'matplotlib' not in sys.modules")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)
    assert proc.returncode == 0, proc.stderr


def test_help_has_examples_and_exit_codes():
    proc = run_inprocess("--help")
    assert proc.returncode == 0
    assert "Examples:" in proc.stdout and "Exit codes:" in proc.stdout
    for code in ("0 ok", "2 bad", "3 the problem has no solution", "4 mechcli", "130"):
        assert code in " ".join(proc.stdout.split())
    proc = run_inprocess("kin", "--help")
    assert "mechcli kin ex1-1.toml" in proc.stdout and "Exit codes:" in proc.stdout


def test_every_help_example_names_a_shipped_example():
    from mechcli.cli import COMMANDS, EXAMPLES
    assert set(EXAMPLES) <= set(COMMANDS)
    for name, lines in EXAMPLES.items():
        for line in lines:
            m = re.search(r"mechcli new (\w+) --from (\S+)", line)
            if m:
                assert m.group(1) == name
                proc = run_inprocess("new", name, "--list")
                assert proc.returncode == 0 and m.group(2) in proc.stdout, (name, proc.stdout)


def test_readme_installs_in_a_venv_lists_every_command_and_completion():
    from mechcli.cli import COMMANDS
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "python3 -m venv .venv && . .venv/bin/activate && pip install -e '.[cjk,test]'" in text
    synopsis = text.split("```", 2)[1]
    for name in COMMANDS:
        assert re.search(rf"^mechcli {name}\b", synopsis, re.M), name
    assert '_MECHCLI_COMPLETE=bash_source mechcli' in text
    assert "--version" in synopsis


@pytest.mark.parametrize("command, spec, label", [
    ("synth", CONFIGS / "ch3" / "ex3-4.toml", "【例 3-4】 "),
    ("flywheel", CONFIGS / "ch6" / "ex6-1.toml", "【例 6-1】 "),
    ("optimize", CONFIGS / "ch7" / "ex7-2-golden.toml", "【例 7-2】 "),
])
def test_every_command_titles_a_worked_example_in_the_books_brackets(tmp_path, command,
                                                                     spec, label):
    """Titles ``例 3-4 …`` of synth, flywheel and optimize as kin's: ``【例 3-4】 …``."""
    lines = _report(tmp_path, command, spec)
    assert lines[0].startswith(label)
