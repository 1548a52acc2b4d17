"""Rigid-body guidance (chapter 3 §3.2–3.4, and Burmester theory): book values,
independent checks, and every design moved through its positions on the engine.

Book values are typed in millimetres as printed and compared in metres with half a
unit of the last printed digit (±0.005 mm for two decimals).
"""

import dataclasses
import math

import numpy as np
import pytest

from mechcli.core.errors import DescribedError
from mechcli.core.linkage import DriverMotion, Linkage, solve
from mechcli.core.synth.design import branch_of, four_bar_design
from mechcli.core.synth.guidance import (BurmesterPair, burmester_curves, burmester_design,
                                         burmester_points, coupler_poses, displacement_matrix,
                                         moving_pivots, three_positions, two_positions)

MM = 1e-3
HALF = 0.005 * MM          # half a unit of two printed decimals [m]


def xy(p):
    return complex(*p)


def engine(design, linkage=None):
    """The design (or another linkage) solved at its prescribed inputs."""
    return solve(linkage or design.linkage, {1: DriverMotion(np.asarray(design.inputs))},
                 order=0)


def flipped(linkage):
    """The same linkage assembled in the other mode."""
    return Linkage(linkage.frame, tuple(
        dataclasses.replace(el, branch=-el.branch) if hasattr(el, "branch") else el
        for el in linkage.elements))


def reproduction_error(design, m, positions):
    """Largest error of the prescribed points (relative to the size) and angles (rad)
    at the given 0-based positions."""
    err = 0.0
    for name, target in design.points.items():
        p = m.points[name]
        got = (p.x + 1j * p.y)[positions]
        err = max(err, float(np.max(np.abs(got - np.asarray(target)[positions]))) / design.size)
    for link, target in design.angles.items():
        d = np.angle(np.exp(1j * (m.links[link].theta - np.asarray(target))))[positions]
        err = max(err, float(np.max(np.abs(d))))
    return err


def assert_reproduced(design, positions=None, linkage=None):
    m = engine(design, linkage)
    positions = list(range(len(design.inputs))) if positions is None else positions
    assert m.feasible[positions].all()
    # loop closure on the engine: round-off, nothing more
    assert reproduction_error(design, m, positions) <= 1e-9


# --------------------------------------------------------------------- 【例 3-2】
EX32_B = [(82 * MM, 0.0), (0.0, 60 * MM)]
EX32_C = [(32 * MM, 0.0), (0.0, 110 * MM)]
EX32_LINE = (1.0, 0.0, -18 * MM)      # x = -18 mm (the program's a=1; b=0; c=-18)


def test_ex3_2_furnace_door_pivots_and_lengths():
    d = two_positions(EX32_B, EX32_C, line_A=EX32_LINE, line_D=EX32_LINE)
    # 例 3-2 计算结果 1: A(-18.00, -50.63), D(-18.00, 45.11)
    assert d.pivots["A"] == pytest.approx((-18.00 * MM, -50.63 * MM), abs=HALF)
    assert d.pivots["D"] == pytest.approx((-18.00 * MM, 45.11 * MM), abs=HALF)
    # 计算结果 2: AB 112.09, BC 50.00, CD 67.34, AD 95.74
    for key, book in (("l1", 112.09), ("l2", 50.00), ("l3", 67.34), ("l4", 95.74)):
        assert d.lengths[key] == pytest.approx(book * MM, abs=HALF), key
    # closed form: on x = -18, |A - B1| = |A - B2| gives 120 y = 164 x - 3124 (mm)
    assert d.pivots["A"][1] == pytest.approx((164 * -18 - 3124) / 120 * MM, rel=1e-13)
    # and 220 y = 64 x + 11076 for D
    assert d.pivots["D"][1] == pytest.approx((64 * -18 + 11076) / 220 * MM, rel=1e-13)
    assert d.kind == "four_bar" and np.allclose(d.inputs, np.angle(
        np.array([xy(p) for p in EX32_B]) - xy(d.pivots["A"])), rtol=0, atol=1e-15)


def test_ex3_2_door_changes_assembly_mode_between_its_positions():
    d = two_positions(EX32_B, EX32_C, line_A=EX32_LINE, line_D=EX32_LINE)
    assert_reproduced(d, [0])
    # The book's door linkage reaches position 2 only in the other assembly mode:
    # C crosses the line BD (B, C, D in line: AB at a limit of its swing) between
    # the positions, so a drive at AB cannot move the door from open to closed; a
    # hand on the door can.  (Not a wrong number: the book does not check it.)
    A, D = xy(d.pivots["A"]), xy(d.pivots["D"])
    b, c = d.points["B"], d.points["C"]
    assert branch_of(b[0], c[0], D) == 1 and branch_of(b[1], c[1], D) == -1
    assert reproduction_error(d, engine(d), [1]) > 0.1
    assert_reproduced(d, [1], flipped(d.linkage))
    assert abs(A - b[0]) == pytest.approx(abs(A - b[1]), rel=1e-14)


def test_two_positions_pivot_given_as_a_point():
    by_line = two_positions(EX32_B, EX32_C, line_A=EX32_LINE, line_D=EX32_LINE)
    d = two_positions(EX32_B, EX32_C, A=by_line.pivots["A"], line_D=EX32_LINE)
    assert d.pivots["A"] == by_line.pivots["A"] and d.lengths == by_line.lengths
    # the book's printed A (two decimals) is 0.0033 mm off the bisector: rejected
    with pytest.raises(DescribedError) as e:
        two_positions(EX32_B, EX32_C, A=(-18.00 * MM, -50.63 * MM), line_D=EX32_LINE)
    assert e.value.reason == "not_on_bisector"
    assert abs(e.value.values["distance_1"] - e.value.values["distance_2"]) > 1e-6 * MM


def test_two_positions_vertical_and_horizontal_bisectors():
    # B1B2 horizontal (the book's slope (3-5) divides by zero); C1C2 vertical
    d = two_positions([(0, 0), (2, 0)], [(0, 1), (2, 1.0)], line_A=(0, 1, -3), line_D=(1, 1, 4))
    assert d.pivots["A"] == pytest.approx((1.0, -3.0), abs=1e-15)
    assert d.pivots["D"] == pytest.approx((1.0, 3.0), abs=1e-15)
    assert_reproduced(d, [0])


@pytest.mark.parametrize("B, C, line_A, reason", [
    ([(1, 0), (1, 0)], [(1, 1), (2, 0)], (1, 0, 0), "coincident"),     # B1 = B2, BC = 1
    ([(0, 0), (1, 0)], [(0, 1), (1, 2)], (1, 0, 0), "not_rigid"),      # BC 1, then sqrt 2
    # the bisector of B1B2 is x = 1; the line x = 5 never meets it
    ([(0, 0), (2, 0)], [(0, 1), (2, 1)], (1, 0, 5), "parallel"),
])
def test_two_positions_without_solution(B, C, line_A, reason):
    with pytest.raises(DescribedError) as e:
        two_positions(B, C, line_A=line_A, line_D=(1, 0, 0))
    assert e.value.reason == reason


def test_two_positions_zero_frame_and_bad_calls():
    # both pivots at the same point of both bisectors: A = D (frame of length 0)
    with pytest.raises(DescribedError) as e:
        two_positions([(0, 0), (2, 0)], [(0, 2), (2, 2)], A=(1, 5), D=(1, 5))
    assert e.value.reason == "zero_link"
    with pytest.raises(ValueError):
        two_positions(EX32_B, EX32_C, A=(0, 0), line_A=EX32_LINE, line_D=EX32_LINE)
    with pytest.raises(ValueError):
        two_positions(EX32_B, EX32_C, line_D=EX32_LINE)
    with pytest.raises(ValueError):
        two_positions(EX32_B, EX32_C, line_A=(0, 0, 1), line_D=EX32_LINE)
    with pytest.raises(ValueError):
        two_positions(EX32_B[:1], EX32_C, line_A=EX32_LINE, line_D=EX32_LINE)


# --------------------------------------------------------------------- 【例 3-3】
EX33_B = [(0.0, 100 * MM), (100 * MM, 200 * MM), (300 * MM, 200 * MM)]
EX33_C = [(0.0, 200 * MM), (200 * MM, 200 * MM), (300 * MM, 100 * MM)]


def test_ex3_3_three_positions():
    d = three_positions(EX33_B, EX33_C)
    # 例 3-3 计算结果 1: A(200.00, 0.00), D(100.00, 0.00)
    assert d.pivots["A"] == pytest.approx((200 * MM, 0.0), abs=HALF)
    assert d.pivots["D"] == pytest.approx((100 * MM, 0.0), abs=HALF)
    # 计算结果 2: AB 223.61, BC 100.00, CD 223.61, AD 100.00
    for key, book in (("l1", 223.61), ("l2", 100.00), ("l3", 223.61), ("l4", 100.00)):
        assert d.lengths[key] == pytest.approx(book * MM, abs=HALF), key
    # closed form: |A - Bj|² = 200² + 100² mm² for j = 1..3 (the data are integers)
    assert d.lengths["l1"] == pytest.approx(math.sqrt(50000) * MM, rel=1e-14)
    assert_reproduced(d)


@pytest.mark.parametrize("B, reason", [
    ([(0, 0), (1, 1), (2, 2)], "collinear"),
    ([(0, 0), (1, 1), (0, 0)], "coincident"),
])
def test_three_positions_without_solution(B, reason):
    C = [(b[0] + 1.0, b[1]) for b in B]      # the coupler translates: BC = 1 throughout
    with pytest.raises(DescribedError) as e:
        three_positions(B, C)
    assert e.value.reason == reason and e.value.values["link"] == 1


# --------------------------------------------------------------------- 【例 3-4】【例 3-5】
EX34_M = [(10 * MM, 32 * MM), (36 * MM, 39 * MM), (45 * MM, 24 * MM)]
EX34_PHI = np.radians([52.0, 29.0, 0.0])
EX34_A, EX34_D = (0.0, 0.0), (63 * MM, 0.0)


def check_ex3_4(d):
    # 例 3-4 / 例 3-5 计算结果 1: B(-3.09, -9.36), C(69.85, 29.15)
    assert d.pivots["B1"] == pytest.approx((-3.09 * MM, -9.36 * MM), abs=HALF)
    assert d.pivots["C1"] == pytest.approx((69.85 * MM, 29.15 * MM), abs=HALF)
    # 计算结果 2: AB 9.86, BC 82.48, CD 29.94, AD 63.00
    for key, book in (("l1", 9.86), ("l2", 82.48), ("l3", 29.94), ("l4", 63.00)):
        assert d.lengths[key] == pytest.approx(book * MM, abs=HALF), key


@pytest.mark.parametrize("method", ["matrix", "nonlinear"])
def test_ex3_4_and_3_5_coupler_poses(method):
    d = coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method=method)
    check_ex3_4(d)
    v = d.values
    assert v["method"] == method and v["tol"] == 1e-12
    assert v["residual"] <= 1e-13          # eqs. 3-31, 3-32 / size²: round-off
    assert (v["iterations"] == 0) == (method == "matrix")
    assert d.pivots["M1"] == EX34_M[0]


def test_ex3_5_from_the_books_fsolve_start():
    # link_fun_main starts B at x' = y' = 0 and C at x' = 34, y' = 48 (coupler frame)
    e1 = np.exp(1j * EX34_PHI[0])
    m1 = xy(EX34_M[0])
    c0 = m1 + (34 + 48j) * MM * e1
    d = coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method="nonlinear",
                      guess=[EX34_M[0], (c0.real, c0.imag)])
    check_ex3_4(d)
    # the equations are linear in B1, C1 once A and D are given: levenberg-marquardt needs
    # 2 Jacobian evaluations from this start (measured; the same as from the default start)
    assert d.values["iterations"] == 2


def test_ex3_4_matrix_and_nonlinear_agree_to_round_off():
    a = coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method="matrix")
    b = coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method="nonlinear")
    for k in ("B1", "C1"):
        assert abs(xy(a.pivots[k]) - xy(b.pivots[k])) <= 1e-9 * a.size
    m = moving_pivots(EX34_A, EX34_D, [(x, y, p) for (x, y), p in zip(EX34_M, EX34_PHI)])
    check_ex3_4(m)
    assert abs(xy(m.pivots["B1"]) - xy(a.pivots["B1"])) <= 1e-12 * a.size


def test_ex3_4_design_reaches_pose_3_only_in_the_other_mode():
    d = coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D)
    assert_reproduced(d, [0, 1])
    # ERRATA (the design, not its numbers): the book's crank-rocker of 例 3-4/3-5
    # reaches poses 1 and 2 with C to the left of B→D and pose 3 with C to the
    # right.  Driven by its crank, a Grashof crank-rocker never has B, C, D in line,
    # so its two assembly modes are separate circuits: the linkage cannot be moved
    # through the three poses without disassembly.  The book does not check it.
    assert reproduction_error(d, engine(d), [2]) > 0.1
    assert_reproduced(d, [2], flipped(d.linkage))


def test_displacement_matrix_eq_3_22():
    D12 = displacement_matrix(EX34_M[0], EX34_PHI[0], EX34_M[1], EX34_PHI[1])
    # M1 -> M2 and a unit vector turned by φ2 - φ1 (eq. 3-23)
    assert D12 @ [*EX34_M[0], 1] == pytest.approx([*EX34_M[1], 1], abs=1e-16)
    t = EX34_PHI[1] - EX34_PHI[0]
    assert D12[:2, :2] @ [1, 0] == pytest.approx([math.cos(t), math.sin(t)], abs=1e-16)


def linear_moving_pivot(M, phi, P):
    """Independent: eq. 3-31 with P given is linear in the coupler-frame (x', y')."""
    Mz = np.array([xy(m) for m in M])
    e = np.exp(1j * np.asarray(phi))
    rows, rhs = [], []
    for i in (1, 2):
        # 2 Re(conj(Mi - P) e_i z) - 2 Re(conj(M1 - P) e_1 z) = |M1 - P|² - |Mi - P|²
        ki, k1 = np.conj(Mz[i] - P) * e[i], np.conj(Mz[0] - P) * e[0]
        rows.append([2 * (ki - k1).real, -2 * (ki - k1).imag])
        rhs.append(abs(Mz[0] - P) ** 2 - abs(Mz[i] - P) ** 2)
    u, v = np.linalg.solve(rows, rhs)
    return Mz[0] + (u + 1j * v) * e[0]


@pytest.mark.parametrize("M, phi_deg, A, D", [
    # 习题 3-6: P(1, 1) 0°, (2, 0.5) 0°, (3, 1.5) 45°; A(0, 0), D(5, 0)
    ([(1, 1), (2, 0.5), (3, 1.5)], [0, 0, 45], (0, 0), (5, 0)),
    # 习题 3-7: M(204, -30) 0°, (144, 80) 22°, (34, 100) 68°; A(0, 0), D(34, -83) [mm]
    ([(204 * MM, -30 * MM), (144 * MM, 80 * MM), (34 * MM, 100 * MM)], [0, 22, 68],
     (0, 0), (34 * MM, -83 * MM)),
])
def test_exercises_3_6_and_3_7(M, phi_deg, A, D):
    phi = np.radians(phi_deg)
    a = coupler_poses(M, phi, A, D, method="matrix")
    b = coupler_poses(M, phi, A, D, method="nonlinear")
    m = moving_pivots(A, D, [(x, y, p) for (x, y), p in zip(M, phi)])
    # the book prints no answer: checked against the linear form of eqs. 3-31, 3-32
    B1, C1 = linear_moving_pivot(M, phi, xy(A)), linear_moving_pivot(M, phi, xy(D))
    for d in (a, b, m):
        assert abs(xy(d.pivots["B1"]) - B1) <= 1e-9 * a.size
        assert abs(xy(d.pivots["C1"]) - C1) <= 1e-9 * a.size
    assert a.values["residual"] <= 1e-12 and b.values["residual"] <= 1e-12
    # poses 1, 2 on the engine; pose 3 in the design's own mode or, for 习题 3-6,
    # the other one (a branch defect of that design, too)
    assert_reproduced(a, [0, 1])
    m3 = engine(a)
    if reproduction_error(a, m3, [2]) > 1e-9:
        assert phi_deg == [0, 0, 45]
        assert_reproduced(a, [2], flipped(a.linkage))
    # θ2 = the angle of B→C turned with the coupler
    assert np.allclose(np.exp(1j * a.angles[2]), np.exp(1j * (
        np.angle(C1 - B1) + phi - phi[0])), rtol=0, atol=1e-12)


def test_coupler_poses_errors():
    # A is the pole P12 of poses 1, 2 (a rotation about A): A does not move
    # relative to the coupler between them, so B1 is not determined
    M = [(1.0, 0.0), (0.0, 1.0), (2.0, 2.0)]
    phi = [0.0, math.pi / 2, 0.3]
    for method in ("matrix", "nonlinear"):
        with pytest.raises(DescribedError) as e:
            coupler_poses(M, phi, (0, 0), (5, 0), method=method)
        assert e.value.reason == "coincident" and e.value.values["positions"] == (1, 2)
    # pure translations: A's positions seen from the coupler are on a line
    with pytest.raises(DescribedError) as e:
        coupler_poses([(0, 0), (1, 0), (2, 0)], [0.0] * 3, (0, -1), (5, -1))
    assert e.value.reason == "collinear"
    with pytest.raises(ValueError):
        coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, method="newton")
    with pytest.raises(ValueError):
        coupler_poses(EX34_M, EX34_PHI, EX34_A, EX34_D, tol=0.0)
    with pytest.raises(ValueError):
        moving_pivots(EX34_A, EX34_D, [(0, 0, 0)] * 2)


# --------------------------------------------------------------------- Burmester
#: a four-bar and its coupler point M (independent of the book; an engine motion)
FB = dict(A=(0.0, 0.0), D=(0.3, 0.05), B1=(0.05, 0.09), C1=(0.28, 0.22), M=(0.2, 0.3))


def fourbar_poses(theta_deg):
    d = four_bar_design(FB["A"], FB["D"], FB["B1"], FB["C1"], coupler_point=FB["M"])
    th = np.radians(theta_deg) + np.angle(xy(FB["B1"]))
    m = solve(d.linkage, {1: DriverMotion(th)}, order=0)
    assert m.feasible.all()
    return list(zip(m.points["M"].x, m.points["M"].y)), m.links[2].theta


def se_residual(M, phi, pair):
    """Largest |W (e^{iβj} - 1) + Z (e^{iαj} - 1) - δj| / max|δj|, βj from the circle
    point's positions (Sandor–Erdman, written out here independently)."""
    Mz, phi = np.array([xy(m) for m in M]), np.asarray(phi)
    W, Z = pair.circle - pair.centre, Mz[0] - pair.circle
    alpha, delta = phi - phi[0], Mz - Mz[0]
    Bj = Mz - Z * np.exp(1j * alpha)
    beta = np.angle((Bj - pair.centre) / W)
    F = W * (np.exp(1j * beta) - 1) + Z * (np.exp(1j * alpha) - 1) - delta
    return float(np.max(np.abs(F)) / np.max(np.abs(delta)))


FIVE = [0.0, 25.0, 50.0, 90.0, 140.0]


def test_burmester_points_of_a_four_bars_five_poses():
    M, phi = fourbar_poses(FIVE)
    pairs = burmester_points(M, phi)
    assert 2 <= len(pairs) <= 4
    for p in pairs:
        assert not p.at_infinity
        assert se_residual(M, phi, p) <= 1e-9
    # the linkage's own dyads are Burmester pairs
    for cen, cir in (("A", "B1"), ("D", "C1")):
        assert min(abs(p.centre - xy(FB[cen])) + abs(p.circle - xy(FB[cir]))
                   for p in pairs) <= 1e-9 * 0.3
    # sorted by the centre point's x
    xs = [p.centre.real for p in pairs]
    assert xs == sorted(xs)


def test_burmester_design_reproduces_the_five_poses_on_the_engine():
    M, phi = fourbar_poses(FIVE)
    pairs = burmester_points(M, phi)
    pa = min(pairs, key=lambda p: abs(p.centre - xy(FB["A"])))
    pb = min(pairs, key=lambda p: abs(p.centre - xy(FB["D"])))
    d = burmester_design(M, phi, pa, pb)
    assert d.values["residual"] <= 1e-12
    assert d.lengths["l4"] == pytest.approx(abs(xy(FB["D"]) - xy(FB["A"])), rel=1e-9)
    assert_reproduced(d)
    assert len(d.inputs) == 5 and d.pivots["M1"] == pytest.approx(FB["M"], abs=1e-15)


def slider_crank_poses():
    """Five coupler poses of an offset slider-crank (A = 0, crank 0.1, rod 0.3, e = 0.04)."""
    from mechcli.core.linkage.elements import RRP, Crank, Ground, PointOnLink
    lk = Linkage(4, (Ground("A", 0, 0), Crank(1, "A", "B", 0.1),
                     RRP("C", "B", 2, 0.3, 3, 4, "A", 0.0, 0.04, 1, "3"),
                     PointOnLink("M", 2, "B", 0.1, 0.08)))
    m = solve(lk, {1: DriverMotion(np.radians([10, 50, 100, 160, 230]))}, order=0)
    assert m.feasible.all()
    return (list(zip(m.points["M"].x, m.points["M"].y)), m.links[2].theta,
            complex(m.points["B"].x[0], m.points["B"].y[0]),
            complex(m.points["C"].x[0], m.points["C"].y[0]))


def test_burmester_slider_pair_is_at_infinity():
    M, phi, B1, C1 = slider_crank_poses()
    pairs = burmester_points(M, phi)
    sliders = [p for p in pairs if p.at_infinity]
    assert len(sliders) == 1 and pairs[-1] is sliders[0]
    s = sliders[0]
    # the slider's pin C moves on y = 0.04: guide along +x, circle point C1
    assert abs(s.centre - 1.0) <= 1e-9 and abs(s.circle - C1) <= 1e-9 * 0.3
    assert any(abs(p.centre) <= 1e-9 and abs(p.circle - B1) <= 1e-9 for p in pairs)
    for p in pairs:
        if not p.at_infinity:
            assert se_residual(M, phi, p) <= 1e-9
    crank = next(p for p in pairs if abs(p.centre) <= 1e-9)
    with pytest.raises(DescribedError) as e:
        burmester_design(M, phi, crank, s)
    assert e.value.reason == "at_infinity"


def test_burmester_errors():
    with pytest.raises(DescribedError) as e:
        burmester_points([(0, 0), (1, 0), (2, 1), (0, 3), (1, 1)], [0.2] * 5)
    assert e.value.reason == "no_rotation"
    with pytest.raises(DescribedError) as e:
        burmester_points([(1, 1)] * 5, [0, 1, 2, 3, 4])
    assert e.value.reason == "coincident"
    with pytest.raises(ValueError):
        burmester_points([(0, 0)] * 4, [0, 1, 2, 3])
    M, phi = fourbar_poses(FIVE)
    with pytest.raises(DescribedError) as e:
        burmester_design(M, phi, BurmesterPair(0j, 0.05 + 0.09j), BurmesterPair(1 + 1j, 0.5j))
    assert e.value.reason == "not_on_circle"


def poles(M, phi):
    """Independent: the poles Pjk of the displacements between poses (fixed points)."""
    Mz = np.array([xy(m) for m in M])
    out = []
    for j in range(len(Mz)):
        for k in range(j + 1, len(Mz)):
            e = np.exp(1j * (phi[k] - phi[j]))
            # P = Mk + e (P - Mj)  ->  P (1 - e) = Mk - e Mj
            out.append((Mz[k] - e * Mz[j]) / (1 - e))
    return out


def distance_to(curves, z):
    """Distance from z to the polylines."""
    best = math.inf
    for c in curves:
        a, b = c[:-1], c[1:]
        t = np.clip(((z - a) * np.conj(b - a)).real / np.maximum(np.abs(b - a) ** 2, 1e-300),
                    0, 1)
        best = min(best, float(np.min(np.abs(a + t * (b - a) - z))))
    return best


def test_burmester_curves_of_four_poses():
    M, phi = fourbar_poses(FIVE[:4])
    cv = burmester_curves(M, phi, n=4001)
    assert len(cv.centre) == len(cv.circle) == len(cv.beta2) >= 1
    Mz, e = np.array([xy(m) for m in M]), np.exp(1j * (phi - phi[0]))
    size = float(np.max(np.abs(Mz - Mz[0])))
    P = [p for p in poles(M, phi) if abs(p - Mz[0]) <= 100 * size]
    # the default disc: 10 sizes, or 1.25 times the farthest pole (up to 100 sizes)
    radius = max([10 * size] + [1.25 * abs(p - Mz[0]) for p in P])
    assert radius > 10 * size      # (a pole beyond 10 sizes: the curves reach it)
    for cen, cir in zip(cv.centre_branches(), cv.circle_branches()):
        assert cen.shape == cir.shape and len(cen) >= 2
        assert np.all(np.isfinite(cen)) and np.all(np.isfinite(cir))
        assert np.all(np.abs(cen - Mz[0]) <= radius * (1 + 1e-12))
        assert np.all(np.abs(cir - Mz[0]) <= radius * (1 + 1e-12))
        # every dyad reaches the four poses: |Bj - A| = |B1 - A| (eq. 3-31)
        B = Mz[None, :] + (cir[:, None] - Mz[0]) * e[None, :]
        r = np.abs(B - cen[:, None])
        assert np.max(np.abs(r - r[:, :1])) <= 1e-9 * size
    # the four-bar's own pivots are on the curves (to the sampling's chord error) ...
    spacing = max(float(np.max(np.abs(np.diff(c)))) for c in cv.centre + cv.circle)
    assert spacing <= radius / 50      # the sampling's longest chord (refined)
    assert distance_to(cv.centre, xy(FB["A"])) <= spacing
    assert distance_to(cv.centre, xy(FB["D"])) <= spacing
    assert distance_to(cv.circle, xy(FB["B1"])) <= spacing
    assert distance_to(cv.circle, xy(FB["C1"])) <= spacing
    # ... and so are the six poles (a property of the centre-point curve)
    assert len(P) == 6
    for pole in P:
        assert distance_to(cv.centre, pole) <= spacing
    # a smaller disc cuts the curves there
    small = burmester_curves(M, phi, n=721, extent=10.0)
    assert all(np.all(np.abs(c - Mz[0]) <= 10 * size * (1 + 1e-12))
               for c in small.centre + small.circle)


def test_burmester_design_from_a_curve_point():
    M, phi = fourbar_poses(FIVE[:4])
    cv = burmester_curves(M, phi, n=361)
    k = max(range(len(cv.centre)), key=lambda i: len(cv.centre[i]))
    i, j = len(cv.centre[k]) // 3, 2 * len(cv.centre[k]) // 3
    d = burmester_design(M, phi, BurmesterPair(cv.centre[k][i], cv.circle[k][i]),
                         BurmesterPair(cv.centre[k][j], cv.circle[k][j]))
    assert d.values["residual"] <= 1e-12 and len(d.inputs) == 4
