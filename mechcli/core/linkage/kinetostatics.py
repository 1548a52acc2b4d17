"""Kinetostatics (动态静力分析) of any linkage of the engine, vectorized.

Every moving link is in equilibrium under its pair reactions, the external
loads, gravity and the d'Alembert inertia force ``-m a_S`` (at the centre of
mass S) and couple ``-J_S alpha`` (eq. 2-1 ... 2-38 of the book, generalised).
The unknowns are

* both components of every revolute-pair reaction,
* the normal force and the couple of every prismatic pair,
* the balancing torque on every crank driver (or the balancing force along the
  line of a slider driver),

and there are three equations (ΣFx, ΣFy, ΣM about S) per moving link: a
square linear system per position.  (Without the condition numbers, a link of a
closed-form block takes its moments about its outer pair's point instead, as by
hand: the same solution, and that pair drops out of the moment equation for free;
the condition numbers are those of the system about the centres of mass.)  It is
assembled from the engine's topology and, because every driver and every dyad of
the engine is a statically determinate group (an Assur group), it is block
lower-triangular in the reverse solving order: each element's 3 or 6 unknowns are
solved for all positions at once, from the last dyad back to the drivers, in closed
form as by hand (:mod:`.dyad_statics`: the moments about the outer pins give the
inner pair, then each outer pair) for every driver and dyad, and by a batched
Gaussian elimination with partial pivoting (:mod:`.elimination`, or LAPACK for
short sweeps) for any block the dyad layout does not describe and where a position
overflows.  Exact zeros and values that are the same at every position (a fixed
point, a block on a fixed guide) are folded as Python floats, so they cost no pass
over memory (:mod:`.folding`).  The model (bodies, loads, pairs, results) is in
:mod:`.force_model`, the load programs in :mod:`.loads`.  The structure of the
system (which equations each unknown enters and through which coefficient, the
blocks, the order) is worked out once per topology (:mod:`.force_plan`); a call
of :func:`solve_forces` computes only the coefficients and solves the blocks, in
steps that pass one record of the call (``_Call``): the known loads → the
right-hand sides → the block solves → the reactions → the frame resultants → the
force and power residuals.

Conventions (as the book, 第二章第一节)
---------------------------------------
``F_Rij`` is the force of link ``i`` on link ``j`` with ``i < j`` (so the
frame, whatever its number, is named like any other link).  The couple of a
prismatic pair is ``M_Rij`` of ``i`` on ``j``, taken about the pair's
reference point (the block's pin: the RRP joint, the RPR block point, the
slider driver's point); the normal force acts there.  Points and moments use
x right, y up, counter-clockwise positive; SI units.

Pins
----
Every point belongs to the link that defines it (a ground point to the frame,
a crank pin to the crank, an RRR joint to its first link, an RRP joint to its
rod, a point on a link to that link).  A later link hinged at that point forms
a revolute pair with the defining link; a compound hinge of k links is thus
k - 1 pairs with the defining link (the pin is part of that link).
"""

from __future__ import annotations

import functools
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.linkage import dyad_statics, force_plan
from mechcli.core.linkage.elimination import gauss
from mechcli.core.linkage.engine import LinkageMotion, _facts
from mechcli.core.linkage.folding import Neg, add, const, div, exact_zero, mul, neg, sub, value

# the model and the load programs, re-exported: this module is the entry point
from mechcli.core.linkage.force_model import (  # noqa: F401
    COND_FLAG,
    Body,
    ForceModelError,
    ForceResult,
    Load,
    Pair,
    PairForce,
    Topology,
    com_of,
    topology,
)
from mechcli.core.linkage.force_plan import Arm, Constant, PairLine, PairNormal
from mechcli.core.linkage.loads import LoadProgram  # noqa: F401
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray


# ---------------------------------------------------------------------------
# solve
# ---------------------------------------------------------------------------
def _mid(a: FloatOrArray, b: FloatOrArray):
    """``(a + b) / 2``, a fixed point's values (a stride-0 array: its zero
    acceleration, a point at the origin) folded as floats."""
    return mul(0.5, add(const(a), const(b)))


def _point(motion, topo, origin, link,
           along, normal, order=2, cos_sin=None):
    """Position (and velocity, acceleration) of a point fixed on ``link``
    (``cos_sin(link)``: the cosine and sine of its angle, when already known).
    ``order`` "a": the position and the acceleration only (velocities None)."""
    o = motion.points[origin]
    k = motion.links[link]
    acc_only = order == "a"
    if acc_only:
        order = 2
    if along is None:  # the midpoint of the link's two points
        second = motion.points[topo.frames[link][1]]
        x, y = _mid(o.x, second.x), _mid(o.y, second.y)
        if order == 0:
            return x, y
        if acc_only:
            return (x, y, None, None, _mid(o.ax, second.ax), _mid(o.ay, second.ay))
        return (x, y, _mid(o.vx, second.vx), _mid(o.vy, second.vy),
                _mid(o.ax, second.ax) if order > 1 else None,
                _mid(o.ay, second.ay) if order > 1 else None)
    if np.ndim(along) == 0 and np.ndim(normal) == 0 and along == 0.0 and normal == 0.0:
        rx = ry = 0.0  # the origin itself: no angle needed
    else:
        c, s = cos_sin(link) if cos_sin is not None else (np.cos(k.theta), np.sin(k.theta))
        rx = value(sub(mul(along, c), mul(normal, s)))
        ry = value(add(mul(along, s), mul(normal, c)))
    if order == 0:
        return o.x + rx, o.y + ry
    w = k.omega
    if acc_only:  # (the acceleration is only read: o.ax itself when rx = ry = 0)
        al, w = const(k.alpha), const(w)
        w2 = mul(w, w)
        return (o.x + rx, o.y + ry, None, None,
                value(sub(sub(o.ax, mul(al, ry)), mul(w2, rx))),
                value(sub(add(o.ay, mul(al, rx)), mul(w2, ry))))
    if order == 1:
        wc = const(w)
        return (o.x + rx, o.y + ry, value(sub(o.vx, mul(wc, ry))),
                value(add(o.vy, mul(wc, rx))),
                None, None)
    vx, vy = o.vx - w * ry, o.vy + w * rx
    w2 = w * w
    return (o.x + rx, o.y + ry, vx, vy,
            o.ax - k.alpha * ry - w2 * rx, o.ay + k.alpha * rx - w2 * ry)


# the system's structure, built once per topology (:mod:`.force_plan`; the names it had here)
_Plan, _plan = force_plan.Plan, force_plan.plan


#: above this many positions a link's cosine and sine come from its element's points
#: (:meth:`~mechcli.core.linkage.elements.Element.direction`, ~9 passes over memory)
#: rather than ``np.cos`` and ``np.sin`` of its angle (~20 ns a position, but two calls
#: instead of nine): the angle's two calls win on a short sweep, the points on a long
#: one (``…_directions_from_points_over_from_angle`` of benchmarks/bench_force.py).
DIRECTION_MIN = 64

#: at most this many positions are solved by LAPACK's batched solve (a few
#: microseconds per call); longer sweeps by the structured elimination
#: (:func:`~mechcli.core.linkage.elimination.gauss`), which skips the zeros: LAPACK
#: wins on a short sweep, the elimination on a long one, about even at this length
#: (``…_dense_over_structured`` of benchmarks/bench_force.py, with and without the
#: condition numbers).  With the condition numbers the closed form
#: (:func:`_solve_closed`) takes over from the same length (on one position the whole
#: call by LAPACK is faster); without them it is used at every length.
DENSE_MAX = 128


def _solve_block(A, b, flat, condition):
    """Solve one element block ``A x = b`` at every position: ``(X, cond)``.

    ``A`` is a k x k list of floats or arrays over the positions, ``b`` a list
    of k arrays.  Short sweeps go through one batched LAPACK solve (with its
    inverse for the condition number); long ones, and any sweep with an exactly
    singular position, through :func:`gauss` (zeros there, cond = inf).
    """
    k = len(A)
    if flat <= DENSE_MAX:
        M = np.empty((flat, k, k))
        for i in range(k):
            for j in range(k):
                M[:, i, j] = A[i][j]
        rhs = np.empty((flat, k, 1))
        for i in range(k):
            rhs[:, i, 0] = b[i]
        try:
            with np.errstate(over="raise", invalid="raise", divide="raise"):
                X = np.linalg.solve(M, rhs)[..., 0]
                c_blk = None
                if condition:
                    inv = np.linalg.inv(M)
                    c_blk = (np.abs(M).sum(axis=1).max(axis=1)
                             * np.abs(inv).sum(axis=1).max(axis=1))
            if np.all(np.isfinite(X)):
                return [X[:, i] for i in range(k)], c_blk
        except (np.linalg.LinAlgError, FloatingPointError):
            pass  # an exactly singular position: the elimination flags it
    if condition:
        # 1-norm of the block: largest column sum of |A| (floats stay floats)
        nrm = np.zeros(flat)
        for j in range(k):
            np.maximum(nrm, sum(abs(A[i][j]) for i in range(k)), out=nrm)
        # the inverse's columns solved with the right-hand side: rows 1..k of X
        eye = np.zeros((k, k + 1, flat))
        for i in range(k):
            eye[i, 1 + i] = 1.0
            eye[i, 0] = b[i]
        b = list(eye)
    X, sing = gauss(A, b)
    c_blk = None
    if condition:
        inv_nrm = np.zeros(flat)
        for j in range(k):
            np.maximum(inv_nrm, sum(np.abs(X[i][1 + j]) for i in range(k)), out=inv_nrm)
        c_blk = nrm * inv_nrm
        if sing is not None:
            c_blk = np.where(sing, np.inf, c_blk)
        X = [xi[0] for xi in X]
    return X, c_blk


def _solve_closed(lay: Any, A: Any, b: Any, flat: Any, condition: bool):
    """Solve one driver or dyad block in closed form (:mod:`.dyad_statics`):
    ``(X, cond)`` as :func:`_solve_block`, or None when a position overflows
    (a nearly singular one: the general elimination then solves the block).
    The condition number's inverse is solved column by column with the same
    factor (unit right-hand sides: Python floats, folded)."""
    k = len(A)
    try:
        with np.errstate(over="raise", invalid="raise", divide="raise"):
            fac = dyad_statics.factor(lay, A)
            X = dyad_statics.apply(fac, A, b, (flat,))
            # arrays of their own: a folded sign (-(-v)) or a coefficient of 1 gives
            # back a right-hand side itself (a load's array, a read-only broadcast of a
            # constant load, an earlier block's unknown) or another unknown of the block
            seen = {id(v.v if type(v) is Neg else v)
                    for v in b + [a for row in A for a in row]}
            for i, v in enumerate(X):
                if id(v) in seen or not v.flags.writeable:
                    X[i] = v = np.array(v)
                seen.add(id(v))
            if not condition:  # (cond stays ones, as the general path leaves it)
                return X, None
            # 1-norm of the block (largest column sum of |A|) and of its inverse
            nrm = np.zeros(flat)
            for j in range(k):
                np.maximum(nrm, sum(abs(A[i][j]) for i in range(k)), out=nrm)
            inv_nrm = np.zeros(flat)
            for j in range(k):
                e = [0.0] * k
                e[j] = 1.0
                col = dyad_statics.apply(fac, A, e, (flat,), arrays=False)
                np.maximum(inv_nrm, sum(abs(v) for v in col), out=inv_nrm)
    except FloatingPointError:
        return None
    c_blk = nrm * inv_nrm
    sing = fac[4]
    if sing is not None:
        c_blk = np.where(sing, np.inf, c_blk)
    return X, c_blk


#: solve driver and dyad blocks in closed form (:mod:`.dyad_statics`); False: every
#: block by the general elimination (the tests compare the two)
CLOSED_FORM = True


#: (the name before :mod:`.folding`)
_exact_zero = exact_zero


def _broadcasts(a: Any, b: Any):
    try:
        np.broadcast_shapes(a, b)
        return True
    except ValueError:
        return False


def _check_shapes(bodies: Dict[int, Any], loads: Sequence[Any], n: int) -> None:
    """Raise ValueError for a body's or a load's array that does not broadcast to
    the motion's shape ``n`` (a batch of designs needs a batched linkage or input)."""
    for what, obj, fields in ([(f"body of link {k}", b, ("mass", "inertia", "along", "normal"))
                               for k, b in bodies.items()]
                              + [(f"load '{ld.name}'", ld, ("fx", "fy", "torque", "along",
                                                            "normal")) for ld in loads]):
        for f in fields:
            v = getattr(obj, f)
            if type(v) is float or type(v) is int or v is None:
                continue
            sh = np.shape(v)
            if sh and not (_broadcasts(sh, n) and np.broadcast_shapes(sh, n) == n):
                raise ValueError(f"{what}: {f} of shape {sh} does not broadcast to the "
                                 f"motion's shape {n} (a batch of designs needs a batched "
                                 "linkage or input)")


@record(eq=False, frozen=False)
class _Call:
    """What the steps of one :func:`solve_forces` call share: the topology, its
    :class:`~.force_plan.Plan` and the motion; ``n`` the motion's shape, ``flat``
    its number of positions; ``Ls`` the length that scales the moment equations
    (1.0 where the scaling changes only round-off); ``condition`` whether the
    condition numbers are computed; ``trig`` the cosine and sine of the links'
    angles computed so far (:meth:`cos_sin`)."""

    topo: Topology
    plan: force_plan.Plan
    motion: LinkageMotion
    n: tuple
    flat: int
    Ls: object
    condition: bool
    trig: dict

    def arr(self, x: FloatOrArray):
        """``x`` as a flat float array over the positions (a view where it is one)."""
        # the common case, an array over the positions already: a view, no broadcast_to
        n, flat = self.n, self.flat
        if type(x) is np.ndarray and x.dtype == np.float64 and x.shape in (n, (flat,)):
            return x.reshape(flat)
        return np.broadcast_to(np.asarray(x, dtype=float), n).reshape(flat)

    def coord(self, v: FloatOrArray):
        """A number that is the same at every position (a Python number, a fixed
        point's stride-0 array) as a float, folded by the arithmetic; else the flat
        array."""
        c = const(v)
        return float(c) if type(c) is float or type(c) is int else self.arr(c)

    def cos_sin(self, link: int):
        """Cosine and sine of ``link``'s angle, once per call (the centres of mass,
        the loads, the directions and the virtual power share them)."""
        th = self.motion.links[link].theta
        cs = self.trig.get(id(th))
        if cs is None:  # keyed by the angle array: a block shares its guide's
            if type(th) is np.ndarray and th.ndim and not any(th.strides):
                # one angle at every position (a block on a fixed guide): floats
                t1 = th.reshape(-1)[:1]
                cs = (float(np.cos(t1)[0]), float(np.sin(t1)[0]), th)
            else:  # from the element's points if it can (cheaper than cos and sin but
                # for a few positions, where the calls cost more than the arithmetic)
                el = self.plan.direction_of.get(link) if th.size > DIRECTION_MIN else None
                u = el.direction(self.motion, link) if el is not None else None
                cs = (np.cos(th), np.sin(th), th) if u is None else (u[0], u[1], th)
            self.trig[id(th)] = cs
        return cs[0], cs[1]


@record(eq=False)
class _Known:
    """The known loads of a call: per moving link ``com[link] = (x, y, origin,
    along, normal)`` (its centre of mass and where it is defined), ``minus[link] =
    [fx, fy, m]`` (minus the known force and moment about the centre of mass: the
    right-hand side of its equations, no negation pass), and ``com_off[link]``, the
    centre's constant offset from its origin where the link's angle is fixed."""

    com: dict
    minus: dict
    com_off: dict


def _known_loads(call: Any, bodies: Dict[int, Any], loads: Sequence[Any],
                 gravity: Optional[Tuple[float, float]]):
    """Step 1: the centres of mass and the known loads on every moving link
    (:class:`_Known`): weight, d'Alembert inertia force and couple, external loads."""
    known = _inertia_loads(call, bodies, gravity)
    for ld in loads:
        _add_load(call, known, ld)
    return known


def _inertia_loads(call, bodies, gravity):
    """The centres of mass and minus their weights and inertia forces and couples:
    ``m (a_S - g)`` and ``J alpha`` (:class:`_Known` without the external loads)."""
    topo, motion, arr, n, cos_sin = call.topo, call.motion, call.arr, call.n, call.cos_sin
    gx, gy = gravity
    com, minus, com_off = {}, {}, {}
    for link in topo.links:
        b = bodies.get(link) or Body(link)
        origin, along, normal = com_of(topo, b, link)
        massless = type(b.mass) in (float, int) and b.mass == 0.0
        # the midpoint's acceleration is (a1 + a2) / 2: the half goes with the mass below
        half = along is None and not massless
        if massless or half:  # no acceleration needed (or summed below)
            x, y = _point(motion, topo, origin, link, along, normal, 0, cos_sin=cos_sin)
        else:
            x, y, _vx, _vy, ax, ay = _point(motion, topo, origin, link, along, normal, "a",
                                            cos_sin=cos_sin)
        x, y = arr(x), arr(y)
        com[link] = (x, y, origin, along, normal)
        if (along is not None and np.ndim(along) == 0 and np.ndim(normal) == 0
                and not (along == 0 and normal == 0)
                and type(const(motion.links[link].theta)) is float):
            c, s = cos_sin(link)  # a fixed angle: the centre's offset from its origin
            com_off[link] = (along * c - normal * s, along * s + normal * c)
        kl = motion.links[link]
        # masses and inertias may be arrays of a batch of designs: arr() flattens
        # them with the positions
        # (an exact zero stays the float 0.0: skipped by the arithmetic below)
        # minus the weight and the inertia force: m (a_S - g); minus the couple: J alpha
        if massless:
            fx = fy = 0.0
        elif half:  # (m / 2) (a1 + a2 - 2 g): the same numbers, one pass fewer
            p1, p2 = motion.points[origin], motion.points[topo.frames[link][1]]
            mh = np.multiply(0.5, b.mass)  # (a list of the designs' masses too)
            fx = arr(mh * arr(sub(add(const(p1.ax), const(p2.ax)), 2.0 * gx)).reshape(n))
            fy = arr(mh * arr(sub(add(const(p1.ay), const(p2.ay)), 2.0 * gy)).reshape(n))
        else:
            fx = arr(b.mass * sub(arr(ax).reshape(n), gx))
            fy = arr(b.mass * sub(arr(ay).reshape(n), gy))
        al = const(kl.alpha)
        m = (arr(b.inertia * arr(kl.alpha).reshape(n))
             if np.any(b.inertia) and not exact_zero(al) else 0.0)
        minus[link] = [fx, fy, m]
    return _Known(com, minus, com_off)


def _add_load(call: Any, known: Any, ld: Any) -> None:
    """Subtract the external load ``ld`` (its force moved to the centre of mass)
    from its link's right-hand side in ``known``."""
    topo, arr, coord = call.topo, call.arr, call.coord
    if ld.link not in known.minus:
        raise ForceModelError(f"load '{ld.name}' is on link {ld.link}, which does not move",
                              ("link", ld.link))
    f = known.minus[ld.link]
    com = known.com[ld.link]
    tq, fx, fy = coord(ld.torque), coord(ld.fx), coord(ld.fy)
    if ld.relative:
        c, s = (arr(v) for v in call.cos_sin(ld.link))
        fx, fy = fx * c - fy * s, fx * s + fy * c
    if np.any(fx) or np.any(fy):
        origin = ld.origin
        if origin is not None and ld.link not in topo.members.get(origin, ()):
            raise ForceModelError(f"load '{ld.name}' acts at '{origin}', which is not on "
                                  f"link {ld.link}", ("point", origin))
        if origin is None:
            px, py = com[0], com[1]
        else:
            px, py = (arr(v) for v in _point(call.motion, topo, origin, ld.link, ld.along,
                                             ld.normal, order=0, cos_sin=call.cos_sin))
        sx, sy = com[0], com[1]
        f[0] = sub(f[0], fx)
        f[1] = sub(f[1], fy)
        tq = add(tq, sub(mul(px - sx, fy), mul(py - sy, fx)))
    f[2] = sub(f[2], tq)


class _Coefficients:
    """The coefficients of one call (:mod:`.force_plan`'s records made numbers):
    moment arms about each link's reference point, scaled by L, and the directions
    of the prismatic pairs and slider drivers, each computed once.

    Without the condition numbers, a closed-form block's link takes its moments
    about its outer pair's point (``Plan.ref_point``): the same solution, fewer
    passes; the condition numbers are those of the system about the centres of
    mass (``ref`` empty)."""

    __slots__ = ("call", "known", "ref", "levers", "directions")

    def __init__(self, call, known):
        self.call, self.known = call, known
        self.ref = call.plan.ref_point if not call.condition and CLOSED_FORM else {}
        self.levers, self.directions = {}, {}

    def lever(self, link: int, point: str):
        """``(dx, dy) / L`` from ``link``'s reference point to ``point``."""
        levers, call = self.levers, self.call
        lv = levers.get((link, point))
        r = self.ref.get(link) if lv is None else None
        if r is not None:  # about the outer pair's point
            if point == r:
                lv = (0.0, 0.0)
            else:
                p, o = call.motion.points[point], call.motion.points[r]
                lv = (div(sub(call.coord(p.x), call.coord(o.x)), call.Ls),
                      div(sub(call.coord(p.y), call.coord(o.y)), call.Ls))
            levers[(link, point)] = lv
        com = self.known.com[link]
        if lv is None and point == com[2]:
            if exact_zero(com[3]) and exact_zero(com[4]):
                lv = levers[(link, point)] = (0.0, 0.0)  # the centre of mass itself
            elif link in self.known.com_off:  # a constant offset: floats
                off = self.known.com_off[link]
                lv = levers[(link, point)] = (div(-off[0], call.Ls), div(-off[1], call.Ls))
        if lv is None:
            p = call.motion.points[point]
            lv = levers[(link, point)] = (div(call.arr(p.x) - com[0], call.Ls),
                                          div(call.arr(p.y) - com[1], call.Ls))
        return lv

    def direction(self, key: Any):
        """The unit vector of a :class:`~.force_plan.PairNormal` or
        :class:`~.force_plan.DriverLine`."""
        u = self.directions.get(key)
        if u is None:
            arr = self.call.arr
            if type(key) is PairNormal:  # the left normal of a prismatic pair's guide
                c, s = self.call.cos_sin(self.call.topo.pairs[key.pair].block)
                u = (neg(s if type(s) is float else arr(s)), c if type(c) is float else arr(c))
            elif type(key) is PairLine:  # an actuated slide's line, as its s grows
                c, s = self.call.cos_sin(self.call.topo.pairs[key.pair].block)
                u = (c if type(c) is float else arr(c), s if type(s) is float else arr(s))
            else:  # a slider driver's line
                ang = self.call.topo.linkage.driver(key.link).angle
                u = (np.cos(ang), np.sin(ang))
                if np.ndim(ang):
                    u = (arr(u[0]), arr(u[1]))
            self.directions[key] = u
        return u

    def of(self, spec: Any):
        """The value of a coefficient record (a float or an array)."""
        kind = type(spec)
        if kind is Constant:
            return spec.value
        if kind is Arm:
            if spec.axis == 0:
                return mul(-spec.sign, self.lever(spec.link, spec.point)[1])
            return mul(spec.sign, self.lever(spec.link, spec.point)[0])
        ux, uy = self.direction(spec.direction)
        if spec.row == 0:
            return mul(spec.sign, ux)
        if spec.row == 1:
            return mul(spec.sign, uy)
        dx, dy = self.lever(spec.link, spec.point)
        return mul(spec.sign, sub(mul(dx, uy), mul(dy, ux)))


def _right_hand_sides(call: Any, known: Any, coefs: Any):
    """Step 2: the right-hand side of every equation (minus the known loads; the
    moment about the link's reference point, scaled by L)."""
    rhs = [None] * call.plan.nrows
    for link in call.topo.links:
        e = call.plan.eq_of[link]
        f = known.minus[link]
        m = f[2]
        r = coefs.ref.get(link)
        if r is not None and not all(type(v) is float and v == 0.0 for v in f[:2]):
            # the known force moved from the centre of mass S to R: + (S - R) x f
            x, y, origin, along, normal = known.com[link]
            if origin == r and along is not None and exact_zero(along) and \
                    exact_zero(normal):
                off = None  # S is R
            elif origin == r and link in known.com_off:
                off = known.com_off[link]
            else:
                o = call.motion.points[r]
                off = (sub(x, call.coord(o.x)), sub(y, call.coord(o.y)))
            if off is not None:
                m = add(m, sub(mul(off[0], f[1]), mul(off[1], f[0])))
        rhs[e], rhs[e + 1], rhs[e + 2] = f[0], f[1], div(m, call.Ls)
    return rhs


def _solve_blocks(call: Any, coefs: Any, rhs: Any):
    """Step 3: the element blocks, from the last element back to the drivers (block
    lower-triangular), each one's unknowns from its links' equations: the scaled
    unknowns and the largest condition number of the blocks at each position."""
    flat, condition = call.flat, call.condition
    coef = coefs.of
    xs = [None] * len(call.plan.columns)  # scaled solution
    cond = np.ones(flat)
    for unk, rows, entries, solved, lay in call.plan.blocks:
        k = len(rows)
        A = [[0.0] * k for _ in range(k)]
        for i, j, spec in entries:
            A[i][j] = add(A[i][j], coef(spec))
        b = [rhs[r] for r in rows]
        for i, u, spec in solved:
            b[i] = sub(b[i], mul(coef(spec), xs[u]))
        got = (_solve_closed(lay, A, b, flat, condition)
               if lay is not None and CLOSED_FORM and (flat > DENSE_MAX or not condition)
               else None)
        if got is None:  # the general elimination (arrays on the right-hand side)
            A = [[value(v) for v in row] for row in A]
            b = [np.full(flat, v) if type(v) is float else value(v) for v in b]
            got = _solve_block(A, b, flat, condition)
        X, c_blk = got
        if c_blk is not None:
            cond = np.maximum(cond, c_blk)
        for jc, u in enumerate(unk):
            xs[u] = X[jc]
    return xs, cond


def _reactions(call: Any, coefs: Any, xs: Any):
    """Step 4: the unknowns in their units: ``(balancing, pairs)``, the balancing
    torque or force of every driver and the :class:`PairForce` of every pair."""
    n, plan, topo = call.n, call.plan, call.topo
    x = [mul(v, call.Ls) if c else v for v, c in zip(xs, plan.is_couple)]
    balancing = {d.link: x[plan.driver_cols[d.link]].reshape(n)
                 for d in topo.linkage.drivers}
    pairs = []
    for pi, (pr, pc) in enumerate(zip(topo.pairs, plan.pair_cols)):
        if pr.kind == "R":
            pairs.append(PairForce(pr, x[pc[0]].reshape(n), x[pc[1]].reshape(n),
                                   np.zeros(n)))
        else:
            nval = x[pc[0]]
            nx, ny = coefs.direction(plan.normal[pi])
            # (a float direction multiplied as such: a fixed guide's -0.0 kept)
            pairs.append(PairForce(pr, (nval * nx if type(nx) is float
                                        else value(mul(nval, nx))).reshape(n),
                                   (nval * ny if type(ny) is float
                                    else value(mul(nval, ny))).reshape(n),
                                   x[pc[1]].reshape(n)))
    for link, pi in plan.actuated.items():
        # an actuator's force (of the guide on the block, along the line) is carried
        # by its pair too: the pair's reaction is the whole force of i on j
        pf, pr = pairs[pi], topo.pairs[pi]
        ux, uy = _line_of(call, pi)
        sign = 1.0 if pr.j == pr.block else -1.0
        f = balancing[link]
        pairs[pi] = PairForce(pr, pf.fx + sign * f * ux, pf.fy + sign * f * uy, pf.couple)
    return balancing, pairs


def _line_of(call: Any, pi: int):
    """Cosine and sine of an actuated slide's line (its block's angle), of the
    motion's shape."""
    c, s = call.cos_sin(call.topo.pairs[pi].block)
    return (np.broadcast_to(c, call.n) if type(c) is float else np.reshape(c, call.n),
            np.broadcast_to(s, call.n) if type(s) is float else np.reshape(s, call.n))


class _Sums:
    """Folded sums (no zeros to start from; a pending sign taken by the next term)
    that remember their array terms: :meth:`own` gives a sum an array of its own."""

    __slots__ = ("sums", "terms")

    def __init__(self, keys):
        self.sums = dict.fromkeys(keys, 0.0)
        self.terms = {k: [] for k in keys}

    def put(self, key: Any, v: FloatOrArray, sign: float = 1.0) -> None:
        self.sums[key] = add(self.sums[key], v) if sign > 0 else sub(self.sums[key], v)
        if type(v) is not float:
            self.terms[key].append(v)

    def own(self, key: Any, flat: Any):
        # an array of its own: a sum of one term is that term (a pair's force) itself
        v = value(self.sums[key])
        if type(v) is float:
            return np.full(flat, v)
        return v.copy() if any(v is t for t in self.terms[key]) else v


def _frame_resultants(call: Any, balancing: Dict[int, np.ndarray], pairs: Any):
    """Step 5: the force and moment (about the origin) transmitted to the frame and
    the input power, as flat arrays ``(fx, fy, m, power)``."""
    motion, flat, arr = call.motion, call.flat, call.arr
    linkage = call.topo.linkage
    frame = linkage.frame
    sums = _Sums(("fx", "fy", "m", "p"))
    for pf in pairs:
        pr = pf.pair
        if frame not in (pr.i, pr.j):
            continue
        p = motion.points[pr.point]
        fx, fy = pf.fx.reshape(flat), pf.fy.reshape(flat)
        px, py = const(p.x), const(p.y)
        t = sub(mul(px if type(px) is float else arr(px), fy),
                mul(py if type(py) is float else arr(py), fx))
        if pr.kind == "P":
            t = add(t, pf.couple.reshape(flat))
        # the force on the frame: + the pair's, or - when frame < link
        sign = 1.0 if pr.j == frame else -1.0
        sums.put("fx", fx, sign)
        sums.put("fy", fy, sign)
        sums.put("m", t, sign)
    plan = call.plan
    for d in linkage.drivers:
        val = balancing[d.link].reshape(flat)
        if d.link in plan.actuated:  # a force inside the machine: only its power
            name = _slide_name(call.topo, plan.actuated[d.link])
            sums.put("p", mul(val, arr(motion.slides[name].v)))
        elif d.rotary:
            sums.put("m", val, -1.0)
            w = const(motion.links[d.link].omega)
            sums.put("p", mul(val, w if type(w) is float else arr(w)))
        else:
            p = motion.points[d.point]
            ux, uy = np.cos(d.angle), np.sin(d.angle)
            if np.ndim(d.angle):
                ux, uy = arr(ux), arr(uy)
            fx, fy = mul(val, ux), mul(val, uy)
            sums.put("fx", fx, -1.0)
            sums.put("fy", fy, -1.0)
            sums.put("m", sub(mul(arr(p.x), fy), mul(arr(p.y), fx)), -1.0)
            sums.put("p", mul(val, arr(motion.slides[d.slide_names(frame)[0]].v)))
    return tuple(sums.own(k, flat) for k in ("fx", "fy", "m", "p"))


def _slide_name(topo: Topology, pi: int):
    """The slide (``LinkageMotion.slides`` key) of prismatic pair ``pi``."""
    pr = topo.pairs[pi]
    return topo.linkage.elements[pr.element].slide_names(topo.linkage.frame)[0]


def _force_residual(call: Any, known: Any, ffx: FloatOrArray, ffy: FloatOrArray):
    """Step 6a: the global balance |Σ known forces (gravity, loads, inertia) - the
    force on the frame| (minus the known forces, summed, plus the force on the
    frame: the same length), flat."""
    links = call.topo.links
    kfx = value(functools.reduce(add, (known.minus[ln][0] for ln in links), 0.0))
    kfy = value(functools.reduce(add, (known.minus[ln][1] for ln in links), 0.0))
    dx, dy = kfx + ffx, kfy + ffy  # |d| without hypot's cost (no overflow at forces)
    dx *= dx
    dy *= dy
    dx += dy
    return np.sqrt(dx, out=dx)


def _power_residual(call: Any, known: Any, balancing: Dict[int, np.ndarray],
                    unit_motion: LinkageMotion):
    """Step 6b: the virtual power with the velocity coefficients ``unit_motion``,
    Σ balancing·ω* + Σ known loads·v*: a second route to the balancing (zeros
    without ``unit_motion``), of the motion's shape."""
    if unit_motion is None:
        return np.zeros(call.n)
    motion, topo, flat, arr = call.motion, call.topo, call.flat, call.arr
    frame = topo.linkage.frame
    pres = np.zeros(flat)
    for d in topo.linkage.drivers:
        val = balancing[d.link].reshape(flat)
        if d.link in call.plan.actuated:
            name = _slide_name(topo, call.plan.actuated[d.link])
            pres += val * arr(unit_motion.slides[name].v)
        elif d.rotary:
            pres += val * arr(unit_motion.links[d.link].omega)
        else:
            pres += val * arr(unit_motion.slides[d.slide_names(frame)[0]].v)
    for link in topo.links:
        f = known.minus[link]
        if all(type(v) is float and v == 0.0 for v in f):
            continue  # no known load on this link (massless, unloaded)
        x0, y0, origin, along, normal = known.com[link]
        # the same positions as the motion (as the callers solve it): its angles' trig
        # (only a centre off its origin needs the angle's trig)
        same = (along is None or (exact_zero(along) and exact_zero(normal))
                or unit_motion.links[link].theta is motion.links[link].theta
                or np.array_equal(unit_motion.links[link].theta,
                                  motion.links[link].theta))
        _x, _y, vx, vy, _a, _b = _point(unit_motion, topo, origin, link, along, normal,
                                         order=1, cos_sin=call.cos_sin if same else None)
        # the known moment is about the centre of mass: P = F·v_S + M·ω (f = -F, -M)
        pres -= value(add(add(mul(f[0], arr(vx)), mul(f[1], arr(vy))),
                          mul(f[2], arr(unit_motion.links[link].omega))))
    return pres.reshape(call.n)


def solve_forces(topo, motion, bodies,
                 loads=(), gravity=(0.0, 0.0),
                 unit_motion=None, scale=None,
                 condition=True):
    """Pair reactions and balancing torques/forces at every position of ``motion``.

    Parameters
    ----------
    topo : Topology
        From :func:`topology`.
    motion : LinkageMotion
        Engine output of order 2 (only regular positions should be passed).
    bodies : dict
        ``{link: Body}``; links not listed are massless with their centre of
        mass at the default point.
    loads : sequence of Load
    gravity : (gx, gy)
        Gravitational acceleration vector [m/s^2] (``(0, -9.8)``; zeros for none).
    unit_motion : LinkageMotion, optional
        Engine output of order 1 with a unit speed of the primary driver (the
        velocity coefficients), for the virtual-power check; default: none.
    scale : float, optional
        Length scaling the moment equations for the condition number
        (default: the linkage's scale).
    condition : bool
        Compute the condition number of every element block (costs about as
        much as the solve itself); otherwise ``cond`` is all NaN-free ones.

    Returns
    -------
    ForceResult

    Notes
    -----
    The steps: the known loads (:func:`_known_loads`) → the right-hand sides
    (:func:`_right_hand_sides`) → the block solves (:func:`_solve_blocks`) → the
    reactions in their units (:func:`_reactions`) → the frame resultants
    (:func:`_frame_resultants`) → the force and power residuals.
    """
    n = motion.feasible.shape
    _check_shapes(bodies, loads, n)
    L = _facts(topo.linkage).scale if scale is None else scale
    plan = _plan(topo)
    call = _Call(topo, plan, motion, n, motion.feasible.size, 1.0, condition, {})
    if np.ndim(L):
        # a batch of designs: one moment scale per design (flattened like the
        # positions), so each design's system is scaled as when solved alone
        L = call.arr(L)
    # the moment equations are scaled by L for the condition numbers and for the
    # general elimination's pivots; when every block is solved in closed form
    # without condition numbers the scaling changes nothing but round-off: skipped
    # (fewer passes over memory)
    if condition or not CLOSED_FORM or not plan.all_closed:
        call.Ls = L
    known = _known_loads(call, bodies, loads, gravity)
    coefs = _Coefficients(call, known)
    rhs = _right_hand_sides(call, known, coefs)
    xs, cond = _solve_blocks(call, coefs, rhs)
    balancing, pairs = _reactions(call, coefs, xs)
    ffx, ffy, fm, power = _frame_resultants(call, balancing, pairs)
    force_residual = _force_residual(call, known, ffx, ffy)
    power_residual = _power_residual(call, known, balancing, unit_motion)
    return ForceResult(balancing, pairs, (ffx.reshape(n), ffy.reshape(n)), fm.reshape(n),
                       power.reshape(n), cond.reshape(n), power_residual,
                       force_residual.reshape(n),
                       {ln: (known.com[ln][0].reshape(n), known.com[ln][1].reshape(n))
                        for ln in topo.links})
