"""Tooth loads from power and speed, and the efficiency of a worm drive.

Gear 1 (the pinion, the worm) drives.  SI units: power [W], angular speed
[rad/s], lengths [m], forces [N], torques [N m], angles [rad]; pure ``math``
(the scalar gear kinds start without numpy).  Every force is a magnitude, the
force *of the mating gear on* the gear named; its direction is the textbook's:

* tangential ``Ft``: on the driving gear against its rotation, on the driven
  gear with it;
* radial ``Fr``: towards the gear's own axis;
* axial ``Fa``: along the gear's axis (the hand of the helix decides which
  way: docs/gear.md).

Models
------
spur and helical pairs
    The normal force lies along the line of action in the base tangent plane;
    it is split at the pitch point of the operating pitch circles d'
    (Ft = 2 T1 / d'1, Fr = Ft tan a'_t, Fa = Ft tan b', tan b' = tan b d'/d);
    for standard gears at the standard centre distance d' = d and
    Fr = Ft tan an / cos b, Fa = Ft tan b.  No friction: T2 = T1 z2/z1.
straight bevel pairs
    The forces act at the middle of the face width, dm = d (1 - 0.5 b/R):
    Ft = 2 T1 / dm1, Fr_i = Ft tan a cos d_i, Fa_i = Ft tan a sin d_i.
worm drives
    The worm thread is an inclined plane of lead angle g; with the flank
    friction coefficient mu and the normal pressure angle an
    (tan an = tan a_x cos g for the axial pressure angle a_x),
    W = Ft1 / (cos an sin g + mu cos g) is the normal force,
    Ft2 = Fa1 = W (cos an cos g - mu sin g), Fr = W sin an, and the efficiency
    with the worm driving is
    eta = (cos an - mu tan g) / (cos an + mu cot g) = tan g / tan(g + phi),
    tan phi = mu / cos an; with the wheel driving,
    eta' = (cos an - mu cot g) / (cos an + mu tan g) = tan(g - phi) / tan g,
    self-locking when g <= phi (eta' <= 0).

Notes
-----
Formulas: Carvill, *Mechanical Engineer's Data Handbook*, section 2.10.6
(worm forces and efficiency); Shigley's *Mechanical Engineering Design*,
sections 13-14 … 13-17 (spur, bevel, helical and worm force components);
Autodesk Inventor's gear-calculation help (Fr = Ft tan a_tw, Fa = Ft tan b,
T2 = T1 i eta).
"""

from __future__ import annotations

import math
from typing import Optional, Tuple

from mechcli.core.gear.spur import GearError
from mechcli.core.records import record


class LoadError(GearError):
    """Loads that cannot exist as asked (``reason``: ``"no_drive"``, ``"bevel_face"``)."""


@record
class ToothLoads:
    """Torques, speeds and tooth forces of a driven pair (gear 1 drives).

    Attributes
    ----------
    kind : str
        ``"spur"``, ``"helical"``, ``"bevel"`` or ``"worm"``.
    power : float
        Input power on shaft 1 (W).
    omega1, omega2 : float
        Angular speeds of shafts 1 and 2 (rad/s).
    T1, T2 : float
        Torques on shafts 1 (input) and 2 (output) (N m); T2 = T1 i eta.
    v : float
        Speed of the pitch point of gear 1 where the forces act (m/s): on the
        operating pitch circle (spur, helical), the mean cone (bevel), the
        worm's reference cylinder (worm).
    d_force1, d_force2 : float
        Diameters on which the tangential forces act (m).
    Ft1, Fr1, Fa1, Ft2, Fr2, Fa2 : float
        Tangential, radial and axial force on gears 1 and 2 (N).
    Fn : float
        Normal tooth force (N) (for a worm, the normal force on the flank,
        without the friction force).
    efficiency : float
        Output over input power (1 without friction).
    friction_angle : float or None
        Worm: the friction angle phi, tan phi = mu / cos an (rad).
    mu : float or None
        Worm: flank friction coefficient.
    efficiency_reverse : float or None
        Worm: efficiency with the wheel driving, the formula's value (<= 0:
        self-locking, the wheel cannot drive; the report shows 0 then).
    sliding_velocity : float or None
        Worm: sliding speed of the flanks v1 / cos g (m/s).
    """

    kind: str
    power: float
    omega1: float
    omega2: float
    T1: float
    T2: float
    v: float
    d_force1: float
    d_force2: float
    Ft1: float
    Fr1: float
    Fa1: float
    Ft2: float
    Fr2: float
    Fa2: float
    Fn: float
    efficiency: float = 1.0
    friction_angle: float | None = None
    mu: float | None = None
    efficiency_reverse: float | None = None
    sliding_velocity: float | None = None

    @property
    def power_out(self) -> float:
        """Output power T2 omega2 (W)."""
        return self.T2 * self.omega2

    @property
    def self_locking(self) -> Optional[bool]:
        """Worm: the wheel cannot drive the worm (None for other kinds)."""
        if self.efficiency_reverse is None:
            return None
        return self.efficiency_reverse <= 0


def parallel_loads(power: float, omega1: float, z1: int, z2: int, d1: float, d2: float, dw1: float,
                   dw2: float, alpha_wt: float, beta: float = 0.0,
                   internal: bool = False) -> ToothLoads:
    """Loads of a spur (``beta = 0``) or helical pair.

    Parameters
    ----------
    power : float
        Input power on gear 1 (W), > 0.
    omega1 : float
        Speed of gear 1 (rad/s), > 0.
    z1, z2 : int
        Teeth (z2 of a ring counted positive).
    d1, d2 : float
        Reference diameters (m).
    dw1, dw2 : float
        Operating pitch diameters (m).
    alpha_wt : float
        Operating (transverse) pressure angle (rad).
    beta : float
        Helix angle on the reference cylinder (rad); 0 for spur gears.

    Returns
    -------
    ToothLoads
        Ft = 2 T1/d'1, Fr = Ft tan a'_t, Fa = Ft tan b' with tan b' = tan b d'1/d1;
        the same magnitudes on both gears.
    """
    t1 = power / omega1
    ft = 2 * t1 / dw1
    fr = ft * math.tan(alpha_wt)
    beta_w = math.atan(math.tan(beta) * dw1 / d1)
    fa = ft * math.tan(beta_w)
    ratio = z2 / z1
    return ToothLoads("helical" if beta else "spur", power, omega1, omega1 / ratio, t1,
                      t1 * ratio, omega1 * dw1 / 2, dw1, dw2, ft, fr, fa, ft, fr, fa,
                      math.hypot(ft, fr, fa))


def bevel_mean_diameters(d1: float, d2: float, cone_distance: float,
                         face_width: float) -> Tuple[float, float]:
    """Mean diameters dm_i = d_i (1 - 0.5 b / R) of a bevel pair of face width b (m).

    Raises
    ------
    LoadError
        reason ``"bevel_face"``: b >= R (no mean cone).
    """
    if not 0 < face_width < cone_distance:
        raise LoadError("the face width must be below the cone distance", "bevel_face",
                        b=face_width, R=cone_distance)
    k = 1 - 0.5 * face_width / cone_distance
    return d1 * k, d2 * k


def bevel_loads(power: float, omega1: float, z1: int, z2: int, d1: float, d2: float,
                cone_distance: float, face_width: float, alpha: float, delta1: float,
                delta2: float) -> ToothLoads:
    """Loads of a straight bevel pair, acting at the middle of the face width.

    dm_i = d_i (1 - 0.5 b / R); Ft = 2 T1 / dm1; on gear i Fr_i = Ft tan a cos d_i
    and Fa_i = Ft tan a sin d_i (Shigley sec. 13-15); Fn = Ft / cos a.

    Raises
    ------
    LoadError
        reason ``"bevel_face"``: b >= R (no mean cone).
    """
    dm1, dm2 = bevel_mean_diameters(d1, d2, cone_distance, face_width)
    t1 = power / omega1
    ft = 2 * t1 / dm1
    ta = math.tan(alpha)
    ratio = z2 / z1
    return ToothLoads("bevel", power, omega1, omega1 / ratio, t1, t1 * ratio,
                      omega1 * dm1 / 2, dm1, dm2,
                      ft, ft * ta * math.cos(delta1), ft * ta * math.sin(delta1),
                      ft, ft * ta * math.cos(delta2), ft * ta * math.sin(delta2),
                      ft / math.cos(alpha))


def worm_normal_pressure_angle(alpha_x: float, gamma: float) -> float:
    """Normal pressure angle of a worm of axial pressure angle *alpha_x* and lead angle
    *gamma*: tan an = tan a_x cos g (rad)."""
    return math.atan(math.tan(alpha_x) * math.cos(gamma))


def worm_efficiency(gamma: float, alpha_n: float, mu: float) -> Tuple[float, float, float]:
    """Efficiencies of a worm drive (worm driving, wheel driving) and the friction angle.

    eta = (cos an - mu tan g)/(cos an + mu cot g), eta' = (cos an - mu cot g)/
    (cos an + mu tan g), tan phi = mu / cos an (Carvill 2.10.6; Shigley eq. 13-46).

    Returns
    -------
    (float, float, float)
        eta, eta' (<= 0: self-locking), phi (rad).
    """
    ca, tg = math.cos(alpha_n), math.tan(gamma)
    eta = (ca - mu * tg) / (ca + mu / tg)
    eta_rev = (ca - mu / tg) / (ca + mu * tg)
    return eta, eta_rev, math.atan(mu / ca)


def worm_loads(power: float, omega1: float, z1: int, z2: int, d1: float, d2: float, gamma: float,
               alpha_x: float, mu: float) -> ToothLoads:
    """Loads of a worm drive with the worm (gear 1) driving.

    Parameters
    ----------
    gamma : float
        Lead angle of the worm on its reference cylinder (rad).
    alpha_x : float
        Axial pressure angle of the worm (rad).
    mu : float
        Flank friction coefficient, >= 0.

    Returns
    -------
    ToothLoads
        Ft1 = 2 T1/d1 = Fa2; Ft2 = Fa1 = W (cos an cos g - mu sin g);
        Fr1 = Fr2 = W sin an, with W = Ft1 / (cos an sin g + mu cos g);
        T2 = Ft2 d2 / 2 = T1 (z2/z1) eta.

    Raises
    ------
    LoadError
        reason ``"no_drive"``: the friction stops the worm from driving
        (eta <= 0, g + phi >= 90 deg).
    """
    alpha_n = worm_normal_pressure_angle(alpha_x, gamma)
    eta, eta_rev, phi = worm_efficiency(gamma, alpha_n, mu)
    if eta <= 0:
        raise LoadError("the friction is so large that the worm cannot drive the wheel",
                        "no_drive", gamma=gamma, phi=phi, mu=mu)
    t1 = power / omega1
    ft1 = 2 * t1 / d1
    ca, sa = math.cos(alpha_n), math.sin(alpha_n)
    cg, sg = math.cos(gamma), math.sin(gamma)
    w = ft1 / (ca * sg + mu * cg)
    ft2 = w * (ca * cg - mu * sg)
    fr = w * sa
    v1 = omega1 * d1 / 2
    return ToothLoads("worm", power, omega1, omega1 * z1 / z2, t1, ft2 * d2 / 2, v1, d1, d2,
                      ft1, fr, ft2, ft2, fr, ft1, w, eta, phi, mu, eta_rev, v1 / cg)
