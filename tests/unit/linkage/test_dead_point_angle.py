"""A dead point is one input with its uncertainty (``SweepResult.dead_points``, JSON
``dead_points_deg`` / ``dead_points_tol_deg``), not an interval whose width the singular
threshold (sin γ <= 1e-7) sets.

References are closed forms (cosine law) written here, independent of the engine:

* a change-point four-bar (s + l = p + q) folds flat where BD = l1 + l4 = l2 + l3:
  θ1 = 180° exactly (cos θ1 = (l1² + l4² − (l2 + l3)²) / (2 l1 l4) = −1);
* a six-bar whose second dyad C-F-G touches |l5 − l6| = |CG| where the rocker of 例 1-1
  points at G: θ3 = 120°, and θ1 from the cosine law in triangle ABC;
* a slider-crank driven by its slider stops at s = √((l1 + l2)² − e²) (Pythagoras).
"""

import json
import math

import numpy as np
import pytest

from mechcli.core.linkage import RRR, Crank, Ground, Linkage, SliderDriver
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities
from tests.conftest import CONFIGS, run_inprocess, write_spec

L1, L2, L3, L4 = 101.6, 254, 177.8, 304.8   # 例 1-1 (configs/ch1/ex1-1.toml), mm


def fourbar(l1, l2, l3, l4):
    return Linkage(4, (Ground("A", 0, 0), Ground("D", l4, 0), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, 1)))


def sweep(lk, q, driver=1, periodic=True, speed=10.0):
    qs = default_quantities(lk, 2)
    return analyse_sweep(lk, Sweep(driver, q, speed, 0.0, {}, periodic), qs, 2, partial=True)


def turn(step=1.0):
    return np.radians(np.arange(0.0, 360.0 + step / 2, step))


@pytest.mark.parametrize("step", [1.0, 0.7, 5.0])
def test_ex1_1_at_its_change_point_has_one_dead_point_at_180(step):
    # 例 1-1 with the frame moved to l4 = l2 + l3 - l1 = 330.2 mm: a change point
    res = sweep(fourbar(L1, L2, L3, L2 + L3 - L1), turn(step))
    (dp,) = res.dead_points
    assert dp.joint == "C" and dp.shape == "touch"
    assert abs(dp.at - math.pi) <= dp.tol
    assert dp.tol < 1e-10                      # not the 2e-7 rad of the excluded interval
    (a, b, why), = res.excluded
    assert why == "dead point" and a < dp.at < b and b - a > 100 * dp.tol


def six_bar():
    """例 1-1 plus a dyad C-F-G (CF = 300, FG = 77.8 mm) with G = D + 400 mm at 120°:
    |CG| >= 400 - l3 = 222.2 = CF - FG, equal where the rocker points at G."""
    phi, rho = math.radians(120.0), 400.0
    g = (L4 + rho * math.cos(phi), rho * math.sin(phi))
    return Linkage(6, (Ground("A", 0, 0), Ground("D", L4, 0), Ground("G", *g),
                       Crank(1, "A", "B", L1), RRR("C", "B", 2, L2, "D", 3, L3, 1),
                       RRR("F", "C", 4, 300.0, "G", 5, 77.8, 1)))


def six_bar_dead_points():
    """θ1 where θ3 = 120°: C = D + l3 e^(i 120°); θ1 = arg(C) ± angle BAC, with
    cos BAC = (l1² + AC² − l2²) / (2 l1 AC).  Returns (108.0796°, 322.9132°) in rad."""
    c = (L4 + L3 * math.cos(math.radians(120)), L3 * math.sin(math.radians(120)))
    ac = math.hypot(*c)
    bac = math.acos((L1 ** 2 + ac ** 2 - L2 ** 2) / (2 * L1 * ac))
    base = math.atan2(c[1], c[0])
    return sorted(((base + bac) % (2 * math.pi), (base - bac) % (2 * math.pi)))


def test_six_bar_dead_points_at_the_cosine_law_angles():
    ref = six_bar_dead_points()
    assert [round(math.degrees(x), 4) for x in ref] == [108.0796, 322.9132]
    res = sweep(six_bar(), turn(1.0))
    assert [d.joint for d in res.dead_points] == ["F", "F"]
    for d, r in zip(res.dead_points, ref):
        assert abs(d.at - r) <= d.tol + 1e-14, (d.at - r, d.tol)
        assert d.tol < 1e-10
    # the old report: the middle of the threshold-set interval, 1e-7 rad wide
    for (a, b, _w), d in zip(res.excluded, res.dead_points):
        assert b - a > 1e-8 and a < d.at < b


def test_parallelogram_dead_points_once_each_through_the_seam():
    res = sweep(fourbar(100, 300, 100, 300), turn(1.0))
    ats = [d.at for d in res.dead_points]
    assert len(ats) == 2           # 0° and 360° are one position
    assert abs(ats[0]) <= res.dead_points[0].tol and abs(ats[1] - math.pi) <= \
        res.dead_points[1].tol


def test_slider_driven_slider_crank_ends_on_a_limit_of_assembly_not_a_dead_point():
    """The sweep ends exactly where crank and rod line up: the linkage does not assemble
    beyond, so it is a limit of assembly (what a gap's end is), not a dead point (a zero of
    sin γ with the linkage assembled on both sides; docs/accuracy.md §4).  Reported as a
    ``cannot assemble`` interval from the limit to the sweep's end, the limit located to its
    ``excluded_tol``, and no dead point."""
    l1, l2, e = 0.1, 0.3, 0.02
    s_end = math.sqrt((l1 + l2) ** 2 - e ** 2)   # crank and rod in line: 0.3994997 m
    lk = Linkage(4, (Ground("A", 0, 0), Ground("O", 0, e), SliderDriver(3, "O", "C"),
                     RRR("B", "A", 1, l1, "C", 2, l2, -1)))
    q = np.linspace(0.25, s_end, 401)
    res = sweep(lk, q, driver=3, periodic=False, speed=1.0)
    assert res.dead_points == []
    (a, b, why), = res.excluded
    (ta, _tb), = res.excluded_tol
    assert why == "cannot assemble" and b == q[-1]
    assert abs(a - s_end) <= ta < 1e-12
    # the same limit swept past (a gap from it to 0.45 m) is the same interval's start
    past = sweep(lk, np.linspace(0.25, 0.45, 401), driver=3, periodic=False, speed=1.0)
    (a2, _b2, why2), = past.excluded
    assert why2 == "cannot assemble" and past.dead_points == []
    assert abs(a2 - s_end) <= past.excluded_tol[0][0] < 1e-12


def test_no_dead_point_no_entry():
    res = sweep(fourbar(L1, L2, L3, L4), turn(1.0))
    assert res.dead_points == [] and res.excluded == []


PARALLELOGRAM = """\
command = "kin"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 100
l2 = 300
l3 = 100
l4 = 300
[input]
omega1 = 10
step = 1
partial = true
"""


def test_kin_json_and_report_give_one_angle_with_its_uncertainty(tmp_path):
    spec = write_spec(tmp_path, PARALLELOGRAM)
    proc = run_inprocess("kin", spec, "--json", "--no-plot", "-o", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    r = json.loads(proc.stdout)["results"]
    assert r["dead_points_deg"] == pytest.approx([0.0, 180.0], abs=1e-8)
    assert all(0 < t < 1e-8 for t in r["dead_points_tol_deg"])
    assert [d["joint"] for d in r["dead_points"]] == ["C", "C"]
    assert len(r["excluded"]) == 3      # the intervals stay, for scripts that read them
    text = (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")
    # a note wraps at 100 columns in report.txt, its continuation lines indented
    text = text.replace("\n  ", " ")
    line = next(ln for ln in text.splitlines() if ln.startswith("dead points (where"))
    assert "θ1 = 0° ± " in line and "θ1 = 180° ± " in line


def test_force_json_gives_the_dead_point_of_ex2_1_at_its_change_point(tmp_path):
    # 例 2-1 (configs/ch2/ex2-1.toml) with l4 = l2 + l3 - l1 = 1300 mm: a change point,
    # BD = l1 + l4 = l2 + l3 at θ1 = 180° (docs/accuracy.md moves it the same way)
    proc = run_inprocess("force", CONFIGS / "ch2" / "ex2-1.toml", "--set", "mechanism.l4=1300",
                         "--set", "input.partial=true", "--json", "--no-plot",
                         "-o", tmp_path / "f")
    assert proc.returncode == 0, proc.stderr
    r = json.loads(proc.stdout)["results"]
    (at,), (tol,) = r["dead_points_deg"], r["dead_points_tol_deg"]
    assert abs(at - 180.0) <= tol < 1e-8
