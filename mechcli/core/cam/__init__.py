"""Disc cams (chapter 4): follower motion programs (:mod:`.motion`); the
follower, the pitch and working profiles with their normals, curvature and
pressure angle per cam angle (:mod:`.geometry`); the refined pressure-angle,
curvature and undercut checks over the cycle (:mod:`.checks`); the base-circle
sizing (:mod:`.sizing`); and the design of a cam from its spec (:mod:`.design`).
Errors carry numbers (SI, radians), no units or spec keys
(:class:`.geometry.CamError`).

May import: numpy, scipy, :mod:`mechcli.core.errors` and
:mod:`mechcli.core.numerics`; nothing of spec, report, commands or cli.
"""
