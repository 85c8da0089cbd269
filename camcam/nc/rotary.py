"""Cylindrical cams on a 4-axis machine: ``G1 X A`` moves, inverse-time feeds.

The tool is a radial end mill (axis through the cam axis, like the roller of
:mod:`camcam.geometry.cylindrical`); X runs along the cam axis and A is the
program cam angle in degrees.  Everything is worked in the developed plane
(u, x) at the groove's reference radius ρ_ref (u = arc length there): the
contours are fitted there with lines (``G1 X A`` cannot carry arcs) and the
chordal error is measured there, on the printed X and A.

* Tool as wide as the groove (diameter = 2 · roller radius): one centre pass
  along the developed groove centre line.
* Narrower tool: a centre pass, then each flank at the developed flank offset
  by the tool radius into the groove (the developed plane's circle model of
  the tool's cross-section).

The tool cuts the same (X, A) path at every depth, but the exact surface does
not scale with the radius: the developed flank at radius ρ is steeper at the
bottom than at the top, so the offset a flank needs changes with depth.
``error_top_mm`` / ``error_bottom_mm`` of each contour measure that: the
two-sided deviation at the groove top (ρ = base radius) and bottom between
the printed path developed at ρ and the exact tool-centre curve there (the
centre line, or the flank offset by the tool radius).  For a translating
roller and a tool of its size both are the fit's chordal error; an
oscillating roller's axis tilts with the arm, which a radial tool cannot
follow.
"""

from __future__ import annotations


import numpy as np

from camcam.errors import GeometryError, InputError
from camcam.geometry.build import BuiltCam
from camcam.nc.result import MachiningResult, deviation_checks
from camcam.nc.tools import groove_passes, job_title
from camcam.nc.settings import MachiningSpec
from camcam.toolpath.budget import DEFAULT_BUDGET
from camcam.toolpath.contours import CutContour, OffsetCurve, fit_printed
from camcam.toolpath.deviation import measure_deviation
from camcam.toolpath.elements import Line
from camcam.toolpath.path import join_toolpaths, rotary_toolpath
from camcam.toolpath.quantizer import Quantizer

__all__ = ["machine_cylindrical", "developed_printed", "printed_axes"]


def printed_axes(elements, quantizer: Quantizer, radius_mm: float) -> np.ndarray:
    """(X, A°) of the contour's vertices as printed: x and u/ρ in degrees on the post's grid."""
    pts = np.array([elements[0].start] + [e.end for e in elements])
    x = quantizer.snap(pts[:, 1])
    a = quantizer.snap(np.degrees(pts[:, 0] / radius_mm))
    return np.stack([x, a], axis=-1)


def developed_printed(axes: np.ndarray, radius_mm: float) -> tuple:
    """The printed (X, A°) polyline developed at ``radius_mm``: lines in (u, x)."""
    uv = np.stack([np.radians(axes[:, 1]) * radius_mm, axes[:, 0]], axis=-1)
    return tuple(Line(tuple(map(float, p)), tuple(map(float, q))) for p, q in zip(uv[:-1], uv[1:]) if tuple(p) != tuple(q))


def _plan(cam, r_t: float):
    """[(label, exact curve at radius ρ as a function of ρ, offset, pass kind)]."""
    centre = ("groove centre", cam.developed_centre, cam.roller_radius, "slot")
    if groove_passes(r_t, cam.roller_radius) == "centre":
        return [centre]
    # flank 0 is the −X wall: the groove lies to its left in (u, x) (u grows with the cam angle)
    return [("groove centre (rough)", cam.developed_centre, cam.roller_radius, "slot"),
            ("flank 0 (-X wall)", lambda r: OffsetCurve(cam.developed_flank(0, r), r_t), r_t, "finish"),
            ("flank 1 (+X wall)", lambda r: OffsetCurve(cam.developed_flank(1, r), -r_t), r_t, "finish")]


def machine_cylindrical(built: BuiltCam, m: MachiningSpec, name: str) -> MachiningResult:
    """The 4-axis program of a cylindrical cam (see the module notes)."""
    cam, post = built.cam, m.post
    if not post.inverse_time:
        raise GeometryError(f"post {post.name}: has no inverse-time feed (G93) for a cylindrical cam's 4-axis program")
    rho = cam.reference_radius
    r_t = m.tool_diameter_mm / 2
    title = job_title(name, built.spec.kind, cam.kind, m.tool_diameter_mm, "lines", m.tolerance_mm, post.name)
    cs = m.cut_settings()
    contours, paths = [], []
    for k, (label, at, offset, kind) in enumerate(_plan(cam, r_t)):
        curve = at(rho)

        def printed(elements):
            return developed_printed(printed_axes(elements, post.quantizer, rho), rho)

        fit, path, dev, segs = fit_printed(curve, m.tolerance_mm, "lines", post.quantizer, post.max_arc_sweep_deg,
                                           printed, f"{name} {label}")
        axes = printed_axes(fit.elements, post.quantizer, rho)
        errors = []
        for r in (cam.base_radius, cam.bottom_radius):
            e = measure_deviation(at(r), developed_printed(axes, r), margin_mm=DEFAULT_BUDGET.margin_mm(m.tolerance_mm))
            errors.append(e.max_deviation_mm)
        # developed (u, x) → (x, arc length at ρ_ref); A = u/ρ_ref
        pts = np.array([fit.elements[0].start] + [e.end for e in fit.elements])
        try:
            paths.append(rotary_toolpath(pts[:, ::-1], cam.base_radius, cs, title, developed_radius_mm=rho,
                                         contour=k, kind=kind))
        except InputError as err:
            raise GeometryError(f"{name} {label}: {err}") from None
        contours.append(CutContour(label, curve, fit, path, dev, offset, False, segs, "both", errors[0], errors[1]))
    toolpath = join_toolpaths(title, paths)
    program = post.write_program(toolpath, name)
    notes = (f"4-axis: X along the cam axis, A = program cam angle (deg), developed at R{rho:g} mm",)
    if m.mode == "arcs":
        notes += ("mode arcs: a 4-axis G1 X A program has lines only",)
    worst = max(max(c.error_top_mm, c.error_bottom_mm) for c in contours)
    if worst > m.tolerance_mm:
        why = ("the roller axis tilts with the arm, a radial tool cannot follow it"
               if cam.kind == "oscillating-roller" else "the flank's slope changes with depth")
        notes += (f"4-axis: the cut leaves the exact groove by up to {worst:.4f} mm at the groove top/bottom ({why})",)
    return MachiningResult(name, built.spec.kind, cam.kind, post, m.tool_diameter_mm, m.tolerance_mm, "lines",
                           tuple(contours), toolpath, program, rho, notes, deviation_checks(contours, m.tolerance_mm))
