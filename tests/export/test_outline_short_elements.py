"""The part outline of a path with elements shorter than the tool radius cuts back (issue 43 D).

A lines fit ends each analytic piece with whatever chord is left, 0.0134 mm long on campaign case 43:444;
offset by the 3 mm tool radius toward the material, both its joints cut it back by more than its length.  It
leaves nothing of the part, and the outline joins its neighbours' offsets directly.  Before: exit 2, "part
outline: the line ending at (-60.7848, 7.9310) is shorter than the tool radius cuts back from it", on a valid
spec.  Checked against shapely's own offset (GEOS, mitred joins) and against the design profile.
"""

import math
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import LineString, Polygon

from camcam.export.nc import part_of
from camcam.geometry.build import build_cam
from camcam.nc.job import machine_program
from camcam.spec import load_spec
from camcam.toolpath.elements import Line, element_tangent
from camcam.toolpath.outline import part_outline

SPEC = Path(__file__).parent / "data" / "outline-short-line-43-444.toml"


def _polygon_path(points):
    return tuple(Line(tuple(p), tuple(q)) for p, q in zip(points, np.roll(points, -1, axis=0)))


def test_a_short_chord_between_joints_turning_into_the_material_drops_out():
    # a ccw 60-gon of radius 60 mm with one vertex split into two 0.0134 mm apart (the case's chord); the material
    # inside, on the left: offset 3 mm to the left
    ang = np.radians(np.arange(60) * 6.0)
    ang = np.sort(np.append(ang, ang[10] + 0.0134 / 60.0))
    pts = np.column_stack([60 * np.cos(ang), 60 * np.sin(ang)])
    out = part_outline(_polygon_path(pts), 3.0)
    assert len(out) == 60 and all(isinstance(e, Line) for e in out)  # the short chord's offset left out
    for e in out:  # closed, each element in the direction of travel
        assert math.dist(e.end, out[(out.index(e) + 1) % len(out)].start) < 1e-9
    # the points at least 3 mm inside every edge of a convex polygon: the intersection of the edges' half-planes,
    # each moved in by 3 mm (GEOS's own buffer simplifies its input by 1 % of the distance first, and moves
    # this one by 0.00068 mm); within 1e-9 mm both ways (floating point of two constructions)
    ref = shapely.box(-100.0, -100.0, 100.0, 100.0)
    for p, q in zip(pts, np.roll(pts, -1, axis=0)):
        t = (q - p) / np.hypot(*(q - p))
        n = np.array([-t[1], t[0]])  # inward (left of a ccw edge)
        a = p + 3.0 * n
        ref = ref.intersection(Polygon([a - 500 * t, a + 500 * t, a + 500 * t + 500 * n, a - 500 * t + 500 * n]))
    mine = LineString([e.start for e in out] + [out[0].start])
    assert shapely.hausdorff_distance(mine, ref.exterior, densify=0.01) < 1e-9


def test_an_element_cut_back_past_itself_is_never_kept():
    # the same with the material outside (a tool inside a pocket): the joints turn away from it, corner arcs
    # join the offsets, and the short chord stays (its offset is a short line between two corner arcs)
    ang = np.radians(np.arange(60) * 6.0)
    ang = np.sort(np.append(ang, ang[10] + 0.0134 / 60.0))
    path = _polygon_path(np.column_stack([60 * np.cos(ang), 60 * np.sin(ang)]))
    out = part_outline(path, -3.0)
    lines = [e for e in out if isinstance(e, Line)]
    assert len(lines) == 61
    assert all(float(np.dot(element_tangent(p, False), np.subtract(e.end, e.start))) > 0 for p, e in zip(path, lines))


def test_campaign_case_444_outline_within_tolerance_of_the_design():
    spec = load_spec(SPEC)
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    result = machine_program(built, spec.machining, spec.name, spec.stock, workers=2)
    assert result.mode == "lines"
    part = part_of(built, result)  # was GeometryError (exit 2)
    ((outline,),) = (part.outlines,)
    tol = spec.machining.tolerance_mm
    assert part.deviation_mm <= tol  # measure_deviation both ways against the exact profile (0.01563 of 0.016)
    # a second method: the outline's dense points against the profile's dense polyline, and back; the polyline
    # through 200 001 profile points errs by under 1e-6 mm (chord 2e-3 mm on radii over 1 mm)
    q = built.cam.profile.evaluate(np.linspace(0.0, 2 * math.pi, 200001))
    prof = LineString(q)
    pts = np.concatenate([e.points(41) for e in outline])
    d_out = shapely.distance(prof, shapely.points(pts)).max()
    poly = LineString(pts)
    d_in = shapely.distance(poly, shapely.points(q[::10])).max()
    assert max(d_out, d_in) <= tol + 1e-3 * tol  # the lines between the 41 samples add < 1e-3·tol: chords of lines
    # the outline closes and every element runs the way the path does
    assert all(math.dist(a.end, b.start) < 1e-9 for a, b in zip(outline, outline[1:] + outline[:1]))
