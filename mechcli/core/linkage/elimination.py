"""Batched sparse Gaussian elimination: one small linear system per position.

The kinetostatic system of a linkage is block lower-triangular over its
Assur groups; each block (3 or 6 unknowns) is solved for all positions at once
by :func:`gauss` (see :mod:`mechcli.core.linkage.kinetostatics`).
"""

from __future__ import annotations

from typing import Any

import numpy as np


def _nonzero(v: Any):
    return not (isinstance(v, float) and v == 0.0)


def gauss(A, B):
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
