"""``--json`` output: scalar results and the written file paths.

Numbers are always round-trip exact, whatever ``--digits`` says for the CSV:
:mod:`json` writes a float with ``float.__repr__``, the shortest text that reads
back to the same double (``0.1 + 0.2`` -> ``0.30000000000000004``), and numpy
scalars become Python floats first.
"""

from __future__ import annotations

import json
import math


def _clean(value):
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"refusing to emit a non-finite JSON number ({value})")
        return float(value)   # a float subclass (np.float64) as a plain float: repr is exact
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if hasattr(value, "item"):  # numpy scalar
        return _clean(value.item())
    return value


def dumps(command, spec, results, files, warnings=(), manifest=None, removed=(), kept=()):
    """JSON text: ``{"command", "spec", "results", "warnings", "files", "manifest",
    "removed", "kept"}``: *manifest* is the path of ``outputs.json`` (which lists *files*),
    *removed* the names of the stale files of an earlier run it removed, *kept* those of
    an earlier run of the same problem it kept as still valid."""
    doc = {
        "command": command,
        "spec": None if spec is None else str(spec),
        "results": _clean(results),
        "warnings": list(warnings),
        "files": [str(f) for f in files],
    }
    if manifest is not None:
        doc["manifest"] = str(manifest)
        doc["removed"] = list(removed)
        doc["kept"] = list(kept)
    return json.dumps(doc, ensure_ascii=False, indent=2)
