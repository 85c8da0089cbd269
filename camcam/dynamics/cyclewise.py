"""Extremes, roots and integrals of functions of the cam angle over the analytic pieces (motion segments).

numpy only (a run's own process does not import scipy).  Extremes: a grid of every piece finds the best
sample; the pieces whose best sample ties with it (to :data:`TIE`) are refined by sectioning: the two cells
around the best of :data:`PARTS` + 1 points are kept, one call of the function per round, until the bracket
is below :data:`XTOL_EXTREME` (1e-9 rad: at a smooth extreme the value is then exact to ~1e-18 of its
curvature; at a piece end the best sample is the end itself).  Roots: a sign change is sectioned the same way,
to :data:`XTOL` (1e-12 rad).  Integrals: Gauss–Legendre with
:data:`GAUSS_NODES` nodes per grid cell (a quarter degree), exact to rounding on the smooth pieces.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["bracket_grid", "Sampled", "sample", "refine_min", "piece_minimum", "section_root", "gauss_span",
           "BRACKET_CELLS", "BRACKET_DEG"]

#: Cells of the bracketing grid: at least this many per piece and one per BRACKET_DEG.
BRACKET_CELLS = 64
BRACKET_DEG = 0.25

#: Points per sectioning round (the bracket shrinks by PARTS/2 a round) and the bracket it stops at, rad.
PARTS = 64
XTOL = 1e-12
XTOL_EXTREME = 1e-9

#: Gauss–Legendre nodes per grid cell.
GAUSS_NODES = 6

#: Pieces whose best sample is within TIE (relative) of the best are refined too.
TIE = 1e-3


def bracket_grid(a: float, b: float) -> np.ndarray:
    """The bracketing grid of the piece [a, b] (rad): :data:`BRACKET_CELLS` cells at least, one per :data:`BRACKET_DEG`."""
    return np.linspace(a, b, max(BRACKET_CELLS, int(math.ceil(math.degrees(b - a) / BRACKET_DEG))) + 1)


class Sampled:
    """A function's values on every piece's grid (``grids[i]``, ``values[i]``)."""

    def __init__(self, grids, values) -> None:
        self.grids = grids
        self.values = values


def sample(f, pieces) -> Sampled:
    grids = [bracket_grid(a, b) for a, b in pieces]
    return Sampled(grids, [np.asarray(f(ts, i), float) for i, ts in enumerate(grids)])


def refine_min(f, lo: float, hi: float, i: int) -> tuple[float, float]:
    """(least value, θ) of ``f(θ, i)`` on [lo, hi] by sectioning (module notes)."""
    best = (math.inf, math.nan)
    rounds = max(1, int(math.ceil(math.log(max(hi - lo, XTOL_EXTREME) / XTOL_EXTREME, PARTS / 2.0))) + 1)
    for _ in range(rounds):
        ts = np.linspace(lo, hi, PARTS + 1)
        v = np.asarray(f(ts, i), float)
        v = np.where(np.isfinite(v), v, np.inf)
        j = int(np.argmin(v))
        if v[j] < best[0]:
            best = (float(v[j]), float(ts[j]))
        lo, hi = ts[max(j - 1, 0)], ts[min(j + 1, PARTS)]
    return best


def piece_minimum(f, pieces, sampled: Sampled | None = None) -> tuple[float, float, int]:
    """(least value, θ, piece) of ``f(θ array, piece) -> values`` over the pieces (module notes); ``sampled``:
    its values on the grids when the caller has them.  (inf, nan, -1) when f is nowhere finite."""
    s = sampled if sampled is not None else sample(f, pieces)
    bests = []
    for i, (ts, v) in enumerate(zip(s.grids, s.values)):
        v = np.where(np.isfinite(v), v, np.inf)
        j = int(np.argmin(v))
        bests.append((float(v[j]), j, i))
    top = min(b[0] for b in bests)
    if not math.isfinite(top):
        return math.inf, math.nan, -1
    spread = max(abs(top), max((abs(b[0]) for b in bests if math.isfinite(b[0])), default=1.0), 1e-300)
    out = (math.inf, math.nan, -1)
    for value, j, i in bests:
        if value > top + TIE * spread:
            continue
        ts, v = s.grids[i], s.values[i]
        cand = (value, float(ts[j]))
        near = v[max(j - 1, 0):j + 2]
        if np.all(near == value):  # flat around the best sample (a dwell): nothing to refine
            if cand[0] < out[0]:
                out = (cand[0], cand[1], i)
            continue
        got = refine_min(f, ts[max(j - 1, 0)], ts[min(j + 1, len(ts) - 1)], i)
        if got[0] < cand[0]:
            cand = got
        if cand[0] < out[0]:
            out = (cand[0], cand[1], i)
    return out


def section_root(g, lo: float, hi: float, i: int) -> float:
    """A root of ``g(θ, i)`` in [lo, hi], where g changes sign, by sectioning to :data:`XTOL`."""
    s_lo = np.sign(float(np.asarray(g(np.array([lo]), i), float)[0]))
    frac = np.arange(1, PARTS) / PARTS
    while hi - lo > XTOL:
        pts = lo + (hi - lo) * frac
        changed = np.sign(np.asarray(g(pts, i), float)) != s_lo
        k = int(np.argmax(changed)) if changed.any() else PARTS - 1
        ends = np.concatenate([[lo], pts, [hi]])
        lo, hi = ends[k], ends[k + 1]
    return 0.5 * (lo + hi)


def gauss_span(a, b) -> tuple[np.ndarray, np.ndarray]:
    """(nodes (n, GAUSS_NODES), weights (n, GAUSS_NODES)) of Gauss–Legendre on the cells [a_k, b_k]."""
    x, w = np.polynomial.legendre.leggauss(GAUSS_NODES)
    a, b = np.atleast_1d(np.asarray(a, float))[:, None], np.atleast_1d(np.asarray(b, float))[:, None]
    return 0.5 * (a + b) + 0.5 * (b - a) * x[None, :], 0.5 * (b - a) * w[None, :]
