"""``--json`` output: scalar results and the written file paths."""

from __future__ import annotations

import json
import math


def _clean(value):
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"refusing to emit a non-finite JSON number ({value})")
        return value
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if hasattr(value, "item"):  # numpy scalar
        return _clean(value.item())
    return value


def dumps(command, spec, results, files, warnings=()):
    """JSON text: ``{"command", "spec", "results", "warnings", "files"}``."""
    doc = {
        "command": command,
        "spec": None if spec is None else str(spec),
        "results": _clean(results),
        "warnings": list(warnings),
        "files": [str(f) for f in files],
    }
    return json.dumps(doc, ensure_ascii=False, indent=2)
