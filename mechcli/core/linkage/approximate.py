"""The approximate (series) slider-crank of the textbooks.

For a centred slider-crank (offset e = 0) with crank r = l1, rod l = l2 and
n = l/r > 1, the slide measured from the crank pivot A is exactly

    s = r cos θ + b sqrt(l² - r² sin²θ)        (b = +1 slider right of A, -1 left)

and the series in λ = 1/n, kept to its first term, gives the books' model

    s ≈ r cos θ + b (l - (r / 2n) sin²θ)
    v ≈ -ωr (sin θ + b sin 2θ / 2n)
    a ≈ -ω²r (cos θ + b cos 2θ / n)

i.e. the piston displacement from top dead centre x = r(1 - cos θ) + (r/2n) sin²θ,
v = ωr(sin θ + sin 2θ/2n), a = ω²r(cos θ + cos 2θ/n) with the sign of mechcli's
slide s3 (s3 = l + r - x for b = +1).  With a crank acceleration α the chain rule
adds ds/dθ · α to a.  The next term of the series is -b r λ³ sin⁴θ / 8, so the
differences to the exact model shrink like 1/n³ (relative to r, ωr, ω²r).

The same series gives the books' moment arm of the piston effort F_P about the
crank pivot (:func:`moment_arm`): T ≈ F_P r (sin θ + sin 2θ / 2n), θ from the
head-end dead centre; exactly it is r sin(θ + φ) / cos φ.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from mechcli.core.numerics import bracketed_root
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    pass

if TYPE_CHECKING:
    from mechcli.core.linkage.engine import LinkageMotion

#: the rounding of a derivative of the series, relative to the sum of its terms' sizes
#: (a few operations on the rounded angle and lengths)
_EPS = float(np.finfo(float).eps)


def series(q: np.ndarray, r: FloatOrArray, l: FloatOrArray, branch: int = 1):
    """``(s, ds/dθ, d²s/dθ²)`` of the first-order series at crank angles *q* [rad]."""
    q = np.asarray(q, dtype=float)
    n = l / r
    b = 1.0 if branch >= 0 else -1.0
    s = r * np.cos(q) + b * (l - r / (2 * n) * np.sin(q) ** 2)
    ds = -r * (np.sin(q) + b * np.sin(2 * q) / (2 * n))
    dds = -r * (np.cos(q) + b * np.cos(2 * q) / n)
    return s, ds, dds


def exact(q: np.ndarray, r: FloatOrArray, l: FloatOrArray, branch: int = 1):
    """``(s, ds/dθ, d²s/dθ²)`` of the exact centred slider-crank (closed form)."""
    q = np.asarray(q, dtype=float)
    b = 1.0 if branch >= 0 else -1.0
    sin, cos = np.sin(q), np.cos(q)
    root = np.sqrt(l * l - (r * sin) ** 2)
    s = r * cos + b * root
    ds = -r * sin - b * r * r * sin * cos / root
    dds = (-r * cos - b * r * r * np.cos(2 * q) / root
           - b * (r * r * sin * cos) ** 2 / root ** 3)
    return s, ds, dds


def moment_arm(q: np.ndarray, r: FloatOrArray, l: FloatOrArray, branch: int = 1):
    """The series moment arm [m] of the piston effort about the crank pivot at crank
    angles *q* [rad]: the turning moment is T ≈ F_P · arm, F_P along the line of
    stroke toward the crank (positive pushing the piston toward the crank pivot).

    By virtual work with a massless rod, T = F_P · (d · u) · ds/dθ (d the direction
    toward the crank, u that of increasing s; d · u = −b for the centred
    slider-crank), so with the series' ds/dθ

        arm = −b ds/dθ = r (b sin θ + sin 2θ / 2n),

    i.e. r (sin θ + sin 2θ / 2n) with θ measured from the head-end dead centre
    (θ1 = 0 for ``b = +1``, 180° for ``b = −1``).  Exactly it is r sin(θ + φ) / cos φ."""
    b = 1.0 if branch >= 0 else -1.0
    return -b * series(q, r, l, branch)[1]


def motion(q: np.ndarray, r: FloatOrArray, l: FloatOrArray, omega: FloatOrArray, alpha: float = 0.0,
           branch: int = 1):
    """Approximate ``(s, v, a)`` of the slider at crank angles *q* [rad], crank
    speed *omega* [rad/s] and acceleration *alpha* [rad/s²]."""
    s, ds, dds = series(q, r, l, branch)
    return s, ds * omega, dds * omega ** 2 + ds * alpha


def slopes(q: np.ndarray, r: FloatOrArray, l: FloatOrArray, omega: FloatOrArray, alpha: float = 0.0,
           branch: int = 1):
    """d/dθ of :func:`motion`'s ``(s, v, a)`` and of their derivatives, in closed form,
    at crank angles *q* [rad], with *omega* and *alpha* held at every angle (the book's
    convention: alpha enters the acceleration only).

    Returns ``((ds, dv, da), (dds, ddv, dda), (scale_s, scale_v, scale_a))``: the first
    and second derivatives with respect to θ, and the sum of the sizes of the terms of
    each first derivative (what its rounding is relative to)."""
    q = np.asarray(q, dtype=float)
    n = l / r
    b = 1.0 if branch >= 0 else -1.0
    sin, cos, sin2, cos2 = np.sin(q), np.cos(q), np.sin(2 * q), np.cos(2 * q)
    d1 = -r * (sin + b * sin2 / (2 * n))            # ds/dθ
    d2 = -r * (cos + b * cos2 / n)                  # d²s/dθ²
    d3 = r * (sin + 2 * b * sin2 / n)               # d³s/dθ³
    d4 = r * (cos + 4 * b * cos2 / n)               # d⁴s/dθ⁴
    size1 = r * (np.abs(sin) + np.abs(sin2) / (2 * n))
    size2 = r * (np.abs(cos) + np.abs(cos2) / n)
    size3 = r * (np.abs(sin) + 2 * np.abs(sin2) / n)
    first = (d1, d2 * omega, d3 * omega ** 2 + d2 * alpha)
    second = (d2, d3 * omega, d4 * omega ** 2 + d3 * alpha)
    sizes = (size1, size2 * abs(omega), size3 * omega ** 2 + size2 * abs(alpha))
    return first, second, sizes


def extremes(q: Any, values: Any, func: Callable[..., Any],
             slope: Any = None):
    """``(max, min)`` of ``func(x)`` (a closed form) over the sweep *q*, refined
    between the neighbours of the best sample.  Returns two ``(value, at, tol)``.

    ``slope(x) -> (d/dθ, d²/dθ², rounding of d/dθ)`` (arrays) is the closed-form
    derivative: the extreme is its root, closed by a safeguarded secant
    (:func:`~mechcli.core.numerics.bracketed_root`) to a float spacing, and ``tol`` is
    half the final bracket or the rounding of the derivative over its slope, whichever is
    larger.  An extreme at an end of the sweep (no root of the slope beside the best
    sample) is that sample, exactly (``tol = 0``).
    """
    out = []
    for sign, pick in ((1.0, np.argmax), (-1.0, np.argmin)):
        i = int(pick(values))
        at, value, tol = float(q[i]), float(values[i]), 0.0
        if slope is not None and q.size > 1:
            d_i = sign * float(slope(np.array([q[i]]))[0][0])
            j = i + 1 if d_i > 0 else i - 1          # the side the function still rises on
            if d_i != 0 and 0 <= j < q.size:
                d_j = sign * float(slope(np.array([q[j]]))[0][0])
                # rising towards the root, falling past it: sign * slope > 0 at lo, <= 0 at hi
                (lo, d_lo), (hi, d_hi) = ((q[i], d_i), (q[j], d_j)) if j > i else \
                    ((q[j], d_j), (q[i], d_i))
                if d_lo > 0 >= d_hi:                  # the slope changes sign: a root inside
                    a, b = bracketed_root(np.array([lo]), np.array([hi]),
                                          lambda x: sign * slope(x)[0], 1e-15,
                                          f_lo=np.array([d_lo]), f_hi=np.array([d_hi]))
                    x = 0.5 * float(a[0] + b[0])
                    _d, dd, noise = (float(v[0]) for v in slope(np.array([x])))
                    t = max(0.5 * abs(float(b[0] - a[0])), float(np.spacing(abs(x))),
                            4.0 * _EPS * noise / abs(dd) if dd else 0.0)
                    v = float(func(x))
                    if sign * v >= sign * value:     # never worse than the sample
                        at, value, tol = x, v, t
        out.append((value, float(at), float(tol)))
    return tuple(out)


def differences(approx: Any, exact_values: Any):
    """Largest |approximate - exact| over the sweep, absolute and relative.

    *approx*, *exact_values*: ``(s, v, a)`` arrays in the same units.  The
    relative difference of s is to the exact stroke (the range of s); of v and
    a to the largest exact |v| and |a| (0 when that is 0).
    """
    out = {}
    for key, x, y in zip("sva", approx, exact_values):
        diff = float(np.max(np.abs(np.asarray(x) - np.asarray(y)))) if np.size(x) else 0.0
        y = np.asarray(y)
        scale = float(np.ptp(y)) if key == "s" else float(np.max(np.abs(y)))
        out[key] = (diff, diff / scale if scale > 0 else 0.0)
    return out


def largest_relative_differences(n: int, samples: Any = 36001):
    """The largest relative differences (s to the stroke 2r, v to max |v|, a to
    max |a|) of the series over a whole turn for rod/crank ratio *n* (ω = 1, α = 0)."""
    q = np.linspace(0.0, 2 * math.pi, samples)
    ex = exact(q, 1.0, float(n))
    ap = series(q, 1.0, float(n))
    d = differences(ap, ex)
    return {k: v[1] for k, v in d.items()}


def slider_crank_parts(linkage):
    """``(r, l, branch, slide symbol suffix)`` of a slider-crank preset's linkage
    (crank, then an RRP dyad whose guide passes through the crank pivot)."""
    crank = next(el for el in linkage.elements if el.kind == "crank")
    dyad = next(el for el in linkage.elements if el.kind == "RRP")
    return float(crank.length), float(dyad.length), int(dyad.branch), str(dyad.slider)


def apply(linkage, sweep, result):
    """*result* (an exact :class:`~mechcli.core.linkage.kinematics.SweepResult` of a
    centred slider-crank) with the slide's s, v, a replaced by the series, their
    extremes refined on the roots of the closed-form derivatives; the other links'
    quantities stay exact.

    Returns ``(result, differences)``: :func:`differences` of the series to the
    exact closed form at the analysed positions [m, m/s, m/s²].
    """
    import dataclasses

    from mechcli.core.linkage.kinematics import Extreme

    r, l, branch, slider = slider_crank_parts(linkage)
    omega, alpha = float(sweep.dq), float(sweep.ddq)
    q = result.q
    approx = motion(q, r, l, omega, alpha, branch)
    s, ds, dds = exact(q, r, l, branch)
    diffs = differences(approx, (s, ds * omega, dds * omega ** 2 + ds * alpha))
    values, ext = dict(result.values), dict(result.extremes)
    for k, prefix in enumerate("sva"):
        sym = f"{prefix}{slider}"
        if sym not in values:
            continue
        values[sym] = approx[k]
        func = (lambda x, k=k: float(motion(np.array([x]), r, l, omega, alpha, branch)[k][0]))

        def slope(x: Any, k: int = k):
            first, second, sizes = slopes(x, r, l, omega, alpha, branch)
            return first[k], second[k], sizes[k]
        if q.size:
            (hv, ha, ht), (lv, la, lt) = extremes(q, approx[k], func, slope)
            ext[sym] = (Extreme(hv, ha, True, ht), Extreme(lv, la, True, lt))
    return dataclasses.replace(result, values=values, extremes=ext), diffs


class SeriesInertia:
    """The d'Alembert force of a centred slider-crank's piston from the series:
    ``force(q, motion) = -mass * a`` [N] along the slide's direction (+s), with
    ``a`` the first-order series acceleration (:func:`motion`) at crank speed
    ``omega`` [rad/s] and acceleration ``alpha`` [rad/s²].  A ``source`` of a
    :class:`~mechcli.core.linkage.loads.LoadProgram` whose load is the unit
    direction of the slide: the approximate model of ``mechcli force``.

    ``moment_arm``: ``"exact"`` (default) or ``"series"``: the engine's named
    results T and FT then take the series moment arm (:meth:`arm`)."""

    def __init__(self, r: FloatOrArray, l: FloatOrArray, branch: int, mass: FloatOrArray,
                 omega: FloatOrArray, alpha: float = 0.0, moment_arm: str = "exact") -> None:
        self.r, self.l, self.branch = float(r), float(l), int(branch)
        self.mass, self.omega, self.alpha = float(mass), float(omega), float(alpha)
        self.moment_arm = str(moment_arm)

    def acceleration(self, q: np.ndarray):
        """The series acceleration of the slide [m/s²] at crank angles ``q``."""
        return motion(q, self.r, self.l, self.omega, self.alpha, self.branch)[2]

    def arm(self, q: np.ndarray):
        """The series moment arm of the piston effort [m] at crank angles ``q``
        (:func:`moment_arm`) with ``moment_arm = "series"``; else None (T and FT
        from the rod's force on the crank pin)."""
        if self.moment_arm != "series":
            return None
        return moment_arm(q, self.r, self.l, self.branch)

    def force(self, q: np.ndarray, motion_: Optional[LinkageMotion] = None):
        return -self.mass * self.acceleration(q)


def force_model(piston: Any, bodies: Dict[int, Any], programs: Sequence[Any],
                gravity: Optional[Tuple[float, float]], omega: FloatOrArray, alpha: float = 0.0):
    """The approximate model of ``mechcli force`` for a centred slider-crank.

    The piston's d'Alembert force −m a is taken from the series (its exact value
    is along the guide too), everything else stays exact: the piston's body
    loses its mass and gains two loads at its pin, its weight m g (when gravity
    acts) and ``SeriesInertia``.  Returns ``(bodies, programs, inertia)``.
    The piston's ``moment_arm`` (``"exact"`` or ``"series"``) is handed to the
    ``SeriesInertia``: it chooses the arm of T and FT only, never the loads.
    """
    from mechcli.core.linkage.force_model import Load
    from mechcli.core.linkage.loads import LoadProgram

    body = bodies.get(piston.link)
    mass = float(body.mass) if body is not None else 0.0
    inertia = SeriesInertia(piston.r, piston.l, piston.branch, mass, omega, alpha,
                            piston.moment_arm)
    if body is None:
        return bodies, tuple(programs), inertia
    bodies = {k: v for k, v in bodies.items() if k != piston.link}
    ux, uy = piston.u
    extra = [LoadProgram(Load("approx_inertia", piston.link, ux, uy, 0.0, piston.pin),
                         source=inertia)]
    gx, gy = gravity or (0.0, 0.0)
    if gx or gy:
        extra.append(LoadProgram(Load("approx_weight", piston.link, mass * gx, mass * gy, 0.0,
                                      piston.pin)))
    return bodies, tuple(programs) + tuple(extra), inertia
