"""One problem of ``mechcli synth``: its kind and data -> a design and its check.

:func:`solve_synthesis` is the only place that maps a problem's kind to a
synthesis function of this package; the spec layer hands it plain data (SI,
radians), the report layer words what it returns.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

from mechcli.core.records import record
from mechcli.core.synth.verify import Verification, verify

if TYPE_CHECKING:
    pass

#: the kinds whose four-bar only has to move a body: either side link may drive it
#: (a function generator's input is its crank by definition)
GUIDANCE = ("two_positions", "three_positions", "moving_pivots", "coupler_poses", "burmester")


@record(eq=False)
class SynthSolution:
    """What one problem gives.

    Attributes
    ----------
    kind : str
        The problem's kind (``two_positions`` …).
    design : LinkageDesign or None
        The designed linkage (None for the Burmester curves of four poses).
    check : Verification or None
        The design moved on the engine (:func:`~.verify.verify`).
    extra : object or None
        What the kind gives beside a design: Burmester curves or pairs.
    other_driver : Verification or None
        When the design has defects with its crank AB driving, the same four-bar
        driven by its rocker CD, checked (None otherwise).
    """

    kind: str
    design: Any
    check: Optional[Verification]
    extra: Any = None
    other_driver: Optional[Verification] = None


def _design(kind: str, d: Any) -> Any:
    if kind == "two_positions":
        from mechcli.core.synth.guidance import two_positions
        return two_positions(d["B"], d["C"], A=d["A"], D=d["D"], line_A=d["line_A"],
                             line_D=d["line_D"], rigid_tol=d["rigid_tol"]), None
    if kind == "three_positions":
        from mechcli.core.synth.guidance import three_positions
        return three_positions(d["B"], d["C"], rigid_tol=d["rigid_tol"]), None
    if kind == "moving_pivots":
        from mechcli.core.synth.guidance import moving_pivots
        poses = [(m[0], m[1], p) for m, p in zip(d["M"], d["phi"])]
        return moving_pivots(d["A"], d["D"], poses), None
    if kind == "coupler_poses":
        from mechcli.core.synth.guidance import coupler_poses
        return coupler_poses(d["M"], d["phi"], d["A"], d["D"], method=d["method"],
                             tol=d["tol"], max_iter=d["max_iter"], guess=d["guess"]), None
    if kind == "burmester":
        from mechcli.core.synth import guidance
        if len(d["M"]) == 4:
            return None, guidance.burmester_curves(d["M"], d["phi"], n=d["samples"])
        pairs = guidance.burmester_points(d["M"], d["phi"])
        i, j = d["pairs"]
        if max(i, j) > len(pairs):
            from mechcli.core.errors import DescribedError
            raise DescribedError(f"the five poses have {len(pairs)} real Burmester pairs; "
                                 f"pair {max(i, j)} does not exist", reason="pairs",
                                 count=len(pairs), asked=max(i, j))
        return guidance.burmester_design(d["M"], d["phi"], pairs[i - 1], pairs[j - 1]), pairs
    if kind == "function":
        from mechcli.core.synth import function
        if "theta1" in d:
            return function.freudenstein(d["theta1"], d["theta3"], alpha0=d["alpha0"],
                                         phi0=d["phi0"], crank=d["crank"]), None
        from mechcli.core.synth.targets import make_function, table_function
        if d["function"] == "table":
            f = table_function(d["table_x"], d["table_y"], interpolation=d["interpolation"])
            x0 = d["x0"] if d["x0"] is not None else min(d["table_x"])
            xm = d["xm"] if d["xm"] is not None else max(d["table_x"])
        else:
            f = make_function(d["function"], exponent=d.get("exponent"),
                              coeffs=d.get("coeffs"))
            x0, xm = d["x0"], d["xm"]
        return function.function_generator(
            f, x0, xm, alpha_m=d["alpha_m"], phi_m=d["phi_m"], alpha0=d["alpha0"],
            phi0=d["phi0"], method=d["method"], n=d.get("n"), x=d.get("x"),
            crank=d["crank"], samples=d["samples"]), None
    if kind == "slider_function":
        from mechcli.core.synth.function import slider_crank_function
        return slider_crank_function(d["theta1"], d["s"], e=d["e"]), None
    if kind == "rocker_slider":
        from mechcli.core.synth.function import rocker_slider
        return rocker_slider(d["phi"], d["s"], e=d["e"]), None
    if kind == "quick_return":
        from mechcli.core.synth import quick_return as qr
        if d["linkage"] == "crank_rocker":
            if "limit_angle" in d:
                return qr.crank_rocker_from_K_limit_angle(
                    d["K"], d["rocker"], d["frame"], d["limit_angle"], limit=d["limit"],
                    gamma_allowed=d["gamma_allowed"]), None
            cond = {k: d[k] for k in ("pivot_line", "crank", "coupler", "frame") if k in d}
            return qr.crank_rocker_from_K(d["K"], d["rocker"], d["swing"], branch=d["branch"],
                                          gamma_allowed=d["gamma_allowed"], **cond), None
        if d["linkage"] == "slider_crank":
            if "H" in d:
                return qr.slider_crank_from_K(d["K"], d["H"], d["e"],
                                              gamma_allowed=d["gamma_allowed"]), None
            return qr.slider_crank_stroke_from_K(d["K"], d["crank"], d["coupler"],
                                                 gamma_allowed=d["gamma_allowed"]), None
        cond = {k: d[k] for k in ("crank", "frame") if k in d}
        return qr.guide_bar_from_K(d["K"], **cond), None
    if kind == "atlas_page":
        import numpy as np

        from mechcli.core.synth import atlas
        (x0, x1), (y0, y1), h = d["grid_x"], d["grid_y"], d["spacing"]
        gx = x0 + h * np.arange(int(np.floor((x1 - x0) / h + 1e-9)) + 1)
        gy = y0 + h * np.arange(int(np.floor((y1 - y0) / h + 1e-9)) + 1)
        GX, GY = np.meshgrid(gx, gy, indexing="ij")
        return None, atlas.atlas_page(d["A"], d["B"], d["C"], GX.ravel(), GY.ravel(),
                                      step=d["step"])
    if kind == "type_chart":
        from mechcli.core.synth import atlas
        chart = atlas.type_chart(d["A"] if len(d["A"]) > 1 else d["A"][0], d["B"], d["C"],
                                 points=d["points"])
        ranges = kind_of = None
        if d["mark"] is not None:
            b, c = d["mark"]
            kind_of = atlas.chain_kind(d["A"][0], b, c)
            if kind_of[0] == "crank-rocker" and kind_of[1]:
                ranges = atlas.admissible_ranges(d["A"][0], b, c)
        return None, AtlasChart(chart, d["mark"], kind_of, ranges)
    raise ValueError(f"unknown synthesis kind {kind!r}")


@record
class AtlasChart:
    """The type chart and the marked point (B, C) with its type, whether link 1
    is its crank, and the admissible ranges of A, B, C (None unless a
    crank-rocker with crank 1)."""

    chart: Any
    mark: Optional[tuple]
    kind: Optional[tuple]
    ranges: Optional[dict]


def solve_synthesis(kind: str, data: Any) -> SynthSolution:
    """Design one problem and check the design on the engine.

    Parameters
    ----------
    kind : str
        One of the kinds of ``mechcli synth`` (``spec.synth.KINDS``).
    data : dict
        The problem's data, SI units and radians; ``driver`` (1 or 3, default 1)
        says which link of a four-bar drives it in the check.

    Raises
    ------
    DescribedError
        The problem has no solution (with the numbers of why).
    """
    design, extra = _design(kind, data)
    if design is None:
        return SynthSolution(kind, None, None, extra)
    driver = data.get("driver", 1)
    check = verify(design, driver)
    other = None
    if check.defects and kind in GUIDANCE and design.inputs is not None \
            and len(design.inputs) > 1:
        other = verify(design, 4 - driver)
    return SynthSolution(kind, design, check, extra, other)
