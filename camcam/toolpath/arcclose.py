"""Closing a closed contour's arc spline: where the march starts, and the closures it may end with.

:mod:`camcam.toolpath.arcspline` starts a closed contour in the middle of a
stretch of near-constant curvature (:func:`quiet_stretches`, a cam's dwell)
and, from each state of its beam, tries to close onto its own first joints:
with a biarc whose join is free (:func:`closing_biarcs`, Held–Eibl's family)
or with one arc that lands tangentially on the circle of an early arc
(:func:`landings`).  ``m`` is the march (its table of the curve ``P``, the
quantizer ``q``, the band ``tolerance_mm``, the sag and sweep limits, the budget).
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.curve import curvature_rate, speed
from camcam.toolpath.arcbatch import MIN_CHORD_STEPS, arc_batch, plain_element, printed_element, touch
from camcam.toolpath.elements import Arc, element_distance, element_distances, element_tangent

__all__ = ["BIARC_RATIOS", "quiet_stretches", "closing_biarcs", "landings"]


#: Join parameters of the closing biarcs tried: tangent length α from the start over the equal-length biarc's.
BIARC_RATIOS = (1.0, 0.7, 1.4, 0.5, 2.0)


def quiet_stretches(curve, a: float, b: float, n: int = 2048) -> tuple[list, float]:
    """A closed curve's stretches of near-constant curvature, longest first, as (middle, half length); and ∫|κ′|^⅓ ds.

    A stretch's middle is where the spline may start and close: there (a
    dwell's circle, for a cam) the curve's own tangent is the optimal joint
    state, so neither the first arc nor the closing arc is cut short.  The
    integral (periodic trapezoid rule on the ``n`` samples) gives the march
    its N_lb.  A curve without such a stretch starts where κ′ is least.
    """
    t = np.linspace(a, b, n, endpoint=False)
    # the N_lb integrand per unit parameter (× (192 δ)^⅓)
    dens = np.cbrt(np.abs(curvature_rate(curve, t))) * speed(curve, t)
    integral = float(dens.sum() * (b - a) / n)
    quiet = dens <= 0.05 * dens.mean()
    if not quiet.any() or quiet.all():
        return [(float(t[int(np.argmin(dens))]), 0.0)], integral
    # cyclic runs of quiet samples
    k0 = int(np.argmin(quiet))  # a loud sample: runs do not wrap past it
    q = np.roll(quiet, -k0)
    runs, run = [], 0
    for k, flag in enumerate(q):
        if flag:
            run += 1
        elif run:
            runs.append((run, k - 1))
            run = 0
    if run:
        runs.append((run, n - 1))
    runs.sort(key=lambda r: -r[0])
    out = []
    for length, end in runs:
        mid = (end - (length - 1) / 2.0 + k0) % n
        out.append((float(a + (b - a) * mid / n), (b - a) * length / (2.0 * n)))
    return out, integral


def closing_biarcs(m, st, p1, t1, ratios, row: int) -> list:
    """Closing biarcs from state ``st`` onto the point ``p1`` with tangent ``t1`` at table ``row``; the feasible ones."""
    p0, tan0 = st.p, st.tan
    v = p1 - p0
    out = []
    rows = np.unique(np.rint(np.linspace(st.i, row, 4 * m.budget.samples)).astype(int))
    q = m.P[rows]
    c = 1.0 - float(tan0 @ t1)
    vt = float(v @ (tan0 + t1))
    if c < 1e-12:
        den = 4.0 * float(v @ tan0)
        if abs(den) < 1e-300:
            return out
        alpha_eq = float(v @ v) / den
    else:
        alpha_eq = (-vt + math.sqrt(vt * vt + 2.0 * c * float(v @ v))) / (2.0 * c)
    joints, chords = [], []
    for k in ratios:
        # tangent lengths α (from p0) and β (into p1) of a G1 biarc: |v − α t0 − β t1| = α + β
        alpha = k * alpha_eq
        w = v - alpha * tan0
        den = 2.0 * (float(w @ t1) + alpha)
        if not alpha > 0 or abs(den) < 1e-300:
            continue
        beta = (float(w @ w) - alpha * alpha) / den
        if not beta > 0:
            continue
        A, B = p0 + alpha * tan0, p1 - beta * t1
        gap = np.hypot(*(B - A))
        if gap <= 0:
            continue
        joint = m.q.snap(A + alpha * (B - A) / gap)
        chord2 = float(np.hypot(*(p1 - joint)))
        if min(float(np.hypot(*(joint - p0))), chord2) < MIN_CHORD_STEPS * m.q.step_mm:
            continue
        joints.append(joint)
        chords.append(chord2)
    if not joints:
        return out
    # the biarcs' two arcs, each as one batch (rows are independent: the same arcs as one at a time)
    J = np.array(joints)
    n = len(J)
    first = arc_batch(np.repeat(p0[None], n, axis=0), np.repeat(tan0[None], n, axis=0), J, m.q, m.sag)
    second = arc_batch(J, first[3], np.repeat(p1[None], n, axis=0), m.q, m.sag)
    kept = []
    for joint, chord2, (c1, w1, l1, _, _, s1), (c2, w2, l2, _, _, s2) in zip(joints, chords, zip(*first), zip(*second)):
        if (not l1 and s1 > m.max_sweep) or (not l2 and s2 > m.max_sweep):
            continue
        e1 = printed_element(p0, joint, c1, w1, l1)
        e2 = printed_element(joint, p1, c2, w2, l2)
        t_end = element_tangent(e2, True)
        # the rounded joint turns the second arc's end tangent a little; more than rounding can is no G1
        if abs(math.atan2(t_end[0] * t1[1] - t_end[1] * t1[0], float(t_end @ t1))) > \
                2 * 0.71 * m.q.step_mm / chord2 + 1e-9:
            continue
        kept.append((joint, e1, e2))
    if not kept:
        return out
    # the kept biarcs measured together (element_distances: each row as element_distance gives it)
    d = element_distances([e for _, e1, e2 in kept for e in (e1, e2)], q)
    dev_c = np.minimum(d[0::2], d[1::2]).max(axis=1)
    # the joint is off the curve: the path → curve direction there as well
    J = np.array([joint for joint, _, _ in kept])[:, None, :]
    dev_j = np.hypot(q[None, :, 0] - J[..., 0], q[None, :, 1] - J[..., 1]).min(axis=1)
    for (_, e1, e2), dc, dj in zip(kept, dev_c.tolist(), dev_j.tolist()):
        dev = max(dc, dj)
        if dev <= m.tolerance_mm:
            out.append((dev, e1, e2))
    return out


def landings(m, st, chain, jmax: int, row_cap: int) -> list:
    """Closing arcs from state ``st`` that land tangentially on the circle of the spline's j-th arc, j ≤ ``jmax``.

    One arc from the state's joint and tangent touches a given circle
    with the same direction of travel at exactly one point (:func:`~camcam.toolpath.arcbatch.touch`).
    Where that point lies on
    the j-th arc's circle ahead of its end, the spline closes with this one
    arc and the j-th arc drawn back to the touch point: arcs 1 … j−1 drop
    out.  A biarc onto the j-th joint spends two arcs for the same; the
    feasible landings (printed, G1 up to the rounding, within the band)
    are returned as (j, deviation, closing arc, lengthened j-th arc).
    """
    out = []
    p, t = st.p, st.tan
    step = m.q.step_mm
    for j in range(1, jmax + 1):
        jt = chain[j - 1]
        row = jt.i + m.last
        if not st.i < row <= row_cap:
            continue
        p_s, p_e, c, ccw, is_line = jt.arc
        if is_line:
            continue
        c = np.asarray(c, float)
        R = float(np.hypot(*(p_e - c)))
        x, good = touch(p[None], t[None], c[None], np.array([R if ccw else -R]))
        if not good[0]:
            continue
        x = m.q.snap(x[0])
        chord1 = float(np.hypot(*(x - p)))
        if min(chord1, float(np.hypot(*(p_e - x)))) < MIN_CHORD_STEPS * step:
            continue
        # the lengthened arc: from x round to the j-th joint, forward and within the sweep limit
        a_x = math.atan2(x[1] - c[1], x[0] - c[0])
        a_e = math.atan2(p_e[1] - c[1], p_e[0] - c[0])
        sweep2 = (a_e - a_x if ccw else a_x - a_e) % (2 * math.pi)
        if not 0 < sweep2 <= m.max_sweep:
            continue
        c1, w1, l1, _, _, s1 = (v[0] for v in arc_batch(p[None], t[None], x[None], m.q, m.sag))
        if (not l1 and s1 > m.max_sweep) or float((x - p) @ t) <= 0:
            continue
        e1 = printed_element(p, x, c1, w1, l1)
        e2 = plain_element(Arc(tuple(x), tuple(p_e), tuple(c), bool(ccw)))
        t_end, t_start = element_tangent(e1, True), element_tangent(e2, False)
        kink = abs(math.atan2(t_end[0] * t_start[1] - t_end[1] * t_start[0], float(t_end @ t_start)))
        # both rounded: the touch point turns the closing arc's end tangent by ≤ 2·0.71·step/chord and the
        # lengthened arc's start tangent by ≤ 0.71·step/R; more than that is no G1
        if kink > 0.71 * step * (2.0 / chord1 + 1.0 / R) + 1e-12:
            continue
        rows = np.unique(np.rint(np.linspace(st.i, row, 4 * m.budget.samples)).astype(int))
        qs = m.P[rows]
        dev_c = float(np.minimum(element_distance(e1, qs), element_distance(e2, qs)).max())
        dev = max(dev_c, float(np.hypot(*(qs - x).T).min()))
        if dev <= m.tolerance_mm:
            out.append((j, dev, e1, e2))
    return out
