"""``mechcli cam`` with the cubic law and laws given by polynomial coefficients: the configs'
hand-derived numbers, independent re-computation (numpy.polynomial for s, v, a, j and a
dense scan of eq. (7-14) for the pressure angle), the jump report, and bad input (exit 2,
one line naming the key)."""

import csv
import json
import math

try:
    import tomllib
except ImportError:     # Python < 3.11
    import tomli as tomllib

import numpy as np
import pytest
from numpy.polynomial import Polynomial

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json
from tests.unit.cam.test_cam_polynomial import SPEC

CH4 = CONFIGS / "ch4"

#: the laws written out from their definitions (not taken from mechcli)
CUBIC = Polynomial([0, 0, 3, -2])
P345 = Polynomial([0, 0, 0, 10, -15, 6])


def _csv(path):
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    return {h: np.array([float(r[i]) for r in rows[1:]]) for i, h in enumerate(head)}


def _independent_motion(delta_deg, program, h):
    """s, ds/dδ, d²s/dδ², d³s/dδ³ of a dwell/rise/dwell/return program from numpy.polynomial,
    each segment [start, end) (the following segment at a boundary), except on the first of
    two rows at the same δ: cam.csv's limit from the left at a jump, (start, end]."""
    out = [np.zeros_like(delta_deg) for _ in range(4)]
    left = np.append(delta_deg[1:] == delta_deg[:-1], False)
    level = 0.0
    for kind, start, span, law in program:
        m = np.where(left, (delta_deg > start) & (delta_deg <= start + span),
                     (delta_deg >= start) & (delta_deg < start + span))
        if kind == "dwell":
            out[0][m] = level
            continue
        beta = math.radians(span)
        u = (delta_deg[m] - start) / span
        sign = 1.0 if kind == "rise" else -1.0
        for k in range(4):
            out[k][m] = (level if k == 0 else 0.0) + sign * h * law.deriv(k)(u) / beta ** k
        level += sign * h
    last = (delta_deg >= 360.0 - 1e-9) & ~left  # the closing row is δ = 0 again
    for k in range(4):
        out[k][last] = out[k][0]
    return out


def _alpha_max(law, h, span, r0, start, rise=True):
    """Largest pressure angle of a radial (e = 0) translating follower, eq. (7-14):
    tan α = |ds/dδ| / (r0 + s), by a dense scan and a parabola through the best three
    points (error ~1e-10 deg at 2e5 points); returns (deg, cam angle deg)."""
    beta = math.radians(span)
    u = np.linspace(0.0, 1.0, 200001)
    s = h * law(u) if rise else h - h * law(u)
    a = np.degrees(np.arctan2(h * law.deriv()(u) / beta, r0 + s))
    i = int(np.argmax(a))
    y0, y1, y2 = a[i - 1], a[i], a[i + 1]
    du = u[1] - u[0]
    off = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2)
    return y1 - 0.25 * (y0 - y2) * off, start + (u[i] + off * du) * span


CONFIG_CASES = {
    # name: (law, h mm, [(kind, start, span)], r0 mm, omega rad/s)
    "cubic-cevp": (CUBIC, 25.0, [("dwell", 0, 90), ("rise", 90, 90), ("dwell", 180, 90),
                                 ("return", 270, 90)], 50.0, 2 * math.pi),
    "polynomial-cevp": (P345, 25.0, [("dwell", 0, 90), ("rise", 90, 90), ("dwell", 180, 90),
                                      ("return", 270, 90)], 50.0, 2 * math.pi),
    "poly345-double-dwell": (P345, 10.0, [("rise", 0, 90), ("dwell", 90, 45),
                                           ("return", 135, 180), ("dwell", 315, 45)],
                             76.2, 10.0),
}


@pytest.mark.parametrize("name", sorted(CONFIG_CASES))
def test_config_against_independent_motion_and_pressure_angle(name, tmp_path):
    law, h, segs, r0, w = CONFIG_CASES[name]
    doc = run_json("cam", CH4 / f"{name}.toml", "--out", tmp_path)
    res = doc["results"]
    # the config's [expected] numbers (typed from the hand derivation in its comment; mechcli
    # check compares them with the run in tests/textbook) agree with this file's computations
    with open(CH4 / f"{name}.toml", "rb") as fh:
        want = tomllib.load(fh)["expected"]
    # s, v, a, j of every CSV row against numpy.polynomial
    col = _csv(tmp_path / "cam.csv")
    program = [(k, st, sp, None if k == "dwell" else law) for k, st, sp in segs]
    s, v, a, j = _independent_motion(col["delta_deg"], program, h)
    scale = max(abs(a).max(), 1.0)
    np.testing.assert_allclose(col["s_mm"], s, rtol=0, atol=1e-7)
    np.testing.assert_allclose(col["v_mm_rad"], v, rtol=0, atol=1e-7)
    np.testing.assert_allclose(col["a_mm_rad2"], a, rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(col["j_mm_rad3"], j, rtol=1e-7, atol=1e-6)
    np.testing.assert_allclose(col["v_mm_s"], v * w, rtol=0, atol=1e-6)
    # the time maxima from the laws' peak coefficients (hand: C_v, C_a, C_j of each law)
    cv, ca, cj = ((1.5, 6.0, 12.0) if law is CUBIC else (1.875, 10 / math.sqrt(3), 60.0))
    beta = math.radians(min(sp for k, _, sp in segs if k != "dwell"))
    assert res["v_max"] == pytest.approx(cv * h * w / beta, rel=1e-9)
    assert res["a_max"] == pytest.approx(ca * h * w ** 2 / beta ** 2, rel=2e-6)  # sampled
    assert res["j_max"] == pytest.approx(cj * h * w ** 3 / beta ** 3, rel=1e-12)
    # pressure angle by an independent scan of eq. (7-14)
    (_, rs, rspan), (_, ts, tspan) = [(k, st, sp) for k, st, sp in segs if k != "dwell"]
    for key, (st, sp, rise) in (("alpha_rise_max", (rs, rspan, True)),
                                ("alpha_return_max", (ts, tspan, False))):
        amax, at = _alpha_max(law, h, sp, r0, st, rise)
        assert res[f"{key}_deg"] == pytest.approx(amax, abs=1e-7)
        assert res[f"{key}_at_deg"] == pytest.approx(at, abs=1e-4)
        # printed to 5 decimals in the config: half a unit of the last digit
        assert want[f"{key}_deg"] == pytest.approx(amax, abs=5e-6)
        assert want[f"{key}_at_deg"] == pytest.approx(at, abs=5e-5)
    assert want["v_max"] == pytest.approx(res["v_max"], rel=1e-6)
    j_want = want["j_max"]
    assert j_want == pytest.approx(cj * h * w ** 3 / beta ** 3, rel=1e-6)


def test_cubic_jumps_reported_with_segments_and_sizes(tmp_path):
    doc = run_json("cam", CH4 / "cubic-cevp.toml", "--out", tmp_path)
    res = doc["results"]
    # hand: f''(0) = 6, f''(1) = -6 -> |Δ d²s/dδ²| = 6h/β² = 6 * 25/(π/2)² = 60.7927 mm/rad²
    jump = 6 * 25 / (math.pi / 2) ** 2
    assert res["soft_impacts_deg"] == [0.0, 90.0, 180.0, 270.0]
    got = [(i["at_deg"], i["kind"], i["before"], i["after"]) for i in res["impacts"]]
    assert got == [(0.0, "soft", "return", "dwell"), (90.0, "soft", "dwell", "rise"),
                   (180.0, "soft", "rise", "dwell"), (270.0, "soft", "dwell", "return")]
    assert [i["jump"] for i in res["impacts"]] == pytest.approx([-jump, jump, jump, -jump])
    seg = res["segments"][1]
    assert seg["law"] == "cubic" and seg["coefficients"] == [0.0, 0.0, 3.0, -2.0]
    assert seg["lift"] == 25.0 and (seg["start_deg"], seg["end_deg"]) == pytest.approx((90, 180))
    report = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "rise    δ = 90.0° … 180.0°, cubic, lift 25.0000 mm\n          s/h = 3u² − 2u³\n" \
        in report
    # two lines per jump: where (between which segments), then its size
    assert "δ = 90.0000°, dwell → rise (cubic)\n" in report
    assert "δ = 180.0000°, rise (cubic) → dwell\n" in report
    assert report.count("Δ(d²s/dδ²) = +60.7927 mm/rad²\n") == 2
    assert report.count("Δ(d²s/dδ²) = -60.7927 mm/rad²\n") == 2
    # two CSV rows at a jump (docs/cam.md): the limit from the left (the dwell, a = 0), then
    # from the right (the cubic, a = +6h/β²) at 90°
    col = _csv(tmp_path / "cam.csv")
    at90 = int(np.argmin(abs(col["delta_deg"] - 90.0)))
    assert col["delta_deg"][at90 + 1] == col["delta_deg"][at90] == 90.0
    assert col["a_mm_rad2"][at90] == 0.0
    assert col["a_mm_rad2"][at90 + 1] == pytest.approx(jump)


def _base(rise):
    """A knife-edge cam: the polynomial rise, 4-5-6-7 return (the unit test's spec)."""
    return SPEC.format(rise=rise, ret="poly4567")


def test_velocity_jump_of_a_polynomial_is_a_rigid_impact(tmp_path):
    # s/h = 2u - u²: f'(0) = 2 (hand) -> the rise starts with ds/dδ = 2h/β = 19.0986 mm/rad
    # out of a dwell: a rigid impact at 0° (and its warning); f'(1) = 0: none at 120°, but
    # f''(1) = -2 -> a soft impact there of +2h/β² = 9.1189 mm/rad²
    spec = tmp_path / "spec.toml"
    spec.write_text(_base("[0, 2, -1]"), encoding="utf-8")
    doc = run_json("cam", spec, "--out", tmp_path / "o")
    res = doc["results"]
    beta = math.radians(120)
    imp = {i["at_deg"]: i for i in res["impacts"]}
    assert imp[0.0]["kind"] == "rigid" and imp[0.0]["jump"] == pytest.approx(2 * 20 / beta)
    assert imp[120.0]["kind"] == "soft" and imp[120.0]["jump"] == pytest.approx(2 * 20 / beta ** 2)
    assert res["rigid_impacts_deg"] == [0.0] and res["n_soft_impacts"] == 1   # 4-5-6-7: none
    assert any("rigid impact (velocity jump) at δ = 0°" in w for w in doc["warnings"])
    report = (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")
    lines = report.splitlines()
    i = next(k for k, ln in enumerate(lines) if "rigid impact (velocity jump)" in ln)
    assert lines[i].endswith("δ = 0.0000°, dwell → rise (polynomial)")
    assert lines[i + 1].strip() == "Δ(ds/dδ) = +19.0986 mm/rad"
    assert "polynomial, lift 20.0000 mm\n          s/h = 2u − u²\n" in report
    assert "poly4567, lift 20.0000 mm\n          s/h = 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷\n" in report


def test_oscillating_follower_polynomial_in_degrees(tmp_path):
    # ψ = 20° swing, rise s/h = 3u² - 2u³ given as coefficients over 150°: the largest
    # dψ/dδ is 1.5 ψ/β = 1.5 * 20/150 = 0.2 (rad/rad, hand), at δ = 75°
    spec = tmp_path / "osc.toml"
    spec.write_text("""command = "cam"
[follower]
motion = "oscillating"
contact = "roller"
a = 60
l = 50
r0 = 25
rr = 8
[motion]
psi = 20
segments = [
  { kind = "rise", angle = 150, law = "polynomial", coefficients = [0, 0, 3, -2] },
  { kind = "dwell", angle = 30 },
  { kind = "return", angle = 150, law = "cubic" },
  { kind = "dwell", angle = 30 },
]
""", encoding="utf-8")
    doc = run_json("cam", spec, "--out", tmp_path / "o", "--lang", "zh")
    res = doc["results"]
    assert res["ds_max"] == pytest.approx(0.2, rel=1e-9)
    assert res["segments"][0]["lift"] == pytest.approx(20.0)
    assert res["n_soft_impacts"] == 4 and res["n_rigid_impacts"] == 0
    report = (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")
    assert "推程  δ = 0.0° … 150.0°, 多项式, 行程 20.0000°\n        s/h = 3u² − 2u³\n" in report
    assert "柔性冲击 (加速度突变)" in report and "休止 → 推程 (polynomial)" in report


@pytest.mark.parametrize("rise, key, words", [
    ("[0.5, 0, 3, -2]", "coefficients", "starts at s/h = 0 at u = 0 (c0 = 0)"),
    ("[0, 0, 3, -2.2]", "coefficients", "reaches the lift"),
    ("[0, 3, -2]", "coefficients", "within [0, stroke]"),
    ("[0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]", "coefficients", "2 to 16"),
    ("[0, 0, 3, true]", "coefficients[3]", "finite number"),
    ("\"3u^2 - 2u^3\"", "coefficients", "array of numbers"),
])
def test_bad_polynomial_exits_2_with_one_line(tmp_path, rise, key, words):
    spec = tmp_path / "bad.toml"
    spec.write_text(_base(rise), encoding="utf-8")
    out = tmp_path / "o"
    proc = run_inprocess("cam", spec, "--no-plot", "--quiet", "--out", out)
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "bad.toml" in line and f"segments.0] {key}:" in line and words in line, line
    assert not (out / "cam.csv").exists()      # nothing half-written


def test_bad_polynomial_error_json(tmp_path):
    spec = tmp_path / "bad.toml"
    spec.write_text(_base("[0, 0, 3, -2.2]"), encoding="utf-8")
    proc = run_inprocess("cam", spec, "--json", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 2
    doc = json.loads(proc.stdout)
    assert "coefficients" in json.dumps(doc)
