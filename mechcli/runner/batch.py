"""Run many specs and compare their ``[expected]`` values: the engine of ``mechcli check``.

This is orchestration, not core: it finds the specs (:func:`collect`), runs
each with the command its ``command`` key names, in this process
(:func:`run_spec`, through :func:`mechcli.cli.main` with stdout and stderr
captured), and compares the run's ``--json`` results with
:func:`mechcli.spec.expected.evaluate`.  :func:`run_batch` spreads the specs
over worker processes.  Everything a worker returns is plain data (dicts), so
it pickles and goes straight into the JSON output.

A spec that cannot run (no ``command``, unreadable, bad spec: exit 2, no
solution: exit 3, an internal error: exit 1) is a failure of that spec; the
rest still run.
"""

from __future__ import annotations

import glob
import os
import time
from pathlib import Path

#: spec statuses
PASSED, FAILED, ERROR = "passed", "failed", "error"


def collect(paths):
    """The spec files named by *paths* (files, folders searched recursively
    for ``*.toml``, glob patterns), in order without duplicates.

    Returns
    -------
    (list of Path, list of dict)
        The specs, and one problem ``{"path", "error", "exit_code"}`` per
        argument that names no spec (a folder without specs, a pattern that
        matches nothing, a missing file).
    """
    specs, problems, seen = [], [], set()

    def add(p):
        key = os.path.normpath(str(p))
        if key not in seen:
            seen.add(key)
            specs.append(Path(p))

    for arg in map(str, paths):
        p = Path(arg)
        if p.is_dir():
            found = sorted(q for q in p.rglob("*.toml") if q.is_file() or q.is_symlink())
            if not found:
                problems.append(_problem(arg, "a folder with no *.toml specs"))
            for q in found:
                add(q)
        elif p.exists() or p.is_symlink():
            add(p)
        elif glob.has_magic(arg):
            found = sorted(glob.glob(arg, recursive=True))
            files = []
            for q in map(Path, found):
                files.extend(sorted(q.rglob("*.toml")) if q.is_dir() else [q])
            if not files:
                problems.append(_problem(arg, "no file matches this pattern"))
            for q in files:
                add(q)
        else:
            problems.append(_problem(arg, "no such file or folder"))
    return specs, problems


def _problem(path, message, code=2):
    return {"path": str(path), "error": message, "exit_code": code}


def _read_command(path):
    """(command, None) or (None, one-line error) from the spec's top-level ``command``."""
    import sys
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    from mechcli.cli import COMMANDS
    from mechcli.spec.errors import closest

    try:
        with open(path, "rb") as fh:
            data = tomllib.loads(fh.read().decode("utf-8"))
    except OSError as exc:
        return None, f"cannot read the file: {exc.strerror or exc}"
    except UnicodeDecodeError:
        return None, "expected UTF-8 text, got undecodable bytes"
    except tomllib.TOMLDecodeError as exc:
        return None, f"expected valid TOML, got a syntax error: {exc}"
    command = data.get("command")
    runnable = sorted(c for c in COMMANDS if c not in ("check", "new", "schema"))
    if command is None:
        return None, ("no top-level command = \"...\" key, so mechcli check cannot tell "
                      "which command runs it (one of " + ", ".join(runnable) + ")")
    if not isinstance(command, str) or command not in runnable:
        near = closest(str(command), runnable)
        return None, (f"command: expected one of {', '.join(runnable)}, got {command!r}"
                      + (f" (did you mean '{near}'?)" if near else ""))
    return command, None


def _last_error(stderr):
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    errs = [ln for ln in lines if ln.startswith("mechcli: error:")]
    line = (errs or lines or ["(no message)"])[-1]
    return line.removeprefix("mechcli: error: ")


def run_spec(path, sets=(), plot=False, out_dir=None, tmp_root=None):
    """Run one spec in this process and compare its ``[expected]`` values.

    Parameters
    ----------
    path : str or Path
        The spec.
    sets : sequence of str
        ``--set KEY=VALUE`` overrides for this run.
    plot : bool
        Write pictures (and the animation the spec asks for); otherwise the
        run gets ``--no-plot --no-animate``.
    out_dir : str or Path or None
        Where the command writes; None: a fresh temporary directory, removed
        afterwards.
    tmp_root : str or Path or None
        Where that temporary directory is made (None: the system's temporary
        folder); :func:`run_batch` gives one it removes even if the batch is
        interrupted.

    Returns
    -------
    dict
        ``{"spec", "command", "status", "exit_code", "time_s", "checks",
        "error", "warnings", "stderr"}``: status ``passed`` (every check
        held), ``failed`` (some did not: exit code 4) or ``error`` (the spec
        could not run: the command's exit code, 2 when it names none).
    """
    import contextlib
    import io
    import json
    import shutil
    import tempfile

    t0 = time.perf_counter()
    out = {"spec": str(path), "command": None, "status": ERROR, "exit_code": 2,
           "time_s": 0.0, "checks": [], "error": None, "warnings": [], "stderr": ""}

    def done():
        out["time_s"] = time.perf_counter() - t0
        return out

    command, error = _read_command(path)
    out["command"] = command
    if error:
        out["error"] = f"{path}: {error}"
        return done()
    tmp = None
    if out_dir is None:
        tmp = out_dir = tempfile.mkdtemp(prefix="mechcli-check-", dir=tmp_root)
    argv = [command, str(path), "--json", "--quiet", "--out", str(out_dir)]
    if not plot:
        argv += ["--no-plot", "--no-animate"]
    for s in sets:
        argv += ["--set", s]
    from mechcli.cli import main

    stdout, stderr = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
            try:
                main(argv)
                code = 0
            except SystemExit as exc:
                code = exc.code if isinstance(exc.code, int) else 1
    finally:
        if tmp is not None:
            shutil.rmtree(tmp, ignore_errors=True)
    out["stderr"] = stderr.getvalue()
    if code == 130:
        # Ctrl-C reached the command (mechcli.cli.main turned it into exit 130):
        # it stops the batch, not only this spec
        raise KeyboardInterrupt
    out["exit_code"] = code
    if code != 0:
        out["error"] = _last_error(out["stderr"])
        return done()
    from mechcli.spec.errors import SpecError
    from mechcli.spec.expected import evaluate

    doc = json.loads(stdout.getvalue())
    try:
        checks = evaluate(path, sets, doc["results"])
    except SpecError as exc:
        out["error"] = exc.format()
        return done()
    out["warnings"] = list(doc.get("warnings", ()))
    out["checks"] = [c.as_dict() for c in checks]
    held = all(c.held for c in checks)
    out["status"], out["exit_code"] = (PASSED, 0) if held else (FAILED, 4)
    return done()


def _init_worker():
    import signal
    os.environ.setdefault("MPLBACKEND", "Agg")
    # Ctrl-C is the parent's business: it stops the pool (a worker that caught
    # SIGINT itself would carry on with the next spec, or die holding the
    # queue's lock and leave the parent waiting for ever)
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_batch(specs, sets=(), jobs=None, plot=False, out_dirs=None, on_done=None):
    """Run every spec (:func:`run_spec`), *jobs* at a time.

    ``jobs == 1`` (or a single spec) runs serially in this process; otherwise
    a :class:`concurrent.futures.ProcessPoolExecutor` of
    ``min(jobs, len(specs))`` workers.  *out_dirs* gives one output directory
    per spec (None: temporary directories).  *on_done(result)* is called as
    each spec finishes.  Returns the results in the order of *specs*.
    """
    specs = list(specs)
    out_dirs = list(out_dirs) if out_dirs is not None else [None] * len(specs)
    jobs = max(1, jobs or os.cpu_count() or 1)
    results = [None] * len(specs)
    if jobs == 1 or len(specs) <= 1:
        for i, (path, od) in enumerate(zip(specs, out_dirs)):
            results[i] = run_spec(path, sets, plot, od)
            if on_done:
                on_done(results[i])
        return results
    import concurrent.futures as cf
    import multiprocessing
    import shutil
    import tempfile

    ctx = multiprocessing.get_context("fork" if hasattr(os, "fork") else "spawn")
    # the workers' temporary directories live in one made here, so that they
    # are removed even when a worker is stopped in the middle of a spec
    tmp_root = tempfile.mkdtemp(prefix="mechcli-check-")
    pool = cf.ProcessPoolExecutor(max_workers=min(jobs, len(specs)), mp_context=ctx,
                                  initializer=_init_worker)
    try:
        futures = {pool.submit(run_spec, path, tuple(sets), plot, od, tmp_root): i
                   for i, (path, od) in enumerate(zip(specs, out_dirs))}
        for fut in cf.as_completed(futures):
            i = futures[fut]
            try:
                results[i] = fut.result()
            except Exception as exc:  # a worker died (killed, out of memory)
                results[i] = {"spec": str(specs[i]), "command": None, "status": ERROR,
                              "exit_code": 1, "time_s": 0.0, "checks": [],
                              "error": f"{specs[i]}: the worker running it failed: "
                                       f"{type(exc).__name__}: {exc}",
                              "warnings": [], "stderr": ""}
            if on_done:
                on_done(results[i])
    except BaseException:
        # Ctrl-C (or any other way out): stop the workers now, do not wait for
        # the specs still queued
        _stop_pool(pool)
        raise
    else:
        pool.shutdown(wait=True)
    finally:
        shutil.rmtree(tmp_root, ignore_errors=True)
    return results


def _stop_pool(pool):
    """Cancel what is queued and terminate the worker processes."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        try:
            proc.terminate()
        except Exception:  # already gone
            pass
    for proc in processes:
        proc.join(timeout=5)


def plot_dirs(specs, root=Path("out") / "check"):
    """``out/check/<stem>`` per spec; a stem seen before gets ``-2``, ``-3``..."""
    seen, out = {}, []
    for p in specs:
        stem = Path(p).stem
        n = seen[stem] = seen.get(stem, 0) + 1
        out.append(root / (stem if n == 1 else f"{stem}-{n}"))
    return out


def exit_code(results, problems):
    """The batch's exit code: 4 if any expected value is not met; else, if a
    spec could not run (or a path named none), the most serious of its codes
    in the order 1 (internal error), 2 (bad spec or input), 3 (no solution);
    else 0."""
    codes = [r["exit_code"] for r in results] + [p["exit_code"] for p in problems]
    if any(r["status"] == FAILED for r in results):
        return 4
    for code in (1, 2, 3):
        if code in codes:
            return code
    return next((c for c in codes if c), 0)
