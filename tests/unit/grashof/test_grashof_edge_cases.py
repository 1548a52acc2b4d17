"""``mechcli grashof`` edge cases: mobility frames, crossed chains, empty or odd
quick-form and batch input, chains that cannot close, RRRRP sliders inside the crank circle."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from mechcli.core.grashof import fourbar as gf
from mechcli.core.grashof.fivebar import rrrrp_crank
from mechcli.core.grashof.mobility import Joint, MobilityError, count_mobility
from mechcli.commands.grashof import build
from mechcli.spec.errors import SpecError
from mechcli.spec.grashof import quick_spec, read_batch_csv, read_grashof_spec


def write(tmp_path, text, name="spec.toml", encoding="utf-8"):
    p = tmp_path / name
    p.write_text(text, encoding=encoding)
    return p


# ------------------------------------------------------------------ mobility
FOURBAR_ZERO = """command = "grashof"
[mobility]
frame = 4
[[mobility.joint]]
links = [0, 1]
[[mobility.joint]]
links = [1, 2]
[[mobility.joint]]
links = [2, 3]
[[mobility.joint]]
links = [3, 0]
"""


def test_mobility_frame_that_no_joint_names_is_an_error(tmp_path):
    """A four-bar with the ground numbered 0 but ``frame = 4`` was counted as n = 4, F = 4."""
    with pytest.raises(MobilityError, match="frame"):
        count_mobility([Joint("R", (0, 1)), Joint("R", (1, 2)), Joint("R", (2, 3)),
                        Joint("R", (3, 0))], frame=4)
    with pytest.raises(SpecError) as exc:
        read_grashof_spec(write(tmp_path, FOURBAR_ZERO))
    assert exc.value.key.endswith("frame")
    # the same chain with the right frame: hand count F = 3·3 − 2·4 = 1
    spec = read_grashof_spec(write(tmp_path, FOURBAR_ZERO.replace("frame = 4", "frame = 0")))
    assert build(spec, "en")[0]["F"] == 1


def test_inversions_of_a_crossed_parallelogram_chain(tmp_path):
    """assembly = "crossed": the type said antiparallelogram, its own inversion row
    (frame 4) said parallelogram."""
    spec = read_grashof_spec(write(tmp_path, 'command = "grashof"\n[fourbar]\n'
                                   'lengths = [20, 30, 20, 30]\nassembly = "crossed"\n'))
    r = build(spec, "en")[0]
    assert r["type"] == "antiparallelogram"
    assert [r[f"inversion_frame{k}"] for k in (1, 2, 3, 4)] == ["antiparallelogram"] * 4
    spec = read_grashof_spec(write(tmp_path, 'command = "grashof"\n[fourbar]\n'
                                   'lengths = [20, 30, 20, 30]\n'))
    r = build(spec, "en")[0]
    assert [r[f"inversion_frame{k}"] for k in (1, 2, 3, 4)] == ["parallelogram"] * 4


# ------------------------------------------------------------------ quick form
def test_quick_form_empty_length_field_is_an_error():
    """``--lengths 100,,150,170,110`` was read as the four-bar 100,150,170,110."""
    with pytest.raises(SpecError) as exc:
        quick_spec("100,,150,170,110")
    assert exc.value.key == "lengths[1]"
    with pytest.raises(SpecError):
        quick_spec("100,150,170,110,")


# ------------------------------------------------------- closure messages in spec units
@pytest.mark.parametrize("lengths, offset, text", [
    ("300,100,100,90", None, "link 1 (300 mm) is not shorter than the sum of the other links "
                             "(290 mm)"),
    ("1,1,1,5,1", None, "link 4 (5 mm) is not shorter than the sum of the other links (4 mm)"),
    ("20,60", -80, "offset |e| = 80 mm is not shorter than crank + coupler = 80 mm"),
])
def test_cannot_close_message_is_in_the_spec_unit(lengths, offset, text):
    """The exit-3 message quoted metres (0.3, 0.29) for lengths given in mm."""
    spec = quick_spec(lengths, offset=offset)
    with pytest.raises(gf.ClosureError) as exc:
        build(spec, "en")
    assert text in str(exc.value)


@pytest.mark.parametrize("inputs", ['[1, "a"]', "[1.0, 4.0]", "[true, 4]"])
def test_fivebar_inputs_that_are_not_link_numbers(tmp_path, inputs):
    """``inputs = [1, "a"]`` crashed with a TypeError (exit 1) in sorted()."""
    with pytest.raises(SpecError) as exc:
        read_grashof_spec(write(tmp_path, 'command = "grashof"\n[fivebar]\n'
                                f"lengths = [10, 21, 19, 20, 5]\ninputs = {inputs}\n"))
    assert exc.value.key.endswith("inputs")


def test_guide_bar_whose_guide_never_reaches_the_crank_pin_cannot_close(tmp_path):
    """a = 10, d = 20, e = 40: CB <= 30 < e, no position exists; it was reported as 'no_crank'."""
    with pytest.raises(gf.ClosureError, match="guide-bar cannot close"):
        gf.analyse_guide_bar(10.0, 20.0, 40.0)
    spec = read_grashof_spec(write(tmp_path, 'command = "grashof"\n[guide_bar]\n'
                                   "crank = 10\nframe = 20\noffset = 40\n"))
    with pytest.raises(gf.ClosureError, match="40 mm"):
        build(spec, "en")
    assert gf.analyse_guide_bar(10.0, 20.0, 29.0).kind == "no_crank"


# ------------------------------------------------------------------ batch CSV
def test_batch_row_numbers_are_file_lines(tmp_path):
    """Blank and comment lines shifted the row number of the error message."""
    p = write(tmp_path, "l1,l2,l3,l4\n# comment\n100,150,170,110\n\n10,-5,35,30\n", "s.csv")
    with pytest.raises(SpecError) as exc:
        read_batch_csv(p)
    assert exc.value.key == "row 5"
    p = write(tmp_path, "100,150,170,110\n\n10,50,35\n", "t.csv")
    with pytest.raises(SpecError) as exc:
        read_batch_csv(p)
    assert exc.value.key == "row 3"


def test_batch_header_with_a_byte_order_mark(tmp_path):
    """Spreadsheets write UTF-8 with a BOM; the header 'l1,l2,l3,l4' was rejected."""
    p = write(tmp_path, "l1,l2,l3,l4\n100,150,170,110\n", "bom.csv", encoding="utf-8-sig")
    bs = read_batch_csv(p)
    assert_allclose(bs.lengths, [[0.1, 0.15, 0.17, 0.11]])


def test_batch_first_row_with_nan_is_a_row_error_not_a_header(tmp_path):
    p = write(tmp_path, "100,150,170,110,nan\n", "n.csv")
    with pytest.raises(SpecError) as exc:
        read_batch_csv(p)
    assert exc.value.key == "row 1"


# ------------------------------------------------------------------ RRRRP
def test_rrrrp_slider_positions_with_the_slider_inside_the_crank_circle():
    """l1 = 5, l2 = 3, l3 = 3.5, e = 0.5: held anywhere with AD <= min(l1 − |l2 − l3|,
    l2 + l3 − l1) = 1.5, i.e. |x| <= sqrt(1.5² − 0.5²), link 1 turns fully; none was reported."""
    rc = rrrrp_crank(5.0, 3.0, 3.5, 0.5)
    assert (rc.slider_lo, rc.slider_hi) == (0.0, 0.0)
    assert_allclose(rc.slider_inner_hi, np.sqrt(1.5 ** 2 - 0.5 ** 2), rtol=1e-12)
    th = np.linspace(0, 2 * np.pi, 20001)
    for x, turns in ((0.0, True), (rc.slider_inner_hi * 0.999, True),
                     (rc.slider_inner_hi * 1.01, False)):
        bd = np.abs(5.0 * np.exp(1j * th) - (x + 0.5j))
        assert bool(((bd >= 0.5) & (bd <= 6.5)).all()) is turns
    # no inner interval when the slider path misses the region AD <= 1.5
    assert not rrrrp_crank(5.0, 3.0, 3.5, 2.0).has_inner
    assert not rrrrp_crank(10.0, 40.0, 25.0, 3.0).has_inner
