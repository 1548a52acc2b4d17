"""JSON Schema of a command's spec, learnt from the spec reader itself.

There is no second, declarative list of keys: :func:`command_schema` runs the
command's own reader with :attr:`mechcli.spec.reader.Section.recorder` set, so
every typed accessor the reader calls (``number``, ``length``, ``string(choices=…)``,
``tables`` …) records the table, the key, its type, bounds, choices and default.
The reader runs over *probe* specs that exercise its branches:

* the seeds: the configs of the command (``configs/`` next to the package, in a
  checkout) and the package templates ``mechcli/templates/<command>.toml`` and
  ``<command>.<type>.toml`` if any, or else a spec holding only ``command``;
* for every choice key seen (``mechanism.type``, a dyad's ``type``, ``contact``…),
  the spec with each other choice;
* for every optional table or array of tables not in the spec, the spec with an
  empty one; for every untyped key (``has``/``raw``), the spec with a value of each
  JSON type (a value the reader rejects at that key is not in the schema);
* whenever the reader stops at a missing required key, the spec with a value that
  the accessor accepts, and the reader runs again.

The records are merged into JSON Schema (draft-07; 2020-12 tools read it
alike): every table has ``additionalProperties: false`` except the free-form
ones the reader iterates (``[expected]``, ``[mechanism.ground]``), whose values
share one schema.  Keys
that depend on a discriminator are merged as a union of properties; a key is
required when every complete reading of its table required it.  Every key then gets
its ``description`` from the catalogue that also writes the key comments of ``mechcli
new``'s templates (:mod:`mechcli.spec.keydocs`).
"""

from __future__ import annotations

import copy
import json
import warnings
from pathlib import Path
from typing import (
    Any,
    Callable,
    Collection,
    Dict,
    Iterable,
    List,
    Optional,
    Sequence,
    Set,
    Tuple,
    Union,
)

from mechcli.spec.errors import SpecError
from mechcli.spec.reader import REQUIRED, Section

COMMANDS = ("kin", "force", "grashof", "cam", "gear", "synth", "flywheel", "optimize")
PROBE_FILE = "<mechcli-schema-probe>.toml"
#: most reader runs per command (each takes well under a millisecond to a few ms)
MAX_RUNS = 3000
#: values tried for an untyped key, one per JSON type
#: seeds a mutation (a choice, a value of an untyped key) is applied to, at most
TRIES = 3
CANDIDATES: tuple = (1, 1.5, "A", True, [1, 2], [1.5, 2.5], ["A", "B"], {})
_JSON_TYPE = {bool: "boolean", int: "integer", float: "number", str: "string", list: "array",
              dict: "object"}
#: draft-07: the newest draft Taplo (Even Better TOML) and most editors validate with; the
#: keywords used here mean the same in draft 2020-12
DRAFT = "http://json-schema.org/draft-07/schema#"


def _json_type(value: object) -> str:
    return _JSON_TYPE.get(type(value), "string")


class Recorder:
    """Collects what the accessors of :class:`Section` see during the probe runs."""

    #: the key each run was refused at ("" the whole file, None refused by the core)
    errors: Dict[int, Optional[str]]
    #: the runs read without error
    ok: Set[int]

    def __init__(self) -> None:
        self.file = PROBE_FILE
        self.data: Any = None
        self.run = -1
        #: (run, path, key, kind, default, present value type, opts)
        self.events: List[tuple] = []
        self.finishes: Set[tuple] = set()  # (run, path)
        self.free: Set[Tuple[str, ...]] = set()      # paths of free-form tables
        self.last_missing: Optional[tuple] = None

    @staticmethod
    def _parts(sec: Section) -> Tuple[str, ...]:
        return tuple(sec.path.split(".")) if sec.path else ()

    def key(self, sec: Section, name: str, kind: str, default: Any, **opts: Any) -> None:
        if sec.file != self.file:
            return
        value = sec.data.get(name, None) if isinstance(sec.data, dict) else None
        present = name in sec.data
        self.events.append((self.run, self._parts(sec), name, kind,
                            REQUIRED if default is REQUIRED else default,
                            _json_type(value) if present else None, opts))

    def missing(self, sec: Section, name: str) -> None:
        if sec.file == self.file:
            kind, opts = "raw", {}
            for ev in reversed(self.events):
                if ev[0] == self.run and ev[1] == self._parts(sec) and ev[2] == name:
                    kind, opts = ev[3], ev[6]
                    break
            self.last_missing = (self._parts(sec), name, kind, opts)

    def freeform(self, sec: Section) -> None:
        if sec.file == self.file and sec.path:
            self.free.add(self._parts(sec))

    def finished(self, sec: Section) -> None:
        if sec.file == self.file:
            self.finishes.add((self.run, self._parts(sec)))


# -- running a reader -----------------------------------------------------------------
def _reader(command: str) -> Callable[[str], Any]:
    if command == "kin":
        import functools

        from mechcli.spec.kin import load_kin_spec
        return functools.partial(load_kin_spec, stream=True)  # as `mechcli kin` reads it
    if command == "force":
        from mechcli.spec.force import load_force_spec
        return load_force_spec
    if command == "gear":
        from mechcli.spec.gear import read_gear_spec
        return read_gear_spec
    if command == "grashof":
        from mechcli.spec.grashof import read_grashof_spec
        return read_grashof_spec
    if command == "synth":
        from mechcli.spec.synth import read_synth_spec
        return read_synth_spec
    if command == "flywheel":
        from mechcli.spec.flywheel import read_flywheel_spec
        return read_flywheel_spec
    if command == "optimize":
        from mechcli.spec.optimize import read_optimize_spec
        return read_optimize_spec
    if command == "cam":
        from mechcli.spec.cam import read_cam_spec
        from mechcli.spec.reader import load_spec
        return lambda path: read_cam_spec(load_spec(path))
    raise KeyError(command)


def _node(data: Any, parts: Iterable[str], create: bool = False) -> Any:
    node = data
    for part in parts:
        if isinstance(node, list):
            node = node[int(part)]
        else:
            if part not in node and create:
                node[part] = {}
            node = node[part]
    return node


def _synths(kind: str, opts: Dict[str, Any], node: Any,
            avoid: Collection[Any] = frozenset()) -> list:
    """Values the accessor *kind* accepts (bounds and choices respected), best first.

    A free string takes the strings of its table first (a point name already
    used there is likelier to be one the reader knows).
    """
    lo, hi = opts.get("lo"), opts.get("hi")
    if kind == "number":
        out = []
        for v in (1.0, 2.0, 10.0, 0.5, 0.0, -1.0, 100.0):
            if opts.get("positive") and v <= 0 or opts.get("nonneg") and v < 0:
                continue
            if (lo is None or v >= lo) and (hi is None or v <= hi):
                out.append(v)
        return out or [lo if lo is not None else hi]
    if kind == "integer":
        base = lo if lo is not None else 1
        return [v for v in (max(base, 1), base, base + 1, base + 2, base + 3)
                if hi is None or v <= hi][:4] or [hi]
    if kind == "string":
        if opts.get("choices"):
            return list(opts["choices"])
        near = [v for v in (node.values() if isinstance(node, dict) else ())
                if isinstance(v, str) and v not in avoid]
        return list(dict.fromkeys(near + ["A", "B"]))[:4]
    if kind == "boolean":
        return [False, True]
    if kind == "numbers":
        n = opts.get("size") or 2
        return [[1.0 + i for i in range(n)], [1.0] * n]
    if kind == "strings":
        return [[opts["choices"][0]]] if opts.get("choices") else [["A", "B"]]
    if kind == "rows":
        count = opts.get("count") or 1
        n = count if isinstance(count, int) else count[0]
        w = opts.get("width") or 2
        return [[[float(i + 1), float(i * i)] + [0.0] * (w - 2) for i in range(n)]]
    if kind == "table":
        return [{}]
    if kind == "tables":
        return [[{}]]
    return list(CANDIDATES)  # raw/has: one value of each JSON type


#: probe specs for branches that the configs and templates do not reach (the
#: synthetic values cannot build a valid linkage): a slider-driven linkage, whose
#: ``[input]`` reads ``v1``/``a1`` and unbounded ``start``/``stop``
_SLIDER = {"mechanism": {"type": "general", "frame": 2, "ground": {"O": [0, 0]},
                         "driver": [{"type": "slider", "link": 1, "origin": "O",
                                     "point": "B"}]},
           "input": {"start": 0, "stop": 10, "v1": 1}}
#: a linkage by its joints with a slider (the configs' joints forms have none): the
#: fire ladder of 习题 2-2, its cylinder drawn by `toward` and by `angle`, driving it
_LADDER: dict = {"units": "m", "mechanism": {
    "type": "joints", "frame": 1, "joints": {"A": [0, 0.8], "B": [0.4, 0.6], "C": [0.8, 0]},
    "link": [{"number": 2, "joints": ["A", "B"]}, {"number": 3, "joints": ["C"]},
             {"number": 4, "joints": ["B"]}],
    "slider": [{"block": 4, "guide": 3, "through": "B", "toward": "C", "name": "cyl"}],
    "driver": [{"type": "crank", "link": 2, "pivot": "A", "actuator": "cyl"}]}}
_LADDER_ANGLE = copy.deepcopy(_LADDER)
_LADDER_ANGLE["mechanism"]["slider"][0].pop("toward")
_LADDER_ANGLE["mechanism"]["slider"][0]["angle"] = -56.309932474020215  # B -> C
PROBES = {"kin": [_SLIDER, _LADDER, _LADDER_ANGLE], "force": [_SLIDER, _LADDER, _LADDER_ANGLE],
          "flywheel": [_LADDER], "optimize": [_LADDER],
          # grashof's [mobility] by the links' joints, with a slider (no config has one)
          "grashof": [{"mobility": {
              "frame": 4, "drivers": [1],
              "link": [{"number": 1, "joints": ["A", "B"]}, {"number": 2, "joints": ["B", "C"]},
                       {"number": 3, "joints": ["C"]}],
              "slider": [{"block": 3, "guide": 4, "name": "C"}]}}]}


def _engine(form: Any) -> Dict[str, Any]:
    """A slider-crank engine (stroke 200 mm) whose gas load has *form* on both sides."""
    return {"units": "mm", "mechanism": {"type": "slider_crank", "l1": 100, "l2": 400},
            "input": {"omega1": 100, "step": 10},
            "load": [{"name": "gas", "link": 3, "bore": 100, "rod": 20, "pressure_unit": "bar",
                      "pressure": form, "crank_side_pressure": copy.deepcopy(form)}]}


#: probe specs run after the configs (their own runs, not their mutations, are what
#: counts: the runs of a command are capped at MAX_RUNS): every form of a pressure table,
#: which the configs use on one side or the other only
LATE_PROBES = {"force": [_engine(f) for f in (
    1.0, {"angle": [0, 360], "value": [1, 1]}, {"fraction": [0, 1], "value": [1, 2]},
    {"x": [0, 200], "value": [1, 2]}, {"fraction": [0, 1], "strokes": [[1, 1], [0, 0]]},
    {"x": [0, 200], "strokes": [[1, 1], [0, 0], [0, 0], [1, 1]]})]}


#: the commands that read kin's [mechanism] table (the linkage forms)
_SHARED_MECHANISM = ("force", "flywheel", "optimize")


def _key_paths(node: Any, prefix: str = "") -> frozenset:
    """The dotted key paths of a table (lists of tables merged): its shape, not its values."""
    out: set = set()
    items = node if isinstance(node, list) else [node]
    for item in items:
        if isinstance(item, dict):
            for k, v in item.items():
                out.add(prefix + k)
                if isinstance(v, (dict, list)) and k != "joints":
                    out |= _key_paths(v, prefix + k + ".")
    return frozenset(out)


def _seeds(command: str,
           configs: Union[str, Path, None] = None) -> List[Tuple[Dict[str, Any], Optional[str]]]:
    seeds: List[Tuple[Dict[str, Any], Optional[str]]] = [
        (dict(copy.deepcopy(p), command=command), None) for p in PROBES.get(command, ())]
    here = Path(__file__).resolve().parent.parent
    template = here / "templates" / f"{command}.toml"
    files = [template] if template.is_file() else []
    files += sorted((here / "templates").glob(f"{command}.*.toml"))   # its other types
    files += sorted((here / "templates" / "examples").glob("*.toml"))
    configs = Path(configs) if configs is not None else here.parent / "configs"
    if configs.is_dir():
        files += sorted(configs.rglob("*.toml"))
    from mechcli.spec.reader import tomllib
    shapes: set = set()
    for f in files:
        try:
            data = tomllib.loads(f.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
            continue
        if data.get("command") == command or (f == template and "command" not in data):
            data["command"] = command
            seeds.append((data, str(f.parent)))
        elif (command in _SHARED_MECHANISM and data.get("command") == "kin"
              and isinstance(data.get("mechanism"), dict)
              and data["mechanism"].get("type") == "joints"
              and _key_paths(data["mechanism"]) not in shapes):
            # the joints form is read by the same reader for every command that moves a
            # linkage: learnt from kin's examples too (its keys, not its other tables;
            # one example per set of keys, so the run budget reaches the late probes)
            shapes.add(_key_paths(data["mechanism"]))
            seeds.append(({"command": command, "units": data.get("units", "mm"),
                           "mechanism": data["mechanism"]}, str(f.parent)))
    seeds += [(dict(copy.deepcopy(p), command=command), None)
              for p in LATE_PROBES.get(command, ())]
    seeds.append(({"command": command}, None))
    return seeds


def _refill(filled: Dict[str, Any], err: Optional[str]) -> Optional[str]:
    """The filled key to try another value of, after an error at *err* (or None)."""
    if not err:
        return None
    if err not in filled:
        table = err.rpartition(".")[0]
        same = [k for k in filled if k.rpartition(".")[0] == table]
        if not same:
            return None
        err = same[-1]
    return err if filled[err][3] + 1 < len(filled[err][2]) else None


#: a probe waiting in the queue: (spec data, depth of mutation, the (parts, name) just
#: set or None, the keys filled in {dotted: (parts, name, values, index)} or None, folder)
_Probe = Tuple[Dict[str, Any], int, Optional[Tuple[Tuple[str, ...], str]],
               Optional[Dict[str, Any]], Optional[str]]


def explore(command: str, extra_seeds: Iterable[dict] = (),
            configs: Union[str, Path, None] = None) -> Recorder:
    """Run *command*'s reader over the probe specs; return the :class:`Recorder`.

    Each probe is read once (:func:`_probe`); what it refused is retried with another
    value first (:func:`_retries`), then every key it read is varied
    (:func:`_mutations`) up to three levels deep."""
    read = _reader(command)
    rec = Recorder()
    queue: list[_Probe] = [(copy.deepcopy(s), 0, None, None, d) for s, d in
                           [(s, None) for s in extra_seeds] + _seeds(command, configs)]
    seen: set[str] = set()
    tried: dict[tuple, int] = {}
    rec.errors = {}
    rec.ok = set()
    old = Section.recorder
    Section.recorder = rec
    try:
        while queue and rec.run < MAX_RUNS:
            data, depth, mutated, filled, folder = queue.pop(0)
            sig = json.dumps(data, sort_keys=True, default=str)
            if sig in seen:
                continue
            seen.add(sig)
            start, choices = _probe(rec, read, data, folder)
            queue[:0] = _retries(rec, data, start, choices, (depth, mutated, filled, folder))
            if depth >= 3:
                continue
            queue.extend(_mutations(rec, data, start, tried, depth, folder))
    finally:
        Section.recorder = old
    return rec


def _probe(rec: Recorder, read: Callable[[str], Any], data: dict,
           folder: Optional[str]) -> tuple[int, set]:
    """Read *data* as the spec file once, recording its keys and whether (and at which
    key) it was refused; ``(index of its first event, the choices seen just before)``."""
    rec.run += 1
    rec.data, rec.last_missing = data, None
    # in the seed's folder, so that a path in the spec (mobility.kin) resolves
    rec.file = str(Path(folder) / PROBE_FILE) if folder else PROBE_FILE
    start = len(rec.events)
    choices = {c for e in rec.events[-200:] for c in (e[6].get("choices") or ())}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            read(rec.file)
        rec.ok.add(rec.run)
    except SpecError as exc:
        rec.errors[rec.run] = exc.key or ""
    except Exception:  # noqa: BLE001  (a probe the core refuses: records stand)
        rec.errors[rec.run] = None
    return start, choices


def _retries(rec: Recorder, data: dict, start: int, choices: set,
             state: tuple) -> list[_Probe]:
    """The probes to read next after *data* (*state*: its depth, mutated, filled and
    folder): a missing key filled in, a refused filled-in value replaced by the next, a
    refused mutation tried without each sibling that may exclude it."""
    depth, mutated, filled, folder = state
    front: list[_Probe] = []
    err = rec.errors.get(rec.run)
    if rec.last_missing is not None:
        parts, name, kind, opts = rec.last_missing
        try:
            node = _node(data, parts)
        except (KeyError, IndexError, TypeError, ValueError):
            node = {}
        values = _synths(kind, opts, node, choices)
        new = copy.deepcopy(data)
        _node(new, parts, create=True)[name] = copy.deepcopy(values[0])
        fills = dict(filled or {})
        fills[".".join(parts + (name,))] = (parts, name, values, 0)
        front.append((new, depth, mutated, fills, folder))
    elif filled and _refill(filled, err):
        # a value filled in was refused (stop <= start, r0 <= e, no such point),
        # or a key of its table was refused with it: the next value
        err = _refill(filled, err)
        parts, name, values, i = filled[err]
        new = copy.deepcopy(data)
        _node(new, parts)[name] = copy.deepcopy(values[i + 1])
        fills = dict(filled)
        fills[err] = (parts, name, values, i + 1)
        front.append((new, depth, mutated, fills, folder))
    if mutated is not None and err and err.startswith(".".join(mutated[0]) + "."):
        # refused at the key just set, or at a sibling that excludes the new value
        # (step or points, tol or rtol, a PRP dyad's branch): try again without
        # the sibling (each optional one in turn)
        parts, name = mutated[0], mutated[1]
        node = _node(data, parts)
        here = ".".join(parts + (name,))
        for e in rec.events[start:]:
            sib = ".".join(parts + (e[2],))
            if e[1] == parts and e[2] != name and e[2] in node \
                    and (err == sib or (err == here and e[4] is not REQUIRED)):
                alt = copy.deepcopy(data)
                del _node(alt, parts)[e[2]]
                front.append((alt, depth, mutated, filled, folder))
    return front


def _mutations(rec: Recorder, data: dict, start: int, tried: dict[tuple, int],
               depth: int, folder: Optional[str]) -> list[_Probe]:
    """The probes one level deeper: every key the last read asked for set to each of its
    choices (a string), a synthesised table or each candidate value (``has``, ``raw``),
    at most :data:`TRIES` times per folded key and value."""
    out: list[_Probe] = []
    for ev in rec.events[start:]:
        _, parts, name, kind, default, present, opts = ev
        fold = _fold(parts, rec.free)
        muts: list = []
        if kind == "string" and opts.get("choices"):
            muts = [c for c in opts["choices"]]
        elif kind in ("table", "tables") and present is None:
            muts = _synths(kind, opts, {})
        elif kind in ("has", "raw"):
            muts = list(CANDIDATES)
        for v in muts:
            tag = (fold, name, json.dumps(v))
            if tried.get(tag, 0) >= TRIES:
                continue
            tried[tag] = tried.get(tag, 0) + 1
            new = copy.deepcopy(data)
            try:
                _node(new, parts)[name] = copy.deepcopy(v)
            except (KeyError, IndexError, TypeError, ValueError):
                continue
            out.append((new, depth + 1, (parts, name), None, folder))
            if kind == "has" and present is None and isinstance(v, dict):
                # mutually exclusive tables (gear/grashof problem tables)
                alt = copy.deepcopy(new)
                node = _node(alt, parts)
                for e in rec.events[start:]:
                    if e[1] == parts and e[3] == "has" and e[2] != name \
                            and isinstance(node.get(e[2]), dict):
                        del node[e[2]]
                out.append((alt, depth + 1, None, None, folder))
    return out


# -- building the schema --------------------------------------------------------------
def _fold(parts: Sequence[str], free: Collection[Tuple[str, ...]]) -> Tuple[str, ...]:
    out = []
    for i, part in enumerate(parts):
        if tuple(parts[:i]) in free:
            out.append("*")
        elif part.isdigit():
            out.append("[]")
        else:
            out.append(part)
    return tuple(out)


def _fragment(kind: str, default: Any, opts: Dict[str, Any]) -> Dict[str, Any]:
    frag: Dict[str, Any] = {}
    if kind in ("number", "integer"):
        frag["type"] = kind
        if opts.get("positive"):
            frag["exclusiveMinimum"] = 0
        if opts.get("nonneg"):
            frag["minimum"] = 0
        for word, bound in (("lo", "minimum"), ("hi", "maximum")):
            if opts.get(word) is not None:
                frag[bound] = opts[word]
    elif kind == "string":
        frag["type"] = "string"
        if opts.get("choices"):
            frag["enum"] = list(opts["choices"])
    elif kind == "boolean":
        frag["type"] = "boolean"
    elif kind == "numbers":
        item: Dict[str, Any] = {"type": "number"}
        if opts.get("positive"):
            item["exclusiveMinimum"] = 0
        frag.update(type="array", items=item, minItems=opts.get("size") or 1)
        if opts.get("size"):
            frag["maxItems"] = opts["size"]
    elif kind == "rows":
        count = opts.get("count")
        few, many = (count, count) if isinstance(count, int) else (count or (1, None))
        num: Dict[str, Any] = {"type": "number"}
        for word, bound in (("lo", "minimum"), ("hi", "maximum")):
            if opts.get(word) is not None:
                num[bound] = opts[word]
        w = opts.get("width") or 2
        frag.update(type="array", minItems=few,
                    items={"type": "array", "items": num, "minItems": w, "maxItems": w})
        if many is not None:
            frag["maxItems"] = many
    elif kind == "strings":
        item = {"type": "string"}
        if opts.get("choices"):
            item["enum"] = list(opts["choices"])
        frag.update(type="array", items=item)
    if frag and default is not REQUIRED and default is not None \
            and isinstance(default, (bool, int, float, str, list)) \
            and not str(default).endswith(PROBE_FILE):
        frag["default"] = default
    return frag


def _merge(frags: List[Dict[str, Any]]) -> Dict[str, Any]:
    """One schema for several accessor records of a key (union when they differ)."""
    unique = []
    for f in frags:
        if f not in unique:
            unique.append(f)
    if len(unique) <= 1:
        return dict(unique[0]) if unique else {}
    bare = []
    for f in unique:
        g = {k: v for k, v in f.items() if k != "default"}
        if g not in bare:
            bare.append(g)
    defaults = {json.dumps(f.get("default")) for f in unique}
    types = {g.get("type") for g in bare}
    if len(types) == 1 and types <= {"number", "integer"} and all(
            set(g) <= {"type", "minimum", "maximum", "exclusiveMinimum"} for g in bare):
        # the same number read with other bounds in other branches: the loosest bounds
        loose: Dict[str, Any] = {"type": bare[0]["type"]}
        lows = [g.get("minimum", g.get("exclusiveMinimum")) for g in bare]
        if None not in lows:
            low = min(v for v in lows if v is not None)   # (none is: typed for mypy)
            strict = all(g.get("exclusiveMinimum") == low for g in bare if
                         g.get("minimum", g.get("exclusiveMinimum")) == low)
            loose["exclusiveMinimum" if strict else "minimum"] = low
        highs = [g.get("maximum") for g in bare]
        if None not in highs:
            loose["maximum"] = max(h for h in highs if h is not None)
        bare = [loose]
    if len(bare) == 1:
        out = dict(bare[0])
        if len(defaults) == 1 and "default" in unique[0]:
            out["default"] = unique[0]["default"]
        return out
    return {"anyOf": bare}


def _covered(json_type: str, frags: Iterable[Dict[str, Any]]) -> bool:
    for f in frags:
        t = f.get("type")
        if t == json_type or (t == "number" and json_type == "integer"):
            return True
        if t == json_type == "array" or (t is None and "anyOf" not in f and f):
            return True
    return False


class _Builder:
    def __init__(self, rec: Recorder) -> None:
        self.rec = rec
        #: folded table path -> key -> list of events
        self.keys: Dict[Tuple[str, ...], Dict[str, List[tuple]]] = {}
        #: folded table path -> {(run, concrete path)}
        self.inst: Dict[Tuple[str, ...], Set[tuple]] = {}
        for ev in rec.events:
            run, parts, name = ev[0], ev[1], ev[2]
            fold = _fold(parts, rec.free)
            self.keys.setdefault(fold, {}).setdefault(name, []).append(ev)
            self.inst.setdefault(fold, set()).add((run, parts))
        self.free = {_fold(p, rec.free) for p in rec.free}

    def _rejected(self, ev: tuple) -> bool:
        """Did the run of *ev* fail at this very key (the value was refused)?"""
        err = self.rec.errors.get(ev[0])
        if not err:
            return False
        here = ".".join(ev[1] + (ev[2],))
        return err == here or err.startswith(here + "[") or err.startswith(here + ".")

    def value_schema(self, fold: Tuple[str, ...], name: str, events: List[tuple]) -> Dict[str, Any]:
        frags = [_fragment(e[3], e[4], e[6]) for e in events if e[3] not in ("has", "raw")]
        frags = [f for f in frags if f]
        kinds = {e[3] for e in events}
        child = fold + (name,)
        alts = []
        if "tables" in kinds or (child + ("[]",)) in self.keys:
            alts.append({"type": "array", "items": self.table(child + ("[]",))})
        if "table" in kinds or child in self.keys or child in self.free:
            alts.append(self.table(child))
        if frags:
            merged = _merge(frags)
            alts.extend(merged["anyOf"] if "anyOf" in merged else [merged])
        seen = sorted({e[5] for e in events if e[3] in ("has", "raw") and e[5]
                       and not self._rejected(e)})
        covered = alts
        extra = [t for t in seen if not _covered(t, covered)]
        if "integer" in extra and "number" in extra:
            extra.remove("integer")
        alts += [{"type": t} for t in extra if not (t == "object" and alts)]
        if not alts or len(extra) >= 5:
            return {}  # anything goes (the reader takes any value: description, note)
        return alts[0] if len(alts) == 1 else {"anyOf": alts}

    def table(self, fold: Tuple[str, ...]) -> Dict[str, Any]:
        out: Dict[str, Any] = {"type": "object"}
        if fold in self.free:
            evs = [e for es in self.keys.get(fold, {}).values() for e in es]
            out["additionalProperties"] = self.value_schema(fold, "*", evs) if evs else True
            return out
        props, required = {}, []
        complete = [(r, p) for r, p in self.inst.get(fold, ()) if (r, p) in self.rec.finishes]
        for name, evs in sorted(self.keys.get(fold, {}).items()):
            props[name] = self.value_schema(fold, name, evs)
            if complete and all(any(e[0] == r and e[1] == p and e[4] is REQUIRED
                                    and e[3] != "has" for e in evs) for r, p in complete):
                required.append(name)
        out["properties"] = props
        if required:
            out["required"] = required
        out["additionalProperties"] = False
        return out


def command_schema(command: str, extra_seeds: Iterable[Dict[str, Any]] = (),
                   configs: Union[str, Path, None] = None) -> Dict[str, Any]:
    """The JSON Schema (a dict) of ``mechcli COMMAND``'s spec, learnt from the reader.

    Parameters
    ----------
    command : str
        One of :data:`COMMANDS`.
    extra_seeds : sequence of dict
        More specs (parsed TOML) to run the reader over.
    configs : path, optional
        A folder of configs to seed from (default: ``configs/`` beside the
        package, in a checkout).  The shipped schemas (:func:`shipped_schema`)
        are learnt with the checkout's ``configs/``.
    """
    rec = explore(command, extra_seeds, configs)
    schema = _Builder(rec).table(())
    out: Dict[str, Any] = {"$schema": DRAFT,
           "title": f"mechcli {command} spec",
           "description": f"A problem file for `mechcli {command}` (generated by "
                          f"`mechcli schema {command}` from the spec reader)."}
    out.update(schema)
    props = out.get("properties", {})
    if "command" in props:
        props["command"] = {"const": command, "type": "string"}
    # every key's meaning, from the catalogue the templates' comments come from
    from mechcli.spec.keydocs import describe_schema
    describe_schema(out, command)
    return out


#: where the schemas learnt in the checkout are shipped (package data)
SHIPPED = Path(__file__).resolve().parent.parent / "schemas"


def shipped_schema_text(command: str) -> str:
    """The shipped schema of ``command`` as JSON text: learnt by :func:`command_schema`
    in the checkout (with every config as a seed) and kept equal to it by
    ``tests/cli/test_schema.py``, so an installed mechcli prints the same schema
    without the configs and without running the reader."""
    return (SHIPPED / f"{command}.json").read_text(encoding="utf-8")


def schema_text(schema: Dict[str, Any]) -> str:
    """The canonical JSON text of a schema (what is shipped and printed)."""
    return json.dumps(schema, indent=2, ensure_ascii=False) + "\n"
