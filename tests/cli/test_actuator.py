"""A machine driven by a cylinder while its motion is given as a link's angle
(`actuator` on a crank driver, issue 30 / 习题 2-2): the balancing force along the
slide, checked by the power balance, against the crank-driven machine by virtual work,
by its joints form, and bad input named in one line."""

import math

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json, write_spec

LADDER = (CONFIGS / "ch2" / "exercise2-2.toml").read_text(encoding="utf-8").split(
    "[expected]")[0]

#: masses on the ladder, the cylinder and the rod, and a fast lift, so that the inertia
#: loads matter (made-up numbers: the test compares two routes to the same physics)
MASSES = """
[[link]]
number = 2
mass = 80
J = 60
com = "S2"
[[link]]
number = 3
mass = 12
J = 0.4
[[link]]
number = 4
mass = 5
J = 0.1
[gravity]
g = 9.81
"""


def _fast(text):
    return text.replace("omega1 = 1 ", "omega1 = 2\nalpha1 = 0.5 ") + MASSES


def test_fire_ladder_balancing_force_is_the_hand_value(tmp_path):
    # 习题 2-2 at φ = 0 by hand (the config's comment): Fb = 4500 √0.52 / 0.16 N; the cylinder
    # is a two-force member, so |FR24| = |FR34| = |FR13| = Fb; no torque is reported at A
    r = run_json("force", write_spec(tmp_path, LADDER), "--out", tmp_path / "o")["results"]
    assert r["Fb_at_0deg_N"] == pytest.approx(4500 * math.sqrt(0.52) / 0.16, rel=1e-12)
    for pair in ("FR24", "FR34", "FR13"):
        assert r[f"{pair}_at_0deg_N"] == pytest.approx(r["Fb_at_0deg_N"], rel=1e-12)
    assert not any(k.startswith("Mb") for k in r)
    assert abs(r["power_balance_residual"]) < 1e-12


def test_cylinder_and_crank_put_the_same_power_in(tmp_path):
    # with inertia and gravity, driven by the cylinder (Fb along it) or by a torque on the
    # ladder (Mb): the loads are the same, so Fb ṡ = Mb ω at every position (the input
    # power P); each solve passes its own power balance
    by_cyl = run_json("force", write_spec(tmp_path, _fast(LADDER), name="cyl.toml"),
                      "--out", tmp_path / "a")["results"]
    torque = _fast(LADDER).replace('actuator = "cyl"', "")
    by_torque = run_json("force", write_spec(tmp_path, torque, name="mb.toml"),
                         "--out", tmp_path / "b")["results"]
    for a in (0, 20, 40, 60, 80):
        p = by_torque[f"P_at_{a}deg_W"]
        assert abs(by_torque[f"Mb_at_{a}deg_N_m"]) > 100
        assert by_cyl[f"P_at_{a}deg_W"] == pytest.approx(p, rel=1e-11, abs=1e-9 * abs(p))
    assert abs(by_cyl["power_balance_residual"]) < 1e-12
    assert abs(by_cyl["force_balance_residual"]) < 1e-12
    # the cylinder's force is not the crank's torque over a lever: the reactions differ
    assert by_cyl["FR12_at_40deg_N"] != pytest.approx(by_torque["FR12_at_40deg_N"], rel=1e-3)


JOINTS = """
command = "force"
units = "m"
[mechanism]
type = "joints"
frame = 1
[mechanism.joints]
A = [0, 0.8]
B = [0.4, 0.6]
C = [0.8, 0]
[[mechanism.link]]
number = 2
joints = ["A", "B"]
[[mechanism.link]]
number = 3
joints = ["C"]
[[mechanism.link]]
number = 4
joints = ["B"]
[[mechanism.slider]]
block = 4
guide = 3
through = "B"
toward = "C"
name = "cyl"
[[mechanism.driver]]
type = "crank"
link = 2
pivot = "A"
actuator = "cyl"
[[mechanism.point]]
name = "S2"
link = 2
from = "A"
along = 1.3416407864998738    # 1.5 cos(atan 0.5): S2 = A + (1.5, 0) at φ = 0
normal = 0.6708203932499369   # 1.5 sin(atan 0.5), left of A -> B
[input]
omega1 = 1
start = -26.56505117707799    # φ = 0: the direction A -> B is φ − atan(0.5)
stop = 53.43494882292201
step = 1
[[load]]
name = "Q"
link = 2
force = [0, -3000]
at = "S2"
"""


def test_the_joints_form_gives_the_same_force(tmp_path):
    # the same ladder drawn by its joints at φ = 0, its slider's line drawn from B toward C:
    # Fb > 0 pushes the rod along the drawn direction (B -> C, retracting), so the lift's
    # push is −Fb of the general form (whose RPR line runs from C to B)
    gen = run_json("force", write_spec(tmp_path, LADDER, name="g.toml"),
                   "--out", tmp_path / "g")["results"]
    r = run_json("force", write_spec(tmp_path, JOINTS, name="j.toml"),
                 "--out", tmp_path / "j")["results"]
    assert r["mechanism_class"] == 2
    assert r["Fb_min_N"] == pytest.approx(-gen["Fb_max_N"], rel=1e-12)   # at φ = 0
    assert r["Fb_max_N"] == pytest.approx(-gen["Fb_min_N"], rel=1e-12)   # at φ = 80°
    assert abs(r["power_balance_residual"]) < 1e-12


@pytest.mark.parametrize("text,key", [
    (LADDER.replace('actuator = "cyl"', 'actuator = "pump"'), "[mechanism.driver.0] actuator"),
    (JOINTS.replace('actuator = "cyl"', 'actuator = "pump"'), "[mechanism.driver.0] actuator"),
])
def test_an_actuator_that_is_no_cylinder_is_exit_2_naming_the_key(tmp_path, text, key):
    proc = run_inprocess("force", write_spec(tmp_path, text), "--out", tmp_path / "o")
    assert proc.returncode == 2
    msg = one_line_error(proc)
    assert key in msg and "pump" in msg
