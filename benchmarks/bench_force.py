"""Speed and accuracy-vs-cost of the kinetostatics (`mechcli force`).

Prints `name: value unit` lines.  Compare ratios within one run: machines are
shared and noisy.  Target (issue #6): 36,001 positions of 例 2-4 (the shaper
six-bar, 15 unknowns) solved in <= 50 ms of compute.  Issue 17: the forces given
the motion <= 2x hand-written numpy for the same model (:func:`hand_written_shaper`,
timed in the same run: Mb and the reactions on the way to it; with ``every_output``,
everything the engine call returns: every reaction, the frame's force and moment, the
power, the balance check); also against the general elimination of every block (the
closed-form dyad statics switched off); the fixed cost of one kinetostatics call (one
position, given its motion) <= 0.5 ms, against one position solve.  The peak RSS of
whole runs and its growth per position (``force_peak_rss_per_position``), the figure
behind ``mechcli.spec.force.MAX_POSITIONS`` (the 1 GiB budget).

Usage: python benchmarks/bench_force.py [--quick] [--json]
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

from benchmarks.bench_kin import best_of  # noqa: E402
from mechcli._alloc import keep_heap_warm  # noqa: E402
from mechcli.core.linkage.force_analysis import ForceEvaluator, analyse_forces  # noqa: E402
from mechcli.core.linkage.kinematics import Sweep  # noqa: E402
from mechcli.core.linkage import kinetostatics  # noqa: E402
from mechcli.core.linkage.kinetostatics import solve_forces  # noqa: E402
from mechcli.core.linkage import solve  # noqa: E402
from mechcli.spec.force import load_force_spec  # noqa: E402


def hand_written_shaper(motion, cutting_fx, m3=20.0, j3=0.12, m4=3.0, j4=0.00025, m5=62.0,
                        x_s5=-0.15, g=9.8, every_output=False, omega1=1.0):
    """Kinetostatics of 例 2-4's shaper given its motion, written by hand in numpy
    (the baseline of issue 17): the book's order, dyad by dyad, in closed form.

    d'Alembert: Q_i = m_i (g - a_Si) at the centre of mass S_i, M_i = -J_i alpha_i.
    Dyad 4-5 (rod DE, ram on y = l6'): ΣFx of the ram gives F45x, Σ moments of
    the rod about D give F45y, ΣF of the rod gives F34.  Dyad 2-3: the massless
    block 2 passes a force normal to the guide, N23 n; Σ moments of link 3 about C
    give N23 (its arm is the slide CB).  Crank: F12 = N23 n, Mb = (B - A) x F12.
    S3, S4 are the midpoints of CD, DE and S5 = E + (x_s5, 0) (the spec's bodies).
    Returns Mb, F34 (x, y), F45 (x, y), N23 [N m, N].

    With *every_output*, also what ``solve_forces`` returns: every pair reaction (force
    of link i on link j, as the engine's ``PairForce``), the couple of the ram's guide,
    the force and moment on the frame, the input power and the global balance
    |Σ known forces − force on the frame| (the condition numbers and the virtual power
    left out, as in the timed engine call); then returns ``{pair label: (fx, fy,
    couple)}``, Mb, frame (fx, fy, moment), power, residual.
    """
    P, L = motion.points, motion.links
    bx, by, ax_, ay_ = P["B"].x, P["B"].y, P["A"].x, P["A"].y
    dx, dy, ex, ey = P["D"].x, P["D"].y, P["E"].x, P["E"].y
    # inertia and gravity (C is fixed: a_S3 = a_D / 2)
    q3x, q3y = -m3 * 0.5 * P["D"].ax, -m3 * (g + 0.5 * P["D"].ay)
    q4x = -m4 * 0.5 * (P["D"].ax + P["E"].ax)
    q4y = -m4 * (g + 0.5 * (P["D"].ay + P["E"].ay))
    q5x = cutting_fx - m5 * P["E"].ax   # (the ram's weight only loads its guide)
    m3i, m4i = -j3 * L[3].alpha, -j4 * L[4].alpha
    # dyad 4-5
    f45x = -q5x
    rex, rey = ex - dx, ey - dy
    k4 = 0.5 * (rex * q4y - rey * q4x) + m4i  # S4 - D = (E - D) / 2
    f45y = (rey * f45x + k4) / rex
    f34x, f34y = f45x - q4x, f45y - q4y
    # dyad 2-3 about C = (0, 0): guide direction u = D / |D|, normal n = i u
    l3 = np.hypot(dx, dy)
    ux, uy = dx / l3, dy / l3
    s23 = bx * ux + by * uy
    k3 = -(dx * f34y - dy * f34x) + 0.5 * (dx * q3y - dy * q3x) + m3i
    n23 = -k3 / s23
    f12x, f12y = -n23 * uy, n23 * ux
    mb = (bx - ax_) * f12y - (by - ay_) * f12x
    if not every_output:
        return mb, (f34x, f34y), (f45x, f45y), n23
    # the rest of the engine's outputs: the frame's reactions from each link's ΣF = 0
    q5y = -m5 * (g + P["E"].ay)
    f36x, f36y = f12x - f34x + q3x, f12y - f34y + q3y      # F23 + F43 + Q3 on the frame
    f56y = f45y + q5y                                       # F45 + Q5 (F45x + Q5x = 0)
    c56 = x_s5 * q5y                                        # Q5's moment about E
    zero = np.zeros_like(mb)
    pairs = {"16": (-f12x, -f12y, zero), "12": (f12x, f12y, zero), "23": (f12x, f12y, zero),
             "36": (f36x, f36y, zero), "34": (f34x, f34y, zero), "45": (f45x, f45y, zero),
             "56": (zero, f56y, c56)}
    ffx = f36x - f12x
    ffy = f36y - f12y + f56y
    fm = (ax_ * -f12y - ay_ * -f12x) + (ex * f56y) + c56 - mb   # C = (0, 0); 56 at E
    power = mb * omega1
    rx = q3x + q4x + q5x - ffx
    ry = q3y + q4y + q5y - ffy
    residual = np.sqrt(rx * rx + ry * ry)
    return pairs, mb, (ffx, ffy, fm), power, residual


def main(quick=False):
    keep_heap_warm()
    spec = load_force_spec(ROOT / "configs" / "ch2" / "ex2-4.toml")
    inp = spec.input
    rep = 3 if quick else 7
    n = 36001
    q = np.linspace(0, 2 * np.pi, n)
    sweep = Sweep(inp.driver, q, inp.omega, inp.alpha, inp.followers, True)
    unit = Sweep(inp.driver, q, 1.0, 0.0, inp.followers, True)
    motion = solve(spec.linkage, sweep.inputs(q), 2)
    umotion = solve(spec.linkage, unit.inputs(q), 1)
    progs = [p.with_band_limits(-0.417137832736, 0.128316712718) for p in spec.loads]
    loads = [p.evaluate(q, motion)[0] for p in progs]
    nunk = sum(2 for _ in spec.topology.pairs) + len(spec.linkage.drivers)
    print(f"ex2-4 unknowns: {nunk}")

    def force_only():
        solve_forces(spec.topology, motion, spec.bodies, loads, spec.gravity, umotion,
                     condition=False)

    def force_cond():
        solve_forces(spec.topology, motion, spec.bodies, loads, spec.gravity, umotion,
                     condition=True)

    pipe = ForceEvaluator(spec.linkage, spec.topology, sweep, spec.bodies, spec.gravity, progs)
    # issue 17: the forces given the motion against hand-written numpy for the same model
    cut = loads[0].fx

    def engine_given_motion():
        return solve_forces(spec.topology, motion, spec.bodies, loads, spec.gravity,
                            condition=False)

    # interleaved, best of many: both take a few ms and the machine is shared
    t_engine = t_hand = float("inf")
    for _ in range(8 * rep):
        t_engine = min(t_engine, best_of(engine_given_motion, 1))
        t_hand = min(t_hand, best_of(lambda: hand_written_shaper(motion, cut), 1))
    fr = engine_given_motion()
    mb, f34, f45, _n23 = hand_written_shaper(motion, cut)
    pf = {pf_.pair.label: pf_ for pf_ in fr.pairs}
    diff = max(np.max(np.abs(fr.balancing[1] - mb)) / np.max(np.abs(mb)),
               np.max(np.hypot(pf["34"].fx - f34[0], pf["34"].fy - f34[1]))
               / np.max(np.hypot(*f34)),
               np.max(np.hypot(pf["45"].fx - f45[0], pf["45"].fy - f45[1]))
               / np.max(np.hypot(*f45)))
    print(f"ex2-4_forces_36001_engine_given_motion: {t_engine * 1e3:.2f} ms")
    print(f"ex2-4_forces_36001_hand_written_numpy: {t_hand * 1e3:.2f} ms")
    print(f"ex2-4_forces_36001_engine_over_hand_written: {t_engine / t_hand:.2f} x (goal <= 2)")
    print(f"ex2-4_forces_36001_max_rel_difference_to_hand_written: {diff:.1e} 1")
    # the same against a hand-written version that returns what the engine returns (every
    # reaction, the frame's force and moment, the power, the balance check)
    t_full = float("inf")
    for _ in range(8 * rep):
        t_full = min(t_full, best_of(lambda: hand_written_shaper(motion, cut, every_output=True), 1))
    hp, hmb, hframe, hpower, hres = hand_written_shaper(motion, cut, every_output=True,
                                                           omega1=inp.omega)
    big = max(np.max(np.hypot(pf_.fx, pf_.fy)) for pf_ in fr.pairs)
    diff_full = max([np.max(np.abs(fr.balancing[1] - hmb)) / np.max(np.abs(hmb))]
                    + [max(np.max(np.abs(pf[lb].fx - hp[lb][0])), np.max(np.abs(pf[lb].fy - hp[lb][1])),
                           np.max(np.abs(pf[lb].couple - hp[lb][2]))) / big for lb in hp]
                    + [np.max(np.abs(fr.frame_force[0] - hframe[0])) / big,
                       np.max(np.abs(fr.frame_force[1] - hframe[1])) / big,
                       np.max(np.abs(fr.frame_moment - hframe[2])) / np.max(np.abs(hmb)),
                       np.max(np.abs(fr.input_power - hpower)) / np.max(np.abs(hpower)),
                       np.max(np.abs(fr.force_residual - hres)) / big])
    print(f"ex2-4_forces_36001_hand_written_every_output_numpy: {t_full * 1e3:.2f} ms")
    print(f"ex2-4_forces_36001_engine_over_hand_written_every_output: {t_engine / t_full:.2f} x")
    print(f"ex2-4_forces_36001_max_rel_difference_to_hand_written_every_output: "
          f"{diff_full:.1e} 1")
    # the same call with every block through the general elimination (the closed-form
    # dyad statics off): what the closed form gains
    kinetostatics.CLOSED_FORM = False
    try:
        t_general = best_of(engine_given_motion, 4 * rep)
    finally:
        kinetostatics.CLOSED_FORM = True
    print(f"ex2-4_forces_36001_general_elimination: {t_general * 1e3:.2f} ms")
    print(f"ex2-4_forces_36001_general_elimination_over_closed_form: "
          f"{t_general / t_engine:.2f} x")
    t = best_of(force_only, rep)
    print(f"ex2-4_forces_36001_given_motion: {t * 1e3:.1f} ms (target <= 50)")
    print(f"ex2-4_forces_36001_given_motion_with_condition: "
          f"{best_of(force_cond, rep) * 1e3:.1f} ms")
    print(f"ex2-4_pipeline_36001: {best_of(lambda: pipe(q), rep) * 1e3:.1f} ms "
          "(kinematics + loads + kinetostatics)")
    # the fixed cost of one call (issue 17: <= 0.5 ms), against one position solve
    q1 = q[:1]
    m1 = solve(spec.linkage, sweep.inputs(q1), 2)
    u1 = solve(spec.linkage, unit.inputs(q1), 1)
    l1 = [p.evaluate(q1, m1)[0] for p in progs]
    t_pos = best_of(lambda: solve(spec.linkage, sweep.inputs(q1), 2), 50)
    t_one = best_of(lambda: solve_forces(spec.topology, m1, spec.bodies, l1, spec.gravity, u1,
                                         condition=False), 50)
    t_one_c = best_of(lambda: solve_forces(spec.topology, m1, spec.bodies, l1, spec.gravity,
                                           u1, condition=True), 50)
    t_pipe1 = best_of(lambda: pipe(q1, condition=True), 50)
    print(f"position_solve_1_position: {t_pos * 1e3:.3f} ms")
    print(f"ex2-4_forces_1_position: {t_one * 1e3:.3f} ms")
    print(f"ex2-4_forces_1_position_over_position_solve: {t_one / t_pos:.2f} x")
    print(f"ex2-4_forces_1_position_with_condition: {t_one_c * 1e3:.3f} ms")
    print(f"ex2-4_pipeline_1_position: {t_pipe1 * 1e3:.3f} ms")
    print(f"ex2-4_pipeline_1_position_over_position_solve: {t_pipe1 / t_pos:.2f} x")
    # the fixed cost of the kinetostatics alone (issue 17: <= 0.5 ms), given the motion
    t_fix = best_of(lambda: solve_forces(spec.topology, m1, spec.bodies, l1, spec.gravity, u1,
                                         condition=True), 200)
    print(f"ex2-4_forces_fixed_cost: {t_fix * 1e3:.3f} ms (goal <= 0.5)")
    print(f"ex2-4_forces_fixed_cost_over_position_solve: {t_fix / t_pos:.2f} x")
    # accuracy vs cost: the mean and the extremes against the step of the sweep
    ref = None
    for step in (0.01, 0.1, 0.5, 1.0, 5.0, 10.0):
        qq = np.radians(np.arange(0.0, 360.0 + step / 2, step))
        sw = Sweep(inp.driver, qq, inp.omega, inp.alpha, inp.followers, True)
        t0 = time.perf_counter()
        res = analyse_forces(spec.linkage, spec.topology, sw, spec.bodies, spec.gravity,
                             spec.loads)
        dt = time.perf_counter() - t0
        mean, mx = res.mean["Mb"], res.extremes["Mb"][0].value
        if ref is None:
            ref = (mean, mx)
        tag = f"ex2-4_step_{step:g}deg"
        print(f"{tag}_analyse: {dt * 1e3:.1f} ms")
        print(f"{tag}_mean_Mb: {mean:.9f} N_m")
        print(f"{tag}_mean_Mb_diff: {abs(mean - ref[0]):.1e} N_m (to the 0.01 deg step)")
        print(f"{tag}_max_Mb: {mx:.9f} N_m")
        print(f"{tag}_max_Mb_diff: {abs(mx - ref[1]):.1e} N_m (to the 0.01 deg step)")
    with tempfile.TemporaryDirectory() as tmp:
        base = best_of(lambda: subprocess.run([sys.executable, "-c", "import numpy"],
                                              check=True), 1 if quick else 3)
        print(f"process_import_numpy: {base:.3f} s")
        for args, label in (([], "png"), (["--no-plot"], "no_plot"),
                            (["--animate"], "png_gif72")):
            cmd = [sys.executable, "-m", "mechcli", "force",
                   str(ROOT / "configs" / "ch2" / "ex2-4.toml"), "--out", tmp, "-q", *args]
            t = best_of(lambda: subprocess.run(cmd, check=True), 1 if quick else 3)
            print(f"process_force_ex2-4_{label}: {t:.2f} s")
            print(f"process_force_ex2-4_{label}_over_import_numpy: {t / base:.1f} x")
    crossovers(spec, sweep, unit, progs, rep)
    peak_rss(quick)


def crossovers(spec, sweep, unit, progs, rep):
    """The lengths at which ``kinetostatics`` changes method (例 2-4, given the motion):
    ``DENSE_MAX`` (LAPACK's batched solve up to it, the structured elimination or the
    closed form beyond) and ``DIRECTION_MIN`` (a link's cosine and sine from its
    element's points beyond it, from its angle up to it), each side forced in turn."""
    for n in sorted({1, 64, 128, 256, 36001, kinetostatics.DENSE_MAX}):
        q = np.linspace(0, 2 * np.pi, n)
        m = solve(spec.linkage, sweep.inputs(q), 2)
        u = solve(spec.linkage, unit.inputs(q), 1)
        loads = [p.evaluate(q, m)[0] for p in progs]
        for cond in (False, True):
            times = {}
            for label, attr, forced in (("dense", "DENSE_MAX", 10**9),
                                        ("structured", "DENSE_MAX", 0),
                                        ("from_points", "DIRECTION_MIN", 0),
                                        ("from_angle", "DIRECTION_MIN", 10**9)):
                kept = getattr(kinetostatics, attr)
                setattr(kinetostatics, attr, forced)
                try:
                    times[label] = best_of(
                        lambda: solve_forces(spec.topology, m, spec.bodies, loads, spec.gravity,
                                             u, condition=cond), 20 * rep if n < 1000 else rep)
                finally:
                    setattr(kinetostatics, attr, kept)
            tag = f"ex2-4_forces_{n}{'_with_condition' if cond else ''}"
            print(f"{tag}_dense_over_structured: {times['dense'] / times['structured']:.2f} x "
                  f"(DENSE_MAX = {kinetostatics.DENSE_MAX})")
            print(f"{tag}_directions_from_points_over_from_angle: "
                  f"{times['from_points'] / times['from_angle']:.2f} x "
                  f"(DIRECTION_MIN = {kinetostatics.DIRECTION_MIN})")


def peak_rss(quick):
    """Peak RSS of ``mechcli force`` (例 2-4, no plots) at two sweep lengths and its growth
    per position: ``mechcli.spec.force.MAX_POSITIONS`` is the 1 GiB budget over this
    growth, rounded down for deeper linkages and more loads."""
    from benchmarks.bench_kin import _peak_rss_run

    lo, hi = (10_001, 40_001) if quick else (10_001, 100_001)
    rss = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in (lo, hi):
            rss[n] = _peak_rss_run(["force", str(ROOT / "configs" / "ch2" / "ex2-4.toml"),
                                    "--set", f"input.count={n}", "--out", tmp, "--no-plot",
                                    "--quiet"])[1]
            print(f"ex2-4_force_{n}_positions_peak_rss: {rss[n] / 2**20:.0f} MB")
    print(f"force_peak_rss_per_position: {(rss[hi] - rss[lo]) / (hi - lo):.0f} B")


if __name__ == "__main__":
    def _all():
        main("--quick" in sys.argv)

    run(_all)
