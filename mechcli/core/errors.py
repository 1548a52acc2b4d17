"""Errors raised by the numerical core.

Every error the core raises for a *problem without solution* derives from
:class:`UnsolvableError`; the command line maps it to exit code 3.
"""

from __future__ import annotations

from typing import Any, Iterable, Tuple


class UnsolvableError(ValueError):
    """The problem, although well-formed, has no solution (exit code 3)."""


class DescribedError(UnsolvableError):
    """A problem without solution described by numbers, for the caller to word.

    The message names the failure in words of the mechanism and names no unit
    or spec key; the command's report layer words it in the spec's units.

    Attributes
    ----------
    reason : str
        What failed, one word (e.g. ``"pitch_cusp"``, ``"tip_inside_base"``;
        see the raising function); empty when the message says it all.
    values : dict
        The numbers of the failure: lengths [m], angles [rad], counts.
    """

    def __init__(self, message: str, reason: str = "", **values: Any) -> None:
        super().__init__(message)
        self.reason, self.values = reason, values


class AssemblyError(UnsolvableError):
    """A linkage cannot be assembled at some input positions.

    Attributes
    ----------
    intervals : list of (float, float, str)
        ``(start, stop, reason)`` of every input interval where the linkage
        cannot be analysed: start and stop in core units (radians for a
        rotary driver, metres for a linear one), reason ``"cannot assemble"``
        or ``"dead point"``.  Empty when the caller gives no intervals.
    too_few : bool
        Fewer than two positions remain to analyse (even with the intervals
        left out).

    The core's message names no unit and no spec key; the report layer words
    the intervals for the user (``report.kin.assembly_message``).
    """

    def __init__(self, message: str, intervals: Iterable[Tuple[float, float, str]] = (),
                 too_few: bool = False) -> None:
        super().__init__(message)
        self.intervals = list(intervals)
        self.too_few = too_few


class ConvergenceError(RuntimeError):
    """An iterative method did not converge (exit code 3)."""

    #: what the method reached, where its raiser attaches it (an optimization's
    #: ``Result``); not set otherwise
    result: Any
