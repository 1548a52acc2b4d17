"""Drawing primitives of the linkage elements: plain data that
``report/kin_plots.py`` turns into pictures (:meth:`Element.sketch
<mechcli.core.linkage.elements.Element.sketch>` returns them).

Kept apart from :mod:`.elements` so that a run that draws nothing (``kin --no-plot``)
does not build their classes at start-up; ``elements.Bar`` etc. and
``mechcli.core.linkage.Bar`` still name them.

May import: nothing of mechcli.
"""

from __future__ import annotations

from typing import Optional

from mechcli.core.records import record


@record
class Bar:
    """A bar drawn between two points."""

    a: str
    b: str


@record
class Block:
    """A slider block at ``point``, turned with link ``link`` (``None``: not turned)."""

    point: str
    link: Optional[int] = None


@record
class Guide:
    """A guide line carried by link ``link``.

    It passes through ``point`` shifted by ``offset`` [m] to the left of its
    direction, which is ``angle`` [rad] relative to the link.  ``ray``: drawn
    from that point along ``branch`` times the direction (a guide bar pivoted
    at ``point``); otherwise a line spanning the range of slide ``slide``.
    """

    link: int
    point: str
    angle: float
    offset: float
    slide: str
    ray: bool = False
    branch: int = 1


@record
class Pivot:
    """A point fixed on the frame, drawn as a ground symbol."""

    name: str
