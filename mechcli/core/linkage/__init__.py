"""The linkage engine and everything built on it (chapters 1, 2, and the
engine behind synth, flywheel, optimize and the atlas).

Holds: the elements (driver, dyads, points) and their solver
(:mod:`.engine`), the sweep analysis with gaps, dead points and refined
extremes (:mod:`.kinematics`), kinetostatics (:mod:`.kinetostatics`) and the
force sweep (:mod:`.force_analysis`).

May import: numpy, scipy, :mod:`mechcli.core.errors` and
:mod:`mechcli.core.refine`; nothing of spec, report, commands or cli.

The names below are the package's public face (``from mechcli.core.linkage
import solve, four_bar``).
"""

from mechcli.core.linkage.engine import (  # noqa: F401
    ASSEMBLY_TOL, RPR, RRP, RRR, SINGULAR_TOL, Crank, DriverMotion, DyadCondition, Element,
    Ground, LinkMotion, Linkage, LinkageDefinitionError, LinkageMotion, PointMotion, PointOnLink,
    SlideMotion, SliderDriver, _needs, solve)
