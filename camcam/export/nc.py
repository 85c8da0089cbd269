"""The NC step's files: the program, the DXF drawing and the report figures of a :class:`MachiningResult`."""

from __future__ import annotations

import math

import numpy as np

from camcam.export.dxf import Circle, ExactCurve, Polyline, Text, contour_dxf
from camcam.geometry.build import BuiltCam
from camcam.nc.result import MachiningResult

__all__ = ["nc_files", "nc_dxf"]


def _title_lines(built: BuiltCam, r: MachiningResult) -> list[str]:
    cam = built.cam
    roller = f", roller R{cam.roller_radius:g} mm" if getattr(cam, "roller_radius", 0) else ""
    return [f"{r.name}: {built.spec.kind} cam, base radius {cam.base_radius:g} mm, rotation {cam.rotation}",
            f"follower {cam.kind}{roller}",
            f"tool D{r.tool_diameter_mm:g} mm, post {r.post.name} ({r.program_filename}), {r.mode}",
            _measured_line(r)]


def _measured_line(r: MachiningResult) -> str:
    if r.groove is None:
        return f"tolerance {r.tolerance_mm:g} mm two-sided; measured {r.max_deviation_mm:.4f} mm on the printed program"
    g = r.groove
    verdict = "within" if g.max_deviation_mm <= r.tolerance_mm else "OUT OF TOLERANCE"
    return (f"tolerance {r.tolerance_mm:g} mm; 3-D groove deviation {g.max_deviation_mm:.4f} mm ({verdict}), "
            f"both walls, r = {g.radii_mm[0]:g}-{g.radii_mm[-1]:g} mm, whole revolution, on the printed program")


def _disc_extras(built: BuiltCam, r: MachiningResult) -> dict:
    cam, spec = built.cam, built.spec
    extras: dict = {"PROFILE": [ExactCurve(cam.profile)]}
    if spec.kind == "disc-groove":
        extras["PROFILE"].append(ExactCurve(cam.flanks[1]))
    extras["TOOLPATH-EXACT"] = [ExactCurve(c.curve) for c in r.contours]
    extras["BASE-CIRCLE"] = [Circle((0.0, 0.0), cam.base_radius)]
    if spec.bore > 0:
        extras["BORE"] = [Circle((0.0, 0.0), spec.bore / 2)]
    angles = np.radians([0.0, 90.0, 180.0, 270.0])
    if cam.pitch is not None:
        extras["PITCH"] = [Polyline(tuple(map(tuple, cam.pitch.polyline(180))), True)]
        extras["ROLLER"] = [Circle(tuple(map(float, p)), cam.roller_radius) for p in cam.pitch.evaluate(angles)]
    p0 = cam.profile.evaluate([0.0])[0]
    reach = float(np.hypot(*p0)) + 10.0
    u = p0 / np.hypot(*p0)
    extras["ANGLE-ZERO"] = [Polyline(((0.0, 0.0), tuple(map(float, u * reach)))),
                            Text("0°", tuple(map(float, u * (reach + 2.0))), 3.0)]
    return extras


def _cyl_extras(built: BuiltCam, r: MachiningResult) -> dict:
    cam = built.cam
    rho = r.reference_radius_mm
    width = 2 * math.pi * rho
    extras: dict = {"PROFILE": [ExactCurve(cam.developed_flank(0, rho)), ExactCurve(cam.developed_flank(1, rho))],
                    "PITCH": [ExactCurve(cam.developed_centre(rho))],
                    "BLANK": [Polyline(((0.0, 0.0), (width, 0.0), (width, cam.length), (0.0, cam.length)), True)],
                    "ANGLE-ZERO": [Polyline(((0.0, -5.0), (0.0, cam.length + 5.0))),
                                   Text("A0 (cam angle 0)", (1.0, cam.length + 2.0), 3.0)]}
    ts = np.radians([0.0, 90.0, 180.0, 270.0])
    extras["ROLLER"] = [Circle(tuple(map(float, p)), cam.roller_radius) for p in cam.developed_centre(rho).evaluate(ts)]
    extras["NOTE"] = [Text(f"developed at radius {rho:g} mm: u = arc length (horizontal), x = cam axis (vertical)",
                           (0.0, -14.0), 2.5)]
    return extras


def nc_dxf(built: BuiltCam, r: MachiningResult):
    """The drawing: machined contours (``CONTOUR``), exact profile/flanks and tool-centre curves as SPLINEs, …"""
    machined = [e for c in r.contours for e in c.printed]
    extras = _cyl_extras(built, r) if r.rotary else _disc_extras(built, r)
    lines = _title_lines(built, r)
    low = -12.0 if not r.rotary else -20.0
    if not r.rotary:
        low = -float(np.abs(r.contours[-1].curve.evaluate(np.linspace(0, 2 * np.pi, 721))).max()) - 15.0
    extras["TITLE-BLOCK"] = [Text(t, (0.0, low - 5.0 * i), 3.0) for i, t in enumerate(lines)]
    return contour_dxf(machined, None, extras)


def nc_files(built: BuiltCam, r: MachiningResult) -> dict[str, bytes]:
    """``{<name>.<ext>: program, <name>.dxf: drawing}``."""
    return {r.program_filename: r.program.text.encode("utf-8"), f"{r.name}.dxf": nc_dxf(built, r).data}
