"""Orchestration outside the layers: runs of many specs and the files they keep.

* :mod:`mechcli.runner.batch` runs many specs in worker processes and compares
  their ``[expected]`` values (the engine of ``mechcli check``);
* :mod:`mechcli.runner.atlas_store` builds, opens and searches the Hrones-Nelson
  atlas on disk (``mechcli synth``'s chunks and manifest), and
  :mod:`mechcli.runner.atlas` runs synth's atlas problems on it (the process
  pool or Dask client the chunks go to, the folder the atlas is kept in);
* :mod:`mechcli.runner.results` computes another command's ``--json`` results in
  this process (``mechcli optimize``'s result objective and constraints).

The runner sits beside ``commands``: it may use ``cli``, ``commands``, ``spec``,
``report`` and ``core``, and it is what file I/O the core must not do.  It
imports no user-interface library itself (click, rich, matplotlib);
tests/unit/test_layering.py checks this.  ``mechcli.batch`` and
``mechcli.atlas_store`` are the same modules under their former names.
"""
