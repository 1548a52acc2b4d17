"""Type of a four-bar chain (Grashof), its figures of merit, slider-crank and guide-bar.

Everything here is closed form and vectorized over arrays of length sets: a
batch of 100 000 four-bars is classified by a handful of numpy operations.
One length set (``mechcli grashof --lengths``) is classified by the pure-Python
twin :mod:`.chain`, which does not import numpy; the scalar slider-crank,
guide-bar and length ranges live there and are re-exported here.

Conventions (book chapter 3 §1, fig. 3-1): the links of a four-bar chain are
numbered 1..4 around the loop, link *k* joined to links *k-1* and *k+1*
(1 joined to 4).  The default frame is link 4, the default input (driver)
link 1, so link 3 (opposite link 1) is the output and link 2 the coupler.
For the figures of merit the linkage is drawn as in the book's figures: the
input pivot A at the origin, the output pivot D on the +x axis at distance
*d* (the frame), the coupler–output joint C above the line AD (the "open"
assembly).  Angles are counter-clockwise from +x, in radians.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, List, Union

import numpy as np

from mechcli.core.errors import UnsolvableError
from mechcli.core.grashof.chain import (
    _CODE,
    CHANGE_POINT_RTOL,
    TYPES,
    ClosureError,
    GuideBar,
    LengthRange,
    SliderCrank,
    analyse_guide_bar,
    analyse_slider_crank,
    driven_links,
    length_ranges,
)
from mechcli.core.records import record

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    #: a length or angle, or an array of them (broadcast together)
    FloatOrArray = Union[float, np.ndarray]


def _lengths_array(lengths: ArrayLike, n: int) -> np.ndarray:
    arr = np.asarray(lengths, dtype=float)
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != n:
        raise ValueError(f"expected lengths of shape (N, {n}), got {arr.shape}")
    return arr


def check_closure(lengths: ArrayLike) -> bool:
    """Raise :class:`ClosureError` if some link is at least as long as all the others.

    Parameters
    ----------
    lengths : array_like, shape (n,) or (N, n)
        Link lengths of one closed chain (or a batch) [m, or any unit].

    Notes
    -----
    A closed chain of rigid links can be assembled (and move) only if every
    link is shorter than the sum of the others; with equality it is a
    straight, immobile line.
    """
    arr = np.asarray(lengths, dtype=float)
    arr = arr if arr.ndim == 2 else arr[None, :]
    longest = arr.max(axis=1)
    rest = arr.sum(axis=1) - longest
    bad = np.flatnonzero(longest >= rest)
    if bad.size:
        i = int(bad[0])
        k = int(np.argmax(arr[i])) + 1
        raise ClosureError("chain", arr[i, k - 1], rest[i], link=k,
                           set_index=i + 1 if arr.shape[0] > 1 else None)
    return True


def closes(lengths: ArrayLike) -> np.ndarray:
    """Boolean array: True where every link is shorter than the sum of the others."""
    arr = _lengths_array(lengths, np.asarray(lengths).shape[-1])
    longest = arr.max(axis=1)
    return longest < arr.sum(axis=1) - longest


@record
class FourBarClass:
    """Classification of a batch of four-bar chains with a chosen frame.

    Attributes
    ----------
    code : ndarray of int, shape (N,)
        Index into :data:`TYPES`.
    grashof : ndarray of bool
        s + l <= p + q (change point included).
    change_point : ndarray of bool
        s + l = p + q within the relative tolerance.
    crank_mask : ndarray of bool, shape (N, 4)
        ``crank_mask[i, k-1]``: link *k* turns fully relative to the frame
        (the frame itself is never marked).
    longest, shortest : ndarray of int
        Link numbers (1..4) of the longest and shortest link (first on ties).
    excess : ndarray of float
        (s + l) - (p + q) [m]; <= 0 for a Grashof chain.
    """

    code: np.ndarray
    grashof: np.ndarray
    change_point: np.ndarray
    crank_mask: np.ndarray
    longest: np.ndarray
    shortest: np.ndarray
    excess: np.ndarray

    @property
    def types(self) -> List[str]:
        """Type names as a list of str."""
        return [TYPES[c] for c in self.code.tolist()]

    def cranks(self, i: int = 0) -> List[int]:
        """Link numbers of the cranks of length set *i*."""
        return [k + 1 for k in np.flatnonzero(self.crank_mask[i]).tolist()]


def classify_fourbar(lengths: ArrayLike, frame: ArrayLike = 4, crossed: ArrayLike = False,
                     rtol: float = CHANGE_POINT_RTOL) -> FourBarClass:
    """Classify four-bar chains (crank-rocker, double-crank, double-rocker, ...).

    Parameters
    ----------
    lengths : array_like, shape (4,) or (N, 4)
        l1..l4 in loop order [m] (any consistent unit).
    frame : int or array of int, shape (N,)
        Link number (1..4) of the frame.
    crossed : bool or array of bool
        Crossed assembly; only changes a parallelogram into an antiparallelogram.
    rtol : float
        Relative tolerance of the change-point test ``|s + l - p - q| <= rtol (s + l)``.

    Returns
    -------
    FourBarClass

    Notes
    -----
    Book eqs. (3-1), (3-2) and the four steps of fig. 3-2 (例 3-1): if s + l > p + q
    every pair is a rocking pair and the chain is a double rocker whatever the
    frame; otherwise the two pairs of the shortest link turn fully, so the frame
    being the shortest link gives a double crank, the shortest link next to the
    frame a crank-rocker (the shortest link is the crank), the shortest link
    opposite the frame a double rocker.  Two pairs of equal opposite links give
    a parallelogram (antiparallelogram when crossed); s + l = p + q otherwise
    is named a change point (the chain can fold flat).  Lengths are not
    checked for closure here: see :func:`check_closure`.
    """
    L = _lengths_array(lengths, 4)
    n = L.shape[0]
    frame = np.broadcast_to(np.asarray(frame, dtype=int), (n,))
    crossed = np.broadcast_to(np.asarray(crossed, dtype=bool), (n,))
    srt = np.sort(L, axis=1)
    s, p, q, lng = srt[:, 0], srt[:, 1], srt[:, 2], srt[:, 3]
    excess = (s + lng) - (p + q)
    change = np.abs(excess) <= rtol * (s + lng)
    grashof = (excess <= 0) | change

    rows = np.arange(n)
    f0 = frame - 1
    adj_a = (f0 + 1) % 4
    adj_b = (f0 + 3) % 4
    tol = rtol * (s + lng)
    is_short = np.abs(L - s[:, None]) <= tol[:, None]
    frame_short = is_short[rows, f0]
    a_short = is_short[rows, adj_a]
    b_short = is_short[rows, adj_b]
    parallel = (np.abs(L[:, 0] - L[:, 2]) <= tol) & (np.abs(L[:, 1] - L[:, 3]) <= tol)

    crank_mask = np.zeros((n, 4), dtype=bool)
    both = grashof & (frame_short | parallel)
    crank_mask[rows, adj_a] = both | (grashof & a_short)
    crank_mask[rows, adj_b] = both | (grashof & b_short)

    code = np.full(n, _CODE["double_rocker"])
    dc = grashof & (frame_short | parallel)
    cr = grashof & ~dc & (a_short | b_short)
    code[cr] = _CODE["crank_rocker"]
    code[dc] = _CODE["double_crank"]
    cp = change & ~parallel
    code[cp & (code == _CODE["crank_rocker"])] = _CODE["change_point_crank_rocker"]
    code[cp & (code == _CODE["double_crank"])] = _CODE["change_point_double_crank"]
    code[cp & grashof & ~dc & ~cr] = _CODE["change_point_double_rocker"]
    code[parallel & ~crossed] = _CODE["parallelogram"]
    code[parallel & crossed] = _CODE["antiparallelogram"]
    return FourBarClass(code=code, grashof=grashof, change_point=change,
                        crank_mask=crank_mask, longest=np.argmax(L, axis=1) + 1,
                        shortest=np.argmin(L, axis=1) + 1, excess=excess)


def classify_inversions(lengths: ArrayLike, rtol: float = CHANGE_POINT_RTOL,
                        crossed: bool = False) -> List[FourBarClass]:
    """The type of the chain for each of the four choices of frame.

    Parameters
    ----------
    lengths : array_like, shape (4,) or (N, 4)
        l1..l4 [m].
    crossed : bool or array of bool
        Crossed assembly: a parallelogram chain is an antiparallelogram whichever
        link is the frame.

    Returns
    -------
    list of FourBarClass
        Element ``k-1`` has link *k* as the frame.

    Notes
    -----
    Kinematic inversion (slides §2-1 "倒置法"): a Grashof chain gives two
    crank-rockers, one double crank and one double rocker.
    """
    return [classify_fourbar(lengths, frame=k, crossed=crossed, rtol=rtol) for k in (1, 2, 3, 4)]


def _acos(x: ArrayLike) -> np.ndarray:
    return np.arccos(np.clip(x, -1.0, 1.0))


def _wrap(angle: ArrayLike) -> np.ndarray:
    return np.mod(angle, 2 * np.pi)


@record
class FourBarMerit:
    """Figures of merit of driven four-bars (arrays over the batch, radians).

    Lengths ``a`` input, ``b`` coupler, ``c`` output, ``d`` frame.  Entries
    that do not exist for a length set (no limit positions for a double
    crank, say) are masked by the boolean ``has_*`` arrays and hold 0.

    Attributes
    ----------
    input_turns, output_turns : ndarray of bool
        The input (output) link turns fully relative to the frame.
    has_limits : ndarray of bool
        Crank-rocker driven by its crank: the output has two limit positions
        and θ, ψ, K exist.
    theta1_ext, theta1_fold : ndarray
        Input angle at the extended (crank and coupler in line, C farthest
        from A) and folded limit positions [rad, 0..2π).
    theta3_ext, theta3_fold : ndarray
        Output angle at those positions [rad, 0..2π).
    theta : ndarray
        Limit-position angle θ (crank angle between the two limit positions
        minus π, absolute value) [rad].
    psi : ndarray
        Output swing ψ [rad].
    K : ndarray
        Time ratio (π + θ)/(π − θ).
    input_lo, input_hi : ndarray
        Input angle range [rad] when the input is a rocker (0, 2π if it turns).
    gamma_min, gamma_max : ndarray
        Extreme transmission angles over the input's motion [rad].
    gamma_min_at, gamma_max_at : ndarray
        Input angle where they occur [rad, 0..π, the mirror 2π − x also].
    has_gamma0, has_gamma180 : ndarray of bool
        The input reaches θ1 = 0 (π) (crank along (against) the frame line).
    gamma0, gamma180 : ndarray
        Transmission angle at θ1 = 0 and θ1 = π (book eq. 3-49) [rad].
    dead_output : ndarray of bool, shape (N, 2)
        Dead point when the output drives: input and coupler in line, extended
        (column 0) and folded (column 1), reachable in the assembly.
    dead_theta3 : ndarray, shape (N, 2)
        Output angles at those dead points [rad, C above AD].
    """

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    input_turns: np.ndarray
    output_turns: np.ndarray
    has_limits: np.ndarray
    theta1_ext: np.ndarray
    theta1_fold: np.ndarray
    theta3_ext: np.ndarray
    theta3_fold: np.ndarray
    theta: np.ndarray
    psi: np.ndarray
    K: np.ndarray
    input_lo: np.ndarray
    input_hi: np.ndarray
    gamma_min: np.ndarray
    gamma_min_at: np.ndarray
    gamma_max: np.ndarray
    gamma_max_at: np.ndarray
    has_gamma0: np.ndarray
    has_gamma180: np.ndarray
    gamma0: np.ndarray
    gamma180: np.ndarray
    dead_output: np.ndarray
    dead_theta3: np.ndarray


def _output_angle(ac: np.ndarray, phi: ArrayLike, c: ArrayLike, d: ArrayLike) -> np.ndarray:
    """Angle of DC [rad] for C at distance *ac* from A in direction *phi*."""
    cx = ac * np.cos(phi) - d
    cy = ac * np.sin(phi)
    return _wrap(np.arctan2(cy, cx))


def fourbar_merit(a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike, input_turns: ArrayLike,
                  output_turns: ArrayLike) -> FourBarMerit:
    """Limit positions, θ, ψ, K, transmission angles and dead points.

    Parameters
    ----------
    a, b, c, d : array_like
        Input, coupler, output and frame lengths [m] (broadcast together).
    input_turns, output_turns : array_like of bool
        Whether input and output turn fully (from :func:`classify_fourbar`).

    Returns
    -------
    FourBarMerit

    Notes
    -----
    Limit positions: crank and coupler in line, AC = b + a (extended) and
    AC = b − a (folded); the triangle ACD gives the directions (law of
    cosines), θ = ∠C1AC2, K = (180° + θ)/(180° − θ) (slides §2-2, book
    eq. 3-39 inverted).  Transmission angle γ = ∠BCD folded into [0, 90°]:
    cos∠BCD = (b² + c² − BD²)/(2bc), BD² = a² + d² − 2ad cos θ1, so γ is
    extreme at θ1 = 0 or π (book eq. 3-49, fig. 3-19) or at the ends of a
    rocking input's range, and 90° where BD² = b² + c².  All exact, no sampling.
    """
    a, b, c, d = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float))
                                       for x in (a, b, c, d)))
    tin = np.broadcast_to(np.asarray(input_turns, dtype=bool), a.shape)
    tout = np.broadcast_to(np.asarray(output_turns, dtype=bool), a.shape)
    has_limits = tin & ~tout

    # limit positions (meaningful where has_limits)
    ac_e = b + a
    ac_f = np.abs(b - a)
    den_e = 2 * ac_e * d
    den_f = np.where(ac_f > 0, 2 * ac_f * d, 1.0)
    phi_e = _acos((ac_e ** 2 + d ** 2 - c ** 2) / den_e)
    phi_f = _acos((ac_f ** 2 + d ** 2 - c ** 2) / den_f)
    theta1_e = _wrap(phi_e)
    theta1_f = _wrap(phi_f + np.pi)
    theta3_e = _output_angle(ac_e, phi_e, c, d)
    theta3_f = _output_angle(ac_f, phi_f, c, d)
    theta = np.abs(phi_f - phi_e)
    dpsi = np.abs(theta3_e - theta3_f)
    psi = np.minimum(dpsi, 2 * np.pi - dpsi)
    K = (np.pi + theta) / (np.pi - np.minimum(theta, np.pi * (1 - 1e-15)))
    zero = np.zeros_like(a)
    theta1_e, theta1_f, theta3_e, theta3_f, theta, psi, K = (
        np.where(has_limits, x, zero) for x in (theta1_e, theta1_f, theta3_e, theta3_f,
                                                  theta, psi, K))

    # range of BD over the input's motion
    bd_lo = np.abs(d - a)
    bd_hi = d + a
    lo = np.maximum(bd_lo, np.abs(b - c))
    hi = np.minimum(bd_hi, b + c)
    lo = np.where(tin, bd_lo, lo)
    hi = np.where(tin, bd_hi, hi)
    two_ad = 2 * a * d
    th_lo = _acos((a ** 2 + d ** 2 - lo ** 2) / two_ad)
    th_hi = _acos((a ** 2 + d ** 2 - hi ** 2) / two_ad)
    input_lo = np.where(tin, 0.0, th_lo)
    input_hi = np.where(tin, 2 * np.pi, th_hi)

    def gamma_of(bd: np.ndarray) -> np.ndarray:
        delta = _acos((b ** 2 + c ** 2 - bd ** 2) / (2 * b * c))
        return np.minimum(delta, np.pi - delta)

    g_lo, g_hi = gamma_of(lo), gamma_of(hi)
    gamma_min = np.minimum(g_lo, g_hi)
    gamma_min_at = np.where(g_lo <= g_hi, th_lo, th_hi)
    right = b ** 2 + c ** 2
    spans = (lo ** 2 <= right) & (right <= hi ** 2)
    th_right = _acos((a ** 2 + d ** 2 - right) / two_ad)
    gamma_max = np.where(spans, np.pi / 2, np.maximum(g_lo, g_hi))
    gamma_max_at = np.where(spans, th_right, np.where(g_lo >= g_hi, th_lo, th_hi))
    has_g0 = tin | (lo <= bd_lo * (1 + 1e-12))
    has_g180 = tin | (hi >= bd_hi * (1 - 1e-12))
    gamma0 = np.where(has_g0, gamma_of(bd_lo), zero)
    gamma180 = np.where(has_g180, gamma_of(bd_hi), zero)

    # dead points with the output driving: input and coupler in line, if C can be there
    c_lo, c_hi = np.abs(d - c), d + c
    dead = np.stack([(ac_e >= c_lo) & (ac_e <= c_hi), (ac_f >= c_lo) & (ac_f <= c_hi)], axis=1)
    dead &= ~tout[:, None]
    dead_th3 = np.where(dead, np.stack([_output_angle(ac_e, phi_e, c, d),
                                        _output_angle(ac_f, phi_f, c, d)], axis=1), 0.0)
    return FourBarMerit(a=a, b=b, c=c, d=d, input_turns=tin, output_turns=tout,
                        has_limits=has_limits, theta1_ext=theta1_e, theta1_fold=theta1_f,
                        theta3_ext=theta3_e, theta3_fold=theta3_f, theta=theta, psi=psi, K=K,
                        input_lo=input_lo, input_hi=input_hi, gamma_min=gamma_min,
                        gamma_min_at=gamma_min_at, gamma_max=gamma_max,
                        gamma_max_at=gamma_max_at, has_gamma0=has_g0, has_gamma180=has_g180,
                        gamma0=gamma0, gamma180=gamma180, dead_output=dead,
                        dead_theta3=dead_th3)


@record
class FourBarAnalysis:
    """One or many four-bars: lengths, frame/input choice, class and merit.

    Attributes
    ----------
    lengths : ndarray, shape (N, 4)
        l1..l4 [m].
    frame, input : ndarray of int
        Link numbers.
    coupler, output : ndarray of int
        Derived link numbers.
    klass : FourBarClass
    merit : FourBarMerit
    """

    lengths: np.ndarray
    frame: np.ndarray
    input: np.ndarray
    coupler: np.ndarray
    output: np.ndarray
    klass: FourBarClass
    merit: FourBarMerit


def analyse_fourbar(lengths: ArrayLike, frame: ArrayLike = 4, input_link: ArrayLike = 1,
                    crossed: ArrayLike = False, rtol: float = CHANGE_POINT_RTOL,
                    require_closure: bool = True) -> FourBarAnalysis:
    """Classify four-bars and compute their figures of merit (vectorized).

    Parameters
    ----------
    lengths : array_like, shape (4,) or (N, 4)
        l1..l4 [m].
    frame, input_link : int or array of int
        Frame and input link numbers; the input must be joined to the frame.
    crossed : bool or array of bool
        Crossed assembly (parallelogram -> antiparallelogram).
    rtol : float
        Change-point tolerance (relative).
    require_closure : bool
        Raise :class:`ClosureError` if a set cannot close (else those rows
        are classified but their merit is meaningless; see :func:`closes`).

    Returns
    -------
    FourBarAnalysis

    Raises
    ------
    ClosureError
        A link is not shorter than the sum of the others.
    ValueError
        An input link that is not joined to the frame.
    """
    L = _lengths_array(lengths, 4)
    n = L.shape[0]
    if require_closure:
        check_closure(L)
    frame = np.broadcast_to(np.asarray(frame, dtype=int), (n,)).copy()
    inp = np.broadcast_to(np.asarray(input_link, dtype=int), (n,)).copy()
    f0 = frame - 1
    nb1, nb2 = (f0 + 1) % 4, (f0 + 3) % 4
    i0 = inp - 1
    if np.any((i0 != nb1) & (i0 != nb2)):
        raise ValueError("the input link must be joined to the frame")
    o0 = np.where(i0 == nb1, nb2, nb1)
    c0 = (f0 + 2) % 4
    klass = classify_fourbar(L, frame, crossed, rtol)
    rows = np.arange(n)
    merit = fourbar_merit(L[rows, i0], L[rows, c0], L[rows, o0], L[rows, f0],
                          klass.crank_mask[rows, i0], klass.crank_mask[rows, o0])
    return FourBarAnalysis(lengths=L, frame=frame, input=inp, coupler=c0 + 1, output=o0 + 1,
                           klass=klass, merit=merit)


# ------------------------------------------------------------ transmission curves
@record
class TransmissionCurve:
    """Transmission angle against the input angle (传动角的变化规律).

    Attributes
    ----------
    theta1 : ndarray
        Input angles [rad].
    gamma : ndarray
        Acute transmission angle [rad] (0 where ``feasible`` is False).
    feasible : ndarray of bool
        The linkage assembles at that input angle.
    """

    theta1: np.ndarray
    gamma: np.ndarray
    feasible: np.ndarray


def fourbar_transmission(a: FloatOrArray, b: FloatOrArray, c: FloatOrArray, d: FloatOrArray,
                         theta1: ArrayLike) -> TransmissionCurve:
    """γ(θ1) of a four-bar: input a, coupler b, output c, frame d [m].

    Notes
    -----
    cos∠BCD = (b² + c² − BD²)/(2bc), BD² = a² + d² − 2ad cos θ1 (both
    assemblies have the same γ); γ is ∠BCD folded into [0, 90°] (slides §2-2).
    """
    th = np.asarray(theta1, dtype=float)
    bd2 = a * a + d * d - 2 * a * d * np.cos(th)
    cosd = (b * b + c * c - bd2) / (2 * b * c)
    ok = np.abs(cosd) <= 1 + 1e-12
    delta = _acos(cosd)
    gamma = np.where(ok, np.minimum(delta, np.pi - delta), 0.0)
    return TransmissionCurve(th, gamma, ok)


def slider_transmission(a: FloatOrArray, b: FloatOrArray, e: FloatOrArray,
                        theta1: ArrayLike) -> TransmissionCurve:
    """γ(θ1) on the slider of an offset slider-crank (γ = 90° − pressure angle).

    Notes
    -----
    sin α = |a sin θ1 − e| / b: the coupler's angle to the slider path (path y = e).
    """
    th = np.asarray(theta1, dtype=float)
    s = np.abs(a * np.sin(th) - e) / b
    ok = s <= 1 + 1e-12
    gamma = np.where(ok, np.pi / 2 - np.arcsin(np.minimum(s, 1.0)), 0.0)
    return TransmissionCurve(th, gamma, ok)


def guide_transmission(a: FloatOrArray, d: FloatOrArray, e: float,
                       theta1: ArrayLike) -> TransmissionCurve:
    """γ(θ1) on the guide of a guide-bar, crank a about A = (0, 0), guide pivot C = (d, 0).

    Notes
    -----
    γ = 90° − arcsin(e/CB), CB² = a² + d² − 2ad cos θ1 (see :func:`analyse_guide_bar`).
    """
    th = np.asarray(theta1, dtype=float)
    cb = np.sqrt(np.maximum(a * a + d * d - 2 * a * d * np.cos(th), 0.0))
    ok = cb >= abs(e) * (1 - 1e-12)
    ratio = np.where(ok & (cb > 0), abs(e) / np.where(cb > 0, cb, 1.0), 0.0)
    gamma = np.where(ok, np.pi / 2 - np.arcsin(np.minimum(ratio, 1.0)), 0.0)
    return TransmissionCurve(th, gamma, ok)


__all__ = ["CHANGE_POINT_RTOL", "TYPES", "ClosureError", "UnsolvableError", "check_closure",
           "closes", "FourBarClass", "classify_fourbar", "classify_inversions", "driven_links",
           "FourBarMerit", "fourbar_merit", "FourBarAnalysis", "analyse_fourbar", "LengthRange",
           "length_ranges", "SliderCrank", "analyse_slider_crank", "GuideBar",
           "analyse_guide_bar", "TransmissionCurve", "fourbar_transmission",
           "slider_transmission", "guide_transmission"]
