"""Atomic file output: a file is either complete or absent, never half-written.

Every file is written into a temporary file that :func:`_temporary` creates in the
target folder (a unique random name, opened with ``O_EXCL``, as
:func:`tempfile.mkstemp` does), then renamed over
the target with :func:`os.replace`.  Parallel runs therefore never share a
temporary file, and when two runs write the same ``--out`` each file is
replaced whole by one of them: a reader sees one run's complete file, never a
mixture.

CSV numbers are ``%.{digits}g`` (``--digits``, default 10 significant digits;
17 reads back bit for bit); the header goes through the :mod:`csv` module, so a
column name that holds a comma, a quote or a line break is quoted, never splits
the header.

:class:`Outputs` is the one way a run writes into ``--out``: every path is a
file name joined to the folder, and a name that is absolute, holds a path
separator or ``..``, or resolves outside the folder is refused
(:class:`OutputPathError`, exit 2 naming ``--out``), whatever the spec layer let
through.  An OS error while writing there (``--out`` under a regular file, a
read-only folder, a folder where the file should go) is the same error with
the OS's reason: the user's ``--out`` is wrong, it is not a bug.

A run's files are staged: :class:`Outputs` writes them into a hidden
folder beside ``--out`` (``.NAME.mechcli-<random>``), and :meth:`Outputs.manifest`
commits the run: the earlier run's files that are still valid for the user (changed
since, or never mechcli's) are hard-linked in, the manifest is written last, and the
staged folder takes the place of ``--out`` in one step (``renameat2`` with
``RENAME_EXCHANGE`` on Linux; elsewhere two renames, with ``--out`` missing for the
instant between them, never mixed).  So at every moment ``--out`` is one run's whole
output with its manifest: a run that fails or is interrupted before its commit leaves
the earlier run's folder exactly as it was, and its staged folder is removed
(:func:`abandon_staged`, from the command line's error boundary).
"""

from __future__ import annotations

import csv
import errno
import io
import math
import os
import sys
from pathlib import Path


class OutputError(RuntimeError):
    """Refusing to write a non-finite number or an unwritable file."""


class OutputPathError(OutputError):
    """``--out`` cannot take a file: an unsafe file name or an OS error there.

    A user error (exit 2, mapped by :func:`mechcli.cli.main` like a
    :class:`~mechcli.spec.errors.SpecError`), worded like one: the option
    ``--out``, what was expected, what was found.
    """

    key = "--out"

    def __init__(self, expected, got):
        self.expected = expected
        self.got = got
        super().__init__(self.format())

    def format(self):
        return f"{self.key}: expected {self.expected}, got {self.got}"


#: significant digits of CSV numbers unless a run asks otherwise (``--digits``)
DEFAULT_DIGITS = 10


def _umask():
    umask = os.umask(0)
    os.umask(umask)
    return umask


_UMASK = _umask()
#: path separators: ``/``, ``\\`` (a separator on Windows, refused everywhere) and the system's
_SEPARATORS = {"/", "\\", os.sep} | ({os.altsep} if os.altsep else set())


#: path -> (bytes, sha256) of the files this process wrote (see :meth:`Outputs.manifest`)
_WRITTEN = {}


#: flags of a new private temporary file (those of tempfile.mkstemp)
_TMP_FLAGS = (os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
              | getattr(os, "O_BINARY", 0))


def _temporary(path):
    """``(fd, name)``: a new file ``.NAME.<random>.tmp`` beside *path*, created with
    ``O_EXCL`` and mode 0600, under a name tried again on a clash -- what
    :func:`tempfile.mkstemp` gives, without importing :mod:`tempfile` (with
    :mod:`shutil` and :mod:`random`, ~2.5 ms of every start-up where nothing else
    imported them)."""
    for _ in range(100):
        name = os.path.join(path.parent, f".{path.name}.{os.urandom(6).hex()}.tmp")
        try:
            return os.open(name, _TMP_FLAGS, 0o600), name
        except FileExistsError:
            continue
        except PermissionError:
            # Windows: a folder of that name (as mkstemp); elsewhere a real refusal
            if os.name == "nt" and os.path.isdir(name):
                continue
            raise
    raise FileExistsError(errno.EEXIST, "no free temporary file name", str(path.parent))


def _atomic(path, data):
    """Write *data* (bytes, or a function that writes into the open binary file) to
    *path* atomically; remember its size and SHA-256 for the manifest."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # unique per call (mkstemp: random suffix, O_CREAT | O_EXCL) in the target folder, so
    # the rename below stays on one file system and is atomic
    fd, tmp = _temporary(path)
    try:
        with os.fdopen(fd, "w+b") as fh:
            if callable(data):
                data(fh)
                # the manifest's checksum of what THIS run wrote (a parallel run may
                # replace the file before outputs.json is written): read back through the
                # open descriptor, never by name (the name could be swapped for a link)
                fh.flush()
                size = fh.seek(0, os.SEEK_END)
                fh.seek(0)
                digest = _digest_of(fh, size)
            else:
                fh.write(data)
                size, digest = len(data), _sha256(data)
            _publish(fh, tmp, path, size, digest)
    except BaseException:
        _discard(tmp)
        raise
    return path


def _publish(fh, tmp, path, size, digest):
    """The finished temporary file *tmp* (open as *fh*) becomes *path*: made public,
    closed (Windows renames only closed files), remembered for the manifest with its
    *size* and SHA-256 *digest*, and renamed over *path* in one step."""
    fh.flush()
    _private_to_public(fh, tmp)
    fh.close()
    _WRITTEN[str(path)] = (size, digest.hexdigest())
    os.replace(tmp, path)


def _discard(tmp):
    """Remove the temporary file of a write that failed or was interrupted."""
    try:
        os.unlink(tmp)
    except OSError:
        pass


def _private_to_public(fh, name):
    """The temporary file's 0600 -> the mode ``open()`` would have given, through the
    open descriptor where the OS allows it (by name elsewhere: Windows)."""
    mode = 0o666 & ~_UMASK
    if os.chmod in os.supports_fd:
        os.chmod(fh.fileno(), mode)
    else:
        os.chmod(name, mode)


def write_bytes(path, data: bytes):
    return _atomic(path, data if isinstance(data, bytes) else bytes(data))


def write_text(path, text: str):
    return _atomic(path, text.encode("utf-8"))


def format_number(x, digits=DEFAULT_DIGITS):
    """Shortest faithful text for a CSV cell (``%.{digits}g``); refuses NaN/inf."""
    if not math.isfinite(x):
        raise OutputError(f"refusing to write a non-finite value ({x})")
    return f"{x:.{digits}g}"


def write_csv(path, columns, digits=DEFAULT_DIGITS):
    """Write named columns (``[(header, sequence), ...]``) as CSV, atomically.

    Every value must be finite: a NaN or inf is a bug upstream and raises
    :class:`OutputError`, and nothing is written.  One chunk of
    :func:`write_csv_stream`, so both write the same bytes.
    """
    cells = sum(len(col) for _, col in columns)
    return write_csv_stream(path, [h for h, _ in columns], [[col for _, col in columns]],
                            digits, guard=cells > _GUARD_CELLS, size_hint=16 * cells)


#: a CSV of more cells than this takes long enough to write (~0.3 s and more) to be
#: guarded against SIGTERM like a stream; a smaller one goes without (no signal import)
_GUARD_CELLS = 500_000


def write_csv_stream(path, headers, chunks, digits=DEFAULT_DIGITS, guard=True,
                     size_hint=None):
    """Write a CSV whose rows arrive chunk by chunk, atomically, in bounded memory.

    *chunks* yields lists of column arrays (in the order of *headers*).  The rows go
    to a temporary file in the target folder, renamed over *path* at the end, so a
    refusal (a NaN or inf, :class:`OutputError`), an error or an interrupt midway
    leaves no half-written file.  The bytes are those :func:`write_csv` writes for
    the same rows; only one chunk is held at a time (a 1e7-row sweep).
    With *guard* (default) a SIGTERM meanwhile removes the temporary file too
    (:func:`_terminate_as_exit`); :func:`write_csv` leaves a small CSV without it.
    *size_hint*: the expected bytes, if known (:func:`_sha256` picks its hash by it).
    """
    import numpy as np

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    digest, size, row = _sha256(size=size_hint), 0, 0
    fmt = ",".join([f"%.{digits}g"] * len(headers))
    restore = _terminate_as_exit() if guard else _nothing
    try:
        fd, tmp = _temporary(path)
    except BaseException:
        restore()
        raise
    try:
        with os.fdopen(fd, "wb") as fh:
            head = io.StringIO()
            csv.writer(head, lineterminator="\n").writerow(headers)
            data = head.getvalue().encode("utf-8")   # the header line
            fh.write(data)
            digest.update(data)
            size += len(data)
            for chunk in chunks:
                arrays = [np.asarray(col, dtype=float) for col in chunk]
                n = len(arrays[0]) if arrays else 0
                if len(arrays) != len(headers):
                    raise OutputError(f"{path.name}: a chunk has {len(arrays)} columns, "
                                      f"expected {len(headers)}")
                for h, a in zip(headers, arrays):
                    if a.shape != (n,):
                        raise OutputError(f"column {h} has {a.shape} values, expected {n}")
                    if not np.all(np.isfinite(a)):
                        bad = int(np.argmax(~np.isfinite(a)))
                        raise OutputError(f"refusing to write non-finite {h} in row "
                                          f"{row + bad + 1}")
                for a in range(0, n, 8192):   # formatted a slice at a time: little text held
                    mat = np.column_stack([col[a:a + 8192] for col in arrays])
                    mat += 0.0   # (a negative zero written as 0, not -0)
                    data = ("\n".join(fmt % tuple(r) for r in mat.tolist()) + "\n").encode()
                    fh.write(data)
                    digest.update(data)
                    size += len(data)
                row += n
            _publish(fh, tmp, path, size, digest)
    except BaseException:
        _discard(tmp)
        raise
    finally:
        restore()
    return path


def _nothing():
    pass


def _terminate_as_exit():
    """While a long stream is written, SIGTERM (``kill``, a CI timeout) raises
    SystemExit(143) so that the temporary file is removed like on Ctrl-C; returns
    the function that puts the previous handler back.  (SIGKILL cannot be caught:
    it leaves the hidden ``.NAME.*.tmp`` beside the target.)"""
    from mechcli._signals import sigterm_as_exit
    return sigterm_as_exit()


def _os_reason(where, exc):
    """``PATH: reason`` for an OS error at *where*, naming the regular file that stands
    where a folder should be (``--out notes.txt/sub``)."""
    reason = exc.strerror or str(exc)
    if exc.errno == errno.ENOTDIR:
        for parent in [Path(where), *Path(where).parents]:
            if parent.exists() and not parent.is_dir():
                return f"{where}: {reason} ({parent} is a file, not a folder)"
    if exc.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
        reason = f"{reason} (no permission to write there)"
    return f"{where}: {reason}"


#: the manifest of the last run into an output folder
MANIFEST = "outputs.json"
#: its layout; a manifest of another layout (or none) is not read
MANIFEST_FORMAT = 1


_SHA256 = None
#: data up to this size is hashed by CPython's built-in SHA-256 (~300 MB/s here), more by
#: hashlib's OpenSSL one (~1,700 MB/s, but 2.3 ms to import): the crossover is ~1 MB
_BUILTIN_HASH_MAX = 1 << 20


def _sha256(data=b"", size=None):
    """A SHA-256 hash object (of *data*, bytes; *size*: the bytes it will be given in
    all, None if unknown).  For small data CPython's built-in implementation (``_sha2``
    from 3.12, ``_sha256`` before): :mod:`hashlib` loads OpenSSL first, 2.3 ms of a
    ~130 ms ``kin`` run.  For large or unknown sizes, and on other Pythons,
    :mod:`hashlib`'s, several times faster per byte.  Both give the same digest
    (``tests/unit/linkage/test_speed_streaming.py``)."""
    global _SHA256
    n = len(data) if size is None and data else size
    if n is None or n > _BUILTIN_HASH_MAX or sys.implementation.name != "cpython":
        from hashlib import sha256
        return sha256(data)
    if _SHA256 is None:
        try:
            if sys.version_info >= (3, 12):
                from _sha2 import sha256 as _SHA256
            else:
                from _sha256 import sha256 as _SHA256
        except ImportError:
            from hashlib import sha256 as _SHA256
    return _SHA256(data)


def _digest_of(fh, size):
    """The SHA-256 hash object of what binary file *fh* holds from its position on
    (*size* bytes, which picks the hash: :func:`_sha256`), read 1 MiB at a time."""
    digest = _sha256(size=size)
    for chunk in iter(lambda: fh.read(1 << 20), b""):
        digest.update(chunk)
    return digest


def file_sha256(path):
    """SHA-256 (hex) of a file's bytes."""
    with open(path, "rb") as fh:
        return _digest_of(fh, os.fstat(fh.fileno()).st_size).hexdigest()


def read_manifest(out_dir, same_as=None):
    """The file entries (``[{"name", "bytes", "sha256"}]``) of the manifest in *out_dir*
    that mechcli wrote, or ``[]`` when there is none or it is not mechcli's.  With
    *same_as* (this run's ``{"command", "spec"}``), only a manifest of the same command
    on the same spec counts: another problem run into the same folder wrote files that
    are its own, not stale ones of this spec."""
    doc = _manifest_doc(out_dir)
    if doc is None:
        return []
    if same_as is not None and any(doc.get(k) != same_as.get(k) for k in ("command", "spec")):
        return []
    return doc["files"]


def _manifest_doc(out_dir):
    """The manifest in *out_dir* as mechcli wrote it (a dict), or None."""
    import json

    try:
        doc = json.loads((Path(out_dir) / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(doc, dict) or doc.get("generator") != "mechcli" \
            or doc.get("format") != MANIFEST_FORMAT or not isinstance(doc.get("files"), list):
        return None
    return doc


def _same_problem(doc, info):
    """The earlier run solved the same problem as this one: the same command on the same
    spec contents (SHA-256) with the same ``--set`` overrides; its files are still valid."""
    return (doc is not None and info.get("spec_sha256") is not None
            and all(doc.get(k) == info.get(k) for k in ("command", "spec", "spec_sha256",
                                                         "sets")))


class Outputs:
    """Collects the files a run writes, in order, for ``--json`` and the summary.

    *digits* is the run's ``--digits``: the significant digits of every CSV
    number this run writes (:meth:`csv`, and the text CSV writers that read
    :attr:`digits`).
    """

    def __init__(self, out_dir, digits=DEFAULT_DIGITS):
        #: where the run's files go once committed: the user's --out
        self.final = Path(out_dir)
        #: where they are written until then (:meth:`_stage`); the final folder after
        self.out_dir = self.final
        self.staged = None
        self.digits = int(digits)
        self.files: list[Path] = []
        #: files of an earlier run of the same problem kept as still valid (:meth:`manifest`)
        self.reused: list = []

    def _relative(self, f):
        """A file's name in the manifest: its path below the output folder."""
        base = self.staged if self.staged is not None else self.final
        try:
            return Path(f).relative_to(base).as_posix()
        except ValueError:
            return Path(f).name

    def _shown(self, where):
        """*where* as the user knows it: a path in the staged folder named in --out."""
        if self.staged is not None:
            try:
                return self.final / Path(where).relative_to(self.staged)
            except ValueError:
                pass
        return where

    def _stage(self):
        """The hidden staging folder beside --out, made on the first write."""
        if self.staged is None:
            final = self.final
            for up in [final, *final.parents]:   # a file where a folder should be
                if up.exists():
                    if not up.is_dir():
                        raise OSError(errno.ENOTDIR, "Not a directory", str(final))
                    break
            parent = final.parent if str(final.parent) else Path(".")
            parent.mkdir(parents=True, exist_ok=True)
            for _ in range(100):
                cand = parent / f".{final.name or 'out'}.mechcli-{os.urandom(6).hex()}"
                try:
                    os.mkdir(cand, 0o777)
                    break
                except FileExistsError:
                    continue
            else:
                raise FileExistsError(errno.EEXIST, "no free staging folder", str(parent))
            self.staged = self.out_dir = cand
            _STAGED.append(self)
        return self.staged

    def staged_folder(self, name):
        """A folder *name* of this run's output, to be filled by other code (an atlas):
        inside the staged folder, started as a copy (hard links) of the earlier run's
        folder of that name, so what it held is reused, and committed with the rest."""
        self._stage()
        path = self.path(name)
        if not path.exists() and (self.final / name).is_dir():
            _carry(self.final / name, path)
        path.mkdir(parents=True, exist_ok=True)
        return path

    def path(self, name):
        """``--out``/*name*, after checking that *name* is a plain file name that stays
        inside the folder (:class:`OutputPathError` otherwise)."""
        name = str(name)
        shown = repr(name if len(name) <= 60 else name[:60] + "...")
        if not name or name in (".", "..") or ".." in name or "\0" in name \
                or os.path.isabs(name) or any(sep in name for sep in _SEPARATORS):
            raise OutputPathError("plain file names (no path separator, no '..', not "
                                  "absolute)", f"the file name {shown}")
        path = self.out_dir / name
        if Path(os.path.realpath(path)).parent != Path(os.path.realpath(self.out_dir)):
            raise OutputPathError(f"files inside {self.out_dir}",
                                  f"{shown}, which resolves to {os.path.realpath(path)}")
        return path

    def _write(self, name, write, *args):
        """Write *name* with ``write(path, *args)``; on a refusal or an OS error remove
        what this run wrote before (as :func:`mechcli.report.run.finish` does), so a
        failed run leaves none of its output, and raise :class:`OutputPathError`."""
        try:
            self._stage()
            path = self.path(name)
        except OutputPathError:
            self.discard()
            raise
        except OSError as exc:
            self.discard()
            raise OutputPathError(f"a folder where mechcli can write {name}",
                                  _os_reason(exc.filename or self.final, exc)) from None
        try:
            self.files.append(write(path, *args))
        except OSError as exc:
            # the path the OS refused: a parent folder (mkdir), else the file itself
            # (the rename target, never the temporary file), named as --out will hold it
            where = exc.filename2 or exc.filename
            if where is None or Path(where).name.startswith(f".{path.name}."):
                where = path
            where = self._shown(where)
            self.discard()
            raise OutputPathError(f"a folder where mechcli can write {name}",
                                  _os_reason(where, exc)) from None
        return self.files[-1]

    def text(self, name, text):
        return self._write(name, write_text, text)

    def bytes(self, name, data):
        """Write *data* (a rendered PNG or GIF) as *name*."""
        return self._write(name, write_bytes, data)

    def csv(self, name, columns, digits=None):
        digits = self.digits if digits is None else digits
        return self._write(name, write_csv, columns, digits)

    def csv_stream(self, name, headers, chunks, digits=None):
        """Write *name* from rows that arrive chunk by chunk (:func:`write_csv_stream`)."""
        digits = self.digits if digits is None else digits
        return self._write(name, write_csv_stream, headers, chunks, digits)

    def manifest(self, info):
        """Write ``outputs.json``, the manifest of this run, and remove what the previous
        run of the same spec into this folder wrote and this one did not.

        The manifest is *info* (command, spec hash, ``--set`` overrides, versions) plus
        ``files``: the name, size and SHA-256 of every file this run wrote.  A file the
        previous manifest lists and this run did not write is kept when the previous run
        solved the same problem (the same spec contents and ``--set`` values: a figure of
        an earlier run stays through a ``--no-plot`` rerun) and is still the file mechcli
        wrote; it is listed with ``"kept": true`` (:attr:`reused`).  Otherwise it is
        stale (a ``kin.gif`` of an earlier ``--animate`` of another spec version beside a
        new ``kin.csv``): removed when it is still the file mechcli wrote (same SHA-256),
        kept as the user's otherwise.  Nothing the previous manifest does not list is ever
        touched, nor a name that is not a plain file name in this folder.

        Returns
        -------
        path : Path
            The manifest.
        removed, kept : list of str
            Stale files removed, and stale files kept because they changed since.
        """
        import json

        final = self.final
        earlier = _manifest_doc(final)
        previous = read_manifest(final, same_as=info)
        still_valid = _same_problem(earlier, info)
        self._stage()
        entries = []
        for f in self.files:
            size, digest = _WRITTEN.get(str(f)) or (f.stat().st_size, file_sha256(f))
            entries.append({"name": self._relative(f), "bytes": size, "sha256": digest})
        doc = {"generator": "mechcli", "format": MANIFEST_FORMAT, **info, "files": entries}
        written = {e["name"] for e in entries} | {MANIFEST}
        self.reused = []
        # what the earlier run wrote and this one did not: removed (left out of the new
        # folder) while it is still the file mechcli wrote, kept (carried over) otherwise
        listed = {}
        for old in previous:
            name = old.get("name") if isinstance(old, dict) else None
            if isinstance(name, str):
                listed[name] = old.get("sha256")
        removed, kept, carry = [], [], []
        for name in sorted(written - {MANIFEST}):
            there = final / name
            if there.is_dir() and not there.is_symlink():   # the user's folder: never replaced
                self.discard()
                raise OutputPathError(f"a folder where mechcli can write {name}",
                                      f"{there}: Is a directory")
        if final.is_dir():
            for entry in sorted(os.listdir(final)):
                if entry in written or entry.startswith(f".{final.name}.mechcli-") \
                        or os.path.lexists(self.staged / entry):   # this run's own folder
                    continue
                src = final / entry
                if entry in listed and not src.is_symlink() and src.is_file():
                    if file_sha256(src) == listed[entry]:
                        if still_valid:    # the same problem's output: still valid
                            self.reused.append(entry)
                            entries.append({"name": entry, "bytes": src.stat().st_size,
                                            "sha256": listed[entry], "kept": True})
                            carry.append(entry)
                            continue
                        removed.append(entry)
                        continue
                    kept.append(entry)
                carry.append(entry)     # never mechcli's, or changed since: the user's
        try:
            for entry in carry:
                _carry(final / entry, self.staged / entry)
        except OSError as exc:
            self.discard()
            raise OutputPathError(f"a folder where mechcli can write {MANIFEST}",
                                  _os_reason(final, exc)) from None
        self._write_quiet(MANIFEST, json.dumps(doc, ensure_ascii=False, indent=2) + "\n")
        self._commit()
        return final / MANIFEST, removed, kept

    def _commit(self):
        """The staged folder becomes --out in one step; the earlier folder is removed."""
        import shutil

        final, staged = self.final, self.staged
        try:
            if not final.exists():
                os.rename(staged, final)
            elif _exchange(staged, final):
                shutil.rmtree(staged, ignore_errors=True)
            else:   # two renames: --out is absent for the instant between them
                old = final.parent / f".{final.name}.mechcli-old-{os.urandom(6).hex()}"
                os.rename(final, old)
                os.rename(staged, final)
                shutil.rmtree(old, ignore_errors=True)
        except OSError as exc:
            self.discard()
            raise OutputPathError("a folder mechcli can replace with its outputs",
                                  _os_reason(final, exc)) from None
        if self in _STAGED:
            _STAGED.remove(self)
        self.staged = None
        self.out_dir = final
        moved = []
        for f in self.files:
            rel = Path(f).relative_to(staged) if staged in Path(f).parents else Path(f.name)
            info = _WRITTEN.get(str(f))
            moved.append(final / rel)
            if info is not None:
                _WRITTEN[str(final / rel)] = info
        self.files = moved

    def _write_quiet(self, name, text):
        """Write *name* as :meth:`text` does (an OS error is an :class:`OutputPathError`),
        without listing it among the run's files."""
        path = self.text(name, text)
        self.files.remove(path)
        return path

    def discard(self):
        """Forget this run's output: its staged folder is removed, so that a run that
        fails after writing leaves the earlier run's folder as it was."""
        if self.staged is not None:
            import shutil
            shutil.rmtree(self.staged, ignore_errors=True)
            if self in _STAGED:
                _STAGED.remove(self)
            self.staged = None
            self.out_dir = self.final
        self.files.clear()


#: Outputs whose staged folder is not committed yet (removed by :func:`abandon_staged`)
_STAGED: list = []


def abandon_staged():
    """Remove the staged folder of every run not committed (an error or an interrupt
    reached the command line's boundary): --out keeps the earlier run's files."""
    for out in list(_STAGED):
        out.discard()


def _carry(src, dst):
    """The earlier folder's entry *src* into the staged folder: hard links (no copy, the
    original untouched until the swap), a copy where the file system has none, and a
    folder (an atlas under --out) as a tree of them."""
    import shutil

    if src.is_symlink():
        os.symlink(os.readlink(src), dst)
    elif src.is_dir():
        shutil.copytree(src, dst, symlinks=True, copy_function=_link_or_copy)
    else:
        _link_or_copy(src, dst)


def _link_or_copy(src, dst):
    try:
        os.link(src, dst)
    except OSError:
        import shutil
        shutil.copy2(src, dst)
    return dst


_RENAME_EXCHANGE = 2
_renameat2 = None


def _exchange(a, b):
    """Swap the folders *a* and *b* atomically (Linux ``renameat2`` with
    ``RENAME_EXCHANGE``); False where that is not available."""
    global _renameat2
    if not sys.platform.startswith("linux"):
        return False
    if _renameat2 is None:
        try:
            import ctypes
            libc = ctypes.CDLL(None, use_errno=True)
            fn = libc.renameat2
            fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                           ctypes.c_uint]
            fn.restype = ctypes.c_int
            _renameat2 = (fn, ctypes)
        except (OSError, AttributeError):
            _renameat2 = False
    if not _renameat2:
        return False
    fn, ctypes = _renameat2
    at_fdcwd = -100
    if fn(at_fdcwd, os.fsencode(str(a)), at_fdcwd, os.fsencode(str(b)), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP if hasattr(errno, "ENOTSUP") else -1):
        return False            # a file system without it: the two renames
    raise OSError(err, os.strerror(err), str(b))
