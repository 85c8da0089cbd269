"""Finding bad points in a lift table automatically.

The rule (leave-one-out against the neighbours' cubic, robust noise scale):

1. For each kept point i, predict its lift from the cubic through its four
   nearest kept neighbours, two on each side (wrapping round 360° for a full
   revolution; at the ends of a rise-only table the four nearest on one side):
   p_i = Σ w_j h_j with Lagrange weights w_j.  The deviation r_i = h_i − p_i is
   what removing point i changes: on even spacing r_i is the local fourth
   difference / 6, i.e. the change of the local third differences when the
   point is replaced by its neighbours' prediction.
2. Noise scale: if the lifts carry independent noise of σ, r_i has standard
   deviation g_i·σ with g_i = √(1 + Σ w_j²) (√(70/36) ≈ 1.39 on even
   spacing).  σ is estimated robustly as σ̂ = 1.4826·median|r_i/g_i| (the MAD
   scale; a few spikes do not move it), floored at the rounding noise
   resolution/√12 of the printed lifts.
3. A point is bad when |r_i| > k·g_i·σ̂ (k = ``threshold``, default 5: a
   5-sigma event has a chance of 6·10⁻⁷ per point, 2·10⁻⁴ per 360-point table, for Gaussian noise) *and*
   |r_i| > ``min_size`` (default 0.001 mm: below a micrometre nothing is
   worth removing).
4. The worst bad point is removed and steps 1–3 are repeated on the rest (a
   spike also disturbs its neighbours' r, by 2/3 and 1/6 of its size, so
   points are removed one at a time), at most ``max_fraction`` of the table
   and at most :data:`MAX_BAD_POINTS`.
5. Each removed point's lift is re-interpolated from the cubic through its
   four nearest kept neighbours; the angles stay.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.lifttable.table import LiftTable

__all__ = ["BadPoint", "BadPointReport", "find_bad_points", "DEFAULT_THRESHOLD", "DEFAULT_MIN_SIZE"]

DEFAULT_THRESHOLD = 5.0
DEFAULT_MIN_SIZE = 1e-3
MAD_TO_SIGMA = 1.4826


@dataclass(frozen=True)
class BadPoint:
    """A removed point: its angle, file row, deviation from its neighbours' cubic, and score r/(g·σ̂)."""

    angle_deg: float
    row: int
    deviation: float
    score: float


@dataclass(frozen=True, kw_only=True)
class BadPointReport:
    """The bad points found (in order of removal) and the noise scale used."""

    points: tuple[BadPoint, ...]
    noise_sigma: float
    threshold: float
    min_size: float
    table: LiftTable  # the cleaned table: bad lifts re-interpolated

    @property
    def angles_deg(self) -> list[float]:
        return sorted(p.angle_deg for p in self.points)


def _predict(xs: np.ndarray, ys: np.ndarray, xi: float) -> tuple[float, float]:
    """Cubic through the 4 points (xs, ys) at xi: (prediction, Σ w²)."""
    w = np.ones(4)
    for j in range(4):
        for m in range(4):
            if m != j:
                w[j] *= (xi - xs[m]) / (xs[j] - xs[m])
    return float(w @ ys), float(w @ w)


def _neighbour_sets(kx: np.ndarray, periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """For every position p among m kept points: (m, 4) indices into kept and angle shifts of its 4 neighbours."""
    m = len(kx)
    p = np.arange(m)[:, None]
    if periodic:
        q = p + np.array([-2, -1, 1, 2])[None, :]
        return q % m, -360.0 * (q < 0) + 360.0 * (q >= m)
    lo = np.clip(p - 2, 0, m - 5)
    q = lo + np.arange(4)[None, :]
    q = q + (q >= p)  # the five from lo without p itself
    return q, np.zeros(q.shape)


def _residuals(kx, ky, periodic):
    """r = lift − the neighbours' cubic, and g = √(1 + Σw²), for every kept point (vectorised
    :func:`_predict`, the same products in the same order)."""
    idx, shift = _neighbour_sets(kx, periodic)
    xs, ys, xi = kx[idx] + shift, ky[idx], kx
    w = np.ones(idx.shape)
    for j in range(4):
        for m in range(4):
            if m != j:
                w[:, j] *= (xi - xs[:, m]) / (xs[:, j] - xs[:, m])
    pred = w[:, 0] * ys[:, 0] + w[:, 1] * ys[:, 1] + w[:, 2] * ys[:, 2] + w[:, 3] * ys[:, 3]
    w2 = w[:, 0] * w[:, 0] + w[:, 1] * w[:, 1] + w[:, 2] * w[:, 2] + w[:, 3] * w[:, 3]
    return ky - pred, np.sqrt(1.0 + w2)


#: Most bad points removed from one table (each removal re-scores the table).
MAX_BAD_POINTS = 1000


def find_bad_points(
    table: LiftTable,
    threshold: float = DEFAULT_THRESHOLD,
    min_size: float = DEFAULT_MIN_SIZE,
    max_fraction: float = 0.1,
) -> BadPointReport:
    """Find, remove and re-interpolate bad points by the rule in the module docstring.

    Examples
    --------
    >>> import numpy as np
    >>> ang = np.arange(0.0, 361.0, 1.0)
    >>> h = 5 - 5 * np.cos(np.radians(ang)) + np.random.default_rng(0).normal(0, 0.002, ang.size)
    >>> h[100] += 0.05; h[-1] = h[0]
    >>> rep = find_bad_points(LiftTable(tuple(ang), tuple(h)))
    >>> rep.angles_deg
    [100.0]
    """
    periodic = table.full_revolution
    x, y = table.x, table.y
    n_unique = len(x) - 1 if periodic else len(x)
    keep = np.ones(n_unique, dtype=bool)
    floor = table.resolution / math.sqrt(12.0)
    found: list[BadPoint] = []
    sigma = floor
    max_remove = min(max(1, int(max_fraction * n_unique)), MAX_BAD_POINTS)
    while keep.sum() > 5:
        kidx = np.flatnonzero(keep)
        kx, ky = x[kidx], y[kidx]
        r, g = _residuals(kx, ky, periodic)
        sigma = max(MAD_TO_SIGMA * float(np.median(np.abs(r / g))), floor)
        if sigma == 0.0:
            break
        score = np.abs(r) / (g * sigma)
        bad = (score > threshold) & (np.abs(r) > min_size)
        if not bad.any() or len(found) >= max_remove:
            break
        p = int(np.argmax(np.where(bad, score, -1.0)))
        i = int(kidx[p])
        found.append(BadPoint(float(x[i]), table.row_of(i), float(r[p]), float(r[p] / (g[p] * sigma))))
        keep[i] = False
    cleaned = y.copy()
    if found:
        kidx = np.flatnonzero(keep)
        kx, ky = x[kidx], y[kidx]
        for i in np.flatnonzero(~keep):
            # the 4 kept neighbours of a removed point: insert it, then use the kept sets
            pos = int(np.searchsorted(kx, x[i]))
            if periodic:
                m = len(kx)
                idx = np.array([(pos + d) % m for d in (-2, -1, 0, 1)])
                shift = np.array([-360.0 * (pos + d < 0) + 360.0 * (pos + d >= m) for d in (-2, -1, 0, 1)])
            else:
                lo = min(max(pos - 2, 0), len(kx) - 4)
                idx = np.arange(lo, lo + 4)
                shift = np.zeros(4)
            cleaned[i], _ = _predict(kx[idx] + shift, ky[idx], x[i])
        if periodic:
            cleaned[-1] = cleaned[0]
    return BadPointReport(points=tuple(found), noise_sigma=sigma, threshold=threshold, min_size=min_size,
                          table=table.with_lift(cleaned))
