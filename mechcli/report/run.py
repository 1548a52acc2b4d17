"""The end of every command: check ``[expected]``, write ``report.txt``, then show the
table or the JSON."""

from __future__ import annotations

import codecs
import re
import sys

from mechcli.report import jsonout
from mechcli.report.table import Block, Report, print_rich, render_text, terminal_width
from mechcli.report.words import say


class RunUsageError(ValueError):
    """An option of the run that does not fit its results (``--columns`` naming no
    column): the command layer shows it as a usage error (exit 2)."""


def _is_terminal():
    try:
        return sys.stdout.isatty()
    except (AttributeError, ValueError):   # replaced or closed
        return False


#: an ANSI escape sequence (colour, style), as click strips it
_ANSI = re.compile(r"\033\[[0-?]*[ -/]*[@-~]")


def _stream(err=False):
    """``sys.stdout`` (``sys.stderr``), or a UTF-8 writer on its bytes when it is set to
    ASCII, as ``click.echo`` writes (None: no stream)."""
    stream = sys.stderr if err else sys.stdout
    if stream is None:
        return None
    encoding = getattr(stream, "encoding", None) or "ascii"
    try:
        ascii_ = codecs.lookup(encoding).name == "ascii"
    except LookupError:
        ascii_ = False
    buffer = getattr(stream, "buffer", None)
    if not ascii_ or buffer is None:
        return stream
    return _Utf8(stream, buffer)


class _Utf8:
    """A text writer on a binary stream in UTF-8, unencodable text replaced."""

    def __init__(self, text, buffer):
        self.text, self.buffer = text, buffer

    def write(self, s):
        self.text.flush()
        self.buffer.write(s.encode("utf-8", "replace"))

    def flush(self):
        self.buffer.flush()

    def isatty(self):
        return self.text.isatty()


def echo(message, nl=True, err=False):
    """Write *message* (and a newline) to stdout (stderr) and flush, as ``click.echo``
    writes text: ANSI escapes stripped when the stream is not a terminal."""
    stream = _stream(err)
    if stream is None:
        return
    out = message + "\n" if nl else message
    if not out:
        stream.flush()
        return
    try:
        tty = stream.isatty()
    except Exception:   # noqa: BLE001 -- as click: a stream that cannot tell is no terminal
        tty = False
    if not tty:
        out = _ANSI.sub("", out)
    stream.write(out)
    stream.flush()


class _Current:
    """What the report layer knows of the run in progress (one run per process at a
    time: the CLI, or the in-process runs of the tests, one after another)."""

    #: the spec's stem (``ex1-1``), or the command's name for a file-less run
    stem = None
    #: one-line notices the pictures raised (no CJK font, glyphs missing), in order
    notices: list = []
    #: the run's ``--dpi`` (None outside a command: the pictures' default)
    dpi = None


def begin(stem, dpi=None):
    """Start a run: remember the spec stem (figure titles fall back to it when their
    Chinese cannot be drawn) and the resolution its pictures are written at, and forget
    the notices of any earlier run."""
    _Current.stem = stem
    _Current.notices = []
    _Current.dpi = dpi


def current_dpi():
    """The ``--dpi`` given to :func:`begin`, or None outside a run."""
    return _Current.dpi


def current_stem():
    """The stem given to :func:`begin`, or None outside a run."""
    return _Current.stem


def notice(text):
    """Add a warning for this run, once however often it is raised."""
    if text not in _Current.notices:
        _Current.notices.append(text)


#: every warning about missing CJK glyphs starts so; :func:`finish` keeps one of them,
#: which ``-q`` silences on stderr (the JSON keeps it)
NO_CJK = "no CJK font found"
#: what that warning says to do about it
CJK_HINT = "(pip install 'mechcli[cjk]')"


def _merge_warnings(warnings):
    """The command's warnings and the pictures' notices, each once, with everything said
    about a missing CJK font in ONE line (the most telling: labels before titles)."""
    out, cjk = [], []
    for w in [*warnings, *_Current.notices]:
        if w.startswith(("no CJK font", NO_CJK)):
            cjk.append(w)
        elif w not in out:
            out.append(w)
    _Current.notices = []
    if cjk:
        labels = any("label" in w for w in cjk)
        out.insert(0, f"{NO_CJK}: " + (
            "figure labels in English, titles without their Chinese" if labels
            else "figure titles without their Chinese") + f" {CJK_HINT}")
    return out


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
    if run.columns:
        from mechcli.report.table import select_columns
        try:
            report = select_columns(report, run.columns)
        except ValueError as exc:
            outputs.discard()
            raise RunUsageError(str(exc)) from None
    warnings = _merge_warnings(warnings)
    shown = list(report.notes)
    # report.txt says what was solved (the given data, the spec and its hash, the --set
    # values) so that a printed report can be handed in; the machine's warnings stay on
    # stderr (and in the JSON)
    given = given_block(run, command)
    handed_in = Report(report.title, ([given] if given else []) + list(report.blocks),
                       list(report.notes))
    outputs.text("report.txt", render_text(handed_in))
    manifest, removed, kept = outputs.manifest(manifest_info(run, command))
    if kept:
        warnings.append(f"kept {', '.join(kept)} in {outputs.out_dir}: written by an earlier "
                        "run and changed since, so not this run's output")
    if run.json:
        echo(jsonout.dumps(command, run.spec_path, results, outputs.files, warnings,
                                 manifest=manifest, removed=removed, kept=outputs.reused))
        return
    if not run.quiet:
        # the table on stdout; the warnings (also in report.txt) on stderr, where a
        # batch or a pipe keeps them apart from the results
        report.notes = shown
        if _is_terminal():
            print_rich(report)
        else:   # a pipe, a file, a Makefile: the plain text, without importing rich
            echo(render_text(report, width=terminal_width()), nl=False)
        echo("written: " + ", ".join(str(f) for f in outputs.files))
        if outputs.reused:
            echo("kept (from an earlier run of the same spec and --set values): "
                       + ", ".join(outputs.reused))
        if removed:
            echo("removed (stale, from an earlier run): " + ", ".join(removed))
    where = f"{run.spec_path}: " if run.spec_path else ""    # traceable in a parallel batch
    for w in warnings:
        if run.quiet and w.startswith(NO_CJK):   # -q: not the fonts, every other warning
            continue
        echo(f"mechcli: warning: {where}{w}", err=True)


#: spec keys that are the book's Greek letters: written as the letters in report.txt
_GREEK = {"omega": "ω", "alpha": "α", "theta": "θ", "phi": "φ", "psi": "ψ", "delta": "δ",
          "beta": "β", "gamma": "γ", "rho": "ρ", "epsilon": "ε", "lambda": "λ", "mu": "μ",
          "sigma": "σ", "tau": "τ", "eta": "η"}
#: the tables a spec gives besides its problem: not given data
_NOT_GIVEN = ("command", "title", "description", "units", "expected", "output")


def _symbol(key):
    """``omega1`` -> ``ω1``, ``alpha_rise`` -> ``α_rise``; other keys as they are."""
    import re

    unit = ""
    if key.endswith("_deg"):    # an angle given in degrees: the book's /(°)
        key, unit = key[:-4], "/(°)"
    m = re.match(r"([a-z]+)(.*)$", key)
    if m and m.group(1) in _GREEK and (not m.group(2) or not m.group(2)[0].isalpha()):
        return _GREEK[m.group(1)] + m.group(2) + unit
    return key + unit


def _given_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return format(v, ".10g")
    if isinstance(v, dict):
        return ", ".join(f"{_symbol(k)} = {_given_value(x)}" for k, x in v.items())
    if isinstance(v, list):
        return "[" + ", ".join(_given_value(x) for x in v) + "]"
    return str(v)


def _given_rows(data, where=""):
    rows = []
    for key, v in data.items():
        if not where and key in _NOT_GIVEN:
            continue
        label = f"{where}{_symbol(key)}"
        if isinstance(v, dict) and any(isinstance(x, (dict, list)) for x in v.values()):
            rows += _given_rows(v, f"{label}.")
        elif isinstance(v, dict):
            rows += [[f"{label}.{_symbol(k)}", _given_value(x)] for k, x in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            rows += [[f"{label}[{i}]", _given_value(x)] for i, x in enumerate(v)]
        else:
            rows.append([label, _given_value(v)])
    return rows


def given_block(run, command):
    """``report.txt``'s first block: the spec (path, SHA-256), the ``--set`` values and the
    given data as solved (every key of the problem's tables, Greek keys as the book's
    letters; lengths in the spec's unit); None without a spec file."""
    data = run.problem_data()
    if data is None:
        return None
    info = manifest_info(run, command)
    unit = data.get("units", "mm" if command != "flywheel" else "m")
    sets = ", ".join(info["sets"])
    head = [say(run.lang, "run.spec", path=info["spec"]),
            f"SHA-256 {(info['spec_sha256'] or '?')[:16]}…"]
    if sets:
        head.append(f"--set {sets}")
    head.append(say(run.lang, "run.units", unit=unit))
    return Block(heading=say(run.lang, "run.given", items="; ".join(head)),
                 rows=_given_rows(data))


def library_versions():
    """``{"mechcli", "python", "numpy", "scipy", "matplotlib"}`` versions (None for a
    library that is not installed), from the loaded module when there is one."""
    from mechcli import __version__
    from mechcli._versions import loaded_or_installed, python_version

    out = {"mechcli": __version__, "python": python_version()}
    for lib in ("numpy", "scipy", "matplotlib"):
        out[lib] = loaded_or_installed(lib)
    return out


def manifest_info(run, command):
    """What ``outputs.json`` says of a run besides its files: the command, the spec and
    its SHA-256 (None without a file), the ``--set`` overrides, the options that change
    the outputs, and the versions of mechcli and the libraries."""
    from mechcli.report.files import file_sha256

    spec_hash = None
    if run.spec_path is not None:
        try:
            spec_hash = file_sha256(run.spec_path)
        except OSError:   # read a moment ago by the command; gone now: say so by None
            spec_hash = None
    return {
        "command": command,
        "spec": None if run.spec_path is None else str(run.spec_path),
        "spec_sha256": spec_hash,
        "sets": [s.strip() for s in run.sets],
        "options": {"lang": run.lang, "plot": run.plot, "animate": run.animate,
                    "digits": run.digits},
        "versions": library_versions(),
    }


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
