"""Spec pieces shared by every command: the header and ``[expected]``.

What an ``[expected]`` value means (tolerances, comparison) lives in
:mod:`mechcli.spec.expected`; :func:`read_expected` is re-exported here for the
spec readers.
"""

from __future__ import annotations

from mechcli.core.records import record
from mechcli.spec.errors import SpecError, closest
from mechcli.spec.expected import Expected, read_expected  # noqa: F401 (re-exported)
from mechcli.spec.reader import load_spec


def check_expected(path, overrides, results):
    """Reject an ``[expected]`` key that names no result of the run (exit 2).

    The keys of ``[expected]`` are compared with the keys of *results* (the
    ``--json`` ``"results"`` object), so a misspelled name fails the run
    instead of passing unchecked.  The spec is read again (a few hundred
    microseconds) so that every command gets the check from
    :func:`mechcli.report.run.finish` without passing its spec along.

    Parameters
    ----------
    path : str or pathlib.Path or None
        The spec file of the run; None for file-less runs (nothing to check).
    overrides : sequence of str
        The run's ``--set KEY=VALUE`` overrides (they may add expected keys).
    results : dict
        The scalar results of the run.

    Raises
    ------
    SpecError
        On the first key of ``[expected]`` that is not a key of *results*,
        with the nearest result name as a suggestion.
    """
    if path is None:
        return
    try:
        root = load_spec(path, overrides)
    except SpecError:
        # the command has read this file already, so it is not a TOML spec
        # (``grashof --batch`` reads a CSV): there is no [expected] table
        return
    from mechcli.spec.expected import has_result
    sec = root.table("expected", None)
    names = sorted(map(str, results))
    for name in [] if sec is None else sec.keys():
        if not has_result(results, name):
            raise SpecError(sec.file, sec.key(name),
                            "the name of a result of this run (a key of --json \"results\")",
                            f"unknown key '{name}'", closest(name, names))


@record
class Header:
    """Top-level keys every spec may have.

    Attributes
    ----------
    title : str
        Shown as the report title.
    unit : str
        Declared length unit (``mm``, ``cm``, ``m``, ``in``).
    scale : float
        Metres per declared unit.
    """

    title: str
    unit: str
    scale: float


def read_header(root, command, default_unit="mm", default_title=None):
    """Read ``command``, ``title``, ``units`` and set the root's length unit.

    ``command`` is optional; when present it must name this subcommand, so a
    cam spec given to ``mechcli kin`` fails with a clear message (exit 2).
    """
    cmd = root.string("command", command)
    if cmd != command:
        raise SpecError(root.file, "command", f"'{command}' (this is `mechcli {command}`)",
                        f"'{cmd}' (run `mechcli {cmd} {root.file}`)")
    title = root.string("title", default_title or root.file)
    unit = root.set_unit_from("units", default_unit)
    root.raw("description", None)
    return Header(title=title, unit=unit, scale=root.unit)
