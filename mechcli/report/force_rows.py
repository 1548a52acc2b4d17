"""``force.csv`` with both sides of every load switch.

Where a conditional load switches on or off inside the sweep, the table gets two
rows at the same input: the limit from the smaller input first, then from the
larger (:class:`~mechcli.core.linkage.load_switches.SwitchRows`, evaluated exactly
at the switch with the load held off and on).  A switch on a sample replaces that
sample's row.  This module merges those rows with the sweep's; the pictures merge
them the same way (:func:`mechcli.report.force_plots.with_switch_rows`).
"""

from __future__ import annotations

import types

import numpy as np

from mechcli.report.force import columns


def merged_order(q, switches):
    """How the sweep's rows and the switch rows interleave.

    Parameters
    ----------
    q : ndarray
        The sweep's inputs (increasing).
    switches : SwitchRows

    Returns
    -------
    keep : ndarray of int
        The sweep rows kept (those a switch row does not replace).
    order : ndarray of int
        Into ``concatenate([q[keep], switches.q])``: the merged rows in increasing
        input, the two rows of a switch in their order.
    """
    replaced = np.unique(switches.row[switches.row >= 0])
    keep = np.setdiff1d(np.arange(q.size), replaced)
    allq = np.concatenate([np.asarray(q, dtype=float)[keep], switches.q])
    return keep, np.argsort(allq, kind="stable")


def merge(values, switch_values, keep, order):
    """One merged column (see :func:`merged_order`)."""
    return np.concatenate([np.asarray(values)[keep], np.asarray(switch_values)])[order]


def csv_columns(spec, res, extra, switches):
    """``force.csv``'s columns (:func:`mechcli.report.force.columns`) with the rows of
    *switches* (None: the sweep's rows alone)."""
    cols = columns(spec, res, extra)
    if switches is None or not len(switches):
        return cols
    view = types.SimpleNamespace(q=switches.q, series=switches.series,
                                 forces=types.SimpleNamespace(cond=switches.cond),
                                 active_mask=switches.active)
    engine = getattr(extra, "engine", None) if extra is not None else None
    side_extra = None
    if extra is not None:
        side_extra = type(extra)(types.SimpleNamespace(series=switches.extra)
                                 if engine is not None else None)
    side = dict(columns(spec, view, side_extra))
    keep, order = merged_order(res.q, switches)
    out = []
    for name, v in cols:
        if name not in side:
            raise KeyError(f"force.csv column {name} has no value at the load switches")
        out.append((name, merge(v, side[name], keep, order)))
    return out
