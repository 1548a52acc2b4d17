"""Disc cams (chapter 4): follower motion programs (:mod:`.motion`), the pitch
and working profiles with curvature and pressure-angle checks
(:mod:`.profile`), and the design of a cam from its spec (:mod:`.design`).

May import: numpy, scipy, :mod:`mechcli.core.errors` and
:mod:`mechcli.core.refine`; nothing of spec, report, commands or cli.
"""
