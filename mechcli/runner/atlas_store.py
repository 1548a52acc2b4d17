"""The Hrones-Nelson atlas on disk: build it chunk by chunk, open it, search it.

An atlas is a directory: ``chunk-00000.npz`` ... (arrays ``desc`` (M, 4H) float32 and
``params`` (M, 5) float32: A, B, C, gx, gy) and ``manifest.json`` (format, version,
build parameters, finished chunks with their counts and sha256).  Chunks are written
to a temporary name and renamed, the manifest is rewritten (atomically) after each
finished chunk: an interrupted build leaves only valid chunks, and the same call
resumes it.  Every task (one chunk) goes through one map-like function: ``map``,
a process pool's ``map``, or a Dask client's (``mechcli synth --workers/--scheduler``).

The numbers (curves, descriptors, ranking) are :mod:`mechcli.core.synth.atlas`'s;
this module only reads and writes files, outside the core as the layering asks.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
from pathlib import Path
from typing import Tuple

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.records import record
from mechcli.core.synth import atlas as at


def _atomic_write(path: Path, data: bytes):
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def chunk_name(index):
    return f"chunk-{index:05d}.npz"


def _build_task(task):
    """Worker: build chunk ``index`` (rows start … stop) and write it; picklable."""
    directory, index, start, stop, parameters = task
    params = at.chunk_params(parameters, start, stop)
    desc, kept, ok = at.build_chunk(params, parameters["harmonics"])
    buf = io.BytesIO()
    np.savez(buf, desc=desc, params=kept)
    data = buf.getvalue()
    name = chunk_name(index)
    _atomic_write(Path(directory) / name, data)
    return {"index": int(index), "file": name, "count": int(desc.shape[0]),
            "candidates": int(stop - start), "bytes": len(data),
            "sha256": hashlib.sha256(data).hexdigest()}


@record
class AtlasInfo:
    """An atlas on disk: its directory, build parameters and finished chunks.

    ``curves``: kept curves in the finished chunks; ``candidates``: the
    parameter rows the build sweeps (ratio sets that are crank-rockers times
    grid points); ``complete``: every chunk finished.
    """

    directory: Path
    parameters: dict
    chunks: Tuple[dict, ...]
    curves: int
    candidates: int
    complete: bool

    @property
    def harmonics(self):
        return int(self.parameters["harmonics"])


def _manifest(parameters, chunks, candidates, nchunks):
    chunks = sorted(chunks, key=lambda c: c["index"])
    return {"format": at.FORMAT, "version": at.VERSION, "descriptor": at.DESCRIPTOR,
            "parameters": parameters, "candidates": int(candidates), "chunk_count": int(nchunks),
            "curves": int(sum(c["count"] for c in chunks)),
            "complete": len(chunks) == nchunks, "chunks": chunks}


def _parameters(A_range, B_range, C_range, grid, chunk, harmonics):
    def rng(r):
        r = tuple(r)
        if len(r) != 3 or int(r[2]) < 1 or not float(r[0]) <= float(r[1]):
            raise DescribedError("a ratio range must be (lo, hi, count) with lo <= hi and "
                                 "count >= 1", "range", range=r)
        return [float(r[0]), float(r[1]), int(r[2])]

    gx, gy = ([float(v) for v in np.asarray(g, dtype=float).reshape(-1)] for g in grid)
    if not gx or not gy:
        raise DescribedError("the coupler-point grid is empty", "grid")
    return {"A_range": rng(A_range), "B_range": rng(B_range), "C_range": rng(C_range),
            "grid": [gx, gy], "chunk": int(chunk), "harmonics": int(harmonics),
            "step": at.STEP, "positions": at.POSITIONS, "branch": 1}


def build_atlas(directory, A_range=at.DEFAULT_A_RANGE, B_range=at.DEFAULT_B_RANGE,
                C_range=at.DEFAULT_C_RANGE, grid=at.DEFAULT_GRID, chunk=20000, mapper=map,
                harmonics=16, resume=True, progress=None) -> AtlasInfo:
    """Sweep A, B, C over their ranges and the coupler point over the grid; keep
    every crank-rocker (crank 1) and store its descriptor with its parameters.

    Parameters
    ----------
    directory : path
        Created if missing.  Holds ``chunk-NNNNN.npz`` and ``manifest.json``.
    A_range, B_range, C_range : (lo, hi, count)
        Ratios (linspace).  Only crank-rocker ratio sets are swept.
    grid : (x values, y values)
        The coupler plane's grid [crank lengths].
    chunk : int
        Parameter rows per chunk (memory is bounded by it: ~ chunk × 72 × a few
        hundred bytes in the worker).
    mapper : callable
        ``mapper(function, tasks)``, e.g. ``map`` or an executor's ``map``;
        each task builds and writes one chunk and returns its manifest entry.
    harmonics : int
    resume : bool
        Skip the chunks the manifest lists (after checking that the build's
        parameters are the same); ``False`` rebuilds everything.
    progress : callable or None
        Called as ``progress(done, chunks, curves=, resumed=)`` once before the
        first task (the chunks a resumed build already has) and after each
        finished chunk: chunks done of all, curves kept so far, chunks found on
        disk (the caller shows it; nothing here prints).

    Raises
    ------
    DescribedError
        ``"no_crank_rocker"`` when the ranges hold no crank-rocker;
        ``"atlas_foreign"`` when the directory holds another atlas (other
        parameters) or a file that is not an atlas manifest; ``"range"``,
        ``"grid"`` for malformed ranges.
    """
    directory = Path(directory)
    parameters = _parameters(A_range, B_range, C_range, grid, chunk, harmonics)
    if int(chunk) < 1:
        raise DescribedError("the chunk size must be at least 1", "chunk", chunk=int(chunk))
    sets = at.ratio_sets(parameters["A_range"], parameters["B_range"], parameters["C_range"])
    if sets.shape[0] == 0:
        raise DescribedError("the ranges of A, B and C contain no crank-rocker",
                             "no_crank_rocker", A=parameters["A_range"][:2],
                             B=parameters["B_range"][:2], C=parameters["C_range"][:2])
    candidates = sets.shape[0] * len(parameters["grid"][0]) * len(parameters["grid"][1])
    nchunks = -(-candidates // int(chunk))
    directory.mkdir(parents=True, exist_ok=True)
    done = {}
    mpath = directory / at.MANIFEST
    if mpath.exists() and resume:
        old = _read_manifest(directory)
        if old["parameters"] != json.loads(json.dumps(parameters)):
            raise DescribedError("the directory holds an atlas built with other parameters",
                                 "atlas_foreign")
        for c in old["chunks"]:
            f = directory / c["file"]
            if f.exists() and f.stat().st_size == c["bytes"]:
                done[c["index"]] = c
    _atomic_write(mpath, json.dumps(_manifest(parameters, list(done.values()), candidates,
                                              nchunks), indent=1).encode())
    tasks = [(str(directory), i, i * int(chunk), min(candidates, (i + 1) * int(chunk)),
              parameters) for i in range(nchunks) if i not in done]
    resumed = len(done)

    def report():
        if progress is not None:
            progress(len(done), nchunks, curves=int(sum(c["count"] for c in done.values())),
                     resumed=resumed)

    report()
    for entry in mapper(_build_task, tasks):
        done[entry["index"]] = entry
        _atomic_write(mpath, json.dumps(_manifest(parameters, list(done.values()), candidates,
                                                  nchunks), indent=1).encode())
        report()
    return open_atlas(directory)


def _read_manifest(directory):
    mpath = Path(directory) / at.MANIFEST
    try:
        present = mpath.is_file()
    except (OSError, ValueError):       # a name too long, a NUL byte
        present = False
    if not present:
        raise DescribedError("the directory holds no atlas manifest", "atlas_foreign")
    try:
        data = json.loads(mpath.read_bytes().decode("utf-8"))
    except OSError as exc:
        raise DescribedError(f"the atlas manifest cannot be read ({exc.strerror})",
                             "atlas_corrupt") from None
    except (ValueError, UnicodeDecodeError):
        raise DescribedError("the atlas manifest is not valid JSON", "atlas_corrupt") from None
    if not isinstance(data, dict) or data.get("format") != at.FORMAT:
        raise DescribedError("the file is not a Hrones-Nelson atlas manifest", "atlas_foreign")
    if data.get("version") != at.VERSION or data.get("descriptor") != at.DESCRIPTOR:
        raise DescribedError("the atlas was written by another version of the format",
                             "atlas_foreign", version=data.get("version"))
    try:
        p = data["parameters"]
        for key in ("A_range", "B_range", "C_range", "grid", "harmonics", "chunk"):
            p[key]
        h = p["harmonics"]
        if isinstance(h, bool) or not isinstance(h, int) or not 1 <= h <= 1024:
            raise TypeError
        for c in data["chunks"]:
            if not (isinstance(c["index"], int) and isinstance(c["count"], int)
                    and isinstance(c["sha256"], str) and c["file"] == chunk_name(c["index"])):
                raise TypeError
        int(data["candidates"]), int(data["chunk_count"])
    except (KeyError, TypeError, ValueError):
        raise DescribedError("the atlas manifest is incomplete or malformed",
                             "atlas_corrupt") from None
    return data


def _load_chunk(directory, entry, verify=True, harmonics=None):
    path = Path(directory) / entry["file"]
    try:
        data = path.read_bytes()
    except OSError:
        raise DescribedError("an atlas chunk listed in the manifest is missing",
                             "atlas_corrupt", chunk=entry["index"]) from None
    if verify and hashlib.sha256(data).hexdigest() != entry["sha256"]:
        raise DescribedError("an atlas chunk does not match its checksum", "atlas_corrupt",
                             chunk=entry["index"])
    try:
        with np.load(io.BytesIO(data), allow_pickle=False) as z:
            desc, params = z["desc"], z["params"]
    except Exception:
        raise DescribedError("an atlas chunk cannot be read", "atlas_corrupt",
                             chunk=entry["index"]) from None
    if desc.shape[0] != entry["count"] or params.shape != (entry["count"], 5) \
            or (harmonics is not None and desc.shape[1:] != (4 * harmonics,)):
        raise DescribedError("an atlas chunk holds another number of curves than listed",
                             "atlas_corrupt", chunk=entry["index"])
    return desc, params


def open_atlas(directory, verify=False) -> AtlasInfo:
    """Read and validate an atlas's manifest (``verify``: also every chunk's
    checksum and shape).  Raises ``DescribedError`` with reason
    ``"atlas_corrupt"`` (unreadable or inconsistent manifest, a missing,
    truncated or altered chunk) or ``"atlas_foreign"`` (not an atlas of this
    format and version)."""
    directory = Path(directory)
    data = _read_manifest(directory)
    for c in data["chunks"]:
        f = directory / c["file"]
        if not f.exists() or f.stat().st_size != c.get("bytes", -1):
            raise DescribedError("an atlas chunk listed in the manifest is missing or "
                                 "truncated", "atlas_corrupt", chunk=c["index"])
        if verify:
            _load_chunk(directory, c, True)
    chunks = tuple(sorted(data["chunks"], key=lambda c: c["index"]))
    return AtlasInfo(directory, data["parameters"], chunks,
                     int(sum(c["count"] for c in chunks)), int(data["candidates"]),
                     len(chunks) == int(data["chunk_count"]))




def _search_task(task):
    """Worker: the k best rows of one chunk for the queries; picklable."""
    directory, entry, Q, k, verify = task
    desc, params = _load_chunk(directory, entry, verify, Q.shape[1] // 4)
    return (*at.rank_chunk(desc, params, Q, k), entry["index"])


def search(directory_or_info, x, y, k=10, closed=True, mapper=map, verify=True,
           progress=None):
    """The k atlas curves nearest the target path by descriptor distance.

    Parameters
    ----------
    directory_or_info : path or AtlasInfo
    x, y : array_like (K,)
        Target points in order (any position, orientation, scale).
    k : int
    closed : bool
        True: the points go round a closed path (the last joined to the
        first).  False: an open path.  An open path is closed by its chord and
        described like a closed one, so it matches a closed curve of which it
        is most (roughly 2/3 or more of the length): the chord stands in for
        the missing arc.  A shorter arc matches poorly and the hit is only a
        start for :func:`refine`, which measures the targets' distance to the
        whole curve (a part of it may serve).  Self-intersecting paths are
        served like any other (the descriptor is that of the curve's
        parametrization, loops included).
    mapper : callable
        ``mapper(function, tasks)`` over the chunks (one task per chunk; each
        streams its chunk from disk; only k rows per chunk come back).
    verify : bool
        Check every chunk's sha256 as it is read.
    progress : callable or None
        Called as ``progress(done, chunks, curves=)`` after each chunk searched:
        chunks done of all, curves compared so far.

    Returns
    -------
    list of Match, nearest first.  Both directions of travel and both signs
    of the descriptor's even harmonics are tried (4 queries per chunk).

    Raises
    ------
    DescribedError
        ``"too_few_points"`` (fewer than 3 distinct points),
        ``"atlas_corrupt"``/``"atlas_foreign"``, ``"atlas_empty"``.
    """
    z = at.target_points(x, y)
    info = directory_or_info if isinstance(directory_or_info, AtlasInfo) \
        else open_atlas(directory_or_info)
    if info.curves == 0:
        raise DescribedError("the atlas holds no curve", "atlas_empty")
    Q = at.queries(z, info.harmonics)
    tasks = [(str(info.directory), c, Q, int(k), verify) for c in info.chunks]
    best = []
    seen = 0
    count = {c["index"]: c["count"] for c in info.chunks}
    for n, (dist, params, var, rows, index) in enumerate(mapper(_search_task, tasks), 1):
        seen += int(count.get(index, 0))
        if progress is not None:
            progress(n, len(tasks), curves=seen)
        for d, p, v, r in zip(dist.tolist(), params.tolist(), var.tolist(), rows.tolist()):
            best.append(at.Match(float(d), *p, reversed=bool(v >= 2), chunk=int(index),
                              row=int(r)))
        best.sort(key=lambda m: m.distance)
        del best[int(k):]
    return best


