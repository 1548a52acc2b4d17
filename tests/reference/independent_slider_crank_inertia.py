#!/usr/bin/env python3
"""Independent equivalent inertia Je(φ) and dJe/dφ of the offset slider-crank (【例 6-1】).

Deliberately self-contained: imports nothing from mechcli (numpy only), and uses no
symbolic algebra: every derivative below is differentiated by hand.

Model (图 6-3)
--------------
A = (0, 0) the crank pivot, B = l1 (cos φ, sin φ), the slider's pin C = (s, e) on the guide
y = e, to the right of A; S2 on the coupler BC at the distance a = l_BS2 from B.

Loop closure in y:  l1 sin φ + l2 sin θ2 = e, so with cos θ2 > 0 (slider on the right)

    sin θ2 = (e - l1 sin φ) / l2,             cos θ2 = +sqrt(1 - sin² θ2)
    θ2'    = -l1 cos φ / (l2 cos θ2)                              (d/dφ of the closure)
    θ2''   = (l1 sin φ + l2 sin θ2 θ2'²) / (l2 cos θ2)            (d/dφ once more)
    s      = l1 cos φ + l2 cos θ2
    s'     = -l1 sin φ - l2 sin θ2 θ2'
    s''    = -l1 cos φ - l2 (cos θ2 θ2'² + sin θ2 θ2'')
    xS2'   = -l1 sin φ - a sin θ2 θ2',         yS2'  = l1 cos φ + a cos θ2 θ2'
    xS2''  = -l1 cos φ - a (cos θ2 θ2'² + sin θ2 θ2''),
    yS2''  = -l1 sin φ - a (sin θ2 θ2'² - cos θ2 θ2'')

(' = d/dφ: the velocity coefficients v/ω1, ω/ω1 of the book, and their derivatives).

Equivalent inertia about the crank axis (eq 6-4), crank with J1 about A:

    Je     = J1 + m2 (xS2'² + yS2'²) + J_S2 θ2'² + m3 s'²
    dJe/dφ = 2 [m2 (xS2' xS2'' + yS2' yS2'') + J_S2 θ2' θ2'' + m3 s' s'']

Run: ``python3 tests/reference/independent_slider_crank_inertia.py`` prints Je and dJe/dφ every
30° and the script's own finite-difference check.
"""

import math

import numpy as np

#: 【例 6-1】 (line 6084 of the OCR text) [m, kg, kg m²]; J1 is about the crank pivot A
EXAMPLE_6_1 = dict(l1=0.2, l2=0.5, a=0.2, e=0.05, J1=3.0, m2=5.0, J_S2=0.15, m3=10.0)


def inertia(phi, l1, l2, a, e, J1, m2, J_S2, m3):
    """``(Je, dJe/dφ)`` [kg m², kg m²/rad] at crank angles ``phi`` [rad] (closed form above)."""
    phi = np.asarray(phi, dtype=float)
    c1, s1 = np.cos(phi), np.sin(phi)
    s2 = (e - l1 * s1) / l2
    c2 = np.sqrt(1.0 - s2 * s2)
    if np.any(1.0 - s2 * s2 <= 0.0):
        raise ValueError("the slider-crank does not assemble")
    t1 = -l1 * c1 / (l2 * c2)                          # θ2'
    t2 = (l1 * s1 + l2 * s2 * t1 * t1) / (l2 * c2)     # θ2''
    v3 = -l1 * s1 - l2 * s2 * t1                       # s'
    a3 = -l1 * c1 - l2 * (c2 * t1 * t1 + s2 * t2)      # s''
    vx = -l1 * s1 - a * s2 * t1
    vy = l1 * c1 + a * c2 * t1
    ax = -l1 * c1 - a * (c2 * t1 * t1 + s2 * t2)
    ay = -l1 * s1 - a * (s2 * t1 * t1 - c2 * t2)
    Je = J1 + m2 * (vx * vx + vy * vy) + J_S2 * t1 * t1 + m3 * v3 * v3
    dJe = 2.0 * (m2 * (vx * ax + vy * ay) + J_S2 * t1 * t2 + m3 * v3 * a3)
    return Je, dJe


def fd_check(h=0.01, **params):
    """Largest |dJe/dφ - 8th-order central difference of Je| over a 1° grid [kg m²/rad].

    The truncation error of the stencil is (h^8 / 630) |Je^(9)|: about 1e-16 · |Je^(9)|
    at h = 0.01 rad, below the round-off (≈ 1e-16 · Je / h ≈ 1e-13)."""
    params = params or EXAMPLE_6_1
    c = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
    phi = np.radians(np.arange(360.0))
    Je, _ = inertia(phi[:, None] + np.arange(-4, 5)[None, :] * h, **params)
    _, dJe = inertia(phi, **params)
    return float(np.max(np.abs(Je @ c / h - dJe)))


if __name__ == "__main__":
    for deg in range(0, 361, 30):
        Je, dJe = inertia(math.radians(deg), **EXAMPLE_6_1)
        print(f"phi = {deg:3d} deg  Je = {float(Je):.12f} kg m^2  dJe/dphi = {float(dJe):+.12f}")
    print(f"finite-difference check: {fd_check():.2e} kg m^2/rad")
