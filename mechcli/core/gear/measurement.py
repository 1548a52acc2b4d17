"""Tooth-thickness measurement and the inverse problem of a shifted pair.

Lengths in metres, angles in radians; pure ``math`` (the pair and helical kinds
start without numpy).  One gear is described in its *normal* plane by the
rack that cuts it (normal module mn, normal pressure angle alpha_n, shift xn)
and its helix angle beta on the reference cylinder (0 for a spur gear, where
normal and transverse planes coincide).  Every quantity below reduces to the
spur formula at beta = 0.

* chordal tooth thickness and chordal addendum (height) at the reference
  circle -- for helical gears on the virtual spur gear of zv = z / cos^3 beta
  teeth in the normal plane -- and, for spur gears, at any radius;
* span measurement: the base tangent length W over k teeth,
  W = mn cos(an) [pi (k - 0.5) + z inv(at)] + 2 xn mn sin(an) - E cos(an),
  with k chosen as ISO 21771 does (the anvils touch the flanks near the
  diameter d + 2 xn mn);
* measurement over two pins (balls for helical gears), the pin diameter by
  default the one touching the flanks on the same diameter d + 2 xn mn;
* a tooth-thickness allowance E (the normal arc thickness on the reference
  circle is s - E), the backlash it gives a pair, and the generating
  profile-shift coefficient x_E of the thinned tooth (ISO 21771);
* the profile-shift sum of a pair for a given centre distance and its split.

Notes
-----
Sources of the formulas: ISO 21771:2007 (span count and base tangent length),
"Elements of Metric Gear Technology" (SDP/SI, KHK) section 10, Tables 10-1 and
10-3 (chordal thickness of spur and helical gears), and the measurement over
pins of the same section (inv phi = s_t/d + inv(at) + dp/(z mn cos an) - pi/z).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Callable, Iterable, Optional, Tuple

from mechcli.core.gear.involute import inverse_involute_scalar, involute_function
from mechcli.core.gear.spur import GearError
from mechcli.core.records import record


class MeasurementError(GearError):
    """A measurement or a shift design that cannot exist as asked (``reason``/``values``)."""


@record
class ToothForm:
    """One gear as its cutting rack sees it (spur: ``beta = 0``).

    Attributes
    ----------
    z : int
        Teeth.
    mn, alpha_n : float
        Normal module (m) and normal pressure angle (rad).
    xn : float
        Normal profile-shift coefficient.
    beta : float
        Helix angle on the reference cylinder (rad).
    ra : float
        Tip radius (m).
    allowance : float
        Tooth-thickness allowance E: reduction of the normal arc thickness on
        the reference circle (m), >= 0.
    """

    z: int
    mn: float
    alpha_n: float
    xn: float = 0.0
    beta: float = 0.0
    ra: float = math.nan
    allowance: float = 0.0

    @property
    def alpha_t(self) -> float:
        """Transverse pressure angle arctan(tan an / cos beta) (rad)."""
        return math.atan(math.tan(self.alpha_n) / math.cos(self.beta))

    @property
    def beta_b(self) -> float:
        """Base helix angle arcsin(sin beta cos an) (rad)."""
        return math.asin(math.sin(self.beta) * math.cos(self.alpha_n))

    @property
    def d(self) -> float:
        """Reference diameter z mn / cos beta (m)."""
        return self.z * self.mn / math.cos(self.beta)

    @property
    def db(self) -> float:
        """Base diameter d cos(at) (m)."""
        return self.d * math.cos(self.alpha_t)

    @property
    def s_n_nominal(self) -> float:
        """Normal arc tooth thickness on the reference circle mn (pi/2 + 2 xn tan an) (m)."""
        return self.mn * (math.pi / 2 + 2 * self.xn * math.tan(self.alpha_n))

    @property
    def s_n(self) -> float:
        """Normal arc thickness with the allowance, s_n_nominal - E (m)."""
        return self.s_n_nominal - self.allowance

    @property
    def s_t(self) -> float:
        """Transverse arc thickness on the reference circle s_n / cos beta (m)."""
        return self.s_n / math.cos(self.beta)

    @property
    def zv(self) -> float:
        """Virtual number of teeth z / cos^3 beta (SDP/SI Table 10-3)."""
        return self.z / math.cos(self.beta) ** 3

    def thickness(self, radius: float) -> float:
        """Transverse arc thickness at a radius >= rb (m), with the allowance."""
        ak = math.acos(min(1.0, self.db / (2 * radius)))
        return 2 * radius * (self.s_t / self.d + involute_function(self.alpha_t)
                             - involute_function(ak))


# -- chordal thickness -----------------------------------------------------------
def chordal(s: float, r: float, height: float) -> Tuple[float, float]:
    """Chord of an arc thickness *s* on a circle of radius *r*, and its height.

    Returns
    -------
    (float, float)
        s_bar = 2 r sin(s / 2r) and h_bar = height + r (1 - cos(s / 2r)) (m),
        *height* being the radial distance from that circle to the tip.
    """
    psi = s / (2 * r)
    return 2 * r * math.sin(psi), height + r * (1 - math.cos(psi))


def chordal_at_reference(g: ToothForm) -> Tuple[float, float]:
    """Chordal thickness and chordal addendum at the reference circle (m).

    Helical gears: on the virtual spur gear of radius zv mn / 2 in the normal
    plane with the normal thickness (SDP/SI Table 10-3); spur gears: eq. of
    Table 10-1, s_bar = z m sin(s / d), h_bar = ha + (z m / 2)(1 - cos(s / d)).
    """
    return chordal(g.s_n, g.zv * g.mn / 2, g.ra - g.d / 2)


def chordal_at_radius(g: ToothForm, radius: float) -> Tuple[float, float]:
    """Chordal thickness and height over the tip at a radius of a spur gear (m)."""
    if g.beta:
        raise ValueError("chordal thickness at any radius is for spur gears")
    return chordal(g.thickness(radius), radius, g.ra - radius)


# -- span measurement ---------------------------------------------------------------
def span_teeth(g: ToothForm) -> int:
    """Number of teeth k in the span, as ISO 21771 chooses it.

    k = round(z/pi (tan a_Mt / cos^2 beta_b - 2 xn tan an / z - inv at) + 0.5), where
    cos a_Mt = db / (d + 2 xn mn): the anvils touch near the diameter
    d + 2 xn mn.  For an unshifted spur gear this is round(z alpha / pi + 0.5)
    (alpha in radians; z alpha/180 deg + 0.5).  At least 1, at most z - 1.
    """
    dm = g.d + 2 * g.xn * g.mn
    c = g.db / dm
    tan_m = math.sqrt(max(1 / (c * c) - 1, 0.0))
    k_th = (g.z / math.pi * (tan_m / math.cos(g.beta_b) ** 2
                             - 2 * g.xn * math.tan(g.alpha_n) / g.z
                             - involute_function(g.alpha_t)) + 0.5)
    return int(min(max(math.floor(k_th + 0.5), 1), max(g.z - 1, 1)))


@record
class Span:
    """Base tangent length W over k teeth (normal plane) and where it touches.

    Attributes
    ----------
    k : int
        Teeth spanned.
    W : float
        Base tangent length in the normal plane (m), with the allowance.
    d_contact : float
        Diameter on which the anvils touch the flanks (m).
    b_min : float
        Face width the anvils need, W sin(beta_b) (m; 0 for spur gears).
    """

    k: int
    W: float
    d_contact: float
    b_min: float


def span(g: ToothForm, k: Optional[int] = None) -> Span:
    """Base tangent length over *k* teeth (default :func:`span_teeth`) (ISO 21771).

    W = mn cos(an) [pi (k - 0.5) + z inv(at)] + 2 xn mn sin(an) - E cos(an);
    the anvils touch the flanks on d = sqrt(db^2 + (W cos beta_b)^2): the measured
    segment lies in the base tangent plane at beta_b to the transverse plane, its
    transverse projection W cos beta_b is tangent to the base circle at its middle.
    """
    k = span_teeth(g) if k is None else int(k)
    an = g.alpha_n
    w = (g.mn * math.cos(an) * (math.pi * (k - 0.5) + g.z * involute_function(g.alpha_t))
         + 2 * g.xn * g.mn * math.sin(an) - g.allowance * math.cos(an))
    return Span(k, w, math.hypot(g.db, w * math.cos(g.beta_b)), w * math.sin(g.beta_b))


# -- measurement over pins (balls) --------------------------------------------------
def ideal_pin_diameter(g: ToothForm) -> float:
    """Pin (ball) diameter touching the nominal flanks on the diameter d + 2 xn mn (m).

    With the contact pressure angle a_c (cos a_c = db / (d + 2 xn mn)), the pin
    centre lies at phi = tan a_c - (s_t/d + inv at - pi/z) and
    dp = z mn cos(an) (tan phi - tan a_c).  For an unshifted spur gear of 20 deg
    this is the pin touching at the reference circle, about 1.72 m - 1.75 m (the
    standard pins of 1.728 m, AGMA; 1.75 m, tandwiel.info).
    """
    nominal = dataclasses.replace(g, allowance=0.0)
    cos_c = min(1.0, nominal.db / (nominal.d + 2 * nominal.xn * nominal.mn))
    tan_c = math.sqrt(max(1 / (cos_c * cos_c) - 1, 0.0))
    phi = tan_c - (nominal.s_t / nominal.d + involute_function(nominal.alpha_t)
                   - math.pi / nominal.z)
    return nominal.z * nominal.mn * math.cos(nominal.alpha_n) * (math.tan(phi) - tan_c)


@record
class OverPins:
    """Measurement over two pins (balls) in opposite spaces.

    Attributes
    ----------
    dp : float
        Pin or ball diameter (m).
    M : float
        Dimension over the pins (m): d_M + dp for an even z,
        d_M cos(pi / 2z) + dp for an odd z.
    d_centre : float
        Diameter of the pin centres d_M = db / cos(phi) (m).
    phi : float
        Transverse pressure angle at the pin centre (rad).
    d_contact : float
        Diameter where the pin touches the flanks (m).
    """

    dp: float
    M: float
    d_centre: float
    phi: float
    d_contact: float


def over_pins(g: ToothForm, dp: Optional[float] = None) -> OverPins:
    """Dimension over two pins (balls for helical gears) of diameter *dp* (m).

    inv phi = s_t / d + inv at + dp / (z mn cos an) - pi / z (with the
    allowance in s_t); the pin touches where tan a_c = tan phi - dp/(z mn cos an).

    Raises
    ------
    MeasurementError
        reason ``"pin_too_small"``: the pin sinks below the base circle
        (inv phi <= 0).
    """
    dp = ideal_pin_diameter(g) if dp is None else float(dp)
    w = dp / (g.z * g.mn * math.cos(g.alpha_n))
    theta = g.s_t / g.d + involute_function(g.alpha_t) + w - math.pi / g.z
    if theta <= 0:
        raise MeasurementError("the pin is so small that it falls into the space below the "
                               "base circle", "pin_too_small", dp=dp, z=g.z)
    phi = inverse_involute_scalar(theta)[0]
    dm = g.db / math.cos(phi)
    m_over = dm + dp if g.z % 2 == 0 else dm * math.cos(math.pi / (2 * g.z)) + dp
    tan_c = math.tan(phi) - w
    d_contact = g.db * math.sqrt(1 + tan_c * tan_c) if tan_c > 0 else g.db
    return OverPins(dp, m_over, dm, phi, d_contact)


# -- backlash ---------------------------------------------------------------------------
def backlash_from_allowances(j0: float, alpha_t: float, alpha_wt: float, beta: float, e1: float,
                             e2: float) -> float:
    """Circumferential backlash on the operating pitch circle with allowances (m).

    j_t = j0 + (E1 + E2) cos(at) / (cos(awt) cos(beta)): a normal thinning E on the
    reference circle is E / cos(beta) there in the transverse plane, E cos(at)/cos(beta)
    along the base circle, and that divided by cos(awt) on the operating pitch circle.
    *j0* is the backlash of the nominal teeth.
    """
    return j0 + (e1 + e2) * math.cos(alpha_t) / (math.cos(alpha_wt) * math.cos(beta))


def allowances_for_backlash(j: float, j0: float, alpha_t: float, alpha_wt: float, beta: float,
                            share1: float = 0.5) -> Tuple[float, float]:
    """Allowances (E1, E2) giving the backlash *j* where the nominal teeth give *j0* (m).

    E1 + E2 = (j - j0) cos(awt) cos(beta) / cos(at), split *share1* : 1 - share1.
    """
    total = (j - j0) * math.cos(alpha_wt) * math.cos(beta) / math.cos(alpha_t)
    return share1 * total, (1 - share1) * total


# -- generating profile shift ------------------------------------------------------------
@record
class GeneratingShift:
    """The generating profile-shift coefficient x_E of a gear thinned by an allowance:
    the (normal) shift at which the rack cuts the thinned tooth at zero backlash with
    the rack.

    Attributes
    ----------
    x : float
        Nominal (normal) profile-shift coefficient.
    E_sn : float
        Signed normal thickness allowance on the reference circle (m): -E (thinning < 0).
    E_bn : float
        Signed normal thickness allowance on the base cylinder, normal to the flank
        (the span allowance, m): the transverse E/cos(beta) carried to the base circle
        (times cos at) and turned into the base tangent plane (times cos beta_b);
        = -E cos(an).
    x_E : float
        ISO 21771's sin form x + E_bn / (2 mn sin an): the span of the thinned tooth is
        the nominal span formula with x_E (W_k = ... + 2 x_E mn sin an).
    x_E_tan : float
        The tan form x + E_sn / (2 mn tan an): the thinned reference thickness is
        mn (pi/2 + 2 x_E tan an).
    """

    x: float
    E_sn: float
    E_bn: float
    x_E: float
    x_E_tan: float


def generating_shift(g: ToothForm) -> GeneratingShift:
    """x_E of the gear *g* with its allowance, in both forms (:class:`GeneratingShift`).

    Notes
    -----
    A rack shifted by x_E mn has the space width mn (pi/2 + 2 x_E tan an) on the line
    that rolls on the reference circle, so the tooth it cuts has that reference
    thickness; thinning by E lowers it by E: x_E = x - E / (2 mn tan an) (DIN ISO
    21771:2014 §7.4, x_E = x + E_sn / (2 mn tan an)).  The same thinning lowers the base-normal
    thickness (and the span W_k) by E cos an, and W_k grows by 2 mn sin an per unit of
    shift: x_E = x + E_bn / (2 mn sin an), the form of ISO 21771:2007's backlash relation
    x_E1 + x_E2 = x1 + x2 (zero backlash at a') - j_bn / (2 mn sin an).  Both give the same
    number (cos at cos beta_b = cos an cos beta); they differ only when one is given the
    other's allowance (a factor cos an).  A ring (internal gear) follows ISO's sign of x.
    """
    e_sn = -g.allowance
    e_bn = e_sn / math.cos(g.beta) * math.cos(g.alpha_t) * math.cos(g.beta_b)
    return GeneratingShift(g.xn, e_sn, e_bn,
                           g.xn + e_bn / (2 * g.mn * math.sin(g.alpha_n)),
                           g.xn + e_sn / (2 * g.mn * math.tan(g.alpha_n)))


# -- profile shifts of a pair for a centre distance -------------------------------------
def shift_sum_for_centre_distance(z1: int, z2: int, alpha: float, a: float,
                                  a_w: float) -> Tuple[float, float]:
    """Sum x1 + x2 that makes a zero-backlash pair at the centre distance a' (ISO 21771).

    cos a' = a cos(alpha) / a',  x1 + x2 = (z1 + z2)(inv a' - inv alpha) / (2 tan alpha).

    Returns
    -------
    (float, float)
        x1 + x2 and the operating pressure angle a' (rad).

    Raises
    ------
    MeasurementError
        reason ``"no_shift_sum"``: a' <= a cos(alpha) (the base circles overlap).
    """
    c = a * math.cos(alpha) / a_w
    if c >= 1:
        raise MeasurementError("no profile-shift sum gives this centre distance: it is not "
                               "above rb1 + rb2", "no_shift_sum", a_w=a_w,
                               limit=a * math.cos(alpha))
    if abs(a_w - a) <= 1e-14 * a:   # the standard distance: exactly no shift (not acos noise)
        return 0.0, alpha
    aw = math.acos(c)
    inv = involute_function(aw) - involute_function(alpha)
    return (z1 + z2) * inv / (2 * math.tan(alpha)), aw


def normal_shift_sum_for_centre_distance(z1: int, z2: int, mn: float, alpha_n: float, beta: float,
                                         a_w: float) -> Tuple[float, float]:
    """Sum xn1 + xn2 of a helical (or, beta = 0, spur) pair that gives the centre distance a'.

    With the transverse pressure angle at = arctan(tan an / cos beta) and the standard
    centre distance a = mn (z1 + z2) / (2 cos beta): cos a_wt = a cos(at) / a' and
    xn1 + xn2 = (z1 + z2)(inv a_wt - inv at) / (2 tan an) (ISO 21771; the inverse of
    the zero-backlash condition of :class:`~.helical.HelicalPair`).

    Returns
    -------
    (float, float)
        xn1 + xn2 and the operating transverse pressure angle a_wt (rad).

    Raises
    ------
    MeasurementError
        reason ``"no_shift_sum"``: a' <= a cos(at) (the base circles overlap).
    """
    at = math.atan(math.tan(alpha_n) / math.cos(beta))
    a = mn * (z1 + z2) / (2 * math.cos(beta))
    x_t, awt = shift_sum_for_centre_distance(z1, z2, at, a, a_w)
    return x_t * math.tan(at) / math.tan(alpha_n), awt


def specific_sliding_at_roots(rb1: float, rb2: float, ra1: float, ra2: float, a_w: float,
                              alpha_w: float, u: float) -> Tuple[float, float]:
    """Specific sliding at the start and end of contact (the two roots).

    zeta1 = 1 - rho2 / (u rho1) at the pinion's root (where the wheel's tip
    meets it), zeta2 = 1 - u rho1 / rho2 at the wheel's root (the pinion's tip);
    rho1, rho2 are the radii of curvature (distances from N1, N2 along N1N2)
    and u = z2 / z1.  -inf where the tip passes the other's tangent point.
    """
    n = a_w * math.sin(alpha_w)
    r2 = math.sqrt(max(ra2 * ra2 - rb2 * rb2, 0.0))
    r1 = math.sqrt(max(ra1 * ra1 - rb1 * rb1, 0.0))
    rho1a, rho2a = n - r2, r2
    rho1e, rho2e = r1, n - r1
    z1 = 1 - rho2a / (u * rho1a) if rho1a > 0 else -math.inf
    z2 = 1 - u * rho1e / rho2e if rho2e > 0 else -math.inf
    return z1, z2


def split_balanced_sliding(zeta: Callable[[float], Tuple[float, float]], x_sum: float,
                           lo: float = -1.5, hi: float = 1.5, tol: float = 1e-12) -> float:
    """x1 (and x2 = x_sum - x1) with equal specific sliding at the two roots.

    *zeta(x1)* returns (zeta1, zeta2) of the pair with shifts (x1, x_sum - x1);
    raising x1 moves the pinion's root contact away from its base circle, so
    zeta1 - zeta2 increases with x1 and the root is found by bisection on
    [max(lo, x_sum - hi), min(hi, x_sum - lo)].

    Raises
    ------
    MeasurementError
        reason ``"no_balanced_split"``: no shift in the range balances them.
    """
    a, b = max(lo, x_sum - hi), min(hi, x_sum - lo)

    def f(x1: float) -> float:
        z1, z2 = zeta(x1)
        if z1 == -math.inf and z2 == -math.inf:
            return math.nan
        if z1 == -math.inf:
            return -math.inf
        if z2 == -math.inf:
            return math.inf
        return z1 - z2

    fa, fb = f(a), f(b)
    if a > b or math.isnan(fa) or math.isnan(fb) or fa > 0 or fb < 0:
        raise MeasurementError("no split of the shift sum in [-1.5, 1.5] balances the specific "
                               "sliding at the roots", "no_balanced_split", x_sum=x_sum, lo=a,
                               hi=b)
    for _ in range(200):
        mid = 0.5 * (a + b)
        fm = f(mid)
        if math.isnan(fm) or fm > 0:
            b = mid
        else:
            a = mid
        if b - a < tol:
            break
    return 0.5 * (a + b)


# -- everything measured on one gear ---------------------------------------------------
@record
class GearMeasures:
    """The measurements of one gear (with its allowance).

    Attributes
    ----------
    form : ToothForm
    s_chord, h_chord : float
        Chordal thickness and chordal addendum at the reference circle (m).
    span : Span
    pins : OverPins
    radii : tuple of (float, float)
        (chordal thickness, chordal height over the tip) at each extra radius
        of a spur gear (m).
    """

    form: ToothForm
    s_chord: float
    h_chord: float
    span: Span
    pins: OverPins
    radii: tuple = ()


def measure(form: ToothForm, k: Optional[int] = None, dp: Optional[float] = None,
            radii: Iterable[float] = ()) -> GearMeasures:
    """Chordal thickness, span and over-pins dimension of one gear (:class:`GearMeasures`)."""
    s_chord, h_chord = chordal_at_reference(form)
    return GearMeasures(form, s_chord, h_chord, span(form, k), over_pins(form, dp),
                        tuple(chordal_at_radius(form, r) for r in radii))


@record
class ShiftDesign:
    """The profile shifts of a pair designed for a centre distance.

    Attributes
    ----------
    rule : str
        ``"x1"`` (x1 given, x2 = sum - x1), ``"sliding"`` (balanced specific
        sliding at the two roots) or ``"strength"`` (equal Y_Fa Y_Sa,
        :mod:`~.strength`).
    x_sum, x1, x2 : float
        Shifts (normal shifts for a helical pair).
    zeta1, zeta2 : float or None
        Specific sliding at the pinion's and the wheel's root with these shifts; None
        where the other gear's tip passes that gear's end N of the line of action
        (interference: the contact would start below its base circle, zeta -> -inf).
    factors : tuple
        The two gears' :class:`~.strength.RootFactors` with these shifts (empty
        unless computed).
    """

    rule: str
    x_sum: float
    x1: float
    x2: float
    zeta1: Optional[float]
    zeta2: Optional[float]
    factors: tuple = ()
