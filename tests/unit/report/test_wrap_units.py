"""Issue 18 item 2 (review): a wrapped line never ends between a number and its unit,
for every unit the reports print, and the rich renderer wraps titles and notes by the
same rule as the plain one."""
import io

import pytest

from mechcli.report.table import Report, print_rich, render_text, wrap


@pytest.mark.parametrize("unit", ["mm", "kW", "rpm", "kg·m²", "MPa", "J", "N·m", "bar", "psi",
                                  "lbf", "rad/s", "°"])
def test_no_line_ends_between_a_number_and_its_unit(unit):
    text = "a" * 20 + f" x = 4.5 {unit} and some more words after it"
    for width in range(28, 40):
        lines = wrap(text, width)
        assert " ".join(lines).split() == text.split()          # no word lost
        assert not any(line.endswith("4.5") for line in lines), (width, lines)


def test_rich_and_plain_wrap_a_long_title_and_note_alike():
    rep = Report(title="【例 1-1】 a four-bar linkage with a very long title that goes on and on, "
                       "l = 54.113 mm, ω1 = 250 rad/s")
    rep.notes.append("a note long enough to wrap at eighty columns with l = 54.113 mm inside "
                     "it and then some more words")
    out = io.StringIO()
    print_rich(rep, file=out, width=80)
    rich_lines = [ln.rstrip() for ln in out.getvalue().splitlines() if ln.strip()]
    plain_lines = [ln.rstrip() for ln in render_text(rep, 80).splitlines() if ln.strip()]
    assert all(len(ln) <= 80 for ln in rich_lines)
    assert not any(ln.endswith(("54.113", "=")) for ln in rich_lines), rich_lines
    assert [ln for ln in rich_lines if "54.113" in ln] == [ln for ln in plain_lines
                                                           if "54.113" in ln]
