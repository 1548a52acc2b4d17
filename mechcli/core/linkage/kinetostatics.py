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
square linear system per position.  It is assembled from the engine's topology
and, because every driver and every dyad of the engine is a statically
determinate group (an Assur group), it is block lower-triangular in the
reverse solving order: each element's 3 or 6 unknowns are solved for all
positions at once by a batched Gaussian elimination with partial pivoting
(:mod:`.elimination`), from the last dyad back to the drivers.  The model
(bodies, loads, pairs, results) is in :mod:`.force_model`, the load programs
in :mod:`.loads`.  :func:`square_system` assembles the
whole matrix of one position (for tests and inspection).

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

from typing import Dict, Optional

import numpy as np

from mechcli.core.linkage.elimination import gauss
from mechcli.core.linkage.engine import LinkageMotion
# the model and the load programs, re-exported: this module is the entry point
from mechcli.core.linkage.force_model import (COND_FLAG, Body, ForceModelError,  # noqa: F401
                                              ForceResult, Load, Pair, PairForce, Topology,
                                              com_of, topology)
from mechcli.core.linkage.loads import LoadProgram  # noqa: F401

# ---------------------------------------------------------------------------
# solve
# ---------------------------------------------------------------------------
def _point(motion, topo, origin, link, along, normal, order=2):
    """Position (and velocity, acceleration) of a point fixed on ``link``."""
    o = motion.points[origin]
    k = motion.links[link]
    if along is None:  # the midpoint of the link's two points
        second = motion.points[topo.frames[link][1]]
        x, y = 0.5 * (o.x + second.x), 0.5 * (o.y + second.y)
        if order == 0:
            return x, y
        return (x, y, 0.5 * (o.vx + second.vx), 0.5 * (o.vy + second.vy),
                0.5 * (o.ax + second.ax) if order > 1 else None,
                0.5 * (o.ay + second.ay) if order > 1 else None)
    c, s = np.cos(k.theta), np.sin(k.theta)
    rx = along * c - normal * s
    ry = along * s + normal * c
    if order == 0:
        return o.x + rx, o.y + ry
    w = k.omega
    vx, vy = o.vx - w * ry, o.vy + w * rx
    if order == 1:
        return o.x + rx, o.y + ry, vx, vy, None, None
    w2 = w * w
    return (o.x + rx, o.y + ry, vx, vy,
            o.ax - k.alpha * ry - w2 * rx, o.ay + k.alpha * rx - w2 * ry)


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
    L = linkage.scale() if scale is None else scale
    gx, gy = gravity

    def arr(x):
        # the common case, an array over the positions already: a view, no broadcast_to
        if type(x) is np.ndarray and x.dtype == np.float64 and x.shape in (n, (flat,)):
            return x.reshape(flat)
        return np.broadcast_to(np.asarray(x, dtype=float), n).reshape(flat)

    for what, obj, fields in ([(f"body of link {k}", b, ("mass", "inertia", "along", "normal"))
                               for k, b in bodies.items()]
                              + [(f"load '{ld.name}'", ld, ("fx", "fy", "torque", "along",
                                                            "normal")) for ld in loads]):
        for f in fields:
            sh = np.shape(getattr(obj, f))
            if sh and not (_broadcasts(sh, n) and np.broadcast_shapes(sh, n) == n):
                raise ValueError(f"{what}: {f} of shape {sh} does not broadcast to the "
                                 f"motion's shape {n} (a batch of designs needs a batched "
                                 "linkage or input)")
    if np.ndim(L):
        # a batch of designs: one moment scale per design (flattened like the
        # positions), so each design's system is scaled as when solved alone
        L = arr(L)

    # centre of mass, its acceleration, and the known force/moment on each link
    com, known = {}, {}
    for link in topo.links:
        b = bodies.get(link) or Body(link)
        origin, along, normal = com_of(topo, b, link)
        x, y, _vx, _vy, ax, ay = _point(motion, topo, origin, link, along, normal)
        x, y = arr(x), arr(y)
        com[link] = (x, y, origin, along, normal)
        kl = motion.links[link]
        # masses and inertias may be arrays of a batch of designs: arr() flattens
        # them with the positions
        fx = arr(b.mass * (gx - arr(ax).reshape(n)))
        fy = arr(b.mass * (gy - arr(ay).reshape(n)))
        m = (arr(-b.inertia * arr(kl.alpha).reshape(n)) if np.any(b.inertia)
             else np.zeros(flat))
        known[link] = [fx, fy, m]
    for ld in loads:
        if ld.link not in known:
            raise ForceModelError(f"load '{ld.name}' is on link {ld.link}, which does not move",
                                  ("link", ld.link))
        f = known[ld.link]
        tq = arr(ld.torque)
        fx, fy = arr(ld.fx), arr(ld.fy)
        if ld.relative:
            th = arr(motion.links[ld.link].theta)
            c, s = np.cos(th), np.sin(th)
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
                                                 ld.normal, order=0))
            sx, sy = com[ld.link][0], com[ld.link][1]
            f[0] = f[0] + fx
            f[1] = f[1] + fy
            tq = tq + (px - sx) * fy - (py - sy) * fx
        f[2] = f[2] + tq

    eq_of = {link: 3 * i for i, link in enumerate(topo.links)}
    # unknown columns: list of (eq row, coefficient array) per unknown; moment
    # rows are divided by L and couple unknowns multiplied by L (scaled system)
    columns, owners = [], []  # owners: (kind, pair index or driver link, component)

    def lever(link, px, py):
        return (px - com[link][0]) / L, (py - com[link][1]) / L

    def add_force(col_x, col_y, link, sign, px, py, ux=None, uy=None):
        if link == frame:
            return
        e = eq_of[link]
        dx, dy = lever(link, px, py)
        if ux is None:
            col_x.append((e, sign * 1.0)); col_x.append((e + 2, -sign * dy))
            col_y.append((e + 1, sign * 1.0)); col_y.append((e + 2, sign * dx))
        else:
            col_x.append((e, sign * ux)); col_x.append((e + 1, sign * uy))
            col_x.append((e + 2, sign * (dx * uy - dy * ux)))

    pair_cols = []
    for pi, pr in enumerate(topo.pairs):
        p = motion.points[pr.point]
        px, py = arr(p.x), arr(p.y)
        if pr.kind == "R":
            cx, cy = [], []
            for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
                add_force(cx, cy, link, sign, px, py)
            pair_cols.append((len(columns), len(columns) + 1))
            columns += [cx, cy]
            owners += [("R", pi, 0), ("R", pi, 1)]
        else:
            th = arr(motion.links[pr.block].theta)
            nx, ny = -np.sin(th), np.cos(th)  # left normal of the guide
            cn, cm = [], []
            for link, sign in ((pr.j, 1.0), (pr.i, -1.0)):
                add_force(cn, None, link, sign, px, py, nx, ny)
                if link != frame:
                    cm.append((eq_of[link] + 2, sign / L))
            pair_cols.append((len(columns), len(columns) + 1, nx, ny))
            columns += [cn, cm]
            owners += [("P", pi, 0), ("P", pi, 1)]
    driver_cols = {}
    for d in linkage.drivers:
        col = []
        if d.rotary:
            col.append((eq_of[d.link] + 2, 1.0 / L))
        else:
            p = motion.points[d.point]
            ux, uy = np.cos(d.angle), np.sin(d.angle)
            if np.ndim(d.angle):
                ux, uy = arr(ux), arr(uy)
            add_force(col, None, d.link, 1.0, arr(p.x), arr(p.y), ux, uy)
        driver_cols[d.link] = len(columns)
        columns.append(col)
        owners.append(("D", d.link, 0))
    # couples and balancing torques: the scaled unknown is value / L
    is_couple = [o[0] == "P" and o[2] == 1 or (o[0] == "D" and linkage.driver(o[1]).rotary)
                 for o in owners]

    rhs = np.zeros((3 * len(topo.links), flat))
    for link in topo.links:
        e = eq_of[link]
        f = known[link]
        rhs[e] = -f[0]
        rhs[e + 1] = -f[1]
        rhs[e + 2] = -f[2] / L

    # element blocks: unknowns of the element's pairs (and its driver), rows of its links
    x = [None] * len(columns)
    cond = np.ones(flat)
    for idx, new_links, pidx in reversed(topo.blocks):
        unk = []
        for pi in pidx:
            unk += list(pair_cols[pi][:2])
        el = linkage.elements[idx]
        if el.is_driver:
            unk.append(driver_cols[el.link])
        rows = [eq_of[ln] + c for ln in new_links for c in range(3)]
        k = len(rows)
        if len(unk) != k:  # pragma: no cover - every engine element is determinate
            raise ForceModelError(f"element {idx} is not statically determinate")
        row_pos = {r: i for i, r in enumerate(rows)}
        A = [[0.0] * k for _ in range(k)]
        for jc, u in enumerate(unk):
            f = L if is_couple[u] else 1.0  # couple unknowns scaled by 1/L
            for r, coef in columns[u]:
                if r in row_pos:
                    A[row_pos[r]][jc] = A[row_pos[r]][jc] + coef * f
        b = [rhs[r] for r in rows]
        # contributions of already solved unknowns (later elements) on these rows
        for u, val in enumerate(x):
            if val is None:
                continue
            for r, coef in columns[u]:
                if r in row_pos:
                    b[row_pos[r]] = b[row_pos[r]] - coef * val
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
        if condition:
            inv_nrm = np.zeros(flat)
            for j in range(k):
                np.maximum(inv_nrm, sum(np.abs(X[i][1 + j]) for i in range(k)), out=inv_nrm)
            c_blk = nrm * inv_nrm
            if sing is not None:
                c_blk = np.where(sing, np.inf, c_blk)
            cond = np.maximum(cond, c_blk)
            X = [xi[0] for xi in X]
        for jc, u in enumerate(unk):
            x[u] = X[jc] * (L if is_couple[u] else 1.0)

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
            pairs.append(PairForce(pr, (nval * nx).reshape(n), (nval * ny).reshape(n),
                                   x[pc[1]].reshape(n)))
    # force and moment transmitted to the frame (about the origin)
    ffx, ffy, fm = np.zeros(flat), np.zeros(flat), np.zeros(flat)
    for pf in pairs:
        pr = pf.pair
        if frame not in (pr.i, pr.j):
            continue
        sign = 1.0 if pr.j == frame else -1.0  # force on the frame
        p = motion.points[pr.point]
        fx, fy = sign * pf.fx.reshape(flat), sign * pf.fy.reshape(flat)
        ffx += fx
        ffy += fy
        fm += arr(p.x) * fy - arr(p.y) * fx + sign * pf.couple.reshape(flat)
    power = np.zeros(flat)
    for d in linkage.drivers:
        val = balancing[d.link].reshape(flat)
        if d.rotary:
            fm -= val
            power += val * arr(motion.links[d.link].omega)
        else:
            p = motion.points[d.point]
            ux, uy = np.cos(d.angle), np.sin(d.angle)
            if np.ndim(d.angle):
                ux, uy = arr(ux), arr(uy)
            ffx -= val * ux
            ffy -= val * uy
            fm -= arr(p.x) * val * uy - arr(p.y) * val * ux
            power += val * arr(motion.slides[d.slide_names(frame)[0]].v)
    # global balance: Σ known forces (gravity, loads, inertia) = force on the frame
    kfx = sum(known[ln][0] for ln in topo.links)
    kfy = sum(known[ln][1] for ln in topo.links)
    force_residual = np.hypot(kfx - ffx, kfy - ffy)
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
            x0, y0, origin, along, normal = com[link]
            _x, _y, vx, vy, _a, _b = _point(unit_motion, topo, origin, link, along, normal,
                                             order=1)
            f = known[link]
            # the known moment is about the centre of mass: P = F·v_S + M·ω
            pres += f[0] * arr(vx) + f[1] * arr(vy) + f[2] * arr(unit_motion.links[link].omega)
        power_residual = pres.reshape(n)
    else:
        power_residual = np.zeros(n)
    return ForceResult(balancing, pairs, (ffx.reshape(n), ffy.reshape(n)), fm.reshape(n),
                       power.reshape(n), cond.reshape(n), power_residual,
                       force_residual.reshape(n),
                       {ln: (com[ln][0].reshape(n), com[ln][1].reshape(n)) for ln in topo.links})
