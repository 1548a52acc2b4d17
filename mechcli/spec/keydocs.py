"""What every spec key means: the one source of the key comments of ``mechcli new``'s
templates and of the ``description`` of every key in ``mechcli schema``.

The text is package data, ``mechcli/templates/keys.toml``: one table per group of
keys (``[common]`` for what every command reads, ``[linkage]`` for the tables of a
linkage that ``kin``, ``force``, ``flywheel`` and ``optimize`` share, one table per
command for its own), each mapping a dotted key path (arrays of tables without an
index, ``*`` for any key of a free-form table such as ``[expected]``) to a one-line
description: meaning, unit in brackets (``[units]`` is the spec's length unit) and
default.  A key whose meaning depends on the problem's type maps each type to its text
(``"mechanism.l3" = { four_bar = "rocker CD …", guide_bar = "…" }``).

* :func:`describe_schema` puts the descriptions into the schema learnt from a reader
  (:func:`mechcli.spec.schema.command_schema`), so the shipped schemas carry them.
* :func:`annotate` writes the description beside every key line of a template (the
  key's comment), which the shipped templates hold already:
  ``python -m mechcli.spec.keydocs`` rewrites them after the catalogue changes, and
  ``tests/unit/test_key_docs.py`` fails while one is stale.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Set, Tuple, Union

#: the catalogue's tables that each command's keys are looked up in, first match first
SECTIONS = {
    "kin": ("linkage", "common"),
    "force": ("linkage", "common"),
    "grashof": ("grashof", "common"),
    "cam": ("cam", "common"),
    "gear": ("gear", "common"),
    "synth": ("synth", "common"),
    "flywheel": ("flywheel", "linkage", "common"),
    "optimize": ("optimize", "linkage", "cam", "common"),
}
#: where a key of a table of problems is described: synth's ``[[case]]`` tables take
#: the keys of ``[synthesis]``
ALIASES = {("synth", "case"): ("synthesis",)}
#: the column of a key's comment in a template, and the width of its lines
COLUMN, WIDTH = 23, 99

TEMPLATES = Path(__file__).resolve().parent.parent / "templates"


@functools.cache
def catalogue() -> Dict[str, Any]:
    """``{table: {dotted path: text or {type: text}}}`` of ``templates/keys.toml``."""
    from mechcli.spec.reader import _toml
    return _toml().loads((TEMPLATES / "keys.toml").read_text(encoding="utf-8"))


def entry(command: str, path: Iterable[str]) -> Union[str, Dict[str, str], None]:
    """The catalogue's entry (a text, or ``{type: text}``) for the key at *path* (a
    tuple of keys, no array indices) of a ``mechcli COMMAND`` spec, or None.

    A key of a free-form table is found under ``*`` (``expected.*.tol``).
    """
    path = tuple(path)
    alias = ALIASES.get((command, path[0])) if path else None
    tries = [path] + ([alias + path[1:]] if alias and len(path) > 1 else [])
    book = catalogue()
    for p in tries:
        for cand in [p] + [p[:i] + ("*",) + p[i + 1:] for i in reversed(range(len(p)))]:
            dotted = ".".join(cand)
            for section in SECTIONS.get(command, ("common",)):
                found = book.get(section, {}).get(dotted)
                if found is not None:
                    return found
    return None


def text(found: Union[str, Dict[str, str], None], tags: Iterable[str] = ()) -> Optional[str]:
    """The words of a catalogue entry: for a type-dependent one, the text of the first
    of *tags* it has, else every type's text (``four_bar: …; guide_bar: …``; types of
    one text together, and one text alone when all are the same)."""
    if found is None or isinstance(found, str):
        return found
    for tag in tags:
        if tag in found:
            return found[tag]
    groups: Dict[str, List[str]] = {}
    for kind, words in found.items():
        groups.setdefault(words, []).append(kind)
    if len(groups) == 1:
        return next(iter(groups))
    return "; ".join(f"{', '.join(kinds)}: {words}" for words, kinds in groups.items())


def describe(command: str, path: Iterable[str], tags: Iterable[str] = ()) -> Optional[str]:
    """The description of the key at *path* of a ``mechcli COMMAND`` spec, or None."""
    return text(entry(command, path), tags)


# -- the schema -----------------------------------------------------------------------
def describe_schema(schema: Dict[str, Any], command: str) -> List[str]:
    """Put a ``description`` into every property of *schema* (in place); return the
    dotted paths that the catalogue does not describe."""
    missing: List[str] = []
    _describe_node(schema, command, (), missing)
    return missing


def _alternatives(node: Any) -> List[Dict[str, Any]]:
    if not isinstance(node, dict):
        return []
    return [node] + [a for a in node.get("anyOf", ()) if isinstance(a, dict)]


def _describe_node(node: Any, command: str, path: Tuple[str, ...], missing: List[str]) -> None:
    for alt in _alternatives(node):
        props = alt.get("properties")
        if isinstance(props, dict):
            for key in list(props):
                sub = props[key]
                words = describe(command, path + (key,))
                if words is None:
                    missing.append(".".join(path + (key,)))
                elif isinstance(sub, dict):
                    props[key] = {"description": words,
                                  **{k: v for k, v in sub.items() if k != "description"}}
                    sub = props[key]
                _describe_node(sub, command, path + (key,), missing)
        items = alt.get("items")
        if isinstance(items, dict):
            _describe_node(items, command, path, missing)
        extra = alt.get("additionalProperties")
        if isinstance(extra, dict):
            here = path + ("*",)
            words = describe(command, here)
            if words is None:
                missing.append(".".join(here))
            else:
                alt["additionalProperties"] = {
                    "description": words,
                    **{k: v for k, v in extra.items() if k != "description"}}
            _describe_node(alt["additionalProperties"], command, here, missing)


def used_paths(schema: Any, path: Tuple[str, ...] = ()) -> Set[str]:
    """Every dotted key path of *schema* (free-form keys as ``*``)."""
    out = set()
    for alt in _alternatives(schema):
        for key, sub in (alt.get("properties") or {}).items():
            out.add(".".join(path + (key,)))
            out |= used_paths(sub, path + (key,))
        if isinstance(alt.get("items"), dict):
            out |= used_paths(alt["items"], path)
        if isinstance(alt.get("additionalProperties"), dict):
            out.add(".".join(path + ("*",)))
            out |= used_paths(alt["additionalProperties"], path + ("*",))
    return out


# -- the templates --------------------------------------------------------------------
_HEADER = re.compile(r"^(\[\[?)\s*([A-Za-z0-9_.]+)\s*(\]\]?)(.*)$")
_COMMENTED_HEADER = re.compile(r"^# (\[\[?)\s*([A-Za-z0-9_.]+)\s*(\]\]?)\s*$")
_KEY = re.compile(r"^(# )?([A-Za-z_][A-Za-z0-9_]*)(\s*=\s*)(.*)$")


def _split_comment(rest: str) -> Tuple[str, str]:
    """``(value, comment)`` of the text after ``key =``: the comment starts at the
    first ``#`` outside a string."""
    quote = None
    i = 0
    while i < len(rest):
        c = rest[i]
        if quote:
            if c == "\\" and quote == '"':
                i += 1
            elif c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c == "#":
            return rest[:i].rstrip(), rest[i:]
        i += 1
    return rest.rstrip(), ""


def _is_value(value: str) -> bool:
    from mechcli.spec.reader import _toml
    tomllib = _toml()
    try:
        tomllib.loads(f"v = {value}")
    except tomllib.TOMLDecodeError:
        return False
    return True


def _comment(base: str, words: str) -> List[str]:
    """*base* (a key line without its comment) with *words* as its comment from column
    :data:`COLUMN` (or two spaces after a longer *base*), wrapped to :data:`WIDTH`
    columns on continuation lines ``#   …`` at :data:`COLUMN`; a bracketed unit or
    default (``[default 0]``) is never split."""
    col = COLUMN if len(base) < COLUMN - 1 else len(base) + 2
    tokens = re.sub(r"\[[^\]]*\]", lambda m: m.group(0).replace(" ", "\0"),
                    words).split(" ")
    lines: List[List[str]] = [[]]
    room = max(WIDTH - col - 2, 20)
    for tok in tokens:
        if lines[-1] and len(" ".join(lines[-1] + [tok])) > room:
            lines.append([])
            room = WIDTH - COLUMN - 4
        lines[-1].append(tok)
    text_ = [" ".join(ln).replace("\0", " ") for ln in lines]
    return [base.ljust(col) + "# " + text_[0]] + [" " * COLUMN + "#   " + t for t in text_[1:]]


def _tags(text_: str) -> Tuple[str, ...]:
    """The string values of a template (its problem's type: ``slider_crank``,
    ``oscillating``, ``function`` …) that pick a type-dependent description."""
    from mechcli.spec.reader import _toml
    try:
        data = _toml().loads(text_)
    except Exception:  # noqa: BLE001  (a template that is not TOML has no tags)
        return ()
    out = []

    def walk(node: Any) -> None:
        if isinstance(node, dict):
            for v in node.values():
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)
        elif isinstance(node, str):
            out.append(node)
    walk(data)
    return tuple(dict.fromkeys(out))


def annotate(text_: str, command: str) -> str:
    """*text_* (a template of ``mechcli COMMAND``) with the catalogue's description as
    the comment of every key line and table header: live keys, and commented-out keys
    ``# key = value`` (a single space after ``#``, a valid TOML value).  The comments
    it wrote before are replaced, so ``annotate(annotate(t)) == annotate(t)``; a key
    the catalogue does not know is left as it is."""
    tags = _tags(text_)
    table, commented, seen_arrays = (), (), set()
    out, cont, written = [], None, set()
    for line in text_.splitlines():
        if cont is not None and re.match(r" {%d,}#   " % cont, line):
            continue   # a continuation of a comment this function wrote: written anew
        cont = None
        header = _HEADER.match(line)
        if header:
            path = tuple(header.group(2).split("."))
            table = commented = path
            base = f"{header.group(1)}{header.group(2)}{header.group(3)}"
            words = describe(command, path, tags)
            if header.group(1) == "[[":
                if path in seen_arrays:
                    words = None
                seen_arrays.add(path)
            if words is None:
                out.append(base if header.group(4).lstrip().startswith("#")
                           else line.rstrip())
                continue
            out += _comment(base, words)
            cont = COLUMN
            continue
        ch = _COMMENTED_HEADER.match(line)
        if ch:
            commented = tuple(ch.group(2).split("."))
            out.append(line)
            continue
        key = _KEY.match(line)
        if key:
            lead, name, eq, rest = key.groups()
            value, _old = _split_comment(rest)
            if value and (not lead or _is_value(value)):
                where = commented if lead else table
                words = describe(command, where + (name,), tags)
                if words is not None and (where, words) in written:
                    out.append(f"{lead or ''}{name}{eq}{value}")   # said once per table
                    cont = COLUMN
                    continue
                if words is not None:
                    written.add((where, words))
                    base = f"{lead or ''}{name}{eq}{value}"
                    out += _comment(base, words)
                    cont = COLUMN
                    continue
        out.append(line)
    return "\n".join(out) + "\n"


def template_files() -> Dict[Path, str]:
    """``{path: command}`` of the shipped templates (``<command>.toml`` and
    ``<command>.<type>.toml``)."""
    out = {}
    for path in sorted(TEMPLATES.glob("*.toml")):
        command = path.name.split(".")[0]
        if command in SECTIONS:
            out[path] = command
    return out


def main() -> None:
    """Rewrite the comments of every shipped template from the catalogue."""
    for path, command in template_files().items():
        old = path.read_text(encoding="utf-8")
        new = annotate(old, command)
        if new != old:
            path.write_text(new, encoding="utf-8")
            print(f"rewrote {path}")


if __name__ == "__main__":
    main()
