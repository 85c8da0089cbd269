"""The printed rounding: one model of the numbers a post writes, used by the fitter, the writer and the rotary path.

A coordinate prints as an integer count of 10^−d mm (d = the post's
decimals).  The count is the *correctly rounded* decimal value of the
coordinate's exact binary value, ties to even — what Python's ``round(x, d)``
gives, and what ``int(round(x · 10^d))`` does not always give (the product is
itself rounded: 292.66865 lies just above the half-way point, yet
292.66865 × 10⁴ is exactly 2926686.5 in binary and rounds down).

Arcs print their centre as I/J (rounded centre) or as R (rounded radius; the
controller rebuilds the centre from the rounded ends, short-arc side) or as
an absolute centre, rounded (arc_format "cc_absolute"): :meth:`Quantizer.printed_elements`
rebuilds the contour the controller will cut from those numbers.

Examples
--------
>>> q = Quantizer(4)
>>> q.count(292.66865), q.snap(292.66865)
(2926687, 292.6687)
>>> int(round(292.66865 * 10**4))  # the product rounds first: one count short
2926686
>>> q.snap(-0.00001)
0.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import ROUND_HALF_EVEN, Decimal

import numpy as np

from camcam.toolpath.elements import Arc, Line

__all__ = ["Quantizer", "ARC_FORMATS"]

#: How a post prints an arc's centre.
ARC_FORMATS = ("ij_incremental", "ij_absolute", "r", "cc_absolute")


def _exact_count(v: float, decimals: int) -> int:
    """The correctly rounded count of 10^−d in ``v`` (exact decimal arithmetic)."""
    return int(Decimal(v).scaleb(decimals).quantize(Decimal(1), rounding=ROUND_HALF_EVEN))


@dataclass(frozen=True)
class Quantizer:
    """The printed rounding of one post: ``decimals`` after the point, arcs in ``arc_format``.

    Parameters
    ----------
    decimals : int
        Digits after the decimal point (0–9).
    arc_format : str
        One of :data:`ARC_FORMATS`.
    """

    decimals: int
    arc_format: str = "ij_incremental"

    def __post_init__(self) -> None:
        if not (isinstance(self.decimals, int) and 0 <= self.decimals <= 9):
            raise ValueError(f"decimals: expected an integer 0–9, got {self.decimals!r}")
        if self.arc_format not in ARC_FORMATS:
            raise ValueError(f"arc_format: expected one of {ARC_FORMATS}, got {self.arc_format!r}")

    @property
    def step_mm(self) -> float:
        """The printed grid step 10^−d."""
        return 10.0 ** (-self.decimals)

    def count(self, v):
        """The printed value of ``v`` as an integer count of 10^−d (int, or an int64 array for an array).

        Vectorised: the product v·10^d decides every value except those within
        a few ulps of a half, which are decided exactly.
        """
        if np.ndim(v) == 0:
            return _exact_count(float(v), self.decimals)
        x = np.asarray(v, float)
        scaled = x * 10.0 ** self.decimals
        n = np.rint(scaled)
        near = np.abs(np.abs(scaled - np.trunc(scaled)) - 0.5) <= 8 * np.spacing(np.abs(scaled)) + 1e-300
        out = n.astype(np.int64)
        for i in zip(*np.nonzero(near)):
            out[i] = _exact_count(float(x[i]), self.decimals)
        return out

    def value(self, count):
        """The number a count stands for (mm), as a float or float array; −0 becomes 0."""
        if np.ndim(count) == 0:
            return int(count) / 10 ** self.decimals + 0.0
        return np.asarray(count, np.int64) / 10 ** self.decimals + 0.0

    def snap(self, v):
        """``v`` as printed: ``value(count(v))``."""
        return self.value(self.count(v))

    def snap_point(self, p) -> tuple[float, ...]:
        """A point's coordinates as printed."""
        return tuple(self.snap(float(x)) for x in p)

    def snap_points(self, points) -> list[tuple[float, ...]]:
        """:meth:`snap_point` of each of ``points`` (any lengths), the coordinates counted as one array.

        The same floats as point by point (the array :meth:`count` is the
        correctly rounded count too), at a fraction of the cost: a contour's
        hundreds of ends are counted in one call, not one exact decimal each.

        Examples
        --------
        >>> q = Quantizer(4)
        >>> q.snap_points([(292.66865, -0.00001), (1.0, 2.00005, 3.0)]) == [q.snap_point((292.66865, -0.00001)),
        ...                                                                q.snap_point((1.0, 2.00005, 3.0))]
        True
        """
        sizes = [len(p) for p in points]
        flat = np.fromiter((float(x) for p in points for x in p), float, count=sum(sizes))
        values = self.value(self.count(flat)).tolist() if len(flat) else []
        out, i = [], 0
        for n in sizes:
            out.append(tuple(values[i:i + n]))
            i += n
        return out

    def _snapped(self, elements):
        """Each element with its printed start, end and centre (None for a line), all counted as one array."""
        snapped = iter(self.snap_points([p for e in elements for p in _points(e)]))
        for e in elements:
            yield e, next(snapped), next(snapped), next(snapped) if isinstance(e, Arc) else None

    def snap_elements(self, elements) -> tuple:
        """Ends and centres on the printed grid (I/J form); elements that collapse are dropped."""
        out = []
        for e, s, t, c in self._snapped(elements):
            if s == t:
                continue
            out.append(Arc(s, t, c, e.ccw) if isinstance(e, Arc) else Line(s, t))
        return tuple(out)

    def radius_count(self, start, centre) -> int:
        """The printed R word of an arc (a count of 10^−d): :meth:`radius_word` of its printed start and centre."""
        return self.radius_word([self.count(float(v)) for v in start[:2]], [self.count(float(v)) for v in centre[:2]])

    @staticmethod
    def radius_word(start_count, centre_count) -> int:
        """The R word from the printed start and centre (counts of 10^−d): their distance, rounded to a count.

        The one rounding of R: the writer (:mod:`camcam.post.gcode`) prints it, and the fitter's model of the
        printed arc (:meth:`radius_count`, :meth:`printed_elements`) rebuilds the centre from it.

        Examples
        --------
        >>> Quantizer.radius_word((0, 0), (30000, 40000))
        50000
        """
        (sx, sy), (cx, cy) = start_count[:2], centre_count[:2]
        return round(math.hypot(cx - sx, cy - sy))

    def printed_elements(self, elements) -> tuple:
        """The contour the controller cuts from the printed numbers.

        With I/J (or CC) the centre is the rounded centre; with R it is rebuilt
        from the rounded ends and the printed radius (:meth:`radius_count`), on
        the short-arc side.
        """
        out = []
        for e, s, t, c in self._snapped(elements):
            if isinstance(e, Line):
                out.append(Line(s, t))
            elif self.arc_format == "r":
                r = self.value(self.radius_count(e.start, e.centre))
                mx, my = (s[0] + t[0]) / 2, (s[1] + t[1]) / 2
                vx, vy = t[0] - s[0], t[1] - s[1]
                half = math.hypot(vx, vy) / 2
                h = math.sqrt(max(r * r - half * half, 0.0))
                nx, ny = -vy / (2 * half), vx / (2 * half)
                side = 1.0 if e.ccw else -1.0  # short arc: centre on the turning side
                out.append(Arc(s, t, (mx + side * h * nx, my + side * h * ny), e.ccw))
            else:
                out.append(Arc(s, t, c, e.ccw))
        return tuple(out)


def _points(e) -> tuple:
    """An element's points as printed in order: start, end, and an arc's centre."""
    return (e.start, e.end, e.centre) if isinstance(e, Arc) else (e.start, e.end)
