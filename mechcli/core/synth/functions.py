"""Former name of :mod:`mechcli.core.synth.targets` (renamed, issue 32 §5), kept importable.

The module is registered under both names, so ``mechcli.core.synth.functions``
*is* ``mechcli.core.synth.targets`` (attributes set on one, e.g. by a test's
monkeypatch, are seen by the other).
"""

import sys
from typing import TYPE_CHECKING

from mechcli.core.synth import targets as _module

if TYPE_CHECKING:  # the names a type checker sees through the alias
    from mechcli.core.synth.targets import *  # noqa: F401,F403

sys.modules[__name__] = _module
