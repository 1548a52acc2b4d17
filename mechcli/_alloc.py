"""Keep freed numpy buffers in the process heap (glibc only).

glibc may serve a large allocation (above its mmap threshold: 128 KiB by
default, about 16,000 float64, adjusted dynamically) with a fresh ``mmap``
and give freed memory back to the system (trim), so a vectorized temporary of
that size can pay one page fault per 4 KiB page before any arithmetic, again
on every solve.  Raising the mmap and trim thresholds lets repeated solves
(extreme refinement, optimizers, benchmarks) reuse warm memory instead.

The effect depends on the machine and the allocation pattern: where page
faults are dear (about 1.5 µs each, as in some virtual machines and
sandboxes) a fresh temporary was measured 6-7x slower than a warm one; where
glibc's dynamic threshold already keeps the buffers, the gain is nil.  The
price is memory the process keeps after its largest solve.  Measure with
``benchmarks/`` on the target machine.
Called once by the command line (for every command but ``grashof``, ``new``
and ``schema``, which repeat no large temporaries: ``mechcli.cli``) and by the
benchmarks, never by ``mechcli.core`` itself.  A no-op where ``mallopt`` is not available
(non-glibc platforms).
"""

import ctypes
import sys

_M_TRIM_THRESHOLD = -1
_M_TOP_PAD = -2
_M_MMAP_THRESHOLD = -3
_done = False


def keep_heap_warm(mmap_threshold=1 << 30, trim_threshold=1 << 31, top_pad=64 << 20):
    global _done
    if _done:
        return True
    if not sys.platform.startswith("linux"):   # mallopt and these options are glibc's
        return False
    try:
        # the running interpreter's own symbols include libc's: no ``ctypes.util``
        # (it imports subprocess and runs ``ldconfig``, ~5 ms of a start-up)
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError, TypeError):   # TypeError: CDLL(None) on Windows
        try:
            from ctypes.util import find_library
            mallopt = ctypes.CDLL(find_library("c") or "libc.so.6").mallopt
        except (OSError, AttributeError, TypeError):
            return False
    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    ok = all(mallopt(opt, val) == 1 for opt, val in (
        (_M_MMAP_THRESHOLD, min(mmap_threshold, 2**31 - 1)),
        (_M_TRIM_THRESHOLD, min(trim_threshold, 2**31 - 1)),
        (_M_TOP_PAD, top_pad)))
    _done = ok
    return ok
