"""An independent second implementation of the flywheel figures of a turning-moment diagram.

Self-contained: numpy and the standard library only, nothing from mechcli.  It works on
piecewise-linear diagrams (a table of nodes over one cycle, linear between them: the
classic triangles and trapezoids of textbook problems) and computes

* the mean moment, the loops about it (crossings by linear interpolation on each
  segment, areas by the trapezoid formula on the pieces), the cumulative energy and
  ΔWmax (the textbook's table of areas);
* the flywheel of eq. 6-30, J = ΔWmax/(ωm² δ);
* the exact flywheel of a machine of constant inertia J under that diagram: the speed
  ω(φ)² = ω0² + 2W(φ)/J, ω0 such that the integral mean (1/T)∫ω dφ is ωm (eq. 6-26),
  and J such that δ = (ωmax − ωmin)/ωm equals the allowed δ (eq. 6-25), both found by
  bisection; the integral by Simpson's rule on a grid refined between the table's nodes
  and the crossings of the mean (W is quadratic there, ω smooth, its extremes on the
  grid).

The functions take degrees and N m, return SI (J, rad/s, kg m²) unless named ``_deg``.
"""

from __future__ import annotations

import math

import numpy as np


def _closed(phi_deg, M, period_deg):
    phi = np.asarray(phi_deg, dtype=float)
    M = np.asarray(M, dtype=float)
    if abs(phi[-1] - phi[0] - period_deg) > 1e-9:
        phi = np.append(phi, phi[0] + period_deg)
        M = np.append(M, M[0])
    return np.radians(phi), M


def mean_moment(phi_deg, M, period_deg=360.0):
    """(1/T) ∫M dφ of the linear table over its cycle [N m]."""
    x, m = _closed(phi_deg, M, period_deg)
    return float(np.sum(0.5 * (m[1:] + m[:-1]) * np.diff(x)) / math.radians(period_deg))


def loop_table(phi_deg, M, period_deg=360.0, mean=None):
    """The loops of ``M − mean`` (mean: the table's own by default).

    Returns
    -------
    dict
        ``bounds_deg`` (n + 1), ``areas`` (n) [J], ``cumulative`` (n + 1) [J],
        ``dW_max`` [J], ``phi_max_deg``, ``phi_min_deg``.
    """
    x, m = _closed(phi_deg, M, period_deg)
    if mean is None:
        mean = mean_moment(phi_deg, M, period_deg)
    d = m - mean
    bounds = [x[0]]
    # a crossing strictly inside a segment where d changes sign
    for i in range(len(x) - 1):
        a, b = d[i], d[i + 1]
        if a * b < 0:
            bounds.append(x[i] + (x[i + 1] - x[i]) * a / (a - b))
        elif b == 0 and i + 1 < len(x) - 1:
            # a node on the mean line: a crossing when the sign around it changes
            nxt = next((v for v in d[i + 2:] if v != 0), 0.0)
            prv = next((v for v in d[i::-1] if v != 0), 0.0)
            if prv * nxt < 0:
                bounds.append(x[i + 1])
    bounds.append(x[-1])
    bounds = np.array(sorted(set(bounds)))

    def W(p):       # ∫_{x0}^{p} (M − mean) dφ, exact for the linear table
        out = 0.0
        for i in range(len(x) - 1):
            lo, hi = x[i], min(x[i + 1], p)
            if hi <= lo:
                break
            slope = (d[i + 1] - d[i]) / (x[i + 1] - x[i])
            out += (hi - lo) * (d[i] + 0.5 * slope * (hi - lo))
        return out

    cum = np.array([W(p) for p in bounds])
    i_max, i_min = int(np.argmax(cum)), int(np.argmin(cum))
    return {"bounds_deg": np.degrees(bounds), "areas": np.diff(cum), "cumulative": cum,
            "dW_max": float(cum[i_max] - cum[i_min]),
            "phi_max_deg": float(np.degrees(bounds[i_max])),
            "phi_min_deg": float(np.degrees(bounds[i_min]))}


def flywheel_approx(dW_max, omega_m, delta, Je=0.0):
    """Eq. 6-29 (Je = 0: eq. 6-30): J_F = ΔWmax/(ωm² δ) − Je [kg m²]."""
    return dW_max / (omega_m ** 2 * delta) - Je


def _work_grid(phi_deg, M, period_deg, mean, per_segment=400):
    """A grid refined between the nodes and the crossings of the mean (an even number of
    steps per piece: the extremes of ω fall on the grid) and the exact work W(φ) of
    ``M − mean`` on it."""
    x, m = _closed(phi_deg, M, period_deg)
    cuts = np.radians(loop_table(phi_deg, M, period_deg, mean)["bounds_deg"])
    x_all = np.unique(np.concatenate((x, cuts)))
    m = np.interp(x_all, x, m)
    x = x_all
    xs, ws = [x[:1]], [np.zeros(1)]
    W0 = 0.0
    for i in range(len(x) - 1):
        t = np.linspace(0.0, 1.0, per_segment + 1)[1:]
        h = x[i + 1] - x[i]
        d0, d1 = m[i] - mean, m[i + 1] - mean
        xs.append(x[i] + h * t)
        ws.append(W0 + h * t * (d0 + 0.5 * (d1 - d0) * t))
        W0 = W0 + h * 0.5 * (d0 + d1)
    return np.concatenate(xs), np.concatenate(ws)


def _simpson(y, x):
    """Composite Simpson on a grid whose pairs of steps are equal (as _work_grid's)."""
    h = np.diff(x)
    a, b = h[0::2], h[1::2]
    y0, y1, y2 = y[0:-1:2], y[1::2], y[2::2]
    return float(np.sum((a + b) / 6.0 * (y0 * (2 - b / a) + y1 * (a + b) ** 2 / (a * b)
                                         + y2 * (2 - a / b))))


def steady_constant_J(phi_deg, M, J, omega_m, period_deg=360.0, mean=None):
    """The steady motion under the balanced linear diagram with the constant inertia J:
    (ω0, ωmax, ωmin, δ) with the integral mean speed ωm (eqs. 6-25, 6-26)."""
    if mean is None:
        mean = mean_moment(phi_deg, M, period_deg)
    x, W = _work_grid(phi_deg, M, period_deg, mean)
    T = x[-1] - x[0]

    def omega(w0):
        return np.sqrt(np.maximum(w0 * w0 + 2.0 * W / J, 0.0))

    lo = math.sqrt(max(0.0, -2.0 * float(W.min()) / J))
    hi = 2.0 * omega_m + lo
    for _ in range(200):        # bisection on the mean speed
        mid = 0.5 * (lo + hi)
        if _simpson(omega(mid), x) / T < omega_m:
            lo = mid
        else:
            hi = mid
    w0 = 0.5 * (lo + hi)
    w = omega(w0)
    return w0, float(w.max()), float(w.min()), float((w.max() - w.min()) / omega_m)


def flywheel_exact(phi_deg, M, omega_m, delta, period_deg=360.0, mean=None):
    """The constant inertia J [kg m²] whose steady state has δ = ``delta`` exactly (eq.
    6-25 with eq. 6-26's mean), by bisection on log J."""
    if mean is None:
        mean = mean_moment(phi_deg, M, period_deg)
    J0 = flywheel_approx(loop_table(phi_deg, M, period_deg, mean)["dW_max"], omega_m, delta)
    lo, hi = 0.5 * J0, 2.0 * J0
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        if steady_constant_J(phi_deg, M, mid, omega_m, period_deg, mean)[3] > delta:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


# --------------------------------------------------------------------------- the configs
#: the tables of the configs in configs/ch6/ that this module checks, as their comments
#: derive them (degrees, N m)
FOUR_STROKE = {"phi_deg": [0, 90, 180, 270, 360, 450, 540, 630, 720],
               "M": [0, -2 * 1350 / math.pi, 0, -2 * 5100 / math.pi, 0, 2 * 20400 / math.pi,
                     0, -2 * 1950 / math.pi, 0], "period_deg": 720.0}


def multi_cylinder():
    """The loops +52, −124, +92, −140, +85, −72, +107 mm² (1 mm = 600 N m, 1 mm = 3°:
    10π J per mm²) as triangles about Tm = 6000 N m on bases of 45, 60, 45, 60, 45, 45,
    60° (configs/ch6/multi-cylinder.toml)."""
    areas = [52, -124, 92, -140, 85, -72, 107]
    bases = [45, 60, 45, 60, 45, 45, 60]
    phi, M, at = [0.0], [6000.0], 0.0
    for A, b in zip(areas, bases):
        h = 2 * A * 10 * math.pi / math.radians(b)
        phi += [at + b / 2, at + b]
        M += [6000.0 + h, 6000.0]
        at += b
    return {"phi_deg": phi, "M": M, "period_deg": 360.0}


#: 表 6-2's resisting moment (例 6-4), every 15° over a turn [N m]
TABLE_6_2_MER = [789, 812, 825, 797, 727, 85, 105, 137, 181, 185, 179, 150, 141, 150, 157, 152,
                 132, 132, 139, 145, 756, 803, 818, 802, 789]


def shaper_drive_mean():
    """表 6-2's Mer against a constant drive equal to its mean (configs/ch6/
    shaper-without-own-inertia.toml): the net moment Md − Mer as a linear table."""
    phi = [15.0 * i for i in range(25)]
    Md = mean_moment(phi, TABLE_6_2_MER)
    return {"phi_deg": phi, "M": [Md - v for v in TABLE_6_2_MER], "period_deg": 360.0,
            "Md": Md}


if __name__ == "__main__":      # print the reference values the configs quote
    t = FOUR_STROKE
    lt = loop_table(t["phi_deg"], t["M"], 720.0)
    wm = 200 * math.pi / 30
    print("four-stroke: Tm", mean_moment(t["phi_deg"], t["M"], 720.0), "loops", lt,
          "J exact", flywheel_exact(t["phi_deg"], t["M"], wm, 0.02, 720.0))
    mc = multi_cylinder()
    print("multi-cylinder:", loop_table(mc["phi_deg"], mc["M"]))
    sh = shaper_drive_mean()
    ls = loop_table(sh["phi_deg"], sh["M"], mean=0.0)
    print("shaper: Md", sh["Md"], "loops", ls, "J approx", flywheel_approx(ls["dW_max"], 5.0, 0.05),
          "J exact", flywheel_exact(sh["phi_deg"], sh["M"], 5.0, 0.05, mean=0.0))
