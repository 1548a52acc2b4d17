"""Geometry of one involute spur gear (standard or profile-shifted).

Lengths in metres, angles in radians.  The gear is the one cut by a standard
rack cutter (module m, pressure angle alpha, addendum ha* m, clearance c* m)
shifted by x m.

The geometry of one float radius is pure ``math`` (no numpy import: the pair
path starts fast); arrays of radii go through numpy.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from mechcli.core.errors import DescribedError
from mechcli.core.gear.involute import inverse_involute_scalar, involute_function
from mechcli.core.records import record

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


class GearError(DescribedError):
    """A gear or gear drive that cannot exist as asked (``reason`` and ``values``:
    see :class:`~mechcli.core.errors.DescribedError`)."""


class GearGeometryError(GearError):
    """A gear that cannot exist as asked (pointed tip, root below the centre, ...)."""


@record
class SpurGear:
    """An involute spur gear and its circles (表 5-2, extended by the profile shift).

    Attributes
    ----------
    z : int
        Number of teeth.
    m : float
        Module (m).
    alpha : float
        Standard pressure angle (rad).
    ha_star, c_star : float
        Addendum and clearance coefficients.
    x : float
        Profile-shift coefficient.  External gear: positive away from the
        centre.  Internal gear (ISO 21771 convention): positive makes the
        ring's teeth thicker and its tip circle smaller.
    internal : bool
        An internal gear (ring): teeth point to the centre, tip circle
        d - 2 ha, root circle d + 2 hf.
    tip_reduction : float
        Addendum removed to keep the standard clearance in a shifted pair,
        Δy m (m) (see :func:`mechcli.core.gear.pair.tip_shortened`).
    nominal_tip : bool
        The mesh takes the tooth to end on the tip circle even when its flanks
        meet below it (a pointed tooth), as books that use the nominal tip circle
        do; False (the default): it ends where the flanks meet
        (:attr:`r_tip_effective`).
    """

    z: int
    m: float
    alpha: float
    ha_star: float = 1.0
    c_star: float = 0.25
    x: float = 0.0
    internal: bool = False
    tip_reduction: float = 0.0
    nominal_tip: bool = False

    @property
    def sign(self) -> int:
        """+1 for an external gear, -1 for an internal one (tips inwards)."""
        return -1 if self.internal else 1

    # -- circles (m) -----------------------------------------------------
    @property
    def d(self) -> float:
        """Reference (pitch) diameter m z (m)."""
        return self.m * self.z

    @property
    def r(self) -> float:
        return self.d / 2

    @property
    def db(self) -> float:
        """Base diameter d cos(alpha) (m), eq. (5-5)."""
        return self.d * math.cos(self.alpha)

    @property
    def rb(self) -> float:
        return self.db / 2

    @property
    def ha(self) -> float:
        """Addendum (ha* + x) m - Δy m (m); ha* m for the standard gear."""
        return (self.ha_star + self.x) * self.m - self.tip_reduction

    @property
    def hf(self) -> float:
        """Dedendum (ha* + c* - x) m (m)."""
        return (self.ha_star + self.c_star - self.x) * self.m

    @property
    def h(self) -> float:
        """Whole depth ha + hf (m)."""
        return self.ha + self.hf

    @property
    def da(self) -> float:
        """Tip diameter d + 2 ha (m), eq. (5-6); d - 2 ha for an internal gear."""
        return self.d + 2 * self.sign * self.ha

    @property
    def ra(self) -> float:
        return self.da / 2

    @property
    def df(self) -> float:
        """Root diameter d - 2 hf (m), eq. (5-7); d + 2 hf for an internal gear."""
        return self.d - 2 * self.sign * self.hf

    @property
    def rf(self) -> float:
        return self.df / 2

    @property
    def p(self) -> float:
        """Circular pitch pi m (m)."""
        return math.pi * self.m

    @property
    def pb(self) -> float:
        """Base pitch p cos(alpha) (m)."""
        return self.p * math.cos(self.alpha)

    @property
    def s(self) -> float:
        """Tooth thickness on the reference circle m (pi/2 + 2 x tan alpha) (m)."""
        return self.m * (math.pi / 2 + 2 * self.x * math.tan(self.alpha))

    @property
    def e(self) -> float:
        """Space width on the reference circle p - s (m)."""
        return self.p - self.s

    @property
    def c(self) -> float:
        """Bottom clearance c* m (m)."""
        return self.c_star * self.m

    @property
    def alpha_a(self) -> float:
        """Pressure angle at the tip circle arccos(rb / ra) (rad), eq. (5-8)."""
        return math.acos(self.rb / self.ra)

    # -- thickness -------------------------------------------------------
    def tooth_thickness(self, radius: ArrayLike) -> Any:
        """Arc tooth thickness at a radius >= rb (m).

        s_K = s r_K / r - 2 r_K (inv alpha_K - inv alpha), alpha_K = arccos(rb / r_K)
        (internal gear: + 2 r_K (...), its teeth widen outwards).
        Negative where the tooth would already be pointed.
        """
        if isinstance(radius, (int, float)):
            ak = math.acos(min(max(self.rb / radius, -1.0), 1.0))
            return radius * (self.s / self.r - 2 * self.sign
                             * (involute_function(ak) - involute_function(self.alpha)))
        import numpy as np
        rk = np.asarray(radius, dtype=float)
        ak = np.arccos(np.clip(self.rb / rk, -1.0, 1.0))
        out = rk * (self.s / self.r - 2 * self.sign
                    * (involute_function(ak) - involute_function(self.alpha)))
        return out if np.ndim(out) else float(out)

    def space_width(self, radius: ArrayLike) -> Any:
        """Arc space width 2 pi r_K / z - s_K at a radius >= rb (m)."""
        if isinstance(radius, (int, float)):
            return 2 * math.pi * radius / self.z - self.tooth_thickness(radius)
        import numpy as np
        rk = np.asarray(radius, dtype=float)
        out = 2 * np.pi * rk / self.z - self.tooth_thickness(rk)
        return out if np.ndim(out) else float(out)

    def half_tooth_angle(self, radius: ArrayLike) -> Any:
        """Half the angle the tooth subtends at a radius >= rb (rad): s_K / (2 r_K)."""
        if isinstance(radius, (int, float)):
            ak = math.acos(min(max(self.rb / radius, -1.0), 1.0))
        else:
            import numpy as np
            ak = np.arccos(np.clip(self.rb / np.asarray(radius, dtype=float), -1.0, 1.0))
        return self.s / (2 * self.r) + self.sign * (involute_function(self.alpha)
                                                    - involute_function(ak))

    @property
    def pointed_radius(self) -> float:
        """Radius where the two flanks meet (tooth thickness 0) (m).

        inv alpha_p = s / d + inv alpha, r_p = rb / cos alpha_p (习题 5-1).  For an
        internal gear (teeth narrowing inwards) inv alpha_p = inv alpha - s / d, and
        rb if that is negative (never pointed above the base circle).
        """
        theta = involute_function(self.alpha) + self.sign * self.s / self.d
        if theta <= 0:
            return self.rb
        ap = inverse_involute_scalar(theta)[0]
        return self.rb / math.cos(ap)

    @property
    def r_tip_effective(self) -> float:
        """Where the tooth really ends (m): the tip circle, or the pointed radius
        if the flanks meet before it (external: below ra; internal: above ra).
        With :attr:`nominal_tip` the tip circle always."""
        if self.nominal_tip:
            return self.ra
        rp = self.pointed_radius
        if self.sign > 0:
            return min(self.ra, rp)
        return max(self.ra, rp) if rp > self.rb else self.ra

    @property
    def alpha_a_effective(self) -> float:
        """Pressure angle at :attr:`r_tip_effective` (rad); equals ``alpha_a``
        unless the tip is pointed below the tip circle."""
        return math.acos(min(1.0, self.rb / self.r_tip_effective))

    # -- undercut ----------------------------------------------------------
    @property
    def z_min(self) -> float:
        """Fewest teeth without undercut by the standard rack, 2 ha* / sin^2 alpha."""
        return 2 * self.ha_star / math.sin(self.alpha) ** 2

    @property
    def x_min(self) -> float:
        """Least profile shift against undercut, ha* (z_min - z) / z_min.

        Computed as ha* - z sin^2(alpha) / 2 (the same, and defined for ha* = 0).
        """
        return self.ha_star - self.z * math.sin(self.alpha) ** 2 / 2

    @property
    def undercut(self) -> bool:
        """True if the standard rack undercuts this gear (x < x_min); False for internal gears.

        This is mechcli's undercut criterion.  The standard rack cutter's tip
        is rounded with the radius c* m / (1 - sin alpha), so its straight flank ends
        ha* m below its reference line; the gear is undercut when that end passes the
        tangent point N of the line of action: (ha* - x) m > r sin^2(alpha).  The book's
        sharp-cornered ``gear_cut`` cutter goes c* m deeper and cuts a little of the
        involute for a few more teeth (:func:`mechcli.core.gear.profile.generated_tooth`);
        that is reported as the measure of the cut, not as the criterion.
        """
        return (not self.internal) and self.x < self.x_min - 1e-12


def spur_gear(z: int, m: float, alpha: float, ha_star: float = 1.0, c_star: float = 0.25,
              x: float = 0.0, internal: bool = False) -> SpurGear:
    """Build a :class:`SpurGear` and check that it can exist.

    Parameters
    ----------
    z : int
        Number of teeth (>= 1).
    m : float
        Module (m), > 0.
    alpha : float
        Pressure angle (rad), in (0, pi/4].
    ha_star, c_star : float
        Addendum and clearance coefficients (>= 0).
    x : float
        Profile-shift coefficient.
    internal : bool
        An internal gear (ring).

    Raises
    ------
    GearGeometryError
        The root circle would not be outside the centre (df <= 0); the tip
        circle inside the base circle (no involute there).
    """
    g = SpurGear(int(z), float(m), float(alpha), float(ha_star), float(c_star), float(x),
                 bool(internal))
    if internal:
        if g.ra < g.rb:
            z_needed = 2 * (g.ha_star + g.x) / (1 - math.cos(g.alpha))
            raise GearGeometryError(
                f"internal gear z = {g.z}: the tip circle is inside the base circle "
                f"(needs z >= {z_needed:.1f})", "ring_tip_inside_base", z=g.z, da=g.da, db=g.db,
                z_needed=z_needed)
        return g
    if g.ra < g.rb:
        raise GearGeometryError(
            f"the tip circle is inside the base circle (z = {g.z}, x = {g.x:g}): the teeth "
            "have no involute", "tip_inside_base", z=g.z, x=g.x, da=g.da, db=g.db)
    if g.df <= 0:
        raise GearGeometryError(
            f"the root diameter would be <= 0 (z = {g.z}, x = {g.x:g}): too few teeth for "
            "this shift", "root_below_centre", z=g.z, x=g.x, df=g.df)
    return g
