"""``[approximate] moment_arm = "series"``: the crank effort by the books' moment arm,
T ≈ F_P r (sin θ + sin 2θ / 2n), FT = T / r (docs/approximate.md), end to end.

Every reference number is computed here with plain ``math`` from the textbook formulas
(a hand derivation): the series arm r (sin θ + sin 2θ / 2n) from the head-end dead centre,
the exact arm r sin(θ + φ) / cos φ with sin φ = sin θ / n, and their difference in the
independent form r sin θ cos θ (1/n − 1/√(n² − sin²θ)).  None of them uses mechcli."""

import csv
import json
import math

import pytest

from tests.conftest import ROOT, one_line_error, run_inprocess

CH2 = ROOT / "configs" / "ch2"

#: the static problem: r = 100 mm, l = 400 mm (n = 4), F_P = 1000 N toward the crank
R, L, F = 0.1, 0.4, 1000.0
N = L / R
ANGLES = [30, 45, 60, 90, 120, 150, 210, 300]

STATIC = """\
command = "force"
units = "mm"
[mechanism]
type = "slider_crank"
l1 = 100
l2 = 400
e = 0
branch = "{branch}"
model = "{model}"
{arm}
[input]
{omega}
step = 1
[[load]]
name = "piston"
link = 3
force = [{fx}, 0]      # F_P = 1000 N toward the crank
[output]
at = {at}
"""

ARM = '[approximate]\nmoment_arm = "series"\n'


def _spec(tmp_path, name="static.toml", branch="right", model="approximate", arm=ARM,
          omega="omega1 = 0"):
    fx = -F if branch == "right" else F     # toward the crank pivot A at the origin
    path = tmp_path / name
    path.write_text(STATIC.format(branch=branch, model=model, arm=arm, omega=omega, fx=fx,
                                  at=json.dumps(ANGLES)), encoding="utf-8")
    return path


def _run(tmp_path, spec, *more):
    proc = run_inprocess("force", spec, "--out", tmp_path / (spec.stem + "-out"), "--no-plot",
                         "--json", *more)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)["results"]


def series_arm(deg):
    """The books' moment arm [m], θ from the head-end dead centre."""
    t = math.radians(deg)
    return R * (math.sin(t) + math.sin(2 * t) / (2 * N))


def exact_arm(deg):
    """r sin(θ + φ) / cos φ [m], sin φ = sin θ / n (the connecting rod's obliquity)."""
    t = math.radians(deg)
    phi = math.asin(math.sin(t) / N)
    return R * math.sin(t + phi) / math.cos(phi)


def arm_difference(deg):
    """series − exact arm [m] in a form of its own: r sin θ cos θ (1/n − 1/√(n² − sin²θ))."""
    t = math.radians(deg)
    s, c = math.sin(t), math.cos(t)
    return R * s * c * (1.0 / N - 1.0 / math.sqrt(N * N - s * s))


def test_the_reference_formulas_agree_with_each_other():
    """The two references of the test are consistent (series − exact = the difference)."""
    for deg in range(0, 361, 5):
        assert series_arm(deg) - exact_arm(deg) == pytest.approx(arm_difference(deg),
                                                                 abs=1e-16)
    # hand values: θ = 30°: 0.1 (0.5 + 0.8660254/8) = 0.06082531755 m
    assert series_arm(30) == pytest.approx(0.06082531755, abs=1e-11)


@pytest.mark.parametrize("branch, head", [("right", 0.0), ("left", 180.0)])
def test_static_turning_moment_is_the_series_arm_times_the_piston_effort(tmp_path, branch,
                                                                         head):
    res = _run(tmp_path, _spec(tmp_path, branch=branch))
    assert res["model"] == "approximate" and res["moment_arm"] == "series"
    assert res["head_end_at_deg"] == pytest.approx(head, abs=1e-9)
    for deg in ANGLES:
        from_head = deg - head
        assert res[f"FP_at_{deg}deg_N"] == pytest.approx(F, rel=1e-12)
        assert res[f"T_at_{deg}deg_N_m"] == pytest.approx(F * series_arm(from_head),
                                                          rel=1e-12, abs=1e-12)
        assert res[f"FT_at_{deg}deg_N"] == pytest.approx(F * series_arm(from_head) / R,
                                                         rel=1e-12, abs=1e-11)
        # the kinetostatics stays exact: Mb balances the exact moment of the rod's force
        assert res[f"Mb_at_{deg}deg_N_m"] == pytest.approx(-F * exact_arm(from_head),
                                                           rel=1e-12, abs=1e-12)
    # the largest difference to the exact T over the 1° grid, in the independent form
    grid = max(abs(F * arm_difference(k - head)) for k in range(361))
    assert res["approx_error_T_max_N_m"] == pytest.approx(grid, rel=1e-9)
    assert res["approx_error_FT_max_N"] == pytest.approx(grid / R, rel=1e-9)
    # largest T: cos θ + cos 2θ / n = 0, so cos θ = (−n + √(n² + 8)) / 4 (hand derivation)
    c = (-N + math.sqrt(N * N + 8)) / 4
    assert res["T_max_N_m"] == pytest.approx(F * R * math.sqrt(1 - c * c) * (1 + c / N),
                                             rel=1e-12)
    assert res["T_max_at_deg"] == pytest.approx((head + math.degrees(math.acos(c))) % 360,
                                                abs=1e-4)
    assert res["power_balance_residual"] <= 1e-12


def test_omega_not_given_is_the_same_static_answer_without_masses(tmp_path):
    """omega1 defaults to 1 rad/s; without a mass there is no inertia: the same numbers."""
    at_rest = _run(tmp_path, _spec(tmp_path))
    turning = _run(tmp_path, _spec(tmp_path, "no-omega.toml", omega=""))
    for deg in ANGLES:
        for sym in ("T", "FT", "Mb", "FP"):
            u = "N_m" if sym in ("T", "Mb") else "N"
            key = f"{sym}_at_{deg}deg_{u}"
            assert turning[key] == pytest.approx(at_rest[key], rel=1e-13, abs=1e-12)


def _without_arm(res):
    return {k: v for k, v in res.items() if not k.startswith(
        ("T_", "FT_", "approx_error_T_", "approx_error_FT_", "moment_arm"))}


def test_the_key_changes_only_T_and_FT(tmp_path):
    """Mb, every pair reaction, the engine's other results, the balances: bit for bit
    those of the run without the key (a dynamic run: the steam engine at 240 rpm)."""
    spec = CH2 / "engine-steam-horizontal.toml"
    plain = _run(tmp_path, spec)
    arm = _run(tmp_path, spec, "--set", 'approximate.moment_arm="series"')
    assert "moment_arm" not in plain and arm["moment_arm"] == "series"
    assert _without_arm(arm) == _without_arm(plain)
    # T = FP · r (sin θ + sin 2θ / 2n) at 60° (r = 0.3 m, n = 1.25/0.3; hand formula)
    r, n, t = 0.3, 1.25 / 0.3, math.radians(60)
    assert arm["T_at_60deg_N_m"] == pytest.approx(
        arm["FP_at_60deg_N"] * r * (math.sin(t) + math.sin(2 * t) / (2 * n)), rel=1e-12)
    assert arm["FT_at_60deg_N"] == pytest.approx(arm["T_at_60deg_N_m"] / r, rel=1e-12)
    # the exact T is the one the run without the key reports
    assert plain["T_at_60deg_N_m"] == pytest.approx(19357.475, abs=1e-3)   # the config's
    assert plain["T_at_60deg_N_m"] != pytest.approx(arm["T_at_60deg_N_m"], rel=1e-4)


def test_csv_and_report(tmp_path):
    out = tmp_path / "o"
    proc = run_inprocess("force", _spec(tmp_path), "--out", out, "--no-plot", "-q")
    assert proc.returncode == 0, proc.stderr
    with open(out / "force.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    for row in rows[::15]:
        deg = float(row["theta1_deg"])
        assert float(row["T_N_m"]) == pytest.approx(float(row["FP_N"]) * series_arm(deg),
                                                    rel=1e-9, abs=1e-9)
        assert float(row["Mb_N_m"]) == pytest.approx(-F * exact_arm(deg), rel=1e-9, abs=1e-9)
    report = " ".join((out / "report.txt").read_text(encoding="utf-8").split())  # unwrapped
    assert "moment arm of T and FT, r (sin θ + sin 2θ / 2n)" in report


def test_config_meets_its_expected_values():
    proc = run_inprocess("check", CH2 / "engine-static-approximate-arm.toml", "-j", "1", "-q")
    assert proc.returncode == 0, proc.stdout + proc.stderr


@pytest.mark.parametrize("model, arm, key, words", [
    ("exact", ARM, "[approximate] moment_arm", 'model = "approximate"'),
    ("exact", "[approximate]\n", "approximate", 'model = "approximate"'),
    ("approximate", '[approximate]\nmoment_arm = "seris"\n', "[approximate] moment_arm",
     "did you mean 'series'"),
    ("approximate", '[approximate]\nmomentarm = "series"\n', "[approximate] momentarm",
     "unknown key"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, model, arm, key, words):
    proc = run_inprocess("force", _spec(tmp_path, model=model, arm=arm), "--out",
                         tmp_path / "o", "--no-plot")
    assert proc.returncode == 2
    line = one_line_error(proc)
    assert "static.toml" in line and key in line and words in line, line
    assert not (tmp_path / "o" / "force.csv").exists()


def test_an_offset_is_still_refused(tmp_path):
    spec = _spec(tmp_path)
    spec.write_text(spec.read_text(encoding="utf-8").replace("e = 0", "e = 10"),
                    encoding="utf-8")
    proc = run_inprocess("force", spec, "--out", tmp_path / "o", "--no-plot")
    assert proc.returncode == 2
    assert "[mechanism] e" in one_line_error(proc)
