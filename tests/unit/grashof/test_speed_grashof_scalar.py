"""The pure-Python four-bar (:mod:`mechcli.core.grashof.chain`, used by ``mechcli grashof
--lengths`` so that it does not import numpy) against the vectorized one
(:mod:`mechcli.core.grashof.fourbar`, batches and type charts): same type, cranks
and figures of merit for every length set, change points and parallelograms included."""

import itertools
import math

import numpy as np
import pytest

from mechcli.core.grashof import chain
from mechcli.core.grashof import fourbar as gf
from mechcli.report.grashof import chain_csv, fourbar_csv

# integer lengths 1..6: many equal links, change points (s + l = p + q) and parallelograms
_SETS = [L for L in itertools.product(range(1, 7), repeat=4) if 2 * max(L) < sum(L)]
_RNG = np.random.default_rng(17)
_SETS += [tuple(x) for x in _RNG.uniform(0.1, 10.0, size=(400, 4)).tolist()
          if 2 * max(x) < sum(x)]

_MERIT = ("theta1_ext", "theta1_fold", "theta3_ext", "theta3_fold", "theta", "psi", "K",
          "input_lo", "input_hi", "gamma_min", "gamma_min_at", "gamma_max", "gamma_max_at",
          "gamma0", "gamma180")
_FLAGS = ("input_turns", "output_turns", "has_limits", "has_gamma0", "has_gamma180")


def test_the_sets_cover_the_special_cases():
    kl = gf.classify_fourbar(np.array(_SETS))
    assert kl.change_point.sum() > 100
    assert {"parallelogram", "change_point_crank_rocker", "change_point_double_crank",
            "change_point_double_rocker", "crank_rocker", "double_crank",
            "double_rocker"} <= set(kl.types)


@pytest.mark.parametrize("frame", [1, 2, 3, 4])
@pytest.mark.parametrize("crossed", [False, True])
def test_type_is_the_vectorized_type(frame, crossed):
    L = np.array(_SETS)
    kl = gf.classify_fourbar(L, frame=frame, crossed=crossed)
    for i, lengths in enumerate(_SETS):
        one = chain.classify_chain(lengths, frame, crossed)
        assert (one.type, one.grashof, one.change_point, one.longest, one.shortest) == \
            (kl.types[i], bool(kl.grashof[i]), bool(kl.change_point[i]), int(kl.longest[i]),
             int(kl.shortest[i])), lengths
        assert list(one.cranks) == kl.cranks(i), lengths
        assert one.excess == kl.excess[i]


@pytest.mark.parametrize("frame, inp", [(4, 1), (4, 3), (1, 2), (2, 3)])
def test_figures_of_merit_are_the_vectorized_ones(frame, inp):
    an = gf.analyse_fourbar(np.array(_SETS), frame, inp)
    m = an.merit
    for i, lengths in enumerate(_SETS):
        one = chain.analyse_chain(lengths, frame, inp)
        assert (one.coupler, one.output) == (int(an.coupler[i]), int(an.output[i]))
        for f in _FLAGS:
            assert getattr(one.merit, f) == bool(getattr(m, f)[i]), (lengths, f)
        for f in _MERIT:   # the same closed forms; libm and numpy may differ in the last bit
            assert math.isclose(getattr(one.merit, f), float(getattr(m, f)[i]),
                                rel_tol=1e-12, abs_tol=1e-12), (lengths, f)
        assert one.merit.dead_output == tuple(m.dead_output[i].tolist())
        for j in (0, 1):
            assert math.isclose(one.merit.dead_theta3[j], float(m.dead_theta3[i, j]),
                                rel_tol=1e-12, abs_tol=1e-12)


def test_one_row_csv_is_the_batch_csv():
    sets = [(40.0, 90.0, 70.0, 100.0), (100.0, 150.0, 170.0, 110.0), (2.0, 3.0, 2.0, 3.0),
            (1.0, 2.0, 3.0, 4.0), (30.0, 10.0, 35.0, 50.0)]
    for L in sets:
        for digits in (4, 10):
            assert chain_csv(chain.analyse_chain(L), 1e-3, digits) == \
                fourbar_csv(gf.analyse_fourbar(L), 1e-3, digits=digits), L


def test_closure_error_is_one_class_for_both_forms():
    with pytest.raises(gf.ClosureError, match="link 2") as exc:
        chain.analyse_chain([10, 100, 20, 30])
    assert (exc.value.length, exc.value.limit, exc.value.link) == (100.0, 60.0, 2)
    assert chain.ClosureError is gf.ClosureError
    with pytest.raises(ValueError, match="joined to the frame"):
        chain.analyse_chain([40, 90, 70, 100], frame=4, input_link=2)


def test_example_3_1_crank_rocker():
    # 例 3-1 style: l = 100, s = 40, p + q = 160 > s + l = 140: crank-rocker, crank link 1
    one = chain.analyse_chain([40, 90, 70, 100])
    assert one.klass.type == "crank_rocker" and one.klass.cranks == (1,)
    assert one.klass.excess == -20.0
    # K = (180 + θ)/(180 − θ) with θ from the law of cosines (independent of the module)
    phi_e = math.acos((130 ** 2 + 100 ** 2 - 70 ** 2) / (2 * 130 * 100))
    phi_f = math.acos((50 ** 2 + 100 ** 2 - 70 ** 2) / (2 * 50 * 100))
    theta = abs(phi_f - phi_e)
    assert one.merit.theta == pytest.approx(theta, rel=1e-14)
    assert one.merit.K == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-14)
