"""A small TOML writer for tests that write modified configs (tomli_w is not a
dependency): every table and array of tables is written inline, one ``key = value``
line per top-level key; :class:`Nested` writes a value nested deep without recursion."""

import json
import math
import re


def _toml_string(text):
    # JSON string escapes are valid TOML basic-string escapes; TOML also forbids raw DEL
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_key(key):
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else _toml_string(key)


class Nested:
    """``value`` inside ``depth`` arrays or tables, written without recursion (TOML 1000 deep
    must not need a Python stack 1000 deep), and a leaf for the mutations."""

    def __init__(self, value, depth, kind):
        self.value, self.depth, self.kind = value, depth, kind

    def __repr__(self):
        return f"Nested({self.value!r:.30}, {self.depth}, {self.kind})"

    def plain(self):
        value = self.value
        for _ in range(self.depth):
            value = [value] if self.kind == "array" else {"a": value}
        return value


def _toml_value(value):
    if isinstance(value, Nested):
        inner = _toml_value(value.value)
        if value.kind == "array":
            return "[" * value.depth + inner + "]" * value.depth
        return "{a = " * value.depth + inner + "}" * value.depth
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}"
                               for k, v in value.items()) + "}"
    raise TypeError(f"no TOML writer for {type(value).__name__}")


def to_toml(doc):
    """``doc`` as TOML text: one ``key = value`` line per top-level key."""
    return "".join(f"{_toml_key(k)} = {_toml_value(v)}\n" for k, v in doc.items())
