"""The motion program as a CSV table (one row per cam-angle step), its summary of extremes, and the
SVAJ plot beside it."""

from __future__ import annotations

import io
import math

import numpy as np

from camcam.motion.program import MotionProgram

__all__ = ["sample_angles_deg", "motion_csv", "dynamics_columns", "motion_summary", "motion_outputs", "SVAJ_PLOT", "svaj_title"]


def sample_angles_deg(step_deg: float) -> np.ndarray:
    """0, step, 2·step, … up to and including 360 (when step divides 360)."""
    n = int(math.floor(360.0 / step_deg + 1e-9))
    angles = np.arange(n + 1) * step_deg
    if angles[-1] < 360.0 - 1e-9:
        angles = np.append(angles, 360.0)
    return angles


def motion_csv(program: MotionProgram, step_deg: float = 0.5, dynamics=None) -> str:
    """CSV text: ``cam_angle_deg`` and the displacement and its time derivatives.

    The column names carry the units (see :data:`camcam.motion.program.PHYSICAL_UNITS`).
    At a join with a jump the row shows the value of the segment that starts there.  With ``dynamics`` (a
    :class:`~camcam.dynamics.cycle.Dynamics` on the same angles) the forces, torque and contact stress follow:
    :func:`dynamics_columns`.
    """
    angles = sample_angles_deg(step_deg)
    theta = np.radians(angles)
    cols = [program.physical(theta, k) for k in range(4)]
    unit = program.units
    names = ["lift", "velocity", "acceleration", "jerk"]
    header = ["cam_angle_deg"] + [f"{n}_{u.replace('/', '_per_').replace('²', '2').replace('³', '3')}" for n, u in zip(names, unit)]
    if dynamics is not None:
        more = dynamics_columns(dynamics, angles)
        header += list(more)
        cols += list(more.values())
    buf = io.StringIO()
    buf.write(",".join(header) + "\n")
    for row in zip(angles, *cols):
        buf.write(",".join(f"{v:.10g}" for v in row) + "\n")
    return buf.getvalue()


def dynamics_columns(dynamics, angles_deg: np.ndarray) -> dict[str, np.ndarray]:
    """The motion table's dynamics columns at ``angles_deg`` (the dynamics' own angles): the follower force
    (N along a translating follower, N·m about an oscillating one's pivot), the contact force (a grooved cam's on
    each flank), the camshaft torque and the Hertz contact stress."""
    if len(angles_deg) != len(dynamics.cam_angle_deg) or not np.allclose(angles_deg, dynamics.cam_angle_deg, rtol=0,
                                                                         atol=1e-9):
        raise ValueError("the motion table and the dynamics must share their cam angles")
    follower = "follower_moment_nm" if dynamics.follower_force_unit == "N·m" else "follower_force_n"
    out = {follower: dynamics.follower_force}
    if dynamics.positive_drive:
        out["lift_flank_force_n"] = dynamics.lift_flank_force_n
        out["return_flank_force_n"] = dynamics.return_flank_force_n
    else:
        out["contact_force_n"] = dynamics.contact_force_n
    out["camshaft_torque_nm"] = dynamics.torque_nm
    out["contact_stress_mpa"] = dynamics.contact_stress_mpa
    return out


def motion_summary(program: MotionProgram) -> dict:
    """Extremes of s, v, a, j with the cam angles where they occur (rounding noise printed as 0:
    :func:`camcam.export.figures.clean`), and the joins."""
    from camcam.export.figures import clean

    names = ["lift", "velocity", "acceleration", "jerk"]
    out = {"rpm": program.rpm, "units": dict(zip(names, program.units)), "extremes": {}}
    for k, n in enumerate(names):
        lo, hi = program.extremes(k)
        scale = max(abs(lo.value), abs(hi.value))  # a lift of -3.55e-15 mm beside a 20 mm rise is 0 (issue 43)
        out["extremes"][n] = {"min": clean(lo.value, scale), "min_at_deg": lo.angle_deg, "max": clean(hi.value, scale),
                              "max_at_deg": hi.angle_deg}
    out["joins"] = [
        {"angle_deg": j.angle_deg, "quantity": {1: "velocity", 2: "acceleration"}[j.order], "jump": j.jump, "unit": j.unit}
        for j in program.joins
    ]
    return out


def motion_outputs(out, name: str, program: MotionProgram, step_deg: float, svaj=None, dynamics=None):
    """Add the motion table and the SVAJ plot to ``out``; returns the plot (the report shows it too),
    a :class:`~camcam.workers.Pending` while it is drawn in a child process.

    ``svaj`` is the plot when a caller already has it being drawn (`camcam run`'s plot server);
    otherwise it is drawn in a forked child that imports matplotlib itself.  ``dynamics``: the table gains its
    columns (:func:`motion_csv`).
    """
    from camcam.workers import call_target, later

    out.add(f"{name}-motion.csv", motion_csv(program, step_deg, dynamics))
    if svaj is None:
        svaj = later(call_target, SVAJ_PLOT, program, title=svaj_title(name, program))
    out.add(f"{name}-svaj.png", svaj)
    return svaj


#: The SVAJ plot's function (imported where it is drawn: matplotlib is loaded only there).
SVAJ_PLOT = "camcam.plots.svaj:svaj_png"


def svaj_title(name: str, program: MotionProgram) -> str:
    return f"{name}: motion at {program.rpm:g} rpm"
