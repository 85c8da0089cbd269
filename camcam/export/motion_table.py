"""The motion program as a CSV table (one row per cam-angle step)."""

from __future__ import annotations

import io
import math

import numpy as np

from camcam.motion.program import MotionProgram

__all__ = ["sample_angles_deg", "motion_csv"]


def sample_angles_deg(step_deg: float) -> np.ndarray:
    """0, step, 2·step, … up to and including 360 (when step divides 360)."""
    n = int(math.floor(360.0 / step_deg + 1e-9))
    angles = np.arange(n + 1) * step_deg
    if angles[-1] < 360.0 - 1e-9:
        angles = np.append(angles, 360.0)
    return angles


def motion_csv(program: MotionProgram, step_deg: float = 0.5) -> str:
    """CSV text: ``cam_angle_deg`` and the displacement and its time derivatives.

    The column names carry the units (see :data:`camcam.motion.program.PHYSICAL_UNITS`).
    At a join with a jump the row shows the value of the segment that starts there.
    """
    angles = sample_angles_deg(step_deg)
    theta = np.radians(angles)
    cols = [program.physical(theta, k) for k in range(4)]
    unit = program.units
    names = ["lift", "velocity", "acceleration", "jerk"]
    header = ["cam_angle_deg"] + [f"{n}_{u.replace('/', '_per_').replace('²', '2').replace('³', '3')}" for n, u in zip(names, unit)]
    buf = io.StringIO()
    buf.write(",".join(header) + "\n")
    for row in zip(angles, *cols):
        buf.write(",".join(f"{v:.10g}" for v in row) + "\n")
    return buf.getvalue()
