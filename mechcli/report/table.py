"""Book-format text tables (``report.txt``) and their rich rendering.

A :class:`Report` is a title, a list of :class:`Block` (a heading plus either a
table or key/value lines) and notes.  ``render_text`` gives the plain text the
book prints; ``print_rich`` shows the same on a terminal through rich.

Wide tables are split as the book splits them: into blocks that each repeat the
first column (the input angle) and hold whole groups of columns -- positions,
velocities, accelerations (told apart by the unit: ``/s``, ``/s²``), the reaction
of one joint (``FR16x``, ``FR16y``, ``FR16``, ``MR16``) -- each block fitting
the width: :data:`REPORT_WIDTH` in ``report.txt``, the terminal's on screen
(:func:`terminal_width`).  :func:`select_columns` keeps only the columns a user
names (``--columns theta3,omega3``).  Everything else fits the same width by
wrapping (:func:`wrap`): titles, headings, notes, and the rows of a key/value block,
whose long values go on under the value column (:func:`kv_layout`).
"""

from __future__ import annotations

import dataclasses
import os
import re
import sys
import unicodedata

from mechcli.core.records import record

#: the widest line of a table in ``report.txt`` (a page, a projector, a diff)
REPORT_WIDTH = 100
#: the terminal width when stdout is not a terminal and ``COLUMNS`` is not set
DEFAULT_WIDTH = 80


@record(frozen=False)
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


@record(frozen=False)
class Report:
    title: str
    blocks: list = dataclasses.field(default_factory=list)
    notes: list = dataclasses.field(default_factory=list)



#: the title of a worked example of the book: 例 1-1 ... -> 【例 1-1】 ...
_EXAMPLE_TITLE = re.compile(r"^\s*例\s*(\d+)\s*[-‐–]\s*(\d+)\s*")


def book_title(title):
    """*title* with the book's label of a worked example in the book's brackets:
    ``例 5-3 标准齿轮`` -> ``【例 5-3】 标准齿轮``; any other title unchanged (every
    command's report)."""
    m = _EXAMPLE_TITLE.match(title or "")
    if not m:
        return title
    rest = title[m.end():]
    return f"【例 {m.group(1)}-{m.group(2)}】" + (f" {rest}" if rest else "")


def unit_header(symbol, unit, name=""):
    """A header or label in the book's notation: ``θ1/(°)``, ``H/(mm)``; with a
    *name* first, ``极位夹角 θ/(°)``; a dimensionless quantity (unit ``""``) has none."""
    text = symbol if unit in ("", "1") else f"{symbol}/({unit})"
    return f"{name} {text}" if name else text

#: the minus sign of a number that prints as zero (``-0``, ``-0.000``, ``-0.00e+00``,
#: ``-0.000mm``), not part of a word or a difference (``x-0.5``, ``5-0``)
_NEGATIVE_ZERO = re.compile(r"(?<![\w.)\]-])-(?=0(?:\.0*)?(?:[eE][+-]?\d+)?(?![\d.]))")


def zero_sign(text):
    """*text* with every number that prints as zero written without a minus sign: a
    value that rounds to zero at the printed digits (a backlash of -2e-17 mm printed
    ``-0.000``) is 0 in a table, whatever its sign before rounding."""
    return _NEGATIVE_ZERO.sub("", text) if isinstance(text, str) and "-0" in text else text


def plain_zeros(report):
    """*report* with :func:`zero_sign` applied to every cell, heading and note (the
    title is the user's text): what every table shows, on a terminal, in a pipe and
    in ``report.txt``.  CSV and JSON keep the values as they are."""
    def fix(rows):
        return [[zero_sign(c) for c in row] for row in rows]

    return Report(report.title,
                  [Block(zero_sign(b.heading), list(b.headers), fix(b.rows))
                   for b in report.blocks],
                  [zero_sign(n) for n in report.notes])


def display_width(text):
    """Terminal columns taken by *text* (CJK characters count two, a combining mark
    such as the bar of ``s̄`` none)."""
    if text.isascii():   # most cells: numbers
        return len(text)
    return sum(0 if unicodedata.combining(c) else
               2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in text)


def _pad(text, width, left=False):
    gap = max(0, width - display_width(text))
    return text + " " * gap if left else " " * gap + text


def terminal_width(stream=None):
    """Columns of the terminal: ``COLUMNS`` when set, the terminal's own width when
    *stream* (stdout) is one, else :data:`DEFAULT_WIDTH`."""
    env = os.environ.get("COLUMNS", "")
    if env.strip().isdigit() and int(env) > 0:
        return int(env)
    stream = sys.stdout if stream is None else stream
    try:
        if stream.isatty():
            return os.get_terminal_size(stream.fileno()).columns
    except (AttributeError, OSError, ValueError):
        pass
    return DEFAULT_WIDTH


#: Greek symbols of the headers and the names a user types for them
_GREEK = {"θ": "theta", "ω": "omega", "α": "alpha", "γ": "gamma", "δ": "delta", "φ": "phi",
          "ψ": "psi", "ε": "epsilon", "β": "beta", "μ": "mu", "τ": "tau", "ρ": "rho"}


def column_symbol(header):
    """The symbol of a column header: ``theta3`` of ``theta3/°`` or ``θ3/(°)``,
    ``FR16x`` of ``FR16x/N``, ``xF`` of ``xF [mm]``."""
    sym = re.split(r"\s*[/\[(]", header.strip(), maxsplit=1)[0].strip()
    # a Chinese name before the symbol (``角速度 ω3/(rad/s)``): the symbol is the last word
    sym = sym.split()[-1] if sym.split() else sym
    return "".join(_GREEK.get(c, c) for c in sym)


def _column_group(header):
    """What a column belongs with: the joint of a reaction, else the order of the
    quantity told by its unit (position, velocity ``/s``, acceleration ``/s²``)."""
    sym = column_symbol(header)
    m = re.match(r"[FM]R(\d+)", sym)
    if m:
        return "R" + m.group(1)
    unit = header[len(header.split("/", 1)[0]):]
    if re.search(r"s(²|\^2|2)\)?\s*$", unit) or sym.startswith("alpha"):
        return "acceleration"
    if re.search(r"/\s*\(?\s*s\)?\s*$", unit) or sym.startswith("omega"):
        return "velocity"
    return "position"


def split_block(block, width, gap=2, edge=0):
    """*block* as blocks no wider than *width*, each repeating the first column.

    A table is split only when it is wider; the columns after the first go in
    groups (:func:`_column_group`), a group whole into one block when it fits
    there.  *gap* is the width between two columns and *edge* the width the
    table's frame adds (rich: 3 and 4; plain text: 2 and 0).
    """
    if not block.headers or len(block.headers) < 3:
        return [block]
    cols = [max([display_width(h)] + [display_width(r[i]) for r in block.rows])
            for i, h in enumerate(block.headers)]
    total = sum(cols) + gap * (len(cols) - 1) + edge
    if total <= width:
        return [block]
    groups = []
    for i in range(1, len(cols)):
        g = _column_group(block.headers[i])
        if groups and groups[-1][0] == g:
            groups[-1][1].append(i)
        else:
            groups.append((g, [i]))
    base = cols[0] + edge
    parts, cur, used = [], [], base
    for _, idx in groups:
        need = sum(cols[i] + gap for i in idx)
        if cur and used + need > width:
            parts.append(cur)
            cur, used = [], base
        if used + need <= width:
            cur += idx
            used += need
            continue
        for i in idx:   # a group wider than the page on its own: column by column
            if cur and used + cols[i] + gap > width:
                parts.append(cur)
                cur, used = [], base
            cur.append(i)
            used += cols[i] + gap
    if cur:
        parts.append(cur)
    if len(parts) == 1:
        return [block]
    out = []
    for k, idx in enumerate(parts, 1):
        keep = [0] + idx
        heading = f"{block.heading} ({k}/{len(parts)})" if block.heading \
            else f"({k}/{len(parts)})"
        out.append(Block(heading, [block.headers[i] for i in keep],
                         [[r[i] for i in keep] for r in block.rows]))
    return out


def select_columns(report, names):
    """*report* with only the table columns *names* (symbols as :func:`column_symbol`
    gives them: ``theta3``, ``omega3``, ``FR16``), after each table's first column.

    Tables holding none of them are left out; key/value blocks stay.  Raises
    :class:`ValueError` naming a column no table has (with the nearest one).
    """
    import difflib

    wanted = ["".join(_GREEK.get(c, c) for c in n.strip()) for n in names if n.strip()]
    if not wanted:
        return report
    have = {}
    for b in report.blocks:
        for h in b.headers[1:]:
            have.setdefault(column_symbol(h), h)
            have.setdefault(column_symbol(h).lower(), h)
    for n in wanted:
        if n not in have and n.lower() not in have:
            near = difflib.get_close_matches(n, list(have), n=1, cutoff=0.5)
            known = sorted({column_symbol(h) for b in report.blocks for h in b.headers[1:]})
            raise ValueError(f"--columns: expected column names of this run's tables ("
                             f"{', '.join(known) or 'none'}), got '{n}'"
                             + (f" (did you mean '{near[0]}'?)" if near else ""))
    keys = {n for n in wanted} | {n.lower() for n in wanted}
    blocks = []
    for b in report.blocks:
        if not b.headers:
            blocks.append(b)
            continue
        idx = [i for i, h in enumerate(b.headers) if i and (
            column_symbol(h) in keys or column_symbol(h).lower() in keys)]
        if idx:
            keep = [0] + idx
            blocks.append(Block(b.heading, [b.headers[i] for i in keep],
                                [[r[i] for i in keep] for r in b.rows]))
    return Report(report.title, blocks, list(report.notes))


#: where a line of prose may best be broken: after a comma or semicolon, before "("
_GOOD_BREAK = re.compile(r"[,;:]$")


def _breakable(words, i):
    """May a line end after ``words[i]``?  Not inside ``sym = value`` nor between a
    number and its unit (``54.113 mm``)."""
    a, b = words[i], words[i + 1]
    if a in ("=", "≈", "<", ">", "≤", "≥", "−", "-", "+", "·", "×") or \
            b in ("=", "≈", "<", ">", "≤", "≥", "·", "×"):
        return False
    return not (re.search(r"\d[)\]]?$", a) and _UNIT_WORD.fullmatch(b))


#: a unit that follows a number (``54.113 mm``, ``4.5 kW,``, ``3 kg·m²)``): no line ends between
_UNIT_WORD = re.compile(r"(mm|cm|m|in|ft|lbf|lb|N|kN|N·m|J|kJ|W|kW|rpm|Pa|kPa|MPa|bar|psi|kg|g|"
                        r"rad|s|%|°)[/\w²³·]*[,;)\]]*")


def wrap(text, width, indent=""):
    """*text* as lines no wider than *width* (display columns, CJK counts two), the
    lines after the first starting with *indent*.  Lines break at spaces, best after a
    comma or semicolon or before a parenthesis, never inside ``x = 1.5 mm``; a word
    wider than a line (CJK text has no spaces) is cut where it must be."""
    width = max(width, display_width(indent) + 8)
    if display_width(text) <= width:
        return [text]
    words = text.split(" ")
    lines, cur = [], []          # cur: the words of the line being filled

    def used(ws, first):
        body = " ".join(ws)
        return display_width(body if first else indent + body)

    for k, word in enumerate(words):
        first = not lines
        if not cur or used(cur + [word], first) <= width:
            cur.append(word)
            continue
        # the line is full: end it at the best break in its second half, else the last allowed
        cut, fallback, ahead = None, None, cur + [word]
        for j in range(len(cur), 0, -1):
            if not _breakable(ahead, j - 1):
                continue
            if fallback is None:
                fallback = j
            good = _GOOD_BREAK.search(ahead[j - 1]) or ahead[j].startswith("(")
            if good and used(cur[:j], first) >= width // 2:
                cut = j
                break
        if cut is None:       # no good break: the last allowed one, unless that leaves a stub
            short = fallback is None or used(cur[:fallback], first) < width // 3
            cut = len(cur) if short else fallback
        lines.append(" ".join(cur[:cut]))
        cur = cur[cut:] + [word]
    if cur:
        lines.append(" ".join(cur))
    out = []
    for n, line in enumerate(lines):                       # a word still too wide: cut it
        lead = "" if n == 0 else indent
        while display_width(lead + line) > width:
            room, cut = width - display_width(lead), 0
            while cut < len(line) and display_width(line[:cut + 1]) <= room:
                cut += 1
            cut = max(cut, 1)
            out.append(lead + line[:cut])
            line, lead = line[cut:].lstrip(" "), indent
        out.append(lead + line)
    return out


def kv_layout(rows, width, frame=4):
    """Lay out the ``[label, value]`` rows of a key/value block in *width* columns,
    of which *frame* go to the block's margins and the gap between its two columns.

    Returns ``(label_width, value_width, [(label_lines, value_lines), ...])``: a value
    too long for its column continues on lines indented two columns under it; a label
    wraps only when the values would otherwise be left less than half the width
    (and 30 columns)."""
    if not rows:
        return 0, 0, []
    lmax = max(display_width(r[0]) for r in rows)
    vmax = max(display_width(r[1]) for r in rows)
    avail = max(width - frame, 20)
    if lmax + vmax <= avail:
        lw, vw = lmax, vmax
    else:
        need = min(vmax, max(30, avail // 2))
        vw = avail - lmax if avail - lmax >= need else min(vmax, max(need, avail // 2))
        # (a wrapped label is never narrower than wrap() makes it: its indent + 8)
        lw = max(min(lmax, avail - vw), min(lmax, 10))
        vw = avail - lw
    cells = [(wrap(r[0], lw, "  "), wrap(r[1], vw, "  ")) for r in rows]
    lw = max(display_width(ln) for lab, _ in cells for ln in lab)
    vw = max(display_width(ln) for _, val in cells for ln in val)
    return lw, vw, cells


def render_text(report: Report, width=REPORT_WIDTH) -> str:
    """Plain-text report as written to ``report.txt``: every line no wider than
    *width* -- tables split into blocks, titles, headings, notes and long key/value
    rows wrapped."""
    report = plain_zeros(report)
    title = wrap(report.title, width)
    out = title + ["=" * min(width, max(20, *map(display_width, title))), ""]
    for block in (b for whole in report.blocks for b in split_block(whole, width)):
        if block.heading:
            out.extend(wrap(block.heading, width, "  "))
        if block.headers:
            widths = [max(display_width(h), *(display_width(r[i]) for r in block.rows))
                      if block.rows else display_width(h) for i, h in enumerate(block.headers)]
            out.append("  ".join(_pad(h, w) for h, w in zip(block.headers, widths)))
            out.append("  ".join("-" * w for w in widths))
            for row in block.rows:
                out.append("  ".join(_pad(c, w) for c, w in zip(row, widths)))
        else:
            lw, _, cells = kv_layout(block.rows, width)
            for label, value in cells:
                for k in range(max(len(label), len(value))):
                    lab = label[k] if k < len(label) else ""
                    val = value[k] if k < len(value) else ""
                    out.append(f"  {_pad(lab, lw, left=True)}  {val}".rstrip())
        out.append("")
    for note in report.notes:
        out.extend(wrap(note, width, "  "))
    return "\n".join(out).rstrip() + "\n"


def print_rich(report: Report, file=None, width=None):
    """Show the report on the terminal with rich tables, split to the terminal's
    *width* (:func:`terminal_width` unless given)."""
    from rich.markup import escape
    from rich.table import Table

    from mechcli.report.console import console as make_console

    report = plain_zeros(report)
    width = width or terminal_width(file)
    blocks = [b for whole in report.blocks for b in split_block(whole, width, gap=3, edge=4)]
    # the key/value blocks laid out once: "│ " label " │ " value " │" (a frame of 7)
    kv = {id(b): kv_layout(b.rows, width, frame=7) for b in blocks if not b.headers and b.rows}
    # never squeeze numbers: widen past the terminal rather than truncate cells (only a
    # table whose first two columns are already wider than the terminal needs it); a
    # key/value block wraps its own rows (kv_layout), a long title or note wraps as text
    need = max([sum(max([display_width(h)] + [display_width(r[i]) for r in b.rows]) + 3
                    for i, h in enumerate(b.headers)) + 1 for b in blocks if b.headers]
               # a key/value block as laid out (a word wider than its column stays whole)
               + [lw + vw + 7 for lw, vw, _ in kv.values()],
               default=0)
    console = make_console(file, highlight=False, width=max(width, need))
    # every text is the user's or ours, never rich markup: a title "door [/bold]" is text
    # titles, headings and notes wrap by our rule (never inside ``x = 1.5 mm``), not rich's
    console.print("\n".join(f"[bold]{escape(line)}[/bold]" for line in wrap(report.title, width)))
    for block in blocks:
        # a table at least as wide as its heading: rich wraps a title to the table's width
        wide = min(display_width(block.heading) + 2, width) if block.heading else None
        if block.headers:
            table = Table(title=escape(block.heading) or None, title_justify="left",
                          min_width=wide)
            for h in block.headers:
                table.add_column(escape(h), justify="right", no_wrap=True)
            for row in block.rows:
                table.add_row(*map(escape, row))
        else:
            lw, vw, cells = kv.get(id(block)) or kv_layout(block.rows, width, frame=7)
            table = Table(title=escape(block.heading) or None, title_justify="left",
                          show_header=False, min_width=min(wide or 0, lw + vw + 7) or None)
            table.add_column(justify="left", width=lw, no_wrap=True)
            table.add_column(justify="left", width=vw, no_wrap=True)
            for label, value in cells:
                table.add_row(escape("\n".join(label)), escape("\n".join(value)))
        console.print(table)
    for note in report.notes:
        console.print("\n".join(wrap(note, width, "  ")), markup=False)
