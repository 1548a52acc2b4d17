"""Installed versions of the libraries, without importing them or :mod:`importlib.metadata`.

``mechcli --version`` and every run's ``outputs.json`` name the versions of numpy,
scipy and matplotlib.  Importing :mod:`importlib.metadata` (email, zipfile, socket,
pathlib ...) and letting it look a distribution up costs about 25 ms of a run of
~100 ms (start-up).  The version is one header of a file that is easy to
find: the first ``NAME-VERSION.dist-info`` directory along :data:`sys.path` (the
order :mod:`importlib.metadata` searches too) holds ``METADATA`` with a
``Version:`` line.  Anything else (an egg, a zip, an odd layout) falls back to
:mod:`importlib.metadata`.
"""

from __future__ import annotations

import os
import sys

__all__ = ["version", "loaded_or_installed", "python_version"]


def _normalize(name):
    """PEP 503 name, with ``_`` as dist-info directories spell it."""
    return name.replace("-", "_").replace(".", "_").lower()


_index = None


def _dist_infos():
    """``{normalized name: METADATA path}`` of the first ``*.dist-info`` of each name
    along sys.path (one directory listing per entry, once per process)."""
    global _index
    if _index is None:
        _index = {}
        for entry in sys.path:
            try:
                names = os.listdir(entry or ".")
            except OSError:   # a zip, a missing directory, a file
                continue
            for d in names:
                if d.endswith(".dist-info"):
                    key = _normalize(d[:-len(".dist-info")].partition("-")[0])
                    _index.setdefault(key, os.path.join(entry or ".", d, "METADATA"))
    return _index


def _from_dist_info(name):
    """The version from the first matching ``*.dist-info/METADATA`` on sys.path, or None
    (not found there: the caller asks :mod:`importlib.metadata`)."""
    path = _dist_infos().get(_normalize(name))
    if path is None:
        return None
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("Version:"):
                    return line.split(":", 1)[1].strip()
                if not line.strip():   # the end of the headers
                    break
    except OSError:
        pass
    return None


def version(name):
    """The installed version of distribution *name*, or None if it is not installed."""
    v = _from_dist_info(name)
    if v is not None:
        return v
    import importlib.metadata
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return None


def loaded_or_installed(name):
    """``module.__version__`` of an imported module (free), else :func:`version`."""
    v = getattr(sys.modules.get(name), "__version__", None)
    return v if v is not None else version(name)


def python_version():
    """``platform.python_version()`` without importing :mod:`platform` (~1.5 ms): the
    first word of :data:`sys.version` (``3.11.7``, ``3.13.0rc1``)."""
    return sys.version.split()[0]
