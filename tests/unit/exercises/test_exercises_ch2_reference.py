"""习题 2-1 and 2-5 (configs/ch2/exercise2-1.toml, exercise2-5.toml): their [expected]
tables against the independent reference tests/reference/independent_exercises_ch2.py.

The reference imports nothing from mechcli: closed-form positions, velocities and
accelerations differentiated by hand, and the dense kinetostatic solver of
tests/reference/independent_force.py (which imports nothing from mechcli either).  This
test reruns it and compares every expected value of both configs under the rule of
docs/check.md (half a unit of the last written digit, or the `tol` / `rtol` given), so a
change to a config or to the reference without the other fails here.  It also checks the
reference itself: its hand derivatives against finite differences, the virtual-power and
force balances of its solution, the hand values written in 习题 2-1's comments, and the
figure reading written in 习题 2-5's comments.
"""

from __future__ import annotations

import ast
import functools
import math
import re

import numpy as np
import pytest

from tests.conftest import CONFIGS, ROOT, load_module

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

SCRIPT = ROOT / "tests" / "reference" / "independent_exercises_ch2.py"
SOLVER = ROOT / "tests" / "reference" / "independent_force.py"


@functools.lru_cache(maxsize=None)
def _ref():
    return load_module(SCRIPT)


@functools.lru_cache(maxsize=None)
def _results(name):
    ref = _ref()
    return {"exercise2-1": ref.exercise_2_1, "exercise2-5": ref.exercise_2_5}[name]()


# ---------------------------------------------------------------------------
# the reference itself
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("path", [SCRIPT, SOLVER], ids=lambda p: p.name)
def test_reference_imports_nothing_from_mechcli(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert names and not [m for m in names if m.split(".")[0] == "mechcli"], names


@pytest.mark.parametrize("cls", ["CrankRockingBlock", "SwingingFeed"])
def test_hand_derivatives_agree_with_finite_differences(cls):
    # 8th-order central differences of the positions, h = 1e-3 rad: truncation ~1e-22,
    # round-off ~1e-16 / h² = 1e-10 of the scale (measured: 5e-10 and 2e-9); a wrong
    # hand derivative would be off by the order of the quantity itself
    worst = _ref().fd_check(getattr(_ref(), cls)())
    assert max(worst.values()) < 1e-7, worst


@pytest.mark.parametrize("cls", ["CrankRockingBlock", "SwingingFeed"])
def test_reference_meets_the_virtual_power_and_force_balances(cls):
    # Mb w1 + Σ (F·v + M ω) = 0 with the hand velocities (the reactions do no work), and
    # the frame's pair forces = Σ (loads + weights − m a_S), at every 5° of a turn:
    # round-off only (measured ≤ 4e-16); a mis-assembled system would leave O(1)
    power, force = _ref().balance_residuals(getattr(_ref(), cls)(), np.arange(0.0, 360.0, 5.0))
    assert power < 1e-12 and force < 1e-12, (power, force)


def test_exercise2_1_hand_values():
    # the hand checks written in configs/ch2/exercise2-1.toml: m2 = 20 kg, g = 9.8,
    # r = l_AB = 0.1, l_BS2 = 0.086, l_AC = 0.2 m, ω1 = 40 rad/s
    m2, g, r, l, w = 20.0, 9.8, 0.1, 0.086, 40.0
    out, _ = _ref().solve(_ref().CrankRockingBlock(), [0.0, 180.0])
    # θ1 = 0: rod along +x through B = (0.1, 0), BC = 0.1, ω2 = −ω1, α2 = 0
    assert out["Mb"][0] == pytest.approx(m2 * g * (r - l), rel=1e-12)           # 2.744
    assert out["FR12x"][0] == pytest.approx(-m2 * w ** 2 * (r + l), rel=1e-12)  # −5952
    assert out["FR12y"][0] == pytest.approx(m2 * g * (1 - l / 0.1), rel=1e-12)  # 27.44
    assert out["FR23y"][0] == pytest.approx(-m2 * g * l / 0.1, rel=1e-12)       # −168.56
    # θ1 = 180°: BC = 0.3, ω2 = ω1/3, α2 = 0
    assert out["Mb"][1] == pytest.approx(-m2 * g * (r - l / 3), rel=1e-12)      # −13.98133
    assert out["FR12x"][1] == pytest.approx(m2 * w ** 2 * (r - l / 9), rel=1e-12)  # 2894.222
    assert out["FR23y"][1] == pytest.approx(-m2 * g * l / 0.3, rel=1e-12)       # −56.18667


def test_exercise2_5_figure_reading():
    # the facts configs/ch2/exercise2-5.toml's FIGURE-READING states, on a 0.1° grid
    ref = _ref()
    prob = ref.SwingingFeed()
    th = np.arange(3600) * 0.1 * ref.DEG
    pts, angs = prob.positions(th)
    xF = pts["F"][:, 0] * 1000.0
    dx = np.diff(np.r_[xF, xF[0]])
    assert np.count_nonzero(np.sign(dx) != np.sign(np.roll(dx, 1))) == 2   # one stroke a turn
    assert xF.max() - xF.min() == pytest.approx(341.2, abs=0.05)           # stroke [mm]
    tilt = np.degrees(np.arcsin(np.abs(pts["E"][:, 1]) / prob.l4)).max()
    assert tilt == pytest.approx(29.6, abs=0.05)                           # EF against the guide
    psi = np.degrees(angs[3])
    assert (psi.min(), psi.max()) == pytest.approx((-146.4, -97.1), abs=0.05)
    assert np.all(pts["F"][:, 0] < pts["E"][:, 0])                         # F left of E
    # the crank is a crank: 80 + 300 ≤ 260 + √(90² + 170²)
    assert 80 + 300 <= 260 + math.hypot(90, 170)
    # at φ1 = 90° the slider moves to −x, so P_r = +4000 N there
    assert _results("exercise2-5")["vF_at_90deg_m_s"] == pytest.approx(-7.4393, abs=5e-5)


# ---------------------------------------------------------------------------
# the configs' [expected] tables
# ---------------------------------------------------------------------------
_NUMBER = re.compile(r"[+-]?(\d+)(?:\.(\d*))?(?:[eE]([+-]?\d+))?")


def _half_unit(literal):
    """Half a unit of the last written digit (docs/check.md): 2.744000 -> 5e-7."""
    m = _NUMBER.fullmatch(literal)
    assert m, literal
    return 0.5 * 10.0 ** (int(m.group(3) or 0) - len(m.group(2) or ""))


def _expected(path):
    """{key: (value, tol)} of the spec's [expected] table, tol by docs/check.md."""
    text = path.read_text(encoding="utf-8")
    table = tomllib.loads(text)["expected"]
    section = text.split("\n[expected]\n", 1)[1]
    out = {}
    for key, raw in table.items():
        if isinstance(raw, dict):
            value = raw["value"]
            tol = raw["tol"] if "tol" in raw else raw["rtol"] * abs(value)
        else:
            m = re.search(r"^%s\s*=\s*([^\s#]+)" % re.escape(key), section, re.M)
            assert m, key
            value, tol = raw, _half_unit(m.group(1))
            assert float(m.group(1)) == value
        out[key] = (float(value), float(tol))
    return out


@pytest.mark.parametrize("name", ["exercise2-1", "exercise2-5"])
def test_config_expected_matches_independent_reference(name):
    expected = _expected(CONFIGS / "ch2" / (name + ".toml"))
    results = _results(name)
    assert len(expected) >= 20
    missing = sorted(set(expected) - set(results))
    assert not missing, missing
    # a relative slack of 1e-9 of the tolerance covers the binary rounding (docs/check.md)
    failed = {k: (v, results[k], tol) for k, (v, tol) in expected.items()
              if not abs(results[k] - v) <= tol * (1 + 1e-9)}
    assert not failed, failed


def test_exercise2_2_config_is_the_hand_derivation():
    # configs/ch2/exercise2-2.toml's [expected] (but the residuals, which the hand
    # derivation does not have) are the reference's fire_ladder values to their digits
    expected = _expected(CONFIGS / "ch2" / "exercise2-2.toml")
    results = _ref().exercise_2_2()
    forces = {k: v for k, v in expected.items() if not k.endswith("_residual")}
    assert len(forces) >= 15
    failed = {k: (v, results[k], tol) for k, (v, tol) in forces.items()
              if not abs(results[k] - v) <= tol * (1 + 1e-9)}
    assert not failed, failed


def test_exercise2_2_virtual_work_against_finite_differences():
    # the reference's Fb = Q dy_S2/dφ / (ds/dφ) with ds/dφ in closed form: checked here
    # with a central difference of s = |CB| (h = 1e-6 rad: error ~1e-12 relative)
    def s_of(phi):
        u = np.array([math.cos(phi), math.sin(phi)])
        n = np.array([-math.sin(phi), math.cos(phi)])
        b = np.array([0.0, 0.8]) + 0.4 * u - 0.2 * n
        return math.hypot(*(b - np.array([0.8, 0.0])))

    h = 1e-6
    for deg in (0, 20, 40, 60, 80):
        phi = math.radians(deg)
        ds = (s_of(phi + h) - s_of(phi - h)) / (2 * h)
        fb = 3000 * 1.5 * math.cos(phi) / ds
        assert _ref().fire_ladder(deg)["Fb"] == pytest.approx(fb, rel=1e-8)
    # the exercise's φ = 0 by hand: B = (0.4, 0.6), ds/dφ = 0.16/√0.52
    assert _ref().fire_ladder(0)["Fb"] == pytest.approx(4500 * math.sqrt(0.52) / 0.16,
                                                        rel=1e-13)
