"""PNG diagrams and GIF animation for ``mechcli force`` (imports matplotlib)."""

from __future__ import annotations


def write(spec, result, sweep, outputs, lang, plots=True, animate=False):
    """Write the force PNGs (and the GIF); return warnings."""
    return []
