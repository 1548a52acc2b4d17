"""``mechcli kin`` problem files -> :class:`KinSpec` (SI units, radians).

Presets (the book's chapter-1 mechanisms) expand into the general form, so
there is one engine and one code path:

* ``four_bar``     l1 crank, l2 coupler, l3 rocker, l4 frame; A=(0,0), D=(l4,0) (图 1-2)
* ``slider_crank`` l1, l2, offset e; A=(0,0), slider guide y = e (图 1-4)
* ``guide_bar``    l1 crank, l4 = AC frame; C=(0,0), A=(0,l4); optional guide offset e (图 1-6)
* ``shaper``       l1, l3, l4, l6, l6p (= l6'); C=(0,0), A=(0,l6), ram guide y = l6p (图 1-8)
* ``general``      ground points, drivers, dyads (RRR, RRP, RPR, PRP) and points on links
* ``joints``       the drawing: joints, links, sliders, drivers; the Assur groups are found
                   (:mod:`mechcli.spec.joints`, :mod:`mechcli.core.linkage.drawing`)
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from mechcli.core.linkage import (
    PRP,
    RPR,
    RRP,
    RRR,
    Crank,
    Ground,
    Linkage,
    LinkageDefinitionError,
    PointOnLink,
    SliderDriver,
    presets,
)
from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.reader import MAX_LENGTH, MIN_LENGTH, Section, load_spec

MECHANISMS = ("four_bar", "slider_crank", "guide_bar", "shaper", "general", "joints")
QUANTITIES = ("position", "velocity", "acceleration")
#: the most positions held in memory: the 1 GiB memory budget of every command over the
#: peak RSS a run takes per position (taken as ~1.5 kB, POSITIONS_WHY, for the deepest
#: presets with plots or animation; ``kin_in_memory_600001_peak_rss_per_position`` of
#: benchmarks/bench_kin.py measures it), rounded down
MAX_POSITIONS = 600_001
POSITIONS_WHY = "1 GiB budget at ~1.5 kB per position"
#: `mechcli kin` streams a longer sweep to its CSV chunk by chunk in bounded memory
#: (the analysis, table and plots run on every k-th row, see InputSpec.count); the cap
#: bounds the run's time and the CSV's size (~10 GB at 1e8 rows)
MAX_STREAMED = 100_000_001
STREAMED_WHY = f"rows past {MAX_POSITIONS:,} are streamed to the CSV"


@record
class Tracer:
    """A named point fixed on a link, reported and drawn (coupler curve)."""

    name: str
    link: int


@record
class InputSpec:
    """The primary driver's program.

    ``start``/``stop``/``q`` are radians for a crank, metres for a slider;
    ``omega`` [rad/s or m/s] and ``alpha`` [rad/s^2 or m/s^2] are the same at
    every position (the book's convention).
    """

    driver: int
    rotary: bool
    start: float
    stop: float
    q: np.ndarray
    omega: float
    alpha: float
    followers: dict
    partial: bool
    #: rows of a streamed sweep (more than MAX_POSITIONS): ``q`` then holds every k-th
    #: of them and the last (:func:`mechcli.core.linkage.streaming.stream_grid`), the
    #: rows are ``np.linspace(start, stop, count)``; 0 when ``q`` is the whole sweep
    count: int = 0

    def sweep(self) -> Any:
        """The core's :class:`~mechcli.core.linkage.kinematics.Sweep` of this program."""
        from mechcli.core.linkage.kinematics import Sweep
        return Sweep(self.driver, self.q, self.omega, self.alpha, self.followers, self.periodic)

    @property
    def periodic(self) -> bool:
        if not self.rotary:
            return False
        turns = (self.stop - self.start) / (2 * math.pi)
        whole = abs(turns - round(turns)) < 1e-9 and round(turns) >= 1
        return whole and all(abs(r - round(r)) < 1e-12 for r, _ in self.followers.values())


@record
class OutputSpec:
    order: int
    table_step: float  # input units (rad or m)
    plots: bool
    animate: bool
    frames: int
    draw_at: float  # input units
    digits: int
    #: warn where fewer correct significant digits than this remain (estimated)
    accuracy_warn: float = 8.0


@record
class KinSpec:
    header: Header
    mechanism: str
    linkage: Linkage
    tracers: Tuple[Tracer, ...]
    input: InputSpec
    output: OutputSpec
    expected: dict
    guide_length: Optional[float] = None  # drawing only (guide-bar l3) [m]
    #: a slider-crank's ``[mechanism] model``: "exact" (the engine) or "approximate"
    #: (kin reports the books' series in 1/n for the slide)
    model: str = "exact"


# ---------------------------------------------------------------------------
def _branch(sec: Section, name: str, default: Union[str, int], named: Dict[str, int]) -> int:
    raw = sec.raw(name, default)
    if isinstance(raw, str) and raw in named:
        return named[raw]
    if isinstance(raw, int) and not isinstance(raw, bool) and raw in (1, -1):
        return raw
    opts = ", ".join([f"'{k}'" for k in named] + ["1", "-1"])
    raise SpecError(sec.file, sec.key(name), f"one of {opts}", repr(raw))


def _preset(mech: Section, kind: str) -> Tuple[int, List[Any], Optional[float]]:
    """Expand a preset into (frame, elements, guide_length) with the core's presets."""
    mech.declare("l1", "l2", "l3", "l4", "l6", "l6p", "e", "branch", "point")
    guide_length = None
    if kind == "four_bar":
        l1, l2, l3, l4 = (mech.length(k) for k in ("l1", "l2", "l3", "l4"))
        br = _branch(mech, "branch", "open", presets.FOUR_BAR_BRANCHES)
        linkage = presets.four_bar(l1, l2, l3, l4, br)
    elif kind == "slider_crank":
        l1, l2 = mech.length("l1"), mech.length("l2")
        e = mech.coordinate("e", 0.0)
        br = _branch(mech, "branch", "right", presets.SLIDER_CRANK_BRANCHES)
        # model = "approximate": kin reports the books' series in 1/n for the slide
        # (mechcli.core.linkage.approximate); the series assumes no offset and n > 1
        model = mech.string("model", "exact", choices=["exact", "approximate"])
        if model == "approximate" and e != 0:
            raise mech.error("e", "e = 0 with model = \"approximate\" (the series in 1/n "
                             "assumes a centred slider-crank)", repr(mech.raw("e")))
        if model == "approximate" and not l2 > l1:
            raise mech.error("l2", "l2 > l1 with model = \"approximate\" (the series in "
                             "n = l2/l1 needs n > 1)", repr(mech.raw("l2")))
        linkage = presets.slider_crank(l1, l2, e, br)
    elif kind == "guide_bar":
        l1, l4 = mech.length("l1"), mech.length("l4")
        e = mech.coordinate("e", 0.0)
        guide_length = mech.length("l3", None)
        br = _branch(mech, "branch", 1, {})
        linkage = presets.guide_bar(l1, l4, e, br)
    elif kind == "shaper":
        l1, l3, l4, l6, l6p = (mech.length(k) for k in ("l1", "l3", "l4", "l6", "l6p"))
        br = _branch(mech, "branch", "left", presets.SHAPER_BRANCHES)
        linkage = presets.shaper(l1, l3, l4, l6, l6p, br)
    else:
        raise AssertionError(kind)
    return linkage.frame, list(linkage.elements), guide_length


def _general(mech: Section) -> Tuple[int, List[Any], dict, List[str]]:
    """Read the general form: ground, driver, dyad tables."""
    frame = mech.integer("frame", lo=1)
    elements: List[Any] = []
    paths: List[str] = []
    ground = mech.table("ground")
    for name in ground.keys():
        ground.check_name(None, name)
        xy = ground.numbers(name, size=2)
        if max(abs(xy[0]), abs(xy[1])) * mech.unit > MAX_LENGTH:
            raise ground.error(name, f"coordinates within ±{MAX_LENGTH:g} m", repr(xy))
        elements.append(Ground(name, xy[0] * mech.unit, xy[1] * mech.unit))
        paths.append(ground.key(name))
    ground.finish()
    followers = {}
    drivers = mech.tables("driver")
    for i, d in enumerate(drivers):
        kind = d.string("type", "crank", choices=["crank", "slider"])
        link = d.integer("link", lo=1)
        if kind == "crank":
            elements.append(Crank(link, d.name("pivot"), d.name("point"), d.length("length"),
                                  d.name("actuator", None)))
        else:
            elements.append(SliderDriver(link, d.name("origin"), d.name("point"),
                                         math.radians(d.number("angle", 0.0)),
                                         d.name("name", None)))
        paths.append(d.path)
        if i > 0:
            followers[link] = (follower_ratio(d),
                               math.radians(d.number("phase", 0.0)) if kind == "crank"
                               else d.number("phase", 0.0) * mech.unit)
        d.finish()
    for dy in mech.tables("dyad", []):
        kind = dy.string("type", choices=list(DYADS))
        elements.append(DYADS[kind](dy, mech.unit))
        paths.append(dy.path)
        dy.finish()
    return frame, elements, followers, paths


#: the largest |ratio| of a secondary driver to the primary one (a gear train's ratio):
#: beyond it the sweep's step would leave the secondary input unresolved
MAX_RATIO = 1e4


def follower_ratio(d: Section) -> float:
    """A secondary driver's ``ratio`` to the primary one, in [-MAX_RATIO, MAX_RATIO]."""
    return d.number("ratio", 1.0, lo=-MAX_RATIO, hi=MAX_RATIO)


def _dyad_branch(dy: Section) -> int:
    return _branch(dy, "branch", 1, {"left": 1, "right": -1})


def _rrr(dy: Section, unit: float) -> RRR:
    br = _dyad_branch(dy)
    pts = dy.strings("points")
    links = dy.raw("links")
    lengths = dy.numbers("lengths", size=2, positive=True)
    for length in lengths:  # the bounds of every other length (Section.length)
        if not MIN_LENGTH <= length * unit <= MAX_LENGTH:
            raise dy.error("lengths", f"lengths between {MIN_LENGTH:g} m and {MAX_LENGTH:g} m",
                           repr(lengths))
    if len(pts) != 2:
        raise dy.error("points", "an array of 2 point names", f"an array of {len(pts)}")
    for i, p in enumerate(pts):
        dy.check_name(f"points[{i}]", p)
    if not (isinstance(links, list) and len(links) == 2
            and all(isinstance(x, int) and not isinstance(x, bool) and x > 0 for x in links)):
        raise dy.error("links", "an array of 2 link numbers", repr(links))
    return RRR(dy.name("joint"), pts[0], links[0], lengths[0] * unit,
               pts[1], links[1], lengths[1] * unit, br)


def _rrp(dy: Section, unit: float) -> RRP:
    br = _dyad_branch(dy)
    return RRP(dy.name("joint"), dy.name("point"), dy.integer("link", lo=1),
               dy.length("length"), dy.integer("slider", lo=1), dy.integer("guide_link", lo=1),
               dy.name("guide_point"), math.radians(dy.number("guide_angle", 0.0)),
               dy.coordinate("offset", 0.0), br, dy.name("name", None))


def _rpr(dy: Section, unit: float) -> RPR:
    br = _dyad_branch(dy)
    return RPR(dy.name("point"), dy.integer("block", lo=1), dy.name("pivot"),
               dy.integer("guide", lo=1), dy.coordinate("offset", 0.0), br,
               dy.name("name", None))


def _prp(dy: Section, unit: float) -> PRP:
    """RRP's guide keys twice, suffixed ``_a`` and ``_b`` (the keys are the fields)."""
    if dy.has("branch"):
        raise dy.error("branch", "no branch (a PRP dyad's joint is the one intersection of "
                       "its two guide lines)", repr(dy.raw("branch")))
    keys = {}
    for x in "ab":
        keys.update({f"slider_{x}": dy.integer(f"slider_{x}", lo=1),
                     f"guide_link_{x}": dy.integer(f"guide_link_{x}", lo=1),
                     f"guide_point_{x}": dy.name(f"guide_point_{x}"),
                     f"guide_angle_{x}": math.radians(dy.number(f"guide_angle_{x}", 0.0)),
                     f"offset_{x}": dy.coordinate(f"offset_{x}", 0.0),
                     f"name_{x}": dy.name(f"name_{x}", None)})
    return PRP(dy.name("joint"), **keys)


#: ``[[mechanism.dyad]] type`` -> reader of that dyad's keys (a new dyad type of
#: the engine adds one reader here)
DYADS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp}


def _points(mech: Section, elements: List[Any], paths: List[str]) -> List[Tracer]:
    """``[[mechanism.point]]``: points fixed on links; traced unless ``trace = false``."""
    tracers = []
    for pt in mech.tables("point", []):
        name = pt.name("name")
        link = pt.integer("link", lo=1)
        origin = pt.name("from")
        along = pt.coordinate("along", 0.0)
        normal = pt.coordinate("normal", 0.0)
        elements.append(PointOnLink(name, link, origin, along, normal))
        paths.append(pt.path)
        if pt.boolean("trace", True):
            tracers.append(Tracer(name, link))
        pt.finish()
    return tracers


#: engine field -> spec key, for pointing an error at the right key
_SPEC_KEY = {"point_a": "points", "point_b": "points", "link_a": "links", "link_b": "links",
             "origin": "from", "joint": "joint", "point": "point", "pivot": "pivot",
             "guide_point": "guide_point", "guide_link": "guide_link", "link": "link",
             "guide": "guide", "block": "block", "slider": "slider", "name": "name",
             **{f"{k}_{x}": f"{k}_{x}" for k in ("guide_point", "guide_link", "slider")
                for x in "ab"}}


#: (element kind, engine field) -> spec key, where the kind's table names it otherwise
_KIND_KEY = {("slider", "origin"): "origin"}


def _build_linkage(mech: Section, frame: int, elements: List[Any],
                   paths: List[str]) -> Linkage:
    try:
        return Linkage(frame=frame, elements=tuple(elements))
    except LinkageDefinitionError as exc:
        key = "mechanism"
        if exc.index is not None:
            el, key = elements[exc.index], paths[exc.index]
            if exc.field is not None and key != "mechanism":
                _kind, value = exc.field
                for f in dataclasses.fields(el):
                    if getattr(el, f.name) == value and f.name in _SPEC_KEY:
                        key += "." + _KIND_KEY.get((el.kind, f.name), _SPEC_KEY[f.name])
                        break
        msg = str(exc)
        cycle = getattr(exc, "cycle", None)
        if cycle:
            msg = ("a closed loop of definitions between "
                   + ", ".join(f"[{paths[i]}]" for i in cycle))
        raise SpecError(mech.file, key, "a linkage whose elements can be solved in order",
                        msg) from None


def _one_of(sec: Section, first: str, second: str) -> str:
    """Two keys of which a spec gives one (``omega1``/``n1``, ``step``/``count``),
    both given: a ``--set`` of one replaces the other from the file (returns the key
    kept); both in the file, or both set, is an error."""
    if sec.is_overridden(second) and not sec.is_overridden(first):
        sec.data = {k: v for k, v in sec.data.items() if k != first}
        return second
    if sec.is_overridden(first) and not sec.is_overridden(second):
        sec.data = {k: v for k, v in sec.data.items() if k != second}
        return first
    raise SpecError(sec.file, sec.key(second), f"either {first} or {second}, not both", "both")


#: a crank's range whose ends are all within this many degrees looks like radians
#: (2π = 6.28; ``stop = 6.2`` meant a whole turn)
_RADIAN_LIKE_DEG = 2 * math.pi * 1.02


def _degrees_hint(rotary: bool, start: float, stop: float) -> str:
    """`` (angles are in degrees ...)`` when a crank's range [rad] looks like it was
    given in radians, else ''."""
    a, b = math.degrees(start), math.degrees(stop)
    if not rotary or max(abs(a), abs(b)) > _RADIAN_LIKE_DEG:
        return ""
    return (f" (start = {a:g}, stop = {b:g}: angles are in degrees, a whole turn is "
            f"stop = {a + 360:g})")


def _input(sec: Section, linkage: Linkage, followers: dict, max_positions: int = MAX_POSITIONS,
           why: str = POSITIONS_WHY, stream_max: Optional[int] = None) -> InputSpec:
    in_memory = max_positions
    if stream_max is not None and stream_max > max_positions:  # kin: longer sweeps stream
        max_positions, why = stream_max, STREAMED_WHY
    first = linkage.drivers[0]
    rotary = first.rotary
    if rotary:
        has_w, has_n = sec.has("omega1"), sec.has("n1")
        if has_w and has_n:
            has_n = _one_of(sec, "omega1", "n1") == "n1"
        if has_n:
            omega = sec.number("n1", lo=-1e7, hi=1e7) * 2 * math.pi / 60.0
        else:
            omega = sec.number("omega1", 1.0, lo=-1e6, hi=1e6)
        alpha = sec.number("alpha1", 0.0, lo=-1e12, hi=1e12)
        start = math.radians(sec.number("start", 0.0, lo=-36000.0, hi=36000.0))
        stop = math.radians(sec.number("stop", 360.0, lo=-36000.0, hi=36000.0))
        unit = math.pi / 180
    else:
        omega = sec.number("v1", 1.0, lo=-1e9, hi=1e9) * sec.unit
        alpha = sec.number("a1", 0.0, lo=-1e15, hi=1e15) * sec.unit
        start = sec.number("start") * sec.unit
        stop = sec.number("stop") * sec.unit
        unit = sec.unit
    if stop <= start:
        raise SpecError(sec.file, sec.key("stop"), f"a value above start ({start / unit:g})",
                        f"{stop / unit:g}")
    if sec.has("step") and sec.has("count"):
        _one_of(sec, "step", "count")
    note = f" ({why})" if why else ""
    if sec.has("count"):
        raw = sec.data["count"]
        if isinstance(raw, int) and not isinstance(raw, bool) and raw > max_positions:
            raise sec.error("count", f"a count of at most {max_positions:,} "
                            f"positions{note}", f"{raw:,}")
        count = sec.integer("count", lo=2, hi=max_positions)
    else:
        given = sec.number("step", 1.0, positive=True)
        step = given * unit
        # a step so small that it underflows, or gives more positions than the limit
        steps = (stop - start) / step if step > 0 else math.inf
        if steps + 1 > max_positions:
            raise SpecError(sec.file, sec.key("step"),
                            f"a step giving at most {max_positions:,} positions{note}",
                            f"{steps + 1:,.0f} positions" if math.isfinite(steps)
                            else f"{given:g} (too small to count positions with)")
        count = int(round(steps)) + 1
        if abs(start + (count - 1) * step - stop) > 1e-9 * max(1.0, abs(stop)):
            raise SpecError(sec.file, sec.key("step"),
                            "a step that divides stop - start into whole steps",
                            f"{step / unit:g} for {(stop - start) / unit:g}"
                            + _degrees_hint(rotary, start, stop))
        count = max(count, 2)
    if count > in_memory:
        from mechcli.core.linkage.streaming import stream_grid
        q, streamed = stream_grid(start, stop, count), count
    else:
        q, streamed = np.linspace(start, stop, count), 0
    partial = sec.boolean("partial", False)
    sec.finish()
    return InputSpec(first.link, rotary, start, stop, q, omega, alpha, followers, partial,
                     streamed)


def _output(sec: Section, inp: InputSpec) -> OutputSpec:
    unit = math.pi / 180 if inp.rotary else sec.unit
    if sec is None:
        return None
    qs = sec.strings("quantities", list(QUANTITIES), choices=list(QUANTITIES))
    if not qs:
        raise sec.error("quantities", "at least one of " + ", ".join(QUANTITIES), "[]")
    order = max(QUANTITIES.index(q) for q in qs)
    span = (inp.stop - inp.start) / unit
    default_step = 30.0 if inp.rotary else span / 10
    # a table row per step: at most MAX_POSITIONS rows, the sweep's own limit
    least = span / (MAX_POSITIONS - 1)
    table_step = sec.number("table_step", default_step, lo=least,
                            expected=f"a step of at least {least:g} (the sweep / "
                                     f"{MAX_POSITIONS - 1:,})") * unit
    plots = sec.boolean("plots", True)
    animate = sec.boolean("animate", False)
    frames = sec.integer("frames", 72, lo=2, hi=3600)
    draw_at = sec.number("draw_at", inp.start / unit, lo=-36000.0, hi=36000.0) * unit
    digits = sec.integer("digits", 4, lo=1, hi=12)
    # correct significant digits below which a warning is given: a float64 result
    # has at most 15.7 (-log10 of the rounding unit), so 16 warns everywhere, 0 never
    accuracy_warn = sec.number("accuracy_warn", 8.0, lo=0.0, hi=16.0)
    sec.finish()
    return OutputSpec(order, table_step, plots, animate, frames, draw_at, digits,
                      accuracy_warn)


def read_mechanism(root: Section) -> Tuple[Any, ...]:
    """Read ``[mechanism]`` (a preset or the general form) into a linkage.

    Returns ``(kind, linkage, tracers, followers, guide_length)``; shared by
    every command that runs the linkage engine (``kin``, ``force``).
    """
    mech = root.table("mechanism")
    kind = mech.string("type", choices=list(MECHANISMS))
    followers: dict = {}
    guide_length = None
    drawn = None
    if kind == "general":
        frame, elements, followers, paths = _general(mech)
    elif kind == "joints":
        from mechcli.spec.joints import read_joints
        frame, elements, followers, paths, drawn = read_joints(mech)
    else:
        frame, elements, guide_length = _preset(mech, kind)
        paths = ["mechanism"] * len(elements)
    n_before = len(elements)
    tracers = _points(mech, elements, paths)
    mech.finish()
    if drawn is not None:
        # a point's `along`/`normal` are measured from its link's first joint to its
        # second as drawn: turned into the engine's direction of that link
        offsets = dict(drawn.linkage.angle_offsets)
        elements[n_before:] = [_turned(el, offsets.get(el.link, 0.0))
                               for el in elements[n_before:]]
        linkage = dataclasses.replace(drawn.linkage, elements=tuple(elements))
    else:
        linkage = _build_linkage(mech, frame, elements, paths)
    if not linkage.drivers:
        raise SpecError(root.file, "mechanism.driver", "at least one driver", "none")
    return kind, linkage, tuple(tracers), followers, guide_length


def _turned(point: PointOnLink, offset: float) -> PointOnLink:
    """A :class:`PointOnLink` whose ``along``/``normal`` are given from its link's
    drawn direction, re-measured from the engine's (``offset`` = drawn − engine)."""
    if offset == 0.0:
        return point
    c, s = math.cos(offset), math.sin(offset)
    return dataclasses.replace(point, along=point.along * c - point.normal * s,
                               normal=point.along * s + point.normal * c)


def read_input(root: Section, linkage: Linkage, followers: dict,
               max_positions: int = MAX_POSITIONS, why: str = POSITIONS_WHY,
               stream_max: Optional[int] = None) -> InputSpec:
    """Read ``[input]`` (the primary driver's program) for *linkage*.

    *max_positions* caps ``count`` (and the count a ``step`` gives); *why* is said
    with the cap in the error, e.g. the memory budget it comes from.  With
    *stream_max* a sweep of up to that many rows is accepted as streamed
    (``InputSpec.count``).
    """
    return _input(root.table("input") if root.has("input") else _empty(root, "input"),
                  linkage, followers, max_positions, why, stream_max)


def load_kin_spec(path: Union[str, Path], overrides: Sequence[str] = (),
                  stream: bool = False) -> KinSpec:
    """Read and validate a ``mechcli kin`` spec (*stream*: accept a sweep of up to
    ``MAX_STREAMED`` rows, streamed to the CSV; see ``InputSpec.count``).

    Raises
    ------
    SpecError
        With the file, key, expectation and what was found.
    """
    return read_kin_root(load_spec(path, overrides), stream)


def read_kin_root(root: Section, stream: bool = False) -> KinSpec:
    """:func:`load_kin_spec` on a root table already loaded (``optimize``
    reads its problem's tables this way)."""
    header = read_header(root, "kin", default_unit="mm")
    kind, linkage, tracers, followers, guide_length = read_mechanism(root)
    inp = read_input(root, linkage, followers, stream_max=MAX_STREAMED if stream else None)
    out_sec = root.table("output") if root.has("output") else _empty(root, "output")
    output = _output(out_sec, inp)
    expected = read_expected(root)
    root.finish()
    return KinSpec(header, kind, linkage, tracers, inp, output, expected, guide_length,
                   _model(root))


def _model(root: Section) -> str:
    """``[mechanism] model`` of a slider-crank (validated by :func:`_preset`)."""
    mech = root.data.get("mechanism", {})
    return str(mech.get("model", "exact")) if isinstance(mech, dict) else "exact"


def _empty(root: Section, name: str) -> Section:
    from mechcli.spec.reader import Section
    sec = Section({}, root.file, name, root.unit)
    sec.overridden = root.overridden
    return sec


def refuse_approximate(root: Section, command: str) -> None:
    """``[mechanism] model = "approximate"`` is kin's (the piston's series in 1/n): the
    other commands that read a linkage solve it exactly, so they refuse the key rather
    than ignore it."""
    mech = root.data.get("mechanism")
    if isinstance(mech, dict) and mech.get("model", "exact") != "exact":
        raise SpecError(root.file, "mechanism.model",
                        f"\"exact\" for `mechcli {command}` (the approximate series is "
                        "`mechcli kin`'s)", repr(mech.get("model")))
