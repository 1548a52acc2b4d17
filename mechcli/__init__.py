"""mechcli: theory of machines (机械原理) from TOML problem files.

Also a library: the linkage engine is public and batched over designs as well
as over input positions (see ``docs/library.md``)::

    import numpy as np
    import mechcli

    m = mechcli.solve(mechcli.four_bar(l1, l2, l3, l4),
                      {1: mechcli.DriverMotion(theta, 10.0)}, order=2)

The names below are imported lazily (module ``__getattr__``), so the command
line does not pay for numpy where it does not need it.
"""

__version__ = "0.1.0"

#: public name -> module that defines it
_PUBLIC = {
    "four_bar": "mechcli.core.linkage.presets",
    "slider_crank": "mechcli.core.linkage.presets",
    "guide_bar": "mechcli.core.linkage.presets",
    "shaper": "mechcli.core.linkage.presets",
    "solve": "mechcli.core.linkage.engine",
    "DriverMotion": "mechcli.core.linkage.engine",
    "kinematic_coefficients": "mechcli.core.linkage.engine",
    "Linkage": "mechcli.core.linkage.engine",
    "LinkageMotion": "mechcli.core.linkage.engine",
    # notebooks: DataFrames, book-format tables, the book's figure (mechcli/notebook.py)
    "to_frame": "mechcli.notebook",
    "summary": "mechcli.notebook",
    "plot": "mechcli.notebook",
    "run_spec": "mechcli.notebook",
}

__all__ = ["__version__", *_PUBLIC]


def __getattr__(name):
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'mechcli' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__():
    return sorted(list(globals()) + list(_PUBLIC))
