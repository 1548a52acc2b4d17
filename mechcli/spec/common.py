"""Spec pieces shared by every command: ``[expected]`` and ``[output]``."""

from __future__ import annotations

import dataclasses
import math

from mechcli.spec.errors import SpecError, closest
from mechcli.spec.reader import load_spec


@dataclasses.dataclass(frozen=True)
class Expected:
    """One expected value (from the book, or an independent hand calculation).

    The default tolerance is half a unit of the last printed digit, taken from
    the number as written in the TOML file (``0.1283`` -> 5e-5).
    """

    name: str
    value: float
    tol: float


def _printed_tolerance(value):
    text = repr(float(value))
    if "e" in text or "E" in text:
        mant, _, exp = text.lower().partition("e")
        decimals = len(mant.partition(".")[2].rstrip("0")) - int(exp)
    else:
        decimals = len(text.partition(".")[2].rstrip("0"))
    return 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)


def read_expected(root):
    """Read the optional ``[expected]`` table of a spec.

    Each key maps a result name (as in ``--json`` ``results``) to a number, or
    to a table ``{ value = …, tol = … }`` / ``{ value = …, rel = … }``.
    Booleans and strings are compared exactly.
    """
    sec = root.table("expected", None)
    if sec is None:
        return {}
    out = {}
    for name in sec.keys():
        raw = sec.raw(name)
        if isinstance(raw, dict):
            sub = sec.table(name)
            value = sub.number("value")
            tol = sub.number("tol", None, nonneg=True)
            rel = sub.number("rel", None, nonneg=True)
            sub.raw("note", None)
            sub.finish()
            if tol is None:
                tol = abs(value) * rel if rel is not None else _printed_tolerance(value)
            out[name] = Expected(name, value, tol)
        elif isinstance(raw, bool) or isinstance(raw, str):
            out[name] = Expected(name, raw, 0.0)
        elif isinstance(raw, (int, float)) and math.isfinite(raw):
            out[name] = Expected(name, float(raw), _printed_tolerance(raw))
        else:
            raise SpecError(sec.file, sec.key(name),
                            "a number, a boolean, a string or { value = …, tol = … }", repr(raw))
    sec.finish()
    return out


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
    sec = root.table("expected", None)
    names = sorted(map(str, results))
    for name in [] if sec is None else sec.keys():
        if name not in results:
            raise SpecError(sec.file, sec.key(name),
                            "the name of a result of this run (a key of --json \"results\")",
                            f"unknown key '{name}'", closest(name, names))


@dataclasses.dataclass(frozen=True)
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
