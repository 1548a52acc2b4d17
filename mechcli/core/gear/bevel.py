"""A pair of straight bevel gears (习题 5-9).  Lengths in metres, angles in radians.

Dimensions at the large end (module m); tip and root cones of the
"unequal clearance" kind (tip cone angle delta + theta_a).
"""

from __future__ import annotations

import math

from mechcli.core.gear.spur import GearError
from mechcli.core.records import record


@record
class BevelPair:
    """Two straight bevel gears with shaft angle sigma.

    Attributes
    ----------
    z1, z2 : int
    m : float
        Module at the large end (m).
    alpha : float
        Pressure angle (rad).
    ha_star, c_star : float
    sigma : float
        Shaft angle (rad).
    """

    z1: int
    z2: int
    m: float
    alpha: float
    ha_star: float
    c_star: float
    sigma: float

    @property
    def delta1(self) -> float:
        """Pitch-cone angle of gear 1, tan d1 = sin S / (z2/z1 + cos S) (rad)."""
        return math.atan2(math.sin(self.sigma), self.z2 / self.z1 + math.cos(self.sigma))

    @property
    def delta2(self) -> float:
        return self.sigma - self.delta1

    def d(self, z: int) -> float:
        """Reference diameter m z (m)."""
        return self.m * z

    @property
    def R(self) -> float:
        """Cone distance d1 / (2 sin delta1) (m)."""
        return self.d(self.z1) / (2 * math.sin(self.delta1))

    @property
    def ha(self) -> float:
        return self.ha_star * self.m

    @property
    def hf(self) -> float:
        return (self.ha_star + self.c_star) * self.m

    @property
    def theta_a(self) -> float:
        """Addendum angle arctan(ha / R) (rad)."""
        return math.atan(self.ha / self.R)

    @property
    def theta_f(self) -> float:
        """Dedendum angle arctan(hf / R) (rad)."""
        return math.atan(self.hf / self.R)

    def delta_a(self, delta: float) -> float:
        """Tip-cone angle delta + theta_a (rad)."""
        return delta + self.theta_a

    def delta_f(self, delta: float) -> float:
        """Root-cone angle delta - theta_f (rad)."""
        return delta - self.theta_f

    def da(self, z: int, delta: float) -> float:
        """Tip diameter d + 2 ha cos(delta) (m)."""
        return self.d(z) + 2 * self.ha * math.cos(delta)

    def df(self, z: int, delta: float) -> float:
        """Root diameter d - 2 hf cos(delta) (m)."""
        return self.d(z) - 2 * self.hf * math.cos(delta)

    @staticmethod
    def zv(z: int, delta: float) -> float:
        """Virtual number of teeth z / cos(delta)."""
        return z / math.cos(delta)


def bevel_pair(z1: int, z2: int, m: float, alpha: float, ha_star: float = 1.0, c_star: float = 0.2,
               sigma: float = math.pi / 2) -> BevelPair:
    """Build a :class:`BevelPair` (习题 5-9).

    Raises
    ------
    GearError
        A pitch cone wider than 90 degrees (an internal bevel gear, not handled).
    """
    pair = BevelPair(int(z1), int(z2), float(m), float(alpha), float(ha_star), float(c_star),
                     float(sigma))
    if max(pair.delta1, pair.delta2) >= math.pi / 2 - 1e-12:
        raise GearError("a pitch cone of pi/2 or more is a crown or internal bevel gear, "
                        "which is not handled", "crown_bevel", delta1=pair.delta1,
                        delta2=pair.delta2)
    return pair
