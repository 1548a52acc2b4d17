"""Results, book-format report and ``flywheel.csv`` of ``mechcli flywheel``.

Turns a :class:`~mechcli.core.flywheel.problems.FlywheelSolution` into the
``--json`` results (SI units in the names: ``omega_max_rad_s``, ``J_F_kg_m2``), the
table of the motion at the book's angles, and the CSV of the whole output grid.
Solves nothing.
"""

from __future__ import annotations

import math

from mechcli.report.table import Block, Report, book_title

#: rows of the printed table at most (the CSV has every point)
TABLE_ROWS = 25


def _label(lang, en, zh):
    return zh if lang == "zh" else en


def _f(x, nd=4):
    return f"{x:.{nd}f}"


def results(spec, sol):
    """The scalar results (names from the issue: stable for scripts and CI)."""
    import numpy as np
    m = sol.motion
    r = {"method": sol.method, "kind": spec.motion.kind}
    Je = np.asarray(m.Je, dtype=float)
    r["Je_min_kg_m2"], r["Je_max_kg_m2"] = float(Je.min()), float(Je.max())
    dJe = np.asarray(m.dJe, dtype=float)
    r["dJe_min_kg_m2_rad"], r["dJe_max_kg_m2_rad"] = float(dJe.min()), float(dJe.max())
    Me = np.asarray(m.Me, dtype=float)
    if sol.moment is not None:
        r["Me_min_N_m"], r["Me_max_N_m"] = float(Me.min()), float(Me.max())
    if sol.swing is not None:
        r["delta_from_dW"], r["omega_max_from_dW_rad_s"], r["omega_min_from_dW_rad_s"] = \
            (float(x) for x in sol.swing)
    if not hasattr(m, "omega"):       # the equivalent model only
        if sol.J_F is not None:
            r["J_F_kg_m2"] = float(sol.J_F)
        return r
    w = np.asarray(m.omega, dtype=float)
    r["omega_max_rad_s"], r["omega_min_rad_s"] = float(w.max()), float(w.min())
    r["omega_final_rad_s"] = float(w[-1])
    r["t_final_s"] = float(m.t[-1])
    r["phi_final_rad"] = float(m.phi[-1])
    r["phi_final_deg"] = math.degrees(float(m.phi[-1]))
    if m.rtol is not None and sol.method not in ("energy", "closed_form", "book"):
        r["rtol"], r["atol"] = float(m.rtol), float(m.atol)
    if m.step is not None:
        r["step_deg"] = math.degrees(float(m.step))
    r["nfev"] = int(m.nfev)
    st = sol.steady
    if st is not None:
        r.update(omega0_rad_s=float(st.omega0), omega_max_rad_s=float(st.omega_max),
                 omega_min_rad_s=float(st.omega_min),
                 phi_at_max_deg=math.degrees(float(st.phi_at_max)),
                 phi_at_min_deg=math.degrees(float(st.phi_at_min)),
                 omega_mean_rad_s=float(st.omega_mean), omega_avg_rad_s=float(st.omega_avg),
                 delta=float(st.delta), delta_avg=float(st.delta_avg),
                 dW_max_J=float(st.dW_max), iterations=int(st.iterations),
                 periodicity_residual_rad_s=float(st.residual), root=st.root)
    for key, val in (("J_F_kg_m2", sol.J_F), ("J_F_approx_kg_m2", sol.J_F_approx),
                     ("J_F_delta", sol.J_F_delta), ("omega_inf_rad_s", sol.omega_inf),
                     ("flywheel_mass_kg", sol.mass), ("flywheel_width_m", sol.width)):
        if val is not None:
            r[key] = float(val)
    return r


def columns(sol):
    """``flywheel.csv``: every point of the output grid."""
    import numpy as np
    m = sol.motion
    if not hasattr(m, "omega"):       # the equivalent model only: the columns it has
        cols = [("phi_deg", np.degrees(m.phi)), ("Je_kg_m2", m.Je),
                ("dJe_dphi_kg_m2_rad", m.dJe)]
        return cols + ([("Me_N_m", m.Me)] if sol.moment is not None else [])
    E = 0.5 * np.asarray(m.Je) * np.asarray(m.omega) ** 2
    return [("phi_deg", np.degrees(m.phi)), ("t_s", m.t), ("Je_kg_m2", m.Je),
            ("dJe_dphi_kg_m2_rad", m.dJe), ("Me_N_m", m.Me),
            ("W_J", E - E[0]), ("omega_rad_s", m.omega), ("alpha_rad_s2", m.alpha)]


def warnings(spec, sol):
    """What the user must know beside the numbers."""
    out = []
    st = sol.steady
    if st is not None and sol.omega_balance is not None:
        off = abs(st.omega_mean - sol.omega_balance)
        if off > 1e-6 * abs(sol.omega_balance):
            out.append(f"the steady state is ill-conditioned: its mean speed "
                       f"{st.omega_mean:.9g} rad/s misses the {sol.omega_balance:.9g} rad/s "
                       "the energy balance requires (the motor's damping changes ω too little "
                       "per period for the integrator's tolerance): tighten rtol/atol")
    if st is not None and spec.flywheel.delta is not None:
        out.append("delta, the speeds and the CSV describe the machine without the sized "
                   f"flywheel; with J_F = {sol.J_F:.6g} kg m², δ = {sol.J_F_delta:.6g}")
    return out


def non_finite(sol):
    """A message naming the first quantity of the solution that is not finite (the
    inputs are too extreme for floating point), else None."""
    import numpy as np
    for name, col in columns(sol):
        a = np.asarray(col, dtype=float)
        if not np.all(np.isfinite(a)):
            i = int(np.argmax(~np.isfinite(a)))
            return (f"the motion leaves the range of floating-point numbers ({name} at row "
                    f"{i + 1}): the inertia, moments or speeds are too extreme")
    return None


def build_report(spec, sol, lang):
    """The motion at up to 25 angles, then the figures of the run."""
    import numpy as np
    m = sol.motion
    rep = Report(book_title(spec.header.title))
    n = len(m.phi)
    idx = np.unique(np.linspace(0, n - 1, min(n, TABLE_ROWS)).round().astype(int))
    if not hasattr(m, "omega"):
        heads = [_label(lang, "phi [deg]", "转角 φ/°"), "Je [kg m2]", "dJe/dφ [kg m2/rad]"]
        rows = [[_f(math.degrees(m.phi[i]), 2), _f(m.Je[i], 5), _f(m.dJe[i], 5)]
                for i in idx]
        if sol.moment is not None:
            heads.append("Me [N m]")
            for row, i in zip(rows, idx):
                row.append(_f(m.Me[i], 3))
    else:
        heads = [_label(lang, "phi [deg]", "转角 φ/°"), "t [s]", "Je [kg m2]", "Me [N m]",
                 "ω [rad/s]", "α [rad/s2]"]
        rows = [[_f(math.degrees(m.phi[i]), 2), _f(m.t[i], 5), _f(m.Je[i], 4),
                 _f(m.Me[i], 2), _f(m.omega[i], 5), _f(m.alpha[i], 3)] for i in idx]
    rep.blocks.append(Block(_label(lang, "Motion of the equivalent link", "等效构件的运动"),
                            heads, rows))
    r = results(spec, sol)
    kv = []
    for key, en, zh, nd in (
            ("Je_min_kg_m2", "Je min [kg m2]", "Je 最小值", 5),
            ("Je_max_kg_m2", "Je max [kg m2]", "Je 最大值", 5),
            ("method", "method", "方法", None), ("omega_max_rad_s", "ω max [rad/s]", "ωmax", 6),
            ("omega_min_rad_s", "ω min [rad/s]", "ωmin", 6),
            ("omega_mean_rad_s", "ω mean (eq. 6-26) [rad/s]", "ωm (式 6-26)", 6),
            ("omega_avg_rad_s", "(ωmax + ωmin)/2 (eq. 6-27) [rad/s]", "ωm (式 6-27)", 6),
            ("delta", "δ (with eq. 6-26)", "速度不均匀系数 δ", 6),
            ("delta_avg", "δ (with eq. 6-27)", "δ (式 6-27)", 6),
            ("dW_max_J", "ΔWmax [J]", "最大盈亏功 ΔWmax/J", 4),
            ("J_F_kg_m2", "flywheel J_F [kg m2]", "飞轮转动惯量 J_F", 4),
            ("delta_from_dW", "δ from ΔWmax (eq. 6-29)", "由 ΔWmax 得 δ", 6),
            ("omega_max_from_dW_rad_s", "ω max (eq. 6-28) [rad/s]", "ωmax (式 6-28)", 6),
            ("omega_min_from_dW_rad_s", "ω min (eq. 6-28) [rad/s]", "ωmin (式 6-28)", 6),
            ("J_F_approx_kg_m2", "J_F by eq. 6-29 [kg m2]", "J_F (式 6-29)", 4),
            ("J_F_delta", "δ with J_F", "加飞轮后 δ", 6),
            ("flywheel_mass_kg", "flywheel mass [kg]", "飞轮质量/kg", 3),
            ("omega_inf_rad_s", "asymptotic ω [rad/s]", "稳定角速度 ω∞", 6),
            ("t_final_s", "t at the end [s]", "终止时间 t/s", 6),
            ("omega_final_rad_s", "ω at the end [rad/s]", "终止角速度", 6),
            ("iterations", "iterations", "迭代次数", None),
            ("periodicity_residual_rad_s", "|ω(T) − ω(0)| [rad/s]", "周期残差", None)):
        if key in r:
            v = r[key]
            text = str(v) if nd is None and not isinstance(v, float) else \
                (f"{v:.2e}" if nd is None else _f(v, nd))
            kv.append([_label(lang, en, zh), text])
    rep.blocks.append(Block(_label(lang, "Results", "计算结果"), rows=kv))
    return rep


def error_message(exc, spec):
    """A flywheel core error in words of the spec's keys."""
    v, reason = exc.values, exc.reason
    where = {"stall": "[motion] omega0", "unreachable": "[motion] omega_end",
             "no_steady_state": "[moment]", "not_periodic": "[inertia]",
             "not_one_period": "[inertia] phi_deg", "not_increasing": "[inertia] phi_deg",
             "too_few": "[inertia] phi_deg", "not_uniform": "[inertia] phi_deg",
             "not_positive": "[inertia] J", "end": "[motion]", "method": "[motion] method",
             "no_flywheel_needed": "[flywheel] delta", "cannot_assemble": "[mechanism]",
             "dead_point": "[mechanism]", "stiff": "[motion] method",
             "moment_not_periodic": "[moment]", "inertia_vanishes": "[[link]]"}.get(reason, "")
    text = str(exc)
    if reason == "stall" and "phi" in v:
        text += f" (at phi = {math.degrees(v['phi']):.6g} deg)"
    if reason == "unreachable" and "omega_inf" in v:
        text += (f" (the speed tends to {v['omega_inf']:.6g} rad/s and never reaches "
                 f"{v['omega_end']:.6g})")
    if reason in ("cannot_assemble", "dead_point", "inertia_vanishes") and "angle" in v:
        text += f" (at phi = {math.degrees(v['angle']):.6g} deg)"
    return f"{where}: {text}" if where else text
