"""Reading TOML problem files with strict, explainable validation.

``load_spec`` parses the file (``tomllib``, or ``tomli`` before Python 3.11),
applies ``--set KEY=VALUE`` overrides and returns the root :class:`Section`.
A :class:`Section` hands out typed values key by key and remembers which keys
were read; :meth:`Section.finish` rejects every key nobody asked for, with a
did-you-mean suggestion.  Overridden keys go through exactly the same checks.
"""

from __future__ import annotations

import math
import re
import sys
from typing import TYPE_CHECKING, Any, Collection, Dict, Iterable, List, Optional, Tuple, Union

from mechcli.spec.errors import SpecError, closest, slip

if TYPE_CHECKING:
    import os
    from types import ModuleType

    from mechcli.spec.schema import Recorder

REQUIRED = object()


def _toml() -> ModuleType:
    """``tomllib`` (``tomli`` before Python 3.11), imported on first use: the quick forms
    (``grashof --lengths``) read no file and skip its ~3 ms of import."""
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    return tomllib


def __getattr__(name: str) -> Any:
    # ``from mechcli.spec.reader import tomllib`` (spec/schema.py) still works
    if name == "tomllib":
        return _toml()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

#: the lengths mechcli accepts [m]: 1 nm to 1,000 km
MIN_LENGTH, MAX_LENGTH = 1e-9, 1e6
#: metres per declared length unit
LENGTH_UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254}

#: the longest name (a point, slide, load or joint name) mechcli accepts
NAME_MAX = 32
#: what a name looks like, as error messages and docs say it
NAME_RULE = (f"a name of 1 to {NAME_MAX} letters (any script: Latin, Greek, CJK), "
             "digits 0-9 or '_'")


def is_name(value: object) -> bool:
    """Is *value* a name: 1 to :data:`NAME_MAX` characters, each a Unicode letter,
    an ASCII digit or ``_``?

    Names become file names (``path_<name>.png``), CSV columns and JSON keys, so
    they hold no path separator, dot, comma, quote, space or control character.
    A leading digit is allowed: slide names such as ``23`` (block 2 on guide 3)
    are the book's.
    """
    return (isinstance(value, str) and 0 < len(value) <= NAME_MAX
            and all(c == "_" or "0" <= c <= "9" or c.isalpha() for c in value))


def _describe_name(value: object, limit: int = 40) -> str:
    """*value* for a message: a string escaped (one line) and cut after *limit* characters."""
    if not isinstance(value, str):
        return _describe(value)
    if value == "":
        return "'' (an empty string)"
    if len(value) <= limit:
        return f"{value!r} (a string)"
    return f"{value[:limit]!r}... (a string of {len(value):,} characters)"


def _describe(value: object) -> str:
    if isinstance(value, bool):
        return f"{str(value).lower()} (a boolean)"
    if isinstance(value, str):
        return f"'{value}' (a string)"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return f"an array of {len(value)}"
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return repr(value)


def _symbol(key: str) -> Optional[Tuple[str, str]]:
    """``(first letter, trailing digits)`` of a key such as ``l2`` or ``omega1``, or None
    when the key does not end in digits."""
    m = re.fullmatch(r"([^\W\d_]).*?(\d+)", str(key))
    return (m.group(1).lower(), m.group(2)) if m else None


def _same_symbol(name: str, candidates: Iterable[str]) -> List[str]:
    """``[candidate]`` when exactly one of *candidates* spells *name* out with the same
    first letter and the same link number (``lenght2``, ``length2``, ``len2`` for ``l2``),
    where :func:`difflib.get_close_matches` finds them too far apart; else ``[]``."""
    sym = _symbol(name)
    if sym is None:
        return []
    hits = [c for c in candidates if c != name and _symbol(c) == sym]
    return hits if len(hits) == 1 else []


#: a number written with a unit inside a string: ``"101.6 mm"``, ``"250 rpm"``, ``"30°"``
_WITH_UNIT = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*"
                        r"([^\d\s.,+\-\[\]{}][^\[\]{}]*?)\s*")
#: units of a speed in revolutions per minute, as written in a string
_RPM_UNITS = {"rpm", "r/min", "rev/min", "1/min", "min-1", "min^-1", "u/min", "转/分"}
_ANGLE_UNITS = {"deg", "degree", "degrees", "°", "rad", "radian", "radians"}
#: the keys that take a speed in rpm, beside one in rad/s (kin, force: n1; flywheel …)
_RPM_KEYS = ("n1", "n1_rpm", "n0_rpm", "n_end_rpm", "n_mean_rpm")


def _unit_words(sec: Section, name: str, value: object, length: bool) -> Optional[str]:
    """What a valid value looks like when *value* is a number with a unit inside a string
    (``"101.6 mm"``, ``"250 rpm"``): units are not written in values, so say how they are
    given (lengths in the file's ``units``, angles in degrees, a speed in rpm by its own
    key).  None when *value* is not such a string."""
    if not isinstance(value, str) or len(value) > 60:
        return None
    if re.fullmatch(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*", value):
        return f"a number, not a string: without the quotes ({name} = {value.strip()})"
    m = _WITH_UNIT.fullmatch(value)
    if m is None:
        return None
    number, unit = m.group(1), m.group(2).strip()
    low = unit.lower()
    plain = "a plain number, not a string with a unit"
    here = next((k for k, v in LENGTH_UNITS.items() if math.isclose(v, sec.unit)), "mm")
    if length or low in LENGTH_UNITS:
        words = f"{plain}: every length is in the file's units = \"{here}\" ({name} = "
        if low in LENGTH_UNITS and low != here:
            there = float(number) * LENGTH_UNITS[low] / LENGTH_UNITS[here]
            return words + (f"{there:.6g}, or {name} = {number} with units = \"{low}\" at the "
                            f"top of the file for every length)")
        return words + f"{number})"
    if low in _RPM_UNITS:
        if name in _RPM_KEYS or name.endswith("_rpm"):
            return f"{plain} ({name} is in rpm: {name} = {number})"
        alt = next((k for k in _RPM_KEYS if k in sec._known or k in sec._declared), None)
        if alt is not None:
            return f"{plain}: {name} is in rad/s (a speed in rpm is {alt} = {number} instead)"
        return (f"{plain}: {name} is in rad/s ({number} rpm is {name} = "
                f"{float(number) * math.pi / 30:.6g})")
    if low in _ANGLE_UNITS:
        deg = number if low[0] in "d°" else f"{math.degrees(float(number)):.6g}"
        return f"{plain}: angles are in degrees ({name} = {deg})"
    return (f"{plain} ({name} = {number} in the unit of the key, which `mechcli schema` and "
            f"the comments of `mechcli new` give)")


def _other_form_key(path: str, name: str) -> bool:
    """Is *name* a key that another form of the table at *path* takes (the shipped
    schemas: :func:`mechcli.spec.unknown.taken_by_another_form`)?"""
    from mechcli.spec.unknown import taken_by_another_form
    try:
        return taken_by_another_form(path, name)
    except Exception:   # noqa: BLE001 -- a hint never hides the error it words
        return False


def parse_override(file: str, text: str) -> Tuple[str, Any]:
    """Split ``KEY=VALUE``; VALUE in TOML syntax (bare words become strings)."""
    key, sep, raw = text.partition("=")
    key = key.strip()
    if not sep or not key or not re.fullmatch(r"[A-Za-z0-9_.\-]+", key):
        raise SpecError(file, "--set", "KEY=VALUE with a dotted key such as mechanism.l1=120",
                        f"'{text}'")
    raw = raw.strip()
    tomllib = _toml()
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_\-]*", raw):
            value = raw  # a bare word: treat as a string (branch=crossed)
        else:
            raise SpecError(file, key, "a TOML value after '=' (quote strings)",
                            f"'{raw}'") from None
    return key, value


def apply_override(file: str, data: Dict[str, Any], key: str, value: object) -> None:
    """Set ``data[a][b][c] = value`` for key ``a.b.c``; integers index arrays."""
    parts = key.split(".")
    node: Any = data
    for i, part in enumerate(parts[:-1]):
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                raise SpecError(file, ".".join(parts[: i + 1]),
                                f"an index below {len(node)}", f"'{part}'")
            node = node[int(part)]
            continue
        nxt = node.get(part)
        if nxt is None:
            nxt = node[part] = {}
        if not isinstance(nxt, (dict, list)):
            raise SpecError(file, ".".join(parts[: i + 1]), "a table", _describe(nxt))
        node = nxt
    last = parts[-1]
    if isinstance(node, list):
        if not last.isdigit() or int(last) >= len(node):
            raise SpecError(file, key, f"an index below {len(node)}", f"'{last}'")
        node[int(last)] = value
    else:
        node[last] = value


def load_spec(path: Union[str, os.PathLike], overrides: Iterable[str] = ()) -> Section:
    """Read a TOML problem file and apply ``--set`` overrides.

    Parameters
    ----------
    path : str or pathlib.Path
        The spec file.
    overrides : sequence of str
        ``KEY=VALUE`` strings (dotted keys, TOML values).

    Returns
    -------
    Section
        The root table.
    """
    file = str(path)
    if Section.recorder is not None and file == Section.recorder.file:
        return _recorded_root(file, overrides)
    try:
        with open(path, "rb") as fh:
            raw = fh.read()
    except FileNotFoundError:
        raise SpecError(file, "", "an existing TOML file", "no such file") from None
    except OSError as exc:
        raise SpecError(file, "", "a readable TOML file", exc.strerror or str(exc)) from None
    tomllib = _toml()
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise SpecError(file, "", "UTF-8 text", "undecodable bytes") from None
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(file, "", "valid TOML", f"a syntax error: {exc}") from None
    except RecursionError:
        raise SpecError(file, "", "TOML nested at most a few hundred tables or arrays deep",
                        "nesting too deep to read") from None
    overridden = set()
    for text in overrides:
        key, value = parse_override(file, text)
        apply_override(file, data, key, value)
        overridden.add(key)
    root = Section(data, file, "")
    root.overridden = frozenset(overridden)
    return root


def _recorded_root(file: str, overrides: Iterable[str]) -> Section:
    """The root of the in-memory spec that :mod:`mechcli.spec.schema` is probing."""
    import copy
    assert Section.recorder is not None   # (load_spec calls it only while recording)
    root = Section(copy.deepcopy(Section.recorder.data), file, "")
    root.overridden = frozenset()
    return root


class Section:
    """A TOML table being validated.

    Every accessor records the key as known; :meth:`finish` raises on the
    first unknown key.  Lengths are converted to metres with :meth:`length`.

    Parameters
    ----------
    data : dict
        The table.
    file : str
        Spec file name for messages.
    path : str
        Dotted path of this table (``""`` for the root).
    unit : float, optional
        Metres per length unit of the spec (inherited by sub-tables).
    """

    #: a recorder while :mod:`mechcli.spec.schema` runs a reader to learn its keys
    #: (``None`` otherwise: then every accessor costs one attribute test more)
    recorder: Optional[Recorder] = None

    def __init__(self, data: Dict[str, Any], file: str, path: str, unit: float = 1.0) -> None:
        self.data = data
        self.file = file
        self.path = path
        self.unit = unit
        self._known: set[str] = set()
        self._declared: set[str] = set()
        #: dotted keys set by --set (shared by sub-tables)
        self.overridden: frozenset[str] = frozenset()

    def declare(self, *names: str) -> None:
        """Name keys that a later accessor will read (so a missing key is not
        mistaken for a misspelling of one of them)."""
        self._declared.update(names)

    # -- helpers ---------------------------------------------------------
    def key(self, name: str) -> str:
        return f"{self.path}.{name}" if self.path else name

    def error(self, name: str, expected: str, got: str) -> SpecError:
        return SpecError(self.file, self.key(name), expected, got)

    def has(self, name: str) -> bool:
        if self.recorder is not None:
            self.recorder.key(self, name, "has", None)
        self._known.add(name)
        return name in self.data

    def _get(self, name: str, default: Any) -> Any:
        self._known.add(name)
        if name in self.data:
            return self.data[name]
        if default is REQUIRED:
            if self.recorder is not None:
                self.recorder.missing(self, name)
            # a missing key next to a misspelled one: report the misspelling
            import difflib
            strays = [k for k in self.data if k not in self._known and k not in self._declared]
            near = (difflib.get_close_matches(name, strays, n=1, cutoff=0.5)
                    or _same_symbol(name, strays))
            if near:
                # say both: the required key that is missing, and the stray that may be it
                raise SpecError(self.file, self.key(near[0]),
                                f"the required key '{name}' (missing)",
                                f"unknown key '{near[0]}'", name)
            raise SpecError(self.file, self.key(name), "this key (it is required)", "nothing")
        return default

    # -- typed accessors ---------------------------------------------------
    def number(self, name: str, default: Any = REQUIRED, *, positive: bool = False,
               nonneg: bool = False, lo: Optional[float] = None, hi: Optional[float] = None,
               expected: Optional[str] = None) -> Any:
        """A finite real number (int or float) with optional bounds."""
        if self.recorder is not None:
            self.recorder.key(self, name, "number", default, positive=positive, nonneg=nonneg,
                              lo=lo, hi=hi)
        return self._number(name, default, positive=positive, nonneg=nonneg, lo=lo, hi=hi,
                            expected=expected)

    def _number(self, name: str, default: Any = REQUIRED, *, positive: bool = False,
                nonneg: bool = False, lo: Optional[float] = None, hi: Optional[float] = None,
                expected: Optional[str] = None, length: bool = False) -> Any:
        value = self._get(name, default)
        if value is None or (value is default and default is not REQUIRED):
            return value
        want = expected or ("a positive number" if positive else
                            "a non-negative number" if nonneg else "a number")
        if lo is not None and hi is not None and not expected:
            want = f"a number in [{lo:g}, {hi:g}]"
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(name, _unit_words(self, name, value, length) or want,
                             _describe(value))
        value = float(value)
        if not math.isfinite(value):
            raise self.error(name, "a finite " + want.removeprefix("a "), _describe(value))
        if (positive and value <= 0) or (nonneg and value < 0) \
                or (lo is not None and value < lo) or (hi is not None and value > hi):
            raise self.error(name, want, _describe(value))
        return value

    def length(self, name: str, default: Any = REQUIRED, *, positive: bool = True,
               nonneg: bool = False) -> Any:
        """A length in the spec's unit, returned in metres.

        Lengths must lie within [MIN_LENGTH, MAX_LENGTH] metres (zero allowed
        with ``nonneg``): far outside, squares of lengths under- or overflow.
        """
        if self.recorder is not None:
            self.recorder.key(self, name, "number", default, positive=positive and not nonneg,
                              nonneg=nonneg)
        value = self._number(name, default, positive=positive and not nonneg, nonneg=nonneg,
                             expected=None, length=True)
        if value is None or (value is default and default is not REQUIRED):
            return value
        metres = value * self.unit
        # value, not metres, decides "zero": a tiny value whose metres underflow to 0 is refused
        if value != 0 and not MIN_LENGTH <= abs(metres) <= MAX_LENGTH:
            raise self.error(name, f"a length between {MIN_LENGTH:g} m and {MAX_LENGTH:g} m",
                             f"{value:g} ({metres:g} m)")
        return metres

    def coordinate(self, name: str, default: Any = REQUIRED) -> Any:
        """A signed length or coordinate in the spec's unit, returned in metres
        (|value| at most MAX_LENGTH metres)."""
        if self.recorder is not None:
            self.recorder.key(self, name, "number", default)
        lim = MAX_LENGTH / self.unit
        value = self._number(name, default, lo=-lim, hi=lim, length=True)
        if value is None or (value is default and default is not REQUIRED):
            return value
        return value * self.unit

    def integer(self, name: str, default: Any = REQUIRED, *, lo: Optional[int] = None,
                hi: Optional[int] = None) -> Any:
        if self.recorder is not None:
            self.recorder.key(self, name, "integer", default, lo=lo, hi=hi)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        want = "an integer" if lo is None else (
            f"an integer >= {lo}" if hi is None else f"an integer in [{lo}, {hi}]")
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(name, _unit_words(self, name, value, False) or want,
                             _describe(value))
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            raise self.error(name, want, _describe(value))
        return value

    def string(self, name: str, default: Any = REQUIRED, *,
               choices: Optional[Collection[str]] = None) -> Any:
        if self.recorder is not None:
            self.recorder.key(self, name, "string", default, choices=choices)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        if choices is not None:
            want = "one of " + ", ".join(f"'{c}'" for c in choices)
        else:
            want = "a string"
        if not isinstance(value, str):
            raise self.error(name, want, _describe(value))
        if choices is not None and value not in choices:
            raise SpecError(self.file, self.key(name), want, _describe(value),
                            closest(value, choices))
        return value

    def name(self, name: str, default: Any = REQUIRED) -> Any:
        """A name that becomes a file name, a CSV column or a JSON key: see
        :func:`is_name` (:data:`NAME_RULE`)."""
        if self.recorder is not None:
            self.recorder.key(self, name, "string", default)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        return self.check_name(name, value)

    def check_name(self, key: Optional[str], value: object) -> str:
        """*value* if it is a name (:func:`is_name`); else a :class:`SpecError` naming
        *key* (an array item such as ``points[0]``), or with *key* ``None`` naming this
        table, whose keys are the names (``[mechanism.ground]``)."""
        if is_name(value):
            return value   # type: ignore[return-value]  # (is_name: a str)
        if key is None:
            raise SpecError(self.file, self.path, "keys that are names: " + NAME_RULE,
                            _describe_name(value))
        raise self.error(key, NAME_RULE, _describe_name(value))

    def boolean(self, name: str, default: Any = REQUIRED) -> Any:
        if self.recorder is not None:
            self.recorder.key(self, name, "boolean", default)
        value = self._get(name, default)
        if not isinstance(value, bool):
            raise self.error(name, "true or false", _describe(value))
        return value

    def numbers(self, name: str, default: Any = REQUIRED, *, size: Optional[int] = None,
                positive: bool = False) -> Any:
        """An array of finite numbers, of exactly *size* items if given."""
        if self.recorder is not None:
            self.recorder.key(self, name, "numbers", default, size=size, positive=positive)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        want = (f"an array of {size} numbers" if size else "an array of numbers")
        if not isinstance(value, list) or (size is not None and len(value) != size) \
                or not value:
            raise self.error(name, want, _describe(value))
        out = []
        for i, item in enumerate(value):
            if isinstance(item, bool) or not isinstance(item, (int, float)) \
                    or not math.isfinite(item) or (positive and item <= 0):
                raise SpecError(self.file, self.key(f"{name}[{i}]"),
                                _unit_words(self, f"{name}[{i}]", item, False)
                                or ("a positive number" if positive else "a finite number"),
                                _describe(item))
            out.append(float(item))
        return out

    def rows(self, name: str, default: Any = REQUIRED, *, width: int = 2,
             count: Union[int, Tuple[int, Optional[int]], None] = None, lo: Optional[float] = None,
             hi: Optional[float] = None, row: Optional[str] = None) -> Any:
        """An array of rows of *width* finite numbers (points ``[x, y]``, poses
        ``[x, y, phi]``): ``count`` rows exactly (an int), or between ``count[0]``
        and ``count[1]``; *lo*/*hi* bound every number; *row* names a row's items
        in messages (``"[x, y, phi]"``).  Returns a list of lists, in the spec's
        units (the caller converts)."""
        if self.recorder is not None:
            self.recorder.key(self, name, "rows", default, width=width, count=count, lo=lo,
                              hi=hi)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        few, many = (count, count) if isinstance(count, int) else (count or (1, None))
        size = (f"{few}" if few == many else f"{few} to {many}" if many else f"at least {few}")
        want = f"an array of {size} rows {row or '[' + ', '.join(['n'] * width) + ']'}"
        if not isinstance(value, list) or len(value) < few \
                or (many is not None and len(value) > many):
            raise self.error(name, want, _describe(value))
        out, row_name = [], row or ""
        for i, items in enumerate(value):
            if not isinstance(items, list) or len(items) != width:
                raise SpecError(self.file, self.key(f"{name}[{i}]"),
                                f"an array of {width} numbers {row_name}".rstrip(),
                                _describe(items))
            for j, item in enumerate(items):
                if isinstance(item, bool) or not isinstance(item, (int, float)) \
                        or not math.isfinite(item) or (lo is not None and item < lo) \
                        or (hi is not None and item > hi):
                    bound = f" in [{lo:g}, {hi:g}]" if lo is not None and hi is not None else ""
                    raise SpecError(self.file, self.key(f"{name}[{i}][{j}]"),
                                    "a finite number" + bound, _describe(item))
            out.append([float(x) for x in items])
        return out

    def strings(self, name: str, default: Any = REQUIRED, *,
                choices: Optional[Collection[str]] = None) -> Any:
        if self.recorder is not None:
            self.recorder.key(self, name, "strings", default, choices=choices)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise self.error(name, "an array of strings", _describe(value))
        if choices is not None:
            for v in value:
                if v not in choices:
                    raise SpecError(self.file, self.key(name),
                                    "items from " + ", ".join(f"'{c}'" for c in choices),
                                    _describe(v), closest(v, choices))
        return list(value)

    def table(self, name: str, default: Any = REQUIRED) -> Any:
        """A sub-table as a :class:`Section` (``None`` if absent and optional)."""
        if self.recorder is not None:
            self.recorder.key(self, name, "table", default)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        if not isinstance(value, dict):
            raise self.error(name, "a table", _describe(value))
        sub = Section(value, self.file, self.key(name), self.unit)
        sub.overridden = self.overridden
        return sub

    def is_overridden(self, name: str) -> bool:
        """Was this key given by ``--set`` (rather than the file)?"""
        return self.key(name) in self.overridden

    def tables(self, name: str, default: Any = REQUIRED) -> Any:
        """An array of tables, as a list of :class:`Section`."""
        if self.recorder is not None:
            self.recorder.key(self, name, "tables", default)
        value = self._get(name, default)
        if value is default and default is not REQUIRED:
            return value
        if isinstance(value, dict):
            value = [value]
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise self.error(name, "an array of tables ([[...]])", _describe(value))
        out = [Section(v, self.file, f"{self.key(name)}.{i}", self.unit)
               for i, v in enumerate(value)]
        for sub in out:
            sub.overridden = self.overridden
        return out

    def raw(self, name: str, default: Any = REQUIRED) -> Any:
        """The untyped value (the caller validates it)."""
        if self.recorder is not None:
            self.recorder.key(self, name, "raw", default)
        return self._get(name, default)

    def keys(self) -> List[str]:
        if self.recorder is not None:
            self.recorder.freeform(self)
        return list(self.data)

    def finish(self) -> None:
        """Reject every key that no accessor asked for."""
        if self.recorder is not None:
            self.recorder.finished(self)
        for name in self.data:
            if name not in self._known:
                if name in self._declared or self._discriminated() and _other_form_key(
                        self.path, name):
                    raise self._other_form(name)
                hint = slip(name, self._known | self._declared) \
                    or closest(name, sorted(self._known)) \
                    or next(iter(_same_symbol(name, self._known)), None)
                raise SpecError(self.file, self.key(name),
                                "a known key" + (f" of [{self.path}]" if self.path else ""),
                                f"unknown key '{name}'", hint)

    def _discriminated(self) -> Optional[Tuple[str, str]]:
        """The ``(key, value)`` of this table's form (``type = "slider_crank"``, ``kind =
        "function"``), when the reader has read one; else None."""
        return next(((k, v) for k, v in self.data.items()
                     if k in ("type", "kind") and isinstance(v, str) and k in self._known),
                    None)

    def _other_form(self, name: str) -> SpecError:
        """The error for *name*, a key this table takes in another of its forms (``l3``
        of a four-bar in a slider-crank's ``[mechanism]``): "slider_crank has no l3",
        with the keys this form reads, and no did-you-mean of a different key."""
        kind = self._discriminated()
        keys = ", ".join(sorted(self._known))
        if kind is None:
            return SpecError(self.file, self.key(name),
                             f"a key of this form of [{self.path}] ({keys})",
                             f"'{name}', a key of another form")
        return SpecError(self.file, self.key(name),
                         f"a key of {kind[0]} = \"{kind[1]}\" ({keys})",
                         f"'{name}': {kind[1]} has no {name}")

    def set_unit_from(self, name: str = "units", default: Any = "mm") -> str:
        """Read the declared length unit and set it for this and later sub-tables."""
        unit = self.string(name, default, choices=list(LENGTH_UNITS))
        if unit not in LENGTH_UNITS:   # a default handed on from another spec (a base)
            raise SpecError(self.file, self.key(name),
                            "one of " + ", ".join(f"'{c}'" for c in LENGTH_UNITS),
                            repr(unit), closest(str(unit), list(LENGTH_UNITS)))
        self.unit = LENGTH_UNITS[unit]
        return unit
