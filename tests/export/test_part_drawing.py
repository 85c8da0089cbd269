"""The NC drawing's PART layer (lines and arcs within tolerance of the design), its layers and extents,
LibreCAD's rendering; the part outline offset against closed forms; the STL in the program's frame."""

import io
import math
import shutil
import subprocess

import ezdxf
import numpy as np
import pytest
import trimesh
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, Point, Polygon

from camcam.export.nc import nc_dxf, part_of
from camcam.geometry.build import build_cam
from camcam.export.stl import program_frame, stl_bytes
from camcam.toolpath.deviation import measure_deviation
from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.outline import part_outline
from tests.nc.test_job import built_and_result


def _elements_from_dxf(doc, layer):
    """LINE/ARC entities of ``layer`` as elements, in file order (each ARC counter-clockwise as DXF stores it)."""
    out = []
    for e in doc.modelspace().query(f"*[layer=='{layer}']"):
        if e.dxftype() == "LINE":
            out.append(Line(tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]))
        else:
            c, r = np.array(e.dxf.center)[:2], e.dxf.radius
            a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
            out.append(Arc(tuple(c + r * np.array([math.cos(a0), math.sin(a0)])),
                           tuple(c + r * np.array([math.cos(a1), math.sin(a1)])), tuple(c), True))
    return out


@pytest.mark.parametrize("sample", ["disc-translating-roller", "disc-translating-flat", "disc-groove", "post-fanuc"])
def test_part_layer_is_lines_and_arcs_within_tolerance_of_the_design(tmp_path, sample):
    spec, built, result = built_and_result(sample)
    part = part_of(built, result)
    f = tmp_path / "cam.dxf"
    f.write_bytes(nc_dxf(built, result, part).data)
    doc = ezdxf.readfile(f)  # strict reader
    assert not doc.audit().has_errors
    kinds = {e.dxftype() for e in doc.modelspace().query("*[layer=='PART']")}
    assert kinds and kinds <= {"LINE", "ARC"}
    assert {e.dxftype() for e in doc.modelspace().query("*[layer=='PROFILE']")} == {"SPLINE"}
    assert {e.dxftype() for e in doc.modelspace().query("*[layer=='TOOL_CENTRE']")} <= {"LINE", "ARC"}
    # every layer its own colour
    colours = [layer.dxf.color for layer in doc.layers if layer.dxf.name not in ("0", "Defpoints")]
    assert len(colours) == len(set(colours))
    # extents set and holding the part
    lo, hi = np.array(doc.header["$EXTMIN"])[:2], np.array(doc.header["$EXTMAX"])[:2]
    v = built.mesh.vertices
    assert np.all(lo <= v[:, :2].min(axis=0)) and np.all(hi >= v[:, :2].max(axis=0))
    # the PART entities as written, against the exact design surface(s), both ways
    elements = _elements_from_dxf(doc, "PART")
    surfaces = [built.cam.profile] if spec.cam.kind == "disc" else list(built.cam.flanks)
    worst = 0.0
    for surface in surfaces:
        q = surface.evaluate(np.linspace(surface.t_start, surface.t_end, 400))
        mine = [e for e in elements if min(np.hypot(*(q - e.points(3)[1]).T)) < 1.0]  # the elements along it
        # ARC entities are drawn ccw in the file: only their geometry matters for the distances
        worst = max(worst, measure_deviation(surface, mine, margin_mm=2e-4).max_deviation_mm)
    # the fit holds the tool centre within the tolerance; an exact offset keeps that distance
    assert worst <= result.tolerance_mm + 2e-4
    assert part.deviation_mm <= result.tolerance_mm
    assert len(part.outlines) == len(surfaces)


def test_lines_mode_part_has_sharp_trimmed_corners():
    _, built, result = built_and_result("disc-translating-roller")
    els = result.contours[0].fit.elements
    # a lines-mode path of the same contour: its chords; the outline at the tool radius into the material
    chords = tuple(Line(e.start, e.end) for e in els)
    out = part_outline(chords, -result.tool_diameter_mm / 2)
    assert all(isinstance(e, Line) for e in out)  # turning into the material: corners cut back, no arcs


def test_joint_arcs_tighter_than_the_tool_leave_a_sharp_corner():
    # a 30 mm square path with R2 corner arcs, material inside, tool radius 8: a tool rolling round a
    # square part leaves its corners sharp (the arcs' offsets would be inverted, radius 2 - 8 < 0), so the
    # part is the 14 mm square of the lines' offsets cut back to their intersections (near-minimal arc
    # splines close with such short tight arcs: the sized sample's best design has one of R5.7, 0.21 mm long)
    c = ((28.0, 2.0), (28.0, 28.0), (2.0, 28.0), (2.0, 2.0))
    path = (Line((2.0, 0.0), (28.0, 0.0)), Arc((28.0, 0.0), (30.0, 2.0), c[0], True),
            Line((30.0, 2.0), (30.0, 28.0)), Arc((30.0, 28.0), (28.0, 30.0), c[1], True),
            Line((28.0, 30.0), (2.0, 30.0)), Arc((2.0, 30.0), (0.0, 28.0), c[2], True),
            Line((0.0, 28.0), (0.0, 2.0)), Arc((0.0, 2.0), (2.0, 0.0), c[3], True))
    out = part_outline(path, 8.0)
    assert all(isinstance(e, Line) for e in out) and len(out) == 4
    corners = sorted(tuple(round(v, 9) for v in e.start) for e in out)  # exact up to float rounding
    assert corners == [(8.0, 8.0), (8.0, 22.0), (22.0, 8.0), (22.0, 22.0)]


needs_librecad = pytest.mark.skipif(shutil.which("librecad") is None or shutil.which("pdftoppm") is None,
                                    reason="LibreCAD (Debian librecad) or pdftoppm (poppler-utils) missing")


@needs_librecad
def test_librecad_renders_the_drawing(tmp_path):
    _, built, result = built_and_result("disc-translating-roller")
    f = tmp_path / "cam.dxf"
    f.write_bytes(nc_dxf(built, result).data)
    env = {"QT_QPA_PLATFORM": "offscreen", "PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    # LibreCAD hangs on a file it cannot read: always under a timeout
    subprocess.run(["timeout", "60", "librecad", "dxf2pdf", "-a", "-t", str(tmp_path), str(f)], env=env,
                   capture_output=True, timeout=90, check=True)
    pdf = tmp_path / "cam.pdf"
    assert pdf.stat().st_size > 10000
    subprocess.run(["pdftoppm", "-png", "-r", "50", "-singlefile", str(pdf), str(tmp_path / "cam")], check=True,
                   timeout=60)
    import matplotlib.image as mpimg

    img = mpimg.imread(tmp_path / "cam.png")
    inked = (img[..., :3].min(axis=-1) < 0.9).mean()
    assert 0.002 < inked < 0.5  # drawn lines on a white page (neither blank nor a black box)


@st.composite
def convex_polygons(draw):
    """Vertices on a circle of radius 20 about the origin, every gap between 0.1 and 0.95 π: strictly convex."""
    n = draw(st.integers(4, 12))
    w = np.array(draw(st.lists(st.floats(1.0, 2.5), min_size=n, max_size=n)))
    gaps = w / w.sum() * 2 * math.pi
    assume(gaps.max() < 0.95 * math.pi)
    ang = draw(st.floats(0.0, 2 * math.pi)) + np.concatenate([[0.0], np.cumsum(gaps)[:-1]])
    return [(20 * math.cos(a), 20 * math.sin(a)) for a in ang]


def _ring(pts):
    return tuple(Line(p, q) for p, q in zip(pts, pts[1:] + pts[:1]))


@settings(max_examples=40, deadline=None)
@given(convex_polygons(), st.floats(0.5, 4.0))
def test_outward_offset_of_a_convex_polygon_steiner_length(pts, d):
    ring = _ring(pts)
    out = part_outline(ring, -d)  # ccw path, material outside (to the right)
    perimeter = sum(e.length for e in ring)
    # Steiner: the parallel body of a convex polygon at distance d has perimeter P + 2πd
    assert sum(e.length for e in out) == pytest.approx(perimeter + 2 * math.pi * d, rel=1e-9)
    assert sum(isinstance(e, Arc) for e in out) == len(pts)  # one corner arc per vertex
    path = LineString(pts + pts[:1])
    for e in out:
        for p in e.points(5):
            assert path.distance(Point(p)) == pytest.approx(d, abs=1e-9)  # every outline point at d from the path


@settings(max_examples=40, deadline=None)
@given(convex_polygons(), st.floats(0.1, 1.0))
def test_inward_offset_of_a_convex_polygon_matches_shapely(pts, d):
    ring = _ring(pts)
    inner = Polygon(pts).buffer(-d, join_style=2)  # mitred: shapely's own exact inward offset
    assume(not inner.is_empty and len(inner.exterior.coords) - 1 == len(pts))  # no edge vanished
    out = part_outline(ring, d)  # material inside (to the left of the ccw path)
    assert all(isinstance(e, Line) for e in out)
    area = Polygon([e.start for e in out]).area
    assert area == pytest.approx(inner.area, rel=1e-9)


def test_stl_in_the_program_frame():
    spec, built, result = built_and_result("disc-translating-roller")
    mesh = trimesh.load(io.BytesIO(stl_bytes(program_frame(built))), file_type="stl")  # the bytes camcam writes
    assert mesh.is_watertight
    z0, z1 = mesh.bounds[:, 2]
    assert z1 == pytest.approx(0.0, abs=1e-9) and z0 == pytest.approx(-spec.cam.thickness, abs=1e-9)  # Z0 top face
    # same X/Y as the program: halfway down, the finish pass's tool centre is one tool radius off the STL's wall
    section = mesh.section(plane_origin=(0, 0, -spec.cam.thickness / 2), plane_normal=(0, 0, 1))
    wall = max((LineString(np.asarray(section.vertices)[ent.points][:, :2]) for ent in section.entities),
               key=lambda s: s.length)
    finish = result.contours[0].printed
    d = [wall.distance(Point(e.end)) for e in finish]
    r_t = result.tool_diameter_mm / 2
    # tolerance 0.01 of the fit + the mesh's chords (180 per piece: sag well under 1 µm at R ≈ 60 mm)
    assert max(abs(x - r_t) for x in d) <= result.tolerance_mm + 1e-3


@pytest.mark.parametrize("tool_mm", [16.0, 8.0])
def test_groove_cut_by_a_smaller_tool_draws_its_two_walls(tmp_path, tool_mm):
    """Issue 50 item 7: disc-groove with a Ø16 tool (roller R10) exited 3, "DXF part outline deviation 4.008 mm":
    each flank pass was offset to both sides, and its side away from its wall (air, 2·(r_roller − r_tool) = 4 mm
    short of the far wall) was drawn on PART and measured against that wall.  With Ø8 a rough pass was taken
    for a wall (2.0076 mm).  PART now holds each flank pass's offset towards the wall it cuts, measured
    against that wall: the two walls, within the tolerance, as the program is (0.0076 mm)."""
    from dataclasses import replace

    from camcam.nc import machine_program

    spec, built, _ = built_and_result("disc-groove")
    m = replace(spec.machining, tool_diameter_mm=tool_mm)
    result = machine_program(built, m, spec.name, spec.stock)
    part = part_of(built, result)
    assert len(part.outlines) == 2
    assert part.deviation_mm <= result.tolerance_mm
    f = tmp_path / "cam.dxf"
    f.write_bytes(nc_dxf(built, result, part).data)
    elements = _elements_from_dxf(ezdxf.readfile(f), "PART")
    # every PART entity lies along one wall and each wall is drawn whole: both ways against its flank
    for flank in built.cam.flanks:
        q = flank.evaluate(np.linspace(flank.t_start, flank.t_end, 400))
        mine = [e for e in elements if min(np.hypot(*(q - e.points(3)[1]).T)) < 1.0]
        # 2e-4: the measurement's own between-sample margin, as in the test above
        assert measure_deviation(flank, mine, margin_mm=2e-4).max_deviation_mm <= result.tolerance_mm + 2e-4
    walls = [np.asarray(f_.evaluate(np.linspace(f_.t_start, f_.t_end, 2000))) for f_ in built.cam.flanks]
    for e in elements:
        mid = np.asarray(e.points(3)[1])
        assert min(float(np.hypot(*(w - mid).T).min()) for w in walls) < 1.0, e  # no entity inside the groove


def test_a_helical_bore_draws_its_wall():
    """Beside item 7: a disc with a helical bore ([machining] bore = true) could not be drawn ("part outline:
    every arc of the path is tighter than the offset 8 mm"): the bore's circle was offset to both sides and
    paired with flanks a disc has none of.  Now the bore's pass is offset towards the bore's wall only."""
    from dataclasses import replace

    from camcam.nc import machine_program
    from camcam.nc.bore import bore_curve

    spec, built, _ = built_and_result("disc-translating-roller")
    spec = replace(spec, cam=replace(spec.cam, bore=24.0))
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    m = replace(spec.machining, bore=True)
    result = machine_program(built, m, spec.name, spec.stock)
    part = part_of(built, result)
    assert len(part.outlines) == 2 and part.deviation_mm <= result.tolerance_mm
    wall = bore_curve(12.0)
    bore_out = min(part.outlines, key=lambda out: abs(math.hypot(*out[0].start) - 12.0))
    assert measure_deviation(wall, bore_out, margin_mm=2e-4).max_deviation_mm <= result.tolerance_mm + 2e-4
