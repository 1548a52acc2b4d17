"""A pair of parallel helical gears (习题 5-6, 5-7).  Lengths in metres, angles in radians."""

from __future__ import annotations

import dataclasses
import math

from mechcli.core.gear.spur import GearError


@dataclasses.dataclass(frozen=True)
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
    """

    z1: int
    z2: int
    mn: float
    alpha_n: float
    han_star: float
    cn_star: float
    beta: float
    b: float | None

    @property
    def mt(self):
        """Transverse module mn / cos(beta) (m)."""
        return self.mn / math.cos(self.beta)

    @property
    def alpha_t(self):
        """Transverse pressure angle arctan(tan alpha_n / cos beta) (rad)."""
        return math.atan(math.tan(self.alpha_n) / math.cos(self.beta))

    def d(self, z):
        """Reference diameter mt z (m)."""
        return self.mt * z

    def da(self, z):
        """Tip diameter d + 2 han* mn (m)."""
        return self.d(z) + 2 * self.han_star * self.mn

    def df(self, z):
        """Root diameter d - 2 (han* + cn*) mn (m)."""
        return self.d(z) - 2 * (self.han_star + self.cn_star) * self.mn

    def db(self, z):
        """Base diameter d cos(alpha_t) (m)."""
        return self.d(z) * math.cos(self.alpha_t)

    def alpha_at(self, z):
        """Transverse pressure angle at the tip arccos(db / da) (rad)."""
        return math.acos(self.db(z) / self.da(z))

    def zv(self, z):
        """Virtual number of teeth z / cos^3(beta)."""
        return z / math.cos(self.beta) ** 3

    @property
    def a(self):
        """Centre distance mn (z1 + z2) / (2 cos beta) (m)."""
        return (self.d(self.z1) + self.d(self.z2)) / 2

    @property
    def epsilon_alpha(self):
        """Transverse contact ratio, the spur formula in the transverse plane."""
        t = math.tan(self.alpha_t)
        return (self.z1 * (math.tan(self.alpha_at(self.z1)) - t)
                + self.z2 * (math.tan(self.alpha_at(self.z2)) - t)) / (2 * math.pi)

    @property
    def epsilon_beta(self):
        """Overlap ratio b sin(beta) / (pi mn); 0 without a face width."""
        return 0.0 if self.b is None else self.b * math.sin(self.beta) / (math.pi * self.mn)

    @property
    def epsilon_gamma(self):
        """Total contact ratio epsilon_alpha + epsilon_beta."""
        return self.epsilon_alpha + self.epsilon_beta


def helical_pair(z1, z2, mn, alpha_n, han_star=1.0, cn_star=0.25, *, beta=None, a_w=None,
                 b=None):
    """A helical pair from its helix angle, or with the helix angle that fits a'.

    cos(beta) = mn (z1 + z2) / (2 a') when the gears are not shifted (习题 5-6).

    Raises
    ------
    GearError
        a' below mn (z1 + z2) / 2, or the helix angle 45 degrees or more.
    """
    if beta is None:
        c = mn * (z1 + z2) / (2 * a_w)
        if c > 1:
            raise GearError("a' is below mn (z1 + z2) / 2: no helix angle fits",
                            "helical_centre_distance", a_w=a_w, limit=mn * (z1 + z2) / 2)
        beta = math.acos(c)
    if not 0 <= beta < math.pi / 4 + 1e-12:
        raise GearError("the helix angle is pi/4 or more", "helix_angle", beta=beta)
    return HelicalPair(int(z1), int(z2), float(mn), float(alpha_n), float(han_star),
                       float(cn_star), float(beta), b)
