"""Candidate arcs of the arc-spline march as arrays: printed joints and centres, and their deviation.

:mod:`camcam.toolpath.arcspline` tries many next arcs at once; each is built
here as the post prints it (joint and centre on the grid,
:func:`grid_joint`, :func:`grid_centre`; :func:`arc_batch`) and measured
against curve samples (:func:`candidate_deviation`, the controller's
spiral included; :func:`peak_deviation` sharpens the sampled maximum).
Rows are candidates: arrays in, arrays out.  :func:`printed_element` turns a
row into the :class:`~camcam.toolpath.elements.Arc` or ``Line`` it prints, and
:func:`touch` finds the one arc from a joint that lands tangentially on a circle.
"""

from __future__ import annotations

import numpy as np

from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.quantizer import Quantizer

__all__ = ["grid_near", "unit_rows", "grid_joint", "grid_centre", "element_tangents", "arc_batch", "candidate_deviation", "peak_deviation",
           "MIN_CHORD_STEPS", "plain_element", "printed_element", "touch"]


#: The four grid points around a point, in steps from the one below and left of it (the order ties go by).
_CORNERS = np.array([[0, 0], [0, 1], [1, 0], [1, 1]], np.int64)


def grid_near(p, weight, q: Quantizer) -> np.ndarray:
    """Of the four grid points around each row of ``p`` (N, 2), the one with the least weight (the first of equals).

    ``weight(d, rows)`` gets the offsets ``d`` (4N, 2) of the candidates from their points, four rows a point
    (in the order of :data:`_CORNERS`), and ``rows`` (4N,), the point each belongs to; it returns (4N,) weights.
    """
    p = np.asarray(p, float)
    lo = np.floor(p / q.step_mm).astype(np.int64)
    cand = q.value(lo[:, None, :] + _CORNERS[None, :, :])
    rows = np.repeat(np.arange(len(p)), 4)
    w = weight((cand - p[:, None, :]).reshape(-1, 2), rows).reshape(-1, 4)
    return cand[np.arange(len(p)), np.argmin(w, axis=1)]


def unit_rows(v):
    return v / np.maximum(np.hypot(v[..., 0], v[..., 1]), 1e-300)[..., None]


def grid_joint(p, nrm, q: Quantizer) -> np.ndarray:
    """The printed joint: of the four grid points around ``p``, the one least off it along the curve normal.

    A shift along the curve only moves where one arc hands over to the next;
    a shift across it is deviation.
    """
    return grid_near(p, lambda d, rows: np.abs(np.einsum("ij,ij->i", d, nrm[rows])) + 1e-3 * np.hypot(d[:, 0], d[:, 1]),
                     q)


def grid_centre(p0, c, q: Quantizer) -> np.ndarray:
    """The printed centre: of the four grid points around the exact centre ``c``, the one nearest the line p0–c.

    Moving the centre along the radius only bends the arc a little (its start
    and tangent stay); moving it across turns the printed arc's start tangent
    by Δc⊥/R, an error that grows along the arc.  So the grid point with the
    least cross-radius shift is printed (the writer prints a centre already on
    the grid unchanged).
    """
    u = unit_rows(c - p0)
    return grid_near(c, lambda d, rows: np.abs(d[:, 0] * u[rows, 1] - d[:, 1] * u[rows, 0]), q)


def element_tangents(p, centre, ccw, is_line, chord) -> np.ndarray:
    """Printed elements' unit tangents (rows) at their point ``p``: across the radius there, in the travel
    direction; a line's along its ``chord`` (end − start)."""
    rad = unit_rows(np.where(is_line[:, None], 1.0, p - centre))
    t_arc = np.where(ccw[:, None], np.stack([-rad[:, 1], rad[:, 0]], -1), np.stack([rad[:, 1], -rad[:, 0]], -1))
    t_line = unit_rows(np.where(is_line[:, None], chord, 1.0))
    return np.where(is_line[:, None], t_line, t_arc)


def arc_batch(p0, tan0, p1, q: Quantizer, sag: float):
    """Printed arcs leaving p0 (N, 2) along tan0 (N, 2) to p1 (N, 2): centres, flags, end tangents.

    ``p0`` and ``p1`` are already on the printed grid; the centre is put on it
    too (:func:`grid_centre`, as an I/J post prints it).  Arcs with sagitta ≤ ``sag`` are lines (nearly straight).
    """
    v = p1 - p0
    nrm = np.stack([-tan0[:, 1], tan0[:, 0]], axis=-1)
    chord2 = np.einsum("ij,ij->i", v, v)
    chord = np.sqrt(chord2)
    h = np.einsum("ij,ij->i", nrm, v)
    half = np.arcsin(np.minimum(1.0, np.abs(h) / np.maximum(chord, 1e-300)))
    half = np.where(np.einsum("ij,ij->i", tan0, v) < 0, np.pi - half, half)
    is_line = (chord / 2 * np.tan(half / 2) <= sag) | (h == 0)
    r = chord2 / (2 * np.where(is_line, 1.0, h))  # a line's centre is never used (a tiny h would overflow)
    centre = grid_centre(p0, p0 + r[:, None] * nrm, q)
    ccw = r > 0
    t_end = element_tangents(p1, centre, ccw, is_line, v)
    a0 = np.arctan2(p0[:, 1] - centre[:, 1], p0[:, 0] - centre[:, 0])
    a1 = np.arctan2(p1[:, 1] - centre[:, 1], p1[:, 0] - centre[:, 0])
    sweep = np.mod(np.where(ccw, a1 - a0, a0 - a1), 2 * np.pi)
    sweep = np.where(sweep <= 0, sweep + 2 * np.pi, sweep)
    return centre, ccw, is_line, t_end, a0, sweep


def candidate_deviation(q, p0, p1, centre, ccw, is_line, a0, sweep) -> np.ndarray:
    """Distance of curve samples q (N, M, 2) from each printed element, (N, M).

    Arcs are the controller's spiral: radius linear in angle from |p0 − c| to
    |p1 − c| (see :func:`~camcam.toolpath.elements.element_nearest`); a sample
    outside the arc's angular span is measured to the nearer end.  Sweeps are
    at most a half turn (the fitter's sweep limit).
    """
    out = np.empty(q.shape[:2])
    li = np.nonzero(is_line)[0]
    if len(li):
        ql, a, d = q[li], p0[li], p1[li] - p0[li]
        L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
        u = np.clip(np.einsum("nmj,nj->nm", ql - a[:, None], d) / L2[:, None], 0.0, 1.0)
        out[li] = np.hypot(*(ql - a[:, None] - u[..., None] * d[:, None]).transpose(2, 0, 1))
    ai = np.nonzero(~is_line)[0]
    if len(ai):
        qa, c, s0, s1 = q[ai], centre[ai], p0[ai], p1[ai]
        v0 = s0 - c
        r0 = np.hypot(v0[:, 0], v0[:, 1])[:, None]
        r1 = np.hypot(*(s1 - c).T)[:, None]
        rel = qa - c[:, None]
        sgn = np.where(ccw[ai], 1.0, -1.0)[:, None]
        cr = sgn * (v0[:, None, 0] * rel[..., 1] - v0[:, None, 1] * rel[..., 0])
        dt = v0[:, None, 0] * rel[..., 0] + v0[:, None, 1] * rel[..., 1]
        frac = np.arctan2(cr, dt) / sweep[ai][:, None]  # angle from the start, in the travel direction
        dist = np.hypot(rel[..., 0], rel[..., 1])
        d_arc = np.abs(dist - (r0 + (r1 - r0) * np.clip(frac, 0.0, 1.0)))
        outside = (frac < 0.0) | (frac > 1.0)
        if outside.any():
            rows, cols = np.nonzero(outside)
            pts = qa[rows, cols]
            d_end = np.minimum(np.hypot(*(pts - s0[rows]).T), np.hypot(*(pts - s1[rows]).T))
            d_arc[rows, cols] = d_end
        out[ai] = d_arc
    return out


def peak_deviation(d: np.ndarray) -> np.ndarray:
    """Row maxima of sampled |e|, sharpened by a parabola through the peak and its neighbours."""
    i = np.argmax(d, axis=1)
    rows = np.arange(len(d))
    y1 = d[rows, i]
    inner = (i > 0) & (i < d.shape[1] - 1)
    y0 = d[rows, np.maximum(i - 1, 0)]
    y2 = d[rows, np.minimum(i + 1, d.shape[1] - 1)]
    curv = y0 - 2 * y1 + y2
    bump = np.where(inner & (curv < 0), -(y2 - y0) ** 2 / (8 * np.where(curv < 0, curv, -1.0)), 0.0)
    return y1 + np.minimum(bump, 0.5 * y1)


#: Shortest chord of an arc or line, in grid steps (a shorter one would print a direction of its own).
MIN_CHORD_STEPS = 50


def plain_element(e):
    """An element with plain-float coordinates."""
    f = lambda p: tuple(float(x) + 0.0 for x in p)  # noqa: E731
    if isinstance(e, Line):
        return Line(f(e.start), f(e.end))
    return Arc(f(e.start), f(e.end), f(e.centre), bool(e.ccw))


def printed_element(p0, p1, centre, ccw, is_line):
    """A candidate row as the element it prints (a line where ``is_line``), plain floats."""
    if is_line:
        return plain_element(Line(tuple(p0), tuple(p1)))
    return plain_element(Arc(tuple(p0), tuple(p1), tuple(centre), bool(ccw)))


def touch(p, t, c, Rs):
    """Where the one arc leaving p (N, 2) along t (N, 2) touches the circle (centre c, signed radius Rs), same travel.

    Signed radii (positive: centre on the left): the arc's centre q = p + ρ n
    and the circle's centre both lie on the common normal at the touch point,
    |q − c| = |ρ − Rs|, so ρ = (Rs² − |p − c|²) / (2 (n·(p − c) + Rs)).
    Returns the touch points and which rows have one (not a line, not the
    circle itself, not a point).
    """
    n = np.stack([-t[:, 1], t[:, 0]], -1)
    d = p - c
    den = 2.0 * (np.einsum("ij,ij->i", d, n) + Rs)
    rho = (Rs * Rs - np.einsum("ij,ij->i", d, d)) / np.where(np.abs(den) > 1e-300, den, 1.0)
    # no touch point: the arc is a line (den = 0), the circle itself (ρ = Rs) or shrinks to p (ρ = 0, p on the
    # circle travelled the other way)
    good = (np.abs(den) > 1e-300) & (np.abs(rho - Rs) > 1e-9 * np.abs(Rs)) & (np.abs(rho) > 1e-9 * np.abs(Rs))
    qc = p + rho[:, None] * n
    # x = c − Rs (q − c)/(ρ − Rs), taken as the circle's radius along the unit direction: for nearly
    # concentric circles (ρ ≈ Rs) the quotient amplifies q's rounding, the direction does not
    # (hypothesis found |x − c| off R by 1.3e-7 mm with p 2e-4 mm outside a 5.43 mm circle)
    v = qc - c
    side = -np.sign(Rs) * np.sign(np.where(good, rho - Rs, 1.0))
    x = c + (side * np.abs(Rs))[:, None] * unit_rows(v)
    return x, good
