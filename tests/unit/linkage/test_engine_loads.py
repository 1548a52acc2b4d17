"""Engine loads of ``mechcli force``: gas pressure on a piston and the engine's named results.

References
----------
* configs/ch2/engine-steam-horizontal.toml: a published worked example (sarthaks.com
  q. 491480, Khurmi & Gupta's horizontal steam engine): F_L = 70685.83 N, F_I = 4319.68 N,
  F_P = 66.366 kN printed; the series with the solution's rounded ω = 25.13, n = 4.167
  gives the printed F_I, which is checked here with an independent evaluation.
* configs/ch2/engine-steam-double-acting.toml: Bevan, The Theory of Machines, ch. 12
  Example 3 (printed T = 6110 lb·ft with the series crank-effort arm).
* An independent closed form of the centred and offset slider-crank written below (own
  geometry, the textbook relations F_Q = F_P / cos φ, F_N = F_P tan φ, F_T = F_Q sin(θ+φ),
  T = F_T r, exact piston acceleration differentiated by hand): every row of the CSV.
* The power balance: with a massless crank, T = −Mb; with a massless rod, F_P = F_L − F_I.
"""

import csv
import math

import numpy as np
import pytest

from tests.conftest import ROOT, one_line_error, run_inprocess, run_json

STEAM = ROOT / "configs" / "ch2" / "engine-steam-horizontal.toml"
BEVAN = ROOT / "configs" / "ch2" / "engine-steam-double-acting.toml"


# ---------------------------------------------------------------------------
# an independent slider-crank (imports nothing from mechcli)
# ---------------------------------------------------------------------------
def closed_form(theta, r, l, e, omega, m, FL):
    """Textbook forces of a slider-crank with the slider to the right of the crank
    pivot, guide y = e, massless crank and rod, piston mass m [kg], gas force FL toward
    the crank [N].  θ from +x, counter-clockwise ω.  Returns a dict of arrays.

    Geometry: pin B = r(cos θ, sin θ); the rod angle β from the piston to B satisfies
    l sin β' = r sin θ − e for β' the rod's angle to the line of stroke, piston
    x = r cos θ + l cos β'.  Differentiating twice at constant ω:
    x' = −r sin θ − l sin β' β'',  with β'_θ = r cos θ / (l cos β').
    """
    theta = np.asarray(theta, dtype=float)
    sb = (r * np.sin(theta) - e) / l
    cb = np.sqrt(1 - sb * sb)
    db = r * np.cos(theta) / (l * cb)                       # dβ'/dθ
    ddb = (-r * np.sin(theta) + l * sb * db * db) / (l * cb)  # d²β'/dθ²
    xdd = -r * np.cos(theta) - l * (cb * db * db + sb * ddb)  # d²x/dθ²
    acc_toward_crank = -xdd * omega ** 2                      # d = −x
    FI = m * acc_toward_crank
    FP = FL - FI
    phi = np.arcsin(sb)                                       # rod's angle to the stroke
    FQ = FP / np.cos(phi)
    FN = FP * np.tan(phi)
    FT = FQ * np.sin(theta + phi)
    return {"FI": FI, "FP": FP, "FQ": FQ, "FN": FN, "FT": FT, "T": FT * r,
            "Frad": FQ * np.cos(theta + phi)}


def _csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def _spec(tmp_path, text, name="e.toml"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


ENGINE = """command = "force"
units = "mm"
[mechanism]
type = "slider_crank"
l1 = 60
l2 = 240
e = {e}
[input]
omega1 = 188.49555921538757
step = 1
[[link]]
number = 3
mass = 1.2
[[load]]
name = "gas"
link = 3
{pressure}
pressure_unit = "kPa"
bore = 80
"""


def _run(tmp_path, text, *extra):
    spec = _spec(tmp_path, text)
    out = tmp_path / "out"
    doc = run_json("force", spec, "--out", out, "--digits", "17", *extra)
    return doc["results"], _csv(out / "force.csv")


# ---------------------------------------------------------------------------
# published examples
# ---------------------------------------------------------------------------
def test_published_steam_engine_approximate_model(tmp_path):
    res = run_json("force", STEAM, "--out", tmp_path)["results"]
    assert res["model"] == "approximate"
    # printed F_L = 70685.83 N (its last digit)
    assert res["FL_at_60deg_N"] == pytest.approx(70685.83, abs=0.005)
    # printed F_I = 4319.68 N from the series with the solution's ω = 25.13, n = 4.167;
    # the same series with exact ω = 8π, n = 1.25/0.3, evaluated independently here:
    th = math.radians(60)
    printed_inputs = 60 * 25.13 ** 2 * 0.3 * (math.cos(th) + math.cos(2 * th) / 4.167)
    assert printed_inputs == pytest.approx(4319.68, abs=0.005)
    exact_inputs = 60 * (8 * math.pi) ** 2 * 0.3 * (math.cos(th) + math.cos(2 * th) / (1.25 / 0.3))
    assert res["FI_at_60deg_N"] == pytest.approx(exact_inputs, rel=1e-12)
    # printed F_P = 66.366 kN (within the 0.83 N of the rounding of ω and n)
    assert res["FP_at_60deg_N"] == pytest.approx(66366, abs=1.0)
    assert res["FP_at_60deg_N"] == pytest.approx(res["FL_at_60deg_N"] - res["FI_at_60deg_N"],
                                                 rel=1e-12)
    # the turning moment from the printed piston effort by the closed form
    phi = math.asin(math.sin(th) / (1.25 / 0.3))
    T = res["FP_at_60deg_N"] * math.sin(th + phi) / math.cos(phi) * 0.3
    assert res["T_at_60deg_N_m"] == pytest.approx(T, rel=1e-12)
    assert res["Mb_at_60deg_N_m"] == pytest.approx(-T, rel=1e-12)
    assert res["power_balance_residual"] < 1e-12


def test_bevan_double_acting_with_piston_rod(tmp_path):
    res = run_json("force", BEVAN, "--out", tmp_path)["results"]
    lbf, ft = 4.4482216152605, 0.3048
    A, a = math.pi * 81 / 4, math.pi * 4 / 4
    F = (160 * A - 32 * (A - a)) * lbf                       # the book's F, in N
    assert res["FL_at_40deg_N"] == pytest.approx(F, rel=1e-12)
    th, n = math.radians(40), 5.0
    series_arm = math.sin(th) + math.sin(2 * th) / (2 * n)   # Bevan's eq. 3.11
    exact_arm = math.sin(th) + math.sin(2 * th) / (2 * math.sqrt(n * n - math.sin(th) ** 2))
    T_book = res["T_at_40deg_N_m"] * series_arm / exact_arm / (lbf * ft)
    assert 6110 <= T_book < 6111                             # printed 6110 lb·ft (rounded down)
    assert res["T_at_40deg_N_m"] / (lbf * ft) == pytest.approx(6117.468, abs=5e-4)


# ---------------------------------------------------------------------------
# independent closed form at every position
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("e", [0, 15])
def test_every_row_matches_the_closed_form(tmp_path, e):
    res, rows = _run(tmp_path, ENGINE.format(e=e, pressure="pressure = 800"))
    theta = np.radians(rows["theta1_deg"])
    FL = 800e3 * math.pi / 4 * 0.08 ** 2
    ref = closed_form(theta, 0.06, 0.24, e * 1e-3, 188.49555921538757, 1.2, FL)
    scale = np.max(np.abs(ref["FP"]))
    np.testing.assert_allclose(rows["FL_N"], FL, rtol=1e-13)
    for sym in ("FI", "FP", "FQ", "FN", "FT", "Frad"):
        np.testing.assert_allclose(rows[f"{sym}_N"], ref[sym], atol=1e-10 * scale, err_msg=sym)
    np.testing.assert_allclose(rows["T_N_m"], ref["T"], atol=1e-10 * scale * 0.06)
    # power balance: the massless crank's balancing torque is minus the rod's moment
    np.testing.assert_allclose(rows["Mb_N_m"], -rows["T_N_m"], atol=1e-10 * scale * 0.06)
    assert res["power_balance_residual"] < 1e-12
    # the offset slider-crank's stroke and dead centres (closed form)
    r, l, ee = 60.0, 240.0, float(e)
    stroke = math.sqrt((l + r) ** 2 - ee ** 2) - math.sqrt((l - r) ** 2 - ee ** 2)
    assert res["stroke_mm"] == pytest.approx(stroke, rel=1e-13)
    assert res["head_end_at_deg"] == pytest.approx(
        math.degrees(math.atan2(ee, math.sqrt((l + r) ** 2 - ee ** 2))) % 360, abs=1e-12)
    # the refined extremes are at least the grid's and agree with a fine closed form
    fine = np.radians(np.arange(0, 360, 0.001))
    ref_f = closed_form(fine, 0.06, 0.24, e * 1e-3, 188.49555921538757, 1.2, FL)
    assert res["T_max_N_m"] == pytest.approx(np.max(ref_f["T"]), rel=1e-9)
    assert res["FN_min_N"] == pytest.approx(np.min(ref_f["FN"]), rel=1e-9)


def test_gravity_on_a_vertical_engine_adds_the_weight_to_the_piston_effort(tmp_path):
    """A vertical engine (guide along y): F_P = F_L − F_I + m g (Khurmi's vertical engine
    rule), checked at every row against the same closed form rotated by 90°."""
    text = ENGINE.format(e=0, pressure="pressure = 800").replace(
        'type = "slider_crank"\nl1 = 60\nl2 = 240\ne = 0\n', "type = \"general\"\nframe = 4\n"
        "ground = { A = [0, 0] }\n"
        "[[mechanism.driver]]\ntype = \"crank\"\nlink = 1\npivot = \"A\"\npoint = \"B\"\n"
        "length = 60\n"
        "[[mechanism.dyad]]\ntype = \"RRP\"\njoint = \"C\"\npoint = \"B\"\nlink = 2\n"
        "length = 240\nslider = 3\nguide_link = 4\nguide_point = \"A\"\n"
        "guide_angle = 90\nbranch = \"left\"\n")
    text += "[gravity]\ng = 9.81\n"
    spec = _spec(tmp_path, text)
    proc = run_inprocess("force", spec, "--out", tmp_path / "o", "--no-plot", "-q")
    assert proc.returncode == 0, proc.stderr
    rows = _csv(tmp_path / "o" / "force.csv")
    FL = 800e3 * math.pi / 4 * 0.08 ** 2
    np.testing.assert_allclose(rows["FP_N"], FL - rows["FI_N"] + 1.2 * 9.81, rtol=1e-11,
                               atol=1e-9 * FL)


# ---------------------------------------------------------------------------
# pressure as a table, an indicator diagram, a double-acting piston
# ---------------------------------------------------------------------------
def test_pressure_against_crank_angle_is_interpolated(tmp_path):
    res, rows = _run(tmp_path, ENGINE.format(
        e=0, pressure="pressure = { angle = [0, 90, 360], value = [2000, 500, 2000] }"))
    area = math.pi / 4 * 0.08 ** 2
    th = rows["theta1_deg"]
    p = np.interp(th, [0, 90, 360], [2000e3, 500e3, 2000e3])
    np.testing.assert_allclose(rows["FL_N"], p * area, rtol=1e-13)


def test_indicator_diagram_of_two_strokes(tmp_path):
    """Out-stroke (θ in [0, 180)) on the first curve, return stroke on the second, both
    against the fraction of the stroke from the head end (x/stroke = (1 − cos θ)/2 + …)."""
    pressure = ("pressure = { fraction = [0, 0.5, 1], strokes = [[3000, 1000, 400], "
                "[100, 300, 900]] }")
    res, rows = _run(tmp_path, ENGINE.format(e=0, pressure=pressure))
    area = math.pi / 4 * 0.08 ** 2
    th = np.radians(rows["theta1_deg"])
    x = 60 * np.cos(th) + np.sqrt(240 ** 2 - (60 * np.sin(th)) ** 2)   # pin from A [mm]
    frac = (300 - x) / 120
    out = np.interp(frac, [0, 0.5, 1], [3000e3, 1000e3, 400e3])
    back = np.interp(frac, [0, 0.5, 1], [100e3, 300e3, 900e3])
    first = np.mod(th, 2 * np.pi) < np.pi
    np.testing.assert_allclose(rows["FL_N"], np.where(first, out, back) * area,
                               rtol=1e-11, atol=1e-6)


def test_four_stroke_indicator_over_two_turns(tmp_path):
    pressure = ("pressure = { x = [0, 120], strokes = [[4000, 400], [100, 100], "
                "[0, 0], [100, 1000]] }")
    text = ENGINE.format(e=0, pressure=pressure).replace("step = 1", "stop = 720\nstep = 1")
    text += "[output]\nat = [90, 270, 450, 630]\n"
    res, rows = _run(tmp_path, text)
    area = math.pi / 4 * 0.08 ** 2
    # x at 90° and 270°: 60 (1 − 0) + 240 − √(240² − 60²) [mm] from the head end
    x = 300 - math.sqrt(240 ** 2 - 60 ** 2)
    f = x / 120
    assert res["FL_at_90deg_N"] == pytest.approx((4000 + (400 - 4000) * f) * 1e3 * area, rel=1e-12)
    assert res["FL_at_270deg_N"] == pytest.approx(100e3 * area, rel=1e-12)
    assert res["FL_at_450deg_N"] == pytest.approx(0.0, abs=1e-9)
    assert res["FL_at_630deg_N"] == pytest.approx((100 + 900 * f) * 1e3 * area, rel=1e-12)


def test_double_acting_with_rod(tmp_path):
    pressure = "pressure = 800\ncrank_side_pressure = 200\nrod = 20"
    res, rows = _run(tmp_path, ENGINE.format(e=0, pressure=pressure))
    A, a = math.pi / 4 * 0.08 ** 2, math.pi / 4 * 0.02 ** 2
    np.testing.assert_allclose(rows["FL_N"], 800e3 * A - 200e3 * (A - a), rtol=1e-13)


# ---------------------------------------------------------------------------
# the approximate model
# ---------------------------------------------------------------------------
def test_approximate_inertia_and_its_difference_to_the_exact_model(tmp_path):
    res, rows = _run(tmp_path, ENGINE.format(e=0, pressure="pressure = 800"),
                     "--set", 'mechanism.model="approximate"')
    w, r, n = 188.49555921538757, 0.06, 4.0
    th = np.radians(rows["theta1_deg"])
    series = 1.2 * w * w * r * (np.cos(th) + np.cos(2 * th) / n)
    np.testing.assert_allclose(rows["FI_N"], series, rtol=1e-12, atol=1e-9)
    FL = 800e3 * math.pi / 4 * 0.08 ** 2
    np.testing.assert_allclose(rows["FP_N"], FL - series, rtol=1e-12)
    exact = closed_form(th, r, 0.24, 0.0, w, 1.2, FL)
    assert res["approx_error_FI_max_N"] == pytest.approx(np.max(np.abs(series - exact["FI"])),
                                                         rel=1e-9)
    assert res["approx_error_FI_max_rel"] == pytest.approx(
        np.max(np.abs(series - exact["FI"])) / np.max(np.abs(exact["FI"])), rel=1e-9)
    assert res["approx_error_T_max_N_m"] > 0
    assert res["model"] == "approximate"
    # the power balance still checks the solve (of the loads as given)
    assert res["power_balance_residual"] < 1e-12


# ---------------------------------------------------------------------------
# bad input: one line naming the key, exit 2
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("pressure, key", [
    ("pressure = { angle = [0, 90, 180], value = [1, 2, 3] }", "[load.0.pressure] angle"),
    ("pressure = { fraction = [0, 0.9], value = [1, 2] }", "[load.0.pressure] fraction"),
    ("pressure = { x = [0, 100], value = [1, 2] }", "[load.0.pressure] x"),
    ("pressure = { fraction = [0, 1], strokes = [[1, 2], [1, 2], [1, 2]] }",
     "[load.0.pressure] strokes"),
    ("pressure = { fraction = [0, 1], value = [1] }", "[load.0.pressure] value"),
    ("pressure = { angle = [0, 360], fraction = [0, 1], value = [1, 2] }",
     "[load.0.pressure] angle"),
    ("pressure = 800\nrod = 90\ncrank_side_pressure = 1", "[load.0] rod"),
    ("pressure = 800\nrod = 10", "[load.0] rod"),
    ("pressure = 800\nforce = [1, 0]", "[load.0] force"),
    ("pressure = 800\narea = 5000", "[load.0] bore"),
    ("pressure = 800\npressure_unit = \"psf\"", "[load.0] pressure_unit"),
])
def test_bad_pressure_loads(tmp_path, pressure, key):
    text = ENGINE.format(e=0, pressure=pressure)
    if "pressure_unit = \"psf\"" in pressure:
        text = text.replace('pressure_unit = "kPa"\n', "", 1)
    proc = run_inprocess("force", _spec(tmp_path, text), "--out", tmp_path / "o", "--no-plot",
                         "-q")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert key in line, line


def test_pressure_on_a_link_that_is_not_a_piston(tmp_path):
    text = ENGINE.format(e=0, pressure="pressure = 800").replace("link = 3\npressure",
                                                                 "link = 2\npressure")
    proc = run_inprocess("force", _spec(tmp_path, text), "--out", tmp_path / "o", "-q")
    assert proc.returncode == 2
    assert "[load.0] link" in one_line_error(proc)


def test_missing_pressure_unit_and_pressure_keys_without_pressure(tmp_path):
    text = ENGINE.format(e=0, pressure="pressure = 800").replace('pressure_unit = "kPa"\n', "")
    proc = run_inprocess("force", _spec(tmp_path, text), "--out", tmp_path / "o", "-q")
    assert proc.returncode == 2 and "[load.0] pressure_unit" in one_line_error(proc)
    text = ENGINE.format(e=0, pressure="torque = 5").replace('\npressure_unit = "kPa"\nbore = 80',
                                                             "\nbore = 80")
    proc = run_inprocess("force", _spec(tmp_path, text, "f.toml"), "--out", tmp_path / "p",
                         "-q")
    assert proc.returncode == 2 and "[load.0] bore" in one_line_error(proc)


def test_output_at_outside_the_sweep(tmp_path):
    text = ENGINE.format(e=0, pressure="pressure = 800") + "[output]\nat = [400]\n"
    proc = run_inprocess("force", _spec(tmp_path, text), "--out", tmp_path / "o", "-q")
    assert proc.returncode == 2 and "[output] at[0]" in one_line_error(proc)


# ---------------------------------------------------------------------------
# review 2: schema forms, table ends, tolerances, rotation, cycle, mean, names, units
# ---------------------------------------------------------------------------
FOUR = ROOT / "configs" / "ch2" / "engine-four-stroke-indicator.toml"


@pytest.mark.parametrize("form", [
    '{ angle = [0, 360], value = [1, 1] }',
    '{ fraction = [0, 1], strokes = [[1, 1], [0, 0]] }',
    '{ fraction = [0, 1], value = [1, 2] }',
    '{ x = [0, 120], value = [1, 2] }',
    '{ x = [0, 120], strokes = [[1, 1], [0, 0], [0, 0], [1, 1]] }',
])
def test_every_crank_side_pressure_form_is_in_the_schema(tmp_path, form):
    """The shipped schema admits every form the reader accepts on both sides."""
    import json

    from mechcli.spec.reader import tomllib
    from mechcli.spec.schema import shipped_schema_text
    from tests.cli.test_schema import errors, valid   # jsonschema's verdict too, if installed
    text = ENGINE.format(e=0, pressure=f"pressure = 800\ncrank_side_pressure = {form}")
    if "720" not in text and "[0, 0], [1, 1]" in form:
        text = text.replace("step = 1", "stop = 720\nstep = 1")
    schema = json.loads(shipped_schema_text("force"))
    for data in (tomllib.loads(text),
                 tomllib.loads(text.replace("pressure = 800\n", f"pressure = {form}\n", 1))):
        assert errors(schema, data) == [] and valid(schema, data), errors(schema, data)
    proc = run_inprocess("force", _spec(tmp_path, text), "--out", tmp_path / "o",
                         "--no-plot", "-q")
    assert proc.returncode == 0, proc.stderr


def test_angle_table_with_unequal_ends_is_not_repeated(tmp_path):
    """angle = [0, 180, 360], value = [10, 5, 1] over 0 … 360: read as it stands, so
    360° has the last value (1 bar; before the fix it repeated and gave 10 bar); over
    90 … 450 it would have to repeat: exit 2 naming the values at both ends."""
    pressure = "pressure = { angle = [0, 180, 360], value = [10, 5, 1] }"
    text = ENGINE.format(e=0, pressure=pressure).replace('"kPa"', '"bar"')
    text += "[output]\nat = [0, 270, 360]\n"
    res, _rows = _run(tmp_path, text)
    area = math.pi / 4 * 0.08 ** 2
    assert res["FL_at_360deg_N"] == pytest.approx(1e5 * area, rel=1e-13)    # by hand
    assert res["FL_at_0deg_N"] == pytest.approx(10e5 * area, rel=1e-13)
    assert res["FL_at_270deg_N"] == pytest.approx(3e5 * area, rel=1e-13)    # 5 − 4·90/180
    bad = text.replace("step = 1", "start = 90\nstop = 450\nstep = 1").replace(
        "at = [0, 270, 360]", "at = [270]")
    proc = run_inprocess("force", _spec(tmp_path, bad, "b.toml"), "--out", tmp_path / "b",
                         "-q")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[load.0.pressure] value" in line and "10 at 0°" in line and "1 at 360°" in line


def test_flat_extremes_are_located_within_their_stated_tolerance(tmp_path):
    """The published steam engine (centred, constant pressures, the series inertia with
    n = 4.17 > 4): FI, FP and Fsh are extreme at the crank-end dead centre 180° by
    symmetry; the stated tolerance must contain 180 and stay small.  FL is constant:
    no location; the round-off Msh and MR34 (~1e-12 N·m) do not set the heading."""
    out = tmp_path / "o"
    res = run_json("force", STEAM, "--out", out, "--no-plot")["results"]
    for key in ("FI_min_at_deg", "FP_max_at_deg", "Fsh_max_at_deg", "Frad_min_at_deg"):
        tol = res[key + "_tol"]
        assert abs(res[key] - 180.0) <= tol < 1e-3, (key, res[key], tol)
    for key in ("FI_max_at_deg", "FP_min_at_deg"):       # 0° by the same symmetry
        assert abs(res[key]) <= res[key + "_tol"] < 1e-3
    assert "FL_max_at_deg" not in res and "FL_min_at_deg" not in res
    assert res["FL_max_N"] == res["FL_min_N"]
    report = (out / "report.txt").read_text(encoding="utf-8")
    head = [ln for ln in report.splitlines() if ln.startswith("Extremes")][0]
    step = float(head.split("±")[1].split("°")[0])
    assert step <= 1e-3, head
    assert "constant" in report


def test_no_mass_gives_a_constant_inertia_force_without_location(tmp_path):
    text = ENGINE.format(e=0, pressure="pressure = 800").replace(
        "[[link]]\nnumber = 3\nmass = 1.2\n", "")
    res, rows = _run(tmp_path, text)
    assert res["FI_max_N"] == 0 and res["FI_min_N"] == 0
    assert "FI_max_at_deg" not in res and "FI_max_at_deg_tol" not in res


def test_indicator_strokes_follow_a_clockwise_crank(tmp_path):
    """ω1 < 0: the first stroke (expansion, 10 → 2 bar) begins at the head end and runs
    through decreasing θ1 (360° → 180°).  By hand: at 270° the piston is at the fraction
    f = (300 − √(240² − 60²))/120 of the stroke, p = 10 − 8 f bar; at 90° it is on the
    return stroke, p = 0.  The gas does the net indicator work W = A · stroke · (mean of
    10 → 2 bar) = A · 0.12 m · 6e5 Pa per turn on the crank, so the balancing torque
    absorbs it: mean Mb · ω1 = −W / 2π · |ω1| (Mb mean = +W / 2π)."""
    pressure = "pressure = { fraction = [0, 1], strokes = [[10, 2], [0, 0]] }"
    text = ENGINE.format(e=0, pressure=pressure).replace('"kPa"', '"bar"').replace(
        "omega1 = 188.49555921538757", "omega1 = -188.49555921538757")
    text += "[output]\nat = [90, 270]\n"
    res, _rows = _run(tmp_path, text)
    area = math.pi / 4 * 0.08 ** 2
    f = (300 - math.sqrt(240 ** 2 - 60 ** 2)) / 120
    assert res["FL_at_270deg_N"] == pytest.approx((10 - 8 * f) * 1e5 * area, rel=1e-12)
    assert res["FL_at_90deg_N"] == pytest.approx(0.0, abs=1e-9)
    W = area * 0.12 * 6e5
    assert res["Mb_mean_N_m"] == pytest.approx(W / (2 * math.pi), rel=1e-10)


def test_four_strokes_over_one_turn_warn(tmp_path):
    pressure = ("pressure = { fraction = [0, 1], strokes = [[1, 2], [3, 4], [5, 6], "
                "[7, 8]] }")
    proc = run_inprocess("force", _spec(tmp_path, ENGINE.format(e=0, pressure=pressure)),
                         "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    assert "four-stroke indicator diagram" in proc.stderr and "720" in proc.stderr
    text = ENGINE.format(e=0, pressure=pressure).replace("step = 1", "stop = 720\nstep = 1")
    proc = run_inprocess("force", _spec(tmp_path, text, "f.toml"), "--out", tmp_path / "p",
                         "--no-plot")
    assert proc.returncode == 0 and "four-stroke" not in proc.stderr


@pytest.mark.parametrize("step", ["1", "5", "10"])
def test_mean_of_a_tabulated_indicator_diagram_is_exact(tmp_path, step):
    """The four-stroke config: mean Mb = −(net indicator work)/4π = −105.1875 N·m by hand
    (configs/ch2/engine-four-stroke-indicator.toml), whatever the step: the table's kinks
    and the dead centres' jumps are split points of the quadrature."""
    res = run_json("force", FOUR, "--out", tmp_path, "--no-plot", "--set",
                   f"input.step={step}")["results"]
    assert res["Mb_mean_N_m"] == pytest.approx(-105.1875, rel=1e-12)


def test_output_at_names_distinct_inputs_and_refuses_duplicates(tmp_path):
    text = ENGINE.format(e=0, pressure="pressure = 800")
    res, _rows = _run(tmp_path, text, "--set", "output.at=[10.0000001, 10.0000004, 10]")
    keys = sorted(k for k in res if k.startswith("FL_at_"))
    assert keys == ["FL_at_10deg_N", "FL_at_10p0000001deg_N", "FL_at_10p0000004deg_N"]
    proc = run_inprocess("force", _spec(tmp_path, text, "d.toml"), "--out", tmp_path / "d",
                         "-q", "--set", "output.at=[10, 20, 10.0000000001]")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "[output] at[2]" in line and "at[0]" in line


def test_crank_that_cannot_turn_is_worded_in_the_spec_units(tmp_path):
    """rod 240 mm, crank 60 mm, offset 200 mm: 240 < 60 + 200 (the spec's own numbers)."""
    proc = run_inprocess("force", _spec(tmp_path, ENGINE.format(e=200, pressure="pressure = 8")
                                        .replace("step = 1", "step = 1\npartial = true")),
                         "--out", tmp_path / "o", "-q")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "rod 240 mm ≤ crank 60 mm + offset 200 mm" in line, line


@pytest.mark.parametrize("value", ['"high"', "true", "[1, 2]"])
def test_a_pressure_of_the_wrong_type_is_refused_by_schema_and_reader(tmp_path, value):
    import json

    from mechcli.spec.reader import tomllib
    from mechcli.spec.schema import shipped_schema_text
    from tests.cli.test_schema import valid   # jsonschema's verdict too, if installed
    text = ENGINE.format(e=0, pressure=f"pressure = 800\ncrank_side_pressure = {value}")
    schema = json.loads(shipped_schema_text("force"))
    for t in (text, text.replace("pressure = 800\n", f"pressure = {value}\n", 1)):
        assert not valid(schema, tomllib.loads(t))
    proc = run_inprocess("force", _spec(tmp_path, text), "--out", tmp_path / "o", "-q")
    assert proc.returncode == 2
    assert "[load.0] crank_side_pressure" in one_line_error(proc)
