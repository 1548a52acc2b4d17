"""An unknown key is reported before any check that depends on the keys present.

A reader learns its keys as it reads them, so a misspelt key (``0r`` for ``r0``,
``mthod`` for ``method``) used to surface as the side effect it has on another
check: a required key missing (the did-you-mean then picked a valid key read later,
``rr``), a default that makes another value out of range.  When a spec fails, this
module looks the whole spec over against the command's shipped schema (every key its
reader knows, learnt from the reader itself: :mod:`mechcli.spec.schema`) and reports
the first key no table knows, naming it, instead.  Only on the error path: a spec that
reads cleanly never loads a schema.
"""

from __future__ import annotations

import functools
import json
from typing import TYPE_CHECKING, Any, Dict, Iterable, List, Optional, Tuple, Union

from mechcli.spec.errors import SpecError, closest

if TYPE_CHECKING:
    import os


def first_unknown_key(command: str, path: Union[str, os.PathLike],
                      overrides: Iterable[str] = ()) -> Optional[SpecError]:
    """A :class:`SpecError` naming the first key of the spec at *path* (with the
    ``--set`` *overrides*) that the command's schema does not know, or None."""
    from mechcli.spec.reader import load_spec
    from mechcli.spec.schema import COMMANDS, shipped_schema_text

    if command not in COMMANDS:
        return None
    try:
        root = load_spec(path, overrides)
        schema = json.loads(shipped_schema_text(command))
    except (SpecError, OSError, ValueError):
        return None
    found = _walk(root.data, schema, ())
    if found is None:
        return None
    where, key, known = found
    table = ".".join(where)
    # a transposition (0r for r0, 2l for l2) before difflib's nearest
    swapped = [k for k in known if sorted(k) == sorted(key)]
    return SpecError(str(path), ".".join(where + (key,)),
                     "a known key" + (f" of [{table}]" if table else ""),
                     f"unknown key '{key}'", swapped[0] if swapped else closest(key, known))


def _walk(node: Any, schema: Any,
          where: Tuple[str, ...]) -> Optional[Tuple[Tuple[str, ...], str, List[str]]]:
    """(path, key, known keys) of the first unknown key under *node*, depth first in
    the spec's own order; None if every key is known."""
    schema = _for(node, schema)
    if schema is None:
        return None
    if isinstance(node, dict):
        props = schema.get("properties", {})
        extra = schema.get("additionalProperties", True)
        for key, value in node.items():
            if key in props:
                sub = props[key]
            elif extra is False:   # suggest among the keys the table does not give yet
                return where, key, sorted(k for k in props if k not in node)
            elif isinstance(extra, dict):
                sub = extra
            else:
                continue
            hit = _walk(value, sub, where + (key,))
            if hit is not None:
                return hit
    elif isinstance(node, list):
        for i, value in enumerate(node):
            hit = _walk(value, schema.get("items"), where + (str(i),))
            if hit is not None:
                return hit
    return None


def _for(node: Any, schema: Any) -> Optional[Dict[str, Any]]:
    """The part of *schema* that describes *node* (a table or an array): its own, or
    the union of its ``anyOf`` alternatives of that type; None for a plain value."""
    if not isinstance(schema, dict) or not isinstance(node, (dict, list)):
        return None
    kind = "object" if isinstance(node, dict) else "array"
    alts = [a for a in [schema] + list(schema.get("anyOf", ()))
            if isinstance(a, dict) and a.get("type") == kind]
    if not alts:
        return None
    if len(alts) == 1 or kind == "array":
        return alts[0]
    props, closed, extra = {}, True, None
    for a in alts:
        props.update(a.get("properties", {}))
        ap = a.get("additionalProperties", True)
        closed &= ap is False
        if isinstance(ap, dict):
            extra = ap
    return {"type": "object", "properties": props,
            "additionalProperties": False if closed else (extra or True)}


def taken_by_another_form(path: str, key: str) -> bool:
    """Does another form of the table at the dotted *path* (``mechanism``,
    ``mechanism.dyad.0``) take *key*: is *key* a key of that table in a command's shipped
    schema, whose tables are the union of their forms (``l3`` of a four-bar in a
    slider-crank's ``[mechanism]``, ``slider`` of an RRP dyad in an RRR one)?  Only on
    the error path of an unknown key."""
    for schema in _shipped_schemas():
        nodes = [schema]
        for part in [p for p in str(path).split(".") if p]:
            nodes = _step(nodes, part)
        if any(key in alt.get("properties", {}) for n in nodes for alt in _alts(n)):
            return True
    return False


@functools.lru_cache(maxsize=1)
def _shipped_schemas() -> Tuple[Dict[str, Any], ...]:
    """Every command's shipped schema (read once, on the first error that needs them)."""
    from mechcli.spec.schema import COMMANDS, shipped_schema_text
    out = []
    for command in COMMANDS:
        try:
            out.append(json.loads(shipped_schema_text(command)))
        except (OSError, ValueError):
            continue
    return tuple(out)


def _alts(node: Any) -> List[Dict[str, Any]]:
    if not isinstance(node, dict):
        return []
    return [node] + [a for a in node.get("anyOf", ()) if isinstance(a, dict)]


def _step(nodes: Iterable[Any], part: str) -> List[Any]:
    """The schemas of the child *part* (a key, or an index of an array) of *nodes*."""
    out = []
    for node in nodes:
        for alt in _alts(node):
            if part.isdigit() and isinstance(alt.get("items"), dict):
                out.append(alt["items"])
            elif not part.isdigit():
                sub = alt.get("properties", {}).get(part)
                if sub is None and isinstance(alt.get("additionalProperties"), dict):
                    sub = alt["additionalProperties"]
                if sub is not None:
                    out.append(sub)
    return out
