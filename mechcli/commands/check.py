"""``mechcli check``: run specs and compare every ``[expected]`` value (batches, CI, JUnit)."""

from __future__ import annotations

import click


@click.command("check")
@click.argument("paths", nargs=-1, required=True, metavar="PATH...")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=None,
              help="Specs run in parallel processes [default: the number of cores].")
@click.option("--junit", type=click.Path(dir_okay=False), metavar="FILE",
              help="Also write a JUnit XML report (one test case per spec).")
@click.option("--json", "json_out", is_flag=True, help="Print the outcome as JSON.")
@click.option("--set", "sets", multiple=True, metavar="KEY=VALUE",
              help="Override a key in every spec (dotted path, TOML value); repeatable.")
@click.option("--plot", is_flag=True,
              help="Also write pictures, into out/check/<spec stem>/ [default: none, "
                   "each spec runs in a temporary directory].")
@click.option("--quiet", "-q", is_flag=True, help="Only the failures, no table or summary.")
def check(paths, jobs, junit, json_out, sets, plot, quiet):
    """Run each spec in PATH... (files, folders searched for *.toml, globs) with
    the command its `command` key names and compare every [expected] value.

    Exit 0 when all hold; 4 when any expected value is not met; otherwise, if
    a spec could not run, its code (1, 2, 3 in that order of precedence)."""
    import os
    import sys
    import time

    from mechcli import batch
    from mechcli.report import check as report
    from mechcli.report.files import write_text

    t0 = time.perf_counter()
    specs, problems = batch.collect(paths)
    jobs = jobs or os.cpu_count() or 1
    out_dirs = batch.plot_dirs(specs) if plot else None
    progress = _Progress(len(specs), enabled=sys.stderr.isatty() and not json_out)
    try:
        results = batch.run_batch(specs, sets, jobs, plot, out_dirs, on_done=progress.advance)
    finally:
        progress.stop()
    code = batch.exit_code(results, problems)
    summary = report.summarize(results, problems, time.perf_counter() - t0, jobs, code)
    files = []
    if junit is not None and not str(junit).strip():
        raise click.BadParameter("expected a file, got an empty path", param_hint="--junit")
    if junit:
        try:
            write_text(junit, report.junit_xml(results, problems, summary))
        except OSError as exc:
            raise click.BadParameter(f"cannot write {junit}: {exc.strerror or exc}",
                                     param_hint="--junit") from None
        files.append(junit)
    for line in report.error_lines(results, problems):
        click.echo(f"mechcli: error: {line}", err=True)
    if json_out:
        click.echo(report.json_doc(results, problems, summary, files))
    else:
        if not quiet:
            report.print_table(results)
            click.echo(report.summary_line(summary))
        for line in report.failure_lines(results):
            click.echo(line)
    if code:
        raise click.exceptions.Exit(code)   # mechcli.cli.main turns it into the exit code


class _Progress:
    """A rich progress bar on stderr, shown only once the batch has run for a second."""

    def __init__(self, total, enabled):
        import time
        self.total, self.enabled, self.t0 = total, enabled and total > 1, time.perf_counter()
        self.done, self.bar, self.task = 0, None, None

    def advance(self, result):
        import time
        self.done += 1
        if not self.enabled:
            return
        if self.bar is None and time.perf_counter() - self.t0 > 1.0 and self.done < self.total:
            from rich.console import Console
            from rich.progress import Progress
            self.bar = Progress(console=Console(stderr=True), transient=True)
            self.bar.start()
            self.task = self.bar.add_task("mechcli check", total=self.total)
        if self.bar is not None:
            self.bar.update(self.task, completed=self.done)

    def stop(self):
        if self.bar is not None:
            self.bar.stop()
