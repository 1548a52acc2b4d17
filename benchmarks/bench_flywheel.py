"""Accuracy against cost of the steady state and the flywheel (``mechcli flywheel``).

For 例 6-4 (the shaper of 表 6-2: Me = 5500 − 1000ω − Mer(φ), Je(φ)) and 例 6-5 (the same
with J_F = 587.92849 kg m² added), prints ``name: value unit`` lines per method:

* the book's explicit fixed-step scheme (eq 6-23) at 15° (the book's), 5°, 1°, 0.1°, 0.01°;
* scipy's RK45, DOP853 and Radau at rtol 1e-6, 1e-8, 1e-10 (the default: DOP853), 1e-12;

each with δ (eq 6-25 with the integral mean of eq 6-26), δ_avg (with eq 6-27's mean), ωm,
their errors against a reference (DOP853 at rtol 1e-13, atol 1e-15, checked against Radau
at rtol 1e-12), the right-hand-side evaluations and the time of one whole steady state
(shooting included), also as a ratio to a baseline measured in the same run: a plain
Python/numpy loop of the book's scheme over one period at 1° (360 steps, hand-written here,
nothing of mechcli).  The default setting must give δ within 1e-6 of the reference.

Then the flywheel for [δ] = 0.06 by eq 6-30 (ΔWmax at constant speed) and by
``flywheel_exact`` (the steady state with the variable Je), with its time.

Usage: python benchmarks/bench_flywheel.py [--quick] [--json]
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _figures import run  # noqa: E402  (prints the figures, or JSON with --json)

from mechcli.core.flywheel.equivalent import TableInertia  # noqa: E402
from mechcli.core.flywheel.motion import (MomentModel, flywheel_approx,  # noqa: E402
                                          flywheel_exact, steady_state)

PHI = np.radians(np.arange(0.0, 361.0, 15.0))
MER = np.array([789, 812, 825, 797, 727, 85, 105, 137, 181, 185, 179, 150, 141, 150, 157,
                152, 132, 132, 139, 145, 756, 803, 818, 802, 789], dtype=float)
JE = np.array([34.0, 33.9, 33.6, 33.1, 32.4, 31.8, 31.2, 31.1, 31.6, 33, 35, 37.2, 38.2,
               37.2, 35, 33, 31.5, 31.1, 31.2, 31.8, 32.4, 33.1, 33.6, 33.9, 34.0])
J_F = 587.92849
DEFAULT_TOL = 1e-6


def best_of(fn, repeat):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def baseline_loop(added=0.0, step_deg=1.0, omega0=5.0):
    """The book's explicit scheme over one period, plain Python floats and numpy.interp."""
    n = int(round(360 / step_deg))
    phi = np.linspace(0.0, 2 * np.pi, n + 1)
    mer = np.interp(phi, PHI, MER).tolist()
    J = (np.interp(phi, PHI, JE) + added).tolist()
    h = 2 * np.pi / n
    w = omega0
    out = [w]
    for i in range(n):
        me = 5500.0 - 1000.0 * w - mer[i]
        w = me * h / (J[i] * w) + (3.0 * J[i] - J[i + 1]) / (2.0 * J[i]) * w
        out.append(w)
    return out


def models(added):
    inertia = TableInertia(PHI, JE)
    if added:
        inertia = inertia.plus(added)
    return inertia, MomentModel(table=(PHI, -MER, "linear"), linear=(5500.0, 1000.0))


def settings(quick):
    rows = [(f"book_{s:g}deg", "book", {"step": math.radians(s)})
            for s in (15.0, 5.0, 1.0, 0.1, 0.01)]
    tols = (1e-6, 1e-8, 1e-10) if quick else (1e-6, 1e-8, 1e-10, 1e-12)
    for method in ("RK45", "DOP853", "Radau"):
        for rtol in tols:
            if quick and method == "Radau" and rtol < 1e-8:
                continue
            rows.append((f"{method}_rtol{rtol:.0e}", method, {"rtol": rtol, "atol": rtol * 1e-2}))
    return rows


def example(tag, added, quick, t_base):
    inertia, moment = models(added)
    ref = steady_state(inertia, moment, omega_guess=5.0, rtol=1e-13, atol=1e-15)
    check = steady_state(inertia, moment, omega_guess=5.0, method="Radau", rtol=1e-12,
                         atol=1e-14)
    print(f"{tag}_reference_delta: {ref.delta:.10f} 1")
    print(f"{tag}_reference_delta_avg: {ref.delta_avg:.10f} 1")
    print(f"{tag}_reference_omega_mean: {ref.omega_mean:.10f} rad/s")
    print(f"{tag}_reference_omega_max: {ref.omega_max:.8f} rad/s")
    print(f"{tag}_reference_omega_min: {ref.omega_min:.8f} rad/s")
    print(f"{tag}_reference_dW_max: {ref.dW_max:.6f} J")
    print(f"{tag}_reference_vs_radau_delta_difference: {abs(check.delta - ref.delta):.1e} 1")
    repeat = 1 if quick else 3
    for name, method, kw in settings(quick):
        t, s = best_of(lambda: steady_state(inertia, moment, omega_guess=5.0, method=method,
                                            **kw), repeat)
        print(f"{tag}_{name}_delta: {s.delta:.10f} 1")
        print(f"{tag}_{name}_delta_avg: {s.delta_avg:.10f} 1")
        print(f"{tag}_{name}_delta_error: {abs(s.delta - ref.delta):.2e} 1")
        print(f"{tag}_{name}_omega_mean: {s.omega_mean:.10f} rad/s")
        print(f"{tag}_{name}_omega_mean_error: {abs(s.omega_mean - ref.omega_mean):.2e} rad/s")
        print(f"{tag}_{name}_nfev: {s.nfev} 1")
        print(f"{tag}_{name}_time: {t * 1e3:.2f} ms")
        print(f"{tag}_{name}_time_over_baseline: {t / t_base:.1f} x")
    t, s = best_of(lambda: steady_state(inertia, moment, omega_guess=5.0), repeat)
    err = abs(s.delta - ref.delta)
    print(f"{tag}_default_delta_error: {err:.2e} 1 (target <= {DEFAULT_TOL:g}: "
          f"{'ok' if err <= DEFAULT_TOL else 'FAIL'})")
    print(f"{tag}_default_time: {t * 1e3:.1f} ms")
    print(f"{tag}_default_time_over_baseline: {t / t_base:.1f} x")
    return err <= DEFAULT_TOL, ref


def flywheel(quick, t_base):
    inertia, moment = models(0.0)
    # eq 6-30 with ΔWmax of ∫(M̄er − Mer)dφ at constant speed (trapezoid of 表 6-2)
    deficit = np.trapezoid(MER, PHI) / (2 * np.pi) - MER
    W = np.concatenate(([0.0], np.cumsum(np.diff(PHI) * 0.5 * (deficit[1:] + deficit[:-1]))))
    dW = float(W.max() - W.min())
    print(f"flywheel_constant_speed_dW_max: {dW:.4f} J")
    print(f"flywheel_approx_eq6_30_delta0.06_omega5: {flywheel_approx(dW, 5.0, 0.06):.4f} kg m2")
    t, jf = best_of(lambda: flywheel_exact(inertia, moment, 0.06, omega_guess=5.0),
                    1 if quick else 2)
    print(f"flywheel_exact_delta0.06: {jf:.4f} kg m2")
    print(f"flywheel_exact_time: {t * 1e3:.0f} ms")
    print(f"flywheel_exact_time_over_baseline: {t / t_base:.0f} x")
    s = steady_state(inertia.plus(J_F), moment, omega_guess=5.0)
    print(f"flywheel_book_J_F_delta: {s.delta:.6f} 1")


def main():
    quick = "--quick" in sys.argv
    t_base, w = best_of(baseline_loop, 5 if quick else 20)
    print(f"baseline_book_loop_1deg_one_period: {t_base * 1e3:.3f} ms")
    ok = True
    for tag, added in (("ex6_4", 0.0), ("ex6_5", J_F)):
        good, _ = example(tag, added, quick, t_base)
        ok &= good
    flywheel(quick, t_base)
    linkage_samples(t_base)
    if not ok:
        sys.exit(1)


def linkage_samples(t_base):
    """The ``[inertia] samples`` knob: a linkage's Je, dJe sampled per turn and interpolated
    by cubic Hermite for the integrators (configs/ch6/linkage-motor.toml, steady state),
    δ against 36,000 samples, with the time of the whole solve."""
    import dataclasses
    from pathlib import Path

    from mechcli.core.flywheel.problems import solve_flywheel
    from mechcli.spec.flywheel import read_flywheel_spec

    cfg = Path(__file__).resolve().parent.parent / "configs" / "ch6" / "linkage-motor.toml"
    spec = read_flywheel_spec(cfg)

    def run(n):
        sp = dataclasses.replace(spec, inertia=dataclasses.replace(spec.inertia, samples=n))
        return solve_flywheel(sp).steady.delta

    ref = run(36000)
    for n in (360, 1800, 3600, 7200):
        t, d = best_of(lambda: run(n), 1)
        print(f"linkage_motor_samples_{n}_delta_error: {abs(d - ref):.1e} 1")
        print(f"linkage_motor_samples_{n}_time: {t * 1e3:.0f} ms")
        print(f"linkage_motor_samples_{n}_time_over_baseline: {t / t_base:.0f} x")


if __name__ == "__main__":
    run(main)
