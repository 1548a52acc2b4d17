"""Accuracy versus cost of the input step, for every extreme `kin` and `force` report (issue 20).

For 【例 1-1】 (``configs/ch1/ex1-1.toml``, ``kin``) and 【例 2-4】 (``configs/ch2/ex2-4.toml``,
``force``) the analysis is run at input steps from 10° down to 0.001°.  For every extreme
the JSON results list (``<q>_max_<unit>`` and ``<q>_min_<unit>``, every quantity of the
report), two errors are measured against a reference, the run at the finest step:

* the **reported extreme** (refined on the exact solution): its value minus the
  reference's, relative to the quantity's peak magnitude, and its input angle minus the
  reference's [°];
  (an extreme reached at several inputs, or on a plateau, has no angle error);
* the **grid peak** (the best sample of the CSV rows, what a plot or the table shows):
  its value minus the reference extreme, relative to the peak.

The time is the analysis plus the JSON results (spec reading excluded), the best of a few
runs.  ``force`` at 0.001° over a turn is 360,001 positions, beyond its 100,001-position
limit (its 1 GiB memory budget): its finest step is 0.005°.

Prints ``name: value unit`` lines and the tables; ``--json`` prints the figures as JSON
(``benchmarks/_figures.py``).  ``--markdown PATH`` also writes the tables into PATH
between the lines ``<!-- bench_accuracy: begin -->`` and ``<!-- bench_accuracy: end -->``
(``docs/accuracy.md`` shows them).

Figure names (stable): ``<case>_step_<s>deg_time`` [ms], ``<case>_step_<s>deg_positions``,
``<case>_step_<s>deg_<q>_<max|min>_grid_error`` and ``..._refined_error`` [1, relative to
the peak], ``<case>_step_<s>deg_worst_grid_error``, ``..._worst_refined_error`` [1] and
``..._worst_refined_at_error`` [deg]; ``<case>`` is ``ex1-1`` or ``ex2-4``.

Usage: python benchmarks/bench_accuracy.py [--quick] [--json] [--markdown docs/accuracy.md]
"""

from __future__ import annotations

import argparse
import datetime
import re
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

STEPS = (10.0, 5.0, 1.0, 0.5, 0.1, 0.01, 0.001)
#: force's finest step over a turn: 0.001° would be 360,001 positions (limit 100,001)
FORCE_FINEST = 0.005
#: a reported extreme whose input differs from the reference's has no angle error when it
#: is the same extreme: on a plateau (the reference's samples over the span between the
#: two inputs, and the nearest one beyond either end, vary by at most PLATEAU_REL of the
#: peak: rounding; MR56 of 例 2-4 is constant while the ram does not cut), or a tie (the
#: values agree within TIE_REL of the peak and the reference's samples between the two
#: inputs fall away from it by more than that: two separate peaks, γC = 90° twice a
#: turn).  Anything else is an angle error, however small.
PLATEAU_REL, TIE_REL = 1e-13, 1e-9
BEGIN, END = "<!-- bench_accuracy: begin -->", "<!-- bench_accuracy: end -->"
_GREEK = {"theta": "θ", "omega": "ω", "alpha": "α", "gamma": "γ"}


def _degrees(q):
    import numpy as np
    return np.degrees(np.asarray(q, dtype=float))


def _kin_case(step):
    """A run of `kin` on 例 1-1 at ``step`` degrees: ``(results, inputs [deg], series)``."""
    from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
    from mechcli.report import kin as report
    from mechcli.spec.kin import load_kin_spec

    spec = load_kin_spec(ROOT / "configs" / "ch1" / "ex1-1.toml", [f"input.step={step}"])
    qs = default_quantities(spec.linkage, spec.output.order, [t.name for t in spec.tracers])

    def once():
        res = analyse_sweep(spec.linkage, spec.input.sweep(), qs, spec.output.order,
                            partial=spec.input.partial)
        return report.scalar_results(spec, qs, res), _degrees(res.q), res.values
    return once


def _force_case(step):
    """A run of `force` on 例 2-4 at ``step`` degrees: ``(results, inputs [deg], series)``."""
    from mechcli.core.linkage.force_analysis import analyse_forces
    from mechcli.report import force as report
    from mechcli.spec.force import load_force_spec

    spec = load_force_spec(ROOT / "configs" / "ch2" / "ex2-4.toml", [f"input.step={step}"])

    def once():
        res = analyse_forces(spec.linkage, spec.topology, spec.input.sweep(), spec.bodies,
                             spec.gravity, spec.loads, partial=spec.input.partial)
        return report.scalar_results(spec, res), _degrees(res.q), res.series
    return once


def timed(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


_GRID = re.compile(r"^(?P<q>.+)_(?P<which>max|min)_grid_error_(?P<unit>.+)$")


def extremes(results):
    """``{"omega3_max": (value, at_deg, grid_error), ...}`` of every reported extreme."""
    out = {}
    for key, grid in results.items():
        m = _GRID.match(key)
        if not m:
            continue
        base = f"{m['q']}_{m['which']}"
        value = results.get(f"{base}_{m['unit']}")
        at = results.get(f"{base}_at_deg")
        if value is not None and at is not None:
            out[base] = (float(value), float(at), float(grid))
    return out


def _peaks(ext):
    """Quantity -> its largest magnitude (max of |max|, |min|)."""
    peak = {}
    for base, (value, _at, _g) in ext.items():
        q = base.rsplit("_", 1)[0]
        peak[q] = max(peak.get(q, 0.0), abs(value))
    return peak


def _at_error(a, b):
    d = abs(a - b) % 360.0
    return min(d, 360.0 - d)   # 0° and 360° are one position of a whole turn


def _between(q_deg, a, b):
    """The samples ``q_deg`` on the shorter arc between inputs ``a`` and ``b`` [deg], with
    the nearest sample beyond either end: ``(indices, inner)``, ``inner`` True for those
    strictly between ``a`` and ``b``."""
    import numpy as np
    q = np.asarray(q_deg, dtype=float)
    start, length = (b, (a - b) % 360.0) if (a - b) % 360.0 <= 180.0 else (a, (b - a) % 360.0)
    off = (q - start) % 360.0
    off = np.where(off > 360.0 - 1e-9, 0.0, off)    # 360° is 0°
    keep = off <= length
    beyond = np.flatnonzero(~keep)
    if beyond.size:   # the nearest sample past the far end, and before the near one
        keep[beyond[np.argmin(off[beyond])]] = True
        keep[beyond[np.argmax(off[beyond])]] = True
    idx = np.flatnonzero(keep)
    return idx, (off[idx] > 0.0) & (off[idx] < length)


def same_extreme(which, rel_diff, at, ref_at, q_deg, series):
    """Is an extreme found at ``at`` [deg] the reference's one at ``ref_at``: a plateau or
    a tie (see ``PLATEAU_REL``, ``TIE_REL``)?  ``rel_diff``: the two values' difference
    relative to the peak; ``q_deg``, ``series``: the reference's samples of the quantity;
    ``which``: ``"max"`` or ``"min"``."""
    import numpy as np
    v = np.asarray(series, dtype=float)
    peak = float(np.max(np.abs(v))) if v.size else 0.0
    if peak == 0.0:
        return True                                        # identically 0: all plateau
    idx, inner = _between(q_deg, at, ref_at)
    if idx.size < 2:
        return False
    span = v[idx]
    if float(np.ptp(span)) <= PLATEAU_REL * peak:
        return True                                        # a plateau
    if rel_diff > TIE_REL or not inner.any():
        return False
    # a tie: between the two inputs the quantity falls away from its extreme by more than
    # TIE_REL (a single smooth peak whose two inputs give values within TIE_REL does not)
    w = span if which == "max" else -span
    return float(np.max(w) - np.min(w[inner])) > TIE_REL * peak


def study(case, make, steps, quick):
    """Run every step; print the figures; return the rows for the tables."""
    runs = {}
    for step in steps:
        once = make(step)
        repeat = 1 if step < 0.01 or quick else 3
        runs[step] = timed(once, repeat)
    ref_res, ref_q, ref_series = runs[steps[-1]][1]
    ref_ext = extremes(ref_res)
    peak = _peaks(ref_ext)
    rows = []
    for step in steps:
        t, (res, _q, _series) = runs[step]
        ext = extremes(res)
        tag = f"{case}_step_{step:g}deg"
        print(f"{tag}_time: {t * 1e3:.1f} ms")
        print(f"{tag}_positions: {res['positions']} 1")
        cells = {}
        worst = {"grid": (0.0, ""), "refined": (0.0, ""), "at": (0.0, "")}
        for base, (value, at, grid) in ext.items():
            rv, rat, _ = ref_ext[base]
            p = peak[base.rsplit("_", 1)[0]] or 1.0
            g = abs(value - grid - rv) / p          # best sample vs the reference extreme
            r = abs(value - rv) / p                 # reported (refined) vs the reference
            a = _at_error(at, rat)
            q_name, which = base.rsplit("_", 1)
            series = ref_series.get(q_name)
            if a > 0 and series is not None and same_extreme(which, r, at, rat, ref_q,
                                                              series):
                a = 0.0   # the same extreme elsewhere (a plateau or a tie): no error
            cells[base] = (g, r)
            print(f"{tag}_{base}_grid_error: {g:.2e} 1")
            print(f"{tag}_{base}_refined_error: {r:.2e} 1")
            for key, val in (("grid", g), ("refined", r), ("at", a)):
                if val >= worst[key][0]:
                    worst[key] = (val, base)
        print(f"{tag}_worst_grid_error: {worst['grid'][0]:.2e} 1 ({worst['grid'][1]})")
        print(f"{tag}_worst_refined_error: {worst['refined'][0]:.2e} 1 ({worst['refined'][1]})")
        print(f"{tag}_worst_refined_at_error: {worst['at'][0]:.2e} deg ({worst['at'][1]})")
        rows.append((step, res["positions"], t, worst, cells))
    return rows


def _label(base):
    q, which = base.rsplit("_", 1)
    for ascii_, letter in _GREEK.items():
        if q.startswith(ascii_):
            q = letter + q[len(ascii_):]
    return f"{q} {which}"


def _num(x):
    return "0" if x == 0 else f"{x:.1e}"


def tables(case, title, rows, finest):
    """The two Markdown tables of one case: per step, then per extreme."""
    out = [f"**{title}** (reference: the run at {finest:g}°)", "",
           "| step | positions | time | reported extremes: worst error (of the peak) | "
           "their input angle: worst error | grid peak: worst error (of the peak) |",
           "|---|---|---|---|---|---|"]
    def cell(key, unit=""):
        val, base = worst[key]
        return f"{_num(val)}{unit} ({_label(base)})" if val else "0"

    for step, n, t, worst, _cells in rows:
        ref = " (reference)" if step == finest else ""
        out.append(f"| {step:g}°{ref} | {n:,} | {t * 1e3:.0f} ms | {cell('refined')} | "
                   f"{cell('at', '°')} | {cell('grid')} |")
    out += ["", "Each extreme: grid peak / reported extreme, errors relative to the peak.", "",
            "| extreme | " + " | ".join(f"{r[0]:g}°" for r in rows) + " |",
            "|---|" + "---|" * len(rows)]
    for base in rows[0][4]:
        out.append(f"| {_label(base)} | " + " | ".join(
            f"{_num(r[4][base][0])} / {_num(r[4][base][1])}" for r in rows) + " |")
    return out


def write_markdown(path, lines):
    """Replace what lies between the markers of *path* by *lines* (the markers stay)."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    if BEGIN not in text or END not in text:
        raise SystemExit(f"{path}: no '{BEGIN}' … '{END}' markers to write the table between")
    head, rest = text.split(BEGIN, 1)
    _old, tail = rest.split(END, 1)
    path.write_text(head + BEGIN + "\n" + "\n".join(lines) + "\n" + END + tail,
                    encoding="utf-8")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="steps 10° … 0.1° only, one run each")
    ap.add_argument("--markdown", metavar="PATH", help="write the tables into PATH between "
                    "its bench_accuracy markers")
    args = ap.parse_args()
    kin_steps = STEPS[:5] if args.quick else STEPS
    force_steps = STEPS[:5] if args.quick else STEPS[:-1] + (FORCE_FINEST,)
    kin_rows = study("ex1-1", _kin_case, kin_steps, args.quick)
    force_rows = study("ex2-4", _force_case, force_steps, args.quick)
    lines = [f"Generated by `python benchmarks/bench_accuracy.py --markdown docs/accuracy.md` "
             f"on {datetime.date.today().isoformat()} (times: one shared, loaded 2-core machine)."
             , ""]
    lines += tables("ex1-1", "【例 1-1】 `kin` (four-bar, ω1 = 250 rad/s)", kin_rows,
                    kin_steps[-1])
    lines += [""]
    lines += tables("ex2-4", "【例 2-4】 `force` (shaper six-bar)", force_rows,
                    force_steps[-1])
    print("\n".join(lines))
    if args.markdown:
        write_markdown(args.markdown, lines)


if __name__ == "__main__":
    run(main)
