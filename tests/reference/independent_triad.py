#!/usr/bin/env python3
"""Independent kinematics of the class-III six-bar of configs/ch1/class3-sixbar.toml.

Deliberately self-contained: imports nothing from mechcli (numpy and scipy only), and
solves the mechanism another way than mechcli's triad element: the six unknowns are
the coordinates of the joints C, E, F (not the ternary link's pose), the six equations
the squared distances of the six pairs of joints on one link, solved by MINPACK's hybrd
(``scipy.optimize.root``) with its own continuation in 1° steps of the crank from the
drawing.  Velocities: the equations differentiated, one 6×6 linear solve per position.

Model
-----
A = (0, 0) the crank's pivot, B = r (cos θ1, sin θ1); the frame pivots G, H; the ternary
link 3 carries C, E, F; link 2 = BC, link 4 = GE, link 5 = HF.  With P = (C, E, F):

    f_ij(P) = |P_i − P_j|² − l_ij² = 0    for BC, CE, EF, CF, GE, HF
    J(P) dP/dt = −∂f/∂t                    (only B moves among the known points)

θ3 is the direction C → E, θ4 the direction G → E, θ5 the direction H → F (the
config lists each link's joints in that order).  The extremes of θ4 and θ5 are the
zeros of ω4, ω5 (brentq between grid samples of opposite sign; ω from the linear
system), located to 1e-13 rad of crank angle.

Run: ``python3 tests/reference/independent_triad.py`` prints the extremes.
"""

import math

import numpy as np
from scipy.optimize import brentq, root

#: the drawing [mm] (configs/ch1/class3-sixbar.toml), the crank at the drawn B
DRAWING = {"A": (0.0, 0.0), "B": (-19.35, -1.44), "C": (81.65, 53.48), "E": (117.78, 50.71),
           "F": (102.9, 93.53), "G": (188.83, 22.69), "H": (80.08, 150.21)}
PAIRS = (("B", "C"), ("C", "E"), ("E", "F"), ("C", "F"), ("G", "E"), ("H", "F"))
UNKNOWN = ("C", "E", "F")
OMEGA1 = 10.0   # rad/s (the config's; the extremes of the angles do not depend on it)


class Triad:
    def __init__(self, drawing=DRAWING):
        self.P = {k: np.array(v, dtype=float) for k, v in drawing.items()}
        self.L = [float(np.linalg.norm(self.P[a] - self.P[b])) for a, b in PAIRS]
        self.r = float(np.linalg.norm(self.P["B"]))
        self.theta0 = math.atan2(self.P["B"][1], self.P["B"][0])

    def _pos(self, u, th):
        pos = {"B": self.r * np.array([math.cos(th), math.sin(th)]), "G": self.P["G"],
               "H": self.P["H"]}
        for k, name in enumerate(UNKNOWN):
            pos[name] = u[2 * k:2 * k + 2]
        return pos

    def equations(self, u, th):
        pos = self._pos(u, th)
        return np.array([np.dot(pos[a] - pos[b], pos[a] - pos[b]) - l * l
                         for (a, b), l in zip(PAIRS, self.L)])

    def jacobian(self, u, th):
        pos = self._pos(u, th)
        J = np.zeros((6, 6))
        for row, (a, b) in enumerate(PAIRS):
            d = 2.0 * (pos[a] - pos[b])
            if a in UNKNOWN:
                i = 2 * UNKNOWN.index(a)
                J[row, i:i + 2] += d
            if b in UNKNOWN:
                i = 2 * UNKNOWN.index(b)
                J[row, i:i + 2] -= d
        return J

    def sweep(self, thetas):
        """Positions at increasing crank angles, continued from the drawing."""
        u = np.concatenate([self.P[n] for n in UNKNOWN])
        th = self.theta0
        out = []
        for target in thetas:
            n = max(1, int(math.ceil(abs(target - th) / math.radians(1.0))))
            for t in np.linspace(th, target, n + 1)[1:]:
                sol = root(self.equations, u, args=(t,), jac=self.jacobian, method="hybr",
                           options={"xtol": 1e-14})
                u = sol.x
            th = target
            out.append(u.copy())
        return np.array(out)

    def velocities(self, u, th):
        """dP/dt at the position u: J v = −∂f/∂t, only B moving (vB = ω1 × B)."""
        pos = self._pos(u, th)
        vB = OMEGA1 * np.array([-pos["B"][1], pos["B"][0]])
        rhs = np.zeros(6)
        rhs[0] = -2.0 * np.dot(pos["B"] - pos["C"], vB)
        return np.linalg.solve(self.jacobian(u, th), rhs)

    def angles(self, u, th):
        pos = self._pos(u, th)
        def ang(a, b):
            d = pos[b] - pos[a]
            return math.atan2(d[1], d[0])
        return {"theta3": ang("C", "E"), "theta4": ang("G", "E"), "theta5": ang("H", "F")}

    def omegas(self, u, th):
        pos, v = self._pos(u, th), self.velocities(u, th)
        vel = {n: v[2 * k:2 * k + 2] for k, n in enumerate(UNKNOWN)}
        vel["G"] = vel["H"] = np.zeros(2)
        def w(a, b):
            d, dv = pos[b] - pos[a], vel[b] - vel[a]
            return (d[0] * dv[1] - d[1] * dv[0]) / np.dot(d, d)
        return {"theta3": w("C", "E"), "theta4": w("G", "E"), "theta5": w("H", "F")}


def extremes(step_deg=1.0):
    """``{name: (max_deg, at_deg, min_deg, at_deg)}`` of θ3, θ4, θ5 over a turn of the
    crank (0° … 360°), each located by brentq on ω between grid samples."""
    tri = Triad()
    grid = np.radians(np.arange(0.0, 360.0 + step_deg / 2, step_deg))
    # continue from the drawing (θ1 = 184.25°) down to 0°, then across the turn
    U = tri.sweep(np.concatenate([grid[::-1], grid[1:]]))[len(grid) - 1:]
    W = {k: np.array([tri.omegas(u, t)[k] for u, t in zip(U, grid)]) for k in
         ("theta3", "theta4", "theta5")}
    out = {}
    for k, w in W.items():
        found = []
        for i in np.flatnonzero(np.sign(w[:-1]) != np.sign(w[1:])):
            u_i = U[i]

            def f(t, i=i):
                return tri.omegas(_refine(tri, U[i], grid[i], t), t)[k]

            t = brentq(f, grid[i], grid[i + 1], xtol=1e-14, rtol=1e-15)
            u = _refine(tri, u_i, grid[i], t)
            found.append((math.degrees(tri.angles(u, t)[k]), math.degrees(t)))
        hi = max(found)
        lo = min(found)
        out[k] = (hi[0], hi[1], lo[0], lo[1])
    return out


def _refine(tri, u, th_from, th):
    """The position at θ1 = th continued from the solution u at th_from (a short step)."""
    sol = root(tri.equations, u, args=(th,), jac=tri.jacobian, method="hybr",
               options={"xtol": 1e-14})
    return sol.x


if __name__ == "__main__":
    for k, (hi, at_hi, lo, at_lo) in extremes().items():
        print(f"{k}: max {hi:.7f} deg at {at_hi:.6f} deg, min {lo:.7f} deg at {at_lo:.6f} deg")
