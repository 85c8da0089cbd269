"""The NC step's files: the program, the DXF drawing and the report figures of a :class:`MachiningResult`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.export.dxf import Circle, ExactCurve, Polyline, Text, contour_dxf
from camcam.geometry.build import BuiltCam
from camcam.geometry.curve import left_normal
from camcam.geometry.mesh import keyway_corners
from camcam.nc.bore import bore_curve
from camcam.nc.result import MachiningResult
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.deviation import measure_deviation
from camcam.toolpath.elements import circular
from camcam.toolpath.outline import part_outline

__all__ = ["nc_files", "nc_dxf", "PartOutline", "part_of"]


@dataclass(frozen=True)
class PartOutline:
    """The finished surfaces as the program cuts them: lines and arcs, and their deviation from the design.

    ``outlines`` are the fitted tool-centre paths of the finishing contours
    offset by the tool radius to the material (:func:`~camcam.toolpath.outline.part_outline`), their
    spiral arcs as the DXF draws them (:func:`~camcam.toolpath.elements.circular`);
    ``deviation_mm`` the largest two-sided deviation of one from its exact
    surface (the profile, or a groove's flank); ``None`` for a cylindrical cam,
    whose developed drawing has no planar offset.
    """

    outlines: tuple[tuple, ...]
    deviation_mm: float | None


#: Parameters at which a contour's exact curve is compared with a surface (:func:`_finished_side`).
_PROBES = 64


def _finished_side(contour_curve, surface, r_t: float) -> float | None:
    """The side (+ left, − right of travel, times ``r_t``) on which the exact tool-centre curve finishes
    ``surface``, or None if it finishes none of it.

    The curves of one cam share their parameter (the cam angle; a bore circle its polar angle): a tool-centre
    curve is an offset of the design it follows, point for point.  So a contour finishes ``surface`` on side d
    iff S(t) = C(t) + d·n(t) at every t, n the contour's left normal: the offset of that side is the wall the
    tool leaves.  Any other offset is not a surface of the part (a groove's flank pass has air on its other
    side, 2(r_roller − r_tool) short of the far wall; a rough pass finishes neither), and a comparison with
    it would set unlike against unlike.  The equality is exact up to rounding; 1e-9 of the largest radius is
    the allowance for that.
    """
    t0, t1 = float(contour_curve.t_start), float(contour_curve.t_end)
    if (t0, t1) != (float(surface.t_start), float(surface.t_end)):
        return None
    t = np.linspace(t0, t1, _PROBES, endpoint=False)
    c, s = contour_curve.evaluate(t), surface.evaluate(t)
    n = left_normal(contour_curve, t)
    scale = 1e-9 * max(1.0, float(np.abs(c).max()), float(np.abs(s).max()))
    for d in (r_t, -r_t):
        if float(np.hypot(*(c + d * n - s).T).max()) <= scale:
            return d
    return None


def _surfaces(built: BuiltCam, r: MachiningResult) -> list:
    """The exact surfaces a disc or face-groove program finishes: the profile or both flanks, and a machined
    bore's circle."""
    cam = built.cam
    out = list(cam.flanks) if built.spec.kind == "disc-groove" else [cam.profile]
    if r.blank is not None and r.blank.bore_machined:
        out.append(bore_curve(r.blank.bore_mm / 2))
    return out


def part_of(built: BuiltCam, r: MachiningResult, budget: FitBudget = DEFAULT_BUDGET) -> PartOutline:
    """The part outline of a disc or face-groove cam's finishing contours (see :class:`PartOutline`).

    Each contour is offset by the tool radius only to the side where it finishes a surface of the design
    (:func:`_finished_side`), and that outline is measured against that surface: a face groove's walls are
    its two flanks, each from the pass that cuts it (or both from a centre pass as wide as the groove); with
    ``budget``'s sampling margin (:meth:`FitBudget.margin_mm <camcam.toolpath.budget.FitBudget.margin_mm>`), as
    the fit's own measurement.
    """
    if r.rotary:
        return PartOutline((), None)
    r_t = r.tool_diameter_mm / 2
    surfaces = _surfaces(built, r)
    outlines, worst = [], 0.0
    for c in r.contours:
        for surface in surfaces:
            d = _finished_side(c.curve, surface, r_t)
            if d is None:
                continue
            # measured as drawn: a spiral of the outline as the ARC through its ends the DXF holds
            out = tuple(circular(e) for e in part_outline(c.fit.elements, d))
            outlines.append(out)
            worst = max(worst, measure_deviation(surface, out,
                                                 margin_mm=budget.margin_mm(r.tolerance_mm)).max_deviation_mm)
    return PartOutline(tuple(outlines), worst)


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
        v = built.mesh_parts.vertices
        extras["OUTER-CIRCLE"] = [Circle((0.0, 0.0), float(np.hypot(v[:, 0], v[:, 1]).max()))]
    extras["TOOLPATH-EXACT"] = [ExactCurve(c.curve) for c in r.contours]
    extras["BASE-CIRCLE"] = [Circle((0.0, 0.0), cam.base_radius)]
    if spec.bore > 0:
        extras["BORE"] = [Circle((0.0, 0.0), spec.bore / 2)]
    if spec.keyway is not None:  # the part's angular datum (issue 47): the walls and bottom, as the mesh has them
        k = spec.keyway
        corners = keyway_corners(spec.bore / 2, k)
        label = corners[1:3].mean(axis=0) * (1 + 3.0 / (spec.bore / 2 + k.depth))
        extras["KEYWAY"] = [Polyline(tuple(map(tuple, corners.tolist()))),
                            Text(f"keyway {k.width:g} x {k.depth:g}", tuple(map(float, label)), 2.0)]
    if spec.dowel is not None:  # or a dowel hole through the disc, as the mesh has it
        d = spec.dowel
        c = np.array(d.centre)
        extras["DOWEL"] = [Circle(tuple(map(float, c)), d.diameter / 2),
                           Text(f"dowel D{d.diameter:g}", tuple(map(float, c + d.diameter / 2 + 1.0)), 2.0)]
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


def nc_dxf(built: BuiltCam, r: MachiningResult, part: PartOutline | None = None):
    """The drawing: the part outline as LINE/ARC (``PART``), the tool-centre path as printed (``TOOL_CENTRE``),
    the exact profile/flanks (``PROFILE``) and tool-centre curves (``TOOLPATH-EXACT``) as SPLINEs, …"""
    machined = [e for c in r.contours for e in c.printed]
    part = part_of(built, r) if part is None else part
    extras = {"PART": [e for out in part.outlines for e in out]} if part.outlines else {}
    extras.update(_cyl_extras(built, r) if r.rotary else _disc_extras(built, r))
    lines = _title_lines(built, r)
    low = -12.0 if not r.rotary else -20.0
    if not r.rotary:
        low = -float(np.abs(r.contours[-1].curve.evaluate(np.linspace(0, 2 * np.pi, 721))).max()) - 15.0
    extras["TITLE-BLOCK"] = [Text(t, (0.0, low - 5.0 * i), 3.0) for i, t in enumerate(lines)]
    if part.deviation_mm is not None:
        lines.append(f"PART: tool path offset by the tool radius, lines and arcs within {part.deviation_mm:.4f} mm "
                     f"of the design; TOOL_CENTRE: the tool centre as programmed")
        extras["TITLE-BLOCK"].append(Text(lines[-1], (0.0, low - 5.0 * (len(lines) - 1)), 3.0))
    return contour_dxf(machined, None, extras, contour_layer="TOOL_CENTRE")


def nc_files(built: BuiltCam, r: MachiningResult, part: PartOutline | None = None) -> dict[str, bytes]:
    """``{<name>.<ext>: program, <name>.dxf: drawing}``."""
    return {r.program_filename: r.program.text.encode("utf-8"), f"{r.name}.dxf": nc_dxf(built, r, part).data}
