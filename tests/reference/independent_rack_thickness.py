"""Independent tooth thickness of a spur gear cut by a rack, by sweeping the rack.

Deliberately self-contained: imports nothing from mechcli (only numpy/scipy).  It checks
the generating profile-shift coefficient x_E (``mechcli.core.gear.measurement
.generating_shift``): a rack set at the shift x_E m must cut the thinned tooth.

Method
------
* The gear is centred at the origin, the tooth being measured centred on +y.  The rack
  (module m, pressure angle alpha, straight flanks, tip (ha* + c*) m below its reference
  line) has its reference line at y = r + shift, r = z m / 2; its line y = r rolls on the
  reference circle: when the gear has turned by phi (counter-clockwise) the rack has moved
  by -r phi along x.
* The rack tooth to the right of the measured gear tooth is centred at x = p/2 - r phi;
  at height y it is  p/4 + (y - r - shift) tan(alpha)  wide on either side of its centre
  and ends at y = r + shift - (ha* + c*) m.
* A point of the gear at radius rho and angle psi (clockwise from +y) is at
  (rho sin(psi - phi), rho cos(psi - phi)) when the gear has turned by phi.  It is cut
  away when, for some phi, it lies inside that rack tooth: the depth of its inside
  g(phi) = min(half width - |x - centre|, y - tip) is positive.
* The half-angle psi* of the finished tooth at rho is where max over phi of g is zero
  (psi < psi* is tooth material): the maximum by a grid and a bounded search, psi* by
  Brent's method.  The tooth is symmetric, so one flank gives the thickness 2 rho psi*.
"""

import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar


def rack_cut_half_angle(z, m, alpha, shift, rho, ha_c=1.25):
    """Half-angle (rad) at the radius *rho* of the tooth a rack at the radial *shift*
    (length, the x m of a profile shift x) cuts on a gear of *z* teeth."""
    r = z * m / 2
    p = math.pi * m
    tan_a = math.tan(alpha)
    tip = r + shift - ha_c * m

    def depth(phi, psi):
        x = rho * np.sin(psi - phi)
        y = rho * np.cos(psi - phi)
        flank = p / 4 + (y - r - shift) * tan_a - np.abs(x - (p / 2 - r * phi))
        return np.minimum(flank, y - tip)

    def deepest(psi):
        grid = np.linspace(-1.0, 1.0, 4001)
        i = int(np.argmax(depth(grid, psi)))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        res = minimize_scalar(lambda f: -float(depth(f, psi)), bounds=(lo, hi),
                              method="bounded", options={"xatol": 1e-14})
        return -res.fun

    return brentq(deepest, 0.0, math.pi / z, xtol=1e-15, rtol=1e-15)


def rack_cut_thickness(z, m, alpha, shift, rho):
    """Arc tooth thickness 2 rho psi* at the radius *rho* (length)."""
    return 2 * rho * rack_cut_half_angle(z, m, alpha, shift, rho)
