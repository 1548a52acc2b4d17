"""Another command's ``--json`` results, computed in this process.

``mechcli optimize`` may minimize (or bound) any scalar result of ``kin`` or
``force``: :class:`ResultTerms` reads the problem's tables with a design's values
set (as ``--set`` would), solves it as the command does and takes the results
its report gives (:func:`problem_results`), one design at a time.  It sits in the
runner because it runs a command: the spec layer reads, the core solves, the
report words; this joins the three as ``commands`` does.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np


class ResultTerms:
    """Objective and constraints read from another command's ``--json``
    results, one design at a time (``force``'s max |Mb| …).  Picklable."""

    def __init__(self, spec: Any, objective: Optional[Tuple[str, float]],
                 bounds: Sequence[Tuple[str, Optional[float], Optional[float]]]) -> None:
        from mechcli.spec.optimize import Candidates
        self.spec = spec
        self.keys = Candidates(spec).keys
        self.objective = objective          # (key, sign) or None
        self.bounds = list(bounds)          # [(key, lo, hi)]

    def results(self, x: Sequence[float]) -> Dict[str, Any]:
        """The problem's results at the design *x* (the variables' values)."""
        from mechcli.spec.optimize import problem_root, read_problem, with_values
        spec = self.spec
        root = problem_root(spec.problem_file, with_values(spec.problem_data,
                                                           dict(zip(self.keys, x))))
        prob = read_problem(spec.problem, root)
        return problem_results(spec.problem, prob)

    def names(self) -> List[str]:
        out = []
        for key, lo, hi in self.bounds:
            if lo is not None:
                out.append(f"{key}>=")
            if hi is not None:
                out.append(f"{key}<=")
        return out

    def __call__(self, X: np.ndarray) -> Tuple[Optional[np.ndarray], np.ndarray, np.ndarray]:
        from mechcli.core.errors import UnsolvableError
        from mechcli.spec.errors import SpecError
        M = len(X)
        f = np.zeros(M) if self.objective else None
        g = np.zeros((M, len(self.names())))
        ok = np.ones(M, dtype=bool)
        for k, x in enumerate(X):
            try:
                r = self.results(x)
            except (UnsolvableError, SpecError, ArithmeticError):
                ok[k] = False
                continue
            try:
                self._read(r, k, f, g)
            except KeyError:
                # a design whose result has no such value (the location of an extreme
                # of a quantity that is constant there): not a design the terms can rate
                ok[k] = False
        return f, g, ok

    def _read(self, r: Dict[str, Any], k: int, f: Optional[np.ndarray], g: np.ndarray) -> None:
        if self.objective and f is not None:
            key, sign = self.objective
            f[k] = sign * float(r[key])
        j = 0
        for key, lo, hi in self.bounds:
            if lo is not None:
                g[k, j] = lo - float(r[key])
                j += 1
            if hi is not None:
                g[k, j] = float(r[key]) - hi
                j += 1

    def at_start(self) -> Dict[str, Any]:
        """The results at the start design; a start the command cannot solve is
        unsolvable (exit 3), said so."""
        from mechcli.core.errors import UnsolvableError
        try:
            return self.results([v.start for v in self.spec.variables])
        except UnsolvableError as exc:
            raise UnsolvableError(f"the start design cannot be analysed by "
                                  f"`{self.spec.problem}`: {exc}") from None


def problem_results(problem: str, prob: Any) -> Dict[str, Any]:
    """The ``--json`` results of ``problem`` (kin or force) on its spec, computed
    in-process without writing anything."""
    if problem == "kin":
        from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
        from mechcli.report import kin as rk
        q = default_quantities(prob.linkage, prob.output.order, [t.name for t in prob.tracers])
        res = analyse_sweep(prob.linkage, prob.input.sweep(), q, prob.output.order,
                            partial=prob.input.partial)
        return rk.scalar_results(prob, q, res)
    from mechcli.commands.force import solve
    from mechcli.report import force as rf
    res, extra, _ = solve(prob, prob.input.sweep())
    return rf.scalar_results(prob, res, None, extra)
