"""Memory of the linkage engine (issue 17): no temporaries kept across elements,
long sweeps solved in chunks into preallocated outputs.  Bounds are generous
(tracemalloc peak, never a timing)."""

import tracemalloc

import numpy as np

from mechcli.core.linkage import (RRR, Crank, DriverMotion, Ground, Linkage, PointOnLink,
                                  engine, solve)


def _fourbar(*extra):
    return Linkage(4, (Ground("A", 0, 0), Ground("D", 0.3048, 0), Crank(1, "A", "B", 0.1016),
                       RRR("C", "B", 2, 0.254, "D", 3, 0.1778, 1)) + extra)


def test_peak_memory_of_a_long_sweep_is_bounded():
    n = 100_001
    th = np.linspace(0, 2 * np.pi, n)
    lk = _fourbar()
    solve(lk, {1: DriverMotion(th[:10], 250.0)}, order=2)  # warm the scratch pool
    tracemalloc.start()
    try:
        m = solve(lk, {1: DriverMotion(th, 250.0)}, order=2)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert m.regular.all()
    # the outputs alone are ~162 B/position; the old engine peaked at ~380
    assert peak / n < 260, peak / n


def test_chunked_sweep_equals_one_pass(monkeypatch):
    lk = _fourbar(PointOnLink("E", 2, "B", 0.1, 0.05))
    th = np.linspace(0, 2 * np.pi, 5001)
    monkeypatch.setattr(engine, "CHUNK", 1000)
    chunked = solve(lk, {1: DriverMotion(th, 250.0, 3.0)}, order=2)
    monkeypatch.setattr(engine, "CHUNK", 10**9)
    whole = solve(lk, {1: DriverMotion(th, 250.0, 3.0)}, order=2)
    for name, p in whole.points.items():
        for f in ("x", "y", "vx", "vy", "ax", "ay"):
            np.testing.assert_array_equal(np.broadcast_to(getattr(chunked.points[name], f), th.shape),
                                          np.broadcast_to(getattr(p, f), th.shape))
    for ln, k in whole.links.items():
        for f in ("theta", "omega", "alpha"):
            np.testing.assert_array_equal(np.broadcast_to(getattr(chunked.links[ln], f), th.shape),
                                          np.broadcast_to(getattr(k, f), th.shape))
    for a, b in zip(chunked.conditions, whole.conditions):
        np.testing.assert_array_equal(a.sin_gamma, b.sin_gamma)
        np.testing.assert_array_equal(a.cos_joint, b.cos_joint)
    np.testing.assert_array_equal(chunked.regular, whole.regular)
    np.testing.assert_array_equal(chunked.feasible, whole.feasible)


def test_results_of_two_solves_do_not_share_memory():
    lk = _fourbar()
    th = np.linspace(0, 2 * np.pi, 361)
    a = solve(lk, {1: DriverMotion(th, 250.0)}, order=2)
    keep = a.points["C"].ax.copy()
    solve(lk, {1: DriverMotion(th + 0.1, 100.0)}, order=2)
    np.testing.assert_array_equal(a.points["C"].ax, keep)
