"""Tables, results, CSV and pictures of ``mechcli gear`` (one function per problem kind).

Every ``present_<kind>`` returns ``(report, results, warnings)`` after writing
its CSV (and PNG/GIF when asked) into *outputs*; the solution comes from
``mechcli.core.gear.problems``.  The findings that a spec may forbid (ε < 1,
interference, pointed tips, undercut) are checked before, by :func:`enforce`,
:func:`error_message` words the core's gear errors and :func:`mounting_error` a
refused mounting as the spec error of its key.  Lengths are shown in
the spec's unit, angles in degrees.

The scalar kinds (involute table, inverse involute, pair, helical, worm,
bevel) never import numpy: their CSV text comes from :func:`csv_text`; only
the profile kinds (spur, generation) and the pictures use numpy.
"""

from __future__ import annotations

import math
import re

from mechcli.core.errors import UnsolvableError
from mechcli.report.files import DEFAULT_DIGITS, OutputError, format_number
from mechcli.report.table import Block, Report, book_title, unit_header
from mechcli.report.words import say


def csv_text(columns, digits=DEFAULT_DIGITS):
    """CSV text of named columns ``[(header, sequence of numbers), ...]`` without numpy.

    The rules of :func:`mechcli.report.files.write_csv`: equal column lengths,
    every value finite (:class:`OutputError` otherwise), ``%.{digits}g`` cells.
    """
    headers = [h for h, _ in columns]
    cols = [[float(v) for v in col] for _, col in columns]
    n = len(cols[0]) if cols else 0
    for h, col in zip(headers, cols):
        if len(col) != n:
            raise OutputError(f"column {h} has {len(col)} values, expected {n}")
        for i, v in enumerate(col):
            if not math.isfinite(v):
                raise OutputError(f"refusing to write non-finite {h} in row {i + 1}")
    lines = [",".join(headers)]
    lines.extend(",".join(format_number(v, digits) for v in row) for row in zip(*cols))
    return "\n".join(lines) + "\n"


# -- result names with their unit ---------------------------------------
#: results that are lengths in the spec's unit: their names carry the unit, ``d`` ->
#: ``d_mm``, ``a_w_2`` -> ``a_w_mm_2`` (a variant's index stays last, as in
#: ``alpha_w_deg_2``); the bare names stay in the JSON as aliases for one release
_LENGTHS = frozenset((
    # one gear (spur), generation, involute curve
    "m", "d", "db", "da", "df", "p", "pb", "s", "e", "h", "ha", "hf", "c", "s_a", "e_a", "s_b",
    "e_b", "r_pointed", "r_form", "r", "rb", "ra", "rf", "undercut_depth", "s_b_generated",
    "r_max", "x_max", "y_max",
    # a pair
    "a", "a_w", "a_zero_backlash", "d1", "d2", "db1", "db2", "da1", "da2", "df1", "df2", "ha1",
    "ha2", "hf1", "hf2", "h1", "h2", "pb1", "pb2", "s1", "s2", "e1", "e2", "dw1", "dw2",
    "backlash", "backlash_n", "clearance1", "clearance2",
    # helical, worm, bevel
    "mt", "mt2", "mx1", "px", "lead", "R", "b_min1", "b_min2", "dm1", "dm2", "b",
    # measurements over spans and pins, of the gear ("") or of gear 1, 2
    *(f"{n}{i}" for n in ("s_chord", "h_chord", "W", "d_W", "dp", "M", "d_M", "d_pin",
                          "allowance", "s_n") for i in ("", "1", "2"))))
#: lengths at the radii a spur spec lists: s_r1, e_r1, s_chord_r1, h_chord_r1, ...
_LENGTH_AT_RADIUS = re.compile(r"(s|e|s_chord|h_chord)_r\d+")
#: a result name and the index of its variant (``a_w_2``: the second mounting)
_VARIANT = re.compile(r"(.+?)(_\d+)?")
#: unit suffixes of the names that already carry one (longest first: N_m before m)
_SUFFIXES = ("rad_s2", "rad_s", "N_m", "m_s", "kW", "rpm", "deg", "rad", "mm", "cm", "in",
             "N", "W", "m")


def _is_length(base):
    return base in _LENGTHS or bool(_LENGTH_AT_RADIUS.fullmatch(base))


def unit_name(key, unit):
    """The name of result *key* with its unit: ``d`` -> ``d_mm``, ``a_w_2`` ->
    ``a_w_mm_2``; a name that is not a length is returned as it is."""
    base, index = _VARIANT.fullmatch(key).groups()
    return f"{base}_{unit}{index or ''}" if _is_length(base) else key


def unit_names(results, unit):
    """``(named, aliases)``: *results* under the names with units (in order), and the
    old bare names of the lengths -> their new name (kept one release as aliases)."""
    named, aliases = {}, {}
    for key, value in results.items():
        new = unit_name(key, unit)
        if new != key:
            if new in results:   # a presenter gave the new name itself: keep that value
                continue
            aliases[key] = new
        named[new] = value
    return named, aliases


def with_aliases(results, unit):
    """The JSON results: every name with its unit, then the old bare length names
    (``d``, ``W``, ``s_a`` …) as aliases of the same values, for one release."""
    named, aliases = unit_names(results, unit)
    return {**named, **{old: named[new] for old, new in aliases.items()}}


def result_unit(name, unit):
    """The unit of a result from its name's suffix (``d_mm`` -> ``mm``, ``alpha_deg`` ->
    ``deg``, ``T1_N_m`` -> ``N_m``); ``""`` for a number without unit."""
    base = _VARIANT.fullmatch(name).group(1)
    for suffix in sorted({unit, *_SUFFIXES}, key=len, reverse=True):   # N_m before m
        if base.endswith("_" + suffix):
            return suffix
    return ""


#: the unit column of results.csv as the reports print units (the name keeps ``N_m``)
_UNIT_TEXT = {"N_m": "N·m", "m_s": "m/s", "rad_s": "rad/s", "rad_s2": "rad/s²"}


def results_csv(results, unit, digits=DEFAULT_DIGITS):
    """``results.csv``: one row ``name,value,unit`` per scalar result (numbers,
    true/false, text), names with their unit (no aliases); lists are left out, and a
    non-finite number, which :func:`mechcli.report.run.finish` refuses (exit 3)."""
    import csv
    import io

    named, _ = unit_names(results, unit)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["name", "value", "unit"])
    for name, v in named.items():
        if isinstance(v, bool):
            text = "true" if v else "false"
        elif isinstance(v, int):
            text = str(v)
        elif isinstance(v, float):
            if not math.isfinite(v):   # report.run.finish refuses the run (exit 3)
                continue
            text = format_number(v, digits)
        elif isinstance(v, str):
            text = v
        else:
            continue
        un = result_unit(name, unit)
        w.writerow([name, text, _UNIT_TEXT.get(un, un)])
    return buf.getvalue()


def wide_csv(first, results, unit, rows=1, digits=DEFAULT_DIGITS):
    """``gear.csv`` of a pair or drive: the columns *first* (``[(name, values)]``, one
    value per row) then every other numeric result, names with their unit, one row per
    mounting (a result of mounting k > 1 is the name + ``_k``; a result common to all
    mountings repeats); true/false as 1/0."""
    named, _ = unit_names(results, unit)
    have = {h for h, _ in first}
    variants = {f"{k}_{i}" for k in named for i in range(2, rows + 1)}
    cols = list(first)
    for key, v in named.items():
        if key in have or key in variants or isinstance(v, str) \
                or not isinstance(v, (int, float)):
            continue
        vals = [named.get(f"{key}_{i + 1}", v) if i else v for i in range(rows)]
        if all(isinstance(x, (int, float)) and math.isfinite(x) for x in vals):
            cols.append((key, vals))   # (a non-finite result: report.run.finish refuses it)
    return csv_text(cols, digits)


def present(spec, solution, run, outputs):
    """The presenter of *spec*'s kind, then ``results.csv`` (every result: name, value,
    unit); returns ``(report, results, warnings)`` with the JSON results (names with
    units and the old bare names as aliases)."""
    rep, results, warnings = PRESENTERS[spec.kind](spec, solution, run, outputs)
    rep.title = book_title(rep.title)
    results = {"kind": spec.kind, **results}
    unit = spec.header.unit
    outputs.text("results.csv", results_csv(results, unit, outputs.digits))
    return rep, with_aliases(results, unit), warnings


# -- undercut: one criterion, one warning ------------------------------
def undercut_margin_text(g, tooth, sc, u, lang="en"):
    """What a sharp-cornered cutter (the book's ``gear_cut``) cuts of the involute: the
    measure beside the criterion x >= x_min (a standard cutter's tip rounding spares
    what it cuts below the depth ha* m)."""
    if tooth is None or not tooth.undercut:
        return say(lang, "gear.undercut_none")
    return (f"{(tooth.r_form - g.rb) / sc:.4f} {u} ("
            + say(lang, "gear.undercut_percent", percent=f"{100 * tooth.undercut_fraction:.2f}"))


def undercut_message(g, tooth, sc, u):
    """The one warning of an undercut gear, in the same words for ``[spur]`` and
    ``[generation]``: the criterion is x < x_min (z < z_min for x = 0), the straight
    flank of the standard rack passing the tangent point N; the sharp-cornered cutter's
    cut (:class:`~mechcli.core.gear.profile.GeneratedTooth`) follows as its measure."""
    text = (f"undercut: z = {g.z}, x = {g.x:g} < x_min = {g.x_min:.4f} (z_min = "
            f"{g.z_min:.2f} for x = 0; standard rack, ha* = {g.ha_star:g})")
    if tooth is not None and tooth.undercut:
        text += (f"; the involute is cut from rb = {g.rb / sc:.4f} {u} up to r = "
                 f"{tooth.r_form / sc:.4f} {u} ({100 * tooth.undercut_fraction:.2f}% of its "
                 "length, sharp-cornered cutter)")
    return text + f"; x >= {g.x_min:.4f} avoids it"


def undercut_rows(g, tooth, sc, u, lang):
    """Report rows (label, symbol, text) of the undercut: the criterion and its margin
    x - x_min, then the sharp-cornered cutter's cut as the measure beside it."""
    verdict = say(lang, "gear.undercut_yes" if g.undercut else "gear.undercut_no")
    return [
        ("gear.undercut_criterion", "x − xmin",
         f"{g.x - g.x_min:+.4f} ({verdict})"),
        ("gear.involute_start", "r_form",
         f"{tooth.r_form / sc:.4f} {u}"),
        ("gear.involute_cut", "Δr",
         undercut_margin_text(g, tooth, sc, u, lang)),
    ]


# -- what a spec may forbid, and the core's errors in words ------------------------------
class RequirementError(UnsolvableError):
    """The spec forbids what the geometry has (ε < 1, interference, pointed tip, undercut)."""


def findings(spec, solution):
    """Warnings about the solution, each with whether the spec forbids it.

    Returns
    -------
    list of (str, bool)
        (one-line message in the spec's length unit, forbidden).
    """
    p, u, sc = spec.problem, spec.header.unit, spec.header.scale
    out = [(m, False) for m in measurement_warnings(spec, solution)]
    if spec.kind == "spur":
        g = solution["gear"]
        if g.tooth_thickness(g.ra) <= 0:
            out.append((f"pointed tip: the flanks meet at r = {g.pointed_radius / sc:.4f} {u} "
                        f"below ra = {g.ra / sc:.4f} {u}", p.forbid_pointed))
        if g.undercut:
            out.append((undercut_message(g, solution.get("tooth"), sc, u), p.forbid_undercut))
    elif spec.kind == "pair":
        first = solution[0]
        for i, g in enumerate((first.g1, first.g2)):
            if g.tooth_thickness(g.ra) <= 0:
                out.append((f"gear {i + 1} (z = {g.z}, x = {g.x:g}) has a pointed tip: the "
                            f"flanks meet at r = {g.pointed_radius / sc:.4f} {u} below "
                            f"ra = {g.ra / sc:.4f} {u}" + pointed_tip_note(g), p.forbid_pointed))
        for pr in solution:
            where = f"a' = {pr.a_w / sc:.3f} {u}"
            eps = pr.epsilon_alpha
            if eps < 1:
                out.append((f"{where}: contact ratio εα = {eps:.3f} < 1, the mesh is "
                            f"not continuous (a' differs from a = {pr.a / sc:.3f} {u} by "
                            f"{(pr.a_w - pr.a) / sc:+.3f} {u})", p.require_continuous))
            if pr.interference:
                n, (r2, r1) = pr.line_of_action, pr.tip_reach
                if pr.g2.internal:
                    which = (f"the ring's tip stops {(n - r2) / sc:.4f} {u} short of the end N1 "
                             "of the line of action: it meets the pinion below its base circle")
                else:
                    which = "; ".join(
                        f"the tip of gear {i} passes the end N{3 - i} of the line of action "
                        f"by {(r - n) / sc:.4f} {u}" for i, r in ((1, r1), (2, r2)) if r > n)
                out.append((f"{where}: interference — {which} (N1N2 = {n / sc:.3f} {u})",
                            p.forbid_interference))
            for i, c in enumerate(pr.clearances):
                if c < 0:
                    out.append((f"{where}: tip of gear {i + 1} hits the root of the other "
                                f"(clearance {c / sc:.3f} {u})", p.forbid_interference))
    return out


def pointed_tip_note(g):
    """How the mesh of a pair treats a gear's pointed tip (``[pair] tip``)."""
    if getattr(g, "nominal_tip", False):
        return ('; tip = "nominal": the contact ratio, tip reach and mesh take the nominal tip '
                "circle ra (the teeth cannot reach it)")
    return ('; the contact ratio, tip reach and mesh end where the flanks meet '
            '(tip = "nominal" takes ra as some books do)')


def _measures_of(spec, solution):
    """(label, GearMeasures) of every measured gear of a solution."""
    if spec.kind == "spur":
        return [("the gear", solution["measures"])]
    if spec.kind in ("pair", "helical"):
        return [(f"gear {i}", m) for i, m in enumerate(solution.measures, start=1)
                if m is not None]
    return []


def measurement_warnings(spec, solution):
    """Where a span or a pin would not touch the involute flanks, or a pin would not
    stand out of the tips, or a helical gear is too narrow for the span."""
    u, sc = spec.header.unit, spec.header.scale
    out = []
    for label, m in _measures_of(spec, solution):
        f, sp, pin = m.form, m.span, m.pins
        da = 2 * f.ra
        if not f.db <= sp.d_contact <= da:
            out.append(f"{label}: the span over k = {sp.k} teeth touches the flanks on "
                       f"d = {sp.d_contact / sc:.4f} {u}, outside the involute "
                       f"(db = {f.db / sc:.4f} … da = {da / sc:.4f} {u}); give another k")
        if not f.db <= pin.d_contact <= da:
            out.append(f"{label}: a pin of {pin.dp / sc:.4f} {u} touches the flanks on "
                       f"d = {pin.d_contact / sc:.4f} {u}, outside the involute "
                       f"(db = {f.db / sc:.4f} … da = {da / sc:.4f} {u}); give pin_diameter")
        elif pin.d_centre / 2 + pin.dp / 2 <= f.ra:
            out.append(f"{label}: a pin of {pin.dp / sc:.4f} {u} does not stand out of the "
                       f"tip circle (da = {da / sc:.4f} {u}): a larger pin is needed to "
                       "measure over it")
        if spec.kind == "helical" and spec.problem.b is not None and sp.b_min > spec.problem.b:
            out.append(f"{label}: the span needs a face width of at least "
                       f"{sp.b_min / sc:.4f} {u} (W sin beta_b), b = {spec.problem.b / sc:g}")
    return out


def measurement_results(m, sfx, L):
    """JSON results of one gear's measurements (:class:`GearMeasures`), names + *sfx*."""
    return {f"s_chord{sfx}": L(m.s_chord), f"h_chord{sfx}": L(m.h_chord),
            f"k{sfx}": m.span.k, f"W{sfx}": L(m.span.W), f"d_W{sfx}": L(m.span.d_contact),
            f"dp{sfx}": L(m.pins.dp), f"M{sfx}": L(m.pins.M), f"d_M{sfx}": L(m.pins.d_centre),
            f"d_pin{sfx}": L(m.pins.d_contact), f"allowance{sfx}": L(m.form.allowance),
            f"s_n{sfx}": L(m.form.s_n)}


def measurement_rows(m, sfx, f3, helical=False, lang="en"):
    """Report rows (label, symbol, text) of one gear's measurements."""
    kind = "helical" if helical else "spur"    # a helical gear's measures are normal ones
    on = say(lang, "gear.touching_on")
    rows = [
        (f"gear.thickness_allowance_{kind}", f"s{sfx} - E{sfx}",
         f"{f3(m.form.s_n)} (E = {f3(m.form.allowance)})"),
        (f"gear.chordal_{kind}", f"s̄{sfx}, h̄{sfx}", f"{f3(m.s_chord)}, {f3(m.h_chord)}"),
        (f"gear.span_{kind}", f"W{sfx} (k)",
         f"{f3(m.span.W)} (k = {m.span.k}, {on} d = {f3(m.span.d_contact)})"),
        (f"gear.pins_{kind}", f"M{sfx} (dp)", f"{f3(m.pins.M)} (dp = {f3(m.pins.dp)}, {on} "
                         f"d = {f3(m.pins.d_contact)})"),
    ]
    if helical:
        rows.append(("gear.face_width_for_span", f"b_min{sfx}",
                     f3(m.span.b_min)))
    return rows


def generating_results(gs, x="x", sfx=""):
    """JSON results of a gear's generating profile shift (:class:`GeneratingShift`):
    ``x_E<sfx>`` (ISO 21771's sin form) and ``x_E_tan<sfx>`` (the tan form); *x* is the
    shift's own name (``xn`` for a helical gear)."""
    return {f"{x}_E{sfx}": gs.x_E + 0.0, f"{x}_E_tan{sfx}": gs.x_E_tan + 0.0}


def generating_row(gs, x="x", sfx=""):
    """The report row (label, symbol, text) of a gear's shift and its generating
    shifts: 'x1 → x_E1 = 0.3000 → 0.2904, 0.2904' (the sin form, then the tan form)."""
    return ("gear.generating_shift",
            f"{x}{sfx} → {x}_E{sfx}", f"{_num4(gs.x)} → {_num4(gs.x_E)}, {_num4(gs.x_E_tan)}")


def root_factor_results(sh):
    """JSON results of the root factors of a shift design split for equal strength."""
    out = {}
    for i, f in enumerate(sh.factors, start=1):
        out.update({f"Y_Fa{i}": f.Y_Fa, f"Y_Sa{i}": f.Y_Sa})
    return out


def _num4(v):
    """A shift to 4 decimals, never '-0.0000'."""
    return f"{0.0 if abs(v) < 5e-5 else v:.4f}"


def shift_text(sh):
    """'0.4066 = 0.4369 + (-0.0303) (ζ1 = …, ζ2 = …; Y_Fa1 Y_Sa1 = …)' of a shift design;
    ζ 'undefined' at a root that a tip passing N reaches below its base circle."""
    z = [("undefined (interference)" if v is None else f"{v:.3f}")
         for v in (sh.zeta1, sh.zeta2)]
    x2 = _num4(sh.x2)
    return (f"{_num4(sh.x_sum)} = {_num4(sh.x1)} + {f'({x2})' if x2.startswith('-') else x2} "
            f"(ζ1 = {z[0]}, ζ2 = {z[1]}" + root_factor_text(sh) + ")")


def root_factor_text(sh):
    """' (Y_Fa·Y_Sa = …, …)' of a strength split, '' otherwise."""
    if not sh.factors:
        return ""
    f1, f2 = sh.factors
    return (f"; Y_Fa1 Y_Sa1 = {f1.Y_Fa:.3f}·{f1.Y_Sa:.3f} = {f1.Y_FaSa:.4f}, "
            f"Y_Fa2 Y_Sa2 = {f2.Y_Fa:.3f}·{f2.Y_Sa:.3f} = {f2.Y_FaSa:.4f}")


def loads_results(ld, drive=None):
    """JSON results of a pair's tooth loads (:class:`~mechcli.core.gear.loads.ToothLoads`):
    SI values, every name with its unit; power and speed as the spec's *drive* gives them
    (not a round trip through W and rad/s: 960 rpm stays 960)."""
    rpm = 30 / math.pi
    p_kw = getattr(drive, "power_kW", None) or ld.power / 1e3
    n1 = getattr(drive, "n1_rpm", None) or ld.omega1 * rpm
    out = {"power_kW": p_kw, "n1_rpm": n1, "n2_rpm": n1 * (ld.omega2 / ld.omega1),
           "T1_N_m": ld.T1, "T2_N_m": ld.T2, "v_m_s": ld.v,
           "Ft1_N": ld.Ft1, "Fr1_N": ld.Fr1, "Fa1_N": ld.Fa1,
           "Ft2_N": ld.Ft2, "Fr2_N": ld.Fr2, "Fa2_N": ld.Fa2, "Fn_N": ld.Fn,
           "efficiency": ld.efficiency, "P2_kW": ld.power_out / 1e3}
    return out


def worm_efficiency_results(eff, mu):
    """JSON results of a worm's efficiency (eta, eta', phi) with the friction *mu*."""
    eta, eta_rev, phi = eff
    # self-locking (eta' <= 0): the wheel cannot drive the worm at all; its efficiency is
    # 0, not the formula's negative value
    return {"mu": mu, "friction_angle_deg": math.degrees(phi), "efficiency": eta,
            "efficiency_reverse": max(eta_rev, 0.0), "self_locking": eta_rev <= 0}


def loads_rows(ld, f3):
    """Report rows (label, symbol, text) of a pair's tooth loads; *f3* words a length."""
    rpm = 30 / math.pi
    speed = {"spur": "gear.speed_pitch_circle", "helical": "gear.speed_pitch_circle",
             "bevel": "gear.speed_mean_cone", "worm": "gear.speed_worm"}[ld.kind]
    rows = [
        ("gear.power_speeds", "P1, n1, n2",
         f"{ld.power / 1e3:.4g} kW, {ld.omega1 * rpm:.4g} rpm, {ld.omega2 * rpm:.4g} rpm"),
        ("gear.torques", "T1, T2",
         f"{ld.T1:.4g} N·m, {ld.T2:.4g} N·m"),
        (speed, "v",
         f"{ld.v:.4g} m/s (d = {f3(ld.d_force1)})"),
        ("gear.forces_gear_1", "Ft1, Fr1, Fa1", f"{ld.Ft1:.4g} N, {ld.Fr1:.4g} N, {ld.Fa1:.4g} N"),
        ("gear.forces_gear_2", "Ft2, Fr2, Fa2", f"{ld.Ft2:.4g} N, {ld.Fr2:.4g} N, {ld.Fa2:.4g} N"),
        ("gear.normal_tooth_force", "Fn", f"{ld.Fn:.4g} N"),
    ]
    if ld.kind == "bevel":
        rows.insert(3, ("gear.mean_diameters", "dm1, dm2",
                        f"{f3(ld.d_force1)}, {f3(ld.d_force2)}"))
    return rows


def worm_efficiency_rows(eff, mu, ld=None, lang="en"):
    """Report rows (label, symbol, text) of a worm's efficiency and self-locking (η' shown
    as 0 when the wheel cannot drive)."""
    eta, eta_rev, phi = eff
    rows = [("gear.friction", "μ, φv",
             f"{mu:.4g}, {math.degrees(phi):.4f}°"),
            ("gear.efficiency_worm", "η = tanγ/tan(γ+φv)",
             f"{eta:.4f}"),
            ("gear.efficiency_wheel", "η' = tan(γ-φv)/tanγ",
             f"{max(eta_rev, 0.0):.4f}"
             + (say(lang, "gear.self_locking") if eta_rev <= 0 else ""))]
    if ld is not None:
        rows.append(("gear.sliding_speed", "vs = v1/cosγ",
                     f"{ld.sliding_velocity:.4g} m/s"))
    return rows


def enforce(spec, solution):
    """Raise :class:`RequirementError` on the first forbidden finding; return all messages."""
    found = findings(spec, solution)
    for message, forbidden in found:
        if forbidden:
            raise RequirementError(message)
    return [m for m, _ in found]


#: reason of a core GearError -> its text from the error's values (lengths in m, angles in rad)
_ERROR_TEXT = {
    "ring_tip_inside_base": lambda v: (
        f"internal gear z = {v['z']}: tip circle da = {v['da']:.6g} m is inside the base "
        f"circle db = {v['db']:.6g} m (needs z (1 - cos alpha) >= 2 (ha* + x), "
        f"z >= {v['z_needed']:.1f})"),
    "tip_inside_base": lambda v: (
        f"tip circle da = {v['da']:.6g} m is inside the base circle db = {v['db']:.6g} m "
        f"(z = {v['z']}, x = {v['x']:g}): the teeth have no involute"),
    "root_below_centre": lambda v: (
        f"root diameter df = {v['df']:.4g} m would be <= 0 (z = {v['z']}, x = {v['x']:g}): "
        "too few teeth for this shift"),
    "base_circles_overlap": lambda v: (
        f"centre distance {v['a_w']:g} m is below rb1 + rb2 = {v['limit']:g} m: the base "
        "circles overlap"),
    "teeth_not_whole": lambda v: (
        f"2 a'/m = {v['total']:.6g} is not a whole number of teeth: a standard pair needs "
        f"a' = m (z1 + z2) / 2, e.g. {v['below']:g} m or {v['above']:g} m"),
    "jam": lambda v: (
        f"centre distance {v['a_w']:.6g} m is {'above' if v['internal'] else 'below'} the "
        f"zero-backlash distance {v['a0']:.6g} m"
        + (" of the internal pair" if v["internal"] else "") + ": the teeth would jam"),
    "no_contact": lambda v: (
        f"at a' = {v['a_w']:.6g} m the tip circles do not reach the line of action "
        f"(εα = {v['epsilon']:.3g}): no contact"),
    "helical_centre_distance": lambda v: (
        f"a' = {v['a_w']:g} m is below mn (z1 + z2) / 2 = {v['limit']:g} m: no helix angle "
        "fits"),
    "helix_angle": lambda v: f"helix angle {math.degrees(v['beta']):.4g} deg is 45 deg or more",
    "pin_too_small": lambda v: (
        f"a pin of {v['dp']:.6g} m falls into the space below the base circle "
        f"(z = {v['z']}): a larger pin is needed"),
    "helical_shift_sum": lambda v: (
        f"xn1 + xn2 = {v['x_sum']:g} is so negative that no zero-backlash mesh exists"),
    "no_drive": lambda v: (
        f"lead angle {math.degrees(v['gamma']):.4g} deg + friction angle "
        f"{math.degrees(v['phi']):.4g} deg >= 90 deg: the worm cannot drive the wheel "
        "(efficiency <= 0)"),
    "bevel_face": lambda v: (
        f"face width {v['b']:.6g} m is not below the cone distance R = {v['R']:.6g} m"),
    "both_given": lambda v: "give a_w or alpha_w, not both",
    "root_factors": lambda v: (
        f"no {math.degrees(v['angle']):.0f}-degree tangent on the root fillet" if "angle" in v
        else "the tooth has no root section"),
    "crown_bevel": lambda v: (
        f"pitch-cone angles {math.degrees(v['delta1']):.3f}° and "
        f"{math.degrees(v['delta2']):.3f}°: a cone of 90° or more is a crown or internal bevel "
        "gear, which is not handled"),
}


def error_message(exc):
    """The user's text of a core ``GearError`` (lengths in metres as the core works)."""
    word = _ERROR_TEXT.get(getattr(exc, "reason", ""))
    return str(exc) if word is None else word(exc.values)


def mounting_error(spec, exc):
    """``(key, expected, got)`` of a pair's mounting the core refused (MeshError reason
    ``"mounting"``, :func:`mechcli.core.gear.pair.check_mountings`): the command
    raises it as the spec error of that key (exit 2), in the spec's length unit."""
    p, sc, v = spec.problem, spec.header.scale, exc.values
    kind = spec.kind
    if v["given"] == "x_split":
        if v["what"] == "base":
            return (p.a_w_keys[0], f"a centre distance above rb1 + rb2 = {v['a0'] / sc:.6g} "
                    "(no profile-shift sum gives a smaller one)", f"{v['a_w'] / sc:g}")
        if v["what"] == "sliding":
            return (f"{kind}.x_split", "a split rule that has a solution: no x1 in [-1.5, 1.5] "
                    f"balances the specific sliding for x1 + x2 = {v['x_sum']:.4f}",
                    '"sliding"')
        if v["what"] == "sum_range":
            return (p.a_w_keys[0] if kind == "pair" else f"{kind}.a_w",
                    "a centre distance whose shift sum x1 + x2 lies in [-3, 3] (two shifts in "
                    f"[-1.5, 1.5]): this one needs {v['x_sum']:.4f}", f"{v['a_w'] / sc:g}")
        if v["what"] == "strength":
            return (f"{kind}.x_split", "a split rule that has a solution: no x1 in [-1.5, 1.5] "
                    f"gives both gears the same Y_Fa Y_Sa for x1 + x2 = {v['x_sum']:.4f}",
                    '"strength"')
        if v["what"] == "strength_rejected":
            why = "; ".join(f"x1 = {x1:.4f}: {split_refusal(w, sc, spec.header.unit)}"
                            for x1, w in v["splits"])
            return (f"{kind}.x_split", "a split rule that has a usable solution: every x1 "
                    f"giving both gears the same Y_Fa Y_Sa for x1 + x2 = {v['x_sum']:.4f} "
                    "makes an unusable pair", f'"strength" ({why})')
        x = "xn" if kind == "helical" else "x"
        if p.x_split != "x1":
            return (f"{kind}.x_split", f"a split leaving both shifts in [-1.5, 1.5] "
                    f"({x}1 + {x}2 = {v['x_sum']:.4f} for a_w)",
                    f'"{p.x_split}" ({x}1 = {v["x1"]:.4f}, {x}2 = {v["x2"]:.4f})')
        return (f"{kind}.{x}1", f"{x}1 leaving {x}2 = {v['x_sum']:.4f} - {x}1 in [-1.5, 1.5] "
                f"({x}1 + {x}2 = {v['x_sum']:.4f} for a_w)",
                f"{v['x1']:g} ({x}2 = {v['x2']:.4f})")
    if v["given"] == "backlash":
        if v["what"] == "below":
            return (f"{kind}.backlash", "a backlash at least that of the nominal teeth at this "
                    f"mounting, {v['j0'] / sc:.6g}", f"{v['j'] / sc:g}")
        return (f"{kind}.backlash", "a backlash whose allowance leaves a tooth: "
                f"E = {v['allowance'] / sc:.6g} >= s = {v['s'] / sc:.6g} (z = {v['z']})",
                f"{v['j'] / sc:g}")
    a, a0 = v["a_w"], v["a0"]
    if v["given"] == "alpha_w":
        return (p.alpha_w_keys[v["index"]], "an operating pressure angle giving a' "
                f"{'<=' if v['internal'] else '>='} {a0 / sc:.6g}",
                f"{math.degrees(v['alpha_w']):g} (a' = {a / sc:.6g})")
    if v["internal"]:
        expected = (f"a centre distance in ({v['lo'] / sc:.6g}, {a0 / sc:.6g}] for this "
                    "internal pair (larger jams the teeth)")
    else:
        bound = ("the base circles rb1 + rb2; these thin teeth never jam" if v["thin"]
                 else "zero backlash; smaller jams the teeth")
        expected = f"a centre distance >= {a0 / sc:.6g} ({bound})"
    return p.a_w_keys[v["index"]], expected, f"{a / sc:g}"


def split_refusal(why, sc, u):
    """Words of why a designed split is no usable pair (``problems._unusable``)."""
    w = why["what"]
    if w == "undercut":
        return (f"gear {why['gear']} (z = {why['z']}) is undercut, x = {why['x']:.4f} < "
                f"x_min = {why['x_min']:.4f}")
    if w == "pointed":
        return f"gear {why['gear']} (z = {why['z']}, x = {why['x']:.4f}) has a pointed tip"
    if w == "interference":
        i = why["gear"]
        return (f"interference, the tip of gear {i} (x = {why['x']:.4f}) passes the end N{3 - i} "
                f"of the line of action by {why['excess'] / sc:.4g} {u}")
    return why.get("text", w)


def _word(lang, word):
    """A row's label: a catalogue key (``"gear.module"``), or ``(key, fields)``."""
    key, fields = (word, {}) if isinstance(word, str) else word
    return say(lang, key, **fields)


def _suffix(k):
    return "" if k == 0 else f"_{k + 1}"


def _kv_block(heading, rows, lang):
    """rows: (label, symbol, text) -> Block of [label, 'symbol = text'] (label: see _word)."""
    return Block(heading, [], [[_word(lang, w), f"{sym} = {txt}"] for w, sym, txt in rows])


# -- involute (【例 5-1】) -----------------------------------------------------------
def present_involute(spec, sol, run, outputs):
    p, u, sc = spec.problem, spec.header.unit, spec.header.scale
    lang = run.lang
    rows, ang, inv = sol["table"]
    ang_flat = [a for line in ang for a in line]
    inv_flat = [v for line in inv for v in line]
    results = {}
    for a, v in zip(ang_flat, inv_flat):
        whole, tenth = divmod(int(round(a * 10)), 10)
        key = f"inv_{whole}_{tenth}" if abs(a * 10 - round(a * 10)) < 1e-6 \
            else "inv_" + f"{a:.6g}".replace(".", "_")
        results[key] = float(v)
    r, th, x, y = sol["curve"]
    results.update({"rb": p.rb / sc, "alpha_max_deg": math.degrees(p.alpha_max),
                    "theta_max_rad": float(th[-1]), "r_max": float(r[-1] / sc),
                    "x_max": float(x[-1] / sc), "y_max": float(y[-1] / sc)})
    outputs.text("involute.csv", csv_text([("alpha_deg", ang_flat), ("inv_alpha_rad", inv_flat)],
                                          outputs.digits))
    outputs.text("curve.csv", csv_text([
        ("alpha_K_deg", [math.degrees(a) for a in sol["alpha"]]),
        (f"r_K_{u}", [v / sc for v in r]), ("theta_K_rad", th),
        (f"x_{u}", [v / sc for v in x]), (f"y_{u}", [v / sc for v in y])], outputs.digits))
    cols = [f"{k * p.table_step_deg:.1f}" for k in range(p.columns)]
    table = Block(say(lang, "gear.table_5_1"),
                  [unit_header("α", "°", say(lang, "gear.alpha_name"))] + cols,
                  [[f"{row:.4f}"] + [f"{v:.{p.digits}f}" for v in line]
                   for row, line in zip(rows, inv)])
    curve = _kv_block(say(lang, "gear.involute_curve"), [
        ("gear.base_radius", "rb", f"{p.rb / sc:.3f} {u}"),
        ("gear.pressure_angle_range", "αK",
         f"0 … {math.degrees(p.alpha_max):g}°"),
        ("gear.end_point_radius", "r_K", f"{r[-1] / sc:.3f} {u}"),
        ("gear.end_point_roll_angle", "θK", f"{th[-1]:.6f} rad"),
        ("gear.end_point", "(x, y)", f"({x[-1] / sc:.3f}, {y[-1] / sc:.3f}) {u}"),
    ], lang)
    report = Report(spec.header.title, [table, curve])
    if run.plot:
        import numpy as np

        from mechcli.report import gear_plots
        curve = tuple(np.asarray(c) for c in sol["curve"])
        gear_plots.plot_involute({**sol, "curve": curve}, spec, run, outputs)
    return report, results, []


# -- inverse involute (【例 5-2】) -----------------------------------------------------
def present_inverse_involute(spec, sol, run, outputs):
    from mechcli.core.gear.involute import degrees_minutes_seconds, format_dms
    p, lang = spec.problem, run.lang
    results, warnings, blocks = {}, [], []
    for k, (th, a, it, res) in enumerate(zip(sol.theta, sol.alpha, sol.iterations,
                                             sol.residual)):
        sfx = _suffix(k)
        dms = format_dms(a, p.dms_seconds_digits, p.dms_rounding)
        d, mnt, s = degrees_minutes_seconds(a, p.dms_seconds_digits, p.dms_rounding)
        rel = abs(res) / th if th > 0 else 0.0
        results.update({f"theta{sfx}": float(th), f"alpha_rad{sfx}": float(a),
                        f"alpha_deg{sfx}": math.degrees(a), f"alpha_dms{sfx}": dms,
                        f"iterations{sfx}": int(it), f"residual{sfx}": float(res),
                        f"relative_residual{sfx}": float(rel)})
        sec = f"{s:.{p.dms_seconds_digits}f}" if p.dms_seconds_digits else f"{int(s)}"
        blocks.append(Block("", [], [
            [say(lang, "gear.involute_function"), f"θ = {th:g}"],
            [say(lang, "gear.involute_pressure_angle"),
             f"α = {a:8.7f} " + say(lang, "gear.rad")],
            [say(lang, "gear.in_dms"),
             say(lang, "gear.dms", d=d, mnt=mnt, sec=sec, dms=str(dms))],
            [say(lang, "gear.newton_iterations"),
             f"{it} (" + (say(lang, "gear.book_start", start=f"{p.start:g}",
                              epsilon=f"{p.epsilon:g}") if p.method == "book"
                          else say(lang, "gear.auto_start")) + ")"],
            [say(lang, "gear.residual"), f"{res:.3e}"],
        ]))
        if p.method == "book" and rel > 1e-6:
            warnings.append(f"theta = {th:g}: the book's absolute stop |f| < {p.epsilon:g} "
                            f"leaves a relative error of {rel:.2g} in inv(alpha); "
                            "use method = \"auto\"")
    outputs.text("involute.csv", csv_text([
        ("theta_rad", sol.theta), ("alpha_rad", sol.alpha),
        ("alpha_deg", [math.degrees(a) for a in sol.alpha]),
        ("iterations", sol.iterations), ("residual_rad", sol.residual)],
        digits=17))   # the inverse involute is always written round-trip exact
    return Report(spec.header.title, blocks), results, warnings


# -- one spur gear (【例 5-3】, 习题 5-1) ---------------------------------------------
def present_spur(spec, sol, run, outputs):
    p, u, sc, lang = spec.problem, spec.header.unit, spec.header.scale, run.lang
    g, tooth, outline = sol["gear"], sol["tooth"], sol["outline"]
    warnings = []
    pointed = g.tooth_thickness(g.ra) <= 0
    s_a, s_b = g.tooth_thickness(g.ra), g.tooth_thickness(g.rb)
    L = lambda v: float(v / sc)  # noqa: E731
    results = {"z": g.z, "m": L(g.m), "alpha_deg": math.degrees(g.alpha), "x": g.x,
               "d": L(g.d), "db": L(g.db), "da": L(g.da), "df": L(g.df), "p": L(g.p),
               "pb": L(g.pb), "s": L(g.s), "e": L(g.e), "h": L(g.h), "ha": L(g.ha),
               "hf": L(g.hf), "c": L(g.c), "alpha_a_deg": math.degrees(g.alpha_a),
               "s_a": L(s_a), "e_a": L(g.space_width(g.ra)), "s_b": L(s_b),
               "e_b": L(g.space_width(g.rb)), "r_pointed": L(g.pointed_radius),
               "z_min": g.z_min, "x_min": g.x_min, "undercut": bool(g.undercut),
               "pointed": bool(pointed), "r_form": L(tooth.r_form),
               "undercut_generated": tooth.undercut,
               "undercut_fraction": tooth.undercut_fraction,
               "undercut_depth": L(tooth.r_form - g.rb) if tooth.undercut else 0.0,
               "undercut_margin": g.x - g.x_min,
               "profile_points": int(outline.x.size)}
    for k, r in enumerate(p.radii):
        results[f"s_r{k + 1}"] = L(g.tooth_thickness(r))
        results[f"e_r{k + 1}"] = L(g.space_width(r))
    ms = sol["measures"]
    gen = sol.get("generating")
    if gen is not None:
        results.update(generating_results(gen))
    results.update(measurement_results(ms, "", L))
    for k, (sc_r, hc_r) in enumerate(ms.radii):
        results[f"s_chord_r{k + 1}"] = L(sc_r)
        results[f"h_chord_r{k + 1}"] = L(hc_r)
    f3 = lambda v: f"{v / sc:.3f} {u}"  # noqa: E731
    rows = [
        ("gear.number_of_teeth", "z", f"{g.z}"),
        ("gear.module", "m", f3(g.m)),
        ("gear.pressure_angle", "α", f"{math.degrees(g.alpha):.3f}°"),
        ("gear.profile_shift_coefficient", "x", f"{g.x:.4f}"),
        *([] if gen is None else [generating_row(gen)]),
        ("gear.reference_diameter", "d", f3(g.d)),
        ("gear.base_diameter", "db", f3(g.db)),
        ("gear.tip_diameter", "da", f3(g.da)),
        ("gear.root_diameter", "df", f3(g.df)),
        ("gear.addendum", "ha", f3(g.ha)),
        ("gear.dedendum", "hf", f3(g.hf)),
        ("gear.whole_depth", "h", f3(g.h)),
        ("gear.pitch", "p", f3(g.p)),
        ("gear.base_pitch", "pb", f3(g.pb)),
        ("gear.tooth_thickness", "s", f3(g.s)),
        ("gear.space_width", "e", f3(g.e)),
        ("gear.tip_pressure_angle", "αa", f"{math.degrees(g.alpha_a):.3f}°"),
        ("gear.tooth_thickness_at_tip", "sa", f3(s_a)),
        ("gear.space_width_at_tip", "ea", f3(g.space_width(g.ra))),
        ("gear.tooth_thickness_at_base_circle", "sb", f3(s_b)),
        ("gear.space_width_at_base_circle", "eb", f3(g.space_width(g.rb))),
        ("gear.radius_of_the_pointed_tip", "rp", f3(g.pointed_radius)),
        ("gear.fewest_teeth_without_undercut", "zmin", f"{g.z_min:.3f}"),
        ("gear.least_shift_against_undercut", "xmin", f"{g.x_min:.4f}"),
        *undercut_rows(g, tooth, sc, u, lang),
    ]
    for k, r in enumerate(p.radii):
        rows.append((("gear.thickness_at_r", {"r": f"{r / sc:g}"}), f"s_r{k + 1}",
                     f3(g.tooth_thickness(r))))
    rows += measurement_rows(ms, "", f3, lang=lang)
    for k, (r, (sc_r, hc_r)) in enumerate(zip(p.radii, ms.radii)):
        rows.append((("gear.chordal_at_r", {"r": f"{r / sc:g}"}),
                     f"s̄_r{k + 1}, h̄_r{k + 1}", f"{f3(sc_r)}, {f3(hc_r)}"))
    report = Report(spec.header.title,
                    [_kv_block(say(lang, "gear.spur_geometry"), rows,
                               lang)])
    outputs.csv("gear.csv", [(f"x_{u}", outline.x / sc), (f"y_{u}", outline.y / sc)])
    if run.plot:
        from mechcli.report import gear_plots
        gear_plots.plot_gear(sol, spec, run, outputs)
    return report, results, warnings


# -- a pair (【例 5-4】, 习题 5-2 … 5-5) ----------------------------------------------
def _pair_results(p, pairs, L):
    """The JSON results of a spur pair that do not change with the mounting (the gears, the
    shift design, the generating shifts, the measurements, the loads)."""
    first = pairs[0]
    g1, g2 = first.g1, first.g2
    results = {"z1": g1.z, "z2": g2.z, "m": L(g1.m), "i12": first.ratio, "a": L(first.a),
               "d1": L(g1.d), "d2": L(g2.d), "db1": L(g1.db), "db2": L(g2.db),
               "da1": L(g1.da), "da2": L(g2.da), "df1": L(g1.df), "df2": L(g2.df),
               "ha1": L(g1.ha), "ha2": L(g2.ha), "hf1": L(g1.hf), "hf2": L(g2.hf),
               "h1": L(g1.h), "h2": L(g2.h), "p": L(g1.p), "pb1": L(g1.pb), "pb2": L(g2.pb),
               "s1": L(g1.s), "s2": L(g2.s), "e1": L(g1.e), "e2": L(g2.e), "c": L(g1.c),
               "alpha_a1_deg": math.degrees(g1.alpha_a),
               "alpha_a2_deg": math.degrees(g2.alpha_a),
               "internal": g2.internal, "x1": g1.x, "x2": g2.x,
               "tip": "nominal" if g1.nominal_tip else "effective"}
    for i, gen in enumerate(pairs.generating, start=1):
        if gen is not None:
            results.update(generating_results(gen, sfx=str(i)))
    for i, m in enumerate(pairs.measures, start=1):
        if m is not None:
            results.update(measurement_results(m, str(i), L))
    if pairs.shift is not None:
        results.update({"x_sum": pairs.shift.x_sum + 0.0, "zeta1": pairs.shift.zeta1,
                        "zeta2": pairs.shift.zeta2})
        results.update(root_factor_results(pairs.shift))
    if pairs.loads is not None:
        results.update(loads_results(pairs.loads, p.drive))
    a0 = first.a_zero_backlash
    if a0 is not None:   # None: teeth so thin that no a' jams
        results["a_zero_backlash"] = L(a0)
    return results


def _mounting_results(pairs, k, sc):
    """The JSON results of mounting *k* (suffix ``_2``, … after the first) and its CSV row."""
    pr, sfx, g2 = pairs[k], _suffix(k), pairs[0].g2
    L = lambda v: float(v / sc)  # noqa: E731
    eps, cl = pr.epsilon_alpha, pr.clearances
    results = {f"a_w{sfx}": L(pr.a_w), f"alpha_w_deg{sfx}": math.degrees(pr.alpha_w),
               f"dw1{sfx}": L(pr.dw1), f"dw2{sfx}": L(pr.dw2),
               f"epsilon_alpha{sfx}": eps,
               f"backlash{sfx}": L(pairs.backlash[k][0]),
               f"backlash_n{sfx}": L(pairs.backlash[k][1]),
               f"clearance1{sfx}": L(cl[0]), f"clearance2{sfx}": L(cl[1]),
               f"interference{sfx}": pr.interference,
               f"y{sfx}": pr.y, f"delta_y{sfx}": pr.delta_y if not g2.internal else 0.0,
               f"continuous{sfx}": eps >= 1}
    row = [pr.a_w / sc, math.degrees(pr.alpha_w), pr.dw1 / sc, pr.dw2 / sc, eps,
           pairs.backlash[k][0] / sc, cl[0] / sc, cl[1] / sc]
    return results, row


def _pair_rows(pairs, k, sc, u, lang):
    """The geometry rows of mounting *k* (in Chinese 【例 5-4】's printout line for line:
    its MATLAB names, lengths as "250.000mm")."""
    pr, g1, g2 = pairs[k], pairs[0].g1, pairs[0].g2
    f3 = lambda v: say(lang, "gear.pair_length", value=f"{v / sc:.3f}", unit=u)  # noqa: E731
    return [
        ("gear.standard_centre_distance", "a", f3(pr.a)),
        ("gear.operating_centre_distance", say(lang, "gear.pair_a_w"), f3(pr.a_w)),
        ("gear.pinion_reference_diameter", "d1", f3(g1.d)),
        ("gear.wheel_reference_diameter", "d2", f3(g2.d)),
        ("gear.pinion_base_diameter", "db1", f3(g1.db)),
        ("gear.wheel_base_diameter", "db2", f3(g2.db)),
        ("gear.pinion_tip_diameter", "da1", f3(g1.da)),
        ("gear.wheel_tip_diameter", "da2", f3(g2.da)),
        ("gear.pinion_root_diameter", "df1", f3(g1.df)),
        ("gear.wheel_root_diameter", "df2", f3(g2.df)),
        ("gear.pinion_tip_pressure_angle", say(lang, "gear.pair_alpha_a1"),
         f"{math.degrees(g1.alpha_a):.3f}°"),
        ("gear.wheel_tip_pressure_angle", say(lang, "gear.pair_alpha_a2"),
         f"{math.degrees(g2.alpha_a):.3f}°"),
        ("gear.operating_pressure_angle", say(lang, "gear.pair_alpha_w"),
         f"{math.degrees(pr.alpha_w):.3f}°"),
        ("gear.contact_ratio", say(lang, "gear.pair_epsilon"), f"{pr.epsilon_alpha:.3f}"),
    ]


def _pair_extra(p, pairs, k, sc_u, lang):
    """The rows below mounting *k*'s geometry: its pitch circles, backlash, clearances; after
    the first mounting also the shift design, generating shifts, measurements, loads and
    where the contact ends."""
    pr, (g1, g2), (sc, u) = pairs[k], (pairs[0].g1, pairs[0].g2), sc_u
    f3 = lambda v: f"{v / sc:.3f} {u}"  # noqa: E731
    cl, a0 = pr.clearances, pairs[0].a_zero_backlash
    extra = [
        ("gear.operating_pitch_diameters", "d1', d2'",
         f"{pr.dw1 / sc:.3f} {u}, {pr.dw2 / sc:.3f} {u}"),
        ("gear.backlash", "j, jn",
         f"{f3(pairs.backlash[k][0])}, {f3(pairs.backlash[k][1])}"),
        ("gear.tip_clearances", "c1', c2'", f"{cl[0] / sc:.3f} {u}, {cl[1] / sc:.3f} {u}"),
        ("gear.zero_backlash_a", "a0'",
         f3(a0) if a0 is not None else say(lang, "gear.no_zero_backlash")),
        ("gear.y_delta_y", "y, Δy", f"{pr.y:.4f}, {pr.delta_y if not g2.internal else 0.0:.4f}"
         + (" (tips shortened)" if p.tip_shortening and pr.delta_y > 1e-12 else "")),
        ("gear.base_pitches", "pb1, pb2", f"{g1.pb / sc:.3f} {u}, {g2.pb / sc:.3f} {u}"),
        ("gear.ratio", "i12", f"{pr.ratio:.4f}"),
    ]
    if k == 0 and (g1.x or g2.x or p.designed or g2.internal):
        extra.insert(0, ("gear.teeth", "z1, z2", f"{g1.z}, {g2.z}"))
    if k == 0 and pairs.shift is not None:
        sh = pairs.shift
        rule = {"x1": "x1 given", "sliding": "balanced specific sliding",
                "strength": "equal Y_Fa Y_Sa"}[sh.rule]
        extra.insert(0, (("gear.shifts", {"rule": rule}), "x1 + x2", shift_text(sh)))
    if k == 0:
        extra += _pair_first_extra(pairs, f3, lang)
    if g2.internal:
        extra.insert(0, ("gear.internal_gear_2", "x2 (ISO: + thickens)",
                         f"{g2.x:g}"))
    return extra


def _pair_first_extra(pairs, f3, lang):
    """The rows only the first mounting shows: generating shifts, measurements, loads and
    where the contact of a pointed (or nominal) tip ends."""
    g1, g2 = pairs[0].g1, pairs[0].g2
    extra = [generating_row(gen, sfx=str(i))
             for i, gen in enumerate(pairs.generating, start=1) if gen is not None]
    for i, m in enumerate(pairs.measures, start=1):
        if m is not None:
            extra += measurement_rows(m, str(i), f3, lang=lang)
    if pairs.loads is not None:
        extra += loads_rows(pairs.loads, f3)
    pointed = [g for g in (g1, g2) if not g.internal and g.tooth_thickness(g.ra) <= 0]
    if pointed or g1.nominal_tip:
        extra.append(("gear.pointed_contact_end", "tip",
                      say(lang, "gear.nominal_tip") if g1.nominal_tip else
                      say(lang, "gear.flanks_meet", radii=", ".join(
                          f"r_p{1 if g is g1 else 2} = {f3(g.pointed_radius)}"
                          for g in pointed))))
    return extra


def present_pair(spec, pairs, run, outputs):
    p, u, sc, lang = spec.problem, spec.header.unit, spec.header.scale, run.lang
    first = pairs[0]
    L = lambda v: float(v / sc)  # noqa: E731
    warnings = []
    results = _pair_results(p, pairs, L)
    blocks = []
    rows_csv = []
    for k in range(len(pairs)):
        mounting, row = _mounting_results(pairs, k, sc)
        results.update(mounting)
        rows_csv.append(row)
        blocks.append(_kv_block(say(lang, "gear.pair_geometry")
                                + ("" if len(pairs) == 1 else f" ({k + 1})"),
                                _pair_rows(pairs, k, sc, u, lang), lang))
        blocks.append(_kv_block("", _pair_extra(p, pairs, k, (sc, u), lang), lang))
    cols = list(zip(*rows_csv))
    names = [f"a_w_{u}", "alpha_w_deg", f"dw1_{u}", f"dw2_{u}", "epsilon_alpha",
             f"backlash_{u}", f"clearance1_{u}", f"clearance2_{u}"]
    # these 8 columns first, then every other result (one row per mounting)
    outputs.text("gear.csv", wide_csv(list(zip(names, cols)), results, u, len(pairs),
                                      outputs.digits))
    animate = p.animate if run.animate is None else run.animate
    if animate and first.g2.internal:
        warnings.append("no mesh animation for internal pairs (pair.png only)")
        animate = False
    _pictures(run, animate, "pair", first, spec, outputs)
    return Report(spec.header.title, blocks), results, warnings


def _pictures(run, animate, kind, solution, spec, outputs):
    """``<kind>.png`` unless --no-plot, and the GIF when asked (gear_plots's
    ``plot_<kind>`` / ``animate_<kind>``; matplotlib imported only here)."""
    if not (run.plot or animate):
        return
    from mechcli.report import gear_plots
    if run.plot:
        getattr(gear_plots, f"plot_{kind}")(solution, spec, run, outputs)
    if animate:
        getattr(gear_plots, f"animate_{kind}")(solution, spec, run, outputs)


# -- generation (gear_cut) ------------------------------------------------------------
def present_generation(spec, sol, run, outputs):
    import numpy as np

    p, u, sc, lang = spec.problem, spec.header.unit, spec.header.scale, run.lang
    L = lambda v: float(v / sc)  # noqa: E731
    results, warnings, blocks, csv_cols = {}, [], [], [[], [], []]
    for k, tooth in enumerate(sol["teeth"]):
        g, sfx = tooth.gear, _suffix(k)
        sb_gen = 2 * g.rb * float(tooth.half_tooth(g.rb)) if g.rb >= g.rf else float("nan")
        x_rack = g.ha_star + g.c_star - g.z * math.sin(g.alpha) ** 2 / 2
        results.update({f"x{sfx}": g.x, f"r{sfx}": L(g.r), f"rb{sfx}": L(g.rb),
                        f"ra{sfx}": L(g.ra), f"rf{sfx}": L(g.rf),
                        f"undercut{sfx}": bool(g.undercut),
                        f"undercut_generated{sfx}": tooth.undercut,
                        f"undercut_margin{sfx}": g.x - g.x_min, f"r_form{sfx}": L(tooth.r_form),
                        f"undercut_depth{sfx}": L(tooth.r_form - g.rb) if tooth.undercut
                        else 0.0,
                        f"undercut_fraction{sfx}": tooth.undercut_fraction,
                        f"s_b{sfx}": L(g.tooth_thickness(g.rb)),
                        f"x_min{sfx}": g.x_min, f"x_min_rack{sfx}": x_rack})
        if math.isfinite(sb_gen):
            results[f"s_b_generated{sfx}"] = L(sb_gen)
        results[f"tip_pointed{sfx}"] = tooth.tip_pointed
        results[f"s_a{sfx}"] = L(max(g.tooth_thickness(g.ra), 0.0))
        if tooth.tip_pointed:
            warnings.append(f"x = {g.x:g}: pointed tip, the flanks meet at r = "
                            f"{g.pointed_radius / sc:.3f} {u} below ra = {g.ra / sc:.3f} {u}")
        if g.undercut:
            warnings.append(undercut_message(g, tooth, sc, u))
        blocks.append(_kv_block(say(lang, "gear.generation", x=f"{g.x:g}"), [
            ("gear.module_teeth_pressure_angle", "m, z, α",
             f"{g.m / sc:g} {u}, {g.z}, {math.degrees(g.alpha):g}°"),
            ("gear.reference_base_radius", "r, rb",
             f"{g.r / sc:.3f}, {g.rb / sc:.3f} {u}"),
            ("gear.tip_root_radius", "ra, rf",
             f"{g.ra / sc:.3f}, {g.rf / sc:.3f} {u}"),
            ("gear.least_shift_ha", "xmin", f"{g.x_min:.4f}"),
            *undercut_rows(g, tooth, sc, u, lang),
            ("gear.least_shift_sharp_cutter", "xmin'",
             f"{x_rack:.4f}"),
        ], lang))
        out = sol["outlines"][k]
        csv_cols[0].append(np.full(out.x.size, k + 1.0))
        csv_cols[1].append(out.x / sc)
        csv_cols[2].append(out.y / sc)
    outputs.csv("gear.csv", [("shift_index", np.concatenate(csv_cols[0])),
                             (f"x_{u}", np.concatenate(csv_cols[1])),
                             (f"y_{u}", np.concatenate(csv_cols[2]))])
    results["positions"] = int(sol["plan"].phi.size)
    _pictures(run, p.animate if run.animate is None else run.animate, "generation", sol, spec,
              outputs)
    return Report(spec.header.title, blocks), results, warnings


# -- helical, worm, bevel (习题 5-6 … 5-9) ------------------------------------------
def present_helical(spec, sol, run, outputs):
    u, sc, lang = spec.header.unit, spec.header.scale, run.lang
    hp = sol.pair
    L = lambda v: float(v / sc)  # noqa: E731
    x1, x2 = hp.xn1, hp.xn2
    results = {"beta_deg": math.degrees(hp.beta), "mt": L(hp.mt),
               "alpha_t_deg": math.degrees(hp.alpha_t), "d1": L(hp.d(hp.z1)),
               "d2": L(hp.d(hp.z2)), "da1": L(hp.da(hp.z1, x1)), "da2": L(hp.da(hp.z2, x2)),
               "df1": L(hp.df(hp.z1, x1)), "df2": L(hp.df(hp.z2, x2)), "db1": L(hp.db(hp.z1)),
               "db2": L(hp.db(hp.z2)), "a": L(hp.a), "epsilon_alpha": hp.epsilon_alpha,
               "epsilon_beta": hp.epsilon_beta, "epsilon_gamma": hp.epsilon_gamma,
               "zv1": hp.zv(hp.z1), "zv2": hp.zv(hp.z2), "xn1": x1, "xn2": x2,
               "a_w": L(hp.a_w), "alpha_wt_deg": math.degrees(hp.alpha_wt)}
    f3 = lambda v: f"{v / sc:.3f} {u}"  # noqa: E731
    extra, warnings = [], []
    for i, gen in enumerate(sol.generating, start=1):
        if gen is not None:
            results.update(generating_results(gen, "xn", str(i)))
            extra.append(generating_row(gen, "xn", str(i)))
    for i, m in enumerate(sol.measures, start=1):
        results.update(measurement_results(m, str(i), L))
        results[f"b_min{i}"] = L(m.span.b_min)
        extra += measurement_rows(m, str(i), f3, helical=True, lang=lang)
    if sol.shift is not None:
        sh = sol.shift
        rule = {"x1": "xn1 given", "sliding": "balanced specific sliding",
                "strength": "equal Y_Fa Y_Sa"}[sh.rule]
        results.update({"xn_sum": sh.x_sum + 0.0, "zeta1": sh.zeta1, "zeta2": sh.zeta2})
        for i, zeta in ((1, sh.zeta1), (2, sh.zeta2)):
            if zeta is None:   # the other gear's tip passes this gear's end N
                warnings.append(f"interference — the tip of gear {3 - i} passes the end N{i} "
                                "of the line of action (transverse plane): the contact starts "
                                f"below the base circle of gear {i}, zeta{i} is undefined")
        results.update(root_factor_results(sh))
        extra.insert(0, (("gear.normal_shifts", {"rule": rule}), "xn1 + xn2", shift_text(sh)))
    if sol.loads is not None:
        results.update(loads_results(sol.loads, spec.problem.drive))
        extra += loads_rows(sol.loads, f3)
    return _simple(spec, run, outputs, say(lang, "gear.helical_pair"), results, [
        ("gear.helix_angle", "β", "beta_deg", "°"),
        ("gear.transverse_module", "mt", "mt", u),
        ("gear.transverse_pressure_angle", "αt", "alpha_t_deg", "°"),
        ("gear.reference_diameters", "d1", "d1", u), ("gear.blank", "d2", "d2", u),
        ("gear.tip_diameters", "da1", "da1", u), ("gear.blank", "da2", "da2", u),
        ("gear.root_diameters", "df1", "df1", u), ("gear.blank", "df2", "df2", u),
        ("gear.centre_distance", "a", "a", u),
        ("gear.transverse_contact_ratio", "εα", "epsilon_alpha", ""),
        ("gear.overlap_ratio", "εβ", "epsilon_beta", ""),
        ("gear.total_contact_ratio", "εγ", "epsilon_gamma", ""),
        ("gear.virtual_teeth", "zv1", "zv1", ""), ("gear.blank", "zv2", "zv2", ""),
        ("gear.normal_profile_shifts", "xn1", "xn1", ""), ("gear.blank", "xn2", "xn2", ""),
        ("gear.operating_centre_distance", "a'", "a_w", u),
        ("gear.operating_transverse_pressure_angle", "αwt", "alpha_wt_deg", "°"),
    ], warnings, extra)


def present_worm(spec, w, run, outputs):
    u, sc, lang = spec.header.unit, spec.header.scale, run.lang
    L = lambda v: float(v / sc)  # noqa: E731
    results = {"m": L(w.m), "mt2": L(w.m), "mx1": L(w.m), "q": w.q, "d1": L(w.d1),
               "d2": L(w.d2), "px": L(w.px), "lead": L(w.lead),
               "gamma_deg": math.degrees(w.gamma), "a": L(w.a), "i12": w.ratio,
               "da1": L(w.da1), "df1": L(w.df1), "da2": L(w.da2), "df2": L(w.df2)}
    extra = []
    if getattr(w, "efficiency", None) is not None:   # a worm with friction (and loads)
        ld = w.loads
        if ld is not None:
            results.update(loads_results(ld, spec.problem.drive))
            results["v_sliding_m_s"] = ld.sliding_velocity
            extra += loads_rows(ld, lambda v: f"{v / sc:.3f} {u}")
        results.update(worm_efficiency_results(w.efficiency, spec.problem.mu))
        extra += worm_efficiency_rows(w.efficiency, spec.problem.mu, ld, lang)
    return _simple(spec, run, outputs, say(lang, "gear.worm_drive"), results, [
        ("gear.worm_module", "m", "m", u),
        ("gear.diameter_factor", "q", "q", ""),
        ("gear.worm_reference_diameter", "d1", "d1", u),
        ("gear.worm_wheel_reference_diameter", "d2", "d2", u),
        ("gear.worm_axial_pitch", "px1", "px", u),
        ("gear.lead", "l", "lead", u),
        ("gear.lead_angle", "γ", "gamma_deg", "°"),
        ("gear.centre_distance", "a", "a", u),
        ("gear.ratio", "i12", "i12", ""),
        ("gear.worm_tip_root_diameter", "da1", "da1", u),
        ("gear.blank", "df1", "df1", u),
        ("gear.wheel_tip_root_diameter", "da2", "da2", u),
        ("gear.blank", "df2", "df2", u),
    ], [], extra)


def present_bevel(spec, b, run, outputs):
    u, sc, lang = spec.header.unit, spec.header.scale, run.lang
    L = lambda v: float(v / sc)  # noqa: E731
    d1, d2 = b.delta1, b.delta2
    results = {"delta1_deg": math.degrees(d1), "delta2_deg": math.degrees(d2),
               "d1": L(b.d(b.z1)), "d2": L(b.d(b.z2)), "R": L(b.R),
               "theta_a_deg": math.degrees(b.theta_a), "theta_f_deg": math.degrees(b.theta_f),
               "delta_a1_deg": math.degrees(b.delta_a(d1)),
               "delta_a2_deg": math.degrees(b.delta_a(d2)),
               "delta_f1_deg": math.degrees(b.delta_f(d1)),
               "delta_f2_deg": math.degrees(b.delta_f(d2)),
               "da1": L(b.da(b.z1, d1)), "da2": L(b.da(b.z2, d2)),
               "df1": L(b.df(b.z1, d1)), "df2": L(b.df(b.z2, d2)),
               "zv1": b.zv(b.z1, d1), "zv2": b.zv(b.z2, d2)}
    extra, warnings = [], []
    width = getattr(b, "face_width", None)
    if width is not None:   # the face width places the mean cone
        dm1, dm2 = b.mean_diameters
        results.update({"b": L(width), "dm1": L(dm1), "dm2": L(dm2)})
        if b.loads is None:
            extra.append(("gear.face_width_mean_diameters",
                          "b, dm1, dm2", f"{width / sc:.3f}, {dm1 / sc:.3f}, {dm2 / sc:.3f} {u}"))
        if width > b.R / 3 * (1 + 1e-12):
            warnings.append(f"face width b = {width / sc:.6g} {u} is above R/3 = "
                            f"{b.R / 3 / sc:.6g} {u} (the usual design rule b <= R/3)")
    if getattr(b, "loads", None) is not None:
        results.update(loads_results(b.loads, spec.problem.drive))
        extra += loads_rows(b.loads, lambda v: f"{v / sc:.3f} {u}")
    return _simple(spec, run, outputs, say(lang, "gear.bevel_pair"),
                   results, [
        ("gear.pitch_cone_angles", "δ1", "delta1_deg", "°"),
        ("gear.blank", "δ2", "delta2_deg", "°"),
        ("gear.reference_diameters", "d1", "d1", u), ("gear.blank", "d2", "d2", u),
        ("gear.cone_distance", "R", "R", u),
        ("gear.addendum_angle", "θa", "theta_a_deg", "°"),
        ("gear.dedendum_angle", "θf", "theta_f_deg", "°"),
        ("gear.tip_cone_angles", "δa1", "delta_a1_deg", "°"),
        ("gear.blank", "δa2", "delta_a2_deg", "°"),
        ("gear.tip_diameters", "da1", "da1", u), ("gear.blank", "da2", "da2", u),
        ("gear.root_diameters", "df1", "df1", u), ("gear.blank", "df2", "df2", u),
        ("gear.virtual_teeth", "zv1", "zv1", ""), ("gear.blank", "zv2", "zv2", ""),
    ], warnings, extra)


def _simple(spec, run, outputs, heading, results, rows, warnings, extra=()):
    """Key/value table of *rows* (label, symbol, result key, unit) and a one-row CSV;
    *extra* rows (label, symbol, text) are shown below, not written to the CSV."""
    lang = run.lang
    block = Block(heading, [], [[_word(lang, w), f"{sym} = {results[key]:.3f}"
                                 + ("" if not un else (un if un == "°" else f" {un}"))]
                                for w, sym, key, un in rows]
                  + [[_word(lang, w), f"{sym} = {txt}"] for w, sym, txt in extra])
    u = spec.header.unit
    cols = [(key if un in ("", "°") else f"{key}_{u}", [results[key]])
            for _, _, key, un in rows]
    # the table's columns first, then every other result
    outputs.text("gear.csv", wide_csv(cols, results, u, 1, outputs.digits))
    return Report(spec.header.title, [block]), results, warnings


PRESENTERS = {"involute": present_involute, "inverse_involute": present_inverse_involute,
              "spur": present_spur, "pair": present_pair, "generation": present_generation,
              "helical": present_helical, "worm": present_worm, "bevel": present_bevel}
