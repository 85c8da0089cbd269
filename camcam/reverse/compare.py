"""A recovered motion against the design: the largest lift, velocity and acceleration errors and their angles.

Used by ``camcam reverse`` and ``camcam inspect`` (the motion a measured cam produces).
"""

from __future__ import annotations

import math

import numpy as np

from camcam.reverse.design import design_motion

__all__ = ["motion_errors"]


def motion_errors(angles_deg, recovered, program, cam_kind: str) -> tuple[np.ndarray, dict]:
    """Design columns at ``angles_deg`` and the largest errors (per degree, and in time units at the design's rpm).

    ``recovered`` is (n, 3): lift, velocity per degree, acceleration per degree².
    """
    design = np.stack([design_motion(program, cam_kind, angles_deg, k) for k in range(3)], axis=-1)
    err = np.abs(recovered - design).max(axis=0)
    at = [float(angles_deg[int(np.argmax(np.abs(recovered[:, k] - design[:, k])))]) for k in range(3)]
    per_rad = [float(err[k] * (180.0 / math.pi) ** k) for k in range(3)]
    phys = [float(abs(program.to_physical(per_rad[k], k))) for k in range(3)]
    return design, {
        "max_lift_error": float(err[0]),
        "max_velocity_error": float(err[1]),
        "max_acceleration_error": float(err[2]),
        "max_error_at_deg": {"lift": at[0], "velocity": at[1], "acceleration": at[2]},
        "physical": {
            "rpm": program.rpm,
            "max_lift_error": phys[0],
            "max_velocity_error": phys[1],
            "max_acceleration_error": phys[2],
            "units": list(program.units[:3]),
        },
    }
