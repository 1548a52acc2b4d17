"""Constant-folding arithmetic of the kinetostatics: floats, arrays and pending negations.

The coefficients and right-hand sides of the kinetostatic system
(:mod:`.kinetostatics`, :mod:`.dyad_statics`) are Python floats where they are the
same at every position (exact zeros, the +-1 of a force and its reaction, a fixed
point's coordinates, a block on a fixed guide) and arrays over the positions
otherwise.  A pass over memory costs about as much as the Python call that makes
it for a few thousand positions, so the arithmetic here counts them:

* :func:`mul`, :func:`add`, :func:`sub` and :func:`div` fold a float 0 or +-1
  (``mul(0.0, a)`` is ``0.0``, ``mul(1.0, a)`` is ``a`` itself, no pass), and
  compute float with float as floats;
* a negation stays pending (:class:`Neg`, made by :func:`neg`) until a sum or a
  product takes its sign (``sub(a, Neg(b))`` is ``a + b``: one pass, not two);
* :func:`value` computes a pending negation where a number leaves this arithmetic
  (give it nothing else); :func:`const` turns an array that holds one value at
  every position (a stride-0 broadcast, as the engine gives a fixed point or a
  fixed angle) into a float, so that it folds.

The results are bit-for-bit those of plain numpy arithmetic on the same numbers:
a fold only skips an operation that would not change a value (``x * 1``, ``x + 0``)
or moves a sign to where it is exact (``-(a - b)`` is ``b - a``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["Neg", "neg", "value", "const", "exact_zero", "mul", "add", "sub", "div",
           "dot3", "cross3"]

_ZERO = 0.0


class Neg:
    """``-v`` not yet computed: a coefficient of -1 (the force of link i on j is
    minus that of j on i) folded into the next sum or product instead of a pass
    over memory of its own.  :func:`value` computes it where it leaves the algebra."""

    __slots__ = ("v",)

    def __init__(self, v: Any) -> None:
        self.v = v

    def __abs__(self):
        return abs(self.v)


def neg(a: Any):
    """``-a``: a float negated, a pending negation undone, an array left pending."""
    ta = type(a)
    if ta is Neg:
        return a.v
    if ta is float:
        return -a
    return Neg(a)


def value(a: Any):
    """``a`` as a float or an array (a pending negation computed)."""
    return -a.v if type(a) is Neg else a


def const(a: Any):
    """A Python float for an array that holds one value at every position (a
    stride-0 broadcast, as the engine gives a fixed point or a fixed angle),
    anything else unchanged: the arithmetic here folds it."""
    if type(a) is np.ndarray and a.ndim and not any(a.strides):
        return float(a.reshape(-1)[0])
    return a


def exact_zero(v: Any):
    """Whether ``v`` is a Python number equal to 0 (an array never is)."""
    return (type(v) is float or type(v) is int) and v == 0


# (the type tests are written out, not calls of a helper: these run a few hundred times
# a call, and the fixed cost of one kinetostatics call is a goal of its own)
def mul(a: Any, b: Any):
    """``a * b``, folded (a float 0 or +-1, a pending sign)."""
    ta, tb = type(a), type(b)
    if ta is float:
        if a == 0.0:
            return _ZERO
        if a == 1.0:
            return b
        if a == -1.0:
            return neg(b)
        if tb is Neg:
            return mul(-a, b.v)
    if tb is float:
        if b == 0.0:
            return _ZERO
        if b == 1.0:
            return a
        if b == -1.0:
            return neg(a)
        if ta is Neg:
            return mul(a.v, -b)
    if ta is Neg:
        return mul(a.v, b.v) if tb is Neg else neg(mul(a.v, b))
    if tb is Neg:
        return neg(mul(a, b.v))
    return a * b


def add(a: Any, b: Any):
    """``a + b``, folded (a float 0, a pending sign)."""
    ta, tb = type(a), type(b)
    if ta is float and a == 0.0:
        return b
    if tb is float and b == 0.0:
        return a
    if tb is Neg:
        return neg(add(a.v, b.v)) if ta is Neg else sub(a, b.v)
    if ta is Neg:
        return sub(b, a.v)
    return a + b


def sub(a: Any, b: Any):
    """``a - b``, folded (a float 0, a pending sign)."""
    ta, tb = type(a), type(b)
    if tb is float and b == 0.0:
        return a
    if ta is float and a == 0.0:
        return neg(b)
    if tb is Neg:
        return sub(b.v, a.v) if ta is Neg else add(a, b.v)
    if ta is Neg:
        return neg(add(a.v, b))
    return a - b


def div(a: Any, b: Any):
    """``a / b``, folded (a float +-1, a pending sign)."""
    ta, tb = type(a), type(b)
    if tb is float:
        if b == 1.0:
            return a
        if b == -1.0:
            return neg(a)
        if ta is Neg:
            return a.v / -b
    if tb is Neg:
        return div(a.v, b.v) if ta is Neg else neg(div(a, b.v))
    if ta is Neg:
        return neg(div(a.v, b))
    return a / b


def dot3(w: Any, c: Any):
    """``w . c`` of two 3-vectors (floats or arrays), folded."""
    return add(add(mul(w[0], c[0]), mul(w[1], c[1])), mul(w[2], c[2]))


def cross3(c1: Any, c2: Any):
    """``c1 x c2`` of two 3-vectors (floats or arrays), folded."""
    return (sub(mul(c1[1], c2[2]), mul(c1[2], c2[1])),
            sub(mul(c1[2], c2[0]), mul(c1[0], c2[2])),
            sub(mul(c1[0], c2[1]), mul(c1[1], c2[0])))
