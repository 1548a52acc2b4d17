"""No ``-0.000`` in any table (issue 31 §4): a value that rounds to zero at the printed
digits prints as 0 on a terminal, in a pipe and in report.txt; CSV and JSON keep it."""

import io
import re

import pytest

from mechcli.report.table import Block, Report, print_rich, render_text, zero_sign
from tests.conftest import CONFIGS, run_inprocess

#: a number printed as a negative zero, as a reader would spot it
NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0(?:\.0+)?(?![\d.])")


@pytest.mark.parametrize("text, shown", [
    ("-0.000", "0.000"),
    ("-0", "0"),
    ("-0.00e+00", "0.00e+00"),
    ("j, jn = -0.000 mm, -0.000 mm", "j, jn = 0.000 mm, 0.000 mm"),
    ("-0.000mm", "0.000mm"),                   # 【例 5-4】's unit glued to the number
    ("(-0.0, 1.5)", "(0.0, 1.5)"),
    ("-0.0°", "0.0°"),
    # not zero, or not a number's sign: unchanged
    ("-0.001", "-0.001"),
    ("-0.0005", "-0.0005"),
    ("-0.5", "-0.5"),
    ("-10.000", "-10.000"),
    ("例 5-0", "例 5-0"),
    ("x-0.000", "x-0.000"),
    ("l2-0", "l2-0"),
])
def test_zero_sign_drops_only_the_sign_of_a_printed_zero(text, shown):
    assert zero_sign(text) == shown


def test_every_table_renderer_prints_a_negative_zero_as_zero():
    rep = Report("-0 stays in the user's title",
                 [Block("at e = -0.00 mm", ["s/(mm)", "v/(mm/s)"], [["-0.000", "-0.001"],
                                                                    ["1.000", "-0.000"]]),
                  Block("pair", rows=[["j, jn", "-0.000 mm, -0.000 mm"]])],
                 ["backlash -0.000 mm"])
    screen = io.StringIO()
    print_rich(rep, file=screen, width=80)
    for text in (render_text(rep), screen.getvalue()):
        body = text.split("\n", 1)[1]
        assert not NEGATIVE_ZERO.search(body), body
        assert "-0.001" in body and "0.000 mm, 0.000 mm" in body and "e = 0.00 mm" in body
        assert text.startswith("-0 stays")
    assert rep.blocks[0].rows[0][0] == "-0.000"     # the report itself is left as it was


#: the gear configs whose tables printed -0.000 (backlash j, jn of a standard pair at the
#: standard centre distance; xn2 = 0 of helical-centre-distance)
PRINTED_NEGATIVE_ZERO = ["exercise5-2", "exercise5-5", "loads-spur", "shift-equal-strength",
                         "shift-helical-centre-distance"]


@pytest.mark.parametrize("name", PRINTED_NEGATIVE_ZERO)
def test_gear_tables_print_no_negative_zero(name, tmp_path):
    proc = run_inprocess("gear", CONFIGS / "ch5" / f"{name}.toml", "--no-plot", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    for text in (proc.stdout, (tmp_path / "report.txt").read_text(encoding="utf-8")):
        assert not NEGATIVE_ZERO.search(text), NEGATIVE_ZERO.search(text)


def test_the_zero_backlash_of_exercise_5_2_prints_as_zero_and_stays_a_number(tmp_path):
    # 习题 5-2: z1 = 20, z2 = 32, m = 3 at a' = 78 mm = m (z1 + z2) / 2, the standard
    # centre distance, where standard teeth mesh without backlash (j = jn = 0 by hand)
    spec = CONFIGS / "ch5" / "exercise5-2.toml"
    proc = run_inprocess("gear", spec, "--no-plot", "-o", tmp_path)
    assert "j, jn = 0.000 mm, 0.000 mm" in proc.stdout
    import json
    doc = json.loads(run_inprocess("gear", spec, "--no-plot", "--json", "-o",
                                   tmp_path / "j").stdout)
    # the JSON value is the computed one (round-off of 1e-15 mm, either sign), not a text
    assert isinstance(doc["results"]["backlash_mm"], float)
    assert abs(doc["results"]["backlash_mm"]) < 1e-9
