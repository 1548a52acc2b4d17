"""Closed-form statics of one Assur group (a driver or a dyad), vectorized over positions.

:mod:`.kinetostatics` assembles, per element of the linkage, a small block
``A x = b`` (3 unknowns for a driver, 6 for a dyad) from the last element back
to the drivers.  Every dyad of the engine (RRR, RRP, RPR, PRP) has the same
structure: links a and b, an outer pair on each (to an earlier link or the
frame) and an inner pair between them; each pair has two unknowns (the force
components of a revolute pair; the normal force and the couple of a prismatic
one).  Its block is solved here in closed form, as by hand:

1. the outer pair of a link enters its three equations through a 3 x 2 matrix
   whose left null vector ``w = c1 x c2`` (the cross product of its columns)
   is the equation free of that pair (the moments about a revolute pin; the
   forces along a prismatic guide);
2. that equation of link a and of link b gives a 2 x 2 system for the inner
   pair's two unknowns (Cramer's rule);
3. each outer pair then follows from its link's force equations (and, for a
   prismatic pair, the moment equation for its couple).

A driver block (a crank's pin and torque; a slider driver's guide reaction,
couple and force) is a 2 x 2 system on the force equations and the moment
equation for the column that only enters it.

The coefficients are those of the general system (scaled as there), Python
floats where constant (exact zeros skipped, +-1 folded), arrays over the
positions otherwise; a negated array stays pending (:class:`~.folding.Neg`)
until a sum or a product takes the sign, so a -1 costs no pass over memory (the
arithmetic is :mod:`.folding`'s).  :func:`factor` does the part that depends on
the matrix only, :func:`apply` the rest for one right-hand side (the condition number
solves the identity's columns with the same factor: unit right-hand sides, all
floats, a few passes over memory each).  Positions where the
2 x 2 determinant vanishes give zeros and are reported, as the general
elimination (:mod:`.elimination`) does; anything the layout does not describe
is left to it (:func:`layout` returns None).
"""

from __future__ import annotations

from typing import Any, Sequence, Tuple

import numpy as np

from mechcli.core.linkage.folding import Neg, add, const, cross3, div, dot3, mul, neg, sub, value  # noqa: F401
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

# the folding arithmetic (:mod:`.folding`); the underscored names are its earlier
# names here, kept for code that imported them
_Neg, _neg, _mul, _add, _sub, _div = Neg, neg, mul, add, sub, div
_dot3, _cross = dot3, cross3


def _isf(v: Any):
    return type(v) is float


@record
class DriverLayout:
    """A driver block: the local columns ``forces`` of the two unknowns its force
    equations give, and the column ``moment`` only its moment equation has."""

    forces: Tuple[int, int]
    moment: int


@record
class OuterPair:
    """A dyad link's outer pair: ``kind`` "R" or "P", the local columns ``cols`` of
    its two unknowns, and ``base``, the local row of its link's first equation."""

    kind: str
    cols: Tuple[int, int]
    base: int


@record
class DyadLayout:
    """A dyad block: the outer pairs of its links ``a`` and ``b`` and the local
    columns ``inner`` of the inner pair's two unknowns."""

    a: OuterPair
    inner: Tuple[int, int]
    b: OuterPair


def layout(kind_of, cols_of_rows, nrows):
    """The closed-form layout of one block (a :class:`DriverLayout` or a
    :class:`DyadLayout`), or None (the general elimination).

    ``kind_of``: per local pair (in the block's column order, two columns
    each) its kind "R"/"P" and the local link indices (0 or 1) it acts on;
    ``cols_of_rows``: per local column, ``{local row: is_const}`` of its
    nonzero entries; ``nrows``: 3 (a driver) or 6 (a dyad).
    """
    if nrows == 3:
        ncol = len(cols_of_rows)
        if ncol != 3:
            return None
        only_m = [c for c in range(3) if set(cols_of_rows[c]) <= {2}]
        if len(only_m) != 1 or not cols_of_rows[only_m[0]]:
            return None
        m = only_m[0]
        f = tuple(c for c in range(3) if c != m)
        return DriverLayout(f, m)
    if nrows != 6 or len(kind_of) != 3 or len(cols_of_rows) != 6:
        return None
    outer, inner = {}, None
    for p, (kind, links) in enumerate(kind_of):
        if len(links) == 2:
            if inner is not None:
                return None
            inner = p
        elif len(links) == 1 and links[0] not in outer:
            outer[links[0]] = p
        else:
            return None
    if inner is None or set(outer) != {0, 1}:
        return None
    out = []
    for ln in (0, 1):
        p = outer[ln]
        kind = kind_of[p][0]
        c0, c1 = 2 * p, 2 * p + 1
        rows = range(3 * ln, 3 * ln + 3)
        r0, r1 = cols_of_rows[c0], cols_of_rows[c1]
        if not set(r0) | set(r1) <= set(rows):
            return None
        base = 3 * ln
        if kind == "R":
            # (s, 0, mx) and (0, s, my): the force rows give the components
            if not (r0.get(base) and r1.get(base + 1) and base + 1 not in r0
                    and base not in r1):
                return None
        else:
            # (ux, uy, um) and (0, 0, s): the normal force, then the couple
            if set(r1) != {base + 2} or not r1[base + 2]:
                return None
        out.append(OuterPair(kind, (c0, c1), base))
    return DyadLayout(out[0], (2 * inner, 2 * inner + 1), out[1])


def _guard(det: Any):
    """``(det, singular)``: exact zeros replaced by 1 (flagged)."""
    if type(det) is Neg:
        det, sing = _guard(det.v)
        return neg(det), sing
    if _isf(det):
        if det == 0.0:
            return 1.0, True
        return det, None
    if det.all():  # (one pass, no mask: the mask only where a zero is)
        return det, None
    zero = det == 0.0
    return np.where(zero, 1.0, det), zero


def _cramer(p: Any, q: FloatOrArray, r: Any, s: Any, det: Any):
    """``(p q - r s) / det``; for a pending negation of ``det`` the products are
    subtracted the other way round (no pass for the sign)."""
    if type(det) is Neg:
        return div(sub(mul(r, s), mul(p, q)), det.v)
    return div(sub(mul(p, q), mul(r, s)), det)


def _residual(bk: Any, a0: Any, y0: Any, a1: Any, y1: Any, over: Any):
    """``(bk - a0 y0 - a1 y1) / over``; for a negative float ``over`` (the force of
    link i on j is minus that of j on i) the terms are summed the other way round
    (no pass for the sign)."""
    if _isf(over) and over < 0.0:
        return div(sub(add(mul(a0, y0), mul(a1, y1)), bk), -over)
    return div(sub(sub(bk, mul(a0, y0)), mul(a1, y1)), over)


def _outer(cols: Tuple[int, int], base: int, A: Sequence[Sequence[Any]], r: Any):
    """A prismatic outer pair's two unknowns from its link's residual equations
    ``r`` (a revolute one's come from :func:`_residual` directly)."""
    c0, c1 = cols
    ux, uy, um = A[base][c0], A[base + 1][c0], A[base + 2][c0]
    n = div(add(mul(ux, r[0]), mul(uy, r[1])), add(mul(ux, ux), mul(uy, uy)))
    return n, div(sub(r[2], mul(um, n)), A[base + 2][c1])


def factor(lay: Any, A: Sequence[Sequence[Any]]):
    """The part of a block's closed-form solution that depends on ``A`` only
    (the equations free of the outer pairs, the 2 x 2 determinant), for
    :func:`apply` to any number of right-hand sides."""
    if type(lay) is DriverLayout:
        f0, f1 = lay.forces
        a00, a01, a10, a11 = A[0][f0], A[0][f1], A[1][f0], A[1][f1]
        det, sing = _guard(sub(mul(a00, a11), mul(a01, a10)))
        return lay, None, (a00, a01, a10, a11), det, sing
    i0, i1 = lay.inner
    ws, gs = [], []
    for c, base in ((lay.a.cols, lay.a.base), (lay.b.cols, lay.b.base)):
        col0 = (A[base][c[0]], A[base + 1][c[0]], A[base + 2][c[0]])
        col1 = (A[base][c[1]], A[base + 1][c[1]], A[base + 2][c[1]])
        w = cross3(col0, col1)
        ws.append(w)
        gs.append((dot3(w, (A[base][i0], A[base + 1][i0], A[base + 2][i0])),
                   dot3(w, (A[base][i1], A[base + 1][i1], A[base + 2][i1]))))
    (g00, g01), (g10, g11) = gs
    det, sing = _guard(sub(mul(g00, g11), mul(g01, g10)))
    return lay, ws, (g00, g01, g10, g11), det, sing


def apply(fac, A, b, shape,
          arrays=True):
    """Solve ``A x = b`` with a :func:`factor` of ``A``: X, a list of the unknowns
    in the block's column order (zero at the singular positions); arrays of
    ``shape`` (or, with ``arrays`` False, Python floats where they are constant)."""
    lay, ws, g, det, sing = fac
    if type(lay) is DriverLayout:
        (f0, f1), m = lay.forces, lay.moment
        a00, a01, a10, a11 = g
        x0 = _cramer(a11, b[0], a01, b[1], det)
        x1 = _cramer(a00, b[1], a10, b[0], det)
        xm = _residual(b[2], A[2][f0], x0, A[2][f1], x1, A[2][m])
        X = [None] * 3
        X[f0], X[f1], X[m] = x0, x1, xm
    else:
        (i0, i1), ba, bb = lay.inner, lay.a.base, lay.b.base
        g00, g01, g10, g11 = g
        h0 = dot3(ws[0], (b[ba], b[ba + 1], b[ba + 2]))
        h1 = dot3(ws[1], (b[bb], b[bb + 1], b[bb + 2]))
        y0 = _cramer(g11, h0, g01, h1, det)
        y1 = _cramer(g00, h1, g10, h0, det)
        X = [None] * 6
        X[i0], X[i1] = y0, y1
        for outer in (lay.a, lay.b):
            c, base = outer.cols, outer.base
            if outer.kind == "R":  # (s, 0, mx) and (0, s, my): each force row gives one component
                X[c[0]], X[c[1]] = (
                    _residual(b[base + k], A[base + k][i0], y0, A[base + k][i1], y1,
                              A[base + k][c[k]]) for k in (0, 1))
                continue
            r = [sub(sub(b[base + k], mul(A[base + k][i0], y0)), mul(A[base + k][i1], y1))
                 for k in (0, 1, 2)]
            X[c[0]], X[c[1]] = _outer(c, base, A, r)
    X = [value(x) for x in X]
    if sing is not None:
        if sing is True:
            X = [np.zeros(shape) for _ in X]
        else:
            X = [np.where(sing, 0.0, x) for x in X]
    if arrays:
        X = [np.full(shape, x) if _isf(x) else x for x in X]
    return X


def solve(lay: Any, A: Sequence[Sequence[Any]], b: Sequence[Any], shape: Tuple[int, ...]):
    """Solve one block in closed form: ``(X, singular)`` (X a list of the
    unknowns in the block's column order, arrays of ``shape``; ``singular`` None,
    True or a mask of the positions with a vanishing determinant, where X is
    zero)."""
    fac = factor(lay, A)
    return apply(fac, A, b, shape), fac[4]
