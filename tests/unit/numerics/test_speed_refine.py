"""The cheaper kernels of issue 17: ``sorted_union`` (no ``numpy.ma`` import) and the
secant refinement of extremes (a few solves instead of ~40 bisection solves), each
against an independent route to the same numbers."""

import math
import subprocess
import sys

import numpy as np
import pytest

from mechcli.core.linkage import kinematics
from mechcli.core.numerics import bisect, bracketed_root, sorted_union
from mechcli.spec.kin import load_kin_spec

from tests.conftest import ROOT


def test_sorted_union_is_union1d():
    rng = np.random.default_rng(3)
    a = np.round(rng.uniform(0, 10, 200), 1)
    b = np.round(rng.uniform(0, 10, 50), 1)
    np.testing.assert_array_equal(sorted_union(a, b), np.union1d(a, b))
    np.testing.assert_array_equal(sorted_union([], [2.0, 1.0, 2.0]), [1.0, 2.0])
    np.testing.assert_array_equal(sorted_union([], []), np.empty(0))


def test_sorted_union_does_not_import_numpy_ma():
    code = ("import sys, numpy; from mechcli.core.numerics import sorted_union;"
            "sorted_union([3.0, 1.0], [1.0, 2.0]); print('numpy.ma' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.strip()
    assert out == "False"


class Counted:
    def __init__(self, f):
        self.f, self.calls = f, 0

    def __call__(self, x):
        self.calls += 1
        return self.f(np.asarray(x))


def test_bracketed_root_matches_bisection_in_few_calls():
    # cos x = 0.3 x has one root in (0, 2): the bisection of the same brackets is the reference
    f = Counted(lambda x: np.cos(x) - 0.3 * x)
    lo, hi = np.array([0.0, 0.5, 1.0, 1.2019]), np.array([2.0, 1.5, 1.25, 1.9])
    a, b = bracketed_root(lo, hi, f, 1e-13)
    ref_lo, ref_hi = bisect(lo, hi, lambda m: f.f(m) > 0, 1e-13)
    root = 0.5 * (ref_lo + ref_hi)
    assert np.all(np.abs(b - a) <= 1e-13 * np.maximum(1.0, np.abs(a)))
    np.testing.assert_allclose(0.5 * (a + b), root, rtol=0, atol=2e-13)
    # bisection takes 44 calls for these brackets, the secant alone 13; with its guard
    # probe past each step (numerics.GUARD) 6
    assert f.calls <= 8


def test_bracketed_root_falls_back_to_bisection_on_a_flat_root():
    # a triple root: the secant crawls, the safeguard bisects every other step
    f = Counted(lambda x: -(x - 0.7) ** 3)
    a, b = bracketed_root([0.0], [2.0], f, 1e-13)
    assert abs(0.5 * (a[0] + b[0]) - 0.7) < 1e-6       # |f| < 1e-18 there: as bisection
    assert f.calls <= 2 * 64 + 1


def test_bracketed_root_keeps_the_orientation_of_bisect():
    # lo on the side where f > 0, whichever way round the bracket is given
    a, b = bracketed_root([2.0], [0.0], lambda x: x - 0.25, 1e-13)
    assert a[0] >= b[0] and abs(a[0] - 0.25) < 1e-13


@pytest.fixture
def ex1_1():
    spec = load_kin_spec(ROOT / "configs" / "ch1" / "ex1-1.toml")
    qs = kinematics.default_quantities(spec.linkage, spec.output.order,
                                       [t.name for t in spec.tracers])
    return spec, qs


def _count_solves(monkeypatch):
    """A list that grows by one at every engine solve of the sweep analysis (``kinematics``
    and the modules of its steps) from now on."""
    from mechcli.core.linkage import accuracy, extremes, limits

    calls = []
    real = kinematics.solve

    def counting(*a, **k):
        calls.append(1)
        return real(*a, **k)

    for mod in (kinematics, limits, extremes, accuracy):
        monkeypatch.setattr(mod, "solve", counting)
    return calls


def test_extremes_are_stationary_points_in_few_solves(ex1_1, monkeypatch):
    spec, qs = ex1_1
    calls = _count_solves(monkeypatch)
    res = kinematics.analyse_sweep(spec.linkage, spec.input.sweep(), qs, spec.output.order)
    # bisection took 40 solves for this sweep (38 on the extremes), the secant 16; with
    # its guard probes, central differences closed to their own rounding and the
    # transmission angle refined on a smooth measure 9 (issue 17: "<= 3 ms")
    assert len(calls) <= 10
    monkeypatch.undo()   # the engine's own solve for the checks
    # at the refined max and min of omega3 its derivative alpha3 vanishes: one Newton
    # step |omega3' / omega3''| measures the distance to the true stationary point
    w1 = spec.input.sweep().dq
    for ext in res.extremes["omega3"]:
        m = kinematics.solve(spec.linkage, spec.input.sweep().inputs(np.array([ext.at])),
                             order=2)
        alpha3 = float(m.links[3].alpha[0])
        assert abs(alpha3) <= 1e-7 * abs(ext.value) * abs(w1), (ext, alpha3)
    # the max of theta3 is where omega3 = 0
    hi = res.extremes["theta3"][0]
    m = kinematics.solve(spec.linkage, spec.input.sweep().inputs(np.array([hi.at])), order=1)
    assert abs(float(m.links[3].omega[0])) <= 1e-9 * abs(w1)
    assert math.isfinite(hi.value)


def test_transmission_angle_max_at_its_fold_in_few_solves(ex1_1, monkeypatch):
    # 例 1-1's γC reaches 90° (configs/ch1/ex1-1.toml: 90.0000° at θ1 = 83.4204°): the
    # acute angle folds there, a kink where a difference quotient has one magnitude either
    # side (15 calls of the secant).  Located on the smooth -cos² of the joint angle, in a
    # few solves; independent check: the joint angle's cosine is 0 there, to the bias of
    # the central difference (h = 1e-5 rad: O(h²) ≈ 1e-11 rad of input, times the
    # cosine's rate |d cos/dθ1| <= (|ω2| + |ω3|) / ω1, 1.2 on this grid)
    spec, qs = ex1_1
    gamma = [q for q in qs if q.symbol == "gammaC"]
    sweep = spec.input.sweep()
    res = kinematics.analyse_sweep(spec.linkage, sweep, qs, spec.output.order)
    calls = _count_solves(monkeypatch)
    only = kinematics.analyse_sweep(spec.linkage, sweep, gamma, 0)
    monkeypatch.undo()
    hi = only.extremes["gammaC"][0]
    assert math.degrees(hi.at) == pytest.approx(83.4204, abs=5e-5)
    assert hi.at == pytest.approx(res.extremes["gammaC"][0].at, abs=1e-12)
    m = kinematics.solve(spec.linkage, sweep.inputs(np.array([hi.at])), order=0)   # (undone)
    cos_joint = float(m.condition("C").cos_joint[0])
    rate = float(np.max(np.abs(res.values["omega2"]) + np.abs(res.values["omega3"]))
                 / sweep.dq)
    assert abs(cos_joint) <= rate * 1e-11
    # the value: 90° less the cosine (γ = atan2(|sin|, |cos|) ≈ π/2 - |cos| there)
    assert hi.value == pytest.approx(math.pi / 2 - abs(cos_joint), abs=1e-15)
    # the whole analysis of γC alone: 13 solves on γ's difference quotient, 9 on -cos²
    assert len(calls) <= 10
