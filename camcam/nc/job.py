"""The machining stage: a built cam and its ``[machining]`` table → contours, tool path, program.

Disc cams: the tool-centre curve is the profile offset by the tool radius away
from the material (``offset_profile(r_t)``), cut with tangent leads on the free
side.  Face grooves: a tool as wide as the groove (diameter = 2 · roller
radius) cuts it in one centre pass along the pitch curve; a narrower one cuts
a centre pass, then each flank at ``offset_flank(i, r_t)`` (a tool below a
third of the groove width would leave a band between these passes and is
refused), all plunged inside the groove without leads.  Cylindrical cams:
:mod:`camcam.nc.rotary`.

Every contour is fitted at the spec's tolerance with the post's decimals and
arc sweep; its deviation is measured on the path the post prints.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.build import BuiltCam
from camcam.geometry.curve import left_normal
from camcam.post.gcode import Program, printed_elements, write_program
from camcam.post.post import Post
from camcam.spec.machining import MachiningSpec
from camcam.toolpath.contours import CutContour, fit_printed
from camcam.toolpath.path import Toolpath, contour_toolpath, depth_levels, slot_toolpath

__all__ = ["MachiningResult", "machine", "SAME_TOOL_MM"]

#: A tool whose diameter is within this of the groove width counts as the roller's size (mm).
SAME_TOOL_MM = 1e-6


@dataclass(frozen=True)
class MachiningResult:
    """Everything the NC step made for one cam (no files: exporters write them).

    ``pass_contours[k]`` names the contour (index into ``contours``) that feed
    pass k follows and ``pass_finish[k]`` whether the pass runs on it (False
    for roughing at a finishing allowance), in the order the program cuts them.
    """

    name: str
    cam_kind: str
    follower_kind: str
    post: Post
    tool_diameter_mm: float
    tolerance_mm: float
    mode: str
    contours: tuple[CutContour, ...]
    toolpath: Toolpath
    program: Program
    pass_contours: tuple[int, ...]
    pass_finish: tuple[bool, ...]
    reference_radius_mm: float | None = None
    notes: tuple[str, ...] = ()

    @property
    def rotary(self) -> bool:
        return self.toolpath.rotary

    @property
    def program_filename(self) -> str:
        return f"{self.name}.{self.program.extension}"

    @property
    def max_deviation_mm(self) -> float:
        """Largest two-sided deviation of a printed contour from its exact tool-centre curve."""
        return max(c.deviation.max_deviation_mm for c in self.contours)

    @property
    def line_blocks(self) -> int:
        """Line blocks on the contours (one pass each; leads and depth repeats not counted)."""
        return sum(c.fit.line_blocks for c in self.contours)

    @property
    def arc_blocks(self) -> int:
        return sum(c.fit.arc_blocks for c in self.contours)

    @property
    def lower_bound_blocks(self) -> float:
        """N_lb = ∫(|κ′|/192δ)^⅓ ds (arcs) or ∫√(|κ|/8δ) ds (lines), summed over the contours."""
        return float(sum(c.lower_bound for c in self.contours))


def _stock_side(curve, free_dir: np.ndarray) -> str:
    """The side of travel where the material is, from the free direction at t_start."""
    n = left_normal(curve, np.array([curve.t_start]))[0]
    return "right" if float(n @ free_dir) > 0 else "left"


def _printer(post: Post):
    return lambda elements: printed_elements(elements, post)


def _disc_plan(built: BuiltCam, r_t: float):
    """[(label, tool-centre curve, offset, free direction at t=0 or None for a groove pass)]."""
    cam, kind = built.cam, built.spec.kind
    away = cam.normal(np.array([0.0]))[0]  # away from the material of the profile / inner flank
    if kind == "disc":
        conc = built.analysis.profile.min_concave_radius
        if conc is not None and r_t >= conc.value:
            raise GeometryError(f"machining.tool_diameter: {2 * r_t:g} mm is too large: the profile's smallest concave "
                                f"radius is {conc.value:.3f} mm at cam angle {conc.angle_deg:.2f}°; expected a tool "
                                f"radius below it")
        return [("profile", cam.offset_profile(r_t), r_t, away)]
    r_r = cam.roller_radius
    if r_t > r_r + SAME_TOOL_MM:
        raise GeometryError(f"machining.tool_diameter: {2 * r_t:g} mm is wider than the groove ({2 * r_r:g} mm, "
                            f"twice the roller radius)")
    if abs(r_t - r_r) <= SAME_TOOL_MM:
        return [("groove centre", cam.pitch, r_r, None)]
    if 3 * r_t < r_r:
        raise GeometryError(f"machining.tool_diameter: {2 * r_t:g} mm is below a third of the groove width "
                            f"{2 * r_r:g} mm: a centre pass and two flank passes would leave material between them")
    return [("groove centre (rough)", cam.pitch, r_r, None), ("inner flank", cam.offset_flank(0, r_t), r_t, None),
            ("outer flank", cam.offset_flank(1, r_t), r_t, None)]


def _join(title: str, paths: list[Toolpath]) -> Toolpath:
    moves, comments = [], []
    for p in paths:
        moves.extend(p.moves)
        comments.extend(p.comments)
    first = paths[0]
    return Toolpath(title, tuple(moves), first.spindle_rpm, first.tool_number, first.tool_diameter_mm,
                    first.rotary, tuple(dict.fromkeys(comments)))


def _title(name: str, built: BuiltCam, m: MachiningSpec, mode: str) -> str:
    return (f"{name}: {built.spec.kind} cam, {built.cam.kind} follower, tool D{m.tool_diameter_mm:g} mm, "
            f"{mode} within {m.tolerance_mm:g} mm, post {m.post.name}")


def machine(built: BuiltCam, m: MachiningSpec, name: str) -> MachiningResult:
    """Tool-centre curves, fitted contours, tool path and program for ``built`` (no I/O).

    Raises
    ------
    GeometryError
        A tool too large for a concave part of the profile, wider than a
        groove, or too small to clear it; a post that cannot hold the program.
    """
    if built.spec.kind == "cylindrical":
        from camcam.nc.rotary import machine_cylindrical

        return machine_cylindrical(built, m, name)
    post, r_t = m.post, m.tool_diameter_mm / 2
    title = _title(name, built, m, m.mode)
    contours, paths, pass_contours, pass_finish = [], [], [], []
    n_levels = len(depth_levels(m.cut_settings()))
    for k, (label, curve, offset, free) in enumerate(_disc_plan(built, r_t)):
        fit, printed, dev, segs = fit_printed(curve, m.tolerance_mm, m.mode, post.quantizer, post.max_arc_sweep_deg,
                                              _printer(post), f"{name} {label}")
        if free is not None:
            side = _stock_side(curve, free)
            cs = m.cut_settings(side)
            paths.append(contour_toolpath(fit.elements, cs, title))
            finals = (1 if cs.finish_allowance_mm > 0 else 0) + (1 if cs.spring_pass else 0)
            pass_finish += [cs.finish_allowance_mm == 0] * n_levels + [True] * finals
            pass_contours += [k] * (n_levels + finals)
        else:
            side = "both"
            paths.append(slot_toolpath(fit.elements, m.cut_settings(), title))
            extra = 1 if m.spring_pass else 0
            pass_finish += [True] * (n_levels + extra)
            pass_contours += [k] * (n_levels + extra)
        contours.append(CutContour(label, curve, fit, printed, dev, offset, free is not None, segs, side))
    toolpath = _join(title, paths)
    try:
        program = write_program(toolpath, post, name)
    except GeometryError as err:
        raise GeometryError(f"post {post.name}: {err}") from None
    notes = ()
    if m.finish_allowance_mm > 0 and built.spec.kind != "disc":
        notes = ("finish_allowance does not apply to groove passes (the flanks have their own passes)",)
    return MachiningResult(name, built.spec.kind, built.cam.kind, post, m.tool_diameter_mm, m.tolerance_mm, m.mode,
                           tuple(contours), toolpath, program, tuple(pass_contours), tuple(pass_finish), None, notes)
