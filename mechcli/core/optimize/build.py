"""The problem of a linkage optimization, built from the spec's plain numbers.

:func:`linkage_problem` assembles the vectorized :class:`~.problem.Problem` of a
kin or force problem on the engine: the goal (a function or a path), the engine
constraints of ``[[constraint]]`` (transmission angle, assembly, the crank
conditions g1 ... g6) with their scales, and the terms another command computes
(``extra``, with the bounds of ``kind = "result"`` constraints).  What the
spec's keys mean and whether the linkage can give them is checked before, by
:func:`mechcli.spec.optimize.check_linkage_problem`; here nothing is read and
nothing is worded.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Callable, List, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.optimize import linkage_problem as lp
from mechcli.core.optimize.problem import Problem, Variable

if TYPE_CHECKING:
    from mechcli.core.cam.design import CamDesign
    from mechcli.core.linkage import Linkage
    from mechcli.core.optimize.cam_problem import PressureAngle

#: the goal of a linkage problem (None for a result objective)
Goal = Optional[Union[lp.FunctionGoal, lp.PathGoal]]

#: a bound on another command's result: (result key, lower or None, upper or None)
Bound = Tuple[str, Optional[float], Optional[float]]


def function_goal(objective: dict, dphi: np.ndarray, dpsi: np.ndarray) -> lp.FunctionGoal:
    """The function-generation goal of an ``[objective]`` (angles in rad; a slide's
    deviation stays in metres, shown in the spec's unit)."""
    return lp.FunctionGoal(objective["output"], objective["phi0"],
                           np.asarray(dphi, dtype=float), np.asarray(dpsi, dtype=float),
                           objective["psi0"], objective["measure"])


def path_goal(objective: dict) -> lp.PathGoal:
    """The path-generation goal of an ``[objective]``."""
    return lp.PathGoal(objective["point"], objective["targets"], objective["angles"],
                       objective["theta0"], objective["measure"])


def engine_terms(constraints: Sequence[dict], size: float) -> Tuple[list, List[float]]:
    """The engine constraints of ``[[constraint]]`` (transmission, assembly, crank)
    and the scale of each of their components (1 for angles and assembly, the
    linkage's *size* for the crank conditions' lengths)."""
    engine: list = []
    scales: List[float] = []
    for c in constraints:
        if c["kind"] == "transmission":
            engine.append(lp.Transmission(c["min"], c["max"], c["over"], c["joints"]))
            scales += [1.0, 1.0]
        elif c["kind"] == "assembly":
            engine.append(lp.Assembly(c["over"]))
            scales.append(1.0)
        elif c["kind"] == "crank":
            engine.append(lp.CrankConditions())
            scales += [size] * 6
    return engine, scales


def bound_scales(bounds: Sequence[Bound]) -> List[float]:
    """The scale of each side of each result bound: its own size (1 for a zero bound)."""
    scales: List[float] = []
    for _key, lo, hi in bounds:
        scales += [max(abs(v), 1e-300) if v else 1.0 for v in (lo, hi) if v is not None]
    return scales


def linkage_problem(candidates: Any, variables: Sequence[Variable], goal: Goal,
                    constraints: Sequence[dict], samples: int,
                    extra: Optional[Callable] = None, extra_names: Sequence[str] = (),
                    bounds: Sequence[Bound] = ()) -> Tuple[Problem, lp.LinkageEvaluator]:
    """The problem and its evaluator: *candidates* (a population -> its linkages,
    :class:`mechcli.spec.optimize.Candidates`), the *goal* (None for a result
    objective), the engine *constraints*, *samples* positions per revolution, and
    *extra* (another command's terms, named *extra_names*, the result *bounds*)."""
    base = candidates.linkage_of(candidates.starts)
    engine, scales = engine_terms(constraints, float(base.scale()))
    if extra is not None:
        scales += bound_scales(bounds)
    evaluator = lp.LinkageEvaluator(candidates, base.drivers[0].link, goal, engine, samples,
                                    extra, extra_names, followers=candidates.followers)
    return Problem(list(variables), evaluator, evaluator.names, scales=scales), evaluator


def optimum_poses(linkage: Linkage, q: np.ndarray, rotary: bool, goal: Goal,
                  details: dict) -> dict:
    """The optimum *linkage* moved through the inputs *q* of its driver (and posed
    at a path goal's angles from the optimum theta0): what the pictures and
    ``--export`` draw.  Keys ``linkage``, ``q``, ``rotary``, ``motion``, ``at``
    (or None) and ``size`` (the goal's length scale)."""
    from mechcli.core.linkage import DriverMotion, solve
    drv = linkage.drivers[0]
    poses = {"linkage": linkage, "q": q, "rotary": rotary,
             "motion": solve(linkage, {drv.link: DriverMotion(q)}, order=0), "at": None,
             "size": float(getattr(goal, "scale", 1.0))}
    if getattr(goal, "angles", None) is not None and "theta0" in details:
        assert isinstance(goal, lp.PathGoal)  # the goal with angles
        qa = float(details["theta0"][0]) + np.asarray(goal.angles, dtype=float)
        poses["at"] = solve(linkage, {drv.link: DriverMotion(qa)}, order=0)
    return poses


def cam_problem(design: CamDesign, maximize: bool, variable: Variable
                ) -> Tuple[Problem, PressureAngle]:
    """例 7-2: the pressure angle of a cam *design* over the cam angle (the one
    *variable*, degrees), with the cam's exact refinement of the same maximum
    (the root of dα/dδ) beside it as the evaluator's ``exact``."""
    import math

    from mechcli.core.optimize.cam_problem import PressureAngle
    ev: Any = PressureAngle(design.follower, design.program, maximize, math.pi / 180)
    ev.exact = design.checks.alpha_rise
    return Problem([variable], ev), ev
