"""The engine reuses the block of a solve's outputs once nothing references it (issue 17:
no page faults in a loop of solves), and never one whose results are still held.

Reference: the values a result had when it was returned (a copy taken then); any later
solve that wrote into a held result's memory would change them.
"""

import gc

import numpy as np

from mechcli.core.linkage import DriverMotion, engine, four_bar, solve


def _solve(scale):
    th = np.linspace(0.0, 2 * np.pi, 5000)
    return solve(four_bar(0.1, 0.25, 0.2, 0.3), {1: DriverMotion(th * scale, 2.0, 0.5)})


def test_a_dropped_result_lends_its_block_to_the_next_solve():
    if engine._FREE_REFS is None:   # no reference counts: no reuse, nothing to check
        return
    gc.collect()
    bases = {id(_solve(1.0).links[3].theta.base) for _ in range(6)}
    assert len(bases) <= 2   # two blocks kept per thread, taken in turn


def test_held_results_are_never_overwritten():
    held = []
    for k in range(8):
        m = _solve(1.0 + 0.1 * k)
        if k % 2 == 0:   # keep every other result, or just one array of it
            held.append((m if k % 4 == 0 else m.points["C"].x,
                         m.points["C"].x.copy(), m.links[3].omega.copy()))
        del m
        gc.collect()
    for obj, x, w in held:
        m_x = obj.points["C"].x if hasattr(obj, "points") else obj
        assert np.array_equal(m_x, x)
        if hasattr(obj, "links"):
            assert np.array_equal(obj.links[3].omega, w)
