"""``mechcli cam`` edge cases: a zero allowed pressure angle, 0° dwells as the book
writes them, sized cams exactly at the limit, segment and lift sums within tolerance."""

import math

import pytest

from mechcli.core.cam.motion import build_program
from mechcli.core.cam.sizing import translating_base_radius_min
from tests.conftest import run_inprocess

SIZED = """command = "cam"
[follower]
contact = "roller"
rr = 5
[motion]
h = 20
segments = [
  { kind = "rise", angle = 180, law = "sine" },
  { kind = "return", angle = 180, law = "sine" },
]
[sizing]
base_radius = true
"""


@pytest.mark.parametrize("key", ["alpha_rise", "alpha_return"])
def test_zero_allowed_pressure_angle_is_a_spec_error(tmp_path, key):
    # [alpha] = 0 used to divide by tan 0 in the sizing (RuntimeWarning, NaN) and report a
    # meaningless "sized base radius 0.628 mm" with exit 3
    spec = tmp_path / "spec.toml"
    spec.write_text(SIZED + f"[limits]\n{key} = 0\n", encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path)
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr.strip()
    assert len(err.splitlines()) == 1 and key in err and "Warning" not in err, err


def test_sizing_core_rejects_a_zero_limit():
    prog = build_program([("rise", math.pi, "sine", 0.02), ("return", math.pi, "sine", 0.02)],
                         0.02)
    with pytest.raises(ValueError, match="allowed pressure angle"):
        translating_base_radius_min(prog, 0.0, 1, 0.0)
    with pytest.raises(ValueError, match="allowed pressure angle"):
        translating_base_radius_min(prog, 0.0, 1, math.radians(30), 0.0)


PROGRAM = """command = "cam"
[follower]
contact = "knife"
r0 = 30
[cam]
rotation = "cw"
[motion]
h = 20
segments = [
  { kind = "rise", angle = 120, law = "cosine" },%s
  { kind = "return", angle = 120, law = "cosine" },
  { kind = "dwell", angle = 120 },
]
"""


def test_zero_degree_dwell_as_the_book_writes_it(tmp_path):
    # 习题 4-1 gives 远休止角 δ01 = 0°: a 0° dwell used to be rejected (exit 2); it is dropped
    import json

    spec = tmp_path / "zero.toml"
    spec.write_text(PROGRAM % "\n  { kind = \"dwell\", angle = 0 },", encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--json", "--out", tmp_path / "a")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    # the hand values of configs/ch4/exercise4-1.toml (cos x = 0.25)
    assert res["alpha_rise_max_deg"] == pytest.approx(21.1713, abs=5e-5)
    assert res["alpha_return_max_at_deg"] == pytest.approx(189.6517, abs=5e-5)
    assert res["n_soft_impacts"] == 2
    # a rise of 0 deg is still an error
    spec.write_text(PROGRAM.replace("angle = 120, law = \"cosine\" },%s",
                                    "angle = 0, law = \"cosine\" },%s") % "", encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path / "b")
    assert proc.returncode == 2 and "angle" in proc.stderr, proc.stderr


EX72_SIZED = """command = "cam"
[follower]
contact = "knife"
[motion]
h = 20
segments = [
  { kind = "rise", angle = 90, law = "cosine" },
  { kind = "dwell", angle = 90 },
  { kind = "return", angle = 90, law = "cosine" },
  { kind = "dwell", angle = 90 },
]
[sizing]
base_radius = true
"""


# 例 7-2's cam sized for [α]: tan α = (πh/2β) sin x/(s0 + h/2 (1 - cos x)) is largest where
# cos x = (h/2)/(s0 + h/2); the smallest s0 (= r0, e = 0) solves max tan α = tan[α]
@pytest.mark.parametrize("alpha", [30.0, 35.0])
def test_sized_cam_at_the_limit_gives_no_pressure_angle_warning(tmp_path, alpha):
    # the sized cam meets [α] with equality; round-off (30.000000000000004°) used to print
    # "max pressure angle in the rise 30.0000° exceeds [α] = 30°"
    import json

    from scipy.optimize import brentq

    spec = tmp_path / "s.toml"
    spec.write_text(EX72_SIZED + f"[limits]\nalpha_rise = {alpha}\nalpha_return = {alpha}\n",
                    encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--json", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    h, beta, t = 20.0, math.pi / 2, math.tan(math.radians(alpha))

    def excess(s0):
        c = (h / 2) / (s0 + h / 2)
        return math.pi * h / (2 * beta) * math.sqrt(1 - c * c) / (s0 + h / 2 * (1 - c)) - t

    assert doc["results"]["r0_min"] == pytest.approx(brentq(excess, 1.0, 1e3, xtol=1e-13),
                                                     rel=1e-9)
    assert doc["results"]["alpha_rise_max_deg"] == pytest.approx(alpha, abs=1e-9)
    assert not [w for w in doc["warnings"] if "exceeds" in w], doc["warnings"]


@pytest.mark.parametrize("extra", [5e-7, -9e-7])
def test_segment_sum_within_the_spec_tolerance_runs(tmp_path, extra):
    # the spec accepts sums within 1e-6 deg of 360 but the core checked 1e-9 rad (5.7e-8 deg):
    # 360.0000005 deg used to end in "internal error: ValueError" (exit 1)
    import json

    spec = tmp_path / "s.toml"
    spec.write_text(PROGRAM.replace("angle = 120, law = \"cosine\" },%s",
                                    f"angle = {120 + extra!r}, law = \"cosine\" }},%s") % "",
                    encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--json", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert res["alpha_rise_max_deg"] == pytest.approx(21.1713, abs=5e-5)
    # one more micro-degree over the tolerance is still a spec error
    spec.write_text(PROGRAM.replace("angle = 120, law = \"cosine\" },%s",
                                    "angle = 120.000002, law = \"cosine\" },%s") % "",
                    encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--out", tmp_path)
    assert proc.returncode == 2 and "360" in proc.stderr, proc.stderr


@pytest.mark.parametrize("rise, ret", [("20.00000001", "20.00000001"), ("20", "20.00000001"),
                                       ("20", "19.99999999")])
def test_lift_within_the_spec_tolerance_runs(tmp_path, rise, ret):
    # the spec accepts lifts within 1e-9 h of the stroke, the core allowed 1e-12 h: a return
    # of 20.00000001 after a rise of h = 20 used to be "internal error: ValueError" (exit 1)
    import json

    spec = tmp_path / "s.toml"
    spec.write_text(PROGRAM.replace("law = \"cosine\" },%s", f"law = \"cosine\", lift = {rise} }},")
                    .replace("{ kind = \"return\", angle = 120, law = \"cosine\" }",
                             f"{{ kind = \"return\", angle = 120, law = \"cosine\", lift = {ret} }}"),
                    encoding="utf-8")
    proc = run_inprocess("cam", spec, "--no-plot", "--json", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert res["alpha_rise_max_deg"] == pytest.approx(21.1713, abs=5e-5)
    assert res["alpha_return_max_deg"] == pytest.approx(21.1713, abs=5e-5)
