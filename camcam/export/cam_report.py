"""The cam figures of ``<name>-report.json``."""

from __future__ import annotations

import math

from camcam.geometry.build import BuiltCam

__all__ = ["cam_report", "mesh_figures"]


def _curv(c):
    if c is None:
        return None
    return {
        "min_radius_mm": c.min_radius_mm,  # inf ("inf" in JSON): a straight curve
        "min_radius_at_deg": c.at_deg,
        "concave_ranges_deg": [list(r) for r in c.concave_deg],
        "min_concave_radius_mm": c.min_concave_radius.value if c.min_concave_radius else None,
    }


def mesh_figures(built: BuiltCam) -> dict:
    """The watertight check, volume and triangle count of the cam's mesh (numpy: ``built.closed_mesh``, which
    raises :class:`~camcam.errors.GeometryError` for a mesh that closes no solid, so "watertight" is true)."""
    mesh = built.closed_mesh
    return {"watertight": True, "volume_mm3": mesh.volume_mm3(), "triangles": int(len(mesh.faces))}


def cam_report(built: BuiltCam, mesh: bool = True) -> dict:
    """Pressure angle, curvature and sizes, with the program cam angles (deg) where they occur.

    ``mesh=False`` leaves ``"mesh"`` None, for a caller that fills in :func:`mesh_figures` later
    (`camcam run` makes the mesh in the child process that writes the STL).
    """
    cam, an, spec = built.cam, built.analysis, built.spec
    out = {
        "cam_kind": spec.kind,
        "follower_kind": cam.kind,
        "base_radius_mm": cam.base_radius,
        "roller_radius_mm": cam.roller_radius,
        "rotation": cam.rotation,
        "max_pressure_angle_deg": an.max_pressure_angle_deg.value,
        "max_pressure_angle_at_deg": an.max_pressure_angle_deg.angle_deg,
        "min_curvature_radius_mm": an.profile.min_radius_mm,  # inf ("inf" in JSON): straight flanks, no curvature
        "min_curvature_radius_at_deg": an.profile.at_deg,  # None there: no place to name
        "profile_curvature": _curv(an.profile),
        "pitch_curvature": _curv(an.pitch),
        "mesh": mesh_figures(built) if mesh else None,
    }
    if an.face is not None:
        out["face"] = {"min_mm": an.face.min_mm.value, "min_at_deg": an.face.min_mm.angle_deg,
                       "max_mm": an.face.max_mm.value, "max_at_deg": an.face.max_mm.angle_deg, "width_mm": an.face.width_mm}
    if spec.kind == "cylindrical":
        out["pressure_angle_radius_mm"] = cam.bottom_radius
        out["curvature_note"] = "developed flanks at the groove bottom"
    # a figure that cannot be computed is None; an infinite radius of curvature is a true figure and stays
    return {k: (None if isinstance(v, float) and not math.isfinite(v) and k != "min_curvature_radius_mm" else v)
            for k, v in out.items()}
