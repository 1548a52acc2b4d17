"""Sweeps too long to hold in memory, solved and handed out chunk by chunk.

A streamed sweep is the rows of ``np.linspace(start, stop, count)`` for a
``count`` past what is kept in memory (``mechcli kin`` beyond 600,001
positions, up to 1e8).  Its analysis (gaps, dead points, refined extremes,
the table, the plots) runs on a subset of its rows (:func:`stream_grid`: every
k-th row, the last one and any rows asked for) through
:func:`~mechcli.core.linkage.kinematics.analyse_sweep`, whose extremes are
refined on the exact solution and so do not depend on the grid;
:class:`StreamedRows` then solves every row chunk by chunk and hands out the
values as ``analyse_sweep`` would give them (the regular rows outside the
excluded intervals, angles unwrapped), so the memory is bounded by one chunk
whatever ``count`` is.  It also keeps the largest and smallest value of every
quantity over all rows, to check the refined extremes against.

Rows are bit for bit those of ``np.linspace`` (:func:`rows_at`), and for a
sweep without gaps the values are bit for bit those of ``analyse_sweep`` over
all the rows at once (``tests/unit/linkage/test_speed_streaming.py``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechcli.core.linkage.engine import CHUNK, solve
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    pass

if TYPE_CHECKING:
    pass

#: rows of a streamed sweep that are analysed (every k-th): a 0.01° grid over a turn,
#: the resolution of a default `kin` run, before the 0.5° search grid of the analysis
ANALYSED = 36_001


def rows_at(start: FloatOrArray, stop: FloatOrArray, count: int, idx: np.ndarray):
    """Rows ``idx`` (integers) of ``np.linspace(start, stop, count)``, bit for bit
    (the same operations: ``i * step + start``, the last row ``stop``)."""
    idx = np.asarray(idx)
    step = (stop - start) / (count - 1)
    y = idx.astype(float)
    y *= step
    y += start
    if idx.size and idx[-1] == count - 1:
        y[idx == count - 1] = stop
    return y


def stream_grid(start: FloatOrArray, stop: FloatOrArray, count: int, extra: Any = (),
                analysed: Any = ANALYSED):
    """The analysed rows of a streamed sweep: every k-th row of
    ``np.linspace(start, stop, count)`` (k the smallest stride giving at most
    *analysed* rows), the last row, and the row nearest each input of *extra*
    (e.g. the table's), sorted, without repeats."""
    k = max(1, -(-(count - 1) // (analysed - 1)))
    idx = np.arange(0, count, k)
    if idx[-1] != count - 1:
        idx = np.append(idx, count - 1)
    extra = np.asarray(extra, dtype=float)
    if extra.size:
        step = (stop - start) / (count - 1)
        near = np.clip(np.rint((extra - start) / step), 0, count - 1).astype(idx.dtype)
        idx = np.sort(np.concatenate((idx, near)))
        idx = idx[np.concatenate(([True], idx[1:] != idx[:-1]))]
    return rows_at(start, stop, count, idx)


def _corrections(dd: FloatOrArray):
    """``np.unwrap``'s phase corrections of the differences ``dd`` (period 2π)."""
    high = np.pi
    ddmod = np.mod(dd + high, 2 * np.pi) - high
    np.copyto(ddmod, high, where=(ddmod == -high) & (dd > 0))
    corr = ddmod - dd
    np.copyto(corr, 0, where=np.abs(dd) < high)
    return corr


class _Unwrap:
    """``np.unwrap`` of one angle carried across chunks: the same differences,
    corrections and running sum as over the whole run at once."""

    def __init__(self) -> None:
        self.last = None   # the previous raw value of the run
        self.total = 0.0   # the running sum of the corrections
        self.shift = 0.0

    def start(self, shift: Any) -> None:
        """A new run, its values shifted by ``-shift``."""
        self.last, self.total, self.shift = None, 0.0, shift

    def __call__(self, p: Any):
        if p.size == 0:
            return p
        if self.last is None:
            dd = np.diff(p)
            up = p.copy()
            if dd.size:
                c = np.cumsum(np.concatenate(([self.total], _corrections(dd))))[1:]
                up[1:] = p[1:] + c
                self.total = c[-1]
        else:
            dd = np.diff(np.concatenate(([self.last], p)))
            c = np.cumsum(np.concatenate(([self.total], _corrections(dd))))[1:]
            up = p + c
            self.total = c[-1]
        self.last = p[-1]
        return up - self.shift


class StreamedRows:
    """The rows of a streamed sweep, chunk by chunk.

    Parameters
    ----------
    linkage, sweep, quantities, order
        As for :func:`~mechcli.core.linkage.kinematics.analyse_sweep`.
    start, stop, count
        The sweep's rows: ``np.linspace(start, stop, count)`` [rad or m].
    result : SweepResult
        ``analyse_sweep`` over the analysed rows (:func:`stream_grid`): its
        excluded intervals are left out of the rows, and its values place each
        run of unwrapped angles on the same turn.
    chunk : int
        Rows solved at a time (the memory bound).
    progress : callable or None
        Called as ``progress(done, count, kept=rows)`` after each chunk: the rows
        solved so far of *count*, and those handed out (the caller shows it; the
        core never prints).

    Iterating gives ``(q, values)`` per chunk: the kept rows' inputs and
    ``{symbol: array}``.  Afterwards ``rows`` is the number of rows handed
    out, ``peaks[symbol] = (max, at, min, at)`` over them, and ``irregular``
    the first and last input of rows that are neither regular nor excluded
    (None if there are none: the analysis saw every gap).
    """

    def __init__(self, linkage, sweep, quantities, order,
                 start, stop, count, result,
                 chunk=CHUNK, progress=None):
        self.linkage, self.sweep, self.quantities, self.order = linkage, sweep, quantities, order
        self.start, self.stop, self.count = start, stop, count
        self.result, self.chunk = result, chunk
        self.progress = progress
        self.rows = 0
        self.peaks = {}
        self.irregular = None

    def __iter__(self):
        from mechcli.core.linkage.sweep import _wrap

        res = self.result
        unwraps = {qt.symbol: _Unwrap() for qt in self.quantities if qt.is_angle}
        multi = bool(res.excluded)
        prev = -2   # the row index of the last kept row
        for a in range(0, self.count, self.chunk):
            b = min(a + self.chunk, self.count)
            idx = np.arange(a, b)
            q = rows_at(self.start, self.stop, self.count, idx)
            m = solve(self.linkage, self.sweep.inputs(q), order=self.order)
            keep = m.regular.copy()
            outside = np.ones(q.shape, dtype=bool)
            for lo, hi, _why in res.excluded:
                outside &= ~((q > lo) & (q < hi))
            bad = ~keep & outside
            if bad.any():
                first = float(q[np.argmax(bad)])
                last = float(q[len(q) - 1 - np.argmax(bad[::-1])])
                self.irregular = (first if self.irregular is None else self.irregular[0], last)
            keep &= outside
            if not keep.all():
                sel = np.flatnonzero(keep)
            else:
                sel = None
            kept = idx if sel is None else idx[sel]
            if kept.size == 0:
                if self.progress is not None:
                    self.progress(b, self.count, kept=self.rows)
                continue
            # runs inside this chunk: a new one where the rows are not consecutive
            breaks = np.flatnonzero(np.diff(kept) > 1) + 1
            if kept[0] != prev + 1:
                breaks = np.concatenate(([0], breaks))
            values = {}
            for qt in self.quantities:
                v = np.asarray(qt.get(m), dtype=float)
                v = np.broadcast_to(v, q.shape) if v.shape != q.shape else v
                v = v if sel is None else v[sel]
                if qt.is_angle:
                    v = self._unwrap(unwraps[qt.symbol], v, q if sel is None else q[sel],
                                     breaks, res, qt.symbol, multi, _wrap)
                values[qt.symbol] = v
                self._peak(qt.symbol, v, q if sel is None else q[sel])
            prev = int(kept[-1])
            self.rows += kept.size
            if self.progress is not None:
                self.progress(b, self.count, kept=self.rows)
            yield (q if sel is None else q[sel]), values

    @staticmethod
    def _unwrap(state, v, q, breaks, res, sym,
                multi, wrap):
        """Unwrapped angles of one chunk: run by run (a run starts at each break)."""
        cuts = list(breaks) + [v.size]
        pieces = []
        if not cuts or cuts[0] != 0:
            pieces.append(state(v[:cuts[0]]))   # the run of the previous chunk goes on
        for i0, i1 in zip(cuts[:-1], cuts[1:]):
            p0 = v[i0]
            shift = p0 - wrap(p0)   # first value in (-pi, pi], as analyse_sweep does
            if multi:
                # several runs: on the turn the analysis put the nearest analysed row on
                j = min(int(np.searchsorted(res.q, q[i0])), res.q.size - 1)
                near = res.values[sym][j]
                shift -= 2 * np.pi * np.round((near - (p0 - shift)) / (2 * np.pi))
            state.start(shift)
            pieces.append(state(v[i0:i1]))
        return pieces[0] if len(pieces) == 1 else np.concatenate(pieces)

    def _peak(self, sym: str, v: Any, q: Any) -> None:
        if v.size == 0:
            return
        i, j = int(np.argmax(v)), int(np.argmin(v))
        hi, at_hi, lo, at_lo = self.peaks.get(sym, (-np.inf, None, np.inf, None))
        if v[i] > hi:
            hi, at_hi = float(v[i]), float(q[i])
        if v[j] < lo:
            lo, at_lo = float(v[j]), float(q[j])
        self.peaks[sym] = (hi, at_hi, lo, at_lo)
