"""One cam problem end to end: size (if asked), sample the profile, check it.

This is what ``mechcli cam`` calls; it only combines
:mod:`mechcli.core.cam.motion`, :mod:`mechcli.core.cam.geometry`,
:mod:`mechcli.core.cam.checks` and :mod:`mechcli.core.cam.sizing`.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional, Sequence

import numpy as np

from mechcli.core.cam.checks import CamChecks, check_cam
from mechcli.core.cam.geometry import (
    CamGeometryError,
    CamProfile,
    Follower,
    UndercutError,
    cam_profile,
)
from mechcli.core.cam.motion import Impact, MotionProgram, build_program, jump_samples
from mechcli.core.cam.sizing import (
    size_flat_base_radius,
    size_oscillating_base_radius,
    translating_base_radius_min,
)
from mechcli.core.records import record

#: coarse search step of the refined extrema, rad
SEARCH_STEP = math.radians(1.0)


@record
class CamSizing:
    """Sizing results (m).

    Attributes
    ----------
    r0_min : float or None
        Smallest base radius meeting the limits (pressure angle for knife and
        roller followers on the spec's offset side, convexity for the flat face).
    r0_min_other_side : float or None
        Same with the translating follower's offset on the other side.
    best_side : int or None
        +1 (right) or −1 (left): the offset side with the smaller r0_min.
    """

    r0_min: float | None = None
    r0_min_other_side: float | None = None
    best_side: int | None = None


@record
class CamDesign:
    """A designed and checked cam.

    Attributes
    ----------
    follower : Follower
        With the base radius actually used (the sized one if r0 was not given).
    program : MotionProgram
    profile : CamProfile
        Sampled at the requested step, with two samples (left, then right limit)
        at every jump of the motion.
    checks : CamChecks
    impacts : tuple of Impact
    sizing : CamSizing or None
    rr_max : float or None
        Largest roller radius without undercut (= smallest convex radius of
        curvature of the pitch curve; 0 when the pitch curve has a convex
        corner), m; None for a flat face.
    """

    follower: Follower
    program: MotionProgram
    profile: CamProfile
    checks: CamChecks
    impacts: tuple
    sizing: CamSizing | None
    rr_max: float | None


def _round_up(value: float, to: float) -> float:
    if to <= 0:
        return value
    return max(math.ceil(value / to * (1 - 1e-12)), 1) * to


def design_cam(motion: str, contact: str, r0: Optional[float], follower_args: Dict[str, Any],
               segments: Sequence[Any], stroke: float, *, angular: bool = False,
               step: float = math.radians(0.1), alpha_rise: float = math.radians(30),
               alpha_return: float = math.radians(70), size_base_radius: bool = False,
               limit_return: bool = False, rho_min: float = 0.0, round_up: float = 0.0,
               forbid_undercut: bool = False) -> CamDesign:
    """Size (optionally), sample and check a disc cam.

    Parameters
    ----------
    motion, contact : str
        Follower kind (see :class:`Follower`).
    r0 : float or None
        Base radius, m; None to use the sized one (needs ``size_base_radius``).
    follower_args : dict
        Other :class:`Follower` fields (SI).
    segments : sequence
        ``(kind, span_rad, law, lift)`` as for :func:`build_program`.
    stroke : float
        Lift h (m) or swing ψ (rad).
    angular : bool
        Oscillating follower.
    step : float
        Profile sampling step, rad.
    alpha_rise, alpha_return : float
        Allowed pressure angles, rad (used for sizing).
    size_base_radius : bool
        Compute the smallest base radius.
    limit_return : bool
        Sizing also keeps the return within ``alpha_return``.
    rho_min : float
        Flat face: smallest allowed working-curve radius of curvature, m.
    round_up : float
        Round a sized r0 that is used for the design up to a multiple of this, m.
    forbid_undercut : bool
        Raise :class:`UndercutError` instead of reporting the undercut.

    Returns
    -------
    CamDesign

    Raises
    ------
    CamGeometryError
        ``reason`` (``values``, m and rad): ``rounded_base_radius`` (``r0``, ``lo``,
        ``hi``: the rounded r0 leaves |a − l| < r0 < a + l), ``unbounded_base_radius``
        (``floor``: the limits hold for any r0 above it), ``roller_too_large`` (``r0``,
        ``rr``), ``arm_past_centre_line`` (``angle`` = φ₀ + ψ ≥ π), and those of
        :func:`cam_profile`, :func:`check_cam` and the sizing functions.
    UndercutError
        With *forbid_undercut*: ``distorted`` (``at``: cam angles of the velocity jumps,
        ``contact``) or ``undercut`` (``at``, ``contact``, ``rr``, ``rho``: the pitch
        curve's smallest radius of curvature, None for a flat face).
    """
    program = build_program(segments, stroke, angular)
    # the extrema are refined on the exact functions: their coarse search step does not
    # depend on the sampling step (benchmarks/bench_cam.py shows the reported values do not
    # change with it)
    search = SEARCH_STEP
    sizing = None
    if size_base_radius:
        ar = alpha_return if limit_return else None
        sizing = _size(program, motion, contact, follower_args, alpha_rise, ar, rho_min,
                       search)
    if r0 is None:
        if sizing is None:
            raise ValueError("r0 is required unless the base radius is sized")
        r0 = _sized_r0(sizing, motion, contact, follower_args, round_up)
    fol = Follower(motion, contact, r0, **follower_args)
    if angular and fol.phi0 + stroke >= math.pi:
        raise CamGeometryError(
            f"the arm angle phi0 + psi = {fol.phi0 + stroke!r} reaches pi: the arm would pass "
            "the line through the pivot and the cam centre", "arm_past_centre_line",
            angle=fol.phi0 + stroke)
    n = max(int(round(2 * math.pi / step)), 36)
    # at a jump (segment end, the parabolic midpoint) two samples: the limits from the left
    # and from the right
    delta, left, grid = jump_samples(program, np.linspace(0.0, 2 * math.pi, n + 1))
    profile = cam_profile(fol, program, delta, left, grid)
    checks = check_cam(fol, program, search)
    if forbid_undercut:
        _refuse_undercut(checks, fol, contact)
    # a convex pitch corner (velocity jump) has ρ = 0: no roller reproduces it
    rr_max = None if contact == "flat" else (
        0.0 if any(convex for _, convex in checks.corners)
        # not flat: the pitch curve has a smallest radius of curvature
        else checks.rho_pitch_min.value)  # type: ignore[union-attr]
    impacts = tuple(i for i in program.impacts())
    return CamDesign(fol, program, profile, checks, impacts, sizing, rr_max)


def _size(program: MotionProgram, motion: str, contact: str, follower_args: Dict[str, Any],
          alpha_rise: float, ar: Optional[float], rho_min: float, search: float) -> CamSizing:
    """The smallest base radius meeting the limits (``ar``: the return's pressure angle
    limit, None for none), on both offset sides for a translating follower."""
    if contact == "flat":
        return CamSizing(r0_min=size_flat_base_radius(program, rho_min, search))
    if motion == "translating":
        e, rot = follower_args.get("e", 0.0), follower_args["rotation"]
        this = translating_base_radius_min(program, e, rot, alpha_rise, ar, search)
        if e == 0:
            return CamSizing(this, this, None)
        other = translating_base_radius_min(program, -e, rot, alpha_rise, ar, search)
        side = 1 if e > 0 else -1
        return CamSizing(this, other, side if this <= other else -side)
    probe = Follower(motion, contact, 0.5 * (abs(follower_args["a"] -
                                                 follower_args["l"]) +
                                             follower_args["a"] + follower_args["l"]),
                     **follower_args)
    return CamSizing(r0_min=size_oscillating_base_radius(
        probe, program, alpha_rise, ar, search))


def _sized_r0(sizing: CamSizing, motion: str, contact: str, follower_args: Dict[str, Any],
              round_up: float) -> float:
    """The sized base radius rounded up, checked against the arm, offset and roller."""
    if sizing.r0_min is None:
        raise ValueError("r0 is required unless the base radius is sized")
    r0 = _round_up(sizing.r0_min, round_up)
    if motion == "oscillating":
        a, l = follower_args["a"], follower_args["l"]
        if not abs(a - l) < r0 < a + l:
            raise CamGeometryError(
                f"the rounded base radius {r0!r} is outside ({abs(a - l)!r}, {a + l!r}) "
                "that the arm allows", "rounded_base_radius", r0=r0, lo=abs(a - l),
                hi=a + l)
    floor = abs(follower_args.get("e", 0.0)) if contact != "flat" else 0.0
    if r0 <= floor * (1 + 1e-12):
        raise CamGeometryError(
            "the limits do not bound the base radius from below (any base radius > "
            f"{floor!r} meets them)", "unbounded_base_radius", floor=floor)
    if contact == "roller" and follower_args["rr"] >= r0:
        raise CamGeometryError(
            f"the sized base radius {r0!r} is not larger than the roller radius "
            f"{follower_args['rr']!r}", "roller_too_large", r0=r0, rr=follower_args["rr"])
    return r0


def _refuse_undercut(checks: CamChecks, fol: Follower, contact: str) -> None:
    """Raise :class:`UndercutError` when the checks found a distortion or an undercut."""
    if checks.distorted:
        raise UndercutError(
            "the follower cannot reproduce the velocity jumps at delta = "
            f"{list(checks.distorted)!r}", "distorted", at=checks.distorted, contact=contact)
    if checks.undercut:
        at = checks.rho_work_min.delta
        # not flat: the pitch curve has a smallest radius of curvature
        rho = None if contact == "flat" else checks.rho_pitch_min.value  # type: ignore[union-attr]
        raise UndercutError(
            f"the working profile is undercut (cusp) near delta = {at!r}", "undercut",
            at=at, contact=contact, rr=fol.rr, rho=rho)


__all__ = ["CamChecks", "CamDesign", "CamProfile", "CamSizing", "Impact", "MotionProgram",
           "design_cam"]
