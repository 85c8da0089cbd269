"""The machining job: a built cam and its ``[machining]`` settings → contours, passes, program.

Disc cams: the tool-centre curve is the profile offset by the tool radius away
from the material (``offset_profile(r_t)``), cut with tangent leads on the free
side.  Face grooves: a tool as wide as the groove (diameter = 2 · roller
radius) cuts it in one centre pass along the pitch curve; a narrower one cuts
a centre pass, then each flank at ``offset_flank(i, r_t)`` (:mod:`camcam.nc.tools`),
all plunged inside the groove without leads.  Cylindrical cams:
:mod:`camcam.nc.rotary`.

Every contour is fitted at the spec's tolerance with the post's printed
rounding (:attr:`Post.quantizer`) and arc sweep; its deviation is measured on
the path the post prints.
"""

from __future__ import annotations

import numpy as np

from camcam.geometry.build import BuiltCam
from camcam.geometry.curve import left_normal
from camcam.nc.result import MachiningResult, deviation_checks
from camcam.nc.tools import check_profile_tool, groove_passes, job_title
from camcam.nc.settings import MachiningSpec
from camcam.toolpath.contours import CutContour, fit_printed
from camcam.toolpath.path import contour_toolpath, join_toolpaths, slot_toolpath

__all__ = ["machine"]


def _stock_side(curve, free_dir: np.ndarray) -> str:
    """The side of travel where the material is, from the free direction at t_start."""
    n = left_normal(curve, np.array([curve.t_start]))[0]
    return "right" if float(n @ free_dir) > 0 else "left"


def _disc_plan(built: BuiltCam, r_t: float):
    """[(label, tool-centre curve, offset, free direction at t=0 or None for a groove pass, pass kind)]."""
    cam, kind = built.cam, built.spec.kind
    away = cam.normal(np.array([0.0]))[0]  # away from the material of the profile / inner flank
    if kind == "disc":
        check_profile_tool(r_t, built.analysis.profile.min_concave_radius)
        return [("profile", cam.offset_profile(r_t), r_t, away, "finish")]
    r_r = cam.roller_radius
    if groove_passes(r_t, r_r) == "centre":
        return [("groove centre", cam.pitch, r_r, None, "slot")]
    return [("groove centre (rough)", cam.pitch, r_r, None, "slot"),
            ("inner flank", cam.offset_flank(0, r_t), r_t, None, "finish"),
            ("outer flank", cam.offset_flank(1, r_t), r_t, None, "finish")]


def machine(built: BuiltCam, m: MachiningSpec, name: str) -> MachiningResult:
    """Tool-centre curves, fitted contours, passes and program for ``built`` (no I/O).

    Parameters
    ----------
    built : BuiltCam
        The cam from :func:`camcam.geometry.build.build_cam`.
    m : MachiningSpec
        The validated ``[machining]`` table.
    name : str
        The job name (program title and file names).

    Returns
    -------
    MachiningResult

    Raises
    ------
    GeometryError
        A tool too large for a concave part of the profile, wider than a
        groove, or too small to clear it.
    FitError, PostError
        Faults of the fitter or the writer on valid input.
    """
    if built.spec.kind == "cylindrical":
        from camcam.nc.rotary import machine_cylindrical

        return machine_cylindrical(built, m, name)
    post, r_t = m.post, m.tool_diameter_mm / 2
    title = job_title(name, built.spec.kind, built.cam.kind, m.tool_diameter_mm, m.mode, m.tolerance_mm, post.name)
    contours, paths = [], []
    for k, (label, curve, offset, free, kind) in enumerate(_disc_plan(built, r_t)):
        fit, printed, dev, segs = fit_printed(curve, m.tolerance_mm, m.mode, post.quantizer, post.max_arc_sweep_deg,
                                              post.quantizer.printed_elements, f"{name} {label}")
        if free is not None:
            side = _stock_side(curve, free)
            paths.append(contour_toolpath(fit.elements, m.cut_settings(side), title, contour=k))
        else:
            side = "both"
            paths.append(slot_toolpath(fit.elements, m.cut_settings(), title, contour=k, kind=kind))
        contours.append(CutContour(label, curve, fit, printed, dev, offset, free is not None, segs, side))
    toolpath = join_toolpaths(title, paths)
    program = post.write_program(toolpath, name)
    notes = ()
    if m.finish_allowance_mm > 0 and built.spec.kind != "disc":
        notes = ("finish_allowance does not apply to groove passes (the flanks have their own passes)",)
    return MachiningResult(name, built.spec.kind, built.cam.kind, post, m.tool_diameter_mm, m.tolerance_mm, m.mode,
                           tuple(contours), toolpath, program, None, notes, deviation_checks(contours, m.tolerance_mm))
