"""The result of every synthesis: a designed linkage and what it must reproduce.

A design is a ``kin`` linkage: :attr:`LinkageDesign.linkage` is built from the
engine's elements with the book's link numbers (1 the crank AB, 2 the coupler
BC, 3 the rocker CD or the slider, 4 the frame) and point names (A, B, C, D,
and M for a coupler point), so :func:`mechcli.core.synth.verify.verify` and
``mechcli kin`` move it exactly as they move any other linkage.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, Dict, Mapping, Optional, Tuple

import numpy as np

from mechcli.core.linkage.elements import RRR, Crank, Ground, PointOnLink
from mechcli.core.linkage.engine import Linkage
from mechcli.core.linkage.presets import slider_crank
from mechcli.core.records import record

if TYPE_CHECKING:
    pass

Point = Tuple[float, float]


@record(eq=False)
class LinkageDesign:
    """A synthesized linkage.

    Attributes
    ----------
    kind : str
        ``"four_bar"``, ``"slider_crank"`` or ``"guide_bar"``.
    linkage : Linkage
        The design on the engine; its driver is link 1 (the crank AB) turning
        about A, its input the absolute angle θ1 of AB, CCW from +x [rad].
    lengths : dict
        ``l1, l2, l3, l4`` (four-bar: AB, BC, CD, AD), ``l1, l2, e`` and
        ``H`` (slider-crank), ``l1, l4`` (guide-bar: crank AB, frame AC) [m].
    pivots : dict
        Named points as ``(x, y)`` [m]: ``A``, ``D`` (fixed), ``B1``, ``C1``
        (moving pivots in position 1), and any others the method defines.
    inputs : ndarray or None, shape (N,)
        θ1 at each prescribed position, in the prescribed order [rad]; None
        for a design with no prescribed positions (design from K).
    points : dict
        Prescribed positions of points: name -> complex array (N,) [m]
        (``"B"``, ``"C"`` for guidance, ``"M"`` for coupler poses).
    angles : dict
        Prescribed link angles: link number -> array (N,) [rad] (θ2 for
        coupler poses, θ3 for function generation).
    slides : dict
        Prescribed slides: name -> array (N,) [m] (``"3"`` for a slider-crank).
    values : dict
        Method-specific scalars and arrays for the report (dimensionless
        ratios ``l, m, n``, θ, K, iterations, structural error …), SI units.
    """

    kind: str
    linkage: Linkage
    lengths: Mapping[str, float]
    pivots: Mapping[str, Point]
    inputs: Optional[np.ndarray] = None
    points: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)
    angles: Mapping[int, np.ndarray] = dataclasses.field(default_factory=dict)
    slides: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)
    values: Mapping[str, object] = dataclasses.field(default_factory=dict)

    @property
    def size(self) -> float:
        """The linkage's size [m]: its longest length (the scale of residuals)."""
        return max(abs(float(v)) for k, v in self.lengths.items() if k.startswith("l"))


def _xy(p: Any) -> complex:
    if isinstance(p, complex):
        return p
    x, y = p
    return complex(float(x), float(y))


def _pt(z: complex) -> Point:
    return (float(z.real), float(z.imag))


def branch_of(b: complex, c: complex, d: complex) -> int:
    """The RRR branch (+1/-1) that puts C to the left/right of the line B→D."""
    cross = (d - b).real * (c - b).imag - (d - b).imag * (c - b).real
    return 1 if cross >= 0 else -1


def four_bar_design(A: Tuple[float, float], D: Tuple[float, float], B1: Any, C1: Any, *,
                    inputs: Optional[np.ndarray] = None,
                    points: Optional[Dict[str, np.ndarray]] = None,
                    angles: Optional[Dict[int, np.ndarray]] = None,
                    coupler_point: Optional[Tuple[float, float]] = None,
                    pivots: Optional[Dict[str, Tuple[float, float]]] = None, values: Any = None
                   ) -> LinkageDesign:
    """A four-bar ABCD from its pivots in position 1.

    Parameters
    ----------
    A, D : (x, y)
        Fixed pivots [m].
    B1, C1 : (x, y)
        Moving pivots in the first prescribed position [m].
    inputs : array (N,), optional
        θ1 at the prescribed positions [rad]; default: the angle of A→B1 only.
    points, angles : dict, optional
        What the design must reproduce (see :class:`LinkageDesign`).
    coupler_point : (x, y), optional
        A coupler point M in position 1 [m]; adds ``PointOnLink("M", 2, "B", ...)``.
    pivots, values : dict, optional
        More named points and report values.

    The assembly branch is the one of position 1 (C to the left of B→D: +1).
    """
    a, d, b, c = (_xy(p) for p in (A, D, B1, C1))
    l1, l2, l3, l4 = abs(b - a), abs(c - b), abs(d - c), abs(d - a)
    elements = [Ground("A", a.real, a.imag), Ground("D", d.real, d.imag),
                Crank(1, "A", "B", l1), RRR("C", "B", 2, l2, "D", 3, l3, branch_of(b, c, d))]
    named = {"A": _pt(a), "D": _pt(d), "B1": _pt(b), "C1": _pt(c)}
    if coupler_point is not None:
        m = _xy(coupler_point)
        rel = (m - b) * np.exp(-1j * np.angle(c - b))     # in link 2's frame
        elements.append(PointOnLink("M", 2, "B", float(rel.real), float(rel.imag)))
        named["M1"] = _pt(m)
    named.update(pivots or {})
    if inputs is None:
        inputs = np.array([math.atan2((b - a).imag, (b - a).real)])
    return LinkageDesign("four_bar", Linkage(4, tuple(elements)),
                         {"l1": l1, "l2": l2, "l3": l3, "l4": l4}, named,
                         np.asarray(inputs, dtype=float), dict(points or {}),
                         dict(angles or {}), {}, dict(values or {}))


def slider_crank_design(l1: float, l2: float, e: float = 0.0, *, branch: int = 1,
                        inputs: Optional[np.ndarray] = None,
                        slides: Optional[Dict[str, np.ndarray]] = None, values: Any = None,
                        H: Optional[float] = None) -> LinkageDesign:
    """An offset slider-crank (图 1-4): A = (0, 0), guide y = e, slide ``s3`` = x of C.

    Parameters
    ----------
    l1, l2, e : float
        Crank AB, connecting rod BC, offset [m].
    branch : {1, -1}
        ``1``: the slider to the right of the crank pivot.
    inputs, slides : optional
        Prescribed θ1 [rad] and slides ``{"3": s}`` [m].
    H : float, optional
        The stroke [m], reported in ``lengths``.
    """
    lengths = {"l1": float(l1), "l2": float(l2), "e": float(e)}
    if H is not None:
        lengths["H"] = float(H)
    link = slider_crank(float(l1), float(l2), float(e), branch)   # the kin preset
    return LinkageDesign("slider_crank", link, lengths, {"A": (0.0, 0.0)},
                         None if inputs is None else np.asarray(inputs, dtype=float),
                         {}, {}, dict(slides or {}), dict(values or {}))
