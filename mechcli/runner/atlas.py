"""``mechcli synth``'s Hrones-Nelson atlas, run: where its chunks go, where it is kept.

:func:`atlas_mapper` is the one map-like function the chunks go through (in
process, a process pool, a Dask cluster), :func:`atlas_folder` the folder an
atlas is built in, and :func:`atlas_case` an ``atlas_build`` or ``path`` problem
run end to end on :mod:`mechcli.runner.atlas_store` (files) with the core's
numbers (:mod:`mechcli.core.synth.atlas`).
"""

from __future__ import annotations


def atlas_mapper(workers, scheduler):
    """The one map-like function the atlas's chunks go through, and a closer:
    ``map`` in-process; a process pool (``--workers N``); a Dask cluster
    (``--scheduler ADDRESS``, the ``dask`` extra)."""
    from mechcli.spec.errors import SpecError
    if scheduler is not None and not scheduler.strip():
        raise SpecError("--scheduler", "", "a Dask scheduler address such as tcp://host:8786",
                        "an empty address")
    if scheduler:
        try:
            from dask.distributed import Client
        except ImportError:
            raise SpecError("--scheduler", "", "the dask extra installed (pip "
                            "install 'mechcli[dask]')", "no dask.distributed") from None
        from mechcli.core.errors import UnsolvableError
        try:
            client = Client(scheduler, timeout="10s")
        except ValueError as exc:           # not an address
            raise SpecError("--scheduler", "", "a Dask scheduler address such as "
                            "tcp://host:8786", f"'{scheduler}' ({exc})") from None
        except Exception as exc:            # noqa: BLE001 (whatever the connection raises)
            raise UnsolvableError(f"--scheduler {scheduler}: cannot reach the Dask "
                                  f"scheduler ({type(exc).__name__}: {exc})") from None

        def dask_map(fn, items):
            return client.gather(client.map(fn, list(items), pure=False))
        return dask_map, client.close
    if workers and workers > 1:
        from concurrent.futures import ProcessPoolExecutor
        pool = ProcessPoolExecutor(workers)
        return pool.map, pool.shutdown
    return map, (lambda: None)


def atlas_folder(prob, run, atlas_dir, outputs=None):
    """Where an ``atlas_build`` writes, or where a ``path`` search builds its default
    atlas: the command line's ``--atlas DIR``, else inside ``--out`` (the spec's
    ``directory``, a relative folder there, or ``atlas``).  Inside ``--out`` the atlas
    is this run's output: it is built in the run's staged folder (*outputs*), started
    from the earlier run's atlas there (hard links: an atlas built once is resumed,
    not rebuilt), and committed with the run's other files."""
    from pathlib import Path

    if atlas_dir is not None:
        return Path(atlas_dir)
    sub = (prob.data.get("directory") if prob.kind == "atlas_build" else None) or "atlas"
    if outputs is None:
        return Path(run.out_dir) / sub
    staged = outputs.staged_folder(sub)
    return staged


def atlas_case(prob, spec, run, mapper, atlas_dir=None, outputs=None, progress=None):
    """``atlas_build`` and ``path``: the atlas on disk (mechcli.runner.atlas_store) with the
    core's numbers; a SynthSolution like the other kinds'.  *progress*
    (:class:`mechcli.report.console.Progress`) shows the build, the search and the
    refinement on a terminal, and a line per chunk or candidate with ``-v``."""
    import time
    from pathlib import Path

    from mechcli.core.synth import atlas
    from mechcli.core.synth.problems import SynthSolution
    from mechcli.report.console import Progress
    from mechcli.runner import atlas_store
    from mechcli.spec.errors import SpecError
    d = prob.data

    if progress is None:
        progress = Progress("synth", show=False)

    def build_line(done, total, curves, resumed):
        return (f"atlas: chunk {done}/{total} built, {curves:,} curves"
                + (f" ({resumed} found on disk)" if resumed else ""))

    def search_line(done, total, curves):
        return f"atlas: chunk {done}/{total} searched, {curves:,} curves compared"

    building = progress.stage("building the atlas (chunks)", detail=build_line)
    searching = progress.stage("searching the atlas (chunks)", detail=search_line)

    def refuse(directory, why):
        if outputs is not None:
            directory = outputs._shown(directory)
        # a folder the atlas cannot go into: the option's or the spec key's, exit 2
        if atlas_dir is not None:
            return SpecError("--atlas", "", "a folder the atlas can be written into",
                             f"'{directory}' ({why})")
        return SpecError(str(spec.path), f"{prob.path}.directory",
                         "a folder for the atlas", f"'{directory}' ({why})")

    if prob.kind == "atlas_build":
        directory = atlas_folder(prob, run, atlas_dir, outputs)
        grid = tuple(tuple(float(v) for v in __import__("numpy").linspace(lo, hi, n))
                     for lo, hi, n in (d["grid_x"], d["grid_y"]))
        t = time.perf_counter()
        if directory.exists() and not directory.is_dir():
            raise refuse(directory, "a file")
        try:
            info = atlas_store.build_atlas(directory, d["A"], d["B"], d["C"], grid,
                                           chunk=d["chunk"], mapper=mapper,
                                           harmonics=d["harmonics"], progress=building)
        except OSError as exc:
            raise refuse(directory, exc.strerror or str(exc)) from None
        return SynthSolution(prob.kind, None, None, (info, time.perf_counter() - t))
    if d["atlas"] is None:      # the default atlas, built once (under --out, or --atlas)
        directory = atlas_folder(prob, run, atlas_dir, outputs)
        if directory.exists() and not directory.is_dir():
            raise refuse(directory, "a file")
        try:
            atlas_store.build_atlas(directory, mapper=mapper, progress=building)
        except OSError as exc:
            raise refuse(directory, exc.strerror or str(exc)) from None
    else:                       # reading an atlas the spec names is allowed
        directory = Path(spec.path).parent / d["atlas"]
    pts = d["points"]
    x = [p[0] for p in pts]
    y = [p[1] for p in pts]
    t = time.perf_counter()
    info = atlas_store.open_atlas(directory)
    matches = atlas_store.search(info, x, y, k=d["k"], closed=d["closed"], mapper=mapper,
                                 progress=searching)
    t1 = time.perf_counter()
    # the matches are refined one by one: counted as the core takes each
    cands = atlas.path_synthesis(
        progress.track(matches, "refining the nearest curves",
                       detail=lambda done, total: f"refined {done}/{total} of the nearest "
                                                  "curves on the path"),
        x, y, d["angles"], method=d["refine"], gamma_min=d["gamma_min"])
    t2 = time.perf_counter()
    # the candidates' coupler curves over a revolution, for path.png
    import numpy as np

    from mechcli.core.linkage import DriverMotion, solve
    curves = {}
    for j, c in enumerate(cands[:5]):
        xo = c.refined.x_opt
        lk = atlas.placed_linkage(xo["A"], xo["B"], xo["C"], xo["gx"], xo["gy"],
                                  *c.refined.placement)
        m = solve(lk, {1: DriverMotion(np.linspace(0, 2 * np.pi, 721), 1.0, 0.0)}, order=0)
        ok = m.feasible
        curves[j] = (np.where(ok, m.points["P"].x, np.nan), np.where(ok, m.points["P"].y,
                                                                     np.nan))
    return SynthSolution(prob.kind, None, None,
                         {"curves": info.curves, "search_s": t1 - t, "refine_s": t2 - t1,
                          "candidates": cands, "targets": (x, y), "closed": d["closed"],
                          "angles": d["angles"], "paths": curves})
