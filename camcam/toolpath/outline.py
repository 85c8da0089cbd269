"""The part outline a closed tool-centre path of lines and arcs cuts: its exact offset by the tool radius.

An offset line is a line and an offset arc is a concentric arc, so the
outline is lines and arcs too.  At a joint where the path turns away from
the material the offsets leave a gap that the tool closes by turning about
the joint: an arc of the tool radius about it.  Where the path turns into the
material the offsets overlap and are cut back to their intersection.  Joints
whose offsets meet within ``snap_mm`` (1 µm: tangent joints of a fitted arc spline, rounded)
are joined at the midpoint of the two ends, as are overlapping ends within
``near_mm`` whose carriers miss each other.

Examples
--------
>>> from camcam.toolpath.elements import Line
>>> square = (Line((0.0, 0.0), (10.0, 0.0)), Line((10.0, 0.0), (10.0, 10.0)),
...           Line((10.0, 10.0), (0.0, 10.0)), Line((0.0, 10.0), (0.0, 0.0)))
>>> out = part_outline(square, -2.0)  # material outside (right of a ccw path): corners rounded
>>> [type(e).__name__ for e in out][:2], round(sum(e.length for e in out), 9)
(['Line', 'Arc'], 52.566370614)
>>> inner = part_outline(square, 2.0)  # material inside: the offsets are cut back at the corners
>>> [e.start for e in inner][:2]
[(2.0, 2.0), (8.0, 2.0)]
"""

from __future__ import annotations

import math

import numpy as np

from camcam.errors import GeometryError
from camcam.toolpath.elements import Arc, Line, element_tangent

__all__ = ["part_outline", "offset_element"]


def offset_element(e, distance_mm: float):
    """``e`` moved ``distance_mm`` to the left of its direction of travel (negative: right)."""
    if isinstance(e, Line):
        t = element_tangent(e, False)
        n = np.array([-t[1], t[0]]) * distance_mm
        return Line(tuple(map(float, np.add(e.start, n))), tuple(map(float, np.add(e.end, n))))
    inward = distance_mm if e.ccw else -distance_mm
    if _inverted(e, distance_mm):
        raise GeometryError(f"the tool radius {abs(distance_mm):g} mm exceeds a path arc's radius {e.radius:g} mm "
                            f"on the material side; the part outline is undefined there")
    c = np.asarray(e.centre)

    def move(p, radius):
        d = np.subtract(p, c)
        return tuple(map(float, c + d / np.hypot(*d) * (radius - inward)))

    # each end from its own radius: a printed arc whose rounded end is off its start's circle is the spiral a
    # controller cuts (Arc.end_radius), and its offset the same spiral less the distance (campaign case 47:36:
    # both ends at the start's radius moved a 90° arc's end by 4e-4 mm and the outline measured 0.00671 mm
    # about a program of 0.00637 mm, over its 0.0067 mm tolerance)
    return Arc(move(e.start, e.radius), move(e.end, e.end_radius), e.centre, e.ccw)


def _inverted(e, distance_mm: float) -> bool:
    """Whether ``e`` is an arc whose offset by ``distance_mm`` (left) would have no positive radius."""
    return isinstance(e, Arc) and min(e.radius, e.end_radius) - (distance_mm if e.ccw else -distance_mm) <= 0


def _circle(e):
    return np.asarray(e.centre, float), e.radius


def _intersections(a, b) -> list[np.ndarray]:
    """Points common to the carriers (infinite line or full circle) of ``a`` and ``b``."""
    if isinstance(a, Line) and isinstance(b, Line):
        p, r = np.asarray(a.start), np.subtract(a.end, a.start)
        q, s = np.asarray(b.start), np.subtract(b.end, b.start)
        den = r[0] * s[1] - r[1] * s[0]
        if den == 0:
            return []
        t = ((q[0] - p[0]) * s[1] - (q[1] - p[1]) * s[0]) / den
        return [p + t * r]
    if isinstance(a, Arc) and isinstance(b, Line):
        a, b = b, a
    if isinstance(a, Line):
        c, rad = _circle(b)
        p, d = np.asarray(a.start), np.subtract(a.end, a.start)
        f = p - c
        A, B, C = d @ d, 2 * f @ d, f @ f - rad * rad
        disc = B * B - 4 * A * C
        if disc < 0:
            return []
        sq = math.sqrt(disc)
        return [p + (-B + s * sq) / (2 * A) * d for s in (-1.0, 1.0)]
    c0, r0 = _circle(a)
    c1, r1 = _circle(b)
    v = c1 - c0
    dist = float(np.hypot(*v))
    if dist == 0 or dist > r0 + r1 or dist < abs(r0 - r1):
        return []
    x = (dist * dist + r0 * r0 - r1 * r1) / (2 * dist)
    h = math.sqrt(max(r0 * r0 - x * x, 0.0))
    u = v / dist
    m = c0 + x * u
    return [m + h * np.array([-u[1], u[0]]), m - h * np.array([-u[1], u[0]])]


def _with_ends(e, start=None, end=None):
    s = tuple(map(float, start)) if start is not None else e.start
    t = tuple(map(float, end)) if end is not None else e.end
    return Line(s, t) if isinstance(e, Line) else Arc(s, t, e.centre, e.ccw)


def part_outline(elements, distance_mm: float, snap_mm: float = 1e-3, near_mm: float = 0.01) -> tuple:
    """The closed outline at ``distance_mm`` to the left of the closed path ``elements`` (negative: right).

    ``elements`` run in the direction of travel and close (last end = first
    start).  Overlapping offsets whose carriers miss each other (nearly
    tangent arcs of a path rounded to a post's decimals) are joined halfway
    when their ends lie within ``near_mm``; the caller measures the result.
    An arc tighter than the offset on its inner side (a short joint arc of a
    fitted arc spline, R < tool radius) is left out: its offset would be an
    inverted arc, and every point of that lies inside the disc of the tool at
    another point of the arc (``|R·u(θ') + (r_t − R)·u(θ)| < r_t``), so the
    part's edge there is its neighbours' offsets, cut back to their
    intersection as at a corner the path turns into the material.

    An element whose offset is cut back past itself by its neighbours' (a
    short chord between two joints that both turn into the material: a lines
    fit's last chord of an analytic piece, 0.013 mm long on campaign case
    43:444, where the tool radius cuts 3 mm back) leaves nothing of the part:
    every point of its offset lies inside the tool at its neighbours, so it is
    left out like an inverted arc and its neighbours' offsets are joined
    directly, one such element at a time (the shortest first), until every
    element keeps its direction.  Raises :class:`GeometryError` where offsets
    cannot be joined.
    """
    els = tuple(elements)
    if math.dist(els[-1].end, els[0].start) > snap_mm:
        raise GeometryError("part outline: the tool path is not closed")
    els = [e for e in els if not _inverted(e, distance_mm)]
    if not els:
        raise GeometryError(f"part outline: every arc of the path is tighter than the offset {abs(distance_mm):g} mm")
    while True:
        out, reversed_ = _joined(els, distance_mm, snap_mm, near_mm)
        if not reversed_:
            return out
        if len(els) <= 3:
            e = els[reversed_[0]]
            raise GeometryError(f"part outline: the element ending at ({e.end[0]:.4f}, {e.end[1]:.4f}) is shorter "
                                f"than the tool radius cuts back from it")
        del els[min(reversed_, key=lambda k: els[k].length)]


def _reverses(path_e, trimmed, offset) -> bool:
    """Whether ``trimmed`` (the offset of ``path_e`` cut back or extended to its joins) runs against ``path_e``."""
    if isinstance(trimmed, Line):
        return float(np.dot(element_tangent(path_e, False), np.subtract(trimmed.end, trimmed.start))) <= 0
    # an arc's joins lie on its circle: cut back past itself, its sweep from the new start to the new end wraps
    # round towards a full turn (a join may extend it by rounding only)
    full = 2.0 * math.pi
    return math.dist(trimmed.start, trimmed.end) > 0 and trimmed.sweep > offset.sweep + 0.5 * (full - offset.sweep)


def _joined(els, distance_mm: float, snap_mm: float, near_mm: float):
    """The offsets of the closed path ``els`` joined at each joint; (outline, indices of elements cut back past
    themselves)."""
    off = [offset_element(e, distance_mm) for e in els]
    n = len(off)
    starts: list = [None] * n
    ends: list = [None] * n
    corners: list = [None] * n  # corner arc after element i
    for i in range(n):
        a, b = off[i], off[(i + 1) % n]
        # the joint (the midpoint of the two path ends where an element between them was left out)
        joint = (np.asarray(els[i].end) + np.asarray(els[(i + 1) % n].start)) / 2
        pa, pb = np.asarray(a.end), np.asarray(b.start)
        if math.dist(pa, pb) <= snap_mm:
            m = (pa + pb) / 2
            ends[i], starts[(i + 1) % n] = m, m
            continue
        ta, tb = element_tangent(els[i], True), element_tangent(els[(i + 1) % n], False)
        turn = ta[0] * tb[1] - ta[1] * tb[0]  # > 0: the path turns left
        into_material = (turn > 0) == (distance_mm > 0)
        if into_material:
            gap = math.dist(pa, pb)
            cands = [q for q in _intersections(a, b)
                     if max(math.dist(q, pa), math.dist(q, pb)) <= max(10.0 * gap, 1e-3)]
            if cands:
                p = min(cands, key=lambda q: float(np.hypot(*(q - joint))))
            elif gap <= near_mm:
                # nearly tangent carriers (a rounded arc spline) that miss or meet far off: join halfway
                p = (pa + pb) / 2
            else:
                raise GeometryError(f"part outline: offsets at ({joint[0]:.4f}, {joint[1]:.4f}) do not meet")
            ends[i], starts[(i + 1) % n] = p, p
        else:
            if math.dist(els[i].end, els[(i + 1) % n].start) > snap_mm:
                raise GeometryError(f"part outline: offsets at ({joint[0]:.4f}, {joint[1]:.4f}) do not meet")
            # the tool turns about the joint the way the path turns
            corners[i] = Arc(tuple(map(float, pa)), tuple(map(float, pb)), tuple(map(float, joint)), turn > 0)
    out, reversed_ = [], []
    for i in range(n):
        e = _with_ends(off[i], starts[i], ends[i])
        if _reverses(els[i], e, off[i]):
            reversed_.append(i)
        out.append(e)
        if corners[i] is not None:
            out.append(corners[i])
    return tuple(out), reversed_
