"""The linkage engine and everything built on it (chapters 1 and 2, and the
engine behind synth, flywheel, optimize and the atlas).

Holds: the elements (drivers, dyads, points, each one class that owns its
solving step, pairs, slide name and drawing: :mod:`.elements`; what they draw,
:mod:`.sketch`), the linkage and
its batched solver (:mod:`.engine`), the book's named linkages
(:mod:`.presets`), the sweep analysis with gaps, dead points and refined
extremes (:mod:`.kinematics`), kinetostatics (:mod:`.kinetostatics`) and the
force sweep (:mod:`.force_analysis`).

May import: numpy, scipy, :mod:`mechcli.core.errors` and
:mod:`mechcli.core.numerics`; nothing of spec, report, commands or cli.

The names below are the package's public face (``from mechcli.core.linkage
import solve, four_bar``).
"""

from mechcli.core.linkage.elements import (  # noqa: F401
    ASSEMBLY_TOL,
    PRP,
    RPR,
    RRP,
    RRR,
    SINGULAR_TOL,
    Crank,
    Element,
    Ground,
    PointOnLink,
    SliderDriver,
)
from mechcli.core.linkage.engine import (  # noqa: F401
    DriverMotion,
    DyadCondition,
    Linkage,
    LinkageDefinitionError,
    LinkageMotion,
    LinkMotion,
    PointMotion,
    SlideMotion,
    kinematic_coefficients,
    solve,
    stack,
)
from mechcli.core.linkage.presets import four_bar, guide_bar, shaper, slider_crank  # noqa: F401

#: the drawing primitives (:mod:`.sketch`): built when first named, not at start-up
_SKETCH = ("Bar", "Block", "Guide", "Pivot")


def __getattr__(name):
    if name in _SKETCH:
        from mechcli.core.linkage import sketch
        return getattr(sketch, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
