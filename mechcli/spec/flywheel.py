"""``mechcli flywheel`` problem files -> :class:`FlywheelSpec` (SI units, radians).

The equivalent model on the crank (the equivalent link, 等效构件): its inertia from
a linkage (``[mechanism]`` and ``[[link]]`` tables, read as ``force`` reads them), a
chain of constant ratios, a table against φ or a constant (``[inertia]``); its
moment from the linkage's ``[[load]]`` tables and/or ``[moment]`` terms (a table
against φ, a motor line a − bω, a constant resisting moment, a harmonic series,
piecewise-linear segments).  ``[motion]`` says what to solve: a run from a start
(``kind = "start"``) or the periodic steady state (``kind = "steady"``);
``[flywheel]`` adds a flywheel or sizes one for an allowed δ.  See docs/flywheel.md.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional, Tuple

from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.force import MAX_FORCE, MAX_INERTIA, read_bodies, read_gravity, read_loads
from mechcli.spec.reader import load_spec

#: the largest |ω| [rad/s] and angle [deg] a spec may give (a 1e6 rad/s shaft is
#: already beyond any machine; angles within a hundred turns)
MAX_OMEGA = 1e6
MAX_ANGLE_DEG = 36000.0
#: the smallest inertia [kg m^2] (a watch wheel is ~1e-10; below, ω² overflows with any moment)
MIN_INERTIA = 1e-12
#: output grid: points over the solved interval (the CSV rows and the plots)
MAX_POINTS = 100_001
METHODS = ("auto", "DOP853", "RK45", "Radau", "book", "energy", "closed_form")


@record
class InertiaSpec:
    kind: str                    # "linkage", "constant", "table", "chain"
    J: float = 0.0               # constant [kg m^2]
    phi: tuple = ()              # table [rad]
    values: tuple = ()           # table [kg m^2]
    method: str = "cubic"        # table interpolation
    members: tuple = ()          # chain: (J, ratio)
    masses: tuple = ()           # chain: (m, v/omega1 [m/rad])
    derivative: str = "exact"    # linkage: dJe/dphi exact or by central differences
    step: float = 1e-5           # linkage: difference step [rad]
    samples: int = 3600          # linkage: angles per turn of the Hermite table the motion uses


@record
class MomentSpec:
    constant: float = 0.0                  # [N m]
    drive: Optional[Tuple[float, float]] = None    # Md = a - b omega
    resisting: float = 0.0                 # constant Mr, subtracted
    table: Optional[tuple] = None          # (phi [rad], M [N m], method), added
    resisting_table: Optional[tuple] = None    # (phi, Mr, method), subtracted
    harmonic: Optional[tuple] = None       # (a0, (a_k), (b_k))
    segments: tuple = ()                   # (phi_from, phi_to, M_from, M_to) [rad, N m]
    torques: tuple = ()                    # chain: (M, ratio)
    loads: bool = False                    # the linkage's [[load]] tables and gravity


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
    J: float = 0.0               # a flywheel added [kg m^2]
    delta: Optional[float] = None    # allowed speed fluctuation [δ]: size J_F
    shape: Optional[str] = None  # "rim" | "disc"
    radius: Optional[float] = None     # a rim's mean radius, a disc's radius [m]
    density: Optional[float] = None    # [kg/m^3]: the width of a disc, or of a rim
    thickness: Optional[float] = None  # a rim's radial thickness [m]
    dW: Optional[float] = None         # a given largest energy swing ΔWmax [J] (eq. 6-28)
    omega_mean: Optional[float] = None   # ... and the mean speed [rad/s]


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
    moment: MomentSpec
    motion: MotionSpec
    flywheel: FlywheelPart
    plots: bool
    expected: dict
    path: Optional[Path]


def _deg_array(sec, name, size=None):
    vals = sec.numbers(name, size=size) if size else sec.numbers(name)
    for i, v in enumerate(vals):
        if abs(v) > MAX_ANGLE_DEG:
            raise SpecError(sec.file, sec.key(f"{name}[{i}]"),
                            f"an angle within ±{MAX_ANGLE_DEG:g}°", f"{v:g}")
    return tuple(math.radians(v) for v in vals)


def _table(sec, value_key, lo, hi, what, methods=("cubic", "linear", "fourier")):
    """``phi_deg = [...]`` and ``<value_key> = [...]`` of one period, increasing φ; the
    interpolation ``method``, the first of *methods* by default."""
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
    return phi, tuple(vals), method


def _inertia(root, has_linkage):
    sec = root.table("inertia", None)
    if sec is None:
        if not has_linkage:
            raise root.error("inertia", "an [inertia] table or a [mechanism] with [[link]] "
                             "tables (the equivalent inertia comes from one of them)",
                             "neither")
        return InertiaSpec("linkage")
    if has_linkage:
        # the linkage's own inertia, dJe by the exact coefficients or differences
        derivative = sec.string("derivative", "exact", choices=["exact", "difference"])
        # difference step [deg]: 1e-6 .. 1 (the benchmark measures its error)
        step = math.radians(sec.number("step_deg", 1e-3, lo=1e-6, hi=1.0))
        # the motion interpolates Je, dJe between exact samples (error ~h^4; the
        # benchmark measures it): 360 .. 360,000 per turn
        samples = sec.integer("samples", 3600, lo=360, hi=360000)
        sec.finish()
        return InertiaSpec("linkage", derivative=derivative, step=step, samples=samples)
    if sec.has("phi_deg"):
        phi, vals, method = _table(sec, "J", MIN_INERTIA, MAX_INERTIA,
                                   "a positive inertia [kg m²]")
        sec.finish()
        return InertiaSpec("table", phi=phi, values=vals, method=method)
    if sec.has("member") or sec.has("mass"):
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
    J = sec.number("J", lo=MIN_INERTIA, hi=MAX_INERTIA)
    sec.finish()
    return InertiaSpec("constant", J=J)


def _moment(root, has_loads):
    sec = root.table("moment", None)
    if sec is None:
        if not has_loads:
            raise root.error("moment", "a [moment] table or [[load]] tables of a linkage "
                             "(the equivalent moment comes from them)", "neither")
        return MomentSpec(loads=True)
    kw = {"loads": has_loads}
    kw["constant"] = sec.number("constant", 0.0, lo=-MAX_FORCE, hi=MAX_FORCE)
    if sec.has("drive"):
        a, b = sec.numbers("drive", size=2)       # Md = a - b omega [N m, N m s]
        if abs(a) > MAX_FORCE or abs(b) > MAX_FORCE:
            raise sec.error("drive", f"[a, b] within ±{MAX_FORCE:g}", repr([a, b]))
        kw["drive"] = (a, b)
    kw["resisting"] = sec.number("resisting", 0.0, lo=-MAX_FORCE, hi=MAX_FORCE)
    for name in ("table", "resisting_table"):
        t = sec.table(name, None)
        if t is not None:
            # linear by default: the work is then exact, and a jump of the moment between
            # two nodes (表 6-2: 727 -> 85 N m) does not overshoot as a spline would
            kw[name] = _table(t, "M", -MAX_FORCE, MAX_FORCE, "a moment [N m]",
                              ("linear", "cubic"))
            t.finish()
    for name in ("table", "resisting_table"):
        if name in kw:
            phi_t, M_t, _m = kw[name]
            if abs(phi_t[-1] - phi_t[0] - 2 * math.pi) <= 1e-9 and M_t[-1] != M_t[0]:
                raise SpecError(sec.file, sec.key(f"{name}.M"), "a last moment equal to the "
                                "first (phi_deg spans a whole turn: the table is periodic)",
                                f"{M_t[0]:g} and {M_t[-1]:g}")
            if phi_t[-1] - phi_t[0] > 2 * math.pi + 1e-9:
                raise SpecError(sec.file, sec.key(f"{name}.phi_deg"),
                                "angles within one turn", f"a span of "
                                f"{math.degrees(phi_t[-1] - phi_t[0]):g}°")
    if "table" in kw and "resisting_table" in kw and kw["table"][0] != kw[
            "resisting_table"][0] and "cubic" in (kw["table"][2], kw["resisting_table"][2]):
        raise sec.error("resisting_table", "the same phi_deg as [moment.table] when either "
                        "is cubic (linear tables on different angles are summed exactly)",
                        "other angles")
    h = sec.table("harmonic", None)
    if h is not None:
        a0 = h.number("a0", 0.0, lo=-MAX_FORCE, hi=MAX_FORCE)
        a = tuple(h.numbers("a", []))
        b = tuple(h.numbers("b", []))
        if len(a) > 100 or len(b) > 100 or any(abs(x) > MAX_FORCE for x in a + b):
            raise h.error("a", f"at most 100 coefficients within ±{MAX_FORCE:g}",
                          f"{len(a)} and {len(b)}")
        kw["harmonic"] = (a0, a, b)
        h.finish()
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
    kw["segments"] = tuple(segs)
    torques = []
    for t in sec.tables("torque", []):
        torques.append((t.number("M", lo=-MAX_FORCE, hi=MAX_FORCE),
                        t.number("ratio", lo=-1e6, hi=1e6)))
        t.finish()
    kw["torques"] = tuple(torques)
    sec.finish()
    return MomentSpec(**kw)


def _motion(root):
    sec = root.table("motion", None)
    if sec is None:
        # no motion asked: the equivalent model only, over one turn (例 6-1)
        out = root.table("output", None)
        points = 361 if out is None else out.integer("points", 361, lo=2, hi=MAX_POINTS)
        return MotionSpec("model", 0.0, 0.0, 2 * math.pi, None, None, "none", 1e-10, 1e-12,
                          None, points, "shooting", 1e-10, 200)
    kind = sec.string("kind", "start", choices=["start", "steady"])
    phi0 = math.radians(sec.number("phi0_deg", 0.0, lo=-MAX_ANGLE_DEG, hi=MAX_ANGLE_DEG))
    # the equivalent link turns forward: ω0 = 0 (a start from rest) up to 1e6 rad/s
    omega0 = sec.number("omega0", lo=0.0, hi=MAX_OMEGA)
    phi_end = omega_end = t_end = None
    if kind == "start":
        ends = [k for k in ("phi_end_deg", "omega_end", "t_end") if sec.has(k)]
        if len(ends) != 1:
            raise sec.error(ends[1] if ends else "phi_end_deg",
                            "exactly one end: phi_end_deg, omega_end or t_end",
                            ", ".join(ends) or "none")
        if ends[0] == "phi_end_deg":
            phi_end = math.radians(sec.number("phi_end_deg", lo=-MAX_ANGLE_DEG,
                                              hi=MAX_ANGLE_DEG))
            if not phi_end > phi0:
                raise sec.error("phi_end_deg", f"an angle above phi0_deg = "
                                f"{math.degrees(phi0):g}", f"{math.degrees(phi_end):g}")
        elif ends[0] == "omega_end":
            omega_end = sec.number("omega_end", lo=0.0, hi=MAX_OMEGA)
        else:
            t_end = sec.number("t_end", positive=True, hi=1e9)
    elif omega0 <= 0:
        raise sec.error("omega0", "a positive speed (the guess of the steady state)",
                        f"{omega0:g}")
    method = sec.string("method", "auto", choices=list(METHODS))
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
                      max_iter)


def _flywheel(root):
    sec = root.table("flywheel", None)
    if sec is None:
        return FlywheelPart()
    J = sec.number("J", 0.0, nonneg=True, hi=MAX_INERTIA)
    delta = sec.number("delta", None, lo=1e-9, hi=2.0)
    shape = sec.string("shape", None, choices=["rim", "disc"])
    radius = sec.length("radius", None)
    density = sec.number("density", None, positive=True, hi=1e6)
    # a rim's radial thickness (its width then follows from the mass and the density)
    thickness = sec.length("thickness", None)
    if thickness is not None and (shape != "rim" or radius is None
                                  or not thickness < 2 * radius):
        raise sec.error("thickness", "a rim's radial thickness, below twice its radius "
                        "(shape = \"rim\")", f"{thickness:g} m")
    if shape is not None and radius is None:
        raise sec.error("radius", f"the {shape}'s radius (with shape)", "nothing")
    # eq. 6-28 from numbers: the speeds a given energy swing leaves (J_e + J)
    dW = sec.number("dW", None, positive=True, hi=1e15)
    omega_mean = sec.number("omega_mean", None, positive=True, hi=MAX_OMEGA)
    if (dW is None) != (omega_mean is None):
        raise sec.error("omega_mean" if dW is not None else "dW",
                        "dW and omega_mean together (eq. 6-28)", "one of them")
    if J > 0 and delta is not None:
        raise sec.error("delta", "either J (a given flywheel) or delta (size one), not both",
                        "both")
    sec.finish()
    return FlywheelPart(J, delta, shape, radius, density, thickness, dW, omega_mean)


def read_flywheel_spec(path, overrides=()) -> FlywheelSpec:
    """Read and validate a ``mechcli flywheel`` spec (SpecError on the first bad key)."""
    root = load_spec(path, overrides)
    header = read_header(root, "flywheel", default_unit="m")
    linkage = topo = None
    bodies, loads, followers, gravity = {}, (), {}, (0.0, 0.0)
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
    inertia = _inertia(root, linkage is not None)
    motion = _motion(root)
    has_loads = bool(loads) or (linkage is not None and any(gravity))
    moment = _moment(root, has_loads) if motion.kind != "model" or root.has("moment") \
        or has_loads else None
    fly = _flywheel(root)
    out = root.table("output", None)
    plots = True
    if out is not None:
        plots = out.boolean("plots", True)
        out.integer("points", 361, lo=2, hi=MAX_POINTS)     # read by _motion (no [motion])
        out.finish()
    expected = read_expected(root, overrides)
    root.finish()
    return FlywheelSpec(header, linkage, topo, bodies, gravity, loads, followers, inertia,
                        moment, motion, fly, plots, expected,
                        Path(path) if path is not None else None)
