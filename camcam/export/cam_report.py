"""The cam figures of ``<name>-report.json``."""

from __future__ import annotations

import math

from camcam.geometry.build import BuiltCam

__all__ = ["cam_report"]


def _curv(c):
    if c is None:
        return None
    return {
        "min_radius_mm": c.min_radius_mm,
        "min_radius_at_deg": c.angle_deg,
        "concave_ranges_deg": [list(r) for r in c.concave_deg],
        "min_concave_radius_mm": c.min_concave_radius.value if c.min_concave_radius else None,
    }


def cam_report(built: BuiltCam) -> dict:
    """Pressure angle, curvature and sizes, with the program cam angles (deg) where they occur."""
    cam, an, spec = built.cam, built.analysis, built.spec
    out = {
        "cam_kind": spec.kind,
        "follower_kind": cam.kind,
        "base_radius_mm": cam.base_radius,
        "roller_radius_mm": cam.roller_radius,
        "rotation": cam.rotation,
        "max_pressure_angle_deg": an.max_pressure_angle_deg.value,
        "max_pressure_angle_at_deg": an.max_pressure_angle_deg.angle_deg,
        "min_curvature_radius_mm": an.profile.min_radius_mm,
        "min_curvature_radius_at_deg": an.profile.angle_deg,
        "profile_curvature": _curv(an.profile),
        "pitch_curvature": _curv(an.pitch),
        "mesh": {"watertight": bool(built.mesh.is_watertight), "volume_mm3": float(built.mesh.volume),
                 "triangles": int(len(built.mesh.faces))},
    }
    if an.face is not None:
        out["face"] = {"min_mm": an.face.min_mm.value, "min_at_deg": an.face.min_mm.angle_deg,
                       "max_mm": an.face.max_mm.value, "max_at_deg": an.face.max_mm.angle_deg, "width_mm": an.face.width_mm}
    if spec.kind == "cylindrical":
        out["pressure_angle_radius_mm"] = cam.bottom_radius
        out["curvature_note"] = "developed flanks at the groove bottom"
    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in out.items()}
