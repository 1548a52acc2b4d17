"""``mechcli check`` output: the table, the summary line, the failing keys, JSON, JUnit XML.

Works on the plain dicts of :func:`mechcli.batch.run_spec` (one per spec:
``spec``, ``command``, ``status``, ``exit_code``, ``time_s``, ``checks``,
``error``, ``warnings``) and the problems of :func:`mechcli.batch.collect`
(``path``, ``error``, ``exit_code``).
"""

from __future__ import annotations

import math


def summarize(results, problems, wall_s, jobs, code):
    """Counts of a batch, for the summary line, JSON ``results`` and JUnit."""
    checks = [c for r in results for c in r["checks"]]
    return {
        "specs": len(results),
        "passed": sum(r["status"] == "passed" for r in results),
        "failed": sum(r["status"] == "failed" for r in results),
        "errors": sum(r["status"] == "error" for r in results),
        "paths_without_specs": len(problems),
        "checks": len(checks),
        "checks_held": sum(c["held"] for c in checks),
        "time_s": round(wall_s, 3),
        "jobs": jobs,
        "exit_code": code,
    }


def fmt(value):
    """A value as the user wrote it, near enough: numbers with up to 10 significant digits."""
    if isinstance(value, list):
        return "[" + ", ".join(fmt(v) for v in value) + "]"
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, float):
        return f"{value:.10g}"
    if isinstance(value, str):
        return repr(value)
    return "missing" if value is None else str(value)


def fmt_tol(tol):
    if tol is None:
        return "exact"
    if isinstance(tol, list):
        tols = [t for t in tol if t is not None]
        if not tols:
            return "exact"
        return f"± {fmt_tol(tols[0])[2:]}" if len(set(tols)) == 1 else \
            "± [" + ", ".join("exact" if t is None else f"{t:.3g}" for t in tol) + "]"
    return f"± {tol:.3g}"


def worst(result):
    """The largest deviation of a spec's checks in units of their tolerance
    (None when it has no numeric check; inf for a mismatch without size)."""
    devs = [math.inf if c["deviation"] is None else c["deviation"] for c in result["checks"]]
    return max(devs) if devs else None


def _fmt_dev(d):
    if d is None:
        return "-"
    return "mismatch" if math.isinf(d) else f"{d:.3g}"


def error_lines(results, problems):
    """One line per path that named no spec and per spec that could not run."""
    lines = [f"{p['path']}: {p['error']}" for p in problems]
    for r in results:
        if r["status"] == "error":
            msg = r["error"] or "could not run"
            lines.append(msg if msg.startswith(r["spec"]) else f"{r['spec']}: {msg}")
    return lines


def failure_lines(results):
    """One line per expected value not met: expected, tolerance, got."""
    lines = []
    for r in results:
        for c in r["checks"]:
            if not c["held"]:
                dev = c["deviation"]
                size = "" if dev is None else f" ({dev:.3g} × tol)"
                lines.append(f"{r['spec']}: [expected] {c['key']}: expected {fmt(c['expected'])}"
                             f" {fmt_tol(c['tol'])}, got {fmt(c['got'])}{size}")
    return lines


def summary_line(s):
    parts = [f"{s['passed']} passed"]
    if s["failed"]:
        parts.append(f"{s['failed']} failed")
    if s["errors"]:
        parts.append(f"{s['errors']} could not run")
    if s["paths_without_specs"]:
        parts.append(f"{s['paths_without_specs']} path(s) named no spec")
    noun = "spec" if s["specs"] == 1 else "specs"
    return (f"mechcli check: {s['specs']} {noun}, " + ", ".join(parts)
            + f"; {s['checks_held']}/{s['checks']} expected values met"
            + f" in {s['time_s']:.1f} s (-j {s['jobs']})")


def print_table(results, file=None):
    """The table: spec, command, checks held/total, worst deviation, time, status.

    On a terminal a rich table (the status coloured, no colour under ``NO_COLOR``); in
    a pipe, a log or a file (``mechcli check configs/ | cat``) the plain text of every
    other command's table: no box drawing, no ANSI escapes, no spec path cut."""
    import sys

    from mechcli.report.console import console as make_console
    from mechcli.report.console import is_terminal

    headers = ["spec", "command", "checks", "worst dev/tol", "time s", ""]
    style = {"passed": "green", "failed": "bold red", "error": "bold yellow"}
    rows, styles = [], []
    for r in results:
        held = sum(c["held"] for c in r["checks"])
        status = {"passed": "ok", "failed": "FAILED", "error": f"error {r['exit_code']}"}
        rows.append([r["spec"], r["command"] or "-",
                     f"{held}/{len(r['checks'])}" if r["status"] != "error" else "-",
                     _fmt_dev(worst(r)), f"{r['time_s']:.2f}", status[r["status"]]])
        styles.append(style[r["status"]])
    justify = ("left", "left", "right", "right", "right", "left")
    stream = sys.stdout if file is None else file
    if not is_terminal(stream):
        stream.write(plain_table("mechcli check", headers, rows, justify))
        return
    from rich.markup import escape
    from rich.table import Table

    table = Table(title="mechcli check", title_justify="left")
    for name, just in zip(headers, justify):
        table.add_column(name, justify=just)
    for row, st in zip(rows, styles):
        table.add_row(*map(escape, row[:-1]), f"[{st}]{escape(row[-1])}[/]")
    make_console(file).print(table)


def plain_table(title, headers, rows, justify):
    """*rows* under *headers* as plain text, each column as wide as its widest cell
    (a long spec path is never cut), *justify* ``left``/``right`` per column."""
    from mechcli.report.table import display_width

    widths = [max([display_width(h)] + [display_width(r[i]) for r in rows])
              for i, h in enumerate(headers)]

    def line(cells):
        out = []
        for c, w, j in zip(cells, widths, justify):
            gap = " " * (w - display_width(c))
            out.append(c + gap if j == "left" else gap + c)
        return "  ".join(out).rstrip()

    return "\n".join([title, line(headers), line(["-" * w for w in widths])]
                     + [line(r) for r in rows]) + "\n"


def json_doc(results, problems, summary, files=()):
    """The ``--json`` document: the usual ``{"command", "spec", "results",
    "warnings", "files"}`` with the counts as ``results``, plus ``specs``
    (one entry per spec with its checks) and ``problems`` (paths that named
    no spec)."""
    import json

    specs = []
    for r in results:
        specs.append({k: r[k] for k in ("spec", "command", "status", "exit_code", "checks",
                                        "error", "warnings")}
                     | {"time_s": round(r["time_s"], 4), "worst_deviation": _json_dev(worst(r))})
    warnings = [f"{r['spec']}: {w}" for r in results for w in r["warnings"]]
    doc = {"command": "check", "spec": None, "results": summary, "warnings": warnings,
           "files": [str(f) for f in files], "specs": specs, "problems": list(problems)}
    return json.dumps(doc, ensure_ascii=False, indent=2)


def _json_dev(d):
    return None if d is None or math.isinf(d) else d


def junit_xml(results, problems, summary):
    """JUnit XML text: one ``testcase`` per spec (``classname`` = command),
    one ``failure`` per key not met, one ``error`` for a spec that could not
    run; a path that named no spec is a test case with an ``error``."""
    import xml.etree.ElementTree as ET

    suites = ET.Element("testsuites")
    suite = ET.SubElement(suites, "testsuite", {
        "name": "mechcli check",
        "tests": str(len(results) + len(problems)),
        "failures": str(summary["failed"]),
        "errors": str(summary["errors"] + summary["paths_without_specs"]),
        "skipped": "0",
        "time": f"{summary['time_s']:.3f}",
    })
    for p in problems:
        case = ET.SubElement(suite, "testcase", {"classname": "mechcli.check", "name": p["path"],
                                                 "time": "0"})
        ET.SubElement(case, "error", {"message": p["error"], "type": f"exit {p['exit_code']}"})
    for r in results:
        case = ET.SubElement(suite, "testcase", {
            "classname": f"mechcli.{r['command'] or 'unknown'}", "name": r["spec"],
            "time": f"{r['time_s']:.3f}"})
        if r["status"] == "error":
            el = ET.SubElement(case, "error", {"message": r["error"] or "could not run",
                                               "type": f"exit {r['exit_code']}"})
            el.text = r.get("stderr") or None
        for c in r["checks"]:
            if not c["held"]:
                msg = (f"{c['key']}: expected {fmt(c['expected'])} {fmt_tol(c['tol'])}, "
                       f"got {fmt(c['got'])}")
                ET.SubElement(case, "failure", {"message": msg, "type": "expected"}).text = msg
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") \
        + "\n"
