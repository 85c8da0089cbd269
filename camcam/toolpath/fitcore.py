"""Helpers of the lines fitting: one analytic piece of a curve, the chord check, the greedy step."""

from __future__ import annotations

import numpy as np

__all__ = ["pieces", "Piece", "lines_deviation", "lines_fit", "greedy", "GREEDY_BATCH", "GREEDY_TIGHT"]


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


def _point_polyline(ep: np.ndarray, a: np.ndarray, e: np.ndarray, e2: np.ndarray) -> np.ndarray:
    """Distances of points ``ep`` (k, n, 2) to the segments a + [0, 1]·e (k, n, m, 2 or broadcast), min over m."""
    rel = ep[:, :, None, :] - a
    v = np.clip(np.einsum("knmj,knmj->knm", rel, np.broadcast_to(e, rel.shape)) / e2, 0.0, 1.0)
    return np.hypot(*(rel - v[..., None] * e).transpose(3, 0, 1, 2)).min(axis=2)


def lines_deviation(piece, t0: float, ts, tolerance_mm: float) -> np.ndarray:
    """The chords from t0 to each of ``ts`` (k,): their two-sided sampled deviation, (k,) mm.

    Two-sided on samples: the 41 curve points on [t0, t] to the chord, and the
    chord's 9 points to the polyline through 81 curve points, for a batch of
    candidate ends at once.  Where the first part alone is over ``tolerance_mm`` the
    chord fails either way, and that part is returned (the second is not
    measured); a chord of length 0 is ``inf`` (it never fits).

    Examples
    --------
    >>> from camcam.geometry.curve import FunctionCurve
    >>> def circle(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 10.0 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], axis=-1)
    >>> piece = Piece(FunctionCurve(circle, 0.0, np.pi), 0.0, np.pi)
    >>> d = lines_deviation(piece, 0.0, [0.2, 0.0], 1.0)   # a 0.2 rad chord of a 10 mm circle: its sagitta
    >>> bool(abs(d[0] - 10.0 * (1 - np.cos(0.1))) < 1e-12), bool(np.isinf(d[1]))
    (True, True)
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
    dev = np.hypot(*(cp - q0 - u[..., None] * d[:, None]).transpose(2, 0, 1)).max(axis=1)
    dev[~(np.hypot(d[:, 0], d[:, 1]) > 0)] = np.inf  # as dev's caller: a chord of length 0 never fits
    both = dev <= tolerance_mm
    if both.any():
        w = np.linspace(0.0, 1.0, 9)[None, :, None]
        ep = ((1 - w) * q0 + w * q1[:, None])[both]  # (k', 9, 2): Line.points(9)
        a, e = dense[both, :-1], dense[both, 1:] - dense[both, :-1]  # (k', 80, 2) polyline segments
        e2 = np.maximum(np.einsum("kmj,kmj->km", e, e), 1e-300)
        dev[both] = np.maximum(dev[both], _point_polyline(ep, a[:, None], e[:, None], e2[:, None]).max(axis=1))
    return dev


def lines_fit(piece, t0: float, ts, tolerance_mm: float) -> np.ndarray:
    """Whether the chord from t0 to each of ``ts`` (k,) is within ``tolerance_mm`` two-sided, (k,) bool.

    The verdict of :func:`lines_deviation`.
    """
    return lines_deviation(piece, t0, ts, tolerance_mm) <= tolerance_mm


#: Expansion steps judged at once by :func:`greedy` (with the rest of the piece in the first batch).  A
#: call of :func:`lines_deviation` costs about 0.05 ms plus 0.013 ms a candidate (measured on
#: disc-oscillating-flat's pieces); the curvature's guess (seed eq. (8)) is mostly within one or two 1.6×
#: steps of the answer, so 4 steps (a factor 6.5) end nearly every expansion in the first call.
GREEDY_BATCH = 4
#: :func:`greedy` stops once its chord uses this much of the tolerance: (1 − 5e-4)·tol, a chord at most
#: 0.025 % shorter than the longest (the deviation grows as the chord's square).
GREEDY_TIGHT = 5e-4


def greedy(t0, b, dev_many, tolerance_mm, guess):
    """A near-longest chord end t1 in (t0, b] within ``tolerance_mm``: expansion from ``guess``, then regula falsi.

    ``dev_many(t0, ts)`` measures a batch of candidate ends (:func:`lines_deviation`).
    ``b`` itself if it fits; otherwise the expansion (by 1.6 from ``guess``, its
    first :data:`GREEDY_BATCH` steps judged with ``b`` in one batch; halving if
    the first fails) brackets the tolerance between a chord that fits and one
    that does not, and the regula falsi with the Illinois rule on
    g(t) = deviation − tol narrows the bracket (one candidate a call: each step
    lands next to the root, where bisection needed about 15 halvings of
    several candidates) until the chord that fits uses (1 − :data:`GREEDY_TIGHT`)
    of the tolerance or the bracket is 1e-6 of the span.  The result fits, unless
    no chord longer than 1e-9 of the span does: then that shortest one is
    returned (the caller's measurement of the printed path rejects it).
    On disc-oscillating-flat at 0.1–0.0005 mm the same 62–952 lines as the
    bisection to 1e-6 of the span before, with 4–6 times fewer candidates.
    """
    span = b - t0
    lo, g_lo, hi, g_hi = t0, -tolerance_mm, None, None  # a chord of length 0 deviates by nothing
    step = min(guess, span)
    first = True
    while hi is None:  # expansion
        steps, s = [], step
        while len(steps) < GREEDY_BATCH and t0 + s < b:
            steps.append(s)
            s *= 1.6
        if first:  # the whole rest of the piece is judged with the first steps, in one batch: the answer if it fits
            dev = dev_many(t0, np.concatenate([[b], t0 + np.array(steps, float)]))
            if dev[0] <= tolerance_mm:
                return b
            g_b, dev, first = float(dev[0]) - tolerance_mm, dev[1:], False
        else:
            dev = dev_many(t0, t0 + np.array(steps)) if steps else np.zeros(0)
        for s, d in zip(steps, dev.tolist()):
            if d <= tolerance_mm:
                lo, g_lo, step = t0 + s, d - tolerance_mm, s * 1.6
            else:
                hi, g_hi, step = t0 + s, d - tolerance_mm, s
                break
        else:
            if len(steps) < GREEDY_BATCH:  # the next step reaches b
                hi, g_hi = b, g_b
    while lo == t0:  # shrink until something fits
        step *= 0.5
        if step < span * 1e-9:
            return t0 + step * 2
        d = float(dev_many(t0, np.array([t0 + step]))[0])
        if d <= tolerance_mm:
            lo, g_lo = t0 + step, d - tolerance_mm
        else:
            hi, g_hi = t0 + step, d - tolerance_mm
    # Illinois: when the same end is replaced twice running, the other end's value counts half in the next
    # secant (s_lo, s_hi: the values the secant uses; g_lo, g_hi stay the measured ones)
    s_lo, s_hi, last = g_lo, g_hi, 0
    for _ in range(60):
        if g_lo >= -GREEDY_TIGHT * tolerance_mm or hi - lo <= 1e-6 * span:
            break
        if np.isfinite(s_hi):
            t = lo + (hi - lo) * (-s_lo) / (s_hi - s_lo)
            t = min(max(t, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))  # never on an end
        else:  # a chord of length 0 (inf) at hi: no slope to follow
            t = 0.5 * (lo + hi)
        g = float(dev_many(t0, np.array([t]))[0]) - tolerance_mm
        if g <= 0:
            lo, g_lo, s_lo = t, g, g
            if last == -1:
                s_hi *= 0.5
            last = -1
        else:
            hi, g_hi, s_hi = t, g, g
            if last == 1:
                s_lo *= 0.5
            last = 1
    return lo
