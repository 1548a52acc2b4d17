"""The independent force reference (tests/reference/independent_force.py) solves square
systems: one balancing torque and two unknowns per lower pair against three equations per
moving link.  Counts from the books' problems; a non-square model is refused with its
numbers, never solved by least squares."""

import importlib.util

import numpy as np
import pytest

from tests.conftest import ROOT


def _reference():
    path = ROOT / "tests" / "reference" / "independent_force.py"
    spec = importlib.util.spec_from_file_location("independent_force", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


#: name -> (moving links, lower pairs): 例 2-1 four-bar 3 and 4, 例 2-2 slider-crank 3 and 4,
#: 例 2-3 guide bar 3 and 4, 例 2-4 shaper 5 and 7 (15 unknowns), 习题 2-8 crusher 5 and 7
COUNTS = {"ex2-1": (3, 4), "ex2-2": (3, 4), "ex2-3": (3, 4), "ex2-4": (5, 7),
          "exercise2-8": (5, 7)}


@pytest.mark.parametrize("name", sorted(COUNTS))
def test_reference_systems_are_square(name):
    ref = _reference()
    prob = next(c() for c in vars(ref).values()
                if isinstance(c, type) and issubclass(c, ref.Problem)
                and getattr(c, "name", None) == name)
    assert (len(prob.links), len(prob.pairs)) == COUNTS[name]
    # the square system solved at three inputs: a reaction for every pair, and its Mb
    # passes the virtual-power balance (Σ known loads · v + Mb ω1 = 0) to round-off of the
    # power's terms (2e-13 .. 7e-13 measured); a mis-assembled system would not
    if hasattr(prob, "prepare"):
        prob.prepare()
    out, _kin, _active = ref.evaluate(prob, np.radians([30.0, 120.0, 200.0]))
    reactions = [k for k in out if k.startswith("FR") and not k.endswith(("x", "y"))]
    assert len(reactions) == len(prob.pairs)
    assert np.all(np.isfinite(out["Mb"])) and np.max(np.abs(out["Mb"])) > 1.0
    assert np.max(out["power_residual_abs"] / out["power_scale"]) < 1e-11


def test_a_non_square_model_is_refused_with_its_counts():
    ref = _reference()
    prob = ref.Shaper()
    prob.pairs = prob.pairs[:-1]                     # the ram's guide left out
    th = np.radians([30.0, 60.0])
    kin = ref.kinematics(ref.Shaper(), th)
    with pytest.raises(ValueError, match="ex2-4: 13 unknowns for 15 equations"):
        ref.kinetostatics(prob, kin, np.zeros(th.shape, bool))
