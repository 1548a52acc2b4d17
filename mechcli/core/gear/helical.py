"""A pair of parallel helical gears (习题 5-6, 5-7).  Lengths in metres, angles in radians."""

from __future__ import annotations

import math
from typing import Optional

from mechcli.core.gear.involute import inverse_involute_scalar, involute_function
from mechcli.core.gear.spur import GearError
from mechcli.core.records import record


@record
class HelicalPair:
    """Two standard helical gears in mesh at the standard centre distance.

    Attributes
    ----------
    z1, z2 : int
        Teeth.
    mn : float
        Normal module (m).
    alpha_n : float
        Normal pressure angle (rad).
    han_star, cn_star : float
        Normal addendum and clearance coefficients.
    beta : float
        Helix angle on the reference cylinder (rad).
    b : float or None
        Face width (m) for the overlap ratio.
    xn1, xn2 : float
        Normal profile-shift coefficients (ISO 21771: the shift is xn mn in
        the normal plane).  A shifted pair runs at its zero-backlash centre
        distance, inv a_wt = 2 tan(an)(xn1 + xn2)/(z1 + z2) + inv at.
    """

    z1: int
    z2: int
    mn: float
    alpha_n: float
    han_star: float
    cn_star: float
    beta: float
    b: float | None
    xn1: float = 0.0
    xn2: float = 0.0

    def xn(self, z: int, xn: Optional[float] = None) -> float:
        """The shift of the gear of *z* teeth (gear 1 when z1 == z2), or *xn* if given."""
        if xn is not None:
            return xn
        return self.xn1 if z == self.z1 else self.xn2

    @property
    def mt(self) -> float:
        """Transverse module mn / cos(beta) (m)."""
        return self.mn / math.cos(self.beta)

    @property
    def alpha_t(self) -> float:
        """Transverse pressure angle arctan(tan alpha_n / cos beta) (rad)."""
        return math.atan(math.tan(self.alpha_n) / math.cos(self.beta))

    def d(self, z: int) -> float:
        """Reference diameter mt z (m)."""
        return self.mt * z

    def da(self, z: int, xn: Optional[float] = None) -> float:
        """Tip diameter d + 2 (han* + xn) mn (m)."""
        return self.d(z) + 2 * (self.han_star + self.xn(z, xn)) * self.mn

    def df(self, z: int, xn: Optional[float] = None) -> float:
        """Root diameter d - 2 (han* + cn* - xn) mn (m)."""
        return self.d(z) - 2 * (self.han_star + self.cn_star - self.xn(z, xn)) * self.mn

    def db(self, z: int) -> float:
        """Base diameter d cos(alpha_t) (m)."""
        return self.d(z) * math.cos(self.alpha_t)

    def alpha_at(self, z: int, xn: Optional[float] = None) -> float:
        """Transverse pressure angle at the tip arccos(db / da) (rad)."""
        return math.acos(self.db(z) / self.da(z, xn))

    def zv(self, z: int) -> float:
        """Virtual number of teeth z / cos^3(beta)."""
        return z / math.cos(self.beta) ** 3

    @property
    def a(self) -> float:
        """Centre distance mn (z1 + z2) / (2 cos beta) (m)."""
        return (self.d(self.z1) + self.d(self.z2)) / 2

    @property
    def alpha_wt(self) -> float:
        """Operating transverse pressure angle of the zero-backlash mesh (rad).

        inv a_wt = 2 tan(an) (xn1 + xn2) / (z1 + z2) + inv at (ISO 21771); at for
        unshifted gears.
        """
        if self.xn1 + self.xn2 == 0:
            return self.alpha_t
        theta = (2 * math.tan(self.alpha_n) * (self.xn1 + self.xn2) / (self.z1 + self.z2)
                 + involute_function(self.alpha_t))
        if theta <= 0:
            raise GearError("xn1 + xn2 is so negative that no zero-backlash mesh exists",
                            "helical_shift_sum", x_sum=self.xn1 + self.xn2)
        return inverse_involute_scalar(theta)[0]

    @property
    def a_w(self) -> float:
        """Operating centre distance a cos(at) / cos(a_wt) (m); a when unshifted."""
        if self.xn1 + self.xn2 == 0:
            return self.a
        return self.a * math.cos(self.alpha_t) / math.cos(self.alpha_wt)

    @property
    def epsilon_alpha(self) -> float:
        """Transverse contact ratio, the spur formula in the transverse plane at a_wt."""
        t = math.tan(self.alpha_wt)
        return (self.z1 * (math.tan(self.alpha_at(self.z1, self.xn1)) - t)
                + self.z2 * (math.tan(self.alpha_at(self.z2, self.xn2)) - t)) / (2 * math.pi)

    @property
    def epsilon_beta(self) -> float:
        """Overlap ratio b sin(beta) / (pi mn); 0 without a face width."""
        return 0.0 if self.b is None else self.b * math.sin(self.beta) / (math.pi * self.mn)

    @property
    def epsilon_gamma(self) -> float:
        """Total contact ratio epsilon_alpha + epsilon_beta."""
        return self.epsilon_alpha + self.epsilon_beta


def helical_pair(z1: int, z2: int, mn: float, alpha_n: float, han_star: float = 1.0,
                 cn_star: float = 0.25, *, beta: Optional[float] = None,
                 a_w: Optional[float] = None, b: Optional[float] = None, xn1: float = 0.0,
                 xn2: float = 0.0) -> HelicalPair:
    """A helical pair from its helix angle, or with the helix angle that fits a'.

    cos(beta) = mn (z1 + z2) / (2 a') when the gears are not shifted (习题 5-6).

    Raises
    ------
    GearError
        a' below mn (z1 + z2) / 2, or the helix angle 45 degrees or more.
    """
    if beta is None:
        c = mn * (z1 + z2) / (2 * a_w)   # type: ignore[operator]  # (a_w given without beta)
        if c > 1:
            raise GearError("a' is below mn (z1 + z2) / 2: no helix angle fits",
                            "helical_centre_distance", a_w=a_w, limit=mn * (z1 + z2) / 2)
        beta = math.acos(c)
    if not 0 <= beta < math.pi / 4 + 1e-12:
        raise GearError("the helix angle is pi/4 or more", "helix_angle", beta=beta)
    if beta is None and (xn1 or xn2):
        raise ValueError("a helix angle from a' is for unshifted gears")
    hp = HelicalPair(int(z1), int(z2), float(mn), float(alpha_n), float(han_star),
                     float(cn_star), float(beta), b, float(xn1), float(xn2))
    _ = hp.alpha_wt   # raises GearError for a shift sum without a zero-backlash mesh
    return hp
