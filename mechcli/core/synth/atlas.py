"""A digital Hrones–Nelson atlas: coupler-curve pages, the type chart,
an atlas of shape descriptors built at scale, path synthesis by atlas search and
local refinement.

Conventions (Hrones & Nelson, *Analysis of the Four-Bar Linkage*, and the seed
``hrones-nelson-fourbar-atlas.txt``): the crank is 1 (all lengths in crank
lengths), the coupler A (link 2), the follower B (link 3), the frame C (link 4).
The crank pivot is at the origin, the follower pivot at (C, 0); the coupler
joint "C" is on the open branch (to the left of crank pin -> follower pivot,
above the frame line when crank and frame are collinear, as the atlas draws it).
A coupler point has grid coordinates (gx, gy) on the coupler plane: origin at
the crank pin "B", x along the coupler (crank pin -> coupler-follower joint),
y to its left.  Each curve has 72 positions, one per 5° of crank.

Descriptor (:func:`descriptors`): the exact complex Fourier coefficients c_k,
0 < |k| <= H, of the closed polyline through the curve's points parametrized by
arc length, normalized (translation: c_0 dropped; scale: unit energy
Σ|c_k|² = 1; rotation and start point: c_1 and c_-1 made real and positive,
the remaining two-fold ambiguity fixed by a sign rule on the even harmonics,
which :func:`search` also tries the other way).

The atlas on disk is :mod:`mechcli.atlas_store`'s (the core does no file I/O): it
builds chunks with :func:`build_chunk`, ranks them with :func:`rank_chunk` and keeps
the format names (:data:`FORMAT`, :data:`VERSION`, :data:`DESCRIPTOR`) this module
defines.

numpy only at module level; scipy (and :mod:`mechcli.core.optimize`, for
:func:`refine`) inside the functions that need them.  Errors are
:class:`~mechcli.core.errors.DescribedError` with a ``reason`` and numbers
(ratios, counts) in ``.values``; no units, no spec keys.
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple, cast

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.grashof.chain import TYPES, length_ranges
from mechcli.core.grashof.fourbar import classify_fourbar
from mechcli.core.linkage import RRR, Crank, DriverMotion, Ground, Linkage, PointOnLink, solve
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.types import FloatOrArray

#: the manifest's format name and version
FORMAT = "mechcli-hrones-nelson-atlas"
VERSION = 1
#: the descriptor's name in the manifest (a change of definition changes it)
DESCRIPTOR = "fourier-arclength-polyline-v1"
MANIFEST = "manifest.json"

#: crank step of an atlas curve (72 dashes per revolution)
STEP = math.radians(5.0)
POSITIONS = 72

#: type chart codes
CRANK_ROCKER, DOUBLE_CRANK, DOUBLE_ROCKER, CHANGE_POINT = 0, 1, 2, 3
REGION_NAMES = ("crank_rocker", "double_crank", "double_rocker", "change_point")

#: a default build (>= 100 000 crank-rocker curves): ratios 1.25 … 4.5 in
#: 14 steps of 0.25 each, the coupler plane's grid -1.5 … 3.5 by 0.5 along
#: the coupler and -2 … 2.5 by 0.5 across it
DEFAULT_A_RANGE = (1.25, 4.5, 14)
DEFAULT_B_RANGE = (1.25, 4.5, 14)
DEFAULT_C_RANGE = (1.25, 4.5, 14)
DEFAULT_GRID = (tuple(np.round(np.arange(-1.5, 3.51, 0.5), 6).tolist()),
                tuple(np.round(np.arange(-2.0, 2.51, 0.5), 6).tolist()))

_CR = {TYPES.index("crank_rocker")}
_REGION_OF = {"crank_rocker": CRANK_ROCKER, "double_crank": DOUBLE_CRANK,
              "parallelogram": DOUBLE_CRANK, "antiparallelogram": DOUBLE_CRANK,
              "double_rocker": DOUBLE_ROCKER, "change_point_crank_rocker": CHANGE_POINT,
              "change_point_double_crank": CHANGE_POINT,
              "change_point_double_rocker": CHANGE_POINT}


# ---------------------------------------------------------------------------
# the linkage and a page
# ---------------------------------------------------------------------------
def atlas_linkage(A: FloatOrArray, B: FloatOrArray, C: FloatOrArray, gx: FloatOrArray,
                  gy: FloatOrArray, branch: int = 1) -> Linkage:
    """The Hrones–Nelson four-bar on the engine, coupler point "P" at (gx, gy).

    Crank pivot "A" = (0, 0), follower pivot "D" = (C, 0); crank 1 (link 1,
    pin "B"), coupler A (link 2, "B" -> "C"), follower B (link 3, "D" -> "C"),
    frame link 4.  (gx, gy) in crank lengths on the coupler plane: origin at
    "B", x along B -> C, y to its left.  ``branch`` +1 (open: "C" left of
    B -> D) as the atlas draws it.  Every argument may be an array (a batch
    of linkages: e.g. shape (M, 1) against crank angles (N,)).
    """
    # the elements' fields are annotated float, but the engine takes arrays (a batch)
    return Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", C, 0.0),  # type: ignore[arg-type]
                       Crank(1, "A", "B", 1.0),
                       RRR("C", "B", 2, A, "D", 3, B, branch),  # type: ignore[arg-type]
                       PointOnLink("P", 2, "B", gx, gy)))  # type: ignore[arg-type]


def _lengths(A: FloatOrArray, B: FloatOrArray, C: FloatOrArray) -> np.ndarray:
    A, B, C = np.broadcast_arrays(*(np.asarray(v, dtype=float).reshape(-1) for v in (A, B, C)))
    return np.stack([np.ones_like(A), A, B, C], axis=1)


def crank_rocker_mask(A: FloatOrArray, B: FloatOrArray, C: FloatOrArray) -> np.ndarray:
    """True where the four-bar (1, A, B, C) is a crank-rocker whose crank is link 1
    (not a change point): the atlas keeps exactly these."""
    L = _lengths(A, B, C)
    cls = classify_fourbar(L, frame=4)
    return (cls.code == TYPES.index("crank_rocker")) & cls.crank_mask[:, 0]


def _kind_of(A: float, B: float, C: float) -> Tuple[str, bool]:
    L = _lengths(A, B, C)
    cls = classify_fourbar(L, frame=4)
    return TYPES[int(cls.code[0])].replace("_", "-"), bool(cls.crank_mask[0, 0])


def chain_kind(A: Any, B: Any, C: Any):
    """(Grashof type of the chain with frame C, e.g. "crank-rocker"; whether link 1
    turns fully)."""
    return _kind_of(float(A), float(B), float(C))


@record
class AtlasPage:
    """The curves of one atlas page.

    Attributes
    ----------
    A, B, C : float
        Coupler, follower, frame [crank lengths].
    gx, gy : ndarray (P,)
        Coupler points on the grid [crank lengths].
    theta : ndarray (N,)
        Crank angles [rad] (0, step, 2·step, …; 72 for 5°).
    x, y : ndarray (P, N)
        The coupler points' positions [crank lengths] (0 where not ``ok``).
    ok : ndarray of bool (P,)
        The curve exists (the linkage turns a full crank revolution).
    kind : str
        Grashof type of the chain with frame C ("crank-rocker", "double-rocker", …).
    reason : str or None
        Why nothing is drawn: ``"not_crank_rocker"`` (the chain's type is
        another), ``"crank_not_link_1"`` (a crank-rocker whose crank is the
        follower), ``"change_point"``; None when the curves are drawn.
    """

    A: float
    B: float
    C: float
    gx: np.ndarray
    gy: np.ndarray
    theta: np.ndarray
    x: np.ndarray
    y: np.ndarray
    ok: np.ndarray
    kind: str
    reason: Optional[str]


def atlas_page(A: float, B: float, C: float, gx: Any, gy: Any, step: float = STEP) -> AtlasPage:
    """The coupler curves of the points (gx, gy) of one linkage (one engine call).

    A linkage whose crank (link 1) cannot turn a full revolution gives
    ``ok`` all False and a ``reason`` (see :class:`AtlasPage`); a step that
    does not divide the revolution is rejected (``reason="step"``).
    """
    A, B, C = float(A), float(B), float(C)
    gx, gy = np.broadcast_arrays(np.atleast_1d(np.asarray(gx, dtype=float)).reshape(-1),
                                 np.atleast_1d(np.asarray(gy, dtype=float)).reshape(-1))
    n = 2 * math.pi / float(step)
    if not (step > 0 and abs(n - round(n)) < 1e-9 and round(n) >= 3):
        raise DescribedError("the crank step must divide the revolution into at least 3 steps",
                             "step", step=float(step))
    theta = np.arange(int(round(n))) * (2 * math.pi / round(n))
    P, N = gx.size, theta.size
    kind, crank1 = _kind_of(A, B, C)
    reason = None
    # drawn when link 1 turns a full revolution (a crank-rocker with crank 1, or a
    # double-crank); not drawn: a change point (it can fold) or a link 1 that rocks
    if kind.startswith("change-point"):
        reason = "change_point"
    elif not crank1:
        reason = "crank_not_link_1" if kind == "crank-rocker" else "not_crank_rocker"
    if reason is not None:
        z = np.zeros((P, N))
        return AtlasPage(A, B, C, gx, gy, theta, z, z.copy(), np.zeros(P, bool), kind, reason)
    m = solve(atlas_linkage(A, B, C, gx[:, None], gy[:, None]), {1: DriverMotion(theta)},
              order=0)
    p = m.points["P"]
    ok = np.all(np.broadcast_to(m.feasible, (P, N)), axis=1)
    x = np.where(ok[:, None], np.broadcast_to(p.x, (P, N)), 0.0)
    y = np.where(ok[:, None], np.broadcast_to(p.y, (P, N)), 0.0)
    return AtlasPage(A, B, C, gx, gy, theta, x, y, ok, kind, None)


# ---------------------------------------------------------------------------
# type chart and ranges
# ---------------------------------------------------------------------------
@record
class TypeChart:
    """The seed's 图 7: the chain's type over the (B, C) plane for given A.

    Attributes
    ----------
    A : float or ndarray (k,)
    B : ndarray (nb,)
    C : ndarray (nc,)
    region : ndarray of int (k, nc, nb)
        :data:`CRANK_ROCKER`, :data:`DOUBLE_CRANK` (parallelograms included),
        :data:`DOUBLE_ROCKER`, :data:`CHANGE_POINT` (s + l = p + q).
    crank : ndarray of int8 (k, nc, nb)
        The crank link of a crank-rocker: 1 (the atlas's) or 3 (B < 1); 0 elsewhere.
    """

    A: object
    B: np.ndarray
    C: np.ndarray
    region: np.ndarray
    crank: np.ndarray


def _axis(r: Any, points: int) -> np.ndarray:
    r = tuple(r)
    if len(r) == 3:
        return np.linspace(float(r[0]), float(r[1]), int(r[2]))
    if len(r) == 2:
        return np.linspace(float(r[0]), float(r[1]), int(points))
    return np.asarray(r, dtype=float)


def type_chart(A: Any, B_range: Any, C_range: Any, points: int = 201) -> TypeChart:
    """Classify (1, A, B, C) over a grid of B (columns) and C (rows), vectorized.

    ``B_range``/``C_range``: (lo, hi) with ``points`` values, (lo, hi, count),
    or the values themselves.  Classification by
    :func:`mechcli.core.grashof.fourbar.classify_fourbar` with frame C.
    """
    scalar = np.ndim(A) == 0
    As = np.atleast_1d(np.asarray(A, dtype=float))
    Bs, Cs = _axis(B_range, points), _axis(C_range, points)
    AA, CC, BB = np.meshgrid(As, Cs, Bs, indexing="ij")
    L = np.stack([np.ones(AA.size), AA.ravel(), BB.ravel(), CC.ravel()], axis=1)
    cls = classify_fourbar(L, frame=4)
    lut = np.array([_REGION_OF[t] for t in TYPES])
    region = lut[cls.code].reshape(AA.shape)
    crank = np.where(region.ravel() == CRANK_ROCKER,
                     np.where(cls.crank_mask[:, 0], 1, np.where(cls.crank_mask[:, 2], 3, 0)),
                     0).astype(np.int8).reshape(AA.shape)
    return TypeChart(float(As[0]) if scalar else As, Bs, Cs, region, crank)


def admissible_ranges(A: float, B: float, C: float) -> dict:
    """Each ratio's interval keeping a crank-rocker with crank 1, the other two fixed.

    ``{"A": (lo, hi), "B": (lo, hi), "C": (lo, hi)}`` from
    :func:`mechcli.core.grashof.chain.length_ranges` (ends included: they are
    change points); the seed's example A = 2.5, B = 2, C = 3 gives C 1.5 … 3.5,
    B 1.5 … 4.5 (and A 2 … 4).  Raises ``DescribedError(reason="not_crank_rocker")``
    when (A, B, C) itself is not such a crank-rocker.
    """
    base = [1.0, float(A), float(B), float(C)]
    out = {}
    for name, link in (("A", 2), ("B", 3), ("C", 4)):
        value = base[link - 1]
        hit = None
        for r in length_ranges(base, link, frame=4):
            if r.type == "crank_rocker" and r.crank == 1 and r.lo <= value <= r.hi:
                hit = (r.lo, r.hi)
        if hit is None:
            raise DescribedError("the linkage is not a crank-rocker with link 1 as the crank",
                                 "not_crank_rocker", A=base[1], B=base[2], C=base[3])
        out[name] = hit
    return out


# ---------------------------------------------------------------------------
# descriptors
# ---------------------------------------------------------------------------
def _ks(harmonics: int) -> np.ndarray:
    return np.concatenate([np.arange(1, harmonics + 1), -np.arange(1, harmonics + 1)])


def polyline_coefficients(x: np.ndarray, y: np.ndarray, harmonics: int = 16) -> Any:
    """Exact Fourier coefficients of closed polylines parametrized by arc length.

    ``x, y`` (M, N) or (N,): the vertices (the last joined to the first).
    Returns ``(c0 (M,), c (M, 2H), L (M,))``: the centroid, the coefficients
    of k = 1 … H, -1 … -H (:math:`z(s) = Σ c_k e^{2πiks/L}`) and the length.

    With u_j the unit tangent of segment j and s_j the arc position of vertex
    j, integrating by parts twice gives
    :math:`c_k = -L/(2πk)^2 Σ_j (u_j - u_{j-1}) e^{-2πiks_j/L}`: no resampling,
    so a curve started at another vertex, moved, turned or scaled has exactly
    the transformed coefficients.  A zero-length segment (u = 0) is exact too.
    """
    z = np.asarray(x, dtype=float) + 1j * np.asarray(y, dtype=float)
    one = z.ndim == 1
    z = np.atleast_2d(z)
    seg = np.roll(z, -1, axis=1) - z
    ln = np.abs(seg)
    L = ln.sum(axis=1)
    Ls = np.where(L > 0, L, 1.0)
    u = seg / np.where(ln > 0, ln, 1.0)
    du = u - np.roll(u, 1, axis=1)
    s = np.concatenate([np.zeros((z.shape[0], 1)), np.cumsum(ln, axis=1)[:, :-1]], axis=1)
    ang = (2 * np.pi) * s / Ls[:, None]
    # the harmonics' sums in single precision (a relative error ~1e-7, below the
    # float32 of the stored descriptors); the recurrence of the powers of w is
    # re-started from w^8 (squarings in double precision) so its round-off
    # does not grow with k
    w2 = np.cos(ang) - 1j * np.sin(ang)
    w = w2.astype(np.complex64)
    duc = du.astype(np.complex64)
    dcc = np.conj(duc)
    H = int(harmonics)
    c = np.empty((z.shape[0], 2 * H), dtype=complex)
    pw = w.copy()
    w8 = None
    for k in range(1, H + 1):
        if k > 1:
            if k % 8 == 1:
                if w8 is None:
                    w8 = w2 * w2
                    w8 *= w8
                    w8 *= w8
                    wk = w8
                else:
                    wk = wk * w8
                pw = (wk * w2).astype(np.complex64)
            else:
                pw *= w
        f = -Ls / (2 * np.pi * k) ** 2
        c[:, k - 1] = f * (duc * pw).sum(axis=1)
        c[:, H + k - 1] = f * np.conj((dcc * pw).sum(axis=1))
    c0 = np.sum(ln * (z + np.roll(z, -1, axis=1)) * 0.5, axis=1) / Ls
    if one:
        return c0[0], c[0], L[0]
    return c0, c, L


def _resampled_coefficients(x: np.ndarray, y: np.ndarray, harmonics: int, samples: int
                           ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    z = np.atleast_2d(np.asarray(x, dtype=float) + 1j * np.asarray(y, dtype=float))
    M, N = z.shape
    zc = np.concatenate([z, z[:, :1]], axis=1)
    ln = np.abs(np.diff(zc, axis=1))
    s = np.concatenate([np.zeros((M, 1)), np.cumsum(ln, axis=1)], axis=1)
    L = s[:, -1]
    t = np.arange(samples)[None, :] * (L[:, None] / samples)
    # per-row searchsorted on one flattened, offset array
    off = (np.arange(M) * (2.0 * (L.max() + 1.0)))[:, None]
    idx = np.searchsorted((s + off).ravel(), (t + off).ravel(), side="right").reshape(M, -1)
    idx = np.clip(idx - np.arange(M)[:, None] * (N + 1) - 1, 0, N - 1)
    rows = np.arange(M)[:, None]
    s0, l0 = s[rows, idx], np.where(ln[rows, idx] > 0, ln[rows, idx], 1.0)
    zs = zc[rows, idx] + (zc[rows, idx + 1] - zc[rows, idx]) * ((t - s0) / l0)
    F = np.fft.fft(zs, axis=1) / samples
    H = int(harmonics)
    c = np.concatenate([F[:, 1:H + 1], F[:, ::-1][:, :H]], axis=1)
    return F[:, 0], c, L


def normalize(c: np.ndarray, harmonics: int = 16) -> np.ndarray:
    """Normalized coefficients (M, 2H) complex of raw ones (see :func:`descriptors`)."""
    H = int(harmonics)
    c = np.atleast_2d(np.asarray(c, dtype=complex))
    E = np.sqrt(np.sum(np.abs(c) ** 2, axis=1))
    c = c / np.where(E > 0, E, 1.0)[:, None]
    # e^{iφ}, e^{iτ} with φ + τ = -arg c_1, φ - τ = -arg c_-1 (τ up to π: the
    # sign rule below picks one of the two), powers by cumulative products
    r1, rm = c[:, 0], c[:, H]
    r1 = np.where(np.abs(r1) > 0, r1 / np.where(np.abs(r1) > 0, np.abs(r1), 1.0), 1.0)
    rm = np.where(np.abs(rm) > 0, rm / np.where(np.abs(rm) > 0, np.abs(rm), 1.0), 1.0)
    et = np.sqrt(np.conj(r1) * rm)
    ep = np.conj(r1) / et
    pos = np.cumprod(np.repeat(et[:, None], H, axis=1), axis=1)
    k = _ks(H)
    c = c * (ep[:, None] * np.concatenate([pos, np.conj(pos)], axis=1))
    even = (k % 2 == 0)
    s = np.sum(c.real[:, even] * np.abs(c[:, even]), axis=1)
    sign = np.where(even, -1.0, 1.0)
    return np.where((s < 0)[:, None], c * sign[None, :], c)


def _real(c: np.ndarray) -> np.ndarray:
    return np.concatenate([c.real, c.imag], axis=1).astype(np.float32)


def descriptors(x: np.ndarray, y: np.ndarray, harmonics: int = 16, samples: int = 128,
                exact: bool = True) -> np.ndarray:
    """Shape descriptors of closed curves: (M, 4H) float32.

    Parameters
    ----------
    x, y : array_like (M, N) or (N,)
        The curves' points in order (the last joined to the first).
    harmonics : int
        H: harmonics k = ±1 … ±H.
    samples : int
        Arc-length samples of the classic resampled form (``exact=False``);
        with ``exact=True`` (default) the coefficients are those of the
        polyline itself (:func:`polyline_coefficients`, the limit of infinitely
        many samples) and ``samples`` is not used.
    exact : bool

    Returns
    -------
    ndarray (M, 4H) float32
        ``[Re c_1…c_H, Re c_-1…c_-H, Im c_1…c_H, Im c_-1…c_-H]`` of the
        normalized coefficients.  Euclidean distance between two descriptors
        is the L2 distance between the two normalized curves low-passed to H
        harmonics (Parseval).

    Notes
    -----
    Invariant to translation (c_0 dropped), scale (divided by the energy
    √Σ|c_k|²), rotation and start point (the factor e^{i(φ + kτ)} that makes
    c_1 and c_-1 real and positive; τ is fixed up to π, which flips the sign
    of every even harmonic: the sign that makes Σ_even Re c_k |c_k| >= 0 is
    kept, and :func:`search` also queries the other one, so a curve whose sum
    is near 0 is still found).  Direction of travel and mirror images ARE
    distinguished: a reversed curve has other descriptors (search queries
    both directions), a mirror image too (it is the other assembly branch's
    curve; not searched).  A circle or any curve with c_-1 = 0 (or c_1 = 0)
    has an undetermined τ; its descriptors are then those of τ from arg 0.
    """
    if exact:
        _, c, _ = polyline_coefficients(np.atleast_2d(x), np.atleast_2d(y), harmonics)
    else:
        _, c, _ = _resampled_coefficients(x, y, harmonics, int(samples))
    return _real(normalize(c, harmonics))


def _flip_even(d: np.ndarray, harmonics: int) -> np.ndarray:
    H = int(harmonics)
    k = _ks(H)
    sign = np.where(k % 2 == 0, -1.0, 1.0).astype(np.float32)
    return d * np.concatenate([sign, sign])[None, :]


# ---------------------------------------------------------------------------
# building
# ---------------------------------------------------------------------------
def _curves(params: np.ndarray, step: float = STEP) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Engine call for a (M, 5) parameter array: (x, y (M, N), ok (M,))."""
    P = np.asarray(params, dtype=float)
    theta = np.arange(POSITIONS) * step if step == STEP else \
        np.arange(int(round(2 * math.pi / step))) * step
    # the columns are A … gy (mypy checks starred items against branch too)
    lk = atlas_linkage(*(P[:, j:j + 1] for j in range(5)))  # type: ignore[arg-type]
    m = solve(lk, {1: DriverMotion(theta)}, order=0)
    p = m.points["P"]
    shape = (P.shape[0], theta.size)
    ok = np.all(np.broadcast_to(m.feasible, shape), axis=1)
    return np.broadcast_to(p.x, shape), np.broadcast_to(p.y, shape), ok


def build_chunk(params: np.ndarray, harmonics: int = 16
               ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Descriptors of a chunk of parameter rows (one engine call for the chunk).

    ``params`` (M, 5): A, B, C, gx, gy.  Only crank-rockers with crank 1 that
    assemble at every position are kept: returns ``(desc (K, 4H) float32,
    params (K, 5) float32, ok (M,) bool)`` with K = ok.sum(), the kept rows in
    input order.
    """
    P = np.atleast_2d(np.asarray(params, dtype=float))
    ok = crank_rocker_mask(P[:, 0], P[:, 1], P[:, 2])
    D = 4 * int(harmonics)
    if not ok.any():
        return np.zeros((0, D), np.float32), np.zeros((0, 5), np.float32), ok
    keep = P[ok]
    x, y, assembled = _curves(keep)
    ok[np.flatnonzero(ok)[~assembled]] = False
    x, y, keep = x[assembled], y[assembled], keep[assembled]
    return descriptors(x, y, harmonics), keep.astype(np.float32), ok


def ratio_sets(A_range: Any, B_range: Any, C_range: Any) -> np.ndarray:
    """The crank-rocker (A, B, C) of the ranges' grid, in a fixed order (K, 3)."""
    a, b, c = (_axis(r, 0) for r in (A_range, B_range, C_range))
    AA, BB, CC = np.meshgrid(a, b, c, indexing="ij")
    sets = np.stack([AA.ravel(), BB.ravel(), CC.ravel()], axis=1)
    return sets[crank_rocker_mask(sets[:, 0], sets[:, 1], sets[:, 2])]


def grid_points(grid: Any) -> np.ndarray:
    gxv, gyv = (np.asarray(v, dtype=float).reshape(-1) for v in grid)
    GX, GY = np.meshgrid(gxv, gyv, indexing="ij")
    return np.stack([GX.ravel(), GY.ravel()], axis=1)


@functools.lru_cache(maxsize=4)
def _ratio_sets_cached(A_range: Tuple[float, float, int], B_range: Tuple[float, float, int],
                       C_range: Tuple[float, float, int]) -> np.ndarray:
    return ratio_sets(A_range, B_range, C_range)


def chunk_params(parameters: Dict[str, Any], start: int, stop: int) -> np.ndarray:
    """The parameter rows start ... stop of a build (the ratio sets are classified once
    per process, not once per chunk)."""
    sets = _ratio_sets_cached(*(tuple(parameters[k]) for k in ("A_range", "B_range",
                                                                "C_range")))
    pts = grid_points(parameters["grid"])
    i = np.arange(start, stop)
    r, g = np.divmod(i, pts.shape[0])
    return np.concatenate([sets[r], pts[g]], axis=1)


# ---------------------------------------------------------------------------
# search
# ---------------------------------------------------------------------------
@record
class Match:
    """An atlas curve near the target: descriptor distance and its parameters.

    ``reversed``: the target matches the curve traversed backwards (the crank
    turning clockwise); ``chunk``/``row`` locate it in the atlas.
    """

    distance: float
    A: float
    B: float
    C: float
    gx: float
    gy: float
    reversed: bool = False
    chunk: int = -1
    row: int = -1


def target_points(x: Any, y: Any) -> np.ndarray:
    x = np.asarray(x, dtype=float).reshape(-1)
    y = np.asarray(y, dtype=float).reshape(-1)
    if x.shape != y.shape:
        raise DescribedError("the target needs as many x as y values", "target_shape",
                             x=x.size, y=y.size)
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise DescribedError("a target coordinate is not finite", "target_not_finite")
    z = x + 1j * y
    if z.size:
        keep = np.concatenate([[True], np.abs(np.diff(z)) > 0])
        z = z[keep]
    if z.size > 1 and z[-1] == z[0]:
        z = z[:-1]
    if np.unique(z).size < 3:
        raise DescribedError("a path needs at least 3 distinct target points",
                             "too_few_points", points=int(np.unique(z).size))
    return z


def queries(z: np.ndarray, harmonics: int) -> np.ndarray:
    d = descriptors(z.real, z.imag, harmonics)
    r = descriptors(z.real[::-1], z.imag[::-1], harmonics)
    Q = np.concatenate([d, _flip_even(d, harmonics), r, _flip_even(r, harmonics)], axis=0)
    return Q.astype(np.float32)


def rank_chunk(desc: np.ndarray, params: np.ndarray, Q: np.ndarray, k: int
              ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The k rows of one chunk nearest any of the queries ``Q`` (q, D): distances
    (float64, exact for the short list), their parameters, which query matched
    (>= 2: the target reversed) and the rows; pure arrays, no file."""
    if desc.shape[0] == 0:
        return np.zeros(0), np.zeros((0, 5)), np.zeros(0, int), np.zeros(0, int)
    d2 = (np.einsum("md,md->m", desc, desc)[:, None] - 2.0 * (desc @ Q.T)
          + np.einsum("qd,qd->q", Q, Q)[None, :])
    best_q = np.argmin(d2, axis=1)
    d2 = d2[np.arange(d2.shape[0]), best_q]
    kk = min(desc.shape[0], max(4 * k, 32))
    idx = np.argpartition(d2, kk - 1)[:kk] if kk < desc.shape[0] else np.arange(desc.shape[0])
    # exact distances (float64) of the short list, then the k best
    diff = desc[idx].astype(float)[:, None, :] - Q.astype(float)[None, :, :]
    e = np.einsum("mqd,mqd->mq", diff, diff)
    dist = np.sqrt(np.min(e, axis=1))
    var = np.argmin(e, axis=1)
    top = np.argsort(dist, kind="stable")[:k]
    return dist[top], params[idx[top]].astype(float), var[top], idx[top]


# ---------------------------------------------------------------------------
# refinement
# ---------------------------------------------------------------------------
@record
class Refined:
    """A refined match.

    Attributes
    ----------
    x_opt : dict
        A, B, C, gx, gy (ratios), tx, ty (crank pivot, target units),
        rotation (frame direction [rad]), scale (crank length, target units),
        and theta0 (crank angle from the frame at the first timing angle
        [rad]) when angles were given.
    error_rms, error_max : float
        Distance of the targets to the placed linkage's coupler curve (at the
        given crank angles when timed), target units.
    linkage : Linkage
        The placed linkage (ground pivots at the placed positions).
    placement : (tx, ty, rotation, scale)
    size : float
        The target's RMS radius about its centroid (errors relative to it).
    method, message : str
    """

    x_opt: dict
    error_rms: float
    error_max: float
    linkage: Linkage
    placement: Tuple[float, float, float, float]
    size: float = 1.0
    method: str = ""
    message: str = ""


def placed_linkage(A: FloatOrArray, B: FloatOrArray, C: FloatOrArray, gx: FloatOrArray,
                   gy: FloatOrArray, tx: FloatOrArray, ty: FloatOrArray, rotation: FloatOrArray,
                   scale: FloatOrArray, branch: int = 1) -> Linkage:
    """The atlas linkage moved to crank pivot (tx, ty), frame direction
    ``rotation`` and crank length ``scale``; arrays broadcast (a population)."""
    c, s = np.cos(rotation), np.sin(rotation)
    # the elements' fields are annotated float, but the engine takes arrays (a population)
    return Linkage(4, (Ground("A", tx, ty),  # type: ignore[arg-type]
                       Ground("D", tx + scale * C * c,  # type: ignore[arg-type]
                              ty + scale * C * s),  # type: ignore[arg-type]
                       Crank(1, "A", "B", scale),  # type: ignore[arg-type]
                       RRR("C", "B", 2, scale * A, "D", 3, scale * B,  # type: ignore[arg-type]
                           branch),
                       PointOnLink("P", 2, "B", scale * gx, scale * gy)))  # type: ignore[arg-type]


_MARGIN = 1e-4


def _crank_rocker_g(X: np.ndarray, gamma_min: float = 0.0) -> np.ndarray:
    """The six crank-rocker inequalities (<= 0 met) and, with ``gamma_min`` > 0,
    the angle BCD within [gamma_min, pi - gamma_min] at its extremes (crank along
    the frame: 式 7-12, 7-13), as cosines."""
    A, B, C = X[:, 0], X[:, 1], X[:, 2]
    g = np.stack([1 - A, 1 - B, 1 - C, C - (A + B - 1), (A - B + 1) - C,
                  (B - A + 1) - C], axis=1) + _MARGIN
    if gamma_min <= 0:
        return g
    c = math.cos(gamma_min)
    cos_lo = (A * A + B * B - (C - 1) ** 2) / (2 * A * B)     # the smallest angle BCD
    cos_hi = (A * A + B * B - (C + 1) ** 2) / (2 * A * B)     # the largest
    return np.concatenate([g, np.stack([cos_lo - c, -c - cos_hi], axis=1)], axis=1)


class _PathFit:
    """``evaluate(X) -> Evaluation`` of the real path error (picklable).

    Without timing each target's distance is to the curve itself: the
    nearest of ``samples`` positions, then Newton steps on the crank angle
    (the foot of the perpendicular), so the error has no polyline floor.
    With timing the distance is to the point at crank angle
    rotation + theta0 + angle.  f = mean squared distance over the target's
    size squared (the targets are normalized: centroid 0, RMS radius 1).
    """

    def __init__(self, T: np.ndarray, angles: Optional[np.ndarray], samples: int,
                 gamma_min: float = 0.0) -> None:
        self.T = T
        self.angles = angles
        self.gamma_min = float(gamma_min)
        self.q = np.arange(int(samples)) * (2 * math.pi / int(samples))

    def candidates(self, X: np.ndarray) -> Tuple[Linkage, np.ndarray, Dict[Any, Any]]:
        # the columns are A … scale (mypy checks starred items against branch too)
        lk = placed_linkage(*(X[:, j:j + 1] for j in range(9)))  # type: ignore[arg-type]
        return lk, np.all(np.isfinite(X), axis=1), {}

    def foot(self, X: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Crank angles (M, K) of the targets' feet, the points there, ok (M,)."""
        lk, built, _ = self.candidates(X)
        M, K = X.shape[0], self.T.size
        rot = X[:, 7:8]
        if self.angles is not None:
            th = rot + X[:, 9:10] + self.angles[None, :]
            m = solve(lk, {1: DriverMotion(th)}, order=0)
            p = m.points["P"]
            return th, np.broadcast_to(p.x + 1j * p.y, (M, K)), built & np.all(m.feasible, 1)
        q = rot + self.q[None, :]
        m = solve(lk, {1: DriverMotion(q)}, order=0)
        ok = built & np.all(np.broadcast_to(m.feasible, q.shape), axis=1)
        pz = np.broadcast_to(m.points["P"].x + 1j * m.points["P"].y, q.shape)
        dist = np.abs(pz[:, :, None] - self.T[None, None, :])                  # (M, S, K)
        # Newton from the three nearest samples: near a crossing of a figure-eight the
        # nearest sample may lie on the other lobe (the best foot is kept)
        starts = np.argsort(dist, axis=1)[:, :3, :] if q.shape[1] > 3 else \
            np.argmin(dist, axis=1)[:, None, :]
        best = None
        for r in range(starts.shape[1]):
            cand = self._newton(lk, np.take_along_axis(q, starts[:, r, :], axis=1), ok)
            if best is None:
                best = cand
            else:
                th_b, pz_b, ok_b = best
                th_c, pz_c, ok_c = cand
                better = np.abs(pz_c - self.T[None, :]) < np.abs(pz_b - self.T[None, :])
                best = (np.where(better, th_c, th_b), np.where(better, pz_c, pz_b),
                        ok_b & ok_c)
        assert best is not None   # at least one start
        return best

    def _newton(self, lk: Linkage, th: np.ndarray, ok: np.ndarray
               ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Newton steps on the crank angle from ``th`` (M, K) towards each target's
        foot; ``(theta, points, ok)``."""
        dq = self.q[1] if self.q.size > 1 else math.pi
        for _ in range(5):
            m = solve(lk, {1: DriverMotion(th, 1.0, 0.0)}, order=2)
            P = m.points["P"]
            r = (P.x + 1j * P.y) - self.T[None, :]
            v, a = P.vx + 1j * P.vy, P.ax + 1j * P.ay
            g = np.real(r * np.conj(v))
            gp = np.abs(v) ** 2 + np.real(r * np.conj(a))
            gp = np.where(gp > 1e-3 * np.abs(v) ** 2, gp, np.abs(v) ** 2 + 1e-300)
            th = th - np.clip(g / gp, -dq, dq)
            ok = ok & np.all(m.feasible, axis=1)
        m = solve(lk, {1: DriverMotion(th)}, order=0)
        p = m.points["P"]
        return th, np.broadcast_to(p.x + 1j * p.y, th.shape), ok & np.all(m.feasible, axis=1)

    def __call__(self, X: np.ndarray) -> Any:   # an optimize.problem.Evaluation
        from mechcli.core.optimize.problem import Evaluation

        X = np.atleast_2d(np.asarray(X, dtype=float))
        with np.errstate(all="ignore"):
            _, pz, ok = self.foot(X)
            d2 = np.abs(pz - self.T[None, :]) ** 2
        f = np.mean(d2, axis=1)
        ok &= np.isfinite(f)
        return Evaluation(np.where(ok, f, 0.0), _crank_rocker_g(X, self.gamma_min), ok)


def _initial_placement(match: Match, z: np.ndarray, samples: int = 720
                      ) -> Tuple[float, float, float, float]:
    """(tx, ty, rotation, scale) that best lays the match's curve on the targets
    (Fourier coefficients: the best start shift, then the complex factor)."""
    th = np.arange(samples) * (2 * math.pi / samples)
    m = solve(atlas_linkage(match.A, match.B, match.C, match.gx, match.gy),
              {1: DriverMotion(th)}, order=0)
    cz = np.broadcast_to(m.points["P"].x + 1j * m.points["P"].y, th.shape)
    H = 16
    t0, tc, _ = polyline_coefficients(z.real, z.imag, H)
    best = None
    for curve in (cz, cz[::-1]):
        c0, cc, _ = polyline_coefficients(curve.real, curve.imag, H)
        k = _ks(H)
        taus = np.arange(720) * (2 * math.pi / 720)
        corr = (np.conj(cc) * tc)[None, :] * np.exp(-1j * np.outer(taus, k))
        s = corr.sum(axis=1)
        i = int(np.argmax(np.abs(s)))
        if best is None or abs(s[i]) > best[0]:
            lam = s[i] / np.sum(np.abs(cc) ** 2)
            best = (abs(s[i]), lam, t0 - lam * c0)
    assert best is not None   # set by the first curve
    _, lam, t = best
    return t.real, t.imag, float(np.angle(lam)), float(abs(lam))


def refine(match: Match, x: np.ndarray, y: np.ndarray, angles: Optional[np.ndarray] = None,
           method: str = "slsqp", samples: int = 360, polish: bool = True, maxiter: int = 200,
           gamma_min: float = 0.0) -> Refined:
    """Refine an atlas match on the real path error, with the linkage's
    placement free.

    Variables A, B, C, gx, gy, tx, ty, rotation, scale (and theta0 with
    ``angles``), minimized by :func:`mechcli.core.optimize.methods.minimize`
    (``method``) on a :class:`mechcli.core.optimize.problem.Problem` whose
    candidates are the placed linkages (ground points at the placed pivots,
    lengths times scale), constrained to stay a crank-rocker with crank 1
    (six linear inequalities on A, B, C).  ``polish``: then Gauss–Newton
    (``scipy.optimize.least_squares``) on the residual vectors with the foot
    angles free, kept only if it stays a crank-rocker and lowers the error:
    a zero-residual fit then reaches round-off.

    Parameters
    ----------
    match : Match (or anything with A, B, C, gx, gy)
    x, y : array_like (K,)
        Targets (any units).
    angles : array_like (K,), optional
        Crank angles of the targets from the first [rad] (prescribed timing,
        the crank turning counter-clockwise).
    samples : int
        Positions of a revolution used to find each target's nearest point
        before the Newton steps.

    Raises
    ------
    DescribedError
        ``"too_few_points"``; ``"angles_shape"``.
    """
    from mechcli.core.errors import ConvergenceError
    from mechcli.core.optimize.methods import minimize
    from mechcli.core.optimize.problem import Problem, Variable

    z = np.asarray(x, dtype=float).reshape(-1) + 1j * np.asarray(y, dtype=float).reshape(-1)
    target_points(z.real, z.imag)
    if angles is not None:
        angles = np.asarray(angles, dtype=float).reshape(-1)
        if angles.size != z.size:
            raise DescribedError("the timing needs one angle per target point", "angles_shape",
                                 points=z.size, angles=angles.size)
        angles = angles - angles[0]
    centre = z.mean()
    size = float(np.sqrt(np.mean(np.abs(z - centre) ** 2)))
    T = (z - centre) / size
    tx, ty, rot, sc = _initial_placement(match, T if angles is None else T, 720)
    fit = _PathFit(T, angles, samples, gamma_min)
    x0 = [match.A, match.B, match.C, match.gx, match.gy, tx, ty, rot, sc]
    names = ["A", "B", "C", "gx", "gy", "tx", "ty", "rotation", "scale"]
    if angles is not None:
        # theta0 from the crank angles of the targets' feet on the placed curve
        probe = _PathFit(T, None, samples)
        th, _, _ = probe.foot(np.array([x0]))
        x0.append(float(np.angle(np.mean(np.exp(1j * (th[0] - rot - angles))))))
        names.append("theta0")
    lo = [1.0, 1.0, 1.0, -20, -20, -50, -50, rot - 4 * math.pi, 1e-3] + \
        ([x0[-1] - 4 * math.pi] if angles is not None else [])
    hi = [50.0, 50.0, 50.0, 20, 20, 50, 50, rot + 4 * math.pi, 1e3] + \
        ([x0[-1] + 4 * math.pi] if angles is not None else [])
    x0 = np.clip(np.array(x0, dtype=float), lo, hi)
    variables = [Variable(n, a, b, s) for n, a, b, s in zip(names, lo, hi, x0)]
    names_g = [f"crank_rocker_{i}" for i in range(6)] + (["gamma_min", "gamma_max"]
                                                         if gamma_min > 0 else [])
    problem = Problem(variables, fit, names_g, chunk=64)
    message = ""
    try:
        res = minimize(problem, method, tol=1e-14, maxiter=maxiter)
        xb, message = res.x, res.message
    except ConvergenceError as exc:
        xb, message = exc.result.x, str(exc)
    except DescribedError as exc:
        if exc.reason != "infeasible":
            raise
        xb, message = np.asarray(exc.values.get("x", x0)), str(exc)
    xb = np.asarray(xb, dtype=float)
    ev = fit(xb[None, :])
    f_best = float(ev.f[0]) if ev.ok[0] else math.inf
    if polish:
        xp = _polish(fit, xb)
        if xp is not None:
            evp = fit(xp[None, :])
            inside = bool(np.all(xp[:len(lo)] >= lo) and np.all(xp[:len(hi)] <= hi))
            if evp.ok[0] and inside and np.all(evp.g[0] <= 0) and evp.f[0] < f_best:
                xb, f_best = xp, float(evp.f[0])
                message += "; polished by Gauss-Newton"
    _, pz, ok = fit.foot(xb[None, :])
    d = np.abs(pz[0] - T) * size
    X = dict(zip(names, xb.tolist()))
    X["tx"] = float(X["tx"] * size + centre.real)
    X["ty"] = float(X["ty"] * size + centre.imag)
    X["scale"] = float(X["scale"] * size)
    lk = placed_linkage(X["A"], X["B"], X["C"], X["gx"], X["gy"], X["tx"], X["ty"],
                        X["rotation"], X["scale"])
    return Refined(X, float(np.sqrt(np.mean(d ** 2))), float(np.max(d)), lk,
                   (X["tx"], X["ty"], X["rotation"], X["scale"]), size, method, message)


def _polish(fit: _PathFit, x: np.ndarray) -> Optional[np.ndarray]:
    """Gauss–Newton (trust region) on P(θ_i) - T_i with the θ_i free."""
    from scipy.optimize import least_squares

    th, _, ok = fit.foot(x[None, :])
    if not ok[0]:
        return None
    n = x.size
    timed = fit.angles is not None
    T = fit.T
    K = T.size

    def points(V: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:   # V (M, n [+ K])
        X = V[:, :n]
        # the columns are A … scale (mypy checks starred items against branch too)
        lk = placed_linkage(*(X[:, j:j + 1] for j in range(9)))  # type: ignore[arg-type]
        q = (X[:, 7:8] + X[:, 9:10] + cast(np.ndarray, fit.angles)[None, :]) if timed else V[:, n:]
        m = solve(lk, {1: DriverMotion(q)}, order=0)
        p = m.points["P"]
        return np.broadcast_to(p.x + 1j * p.y, q.shape), np.all(m.feasible, axis=1)

    def res(v: np.ndarray) -> np.ndarray:
        pz, _ = points(v[None, :])
        r = pz[0] - T
        return np.concatenate([r.real, r.imag])

    def jac(v: np.ndarray) -> np.ndarray:
        h = 1e-7 * np.maximum(np.abs(v), 1.0)
        V = np.repeat(v[None, :], 2 * v.size, axis=0)
        idx = np.arange(v.size)
        V[2 * idx, idx] += h
        V[2 * idx + 1, idx] -= h
        pz, _ = points(V)
        d = (pz[0::2] - pz[1::2]) / (2 * h)[:, None]
        return np.concatenate([d.real, d.imag], axis=1).T

    v0 = x.copy() if timed else np.concatenate([x, th[0]])
    try:
        with np.errstate(all="ignore"):
            out = least_squares(res, v0, jac=jac, method="lm" if 2 * K >= v0.size else "trf",
                                xtol=1e-15, ftol=1e-15,
                                gtol=1e-15, max_nfev=200 * (v0.size + 1))
    except Exception:
        return None
    if not np.all(np.isfinite(out.x)):
        return None
    return out.x[:n]


# ---------------------------------------------------------------------------
# path synthesis: the search's matches refined and checked
# ---------------------------------------------------------------------------
@record
class PathCandidate:
    """One refined atlas match: the match, its refinement (None when not
    refined), the transmission angle's range over a revolution [rad] (the angle
    BCD at the coupler-follower joint) and the chain's Grashof type."""

    match: Match
    refined: Optional[Refined]
    mu_min: float
    mu_max: float
    kind: str


def path_synthesis(matches: Any, x: Any, y: Any, angles: Optional[Any] = None,
                   method: str = "slsqp", samples: int = 360, gamma_min: float = 0.0):
    """Refine each of the search's ``matches`` on the real path error (see
    :func:`refine`) and measure its transmission angles; the candidates sorted by
    their path error (RMS)."""
    from mechcli.core.optimize import terms

    out = []
    for m in matches:
        ref = refine(m, x, y, angles, method=method, samples=samples, gamma_min=gamma_min)
        A, B, C = (ref.x_opt[k] for k in ("A", "B", "C"))
        lk = placed_linkage(A, B, C, ref.x_opt["gx"], ref.x_opt["gy"], *ref.placement)
        pop = terms.Population(lk, 1, samples)
        lo, hi, ok = terms.transmission_range(pop.revolution(0), ["C"])
        out.append(PathCandidate(m, ref, float(np.ravel(lo)[0]), float(np.ravel(hi)[0]),
                                 chain_kind(A, B, C)[0]))
    # every candidate here has its refinement (refine returns one)
    out.sort(key=lambda c: cast(Refined, c.refined).error_rms)
    # matches that refine to the same linkage are one candidate
    distinct: List[PathCandidate] = []
    for c in out:
        v = np.array([cast(Refined, c.refined).x_opt[k] for k in ("A", "B", "C", "gx", "gy")])
        if all(np.max(np.abs(v - w)) > 1e-6 * max(1.0, float(np.max(np.abs(v))))
               for w in (np.array([cast(Refined, d.refined).x_opt[k]
                                   for k in ("A", "B", "C", "gx", "gy")])
                         for d in distinct)):
            distinct.append(c)
    return distinct
