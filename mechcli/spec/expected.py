"""What ``[expected]`` means: one implementation for ``mechcli check`` and the tests.

Each key of a spec's ``[expected]`` table names a result of the run (a key of
``--json`` ``"results"``, or a quoted dotted path into nested results such as
``"cases.0.l1"``, 0-based like the JSON) and gives the value it must have:

* a number: it holds within the tolerance the spec gives
  (``{ value = …, tol = … }``, or a relative ``{ value = …, rtol = … }``;
  ``rel`` is the older spelling of ``rtol``), otherwise within half a unit of
  the last digit **as written in the TOML text** (``0.5454`` -> 5e-5,
  ``1.2300`` -> 5e-5, ``1e-3`` -> 5e-4, ``120`` -> 0.5).  tomllib keeps no
  digits, so the literal is read from the file's ``[expected]`` lines (or
  from the ``--set expected.KEY=...`` text that gave the value);
* a string or a boolean: it holds when equal;
* an array: element by element against an array result of the same length.

:func:`read_expected` validates the table (a wrong type or a tolerance <= 0
is a :class:`~mechcli.spec.errors.SpecError`, exit 2); :func:`compare` gives,
per key, whether it held, the expected and obtained values, the tolerance and
the deviation in units of the tolerance.
"""

from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING, Any, Dict, Iterable, List, Optional, Tuple, Union

from mechcli.core.records import record
from mechcli.spec.errors import SpecError, closest
from mechcli.spec.reader import load_spec

if TYPE_CHECKING:
    import os

    from typing_extensions import TypeGuard

    from mechcli.spec.reader import Section

#: the text of a number literal, or of each element of a one-line array
LiteralText = Union[str, List[str]]
#: one expected value: a number (as a float), a boolean or a string
Scalar = Union[float, bool, str]
#: a tolerance: absolute, one per element of an array, None for an exact comparison
Tol = Union[Optional[float], List[Optional[float]]]

#: a TOML decimal number literal (no inf/nan/hex: those take the fallback)
_NUMBER = re.compile(r"[+-]?(\d[\d_]*)(?:\.([\d_]*))?(?:[eE]([+-]?[\d_]+))?")
_HEADER = re.compile(r"\s*\[\s*([^\[\]]+?)\s*\]\s*(?:#.*)?$")
_KEYLINE = re.compile(r"\s*(\"[^\"]*\"|'[^']*'|[A-Za-z0-9_\-.]+)\s*=\s*(.*)$")
_VALUE_IN_TABLE = re.compile(r"(?:^|[{,\s])value\s*=\s*")

#: relative slack on a tolerance, for the binary rounding of the two numbers
SLACK = 1e-9

WANT = "a number, a boolean, a string, an array of those or { value = …, tol = … }"


def tolerance_of_literal(text: str) -> Optional[float]:
    """Half a unit of the last digit of a TOML number literal; None if *text*
    is not a decimal number literal (``inf``, ``0x1f``, a string...).

    >>> tolerance_of_literal("1.2300"), tolerance_of_literal("120"), tolerance_of_literal("1e-3")
    (5e-05, 0.5, 0.0005)
    """
    m = _NUMBER.fullmatch(text.strip())
    if not m:
        return None
    frac = (m.group(2) or "").replace("_", "")
    exp = int((m.group(3) or "0").replace("_", ""))
    return 0.5 * 10.0 ** (exp - len(frac))


def _tolerance_of_float(value: float) -> Optional[float]:
    """Fallback when no literal text is known: the shortest repr of the float
    (trailing zeros are lost there)."""
    text = repr(float(value))
    return tolerance_of_literal(text) if "n" not in text else None


def _leading_literal(rest: str) -> Optional[LiteralText]:
    """The scalar or array literal at the start of *rest* (text after ``=``)."""
    rest = rest.strip()
    if rest.startswith("["):
        depth, end = 0, None
        for i, ch in enumerate(rest):
            depth += ch == "["
            depth -= ch == "]"
            if depth == 0:
                end = i
                break
        if end is None:
            return None  # a multi-line array: no texts (fallback)
        items = [s.strip() for s in rest[1:end].split(",")]
        return [s for s in items if s]
    m = _NUMBER.match(rest)
    return m.group(0) if m else None


def _literal_of(rest: str) -> Optional[LiteralText]:
    rest = rest.strip()
    if rest.startswith("{"):
        m = _VALUE_IN_TABLE.search(rest)
        return _leading_literal(rest[m.end():]) if m else None
    return _leading_literal(rest)


def _unquote(key: str) -> str:
    return key[1:-1] if key[:1] in "\"'" and key[-1:] == key[:1] else key


def _split_inline(body: str) -> List[str]:
    """The ``key = value`` items of the inside of a one-line inline table,
    split at the commas outside brackets, braces and strings."""
    items, depth, quote, start = [], 0, None, 0
    for i, ch in enumerate(body):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            items.append(body[start:i])
            start = i + 1
    items.append(body[start:])
    return [it for it in items if it.strip()]


def _inline_table_texts(rest: str) -> Dict[str, LiteralText]:
    """``{key: literal}`` of a one-line inline table ``{ K = 1.20, … }``
    (the text after ``expected =``)."""
    rest = rest.strip()
    if not rest.startswith("{"):
        return {}
    depth, end = 0, None
    for i, ch in enumerate(rest):
        depth += ch == "{"
        depth -= ch == "}"
        if depth == 0:
            end = i
            break
    if end is None:
        return {}
    out = {}
    for item in _split_inline(rest[1:end]):
        m = _KEYLINE.match(item)
        if m:
            lit = _literal_of(m.group(2))
            if lit is not None:
                out[_unquote(m.group(1))] = lit
    return out


def literal_texts(text: str) -> Dict[str, LiteralText]:
    """``{key: literal}`` of the ``[expected]`` table in a spec's TOML text.

    A literal is the number's text (``"1.2300"``), or a list of the element
    texts for a one-line array; keys whose value is given as
    ``{ value = …, … }`` map to the text after ``value =``.  Keys written as
    ``expected.KEY = …`` or ``expected = { KEY = …, … }`` at the top level,
    and the ``value = …`` of an ``[expected.KEY]`` table, are found too.
    Lines inside multi-line strings are skipped.
    """
    out: Dict[str, LiteralText] = {}
    table: Optional[str] = ""
    in_string: Optional[str] = None
    for line in text.splitlines():
        if in_string:
            if line.count(in_string) % 2:
                in_string = None
            continue
        h = _HEADER.match(line)
        if line.lstrip().startswith("[["):
            table = None
            continue
        if h:
            table = ".".join(_unquote(p.strip()) for p in h.group(1).split("."))
            continue
        m = _KEYLINE.match(line)
        for quote in ('"""', "'''"):
            if m and m.group(2).count(quote) % 2:
                in_string = quote
        if not m or table is None:
            continue
        key = _unquote(m.group(1))
        if table == "" and key == "expected":
            out.update(_inline_table_texts(m.group(2)))
            continue
        if table == "" and key.startswith("expected."):
            key = key[len("expected."):]
        elif table.startswith("expected.") and key == "value":
            key = table[len("expected."):]
        elif table != "expected":
            continue
        if key.endswith(".value"):
            key, rest = key[: -len(".value")], m.group(2)
            lit = _leading_literal(rest)
        else:
            lit = _literal_of(m.group(2))
        if lit is not None:
            out[key] = lit
    return out


def override_texts(sets: Iterable[str]) -> Dict[str, LiteralText]:
    """``{key: literal}`` for ``--set expected.KEY=VALUE`` overrides (last wins)."""
    out: Dict[str, LiteralText] = {}
    lit: Optional[LiteralText]
    for text in sets:
        key, sep, raw = text.partition("=")
        key = key.strip()
        if sep and key == "expected":
            for name, lit in _inline_table_texts(raw).items():
                out.pop(name, None)
                out[name] = lit
            continue
        if not sep or not key.startswith("expected."):
            continue
        key = key[len("expected."):]
        if key.endswith(".value"):
            key = key[: -len(".value")]
            lit = _leading_literal(raw)
        else:
            lit = _literal_of(raw)
        out.pop(key, None)
        if lit is not None:
            out[key] = lit
    return out


@record
class Expected:
    """One expected value (from the book, or an independent hand calculation).

    Attributes
    ----------
    name : str
        The result it names.
    value : float, bool, str or list
        The expected value (numbers as floats).
    tol : float, list or None
        Absolute tolerance (a list, per element, for arrays; None for an exact
        comparison: strings, booleans).
    """

    name: str
    value: Union[Scalar, List[Scalar]]
    tol: Tol


@record
class Check:
    """The comparison of one ``[expected]`` key with the run's result.

    ``deviation`` is |got - expected| / tol (the worst element for arrays),
    0 for an exact match, ``inf`` for a mismatch that has no size (a string,
    a boolean, a missing result, a wrong type or length).
    """

    name: str
    held: bool
    expected: object
    got: object
    tol: object
    deviation: float

    def as_dict(self) -> Dict[str, object]:
        dev = self.deviation if math.isfinite(self.deviation) else None
        return {"key": self.name, "held": self.held, "expected": self.expected,
                "got": self.got, "tol": self.tol, "deviation": dev}


def _is_number(x: object) -> TypeGuard[float]:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _scalar(sec: Section, key: str, raw: object, literal: Optional[LiteralText]
            ) -> Tuple[Scalar, Optional[float]]:
    """(value, tol) of one scalar; None if it is not a scalar we accept."""
    if isinstance(raw, (bool, str)):
        return raw, None
    if _is_number(raw) and math.isfinite(raw):
        tol = tolerance_of_literal(literal) if isinstance(literal, str) else None
        if tol is None:
            tol = _tolerance_of_float(raw)
        return float(raw), tol
    raise SpecError(sec.file, sec.key(key), WANT, _show(raw))


def _show(raw: object) -> str:
    if isinstance(raw, dict):
        return "a table"
    if isinstance(raw, list):
        return f"an array of {len(raw)}"
    return f"{raw!r} ({type(raw).__name__})"


def _array(sec: Section, name: str, raw: List[object], literal: Optional[LiteralText]
           ) -> Tuple[List[Scalar], List[Optional[float]]]:
    if not raw:
        raise SpecError(sec.file, sec.key(name), "a non-empty array", "an empty array")
    texts = literal if isinstance(literal, list) and len(literal) == len(raw) else [None] * len(raw)
    values, tols = [], []
    for i, (item, lit) in enumerate(zip(raw, texts)):
        if isinstance(item, (list, dict)):
            raise SpecError(sec.file, sec.key(f"{name}[{i}]"),
                            "a number, a boolean or a string", _show(item))
        v, t = _scalar(sec, f"{name}[{i}]", item, lit)
        values.append(v)
        tols.append(t)
    return values, tols


def _positive(sub: Section, key: str) -> Optional[float]:
    value = sub.raw(key, None)
    if value is None:
        return None
    if not _is_number(value) or not math.isfinite(value) or value <= 0:
        raise SpecError(sub.file, sub.key(key), "a positive tolerance", _show(value))
    return float(value)


def read_expected(root: Section, sets: Iterable[str] = ()) -> Dict[str, Expected]:
    """Read and validate the optional ``[expected]`` table of a spec.

    Parameters
    ----------
    root : mechcli.spec.reader.Section
        The spec's root table (from :func:`~mechcli.spec.reader.load_spec`).
    sets : sequence of str
        The ``--set`` overrides the root was loaded with: the text of an
        ``expected.KEY=...`` override gives that key's printed digits.

    Returns
    -------
    dict
        ``{name: Expected}`` in the order of the file.

    Raises
    ------
    SpecError
        A value of a wrong type, an empty array, a tolerance <= 0.
    """
    sec = root.table("expected", None)
    if sec is None:
        return {}
    texts = {}
    try:
        with open(root.file, encoding="utf-8") as fh:
            texts = literal_texts(fh.read())
    except (OSError, UnicodeDecodeError):
        pass
    texts.update(override_texts(sets))
    out = {}
    for name in sec.keys():
        raw = sec.raw(name)
        lit = texts.get(name)
        if isinstance(raw, dict):
            sub = sec.table(name)
            value = sub.raw("value")
            tol = _positive(sub, "tol")
            rtol = [r for r in (_positive(sub, "rtol"), _positive(sub, "rel")) if r is not None]
            sub.raw("note", None)
            sub.finish()
            if tol is not None and rtol:
                raise SpecError(sub.file, sub.key("rtol" if sub.has("rtol") else "rel"),
                                "either tol or rtol, not both", "both")
            values: Union[Scalar, List[Scalar]]
            tols: Tol
            if isinstance(value, list):
                values, tols = _array(sub, "value", value, lit)
                if any(isinstance(v, (bool, str)) for v in values) and (tol or rtol):
                    raise SpecError(sub.file, sub.key("value"),
                                    "numbers (a tolerance applies to numbers)", _show(value))
            elif _is_number(value) and math.isfinite(value):
                values, tols = _scalar(sub, "value", value, lit)
            else:
                raise SpecError(sub.file, sub.key("value"),
                                "a number or an array of numbers", _show(value))
            if tol is not None or rtol:
                def _tol(v: float) -> float:
                    t = tol if tol is not None else abs(v) * rtol[0]
                    if not t > 0:
                        raise SpecError(sub.file, sub.key("rtol" if sub.has("rtol") else "rel"),
                                        "a non-zero value for a relative tolerance (use tol)",
                                        "value 0")
                    return t
                # (numbers: a boolean or a string with a tolerance was refused above)
                tols = [_tol(v) for v in values] if isinstance(values, list) else _tol(values)  # type: ignore[arg-type]
            out[name] = Expected(name, values, tols)
        elif isinstance(raw, list):
            values, tols = _array(sec, name, raw, lit)
            out[name] = Expected(name, values, tols)
        else:
            out[name] = Expected(name, *_scalar(sec, name, raw, lit))
    sec.finish()
    return out


def _one(value: Scalar, tol: Optional[float], got: object) -> Tuple[bool, float]:
    """(held, deviation) of one scalar."""
    if tol is None:
        same = type(got) is type(value) and got == value
        return same, 0.0 if same else math.inf
    if not _is_number(got) or not math.isfinite(got):
        return False, math.inf
    assert not isinstance(value, str)  # a tolerance is a number's
    dev = abs(got - value) / tol
    return dev <= 1 + SLACK, dev


_MISSING = object()


def lookup(results: Dict[str, Any], name: str, default: object = _MISSING) -> Any:
    """The result *name* names: a key of *results*, or a dotted path into nested
    results (``"cases.0.l1"``: key ``cases``, item 0 (0-based, as in the JSON),
    key ``l1``); *default* (or a private sentinel) when there is none."""
    if name in results:
        return results[name]
    return _walk(results, name.split("."), default)


def _walk(node: object, parts: List[str], default: object) -> Any:
    """Follow *parts* into *node*; a dict key may itself hold dots (``optimize``'s
    ``x`` is keyed by dotted spec paths: ``"x.mechanism.l2"``), so the longest
    joined run of parts that is a key is tried first."""
    if not parts:
        return node
    if isinstance(node, dict):
        for k in range(len(parts), 0, -1):
            key = ".".join(parts[:k])
            if key in node:
                found = _walk(node[key], parts[k:], default)
                if found is not default:
                    return found
        return default
    if isinstance(node, (list, tuple)) and parts[0].isdigit() and int(parts[0]) < len(node):
        return _walk(node[int(parts[0])], parts[1:], default)
    return default


def has_result(results: Dict[str, Any], name: str) -> bool:
    """Does *name* (a key or a dotted path, see :func:`lookup`) name a result?"""
    return lookup(results, name) is not _MISSING


def compare(expected: Dict[str, Expected], results: Dict[str, Any]) -> List[Check]:
    """Compare every expected value with the run's *results*.

    Parameters
    ----------
    expected : dict
        ``{name: Expected}`` from :func:`read_expected`.
    results : dict
        The run's ``--json`` ``"results"``.

    Returns
    -------
    list of Check
        One per expected key, in order.
    """
    out = []
    for name, exp in expected.items():
        got = lookup(results, name)
        if got is _MISSING:
            out.append(Check(name, False, exp.value, None, exp.tol, math.inf))
            continue
        if isinstance(exp.value, list):
            if not isinstance(got, (list, tuple)) or len(got) != len(exp.value):
                out.append(Check(name, False, exp.value, got, exp.tol, math.inf))
                continue
            assert isinstance(exp.tol, list)  # an array's tolerances: one per element
            pairs = [_one(v, t, g) for v, t, g in zip(exp.value, exp.tol, got)]
            out.append(Check(name, all(h for h, _ in pairs), exp.value, list(got), exp.tol,
                             max(d for _, d in pairs)))
            continue
        assert not isinstance(exp.tol, list)  # a scalar's tolerance
        held, dev = _one(exp.value, exp.tol, got)
        out.append(Check(name, held, exp.value, got, exp.tol, dev))
    return out


def evaluate(path: Union[str, os.PathLike], sets: Iterable[str], results: Dict[str, Any]
             ) -> List[Check]:
    """Read the ``[expected]`` table of the spec at *path* (with *sets*) and
    compare it with *results*; an expected key that names no result is a
    :class:`SpecError` (exit 2, with did-you-mean), as in every command."""
    check_expected(path, sets, results)
    return compare(read_expected(load_spec(path, sets), sets), results)


def check_expected(path: Optional[Union[str, os.PathLike]], overrides: Iterable[str],
                   results: Dict[str, Any]) -> None:
    """Reject an ``[expected]`` key that names no result of the run (exit 2).

    The keys of ``[expected]`` are compared with the keys of *results* (the
    ``--json`` ``"results"`` object), so a misspelled name fails the run
    instead of passing unchecked.  The spec is read again (a few hundred
    microseconds) so that every command gets the check from
    :func:`mechcli.report.run.finish` without passing its spec along.

    Parameters
    ----------
    path : str or pathlib.Path or None
        The spec file of the run; None for file-less runs (nothing to check).
    overrides : sequence of str
        The run's ``--set KEY=VALUE`` overrides (they may add expected keys).
    results : dict
        The scalar results of the run.

    Raises
    ------
    SpecError
        On the first key of ``[expected]`` that is not a key of *results*,
        with the nearest result name as a suggestion.
    """
    if path is None:
        return
    try:
        root = load_spec(path, overrides)
    except SpecError:
        # the command has read this file already, so it is not a TOML spec
        # (``grashof --batch`` reads a CSV): there is no [expected] table
        return
    sec = root.table("expected", None)
    names = sorted(map(str, results))
    for name in [] if sec is None else sec.keys():
        if not has_result(results, name):
            raise SpecError(sec.file, sec.key(name),
                            "the name of a result of this run (a key of --json \"results\")",
                            f"unknown key '{name}'", closest(name, names))
