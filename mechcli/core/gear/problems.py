"""Solve one ``mechcli gear`` problem: a function per kind, and :func:`solve_gear`.

Each ``solve_<kind>`` takes plain problem data (any object with the attributes
of the spec's problem of that kind, ``mechcli.spec.gear``: lengths [m], angles
[rad]) and returns what the report of that kind shows.  The modules of a kind
are imported only when it is solved: the scalar kinds (involute table,
inverse involute, pair, helical, worm, bevel) never import numpy.
"""

from __future__ import annotations

import math


def solve_involute(p):
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


def solve_inverse_involute(p):
    """α = inv⁻¹(θ) for each ``p.theta`` (【例 5-2】): an :class:`~.involute.InverseInvolute`
    of tuples."""
    from mechcli.core.gear.involute import (InverseInvolute, involute_function,
                                            inverse_involute_scalar)
    found = [inverse_involute_scalar(t, p.method, start=p.start, epsilon=p.epsilon,
                                     max_iter=p.max_iter) for t in p.theta]
    alpha = tuple(f[0] for f in found)
    return InverseInvolute(theta=tuple(p.theta), alpha=alpha,
                           iterations=tuple(f[1] for f in found),
                           residual=tuple(involute_function(a) - t
                                          for a, t in zip(alpha, p.theta)),
                           method=p.method, start=tuple(f[2] for f in found))


def _gear(teeth, z, x, internal=False, ha_star=None):
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


def _form(g, allowance=0.0):
    from mechcli.core.gear.measurement import ToothForm
    return ToothForm(g.z, g.m, g.alpha, g.x, 0.0, g.ra, allowance)


def solve_spur(p):
    """One spur gear (【例 5-3】): dict of ``gear`` (SpurGear), ``tooth`` (the
    rack-generated tooth) and ``outline`` (GearOutline of ``p.points``, ``p.root``)."""
    from mechcli.core.gear.measurement import measure
    from mechcli.core.gear.profile import gear_outline, generated_tooth
    g = _gear(p.teeth, p.z, p.x)
    tooth = generated_tooth(g)
    measures = measure(_form(g, getattr(p, "allowance", 0.0)), getattr(p, "k", None),
                       getattr(p, "pin_diameter", None), p.radii)
    return {"gear": g, "tooth": tooth, "outline": gear_outline(tooth, p.points, p.root),
            "measures": measures}


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
    """

    measures = (None, None)
    allowances = (0.0, 0.0)
    backlash = ()
    shift = None


def _refuse(message, given, **values):
    """A spec value no mounting accepts: MeshError reason ``"mounting"`` naming it."""
    from mechcli.core.gear.pair import MeshError
    return MeshError(message, "mounting", given=given, **values)


def _design_shifts(p, z1, z2):
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

    def zeta(x1):
        x = (x1, x_sum - x1)
        rb = [t.m * z * math.cos(t.alpha) / 2 for z in (z1, z2)]
        ra = [t.m * z / 2 + (h + xi - max(dy, 0.0)) * t.m for z, h, xi in zip((z1, z2), hs, x)]
        return ms.specific_sliding_at_roots(rb[0], rb[1], ra[0], ra[1], a_w, aw, z2 / z1)

    if p.x_split == "x1":
        x1 = p.x1
    else:
        try:
            x1 = ms.split_balanced_sliding(zeta, x_sum)
        except ms.MeasurementError:
            raise _refuse("no split balances the specific sliding", "x_split", a_w=a_w,
                          x_sum=x_sum, what="sliding") from None
    x2 = x_sum - x1
    if not -1.5 <= x2 <= 1.5:
        raise _refuse("the wheel's shift is outside [-1.5, 1.5]", "x_split", a_w=a_w,
                      x_sum=x_sum, x1=x1, x2=x2, what="x2")
    z_1, z_2 = zeta(x1)
    return ms.ShiftDesign(p.x_split, x_sum, x1, x2, z_1, z_2)


def _ha(p, i):
    value = getattr(p, f"ha_star{i}", None)
    return p.teeth.ha_star if value is None else value


def solve_pair(p):
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
    from mechcli.core.gear.pair import (check_mountings, design_teeth_from_ratio, gear_pair,
                                        tip_shortened)
    if p.ratio is None:
        z1, z2 = p.z1, p.z2
    else:
        z1, z2 = design_teeth_from_ratio(p.ratio, p.a_w[0], p.teeth.m)
    x_split = getattr(p, "x_split", None)
    shift = _design_shifts(p, z1, z2) if x_split else None
    x1, x2 = (shift.x1, shift.x2) if shift else (p.x1, p.x2)
    g1 = _gear(p.teeth, z1, x1, ha_star=_ha(p, 1))
    g2 = _gear(p.teeth, z2, x2, p.internal, ha_star=_ha(p, 2))
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
    out.shift = shift
    return out


def solve_generation(p):
    """Rack-cutter generation for each shift ``p.shifts``: dict of ``teeth``
    (generated teeth), ``outlines`` (GearOutline of ``p.points`` each) and ``plan``
    (cutter positions up to ``p.limit`` every ``p.step``)."""
    from mechcli.core.gear.generation import generation_plan
    from mechcli.core.gear.profile import gear_outline, generated_tooth
    teeth = [generated_tooth(_gear(p.teeth, p.z, x)) for x in p.shifts]
    return {"teeth": teeth, "outlines": [gear_outline(t, p.points) for t in teeth],
            "plan": generation_plan(p.limit, p.step)}


def solve_helical(p):
    """A helical pair (习题 5-6, 5-7): :class:`~.helical.HelicalPair` with ``measures``
    (:class:`~.measurement.GearMeasures` of both gears, in the normal plane)."""
    from mechcli.core.gear.helical import helical_pair
    from mechcli.core.gear.measurement import ToothForm, measure
    xn = (getattr(p, "xn1", 0.0), getattr(p, "xn2", 0.0))
    hp = helical_pair(p.z1, p.z2, p.mn, p.alpha_n, p.han_star, p.cn_star, beta=p.beta,
                      a_w=p.a_w, b=p.b, xn1=xn[0], xn2=xn[1])
    measures = []
    for i, (z, x) in enumerate(zip((hp.z1, hp.z2), xn), start=1):
        form = ToothForm(z, hp.mn, hp.alpha_n, x, hp.beta, hp.da(z, x) / 2,
                         getattr(p, f"allowance{i}", 0.0))
        measures.append(measure(form, getattr(p, f"k{i}", None),
                                getattr(p, f"pin_diameter{i}", None)))
    return HelicalSolution(hp, tuple(measures))


class HelicalSolution:
    """A helical pair and the measurements of its gears (``pair``, ``measures``);
    attributes not found here are the pair's."""

    def __init__(self, pair, measures):
        self.pair, self.measures = pair, measures

    def __getattr__(self, name):
        return getattr(self.pair, name)


def solve_worm(p):
    """A worm drive (习题 5-8): :class:`~.worm.WormDrive`."""
    from mechcli.core.gear.worm import worm_drive
    return worm_drive(p.z1, p.z2, m=p.m, d2=p.d2, q=p.q, d1=p.d1, alpha=p.alpha,
                      ha_star=p.ha_star, c_star=p.c_star)


def solve_bevel(p):
    """A straight bevel pair (习题 5-9): :class:`~.bevel.BevelPair`."""
    from mechcli.core.gear.bevel import bevel_pair
    return bevel_pair(p.z1, p.z2, p.m, p.alpha, p.ha_star, p.c_star, p.sigma)


SOLVERS = {"involute": solve_involute, "inverse_involute": solve_inverse_involute,
           "spur": solve_spur, "pair": solve_pair, "generation": solve_generation,
           "helical": solve_helical, "worm": solve_worm, "bevel": solve_bevel}


def solve_gear(kind, problem):
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
