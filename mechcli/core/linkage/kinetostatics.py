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
positions at once by a batched Gaussian elimination with partial pivoting,
from the last dyad back to the drivers.  :func:`square_system` assembles the
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

import dataclasses
from typing import Dict, Optional, Tuple

import numpy as np

from mechcli.core.linkage import (RPR, RRP, RRR, Crank, Ground, Linkage, LinkageMotion,
                                  PointOnLink, SliderDriver)

#: condition number of an element block above which a position is flagged
#: (reactions then carry ~cond * 1e-16 relative error)
COND_FLAG = 1e8


class ForceModelError(ValueError):
    """The linkage, bodies or loads cannot be modelled (bad point or link)."""

    def __init__(self, message, what=None):
        super().__init__(message)
        self.what = what


# ---------------------------------------------------------------------------
# model description
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Body:
    """Inertia of one moving link.

    The centre of mass is ``origin + (along + i*normal) * exp(i*theta_link)``
    (as :class:`~mechcli.core.linkage.PointOnLink`); ``mass`` [kg] and
    ``inertia`` J_S about the centre of mass [kg m^2].
    """

    link: int
    mass: float = 0.0
    inertia: float = 0.0
    origin: Optional[str] = None
    along: float = 0.0
    normal: float = 0.0


@dataclasses.dataclass(frozen=True)
class Load:
    """An external force (at a point of a link) or torque on a link.

    ``fx``, ``fy`` [N] (a force) or ``torque`` [N m]: scalars or arrays over
    the positions (already multiplied by any table factor and active mask).
    The force acts at ``origin + (along + i*normal) * exp(i*theta_link)``
    (default: the link's centre of mass).  With ``relative`` the force's
    components are in the link's own axes (along, left normal).
    """

    name: str
    link: int
    fx: object = 0.0
    fy: object = 0.0
    torque: object = 0.0
    origin: Optional[str] = None
    along: float = 0.0
    normal: float = 0.0
    relative: bool = False


@dataclasses.dataclass(frozen=True)
class Pair:
    """A kinematic pair between links ``i < j`` at point ``point``.

    ``kind`` is ``"R"`` (revolute) or ``"P"`` (prismatic; ``guide`` is the
    link that carries the guide line, ``block`` the sliding one).
    """

    i: int
    j: int
    kind: str
    point: str
    element: int
    guide: Optional[int] = None
    block: Optional[int] = None

    @property
    def label(self):
        sep = "_" if self.i >= 10 or self.j >= 10 else ""
        return f"{self.i}{sep}{self.j}"


@dataclasses.dataclass(frozen=True)
class Topology:
    """Pairs, drivers and link reference points of a linkage.

    ``frames[link] = (origin, second)``: the point the link's local
    coordinates start from and the second point that fixes its length (None
    for a block or a guide with no point on it); the default centre of mass is
    their midpoint (or the origin).
    """

    linkage: Linkage
    links: Tuple[int, ...]
    pairs: Tuple[Pair, ...]
    members: Dict[str, frozenset]
    owner: Dict[str, int]
    frames: Dict[int, Tuple[str, Optional[str]]]
    blocks: Tuple[Tuple[int, Tuple[int, ...], Tuple[int, ...]], ...]


def topology(linkage: Linkage) -> Topology:
    """Derive the pairs of a linkage from its elements (see the module notes)."""
    frame = linkage.frame
    owner: Dict[str, int] = {}
    members: Dict[str, set] = {}
    frames: Dict[int, list] = {}
    pairs = []
    blocks = []

    def put(point, link):
        members.setdefault(point, set()).add(link)

    def new_point(point, link):
        owner[point] = link
        put(point, link)

    def rev(point, link, idx):
        a = owner[point]
        put(point, link)
        pairs.append(Pair(min(a, link), max(a, link), "R", point, idx))

    def pri(guide, block, point, idx):
        pairs.append(Pair(min(guide, block), max(guide, block), "P", point, idx, guide, block))

    for idx in linkage.order:
        el = linkage.elements[idx]
        start = len(pairs)
        if isinstance(el, Ground):
            new_point(el.name, frame)
            continue
        if isinstance(el, PointOnLink):
            if el.link not in members.get(el.origin, ()):
                raise ForceModelError(
                    f"point '{el.name}' is placed from '{el.origin}', which is not on link "
                    f"{el.link}", ("point", el.name))
            new_point(el.name, el.link)
            if frames[el.link][1] is None:
                frames[el.link][1] = el.name
            continue
        if isinstance(el, Crank):
            rev(el.pivot, el.link, idx)
            new_point(el.point, el.link)
            frames[el.link] = [el.pivot, el.point]
            new_links = (el.link,)
        elif isinstance(el, SliderDriver):
            if owner.get(el.origin) != frame:
                raise ForceModelError(
                    f"the slider driver of link {el.link} needs its origin '{el.origin}' on "
                    "the frame", ("link", el.link))
            new_point(el.point, el.link)
            pri(frame, el.link, el.point, idx)
            frames[el.link] = [el.point, None]
            new_links = (el.link,)
        elif isinstance(el, RRR):
            rev(el.point_a, el.link_a, idx)
            new_point(el.joint, el.link_a)
            put(el.joint, el.link_b)
            pairs.append(Pair(min(el.link_a, el.link_b), max(el.link_a, el.link_b), "R",
                              el.joint, idx))
            rev(el.point_b, el.link_b, idx)
            frames[el.link_a] = [el.point_a, el.joint]
            frames[el.link_b] = [el.point_b, el.joint]
            new_links = (el.link_a, el.link_b)
        elif isinstance(el, RRP):
            rev(el.point, el.link, idx)
            new_point(el.joint, el.link)
            put(el.joint, el.slider)
            pairs.append(Pair(min(el.link, el.slider), max(el.link, el.slider), "R",
                              el.joint, idx))
            pri(el.guide_link, el.slider, el.joint, idx)
            frames[el.link] = [el.point, el.joint]
            frames[el.slider] = [el.joint, None]
            new_links = (el.link, el.slider)
        elif isinstance(el, RPR):
            rev(el.point, el.block, idx)
            pri(el.guide, el.block, el.point, idx)
            rev(el.pivot, el.guide, idx)
            frames[el.block] = [el.point, None]
            frames[el.guide] = [el.pivot, None]
            new_links = (el.block, el.guide)
        else:  # pragma: no cover - the engine has no other element
            raise ForceModelError(f"unsupported element {el!r}")
        blocks.append((idx, new_links, tuple(range(start, len(pairs)))))
    links = tuple(ln for _, nl, _ in blocks for ln in nl)
    return Topology(linkage, links, tuple(pairs), {k: frozenset(v) for k, v in members.items()},
                    owner, {k: (v[0], v[1]) for k, v in frames.items()}, tuple(blocks))


def com_of(topo: Topology, body: Optional[Body], link):
    """``(origin, along, normal)`` of a link's centre of mass; ``along is None``
    means the midpoint of the link's two points (the default)."""
    if body is not None and body.origin is not None:
        return body.origin, body.along, body.normal
    origin, second = topo.frames[link]
    return (origin, 0.0, 0.0) if second is None else (origin, None, None)


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class PairForce:
    """Reaction of a pair over the positions: force of ``i`` on ``j`` (fx, fy) [N]
    and, for a prismatic pair, the couple of ``i`` on ``j`` [N m] about the
    pair's point (zero for a revolute pair)."""

    pair: Pair
    fx: np.ndarray
    fy: np.ndarray
    couple: np.ndarray

    @property
    def magnitude(self):
        return np.hypot(self.fx, self.fy)


@dataclasses.dataclass(frozen=True)
class ForceResult:
    """Kinetostatics over the positions of a motion.

    Attributes
    ----------
    balancing : dict
        ``{driver link: array}``: torque [N m] on a crank, force [N] along a
        slider driver's line.
    pairs : list of PairForce
        In the order of the topology's pairs.
    frame_force : (ndarray, ndarray)
        Force transmitted to the frame (through its pairs and the drives) [N].
    frame_moment : ndarray
        Moment transmitted to the frame about the origin (0, 0) [N m].
    input_power : ndarray
        Σ balancing · driver speed [W].
    cond : ndarray
        Largest 1-norm condition number of the (scaled) element blocks.
    power_residual : ndarray
        Virtual-power balance Σ balancing·ω* + Σ known loads·v* (ω*, v* per unit
        primary input speed): zero up to round-off (a second route to Mb).
    force_residual : ndarray
        |Σ external + gravity + frame reactions − Σ m a_S| over the mechanism [N].
    active : dict
        ``{load name: bool array}`` (only for conditional loads; set by callers).
    """

    balancing: Dict[int, np.ndarray]
    pairs: list
    frame_force: Tuple[np.ndarray, np.ndarray]
    frame_moment: np.ndarray
    input_power: np.ndarray
    cond: np.ndarray
    power_residual: np.ndarray
    force_residual: np.ndarray
    com: Dict[int, Tuple[np.ndarray, np.ndarray]]


# ---------------------------------------------------------------------------
# batched sparse Gaussian elimination
# ---------------------------------------------------------------------------
def _nonzero(v):
    return not (isinstance(v, float) and v == 0.0)


def _gauss(A, B):
    """Solve ``A X = B`` at every position by Gaussian elimination.

    ``A`` is a k x k list of lists whose entries are Python floats (the same at
    every position; exact zeros are skipped) or arrays over the positions;
    ``B`` a list of k arrays of shape (..., N).  A column with a constant pivot
    of magnitude >= 0.5 (the +-1 of a force equation) is eliminated with it;
    otherwise the pivot is chosen per position among the candidate rows
    (partial pivoting).  An exactly singular position gives zeros, never inf or
    NaN, and is reported in the returned mask.
    """
    k = len(A)
    A = [list(r) for r in A]
    B = list(B)
    free = list(range(k))
    pivots = []
    singular = None
    for c in range(k):
        cand = [r for r in free if _nonzero(A[r][c])]
        const = [r for r in cand if isinstance(A[r][c], float) and abs(A[r][c]) >= 0.5]
        if const:
            p = max(const, key=lambda r: abs(A[r][c]))
        elif len(cand) == 1:
            p = cand[0]
        elif cand:
            # partial pivoting per position among the candidate rows
            mags = np.stack([np.abs(np.broadcast_to(A[r][c], B[0].shape[-1:])) for r in cand])
            sel = np.argmax(mags, axis=0)
            p = cand[0]
            if np.any(sel != 0):
                rows = [A[r] for r in cand]
                rhs = [B[r] for r in cand]
                new0 = [np.choose(sel, [np.broadcast_to(row[j], sel.shape) for row in rows])
                        if any(_nonzero(row[j]) for row in rows) else 0.0 for j in range(k)]
                rhs0 = np.choose(sel, rhs) if B[0].ndim == 1 else np.where(
                    sel == 0, rhs[0], 0.0) + sum(np.where(sel == i, rhs[i], 0.0)
                                                 for i in range(1, len(cand)))
                for i, r in enumerate(cand[1:], start=1):
                    hit = sel == i
                    A[r] = [np.where(hit, rows[0][j], rows[i][j])
                            if _nonzero(rows[0][j]) or _nonzero(rows[i][j]) else 0.0
                            for j in range(k)]
                    B[r] = np.where(hit, rhs[0], rhs[i])
                A[p], B[p] = new0, rhs0
        else:
            p = free[0]  # a structurally singular column
        free.remove(p)
        pivots.append(p)
        piv = A[p][c]
        if isinstance(piv, float):
            if piv == 0.0:
                singular = np.ones(B[0].shape[-1], dtype=bool)
                piv = 1.0
        else:
            zero = piv == 0.0
            if zero.any():
                singular = zero if singular is None else singular | zero
                piv = np.where(zero, 1.0, piv)
        inv = 1.0 / piv
        for r in free:
            if not _nonzero(A[r][c]):
                continue
            f = A[r][c] * inv
            A[r][c] = 0.0
            for j in range(c + 1, k):
                if _nonzero(A[p][j]):
                    A[r][j] = A[r][j] - f * A[p][j]
            B[r] = B[r] - f * B[p]
        A[p][c] = piv
    X = [None] * k
    for c in range(k - 1, -1, -1):
        p = pivots[c]
        acc = B[p]
        for j in range(c + 1, k):
            if _nonzero(A[p][j]):
                acc = acc - A[p][j] * X[j]
        X[c] = acc / A[p][c]
    if singular is not None and singular.any():
        X = [np.where(singular, 0.0, x) for x in X]
    return X, singular


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
    L = scale or linkage.scale()
    gx, gy = gravity

    def arr(x):
        return np.broadcast_to(np.asarray(x, dtype=float), n).reshape(flat)

    # centre of mass, its acceleration, and the known force/moment on each link
    com, known = {}, {}
    for link in topo.links:
        b = bodies.get(link) or Body(link)
        origin, along, normal = com_of(topo, b, link)
        x, y, _vx, _vy, ax, ay = _point(motion, topo, origin, link, along, normal)
        x, y = arr(x), arr(y)
        com[link] = (x, y, origin, along, normal)
        kl = motion.links[link]
        fx = b.mass * (gx - arr(ax))
        fy = b.mass * (gy - arr(ay))
        m = -b.inertia * arr(kl.alpha) if b.inertia else np.zeros(flat)
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
        if isinstance(d, Crank):
            col.append((eq_of[d.link] + 2, 1.0 / L))
        else:
            p = motion.points[d.point]
            ux, uy = np.cos(d.angle), np.sin(d.angle)
            add_force(col, None, d.link, 1.0, arr(p.x), arr(p.y), ux, uy)
        driver_cols[d.link] = len(columns)
        columns.append(col)
        owners.append(("D", d.link, 0))
    # couples and balancing torques: the scaled unknown is value / L
    is_couple = [o[0] == "P" and o[2] == 1 or (o[0] == "D" and isinstance(
        _driver(linkage, o[1]), Crank)) for o in owners]

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
        if isinstance(el, (Crank, SliderDriver)):
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
            full = [[np.broadcast_to(np.abs(v), (flat,)) for v in row] for row in A]
            nrm = np.max([sum(full[i][j] for i in range(k)) for j in range(k)], axis=0)
            b = [np.concatenate([bi[None, :], np.eye(k)[i][:, None] + np.zeros((1, flat))])
                 for i, bi in enumerate(b)]
        X, sing = _gauss(A, b)
        if condition:
            inv_nrm = np.max([sum(np.abs(X[i][1 + j]) for i in range(k)) for j in range(k)],
                             axis=0)
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
        if isinstance(d, Crank):
            fm -= val
            power += val * arr(motion.links[d.link].omega)
        else:
            p = motion.points[d.point]
            ux, uy = np.cos(d.angle), np.sin(d.angle)
            ffx -= val * ux
            ffy -= val * uy
            fm -= arr(p.x) * val * uy - arr(p.y) * val * ux
            power += val * arr(motion.slides[d.name or str(d.link)].v)
    # global balance: Σ known forces (gravity, loads, inertia) = force on the frame
    kfx = sum(known[ln][0] for ln in topo.links)
    kfy = sum(known[ln][1] for ln in topo.links)
    force_residual = np.hypot(kfx - ffx, kfy - ffy)
    # virtual power with the velocity coefficients: a second route to the balancing
    if unit_motion is not None:
        pres = np.zeros(flat)
        for d in linkage.drivers:
            val = balancing[d.link].reshape(flat)
            if isinstance(d, Crank):
                pres += val * arr(unit_motion.links[d.link].omega)
            else:
                pres += val * arr(unit_motion.slides[d.name or str(d.link)].v)
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


def _driver(linkage, link):
    for d in linkage.drivers:
        if d.link == link:
            return d
    raise KeyError(link)


# ---------------------------------------------------------------------------
# load programs: constant, tabulated, conditional
# ---------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class LoadProgram:
    """A load with its program over the input.

    ``window`` (lo, hi) of the primary input [rad or m] (periodic in 2*pi when
    ``rotary``; lo > hi wraps through 0); ``velocity`` a
    :class:`~mechcli.core.linkage.kinematics.Quantity` whose sign must be ``sign``;
    ``slide`` a slide quantity that must lie within ``band`` (absolute limits
    [m], see :meth:`with_band_limits`; fractions of the stroke until then);
    ``table`` (xs, ys) a factor tabulated against the input (linear, periodic
    when rotary).
    """

    load: Load
    window: Optional[Tuple[float, float]] = None
    rotary: bool = True
    velocity: object = None
    sign: int = 0
    slide: object = None
    band: Optional[Tuple[float, float]] = None
    table: Optional[Tuple[np.ndarray, np.ndarray]] = None
    band_limits: Optional[Tuple[float, float]] = None

    @property
    def conditional(self):
        return self.window is not None or self.velocity is not None or self.band is not None

    def with_band_limits(self, s_min, s_max):
        """Fix the band to absolute slide limits from the slide's stroke."""
        lo, hi = self.band
        h = s_max - s_min
        return dataclasses.replace(self, band_limits=(s_min + lo * h, s_min + hi * h))

    def active(self, q, motion):
        """Boolean mask of the positions where the load acts."""
        q = np.asarray(q, dtype=float)
        on = np.ones(q.shape, dtype=bool)
        if self.window is not None:
            lo, hi = self.window
            if self.rotary:
                two_pi = 2 * np.pi
                x = np.mod(q - lo, two_pi)
                width = np.mod(hi - lo, two_pi)
                if hi - lo >= two_pi:
                    width = two_pi
                # inclusive at both ends, to round-off of the input grid
                tol = 1e-12 * two_pi
                on &= (x <= width + tol) | (x >= two_pi - tol)
            else:
                on &= (q >= lo) & (q <= hi)
        if self.velocity is not None:
            v = np.asarray(self.velocity.get(motion))
            on &= (v > 0) if self.sign > 0 else (v < 0)
        if self.band_limits is not None:
            s = np.asarray(self.slide.get(motion))
            lo, hi = self.band_limits
            on &= (s >= lo) & (s <= hi)
        return on

    def factor(self, q):
        if self.table is None:
            return 1.0
        xs, ys = self.table
        if self.rotary:
            # periodic: close the table over one turn (the last point joins the first)
            period = 2 * np.pi
            if xs[-1] - xs[0] < period * (1 - 1e-12):
                xs = np.append(xs, xs[0] + period)
                ys = np.append(ys, ys[0])
            return np.interp(np.mod(q - xs[0], period) + xs[0], xs, ys)
        return np.interp(q, xs, ys)

    def evaluate(self, q, motion):
        """The load with its components as arrays over ``q``; and the active mask."""
        on = self.active(q, motion)
        f = np.where(on, 1.0, 0.0) * self.factor(q)
        ld = self.load
        return dataclasses.replace(ld, fx=ld.fx * f, fy=ld.fy * f, torque=ld.torque * f), on
