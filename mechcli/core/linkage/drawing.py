"""A linkage given by its joints: the drawing in, the elements and Assur groups out.

The student draws the mechanism: every joint's position, every link as the joints
it carries, the prismatic pairs as lines of sliding, the drivers.  This module does
the structural analysis (:func:`mechcli.core.grashof.structure.decompose`) and turns
each group into the engine's elements, solving order included:

* a crank: :class:`~.elements.Crank` from its pivot to its first other joint;
* a dyad: :class:`~.elements.RRR`, :class:`~.elements.RRP`, :class:`~.elements.RPR`
  or :class:`~.elements.PRP`, its lengths, offsets and guide angles measured on the
  drawing, its assembly branch the one the drawing shows;
* every further joint of a link: a :class:`~.elements.PointOnLink` on it.

Each step is checked on the engine itself: the partial linkage is solved at the
drawing's input angles and must put every joint where the drawing has it (to
:data:`CLOSE_TOL` of the linkage's size); a drawing whose lengths do not close, or a
group drawn at its dead point, is a :class:`DrawingError` naming the joint.

A link's angle is the direction from its first joint to its second, as listed; the
engine measures some links from another pair of their points, so the difference,
constant on a rigid link, is returned (:attr:`FromDrawing.angle_offsets`) for the
reports to add.  SI units and radians, like the rest of the core.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Optional

import numpy as np

from mechcli.core.grashof.mobility import Joint, MobilityError, count_mobility
from mechcli.core.grashof.structure import decompose
from mechcli.core.linkage.elements import (
    PRP,
    RPR,
    RRP,
    RRR,
    Crank,
    Ground,
    PointOnLink,
    _slide_symbol,
)
from mechcli.core.linkage.engine import DriverMotion, Linkage, solve
from mechcli.core.records import record

#: how closely the engine must reproduce the drawing's joints (relative to its size)
CLOSE_TOL = 1e-9
#: a dyad drawn within this sine of its toggle (relative) has no defined branch
TOGGLE_TOL = 1e-9


class DrawingError(ValueError):
    """The drawing does not describe a solvable linkage.

    Attributes
    ----------
    what : str
        ``"joint"``, ``"link"``, ``"slider"``, ``"driver"`` or ``"drivers"``.
    name : str or int or None
        The joint's name, the link's number, the slider's index ...
    lone : bool
        A joint on one link only (the spec layer says what such a point is).
    """

    def __init__(self, message: str, what: str, name: Any = None, lone: bool = False) -> None:
        super().__init__(message)
        self.what = what
        self.name = name
        self.lone = lone


@record
class Slider:
    """A prismatic pair of the drawing: ``block`` slides on ``guide`` along the line
    through ``through`` (a joint) in direction ``angle`` [rad, absolute, as drawn]."""

    block: int
    guide: int
    through: str
    angle: float
    name: Optional[str] = None


@record
class Drawing:
    """A planar linkage as drawn.

    Attributes
    ----------
    frame : int
    joints : dict
        name -> (x, y) [m].
    links : dict
        link number -> tuple of joint names (the first two fix its angle).
    sliders : tuple of Slider
    drivers : tuple of (link, pivot)
        Cranks: the link and its pivot joint on the frame, the primary one first.
    actuators : dict
        driver link -> the name of the slider (an RPR group's prismatic pair, e.g. a
        hydraulic cylinder) that drives the machine while the motion is given as that
        driver's angle (:attr:`.elements.Crank.actuator`).
    followers : dict
        secondary driver link -> ``(ratio, phase)``: its angle is ``ratio q1 + phase``
        (phase None: the drawing's); what the continuation of a Newton-solved group
        follows when a group hangs on more than one driver.
    """

    frame: int
    joints: dict
    links: dict
    sliders: tuple
    drivers: tuple
    actuators: dict = dataclasses.field(default_factory=dict)
    followers: dict = dataclasses.field(default_factory=dict)


@record
class FromDrawing:
    """The linkage a drawing describes.

    Attributes
    ----------
    linkage : Linkage
    structure : Structure
        Drivers and Assur groups in solving order.
    inputs : dict
        driver link -> its angle in the drawing [rad] (where continuation starts).
    angle_offsets : dict
        link -> (its angle from its first joint to its second) − (the engine's
        angle of that link) [rad], for links where they differ.
    mobility : Mobility
    """

    linkage: Linkage
    structure: object
    inputs: dict
    angle_offsets: dict
    mobility: object


def _angle(v: Any):
    return math.atan2(v[1], v[0])


def _wrap(a: Any):
    return (a + math.pi) % (2 * math.pi) - math.pi


def _unit(a: Any):
    return np.array([math.cos(a), math.sin(a)])


def _cross(u: Any, v: Any):
    return float(u[0] * v[1] - u[1] * v[0])


def _topology(drawing: Any):
    """Mobility joints: one revolute per joint name (a compound hinge where more than
    two links meet), one prismatic pair per slider; the frame's joints."""
    for n, names in drawing.links.items():
        for j in names:
            if j not in drawing.joints:
                raise DrawingError(f"link {n} names joint '{j}', which the drawing does not "
                                   "place", "link", n)
    joints = pairs_of_links(drawing.frame, drawing.links, drawing.sliders)
    frame_joints = [j.name for j in joints if j.kind == "R" and drawing.frame in j.links]
    return joints, frame_joints


def pairs_of_links(frame: int, links: Any, sliders: Any = ()):
    """The kinematic pairs of a linkage given by the joints its links carry.

    Parameters
    ----------
    frame : int
    links : dict
        link number -> joint names it carries.  A name on two or more links is a
        revolute joining them (a compound hinge where more than two meet); a name on
        one link only is a pivot on the frame, unless the frame is listed itself.
    sliders : sequence of Slider (or records with ``block``, ``guide``, ``name``)
        One prismatic pair each.

    Returns
    -------
    list of :class:`~mechcli.core.grashof.mobility.Joint`
        The revolutes in order of first mention, then the prismatic pairs.

    Raises
    ------
    DrawingError
        A joint on one link only when the frame is listed (it joins nothing).
    """
    on: dict = {}
    for n, names in links.items():
        for j in names:
            on.setdefault(j, []).append(n)
    explicit = frame in links
    joints = []
    for j, on_links in on.items():
        if not explicit and frame not in on_links and len(on_links) == 1:
            on_links = [frame] + on_links            # a pivot of the frame
        if len(on_links) < 2:
            raise DrawingError(f"joint '{j}' is on link {on_links[0]} only: a joint joins "
                               "two links", "joint", j, lone=True)
        joints.append(Joint("R", tuple(on_links), j))
    for s in sliders:
        joints.append(Joint("P", (s.block, s.guide), s.name or f"{s.block}{s.guide}"))
    return joints


def from_drawing(drawing: Drawing) -> FromDrawing:
    """The engine's linkage for a drawing, its structure and its input angles.

    Raises
    ------
    DrawingError
        A name the drawing does not place, a mobility other than the number of
        drivers, a group the engine has no element for, a group drawn at its dead
        point, or lengths that do not close (the engine does not reproduce a joint).
    """
    joints, frame_joints = _topology(drawing)
    frame = drawing.frame
    mob = count_mobility(joints, frame)
    drivers = tuple(d for d, _ in drawing.drivers)
    if mob.F != len(drivers):
        raise DrawingError(f"the mobility is F = 3×{mob.n} − 2×{mob.P_L} = {mob.F}, "
                           f"but {len(drivers)} driver{'s' if len(drivers) != 1 else ''} "
                           f"{list(drivers)} {'is' if len(drivers) == 1 else 'are'} given",
                           "drivers")
    try:
        structure = decompose(joints, frame, drivers)
    except MobilityError as exc:
        raise DrawingError(str(exc), "drivers") from None
    b = _Builder(drawing, joints, frame_joints)
    for (link, pivot), group in zip(drawing.drivers, structure.groups):
        b.crank(link, pivot)
    for group in structure.groups[len(drivers):]:
        b.group(group)
    _check_actuators(drawing, b.elements)
    offsets = b.offsets()
    linkage = Linkage(frame, tuple(b.elements), angle_offsets=tuple(sorted(offsets.items())),
                      structure=structure)
    return FromDrawing(linkage, structure, dict(b.inputs), offsets, mob)


def _check_actuators(drawing: Any, elements: Any):
    """Every actuator names the slide of an RPR group (a cylinder between pivots)."""
    slides = {el.slide_names(drawing.frame)[0] for el in elements if type(el) is RPR}
    for link, name in drawing.actuators.items():
        if name not in slides:
            have = ", ".join(f"'{n}'" for n in sorted(slides)) or "none"
            raise DrawingError(f"the actuator '{name}' of driver {link} is not the slider of "
                               f"an RPR group (a cylinder between two pivots; those of "
                               f"this linkage: {have})", "driver", link)


class _Builder:
    """Elements added group by group, each checked on the engine at the drawing."""

    def __init__(self, drawing: Any, joints: Any, frame_joints: Any):
        self.d = drawing
        self.xy = {k: (float(v[0]), float(v[1])) for k, v in drawing.joints.items()}
        self.frame = drawing.frame
        self.elements: list = [Ground(j, *drawing.joints[j]) for j in frame_joints]
        self.known = set(frame_joints)           # joints the elements position
        self.links = {self.frame}
        self.inputs: dict = {}
        self.engine_angle = {self.frame: 0.0}
        sizes = [abs(v) for xy in drawing.joints.values() for v in xy]
        self.scale = max(sizes + [1e-300])
        self.hinges = {j.name: j.links for j in joints if j.kind == "R"}
        self.sliders = {frozenset((s.block, s.guide)): s for s in drawing.sliders}

    def _p(self, name: str):
        return np.array(self.xy[name], dtype=float)

    # -- the engine at the drawing -------------------------------------------
    def linkage(self):
        return Linkage(self.frame, tuple(self.elements))

    def _solve(self):
        lk = self.linkage()
        m = solve(lk, {k: DriverMotion(np.array([q])) for k, q in self.inputs.items()},
                  order=0)
        return m

    def _check(self, made_links: Any, group_name: Any):
        """Solve at the drawing: every known joint where drawn; the new links'
        engine angles; then the links' further joints as points on them."""
        m = self._solve()
        for j in sorted(self.known):
            p = m.points[j]
            x, y = float(np.ravel(p.x)[0]), float(np.ravel(p.y)[0])
            want = self.xy[j]
            err = math.hypot(x - want[0], y - want[1])
            if not math.isfinite(err) or err > CLOSE_TOL * self.scale:
                raise DrawingError(
                    f"the drawing does not close at joint '{j}' ({group_name}): its links' "
                    f"lengths put it at ({x:.6g}, {y:.6g}), drawn at ({want[0]:.6g}, "
                    f"{want[1]:.6g})", "joint", j)
        for n in made_links:
            self.engine_angle[n] = float(np.ravel(m.links[n].theta)[0])
        self._further_joints(made_links)

    def _further_joints(self, made_links: Any):
        for n in made_links:
            names = self.d.links.get(n, ())
            origin = next((j for j in names if j in self.known), None)
            if origin is None:
                continue
            th = self.engine_angle[n]
            o = self._p(origin)
            for j in names:
                if j in self.known:
                    continue
                r = self._p(j) - o
                c, s = math.cos(th), math.sin(th)
                along, normal = r[0] * c + r[1] * s, -r[0] * s + r[1] * c
                self.elements.append(PointOnLink(j, n, origin, along, normal))
                self.known.add(j)

    # -- drivers and groups ----------------------------------------------------
    def crank(self, link: int, pivot: Any):
        names = self.d.links.get(link, ())
        if pivot not in names:
            raise DrawingError(f"the crank's pivot '{pivot}' is not a joint of link {link} "
                               f"{list(names)}", "driver", link)
        if self.frame not in self.hinges.get(pivot, ()):
            raise DrawingError(f"the crank's pivot '{pivot}' is not on the frame "
                               f"{self.frame}", "driver", link)
        others = [j for j in names if j != pivot]
        if not others:
            raise DrawingError(f"link {link} has no joint besides its pivot '{pivot}'",
                               "driver", link)
        point = others[0]
        r = self._p(point) - self._p(pivot)
        length = math.hypot(*r)
        if length <= CLOSE_TOL * self.scale:
            raise DrawingError(f"the crank's joints '{pivot}' and '{point}' coincide",
                               "joint", point)
        self.elements.append(Crank(link, pivot, point, length,
                                   self.d.actuators.get(link)))
        self.inputs[link] = _angle(r)
        self.known.add(point)
        self.links.add(link)
        self._check((link,), f"crank {link}")

    def group(self, g: Any):
        kind = g.type
        if kind == "RRR":
            self._rrr(g)
        elif kind == "RRP":
            self._rrp(g)
        elif kind == "RPR":
            self._rpr(g)
        elif kind == "PRP":
            self._prp(g)
        elif (kind == "triad" and len(self.inputs) == 1
              and all(self._kind_of(j) == "R" for j in g.joints)):
            self._triad(g)
            return
        else:
            self._newton_group(g)
            return
        self.links.update(g.links)
        self._check(g.links, f"{kind} dyad of links {g.links[0]} and {g.links[1]}")

    def _kind_of(self, pair: Any):
        return "R" if pair in self.hinges else "P"

    def _triad(self, g: Any):
        """A ternary link held by three binary links: :class:`~.triad.Triad`, its
        Newton started from a continuation table made here from the drawing."""
        from mechcli.core.linkage.triad import Triad, continuation_table

        inner = [j for j in g.joints if not any(k in self.links for k in self.hinges[j])]
        count = {n: sum(1 for j in inner if n in self.hinges[j]) for n in g.links}
        tern = next(n for n in g.links if count[n] == 3)
        order = [j for j in self.d.links.get(tern, ()) if j in inner]
        binaries, points = [], []
        for j in order:
            b = next(k for k in self.hinges[j] if k in g.links and k != tern)
            outer = next(o for o in self.d.links.get(b, ()) if o != j)
            binaries.append(b)
            points.append(outer)
        p1, p2, p3 = (self._p(j) for j in order)
        e = p2 - p1
        c = float(np.hypot(*e))
        u = e / c
        rel = p3 - p1
        bp, bq = float(rel @ u), float(_cross(u, rel))
        lengths = [float(np.hypot(*(self._p(j) - self._p(o)))) for j, o in zip(order, points)]
        (driver, q0), = self.inputs.items()
        pose0 = (float(p1[0]), float(p1[1]), _angle(e))
        proto = Triad(tern, *order, *binaries, *points, *lengths, c, bp, bq,  # type: ignore[call-arg]
                      driver)  # (the star-args are three each: mypy cannot count them)
        lk = self.linkage()

        def known(q: Any):
            m = solve(lk, {driver: DriverMotion(np.asarray(q, dtype=float))}, order=0)
            return [m.points[p] for p in points]

        table, period = continuation_table(proto, known, q0, pose0)
        import dataclasses
        self.elements.append(dataclasses.replace(proto, table=table, period=period))
        self.known.update(order)
        self.links.update(g.links)
        self._check(g.links, f"triad of links {', '.join(map(str, g.links))}")

    def _newton_group(self, g: Any) -> None:
        """A group with no closed form (a triad with sliders, class IV and up, an RPP
        dyad, a triad under two drivers): :class:`~.newton_group.NewtonGroup`, each
        link a body with the drawing's first joint as origin and its first-to-second
        joint direction as reference angle (a slider's block: the line's direction, so
        that the statics sees its pair's normal), started by continuation."""
        from mechcli.core.linkage.newton_group import NewtonGroup

        sliders = [self._named(j) for j in g.joints if self._kind_of(j) == "P"]
        fr = _Bodies(self, list(g.links))
        line_of = fr.orient(sliders)
        pins = self._group_pins(g, fr)
        slides = [self._group_slide(s, line_link, fr) for s, line_link in zip(sliders, line_of)]
        (driver, _q0), *_rest = self.inputs.items()
        ends = tuple((names[0], names[1] if len(names) > 1 else "")
                     for names in (tuple(self.d.links.get(ln, ())) for ln in fr.links))
        proto = NewtonGroup(tuple(fr.links), tuple(pins), tuple(slides), tuple(fr.known),
                            driver, ends, g.type)
        self._start_group(g, proto, fr.pose())

    def _group_pins(self, g: Any, fr: _Bodies) -> list:
        """The group's revolute pairs as :attr:`NewtonGroup.pins`: at a known joint, each
        group link there pinned to it; inside the group, the first link's point pinned to
        each other's."""
        pins = []
        for j in g.joints:
            if self._kind_of(j) != "R":
                continue
            at = [k for k in self.hinges[j] if k in fr.idx]
            p = self._p(j)
            if any(k in self.links for k in self.hinges[j]):
                if j not in self.known:  # pragma: no cover - a known link's joints are known
                    raise DrawingError(f"joint '{j}' is not positioned", "joint", j)
                pins += [(j,) + fr.end(k, p) + (-1, 0.0, 0.0) for k in at]
            else:
                a = fr.end(at[0], p)
                pins += [(j,) + a + fr.end(k, p) for k in at[1:]]
        return pins

    def _group_slide(self, s: Slider, line_link: int, fr: _Bodies) -> tuple:
        """One prismatic pair as a :attr:`NewtonGroup.slides` entry: the block's point (its
        first revolute joint as drawn) kept at its drawn offset from the guide's line."""
        blk, gd = s.block, s.guide
        p0, t = self._line(s)
        names = list(self.d.links.get(blk, ())) + list(self.d.links.get(gd, ()))
        pt = next((j for j in names if j in self.hinges), s.through)
        p = self._p(pt)
        h0 = float(-t[1] * (p[0] - p0[0]) + t[0] * (p[1] - p0[1]))
        a, b = fr.end(blk, p), fr.end(gd, p0)
        beta = _wrap(s.angle - fr.angle_of(gd))
        c0 = _wrap(fr.angle_of(blk) - fr.angle_of(gd))
        roles = (gd, blk) if line_link == blk else (blk, gd)   # (guide, block): statics
        name = _slide_symbol(s.name, blk, gd, self.frame)
        return (name, pt) + a + b + (float(beta), h0, float(c0), roles[1], roles[0])

    def _start_group(self, g: Any, proto: Any, pose0: list) -> None:
        """Refuse a group drawn at its dead point; continue it from the drawing over the
        primary driver's turn (secondary drivers geared to it); add it and check it."""
        from mechcli.core.linkage.newton_group import (
            best_conditioning,
            continuation_table,
            drawn_conditioning,
        )

        (driver, q0), *rest = self.inputs.items()
        lk = self.linkage()
        follow = {}
        for k, qk in rest:
            ratio, phase = self.d.followers.get(k, (1.0, None))
            follow[k] = (ratio, qk - ratio * q0 if phase is None else phase)

        def known_motion(q: Any) -> Any:
            q = np.asarray(q, dtype=float)
            ins = {driver: DriverMotion(q)}
            ins.update({k: DriverMotion(r * q + ph) for k, (r, ph) in follow.items()})
            return solve(lk, ins, order=0)

        named = f"{g.type} of links {', '.join(map(str, g.links))}"
        at_drawing = drawn_conditioning(proto, known_motion(np.array([q0])), pose0,
                                        self.scale, self.frame)
        if at_drawing < TOGGLE_TOL:
            raise DrawingError(f"the {named} is drawn at its dead point (its Jacobian is "
                               f"singular there): the drawing fixes no assembly branch; draw "
                               f"it off the dead point", "link", g.links[0])
        try:
            table, period = continuation_table(proto, known_motion, q0, pose0, self.scale,
                                               self.frame)
        except ValueError as exc:
            raise DrawingError(f"the {named}: {exc}", "link", g.links[0]) from None
        well = best_conditioning(proto, known_motion(table[0]), table, self.scale, self.frame)
        self.elements.append(dataclasses.replace(proto, table=table, period=period, well=well))
        self.known.update(proto.inner_joints)
        self.links.update(g.links)
        self._check(g.links, named)

    def _named(self, pair: Any):
        """The slider whose prismatic pair the decomposition calls *pair*."""
        return next(sl for sl in self.d.sliders
                    if (sl.name or f"{sl.block}{sl.guide}") == pair)

    def _line(self, s: Any):
        """The slider's line: a point on it and its unit direction, as drawn."""
        return self._p(s.through), _unit(s.angle)

    def _branch_sign(self, value: Any, joint: Any, what: Any):
        if abs(value) <= TOGGLE_TOL * self.scale * self.scale:
            raise DrawingError(f"the {what} at joint '{joint}' is drawn at its dead point "
                               f"(its two links in line): the drawing fixes no assembly "
                               f"branch; draw it off the toggle", "joint", joint)
        return 1 if value > 0 else -1

    def _rrr(self, g: Any):
        (a, b), (oa, ji, ob) = g.links, g.joints
        pa, pj, pb = self._p(oa), self._p(ji), self._p(ob)
        br = self._branch_sign(_cross(pb - pa, pj - pa), ji, "RRR dyad")
        self.elements.append(RRR(ji, oa, a, float(np.hypot(*(pj - pa))), ob, b,
                                 float(np.hypot(*(pj - pb))), br))
        self.known.add(ji)

    def _guide_frame(self, guide: Any, s: Any):
        """(guide_point, guide_angle, offset) of a line of sliding fixed on ``guide``."""
        p0, u = self._line(s)
        n = np.array([-u[1], u[0]])
        if guide == self.frame:
            if s.through in self.known:   # a frame pivot on the line
                gp = s.through
            else:                         # a point of the frame on the line
                gp = f"{s.through}_{guide}"
                if gp not in self.known:
                    self.elements.append(Ground(gp, float(p0[0]), float(p0[1])))
                    self.known.add(gp)
                    self.xy[gp] = (float(p0[0]), float(p0[1]))
            return gp, s.angle, 0.0
        names = self.d.links.get(guide, ())
        gp = next((j for j in names if j in self.known), None)
        if gp is None:
            raise DrawingError(f"the guide link {guide} of a slider has no known joint to "
                               f"carry its line of sliding", "link", guide)
        offset = float((p0 - self._p(gp)) @ n)
        return gp, _wrap(s.angle - self.engine_angle[guide]), offset

    def _rrp(self, g: Any):
        (a, b), (oa, ji, op) = g.links, g.joints
        s = self._named(op)
        guide = s.guide if s.block == b else s.block
        p0, u = self._line(s)
        pa, pj = self._p(oa), self._p(ji)
        n = np.array([-u[1], u[0]])
        if abs(float((pj - p0) @ n)) > CLOSE_TOL * self.scale:
            raise DrawingError(f"joint '{ji}' of the slider block {b} is not on its line of "
                               f"sliding (through '{s.through}')", "joint", ji)
        foot = p0 + float((pa - p0) @ u) * u
        br = self._branch_sign(float((pj - foot) @ u) * self.scale, ji, "RRP dyad")
        gp, gang, off = self._guide_frame(guide, s)
        self.elements.append(RRP(ji, oa, a, float(np.hypot(*(pj - pa))), b, guide, gp, gang,
                                 off, br, s.name))
        self.known.add(ji)

    def _rpr(self, g: Any):
        # RPR: the block's pin (outer R), the block-guide slide (inner P), the guide's
        # pivot (outer R); which link is the block the slider says
        a, (oa, ip, ob) = g.links[0], g.joints
        s = self._named(ip)
        blk, guide = s.block, s.guide
        op, oc = (oa, ob) if a == blk else (ob, oa)
        p0, u = self._line(s)
        n = np.array([-u[1], u[0]])
        pp, pc = self._p(op), self._p(oc)
        if abs(float((pp - p0) @ n)) > CLOSE_TOL * self.scale:
            raise DrawingError(f"joint '{op}' of the block {blk} is not on its line of "
                               f"sliding (through '{s.through}')", "joint", op)
        br = self._branch_sign(float((pp - pc) @ u) * self.scale, op, "RPR dyad")
        offset = float((p0 - pc) @ n)
        self.elements.append(RPR(op, blk, oc, guide, offset, br, s.name))

    def _prp(self, g: Any):
        (a, b), (oa, ji, ob) = g.links, g.joints
        keys = {}
        for x, pair, blk in (("a", oa, a), ("b", ob, b)):
            sl = self._named(pair)
            guide = sl.guide if sl.block == blk else sl.block
            gp, gang, off = self._guide_frame(guide, sl)
            keys.update({f"slider_{x}": blk, f"guide_link_{x}": guide,
                         f"guide_point_{x}": gp, f"guide_angle_{x}": gang,
                         f"offset_{x}": off, f"name_{x}": sl.name})
        self.elements.append(PRP(ji, **keys))
        self.known.add(ji)

    def offsets(self):
        """Spec angle (first -> second joint) minus the engine's, where they differ."""
        out = {}
        for n, names in self.d.links.items():
            if n == self.frame or len(names) < 2 or n not in self.engine_angle:
                continue
            spec = _angle(self._p(names[1]) - self._p(names[0]))
            off = _wrap(spec - self.engine_angle[n])
            if abs(off) > 1e-12:
                out[n] = off
        return out


class _Bodies:
    """The bodies of a Newton-solved group as drawn: each link's origin (its first joint)
    and reference angle (first to second joint, or the line of a slider it carries), and
    the known links its pairs refer to (:attr:`NewtonGroup.known`)."""

    def __init__(self, b: _Builder, links: list) -> None:
        self.b, self.links = b, links
        self.idx = {ln: i for i, ln in enumerate(links)}
        self.angle: dict = {}
        self.origin: dict = {}
        self.known: list = []

    def orient(self, sliders: list) -> list:
        """Give each slider's line to one of its group links (that link's angle is then
        the line's); the links' origins and other angles from the drawing.  Returns the
        link of each slider that carries its line."""
        b, line_of = self.b, []
        for s in sliders:
            mine = [ln for ln in (s.block, s.guide) if ln in self.idx]
            free = [ln for ln in mine if ln not in self.angle]
            if free:
                self.angle[free[0]] = s.angle
                line_of.append(free[0])
                continue
            turn = abs(_wrap(self.angle[mine[0]] - s.angle))
            if min(turn, math.pi - turn) > 1e-9:
                raise DrawingError(f"link {mine[0]} slides along two lines that are not "
                                   f"parallel; the joints form solves a group whose blocks "
                                   f"each slide along one direction", "link", mine[0])
            line_of.append(mine[0])
        for ln in self.links:
            names = b.d.links.get(ln, ())
            self.origin[ln] = tuple(b._p(names[0]))
            if ln not in self.angle:
                self.angle[ln] = _angle(b._p(names[1]) - b._p(names[0])) \
                    if len(names) > 1 else 0.0
        return line_of

    def end(self, ln: int, p: Any) -> tuple:
        """(body index, local x, local y) of the drawn point p fixed on link ln (a known
        link: index -1 - k of :attr:`known`)."""
        from mechcli.core.linkage.newton_group import local

        b = self.b
        if ln in self.idx:
            return (self.idx[ln],) + local(self.origin[ln], self.angle[ln], p)
        if ln == b.frame:
            key: tuple = (ln, "")
            o, th = (0.0, 0.0), 0.0
        else:
            o_name = next(j for j in b.d.links.get(ln, ()) if j in b.known)
            key, o, th = (ln, o_name), b.xy[o_name], b.engine_angle[ln]
        if key not in self.known:
            self.known.append(key)
        return (-1 - self.known.index(key),) + local(o, th, p)

    def angle_of(self, ln: int) -> float:
        return self.angle[ln] if ln in self.idx else self.b.engine_angle.get(ln, 0.0)

    def pose(self) -> list:
        """The drawn poses ``(x, y, θ)`` of the bodies, in order (the table's start)."""
        out: list = []
        for ln in self.links:
            out += [self.origin[ln][0], self.origin[ln][1], self.angle[ln]]
        return out
