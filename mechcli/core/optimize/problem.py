"""The vectorized optimization problem: variables, evaluation, history.

A :class:`Problem` evaluates a population ``X`` of shape ``(M, n)`` at once:
the objective ``f`` (M,), the constraints ``g`` (M, k) in the convention
``g <= 0`` is satisfied, and ``ok`` (M,): the design could be evaluated at all
(a linkage that cannot be assembled over its range is not ``ok``; its ``f`` is
never NaN, it is simply infeasible).
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.types import Array, BoolArray, FloatOrArray


@record
class Variable:
    """A design variable: a name (the caller's, e.g. a dotted spec path),
    bounds and a start value, in the caller's numbers."""

    name: str
    lo: float
    hi: float
    start: float


@record
class Evaluation:
    """Values of a population: ``f`` (M,), ``g`` (M, k) with ``g <= 0``
    satisfied, ``ok`` (M,) evaluable.  Where not ``ok``, ``f`` is 0 and ``g``
    holds the violation the evaluator could measure (>= 0)."""

    f: np.ndarray
    g: np.ndarray
    ok: np.ndarray

    @staticmethod
    def concat(parts: Sequence[Evaluation]) -> Evaluation:
        return Evaluation(np.concatenate([p.f for p in parts]),
                          np.concatenate([p.g for p in parts]),
                          np.concatenate([p.ok for p in parts]))


@record(frozen=False)
class Record:
    """One row of the history: an iteration of the method (or a generation)."""

    iteration: int
    evaluations: int
    time_s: float
    x: np.ndarray
    f: float
    violation: float
    evaluable: bool = True


class Problem:
    """A vectorized problem.

    Parameters
    ----------
    variables : sequence of Variable
    evaluate : callable
        ``evaluate(X) -> Evaluation`` for ``X`` of shape (M, n).  Must be
        picklable when a process pool is the mapper.
    constraint_names : sequence of str
        One name per column of ``g``.
    mapper : callable, optional
        A map-like function (``map(fn, chunks)``, e.g. an executor's
        ``map``); every population goes through it in chunks of ``chunk``.
    chunk : int
        Candidates per call of ``evaluate``.
    scales : sequence of float, optional
        A typical size of each constraint (default 1): a design is feasible
        when every ``g <= FEASIBLE_TOL * scale`` and a constraint is active
        when ``|g| <= ACTIVE_TOL * scale``.
    """

    #: feasibility slack (relative to each constraint's scale): what the local
    #: methods reach (SLSQP and trust-constr stop within ~1e-10 of a bound)
    FEASIBLE_TOL = 1e-8
    #: a constraint within this of its bound is reported active
    ACTIVE_TOL = 1e-5

    def __init__(self, variables: Sequence[Variable], evaluate: Evaluator,
                 constraint_names: Sequence[str] = (),
                 mapper: Optional[Callable[..., Iterable[Evaluation]]] = None, chunk: int = 512,
                 scales: Optional[Sequence[float]] = None):
        self.variables = tuple(variables)
        self._evaluate = evaluate
        self.constraint_names = tuple(constraint_names)
        self.mapper = mapper or map
        self.chunk = int(chunk)
        self.scales = (np.ones(len(self.constraint_names)) if scales is None
                       else np.asarray(scales, dtype=float))
        self.evaluations = 0
        self.calls = 0
        self.history: List[Record] = []
        self.started = time.perf_counter()
        self._cache: Dict[bytes, Tuple[float, np.ndarray, bool]] = {}

    @property
    def n(self):
        return len(self.variables)

    @property
    def lo(self):
        return np.array([v.lo for v in self.variables])

    @property
    def hi(self):
        return np.array([v.hi for v in self.variables])

    @property
    def start(self):
        return np.array([v.start for v in self.variables])

    def evaluate(self, X: Array) -> Evaluation:
        """Evaluate a population (M, n) through the mapper, in chunks."""
        X = np.atleast_2d(np.asarray(X, dtype=float))
        M = X.shape[0]
        self.evaluations += M
        self.calls += 1
        chunks = [X[i:i + self.chunk] for i in range(0, M, self.chunk)]
        parts = list(self.mapper(self._evaluate, chunks))
        ev = Evaluation.concat(parts)
        if ev.f.shape != (M,) or ev.g.shape != (M, len(self.constraint_names)):
            raise ValueError(f"evaluate returned f {ev.f.shape}, g {ev.g.shape} for {M} "
                             f"candidates and {len(self.constraint_names)} constraints")
        return ev

    def one(self, x: Array) -> Tuple[float, np.ndarray, bool]:
        """f, g, ok of one design (cached on its exact value)."""
        key = np.asarray(x, dtype=float).tobytes()
        hit = self._cache.get(key)
        if hit is None:
            ev = self.evaluate(np.asarray(x, dtype=float)[None, :])
            hit = (float(ev.f[0]), ev.g[0].copy(), bool(ev.ok[0]))
            if len(self._cache) > 4096:
                self._cache.clear()
            self._cache[key] = hit
        return hit

    def violation(self, g: Array, ok: Union[BoolArray, bool] = True) -> Array:
        """Total violation (>= 0): each constraint's excess over its scale, plus 1
        for a design that cannot be evaluated."""
        g = np.asarray(g, dtype=float)
        v = np.sum(np.maximum(g, 0.0) / self.scales, axis=-1)
        return np.where(ok, v, v + 1.0)

    def feasible(self, g: Array, ok: Union[BoolArray, bool] = True) -> BoolArray:
        g = np.asarray(g, dtype=float)
        return np.asarray(ok) & np.all(g <= self.FEASIBLE_TOL * self.scales, axis=-1)

    def active(self, g: Array) -> BoolArray:
        """Which constraints are active (within ACTIVE_TOL of their bound) at ``g``.
        A constraint that is 0 whenever it is met (``assembly``: the fraction of
        positions that fail) is never called active."""
        g = np.asarray(g, dtype=float)
        act = np.abs(g) <= self.ACTIVE_TOL * self.scales
        flat = np.array([n.startswith("assembly") for n in self.constraint_names], dtype=bool)
        return act & ~(flat & (g <= 0))

    def record(self, iteration: int, x: Array, f: float, violation: FloatOrArray,
               evaluable: bool = True) -> None:
        self.history.append(Record(int(iteration), self.evaluations,
                                   time.perf_counter() - self.started,
                                   np.array(x, dtype=float), float(f), float(violation),
                                   bool(evaluable)))


@record
class Result:
    """The outcome of :func:`mechcli.core.optimize.methods.minimize`.

    Attributes
    ----------
    x : ndarray
        The best design found.
    f : float
        Its objective.
    g : ndarray
        Its constraints (``<= 0`` satisfied).
    active : ndarray of bool
        Constraints active at ``x``.
    feasible : bool
    success : bool
        The method reports convergence and ``x`` is feasible.
    message : str
        The method's own words.
    method : str
    iterations, evaluations : int
    time_s : float
    history : list of Record
    starts : list of (x0, x, f, feasible)
        Multi-start: each start and where it ended.
    """

    x: np.ndarray
    f: float
    g: np.ndarray
    active: np.ndarray
    feasible: bool
    success: bool
    message: str
    method: str
    iterations: int
    evaluations: int
    time_s: float
    history: Tuple[Record, ...]
    starts: Tuple = ()
    extra: Optional[dict] = None


def grid(problem: Problem, i: int, j: int, x: Array, count: int = 41,
         span: Optional[Tuple[Tuple[float, float], Tuple[float, float]]] = None
         ) -> Tuple[Array, Array, Array, BoolArray]:
    """The objective and feasibility on a grid of variables i and j (the others
    at ``x``): ``(u, v, F, feasible)`` with F of shape (count, count), rows
    along v; for the surface plot (the book's ``crankobjfun_VR``).  One
    population evaluation."""
    lo, hi = problem.lo, problem.hi
    if span is not None:
        (lo_i, hi_i), (lo_j, hi_j) = span
    else:
        lo_i, hi_i, lo_j, hi_j = lo[i], hi[i], lo[j], hi[j]
    u = np.linspace(lo_i, hi_i, count)
    v = np.linspace(lo_j, hi_j, count)
    U, V = np.meshgrid(u, v)
    X = np.repeat(np.asarray(x, dtype=float)[None, :], U.size, axis=0)
    X[:, i], X[:, j] = U.ravel(), V.ravel()
    saved = problem.evaluations
    ev = problem.evaluate(X)
    problem.evaluations = saved          # the picture is not the method's cost
    feas = problem.feasible(ev.g, ev.ok).reshape(U.shape)
    F = np.where(ev.ok, ev.f, np.nan).reshape(U.shape)
    return u, v, F, feas


#: what ``Callable`` evaluators look like, for type hints
Evaluator = Callable[[np.ndarray], Evaluation]
