"""A pair of external involute spur gears: centre distance, operating pressure
angle, pitch circles, backlash, clearance and the contact ratio (表 5-2, 【例 5-4】).

Lengths in metres, angles in radians.  Only :func:`mesh_positions` (arrays)
imports numpy.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Optional, Sequence, Tuple

from mechcli.core.gear.involute import inverse_involute_scalar, involute_function
from mechcli.core.gear.spur import GearError, SpurGear
from mechcli.core.records import record

if TYPE_CHECKING:  # annotations only: numpy is imported lazily
    import numpy as np
    from numpy.typing import ArrayLike


class MeshError(GearError):
    """Two gears cannot mesh as asked (numbers in ``reason``/``values``, see :class:`GearError`)."""


def standard_centre_distance(g1: SpurGear, g2: SpurGear) -> float:
    """a = m (z1 + z2) / 2 (m); m (z2 - z1) / 2 when gear 2 is internal."""
    return g1.m * (g2.z + g2.sign * g1.z) / 2 if g2.internal else g1.m * (g1.z + g2.z) / 2


def zero_backlash_pressure_angle(g1: SpurGear, g2: SpurGear) -> float:
    """Operating pressure angle of the zero-backlash mesh (rad).

    inv alpha' = 2 tan(alpha) (x1 + x2) / (z1 + z2) + inv alpha (习题 5-3); for an
    internal gear 2, z2 counts negative (ISO 21771): 2 tan(alpha) (x1 + x2) / (z1 - z2).
    """
    theta = (2 * math.tan(g1.alpha) * (g1.x + g2.x) / (g1.z + g2.sign * g2.z)
             + involute_function(g1.alpha))
    if theta <= 0:
        raise MeshError(f"x1 + x2 = {g1.x + g2.x:g} is so negative that no zero-backlash "
                        "pressure angle exists (inv alpha' <= 0)")
    return inverse_involute_scalar(theta)[0]


def zero_backlash_distance(g1: SpurGear, g2: SpurGear) -> Optional[float]:
    """Centre distance of the zero-backlash mesh (m), the bound below which the teeth jam.

    None for an external pair whose teeth are so thin (x1 + x2 strongly
    negative) that even at a' = rb1 + rb2 there is backlash: no a' jams.

    Raises
    ------
    MeshError
        An internal pair without a zero-backlash mounting.
    """
    if not g2.internal and (2 * math.tan(g1.alpha) * (g1.x + g2.x) / (g1.z + g2.z)
                            + involute_function(g1.alpha)) <= 0:
        return None
    return centre_distance_from_pressure_angle(g1, g2, zero_backlash_pressure_angle(g1, g2))


def centre_distance_from_pressure_angle(g1: SpurGear, g2: SpurGear, alpha_w: float) -> float:
    """a' = a cos(alpha) / cos(alpha') (m)."""
    return standard_centre_distance(g1, g2) * math.cos(g1.alpha) / math.cos(alpha_w)


def pressure_angle_from_centre_distance(g1: SpurGear, g2: SpurGear, a_w: float) -> float:
    """alpha' = arccos(a cos(alpha) / a') (rad); needs a' >= rb1 + rb2."""
    c = standard_centre_distance(g1, g2) * math.cos(g1.alpha) / a_w
    if c > 1:
        raise MeshError("the centre distance is below rb1 + rb2: the base circles overlap",
                        "base_circles_overlap", a_w=a_w, limit=g1.rb + g2.rb)
    return math.acos(c)


def check_mountings(g1: SpurGear, g2: SpurGear, a_w: Sequence[float] = (),
                    alpha_w: Sequence[float] = ()) -> None:
    """Refuse the first operating centre distance, then pressure angle, at which the
    teeth would jam (checked before any pair is mounted).

    External pair: a' >= a0, the zero-backlash distance; when the teeth are so
    thin that no a' jams, a' > rb1 + rb2.  Internal pair: a cos(alpha) < a' <= a0.
    A pressure angle alpha' stands for a' = a cos(alpha) / cos(alpha').

    Raises
    ------
    MeshError
        reason ``"mounting"``, values: ``given`` (``"a_w"`` or ``"alpha_w"``:
        which argument), ``index`` (in it), ``a_w`` (the a' [m]), ``alpha_w``
        (the alpha' [rad] or None), ``a0`` (the bound [m]: the zero-backlash
        distance, or rb1 + rb2 when ``thin``), ``lo`` (internal: a cos(alpha)
        [m], else None), ``internal``, ``thin``; or the MeshError of
        :func:`zero_backlash_distance` (an internal pair without one).
    """
    internal = g2.internal
    a0 = zero_backlash_distance(g1, g2)
    base = standard_centre_distance(g1, g2) * math.cos(g1.alpha)   # rb1 + rb2 (rb2 - rb1)
    thin = a0 is None
    if a0 is None:   # (thin) thin teeth never jam: only the base circles bound a' (rb1 + rb2 < a')
        a0 = base * (1 + 1e-9)
    lo = base if internal else None
    for given, values in (("a_w", a_w), ("alpha_w", alpha_w)):
        for i, value in enumerate(values):
            a = value if given == "a_w" else base / math.cos(value)
            if internal:
                bad = not base < a <= a0 * (1 + 1e-12) if given == "a_w" \
                    else a > a0 * (1 + 1e-12)
            else:
                bad = a < a0 * (1 - 1e-12)
            if bad:
                where = f"in ({lo:.6g}, {a0:.6g}]" if internal else f">= {a0:.6g}"
                by = "centre distance" if given == "a_w" else "operating pressure angle"
                raise MeshError(
                    f"mounting by {by} [{i}]: a' = {a:.6g} is not {where}, where the teeth "
                    "neither jam nor overlap their base circles", "mounting",
                    given=given, index=i, a_w=a, alpha_w=None if given == "a_w" else value,
                    a0=a0, lo=lo, internal=internal, thin=thin)


def design_teeth_from_ratio(ratio: float, a_w: float, m: float) -> Tuple[int, int]:
    """Tooth numbers of a standard pair from the ratio, centre distance and module.

    z1 + z2 = 2 a' / m, z2 = i z1 (习题 5-2).

    Raises
    ------
    MeshError
        2 a' / m or z1 is not a whole number: say which neighbours would work.
    """
    total = 2 * a_w / m
    if abs(total - round(total)) > 1e-9 * max(1.0, total):
        raise MeshError(f"2 a'/m = {total:.6g} is not a whole number of teeth: a standard "
                        "pair needs a' = m (z1 + z2) / 2", "teeth_not_whole",
                        total=total, below=m * math.floor(total) / 2,
                        above=m * math.ceil(total) / 2)
    total = int(round(total))
    z1 = total / (1 + ratio)
    if z1 < 1 - 1e-9 or total - round(z1) < 1:
        raise MeshError(f"z1 + z2 = 2 a'/m = {total} teeth in all leaves z1 = {z1:.6g} for the "
                        f"ratio {ratio:.6g}: a pair needs at least one tooth on each gear",
                        "too_few_teeth", total=total, z1=z1)
    if abs(z1 - round(z1)) > 1e-9 * total:
        lo = int(math.floor(z1))
        raise MeshError(f"z1 = (z1 + z2)/(1 + i) = {z1:.6g} is not whole: with z1 + z2 = "
                        f"{total} the nearest ratios are {(total - lo) / lo:.5g} (z1 = {lo}) "
                        f"and {(total - lo - 1) / (lo + 1):.5g} (z1 = {lo + 1})")
    z1 = int(round(z1))
    return z1, total - z1


@record
class GearPair:
    """Two spur gears (external pair, or external pinion in a ring) at a centre distance.

    Attributes
    ----------
    g1, g2 : SpurGear
        Pinion and wheel (same m, alpha).
    a_w : float
        Operating centre distance a' (m).
    alpha_w : float
        Operating pressure angle alpha' (rad).
    """

    g1: SpurGear
    g2: SpurGear
    a_w: float
    alpha_w: float

    @property
    def a(self) -> float:
        """Standard centre distance m (z1 + z2) / 2 (m)."""
        return standard_centre_distance(self.g1, self.g2)

    @property
    def ratio(self) -> float:
        """i12 = z2 / z1."""
        return self.g2.z / self.g1.z

    @property
    def dw1(self) -> float:
        """Operating pitch diameter d1' = db1 / cos alpha' (m)."""
        return self.g1.db / math.cos(self.alpha_w)

    @property
    def dw2(self) -> float:
        return self.g2.db / math.cos(self.alpha_w)

    @property
    def epsilon_alpha(self) -> float:
        """Transverse contact ratio (表 5-2)::

            [z1 (tan aa1 - tan a') + z2 (tan aa2 - tan a')] / (2 pi)
        """
        t = math.tan(self.alpha_w)
        # a pointed tooth ends where its flanks meet, below the tip circle: the
        # contact stops there (alpha_a_effective), not at ra
        return (self.g1.z * (math.tan(self.g1.alpha_a_effective) - t)
                + self.g2.sign * self.g2.z * (math.tan(self.g2.alpha_a_effective) - t)
                ) / (2 * math.pi)

    @property
    def line_of_action(self) -> float:
        """Length N1N2 = a' sin alpha' of the theoretical line of action (m)."""
        return self.a_w * math.sin(self.alpha_w)

    @property
    def contact_length(self) -> float:
        """Length B1B2 of the actual path of contact (m); equals epsilon_alpha * pb."""
        return self.epsilon_alpha * self.g1.pb

    @property
    def tip_reach(self) -> Tuple[float, float]:
        """(N2B1, N1B2): how far each tip circle cuts the line of action from the
        other gear's tangent point (m); above N1N2 means interference."""
        r1 = math.sqrt(max(self.g1.r_tip_effective ** 2 - self.g1.rb ** 2, 0.0))
        r2 = math.sqrt(max(self.g2.r_tip_effective ** 2 - self.g2.rb ** 2, 0.0))
        return r2, r1

    @property
    def interference(self) -> bool:
        """True if a tip passes the other gear's tangent point N (meshes below its base circle).

        Internal pair: the ring's tip must stay beyond the pinion's point N1,
        sqrt(ra2^2 - rb2^2) >= N1N2.
        """
        n = self.line_of_action
        if self.g2.internal:
            return self.tip_reach[0] < n * (1 - 1e-12)   # N2B1: the ring's tip
        return any(r > n * (1 + 1e-12) for r in self.tip_reach)

    @property
    def clearances(self) -> Tuple[float, float]:
        """Radial tip clearances (a' - ra1 - rf2, a' - ra2 - rf1) (m).

        Internal pair: (rf2 - a' - ra1, ra2 - a' - rf1).
        """
        if self.g2.internal:
            return (self.g2.rf - self.a_w - self.g1.ra, self.g2.ra - self.a_w - self.g1.rf)
        return (self.a_w - self.g1.ra - self.g2.rf, self.a_w - self.g2.ra - self.g1.rf)

    @property
    def backlash(self) -> float:
        """Circumferential backlash on the operating pitch circle (m).

        j = 2 pi r1' / z1 - s1' - s2', zero at the zero-backlash a'.
        """
        rw1, rw2 = self.dw1 / 2, self.dw2 / 2
        return (2 * math.pi * rw1 / self.g1.z - self.g1.tooth_thickness(rw1)
                - self.g2.tooth_thickness(rw2))

    @property
    def y(self) -> float:
        """Centre-distance modification coefficient (a' - a) / m."""
        return (self.a_w - self.a) / self.g1.m

    @property
    def delta_y(self) -> float:
        """Tip-shortening coefficient x1 + x2 - y (external pairs)."""
        return self.g1.x + self.g2.x - self.y

    @property
    def a_zero_backlash(self) -> Optional[float]:
        """Centre distance of the zero-backlash mesh (m) (习题 5-3); None if no a' jams
        (see :func:`zero_backlash_distance`)."""
        return zero_backlash_distance(self.g1, self.g2)


def tip_shortened(pair: GearPair) -> Tuple[GearPair, float]:
    """The pair with both tips shortened by Δy m to keep the standard clearance c* m.

    y = (a' - a) / m, Δy = (x1 + x2) - y (表 of shifted gears; 0 for standard
    gears at a' = a).  Only external pairs with Δy > 0 are changed.

    Returns
    -------
    (GearPair, float)
        The new pair and Δy.
    """
    g1, g2 = pair.g1, pair.g2
    if g2.internal:
        return pair, 0.0
    dy = pair.delta_y
    if dy <= 1e-12:
        return pair, dy
    cut = dy * g1.m
    return (GearPair(dataclasses.replace(g1, tip_reduction=g1.tip_reduction + cut),
                     dataclasses.replace(g2, tip_reduction=g2.tip_reduction + cut),
                     pair.a_w, pair.alpha_w), dy)


def gear_pair(g1: SpurGear, g2: SpurGear, a_w: Optional[float] = None,
              alpha_w: Optional[float] = None) -> GearPair:
    """Mount two gears: from a', from alpha', or (neither) at zero backlash.

    Parameters
    ----------
    g1, g2 : SpurGear
        Same module and pressure angle.
    a_w : float, optional
        Operating centre distance (m); between the zero-backlash distance and
        the last contact (above it for external pairs, below it for internal ones).
    alpha_w : float, optional
        Operating pressure angle (rad).

    Returns
    -------
    GearPair

    Raises
    ------
    MeshError
        Different modules or pressure angles; both a_w and alpha_w given
        (reason ``"both_given"``); a' on the jamming side of the
        zero-backlash distance; the tips do not reach the line of
        action (epsilon_alpha <= 0: the gears do not touch).
    """
    if not (math.isclose(g1.m, g2.m, rel_tol=1e-12)
            and math.isclose(g1.alpha, g2.alpha, rel_tol=1e-12)):
        raise MeshError("the two gears need the same module and pressure angle to mesh")
    if g1.internal or (g2.internal and g2.z <= g1.z):
        raise MeshError("an internal pair needs an external pinion (gear 1) and a ring gear 2 "
                        "with more teeth")
    if a_w is not None and alpha_w is not None:
        raise MeshError("the centre distance and the operating pressure angle are both "
                        "given (each fixes the other)", "both_given")
    if a_w is None and alpha_w is None:
        alpha_w = zero_backlash_pressure_angle(g1, g2)
    if a_w is None:   # (alpha_w is given or was just found)
        a_w = centre_distance_from_pressure_angle(g1, g2, alpha_w)  # type: ignore[arg-type]
    else:
        alpha_w = pressure_angle_from_centre_distance(g1, g2, a_w)
    pair = GearPair(g1, g2, float(a_w), float(alpha_w))  # type: ignore[arg-type]
    a0 = pair.a_zero_backlash
    if a0 is not None and not g2.internal and pair.a_w < a0 * (1 - 1e-12):
        raise MeshError("the centre distance is below the zero-backlash distance: the teeth "
                        "would jam", "jam", a_w=pair.a_w, a0=a0, internal=False)
    # (an internal pair has a0: zero_backlash_distance raises otherwise)
    if g2.internal and pair.a_w > a0 * (1 + 1e-12):  # type: ignore[operator]
        raise MeshError("the centre distance is above the zero-backlash distance of the "
                        "internal pair: the teeth would jam", "jam", a_w=pair.a_w, a0=a0,
                        internal=True)
    if pair.epsilon_alpha <= 0:
        raise MeshError(f"the tip circles do not reach the line of action (εα = "
                        f"{pair.epsilon_alpha:.3g}): no contact", "no_contact", a_w=pair.a_w,
                        epsilon=pair.epsilon_alpha)
    return pair


@record
class MeshPositions:
    """Both gears turned through a mesh cycle, and their points of contact.

    The pinion is centred at the origin (tooth 0 on +y at phi1 = 0) and turns
    counter-clockwise, driving with the left-hand flanks of its teeth (those
    at polar angle tooth centre + psi); the wheel is centred at (0, a') and
    turns clockwise.  Contact points lie on
    the line of action N1N2, where N1 = rb1 (sin a', cos a').

    Attributes
    ----------
    phi1 : numpy.ndarray
        Pinion angles (rad).
    phi2 : numpy.ndarray
        Wheel rotation angles to draw it with (rad, counter-clockwise from
        tooth 0 on +y, the phase that brings the driven flanks into contact).
    points : numpy.ndarray, shape (len(phi1), K, 2)
        Candidate points on the line of action (m), one per pinion tooth
        slot k; only those with ``in_contact`` are real.
    in_contact : numpy.ndarray of bool, shape (len(phi1), K)
        Which candidates lie on the path of contact; a row without any means
        the mesh is interrupted (epsilon_alpha < 1).
    n1, n2 : numpy.ndarray
        The tangent points N1, N2 (m).
    """

    phi1: np.ndarray
    phi2: np.ndarray
    points: np.ndarray
    in_contact: np.ndarray
    n1: np.ndarray
    n2: np.ndarray

    @property
    def count(self) -> np.ndarray:
        """Number of tooth pairs in contact at each position."""
        return self.in_contact.sum(axis=1)

    def contact(self, i: int) -> np.ndarray:
        """The points of contact at position *i* (k x 2, m)."""
        return self.points[i][self.in_contact[i]]


def mesh_positions(pair: GearPair, phi1: ArrayLike) -> MeshPositions:
    """Positions of an external pair through pinion angles *phi1* (rad), with contacts.

    Notes
    -----
    The left flank of pinion tooth k touches the line of action at the
    distance l_k = rb1 (a' + psi_b1 + 2 pi k / z1 + phi1) from N1 (psi_b1 = the
    tooth half-angle at the base circle); contact is real between the wheel's
    tip (l = N1N2 - sqrt(ra2^2 - rb2^2)) and the pinion's tip (l = sqrt(ra1^2 - rb1^2)),
    so that on average epsilon_alpha points are in contact.
    """
    import numpy as np
    g1, g2 = pair.g1, pair.g2
    if g2.internal:
        raise ValueError("mesh_positions handles external pairs")
    phi1 = np.atleast_1d(np.asarray(phi1, dtype=float))
    aw = pair.alpha_w
    n1n2 = pair.line_of_action
    psi_b1, psi_b2 = float(g1.half_tooth_angle(g1.rb)), float(g2.half_tooth_angle(g2.rb))
    # left flank of pinion tooth k (polar angle pi/2 + psi(rho)) touches N1N2 at l_k from N1
    l0 = g1.rb * (aw + psi_b1)
    # the wheel's flank (its polar angle centre + psi2) then touches at N1N2 - l from N2
    phi2 = (n1n2 - l0) / g2.rb - math.pi - psi_b2 - aw - phi1 * g1.z / g2.z
    foot = np.array([math.sin(aw), math.cos(aw)])
    n1 = g1.rb * foot
    n2 = np.array([0.0, pair.a_w]) - g2.rb * foot
    direction = (n2 - n1) / n1n2
    lo = n1n2 - math.sqrt(max(g2.r_tip_effective ** 2 - g2.rb ** 2, 0.0))
    hi = math.sqrt(max(g1.r_tip_effective ** 2 - g1.rb ** 2, 0.0))
    pb = g1.pb
    base = l0 + g1.rb * phi1
    k = np.arange(math.floor((lo - base.max()) / pb), math.ceil((hi - base.min()) / pb) + 1)
    ell = base[:, None] + k[None, :] * pb
    tol = 1e-12 * pb
    valid = (ell >= max(lo, 0.0) - tol) & (ell <= min(hi, n1n2) + tol)
    points = n1[None, None, :] + ell[:, :, None] * direction[None, None, :]
    return MeshPositions(phi1, phi2, points, valid, n1, n2)
