"""mechcli in a notebook (mechcli/notebook.py, issue 33 §2): DataFrames with the CSVs'
columns, book-format tables as HTML, the book's 2x2 figure.

The DataFrames are checked against the CSV that ``mechcli kin|cam|gear`` writes for the
same spec (its header, and every value to the CSV's digits); the table and the figure
against hand derivations of the slider-crank (s3 = l1 cos θ1 + √(l2² − (l1 sin θ1 − e)²))
and the four-bar's crank pin (B = l1 e^{iθ1}).
"""

import csv
import math
import subprocess
import sys

import numpy as np
import pytest

import mechcli
from mechcli import notebook
from mechcli.spec.kin import load_kin_spec
from tests.conftest import CONFIGS, ROOT, run_inprocess, write_spec


def _pandas():
    """pandas, or this test is skipped (the DataFrames need it; the rest does not)."""
    return pytest.importorskip("pandas")

#: a non-Grashof four-bar (100 + 200 > 150 + 120) swept through its gaps: two runs of
#: regular positions, joined through 360° = 0° (θ3 passes ±180°), a point P on the coupler
GAPS = """
command = "kin"
title = "non-Grashof four-bar, partial sweep"
units = "mm"

[mechanism]
type = "four_bar"
l1 = 100
l2 = 150
l3 = 120
l4 = 200

[[mechanism.point]]
name = "P"
link = 2
from = "B"
along = 60
normal = 30

[input]
omega1 = 10
start = 0
stop = 360
step = 1
partial = true
"""

KIN_SPECS = ["ch1/ex1-1.toml", "ch1/ex1-2.toml", "ch1/class3-sixbar.toml",
             "ch1/exercise1-15.toml", "ch1/ex1-4.toml", "gaps"]


def _spec(tmp_path, name):
    return write_spec(tmp_path, GAPS, "gaps.toml") if name == "gaps" else CONFIGS / name


def _csv_of(tmp_path, command, spec, name):
    """The CSV *name* that ``mechcli COMMAND SPEC`` writes: (header, rows of text)."""
    out = tmp_path / "out"
    proc = run_inprocess(command, spec, "--out", out, "--no-plot", "--json")
    assert proc.returncode == 0, proc.stderr
    with open(out / name, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def _assert_same(frame, header, rows):
    """Columns equal to the CSV's header, every value equal to its cell at the cell's
    digits (the CSV holds %.{digits}g of the same float: a value and its cell differ by
    less than half a unit of the cell's last digit)."""
    assert list(frame.columns) == header
    values = frame.to_numpy(dtype=float)
    assert values.shape == (len(rows), len(header))
    for i, row in enumerate(rows):
        for j, cell in enumerate(row):
            digits = len(cell.lstrip("-").split("e")[0].replace(".", "").lstrip("0")) or 1
            assert float(f"{values[i, j]:.{digits}g}") == float(cell), (i, header[j], cell)


@pytest.mark.parametrize("name", KIN_SPECS)
def test_kin_frames_are_kin_csv(tmp_path, name):
    """``run_spec(spec).to_frame()`` and ``to_frame(solve(...), linkage)`` at the spec's
    positions are kin.csv: the same columns, rows and values."""
    _pandas()
    spec_path = _spec(tmp_path, name)
    header, rows = _csv_of(tmp_path, "kin", spec_path, "kin.csv")
    _assert_same(mechcli.run_spec(spec_path).to_frame(), header, rows)
    spec = load_kin_spec(spec_path)
    m = mechcli.solve(spec.linkage, spec.input.sweep().inputs(spec.input.q), spec.output.order)
    frame = mechcli.to_frame(m, spec.linkage, unit=spec.header.unit,
                             tracers=[t.name for t in spec.tracers])
    _assert_same(frame, header, rows)


def test_gaps_are_left_out_and_angles_run_on(tmp_path):
    """The partial sweep's frame has kin.csv's rows only (none in the gaps) and θ3 runs
    on through ±180° and from 360° into 0°: θ1 = 0° and 360° are one pose, where the
    first run continues the last, so θ3 is the same number at both ends."""
    _pandas()
    spec = load_kin_spec(write_spec(tmp_path, GAPS, "gaps.toml"))
    m = mechcli.solve(spec.linkage, spec.input.sweep().inputs(spec.input.q))
    frame = mechcli.to_frame(m, spec.linkage, unit="mm")
    assert len(frame) == int(np.count_nonzero(m.regular)) < m.regular.size
    assert "xP_mm" in frame.columns   # a point on a link is traced unless told otherwise
    theta3 = frame["theta3_deg"].to_numpy()
    assert theta3[0] == theta3[-1] and theta3.min() < -180.0 < theta3.max()
    steps = np.abs(np.diff(theta3))
    assert np.count_nonzero(steps > 10.0) == 1   # 1° apart but at the gap, none wrapped


@pytest.mark.parametrize("name, csv_name", [
    ("ch7/ex7-2.toml", "cam.csv"),              # a cam: columns of arrays
    ("ch5/ex5-3.toml", "gear.csv"),             # a spur gear's outline: columns of arrays
    ("ch5/internal-pair.toml", "gear.csv"),     # a pair: CSV text of scalar columns
    ("ch5/ex5-1.toml", "involute.csv"),         # the involute table
])
def test_cam_and_gear_frames_are_their_csv(tmp_path, name, csv_name):
    _pandas()
    command = "cam" if name.startswith("ch7") else "gear"
    header, rows = _csv_of(tmp_path, command, CONFIGS / name, csv_name)
    r = mechcli.run_spec(CONFIGS / name)
    assert r.command == command and r.csv_name == csv_name
    _assert_same(mechcli.to_frame(r), header, rows)


def test_other_csvs_of_a_run(tmp_path):
    _pandas()
    header, rows = _csv_of(tmp_path, "gear", CONFIGS / "ch5/ex5-1.toml", "curve.csv")
    r = mechcli.run_spec(CONFIGS / "ch5/ex5-1.toml")
    _assert_same(r.to_frame("curve.csv"), header, rows)
    assert list(r.to_frame("results.csv").columns) == ["name", "value", "unit"]
    with pytest.raises(KeyError, match="writes no cam.csv; its CSVs: involute.csv"):
        r.to_frame("cam.csv")


def test_without_pandas_the_error_says_what_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)   # import pandas raises ImportError
    sc = mechcli.slider_crank(0.1, 0.3)
    m = mechcli.solve(sc, {1: mechcli.DriverMotion(np.radians([0.0, 90.0]), 1.0)})
    with pytest.raises(ImportError, match=r"pip install 'mechcli\[pandas\]'"):
        mechcli.to_frame(m, sc)


def test_html_tables_carry_the_books_headers():
    r = mechcli.run_spec(CONFIGS / "ch1/ex1-1.toml")
    page = r._repr_html_()
    for head in ("θ1/(°)", "θ2/(°)", "θ3/(°)", "γC/(°)", "ω3/(rad/s)", "α3/(rad/s²)"):
        assert f"<th>{head}</th>" in page
    assert "【例 1-1】" in page and page.count("<table") == len(r.report.blocks)
    assert str(r).splitlines()[0].startswith("【例 1-1】")   # report.txt's text
    cam = mechcli.run_spec(CONFIGS / "ch7/ex7-2.toml")._repr_html_()
    assert "<th>δ/(°)</th>" in cam and "<th>α/(°)</th>" in cam


def test_summary_of_a_motion_is_kins_table():
    """A row every 30°, the book's headers; s3 at θ1 = 90° from the hand derivation
    s3 = √(l2² − (l1 − e)²) = √(0.3² − 0.08²) m = 289.1366 mm."""
    sc = mechcli.slider_crank(0.1, 0.3, e=0.02)
    m = mechcli.solve(sc, {1: mechcli.DriverMotion(np.radians(np.arange(0.0, 361.0)), 10.0)})
    table = mechcli.summary(m, sc, unit="mm")
    block = table.report.blocks[0]
    assert block.headers[:3] == ["θ1/(°)", "θ2/(°)", "s3/(mm)"]
    assert [row[0] for row in block.rows] == [f"{a:.2f}" for a in range(0, 361, 30)]
    row90 = block.rows[3]
    assert row90[2] == f"{1e3 * math.sqrt(0.3 ** 2 - 0.08 ** 2):.4f}" == "289.1366"
    assert "<th>s3/(mm)</th>" in table._repr_html_() and "s3/(mm)" in str(table)


def test_html_is_escaped():
    from mechcli.report.table import Block, Report
    page = notebook.report_html(Report("a <b> & c", [Block("h", ["x<y"], [["-0.000"]])], []))
    assert "a &lt;b&gt; &amp; c" in page and "<th>x&lt;y</th>" in page
    assert ">0.000<" in page   # a zero without its sign, as every table prints it


def _panels(fig):
    """The 2x2 grid's panels (a twin axis shares its panel's place)."""
    return {ax.get_subplotspec().num1 for ax in fig.axes}


def test_plot_of_a_spec_is_kins_figure():
    """Four panels on the Agg canvas; the mechanism drawn at draw_at = 70°, where the
    crank pin is B = l1 (cos 70°, sin 70°) = (34.749, 95.473) mm (l1 = 101.6 mm)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = mechcli.plot(mechcli.run_spec(CONFIGS / "ch1/ex1-1.toml"))
    assert isinstance(fig, Figure) and isinstance(fig.canvas, FigureCanvasAgg)
    assert len(fig.axes) == 4 and _panels(fig) == {0, 1, 2, 3}
    mech = fig.axes[3]
    b = 101.6 * np.exp(1j * math.radians(70.0))
    ends = np.concatenate([np.column_stack(line.get_data()) for line in mech.lines
                           if len(line.get_xdata()) == 2])
    assert np.min(np.abs(ends[:, 0] + 1j * ends[:, 1] - b)) < 1e-9
    assert fig._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_of_a_motion():
    """A slider-crank: its linear quantities on twin axes, still four panels; the
    mechanism at the input nearest draw_at (61° asked, 60° drawn: B = l1 e^{i60°})."""
    sc = mechcli.slider_crank(0.1, 0.3, e=0.02)
    m = mechcli.solve(sc, {1: mechcli.DriverMotion(np.radians(np.arange(0.0, 361.0, 2.0)),
                                                   10.0)})
    fig = mechcli.plot(m, sc, unit="mm", draw_at=math.radians(61.0))
    assert _panels(fig) == {0, 1, 2, 3} and len(fig.axes) > 4
    assert "60" in fig.axes[3].get_title()
    b = 100 * np.exp(1j * math.radians(60.0))
    ends = np.concatenate([np.column_stack(line.get_data()) for line in fig.axes[3].lines
                           if len(line.get_xdata()) == 2])
    assert np.min(np.abs(ends[:, 0] + 1j * ends[:, 1] - b)) < 1e-9


def test_what_cannot_be_named_is_refused(tmp_path):
    sc = mechcli.slider_crank(0.1, 0.3)
    m = mechcli.solve(sc, {1: mechcli.DriverMotion(np.radians([0.0, 90.0]), 1.0)})
    with pytest.raises(TypeError, match=r"to_frame\(m, linkage\)"):
        mechcli.to_frame(m)
    with pytest.raises(ValueError, match="unit must be one of mm, cm, m, in"):
        mechcli.to_frame(m, sc, unit="furlong")
    batch = mechcli.slider_crank(np.array([[0.1], [0.12]]), 0.3)
    mb = mechcli.solve(batch, {1: mechcli.DriverMotion(np.radians([0.0, 90.0]), 1.0)})
    with pytest.raises(ValueError, match=r"one design at a time: .*\(2, 2\)"):
        mechcli.to_frame(mb, batch)
    with pytest.raises(TypeError, match="expected a LinkageMotion"):
        mechcli.to_frame(np.zeros(3), sc)
    with pytest.raises(ValueError, match="plot draws kin results"):
        mechcli.plot(mechcli.run_spec(CONFIGS / "ch7/ex7-2.toml"))
    from mechcli.spec.errors import SpecError
    force = CONFIGS / "ch2" / "ex2-1.toml"
    with pytest.raises(SpecError, match="command"):
        mechcli.run_spec(force)


def test_notebook_names_are_lazy_and_leave_matplotlib_alone():
    """``mechcli.to_frame`` & co. import nothing heavy until used; ``plot`` uses no pyplot
    and leaves matplotlib's settings as they were."""
    code = (
        "import sys, mechcli\n"
        "mechcli.to_frame, mechcli.plot, mechcli.summary, mechcli.run_spec\n"
        "print(sorted(m for m in ('numpy', 'pandas', 'matplotlib') if m in sys.modules))\n"
        "import matplotlib\n"
        "before = dict(matplotlib.rcParams)\n"
        "mechcli.plot(mechcli.run_spec('configs/ch1/ex1-1.toml'))\n"
        "print('matplotlib.pyplot' in sys.modules, dict(matplotlib.rcParams) == before)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.split("\n")
    assert out[:2] == ["[]", "False True"]
