"""``mechcli synth`` problem files -> :class:`SynthSpec` (SI units, radians).

A spec holds one design problem in ``[synthesis]`` (its ``kind`` says which),
or several in ``[[case]]`` tables of the same keys (【例 3-8】's four cases in
one file).  Points are rows ``[x, y]`` in the spec's length unit, poses rows
``[x, y, phi]`` with phi in degrees, angles in degrees (see docs/synth.md).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Dict, Optional, Sequence, Tuple, Union

from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.reader import MAX_LENGTH, REQUIRED, Section, load_spec

KINDS = ("two_positions", "three_positions", "moving_pivots", "coupler_poses", "burmester",
         "function", "slider_function", "rocker_slider", "quick_return",
         "atlas_page", "type_chart", "atlas_build", "path")
#: the atlas kinds (a digital Hrones-Nelson atlas; ratios in crank lengths)
ATLAS_KINDS = ("atlas_page", "type_chart", "atlas_build", "path")
#: link-length ratios of the atlas (the seed's charts run to about 5; a bound keeps
#: the curves of a page drawable)
RATIO_MAX = 100.0
#: most curves of one page, of one build
PAGE_POINTS_MAX = 5000
BUILD_CURVES_MAX = 200_000_000
RATIO_SETS_MAX = 2_000_000
GRID_POINTS_MAX = 100_000
#: most target points of a path: the refinement's arrays grow with revolution samples x
#: targets x a stencil (500 points: about 0.3 GB)
PATH_POINTS_MAX = 500
#: the named functions of function generation (core.synth.targets.NAMES)
FUNCTIONS = ("log10", "ln", "sqrt", "power", "sin", "cos", "tan", "exp", "reciprocal",
             "polynomial")
#: largest number of cases in one spec (each is a design and a picture)
MAX_CASES = 64

Point = Tuple[float, float]


@record
class Problem:
    """One design problem: its kind and its keys, converted (lengths in m,
    angles in rad); ``path`` is the table's dotted path, for messages."""

    kind: str
    path: str
    data: dict
    keys: Tuple[str, ...] = ()     # the keys the spec's table has (for messages)


@record
class SynthSpec:
    header: Header
    cases: Tuple[Problem, ...]
    multi: bool               # the spec has [[case]] tables (results per case)
    expected: dict
    path: Optional[Path]
    draw: bool                # pictures of the design in its positions


def _points(sec: Section, name: str, count: Any,
            default: Any = REQUIRED) -> Optional[Tuple[Tuple[float, float], ...]]:
    """Rows [x, y] in the spec's unit -> tuples in metres (*default* if absent)."""
    lim = MAX_LENGTH / sec.unit
    rows = sec.rows(name, default, width=2, count=count, lo=-lim, hi=lim, row="[x, y]")
    if rows is None:
        return None
    return tuple((x * sec.unit, y * sec.unit) for x, y in rows)


def _point(sec: Section, name: str, default: Any = ...) -> Optional[Tuple[float, float]]:
    """One point [x, y] -> metres (None if absent and optional)."""
    lim = MAX_LENGTH / sec.unit
    xy = sec.numbers(name, size=2) if default is ... else sec.numbers(name, default, size=2)
    if xy is None:
        return None
    for i, v in enumerate(xy):
        if abs(v) > lim:
            raise SpecError(sec.file, sec.key(f"{name}[{i}]"),
                            f"a coordinate within ±{lim:g}", f"{v:g}")
    return (xy[0] * sec.unit, xy[1] * sec.unit)


def _line(sec: Section, name: str) -> Optional[Tuple[float, float, float]]:
    """``[a, b, c]``: the line a x + b y = c (c in the spec's unit) -> (a, b, c [m])."""
    abc = sec.numbers(name, None, size=3)
    if abc is None:
        return None
    a, b, c = abc
    if a == 0 and b == 0:
        raise sec.error(name, "[a, b, c] of a line a x + b y = c with a or b not 0",
                        repr(abc))
    return (a, b, c * sec.unit)


def _poses(sec: Section, name: str,
           count: Any) -> Tuple[Tuple[Tuple[float, float], ...], Tuple[float, ...]]:
    """Rows [x, y, phi_deg] -> ((x [m], y [m]), ...), (phi [rad], ...)."""
    lim = MAX_LENGTH / sec.unit
    rows = sec.rows(name, width=3, count=count, lo=-lim, hi=lim, row="[x, y, phi_deg]")
    for i, (_x, _y, phi) in enumerate(rows):
        if abs(phi) > 36000:
            raise SpecError(sec.file, sec.key(f"{name}[{i}][2]"), "an angle within ±36000°",
                            f"{phi:g}")
    return (tuple((x * sec.unit, y * sec.unit) for x, y, _ in rows),
            tuple(math.radians(p) for _, _, p in rows))


def _angles(sec: Section, name: str, count: Any,
            default: Any = ...) -> Optional[Tuple[float, ...]]:
    """An array of angles in degrees -> radians."""
    vals = sec.numbers(name) if default is ... else sec.numbers(name, default)
    if vals is None:
        return None
    few, many = (count, count) if isinstance(count, int) else count
    if not few <= len(vals) <= many:
        want = f"{few}" if few == many else f"{few} to {many}"
        raise sec.error(name, f"an array of {want} angles [deg]", f"{len(vals)} values")
    for i, v in enumerate(vals):
        if abs(v) > 36000:
            raise SpecError(sec.file, sec.key(f"{name}[{i}]"), "an angle within ±36000°",
                            f"{v:g}")
    return tuple(math.radians(v) for v in vals)


def _deg(sec: Section, name: str, default: Any = ..., lo: float = -36000.0,
         hi: float = 36000.0) -> Optional[float]:
    v = sec.number(name, lo=lo, hi=hi) if default is ... else \
        sec.number(name, default, lo=lo, hi=hi)
    return None if v is None else math.radians(v)


def _misspelt(sec: Section, names: Sequence[str], want: str,
              got: str = "nothing") -> SpecError:
    """A SpecError for a missing choice among *names*: it names a stray key of the table
    that is close to one of them (``pivot_lin`` for ``pivot_line``) when there is one."""
    import difflib
    strays = [k for k in sec.data if k not in sec._known and k not in sec._declared]
    for name in names:
        near = difflib.get_close_matches(name, strays, n=1, cutoff=0.6)
        if near:
            return SpecError(sec.file, sec.key(near[0]), f"{want} (missing)",
                             f"unknown key '{near[0]}'", name)
    return sec.error(names[0], want, got)


def _pivot(sec: Section,
           name: str) -> Tuple[Optional[Tuple[float, float]], Optional[Tuple[float, float, float]]]:
    """A fixed pivot given as a point ``name`` or a line ``name_line``."""
    point = _point(sec, name, None)
    line = _line(sec, f"{name}_line")
    if point is not None and line is not None:
        raise sec.error(f"{name}_line", f"either {name} or {name}_line, not both", "both")
    return point, line


# --------------------------------------------------------------------- the kinds
def _two_positions(sec: Section) -> Dict[str, Any]:
    B, C = _points(sec, "B", 2), _points(sec, "C", 2)
    shared = _line(sec, "pivot_line")
    A, A_line = _pivot(sec, "A")
    D, D_line = _pivot(sec, "D")
    for name, p, ln in (("A", A, A_line), ("D", D, D_line)):
        if p is None and ln is None and shared is None:
            raise _misspelt(sec, (name, f"{name}_line", "pivot_line"),
                            f"{name} = [x, y], {name}_line = [a, b, c] or pivot_line "
                            "(two positions leave each fixed pivot anywhere on a bisector)")
        if shared is not None and (p is not None or ln is not None):
            raise sec.error("pivot_line", f"pivot_line or {name}/{name}_line, not both",
                            "both")
    return dict(B=B, C=C, A=A, D=D, line_A=A_line or (shared if A is None else None),
                line_D=D_line or (shared if D is None else None), rigid_tol=_rigid_tol(sec))


def _rigid_tol(sec: Section) -> float:
    """How much |BC| may vary between the given positions, relative to their size: the
    book's program allows 1e-2 mm (1e-4 of ~100 mm); 1e-12 is round-off of exact data."""
    return sec.number("rigid_tol", 1e-4, lo=1e-12, hi=1e-1)


def _three_positions(sec: Section) -> Dict[str, Any]:
    return dict(B=_points(sec, "B", 3), C=_points(sec, "C", 3), rigid_tol=_rigid_tol(sec))


def _moving_pivots(sec: Section) -> Dict[str, Any]:
    M, phi = _poses(sec, "poses", 3)
    return dict(A=_point(sec, "A"), D=_point(sec, "D"), M=M, phi=phi)


def _coupler_poses(sec: Section) -> Dict[str, Any]:
    M, phi = _poses(sec, "poses", 3)
    method = sec.string("method", "matrix", choices=["matrix", "nonlinear"])
    data = dict(A=_point(sec, "A"), D=_point(sec, "D"), M=M, phi=phi, method=method)
    # tol: the solver's tolerance on the equations, relative to the linkage size
    # (1e-15 is round-off; above 1e-3 a "design" is a sketch)
    data["tol"] = sec.number("tol", 1e-12, lo=1e-15, hi=1e-3)
    data["max_iter"] = sec.integer("max_iter", 100, lo=1, hi=10000)
    data["guess"] = _points(sec, "guess", 2, None)   # [B1, C1], for the nonlinear solve
    return data


def _burmester(sec: Section) -> Dict[str, Any]:
    M, phi = _poses(sec, "poses", (4, 5))
    data = dict(M=M, phi=phi)
    if len(M) == 5:
        pair = sec.raw("pairs", [1, 2])
        if not (isinstance(pair, list) and len(pair) == 2 and all(
                isinstance(v, int) and not isinstance(v, bool) and 1 <= v <= 4 for v in pair)
                and pair[0] != pair[1]):
            raise sec.error("pairs", "two different Burmester pair numbers 1..4, e.g. [1, 2]",
                            repr(pair))
        data["pairs"] = tuple(pair)
    else:
        # points on each curve: the picture's resolution, not an accuracy knob
        data["samples"] = sec.integer("samples", 721, lo=37, hi=100001)
    return data


def _function(sec: Section) -> Dict[str, Any]:
    method = sec.string("method", "precision", choices=["precision", "chebyshev",
                                                        "least_squares"])
    data = dict(method=method, crank=sec.length("crank", 1.0 * sec.unit))
    if sec.has("theta1") or sec.has("theta3"):
        if method != "precision":
            raise sec.error("theta1", "theta1/theta3 only with method = \"precision\" "
                            "(give a function for chebyshev or least_squares)", method)
        data["theta1"] = _angles(sec, "theta1", (3, 5))
        data["theta3"] = _angles(sec, "theta3", (len(data["theta1"]),) * 2)
        data["alpha0"], data["phi0"] = _origins(sec, len(data["theta1"]), False)
        return data
    name = sec.string("function", choices=list(FUNCTIONS) + ["table"])
    data["function"] = name
    if name == "power":
        data["exponent"] = sec.number("exponent", lo=-100.0, hi=100.0)
    if name == "polynomial":
        coeffs = sec.numbers("coeffs")      # c0 + c1 x + c2 x^2 + ... (ascending powers)
        if len(coeffs) > 16 or any(abs(c) > 1e12 for c in coeffs):
            raise sec.error("coeffs", "at most 16 coefficients within ±1e12",
                            f"{len(coeffs)} coefficients, largest {max(map(abs, coeffs)):g}")
        data["coeffs"] = tuple(coeffs)
    if name == "table":
        data["table_x"] = tuple(sec.numbers("table_x"))
        data["table_y"] = tuple(sec.numbers("table_y", size=len(data["table_x"])))
        for key in ("table_x", "table_y"):     # as x0, xm: squares stay finite
            big = [v for v in data[key] if abs(v) > 1e12]
            if big:
                raise sec.error(key, "values within ±1e12", f"{big[0]:g}")
        data["interpolation"] = sec.string("interpolation", "cubic",
                                           choices=["cubic", "linear"])
        tx = data["table_x"]
        if len(tx) < 2 or any(b <= a for a, b in zip(tx, tx[1:])):
            raise sec.error("table_x", "at least 2 increasing x values", repr(list(tx)))
    # a table's own range is the default interval
    bound = None if name == "table" else REQUIRED
    data["x0"] = sec.number("x0", bound, lo=-1e12, hi=1e12)
    data["xm"] = sec.number("xm", bound, lo=-1e12, hi=1e12)
    x0 = data["x0"] if data["x0"] is not None else data["table_x"][0]
    xm = data["xm"] if data["xm"] is not None else data["table_x"][-1]
    if not xm > x0:
        raise sec.error("xm", f"a number above x0 = {x0:g}", f"{xm:g}")
    # swings below 180°: Freudenstein's equation maps the swings onto side links that
    # turn less than half a turn between the ends of the interval
    data["alpha_m"] = _deg(sec, "alpha_m", lo=0.01, hi=179.99)
    data["phi_m"] = _deg(sec, "phi_m", lo=0.01, hi=179.99)
    if method == "precision" and sec.has("x"):
        data["x"] = tuple(sec.numbers("x"))
        if not 3 <= len(data["x"]) <= 5:
            raise sec.error("x", "an array of 3 to 5 precision points", f"{len(data['x'])}")
        if any(not x0 <= v <= xm for v in data["x"]):
            raise sec.error("x", f"points within [x0, xm] = [{x0:g}, {xm:g}]",
                            repr(list(data["x"])))
        count = len(data["x"])
    elif method == "precision" and name == "table" and not sec.has("n"):
        count = len(data["table_x"])          # the table's own points are the precision points
        if not 3 <= count <= 5:
            raise sec.error("table_x", "3 to 5 points (they are the precision points), or "
                            "give x or n", f"{count}")
    else:
        lo = 3 if method != "least_squares" else 4
        hi = 5 if method != "least_squares" else 10000
        data["n"] = count = sec.integer("n", 3 if method != "least_squares" else 11,
                                        lo=lo, hi=hi)
        if method == "precision":       # n evenly spaced precision points
            data["x"] = tuple(x0 + (xm - x0) * i / (count - 1) for i in range(count))
    data["alpha0"], data["phi0"] = _origins(sec, count, method == "least_squares")
    # samples of the structural-error curve: its maximum is read on them (the error
    # of that maximum is measured in benchmarks/bench_synth.py)
    data["samples"] = sec.integer("samples", 1001, lo=11, hi=1000001)
    return data


def _origins(sec: Section, count: int,
             both: bool) -> Tuple[Optional[float], Optional[float]]:
    """alpha0, phi0 [rad]: 3 precision points (or least squares, *both*) need both,
    4 exactly one (the other is solved), 5 neither (both are solved)."""
    a0, p0 = _deg(sec, "alpha0", None), _deg(sec, "phi0", None)
    given = [k for k, v in (("alpha0", a0), ("phi0", p0)) if v is not None]
    if both or count == 3:
        if count == 3 and not both and not given:
            return 0.0, 0.0         # angles measured from the frame line (例 3-6)
        want, ok = "both alpha0 and phi0", len(given) == 2
    elif count == 4:
        want, ok = "exactly one of alpha0 and phi0 (4 points solve the other)", len(given) == 1
    else:
        want, ok = "neither alpha0 nor phi0 (5 points solve both)", not given
    if not ok:
        raise sec.error(given[-1] if given else "alpha0", want, ", ".join(given) or "neither")
    return a0, p0


def _lengths_list(sec: Section, name: str, size: Any) -> Tuple[float, ...]:
    """*size* slider positions in the spec's unit -> metres (each within ±MAX_LENGTH)."""
    vals = sec.numbers(name, size=size)
    lim = MAX_LENGTH / sec.unit
    for i, v in enumerate(vals):
        if abs(v) > lim:
            raise SpecError(sec.file, sec.key(f"{name}[{i}]"), f"a position within ±{lim:g}",
                            f"{v:g}")
    return tuple(v * sec.unit for v in vals)


def _slider_function(sec: Section) -> Dict[str, Any]:
    """Crank angle <-> slider position: 3 pairs (the offset e is found), or 2 pairs
    with a given offset e (习题 3-12)."""
    e = sec.coordinate("e", None)
    count = 2 if e is not None else 3
    theta1 = _angles(sec, "theta1", (count, count))
    return dict(theta1=theta1, s=_lengths_list(sec, "s", count), e=e)


def _rocker_slider(sec: Section) -> Dict[str, Any]:
    """Rocker angle <-> slider position, 3 pairs, the guide's offset e given (习题 3-9)."""
    return dict(phi=_angles(sec, "phi", (3, 3)), s=_lengths_list(sec, "s", 3),
                e=sec.coordinate("e"))


def _quick_return(sec: Section) -> Dict[str, Any]:
    linkage = sec.string("linkage", "crank_rocker",
                         choices=["crank_rocker", "slider_crank", "guide_bar"])
    # K > 1 (K = 1 has no quick return) up to 1e3 (θ within 0.4° of 180°)
    K = sec.number("K", lo=1.0, hi=1000.0)
    if K <= 1.0:
        raise sec.error("K", "a time ratio K > 1 (K = 1 has no quick return)", f"{K:g}")
    data = dict(linkage=linkage, K=K)
    allowed = _deg(sec, "gamma_allowed", None, lo=0.0, hi=90.0)
    if linkage == "crank_rocker":
        data["rocker"] = sec.length("rocker")
        data["gamma_allowed"] = allowed
        if sec.has("limit_angle"):
            # 习题 3-15: frame and the angle ADC of one limit position instead of the swing
            data["frame"] = sec.length("frame")
            data["limit_angle"] = _deg(sec, "limit_angle", lo=0.01, hi=179.99)
            data["limit"] = sec.string("limit", "best", choices=["best", "extended", "folded"])
            return data
        data["swing"] = _deg(sec, "swing", lo=0.01, hi=179.99)
        given = [k for k in ("pivot_line", "crank", "coupler", "frame") if sec.has(k)]
        want = "exactly one extra condition: pivot_line, crank, coupler or frame"
        if not given:
            raise _misspelt(sec, ("pivot_line", "crank", "coupler", "frame", "limit_angle"),
                            want, "none")
        if len(given) != 1:
            raise sec.error(given[1], want, ", ".join(given))
        cond = given[0]
        data[cond] = _line(sec, cond) if cond == "pivot_line" else sec.length(cond)
        # which of the two solutions (A left or right of the y axis); "best": larger γmin
        data["branch"] = sec.string("branch", "best", choices=["best", "left", "right"])
    elif linkage == "slider_crank":
        data["gamma_allowed"] = allowed
        if sec.has("H") and (sec.has("crank") or sec.has("coupler")):
            raise sec.error("crank", "either H and e (习题 3-16) or crank and coupler (the "
                            "stroke is sought), not both", "H and crank/coupler")
        if sec.has("H"):
            data["H"] = sec.length("H")
            data["e"] = sec.length("e")
        else:
            # the slides' exam problem 3: crank and coupler given, the stroke sought
            data["crank"] = sec.length("crank")
            data["coupler"] = sec.length("coupler")
            if not data["coupler"] > data["crank"]:
                raise sec.error("coupler", "a coupler longer than the crank "
                                f"({data['crank'] / sec.unit:g})",
                                f"{data['coupler'] / sec.unit:g}")
    else:
        given = [k for k in ("crank", "frame") if sec.has(k)]
        if not given:
            raise _misspelt(sec, ("crank", "frame"), "exactly one of crank or frame", "none")
        if len(given) != 1:
            raise sec.error("frame", "exactly one of crank or frame", ", ".join(given))
        data[given[0]] = sec.length(given[0])
    return data


# -- the atlas -------------------------------------------------------------------------
def _ratio(sec: Section, name: str, default: Any = REQUIRED) -> float:
    return sec.number(name, default, lo=1e-3, hi=RATIO_MAX)


def _span(sec: Section, name: str, default: Any, count: bool = False) -> Tuple[Any, ...]:
    """``[lo, hi]`` (or ``[lo, hi, count]``) of a ratio or a grid coordinate."""
    vals = sec.numbers(name, default)
    want = 3 if count else 2
    if len(vals) != want:
        raise sec.error(name, "[lo, hi, count]" if count else "[lo, hi]", repr(vals))
    lo, hi = vals[0], vals[1]
    if not (abs(lo) <= RATIO_MAX and abs(hi) <= RATIO_MAX and hi >= lo):
        raise sec.error(name, f"lo <= hi within ±{RATIO_MAX:g}", repr(vals))
    if count:
        n = vals[2]
        if n != int(n) or not 1 <= n <= 100000 or (n > 1) != (hi > lo):
            raise sec.error(name, "a whole count from 1 to 100000 (1 exactly when lo = hi)",
                            repr(vals))
        return (float(lo), float(hi), int(n))
    return (float(lo), float(hi))


def _grid(sec: Section) -> Tuple[Tuple[Any, ...], Tuple[Any, ...], float]:
    """The coupler-plane grid of a page: x, y spans and a spacing (crank lengths)."""
    gx = _span(sec, "grid_x", [-1.0, 3.0])
    gy = _span(sec, "grid_y", [-1.0, 1.0])
    h = sec.number("spacing", 0.5, lo=1e-3, hi=RATIO_MAX)
    # points lo, lo + h, ... up to hi (never past it)
    nx, ny = (int(math.floor((g[1] - g[0]) / h + 1e-9)) + 1 for g in (gx, gy))
    if nx * ny > PAGE_POINTS_MAX:
        raise sec.error("spacing", f"at most {PAGE_POINTS_MAX} grid points on a page",
                        f"{nx} x {ny}")
    return gx, gy, h


def _atlas_page(sec: Section) -> Dict[str, Any]:
    data: Dict[str, Any] = {k: _ratio(sec, k) for k in ("A", "B", "C")}
    data["grid_x"], data["grid_y"], data["spacing"] = _grid(sec)
    data["step"] = _deg(sec, "step", 5.0, lo=0.1, hi=45.0)
    return data


def _type_chart(sec: Section) -> Dict[str, Any]:
    raw = sec.raw("A")
    data: Dict[str, Any]
    if isinstance(raw, list):
        data = {"A": tuple(sec.numbers("A"))}
        if not 1 <= len(data["A"]) <= 12 or not all(0 < a <= RATIO_MAX for a in data["A"]):
            raise sec.error("A", f"1 to 12 ratios in (0, {RATIO_MAX:g}]", repr(raw))
    else:
        data = {"A": (_ratio(sec, "A"),)}
    data["B"] = _span(sec, "B", [0.0, 6.0])
    data["C"] = _span(sec, "C", [0.0, 6.0])
    if data["B"][0] < 0 or data["C"][0] < 0:
        raise sec.error("B", "ratios >= 0", repr(data["B"]))
    data["points"] = sec.integer("points", 301, lo=11, hi=2001)
    mark = sec.numbers("mark", None, size=2)
    if mark is not None and not all(0 < v <= RATIO_MAX for v in mark):
        raise sec.error("mark", f"[B, C] ratios in (0, {RATIO_MAX:g}]", repr(mark))
    data["mark"] = tuple(mark) if mark is not None else None
    return data


def _atlas_build(sec: Section) -> Dict[str, Any]:
    data: Dict[str, Any]
    data = {"A": _span(sec, "A", [1.5, 4.5, 9], True), "B": _span(sec, "B", [1.5, 4.5, 9], True),
            "C": _span(sec, "C", [1.5, 4.5, 9], True),
            "grid_x": _span(sec, "grid_x", [-1.5, 3.5, 21], True),
            "grid_y": _span(sec, "grid_y", [-1.5, 2.0, 15], True)}
    for k in ("A", "B", "C"):
        if data[k][0] <= 0:
            raise sec.error(k, "ratios above 0", repr(list(data[k])))
    total = math.prod(data[k][2] for k in ("A", "B", "C", "grid_x", "grid_y"))
    if total > BUILD_CURVES_MAX:
        raise sec.error("A", f"at most {BUILD_CURVES_MAX:g} curves in a build", f"{total:g}")
    # the ratio sets are classified in memory (24 bytes each), the grid too: both bounded
    # so that a build's memory is set by its chunk
    sets = math.prod(data[k][2] for k in ("A", "B", "C"))
    if sets > RATIO_SETS_MAX:
        raise sec.error("A", f"at most {RATIO_SETS_MAX:g} (A, B, C) ratio sets (the counts' "
                        "product)", f"{sets:g}")
    if data["grid_x"][2] * data["grid_y"][2] > GRID_POINTS_MAX:
        raise sec.error("grid_x", f"at most {GRID_POINTS_MAX:g} grid points",
                        f"{data['grid_x'][2] * data['grid_y'][2]:g}")
    data["chunk"] = sec.integer("chunk", 20000, lo=100, hi=1_000_000)
    data["harmonics"] = sec.integer("harmonics", 16, lo=2, hi=64)
    data["directory"] = _inside_out(sec, "directory")
    return data


def _inside_out(sec: Section, key: str) -> Optional[str]:
    """A folder for the atlas *inside* ``--out``: a relative path without ``..``.  A
    spec is data (a teacher's CI runs students' specs): it never chooses where mechcli
    writes; the command line's ``--atlas DIR`` does."""
    from pathlib import PurePosixPath, PureWindowsPath

    raw = sec.string(key, None)
    if raw is None:
        return None
    parts = PurePosixPath(raw.replace("\\", "/")).parts
    if (not raw.strip() or PurePosixPath(raw).is_absolute() or PureWindowsPath(raw).drive
            or PureWindowsPath(raw).is_absolute() or ".." in parts):
        raise sec.error(key, "a folder inside --out (a relative path without '..'; a spec "
                        "never chooses where mechcli writes: give `mechcli synth --atlas "
                        "DIR` for a folder elsewhere)", repr(raw))
    return raw


def _path(sec: Section) -> Dict[str, Any]:
    lim = MAX_LENGTH / sec.unit
    if sec.has("points"):
        data: Dict[str, Any] = {"points": _points(sec, "points", (3, PATH_POINTS_MAX))}
    else:
        xs = sec.numbers("x")
        ys = sec.numbers("y", size=len(xs))
        if not 3 <= len(xs) <= PATH_POINTS_MAX:
            raise sec.error("x", f"3 to {PATH_POINTS_MAX} target points", f"{len(xs)}")
        if any(abs(v) > lim for v in xs + ys):
            raise sec.error("x", f"coordinates within ±{lim:g}", "a larger one")
        data = {"points": tuple((x * sec.unit, y * sec.unit) for x, y in zip(xs, ys))}
    data["closed"] = sec.boolean("closed", True)
    data["angles"] = _angles(sec, "angles", len(data["points"]), None)
    # an atlas directory built by kind = "atlas_build" (relative to this spec); without
    # one, the default atlas is built (once: it is resumed) under --out
    data["atlas"] = sec.string("atlas", None)
    data["k"] = sec.integer("k", 5, lo=1, hi=100)
    data["refine"] = sec.string("method", "slsqp", choices=["slsqp", "nelder-mead",
                                                           "trust-constr"])
    data["gamma_min"] = _deg(sec, "gamma_min", 0.0, lo=0.0, hi=89.0)
    return data


READERS = {"two_positions": _two_positions, "three_positions": _three_positions,
           "moving_pivots": _moving_pivots, "coupler_poses": _coupler_poses,
           "burmester": _burmester, "function": _function, "slider_function": _slider_function,
           "rocker_slider": _rocker_slider, "quick_return": _quick_return,
           "atlas_page": _atlas_page, "type_chart": _type_chart, "atlas_build": _atlas_build,
           "path": _path}


#: kinds whose design is a four-bar that either side link may drive
DRIVEN_EITHER_WAY = ("two_positions", "three_positions", "moving_pivots", "coupler_poses",
                     "burmester")


def _problem(sec: Section) -> Problem:
    kind = sec.string("kind", choices=list(KINDS))
    sec.string("name", None)
    data = READERS[kind](sec)
    if kind in DRIVEN_EITHER_WAY:
        # which side link drives the design when it is checked and in linkage.toml
        data["driver"] = {"AB": 1, "CD": 3}[sec.string("driver", "AB", choices=["AB", "CD"])]
    sec.finish()
    return Problem(kind, sec.path, data, tuple(sec.data))


def read_synth_spec(path: Union[str, Path], overrides: Sequence[str] = ()) -> SynthSpec:
    """Read and validate a ``mechcli synth`` spec (SpecError on the first bad key)."""
    root = load_spec(path, overrides)
    header = read_header(root, "synth")
    has_one, has_many = root.has("synthesis"), root.has("case")
    if has_one == has_many:
        raise SpecError(root.file, "synthesis", "a [synthesis] table or [[case]] tables "
                        "(exactly one of them)", "both" if has_one else "neither")
    cases: Tuple[Problem, ...]
    if has_one:
        cases = (_problem(root.table("synthesis")),)
    else:
        tables = root.tables("case")
        if not 1 <= len(tables) <= MAX_CASES:
            raise root.error("case", f"1 to {MAX_CASES} [[case]] tables", f"{len(tables)}")
        cases = tuple(_problem(t) for t in tables)
    out = root.table("output", None)
    draw = True
    if out is not None:
        draw = out.boolean("draw", True)
        out.finish()
    expected = read_expected(root, overrides)
    root.finish()
    return SynthSpec(header, cases, has_many, expected,
                     Path(path) if path is not None else None, draw)
