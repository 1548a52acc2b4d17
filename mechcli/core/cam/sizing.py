"""Base-circle sizing of a disc cam: the smallest base radius that keeps the
pressure angle within [α] (translating and oscillating followers) or the
flat-faced cam convex.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Optional, Tuple

import numpy as np

from mechcli.core.cam.checks import max_pressure_angle, maximize_on_pieces, phase_pieces
from mechcli.core.cam.geometry import CamGeometryError

if TYPE_CHECKING:
    from mechcli.core.cam.geometry import Follower
    from mechcli.core.cam.motion import MotionProgram


def _translating_s0_needed(program: MotionProgram, e: float, sigma: int, kind: str,
                           tan_allow: float, step: float) -> float:
    """Smallest s0 keeping |α| ≤ [α] on the *kind* segments (translating)."""
    pieces = phase_pieces(program, kind)
    if not pieces:
        return -math.inf

    best = -math.inf
    for sgn in (1.0, -1.0):
        def func(s: np.ndarray, s1: np.ndarray, s2: np.ndarray, s3: np.ndarray, sgn: float = sgn
                ) -> Tuple[np.ndarray, np.ndarray]:
            return sgn * (s1 - sigma * e) / tan_allow - s, sgn * s2 / tan_allow - s1
        best = max(best, maximize_on_pieces(program, pieces, func, step)[1])
    return best


def translating_base_radius_min(program: MotionProgram, e: float, rotation: int, alpha_rise: float,
                                alpha_return: Optional[float] = None,
                                step: float = math.radians(1.0)) -> float:
    """Smallest base radius of a translating knife/roller follower for [α].

    Parameters
    ----------
    program : MotionProgram
    e : float
        Signed offset, m (positive: guide right of the cam centre).
    rotation : int
        +1 counter-clockwise cam, −1 clockwise.
    alpha_rise : float
        Allowed pressure angle in the rise, rad.
    alpha_return : float, optional
        Allowed pressure angle in the return, rad (None: not limited).
    step : float
        Coarse search step, rad.

    Returns
    -------
    float
        ``r0_min``, m.

    Notes
    -----
    From eq. (7-14): ``tan α = |s' − σe|/(s0 + s) ≤ tan[α]`` gives
    ``s0 ≥ max(|s' − σe|/tan[α] − s)`` and ``r0 = sqrt(s0² + e²)`` (习题 4-2).
    """
    for limit in (alpha_rise, alpha_return):
        if limit is not None and not 0 < limit < math.pi / 2:
            raise ValueError(f"the allowed pressure angle must be in (0, pi/2), got "
                             f"{limit!r}")
    need = _translating_s0_needed(program, e, rotation, "rise", math.tan(alpha_rise), step)
    if alpha_return is not None:
        need = max(need, _translating_s0_needed(program, e, rotation, "return",
                                                math.tan(alpha_return), step))
    return math.hypot(max(need, 0.0), e)


def size_flat_base_radius(program: MotionProgram, rho_min: float = 0.0,
                          step: float = math.radians(1.0)) -> float:
    """Smallest base radius of a flat-faced cam with ρ = r0 + s + s'' ≥ ρ_min (m)."""
    allk = range(len(program.pieces()))
    hit = maximize_on_pieces(program, allk, lambda s, s1, s2, s3: (-(s + s2), -(s1 + s3)), step)
    return max(hit[1] + rho_min, 0.0)


def size_oscillating_base_radius(fol: Follower, program: MotionProgram, alpha_rise: float,
                                 alpha_return: Optional[float] = None,
                                 step: float = math.radians(1.0), rtol: float = 1e-12) -> float:
    """Smallest base radius of an oscillating follower for [α] (bisection on r0).

    Searches r0 in (|a − l|, a + l) for the smallest value whose pressure-angle
    maxima stay within the limits; raises :class:`CamGeometryError`
    (``reason = "no_base_radius"``, ``lo`` and ``hi`` the ends, m) if none.
    """
    lo_lim, hi_lim = abs(fol.a - fol.l), fol.a + fol.l
    psi = max(seg.s_start + max(seg.lift, 0) for seg in program.segments)

    def ok(r0: float) -> bool:
        f = dataclasses.replace(fol, r0=r0)
        if f.phi0 + psi >= math.pi:
            return False
        ar = max_pressure_angle(f, program, "rise", step)
        good = ar is None or ar.value <= alpha_rise
        if alpha_return is not None:
            at = max_pressure_angle(f, program, "return", step)
            good = good and (at is None or at.value <= alpha_return)
        return good

    grid = np.linspace(lo_lim, hi_lim, 202)[1:-1]
    first = next((i for i, r in enumerate(grid) if ok(float(r))), None)
    if first is None:
        raise CamGeometryError(f"no base radius in ({lo_lim!r}, {hi_lim!r}) meets the "
                               "pressure-angle limit", "no_base_radius", lo=lo_lim, hi=hi_lim)
    lo = lo_lim if first == 0 else float(grid[first - 1])
    hi = float(grid[first])
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi
