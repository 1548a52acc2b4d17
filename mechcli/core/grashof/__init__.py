"""Type of a linkage chain (chapter 3 §3.1): Grashof's criterion for four-bars
and their inversions (:mod:`.fourbar`), five-bar and RRRRP classification
(:mod:`.fivebar`), and the mobility (degrees of freedom) count
(:mod:`.mobility`).

May import: numpy, scipy, :mod:`mechcli.core.errors`, :mod:`mechcli.core.refine`
and :mod:`mechcli.core.linkage` (to check a classification on the engine);
nothing of spec, report, commands or cli.
"""
