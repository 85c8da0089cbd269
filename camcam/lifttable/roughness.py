"""Pre-fairing analysis (seed 004, 1.3.1): difference quotients as the roughness picture.

At each table point the first and second difference quotients on uneven spacing,

    h'_i  ≈ (h_{i+1} − h_{i−1}) / (α_{i+1} − α_{i−1})
    h''_i ≈ 2·[ (h_{i+1} − h_i)/(α_{i+1} − α_i) − (h_i − h_{i−1})/(α_i − α_{i−1}) ] / (α_{i+1} − α_{i−1})

stand in for the follower's velocity and acceleration (per degree, per degree²).
The second quotient is 2·f[α_{i−1}, α_i, α_{i+1}], exact for a parabola on any
spacing (the seed's printed form has a sign slip and, on even spacing, a factor
of 4; seed 002's eq. 3 gives the same quotient as here).  Its largest absolute
value is the table's *roughness*.  A full revolution wraps round 360°/0°; a
rise-only table has quotients at its interior points only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.lifttable.table import LiftTable

__all__ = ["Roughness", "neighbours", "difference_quotients"]


@dataclass(frozen=True)
class Roughness:
    """First and second difference quotients at ``angles_deg``."""

    angles_deg: np.ndarray
    first: np.ndarray
    second: np.ndarray

    @property
    def max_abs_second(self) -> float:
        """The roughness: largest |second difference quotient| (lift per degree²)."""
        return float(np.max(np.abs(self.second)))


def neighbours(x: np.ndarray, y: np.ndarray, periodic: bool):
    """(x_prev, y_prev, x, y, x_next, y_next) at the points that have both neighbours.

    For ``periodic`` tables (x spanning 360° with y[-1] == y[0]) the closing
    point is dropped and neighbours wrap round by ±360°.
    """
    if periodic:
        xu, yu = x[:-1], y[:-1]
        xp = np.concatenate([[x[-2] - 360.0], xu[:-1]])
        yp = np.concatenate([[y[-2]], yu[:-1]])
        xn = np.concatenate([xu[1:], [x[1] + 360.0]])
        yn = np.concatenate([yu[1:], [y[1]]])
        return xp, yp, xu, yu, xn, yn
    return x[:-2], y[:-2], x[1:-1], y[1:-1], x[2:], y[2:]


def difference_quotients(table: LiftTable) -> Roughness:
    """Seed 004's first and second difference quotients of ``table``.

    Examples
    --------
    >>> t = LiftTable((0.0, 1.0, 3.0, 4.0, 7.0), (0.0, 1.0, 9.0, 16.0, 49.0))  # y = x², uneven
    >>> r = difference_quotients(t)
    >>> [float(v) for v in r.second], [float(v) for v in r.first]
    ([2.0, 2.0, 2.0], [3.0, 5.0, 10.0])
    """
    xp, yp, x, y, xn, yn = neighbours(table.x, table.y, table.full_revolution)
    first = (yn - yp) / (xn - xp)
    second = 2.0 * ((yn - y) / (xn - x) - (y - yp) / (x - xp)) / (xn - xp)
    return Roughness(x, first, second)
