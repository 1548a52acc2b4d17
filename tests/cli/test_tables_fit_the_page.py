"""Tables fit the terminal and the page (issue 18, item 2): wide tables split into blocks
that repeat the input angle and keep groups of columns whole; ``--columns`` chooses."""

import copy
import io
import json
try:
    import tomllib
except ImportError:      # Python < 3.11
    import tomli as tomllib

import pytest

import mechcli.report.run as run_module
from mechcli.report.table import (REPORT_WIDTH, Block, Report, display_width, kv_layout,
                                  print_rich, render_text, split_block, wrap)
from tests.conftest import CONFIGS, one_line_error, run_inprocess

EX1_2 = CONFIGS / "ch1" / "exercise1-2.toml"   # kin with a traced point: 14 columns
EX2_4 = CONFIGS / "ch2" / "ex2-4.toml"         # force of the shaper: 25 columns


def _table_lines(text):
    return [ln for ln in text.splitlines() if not ln.startswith(("written:", "removed"))]


@pytest.mark.parametrize("columns, blocks", [("80", 3), ("120", 2)])
def test_kin_table_fits_the_terminal(tmp_path, monkeypatch, columns, blocks):
    monkeypatch.setenv("COLUMNS", columns)
    proc = run_inprocess("kin", EX1_2, "--no-plot", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    lines = _table_lines(proc.stdout)
    assert max(display_width(ln) for ln in lines) <= int(columns)
    heads = [ln.strip() for ln in lines if ln.startswith("Results (every 30°")]
    assert heads == [f"Results (every 30°, lengths in mm) ({k}/{blocks})"
                     for k in range(1, blocks + 1)]
    # the input angle starts every block; the first row's ω3 (−10.47 rad/s at θ1 = 0) is there
    assert sum("θ1/(°)" in ln for ln in lines) == blocks
    assert any("0.00" in ln and "-10.4700" in ln for ln in lines)


@pytest.mark.parametrize("spec, command, before", [(EX1_2, "kin", 170), (EX2_4, "force", 241)])
def test_report_txt_tables_fit_100_columns(tmp_path, spec, command, before):
    proc = run_inprocess(command, spec, "-q", "--no-plot", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    widest = max(display_width(ln) for ln in text.splitlines())
    assert widest <= REPORT_WIDTH < before


def test_force_blocks_keep_each_joint_whole(tmp_path):
    proc = run_inprocess("force", EX2_4, "-q", "--no-plot", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8").splitlines()
    headers = [ln.split() for ln in text if ln.startswith("θ1/(°)")]
    assert len(headers) >= 3 and all(h[0] == "θ1/(°)" for h in headers)
    for h in headers:
        joints = {c[:4] for c in h[1:] if c.startswith(("FR", "MR"))}
        for j in joints:   # FR23x, FR23y, FR23 and MR23 of a joint stand in one block
            assert sum(c.startswith(("FR" + j[2:], "MR" + j[2:])) for c in h[1:]) \
                == sum(c.startswith(("FR" + j[2:], "MR" + j[2:]))
                       for hh in headers for c in hh[1:])
    # every column once, in the original order
    flat = [c for h in headers for c in h[1:]]
    assert flat[:2] == ["Mb/(N·m)", "FR16x/(N)"] and len(flat) == len(set(flat)) == 24


def test_split_block_groups_by_unit_order_and_joint():
    headers = ["theta1/°", "theta2/°", "xF/mm", "omega2/rad/s", "vxF/mm/s",
               "alpha2/rad/s²", "axF/mm/s²"]
    rows = [["0.00", "51.3178", "69.6938", "-10.4700", "555.8260", "81.9158", "-11988.5973"]]
    parts = split_block(Block("R", headers, rows), 40)
    assert [p.headers for p in parts] == [
        ["theta1/°", "theta2/°", "xF/mm"], ["theta1/°", "omega2/rad/s", "vxF/mm/s"],
        ["theta1/°", "alpha2/rad/s²", "axF/mm/s²"]]
    assert [p.heading for p in parts] == ["R (1/3)", "R (2/3)", "R (3/3)"]
    assert parts[2].rows == [["0.00", "81.9158", "-11988.5973"]]
    assert split_block(Block("R", headers, rows), 200) == [Block("R", headers, rows)]
    text = render_text(Report("t", [Block("R", headers, rows)]), width=40)
    assert max(map(display_width, text.splitlines())) <= 40


def test_columns_chooses_what_the_tables_show(tmp_path):
    proc = run_inprocess("kin", EX1_2, "-q", "--no-plot", "-o", tmp_path,
                         "--columns", "theta3, ω3")
    assert proc.returncode == 0, proc.stderr
    lines = (tmp_path / "report.txt").read_text(encoding="utf-8").splitlines()
    i = lines.index("Results (every 30°, lengths in mm)")
    assert lines[i + 1].split() == ["θ1/(°)", "θ3/(°)", "ω3/(rad/s)"]
    assert lines[i + 3].split() == ["0.00", "69.5127", "-10.4700"]
    # the CSV keeps every column
    assert (tmp_path / "kin.csv").read_text().splitlines()[0].count(",") == 13


def test_unknown_column_is_a_usage_error(tmp_path):
    proc = run_inprocess("kin", EX1_2, "-q", "--no-plot", "-o", tmp_path, "--columns", "omga3")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "--columns: expected column names of this run's tables (" in line
    assert line.endswith("got 'omga3' (did you mean 'omega3'?)")
    proc = run_inprocess("kin", EX1_2, "--json", "--no-plot", "-o", tmp_path,
                         "--columns", "omga3")
    assert proc.returncode == 2 and json.loads(proc.stdout)["exit_code"] == 2


# -- every config's report, on an 80-column terminal and in report.txt ---------------------

#: configs whose run takes seconds (a differential evolution, an atlas search): their
#: reports are built by the same Report/Block code as the fast configs of their command
#: (optimize: ch7/ex7-1, ex7-2-golden, exercise7-2; synth's atlas: atlas/page-seed-example)
SLOW = {"ch7/exercise7-1.toml", "ch7/exercise7-3.toml", "ch7/exercise7-4.toml",
        "ch7/ex2-1-min-Mb.toml", "atlas/exercise7-3-atlas.toml", "atlas/exercise7-4-atlas.toml"}
EVERY = sorted(p for p in CONFIGS.rglob("*.toml")
               if p.relative_to(CONFIGS).as_posix() not in SLOW)


def _widest(text):
    return max(map(display_width, text.splitlines()), default=0)


@pytest.mark.parametrize("path", EVERY, ids=[p.relative_to(CONFIGS).as_posix() for p in EVERY])
def test_every_report_fits_80_columns_and_100_in_report_txt(path, tmp_path, monkeypatch):
    """One run per config: report.txt within 100 columns, and the same report (with its
    warnings) within 80 columns both as the plain text a pipe gets and as rich tables."""
    seen = []

    def recording(report, width=REPORT_WIDTH):
        seen.append(copy.deepcopy(report))
        return render_text(report, width)

    monkeypatch.setattr(run_module, "render_text", recording)
    command = tomllib.loads(path.read_text(encoding="utf-8"))["command"]
    proc = run_inprocess(command, path, "-q", "--no-plot", "--no-animate", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert _widest((tmp_path / "report.txt").read_text(encoding="utf-8")) <= REPORT_WIDTH
    report = seen[0]
    assert _widest(render_text(report, width=80)) <= 80
    screen = io.StringIO()
    print_rich(report, file=screen, width=80)
    assert _widest(screen.getvalue()) <= 80
    # a narrow terminal: rich never cuts a label or a number ("…"): a key/value block wider
    # than the terminal widens the table, as a wide table does (the text's own "…" stay)
    own = sum(text.count("…") for text in [report.title, *report.notes]
              + [b.heading for b in report.blocks]
              + [c for b in report.blocks for c in [*b.headers, *(x for r in b.rows for x in r)]])
    for narrow in (40, 30):
        screen = io.StringIO()
        print_rich(report, file=screen, width=narrow)
        assert screen.getvalue().count("…") <= own, narrow
    # nothing is lost on the way: the wrapped lines of a key/value row hold all its text
    for block in report.blocks:
        if block.rows and not block.headers:
            for row, cell in zip(block.rows, kv_layout(block.rows, 80)[2]):
                assert ["".join("".join(part).split()) for part in cell] \
                    == ["".join(text.split()) for text in row]


def test_wrap_breaks_prose_where_a_reader_would():
    value = "W (k) = 54.113 mm (k = 4, touching on d = 173.121 mm)"   # 【例 5-3】's span
    assert wrap(value, 60) == [value]
    lines = wrap(value, 30, "  ")
    assert lines == ["W (k) = 54.113 mm (k = 4,", "  touching on d = 173.121 mm)"]
    # never between a symbol and its value, nor a number and its unit
    for width in range(20, 40):
        for line in wrap(value, width, "  "):
            assert not line.rstrip().endswith(("=", "54.113", "173.121"))
            assert display_width(line) <= width
        assert " ".join(ln.strip() for ln in wrap(value, width, "  ")) == value
    # CJK text has no spaces: it is cut by display columns (two per character)
    assert wrap("渐开线起始圆半径" * 2, 10, "  ") == ["渐开线起始", "  圆半径渐", "  开线起始",
                                                      "  圆半径"]


def test_key_value_rows_wrap_their_values_under_the_value_column():
    rows = [["base tangent length over k teeth", "W (k) = 54.113 mm (k = 4, touching on "
             "d = 173.121 mm)"], ["number of teeth", "z = 35"]]
    text = render_text(Report("t", [Block("Spur gear geometry", [], rows)]), width=70)
    lines = text.splitlines()
    i = lines.index("Spur gear geometry")
    assert lines[i + 1] == "  base tangent length over k teeth  W (k) = 54.113 mm (k = 4,"
    # the continuation starts two columns inside the value column
    assert lines[i + 2] == " " * 36 + "  touching on d = 173.121 mm)"
    assert lines[i + 3] == "  number of teeth                   z = 35"
    # a label wraps only when the values would get less than half the width
    lw, vw, cells = kv_layout([["a very long label " * 3, "x = 1"]], 40)
    assert lw + vw + 4 <= 40 and len(cells[0][0]) > 1 and cells[0][1] == ["x = 1"]
