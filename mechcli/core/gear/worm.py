"""A cylindrical worm and its worm wheel (习题 5-8).  Lengths in metres, angles in radians."""

from __future__ import annotations

import math
from typing import Optional

from mechcli.core.records import record


@record
class WormDrive:
    """Worm (z1 starts, diameter factor q) and worm wheel (z2) in the mid-plane.

    Attributes
    ----------
    z1, z2 : int
        Worm starts and wheel teeth.
    m : float
        Axial module of the worm = transverse module of the wheel (m).
    q : float
        Diameter factor d1 / m.
    alpha : float
        Pressure angle (rad).
    ha_star, c_star : float
        Addendum and clearance coefficients.
    """

    z1: int
    z2: int
    m: float
    q: float
    alpha: float
    ha_star: float
    c_star: float

    @property
    def d1(self) -> float:
        """Worm reference diameter q m (m)."""
        return self.q * self.m

    @property
    def d2(self) -> float:
        """Wheel reference diameter m z2 (m)."""
        return self.m * self.z2

    @property
    def px(self) -> float:
        """Axial pitch of the worm pi m (m)."""
        return math.pi * self.m

    @property
    def lead(self) -> float:
        """Lead of the worm thread z1 px (m)."""
        return self.z1 * self.px

    @property
    def gamma(self) -> float:
        """Lead angle arctan(z1 / q) (rad) (= wheel helix angle)."""
        return math.atan(self.z1 / self.q)

    @property
    def a(self) -> float:
        """Centre distance (d1 + d2) / 2 (m)."""
        return (self.d1 + self.d2) / 2

    @property
    def ratio(self) -> float:
        """i12 = z2 / z1."""
        return self.z2 / self.z1

    @property
    def da1(self) -> float:
        return self.d1 + 2 * self.ha_star * self.m

    @property
    def df1(self) -> float:
        return self.d1 - 2 * (self.ha_star + self.c_star) * self.m

    @property
    def da2(self) -> float:
        return self.d2 + 2 * self.ha_star * self.m

    @property
    def df2(self) -> float:
        return self.d2 - 2 * (self.ha_star + self.c_star) * self.m


def worm_drive(z1: int, z2: int, *, m: Optional[float] = None, d2: Optional[float] = None,
               q: Optional[float] = None, d1: Optional[float] = None,
               alpha: float = math.radians(20.0), ha_star: float = 1.0,
               c_star: float = 0.2) -> WormDrive:
    """A worm drive from m (or d2 = m z2) and q (or d1 = q m).

    Notes
    -----
    m_t2 = m_x1 = d2 / z2; px = pi m; l = z1 px; a = m (q + z2) / 2; i = z2 / z1 (习题 5-8).
    """
    # (the caller gives m or d2, and q or d1)
    if m is None:
        m = d2 / z2   # type: ignore[operator]
    if q is None:
        q = d1 / m    # type: ignore[operator]
    return WormDrive(int(z1), int(z2), float(m), float(q), float(alpha), float(ha_star),
                     float(c_star))
