"""The book's named linkages built from numbers (chapter 1, 图 1-2 … 1-8).

Each preset returns a :class:`~mechcli.core.linkage.engine.Linkage` of the
general form, with the book's link numbers (1 the crank, the frame the
highest number) and point names, so ``kin``, ``force``, synthesis checks,
optimization and the atlas all use one engine.  Lengths are in metres (or any
one consistent unit); every length may be an array, e.g. of shape ``(M, 1)``,
for a batch of M designs.
"""

from __future__ import annotations

from typing import Any

from mechcli.core.linkage.elements import RPR, RRP, RRR, Crank, Ground, PointOnLink
from mechcli.core.linkage.engine import Linkage

#: assembly modes by name: +1 / -1 as the dyads take them
FOUR_BAR_BRANCHES = {"open": 1, "crossed": -1}
SLIDER_CRANK_BRANCHES = {"right": 1, "left": -1}
SHAPER_BRANCHES = {"left": -1, "right": 1}


def _branch(branch: int, named: bool):
    if isinstance(branch, str):
        if branch not in named:
            raise ValueError(f"branch must be one of {sorted(named)} or +1/-1, got {branch!r}")
        return named[branch]
    return branch


def four_bar(l1, l2, l3, l4,
             branch=1):
    """Four-bar linkage ABCD (图 1-2, 例 1-1).

    Parameters
    ----------
    l1, l2, l3, l4 : float or array
        Crank AB (link 1), coupler BC (link 2), rocker CD (link 3), frame AD
        (link 4) [m].
    branch : {1, -1, "open", "crossed"}
        ``1``/``"open"``: C to the left of B→D, as in the book's figure.

    Notes
    -----
    A = (0, 0), D = (l4, 0); input: the crank angle θ1 of link 1.
    """
    return Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", l4, 0.0), Crank(1, "A", "B", l1),
                       RRR("C", "B", 2, l2, "D", 3, l3, _branch(branch, FOUR_BAR_BRANCHES))))


def slider_crank(l1, l2, e=0.0, branch=1):
    """Offset slider-crank (图 1-4, 例 1-2).

    Parameters
    ----------
    l1, l2 : float or array
        Crank AB (link 1) and connecting rod BC (link 2) [m].
    e : float or array
        Offset of the slider guide y = e [m].
    branch : {1, -1, "right", "left"}
        ``1``/``"right"``: the slider to the right of the crank pivot.

    Notes
    -----
    A = (0, 0); the slider is link 3, the frame link 4; the slide ``s3`` is
    the slider's x.
    """
    return Linkage(4, (Ground("A", 0.0, 0.0), Crank(1, "A", "B", l1),
                       RRP("C", "B", 2, l2, 3, 4, "A", 0.0, e,
                           _branch(branch, SLIDER_CRANK_BRANCHES), "3")))


def guide_bar(l1: Any, l4: Any, e: float = 0.0, branch: int = 1) -> Linkage:
    """Guide-bar (导杆) linkage (图 1-6, 例 1-3), oscillating (l1 < l4) or rotating.

    Parameters
    ----------
    l1, l4 : float or array
        Crank AB (link 1) and frame AC [m].
    e : float or array
        Offset of the guide line from its pivot C [m].
    branch : {1, -1}
        ``1``: the guide points from C towards B.

    Notes
    -----
    C = (0, 0), A = (0, l4); block 2 slides on guide 3 (slide ``s23`` = CB);
    the frame is link 4.
    """
    return Linkage(4, (Ground("C", 0.0, 0.0), Ground("A", 0.0, l4), Crank(1, "A", "B", l1),
                       RPR("B", 2, "C", 3, e, branch, "23")))


def shaper(l1, l3, l4, l6,
           l6p, branch=-1):
    """Shaper six-bar (牛头刨床, 图 1-8, 例 1-4).

    Parameters
    ----------
    l1 : float or array
        Crank AB (link 1) [m].
    l3 : float or array
        Guide bar CD (link 3) [m].
    l4 : float or array
        Link DE (link 4) [m].
    l6, l6p : float or array
        Frame CA and the height of the ram guide (the book's l6′) [m].
    branch : {-1, 1, "left", "right"}
        ``-1``/``"left"``: E to the left of D, as in the book.

    Notes
    -----
    C = (0, 0), A = (0, l6), ram guide y = l6p; block 2 on guide 3 (slide
    ``s23``), ram 5 (slide ``sE``), frame 6.
    """
    return Linkage(6, (Ground("C", 0.0, 0.0), Ground("A", 0.0, l6), Ground("G", 0.0, l6p),
                       Crank(1, "A", "B", l1), RPR("B", 2, "C", 3, 0.0, 1, "23"),
                       PointOnLink("D", 3, "C", l3, 0.0),
                       RRP("E", "D", 4, l4, 5, 6, "G", 0.0, 0.0,
                           _branch(branch, SHAPER_BRANCHES), "E")))
