"""The ``mechcli gear`` problem file: one table naming the kind of problem.

A spec holds exactly one of ``[involute]``, ``[inverse_involute]``, ``[spur]``,
``[pair]``, ``[generation]``, ``[helical]``, ``[worm]``, ``[bevel]`` (see
``docs/gear.md``).  Lengths are in the spec's ``units`` and converted to metres
here; angles are given in degrees (keys ending in ``_deg``) and converted to
radians.  The problem dataclasses are plain data: ``mechcli.core.gear.problems``
solves them, ``mechcli.report.gear`` words what the spec forbids.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Iterable, List, Optional, Tuple, Union

from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError, closest
from mechcli.spec.reader import MAX_LENGTH, MIN_LENGTH, Section, load_spec

if TYPE_CHECKING:
    import os

#: most points of an involute curve or table (larger is a mistyped step, not a wish)
MAX_POINTS = 1_000_000

KINDS = ("involute", "inverse_involute", "spur", "pair", "generation", "helical", "worm",
         "bevel")


# -- shared readers ----------------------------------------------------------------
# The declared range of every kind of number (``lo``/``hi`` of the accessor, so
# ``mechcli schema gear`` prints it and no solver sees a value outside it).

#: pressure angle [deg] (alpha, alpha_n, and the working alpha' of a pair): below 1 deg
#: no gear of at most 10000 teeth escapes undercut (z_min = 2 ha* / sin^2 alpha = 6567 at
#: 1 deg), and near 0 the involute function alpha^3/3 and tan^2 alpha underflow (the
#: solvers divide by them); 45 deg (excluded) is the rack's practical limit (standards use
#: 14.5 - 25)
PRESSURE_ANGLE_DEG = (1.0, 45.0)
#: operating pressure angle alpha' [deg] of a mounting: a' = a cos(alpha) / cos(alpha'),
#: so a' grows without bound as alpha' -> 90 deg; 89 deg is a' = 57 a
WORKING_ANGLE_DEG = (1.0, 89.0)
#: addendum and clearance coefficients (ha*, c*, han*, cn*): the rack cutter's tooth is
#: pointed once (ha* + c*) tan(alpha) >= pi/4, so at the smallest accepted pressure angle
#: (1 deg) no tooth system has ha* + c* above pi / (4 tan 1 deg) = 45.0
COEFFICIENT = (0.0, 45.0)
#: an angle of the involute curve or table [deg]: the involute ends at 90 deg (tan)
INVOLUTE_DEG = (0.0, 89.0)


def _teeth(sec: Section, name: str, lo: int = 1, hi: int = 10000) -> int:
    """A tooth number: an integer in [1, 10000] (a float such as 20.5, or 0, is an error)."""
    return sec.integer(name, lo=lo, hi=hi)


def _tooth_numbers(sec: Section) -> Tuple[int, int]:
    """z1 and z2 of a pair.  Both are declared first, so a missing z1 is reported as
    missing, not as a misspelling of the z2 that follows it."""
    sec.declare("z1", "z2")
    return _teeth(sec, "z1"), _teeth(sec, "z2")


def _exactly_one(sec: Section, a: str, b: str, va: object, vb: object, why: str = "") -> None:
    """Refuse both or neither of the alternative keys *a*, *b* (values *va*, *vb*).

    Neither, next to a key nobody reads that is close to one of them: name that key and
    the missing one together (a misspelt ``beta_dg`` is why ``beta_deg`` is missing)."""
    if (va is None) != (vb is None):
        return
    want = f"{a} or {b} (exactly one{why})"
    if va is None:
        read: set = getattr(sec, "_known", set())
        for k in sec.data:
            hint = closest(k, (a, b))
            if hint and k not in read:
                raise SpecError(sec.file, sec.key(k), f"a known key ({want}: neither is given)",
                                f"unknown key '{k}'", hint)
    raise sec.error(a, want, "both" if va is not None else "neither")


def _degrees(sec: Section, name: str, default: Optional[float], bounds: Tuple[float, float],
             positive: bool = False, open_hi: bool = False) -> Any:
    """An angle in degrees within *bounds* (declared on the accessor); returned in degrees.

    ``positive`` excludes the lower bound 0 (a step, a span); ``open_hi`` the upper one."""
    lo, hi = bounds
    want = f"degrees in {'(' if positive else '['}{lo:g}, {hi:g}{')' if open_hi else ']'}"
    value = sec.number(name, default, lo=lo, hi=hi, positive=positive, expected=want)
    if open_hi and value == hi:
        raise sec.error(name, want, repr(value))
    return value


def _pressure_angle(sec: Section, name: str = "alpha_deg", default: float = 20.0) -> float:
    """A pressure angle in degrees, within PRESSURE_ANGLE_DEG; returned in radians."""
    return math.radians(_degrees(sec, name, default, PRESSURE_ANGLE_DEG, open_hi=True))


def _coefficient(sec: Section, name: str, default: float) -> float:
    """A tooth-system coefficient (ha*, c*) within COEFFICIENT."""
    return sec.number(name, default, lo=COEFFICIENT[0], hi=COEFFICIENT[1])


def _module(sec: Section, name: str = "m") -> float:
    return sec.length(name)   # positive, converted to metres


def _one_or_many(sec: Section, name: str) -> List[float]:
    """A number or an array of numbers; returns a list (empty if absent)."""
    raw = sec.raw(name, None)
    if raw is None:
        return []
    if isinstance(raw, list):
        return sec.numbers(name, positive=True)
    return [sec.number(name, positive=True)]


def _lengths(sec: Section, name: str) -> List[float]:
    """A length or an array of lengths in the spec's unit, returned in metres (empty if
    absent); each within the lengths mechcli accepts (``reader.MIN_LENGTH`` …
    ``MAX_LENGTH``, as :meth:`Section.length`)."""
    values = _one_or_many(sec, name)
    for key, v in zip(_item_keys(sec, name, len(values)), values):
        if not MIN_LENGTH <= v * sec.unit <= MAX_LENGTH:
            raise SpecError(sec.file, key, f"a length between {MIN_LENGTH:g} m and "
                            f"{MAX_LENGTH:g} m", f"{v:g} ({v * sec.unit:g} m)")
    return [v * sec.unit for v in values]


def _angles(sec: Section, name: str, bounds: Tuple[float, float]) -> List[float]:
    """An angle or an array of angles in degrees within *bounds*, in radians."""
    values = _one_or_many(sec, name)
    lo, hi = bounds
    for key, v in zip(_item_keys(sec, name, len(values)), values):
        if not lo <= v <= hi:
            raise SpecError(sec.file, key, f"degrees in [{lo:g}, {hi:g}]", repr(v))
    return [math.radians(v) for v in values]


@record
class ToothSystem:
    """Module (m), pressure angle (rad), addendum and clearance coefficients."""

    m: float
    alpha: float
    ha_star: float
    c_star: float


def _tooth_system(sec: Section, c_default: float = 0.25) -> ToothSystem:
    m = _module(sec)
    alpha = _pressure_angle(sec)
    ha = _coefficient(sec, "ha_star", 1.0)
    c = _coefficient(sec, "c_star", c_default)
    return ToothSystem(m, alpha, ha, c)


def _shift(sec: Section, name: str) -> float:
    return sec.number(name, 0.0, lo=-1.5, hi=1.5)


def _item_keys(sec: Section, name: str, n: int) -> Tuple[str, ...]:
    """Key paths of the n values of a number-or-array key (``a_w``; ``a_w[0]``, ``a_w[1]``)."""
    return tuple(sec.key(name if n == 1 else f"{name}[{i}]") for i in range(n))


def _inv(a: float) -> float:
    return math.tan(a) - a


def _measurement(sec: Section, z: int, mn: float, alpha_n: float, xn: float, beta: float = 0.0,
                 suffix: str = "") -> Tuple[Optional[int], Optional[float], float]:
    """``k``, ``pin_diameter`` and ``thickness_allowance`` (+ *suffix*) of one gear.

    Bounds: k in [1, z - 1] (a span over z teeth would close around the gear); the
    allowance below the normal arc thickness s_n = mn (pi/2 + 2 xn tan an) on the
    reference circle (a larger one takes the whole tooth away); the pin between the
    smallest that still rests on the flanks above the base circle
    (inv phi = s_t/d + inv at + dp/(z mn cos an) - pi/z > 0) and one circular pitch
    pi mn (a larger pin no longer sits in one space).
    """
    kk, pk, ek = (f"k{suffix}", f"pin_diameter{suffix}", f"thickness_allowance{suffix}")
    k = sec.integer(kk, None, lo=1, hi=10000)
    if k is not None and k > max(z - 1, 1):
        raise sec.error(kk, f"a number of teeth in [1, z - 1 = {max(z - 1, 1)}]", repr(k))
    s_n = mn * (math.pi / 2 + 2 * xn * math.tan(alpha_n))
    e = sec.length(ek, 0.0, positive=False, nonneg=True)
    if sec.has(ek) and e >= s_n:   # (a gear without a tooth is the core's to refuse)
        raise sec.error(ek, f"an allowance below the tooth thickness s = {s_n / sec.unit:.6g} "
                        "(larger takes the whole tooth)", f"{e / sec.unit:g}")
    dp = sec.length(pk, None)
    if dp is not None:
        at = math.atan(math.tan(alpha_n) / math.cos(beta))
        low = (math.pi / z - (s_n - e) / (z * mn) - _inv(at)) * z * mn * math.cos(alpha_n)
        if not max(low, 0.0) < dp <= math.pi * mn:
            raise sec.error(pk, f"a pin diameter in ({max(low, 0.0) / sec.unit:.6g}, "
                            f"{math.pi * mn / sec.unit:.6g}] (resting on the flanks above "
                            "the base circle, within one circular pitch)",
                            f"{dp / sec.unit:g}")
    return k, dp, e


#: input power [kW]: 1e6 kW (1 GW) is past the largest gear drive (ship and turbine
#: gearboxes reach about 1e5 kW); 1e-9 kW (1 microwatt) is below a watch's gear train
#: (a few microwatts)
POWER_KW = (1e-9, 1e6)
#: speed of the driving shaft [rpm]: 1e6 rpm is past any gear drive (turbochargers and
#: dental drills turn at about 3e5 rpm); 1e-6 rpm (one turn in two years) is below the
#: slowest drive shafts (a clock's hour wheel turns at 1/720 rpm).  Within both ranges
#: and the lengths mechcli accepts, T1 = P / omega and the tooth forces stay within
#: floating point (at most about 1e25 N, at least about 1e-17 N)
SPEED_RPM = (1e-6, 1e6)


@record
class Drive:
    """Power and speed on shaft 1 (gear 1, the pinion or the worm, drives)."""

    power: float              # W
    omega1: float             # rad/s
    power_kW: float | None = None   # as the spec gives them (the report shows these, not
    n1_rpm: float | None = None     # a round trip through W and rad/s)


def _drive(sec: Section) -> Optional[Drive]:
    """``power_kW`` and ``n1_rpm`` (both or neither): the :class:`Drive`, or None."""
    sec.declare("power_kW", "n1_rpm")
    power = sec.number("power_kW", None, lo=POWER_KW[0], hi=POWER_KW[1],
                       expected=f"a power in kW in [{POWER_KW[0]:g}, {POWER_KW[1]:g}]")
    n1 = sec.number("n1_rpm", None, lo=SPEED_RPM[0], hi=SPEED_RPM[1],
                    expected=f"a speed in rpm in [{SPEED_RPM[0]:g}, {SPEED_RPM[1]:g}]")
    if (power is None) != (n1 is None):
        missing = "n1_rpm" if power is not None else "power_kW"
        given = "power_kW" if power is not None else "n1_rpm"
        raise sec.error(missing, f"this key with {given} (the loads need power and speed)",
                        "nothing")
    if power is None:
        return None
    return Drive(power * 1e3, n1 * math.pi / 30, power, n1)


# -- the problem kinds ---------------------------------------------------------------
@record
class InvoluteProblem:
    """Involute curve of a base circle and the involute-function table (【例 5-1】)."""

    rb: float                 # m
    alpha_max: float          # rad
    curve_step: float         # rad
    table_from_deg: float
    table_to_deg: float
    table_step_deg: float
    columns: int
    digits: int


@record
class InverseInvoluteProblem:
    """alpha = inv^-1(theta) (【例 5-2】)."""

    theta: tuple
    method: str
    start: float
    epsilon: float
    max_iter: int
    dms_rounding: str
    dms_seconds_digits: int


@record
class SpurProblem:
    """One spur gear (【例 5-3】, 习题 5-1)."""

    z: int
    teeth: ToothSystem
    x: float
    points: int
    root: str
    radii: tuple              # extra radii for the thickness (m)
    forbid_undercut: bool
    forbid_pointed: bool
    k: int | None = None              # teeth in the span (None: ISO 21771's choice)
    pin_diameter: float | None = None  # m (None: touching on d + 2 x m)
    allowance: float = 0.0            # tooth-thickness allowance E (m)


@record
class PairProblem:
    """A pair of external spur gears (【例 5-4】, 习题 5-2 … 5-5)."""

    z1: int | None            # None: designed from the ratio
    z2: int | None
    ratio: float | None       # z1, z2 to find from ratio, a', m (the core does)
    teeth: ToothSystem
    x1: float
    x2: float
    a_w: tuple                # operating centre distances (m)
    alpha_w: tuple            # operating pressure angles (rad)
    require_continuous: bool
    forbid_interference: bool
    forbid_pointed: bool
    internal: bool            # gear 2 is a ring gear
    tip_shortening: bool      # shorten both tips by Δy m (shifted external pair)
    animate: bool             # pair.gif of the first mounting (external pairs)
    a_w_keys: tuple           # key path of each a_w value (the core refuses a mounting
    alpha_w_keys: tuple       # by index; the command names the key)
    ha_star1: float | None = None   # tip of each gear (None: the tooth system's ha*)
    ha_star2: float | None = None
    x_split: str | None = None      # design x1, x2 for a_w: "x1" (given), "sliding", "strength"
    k1: int | None = None
    k2: int | None = None
    pin_diameter1: float | None = None
    pin_diameter2: float | None = None
    allowance1: float = 0.0         # tooth-thickness allowances E1, E2 (m)
    allowance2: float = 0.0
    backlash: float | None = None   # wanted backlash (m): split into E1, E2 by the core
    backlash_share1: float = 0.5
    drive: Drive | None = None      # power and speed: tooth loads of the first mounting
    tip: str = "effective"          # "nominal": a pointed tooth's mesh ends on the tip circle

    @property
    def designed(self) -> bool:
        """z1, z2 are found from the ratio."""
        return self.ratio is not None


@record
class GenerationProblem:
    """Rack-cutter generation of a gear (``gear_cut``)."""

    z: int
    teeth: ToothSystem
    shifts: tuple
    step: float               # rad
    limit: float              # rad
    cutter_teeth: int
    animate: bool
    points: int


@record
class HelicalProblem:
    """A pair of helical gears (习题 5-6, 5-7)."""

    z1: int
    z2: int
    mn: float
    alpha_n: float
    han_star: float
    cn_star: float
    beta: float | None        # rad; None: from a_w
    a_w: float | None         # m
    b: float | None           # face width (m)
    xn1: float = 0.0
    xn2: float = 0.0
    k1: int | None = None
    k2: int | None = None
    pin_diameter1: float | None = None
    pin_diameter2: float | None = None
    allowance1: float = 0.0   # normal tooth-thickness allowances (m)
    allowance2: float = 0.0
    drive: Drive | None = None   # power and speed: tooth loads
    x_split: str | None = None   # design xn1, xn2 for a_w at beta: "x1", "sliding", "strength"


@record
class WormProblem:
    """A worm and worm wheel (习题 5-8)."""

    z1: int
    z2: int
    m: float | None
    d2: float | None
    q: float | None
    d1: float | None
    alpha: float
    ha_star: float
    c_star: float
    drive: Drive | None = None   # power and speed of the worm: loads and efficiency
    mu: float | None = None      # flank friction coefficient (None: no friction given)


@record
class BevelProblem:
    """A pair of straight bevel gears (习题 5-9)."""

    z1: int
    z2: int
    m: float
    alpha: float
    ha_star: float
    c_star: float
    sigma: float              # shaft angle (rad)
    drive: Drive | None = None   # power and speed of the pinion: tooth loads
    b: float | None = None       # face width (m): the loads act on the mean cone


@record
class GearSpec:
    header: Header
    kind: str
    problem: object
    expected: dict


# -- readers per kind -------------------------------------------------------------------
def _read_involute(sec: Section) -> InvoluteProblem:
    rb = sec.length("rb")
    amax = _degrees(sec, "alpha_max_deg", 40.0, INVOLUTE_DEG, positive=True)
    step = _degrees(sec, "curve_step_deg", 0.1, INVOLUTE_DEG, positive=True)
    t0 = _degrees(sec, "table_from_deg", 10.0, INVOLUTE_DEG)
    t1 = _degrees(sec, "table_to_deg", 30.0, INVOLUTE_DEG)
    ts = _degrees(sec, "table_step_deg", 0.1, INVOLUTE_DEG, positive=True)
    cols = sec.integer("columns", 10, lo=1, hi=20)
    if t1 < t0:
        raise sec.error("table_to_deg", f"a number >= table_from_deg = {t0:g}", repr(t1))
    if t1 + ts * (cols - 1) >= 90:
        # a row holds `columns` values table_step_deg apart: the step (or the column
        # count) is what takes the last row past 90 deg, not table_to_deg
        raise sec.error("table_step_deg", f"a step whose last row, table_to_deg + step x "
                        f"(columns - 1) = {t1:g} + {ts:g} x {cols - 1}, stays below 90 "
                        "degrees", repr(ts))
    if amax / step > MAX_POINTS:
        raise sec.error("curve_step_deg", f"a step giving at most {MAX_POINTS} curve points "
                        f"up to {amax:g} degrees", repr(step))
    if (t1 - t0) / ts + cols > MAX_POINTS:
        raise sec.error("table_step_deg", f"a step giving at most {MAX_POINTS} table values",
                        repr(ts))
    digits = sec.integer("digits", 4, lo=1, hi=15)
    return InvoluteProblem(rb, math.radians(amax), math.radians(step), t0, t1, ts, cols, digits)


def _read_inverse(sec: Section) -> InverseInvoluteProblem:
    raw = sec.raw("theta")
    if isinstance(raw, list):
        theta = sec.numbers("theta")
    else:
        theta = [sec.number("theta")]
    for i, t in enumerate(theta):
        if t < 0:
            key = "theta" if not isinstance(raw, list) else f"theta[{i}]"
            raise SpecError(sec.file, sec.key(key), "a number >= 0", repr(t))
    method = sec.string("method", "auto", choices=["auto", "book"])
    # Newton's first step from alpha0 is (inv(alpha0) - theta) / tan^2(alpha0): below
    # 1e-3 rad, tan^2 < 1e-6 throws it out of (0, pi/2) for every theta > 2e-6 (and near
    # 1e-154 rad tan^2 underflows to 0); 1.57 rad is 0.04 deg short of pi/2, where tan -> inf
    start = sec.number("book_start", 0.8, lo=1e-3, hi=1.57,
                       expected="an angle in radians in [0.001, 1.57] (inside (0, pi/2))")
    # the stop |inv(alpha) - theta| < epsilon: at 1 or more it stops at the start
    eps = sec.number("book_epsilon", 1e-7, positive=True, hi=1.0)
    max_iter = sec.integer("max_iter", 100, lo=1)
    rounding = sec.string("dms_rounding", "truncate", choices=["truncate", "round"])
    sd = sec.integer("dms_seconds_digits", 0, lo=0, hi=6)
    return InverseInvoluteProblem(tuple(theta), method, start, eps, max_iter, rounding, sd)


def _read_spur(sec: Section) -> SpurProblem:
    z = _teeth(sec, "z")
    ts = _tooth_system(sec)
    x = _shift(sec, "x")
    points = sec.integer("points", 40, lo=2, hi=100000)
    root = sec.string("root", "generated", choices=["generated", "radial"])
    radii = tuple(_lengths(sec, "thickness_radii"))
    rb = ts.m * z * math.cos(ts.alpha) / 2
    for key, r in zip(_item_keys(sec, "thickness_radii", len(radii)), radii):
        if r < rb:
            raise SpecError(sec.file, key, f"radii >= rb = {rb / sec.unit:.6g} "
                            "(no involute inside the base circle)", f"{r / sec.unit:g}")
    fu = sec.boolean("forbid_undercut", False)
    fp = sec.boolean("forbid_pointed", False)
    k, dp, e = _measurement(sec, z, ts.m, ts.alpha, x)
    return SpurProblem(z, ts, x, points, root, radii, fu, fp, k, dp, e)


def _read_pair(sec: Section) -> PairProblem:
    ts = _tooth_system(sec)
    a_w = tuple(_lengths(sec, "a_w"))
    alpha_w = _angles(sec, "alpha_w_deg", WORKING_ANGLE_DEG)
    internal = sec.boolean("internal", False)
    designed = sec.has("ratio")
    if designed and internal:
        raise sec.error("ratio", "z1 and z2 for an internal pair (design from the ratio is for "
                        "external pairs)", "ratio with internal = true")
    if designed:
        if sec.has("z1") or sec.has("z2"):
            raise sec.error("ratio", "either ratio (design) or z1 and z2, not both",
                            "both")
        ratio = sec.number("ratio", positive=True)
        if len(a_w) != 1:
            raise sec.error("a_w", "one centre distance to design the teeth from",
                            f"{len(a_w)} values")
        z1 = z2 = None   # the core designs them (MeshError: exit 3)
    else:
        ratio = None
        z1, z2 = _tooth_numbers(sec)
        if internal and z2 <= z1:
            raise sec.error("z2", f"more teeth than the pinion (z1 = {z1}) for a ring gear",
                            repr(z2))
    x_split = sec.string("x_split", None, choices=["x1", "sliding", "strength"])
    if x_split is not None:
        if internal or designed or len(a_w) != 1 or alpha_w:
            raise sec.error("x_split", "an external pair of given z1, z2 with one a_w (the "
                            "shifts are designed for that centre distance)",
                            "internal = true" if internal else "ratio" if designed
                            else f"{len(a_w)} a_w and {len(alpha_w)} alpha_w_deg")
        for key in ("x2",) + (("x1",) if x_split != "x1" else ()):
            if sec.has(key):
                raise sec.error(key, f"no {key}: x_split = \"{x_split}\" designs it",
                                repr(sec.raw(key)))
    x1, x2 = _shift(sec, "x1"), _shift(sec, "x2")
    ha1 = sec.number("ha_star1", None, lo=COEFFICIENT[0], hi=COEFFICIENT[1])
    ha2 = sec.number("ha_star2", None, lo=COEFFICIENT[0], hi=COEFFICIENT[1])
    meas: List[Tuple[Optional[int], Optional[float], float]] = []
    for i, (z, x) in enumerate(((z1, x1), (z2, x2)), start=1):
        if z is None or (i == 2 and internal) or (x_split and (i == 2 or x_split != "x1")):
            # designed teeth or shifts (the core measures them with their defaults), or a ring
            for key in (f"k{i}", f"pin_diameter{i}", f"thickness_allowance{i}"):
                if sec.has(key):
                    raise sec.error(key, "no measurement key for a gear whose teeth or shift "
                                    "are designed, or for a ring gear", repr(sec.raw(key)))
            meas.append((None, None, 0.0))
        else:
            meas.append(_measurement(sec, z, ts.m, ts.alpha, x, suffix=str(i)))
    backlash = sec.length("backlash", None)
    share = sec.number("backlash_share1", 0.5, lo=0.0, hi=1.0)   # a share of the total
    if backlash is not None:
        if meas[0][2] or meas[1][2]:
            raise sec.error("backlash", "backlash or thickness_allowance1/2, not both", "both")
        if len(a_w) + len(alpha_w) > 1:
            raise sec.error("backlash", "a pair with one mounting (the allowances are "
                            "sized for it)", "several mountings")
    rc = sec.boolean("require_continuous", False)
    fi = sec.boolean("forbid_interference", False)
    fp = sec.boolean("forbid_pointed", False)
    ts_short = sec.boolean("tip_shortening", False)
    animate = sec.boolean("animate", False)
    if ts_short and (internal or len(a_w) + len(alpha_w) > 1):
        raise sec.error("tip_shortening", "an external pair with one mounting",
                        "internal = true" if internal else "several mountings")
    # where a pointed tooth's contact ends: where its flanks meet ("effective"), or on the
    # nominal tip circle as some books take it ("nominal")
    tip = sec.string("tip", "effective", choices=["effective", "nominal"])
    drive = _drive(sec)
    if drive is not None and len(a_w) + len(alpha_w) > 1:
        raise sec.error("power_kW", "a pair with one mounting (the loads are of that mesh)",
                        "several mountings")
    # a' jamming the teeth is refused by the core, named by these keys (exit 2)
    return PairProblem(z1, z2, ratio, ts, x1, x2, a_w, tuple(alpha_w), rc, fi, fp, internal,
                       ts_short, animate, _item_keys(sec, "a_w", len(a_w)),
                       _item_keys(sec, "alpha_w_deg", len(alpha_w)), ha1, ha2, x_split,
                       meas[0][0], meas[1][0], meas[0][1], meas[1][1], meas[0][2], meas[1][2],
                       backlash, share, drive, tip)


def _read_generation(sec: Section) -> GenerationProblem:
    z = _teeth(sec, "z")
    ts = _tooth_system(sec)
    raw = sec.raw("x", None)
    if isinstance(raw, list):
        shifts = sec.numbers("x")
        for i, v in enumerate(shifts):
            if not -1.5 <= v <= 1.5:
                raise SpecError(sec.file, sec.key(f"x[{i}]"), "a number in [-1.5, 1.5]",
                                repr(v))
    else:
        shifts = [_shift(sec, "x")]
    # the cutter rolls +-limit/2 of the gear's turn: one full turn shows every tooth
    limit = _degrees(sec, "limit_deg", 126.0, (0.0, 360.0), positive=True)
    step = _degrees(sec, "step_deg", 6.0, (0.0, 360.0), positive=True)
    teeth = sec.integer("cutter_teeth", 5, lo=1, hi=50)
    animate = sec.boolean("animate", False)
    points = sec.integer("points", 60, lo=2, hi=100000)
    if limit / step > 5000:
        raise sec.error("step_deg", f"a step giving at most 5000 positions up to {limit:g}",
                        repr(step))
    return GenerationProblem(z, ts, tuple(shifts), math.radians(step), math.radians(limit),
                             teeth, animate, points)


def _read_helical(sec: Section) -> HelicalProblem:
    z1, z2 = _tooth_numbers(sec)
    mn = sec.length("mn")
    an = _pressure_angle(sec, "alpha_n_deg")
    han = _coefficient(sec, "han_star", 1.0)
    cn = _coefficient(sec, "cn_star", 0.25)
    # helix angle: helical gears use 8 - 45 deg (above 45 the axial thrust exceeds the
    # tangential force); 0 is a spur pair
    beta = _degrees(sec, "beta_deg", None, (0.0, 45.0), positive=True)
    a_w = sec.length("a_w", None)
    b = sec.length("b", None)
    x_split = sec.string("x_split", None, choices=["x1", "sliding", "strength"])
    if x_split is None:
        _exactly_one(sec, "beta_deg", "a_w", beta, a_w)
        if a_w is not None and a_w < mn * (z1 + z2) / 2 * (1 - 1e-12):
            raise sec.error("a_w", f"a centre distance >= mn (z1 + z2) / 2 = "
                            f"{mn * (z1 + z2) / 2 / sec.unit:g} (beta = 0)",
                            f"{a_w / sec.unit:g}")
    else:
        for key, value in (("beta_deg", beta), ("a_w", a_w)):
            if value is None:
                raise sec.error(key, "this key with x_split (the normal shifts are designed "
                                "for the centre distance a_w at the helix angle beta_deg)",
                                "nothing")
        at = math.atan(math.tan(an) / math.cos(math.radians(beta)))
        base = mn * (z1 + z2) / (2 * math.cos(math.radians(beta))) * math.cos(at)
        if a_w <= base * (1 + 1e-12):
            raise sec.error("a_w", f"a centre distance above rb1 + rb2 = {base / sec.unit:.6g} "
                            "(no profile-shift sum gives a smaller one)", f"{a_w / sec.unit:g}")
        for key in ("xn2",) + (("xn1",) if x_split != "x1" else ()):
            if sec.has(key):
                raise sec.error(key, f"no {key}: x_split = \"{x_split}\" designs it",
                                repr(sec.raw(key)))
    xn1, xn2 = _shift(sec, "xn1"), _shift(sec, "xn2")
    if a_w is not None and x_split is None and (xn1 or xn2):
        raise sec.error("xn1" if xn1 else "xn2", "no shift when the helix angle is found from "
                        "a_w (cos beta = mn (z1 + z2) / (2 a'), unshifted gears)",
                        repr(xn1 or xn2))
    if xn1 + xn2 < 0:
        at = math.atan(math.tan(an) / math.cos(math.radians(beta)))
        if 2 * math.tan(an) * (xn1 + xn2) / (z1 + z2) + _inv(at) <= 0:
            raise sec.error("xn2", "shifts whose sum leaves a zero-backlash mesh "
                            "(inv a_wt = 2 tan an (xn1 + xn2)/(z1 + z2) + inv at > 0)",
                            f"xn1 + xn2 = {xn1 + xn2:g}")
    beta_rad = None if beta is None else math.radians(beta)
    meas: List[Tuple[Optional[int], Optional[float], float]] = []
    for i, (z, x) in enumerate(((z1, xn1), (z2, xn2)), start=1):
        if x_split and (i == 2 or x_split != "x1"):   # a designed shift: default measures
            for key in (f"k{i}", f"pin_diameter{i}", f"thickness_allowance{i}"):
                if sec.has(key):
                    raise sec.error(key, "no measurement key for a gear whose shift is "
                                    "designed (x_split)", repr(sec.raw(key)))
            meas.append((None, None, 0.0))
            continue
        if beta_rad is None:   # beta from a': measured with the defaults only
            beta_rad_i = math.acos(mn * (z1 + z2) / (2 * a_w))
        else:
            beta_rad_i = beta_rad
        meas.append(_measurement(sec, z, mn, an, x, beta_rad_i, suffix=str(i)))
    drive = _drive(sec)
    return HelicalProblem(z1, z2, mn, an, han, cn, beta_rad, a_w, b, xn1, xn2,
                          meas[0][0], meas[1][0], meas[0][1], meas[1][1], meas[0][2],
                          meas[1][2], drive, x_split)


#: q = d1 / m, the worm's diameter in modules: standards tabulate 7.1 - 22.4 (GB/T 10088);
#: [1, 100] keeps d1 = q m within a hundred modules (given as q, or as d1)
WORM_Q = (1.0, 100.0)


def _read_worm(sec: Section) -> WormProblem:
    z1, z2 = _tooth_numbers(sec)
    m = sec.length("m", None)
    d2 = sec.length("d2", None)
    q = sec.number("q", None, lo=WORM_Q[0], hi=WORM_Q[1])
    d1 = sec.length("d1", None)
    _exactly_one(sec, "m", "d2", m, d2)   # after every alternative is read (not a stray)
    _exactly_one(sec, "q", "d1", q, d1, ": the worm diameter is not implied")
    if d1 is not None:   # the same limit on q = d1 / m
        mm = d2 / z2 if m is None else m
        if not WORM_Q[0] * (1 - 1e-12) <= d1 / mm <= WORM_Q[1] * (1 + 1e-12):
            raise sec.error("d1", f"a worm diameter d1 = q m with q in [{WORM_Q[0]:g}, "
                            f"{WORM_Q[1]:g}]: d1 in [{WORM_Q[0] * mm / sec.unit:.6g}, "
                            f"{WORM_Q[1] * mm / sec.unit:.6g}]",
                            f"{d1 / sec.unit:g} (q = {d1 / mm:.6g})")
    alpha = _pressure_angle(sec)
    ha = _coefficient(sec, "ha_star", 1.0)
    c = _coefficient(sec, "c_star", 0.2)
    drive = _drive(sec)
    mu = _worm_friction(sec, z1, z2, m, d2, q, d1, alpha, drive)
    return WormProblem(z1, z2, m, d2, q, d1, alpha, ha, c, drive, mu)


#: flank friction of a worm drive: the friction angle phi in [0, 45] deg, or mu in [0, 1]
#: (worm drives run at 0.01 - 0.15) whose friction angle arctan(mu / cos an) is also at most
#: 45 deg, mu <= cos an (checked once the normal pressure angle an is known): both keys
#: admit the same frictions
WORM_MU = (0.0, 1.0)
WORM_FRICTION_DEG = (0.0, 45.0)


def _worm_friction(sec: Section, z1: int, z2: int, m: Optional[float], d2: Optional[float],
                   q: Optional[float], d1: Optional[float], alpha: float,
                   drive: Optional[Drive]) -> Optional[float]:
    """``mu`` or ``friction_angle_deg`` (at most one; one is required with power_kW):
    the friction coefficient, or None.

    The friction angle phi is the one of the efficiency tan g / tan(g + phi):
    tan phi = mu / cos an, an the normal pressure angle (tan an = tan a cos g).
    The worm drives only while g + phi < 90 deg: a larger friction is refused here,
    naming the key that gives it.
    """
    mu = sec.number("mu", None, lo=WORM_MU[0], hi=WORM_MU[1])
    phi_deg = sec.number("friction_angle_deg", None, lo=WORM_FRICTION_DEG[0],
                         hi=WORM_FRICTION_DEG[1])
    if mu is not None and phi_deg is not None:
        raise sec.error("friction_angle_deg", "mu or friction_angle_deg (at most one)",
                        "both")
    key = "mu" if mu is not None else "friction_angle_deg"
    if mu is None and phi_deg is None:
        if drive is not None:
            raise sec.error("mu", "the flank friction (mu or friction_angle_deg) with "
                            "power_kW: the loads of a worm drive depend on it", "nothing")
        return None
    # (_exactly_one in _read_worm: d2 is given without m, d1 without q)
    m = d2 / z2 if m is None else m   # type: ignore[operator]
    q = d1 / m if q is None else q    # type: ignore[operator]
    gamma = math.atan(z1 / q)
    alpha_n = math.atan(math.tan(alpha) * math.cos(gamma))
    if mu is None:
        mu = math.tan(math.radians(phi_deg)) * math.cos(alpha_n)
    elif mu > math.cos(alpha_n) * (1 + 1e-12):   # the friction angle's 45 deg
        raise sec.error("mu", f"a friction coefficient in [0, cos an = {math.cos(alpha_n):.6g}] "
                        f"(a friction angle arctan(mu / cos an) of at most "
                        f"{WORM_FRICTION_DEG[1]:g} deg, as friction_angle_deg)",
                        f"{mu:g} (friction angle "
                        f"{math.degrees(math.atan(mu / math.cos(alpha_n))):.4g} deg)")
    phi = math.atan(mu / math.cos(alpha_n))
    if gamma + phi >= math.pi / 2 * (1 - 1e-12):
        got = sec.raw(key)
        raise sec.error(key, f"a friction angle below 90 deg - lead angle "
                        f"{math.degrees(gamma):.4g} deg = {90 - math.degrees(gamma):.4g} deg "
                        "(at more the worm cannot drive: efficiency <= 0)",
                        f"{got:g} (friction angle {math.degrees(phi):.4g} deg)")
    return mu


def _read_bevel(sec: Section) -> BevelProblem:
    z1, z2 = _tooth_numbers(sec)
    m = _module(sec)
    alpha = _pressure_angle(sec)
    ha = _coefficient(sec, "ha_star", 1.0)
    c = _coefficient(sec, "c_star", 0.2)
    # shaft angle: within 1 deg of 0 or 180 the cone distance R = r / sin(delta) exceeds 57
    # pitch radii (a spur or an internal pair, not a bevel pair)
    sigma = _degrees(sec, "sigma_deg", 90.0, (1.0, 179.0))
    drive = _drive(sec)
    # face width: places the mean cone dm = d (1 - 0.5 b/R) (where the loads act); b > R/3
    # is warned by the report, b >= R has no mean cone
    b = sec.length("b", None)
    if drive is not None and b is None:
        raise sec.error("b", "the face width with power_kW (the loads act on the mean cone, "
                        "d (1 - 0.5 b/R))", "nothing")
    if b is not None:
        s_ = math.radians(sigma)
        cone = m * z1 / (2 * math.sin(math.atan2(math.sin(s_), z2 / z1 + math.cos(s_))))
        if b >= cone:
            raise sec.error("b", f"a face width below the cone distance R = "
                            f"{cone / sec.unit:.12g} (b <= R/3 = {cone / 3 / sec.unit:.6g} "
                            "by the usual design rule)", f"{b / sec.unit:.12g}")
    return BevelProblem(z1, z2, m, alpha, ha, c, math.radians(sigma), drive, b)


READERS = {"involute": _read_involute, "inverse_involute": _read_inverse, "spur": _read_spur,
           "pair": _read_pair, "generation": _read_generation, "helical": _read_helical,
           "worm": _read_worm, "bevel": _read_bevel}


def read_gear_spec(path: Union[str, os.PathLike], overrides: Iterable[str] = ()) -> GearSpec:
    """Read and validate a gear problem file.

    Returns
    -------
    GearSpec

    Raises
    ------
    SpecError
        Unknown or missing keys, wrong types, values out of range, no or
        several problem tables.
    """
    root = load_spec(path, overrides)
    header = read_header(root, "gear")
    present = [k for k in KINDS if root.has(k)]
    if len(present) != 1:
        want = "exactly one problem table: " + ", ".join(f"[{k}]" for k in KINDS)
        if present:
            got = " and ".join(f"[{k}]" for k in present)
        else:
            extra = [k for k in root.keys() if isinstance(root.data[k], dict)
                     and k != "expected"]
            hint = closest(extra[0], KINDS) if extra else None
            raise SpecError(root.file, extra[0] if extra else "", want,
                            f"[{extra[0]}]" if extra else "none", hint)
        raise SpecError(root.file, "", want, got)
    kind = present[0]
    sec = root.table(kind)
    problem = READERS[kind](sec)
    sec.finish()
    expected = read_expected(root)
    root.finish()
    return GearSpec(header, kind, problem, expected)
