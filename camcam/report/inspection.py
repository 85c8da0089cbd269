"""The inspection table: what a CMM or a dial indicator should find at each cam angle.

For a disc cam at program cam angle θ (cam frame, drawing at cam angle 0):
the profile contact point, its radius from the cam centre, the outward
normal direction, the roller-centre position (roller followers), the nominal
lift and the tolerance band (the profile may lie anywhere within ±tolerance
along the normal).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.export.figures import fixed
from camcam.export.motion_table import sample_angles_deg
from camcam.geometry.disc import DiscCam
from camcam.geometry.groove import GrooveCam

__all__ = ["InspectionTable", "inspection_table"]


@dataclass(frozen=True, kw_only=True)
class InspectionTable:
    """Columns, each shape (n,): angles in degrees, lengths in mm, lift in the program's unit."""

    angle_deg: np.ndarray
    profile_xy: np.ndarray  # (n, 2)
    radius_mm: np.ndarray
    normal_deg: np.ndarray
    roller_centre_xy: np.ndarray | None  # (n, 2) or None for flat faces
    lift: np.ndarray
    lift_unit: str
    tolerance_mm: float

    header = ("cam angle [deg]", "x [mm]", "y [mm]", "radius [mm]", "normal [deg]", "roller x [mm]", "roller y [mm]",
              "lift", "band [mm]")

    def rows(self) -> list[tuple[str, ...]]:
        """Formatted rows (3 decimals for positions, 4 for lift; no "-0.000": :func:`camcam.export.figures.fixed`)."""
        out = []
        for i, a in enumerate(self.angle_deg):
            rc = self.roller_centre_xy[i] if self.roller_centre_xy is not None else (np.nan, np.nan)
            out.append((
                f"{a:g}", fixed(self.profile_xy[i, 0], 3), fixed(self.profile_xy[i, 1], 3), fixed(self.radius_mm[i], 3),
                fixed(self.normal_deg[i], 2),
                "—" if np.isnan(rc[0]) else fixed(rc[0], 3), "—" if np.isnan(rc[1]) else fixed(rc[1], 3),
                f"{fixed(self.lift[i], 4)} {self.lift_unit}", f"±{self.tolerance_mm:g}",
            ))
        return out

    def csv(self) -> str:
        cols = "cam_angle_deg,x_mm,y_mm,radius_mm,normal_deg,roller_x_mm,roller_y_mm,lift,tolerance_mm\n"
        lines = [cols]
        for i, a in enumerate(self.angle_deg):
            rc = self.roller_centre_xy[i] if self.roller_centre_xy is not None else ("", "")
            vals = [a, *self.profile_xy[i], self.radius_mm[i], self.normal_deg[i], *rc, self.lift[i], self.tolerance_mm]
            lines.append(",".join(v if isinstance(v, str) else fixed(v, 6) for v in vals) + "\n")
        return "".join(lines)


def inspection_table(cam: DiscCam | GrooveCam, tolerance_mm: float, step_deg: float = 10.0) -> InspectionTable:
    """Inspection rows every ``step_deg`` of cam angle (0 … < 360).

    Examples
    --------
    >>> from camcam.geometry.disc import DiscCam
    >>> from camcam.geometry.followers import TranslatingRoller
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> from camcam.motion.standard import dwell
    >>> cam = DiscCam(TranslatingRoller(10.0), MotionProgram((Segment(dwell(), 0, 360, 0.0),), 60), 40.0)
    >>> t = inspection_table(cam, 0.01, 90.0)
    >>> [round(float(r), 9) for r in t.radius_mm]  # a base circle: radius 40 everywhere
    [40.0, 40.0, 40.0, 40.0]
    """
    angles = sample_angles_deg(step_deg)[:-1]
    theta = np.radians(angles)
    disc = cam.cam if isinstance(cam, GrooveCam) else cam
    profile = cam.profile.evaluate(theta, 0)
    normal = disc.normal(theta)
    pitch = disc.pitch.evaluate(theta, 0) if disc.pitch is not None else None
    return InspectionTable(
        angle_deg=angles,
        profile_xy=profile,
        radius_mm=np.hypot(profile[:, 0], profile[:, 1]),
        normal_deg=np.degrees(np.arctan2(normal[:, 1], normal[:, 0])),
        roller_centre_xy=pitch,
        lift=disc.program.lift(theta),
        lift_unit=disc.program.unit,
        tolerance_mm=tolerance_mm,
    )
