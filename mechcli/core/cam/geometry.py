"""Disc-cam geometry by the inversion method (反转法), with exact normals.

The follower, the pitch and working profiles, their normals, curvature and
pressure angle per cam angle, the corners of the pitch curve and the working
outline drawn round them.  The refined extrema over the cycle are in
:mod:`mechcli.core.cam.checks`, the base-circle sizing in
:mod:`mechcli.core.cam.sizing`.

Every follower is described in the *fixed* frame (cam centre O at the origin,
follower guide along +y): a reference point ``P(δ)`` (roller centre / knife
edge / flat-face contact point) with its exact derivatives with respect to the
cam angle δ.  The cam-fixed profile is ``Q(δ) = R(-σδ) P(δ)`` where
``σ = +1`` for a counter-clockwise cam and ``-1`` for a clockwise one; its
derivatives follow from ``Q⁽ᵏ⁾ = R(-σδ) Vₖ`` with ``V₀ = P`` and
``Vₖ₊₁ = Vₖ' − σ J Vₖ`` (``J`` = rotation by +90°).  Tangent, normal, pressure
angle and curvature are computed from ``V₁, V₂, V₃`` (rotation invariants),
never by differencing samples.

Notes
-----
Counter-clockwise cam, follower right of the centre: ``P = (e, s₀ + s)`` gives
eq. (4-1) of the book; the working curve of a roller follower is the pitch
curve moved by ``r_r`` along the inner normal (eq. 4-2 with the normal of eq.
4-3).  Flat-faced follower: the contact point ``P = (σ s', r₀ + s)`` gives eq.
(4-4).  Oscillating follower with pivot ``A = (0, a)`` and arm ``l``:
``P = A + l (−κ sin θ, −cos θ)``, ``θ = φ₀ + φ``, κ = +1 for the arm on the
left (图 4-3) gives eq. (4-5); φ₀ from the law of cosines (eq. 4-6).  A
clockwise cam with the arm on the right is the mirror image (x → −x) of the
counter-clockwise one with the arm on the left.  Pressure angle: angle between the profile normal at
the contact and the velocity of the follower point (eq. 7-14 for the
translating follower).
"""

from __future__ import annotations

import math
from typing import Any, List, Optional, Tuple

import numpy as np

from mechcli.core.cam.motion import MotionProgram
from mechcli.core.errors import DescribedError
from mechcli.core.numerics import sign_changes
from mechcli.core.records import record

FOLLOWER_MOTIONS = ("translating", "oscillating")
FOLLOWER_CONTACTS = ("knife", "roller", "flat")

#: |ρ| is reported at most RHO_CAP × r0 (a straight stretch has ρ = ∞)
RHO_CAP = 1e6


class CamError(DescribedError):
    """A cam problem without solution (``reason`` and ``values``: see
    :class:`~mechcli.core.errors.DescribedError`)."""


class UndercutError(CamError):
    """The working profile has a cusp or loop (undercut) and the spec forbids it."""


class CamGeometryError(CamError):
    """The follower cannot be placed as asked (e.g. swing past the geometric limit)."""


@record
class Follower:
    """Follower type and mechanism dimensions (SI units).

    Attributes
    ----------
    motion : str
        ``translating`` (直动) or ``oscillating`` (摆动).
    contact : str
        ``knife`` (尖顶), ``roller`` (滚子) or ``flat`` (平底; translating only).
    r0 : float
        Base-circle radius, m (of the pitch curve for knife/roller followers,
        of the working curve for the flat-faced follower).
    rotation : int
        +1 for a counter-clockwise cam (the book's examples), −1 clockwise.
    e : float
        Signed offset of the translating follower's guide, m (positive: right
        of the cam centre when the follower points up).
    rr : float
        Roller radius, m (0 for knife-edge and flat-faced followers).
    a : float
        Centre distance cam–pivot of an oscillating follower, m.
    l : float
        Arm length of an oscillating follower, m.
    arm : int or None
        Oscillating follower: +1 when the arm reaches from the pivot to the left
        of the line pivot–cam centre (图 4-3), −1 to the right; None (default)
        means the side that makes the follower swing out in the cam's sense of
        rotation (left for a ccw cam as in 图 4-3, right for a cw cam).
    """

    motion: str
    contact: str
    r0: float
    rotation: int = 1
    e: float = 0.0
    rr: float = 0.0
    a: float = 0.0
    l: float = 0.0
    arm: int | None = None

    def __post_init__(self) -> None:
        if self.motion not in FOLLOWER_MOTIONS or self.contact not in FOLLOWER_CONTACTS:
            raise ValueError(f"unknown follower {self.motion}/{self.contact}")
        if self.rotation not in (1, -1):
            raise ValueError("rotation must be +1 (ccw) or -1 (cw)")
        if self.arm not in (None, 1, -1):
            raise ValueError("arm must be +1 (left), -1 (right) or None")
        if not self.r0 > 0:
            raise ValueError("r0 must be positive")
        if self.motion == "translating" and self.contact != "flat" and abs(self.e) >= self.r0:
            raise ValueError("the offset must be smaller than the base radius")
        if self.motion == "oscillating":
            if self.contact == "flat":
                raise ValueError("an oscillating flat-faced follower is not supported")
            if not (abs(self.a - self.l) < self.r0 < self.a + self.l):
                raise ValueError("a, l and r0 cannot form the oscillating follower")

    @property
    def sigma(self) -> int:
        return self.rotation

    @property
    def arm_side(self) -> int:
        """+1: oscillating arm left of the line pivot–cam centre, −1: right."""
        return self.rotation if self.arm is None else self.arm

    @property
    def s0(self) -> float:
        """``sqrt(r0² − e²)``: start height of the follower point, m (eq. 4-1)."""
        if self.contact == "flat":
            return self.r0
        return math.sqrt(self.r0 ** 2 - self.e ** 2)

    @property
    def phi0(self) -> float:
        """Initial arm angle φ₀ of the oscillating follower, rad (eq. 4-6)."""
        return math.acos((self.a ** 2 + self.l ** 2 - self.r0 ** 2) / (2 * self.a * self.l))

    @property
    def oscillating(self):
        return self.motion == "oscillating"


def _J(v: np.ndarray) -> np.ndarray:
    return np.stack([-v[1], v[0]])


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[0] * v[1] - u[1] * v[0]


def _dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[0] * v[0] + u[1] * v[1]


def _rotate(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def follower_point(fol: Follower, s: np.ndarray, s1: np.ndarray, s2: np.ndarray, s3: np.ndarray
                  ) -> Tuple[np.ndarray, ...]:
    """Follower reference point in the fixed frame and its δ-derivatives.

    Parameters
    ----------
    fol : Follower
    s, s1, s2, s3 : ndarray
        Displacement (m or rad) and its derivatives with respect to δ.

    Returns
    -------
    P, P1, P2, P3, d, d1 : ndarray, shape (2, n)
        Point (m) and derivatives (m/rad^k); unit direction of the follower
        point's motion for increasing s, and its δ-derivative.
    """
    sg = fol.sigma
    z = np.zeros_like(s)
    if fol.motion == "translating":
        d = np.stack([z, z + 1.0])
        if fol.contact == "flat":
            P = np.stack([sg * s1, fol.r0 + s])
            return (P, np.stack([sg * s2, s1]), np.stack([sg * s3, s2]),
                    np.stack([z, s3]), d, np.stack([z, z]))
        P = np.stack([z + fol.e, fol.s0 + s])
        return P, np.stack([z, s1]), np.stack([z, s2]), np.stack([z, s3]), d, np.stack([z, z])
    th = fol.phi0 + s
    side = fol.arm_side
    u = np.stack([-side * np.sin(th), -np.cos(th)])
    up = np.stack([-side * np.cos(th), np.sin(th)])
    P = np.stack([z, z + fol.a]) + fol.l * u
    P1 = fol.l * up * s1
    P2 = fol.l * (-u * s1 ** 2 + up * s2)
    P3 = fol.l * (-up * s1 ** 3 - 3 * u * s1 * s2 + up * s3)
    return P, P1, P2, P3, up, -u * s1


def _derived(fol: Follower, s: np.ndarray, s1: np.ndarray, s2: np.ndarray, s3: np.ndarray
            ) -> Tuple[np.ndarray, ...]:
    """V₀…V₃ (fixed-frame images of the profile derivatives) and d, d'."""
    sg = fol.sigma
    P, P1, P2, P3, d, d1 = follower_point(fol, s, s1, s2, s3)
    V1 = P1 - sg * _J(P)
    V2 = P2 - 2 * sg * _J(P1) - P
    V3 = P3 - 3 * sg * _J(P2) - 3 * P1 + sg * _J(P)
    return P, V1, V2, V3, d, d1


def pressure_angle_and_rate(fol: Follower, s: np.ndarray, s1: np.ndarray, s2: np.ndarray,
                            s3: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Signed pressure angle α (rad) and dα/dδ.

    α = atan2(V₁·d, σ V₁×d): positive when the normal force opposes the
    follower's motion in a rise.  Zero for a flat face perpendicular to the
    guide.  Notes: eq. (7-14) for the translating follower.
    """
    if fol.contact == "flat":
        z = np.zeros_like(s)
        return z, z.copy()
    sg = fol.sigma
    P, V1, V2, V3, d, d1 = _derived(fol, s, s1, s2, s3)
    N = _dot(V1, d)
    D = sg * _cross(V1, d)
    dV1 = V2 + sg * _J(V1)
    dN = _dot(dV1, d) + _dot(V1, d1)
    dD = sg * (_cross(dV1, d) + _cross(V1, d1))
    return np.arctan2(N, D), (dN * D - N * dD) / (N ** 2 + D ** 2)


def curvature_and_rate(fol: Follower, s: np.ndarray, s1: np.ndarray, s2: np.ndarray, s3: np.ndarray
                      ) -> Tuple[np.ndarray, np.ndarray]:
    """Signed curvature of the pitch curve (1/m, convex positive) and dκ/dδ.

    For the flat-faced follower: ``-(r0 + s + s'')`` and its derivative
    (the quantity whose maximum gives the smallest radius of curvature).
    """
    if fol.contact == "flat":
        return -(fol.r0 + s + s2), -(s1 + s3)
    sg = fol.sigma
    P, V1, V2, V3, d, d1 = _derived(fol, s, s1, s2, s3)
    n2 = _dot(V1, V1)
    n3 = n2 ** 1.5
    c12 = _cross(V1, V2)
    kappa = -sg * c12 / n3
    dkappa = -sg * (_cross(V1, V3) / n3 - 3 * c12 * _dot(V1, V2) / (n3 * n2))
    return kappa, dkappa


def _rho(kappa: np.ndarray, cap: float) -> np.ndarray:
    big = np.abs(kappa) * cap <= 1.0
    safe = np.where(big, 1.0, kappa)
    return np.where(big, np.where(kappa < 0, -cap, cap), 1.0 / safe)


@record
class CamProfile:
    """Sampled cam: motion, pitch and working curves, checks per sample.

    Attributes
    ----------
    delta : ndarray
        Cam angle, rad.
    s, s1, s2, s3 : ndarray
        Displacement (m or rad) and derivatives per rad, rad², rad³.
    pitch : ndarray (2, n) or None
        Pitch (theoretical) curve in the cam frame, m (None for flat-faced).
    work : ndarray (2, n)
        Working (actual) curve in the cam frame, m.
    normal : ndarray (2, n)
        Outward unit normal of the profile in the cam frame.
    alpha : ndarray
        Signed pressure angle, rad.
    rho_pitch : ndarray or None
        Radius of curvature of the pitch curve, m (convex positive, capped at
        ``RHO_CAP × r0``).
    rho_work : ndarray
        Radius of curvature of the working curve, m (convex positive).
    roller_angle : ndarray or None
        Roller rotation angle as the book's simulation computes it: working
        curve arc length from δ = 0 divided by r_r, rad.
    face_offset : ndarray or None
        Flat face: contact point measured from the follower axis, m.
    left : ndarray of bool or None
        True where the sample is the limit from the left at a jump (the next
        sample has the same δ and is the limit from the right); None: no such
        sample.
    grid : ndarray of bool or None
        True where the sample is one of the uniform grid (the others are the
        added jump samples); None: all are.
    """

    delta: np.ndarray
    s: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    s3: np.ndarray
    pitch: np.ndarray | None
    work: np.ndarray
    normal: np.ndarray
    alpha: np.ndarray
    rho_pitch: np.ndarray | None
    rho_work: np.ndarray
    roller_angle: np.ndarray | None
    face_offset: np.ndarray | None
    left: np.ndarray | None = None
    grid: np.ndarray | None = None


def cam_profile(fol: Follower, program: MotionProgram, delta: np.ndarray,
                left: Optional[np.ndarray] = None, grid: Optional[np.ndarray] = None) -> CamProfile:
    """Pitch and working curves of the cam at cam angles *delta*.

    Parameters
    ----------
    fol : Follower
    program : MotionProgram
    delta : ndarray
        Cam angles, rad (increasing, typically 0 … 2π).
    left, grid : ndarray of bool, optional
        The limit from the left where *left* is true (see
        :func:`mechcli.core.cam.motion.jump_samples`, which makes all three
        arrays); both are kept in the profile.

    Returns
    -------
    CamProfile

    Raises
    ------
    CamGeometryError
        ``reason = "pitch_cusp"``, ``at`` the cam angle (rad): the follower
        point moves with the cam, the pitch curve has no normal there.
    """
    st = program.evaluate(delta, left)
    s, s1, s2, s3 = st.s, st.s1, st.s2, st.s3
    marks = dict(left=left, grid=grid)
    sg = fol.sigma
    rot = -sg * np.asarray(delta, dtype=float)
    P, V1, V2, V3, d, d1 = _derived(fol, s, s1, s2, s3)
    alpha, _ = pressure_angle_and_rate(fol, s, s1, s2, s3)
    cap = RHO_CAP * fol.r0
    if fol.contact == "flat":
        work = _rotate(P, rot)
        normal = _rotate(np.stack([np.zeros_like(s), np.ones_like(s)]), rot)
        rho = fol.r0 + s + s2
        return CamProfile(st.delta, s, s1, s2, s3, None, work, normal, alpha, None,
                          np.clip(rho, -cap, cap), None, sg * s1 - fol.e, **marks)
    speed = np.sqrt(_dot(V1, V1))
    if not np.all(speed > 1e-12 * fol.r0):
        at = float(np.asarray(delta, dtype=float)[np.argmin(speed)])
        raise CamGeometryError(f"the pitch curve has a cusp near delta = {at!r} (the follower "
                               "point moves with the cam): no normal, no profile",
                               "pitch_cusp", at=at)
    n_fixed = sg * _J(V1) / speed
    pitch = _rotate(P, rot)
    normal = _rotate(n_fixed, rot)
    kappa = -sg * _cross(V1, V2) / speed ** 3
    rho_p = _rho(kappa, cap)
    if fol.contact == "roller":
        work = pitch - fol.rr * normal
        rho_w = np.clip(rho_p - fol.rr, -cap, cap)
        wspeed = speed * np.abs(1 - fol.rr * kappa)
        arc = np.concatenate([[0.0], np.cumsum(0.5 * (wspeed[1:] + wspeed[:-1])
                                                 * np.diff(st.delta))])
        roller = arc / fol.rr
    else:
        work, rho_w, roller = pitch, rho_p, None
    return CamProfile(st.delta, s, s1, s2, s3, pitch, work, normal, alpha, rho_p, rho_w,
                      roller, None, **marks)



def pitch_corners(fol: Follower, program: MotionProgram) -> Any:
    """Corners of the pitch curve where the follower velocity jumps.

    Parameters
    ----------
    fol : Follower
    program : MotionProgram

    Returns
    -------
    tuple of (float, bool)
        Cam angle (rad) of every rigid impact and whether the pitch curve is
        convex there; empty for a flat-faced follower.
    """
    out = []
    if fol.contact == "flat":
        return ()
    allp = program.pieces()
    for imp in program.impacts():
        if imp.kind != "rigid":
            continue
        k = next(j for j, p in enumerate(allp) if abs(p[1] - imp.delta) < 1e-12)
        left = program.piece_state((k - 1) % len(allp), np.array([allp[k - 1][2]]))
        right = program.piece_state(k, np.array([imp.delta]))
        _, Vl, *_ = _derived(fol, *left)
        _, Vr, *_ = _derived(fol, *right)
        convex = bool(-fol.sigma * _cross(Vl, Vr)[0] > 0)
        out.append((imp.delta, convex))
    return tuple(out)



def _corner_normals(fol: Follower, program: MotionProgram, dc: float
                   ) -> List[Tuple[np.ndarray, np.ndarray]]:
    """Pitch point and outward normals (cam frame) on both sides of a corner at *dc*."""
    sg = fol.sigma
    allp = program.pieces()
    k = next(j for j, p in enumerate(allp) if abs(p[1] - dc) < 1e-12)
    ends = []
    for kk, x in (((k - 1) % len(allp), allp[k - 1][2]), (k, dc)):
        P, V1, *_ = _derived(fol, *program.piece_state(kk, np.array([x])))
        n = _rotate(sg * _J(V1) / np.sqrt(_dot(V1, V1)), np.array([-sg * dc]))
        ends.append((_rotate(P, np.array([-sg * dc]))[:, 0], n[:, 0]))
    return ends


def _trim_loop(left: np.ndarray, right: np.ndarray
               ) -> Optional[Tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Cut the overlap of two working-curve branches meeting at a convex pitch corner.

    Both branches are taken as functions r(θ) of the polar angle about the cam
    centre near the corner; returns (points kept of *left*, of *right*, the
    crossing point) or None when they do not cross.
    """
    tl = np.unwrap(np.arctan2(left[1], left[0]))
    tr = np.unwrap(np.arctan2(right[1], right[0]))
    tr += 2 * np.pi * np.round((tl[-1] - tr[0]) / (2 * np.pi))
    if tl[0] > tl[-1]:  # make the angle increase along the curve
        tl, tr = -tl, -tr
    if not (np.all(np.diff(tl) > 0) and np.all(np.diff(tr) > 0)) or tr[0] >= tl[-1]:
        return None
    lo, hi = max(tl[0], tr[0]), min(tl[-1], tr[-1])
    grid = np.sort(np.concatenate([tl[(tl >= lo) & (tl <= hi)], tr[(tr >= lo) & (tr <= hi)]]))
    if len(grid) < 2:
        return None
    rl = np.interp(grid, tl, np.hypot(*left))
    rr = np.interp(grid, tr, np.hypot(*right))
    diff = rl - rr
    change = sign_changes(diff)
    if not len(change):
        return None
    i = change[0]
    w = diff[i] / (diff[i] - diff[i + 1]) if diff[i] != diff[i + 1] else 0.0
    th = grid[i] + w * (grid[i + 1] - grid[i])
    xl = np.interp(th, tl, left[0]), np.interp(th, tl, left[1])
    return tl < th, tr > th, np.array(xl)


def working_outline(fol: Follower, program: MotionProgram, profile: CamProfile, corners: Any,
                    arc_step: float = math.radians(2.0)) -> np.ndarray:
    """The closed working curve to draw, with the roller's behaviour at pitch corners.

    Where the follower velocity jumps (uniform law) the pitch curve has a corner.
    At a concave corner the roller sits in the notch and pivots about the corner
    point: the working curve there is an arc of radius r_r that no per-angle
    sample holds, and it is inserted.  At a convex corner the two offset
    branches overlap: the loop is cut at their crossing (the cam has a sharp
    edge there).

    Parameters
    ----------
    fol : Follower
    program : MotionProgram
    profile : CamProfile
        Sampled over the whole revolution (δ from 0 to 2π).
    corners : sequence of (float, bool)
        :func:`pitch_corners` (``CamChecks.corners``).
    arc_step : float
        Angular step of the inserted arcs, rad.

    Returns
    -------
    ndarray, shape (2, m)
        Closed polyline in the cam frame, m.
    """
    work, delta = profile.work, profile.delta
    if fol.contact != "roller" or not corners:
        return work
    if profile.left is not None:             # one sample per angle: the arcs and cuts join
        keep = ~profile.left                 # the branches at the corners themselves
        work, delta = work[:, keep], delta[keep]
    n = work.shape[1] - 1
    base = work[:, :-1]                      # cyclic: point n is point 0 again
    idx = [int(np.searchsorted(delta[:-1], dc - 1e-12)) % n for dc, _ in corners]
    # start the cyclic walk in the middle of the largest gap between corners
    cuts = sorted(idx)
    gaps = [((cuts[(i + 1) % len(cuts)] - c) % n or n, c) for i, c in enumerate(cuts)]
    size, c0 = max(gaps)
    shift = (c0 + size // 2) % n
    base = np.roll(base, -shift, axis=1)
    order = sorted(((i - shift) % n, dc, convex) for i, (dc, convex) in zip(idx, corners))
    window = max(2, n // (2 * len(order) + 2))
    out, last = [], 0
    for pos, dc, convex in order:
        (c, n0), (_, n1) = _corner_normals(fol, program, dc)
        if not convex:
            a0, a1 = math.atan2(-n0[1], -n0[0]), math.atan2(-n1[1], -n1[0])
            sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
            t = a0 + sweep * np.linspace(0, 1, max(2, int(abs(sweep) / arc_step) + 2))
            out.extend([base[:, last:pos], c[:, None] + fol.rr * np.stack([np.cos(t),
                                                                          np.sin(t)])])
            last = pos
            continue
        lo = max(last, pos - window)
        left, right = base[:, lo:pos], base[:, pos:pos + window]
        cut = _trim_loop(left, right) if left.shape[1] > 1 and right.shape[1] > 1 else None
        if cut is None:
            continue
        keep_l, keep_r, x = cut
        out.extend([base[:, last:lo], left[:, keep_l], x[:, None]])
        last = pos + int(np.argmax(keep_r))
    out.append(base[:, last:])
    curve = np.concatenate(out, axis=1)
    return np.concatenate([curve, curve[:, :1]], axis=1)
