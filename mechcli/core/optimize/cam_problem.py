"""Optimization on a cam (【例 7-2】): the pressure angle as a function of the
cam angle, the one design variable, vectorized over a population of angles.

May import: numpy, :mod:`mechcli.core.cam`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechcli.core.cam.geometry import pressure_angle_and_rate
from mechcli.core.optimize.problem import Evaluation

if TYPE_CHECKING:
    from mechcli.core.cam.geometry import Follower
    from mechcli.core.cam.motion import MotionProgram
    from mechcli.core.types import Array, FloatOrArray


class PressureAngle:
    """``evaluator(X) -> Evaluation``: f = -|α| (``maximize``) or |α| at the cam
    angles ``X[:, 0] * unit`` [rad], for the follower ``fol`` on ``program``."""

    def __init__(self, fol: Follower, program: MotionProgram, maximize: bool = True,
                 unit: float = 1.0) -> None:
        self.fol, self.program = fol, program
        self.sign = -1.0 if maximize else 1.0
        self.unit = unit            # radians per unit of the variable (pi/180: degrees)

    def alpha(self, delta: FloatOrArray) -> Array:
        st = self.program.evaluate(np.asarray(delta, dtype=float))
        a, _ = pressure_angle_and_rate(self.fol, st.s, st.s1, st.s2, st.s3)
        return np.abs(np.asarray(a, dtype=float))

    def __call__(self, X: Array) -> Evaluation:
        X = np.atleast_2d(np.asarray(X, dtype=float))
        a = self.alpha(X[:, 0] * self.unit)
        ok = np.isfinite(a)
        return Evaluation(np.where(ok, self.sign * a, 0.0), np.zeros((len(X), 0)), ok)
