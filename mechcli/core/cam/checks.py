"""Checks of a disc cam over the whole cycle, refined on the exact functions.

Largest pressure angle in the rise and the return, smallest radius of
curvature of the pitch and working curves, undercut and the velocity jumps no
follower can reproduce (:func:`check_cam`), and the maximiser over the pieces
of a motion program they share with :mod:`mechcli.core.cam.sizing`
(:func:`maximize_on_pieces`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Callable, List, Optional, Tuple

import numpy as np

from mechcli.core.cam.geometry import (
    CamGeometryError,
    curvature_and_rate,
    pitch_corners,
    pressure_angle_and_rate,
)
from mechcli.core.numerics import maximize_piecewise
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.cam.geometry import Follower
    from mechcli.core.cam.motion import MotionProgram


def maximize_on_pieces(program: MotionProgram, pieces: Any, func: Callable[..., Any], step: float
                       ) -> Tuple[float, float]:
    """Maximum of a piecewise-smooth function of δ, refined to ~1e-13 rad.

    Parameters
    ----------
    program : MotionProgram
    pieces : sequence of int
        Indices into ``program.pieces()`` to search.
    func : callable
        ``func(s, s1, s2, s3) -> (g, dg/dδ)`` on arrays.
    step : float
        Coarse sampling step, rad (each piece gets at least 17 samples).

    Returns
    -------
    (float, float) or None
        ``(delta_at_max, g_max)``; None if *pieces* is empty.

    Notes
    -----
    :func:`mechcli.core.numerics.maximize_piecewise` on the follower state of
    each piece: the coarse maximum is bracketed between its grid neighbours and
    the root of dg/dδ refined; a maximum at a piece end (one-sided, e.g. a kink)
    is taken as is.  This replaces the golden-section search of 例 7-2 (whose
    tolerance is 1e-5 rad).
    """
    allp = program.pieces()
    # the callers pass pieces that exist, so a maximum (δ, value) is found
    return maximize_piecewise([(allp[k][1], allp[k][2], _on_piece(program, k, func))  # type: ignore[return-value]
                               for k in pieces], step)


def _on_piece(program: MotionProgram, k: int, func: Callable[..., Any]) -> Callable[..., Any]:
    def g(x: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        return func(*program.piece_state(k, x))
    return g


def phase_pieces(program: MotionProgram, kind: str) -> List[int]:
    """Indices into ``program.pieces()`` of the pieces in *kind* (``rise``/``return``) segments."""
    return [k for k, (i, *_rest) in enumerate(program.pieces())
            if program.segments[i].kind == kind]


@record
class Extremum:
    """A refined extreme value: where (cam angle, rad) and how much."""

    delta: float
    value: float


@record
class CamChecks:
    """Pressure angle, curvature and undercut checks over the cycle.

    Attributes
    ----------
    alpha_rise, alpha_return : Extremum or None
        Largest |α| in the rise (return) segments, rad (None if none).
    rho_pitch_min : Extremum or None
        Smallest radius of curvature of the convex pitch curve, m.
    rho_work_min : Extremum
        Smallest radius of curvature of the working curve (convex side), m;
        ≤ 0 means a cusp (undercut).
    undercut : bool
        Roller: r_r ≥ ρ_pitch,min; flat face: r0 + s + s'' ≤ 0 somewhere.
    corners : tuple of (float, bool)
        Cam angles (rad) where the pitch curve has a corner (velocity jump)
        and whether the corner is convex.
    face_width_min : float or None
        Flat face: 2 max |contact offset from the follower axis|, m.
    distorted : tuple of float
        Cam angles (rad) of velocity jumps the follower cannot reproduce: a
        roller at a convex pitch-curve corner (ρ = 0 < r_r: it rolls round the
        cam's sharp edge instead), a flat face where ds/dδ drops (r0 + s + s''
        has a negative impulse: a cusp).  Each makes ``undercut`` true.
    """

    alpha_rise: Extremum | None
    alpha_return: Extremum | None
    rho_pitch_min: Extremum | None
    rho_work_min: Extremum
    undercut: bool
    corners: tuple
    face_width_min: float | None
    distorted: tuple = ()


def _abs_alpha_func(fol: Follower, sign: float) -> Callable[..., Any]:
    def func(s: np.ndarray, s1: np.ndarray, s2: np.ndarray, s3: np.ndarray
            ) -> Tuple[np.ndarray, np.ndarray]:
        a, da = pressure_angle_and_rate(fol, s, s1, s2, s3)
        return sign * a, sign * da
    return func


def max_pressure_angle(fol: Follower, program: MotionProgram, kind: str,
                       step: float = math.radians(1.0)) -> Optional[Extremum]:
    """Largest |α| over the *kind* (``rise``/``return``) segments.

    Returns
    -------
    Extremum or None
        Cam angle (rad) and |α| (rad), refined to ~1e-13 rad of cam angle.
        Notes: 例 7-2 (r0 = 40, e = 0, h = 20, 90° cosine rise:
        22.2077° at 39.2315°).
    """
    pieces = phase_pieces(program, kind)
    if not pieces or fol.contact == "flat":
        return None if not pieces else Extremum(program.pieces()[pieces[0]][1], 0.0)
    hits = [maximize_on_pieces(program, pieces, _abs_alpha_func(fol, sgn), step)
            for sgn in (1.0, -1.0)]
    x, g = max(hits, key=lambda h: h[1])
    return Extremum(x, g)



def check_cam(fol: Follower, program: MotionProgram, step: float = math.radians(1.0)) -> CamChecks:
    """Pressure-angle maxima, curvature minima and undercut of a cam.

    Parameters
    ----------
    fol : Follower
    program : MotionProgram
    step : float
        Coarse search step, rad (the maxima are refined independently of it).

    Returns
    -------
    CamChecks

    Raises
    ------
    CamGeometryError
        ``reason = "no_convex_pitch"``: the pitch curve is nowhere convex.
    """
    a_rise = max_pressure_angle(fol, program, "rise", step)
    a_ret = max_pressure_angle(fol, program, "return", step)
    allk = range(len(program.pieces()))
    hit = maximize_on_pieces(
        program, allk, lambda *st: curvature_and_rate(fol, *st), step)
    x, kmax = hit
    face = None
    if fol.contact == "flat":
        rho_p = None
        rho_w = Extremum(x, -kmax)
        undercut = rho_w.value <= 0
        vals = []
        for sgn in (1.0, -1.0):
            h = maximize_on_pieces(program, allk,
                                   lambda s, s1, s2, s3, sgn=sgn:
                                   (sgn * (fol.sigma * s1 - fol.e),
                                    sgn * fol.sigma * s2), step)
            vals.append(h[1])
        face = 2 * max(vals)
    else:
        if kmax <= 0:
            raise CamGeometryError("the pitch curve has no convex part", "no_convex_pitch")
        rho_p = Extremum(x, 1.0 / kmax)
        rho_w = Extremum(x, rho_p.value - fol.rr)
        undercut = fol.contact == "roller" and rho_p.value <= fol.rr
    corners = pitch_corners(fol, program)
    if fol.contact == "roller":
        distorted = tuple(d for d, convex in corners if convex)
    elif fol.contact == "flat":
        distorted = tuple(i.delta for i in program.impacts() if i.kind == "rigid" and i.jump < 0)
    else:
        distorted = ()
    return CamChecks(a_rise, a_ret, rho_p, rho_w, bool(undercut or distorted), corners, face,
                     distorted)
