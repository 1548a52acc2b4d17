"""One notation in gear and grashof (issue 18 item 8), and options that do nothing for a
form of grashof (item 11): book-notation headers that fit 80 columns, units with a space,
【例 N-M】 titles, JSON names with their unit beside the old names (aliases for one release),
and the results of a gear in results.csv / gear.csv."""

import csv
import io
import json
import re
import unicodedata

import pytest

from tests.conftest import CONFIGS, run_inprocess, write_spec

CH3, CH5 = CONFIGS / "ch3", CONFIGS / "ch5"
#: symbol/(unit), the book's notation of a table header (a Chinese name may come first)
BOOK_HEADER = re.compile(r"^(\S+ )?\S+/\(.+\)$")


def _width(text):
    return sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in text)


def _json(*args):
    proc = run_inprocess(*args, "--json")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def _table_lines(text, first):
    """The lines of every table whose header starts with *first*: header, rule, rows."""
    lines, out = text.splitlines(), []
    for i, ln in enumerate(lines):
        if ln.lstrip().startswith(first) and i + 1 < len(lines) and set(lines[i + 1]) <= {"-", " "}:
            j = i
            while j < len(lines) and lines[j].strip() and not lines[j].startswith("written"):
                out.append(lines[j])
                j += 1
    return out


# -- gear: headers, units, titles ---------------------------------------------------------

@pytest.mark.parametrize("lang, first", [("en", "α/(°)"), ("zh", "压力角 α/(°)")])
def test_gear_involute_table_fits_80_columns_in_the_books_notation(tmp_path, monkeypatch,
                                                                   lang, first):
    monkeypatch.setenv("COLUMNS", "80")
    proc = run_inprocess("gear", CH5 / "ex5-1.toml", "--no-plot", "--lang", lang,
                         "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    table = _table_lines(proc.stdout, first)
    # 表 5-1: 21 rows of 10 columns, split in two blocks that each repeat α/(°)
    assert len(table) == 2 * (2 + 21)
    assert max(map(_width, table)) <= 80
    headers = [ln for ln in table if ln.lstrip().startswith(first)]
    assert len(headers) == 2
    assert all(re.split(r"\s{2,}", h.strip())[0] == first for h in headers)
    assert all(BOOK_HEADER.match(first) for h in headers)
    report = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert max(map(_width, _table_lines(report, first))) <= 100
    assert "deg " not in report and "度 " not in report


GEAR_SPECS = sorted(CH5.glob("*.toml"))


@pytest.mark.parametrize("lang", ["en", "zh"])
@pytest.mark.parametrize("spec", GEAR_SPECS, ids=[p.stem for p in GEAR_SPECS])
def test_every_gear_report_fits_80_columns_and_report_txt_100(tmp_path, monkeypatch, spec,
                                                              lang):
    """Measurement rows (W (k) = … (k = 4, touching on d = …)), the pair's long rows and
    long titles wrap, their continuation indented under the value (before: up to 182
    columns on screen, 229 in report.txt)."""
    from mechcli.report.table import display_width

    monkeypatch.setenv("COLUMNS", "80")
    proc = run_inprocess("gear", spec, "--no-plot", "--lang", lang, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    screen = [ln for ln in proc.stdout.splitlines() if not ln.startswith("written:")]
    assert max(map(display_width, screen)) <= 80
    report = (tmp_path / "report.txt").read_text(encoding="utf-8").splitlines()
    assert max(map(display_width, report)) <= 100
    if spec.stem == "ex5-3":
        # 【例 5-3】's span W over k = 4 teeth (W = 54.113 mm, printed in the book): the
        # value goes on under its value column, two columns further in
        i = next(i for i, ln in enumerate(screen) if "W (k) = 54.113 mm" in ln)
        col = display_width(screen[i][:screen[i].index("W (k)")])
        on = "touching on" if lang == "en" else "切点在"
        assert screen[i + 1] == " " * (col + 2) + f"{on} d = 173.121 mm)"


def test_gear_units_with_a_space_and_greek_symbols(tmp_path):
    run_inprocess("gear", CH5 / "ex5-3.toml", "--no-plot", "-q", "-o", tmp_path)
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    # 【例 5-3】: d = m z = 175 mm, da = d + 2m = 185 mm (by hand)
    assert "d = 175.000 mm" in text and "da = 185.000 mm" in text
    assert not re.search(r"\d(mm|cm|in)\b", text), "a unit glued to its number"
    run_inprocess("gear", CH5 / "ex5-4.toml", "--no-plot", "-q", "-o", tmp_path / "p")
    pair = (tmp_path / "p" / "report.txt").read_text(encoding="utf-8")
    # 【例 5-4】 prints aT = 255.000mm, alpha = 22.888°, epsilon = 0.765
    for line in ("a' = 255.000 mm", "α' = 22.888°", "εα = 0.765", "αa1 = 31.321°"):
        assert line in pair
    assert not re.search(r"\b(aT|alpha\d?|epsilon) =", pair)


def test_gear_title_in_the_books_brackets(tmp_path):
    spec = write_spec(tmp_path, 'command = "gear"\ntitle = "例 5-3 标准齿轮"\nunits = "mm"\n'
                      "[spur]\nz = 35\nm = 5\n")
    run_inprocess("gear", spec, "--no-plot", "-q", "-o", tmp_path / "o")
    assert (tmp_path / "o" / "report.txt").read_text(encoding="utf-8").startswith(
        "【例 5-3】 标准齿轮\n")


# -- gear: names with units, old names as aliases -------------------------------------------

#: config, old name -> new name, the value (where it comes from)
RENAMED = [
    ("ex5-3", {"d": "d_mm", "db": "db_mm", "da": "da_mm", "s_a": "s_a_mm", "W": "W_mm",
               "M": "M_mm", "r_form": "r_form_mm", "s_chord": "s_chord_mm", "p": "p_mm",
               "m": "m_mm"}, ("d_mm", 175.0)),                   # m z = 5 × 35
    ("ex5-4", {"a": "a_mm", "a_w": "a_w_mm", "d1": "d1_mm", "db2": "db2_mm", "dw1": "dw1_mm",
               "clearance1": "clearance1_mm"}, ("a_mm", 250.0)),  # 【例 5-4】 a = 250.000mm
    ("exercise5-5", {"a_w_2": "a_w_mm_2", "dw1_2": "dw1_mm_2", "backlash_2": "backlash_mm_2"},
     ("a_w_mm_2", 154.0)),                                          # 习题 5-5's second a'
    ("exercise5-7", {"mt": "mt_mm", "W1": "W1_mm", "b_min1": "b_min1_mm"}, None),
    ("exercise5-8", {"px": "px_mm", "lead": "lead_mm", "mx1": "mx1_mm"}, ("d2_mm", 280.0)),
    ("exercise5-9", {"R": "R_mm", "da1": "da1_mm"}, ("d1_mm", 100.0)),  # m z1 = 5 × 20
    ("gear-cut", {"rb": "rb_mm", "r_form_3": "r_form_mm_3", "s_a_2": "s_a_mm_2",
                  "undercut_depth": "undercut_depth_mm"}, ("r_mm", 45.0)),  # m z / 2
    ("ex5-1", {"rb": "rb_mm", "r_max": "r_max_mm"}, ("rb_mm", 50.0)),  # 【例 5-1】 rb = 50
]


@pytest.mark.parametrize("name, renamed, value", RENAMED)
def test_gear_json_names_with_units_and_the_old_names_equal(tmp_path, name, renamed, value):
    r = _json("gear", CH5 / f"{name}.toml", "--no-plot", "-o", tmp_path)["results"]
    for old, new in renamed.items():
        assert old in r and new in r, (old, new)
        assert r[old] == r[new]
    # the new names come first, the aliases after them
    keys = list(r)
    assert max(keys.index(n) for n in renamed.values()) < min(keys.index(o) for o in renamed)
    if value:
        assert r[value[0]] == pytest.approx(value[1], rel=1e-12)
    # angles keep their names; numbers without unit keep theirs
    assert not any(k.endswith("_deg_mm") or k.endswith("_mm_mm") for k in r)


def test_gear_names_carry_the_specs_unit(tmp_path):
    spec = write_spec(tmp_path, 'command = "gear"\nunits = "cm"\n[spur]\nz = 35\nm = 0.5\n')
    r = _json("gear", spec, "--no-plot", "-o", tmp_path / "o")["results"]
    assert r["d_cm"] == r["d"] == pytest.approx(17.5, rel=1e-12)   # 0.5 cm × 35
    assert "d_mm" not in r and r["z"] == 35 and "z_cm" not in r


def test_expected_blocks_with_old_names_still_pass(tmp_path):
    # configs/ch5/ex5-3.toml checks d, db, da ... by their old names
    text = (CH5 / "ex5-3.toml").read_text(encoding="utf-8")
    assert re.search(r"^db = ", text, re.M)
    proc = run_inprocess("gear", CH5 / "ex5-3.toml", "--no-plot", "-q", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr


# -- gear: results.csv and gear.csv -----------------------------------------------------------

def test_results_csv_holds_every_result_of_a_spur_gear(tmp_path):
    r = _json("gear", CH5 / "ex5-3.toml", "--no-plot", "-o", tmp_path)["results"]
    rows = list(csv.DictReader(io.StringIO((tmp_path / "results.csv").read_text())))
    got = {row["name"]: row for row in rows}
    assert len(rows) >= 40
    aliases = {"d", "db", "da", "W", "M", "s_a"}
    assert not aliases & set(got), "aliases are not repeated in results.csv"
    for name, row in got.items():
        v = r[name]
        if isinstance(v, bool):
            assert row["value"] == ("true" if v else "false")
        elif isinstance(v, (int, float)):
            assert float(row["value"]) == pytest.approx(v, rel=1e-9, abs=1e-12)
    assert (got["d_mm"]["unit"], got["alpha_a_deg"]["unit"], got["z"]["unit"]) == \
        ("mm", "deg", "")
    # every scalar result of the JSON (but the aliases) is there
    scalars = {k for k, v in r.items() if isinstance(v, (int, float, str, bool))}
    assert scalars - set(got) <= {k for k in r if f"{k}_mm" in r}
    # the outline stays in gear.csv
    assert (tmp_path / "gear.csv").read_text().startswith("x_mm,y_mm\n")


def test_pair_gear_csv_holds_every_result_one_row_per_mounting(tmp_path):
    r = _json("gear", CH5 / "exercise5-5.toml", "--no-plot", "-o", tmp_path)["results"]
    rows = list(csv.DictReader(io.StringIO((tmp_path / "gear.csv").read_text())))
    head = list(rows[0])
    assert head[:8] == ["a_w_mm", "alpha_w_deg", "dw1_mm", "dw2_mm", "epsilon_alpha",
                        "backlash_mm", "clearance1_mm", "clearance2_mm"]
    assert len(head) >= 40 and len(rows) == 2
    # 习题 5-5: a' = 150 mm and 154 mm; d1 = m z1 = 100 mm for both
    assert [float(x["a_w_mm"]) for x in rows] == [150.0, 154.0]
    assert [float(x["d1_mm"]) for x in rows] == [100.0, 100.0]
    assert float(rows[1]["dw1_mm"]) == pytest.approx(r["dw1_mm_2"], rel=1e-9)
    assert float(rows[0]["dw1_mm"]) == pytest.approx(r["dw1_mm"], rel=1e-9)
    assert not any(h.endswith("_2") for h in head)


@pytest.mark.parametrize("name, least", [("exercise5-7", 40), ("exercise5-8", 15),
                                         ("exercise5-9", 17)])
def test_drive_gear_csv_holds_every_numeric_result(tmp_path, name, least):
    r = _json("gear", CH5 / f"{name}.toml", "--no-plot", "-o", tmp_path)["results"]
    rows = list(csv.DictReader(io.StringIO((tmp_path / "gear.csv").read_text())))
    assert len(rows) == 1 and len(rows[0]) >= least
    for k, v in rows[0].items():
        assert float(v) == pytest.approx(float(r[k]), rel=1e-9, abs=1e-12), k


# -- grashof: headers, units, titles, names -------------------------------------------------

@pytest.mark.parametrize("lang", ["en", "zh"])
def test_grashof_headers_at_80_columns(tmp_path, monkeypatch, lang):
    monkeypatch.setenv("COLUMNS", "80")
    proc = run_inprocess("grashof", CH3 / "exercise3-1.toml", "--no-plot", "--lang", lang,
                         "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    first = "θ1/(°)" if lang == "en" else "原动件转角 θ1/(°)"
    table = _table_lines(proc.stdout, first)
    assert table and max(map(_width, table)) <= 80
    header = [h.strip() for h in re.split(r"\s{2,}", table[0].strip())]
    assert header == ([first, "γ/(°)"] if lang == "en" else [first, "传动角 γ/(°)"])
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "[°]" not in text and "(°)" in text and not re.search(r"\[(mm|cm|m|in)\]", text)


def test_grashof_labels_title_and_ranges(tmp_path):
    run_inprocess("grashof", CH3 / "ex3-1.toml", "--no-plot", "-q", "-o", tmp_path)
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert text.startswith("【例 3-1】 ")   # the spec's title is "例 3-1 …"
    assert "s + l − (p + q)/(mm)" in text and "minimum transmission angle γmin/(°)" in text
    run_inprocess("grashof", CH3 / "hrones-nelson-ranges.toml", "--no-plot", "-q",
                  "-o", tmp_path / "r")
    ranges = (tmp_path / "r" / "report.txt").read_text(encoding="utf-8")
    assert "range/(" in ranges and "double crank" in ranges


def test_grashof_json_lengths_with_units_and_aliases(tmp_path):
    r = _json("grashof", "--lengths", "28,52,50,72", "-o", tmp_path / "a")["results"]
    # the lengths given: longest 72, shortest 28, s + l - p - q = 100 - 102 = -2
    assert r["longest_mm"] == r["longest"] == 72.0 and r["shortest_mm"] == r["shortest"] == 28.0
    assert r["excess_mm"] == r["excess"] == pytest.approx(-2.0, abs=1e-12)
    r = _json("grashof", "--lengths", "30,60", "--offset", "10", "--units", "cm",
              "-o", tmp_path / "b")["results"]
    # stroke = sqrt(90² - 10²) - sqrt(30² - 10²) = 89.4427 - 28.2843 (by hand)
    assert r["stroke_cm"] == r["stroke"] == pytest.approx(61.158448, abs=5e-7)
    assert r["x_ext_cm"] == r["x_ext"] and r["dead_points_slider_driving_cm"] == \
        r["dead_points_slider_driving"]
    r = _json("grashof", "--lengths", "10,21,19,20,5", "-o", tmp_path / "c")["results"]
    assert r["longest_mm"] == 21.0 and "shortest_mm" not in r   # five-bar: link numbers
    r = _json("grashof", CH3 / "hrones-nelson-ranges.toml", "--no-plot",
              "-o", tmp_path / "d")["results"]
    assert r["l2_crank_rocker_mm"] == r["l2_crank_rocker"]


# -- grashof: options that do nothing for a form (item 11) ----------------------------------

@pytest.mark.parametrize("args, option", [
    (("--lengths", "40,90,70,100", "--dpi", "300"), "--dpi"),
    (("--lengths", "40,90,70,100", "--set", "fourbar.frame=2"), "--set"),
    (("--lengths", "40,90,70,100", "--animate"), "--animate"),
    ((str(CH3 / "ex3-1.toml"), "--animate"), "--animate"),
])
def test_grashof_refuses_options_its_form_cannot_serve(tmp_path, args, option):
    proc = run_inprocess("grashof", *args, "-o", tmp_path)
    assert proc.returncode == 2
    line = proc.stderr.strip()
    assert "\n" not in line and f"{option} does nothing for grashof" in line
    doc = json.loads(run_inprocess("grashof", *args, "--json", "-o", tmp_path).stdout)
    assert doc["exit_code"] == 2 and option in doc["error"]


def test_grashof_batch_refuses_dpi(tmp_path):
    sets = tmp_path / "sets.csv"
    sets.write_text("l1,l2,l3,l4\n28,52,50,72\n")
    proc = run_inprocess("grashof", "--batch", sets, "--dpi", "150", "-o", tmp_path / "o")
    assert proc.returncode == 2 and "--dpi does nothing for grashof --batch" in proc.stderr


@pytest.mark.parametrize("extra", [("--no-plot",), ("--no-animate",), ("--no-plot", "--dpi", "90")])
def test_grashof_quick_form_takes_the_negative_flags_as_no_ops(tmp_path, extra):
    proc = run_inprocess("grashof", "--lengths", "40,90,70,100", *extra, "-q", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert not list(tmp_path.glob("*.png"))


def test_grashof_help_does_not_offer_animate():
    proc = run_inprocess("grashof", "--help")
    assert proc.returncode == 0
    assert "--animate" not in proc.stdout and "--dpi" in proc.stdout
    assert "SPEC.toml form only" in " ".join(proc.stdout.split())


def test_grashof_csv_lengths_keep_the_batch_inputs_names(tmp_path):
    """grashof.csv's l1…l4 stay unsuffixed (docs/grashof.md): its first six columns are the
    --batch input's, so the output cut to them is a valid batch again, and report.txt says
    the unit.  习题 3-1's four-bar 28, 52, 50, 72 (configs/ch3/exercise3-1.toml): a crank-rocker."""
    sets = write_spec(tmp_path, "l1,l2,l3,l4,frame,input\n2.8,5.2,5.0,7.2,4,1\n", "sets.csv")
    proc = run_inprocess("grashof", "--batch", sets, "--units", "cm", "-q", "-o", tmp_path / "a")
    assert proc.returncode == 0, proc.stderr
    rows = (tmp_path / "a" / "grashof.csv").read_text().splitlines()
    assert rows[0].split(",")[:6] == ["l1", "l2", "l3", "l4", "frame", "input"]
    assert rows[1].startswith("2.8,5.2,5,7.2,4,1,crank_rocker,")
    report = (tmp_path / "a" / "report.txt").read_text(encoding="utf-8")
    assert "grashof.csv: lengths l1…l4 in cm, as given" in report
    again = write_spec(tmp_path, "\n".join(",".join(r.split(",")[:6]) for r in rows) + "\n",
                       "again.csv")
    proc = run_inprocess("grashof", "--batch", again, "--units", "cm", "-q", "-o", tmp_path / "b")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "b" / "grashof.csv").read_text().splitlines() == rows
