"""Atomic file output: a file is either complete or absent, never half-written."""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path


class OutputError(RuntimeError):
    """Refusing to write a non-finite number or an unwritable file."""


def _atomic(path, write):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
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


def format_number(x, digits=10):
    """Shortest faithful text for a CSV cell (``%.{digits}g``); refuses NaN/inf."""
    if not math.isfinite(x):
        raise OutputError(f"refusing to write a non-finite value ({x})")
    return f"{x:.{digits}g}"


def write_csv(path, columns, digits=10):
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
    """Collects the files a run writes, in order, for ``--json`` and the summary."""

    def __init__(self, out_dir):
        self.out_dir = Path(out_dir)
        self.files: list[Path] = []

    def path(self, name):
        return self.out_dir / name

    def text(self, name, text):
        self.files.append(write_text(self.path(name), text))
        return self.files[-1]

    def csv(self, name, columns, digits=10):
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
