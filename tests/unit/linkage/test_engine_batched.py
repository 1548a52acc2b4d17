"""The engine batched over designs, as optimize and the atlas use it: every element
parameter may be an array; a batch equals separate solves; a bad design stays in its
own row; misuse fails with a clear message; the kinetostatic evaluator and the
sweeps accept what the library docs promise.

Where the numbers come from: every "expected" value below is the same engine run on
one design at a time (the batch must equal it bit for bit: the same floating-point
operations on the same numbers), a closed form stated at the test, or a balance.
"""

import warnings

import numpy as np
import pytest

import mechcli
from mechcli.core.linkage import (PRP, RPR, RRP, RRR, Crank, DriverMotion, Ground, Linkage,
                                  LinkageDefinitionError, PointOnLink, SliderDriver,
                                  kinematic_coefficients, solve)
from mechcli.core.linkage.force_analysis import ForceEvaluator
from mechcli.core.linkage.kinematics import Quantity, Sweep, analyse_sweep, default_quantities
from mechcli.core.linkage.kinetostatics import Body, Load, LoadProgram, topology

TH = np.radians(np.linspace(0.0, 360.0, 25))


def _col(*v):
    return np.array(v, dtype=float)[:, None]


def _four_bar(ax=0.0, dx=0.3, dy=0.0, l1=0.1, l2=0.25, l3=0.2, br=1):
    return Linkage(4, (Ground("A", ax, 0.0), Ground("D", dx, dy), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, br)))


def _slider_crank(l2=0.3, e=0.02, ga=0.0, br=1):
    return Linkage(4, (Ground("A", 0.0, 0.0), Crank(1, "A", "B", 0.1),
                       RRP("C", "B", 2, l2, 3, 4, "A", ga, e, br, "3")))


def _guide_bar(l1=0.1, l4=0.3, e=0.0, br=1):
    return Linkage(4, (Ground("C", 0.0, 0.0), Ground("A", 0.0, l4), Crank(1, "A", "B", l1),
                       RPR("B", 2, "C", 3, e, br, "23")))


def _coupler_point(along=0.1, normal=0.05):
    return _four_bar().with_elements(PointOnLink("E", 2, "B", along, normal))


def _cross_slide(ga=0.5, gb=2.0, oa=0.0, ob=0.01):
    return Linkage(4, (Ground("A", 0.0, 0.0), Ground("G", 0.3, 0.0), Crank(1, "A", "B", 0.1),
                       PRP("C", 2, 1, "B", 3, 4, "G", ga, oa, gb, ob)))


def _slider_driven(angle=0.2):
    return Linkage(4, (Ground("O", 0.0, 0.0), Ground("A", 0.1, 0.15),
                       SliderDriver(1, "O", "B", angle), RRR("C", "B", 2, 0.2, "A", 3, 0.15, 1)))


def _crank_input(q):
    return {1: DriverMotion(q, 10.0, 3.0)}


def _slide_input(q):
    return {1: DriverMotion(0.05 * np.cos(q), 0.3, 0.1)}


def _arrays(m):
    """Every result array of a motion, by a readable key."""
    out = {"feasible": m.feasible, "regular": m.regular}
    for n, p in m.points.items():
        for a in ("x", "y", "vx", "vy", "ax", "ay"):
            out[f"{a}{n}"] = getattr(p, a)
    for n, k in m.links.items():
        for a in ("theta", "omega", "alpha"):
            out[f"{a}{n}"] = getattr(k, a)
    for n, s in m.slides.items():
        for a in ("s", "v", "a"):
            out[f"{a}{n}"] = getattr(s, a)
    for c in m.conditions:
        out[f"sin_gamma{c.joint}"] = c.sin_gamma
    return out


# (builder, batched parameters (M, 1), input): every parameter position of every element,
# including zero-length, infeasible and parallel-guide designs inside the batch
CASES = {
    "ground x": (_four_bar, dict(ax=_col(0, 0.01, -0.02)), _crank_input),
    "ground x, y": (_four_bar, dict(dx=_col(0.3, 0.28, 0.0), dy=_col(0, 0.02, 0.0)), _crank_input),
    "crank length (one design does not assemble, one is zero)":
        (_four_bar, dict(l1=_col(0.1, 0.2, 0.0)), _crank_input),
    "RRR lengths (zero coupler, zero rocker)":
        (_four_bar, dict(l2=_col(0.25, 0.0, 0.23), l3=_col(0.2, 0.21, 0.0)), _crank_input),
    "RRR branch": (_four_bar, dict(br=np.array([1, -1, 1])[:, None]), _crank_input),
    "RRP length (zero rod)": (_slider_crank, dict(l2=_col(0.3, 0.0, 0.25)), _crank_input),
    "RRP offset": (_slider_crank, dict(e=_col(0.02, 0.0, -0.03)), _crank_input),
    "RRP guide angle": (_slider_crank, dict(ga=_col(0.0, 0.3, -0.5)), _crank_input),
    "RRP branch": (_slider_crank, dict(br=np.array([1, -1])[:, None]), _crank_input),
    "RPR frame, crank (block through the pivot, zero frame)":
        (_guide_bar, dict(l1=_col(0.1, 0.3, 0.2), l4=_col(0.3, 0.3, 0.0)), _crank_input),
    "RPR offset": (_guide_bar, dict(e=_col(0.0, 0.02, -0.01)), _crank_input),
    "RPR branch": (_guide_bar, dict(br=np.array([1, -1])[:, None]), _crank_input),
    "PointOnLink along, normal":
        (_coupler_point, dict(along=_col(0.1, 0.2, 0.0), normal=_col(0.05, 0.0, -0.1)),
         _crank_input),
    "PRP angles (one design with parallel guides), offsets":
        (_cross_slide, dict(ga=_col(0.5, 0.5, 1.5), gb=_col(2.0, 0.5, 2.5),
                            oa=_col(0.0, 0.01, -0.02), ob=_col(0.01, 0.0, 0.03)), _crank_input),
    "SliderDriver angle": (_slider_driven, dict(angle=_col(0.0, 0.3, -0.4)), _slide_input),
}


@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("case", sorted(CASES))
def test_batch_equals_separate_solves_in_every_parameter(case, order):
    """A batch of M designs (parameters (M, 1), inputs (N,)) equals M separate solves
    bit for bit (the same operations on the same numbers), masks included, with no
    warning even where one design has a zero-length link or parallel guides."""
    build, params, inputs = CASES[case]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        batch = _arrays(solve(build(**params), inputs(TH), order=order))
        m = len(next(iter(params.values())))
        for i in range(m):
            one = _arrays(solve(build(**{k: v[i, 0] for k, v in params.items()}),
                                inputs(TH), order=order))
            assert one.keys() == batch.keys()
            for key, expect in one.items():
                if expect is None:
                    assert batch[key] is None, key
                    continue
                got = np.broadcast_to(batch[key], (m, TH.size))[i]
                assert np.array_equal(got, expect), (case, key, i)
                assert np.all(np.isfinite(got)), (case, key, i)


def test_zero_length_designs_are_infeasible_not_nan():
    """A rocker, a coupler or a slider rod of zero length cannot assemble (its angle is
    undefined): the design is infeasible at every input, its neighbours are not touched
    (例 1-1's four-bar, l3 = 177.8 mm, turns a full revolution)."""
    l3 = _col(0.1778, 0.0, 0.1778)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m = mechcli.solve(mechcli.four_bar(0.1016, 0.254, l3, 0.3048),
                          {1: DriverMotion(TH, 250.0)})
        s = mechcli.solve(mechcli.slider_crank(0.1, _col(0.3, 0.0)), {1: DriverMotion(TH, 1.0)})
    assert m.feasible.all(axis=-1).tolist() == [True, False, True]
    assert not m.regular[1].any()
    assert np.array_equal(m.links[3].omega[0], m.links[3].omega[2])
    assert s.feasible.any(axis=-1).tolist() == [True, False]


def test_non_finite_design_is_infeasible_without_warnings():
    """An optimizer's inf or NaN parameter makes that design infeasible, silently for
    the others (pytest turns any RuntimeWarning into an error)."""
    l1 = _col(0.1, np.inf, np.nan, 0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m = mechcli.solve(mechcli.four_bar(l1, 0.25, 0.2, 0.3), {1: DriverMotion(TH, 10.0)})
    assert m.feasible.all(axis=-1).tolist() == [True, False, False, True]
    assert not m.regular[1:3].any()
    assert np.array_equal(m.links[3].alpha[0], m.links[3].alpha[3])


@pytest.mark.parametrize("lengths, angles", [
    ((4, 13), (13,)),        # a length per design and position against the angles
    ((2, 1, 1), (3, 13)),    # designs against a (K, N) block of inputs
])
def test_batch_shapes_broadcast(lengths, angles):
    """Results take the broadcast shape of parameters and inputs, and every value
    equals the single-design, single-position solve."""
    rng = np.random.default_rng(1)
    l3 = 0.19 + 0.02 * rng.random(lengths)
    q = rng.uniform(0.0, 2 * np.pi, angles)
    m = solve(mechcli.four_bar(0.1, 0.25, l3, 0.3), {1: DriverMotion(q, 10.0, 2.0)})
    shape = np.broadcast_shapes(lengths, angles)
    assert m.links[3].alpha.shape == m.points["A"].x.shape == m.feasible.shape == shape
    l3b, qb = np.broadcast_to(l3, shape), np.broadcast_to(q, shape)
    for idx in [(0,) * len(shape), tuple(s - 1 for s in shape)]:
        one = solve(mechcli.four_bar(0.1, 0.25, l3b[idx], 0.3),
                    {1: DriverMotion(qb[idx], 10.0, 2.0)})
        assert m.links[3].alpha[idx] == one.links[3].alpha
        assert m.points["C"].vy[idx] == one.points["C"].vy


def test_rate_arrays_set_the_result_shape():
    """ω1 per design (shape (M, 1)) against angles (N,): every result, positions and
    masks included, has the shape (M, N) (before, positions and masks kept (N,) while
    the velocities were (M, N)); ω3 is ω1 times the coefficient dθ3/dφ."""
    w = _col(1.0, 2.0)
    m = solve(mechcli.four_bar(0.1, 0.25, 0.2, 0.3), {1: DriverMotion(TH, w)})
    c = kinematic_coefficients(mechcli.four_bar(0.1, 0.25, 0.2, 0.3), TH)
    for a in (m.feasible, m.regular, m.links[1].theta, m.points["B"].x, m.links[3].omega):
        assert a.shape == (2, TH.size)
    np.testing.assert_allclose(m.links[3].omega, w * c.links[3].omega, rtol=0, atol=1e-12)
    # order 0 does not use the rates: positions keep the inputs' shape
    assert solve(mechcli.four_bar(0.1, 0.25, 0.2, 0.3), {1: DriverMotion(TH, w)},
                 order=0).feasible.shape == TH.shape


def test_list_parameters_are_arrays():
    """A list of lengths is a batch, as an array is."""
    m = solve(mechcli.four_bar([0.1, 0.12], 0.25, 0.2, 0.3), {1: DriverMotion(0.3, 1.0)})
    e = solve(mechcli.four_bar(np.array([0.1, 0.12]), 0.25, 0.2, 0.3), {1: DriverMotion(0.3)})
    assert np.array_equal(m.links[3].theta, e.links[3].theta)


@pytest.mark.parametrize("call, error, match", [
    (lambda lk: solve(lk, {}), LinkageDefinitionError, "no input given for driver link 1"),
    (lambda lk: solve(lk, {1: DriverMotion(TH), 2: DriverMotion(TH)}),
     LinkageDefinitionError, "link 2, which is not driven"),
    (lambda lk: solve(lk, {1: TH}), TypeError, "must be a DriverMotion"),
    (lambda lk: solve(lk, {1: DriverMotion(TH, np.ones(5))}), ValueError,
     r"do not broadcast together: q of link 1 \(25,\), dq of link 1 \(5,\)"),
    (lambda lk: solve(lk, {1: DriverMotion(TH, 1.0, np.ones(5))}), ValueError,
     r"ddq of link 1 \(5,\)"),
    (lambda lk: solve(lk, {1: DriverMotion(TH)}, on_fail="rais"), ValueError,
     "on_fail must be 'mask' or 'raise'"),
    (lambda lk: solve(lk, {1: DriverMotion(TH)}, order=3), ValueError, "order must be"),
])
def test_misuse_fails_clearly(call, error, match):
    with pytest.raises(error, match=match):
        call(mechcli.four_bar(0.1, 0.25, 0.2, 0.3))


def test_lengths_that_do_not_broadcast_name_the_shapes():
    with pytest.raises(ValueError, match=r"q of link 1 \(25,\).*linkage parameters \(5,\)"):
        solve(mechcli.four_bar(np.full(5, 0.1), 0.25, 0.2, 0.3), {1: DriverMotion(TH)})
    lk = mechcli.four_bar(np.full(5, 0.1), np.full(3, 0.25), 0.2, 0.3)
    with pytest.raises(ValueError, match=r"do not broadcast.*length \(5,\).*length_a \(3,\)"):
        lk.shape


@pytest.mark.parametrize("branch", [0, 2, -2, 0.5])
def test_branch_must_be_plus_or_minus_one(branch):
    """Branch 0 puts the joint on the line of centres, 2 off both circles: neither is
    an assembly mode, and before they solved silently."""
    with pytest.raises(ValueError, match="branch must be"):
        mechcli.four_bar(0.1, 0.25, 0.2, 0.3, branch=branch)
    with pytest.raises(ValueError, match="branch must be"):
        mechcli.four_bar(0.1, 0.25, 0.2, 0.3, branch=np.array([[1], [branch]]))


def test_on_fail_raise_counts_every_design():
    """Design 2 (l1 = 0.2 m > the Grashof limit) fails at 3 of 13 positions
    (a count from the masked solve of the same batch)."""
    lk = mechcli.four_bar(_col(0.1, 0.2), 0.25, 0.2, 0.3)
    q = np.radians(np.linspace(0, 360, 13))
    bad = int(np.count_nonzero(~solve(lk, {1: DriverMotion(q, 1.0)}).regular))
    assert bad == 3
    from mechcli.core.errors import AssemblyError
    with pytest.raises(AssemblyError, match="at 3 of 26 input positions"):
        solve(lk, {1: DriverMotion(q, 1.0)}, on_fail="raise")


def test_linkage_queries_of_a_batch():
    lk = mechcli.four_bar(_col(0.1, 0.2, 0.05), 0.25, 0.2, 0.3)
    assert lk.shape == (3, 1)
    np.testing.assert_array_equal(lk.scale(), np.full((3, 1), 0.3))   # the frame, 0.3 m
    assert lk.with_elements(PointOnLink("E", 2, "B", np.array([0.1, 0.2]))).shape == (3, 2)
    sh = mechcli.shaper(0.1, 0.5, 0.15, 0.3, 0.55)
    assert (sh.rotating_links, sh.slide_names, sh.translating_links) == ((3, 4), ("23", "E"),
                                                                         (5,))
    assert lk.transmission_joints == ("C",)
    m = solve(sh, {1: DriverMotion(TH, 1.0)})
    assert [c.joint for c in m.conditions] == ["B", "E"]


def _five_bar():
    """configs/ch1/fivebar.toml in metres: two cranks, θ4 = 90° − θ1."""
    return Linkage(5, (Ground("A", 0.0, 0.0), Ground("E", 0.021, 0.0),
                       Crank(1, "A", "B", 0.005), Crank(4, "E", "D", 0.013),
                       RRR("C", "B", 2, 0.020, "D", 3, 0.022, 1)))


def test_coefficients_with_a_follower_are_total_derivatives():
    """dθ3/dφ and d²θ3/dφ² of the two-crank five-bar (θ4 = π/2 − θ1) against central
    differences of θ3(φ) with both cranks moved (h = 1e-4 rad: error ~h² ≈ 1e-8)."""
    lk, h = _five_bar(), 1e-4
    c = kinematic_coefficients(lk, TH, {4: (-1.0, np.pi / 2)})
    t = [solve(lk, {1: DriverMotion(TH + d), 4: DriverMotion(np.pi / 2 - TH - d)},
               order=0).links[3].theta for d in (-h, 0.0, h)]
    np.testing.assert_allclose(c.links[3].omega, (t[2] - t[0]) / (2 * h), atol=1e-7)
    np.testing.assert_allclose(c.links[3].alpha, (t[2] - 2 * t[1] + t[0]) / h**2, atol=1e-4)
    assert np.all(c.links[4].omega == -1.0)
    with pytest.raises(LinkageDefinitionError, match=r"links \[4\] are secondary drivers"):
        kinematic_coefficients(lk, TH)


def test_coefficients_with_a_slider_driver():
    """dθ3/ds [rad/m] against a central difference (h = 1e-6 m)."""
    lk, s, h = _slider_driven(), np.linspace(-0.05, 0.05, 11), 1e-6
    c = kinematic_coefficients(lk, s)
    t = [solve(lk, {1: DriverMotion(s + d)}, order=0).links[3].theta for d in (-h, h)]
    np.testing.assert_allclose(c.links[3].omega, (t[1] - t[0]) / (2 * h), atol=1e-6)
    assert np.all(c.slides["1"].v == 1.0)


def _slider_crank_forces(l1, mass1=2.0, angle_load=False):
    lk = mechcli.slider_crank(l1, 0.35, 0.02)
    bodies = {1: Body(1, mass1, 0.01), 2: Body(2, 3.0, 0.04), 3: Body(3, 5.0, 0.0)}
    vel = Quantity("v3", "velocity", 1, lambda m: m.slides["3"].v)
    # the resistance acts only while the slider moves back (a velocity-sign program)
    programs = [LoadProgram(Load("Fr", 3, fx=-400.0), velocity=vel, sign=-1)]
    sweep = Sweep(1, TH, lambda q: 10.0 + 2.0 * np.sin(q),
                  lambda q: 2.0 * np.cos(q) * (10.0 + 2.0 * np.sin(q)))
    return ForceEvaluator(lk, topology(lk), sweep, bodies, (0.0, -9.8), programs)


def test_force_evaluator_over_a_batch_equals_separate_evaluations():
    """Reactions, balancing torque, load masks and the virtual-power residual of a
    batch of 3 slider-cranks (crank lengths and crank masses per design) equal the
    separate evaluations bit for bit; before, the batch failed inside numpy."""
    l1, mass = _col(0.08, 0.1, 0.12), _col(1.0, 2.0, 3.0)
    fr, masks, motion = _slider_crank_forces(l1, mass)(TH)
    assert fr.balancing[1].shape == masks["Fr"].shape == fr.cond.shape == (3, TH.size)
    for i in range(3):
        f1, m1, _ = _slider_crank_forces(float(l1[i, 0]), float(mass[i, 0]))(TH)
        assert np.array_equal(fr.balancing[1][i], f1.balancing[1])
        assert np.array_equal(masks["Fr"][i], m1["Fr"])
        for pa, pb in zip(fr.pairs, f1.pairs):
            assert np.array_equal(pa.fx[i], pb.fx) and np.array_equal(pa.couple[i], pb.couple)
        assert np.array_equal(fr.cond[i], f1.cond)
    assert float(np.max(np.abs(fr.power_residual))) <= 1e-9 * float(np.max(np.abs(fr.balancing[1])))


def test_force_bodies_that_do_not_match_the_motion_fail_clearly():
    """Masses per design need a batched linkage (or input): a (2, 1) mass against a
    single design's motion of shape (25,) is named in the error."""
    ev = _slider_crank_forces(0.1, _col(1.0, 2.0))
    with pytest.raises(ValueError, match=r"body of link 1: mass of shape \(2, 1\).*\(25,\)"):
        ev(TH)


def test_rate_array_over_a_falling_sweep_interpolates():
    """A crank turning backwards: q from 360° down to 0° with ω(q) tabulated on it.
    Between nodes the rate is the linear interpolation (ω = 10 + 2 sin q is within
    2·(5°)²/8 ≈ 0.0019 rad/s of it); before, np.interp got falling nodes and returned
    the end value 10 everywhere."""
    q = np.radians(np.arange(360.0, -1.0, -5.0))
    sweep = Sweep(1, q, 10.0 + 2.0 * np.sin(q))
    x = np.radians([12.5, 100.0, 222.5])
    np.testing.assert_allclose(sweep.speed(x), 10.0 + 2.0 * np.sin(x), atol=2e-3)
    with pytest.raises(ValueError, match="strictly monotonic"):
        Sweep(1, np.array([0.0, 1.0, 0.5]), np.ones(3)).speed(np.array([0.2]))


def test_refined_analysis_refuses_a_batch_clearly():
    lk = mechcli.four_bar(_col(0.1, 0.12), 0.25, 0.2, 0.3)
    with pytest.raises(ValueError, match=r"one design at a time.*\(2, 1\)"):
        analyse_sweep(lk, Sweep(1, TH, 1.0), default_quantities(_four_bar(), 2), 2)


@pytest.mark.parametrize("rate", ["array", "callable"])
def test_partial_sweep_with_varying_rate(rate):
    """A four-bar that cannot turn fully (l3 = 0.1 m) analysed on its feasible range with
    ω1(φ), α1(φ): at every analysed row α3 = α1 dθ3/dφ + ω1² d²θ3/dφ² (the coefficients
    combine exactly on the grid nodes, where both rate forms are exact)."""
    lk = mechcli.four_bar(0.1, 0.25, 0.1, 0.3)
    q = np.radians(np.arange(0.0, 361.0, 1.0))

    def om(x):
        return 10.0 + 2.0 * np.sin(x)

    def al(x):
        return 2.0 * np.cos(x) * om(x)

    dq, ddq = (om(q), al(q)) if rate == "array" else (om, al)
    res = analyse_sweep(lk, Sweep(1, q, dq, ddq, {}, True), default_quantities(lk, 2), 2,
                        partial=True)
    assert res.excluded and res.excluded[0][2] == "cannot assemble"
    c = kinematic_coefficients(lk, res.q)
    expect = al(res.q) * c.links[3].omega + om(res.q) ** 2 * c.links[3].alpha
    np.testing.assert_allclose(res.values["alpha3"], expect, rtol=0, atol=1e-9)
