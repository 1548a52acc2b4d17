"""Book-format text tables (``report.txt``) and their rich rendering.

A :class:`Report` is a title, a list of :class:`Block` (a heading plus either a
table or key/value lines) and notes.  ``render_text`` gives the plain text the
book prints; ``print_rich`` shows the same on a terminal through rich.
"""

from __future__ import annotations

import dataclasses
import unicodedata


@dataclasses.dataclass
class Block:
    """One section of a report.

    Attributes
    ----------
    heading : str
        Section title (already in the chosen language).
    headers : list of str
        Column headers for a table block (empty for a key/value block).
    rows : list of list of str
        Formatted cells; for a key/value block, rows of ``[label, value]``.
    """

    heading: str
    headers: list = dataclasses.field(default_factory=list)
    rows: list = dataclasses.field(default_factory=list)


@dataclasses.dataclass
class Report:
    title: str
    blocks: list = dataclasses.field(default_factory=list)
    notes: list = dataclasses.field(default_factory=list)


def display_width(text):
    """Terminal columns taken by *text* (CJK characters count two)."""
    return sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in text)


def _pad(text, width, left=False):
    gap = max(0, width - display_width(text))
    return text + " " * gap if left else " " * gap + text


def render_text(report: Report) -> str:
    """Plain-text report as written to ``report.txt``."""
    out = [report.title, "=" * max(20, display_width(report.title)), ""]
    for block in report.blocks:
        if block.heading:
            out.append(block.heading)
        if block.headers:
            widths = [max(display_width(h), *(display_width(r[i]) for r in block.rows))
                      if block.rows else display_width(h) for i, h in enumerate(block.headers)]
            out.append("  ".join(_pad(h, w) for h, w in zip(block.headers, widths)))
            out.append("  ".join("-" * w for w in widths))
            for row in block.rows:
                out.append("  ".join(_pad(c, w) for c, w in zip(row, widths)))
        else:
            lw = max((display_width(r[0]) for r in block.rows), default=0)
            for row in block.rows:
                out.append(f"  {_pad(row[0], lw, left=True)}  {row[1]}")
        out.append("")
    for note in report.notes:
        out.append(note)
    return "\n".join(out).rstrip() + "\n"


def print_rich(report: Report, file=None):
    """Show the report on the terminal with rich tables."""
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    natural = max((display_width(line) for line in render_text(report).splitlines()), default=80)
    probe = Console(file=file)
    # never squeeze numbers: widen past the terminal rather than truncate cells
    console = Console(file=file, highlight=False, width=max(probe.width, natural + 4 * max(
        (len(b.headers) for b in report.blocks), default=0) + 4))
    # every text is the user's or ours, never rich markup: a title "door [/bold]" is text
    console.print(f"[bold]{escape(report.title)}[/bold]")
    for block in report.blocks:
        # a table at least as wide as its heading: rich wraps a title to the table's width
        wide = display_width(block.heading) + 2 if block.heading else None
        if block.headers:
            table = Table(title=escape(block.heading) or None, title_justify="left",
                          min_width=wide)
            for h in block.headers:
                table.add_column(escape(h), justify="right", no_wrap=True)
            for row in block.rows:
                table.add_row(*map(escape, row))
        else:
            table = Table(title=escape(block.heading) or None, title_justify="left",
                          show_header=False, min_width=wide)
            table.add_column(justify="left")
            table.add_column(justify="right")
            for row in block.rows:
                table.add_row(*map(escape, row))
        console.print(table)
    for note in report.notes:
        console.print(note, markup=False)
