"""A fitted lift table as a motion law, and as a motion program.

A cubic spline becomes a :class:`~camcam.motion.law.PiecewiseLaw` of
polynomial :class:`~camcam.motion.piece.TrigPoly` pieces (extremes are
polynomial roots); seed 002's B-spline becomes a :class:`ChordBSplineLaw`
whose extremes are roots of its rational derivatives' numerators.

A full-revolution table is its own law: S(T) is the lift itself (mm or deg)
at angle 360·T, used as one segment over 0–360° with scale 1 and base 0.  A
rise-only table is normalised to a rise law, S = (h − h_0)/(h_N − h_0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from camcam.errors import InputError
from camcam.lifttable.bspline import ChordBSpline
from camcam.lifttable.interpolate import interpolate
from camcam.lifttable.table import LiftTable
from camcam.motion.law import JUMP_ATOL, Extreme, MotionLaw, PiecewiseLaw, check_T
from camcam.motion.piece import TrigPoly
from camcam.motion.program import MotionProgram, Segment

__all__ = ["ChordBSplineLaw", "law_from_interpolant", "table_law", "table_program"]


@dataclass(frozen=True, eq=False, kw_only=True)
class ChordBSplineLaw(MotionLaw):
    """S(T) = (y(a + T·span) − offset) / scale for a :class:`ChordBSpline` y(x)."""

    name: str
    spline: ChordBSpline
    a: float
    span: float
    offset: float = 0.0
    scale: float = 1.0
    rest_to_rest: bool = False

    def evaluate(self, T, order: int = 0) -> np.ndarray:
        if not 0 <= order <= 4:
            raise ValueError(f"order must be 0..4, got {order!r}")
        T = check_T(T)
        x = np.clip(self.a + T * self.span, self.spline.x_knots[0], self.spline.x_knots[-1])
        val = self.spline(x, order) * self.span**order
        if order == 0:
            val = val - self.offset
        return val / self.scale

    def extreme(self, order: int, rest_ends: bool | None = None) -> tuple[Extreme, Extreme]:
        rest_ends = self.rest_to_rest if rest_ends is None else rest_ends
        if not 0 <= order <= 3:
            raise ValueError(f"order must be 0..3, got {order!r}")
        k = self.span**order / self.scale
        xk = self.spline.x_knots
        cands = []
        for i in range(len(xk) - 1):
            ends = np.array([xk[i], xk[i + 1]])
            ang, val = self.spline.stationary(order, i)
            allx = np.concatenate([ends, ang])
            end_vals = self.spline.piece_value(order, i, [0.0, self.spline.lengths[i]])  # one-sided at the knots
            vals = np.concatenate([end_vals, val])
            for xa, v in zip(allx, vals):
                cands.append((float(k * v - (self.offset / self.scale if order == 0 else 0.0)), float((xa - self.a) / self.span)))
        if rest_ends:  # V or A not zero at an end: a jump from or to rest
            for lower in range(1, order):
                for T in (0.0, 1.0):
                    v = float(self.evaluate(T, lower))
                    if abs(v) > JUMP_ATOL * max(1.0, abs(v)):
                        jump = v if T == 0.0 else -v
                        if lower == order - 1:
                            cands.append((math.copysign(math.inf, jump), T))
                        else:
                            cands += [(math.inf, T), (-math.inf, T)]
        lo = min(cands, key=lambda c: (c[0], c[1]))
        hi = max(cands, key=lambda c: (c[0], -c[1]))
        return Extreme(lo[0], lo[1]), Extreme(hi[0], hi[1])


def law_from_interpolant(f, x_knots, *, name: str, normalize: bool, rest_to_rest: bool) -> MotionLaw:
    """The motion law of interpolant ``f`` over its knots ``x_knots`` (degrees).

    With ``normalize`` S = (f − f(x_0)) / (f(x_N) − f(x_0)); else S = f.
    """
    x = np.asarray(x_knots, dtype=float)
    a, span = float(x[0]), float(x[-1] - x[0])
    y0, yN = float(f(x[0])), float(f(x[-1]))
    offset, scale = 0.0, 1.0
    if normalize:
        if abs(yN - y0) <= JUMP_ATOL * max(1.0, abs(y0)):
            raise InputError(f"the table rises by {yN - y0:g} from {x[0]:g}° to {x[-1]:g}°; a rise law needs a non-zero rise")
        offset, scale = y0, yN - y0
    if isinstance(f, ChordBSpline):
        return ChordBSplineLaw(name=name, spline=f, a=a, span=span, offset=offset, scale=scale,
                               rest_to_rest=rest_to_rest)
    if not isinstance(f, CubicSpline):
        raise TypeError(f"cannot make a law of {type(f).__name__}")
    breaks = (f.x - a) / span
    breaks[0], breaks[-1] = 0.0, 1.0
    pieces = []
    for i in range(len(f.x) - 1):
        c3, c2, c1, c0 = f.c[:, i]
        poly = (c0 - offset, c1 * span, c2 * span**2, c3 * span**3)
        pieces.append(TrigPoly(tuple(c / scale for c in poly)))
    return PiecewiseLaw(name, tuple(float(b) for b in breaks), tuple(pieces), rest_to_rest)


def table_law(table: LiftTable, fit: str, end_slopes: tuple[float, float] = (0.0, 0.0)) -> MotionLaw:
    """The law of a table: the lift itself for a full revolution, a normalised rise otherwise.

    Examples
    --------
    >>> import numpy as np
    >>> from camcam.lifttable.table import LiftTable
    >>> ang = np.arange(0.0, 361.0, 5.0); h = 2.0 - 2.0 * np.cos(np.radians(ang))
    >>> law = table_law(LiftTable(tuple(ang), tuple(h)), "periodic")
    >>> round(float(law.evaluate(0.5)), 6), law.rest_to_rest
    (4.0, False)
    """
    f = interpolate(table.x, table.y, fit, end_slopes)
    if table.full_revolution:
        return law_from_interpolant(f, table.x, name=f"lift-table:{fit}", normalize=False, rest_to_rest=False)
    return law_from_interpolant(f, table.x, name=f"lift-table:{fit}", normalize=True, rest_to_rest=True)


def table_program(law: MotionLaw, rpm: float, unit: str = "mm") -> MotionProgram:
    """The motion program of a full-revolution table law: one segment 0–360°, scale 1, base 0."""
    return MotionProgram((Segment(law, 0.0, 360.0, 1.0, base=0.0),), rpm, unit)
