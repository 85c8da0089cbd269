"""A motion program's polynomial and sinusoid pieces as one table: every segment evaluated in one pass.

:meth:`MotionProgram.lifts <camcam.motion.program.MotionProgram.lifts>` evaluates segment by segment, each
law on its own angles.  On a few thousand angles that is some 35 numpy calls a segment, most of the time
in the calls' overhead: 0.3–0.4 ms for 2 880 angles of a four- or five-segment program, paid hundreds of
times by the exact curves (jets) and the barrel cam's 3-D groove measurement.  :class:`PieceTable` puts
every piece of every segment's law in one table, so that each order is one gather, one Horner pass and one
sine and cosine for all angles.

The arithmetic is the segment loop's, element by element, so the values are the same bit for bit
(``tests/motion/test_piece_table.py``):

* the law's piece is the count of its inner breaks at or below T, which is ``searchsorted(breaks, T,
  "right") − 1`` clipped to the pieces (T lies in [0, 1], the first break is 0 and the last 1);
* the polynomial coefficients are padded with zeros on the high side, and Horner's steps over the zeros
  give 0·u + c = c exactly before the law's own highest coefficient;
* the sinusoid is added only on the pieces of a law whose table at that order has one (as
  :meth:`PiecewiseLaw.evaluate <camcam.motion.law.PiecewiseLaw.evaluate>` adds it to every piece of such a law);
* each segment's ``scale·r / span^k + base`` (``0.0`` added for k > 0) with the same Python floats.

Only laws made of :class:`~camcam.motion.piece.TrigPoly` pieces (:meth:`MotionLaw.as_piecewise
<camcam.motion.law.MotionLaw.as_piecewise>`) with at most :data:`MAX_INNER_BREAKS` inner breaks go in a
table; a program with any other law (a lift table's B-spline, a law of many pieces) keeps the segment loop.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PieceTable", "MAX_INNER_BREAKS"]

#: The most inner breaks a law of a tabled program has: each angle is compared with its segment's inner
#: breaks (an (n, breaks) table); an optimised B-spline law of many pieces keeps the segment loop.
MAX_INNER_BREAKS = 16


@dataclass(frozen=True, eq=False)
class _Order:
    """One derivative order of every piece: coefficients (pieces, degree + 1) padded with zeros, the
    sinusoid's a, b, ω (pieces,), and whether the piece's law adds a sinusoid at this order."""

    coef: np.ndarray
    a: np.ndarray
    b: np.ndarray
    w: np.ndarray
    trig: np.ndarray


@dataclass(frozen=True, eq=False, kw_only=True)
class PieceTable:
    """Every piece of a program's laws in one table (see the module notes).

    ``inner`` is (segments, :data:`MAX_INNER_BREAKS` at most) with each segment's inner law breaks, +inf after
    them; ``first`` each segment's first row in the table; ``start`` each row's law break (u = T − start);
    ``scale``, ``base`` per segment; ``span_pow[i, k]`` segment i's span (rad) to the k-th power.
    """

    inner: np.ndarray
    first: np.ndarray
    start: np.ndarray
    orders: tuple[_Order, ...]
    scale: np.ndarray
    base: np.ndarray
    span_pow: np.ndarray

    @staticmethod
    def of(segments) -> "PieceTable | None":
        """The table of ``segments`` (:class:`~camcam.motion.program.Segment`), or None when a law does not
        go in one (module notes)."""
        laws = [s.law.as_piecewise() for s in segments]
        if any(law is None or len(law.breaks) - 2 > MAX_INNER_BREAKS for law in laws):
            return None
        m = max(len(law.breaks) - 2 for law in laws)
        inner = np.full((len(laws), max(m, 1)), np.inf)
        for i, law in enumerate(laws):
            inner[i, : len(law.breaks) - 2] = law.breaks[1:-1]
        counts = [len(law.pieces) for law in laws]
        first = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(int)
        start = np.concatenate([np.asarray(law.breaks[:-1], dtype=float) for law in laws])
        orders = []
        for k in range(min(len(law.tables) for law in laws)):
            tables = [law.tables[k] for law in laws]
            width = max(t[0].shape[1] for t in tables)
            coef = np.zeros((len(start), width))
            for f, t in zip(first, tables):
                coef[f:f + len(t[0]), : t[0].shape[1]] = t[0]
            a, b, w = (np.concatenate([t[j] for t in tables]) for j in (1, 2, 3))
            trig = np.concatenate([np.full(len(t[3]), bool(t[3].any())) for t in tables])
            orders.append(_Order(coef, a, b, w, trig))
        span_pow = np.array([[s.span_rad**k for k in range(len(orders))] for s in segments])
        return PieceTable(inner=inner, first=first, start=start, orders=tuple(orders),
                          scale=np.array([s.scale for s in segments], dtype=float),
                          base=np.array([s.base for s in segments], dtype=float), span_pow=span_pow)

    def lifts(self, idx: np.ndarray, T: np.ndarray, orders) -> np.ndarray:
        """Segment ``idx``'s lift of each of ``orders`` at its T (1-D arrays, T in [0, 1]): (len(orders), n)."""
        row = self.first[idx] + np.count_nonzero(self.inner[idx] <= T[:, None], axis=1)
        u = T - self.start[row]
        scale, base = self.scale[idx], self.base[idx]
        out = np.empty((len(orders), T.size))
        sin_cos = None  # (the angles with a sinusoid, their ω, sin ωu, cos ωu) of the last order that had one
        for r, k in zip(out, orders):
            o = self.orders[k]
            c = o.coef[row]
            v = c[:, -1]
            for j in range(c.shape[1] - 2, -1, -1):
                v = v * u + c[:, j]
            at = np.flatnonzero(o.trig[row])  # the sine and cosine only where a law has them (a dwell has not)
            if len(at):
                rows = row[at]
                w = o.w[rows]
                if sin_cos is None or not (np.array_equal(sin_cos[0], at) and np.array_equal(sin_cos[1], w)):
                    wu = w * u[at]
                    sin_cos = (at, w, np.sin(wu), np.cos(wu))
                v = v.copy() if v.base is not None else v  # a column of the gathered table: not to be written
                v[at] = v[at] + o.a[rows] * sin_cos[2] + o.b[rows] * sin_cos[3]
            r[:] = scale * v / self.span_pow[idx, k] + (base if k == 0 else 0.0)
        return out
