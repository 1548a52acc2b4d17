"""Pure numerical core of mechcli: numpy/scipy only, SI units, radians.

Nothing in this package prints, plots, reads files or imports click, rich,
matplotlib or tomllib (checked by ``tests/unit/test_layering.py``).
"""
