"""Optimization of linkages and cams on the engine (chapter 7).

Holds: the design variables and the vectorized problem (:mod:`.problem`: a
whole population of candidate designs is one call of ``evaluate``, split into
chunks through one map-like function so that an executor can be plugged in),
the terms built on the linkage engine (:mod:`.terms`: function-generation and
path errors, transmission angles, assembly over a range, the crank conditions
of the book's g1...g6) and the methods (:mod:`.methods`: SLSQP, trust-constr,
Nelder-Mead, differential evolution, golden section, Brent, multi-start; all
from ``scipy.optimize`` except the book's golden section, which is
:func:`mechcli.core.numerics.golden_section_max`).

Design variables are plain numbers (the spec's numbers, e.g. millimetres and
degrees); the core never sees a unit or a spec key: :mod:`.build` makes the
problem from the numbers the spec layer has read and checked.

May import: numpy, scipy (inside functions), :mod:`mechcli.core.errors`,
:mod:`mechcli.core.numerics`, :mod:`mechcli.core.linkage`.
"""
