"""Random assemblable drawings (issue 30 §4): a drawing of a four-bar, of the class-III
six-bar or of the class-IV six-bar (a Newton-solved group) with its joints moved at random is solved by mechcli.core.linkage.drawing; over
the range its continuation reaches, every pair of joints on one link keeps its drawn
distance (loop closure), the velocities are the derivatives of the positions (central
differences), and the drawn pose is reproduced at the drawn input angle."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.linkage.drawing import Drawing, DrawingError, from_drawing

SET = settings(max_examples=25, deadline=None)
#: the class-III six-bar of configs/ch1/class3-sixbar.toml [m]
TRIAD = {"A": (0.0, 0.0), "B": (-0.01935, -0.00144), "C": (0.08165, 0.05348),
         "E": (0.11778, 0.05071), "F": (0.1029, 0.09353), "G": (0.18883, 0.02269),
         "H": (0.08008, 0.15021)}
TRIAD_LINKS = {1: ("A", "B"), 2: ("B", "C"), 3: ("C", "E", "F"), 4: ("G", "E"), 5: ("H", "F")}
move = st.floats(-0.008, 0.008)
#: the class-IV six-bar of configs/ch1/class4-group.toml [m]
CLASS4 = {"A": (0.0, 0.0), "B": (0.01, 0.0), "C": (0.088, 0.073), "D": (0.117, 0.057),
          "E": (0.106, 0.049), "F": (0.076, 0.005), "G": (0.15, 0.0)}
CLASS4_LINKS = {1: ("A", "B"), 2: ("B", "C", "F"), 3: ("C", "D"), 4: ("G", "D", "E"),
                5: ("E", "F")}


def _check(fd, xy, links):
    lk = fd.linkage
    q0 = fd.inputs[1]
    tri = [e for e in lk.elements if e.kind in ("triad", "group")]
    if tri and not tri[0].period:                 # the range the continuation reached
        lo, hi = min(tri[0].table[0]), max(tri[0].table[0])
    else:
        lo, hi = q0 - math.pi, q0 + math.pi
    q = np.linspace(lo, hi, 97)[1:-1]
    m = solve(lk, {1: DriverMotion(q, 1.0)}, order=1)
    ok = m.regular
    assume(ok.sum() > 20)
    size = max(abs(v) for p in xy.values() for v in p)
    for n, names in links.items():
        for a_i, a in enumerate(names):
            for b in names[a_i + 1:]:
                d = np.hypot(m.points[a].x - m.points[b].x, m.points[a].y - m.points[b].y)
                want = math.dist(xy[a], xy[b])
                assert np.max(np.abs(d - want)[ok]) <= 1e-12 * size, (n, a, b)
    h = 1e-6
    mp = solve(lk, {1: DriverMotion(q + h, 1.0)}, order=0)
    mm = solve(lk, {1: DriverMotion(q - h, 1.0)}, order=0)
    # away from toggles (sin γ > 0.05 for every group), where x''' stays moderate
    sin_min = np.min([np.broadcast_to(c.sin_gamma, q.shape) for c in m.conditions], axis=0)
    good = ok & mp.regular & mm.regular & (sin_min > 0.05)
    assume(good.sum() > 10)
    for p in xy:
        fdv = (mp.points[p].x - mm.points[p].x) / (2 * h)
        v = m.points[p].vx
        # central difference: truncation h^2 |x'''| / 6, rounding eps |x| / h (~1e-10 m)
        assert np.max(np.abs(fdv - v)[good]) <= 1e-6 * np.max(np.abs(v[good])) + 1e-9, p
    # the drawing itself, at its input angle
    m0 = solve(lk, {1: DriverMotion(np.array([q0]))}, order=0)
    for p, (x, y) in xy.items():
        assert math.hypot(m0.points[p].x[0] - x, m0.points[p].y[0] - y) <= 1e-9 * size


def _moved_triad(dcx, dcy, dex, dey, dfx, dfy):
    """The class-III drawing with its triad's joints C, E, F moved (a drawing that does
    not assemble is not an example)."""
    xy = dict(TRIAD)
    for k, (dx, dy) in zip("CEF", ((dcx, dcy), (dex, dey), (dfx, dfy))):
        xy[k] = (xy[k][0] + dx, xy[k][1] + dy)
    try:
        return xy, from_drawing(Drawing(6, xy, TRIAD_LINKS, (), ((1, "A"),)))
    except DrawingError:
        assume(False)


@SET
@given(move, move, move, move, move, move)
def test_a_moved_class3_drawing_closes_and_differentiates(dcx, dcy, dex, dey, dfx, dfy):
    xy, fd = _moved_triad(dcx, dcy, dex, dey, dfx, dfy)
    assert fd.structure.mechanism_class == 3
    _check(fd, xy, TRIAD_LINKS)


@SET
@given(st.floats(0.02, 0.2), st.floats(0.0, 2 * math.pi), st.floats(0.05, 0.4),
       st.floats(-0.3, 0.3), st.floats(0.1, 0.5))
def test_a_random_four_bar_drawing_closes_and_differentiates(r, th, cx, cy, dx):
    xy = {"A": (0.0, 0.0), "B": (r * math.cos(th), r * math.sin(th)), "C": (cx, cy),
          "D": (dx, 0.0)}
    links = {1: ("A", "B"), 2: ("B", "C"), 3: ("D", "C")}
    try:
        fd = from_drawing(Drawing(4, xy, links, (), ((1, "A"),)))
    except DrawingError:
        assume(False)
    _check(fd, xy, links)


@SET
@given(move, move, move, move, move, move, st.floats(0.1, 5.0), st.floats(0.1, 5.0),
       st.floats(-2.0, 2.0))
def test_a_moved_class3_drawing_passes_the_power_balance(dcx, dcy, dex, dey, dfx, dfy,
                                                         m3, m4, alpha1):
    # random masses and an accelerating crank on the moved triad: the kinetostatics'
    # balancing torque equals the virtual power of the loads (Mb ω* + Σ(F·v* + M ω*) = 0,
    # the unit-speed velocities from the engine's own linear solves), and the frame takes
    # what the moving links do not balance (the force balance)
    from mechcli.core.linkage.kinetostatics import Body, solve_forces, topology

    xy, fd = _moved_triad(dcx, dcy, dex, dey, dfx, dfy)
    lk = fd.linkage
    q = fd.inputs[1] + np.linspace(-0.3, 0.3, 25)
    m = solve(lk, {1: DriverMotion(q, 7.0, alpha1)}, order=2)
    assume(bool(np.all(m.regular)))
    unit = solve(lk, {1: DriverMotion(q, 1.0, 0.0)}, order=1)
    bodies = {1: Body(1, 0.4, 2e-4), 2: Body(2, 1.1, 4e-3), 3: Body(3, m3, 6e-3),
              4: Body(4, m4, 3e-3), 5: Body(5, 0.8, 2e-3)}
    fr = solve_forces(topology(lk), m, bodies, gravity=(0.0, -9.81), unit_motion=unit)
    peak = max(float(np.max(np.abs(v))) for v in fr.balancing.values())
    assert peak > 1e-3
    assert float(np.max(np.abs(fr.power_residual))) <= 1e-9 * peak
    assert float(np.max(fr.force_residual)) <= 1e-9 * max(peak, 1.0)


def _moved_class4(dcx, dcy, ddx, ddy, dex, dey, dfx, dfy):
    xy = dict(CLASS4)
    for k, (dx, dy) in zip("CDEF", ((dcx, dcy), (ddx, ddy), (dex, dey), (dfx, dfy))):
        xy[k] = (xy[k][0] + dx, xy[k][1] + dy)
    try:
        return xy, from_drawing(Drawing(6, xy, CLASS4_LINKS, (), ((1, "A"),)))
    except DrawingError:
        assume(False)


small = st.floats(-0.004, 0.004)


#: each class-IV example builds a continuation table (~0.5 s): fewer examples
SET4 = settings(max_examples=8, deadline=None)


@SET4
@given(small, small, small, small, small, small, small, small)
def test_a_moved_class4_drawing_closes_and_differentiates(dcx, dcy, ddx, ddy, dex, dey,
                                                         dfx, dfy):
    xy, fd = _moved_class4(dcx, dcy, ddx, ddy, dex, dey, dfx, dfy)
    assert fd.structure.mechanism_class == 4
    assert [e.kind for e in fd.linkage.elements].count("group") == 1
    _check(fd, xy, CLASS4_LINKS)


@SET4
@given(small, small, small, small, small, small, small, small, st.floats(0.1, 5.0),
       st.floats(-2.0, 2.0))
def test_a_moved_class4_drawing_passes_the_power_balance(dcx, dcy, ddx, ddy, dex, dey,
                                                         dfx, dfy, m4, alpha1):
    from mechcli.core.linkage.kinetostatics import Body, solve_forces, topology

    xy, fd = _moved_class4(dcx, dcy, ddx, ddy, dex, dey, dfx, dfy)
    lk = fd.linkage
    q = fd.inputs[1] + np.linspace(-0.3, 0.3, 25)
    m = solve(lk, {1: DriverMotion(q, 7.0, alpha1)}, order=2)
    assume(bool(np.all(m.regular)))
    unit = solve(lk, {1: DriverMotion(q, 1.0, 0.0)}, order=1)
    bodies = {1: Body(1, 0.4, 2e-4), 2: Body(2, 1.1, 4e-3), 3: Body(3, 0.5, 1e-3),
              4: Body(4, m4, 3e-3), 5: Body(5, 0.8, 2e-3)}
    fr = solve_forces(topology(lk), m, bodies, gravity=(0.0, -9.81), unit_motion=unit)
    peak = max(float(np.max(np.abs(v))) for v in fr.balancing.values())
    assert peak > 1e-3
    assert float(np.max(np.abs(fr.power_residual))) <= 1e-9 * peak
    assert float(np.max(fr.force_residual)) <= 1e-9 * max(peak, 1.0)
