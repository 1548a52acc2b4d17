"""5R five-bar and RRRRP crank conditions (the five-bar paper), and the mobility count.

The paper's double-crank criterion is checked independently by sweeping both
input angles of the 2-DOF five-bar through the linkage engine: the two inputs
turn fully and independently iff the linkage assembles, with links 2 and 3
never in line, at every pair of input angles.  The grids contain 0 and π, where
B and D are closest and farthest apart (the paper's eqs. 9-10), so the sweep
sees the extreme configurations exactly.
"""

import numpy as np
import pytest

from mechcli.core.grashof.fivebar import classify_fivebar, fivebar_roles, rrrrp_crank
from mechcli.core.errors import UnsolvableError
from mechcli.core.linkage import RRP, RRR, Crank, DriverMotion, Ground, Linkage, solve
from mechcli.core.grashof.mobility import Joint, MobilityError, count_mobility


def _five_bar(L, frame=5):
    """The engine's five-bar: frame link on the x axis, inputs about its two ends."""
    i1, i2, c1, c2 = fivebar_roles(frame)
    f = L[frame - 1]
    return Linkage(frame=frame, elements=(
        Ground("A", 0.0, 0.0), Ground("E", f, 0.0),
        Crank(link=i1, pivot="A", point="B", length=L[i1 - 1]),
        Crank(link=i2, pivot="E", point="D", length=L[i2 - 1]),
        RRR(joint="C", point_a="B", link_a=c1, length_a=L[c1 - 1], point_b="D", link_b=c2,
            length_b=L[c2 - 1], branch=+1)))


def _sweep_all_regular(L, frame=5, n=145):
    i1, i2, _, _ = fivebar_roles(frame)
    th = np.linspace(0, 2 * np.pi, n)          # step 2.5°, contains 0 and π
    t1, t4 = np.meshgrid(th, th, indexing="ij")
    mo = solve(_five_bar(L, frame), {i1: DriverMotion(t1), i2: DriverMotion(t4)}, order=0,
               on_fail="mask")
    if not mo.feasible.all():
        return False
    # links 2 and 3 never in line (no dead point of the 2-DOF linkage)
    _, _, c1, c2 = fivebar_roles(frame)
    s = np.abs(np.sin(mo.links[c1].theta - mo.links[c2].theta))
    return bool(s.min() > 1e-9)


def test_paper_example_1_triple_crank():
    kl = classify_fivebar([10, 21, 19, 20, 5])
    assert kl.types == ["triple_crank"] and kl.klass[0] == 1
    assert kl.cranks() == [1, 2, 4]     # AB, DE input cranks, BC the coupler crank
    assert _sweep_all_regular([10, 21, 19, 20, 5])


def test_paper_example_2_double_crank():
    kl = classify_fivebar([5, 20, 22, 13, 21])
    assert kl.types == ["double_crank"] and kl.cranks() == [1, 4]
    assert _sweep_all_regular([5, 20, 22, 13, 21])


def test_the_rule_against_the_engine_sweep():
    """Triple or double crank (the paper) <=> both inputs turn independently (engine)."""
    rng = np.random.default_rng(11)
    seen = set()
    count = 0
    while count < 40:
        L = rng.integers(2, 30, 5).astype(float)
        if L.max() >= L.sum() - L.max():
            continue
        frame = int(rng.integers(1, 6))
        kl = classify_fivebar(L, frame=frame)
        t = kl.types[0]
        if t in seen and count > 20 and t not in ("triple_crank", "double_crank"):
            continue
        if abs(kl.excess[0]) < 0.5:          # keep clear of the class-I boundary
            continue
        seen.add(t)
        count += 1
        expect = t in ("triple_crank", "double_crank")
        assert kl.inputs_independent[0] == expect, (L, frame, t)
        assert _sweep_all_regular(list(L), frame) == expect, (L, frame, t)
    assert {"triple_crank", "double_crank"} <= seen and len(seen) >= 4


def test_closed_form_independence_matches_rule_on_many_samples():
    rng = np.random.default_rng(5)
    L = rng.uniform(1, 10, (50_000, 5))
    L = L[L.max(axis=1) < L.sum(axis=1) - L.max(axis=1)]
    for frame in (1, 3, 5):
        kl = classify_fivebar(L, frame=frame)
        rule = np.isin(kl.code, [0, 1])
        assert np.array_equal(rule, kl.inputs_independent)


def test_fivebar_that_cannot_close():
    with pytest.raises(UnsolvableError, match="cannot close"):
        classify_fivebar([1, 1, 1, 1, 10])


# ------------------------------------------------------------------------ RRRRP
def _slider_crank(l1, c, e):
    return Linkage(frame=4, elements=(
        Ground("A", 0.0, 0.0), Ground("O", 0.0, e),
        Crank(link=1, pivot="A", point="B", length=l1),
        RRP(joint="D", point="B", link=2, length=c, slider=3, guide_link=4, guide_point="O")))


@pytest.mark.parametrize("l1, l2, l3, e", [(10, 40, 25, 3), (10, 40, 30, 0), (10, 40, 28, 3)])
def test_rrrrp_condition_against_locked_fold_angles(l1, l2, l3, e):
    """Eq. (20) with offset: link 1 turns for every locked angle between links 2 and 3.

    Each locked angle makes a slider-crank with coupler BD between |l2 - l3| and
    l2 + l3; the engine sweeps the crank through a full turn for each.
    """
    rc = rrrrp_crank(l1, l2, l3, e)
    th = np.linspace(0, 2 * np.pi, 3601)
    all_turn = True
    for c in np.linspace(abs(l2 - l3), l2 + l3, 41):
        mo = solve(_slider_crank(l1, c, e), {1: DriverMotion(th)}, order=0, on_fail="mask")
        all_turn &= bool(mo.feasible.all())
    assert rc.crank_any_fold == all_turn
    assert rc.crank_any_fold == (l1 + e <= abs(l2 - l3))


def test_rrrrp_slider_positions_where_link1_turns():
    """With the slider held at x, the crank + RRR to D = (x, e) turns iff x in [lo, hi]."""
    l1, l2, l3, e = 10.0, 40.0, 25.0, 3.0
    rc = rrrrp_crank(l1, l2, l3, e)
    th = np.linspace(0, 2 * np.pi, 3601)

    def turns(x):
        lk = Linkage(frame=5, elements=(
            Ground("A", 0.0, 0.0), Ground("D", x, e),
            Crank(link=1, pivot="A", point="B", length=l1),
            RRR(joint="C", point_a="B", link_a=2, length_a=l2, point_b="D", link_b=3,
                length_b=l3)))
        return bool(solve(lk, {1: DriverMotion(th)}, order=0, on_fail="mask").feasible.all())

    for x in np.linspace(rc.slider_lo, rc.slider_hi, 7)[1:-1]:
        assert turns(x) and turns(-x)
    assert not turns(rc.slider_lo - 0.5) and not turns(rc.slider_hi + 0.5)


# ---------------------------------------------------------------------- mobility
def test_mobility_counts_compound_hinge_local_dof_and_redundancy():
    mob = count_mobility([Joint("R", (6, 1), "A"), Joint("R", (1, 2), "B"),
                          Joint("R", (2, 3, 4), "C"), Joint("R", (3, 6), "D"),
                          Joint("R", (4, 5), "E"), Joint("P", (5, 6))], frame=6)
    assert (mob.n, mob.P_L, mob.P_H, mob.F) == (5, 7, 0, 1)
    cam = count_mobility([Joint("R", (1, 2)), Joint("R", (3, 4)), Joint("P", (4, 1)),
                          Joint("H", (2, 3))], frame=1, local_dof=1)
    assert cam.F == 1 and cam.P_H == 1
    # a parallelogram with a third parallel crank: F = 3·4 − 2·6 = 0 counted, 1 redundant
    par = count_mobility([Joint("R", (4, 1)), Joint("R", (1, 2)), Joint("R", (2, 3)),
                          Joint("R", (3, 4)), Joint("R", (4, 5)), Joint("R", (5, 2))],
                         frame=4, redundant=1)
    assert par.F == 1


def test_mobility_rejects_bad_joints():
    with pytest.raises(MobilityError):
        count_mobility([Joint("H", (1, 2, 3))], frame=1)
    with pytest.raises(MobilityError):
        count_mobility([Joint("R", (1, 1))], frame=1)


KIN_SPECS = sorted((__import__("tests.conftest", fromlist=["CONFIGS"]).CONFIGS / "ch1")
                   .glob("*.toml"))


@pytest.mark.parametrize("kin", KIN_SPECS, ids=[p.name for p in KIN_SPECS])
def test_mobility_of_every_kin_config_equals_its_number_of_drivers(kin, tmp_path):
    """F from the pairs of each chapter-1 linkage = the drivers the engine needs."""
    from mechcli.spec.grashof import read_grashof_spec
    from mechcli.spec.kin import load_kin_spec

    spec = tmp_path / "mob.toml"
    spec.write_text(f'command = "grashof"\n[mobility]\nkin = "{kin.as_posix()}"\n',
                    encoding="utf-8")
    p = read_grashof_spec(spec).problem
    mob = count_mobility([Joint(j.kind, j.links, j.name) for j in p.joints], p.frame)
    assert mob.F == len(load_kin_spec(kin, ()).linkage.drivers)


def _winds(F, axis):
    """The periodic feasible set F (n×n over θ1, θ4) holds a loop turning once in ``axis``."""
    from scipy import ndimage

    n = F.shape[0]
    lab, _ = ndimage.label(np.tile(F, (3, 3)))
    mid = lab[n:2 * n, n:2 * n]
    for other in (-1, 0, 1):
        d0, d1 = (1, other) if axis == 0 else (other, 1)
        shifted = lab[n + d0 * n:2 * n + d0 * n, n + d1 * n:2 * n + d1 * n]
        if np.any((mid > 0) & (mid == shifted)):
            return True
    return False


def _margin(L):
    """Distance of the lengths from the equalities of the revolvability test."""
    out = []
    for j in (0, 3):
        others = [L[m] for m in range(5) if m not in (j, 4)]
        tot = sum(others)
        out.append(abs(tot - L[j] - L[4]))
        if 2 * max(others) > tot:
            out.append(abs(abs(L[j] - L[4]) - (2 * max(others) - tot)))
    return min(out)


def test_cranks_are_the_inputs_that_really_turn_fully():
    """Which inputs turn fully relative to the frame (the other input moving as needed).

    A feasible loop of the engine's (θ1, θ4) sweep that winds once in θ_i means
    input i can make whole turns.  That must be exactly the inputs we report as
    cranks, in class I and class II; the lengths keep 1.5 units away from the
    equalities so that a 2.5° grid resolves the feasible set.
    """
    rng = np.random.default_rng(21)
    n = 144
    th = np.linspace(0, 2 * np.pi, n, endpoint=False)
    t1, t4 = np.meshgrid(th, th, indexing="ij")
    kinds = set()
    tested = 0
    while tested < 40:
        L = rng.uniform(2, 30, 5)
        if L.max() >= L.sum() - L.max() or _margin(L) < 1.5:
            continue
        kl = classify_fivebar(L)
        mo = solve(_five_bar(list(L)), {1: DriverMotion(t1), 4: DriverMotion(t4)}, order=0,
                   on_fail="mask")
        got = [k for k, axis in ((1, 0), (4, 1)) if _winds(mo.feasible, axis)]
        assert got == [k for k in kl.cranks() if k in (1, 4)], (L, kl.types)
        tested += 1
        kinds.add((int(kl.klass[0]), kl.types[0], len(got)))
    assert {(1, "single_crank", 1), (2, "single_crank", 1), (2, "no_crank", 0)} <= kinds, kinds


def test_class_I_types_follow_the_papers_short_link_rule():
    """§2.1: the place of the two short links (frame, inputs, couplers) decides the type."""
    rng = np.random.default_rng(8)
    L = rng.uniform(1, 10, (50_000, 5))
    L = L[L.max(axis=1) < L.sum(axis=1) - L.max(axis=1)]
    kl = classify_fivebar(L, frame=5)
    one = kl.klass == 1
    short = np.zeros((len(L), 5), dtype=bool)
    short[np.arange(len(L)), kl.short1 - 1] = True
    short[np.arange(len(L)), kl.short2 - 1] = True
    ground = short[:, 4].astype(int) + short[:, 0] + short[:, 3]
    types = np.array(kl.types)
    assert np.all(types[one & short[:, 4] & (short[:, 0] | short[:, 3])] == "triple_crank")
    assert np.all(types[one & short[:, 0] & short[:, 3]] == "double_crank")
    assert np.all(types[one & (ground == 1)] == "single_crank")
    assert np.all(types[one & (ground == 0)] == "no_crank")
    assert set(types[~one]) <= {"single_crank", "no_crank"}    # §2.2
