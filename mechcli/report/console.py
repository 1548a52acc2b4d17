"""The terminal: rich consoles that honour ``NO_COLOR``, and the progress of long work.

Tables reach stdout as rich tables only when stdout is a terminal; a pipe, a file or a
Makefile gets the plain text of :func:`mechcli.report.table.render_text` (no box
drawing, no ANSI escapes).  ``NO_COLOR`` (https://no-color.org: set and not empty)
turns every ANSI escape off, colours and bold alike, on a terminal too (:func:`console`).

:class:`Progress` draws the progress of long work (an atlas build and search,
differential evolution, a streamed ``kin`` sweep, ``mechcli check``) on stderr: only
when stderr is a terminal, only once the work has run for :data:`DELAY` seconds, never
with ``-q``; it disappears when the work ends.  The core never prints: it reports
through an optional callback, ``progress(done, total, **values)`` (*total* None when
unknown, *values* numbers), which :meth:`Progress.stage` makes.  ``-v`` adds one line
per call (a chunk, a generation, a spec) on stderr, terminal or not: the user asked
for it.
"""

from __future__ import annotations

import os
import sys
import time

#: work shorter than this shows no progress bar [s]
DELAY = 2.0


def is_terminal(stream):
    """Is *stream* a terminal?  False for a pipe, a file, a ``StringIO``, a closed or
    replaced stream."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def no_color(environ=None):
    """``NO_COLOR`` set and not empty (https://no-color.org)."""
    return bool((os.environ if environ is None else environ).get("NO_COLOR", ""))


def console(file=None, **kwargs):
    """A rich ``Console`` (keyword arguments as rich's) that writes no ANSI escape at
    all under ``NO_COLOR``: rich alone drops only the colours and keeps bold."""
    from rich.console import Console

    if no_color():
        kwargs["color_system"] = None
    return Console(file=file, **kwargs)


class Progress:
    """The progress of one long piece of work on stderr (see the module's docstring).

    Parameters
    ----------
    label : str
        What the work is (``synth``, ``check``): the start of every line.
    show : bool
        The run allows a bar (False with ``-q``); it is drawn only if stderr is also a
        terminal, and only once :data:`DELAY` seconds have passed since the start.
    verbose : bool
        ``-v``: one line per call of a stage's callback.
    file : file or None
        Where to draw (None: ``sys.stderr`` as it is when the work starts).
    delay : float
        Seconds before a bar appears.
    clock : callable
        The time in seconds (a test's own clock).

    Use it as a context manager (the bar is removed however the work ends), hand
    ``stage(...)``'s callback to the core, or wrap an iterable with :meth:`track`.
    """

    def __init__(self, label, *, show=True, verbose=False, file=None, delay=DELAY,
                 clock=time.perf_counter):
        self.file = sys.stderr if file is None else file
        self.label = label
        self.show = bool(show) and is_terminal(self.file)
        self.verbose = bool(verbose)
        self.delay, self.clock = float(delay), clock
        self.t0 = clock()
        self.bar = self.task = None
        self.current = None        # (description, total) of the bar's task

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def stage(self, description, total=None, detail=None):
        """The callback of one stage: ``callback(done, total=None, **values)``.

        *description* names the stage on the bar (``building the atlas``); *total*
        is used when the call gives none.  *detail(done, total, **values)* words the
        ``-v`` line (default: ``description done/total``); a call with nothing done
        yet (the stage's start) has none."""
        def callback(done, total_=None, **values):
            n = total if total_ is None else total_
            line = None
            if self.verbose and done > 0:
                line = detail(done, n, **values) if detail else \
                    f"{description} {done}" + ("" if n is None else f"/{n}")
            self.update(description, done, n, line)
        return callback

    def track(self, items, description, total=None, detail=None):
        """*items* (a sequence) for a loop, the stage's count going up as the loop
        asks for the next item: the core's loop over a list is counted without a
        callback of its own."""
        return _Tracked(items, self.stage(description, len(items) if total is None
                                          else total, detail))

    def update(self, description, done, total=None, line=None):
        """*done* of *total* (None: unknown) in the stage *description*; *line*:
        the ``-v`` line, if any."""
        if line is not None:
            self.echo(line)
        if not self.show:
            return
        if self.bar is None:
            if self.clock() - self.t0 < self.delay or (total is not None and done >= total):
                return
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                ProgressColumn,
                TextColumn,
                TimeRemainingColumn,
            )
            from rich.progress import Progress as Bar
            from rich.text import Text

            clock, t0 = self.clock, self.t0

            class Elapsed(ProgressColumn):
                """The time since the work started (not since the bar appeared)."""

                def render(self, task):
                    s = int(clock() - t0)
                    return Text(f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}",
                                style="progress.elapsed")

            self.bar = Bar(
                TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                Elapsed(), TimeRemainingColumn(),
                console=console(self.file), transient=True,
                redirect_stdout=False, redirect_stderr=False)
            self.bar.start()
        text = f"{self.label}: {description}"
        if self.current != (text, total):
            if self.task is not None:
                self.bar.remove_task(self.task)
            self.task = self.bar.add_task(text, total=total, completed=done)
            self.current = (text, total)
        else:
            self.bar.update(self.task, completed=done)

    def echo(self, line):
        """A ``-v`` line on stderr (above the bar while one is drawn)."""
        text = f"mechcli: {self.label}: {line}"
        if self.bar is not None:
            self.bar.console.print(text, markup=False, highlight=False, soft_wrap=True)
        else:
            print(text, file=self.file, flush=True)

    def close(self):
        """Remove the bar (the work is over, or stopped)."""
        if self.bar is not None:
            self.bar.stop()
            self.bar = self.task = None
            self.current = None


class _Tracked:
    """A sequence whose iteration reports each item done (:meth:`Progress.track`)."""

    def __init__(self, items, step):
        self.items, self.step = items, step

    def __len__(self):
        return len(self.items)

    def __getitem__(self, i):
        return self.items[i]

    def __iter__(self):
        self.step(0)
        for k, item in enumerate(self.items, 1):
            yield item
            self.step(k)
