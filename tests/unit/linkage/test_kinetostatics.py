"""Kinetostatics: independent reference values, link-by-link equilibrium, power
balance, global force balance, statics (omega -> 0), dead points, slider and
two-driver linkages."""

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechcli.core.linkage.force_analysis import analyse_forces
from mechcli.core.linkage.kinematics import Sweep
from mechcli.core.linkage.kinetostatics import (Body, Load, LoadProgram, solve_forces,
                                        topology)
from mechcli.core.linkage import (RPR, RRP, RRR, Crank, Ground, Linkage, PointOnLink, stack,
                                  SliderDriver, solve)
from mechcli.spec.force import load_force_spec
from tests.conftest import CONFIGS, ROOT

REF = json.loads((ROOT / "tests" / "reference" / "force_reference.json").read_text())


def _analyse(spec):
    inp = spec.input
    sweep = inp.sweep()
    return analyse_forces(spec.linkage, spec.topology, sweep, spec.bodies, spec.gravity,
                          spec.loads, partial=inp.partial)


@pytest.mark.parametrize("name", sorted(REF))
def test_matches_independent_reference(name):
    """Every reaction component and Mb at every 30° agree with an independent
    implementation (own geometry, finite-difference kinematics, dense solve)."""
    ref = REF[name]
    res = _analyse(load_force_spec(CONFIGS / "ch2" / f"{name}.toml"))
    deg = np.degrees(res.q)
    idx = [int(np.argmin(np.abs(deg - a))) for a in ref["positions_deg"]]
    assert np.allclose(deg[idx], ref["positions_deg"], atol=1e-9)
    peak = max(max(abs(x) for x in v) for k, v in ref.items()
               if isinstance(v, list) and k.startswith(("FR", "Mb")) and k != "positions_deg"
               and not isinstance(v[0], list))
    checked = 0
    for key, values in ref.items():
        if not (isinstance(values, list) and key.startswith(("FR", "Mb", "MR"))):
            continue
        sym = key[: -len("_N_m")] if key.endswith("_N_m") else key[: -len("_N")]
        ours = res.series[sym][idx]
        assert np.max(np.abs(ours - np.asarray(values))) <= 1e-8 * peak, key
        checked += 1
    assert checked >= 9


def _known_forces(topo, motion, bodies, loads, gravity):
    """Per link: resultant known force and moment about the origin (independent)."""
    out = {}
    for link in topo.links:
        out[link] = [0.0, 0.0, 0.0]
    for link in topo.links:
        b = bodies.get(link, Body(link))
        # centre of mass via PointOnLink kinematics solved again by the engine
        origin, second = topo.frames[link]
        if b.origin is None:
            if second is None:
                el, along, normal = origin, 0.0, 0.0
            else:
                el, along, normal = None, None, None
        else:
            el, along, normal = b.origin, b.along, b.normal
        if el is None:
            p, q = motion.points[origin], motion.points[second]
            x, y = 0.5 * (p.x + q.x), 0.5 * (p.y + q.y)
            ax, ay = 0.5 * (p.ax + q.ax), 0.5 * (p.ay + q.ay)
        else:
            o, k = motion.points[el], motion.links[link]
            r = (along + 1j * normal) * np.exp(1j * k.theta)
            pos = o.p + r
            acc = o.a + (1j * k.alpha - k.omega ** 2) * r
            x, y, ax, ay = pos.real, pos.imag, acc.real, acc.imag
        fx = b.mass * (gravity[0] - ax)
        fy = b.mass * (gravity[1] - ay)
        m = -b.inertia * motion.links[link].alpha + x * fy - y * fx
        out[link] = [fx, fy, m]
    for ld in loads:
        f = out[ld.link]
        f[2] = f[2] + ld.torque
        if ld.fx or ld.fy:
            p = motion.points[ld.origin]
            k = motion.links[ld.link]
            pos = p.p + (ld.along + 1j * ld.normal) * np.exp(1j * k.theta)
            f[0] = f[0] + ld.fx
            f[1] = f[1] + ld.fy
            f[2] = f[2] + pos.real * ld.fy - pos.imag * ld.fx
    return out


def _equilibrium_residual(topo, motion, fr, bodies, loads, gravity):
    """Largest residual of ΣF, ΣM (about the origin) over every moving link."""
    tot = _known_forces(topo, motion, bodies, loads, gravity)
    for pf in fr.pairs:
        pr = pf.pair
        p = motion.points[pr.point]
        for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
            if link not in tot:
                continue
            t = tot[link]
            t[0] = t[0] + sign * pf.fx
            t[1] = t[1] + sign * pf.fy
            t[2] = t[2] + sign * (p.x * pf.fy - p.y * pf.fx + pf.couple)
    for d in topo.linkage.drivers:
        val = fr.balancing[d.link]
        t = tot[d.link]
        if isinstance(d, Crank):
            t[2] = t[2] + val
        else:
            p = motion.points[d.point]
            ux, uy = math.cos(d.angle), math.sin(d.angle)
            t[0] = t[0] + val * ux
            t[1] = t[1] + val * uy
            t[2] = t[2] + p.x * val * uy - p.y * val * ux
    return max(float(np.max(np.abs(c))) for t in tot.values() for c in t)


def _run(linkage, q, w, bodies, loads=(), gravity=(0.0, -9.8), alpha=0.0, followers=None):
    topo = topology(linkage)
    sweep = Sweep(linkage.drivers[0].link, q, w, alpha, followers or {})
    motion = solve(linkage, sweep.inputs(q), order=2)
    assert motion.regular.all()
    unit = solve(linkage, Sweep(sweep.driver, q, 1.0, 0.0, followers or {}).inputs(q), order=1)
    fr = solve_forces(topo, motion, bodies, loads, gravity, unit)
    return topo, motion, fr


SHAPER = Linkage(6, (Ground("C", 0.0, 0.0), Ground("A", 0.0, 0.275), Ground("G", 0.0, 0.575),
                     Crank(1, "A", "B", 0.125), RPR("B", 2, "C", 3, 0.0, 1, "23"),
                     PointOnLink("D", 3, "C", 0.6, 0.0),
                     RRP("E", "D", 4, 0.15, 5, 6, "G", 0.0, 0.0, -1, "E")))


def test_every_link_is_in_equilibrium_shaper():
    q = np.radians(np.arange(0.0, 360.0, 7.0))
    bodies = {3: Body(3, 20, 0.12), 4: Body(4, 3, 0.00025), 5: Body(5, 62, 0.0, "E", -0.15, 0.0)}
    loads = [Load("cut", 5, 5880.0, 300.0, 7.0, "E", 0.05, 0.02)]
    topo, motion, fr = _run(SHAPER, q, 1.3, bodies, loads, alpha=0.4)
    peak = max(np.max(np.abs(pf.magnitude)) for pf in fr.pairs)
    assert _equilibrium_residual(topo, motion, fr, bodies, loads, (0.0, -9.8)) < 1e-10 * peak
    assert np.max(np.abs(fr.power_residual)) < 1e-10 * np.max(np.abs(fr.balancing[1]))
    # the RPR block is massless: no couple in its prismatic pair, F_R12 = F_R23
    p12, p23 = fr.pairs[1], fr.pairs[2]
    assert np.allclose(p12.fx, p23.fx, atol=1e-9 * peak) and np.allclose(p23.couple, 0,
                                                                          atol=1e-9 * peak)


def test_statics_when_omega_is_zero():
    """omega1 = 0: no inertia, Mb balances gravity and loads (virtual work)."""
    link = Linkage(4, (Ground("A", 0.0, 0.0), Crank(1, "A", "B", 0.5)))
    q = np.radians(np.arange(0.0, 360.0, 15.0))
    topo, motion, fr = _run(link, q, 0.0, {1: Body(1, 2.0, 0.1, "A", 0.5, 0.0)})
    # a mass at the crank pin: Mb = m g l cos(theta)
    assert np.allclose(fr.balancing[1], 2.0 * 9.8 * 0.5 * np.cos(q), rtol=0, atol=1e-12)
    # a four-bar at rest under a torque on the rocker: Mb = -M3 * omega3 / omega1
    fb = Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", 1.2, 0.0), Crank(1, "A", "B", 0.4),
                     RRR("C", "B", 2, 1.0, "D", 3, 0.7, 1)))
    topo, motion, fr = _run(fb, q, 0.0, {}, [Load("M", 3, torque=-100.0)], gravity=(0, 0))
    ratio = solve(fb, Sweep(1, q, 1.0).inputs(q), order=1).links[3].omega
    assert np.allclose(fr.balancing[1], 100.0 * ratio, rtol=1e-12, atol=1e-12)
    assert np.all(np.isfinite(fr.power_residual)) and np.max(np.abs(fr.power_residual)) < 1e-10


def test_slider_driver_balancing_force():
    """A block driven along x with a rod to a crank: Fb balances by virtual power."""
    lk = Linkage(4, (Ground("O", 0.0, 0.0), Ground("A", 0.0, 0.6),
                     SliderDriver(1, "O", "B", 0.0, "1"),
                     RRR("C", "B", 2, 0.5, "A", 3, 0.3, 1)))
    q = np.linspace(-0.15, 0.15, 41)
    bodies = {1: Body(1, 5.0), 2: Body(2, 2.0, 0.05), 3: Body(3, 1.0, 0.02)}
    loads = [Load("M3", 3, torque=12.0)]
    topo, motion, fr = _run(lk, q, 0.8, bodies, loads, alpha=0.3)
    assert _equilibrium_residual(topo, motion, fr, bodies, loads, (0.0, -9.8)) < 1e-9
    assert np.max(np.abs(fr.power_residual)) < 1e-10 * np.max(np.abs(fr.balancing[1]))


def test_two_drivers_share_the_power():
    """The 2-DOF five-bar with geared cranks: Σ Mb_i ω_i balances the loads."""
    lk = Linkage(5, (Ground("A", 0.0, 0.0), Ground("E", 0.21, 0.0), Crank(1, "A", "B", 0.05),
                     Crank(4, "E", "D", 0.13), RRR("C", "B", 2, 0.2, "D", 3, 0.22, 1)))
    q = np.radians(np.arange(0.0, 360.0, 5.0))
    bodies = {k: Body(k, 1.0 + k, 0.01 * k) for k in (1, 2, 3, 4)}
    followers = {4: (-1.0, math.radians(30))}
    topo, motion, fr = _run(lk, q, 10.0, bodies, [Load("F", 3, 50.0, -20.0, 0.0, "C")],
                            followers=followers)
    assert set(fr.balancing) == {1, 4}
    assert np.max(np.abs(fr.power_residual)) < 1e-10 * max(
        np.max(np.abs(v)) for v in fr.balancing.values())


@settings(max_examples=40, deadline=None)
@given(st.floats(0.5, 1.5), st.floats(2.0, 3.0), st.floats(2.0, 3.0), st.floats(-0.3, 0.3),
       st.floats(0.1, 5), st.floats(0.0, 0.5), st.floats(-0.5, 0.5), st.floats(-40, 40),
       st.floats(0.1, 20), st.sampled_from(["four_bar", "slider_crank", "guide_bar"]),
       st.floats(1e-3, 1e3))
def test_power_and_force_balance_random(l1, l2, l3, off, m, J, dn, w, fmag, kind, scale):
    """Random linkages, inertia, loads and scales: power balance to 1e-9 of the
    peak |Mb| at every position and Σ forces = Σ m a_S."""
    s = scale
    if kind == "four_bar":
        lk = Linkage(4, (Ground("A", 0, 0), Ground("D", 0.5 * (l2 + l3) * s, 0),
                         Crank(1, "A", "B", l1 * 0.3 * s), RRR("C", "B", 2, l2 * s, "D", 3,
                                                               l3 * s, 1)))
    elif kind == "slider_crank":
        lk = Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", l1 * s),
                         RRP("C", "B", 2, l2 * s, 3, 4, "A", 0.0, off * s, 1, "3")))
    else:
        lk = Linkage(4, (Ground("C", 0, 0), Ground("A", 0, l2 * s), Crank(1, "A", "B", l1 * s),
                         RPR("B", 2, "C", 3, off * 0.5 * s, 1, "23"),
                         PointOnLink("D", 3, "C", l3 * s, 0.0)))
    topo = topology(lk)
    bodies = {ln: Body(ln, m * (1 + ln), J * s * s * ln, topo.frames[ln][0], 0.3 * s,
                       dn * s) for ln in topo.links}
    origin = topo.frames[3][0]
    loads = [Load("F", 3, fmag * 7, -fmag, 0.0, origin, 0.2 * s, 0.1 * s),
             Load("T", 2, torque=fmag * s)]
    q = np.radians(np.arange(0.0, 360.0, 3.0))
    topo, motion, fr = _run(lk, q, w, bodies, loads, gravity=(0.0, -9.81))
    peak = np.max(np.abs(fr.balancing[1]))
    assert np.all(np.isfinite(fr.balancing[1]))
    assert np.max(np.abs(fr.power_residual)) <= 1e-9 * peak
    assert np.max(fr.force_residual) <= 1e-11 * max(1.0, np.max(np.hypot(*fr.frame_force)))
    assert _equilibrium_residual(topo, motion, fr, bodies, loads, (0.0, -9.81)) <= 1e-9 * max(
        peak / s, max(np.max(pf.magnitude) for pf in fr.pairs))
    # without the condition numbers the closed-form blocks take each link's moments about
    # its outer pair's point (not its centre of mass): the same solution to round-off
    fast = solve_forces(topo, motion, bodies, loads, (0.0, -9.81), condition=False)
    big = max(np.max(pf.magnitude) for pf in fr.pairs)
    assert np.max(np.abs(fast.balancing[1] - fr.balancing[1])) <= 1e-10 * peak
    for a, b in zip(fast.pairs, fr.pairs):
        assert max(np.max(np.abs(a.fx - b.fx)), np.max(np.abs(a.fy - b.fy))) <= 1e-10 * big
        assert np.max(np.abs(a.couple - b.couple)) <= 1e-10 * max(peak, big * s)


def test_near_dead_point_is_flagged_not_nan():
    """A crank-rocker whose transmission angle nearly vanishes: large condition
    number reported and flagged, finite reactions, power balance still holds."""
    eps = 1e-9
    lk = Linkage(4, (Ground("A", 0, 0), Ground("D", 5.0 - eps, 0), Crank(1, "A", "B", 1.0),
                     RRR("C", "B", 2, 3.0, "D", 3, 3.0, 1)))
    q = np.radians(np.linspace(0.0, 360.0, 3601))
    topo = topology(lk)
    sweep = Sweep(1, q, 10.0, 0.0, {}, True)
    res = analyse_forces(lk, topo, sweep, {2: Body(2, 1.0, 0.1)}, (0.0, -9.8),
                         (LoadProgram(Load("M", 3, torque=-10.0)),), partial=True)
    fr = res.forces
    assert all(np.all(np.isfinite(v)) for v in res.series.values())
    assert np.max(fr.cond) > 1e3
    assert np.max(fr.cond) / np.min(fr.cond) > 100


def test_conditional_load_intervals_refined():
    """例 2-3: the resisting torque acts exactly while omega3 > 0 (edges where the
    guide bar reverses: the tangents from C to the crank circle)."""
    res = _analyse(load_force_spec(CONFIGS / "ch2" / "ex2-3.toml"))
    (a0, a1), (b0, b1) = res.active["Mr"]
    edge = math.degrees(math.asin(0.4 / 1.0))  # sin of the tangent angle = l1 / l4
    assert a0 == 0.0 and b1 == pytest.approx(2 * math.pi, abs=1e-12)
    assert math.degrees(a1) == pytest.approx(180 + edge, abs=1e-9)
    assert math.degrees(b0) == pytest.approx(360 - edge, abs=1e-9)


@pytest.mark.parametrize("e, branch, pivot", [(0.0, 1, (0.0, 0.0)), (0.03, 1, (0.0, 0.0)),
                                              (-0.04, -1, (0.2, -0.1)), (0.0, -1, (0.2, -0.1))])
def test_rpr_direction_is_the_cosine_and_sine_of_its_angle(e, branch, pivot):
    """Element.direction of an RPR guide (formed from its points and slide, for the
    kinetostatics instead of np.cos/np.sin) equals the cosine and sine of the engine's
    guide angle to round-off, for both links it makes (guide and block)."""
    cx, cy = pivot
    lk = Linkage(4, (Ground("C", cx, cy), Ground("A", cx + 0.01, cy + 0.3),
                     Crank(1, "A", "B", 0.1), RPR("B", 2, "C", 3, e, branch, "23")))
    q = np.radians(np.arange(0.0, 360.0, 1.0))
    m = solve(lk, Sweep(1, q, 2.0).inputs(q), order=2)
    assert m.regular.all()
    rpr = lk.elements[-1]
    for link in (2, 3):
        c, s = rpr.direction(m, link)
        th = m.links[link].theta
        assert np.max(np.abs(c - np.cos(th))) < 4e-16 and np.max(np.abs(s - np.sin(th))) < 4e-16


def test_rpr_direction_of_a_batch_of_offsets():
    """A batch of designs (offsets per design): each row as its own linkage's angle."""
    es = np.array([[0.0], [0.02], [-0.03]])
    lk = Linkage(4, (Ground("C", 0.0, 0.0), Ground("A", 0.0, 0.3), Crank(1, "A", "B", 0.1),
                     RPR("B", 2, "C", 3, es, 1, "23")))
    q = np.radians(np.arange(0.0, 360.0, 5.0))
    m = solve(lk, Sweep(1, q, 1.0).inputs(q), order=1)
    c, s = lk.elements[-1].direction(m, 3)
    assert c.shape == s.shape == m.links[3].theta.shape == (3, q.size)
    assert np.max(np.abs(c - np.cos(m.links[3].theta))) < 4e-16
    assert np.max(np.abs(s - np.sin(m.links[3].theta))) < 4e-16


def test_forces_from_the_guide_direction_equal_those_from_its_angle():
    """The shaper's reactions with the RPR guide's direction from its points equal
    those with cos/sin of its angle (the plan's direction map emptied) to round-off."""
    from mechcli.core.linkage.kinetostatics import _plan

    q = np.radians(np.arange(0.0, 360.0, 2.0))
    bodies = {3: Body(3, 20, 0.12), 4: Body(4, 3, 0.00025), 5: Body(5, 62, 0.0, "E", -0.15, 0.0)}
    loads = [Load("cut", 5, 5880.0, 300.0, 7.0, "E", 0.05, 0.02)]
    topo, motion, fr = _run(SHAPER, q, 1.3, bodies, loads, alpha=0.4)
    plan = _plan(topo)
    assert set(plan.direction_of) == {2, 3}
    saved = plan.direction_of
    try:
        plan.direction_of = {}
        ref = solve_forces(topo, motion, bodies, loads, (0.0, -9.8))
    finally:
        plan.direction_of = saved
    peak = max(np.max(np.abs(pf.magnitude)) for pf in ref.pairs)
    for a, b in zip(fr.pairs, ref.pairs):
        assert np.max(np.abs(a.fx - b.fx)) < 1e-12 * peak
        assert np.max(np.abs(a.fy - b.fy)) < 1e-12 * peak
        assert np.max(np.abs(a.couple - b.couple)) < 1e-12 * peak
    assert np.max(np.abs(fr.balancing[1] - ref.balancing[1])) < 1e-12 * np.max(
        np.abs(ref.balancing[1]))


def test_results_are_arrays_of_their_own():
    """No returned array is the caller's load array, a read-only broadcast or another
    result (the folded signs hand right-hand sides back as they are): a massless
    coupler's F_R12 and F_R23 are equal but separate, a slider's couple is not the
    torque the caller passed.  (Found by an independent review, 2026-11-25.)"""
    lk = Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", 0.1),
                     RRP("C", "B", 2, 0.4, 3, 4, "A", 0.0, 0.0, 1, "3")))
    q = np.linspace(0.0, 6.0, 10)
    m = solve(lk, Sweep(1, q, 5.0).inputs(q), order=2)
    for torque in (np.linspace(1.0, 2.0, 10), 5.0):
        for condition in (False, True):
            fr = solve_forces(topology(lk), m, {}, [Load("T", 3, torque=torque)],
                              (0.0, -9.81), condition=condition)
            arrays = ([fr.balancing[1], *fr.frame_force, fr.frame_moment, fr.input_power]
                      + [a for pf in fr.pairs for a in (pf.fx, pf.fy, pf.couple)])
            assert all(a.flags.writeable for a in arrays)
            for i, a in enumerate(arrays):
                assert not np.shares_memory(a, torque)
                assert not any(np.shares_memory(a, b) for b in arrays[i + 1:])
            # the massless coupler passes the force on: F_R12 = F_R23 (equal, not shared)
            p12, p23 = (pf for pf in fr.pairs if pf.pair.label in ("12", "23"))
            assert np.array_equal(p12.fx, p23.fx) and np.array_equal(p12.fy, p23.fy)


def test_frame_force_of_one_pair_is_its_own_array():
    """A crank alone: the force on the frame is the one pair's force, equal, not shared."""
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Crank(1, "A", "B", 0.5)))
    q = np.radians(np.arange(0.0, 360.0, 30.0))
    topo, motion, fr = _run(lk, q, 3.0, {1: Body(1, 2.0, 0.1, "A", 0.5, 0.0)})
    (pa,) = fr.pairs
    assert np.array_equal(fr.frame_force[0], pa.fx) and np.array_equal(fr.frame_force[1], pa.fy)
    assert not np.shares_memory(fr.frame_force[0], pa.fx)
    assert not np.shares_memory(fr.frame_force[1], pa.fy)


def test_masses_of_a_batch_given_as_a_list():
    """Masses of a batch of designs as a nested list on a link with the default
    (midpoint) centre of mass: each design as solved alone."""
    lks = [Linkage(4, (Ground("A", 0, 0), Ground("D", 0.5, 0), Crank(1, "A", "B", 0.1),
                       RRR("C", "B", 2, 0.5 + 0.01 * k, "D", 3, 0.4, 1))) for k in range(2)]
    q = np.linspace(0.0, 6.0, 10)
    m = solve(stack(lks), Sweep(1, q, 5.0).inputs(q), order=2)
    fr = solve_forces(topology(stack(lks)), m, {2: Body(2, [[1.0], [2.0]], 0.01)}, [],
                      (0.0, -9.81))
    assert fr.balancing[1].shape == (2, 10)
    for k, mass in enumerate((1.0, 2.0)):
        mk = solve(lks[k], Sweep(1, q, 5.0).inputs(q), order=2)
        one = solve_forces(topology(lks[k]), mk, {2: Body(2, mass, 0.01)}, [], (0.0, -9.81))
        assert np.allclose(fr.balancing[1][k], one.balancing[1], rtol=1e-12, atol=1e-12)
