"""Timing fresh processes the way users run them (``bench_startup.py``, ``bench_pictures.py``).

Start-up is measured with the bytecode cached, as after ``pip install`` (which compiles
every module) or any earlier run of an editable install.  An environment that sets
``PYTHONDONTWRITEBYTECODE`` (some sandboxes and containers do) would otherwise make every
run compile mechcli's sources again (~50 ms of a ~200 ms ``kin`` run) while numpy's
installed bytecode is used: the ratio would measure the compiler, not mechcli.  So the
processes run with bytecode writing on and ``PYTHONPYCACHEPREFIX`` pointing into a
temporary directory (nothing is written into the source tree or site-packages; the
baseline's numpy is compiled into the same cache by the warm-up run, so both sides read
cached bytecode).  ``--no-bytecode-cache`` measures the environment as it is.

Besides the wall time, each run's CPU time is kept: the CPU time of the process' main
thread from its start to its exit (:func:`time.thread_time`, printed by an ``atexit``
hook that :func:`once` adds to the command).  On a machine shared with other jobs the
wall time of a long command rarely gets a quiet moment while a short one often does,
which biases the wall-time ratio against the long command; the main thread's CPU time
does not count the waiting for a core.  (The process' CPU time would count the BLAS
threads that numpy's import starts, in the baseline too.)
"""

from __future__ import annotations

import os
import subprocess
import sys
import time


def bench_env(cache_dir, bytecode_cache=True, site_hooks=True):
    """The environment of the timed processes (a copy of ``os.environ``).

    ``site_hooks=False`` is for processes run with ``python -S`` (:func:`interpreter`):
    the site directories and mechcli's own go on ``PYTHONPATH`` instead, so that the
    ``.pth`` files of the environment (which may import modules into every process:
    some sandboxes import certifi, typing, tempfile, pathlib ... that way) run in
    neither mechcli's processes nor the baseline's, as on a clean installation."""
    env = dict(os.environ)
    if bytecode_cache:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(cache_dir)
    if not site_hooks:
        import site

        import mechcli

        paths = [os.path.dirname(os.path.dirname(os.path.abspath(mechcli.__file__)))]
        paths += site.getsitepackages()
        if site.ENABLE_USER_SITE:
            paths.append(site.getusersitepackages())
        if env.get("PYTHONPATH"):
            paths.append(env["PYTHONPATH"])
        env["PYTHONPATH"] = os.pathsep.join(paths)
    return env


def interpreter(site_hooks=True):
    """``[python]``, or ``[python, "-S"]`` without the site hooks (:func:`bench_env`)."""
    return [sys.executable] if site_hooks else [sys.executable, "-S"]


#: run first in the timed process: report the main thread's CPU time at exit
_HOOK = ("import atexit, sys, time\n"
         "atexit.register(lambda: sys.__stderr__.write("
         "'\\nMAIN_THREAD_CPU %r\\n' % time.thread_time()))\n")


def _hooked(argv):
    """*argv* (``python -c CODE ...`` or ``python -m MODULE ...``) with :data:`_HOOK` run
    first, in the same process."""
    py, *argv = argv
    opts = []
    while argv[0] not in ("-c", "-m"):   # interpreter options (-S)
        opts.append(argv.pop(0))
    flag, what, *rest = argv
    if flag == "-c":
        code = _HOOK + what
        return [py, *opts, "-c", code, *rest]
    if flag == "-m":
        code = (_HOOK + "import runpy\nsys.argv[0] = %r\n"
                "runpy.run_module(%r, run_name='__main__', alter_sys=True)\n" % (what, what))
        return [py, *opts, "-c", code, *rest]
    raise ValueError(f"cannot time {argv!r}")


def once(argv, cwd, env):
    """``(wall, cpu)`` [s] of one run of *argv* (stdout and stderr a pipe, as in CI);
    *cpu* is the CPU time of the process' main thread."""
    t0 = time.perf_counter()
    proc = subprocess.run(_hooked(argv), cwd=cwd, env=env, check=True, capture_output=True,
                          text=True)
    wall = time.perf_counter() - t0
    cpu = [ln for ln in proc.stderr.splitlines() if ln.startswith("MAIN_THREAD_CPU ")]
    return wall, float(cpu[-1].split()[1])


def round_robin(cmds, runs, cwd, env):
    """``({name: minimum wall time [s]}, {name: minimum CPU time [s]})`` of each of
    *cmds* ``{name: argv}``, run in turn *runs* times after one warm-up run each
    (bytecode, font and page caches), so that every command sees the same load."""
    for argv in cmds.values():
        once(argv, cwd, env)
    wall = {name: float("inf") for name in cmds}
    cpu = dict(wall)
    for _ in range(runs):
        for name, argv in cmds.items():
            w, c = once(argv, cwd, env)
            wall[name], cpu[name] = min(wall[name], w), min(cpu[name], c)
    return wall, cpu
