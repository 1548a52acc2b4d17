"""Load programs: when and how strongly an external load acts over the input.

A :class:`LoadProgram` wraps a :class:`~mechcli.core.linkage.force_model.Load`
with a window of input angle, a velocity-sign condition, a stroke band or a
tabulated factor (例 2-3's working-stroke-only resistance, 例 2-4's cutting
force in part of the stroke) or a magnitude computed from the motion
(``source``: the gas force on a piston, :mod:`mechcli.core.linkage.piston`).
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Optional, Tuple

import numpy as np

from mechcli.core.linkage.force_model import Load
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    pass

if TYPE_CHECKING:
    pass


@record
class LoadProgram:
    """A load with its program over the input.

    ``window`` (lo, hi) of the primary input [rad or m] (periodic in 2*pi when
    ``rotary``; lo > hi wraps through 0); ``velocity`` a
    :class:`~mechcli.core.linkage.kinematics.Quantity` whose sign must be ``sign``;
    ``slide`` a slide quantity that must lie within ``band`` (absolute limits
    [m], see :meth:`with_band_limits`; fractions of the stroke until then);
    ``table`` (xs, ys) a factor tabulated against the input (linear, periodic
    when rotary).  ``source`` an object with ``force(q, motion) -> array``: a
    magnitude over the positions [N] that multiplies the load's components (a
    unit direction then), e.g. :class:`~mechcli.core.linkage.piston.GasLoad`.
    """

    load: Load
    window: Optional[Tuple[float, float]] = None
    rotary: bool = True
    velocity: object = None
    sign: int = 0
    slide: object = None
    band: Optional[Tuple[float, float]] = None
    table: Optional[Tuple[np.ndarray, np.ndarray]] = None
    band_limits: Optional[Tuple[float, float]] = None
    source: object = None

    @property
    def conditional(self):
        return self.window is not None or self.velocity is not None or self.band is not None

    def with_band_limits(self, s_min, s_max):
        """Fix the band to absolute slide limits from the slide's stroke."""
        lo, hi = self.band
        h = s_max - s_min
        return dataclasses.replace(self, band_limits=(s_min + lo * h, s_min + hi * h))

    def active(self, q, motion):
        """Boolean mask of the positions where the load acts."""
        q = np.asarray(q, dtype=float)
        on = np.ones(q.shape, dtype=bool)
        if self.window is not None:
            lo, hi = self.window
            if self.rotary:
                two_pi = 2 * np.pi
                x = np.mod(q - lo, two_pi)
                width = np.mod(hi - lo, two_pi)
                if hi - lo >= two_pi:
                    width = two_pi
                # inclusive at both ends, to round-off of the input grid
                tol = 1e-12 * two_pi
                on = on & ((x <= width + tol) | (x >= two_pi - tol))
            else:
                on = on & (q >= lo) & (q <= hi)
        if self.velocity is not None:
            v = np.asarray(self.velocity.get(motion))
            # not in place: over a batch of designs v has the motion's shape
            on = on & ((v > 0) if self.sign > 0 else (v < 0))
        if self.band_limits is not None:
            s = np.asarray(self.slide.get(motion))
            lo, hi = self.band_limits
            on = on & (s >= lo) & (s <= hi)
        return on

    def breaks(self, lo: FloatOrArray, hi: FloatOrArray):
        """The inputs in [lo, hi] where the load's magnitude has a kink or a jump from its
        tabulated ``factor`` (with its repeats when rotary) or its ``source`` (one with a
        ``breaks(lo, hi)``); the switches of the conditions are found separately."""
        out = []
        if self.table is not None:
            xs = self.table[0]
            if self.rotary:
                period = 2 * np.pi
                for x in xs:
                    k = np.ceil((lo - x) / period)
                    while x + k * period <= hi:
                        out.append(float(x + k * period))
                        k += 1
            else:
                out += [float(x) for x in xs if lo <= x <= hi]
        if self.source is not None and hasattr(self.source, "breaks"):
            out += list(self.source.breaks(lo, hi))
        return out

    def factor(self, q: np.ndarray):
        if self.table is None:
            return 1.0
        xs, ys = self.table
        if self.rotary:
            # periodic: close the table over one turn (the last point joins the first)
            period = 2 * np.pi
            if xs[-1] - xs[0] < period * (1 - 1e-12):
                xs = np.append(xs, xs[0] + period)
                ys = np.append(ys, ys[0])
            return np.interp(np.mod(q - xs[0], period) + xs[0], xs, ys)
        return np.interp(q, xs, ys)

    def evaluate(self, q, motion):
        """The load with its components as arrays over ``q``; and the active mask."""
        on = self.active(q, motion)
        f = np.where(on, 1.0, 0.0) * self.factor(q)
        if self.source is not None:
            f = f * self.source.force(q, motion)
        ld = self.load
        return dataclasses.replace(ld, fx=ld.fx * f, fy=ld.fy * f, torque=ld.torque * f), on
