"""Former name of :mod:`mechcli.runner.atlas_store` (moved there), kept importable.

The module is registered under both names, so ``mechcli.atlas_store`` *is*
``mechcli.runner.atlas_store`` (attributes set on one, e.g. by a test's monkeypatch, are
seen by the other).
"""

import sys

from mechcli.runner import atlas_store as _module

sys.modules[__name__] = _module
