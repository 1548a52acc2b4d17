"""CAD files of the geometry a command draws: ``--export dxf,svg``.

A :class:`Sketch` holds closed or open polylines and circles, each on a named layer
(one layer per kind of line: ``PROFILE``, ``PITCH``, ``OUTLINE``, ``LINKS``, ``PINS``,
``COUPLER_CURVE`` ...), in the spec's length unit.  :func:`dxf_bytes` writes it with
ezdxf (the ``cad`` extra, imported only here, inside the function) with the unit in the
header (``$INSUNITS``, ``$MEASUREMENT``); :func:`svg_text` writes it directly (no
dependency): the same layers as groups, coordinates in the spec's unit, a ``viewBox``
holding the part and the physical size in ``width``/``height``.  :func:`write` puts
both into the run's :class:`~mechcli.report.files.Outputs` (atomic, in the manifest).

The builders take the arrays the command's CSV and pictures draw, never a second
computation of them: :func:`cam_sketch` (the profile's pitch and working curves),
:func:`gear_sketch` / :func:`pair_sketch` (the outlines of ``core.gear.profile``),
:func:`linkage_sketch` (the elements' ``sketch()`` primitives at one pose of the
engine, and the traced points over the sweep).  They call no solver: the command
poses the linkage and outlines the gears (the layer contract of
``tests/unit/test_layering.py``).  See docs/cad.md.
"""

from __future__ import annotations

import math

import numpy as np

#: DXF ``$INSUNITS`` of each spec unit (AutoCAD's codes: 1 inch, 4 mm, 5 cm, 6 m)
INSUNITS = {"in": 1, "mm": 4, "cm": 5, "m": 6}
#: a spec unit -> (SVG's unit for width/height, its size in that unit)
_SVG_UNIT = {"mm": ("mm", 1.0), "cm": ("cm", 1.0), "in": ("in", 1.0), "m": ("mm", 1000.0)}

#: layer -> (AutoCAD colour index, SVG stroke colour, what it holds); the order in files
LAYERS = {
    "PROFILE": (5, "#1f4fbf", "cam working (actual) profile, closed"),
    "PITCH": (1, "#d62728", "cam pitch curve (the roller centre's path), closed"),
    "BASE_CIRCLE": (3, "#2ca02c", "base circle"),
    "PRIME_CIRCLE": (4, "#17becf", "cam prime circle (r0 of the pitch curve)"),
    "OFFSET_CIRCLE": (8, "#7f7f7f", "cam offset circle (radius |e|)"),
    "FOLLOWER": (6, "#9467bd", "the follower's roller or flat face at cam angle 0"),
    "OUTLINE": (7, "#000000", "gear outline: every tooth, fillets as generated, closed"),
    "INVOLUTE": (5, "#1f4fbf", "involute curve"),
    "REFERENCE_CIRCLE": (3, "#2ca02c", "gear reference circle"),
    "TIP_CIRCLE": (1, "#d62728", "gear tip circle"),
    "ROOT_CIRCLE": (5, "#1f4fbf", "gear root circle"),
    "PITCH_CIRCLE": (3, "#2ca02c", "operating pitch circles of a pair"),
    "LINE_OF_ACTION": (6, "#9467bd", "line of action N1N2 of a pair"),
    "LINKS": (5, "#1f4fbf", "each moving link's outline at the drawn input, closed"),
    "SLIDERS": (30, "#ff7f0e", "slider blocks at the drawn input, closed"),
    "GUIDES": (8, "#7f7f7f", "guide lines of prismatic pairs"),
    "CENTRE_LINES": (8, "#7f7f7f", "link centre lines, joint to joint"),
    "PINS": (7, "#000000", "a circle at every joint and traced point"),
    "COUPLER_CURVE": (1, "#d62728", "paths of the traced points over the sweep"),
}


class Sketch:
    """Polylines and circles on layers, in one length unit (the spec's).

    Parameters
    ----------
    unit : str
        The spec's length unit (a key of :data:`INSUNITS`).
    title : str
        The spec's title (the SVG's ``<title>``).
    """

    def __init__(self, unit, title=""):
        self.unit, self.title = unit, title
        self.items = []   # (layer, "polyline", (n, 2) array, closed) / (layer, "circle", ...)

    def polyline(self, layer, x, y, closed=False):
        """A polyline through the points (x, y); *closed*: joined back to its first
        point (a repeated last point is dropped).  Consecutive points that coincide
        (a jump's two samples at one cam angle) are written once."""
        pts = np.column_stack([np.asarray(x, dtype=float).ravel(),
                               np.asarray(y, dtype=float).ravel()])
        pts = pts[np.all(np.isfinite(pts), axis=1)]
        if len(pts) < 2:
            return
        size = float(np.max(np.ptp(pts, axis=0))) or 1.0
        step = np.hypot(*np.diff(pts, axis=0).T)
        pts = pts[np.concatenate([[True], step > 1e-12 * size])]
        if closed and len(pts) > 2 and math.hypot(*(pts[-1] - pts[0])) <= 1e-12 * size:
            pts = pts[:-1]
        if len(pts) >= 2:
            self.items.append((layer, "polyline", pts, bool(closed and len(pts) > 2)))

    def circle(self, layer, cx, cy, r):
        if r > 0 and math.isfinite(r):
            self.items.append((layer, "circle", (float(cx), float(cy), float(r)), True))

    def bounds(self):
        """``(xmin, ymin, xmax, ymax)`` of everything drawn."""
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for _layer, kind, data, _closed in self.items:
            if kind == "polyline":
                lo, hi = np.minimum(lo, data.min(axis=0)), np.maximum(hi, data.max(axis=0))
            else:
                cx, cy, r = data
                lo = np.minimum(lo, (cx - r, cy - r))
                hi = np.maximum(hi, (cx + r, cy + r))
        if not np.all(np.isfinite(lo)):
            return (0.0, 0.0, 1.0, 1.0)
        return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))

    def layers(self):
        """The layers used, in :data:`LAYERS`' order."""
        used = {item[0] for item in self.items}
        return [name for name in LAYERS if name in used]


def dxf_bytes(sketch):
    """The sketch as an ASCII DXF (R2010) made with ezdxf: LWPOLYLINEs (closed ones
    flagged closed) and CIRCLEs on one layer per kind of line, ``$INSUNITS`` and
    ``$MEASUREMENT`` from the spec's unit, the extents in ``$EXTMIN``/``$EXTMAX``.
    Coordinates are written as ezdxf writes doubles (round-trip exact)."""
    import io

    import ezdxf

    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = INSUNITS[sketch.unit]
    doc.header["$MEASUREMENT"] = 0 if sketch.unit == "in" else 1
    x0, y0, x1, y1 = sketch.bounds()
    doc.header["$EXTMIN"] = (x0, y0, 0.0)
    doc.header["$EXTMAX"] = (x1, y1, 0.0)
    for name in sketch.layers():
        layer = doc.layers.add(name, color=LAYERS[name][0])
        try:
            layer.description = LAYERS[name][2]
        except AttributeError:   # (an ezdxf without layer descriptions)
            pass
    msp = doc.modelspace()
    for layer, kind, data, closed in sketch.items:
        if kind == "polyline":
            msp.add_lwpolyline(data.tolist(), format="xy", close=closed,
                               dxfattribs={"layer": layer})
        else:
            cx, cy, r = data
            msp.add_circle((cx, cy), r, dxfattribs={"layer": layer})
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode("utf-8")   # R2010: UTF-8; every name is ASCII


def _xml(text):
    return (str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;"))


def svg_text(sketch, digits=10):
    """The sketch as SVG 1.1, written directly: one group per layer (an Inkscape
    layer of the same name), coordinates in the spec's unit to *digits* significant
    digits (the CSV's ``--digits``), y up (each layer is drawn ``scale(1,-1)``, so
    the file's numbers are the model's).  The ``viewBox`` holds the part with a 2 %
    margin and ``width``/``height`` give it its physical size (metres as mm)."""
    def f(v):
        return f"{v:.{digits}g}"

    x0, y0, x1, y1 = sketch.bounds()
    size = max(x1 - x0, y1 - y0) or 1.0
    pad = 0.02 * size
    w, h = x1 - x0 + 2 * pad, y1 - y0 + 2 * pad
    unit, k = _SVG_UNIT[sketch.unit]
    stroke = f(size / 500)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<svg xmlns="http://www.w3.org/2000/svg" version="1.1" '
           'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
           f'width="{f(w * k)}{unit}" height="{f(h * k)}{unit}" '
           f'viewBox="{f(x0 - pad)} {f(-(y1 + pad))} {f(w)} {f(h)}">',
           f"<title>{_xml(sketch.title)}</title>",
           f"<desc>mechcli --export: units {sketch.unit}; y up (each layer is "
           "scale(1,-1))</desc>"]
    for name in sketch.layers():
        out.append(f'<g id="{name}" inkscape:groupmode="layer" inkscape:label="{name}" '
                   f'transform="scale(1,-1)" fill="none" stroke="{LAYERS[name][1]}" '
                   f'stroke-width="{stroke}" stroke-linejoin="round">')
        for layer, kind, data, closed in sketch.items:
            if layer != name:
                continue
            if kind == "polyline":
                pts = " ".join(f"{f(x)},{f(y)}" for x, y in data)
                out.append(f'<{"polygon" if closed else "polyline"} points="{pts}"/>')
            else:
                cx, cy, r = data
                out.append(f'<circle cx="{f(cx)}" cy="{f(cy)}" r="{f(r)}"/>')
        out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write(outputs, stem, sketch, formats):
    """Write ``<stem>.dxf`` / ``<stem>.svg`` (*formats*) into the run's outputs."""
    for fmt in formats:
        if fmt == "dxf":
            outputs.bytes(f"{stem}.dxf", dxf_bytes(sketch))
        elif fmt == "svg":
            outputs.text(f"{stem}.svg", svg_text(sketch, outputs.digits))


def _circle_points(cx, cy, r, n=361):
    t = np.linspace(0.0, 2 * np.pi, n)
    return cx + r * np.cos(t), cy + r * np.sin(t)


# -- cam ---------------------------------------------------------------------------
def cam_sketch(cs, design, outline):
    """The disc cam in the cam frame at δ = 0 (as ``profile.png`` draws it).

    ``PROFILE``: *outline*, the working curve as ``profile.png`` draws it
    (``core.cam.geometry.working_outline``: cam.csv's ``x_work``/``y_work`` at the
    profile's sampling, with a roller's arcs at concave pitch corners and cuts at convex
    ones); ``PITCH``: cam.csv's ``x_pitch``/``y_pitch`` (roller followers: the
    roller centre's path); ``PRIME_CIRCLE``: r0 of the pitch curve (roller);
    ``BASE_CIRCLE``: the working profile's base circle (r0 − rr for a roller, r0
    otherwise); ``OFFSET_CIRCLE``: |e| of an offset translating follower;
    ``FOLLOWER``: the roller (radius rr about the pitch curve's first point) or the
    flat face at δ = 0 (through the contact point, across the contact offsets of a
    revolution).
    """
    p, fol, u = design.profile, design.follower, cs.header.scale
    sk = Sketch(cs.header.unit, cs.header.title)
    sk.polyline("PROFILE", outline[0] / u, outline[1] / u, closed=True)
    if p.pitch is not None and fol.contact == "roller":
        sk.polyline("PITCH", p.pitch[0] / u, p.pitch[1] / u, closed=True)
        sk.circle("PRIME_CIRCLE", 0.0, 0.0, fol.r0 / u)
        sk.circle("BASE_CIRCLE", 0.0, 0.0, (fol.r0 - fol.rr) / u)
        sk.circle("FOLLOWER", p.pitch[0][0] / u, p.pitch[1][0] / u, fol.rr / u)
    else:
        sk.circle("BASE_CIRCLE", 0.0, 0.0, fol.r0 / u)
    if fol.motion == "translating" and fol.e != 0 and fol.contact != "flat":
        sk.circle("OFFSET_CIRCLE", 0.0, 0.0, abs(fol.e) / u)
    if p.face_offset is not None:
        c, n = p.work[:, 0], p.normal[:, 0]
        t = np.array([n[1], -n[0]])   # along the face, as the offset is counted
        ends = [c + (o - p.face_offset[0]) * t
                for o in (float(np.min(p.face_offset)), float(np.max(p.face_offset)))]
        sk.polyline("FOLLOWER", [e[0] / u for e in ends], [e[1] / u for e in ends])
    return sk


# -- gear --------------------------------------------------------------------------
def gear_sketch(g, outline, spec, centre=(0.0, 0.0), rotation=0.0, sketch=None,
                circles=True):
    """One gear: ``OUTLINE`` (a :class:`~mechcli.core.gear.profile.GearOutline`, the
    arrays gear.csv holds for a spur gear), and its tip, reference, base and root
    circles, turned by *rotation* [rad] about its centre and moved to *centre* [m]."""
    sc = spec.header.scale
    sk = sketch or Sketch(spec.header.unit, spec.header.title)
    c, s = math.cos(rotation), math.sin(rotation)
    x = c * np.asarray(outline.x) - s * np.asarray(outline.y) + centre[0]
    y = s * np.asarray(outline.x) + c * np.asarray(outline.y) + centre[1]
    sk.polyline("OUTLINE", x / sc, y / sc, closed=True)
    if circles:
        for layer, r in (("TIP_CIRCLE", g.ra), ("REFERENCE_CIRCLE", g.r),
                         ("BASE_CIRCLE", g.rb), ("ROOT_CIRCLE", g.rf)):
            sk.circle(layer, centre[0] / sc, centre[1] / sc, r / sc)
    return sk


def pair_sketch(pair, outlines, rotation2, spec):
    """A pair in mesh at its centre distance a', as ``pair.png`` draws it: the pinion
    at the origin with a tooth on +y, the wheel's centre at (0, a') (a ring's at
    (0, −a')) turned by *rotation2*; their ``OUTLINE``, operating ``PITCH_CIRCLE``,
    ``BASE_CIRCLE`` and the ``LINE_OF_ACTION`` N1N2."""
    sc = spec.header.scale
    g1, g2 = pair.g1, pair.g2
    c2 = -pair.a_w if g2.internal else pair.a_w
    sk = gear_sketch(g1, outlines[0], spec, circles=False)
    gear_sketch(g2, outlines[1], spec, (0.0, c2), rotation2, sk, circles=False)
    for layer, r1, r2 in (("PITCH_CIRCLE", pair.dw1 / 2, pair.dw2 / 2),
                          ("BASE_CIRCLE", g1.rb, g2.rb)):
        sk.circle(layer, 0.0, 0.0, r1 / sc)
        sk.circle(layer, 0.0, c2 / sc, r2 / sc)
    aw = pair.alpha_w
    foot = np.array([math.sin(aw), math.cos(aw)])
    n1 = g1.rb * foot
    n2 = np.array([0.0, c2]) + g2.rb * (foot if g2.internal else -foot)
    sk.polyline("LINE_OF_ACTION", [n1[0] / sc, n2[0] / sc], [n1[1] / sc, n2[1] / sc])
    return sk


def involute_sketch(sol, spec):
    """【例 5-1】: the involute (curve.csv's x, y) and its base circle."""
    sc = spec.header.scale
    sk = Sketch(spec.header.unit, spec.header.title)
    _r, _th, x, y = sol["curve"]
    sk.polyline("INVOLUTE", np.asarray(x) / sc, np.asarray(y) / sc)
    sk.circle("BASE_CIRCLE", 0.0, 0.0, spec.problem.rb / sc)
    return sk


# -- linkages ----------------------------------------------------------------------
def _element_links(el, frame):
    """``[(primitive, link)]`` of an element's bars: the link a bar is part of (as
    ``report.kin_plots`` assigns them; and a triad's binary links ``link_k``, pinned
    at its known points ``point_k``, apart from its ternary ``link``)."""
    out = []
    binary = {getattr(el, f"point_{i}"): getattr(el, f"link_{i}") for i in (1, 2, 3)
              if hasattr(el, f"point_{i}") and hasattr(el, f"link_{i}")}
    for prim in el.sketch(frame):
        if type(prim).__name__ != "Bar":
            continue
        if prim.a in binary or prim.b in binary:
            out.append((prim, binary.get(prim.a, binary.get(prim.b))))
        elif hasattr(el, "link_a") and prim.a == getattr(el, "point_a", None):
            out.append((prim, el.link_a))
        elif hasattr(el, "link_b") and prim.a == getattr(el, "point_b", None):
            out.append((prim, el.link_b))
        else:
            out.append((prim, getattr(el, "link", None)))
    return out


def _hull(points):
    """Convex hull (counter-clockwise, Andrew's monotone chain) of (n, 2) points."""
    pts = np.unique(points, axis=0)
    if len(pts) < 3:
        return pts

    def half(seq):
        h = []
        for p in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (p[1] - h[-2][1])
                                   - (h[-1][1] - h[-2][1]) * (p[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(p)
        return h
    lower, upper = half(pts), half(pts[::-1])
    return np.array(lower[:-1] + upper[:-1])


def _outline_round(centres, radius, step=math.radians(5.0)):
    """The closed outline of a plate round *centres* (complex) at *radius*: the
    convex hull of circles about each (a stadium for two, a rounded triangle for three)."""
    t = np.arange(0.0, 2 * np.pi, step)
    ring = radius * np.exp(1j * t)
    pts = np.concatenate([c + ring for c in centres])
    return _hull(np.column_stack([pts.real, pts.imag]))


def linkage_sketch(linkage, pose, sweep_motion, scale, unit, title="", curves=(),
                   guide_length=None, index=0, feasible=None):
    """A linkage at one input (*pose*: the engine's motion there, position *index*;
    None: not drawn, only the paths),
    drawn with the elements' ``sketch()`` primitives, and the traced points' paths.

    ``LINKS``: each moving link as a plate round its joints (the convex hull of
    circles of radius s/2 about them: a stadium for a bar, a rounded polygon for a
    coupler with a traced point), s = 0.06 × the linkage's extent over the sweep (the
    size of the blocks of ``kin.png``); a link carrying a guide includes the guide's
    drawn ends (a slotted guide bar).  ``PINS``: a circle of radius s/5 at every joint
    and traced point (a hole for a pin or a pen).  ``CENTRE_LINES``: the bars joint to
    joint.  ``SLIDERS``: each block, 2.8 s × 1.4 s turned with its link; ``GUIDES``:
    the guide lines as ``kin.png`` draws them.  ``COUPLER_CURVE``: *curves*, a list of
    complex arrays [m] (one per run of the sweep; closed when it returns to its start).
    Lengths in the model are metres; the file is in *unit* (*scale* metres each).
    *sweep_motion*: the engine's motion over the sweep (the size of the drawing and
    the guides' reach), at its *feasible* positions only when given (a mask).
    """
    k = 1.0 / scale
    sk = Sketch(unit, title)
    if feasible is not None:
        sweep_motion = _Feasible(sweep_motion, np.asarray(feasible, dtype=bool))
    allp = np.concatenate([np.asarray(pm.p).ravel() for pm in sweep_motion.points.values()])
    allp = allp[np.isfinite(allp)]
    extent = max(float(np.ptp(allp.real)), float(np.ptp(allp.imag)), 1e-300) \
        if allp.size else 1.0
    if pose is not None:
        _links(sk, linkage, pose, index, sweep_motion, 0.06 * extent, k, guide_length)
    for curve in curves:
        z = np.asarray(curve)
        closed = z.size > 2 and abs(z[-1] - z[0]) <= 1e-9 * extent
        sk.polyline("COUPLER_CURVE", z.real * k, z.imag * k, closed=closed)
    return sk


class _Feasible:
    """The points and slides of a motion at its feasible positions (the engine leaves
    zeros at the others)."""

    def __init__(self, motion, ok):
        import types

        def pick(v):
            v = np.asarray(v)
            return v[np.broadcast_to(ok, v.shape)] if v.ndim else v
        self.points = {n: types.SimpleNamespace(p=pick(pm.p)) for n, pm in motion.points.items()}
        self.slides = {n: types.SimpleNamespace(s=pick(sl.s)) for n, sl in motion.slides.items()}


def _links(sk, linkage, pose, index, sweep_motion, size, k, guide_length):
    """The LINKS, PINS, CENTRE_LINES, SLIDERS and GUIDES of :func:`linkage_sketch`."""
    frame = linkage.frame
    P = {n: complex(pm.p[index]) for n, pm in pose.points.items()}
    bodies = {}
    prims = [p for el in linkage.elements for p in el.sketch(frame)]
    for el in linkage.elements:
        for bar, link in _element_links(el, frame):
            if bar.a in P and bar.b in P:
                sk.polyline("CENTRE_LINES", [P[bar.a].real * k, P[bar.b].real * k],
                            [P[bar.a].imag * k, P[bar.b].imag * k])
            if link is None or link == frame:
                continue
            pts = bodies.setdefault(link, [])
            for n in (bar.a, bar.b):
                if n not in pts and n in P:
                    pts.append(n)
    centres = {ln: [P[n] for n in pts] for ln, pts in bodies.items()}
    for g in (p for p in prims if type(p).__name__ == "Guide"):
        th = float(pose.links[g.link].theta[index]) + g.angle
        u = complex(math.cos(th), math.sin(th))
        c = P[g.point] + g.offset * 1j * u
        s = (np.asarray(sweep_motion.slides[g.slide].s, dtype=float)
             if g.slide in sweep_motion.slides else None)
        if g.ray:
            reach = guide_length or (1.15 * float(np.nanmax(np.abs(s))) if s is not None
                                     else 8 * size)
            ends = [c, c + reach * u * g.branch]
        else:
            span = 8 * size
            lo, hi = ((float(np.nanmin(s)) - span, float(np.nanmax(s)) + span)
                      if s is not None else (-span, span))
            ends = [c + lo * u, c + hi * u]
        sk.polyline("GUIDES", [e.real * k for e in ends], [e.imag * k for e in ends])
        if g.link != frame:
            centres.setdefault(g.link, []).extend(ends)
    for ln in sorted(centres):
        if centres[ln]:
            o = _outline_round(centres[ln], size / 2)
            sk.polyline("LINKS", o[:, 0] * k, o[:, 1] * k, closed=True)
    for b in (p for p in prims if type(p).__name__ == "Block"):
        th = 0.0 if b.link is None else float(pose.links[b.link].theta[index])
        u = complex(math.cos(th), math.sin(th)) * size
        corners = [P[b.point] + z * u for z in (-1.4 - 0.7j, 1.4 - 0.7j, 1.4 + 0.7j,
                                                -1.4 + 0.7j)]
        sk.polyline("SLIDERS", [c.real * k for c in corners], [c.imag * k for c in corners],
                    closed=True)
    for n in sorted(P):
        sk.circle("PINS", P[n].real * k, P[n].imag * k, size / 5 * k)


def runs_of(points, runs):
    """The path of a traced point split at the sweep's gaps: one array per run
    (``SweepResult.runs``, as the pictures break their curves)."""
    p = np.asarray(points)
    if not runs:
        return [p]
    return [p[i0:i1] for i0, i1 in runs]
