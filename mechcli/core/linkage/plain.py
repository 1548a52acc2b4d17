"""Readable twins of the engine's kernels: each element's mathematics as written by hand.

The elements of :mod:`.elements` are fast because their ``step`` methods are fused numpy
with scratch buffers, written for memory traffic rather than for reading.  This module is
the same mathematics in the terms of their docstrings, one formula per line: points are
complex numbers ``x + iy`` (a rotation by a link's angle is a product with ``e^{iθ}``, the
velocity of a link's point is ``iω r``), every rate comes from one small linear solve of
the differentiated loop equation.  Nothing here is used by the engine;
``tests/property/test_plain_twins.py`` checks that every twin equals its element's
``step`` on random batched inputs (positions, velocities, accelerations).

A known point is a :class:`Pt` (position, velocity, acceleration, complex arrays), a
solved link a :class:`Ln` (angle, angular velocity, angular acceleration).  SI units and
radians.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from mechcli.core.types import FloatOrArray


class Pt(NamedTuple):
    """A point's position, velocity and acceleration as complex numbers [m, m/s, m/s²]."""

    p: np.ndarray
    v: np.ndarray
    a: np.ndarray


class Ln(NamedTuple):
    """A link's angle, angular velocity and angular acceleration [rad, rad/s, rad/s²]."""

    theta: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray


FRAME = Ln(np.zeros(()), np.zeros(()), np.zeros(()))


def _solve2(u: FloatOrArray, w: FloatOrArray, rhs: FloatOrArray):
    """``x, y`` real with ``x u + y w = rhs`` (complex u, w, rhs: two real equations)."""
    det = u.real * w.imag - u.imag * w.real
    x = (rhs.real * w.imag - rhs.imag * w.real) / det
    y = (u.real * rhs.imag - u.imag * rhs.real) / det
    return x, y


def carried(g: Pt, link: Ln, r: FloatOrArray):
    """The point ``g + r`` fixed on ``link`` (carried by it): position, velocity
    ``g' + iω r``, acceleration ``g'' + (iα − ω²) r``."""
    return Pt(g.p + r, g.v + 1j * link.omega * r,
              g.a + (1j * link.alpha - link.omega ** 2) * r)


def crank(pivot, length, theta, omega,
          alpha=0.0):
    """:class:`~.elements.Crank`: ``point = pivot + length e^{iθ}``."""
    link = Ln(theta, omega, alpha)
    return carried(pivot, link, length * np.exp(1j * theta)), link


def point_on_link(origin: Pt, link: Ln, along: FloatOrArray, normal: FloatOrArray):
    """:class:`~.elements.PointOnLink`: ``origin + (along + i normal) e^{iθ}``."""
    return carried(origin, link, (along + 1j * normal) * np.exp(1j * link.theta))


def rrr(A: Pt, length_a: FloatOrArray, B: Pt, length_b: FloatOrArray, branch: int = 1):
    """:class:`~.elements.RRR`: the joint J where the circle of radius ``length_a`` about
    A meets that of ``length_b`` about B, left of A -> B for ``branch = +1``.

    Rates from ``J' = A' + iω_a r_a = B' + iω_b r_b`` and the same differentiated once
    more (r_a = J − A, r_b = J − B).  Returns ``(J, link_a, link_b)``."""
    d = B.p - A.p
    dist = np.abs(d)
    along = (length_a ** 2 - length_b ** 2 + dist ** 2) / (2 * dist)
    height = branch * np.sqrt(length_a ** 2 - along ** 2)
    J = A.p + (along + 1j * height) * d / dist
    ra, rb = J - A.p, J - B.p
    wa, wb = _solve2(1j * ra, -1j * rb, B.v - A.v)
    aa, ab = _solve2(1j * ra, -1j * rb, B.a - A.a + wa ** 2 * ra - wb ** 2 * rb)
    la, lb = Ln(np.angle(ra), wa, aa), Ln(np.angle(rb), wb, ab)
    return carried(A, la, ra), la, lb


def _guide(G: Pt, link: Ln, angle: FloatOrArray, offset: FloatOrArray):
    """A guide line carried by ``link`` through its point G, at ``angle`` to the link,
    shifted by ``offset`` along its left normal: ``(base, u)``, base + s u on the line."""
    u = np.exp(1j * (link.theta + angle))
    return G.p + 1j * offset * u, u


def rrp(P: Pt, length: FloatOrArray, G: Pt, guide: Ln, guide_angle: float = 0.0,
        offset: float = 0.0, branch: int = 1):
    """:class:`~.elements.RRP`: the pin J on the guide line (base + s u) at ``length``
    from P, the larger s for ``branch = +1``.

    J seen from the guide link (its coincident point plus the slide) and from the rod:
    ``ṡ u + [G' + iω_g (J − G)] = P' + iω r`` and its derivative with the Coriolis term
    ``2 iω_g ṡ u``.  Returns ``(J, rod, (s, ṡ, s̈))``."""
    base, u = _guide(G, guide, guide_angle, offset)
    foot = np.real(np.conj(u) * (P.p - base))          # u · (P − base)
    h = np.imag(np.conj(u) * (P.p - base))             # u × (P − base)
    s = foot + branch * np.sqrt(length ** 2 - h ** 2)
    J = base + s * u
    r = J - P.p
    on_guide = carried(G, guide, J - G.p)                # the guide's point under J
    sd, w = _solve2(u, -1j * r, P.v - on_guide.v)
    coriolis = 2j * guide.omega * sd * u
    sdd, al = _solve2(u, -1j * r, P.a - w ** 2 * r - on_guide.a - coriolis)
    rod = Ln(np.angle(r), w, al)
    return carried(P, rod, r), rod, (s, sd, sdd)


def rpr(P: Pt, C: Pt, offset: float = 0.0, branch: int = 1):
    """:class:`~.elements.RPR`: the guide link turning about C passes through the block
    pinned at P, its line at ``offset`` to the left of C: ``P − C = (s + i e) u``, s > 0
    for ``branch = +1``.

    Rates from ``P' − C' = ṡ u + iω (P − C)`` and its derivative
    ``P'' − C'' = s̈ u + 2iω ṡ u + iα (P − C) − ω² (P − C)``.
    Returns ``(guide, (s, ṡ, s̈))``."""
    d = P.p - C.p
    s = branch * np.sqrt(np.abs(d) ** 2 - offset ** 2)
    u = d / (s + 1j * offset)
    sd, w = _solve2(u, 1j * d, P.v - C.v)
    sdd, al = _solve2(u, 1j * d, P.a - C.a - 2j * w * sd * u + w ** 2 * d)
    return Ln(np.angle(u), w, al), (s, sd, sdd)


def prp(Ga: Pt, guide_a: Ln, angle_a: FloatOrArray, offset_a: FloatOrArray, Gb: Pt, guide_b: Ln,
        angle_b: FloatOrArray, offset_b: FloatOrArray):
    """:class:`~.elements.PRP`: the pin J where two guide lines meet,
    ``base_a + s_a u_a = base_b + s_b u_b``.

    Each side: J's velocity is the guide's coincident point plus the slide,
    ``[G' + iω (J − G)] + ṡ u``; equal on both sides (and so their derivatives, with the
    Coriolis terms ``2 iω ṡ u``).  Returns ``(J, (s_a, ṡ_a, s̈_a), (s_b, ṡ_b, s̈_b))``."""
    base_a, ua = _guide(Ga, guide_a, angle_a, offset_a)
    base_b, ub = _guide(Gb, guide_b, angle_b, offset_b)
    sa, sb = _solve2(ua, -ub, base_b - base_a)
    J = base_a + sa * ua
    on_a, on_b = carried(Ga, guide_a, J - Ga.p), carried(Gb, guide_b, J - Gb.p)
    sda, sdb = _solve2(ua, -ub, on_b.v - on_a.v)
    cor_a, cor_b = 2j * guide_a.omega * sda * ua, 2j * guide_b.omega * sdb * ub
    sdda, sddb = _solve2(ua, -ub, on_b.a + cor_b - on_a.a - cor_a)
    joint = Pt(J, on_a.v + sda * ua, on_a.a + cor_a + sdda * ua)
    return joint, (sa, sda, sdda), (sb, sdb, sddb)


# ---------------------------------------------------------------------------
# the force blocks (:mod:`.dyad_statics`, :mod:`.elimination`, :mod:`.kinetostatics`)
# ---------------------------------------------------------------------------
def block_solve(A: Any, b: Any):
    """:func:`.dyad_statics.solve` and :func:`.elimination.gauss`: one block ``A x = b``
    (entries floats or arrays over N positions) by ``numpy.linalg.solve``, one position
    at a time.  Returns the unknowns as a (k, N) array."""
    n = max(np.size(v) for row in list(A) + [b] for v in row)
    X = np.empty((len(A), n))
    for j in range(n):
        M = [[np.broadcast_to(v, (n,))[j] for v in row] for row in A]
        X[:, j] = np.linalg.solve(M, [np.broadcast_to(v, (n,))[j] for v in b])
    return X


def rrr_dyad_reactions(B: Any, C: Any, D: Any, Fa: Any,
                       Sa: Any, Ma: Any, Fb: Any, Sb: Any,
                       Mb: Any):
    """The RRR dyad's pair reactions (:mod:`.dyad_statics`) from the equilibrium of its
    two links, written out.  Link a (pins B, C) carries the force ``Fa`` at ``Sa`` and
    the couple ``Ma``, link b (pins C, D) ``Fb`` at ``Sb`` and ``Mb`` (every load summed,
    inertia included; points and forces complex).  Unknowns: ``R_B`` on link a from
    its outer link, ``R_C`` of link a on link b, ``R_D`` on link b from its outer link:

    * link a: ``R_B − R_C + Fa = 0`` and ``B × R_B − C × R_C + Sa × Fa + Ma = 0``
    * link b: ``R_C + R_D + Fb = 0`` and ``C × R_C + D × R_D + Sb × Fb + Mb = 0``

    (moments about the origin).  Returns ``(R_B, R_C, R_D)``, complex."""
    out = np.empty((3, np.size(B)), dtype=complex)
    for j in range(np.size(B)):
        b, c, d = B[j], C[j], D[j]
        A = [[1, 0, -1, 0, 0, 0],                      # ΣFx of a
             [0, 1, 0, -1, 0, 0],                      # ΣFy of a
             [-b.imag, b.real, c.imag, -c.real, 0, 0],  # ΣM of a
             [0, 0, 1, 0, 1, 0],                       # ΣFx of b
             [0, 0, 0, 1, 0, 1],                       # ΣFy of b
             [0, 0, -c.imag, c.real, -d.imag, d.real]]  # ΣM of b
        mom_a = Sa[j].real * Fa[j].imag - Sa[j].imag * Fa[j].real + Ma[j]
        mom_b = Sb[j].real * Fb[j].imag - Sb[j].imag * Fb[j].real + Mb[j]
        x = np.linalg.solve(A, [-Fa[j].real, -Fa[j].imag, -mom_a,
                                -Fb[j].real, -Fb[j].imag, -mom_b])
        out[:, j] = x[0::2] + 1j * x[1::2]
    return out[0], out[1], out[2]


def crank_reactions(A: Any, B: Any, R_B: Any, F: Any,
                    S: Any, M: Any):
    """A crank's frame reaction and balancing torque (the driver block of
    :mod:`.dyad_statics`): the crank (pins A on the frame, B) carries ``F`` at ``S``,
    the couple ``M`` and ``−R_B`` at B (``R_B`` its force on the next link).
    ``R_A − R_B + F = 0`` and ``A × R_A − B × R_B + S × F + M + M_b = 0``, solved by
    ``numpy.linalg.solve`` per position.  Returns ``(R_A, M_b)``."""
    ra, mb = np.empty(np.size(A), dtype=complex), np.empty(np.size(A))
    for j in range(np.size(A)):
        a, fb, f = A[j], R_B[j], F[j] - R_B[j]
        mom = (B[j].real * -fb.imag + B[j].imag * fb.real
               + S[j].real * F[j].imag - S[j].imag * F[j].real + M[j])
        x = np.linalg.solve([[1, 0, 0], [0, 1, 0], [-a.imag, a.real, 1]],
                            [-f.real, -f.imag, -mom])
        ra[j], mb[j] = x[0] + 1j * x[1], x[2]
    return ra, mb
