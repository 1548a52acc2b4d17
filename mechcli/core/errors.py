"""Errors raised by the numerical core.

Every error the core raises for a *problem without solution* derives from
:class:`UnsolvableError`; the command line maps it to exit code 3.
"""


class UnsolvableError(ValueError):
    """The problem, although well-formed, has no solution (exit code 3)."""


class AssemblyError(UnsolvableError):
    """A linkage cannot be assembled at some input positions.

    Attributes
    ----------
    intervals : list of (float, float)
        Input-angle intervals (degrees for rotary drivers, spec length unit
        for linear drivers, as given by the caller) where assembly fails.
    """

    def __init__(self, message, intervals=()):
        super().__init__(message)
        self.intervals = list(intervals)


class ConvergenceError(RuntimeError):
    """An iterative method did not converge (exit code 3)."""
