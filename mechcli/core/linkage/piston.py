"""The piston of a reciprocating engine: gas loads and the engine's named forces.

A *piston* is a block sliding on a guide of the frame (an RRP dyad whose guide
link is the frame), pinned to a connecting rod whose other end is the pin of
the crank that drives the linkage (the slider-crank preset, or the same chain
in the general form).  :class:`Piston` holds its geometry in closed form:

* the guide line ``base + s u`` (``u`` the direction of increasing slide s);
* the crank pivot A, crank r, rod l, and ``h`` the distance of A from the line;
* the dead centres: the pin is at |P − A| = l + r at the *head end* (outer dead
  centre, "TDC" / inner dead centre of a horizontal engine: the piston farthest
  from the crank) and at l − r at the *crank end*; the stroke is
  sqrt((l + r)² − h²) − sqrt((l − r)² − h²) (2r without offset);
* ``d`` the unit vector of the line of stroke pointing from the head end
  toward the crank.

:class:`PressureCurve` is a pressure [Pa] as a function of the crank angle, of
the piston's displacement from the head end, or an indicator diagram (one
pressure curve against displacement per stroke, 2 or 4 strokes per cycle).
:class:`GasLoad` is the force ``p_head · A − p_crank · (A − A_rod)`` along
``d`` [N] (positive toward the crank), a ``source`` of a
:class:`~mechcli.core.linkage.loads.LoadProgram`.

:func:`engine_series` derives the named results of the textbooks from a
kinetostatic solution (see its docstring); with a massless rod they equal the
closed forms F_Q = F_P / cos φ, F_N = F_P tan φ, F_T = F_Q sin(θ + φ),
T = F_T r.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Dict, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    pass

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import LinkageMotion
    from mechcli.core.linkage.force_model import Topology


class PistonError(ValueError):
    """The link is not a piston of a crank-driven chain, or its crank cannot turn.

    ``lengths``: ``{"rod": l, "crank": r, "offset": h}`` [m] when the crank cannot make a
    whole turn (the spec words the message in its own units), else None."""

    def __init__(self, message: str, lengths: Optional[Dict[str, float]] = None) -> None:
        super().__init__(message)
        self.lengths = lengths


@record
class Piston:
    """Geometry of a piston (see the module notes); lengths [m], angles [rad].

    ``moment_arm``: the arm of the approximate model's T and FT, ``"exact"`` (the
    rod's force on the crank pin) or ``"series"`` (r (sin θ + sin 2θ / 2n), handed on
    by :func:`~mechcli.core.linkage.approximate.force_model`); the exact model and
    the kinetostatics never read it."""

    link: int
    pin: str
    rod: int
    crank: int
    crank_pin: str
    pivot: Tuple[float, float]
    r: float
    l: float
    h: float
    u: Tuple[float, float]
    base: Tuple[float, float]
    slide: str
    branch: int
    s_head: float
    s_crank: float
    theta_head: float
    theta_crank: float
    moment_arm: str = "exact"

    @property
    def stroke(self):
        return abs(self.s_crank - self.s_head)

    @property
    def d(self):
        """Unit vector of the line of stroke, from the head end toward the crank."""
        sgn = 1.0 if self.s_crank > self.s_head else -1.0
        return (sgn * self.u[0], sgn * self.u[1])

    @property
    def out_stroke(self):
        """Crank angle [rad] turned from the head-end dead centre to the crank end
        (in increasing input angle; π without offset)."""
        return (self.theta_crank - self.theta_head) % (2 * math.pi)

    def crank_angles(self, frac: FloatOrArray, lo: FloatOrArray, hi: FloatOrArray):
        """The input angles in [lo, hi] [rad] where the piston is the fraction ``frac`` of
        the stroke from the head end (closed form: the crank pin on the circle of radius l
        about the piston pin; two per turn, one on each stroke)."""
        sgn = 1.0 if self.s_crank > self.s_head else -1.0
        s = self.s_head + sgn * frac * self.stroke
        px, py = self.base[0] + s * self.u[0], self.base[1] + s * self.u[1]
        wx, wy = px - self.pivot[0], py - self.pivot[1]
        d = math.hypot(wx, wy)
        c = (self.r ** 2 + d * d - self.l ** 2) / (2 * self.r * d)
        if not -1.0 - 1e-9 <= c <= 1.0 + 1e-9:
            return []
        c = min(1.0, max(-1.0, c))      # a dead centre: one angle
        psi, half = math.atan2(wy, wx), math.acos(c)
        out = []
        for th in (psi - half, psi + half):
            if abs(self.fraction_at(th) - frac) > 1e-9:   # the other branch's position
                continue
            k = math.ceil((lo - th) / (2 * math.pi))
            while th + 2 * math.pi * k <= hi:
                out.append(th + 2 * math.pi * k)
                k += 1
        return out

    def fraction_at(self, theta: FloatOrArray):
        """The piston's fraction of the stroke from the head end at input angle ``theta``
        [rad] (closed form, scalar)."""
        bx = self.pivot[0] + self.r * math.cos(theta) - self.base[0]
        by = self.pivot[1] + self.r * math.sin(theta) - self.base[1]
        along = bx * self.u[0] + by * self.u[1]
        normal = -bx * self.u[1] + by * self.u[0]
        s = along + self.branch * math.sqrt(max(self.l ** 2 - normal ** 2, 0.0))
        return float(self.displacement(s) / self.stroke)

    def displacement(self, s: FloatOrArray):
        """Distance of the pin from the head-end dead centre [m] (0 … stroke)."""
        sgn = 1.0 if self.s_crank > self.s_head else -1.0
        return sgn * (np.asarray(s, dtype=float) - self.s_head)

    @classmethod
    def of(cls, linkage, link):
        """The piston ``link`` of ``linkage`` (closed form; raises :class:`PistonError`)."""
        frame = linkage.frame
        dyads = [el for el in linkage.elements if el.kind == "RRP" and el.slider == link]
        if not dyads or dyads[0].guide_link != frame:
            raise PistonError(f"link {link} is not a block sliding on a guide of the frame "
                              "(the slider of an RRP dyad whose guide is the frame)")
        dy = dyads[0]
        if len(linkage.drivers) != 1 or not linkage.drivers[0].rotary:
            raise PistonError("a piston needs a linkage driven by one crank")
        crank = linkage.drivers[0]
        if crank.point != dy.point:
            raise PistonError(f"the rod of piston {link} (link {dy.link}) is not pinned to "
                              f"the crank pin {crank.point}")
        grounds = {el.name: (float(el.x), float(el.y)) for el in linkage.elements
                   if el.kind == "ground"}
        if crank.pivot not in grounds or dy.guide_point not in grounds:
            raise PistonError("a piston needs the crank pivot and the guide on ground points")
        ax, ay = grounds[crank.pivot]
        gx, gy = grounds[dy.guide_point]
        ux, uy = math.cos(float(dy.guide_angle)), math.sin(float(dy.guide_angle))
        e = float(dy.offset)
        bx, by = gx - e * uy, gy + e * ux
        wx, wy = ax - bx, ay - by
        s0 = wx * ux + wy * uy                   # A projected on the guide line
        h = abs(-wx * uy + wy * ux)              # A's distance from the line
        r, rod = float(crank.length), float(dy.length)
        if rod - r < h * (1 + 1e-12) or rod <= r:
            raise PistonError(f"the crank of piston {link} cannot make a whole turn (rod "
                              f"{rod:g} ≤ crank {r:g} + offset {h:g}, SI)",
                              {"rod": rod, "crank": r, "offset": h})
        b = 1.0 if dy.branch >= 0 else -1.0
        s_head = s0 + b * math.sqrt((rod + r) ** 2 - h * h)
        s_crank = s0 + b * math.sqrt((rod - r) ** 2 - h * h)
        ph = (bx + s_head * ux - ax, by + s_head * uy - ay)
        pc = (bx + s_crank * ux - ax, by + s_crank * uy - ay)
        th_head = math.atan2(ph[1], ph[0]) % (2 * math.pi)
        th_crank = math.atan2(-pc[1], -pc[0]) % (2 * math.pi)
        slide = dy.slide_names(frame)[0]
        return cls(link, dy.joint, dy.link, crank.link, crank.point, (ax, ay), r, rod, h,
                   (ux, uy), (bx, by), slide, int(b), s_head, s_crank, th_head, th_crank)


@record
class PressureCurve:
    """A pressure [Pa] over the cycle.

    ``kind``: ``"constant"`` (``value``); ``"angle"`` (``xs`` input angles [rad],
    ``ys``; periodic with ``period`` [rad] when given, else clamped at the ends);
    ``"stroke"`` (``xs`` displacements from the head end as fractions of the
    stroke, 0 … 1, ``ys``); ``"indicator"`` (``xs`` fractions, ``ys`` of shape
    (k, len(xs)): the pressure on each of k = 2 or 4 strokes of the cycle, the
    first beginning at the head-end dead centre, numbered in the direction of
    rotation: ``direction`` +1 in increasing input angle (ω1 ≥ 0), −1 in
    decreasing input angle (a crank turning clockwise, ω1 < 0)).
    """

    kind: str
    value: float = 0.0
    xs: Optional[np.ndarray] = None
    ys: Optional[np.ndarray] = None
    period: Optional[float] = None
    direction: int = 1

    @property
    def strokes(self):
        """Strokes per cycle of an indicator diagram (2 or 4), else 0."""
        return int(self.ys.shape[0]) if self.kind == "indicator" else 0

    def breaks(self, piston, lo, hi):
        """The input angles in [lo, hi] [rad] where the pressure has a kink or a jump: the
        table's points (against the angle, with their repeats; against the stroke, where
        the piston reaches them) and, for an indicator diagram, the dead centres."""
        if self.kind == "constant":
            return []
        if self.kind == "angle":
            if self.period is None:
                return [float(x) for x in self.xs if lo <= x <= hi]
            out = []
            for x in self.xs:
                k = math.ceil((lo - x) / self.period)
                while x + k * self.period <= hi:
                    out.append(float(x + k * self.period))
                    k += 1
            return out
        fracs = [float(f) for f in self.xs if 0.0 < f < 1.0]
        if self.kind == "indicator":
            fracs += [0.0, 1.0]
        return [a for f in fracs for a in piston.crank_angles(f, lo, hi)]

    def at(self, q, frac, piston):
        q = np.asarray(q, dtype=float)
        if self.kind == "constant":
            return np.full(np.shape(q), float(self.value))
        if self.kind == "angle":
            if self.period is not None:
                x0 = self.xs[0]
                return np.interp(np.mod(q - x0, self.period) + x0, self.xs, self.ys)
            return np.interp(q, self.xs, self.ys)
        frac = np.clip(frac, 0.0, 1.0)
        if self.kind == "stroke":
            return np.interp(frac, self.xs, self.ys)
        k = self.ys.shape[0]
        # crank angle turned since the head-end dead centre that begins the cycle, in the
        # direction of rotation, and the angle of the stroke out to the crank end
        if self.direction >= 0:
            phase = np.mod(q - piston.theta_head, 2 * math.pi * (k // 2))
            out_stroke = piston.out_stroke
        else:
            phase = np.mod(piston.theta_head - q, 2 * math.pi * (k // 2))
            out_stroke = 2 * math.pi - piston.out_stroke
        turn = np.floor(phase / (2 * math.pi))
        within = phase - 2 * math.pi * turn
        index = np.clip(2 * turn + (within >= out_stroke), 0, k - 1).astype(int)
        out = np.zeros(np.shape(q))
        for i in range(k):
            sel = index == i
            if np.any(sel):
                out = np.where(sel, np.interp(frac, self.xs, self.ys[i]), out)
        return out


@record
class GasLoad:
    """Gas force on a piston: ``head · area − crank · (area − rod_area)`` [N] along
    the piston's ``d`` (toward the crank); ``crank`` may be None."""

    piston: Piston
    head: PressureCurve
    area: float
    crank: Optional[PressureCurve] = None
    rod_area: float = 0.0

    def breaks(self, lo: FloatOrArray, hi: FloatOrArray):
        """The input angles in [lo, hi] [rad] where the force has a kink or a jump
        (:meth:`PressureCurve.breaks` of both sides)."""
        out = self.head.breaks(self.piston, lo, hi)
        if self.crank is not None:
            out += self.crank.breaks(self.piston, lo, hi)
        return out

    def force(self, q: np.ndarray, motion: LinkageMotion):
        s = np.asarray(motion.slides[self.piston.slide].s, dtype=float)
        frac = self.piston.displacement(s) / self.piston.stroke
        q = np.broadcast_to(np.asarray(q, dtype=float), np.shape(s))
        f = self.head.at(q, frac, self.piston) * self.area
        if self.crank is not None:
            f = f - self.crank.at(q, frac, self.piston) * (self.area - self.rod_area)
        return f


#: the named results of :func:`engine_series` (symbol, needs a crank pin force)
ENGINE_SYMBOLS = ("FL", "FI", "FP", "FQ", "FN", "FT", "Frad", "T")


def _pair(topo: Topology, a: FloatOrArray, b: FloatOrArray, point: str):
    """``(pair force, sign)``: the force of ``a`` on ``b`` is ``sign * (fx, fy)``."""
    lo, hi = min(a, b), max(a, b)
    for k, pr in enumerate(topo.pairs):
        if pr.i == lo and pr.j == hi and pr.point == point:
            return k, (1.0 if a == lo else -1.0)
    raise PistonError(f"no pair between links {a} and {b} at {point}")


def engine_series(piston: Any, topo: Topology, fr: Any, motion: LinkageMotion, gas: FloatOrArray,
                  inertia_accel: Optional[FloatOrArray] = None, mass: float = 0.0,
                  arm: Optional[FloatOrArray] = None):
    """The engine's named results over the positions of a kinetostatic solution [N, N m].

    Parameters
    ----------
    piston : Piston
    topo : Topology
    fr : ForceResult
        The kinetostatics at the positions of ``motion``.
    motion : LinkageMotion
        At the real input speed.
    gas : ndarray or float
        The gas force on the piston along ``d`` [N] (Σ of its :class:`GasLoad`).
    inertia_accel : ndarray, optional
        The piston's acceleration along ``u`` used for ``FI`` [m/s²] (the
        approximate model's series); default the engine's exact acceleration.
    mass : float
        The reciprocating mass [kg] (the piston link's).
    arm : ndarray, optional
        The moment arm [m] of the piston effort about the crank pivot at the
        positions (the approximate model's series,
        :func:`~mechcli.core.linkage.approximate.moment_arm`): then T = FP · arm
        and FT = T / r, the books' T ≈ F_P r (sin θ + sin 2θ / 2n); the other
        results are unchanged.  Default: T and FT from the rod's force on the
        crank pin.

    Returns
    -------
    dict
        ``FL`` the gas force toward the crank; ``FI`` = m a·d, the force that
        accelerates the reciprocating mass (the books' inertia force; the
        d'Alembert force is −FI); ``FP`` the piston effort, the force of the
        piston on the rod along d (= FL − FI with a massless rod, no gravity or
        other piston loads); ``FQ`` the force along the rod (compression
        positive); ``FN`` the force of the piston on the cylinder wall along
        the left normal of d; ``FT`` the crank effort, the rod's force on the
        crank pin along the crank's counter-clockwise tangent; ``Frad`` its
        component toward the crank axis; ``T`` = r FT, the rod's turning moment
        on the crank about its pivot (counter-clockwise positive).
    """
    dx, dy = piston.d
    ux, uy = piston.u
    pin = motion.points[piston.pin]
    if inertia_accel is None:
        acc_d = pin.ax * dx + pin.ay * dy
    else:
        acc_d = np.asarray(inertia_accel) * (ux * dx + uy * dy)
    k, sgn = _pair(topo, piston.rod, piston.link, piston.pin)
    pf = fr.pairs[k]
    # force of the piston on the rod
    fpx, fpy = -sgn * pf.fx, -sgn * pf.fy
    b = motion.points[piston.crank_pin]
    ex, ey = b.x - pin.x, b.y - pin.y
    length = np.hypot(ex, ey)
    out = {"FL": np.broadcast_to(np.asarray(gas, dtype=float), np.shape(acc_d)) + 0.0,
           "FI": mass * acc_d,
           "FP": fpx * dx + fpy * dy,
           "FQ": (fpx * ex + fpy * ey) / length}
    kw, sw = _pair(topo, piston.link, topo.linkage.frame, piston.pin)
    pw = fr.pairs[kw]
    out["FN"] = sw * (-pw.fx * dy + pw.fy * dx)
    kc, sc = _pair(topo, piston.rod, piston.crank, piston.crank_pin)
    pc = fr.pairs[kc]
    fcx, fcy = sc * pc.fx, sc * pc.fy
    rx, ry = b.x - piston.pivot[0], b.y - piston.pivot[1]
    out["FT"] = (-ry * fcx + rx * fcy) / piston.r
    out["Frad"] = -(rx * fcx + ry * fcy) / piston.r
    out["T"] = rx * fcy - ry * fcx
    if arm is not None:
        out["T"] = out["FP"] * np.asarray(arm, dtype=float)
        out["FT"] = out["T"] / piston.r
    return out


def gas_force(piston: Any, programs: Sequence[Any], q: np.ndarray, motion: LinkageMotion):
    """Σ of the gas loads on ``piston`` along its ``d`` [N] at inputs ``q``."""
    dx, dy = piston.d
    total = np.zeros(np.shape(motion.feasible))
    for p in programs:
        if isinstance(p.source, GasLoad) and p.load.link == piston.link:
            ld, _on = p.evaluate(q, motion)
            total = total + ld.fx * dx + ld.fy * dy
    return total


#: the absolute round-off of a kinetostatic result, in units of EPS times the largest
#: magnitude among the results of the sweep (the solve cancels terms of that size)
NOISE = 32.0
EPS = float(np.finfo(float).eps)


def noise_level(series: Dict[str, np.ndarray]):
    """The round-off of the results in ``series`` (symbol -> array) [N or N m]:
    :data:`NOISE` · EPS · their largest magnitude (forces and moments together)."""
    peak = max((float(np.max(np.abs(v))) for v in series.values() if np.size(v)), default=0.0)
    return NOISE * EPS * peak


def is_constant(values: Dict[str, np.ndarray], noise: FloatOrArray):
    """True when ``values`` vary by no more than the round-off ``noise`` (×100): an
    extreme of such a quantity has no location."""
    v = np.asarray(values, dtype=float)
    return v.size == 0 or float(np.max(v) - np.min(v)) <= 100.0 * noise


def located_within(q: np.ndarray, values: Dict[str, np.ndarray], at: FloatOrArray,
                   tol: FloatOrArray, noise: FloatOrArray, periodic: bool = False):
    """How closely a refined extreme's input ``at`` is known [rad or m].

    The search compares values, so near a smooth extreme it cannot tell apart inputs
    whose values differ by less than their round-off ``noise``: the location is known to
    about δ = sqrt(2 · noise / |f''|), f'' from the second difference of the samples
    ``values`` at ``q`` nearest ``at`` (uniform step; ``periodic``: a whole turn, the
    last sample the first).  Returns max(``tol``, δ), at most the two steps around the
    sample (where f'' vanishes to the samples' precision)."""
    q = np.asarray(q, dtype=float)
    f = np.asarray(values, dtype=float)
    n = q.size
    if n < 3:
        return float(tol)
    k = int(np.argmin(np.abs(q - at)))
    if 0 < k < n - 1:
        a, b = k - 1, k + 1
    elif periodic and n > 3:
        a, b = n - 2, 1          # the first and last samples are the same position
    else:
        k = 1 if k == 0 else n - 2
        a, b = k - 1, k + 1
    h = float(np.max(np.diff(q)))
    cap = 2.0 * h
    curv = abs(f[a] - 2.0 * f[k] + f[b]) / (h * h)
    if curv <= 0.0 or not np.isfinite(curv):
        return float(max(tol, cap))
    return float(min(max(tol, np.sqrt(2.0 * noise / curv)), max(cap, tol)))


@record
class EngineSweep:
    """The named engine results over a force sweep: ``series`` symbol -> array at
    the sweep's positions; ``extremes`` symbol -> ((max, at, tol), (min, at, tol))
    [N or N m, rad], refined by golden-section search between the neighbours of
    the best sample, ``tol`` from :func:`located_within`; ``at`` and ``tol`` are
    None for a quantity constant to round-off (:func:`is_constant`: FL of constant
    pressures, FI without a mass)."""

    series: dict
    extremes: dict


def engine_at(piston: Any, topo: Topology, evaluator: Any, q: Any, mass: Any,
              approx: Any = None):
    """``(series of the kinetostatics, engine series)`` at inputs ``q`` through a
    :class:`~mechcli.core.linkage.force_analysis.ForceEvaluator`; ``approx`` (the
    approximate model's :class:`~mechcli.core.linkage.approximate.SeriesInertia`)
    gives FI's acceleration and, when it asks for it, T's moment arm."""
    fr, _masks, motion = evaluator(np.asarray(q, dtype=float))
    acc = None if approx is None else approx.acceleration(q)
    arm = None if approx is None else approx.arm(q)
    gas = gas_force(piston, evaluator.programs, q, motion)
    return fr, engine_series(piston, topo, fr, motion, gas, acc, mass, arm)


def analyse_engine(piston, topo, evaluator, q, fr,
                   motion, mass, approx=None,
                   periodic=False, iterations=48):
    """:class:`EngineSweep` over the analysed positions ``q`` (with their
    kinetostatics ``fr`` and ``motion``)."""
    acc = None if approx is None else approx.acceleration(q)
    arm = None if approx is None else approx.arm(q)
    gas = gas_force(piston, evaluator.programs, q, motion)
    series = engine_series(piston, topo, fr, motion, gas, acc, mass, arm)
    extremes = {}
    if q.size == 0:
        return EngineSweep(series, extremes)
    targets, lo, hi = [], [], []
    step = q[1] - q[0] if q.size > 1 else 0.0
    for sym, v in series.items():
        for sign in (1.0, -1.0):
            k = int(np.argmax(sign * v))
            a = q[k - 1] if k > 0 else (q[k] - step if periodic else q[k])
            b = q[k + 1] if k < q.size - 1 else (q[k] + step if periodic else q[k])
            targets.append((sym, sign, k))
            lo.append(a)
            hi.append(b)
    from mechcli.core.numerics import golden_section_max
    signs = np.array([t[1] for t in targets])

    def values(x: Any):
        _fr, ser = engine_at(piston, topo, evaluator, x, mass, approx)
        return np.array([ser[t[0]][i] for i, t in enumerate(targets)]) * signs

    xb, fb = golden_section_max(values, np.array(lo), np.array(hi), iterations)
    noise = noise_level(series)
    best = {}
    for i, (sym, sign, k) in enumerate(targets):
        grid = (float(series[sym][k]) * sign, float(q[k]))
        val, at = max(grid, (float(fb[i]), float(xb[i])))
        if is_constant(series[sym], noise):
            best[(sym, sign)] = (val * sign + 0.0, None, None)
            continue
        # the refined input is good to what the round-off of the compared values allows
        # at the curvature there; a grid sample that ties or beats it (by round-off, at
        # an extreme on the grid) to that plus its distance, at most half the bracket
        xr = float(xb[i])
        tol = located_within(q, series[sym], xr, 1.5e-8 * max(1.0, abs(xr)), noise, periodic)
        if at != xr:
            tol = min(0.5 * float(hi[i] - lo[i]), abs(at - xr) + tol)
        best[(sym, sign)] = (val * sign + 0.0, at, tol)
    for sym in series:
        extremes[sym] = (best[(sym, 1.0)], best[(sym, -1.0)])
    return EngineSweep(series, extremes)
