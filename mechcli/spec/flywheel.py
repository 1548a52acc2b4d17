"""``mechcli flywheel`` problem files -> :class:`FlywheelSpec` (SI units, radians).

The equivalent model on the crank (the equivalent link, 等效构件): its inertia from
a linkage (``[mechanism]`` and ``[[link]]`` tables, read as ``force`` reads them), a
chain of constant ratios, a table against φ or a constant (``[inertia]``); its
moment from the linkage's ``[[load]]`` tables and/or ``[moment]`` terms (a table
against φ, a motor line a − bω, a constant resisting moment, a harmonic series,
piecewise-linear segments), each over one period (``period_deg``: 360 by default,
720 for a four-stroke engine).  ``[motion]`` says what to solve: a run from a start
(``kind = "start"``) or the periodic steady state (``kind = "steady"``);
``[flywheel]`` adds a flywheel (J, or mass and radius of gyration) or sizes one for an
allowed δ, in a steady state or from an energy swing.  Every key a form does not use is
an error naming it.  See docs/flywheel.md.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any, Iterable, Optional, Sequence, Tuple, Union

from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.force import MAX_FORCE, MAX_INERTIA, read_bodies, read_gravity, read_loads
from mechcli.spec.reader import REQUIRED, Section, load_spec

#: the largest |ω| [rad/s] and angle [deg] a spec may give (a 1e6 rad/s shaft is
#: already beyond any machine; angles within a hundred turns)
MAX_OMEGA = 1e6
MAX_ANGLE_DEG = 36000.0
#: the smallest inertia [kg m^2] (a watch wheel is ~1e-10; below, ω² overflows with any moment)
MIN_INERTIA = 1e-12
#: output grid: points over the solved interval (the CSV rows and the plots)
MAX_POINTS = 100_001
METHODS = ("auto", "DOP853", "RK45", "Radau", "book", "energy", "closed_form")
#: rad/s per r/min
RPM = math.pi / 30.0
#: the longest period a table or series may have [deg]: a cycle of 100 turns
MAX_PERIOD_DEG = 36000.0
#: how a moment table's work is integrated (the interpolation that integrates exactly so)
INTEGRATIONS = ("exact", "trapezoid", "simpson")


@record
class InertiaSpec:
    kind: str                    # "linkage", "constant", "table", "chain", "none" (Je = 0)
    J: float = 0.0               # constant [kg m^2]
    phi: tuple = ()              # table [rad]
    values: tuple = ()           # table [kg m^2]
    method: str = "cubic"        # table interpolation
    members: tuple = ()          # chain: (J, ratio)
    masses: tuple = ()           # chain: (m, v/omega1 [m/rad])
    derivative: str = "exact"    # linkage: dJe/dphi exact or by central differences
    step: float = 1e-5           # linkage: difference step [rad]
    samples: int = 3600          # linkage: angles per turn of the Hermite table the motion uses
    period: float = 2 * math.pi  # table: its period [rad]


@record
class MomentSpec:
    constant: float = 0.0                  # [N m]
    drive: Optional[Tuple[float, float]] = None    # Md = a - b omega
    resisting: float = 0.0                 # constant Mr, subtracted
    table: Optional[tuple] = None          # (phi [rad], M [N m], method, period, integration)
    resisting_table: Optional[tuple] = None    # (phi, Mr, method, period, integration)
    harmonic: Optional[tuple] = None       # (a0, (a_k), (b_k), period [rad])
    segments: tuple = ()                   # (phi_from, phi_to, M_from, M_to) [rad, N m]
    torques: tuple = ()                    # chain: (M, ratio)
    loads: bool = False                    # the linkage's [[load]] tables and gravity
    period: float = 2 * math.pi            # [moment] period_deg: the segments' (and default)
    mean: Optional[str] = None             # "constant" | "resisting": the term = "mean"


@record
class MotionSpec:
    kind: str                    # "start" | "steady" | "model" (no [motion]: Je, Me only)
    phi0: float
    omega0: float
    phi_end: Optional[float]
    omega_end: Optional[float]
    t_end: Optional[float]
    method: str
    rtol: float
    atol: float
    step: Optional[float]        # [rad] fixed step of the book's method
    points: int
    root: str
    tol: float
    max_iter: int


@record
class FlywheelPart:
    J: float = 0.0               # a flywheel added [kg m^2] (J, or mass k²)
    delta: Optional[float] = None    # allowed speed fluctuation [δ]: size J_F
    shape: Optional[str] = None  # "rim" | "disc"
    radius: Optional[float] = None     # a rim's mean radius, a disc's radius [m]
    density: Optional[float] = None    # [kg/m^3]: the width of a disc, or of a rim
    thickness: Optional[float] = None  # a rim's radial thickness [m]
    dW: Optional[float] = None         # a given largest energy swing ΔWmax [J] (eq. 6-28)
    omega_mean: Optional[float] = None   # ... and the mean speed [rad/s]
    k: Optional[float] = None          # a radius of gyration [m]: the mass J/k² of a sized J_F
    rpm: bool = False                  # the speeds were given in r/min (also report them so)


@record
class FlywheelSpec:
    header: Header
    linkage: object
    topo: object
    bodies: dict
    gravity: tuple
    loads: tuple
    followers: dict
    inertia: InertiaSpec
    moment: Optional[MomentSpec]
    motion: MotionSpec
    flywheel: FlywheelPart
    plots: bool
    expected: dict
    path: Optional[Path]


def _deg_array(sec: Section, name: str, size: Optional[int] = None) -> Tuple[float, ...]:
    vals = sec.numbers(name, size=size) if size else sec.numbers(name)
    for i, v in enumerate(vals):
        if abs(v) > MAX_ANGLE_DEG:
            raise SpecError(sec.file, sec.key(f"{name}[{i}]"),
                            f"an angle within ±{MAX_ANGLE_DEG:g}°", f"{v:g}")
    return tuple(math.radians(v) for v in vals)


def _period(sec: Section, default: float = 2 * math.pi) -> float:
    """``period_deg`` [deg] -> [rad]: the angle after which the table or series repeats
    (360 by default; 720 for a four-stroke engine's cycle)."""
    deg = sec.number("period_deg", None, lo=1e-3, hi=MAX_PERIOD_DEG)
    return default if deg is None else math.radians(deg)


def _table(sec: Section, value_key: str, lo: float, hi: float, what: str,
           methods: Sequence[str] = ("cubic", "linear", "fourier"),
           default_period: float = 2 * math.pi
           ) -> Tuple[Tuple[float, ...], Tuple[float, ...], str, float]:
    """``phi_deg = [...]`` and ``<value_key> = [...]`` of one period (``period_deg``),
    increasing φ; the interpolation ``method``, the first of *methods* by default.
    Returns ``(phi, values, method, period)``."""
    phi = _deg_array(sec, "phi_deg")
    vals = sec.numbers(value_key, size=len(phi))
    if len(phi) < 3 or any(b <= a for a, b in zip(phi, phi[1:])):
        raise sec.error("phi_deg", "at least 3 increasing angles over one period",
                        repr([round(math.degrees(p), 9) for p in phi]))
    for i, v in enumerate(vals):
        if not lo <= v <= hi:
            raise SpecError(sec.file, sec.key(f"{value_key}[{i}]"),
                            f"{what} in [{lo:g}, {hi:g}]", f"{v:g}")
    method = sec.string("method", methods[0], choices=list(methods))
    period = _period(sec, default_period)
    span = phi[-1] - phi[0]
    if span > period * (1 + 1e-9):
        raise sec.error("phi_deg", f"angles within one period ({math.degrees(period):g}°; "
                        "a longer cycle needs period_deg, e.g. 720 for a four-stroke engine)",
                        f"a span of {math.degrees(span):g}°")
    return phi, tuple(vals), method, period


def _inertia(root: Section, has_linkage: bool, optional: bool = False) -> InertiaSpec:
    """The inertia forms; *optional*: the spec sizes or gives a flywheel, so without an
    [inertia] the machine's own is neglected (Je = 0, eq. 6-30)."""
    sec = root.table("inertia", None)
    if sec is None:
        if has_linkage:
            return InertiaSpec("linkage")
        if optional:
            return InertiaSpec("none")
        raise root.error("inertia", "an [inertia] table or a [mechanism] with [[link]] "
                         "tables (the equivalent inertia comes from one of them), or a "
                         "[flywheel] that carries it", "neither")
    if has_linkage:
        # the linkage's own inertia, dJe by the exact coefficients or differences
        derivative = sec.string("derivative", "exact", choices=["exact", "difference"])
        # difference step [deg]: 1e-6 .. 1 (the benchmark measures its error)
        if derivative != "difference" and sec.has("step_deg"):
            raise sec.error("step_deg", 'no step with derivative = "exact" (the step of '
                            'derivative = "difference")', repr(sec.raw("step_deg")))
        step = math.radians(sec.number("step_deg", 1e-3, lo=1e-6, hi=1.0))
        # the motion interpolates Je, dJe between exact samples (error ~h^4; the
        # benchmark measures it): 360 .. 360,000 per turn
        samples = sec.integer("samples", 3600, lo=360, hi=360000)
        sec.finish()
        return InertiaSpec("linkage", derivative=derivative, step=step, samples=samples)
    if sec.has("phi_deg"):
        phi, vals, method, period = _table(sec, "J", MIN_INERTIA, MAX_INERTIA,
                                           "a positive inertia [kg m²]")
        if abs(phi[-1] - phi[0] - period) > 1e-9 * period:
            raise sec.error("phi_deg", f"a table over exactly one period "
                            f"({math.degrees(period):g}°, period_deg): the last angle one "
                            "period after the first", f"a span of "
                            f"{math.degrees(phi[-1] - phi[0]):g}°")
        sec.finish()
        return InertiaSpec("table", phi=phi, values=vals, method=method, period=period)
    # [[inertia.mass]] tables: the chain's sliding members (a number: J = mass k²)
    if sec.has("member") or isinstance(sec.data.get("mass"), (list, dict)):
        members = []
        for t in sec.tables("member", []):
            members.append((t.number("J", lo=MIN_INERTIA, hi=MAX_INERTIA),
                            t.number("ratio", lo=-1e6, hi=1e6)))
            t.finish()
        masses = []
        for t in sec.tables("mass", []):
            masses.append((t.number("m", positive=True, hi=1e9),
                           t.number("ratio", lo=-1e6, hi=1e6)))   # v / omega1 [m/rad]
            t.finish()
        sec.finish()
        return InertiaSpec("chain", members=tuple(members), masses=tuple(masses))
    J = _mass_k(sec, "J", MIN_INERTIA)
    sec.finish()
    return InertiaSpec("constant", J=J)


def _mass_k(sec: Section, key: str, lo: float, default: Any = REQUIRED,
            k_alone: bool = False) -> Any:
    """``J`` [kg m²], or ``mass`` [kg] with ``k``, the radius of gyration [units]: J = m k²
    (problems give a flywheel or a rotor so).  Not both.  *k_alone*: ``k`` without
    ``mass`` is another key's business (a sized flywheel's radius of gyration)."""
    if sec.has("mass") or (sec.has("k") and not k_alone):
        if sec.has(key):
            raise sec.error("mass" if sec.has("mass") else "k", f"either {key} or mass and "
                            "k (J = m k²), not both", "both")
        if not (sec.has("mass") and sec.has("k")):
            raise sec.error("k" if sec.has("mass") else "mass", "mass and k together "
                            "(J = m k², k the radius of gyration)", "one of them")
        # a mass up to 1e9 kg (a million tonnes: far beyond any rotor)
        m = sec.number("mass", positive=True, hi=1e9)
        k = sec.length("k")
        J = m * k * k
        if not lo <= J <= MAX_INERTIA:
            raise sec.error("mass", f"m k² in [{lo:g}, {MAX_INERTIA:g}] kg m²", f"{J:g}")
        return J
    return sec.number(key, default, lo=lo, hi=MAX_INERTIA)


def _mean_or_number(sec: Section, name: str) -> Union[float, str]:
    """A constant moment [N m], or ``"mean"``: the value that makes the work over a cycle
    vanish (the textbook's "the resisting moment is the mean"), computed by the core."""
    if isinstance(sec.data.get(name), str):
        sec.string(name, choices=["mean"])
        return "mean"
    return sec.number(name, 0.0, lo=-MAX_FORCE, hi=MAX_FORCE)


def _moment(root: Section, has_loads: bool) -> MomentSpec:
    """``[moment]``'s terms (or the linkage's loads alone), in named steps: the constant
    terms and the motor line, the tables, the harmonic series, the segments and the
    chain's torques, then the checks of the whole."""
    sec = root.table("moment", None)
    if sec is None:
        if not has_loads:
            raise root.error("moment", "a [moment] table or [[load]] tables of a linkage "
                             "(the equivalent moment comes from them)", "neither")
        return MomentSpec(loads=True)
    kw: dict[str, Any] = {"loads": has_loads}
    period = _period(sec)
    kw["period"] = period
    _moment_constants(sec, kw)
    for name in ("table", "resisting_table"):
        t = sec.table(name, None)
        if t is not None:
            kw[name] = _moment_table(sec, t, name, period)
    _same_table_angles(sec, kw)
    h = sec.table("harmonic", None)
    if h is not None:
        a0 = h.number("a0", 0.0, lo=-MAX_FORCE, hi=MAX_FORCE)
        a = tuple(h.numbers("a", []))
        b = tuple(h.numbers("b", []))
        if len(a) > 100 or len(b) > 100 or any(abs(x) > MAX_FORCE for x in a + b):
            raise h.error("a", f"at most 100 coefficients within ±{MAX_FORCE:g}",
                          f"{len(a)} and {len(b)}")
        kw["harmonic"] = (a0, a, b, _period(h, period))
        h.finish()
    kw["segments"] = _moment_segments(sec, period)
    torques = []
    for t in sec.tables("torque", []):
        torques.append((t.number("M", lo=-MAX_FORCE, hi=MAX_FORCE),
                        t.number("ratio", lo=-1e6, hi=1e6)))
        t.finish()
    kw["torques"] = tuple(torques)
    _check_moment(sec, kw, has_loads)
    sec.finish()
    return MomentSpec(**kw)


def _moment_constants(sec: Section, kw: dict[str, Any]) -> None:
    """``constant``, ``drive`` (Md = a − bω) and ``resisting`` into *kw*, with ``mean``:
    the one of ``constant``/``resisting`` given as ``"mean"`` (then 0.0 in *kw*)."""
    constant = _mean_or_number(sec, "constant")
    if sec.has("drive"):
        a, b = sec.numbers("drive", size=2)       # Md = a - b omega [N m, N m s]
        if abs(a) > MAX_FORCE or abs(b) > MAX_FORCE:
            raise sec.error("drive", f"[a, b] within ±{MAX_FORCE:g}", repr([a, b]))
        kw["drive"] = (a, b)
    resisting = _mean_or_number(sec, "resisting")
    means = [n for n, v in (("constant", constant), ("resisting", resisting)) if v == "mean"]
    if len(means) > 1:
        raise sec.error("resisting", 'one term = "mean" (the other balances it)',
                        'constant and resisting both "mean"')
    if means and "drive" in kw and kw["drive"][1] != 0:
        raise sec.error(means[0], 'a number with a motor line drive = [a, b] (the mean of a '
                        "moment of ω depends on the motion)", '"mean"')
    kw["mean"] = means[0] if means else None
    kw["constant"] = 0.0 if constant == "mean" else constant
    kw["resisting"] = 0.0 if resisting == "mean" else resisting


def _moment_table(sec: Section, t: Section, name: str, period: float) -> tuple:
    """``[moment.<name>]`` (``table`` or ``resisting_table``): ``(phi [rad], M [N m],
    method, period [rad], integration)``."""
    # linear by default: the work is then exact, and a jump of the moment between
    # two nodes (表 6-2: 727 -> 85 N m) does not overshoot as a spline would
    phi_t, M_t, method, per = _table(t, "M", -MAX_FORCE, MAX_FORCE, "a moment [N m]",
                                     ("linear", "cubic"), period)
    integration = t.string("integration", "exact", choices=list(INTEGRATIONS))
    if integration != "exact" and t.has("method"):
        raise t.error("method", f'no method with integration = "{integration}" '
                      "(the rule fixes the interpolation: trapezoid = linear, "
                      "simpson = a parabola over each pair of intervals)",
                      repr(t.raw("method")))
    if integration == "trapezoid":
        method = "linear"
    elif integration == "simpson":
        method = "quadratic"
        closed = abs(phi_t[-1] - phi_t[0] - per) <= 1e-9 * per
        n = len(phi_t) - 1 if closed else len(phi_t)
        if n % 2:
            raise t.error("integration", "an even number of intervals per period "
                          "for Simpson's rule", f"{n} intervals")
    if abs(phi_t[-1] - phi_t[0] - per) <= 1e-9 * per and M_t[-1] != M_t[0]:
        raise SpecError(sec.file, sec.key(f"{name}.M"), "a last moment equal to the "
                        "first (phi_deg spans a whole period: the table is periodic)",
                        f"{M_t[0]:g} and {M_t[-1]:g}")
    t.finish()
    return (phi_t, M_t, method, per, integration)


def _same_table_angles(sec: Section, kw: dict[str, Any]) -> None:
    """A driving and a resisting table on other angles are summed exactly only when both
    are linear."""
    if "table" in kw and "resisting_table" in kw and kw["table"][1:] != kw[
            "resisting_table"][1:] and ("linear", "linear") != (kw["table"][2],
                                                               kw["resisting_table"][2]) and (
            kw["table"][0] != kw["resisting_table"][0] or kw["table"][2:4]
            != kw["resisting_table"][2:4]):
        raise sec.error("resisting_table", "the same phi_deg and period as [moment.table] "
                        "unless both are linear (linear tables on different angles are "
                        "summed exactly)", "other angles")


def _moment_segments(sec: Section, period: float) -> tuple:
    """``[[moment.segment]]``: ``(phi_from, phi_to, M_from, M_to)`` [rad, N m] each, a
    resisting one negated; no overlaps, all within one period."""
    segs = []
    for s in sec.tables("segment", []):
        phi = _deg_array(s, "phi_deg", size=2)
        M = s.numbers("M", size=2)
        if not phi[1] > phi[0]:
            raise s.error("phi_deg", "[from, to] with from < to", repr(s.raw("phi_deg")))
        if any(abs(x) > MAX_FORCE for x in M):
            raise s.error("M", f"moments within ±{MAX_FORCE:g} N m", repr(M))
        sign = -1.0 if s.boolean("resisting", False) else 1.0
        segs.append((phi[0], phi[1], sign * M[0], sign * M[1]))
        s.finish()
    for a, b in zip(sorted(segs), sorted(segs)[1:]):
        if b[0] < a[1] - 1e-12:
            raise sec.error("segment", "segments that do not overlap",
                            f"[{math.degrees(a[0]):g}, {math.degrees(a[1]):g}]° and "
                            f"[{math.degrees(b[0]):g}, {math.degrees(b[1]):g}]°")
    if segs and max(x[1] for x in segs) - min(x[0] for x in segs) > period * (1 + 1e-9):
        raise sec.error("segment", f"segments within one period ({math.degrees(period):g}°; "
                        "a longer cycle needs [moment] period_deg)", "a longer span")
    return tuple(segs)


def _check_moment(sec: Section, kw: dict[str, Any], has_loads: bool) -> None:
    """What the terms together must be: linear tables beside the loads, a period only with
    a term that varies with φ, a ``"mean"`` only with such a term."""
    segs = kw["segments"]
    for name in ("table", "resisting_table"):
        if has_loads and name in kw and kw[name][2] != "linear":
            raise sec.error(f"{name}.method", "a linear table (the loads of the linkage are "
                            "summed with it as a linear table every 0.1°)", kw[name][2])
    if not (segs or "table" in kw or "resisting_table" in kw or "harmonic" in kw) \
            and sec.has("period_deg"):
        raise sec.error("period_deg", "a period only with a table, a harmonic series or "
                        "segments (the terms that vary with φ)", repr(sec.raw("period_deg")))
    if kw["mean"] and not (segs or "table" in kw or "resisting_table" in kw
                           or "harmonic" in kw or has_loads):
        raise sec.error(kw["mean"], '"mean" with a moment that varies with φ (a table, a '
                        "harmonic series, segments or loads)", '"mean"')


def _speed(sec: Section, name: str, rpm_name: str, default: Any = REQUIRED,
           lo: float = 0.0) -> Tuple[Any, bool]:
    """A speed [rad/s] given as ``name`` [rad/s] or ``rpm_name`` [r/min] (not both).
    Returns ``(value, given in r/min)``."""
    if sec.has(rpm_name):
        if sec.has(name):
            raise sec.error(rpm_name, f"either {name} [rad/s] or {rpm_name} [r/min], not "
                            "both", "both")
        if lo > 0:
            return sec.number(rpm_name, positive=True, hi=MAX_OMEGA / RPM) * RPM, True
        return sec.number(rpm_name, lo=0.0, hi=MAX_OMEGA / RPM) * RPM, True
    sec.declare(rpm_name)
    if lo > 0:
        return sec.number(name, default, positive=True, hi=MAX_OMEGA), False
    return sec.number(name, default, lo=0.0, hi=MAX_OMEGA), False


def _unused(sec: Section, keys: Iterable[str], why: str) -> None:
    """Exit 2 on the first of *keys* the section has: the form does not use it."""
    for k in keys:
        if sec.has(k):
            raise sec.error(k, f"no {k} {why}", repr(sec.raw(k)))


def _motion(root: Section, omega_dependent: bool) -> Tuple[MotionSpec, bool]:
    """[motion]; *omega_dependent*: the moment has a motor line −bω (else Me(φ) only)."""
    sec = root.table("motion", None)
    if sec is None:
        # no motion asked: the equivalent model only, over one cycle (例 6-1)
        out = root.table("output", None)
        points = 361 if out is None else out.integer("points", 361, lo=2, hi=MAX_POINTS)
        return MotionSpec("model", 0.0, 0.0, 2 * math.pi, None, None, "none", 1e-10, 1e-12,
                          None, points, "shooting", 1e-10, 200), False
    out = root.table("output", None)
    if out is not None:
        _unused(out, ["points"], "here with [motion] (its own points key sets the grid)")
    kind = sec.string("kind", "start", choices=["start", "steady"])
    phi0 = math.radians(sec.number("phi0_deg", 0.0, lo=-MAX_ANGLE_DEG, hi=MAX_ANGLE_DEG))
    # the equivalent link turns forward: ω0 = 0 (a start from rest) up to 1e6 rad/s
    omega0, rpm = _speed(sec, "omega0", "n0_rpm")
    phi_end = omega_end = t_end = None
    if kind == "start":
        ends = [k for k in ("phi_end_deg", "omega_end", "n_end_rpm", "t_end") if sec.has(k)]
        if len(ends) != 1:
            raise sec.error(ends[1] if ends else "phi_end_deg",
                            "exactly one end: phi_end_deg, omega_end (n_end_rpm) or t_end",
                            ", ".join(ends) or "none")
        if ends[0] == "phi_end_deg":
            phi_end = math.radians(sec.number("phi_end_deg", lo=-MAX_ANGLE_DEG,
                                              hi=MAX_ANGLE_DEG))
            if not phi_end > phi0:
                raise sec.error("phi_end_deg", f"an angle above phi0_deg = "
                                f"{math.degrees(phi0):g}", f"{math.degrees(phi_end):g}")
        elif ends[0] in ("omega_end", "n_end_rpm"):
            omega_end, _ = _speed(sec, "omega_end", "n_end_rpm")
        else:
            t_end = sec.number("t_end", positive=True, hi=1e9)
        _unused(sec, ["root", "tol", "max_iter"], 'with kind = "start" (the steady state\'s '
                "search)")
    elif omega0 <= 0:
        raise sec.error("n0_rpm" if rpm else "omega0",
                        "a positive speed (the guess of the steady state)", f"{omega0:g}")
    method = sec.string("method", "auto", choices=list(METHODS))
    # what "auto" resolves to, as solve_flywheel resolves it (the keys of the others unused)
    resolved = method
    if kind == "start" and phi_end is None:
        resolved = "closed_form" if method == "auto" else method
    elif not omega_dependent and method == "auto":
        resolved = "energy"
    if kind == "steady" and not omega_dependent:
        if method not in ("auto", "energy"):
            raise sec.error("method", 'auto or "energy": the steady state of a moment of φ '
                            "only is the exact energy integral", f"'{method}'")
        _unused(sec, ["rtol", "atol", "root"], "for a moment of φ only (the steady state is "
                "the exact energy integral at the mean speed omega0)")
    if resolved in ("energy", "closed_form", "book"):
        _unused(sec, ["rtol", "atol"], f'with method "{resolved}" (the tolerances of '
                "DOP853, RK45 and Radau)")
    if method != "book":
        _unused(sec, ["step_deg"], 'without method = "book" (its fixed step)')
    # tolerances of the adaptive methods (relative to omega): 1e-14 is round-off
    rtol = sec.number("rtol", 1e-10, lo=1e-14, hi=1e-2)
    atol = sec.number("atol", 1e-12, lo=1e-300, hi=1.0)
    step = sec.number("step_deg", None, lo=1e-3, hi=90.0)
    if method == "book" and step is None:
        raise sec.error("step_deg", "the fixed step of method = \"book\" [deg] (the book: 15)",
                        "nothing")
    if step is not None and abs(360.0 / step - round(360.0 / step)) > 1e-9 * 360.0 / step:
        raise sec.error("step_deg", "a step that divides 360° into whole steps (the book: 15)",
                        f"{step:g}")
    points = sec.integer("points", 361, lo=2, hi=MAX_POINTS)
    root_method = sec.string("root", "shooting", choices=["shooting", "repeat"])
    # the steady state's periodicity |omega(T) - omega(0)| [rad/s]
    tol = sec.number("tol", 1e-10, lo=1e-14, hi=1.0)
    max_iter = sec.integer("max_iter", 200, lo=1, hi=100000)
    sec.finish()
    return MotionSpec(kind, phi0, omega0, phi_end, omega_end, t_end, method, rtol, atol,
                      None if step is None else math.radians(step), points, root_method, tol,
                      max_iter), rpm


#: the keys of [flywheel] that describe its shape (they need a J_F to size)
SHAPE_KEYS = ("shape", "radius", "thickness", "density", "k")
#: the keys of the energy-swing forms (no [motion])
SWING_KEYS = ("dW", "energy_coefficient", "work_per_cycle", "omega_mean", "n_mean_rpm")


def _flywheel(root: Section, motion: MotionSpec, has_moment: bool) -> FlywheelPart:
    """[flywheel] in the form *motion* allows (see docs/flywheel.md):

    * with [motion]: ``J`` (or ``mass`` and ``k``) added, or ``delta`` sized in the steady
      state; the energy-swing keys are refused (the motion gives ΔW and ωm);
    * without: the energy swing (``dW``, or ``energy_coefficient`` × ``work_per_cycle``, or
      the moment's diagram) at ``omega_mean`` (``n_mean_rpm``) gives δ for a given J, or J_F
      for ``delta``.
    """
    sec = root.table("flywheel", None)
    if sec is None:
        return FlywheelPart()
    J = _mass_k(sec, "J", 0.0, 0.0, k_alone=True)
    given = J > 0 or sec.has("mass")
    if sec.has("delta") and sec.has("Cs"):
        raise sec.error("Cs", "either delta or Cs (the same coefficient of speed "
                        "fluctuation), not both", "both")
    # δ = (ωmax − ωmin)/ωm lies in (0, 2): at 2 the least speed is 0
    dkey = "Cs" if sec.has("Cs") else "delta"
    delta = sec.number(dkey, None, lo=1e-9, hi=2.0)
    if delta is not None and delta >= 2.0:
        raise sec.error(dkey, "a coefficient in (0, 2) (at 2 the least speed is 0)",
                        f"{delta:g}")
    sec.declare("delta")
    if given and delta is not None:
        raise sec.error(dkey, "either J (mass and k: a given flywheel) or delta (size one), "
                        "not both", "both")
    if motion.kind != "model":
        _unused(sec, SWING_KEYS, "with [motion] (the motion gives the energy swing and the "
                "mean speed)")
        if motion.kind == "start":
            _unused(sec, ["delta", "Cs"], 'with kind = "start" (a flywheel is sized in the '
                    'steady state: kind = "steady")')
    dW = omega_mean = None
    rpm = False
    if motion.kind == "model":
        if sec.has("dW") and (sec.has("energy_coefficient") or sec.has("work_per_cycle")):
            raise sec.error("energy_coefficient", "either dW or energy_coefficient with "
                            "work_per_cycle (ΔW = Ce W), not both", "both")
        if sec.has("energy_coefficient") != sec.has("work_per_cycle"):
            raise sec.error("work_per_cycle" if sec.has("energy_coefficient")
                            else "energy_coefficient", "energy_coefficient and work_per_cycle "
                            "together (ΔWmax = Ce × W per cycle)", "one of them")
        if sec.has("energy_coefficient"):
            # the coefficient of fluctuation of energy: ΔWmax/W, at most a few (0.1 .. 1.3)
            ce = sec.number("energy_coefficient", positive=True, hi=100.0)
            dW = ce * sec.number("work_per_cycle", positive=True, hi=1e15)
        else:
            dW = sec.number("dW", None, positive=True, hi=1e15)
        omega_mean, rpm = _speed(sec, "omega_mean", "n_mean_rpm", None, lo=1.0)
        if dW is not None and omega_mean is None:
            raise sec.error("omega_mean", "the mean speed with the energy swing (eq. 6-28): "
                            "omega_mean [rad/s] or n_mean_rpm", "nothing")
        if omega_mean is not None and dW is None and not has_moment:
            raise sec.error("dW", "the energy swing with the mean speed: dW [J], or "
                            "energy_coefficient and work_per_cycle, or a [moment] diagram",
                            "nothing")
        if delta is not None and omega_mean is None:
            raise sec.error(dkey, "delta with the mean speed and the energy swing (eq. "
                            "6-29: J_F = ΔWmax/(ωm² δ) − Je): omega_mean or n_mean_rpm",
                            "no mean speed")
    sized = delta is not None
    if not (sized or J > 0):
        _unused(sec, SHAPE_KEYS, "without a flywheel to shape (J, or delta to size one)")
    if sec.has("mass"):
        _unused(sec, SHAPE_KEYS[:-1], "with mass and k (the flywheel's mass is given)")
    shape = sec.string("shape", None, choices=["rim", "disc"])
    radius = sec.length("radius", None)
    density = sec.number("density", None, positive=True, hi=1e6)
    k = None if sec.has("mass") else sec.length("k", None)
    if k is not None and shape is not None:
        raise sec.error("k", "either k (the radius of gyration: m = J/k²) or shape with "
                        "radius, not both", "both")
    if density is not None and shape is None:
        raise sec.error("density", "a density with shape = \"rim\" or \"disc\" (it gives the "
                        "width)", f"{density:g} without a shape")
    # a rim's radial thickness (its width then follows from the mass and the density)
    thickness = sec.length("thickness", None)
    if thickness is not None and (shape != "rim" or radius is None
                                  or not thickness < 2 * radius):
        raise sec.error("thickness", "a rim's radial thickness, below twice its radius "
                        "(shape = \"rim\")", f"{thickness:g} m")
    if shape is not None and radius is None:
        raise sec.error("radius", f"the {shape}'s radius (with shape)", "nothing")
    if radius is not None and shape is None:
        raise sec.error("shape", "shape = \"rim\" or \"disc\" with radius", "nothing")
    if shape == "disc" and thickness is not None:
        raise sec.error("thickness", "no thickness for a disc (a rim's)", f"{thickness:g}")
    sec.finish()
    return FlywheelPart(J, delta, shape, radius, density, thickness, dW, omega_mean, k, rpm)


def _check_periods(root: Section, inertia: InertiaSpec, moment: Optional[MomentSpec],
                   has_linkage: bool) -> None:
    """The periods of the inertia and the moment's terms must divide the longest one (the
    cycle): 360° and 720° make a 720° cycle; 360° and 500° make none."""
    periods = []            # (period [rad], the key that set it)
    if has_linkage:
        periods.append((2 * math.pi, "mechanism"))
    if inertia.kind == "table":
        periods.append((inertia.period, "inertia.period_deg"))
    if moment is not None:
        for name in ("table", "resisting_table"):
            t = getattr(moment, name)
            if t is not None:
                periods.append((t[3], f"moment.{name}.period_deg"))
        if moment.harmonic is not None:
            periods.append((moment.harmonic[3], "moment.harmonic.period_deg"))
        if moment.segments:
            periods.append((moment.period, "moment.period_deg"))
    if not periods:
        return
    T = max(p for p, _ in periods)
    for p, key in periods:
        r = T / p
        if abs(r - round(r)) > 1e-9 * r:
            raise SpecError(root.file, key, f"a period that divides the longest one "
                            f"({math.degrees(T):g}°: the cycle)", f"{math.degrees(p):g}°")


def read_flywheel_spec(path: Union[str, Path], overrides: Iterable[str] = ()) -> FlywheelSpec:
    """Read and validate a ``mechcli flywheel`` spec (SpecError on the first bad key)."""
    root = load_spec(path, overrides)
    header = read_header(root, "flywheel", default_unit="m")
    linkage = topo = None
    loads: tuple = ()
    bodies, followers, gravity = {}, {}, (0.0, 0.0)
    if root.has("mechanism"):
        from mechcli.core.linkage.kinematics import default_quantities
        from mechcli.core.linkage.kinetostatics import ForceModelError, topology
        from mechcli.spec.kin import read_mechanism, refuse_approximate
        refuse_approximate(root, "flywheel")
        _kind, linkage, _tracers, followers, _guide = read_mechanism(root)
        first = linkage.drivers[0]
        if not first.rotary or first.link != 1 or len(linkage.drivers) > 1:
            raise root.error("mechanism", "a linkage driven by one crank, link 1 (the "
                             "equivalent link)", f"driver of link {first.link}")
        if getattr(first, "actuator", None) is not None:
            raise root.error("mechanism", "a linkage driven by a torque on its crank (an "
                             "`actuator` drives through a slide: not a flywheel problem)",
                             f"actuator {first.actuator!r}")
        try:
            topo = topology(linkage)
        except ForceModelError as exc:
            raise SpecError(root.file, "mechanism", "a linkage whose pairs can carry forces",
                            str(exc)) from None
        bodies = read_bodies(root, topo, linkage.frame)
        if not bodies:
            raise root.error("link", "[[link]] tables with the masses and inertias of the "
                             "moving links", "none")
        gravity = read_gravity(root)
        quantities = default_quantities(linkage, 2, list(linkage.point_names))
        loads = tuple(read_loads(root, topo, linkage.frame, True, quantities))
    fly_sec = root.table("flywheel", None)
    carries = fly_sec is not None and any(fly_sec.has(k) for k in (
        "J", "mass", "delta", "Cs"))
    inertia = _inertia(root, linkage is not None, optional=carries)
    mom = root.table("moment", None)
    drive = None if mom is None else mom.data.get("drive")
    omega_dependent = isinstance(drive, list) and len(drive) == 2 and drive[1] != 0
    motion, rpm = _motion(root, omega_dependent)
    has_loads = bool(loads) or (linkage is not None and any(gravity))
    moment = _moment(root, has_loads) if motion.kind != "model" or root.has("moment") \
        or has_loads else None
    fly = _flywheel(root, motion, moment is not None)
    if rpm:         # [motion] n0_rpm: the speeds are reported in r/min too
        fly = dataclasses.replace(fly, rpm=True)
    if inertia.kind == "none" and motion.kind == "model" and not fly.J and (
            fly.delta is None) and fly.dW is None:
        raise root.error("inertia", "an [inertia] (the model has no inertia without it)",
                         "nothing")
    if inertia.kind == "none" and fly.J == 0 and fly.delta is None:
        raise root.error("inertia", "an [inertia], or a [flywheel] J or delta (the machine "
                         "needs an inertia to move)", "nothing")
    _check_periods(root, inertia, moment, linkage is not None)
    out = root.table("output", None)
    plots = True
    if out is not None:
        plots = out.boolean("plots", True)
        if motion.kind == "model":
            out.integer("points", 361, lo=2, hi=MAX_POINTS)     # read by _motion
        out.finish()
    expected = read_expected(root, overrides)
    root.finish()
    return FlywheelSpec(header, linkage, topo, bodies, gravity, loads, followers, inertia,
                        moment, motion, fly, plots, expected,
                        Path(path) if path is not None else None)
