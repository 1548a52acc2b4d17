"""`grashof`'s [mobility] in the joints form of `kin` (issue 30 §2): [[mobility.link]]
with the joints each link carries, [[mobility.slider]] for prismatic pairs; the same
structure as the pair-by-pair form, and bad input named in one line."""

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json, write_spec

#: a slider-crank (例 1-2's chain) in the links form: A on 1 only is its frame pivot; the
#: block 3 carries C and slides on the frame 4
SLIDER_CRANK = """
command = "grashof"
[mobility]
frame = 4
drivers = [1]
[[mobility.link]]
number = 1
joints = ["A", "B"]
[[mobility.link]]
number = 2
joints = ["B", "C"]
[[mobility.link]]
number = 3
joints = ["C"]
[[mobility.slider]]
block = 3
guide = 4
name = "C"
"""


def test_links_form_equals_the_pair_form(tmp_path):
    # the same six-bar as configs/ch3/structure-class3.toml: every structural result equal
    a = run_json("grashof", CONFIGS / "ch3" / "structure-class3.toml", "--out", tmp_path / "a")
    b = run_json("grashof", CONFIGS / "ch3" / "structure-class3-links.toml",
                 "--out", tmp_path / "b")
    for key in ("F", "n", "P_L", "P_H", "mechanism_class", "groups"):
        assert a["results"][key] == b["results"][key], key


def test_a_slider_crank_by_its_links(tmp_path):
    # by hand: n = 3, P_L = 4 (A, B, C revolutes and the slide), F = 9 − 8 = 1; one RRP dyad
    r = run_json("grashof", write_spec(tmp_path, SLIDER_CRANK), "--out", tmp_path / "o")
    r = r["results"]
    assert (r["F"], r["n"], r["P_L"], r["mechanism_class"]) == (1, 3, 4, 2)
    assert [g["type"] for g in r["groups"]] == ["driver", "RRP"]


@pytest.mark.parametrize("edit,key", [
    (lambda t: t.replace("guide = 4", "guide = 9"), "[mobility.slider.0] guide"),
    (lambda t: t.replace('joints = ["C"]', 'joints = ["C", "C"]'), "[mobility.link.2] joints"),
    (lambda t: t + "[[mobility.link]]\nnumber = 4\njoints = [\"A\", \"Z\"]\n",
     "[mobility.link.3] joints"),     # the frame listed: Z on it alone joins nothing
    (lambda t: t + "[[mobility.joint]]\nlinks = [1, 4]\n", "[mobility] joint"),
])
def test_bad_links_are_one_line_naming_the_key(tmp_path, edit, key):
    proc = run_inprocess("grashof", write_spec(tmp_path, edit(SLIDER_CRANK)),
                         "--out", tmp_path / "o")
    assert proc.returncode == 2
    assert key in one_line_error(proc)
