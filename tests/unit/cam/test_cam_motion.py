"""Motion laws: end values, continuity, exact derivatives, impact classification."""

import math

import numpy as np
import pytest

from mechcli.core.cam.motion import LAWS, build_program, law_pieces, law_values

RAD = math.radians

#: law -> (continuous velocity at the ends, continuous acceleration at the ends,
#          peak |f''|, peak f')   (normalized; textbook coefficients C_a, C_v)
PROPERTIES = {
    "uniform": (False, False, 0.0, 1.0),
    "parabolic": (True, False, 4.0, 2.0),
    "cosine": (True, False, math.pi ** 2 / 2, math.pi / 2),
    "sine": (True, True, 2 * math.pi, 2.0),
    "cubic": (True, False, 6.0, 1.5),   # f = 3u² − 2u³: f'' = 6 − 12u, f'(1/2) = 3/2
    "poly345": (True, True, 10 / math.sqrt(3), 1.875),
    "poly4567": (True, True, 7.5132, 2.1875),
    "modified-trapezoid": (True, True, 4.8881, 2.0),
    "modified-sine": (True, True, 5.5280, 1.7596),
}


@pytest.mark.parametrize("law", LAWS)
def test_law_ends_and_peaks(law):
    f, f1, f2, _ = law_values(law, np.array([0.0, 1.0]))
    assert f[0] == pytest.approx(0.0, abs=1e-14) and f[1] == pytest.approx(1.0, abs=1e-14)
    v_cont, a_cont, a_peak, v_peak = PROPERTIES[law]
    if v_cont:
        assert np.allclose(f1, 0.0, atol=1e-12)
    else:
        assert not np.allclose(f1, 0.0)
    if a_cont:
        assert np.allclose(f2, 0.0, atol=1e-12)
    u = np.linspace(0, 1, 200001)
    _, g1, g2, _ = law_values(law, u)
    assert np.max(np.abs(g2)) == pytest.approx(a_peak, rel=2e-4, abs=1e-12)
    assert np.max(g1) == pytest.approx(v_peak, rel=2e-4)


@pytest.mark.parametrize("law", LAWS)
def test_derivatives_match_finite_differences(law):
    # central differences inside every piece, away from its ends
    for piece in law_pieces(law):
        u = np.linspace(piece.u0, piece.u1, 41)[1:-1]
        h = 1e-6
        f, f1, f2, f3 = piece.func(u)
        fp, f1p, f2p, _ = piece.func(u + h)
        fm, f1m, f2m, _ = piece.func(u - h)
        np.testing.assert_allclose((fp - fm) / (2 * h), f1, atol=1e-7)
        np.testing.assert_allclose((f1p - f1m) / (2 * h), f2, atol=1e-6)
        np.testing.assert_allclose((f2p - f2m) / (2 * h), f3, atol=1e-5)


@pytest.mark.parametrize("law", LAWS)
def test_pieces_join_continuously(law):
    pieces = law_pieces(law)
    for left, right in zip(pieces, pieces[1:]):
        a = left.func(np.array([left.u1]))
        b = right.func(np.array([right.u0]))
        assert a[0][0] == pytest.approx(b[0][0], abs=1e-13)      # s
        assert a[1][0] == pytest.approx(b[1][0], abs=1e-12)      # v
        if law != "parabolic":                                   # a jumps only there
            assert a[2][0] == pytest.approx(b[2][0], abs=1e-11)


def test_table_4_1_return_formulas():
    """Return segment reproduces the return column of 表 4-1."""
    h, b = 0.06, RAD(90)
    prog = build_program([("rise", RAD(100), "parabolic", h), ("dwell", RAD(60), None, 0),
                          ("return", b, "cosine", h), ("dwell", RAD(110), None, 0)], h)
    d = RAD(160) + np.linspace(0, b, 7)
    st = prog.evaluate(d)
    x = np.pi * (d - RAD(160)) / b
    np.testing.assert_allclose(st.s[:-1], h / 2 * (1 + np.cos(x[:-1])), atol=1e-15)
    np.testing.assert_allclose(st.s1[:-1], -np.pi * h / (2 * b) * np.sin(x[:-1]), atol=1e-14)
    np.testing.assert_allclose(st.s2[:-1], -np.pi ** 2 * h / (2 * b * b) * np.cos(x[:-1]),
                               atol=1e-13)
    # parabolic rise, second half (表 4-1): s = h - 2h (δ0 - δ)^2/δ0^2
    b0 = RAD(100)
    d = np.array([RAD(60), RAD(80)])
    np.testing.assert_allclose(prog.evaluate(d).s, h - 2 * h * (b0 - d) ** 2 / b0 ** 2)


def test_program_cycle_values():
    h = 0.02
    prog = build_program([("rise", RAD(120), "sine", h), ("dwell", RAD(30), None, 0),
                          ("return", RAD(60), "cosine", h), ("dwell", RAD(150), None, 0)], h)
    st = prog.evaluate(np.radians([0, 60, 120, 135, 150, 180, 210, 300, 360]))
    np.testing.assert_allclose(st.s, [0, h / 2, h, h, h, h / 2, 0, 0, 0], atol=1e-15)


def test_impacts_classified():
    h = 0.02
    prog = build_program([("rise", RAD(120), "uniform", h), ("dwell", RAD(60), None, 0),
                          ("return", RAD(90), "parabolic", h), ("dwell", RAD(90), None, 0)], h)
    got = [(round(math.degrees(i.delta), 6), i.kind) for i in prog.impacts()]
    assert got == [(0.0, "rigid"), (120.0, "rigid"), (180.0, "soft"), (225.0, "soft"),
                   (270.0, "soft")]
    # rigid jump = h/δ0 per rad
    assert prog.impacts()[0].jump == pytest.approx(h / RAD(120))


def test_smooth_laws_have_no_impacts():
    h = 0.01
    for law in ("sine", "poly345", "poly4567", "modified-trapezoid", "modified-sine"):
        prog = build_program([("rise", RAD(150), law, h), ("dwell", RAD(30), None, 0),
                              ("return", RAD(150), law, h), ("dwell", RAD(30), None, 0)], h)
        assert prog.impacts() == ()


def test_multiple_rises_and_partial_lifts():
    h = 0.03
    prog = build_program([("rise", RAD(90), "sine", 0.01), ("dwell", RAD(30), None, 0),
                          ("rise", RAD(90), "poly345", 0.02), ("return", RAD(150), "cosine", h)],
                         h)
    st = prog.evaluate(np.radians([90, 120, 210, 359.999999]))
    np.testing.assert_allclose(st.s[:3], [0.01, 0.01, 0.03], atol=1e-15)
    assert st.s[3] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("segments, match", [
    ([("rise", RAD(180), "sine", 0.01), ("return", RAD(170), "sine", 0.01)], "full turn"),
    ([("rise", RAD(180), "sine", 0.01), ("return", RAD(180), "sine", 0.005)], "return"),
    ([("rise", RAD(180), "bogus", 0.01), ("return", RAD(180), "sine", 0.01)], "valid"),
])
def test_bad_programs_raise(segments, match):
    with pytest.raises(ValueError, match=match):
        prog = build_program(segments, 0.01)
        prog.evaluate(np.array([0.1]))


def test_spans_short_of_a_turn_carry_their_sum():
    """The core words no unit: the sum is a number (rad) for the spec layer to word."""
    from mechcli.core.errors import DescribedError
    with pytest.raises(DescribedError) as err:
        build_program([("rise", RAD(180), "sine", 0.01), ("return", RAD(170), "sine", 0.01)],
                      0.01)
    assert err.value.reason == "span_sum"
    assert err.value.values["total"] == pytest.approx(RAD(350), rel=1e-15)   # 180° + 170°
