"""The helical bore (``[machining] bore = true``, and the dowel hole with ``dowel = true``): helix down at the
ramp angle, then a full circle.

The tool centre runs on the circle of radius ``bore/2 − r_t`` about the cam
axis (a dowel hole's: about the hole's centre); it winds down from the blank's top in quarter-turn helical arcs at no
more than the ramp angle to the bore's depth (through the cam: its
thickness, or the cut depth if deeper), then cuts one full circle there:
the circle is a contour of the job, fitted and measured like the others.
A tool of at least half the bore leaves no core.  Cutting from solid, the helix engages the tool's full diameter when
the bore is less than twice the tool: the pass is a stated slot (``bore``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from camcam.geometry.jet import Jet
from camcam.geometry.jetcurve import JetCurve
from camcam.nc.direction import reverse_elements
from camcam.nc.stock import Blank
from camcam.toolpath.path import ArcMove, Feed, Pass, Rapid, contour_moves

__all__ = ["bore_passes", "bore_circle_radius", "bore_curve", "dowel_curve", "dowel_passes"]


def bore_circle_radius(blank: Blank, tool_radius_mm: float) -> float:
    """Radius of the tool centre's circle (mm)."""
    return blank.bore_mm / 2 - tool_radius_mm


def bore_curve(radius_mm: float, centre: tuple[float, float] = (0.0, 0.0)) -> JetCurve:
    """The tool centre's circle about ``centre``, counter-clockwise from centre + (radius, 0), as an exact curve
    for the fitter (counter-clockwise inside a hole is climb milling with the spindle clockwise, M3)."""
    # a module-level callable, not a closure: the contour goes pickled to the drawing's child process (a closure
    # made `camcam run` with bore = true end in an internal error: "Can't pickle local object")
    return JetCurve(_Circle(radius_mm, *map(float, centre)), np.array([0.0, math.pi / 2, math.pi, 1.5 * math.pi,
                                                                        2 * math.pi]))


@dataclass(frozen=True)
class _Circle:
    """The jets of the circle of ``radius_mm`` about (``cx``, ``cy``) at angle t (a JetCurve's function)."""

    radius_mm: float
    cx: float
    cy: float

    def __call__(self, t, K, piece=None):
        a = Jet.variable(t, K)
        return a.cos() * self.radius_mm + self.cx, a.sin() * self.radius_mm + self.cy


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
    return _helix_passes(contour, elements, (0.0, 0.0), blank.top_z_mm, z_clear, min(z_depth, -thickness_mm),
                         ramp_angle_deg=ramp_angle_deg, plunge_feed_mm_min=plunge_feed_mm_min,
                         feed_mm_min=feed_mm_min, ccw=ccw)


def dowel_curve(blank: Blank, tool_radius_mm: float) -> JetCurve:
    """The tool centre's circle in the dowel hole ``blank.dowel`` (:func:`bore_curve` about its centre)."""
    return bore_curve(blank.dowel.diameter / 2 - tool_radius_mm, blank.dowel.centre)


def dowel_passes(contour: int, elements, blank: Blank, tool_radius_mm: float, z_clear: float, z_depth: float,
                 thickness_mm: float, *, ramp_angle_deg: float, plunge_feed_mm_min: float,
                 feed_mm_min: float, ccw: bool = True) -> list[Pass]:
    """The dowel hole through the cam (``[machining] dowel = true``): a ``bore`` pass about its centre, as
    :func:`bore_passes` (``ccw`` likewise), noted as the dowel hole."""
    d = blank.dowel
    passes = _helix_passes(contour, elements, d.centre, blank.top_z_mm, z_clear, min(z_depth, -thickness_mm),
                           ramp_angle_deg=ramp_angle_deg, plunge_feed_mm_min=plunge_feed_mm_min,
                           feed_mm_min=feed_mm_min, ccw=ccw)
    note = f"dowel hole Ø{d.diameter:g} mm at R{d.radius:g} mm, {d.angle_deg % 360:g}° from +X"
    return [replace(p, note=note) for p in passes]


def _helix_passes(contour: int, elements, centre, z_top: float, z_clear: float, z_end: float, *,
                  ramp_angle_deg: float, plunge_feed_mm_min: float, feed_mm_min: float,
                  ccw: bool) -> list[Pass]:
    """A helix about ``centre`` from ``z_top`` to ``z_end``, then the fitted circle ``elements``
    (counter-clockwise) there, and the retract; both run clockwise unless ``ccw``.

    The helix runs about ``centre`` on the circle through the fitted circle's first point (within the fit's
    tolerance of the exact tool-centre circle)."""
    cx, cy = centre
    start = tuple(map(float, elements[0].start))
    # the helix turns on the circle through the fitted circle's first printed point, which lies up to the fit's
    # deviation off the exact radius ρ: quarter points on ρ itself made arcs whose ends are at two radii, and a
    # post refuses more than its max_radius_error_mm (campaign case 50:51: a 2.4 mm bore circle at a tolerance
    # of 0.047 mm began 0.0026 mm off ρ, "start/end radius differ by 0.002642 mm", an internal error on haas)
    rho = math.dist(start, centre)
    quarter = math.pi / 2 * rho
    per_quarter = quarter * math.tan(math.radians(ramp_angle_deg))
    n = 4 * max(1, math.ceil((z_top - z_end) / per_quarter / 4 * (1 + 1e-9)))  # whole turns: ends at the start
    phi0 = math.atan2(start[1] - cy, start[0] - cx)
    turn = math.pi / 2 if ccw else -math.pi / 2
    pts = [start] + [(cx + rho * math.cos(phi0 + k * turn), cy + rho * math.sin(phi0 + k * turn)) for k in (1, 2, 3)]
    moves = [Rapid(start[0], start[1], None), Rapid(None, None, z_clear), Feed(None, None, z_top, plunge_feed_mm_min)]
    for i in range(n):
        x, y = pts[(i + 1) % 4]
        moves.append(ArcMove(x, y, cx, cy, ccw=ccw, z=z_top + (z_end - z_top) * (i + 1) / n,
                             feed_mm_min=feed_mm_min))
    moves += contour_moves(elements if ccw else reverse_elements(elements), z_end, feed_mm_min)
    moves.append(Rapid(None, None, z_clear))
    return [Pass(contour, "bore", z_end, tuple(moves))]
