"""Jumps are given from both sides: at a cam segment end (and at a force load window's edge)
the CSV has two rows at the same abscissa, the limit from the left first, then from the right
(issue 20, section 3).  Each row is checked against a closed form of the law (or load) that
holds on its side, written here independently of mechcli."""

import csv
import math

import numpy as np
import pytest

from tests.conftest import CONFIGS, run_json, write_spec


def _rows(path):
    with open(path, newline="", encoding="utf-8") as fh:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(fh)]


def _columns(rows):
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}


# ---------------------------------------------------------------- cam: 【例 4-2】

#: configs/ch4/ex4-2.toml (例 4-2): r0 = 30 mm flat face, h = 20 mm, cosine rise 120°,
#: cosine return 150°, dwell 90°
R0, H, RISE, RET = 30.0, 20.0, math.radians(120), math.radians(150)


def _cosine_rise(delta):
    """s, s', s'', s''' of the cosine (simple-harmonic) rise, 表 4-1: s = h/2 (1 − cos πδ/δ0)."""
    k = math.pi / RISE
    return (H / 2 * (1 - math.cos(k * delta)), H / 2 * k * math.sin(k * delta),
            H / 2 * k ** 2 * math.cos(k * delta), -H / 2 * k ** 3 * math.sin(k * delta))


def _cosine_return(delta):
    """The cosine return from δ = δ0, 表 4-1: s = h/2 (1 + cos π(δ − δ0)/δ0′)."""
    k, t = math.pi / RET, delta - RISE
    return (H / 2 * (1 + math.cos(k * t)), -H / 2 * k * math.sin(k * t),
            -H / 2 * k ** 2 * math.cos(k * t), H / 2 * k ** 3 * math.sin(k * t))


def _flat_row(s, s1, s2, s3, delta):
    """The flat-faced follower's columns (ccw cam): ρ′ = r0 + s + s″ (envelope of the face),
    contact point (s′, r0 + s) in the fixed frame turned by −δ into the cam frame, and the
    face offset s′ (eq. 4-4)."""
    x, y = s1, R0 + s
    c, sn = math.cos(-delta), math.sin(-delta)
    return {"s_mm": s, "v_mm_rad": s1, "a_mm_rad2": s2, "j_mm_rad3": s3,
            "rho_work_mm": R0 + s + s2, "x_work_mm": c * x - sn * y,
            "y_work_mm": sn * x + c * y, "face_offset_mm": s1, "pressure_angle_deg": 0.0}


def test_ex4_2_both_sides_of_the_rise_end(tmp_path):
    doc = run_json("cam", CONFIGS / "ch4" / "ex4-2.toml", "--out", tmp_path)
    rows = _rows(tmp_path / "cam.csv")
    at = [i for i, r in enumerate(rows) if r["delta_deg"] == 120.0]
    assert len(at) == 2 and at[1] == at[0] + 1          # two rows, next to each other
    before, after = rows[at[0]], rows[at[1]]
    # hand (issue 20): ρ′ = r0 + h − π²h/(2δ0²) = 30 + 20 − 22.5 = 27.5 mm from the left
    # (the minimum, rho_work_min), r0 + h − π²h/(2δ0′²) = 50 − 14.4 = 35.6 mm from the right
    assert before["rho_work_mm"] == pytest.approx(27.5, abs=1e-9)
    assert after["rho_work_mm"] == pytest.approx(35.6, abs=1e-9)
    assert doc["results"]["rho_work_min"] == pytest.approx(before["rho_work_mm"], abs=1e-9)
    # every column of each row against its own segment's law (CSV written to 10 digits)
    for row, law in ((before, _cosine_rise), (after, _cosine_return)):
        want = _flat_row(*law(RISE), RISE)
        for key, value in want.items():
            assert row[key] == pytest.approx(value, rel=1e-9, abs=1e-9), key
    # the report's table shows both rows too, the left limit first
    report = (tmp_path / "report.txt").read_text(encoding="utf-8")
    lines = [ln.split() for ln in report.splitlines() if ln.lstrip().startswith("120.0 ")]
    assert [ln[-1] for ln in lines] == ["27.5000", "35.6000"]


def test_ex4_2_every_jump_and_only_the_jumps_have_two_rows(tmp_path):
    run_json("cam", CONFIGS / "ch4" / "ex4-2.toml", "--out", tmp_path, "--step", "1")
    col = _columns(_rows(tmp_path / "cam.csv"))
    d = col["delta_deg"]
    assert np.all(np.diff(d) >= 0)
    twice = d[1:][np.diff(d) == 0]
    # the acceleration jumps of 例 4-2: 120° (rise → return), 270° (return → dwell) and the
    # wrap 360° ≡ 0° (dwell → rise); 0° itself has one row (nothing left of it)
    assert list(twice) == [120.0, 270.0, 360.0]
    assert len(d) == 361 + 3
    # at 270°: left ρ′ = r0 + 0 + π²h/(2δ0′²) = 30 + 14.4, right: the dwell's r0 = 30 mm
    i = int(np.flatnonzero(d == 270.0)[0])
    assert col["rho_work_mm"][i:i + 2] == pytest.approx([44.4, 30.0], abs=1e-9)
    # at 360°: the dwell's end, then the rise's start again (the first row, ρ′ = 30 + 22.5)
    assert col["a_mm_rad2"][-2:] == pytest.approx([0.0, H / 2 * (math.pi / RISE) ** 2])
    for key in col:          # the closing row repeats the first one (the profile closes)
        if key != "delta_deg":
            assert col[key][-1] == pytest.approx(col[key][0], abs=1e-9), key


def test_jump_between_grid_angles_gets_two_rows_at_its_exact_angle(tmp_path):
    # --points 514: the grid step 360/514° puts neither 120° nor 270° on the grid
    run_json("cam", CONFIGS / "ch4" / "ex4-2.toml", "--out", tmp_path, "--points", "514")
    col = _columns(_rows(tmp_path / "cam.csv"))
    d = col["delta_deg"]
    assert len(d) == 515 + 2 + 2 + 1      # grid, two rows at 120° and at 270°, one at 360°
    for where, rho in ((120.0, (27.5, 35.6)), (270.0, (44.4, 30.0))):
        k = np.flatnonzero(d == where)
        assert len(k) == 2 and tuple(col["rho_work_mm"][k]) == pytest.approx(rho, abs=1e-9)
        assert d[k[0] - 1] < where < d[k[1] + 1]


def test_continuous_segment_ends_keep_one_row(tmp_path):
    # the 4-5-6-7 polynomial has s′ = s″ = s‴ = 0 at both ends (its definition): against
    # dwells nothing jumps, so the CSV is the plain grid
    spec = write_spec(tmp_path, """command = "cam"
units = "mm"
[follower]
contact = "knife"
r0 = 50
[motion]
h = 20
segments = [
  { kind = "rise", angle = 90, law = "poly4567" },
  { kind = "dwell", angle = 90 },
  { kind = "return", angle = 90, law = "poly4567" },
  { kind = "dwell", angle = 90 },
]
""")
    res = run_json("cam", spec, "--out", tmp_path / "o", "--step", "1")["results"]
    assert res["impacts"] == []
    d = _columns(_rows(tmp_path / "o" / "cam.csv"))["delta_deg"]
    assert len(d) == 361 and np.all(np.diff(d) > 0)


# ------------------------------------------------------------- force: load switches

def _reference():
    """tests/reference/independent_force.py: its own geometry, finite-difference
    kinematics and one dense system per position; imports nothing from mechcli."""
    import importlib.util

    path = CONFIGS.parent / "tests" / "reference" / "independent_force.py"
    spec = importlib.util.spec_from_file_location("independent_force", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _pairs_of_rows(rows, key="theta1_deg"):
    d = np.array([r[key] for r in rows])
    at = np.flatnonzero(d[1:] == d[:-1])
    return [(rows[i], rows[i + 1]) for i in at]


def _explicit(config, theta, on):
    """mechcli's force pipeline at *theta* (rad) with the config's conditional load held
    off (left out) or on (its conditions removed), written out here rather than through
    the code that makes the CSV rows."""
    import dataclasses

    from mechcli.core.linkage.force_analysis import ForceEvaluator
    from mechcli.spec.force import load_force_spec

    spec = load_force_spec(config, ())
    progs = []
    for p in spec.loads:
        if not p.conditional:
            progs.append(p)
        elif on:
            progs.append(dataclasses.replace(p, window=None, velocity=None, sign=0, band=None,
                                             band_limits=None))
    pipe = ForceEvaluator(spec.linkage, spec.topology, spec.input.sweep(), spec.bodies,
                          spec.gravity, tuple(progs))
    fr, _masks, _motion = pipe(np.array([theta]))
    return fr


def _check_against_reference(prob, ref, row, theta, on, symbols):
    out, _kin, _act = ref.evaluate(prob, np.array([theta]), active=np.array([on]))
    scale = max(abs(out[s][0]) for s in symbols if s.startswith("FR"))
    for sym in symbols:
        unit = "_N_m" if sym.startswith(("Mb", "MR")) else "_N"
        # the CSV's 10 digits and the reference's finite differences (~1e-12): 1e-8 of the
        # largest force
        assert row[sym + unit] == pytest.approx(out[sym][0], abs=1e-8 * scale), sym
    # the reference's own power balance on this side of the switch
    assert out["power_residual_abs"][0] <= 1e-9 * out["power_scale"][0]


def test_ex2_4_cutting_force_switches_give_both_sides(tmp_path):
    from scipy.optimize import brentq

    from tests.cli.test_force_cli import shaper_cutting_band, shaper_sE

    config = CONFIGS / "ch2" / "ex2-4.toml"
    res = run_json("force", config, "--out", tmp_path)["results"]
    rows = _rows(tmp_path / "force.csv")
    assert len(rows) == 361 + 4          # 1° grid, two rows at each of the two switches
    (start, stop), = res["active_cutting_deg"]
    pairs = _pairs_of_rows(rows)
    assert [p[0]["theta1_deg"] for p in pairs] == pytest.approx([start, stop], abs=1e-8)
    # the cutting starts where the ram, moving left, enters the band sE = sEmax − 0.05H:
    # closed form of the shaper (tests/cli/test_force_cli.py), 0.0138673834°
    _lo, hi = shaper_cutting_band()
    th0 = brentq(lambda q: shaper_sE(q) - hi, -0.1, 0.3, xtol=1e-15)
    assert math.radians(start) == pytest.approx(th0, abs=1e-12)
    # without the load, then with it at the start; the reverse where it stops
    assert [(a["active_cutting"], b["active_cutting"]) for a, b in pairs] == [(0, 1), (1, 0)]
    ref = _reference()
    prob = ref.Shaper()
    prob.prepare()
    symbols = ["Mb", "FR16x", "FR16y", "FR12x", "FR12y", "FR23x", "FR23y", "MR23", "FR36x",
               "FR36y", "FR34x", "FR34y", "FR45x", "FR45y", "FR56x", "FR56y", "MR56"]
    for (first, second), deg in zip(pairs, (start, stop)):
        th = math.radians(deg)
        for row in (first, second):
            on = bool(row["active_cutting"])
            _check_against_reference(prob, ref, row, th, on, symbols)
            fr = _explicit(config, th, on)
            assert row["Mb_N_m"] == pytest.approx(float(fr.balancing[1][0]), rel=1e-9)
            # mechcli's power balance on this side (virtual power, per unit crank speed)
            assert abs(float(fr.power_residual[0])) <= 1e-9 * abs(row["Mb_N_m"])
        # the jump of the input power is the power of the cutting force alone (the motion,
        # inertia and weights are the same on both sides): P_on − P_off = −F vE, F = 5880 N
        # along +x on the ram, vE = ω1 dsE/dθ1 (ω1 = 1 rad/s) by a central difference of the
        # closed form (h = 1e-6 rad: error ~1e-12 of vE)
        h = 1e-6
        v = (shaper_sE(th + h) - shaper_sE(th - h)) / (2 * h)
        on_row, off_row = (second, first) if second["active_cutting"] else (first, second)
        assert on_row["P_W"] - off_row["P_W"] == pytest.approx(-5880.0 * v, rel=1e-7)


def test_exercise2_8_window_on_the_grid_gives_both_sides(tmp_path):
    config = CONFIGS / "ch2" / "exercise2-8.toml"
    run_json("force", config, "--out", tmp_path)
    rows = _rows(tmp_path / "force.csv")
    # when = { window = [90, 210] } on the 1° grid: the two rows replace the sample's row
    assert len(rows) == 361 + 2
    pairs = _pairs_of_rows(rows)
    assert [p[0]["theta1_deg"] for p in pairs] == pytest.approx([90.0, 210.0], abs=1e-9)
    assert [(a["active_ore"], b["active_ore"]) for a, b in pairs] == [(0, 1), (1, 0)]
    ref = _reference()
    prob = ref.Crusher()
    prob.prepare()
    symbols = ["Mb"] + [f"FR{ij}{c}" for ij in ("16", "12", "23", "24", "36", "45", "56")
                        for c in "xy"]
    for first, second in pairs:
        th = math.radians(first["theta1_deg"])
        for row in (first, second):
            on = bool(row["active_ore"])
            _check_against_reference(prob, ref, row, th, on, symbols)
            fr = _explicit(config, th, on)
            assert row["Mb_N_m"] == pytest.approx(float(fr.balancing[1][0]), rel=1e-9)
            assert abs(float(fr.power_residual[0])) <= 1e-9 * max(abs(row["Mb_N_m"]), 1.0)
        # the jump of the input power is minus the power of the 300 N ore force, F·v at its
        # point S5, from the reference's kinematics (finite differences, m/s)
        _out, kin, _a = ref.evaluate(prob, np.array([th]), active=np.array([True]))
        (_link, force, point, _c), = prob.loads(kin, np.array([True]))
        power = float(force[0] @ kin["vel"][point][0])
        on_row, off_row = (second, first) if second["active_ore"] else (first, second)
        assert on_row["P_W"] - off_row["P_W"] == pytest.approx(-power, rel=1e-7)
