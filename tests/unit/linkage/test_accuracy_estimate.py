"""The digits-lost estimate of ``kin`` and ``force`` against a 60-digit reference.

The reference is an independent closed form evaluated with mpmath (60 digits): the
four-bar of 例 1-1 (l1, l2, l3 as the book's) with its frame l4 moved to a relative
distance 1e-3 ... 1e-13 from the change point l1 + l4 = l2 + l3, where the transmission
angle at C reaches sin(gamma) ~ sqrt(distance) at theta1 = 180°; for forces the
four-bar of 例 2-1 (its masses, inertias, gravity and load torque), Mb by virtual work
and |F_R23| from the moment equations of links 2 and 3.  The true loss is the largest
error over the sweep relative to the quantity's largest magnitude, as the estimate
counts it.  The estimate must be within one digit of it, and the warning must appear
exactly when the estimate falls below the threshold.
"""

import math

import numpy as np
import pytest

from mechcli.core.linkage import DriverMotion, four_bar, solve
from mechcli.core.linkage.kinematics import (ACCURACY_WARN, Sweep, analyse_sweep,
                                             default_quantities)

from tests.conftest import run_inprocess

mp = pytest.importorskip("mpmath")

L1, L2, L3 = 0.1016, 0.254, 0.1778          # 例 1-1 [m]
W1 = 250.0                                   # rad/s, 例 1-1


def _four_bar_ref(l1, l2, l3, l4, th, w1, branch=1):
    """theta, omega, alpha of links 2 and 3 (closed form, 60 digits)."""
    l1, l2, l3, l4, th, w1 = map(mp.mpf, (l1, l2, l3, l4, th, w1))
    bx, by = l1 * mp.cos(th), l1 * mp.sin(th)
    dx, dy = l4 - bx, -by
    d2 = dx * dx + dy * dy
    d = mp.sqrt(d2)
    al = (l2 * l2 - l3 * l3 + d2) / (2 * d)
    h = mp.sqrt(l2 * l2 - al * al) * branch
    ex, ey = dx / d, dy / d
    cx, cy = bx + al * ex - h * ey, by + al * ey + h * ex
    rax, ray, rbx, rby = cx - bx, cy - by, cx - l4, cy
    vbx, vby = -w1 * by, w1 * bx
    abx, aby = -w1 ** 2 * bx, -w1 ** 2 * by
    A = mp.matrix([[-ray, rby], [rax, -rbx]])
    w = mp.lu_solve(A, mp.matrix([-vbx, -vby]))
    a = mp.lu_solve(A, mp.matrix([-abx + w[0] ** 2 * rax - w[1] ** 2 * rbx,
                                  -aby + w[0] ** 2 * ray - w[1] ** 2 * rby]))
    return {"theta2": mp.atan2(ray, rax), "theta3": mp.atan2(rby, rbx),
            "omega2": w[0], "omega3": w[1], "alpha2": a[0], "alpha3": a[1]}


def _angles():
    # 1° rows, and inputs crowding 180° where the dyad is nearly singular
    near = 180 + np.concatenate([np.linspace(-2, 2, 81), np.logspace(-8, 0, 25),
                                 -np.logspace(-8, 0, 25)])
    return np.radians(np.unique(np.concatenate([np.arange(0.0, 361.0), near])))


def _true_digits(l4, th):
    m = solve(four_bar(L1, L2, L3, l4), {1: DriverMotion(th, W1, 0.0)}, order=2)
    err, peak = {}, {}
    for i, t in enumerate(th):
        ref = _four_bar_ref(L1, L2, L3, l4, t, W1)
        for sym, r in ref.items():
            got = getattr(m.links[int(sym[-1])], sym[:-1])[i]
            e = abs(mp.mpf(float(got)) - r)
            if sym.startswith("theta"):
                e = min(e, abs(e - 2 * mp.pi))
            err[sym] = max(err.get(sym, 0.0), float(e))
            peak[sym] = max(peak.get(sym, 0.0), abs(float(r)))
    # an angle is counted against a radian at least, as the estimate does
    return {s: -math.log10(max(err[s], 1e-300) / max(peak[s], 1.0 if s[0] == "t" else 0.0))
            for s in err}


@pytest.mark.parametrize("distance", [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13])
def test_kin_estimate_within_one_digit_near_the_change_point(distance):
    l4 = (L2 + L3 - L1) - distance * (L2 + L3)
    th = _angles()
    linkage = four_bar(L1, L2, L3, l4)
    res = analyse_sweep(linkage, Sweep(1, th, W1, 0.0), default_quantities(linkage, 2), 2)
    est = res.accuracy.by_quantity
    true = _true_digits(l4, th)
    for sym, d in true.items():
        d = min(d, 15.65)          # both are capped at the digits a float64 has
        assert abs(est[sym] - d) <= 1.0, (sym, est[sym], d)


@pytest.mark.parametrize("distance", [1e-5, 1e-7, 1e-9, 1e-11])
def test_warning_exactly_when_the_estimate_is_below_the_threshold(tmp_path, distance):
    import json
    l4_mm = 330.2 - distance * 431.8
    spec = tmp_path / "near.toml"
    spec.write_text(
        'command = "kin"\nunits = "mm"\n[mechanism]\ntype = "four_bar"\n'
        f'l1 = 101.6\nl2 = 254\nl3 = 177.8\nl4 = {l4_mm!r}\n'
        '[input]\nomega1 = 250\nstart = 0\nstop = 360\nstep = 1\n'
        '[output]\nplots = false\n', encoding="utf-8")
    for threshold in (ACCURACY_WARN, 4.0):
        args = ["kin", str(spec), "--json", "--no-plot", "-o", str(tmp_path / "o")]
        if threshold != ACCURACY_WARN:
            args += ["--accuracy-warn", str(threshold)]
        proc = run_inprocess(*args)
        assert proc.returncode == 0, proc.stderr
        doc = json.loads(proc.stdout)
        acc = doc["results"]["accuracy"]
        low = {c for c in ("positions", "velocities", "accelerations") if acc[c] < threshold}
        warned = [w for w in doc["warnings"] if "correct significant digits" in w]
        # once per range: here the one range around 180°, one line per class that is low
        assert sorted(w.split()[0] for w in warned) == sorted(low), (warned, acc)
        for w in warned:
            assert "180" in w and f"fewer than {threshold:g}" in w


def _force_ref(l4, th):
    """Mb (virtual work) and |F_R23| of 例 2-1 at the crank angle ``th`` (60 digits)."""
    l1, l2, l3, l4, th, w1, g, mr = map(mp.mpf, (0.4, 1.0, 0.7, l4, th, 10, 10, -100))
    m = [mp.mpf(x) for x in (1.2, 3, 2.2)]
    J = [mp.mpf(x) for x in (0.016, 0.25, 0.09)]
    bx, by = l1 * mp.cos(th), l1 * mp.sin(th)
    dx, dy = l4 - bx, -by
    d2 = dx * dx + dy * dy
    d = mp.sqrt(d2)
    al = (l2 * l2 - l3 * l3 + d2) / (2 * d)
    h = mp.sqrt(l2 * l2 - al * al)
    cx, cy = bx + (al * dx - h * dy) / d, by + (al * dy + h * dx) / d
    ra, rb = (cx - bx, cy - by), (cx - l4, cy)
    vB, aB = (-w1 * by, w1 * bx), (-w1 ** 2 * bx, -w1 ** 2 * by)
    A = mp.matrix([[-ra[1], rb[1]], [ra[0], -rb[0]]])
    w = mp.lu_solve(A, mp.matrix([-vB[0], -vB[1]]))
    a = mp.lu_solve(A, mp.matrix([-aB[0] + w[0] ** 2 * ra[0] - w[1] ** 2 * rb[0],
                                  -aB[1] + w[0] ** 2 * ra[1] - w[1] ** 2 * rb[1]]))
    vC = (vB[0] - w[0] * ra[1], vB[1] + w[0] * ra[0])
    aC = (aB[0] - a[0] * ra[1] - w[0] ** 2 * ra[0], aB[1] + a[0] * ra[0] - w[0] ** 2 * ra[1])
    v = [(vB[0] / 2, vB[1] / 2), ((vB[0] + vC[0]) / 2, (vB[1] + vC[1]) / 2),
         (vC[0] / 2, vC[1] / 2)]
    acc = [(aB[0] / 2, aB[1] / 2), ((aB[0] + aC[0]) / 2, (aB[1] + aC[1]) / 2),
           (aC[0] / 2, aC[1] / 2)]
    F = [(-m[i] * acc[i][0], -m[i] * acc[i][1] - m[i] * g) for i in range(3)]
    M = [0, -J[1] * a[0], -J[2] * a[1] + mr]
    om = [w1, w[0], w[1]]
    mb = -sum(F[i][0] * v[i][0] + F[i][1] * v[i][1] + M[i] * om[i] for i in range(3)) / w1
    s2 = ((cx - bx) / 2, (cy - by) / 2)
    s3 = ((cx - l4) / 2, cy / 2)
    K = mp.matrix([[-rb[1], rb[0]], [ra[1], -ra[0]]])
    rhs = mp.matrix([-(s3[0] * F[2][1] - s3[1] * F[2][0] + M[2]),
                     -(s2[0] * F[1][1] - s2[1] * F[1][0] + M[1])])
    R = mp.lu_solve(K, rhs)
    return mb, mp.sqrt(R[0] ** 2 + R[1] ** 2)


@pytest.mark.parametrize("distance", [1e-2, 1e-6, 1e-8, 1e-10, 1e-12])
def test_force_estimate_within_one_digit_near_the_change_point(tmp_path, distance):
    from mechcli.core.linkage.force_analysis import analyse_forces
    from mechcli.spec.force import load_force_spec
    import pathlib
    l4_mm = 1300 - distance * 1700
    src = (pathlib.Path(__file__).parents[3] / "configs/ch2/ex2-1.toml").read_text("utf-8")
    spec_path = tmp_path / "near.toml"
    spec_path.write_text(src.replace("l4 = 1200", f"l4 = {l4_mm!r}"), encoding="utf-8")
    spec = load_force_spec(str(spec_path))
    sweep = spec.input.sweep()
    res = analyse_forces(spec.linkage, spec.topology, sweep, spec.bodies, spec.gravity,
                         spec.loads)
    est = res.accuracy.minimum()["forces"]
    # the reference at the 1° rows and crowding 180° (where the loss is: the error
    # vanishes at 180° itself, by symmetry, and peaks just beside it)
    th = _angles()
    from mechcli.core.linkage.force_analysis import ForceEvaluator
    fr, _m, _mo = ForceEvaluator(spec.linkage, spec.topology, sweep, spec.bodies,
                                 spec.gravity, spec.loads)(th)
    pf = next(p for p in fr.pairs if p.pair.label == "23")
    e_mb = e_fr = p_mb = p_fr = 0.0
    for i, t in enumerate(th):
        mb, f23 = _force_ref(l4_mm / 1000, t)
        e_mb = max(e_mb, float(abs(mp.mpf(float(fr.balancing[1][i])) - mb)))
        e_fr = max(e_fr, float(abs(mp.mpf(float(pf.magnitude[i])) - f23)))
        p_mb, p_fr = max(p_mb, abs(float(mb))), max(p_fr, float(f23))
    true = min(-math.log10(max(e_mb, 1e-300) / p_mb), -math.log10(max(e_fr, 1e-300) / p_fr))
    assert abs(est - min(true, 15.65)) <= 1.0, (est, true)
