"""Extremes and sign ranges of functions of the cam angle, per analytic piece.

Within a piece (between two motion-segment boundaries) every cam quantity is
analytic, but where the segment's law changes piece (``inner`` breaks: the
parabolic law's acceleration jumps at mid-rise) a quantity built on a jumping
derivative jumps too.  Its stationary points are the roots of its exact derivative: a
sample of the derivative only *brackets* them, and a 16-section search of all
brackets at once (vectorised over the brackets) finds them to 1e-13 rad.  Piece ends are candidates too,
evaluated one-sided, and so are both sides of every inner break (:data:`INNER_SIDE_RAD` off it): campaign
case 45:59's flat-faced profile has radius of curvature +354 mm before the parabolic law's mid-rise and
−1.07 mm after it, a cusp that no root of its derivative shows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["Candidate", "roots", "roots_in", "stationary_candidates", "negative_ranges", "extreme"]

#: Samples per piece used to bracket roots (the roots themselves are bisected to
#: ROOT_XTOL), and at least one per BRACKET_MAX_RAD of cam angle: a lift table's
#: spline has a knot every degree or so, and two roots must not share a bracket.
BRACKETS_PER_PIECE = 48
BRACKET_MAX_RAD = math.radians(0.5)

#: Root tolerance on the cam angle, rad.
ROOT_XTOL = 1e-13

#: Parts each bracket is cut into per round of the root search (4 bits a round instead of bisection's 1,
#: for about the same cost: a round is one call of the function on small arrays).
SECTIONS = 16

#: Offset (rad) either side of a law's inner break at which it is evaluated: the one-sided values to
#: |f′|·1e-10 (1e-6 mm for a radius of curvature changing by 1e4 mm/rad), far above the angle's rounding
#: (1e-15 rad) so that each side takes its own piece of the law.
INNER_SIDE_RAD = 1e-10

PieceFunc = Callable[[np.ndarray, int], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class Candidate:
    t: float
    value: float
    piece: int


def roots(g: Callable[[np.ndarray], np.ndarray], a: float, b: float, xtol: float = ROOT_XTOL) -> list[float]:
    """Roots of g in [a, b] (:func:`roots_in` on one interval)."""
    return roots_in(g, [(a, b)], xtol)[0]


def roots_in(g: Callable[[np.ndarray], np.ndarray], intervals, xtol: float = ROOT_XTOL) -> list[list[float]]:
    """Roots of g in each interval [a, b], ascending: sign changes on a grid bracket them, then every
    bracket is cut into :data:`SECTIONS` parts at once (all brackets of all intervals in one call of
    ``g``) and the part holding the sign change kept, until narrower than ``xtol``.

    The grid has at least :data:`BRACKETS_PER_PIECE` cells per interval and one per
    :data:`BRACKET_MAX_RAD`; a pair of roots closer than a cell is not seen.
    """
    cells = [max(BRACKETS_PER_PIECE, int(math.ceil((b - a) / BRACKET_MAX_RAD))) for a, b in intervals]
    grids = [np.linspace(a, b, n + 1) for (a, b), n in zip(intervals, cells)]
    vals = np.split(g(np.concatenate(grids)), np.cumsum([len(ts) for ts in grids])[:-1])
    found: list[list[float]] = []
    lo_l, hi_l, s_l, owner_l = [], [], [], []
    widest = xtol
    for k, (ts, vs, (a, b), n) in enumerate(zip(grids, vals, intervals, cells)):
        found.append([float(ts[i]) for i in range(1, len(ts) - 1) if vs[i] == 0.0])
        idx = np.flatnonzero(vs[:-1] * vs[1:] < 0)
        lo_l.append(ts[idx]), hi_l.append(ts[idx + 1]), s_l.append(np.sign(vs[idx]))
        owner_l.append(np.full(idx.size, k))
        widest = max(widest, (b - a) / n)
    lo, hi, s_lo, owner = (np.concatenate(x) for x in (lo_l, hi_l, s_l, owner_l))
    if lo.size:
        frac = np.arange(1, SECTIONS) / SECTIONS
        rows = np.arange(len(lo))
        # each round shrinks every bracket by SECTIONS: from a grid cell to 1e-13 rad takes < 13 rounds
        rounds = max(1, int(math.ceil(math.log(widest / xtol, SECTIONS))) + 1)
        for _ in range(rounds):
            pts = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
            fm = g(pts.ravel()).reshape(pts.shape)
            # the first cut whose sign differs from the bracket's low end (hi's own sign differs: a sentinel)
            changed = np.concatenate([np.sign(fm) != s_lo[:, None], np.ones((len(lo), 1), bool)], axis=1)
            j = np.argmax(changed, axis=1)
            ends = np.concatenate([lo[:, None], pts, hi[:, None]], axis=1)
            lo, hi = ends[rows, j], ends[rows, j + 1]
        for k, x in zip(owner, 0.5 * (lo + hi)):
            found[int(k)].append(float(x))
    return [sorted(f) for f in found]


def stationary_candidates(f: PieceFunc, breaks: np.ndarray, inner=None) -> list[Candidate]:
    """Piece ends, roots of f′ and both sides of the inner breaks (``inner[i]``: the angles inside piece i where
    f may jump) in every piece; ``f(t, piece)`` → (value, derivative)."""
    out = []
    for i, (a, b) in enumerate(zip(breaks, breaks[1:])):
        ts = [a, b, *roots(lambda t: f(t, i)[1], a, b)]
        if inner is not None:
            ts += [float(x) + side * INNER_SIDE_RAD for x in inner[i] for side in (-1.0, 1.0)]
        vals = f(np.array(ts), i)[0]
        out += [Candidate(float(t), float(v), i) for t, v in zip(ts, vals)]
    return out


def extreme(f: PieceFunc, breaks: np.ndarray, kind: str, inner=None) -> Candidate:
    """The ``"max"``, ``"min"`` or ``"absmax"`` of f over the revolution (first angle on ties); ``inner``: per
    piece the angles where f may jump (a cam's ``inner_breaks``).

    Examples
    --------
    f = t on [0, 1), t − 2 on [1, 2]: its least value −1 is just after the jump at 1, where f′ has no root.

    >>> f = lambda t, i: (np.where(t < 1.0, t, t - 2.0), np.ones_like(t))
    >>> round(extreme(f, np.array([0.0, 2.0]), "min").value, 6), round(extreme(f, np.array([0.0, 2.0]), "min",
    ...     inner=[[1.0]]).value, 6)
    (0.0, -1.0)
    """
    cands = stationary_candidates(f, breaks, inner)
    key = {"max": lambda c: c.value, "min": lambda c: -c.value, "absmax": lambda c: abs(c.value)}[kind]
    best = max(key(c) for c in cands)
    return min((c for c in cands if key(c) >= best - 1e-12 * max(1.0, abs(best))), key=lambda c: c.t)


def negative_ranges(f: Callable[[np.ndarray, int], np.ndarray], breaks: np.ndarray) -> list[tuple[float, float]]:
    """Parameter ranges where f < 0 (roots per piece), merged across breaks and 2π."""
    spans: list[list[float]] = []
    for i, (a, b) in enumerate(zip(breaks, breaks[1:])):
        g = lambda t, i=i: f(t, i)  # noqa: E731
        edges = [a, *roots(g, a, b), b]
        for lo, hi in zip(edges, edges[1:]):
            if hi - lo <= 0:
                continue
            if float(g(np.array([0.5 * (lo + hi)]))[0]) < 0:
                if spans and abs(spans[-1][1] - lo) < 1e-12:
                    spans[-1][1] = hi
                else:
                    spans.append([lo, hi])
    if len(spans) > 1 and abs(spans[0][0] - breaks[0]) < 1e-12 and abs(spans[-1][1] - breaks[-1]) < 1e-12:
        spans[0][0] = spans.pop()[0] - 2 * math.pi
    return [(lo, hi) for lo, hi in spans]
