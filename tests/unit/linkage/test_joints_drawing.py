"""A linkage given by its joints (issue 30): the drawing in, the elements and Assur
groups out (mechcli.core.linkage.drawing), and the class-III triad solved by Newton
(mechcli.core.linkage.triad).

References: every preset re-drawn by joints equals the preset; Watt's and
Stephenson's six-bars by joints equal their dyad forms; the triad against an
independent solution (scipy.optimize.root on the six distance equations of its
joints, with its own continuation, velocities from the differentiated equations'
linear system), its loop closure and finite differences of its positions.
"""

import math

import numpy as np
import pytest

from mechcli.core.linkage import (RRR, Crank, DriverMotion, Ground, Linkage, PointOnLink,
                                  presets, solve)
from mechcli.core.linkage.drawing import Drawing, DrawingError, Slider, from_drawing

Q = np.radians(np.arange(0.0, 360.0, 0.5))


def _drawn(linkage, theta, names=None):
    """The joints of *linkage* solved at the crank angle *theta* [rad]: a drawing."""
    m = solve(linkage, {1: DriverMotion(np.array([theta]))}, order=0)
    return {k: (float(np.ravel(p.x)[0]), float(np.ravel(p.y)[0]))
            for k, p in m.points.items() if names is None or k in names}


def _same_motion(a, b, points, links, tol=1e-12):
    """Positions, velocities and accelerations of two linkages over Q (ω1 = 10, α1 = 3)
    equal to *tol* of each quantity's peak."""
    ma = solve(a, {1: DriverMotion(Q, 10.0, 3.0)})
    mb = solve(b, {1: DriverMotion(Q, 10.0, 3.0)})
    assert ma.regular.all() and mb.regular.all()
    for p in points:
        for f in ("x", "y", "vx", "vy", "ax", "ay"):
            va, vb = getattr(ma.points[p], f), getattr(mb.points[p], f)
            assert np.max(np.abs(va - vb)) <= tol * max(1.0, np.max(np.abs(va))), (p, f)
    for n in links:
        for f in ("omega", "alpha"):
            va, vb = getattr(ma.links[n], f), getattr(mb.links[n], f)
            assert np.max(np.abs(va - vb)) <= tol * np.max(np.abs(va)), (n, f)


def test_four_bar_by_joints_is_the_preset():
    pre = presets.four_bar(0.1016, 0.254, 0.1778, 0.3048, 1)       # 例 1-1
    d = Drawing(4, _drawn(pre, math.radians(60)), {1: ("A", "B"), 2: ("B", "C"),
                                                    3: ("D", "C")}, (), ((1, "A"),))
    fd = from_drawing(d)
    assert [type(e).__name__ for e in fd.linkage.elements] == ["Ground", "Ground", "Crank",
                                                               "RRR"]
    assert fd.linkage.elements[3].branch == 1 and fd.structure.mechanism_class == 2
    assert fd.inputs == {1: pytest.approx(math.radians(60), abs=1e-15)}
    _same_motion(pre, fd.linkage, "BC", (2, 3))
    # drawn in the other assembly mode (C mirrored in BD), the branch follows the drawing
    crossed = presets.four_bar(0.1016, 0.254, 0.1778, 0.3048, -1)
    d2 = Drawing(4, _drawn(crossed, math.radians(60)), d.links, (), ((1, "A"),))
    assert from_drawing(d2).linkage.elements[3].branch == -1


def test_link_angles_follow_the_drawn_order():
    pre = presets.four_bar(0.1016, 0.254, 0.1778, 0.3048, 1)
    xy = _drawn(pre, math.radians(60))
    # link 3 listed C first: its angle is C -> D, the engine's (D -> C) plus 180°
    fd = from_drawing(Drawing(4, xy, {1: ("A", "B"), 2: ("B", "C"), 3: ("C", "D")}, (),
                              ((1, "A"),)))
    assert dict(fd.linkage.angle_offsets) == {3: pytest.approx(-math.pi, abs=1e-12)}


def test_slider_crank_guide_bar_and_shaper_by_joints_are_the_presets():
    sc = presets.slider_crank(0.1, 0.3, 0.02, 1)
    xy = _drawn(sc, math.radians(40))
    fd = from_drawing(Drawing(4, xy, {1: ("A", "B"), 2: ("B", "C"), 3: ("C",)},
                              (Slider(3, 4, "C", 0.0),), ((1, "A"),)))
    assert [g.type for g in fd.structure.groups] == ["driver", "RRP"]
    _same_motion(sc, fd.linkage, "BC", (2,))
    gb = presets.guide_bar(0.1, 0.3, 0.0, 1)                          # 例 1-3's layout
    m = solve(gb, {1: DriverMotion(np.array([math.radians(40)]))}, order=0)
    xy = _drawn(gb, math.radians(40))
    g3 = float(np.ravel(m.links[3].theta)[0])
    fd = from_drawing(Drawing(4, xy, {1: ("A", "B"), 2: ("B",), 3: ("C",)},
                              (Slider(2, 3, "B", g3),), ((1, "A"),)))
    assert [g.type for g in fd.structure.groups] == ["driver", "RPR"]
    _same_motion(gb, fd.linkage, "B", (3,))
    sh = presets.shaper(0.125, 0.6, 0.15, 0.275, 0.575, 1)             # 例 1-4
    m = solve(sh, {1: DriverMotion(np.array([math.radians(30)]))}, order=0)
    xy = _drawn(sh, math.radians(30), "ABCDE")
    g3 = float(np.ravel(m.links[3].theta)[0])
    fd = from_drawing(Drawing(6, xy, {1: ("A", "B"), 2: ("B",), 3: ("C", "D"), 4: ("D", "E"),
                                      5: ("E",)},
                              (Slider(2, 3, "B", g3, "23"), Slider(5, 6, "E", 0.0, "E")),
                              ((1, "A"),)))
    assert [g.type for g in fd.structure.groups] == ["driver", "RPR", "RRP"]
    _same_motion(sh, fd.linkage, "BDE", (3, 4))


def _six_bar(kind):
    """Watt's (the rocker 3 is ternary) or Stephenson's (the coupler 2 is ternary)
    six-bar in the dyad form, A = (0, 0), D = (0.3, 0), G the second dyad's pivot."""
    els = [Ground("A", 0.0, 0.0), Ground("D", 0.3, 0.0), Ground("G", 0.45, 0.25),
           Crank(1, "A", "B", 0.08), RRR("C", "B", 2, 0.25, "D", 3, 0.2, 1)]
    if kind == "watt":
        els += [PointOnLink("E", 3, "D", 0.12, -0.06), RRR("F", "E", 4, 0.22, "G", 5, 0.18, 1)]
    else:
        els += [PointOnLink("E", 2, "B", 0.15, -0.08), RRR("F", "E", 4, 0.2, "G", 5, 0.25, 1)]
    return Linkage(6, tuple(els))


@pytest.mark.parametrize("kind,links", [
    ("watt", {1: ("A", "B"), 2: ("B", "C"), 3: ("D", "C", "E"), 4: ("E", "F"), 5: ("G", "F")}),
    ("stephenson", {1: ("A", "B"), 2: ("B", "C", "E"), 3: ("D", "C"), 4: ("E", "F"),
                    5: ("G", "F")})])
def test_watt_and_stephenson_six_bars_by_joints_equal_their_dyad_forms(kind, links):
    ref = _six_bar(kind)
    fd = from_drawing(Drawing(6, _drawn(ref, math.radians(75)), links, (), ((1, "A"),)))
    assert [g.type for g in fd.structure.groups] == ["driver", "RRR", "RRR"]
    _same_motion(ref, fd.linkage, "BCEF", (2, 3, 4, 5))


# -- the class-III triad ------------------------------------------------------------
#: a crank 1 (A) drives the ternary link 3 (C, E, F) through 2; 3 is held by the rockers
#: 4 (E-G) and 5 (F-H): the drawing of configs/ch1/class3-sixbar.toml [mm]
TRIAD_XY = {"A": (0.0, 0.0), "B": (-19.35, -1.44), "C": (81.65, 53.48), "E": (117.78, 50.71),
            "F": (102.9, 93.53), "G": (188.83, 22.69), "H": (80.08, 150.21)}
TRIAD_LINKS = {1: ("A", "B"), 2: ("B", "C"), 3: ("C", "E", "F"), 4: ("G", "E"),
               5: ("H", "F")}


def _triad():
    xy = {k: (x / 1000, y / 1000) for k, (x, y) in TRIAD_XY.items()}
    return xy, from_drawing(Drawing(6, xy, TRIAD_LINKS, (), ((1, "A"),)))


def _fsolve_triad(xy, thetas):
    """Independent: scipy's root (MINPACK hybrd) on the six distance equations of C, E, F, continued
    from the drawing in 1° steps; velocities from the differentiated equations."""
    from scipy.optimize import root

    P = {k: np.array(v) for k, v in xy.items()}
    pairs = [("B", "C"), ("C", "E"), ("E", "F"), ("C", "F"), ("E", "G"), ("F", "H")]
    L = [np.linalg.norm(P[a] - P[b]) for a, b in pairs]
    r1 = np.linalg.norm(P["B"])
    th0 = math.atan2(P["B"][1], P["B"][0])

    def known(th):
        return {"B": r1 * np.array([math.cos(th), math.sin(th)]), "G": P["G"], "H": P["H"]}

    def eqs(u, th):
        pos = {**known(th), "C": u[0:2], "E": u[2:4], "F": u[4:6]}
        return [np.dot(pos[a] - pos[b], pos[a] - pos[b]) - l * l for (a, b), l in zip(pairs, L)]

    def jac(u, th):
        pos = {**known(th), "C": u[0:2], "E": u[2:4], "F": u[4:6]}
        idx = {"C": 0, "E": 2, "F": 4}
        J = np.zeros((6, 6))
        for row, (a, b) in enumerate(pairs):
            d = 2 * (pos[a] - pos[b])
            if a in idx:
                J[row, idx[a]:idx[a] + 2] += d
            if b in idx:
                J[row, idx[b]:idx[b] + 2] -= d
        return J

    out = {}
    u = np.concatenate([P["C"], P["E"], P["F"]])
    for target in thetas:
        steps = max(1, int(abs(target - th0) / math.radians(1.0)))
        for th in np.linspace(th0, target, steps + 1)[1:]:
            sol = root(eqs, u, args=(th,), jac=jac, method="hybr", options={"xtol": 1e-13})
            u = sol.x
        th0 = target
        J = jac(u, target)
        B = known(target)["B"]
        vB = 10.0 * np.array([-B[1], B[0]])       # ω1 = 10 rad/s
        # d/dt of |B - C|^2: 2 (B - C).(vB - vC): the known part moves to the right side
        rhs = np.zeros(6)
        rhs[0] = -2 * np.dot(B - u[0:2], vB)
        out[target] = (u.copy(), np.linalg.solve(J, rhs))
    return out


def test_triad_against_an_independent_solution():
    xy, fd = _triad()
    assert fd.structure.mechanism_class == 3
    assert [g.type for g in fd.structure.groups] == ["driver", "triad"]
    tri = fd.linkage.elements[-1]
    assert tri.kind == "triad" and tri.period == pytest.approx(2 * math.pi)
    thetas = [math.radians(a) for a in (-15.0, 40.0, 130.0, 200.0, 300.0)]
    ref = _fsolve_triad(xy, thetas)
    m = solve(fd.linkage, {1: DriverMotion(np.array(thetas), 10.0, 0.0)})
    peak = 0.2                                        # the drawing's size [m]
    for i, th in enumerate(thetas):
        u, v = ref[th]
        for k, p in enumerate("CEF"):
            got = np.array([m.points[p].x[i], m.points[p].y[i]])
            assert np.max(np.abs(got - u[2 * k:2 * k + 2])) <= 1e-9 * peak
            gv = np.array([m.points[p].vx[i], m.points[p].vy[i]])
            assert np.max(np.abs(gv - v[2 * k:2 * k + 2])) <= 1e-9 * np.max(np.abs(v))


def test_triad_closes_and_its_rates_are_the_derivatives_of_its_positions():
    xy, fd = _triad()
    m = solve(fd.linkage, {1: DriverMotion(Q, 10.0, 0.0)})
    assert m.regular.all()
    P = {k: np.array(v) for k, v in xy.items()}
    for a, b in [("B", "C"), ("C", "E"), ("E", "F"), ("C", "F"), ("E", "G"), ("F", "H")]:
        d = np.hypot(m.points[a].x - m.points[b].x, m.points[a].y - m.points[b].y)
        # closure residual within 1e-12 of the linkage's size (0.2 m)
        assert np.max(np.abs(d - np.linalg.norm(P[a] - P[b]))) <= 1e-12 * 0.2
    # central differences, h = 1e-5 rad: truncation ~h^2 |x'''| / 6, rounding ~eps x / h
    h = 1e-5
    mp = solve(fd.linkage, {1: DriverMotion(Q + h, 10.0)}, order=1)
    mm = solve(fd.linkage, {1: DriverMotion(Q - h, 10.0)}, order=1)
    for p in "CEF":
        v = (mp.points[p].x - mm.points[p].x) / (2 * h) * 10.0
        assert np.max(np.abs(v - m.points[p].vx)) <= 1e-7 * np.max(np.abs(m.points[p].vx))
        a = (mp.points[p].vx - mm.points[p].vx) / (2 * h) * 10.0
        assert np.max(np.abs(a - m.points[p].ax)) <= 1e-7 * np.max(np.abs(m.points[p].ax))
    for n in (3, 4, 5):
        al = (mp.links[n].omega - mm.links[n].omega) / (2 * h) * 10.0
        assert np.max(np.abs(al - m.links[n].alpha)) <= 1e-7 * np.max(np.abs(m.links[n].alpha))


def test_a_single_position_far_from_the_drawing_keeps_the_drawn_branch():
    # a refinement solves one angle at a time: the continuation table starts it right
    xy, fd = _triad()
    m_all = solve(fd.linkage, {1: DriverMotion(Q, 10.0)}, order=0)
    for i in (0, 250, 500):
        m1 = solve(fd.linkage, {1: DriverMotion(Q[i:i + 1], 10.0)}, order=0)
        assert float(m1.points["F"].x[0]) == pytest.approx(float(m_all.points["F"].x[i]),
                                                           abs=1e-15)


def test_drawing_errors_name_what_is_wrong():
    pre = presets.four_bar(0.1016, 0.254, 0.1778, 0.3048, 1)
    xy = _drawn(pre, math.radians(60))
    links = {1: ("A", "B"), 2: ("B", "C"), 3: ("D", "C")}
    with pytest.raises(DrawingError, match="= 1, but 2 drivers") as e:
        from_drawing(Drawing(4, xy, links, (), ((1, "A"), (3, "D"))))
    assert e.value.what == "drivers"
    with pytest.raises(DrawingError, match="names joint 'X'"):
        from_drawing(Drawing(4, xy, {**links, 2: ("B", "X")}, (), ((1, "A"),)))
    # with the frame listed, a joint on one moving link only is no pivot
    with pytest.raises(DrawingError, match="joint 'D' is on link 3 only"):
        from_drawing(Drawing(4, xy, {**links, 4: ("A",)}, (), ((1, "A"),)))
    # C drawn on the line B-D: the dyad's branch is not fixed by the drawing
    flat = dict(xy, C=(xy["B"][0] + 0.6 * (xy["D"][0] - xy["B"][0]),
                       xy["B"][1] + 0.6 * (xy["D"][1] - xy["B"][1])))
    with pytest.raises(DrawingError, match="dead point") as e:
        from_drawing(Drawing(4, flat, links, (), ((1, "A"),)))
    assert (e.value.what, e.value.name) == ("joint", "C")
    # the slider's joint off its line of sliding
    sc = presets.slider_crank(0.1, 0.3, 0.02, 1)
    sxy = _drawn(sc, math.radians(40))
    with pytest.raises(DrawingError, match="not on its line of sliding"):
        from_drawing(Drawing(4, sxy, {1: ("A", "B"), 2: ("B", "C"), 3: ("C",)},
                             (Slider(3, 4, "A", 0.0),), ((1, "A"),)))


def test_class3_config_against_its_independent_reference():
    # configs/ch1/class3-sixbar.toml's [expected] extremes are the reference's
    # (tests/reference/independent_triad.py: MINPACK on the joints' coordinates); they
    # agree to 1e-12 deg, so the written 9 decimals (±5e-10) hold
    from tests.conftest import CONFIGS, ROOT, load_module
    try:
        import tomllib
    except ImportError:   # Python < 3.11
        import tomli as tomllib

    ref = load_module(ROOT / "tests" / "reference" / "independent_triad.py")
    cfg = tomllib.loads((CONFIGS / "ch1" / "class3-sixbar.toml").read_text(encoding="utf-8"))
    assert {k: tuple(v) for k, v in cfg["mechanism"]["joints"].items()} == ref.DRAWING
    exp = cfg["expected"]
    for name, (hi, at_hi, lo, at_lo) in ref.extremes().items():
        assert exp[f"{name}_max_deg"] == pytest.approx(hi, abs=5e-10)
        assert exp[f"{name}_max_at_deg"] == pytest.approx(at_hi, abs=5e-10)
        assert exp[f"{name}_min_deg"] == pytest.approx(lo, abs=5e-10)
        assert exp[f"{name}_min_at_deg"] == pytest.approx(at_lo, abs=5e-10)


def test_class3_designs_stack_into_one_batch():
    # optimize moves a population of drawings at once (engine.stack): designs whose
    # triads have their own continuation tables keep them per design, and the batch
    # gives each design's motion exactly as solved alone
    from mechcli.core.linkage import stack

    base = {"A": (0.0, 0.0), "B": (-0.01935, -0.00144), "C": (0.08165, 0.05348),
            "E": (0.11778, 0.05071), "F": (0.1029, 0.09353), "G": (0.18883, 0.02269),
            "H": (0.08008, 0.15021)}
    links = {1: ("A", "B"), 2: ("B", "C"), 3: ("C", "E", "F"), 4: ("G", "E"), 5: ("H", "F")}
    designs = []
    for dx, dy in ((0.0, 0.0), (0.006, -0.01), (-0.004, 0.003)):
        xy = dict(base, H=(base["H"][0] + dx, base["H"][1] + dy))
        designs.append(from_drawing(Drawing(6, xy, links, (), ((1, "A"),))).linkage)
    batch = stack(designs)
    q = np.radians(np.arange(0.0, 360.0, 5.0))
    mb = solve(batch, {1: DriverMotion(q, 10.0, 1.5)}, order=2)
    for k, lk in enumerate(designs):
        m = solve(lk, {1: DriverMotion(q, 10.0, 1.5)}, order=2)
        assert np.array_equal(mb.regular[k], m.regular)
        ok = m.regular
        assert ok.sum() > 30
        for p in ("C", "E", "F"):
            for f in ("x", "y", "vx", "vy", "ax", "ay"):
                got = getattr(mb.points[p], f)[k][ok]
                want = getattr(m.points[p], f)[ok]
                assert np.allclose(got, want, rtol=1e-12, atol=1e-12 * np.max(np.abs(want)))
    # designs that differ in their structure still cannot be stacked
    other = presets.four_bar(0.1, 0.3, 0.2, 0.25)
    with pytest.raises(ValueError):
        stack([designs[0], other])
