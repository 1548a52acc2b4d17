"""Generating a spur gear with a rack cutter: cutter positions and the swept space
(the book's ``gear_cut``, eq. 5-18 … 5-21).

The gear stands still; the cutter translates by r*phi along its rolling line
and turns by phi about the gear centre.  Coordinates are in the gear's frame
with the gear centre at the origin and the cutter below it (its rolling line
tangent to the reference circle at (0, -r) for phi = 0).  Lengths in metres,
angles in radians.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Tuple

import numpy as np

from mechcli.core.gear.spur import SpurGear
from mechcli.core.records import record

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


def rack_outline(g: SpurGear, teeth: int = 5) -> Tuple[np.ndarray, np.ndarray]:
    """Outline of the rack cutter, *teeth* teeth centred on u = 0 (book: 5 teeth, 20 points).

    Returns
    -------
    u, depth : numpy.ndarray
        Position along the rolling line (m) and depth below the cutter's
        reference line towards the gear centre (m); tips at depth (ha*+c*) m.
    """
    hc = (g.ha_star + g.c_star) * g.m
    t = math.tan(g.alpha)
    tip = math.pi * g.m / 4 - hc * t      # half width of the rack tip
    root = math.pi * g.m / 4 + hc * t     # half width at the rack root line
    centres = (np.arange(teeth) - (teeth - 1) / 2) * g.p
    u = np.stack([centres - root, centres - tip, centres + tip, centres + root], axis=1)
    d = np.tile([-hc, hc, hc, -hc], (teeth, 1))
    return u.ravel(), d.ravel()


def cutter_positions(g: SpurGear, phi: ArrayLike, teeth: int = 5,
                     body: bool = False) -> Tuple[np.ndarray, np.ndarray]:
    """The cutter outline at gear turns *phi*, in the gear's frame (eq. 5-18 … 5-21).

    Parameters
    ----------
    g : SpurGear
    phi : array_like
        Rolling angles (rad).
    teeth : int
        Cutter teeth.
    body : bool
        Close the outline through the cutter body (two points 3 m behind its
        root line) so that it can be filled as a polygon.

    Returns
    -------
    x, y : numpy.ndarray, shape (len(phi), 4 * teeth [+ 2])
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))[:, None]
    u, d = rack_outline(g, teeth)
    if body:
        back = -(g.ha_star + g.c_star + 3) * g.m
        u = np.concatenate([u, [u[-1], u[0]]])
        d = np.concatenate([d, [back, back]])
    wx = u[None, :] + g.r * phi                  # translated by r phi (eq. 5-18)
    wy = -(g.r + g.x * g.m - d[None, :])
    c, s = np.cos(phi), np.sin(phi)              # then turned back by phi about O
    return c * wx + s * wy, -s * wx + c * wy


def swept_half_space(g: SpurGear, rho: ArrayLike, phi: ArrayLike) -> np.ndarray:
    """Half-angle of the space the cutter sweeps at radius rho, by brute force (rad).

    For every position phi, the circle of radius rho is intersected with the
    right flank and the tip of the central cutter tooth (closed-form
    line-circle intersections); the largest polar angle from the space centre
    over all positions is returned.  This is the numerical envelope that the
    analytic profile of :mod:`mechcli.core.gear.profile` is checked against.

    Parameters
    ----------
    rho : array_like
        Radii (m).
    phi : array_like
        Rolling angles sampled (rad); the error falls with their spacing squared.

    Returns
    -------
    numpy.ndarray
        eta(rho) (rad); -inf where no position reaches rho (not expected for
        rf <= rho <= ra).
    """
    rho = np.asarray(rho, dtype=float)[None, :]
    ph = np.asarray(phi, dtype=float)[:, None]
    hc = (g.ha_star + g.c_star) * g.m
    t = math.tan(g.alpha)
    big_a = math.pi * g.m / 4 + g.r * ph       # flank: x = A - h t, depth below O: B - h
    big_b = g.r + g.x * g.m
    qa = 1 + t * t
    qb = -2 * (big_a * t + big_b)
    qc = big_a ** 2 + big_b ** 2 - rho ** 2
    disc = qb * qb - 4 * qa * qc
    ok = disc >= 0
    root = np.sqrt(np.where(ok, disc, 0.0))
    best = np.full(np.broadcast_shapes(ph.shape, rho.shape), -np.inf)
    for sign in (-1.0, 1.0):
        h = (-qb + sign * root) / (2 * qa)
        valid = ok & (h >= -hc) & (h <= hc)
        x = big_a - h * t
        yd = big_b - h                              # distance below the centre
        beta = np.arctan2(x, yd) - ph
        best = np.maximum(best, np.where(valid, beta, -np.inf))
    # tip line at distance rf below the centre, |x - r phi| <= tip half width
    tip = math.pi * g.m / 4 - hc * t
    w = np.sqrt(np.maximum(rho ** 2 - g.rf ** 2, 0.0))
    for sign in (-1.0, 1.0):
        x = sign * w + 0 * ph
        valid = (rho >= g.rf) & (np.abs(x - g.r * ph) <= tip)
        beta = np.arctan2(x, g.rf) - ph
        best = np.maximum(best, np.where(valid, beta, -np.inf))
    return best.max(axis=0)


@record
class GenerationPlan:
    """Rolling angles of a generation simulation (the book: +-126 deg by 6 deg).

    Attributes
    ----------
    phi : numpy.ndarray
        Rolling angles in the order drawn (rad): 0 up to +limit, then 0 down to -limit.
    """

    phi: np.ndarray


def generation_plan(limit: float, step: float) -> GenerationPlan:
    """Rolling angles 0 .. +limit then 0 .. -limit by *step* (rad), as ``gear_cut``."""
    n = int(math.floor(limit / step + 1e-9))
    up = step * np.arange(n + 1)
    return GenerationPlan(np.concatenate([up, -up]))
