"""The helical bore (``[machining] bore = true``): helix down at the ramp angle, then a full circle.

The tool centre runs on the circle of radius ``bore/2 − r_t`` about the cam
axis; it winds down from the blank's top in quarter-turn helical arcs at no
more than the ramp angle to the bore's depth (through the cam: its
thickness, or the cut depth if deeper), then cuts one full circle there:
the circle is a contour of the job, fitted and measured like the others.
A tool of at least half the bore leaves no core.  Cutting from solid, the helix engages the tool's full diameter when
the bore is less than twice the tool: the pass is a stated slot (``bore``).
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.jet import Jet
from camcam.geometry.jetcurve import JetCurve
from camcam.nc.direction import reverse_elements
from camcam.nc.stock import Blank
from camcam.toolpath.path import ArcMove, Feed, Pass, Rapid, contour_moves

__all__ = ["bore_passes", "bore_circle_radius", "bore_curve"]


def bore_circle_radius(blank: Blank, tool_radius_mm: float) -> float:
    """Radius of the tool centre's circle (mm)."""
    return blank.bore_mm / 2 - tool_radius_mm


def bore_curve(radius_mm: float) -> JetCurve:
    """The tool centre's circle, counter-clockwise from (radius, 0), as an exact curve for the fitter."""

    def func(t, K, piece=None):
        a = Jet.variable(t, K)
        return a.cos() * radius_mm, a.sin() * radius_mm

    return JetCurve(func, np.array([0.0, math.pi / 2, math.pi, 1.5 * math.pi, 2 * math.pi]))


def bore_passes(contour: int, elements, blank: Blank, tool_radius_mm: float, z_clear: float, z_depth: float,
                thickness_mm: float, *, ramp_angle_deg: float, plunge_feed_mm_min: float,
                feed_mm_min: float, ccw: bool = True) -> list[Pass]:
    """One ``bore`` pass: helix from the top to ``min(z_depth, −thickness)``, the fitted circle there, retract.

    The helix descends at ``ramp_angle_deg`` (``[machining] ramp_angle``); it is entered at
    ``plunge_feed_mm_min`` and cut at ``feed_mm_min``.

    ``elements`` are the fitted circle (:func:`bore_curve`, counter-clockwise); the arc fitter may
    start a closed contour anywhere, so the helix turns about the axis from the circle's first printed
    point.  ``ccw`` runs helix and circle counter-clockwise (climb with an M3 spindle: the material is
    outside, on the right of travel), else clockwise (conventional; :mod:`camcam.nc.direction`).
    """
    rho = bore_circle_radius(blank, tool_radius_mm)
    z_top, z_end = blank.top_z_mm, min(z_depth, -thickness_mm)
    quarter = math.pi / 2 * rho
    per_quarter = quarter * math.tan(math.radians(ramp_angle_deg))
    n = 4 * max(1, math.ceil((z_top - z_end) / per_quarter / 4 * (1 + 1e-9)))  # whole turns: ends at (ρ, 0)
    start = tuple(map(float, elements[0].start))
    phi0 = math.atan2(start[1], start[0])
    turn = math.pi / 2 if ccw else -math.pi / 2
    pts = [start] + [(rho * math.cos(phi0 + k * turn), rho * math.sin(phi0 + k * turn)) for k in (1, 2, 3)]
    moves = [Rapid(start[0], start[1], None), Rapid(None, None, z_clear), Feed(None, None, z_top, plunge_feed_mm_min)]
    for i in range(n):
        x, y = pts[(i + 1) % 4]
        moves.append(ArcMove(x, y, 0.0, 0.0, ccw=ccw, z=z_top + (z_end - z_top) * (i + 1) / n,
                             feed_mm_min=feed_mm_min))
    moves += contour_moves(elements if ccw else reverse_elements(elements), z_end, feed_mm_min)
    moves.append(Rapid(None, None, z_clear))
    return [Pass(contour, "bore", z_end, tuple(moves))]
