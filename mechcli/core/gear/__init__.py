"""Involute gears (chapter 5): the involute function and its inverse
(:mod:`.involute`), spur gear geometry (:mod:`.spur`), gear pairs
(:mod:`.pair`), tooth outlines (:mod:`.profile`), generation by a rack or a
shaper cutter (:mod:`.generation`), helical (:mod:`.helical`), bevel
(:mod:`.bevel`) and worm (:mod:`.worm`) drives.

May import: numpy, scipy, :mod:`mechcli.core.errors` and
:mod:`mechcli.core.refine`; nothing of spec, report, commands or cli.
"""
