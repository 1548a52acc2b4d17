"""Solve one ``mechcli gear`` problem: a function per kind, and :func:`solve_gear`.

Each ``solve_<kind>`` takes plain problem data (any object with the attributes
of the spec's problem of that kind, ``mechcli.spec.gear``: lengths [m], angles
[rad]) and returns what the report of that kind shows.  The modules of a kind
are imported only when it is solved: the scalar kinds (involute table,
inverse involute, pair, helical, worm, bevel) never import numpy.
"""

from __future__ import annotations


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


def _gear(teeth, z, x, internal=False):
    from mechcli.core.gear.spur import spur_gear
    return spur_gear(z, teeth.m, teeth.alpha, teeth.ha_star, teeth.c_star, x, internal)


def solve_spur(p):
    """One spur gear (【例 5-3】): dict of ``gear`` (SpurGear), ``tooth`` (the
    rack-generated tooth) and ``outline`` (GearOutline of ``p.points``, ``p.root``)."""
    from mechcli.core.gear.profile import gear_outline, generated_tooth
    g = _gear(p.teeth, p.z, p.x)
    tooth = generated_tooth(g)
    return {"gear": g, "tooth": tooth, "outline": gear_outline(tooth, p.points, p.root)}


def solve_pair(p):
    """A pair at each mounting (``p.a_w``, then ``p.alpha_w``; zero backlash if none)
    (【例 5-4】): list of :class:`~.pair.GearPair`, tips shortened when asked.

    The teeth are ``p.z1``, ``p.z2``, or designed from ``p.ratio`` (not None) and
    the one centre distance ``p.a_w[0]`` (习题 5-2).  Every mounting is checked
    before any pair is mounted (:func:`~.pair.check_mountings`: MeshError with
    reason ``"mounting"`` when the teeth would jam).
    """
    from mechcli.core.gear.pair import (check_mountings, design_teeth_from_ratio, gear_pair,
                                        tip_shortened)
    if p.ratio is None:
        z1, z2 = p.z1, p.z2
    else:
        z1, z2 = design_teeth_from_ratio(p.ratio, p.a_w[0], p.teeth.m)
    g1 = _gear(p.teeth, z1, p.x1)
    g2 = _gear(p.teeth, z2, p.x2, p.internal)
    check_mountings(g1, g2, p.a_w, p.alpha_w)
    pairs = [gear_pair(g1, g2, a_w=a) for a in p.a_w]
    pairs += [gear_pair(g1, g2, alpha_w=aw) for aw in p.alpha_w]
    if not pairs:
        pairs = [gear_pair(g1, g2)]
    if p.tip_shortening:
        pairs = [tip_shortened(pr)[0] for pr in pairs]
    return pairs


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
    """A helical pair (习题 5-6, 5-7): :class:`~.helical.HelicalPair`."""
    from mechcli.core.gear.helical import helical_pair
    return helical_pair(p.z1, p.z2, p.mn, p.alpha_n, p.han_star, p.cn_star, beta=p.beta,
                        a_w=p.a_w, b=p.b)


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
