"""SIGTERM (``kill``, a CI timeout) as an exit through Python's unwinding, so that the
``finally`` blocks run: temporary and staged output files are removed as on Ctrl-C.
Standard library only (the command line's start-up imports it)."""

from __future__ import annotations


def sigterm_as_exit():
    """Make SIGTERM raise ``SystemExit(143)``; returns the function that puts the previous
    handler back (a no-op off the main thread or where the handler cannot be set).
    SIGKILL cannot be caught."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return lambda: None

    def _exit(signum, frame):
        raise SystemExit(128 + signum)

    try:
        previous = signal.signal(signal.SIGTERM, _exit)
    except (ValueError, OSError):      # not settable here
        return lambda: None
    return lambda: signal.signal(signal.SIGTERM, previous)
