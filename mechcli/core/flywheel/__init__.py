"""Flywheels and the motion of a machine under its forces (chapter 6).

Holds: the equivalent dynamic model of a one-degree-of-freedom machine reduced to its input
link (第二节): the equivalent moment of inertia Je(φ) with its derivative dJe/dφ (eq 6-4)
and the equivalent moment Me (eq 6-2), for a linkage of the engine, a table, a constant or a
gear train (:mod:`.equivalent`); the equation of motion of that model, its speed fluctuation
and the flywheel that bounds it (:mod:`.motion`).

May import: numpy, scipy (inside the functions that need it), :mod:`mechcli.core.errors`,
:mod:`mechcli.core.numerics` and :mod:`mechcli.core.linkage`; nothing of spec, report, commands
or cli.
"""
