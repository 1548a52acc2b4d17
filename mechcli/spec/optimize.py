"""``mechcli optimize`` problem files -> :class:`OptimizeSpec`.

An optimize spec is a problem spec of another command (``problem = "kin"``
or ``"force"``; its tables inline, or from ``base = "other.toml"``) plus the
tables of the optimization:

* ``[[variable]]``: ``key`` (a dotted path of the problem, as ``--set`` names
  it: ``mechanism.l2``, ``mechanism.ground.D.0``, ``mechanism.point.0.along``;
  or ``objective.phi0``/``psi0``/``theta0``), ``lo``, ``hi``, ``start``;
* ``[objective]``: ``kind = "function" | "path" | "result"``;
* ``[[constraint]]``: ``kind = "transmission" | "crank" | "assembly" | "result"``;
* ``[method]``: ``name``, ``tol``, ``maxiter``, ``popsize``, ``seed``,
  ``starts``, ``polish``, ``gradient``, ``samples``, ``workers``.

Variables are in the problem's numbers (its length unit, degrees).  See
docs/optimize.md.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.reader import MAX_LENGTH, REQUIRED, Section, apply_override, load_spec

#: commands whose specs can be optimized
PROBLEMS = ("kin", "force", "cam")
#: top-level keys that belong to the optimization, not to the problem
OWN_KEYS = ("command", "title", "units", "description", "problem", "base", "variable",
            "objective", "constraint", "method", "expected")
OBJECTIVES = ("function", "path", "result", "pressure_angle")
CONSTRAINTS = ("transmission", "crank", "assembly", "result")
METHODS = ("slsqp", "trust-constr", "nelder-mead", "differential_evolution", "golden",
           "brent")
MEASURES = ("sum_squares", "rms", "mean_abs", "max_abs")
FUNCTIONS = ("log10", "ln", "sqrt", "power", "sin", "cos", "tan", "exp", "reciprocal",
             "polynomial")
#: goal parameters that may be design variables, and whether they are angles
GOAL_VARIABLES = {"phi0": True, "psi0": True, "theta0": True, "delta": True}
#: keys that hold a choice, not a measure: never design variables
DISCRETE = ("branch", "link", "links", "frame", "block", "slider", "guide", "guide_link",
            "count", "step", "table_step", "digits", "frames", "ratio", "samples")
#: a design: the variables' values, in order (a sequence or an array)
Design = Union[Sequence[float], np.ndarray]
#: most design variables (a DE population is 15 x n designs per generation)
MAX_VARIABLES = 32


@record
class VariableSpec:
    key: str            # the dotted path
    lo: float
    hi: float
    start: float
    goal: bool          # a parameter of [objective] (phi0, psi0, theta0)


@record
class MethodSpec:
    name: str
    tol: float
    maxiter: int
    popsize: int
    seed: Optional[int]
    starts: int
    polish: bool
    central: bool
    samples: int
    workers: int
    surface: bool
    surface_points: int


@record
class OptimizeSpec:
    header: Header
    problem: str                 # "kin" | "force"
    problem_file: str            # the file the problem's tables come from (messages)
    problem_data: dict           # the problem's tables (overrides applied), command set
    base: Optional[Path]
    variables: Tuple[VariableSpec, ...]
    objective: dict              # kind and its keys, converted (rad, m)
    constraints: Tuple[dict, ...]
    method: MethodSpec
    expected: dict
    path: Path
    unit: float                  # metres per length unit of the problem


def _merge(base: dict, over: dict) -> dict:
    out = copy.deepcopy(base)
    for k, v in over.items():
        if isinstance(v, dict) and isinstance(out.get(k), dict):
            out[k] = _merge(out[k], v)
        else:
            out[k] = copy.deepcopy(v)
    return out


def _resolve(data: Any, key: str) -> Any:
    """The value at dotted ``key`` of ``data``, or raise KeyError with the part
    that is missing."""
    node = data
    for part in key.split("."):
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                raise KeyError(part)
            node = node[int(part)]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            raise KeyError(part)
    return node


def _numeric_paths(data: Any, prefix: str = "") -> List[str]:
    out = []
    if isinstance(data, dict):
        for k, v in data.items():
            out += _numeric_paths(v, f"{prefix}.{k}" if prefix else k)
    elif isinstance(data, list):
        for i, v in enumerate(data):
            out += _numeric_paths(v, f"{prefix}.{i}")
    elif isinstance(data, (int, float)) and not isinstance(data, bool):
        out.append(prefix)
    return out


def problem_root(spec_file: str, data: dict, unit_name: Optional[str] = None) -> Section:
    """A root Section over a deep copy of the problem's tables."""
    root = Section(copy.deepcopy(data), spec_file, "")
    root.overridden = frozenset()
    return root


def read_problem(problem: str, root: Section) -> Any:
    """The problem command's spec read from ``root`` (full validation)."""
    if problem == "kin":
        from mechcli.spec.kin import read_kin_root
        return read_kin_root(root)
    if problem == "cam":
        from mechcli.spec.cam import read_cam_spec
        return read_cam_spec(root)
    from mechcli.spec.force import read_force_root
    return read_force_root(root)


def _variables(root: Section, problem_file: str, data: dict,
               objective_data: dict) -> Tuple[VariableSpec, ...]:
    out = []
    tables = root.tables("variable")
    if not tables:
        raise root.error("variable", "at least one [[variable]] table", "none")
    if len(tables) > MAX_VARIABLES:
        raise root.error("variable", f"at most {MAX_VARIABLES} design variables",
                         f"{len(tables)}")
    seen = set()
    for t in tables:
        key = t.string("key")
        parts = key.split(".")
        goal = parts[0] == "objective"
        if goal:
            if len(parts) != 2 or parts[1] not in GOAL_VARIABLES:
                raise t.error("key", "objective." + "/".join(GOAL_VARIABLES)
                              + " (the goal parameters that may vary)", f"'{key}'")
            value = objective_data.get(parts[1])
            if value is None and t.has("start"):     # a goal variable needs no value there
                value = t.raw("start")
        else:
            if parts[0] in OWN_KEYS:
                raise t.error("key", "a key of the problem's tables (mechanism..., input...)",
                              f"'{key}'")
            try:
                value = _resolve(data, key)
            except KeyError as exc:
                import difflib
                near = difflib.get_close_matches(key, _numeric_paths(data), n=1, cutoff=0.6)
                hint = f"; did you mean '{near[0]}'?" if near else ""
                raise t.error("key", "a numeric key of the problem spec (e.g. mechanism.l2)",
                              f"'{key}' (no key '{exc.args[0]}' there{hint})") from None
        if parts[-1] in DISCRETE or (len(parts) > 1 and parts[-2] in DISCRETE
                                     and parts[-1].isdigit()):
            raise t.error("key", "a continuous number (a length, coordinate or angle): "
                          "links, branches and counts are not design variables", f"'{key}'")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise t.error("key", "the path of a number",
                          f"'{key}' = {value!r}" if value is not None else f"'{key}' (unset)")
        if key in seen:
            raise t.error("key", "each variable once", f"'{key}' twice")
        seen.add(key)
        lo = t.number("lo", lo=-1e12, hi=1e12)
        hi = t.number("hi", lo=-1e12, hi=1e12)
        if not hi > lo:
            raise t.error("hi", f"a number above lo = {lo:g}", f"{hi:g}")
        start = t.number("start", float(value), lo=-1e12, hi=1e12)
        if not lo <= start <= hi:
            raise t.error("start", f"a start within [lo, hi] = [{lo:g}, {hi:g}]",
                          f"{start:g}" + ("" if t.has("start") else f" (the value of {key})"))
        t.finish()
        out.append(VariableSpec(key, lo, hi, start, goal))
    return tuple(out)


def _deg(sec: Section, name: str, default: Any = REQUIRED, lo: float = -36000.0,
         hi: float = 36000.0) -> Optional[float]:
    v = sec.number(name, default, lo=lo, hi=hi)
    return None if v is None else math.radians(v)


def _function_objective(sec: Section) -> dict:
    data: Dict[str, Any] = {"kind": "function"}
    out = sec.raw("output", 3)
    if isinstance(out, bool) or not isinstance(out, (int, str)) or (
            isinstance(out, int) and out < 1):
        raise sec.error("output", "a link number (its angle) or a slide name ('3', 'E')",
                        repr(out))
    data["output"] = out
    phi0 = sec.raw("phi0", "output_min")
    if isinstance(phi0, str):
        if phi0 not in ("output_min", "output_max"):
            raise sec.error("phi0", "'output_min', 'output_max' (the input's limit position "
                            "where the output is least/greatest) or an angle in degrees",
                            repr(phi0))
        data["phi0"] = phi0
    else:
        data["phi0"] = _deg(sec, "phi0")
    psi0 = sec.raw("psi0", "actual")
    if isinstance(psi0, str):
        if psi0 != "actual":
            raise sec.error("psi0", "'actual' (the output at phi0) or a number", repr(psi0))
        data["psi0"] = None
    else:
        data["psi0"] = (_deg(sec, "psi0") if not isinstance(out, str)
                        else sec.coordinate("psi0"))
    data["measure"] = sec.string("measure", "sum_squares", choices=list(MEASURES))
    if sec.has("phi") or sec.has("psi"):
        # a table of corresponding positions, relative to phi0 and psi0 (习题 7-2)
        phi = sec.numbers("phi")
        psi = sec.numbers("psi", size=len(phi))
        if not 1 <= len(phi) <= 10000:
            raise sec.error("phi", "1 to 10000 input angles", f"{len(phi)}")
        data["dphi"] = np.radians(phi)
        data["dpsi"] = np.radians(psi) if not isinstance(out, str) else np.asarray(psi) * sec.unit
        return data
    name = sec.string("function", choices=list(FUNCTIONS))
    data["function"] = name
    if name == "power":
        data["exponent"] = sec.number("exponent", lo=-100.0, hi=100.0)
    if name == "polynomial":
        coeffs = sec.numbers("coeffs")
        if not 1 <= len(coeffs) <= 16 or any(abs(c) > 1e12 for c in coeffs):
            raise sec.error("coeffs", "1 to 16 coefficients within ±1e12", f"{coeffs!r}")
        data["coeffs"] = tuple(coeffs)
    data["x0"] = sec.number("x0", lo=-1e12, hi=1e12)
    data["xm"] = sec.number("xm", lo=-1e12, hi=1e12)
    if not data["xm"] > data["x0"]:
        raise sec.error("xm", f"a number above x0 = {data['x0']:g}", f"{data['xm']:g}")
    data["n"] = sec.integer("n", 30, lo=2, hi=100000)
    phi_m = sec.number("phi_m", lo=-360.0, hi=360.0)
    if phi_m == 0:
        raise sec.error("phi_m", "a non-zero input swing in degrees (negative: clockwise)", "0")
    data["phi_m"] = math.radians(phi_m)
    if isinstance(out, str):
        data["psi_m"] = sec.coordinate("psi_m")
    else:
        data["psi_m"] = _deg(sec, "psi_m", lo=-360.0, hi=360.0)
    return data


def _path_objective(sec: Section) -> dict:
    data = {"kind": "path", "point": sec.name("point")}
    xs = sec.numbers("x")
    ys = sec.numbers("y", size=len(xs))
    if not 1 <= len(xs) <= 10000:
        raise sec.error("x", "1 to 10000 target points", f"{len(xs)}")
    lim = MAX_LENGTH / sec.unit
    if any(abs(v) > lim for v in xs + ys):
        raise sec.error("x", f"coordinates within ±{lim:g}", "a larger one")
    data["targets"] = np.column_stack([xs, ys]) * sec.unit
    if sec.has("angles"):
        data["angles"] = np.radians(sec.numbers("angles", size=len(xs)))
    else:
        data["angles"] = None
    data["theta0"] = _deg(sec, "theta0", 0.0)
    data["measure"] = sec.string("measure", "sum_squares", choices=list(MEASURES))
    return data


def _result_objective(sec: Section) -> dict:
    return {"kind": "result", "key": sec.string("key"),
            "goal": sec.string("goal", "minimize", choices=["minimize", "maximize"])}


def _constraint(t: Section) -> dict:
    kind = t.string("kind", choices=list(CONSTRAINTS))
    c = {"kind": kind, "path": t.path}
    if kind == "transmission":
        c["min"] = _deg(t, "min", 0.0, lo=0.0, hi=90.0)
        c["max"] = _deg(t, "max", math.degrees(math.pi - c["min"]), lo=90.0, hi=180.0)
        c["over"] = t.string("over", "revolution", choices=["revolution", "range"])
        c["joints"] = tuple(t.strings("joints", []))
    elif kind == "assembly":
        c["over"] = t.string("over", "revolution", choices=["revolution", "range"])
    elif kind == "result":
        c["key"] = t.string("key")
        c["min"] = t.number("min", None)
        c["max"] = t.number("max", None)
        if c["min"] is None and c["max"] is None:
            raise t.error("max", "a bound: min, max or both", "neither")
    t.finish()
    return c


def _method(sec: Section, nvar: int, kind: Optional[str] = None) -> MethodSpec:
    name = sec.string("name", "slsqp" if nvar > 1 else "brent", choices=list(METHODS))
    if name in ("golden", "brent") and nvar != 1:
        raise sec.error("name", "a method for several variables (slsqp, trust-constr, "
                        "nelder-mead, differential_evolution): golden and brent search one",
                        f"'{name}' with {nvar} variables")
    # tol: ftol of SLSQP, gtol/xtol of trust-constr, xatol of NM/golden/Brent,
    # tol of DE (relative spread of the population); error-vs-cost in
    # benchmarks/bench_optimize.py
    # DE stops when the population's spread of f is below tol x |mean f| (scipy's
    # rule; its own default is 1e-2): 1e-4 with the SLSQP polish reaches 例 7-1's
    # optimum to 1e-8 (benchmarks/bench_optimize.py)
    default_tol = {"differential_evolution": 1e-4, "golden": 1e-5}.get(name, 1e-10)
    return MethodSpec(
        name=name,
        tol=sec.number("tol", default_tol, lo=1e-15, hi=1.0),
        maxiter=sec.integer("maxiter", 1000, lo=1, hi=1_000_000),
        popsize=sec.integer("popsize", 15, lo=4, hi=1000),
        seed=sec.integer("seed", 1, lo=0, hi=2**32 - 1),
        starts=sec.integer("starts", 1, lo=1, hi=1000),
        polish=sec.boolean("polish", True),
        central=sec.string("gradient", "central", choices=["central", "forward"]) == "central",
        samples=sec.integer("samples", 360, lo=12, hi=100000),
        workers=sec.integer("workers", 1, lo=1, hi=256),
        # a result goal runs its command once per grid point: no surface unless asked
        surface=sec.boolean("surface", nvar == 2 and kind != "result"),
        surface_points=sec.integer("surface_points", 41, lo=5, hi=401),
    )


def read_optimize_spec(path: str | Path, overrides: Sequence[str] = ()) -> OptimizeSpec:
    """Read and validate a ``mechcli optimize`` spec (exit 2 on any error)."""
    root = load_spec(path, overrides)
    file = root.file
    problem, data, problem_file, base_path, own = _problem_tables(root)
    header = read_header(root, "optimize", default_unit=data.get("units", "mm"))
    if problem != "cam":    # optimize moves the exact linkage
        from mechcli.spec.kin import refuse_approximate
        refuse_approximate(Section(data, problem_file, ""), "optimize")
    # the problem itself must be a valid spec of its command; a key this file gives
    # (or --set) is reported against this file, a key of the base against the base
    try:
        prob = read_problem(problem, problem_root(problem_file, data))
    except SpecError as exc:
        if base_path is not None and (exc.key or "").split(".")[0].split("[")[0] in own:
            raise SpecError(file, exc.key, exc.expected, exc.got, exc.suggestion) from None
        raise
    obj_sec = root.table("objective")
    obj_sec.unit = prob.header.scale
    kind = obj_sec.string("kind", choices=list(OBJECTIVES))
    variables = _variables(root, problem_file, data, obj_sec.data)
    objective = _objective(root, obj_sec, kind, problem, variables)
    _check_goal_variables(file, variables, kind, objective)
    constraints = _constraints(root, problem, prob.header.scale)
    method_sec = root.table("method") if root.has("method") else Section({}, file, "method")
    method = _method(method_sec, len(variables), kind)
    method_sec.finish()
    expected = read_expected(root, overrides)
    root.finish()
    spec = OptimizeSpec(header, problem, problem_file, data, base_path, variables, objective,
                        tuple(constraints), method, expected, Path(file), prob.header.scale)
    _check_bounds(spec)
    return spec


def _problem_tables(root: Section) -> Tuple[str, dict, str, Optional[Path], dict]:
    """The problem's command, its tables (this file's over ``base``'s, ``command``
    set), the file they come from, the base's path and this file's own tables."""
    file = root.file
    problem = root.string("problem", None, choices=list(PROBLEMS))
    base = root.string("base", None)
    own = {k: v for k, v in root.data.items() if k not in OWN_KEYS}
    for k in own:           # the problem's tables: validated by the problem's reader
        root.raw(k, None)
    base_path = None
    if base is not None:
        base_path = (Path(file).parent / base)
        try:
            found = base_path.is_file()
        except (OSError, ValueError):       # a name too long, a NUL byte
            found = False
        if not found:
            raise root.error("base", "an existing spec file (relative to this one)",
                             f"'{base}' (no such file: {base_path})")
        base_root = load_spec(base_path)
        bdata = dict(base_root.data)
        base_cmd = bdata.get("command", "kin")
        if problem is None:
            problem = base_cmd
        if base_cmd != problem or problem not in PROBLEMS:
            raise root.error("base", f"a {' or '.join(PROBLEMS)} spec"
                             + (f" (problem = '{problem}')" if root.has("problem") else ""),
                             f"a '{base_cmd}' spec")
        data = _merge({k: v for k, v in bdata.items() if k not in ("expected", "command")},
                      own)
        problem_file = str(base_path)
    else:
        problem = problem or "kin"
        data = own
        problem_file = file
        if "units" in root.data:
            data = dict(data, units=root.data["units"])
    if "units" not in data and "units" in root.data:
        data["units"] = root.data["units"]
    return problem, dict(data, command=problem), problem_file, base_path, own


def _objective(root: Section, obj_sec: Section, kind: str, problem: str,
               variables: Tuple[VariableSpec, ...]) -> dict:
    """``[objective]`` of its *kind*, converted (rad, m); ``path`` = "objective"."""
    if kind == "function":
        objective = _function_objective(obj_sec)
    elif kind == "path":
        objective = _path_objective(obj_sec)
    elif kind == "pressure_angle":
        # 例 7-2: the cam angle is the one variable (key = "objective.delta", degrees)
        if problem != "cam":
            raise obj_sec.error("kind", "a goal of a kin or force problem (function, path, "
                                "result)", f"'pressure_angle' with problem = '{problem}'")
        objective = {"kind": kind, "goal": obj_sec.string("goal", "maximize",
                                                            choices=["maximize", "minimize"])}
        if [v.key for v in variables] != ["objective.delta"]:
            raise root.error("variable", "one [[variable]] with key = \"objective.delta\" "
                             "(the cam angle in degrees)",
                             ", ".join(v.key for v in variables))
    else:
        objective = _result_objective(obj_sec)
    if problem == "cam" and kind != "pressure_angle":
        raise obj_sec.error("kind", "'pressure_angle' for a cam problem", f"'{kind}'")
    objective["path"] = "objective"
    obj_sec.finish()
    return objective


def _check_goal_variables(file: str, variables: Tuple[VariableSpec, ...], kind: str,
                          objective: dict) -> None:
    """A variable of ``[objective]`` (phi0, psi0, theta0, delta) must be one the goal
    uses, else it would not move (exit 2)."""
    for i, v in enumerate(variables):
        if not v.goal:
            continue
        name = v.key.split(".")[1]
        used = {"phi0": kind == "function" and not isinstance(objective.get("phi0"), str),
                "psi0": kind == "function" and objective.get("psi0") is not None,
                "theta0": kind == "path" and objective.get("angles") is not None,
                "delta": kind == "pressure_angle"}[name]
        if not used:
            need = {"phi0": "[objective] phi0 given as an angle (not output_min/output_max)",
                    "psi0": "[objective] psi0 given as an angle (not actual)",
                    "theta0": "a path goal with angles = [...]",
                    "delta": "kind = \"pressure_angle\""}[name]
            raise SpecError(file, f"variable[{i}].key", f"a goal parameter the goal uses "
                            f"({v.key} needs {need})", f"'{v.key}', which would not move")


def _constraints(root: Section, problem: str, scale: float) -> List[dict]:
    """Every ``[[constraint]]`` (none for a cam problem), lengths in metres."""
    constraints = []
    if problem == "cam" and root.has("constraint"):
        raise root.error("constraint", "no constraints for a cam problem (the cam angle's "
                         "bounds are the variable's lo and hi)", "[[constraint]] tables")
    for t in root.tables("constraint", []):
        t.unit = scale
        constraints.append(_constraint(t))
    return constraints


def _check_bounds(spec: OptimizeSpec) -> None:
    """Each variable's lo and hi (the others at their starts) must be values the
    problem's reader accepts: a bound outside a key's own range is exit 2 here,
    never a failed design deep inside the search."""
    for i, v in enumerate(spec.variables):
        if v.goal:
            continue
        for side in ("lo", "hi"):
            x = {w.key: w.start for w in spec.variables}
            x[v.key] = getattr(v, side)
            try:
                read_problem(spec.problem, problem_root(spec.problem_file,
                                                        with_values(spec.problem_data, x)))
            except SpecError as exc:
                raise SpecError(str(spec.path), f"variable[{i}].{side}",
                                f"a value that {v.key} accepts", f"{getattr(v, side):g}: "
                                f"{exc.expected} expected there") from None


def with_values(data: dict, values: Dict[str, float]) -> dict:
    """A deep copy of the problem's tables with ``{dotted key: value}`` set."""
    d = copy.deepcopy(data)
    for key, value in values.items():
        if key.split(".")[0] == "objective":
            continue
        old = _resolve(d, key)
        apply_override("", d, key, int(value) if isinstance(old, int) and float(
            value).is_integer() and abs(value) < 2**53 else float(value))
    return d


class Candidates:
    """``candidates(X) -> (linkage, ok, params)`` for a population: every row's
    problem tables read (as ``--set`` would) into a linkage, the linkages
    stacked into one batched linkage.  Picklable (for ``--workers``)."""

    def __init__(self, spec: OptimizeSpec) -> None:
        self.problem = spec.problem
        self.file = spec.problem_file
        self.data = spec.problem_data
        self.keys = [v.key for v in spec.variables]
        self.goal = [(i, v.key.split(".")[1]) for i, v in enumerate(spec.variables) if v.goal]
        self.starts = [v.start for v in spec.variables]
        self.lo = np.array([v.lo for v in spec.variables])
        self.hi = np.array([v.hi for v in spec.variables])
        self.affine: Any = None         # (base, slots, x0, p0, J) of the fast path
        self.followers: dict = {}
        if self.problem != "cam":
            # secondary drivers (a five-bar's second crank) follow the first by
            # their ratio and phase, which are not design variables (DISCRETE)
            self.followers = dict(self._read(self.starts)[3])
            self._probe()

    # -- the fast path: parameters affine in the variables --------------------
    @staticmethod
    def _slots(linkage: Any) -> List[Tuple[int, str]]:
        return [(i, f) for i, el in enumerate(linkage.elements)
                for f in el.lengths_ + el.angles_ + ("branch",) if hasattr(el, f)]

    def _params(self, x: Design) -> Tuple[Any, np.ndarray]:
        lk = self.linkage_of(x)
        return lk, np.array([float(getattr(lk.elements[i], f)) for i, f in self._slots(lk)])

    def _probe(self) -> None:
        """Most readers map a variable to the engine's parameters by a constant
        factor (a unit, degrees to radians): then a population's linkages are
        ``p0 + J (x - x0)``, one matrix product, instead of one reading per
        design.  The map is measured on the variables' axes and accepted only
        if it predicts the parameters at two other points of the box to 1e-12
        (else every design is read, as ``--set`` would)."""
        x0 = np.array(self.starts, dtype=float)
        try:
            base, p0 = self._params(x0)
            cols = []
            for i in range(len(x0)):
                h = 0.5 * (self.hi[i] - x0[i]) if self.hi[i] - x0[i] >= x0[i] - self.lo[i] \
                    else -0.5 * (x0[i] - self.lo[i])
                x = x0.copy()
                x[i] += h
                cols.append((self._params(x)[1] - p0) / h)
            J = np.column_stack(cols) if cols else np.zeros((p0.size, 0))
            rng = np.random.default_rng(0)
            for _ in range(2):
                x = self.lo + rng.random(len(x0)) * (self.hi - self.lo)
                p = self._params(x)[1]
                if not np.allclose(p, p0 + J @ (x - x0), rtol=1e-12,
                                   atol=1e-12 * max(1.0, float(np.max(np.abs(p0))))):
                    return
        except SpecError:
            return
        slots = self._slots(base)
        if any(f == "branch" and np.any(J[k] != 0) for k, (i, f) in enumerate(slots)):
            return
        self.affine = (base, slots, x0, p0, J)

    def _affine_linkage(self, X: np.ndarray) -> Any:
        import dataclasses as dc

        from mechcli.core.linkage import Linkage
        base, slots, x0, p0, J = self.affine
        P = p0[None, :] + (X - x0[None, :]) @ J.T          # (M, parameters)
        fields: Dict[int, Dict[str, Any]] = {}
        for k, (i, f) in enumerate(slots):
            if f != "branch" and np.any(J[k] != 0):
                fields.setdefault(i, {})[f] = P[:, k][:, None]
        if not fields:              # only goal variables vary: one linkage, broadcast
            fields = {slots[0][0]: {slots[0][1]: np.full((len(X), 1), p0[0])}} if slots else {}
        els = [dc.replace(el, **fields[i]) if i in fields else el
               for i, el in enumerate(base.elements)]
        return Linkage(base.frame, tuple(els))

    def linkage_of(self, x: Design) -> Any:
        return self._read(x)[1]

    def _read(self, x: Design) -> Tuple[str, Any, tuple, dict, Optional[float]]:
        from mechcli.spec.kin import read_mechanism
        root = problem_root(self.file, with_values(self.data, dict(zip(self.keys, x))))
        read_header(root, self.problem, default_unit="mm")
        return read_mechanism(root)

    def parameters(self, x: Design) -> np.ndarray:
        """The engine's numbers of the design x (every element parameter)."""
        return self._params(x)[1]

    def __call__(self, X: np.ndarray) -> Tuple[Any, np.ndarray, Dict[str, np.ndarray]]:
        from mechcli.core.linkage import stack
        X = np.atleast_2d(X)
        params = {}
        for i, name in self.goal:
            params[name] = np.radians(X[:, i]) if GOAL_VARIABLES[name] else X[:, i]
        if self.affine is not None:
            return self._affine_linkage(X), np.ones(len(X), dtype=bool), params
        linkages, ok = [], np.ones(len(X), dtype=bool)
        fallback = None
        for k, x in enumerate(X):
            try:
                lk = self.linkage_of(x)
                fallback = fallback or lk
            except SpecError:
                lk = None
                ok[k] = False
            linkages.append(lk)
        if fallback is None:
            fallback = self.linkage_of(self.starts)
        linkages = [lk if lk is not None else fallback for lk in linkages]
        return stack(linkages), ok, params


# ---------------------------------------------------------------------------
# the checks of a linkage problem against its linkage, before it is built
# (mechcli.core.optimize.build): exit 2 naming the spec's key

def check_linkage_problem(spec: OptimizeSpec,
                          cands: Candidates) -> Optional[Tuple[np.ndarray, np.ndarray]]:
    """What the linkage of *cands* cannot give the goal and constraints of *spec*
    (exit 2): a variable that moves nothing, a function output it does not report
    (or a named function's bad interval), a transmission angle without an RRR
    dyad, crank conditions without a four-bar.  Returns a function goal's
    :func:`function_targets` (None for another goal)."""
    obj, file = spec.objective, str(spec.path)
    base = cands.linkage_of(cands.starts)
    if obj["kind"] in ("function", "path"):
        _check_variables_move(spec, cands)
    if obj["kind"] == "function":
        out = obj["output"]
        names = (base.rotating_links if not isinstance(out, str) else base.slide_names)
        if out not in names:
            raise SpecError(file, "objective.output",
                            "a link whose angle the linkage reports, or a slide: one of "
                            + ", ".join(repr(n) for n in base.rotating_links + base.slide_names),
                            repr(out))
    targets = function_targets(spec) if obj["kind"] == "function" else None
    for c in spec.constraints:
        if c["kind"] == "transmission":
            rrr = base.transmission_joints
            if not rrr:
                raise SpecError(file, f"{c['path']}.kind", "a linkage with an RRR dyad "
                                "(the transmission angle is the angle at its joint)",
                                "no RRR dyad in the mechanism")
            bad = [j for j in c["joints"] if j not in rrr]
            if bad:
                raise SpecError(file, f"{c['path']}.joints", "joints of RRR dyads: "
                                + ", ".join(rrr), ", ".join(bad))
        elif c["kind"] == "crank":
            from mechcli.core.errors import DescribedError
            from mechcli.core.optimize.terms import four_bar_lengths
            try:
                four_bar_lengths(base)
            except DescribedError:
                raise SpecError(file, f"{c['path']}.kind", "a four-bar (one crank and one RRR "
                                "dyad) for the book's g1 ... g6; use kind = \"assembly\" for "
                                "other linkages", "'crank'") from None
    return targets


def _check_variables_move(spec: OptimizeSpec, cands: Candidates) -> None:
    """A variable of the problem's tables must move the linkage (input.omega1 does not
    change a position goal): exit 2 instead of a variable that stays at its start."""
    x0 = np.array(cands.starts, dtype=float)
    base = cands.parameters(x0)
    for i, v in enumerate(spec.variables):
        if v.goal:
            continue
        x = x0.copy()
        x[i] = v.hi if v.hi != x0[i] else v.lo
        if np.array_equal(cands.parameters(x), base):
            raise SpecError(str(spec.path), f"variable[{i}].key", "a number that changes the "
                            "linkage (a length, coordinate or angle of [mechanism])",
                            f"'{v.key}', which moves nothing the goal depends on")


def function_targets(spec: OptimizeSpec) -> Tuple[np.ndarray, np.ndarray]:
    """(dphi, dpsi) [rad] of a function goal: given (``dphi``/``dpsi``), or of a named
    function, x from x0 to xm mapped linearly onto the input swing phi_m, y onto the
    output swing psi_m (§3.5's scaling)."""
    obj = spec.objective
    if "dphi" in obj:
        return (np.asarray(obj["dphi"], dtype=float), np.asarray(obj["dpsi"], dtype=float))
    from mechcli.core.errors import DescribedError
    from mechcli.core.synth.targets import make_function
    f = make_function(obj["function"], exponent=obj.get("exponent"), coeffs=obj.get("coeffs"))
    try:
        f.check_domain(obj["x0"], obj["xm"])
    except DescribedError as exc:
        raise SpecError(str(spec.path), "objective.x0", "an interval inside the function's "
                        "domain", str(exc)) from None
    n = obj["n"]
    x = obj["x0"] + (obj["xm"] - obj["x0"]) * np.arange(1, n + 1) / n
    y0, ym = float(f(obj["x0"])), float(f(obj["xm"]))
    if not np.isfinite(y0) or not np.isfinite(ym) or y0 == ym:
        raise SpecError(str(spec.path), "objective.xm", "an interval where f(x0) != f(xm)",
                        f"f(x0) = {y0:g}, f(xm) = {ym:g}")
    dphi = obj["phi_m"] * np.arange(1, n + 1) / n
    dpsi = obj["psi_m"] * (f(x) - y0) / (ym - y0)
    return np.asarray(dphi, dtype=float), np.asarray(dpsi, dtype=float)


def result_bounds(spec: OptimizeSpec) -> List[Tuple[str, Optional[float], Optional[float]]]:
    """``(key, min, max)`` of every ``kind = "result"`` constraint, in order."""
    return [(c["key"], c["min"], c["max"]) for c in spec.constraints if c["kind"] == "result"]


def result_objective(spec: OptimizeSpec) -> Optional[Tuple[str, float]]:
    """``(key, sign)`` of a result objective (sign -1 to maximize), else None."""
    obj = spec.objective
    if obj["kind"] != "result":
        return None
    return obj["key"], -1.0 if obj["goal"] == "maximize" else 1.0


def check_result_keys(spec: OptimizeSpec, results: Dict[str, object]) -> None:
    """Every result key of *spec* names a numeric result of its problem (*results*:
    the problem's ``--json`` results at the start design); exit 2 otherwise."""
    import difflib
    wanted = ([("objective.key", spec.objective["key"])] if spec.objective["kind"] == "result"
              else []) + [(f"{c['path']}.key", c["key"]) for c in spec.constraints
                          if c["kind"] == "result"]
    numeric = [k for k, v in results.items()
               if isinstance(v, (int, float)) and not isinstance(v, bool)]
    for where, key in wanted:
        if key not in numeric:
            near = difflib.get_close_matches(key, numeric, n=1, cutoff=0.5)
            raise SpecError(str(spec.path), where,
                            f"a numeric result of `mechcli {spec.problem} --json`",
                            f"'{key}'" + (f"; did you mean '{near[0]}'?" if near else ""))
