"""A printed spiral arc in the DXF: the ARC through its two ends, so a chain of entities closes as the program's
path does (campaign case 47:36's four printed arcs, tests/export/test_outline_spiral_arcs.py).

An ARC entity has one radius.  Drawn from its centre at its start radius, a printed arc whose rounded end lies at
another radius (``Arc.end_radius``, the spiral a controller cuts) ended |Δr| from its end: gaps of up to 1.45e-3 mm
in this chain, and the PART layer's figure was measured on spirals the file did not hold.
"""

import io
import math

import ezdxf
import pytest

from camcam.export.dxf import contour_dxf
from camcam.toolpath.elements import circular, element_distance
from tests.export.test_outline_spiral_arcs import PRINTED, TOOL_R
from camcam.toolpath.outline import part_outline


def _arcs(data: bytes, layer: str):
    doc = ezdxf.read(io.StringIO(data.decode("utf-8")))
    return [e for e in doc.modelspace() if e.dxf.layer == layer and e.dxftype() == "ARC"]


def _gaps(path, arcs):
    """The distance from each joint of ``path`` to the nearest end of each of the two entities drawn beside it."""
    out = []
    for k, e in enumerate(path):
        ends = [tuple(p)[:2] for a in (arcs[k], arcs[(k + 1) % len(path)]) for p in (a.start_point, a.end_point)]
        near = sorted(math.dist(e.end, p) for p in ends)
        out.append(near[1])  # both entities must reach the joint: the second nearest end
    return out


def test_the_program_path_is_drawn_as_a_closed_chain():
    # spirals as printed: the third arc's ends are 1.451e-3 mm apart in radius
    assert max(abs(e.end_radius - e.radius) for e in PRINTED) == pytest.approx(1.451e-3, abs=1e-6)
    arcs = _arcs(contour_dxf(PRINTED, contour_layer="TOOL_CENTRE").data, "TOOL_CENTRE")
    assert len(arcs) == 4
    # each joint is the end of both entities beside it, to the DXF's float text (1e-9 mm: a chain a CAD
    # program joins at its default tolerances); it was 1.45e-3 mm at the worst joint
    assert max(_gaps(PRINTED, arcs)) <= 1e-9


def test_the_drawn_arc_keeps_to_the_spiral():
    for e in PRINTED:
        drawn = circular(e)
        assert (drawn.start, drawn.end, drawn.ccw) == (e.start, e.end, e.ccw)
        # within |Δr|/20 of the spiral over the arc (a 90° sweep; about |Δr|/47 at 90°, checked densely)
        assert element_distance(drawn, e.points(4001)).max() <= abs(e.end_radius - e.radius) / 20


def test_the_part_layer_is_the_outline_as_measured():
    outline = part_outline(PRINTED, TOOL_R)
    arcs = _arcs(contour_dxf((), extras={"PART": list(outline)}).data, "PART")
    assert max(_gaps(outline, arcs)) <= 1e-9  # the offset spirals, drawn as closing ARCs (to the file's text)
