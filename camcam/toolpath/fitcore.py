"""Helpers of the second fitting: one analytic piece of a curve, fitting checks, biarcs."""

from __future__ import annotations

import math

import numpy as np

from camcam.toolpath.elements import Arc, arc_from_tangent, element_distance, element_tangent

__all__ = ["pieces", "Piece", "unit", "end_tangent", "dev", "biarc", "sweep_ok", "greedy", "signed_angle"]


def pieces(curve, a=None, b=None):
    br = np.asarray(curve.breaks, float)
    a = br[0] if a is None else a
    b = br[-1] if b is None else b
    edges = [a, *[x for x in br if a < x < b], b]
    return list(zip(edges, edges[1:]))


class Piece:
    """One analytic piece of the curve with tangent angles unwrapped continuously."""

    def __init__(self, curve, a, b):
        self.curve, self.a, self.b = curve, a, b
        self.grid = np.linspace(a, b, 4097)
        d = curve.evaluate(self.grid, 1)
        self.phi_grid = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
        self._points: dict[float, np.ndarray] = {}

    def point(self, t) -> np.ndarray:
        """Curve point(s) at ``t``; single parameters are memoised (the march revisits its nodes)."""
        if np.ndim(t) == 0:
            key = float(t)
            p = self._points.get(key)
            if p is None:
                if len(self._points) > 65536:
                    self._points.clear()
                p = self._points[key] = self.curve.evaluate(np.atleast_1d(key), 0)
            return p
        return self.curve.evaluate(np.atleast_1d(t), 0)

    def phi(self, t) -> np.ndarray:
        t = np.atleast_1d(np.asarray(t, float))
        ref = np.interp(t, self.grid, self.phi_grid)
        d = self.curve.evaluate(t, 1)
        raw = np.arctan2(d[:, 1], d[:, 0])
        return ref + (raw - ref + np.pi) % (2 * np.pi) - np.pi

    def samples(self, t0, t1, n=33) -> np.ndarray:
        return self.point(np.linspace(t0, t1, n))


def unit(angle):
    return np.array([math.cos(angle), math.sin(angle)])


def end_tangent(e) -> np.ndarray:
    """Unit tangent at the end of ``e`` (:func:`element_tangent`)."""
    return element_tangent(e, True)


def _seg_dist(q, poly):
    """Distance from points q (n,2) to the polyline poly (m,2)."""
    a, b = poly[:-1], poly[1:]
    d = b - a
    L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    rel = q[:, None, :] - a[None, :, :]
    u = np.clip(np.einsum("nmj,mj->nm", rel, d) / L2, 0, 1)
    foot = a[None] + u[..., None] * d[None]
    return np.hypot(*(q[:, None, :] - foot).transpose(2, 0, 1)).min(axis=1)


def dev(piece, elems, t0, t1) -> float:
    """Two-sided deviation of ``elems`` from the curve on [t0, t1], densely sampled (a fitting check)."""
    cp = piece.samples(t0, t1, 41)
    d1 = np.min([element_distance(e, cp) for e in elems], axis=0).max()
    ep = np.concatenate([e.points(9) for e in elems])
    dense = piece.samples(t0, t1, 81)
    d2 = _seg_dist(ep, dense).max()
    return float(max(d1, d2))


def biarc(p0, t0, p1, t1, sag):
    """Equal-tangent-length biarc from (p0, t0) to (p1, t1) (unit tangents)."""
    p0, t0, p1, t1 = (np.asarray(x, float) for x in (p0, t0, p1, t1))
    v = p1 - p0
    t = t0 + t1
    c = 1.0 - float(t0 @ t1)
    vt = float(v @ t)
    if c < 1e-12:
        denom = 4.0 * float(v @ t0)
        if abs(denom) < 1e-300:
            return None
        alpha = float(v @ v) / denom
    else:
        alpha = (-vt + math.sqrt(vt * vt + 2.0 * c * float(v @ v))) / (2.0 * c)
    if not alpha > 0:
        return None
    joint = 0.5 * (p0 + alpha * t0 + p1 - alpha * t1)
    if np.hypot(*(joint - p0)) < 1e-9 or np.hypot(*(p1 - joint)) < 1e-9:
        return None
    e1 = arc_from_tangent(p0, t0, joint, sag)
    e2 = arc_from_tangent(joint, end_tangent(e1), p1, sag)
    return [e1, e2]


def sweep_ok(elems, max_sweep) -> bool:
    return all(not isinstance(e, Arc) or e.sweep <= max_sweep for e in elems)


def greedy(t0, b, ok, guess):
    """Largest t1 in (t0, b] with ok(t0, t1), by expansion from ``guess`` then bisection."""
    if ok(t0, b):
        return b
    span = b - t0
    lo, hi = t0, None
    step = min(guess, span)
    while True:
        t = t0 + step
        if t >= b:
            hi = b
            break
        if ok(t0, t):
            lo = t
            step *= 1.6
        else:
            hi = t
            break
    if lo == t0:  # shrink until something works
        while True:
            step *= 0.5
            if step < span * 1e-9:
                return t0 + step * 2
            if ok(t0, t0 + step):
                lo, hi = t0 + step, t0 + 2 * step
                break
    for _ in range(30):
        if hi - lo <= 1e-6 * span:
            break
        mid = 0.5 * (lo + hi)
        if ok(t0, mid):
            lo = mid
        else:
            hi = mid
    return lo


def signed_angle(u, v) -> float:
    return math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1])
