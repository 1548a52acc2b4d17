"""Spec pieces shared by every command: the header and ``[expected]``.

What an ``[expected]`` value means (tolerances, comparison, the check that every
key names a result) lives in :mod:`mechcli.spec.expected`; :func:`read_expected`
and :func:`check_expected` are re-exported here for the spec readers and
``report.run`` (this module imports ``expected``, never the other way round).
"""

from __future__ import annotations

from mechcli.core.records import record
from mechcli.spec.errors import SpecError
from mechcli.spec.expected import (  # noqa: F401 (re-exported)
    Expected,
    check_expected,
    read_expected,
)


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
