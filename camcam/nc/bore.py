"""The helical bore (``[machining] bore = true``): helix down at the ramp angle, then a full circle.

The tool centre runs on the circle of radius ``bore/2 − r_t`` about the cam
axis, in quarter-turn arcs (the post prints their exact centre, 0/0, so the
circle is within the post's rounding of the bore); it winds down from the
blank's top at no more than the ramp angle to the bore's depth (through the
cam: its thickness, or the cut depth if deeper), then cuts one full circle
there.  Cutting from solid, the helix engages the tool's full diameter when
the bore is less than twice the tool: the pass is a stated slot (``bore``).
"""

from __future__ import annotations

import math

from camcam.nc.passes import Pass
from camcam.nc.stock import Blank
from camcam.toolpath.path import ArcMove, Feed, Rapid

__all__ = ["bore_passes", "bore_circle_radius"]


def bore_circle_radius(blank: Blank, tool_radius_mm: float) -> float:
    """Radius of the tool centre's circle (mm)."""
    return blank.bore_mm / 2 - tool_radius_mm


def bore_passes(blank: Blank, tool_radius_mm: float, m, z_clear: float, z_depth: float, thickness_mm: float) -> list[Pass]:
    """One ``bore`` pass: helix from the top to ``min(z_depth, −thickness)``, full circle, retract."""
    rho = bore_circle_radius(blank, tool_radius_mm)
    z_top, z_end = blank.top_z_mm, min(z_depth, -thickness_mm)
    quarter = math.pi / 2 * rho
    per_quarter = quarter * math.tan(math.radians(m.ramp_angle_deg))
    n = max(1, math.ceil((z_top - z_end) / per_quarter * (1 + 1e-9)))
    plunge = m.plunge_feed_mm_min
    pts = [(rho, 0.0), (0.0, rho), (-rho, 0.0), (0.0, -rho)]
    moves = [Rapid(rho, 0.0, None), Rapid(None, None, z_clear), Feed(None, None, z_top, plunge)]
    for i in range(n):
        x, y = pts[(i + 1) % 4]
        moves.append(ArcMove(x, y, 0.0, 0.0, True, z_top + (z_end - z_top) * (i + 1) / n, m.feed_mm_min))
    for i in range(n, n + 4):
        x, y = pts[(i + 1) % 4]
        moves.append(ArcMove(x, y, 0.0, 0.0, True, z_end, m.feed_mm_min))
    moves.append(Rapid(None, None, z_clear))
    return [Pass(None, "bore", z_end, tuple(moves))]
