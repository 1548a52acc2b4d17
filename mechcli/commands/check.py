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
@click.option("--verbose", "-v", is_flag=True,
              help="One line on stderr as each spec finishes (its checks and time).")
def check(paths, jobs, junit, json_out, sets, plot, quiet, verbose=False):
    """Run each spec in PATH... (files, folders searched for *.toml, globs) with
    the command its `command` key names and compare every [expected] value.

    Exit 0 when all hold; 4 when any expected value is not met; otherwise, if
    a spec could not run, its code (1, 2, 3 in that order of precedence)."""
    import os
    import time

    from mechcli import batch
    from mechcli.report import check as report
    from mechcli.report.console import Progress
    from mechcli.report.files import write_text

    t0 = time.perf_counter()
    specs, problems = batch.collect(paths)
    jobs = jobs or os.cpu_count() or 1
    out_dirs = batch.plot_dirs(specs) if plot else None
    # a bar on stderr (a terminal only, after 2 s, never with -q); -v: a line per spec
    with Progress("check", show=not quiet, verbose=verbose) as progress:
        step = progress.stage("specs", len(specs), detail=_spec_line)
        done = []

        def on_done(result):
            done.append(result)
            step(len(done), result=result)

        results = batch.run_batch(specs, sets, jobs, plot, out_dirs, on_done=on_done)
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


def _spec_line(done, total, result):
    """``-v``: ``3/25 configs/ch1/ex1-1.toml: ok (6/6 expected values, 0.24 s)``."""
    held = sum(c["held"] for c in result["checks"])
    status = {"passed": "ok", "failed": "FAILED", "error": f"error {result['exit_code']}"}
    checks = (f"{held}/{len(result['checks'])} expected values, "
              if result["status"] != "error" else "")
    return (f"{done}/{total} {result['spec']}: {status[result['status']]} "
            f"({checks}{result['time_s']:.2f} s)")
