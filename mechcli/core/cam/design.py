"""One cam problem end to end: size (if asked), sample the profile, check it.

This is what ``mechcli cam`` calls; it only combines
:mod:`mechcli.core.cam.motion` and :mod:`mechcli.core.cam.profile`.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mechcli.core.cam.motion import Impact, MotionProgram, build_program
from mechcli.core.cam.profile import (CamChecks, CamGeometryError, CamProfile, Follower,
                                      UndercutError, cam_profile, check_cam,
                                      size_flat_base_radius, size_oscillating_base_radius,
                                      translating_base_radius_min)

#: coarse search step of the refined extrema, rad
SEARCH_STEP = math.radians(1.0)


@dataclasses.dataclass(frozen=True)
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


@dataclasses.dataclass(frozen=True)
class CamDesign:
    """A designed and checked cam.

    Attributes
    ----------
    follower : Follower
        With the base radius actually used (the sized one if r0 was not given).
    program : MotionProgram
    profile : CamProfile
        Sampled at the requested step.
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


def _round_up(value, to):
    if to <= 0:
        return value
    return max(math.ceil(value / to * (1 - 1e-12)), 1) * to


def design_cam(motion, contact, r0, follower_args, segments, stroke, *, angular=False,
               step=math.radians(0.1), alpha_rise=math.radians(30),
               alpha_return=math.radians(70), size_base_radius=False, limit_return=False,
               rho_min=0.0, round_up=0.0, forbid_undercut=False):
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
    """
    program = build_program(segments, stroke, angular)
    # the extrema are refined on the exact functions: their coarse search step does not
    # depend on the sampling step (benchmarks/bench_cam.py shows the reported values do not
    # change with it)
    search = SEARCH_STEP
    sizing = None
    if size_base_radius:
        ar = alpha_return if limit_return else None
        if contact == "flat":
            sizing = CamSizing(r0_min=size_flat_base_radius(program, rho_min, search))
        elif motion == "translating":
            e, rot = follower_args.get("e", 0.0), follower_args["rotation"]
            this = translating_base_radius_min(program, e, rot, alpha_rise, ar, search)
            if e == 0:
                sizing = CamSizing(this, this, None)
            else:
                other = translating_base_radius_min(program, -e, rot, alpha_rise, ar, search)
                side = 1 if e > 0 else -1
                sizing = CamSizing(this, other, side if this <= other else -side)
        else:
            probe = Follower(motion, contact, 0.5 * (abs(follower_args["a"] -
                                                         follower_args["l"]) +
                                                     follower_args["a"] + follower_args["l"]),
                             **follower_args)
            sizing = CamSizing(r0_min=size_oscillating_base_radius(
                probe, program, alpha_rise, ar, search))
    if r0 is None:
        if sizing is None:
            raise ValueError("r0 is required unless the base radius is sized")
        r0 = _round_up(sizing.r0_min, round_up)
        if motion == "oscillating":
            a, l = follower_args["a"], follower_args["l"]
            if not abs(a - l) < r0 < a + l:
                raise CamGeometryError(
                    f"the rounded base radius {r0 * 1e3:.6g} mm is outside |a - l| < r0 < a + l "
                    f"({abs(a - l) * 1e3:.6g} .. {(a + l) * 1e3:.6g} mm); use a smaller "
                    "round_up")
        floor = abs(follower_args.get("e", 0.0)) if contact != "flat" else 0.0
        if r0 <= floor * (1 + 1e-12):
            raise CamGeometryError(
                "the limits do not bound the base radius from below (any r0 > "
                f"{floor * 1e3:.6g} mm meets them); give r0, or round_up, or stricter limits")
        if contact == "roller" and follower_args["rr"] >= r0:
            raise CamGeometryError(
                f"the sized base radius {r0 * 1e3:.6g} mm is not larger than the roller "
                f"radius {follower_args['rr'] * 1e3:.6g} mm; give r0 or a smaller roller")
    fol = Follower(motion, contact, r0, **follower_args)
    if angular and fol.phi0 + stroke >= math.pi:
        raise CamGeometryError(
            f"phi0 + psi = {math.degrees(fol.phi0 + stroke):.6g} deg reaches 180 deg: "
            "the arm would pass the line through the pivot and the cam centre")
    n = max(int(round(2 * math.pi / step)), 36)
    delta = np.linspace(0.0, 2 * math.pi, n + 1)
    profile = cam_profile(fol, program, delta)
    checks = check_cam(fol, program, search)
    if checks.distorted and forbid_undercut:
        where = ", ".join(f"{math.degrees(d):.4g}" for d in checks.distorted)
        raise UndercutError(
            f"the follower cannot reproduce the velocity jump at {where} deg: "
            + ("the roller rolls round the cam's sharp edge at the convex corner of the "
               "pitch curve" if contact == "roller" else
               "the flat face would need a cusp (r0 + s + s'' has a negative impulse)")
            + "; use a law without velocity jumps")
    if checks.undercut and forbid_undercut:
        where = math.degrees(checks.rho_work_min.delta)
        raise UndercutError(
            f"the working profile is undercut (cusp) near {where:.4g} deg: "
            + ("r0 + s + s'' <= 0" if contact == "flat" else
               f"roller radius {fol.rr * 1e3:.6g} mm >= pitch-curve radius of curvature "
               f"{checks.rho_pitch_min.value * 1e3:.6g} mm"))
    # a convex pitch corner (velocity jump) has ρ = 0: no roller reproduces it
    rr_max = None if contact == "flat" else (
        0.0 if any(convex for _, convex in checks.corners) else checks.rho_pitch_min.value)
    impacts = tuple(i for i in program.impacts())
    return CamDesign(fol, program, profile, checks, impacts, sizing, rr_max)


__all__ = ["CamChecks", "CamDesign", "CamProfile", "CamSizing", "Impact", "MotionProgram",
           "design_cam"]
