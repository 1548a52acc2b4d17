"""``--export dxf,svg`` (issue 33 §1): the CAD files lie on the points the CSV holds.

Each DXF is read back with ezdxf (the ``cad`` extra; these tests are skipped without
it, the SVG and refusal tests are not) and compared with the run's own CSV to the
CSV's digits (10 significant: ``--digits``' default), so a file that drew anything
else -- another sampling, a unit slip, a curve not closed -- fails.  Lengths that the
CSV does not hold come from the spec by hand (stated at each assertion).
"""

from __future__ import annotations

import csv
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from tests.conftest import ROOT, run_inprocess

CAM = ROOT / "configs" / "ch4" / "ex4-1.toml"        # translating roller, r0 = 40, rr = 10
GEAR = ROOT / "configs" / "ch5" / "ex5-3.toml"       # spur z = 35, m = 5 mm
PAIR = ROOT / "configs" / "ch5" / "ex5-4.toml"       # z1 = 20, z2 = 80, m = 5, a' = 255
KIN = ROOT / "configs" / "ch1" / "exercise1-2.toml"  # four-bar with coupler point F
#: the CSV's digits (``%.10g``): a value read back is within this relative error
CSV_RTOL = 1e-9
SVG = "{http://www.w3.org/2000/svg}"


def _run(*args):
    proc = run_inprocess(*map(str, args))
    assert proc.returncode == 0, proc.stderr
    return proc


def _csv(path):
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    return {h: np.array([float(r[i]) for r in rows[1:]]) for i, h in enumerate(rows[0])}


def _as_drawn(x, y):
    """CSV points as a closed polyline is written: consecutive repeats (a jump's two
    samples) once, the repeated closing point dropped."""
    p = np.column_stack([x, y])
    size = float(np.max(np.ptp(p, axis=0)))
    keep = np.concatenate([[True], np.hypot(*np.diff(p, axis=0).T) > 1e-12 * size])
    p = p[keep]
    if np.hypot(*(p[-1] - p[0])) <= 1e-12 * size:
        p = p[:-1]
    return p


def _assert_on_csv(vertices, x, y):
    """The polyline's vertices are the CSV's points, in order, to the CSV's digits."""
    want = _as_drawn(x, y)
    got = np.asarray(vertices, dtype=float)[:, :2]
    assert got.shape == want.shape
    scale = float(np.max(np.abs(want)))
    np.testing.assert_allclose(got, want, rtol=CSV_RTOL, atol=CSV_RTOL * scale)


def _dxf(path):
    ezdxf = pytest.importorskip("ezdxf")
    return ezdxf.readfile(str(path))


def _layer(doc, layer, kind):
    return [e for e in doc.modelspace() if e.dxf.layer == layer and e.dxftype() == kind]


def _svg_points(path):
    """``{layer: [(n, 2) arrays (polylines), (cx, cy, r) (circles)]}`` and the
    viewBox, from the SVG (y as the model's: each layer is ``scale(1,-1)``)."""
    root = ET.parse(path).getroot()
    box = [float(v) for v in root.get("viewBox").split()]
    layers = {}
    for g in root.iter(f"{SVG}g"):
        assert g.get("transform") == "scale(1,-1)"
        items = layers.setdefault(g.get("id"), [])
        for el in g:
            if el.tag in (f"{SVG}polygon", f"{SVG}polyline"):
                items.append(np.array([[float(v) for v in pt.split(",")]
                                       for pt in el.get("points").split()]))
            elif el.tag == f"{SVG}circle":
                items.append(tuple(float(el.get(k)) for k in ("cx", "cy", "r")))
    return layers, box


def _assert_view_box_holds(path):
    """Every point of every polyline and every circle lies inside the viewBox."""
    layers, (x0, y0, w, h) = _svg_points(path)
    assert layers
    for items in layers.values():
        for it in items:
            if isinstance(it, tuple):
                cx, cy, r = it
                pts = np.array([[cx - r, cy - r], [cx + r, cy + r]])
            else:
                pts = it
            sx, sy = pts[:, 0], -pts[:, 1]       # scale(1,-1): screen y = -model y
            assert np.all(sx >= x0) and np.all(sx <= x0 + w)
            assert np.all(sy >= y0) and np.all(sy <= y0 + h)


def _inside(pt, poly):
    """Point in polygon (even-odd rule)."""
    x, y = pt
    inside = False
    for (x1, y1), (x2, y2) in zip(poly, np.roll(poly, -1, axis=0)):
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


# -- cam ---------------------------------------------------------------------------
def test_cam_dxf_profile_and_pitch_lie_on_the_csv(tmp_path):
    out = tmp_path / "cam"
    _run("cam", CAM, "-o", out, "-q", "--no-plot", "--export", "dxf,svg")
    data = _csv(out / "cam.csv")
    doc = _dxf(out / "cam.dxf")
    assert doc.header["$INSUNITS"] == 4          # the spec's units = "mm" (AutoCAD: 4)
    assert doc.header["$MEASUREMENT"] == 1       # metric
    for layer, col in (("PROFILE", "work"), ("PITCH", "pitch")):
        (pl,) = _layer(doc, layer, "LWPOLYLINE")
        assert pl.closed
        _assert_on_csv(list(pl.get_points("xy")), data[f"x_{col}_mm"], data[f"y_{col}_mm"])
    radii = {e.dxf.layer: e.dxf.radius for e in doc.modelspace() if e.dxftype() == "CIRCLE"}
    # the spec: r0 = 40 (the pitch curve's), rr = 10: working base circle 30, |e| = 15
    assert radii == pytest.approx({"PRIME_CIRCLE": 40.0, "BASE_CIRCLE": 30.0,
                                   "OFFSET_CIRCLE": 15.0, "FOLLOWER": 10.0}, rel=1e-12)
    # the roller at delta = 0 sits on the pitch curve's first point (cam.csv's first row)
    (roller,) = _layer(doc, "FOLLOWER", "CIRCLE")
    assert roller.dxf.center[0] == pytest.approx(data["x_pitch_mm"][0], rel=CSV_RTOL)
    assert roller.dxf.center[1] == pytest.approx(data["y_pitch_mm"][0], rel=CSV_RTOL)


def test_cam_svg_lies_on_the_csv_and_fits_its_view_box(tmp_path):
    out = tmp_path / "cam"
    _run("cam", CAM, "-o", out, "-q", "--no-plot", "--export", "svg")
    assert not (out / "cam.dxf").exists()
    data = _csv(out / "cam.csv")
    layers, _box = _svg_points(out / "cam.svg")
    (profile,) = layers["PROFILE"]
    _assert_on_csv(profile, data["x_work_mm"], data["y_work_mm"])
    _assert_view_box_holds(out / "cam.svg")
    root = ET.parse(out / "cam.svg").getroot()
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    assert root.find(f"{SVG}g[@id='PROFILE']").find(f"{SVG}polygon") is not None  # closed


def test_flat_faced_follower_face_spans_the_contact_offsets(tmp_path):
    # 例 4-2: flat face, r0 = 30 mm; the face at delta = 0 is the line y = r0 + s(0) = 30
    # through the axis x = 0, across the contact offsets of cam.csv (face_offset_mm)
    out = tmp_path / "flat"
    _run("cam", ROOT / "configs" / "ch4" / "ex4-2.toml", "-o", out, "-q", "--no-plot",
         "--export", "dxf")
    data = _csv(out / "cam.csv")
    doc = _dxf(out / "cam.dxf")
    (face,) = _layer(doc, "FOLLOWER", "LWPOLYLINE")
    (x1, y1), (x2, y2) = list(face.get_points("xy"))
    assert (y1, y2) == pytest.approx((30.0, 30.0), rel=1e-12)
    assert sorted((x1, x2)) == pytest.approx([data["face_offset_mm"].min(),
                                              data["face_offset_mm"].max()], rel=CSV_RTOL)
    assert not _layer(doc, "PITCH", "LWPOLYLINE")      # a flat face has no pitch curve


# -- gear --------------------------------------------------------------------------
def test_spur_gear_outline_lies_on_gear_csv(tmp_path):
    out = tmp_path / "gear"
    _run("gear", GEAR, "-o", out, "-q", "--no-plot", "--export", "dxf,svg")
    data = _csv(out / "gear.csv")
    doc = _dxf(out / "gear.dxf")
    assert doc.header["$INSUNITS"] == 4
    (outline,) = _layer(doc, "OUTLINE", "LWPOLYLINE")
    assert outline.closed
    _assert_on_csv(list(outline.get_points("xy")), data["x_mm"], data["y_mm"])
    radii = {e.dxf.layer: e.dxf.radius for e in doc.modelspace() if e.dxftype() == "CIRCLE"}
    # the config's hand calculation: d = 175, db = 164.4462, da = 185, df = 162.5
    assert radii["REFERENCE_CIRCLE"] == pytest.approx(87.5, rel=1e-12)
    assert radii["BASE_CIRCLE"] == pytest.approx(164.4462 / 2, abs=5e-5)
    assert radii["TIP_CIRCLE"] == pytest.approx(92.5, rel=1e-12)
    assert radii["ROOT_CIRCLE"] == pytest.approx(81.25, rel=1e-12)
    _assert_view_box_holds(out / "gear.svg")
    layers, _ = _svg_points(out / "gear.svg")
    _assert_on_csv(layers["OUTLINE"][0], data["x_mm"], data["y_mm"])


def _teeth(points, r):
    """Teeth of an outline: its upward crossings of the circle of radius r, / 2."""
    rho = np.hypot(points[:, 0], points[:, 1]) - r
    s = np.sign(rho)
    return int(np.count_nonzero(s != np.roll(s, 1))) // 2


def test_pair_at_its_centre_distance(tmp_path):
    out = tmp_path / "pair"
    _run("gear", PAIR, "-o", out, "-q", "--no-plot", "--export", "dxf")
    # 例 5-4: z1 = 20, z2 = 80, m = 5: r1 = 50, r2 = 200; a' = 255
    for name, z, r in (("gear1", 20, 50.0), ("gear2", 80, 200.0)):
        (pl,) = _layer(_dxf(out / f"{name}.dxf"), "OUTLINE", "LWPOLYLINE")
        assert pl.closed
        assert _teeth(np.array(list(pl.get_points("xy"))), r) == z
    doc = _dxf(out / "pair.dxf")
    outlines = _layer(doc, "OUTLINE", "LWPOLYLINE")
    assert len(outlines) == 2 and all(o.closed for o in outlines)
    pitch = sorted(_layer(doc, "PITCH_CIRCLE", "CIRCLE"), key=lambda c: c.dxf.radius)
    centres = [(c.dxf.center.x, c.dxf.center.y) for c in pitch]
    assert centres[0] == (0.0, 0.0)
    assert centres[1] == pytest.approx((0.0, 255.0), rel=1e-12)      # a' = 255
    # the operating pitch circles touch: rw1 + rw2 = a', rw2 / rw1 = z2 / z1
    rw1, rw2 = (c.dxf.radius for c in pitch)
    assert rw1 + rw2 == pytest.approx(255.0, rel=1e-12)
    assert rw2 / rw1 == pytest.approx(4.0, rel=1e-12)
    # the wheel is the outline round (0, a'), with 80 teeth about its reference circle
    wheel = max(outlines, key=lambda o: np.mean([p[1] for p in o.get_points("xy")]))
    pts = np.array(list(wheel.get_points("xy"))) - (0.0, 255.0)
    assert _teeth(pts, 200.0) == 80


def test_gear_problem_without_geometry_refuses_export(tmp_path):
    out = tmp_path / "helical"
    proc = run_inprocess("gear", ROOT / "configs" / "ch5" / "exercise5-6.toml", "-o", out,
                         "-q", "--export", "svg")
    assert proc.returncode == 2
    line = proc.stderr.strip()
    assert "\n" not in line and "--export" in line and "[helical]" in line
    assert not out.exists()


# -- linkages ----------------------------------------------------------------------
def test_kin_coupler_curve_and_pins_lie_on_kin_csv(tmp_path):
    out = tmp_path / "kin"
    _run("kin", KIN, "-o", out, "-q", "--no-plot", "--export", "dxf,svg",
         "--set", "output.draw_at=70")
    data = _csv(out / "kin.csv")
    doc = _dxf(out / "kin.dxf")
    assert doc.header["$INSUNITS"] == 4
    (curve,) = _layer(doc, "COUPLER_CURVE", "LWPOLYLINE")
    assert curve.closed                          # a crank's full turn: the path closes
    _assert_on_csv(list(curve.get_points("xy")), data["xF_mm"], data["yF_mm"])
    pins = {(e.dxf.center.x, e.dxf.center.y) for e in _layer(doc, "PINS", "CIRCLE")}
    row = int(np.flatnonzero(data["theta1_deg"] == 70)[0])
    want = [(0.0, 0.0), (80.0, 0.0),             # A, D: the frame l4 = 80 along x
            (40 * math.cos(math.radians(70)), 40 * math.sin(math.radians(70))),  # B, l1 = 40
            (data["xF_mm"][row], data["yF_mm"][row])]                         # F at 70°
    for p in want:
        assert min(math.dist(p, q) for q in pins) <= 1e-7 * 120
    assert len(pins) == 5                        # A, B, C, D and the traced F
    links = [np.array(list(e.get_points("xy"))) for e in _layer(doc, "LINKS", "LWPOLYLINE")]
    assert len(links) == 3                       # crank 1, coupler 2 (with F), rocker 3
    assert all(e.closed for e in _layer(doc, "LINKS", "LWPOLYLINE"))
    for p in pins:                               # every pin is on a link's plate
        assert any(_inside(p, poly) for poly in links)
    _assert_view_box_holds(out / "kin.svg")
    layers, _ = _svg_points(out / "kin.svg")
    _assert_on_csv(layers["COUPLER_CURVE"][0], data["xF_mm"], data["yF_mm"])


@pytest.mark.parametrize("units, insunits, measurement, svg_unit, per_unit", [
    ("m", 6, 1, "mm", 1000.0),     # AutoCAD's codes: 6 metres, 1 inch; SVG has no "m"
    ("in", 1, 0, "in", 1.0),
])
def test_header_units_follow_the_spec(tmp_path, units, insunits, measurement, svg_unit,
                                      per_unit):
    out = tmp_path / units
    _run("kin", KIN, "-o", out, "-q", "--no-plot", "--export", "dxf,svg",
         "--set", f'units="{units}"')
    doc = _dxf(out / "kin.dxf")
    assert (doc.header["$INSUNITS"], doc.header["$MEASUREMENT"]) == (insunits, measurement)
    root = ET.parse(out / "kin.svg").getroot()
    width, box = root.get("width"), [float(v) for v in root.get("viewBox").split()]
    assert width.endswith(svg_unit)
    # the physical width is the viewBox's width (model units) in the file's unit
    assert float(width[:-len(svg_unit)]) == pytest.approx(box[2] * per_unit, rel=1e-9)
    data = _csv(out / "kin.csv")
    (curve,) = _layer(doc, "COUPLER_CURVE", "LWPOLYLINE")
    _assert_on_csv(list(curve.get_points("xy")), data[f"xF_{units}"], data[f"yF_{units}"])


@pytest.mark.parametrize("command, spec, stem", [
    ("force", ROOT / "configs" / "ch2" / "ex2-1.toml", "force"),
    ("synth", ROOT / "configs" / "ch3" / "ex3-4.toml", "synth"),
    ("optimize", ROOT / "configs" / "ch7" / "ex7-1.toml", "optimize"),
])
def test_linkage_commands_export_their_linkage(tmp_path, command, spec, stem):
    out = tmp_path / command
    _run(command, spec, "-o", out, "-q", "--no-plot", "--export", "svg")
    layers, _ = _svg_points(out / f"{stem}.svg")
    assert layers["LINKS"] and layers["PINS"]
    _assert_view_box_holds(out / f"{stem}.svg")
    manifest = json.loads((out / "outputs.json").read_text(encoding="utf-8"))
    assert f"{stem}.svg" in json.dumps(manifest)


# -- the option --------------------------------------------------------------------
def test_export_files_are_in_the_manifest(tmp_path):
    pytest.importorskip("ezdxf")
    out = tmp_path / "cam"
    _run("cam", CAM, "-o", out, "-q", "--no-plot", "--export", "svg,dxf")
    text = (out / "outputs.json").read_text(encoding="utf-8")
    assert "cam.dxf" in text and "cam.svg" in text


@pytest.mark.parametrize("value", ["stl", "dxf,stl", ""])
def test_bad_export_value_is_a_usage_error(tmp_path, value):
    out = tmp_path / "bad"
    proc = run_inprocess("cam", CAM, "-o", out, "-q", "--export", value)
    assert proc.returncode == 2
    line = proc.stderr.strip()
    assert "\n" not in line and "Traceback" not in line
    assert "'--export'" in line and "dxf" in line and "svg" in line
    assert not out.exists()


def test_commands_without_geometry_do_not_take_export(tmp_path):
    proc = run_inprocess("grashof", "--lengths", "40,90,70,100", "-o", tmp_path / "g",
                         "--export", "svg")
    assert proc.returncode == 2 and "--export" in proc.stderr


def test_dxf_without_ezdxf_names_the_extra_before_anything_is_written(tmp_path,
                                                                      monkeypatch):
    import importlib.util
    import sys

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "ezdxf" else real(name, *a))
    monkeypatch.setitem(sys.modules, "ezdxf", None)          # `import ezdxf` fails
    out = tmp_path / "cam"
    proc = run_inprocess("cam", CAM, "-o", out, "-q", "--export", "dxf,svg")
    assert proc.returncode == 2
    line = proc.stderr.strip()
    assert "\n" not in line and "--export" in line and "pip install 'mechcli[cad]'" in line
    assert not out.exists()                                  # nothing computed or written
    # SVG needs no extra
    proc = run_inprocess("cam", CAM, "-o", out, "-q", "--no-plot", "--export", "svg")
    assert proc.returncode == 0, proc.stderr
    assert (out / "cam.svg").is_file()


def test_the_command_line_does_not_import_ezdxf():
    import subprocess
    import sys

    code = ("import sys; from mechcli import cli, options;"
            "print('ezdxf' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.strip()
    assert out == "False"
