"""The part outline of printed arcs whose rounded ends are off their start's circle (campaign case 47:36).

A base circle (a dwell all round, R 56.6 mm, Ø12 mm tool, post grbl) fitted with four arcs: as printed, each
arc's end lies at another radius from its centre than its start (62.58776 → 62.58746 mm), and a controller cuts
the spiral between (:class:`~camcam.toolpath.elements.Arc`'s ``end_radius``).  The outline put both ends of each
offset arc at the start's radius less the tool's: 0.00671 mm from the design against the program's 0.00637 mm,
and with the sampling margin the job failed its 0.0067 mm tolerance on the DXF alone (exit 3, "use a post with
more decimals or a larger tolerance").  An offset of a path by the tool radius is at most as far from the
design's as the path is from the exact tool-centre curve (the Minkowski sum with the tool's disc keeps the
Hausdorff distance), so the outline may not add to the program's figure.
"""

import numpy as np
import pytest

from camcam.toolpath.elements import Arc
from camcam.toolpath.outline import offset_element, part_outline

DESIGN_R = 56.6  # the base circle, about the origin
TOOL_R = 6.0
# the program's four arcs as printed (3 decimals), G3 round the circle: campaign case 47:36 (benchmarks/anycam.py
# --seed 47 --show 36), camcam 40eb4a6
PRINTED = (Arc((-13.976, -61.017), (30.835, -54.479), (0.006, -0.011), True),
           Arc((30.835, -54.479), (31.874, 53.88), (-0.002, 0.002), True),
           Arc((31.874, 53.88), (-62.582, 1.32), (0.001, 0.007), True),
           Arc((-62.582, 1.32), (-13.976, -61.017), (0.01, 0.007), True))
U = np.linspace(0.0, 1.0, 20001)  # 20 000 steps of a 90° arc: 0.003 mm apart, where |r′| < 1e-5 mm per step


def _radial_error(elements, radius):
    """The largest | |p| − radius | over dense points of ``elements`` (the design is a circle about the origin)."""
    return max(float(np.abs(np.hypot(*e.at(U).T) - radius).max()) for e in elements)


def test_an_offset_spiral_keeps_each_ends_radius_less_the_offset():
    arc = PRINTED[0]
    assert arc.end_radius - arc.radius == pytest.approx(-3.04e-4, abs=1e-6)  # a spiral, as printed
    out = offset_element(arc, TOOL_R)  # to the left of a G3: towards the centre
    # each end from its own radius; the rounding of float sums: 1e-12 mm
    assert out.radius == pytest.approx(arc.radius - TOOL_R, abs=1e-12)
    assert out.end_radius == pytest.approx(arc.end_radius - TOOL_R, abs=1e-12)


def test_the_outline_is_no_farther_from_the_design_than_the_program_from_its_curve():
    program = _radial_error(PRINTED, DESIGN_R + TOOL_R)
    outline = _radial_error(part_outline(PRINTED, TOOL_R), DESIGN_R)
    assert program == pytest.approx(0.0062401, abs=1e-7)  # the program's own figure (the report's 0.0064 has margin)
    # the same spiral less 6 mm: the same radial error to 1e-9 mm (was 0.0067134 mm, 4.7e-4 over)
    assert outline <= program + 1e-9
