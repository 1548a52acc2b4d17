"""``[mechanism] type = "joints"``: a linkage given by its drawing.

::

    [mechanism]
    type = "joints"
    frame = 4                      # the frame's link number

    [mechanism.joints]             # every joint's position in the drawing [units]
    A = [0, 0]
    B = [50.8, 88]
    C = [288.7, 177.1]
    D = [304.8, 0]

    [[mechanism.link]]             # a rigid link: the joints it carries (its angle: from
    number = 2                     # the first to the second); a joint on one moving link
    joints = ["B", "C"]            # only is a pivot of the frame (unless the frame is listed)

    [[mechanism.slider]]           # a prismatic pair: `block` slides on `guide` along the
    block = 3                      # line through `through` (default: the block's joint) in
    guide = 4                      # direction `angle` [deg] or towards the joint `toward`
    angle = 0

    [[mechanism.driver]]
    type = "crank"
    link = 1
    pivot = "A"

The core (:mod:`mechcli.core.linkage.drawing`) finds the Assur groups and the elements;
a :class:`~mechcli.core.linkage.drawing.DrawingError` becomes a :class:`SpecError` naming
the joint, link, slider or driver at fault.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Tuple

from mechcli.spec.errors import SpecError
from mechcli.spec.reader import MAX_LENGTH


def read_joints(mech: Any) -> Tuple[int, list, dict, list, Any]:
    """Read the joints form of ``[mechanism]``.

    Returns
    -------
    frame : int
    elements : list of Element
    followers : dict
        Secondary drivers' ``(ratio, phase)`` (as the general form's).
    paths : list of str
        The spec key of each element (for messages).
    drawing : FromDrawing
        The structure, the drawing's input angles and the links' angle offsets.
    """
    from mechcli.core.linkage.drawing import Drawing, DrawingError

    frame = mech.integer("frame", lo=1)
    joints = _read_joint_positions(mech)
    links, link_paths = _read_links(mech, joints)
    sliders, slider_paths = _read_sliders(mech, joints, links, frame)
    drivers, driver_paths, followers, actuators = _read_drivers(mech, links, sliders)
    drawing = Drawing(frame, joints, links, tuple(sliders), tuple(drivers), actuators,
                      dict(followers))
    try:
        result = _solved_drawing(drawing)
    except DrawingError as exc:
        raise SpecError(mech.file, _where(mech, exc, link_paths, slider_paths, driver_paths,
                                          drivers),
                        "a drawing of a linkage the engine can solve", str(exc)
                        + (" (a point on a link is a [[mechanism.point]])" if exc.lone else "")
                        ) from None
    if drivers:
        q1 = result.inputs[drivers[0][0]]
        followers = {k: (ratio, result.inputs[k] - ratio * q1 if phase is None else phase)
                     for k, (ratio, phase) in followers.items()}
    paths = [mech.key("joints")] * len(result.linkage.elements)
    return frame, list(result.linkage.elements), followers, paths, result


def _read_joint_positions(mech: Any) -> Dict[str, Tuple[float, float]]:
    """``[mechanism.joints]``: every joint's drawn position [m]."""
    jt = mech.table("joints")
    joints = {}
    for name in jt.keys():
        jt.check_name(None, name)
        xy = jt.numbers(name, size=2)
        if max(abs(xy[0]), abs(xy[1])) * mech.unit > MAX_LENGTH:
            raise jt.error(name, f"coordinates within ±{MAX_LENGTH:g} m", repr(xy))
        joints[name] = (xy[0] * mech.unit, xy[1] * mech.unit)
    jt.finish()
    if len(joints) < 2:
        raise mech.error("joints", "at least two joints", f"{len(joints)}")
    return joints


def _read_links(mech: Any, joints: dict) -> Tuple[Dict[int, tuple], Dict[int, str]]:
    """``[[mechanism.link]]``: each link's joints (and its spec path, for messages)."""
    links: Dict[int, tuple] = {}
    link_paths: Dict[int, str] = {}
    for t in mech.tables("link"):
        n = t.integer("number", lo=1)
        names = t.strings("joints")
        if not names or len(set(names)) != len(names):
            raise t.error("joints", "an array of different joint names", repr(names))
        for i, j in enumerate(names):
            t.check_name(f"joints[{i}]", j)
            if j not in joints:
                raise t.error(f"joints[{i}]", f"a joint of [mechanism.joints] "
                              f"({', '.join(sorted(joints))})", repr(j))
        if n in links:
            raise t.error("number", "a link number not given before", repr(n))
        links[n] = tuple(names)
        link_paths[n] = t.path
        t.finish()
    return links, link_paths


def _read_sliders(mech: Any, joints: dict, links: dict, frame: int) -> Tuple[list, list]:
    """``[[mechanism.slider]]``: each prismatic pair's block, guide and drawn line."""
    from mechcli.core.linkage.drawing import Slider

    sliders, slider_paths = [], []
    for t in mech.tables("slider", []):
        block, guide = t.integer("block", lo=1), t.integer("guide", lo=1)
        if block == guide:
            raise t.error("guide", "a link other than the block", repr(guide))
        for key, n in (("block", block), ("guide", guide)):
            if n not in links and n != frame:
                raise t.error(key, f"a link of [[mechanism.link]] or the frame {frame}",
                              repr(n))
        own = links.get(block, ())
        through = t.name("through", None)
        if through is None:
            if len(own) != 1:
                raise t.error("through", f"the joint the line of sliding passes through "
                              f"(block {block} carries {len(own)} joints)", "none")
            through = own[0]
        elif through not in joints:
            raise t.error("through", "a joint of [mechanism.joints]", repr(through))
        if t.has("angle") == t.has("toward"):
            raise t.error("angle", "exactly one of `angle` [deg] and `toward` (a joint)",
                          "both" if t.has("angle") else "neither")
        if t.has("angle"):
            angle = math.radians(t.number("angle"))
        else:
            toward = t.name("toward")
            if toward not in joints or toward == through:
                raise t.error("toward", f"a joint of [mechanism.joints] other than "
                              f"'{through}'", repr(toward))
            (x0, y0), (x1, y1) = joints[through], joints[toward]
            angle = math.atan2(y1 - y0, x1 - x0)
        sliders.append(Slider(block, guide, through, angle, t.name("name", None)))
        slider_paths.append(t.path)
        t.finish()
    return sliders, slider_paths


def _read_drivers(mech: Any, links: dict, sliders: list) -> Tuple[list, list, dict, dict]:
    """``[[mechanism.driver]]``: the cranks (link, pivot), the secondary drivers'
    ``(ratio, phase or None)`` and the actuated slides."""
    drivers: list = []
    driver_paths: list = []
    followers: dict = {}
    actuators: dict = {}
    for i, d in enumerate(mech.tables("driver")):
        d.string("type", "crank", choices=["crank"])
        link = d.integer("link", lo=1)
        if link not in links:
            raise d.error("link", "a link of [[mechanism.link]]", repr(link))
        pivot = d.name("pivot")
        drivers.append((link, pivot))
        actuator = d.name("actuator", None)
        if actuator is not None:
            names = {sl.name or f"{sl.block}{sl.guide}" for sl in sliders}
            if actuator not in names:
                raise d.error("actuator", "the name of a [[mechanism.slider]] (the cylinder "
                              "that drives the machine)", repr(actuator))
            actuators[link] = actuator
        driver_paths.append(d.path)
        if i > 0:   # the phase defaults to the drawing's: q = ratio q1 + phase there
            from mechcli.spec.kin import follower_ratio
            phase = d.number("phase", None)
            followers[link] = (follower_ratio(d),
                               None if phase is None else math.radians(phase))
        d.finish()
    return drivers, driver_paths, followers, actuators


def _where(mech: Any, exc: Any, link_paths: dict, slider_paths: list, driver_paths: list,
           drivers: list) -> str:
    """The spec key a :class:`DrawingError` is about."""
    if exc.what == "joint" and exc.name is not None:
        return mech.key(f"joints.{exc.name}")
    if exc.what == "link" and exc.name in link_paths:
        return link_paths[exc.name]
    if exc.what == "driver":
        for (link, _), path in zip(drivers, driver_paths):
            if link == exc.name:
                return path
    if exc.what == "drivers":
        return mech.key("driver")
    return mech.path


#: drawings already turned into linkages in this process, newest last (a drawing's
#: continuation tables take ~0.1-0.5 s; `mechcli schema --learn` reads one spec hundreds
#: of times with only other keys changed, an optimize run one drawing per design)
_SOLVED: dict = {}
_SOLVED_MAX = 8


def _solved_drawing(drawing: Any) -> Any:
    """:func:`~mechcli.core.linkage.drawing.from_drawing`, remembered for the last few
    drawings (the result is immutable records; the same drawing gives the same linkage)."""
    from mechcli.core.linkage.drawing import from_drawing

    key = repr((drawing.frame, sorted(drawing.joints.items()),
                sorted((k, tuple(v)) for k, v in drawing.links.items()), drawing.sliders,
                drawing.drivers, sorted(drawing.actuators.items()),
                sorted(drawing.followers.items())))
    hit = _SOLVED.pop(key, None)
    if hit is None:
        hit = from_drawing(drawing)       # a DrawingError is not remembered
    _SOLVED[key] = hit
    while len(_SOLVED) > _SOLVED_MAX:
        _SOLVED.pop(next(iter(_SOLVED)))
    return hit
