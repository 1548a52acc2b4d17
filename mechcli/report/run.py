"""The end of every command: check ``[expected]``, write ``report.txt``, then show the
table or the JSON."""

from __future__ import annotations

import click

from mechcli.report import jsonout
from mechcli.report.table import print_rich, render_text


def finish(run, command, report, results, outputs, warnings=()):
    """Check ``[expected]``, write ``report.txt`` into *outputs* and print what the
    user asked for.

    Every key of the spec's ``[expected]`` table must name a key of *results*:
    otherwise a :class:`~mechcli.spec.errors.SpecError` (exit 2) is raised
    before anything is printed, and the files this run already wrote (CSV,
    plots, GIF: each complete, as every write is atomic) are removed, so the
    failed run leaves no output of its own behind.

    Parameters
    ----------
    run : mechcli.options.RunOptions
    command : str
        Subcommand name (for the JSON document).
    report : mechcli.report.table.Report
    results : dict
        Scalar results (finite floats, ints, bools, strings, lists of those).
    outputs : mechcli.report.files.Outputs
        Files already written; ``report.txt`` is added here.
    warnings : sequence of str
        One-line warnings; shown on stderr unless ``--json`` (then in the JSON).
    """
    from mechcli.core.errors import UnsolvableError
    from mechcli.spec.common import check_expected
    from mechcli.spec.errors import SpecError

    try:
        check_expected(run.spec_path, run.sets, results)
        _check_finite(results)
    except (SpecError, UnsolvableError):
        outputs.discard()
        raise
    shown = list(report.notes)
    for w in warnings:
        report.notes.append(("警告: " if run.lang == "zh" else "warning: ") + w)
    outputs.text("report.txt", render_text(report))
    if run.json:
        click.echo(jsonout.dumps(command, run.spec_path, results, outputs.files, warnings))
        return
    if not run.quiet:
        # the table on stdout; the warnings (also in report.txt) on stderr, where a
        # batch or a pipe keeps them apart from the results
        report.notes = shown
        print_rich(report)
        click.echo("written: " + ", ".join(str(f) for f in outputs.files))
    where = f"{run.spec_path}: " if run.spec_path else ""    # traceable in a parallel batch
    for w in warnings:
        click.echo(f"mechcli: warning: {where}{w}", err=True)


def _check_finite(results, path=""):
    """A result that overflowed (inf) or is undefined (NaN) is out of the range
    mechcli can report: exit 3 naming it, before anything is printed or kept."""
    import math

    from mechcli.core.errors import UnsolvableError

    items = results.items() if isinstance(results, dict) else enumerate(results)
    for k, v in items:
        name = f"{path}.{k}" if path and isinstance(k, str) else (f"{path}[{k}]" if path else k)
        if isinstance(v, (dict, list, tuple)):
            _check_finite(v, name)
        elif isinstance(v, float) or hasattr(v, "dtype"):
            try:
                x = float(v)
            except (TypeError, ValueError):
                continue
            if not math.isfinite(x):
                raise UnsolvableError(f"the result {name} is out of the range of floating-point "
                                      f"numbers ({x}): the inputs are too extreme to report it")
