"""Solve one ``mechcli gear`` problem: a function per kind, and :func:`solve_gear`.

Each ``solve_<kind>`` takes plain problem data (any object with the attributes
of the spec's problem of that kind, ``mechcli.spec.gear``: lengths [m], angles
[rad]) and returns what the report of that kind shows.  The modules of a kind
are imported only when it is solved: the scalar kinds (involute table,
inverse involute, pair, helical, worm, bevel) never import numpy.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Callable, Dict, Optional, Sequence, Tuple, Union

if TYPE_CHECKING:   # annotations only: each kind imports its modules when solved
    from mechcli.core.gear.bevel import BevelPair
    from mechcli.core.gear.helical import HelicalPair
    from mechcli.core.gear.involute import InverseInvolute
    from mechcli.core.gear.loads import ToothLoads
    from mechcli.core.gear.measurement import GearMeasures, GeneratingShift, ShiftDesign, ToothForm
    from mechcli.core.gear.pair import MeshError
    from mechcli.core.gear.spur import SpurGear
    from mechcli.core.gear.strength import RootFactors
    from mechcli.core.gear.worm import WormDrive


def solve_involute(p: Any) -> Dict[str, Any]:
    """Involute curve from 0 to ``p.alpha_max`` every ``p.curve_step`` and the table
    of inv(α) (【例 5-1】).

    Returns
    -------
    dict
        ``alpha`` (list [rad]), ``curve`` ((r, θ, x, y) lists [m, rad]) and
        ``table`` (:func:`~.involute.involute_table_rows`).
    """
    from mechcli.core.gear.involute import involute_point, involute_table_rows
    n = int(round(p.alpha_max / p.curve_step)) + 1
    alpha = [p.alpha_max * i / (n - 1) for i in range(n)] if n > 1 else [0.0]
    curve = tuple(map(list, zip(*(involute_point(p.rb, a) for a in alpha))))
    table = involute_table_rows(p.table_from_deg, p.table_to_deg, p.table_step_deg, p.columns)
    return {"alpha": alpha, "curve": curve, "table": table}


def solve_inverse_involute(p: Any) -> InverseInvolute:
    """α = inv⁻¹(θ) for each ``p.theta`` (【例 5-2】): an :class:`~.involute.InverseInvolute`
    of tuples."""
    from mechcli.core.gear.involute import (
        InverseInvolute,
        inverse_involute_scalar,
        involute_function,
    )
    found = [inverse_involute_scalar(t, p.method, start=p.start, epsilon=p.epsilon,
                                     max_iter=p.max_iter) for t in p.theta]
    alpha = tuple(f[0] for f in found)
    return InverseInvolute(theta=tuple(p.theta), alpha=alpha,
                           iterations=tuple(f[1] for f in found),
                           residual=tuple(involute_function(a) - t
                                          for a, t in zip(alpha, p.theta)),
                           method=p.method, start=tuple(f[2] for f in found))


def _gear(teeth: Any, z: int, x: float, internal: bool = False,
          ha_star: Optional[float] = None) -> SpurGear:
    """A gear cut by the tooth system's rack; *ha_star* (not None) sets its own tip
    (h_a = (ha_star + x) m: unequal addenda) while the cutter, and so the root,
    stays the tooth system's."""
    import dataclasses

    from mechcli.core.gear.spur import GearGeometryError, spur_gear
    g = spur_gear(z, teeth.m, teeth.alpha, teeth.ha_star, teeth.c_star, x, internal)
    if ha_star is None or ha_star == teeth.ha_star:
        return g
    g = dataclasses.replace(g, tip_reduction=(teeth.ha_star - ha_star) * teeth.m)
    if (g.ra < g.rb) if not internal else (g.ra > g.rf):
        raise GearGeometryError(
            f"the tip circle is inside the base circle (z = {g.z}, x = {g.x:g}): the teeth "
            "have no involute", "tip_inside_base", z=g.z, x=g.x, da=g.da, db=g.db)
    return g


def _form(g: SpurGear, allowance: float = 0.0) -> ToothForm:
    from mechcli.core.gear.measurement import ToothForm
    return ToothForm(g.z, g.m, g.alpha, g.x, 0.0, g.ra, allowance)


def solve_spur(p: Any) -> Dict[str, Any]:
    """One spur gear (【例 5-3】): dict of ``gear`` (SpurGear), ``tooth`` (the
    rack-generated tooth), ``outline`` (GearOutline of ``p.points``, ``p.root``),
    ``measures`` and ``generating`` (:class:`~.measurement.GeneratingShift` of a gear
    with an allowance, else None)."""
    from mechcli.core.gear.measurement import generating_shift, measure
    from mechcli.core.gear.profile import gear_outline, generated_tooth
    g = _gear(p.teeth, p.z, p.x)
    tooth = generated_tooth(g)
    allowance = getattr(p, "allowance", 0.0)
    measures = measure(_form(g, allowance), getattr(p, "k", None),
                       getattr(p, "pin_diameter", None), p.radii)
    return {"gear": g, "tooth": tooth, "outline": gear_outline(tooth, p.points, p.root),
            "measures": measures,
            "generating": generating_shift(measures.form) if allowance > 0 else None}


class PairSolution(list):
    """The mounted pairs (a list of :class:`~.pair.GearPair`, one per mounting) and
    what was measured and designed on the gears.

    Attributes
    ----------
    measures : tuple
        :class:`~.measurement.GearMeasures` of gear 1 and gear 2 (None for a ring).
    allowances : (float, float)
        Tooth-thickness allowances E1, E2 (m).
    backlash : list of (float, float)
        Per mounting: circumferential backlash on the operating pitch circle
        and normal backlash (along the line of action), with the allowances (m).
    shift : ShiftDesign or None
        The shifts designed for the centre distance (``p.x_split``).
    loads : ToothLoads or None
        Torques and tooth forces of the first mounting (``p.drive``).
    generating : tuple
        :class:`~.measurement.GeneratingShift` of gear 1 and gear 2: of a gear with an
        allowance (given, or both gears when found from ``p.backlash``), else None.
    """

    measures: Tuple[Optional[GearMeasures], ...] = (None, None)
    generating: Tuple[Optional[GeneratingShift], ...] = (None, None)
    allowances: Tuple[float, ...] = (0.0, 0.0)
    backlash: Sequence[Tuple[float, float]] = ()
    shift: Optional[ShiftDesign] = None
    loads: Optional[ToothLoads] = None


def _refuse(message: str, given: str, **values: Any) -> MeshError:
    """A spec value no mounting accepts: MeshError reason ``"mounting"`` naming it."""
    from mechcli.core.gear.pair import MeshError
    return MeshError(message, "mounting", given=given, **values)


def _design_shifts(p: Any, z1: int, z2: int) -> ShiftDesign:
    """x1, x2 for the one centre distance ``p.a_w[0]`` (``p.x_split``): ShiftDesign."""
    from mechcli.core.gear import measurement as ms
    t = p.teeth
    a = t.m * (z1 + z2) / 2
    a_w = p.a_w[0]
    try:
        x_sum, aw = ms.shift_sum_for_centre_distance(z1, z2, t.alpha, a, a_w)
    except ms.MeasurementError:
        raise _refuse("no profile-shift sum gives this centre distance", "x_split", a_w=a_w,
                      a0=a * math.cos(t.alpha), what="base") from None
    hs = (_ha(p, 1), _ha(p, 2))
    dy = (x_sum - (a_w - a) / t.m) if p.tip_shortening else 0.0

    def zeta(x1: float) -> Tuple[float, float]:
        x = (x1, x_sum - x1)
        rb = [t.m * z * math.cos(t.alpha) / 2 for z in (z1, z2)]
        ra = [t.m * z / 2 + (h + xi - max(dy, 0.0)) * t.m for z, h, xi in zip((z1, z2), hs, x)]
        return ms.specific_sliding_at_roots(rb[0], rb[1], ra[0], ra[1], a_w, aw, z2 / z1)

    def factors(x1: float) -> Tuple[RootFactors, ...]:
        from mechcli.core.gear.strength import full_radius, root_factors
        x = (x1, x_sum - x1)
        return tuple(root_factors(z, t.m, t.alpha, xi, t.m * z + 2 * (h + xi - max(dy, 0.0)) * t.m,
                                  h_fP=(t.ha_star + t.c_star) * t.m,
                                  rho_fP=full_radius(t.c_star, t.alpha) * t.m)
                     for z, h, xi in zip((z1, z2), hs, x))

    def reject(x1: float) -> Optional[dict]:
        """Why the split (x1, x_sum - x1) is no usable pair (None: it is)."""
        import dataclasses

        from mechcli.core.gear.spur import GearGeometryError, spur_gear
        try:
            gears = [dataclasses.replace(
                spur_gear(z, t.m, t.alpha, t.ha_star, t.c_star, xi),
                tip_reduction=(t.ha_star - h + max(dy, 0.0)) * t.m)
                for z, h, xi in zip((z1, z2), hs, (x1, x_sum - x1))]
        except GearGeometryError as exc:
            return {"what": "geometry", "text": str(exc)}
        n = a_w * math.sin(aw)
        return _unusable(gears[0].z, gears[1].z, [(g.x, g.x_min, g.undercut,
                                                   g.tooth_thickness(g.ra), g.ra, g.rb)
                                                  for g in gears], n)

    return _split_shifts(p.x_split, p.x1, x_sum, a_w, zeta, factors, reject)


def _unusable(z1: int, z2: int, gears: Sequence[tuple], n: float) -> Optional[dict]:
    """Why a designed pair is not usable, or None: a gear undercut, a pointed tip, or a
    tip circle cutting the line of action beyond the other gear's tangent point N
    (interference).

    *gears*: per gear (x, x_min, undercut, tip thickness, ra, rb); *n* = N1N2 (m).
    Returns a dict: ``what`` (``"undercut"``, ``"pointed"``, ``"interference"``),
    ``gear`` (1 or 2), ``z``, ``x``, and ``x_min`` (undercut) or ``excess`` (how far
    the tip passes N, m)."""
    for i, (z, (x, x_min, cut, s_a, _, _)) in enumerate(zip((z1, z2), gears), start=1):
        if cut:
            return {"what": "undercut", "gear": i, "z": z, "x": x, "x_min": x_min}
        if s_a <= 0:
            return {"what": "pointed", "gear": i, "z": z, "x": x}
    for i, (z, (x, _, _, _, ra, rb)) in enumerate(zip((z1, z2), gears), start=1):
        reach = math.sqrt(max(ra * ra - rb * rb, 0.0))
        if reach > n * (1 + 1e-12):
            return {"what": "interference", "gear": i, "z": z, "x": x, "excess": reach - n}
    return None


def _split_shifts(rule: str, x1_given: float, x_sum: float, a_w: float,
                  zeta: Callable[[float], Tuple[float, float]],
                  factors: Callable[[float], Tuple[RootFactors, ...]],
                  reject: Optional[Callable[[float], Optional[dict]]] = None) -> ShiftDesign:
    """x1, x2 of the sum *x_sum* by *rule* (``"x1"``, ``"sliding"``, ``"strength"``):
    :class:`~.measurement.ShiftDesign`; *zeta(x1)* gives the specific sliding,
    *factors(x1)* the two gears' root factors, *reject(x1)* why a split is no usable pair
    (:func:`_unusable`; the ``"strength"`` rule takes the strongest usable equal split,
    :func:`~.strength.split_equal_strength`) (MeshError ``"mounting"`` naming
    ``x_split`` when the rule has no (usable) solution or x2 leaves [-1.5, 1.5]).
    A zeta of -inf (a tip passing the other gear's end N: interference, which the
    report warns about) is returned as None."""
    from mechcli.core.gear import measurement as ms
    from mechcli.core.gear.strength import split_equal_strength
    if not -3.0 <= x_sum <= 3.0:   # two shifts in [-1.5, 1.5] cannot carry it
        raise _refuse("the shift sum is beyond two shifts in [-1.5, 1.5]", "x_split",
                      a_w=a_w, x_sum=x_sum, what="sum_range")
    if rule == "x1":
        x1 = x1_given
    elif rule == "sliding":
        try:
            x1 = ms.split_balanced_sliding(zeta, x_sum)
        except ms.MeasurementError:
            raise _refuse("no split balances the specific sliding", "x_split", a_w=a_w,
                          x_sum=x_sum, what="sliding") from None
    else:
        try:
            x1 = split_equal_strength(factors, x_sum, reject=reject)
        except ms.MeasurementError as exc:
            if exc.reason == "strength_split_rejected":
                raise _refuse("every split of equal root strength is refused", "x_split",
                              a_w=a_w, x_sum=x_sum, what="strength_rejected",
                              splits=exc.values["splits"]) from None
            raise _refuse("no split gives equal root strength", "x_split", a_w=a_w,
                          x_sum=x_sum, what="strength") from None
    x2 = x_sum - x1
    if not -1.5 <= x2 <= 1.5:
        raise _refuse("the wheel's shift is outside [-1.5, 1.5]", "x_split", a_w=a_w,
                      x_sum=x_sum, x1=x1, x2=x2, what="x2")
    # a tip passing the other gear's tangent point N (interference, warned as for any
    # pair) leaves the specific sliding at that root undefined (-inf): None
    z_1, z_2 = (None if math.isinf(z) else z for z in zeta(x1))
    return ms.ShiftDesign(rule, x_sum, x1, x2, z_1, z_2,
                          factors(x1) if rule == "strength" else ())


def _ha(p: Any, i: int) -> float:
    value = getattr(p, f"ha_star{i}", None)
    return p.teeth.ha_star if value is None else value


def solve_pair(p: Any) -> PairSolution:
    """A pair at each mounting (``p.a_w``, then ``p.alpha_w``; zero backlash if none)
    (【例 5-4】): :class:`PairSolution` (a list of :class:`~.pair.GearPair`), tips
    shortened when asked, with the measurements of both gears.

    The teeth are ``p.z1``, ``p.z2``, or designed from ``p.ratio`` (not None) and
    the one centre distance ``p.a_w[0]`` (习题 5-2).  With ``p.x_split`` the shifts
    are designed for that one centre distance (x1 given, or balanced sliding).
    Every mounting is checked before any pair is mounted
    (:func:`~.pair.check_mountings`: MeshError with reason ``"mounting"`` when the
    teeth would jam; the same reason, with ``given`` = ``"x_split"`` or
    ``"backlash"``, for a shift design or a backlash that cannot be had).
    """
    from mechcli.core.gear import measurement as ms
    from mechcli.core.gear.pair import (
        check_mountings,
        design_teeth_from_ratio,
        gear_pair,
        tip_shortened,
    )
    if p.ratio is None:
        z1, z2 = p.z1, p.z2
    else:
        z1, z2 = design_teeth_from_ratio(p.ratio, p.a_w[0], p.teeth.m)
    x_split = getattr(p, "x_split", None)
    shift = _design_shifts(p, z1, z2) if x_split else None
    x1, x2 = (shift.x1, shift.x2) if shift else (p.x1, p.x2)
    g1 = _gear(p.teeth, z1, x1, ha_star=_ha(p, 1))
    g2 = _gear(p.teeth, z2, x2, p.internal, ha_star=_ha(p, 2))
    if getattr(p, "tip", "effective") == "nominal":   # the mesh ends on the tip circles
        import dataclasses
        g1, g2 = (dataclasses.replace(g, nominal_tip=True) for g in (g1, g2))
    check_mountings(g1, g2, p.a_w, p.alpha_w)
    pairs = [gear_pair(g1, g2, a_w=a) for a in p.a_w]
    pairs += [gear_pair(g1, g2, alpha_w=aw) for aw in p.alpha_w]
    if not pairs:
        pairs = [gear_pair(g1, g2)]
    if p.tip_shortening:
        pairs = [tip_shortened(pr)[0] for pr in pairs]
    first = pairs[0]
    alpha = p.teeth.alpha
    e = (getattr(p, "allowance1", 0.0), getattr(p, "allowance2", 0.0))
    wanted = getattr(p, "backlash", None)
    if wanted is not None:
        j0 = first.backlash
        if wanted < j0 * (1 - 1e-12):
            raise _refuse("the nominal teeth already have more backlash", "backlash",
                          j=wanted, j0=j0, what="below")
        e = ms.allowances_for_backlash(wanted, j0, alpha, first.alpha_w, 0.0,
                                       getattr(p, "backlash_share1", 0.5))
        for g, ei in zip((first.g1, first.g2), e):
            if ei >= g.s:
                raise _refuse("the allowance would take the whole tooth", "backlash",
                              j=wanted, j0=j0, allowance=ei, s=g.s, z=g.z, what="tooth")
    out = PairSolution(pairs)
    out.allowances = tuple(e)
    out.backlash = []
    for pr in pairs:
        j = ms.backlash_from_allowances(pr.backlash, alpha, pr.alpha_w, 0.0, *e)
        out.backlash.append((j, j * math.cos(pr.alpha_w)))
    ks = (getattr(p, "k1", None), getattr(p, "k2", None))
    dps = (getattr(p, "pin_diameter1", None), getattr(p, "pin_diameter2", None))
    out.measures = tuple(
        None if g.internal else ms.measure(_form(g, ei), k, dp)
        for g, ei, k, dp in zip((first.g1, first.g2), e, ks, dps))
    out.generating = tuple(   # a ring too: x_E in ISO's sign of x (+ thickens its teeth)
        ms.generating_shift(_form(g, ei)) if ei > 0 or wanted is not None else None
        for g, ei in zip((first.g1, first.g2), e))
    out.shift = shift
    drive = getattr(p, "drive", None)
    if drive is not None:
        from mechcli.core.gear.loads import parallel_loads
        out.loads = parallel_loads(drive.power, drive.omega1, first.g1.z, first.g2.z,
                                   first.g1.d, first.g2.d, first.dw1, first.dw2,
                                   first.alpha_w)
    return out


def solve_generation(p: Any) -> Dict[str, Any]:
    """Rack-cutter generation for each shift ``p.shifts``: dict of ``teeth``
    (generated teeth), ``outlines`` (GearOutline of ``p.points`` each) and ``plan``
    (cutter positions up to ``p.limit`` every ``p.step``)."""
    from mechcli.core.gear.generation import generation_plan
    from mechcli.core.gear.profile import gear_outline, generated_tooth
    teeth = [generated_tooth(_gear(p.teeth, p.z, x)) for x in p.shifts]
    return {"teeth": teeth, "outlines": [gear_outline(t, p.points) for t in teeth],
            "plan": generation_plan(p.limit, p.step)}


def solve_helical(p: Any) -> HelicalSolution:
    """A helical pair (习题 5-6, 5-7): :class:`~.helical.HelicalPair` with ``measures``
    (:class:`~.measurement.GearMeasures` of both gears, in the normal plane) and
    ``generating`` (:class:`~.measurement.GeneratingShift` of a gear with an allowance,
    else None)."""
    from mechcli.core.gear.helical import helical_pair
    from mechcli.core.gear.measurement import ToothForm, generating_shift, measure
    xn = (getattr(p, "xn1", 0.0), getattr(p, "xn2", 0.0))
    shift = None
    if getattr(p, "x_split", None):
        shift = _design_helical_shifts(p)
        xn = (shift.x1, shift.x2)
    hp = helical_pair(p.z1, p.z2, p.mn, p.alpha_n, p.han_star, p.cn_star, beta=p.beta,
                      a_w=None if shift else p.a_w, b=p.b, xn1=xn[0], xn2=xn[1])
    measures = []
    for i, (z, x) in enumerate(zip((hp.z1, hp.z2), xn), start=1):
        form = ToothForm(z, hp.mn, hp.alpha_n, x, hp.beta, hp.da(z, x) / 2,
                         getattr(p, f"allowance{i}", 0.0))
        measures.append(measure(form, getattr(p, f"k{i}", None),
                                getattr(p, f"pin_diameter{i}", None)))
    loads = None
    drive = getattr(p, "drive", None)
    if drive is not None:
        from mechcli.core.gear.loads import parallel_loads
        dw = [hp.d(z) * hp.a_w / hp.a for z in (hp.z1, hp.z2)]
        loads = parallel_loads(drive.power, drive.omega1, hp.z1, hp.z2, hp.d(hp.z1),
                               hp.d(hp.z2), dw[0], dw[1], hp.alpha_wt, hp.beta)
    out = HelicalSolution(hp, tuple(measures), loads)
    out.shift = shift
    out.generating = tuple(generating_shift(m.form) if m.form.allowance > 0 else None
                           for m in measures)
    return out


def _design_helical_shifts(p: Any) -> ShiftDesign:
    """xn1, xn2 of a helical pair of helix angle ``p.beta`` for the centre distance
    ``p.a_w`` (``p.x_split``): :class:`~.measurement.ShiftDesign` of normal shifts.

    The sum from ISO 21771 (:func:`~.measurement.normal_shift_sum_for_centre_distance`);
    the specific sliding in the transverse plane, the root factors on the virtual
    spur gears (:func:`~.strength.root_factors`)."""
    from mechcli.core.gear import measurement as ms
    from mechcli.core.gear.strength import full_radius, root_factors
    z1, z2, mn, an, beta, a_w = p.z1, p.z2, p.mn, p.alpha_n, p.beta, p.a_w
    try:
        x_sum, awt = ms.normal_shift_sum_for_centre_distance(z1, z2, mn, an, beta, a_w)
    except ms.MeasurementError:
        at = math.atan(math.tan(an) / math.cos(beta))
        raise _refuse("no profile-shift sum gives this centre distance", "x_split", a_w=a_w,
                      a0=mn * (z1 + z2) / (2 * math.cos(beta)) * math.cos(at),
                      what="base") from None
    at = math.atan(math.tan(an) / math.cos(beta))
    d = [mn * z / math.cos(beta) for z in (z1, z2)]

    def zeta(x1: float) -> Tuple[float, float]:
        x = (x1, x_sum - x1)
        rb = [di * math.cos(at) / 2 for di in d]
        ra = [di / 2 + (p.han_star + xi) * mn for di, xi in zip(d, x)]
        return ms.specific_sliding_at_roots(rb[0], rb[1], ra[0], ra[1], a_w, awt, z2 / z1)

    def factors(x1: float) -> Tuple[RootFactors, ...]:
        x = (x1, x_sum - x1)
        return tuple(root_factors(z, mn, an, xi, di + 2 * (p.han_star + xi) * mn, beta,
                                  h_fP=(p.han_star + p.cn_star) * mn,
                                  rho_fP=full_radius(p.cn_star, an) * mn)
                     for z, di, xi in zip((z1, z2), d, x))

    def reject(x1: float) -> Optional[dict]:
        """Why the split is no usable pair (None: it is), in the transverse plane: undercut
        when (han* - xn) mn > r sin^2 at (x_min = han* - z sin^2 at / (2 cos beta)), the
        transverse tip thickness da (st/d + inv at - inv a_at) <= 0, or a tip passing N."""
        from mechcli.core.gear.involute import involute_function as inv
        mt = mn / math.cos(beta)
        gears = []
        for z, di, xi in zip((z1, z2), d, (x1, x_sum - x1)):
            x_min = p.han_star - z * math.sin(at) ** 2 / (2 * math.cos(beta))
            ra, rb = di / 2 + (p.han_star + xi) * mn, di * math.cos(at) / 2
            st = mt * (math.pi / 2 + 2 * xi * math.tan(an))
            s_a = 2 * ra * (st / di + inv(at) - inv(math.acos(min(1.0, rb / ra))))
            gears.append((xi, x_min, xi < x_min - 1e-12, s_a, ra, rb))
        return _unusable(z1, z2, gears, a_w * math.sin(awt))

    return _split_shifts(p.x_split, getattr(p, "xn1", 0.0), x_sum, a_w, zeta, factors,
                         reject)


class HelicalSolution:
    """A helical pair, the measurements of its gears, its loads and designed shifts
    (``pair``, ``measures``, ``loads``: ToothLoads or None, ``shift``: ShiftDesign or
    None, ``generating``: GeneratingShift or None per gear); attributes not found here
    are the pair's."""

    shift: Optional[ShiftDesign] = None
    generating: Tuple[Optional[GeneratingShift], ...] = (None, None)

    def __init__(self, pair: HelicalPair, measures: Sequence[GearMeasures],
                 loads: Optional[ToothLoads] = None) -> None:
        self.pair, self.measures, self.loads = pair, measures, loads

    def __getattr__(self, name: str) -> Any:
        return getattr(self.pair, name)


class Loaded:
    """A drive (worm, bevel pair) with its ``loads`` (ToothLoads or None), for a
    worm with friction ``efficiency`` (eta, eta', phi: :func:`~.loads.worm_efficiency`),
    for a bevel pair of given face width ``face_width`` (m) and ``mean_diameters``
    (dm1, dm2: :func:`~.loads.bevel_mean_diameters`); attributes not found here are the
    drive's."""

    def __init__(self, drive: Any, loads: Optional[ToothLoads] = None,
                 efficiency: Optional[Tuple[float, float, float]] = None,
                 face_width: Optional[float] = None,
                 mean_diameters: Optional[Tuple[float, float]] = None) -> None:
        self.drive, self.loads, self.efficiency = drive, loads, efficiency
        self.face_width, self.mean_diameters = face_width, mean_diameters

    def __getattr__(self, name: str) -> Any:
        return getattr(self.drive, name)


def solve_worm(p: Any) -> Union[WormDrive, Loaded]:
    """A worm drive (习题 5-8): :class:`~.worm.WormDrive`, or with power and speed
    (``p.drive``) or a friction (``p.mu``) a :class:`Loaded` one."""
    from mechcli.core.gear.worm import worm_drive
    w = worm_drive(p.z1, p.z2, m=p.m, d2=p.d2, q=p.q, d1=p.d1, alpha=p.alpha,
                   ha_star=p.ha_star, c_star=p.c_star)
    drive, mu = getattr(p, "drive", None), getattr(p, "mu", None)
    if drive is None and mu is None:
        return w
    from mechcli.core.gear import loads as ld
    # (mu is given with a drive: the spec requires it)
    eff = ld.worm_efficiency(w.gamma, ld.worm_normal_pressure_angle(w.alpha, w.gamma),
                             mu)  # type: ignore[arg-type]
    loads = None
    if drive is not None:
        loads = ld.worm_loads(drive.power, drive.omega1, w.z1, w.z2, w.d1, w.d2, w.gamma,
                              w.alpha, mu)  # type: ignore[arg-type]
    return Loaded(w, loads, eff)


def solve_bevel(p: Any) -> Union[BevelPair, Loaded]:
    """A straight bevel pair (习题 5-9): :class:`~.bevel.BevelPair`, or with power and
    speed (``p.drive``) a :class:`Loaded` one."""
    from mechcli.core.gear.bevel import bevel_pair
    b = bevel_pair(p.z1, p.z2, p.m, p.alpha, p.ha_star, p.c_star, p.sigma)
    drive, width = getattr(p, "drive", None), getattr(p, "b", None)
    if drive is None and width is None:
        return b
    from mechcli.core.gear.loads import bevel_loads, bevel_mean_diameters
    # (the face width is given with a drive: the spec requires it)
    dm = bevel_mean_diameters(b.d(b.z1), b.d(b.z2), b.R, width)  # type: ignore[arg-type]
    loads = None if drive is None else bevel_loads(drive.power, drive.omega1, b.z1, b.z2,
                                                   b.d(b.z1), b.d(b.z2), b.R, width,  # type: ignore[arg-type]
                                                   b.alpha,
                                                   b.delta1, b.delta2)
    return Loaded(b, loads, face_width=width, mean_diameters=dm)


SOLVERS = {"involute": solve_involute, "inverse_involute": solve_inverse_involute,
           "spur": solve_spur, "pair": solve_pair, "generation": solve_generation,
           "helical": solve_helical, "worm": solve_worm, "bevel": solve_bevel}


def solve_gear(kind: str, problem: Any) -> Any:
    """Solve a gear problem of a kind in :data:`SOLVERS`.

    Raises
    ------
    GearError
        The gear or drive cannot exist as asked (numbers as attributes).
    ConvergenceError
        The inverse involute did not converge.
    """
    if kind not in SOLVERS:
        raise ValueError(f"unknown kind {kind!r}: one of {', '.join(SOLVERS)}")
    return SOLVERS[kind](problem)
