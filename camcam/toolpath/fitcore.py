"""Helpers of the lines fitting: one analytic piece of a curve, the fitting check, the greedy step."""

from __future__ import annotations

import numpy as np

from camcam.toolpath.elements import element_distance

__all__ = ["pieces", "Piece", "dev", "greedy"]


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


