"""mechcli in a notebook: DataFrames, book-format tables and the book's 2x2 figure.

Two kinds of result are understood:

* a :class:`LinkageMotion` of :func:`mechcli.solve`, with the linkage it moved
  (``mechcli.to_frame(m, lk)``, ``mechcli.summary(m, lk)``, ``mechcli.plot(m, lk)``);
* a :class:`Result` of :func:`run_spec`: a ``kin``, ``cam`` or ``gear`` spec solved as
  its command solves it, without writing files; it shows itself in a notebook as the
  command's book-format report (``_repr_html_``), ``.to_frame()`` is its CSV and
  ``.plot()`` (``kin``) the figure of ``kin.png``.

Every name comes from the report layer: a DataFrame's columns are the CSV writer's
(:func:`mechcli.report.kin.columns`, :func:`mechcli.report.cam.csv_columns`, the gear
presenters' CSVs), a table's headers the reports' (``θ3/(°)``), the figure is drawn
with :mod:`mechcli.report.kin_plots`' panels.  pandas is optional (``pip install
'mechcli[pandas]'``); matplotlib is imported only by :func:`plot`, on its Agg canvas
(no pyplot).  This module is glue, like ``mechcli.commands``: it may import every layer.
"""

from __future__ import annotations

import functools
import html
import types
from pathlib import Path

#: the commands :func:`run_spec` runs: those with a CSV of rows
COMMANDS = ("kin", "cam", "gear")

#: what to install when pandas is missing
PANDAS_HINT = "pip install 'mechcli[pandas]'"


def _pandas():
    try:
        import pandas
    except ImportError as exc:
        raise ImportError(f"mechcli.to_frame needs pandas, which is not installed: "
                          f"{PANDAS_HINT} (or pip install pandas)", name="pandas") from exc
    return pandas


# -- a spec solved as its command solves it -------------------------------------------------
class _Captured:
    """The part of :class:`mechcli.report.files.Outputs` a presenter writes through,
    kept in memory: ``files[name]`` is ``[(header, values)]`` or CSV text.  17 digits:
    a text CSV's numbers read back as the very floats the presenter had."""

    digits = 17

    def __init__(self):
        self.files = {}

    def csv(self, name, columns, digits=None):
        self.files[name] = list(columns)

    def text(self, name, text):
        self.files[name] = text

    def bytes(self, name, data):   # (pictures are not asked for)
        self.files[name] = data


class Result:
    """A spec solved by :func:`run_spec`.

    Attributes
    ----------
    command : str
        ``kin``, ``cam`` or ``gear``.
    spec : object
        The read spec (SI inside, the file's ``units`` for every output).
    solution : object
        The core's result: a ``SweepResult`` (kin), a ``CamDesign`` (cam), the gear
        problem's solution (gear).
    report : mechcli.report.table.Report
        The book-format report the command prints.
    results : dict
        The ``--json`` results (names with their units).
    warnings : list of str
        The run's warnings.
    files : dict
        CSV file name -> ``[(header, values)]`` or the CSV text, as the command writes
        them (``kin.csv``, ``cam.csv``, ``gear.csv``, ``results.csv``, ...).
    """

    def __init__(self, command, path, spec, solution, report, results, warnings, files,
                 extra=None):
        self.command, self.path, self.spec, self.solution = command, path, spec, solution
        self.report, self.results, self.warnings, self.files = report, results, warnings, files
        self._extra = extra or {}

    @property
    def csv_name(self):
        """The command's main CSV: ``kin.csv``, ``cam.csv``, ``gear.csv`` (``involute.csv``
        for the involute kinds)."""
        return next(n for n in (f"{self.command}.csv", "involute.csv") if n in self.files)

    def to_frame(self, name=None):
        """The CSV *name* (default :attr:`csv_name`) as a pandas DataFrame: the CSV's
        columns, with their units in their names, at full precision."""
        name = name or self.csv_name
        if name not in self.files:
            raise KeyError(f"{Path(self.path).name} writes no {name}; its CSVs: "
                           f"{', '.join(n for n in self.files if n.endswith('.csv'))}")
        return _frame(self.files[name])

    def plot(self, lang="en"):
        """The book's 2x2 figure of a ``kin`` spec (``kin.png``): displacement, velocity,
        acceleration and the mechanism at ``draw_at``; a matplotlib Figure."""
        if self.command != "kin":
            raise ValueError(f"plot draws kin results (the book's 2x2 figure); the pictures "
                             f"of {self.command}: mechcli {self.command} {self.path}")
        from mechcli.core.linkage import solve
        from mechcli.report import run as run_state

        spec, res = self.spec, self.solution
        run_state.begin(Path(self.path).stem)   # a title without CJK falls back to it
        pose = solve(spec.linkage, spec.input.sweep().inputs([spec.output.draw_at]), order=0)
        return _kin_figure(spec, self._extra["quantities"], res, (pose, 0), lang)

    def _repr_html_(self):
        return report_html(self.report)

    def __str__(self):
        from mechcli.report.table import render_text
        return render_text(self.report)

    def __repr__(self):
        rows = _rows(self.files.get(self.csv_name))
        return (f"<mechcli {self.command} result of {Path(self.path).name}: {self.csv_name}"
                f"{f', {rows} rows' if rows is not None else ''}>")


def run_spec(path, *sets, lang="en"):
    """Solve the ``kin``, ``cam`` or ``gear`` spec *path* as ``mechcli COMMAND`` does
    (with ``--set`` overrides *sets*, ``"KEY=VALUE"``), without writing a file.

    Returns a :class:`Result`.  A bad spec raises ``SpecError``, an unsolvable problem
    ``UnsolvableError`` (or ``AssemblyError``), with the command's one-line message."""
    from mechcli.spec.errors import SpecError
    from mechcli.spec.reader import load_spec

    path = str(path)
    command = load_spec(path, sets).data.get("command")
    if command not in COMMANDS:
        raise SpecError(path, "command", f"one of {', '.join(COMMANDS)} (run_spec runs the "
                        f"commands that write a CSV of rows)", repr(command))
    return {"kin": _run_kin, "cam": _run_cam, "gear": _run_gear}[command](path, sets, lang)


def _run_kin(path, sets, lang):
    """``mechcli kin``'s steps (mechcli/commands/kin.py) without its files."""
    from mechcli.core.errors import AssemblyError
    from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
    from mechcli.report import kin as report
    from mechcli.spec.kin import load_kin_spec

    spec = load_kin_spec(path, sets)   # past the in-memory limit: refused (no streaming)
    sweep = spec.input.sweep()
    quantities = default_quantities(spec.linkage, spec.output.order,
                                    [t.name for t in spec.tracers])
    try:
        result = analyse_sweep(spec.linkage, sweep, quantities, spec.output.order,
                               partial=spec.input.partial)
    except AssemblyError as exc:
        raise AssemblyError(report.assembly_message(spec, exc), exc.intervals) from None
    approx = None
    if spec.mechanism == "slider_crank" and spec.model == "approximate":
        from mechcli.core.linkage import approximate
        result, approx = approximate.apply(spec.linkage, sweep, result)
    return Result("kin", path, spec, result,
                  report.build_report(spec, quantities, result, lang, approx),
                  report.scalar_results(spec, quantities, result, None, approx),
                  report.warnings(spec, result),
                  {"kin.csv": report.columns(spec, quantities, result)},
                  {"quantities": quantities})


def _run_cam(path, sets, lang):
    """``mechcli cam``'s steps (mechcli/report/cam.cam_report) without its files."""
    from mechcli.commands.cam import design_of
    from mechcli.report import cam as report
    from mechcli.spec.cam import read_cam_spec
    from mechcli.spec.reader import load_spec

    cs = read_cam_spec(load_spec(path, sets), None, None)
    design = design_of(cs)
    return Result("cam", path, cs, design, report.build_report(cs, design, lang),
                  report.results_dict(cs, design), report.warnings_for(cs, design, lang),
                  {"cam.csv": report.csv_columns(cs, design)})


def _run_gear(path, sets, lang):
    """``mechcli gear``'s steps (mechcli/commands/gear.py), its files kept in memory."""
    from mechcli.core.gear.problems import solve_gear
    from mechcli.core.gear.spur import GearError
    from mechcli.report import gear as report
    from mechcli.spec.errors import SpecError
    from mechcli.spec.gear import read_gear_spec

    spec = read_gear_spec(path, sets)
    try:
        solution = solve_gear(spec.kind, spec.problem)
    except GearError as exc:
        if exc.reason == "mounting":
            raise SpecError(path, *report.mounting_error(spec, exc)) from None
        exc.args = (report.error_message(exc),)
        raise
    warnings = report.enforce(spec, solution)
    out = _Captured()
    run = types.SimpleNamespace(lang=lang, plot=False, animate=False)
    rep, results, more = report.present(spec, solution, run, out)
    return Result("gear", path, spec, solution, rep, results, warnings + more, out.files)


# -- a LinkageMotion of mechcli.solve ----------------------------------------------------------
def _length_scale(unit):
    from mechcli.spec.reader import LENGTH_UNITS
    if unit not in LENGTH_UNITS:
        raise ValueError(f"unit must be one of {', '.join(LENGTH_UNITS)}, got {unit!r}")
    return LENGTH_UNITS[unit]


def _kin_of_motion(m, linkage, unit="m", tracers=None):
    """``(spec, quantities, result)`` of a motion as ``mechcli kin`` would name them: a
    spec-like namespace (the fields the report helpers read), the book's quantities and
    a sweep-result-like namespace over the regular positions (kin.csv's rows), angles
    continuous along every run of them as in kin.csv."""
    import numpy as np

    from mechcli.core.linkage import LinkageMotion, PointOnLink
    from mechcli.core.linkage.sweep import _take, _unwrap_runs, default_quantities
    from mechcli.core.numerics import true_runs

    if not isinstance(m, LinkageMotion):
        raise TypeError(f"expected a LinkageMotion of mechcli.solve or a result of "
                        f"mechcli.run_spec, got {type(m).__name__}")
    if linkage is None:
        raise TypeError("a LinkageMotion needs the linkage it moved to be named as kin.csv "
                        "names it: to_frame(m, linkage)")
    shape = np.shape(m.regular)
    if len(shape) > 1 or linkage.shape != ():
        raise ValueError(f"one design at a time: this motion has the shape {shape} (a batch "
                         f"of designs); solve the design you want on its own")
    scale = _length_scale(unit)
    regular = np.reshape(m.regular, -1)
    drv = linkage.drivers[0]
    if drv.rotary:
        q = m.links[drv.link].theta
    else:
        q = m.slides[drv.slide_names(linkage.frame)[0]].s
    if tracers is None:   # the points put on links (kin's [[mechanism.point]])
        tracers = [el.name for el in linkage.elements if isinstance(el, PointOnLink)]
    quantities = default_quantities(linkage, m.order, list(tracers))
    idx = np.flatnonzero(regular)
    full = idx.size == regular.size

    def rows(v):
        v = np.reshape(np.broadcast_to(np.asarray(v, dtype=float), shape), -1)
        return v if full else v[idx]

    lengths = [int(b - a) for a, b in true_runs(regular)]   # the runs, among the rows kept
    ends = np.cumsum(lengths, dtype=int)
    runs = [(int(e - n), int(e)) for n, e in zip(lengths, ends)]
    # kin's rule (InputSpec.periodic, kinematics._grid_runs): a sweep of whole turns of
    # every driver, regular at both ends, continues from its last run into its first
    def whole_turns(el):
        if not el.rotary:
            return False
        x = np.reshape(np.broadcast_to(m.links[el.link].theta, shape), -1)
        turns = (x[-1] - x[0]) / (2 * np.pi) if x.size > 1 else 0.0
        return abs(turns - round(turns)) < 1e-9 and round(turns) >= 1

    connected = (len(runs) > 1 and bool(regular[0] and regular[-1])
                 and all(whole_turns(el) for el in linkage.drivers))
    values = {}
    for qt in quantities:
        v = rows(qt.get(m))
        values[qt.symbol] = _unwrap_runs(v, runs, connected) if qt.is_angle and runs else v
    q_rows = rows(q)
    motion = m if full or not shape else _take(m, idx)
    result = types.SimpleNamespace(q=q_rows, values=values, runs=runs, motion=motion)
    start, stop = (float(q_rows[0]), float(q_rows[-1])) if q_rows.size else (0.0, 0.0)
    spec = types.SimpleNamespace(
        header=types.SimpleNamespace(title="", unit=unit, scale=scale),
        input=types.SimpleNamespace(driver=drv.link, rotary=drv.rotary, start=start,
                                    stop=stop),
        output=types.SimpleNamespace(draw_at=start, digits=4),
        linkage=linkage, tracers=tuple(types.SimpleNamespace(name=t) for t in tracers),
        guide_length=None)
    return spec, quantities, result


def _frame(columns):
    pd = _pandas()
    if isinstance(columns, str):
        import io
        return pd.read_csv(io.StringIO(columns))
    return pd.DataFrame({h: v for h, v in columns})


def _rows(columns):
    if columns is None:
        return None
    if isinstance(columns, str):
        return columns.count("\n") - 1
    return len(columns[0][1]) if columns else 0


def to_frame(result, linkage=None, *, name=None, unit="m", tracers=None):
    """A result as a pandas DataFrame with the columns of its CSV.

    Parameters
    ----------
    result : Result or LinkageMotion
        A :func:`run_spec` result (its CSV *name*, default ``kin.csv``, ``cam.csv``,
        ``gear.csv``), or a motion of :func:`mechcli.solve` of one design with the
        *linkage* it moved: kin.csv's columns and rows (the regular positions; the input
        ``theta1_deg`` first, angles in degrees, continuous along each run of positions),
        lengths in *unit* (``m``, ``mm``, ``cm``, ``in``), the points on links (or
        *tracers*) traced.

    Raises
    ------
    ImportError
        pandas is not installed (``pip install 'mechcli[pandas]'``).
    """
    if isinstance(result, Result):
        return result.to_frame(name)
    from mechcli.report import kin as report

    spec, quantities, res = _kin_of_motion(result, linkage, unit, tracers)
    pd = _pandas()
    return pd.DataFrame(dict(report.columns(spec, quantities, res)))


# -- book-format tables --------------------------------------------------------------------
class Summary:
    """A book-format report that shows itself in a notebook (``_repr_html_``) and as
    the text ``report.txt`` holds (``str``)."""

    def __init__(self, report):
        self.report = report

    def _repr_html_(self):
        return report_html(self.report)

    def __str__(self):
        from mechcli.report.table import render_text
        return render_text(self.report)

    __repr__ = __str__


def summary(result, linkage=None, *, unit="m", tracers=None, step=None, digits=4,
            lang="en"):
    """The book-format table of a result (a :class:`Summary`).

    A :func:`run_spec` result: the command's whole report.  A motion of
    :func:`mechcli.solve` with its *linkage*: kin's results table (headers ``θ3/(°)``,
    ``ω3/(rad/s)``, lengths in *unit*), a row every *step* of the input [rad, or m for
    a slider input] (default 30°, or a tenth of the stroke), *digits* decimals."""
    if isinstance(result, Result):
        return Summary(result.report)
    import math

    import numpy as np

    from mechcli.report import kin as report
    from mechcli.report.table import Block, Report

    spec, quantities, res = _kin_of_motion(result, linkage, unit, tracers)
    zh = lang == "zh"
    inp = spec.input
    if step is None:
        step = math.radians(30.0) if inp.rotary else (inp.stop - inp.start) / 10
    cols = report.columns(spec, quantities, res)
    if res.q.size > 1 and inp.stop > inp.start and step > 0:
        idx = report.table_rows(spec, res, step)
    else:
        idx = np.arange(res.q.size)
    rows = [[report.fixed(cols[0][1][i], 2)] + [report.fixed(c[1][i], digits) for c in cols[1:]]
            for i in idx]
    headers = [report.input_header(spec, zh)] + [report.quantity_label(q, unit, lang)
                                                 for q in quantities]
    fin = report.input_factor(spec)
    where = (f"every {step * fin:g}{report.input_suffix(spec)}, lengths in {unit}" if not zh
             else f"每 {step * fin:g}{report.input_suffix(spec)} 一行，长度单位 {unit}")
    n, total = res.q.size, int(np.size(result.regular))
    notes = [f"{total} 个位置中 {n} 个正常" if zh else f"{n} of {total} positions regular"]
    heading = ("Results" if not zh else "计算结果") + f" ({where})"
    return Summary(Report("Kinematics" if not zh else "运动分析",
                          [Block(heading, headers, rows)], notes))


def report_html(report):
    """HTML of a :class:`~mechcli.report.table.Report`: its title, one table per block
    (a key/value block as two columns), its notes; cells as the text report prints
    them (numbers right-aligned, no minus sign on a zero)."""
    from mechcli.report.table import plain_zeros

    report = plain_zeros(report)
    esc = html.escape
    out = ['<div class="mechcli-report">']
    if report.title:
        out.append(f"<p><strong>{esc(report.title)}</strong></p>")
    for block in report.blocks:
        out.append('<table class="mechcli-table">')
        if block.heading:
            out.append(f'<caption style="text-align:left"><strong>{esc(block.heading)}'
                       "</strong></caption>")
        if block.headers:
            out.append("<thead><tr>" + "".join(f"<th>{esc(str(h))}</th>" for h in block.headers)
                       + "</tr></thead>")
        out.append("<tbody>")
        for row in block.rows:
            align = "right" if block.headers else "left"
            out.append("<tr>" + "".join(f'<td style="text-align:{align}">{esc(str(c))}</td>'
                                        for c in row) + "</tr>")
        out.append("</tbody></table>")
    for note in report.notes:
        out.append(f"<p>{esc(str(note))}</p>")
    out.append("</div>")
    return "\n".join(out)


# -- the book's 2x2 figure ---------------------------------------------------------------
def plot(result, linkage=None, *, unit="m", tracers=None, draw_at=None, lang="en"):
    """The book's 2x2 figure of a kinematic result (``kin.png``): displacement,
    velocity and acceleration against the input, and the mechanism.

    *result* is a ``kin`` :func:`run_spec` result (the mechanism at the spec's
    ``draw_at``), or a motion of :func:`mechcli.solve` with its *linkage* (lengths in
    *unit*; the mechanism at the regular position nearest the input *draw_at* [rad or
    m], default the first).  Returns a :class:`matplotlib.figure.Figure` on the Agg
    canvas (no pyplot: a notebook shows it, ``fig.savefig`` writes it)."""
    if isinstance(result, Result):
        return result.plot(lang)
    import numpy as np

    spec, quantities, res = _kin_of_motion(result, linkage, unit, tracers)
    if np.ndim(result.regular) == 0 or res.q.size == 0:
        raise ValueError("nothing to plot: a sweep of positions is needed, and the linkage "
                         "is regular at none of these")
    i = 0 if draw_at is None else int(np.argmin(np.abs(res.q - draw_at)))
    spec.output.draw_at = float(res.q[i])
    return _kin_figure(spec, quantities, res, (res.motion, i), lang)


def _kin_figure(spec, quantities, result, pose, lang):
    """``kin.png``'s figure (:func:`mechcli.report.kin_plots.write`'s panels) posed at
    ``pose = (motion, index)``; matplotlib's settings changed only while it is made."""
    import matplotlib
    import numpy as np

    from mechcli.report import kin_plots, plotting
    from mechcli.report.kin import input_factor

    with matplotlib.rc_context():
        used = plotting.setup(lang)
        t = kin_plots._TITLES[used]
        unit, scale = spec.header.unit, spec.header.scale
        fin = input_factor(spec)
        x = result.q * fin
        k = 1 / scale
        groups = kin_plots._groups(quantities)
        fig, axs = plotting.subplots(2, 2, figsize=(11, 8.5))
        for ax, order, title in zip(axs.flat[:3], (0, 1, 2), (t["disp"], t["vel"], t["acc"])):
            ax.set_title(title, pad=22, y=1.0)
            ax.set_xlabel(kin_plots.input_label(spec, t))
            if groups[order]:
                kin_plots._plot_group(ax, spec, result, groups[order], x, t)
                ax.set_xlim(float(np.min(x)), float(np.max(x)))
            else:
                ax.set_visible(False)
        ax = axs[1, 1]
        motion, i = pose
        if bool(np.reshape(motion.regular, -1)[i]):
            d = kin_plots.Drawing(ax, spec.linkage, result.motion, scale, spec.guide_length)
            d.update(motion, i)
        for j, tr in enumerate(spec.tracers):
            p = kin_plots.broken(result, result.motion.points[tr.name].p * k)
            ax.plot(p.real, p.imag, ":", lw=1.2, color=f"C{(3 + j) % 10}",
                    label=t["path"].format(name=tr.name))
        kin_plots.limits(ax, result.motion, k)
        if spec.tracers:
            ax.legend(fontsize=7, loc="best")
        at = spec.output.draw_at * fin
        sym = plotting.symbol(f"theta{spec.input.driver}")
        ax.set_title(f"{t['mech']} {sym} = {at:g}°" if spec.input.rotary else t["mech"],
                     pad=22, y=1.0)
        ax.set_xlabel(f"x / {unit}")
        ax.set_ylabel(f"y / {unit}")
        if spec.header.title:
            fig.suptitle(plotting.title(spec.header.title), wrap=True)
        fig.subplots_adjust(left=0.08, right=0.92, bottom=0.07, top=0.885, wspace=0.5,
                            hspace=0.45)
    # a notebook shows the figure as a PNG even where pyplot's inline backend is not set up
    fig._repr_png_ = functools.partial(_png, fig)
    return fig


def _png(fig, dpi=100):
    """The figure as PNG bytes, cropped to its ink (what a notebook shows)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    return buf.getvalue()
