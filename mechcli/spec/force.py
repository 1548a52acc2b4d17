"""``mechcli force`` problem files -> :class:`ForceSpec` (SI units, radians).

The mechanism and the input program are read exactly as for ``mechcli kin``
(:func:`mechcli.spec.kin.read_mechanism`, :func:`~mechcli.spec.kin.read_input`);
this module adds the inertia of the links, gravity and the external loads::

    [gravity]
    g = 9.8                    # m/s^2, along -y (0 or no table: none)

    [[link]]
    number = 3
    mass = 20                  # kg (> 0)
    J = 0.12                   # kg m^2 about the centre of mass (default 0)
    com = "mid"                # "mid" (default), a point name, or [along, normal]
    com_from = "C"             # origin of [along, normal] (default: the link's first point)

    [[load]]
    name = "cutting"
    link = 5
    force = [5880, 0]          # N; or magnitude = …, angle = … (deg), relative = true|false
    torque = -100              # N m (instead of, or with, a force)
    at = "E"                   # point name or [along, normal]; default the centre of mass
    at_from = "E"
    factor = { at = [0, 180, 360], value = [1, 0.5, 1] }  # tabulated against the input
    when = { window = [90, 210], velocity = "vE", sign = "negative",
             band = [0.05, 0.95], slide = "E" }

    [[load]]                   # a gas pressure on a piston (docs/force.md, "Engine loads")
    name = "gas"
    link = 3                   # a block on a frame guide, its rod on the driving crank
    bore = 100                 # or area = … (spec length unit squared)
    pressure_unit = "bar"      # Pa, kPa, kN/m2, MPa, N/mm2, bar, psi
    pressure = 12              # or {angle|fraction|x = […], value = […]}
                               # or {fraction|x = […], strokes = [[…], […](, […], […])]}
    crank_side_pressure = 1    # optional, same forms; rod = … reduces its area

    [output]
    at = [60]                  # values at these inputs, by name (T_at_60deg_N_m …)

    [approximate]              # only with [mechanism] model = "approximate"
    moment_arm = "series"      # T = FP r (sin θ + sin 2θ / 2n), FT = T / r (default "exact")
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.linkage.force_plan import actuated_pair
from mechcli.core.linkage.kinetostatics import Body, ForceModelError, LoadProgram, topology
from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError, closest
from mechcli.spec.kin import InputSpec, _empty, read_input, read_mechanism
from mechcli.spec.reader import MAX_LENGTH, Section, load_spec

if TYPE_CHECKING:
    import os

    from mechcli.core.linkage.force_model import Topology
    from mechcli.core.linkage.kinetostatics import Load
    from mechcli.core.linkage.piston import GasLoad, Piston, PressureCurve
    from mechcli.core.linkage.sweep import Quantity

#: bounds on the inertia and load data: large enough for any machine, small
#: enough that no product or square in the solve and the RMS overflows to inf
MAX_MASS = 1e9        # kg
MAX_INERTIA = 1e12    # kg m^2
MAX_FORCE = 1e12      # N (and N m for torques)
MAX_G = 1e6           # m/s^2
MAX_FACTOR = 1e6

#: memory budget of one ``mechcli force`` run (any accepted spec), bytes
MEMORY_BUDGET = 2**30  # 1 GiB
#: the most positions of a sweep: the budget over the peak RSS a run grows by per
#: position (taken as ~9.1 kB, POSITIONS_WHY; ``force_peak_rss_per_position`` of
#: benchmarks/bench_force.py measures it), rounded down for deeper linkages, more loads
#: and plots
MAX_POSITIONS = 100_001
POSITIONS_WHY = "1 GiB budget at ~9.1 kB per position"


def _bounded(sec: Section, key: str, values: Sequence[float], lim: float,
             what: str) -> Sequence[float]:
    for v in values:
        if abs(v) > lim:
            raise sec.error(key, f"{what} within ±{lim:g}", repr(list(values)) if
                            len(values) > 1 else f"{v:g}")
    return values


@record
class ForceOutput:
    table_step: float  # input units
    plots: bool
    animate: bool
    frames: int
    draw_at: float
    digits: int
    #: warn where fewer correct significant digits than this remain (estimated)
    accuracy_warn: float = 8.0
    #: inputs [rad or m] whose values are reported by name (``<sym>_at_<v><unit>``)
    at: tuple = ()


@record
class ForceSpec:
    header: Header
    mechanism: str
    linkage: object
    topology: object
    tracers: tuple
    input: InputSpec
    bodies: dict
    gravity: Tuple[float, float]
    loads: Tuple[LoadProgram, ...]
    output: ForceOutput
    expected: dict
    guide_length: Optional[float] = None
    #: ``[mechanism] model``: "exact" or "approximate" (the piston's inertia force
    #: from the series in 1/n, docs/approximate.md)
    model: str = "exact"
    #: the engine's piston (core.linkage.piston.Piston) when a pressure load or the
    #: approximate model names one; its named results are reported (with the
    #: approximate model its ``moment_arm`` is ``[approximate] moment_arm``)
    piston: object = None


def _link_number(sec: Section, key: str, topo: Topology, frame: int) -> int:
    n = sec.integer(key, lo=1)
    if n == frame:
        raise sec.error(key, "a moving link (the frame carries no inertia or loads)",
                        f"{n} (the frame)")
    if n not in topo.links:
        raise sec.error(key, "a moving link: one of " + ", ".join(map(str, topo.links)),
                        str(n))
    return n


def _place(sec: Section, key: str, from_key: str, topo: Topology, link: int,
           allow_mid: bool) -> Optional[Tuple[str, Any, Any]]:
    """A point fixed on ``link``: ``(origin, along, normal)``; along None = midpoint
    (then normal None too; else both floats [m])."""
    raw = sec.raw(key, "mid" if allow_mid else None)
    origin = sec.name(from_key, None)
    if origin is not None and link not in topo.members.get(origin, ()):
        on = sorted(p for p, ls in topo.members.items() if link in ls)
        raise sec.error(from_key, f"a point on link {link} ({', '.join(on)})", f"'{origin}'")
    if raw is None:
        return None
    if isinstance(raw, str):
        if raw != "mid" or not allow_mid:
            sec.check_name(key, raw)
        if raw == "mid" and allow_mid:
            if origin is not None:
                raise sec.error(from_key, f"no {from_key} with {key} = \"mid\"", f"'{origin}'")
            return topo.frames[link][0], None, None
        if link not in topo.members.get(raw, ()):
            on = sorted(p for p, ls in topo.members.items() if link in ls)
            hint = closest(raw, on)
            raise SpecError(sec.file, sec.key(key),
                            f"a point on link {link} ({', '.join(on)})"
                            + (', "mid"' if allow_mid else "") + " or [along, normal]",
                            f"'{raw}'", hint)
        return raw, 0.0, 0.0
    xy = sec.numbers(key, size=2)
    _bounded(sec, key, xy, MAX_LENGTH / sec.unit, "offsets")
    return origin or topo.frames[link][0], xy[0] * sec.unit, xy[1] * sec.unit


def read_gravity(root: Section) -> Tuple[float, float]:
    """``[gravity] g, angle`` -> (gx, gy) [m/s^2]; (0, 0) without the table."""
    if not root.has("gravity"):
        return (0.0, 0.0)
    g = root.table("gravity")
    gval = g.number("g", 9.81, nonneg=True, hi=MAX_G)
    ang = math.radians(g.number("angle", -90.0))
    g.finish()
    grav = (gval * math.cos(ang), gval * math.sin(ang))
    if abs(grav[0]) < 1e-15 * max(gval, 1.0):
        grav = (0.0, grav[1])
    return grav


def read_bodies(root: Section, topo: Topology, frame: int) -> Dict[int, Body]:
    """``[[link]]`` tables -> ``{link: Body}`` (mass, J about the centre of mass, com)."""
    bodies = {}
    for t in root.tables("link", []):
        n = _link_number(t, "number", topo, frame)
        if n in bodies:
            raise t.error("number", "each link once", f"link {n} again")
        mass = t.number("mass", expected="a positive mass [kg]")
        if not 0 < mass <= MAX_MASS:
            raise t.error("mass", f"a positive mass [kg] up to {MAX_MASS:g}", f"{mass:g}")
        J = t.number("J", 0.0, nonneg=True, hi=MAX_INERTIA)
        place = _place(t, "com", "com_from", topo, n, allow_mid=True)
        assert place is not None   # (allow_mid: "mid" by default, never None)
        origin, along, normal = place
        if along is None:  # the default midpoint
            bodies[n] = Body(n, mass, J)
        else:
            bodies[n] = Body(n, mass, J, origin, along, normal)
        t.finish()
    return bodies


def read_loads(root: Section, topo: Topology, frame: int, rotary: bool,
               quantities: Iterable[Quantity], span: Optional[Tuple[float, float]] = None,
               pressure: bool = False, direction: int = 1) -> Tuple[LoadProgram, ...]:
    """``[[load]]`` tables -> LoadProgram tuple (windows in degrees of a rotary input).

    With ``pressure`` a load may be a gas pressure on a piston (``mechcli force``;
    other commands leave those keys unknown); ``span`` (start, stop) [rad] of the
    analysed input: a pressure table against the input angle must span it (or one
    whole cycle, 360° or 720°); ``direction`` the sense of rotation of the crank (−1:
    ω1 < 0), in which the strokes of an indicator diagram follow each other."""
    by_symbol = {q.symbol: q for q in quantities}
    velocities = sorted(s for s, q in by_symbol.items() if q.order == 1 and q.kind in
                        ("angvel", "velocity"))
    slides = sorted(s[1:] for s, q in by_symbol.items() if q.kind == "length"
                    and q.symbol.startswith("s"))
    unit = math.pi / 180 if rotary else root.unit
    out, names = [], set()
    piston_link = None
    for i, t in enumerate(root.tables("load", [])):
        name = t.name("name", f"load{i + 1}")
        if name in names:
            raise t.error("name", "a name not used by another load", f"'{name}'")
        names.add(name)
        link = _link_number(t, "link", topo, frame)
        gas = None
        if pressure and t.has("pressure"):
            gas, load = _gas_load(t, name, link, topo, rotary, span, direction)
            if piston_link is not None and link != piston_link:
                raise t.error("link", f"the piston of the other pressure loads (link "
                              f"{piston_link}): one piston per spec", str(link))
            piston_link = link
        else:
            for key in PRESSURE_KEYS[1:] if pressure else ():
                if t.has(key):
                    raise t.error(key, "a pressure load (pressure = …) to go with it",
                                  "no pressure")
            load = _force_load(t, name, link, topo)
        table = None
        if t.has("factor"):
            ft = t.table("factor")
            xs = ft.numbers("at")
            ys = _bounded(ft, "value", ft.numbers("value"), MAX_FACTOR, "factors")
            if len(xs) != len(ys) or len(xs) < 2:
                raise ft.error("value", "as many values as 'at' points (at least 2)",
                               f"{len(ys)} values for {len(xs)} points")
            if any(b <= a for a, b in zip(xs, xs[1:])):
                raise ft.error("at", "increasing input positions", repr(xs))
            if rotary and xs[-1] - xs[0] > 360.0:
                raise ft.error("at", "input angles spanning at most 360° (the table is "
                               "periodic)", repr(xs))
            ft.finish()
            table = (np.asarray(xs) * unit, np.asarray(ys, dtype=float))
        window = velocity = band = slide = None
        sign = 0
        if t.has("when"):
            w = t.table("when")
            if w.has("window"):
                lo, hi = w.numbers("window", size=2)
                if (lo >= hi) if not rotary else (lo == hi):
                    raise w.error("window", "[lo, hi] with lo < hi" if not rotary else
                                  "[lo, hi] with lo != hi (lo > hi wraps through 360°)",
                                  repr([lo, hi]))
                window = (lo * unit, hi * unit)
            if w.has("velocity"):
                sym = w.name("velocity")
                if sym not in by_symbol or by_symbol[sym].order != 1:
                    raise SpecError(w.file, w.key("velocity"),
                                    "a velocity of this linkage: " + ", ".join(velocities),
                                    f"'{sym}'", closest(sym, velocities))
                velocity = by_symbol[sym]
                sign = {"positive": 1, "negative": -1}[
                    w.string("sign", choices=["positive", "negative"])]
            elif w.has("sign"):
                raise w.error("sign", "a velocity to take the sign of (when.velocity)",
                              "a sign alone")
            if w.has("band"):
                lo, hi = w.numbers("band", size=2)
                if not 0.0 <= lo < hi <= 1.0:
                    raise w.error("band", "[lo, hi] with 0 <= lo < hi <= 1 (fractions of "
                                  "the stroke)", repr([lo, hi]))
                default_slide = None
                if velocity is not None and velocity.kind == "velocity" \
                        and ("s" + velocity.symbol[1:]) in by_symbol:
                    default_slide = velocity.symbol[1:]
                sname = w.name("slide", default_slide)
                if sname is None or "s" + sname not in by_symbol:
                    raise SpecError(w.file, w.key("slide"),
                                    ("a slide of this linkage: " + ", ".join(slides)) if slides
                                    else "a band only on a linkage with a slide (an RRP or "
                                    "RPR dyad); limit the input with when.window instead",
                                    repr(sname), closest(str(sname), slides))
                slide = by_symbol["s" + sname]
                band = (lo, hi)
            elif w.has("slide"):
                raise w.error("slide", "a band to go with the slide (when.band)", "a slide alone")
            w.finish()
        t.finish()
        out.append(LoadProgram(load, window, rotary, velocity, sign, slide, band, table,
                               source=gas))
    return tuple(out)


#: the keys of a pressure (gas) load on a piston; the first makes a load one
PRESSURE_KEYS = ("pressure", "crank_side_pressure", "pressure_unit", "bore", "area", "rod")
#: pressure units [Pa]: N/mm² = MPa and kN/m² = kPa as the engine books write them
PRESSURE_UNITS = {"Pa": 1.0, "kPa": 1e3, "kN/m2": 1e3, "MPa": 1e6, "N/mm2": 1e6, "bar": 1e5,
                  # lbf/in²: 4.4482216152605 N (lbf, exact by definition) / 0.0254² m²
                  "psi": 4.4482216152605 / 0.0254 ** 2}
#: bound of a pressure in its unit (1e11: 100 GPa in Pa, far above any engine or press;
#: in MPa or psi still finite through p·A and the solve)
MAX_PRESSURE = 1e11
#: the force keys a pressure load cannot have (it acts along the line of stroke at the pin)
_FORCE_KEYS = ("force", "magnitude", "angle", "torque", "at", "at_from", "relative")


_PRESSURE_FORMS = ("a pressure (a number) or a table {angle|fraction|x = [...], value = "
                   "[...]} or {fraction|x = [...], strokes = [[...], [...]]}")


def _pressure_curve(t: Section, key: str, scale: float, rotary: bool,
                    span: Optional[Tuple[float, float]], piston: Piston,
                    direction: int = 1) -> PressureCurve:
    """``pressure`` (a number or a table) -> :class:`PressureCurve` [Pa]."""
    from mechcli.core.linkage.piston import PressureCurve

    raw = t.raw(key)
    if not isinstance(raw, dict):
        value = t.number(key, lo=-MAX_PRESSURE, hi=MAX_PRESSURE, expected=_PRESSURE_FORMS)
        return PressureCurve("constant", value * scale)
    pt = t.table(key)
    bases = [b for b in ("angle", "fraction", "x") if pt.has(b)]
    if len(bases) != 1:
        raise pt.error("angle", "exactly one of angle (input angles, °), fraction (of the "
                       "stroke) or x (displacement from the head end)",
                       ", ".join(bases) or "none")
    basis = bases[0]
    xs = pt.numbers(basis)
    if len(xs) < 2 or any(b <= a for a, b in zip(xs, xs[1:])):
        raise pt.error(basis, "at least 2 increasing values", repr(xs))
    rows = None
    if pt.has("strokes"):
        if basis == "angle":
            raise pt.error("strokes", "an indicator diagram against fraction or x (a "
                           "table against angle takes value = [...])", "strokes")
        raw = pt.raw("strokes")
        want = (f"2 or 4 strokes, each an array of {len(xs)} pressures (one per {basis}): "
                "[[...], [...]]")
        if not isinstance(raw, list) or not 2 <= len(raw) <= 4:
            raise pt.error("strokes", want, f"{len(raw) if isinstance(raw, list) else raw!r}"
                           + (" strokes" if isinstance(raw, list) else ""))
        rows = []
        for i, row in enumerate(raw):
            ok = isinstance(row, list) and len(row) == len(xs) and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                and abs(v) <= MAX_PRESSURE for v in row)
            if not ok:
                raise SpecError(pt.file, pt.key(f"strokes[{i}]"),
                                f"an array of {len(xs)} finite pressures within "
                                f"±{MAX_PRESSURE:g} (one per {basis})", repr(row))
            rows.append([float(v) for v in row])
        if len(rows) == 3:
            raise pt.error("strokes", "2 strokes (one turn) or 4 strokes (two turns)",
                           "3 strokes")
        ys = np.asarray(rows, dtype=float) * scale
    else:
        ys = pt.numbers("value")
        if len(ys) != len(xs):
            raise pt.error("value", f"as many values as {basis} points ({len(xs)})",
                           f"{len(ys)} values")
        _bounded(pt, "value", ys, MAX_PRESSURE, "pressures")
        ys = np.asarray(ys, dtype=float) * scale
    xs = np.asarray(xs, dtype=float)
    if basis == "angle":
        if not rotary:
            raise pt.error("angle", "a table against fraction or x (the input is a slider, "
                           "not a crank)", "angle")
        width = xs[-1] - xs[0]
        whole = [c for c in (360.0, 720.0) if abs(width - c) <= 1e-9 * c]
        pt.finish()
        lo, hi = sorted(math.degrees(v) for v in span) if span is not None else (None, None)
        # (lo and hi are floats when span is given)
        spans = span is not None and xs[0] <= lo + 1e-9 and xs[-1] >= hi - 1e-9  # type: ignore[operator]
        # a whole cycle repeats when both ends give the same pressure (they are the same
        # crank position); with unequal ends it is read as it stands, over the input it spans
        if whole and ys[0] == ys[-1]:
            return PressureCurve("angle", xs=np.radians(xs), ys=ys,
                                 period=math.radians(whole[0]))
        if spans:
            return PressureCurve("angle", xs=np.radians(xs), ys=ys)
        if whole:
            raise pt.error("value", f"equal values at both ends of a table repeating every "
                           f"{whole[0]:g}° (the same crank position), or angles spanning the "
                           f"analysed input {lo:g}° … {hi:g}°",
                           f"{ys[0] / scale:g} at {xs[0]:g}° and {ys[-1] / scale:g} at "
                           f"{xs[-1]:g}°")
        if span is not None:
            raise pt.error("angle", f"input angles spanning the analysed input {lo:g}° … "
                           f"{hi:g}° (or one whole cycle of 360° or 720°)",
                           f"{xs[0]:g}° … {xs[-1]:g}°")
        raise pt.error("angle", "input angles spanning one whole cycle (360° or 720°)",
                       f"{xs[0]:g}° … {xs[-1]:g}°")
    pt.finish()
    # against the stroke: the table must span it, head end (0) to crank end
    stroke = piston.stroke / t.unit if basis == "x" else 1.0
    if not (xs[0] <= 1e-9 * stroke and xs[-1] >= stroke * (1 - 1e-9)):
        what = (f"x from 0 to the stroke {stroke:.6g} (the displacement from the head-end "
                "dead centre, spec units)" if basis == "x" else
                "fractions from 0 (head end) to 1 (crank end)")
        raise pt.error(basis, f"a table spanning the stroke: {what}",
                       f"{xs[0]:g} … {xs[-1]:g}")
    if basis == "x":
        xs = xs / stroke
    return PressureCurve("indicator" if rows is not None else "stroke", xs=xs, ys=ys,
                         direction=-1 if direction < 0 else 1)


def _gas_load(t: Section, name: str, link: int, topo: Topology, rotary: bool,
              span: Optional[Tuple[float, float]], direction: int = 1) -> Tuple[GasLoad, Load]:
    """A pressure load on a piston -> ``(GasLoad, Load)`` (the load's components are
    the unit vector of the line of stroke toward the crank; the source scales them)."""
    from mechcli.core.linkage.kinetostatics import Load
    from mechcli.core.linkage.piston import GasLoad, Piston, PistonError

    for key in ("pressure", "crank_side_pressure"):
        # a number or a table, checked first: a wrong type is named at its own key
        if t.has(key) and not isinstance(t.raw(key), dict):
            t.number(key, lo=-MAX_PRESSURE, hi=MAX_PRESSURE, expected=_PRESSURE_FORMS)
    for key in _FORCE_KEYS:
        if t.has(key):
            raise t.error(key, "no force, torque or point with pressure (the gas force acts "
                          "along the line of stroke at the piston pin)", key)
    try:
        piston = Piston.of(topo.linkage, link)
    except PistonError as exc:
        found = str(exc)
        if exc.lengths is not None:   # worded in the spec's length unit
            from mechcli.spec.reader import LENGTH_UNITS
            u = next((k for k, v in LENGTH_UNITS.items() if v == t.unit), "m")
            sc = LENGTH_UNITS.get(u, 1.0)
            ln = {k: f"{v / sc:.6g} {u}" for k, v in exc.lengths.items()}
            found = (f"the crank of piston {link} cannot make a whole turn (rod {ln['rod']} "
                     f"≤ crank {ln['crank']} + offset {ln['offset']})")
        raise t.error("link", "a piston: a block on a guide of the frame, pinned to a rod "
                      "on the crank that drives the linkage", found) from None
    unit = t.string("pressure_unit", choices=list(PRESSURE_UNITS))
    scale = PRESSURE_UNITS[unit]
    if t.has("bore") == t.has("area"):
        raise t.error("bore", "either bore (the cylinder diameter) or area (the piston "
                      "area), not both", "both" if t.has("bore") else "neither")
    if t.has("bore"):
        area = math.pi / 4 * t.length("bore") ** 2
    else:
        # the bounds of a length (Section.length), squared
        area = t.number("area", positive=True, hi=(MAX_LENGTH / t.unit) ** 2) * t.unit ** 2
    rod = t.length("rod", 0.0, positive=False, nonneg=True)
    rod_area = math.pi / 4 * rod * rod
    if rod_area >= area:
        raise t.error("rod", "a piston-rod diameter smaller than the bore",
                      f"{t.raw('rod')!r}")
    head = _pressure_curve(t, "pressure", scale, rotary, span, piston, direction)
    crank = (_pressure_curve(t, "crank_side_pressure", scale, rotary, span, piston, direction)
             if t.has("crank_side_pressure") else None)
    if crank is None and t.has("rod"):
        raise t.error("rod", "a crank_side_pressure for the rod to reduce (the rod is on "
                      "the crank side)", f"{t.raw('rod')!r}")
    dx, dy = piston.d
    load = Load(name, link, dx, dy, 0.0, piston.pin, 0.0, 0.0, False)
    return GasLoad(piston, head, area, crank, rod_area), load


def _force_load(t: Section, name: str, link: int, topo: Topology) -> Load:
    """A force and/or torque load (``force``/``magnitude``, ``torque``, ``at``)."""
    from mechcli.core.linkage.kinetostatics import Load

    fx = fy = 0.0
    has_force = t.has("force") or t.has("magnitude")
    if t.has("force") and t.has("magnitude"):
        raise t.error("magnitude", "either force or magnitude, not both", "both")
    if t.has("force"):
        fx, fy = _bounded(t, "force", t.numbers("force", size=2), MAX_FORCE,
                          "components [N]")
    elif t.has("magnitude"):
        mag = t.number("magnitude", nonneg=True, hi=MAX_FORCE)
        ang = math.radians(t.number("angle"))
        fx, fy = mag * math.cos(ang), mag * math.sin(ang)
    relative = t.boolean("relative", False)
    torque = t.number("torque", 0.0, lo=-MAX_FORCE, hi=MAX_FORCE)
    if not has_force and not t.has("torque"):
        raise t.error("force", "a force (force = [fx, fy] or magnitude/angle) or a torque",
                      "neither")
    origin, along, normal = None, 0.0, 0.0
    if t.has("at") or t.has("at_from"):
        if not has_force:
            raise t.error("at" if t.has("at") else "at_from",
                          "no point of action for a pure torque", "a point")
        origin, along, normal = _place(t, "at", "at_from", topo, link, allow_mid=False) \
            or (t.name("at_from"), 0.0, 0.0)
    return Load(name, link, fx, fy, torque, origin, along, normal, relative)


def _output(sec: Section, inp: InputSpec) -> ForceOutput:
    unit = math.pi / 180 if inp.rotary else sec.unit
    span = (inp.stop - inp.start) / unit
    # a table row per step: at most the sweep's own number of positions
    least = span / (MAX_POSITIONS - 1)
    table_step = sec.number("table_step", 30.0 if inp.rotary else span / 10, lo=least,
                            expected=f"a step of at least {least:g} (the sweep / "
                                     f"{MAX_POSITIONS - 1:,})") * unit
    plots = sec.boolean("plots", True)
    animate = sec.boolean("animate", False)
    frames = sec.integer("frames", 72, lo=2, hi=3600)
    draw_at = sec.number("draw_at", inp.start / unit, lo=-36000.0, hi=36000.0) * unit
    digits = sec.integer("digits", 2, lo=0, hi=12)
    # correct significant digits below which a warning is given: a float64 result
    # has at most 15.7 (-log10 of the rounding unit), so 16 warns everywhere, 0 never
    accuracy_warn = sec.number("accuracy_warn", 8.0, lo=0.0, hi=16.0)
    # inputs whose values are reported by name (a worked example's crank angle)
    at = sec.numbers("at", [])
    if len(at) > 100:
        raise sec.error("at", "at most 100 input positions", f"{len(at)}")
    lo, hi = sorted((inp.start / unit, inp.stop / unit))
    named: Dict[float, int] = {}
    for i, v in enumerate(at):
        if not lo - 1e-9 <= v <= hi + 1e-9:
            raise SpecError(sec.file, sec.key(f"at[{i}]"), f"an input within the analysed "
                            f"range {lo:g} … {hi:g}", f"{v:g}")
        # the results are named by the input rounded to 9 decimals (report.force.at_text):
        # one name per input, or they would overwrite each other
        key = round(float(v), 9) + 0.0
        if key in named:
            raise SpecError(sec.file, sec.key(f"at[{i}]"), "inputs that differ after "
                            "rounding to 9 decimals (each names its results "
                            "<sym>_at_<value>)", f"{v!r}, the same as at[{named[key]}] = "
                            f"{at[named[key]]!r}")
        named[key] = i
    sec.finish()
    return ForceOutput(table_step, plots, animate, frames, draw_at, digits,
                       accuracy_warn, tuple(v * unit for v in at))


#: ``[approximate] moment_arm``: the arm of the approximate model's T and FT
MOMENT_ARMS = ("exact", "series")


def read_approximate(root: Section, model: str) -> str:
    """``[approximate]`` -> the moment arm of the approximate model's T and FT:
    ``"exact"`` (the default: the rod's force on the crank pin) or ``"series"``
    (T = FP · r (sin θ + sin 2θ / 2n), docs/approximate.md).  The table belongs to
    ``[mechanism] model = "approximate"``: with the exact model it is exit 2."""
    if not root.has("approximate"):
        return "exact"
    sec = root.table("approximate")
    arm = sec.string("moment_arm", "exact", choices=list(MOMENT_ARMS))
    sec.finish()
    if model != "approximate":
        key = next(iter(sec.data), None)
        raise SpecError(root.file, sec.key(key) if key is not None else "approximate",
                        "[mechanism] model = \"approximate\" with an [approximate] table "
                        "(the series moment arm belongs to the approximate model)",
                        f"model = \"{model}\"")
    return arm


def load_force_spec(path: Union[str, os.PathLike], overrides: Iterable[str] = ()) -> ForceSpec:
    """Read and validate a ``mechcli force`` spec (exit 2 on any error)."""
    return read_force_root(load_spec(path, overrides))


def read_force_root(root: Section) -> ForceSpec:
    """:func:`load_force_spec` on a root table already loaded (``optimize``
    reads its problem's tables this way)."""
    from mechcli.core.linkage.kinematics import default_quantities

    header = read_header(root, "force", default_unit="mm")
    mech = root.data.get("mechanism")
    model = mech.get("model", "exact") if isinstance(mech, dict) else "exact"
    kind, linkage, tracers, followers, guide_length = read_mechanism(root)
    try:
        topo = topology(linkage)
    except ForceModelError as exc:
        raise SpecError(root.file, "mechanism", "a linkage whose pairs can carry forces",
                        str(exc)) from None
    for i, d in enumerate(linkage.drivers):
        if getattr(d, "actuator", None) is not None:
            try:
                actuated_pair(topo, d.actuator)
            except ForceModelError as exc:
                raise SpecError(root.file, f"mechanism.driver.{i}.actuator",
                                "the name of an RPR dyad's slide (the cylinder that drives "
                                "the machine)", f"{d.actuator!r}: {exc}") from None
    inp = read_input(root, linkage, followers, MAX_POSITIONS, POSITIONS_WHY)
    grav = read_gravity(root)
    bodies = read_bodies(root, topo, linkage.frame)
    quantities = default_quantities(linkage, 2, [p for p in linkage.point_names])
    loads = read_loads(root, topo, linkage.frame, inp.rotary, quantities,
                       (inp.start, inp.stop), pressure=True,
                       direction=-1 if inp.rotary and inp.omega < 0 else 1)
    out = _output(root.table("output") if root.has("output") else _empty(root, "output"), inp)
    arm = read_approximate(root, model)
    expected = read_expected(root)
    root.finish()
    # (a load's source is a GasLoad, typed object in LoadProgram)
    piston = next((p.source.piston for p in loads  # type: ignore[attr-defined]
                   if p.source is not None), None)
    if model == "approximate":
        from mechcli.core.linkage.piston import Piston
        piston = Piston.of(linkage, 3)      # the slider-crank preset's slider
        if arm != "exact":
            import dataclasses
            piston = dataclasses.replace(piston, moment_arm=arm)
    return ForceSpec(header, kind, linkage, topo, tracers, inp, bodies, grav, loads, out,
                     expected, guide_length, model, piston)
