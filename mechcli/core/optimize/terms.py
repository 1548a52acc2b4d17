"""Objective and constraint terms computed on the linkage engine, for a whole
population of candidate linkages at once (a batched
:class:`~mechcli.core.linkage.Linkage`, parameters of shape ``(M, 1)``).

Every function returns arrays of shape ``(M,)`` (or ``(M, k)``) and an ``ok``
mask: a candidate that does not assemble where it is asked to move is not
``ok``; its values are finite placeholders (0), never NaN.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.linkage import RRR, Crank, DriverMotion, Ground, solve
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.linkage import Linkage, LinkageMotion
    from mechcli.core.types import Array, BoolArray, FloatOrArray, IntArray

#: an output: a link number (its angle) or a slide name
Output = Union[int, str]

#: measures of a deviation vector (function or path error)
MEASURES = ("sum_squares", "rms", "mean_abs", "max_abs")


def _wrap(a: FloatOrArray) -> FloatOrArray:
    return (a + math.pi) % (2 * math.pi) - math.pi


def measure(dev: Array, kind: str, ok: Optional[BoolArray] = None) -> Array:
    """Reduce deviations (M, N) to one number per candidate by ``kind``."""
    dev = np.asarray(dev, dtype=float)
    if ok is not None:
        dev = np.where(ok, dev, 0.0)
    if kind == "sum_squares":
        return np.sum(dev * dev, axis=-1)
    if kind == "rms":
        return np.sqrt(np.mean(dev * dev, axis=-1))
    if kind == "mean_abs":
        return np.mean(np.abs(dev), axis=-1)
    if kind == "max_abs":
        return np.max(np.abs(dev), axis=-1)
    raise ValueError(f"measure must be one of {MEASURES}, got {kind!r}")


def output_of(motion: LinkageMotion, output: Output) -> Tuple[Any, Any, Any]:
    """(value, rate, acceleration) of an output: a link number (angle) or a
    slide name (``"3"``, ``"E"``)."""
    if isinstance(output, str):
        s = motion.slides[output]
        return s.s, s.v, s.a
    ln = motion.links[output]
    return ln.theta, ln.omega, ln.alpha


@record(frozen=False)
class Population:
    """A batched linkage and its primary driver, with the full-revolution
    sweep computed once and shared by every term that needs it."""

    linkage: object
    driver: int
    samples: int = 360
    followers: dict = dataclasses.field(default_factory=dict)
    _rev: dict = dataclasses.field(default_factory=dict)

    def inputs(self, q: FloatOrArray) -> Dict[int, DriverMotion]:
        """Driver inputs at primary positions q (secondary drivers follow by
        ``{link: (ratio, phase)}``), at unit speed."""
        out = {self.driver: DriverMotion(q, 1.0, 0.0)}
        for link, (ratio, phase) in self.followers.items():
            out[link] = DriverMotion(phase + ratio * np.asarray(q), ratio, 0.0)
        return out

    @property
    def size(self):
        shape = self.linkage.shape
        return shape[0] if shape else 1

    def revolution(self, order: int = 1) -> LinkageMotion:
        """The motion at ``samples`` crank angles k·360°/samples (0° and 180°
        among them), order >= ``order``; results (M, samples)."""
        for o in (order, 1, 2):
            if o in self._rev and o >= order:
                return self._rev[o]
        q = np.linspace(0.0, 2 * math.pi, self.samples, endpoint=False)
        m = solve(self.linkage, self.inputs(q), order=order)
        self._rev[order] = m
        return m

    def at(self, q: Array, order: int = 0) -> LinkageMotion:
        """The motion at input positions ``q`` (M, N) or (N,)."""
        return solve(self.linkage, self.inputs(q), order=order)


def _column(a: FloatOrArray, size: int) -> Array:
    a = np.asarray(a, dtype=float)
    return np.broadcast_to(a.reshape(-1), (size,)) if a.size in (1, size) else a


def input_limit(pop: Population, output: Output, which: str = "min", iterations: int = 12
                ) -> Tuple[Array, BoolArray]:
    """Input angle [rad] where the output is least (``which="min"``) or
    greatest (``"max"``) over a revolution: the book's limit position of a
    rocker (例 7-1's φ0, the crank's right limit, is where the rocker angle is
    least).  Found on the revolution's samples, then by Newton steps on the
    velocity coefficient (dψ/dφ = 0) kept inside the neighbouring samples.

    Returns ``(phi, ok)``, each (M,).
    """
    m = pop.revolution(1)
    val, rate, _ = output_of(m, output)
    val = np.broadcast_to(val, m.feasible.shape)
    ok = np.all(m.regular, axis=-1)
    rel = _wrap(val - val[..., :1]) if not isinstance(output, str) else val - val[..., :1]
    rel = np.where(m.regular, rel, np.inf if which == "min" else -np.inf)
    k = np.argmin(rel, axis=-1) if which == "min" else np.argmax(rel, axis=-1)
    step = 2 * math.pi / pop.samples
    q0 = k * step
    lo, hi = q0 - step, q0 + step
    q = q0.astype(float)
    for _ in range(iterations):
        mm = pop.at(q[:, None], order=2)
        _, w, a = output_of(mm, output)
        w, a = np.asarray(w).reshape(-1), np.asarray(a).reshape(-1)
        good = np.abs(a) > 1e-300
        nq = np.where(good, q - w / np.where(good, a, 1.0), q)
        nq = np.where((nq > lo) & (nq < hi), nq, q)
        if np.all(np.abs(nq - q) <= 1e-15 * np.maximum(1.0, np.abs(q))):
            q = nq
            break
        q = nq
    return np.mod(q, 2 * math.pi), ok


def function_deviation(pop: Population, output: Output, phi0: FloatOrArray, dphi: Array,
                       dpsi: Array, psi0: Optional[FloatOrArray] = None, scale: float = 1.0
                       ) -> Tuple[Array, Array, Array, BoolArray]:
    """Deviation of a function generator at input positions ``phi0 + dphi``:
    ``(psi - psi0) - dpsi`` with ``psi0`` the output at ``phi0`` (when None)
    or given.  Angles in rad (a slide output in m, divided by ``scale``).

    Returns ``(dev (M, N), psi (M, N), q (M, N), ok (M,))``.
    """
    M = pop.size
    phi0 = _column(phi0, M)
    dphi = np.asarray(dphi, dtype=float)
    q = phi0[:, None] + np.concatenate([[0.0], dphi])[None, :]
    m = pop.at(q, order=0)
    val, _, _ = output_of(m, output)
    val = np.broadcast_to(val, q.shape)
    ok = np.all(m.feasible, axis=-1)
    base = val[:, :1] if psi0 is None else _column(psi0, M)[:, None]
    if isinstance(output, str):     # a slide [m]: the deviation over the linkage's size
        dev = (val[:, 1:] - base - np.asarray(dpsi, dtype=float)[None, :]) / scale
    else:
        dev = _wrap(val[:, 1:] - base) - np.asarray(dpsi, dtype=float)[None, :]
    dev = np.where(ok[:, None], dev, 0.0)
    return dev, val[:, 1:], q[:, 1:], ok


def path_deviation(pop: Population, point: str, targets: Array, angles: Optional[Array] = None,
                   theta0: Any = None) -> Tuple[Array, BoolArray]:
    """Distance of a traced point's path to target points [m].

    With ``angles`` (K,) the point is taken at the inputs ``theta0 + angles``
    (prescribed timing, 习题 7-4); without, at the revolution's samples, and
    each target's distance is to the closed polyline through them (the error
    of that polyline against the true curve is O(step²·curvature), measured in
    ``benchmarks/bench_optimize.py``).

    Returns ``(dist (M, K), ok (M,))``.
    """
    T = np.asarray(targets, dtype=float)
    tx, ty = T[:, 0], T[:, 1]
    if angles is not None:
        M = pop.size
        q = _column(theta0, M)[:, None] + np.asarray(angles, dtype=float)[None, :]
        m = pop.at(q, order=0)
        p = m.points[point]
        px, py = np.broadcast_to(p.x, q.shape), np.broadcast_to(p.y, q.shape)
        ok = np.all(m.feasible, axis=-1)
        d = np.hypot(px - tx, py - ty)
        return np.where(ok[:, None], d, 0.0), ok
    m = pop.revolution(0)
    p = m.points[point]
    px, py = np.broadcast_to(p.x, m.feasible.shape), np.broadcast_to(p.y, m.feasible.shape)
    ok = np.all(m.feasible, axis=-1)
    # the nearest sample of each target, then the exact distance to the two segments
    # beside it (on a polyline this dense the nearest segment is one of them: the
    # difference is below the sampling error measured in bench_optimize.py)
    S = px.shape[-1]
    d2 = (px[..., None] - tx) ** 2 + (py[..., None] - ty) ** 2          # (M, S, K)
    j = np.argmin(d2, axis=-2)                                           # (M, K)
    best: Optional[Array] = None
    for a_off, b_off in ((-1, 0), (0, 1)):
        ia, ib = (j + a_off) % S, (j + b_off) % S
        ax, ay = np.take_along_axis(px, ia, -1), np.take_along_axis(py, ia, -1)
        bx, by = np.take_along_axis(px, ib, -1), np.take_along_axis(py, ib, -1)
        ex, ey = bx - ax, by - ay
        den = ex * ex + ey * ey
        t = np.clip(((tx - ax) * ex + (ty - ay) * ey) / np.where(den > 0, den, 1.0), 0.0, 1.0)
        dx, dy = ax + t * ex - tx, ay + t * ey - ty
        dd = dx * dx + dy * dy
        best = dd if best is None else np.minimum(best, dd)
    assert best is not None  # two segments were measured
    d = np.sqrt(best)                                                    # (M, K)
    return np.where(ok[:, None], d, 0.0), ok


def _parabola_extreme(y: Array, k: IntArray, which: str, cyclic: bool = True) -> Array:
    """Vertex of the parabola through samples k-1, k, k+1 of y (M, S): cyclic over a
    revolution; over a range an end sample is its own extreme (no neighbour beyond)."""
    S = y.shape[-1]
    rows = np.arange(y.shape[0])
    if not cyclic:
        end = (k == 0) | (k == S - 1)
        kk = np.clip(k, 1, S - 2) if S >= 3 else k
        v = _parabola_extreme(y, kk, which, True) if S >= 3 else y[rows, k]
        return np.where(end, y[rows, k], v)
    y0, y1, y2 = y[rows, (k - 1) % S], y[rows, k], y[rows, (k + 1) % S]
    den = y0 - 2 * y1 + y2
    shift = np.where(np.abs(den) > 1e-300, (y0 - y2) / (2 * np.where(den != 0, den, 1.0)), 0.0)
    shift = np.clip(shift, -1.0, 1.0)
    v = y1 - 0.25 * (y0 - y2) * shift
    return np.minimum(v, y1) if which == "min" else np.maximum(v, y1)


def joint_angles(m: LinkageMotion, joints: Sequence[str]) -> List[Array]:
    """The angle at each RRR joint (between its two links, 0…π) [rad], (M, S, J)."""
    out = []
    for j in joints:
        c = m.condition(j)
        if c.cos_joint is None:
            raise DescribedError(f"joint {j} is not an RRR dyad's joint", "joint", joint=j)
        out.append(np.arccos(np.clip(c.cos_joint, -1.0, 1.0)))
    return out


def transmission_range(m: LinkageMotion, joints: Sequence[str], cyclic: bool = True
                       ) -> Tuple[Array, Array, BoolArray]:
    """Least and greatest joint angle over the positions of ``m`` (refined by
    a parabola through the extreme sample and its neighbours; ``cyclic``: the
    positions are a whole revolution), over all ``joints``; ``(mu_min, mu_max,
    ok)`` each (M,)."""
    ok = np.all(m.regular, axis=-1)
    lo = hi = None
    for mu in joint_angles(m, joints):
        mu = np.broadcast_to(mu, m.feasible.shape)
        mu = np.atleast_2d(mu)
        reg = np.atleast_2d(m.regular)
        a = np.where(reg, mu, np.inf)
        b = np.where(reg, mu, -np.inf)
        kmin, kmax = np.argmin(a, axis=-1), np.argmax(b, axis=-1)
        vmin = _parabola_extreme(np.where(reg, mu, mu[..., :1]), kmin, "min", cyclic)
        vmax = _parabola_extreme(np.where(reg, mu, mu[..., :1]), kmax, "max", cyclic)
        lo = vmin if lo is None else np.minimum(lo, vmin)
        hi = vmax if hi is None else np.maximum(hi, vmax)
    ok = np.atleast_1d(ok)
    # (lo and hi are None only without joints: the callers pass at least one)
    return np.where(ok, lo, 0.0), np.where(ok, hi, 0.0), ok  # type: ignore[arg-type]


def failed_fraction(m: LinkageMotion) -> Array:
    """Fraction of positions where the linkage does not assemble or is at a
    dead point, (M,)."""
    reg = np.atleast_2d(m.regular)
    return 1.0 - np.mean(reg, axis=-1)


def four_bar_lengths(linkage: Linkage) -> Tuple[Array, ...]:
    """(l1 crank, l2 coupler, l3 rocker, l4 frame) of a four-bar (a crank and an
    RRR dyad closing on a ground point), each (M,) for a batch; DescribedError
    ``reason="not_four_bar"`` otherwise."""
    els = linkage.elements
    grounds = {e.name: e for e in els if isinstance(e, Ground)}
    cranks = [e for e in els if isinstance(e, Crank)]
    rrrs = [e for e in els if isinstance(e, RRR)]
    if len(cranks) != 1 or len(rrrs) != 1 or not all(
            isinstance(e, (Ground, Crank, RRR)) or e.kind == "point" for e in els):
        raise DescribedError("the crank conditions need a four-bar (one crank, one RRR dyad)",
                             "not_four_bar")
    c, d = cranks[0], rrrs[0]
    if d.point_a == c.point and d.point_b in grounds:
        l2, l3, far = d.length_a, d.length_b, grounds[d.point_b]
    elif d.point_b == c.point and d.point_a in grounds:
        l2, l3, far = d.length_b, d.length_a, grounds[d.point_a]
    else:
        raise DescribedError("the crank conditions need a four-bar (one crank, one RRR dyad)",
                             "not_four_bar")
    piv = grounds[c.pivot]
    l4 = np.hypot(np.asarray(far.x) - piv.x, np.asarray(far.y) - piv.y)
    size = int(np.prod(linkage.shape)) if linkage.shape else 1
    return tuple(np.broadcast_to(np.reshape(np.asarray(v, dtype=float), -1), (size,))
                 for v in (c.length, l2, l3, l4))


#: the book's g1 … g6 (式 7-8 … 7-11): the crank l1 is the shortest link and
#: each sum of the crank and one link is at most the sum of the other two
CRANK_NAMES = ("g1", "g2", "g3", "g4", "g5", "g6")


def crank_conditions(l1: FloatOrArray, l2: FloatOrArray, l3: FloatOrArray, l4: FloatOrArray
                     ) -> Array:
    """The book's g1 … g6 (<= 0 when link 1 can turn fully as a crank), (M, 6)."""
    l1, l2, l3, l4 = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (l1, l2, l3, l4)))
    return np.stack([l1 - l2, l1 - l3, l1 - l4, l1 + l4 - l2 - l3, l1 + l2 - l3 - l4,
                     l1 + l3 - l2 - l4], axis=-1)
