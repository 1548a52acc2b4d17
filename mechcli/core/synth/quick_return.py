"""Design from the time ratio K (chapter 3 §6, 图 3-15 … 3-19, 【例 3-8】; slides §2-3 一).

Every design starts from the limit-position angle (eq. 3-39)

    θ = 180° (K − 1)/(K + 1),

the crank angle between the two limit positions, where crank and coupler are
in line: extended (AC = l2 + l1) and folded (AC = l2 − l1).  The designs:

* :func:`crank_rocker_from_K` — rocker CD, swing ψ, K and one extra condition
  (A on a line, the crank l1, the coupler l2 or the frame l4): the four cases
  of 【例 3-8】 and 习题 3-14;
* :func:`crank_rocker_from_K_limit_angle` — rocker CD, frame AD, K and the
  angle ∠ADC of one limit position (习题 3-15; no swing given);
* :func:`slider_crank_from_K` — offset slider-crank from K, the stroke H and
  the offset e (习题 3-16);
* :func:`slider_crank_stroke_from_K` — offset slider-crank from K, the crank
  and the coupler: the stroke and the offset (slides exam problem 3);
* :func:`guide_bar_from_K` — oscillating guide-bar, ψ = θ, from the frame d
  or the crank a: a = d sin(ψ/2).  This is also the slides' "已知：机架长度 d,
  K, 设计此机构" (slides §2-3 一.2).

Every design's θ, ψ, K, γ come from the Grashof core
(:mod:`mechcli.core.grashof.fourbar`) applied to the designed lengths, so a
design and ``mechcli grashof`` can never disagree.  SI units and radians; a
problem without solution raises :class:`~mechcli.core.errors.DescribedError`
with the reachable range in its values.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Dict, List, Optional, Sequence, Tuple, cast

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.grashof.fourbar import (
    CHANGE_POINT_RTOL,
    analyse_fourbar,
    analyse_guide_bar,
    analyse_slider_crank,
)
from mechcli.core.linkage.presets import guide_bar as guide_bar_linkage
from mechcli.core.numerics import golden_section_max
from mechcli.core.records import record
from mechcli.core.synth.design import LinkageDesign, four_bar_design, slider_crank_design

Point = Tuple[float, float]

#: which A when the condition leaves two: ``best`` the larger γmin (ties: the
#: left one), ``left``/``right`` the smaller/larger x of A in the book's frame
BRANCHES = ("best", "left", "right")
#: the given limit position of :func:`crank_rocker_from_K_limit_angle`
LIMITS = ("best", "extended", "folded")


# ------------------------------------------------------------------------ K and θ
def limit_angle_from_K(K: float) -> float:
    """The limit-position angle θ = π (K − 1)/(K + 1) [rad] (eq. 3-39).

    Raises
    ------
    DescribedError
        reason ``"K"`` for K <= 1 (values ``K``, ``lo`` = 1): K = 1 has no
        quick return (θ = 0) and fixes no design.
    ValueError
        K not finite.
    """
    K = float(K)
    if not math.isfinite(K):
        raise ValueError(f"K must be finite, got {K!r}")
    if K <= 1.0:
        raise DescribedError("the time ratio K must exceed 1 for a quick-return design",
                             reason="K", K=K, lo=1.0)
    return math.pi * (K - 1.0) / (K + 1.0)


def time_ratio(theta: float) -> float:
    """K = (π + θ)/(π − θ) for a limit-position angle θ [rad] (slides §2-2)."""
    return (math.pi + theta) / (math.pi - theta)


def _positive(name: str, x: float) -> float:
    x = float(x)
    if not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a positive length, got {x!r}")
    return x


def _branch(branch: str, allowed: Tuple[str, str, str] = BRANCHES) -> str:
    if branch not in allowed:
        raise ValueError(f"branch must be one of {allowed}, got {branch!r}")
    return branch


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.hypot(v[0], v[1])


def _pt(v: np.ndarray) -> Point:
    return (float(v[0]), float(v[1]))


def _gamma_ok(gamma_min: float, gamma_allowed: Optional[float]) -> Optional[bool]:
    return None if gamma_allowed is None else bool(gamma_min >= gamma_allowed)


# ------------------------------------------------------------------ crank-rocker
@record
class PivotCircle:
    """The circle L of A (图 3-15, eqs. 3-40 … 3-42) and the valid part of it.

    The book's frame: D = (0, 0), the y axis bisects the swing, the rocker's
    limit positions C1 = (−x_C2, y_C2) (left) and C2 = (x_C2, y_C2) with
    x_C2 = l3 sin(ψ/2), y_C2 = l3 cos(ψ/2).  Every point of L below the chord
    C1C2 sees it under θ: R = x_C2 / sin θ, O = (0, y_C2 − R cos θ).

    Attributes
    ----------
    theta, psi, rocker : float
        θ, ψ [rad] and l3 [m].
    C1, C2, O : ndarray (2,)
        Limit positions of C and the centre of L [m].
    R : float
        Radius of L [m].
    E : ndarray (2,)
        The end of the usable arc on C1's side: where the line AD passes
        through C1 or C2 (a change point, s + l = p + q).  A on the arc
        strictly between C1 and E gives a crank-rocker with θ and ψ; on the
        rest of the lower arc the line AD separates C1 from C2, so the
        linkage's limit positions are not C1, C2.  Its mirror bounds C2's side.
    crank, coupler, frame : (float, float)
        The open ranges of l1, l2, l4 over the usable arc [m].
    """

    theta: float
    psi: float
    rocker: float
    C1: np.ndarray
    C2: np.ndarray
    O: np.ndarray
    R: float
    E: np.ndarray
    crank: Tuple[float, float]
    coupler: Tuple[float, float]
    frame: Tuple[float, float]

    def lengths_at(self, A: np.ndarray) -> Tuple[float, float, float]:
        """(l1, l2, l4) for A on L: l1 = |AC2 − AC1|/2, l2 = (AC1 + AC2)/2, l4 = AD."""
        A = np.asarray(A, dtype=float)
        ac1, ac2 = np.hypot(*(A - self.C1)), np.hypot(*(A - self.C2))
        return abs(ac2 - ac1) / 2, (ac1 + ac2) / 2, float(np.hypot(*A))

    def from_delta(self, delta: float) -> np.ndarray:
        """A on C1's side of L for the parameter δ ∈ (0, (π − θ)/2).

        With x = ∠AC1C2 and y = ∠AC2C1 (x + y = π − θ), δ = (x − y)/2; the law
        of sines in △AC1C2 (AC1 = 2R sin y, AC2 = 2R sin x) gives
        l1 = 2R sin(θ/2) sin δ and l2 = 2R cos(θ/2) cos δ (eq. 3-45 solved for
        either length).  δ = (π − θ)/2 is A = C1.
        """
        th, R = self.theta, self.R
        l1 = 2 * R * math.sin(th / 2) * math.sin(delta)
        l2 = 2 * R * math.cos(th / 2) * math.cos(delta)
        x = delta + (math.pi - th) / 2
        return self.C1 + (l2 - l1) * np.array([math.cos(x), -math.sin(x)])

    def usable(self, A: np.ndarray, rtol: float = 1e-12) -> bool:
        """A is on the usable arcs: below the chord, and C1, C2 strictly on one side of AD."""
        A = np.asarray(A, dtype=float)
        scale = self.rocker
        if A[1] >= self.C1[1] - rtol * scale:
            return False
        u = -A                                     # A -> D

        def side(P: np.ndarray) -> float:
            w = P - A
            return (u[0] * w[1] - u[1] * w[0]) / scale ** 2

        s1, s2 = side(self.C1), side(self.C2)
        return bool(s1 * s2 > 0 and min(abs(s1), abs(s2)) > rtol)


def pivot_circle(K: float, rocker: float, swing: float) -> PivotCircle:
    """The circle L of A for K, the rocker l3 and the swing ψ (eqs. 3-39 … 3-42).

    Parameters
    ----------
    K : float
        Time ratio (> 1).
    rocker : float
        Rocker CD, l3 [m].
    swing : float
        Swing ψ of the rocker, the book's φ [rad], 0 < ψ < π.

    Returns
    -------
    PivotCircle

    Raises
    ------
    DescribedError
        reason ``"K"``: K <= 1 (values ``K``, ``lo``), or θ >= (π + ψ)/2, no
        crank-rocker has such a quick return with this swing (values ``K``,
        ``theta``, ``lo`` = 1, ``hi`` the largest K, ``theta_max``, ``psi``);
        reason ``"swing"``: ψ outside (0, π) (values ``psi``, ``lo``, ``hi``).

    Notes
    -----
    ERRATA: eq. (3-41) prints y_O = l3 cos(φ/2) − R cos(θ/2); the centre of
    a circle whose chord 2 x_C2 subtends the inscribed angle θ lies R cos θ
    from the chord (central angle 2θ), as the book's own program computes
    (``yo=l3*cos(phi/2)-R*cos(theta)``) and as its printed results need.

    The usable arc: the power of D about L is y_O² − R² = τ l3 with
    τ = l3 sin(θ − ψ)/sin θ, so the line DC1 (τ > 0) or DC2 (τ < 0) meets L
    again at E = (−sin(ψ/2) |τ|, cos(ψ/2) τ).  A usable arc exists iff τ < l3, i.e.
    sin(θ − ψ) < sin θ: θ < 90° + ψ/2 (the bound of the K error).
    """
    theta = limit_angle_from_K(K)
    l3 = _positive("rocker", rocker)
    psi = float(swing)
    if not (0.0 < psi < math.pi):
        raise DescribedError("the rocker's swing must lie strictly between 0 and half a turn",
                             reason="swing", psi=psi, lo=0.0, hi=math.pi)
    theta_max = (math.pi + psi) / 2
    if theta >= theta_max:
        raise DescribedError(
            "no crank-rocker has this time ratio with this swing", reason="K", K=float(K),
            theta=theta, lo=1.0, hi=time_ratio(theta_max), theta_max=theta_max, psi=psi)
    s, c = math.sin(psi / 2), math.cos(psi / 2)
    C1, C2 = np.array([-l3 * s, l3 * c]), np.array([l3 * s, l3 * c])
    R = l3 * s / math.sin(theta)                                    # eq. 3-40
    # ERRATA: eq. 3-41 prints R cos(θ/2); the centre is R cos θ from the chord (Notes)
    O = np.array([0.0, l3 * c - R * math.cos(theta)])               # eq. 3-41
    tau = l3 * math.sin(theta - psi) / math.sin(theta)
    E = np.array([-s * abs(tau), c * tau])
    circle = PivotCircle(theta, psi, l3, C1, C2, O, R, E, (0.0, 0.0), (0.0, 0.0), (0.0, 0.0))
    l1E, l2E, l4E = circle.lengths_at(E)
    return dataclasses.replace(circle, crank=(l1E, l3 * s), coupler=(l3 * s, l2E),
                               frame=(min(l3, l4E), max(l3, l4E)))


def _check_range(name: str, reason: str, key: str, value: float, rng: Tuple[float, float]) -> None:
    lo, hi = rng
    if not (lo < value < hi):
        raise DescribedError(
            f"no crank-rocker with this time ratio and swing has this {name} (the "
            f"range is in the error's lo, hi)", reason=reason,
            **{key: value, "value": value, "lo": lo, "hi": hi})


def _line_points(circle: PivotCircle, line: Any) -> List[np.ndarray]:
    """Intersections of a x + b y = c with L, ordered by x (then y)."""
    a, b, c = (float(v) for v in line)
    n = math.hypot(a, b)
    if not (n > 0 and all(map(math.isfinite, (a, b, c)))):
        raise ValueError("pivot_line (a, b, c) needs finite numbers and (a, b) != 0, "
                         f"got {line!r}")
    nv = np.array([a, b]) / n
    at_centre = float(nv @ circle.O)
    h = c / n - at_centre                           # signed distance of the line from O
    if abs(h) > circle.R:
        raise DescribedError(
            "the line of A misses the circle the fixed pivot A lies on (图 3-16)",
            reason="pivot_line_misses",
            a=a, b=b, c=c, lo=(at_centre - circle.R) * n, hi=(at_centre + circle.R) * n,
            centre=_pt(circle.O), radius=circle.R)
    foot = circle.O + h * nv
    t = np.array([-nv[1], nv[0]])
    half = math.sqrt(max(circle.R ** 2 - h ** 2, 0.0))
    pts = [foot - half * t, foot + half * t]
    pts.sort(key=lambda p: (p[0], p[1]))
    return pts


def _crank_rocker_at(circle: PivotCircle, A: np.ndarray, K: float, gamma_allowed: Optional[float],
                     side: str) -> LinkageDesign:
    """The design for a pivot A on the usable arc (B1 where A, B1, C1 are in line)."""
    A = np.asarray(A, dtype=float)
    C1, C2, D = circle.C1, circle.C2, np.zeros(2)
    l1 = circle.lengths_at(A)[0]
    u1, u2 = _unit(C1 - A), _unit(C2 - A)
    if np.hypot(*(C1 - A)) <= np.hypot(*(C2 - A)):
        B1, B2 = A - l1 * u1, A + l1 * u2          # C1 folded, C2 extended
    else:
        B1, B2 = A + l1 * u1, A - l1 * u2          # C1 extended, C2 folded
    design = four_bar_design(_pt(A), _pt(D), _pt(B1), _pt(C1),
                             pivots={"C2": _pt(C2), "B2": _pt(B2), "O": _pt(circle.O)})
    # θ, ψ, γ of the lengths as designed (those the Grashof core and verify see)
    merit = analyse_fourbar([design.lengths[k] for k in ("l1", "l2", "l3", "l4")]).merit
    gamma_min = float(merit.gamma_min[0])
    values = {"K": float(K), "theta": circle.theta, "psi": circle.psi,
              "gamma_1": float(merit.gamma0[0]), "gamma_2": float(merit.gamma180[0]),
              "gamma_min": gamma_min, "gamma_ok": _gamma_ok(gamma_min, gamma_allowed),
              "R": circle.R, "branch": side}
    return dataclasses.replace(design, inputs=None, values=values)


def crank_rocker_from_K(K: float, rocker: float, swing: float, *,
                        pivot_line: Optional[Sequence[float]] = None,
                        crank: Optional[float] = None, coupler: Optional[float] = None,
                        frame: Optional[float] = None, gamma_allowed: Optional[float] = None,
                        branch: str = "best") -> LinkageDesign:
    """Crank-rocker from K, the rocker and its swing, plus one condition (【例 3-8】).

    Parameters
    ----------
    K : float
        Time ratio (> 1); θ = 180°(K − 1)/(K + 1) (eq. 3-39).
    rocker : float
        Rocker CD, l3 [m].
    swing : float
        Swing ψ of the rocker (the book's φ) [rad], 0 < ψ < π.
    pivot_line : (a, b, c), optional
        Case (1): A on the line a x + b y = c (eq. 3-43) in the book's frame
        (D at the origin, the y axis the bisector of the swing, C above D;
        ``c`` in m).
    crank : float, optional
        Case (2): the crank l1 [m] (eq. 3-45).
    coupler : float, optional
        Case (3): the coupler l2 [m] (eq. 3-47).
    frame : float, optional
        Case (4): the frame l4 = AD [m] (eq. 3-48).
    gamma_allowed : float, optional
        The allowed [γmin] [rad]; sets ``values["gamma_ok"]``.
    branch : {"best", "left", "right"}
        Which A when two exist.  Case (1): the line's two intersections with
        L, ``left``/``right`` the one of smaller/larger x; ``best`` the usable
        one with the larger γmin.  Cases (2)–(4): A on C1's side (``left``,
        the book's placement, x_A < 0, C1 the folded limit position) or its
        mirror image about the y axis (``right``, C2 folded; the same
        lengths); ``best`` is ``left``.

    Returns
    -------
    LinkageDesign
        A four-bar (``four_bar_design``) with A, D, B1, C1 as the book places
        them, B1 in line with A and C1; ``pivots`` also ``C2``, ``B2`` and the
        centre ``O`` of L.  ``inputs`` is None (no prescribed positions: the
        check is K and ψ).  ``values``: ``K``, ``theta`` θ, ``psi`` ψ,
        ``gamma_1`` and ``gamma_2`` the transmission angles with the crank
        along the frame line, θ1 = 0 and 180° from AD (eq. 3-49, folded to
        <= 90° as the book prints them), ``gamma_min``, ``gamma_ok`` (None
        without ``gamma_allowed``), ``R`` the radius of L, ``branch`` the side
        chosen (``left``/``right``) [rad, m].

    Raises
    ------
    ValueError
        Not exactly one condition, a non-positive length, an unknown branch,
        or a line with a = b = 0.
    DescribedError
        reason ``"K"`` or ``"swing"`` (see :func:`pivot_circle`);
        ``"pivot_line_misses"``: the line misses L (values ``a, b, c`` and the
        range ``lo, hi`` of c that meets L, ``centre``, ``radius``);
        ``"pivot_line_unusable"``: it meets L only where no crank-rocker has
        these C1, C2 as limit positions, or the chosen branch is one of those
        (values ``points``, ``usable`` (list of bool));
        ``"crank_range"``, ``"coupler_range"``, ``"frame_range"``: the length
        is outside the open range ``lo, hi`` of the usable arc (values
        ``value`` and the same under ``l1``/``l2``/``l4``, ``lo``, ``hi``).

    Notes
    -----
    Cases (2) and (3) solve eq. 3-45/3-47 in the parameter δ of
    :meth:`PivotCircle.from_delta` (the book's l4 of eq. 3-46 then equals
    |AD|); case (4) intersects L with the circle (D, l4), whose radical line is
    y = (l4² + y_O² − R²)/(2 y_O).  In case (1) with the book's data the line
    x + y = 0 meets L at (−196.1, 196.1) (the book's A, γmin = 43.6°) and at
    (151.7, −151.7), a usable crank-rocker too (l1 = 27.85, l2 = 462.05, γmin
    = 11.3°): ``best`` picks the book's.
    """
    given = {k: v for k, v in (("pivot_line", pivot_line), ("crank", crank),
                               ("coupler", coupler), ("frame", frame)) if v is not None}
    if len(given) != 1:
        raise ValueError("exactly one of pivot_line, crank, coupler, frame is needed, got "
                         f"{sorted(given) or 'none'}")
    _branch(branch)
    circle = pivot_circle(K, rocker, swing)
    if pivot_line is not None:
        return _on_pivot_line(circle, pivot_line, K, gamma_allowed, branch)
    A = _pivot_from_length(circle, crank, coupler, frame)
    side = "right" if branch == "right" else "left"
    if side == "right":
        A = np.array([-A[0], A[1]])
    return _crank_rocker_at(circle, A, K, gamma_allowed, side)


def _on_pivot_line(circle: PivotCircle, pivot_line: Sequence[float], K: float,
                   gamma_allowed: Optional[float], branch: str) -> LinkageDesign:
    """Case (1) of :func:`crank_rocker_from_K`: A where the line meets L."""
    pts = _line_points(circle, pivot_line)
    ok = [circle.usable(p) for p in pts]
    if branch == "best":
        cands = [_crank_rocker_at(circle, p, K, gamma_allowed, "left" if i == 0 else "right")
                 for i, p in enumerate(pts) if ok[i]]
        if cands:
            return max(cands, key=lambda d: cast(float, d.values["gamma_min"]))
    else:
        i = 0 if branch == "left" else 1
        if ok[i]:
            return _crank_rocker_at(circle, pts[i], K, gamma_allowed, branch)
    raise DescribedError(
        "the line of A meets the circle of A only where the linkage's limit positions "
        "are not C1 and C2 (the line AD passes between them)" if branch == "best" else
        f"the {branch} intersection of the line with the circle of A gives no "
        "crank-rocker with these limit positions", reason="pivot_line_unusable",
        points=[_pt(p) for p in pts], usable=ok, branch=branch)


def _pivot_from_length(circle: PivotCircle, crank: Optional[float], coupler: Optional[float],
                       frame: Optional[float]) -> np.ndarray:
    """Cases (2)–(4) of :func:`crank_rocker_from_K`: A on C1's side from the one length
    given (crank, coupler or frame)."""
    th, R = circle.theta, circle.R
    if crank is not None:
        l1 = _positive("crank", crank)
        _check_range("crank", "crank_range", "l1", l1, circle.crank)
        return circle.from_delta(math.asin(l1 / (2 * R * math.sin(th / 2))))
    if coupler is not None:
        l2 = _positive("coupler", coupler)
        _check_range("coupler", "coupler_range", "l2", l2, circle.coupler)
        return circle.from_delta(math.acos(l2 / (2 * R * math.cos(th / 2))))
    l4 = _positive("frame", cast(float, frame))  # the one length given
    _check_range("frame", "frame_range", "l4", l4, circle.frame)
    yo = circle.O[1]
    if yo == 0.0:      # D is the centre of L: every A is l3 from D, the range is empty
        raise DescribedError("with D at the centre of the circle of A the frame does not "
                             "fix A", reason="frame_range", l4=l4, value=l4,
                             lo=circle.rocker, hi=circle.rocker)
    y = (l4 ** 2 + yo ** 2 - R ** 2) / (2 * yo)
    return np.array([-math.sqrt(max(l4 ** 2 - y ** 2, 0.0)), y])


def crank_rocker_from_K_limit_angle(K: float, rocker: float, frame: float,
                                    limit_angle: float, *, limit: str = "best",
                                    gamma_allowed: Optional[float] = None) -> LinkageDesign:
    """Crank-rocker from K, the rocker, the frame and one limit position (习题 3-15).

    The rocker CD makes the angle ∠ADC1 = ``limit_angle`` with the frame at
    one of its limit positions; the swing is not given.

    Parameters
    ----------
    K : float
        Time ratio (> 1).
    rocker, frame : float
        l3 = CD and l4 = AD [m].
    limit_angle : float
        ∠ADC1 of the given limit position [rad], 0 < angle < π.
    limit : {"best", "extended", "folded"}
        Which limit position C1 is: crank and coupler extended (AC1 = l2 + l1)
        or folded (AC1 = l2 − l1); ``best`` the one with the larger γmin.
    gamma_allowed : float, optional
        The allowed [γmin] [rad].

    Returns
    -------
    LinkageDesign
        A = (0, 0), D = (l4, 0), C1 above AD; ``pivots`` also ``C2``, ``B2``;
        ``inputs`` None.  ``values``: ``K``, ``theta``, ``psi`` (the swing that
        results), ``gamma_1``, ``gamma_2``, ``gamma_min``, ``gamma_ok``,
        ``limit`` (``extended``/``folded``), ``limit_angle``.

    Raises
    ------
    DescribedError
        reason ``"limit_angle"``: no crank-rocker of this kind (values ``K``,
        ``theta``, ``limit_angle``, ``limit``, and ``K_hi``, the largest K a
        crank-rocker with this rocker, frame and limit position reaches: the
        best of 4096 cranks refined by golden section).

    Notes
    -----
    AC1 follows from △ADC1 (law of cosines).  The other limit position C2 is
    on the circle (D, l3) and on a ray from A at ±θ from AC1 (the crank
    turns θ + 180° between them); each candidate (l1 = |AC2 − AC1|/2,
    l2 = (AC1 + AC2)/2) is kept when the Grashof core finds a crank-rocker with
    this K and its given-kind limit position at ∠ADC = ``limit_angle``.  With
    the exercise's data (K = 1.5, l3 = 75, l4 = 100, 45°) both kinds exist.
    """
    _branch(limit, LIMITS)
    theta = limit_angle_from_K(K)
    c, d = _positive("rocker", rocker), _positive("frame", frame)
    delta = float(limit_angle)
    if not (0.0 < delta < math.pi):
        raise ValueError(f"limit_angle must lie strictly between 0 and pi, got {delta!r}")
    C1 = np.array([d - c * math.cos(delta), c * math.sin(delta)])
    s1 = float(np.hypot(*C1))
    phi1 = math.atan2(C1[1], C1[0])
    target_theta3 = math.pi - delta                # the core's angle of DC from +x
    found: Dict[str, Tuple[float, float, float, np.ndarray, Any]] = {}
    for sign in (1, -1):
        phi = phi1 + sign * theta
        b = d * math.cos(phi)
        disc = b * b - (d * d - c * c)
        if disc < 0:
            continue
        for t in (b - math.sqrt(disc), b + math.sqrt(disc)):
            if t <= 0 or abs(t - s1) <= 1e-12 * s1:
                continue
            kind = "folded" if t > s1 else "extended"     # what C1 is
            l1, l2 = abs(t - s1) / 2, (t + s1) / 2
            an = analyse_fourbar([l1, l2, c, d], require_closure=False)
            m = an.merit
            if not (an.klass.types[0] == "crank_rocker" and m.has_limits[0]):
                continue
            th3 = m.theta3_fold[0] if kind == "folded" else m.theta3_ext[0]
            if abs(m.K[0] - K) > 1e-9 * K or abs(th3 - target_theta3) > 1e-9:
                continue
            C2 = np.array([t * math.cos(phi), t * math.sin(phi)])
            gmin = float(m.gamma_min[0])
            if kind not in found or gmin > found[kind][0]:
                found[kind] = (gmin, l1, l2, C2, m)
    keys = [k for k in ("extended", "folded") if k in found and limit in ("best", k)]
    if not keys:
        raise DescribedError(
            "no crank-rocker with this rocker and frame has this time ratio with the given "
            "limit position", reason="limit_angle", K=float(K), theta=theta,
            limit_angle=delta, limit=limit,
            K_hi=_limit_angle_K_hi(c, d, s1, delta, limit), other=sorted(found))
    kind = max(keys, key=lambda k: found[k][0])
    gmin, l1, l2, C2, m = found[kind]
    A = np.zeros(2)
    u1, u2 = _unit(C1), _unit(C2)
    B1, B2 = (A - l1 * u1, A + l1 * u2) if kind == "folded" else (A + l1 * u1, A - l1 * u2)
    values = {"K": float(K), "theta": theta, "psi": float(m.psi[0]),
              "gamma_1": float(m.gamma0[0]), "gamma_2": float(m.gamma180[0]),
              "gamma_min": gmin, "gamma_ok": _gamma_ok(gmin, gamma_allowed),
              "limit": kind, "limit_angle": delta}
    design = four_bar_design((0.0, 0.0), (d, 0.0), _pt(B1), _pt(C1), values=values,
                             pivots={"C2": _pt(C2), "B2": _pt(B2)})
    return dataclasses.replace(design, inputs=None)


def _limit_angle_K_hi(c: float, d: float, s1: float, delta: float, limit: str) -> float:
    """Largest K of the crank-rockers with AC1 = s1 at ∠ADC1 = delta: the best of 4096
    cranks per kind, refined by golden section between its grid neighbours (K is -inf
    where the crank-rocker ceases, so an edge maximum is approached from inside)."""
    kinds = ("extended", "folded") if limit == "best" else (limit,)
    best = 1.0
    for kind in kinds:
        def K_of(a: np.ndarray, kind: str = kind) -> np.ndarray:
            a = np.atleast_1d(np.asarray(a, dtype=float))
            b = s1 - a if kind == "extended" else s1 + a
            L = np.stack([a, b, np.full_like(a, c), np.full_like(a, d)], axis=1)
            an = analyse_fourbar(L, require_closure=False)
            m = an.merit
            th3 = m.theta3_ext if kind == "extended" else m.theta3_fold
            ok = m.has_limits & (np.abs(th3 - (math.pi - delta)) < 1e-9) \
                & (np.array(an.klass.types) == "crank_rocker") & (a > 0) & (b > 0)
            return np.where(ok, m.K, -np.inf)

        hi = s1 / 2 if kind == "extended" else max(c, d, s1)
        a = np.linspace(0, hi, 4098)[1:-1]
        K = K_of(a)
        if not np.isfinite(K).any():
            continue
        i = int(np.argmax(K))
        lo_i, hi_i = max(i - 1, 0), min(i + 1, a.size - 1)
        _x, k = golden_section_max(K_of, np.array([a[lo_i]]), np.array([a[hi_i]]),
                                   iterations=80, rtol=1e-14)
        best = max(best, float(K[i]), float(k[0]) if np.isfinite(k[0]) else 1.0)
    return best


# ------------------------------------------------------------------ slider-crank
def slider_crank_from_K(K: float, H: float, e: float, *,
                        gamma_allowed: Optional[float] = None) -> LinkageDesign:
    """Offset slider-crank from K, the stroke H and the offset e (习题 3-16).

    Parameters
    ----------
    K : float
        Time ratio (> 1).
    H : float
        Stroke C1C2 [m].
    e : float
        Offset of the slider path from the crank pivot [m] (path y = e; the
        sign only mirrors the design).
    gamma_allowed : float, optional
        The allowed [γmin] [rad].

    Returns
    -------
    LinkageDesign
        ``slider_crank_design(l1, l2, e, H=H)``: A = (0, 0), the slider to the
        right.  ``pivots`` also ``C1`` (folded, nearer A), ``C2`` (extended),
        ``B1``, ``B2``.  ``values``: ``K``, ``theta``, ``H``, ``e_max``,
        ``b_minus_a`` = AC1, ``b_plus_a`` = AC2, ``alpha_max`` the largest
        pressure angle on the slider, ``gamma_min`` = 90° − α_max (over a
        turn), ``gamma_ok``, ``boundary`` (a + |e| = b: e = e_max).

    Raises
    ------
    ValueError
        H <= 0.
    DescribedError
        reason ``"K"``: K <= 1 (values ``K``, ``lo``) or θ >= 90° (values
        ``K``, ``theta``, ``hi`` = 3, ``theta_limit`` = π/2: no offset
        slider-crank reaches it);
        reason ``"offset"``: e = 0 (a centred slider-crank has K = 1) or
        |e| > e_max = H cot θ (values ``e``, ``lo`` = 0, ``hi`` = e_max,
        ``H``, ``theta``).

    Notes
    -----
    In △AC1C2 (AC1 = b − a, AC2 = b + a, angle θ at A, height e on C1C2):
    H² = (b − a)² + (b + a)² − 2(b² − a²) cos θ (as eq. 3-44) and twice the
    area (b² − a²) sin θ = H e, hence

        a² = H/4 · (H − 2e tan(θ/2)),   b² = H/4 · (H + 2e cot(θ/2)).

    The crank condition a + e <= b of the slides is AC1 >= e, and AC1 = e is
    C1 straight above A: e <= H cot θ (slides exam 3: e = 40 = H cot 60°,
    the boundary).  Beyond it the foot of A falls between C1 and C2, and the
    slider's dead positions are not C1, C2.
    """
    theta = limit_angle_from_K(K)
    H = _positive("H", H)
    e = float(e)
    if theta >= math.pi / 2 * (1 - 1e-15):
        raise DescribedError("no offset slider-crank has a limit-position angle of a "
                             "quarter turn or more (K >= 3)", reason="K", K=float(K),
                             theta=theta, lo=1.0, hi=3.0, theta_limit=math.pi / 2)
    e_max = H / math.tan(theta)
    ea = abs(e)
    if not (0.0 < ea <= e_max * (1 + CHANGE_POINT_RTOL)):
        raise DescribedError(
            "no offset slider-crank has this time ratio and stroke with this offset",
            reason="offset", e=e, lo=0.0, hi=e_max, H=H,
            theta=theta)
    if ea >= e_max * (1 - CHANGE_POINT_RTOL):
        ea = e_max                                  # the boundary a + e = b
    a = math.sqrt(max(H / 4 * (H - 2 * ea * math.tan(theta / 2)), 0.0))
    b = math.sqrt(H / 4 * (H + 2 * ea / math.tan(theta / 2)))
    return _slider_design(a, b, math.copysign(ea, e) if e else e, K, theta, H,
                          gamma_allowed, e_max=e_max)


def slider_crank_stroke_from_K(K: float, crank: float, coupler: float, *,
                               gamma_allowed: Optional[float] = None) -> LinkageDesign:
    """Offset slider-crank from K, the crank a and the coupler b (slides exam 3).

    The slides (2011): a = 20 cm, b = 60 cm, K = 2, "试求：滑块行程": the
    stroke follows from △AC1C2 alone, the offset from its area.

    Parameters
    ----------
    K : float
        Time ratio (> 1).
    crank, coupler : float
        a = AB and b = BC [m], a < b.
    gamma_allowed : float, optional
        The allowed [γmin] [rad].

    Returns
    -------
    LinkageDesign
        As :func:`slider_crank_from_K`; ``lengths`` ``l1, l2, e, H``.

    Raises
    ------
    ValueError
        a >= b or a non-positive length.
    DescribedError
        reason ``"K"``: K <= 1, or θ > θ_max = arccos((b − a)/(b + a)) where
        the offset would exceed b − a and the crank could not turn (values
        ``K``, ``theta``, ``lo`` = 1, ``hi`` the largest K, ``theta_max``).

    Notes
    -----
    H² = (b − a)² + (b + a)² − 2(b² − a²) cos θ (slides: √(80² + 40² −
    2·80·40 cos 60°) = 69.28) and e = (b² − a²) sin θ / H.  At θ_max, AC1 is
    normal to the path (e = b − a): the slides' own numbers are that
    boundary (e = 40 = 60 − 20).
    """
    theta = limit_angle_from_K(K)
    a, b = _positive("crank", crank), _positive("coupler", coupler)
    if a >= b:
        raise ValueError(f"the coupler must be longer than the crank, got a={a!r}, b={b!r}")
    theta_max = math.acos((b - a) / (b + a))
    if theta > theta_max * (1 + CHANGE_POINT_RTOL):
        raise DescribedError(
            "with this crank and coupler the time ratio needs an offset larger than "
            "coupler - crank, and the crank could not turn", reason="K", K=float(K),
            theta=theta, lo=1.0, hi=time_ratio(theta_max), theta_max=theta_max)
    H = math.sqrt((b - a) ** 2 + (b + a) ** 2 - 2 * (b * b - a * a) * math.cos(theta))
    e = (b * b - a * a) * math.sin(theta) / H
    if e >= (b - a) - CHANGE_POINT_RTOL * (a + b):
        e = b - a                                   # the boundary a + e = b (exam 3)
    return _slider_design(a, b, e, K, theta, H, gamma_allowed)


def _slider_design(a: float, b: float, e: float, K: float, theta: float, H: float,
                   gamma_allowed: Optional[Any], **extra: Any) -> LinkageDesign:
    """The slider-crank design with its limit positions (A = (0, 0), path y = e)."""
    xf = math.sqrt(max((b - a) ** 2 - e * e, 0.0))
    xe = math.sqrt((b + a) ** 2 - e * e)
    C1, C2 = np.array([xf, e]), np.array([xe, e])
    B1, B2 = -a * C1 / (b - a), a * C2 / (b + a)
    sc = analyse_slider_crank(a, b, e)
    gamma_min = math.pi / 2 - sc.alpha_max
    values = {"K": float(K), "theta": theta, "H": H, "b_minus_a": b - a, "b_plus_a": b + a,
              "alpha_max": sc.alpha_max, "gamma_min": gamma_min,
              "gamma_ok": _gamma_ok(gamma_min, gamma_allowed), "boundary": sc.boundary,
              **extra}
    design = slider_crank_design(a, b, e, H=H, values=values)
    pivots = dict(design.pivots, C1=_pt(C1), C2=_pt(C2), B1=_pt(B1), B2=_pt(B2))
    return dataclasses.replace(design, pivots=pivots)


# ---------------------------------------------------------------------- guide-bar
def guide_bar_from_K(K: float, *, crank: Optional[float] = None,
                     frame: Optional[float] = None) -> LinkageDesign:
    """Oscillating guide-bar from K and the frame d or the crank a (slides §2-3 一.2).

    Parameters
    ----------
    K : float
        Time ratio (> 1).
    crank : float, optional
        Crank AB, a = l1 [m]: then d = a / sin(θ/2).
    frame : float, optional
        Frame AC, d = l4 [m]: then a = d sin(θ/2) (the slides' "已知：机架长度
        d, K，设计此机构").

    Returns
    -------
    LinkageDesign
        kind ``"guide_bar"``, ``presets.guide_bar(l1, l4)`` (C = (0, 0),
        A = (0, l4)); ``lengths`` ``l1, l4``; ``pivots`` ``A``, ``C`` and the
        crank pin at the limit positions ``B1``, ``B2`` (AB ⟂ CB);
        ``inputs`` None.  ``values``: ``K``, ``theta``, ``psi`` (= θ),
        ``gamma_min`` (90°: the guide passes through C).

    Raises
    ------
    ValueError
        Not exactly one of crank, frame; a non-positive length.
    DescribedError
        reason ``"K"``: K <= 1 (the crank would be 0).

    Notes
    -----
    At both limit positions the crank is normal to the guide, so the guide's
    swing ψ equals the crank's limit-position angle θ (slides: "θ = ψ"), and
    in the right triangle ABC sin(ψ/2) = a/d.  Slides fill-in 1: ψ = 30°,
    K = 1.4.
    """
    if (crank is None) == (frame is None):
        raise ValueError("exactly one of crank, frame is needed")
    theta = limit_angle_from_K(K)
    half = math.sin(theta / 2)
    if frame is not None:
        l4 = _positive("frame", frame)
        l1 = l4 * half
    else:
        l1 = _positive("crank", cast(float, crank))  # exactly one of crank, frame
        l4 = l1 / half
    A = np.array([0.0, l4])
    q = (-theta / 2, -math.pi + theta / 2)     # crank angles at the limits: AB ⟂ CB
    B1, B2 = (A + l1 * np.array([math.cos(x), math.sin(x)]) for x in q)
    gb = analyse_guide_bar(l1, l4)
    values = {"K": float(K), "theta": theta, "psi": theta, "gamma_min": gb.gamma_min}
    return LinkageDesign("guide_bar", guide_bar_linkage(l1, l4), {"l1": l1, "l4": l4},
                         {"A": _pt(A), "C": (0.0, 0.0), "B1": _pt(B1), "B2": _pt(B2)},
                         values=values)
