"""The machining job: a built cam and its ``[machining]`` settings → contours, passes, program.

Disc cams are cut from the blank of ``[stock]`` (:mod:`camcam.nc.stock`): at
every depth level a roughing spiral from the blank to the finish allowance
(:mod:`camcam.nc.roughing`), then the finish contour, the profile offset by
the tool radius away from the material (``offset_profile(r_t)``), cut with
tangent leads on the free side, then the optional spring pass.  Face
grooves: a tool as wide as the groove (diameter = 2 · roller radius) cuts it
in one centre pass along the pitch curve (a stated slot); a narrower one
cuts a centre pass, rough offsets whose every band the tool meets is within
the stepover (:func:`camcam.nc.roughing.groove_rings`), then each flank at
``offset_flank(i, r_t)`` (:mod:`camcam.nc.tools`); every groove pass
is ramped down along its contour at no more than the ramp angle.  With
``[machining] bore = true`` the bore is cut as a helical bore
(:mod:`camcam.nc.bore`).  Cylindrical cams: :mod:`camcam.nc.rotary` (4 axes) and, for an
oscillating roller, :mod:`camcam.nc.fiveaxis` (5 axes, ``[machining] axes``).

The printed program is read back and checked against the blank, 2.5-D, by
:mod:`camcam.verify` (:mod:`camcam.verify.removal`); its figures are checks of the job.

Every contour is fitted at the spec's tolerance with the post's printed
rounding (:attr:`Post.quantizer`) and arc sweep; its deviation is measured on
the path the post prints.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from camcam.workers import ChildGroup, ProcessMap, resolve
from camcam.geometry.build import BuiltCam
from camcam.geometry.curve import left_normal
from camcam.nc.direction import direction_of, orient
from camcam.nc.bore import bore_circle_radius, bore_curve, bore_passes, dowel_curve, dowel_passes
from camcam.nc.feeds import with_cutting_data
from camcam.nc.passes import finish_moves, ramp_loop_passes, spiral_moves, with_markers
from camcam.nc.result import MachiningResult, deviation_checks
from camcam.nc.roughing import RING_STEP_FRACTION, Spiral, disc_spiral, groove_rings
from camcam.nc.settings import DEFAULT_STOCK, MachiningSpec, StockSpec
from camcam.nc.stock import blank_for
from camcam.nc.tools import check_profile_tool, groove_passes, job_title
from camcam.toolpath.arcsweep import passes_within_sweep
from camcam.toolpath.contours import CutContour, fit_printed
from camcam.toolpath.path import Pass, Rapid, Toolpath, depth_levels

__all__ = ["machine_program"]

#: The contour label of the dowel hole's circle (``[machining] dowel = true``).
DOWEL_LABEL = "dowel hole"


def _stock_side(curve, free_dir: np.ndarray) -> str:
    """The side of travel where the material is, from the free direction at t_start."""
    n = left_normal(curve, np.array([curve.t_start]))[0]
    return "right" if float(n @ free_dir) > 0 else "left"


def _disc_plan(built: BuiltCam, r_t: float, stepover_mm: float):
    """[(label, tool-centre curve, offset, free direction at t=0 or None for a groove pass, pass kind, note,
    the groove wall a groove pass cuts toward: 0 inner, 1 outer, None both or a profile)]."""
    cam, kind = built.cam, built.spec.kind
    away = cam.normal(np.array([0.0]))[0]  # away from the material of the profile / inner flank
    if kind == "disc":
        check_profile_tool(r_t, built.analysis.profile.min_concave_radius)
        return [("profile", cam.offset_profile(r_t), r_t, away, "finish", "", None)]
    r_r = cam.roller_radius
    if groove_passes(r_t, r_r) == "centre":
        return [("groove centre", cam.pitch, r_r, None, "slot", "", None)]
    step = RING_STEP_FRACTION * stepover_mm
    span = r_r - r_t  # from the centre line to a flank pass
    rough = []
    for i, side in ((0, "inner"), (1, "outer")):
        # rough offsets between the centre pass and the flank pass, each band within the step as the tool meets
        # it, round the bends away from the material too (camcam.nc.roughing.groove_rings; issue 43 E)
        rings = groove_rings(lambda o, i=i: cam.offset_flank(i, r_r - o), _material_side(cam, i), span, r_t, step)
        rough += [(f"groove rough {side} {j}", cam.offset_flank(i, r_r - o), r_t, None, "rough", rings.describe(j),
                   i) for j, o in enumerate(rings.offsets, start=1)]
    return [("groove centre (rough)", cam.pitch, r_r, None, "slot", "", None), *rough,
            ("inner flank", cam.offset_flank(0, r_t), r_t, None, "finish", "", 0),
            ("outer flank", cam.offset_flank(1, r_t), r_t, None, "finish", "", 1)]


def _plan_side(cam, curve, free, wall) -> str:
    """The side of a planned contour's travel where its material is: "left", "right", or "both" (a slot)."""
    if free is not None:
        return _stock_side(curve, free)
    if wall is None:
        return "both"
    return "left" if _material_side(cam, wall)(curve, np.array([curve.t_start]))[0] > 0 else "right"


def _material_side(cam, flank: int):
    """(curve, t) → +1 where flank ``flank``'s material lies left of ``curve``'s travel (a curve between the
    groove's centre line and that flank), −1 where right."""
    def side(curve, t):
        toward = cam.offset_flank(flank, 0.0).evaluate(t) - cam.pitch.evaluate(t)  # centre line → flank
        return np.sign(np.einsum("ij,ij->i", left_normal(curve, t), toward))
    return side


def machine_program(built: BuiltCam, m: MachiningSpec, name: str, stock: StockSpec = DEFAULT_STOCK,
                    workers: int = 1) -> MachiningResult:
    """Tool-centre curves, fitted contours, passes and the printed program for ``built`` (no I/O).

    What is measured on the printed program (a disc's material check, a barrel's 3-D groove check) is
    :mod:`camcam.verify`'s: :func:`camcam.verify.check_job` (``checked`` does both steps).

    Parameters
    ----------
    built : BuiltCam
        The cam from :func:`camcam.geometry.build.build_cam`.
    m : MachiningSpec
        The validated ``[machining]`` table.
    name : str
        The job name (program title and file names).
    stock : StockSpec
        The blank (``[stock]``; default: round, 2 mm over the cam's largest radius).
    workers : int
        Processes the work may be shared with where it splits into independent
        parts: the further starts of a closed contour's arc spline
        (:func:`camcam.toolpath.arcspline.fit_arc_spline`) and a barrel cam's
        passes (:func:`camcam.nc.rotary.machine_cylindrical`); the same result
        for any count.

    Returns
    -------
    MachiningResult

    Raises
    ------
    GeometryError
        A tool too large for a concave part of the profile, wider than a
        groove, or too small to clear it.
    SpecError
        A blank smaller than the cam, a bore larger than the base circle minus
        the roller, a helical bore the tool does not fit.
    FitError, PostError
        Faults of the fitter or the writer on valid input.
    """
    if built.spec.kind == "cylindrical":
        if m.axes == 5:
            from camcam.nc.fiveaxis import machine_five_axis

            return machine_five_axis(built, m, name)  # one pass: nothing to share (its 3-D check is verify's)
        from camcam.nc.rotary import machine_cylindrical

        return machine_cylindrical(built, m, name, workers)
    post, r_t = m.post, m.tool_diameter_mm / 2
    title = job_title(name, built.spec.kind, built.cam.kind, m.tool_diameter_mm, m.mode, m.tolerance_mm, post.name)
    blank = blank_for(built, stock, m.tool_diameter_mm, m.bore, m.dowel)
    z_clear = blank.top_z_mm + m.clearance_z_mm
    levels = depth_levels(m.cut_settings())
    plan = _disc_plan(built, r_t, m.stepover_mm)
    if m.bore:
        plan.append(("bore", bore_curve(bore_circle_radius(blank, r_t)), r_t, None, "bore", "", None))
    if blank.dowel is not None:
        plan.append((DOWEL_LABEL, dowel_curve(blank, r_t), r_t, None, "bore", "", None))
    contours, passes = [], []
    sides = [_plan_side(built.cam, curve, free, wall) for _, curve, _, free, _, _, wall in plan]
    # the side each pass runs with the material on: climb or conventional as asked (camcam.nc.direction)
    travel = [orient((), s, m.direction)[1] for s in sides]
    with ChildGroup() as group:
        # a profile's roughing spiral needs only the blank and the side the material is on: with a second
        # process it is made in a child beside its contour's fit (the same call, the same spiral)
        spirals = {k: group.later(_roughing_spiral, blank, m, travel[k])
                   for k, (_, _, _, free, kind, _, _) in enumerate(plan)
                   if workers > 1 and free is not None and kind != "bore"}
        for k, (label, curve, offset, free, kind, note, _) in enumerate(plan):
            fit, printed, dev, segs = fit_printed(curve, m.tolerance_mm, m.mode, post.quantizer,
                                                  post.max_arc_sweep_deg, post.quantizer.printed_elements,
                                                  f"{name} {label}", mapper=ProcessMap(workers))
            side = sides[k]
            elements, run = orient(fit.elements, side, m.direction)
            cs = replace(m.cut_settings(run if free is not None else "right"), clearance_z_mm=z_clear,
                         safe_z_mm=max(m.safe_z_mm, z_clear))
            if kind == "bore":
                hole = dowel_passes if label == DOWEL_LABEL else bore_passes
                new = hole(k, fit.elements, blank, r_t, z_clear, levels[-1], built.spec.thickness,
                           ramp_angle_deg=m.ramp_angle_deg, plunge_feed_mm_min=m.plunge_feed_mm_min,
                           feed_mm_min=m.feed_mm_min, ccw=m.direction == "climb")
                run = "right" if m.direction == "climb" else "left"  # the material is outside the hole's circle
            elif free is not None:
                spiral = resolve(spirals[k]) if k in spirals else _roughing_spiral(blank, m, run)
                new = _profile_passes(k, elements, spiral, cs, levels, allowance_mm=m.finish_allowance_mm,
                                      spring_pass=m.spring_pass)
            else:
                new = [replace(p, note=note) if p.kind == "rough" else p  # a groove's rough ring: its plan
                       for p in ramp_loop_passes(k, kind, elements, levels, blank.top_z_mm, m.ramp_angle_deg,
                                                 cs, m.spring_pass)]
            passes += [replace(p, direction=direction_of(run)) for p in new]
            contours.append(CutContour(label=label, curve=curve, fit=fit, printed=printed, deviation=dev,
                                       offset_mm=offset, leads=free is not None, segments=segs, stock_side=side))
    # lead arcs, spirals and ramps planned at the post's largest sweep print within it (contours already do)
    passes = [replace(q, note=p.note) for p, q in
              zip(passes, passes_within_sweep(passes, post.quantizer, post.max_arc_sweep_deg), strict=True)]
    passes = with_cutting_data(passes, m)  # each kind's speed and feed, held at the edge on arcs (cutting data)
    safe = (Rapid(None, None, max(m.safe_z_mm, z_clear)),)
    counts: dict[str, int] = {}
    for p in passes:
        counts[p.kind] = counts.get(p.kind, 0) + 1
    summary = ", ".join(f"{n} {kind}" for kind, n in counts.items())
    spindle = passes[0].spindle_rpm or m.spindle_rpm  # the header starts the first pass's speed
    toolpath = Toolpath(title, with_markers(passes, [c.label for c in contours]), spindle,
                        tool_number=m.tool_number, tool_diameter_mm=m.tool_diameter_mm, rotary=False,
                        comments=(f"{len(passes)} passes [{summary}] in {len(levels)} depth levels to "
                                  f"{levels[-1]:g} mm",),
                        opening=safe, closing=safe)
    program = post.write_program(toolpath, name, m.setup)
    notes = ()
    if m.finish_allowance_mm > 0 and built.spec.kind != "disc":
        notes = ("finish_allowance does not apply to groove passes (the flanks have their own passes)",)
    # a contour whose arc spline no march closed is cut with lines (camcam.toolpath.arcfit, issue 43 C): said
    notes += tuple(f"{c.label}: no arc spline closed on {len(c.fit.lines_sections)} section(s); cut with "
                   f"{c.fit.line_blocks} lines within the tolerance instead" for c in contours if c.fit.lines_sections)
    return MachiningResult(name=name, cam_kind=built.spec.kind, follower_kind=built.cam.kind, post=post,
                           tool_diameter_mm=m.tool_diameter_mm, tolerance_mm=m.tolerance_mm, mode=m.mode,
                           contours=tuple(contours), toolpath=toolpath, program=program, reference_radius_mm=None,
                           notes=notes,
                           checks=deviation_checks(contours, m.tolerance_mm), blank=blank)


def _roughing_spiral(blank, m: MachiningSpec, side: str) -> Spiral | None:
    """A disc profile's roughing spiral from the blank to the finish allowance (:func:`disc_spiral`), in the
    direction of the finish pass (clockwise about the cam axis when the material is on the right)."""
    return disc_spiral(blank.part, blank.region, m.tool_diameter_mm / 2, m.finish_allowance_mm, m.stepover_mm,
                       clockwise=(side == "right"), max_sweep_deg=m.post.max_arc_sweep_deg)


def _profile_passes(k: int, elements, spiral: Spiral | None, cs, levels, *, allowance_mm: float,
                    spring_pass: bool) -> list[Pass]:
    """A disc profile: a roughing spiral at each level, then finish (each level without an allowance) and spring."""
    a, passes = allowance_mm, []
    for z in levels:
        if spiral is not None:
            passes.append(Pass(k, "rough", z, spiral_moves(spiral, z, cs), note=spiral.describe()))
        if a == 0:
            passes.append(Pass(k, "finish", z, finish_moves(elements, z, cs)))
    if a > 0:
        passes.append(Pass(k, "finish", levels[-1], finish_moves(elements, levels[-1], cs)))
    if spring_pass:
        passes.append(Pass(k, "spring", levels[-1], finish_moves(elements, levels[-1], cs)))
    return passes
