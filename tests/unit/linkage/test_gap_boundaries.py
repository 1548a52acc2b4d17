"""Gap (assembly) boundaries are the roots of the failing dyad's discriminant, located to
the rounding of the inputs, and the JSON says how closely (``excluded_tol_deg``).

References: the cosine law for the input where the dyad's two known points are l_a + l_b
(or |l_a - l_b|) apart, evaluated with mpmath at 40 digits from the same float64 lengths
(so the reference carries no rounding of its own).
"""

import json
import math

import mpmath
import numpy as np
import pytest

from mechcli.core.errors import AssemblyError
from mechcli.core.linkage import RRR, Crank, Ground, Linkage
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities
from tests.conftest import run_inprocess, write_spec

mpmath.mp.dps = 40


def fourbar(l1, l2, l3, l4):
    return Linkage(4, (Ground("A", 0, 0), Ground("D", l4, 0), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, 1)))


def sweep(lk, start, stop, step, driver=1, partial=True):
    q = np.radians(np.arange(start, stop + step / 2, step))
    qs = default_quantities(lk, 2)
    return analyse_sweep(lk, Sweep(driver, q, 10.0, 0.0, {}, abs(stop - start - 360) < 1e-9),
                         qs, 2, partial=partial)


def crank_limit(l1, l4, far):
    """Crank angle where |BD| = far for B = l1 e^(i theta), D = (l4, 0) (cosine law), and
    its mirror image, in 40 digits."""
    l1, l4, far = (mpmath.mpf(x) for x in (l1, l4, far))
    th = mpmath.acos((l1 ** 2 + l4 ** 2 - far ** 2) / (2 * l1 * l4))
    return th, 2 * mpmath.pi - th


def test_narrow_gap_of_a_crank_is_the_cosine_law_root():
    # the gap between grid points of tests/unit/linkage/test_kinematics.py: B is farther than
    # l2 + l3 = 399.999 from D for theta1 in 179.7041° ... 180.2959°
    res = sweep(fourbar(100, 250, 149.999, 300), 0.5, 360.5, 1.0)
    (start, stop, why), = res.excluded
    assert why == "cannot assemble"
    ref = crank_limit(100, 300, mpmath.mpf(250) + mpmath.mpf(149.999))
    (tol_a, tol_b), = res.excluded_tol
    # before this change the ends were the last regular inputs, 3.1e-10 rad inside
    for x, r, tol in ((start, ref[0], tol_a), (stop, ref[1], tol_b)):
        err = abs(x - float(r))
        assert err <= tol, (err, tol)
        assert tol < 2e-12          # the rounding of the inputs, not a threshold
    # the analysis still stops at regular inputs next to the limit
    assert res.q.size > 300 and np.all(np.isfinite(res.values["omega3"]))


def test_rocker_driven_ex1_1_stops_where_crank_and_coupler_line_up():
    """例 1-1 (configs/ch1/ex1-1.toml) driven by its rocker: the rocker cannot pass the
    positions where crank and coupler are in line (its dead points with the output
    driving), AC = l2 - l1 and l2 + l1; theta3 = 180° - angle ADC (cosine law in ADC), the
    hand calculation of the config: 159.1513° and 88.9768°."""
    l1, l2, l3, l4 = 101.6, 254, 177.8, 304.8
    lk = Linkage(4, (Ground("A", 0, 0), Ground("D", l4, 0), Crank(3, "D", "C", l3),
                     RRR("B", "A", 1, l1, "C", 2, l2, -1)))
    res = sweep(lk, 0, 360, 1.0, driver=3)

    def theta3(ac):
        l3m, l4m = mpmath.mpf(l3), mpmath.mpf(l4)
        return mpmath.pi - mpmath.acos((l3m ** 2 + l4m ** 2 - ac ** 2) / (2 * l3m * l4m))

    hi = theta3(mpmath.mpf(l2) - mpmath.mpf(l1))   # 159.1513°: crank folded on the coupler
    lo = theta3(mpmath.mpf(l2) + mpmath.mpf(l1))   # 88.9768°: crank and coupler extended
    assert math.degrees(float(hi)) == pytest.approx(159.1513, abs=5e-5)
    assert math.degrees(float(lo)) == pytest.approx(88.9768, abs=5e-5)
    # the rocker assembles for 88.9768° ... 159.1513° and for its mirror image below AD,
    # 200.8487° ... 271.0232°; the rest of the turn is left out
    assert [why for *_ab, why in res.excluded] == ["cannot assemble"] * 3
    ends = [(res.excluded[0][1], res.excluded_tol[0][1], lo),
            (res.excluded[1][0], res.excluded_tol[1][0], hi),
            (res.excluded[1][1], res.excluded_tol[1][1], 2 * mpmath.pi - hi),
            (res.excluded[2][0], res.excluded_tol[2][0], 2 * mpmath.pi - lo)]
    for x, tol, ref in ends:
        err = abs(x - float(ref))
        assert err <= tol < 1e-13, (x, err, tol)


def test_assembly_error_names_the_roots():
    with pytest.raises(AssemblyError) as exc:
        sweep(fourbar(100, 250, 149.999, 300), 0.5, 360.5, 1.0, partial=False)
    (start, stop, _why), = exc.value.intervals
    ref = crank_limit(100, 300, mpmath.mpf(250) + mpmath.mpf(149.999))
    assert abs(start - float(ref[0])) < 2e-12 and abs(stop - float(ref[1])) < 2e-12


GAP = """\
command = "kin"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 100
l2 = 250
l3 = 149.999
l4 = 300
[input]
omega1 = 10
start = 0.5
stop = 360.5
step = 1
partial = true
"""


def test_json_gives_each_end_with_its_uncertainty(tmp_path):
    spec = write_spec(tmp_path, GAP)
    proc = run_inprocess("kin", spec, "--json", "--no-plot", "-o", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    r = json.loads(proc.stdout)["results"]
    (a, b, why), = r["excluded"]
    (ta, tb), = r["excluded_tol_deg"]
    ref = [math.degrees(float(x)) for x in crank_limit(100, 300, mpmath.mpf(250)
                                                       + mpmath.mpf(149.999))]
    assert why == "cannot assemble"
    assert abs(a - ref[0]) <= ta < 1e-10 and abs(b - ref[1]) <= tb < 1e-10
    assert r["dead_points_deg"] == [] and r["dead_points_tol_deg"] == []


SLIDER_DRIVEN = """\
command = "kin"
units = "mm"
[mechanism]
type = "general"
frame = 4
[mechanism.ground]
A = [0, 0]
O = [0, 25]
[[mechanism.driver]]
type = "slider"
link = 3
origin = "O"
point = "P"
angle = 0
[[mechanism.dyad]]
type = "RRR"
joint = "B"
points = ["P", "A"]
links = [2, 1]
lengths = [200, 80]
branch = 1
[input]
v1 = 100
start = {start}
stop = {stop}
{step}
partial = true
"""


def test_a_gap_end_and_a_sweep_ending_on_it_are_one_limit_of_assembly(tmp_path):
    """A slider P on y = 25 mm drives a crank A-B (80 mm) through a rod B-P (200 mm): it
    assembles for 120 <= |AP| <= 280 mm, s = √(120² − 25²) = 117.3670 mm ...
    √(280² − 25²) = 278.8817 mm (Pythagoras, by hand; mpmath below).  Swept past both ends
    or ending exactly on the far one, that position is the same limit of assembly: the
    same `excluded` start and `excluded_tol_mm`, no dead point (docs/accuracy.md §4), and
    the warnings call it a limit of assembly, never a dead point (they used to say "dead
    points" while `dead_points_mm` was empty, and "dead point" with shape "limit" when the
    sweep ended on it)."""
    near = float(mpmath.sqrt(mpmath.mpf(120) ** 2 - 25 ** 2))
    far = float(mpmath.sqrt(mpmath.mpf(280) ** 2 - 25 ** 2))
    runs = {}
    for name, start, stop, step in (("past", 50, 300, "step = 1"),
                                    ("on", 150, repr(far), "count = 1001")):
        spec = write_spec(tmp_path, SLIDER_DRIVEN.format(start=start, stop=stop, step=step),
                          f"{name}.toml")
        proc = run_inprocess("kin", spec, "--json", "--no-plot", "-o", tmp_path / name)
        assert proc.returncode == 0, proc.stderr
        runs[name] = json.loads(proc.stdout)
    past, on = runs["past"]["results"], runs["on"]["results"]
    assert [e[2] for e in past["excluded"]] == ["cannot assemble"] * 2
    assert past["excluded"][0][1] == pytest.approx(near, abs=1e-9)
    assert past["excluded"][1][0] == pytest.approx(far, abs=1e-9)
    (a, b, why), = on["excluded"]
    assert why == "cannot assemble" and b == far
    assert abs(a - far) <= on["excluded_tol_mm"][0][0] < 1e-9
    assert a == pytest.approx(past["excluded"][1][0], abs=1e-12)
    assert past["dead_points_mm"] == on["dead_points_mm"] == []
    for doc in runs.values():
        text = " ".join(doc["warnings"])
        assert "dead point" not in text and "limit" in text
    assert "omega2, alpha1 grow without bound towards the limits of assembly at s3 = " \
        "117.367 mm, 278.882 mm" in runs["past"]["warnings"]
    assert "limit of assembly at s3 = 278.882 mm (dyad B): excluded from the analysis" \
        in runs["on"]["warnings"]


def test_the_partial_hint_only_when_partial_is_not_set(tmp_path):
    """Exit 3 with nothing to analyse: "set input.partial = true" is advice only when it is
    not set already (it was given with partial = true too).  By hand: a crank of 1000 mm
    on a 304.8 mm frame keeps |BD| >= 1000 − 304.8 = 695.2 mm, and the dyad (50 + 100 mm)
    reaches at most 150 mm: it never assembles."""
    text = """\
command = "kin"
units = "mm"
[mechanism]
type = "four_bar"
l1 = 1000
l2 = 50
l3 = 100
l4 = 304.8
[input]
omega1 = 10
step = 1
"""
    spec = write_spec(tmp_path, text)
    off = run_inprocess("kin", spec, "--no-plot", "-o", tmp_path / "a")
    on = run_inprocess("kin", spec, "--set", "input.partial=true", "--no-plot",
                       "-o", tmp_path / "b")
    assert off.returncode == on.returncode == 3
    assert "set input.partial = true" in off.stderr
    assert "set input.partial = true" not in on.stderr
    assert "cannot assemble" in on.stderr and "Traceback" not in on.stderr
