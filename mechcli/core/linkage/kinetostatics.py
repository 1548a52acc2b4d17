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
the condition numbers are those of the system about the centres of mass.)  It is assembled from the engine's topology
and, because every driver and every dyad of the engine is a statically
determinate group (an Assur group), it is block lower-triangular in the
reverse solving order: each element's 3 or 6 unknowns are solved for all
positions at once, from the last dyad back to the drivers, in closed form as by
hand (:mod:`.dyad_statics`: the moments about the outer pins give the inner
pair, then each outer pair) for every driver and dyad, and by a batched Gaussian
elimination with partial pivoting (:mod:`.elimination`, or LAPACK for short
sweeps) for any block the dyad layout does not describe and where a position
overflows.  Exact zeros and values that are the same at every position (a fixed
point, a block on a fixed guide) are folded as Python floats, so they cost no
pass over memory.  The model
(bodies, loads, pairs, results) is in :mod:`.force_model`, the load programs
in :mod:`.loads`.  The structure of the system (which equations each unknown
enters, the blocks, the order) is worked out once per topology (``_Plan``);
a call computes only the coefficients and solves the blocks.

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
from typing import Dict, Optional

import numpy as np

from mechcli.core.linkage import dyad_statics
from mechcli.core.linkage.dyad_statics import _add, _div, _mul, _neg, _sub, const, value
from mechcli.core.linkage.elimination import gauss
from mechcli.core.linkage.elements import Element
from mechcli.core.linkage.engine import LinkageMotion, _facts
# the model and the load programs, re-exported: this module is the entry point
from mechcli.core.linkage.force_model import (COND_FLAG, Body, ForceModelError,  # noqa: F401
                                              ForceResult, Load, Pair, PairForce, Topology,
                                              com_of, topology)
from mechcli.core.linkage.loads import LoadProgram  # noqa: F401

# ---------------------------------------------------------------------------
# solve
# ---------------------------------------------------------------------------
def _mid(a, b):
    """``(a + b) / 2``, a fixed point's values (a stride-0 array: its zero
    acceleration, a point at the origin) folded as floats."""
    return _mul(0.5, _add(const(a), const(b)))


def _point(motion, topo, origin, link, along, normal, order=2, cos_sin=None):
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
        rx = value(_sub(_mul(along, c), _mul(normal, s)))
        ry = value(_add(_mul(along, s), _mul(normal, c)))
    if order == 0:
        return o.x + rx, o.y + ry
    w = k.omega
    if acc_only:  # (the acceleration is only read: o.ax itself when rx = ry = 0)
        al, w = const(k.alpha), const(w)
        w2 = _mul(w, w)
        return (o.x + rx, o.y + ry, None, None,
                value(_sub(_sub(o.ax, _mul(al, ry)), _mul(w2, rx))),
                value(_sub(_add(o.ay, _mul(al, rx)), _mul(w2, ry))))
    if order == 1:
        wc = const(w)
        return (o.x + rx, o.y + ry, value(_sub(o.vx, _mul(wc, ry))),
                value(_add(o.vy, _mul(wc, rx))),
                None, None)
    vx, vy = o.vx - w * ry, o.vy + w * rx
    w2 = w * w
    return (o.x + rx, o.y + ry, vx, vy,
            o.ax - k.alpha * ry - w2 * rx, o.ay + k.alpha * rx - w2 * ry)


# ---------------------------------------------------------------------------
# the system's structure, built once per topology
# ---------------------------------------------------------------------------
class _Plan:
    """The structure of a linkage's kinetostatic system, worked out once per
    topology (cached on it): the unknowns, which equations each enters and how
    its coefficient is computed, and, per element block (in the reverse solving
    order), where each coefficient goes in the block's matrix and which solved
    unknowns of later blocks enter its right-hand side.

    Unknowns are solved scaled: forces as they are, couples and balancing
    torques divided by the length scale L (the moment rows are divided by L),
    so every coefficient below is dimensionless: ``("c", v)`` a constant,
    ``("mx"|"my", link, point, sign)`` the moment arm of a force component
    about the link's centre of mass, ``("ux"|"uy"|"um", link, point, direction,
    sign)`` a force along a (normal or driver) direction.
    """

    def __init__(self, topo):
        linkage = topo.linkage
        frame = linkage.frame
        self.eq_of = eq_of = {link: 3 * i for i, link in enumerate(topo.links)}
        columns, owners, self.pair_cols, self.driver_cols = [], [], [], {}

        def force(col_x, col_y, link, sign, point, direction=None):
            if link == frame:
                return
            e = eq_of[link]
            if direction is None:
                col_x += [(e, ("c", sign)), (e + 2, ("mx", link, point, sign))]
                col_y += [(e + 1, ("c", sign)), (e + 2, ("my", link, point, sign))]
            else:
                col_x += [(e, ("ux", link, point, direction, sign)),
                          (e + 1, ("uy", link, point, direction, sign)),
                          (e + 2, ("um", link, point, direction, sign))]

        for pi, pr in enumerate(topo.pairs):
            if pr.kind == "R":
                cx, cy = [], []
                for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
                    force(cx, cy, link, sign, pr.point)
                self.pair_cols.append((len(columns), len(columns) + 1))
                columns += [cx, cy]
                owners += [("R", pi, 0), ("R", pi, 1)]
            else:
                cn, cm = [], []
                for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
                    force(cn, None, link, sign, pr.point, ("n", pi))
                    if link != frame:
                        cm.append((eq_of[link] + 2, ("c", sign)))  # the couple (scaled)
                self.pair_cols.append((len(columns), len(columns) + 1))
                columns += [cn, cm]
                owners += [("P", pi, 0), ("P", pi, 1)]
        for d in linkage.drivers:
            col = []
            if d.rotary:
                col.append((eq_of[d.link] + 2, ("c", 1.0)))  # the torque (scaled)
            else:
                force(col, None, d.link, 1.0, d.point, ("d", d.link))
            self.driver_cols[d.link] = len(columns)
            columns.append(col)
            owners.append(("D", d.link, 0))
        # couples and balancing torques: the scaled unknown is value / L
        self.is_couple = [o[0] == "P" and o[2] == 1
                          or (o[0] == "D" and linkage.driver(o[1]).rotary) for o in owners]
        self.columns = columns
        self.nrows = 3 * len(topo.links)
        self.blocks = []
        self.ref_point = {}
        solved = []
        for idx, new_links, pidx in reversed(topo.blocks):
            unk = [u for pi in pidx for u in self.pair_cols[pi]]
            el = linkage.elements[idx]
            if el.is_driver:
                unk.append(self.driver_cols[el.link])
            rows = [eq_of[ln] + c for ln in new_links for c in range(3)]
            if len(unk) != len(rows):  # pragma: no cover - every engine element is determinate
                raise ForceModelError(f"element {idx} is not statically determinate")
            row_pos = {r: i for i, r in enumerate(rows)}
            entries = [(row_pos[r], jc, spec) for jc, u in enumerate(unk)
                       for r, spec in columns[u] if r in row_pos]
            known = [(row_pos[r], u, spec) for u in solved for r, spec in columns[u]
                     if r in row_pos]
            # the closed-form layout of the block (a driver or a dyad), if it has one
            cols_of_rows = [{} for _ in unk]
            for i, jc, spec in entries:
                cols_of_rows[jc][i] = spec[0] == "c"
            kind_of = [(topo.pairs[pi].kind,
                        tuple(k for k, ln in enumerate(new_links)
                              if ln in (topo.pairs[pi].i, topo.pairs[pi].j)))
                       for pi in pidx]
            lay = dyad_statics.layout(kind_of, cols_of_rows, len(rows))
            self.blocks.append((unk, rows, entries, known, lay))
            solved += unk
            # a closed-form block's links may take their moments about their outer pair's
            # point instead of the centre of mass (the same solution): that pair then
            # drops out of the moment equation with no pass over memory
            if lay is not None and lay[0] == "dyad":
                for ln, (_kind, cols, _base) in zip(new_links, (lay[1], lay[3])):
                    self.ref_point[ln] = topo.pairs[pidx[cols[0] // 2]].point
            elif lay is not None and len(pidx) == 1 and len(new_links) == 1:
                self.ref_point[new_links[0]] = topo.pairs[pidx[0]].point
        self.all_closed = all(blk[-1] is not None for blk in self.blocks)
        # the element that makes each link, where it can give the angle's cosine and
        # sine from its points (Element.direction)
        self.direction_of = {ln: el for el in linkage.elements for ln in el.makes()[1]
                             if type(el).direction is not Element.direction}


def _plan(topo):
    plan = topo.__dict__.get("_force_plan")
    if plan is None:
        plan = _Plan(topo)
        object.__setattr__(topo, "_force_plan", plan)
    return plan


#: above this many positions a link's cosine and sine come from its element's points
#: (:meth:`~mechcli.core.linkage.elements.Element.direction`, ~9 passes over memory)
#: rather than ``np.cos`` and ``np.sin`` of its angle (~20 ns a position, but two calls
#: instead of nine).  Measured on 例 2-4 (2026-11-25): the fixed cost of one position
#: 0.448 ms from the points, 0.42 ms from the angle; 36,001 positions 0.6 ms less.
DIRECTION_MIN = 64

#: at most this many positions are solved by LAPACK's batched solve (a few
#: microseconds per call); longer sweeps by the structured elimination
#: (:func:`~mechcli.core.linkage.elimination.gauss`), which skips the zeros.  Measured
#: on 例 2-4 (2026-11-25): one position 0.31 vs 0.56 ms (0.35 vs 0.78 with the
#: condition numbers); even at 128 (0.83 vs 0.88 ms with them), the elimination ahead
#: from 256 (1.31 vs 0.98 ms).  With the condition numbers the closed form
#: (:func:`_solve_closed`) takes over from the same length (one position: 0.60 vs 0.40
#: ms the whole call by LAPACK); without them it is used at every length.
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


def _solve_closed(lay, A, b, flat, condition):
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
            seen = {id(v.v if type(v) is dyad_statics._Neg else v)
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


def _exact_zero(v):
    return (type(v) is float or type(v) is int) and v == 0


def _broadcasts(a, b):
    try:
        np.broadcast_shapes(a, b)
        return True
    except ValueError:
        return False


def solve_forces(topo: Topology, motion: LinkageMotion, bodies: Dict[int, Body], loads=(),
                 gravity=(0.0, 0.0), unit_motion: Optional[LinkageMotion] = None,
                 scale: Optional[float] = None, condition: bool = True) -> ForceResult:
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
    """
    linkage = topo.linkage
    frame = linkage.frame
    n = motion.feasible.shape
    flat = motion.feasible.size
    L = _facts(linkage).scale if scale is None else scale
    gx, gy = gravity

    def arr(x):
        # the common case, an array over the positions already: a view, no broadcast_to
        if type(x) is np.ndarray and x.dtype == np.float64 and x.shape in (n, (flat,)):
            return x.reshape(flat)
        return np.broadcast_to(np.asarray(x, dtype=float), n).reshape(flat)

    def coord(v):
        # a number that is the same at every position (a Python number, a fixed point's
        # stride-0 array) as a float, folded by the arithmetic; else the flat array
        c = const(v)
        return float(c) if type(c) is float or type(c) is int else arr(c)

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
    if np.ndim(L):
        # a batch of designs: one moment scale per design (flattened like the
        # positions), so each design's system is scaled as when solved alone
        L = arr(L)
    # the moment equations are scaled by L for the condition numbers and for the
    # general elimination's pivots; when every block is solved in closed form
    # without condition numbers the scaling changes nothing but round-off: skipped
    # (fewer passes over memory)
    plan = _plan(topo)
    Ls = 1.0 if not condition and CLOSED_FORM and plan.all_closed else L

    # cosine and sine of each link's angle, once per call (the centres of mass,
    # the loads and the virtual power share them)
    trig = {}

    def cos_sin(link):
        th = motion.links[link].theta
        cs = trig.get(id(th))
        if cs is None:  # keyed by the angle array: a block shares its guide's
            if type(th) is np.ndarray and th.ndim and not any(th.strides):
                # one angle at every position (a block on a fixed guide): floats
                t1 = th.reshape(-1)[:1]
                cs = (float(np.cos(t1)[0]), float(np.sin(t1)[0]), th)
            else:  # from the element's points if it can (cheaper than cos and sin but
                # for a few positions, where the calls cost more than the arithmetic)
                el = plan.direction_of.get(link) if th.size > DIRECTION_MIN else None
                u = el.direction(motion, link) if el is not None else None
                cs = (np.cos(th), np.sin(th), th) if u is None else (u[0], u[1], th)
            trig[id(th)] = cs
        return cs[0], cs[1]

    # centre of mass, its acceleration, and minus the known force/moment on each link
    # (the right-hand side of its equations: no negation pass)
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
            fx = arr(mh * arr(_sub(_add(const(p1.ax), const(p2.ax)), 2.0 * gx)).reshape(n))
            fy = arr(mh * arr(_sub(_add(const(p1.ay), const(p2.ay)), 2.0 * gy)).reshape(n))
        else:
            fx = arr(b.mass * _sub(arr(ax).reshape(n), gx))
            fy = arr(b.mass * _sub(arr(ay).reshape(n), gy))
        al = const(kl.alpha)
        m = (arr(b.inertia * arr(kl.alpha).reshape(n))
             if np.any(b.inertia) and not _exact_zero(al) else 0.0)
        minus[link] = [fx, fy, m]
    for ld in loads:
        if ld.link not in minus:
            raise ForceModelError(f"load '{ld.name}' is on link {ld.link}, which does not move",
                                  ("link", ld.link))
        f = minus[ld.link]
        tq, fx, fy = coord(ld.torque), coord(ld.fx), coord(ld.fy)
        if ld.relative:
            c, s = (arr(v) for v in cos_sin(ld.link))
            fx, fy = fx * c - fy * s, fx * s + fy * c
        if np.any(fx) or np.any(fy):
            origin = ld.origin
            if origin is not None and ld.link not in topo.members.get(origin, ()):
                raise ForceModelError(f"load '{ld.name}' acts at '{origin}', which is not on "
                                      f"link {ld.link}", ("point", origin))
            if origin is None:
                px, py = com[ld.link][0], com[ld.link][1]
            else:
                px, py = (arr(v) for v in _point(motion, topo, origin, ld.link, ld.along,
                                                 ld.normal, order=0, cos_sin=cos_sin))
            sx, sy = com[ld.link][0], com[ld.link][1]
            f[0] = _sub(f[0], fx)
            f[1] = _sub(f[1], fy)
            tq = _add(tq, _sub(_mul(px - sx, fy), _mul(py - sy, fx)))
        f[2] = _sub(f[2], tq)

    # the coefficients of this call: moment arms about the centres of mass
    # (scaled by L) and the directions of the prismatic pairs and slider drivers
    levers, directions = {}, {}

    # without the condition numbers, a closed-form block's link takes its moments about
    # its outer pair's point (_Plan.ref_point): the same solution, fewer passes; the
    # condition numbers are those of the system about the centres of mass
    ref = plan.ref_point if not condition and CLOSED_FORM else {}

    def lever(link, point):
        lv = levers.get((link, point))
        r = ref.get(link) if lv is None else None
        if r is not None:  # about the outer pair's point
            if point == r:
                lv = (0.0, 0.0)
            else:
                p, o = motion.points[point], motion.points[r]
                lv = (_div(_sub(coord(p.x), coord(o.x)), Ls),
                      _div(_sub(coord(p.y), coord(o.y)), Ls))
            levers[(link, point)] = lv
        if lv is None and point == com[link][2]:
            if _exact_zero(com[link][3]) and _exact_zero(com[link][4]):
                lv = levers[(link, point)] = (0.0, 0.0)  # the centre of mass itself
            elif link in com_off:  # a constant offset: floats
                off = com_off[link]
                lv = levers[(link, point)] = (_div(-off[0], Ls), _div(-off[1], Ls))
        if lv is None:
            p = motion.points[point]
            lv = levers[(link, point)] = (_div(arr(p.x) - com[link][0], Ls),
                                          _div(arr(p.y) - com[link][1], Ls))
        return lv

    def direction(key):
        u = directions.get(key)
        if u is None:
            if key[0] == "n":  # the left normal of a prismatic pair's guide
                c, s = cos_sin(topo.pairs[key[1]].block)
                u = (_neg(s if type(s) is float else arr(s)), c if type(c) is float else arr(c))
            else:  # a slider driver's line
                ang = linkage.driver(key[1]).angle
                u = (np.cos(ang), np.sin(ang))
                if np.ndim(ang):
                    u = (arr(u[0]), arr(u[1]))
            directions[key] = u
        return u

    def coef(spec):
        kind = spec[0]
        if kind == "c":
            return spec[1]
        if kind == "mx":
            return _mul(-spec[3], lever(spec[1], spec[2])[1])
        if kind == "my":
            return _mul(spec[3], lever(spec[1], spec[2])[0])
        ux, uy = direction(spec[3])
        if kind == "ux":
            return _mul(spec[4], ux)
        if kind == "uy":
            return _mul(spec[4], uy)
        dx, dy = lever(spec[1], spec[2])
        return _mul(spec[4], _sub(_mul(dx, uy), _mul(dy, ux)))

    rhs = [None] * plan.nrows
    for link in topo.links:
        e = plan.eq_of[link]
        f = minus[link]
        m = f[2]
        r = ref.get(link)
        if r is not None and not all(type(v) is float and v == 0.0 for v in f[:2]):
            # the known force moved from the centre of mass S to R: + (S - R) x f
            x, y, origin, along, normal = com[link]
            if origin == r and along is not None and _exact_zero(along) and \
                    _exact_zero(normal):
                off = None  # S is R
            elif origin == r and link in com_off:
                off = com_off[link]
            else:
                o = motion.points[r]
                off = (_sub(x, coord(o.x)), _sub(y, coord(o.y)))
            if off is not None:
                m = _add(m, _sub(_mul(off[0], f[1]), _mul(off[1], f[0])))
        rhs[e], rhs[e + 1], rhs[e + 2] = f[0], f[1], _div(m, Ls)

    # element blocks, from the last element back to the drivers (block
    # lower-triangular): each one's unknowns from its links' equations
    xs = [None] * len(plan.columns)  # scaled solution
    cond = np.ones(flat)
    for unk, rows, entries, solved, lay in plan.blocks:
        k = len(rows)
        A = [[0.0] * k for _ in range(k)]
        for i, j, spec in entries:
            A[i][j] = _add(A[i][j], coef(spec))
        b = [rhs[r] for r in rows]
        for i, u, spec in solved:
            b[i] = _sub(b[i], _mul(coef(spec), xs[u]))
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
    x = [_mul(v, Ls) if c else v for v, c in zip(xs, plan.is_couple)]
    pair_cols = [pc + ((direction(("n", pi)) if pr.kind == "P" else ()))
                 for pi, (pr, pc) in enumerate(zip(topo.pairs, plan.pair_cols))]
    driver_cols = plan.driver_cols

    # results
    balancing = {d.link: x[driver_cols[d.link]].reshape(n) for d in linkage.drivers}
    pairs = []
    for pi, pr in enumerate(topo.pairs):
        pc = pair_cols[pi]
        if pr.kind == "R":
            pairs.append(PairForce(pr, x[pc[0]].reshape(n), x[pc[1]].reshape(n),
                                   np.zeros(n)))
        else:
            nval, nx, ny = x[pc[0]], pc[2], pc[3]
            # (a float direction multiplied as such: a fixed guide's -0.0 kept)
            pairs.append(PairForce(pr, (nval * nx if type(nx) is float
                                        else value(_mul(nval, nx))).reshape(n),
                                   (nval * ny if type(ny) is float
                                    else value(_mul(nval, ny))).reshape(n),
                                   x[pc[1]].reshape(n)))
    # force and moment transmitted to the frame (about the origin), input power: folded
    # sums (no zeros to start from; a pending sign taken by the next term)
    sums = {"fx": 0.0, "fy": 0.0, "m": 0.0, "p": 0.0}
    terms = {k: [] for k in sums}

    def put(key, v, sign=1.0):
        sums[key] = _add(sums[key], v) if sign > 0 else _sub(sums[key], v)
        if type(v) is not float:
            terms[key].append(v)

    for pf in pairs:
        pr = pf.pair
        if frame not in (pr.i, pr.j):
            continue
        p = motion.points[pr.point]
        fx, fy = pf.fx.reshape(flat), pf.fy.reshape(flat)
        px, py = const(p.x), const(p.y)
        t = _sub(_mul(px if type(px) is float else arr(px), fy),
                 _mul(py if type(py) is float else arr(py), fx))
        if pr.kind == "P":
            t = _add(t, pf.couple.reshape(flat))
        # the force on the frame: + the pair's, or - when frame < link
        sign = 1.0 if pr.j == frame else -1.0
        put("fx", fx, sign)
        put("fy", fy, sign)
        put("m", t, sign)
    for d in linkage.drivers:
        val = balancing[d.link].reshape(flat)
        if d.rotary:
            put("m", val, -1.0)
            w = const(motion.links[d.link].omega)
            put("p", _mul(val, w if type(w) is float else arr(w)))
        else:
            p = motion.points[d.point]
            ux, uy = np.cos(d.angle), np.sin(d.angle)
            if np.ndim(d.angle):
                ux, uy = arr(ux), arr(uy)
            fx, fy = _mul(val, ux), _mul(val, uy)
            put("fx", fx, -1.0)
            put("fy", fy, -1.0)
            put("m", _sub(_mul(arr(p.x), fy), _mul(arr(p.y), fx)), -1.0)
            put("p", _mul(val, arr(motion.slides[d.slide_names(frame)[0]].v)))

    def own(key):
        # an array of its own: a sum of one term is that term (a pair's force) itself
        v = value(sums[key])
        if type(v) is float:
            return np.full(flat, v)
        return v.copy() if any(v is t for t in terms[key]) else v

    ffx, ffy, fm, power = own("fx"), own("fy"), own("m"), own("p")
    # global balance: Σ known forces (gravity, loads, inertia) = force on the frame
    # (minus the known forces, summed, plus the force on the frame: the same |d|)
    kfx = value(functools.reduce(_add, (minus[ln][0] for ln in topo.links), 0.0))
    kfy = value(functools.reduce(_add, (minus[ln][1] for ln in topo.links), 0.0))
    dx, dy = kfx + ffx, kfy + ffy  # |d| without hypot's cost (no overflow at forces)
    dx *= dx
    dy *= dy
    dx += dy
    force_residual = np.sqrt(dx, out=dx)
    # virtual power with the velocity coefficients: a second route to the balancing
    if unit_motion is not None:
        pres = np.zeros(flat)
        for d in linkage.drivers:
            val = balancing[d.link].reshape(flat)
            if d.rotary:
                pres += val * arr(unit_motion.links[d.link].omega)
            else:
                pres += val * arr(unit_motion.slides[d.slide_names(frame)[0]].v)
        for link in topo.links:
            f = minus[link]
            if all(type(v) is float and v == 0.0 for v in f):
                continue  # no known load on this link (massless, unloaded)
            x0, y0, origin, along, normal = com[link]
            # the same positions as the motion (as the callers solve it): its angles' trig
            # (only a centre off its origin needs the angle's trig)
            same = (along is None or (_exact_zero(along) and _exact_zero(normal))
                    or unit_motion.links[link].theta is motion.links[link].theta
                    or np.array_equal(unit_motion.links[link].theta,
                                      motion.links[link].theta))
            _x, _y, vx, vy, _a, _b = _point(unit_motion, topo, origin, link, along, normal,
                                             order=1, cos_sin=cos_sin if same else None)
            # the known moment is about the centre of mass: P = F·v_S + M·ω (f = -F, -M)
            pres -= value(_add(_add(_mul(f[0], arr(vx)), _mul(f[1], arr(vy))),
                               _mul(f[2], arr(unit_motion.links[link].omega))))
        power_residual = pres.reshape(n)
    else:
        power_residual = np.zeros(n)
    return ForceResult(balancing, pairs, (ffx.reshape(n), ffy.reshape(n)), fm.reshape(n),
                       power.reshape(n), cond.reshape(n), power_residual,
                       force_residual.reshape(n),
                       {ln: (com[ln][0].reshape(n), com[ln][1].reshape(n)) for ln in topo.links})
