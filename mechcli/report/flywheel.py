"""Results, book-format report and ``flywheel.csv`` of ``mechcli flywheel``.

Turns a :class:`~mechcli.core.flywheel.problems.FlywheelSolution` into the
``--json`` results (SI units in the names: ``omega_max_rad_s``, ``J_F_kg_m2``), the
table of the motion at the book's angles, and the CSV of the whole output grid.
Solves nothing.
"""

from __future__ import annotations

import math

from mechcli.report.kin import header
from mechcli.report.table import Block, Report, book_title
from mechcli.report.words import say

#: rows of the printed table at most (the CSV has every point)
TABLE_ROWS = 25


def _f(x, nd=4):
    return f"{x:.{nd}f}"


#: r/min per rad/s
_RPM = 30.0 / math.pi


def _cycle_results(spec, sol):
    """The numbers of a cycle: its length, the loop table's ΔWmax and where the speed
    peaks, the work per cycle, the mean moment and power, the balancing mean term."""
    r = {"cycle_deg": math.degrees(sol.period)}
    if sol.mean_term is not None:
        name, value = sol.mean_term
        r["Mr_mean_N_m" if name == "resisting" else "Md_mean_N_m"] = float(value)
    lp = sol.loops
    if lp is not None:
        r.update(dE_max_J=float(lp.dW_max), phi_E_max_deg=math.degrees(lp.phi_max),
                 phi_E_min_deg=math.degrees(lp.phi_min), loops=int(lp.areas.size))
    if sol.dW_trapezoid is not None:
        r["dE_max_trapezoid_J"] = float(sol.dW_trapezoid)
    if sol.work_per_cycle is not None:
        r["work_per_cycle_J"] = float(sol.work_per_cycle)
        r["M_mean_N_m"] = float(sol.work_per_cycle / sol.period)
        if sol.omega_m is not None:
            r["power_mean_W"] = float(sol.work_per_cycle / sol.period * sol.omega_m)
    if sol.equation is not None:
        r["J_F_equation"] = sol.equation
    if sol.motion_with_J_F:
        r["motion_with_J_F"] = True
    return r


def loop_rows(sol):
    """``loops.csv``: each loop's ends, energy and the cumulative energy at its end."""
    import numpy as np
    lp = sol.loops
    return [("phi_from_deg", np.degrees(lp.bounds[:-1])), ("phi_to_deg", np.degrees(lp.bounds[1:])),
            ("dE_J", lp.areas), ("E_J", lp.cumulative[1:])]


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
        if spec.flywheel.rpm:
            r["n_max_from_dW_rpm"] = float(sol.swing[1]) * _RPM
            r["n_min_from_dW_rpm"] = float(sol.swing[2]) * _RPM
    r.update(_cycle_results(spec, sol))
    if not hasattr(m, "omega"):       # the equivalent model only
        for key, val in (("J_F_kg_m2", sol.J_F), ("flywheel_mass_kg", sol.mass),
                         ("flywheel_width_m", sol.width)):
            if val is not None:
                r[key] = float(val)
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
        if spec.flywheel.rpm:
            r.update(n_mean_rpm=float(st.omega_mean) * _RPM,
                     n_max_rpm=float(st.omega_max) * _RPM,
                     n_min_rpm=float(st.omega_min) * _RPM)
    for key, val in (("J_F_kg_m2", sol.J_F), ("J_F_approx_kg_m2", sol.J_F_approx),
                     ("J_F_delta", sol.J_F_delta), ("omega_inf_rad_s", sol.omega_inf),
                     ("flywheel_mass_kg", sol.mass), ("flywheel_width_m", sol.width),
                     ("flywheel_mass_approx_kg", sol.mass_approx)):
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
    if st is not None and spec.flywheel.delta is not None and sol.motion_with_J_F:
        out.append("the machine cannot run at that mean speed without a flywheel: delta, the "
                   f"speeds and the CSV describe it with the sized J_F = {sol.J_F:.6g} kg m²")
    elif st is not None and spec.flywheel.delta is not None:
        out.append("delta, the speeds and the CSV describe the machine without the sized "
                   f"flywheel; with J_F = {sol.J_F:.6g} kg m², δ = {sol.J_F_delta:.6g}")
    if sol.dW_trapezoid is not None and sol.loops is not None:
        d = sol.loops.dW_max - sol.dW_trapezoid
        out.append(f"integration = \"simpson\": ΔWmax = {sol.loops.dW_max:.6g} J; the same "
                   f"tables read linearly (the trapezoid rule) give {sol.dW_trapezoid:.6g} J "
                   f"({d:+.4g} J, {d / sol.dW_trapezoid:+.3%})")
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
    phi = header("φ", "°", say(lang, "flywheel.angle"))
    idx = np.unique(np.linspace(0, n - 1, min(n, TABLE_ROWS)).round().astype(int))
    if not hasattr(m, "omega"):
        heads = [phi, header("Je", "kg·m²"), header("dJe/dφ", "kg·m²/rad")]
        rows = [[_f(math.degrees(m.phi[i]), 2), _f(m.Je[i], 5), _f(m.dJe[i], 5)]
                for i in idx]
        if sol.moment is not None:
            heads.append(header("Me", "N·m"))
            for row, i in zip(rows, idx):
                row.append(_f(m.Me[i], 3))
    else:
        heads = [phi, header("t", "s"), header("Je", "kg·m²"), header("Me", "N·m"),
                 header("ω", "rad/s"), header("α", "rad/s²")]
        rows = [[_f(math.degrees(m.phi[i]), 2), _f(m.t[i], 5), _f(m.Je[i], 4),
                 _f(m.Me[i], 2), _f(m.omega[i], 5), _f(m.alpha[i], 3)] for i in idx]
    rep.blocks.append(Block(say(lang, "flywheel.motion"),
                            heads, rows))
    if sol.loops is not None:
        lp = sol.loops
        rows = [[str(i + 1), _f(math.degrees(lp.bounds[i]), 3),
                 _f(math.degrees(lp.bounds[i + 1]), 3),
                 ("+" if lp.areas[i] >= 0 else "") + _f(lp.areas[i], 3),
                 _f(lp.cumulative[i + 1], 3)] for i in range(lp.areas.size)]
        rep.blocks.append(Block(
            say(lang, "flywheel.loops"),
            [say(lang, "flywheel.loop"), header("φ", "°", say(lang, "flywheel.from")),
             header("φ", "°", say(lang, "flywheel.to")), header("ΔE", "J"),
             header("E", "J", say(lang, "flywheel.cumulative"))],
            rows))
    r = results(spec, sol)
    kv = []
    for key, nd in (
            ('Je_min_kg_m2', 5), ('Je_max_kg_m2', 5), ('method', None), ('omega_max_rad_s', 6),
            ('omega_min_rad_s', 6), ('omega_mean_rad_s', 6), ('omega_avg_rad_s', 6), ('delta', 6),
            ('delta_avg', 6), ('dW_max_J', 4), ('cycle_deg', 2), ('Mr_mean_N_m', 4),
            ('Md_mean_N_m', 4), ('work_per_cycle_J', 4), ('M_mean_N_m', 4), ('power_mean_W', 3),
            ('dE_max_J', 4), ('dE_max_trapezoid_J', 4), ('phi_E_max_deg', 3),
            ('phi_E_min_deg', 3), ('n_mean_rpm', 4), ('n_max_rpm', 4), ('n_min_rpm', 4),
            ('J_F_kg_m2', 4), ('J_F_equation', None), ('delta_from_dW', 6),
            ('omega_max_from_dW_rad_s', 6), ('omega_min_from_dW_rad_s', 6),
            ('n_max_from_dW_rpm', 4), ('n_min_from_dW_rpm', 4), ('J_F_approx_kg_m2', 4),
            ('J_F_delta', 6), ('flywheel_mass_kg', 3), ('flywheel_mass_approx_kg', 3),
            ('flywheel_width_m', 5), ('omega_inf_rad_s', 6), ('t_final_s', 6),
            ('omega_final_rad_s', 6), ('iterations', None), ('periodicity_residual_rad_s', None)):
        if key in r:
            v = r[key]
            text = str(v) if nd is None and not isinstance(v, float) else \
                (f"{v:.2e}" if nd is None else _f(v, nd))
            kv.append([say(lang, f"flywheel.r_{key}"), text])
    rep.blocks.append(Block(say(lang, "flywheel.results"), rows=kv))
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
             "moment_not_periodic": "[moment]", "inertia_vanishes": "[[link]]",
             "no_loops": "[moment]"}.get(reason, "")
    text = str(exc)
    if reason == "stall" and "phi" in v:
        text += f" (at phi = {math.degrees(v['phi']):.6g} deg)"
    if reason == "unreachable" and "omega_inf" in v:
        text += (f" (the speed tends to {v['omega_inf']:.6g} rad/s and never reaches "
                 f"{v['omega_end']:.6g})")
    if reason in ("no_loops", "no_steady_state") and "net_work" in v:
        text += (f" (the net work per cycle is {v['net_work']:.6g} J: make a term the mean, "
                 'e.g. resisting = "mean")')
    if reason == "end" and "to_angle" in v:
        text += (": give phi_end_deg (omega_end and t_end need the closed form: a constant "
                 "inertia and a moment of the speed only)" if v["to_angle"]
                 else ": give omega_end or t_end")
    if reason in ("cannot_assemble", "dead_point", "inertia_vanishes") and "angle" in v:
        text += f" (at phi = {math.degrees(v['angle']):.6g} deg)"
    return f"{where}: {text}" if where else text
