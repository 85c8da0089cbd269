"""The recovered motion as CSV: ``cam_angle_deg, lift, velocity, acceleration``.

Lift in mm (deg for an oscillating follower), velocity and acceleration per
degree of cam angle.  The rows run 0, 360/N, … and close at 360° with the
first row's values, so the file is a full-revolution lift table
(:func:`camcam.lifttable.table.parse_lift_table` reads its first two columns).
"""

from __future__ import annotations

import io

import numpy as np

__all__ = ["motion_csv", "HEADER"]

HEADER = "cam_angle_deg,lift,velocity,acceleration"


def motion_csv(angles_deg: np.ndarray, cols: np.ndarray) -> str:
    """CSV text of ``angles_deg`` (n,) and ``cols`` (n, 3).

    Examples
    --------
    >>> import numpy as np
    >>> print(motion_csv(np.array([0.0, 360.0]), np.array([[1.0, 0.5, 0.0], [1.0, 0.5, 0.0]])).strip())
    cam_angle_deg,lift,velocity,acceleration
    0,1,0.5,0
    360,1,0.5,0
    """
    buf = io.StringIO()
    buf.write(HEADER + "\n")
    for a, row in zip(angles_deg, cols):
        buf.write(",".join(f"{v + 0.0:.10g}" for v in np.round([a, *row], 12)) + "\n")
    return buf.getvalue()
