"""Names are data, never paths (issue 21 items 1-4).

A name from a spec (a point, slide, load or joint name) becomes a file name
(``path_<name>.png``), a CSV column and a JSON key, so the spec layer accepts
only names of 1 to 32 letters (any script), digits and ``_``
(:meth:`mechcli.spec.reader.Section.name`), exit 2 naming the key.  Behind it
:class:`mechcli.report.files.Outputs` refuses any file name that would leave
``--out``, writes CSV headers through the :mod:`csv` module, and turns an OS
error in ``--out`` into exit 2 naming ``--out`` and the OS's reason.
"""

import csv
import io
import os
import sys
import time

import pytest

from mechcli.report.files import OutputPathError, Outputs, write_csv
from mechcli.spec.reader import NAME_MAX, is_name
from tests.conftest import CONFIGS, one_line_error, run_inprocess, write_spec

#: a four-bar (crank 30, coupler 90, rocker 60, frame 100 mm) with a traced point on
#: the coupler: every kind of name of the general form in a few lines
FOUR_BAR = """\
command = "kin"
title = "four-bar with a traced coupler point"
units = "mm"

[mechanism]
type = "general"
frame = 4

[mechanism.ground]
{ground_a} = [0, 0]
D = [100, 0]

[[mechanism.driver]]
type = "crank"
link = 1
pivot = "{pivot}"
point = "B"
length = 30

[[mechanism.dyad]]
type = "RRR"
joint = "C"
points = ["B", "D"]
links = [2, 3]
lengths = [90, 60]

[[mechanism.point]]
name = "{point}"
link = 2
from = "B"
along = 45
normal = 10

[input]
omega1 = 1
start = 0
stop = 360
step = 30
"""

HOSTILE = {
    "parent": "../../../evil",
    "absolute": "/abs/x",
    "comma": "a,b",
    "newline": "a\\nb",          # TOML escape: the name holds a line break
    "empty": "",
    "huge": "x" * 5000,
    "dot": "a.b",
    "space": "a b",
    "quote": "a\\\"b",
    "too_long": "p" * (NAME_MAX + 1),
}


def _spec(tmp_path, point="P", pivot="A", ground_a="A"):
    folder = tmp_path / "spec"
    folder.mkdir(exist_ok=True)
    return write_spec(folder, FOUR_BAR.format(point=point, pivot=pivot, ground_a=ground_a))


def _out(tmp_path):
    """An --out three folders deep, so a write 1-3 levels up stays inside tmp_path."""
    return tmp_path / "a" / "b" / "c" / "out"


def _files(tmp_path):
    return sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_file())


def _assert_nothing_written(tmp_path):
    """Only the spec exists under tmp_path (and nothing appeared at /abs)."""
    assert _files(tmp_path) == [os.path.join("spec", "spec.toml")]
    assert not os.path.exists("/abs/x") and not os.path.exists("/abs/x.png")


# -- the spec layer: one accessor for every name ----------------------------------------
@pytest.mark.parametrize("case", sorted(HOSTILE))
def test_hostile_point_name_is_exit_2_naming_the_key(tmp_path, case):
    spec = _spec(tmp_path, point=HOSTILE[case])
    proc = run_inprocess("kin", spec, "--quiet", "--out", _out(tmp_path))  # plots on
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert "[mechanism.point.0] name: expected a name of 1 to 32 letters" in line
    assert len(line) < 400   # a 5,000-character name is cut in the message
    _assert_nothing_written(tmp_path)


def test_huge_name_fails_fast(tmp_path):
    # the issue: 184 s and 21 GB before failing; the check is the first thing done with it
    spec = _spec(tmp_path, point="x" * 5000)
    t0 = time.perf_counter()
    proc = run_inprocess("kin", spec, "--quiet", "--no-plot", "--out", _out(tmp_path))
    assert proc.returncode == 2
    assert time.perf_counter() - t0 < 20   # generous for a shared machine; was 184 s
    assert "a string of 5,000 characters" in one_line_error(proc)


@pytest.mark.parametrize("where, kwargs, key", [
    ("pivot", {"pivot": "../up"}, "[mechanism.driver.0] pivot"),
    ("ground key", {"ground_a": '"../up"', "pivot": "../up"}, "[mechanism] ground"),
])
def test_hostile_names_everywhere_in_the_general_form(tmp_path, where, kwargs, key):
    spec = _spec(tmp_path, **kwargs)
    proc = run_inprocess("kin", spec, "--quiet", "--out", _out(tmp_path))
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert key in line and "'../up'" in line, line
    _assert_nothing_written(tmp_path)


@pytest.mark.parametrize("sets, key", [
    (['mechanism.dyad.0.points=["B", "../D"]'], "[mechanism.dyad.0] points[1]"),
    (['mechanism.dyad.0.joint="C/"'], "[mechanism.dyad.0] joint"),
    (['mechanism.point.0.from="B,"'], "[mechanism.point.0] from"),
])
def test_hostile_references_are_names_too(tmp_path, sets, key):
    spec = _spec(tmp_path)
    args = [a for s in sets for a in ("--set", s)]
    proc = run_inprocess("kin", spec, "--quiet", "--no-plot", "--out", _out(tmp_path), *args)
    assert proc.returncode == 2, proc.stderr
    assert key in one_line_error(proc)


@pytest.mark.parametrize("value", ['"../../../evil"', '"a,b"', '""', '"/abs/x"'])
def test_hostile_load_name_is_exit_2(tmp_path, value):
    out = _out(tmp_path)
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-4.toml", "--quiet", "--out", out,
                         "--set", f"load.0.name={value}")
    assert proc.returncode == 2, proc.stderr
    assert "[load.0] name: expected a name" in one_line_error(proc)
    assert _files(tmp_path) == []


def test_hostile_slide_name_is_exit_2(tmp_path):
    proc = run_inprocess("kin", CONFIGS / "ch1" / "exercise1-13.toml", "--quiet", "--no-plot",
                         "--out", _out(tmp_path), "--set", 'mechanism.dyad.1.name="E,x"')
    assert proc.returncode == 2, proc.stderr
    assert "[mechanism.dyad.1] name: expected a name" in one_line_error(proc)


@pytest.mark.parametrize("value", ['"../x"', '""'])
def test_hostile_mobility_joint_name_is_exit_2(tmp_path, value):
    proc = run_inprocess("grashof", CONFIGS / "ch3" / "mobility-compound-hinge.toml", "--quiet",
                         "--out", _out(tmp_path), "--set", f"mobility.joint.0.name={value}")
    assert proc.returncode == 2, proc.stderr
    assert "[mobility.joint.0] name: expected a name" in one_line_error(proc)


@pytest.mark.parametrize("name, plots", [("α1", True), ("点甲", False), ("23", False),
                                         ("p" * NAME_MAX, False)])
def test_greek_cjk_and_digit_names_are_accepted(tmp_path, name, plots):
    # CJK without plots: drawing it needs a CJK font, which a test machine may lack
    out = _out(tmp_path)
    spec = _spec(tmp_path, point=name)
    proc = run_inprocess("kin", spec, "--quiet", "--out", out, *([] if plots else ["--no-plot"]))
    assert proc.returncode == 0, proc.stderr
    with open(out / "kin.csv", encoding="utf-8") as fh:
        header = next(csv.reader(fh))
    assert f"x{name}_mm" in header and f"ay{name}_mm_s2" in header
    if plots:
        assert (out / f"path_{name}.png").is_file()


@pytest.mark.parametrize("value, ok", [
    ("E", True), ("s23", True), ("23", True), ("α1", True), ("点甲", True), ("_", True),
    ("", False), ("a b", False), ("a.b", False), ("a-b", False), ("a/b", False),
    ("a\\b", False), ("..", False), ("a\nb", False), ("x" * 33, False), ("١٢", False),
    (3, False), (None, False),
])
def test_the_name_rule(value, ok):
    # letters of any script, ASCII digits (not other scripts' digits) and '_'
    assert is_name(value) is ok


# -- the writer: defence in depth --------------------------------------------------------
@pytest.mark.parametrize("name", ["../evil.png", "../../x.csv", "/abs/x.png", "path_/abs/x.png",
                                  "a/b.csv", "a\\b.csv", "..", ".", "", "a..b", "x\0.csv"])
def test_outputs_refuse_names_that_leave_out(tmp_path, name):
    out = Outputs(tmp_path / "out")
    for write in (lambda: out.text(name, "x"), lambda: out.bytes(name, b"x"),
                  lambda: out.csv(name, [("a", [1.0])])):
        with pytest.raises(OutputPathError, match="^--out: expected plain file names"):
            write()
    assert _files(tmp_path) == []


def test_a_link_in_out_cannot_send_a_write_outside(tmp_path):
    # the run writes into its own new staged folder, so a link planted in --out under
    # an output's name is never written through; the commit replaces it by the file
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "kin.csv").symlink_to(tmp_path / "elsewhere.csv")
    out = Outputs(tmp_path / "out")
    out.text("kin.csv", "x")
    out.manifest({"command": "kin", "spec": "s"})
    assert not (tmp_path / "elsewhere.csv").exists()
    assert not (tmp_path / "out" / "kin.csv").is_symlink()
    assert (tmp_path / "out" / "kin.csv").read_text(encoding="utf-8") == "x"


def test_a_refused_write_removes_the_runs_earlier_files(tmp_path):
    out = Outputs(tmp_path / "out")
    first = out.text("report.txt", "x")
    with pytest.raises(OutputPathError):
        out.text("../x", "y")
    assert not first.exists() and out.files == []


def test_plots_go_through_the_same_check(tmp_path):
    pytest.importorskip("matplotlib")
    from mechcli.report import plotting

    fig = plotting.plt.figure()
    with pytest.raises(OutputPathError):
        plotting.save_png(fig, Outputs(tmp_path / "out"), "../evil.png")
    assert _files(tmp_path) == []


# -- CSV through the csv module ----------------------------------------------------------
def test_csv_header_is_quoted_and_numbers_are_as_before(tmp_path):
    path = write_csv(tmp_path / "t.csv", [("a,b", [1.0, 2.5]), ('q"x', [1e-20, -3.0]),
                                          ("n\nl", [0.0, 1 / 3]), ("x_mm", [7.0, 8.0])],
                     digits=4)
    text = path.read_bytes().decode("utf-8")
    assert text == '"a,b","q""x","n\nl",x_mm\n1,1e-20,0,7\n2.5,-3,0.3333,8\n'
    rows = list(csv.reader(io.StringIO(text)))
    assert rows[0] == ["a,b", 'q"x', "n\nl", "x_mm"]
    assert all(len(r) == 4 for r in rows)


def test_plain_csv_header_is_unquoted(tmp_path):
    # the bytes of a normal header are what ",".join wrote before the csv module
    cols = [("theta1_deg", [0.0]), ("x点甲_mm", [1.0]), ("sE_mm", [2.0])]
    text = write_csv(tmp_path / "t.csv", cols).read_text(encoding="utf-8")
    assert text == "theta1_deg,x点甲_mm,sE_mm\n0,1,2\n"


# -- --out OS errors: exit 2 naming --out and the reason ---------------------------------
def _run_kin(out):
    return run_inprocess("kin", CONFIGS / "ch1" / "ex1-4.toml", "--quiet", "--no-plot",
                         "--out", out)


def test_out_under_a_regular_file(tmp_path):
    (tmp_path / "file").write_text("x")
    proc = _run_kin(tmp_path / "file" / "out")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert line.startswith("mechcli: error: --out: expected a folder where mechcli can write")
    assert "Not a directory" in line or "File exists" in line, line


def test_out_where_the_csv_is_a_folder(tmp_path):
    (tmp_path / "out" / "kin.csv").mkdir(parents=True)
    proc = _run_kin(tmp_path / "out")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert "--out" in line and "kin.csv" in line and "directory" in line.lower(), line
    # no temporary file left behind, the folder untouched
    assert sorted(os.listdir(tmp_path / "out")) == ["kin.csv"]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="needs /proc")
def test_out_where_nothing_may_be_created():
    # /proc takes no new folders, even for root (chmod would not stop root)
    proc = _run_kin("/proc/mechcli-test-out/x")
    assert proc.returncode == 2, proc.stderr
    assert "--out" in one_line_error(proc)


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0,
                    reason="root writes into read-only folders")
def test_out_in_a_read_only_folder(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        proc = _run_kin(ro / "out")
    finally:
        ro.chmod(0o700)
    assert proc.returncode == 2, proc.stderr
    assert "--out" in one_line_error(proc) and "Permission denied" in proc.stderr


def test_out_error_with_json_is_the_json_error_object(tmp_path):
    import json

    (tmp_path / "file").write_text("x")
    proc = run_inprocess("kin", CONFIGS / "ch1" / "ex1-4.toml", "--json", "--no-plot",
                         "--out", tmp_path / "file" / "out")
    assert proc.returncode == 2
    doc = json.loads(proc.stdout)
    assert doc["exit_code"] == 2 and doc["error"].startswith("--out: ")
