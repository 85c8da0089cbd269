"""The faired lift table as CSV: lift and its derivatives per degree of cam angle."""

from __future__ import annotations

import io

import numpy as np

__all__ = ["faired_angles_deg", "faired_csv"]


def faired_angles_deg(x0: float, x1: float, step_deg: float) -> np.ndarray:
    """x0, x0 + step, … and x1 itself (the last row is always the table's end)."""
    n = int(np.floor((x1 - x0) / step_deg + 1e-9))
    ang = x0 + np.arange(n + 1) * step_deg
    if ang[-1] < x1 - 1e-9:
        ang = np.append(ang, x1)
    return ang


def faired_csv(f, x0: float, x1: float, step_deg: float) -> str:
    """``angle_deg, lift_mm, velocity, acceleration, jerk`` from interpolant ``f(x, nu)``.

    velocity, acceleration, jerk are d^k lift / dα^k in mm/deg, mm/deg², mm/deg³
    (deg/deg… for an oscillating follower).

    Examples
    --------
    >>> from scipy.interpolate import CubicSpline
    >>> import numpy as np
    >>> x = np.arange(0.0, 5.0); print(faired_csv(CubicSpline(x, 2 * x), 0, 4, 2).strip())
    angle_deg,lift_mm,velocity,acceleration,jerk
    0,0,2,0,0
    2,4,2,0,0
    4,8,2,0,0
    """
    ang = faired_angles_deg(x0, x1, step_deg)
    cols = [f(ang, k) for k in range(4)]
    buf = io.StringIO()
    buf.write("angle_deg,lift_mm,velocity,acceleration,jerk\n")
    for row in zip(ang, *cols):
        buf.write(",".join(f"{v + 0.0:.10g}" for v in np.round(row, 12)) + "\n")
    return buf.getvalue()
