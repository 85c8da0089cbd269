"""A fewest-arcs chain put on the printed grid: the program's elements, each arc as the post prints it.

:mod:`camcam.toolpath.arcchain` gives a closed G1 chain of exact numbers;
the program prints every joint and centre rounded to the post's grid, and an
arc leaves along the previous printed arc's end tangent (the controller's
G1).  Rounding a joint across the curve by up to 0.71 steps turns the arc's
end tangent by up to 1.4 steps over its chord, and the next arc carries that
turn over its whole length (ε·c/4 at its middle): on an 80 mm dwell arc a
turn of 10⁻⁶ rad is 2·10⁻⁵ mm.  So each joint is chosen among the grid points
near the chain's (:func:`near_grid`: along the chain, where a shift only moves
the hand-over, and one step across), by a beam over the joints
(:func:`printed_spline`), and the result is measured both ways
(:func:`measured_deviation`).
"""

from __future__ import annotations

import math

import numpy as np

from camcam.toolpath.arcbatch import arc_batch, candidate_deviation, element_tangents, printed_element
from camcam.toolpath.arcchain import CurveTable, OnCurve, joint_rows
from camcam.toolpath.beam import ArcSpline
from camcam.toolpath.elements import element_distance
from camcam.toolpath.quantizer import Quantizer

__all__ = ["near_grid", "printed_spline", "measured_deviation", "printed_chain"]


def near_grid(J, T, quantizer: Quantizer, along: int) -> np.ndarray:
    """Grid points near J (2,): along the direction T within ``along`` steps, and one step across, (m, 2)."""
    step = quantizer.step_mm
    lam = np.arange(-along, along + 1) * step
    N = np.array([-T[1], T[0]])
    base = J[None, :] + lam[:, None] * T[None, :]
    base = np.concatenate([base + o * step * N[None, :] for o in (-1.0, 0.0, 1.0)])
    return quantizer.value(np.unique(np.rint(base / step).astype(np.int64), axis=0))


def _radii(p0, centre, is_line) -> np.ndarray:
    """The printed elements' start radii (rows; a line's is infinite)."""
    return np.where(is_line, np.inf, np.hypot(*(p0 - centre).T))


def _kink_allowance(p0, p1, first_radius, step: float) -> np.ndarray:
    """What rounding may turn the closing arc p0 → p1 against the first arc's start (rows): the closing joint's
    rounding over the closing chord, 2·0.71 steps, and the first arc's centre across its radius, 0.71 steps
    (the bound ``tests/toolpath/test_arcspline.py`` holds every closed spline to, less the spirals' lean)."""
    chord = np.hypot(*(p1 - p0).T)
    return 2 * 0.71 * step / chord + 0.71 * step / first_radius


def _angle_between(t0, t1) -> np.ndarray:
    return np.abs(np.arctan2(t0[:, 0] * t1[:, 1] - t0[:, 1] * t1[:, 0], np.einsum("ij,ij->i", t0, t1)))


def printed_spline(oc: OnCurve, tab: CurveTable, quantizer: Quantizer, sag: float, max_sweep: float, tolerance_mm: float,
                   along: int = 6, beam: int = 12, samples: int = 48):
    """The printed form of an optimised chain: joints on the grid, each arc as the post prints it.

    A beam over the grid points near each joint (:func:`near_grid`): each
    kept state (printed joint, the printed arc's end tangent, the worst
    deviation so far, its first arc's printed start tangent) is extended to
    every grid point near the next joint; the states kept are those whose
    worst deviation, with what their offset and tangent error will cost the
    next arc (ε·c/4 for a chord c), is least; at the last joint, whose closing
    arc each candidate's own is measured, those that close within the band
    and G1 up to the rounding.  Returns (elements, the worst deviation on the
    arcs' sampled inner rows); no elements when no state closes.
    """
    n = len(oc.t)
    ch = oc.joints
    step = quantizer.step_mm
    rf = joint_rows(oc, tab)
    clear = (along + 1) * step * tab.n / max(float(np.hypot(*np.diff(tab.P, axis=0).T).sum()), 1e-300)
    Tj = np.stack([np.cos(ch.theta), np.sin(ch.theta)], -1)
    _, c_all, _, k_all, _ = ch.arcs()
    med = float(np.median(c_all))

    def arc_rows(i):
        """Sampled table rows inside arc i's span, clear of where its ends may move along the curve."""
        rows = np.mod(np.arange(math.ceil(rf[i] + clear), math.floor(rf[i + 1] - clear) + 1), tab.n)
        want = int(samples * max(1.0, c_all[i] / med))
        return rows[np.unique(np.rint(np.linspace(0, len(rows) - 1, min(len(rows), want))).astype(int))]

    def printed(p0, t0, p1, i):
        """The printed arcs p0 → p1 leaving along t0 (rows) and their deviation on arc i's rows."""
        centre, ccw, is_line, t_end, a0, sweep = arc_batch(p0, t0, p1, quantizer, sag)
        q = tab.P[arc_rows(i)]
        dev = candidate_deviation(np.broadcast_to(q[None], (len(p0),) + q.shape), p0, p1, centre, ccw, is_line,
                                  a0, sweep).max(axis=1) if len(q) else np.zeros(len(p0))
        dev = np.where(is_line | (sweep <= max_sweep), dev, np.inf)
        return (centre, ccw, is_line, t_end), dev

    # the states after each level: joint (K, 2), end tangent (K, 2), worst (K,), the state's first joint and its
    # first arc's start tangent; per level the kept arcs (parent index, end, centre, ccw, is_line)
    P0 = near_grid(ch.J[0], Tj[0], quantizer, along)
    d0 = P0 - ch.J[0]
    keep = np.argsort(np.abs(d0[:, 1] * Tj[0, 0] - d0[:, 0] * Tj[0, 1]), kind="stable")[:beam]
    P0 = P0[keep]
    pts, tans, worst = P0, np.repeat(Tj[:1], len(keep), 0), np.zeros(len(keep))
    first, t_first, r_first = pts.copy(), None, None
    history = []
    for i in range(n - 1):
        j = i + 1
        K = len(pts)
        C = near_grid(ch.J[j], Tj[j], quantizer, int(along * min(4.0, max(1.0, c_all[j] / med))))
        src = np.repeat(np.arange(K), len(C))
        tgt = np.tile(C, (K, 1))
        (centre, ccw, is_line, t_end), dev = printed(pts[src], tans[src], tgt, i)
        new_worst = np.maximum(worst[src], dev)
        firsts = first[src]
        if i == 0:
            t_firsts = element_tangents(pts[src], centre, ccw, is_line, tgt - pts[src])
            r_firsts = _radii(pts[src], centre, is_line)
        else:
            t_firsts, r_firsts = t_first[src], r_first[src]
        # what the offset and the end tangent's error will cost the next arc
        d = tgt - ch.J[j]
        dv = d[:, 1] * Tj[j, 0] - d[:, 0] * Tj[j, 1]
        want = ch.theta[j] + k_all[j] * (d @ Tj[j])
        eps = np.mod(np.arctan2(t_end[:, 1], t_end[:, 0]) - want + np.pi, 2 * np.pi) - np.pi
        rank = new_worst + np.abs(dv) + 0.25 * c_all[j] * np.abs(eps)
        if j == n - 1:
            # the last joint: each candidate's closing arc onto its own first joint, measured; a closure that
            # kinks more than rounding makes, or leaves the band, ranks last
            (c2, w2, l2, t2), dev2 = printed(tgt, t_end, firsts, j)
            kink = _angle_between(t2, t_firsts)
            closes = kink <= _kink_allowance(tgt, firsts, r_firsts, step)
            rank = np.where(closes, np.maximum(new_worst, dev2), np.inf)
            new_worst = np.maximum(new_worst, dev2)
        keep = np.argsort(rank, kind="stable")[:beam]
        if j == n - 1:
            keep = keep[np.isfinite(rank[keep]) & (new_worst[keep] <= tolerance_mm)]
            if not len(keep):
                return [], float(np.min(new_worst))
        history.append((src[keep], tgt[keep], centre[keep], ccw[keep], is_line[keep]))
        if j == n - 1:  # the best closing state: the first kept
            b = keep[0]
            closing = (tgt[b], firsts[b], c2[b], w2[b], l2[b])
            worst_k = float(new_worst[b])
            break
        pts, tans, worst = tgt[keep], t_end[keep], new_worst[keep]
        first, t_first, r_first = firsts[keep], t_firsts[keep], r_firsts[keep]
    # back through the levels
    elements = [printed_element(*closing)]
    kk = 0
    for level in range(len(history) - 1, -1, -1):
        src, tgt, centre, ccw, is_line = history[level]
        start = history[level - 1][1][src[kk]] if level else P0[src[kk]]
        elements.append(printed_element(start, tgt[kk], centre[kk], ccw[kk], is_line[kk]))
        kk = src[kk]
    elements.reverse()
    return elements, worst_k


def measured_deviation(elements, oc: OnCurve, tab: CurveTable) -> float:
    """The printed spline's deviation from the table's curve, both ways.

    Curve → path: every row of each element's span (and a few beyond) to the
    nearest of that element and its two neighbours.  Path → curve: each
    joint to the table's polyline (the segment on either side of its row).  ``elements`` start at the
    joints of ``oc``.
    """
    rf = joint_rows(oc, tab)
    n = len(elements)
    worst = 0.0
    for i in range(n):
        rows = np.mod(np.arange(math.floor(rf[i]) - 2, math.ceil(rf[i + 1]) + 3), tab.n)
        q = tab.P[rows]
        d = np.minimum(element_distance(elements[i], q),
                       np.minimum(element_distance(elements[i - 1], q), element_distance(elements[(i + 1) % n], q)))
        worst = max(worst, float(d.max()))
        # the joint to the curve's polyline
        r = int(math.floor(rf[i]))
        seg = tab.P[np.mod(np.arange(r - 2, r + 4), tab.n)]
        x = np.asarray(elements[i].start, float)
        u = seg[1:] - seg[:-1]
        f = np.clip(np.einsum("ij,ij->i", x - seg[:-1], u) / np.einsum("ij,ij->i", u, u), 0.0, 1.0)
        worst = max(worst, float(np.hypot(*(seg[:-1] + f[:, None] * u - x).T).min()))
    return worst


def printed_chain(oc: OnCurve, tab: CurveTable, quantizer: Quantizer, sag: float, max_sweep: float,
                  tolerance_mm: float) -> tuple[ArcSpline, ...]:
    """An optimised chain as the program prints it (:func:`printed_spline`), kept only if it is within ``tolerance_mm``
    both ways on the table's curve (:func:`measured_deviation`): the one spline, its elements starting at the
    curve parameters ``oc.t``; or nothing (no printed form closes within the band, or it measures over it)."""
    elements, _ = printed_spline(oc, tab, quantizer, sag, max_sweep, tolerance_mm)
    if not elements or measured_deviation(elements, oc, tab) > tolerance_mm:
        return ()
    return (ArcSpline(tuple(elements), tuple(float(t) for t in oc.t)),)
