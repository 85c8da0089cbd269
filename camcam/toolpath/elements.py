"""Planar path elements: straight lines and circular arcs.

A fitted contour is a tuple of these, in the direction of travel.  Arcs keep
their centre, radius and direction explicitly so the G-code writer and the DXF
exporter print exactly the geometry the deviation was measured on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Line", "Arc", "circular", "element_tangent", "arc_from_tangent", "element_points", "element_nearest",
           "element_distance", "element_distances", "contour_length"]


@dataclass(frozen=True)
class Line:
    """Straight segment from ``start`` to ``end`` (mm)."""

    start: tuple[float, float]
    end: tuple[float, float]

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    def points(self, n: int) -> np.ndarray:
        return self.at(np.linspace(0.0, 1.0, n))

    def at(self, u) -> np.ndarray:
        """Points (k, 2) at fractions ``u`` (k,) of the way from start to end."""
        u = np.asarray(u, float)[:, None]
        return (1 - u) * np.asarray(self.start) + u * np.asarray(self.end)


@dataclass(frozen=True)
class Arc:
    """Circular arc from ``start`` to ``end`` about ``centre``; ``ccw`` is G3, otherwise G2.

    ``end_radius`` differs from ``radius`` (the start radius) only for printed
    arcs whose rounded end is not exactly on the circle: between the ends the
    radius is interpolated linearly in angle (the spiral a controller cuts).

    Examples
    --------
    >>> a = Arc((1.0, 0.0), (0.0, 1.0), (0.0, 0.0), True)
    >>> round(a.sweep, 12), round(a.length, 12)
    (1.570796326795, 1.570796326795)
    """

    start: tuple[float, float]
    end: tuple[float, float]
    centre: tuple[float, float]
    ccw: bool

    @property
    def radius(self) -> float:
        return math.dist(self.start, self.centre)

    @property
    def end_radius(self) -> float:
        return math.dist(self.end, self.centre)

    @property
    def start_angle(self) -> float:
        return math.atan2(self.start[1] - self.centre[1], self.start[0] - self.centre[0])

    @property
    def sweep(self) -> float:
        """Unsigned swept angle in (0, 2π) (rad)."""
        a0 = self.start_angle
        a1 = math.atan2(self.end[1] - self.centre[1], self.end[0] - self.centre[0])
        d = (a1 - a0) if self.ccw else (a0 - a1)
        d = math.fmod(d, 2 * math.pi)
        return d + 2 * math.pi if d <= 0 else d

    @property
    def length(self) -> float:
        return 0.5 * (self.radius + self.end_radius) * self.sweep

    @property
    def curvature(self) -> float:
        """Signed curvature: +1/R for G3 (left turn), −1/R for G2."""
        return (1.0 if self.ccw else -1.0) / self.radius

    def points(self, n: int) -> np.ndarray:
        return self.at(np.linspace(0.0, 1.0, n))

    def at(self, u) -> np.ndarray:
        """Points (k, 2) at fractions ``u`` (k,) of the sweep from start to end (and of the radius's change)."""
        u = np.asarray(u, float)
        ang = self.start_angle + (1.0 if self.ccw else -1.0) * self.sweep * u
        r = self.radius + (self.end_radius - self.radius) * u
        return np.asarray(self.centre) + r[:, None] * np.stack([np.cos(ang), np.sin(ang)], axis=-1)


def circular(e: Line | Arc) -> Line | Arc:
    """``e`` as a drawing's LINE or ARC can hold it: a line or an arc on one circle as it is, a printed spiral
    arc (``end_radius`` ≠ ``radius``) as the circular arc through its start, the midpoint of its spiral and its
    end.

    An ARC entity has one radius, so a spiral drawn from its centre at its start radius ends |Δr| off its
    end (a gap in a chain of entities, 0.0019 mm on a 137 mm dwell arc printed on a 0.001 mm grid).  The
    arc through the three points keeps both ends exactly; it strays from the spiral by about |Δr|/25 over
    a 120° sweep (7.9e-5 mm at Δr = 0.002 mm, r = 65 mm), and the drawing's figures are measured on it.

    Examples
    --------
    >>> spiral = Arc((10.0, 0.0), (0.0, 10.002), (0.0, 0.0), True)
    >>> a = circular(spiral)
    >>> a.start == spiral.start and a.end == spiral.end, round(a.end_radius - a.radius, 12) + 0.0
    (True, 0.0)
    >>> d = element_distance(a, spiral.points(101))  # the spiral from the arc drawn for it (mm)
    >>> round(float(d[50]), 12), float(d.max()) < 0.002 / 25
    (0.0, True)
    """
    if isinstance(e, Line) or e.end_radius == e.radius:
        return e
    (ax, ay), (bx, by), (cx, cy) = e.start, tuple(e.at([0.5])[0]), e.end
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    centre = ((a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d,
              (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d)
    return Arc(e.start, e.end, (float(centre[0]), float(centre[1])), e.ccw)


def element_tangent(e: Line | Arc, end: bool = True) -> np.ndarray:
    """Unit tangent of ``e`` in its direction of travel, at its end (or start).

    Examples
    --------
    >>> bool(np.allclose(element_tangent(Arc((1.0, 0.0), (0.0, 1.0), (0.0, 0.0), True)), [-1.0, 0.0]))
    True
    """
    if isinstance(e, Line):
        v = np.subtract(e.end, e.start)
        return v / np.hypot(*v)
    r = np.subtract(e.end if end else e.start, e.centre)
    r = r / np.hypot(*r)
    return np.array([-r[1], r[0]]) if e.ccw else np.array([r[1], -r[0]])


def arc_from_tangent(start, tangent, end, line_sagitta: float = 0.0) -> Line | Arc:
    """The arc leaving ``start`` along unit ``tangent`` and ending at ``end``.

    Returns a :class:`Line` when the arc's sagitta is at most ``line_sagitta``
    (a straight or nearly straight piece; also what keeps huge radii out of
    the program).

    Examples
    --------
    >>> a = arc_from_tangent((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0))
    >>> a.centre, a.ccw
    ((0.0, 0.0), True)
    """
    p0 = np.asarray(start, float)
    t = np.asarray(tangent, float)
    v = np.asarray(end, float) - p0
    n = np.array([-t[1], t[0]])
    chord2 = float(v @ v)
    h = float(n @ v)  # signed offset of the end from the tangent line
    # sagitta of the arc over its chord: r(1 - cos(sweep/2)), with sin(sweep/2) = |h|/chord
    chord = math.sqrt(chord2)
    if chord == 0.0:
        raise ValueError("arc with coincident ends")
    half = math.asin(min(1.0, abs(h) / chord))
    if float(t @ v) < 0:  # more than a half turn
        half = math.pi - half
    sag = (chord / 2) * math.tan(half / 2)
    if sag <= line_sagitta:
        return Line(tuple(map(float, p0)), tuple(map(float, p0 + v)))
    r = chord2 / (2 * h)  # signed: > 0 centre on the left
    c = p0 + r * n
    return Arc(tuple(map(float, p0)), tuple(map(float, p0 + v)), (float(c[0]), float(c[1])), r > 0)


def element_points(elements, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Points every ≤ ``spacing`` mm along each element (ends included) and their element index."""
    pts, idx = [], []
    for i, e in enumerate(elements):
        n = max(2, int(math.ceil(e.length / spacing)) + 1)
        pts.append(e.points(n))
        idx.append(np.full(n, i))
    return np.concatenate(pts), np.concatenate(idx)


def element_nearest(e: Line | Arc, q: np.ndarray) -> np.ndarray:
    """Nearest points of element ``e`` to points ``q`` (n, 2), shape (n, 2).

    A printed arc whose rounded end is off its circle is the spiral a controller
    cuts: its radius is interpolated linearly in angle between the ends.
    """
    q = np.atleast_2d(np.asarray(q, dtype=float))
    a, b = np.asarray(e.start, dtype=float), np.asarray(e.end, dtype=float)
    if isinstance(e, Line):
        d = b - a
        L2 = float(d @ d)
        u = np.clip(((q - a) @ d) / L2, 0.0, 1.0) if L2 > 0 else np.zeros(len(q))
        return a + u[:, None] * d
    nearer_end = np.where((np.hypot(*(q - a).T) <= np.hypot(*(q - b).T))[:, None], a, b)
    c = np.asarray(e.centre, dtype=float)
    rel = q - c
    dist = np.hypot(rel[:, 0], rel[:, 1])
    ang = np.arctan2(rel[:, 1], rel[:, 0])
    s = 1.0 if e.ccw else -1.0
    u = np.mod(s * (ang - e.start_angle), 2 * np.pi) / e.sweep
    r = e.radius + (e.end_radius - e.radius) * np.clip(u, 0, 1)
    safe = np.where(dist > 0, dist, 1.0)  # a point at the centre: any ray will do
    on_arc = c + (r / safe)[:, None] * np.where((dist > 0)[:, None], rel, a - c)
    use_arc = (u <= 1.0) & (np.hypot(*(q - on_arc).T) < np.hypot(*(q - nearer_end).T))
    return np.where(use_arc[:, None], on_arc, nearer_end)


def element_distance(e: Line | Arc, q: np.ndarray) -> np.ndarray:
    """Exact distance from points ``q`` (n, 2) to element ``e``."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    return np.hypot(*(q - element_nearest(e, q)).T)


def element_distances(elements, q: np.ndarray) -> np.ndarray:
    """Exact distances from points ``q`` (n, 2) to each of ``elements``, shape (len(elements), n).

    Row k is ``element_distance(elements[k], q)`` to the last bit: the arcs are
    measured together with :func:`element_nearest`'s elementwise arithmetic
    (numpy's elementwise functions give each element the same result in any
    array), their scalars (radii, start angle, sweep) from the same
    properties; a line's row is :func:`element_distance` itself (its
    projection is a dot product, whose rounding may depend on the array).
    One call instead of one per element: what the closing biarcs of
    :mod:`camcam.toolpath.arcclose` spend their time on.

    Examples
    --------
    >>> arcs = [Arc((1.0, 0.0), (0.0, 1.0), (0.0, 0.0), True), Line((0.0, 0.0), (1.0, 0.0))]
    >>> element_distances(arcs, np.array([[2.0, 0.0], [0.5, 0.5]])).round(6).tolist()
    [[1.0, 0.292893], [1.0, 0.5]]
    """
    q = np.atleast_2d(np.asarray(q, dtype=float))
    out = np.empty((len(elements), len(q)))
    rows = [k for k, e in enumerate(elements) if isinstance(e, Arc)]
    for k, e in enumerate(elements):
        if not isinstance(e, Arc):
            out[k] = element_distance(e, q)
    if not rows:
        return out
    arcs = [elements[k] for k in rows]
    col = lambda values: np.array(values, dtype=float)[:, None]  # noqa: E731  one scalar per arc, (k, 1)
    a = np.array([e.start for e in arcs], dtype=float)[:, None, :]
    b = np.array([e.end for e in arcs], dtype=float)[:, None, :]
    c = np.array([e.centre for e in arcs], dtype=float)[:, None, :]
    radius, end_radius = col([e.radius for e in arcs]), col([e.end_radius for e in arcs])
    start_angle, sweep = col([e.start_angle for e in arcs]), col([e.sweep for e in arcs])
    s = col([1.0 if e.ccw else -1.0 for e in arcs])
    qq = q[None, :, :]
    da, db = qq - a, qq - b
    nearer_end = np.where((np.hypot(da[..., 0], da[..., 1]) <= np.hypot(db[..., 0], db[..., 1]))[..., None], a, b)
    rel = qq - c
    dist = np.hypot(rel[..., 0], rel[..., 1])
    ang = np.arctan2(rel[..., 1], rel[..., 0])
    u = np.mod(s * (ang - start_angle), 2 * np.pi) / sweep
    r = radius + (end_radius - radius) * np.clip(u, 0, 1)
    safe = np.where(dist > 0, dist, 1.0)
    on_arc = c + (r / safe)[..., None] * np.where((dist > 0)[..., None], rel, a - c)
    d_arc, d_end = qq - on_arc, qq - nearer_end
    use_arc = (u <= 1.0) & (np.hypot(d_arc[..., 0], d_arc[..., 1]) < np.hypot(d_end[..., 0], d_end[..., 1]))
    near = np.where(use_arc[..., None], on_arc, nearer_end)
    d = qq - near
    out[rows] = np.hypot(d[..., 0], d[..., 1])
    return out


def contour_length(elements) -> float:
    return float(sum(e.length for e in elements))
