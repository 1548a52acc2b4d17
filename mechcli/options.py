"""Options shared by every subcommand (same names everywhere) and the run context."""

from __future__ import annotations

import re
from pathlib import Path

import click

from mechcli.core.records import record

#: significant digits of CSV numbers unless ``--digits`` says otherwise
DEFAULT_DIGITS = 10
#: ``%.17g`` writes every double so that it reads back bit for bit
EXACT_DIGITS = 17
#: resolution of PNG pictures unless ``--dpi`` says otherwise (print quality)
DEFAULT_DPI = 200


@record
class RunOptions:
    """What the user asked of one run, independent of the command.

    Attributes
    ----------
    spec_path : Path or None
        The problem file (None for file-less quick forms).
    out_dir : Path
        Output directory (default ``out/<spec stem>/``).
    json : bool
        Print scalar results and written paths as JSON on stdout.
    plot : bool
        Write PNG plots (``--no-plot`` turns them off).
    animate : bool or None
        Write a GIF; None means "as the spec says".
    lang : str
        ``en`` or ``zh`` labels.
    quiet : bool
        No terminal table (and no progress bar).
    verbose : bool
        ``-v``: a line on stderr per step of long work (an atlas chunk, a
        generation, a streamed chunk), besides the progress bar of a terminal.
    traceback : bool
        Show the traceback of an internal error.
    sets : tuple of str
        ``KEY=VALUE`` overrides.
    digits : int
        Significant digits of CSV numbers (``--digits``; 17 is round-trip exact).
    columns : tuple of str
        ``--columns``: the only table columns shown (after each table's first).
    dpi : int
        ``--dpi``: resolution of the PNG pictures (the plots read it through
        :func:`mechcli.report.plotting.dpi`).
    export : tuple of str
        ``--export``: the CAD formats to write (``"dxf"``, ``"svg"``; see
        :mod:`mechcli.report.cad`); empty for none and for the commands without it.
    """

    spec_path: Path | None
    out_dir: Path
    json: bool = False
    plot: bool = True
    animate: bool | None = None
    lang: str = "en"
    quiet: bool = False
    verbose: bool = False
    traceback: bool = False
    sets: tuple = ()
    digits: int = DEFAULT_DIGITS
    columns: tuple = ()
    dpi: int = DEFAULT_DPI
    export: tuple = ()

    @classmethod
    def from_click(cls, spec_path, opts, stem=None):
        from mechcli.report import run as report_run

        spec = Path(spec_path) if spec_path else None
        out = opts.pop("out", None)
        sets = tuple(opts.get("sets", ()) or ())
        name = stem or (spec.stem if spec else "mechcli")
        report_run.begin(spec.stem if spec else name, opts.get("dpi"))
        if out is not None and not str(out).strip():
            # an empty --out would write into the working folder: say so, never guess
            import click
            raise click.BadParameter("expected a folder, got an empty path", param_hint="--out")
        if out is None:
            out = Path("out") / default_dir_name(name, sets, None if spec else _quick_form())
        return cls(
            spec_path=spec,
            out_dir=Path(out),
            json=opts.pop("json_out", False),
            plot=not opts.pop("no_plot", False),
            animate=opts.pop("animate", None),
            lang=opts.pop("lang", "en"),
            quiet=opts.pop("quiet", False),
            verbose=opts.pop("verbose", False),
            traceback=opts.pop("traceback", False),
            sets=tuple(opts.pop("sets", ()) or ()),
            digits=opts.pop("digits", None) or DEFAULT_DIGITS,
            columns=tuple(c.strip() for c in (opts.pop("columns", None) or "").split(",")
                          if c.strip()),
            dpi=opts.pop("dpi", None) or DEFAULT_DPI,
            export=tuple(opts.pop("export", None) or ()),
        )

    @property
    def show_table(self):
        return not (self.quiet or self.json)

    def problem_data(self):
        """The spec's tables as this run solved them (the file with the ``--set``
        overrides applied), for ``report.txt``'s given data; None without a spec file
        or when it cannot be read again."""
        if self.spec_path is None:
            return None
        from mechcli.spec.errors import SpecError
        from mechcli.spec.reader import load_spec

        try:
            return load_spec(self.spec_path, self.sets).data
        except (SpecError, OSError):
            return None


#: the characters a default output folder's name keeps from the quick-form values
_PLAIN = re.compile(r"[^A-Za-z0-9.+-]+")
#: a longer derived name is replaced by a hash (file systems allow 255 bytes)
_NAME_MAX = 64


def _short_hash(parts):
    import hashlib  # only for --set and long quick forms: not on every start-up

    return hashlib.sha256("\0".join(parts).encode("utf-8")).hexdigest()[:8]


def default_dir_name(stem, sets=(), quick=None):
    """The folder under ``out/`` a run writes to without ``--out``.

    A spec run writes ``<stem>``; with ``--set`` overrides ``<stem>+<hash>``, the
    first 8 hex digits of the SHA-256 of the overrides, so a sweep never overwrites
    the base run nor another point of the sweep; a run without a spec file
    (``grashof --lengths 28,52,50,72``) names its folder after the values given,
    ``grashof-28_52_50_72`` (or a hash of them when that is long).

    Parameters
    ----------
    stem : str
        The spec's stem, or the command's name for a file-less run.
    sets : sequence of str
        The ``--set KEY=VALUE`` overrides, in order.
    quick : sequence of (str, object) or None
        The quick-form options of a file-less run: option name, value.
    """
    name = stem
    if quick:
        parts = [_PLAIN.sub("_", str(v)).strip("_") if k == "lengths" else
                 _PLAIN.sub("_", f"{k}{v}").strip("_") for k, v in quick]
        tail = "-".join(p for p in parts if p)
        if tail:
            name += "-" + (tail if len(tail) <= _NAME_MAX else
                           _short_hash([f"{k}={v}" for k, v in quick]))
    sets = [s.strip() for s in sets]
    if sets:
        name += "+" + _short_hash(sets)
    return name


def _quick_form():
    """``[(option, value)]`` of the command's own options that were given (the quick
    form of a file-less run), from the click context; [] outside one."""
    ctx = click.get_current_context(silent=True)
    if ctx is None:
        return []
    shared = {"out", "json_out", "no_plot", "animate", "lang", "quiet", "verbose", "traceback",
              "digits", "sets", "columns", "dpi", "export"}
    given = []
    for param in ctx.command.params:
        value = ctx.params.get(param.name)
        if param.name in shared or value in (None, False, (), "") \
                or not isinstance(param, click.Option):
            continue
        if ctx.get_parameter_source(param.name) != click.core.ParameterSource.COMMANDLINE:
            continue
        long = next((o for o in param.opts if o.startswith("--")), param.name)
        given.append((long.lstrip("-"), value))
    return given


#: the formats of ``--export`` (mechcli.report.cad writes them)
EXPORT_FORMATS = ("dxf", "svg")


class ExportFormats(click.ParamType):
    """``--export dxf,svg``: a comma-separated list of CAD formats, checked when the
    command line is parsed (before anything is read, computed or written): an unknown
    format, or DXF without the ``cad`` extra (ezdxf), is a usage error (exit 2) naming
    the option.  The value is a tuple of formats in the order given, each once."""

    name = "formats"

    def convert(self, value, param, ctx):
        if isinstance(value, tuple):
            return value
        given = [v.strip().lower() for v in str(value).split(",")]
        bad = [v for v in given if v not in EXPORT_FORMATS]
        if bad or not given:
            self.fail(f"expected {', '.join(EXPORT_FORMATS)} or both (dxf,svg), "
                      f"got {value!r}", param, ctx)
        if "dxf" in given:
            import importlib.util  # found, not imported: ezdxf loads only when it writes
            if importlib.util.find_spec("ezdxf") is None:
                self.fail("DXF needs ezdxf, the cad extra: pip install 'mechcli[cad]' "
                          "(or --export svg)", param, ctx)
        return tuple(dict.fromkeys(given))


def export_option(func):
    """``--export dxf,svg``: the drawn geometry as CAD files (the commands that draw
    geometry: cam, gear, kin, force, synth, optimize; docs/cad.md)."""
    return click.option("--export", "export", type=ExportFormats(), default=None,
                        metavar="dxf,svg",
                        help="Also write the drawn geometry as CAD files: DXF (the cad "
                             "extra, ezdxf) and/or SVG, in the spec's units "
                             "(docs/cad.md).")(func)


def common_options(func):
    """Decorate a click command with the options every subcommand shares (and show the
    report layer's :class:`~mechcli.report.run.RunUsageError` as click's usage error:
    exit 2, the command's name before the message)."""
    func = _usage_errors(func)
    opts = [
        click.option("--out", "-o", "out", type=click.Path(file_okay=False),
                     default=None,
                     help="Output directory [default: out/<spec stem>/, "
                          "out/<spec stem>+<hash of the --set values>/ with --set]."),
        click.option("--json", "json_out", is_flag=True,
                     help="Print scalar results and written files as JSON."),
        click.option("--no-plot", is_flag=True, help="Do not write PNG plots."),
        click.option("--animate/--no-animate", default=None,
                     help="Write (or not) the GIF animation [default: as the spec says]."),
        click.option("--lang", type=click.Choice(["en", "zh"]), default="en", show_default=True,
                     help="Labels in English or the book's Chinese."),
        click.option("--quiet", "-q", is_flag=True, help="No table on the terminal."),
        click.option("--verbose", "-v", is_flag=True,
                     help="Detail of long work on stderr (a line per atlas chunk, "
                          "generation or streamed chunk)."),
        click.option("--traceback", is_flag=True, help="Show the traceback of internal errors."),
        click.option("--digits", type=click.IntRange(1, EXACT_DIGITS), default=DEFAULT_DIGITS,
                     show_default=True, metavar="N",
                     help="Significant digits of CSV numbers (17: round-trip exact)."),
        click.option("--columns", metavar="COL,COL",
                     help="Only these columns in the tables (terminal and report.txt), "
                          "e.g. theta3,omega3; the CSV keeps every column."),
        click.option("--dpi", type=click.IntRange(20, 1200), default=DEFAULT_DPI,
                     show_default=True, metavar="N", help="Resolution of the PNG pictures."),
        click.option("--set", "sets", multiple=True, metavar="KEY=VALUE",
                     help="Override a spec key (dotted path, TOML value); repeatable."),
    ]
    for opt in reversed(opts):
        func = opt(func)
    return func


def _usage_errors(func):
    """*func* raising click's ``UsageError`` for the report layer's ``RunUsageError``."""
    import functools

    @functools.wraps(func)
    def run(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except ValueError as exc:
            from mechcli.report.run import RunUsageError
            if isinstance(exc, RunUsageError):
                raise click.UsageError(str(exc)) from None
            raise
    return run
