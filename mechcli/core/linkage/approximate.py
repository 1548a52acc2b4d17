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
"""

from __future__ import annotations

import math

import numpy as np

#: golden-section iterations of an extreme's refinement (bracket shrinks 0.618^k)
_ITERATIONS = 80


def series(q, r, l, branch=1):
    """``(s, ds/dθ, d²s/dθ²)`` of the first-order series at crank angles *q* [rad]."""
    q = np.asarray(q, dtype=float)
    n = l / r
    b = 1.0 if branch >= 0 else -1.0
    s = r * np.cos(q) + b * (l - r / (2 * n) * np.sin(q) ** 2)
    ds = -r * (np.sin(q) + b * np.sin(2 * q) / (2 * n))
    dds = -r * (np.cos(q) + b * np.cos(2 * q) / n)
    return s, ds, dds


def exact(q, r, l, branch=1):
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


def motion(q, r, l, omega, alpha=0.0, branch=1):
    """Approximate ``(s, v, a)`` of the slider at crank angles *q* [rad], crank
    speed *omega* [rad/s] and acceleration *alpha* [rad/s²]."""
    s, ds, dds = series(q, r, l, branch)
    return s, ds * omega, dds * omega ** 2 + ds * alpha


def _golden(f, a, b, sign):
    """The input in [a, b] where ``sign * f`` is largest, and the final half-bracket."""
    g = (math.sqrt(5) - 1) / 2
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = sign * f(c), sign * f(d)
    for _ in range(_ITERATIONS):
        if fc >= fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = sign * f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = sign * f(d)
        if b - a < 1e-15 * max(1.0, abs(a)):
            break
    return 0.5 * (a + b), 0.5 * (b - a)


def extremes(q, values, func):
    """``(max, min)`` of ``func(x)`` (a closed form) over the sweep *q*, refined
    between the neighbours of the best sample.  Returns two ``(value, at, tol)``."""
    out = []
    for sign, pick in ((1.0, np.argmax), (-1.0, np.argmin)):
        i = int(pick(values))
        lo, hi = q[max(i - 1, 0)], q[min(i + 1, q.size - 1)]
        at, tol = _golden(func, lo, hi, sign)
        value = float(func(at))
        if sign * value < sign * float(values[i]):   # never worse than the sample
            at, value, tol = float(q[i]), float(values[i]), 0.0
        out.append((value, float(at), float(tol)))
    return tuple(out)


def differences(approx, exact_values):
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


def largest_relative_differences(n, samples=36001):
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
    extremes refined on the closed form; the other links' quantities stay exact.

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
        if q.size:
            (hv, ha, ht), (lv, la, lt) = extremes(q, approx[k], func)
            ext[sym] = (Extreme(hv, ha, True, ht), Extreme(lv, la, True, lt))
    return dataclasses.replace(result, values=values, extremes=ext), diffs
