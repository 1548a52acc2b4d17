"""Linkage synthesis (chapter 3 §3.2–3.4): designs, each checked on the engine.

Modules
-------
design
    :class:`~.design.LinkageDesign`, the result every synthesis returns: the
    designed :class:`~mechcli.core.linkage.engine.Linkage`, its lengths and
    pivots, and what it must reproduce at its prescribed positions; builders
    from pivots (:func:`~.design.four_bar_design`, :func:`~.design.slider_crank_design`).
atlas
    The digital Hrones–Nelson atlas: pages of coupler curves, the type chart (图 7)
    and admissible ranges, Fourier shape descriptors, the build's chunks
    (:func:`~.atlas.build_chunk`), the ranking of a chunk against a target, and
    path synthesis (the matches refined with :mod:`mechcli.core.optimize`).  The
    files are :mod:`mechcli.atlas_store`'s.
guidance
    Rigid-body guidance: two and three positions of B and C (perpendicular
    bisectors, circumcentres), the inverse problem (moving pivots for given
    fixed pivots), coupler poses by the displacement matrix or a nonlinear
    solve, Burmester curves (four poses) and points (five poses).
function
    Function generation: Freudenstein's equation at 3–5 precision points,
    Chebyshev spacing, least squares, slider-crank and rocker–slider;
    the structural error.
targets
    The target functions y = f(x) a function generator is asked to reproduce:
    named ones a spec may ask for (never text evaluated) and tables of points.
    (``functions``, its former name, is the same module.)
quick_return
    Design from the time ratio K: crank-rocker (the four cases of 【例 3-8】),
    offset slider-crank, guide-bar.
verify
    :func:`~.verify.verify`: the design moved through its positions on the
    engine: residuals, Grashof type, γmin, branch/circuit and order defects.

May import: numpy, scipy (inside the functions that need it, so that kinds
without a nonlinear solve start fast), :mod:`mechcli.core.errors`,
:mod:`mechcli.core.numerics`, :mod:`mechcli.core.linkage` and
:mod:`mechcli.core.grashof`; nothing of spec, report, commands or cli.  SI
units and radians; errors carry numbers (:class:`~mechcli.core.errors.DescribedError`)
and no unit names.
"""
