"""Helpers of the lines fitting: one analytic piece of a curve, the fitting check, the greedy step."""

from __future__ import annotations

import numpy as np

from camcam.toolpath.elements import element_distance

__all__ = ["pieces", "Piece", "dev", "lines_fit", "greedy", "GREEDY_BATCH", "GREEDY_LEVELS"]


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


#: Polyline segments on each side of a chord point's own place that :func:`lines_fit` looks
#: at first (the chord point at fraction w of the chord is compared with the whole polyline
#: only when these leave it outside the tolerance).
WINDOW = 6


def _point_polyline(ep: np.ndarray, a: np.ndarray, e: np.ndarray, e2: np.ndarray) -> np.ndarray:
    """Distances of points ``ep`` (k, n, 2) to the segments a + [0, 1]·e (k, n, m, 2 or broadcast), min over m."""
    rel = ep[:, :, None, :] - a
    v = np.clip(np.einsum("knmj,knmj->knm", rel, np.broadcast_to(e, rel.shape)) / e2, 0.0, 1.0)
    return np.hypot(*(rel - v[..., None] * e).transpose(3, 0, 1, 2)).min(axis=2)


def lines_fit(piece, t0: float, ts, tol: float) -> np.ndarray:
    """Whether the chord from t0 to each of ``ts`` (k,) is within ``tol``: ``dev(chord) <= tol``, (k,) bool.

    The same samples as :func:`dev` (41 curve points to the chord, the chord's 9
    points to the 81-point curve polyline), for a batch of candidate ends at
    once; a chord of length 0 never fits.  A chord point's distance to the
    polyline is first taken over the :data:`WINDOW` segments on each side of
    its own place: that is never below the distance to the whole polyline, so
    it decides every chord it leaves within ``tol``; the others are measured
    against the whole polyline.
    """
    ts = np.atleast_1d(np.asarray(ts, float))
    k = len(ts)
    q0 = piece.point(t0)[0]
    # one evaluation for both sample sets (the curve is evaluated point by point, so the values are those
    # of separate calls); a linspace ends exactly at its stop, so the chords' ends are cp[:, -1]
    both = piece.point(np.concatenate([np.linspace(t0, ts, 41, axis=1).ravel(), np.linspace(t0, ts, 81, axis=1).ravel()]))
    cp, dense = both[:41 * k].reshape(k, 41, 2), both[41 * k:].reshape(k, 81, 2)
    q1 = cp[:, -1]
    d = q1 - q0
    L2 = np.einsum("kj,kj->k", d, d)
    safe = np.where(L2 > 0, L2, 1.0)
    u = np.where(L2[:, None] > 0, np.clip(np.einsum("knj,kj->kn", cp - q0, d) / safe[:, None], 0.0, 1.0), 0.0)
    d1 = np.hypot(*(cp - q0 - u[..., None] * d[:, None]).transpose(2, 0, 1)).max(axis=1)
    fits = (np.hypot(d[:, 0], d[:, 1]) > 0) & (d1 <= tol)  # as dev's caller: a chord of length 0 never fits
    if not fits.any():
        return fits
    w = np.linspace(0.0, 1.0, 9)[None, :, None]
    ep = ((1 - w) * q0 + w * q1[:, None])[fits]  # (k', 9, 2): Line.points(9)
    a, e = dense[fits, :-1], dense[fits, 1:] - dense[fits, :-1]  # (k', 80, 2) polyline segments
    e2 = np.maximum(np.einsum("kmj,kmj->km", e, e), 1e-300)
    kk = np.arange(len(ep))[:, None, None]
    near = np.clip(np.arange(9)[:, None] * 10 + np.arange(-WINDOW, WINDOW)[None, :], 0, 79)[None]  # (1, 9, 2W)
    d2 = _point_polyline(ep, a[kk, near], e[kk, near], e2[kk, near]).max(axis=1)
    wide = d2 > tol
    if wide.any():
        d2[wide] = _point_polyline(ep[wide], a[wide][:, None], e[wide][:, None], e2[wide][:, None]).max(axis=1)
    fits[fits] = d2 <= tol
    return fits


#: Candidate ends tried at once by :func:`greedy`: expansion steps a batch, and bisection
#: levels a batch (2**levels − 1 midpoints).
GREEDY_BATCH = 8
GREEDY_LEVELS = 4


def greedy(t0, b, ok_many, guess):
    """Largest t1 in (t0, b] with ok(t0, t1), by expansion from ``guess`` then bisection.

    ``ok_many(t0, ts)`` judges a batch of candidate ends (bool array).  The
    search is the one-at-a-time one (expand by 1.6 from ``guess`` until a
    candidate fails, halve if the first fails, bisect to 1e-6 of the span),
    with the candidates it may need next judged ahead in one batch: the
    expansion's next :data:`GREEDY_BATCH` steps, the next
    :data:`GREEDY_LEVELS` bisection levels.  So each decision, and the result,
    is that of the sequential search.
    """
    if ok_many(t0, np.array([b]))[0]:
        return b
    span = b - t0
    lo, hi = t0, None
    step = min(guess, span)
    while hi is None:  # expansion
        steps, s = [], step
        while len(steps) < GREEDY_BATCH and t0 + s < b:
            steps.append(s)
            s *= 1.6
        ok = ok_many(t0, t0 + np.array(steps)) if steps else np.zeros(0, bool)
        for s, good in zip(steps, ok):
            if good:
                lo = t0 + s
                step = s * 1.6
            else:
                hi, step = t0 + s, s
                break
        else:
            if len(steps) < GREEDY_BATCH:  # the next step reaches b
                hi = b
    if lo == t0:  # shrink until something works
        while True:
            steps, s = [], step
            for _ in range(GREEDY_BATCH):
                s *= 0.5
                steps.append(s)
            for s, good in zip(steps, ok_many(t0, t0 + np.array([x for x in steps if x >= span * 1e-9]))):
                if good:
                    lo, hi = t0 + s, t0 + 2 * s
                    break
            else:
                if steps[-1] >= span * 1e-9:
                    step = steps[-1]
                    continue
                first_small = next(x for x in steps if x < span * 1e-9)
                return t0 + first_small * 2
            break
    levels = 0
    while levels < 30 and hi - lo > 1e-6 * span:  # bisection, GREEDY_LEVELS levels judged at once
        mids = {}

        def plan(lo_, hi_, depth):
            if depth == 0 or levels + (GREEDY_LEVELS - depth) >= 30 or hi_ - lo_ <= 1e-6 * span:
                return
            mid = 0.5 * (lo_ + hi_)
            mids[(lo_, hi_)] = mid
            plan(mid, hi_, depth - 1)
            plan(lo_, mid, depth - 1)

        plan(lo, hi, GREEDY_LEVELS)
        keys = list(mids)
        verdict = dict(zip(keys, ok_many(t0, np.array([mids[k] for k in keys]))))
        for _ in range(GREEDY_LEVELS):
            if levels >= 30 or hi - lo <= 1e-6 * span:
                break
            mid = mids[(lo, hi)]
            if verdict[(lo, hi)]:
                lo = mid
            else:
                hi = mid
            levels += 1
    return lo
