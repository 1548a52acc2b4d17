"""Former name of :mod:`mechcli.runner.batch` (moved there), kept importable.

The module is registered under both names, so ``mechcli.batch`` *is*
``mechcli.runner.batch`` (attributes set on one, e.g. by a test's monkeypatch, are
seen by the other).
"""

import sys

from mechcli.runner import batch as _module

sys.modules[__name__] = _module
