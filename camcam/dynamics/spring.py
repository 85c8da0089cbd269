"""Spring sizing (``[dynamics] spring = "size"``): the least spring that keeps the follower on the cam.

The rule, a linear program over the two unknowns, rate k (N/mm) ≥ 0 and preload P (N) ≥ 0:

    minimise   P + k·x̄                      (the spring force averaged over the cycle, x̄ the mean deflection)
    subject to F_n(θ, ω) ≥ F_min            for every cam angle θ and every speed 0 ≤ ω ≤ overspeed × ω_spec

with F_min = ``min_contact_force_n`` (default 0).  At one angle the contact force is Q·g with g > 0 and
Q = a ω² + b ω + w·(P + k·x + F_ext) (:mod:`camcam.dynamics.forces`), so over the speeds the worst case is at
rest, at the overspeed, or at the vertex −b/2a of the quadratic when it lies between them: each constraint is
linear in (k, P), ``P + k·x(θ) ≥ r(θ)``.  The angles are a grid of every motion segment; then the exact worst
angle of the solution (a bounded Brent search per segment) is added as a cut and the program solved again
until no angle violates it (:func:`least_mean_spring` solves each program exactly on the upper hull).  The result is rounded up to
0.001 N/mm and 0.01 N, which keeps it on the safe side; the margin is the overspeed itself (the sized spring
lets go exactly at overspeed × rpm, before the rounding).

Minimising the mean spring force (rather than the largest, whose optimum is any spring through the worst
point, down to a constant force) picks the supporting line of the required force from above at the mean
deflection: the softest spring that does the job there, and the least average contact force, torque and wear.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.dynamics.cyclewise import Sampled, bracket_grid, gauss_span, piece_minimum
from camcam.dynamics.forces import cam_pieces, coefficients
from camcam.dynamics.train import DynamicsSpec

__all__ = ["size_spring", "required_spring_force", "least_mean_spring", "SPRING_RULE"]

#: The rule as the report states it.
SPRING_RULE = ("least mean spring force P + k·x̄ keeping the contact force ≥ min_contact_force_n at every cam "
               "angle and every speed up to overspeed × rpm (linear program in k and P), rounded up to "
               "0.001 N/mm and 0.01 N")

#: Rounds of cuts at the exact worst angle before giving up (each adds one constraint; 2–3 are typical).
MAX_CUTS = 30


def required_spring_force(built, d: DynamicsSpec, rpm: float, theta, piece=None) -> tuple[np.ndarray, np.ndarray]:
    """(x, r): the spring's deflection (mm) and the least spring force P + k·x (N) each cam angle needs."""
    bare = d.with_spring(0.0, 0.0)
    k = coefficients(built, bare, theta, piece, radii=False)
    w_o = 2.0 * math.pi * rpm * d.overspeed / 60.0
    a, b = k.inertia, k.damping
    worst = np.minimum(0.0, a * w_o * w_o + b * w_o)
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = -b / (2.0 * a)
        inside = (a > 0) & (vertex > 0) & (vertex < w_o)
        worst = np.where(inside, np.minimum(worst, -b * b / (4.0 * a)), worst)
    need_q = d.min_contact_force_n / k.gain_lift  # Q ≥ F_min/g
    r = (need_q - worst) / k.lever_m - k.external_n
    return k.deflection_mm, r


def least_mean_spring(x: np.ndarray, r: np.ndarray, mean_x: float) -> tuple[float, float]:
    """The linear program of the module notes on the constraints P + k·x_i ≥ r_i, solved exactly.

    For a rate k the least feasible preload is P(k) = max(0, max_i (r_i − k·x_i)), so the program is the
    one-dimensional minimum of the convex, piecewise linear g(k) = P(k) + k·x̄ over k ≥ 0.  Its minimum lies
    at k = 0 or at a kink, where two constraint lines (or one and P = 0) cross: P(k) has slope −x_j of its
    active constraint j, so g's slope x̄ − x_j changes sign where the active deflection passes x̄.  The
    kinks are those of the upper hull of the points (x_i, r_i); walking it from k = 0 finds the minimum.
    """
    order = np.lexsort((r, x))
    xs, rs = x[order], r[order]
    # upper hull of the points (x, r), by increasing x (Andrew's monotone chain)
    hull: list[int] = []
    for idx in range(len(xs)):
        while len(hull) >= 2:
            (x1, r1), (x2, r2) = (xs[hull[-2]], rs[hull[-2]]), (xs[hull[-1]], rs[hull[-1]])
            if (x2 - x1) * (rs[idx] - r1) - (r2 - r1) * (xs[idx] - x1) >= 0:
                hull.pop()
            else:
                break
        hull.append(idx)
    # the candidate rates: 0 and the slopes of the hull's edges (each a kink of P(k)), and, where P reaches 0,
    # the rates r_i/x_i that make the line pass through the origin
    cands = [0.0]
    for a, b in zip(hull, hull[1:]):
        if xs[b] > xs[a]:
            cands.append(max(0.0, (rs[b] - rs[a]) / (xs[b] - xs[a])))
    pos = xs > 0
    if pos.any():
        cands.append(max(0.0, float(np.max(rs[pos] / xs[pos]))))
    best = (math.inf, 0.0, 0.0)
    for k in cands:
        p = max(0.0, float(np.max(rs - k * xs)))
        g = p + k * mean_x
        if g < best[0] - 1e-15 * max(1.0, abs(g)):
            best = (g, k, p)
    return best[1], best[2]


def size_spring(built, rpm: float, d: DynamicsSpec) -> tuple[float, float]:
    """(rate N/mm, preload N) by the rule of the module notes."""
    pieces = cam_pieces(built)
    grids = [bracket_grid(a, b) for a, b in pieces]
    pairs = [required_spring_force(built, d, rpm, ts, i) for i, ts in enumerate(grids)]
    x = np.concatenate([p[0] for p in pairs])
    r = np.concatenate([p[1] for p in pairs])
    mean_x = _mean_deflection(built, d, rpm, grids)
    scale = max(1.0, float(np.max(np.abs(r))))
    rate = preload = 0.0
    for _ in range(MAX_CUTS):
        rate, preload = least_mean_spring(x, r, mean_x)

        def slack(ts, i, rate=rate, preload=preload):
            xx, rr = required_spring_force(built, d, rpm, ts, i)
            return preload + rate * xx - rr

        sampled = Sampled(grids, [preload + rate * p[0] - p[1] for p in pairs])
        least, t, i = piece_minimum(slack, pieces, sampled)
        if least >= -1e-9 * scale:
            break
        xx, rr = required_spring_force(built, d, rpm, np.array([t]), i)
        x, r = np.append(x, xx), np.append(r, rr)
    rate = math.ceil(rate * 1000.0) / 1000.0
    preload = math.ceil(preload * 100.0) / 100.0
    # a deflection below zero (a lift under the base circle) is less pushed by a stiffer spring: top the preload up
    sampled = Sampled(grids, [preload + rate * p[0] - p[1] for p in pairs])
    least, _, _ = piece_minimum(lambda ts, i: (lambda xr: preload + rate * xr[0] - xr[1])(
        required_spring_force(built, d, rpm, ts, i)), pieces, sampled)
    if least < 0:
        preload = math.ceil((preload - least) * 100.0) / 100.0
    return rate, preload


def _mean_deflection(built, d, rpm, grids) -> float:
    total = 0.0
    for i, ts in enumerate(grids):
        nodes, weights = gauss_span(ts[:-1], ts[1:])
        total += float(np.sum(weights * required_spring_force(built, d, rpm, nodes.ravel(), i)[0].reshape(nodes.shape)))
    return total / (2 * math.pi)
