"""What every ``benchmarks/bench_*.py`` prints: ``name: value unit`` lines, or with
``--json`` one JSON object of the same figures under the same names.

A script writes its figures as ``name: value unit [note]`` lines from ``main()`` and
ends with ``run(main)``.  With ``--json`` on its command line the lines are collected
and printed as::

    {"benchmark": "bench_startup",
     "figures": {"import_numpy_process": {"value": 104.2, "unit": "ms"}, ...},
     "text": ["lines that are not figures"]}

Names are the interface (CI and users track them): keep them when changing a script.
A speed figure comes with its baseline, measured in the same run, and their ratio
(``..._over_<baseline>`` or ``..._ratio``, unit ``x``).
"""

from __future__ import annotations

import contextlib
import io
import json
import re
import sys
from pathlib import Path

_LINE = re.compile(r"^(?P<name>[A-Za-z0-9_.\-]+): (?P<value>[-+]?(?:\d+(?:\.\d*)?(?:[eE][-+]?\d+)?"
                   r"|nan|inf))(?: (?P<unit>[^\s(]\S*))?(?P<note>.*)$")


def parse(text):
    """``(figures, other_lines)`` of a script's output."""
    figures, other = {}, []
    for line in text.splitlines():
        m = _LINE.match(line.strip())
        if not m:
            if line.strip():
                other.append(line.rstrip())
            continue
        v = m["value"]
        value = int(v) if re.fullmatch(r"[-+]?\d+", v) else float(v)
        fig = {"value": value, "unit": (m["unit"] or "1").rstrip(",;")}
        if m["note"].strip():
            fig["note"] = m["note"].strip()
        figures[m["name"]] = fig
    return figures, other


def run(main):
    """Call ``main()``; with ``--json`` in ``sys.argv`` print its figures as JSON instead."""
    if "--json" not in sys.argv[1:]:
        return main()
    sys.argv = [a for a in sys.argv if a != "--json"]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main()
    figures, other = parse(buf.getvalue())
    json.dump({"benchmark": Path(sys.argv[0]).stem, "figures": figures, "text": other},
              sys.stdout, indent=2, ensure_ascii=False)
    sys.stdout.write("\n")
    return None
