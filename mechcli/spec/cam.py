"""The ``mechcli cam`` problem file: follower, motion program, checks, sizing.

See ``docs/cam.md`` for every key, its unit and default.  Lengths are read in
the spec's ``units`` and converted to metres; angles are degrees in the file
and radians in the returned :class:`CamSpec`.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Iterable, Iterator, Optional, Tuple

from mechcli.core.cam.motion import PolynomialLaw
from mechcli.core.records import record
from mechcli.spec.common import read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.reader import Section

LAW_CHOICES = ("uniform", "parabolic", "cosine", "sine", "cubic", "poly345", "poly4567",
               "modified-trapezoid", "modified-sine", "polynomial", "constant-velocity",
               "linear", "constant-acceleration", "harmonic", "simple-harmonic", "cycloidal",
               "poly23", "2-3", "3-4-5", "4-5-6-7")

#: a polynomial law must start at s/h = 0 and reach s/h = 1 to this tolerance (1e-6 of the
#: segment's lift: 0.06 µm on a 60 mm stroke, below any machining tolerance, and above the
#: rounding of coefficients typed with 7 or more significant digits); within it the
#: coefficients are scaled to reach the lift exactly
POLY_TOL = 1e-6
#: at most 16 coefficients (degree 15): the polydyne and 4-5-6-7 families of the literature
#: stay below degree 12, and beyond 15 the monomial form loses more digits than POLY_TOL
MAX_POLY_TERMS = 16
#: |c_k| <= 1e6: a degree-15 law with a bounded acceleration has coefficients below ~1e5;
#: larger ones cancel to nothing in double precision (1e6 * 1e-16 = 1e-10 << POLY_TOL)
MAX_POLY_COEF = 1e6

#: default sampling step of the profile, degrees (see docs/cam.md and benchmarks/bench_cam.py)
DEFAULT_STEP_DEG = 0.1

#: memory budget of one ``mechcli cam`` run (any accepted spec), bytes
MEMORY_BUDGET = 2**30  # 1 GiB
#: the most profile points per revolution: the budget over the peak RSS a run grows by
#: per point (taken as ~1.2 kB, POINTS_WHY; ``cam_peak_rss_per_point`` of
#: benchmarks/bench_cam.py measures it), plots and animation included, rounded down;
#: i.e. a step of at least 0.0005 deg
MAX_POINTS = 720_000
#: shortest segment [deg]: the tolerance to which the segments must sum to 360 deg
MIN_SPAN_DEG = 1e-6
#: smallest allowed pressure angle [deg] (see the limits reader)
MIN_ALPHA_DEG = 0.01
MIN_STEP_DEG = 360.0 / MAX_POINTS
POINTS_WHY = "1 GiB budget at ~1.2 kB per point"


@record
class Limits:
    """Allowed pressure angles (rad) and the undercut policy."""

    alpha_rise: float
    alpha_return: float
    forbid_undercut: bool


@record
class Sizing:
    """What to size (``[sizing]``); lengths in m.

    Attributes
    ----------
    base_radius : bool
        Find the smallest base radius (pressure angle for knife/roller,
        convexity ρ ≥ rho_min for the flat face).
    limit_return : bool
        Also keep the return within ``alpha_return`` when sizing (default true).
    rho_min : float
        Flat face: smallest allowed radius of curvature of the working curve, m.
    round_up : float
        Round the sized base radius up to a multiple of this, m (0: no rounding).
    """

    base_radius: bool
    limit_return: bool
    rho_min: float
    round_up: float


@record
class CamSpec:
    """A validated cam problem (SI units, radians).

    ``follower_args`` are the keyword arguments of
    :class:`mechcli.core.cam.geometry.Follower` except ``r0`` when it is to be
    sized (``r0`` is None then).  ``segments`` are ``(kind, span, law, lift)``.
    """

    header: object
    motion: str
    contact: str
    r0: float | None
    follower_args: dict
    segments: tuple
    stroke: float
    angular: bool
    omega: float | None
    limits: Limits
    sizing: Sizing | None
    step: float
    table_step: float
    plot: bool
    animate: bool
    frames: int
    expected: dict


def _segments(motion_sec: Section, stroke: float, angular: bool, file: str) -> tuple:
    secs = motion_sec.tables("segments")
    if not secs:
        raise motion_sec.error("segments", "at least one segment", "an empty array")
    out = []
    total = 0.0
    level = 0.0
    unit_word = "deg" if angular else "length"
    for sec in secs:
        kind = sec.string("kind", choices=["rise", "dwell", "return"])
        # a dwell may last 0 deg (the book's 远休止角 0°, 习题 4-1/4-4): it is dropped
        # spans below the 1e-6 deg tolerance of the segment sum are indistinguishable from 0
        # (and underflow in radians): a rise or return must be longer, a dwell 0 or longer
        span = sec.number("angle", nonneg=True)
        if (kind != "dwell" or span != 0) and span < MIN_SPAN_DEG:
            raise sec.error("angle", f"an angle of at least {MIN_SPAN_DEG:g} deg"
                            + (" (or 0 for a dwell)" if kind == "dwell" else ""), f"{span:g}")
        if kind == "dwell":
            law, lift = None, 0.0
        else:
            law = sec.string("law", choices=list(LAW_CHOICES))
            if law == "polynomial":
                law = _polynomial(sec)
            if angular:
                lift = math.radians(sec.number("lift", math.degrees(stroke), positive=True,
                                               hi=180.0))   # at most psi
            else:
                lift = sec.length("lift") if sec.has("lift") else stroke
            new = level + (lift if kind == "rise" else -lift)
            tol = 1e-9 * stroke
            if new > stroke + tol:
                raise sec.error("lift", f"a rise ending at most at the stroke ({unit_word} "
                                f"{'psi' if angular else 'h'})", "one that goes beyond it")
            if new < -tol:
                raise sec.error("lift" if sec.has("lift") else "kind",
                                "a return no larger than the lift reached before it "
                                "(return lift = rise lift)",
                                f"a return of {_show(lift, angular, sec.unit)} from "
                                f"{_show(level, angular, sec.unit)}")
            # a lift within the tolerance of reaching 0 or the stroke reaches it exactly (the
            # core allows no excursion outside [0, stroke])
            if abs(new) <= tol and kind == "return":
                lift, new = level, 0.0
            elif abs(new - stroke) <= tol and kind == "rise":
                lift, new = stroke - level, stroke
            if isinstance(law, PolynomialLaw):
                _check_range(sec, law, kind, level, lift, stroke, angular)
            level = 0.0 if abs(new) <= tol else new
        sec.finish()
        total += span
        if span > 0:
            out.append((kind, math.radians(span), law, lift))
    if abs(total - 360.0) > 1e-6:
        raise SpecError(file, motion_sec.key("segments"), "segment angles summing to 360 deg",
                        f"{total:g} deg")
    if abs(level) > 1e-9 * stroke:
        raise SpecError(file, motion_sec.key("segments"),
                        "returns that bring the follower back (return lift = rise lift)",
                        f"the cycle ending {_show(level, angular, motion_sec.unit)} above "
                        "the start")
    if max(_levels(out)) < stroke * (1 - 1e-9):
        raise SpecError(file, motion_sec.key("segments"),
                        "rises that reach the stroke " + ("psi" if angular else "h"),
                        "a largest displacement below it")
    # within the 1e-6 deg accepted above, stretch the spans to exactly 360 deg (the core
    # checks the sum to 1e-9 rad)
    return tuple((kind, span * (2 * math.pi / sum(o[1] for o in out)), law, lift)
                 for kind, span, law, lift in out)


def _polynomial(sec: Section) -> PolynomialLaw:
    """The ``coefficients`` of a ``law = "polynomial"`` segment: s/h = Σ c_k u^k,
    u = δ/δ0, checked to start at 0 and reach 1 (within POLY_TOL, then exactly)."""
    key = "coefficients"
    c = sec.numbers(key)
    if not 2 <= len(c) <= MAX_POLY_TERMS:
        raise sec.error(key, f"2 to {MAX_POLY_TERMS} coefficients c0, c1, ... of "
                        "s/h = c0 + c1 u + c2 u^2 + ... (u = δ/δ0)", f"{len(c)}")
    for i, ck in enumerate(c):
        if abs(ck) > MAX_POLY_COEF:
            raise SpecError(sec.file, sec.key(f"{key}[{i}]"),
                            f"a coefficient within ±{MAX_POLY_COEF:g}", f"{ck:g}")
    if abs(c[0]) > POLY_TOL:
        raise sec.error(key, "a polynomial that starts at s/h = 0 at u = 0 (c0 = 0): the "
                        "segment starts where the one before it ends", f"c0 = {c[0]:g}")
    total = math.fsum(c)
    if abs(total - 1.0) > POLY_TOL:
        raise sec.error(key, "a polynomial that reaches the lift, s/h = c0 + c1 + ... = 1 at "
                        "u = 1", f"a sum of {total:.9g}")
    c[0] = 0.0
    total = math.fsum(c)
    return PolynomialLaw(tuple(ck / total for ck in c))


def _check_range(sec: Section, law: PolynomialLaw, kind: str, level: float, lift: float,
                 stroke: float, angular: bool) -> None:
    """The follower stays within [0, stroke] inside a polynomial segment."""
    fmin, umin, fmax, umax = law.extremes()
    sign = 1.0 if kind == "rise" else -1.0
    lo, ulo = (level + lift * fmin, umin) if sign > 0 else (level - lift * fmax, umax)
    hi, uhi = (level + lift * fmax, umax) if sign > 0 else (level - lift * fmin, umin)
    tol = POLY_TOL * stroke
    sym = "psi" if angular else "s"
    if lo < -tol:
        raise sec.error("coefficients", "a polynomial that keeps the follower within "
                        "[0, stroke] (s/h between 0 and 1)",
                        f"{sym} = {_show(lo, angular, sec.unit)} at u = {ulo:.6g}")
    if hi > stroke + tol:
        raise sec.error("coefficients", "a polynomial that keeps the follower within "
                        "[0, stroke] (s/h between 0 and 1)",
                        f"{sym} = {_show(hi, angular, sec.unit)} at u = {uhi:.6g}, beyond "
                        f"the stroke {_show(stroke, angular, sec.unit)}")


def _levels(segs: Iterable[tuple]) -> Iterator[float]:
    level = 0.0
    for kind, _, _, lift in segs:
        level += lift if kind == "rise" else (-lift if kind == "return" else 0.0)
        yield level


def _show(value: float, angular: bool, unit: float) -> str:
    return f"{math.degrees(value):g} deg" if angular else f"{value / unit:g}"


def read_cam_spec(root: Section, step_override: Optional[float] = None,
                  points_override: Optional[int] = None) -> CamSpec:
    """Validate a ``mechcli cam`` spec.

    Parameters
    ----------
    root : mechcli.spec.reader.Section
    step_override : float, optional
        ``--step`` (deg).
    points_override : int, optional
        ``--points`` (profile points per revolution).

    Returns
    -------
    CamSpec
    """
    header = read_header(root, "cam")
    motion, contact, angular, r0, args, sizing = _follower(root)
    rotation, omega = _cam_table(root)
    args["rotation"] = rotation
    stroke, segments = _motion_table(root, angular, r0, args)
    limits = _limits(root, angular)
    step = _sampling(root, step_override, points_override)
    table_step, plot, animate, frames = _output(root)
    expected = read_expected(root)
    root.finish()
    return CamSpec(header, motion, contact, r0, args, segments, stroke, angular, omega,
                   limits, sizing, math.radians(step), math.radians(table_step), plot,
                   animate, frames, expected)


def _follower(
        root: Section) -> Tuple[str, str, bool, Optional[float], Dict[str, Any], Optional[Sizing]]:
    """[follower] (and [sizing], which decides whether r0 is required): ``(motion,
    contact, angular, r0, args, sizing)``; ``args`` the profile's keyword arguments."""
    fol = root.table("follower")
    motion = fol.string("motion", "translating", choices=["translating", "oscillating"])
    arm = [k for k in ("a", "l") if k in fol.data]
    if arm and "motion" not in fol.data:
        # the default 'translating' would report a and l as unknown keys: name the key
        # that is missing as well as the keys it explains
        raise fol.error("motion", "'oscillating' for an arm of length l pivoted at a "
                        f"(the default 'translating' has no {' or '.join(arm)})", "nothing")
    contact = fol.string("contact", choices=["knife", "roller", "flat"])
    angular = motion == "oscillating"
    if angular and contact == "flat":
        raise fol.error("contact", "'knife' or 'roller' for an oscillating follower",
                        "'flat'")
    sz = root.table("sizing", None)
    sizing = None
    if sz is not None:
        sizing = Sizing(base_radius=sz.boolean("base_radius", True),
                        limit_return=sz.boolean("limit_return", True),
                        rho_min=sz.length("rho_min", 0.0, nonneg=True),
                        round_up=sz.length("round_up", 0.0, nonneg=True))
        sz.finish()
    sized = sizing is not None and sizing.base_radius
    r0 = fol.length("r0") if fol.has("r0") or not sized else None
    args = {}
    if contact == "roller":
        args["rr"] = fol.length("rr")
    if motion == "translating":
        e = fol.length("e", 0.0, nonneg=True)
        side = fol.string("side", "right", choices=["right", "left"])
        args["e"] = e if side == "right" else -e
        if r0 is not None and contact != "flat" and r0 <= e:
            raise fol.error("r0", f"a base radius larger than the offset e = {e / root.unit:g}",
                            f"{r0 / root.unit:g}")
    else:
        args["a"] = fol.length("a")
        args["l"] = fol.length("l")
        if fol.has("arm"):
            args["arm"] = 1 if fol.string("arm", choices=["left", "right"]) == "left" else -1
        a, l = args["a"], args["l"]
        if r0 is not None and not abs(a - l) < r0 < a + l:
            raise fol.error("r0", f"|a - l| < r0 < a + l (here {abs(a - l) / root.unit:g} "
                            f"< r0 < {(a + l) / root.unit:g}) so that a, l, r0 form the "
                            "oscillating follower (eq. 4-6)", f"{r0 / root.unit:g}")
    if contact == "roller" and r0 is not None and args["rr"] >= r0:
        raise fol.error("rr", f"a roller radius smaller than r0 = {r0 / root.unit:g}",
                        f"{args['rr'] / root.unit:g}")
    fol.finish()

    return motion, contact, angular, r0, args, sizing


def _cam_table(root: Section) -> Tuple[int, Optional[float]]:
    """[cam]: ``(rotation, omega)`` (+1 counter-clockwise; omega None if not given)."""
    cam = root.table("cam", None)
    rotation, omega = 1, None
    if cam is not None:
        rotation = 1 if cam.string("rotation", "ccw", choices=["ccw", "cw"]) == "ccw" else -1
        # [rad/s]: 1e6 rad/s is ten million rpm, past any machine (an ultracentrifuge turns
        # at 1.6e4 rad/s), and keeps omega^2 (the accelerations) finite; 1e-6 rad/s is a turn
        # in 72 days, below which omega^2 underflows next to the lengths
        omega = cam.number("omega", None, lo=1e-6, hi=1e6)
        cam.finish()

    return rotation, omega


def _motion_table(root: Section, angular: bool, r0: Optional[float],
                  args: Dict[str, Any]) -> Tuple[float, tuple]:
    """[motion]: ``(stroke, segments)``, the stroke in m or rad."""
    file = root.file
    mot = root.table("motion")
    if angular:
        psi = mot.number("psi", positive=True, hi=180.0)   # phi0 + psi < 180 deg (eq. 4-6)
        stroke = math.radians(psi)
        if r0 is not None:
            a, l = args["a"], args["l"]
            phi0 = math.acos((a * a + l * l - r0 * r0) / (2 * a * l))
            if phi0 + stroke >= math.pi:
                raise mot.error("psi", f"a swing below {180 - math.degrees(phi0):.6g} deg "
                                f"(phi0 = {math.degrees(phi0):.6g} deg; phi0 + psi < 180 deg)",
                                f"{psi:g}")
    else:
        stroke = mot.length("h")
    segments = _segments(mot, stroke, angular, file)
    mot.finish()

    return stroke, segments


def _limits(root: Section, angular: bool) -> Limits:
    """[limits]: the allowed pressure angles and the undercut rule."""
    lim = root.table("limits", None)
    a_rise_default = 45.0 if angular else 30.0
    if lim is not None:
        # [α] = 0 admits no cam (tan 0 would divide the sizing by zero), and the base circle
        # grows like 1/tan[α]: below 0.01 deg (r0 > ~5,700 times the largest ds/dφ) it is no
        # cam either, and at 1e-300 deg the sizing overflows (found by the fuzzer)
        want = f"an allowed pressure angle in [{MIN_ALPHA_DEG:g}, 89.999] deg"
        limits = Limits(math.radians(lim.number("alpha_rise", a_rise_default, lo=MIN_ALPHA_DEG,
                                                hi=89.999, expected=want)),
                        math.radians(lim.number("alpha_return", 70.0, lo=MIN_ALPHA_DEG,
                                                hi=89.999, expected=want)),
                        lim.boolean("forbid_undercut", False))
        lim.finish()
    else:
        limits = Limits(math.radians(a_rise_default), math.radians(70.0), False)

    return limits


def _sampling(root: Section, step_override: Optional[float],
              points_override: Optional[int]) -> float:
    """[sampling] and ``--step``/``--points``: the profile's step [deg]."""
    file = root.file
    samp = root.table("sampling", None)
    step = DEFAULT_STEP_DEG
    if samp is not None:
        if samp.has("step") and samp.has("points"):
            raise samp.error("points", "either step or points, not both", "both")
        if samp.has("step"):
            raw = samp.data["step"]
            if isinstance(raw, (int, float)) and not isinstance(raw, bool) \
                    and 0 < raw < MIN_STEP_DEG:
                raise samp.error("step", f"a step of at least {MIN_STEP_DEG:g} deg: at most "
                                 f"{MAX_POINTS:,} points per revolution ({POINTS_WHY})",
                                 f"{raw:g} ({360.0 / raw:,.0f} points)")
        step = samp.number("step", step, lo=MIN_STEP_DEG, hi=10.0)
        if samp.has("points"):
            raw = samp.data["points"]
            if isinstance(raw, int) and not isinstance(raw, bool) and raw > MAX_POINTS:
                raise samp.error("points", f"at most {MAX_POINTS:,} points per revolution "
                                 f"({POINTS_WHY})", f"{raw:,}")
            step = 360.0 / samp.integer("points", lo=36, hi=MAX_POINTS)
        samp.finish()
    if step_override is not None:
        step = float(step_override)
        if step < MIN_STEP_DEG:
            raise SpecError(file, "sampling.step", f"a step (--step) of at least "
                            f"{MIN_STEP_DEG:g} deg: at most {MAX_POINTS:,} points per "
                            f"revolution ({POINTS_WHY})", f"{step:g}")
    if points_override is not None:
        if int(points_override) > MAX_POINTS:
            raise SpecError(file, "sampling.points", f"at most {MAX_POINTS:,} points per "
                            f"revolution (--points; {POINTS_WHY})", f"{int(points_override):,}")
        step = 360.0 / int(points_override)

    return step


def _output(root: Section) -> Tuple[float, bool, bool, int]:
    """[output]: ``(table_step [deg], plots, animate, frames)``."""
    out = root.table("output", None)
    table_step, plot, animate, frames = 10.0, True, False, 72
    if out is not None:
        table_step = out.number("table_step", table_step, lo=0.01, hi=180.0)
        plot = out.boolean("plots", True)
        animate = out.boolean("animate", False)
        frames = out.integer("frames", frames, lo=4, hi=720)
        out.finish()
    return table_step, plot, animate, frames
