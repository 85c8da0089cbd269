"""Helpers of the lines fitting: one analytic piece of a curve, the chord check, the greedy step."""

from __future__ import annotations

import numpy as np

__all__ = ["pieces", "Piece", "lines_fit", "greedy", "GREEDY_BATCH", "GREEDY_LEVELS"]


def pieces(curve, a=None, b=None):
    br = np.asarray(curve.breaks, float)
    a = br[0] if a is None else a
    b = br[-1] if b is None else b
    edges = [a, *[x for x in br if a < x < b], b]
    return list(zip(edges, edges[1:]))


class Piece:
    """One analytic piece of the curve: its parameter grid and its points, single ones memoised."""

    def __init__(self, curve, a, b):
        self.curve, self.a, self.b = curve, a, b
        self.grid = np.linspace(a, b, 4097)
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
    """Whether the chord from t0 to each of ``ts`` (k,) is within ``tol`` two-sided, (k,) bool.

    Two-sided on samples: 41 curve points on [t0, t] to the chord, and the
    chord's 9 points to the polyline through 81 curve points, for a batch of
    candidate ends at once; a chord of length 0 never fits.  A chord point's distance to the
    polyline is first taken over the :data:`WINDOW` segments on each side of
    its own place: that is never below the distance to the whole polyline, so
    it decides every chord it leaves within ``tol``; the others are measured
    against the whole polyline.
    """
    ts = np.atleast_1d(np.asarray(ts, float))
    k = len(ts)
    q0 = piece.point(t0)[0]
    # the 41 chord-test samples are every other one of the 81 polyline samples, to the bit: linspace's
    # i-th value is i·(Δ/div) + t0, and Δ/80 is Δ/40 halved exactly (unless it is subnormal: a span under
    # 1e-290 takes the two sets apart), so 2i·(Δ/80) and i·(Δ/40) are the one product rounded once
    # (tests/toolpath/test_fitcore.py); the curve is evaluated point by point, so one evaluation of the 81
    # gives both sets, as two calls would.  A linspace ends exactly at its stop: the chords' ends are cp[:, -1]
    dense = piece.point(np.linspace(t0, ts, 81, axis=1).ravel()).reshape(k, 81, 2)
    if np.any(np.abs(ts - t0) < 1e-290):
        cp = piece.point(np.linspace(t0, ts, 41, axis=1).ravel()).reshape(k, 41, 2)
    else:
        cp = dense[:, ::2]
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
#: levels a batch (2**levels − 1 midpoints).  A call of :func:`lines_fit` costs about 0.05 ms
#: plus 0.013 ms a candidate (measured on disc-oscillating-flat's pieces), so ``L`` levels a
#: batch cost (0.05 + 0.013·(2^L − 1))/L ms a level: least at 2–3 levels.  The curvature's
#: guess (seed eq. (8)) is mostly within one or two 1.6× steps of the answer, so 4 expansion
#: steps (a factor 6.5) end nearly every expansion in the first call.  Measured on
#: disc-oscillating-flat at 0.001 mm, 632 lines, the same lines for any sizes: (8, 4) 3 223
#: calls, 0.73–0.78 CPU s; (4, 3) 3 889 calls, 0.61–0.63 s; (4, 2) 5 249 calls, 0.65 s.
GREEDY_BATCH = 4
GREEDY_LEVELS = 3


def greedy(t0, b, ok_many, guess):
    """Largest t1 in (t0, b] with ok(t0, t1), by expansion from ``guess`` then bisection.

    ``ok_many(t0, ts)`` judges a batch of candidate ends (bool array).  The
    search is the one-at-a-time one (b itself if it fits, else expand by 1.6
    from ``guess`` until a candidate fails, halve if the first fails, bisect
    to 1e-6 of the span), with the candidates it may need next judged ahead
    in one batch: b with the expansion's first :data:`GREEDY_BATCH` steps
    (a call of its own cost as much as 11 more candidates), then the next
    steps, the next :data:`GREEDY_LEVELS` bisection levels.  So each decision, and the result,
    is that of the sequential search.
    """
    span = b - t0
    lo, hi = t0, None
    step = min(guess, span)
    first = True
    while hi is None:  # expansion
        steps, s = [], step
        while len(steps) < GREEDY_BATCH and t0 + s < b:
            steps.append(s)
            s *= 1.6
        if first:  # the whole rest of the piece is judged with the first steps, in one batch: the answer if it fits
            ok = ok_many(t0, np.concatenate([[b], t0 + np.array(steps, float)]))
            if ok[0]:
                return b
            ok, first = ok[1:], False
        else:
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
    while lo == t0:  # shrink until something works
        steps, s = [], step
        while len(steps) < GREEDY_BATCH:
            s *= 0.5
            if s < span * 1e-9:
                break
            steps.append(s)
        ok = ok_many(t0, t0 + np.array(steps)) if steps else np.zeros(0, bool)
        for s_ok, good in zip(steps, ok):
            if good:
                lo, hi = t0 + s_ok, t0 + 2 * s_ok
                break
        else:
            if len(steps) < GREEDY_BATCH:  # the next halving is below 1e-9 of the span
                return t0 + s * 2
            step = steps[-1]
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
