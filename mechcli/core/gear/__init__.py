"""Involute gears (chapter 5).

Modules
-------
involute
    The involute function, its inverse, curve points and the book's table.
spur
    Spur gear geometry; :class:`~.spur.GearError` (numbers as attributes, no
    unit names: the report layer words them) and ``GearGeometryError``.
pair
    Gear pairs (external and internal): mounting, backlash, contact ratio;
    ``MeshError``.
profile
    Tooth outlines (rack-generated teeth, rings).
generation
    Generation by a rack cutter: cutter positions.
helical, bevel, worm
    Helical, straight bevel and worm drives.
problems
    One ``mechcli gear`` problem (duck-typed problem data) solved per kind:
    :func:`~.problems.solve_gear`.

May import: numpy and scipy (lazily: involute, spur, pair, helical, bevel,
worm and problems load without numpy so the scalar kinds start fast),
:mod:`mechcli.core.errors` and :mod:`mechcli.core.numerics`; nothing of spec,
report, commands or cli.
"""
