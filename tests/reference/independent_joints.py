#!/usr/bin/env python3
"""Independent kinematics of a linkage given by its joints (any class), for the tests of
mechcli's Newton-solved groups.

Deliberately self-contained: imports nothing from mechcli (numpy and scipy only), reads
the drawing itself from the spec (tomllib), and models the linkage another way than
mechcli's engine: the unknowns are the coordinates of the moving joints (no link poses,
no Assur groups); the equations are the rigid links' distances (a link carrying k
joints: its first joint to every other, its second to the third and on: 2k − 3
distances, a triangulation) and the prismatic pairs' conditions (a block's joint stays
on its guide's line, as drawn; a block carrying two joints keeps its angle to the
guide), solved by MINPACK's hybrd (``scipy.optimize.root``) with its own continuation
from the drawing in 0.25° steps of the primary crank.  Secondary cranks follow as
``ratio q1 + phase`` (the phase the drawing's when not given).  Velocities and
accelerations by central differences of the positions in the crank angle (velocities:
step 1e-5 rad, truncation ~1e-10 of the peak; accelerations: steps 1e-3 and 2e-3 rad
combined by Richardson, ~1e-9), times ω1 (constant).

Run: ``python3 tests/reference/independent_joints.py SPEC.toml`` prints the joints at
every 30° of the spec's sweep.
"""

import math
import sys

import numpy as np
from scipy.optimize import root

try:
    import tomllib
except ImportError:  # pragma: no cover - Python < 3.11
    import tomli as tomllib

STEP = math.radians(0.25)


class JointsLinkage:
    def __init__(self, path):
        with open(path, "rb") as fh:
            spec = tomllib.load(fh)
        unit = {"mm": 1e-3, "m": 1.0, "cm": 1e-2}[spec.get("units", "mm")]
        mech = spec["mechanism"]
        self.frame = mech["frame"]
        self.P0 = {k: np.array(v, dtype=float) * unit for k, v in mech["joints"].items()}
        self.links = {ln["number"]: list(ln["joints"]) for ln in mech["link"]}
        self.drivers = mech["driver"]
        self.omega1 = float(spec["input"].get("omega1", 1.0))
        fixed = set(self.links.get(self.frame, []))
        on = {}
        for n, js in self.links.items():
            for j in js:
                on.setdefault(j, set()).add(n)
        self.sliders = []
        for s in mech.get("slider", []):
            ang = math.radians(s["angle"]) if "angle" in s else math.atan2(
                *(self.P0[s["toward"]] - self.P0[s["through"]])[::-1])
            self.sliders.append((s["block"], s["guide"], s["through"], ang))
        # joints on the frame stay: the frame link's, and a joint on one moving link only
        # (a joint joins two links or more: the other is the frame); crank points move
        # with their crank
        self.crank = {}
        for i, d in enumerate(self.drivers):
            link, pivot = d["link"], d["pivot"]
            point = next(j for j in self.links[link] if j != pivot)
            q0 = math.atan2(*(self.P0[point] - self.P0[pivot])[::-1])
            self.crank[link] = (pivot, point, float(np.linalg.norm(self.P0[point]
                                                                   - self.P0[pivot])), q0)
        q1 = self.crank[self.drivers[0]["link"]][3]
        self.follow = {}
        for d in self.drivers[1:]:
            ratio = float(d.get("ratio", 1.0))
            phase = math.radians(d["phase"]) if "phase" in d else \
                self.crank[d["link"]][3] - ratio * q1
            self.follow[d["link"]] = (ratio, phase)
        self.fixed = {j for j in self.P0 if j in fixed or len(on.get(j, ())) == 1}
        moving_points = {self.crank[k][1] for k in self.crank}
        self.unknown = [j for j in self.P0 if j not in self.fixed and j not in moving_points
                        and j in on]
        self.q0 = q1
        self.eqs = []
        for n, js in self.links.items():
            if n == self.frame or n in self.crank:
                continue
            pairs = [(js[0], j) for j in js[1:]] + [(js[1], j) for j in js[2:]]
            for a, b in pairs:
                self.eqs.append(("dist", a, b, float(np.linalg.norm(self.P0[a] - self.P0[b]))))
        for blk, guide, through, ang in self.sliders:
            pin = next(j for j in self.links[blk])
            self.eqs.append(("line", pin, guide, through, ang))
            if len(self.links[blk]) > 1:
                self.eqs.append(("angle", blk, guide))

    # -- the equations -----------------------------------------------------------------
    def positions(self, u, q):
        pos = {j: self.P0[j] for j in self.fixed}
        for link, (pivot, point, r, q0) in self.crank.items():
            qk = q if link == self.drivers[0]["link"] else \
                self.follow[link][0] * q + self.follow[link][1]
            pos[point] = self.P0[pivot] + r * np.array([math.cos(qk), math.sin(qk)])
        for k, j in enumerate(self.unknown):
            pos[j] = u[2 * k:2 * k + 2]
        return pos

    def _link_angle(self, pos, n):
        if n == self.frame:
            return 0.0
        a, b = self.links[n][:2]
        d = pos[b] - pos[a]
        return math.atan2(d[1], d[0])

    def _line(self, pos, guide, through, ang):
        """A point on the guide's line and its direction, carried by the guide."""
        if guide == self.frame:
            return self.P0[through], ang
        g0 = self.links[guide][0]
        turn = self._link_angle(pos, guide) - self._link_angle(self.P0, guide)
        c, s = math.cos(turn), math.sin(turn)
        r = self.P0[through] - self.P0[g0]
        return pos[g0] + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]]), ang + turn

    def equations(self, u, q):
        pos = self.positions(u, q)
        out = []
        for e in self.eqs:
            if e[0] == "dist":
                d = pos[e[1]] - pos[e[2]]
                out.append(float(np.dot(d, d)) - e[3] ** 2)
            elif e[0] == "line":
                _, pin, guide, through, ang = e
                p, a = self._line(pos, guide, through, ang)
                d = pos[pin] - p
                out.append(-math.sin(a) * d[0] + math.cos(a) * d[1])
            else:
                _, blk, guide = e
                want = self._link_angle(self.P0, blk) - self._link_angle(self.P0, guide)
                got = self._link_angle(pos, blk) - self._link_angle(pos, guide)
                out.append(math.sin(got - want))
        return np.array(out)

    def solve_at(self, q, u):
        sol = root(self.equations, u, args=(q,), method="hybr", options={"xtol": 1e-15})
        if not sol.success and np.max(np.abs(self.equations(sol.x, q))) > 1e-12:
            raise RuntimeError(f"no position at q = {math.degrees(q):.4f}°")
        return sol.x

    def sweep(self, qs):
        """The unknown joints at the crank angles ``qs`` (increasing or decreasing from
        wherever), continued from the drawing in STEP steps."""
        u = np.concatenate([self.P0[j] for j in self.unknown])
        q = self.q0
        out = []
        for target in qs:
            n = max(1, int(math.ceil(abs(target - q) / STEP)))
            for t in np.linspace(q, target, n + 1)[1:]:
                u = self.solve_at(t, u)
            q = target
            out.append(u.copy())
        return np.array(out)

    def motion(self, qs):
        """``{joint: (p, v, a)}`` at the crank angles ``qs``: positions continued from
        the drawing, v and a by central differences in q (times ω1, ω1²)."""
        U = self.sweep(qs)
        out = {j: ([], [], []) for j in self.unknown}
        for q, u in zip(qs, U):
            h1, h2 = 1e-5, 1e-3
            up, um = self.solve_at(q + h1, u), self.solve_at(q - h1, u)
            vp, vm = self.solve_at(q + h2, u), self.solve_at(q - h2, u)
            wp, wm = self.solve_at(q + 2 * h2, u), self.solve_at(q - 2 * h2, u)
            for k, j in enumerate(self.unknown):
                s = slice(2 * k, 2 * k + 2)
                out[j][0].append(u[s])
                out[j][1].append((up[s] - um[s]) / (2 * h1) * self.omega1)
                d1 = (vp[s] - 2 * u[s] + vm[s]) / h2 ** 2
                d2 = (wp[s] - 2 * u[s] + wm[s]) / (2 * h2) ** 2
                out[j][2].append((4 * d1 - d2) / 3 * self.omega1 ** 2)   # Richardson
        return {j: tuple(np.array(x) for x in v) for j, v in out.items()}


    def slides_at(self, u, q):
        """Each slider's slide [m]: its block's first joint along the line of sliding,
        from the ``through`` point (both as the guide carries them)."""
        pos = self.positions(u, q)
        out = []
        for blk, guide, through, ang in self.sliders:
            p, a = self._line(pos, guide, through, ang)
            out.append(float(np.dot(pos[self.links[blk][0]] - p, [math.cos(a), math.sin(a)])))
        return np.array(out)

    def slide_motion(self, qs):
        """``[(s, v, a)]`` per slider (spec order) at the crank angles ``qs``, by the
        same continuation and central differences as :meth:`motion`."""
        U = self.sweep(qs)
        rows = []
        for q, u in zip(qs, U):
            h1, h2 = 1e-5, 1e-3
            f = {d: self.slides_at(self.solve_at(q + d, u), q + d)
                 for d in (h1, -h1, h2, -h2, 2 * h2, -2 * h2)}
            s = self.slides_at(u, q)
            d1 = (f[h2] - 2 * s + f[-h2]) / h2 ** 2
            d2 = (f[2 * h2] - 2 * s + f[-2 * h2]) / (2 * h2) ** 2
            rows.append((s, (f[h1] - f[-h1]) / (2 * h1) * self.omega1,
                         (4 * d1 - d2) / 3 * self.omega1 ** 2))
        return [tuple(np.array([r[i][k] for r in rows]) for i in range(3))
                for k in range(len(self.sliders))]


if __name__ == "__main__":
    lk = JointsLinkage(sys.argv[1])
    qs = np.radians(np.arange(0.0, 361.0, 30.0))
    m = lk.motion(qs)
    for j, (p, _v, _a) in m.items():
        print(j, np.round(p * 1e3, 4).tolist())


def link_angle(lk, u, q, link):
    """The angle of ``link`` (its first joint to its second) at the position u [rad]."""
    return lk._link_angle(lk.positions(u, q), link)


def extremes(lk, link, qs):
    """``(max_deg, at_deg, min_deg, at_deg)`` of ``link``'s angle over the crank angles
    ``qs`` (increasing, reached by continuation from the drawing): the samples' largest
    and smallest, each refined by a bounded scalar search (scipy's ``minimize_scalar``)
    within a sample step either side; angles unwrapped along the sweep."""
    from scipy.optimize import minimize_scalar

    U = lk.sweep(qs)
    ang = np.unwrap([link_angle(lk, u, q, link) for u, q in zip(U, qs)])
    h = qs[1] - qs[0]
    out = []
    for sign, i in ((1.0, int(np.argmax(ang))), (-1.0, int(np.argmin(ang)))):
        turn = ang[i] - link_angle(lk, U[i], qs[i], link)

        def f(q, i=i, sign=sign, turn=turn):
            u = lk.solve_at(q, U[i])
            return -sign * (link_angle(lk, u, q, link) + turn)

        lo, hi = max(qs[0], qs[i] - h), min(qs[-1], qs[i] + h)
        res = minimize_scalar(f, bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-11})
        out += [math.degrees(-sign * res.fun), math.degrees(res.x)]
    return tuple(out)
