"""A fast stand-in for an exact cam curve while the fitter marches: Chebyshev series per analytic piece.

The fitter evaluates its curve thousands of times at single parameters; a cam
curve built from Taylor jets costs ~0.5 ms a call.  Between two breaks the
curve is analytic (or, inside a piecewise law such as the modified sine, smooth up to
a jump of a high derivative), so a Chebyshev interpolant of x(t) and y(t) of
degree 12 is tried, and an interval where it is not within ``accuracy_mm`` of
the exact curve at points between the nodes is halved (measured, and the
worst kept as ``error_mm``).  Only the fitting runs on it: the printed program is
measured against the exact curve afterwards.

A curve may turn by a corner inside a piece, where a law changes piece and the
acceleration jumps (a tilting roller's flank; its tool path, offset from it, jumps
there): such a curve names those angles (``inner``,
:class:`~camcam.geometry.jetcurve.JetCurve`) and the copy is split at them too, each
sub-interval measured on its own side of its ends (:data:`END_INSET`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev as C

__all__ = ["ChebyshevCurve", "chebyshev_curve"]


@dataclass(frozen=True, kw_only=True)
class ChebyshevCurve:
    """Piecewise Chebyshev copy of a curve: same parameter, breaks and ends."""

    breaks: np.ndarray
    knots: np.ndarray  # sub-interval ends (the breaks among them)
    series: tuple  # per sub-interval: coefficient arrays (n+1, 2) of P, P′, P″, P‴ in s ∈ [−1, 1]
    error_mm: float
    closed: bool

    @property
    def t_start(self) -> float:
        return float(self.breaks[0])

    @property
    def t_end(self) -> float:
        return float(self.breaks[-1])

    def evaluate(self, t, order: int = 0) -> np.ndarray:
        if not 0 <= order <= 3:
            raise ValueError(f"order must be 0..3, got {order!r}")
        t = np.atleast_1d(np.asarray(t, float))
        idx = np.clip(np.searchsorted(self.knots, t, side="right") - 1, 0, len(self.series) - 1)
        table = self._tables[order]  # (n+1, n_sub, 2)
        if t.size and (idx == idx[0]).all():
            # the usual call (a fitter's chord samples): one sub-interval, whose terms broadcast over the
            # points; gathering a copy of them per point cost about a third of the call
            j = int(idx[0])
            lo, hi = self.knots[j], self.knots[j + 1]
            c = table[:, j]  # (n+1, 2)
        else:
            lo, hi = self.knots[idx], self.knots[idx + 1]
            c = table[:, idx]  # (n+1, m, 2): every sub-interval at once, one term per contiguous slab
        u = ((2.0 * t - lo - hi) / (hi - lo))[:, None]
        # Clenshaw's recurrence for Σ c_k T_k(u), vectorised over the points, in place: each step is
        # (c_k + 2u·b1) − b2 as written out, the same operations in the same order, so the same bits
        u2 = 2.0 * u
        b1 = np.zeros((t.size, 2))
        b2 = np.zeros((t.size, 2))
        step = np.empty((t.size, 2))
        for k in range(c.shape[0] - 1, 0, -1):
            np.multiply(u2, b1, out=step)
            step += c[k]
            step -= b2
            b1, b2, step = step, b1, b2
        out = u * b1
        out += c[0]
        out -= b2
        return out

    @property
    def _tables(self) -> tuple:
        """Per derivative order: the series of all sub-intervals padded to one length, (n+1, n_sub, 2)."""
        cached = self.__dict__.get("_tables_cache")
        if cached is None:
            width = max(len(ser[0]) for ser in self.series)
            cached = []
            for order in range(4):
                arr = np.zeros((len(self.series), width, 2))
                for i, ser in enumerate(self.series):
                    arr[i, : len(ser[order])] = ser[order]
                cached.append(np.ascontiguousarray(arr.transpose(1, 0, 2)))
            cached = tuple(cached)
            object.__setattr__(self, "_tables_cache", cached)
        return cached


DEGREE = 12

#: How far inside a sub-interval its end checks are, as a share of its length (:func:`_piece`: each side of a break
#: measured on its own):
#: far above the spacing of doubles at a cam angle (4e-16 rad at 2π against 1e-12 × the length), far below
#: anything the copy's error could see (a curve moving 100 mm/rad moves 1e-10 mm over 1e-12 rad).
END_INSET = 1e-12


def _piece(curve, lo: float, hi: float, accuracy_mm: float, depth: int, out: list) -> float:
    """Append (lo, hi, series) sub-intervals covering [lo, hi]; return their worst error."""
    n = DEGREE
    k = np.arange(n + 1)
    nodes = 0.5 * (lo + hi) + 0.5 * (hi - lo) * np.cos(np.pi * (k + 0.5) / (n + 1))
    vals = curve.evaluate(nodes, 0)
    c = C.chebfit(np.cos(np.pi * (k + 0.5) / (n + 1)), vals, n)  # (n+1, 2), s ∈ [−1, 1]
    check = np.linspace(lo, hi, 4 * n + 3)
    # the ends a hair inside: the curve is measured on this sub-interval's side of a break, where an offset of a
    # curve with a corner jumps (the exact curve evaluated at a break takes the next piece's side)
    check[[0, -1]] += np.array([1.0, -1.0]) * END_INSET * (hi - lo)
    approx = C.chebval((2.0 * check - lo - hi) / (hi - lo), c).T
    err = float(np.hypot(*(approx - curve.evaluate(check, 0)).T).max())
    if err <= accuracy_mm or depth >= 14:
        scale = 2.0 / (hi - lo)
        out.append((lo, hi, tuple(C.chebder(c, j) * scale**j if j else c for j in range(4))))
        return err
    mid = 0.5 * (lo + hi)
    return max(_piece(curve, lo, mid, accuracy_mm, depth + 1, out), _piece(curve, mid, hi, accuracy_mm, depth + 1, out))


def chebyshev_curve(curve, accuracy_mm: float = 1e-7) -> ChebyshevCurve:
    """The Chebyshev copy of ``curve`` (any planar curve with ``breaks``).

    Examples
    --------
    >>> from camcam.geometry.curve import FunctionCurve
    >>> def circ(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 3.0 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], axis=-1)
    >>> C = chebyshev_curve(FunctionCurve(circ, 0.0, 2 * np.pi, closed=True))
    >>> C.error_mm < 1e-7, bool(abs(C.evaluate([1.0], 2)[0, 0] + 3 * np.cos(1.0)) < 1e-6)
    (True, True)
    """
    br = np.asarray(curve.breaks, float)
    inner = np.asarray(getattr(curve, "inner", ()), float)
    parts: list = []
    worst = 0.0
    for lo, hi in zip(br, br[1:]):
        ends = [float(lo), *(float(x) for x in inner[(inner > lo) & (inner < hi)]), float(hi)]
        for a, b in zip(ends, ends[1:]):
            worst = max(worst, _piece(curve, a, b, accuracy_mm, 0, parts))
    knots = np.array([p[0] for p in parts] + [parts[-1][1]])
    return ChebyshevCurve(breaks=br, knots=knots, series=tuple(p[2] for p in parts), error_mm=worst,
                          closed=bool(curve.closed))
