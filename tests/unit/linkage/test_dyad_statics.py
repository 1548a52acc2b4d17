"""The closed-form statics of the drivers and dyads (mechcli.core.linkage.dyad_statics)
against the general elimination (elimination.gauss / LAPACK) of the same block system.

References: the general elimination of the same linear system (an independent
solver: Gaussian elimination with partial pivoting, kinetostatics.CLOSED_FORM =
False), the virtual-power balance (a second route to the balancing torque), and,
for the exactly singular positions, the block written by hand below (three
collinear pins: the dyad's 2 x 2 determinant vanishes exactly).
"""

import math

import numpy as np
import pytest

from mechcli.core.linkage import (PRP, RPR, RRP, RRR, Crank, Ground, Linkage, PointOnLink,
                                  SliderDriver, solve)
from mechcli.core.linkage import dyad_statics, kinetostatics
from mechcli.core.linkage.elimination import gauss
from mechcli.core.linkage.kinematics import Sweep
from mechcli.core.linkage.kinetostatics import Body, Load, solve_forces, topology

EPS = np.finfo(float).eps


def _linkages(rng):
    """One linkage per dyad type (and a driver of each kind), random dimensions [m]
    chosen so that every position of a turn assembles; and two six-bars."""
    u = rng.uniform
    l1 = u(0.05, 0.15)
    four_bar = Linkage(4, (Ground("A", 0, 0), Ground("D", u(0.45, 0.55), u(-0.05, 0.05)),
                           Crank(1, "A", "B", l1),
                           RRR("C", "B", 2, u(0.45, 0.6), "D", 3, u(0.35, 0.5), 1)))
    slider_crank = Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", l1),
                               RRP("C", "B", 2, u(0.3, 0.5), 3, 4, "A", u(-0.3, 0.3),
                                   u(-0.05, 0.05), 1, "3")))
    guide_bar = Linkage(4, (Ground("C", 0, 0), Ground("A", 0, u(0.25, 0.35)),
                            Crank(1, "A", "B", l1), RPR("B", 2, "C", 3, u(-0.02, 0.02), 1, "23"),
                            PointOnLink("D", 3, "C", u(0.4, 0.6), 0.0)))
    prp = Linkage(4, (Ground("A", 0, 0), Ground("G", u(0.2, 0.3), u(-0.06, -0.04)),
                      Crank(1, "A", "B", l1),
                      PRP("C", 2, 1, "B", 3, 4, "G", u(0.4, 0.8), u(0, 0.03), u(1.7, 2.1),
                          u(-0.03, 0))))
    prp_moving = Linkage(6, (Ground("A", 0, 0), Ground("E", 0.3, 0.05),
                             Crank(1, "A", "B", 0.1), Crank(5, "E", "D", 0.08),
                             PRP("C", 2, 1, "B", 3, 5, "D", u(0.3, 0.5), 0.01, u(-1.2, -1.0),
                                 -0.015)))
    shaper = Linkage(6, (Ground("C", 0.0, 0.0), Ground("A", 0.0, u(0.25, 0.3)),
                         Ground("G", 0.0, u(0.55, 0.6)), Crank(1, "A", "B", u(0.1, 0.13)),
                         RPR("B", 2, "C", 3, 0.0, 1, "23"), PointOnLink("D", 3, "C", 0.6, 0.0),
                         RRP("E", "D", 4, u(0.14, 0.16), 5, 6, "G", 0.0, 0.0, -1, "E")))
    # Watt-type six-bar: a four-bar, then an RRR dyad on the coupler's third point
    watt = Linkage(6, (Ground("A", 0, 0), Ground("D", 0.5, 0.0), Ground("F", 0.3, -0.4),
                       Crank(1, "A", "B", l1), RRR("C", "B", 2, 0.55, "D", 3, 0.4, 1),
                       PointOnLink("E", 2, "B", 0.3, u(-0.1, -0.05)),
                       RRR("H", "E", 4, 0.5, "F", 5, 0.45, 1)))
    slider_driven = Linkage(4, (Ground("O", 0.0, 0.0), Ground("A", 0.0, 0.6),
                                SliderDriver(1, "O", "B", u(-0.2, 0.2), "1"),
                                RRR("C", "B", 2, 0.5, "A", 3, 0.3, 1)))
    return {"RRR": (four_bar, None), "RRP": (slider_crank, None), "RPR": (guide_bar, None),
            "PRP": (prp, None), "PRP_moving_guides": (prp_moving, {5: (-1.3, 0.4)}),
            "shaper_RPR_RRP": (shaper, None), "watt_RRR_RRR": (watt, None),
            "slider_driver_RRR": (slider_driven, None)}


def _model(linkage, rng):
    topo = topology(linkage)
    bodies = {ln: Body(ln, rng.uniform(0.5, 5.0), rng.uniform(0.0, 0.05), topo.frames[ln][0],
                       rng.uniform(-0.1, 0.1), rng.uniform(-0.05, 0.05))
              for ln in topo.links}
    last = topo.links[-1]
    loads = [Load("F", last, rng.uniform(-500, 500), rng.uniform(-500, 500), 0.0,
                  topo.frames[last][0], rng.uniform(-0.05, 0.05), 0.0),
             Load("T", topo.links[1], torque=rng.uniform(-20, 20))]
    return topo, bodies, loads


def _solve_both(monkeypatch, linkage, followers, q, rng, w=7.0, alpha=1.5):
    topo, bodies, loads = _model(linkage, rng)
    driver = linkage.drivers[0].link
    if not linkage.driver(driver).rotary:
        q = 0.1 * np.sin(q)
    sweep = Sweep(driver, q, w, alpha, followers or {})
    motion = solve(linkage, sweep.inputs(q), order=2)
    ok = motion.regular.reshape(-1)
    assert ok.mean() > 0.5, "the random linkage should assemble over most of the turn"
    q = q[ok]
    sweep = Sweep(driver, q, w, alpha, followers or {})
    motion = solve(linkage, sweep.inputs(q), order=2)
    unit = solve(linkage, Sweep(driver, q, 1.0, 0.0, followers or {}).inputs(q), order=1)
    out = {}
    for closed in (True, False):
        monkeypatch.setattr(kinetostatics, "CLOSED_FORM", closed)
        for cond in (False, True):
            out[closed, cond] = solve_forces(topo, motion, bodies, loads, (0.0, -9.81), unit,
                                             condition=cond)
    monkeypatch.setattr(kinetostatics, "CLOSED_FORM", True)
    return topo, out


def _peak(fr):
    return max([np.max(np.abs(c)) for pf in fr.pairs for c in (pf.fx, pf.fy)]
               + [np.max(np.abs(v)) for v in fr.balancing.values()])


def _max_diff(a, b):
    d = max(np.max(np.abs(getattr(pa, f) - getattr(pb, f)))
            for pa, pb in zip(a.pairs, b.pairs) for f in ("fx", "fy", "couple"))
    d = max([d] + [np.max(np.abs(a.balancing[k] - b.balancing[k])) for k in a.balancing])
    for x, y in ((a.frame_force[0], b.frame_force[0]), (a.frame_force[1], b.frame_force[1])):
        d = max(d, np.max(np.abs(x - y)))
    return d


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("name", ["RRR", "RRP", "RPR", "PRP", "PRP_moving_guides",
                                  "shaper_RPR_RRP", "watt_RRR_RRR", "slider_driver_RRR"])
def test_closed_form_matches_general_elimination(monkeypatch, name, seed):
    """Every block of these linkages has a closed-form layout, and its reactions,
    balancing and condition numbers equal the general elimination's to round-off
    (1e-12 of the largest force; 300 positions, so both the condition-number path
    and the plain one go through the closed form)."""
    rng = np.random.default_rng(seed)
    linkage, followers = _linkages(rng)[name]
    q = np.linspace(0.0, 2 * math.pi, 301)
    topo, out = _solve_both(monkeypatch, linkage, followers, q, rng)
    # the closed form is used for every block (a layout the test can see fail)
    assert all(blk[-1] is not None for blk in kinetostatics._plan(topo).blocks)
    for cond in (False, True):
        a, b = out[True, cond], out[False, cond]
        peak = _peak(b)
        assert _max_diff(a, b) <= 1e-12 * peak, (name, cond)
        # a second route to the balancing: the virtual power
        assert np.max(np.abs(a.power_residual)) <= 1e-9 * peak * max(
            1.0, np.max(np.abs(a.input_power)) / peak)
    ca, cb = out[True, True].cond, out[False, True].cond
    assert np.all(np.isfinite(ca)) and np.allclose(ca, cb, rtol=1e-9, atol=0)


def test_near_dead_point_agrees_within_its_condition(monkeypatch):
    """A crank-rocker whose transmission angle nearly vanishes (D moved 1e-7 m
    inside the dead-point distance 5 m): cond reaches ~1e4 and more; the two
    solvers then agree within ~cond x eps of the peak force at each position."""
    lk = Linkage(4, (Ground("A", 0, 0), Ground("D", 5.0 - 1e-7, 0), Crank(1, "A", "B", 1.0),
                     RRR("C", "B", 2, 3.0, "D", 3, 3.0, 1)))
    q = np.radians(np.linspace(0.0, 360.0, 7201))
    topo = topology(lk)
    bodies = {2: Body(2, 1.0, 0.1), 3: Body(3, 2.0, 0.2)}
    loads = [Load("M", 3, torque=-10.0)]
    sweep = Sweep(1, q, 10.0, 0.0, {}, True)
    motion = solve(lk, sweep.inputs(q), order=2)
    ok = motion.regular
    sweep = Sweep(1, q[ok], 10.0, 0.0, {}, True)
    motion = solve(lk, sweep.inputs(q[ok]), order=2)
    res = {}
    for closed in (True, False):
        monkeypatch.setattr(kinetostatics, "CLOSED_FORM", closed)
        res[closed] = solve_forces(topo, motion, bodies, loads, (0.0, -9.8), condition=True)
    a, b = res[True], res[False]
    assert np.max(b.cond) > 1e4
    peak = _peak(b)
    for pa, pb in zip(a.pairs, b.pairs):
        for f in ("fx", "fy"):
            err = np.abs(getattr(pa, f) - getattr(pb, f))
            assert np.all(np.isfinite(getattr(pa, f)))
            assert np.all(err <= 64 * EPS * b.cond * np.maximum(peak, np.abs(getattr(pb, f))))
    assert np.allclose(a.cond, b.cond, rtol=1e-6)


def _rrr_block(bx, by, cx, cy, dx, dy):
    """The scaled 6 x 6 block of an RRR dyad B-C-D (L = 1), written by hand from the
    equilibrium of its two links (centres of mass at the midpoints S2 of BC, S3 of
    DC): unknowns F_B (on link 2), F_23 (of 2 on 3, at C), F_D (on link 3); rows
    ΣFx, ΣFy, ΣM_S of link 2 then link 3."""
    s2x, s2y, s3x, s3y = (bx + cx) / 2, (by + cy) / 2, (dx + cx) / 2, (dy + cy) / 2
    z = 0.0
    A = [[1.0, z, -1.0, z, z, z],
         [z, 1.0, z, -1.0, z, z],
         [-(by - s2y), bx - s2x, (cy - s2y), -(cx - s2x), z, z],
         [z, z, 1.0, z, 1.0, z],
         [z, z, z, 1.0, z, 1.0],
         [z, z, -(cy - s3y), cx - s3x, -(dy - s3y), dx - s3x]]
    kind_of = [("R", (0,)), ("R", (0, 1)), ("R", (1,))]
    cols = [{r: isinstance(A[r][c], float) for r in range(6)
             if not (isinstance(A[r][c], float) and A[r][c] == 0.0)} for c in range(6)]
    return A, kind_of, cols


def test_exactly_singular_positions_give_zeros_like_the_elimination():
    """Three collinear pins on the x axis (B, C, D at x = 0, 1, 2 with every y = 0):
    the dyad's determinant is exactly zero; the closed form gives zeros there and
    flags the position, as the elimination does; elsewhere the two agree."""
    rng = np.random.default_rng(5)
    n = 200
    cy = rng.uniform(-0.5, 0.5, n)
    cy[[3, 50, 199]] = 0.0  # collinear: singular
    bx, by = np.zeros(n), np.zeros(n)
    cx = np.ones(n)
    dx, dy = np.full(n, 2.0), np.zeros(n)
    A, kind_of, cols = _rrr_block(bx, by, cx, cy, dx, dy)
    lay = dyad_statics.layout(kind_of, cols, 6)
    assert lay is not None and type(lay) is dyad_statics.DyadLayout
    b = [rng.uniform(-10, 10, n) for _ in range(6)]
    X, sing = dyad_statics.solve(lay, A, b, (n,))
    Xg, sing_g = gauss(A, b)
    assert int(np.count_nonzero(sing)) == int(np.count_nonzero(sing_g)) == 3  # the three set above
    assert np.array_equal(sing, sing_g) and np.flatnonzero(sing).tolist() == [3, 50, 199]
    for x, xg in zip(X, Xg):
        assert np.all(x[sing] == 0.0)
        reg = ~sing
        assert np.allclose(x[reg], xg[reg], rtol=0, atol=1e-11 * np.max(np.abs(Xg)))
    # through the solver of kinetostatics: cond = inf there, as the elimination's
    X2, c2 = kinetostatics._solve_closed(lay, A, b, n, True)
    Xg2, cg2 = kinetostatics._solve_block(A, b, n, True)
    assert np.all(np.isinf(c2[sing])) and np.all(np.isinf(cg2[sing]))
    assert np.allclose(c2[~sing], cg2[~sing], rtol=1e-9)


def test_layout_refuses_what_it_cannot_express():
    """Blocks outside the dyad structure are left to the general elimination."""
    # two inner pairs (a two-loop body): no layout
    assert dyad_statics.layout([("R", (0, 1)), ("R", (0, 1)), ("R", (1,))],
                               [{0: True}] * 6, 6) is None
    # both outer pairs on the same link
    assert dyad_statics.layout([("R", (0,)), ("R", (0, 1)), ("R", (0,))],
                               [{0: True}] * 6, 6) is None
    # a 9-row block (a triad)
    assert dyad_statics.layout([("R", (0,))] * 4, [{0: True}] * 9, 9) is None


def test_folded_arithmetic_equals_plain_numpy():
    """The folding helpers (exact zeros, +-1 and pending negations kept as Python
    floats or ``_Neg`` instead of passes over memory) give exactly what plain numpy
    gives, for every combination of a float (special or not), an array and a pending
    negation of one, and nested negations."""
    from mechcli.core.linkage.dyad_statics import _add, _div, _mul, _neg, _sub, value
    from mechcli.core.linkage.folding import Neg

    rng = np.random.default_rng(3)
    arr = rng.uniform(-2.0, 2.0, 7)   # (no exact zero: a divisor too)
    arr2 = rng.uniform(0.5, 2.0, 7)
    plain = [0.0, 1.0, -1.0, 2.5, -0.75, arr, arr2]
    cases = []
    for v in plain:
        cases.append((v, v))
        cases.append((_neg(v), -v))
        cases.append((_neg(_neg(v)), v))
    ops = {_add: np.add, _sub: np.subtract, _mul: np.multiply, _div: np.divide}
    checked = 0
    for f, ref in ops.items():
        for a, ra in cases:
            for b, rb in cases:
                if f is _div and np.ndim(rb) == 0 and rb == 0.0:
                    continue  # (no division by an exact zero)
                got = value(f(a, b))
                want = ref(ra, rb)
                assert np.array_equal(np.broadcast_to(got, np.shape(want)), want), (f, ra, rb)
                checked += 1
    assert checked > 600
    # floats stay floats (no array made), a negated array stays pending
    assert type(_mul(_neg(2.0), 3.0)) is float and type(_sub(0.0, arr)) is Neg
    assert value(_sub(0.0, arr)) is not arr and np.array_equal(value(_sub(0.0, arr)), -arr)
