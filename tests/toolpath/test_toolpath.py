import math

import numpy as np
import pytest

from camcam.errors import InputError
from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.elements import element_tangent
from camcam.toolpath.path import ArcMove, CutSettings, Feed, Rapid, contour_toolpath, offset_elements

SQUAREISH = (Line((0.0, 0.0), (10.0, 0.0)), Arc((10.0, 0.0), (10.0, 10.0), (10.0, 5.0), True),
             Line((10.0, 10.0), (0.0, 10.0)))


def test_depth_passes_and_heights():
    cs = CutSettings(depth_mm=10, stepdown_mm=4, feed_mm_min=300, spindle_rpm=1000, safe_z_mm=20, clearance_z_mm=3)
    tp = contour_toolpath(SQUAREISH, cs)
    zs = sorted({m.z for m in tp.moves if isinstance(m, ArcMove)})
    # ceil(10/4) = 3 equal passes of 10/3 mm (float rounding only)
    assert np.allclose(zs, [-10.0, -20 / 3, -10 / 3], atol=1e-12)
    assert tp.moves[0] == Rapid(None, None, 20) and tp.moves[-1] == Rapid(None, None, 20)
    assert Rapid(None, None, 3) in tp.moves


@pytest.mark.parametrize("side", ["left", "right"])
def test_leads_are_tangent_and_on_the_free_side(side):
    cs = CutSettings(depth_mm=2, stepdown_mm=2, feed_mm_min=300, spindle_rpm=1000, lead_radius_mm=4, stock_side=side)
    moves = contour_toolpath(SQUAREISH, cs).moves
    lead = next(m for m in moves if isinstance(m, ArcMove))
    start = next(m for m in moves if isinstance(m, Rapid) and m.x is not None)
    arc = Arc((start.x, start.y), (lead.x, lead.y), (lead.cx, lead.cy), lead.ccw)
    t_lead, t_contour = element_tangent(arc, True), element_tangent(SQUAREISH[0], False)
    assert np.allclose(t_lead, t_contour, atol=1e-12)  # G1 entry (exact construction, float rounding)
    # the first element runs along +X: stock on the right means the lead comes from +Y
    assert (lead.cy > 0) == (side == "right")
    assert math.isclose(arc.sweep, math.pi / 2, rel_tol=1e-12)


def test_allowance_and_spring_pass():
    cs = CutSettings(depth_mm=2, stepdown_mm=2, feed_mm_min=300, spindle_rpm=1000, finish_allowance_mm=0.5,
                     spring_pass=True, stock_side="right")
    moves = contour_toolpath(SQUAREISH, cs).moves
    ends = [(m.x, m.y) for m in moves if isinstance(m, Feed) and m.x is not None]
    # first straight of the contour ends at (10, 0) on finishing passes, (10, 0.5) on the rough pass
    assert ends.count((10.0, 0.5)) == 1 and ends.count((10.0, 0.0)) == 2


def test_offset_keeps_arcs_concentric_and_refuses_vanishing():
    off = offset_elements(SQUAREISH, 1.0)
    assert off[1].centre == (10.0, 5.0) and math.isclose(off[1].radius, 4.0, rel_tol=1e-12)
    with pytest.raises(InputError, match="exceeds an arc radius"):
        offset_elements(SQUAREISH, 6.0)


def test_bad_settings_name_the_field():
    with pytest.raises(InputError, match="^stepdown_mm: expected > 0"):
        CutSettings(depth_mm=2, stepdown_mm=0, feed_mm_min=300, spindle_rpm=1000)
