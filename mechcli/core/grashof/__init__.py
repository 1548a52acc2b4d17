"""Type of a linkage chain (chapter 3 §3.1).

Modules
-------
chain
    One four-bar in pure Python (no numpy, so ``mechcli grashof --lengths``
    starts fast): Grashof's criterion, inversions, figures of merit (θ, ψ, K,
    γ, dead points), length ranges, slider-crank and guide-bar;
    :class:`~.chain.ClosureError`.
fourbar
    The same for batches of four-bars, vectorized with numpy (re-exports the
    scalar names of :mod:`.chain`), and transmission-angle curves.
fivebar
    5R five-bar classes and types, the RRRRP crank condition.
mobility
    The mobility (degrees of freedom) count F = 3n − 2P_L − P_H − F' + p'.
analysis
    :func:`~.analysis.solve_grashof`: one problem of ``mechcli grashof``
    (duck-typed problem data) -> :class:`~.analysis.GrashofSolution`;
    :func:`~.analysis.classify_batch` for ``--batch``.

May import: numpy (not in :mod:`.chain`, :mod:`.analysis` and :mod:`.mobility`
at module level; no scipy), :mod:`mechcli.core.errors`,
:mod:`mechcli.core.numerics` and :mod:`mechcli.core.linkage`; nothing of spec,
report, commands or cli.  Errors carry their numbers as attributes and no unit
names; the report layer words them.
"""
