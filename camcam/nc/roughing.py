"""Roughing geometry: spirals from the blank to the finish allowance, ramps along closed contours.

A disc cam is roughed at each depth level by one spiral that starts with the
tool's edge on the blank's outline and winds inward to the last ring, the part
(shapely polygon) offset by ``allowance + margin + r_t`` (the tool-centre path
with its edge at the allowance and :data:`ROUGH_MARGIN_MM`), then closes on
that ring.  In polar form about the cam axis every turn is a blend of the two,
r = r_last + t·(r_first − r_last), t falling by 1/n a turn: each turn lies
parallel to the one before it, and the first one to the blank's edge, so the
tool meets the material side-on everywhere, never across its path.  (Rings
offset from the part, as before, ran across the round blank's edge wherever
the part's outline bends inward, and the tool met that edge at an angle: 25 %
over the stepover, whatever the stepover.)  How many turns: enough that
no turn advances more than the step normal to itself, and less where it is
concave toward the material, where a band spans more of the tool than its depth
(:func:`loops_needed`); so the engagement the material check measures stays
within the stepover by construction.  The spiral is fitted with lines and arcs
(:func:`polyline_elements`) within :data:`ROUGH_FIT_MM`; the last ring keeps
:data:`ROUGH_MARGIN_MM` more than the finish allowance so the fitted path stays
at least the allowance off the part.

Closed contours that have no way in from outside the material (a face
groove) are entered down a ramp along the contour itself
(:func:`ramp_elements`), no steeper than the ramp angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Polygon

from camcam.errors import GeometryError
from camcam.geometry.curve import curvature
from camcam.toolpath.elements import Arc, Line

__all__ = ["Spiral", "disc_spiral", "polygon_distance", "polyline_elements", "polar_radii", "ROUGH_FIT_MM",
           "ROUGH_MARGIN_MM", "RING_STEP_FRACTION", "GrooveRings", "groove_rings", "band_width"]

#: Fit tolerance of roughing paths (mm): they need not meet the finish tolerance, only stay off the part.
ROUGH_FIT_MM = 0.02
#: Extra stock the last roughing ring keeps over the finish allowance (mm); covers the fit, the polygons and rounding.
ROUGH_MARGIN_MM = 0.05
#: Ring spacing as a fraction of the stepover: the spiral's drift across a revolution adds to the band it cuts.
RING_STEP_FRACTION = 0.9
#: Samples per revolution of a spiral before fitting.
SPIRAL_SAMPLES = 1440
#: Arc length each side over which a loop's radii are averaged before its curvature is taken (mm).
CURVATURE_SPAN_MM = 1.0
#: Distance the entry point sits outside the first ring, radially (mm).
ENTRY_CLEARANCE_MM = 1.0


def polar_radii(ring: np.ndarray, thetas: np.ndarray, what: str) -> np.ndarray:
    """Radii of a closed ring (n, 2) about the origin at polar angles ``thetas`` (linear between vertices).

    Raises :class:`GeometryError` if the ring is not star-shaped about the origin.
    """
    phi = np.unwrap(np.arctan2(ring[:, 1], ring[:, 0]))
    rho = np.hypot(ring[:, 0], ring[:, 1])
    steps = np.diff(phi)
    if np.all(steps < 0):
        phi, rho = phi[::-1], rho[::-1]
        steps = -steps[::-1]
    if not np.all(steps > 0) or abs(phi[-1] - phi[0] - 2 * math.pi) > 1e-6:
        raise GeometryError(f"roughing: the {what} is not star-shaped about the cam axis; cannot spiral to it")
    base = phi[0]
    return np.interp(np.mod(thetas - base, 2 * math.pi) + base, phi, rho)


def _ring(poly: Polygon) -> np.ndarray:
    if poly.geom_type != "Polygon":
        raise GeometryError("roughing: an offset of the part falls apart; cannot spiral to it")
    return np.asarray(poly.exterior.coords)


@dataclass(frozen=True, kw_only=True)
class Spiral:
    """One level's roughing path: ``entry`` (clear of the blank) then ``elements`` (tool centre, direction of cut).

    ``revolutions`` spiral turns plus one closing ring; ``step_mm`` the most a
    turn advances normal to the path where it is straight or convex (less where
    it is concave); ``clearance_mm`` the tool edge's intended distance from the
    part on the last ring; ``plain_revolutions`` the turns the same step would
    need without the concave parts (fewer than ``revolutions`` where they add turns).
    """

    entry: tuple[float, float]
    elements: tuple
    revolutions: int
    step_mm: float
    clearance_mm: float
    plain_revolutions: int = 0

    def describe(self) -> str:
        """The spiral in the pass table and the pass comment."""
        more = self.revolutions - self.plain_revolutions
        extra = f", {more} more where the path is concave" if more > 0 and self.plain_revolutions else ""
        return f"spiral {self.revolutions} turns at most {self.step_mm:.2f} mm apart{extra}"


def polygon_distance(poly, xy: np.ndarray) -> np.ndarray:
    """``shapely.distance(poly, shapely.points(xy))``, (n,) for points (n, 2), through an R-tree of its edges.

    GEOS measures a point against every edge of a polygon; an offset blank has
    10 000 edges, so 10 000 points took 2.3 s.  The nearest edge from the tree
    gives the same distance (GEOS's point-to-segment distance either way) to
    within an ulp: edges that meet at the nearest vertex each give its distance
    to within one, and the tree may return one above GEOS's least (two circles
    1e-15 mm apart, merged: 37.4234375 against 37.42343749999999; measuring
    every edge near the nearest one to settle that took 0.27 → 0.44 s for
    10 000 points); a point inside the polygon is at 0.  ``poly`` is a Polygon or a
    MultiPolygon (the edges of all its parts; inside any part is 0).

    Examples
    --------
    >>> square = shapely.box(0.0, 0.0, 2.0, 2.0)
    >>> polygon_distance(square, np.array([[3.0, 1.0], [1.0, 1.0], [3.0, 3.0]])).round(6).tolist()
    [1.0, 0.0, 1.414214]
    """
    xy = np.asarray(xy, float)
    segments = []
    for part in shapely.get_parts(poly):
        for ring in (part.exterior, *part.interiors):
            c = np.asarray(ring.coords)
            segments.append(np.stack([c[:-1], c[1:]], axis=1))
    tree = shapely.STRtree(shapely.linestrings(np.concatenate(segments)))
    (which, _), dist = tree.query_nearest(shapely.points(xy), return_distance=True, all_matches=False)
    out = np.empty(len(xy))
    out[which] = dist
    out[shapely.contains_xy(poly, xy[:, 0], xy[:, 1])] = 0.0
    return out


def disc_spiral(part: Polygon, blank: Polygon, tool_radius_mm: float, allowance_mm: float, stepover_mm: float,
                clockwise: bool, max_sweep_deg: float) -> Spiral | None:
    """The roughing spiral from ``blank`` to ``allowance_mm`` (+ margin) around ``part``; ``None`` if nothing to rough.

    ``clockwise``: the direction of travel about the cam axis (the finish pass's).  The loops run from the
    blank's own outline (the tool's edge on it) to the last ring, each a polar blend of the two
    (:func:`loops_needed` says how many hold the engagement to ``stepover_mm``).
    """
    r_t = tool_radius_mm
    keep = allowance_mm + ROUGH_MARGIN_MM
    # what one loop may advance normal to the path: the stepover less the drift across a revolution and the
    # fit of this loop and the one before it (each within ROUGH_FIT_MM of its samples)
    step = max(RING_STEP_FRACTION * stepover_mm - 2 * ROUGH_FIT_MM, 0.5 * RING_STEP_FRACTION * stepover_mm)
    s = -1.0 if clockwise else 1.0
    th = np.linspace(0.0, 2 * math.pi, SPIRAL_SAMPLES, endpoint=False)
    r0 = polar_radii(_ring(part.buffer(keep + r_t, quad_segs=64)), th, "last ring")
    # the first loop: the tool's edge on the blank's outline (nowhere inside the last ring)
    rb = np.maximum(polar_radii(_ring(blank.buffer(r_t, quad_segs=64)), th, "blank's outline"), r0)
    n, plain = loops_needed(th, r0, rb, r_t, step)
    if n <= 0:
        return None
    j0 = int(np.argmax(rb - r0))  # start where most material lies: the first loop runs on the blank's outline
    order = (j0 + s * np.arange(SPIRAL_SAMPLES)).astype(int) % SPIRAL_SAMPLES
    th_o = th[order]
    f = np.arange(SPIRAL_SAMPLES) / SPIRAL_SAMPLES
    ang, rad = [], []
    for rev in range(n):
        ang.append(th_o)
        rad.append(r0[order] + (1 - (rev + f) / n) * (rb - r0)[order])
    ang.append(th_o)
    rad.append(r0[order])
    ang.append(th_o[:1])
    rad.append(r0[order][:1])
    ang, rad = np.concatenate(ang), np.concatenate(rad)
    pts = np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])
    u = pts[0] / np.hypot(*pts[0])
    entry = pts[0] + ENTRY_CLEARANCE_MM * u
    return Spiral(entry=(float(entry[0]), float(entry[1])),
                  elements=polyline_elements(pts, ROUGH_FIT_MM, max_sweep_deg),
                  revolutions=n, step_mm=step, clearance_mm=keep, plain_revolutions=plain)


def loops_needed(th: np.ndarray, r0: np.ndarray, rb: np.ndarray, tool_radius_mm: float, step_mm: float,
                 blends: int = 21) -> tuple[int, int]:
    """Loops a spiral from the polar curve ``rb`` to ``r0`` (radii at angles ``th``) needs: (with the concave
    parts, without them).

    A loop at blend t, r = r0 + t·(rb − r0), lies (rb − r0)/n·cos β from the next one along its normal (β the
    angle between the radius and the normal, tan β = r′/r).  The material still to cut lies inside the loop,
    toward the part.  Where the loop is concave seen from the cam axis (the part's outline bends inward; the
    centre of curvature, radius ρ, lies on the cut side, as in a pocket), a tool on it that meets a band
    ``ae`` deep spans more than ``ae`` across its travel: the band's edge is a circle of radius ρ + r_t − ae
    about the same centre, and the tool's leading half meets the material beyond it over the width
    ae·(1 + (2 r_t − ae)/(2ρ)).
    So a loop may advance at most the ae that makes that ``step_mm``, the root
    ae = (ρ + r_t) − √((ρ + r_t)² − 2ρ·step) (``step_mm`` on a straight or convex stretch).  The curvature is
    the polar curve's, its radii averaged over :data:`CURVATURE_SPAN_MM` each side (the polygons' vertices
    would make it noise; averaged over a tool radius, it missed short concave stretches: 1.000 of the stepover
    measured at stepover 0.1), on ``blends`` loops from the last to the first.
    """
    r_t = tool_radius_mm
    dth = float(th[1] - th[0])
    dr = rb - r0
    need = plain = 0.0
    for t in np.linspace(0.0, 1.0, blends):
        r = r0 + t * dr
        w = max(1, int(round(CURVATURE_SPAN_MM / (float(r.mean()) * dth))))
        rs = np.convolve(np.concatenate([r[-w:], r, r[:w]]), np.ones(2 * w + 1) / (2 * w + 1), mode="valid")
        r1 = (np.roll(rs, -1) - np.roll(rs, 1)) / (2 * dth)
        r2 = (np.roll(rs, -1) - 2 * rs + np.roll(rs, 1)) / dth**2
        kappa = (rs**2 + 2 * r1**2 - rs * r2) / (rs**2 + r1**2) ** 1.5  # > 0 convex (about the cam axis)
        cos_b = rs / np.hypot(rs, r1)
        rho = 1.0 / np.maximum(-kappa, 1e-12)
        a = rho + r_t
        ae = np.where(kappa < 0, a - np.sqrt(np.maximum(a * a - 2 * rho * step_mm, 0.0)), step_mm)
        need = max(need, float((dr * cos_b / ae).max()))
        plain = max(plain, float((dr * cos_b).max()) / step_mm)
    return int(math.ceil(need - 1e-9)), int(math.ceil(plain - 1e-9))


def band_width(ae, bend, tool_radius_mm: float):
    """The width across its travel of a band ``ae`` deep that a tool meets on a path bending away from the
    material with curvature ``bend`` (1/mm; 0 where the path is straight or bends toward the material).

    The band's edge is a circle of radius ρ + r_t − ae about the path's centre of curvature (ρ = 1/bend), and
    the tool's leading half meets the material beyond it over ae·(1 + (2 r_t − ae)/(2ρ)) (:func:`loops_needed`),
    written with the curvature so that a straight path gives ``ae`` itself.

    Examples
    --------
    >>> band_width(5.65, 0.0, 8.0), round(float(band_width(5.65, 1 / 28.5, 8.0)), 3)  # straight; case 43:140's ring
    (5.65, 6.676)
    """
    return ae * (1.0 + (2.0 * tool_radius_mm - ae) * bend / 2.0)


@dataclass(frozen=True, kw_only=True)
class GrooveRings:
    """A face groove's rough rings on one side of its centre pass: their offsets from the centre line (mm,
    toward the flank; the flank pass at ``span_mm`` follows them), and how many the step alone needs.

    ``widest_mm`` is the widest band any ring or the flank pass meets (:func:`band_width`), within ``step_mm``.
    """

    offsets: tuple[float, ...]
    span_mm: float
    step_mm: float
    plain: int
    widest_mm: float

    def describe(self, j: int) -> str:
        """Ring ``j`` (from 1) in the pass table and the pass comment."""
        n = len(self.offsets)
        more = n - self.plain
        extra = f", {more} more where the path is concave" if more > 0 else ""
        return f"ring {j} of {n}, {self.span_mm / (n + 1):.2f} mm apart{extra}"


def groove_rings(ring_curve, material_side, span_mm: float, tool_radius_mm: float, step_mm: float,
                 samples: int = 4096) -> GrooveRings:
    """The rough rings between a groove's centre pass and one flank pass, each band within ``step_mm``.

    ``ring_curve(o)``: the tool-centre curve ``o`` mm from the centre line toward the flank (``o`` =
    ``span_mm``: the flank pass); ``material_side(curve, t)``: +1 where the material lies left of its travel, −1
    right.  The rings are spaced equally, span/(n + 1) apart: n the least count whose every band (the centre
    pass's edge to ring 1, … , the last ring to the flank pass) is at most ``step_mm`` wide as the tool meets it,
    widened where the ring bends away from the material (:func:`band_width`: a groove's outer rings round a
    bend of the pitch curve; its inner rings round the opposite bends), not only straight.  Equal steps of
    span/step gave case 43:140 one ring 5.65 mm from the centre pass, 6.687 mm wide round the pitch
    curve's 22.9 mm bend, for a 6.4 mm stepover (issue 43 E).
    """
    r_t = tool_radius_mm
    plain = max(0, math.ceil(span_mm / step_mm - 1e-9) - 1)
    bends: dict[float, float] = {}

    def bend(o: float) -> float:
        """The largest curvature of the ring ``o`` from the centre line away from the material."""
        if o not in bends:
            c = ring_curve(o)
            t = np.linspace(float(c.t_start), float(c.t_end), samples, endpoint=False)
            t = np.union1d(t, np.clip(np.asarray(c.breaks, float), c.t_start, c.t_end - 1e-12))
            k = curvature(c, t) * material_side(c, t)
            bends[o] = float(np.max(np.maximum(-k, 0.0)))
        return bends[o]

    n = plain
    while True:
        ae = span_mm / (n + 1)
        offsets = [span_mm * j / (n + 1) for j in range(1, n + 2)]
        widest = max(float(band_width(ae, bend(o), r_t)) for o in offsets)
        if widest <= step_mm or ae <= 1e-3:
            return GrooveRings(offsets=tuple(offsets[:-1]), span_mm=span_mm, step_mm=step_mm, plain=plain,
                               widest_mm=widest)
        n += 1


# -- fitting a dense polyline with lines and arcs ------------------------------------------------------------


def _circle(p, q, r):
    """Centre and radius of the circle through three points, or None when (nearly) collinear."""
    ax, ay = q[0] - p[0], q[1] - p[1]
    bx, by = r[0] - p[0], r[1] - p[1]
    d = 2 * (ax * by - ay * bx)
    if abs(d) < 1e-12:
        return None
    a2, b2 = ax * ax + ay * ay, bx * bx + by * by
    cx = p[0] + (by * a2 - ay * b2) / d
    cy = p[1] + (ax * b2 - bx * a2) / d
    return (cx, cy), math.hypot(cx - p[0], cy - p[1]), d > 0


def _try(pts: np.ndarray, i: int, j: int, tolerance_mm: float, max_sweep: float):
    """An element from pts[i] to pts[j] within ``tolerance_mm`` of every point between, or None."""
    seg = pts[i:j + 1]
    a, b = seg[0], seg[-1]
    d = b - a
    L = math.hypot(*d)
    if L == 0:
        return None
    off = np.abs((seg[:, 0] - a[0]) * d[1] - (seg[:, 1] - a[1]) * d[0]) / L
    if off.max() <= tolerance_mm:
        return Line((float(a[0]), float(a[1])), (float(b[0]), float(b[1])))
    circ = _circle(a, seg[len(seg) // 2], b)
    if circ is None:
        return None
    c, radius, ccw = circ
    if radius > 1e5:
        return None
    dist = np.hypot(seg[:, 0] - c[0], seg[:, 1] - c[1])
    if np.abs(dist - radius).max() > tolerance_mm:
        return None
    arc = Arc((float(a[0]), float(a[1])), (float(b[0]), float(b[1])), (float(c[0]), float(c[1])), bool(ccw))
    if arc.sweep > max_sweep:
        return None
    # the points must run along the arc in order (no fold-back)
    ang = np.unwrap(np.arctan2(seg[:, 1] - c[1], seg[:, 0] - c[0]))
    steps = np.diff(ang) * (1 if ccw else -1)
    return arc if np.all(steps >= -1e-12) else None


def polyline_elements(points: np.ndarray, tolerance_mm: float, max_sweep_deg: float) -> tuple:
    """Greedy lines and arcs through a dense polyline, each within ``tolerance_mm`` of the points it replaces.

    Examples
    --------
    >>> a = np.linspace(0, np.pi, 181)
    >>> els = polyline_elements(np.column_stack([10 * np.cos(a), 10 * np.sin(a)]), 0.01, 120.0)
    >>> [type(e).__name__ for e in els], round(els[0].radius, 6)
    (['Arc', 'Arc'], 10.0)
    """
    pts = np.asarray(points, float)
    max_sweep = math.radians(min(max_sweep_deg, 179.0))
    out, i, n = [], 0, len(pts)
    while i < n - 1:
        best, good = _try(pts, i, i + 1, tolerance_mm, max_sweep), i + 1
        step, bad = 1, None
        while good + step <= n - 1:  # gallop, then bisect between the last fit and the first miss
            e = _try(pts, i, good + step, tolerance_mm, max_sweep)
            if e is None:
                bad = good + step
                break
            best, good = e, good + step
            step *= 2
        if bad is None:
            bad = n
        while bad - good > 1:
            mid = (good + bad) // 2
            e = _try(pts, i, mid, tolerance_mm, max_sweep)
            if e is None:
                bad = mid
            else:
                best, good = e, mid
        out.append(best)
        i = good
    return tuple(out)
