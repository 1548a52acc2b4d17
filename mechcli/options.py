"""Options shared by every subcommand (same names everywhere) and the run context."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import click

#: significant digits of CSV numbers unless ``--digits`` says otherwise
DEFAULT_DIGITS = 10
#: ``%.17g`` writes every double so that it reads back bit for bit
EXACT_DIGITS = 17


@dataclasses.dataclass(frozen=True)
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
        No terminal table.
    traceback : bool
        Show the traceback of an internal error.
    sets : tuple of str
        ``KEY=VALUE`` overrides.
    digits : int
        Significant digits of CSV numbers (``--digits``; 17 is round-trip exact).
    """

    spec_path: Path | None
    out_dir: Path
    json: bool = False
    plot: bool = True
    animate: bool | None = None
    lang: str = "en"
    quiet: bool = False
    traceback: bool = False
    sets: tuple = ()
    digits: int = DEFAULT_DIGITS

    @classmethod
    def from_click(cls, spec_path, opts, stem=None):
        spec = Path(spec_path) if spec_path else None
        out = opts.pop("out", None)
        if out is None:
            out = Path("out") / (stem or (spec.stem if spec else "mechcli"))
        return cls(
            spec_path=spec,
            out_dir=Path(out),
            json=opts.pop("json_out", False),
            plot=not opts.pop("no_plot", False),
            animate=opts.pop("animate", None),
            lang=opts.pop("lang", "en"),
            quiet=opts.pop("quiet", False),
            traceback=opts.pop("traceback", False),
            sets=tuple(opts.pop("sets", ()) or ()),
            digits=opts.pop("digits", None) or DEFAULT_DIGITS,
        )

    @property
    def show_table(self):
        return not (self.quiet or self.json)


def common_options(func):
    """Decorate a click command with the options every subcommand shares."""
    opts = [
        click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
                     help="Output directory [default: out/<spec stem>/]."),
        click.option("--json", "json_out", is_flag=True,
                     help="Print scalar results and written files as JSON."),
        click.option("--no-plot", is_flag=True, help="Do not write PNG plots."),
        click.option("--animate/--no-animate", default=None,
                     help="Write (or not) the GIF animation [default: as the spec says]."),
        click.option("--lang", type=click.Choice(["en", "zh"]), default="en", show_default=True,
                     help="Labels in English or the book's Chinese."),
        click.option("--quiet", "-q", is_flag=True, help="No table on the terminal."),
        click.option("--traceback", is_flag=True, help="Show the traceback of internal errors."),
        click.option("--digits", type=click.IntRange(1, EXACT_DIGITS), default=DEFAULT_DIGITS,
                     show_default=True, metavar="N",
                     help="Significant digits of CSV numbers (17: round-trip exact)."),
        click.option("--set", "sets", multiple=True, metavar="KEY=VALUE",
                     help="Override a spec key (dotted path, TOML value); repeatable."),
    ]
    for opt in reversed(opts):
        func = opt(func)
    return func
