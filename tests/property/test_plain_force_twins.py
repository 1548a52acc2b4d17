"""The force blocks equal their readable twins in mechcli.core.linkage.plain (issue 32 §2)
on random batched inputs: a dyad block and a driver block solved in closed form
(dyad_statics.solve) and any block by the batched elimination (elimination.gauss) against
numpy.linalg.solve one position at a time (plain.block_solve); and the reactions and
balancing torque of a four-bar from solve_forces against the equilibrium equations of
its RRR dyad and its crank written out (plain.rrr_dyad_reactions, plain.crank_reactions).
"""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechcli.core.linkage import RRR, Crank, DriverMotion, Ground, Linkage, plain, solve
from mechcli.core.linkage.dyad_statics import DriverLayout, DyadLayout, OuterPair
from mechcli.core.linkage.dyad_statics import solve as closed_form
from mechcli.core.linkage.elimination import gauss
from mechcli.core.linkage.kinetostatics import Body, Load, solve_forces, topology

SET = settings(max_examples=30, deadline=None)
N = 40
seeds = st.integers(0, 2 ** 32 - 1)


def _close(fast, twin, scale):
    fast, twin = np.asarray(fast), np.asarray(twin)
    assert np.max(np.abs(fast - twin)) <= 1e-9 * scale, np.max(np.abs(fast - twin))


def _dyad_block(rng):
    """A dyad's 6 x 6 block as kinetostatics assembles it: two revolute outer pairs
    (columns 0, 1 on link a; 4, 5 on link b), the inner pair (2, 3) on both; the force
    rows hold +-1 (floats), the moment rows the lever arms (arrays)."""
    arm = lambda: rng.uniform(-0.5, 0.5, N)  # noqa: E731
    A = [[1.0, 0.0, -1.0, 0.0, 0.0, 0.0],
         [0.0, 1.0, 0.0, -1.0, 0.0, 0.0],
         [arm(), arm(), arm(), arm(), 0.0, 0.0],
         [0.0, 0.0, 1.0, 0.0, 1.0, 0.0],
         [0.0, 0.0, 0.0, 1.0, 0.0, 1.0],
         [0.0, 0.0, arm(), arm(), arm(), arm()]]
    return A, [rng.uniform(-100, 100, N) for _ in range(6)]


@SET
@given(seeds)
def test_dyad_block_closed_form_and_elimination_equal_linalg_solve(seed):
    rng = np.random.default_rng(seed)
    A, b = _dyad_block(rng)
    twin = plain.block_solve(A, b)
    assume(np.all(np.abs([np.linalg.cond(np.array(
        [[np.broadcast_to(v, (N,))[j] for v in row] for row in A])) for j in range(N)]) < 1e6))
    scale = float(np.max(np.abs(twin)))
    lay = DyadLayout(OuterPair("R", (0, 1), 0), (2, 3), OuterPair("R", (4, 5), 3))
    X, singular = closed_form(lay, A, b, (N,))
    assert singular is None
    _close(np.array(X), twin, scale)
    Xg, _sing = gauss(A, b)
    _close(np.array(Xg), twin, scale)


@SET
@given(seeds)
def test_driver_block_closed_form_and_elimination_equal_linalg_solve(seed):
    rng = np.random.default_rng(seed)
    # a crank's block: its pin's two force components and the balancing torque
    A = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0],
         [rng.uniform(-0.2, 0.2, N), rng.uniform(-0.2, 0.2, N), 1.0]]
    b = [rng.uniform(-100, 100, N) for _ in range(3)]
    twin = plain.block_solve(A, b)
    scale = float(np.max(np.abs(twin)))
    X, singular = closed_form(DriverLayout((0, 1), 2), A, b, (N,))
    _close(np.array(X), twin, scale)
    _close(np.array(gauss(A, b)[0]), twin, scale)


@SET
@given(seeds)
def test_dense_block_elimination_equals_linalg_solve(seed):
    """A block no layout describes: dense, arrays and floats mixed (pivoting per position)."""
    rng = np.random.default_rng(seed)
    k = int(rng.integers(3, 7))
    A = [[float(rng.uniform(-1, 1)) if rng.random() < 0.3 else rng.uniform(-1, 1, N)
          for _ in range(k)] for _ in range(k)]
    b = [rng.uniform(-1, 1, N) for _ in range(k)]
    twin = plain.block_solve(A, b)
    conds = [np.linalg.cond([[np.broadcast_to(v, (N,))[j] for v in row] for row in A])
             for j in range(N)]
    assume(max(conds) < 1e6)
    _close(np.array(gauss(A, b)[0]), twin, float(np.max(np.abs(twin))) * max(conds) / 1e3)


def _cpx(m, name):
    p = m.points[name]
    return plain.Pt(p.x + 1j * p.y, p.vx + 1j * p.vy, p.ax + 1j * p.ay)


def _link(m, n):
    ln = m.links[n]
    return plain.Ln(ln.theta, np.broadcast_to(ln.omega, ln.theta.shape),
                    np.broadcast_to(ln.alpha, ln.theta.shape))


@SET
@given(seeds, st.sampled_from([1, -1]), st.floats(1.0, 20.0), st.floats(-5.0, 5.0))
def test_four_bar_reactions_equal_the_equilibrium_equations(seed, branch, w, al):
    rng = np.random.default_rng(seed)
    u = rng.uniform
    r, a, b, d = u(0.05, 0.12), u(0.35, 0.5), u(0.3, 0.45), u(0.4, 0.5)
    lk = Linkage(4, (Ground("A", 0.0, 0.0), Ground("D", d, 0.0), Crank(1, "A", "B", r),
                     RRR("C", "B", 2, a, "D", 3, b, branch)))
    q = np.linspace(0.0, 2 * math.pi, N)
    m = solve(lk, {1: DriverMotion(q, w, al)}, order=2)
    ok = m.regular & (np.abs(np.broadcast_to(m.conditions[0].sin_gamma, q.shape)) > 0.1)
    assume(ok.sum() > 5)
    topo = topology(lk)
    bodies = {ln: Body(ln, u(0.5, 5.0), u(0.0, 0.05), topo.frames[ln][0], u(-0.1, 0.1),
                       u(-0.05, 0.05)) for ln in topo.links}
    F, T = complex(u(-500, 500), u(-500, 500)), u(-20, 20)
    loads = [Load("F", 3, F.real, F.imag, 0.0, "D", 0.7 * b, 0.0), Load("T", 2, torque=T)]
    g = -9.81j
    fr = solve_forces(topo, m, bodies, loads, (0.0, -9.81))
    # every link's loads at its centre of mass S: gravity, d'Alembert, the external ones
    force, at, couple = {}, {}, {}
    for ln, bd in bodies.items():
        link = _link(m, ln)
        S = plain.point_on_link(_cpx(m, bd.origin), link, bd.along, bd.normal)
        force[ln] = bd.mass * (g - S.a)
        at[ln], couple[ln] = S.p, -bd.inertia * link.alpha
    couple[2] = couple[2] + T
    P = plain.point_on_link(_cpx(m, "D"), _link(m, 3), 0.7 * b, 0.0).p
    force[3] = force[3] + F
    couple[3] = couple[3] + ((P - at[3]) * np.conj(F)).imag * -1.0
    B, C, D = (_cpx(m, n).p for n in "BCD")
    R_B, R_C, R_D = plain.rrr_dyad_reactions(B, C, D, force[2], at[2], couple[2],
                                             force[3], at[3], couple[3])
    R_A, Mb = plain.crank_reactions(_cpx(m, "A").p + 0 * q, B, R_B, force[1], at[1],
                                    couple[1])
    pair = {(pf.pair.i, pf.pair.j): pf.fx + 1j * pf.fy for pf in fr.pairs}
    scale = float(np.max(np.abs(np.concatenate([R_A, R_B, R_C, R_D])[np.tile(ok, 4)])))
    _close(pair[1, 2][ok], R_B[ok], scale)       # of 1 on 2
    _close(pair[2, 3][ok], R_C[ok], scale)       # of 2 on 3
    _close(pair[3, 4][ok], -R_D[ok], scale)      # of 3 on the frame 4
    _close(pair[1, 4][ok], -R_A[ok], scale)      # of 1 on the frame 4
    _close(fr.balancing[1][ok], Mb[ok], scale * max(r, 0.1))
