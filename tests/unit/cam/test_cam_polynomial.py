"""Polynomial motion laws: the cubic 3u² − 2u³, laws given by their coefficients
(``PolynomialLaw``), their boundary values and the jumps against the neighbouring segments.

Independent checks: numpy.polynomial evaluates the same coefficients on its own (the law
is written out here, not taken from mechcli), central finite differences of s → v → a →
jerk on the whole program, the hand-derived boundary values and peaks of each law, and
the existing parabolic law rebuilt from two polynomial segments.
"""

import math

import numpy as np
import pytest
from numpy.polynomial import Polynomial

from mechcli.core.cam.motion import (LAWS, POLYNOMIAL_LAWS, PolynomialLaw, build_program,
                                     law_pieces, law_values)
from mechcli.spec.cam import read_cam_spec
from mechcli.spec.errors import SpecError
from mechcli.spec.reader import load_spec

RAD = math.radians

#: the laws' coefficients written out from their definitions (not from mechcli):
#: cubic: s/h = 3u² − 2u³ (s(0) = 0, s(1) = 1, v(0) = v(1) = 0); 3-4-5 and 4-5-6-7: the
#: polynomials of 6 and 8 boundary conditions (rest to rest, a = 0 (and j = 0) at the ends)
WRITTEN = {
    "cubic": [0, 0, 3, -2],
    "poly345": [0, 0, 0, 10, -15, 6],
    "poly4567": [0, 0, 0, 0, 35, -84, 70, -20],
}

#: hand-derived boundary values (f'(0), f''(0), f'(1), f''(1)) and peaks (max f', max |f''|,
#: max |f'''|) of the normalized laws; computed by hand from the coefficients above:
#: cubic f' = 6u − 6u², f'' = 6 − 12u, f''' = −12: peaks at u = 1/2 (1.5), u = 0/1 (6), 12.
#: 3-4-5 f' = 30u²(1−u)², max 30/16 = 1.875 at 1/2; f'' = 60u(1 − 3u + 2u²), max at
#: u = 1/2 ∓ √3/6: 10/√3 = 5.7735; f''' = 60(1 − 6u + 6u²), max 60 at the ends.
#: 4-5-6-7 f' = 140u³(1−u)³, max 140/64 = 2.1875 at 1/2.
HAND = {
    "cubic": ((0.0, 6.0, 0.0, -6.0), (1.5, 6.0, 12.0)),
    "poly345": ((0.0, 0.0, 0.0, 0.0), (1.875, 10 / math.sqrt(3), 60.0)),
    "poly4567": ((0.0, 0.0, 0.0, 0.0), (2.1875, None, None)),
}


def test_named_polynomial_laws_are_listed_with_their_coefficients():
    # the cubic joins the book's laws; 3-4-5 and 4-5-6-7 were there already
    assert {"cubic", "poly345", "poly4567"} <= set(LAWS)
    for name, c in WRITTEN.items():
        assert POLYNOMIAL_LAWS[name] == tuple(float(x) for x in c)


@pytest.mark.parametrize("name", sorted(WRITTEN))
@pytest.mark.parametrize("alias", [False, True])
def test_named_law_against_numpy_polynomial(name, alias):
    # numpy.polynomial as the independent evaluator of f, f', f'', f'''
    law = {"cubic": "2-3", "poly345": "3-4-5", "poly4567": "4-5-6-7"}[name] if alias else name
    p = Polynomial(WRITTEN[name])
    u = np.linspace(0.0, 1.0, 1001)
    got = law_values(law, u)
    for k in range(4):
        np.testing.assert_allclose(got[k], p.deriv(k)(u), rtol=0, atol=1e-11 * (1 + 60 * k))
    # the same coefficients as a PolynomialLaw give the same law
    again = law_values(PolynomialLaw(tuple(WRITTEN[name])), u)
    for a, b in zip(got, again):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", sorted(WRITTEN))
def test_boundary_values_and_peaks_by_hand(name):
    (v0, a0, v1, a1), (vpk, apk, jpk) = HAND[name]
    f, f1, f2, _ = law_values(name, np.array([0.0, 1.0]))
    assert f.tolist() == pytest.approx([0.0, 1.0], abs=1e-14)
    assert [f1[0], f2[0], f1[1], f2[1]] == pytest.approx([v0, a0, v1, a1], abs=1e-12)
    start, end = PolynomialLaw(tuple(WRITTEN[name])).ends()
    assert start + end == pytest.approx((0.0, v0, a0, 1.0, v1, a1), abs=1e-12)
    u = np.linspace(0.0, 1.0, 600001)
    _, g1, g2, g3 = law_values(name, u)
    # peaks on a 600001-point grid: the maxima lie on or within 1e-6 of a grid point
    assert np.max(g1) == pytest.approx(vpk, rel=1e-9)
    if apk is not None:
        assert np.max(np.abs(g2)) == pytest.approx(apk, rel=1e-9)
        assert np.max(np.abs(g3)) == pytest.approx(jpk, rel=1e-12)


def _program(law_rise, law_return, h=0.025, spans=(90, 90, 90, 90)):
    return build_program([("dwell", RAD(spans[0]), None, 0.0),
                          ("rise", RAD(spans[1]), law_rise, h),
                          ("dwell", RAD(spans[2]), None, 0.0),
                          ("return", RAD(spans[3]), law_return, h)], h)


@pytest.mark.parametrize("law", ["cubic", PolynomialLaw((0, 0.5, 0.5)),
                                 PolynomialLaw((0, 0, 0, 10, -15, 6)),
                                 PolynomialLaw((0, 1.2, -0.6, 0.4))])
def test_program_derivatives_are_finite_differences_of_s(law):
    # s -> ds/dδ -> d²s/dδ² -> d³s/dδ³ by central differences inside each moving segment
    prog = _program(law, law)
    h = 1e-5    # rad; truncation error of a central difference ~ h²/6 * (next derivative)
    for seg in prog.segments:
        if seg.law is None:
            continue
        d = np.linspace(seg.start, seg.end, 31)[2:-2]
        st, plus, minus = prog.evaluate(d), prog.evaluate(d + h), prog.evaluate(d - h)
        np.testing.assert_allclose((plus.s - minus.s) / (2 * h), st.s1, rtol=0, atol=1e-9)
        np.testing.assert_allclose((plus.s1 - minus.s1) / (2 * h), st.s2, rtol=0, atol=1e-8)
        np.testing.assert_allclose((plus.s2 - minus.s2) / (2 * h), st.s3, rtol=0, atol=1e-7)
        # and the return mirrors the rise: s = s_start ∓ h f(u) with numpy's f
        u = (d - seg.start) / seg.span
        f = Polynomial(law.coefficients if isinstance(law, PolynomialLaw) else WRITTEN[law])
        np.testing.assert_allclose(st.s, seg.s_start + seg.lift * f(u), rtol=0, atol=1e-15)


def test_cubic_program_soft_impacts_with_hand_jumps():
    # cubic between dwells: v is continuous (v(0) = v(1) = 0), a jumps by ±6h/β² at all four
    # segment ends (hand: f''(0) = 6, f''(1) = -6; a return flips the sign)
    h, beta = 0.025, RAD(90)
    prog = _program("cubic", "cubic", h)
    got = [(round(math.degrees(i.delta), 9), i.kind) for i in prog.impacts()]
    assert got == [(0.0, "soft"), (90.0, "soft"), (180.0, "soft"), (270.0, "soft")]
    jumps = [i.jump for i in prog.impacts()]
    a = 6 * h / beta ** 2
    # at 0° (= 360°, end of the return, s = h - h f): a(1⁻) = -h f''(1)/β² = +a, then the
    # dwell's 0: a jump of -a; at 90° the rise starts with +a; at 180° it ends with -a (jump
    # +a); at 270° the return starts with -h f''(0)/β² = -a
    assert jumps == pytest.approx([-a, a, a, -a], rel=1e-12)


def test_polynomial_with_end_velocity_is_a_rigid_impact():
    # s/h = 0.5u + 0.5u²: f'(0) = 0.5, f'(1) = 1.5 (hand) -> velocity jumps of 0.5h/β at the
    # rise's start and 1.5h/β at its end; the dwells have zero velocity
    h, beta = 0.025, RAD(90)
    law = PolynomialLaw((0, 0.5, 0.5))
    prog = _program(law, "cubic", h)
    imp = {round(math.degrees(i.delta), 9): i for i in prog.impacts()}
    assert imp[90.0].kind == "rigid" and imp[90.0].jump == pytest.approx(0.5 * h / beta)
    assert imp[180.0].kind == "rigid" and imp[180.0].jump == pytest.approx(-1.5 * h / beta)
    # the cubic return still gives its two soft impacts
    assert imp[270.0].kind == "soft" and imp[0.0].kind == "soft"


def test_polynomial_segments_rebuild_the_parabolic_law():
    # the parabolic law (表 4-1) over 2β is s/h' = u² then 2u − u² on two halves of lift h/2:
    # the same s, v, a everywhere and the same jumps (soft at 0, β, 2β), as an independent
    # check of the polynomial segments against an existing law
    h = 0.06
    parab = build_program([("rise", RAD(100), "parabolic", h), ("dwell", RAD(60), None, 0),
                           ("return", RAD(90), "cosine", h), ("dwell", RAD(110), None, 0)], h)
    split = build_program([("rise", RAD(50), PolynomialLaw((0, 0, 1)), h / 2),
                           ("rise", RAD(50), PolynomialLaw((0, 2, -1)), h / 2),
                           ("dwell", RAD(60), None, 0), ("return", RAD(90), "cosine", h),
                           ("dwell", RAD(110), None, 0)], h)
    d = np.linspace(0, 2 * math.pi, 3601)
    a, b = parab.evaluate(d), split.evaluate(d)
    for x, y in ((a.s, b.s), (a.s1, b.s1), (a.s2, b.s2), (a.s3, b.s3)):
        np.testing.assert_allclose(x, y, rtol=0, atol=1e-12)
    key = [(round(i.delta, 9), i.kind, round(i.jump, 9)) for i in parab.impacts()]
    assert key == [(round(i.delta, 9), i.kind, round(i.jump, 9)) for i in split.impacts()]


def test_extremes_of_an_overshooting_polynomial():
    # f = 3u − 2u²: f' = 3 − 4u = 0 at u = 3/4, f(3/4) = 9/4 − 9/8 = 9/8 (hand)
    fmin, umin, fmax, umax = PolynomialLaw((0, 3, -2)).extremes()
    assert (fmin, umin) == pytest.approx((0.0, 0.0))
    assert (fmax, umax) == pytest.approx((1.125, 0.75), abs=1e-12)
    # a monotone law has its extremes at the ends
    assert PolynomialLaw(tuple(WRITTEN["poly345"])).extremes() == pytest.approx((0, 0, 1, 1))


def test_polynomial_text():
    assert str(PolynomialLaw((0, 0, 3, -2))) == "3u² − 2u³"
    assert str(PolynomialLaw((0, 1))) == "u"
    assert str(PolynomialLaw((0, -1, 2))) == "−u + 2u²"


@pytest.mark.parametrize("coef, match", [
    ((1.0,), "at least two"), ((0.0, float("nan")), "finite"), ((0.0, float("inf")), "finite")])
def test_polynomial_law_rejects_bad_coefficients(coef, match):
    with pytest.raises(ValueError, match=match):
        PolynomialLaw(coef)


@pytest.mark.parametrize("coef", [(0.1, 0, 3, -2), (0, 0, 3, -2.5)])
def test_build_program_rejects_a_polynomial_not_going_from_0_to_1(coef):
    with pytest.raises(ValueError, match="does not go from 0 to 1"):
        _program(PolynomialLaw(coef), "cubic")


def test_piece_cache_keys_polynomials_by_value():
    # law_pieces is cached: equal coefficients share pieces, different ones do not
    a, b = PolynomialLaw((0, 0, 3, -2)), PolynomialLaw((0.0, 0.0, 3.0, -2.0))
    assert law_pieces(a) is law_pieces(b)
    assert law_pieces(a) is not law_pieces(PolynomialLaw((0, 0.5, 0.5)))


SPEC = """command = "cam"
units = "mm"
[follower]
contact = "knife"
r0 = 50
[motion]
h = 20
segments = [
  {{ kind = "rise", angle = 120, law = "polynomial", coefficients = {rise} }},
  {{ kind = "dwell", angle = 60 }},
  {{ kind = "return", angle = 120, law = "{ret}" }},
  {{ kind = "dwell", angle = 60 }},
]
"""


def _read(tmp_path, rise="[0, 0, 3, -2]", ret="cubic"):
    p = tmp_path / "spec.toml"
    p.write_text(SPEC.format(rise=rise, ret=ret), encoding="utf-8")
    return read_cam_spec(load_spec(p))


def test_reader_builds_the_polynomial_law(tmp_path):
    cs = _read(tmp_path)
    law = cs.segments[0][2]
    assert isinstance(law, PolynomialLaw) and law.coefficients == (0.0, 0.0, 3.0, -2.0)
    assert cs.segments[2][2] == "cubic"


def test_reader_scales_a_sum_within_tolerance_to_exactly_one(tmp_path):
    # coefficients typed to 8 digits: Σ = 1 + 1e-8, within the 1e-6 tolerance; c0 = 1e-9
    law = _read(tmp_path, rise="[1e-9, 0, 3.00000001, -2]").segments[0][2]
    assert law.coefficients[0] == 0.0
    assert math.fsum(law.coefficients) == pytest.approx(1.0, abs=1e-15)
    assert law.coefficients[2] == pytest.approx(3.00000001 / 1.00000001, rel=1e-15)


@pytest.mark.parametrize("rise, ret, key, words", [
    ("[0.01, 0, 3, -2]", "cubic", "coefficients", "c0 = 0.01"),
    ("[0, 0, 3, -2.1]", "cubic", "coefficients", "a sum of 0.9"),
    ("[0, 0, 3, -1.99]", "cubic", "coefficients", "reaches the lift"),
    # f = 3u − 2u² rises to 9/8 h = 22.5 mm > h at u = 3/4
    ("[0, 3, -2]", "cubic", "coefficients", "s = 22.5 at u = 0.75"),
    # f = −u + 2u²: below 0 at u = 1/4 (f = −1/8, s = −2.5 mm)
    ("[0, -1, 2]", "cubic", "coefficients", "s = -2.5 at u = 0.25"),
    ("[1]", "cubic", "coefficients", "2 to 16 coefficients"),
    ("[]", "cubic", "coefficients", "array of numbers"),
    ("[0, 0, 3e7, -3e7, 1]", "cubic", "coefficients[2]", "within ±1e+06"),
    ("[0, 0, 3, 'x']", "cubic", "coefficients[3]", "finite number"),
    ("[0, 0, 3, -2]", "cubik", "law", "cubic"),
])
def test_reader_bad_polynomials_name_the_key(tmp_path, rise, ret, key, words):
    with pytest.raises(SpecError) as err:
        _read(tmp_path, rise=rise, ret=ret)
    text = str(err.value)
    assert f"{key}:" in text and words in text, text
    assert "\n" not in text


def test_reader_coefficients_need_law_polynomial(tmp_path):
    # coefficients beside a named law would be ignored: an unknown key
    p = tmp_path / "spec.toml"
    p.write_text(SPEC.format(rise="[0, 0, 3, -2]", ret="cubic").replace(
        'law = "cubic"', 'law = "cubic", coefficients = [0, 1]'), encoding="utf-8")
    with pytest.raises(SpecError, match="coefficients"):
        read_cam_spec(load_spec(p))
    # law = "polynomial" without coefficients names the missing key
    p.write_text(SPEC.format(rise="[0, 0, 3, -2]", ret="polynomial"), encoding="utf-8")
    with pytest.raises(SpecError, match=r"segments.*coefficients"):
        read_cam_spec(load_spec(p))
