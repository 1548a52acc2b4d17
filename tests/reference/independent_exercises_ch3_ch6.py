#!/usr/bin/env python3
"""Independent reference numbers for 习题 3-5, 3-8 and 6-1 of 李滨城, 徐超《机械原理 MATLAB
辅助分析》, written for configs/ch3/exercise3-5.toml, configs/ch3/exercise3-8.toml and
configs/ch6/exercise6-1.toml.

Self-contained: numpy and the standard library only, nothing from mechcli.  The figures of
the three exercises are lost in the OCR text; the readings below are the ones written as
FIGURE-READING comments in the configs.  Conventions: x right, y up, angles counter-clockwise
from +x, a prime is d/d(crank angle).

习题 3-5 (clamping four-bar, 夹紧机构; OCR line ~4691)
------------------------------------------------------
Coupler poses P1 = (0.5, 0.5), theta1 = 20 deg; P2 = (1.5, 1.8), theta2 = 38 deg.  Reading:
the moving pivots on the coupler's reference line, B at P and C one unit further
(coupler coordinates B' = (0, 0), C' = (1, 0)), so  B_i = P_i,  C_i = P_i + u_i,
u_i = (cos theta_i, sin theta_i).  Conditions:
  * A on the perpendicular bisector of B1B2 (eq. 3-7):     (A - M_B) . (B2 - B1) = 0;
  * the dead point at pose 2 with CD driving: A, B2, C2 collinear, A = B2 + t u2, so
        t = -(B2 - M_B) . (B2 - B1) / (u2 . (B2 - B1)),   l_AB = |t|
    (t < 0: B2 lies between A and C2, the extended toggle);
  * D on the bisector of C1C2 (eq. 3-8) and on the vertical through C2 (C2D vertical):
        D = (x_C2, y),  y = y_M - (x_C2 - x_M)(x_C2 - x_C1)/(y_C2 - y_C1),  M = (C1 + C2)/2.
The crank angle of AB at each pose is atan2(B_i - A).  Grashof by hand: shortest s, longest
l, the others p, q; s + l > p + q is a double rocker whatever the frame.  `clamp_motion`
turns CD from pose 1 to pose 2 (both ways round) and reports whether |AC| stays strictly
inside (|l1 - l2|, l1 + l2) up to the pose 2, where it equals l1 + l2 (the dead point).

习题 3-8 (bus door, 公共汽车车门; OCR line ~4711)
-------------------------------------------------
Door BC = l = 400 mm, C on a straight track, C1C2 = 550 mm, AB1 parallel to C1C2.  Reading:
the closed door lies along the track (the bus side), so AB1 parallel to the track through B1
puts A on the track: A, B1, C1 collinear (the extended dead centre: the closed door cannot
be pushed open); C slides 550 mm towards A and the open door B2C2 makes 115 deg with the
closed door B1C1 at C2 (the door turns 65 deg).  With r = l_AB, A at distance r + l from
C1 and r + l - 550 = r - 150 from C2, the cosine law in triangle A C2 B2 (angle 65 deg at C2):
    r^2 = l^2 + (r - 150)^2 - 2 l (r - 150) cos 65
    =>  r = (l^2 + 150^2 + 300 l cos 65) / (300 + 2 l cos 65)
          = (182500 + 120000 cos 65) / (300 + 800 cos 65)
In the `kin` preset's frame (A = (0, 0), track y = 0, C at x = s3 > 0): closed at crank angle
0 (s3 = r + l, door angle theta2 = 0); open at B2 = (r - 150 + l cos 115, l sin 115),
crank angle atan2(B2), s3 = r - 150, theta2 = -65 deg.  On the way, sin(-theta2) = r sin(th)/l
grows with th (th < 90 deg), so the door turns monotonically and the transmission angle
gamma = 90 - |theta2| is least at the open position: 25 deg.  `door_sweep` checks this on a
grid with the closed-form slider-crank  s3 = r cos th + sqrt(l^2 - r^2 sin^2 th).
`door_readings` tries the four designs with the closed door along the track (a turn of 65 or
115 deg, C moving towards or away from B1): only this one (65 deg, towards B1) moves from
closed to open without taking the slider to its other assembly branch.

习题 6-1 (carrier mechanism, 搬运器; OCR line ~6619)
---------------------------------------------------
l_AB = l_ED = 100, l_BC = l_CD = l_EF = 200 mm, m5 = 20 kg, F5 = 1 kN at the position
phi1 = phi2 = phi3 = 90 deg.  Reading: crank AB (1) about A, coupler BC (2), rocker C-D-E (3)
about D, rod EF (4), slider 5 at F on a guide of the frame; phi1 = angle ABC, phi2 = angle BCD,
phi3 = angle DEF, and the guide along EF in that position.  Layout (mm; the position at crank
angle 0): A = (0, 0), B = (100, 0), C = (100, 200), D = (-100, 200), the rocker a straight
lever (E = D - 100 e3, opposite C), E = (-200, 200), F = (-200, 0), guide x = -200 (vertical).
AD = sqrt(100^2 + 200^2) = 223.6 mm: 100 + 223.6 < 200 + 200, a crank-rocker (AB turns).
Kinematics with th the crank angle:
    B = r e(th),  B' = r n(th),  B'' = -B            (e = (cos, sin), n = e rotated +90 deg)
    C: circle intersection, to the right of B -> D;  e2 = (C - B)/l2,  e3 = (C - D)/l3
    l2 phi2' n2 - l3 phi3' n3 = -B'                                              (2x2)
    l2 phi2'' n2 - l3 phi3'' n3 = -B'' + l2 phi2'^2 e2 - l3 phi3'^2 e3           (2x2)
    E = D - l_DE e3,  E' = -l_DE phi3' n3,  E'' = -l_DE (phi3'' n3 - phi3'^2 e3)
    F = E + l4 e4 with F_x = x_g:  cos phi4 = (x_g - E_x)/l4,  sin phi4 < 0 (F below E)
    phi4' = E_x' / (l4 sin phi4),   F_y' = E_y' + l4 cos phi4 phi4'
    phi4'' = (E_x'' - l4 cos phi4 phi4'^2) / (l4 sin phi4)
    F_y'' = E_y'' + l4 (cos phi4 phi4'' - sin phi4 phi4'^2)
    Je = m5 (F_y')^2 (eq. 6-4, the slider only),  dJe/dth = 2 m5 F_y' F_y'',
    Me = F5 . F' (eq. 6-2) with F5 = (0, +1000) N, against the slider's velocity there.
By hand at th = 0: omega2 = 0 (vB and vC both along BC), omega3 = omega1 l_AB / l_CD, vF = vE =
omega3 l_DE = omega1 l_AB l_DE / l_CD = 0.05 m * omega1, so Je = 20 * 0.05^2 = 0.05 kg m^2 and
Me = -1000 * 0.05 = -50 N m (|Mer| = 50 N m); alpha3 = 0 there (the y-row of the acceleration
loop), so aF = 0 and dJe/dth = 0.

Run:  python3 tests/reference/independent_exercises_ch3_ch6.py   (prints the three result sets)
"""
from __future__ import annotations

import math

import numpy as np

DEG = math.pi / 180.0


def _rot90(v):
    return np.array([-v[1], v[0]])


# ---------------------------------------------------------------- 习题 3-5 ----------
POSE1 = (0.5, 0.5, 20.0)
POSE2 = (1.5, 1.8, 38.0)
B_LOCAL = (0.0, 0.0)         # B at P
C_LOCAL = (1.0, 0.0)         # C one unit along the reference line


def _place(pose, local):
    x, y, th = pose
    c, s = math.cos(th * DEG), math.sin(th * DEG)
    return np.array([x + c * local[0] - s * local[1], y + s * local[0] + c * local[1]])


def clamp_design():
    """The four-bar of 习题 3-5 (see the module docstring): pivots, lengths, angles."""
    B1, B2 = _place(POSE1, B_LOCAL), _place(POSE2, B_LOCAL)
    C1, C2 = _place(POSE1, C_LOCAL), _place(POSE2, C_LOCAL)
    u2 = (C2 - B2) / np.linalg.norm(C2 - B2)
    dB, mB = B2 - B1, (B1 + B2) / 2
    t = -float((B2 - mB) @ dB) / float(u2 @ dB)
    A = B2 + t * u2
    mC = (C1 + C2) / 2
    y = mC[1] - (C2[0] - mC[0]) * (C2[0] - C1[0]) / (C2[1] - C1[1])
    D = np.array([C2[0], y])
    l1, l2 = float(np.linalg.norm(B1 - A)), float(np.linalg.norm(C1 - B1))
    l3, l4 = float(np.linalg.norm(C1 - D)), float(np.linalg.norm(D - A))
    return {"A": A, "D": D, "B1": B1, "B2": B2, "C1": C1, "C2": C2, "t": t,
            "l1": l1, "l2": l2, "l3": l3, "l4": l4}


def grashof_type(l1, l2, l3, l4):
    """Crank AB (1), coupler (2), rocker (3), frame (4): the type by eqs. 3-1, 3-2."""
    L = [l1, l2, l3, l4]
    s, lg = min(L), max(L)
    if s + lg > sum(L) - s - lg:
        return "double_rocker"
    k = L.index(s)
    return {0: "crank_rocker", 2: "crank_rocker", 3: "double_crank", 1: "double_rocker"}[k]


def clamp_motion(n=200001):
    """Turn CD about D from pose 1 to pose 2, both ways round; per direction the smallest
    relative margin of |AC| inside (|l1 - l2|, l1 + l2) before pose 2, and the relative
    gap at pose 2 itself (0: the dead point)."""
    d = clamp_design()
    A, D, C1, C2 = d["A"], d["D"], d["C1"], d["C2"]
    lo, hi = abs(d["l1"] - d["l2"]), d["l1"] + d["l2"]
    f1 = math.atan2(*(C1 - D)[::-1])
    f2 = math.atan2(*(C2 - D)[::-1])
    out = {}
    for sign in (1, -1):
        sweep = (sign * (f2 - f1)) % (2 * math.pi)
        f = f1 + sign * np.linspace(0.0, sweep, n)
        C = D[:, None] + d["l3"] * np.array([np.cos(f), np.sin(f)])
        r = np.hypot(C[0] - A[0], C[1] - A[1])
        margin = np.minimum(r - lo, hi - r) / hi
        out[sign] = (float(np.degrees(sweep)), float(margin[:-1].min()), float(margin[-1]))
    return out


def exercise_3_5():
    d = clamp_design()
    th = [math.degrees(math.atan2(*(d[k] - d["A"])[::-1])) for k in ("B1", "B2")]
    return {"A": [float(v) for v in d["A"]], "D": [float(v) for v in d["D"]],
            "l1": d["l1"], "l2": d["l2"], "l3": d["l3"], "l4": d["l4"],
            "theta1_deg": th, "type": grashof_type(d["l1"], d["l2"], d["l3"], d["l4"])}


# ---------------------------------------------------------------- 习题 3-8 ----------
DOOR = 400.0          # l_BC
TRAVEL = 550.0        # C1C2
TURN = 65.0           # the door's turn: 180 - alpha, alpha = 115 deg


def door_crank():
    c = math.cos(TURN * DEG)
    return (DOOR ** 2 + (TRAVEL - DOOR) ** 2 + 2 * DOOR * (TRAVEL - DOOR) * c) \
        / (2 * (TRAVEL - DOOR) + 2 * DOOR * c)


def door_open_angle():
    """Crank angle of the open position in the kin preset's frame [deg]."""
    r = door_crank()
    xB = r + DOOR - TRAVEL + DOOR * math.cos((180.0 - TURN) * DEG)
    yB = DOOR * math.sin((180.0 - TURN) * DEG)
    return math.degrees(math.atan2(yB, xB))


def door_sweep(n=20001):
    """The centred slider-crank (r, l) from crank angle 0 to the open position: the
    slide s3, the door angle theta2 (B -> C) and gamma = 90 - |theta2|."""
    r, l = door_crank(), DOOR
    th = np.linspace(0.0, door_open_angle() * DEG, n)
    s3 = r * np.cos(th) + np.sqrt(l * l - (r * np.sin(th)) ** 2)
    theta2 = np.degrees(np.arctan2(-r * np.sin(th), s3 - r * np.cos(th)))
    return th, s3, theta2, 90.0 - np.abs(theta2)


def door_readings(n=20001):
    """The four designs with the closed door along the track and A on it: the door turning
    65 or 115 deg (sign +1: B rises) with C moving towards or away from B1.  For each: l_AB
    and whether the crank carries the door from closed to open on one assembly branch of
    the slider (|y_B| < l on the way and the door never square to the track)."""
    out = {}
    l = DOOR
    for turn in (65.0, 115.0):
        for way, b1 in (("towards", l), ("away", -l)):
            C2 = np.array([TRAVEL, 0.0])
            B1 = np.array([b1, 0.0])
            psi2 = math.atan2(0.0, b1) + (turn * DEG if b1 > 0 else -turn * DEG)
            B2 = C2 + l * np.array([math.cos(psi2), math.sin(psi2)])
            xA = (B2 @ B2 - b1 * b1) / (2 * (B2[0] - b1))      # A = (xA, 0), |AB1| = |AB2|
            A = np.array([xA, 0.0])
            r = abs(xA - b1)
            q1 = math.atan2(*(B1 - A)[::-1])
            q2 = math.atan2(*(B2 - A)[::-1])
            moves = False
            for sign in (1, -1):
                q = q1 + sign * np.linspace(0.0, (sign * (q2 - q1)) % (2 * math.pi), n)
                yB = r * np.sin(q)
                if np.any(np.abs(yB[1:-1]) >= l):
                    continue
                # the door's direction C -> B keeps the sign of its x-part (never square)
                cx = math.copysign(1.0, b1)
                xC = A[0] + r * np.cos(q) - cx * np.sqrt(l * l - yB ** 2)
                if abs(xC[-1] - TRAVEL) < 1e-6 * l:
                    moves = True
            out[(turn, way)] = (r, moves)
    return out


def exercise_3_8():
    r = door_crank()
    th, s3, theta2, gamma = door_sweep()
    assert np.all(np.diff(s3) < 0) and np.all(np.diff(theta2) < 0)   # monotonic
    # the open position from the closed forms, not the grid
    s_open = r + DOOR - TRAVEL
    B2 = np.array([s_open + DOOR * math.cos((180 - TURN) * DEG),
                   DOOR * math.sin((180 - TURN) * DEG)])
    assert abs(np.hypot(*B2) - r) < 1e-9 * r                        # B2 is on the crank circle
    return {"l_AB": r, "open_deg": door_open_angle(),
            "s3_max_mm": r + DOOR, "s3_max_at_deg": 0.0,
            "s3_min_mm": s_open, "s3_min_at_deg": door_open_angle(),
            "s3_stroke_mm": TRAVEL,
            "theta2_max_deg": 0.0, "theta2_min_deg": -TURN,
            "theta2_min_at_deg": door_open_angle(), "theta2_swing_deg": TURN,
            "gamma_min_deg": 90.0 - TURN, "gamma_min_grid_deg": float(gamma.min())}


# ---------------------------------------------------------------- 习题 6-1 ----------
L_AB, L_BC, L_CD, L_DE, L_EF = 100.0, 200.0, 200.0, 100.0, 200.0     # mm
A6 = np.array([0.0, 0.0])
D6 = np.array([-100.0, 200.0])
X_GUIDE = -200.0
M5 = 20.0            # kg
F5 = np.array([0.0, 1000.0])      # N, against the slider's velocity at th = 0


def carrier(th):
    """Positions and th-derivatives (first and second) of 习题 6-1's six-bar [mm, rad]."""
    e1 = np.array([math.cos(th), math.sin(th)])
    B = A6 + L_AB * e1
    dB, ddB = L_AB * _rot90(e1), -L_AB * e1
    # C: circle (B, l2) meets circle (D, l3), to the right of B -> D
    w = D6 - B
    dist = float(np.hypot(*w))
    a = (L_BC ** 2 - L_CD ** 2 + dist ** 2) / (2 * dist)
    h = math.sqrt(L_BC ** 2 - a * a)
    C = B + a * w / dist - h * _rot90(w) / dist
    e2, e3 = (C - B) / L_BC, (C - D6) / L_CD
    n2, n3 = _rot90(e2), _rot90(e3)
    M = np.column_stack([L_BC * n2, -L_CD * n3])
    p2, p3 = np.linalg.solve(M, -dB)
    q2, q3 = np.linalg.solve(M, -ddB + L_BC * p2 ** 2 * e2 - L_CD * p3 ** 2 * e3)
    E = D6 - L_DE * e3
    dE = -L_DE * p3 * n3
    ddE = -L_DE * (q3 * n3 - p3 ** 2 * e3)
    c4 = (X_GUIDE - E[0]) / L_EF
    s4 = -math.sqrt(1.0 - c4 * c4)                 # F below E
    F = E + L_EF * np.array([c4, s4])
    p4 = dE[0] / (L_EF * s4)
    dF = np.array([0.0, dE[1] + L_EF * c4 * p4])
    q4 = (ddE[0] - L_EF * c4 * p4 ** 2) / (L_EF * s4)
    ddF = np.array([0.0, ddE[1] + L_EF * (c4 * q4 - s4 * p4 ** 2)])
    return {"B": B, "C": C, "E": E, "F": F, "dB": dB, "dC": dB + L_BC * p2 * n2,
            "dE": dE, "dF": dF, "ddF": ddF, "omega2": p2, "omega3": p3, "alpha3": q3}


def equivalent(th):
    """Je [kg m^2], dJe/dth [kg m^2/rad], Me [N m] of 习题 6-1 at crank angle th."""
    k = carrier(th)
    vF, aF = k["dF"] / 1000.0, k["ddF"] / 1000.0    # m per rad of crank
    return (M5 * float(vF @ vF), 2 * M5 * float(vF @ aF), float(F5 @ vF))


def fd_check(h=1e-3):
    """Largest gap between the hand derivatives and an 8th-order central difference of the
    positions (and of F_y'), at a few crank angles; relative to the quantity's scale."""
    w = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    worst = {}
    for th in (0.0, 0.4, 1.3, 2.6, 4.0, 5.5):
        ks = [carrier(th + j * h) for j in range(-4, 5)]
        k0 = carrier(th)
        for key, dkey in (("B", "dB"), ("C", "dC"), ("E", "dE"), ("F", "dF")):
            fd = sum(wj * kj[key] for wj, kj in zip(w, ks)) / h
            worst[dkey] = max(worst.get(dkey, 0.0), float(np.max(np.abs(fd - k0[dkey]))) / 100)
        fd = sum(wj * kj["dF"] for wj, kj in zip(w, ks)) / h
        worst["ddF"] = max(worst.get("ddF", 0.0), float(np.max(np.abs(fd - k0["ddF"]))) / 100)
    return worst


def exercise_6_1():
    k = carrier(0.0)
    Je, dJe, Me = equivalent(0.0)
    # the reading's position: the three right angles, the guide along EF, E on the guide
    ab, bc, cd = k["B"] - A6, k["C"] - k["B"], D6 - k["C"]
    de, ef = k["E"] - D6, k["F"] - k["E"]
    assert abs(float(ab @ bc)) < 1e-9 and abs(float(bc @ cd)) < 1e-9
    assert abs(float(de @ ef)) < 1e-9 and abs(ef[0]) < 1e-9
    return {"Je_min_kg_m2": Je, "Je_max_kg_m2": Je, "dJe_min_kg_m2_rad": dJe,
            "dJe_max_kg_m2_rad": dJe, "Me_min_N_m": Me, "Me_max_N_m": Me,
            "omega2_per_omega1": k["omega2"], "omega3_per_omega1": k["omega3"],
            "alpha3_per_omega1_sq": k["alpha3"]}


def reference():
    return {"3-5": exercise_3_5(), "3-8": exercise_3_8(), "6-1": exercise_6_1()}


if __name__ == "__main__":
    for name, res in reference().items():
        print(f"习题 {name}")
        for key, val in res.items():
            print(f"  {key} = {val!r}")
    print("3-5 clamp motion (direction: sweep deg, min margin before pose 2, gap at pose 2):",
          clamp_motion())
    print("6-1 finite differences:", fd_check())
