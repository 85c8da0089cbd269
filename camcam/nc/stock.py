"""The blank a disc cam is cut from, as a region in the program's XY plane.

:func:`blank_for` turns the ``[stock]`` table into a :class:`Blank` for a
built cam and refuses one that cannot make the part: a blank smaller than
the cam, a bore larger than the base circle minus the roller, a helical bore
the tool does not fit.  Regions are shapely polygons in the cam frame (X0 Y0
on the cam axis), the same frame as the program.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Point, Polygon

from camcam.errors import SpecError
from camcam.geometry.build import BuiltCam, groove_outer_radius
from camcam.geometry.extrema import extreme
from camcam.nc.settings import DEFAULT_OVERSIZE_MM, DEFAULT_STOCK, STOCK_KINDS, StockSpec

__all__ = ["Blank", "blank_for", "largest_radius", "curve_polygon", "CIRCLE_SEGMENTS",
           "DEFAULT_OVERSIZE_MM", "STOCK_KINDS", "bore_region"]

#: Segments of a polygonised circle (blank, bore): chord error R·(1 − cos(π/n)), 3.8e-5·R.
CIRCLE_SEGMENTS = 512

#: Points per analytic piece when a cam curve becomes a polygon (chord error < 1e-4 mm on the samples).
POINTS_PER_PIECE = 2000


def largest_radius(curve) -> tuple[float, float]:
    """(largest distance from the cam axis, cam angle in degrees) of a closed cam curve, from the roots of d|p|²/dθ."""

    def r2(t, i):
        x, y = curve.jets(t, 1, i)
        j = x * x + y * y
        return j.d[0], j.d[1]

    c = extreme(r2, curve.breaks, "max")
    return math.sqrt(c.value), math.degrees(c.t)


def curve_polygon(curve, per_piece: int = POINTS_PER_PIECE) -> Polygon:
    """A closed cam curve as a polygon (its samples as vertices; valid and oriented ccw)."""
    br = curve.breaks
    t = np.concatenate([np.linspace(a, b, per_piece, endpoint=False) for a, b in zip(br, br[1:])])
    poly = Polygon(curve.evaluate(t))
    if not poly.is_valid:
        raise SpecError("cam", "the profile crosses itself; cannot build the material regions")
    return shapely.geometry.polygon.orient(poly, 1.0)


def _circle(radius: float) -> Polygon:
    a = np.linspace(0.0, 2 * math.pi, CIRCLE_SEGMENTS, endpoint=False)
    return Polygon(np.column_stack([radius * np.cos(a), radius * np.sin(a)]))


@dataclass(frozen=True)
class Blank:
    """The blank and the part it must become, in the program's XY frame (mm).

    ``region`` is the blank's outline (bore not pre-drilled: solid); ``part``
    the finished outline at the final depth (a disc cam's profile; for a face
    groove the groove, which is what is removed); ``cam_radius_mm`` the cam's
    largest radius; ``top_z_mm`` the blank's top above Z0 (face stock).
    """

    kind: str
    region: Polygon
    part: Polygon
    cam_radius_mm: float
    cam_radius_at_deg: float
    diameter_mm: float | None
    allowance_mm: float | None
    top_z_mm: float
    stated: bool
    groove: bool
    bore_mm: float
    bore_machined: bool

    def describe(self) -> str:
        """One line for the report's setup."""
        if self.kind == "round":
            text = f"round blank Ø{self.diameter_mm:g} mm, centred on the cam axis"
        else:
            text = f"pre-profiled blank, {self.allowance_mm:g} mm over the finished profile"
        if not self.stated:
            text += f" (default: no [stock] table; {DEFAULT_OVERSIZE_MM:g} mm over the cam's largest radius " \
                    f"{self.cam_radius_mm:.3f} mm)"
        return text

    def top_note(self) -> str:
        if self.top_z_mm > 0:
            return (f"{self.top_z_mm:g} mm of face stock above Z0 is not cut by this program: face the blank to Z0 "
                    f"first (the roughing passes start at Z0)")
        return "the blank's top face is Z0"

    def bore_note(self) -> str:
        if self.bore_mm <= 0:
            return "no bore"
        if self.bore_machined:
            return f"bore Ø{self.bore_mm:g} mm machined as a helical bore ([machining] bore = true)"
        return f"bore Ø{self.bore_mm:g} mm is NOT machined by this program (set [machining] bore = true to cut it)"


def blank_for(built: BuiltCam, stock: StockSpec, tool_diameter_mm: float, bore: bool = False) -> Blank:
    """The blank of ``stock`` around ``built`` (a disc or face-groove cam).

    Raises
    ------
    SpecError
        ``stock.diameter`` smaller than the cam, ``cam.bore`` larger than the
        base circle minus the roller, ``machining.bore`` with no bore or one the
        tool does not fit.
    """
    cam, spec = built.cam, built.spec
    groove = spec.kind == "disc-groove"
    roller = cam.roller_radius or 0.0
    if spec.bore > 0 and spec.bore / 2 > cam.base_radius - roller:
        raise SpecError("cam.bore", f"Ø{spec.bore:g} mm is larger than the base circle minus the roller; expected at "
                                    f"most Ø{2 * (cam.base_radius - roller):g} mm (2 × ({cam.base_radius:g} − {roller:g}))")
    if bore:
        if spec.bore <= 0:
            raise SpecError("machining.bore", "true, but the cam has no bore (cam.bore = 0)")
        if spec.bore <= tool_diameter_mm:
            raise SpecError("machining.bore", f"the tool Ø{tool_diameter_mm:g} mm does not fit the bore "
                                              f"Ø{spec.bore:g} mm; expected a tool smaller than the bore")
        if spec.bore / 2 > tool_diameter_mm:
            raise SpecError("machining.bore", f"a Ø{tool_diameter_mm:g} mm tool on a helix in the Ø{spec.bore:g} mm "
                                              f"bore leaves a core standing; expected a tool of at least "
                                              f"Ø{spec.bore / 2:g} mm (half the bore)")
    if groove:
        outer = groove_outer_radius(cam, spec)
        radius, at = outer, 0.0
        inner, outer_flank = curve_polygon(cam.flanks[0]), curve_polygon(cam.flanks[1])
        part = outer_flank.difference(inner)
    else:
        radius, at = largest_radius(cam.profile)
        part = curve_polygon(cam.profile)
    if stock.kind == "round":
        diameter = stock.diameter_mm if stock.diameter_mm is not None else 2 * (radius + DEFAULT_OVERSIZE_MM)
        if diameter / 2 < radius:
            raise SpecError("stock.diameter", f"{diameter:g} mm is smaller than the cam: its largest radius is "
                                              f"{radius:.3f} mm (at cam angle {at:.2f}°); expected at least "
                                              f"{2 * radius:.3f} mm")
        region = _circle(diameter / 2 / math.cos(math.pi / CIRCLE_SEGMENTS))  # circumscribed: never smaller
        allowance = None
    else:
        diameter, allowance = None, stock.allowance_mm
        region = part.buffer(allowance, quad_segs=64)
    return Blank(stock.kind, region, part, radius, at, diameter, allowance, stock.top_allowance_mm, stock.stated,
                 groove, spec.bore, bore)


def bore_region(b: Blank) -> Polygon:
    """The bore as a polygon (inscribed: a cut to it is never short of the circle)."""
    return _circle(b.bore_mm / 2) if b.bore_mm > 0 else Point(0.0, 0.0).buffer(0.0)
