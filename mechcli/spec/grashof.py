"""``mechcli grashof`` problem files -> :class:`GrashofSpec` (SI units).

One spec holds exactly one problem table: ``[fourbar]``, ``[slider_crank]``,
``[guide_bar]``, ``[fivebar]``, ``[rrrrp]`` or ``[mobility]`` (see
docs/grashof.md).  The quick form ``--lengths`` builds the same spec without a
file (:func:`quick_spec`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Collection, Iterable, Optional, Sequence, Tuple, Union

from mechcli.core.records import record
from mechcli.spec.common import Header, read_expected, read_header
from mechcli.spec.errors import SpecError
from mechcli.spec.reader import LENGTH_UNITS, MAX_LENGTH, MIN_LENGTH, Section, load_spec

if TYPE_CHECKING:
    from mechcli.core.linkage.force_model import Pair

PROBLEMS = ("fourbar", "slider_crank", "guide_bar", "fivebar", "rrrrp", "mobility")


@record
class FourBarProblem:
    lengths: tuple          # l1..l4 [m]
    frame: int
    input: int
    crossed: bool
    vary: tuple             # link numbers whose length ranges are wanted
    rtol: float
    curve_step: float | None = None   # [rad] step of the transmission-angle curve
    draw: bool = False                # picture of the limit positions (limits.png)


@record
class SliderCrankProblem:
    crank: float            # [m]
    coupler: float
    offset: float
    rtol: float
    curve_step: float | None = None


@record
class GuideBarProblem:
    crank: float            # [m]
    frame: float
    offset: float
    rtol: float
    curve_step: float | None = None


@record
class FiveBarProblem:
    lengths: tuple          # l1..l5 [m]
    frame: int
    inputs: tuple
    rtol: float


@record
class RRRRPProblem:
    l1: float
    l2: float
    l3: float
    offset: float
    rtol: float


@record
class JointSpec:
    kind: str
    links: tuple
    name: str


@record
class MobilityProblem:
    joints: tuple           # of JointSpec
    frame: int
    local_dof: int
    redundant: int
    source: str             # "joints", "links" (the joints form) or the kin spec path
    drivers: tuple = ()     # the driving links: the structural analysis (groups) when given


@record
class GrashofSpec:
    header: Header
    kind: str
    problem: object
    expected: dict
    path: Path | None


def _check_length(file: str, key: str, value: float, scale: float, signed: bool = False) -> float:
    """The one range check of a grashof length (a spec array item, a ``--lengths`` item,
    ``--offset``): within the lengths every reader accepts, ``reader.MIN_LENGTH`` …
    ``MAX_LENGTH`` metres (far outside, sums of squares of lengths under- or overflow and
    the type test compares rounding noise).  *signed*: an offset, zero or either sign."""
    metres = abs(value) * scale
    if signed and (metres == 0 or MIN_LENGTH <= metres <= MAX_LENGTH) \
            or not signed and MIN_LENGTH <= metres <= MAX_LENGTH:
        return value * scale
    want = f"a length between {MIN_LENGTH:g} m and {MAX_LENGTH:g} m"
    raise SpecError(file, key, ("0 or " if signed else "") + want
                    + (" in size" if signed else ""), f"{value:g} ({value * scale:g} m)")


def _lengths(sec: Section, name: str, size: int) -> Tuple[float, ...]:
    """An array of *size* lengths in the spec's unit, in metres."""
    return tuple(_check_length(sec.file, sec.key(f"{name}[{i}]"), v, sec.unit)
                 for i, v in enumerate(sec.numbers(name, size=size, positive=True)))


def _rtol(sec: Section) -> float:
    return sec.number("change_point_rtol", 1e-9, lo=0.0, hi=1e-2)


def _curve_step(sec: Section) -> Optional[float]:
    """``curve_step`` [deg] -> radians, or None (no transmission-angle curve)."""
    step = sec.number("curve_step", None, lo=0.01, hi=90.0)
    return None if step is None else step * 3.141592653589793 / 180.0


def _link_number(sec: Section, name: str, default: Optional[int], n: int) -> Any:
    return sec.integer(name, default, lo=1, hi=n)


def _read_fourbar(sec: Section) -> FourBarProblem:
    lengths = _lengths(sec, "lengths", 4)
    frame = _link_number(sec, "frame", 4, 4)
    neighbours = ((frame % 4) + 1, ((frame + 2) % 4) + 1)
    default_input = 1 if 1 in neighbours else neighbours[0]
    inp = sec.integer("input", default_input, lo=1, hi=4)
    if inp not in neighbours:
        raise sec.error("input", f"a link joined to the frame {frame}: "
                        f"{neighbours[0]} or {neighbours[1]}", repr(inp))
    assembly = sec.string("assembly", "open", choices=["open", "crossed"])
    vary = sec.raw("vary", [])
    if isinstance(vary, int) and not isinstance(vary, bool):
        vary = [vary]
    if not isinstance(vary, list) or not all(isinstance(v, int) and not isinstance(v, bool)
                                             and 1 <= v <= 4 for v in vary):
        raise sec.error("vary", "a link number 1..4 or an array of them", repr(vary))
    rtol = _rtol(sec)
    step = _curve_step(sec)
    draw = sec.boolean("draw", False)
    sec.finish()
    return FourBarProblem(lengths, frame, inp, assembly == "crossed", tuple(vary), rtol, step,
                          draw)


def _read_slider(sec: Section) -> SliderCrankProblem:
    prob = SliderCrankProblem(sec.length("crank"), sec.length("coupler"),
                              sec.length("offset", 0.0, positive=False) or 0.0, _rtol(sec),
                              _curve_step(sec))
    sec.finish()
    return prob


def _read_guide(sec: Section) -> GuideBarProblem:
    prob = GuideBarProblem(sec.length("crank"), sec.length("frame"),
                           sec.length("offset", 0.0, nonneg=True) or 0.0, _rtol(sec),
                           _curve_step(sec))
    sec.finish()
    return prob


def _read_fivebar(sec: Section) -> FiveBarProblem:
    lengths = _lengths(sec, "lengths", 5)
    frame = _link_number(sec, "frame", 5, 5)
    nb = sorted(((frame % 5) + 1, ((frame + 3) % 5) + 1))
    inputs = sec.raw("inputs", list(nb))
    if not isinstance(inputs, list) or not all(
            isinstance(v, int) and not isinstance(v, bool) for v in inputs) \
            or sorted(inputs) != nb:
        raise sec.error("inputs", f"the two links joined to the frame {frame}: {nb}",
                        repr(inputs))
    prob = FiveBarProblem(lengths, frame, tuple(nb), _rtol(sec))
    sec.finish()
    return prob


def _read_rrrrp(sec: Section) -> RRRRPProblem:
    prob = RRRRPProblem(sec.length("l1"), sec.length("l2"), sec.length("l3"),
                        sec.length("offset", 0.0, positive=False) or 0.0, _rtol(sec))
    sec.finish()
    return prob


def _read_mobility(sec: Section, spec_dir: Path) -> MobilityProblem:
    local = sec.integer("local_dof", 0, lo=0)
    redundant = sec.integer("redundant", 0, lo=0)
    kin = sec.string("kin", None)
    if kin is not None:
        path = Path(kin)
        if not path.is_absolute():
            path = spec_dir / path
        try:
            why = "" if not kin.strip() else None if path.is_file() else \
                " (a folder)" if path.is_dir() else " (no such file)"
        except OSError as exc:   # a name too long for the OS, ...
            why = f" ({exc.strerror or exc})"
        if why is not None:   # name this spec and key, not the folder or file it points to
            raise sec.error("kin", "the path of a `mechcli kin` spec (relative to this file)",
                            f"'{kin}'{why}")
        kin_joints, frame, drivers = _joints_from_kin(path)
        sec.finish()
        return MobilityProblem(kin_joints, frame, local, redundant, str(kin), drivers)
    frame = sec.integer("frame", lo=0)
    if sec.has("link"):
        return _read_mobility_links(sec, frame, local, redundant)
    joints = []
    for js in sec.tables("joint"):
        kind = js.string("kind", "R", choices=["R", "P", "H"])
        links = js.raw("links")
        if not isinstance(links, list) or not all(isinstance(v, int) and not isinstance(v, bool)
                                                  and v >= 0 for v in links) \
                or len(links) < 2 or len(set(links)) != len(links):
            raise js.error("links", "an array of at least 2 different link numbers",
                           repr(links))
        if kind == "H" and len(links) != 2:
            raise js.error("links", "exactly 2 links for a higher pair", repr(links))
        name = js.name("name", None) or ""
        js.finish()
        joints.append(JointSpec(kind, tuple(links), name))
    if not joints:
        raise sec.error("joint", "at least one [[mobility.joint]]", "none")
    return _mobility_problem(sec, joints, frame, local, redundant, "joints")


def _mobility_problem(sec: Section, joints: Sequence[JointSpec], frame: int, local: int,
                      redundant: int, source: str) -> MobilityProblem:
    """The problem of the joints read (the frame among their links, the drivers checked)."""
    used = sorted({ln for j in joints for ln in j.links})
    if frame not in used:
        raise sec.error("frame", f"a link named by a joint: {used}", repr(frame))
    drivers = _drivers(sec, joints, frame, used)
    sec.finish()
    return MobilityProblem(tuple(joints), frame, local, redundant, source, drivers)


def _read_mobility_links(sec: Section, frame: int, local: int, redundant: int) -> MobilityProblem:
    """``[[mobility.link]]`` (number, joints) and ``[[mobility.slider]]`` (block, guide,
    name): the joints form of ``kin``'s ``type = "joints"`` without the positions (the
    structure does not depend on them); the same rule makes the pairs."""
    from mechcli.core.linkage.drawing import DrawingError, Slider, pairs_of_links

    if sec.has("joint"):
        raise sec.error("joint", "either [[mobility.joint]] or [[mobility.link]], not both",
                        "both")
    links, paths = {}, {}
    for t in sec.tables("link"):
        n = t.integer("number", lo=0)
        if n in links:
            raise t.error("number", "a link number not listed before", repr(n))
        names = t.strings("joints")
        if not names or len(set(names)) != len(names):
            raise t.error("joints", "an array of different joint names", repr(names))
        for i, j in enumerate(names):
            t.check_name(f"joints[{i}]", j)
        links[n], paths[n] = tuple(names), t
        t.finish()
    sliders = []
    for t in sec.tables("slider", []):
        block, guide = t.integer("block", lo=0), t.integer("guide", lo=0)
        for key, n in (("block", block), ("guide", guide)):
            if n not in links and n != frame:
                raise t.error(key, f"a link of [[mobility.link]] or the frame {frame}", repr(n))
        if block == guide:
            raise t.error("guide", "a link other than the block", repr(guide))
        sliders.append(Slider(block, guide, "", 0.0, t.name("name", None)))
        t.finish()
    try:
        pairs = pairs_of_links(frame, links, sliders)
    except DrawingError as exc:
        where = next(t for n, t in paths.items() if exc.name in links[n])
        raise where.error("joints", "joints that each join two links or a link to the "
                          "frame", str(exc) + (" (a point on a link is a [[mechanism.point]])"
                                               if exc.lone else "")) from None
    joints = [JointSpec(j.kind, j.links, j.name) for j in pairs]
    return _mobility_problem(sec, joints, frame, local, redundant, "links")


def _drivers(sec: Section, joints: Sequence[JointSpec], frame: int,
             used: Collection[int]) -> Tuple[int, ...]:
    """``drivers = [1, ...]``: the driving links, each joined to the frame by one lower
    pair (optional: without it only the mobility is counted)."""
    raw = sec.raw("drivers", None)
    if raw is None:
        return ()
    if not isinstance(raw, list) or not raw or not all(
            isinstance(v, int) and not isinstance(v, bool) for v in raw) \
            or len(set(raw)) != len(raw):
        raise sec.error("drivers", "an array of different link numbers", repr(raw))
    for d in raw:
        if d == frame or d not in used or not any(
                j.kind in ("R", "P") and frame in j.links and d in j.links for j in joints):
            raise sec.error("drivers", f"moving links each joined to the frame {frame} by a "
                            f"lower pair", f"{raw} (link {d} is not)")
    if any(j.kind == "H" for j in joints):
        raise sec.error("drivers", "a mechanism of lower pairs for the structural analysis "
                        "(replace each higher pair by a link and two lower pairs first)",
                        repr(raw))
    return tuple(raw)


def _joints_from_kin(path: Path) -> Tuple[Tuple[JointSpec, ...], int, Tuple[int, ...]]:
    """Joints of a ``mechcli kin`` spec's linkage: its kinematic pairs, revolutes
    merged by point name.

    The pairs are the engine's (each element declares its own); a point where
    several revolutes meet becomes one compound hinge.
    """
    from mechcli.core.linkage.kinetostatics import topology
    from mechcli.spec.kin import load_kin_spec

    lk = load_kin_spec(path, ()).linkage
    topo = topology(lk)
    hinges, others = [], []
    # the spec's element order; a dyad's pairs to known points first
    def spec_order(pr: Pair) -> Tuple[int, bool]:
        made = lk.elements[pr.element].makes()[1]
        return pr.element, pr.i in made and pr.j in made

    for pr in sorted(topo.pairs, key=spec_order):
        if pr.kind == "R":
            if pr.point not in hinges:
                hinges.append(pr.point)
        else:
            name = getattr(lk.elements[pr.element], "name", None) or pr.point
            others.append(JointSpec("P", (pr.block, pr.guide), name))
    joints = [JointSpec("R", topo.links_at[p], p) for p in hinges]
    drivers = tuple(el.link for el in lk.drivers)
    return tuple(joints + others), lk.frame, drivers


def read_grashof_spec(path: Union[str, Path], overrides: Iterable[str] = ()) -> GrashofSpec:
    """Load and validate a ``mechcli grashof`` spec.

    Raises
    ------
    SpecError
        Any invalid, missing or unknown key (exit code 2).
    """
    root = load_spec(path, overrides)
    header = read_header(root, "grashof")
    present = [k for k in PROBLEMS if root.has(k)]
    if len(present) != 1:
        raise SpecError(root.file, "", "exactly one problem table: "
                        + ", ".join(f"[{k}]" for k in PROBLEMS),
                        "none" if not present else ", ".join(f"[{k}]" for k in present))
    kind = present[0]
    sec = root.table(kind)
    readers = {"fourbar": _read_fourbar, "slider_crank": _read_slider,
               "guide_bar": _read_guide, "fivebar": _read_fivebar, "rrrrp": _read_rrrrp}
    problem: object
    if kind == "mobility":
        problem = _read_mobility(sec, Path(path).resolve().parent)
    else:
        problem = readers[kind](sec)
    expected = read_expected(root)
    root.finish()
    return GrashofSpec(header, kind, problem, expected, Path(path))


def quick_spec(lengths_text: str, frame: Optional[int] = None, input_link: Optional[int] = None,
               offset: Optional[float] = None, units: str = "mm") -> GrashofSpec:
    """The spec of the file-less quick form ``--lengths 100,150,170,110``.

    Two lengths with ``--offset`` (or two lengths alone) make a slider-crank
    (crank, coupler), four a four-bar, five a 5R five-bar.
    """
    where = "--lengths"
    parts = [p.strip() for p in str(lengths_text).split(",")]
    if parts == [""]:
        parts = []
    vals = []
    for i, p in enumerate(parts):
        try:
            v = float(p)
        except ValueError:
            raise SpecError(where, f"lengths[{i}]", "a positive number", repr(p)) from None
        if not (v > 0) or v != v or v in (float("inf"),):
            raise SpecError(where, f"lengths[{i}]", "a positive finite number", repr(p))
        vals.append(v)
    scale = LENGTH_UNITS[units]
    header = Header(title="mechcli grashof --lengths " + ",".join(parts), unit=units,
                    scale=scale)
    m = [_check_length(where, f"lengths[{i}]", v, scale) for i, v in enumerate(vals)]
    if len(vals) == 2:
        for opt, val in (("--frame", frame), ("--input", input_link)):
            if val is not None:
                raise SpecError(where, opt, "no --frame/--input for a slider-crank "
                                "(crank, coupler[, --offset])", repr(val))
        off = 0.0 if offset is None else _check_length("--offset", "", float(offset), scale,
                                                        signed=True)
        prob = SliderCrankProblem(m[0], m[1], off, 1e-9)
        return GrashofSpec(header, "slider_crank", prob, {}, None)
    if offset is not None:
        raise SpecError(where, "--offset", "2 lengths (crank, coupler) with --offset",
                        f"{len(vals)} lengths")
    if len(vals) == 4:
        fr = 4 if frame is None else frame
        if not 1 <= fr <= 4:
            raise SpecError(where, "--frame", "a link number 1..4", repr(fr))
        nb: Tuple[int, ...] = ((fr % 4) + 1, ((fr + 2) % 4) + 1)
        inp = input_link if input_link is not None else (1 if 1 in nb else nb[0])
        if inp not in nb:
            raise SpecError(where, "--input", f"a link joined to the frame {fr}: "
                            f"{nb[0]} or {nb[1]}", repr(inp))
        return GrashofSpec(header, "fourbar", FourBarProblem(tuple(m), fr, inp, False, (), 1e-9),
                           {}, None)
    if len(vals) == 5:
        if input_link is not None:
            raise SpecError(where, "--input", "no --input for a five-bar (its inputs are the "
                            "two links joined to --frame)", repr(input_link))
        fr = 5 if frame is None else frame
        if not 1 <= fr <= 5:
            raise SpecError(where, "--frame", "a link number 1..5", repr(fr))
        nb = tuple(sorted(((fr % 5) + 1, ((fr + 3) % 5) + 1)))
        return GrashofSpec(header, "fivebar", FiveBarProblem(tuple(m), fr, nb, 1e-9), {}, None)
    raise SpecError(where, "lengths", "2 (slider-crank), 4 (four-bar) or 5 (five-bar) "
                    "comma-separated lengths", f"{len(vals)}")


@record
class BatchSpec:
    """Length sets from a CSV file (``--batch``), lengths in metres."""

    header: Header
    lengths: object         # ndarray (N, 4)
    frame: object           # ndarray (N,) of int
    input: object           # ndarray (N,) of int
    path: Path


def read_batch_csv(path: Union[str, Path], units: str = "mm") -> BatchSpec:
    """Read ``l1,l2,l3,l4[,frame,input]`` rows (an optional header line) from a CSV file.

    Raises
    ------
    SpecError
        Unreadable file, wrong column count, non-numeric or non-positive
        lengths, a frame or input that is not a link (the message names the row).
    """
    import numpy as np

    file = str(path)
    try:
        # utf-8-sig: spreadsheets save CSV with a byte-order mark
        text = Path(path).read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise SpecError(file, "", "an existing CSV file", "no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SpecError(file, "", "a readable UTF-8 CSV file", str(exc)) from None
    # (file line number, text) of the lines that hold data: error messages name file lines
    numbered = [(k, ln) for k, ln in enumerate(text.splitlines(), start=1)
                if ln.strip() and not ln.lstrip().startswith("#")]

    def is_number(cell: str) -> bool:
        try:
            float(cell)
        except ValueError:
            return False
        return True

    # a header line starts with a name (l1); a data row starts with a number
    first = numbered[0][1].split(",")[0].strip() if numbered else ""
    if first[:1].isalpha() and not is_number(first):
        head = [h.strip().lower() for h in numbered[0][1].split(",")]
        if head[:4] != ["l1", "l2", "l3", "l4"] or head[4:] not in ([], ["frame"],
                                                                    ["frame", "input"]):
            raise SpecError(file, "header", "l1,l2,l3,l4[,frame[,input]]",
                            repr(numbered[0][1]))
        numbered = numbered[1:]
    if not numbered:
        raise SpecError(file, "", "at least one row of lengths", "none")
    rows = [k for k, _ in numbered]
    lines = [ln for _, ln in numbered]
    ncol = lines[0].count(",") + 1
    if ncol not in (4, 5, 6):
        raise SpecError(file, f"row {rows[0]}", "4 to 6 comma-separated columns "
                        "(l1,l2,l3,l4[,frame[,input]])", f"{ncol} columns")
    try:
        data = np.array([ln.split(",") for ln in lines], dtype=float)
    except ValueError:
        for i, ln in enumerate(lines):
            cells = ln.split(",")
            if len(cells) != ncol:
                raise SpecError(file, f"row {rows[i]}", f"{ncol} columns",
                                f"{len(cells)}") from None
            for j, c in enumerate(cells):
                if not is_number(c):
                    raise SpecError(file, f"row {rows[i]}", "numbers",
                                    f"{c.strip()!r} in column {j + 1}") from None
        raise
    L = data[:, :4]
    bad = ~(np.isfinite(L) & (L > 0))
    if bad.any():
        i, j = map(int, np.argwhere(bad)[0])
        raise SpecError(file, f"row {rows[i]}", f"a positive length l{j + 1}",
                        repr(float(L[i, j])))
    frame = data[:, 4] if ncol >= 5 else np.full(len(L), 4.0)
    fr_ok = np.isin(frame, (1, 2, 3, 4))
    if not fr_ok.all():
        i = int(np.flatnonzero(~fr_ok)[0])
        raise SpecError(file, f"row {rows[i]}", "a frame link number 1..4",
                        repr(float(frame[i])))
    frame = frame.astype(int)
    nb1, nb2 = frame % 4 + 1, (frame + 2) % 4 + 1
    if ncol == 6:
        inp = data[:, 5]
        ok = (inp == nb1) | (inp == nb2)
        if not ok.all():
            i = int(np.flatnonzero(~ok)[0])
            raise SpecError(file, f"row {rows[i]}",
                            f"an input link joined to the frame {frame[i]}: {nb1[i]} or {nb2[i]}",
                            repr(float(inp[i])))
        inp = inp.astype(int)
    else:
        inp = np.where((nb1 == 1) | (nb2 == 1), 1, nb1)
    scale = LENGTH_UNITS[units]
    far = (L * scale < MIN_LENGTH) | (L * scale > MAX_LENGTH)
    if far.any():   # the range of _check_length, on the whole array
        i, j = map(int, np.argwhere(far)[0])
        _check_length(file, f"row {rows[i]}", float(L[i, j]), scale)
    header = Header(title=f"mechcli grashof --batch {file}", unit=units, scale=scale)
    return BatchSpec(header, L * scale, frame, inp, Path(path))
