"""One four-bar chain, slider-crank or guide-bar: type and figures of merit in pure Python.

``mechcli grashof --lengths`` classifies four numbers: importing numpy for them
would cost more than everything else the command does.  This module is the
scalar twin of :mod:`.fourbar` (the vectorized form for batches, type charts
and synthesis) and imports nothing but :mod:`math`, :mod:`typing` and
:mod:`mechcli.core.errors`; the two are checked against each other in
``tests/unit/grashof/test_speed_grashof_scalar.py``.  Its results are named tuples, not
dataclasses: a frozen dataclass costs about 1 ms of start-up to create, a named
tuple a twentieth of that.

Conventions as in :mod:`.fourbar` (book chapter 3 §1, fig. 3-1): links 1..4
around the loop, the default frame link 4 and input link 1; the input pivot A
at the origin, the output pivot D on +x, C above AD (the "open" assembly);
angles counter-clockwise from +x, in radians.
"""

from __future__ import annotations

import math
from typing import List, NamedTuple, Optional, Sequence, Tuple

from mechcli.core.errors import UnsolvableError

#: type names, index = integer type code used in batch arrays
TYPES = (
    "crank_rocker",
    "double_crank",
    "double_rocker",
    "parallelogram",
    "antiparallelogram",
    "change_point_crank_rocker",
    "change_point_double_crank",
    "change_point_double_rocker",
)
_CODE = {name: i for i, name in enumerate(TYPES)}

#: default relative tolerance of the change-point test s + l = p + q
CHANGE_POINT_RTOL = 1e-9

_TWO_PI = 2 * math.pi


class ClosureError(UnsolvableError):
    """The lengths cannot form a closed loop (one link as long as all others together).

    The message holds no numbers with units: the caller words them from the
    attributes (lengths in the unit of the call).

    Attributes
    ----------
    chain : str
        ``"chain"`` (a closed loop of links), ``"slider-crank"``, ``"guide-bar"``
        or ``"RRRRP"``.
    length : float
        The link (``chain``) or the offset that is too long.
    limit : float
        The sum it must be shorter than: the other links; crank + coupler;
        crank + frame; l1 + l2 + l3.
    link : int or None
        Link number of a ``chain``.
    set_index : int or None
        1-based length set, when a batch of several sets was checked.
    """

    def __init__(self, chain: str, length: float, limit: float, link: Optional[int] = None,
                 set_index: Optional[int] = None) -> None:
        what = f"link {link}" if link is not None else "the offset"
        super().__init__(f"the {chain} cannot close: {what} is not shorter than "
                         + ("the sum of the other links" if chain == "chain" else
                            "the sum of the other lengths")
                         + (f" (length set {set_index})" if set_index is not None else ""))
        self.chain, self.length, self.limit = chain, float(length), float(limit)
        self.link, self.set_index = link, set_index


def check_chain_closure(lengths: Sequence[float]) -> bool:
    """Raise :class:`ClosureError` if one link of a chain is at least as long as the others.

    Parameters
    ----------
    lengths : sequence of float
        Link lengths of one closed chain [m, or any unit].

    Notes
    -----
    The scalar form of :func:`.fourbar.check_closure` (which takes batches):
    a closed chain of rigid links can be assembled only if every link is
    shorter than the sum of the others.
    """
    arr = [float(x) for x in lengths]
    longest = max(arr)
    rest = sum(arr) - longest
    if longest >= rest:
        k = arr.index(longest) + 1
        raise ClosureError("chain", longest, rest, link=k)
    return True


def driven_links(frame: int, input_link: int) -> Tuple[int, int, int]:
    """(input, coupler, output) link numbers for a frame and an input next to it.

    Raises
    ------
    ValueError
        If the input is the frame or not joined to it.
    """
    f0 = frame - 1
    nb = ((f0 + 1) % 4 + 1, (f0 + 3) % 4 + 1)
    if input_link not in nb:
        raise ValueError(f"the input link must be joined to the frame {frame}: one of {nb}")
    output = nb[1] if input_link == nb[0] else nb[0]
    coupler = (f0 + 2) % 4 + 1
    return input_link, coupler, output


# ------------------------------------------------------------------ type
class ChainType(NamedTuple):
    """Type of one four-bar chain with a chosen frame (one row of :class:`.fourbar.FourBarClass`).

    Attributes
    ----------
    code : int
        Index into :data:`TYPES`.
    grashof : bool
        s + l <= p + q (change point included).
    change_point : bool
        s + l = p + q within the relative tolerance.
    cranks : tuple of int
        Link numbers that turn fully relative to the frame.
    longest, shortest : int
        Link numbers (1..4) of the longest and shortest link (first on ties).
    excess : float
        (s + l) - (p + q) [m]; <= 0 for a Grashof chain.
    """

    code: int
    grashof: bool
    change_point: bool
    cranks: tuple
    longest: int
    shortest: int
    excess: float

    @property
    def type(self) -> str:
        """Type name, one of :data:`TYPES`."""
        return TYPES[self.code]


def classify_chain(lengths: Sequence[float], frame: int = 4, crossed: bool = False,
                   rtol: float = CHANGE_POINT_RTOL) -> ChainType:
    """Classify one four-bar chain (crank-rocker, double-crank, double-rocker, ...).

    Parameters
    ----------
    lengths : sequence of 4 float
        l1..l4 in loop order [m] (any consistent unit).
    frame : int
        Link number (1..4) of the frame.
    crossed : bool
        Crossed assembly; only changes a parallelogram into an antiparallelogram.
    rtol : float
        Relative tolerance of the change-point test ``|s + l - p - q| <= rtol (s + l)``.

    Returns
    -------
    ChainType

    Notes
    -----
    Book eqs. (3-1), (3-2) and fig. 3-2 (例 3-1); the same arithmetic, in the
    same order, as :func:`.fourbar.classify_fourbar` (see its notes).
    """
    L = [float(x) for x in lengths]
    if len(L) != 4:
        raise ValueError(f"expected 4 lengths, got {len(L)}")
    s, p, q, lng = sorted(L)
    excess = (s + lng) - (p + q)
    tol = rtol * (s + lng)
    change = abs(excess) <= tol
    grashof = excess <= 0 or change
    f0 = int(frame) - 1
    adj_a, adj_b = (f0 + 1) % 4, (f0 + 3) % 4
    is_short = [abs(x - s) <= tol for x in L]
    parallel = abs(L[0] - L[2]) <= tol and abs(L[1] - L[3]) <= tol
    dc = grashof and (is_short[f0] or parallel)
    turns = {adj_a: dc or (grashof and is_short[adj_a]),
             adj_b: dc or (grashof and is_short[adj_b])}
    cr = grashof and not dc and (is_short[adj_a] or is_short[adj_b])
    name = "double_crank" if dc else ("crank_rocker" if cr else "double_rocker")
    if change and not parallel and grashof:
        name = "change_point_" + name
    if parallel:
        name = "antiparallelogram" if crossed else "parallelogram"
    return ChainType(code=_CODE[name], grashof=grashof, change_point=change,
                     cranks=tuple(k + 1 for k in sorted(turns) if turns[k]),
                     longest=L.index(max(L)) + 1, shortest=L.index(min(L)) + 1,
                     excess=excess)


def chain_inversions(lengths: Sequence[float], rtol: float = CHANGE_POINT_RTOL,
                     crossed: bool = False) -> Tuple[ChainType, ...]:
    """The type of one chain for each of the four choices of frame.

    Returns
    -------
    tuple of ChainType
        Element ``k-1`` has link *k* as the frame (slides §2-1 "倒置法").
    """
    return tuple(classify_chain(lengths, k, crossed, rtol) for k in (1, 2, 3, 4))


# --------------------------------------------------------- figures of merit
def _acos(x: float) -> float:
    return math.acos(min(1.0, max(-1.0, x)))


def _output_angle(ac: float, phi: float, d: float) -> float:
    """Angle of DC [rad, 0..2π) for C at distance *ac* from A in direction *phi*."""
    return math.atan2(ac * math.sin(phi), ac * math.cos(phi) - d) % _TWO_PI


class FigureOfMerit(NamedTuple):
    """Figures of merit of one driven four-bar (radians): one row of
    :class:`.fourbar.FourBarMerit`, with the same attribute names and meaning;
    ``dead_output`` and ``dead_theta3`` are pairs (extended, folded)."""

    a: float
    b: float
    c: float
    d: float
    input_turns: bool
    output_turns: bool
    has_limits: bool
    theta1_ext: float
    theta1_fold: float
    theta3_ext: float
    theta3_fold: float
    theta: float
    psi: float
    K: float
    input_lo: float
    input_hi: float
    gamma_min: float
    gamma_min_at: float
    gamma_max: float
    gamma_max_at: float
    has_gamma0: bool
    has_gamma180: bool
    gamma0: float
    gamma180: float
    dead_output: tuple
    dead_theta3: tuple


def figures_of_merit(a: float, b: float, c: float, d: float, input_turns: bool,
                     output_turns: bool) -> FigureOfMerit:
    """Limit positions, θ, ψ, K, transmission angles and dead points of one four-bar.

    Parameters
    ----------
    a, b, c, d : float
        Input, coupler, output and frame lengths [m].
    input_turns, output_turns : bool
        Whether input and output turn fully (from :func:`classify_chain`).

    Returns
    -------
    FigureOfMerit

    Notes
    -----
    The closed forms of :func:`.fourbar.fourbar_merit` (slides §2-2, book
    eqs. 3-39 and 3-49), evaluated for one length set.
    """
    a, b, c, d = float(a), float(b), float(c), float(d)
    tin, tout = bool(input_turns), bool(output_turns)
    has_limits = tin and not tout
    pi = math.pi

    ac_e = b + a
    ac_f = abs(b - a)
    phi_e = _acos((ac_e ** 2 + d ** 2 - c ** 2) / (2 * ac_e * d))
    phi_f = _acos((ac_f ** 2 + d ** 2 - c ** 2) / (2 * ac_f * d if ac_f > 0 else 1.0))
    th3_e = _output_angle(ac_e, phi_e, d)
    th3_f = _output_angle(ac_f, phi_f, d)
    if has_limits:
        theta1_e, theta1_f = phi_e % _TWO_PI, (phi_f + pi) % _TWO_PI
        theta3_e, theta3_f = th3_e, th3_f
        theta = abs(phi_f - phi_e)
        dpsi = abs(theta3_e - theta3_f)
        psi = min(dpsi, 2 * pi - dpsi)
        K = (pi + theta) / (pi - min(theta, pi * (1 - 1e-15)))
    else:
        theta1_e = theta1_f = theta3_e = theta3_f = theta = psi = K = 0.0

    # range of BD over the input's motion
    bd_lo, bd_hi = abs(d - a), d + a
    if tin:
        lo, hi = bd_lo, bd_hi
    else:
        lo, hi = max(bd_lo, abs(b - c)), min(bd_hi, b + c)
    two_ad = 2 * a * d
    th_lo = _acos((a ** 2 + d ** 2 - lo ** 2) / two_ad)
    th_hi = _acos((a ** 2 + d ** 2 - hi ** 2) / two_ad)
    input_lo, input_hi = (0.0, 2 * pi) if tin else (th_lo, th_hi)

    def gamma_of(bd: float) -> float:
        delta = _acos((b ** 2 + c ** 2 - bd ** 2) / (2 * b * c))
        return min(delta, pi - delta)

    g_lo, g_hi = gamma_of(lo), gamma_of(hi)
    gamma_min = min(g_lo, g_hi)
    gamma_min_at = th_lo if g_lo <= g_hi else th_hi
    right = b ** 2 + c ** 2
    if lo ** 2 <= right <= hi ** 2:
        gamma_max, gamma_max_at = pi / 2, _acos((a ** 2 + d ** 2 - right) / two_ad)
    else:
        gamma_max = max(g_lo, g_hi)
        gamma_max_at = th_lo if g_lo >= g_hi else th_hi
    has_g0 = tin or lo <= bd_lo * (1 + 1e-12)
    has_g180 = tin or hi >= bd_hi * (1 - 1e-12)
    gamma0 = gamma_of(bd_lo) if has_g0 else 0.0
    gamma180 = gamma_of(bd_hi) if has_g180 else 0.0

    # dead points with the output driving: input and coupler in line, if C can be there
    c_lo, c_hi = abs(d - c), d + c
    dead = tuple(not tout and c_lo <= ac <= c_hi for ac in (ac_e, ac_f))
    dead_th3 = tuple(t if k else 0.0 for t, k in zip((th3_e, th3_f), dead))
    return FigureOfMerit(a=a, b=b, c=c, d=d, input_turns=tin, output_turns=tout,
                         has_limits=has_limits, theta1_ext=theta1_e, theta1_fold=theta1_f,
                         theta3_ext=theta3_e, theta3_fold=theta3_f, theta=theta, psi=psi, K=K,
                         input_lo=input_lo, input_hi=input_hi, gamma_min=gamma_min,
                         gamma_min_at=gamma_min_at, gamma_max=gamma_max,
                         gamma_max_at=gamma_max_at, has_gamma0=has_g0, has_gamma180=has_g180,
                         gamma0=gamma0, gamma180=gamma180, dead_output=dead,
                         dead_theta3=dead_th3)


class FourBarChain(NamedTuple):
    """One four-bar: lengths, frame/input choice, type and figures of merit.

    Attributes
    ----------
    lengths : tuple of 4 float
        l1..l4 [m].
    frame, input, coupler, output : int
        Link numbers.
    klass : ChainType
    merit : FigureOfMerit
    """

    lengths: tuple
    frame: int
    input: int
    coupler: int
    output: int
    klass: ChainType
    merit: FigureOfMerit


def analyse_chain(lengths: Sequence[float], frame: int = 4, input_link: int = 1,
                  crossed: bool = False, rtol: float = CHANGE_POINT_RTOL) -> FourBarChain:
    """Classify one four-bar and compute its figures of merit (the scalar
    :func:`.fourbar.analyse_fourbar`).

    Parameters
    ----------
    lengths : sequence of 4 float
        l1..l4 [m].
    frame, input_link : int
        Frame and input link numbers; the input must be joined to the frame.
    crossed : bool
        Crossed assembly (parallelogram -> antiparallelogram).
    rtol : float
        Change-point tolerance (relative).

    Returns
    -------
    FourBarChain

    Raises
    ------
    ClosureError
        A link is not shorter than the sum of the others.
    ValueError
        An input link that is not joined to the frame.
    """
    L = tuple(float(x) for x in lengths)
    check_chain_closure(L)
    frame, inp = int(frame), int(input_link)
    try:
        i, c, o = driven_links(frame, inp)
    except ValueError:
        raise ValueError("the input link must be joined to the frame") from None
    klass = classify_chain(L, frame, crossed, rtol)
    merit = figures_of_merit(L[i - 1], L[c - 1], L[o - 1], L[frame - 1],
                             i in klass.cranks, o in klass.cranks)
    return FourBarChain(lengths=L, frame=frame, input=i, coupler=c, output=o, klass=klass,
                        merit=merit)


# --------------------------------------------------------------------------- ranges
class LengthRange(NamedTuple):
    """One interval of a varied link length with a constant type.

    Attributes
    ----------
    type : str
        Basic type (change-point ends are folded into the neighbouring type).
    crank : int or None
        The crank link of a crank-rocker.
    lo, hi : float
        Interval ends [m].
    lo_closed, hi_closed : bool
        Whether the ends belong to the interval.
    """

    type: str
    crank: int | None
    lo: float
    hi: float
    lo_closed: bool
    hi_closed: bool


_BASIC = {"change_point_crank_rocker": "crank_rocker",
          "change_point_double_crank": "double_crank",
          "change_point_double_rocker": "double_rocker"}


def length_ranges(lengths: Sequence[float], vary: int, frame: int = 4,
                  rtol: float = CHANGE_POINT_RTOL) -> List[LengthRange]:
    """Intervals of one link's length giving each type, the other three fixed.

    Parameters
    ----------
    lengths : sequence of 4 float
        l1..l4 [m]; the entry of the varied link is ignored.
    vary : int
        Link number (1..4) whose length varies over (0, sum of the others).
    frame : int
        Frame link number.

    Returns
    -------
    list of LengthRange
        Adjacent, covering (0, sum of the others); a change point s + l = p + q
        belongs to the neighbouring Grashof type (book eq. 3-1 has "<="), a
        parallelogram is a one-point interval of its own.

    Notes
    -----
    The type can only change where the varied length equals another length
    (the shortest/longest link changes) or where s + l = p + q; those
    candidate points split (0, Σ) into pieces whose type is constant and is
    read at the midpoint (slides exam problems 2 and 4; Hrones–Nelson's
    ranges example).
    """
    fixed = [float(x) for k, x in enumerate(lengths) if k != vary - 1]
    total = sum(fixed)
    cand = {0.0, total}
    cand.update(fixed)
    for i in range(3):
        j, k = [m for m in range(3) if m != i]
        for x in (fixed[j] + fixed[k] - fixed[i], fixed[i] + fixed[j] - fixed[k],
                  fixed[i] + fixed[k] - fixed[j]):
            if 0 < x < total:
                cand.add(x)
    pts = sorted(cand)
    base = [float(x) for x in lengths]

    def label(x: float) -> Tuple[str, Optional[int]]:
        L = list(base)
        L[vary - 1] = x
        kl = classify_chain(L, frame=frame, rtol=rtol)
        name = _BASIC.get(kl.type, kl.type)
        return name, (kl.cranks[0] if name == "crank_rocker" and kl.cranks else None)

    # walk left to right: piece, point, piece, point, ...
    seq = []
    for u, v in zip(pts[:-1], pts[1:]):
        if v - u > rtol * total:
            seq.append(("open", u, v, label((u + v) / 2)))
        if 0 < v < total:
            seq.append(("point", v, v, label(v)))
    out: List[LengthRange] = []
    for kind, u, v, lab in seq:
        if out and (out[-1].type, out[-1].crank) == lab:
            prev = out[-1]
            out[-1] = prev._replace(hi=v, hi_closed=(kind == "point"))
            continue
        out.append(LengthRange(type=lab[0], crank=lab[1], lo=u, hi=v,
                               lo_closed=(kind == "point"), hi_closed=(kind == "point")))
    return out


# ---------------------------------------------------------------- slider-crank, guide-bar
class SliderCrank(NamedTuple):
    """Offset slider-crank: crank a about A, coupler b, slider pin on the line y = e.

    Attributes
    ----------
    crank_exists : bool
        a + |e| <= b.
    boundary : bool
        a + |e| = b within tolerance (the coupler reaches 90° to the guide).
    stroke : float
        H [m].
    x_ext, x_fold : float
        Slider positions at the limit (dead) positions [m].
    theta1_ext, theta1_fold : float
        Crank angles there [rad].
    theta, K : float
        Limit-position angle [rad] and time ratio.
    alpha_max, alpha_max_at : float
        Maximum pressure angle on the slider (crank driving) and the crank
        angle where it occurs [rad].
    """

    a: float
    b: float
    e: float
    crank_exists: bool
    boundary: bool
    stroke: float
    x_ext: float
    x_fold: float
    theta1_ext: float
    theta1_fold: float
    theta: float
    K: float
    alpha_max: float
    alpha_max_at: float


def analyse_slider_crank(a: float, b: float, e: float = 0.0,
                         rtol: float = CHANGE_POINT_RTOL) -> SliderCrank:
    """Crank condition, stroke, θ, K and pressure angle of an offset slider-crank.

    Parameters
    ----------
    a, b : float
        Crank and coupler lengths [m].
    e : float
        Offset of the slider path from the crank pivot [m] (path y = e).

    Returns
    -------
    SliderCrank

    Raises
    ------
    ClosureError
        |e| >= a + b: the coupler never reaches the slider path.

    Notes
    -----
    Slides §2-2: the crank exists iff a + e <= b.  Limit positions with crank
    and coupler in line: x = sqrt((b ± a)² − e²), θ = |arcsin(e/(b − a)) −
    arcsin(e/(b + a))|, H = x_ext − x_fold, K = (π + θ)/(π − θ).  The pressure
    angle on the slider is the angle of the coupler to the path,
    sin α = (a sin θ1 − e)/b, greatest at θ1 = 270° (e >= 0) where
    sin α = (a + e)/b.  Exam problem 3 of the slides (a = 20, b = 60, K = 2,
    H = 69.28) has e = 40 = b − a: the boundary case.
    """
    a, b, e = float(a), float(b), float(e)
    if abs(e) >= a + b:
        raise ClosureError("slider-crank", abs(e), a + b)
    slack = b - (a + abs(e))
    boundary = abs(slack) <= rtol * (a + b)
    exists = slack >= 0 or boundary
    if not exists:
        return SliderCrank(a, b, e, False, False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    s_e = e / (a + b)
    s_f = min(1.0, max(-1.0, e / (b - a))) if b > a else 0.0
    x_e = math.sqrt(max((a + b) ** 2 - e ** 2, 0.0))
    x_f = math.sqrt(max((b - a) ** 2 - e ** 2, 0.0))
    t_e, t_f = math.asin(s_e), math.asin(s_f)
    theta = abs(t_f - t_e)
    K = (math.pi + theta) / (math.pi - theta)
    alpha_max = math.asin(min(1.0, (a + abs(e)) / b))
    at = 1.5 * math.pi if e >= 0 else 0.5 * math.pi
    return SliderCrank(a, b, e, True, bool(boundary), x_e - x_f, x_e, x_f,
                       t_e % _TWO_PI, (t_f + math.pi) % _TWO_PI, theta, K, alpha_max, at)


class GuideBar(NamedTuple):
    """Guide-bar (导杆机构): crank a about A, guide pivoted at C, frame AC = d.

    Attributes
    ----------
    kind : str
        ``oscillating``, ``rotating``, ``boundary`` (a + e = d or d + e = a)
        or ``no_crank`` (|d − a| < e: the crank cannot turn).
    theta, psi, K : float
        For an oscillating guide: θ = ψ [rad] and the time ratio (K = 0 when
        θ = 180°, the boundary a = d, where it is unbounded).
    gamma_min, gamma_max : float
        Transmission angle on the guide, crank driving [rad]: 90° − arcsin(e/CB).
    """

    a: float
    d: float
    e: float
    kind: str
    theta: float
    psi: float
    K: float
    gamma_min: float
    gamma_max: float


def analyse_guide_bar(a: float, d: float, e: float = 0.0,
                      rtol: float = CHANGE_POINT_RTOL) -> GuideBar:
    """Oscillating or rotating guide, θ = ψ, K and transmission angle.

    Parameters
    ----------
    a : float
        Crank length AB [m].
    d : float
        Frame length AC (crank pivot to guide pivot) [m].
    e : float
        Offset of the guide line from its pivot C [m] (0: the guide passes through C).

    Returns
    -------
    GuideBar

    Raises
    ------
    ClosureError
        e >= a + d: the guide line never comes near enough to the crank pin B.

    Notes
    -----
    Slides §2-2: a + e <= d gives an oscillating guide (crank exists, the guide
    rocks), d + e <= a a rotating guide.  Extreme guide directions where the
    guide line touches the crank circle: cos β = (±a − e)/d, hence
    ψ = arccos((−a − e)/d) − arccos((a − e)/d) and θ = ψ (the crank is normal
    to the guide at both limits); for e = 0, ψ = 2 arcsin(a/d).  The force of
    the block on the guide is normal to the guide and the velocity of the
    guide's point at B is normal to CB, so γ = 90° − arcsin(e/CB), CB between
    |d − a| and d + a.  Slides fill-in 1: ψ = 30° gives K = 1.4.
    """
    a, d, e = float(a), float(d), abs(float(e))
    if e >= a + d:
        raise ClosureError("guide-bar", e, a + d)
    tol = rtol * (a + d)
    if a + e < d - tol:
        kind = "oscillating"
    elif d + e < a - tol:
        kind = "rotating"
    elif abs(a + e - d) <= tol or abs(d + e - a) <= tol:
        kind = "boundary"
    else:
        kind = "no_crank"
    theta = psi = 0.0
    K = 1.0
    if kind == "oscillating" or (kind == "boundary" and a <= d):
        lo = _acos((a - e) / d)
        hi = _acos((-a - e) / d)
        theta = psi = hi - lo
        # a boundary guide-bar (a = d, e = 0) swings 180°: K is unbounded, reported as 0
        K = (math.pi + theta) / (math.pi - theta) if theta < math.pi * (1 - 1e-9) else 0.0
    if kind == "no_crank":
        return GuideBar(a, d, e, kind, 0.0, 0.0, 0.0, 0.0, 0.0)
    cb_lo, cb_hi = abs(d - a), d + a
    g_min = math.pi / 2 - math.asin(min(1.0, e / cb_lo)) if cb_lo > 0 else 0.0
    g_max = math.pi / 2 - math.asin(min(1.0, e / cb_hi))
    return GuideBar(a, d, e, kind, theta, psi, K, g_min, g_max)


__all__ = ["CHANGE_POINT_RTOL", "TYPES", "ChainType", "ClosureError", "FigureOfMerit",
           "FourBarChain", "GuideBar", "LengthRange", "SliderCrank", "analyse_chain",
           "analyse_guide_bar", "analyse_slider_crank", "chain_inversions",
           "check_chain_closure", "classify_chain", "driven_links", "figures_of_merit",
           "length_ranges"]
