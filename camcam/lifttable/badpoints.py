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
   points are removed one at a time), at most ``max_fraction`` of the table.
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


@dataclass(frozen=True)
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


def _neighbour_sets(kx: np.ndarray, periodic: bool):
    """For position p among m kept points: (indices into kept, angle shifts) of its 4 neighbours."""
    m = len(kx)
    out = []
    for p in range(m):
        if periodic:
            idx = [(p + d) % m for d in (-2, -1, 1, 2)]
            shift = [-360.0 * (p + d < 0) + 360.0 * (p + d >= m) for d in (-2, -1, 1, 2)]
        else:
            lo = min(max(p - 2, 0), m - 5)
            idx = [q for q in range(lo, lo + 5) if q != p]
            shift = [0.0] * 4
        out.append((np.array(idx), np.array(shift)))
    return out


def _residuals(kx, ky, periodic):
    r = np.empty(len(kx))
    g = np.empty(len(kx))
    for p, (idx, shift) in enumerate(_neighbour_sets(kx, periodic)):
        pred, w2 = _predict(kx[idx] + shift, ky[idx], kx[p])
        r[p] = ky[p] - pred
        g[p] = math.sqrt(1.0 + w2)
    return r, g


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
    max_remove = max(1, int(max_fraction * n_unique))
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
    return BadPointReport(tuple(found), sigma, threshold, min_size, table.with_lift(cleaned))
