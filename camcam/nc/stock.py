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
from camcam.geometry.params import Dowel
from camcam.nc.settings import DEFAULT_OVERSIZE_MM, DEFAULT_STOCK, STOCK_KINDS, StockSpec

__all__ = ["Blank", "blank_for", "largest_radius", "curve_polygon", "CIRCLE_SEGMENTS", "MeasuringPolygon",
           "measuring_polygon", "measuring_circle", "MAX_POLYGON_POINTS", "DEFAULT_OVERSIZE_MM", "STOCK_KINDS",
           "bore_region"]

#: Segments of a planning circle (the blank's outline, :func:`bore_region`): chord error R·(1 − cos(π/n)),
#: 1.9e-5·R.  Not a measuring polygon: the material check measures against :func:`measuring_circle`.
CIRCLE_SEGMENTS = 512

#: Points per analytic piece of a planning polygon (:func:`curve_polygon`: the part the roughing rings are offset
#: from, whose margin ``ROUGH_MARGIN_MM`` covers its chords).  Its chord error grows with the cam's size (4.2e-4 mm
#: on the default cam's 120° rise at R 3000), so figures are never measured against it: :func:`measuring_polygon`.
POINTS_PER_PIECE = 2000

#: Most vertices one measuring polygon gets (:func:`measuring_polygon`, :func:`measuring_circle`).  At the
#: budget's 1 % of δ the default cam at R 5 m and δ = 0.001 mm needs 49 820; a polygon that would need more than
#: this gets this many, and its larger measured chord error is what :attr:`MeasuringPolygon.error_mm` says.
MAX_POLYGON_POINTS = 400_000

#: Parameter samples per analytic piece where the curvature is read to place a measuring polygon's vertices.
_SCAN = 256


def largest_radius(curve) -> tuple[float, float]:
    """(largest distance from the cam axis, cam angle in degrees) of a closed cam curve, from the roots of d|p|²/dθ."""

    def r2(t, i):
        x, y = curve.jets(t, 1, i)
        j = x * x + y * y
        return j.d[0], j.d[1]

    c = extreme(r2, curve.breaks, "max")
    return math.sqrt(c.value), math.degrees(c.t)


def curve_polygon(curve, per_piece: int = POINTS_PER_PIECE) -> Polygon:
    """A closed cam curve as a planning polygon, ``per_piece`` samples per analytic piece as vertices (valid and
    oriented ccw).  Figures are measured against :func:`measuring_polygon` instead."""
    br = curve.breaks
    t = np.concatenate([np.linspace(a, b, per_piece, endpoint=False) for a, b in zip(br, br[1:])])
    poly = Polygon(curve.evaluate(t))
    if not poly.is_valid:
        raise SpecError("cam", "the profile crosses itself; cannot build the material regions")
    return shapely.geometry.polygon.orient(poly, 1.0)


@dataclass(frozen=True)
class MeasuringPolygon:
    """A polygon a figure is measured against, and its measured chord error (mm, one-sided off the curve)."""

    polygon: Polygon
    error_mm: float


def _chord_sag(curve, t: np.ndarray, closed_end: float) -> np.ndarray:
    """Each chord's distance from the curve at its parameter midpoint (the chords t[i] → t[i+1], the last one
    to ``closed_end``), (n,): a smooth arc's sag peaks there, to leading order (κh²/8)."""
    t1 = np.append(t[1:], closed_end)
    p0, p1, pm = curve.evaluate(t), curve.evaluate(t1), curve.evaluate(0.5 * (t + t1))
    d = p1 - p0
    length = np.hypot(d[:, 0], d[:, 1])
    cross = np.abs(d[:, 0] * (pm[:, 1] - p0[:, 1]) - d[:, 1] * (pm[:, 0] - p0[:, 0]))
    return np.where(length > 0, cross / np.where(length > 0, length, 1.0), np.hypot(*(pm - p0).T))


def measuring_polygon(curve, chord_mm: float, max_points: int = MAX_POLYGON_POINTS) -> MeasuringPolygon:
    """A closed cam curve as a polygon whose chords stay within ``chord_mm`` of it (valid, oriented ccw).

    A chord of length h where the radius of curvature is ρ lies h²/8ρ off the curve (seed 004's
    δ ≈ ρΔφ²/8), so the vertices are spaced by h = √(8ρ·``chord_mm``): placed at equal steps of
    ∫√κ ds (κ read on :data:`_SCAN` samples per analytic piece), then every chord's sag is measured at its
    midpoint and a chord still over ``chord_mm`` is halved, until none is.  Past ``max_points`` vertices
    the spacing is widened to fit the cap and the measured error says how far the polygon is off.

    Examples
    --------
    >>> from camcam.geometry.curve import FunctionCurve
    >>> circle = FunctionCurve(lambda t, k: 5000.0 * np.column_stack([np.cos(t + k * np.pi / 2),
    ...                                                             np.sin(t + k * np.pi / 2)]), 0.0, 2 * np.pi)
    >>> m = measuring_polygon(circle, 1e-5)
    >>> m.error_mm <= 1e-5, len(m.polygon.exterior.coords) - 1   # 2000 points would err by 0.0062 mm
    (True, 49673)
    """
    from camcam.geometry.curve import curvature, speed

    br = np.asarray(curve.breaks, float)
    pieces, totals = [], []
    for a, b in zip(br, br[1:]):
        tt = np.linspace(a, b, _SCAN + 1)
        w = np.sqrt(np.abs(curvature(curve, tt))) * speed(curve, tt)
        u = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(tt))])
        u += np.linspace(0.0, 1e-9 * max(u[-1], 1.0), len(u))  # strictly increasing where the curve is straight
        pieces.append((tt, u))
        totals.append(u[-1])
    step = math.sqrt(8.0 * chord_mm)  # ∫√κ ds per chord
    need = sum(max(1, math.ceil(total / step)) for total in totals)
    if need > max_points:
        step *= need / max_points
    t = np.concatenate([np.interp(np.linspace(0.0, u[-1], max(1, math.ceil(u[-1] / step)), endpoint=False), u, tt)
                        for tt, u in pieces])
    end = float(br[-1])
    sag = _chord_sag(curve, t, end)
    while (sag > chord_mm).any() and 2 * len(t) <= max_points:
        over = np.flatnonzero(sag > chord_mm)
        t1 = np.append(t[1:], end)
        t = np.sort(np.concatenate([t, 0.5 * (t[over] + t1[over])]))
        sag = _chord_sag(curve, t, end)
    poly = Polygon(curve.evaluate(t))
    if not poly.is_valid:
        raise SpecError("cam", "the profile crosses itself; cannot build the material regions")
    return MeasuringPolygon(shapely.geometry.polygon.orient(poly, 1.0), float(sag.max()))


def measuring_circle(radius: float, chord_mm: float, max_points: int = MAX_POLYGON_POINTS) -> MeasuringPolygon:
    """A circle about the cam axis as an inscribed polygon whose chords lie within ``chord_mm`` of it:
    n = ⌈π / arccos(1 − ``chord_mm``/R)⌉ sides (at least :data:`CIRCLE_SEGMENTS`, at most ``max_points``)."""
    n = CIRCLE_SEGMENTS
    if radius > chord_mm:
        n = min(max(n, math.ceil(math.pi / math.acos(1.0 - chord_mm / radius))), max_points)
    a = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    return MeasuringPolygon(Polygon(np.column_stack([radius * np.cos(a), radius * np.sin(a)])),
                            radius * (1.0 - math.cos(math.pi / n)))


def _circle(radius: float) -> Polygon:
    a = np.linspace(0.0, 2 * math.pi, CIRCLE_SEGMENTS, endpoint=False)
    return Polygon(np.column_stack([radius * np.cos(a), radius * np.sin(a)]))


@dataclass(frozen=True, kw_only=True)
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
    dowel: Dowel | None = None  # the dowel hole when the program cuts it ([machining] dowel = true)

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


def blank_for(built: BuiltCam, stock: StockSpec, tool_diameter_mm: float, bore: bool = False,
              dowel: bool = False) -> Blank:
    """The blank of ``stock`` around ``built`` (a disc or face-groove cam).

    Raises
    ------
    SpecError
        ``stock.diameter`` smaller than the cam, ``cam.bore`` larger than the
        base circle minus the roller, ``machining.bore`` with no bore or one the
        tool does not fit, ``machining.dowel`` with no dowel hole or one the tool does not fit.
    """
    cam, spec = built.cam, built.spec
    groove = spec.kind == "disc-groove"
    roller = cam.roller_radius or 0.0
    # 1e-9 mm: a bore exactly as wide as the room is taken, however the subtraction rounds (15.85 − 12 is
    # 3.8499999999999996 in floats: the advice "base_radius >= 15.85 takes the Ø7.7 bore" refused itself)
    if spec.bore > 0 and spec.bore / 2 > cam.base_radius - roller + 1e-9:
        room = 2 * (cam.base_radius - roller)
        # the base radius that takes this bore, up to the 0.01 mm a spec is typed in
        fix = f"cam.base_radius >= {math.ceil((roller + spec.bore / 2) * 100 - 1e-9) / 100:g} mm takes the " \
              f"Ø{spec.bore:g} mm bore"
        if room <= 0:  # never "at most Ø-4 mm": no bore fits at all
            raise SpecError("cam.bore", f"Ø{spec.bore:g} mm: no bore fits, the base circle minus the roller leaves "
                                        f"nothing ({cam.base_radius:g} − {roller:g} mm); expected cam.bore = 0 "
                                        f"(no bore), or {fix}")
        raise SpecError("cam.bore", f"Ø{spec.bore:g} mm is larger than the base circle minus the roller; expected at "
                                    f"most Ø{room:g} mm (2 × ({cam.base_radius:g} − {roller:g})), or {fix}")
    if bore:
        _check_helix_fits("machining.bore", "bore", spec.bore, tool_diameter_mm, "the cam has no bore (cam.bore = 0)")
    if dowel:
        _check_helix_fits("machining.dowel", "dowel hole", spec.dowel.diameter if spec.dowel else 0.0,
                          tool_diameter_mm, "the cam has no dowel hole ([cam] dowel)")
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
            # the 0.001 mm value at or above the cam's diameter, so that a stock of the size named holds it (campaign
            # case 45:2 was told "expected at least 337.880 mm" for a radius of 168.94002 mm, and refused 337.88)
            least = math.ceil(2 * radius * 1000.0) / 1000.0
            raise SpecError("stock.diameter", f"{diameter:g} mm is smaller than the cam: its largest radius is "
                                              f"{radius:.3f} mm (at cam angle {at:.2f}°); expected at least "
                                              f"{least:.3f} mm")
        region = _circle(diameter / 2 / math.cos(math.pi / CIRCLE_SEGMENTS))  # circumscribed: never smaller
        allowance = None
    else:
        diameter, allowance = None, stock.allowance_mm
        region = part.buffer(allowance, quad_segs=64)
    return Blank(kind=stock.kind, region=region, part=part, cam_radius_mm=radius, cam_radius_at_deg=at,
                 diameter_mm=diameter, allowance_mm=allowance, top_z_mm=stock.top_allowance_mm, stated=stock.stated,
                 groove=groove, bore_mm=spec.bore, bore_machined=bore, dowel=spec.dowel if dowel else None)


def _check_helix_fits(key: str, what: str, diameter_mm: float, tool_diameter_mm: float, missing: str) -> None:
    """A hole cut as a helical bore (:mod:`camcam.nc.bore`) needs a tool smaller than it and at least half as
    wide (a smaller one leaves a core standing): :class:`SpecError` naming ``key`` otherwise."""
    if diameter_mm <= 0:
        raise SpecError(key, f"true, but {missing}")
    if diameter_mm <= tool_diameter_mm:
        raise SpecError(key, f"the tool Ø{tool_diameter_mm:g} mm does not fit the {what} Ø{diameter_mm:g} mm; "
                             f"expected a tool smaller than the {what}")
    if diameter_mm / 2 > tool_diameter_mm:
        raise SpecError(key, f"a Ø{tool_diameter_mm:g} mm tool on a helix in the Ø{diameter_mm:g} mm {what} leaves "
                             f"a core standing; expected a tool of at least Ø{diameter_mm / 2:g} mm (half the {what})")


def bore_region(b: Blank) -> Polygon:
    """The bore as a polygon (inscribed: a cut to it is never short of the circle)."""
    return _circle(b.bore_mm / 2) if b.bore_mm > 0 else Point(0.0, 0.0).buffer(0.0)
