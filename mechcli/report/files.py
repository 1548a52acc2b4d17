"""Atomic file output: a file is either complete or absent, never half-written.

Every file is written into a temporary file that :func:`tempfile.mkstemp` creates
in the target folder (a unique name, opened with ``O_EXCL``), then renamed over
the target with :func:`os.replace`.  Parallel runs therefore never share a
temporary file, and when two runs write the same ``--out`` each file is
replaced whole by one of them: a reader sees one run's complete file, never a
mixture.

CSV numbers are ``%.{digits}g`` (``--digits``, default 10 significant digits;
17 reads back bit for bit).
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path


class OutputError(RuntimeError):
    """Refusing to write a non-finite number or an unwritable file."""


#: significant digits of CSV numbers unless a run asks otherwise (``--digits``)
DEFAULT_DIGITS = 10


def _umask():
    umask = os.umask(0)
    os.umask(umask)
    return umask


_UMASK = _umask()


def _atomic(path, write):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # unique per call (mkstemp: random suffix, O_CREAT | O_EXCL) in the target folder, so
    # the rename below stays on one file system and is atomic
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        os.chmod(tmp, 0o666 & ~_UMASK)   # mkstemp's 0600 -> what open() would give
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return path


def write_bytes(path, data: bytes):
    return _atomic(path, lambda fh: fh.write(data))


def write_text(path, text: str):
    return _atomic(path, lambda fh: fh.write(text.encode("utf-8")))


def format_number(x, digits=DEFAULT_DIGITS):
    """Shortest faithful text for a CSV cell (``%.{digits}g``); refuses NaN/inf."""
    if not math.isfinite(x):
        raise OutputError(f"refusing to write a non-finite value ({x})")
    return f"{x:.{digits}g}"


def write_csv(path, columns, digits=DEFAULT_DIGITS):
    """Write named columns (``[(header, sequence), ...]``) as CSV, atomically.

    Every value must be finite: a NaN or inf is a bug upstream and raises
    :class:`OutputError` before anything is written.
    """
    import numpy as np

    headers = [h for h, _ in columns]
    arrays = [np.asarray(col, dtype=float) for _, col in columns]
    n = len(arrays[0]) if arrays else 0
    for h, a in zip(headers, arrays):
        if a.shape != (n,):
            raise OutputError(f"column {h} has {a.shape} values, expected {n}")
        if not np.all(np.isfinite(a)):
            bad = int(np.argmax(~np.isfinite(a)))
            raise OutputError(f"refusing to write non-finite {h} in row {bad + 1}")
    lines = [",".join(headers)]
    if n:
        fmt = ",".join([f"%.{digits}g"] * len(arrays))
        mat = np.column_stack(arrays)
        lines.extend(fmt % tuple(row) for row in mat.tolist())
    return write_text(path, "\n".join(lines) + "\n")


class Outputs:
    """Collects the files a run writes, in order, for ``--json`` and the summary.

    *digits* is the run's ``--digits``: the significant digits of every CSV
    number this run writes (:meth:`csv`, and the text CSV writers that read
    :attr:`digits`).
    """

    def __init__(self, out_dir, digits=DEFAULT_DIGITS):
        self.out_dir = Path(out_dir)
        self.digits = int(digits)
        self.files: list[Path] = []

    def path(self, name):
        return self.out_dir / name

    def text(self, name, text):
        self.files.append(write_text(self.path(name), text))
        return self.files[-1]

    def csv(self, name, columns, digits=None):
        digits = self.digits if digits is None else digits
        self.files.append(write_csv(self.path(name), columns, digits))
        return self.files[-1]

    def add(self, path):
        self.files.append(Path(path))
        return self.files[-1]

    def discard(self):
        """Remove the files this run wrote (each was complete: see :func:`_atomic`),
        so that a run that fails after writing leaves none of its output."""
        for f in self.files:
            try:
                f.unlink()
            except FileNotFoundError:
                pass
        self.files.clear()
