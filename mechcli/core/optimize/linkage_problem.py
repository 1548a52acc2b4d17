"""Optimization problems on linkages: the goals and constraints of chapter 7
turned into one vectorized evaluator.

The caller supplies ``candidates(X)``: the batched linkage of a population
(parameters (M, 1)), an ``ok`` mask of the designs that could be built, and
the values of any goal parameter that is itself a design variable (e.g. the
angle origin φ0).  :class:`LinkageEvaluator` then moves the whole population
on the engine once per term and returns an
:class:`~mechcli.core.optimize.problem.Evaluation`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.optimize import terms
from mechcli.core.optimize.problem import Evaluation
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.types import Array, BoolArray


@record
class FunctionGoal:
    """Function generation: the output (a link number or a slide name) should
    move by ``dpsi`` when the input moves by ``dphi`` from ``phi0``.

    ``phi0``: ``"output_min"``/``"output_max"`` (the input's limit position
    where the output is least/greatest, found per design), or a number [rad];
    ``psi0``: None (the output at φ0) or a number [rad or m].
    ``scale`` divides a slide's deviation (1 for angles).
    """

    output: Union[int, str]
    phi0: object
    dphi: np.ndarray
    dpsi: np.ndarray
    psi0: Optional[float] = None
    measure: str = "sum_squares"
    scale: float = 1.0


@record
class PathGoal:
    """Path generation: point ``point`` through ``targets`` (K, 2) [m], at the
    inputs ``theta0 + angles`` when ``angles`` is given."""

    point: str
    targets: np.ndarray
    angles: Optional[np.ndarray] = None
    theta0: float = 0.0
    measure: str = "sum_squares"


@record
class Transmission:
    """Joint angles (between the two links of each RRR dyad, 0…π) within
    [lo, hi] [rad] over the revolution or the goal's range."""

    lo: float
    hi: float
    over: str = "revolution"
    joints: Tuple[str, ...] = ()


@record
class Assembly:
    """The linkage assembles, with no dead point, over the revolution or the
    goal's range."""

    over: str = "revolution"


@record
class CrankConditions:
    """The book's g1 … g6: the four-bar's link 1 is a crank (式 7-8 … 7-11)."""


def constraint_names(constraints: Sequence[object], extra: Sequence[str] = ()) -> List[str]:
    """One name per column of g; a name met again gets ``_2``, ``_3`` … (the
    first keeps the plain name: ``gamma_min``)."""
    names = []
    for c in constraints:
        if isinstance(c, Transmission):
            names += ["gamma_min", "gamma_max"]
        elif isinstance(c, Assembly):
            names.append(f"assembly_{c.over}")
        elif isinstance(c, CrankConditions):
            names += list(terms.CRANK_NAMES)
    names += list(extra)
    out: List[str] = []
    seen: Dict[str, int] = {}
    for n in names:
        seen[n] = seen.get(n, 0) + 1
        out.append(n if seen[n] == 1 else f"{n}_{seen[n]}")
    return out


class LinkageEvaluator:
    """``evaluator(X) -> Evaluation`` for a goal and constraints.

    Parameters
    ----------
    candidates : callable
        ``candidates(X) -> (linkage, ok, params)``: the batched linkage, the
        designs that could be built, and ``{name: (M,) array}`` of goal
        parameters that are design variables (``"phi0"``, ``"psi0"``,
        ``"theta0"``).
    driver : int
        The primary driver's link.
    goal : FunctionGoal or PathGoal or None
    constraints : sequence
    samples : int
        Positions of the revolution (the grid of transmission, assembly and
        path terms).
    extra : callable, optional
        ``extra(X) -> (f or None, g (M, k2), ok)``: terms the engine does not
        compute (results of another command, one design at a time).
    """

    def __init__(self, candidates: Callable, driver: int,
                 goal: Optional[Union[FunctionGoal, PathGoal]] = None,
                 constraints: Sequence[Union[Transmission, Assembly, CrankConditions]] = (),
                 samples: int = 360, extra: Optional[Callable] = None,
                 extra_names: Sequence[str] = (),
                 followers: Optional[Dict[int, Tuple[float, float]]] = None):
        self.candidates = candidates
        self.driver = driver
        self.followers = dict(followers or {})
        self.goal = goal
        self.constraints = tuple(constraints)
        self.samples = int(samples)
        self.extra = extra
        self.names = constraint_names(self.constraints, extra_names)

    # -- the goal ---------------------------------------------------------
    def _function(self, pop: terms.Population, goal: FunctionGoal, params: Dict[str, Any]
                  ) -> Tuple[Array, BoolArray, Array]:
        ok0: Union[BoolArray, bool]
        if isinstance(goal.phi0, str):
            phi0, ok0 = terms.input_limit(pop, goal.output, goal.phi0.split("_")[1])
        else:
            phi0, ok0 = params.get("phi0", goal.phi0), True
        psi0 = params.get("psi0", goal.psi0)
        dev, psi, q, ok = terms.function_deviation(pop, goal.output, phi0, goal.dphi,
                                                   goal.dpsi, psi0, goal.scale)
        # the goal's range includes phi0 itself (the constraints' "range")
        q = np.concatenate([np.asarray(phi0, dtype=float).reshape(-1, 1)
                            * np.ones((q.shape[0], 1)), q], axis=1)
        return terms.measure(dev, goal.measure), ok & ok0, q

    def _path(self, pop: terms.Population, goal: PathGoal, params: Dict[str, Any]
              ) -> Tuple[Array, BoolArray, Optional[Array]]:
        theta0 = params.get("theta0", goal.theta0)
        d, ok = terms.path_deviation(pop, goal.point, goal.targets, goal.angles, theta0)
        q = None
        if goal.angles is not None:
            q = np.asarray(theta0, dtype=float).reshape(-1, 1) + goal.angles[None, :]
        return terms.measure(d, goal.measure), ok, q

    def _dense(self, q: Array) -> Array:
        """The goal's input range (M, N) sampled as densely as a revolution's
        ``samples`` (the goal's own positions included), for the constraints
        ``over = "range"``."""
        q = np.asarray(q, dtype=float)
        lo, hi = q.min(axis=-1, keepdims=True), q.max(axis=-1, keepdims=True)
        span = float(np.max(hi - lo)) if q.size else 0.0
        n = max(8, int(math.ceil(self.samples * span / (2 * math.pi))) + 1)
        t = np.linspace(0.0, 1.0, n)
        return np.sort(np.concatenate([lo + (hi - lo) * t, q], axis=-1), axis=-1)

    def details(self, X: Array) -> Dict[str, Any]:
        """Per-design details for the report: deviations and inputs (M, N)."""
        linkage, built, params = self.candidates(np.atleast_2d(X))
        pop = terms.Population(linkage, self.driver, self.samples, self.followers)
        goal = self.goal
        out = {"linkage": linkage}
        if isinstance(goal, FunctionGoal):
            if isinstance(goal.phi0, str):
                phi0, _ = terms.input_limit(pop, goal.output, goal.phi0.split("_")[1])
            else:
                phi0 = params.get("phi0", goal.phi0)
            psi0 = params.get("psi0", goal.psi0)
            dev, psi, q, ok = terms.function_deviation(pop, goal.output, phi0, goal.dphi,
                                                       goal.dpsi, psi0, goal.scale)
            out.update(dev=dev, psi=psi, q=q, phi0=np.asarray(phi0, dtype=float).reshape(-1))
        elif isinstance(goal, PathGoal):
            theta0 = params.get("theta0", goal.theta0)
            d, ok = terms.path_deviation(pop, goal.point, goal.targets, goal.angles, theta0)
            out.update(dist=d, theta0=np.asarray(theta0, dtype=float).reshape(-1))
        return out

    def __call__(self, X: Array) -> Evaluation:
        X = np.atleast_2d(np.asarray(X, dtype=float))
        M = X.shape[0]
        linkage, built, params = self.candidates(X)
        pop = terms.Population(linkage, self.driver, self.samples, self.followers)
        ok = np.asarray(built, dtype=bool).copy()
        f = np.zeros(M)
        q_range = None
        if isinstance(self.goal, FunctionGoal):
            f, okg, q_range = self._function(pop, self.goal, params)
            ok &= okg
        elif isinstance(self.goal, PathGoal):
            f, okg, q_range = self._path(pop, self.goal, params)
            ok &= okg
        cols = []
        for c in self.constraints:
            if isinstance(c, CrankConditions):
                cols.append(terms.crank_conditions(*terms.four_bar_lengths(linkage)))
                continue
            ranged = c.over == "range" and q_range is not None
            # dead points need the velocity solve; angles and assembly do not
            order = 1 if isinstance(c, Assembly) else 0
            if ranged:
                assert q_range is not None  # ranged
                m = pop.at(self._dense(q_range), order=order)
            else:
                m = pop.revolution(order)
            if isinstance(c, Transmission):
                joints = c.joints or linkage.transmission_joints
                lo, hi, okt = terms.transmission_range(m, joints, cyclic=not ranged)
                cols.append(np.stack([np.where(okt, c.lo - lo, 0.0),
                                      np.where(okt, hi - c.hi, 0.0)], axis=-1))
            elif isinstance(c, Assembly):
                cols.append(terms.failed_fraction(m)[:, None] * np.ones((M, 1)))
        if self.extra is not None:
            fe, ge, oke = self.extra(X)
            if fe is not None:
                f = fe
            ok &= oke
            cols.append(np.asarray(ge, dtype=float).reshape(M, -1))
        g = np.concatenate(cols, axis=-1) if cols else np.zeros((M, 0))
        g = np.where(np.isfinite(g), g, 1.0)
        f = np.where(ok & np.isfinite(f), f, 0.0)
        return Evaluation(f, g, ok)


