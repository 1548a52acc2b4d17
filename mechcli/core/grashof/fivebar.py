"""Type of a 5R five-bar (2 DOF) and the crank condition of the RRRRP five-bar.

Source: 李辉, 张策, 孟宪举, 《平面五杆机构类型判别方法的研究》, 机械设计 2002(5)
("the paper").  Links are numbered 1..5 around the loop (link *k* joined to
*k-1* and *k+1*, 5 joined to 1); the default frame is link 5 and the two
inputs are the links joined to the frame (1 and 4).  Only numpy is used.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, List, Tuple

import numpy as np

from mechcli.core.errors import UnsolvableError
from mechcli.core.grashof.chain import CHANGE_POINT_RTOL, ClosureError
from mechcli.core.grashof.fourbar import check_closure
from mechcli.core.records import record

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

FIVEBAR_TYPES = ("triple_crank", "double_crank", "single_crank", "no_crank")


def fivebar_roles(frame: int) -> Tuple[int, int, int, int]:
    """(input_1, input_2, coupler_1, coupler_2) link numbers for a frame link.

    ``input_1`` is the link after the frame in the loop, ``coupler_1`` is
    joined to ``input_1``; for the default frame 5: (1, 4, 2, 3).
    """
    f0 = frame - 1
    return ((f0 + 1) % 5 + 1, (f0 + 4) % 5 + 1, (f0 + 2) % 5 + 1, (f0 + 3) % 5 + 1)


def joint_revolvable(lengths: ArrayLike, j: int, k: int,
                     rtol: float = CHANGE_POINT_RTOL) -> np.ndarray:
    """Whether adjacent links *j* and *k* of a closed 5R chain turn fully relative to each other.

    Parameters
    ----------
    lengths : ndarray, shape (N, 5)
        l1..l5 [m].
    j, k : int
        Adjacent link numbers.

    Returns
    -------
    ndarray of bool

    Notes
    -----
    The free ends of links j and k are |l_j − l_k| .. l_j + l_k apart as the
    joint turns; the open chain of the other three links reaches exactly the
    distances max(0, 2 l_max' − Σ') .. Σ'.  The joint turns fully iff the first
    interval lies inside the second (the classical revolvability argument of
    the paper's §1 applied to one joint).  Checked against winding loops of an
    engine sweep of both inputs in the tests.
    """
    L = np.asarray(lengths, dtype=float)
    rest = [m for m in range(5) if m not in (j - 1, k - 1)]
    others = L[:, rest]
    total = others.sum(axis=1)
    reach_min = np.maximum(0.0, 2 * others.max(axis=1) - total)
    lj, lk = L[:, j - 1], L[:, k - 1]
    tol = rtol * total
    return (lj + lk <= total + tol) & (np.abs(lj - lk) >= reach_min - tol)


@record
class FiveBarClass:
    """Classification of 5R five-bars (arrays over the batch).

    Attributes
    ----------
    klass : ndarray of int
        1 (class I: L_max + L_min1 + L_min2 <= a + b) or 2 (class II).
    boundary : ndarray of bool
        Equality in the class-I condition within the tolerance.
    code : ndarray of int
        Index into :data:`FIVEBAR_TYPES`: triple and double crank by the
        paper's rule (§2.1, the inputs turn independently); otherwise single
        crank if an input can turn fully, else no crank.
    crank_mask : ndarray of bool, shape (N, 5)
        Inputs that turn fully relative to the frame (the other input moving
        as needed, :func:`joint_revolvable`), plus the coupler crank of a
        triple crank.  A "single crank" may have both inputs turning, though
        not independently (class I with a short frame, and class II).
    short1, short2 : ndarray of int
        Link numbers of the shortest and second-shortest links.
    excess : ndarray
        (L_max + L_min1 + L_min2) − (a + b) [m].
    inputs_independent : ndarray of bool
        Closed-form check: the linkage assembles for every pair of input
        angles with links 2 and 3 never in line (BD stays inside
        (|l_c1 − l_c2|, l_c1 + l_c2) over the whole torus).
    """

    klass: np.ndarray
    boundary: np.ndarray
    code: np.ndarray
    crank_mask: np.ndarray
    short1: np.ndarray
    short2: np.ndarray
    excess: np.ndarray
    inputs_independent: np.ndarray

    @property
    def types(self) -> List[str]:
        return [FIVEBAR_TYPES[c] for c in self.code.tolist()]

    def cranks(self, i: int = 0) -> List[int]:
        return [k + 1 for k in np.flatnonzero(self.crank_mask[i]).tolist()]


def classify_fivebar(lengths: ArrayLike, frame: int = 5,
                     rtol: float = CHANGE_POINT_RTOL) -> FiveBarClass:
    """Class (I/II) and type of 5R five-bars with the two frame links as inputs.

    Parameters
    ----------
    lengths : array_like, shape (5,) or (N, 5)
        l1..l5 in loop order [m].
    frame : int
        Frame link number (1..5); the inputs are its two neighbours.
    rtol : float
        Relative tolerance of the class-I equality.

    Returns
    -------
    FiveBarClass

    Raises
    ------
    ClosureError
        A link is not shorter than the sum of the others.

    Notes
    -----
    The paper, eq. (19): class I iff L_max + L_min1 + L_min2 <= a + b.  For
    class I (§2.1): one short link the frame and the other an input gives a
    triple crank (both inputs and the coupler joined to the short input, the
    paper's example 1); both short links the inputs a double crank (example 2);
    one short link the frame or an input and the other neither, a single
    crank; otherwise no crank.  Class II (§2.2) has a single crank or none;
    the paper gives no rule to tell which, so single vs no crank is decided
    for both classes by whether an input joint is revolvable
    (:func:`joint_revolvable`), which reproduces the paper's class-I cases.
    The independent check ``inputs_independent`` uses that B and D are
    farthest/closest apart at input angles 0 or π (the paper's eqs. 9-10).
    """
    L = np.asarray(lengths, dtype=float)
    L = L[None, :] if L.ndim == 1 else L
    if L.ndim != 2 or L.shape[1] != 5:
        raise ValueError(f"expected lengths of shape (N, 5), got {L.shape}")
    check_closure(L)
    n = L.shape[0]
    rows = np.arange(n)
    order = np.argsort(L, axis=1, kind="stable")
    srt = np.take_along_axis(L, order, axis=1)
    excess = (srt[:, 4] + srt[:, 0] + srt[:, 1]) - (srt[:, 2] + srt[:, 3])
    boundary = np.abs(excess) <= rtol * srt[:, 4]
    class1 = (excess <= 0) | boundary
    s1, s2 = order[:, 0], order[:, 1]
    i1, i2, c1, c2 = (x - 1 for x in fivebar_roles(frame))
    f0 = frame - 1
    short = np.zeros((n, 5), dtype=bool)
    short[rows, s1] = True
    short[rows, s2] = True
    fs = short[:, f0]
    s_in1, s_in2 = short[:, i1], short[:, i2]
    triple = class1 & fs & (s_in1 | s_in2)
    double = class1 & s_in1 & s_in2
    turn1 = joint_revolvable(L, i1 + 1, frame)
    turn2 = joint_revolvable(L, i2 + 1, frame)
    code = np.full(n, FIVEBAR_TYPES.index("no_crank"))
    code[turn1 | turn2] = FIVEBAR_TYPES.index("single_crank")
    code[double] = FIVEBAR_TYPES.index("double_crank")
    code[triple] = FIVEBAR_TYPES.index("triple_crank")
    mask = np.zeros((n, 5), dtype=bool)
    mask[:, i1] = turn1
    mask[:, i2] = turn2
    mask[:, c1] = triple & s_in1
    mask[:, c2] = triple & s_in2

    p, q, g, h, f = L[:, i1], L[:, i2], L[:, c1], L[:, c2], L[:, f0]
    bd_max = f + p + q
    bd_min = np.maximum.reduce([np.zeros(n), f - p - q, p - f - q, q - f - p])
    independent = (bd_min > np.abs(g - h)) & (bd_max < g + h)
    return FiveBarClass(klass=np.where(class1, 1, 2), boundary=boundary, code=code,
                        crank_mask=mask, short1=s1 + 1, short2=s2 + 1, excess=excess,
                        inputs_independent=independent)


@record
class RRRRPCrank:
    """Crank condition of the RRRRP five-bar.

    Crank 1 (length l1) about A at the origin, links 2 (l2) and 3 (l3), joint
    D of link 3 on a slider moving on the line y = e; inputs: link 1 and the
    slider.

    Attributes
    ----------
    crank_any_fold : bool
        Paper eq. (20) with the offset: l1 + |e| <= |l2 − l3|; link 1 then
        turns fully whatever the angle between links 2 and 3 (each locked
        angle is a slider-crank whose coupler BD >= |l2 − l3|).
    boundary : bool
        Equality in that condition.
    slider_lo, slider_hi : float
        Slider positions x >= 0 [m] between which link 1 turns fully with the
        slider held still (AD between l1 + |l2 − l3| and l2 + l3 − l1);
        mirrored for x <= 0.  Both 0 when there are none.
    has_inner : bool
        Link 1 also turns fully with the slider held inside the crank circle,
        |x| <= ``slider_inner_hi`` (AD <= l1 − |l2 − l3| and l1 + AD <= l2 + l3:
        B circles around D).
    slider_inner_hi : float
        That bound [m] (0 when ``has_inner`` is False).
    """

    l1: float
    l2: float
    l3: float
    e: float
    crank_any_fold: bool
    boundary: bool
    slider_lo: float
    slider_hi: float
    has_inner: bool = False
    slider_inner_hi: float = 0.0


def rrrrp_crank(l1: float, l2: float, l3: float, e: float = 0.0,
                rtol: float = CHANGE_POINT_RTOL) -> RRRRPCrank:
    """Crank condition of the RRRRP five-bar (the paper's §4), with slider offset.

    Parameters
    ----------
    l1, l2, l3 : float
        Crank, second and third link lengths [m].
    e : float
        Offset of the slider path from the crank pivot A [m].

    Returns
    -------
    RRRRPCrank

    Notes
    -----
    With links 2 and 3 folded onto each other (paper fig. 9) A, B, D form a
    slider-crank with coupler |l2 − l3|; its crank condition (slides:
    a + e <= b) is l1 + |e| <= |l2 − l3|, the paper's eq. (20) for e = 0.  Any
    other angle between 2 and 3 makes BD longer, so the condition holds for
    all of them.  With the slider held at x, link 1 turns iff B–D distances
    |AD − l1| .. AD + l1 stay within |l2 − l3| .. l2 + l3: either
    l1 + |l2 − l3| <= AD <= l2 + l3 − l1 (D outside the crank circle) or
    AD <= min(l1 − |l2 − l3|, l2 + l3 − l1) (D inside it), AD >= |e|.
    """
    l1, l2, l3, e = float(l1), float(l2), float(l3), abs(float(e))
    if e >= l1 + l2 + l3:
        raise ClosureError("RRRRP", e, l1 + l2 + l3)
    fold = abs(l2 - l3)
    slack = fold - (l1 + e)
    boundary = abs(slack) <= rtol * (l1 + l2 + l3)
    ad_lo, ad_hi = max(l1 + fold, e), l2 + l3 - l1
    if ad_lo <= ad_hi:
        s_lo = float(np.sqrt(max(ad_lo ** 2 - e ** 2, 0.0)))
        s_hi = float(np.sqrt(max(ad_hi ** 2 - e ** 2, 0.0)))
    else:
        s_lo = s_hi = 0.0
    in_hi = min(l1 - fold, l2 + l3 - l1)
    has_inner = in_hi >= e
    s_in = float(np.sqrt(max(in_hi ** 2 - e ** 2, 0.0))) if has_inner else 0.0
    return RRRRPCrank(l1, l2, l3, e, bool(slack >= 0 or boundary), bool(boundary), s_lo, s_hi,
                      bool(has_inner), s_in)


__all__ = ["FIVEBAR_TYPES", "FiveBarClass", "classify_fivebar", "fivebar_roles",
           "RRRRPCrank", "rrrrp_crank", "ClosureError", "UnsolvableError"]
