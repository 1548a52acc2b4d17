"""`mechcli grashof` with `[mobility] drivers`: the structural analysis as an output
(issue 30 §2): JSON `mechanism_class` and `groups`, the report's block, and exit 2 when
the drivers do not match the mobility.  Decompositions by hand (configs/ch3/
structure-class3.toml's comments)."""

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json

TRIAD = CONFIGS / "ch3" / "structure-class3.toml"


def test_groups_and_class_in_json(tmp_path):
    r = run_json("grashof", TRIAD, "--out", tmp_path)["results"]
    assert r["mechanism_class"] == 3
    assert r["groups"] == [
        {"type": "driver", "class": 1, "links": [1], "joints": ["A"]},
        {"type": "triad", "class": 3, "links": [2, 3, 4, 5],
         "joints": ["B", "G", "H", "C", "E", "F"]}]


def test_another_driver_splits_the_chain_into_dyads(tmp_path):
    r = run_json("grashof", TRIAD, "--out", tmp_path, "--set", "mobility.drivers=[4]")
    assert r["results"]["mechanism_class"] == 2
    assert [(g["type"], g["links"]) for g in r["results"]["groups"]] == [
        ("driver", [4]), ("RRR", [3, 5]), ("RRR", [1, 2])]


def test_report_prints_the_decomposition(tmp_path):
    proc = run_inprocess("grashof", TRIAD, "--out", tmp_path, "--lang", "zh")
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "杆组分解: III 级机构" in text and "III 级三级杆组" in text
    assert "原动件 1 与机架 6" in text


def test_the_kin_form_takes_the_linkages_drivers(tmp_path):
    # the 2-DOF five-bar's kin spec drives links 1 and 4: one RRR dyad is left
    r = run_json("grashof", CONFIGS / "ch3" / "mobility-fivebar.toml", "--out", tmp_path)
    assert r["results"]["mechanism_class"] == 2
    assert [g["type"] for g in r["results"]["groups"]] == ["driver", "driver", "RRR"]


def test_drivers_that_do_not_match_the_mobility_exit_2(tmp_path):
    for value, got in (("[1, 4]", "F = 1 with 2 drivers [1, 4]"),
                       ("[3]", "[3] (link 3 is not)"),
                       ("[]", "[]"), ("1", "1")):
        proc = run_inprocess("grashof", TRIAD, "--out", tmp_path, "--set",
                             f"mobility.drivers={value}")
        assert proc.returncode == 2, proc.stderr
        line = one_line_error(proc)
        assert "[mobility] drivers" in line and got in line, line
