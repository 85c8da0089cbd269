"""Cylindrical cams on a 4-axis machine: ``G1 X A`` moves, inverse-time feeds, checked in 3-D.

Machine frame (DESIGN.md "Machine frames", stated in every program's header):
the cam axis is machine X with Y = Z = 0 on it and X0 at the left end face;
A turns the part about +X, a part point p sits at Rx(a)·p with a = A
(``[machining] a_axis = "right-hand"``) or −A ("left-hand"); the tool is
radial (B = 0, axis +Z) and X Y Z are its tip.  The follower at program
angle θ sees the cam turned by σθ (σ = +1 ccw, −1 cw), so the program prints
A = σ·θ (right-hand) or −σ·θ (left-hand): cw and ccw cut mirror-image grooves.

The contours are worked in the developed plane (u = ρ_d·θ, x) at the
development radius ρ_d = the outer radius: a printed chord's error normal to
the wall is its gap along x times cos ψ, ψ the wall's slope, and cos ψ is
largest at the outer radius, so a fit held there holds at every depth.

* Tool as wide as the groove (diameter = 2 · roller radius): one centre pass
  along the groove centre line; for a translating roller this is exact at
  every radius, to the fit.
* Narrower tool: a centre pass, then each flank pass displaced from the
  centre line along the wall normal by q(θ), chosen per station to minimise
  the largest 3-D error over the flank depth (:mod:`camcam.nc.flank`,
  translating rollers; an oscillating roller's flank passes use the offset
  that is exact at the development radius).

The final depth pass runs below the groove bottom by what the tool's flat end
needs to reach the wall corner there: the wall contact is y off the tool's
axis plane (r_t·sin α on a flat bottom, α the pressure angle at the bottom;
farther out on the curved one, :func:`corner_offset_mm`), where the end face
sits at √(Z² + y²) from the cam axis.

The printed program is measured, from its own axis words, by
:func:`camcam.verify.job_checks.check_job` (:mod:`camcam.verify.groove3d`):
that 3-D figure is the job's deviation.  The plan hands it what it needs
(:class:`~camcam.nc.result.GroovePlan`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from camcam.errors import GeometryError, InputError, SpecError
from camcam.workers import parallel_map
from camcam.geometry.build import BuiltCam
from camcam.nc.direction import direction_of, material_side
from camcam.nc.feeds import with_cutting_data
from camcam.nc.flank import DisplacedCurve, plan_flank, smallest_tool_radius
from camcam.nc.passes import with_markers
from camcam.nc.result import GroovePlan, MachiningResult, deviation_checks
from camcam.nc.settings import MachiningSpec
from camcam.nc.tools import SAME_TOOL_MM, groove_passes
from camcam.toolpath.budget import DEFAULT_BUDGET, DEFAULT_GROOVE_BUDGET, FitBudget, GrooveBudget
from camcam.toolpath.contours import CutContour, OffsetCurve, fit_printed
from camcam.toolpath.elements import Line
from camcam.toolpath.path import join_toolpaths, rotary_toolpath, shortest_rotation
from camcam.toolpath.poses import A_AXIS_SENSE
from camcam.toolpath.quantizer import Quantizer

__all__ = ["machine_cylindrical", "developed_printed", "printed_axes", "machine_frame_lines"]


def printed_axes(elements, quantizer: Quantizer, radius_mm: float, turn: int = 1) -> np.ndarray:
    """(X, A°) of the contour's vertices as printed: x and turn·u/ρ in degrees on the post's grid."""
    pts = np.array([elements[0].start] + [e.end for e in elements])
    x = quantizer.snap(pts[:, 1])
    a = quantizer.snap(turn * np.degrees(pts[:, 0] / radius_mm))
    return np.stack([x, a], axis=-1)


def developed_printed(axes: np.ndarray, radius_mm: float, turn: int = 1) -> tuple:
    """The printed (X, A°) polyline developed at ``radius_mm``: lines in (u, x), u = ρ·A/turn."""
    uv = np.stack([turn * np.radians(axes[:, 1]) * radius_mm, axes[:, 0]], axis=-1)
    return tuple(Line(tuple(map(float, p)), tuple(map(float, q))) for p, q in zip(uv[:-1], uv[1:]) if tuple(p) != tuple(q))


def machine_frame_lines(a_axis: str, rho_d: float) -> tuple[str, ...]:
    """The header comment lines stating the development radius and the machine frame."""
    sense = "right-hand rule" if a_axis == "right-hand" else "left-hand rule [a_axis = left-hand]"
    return (f"developed at R{rho_d:g} mm: A = cam angle, u = R{rho_d:g} x A",
            "machine frame: cam axis = X, Y = Z = 0 on it, X0 at the left end face",
            f"A turns the part about +X by the {sense}; part point p at Rx[A].p",
            "tool axis +Z [B = 0]; X Y Z = tool tip, centre of the flat end")


def _plan(cam, r_t: float, rho_d: float, tolerance_mm: float, groove: GrooveBudget):
    """[(label, developed curve at ρ_d, offset from the wall)] and the flank plan's first-order error; a tool
    below a third of the groove is refused naming the thinnest whose flank error holds ``groove``'s share of
    ``tolerance_mm`` where that is more (a radial roller axis: the tool a tilting one needs is its own advice)."""
    r_r = cam.roller_radius
    centre = cam.developed_centre(rho_d)
    thinnest = None if cam.follower.roller_axis_tilts else (
        lambda: 2 * smallest_tool_radius(cam, groove.flank_tool_mm(tolerance_mm), rho_d))
    if groove_passes(r_t, r_r, thinnest) == "centre":
        return [("groove centre", centre, r_r, "slot")], 0.0
    rough = ("groove centre (rough)", centre, r_r, "slot")
    if not cam.follower.roller_axis_tilts:  # a radial tool can follow a radial roller axis: balanced flanks
        plan = plan_flank(cam, r_t, rho_d)
        # flank 0 is the −X wall: to the right of the centre line in (u, x) (u grows with the cam angle)
        return [rough, ("flank 0 (-X wall)", DisplacedCurve(centre, -1.0, plan), r_t, "finish"),
                ("flank 1 (+X wall)", DisplacedCurve(centre, 1.0, plan), r_t, "finish")], plan.error_mm
    return [rough, ("flank 0 (-X wall)", OffsetCurve(cam.developed_flank(0, rho_d), r_t), r_t, "finish"),
            ("flank 1 (+X wall)", OffsetCurve(cam.developed_flank(1, rho_d), -r_t), r_t, "finish")], 0.0


def _wall_side(label: str, pts: np.ndarray, a_axis: str) -> str:
    """The side of travel a barrel pass's wall is on, seen down the radial tool ("both" for the centre pass).

    ``pts`` are the pass's (X, A·ρ) in printed order.  Under the tool (at Y0, Z = ρ, looking down −Z with
    X to the right and Y up) a part point p sits at Rx(±A)·p, so the tool runs over the part along +Y as
    the printed A grows by the right-hand rule (``a_axis`` "right-hand"), along −Y by the left-hand rule;
    flank 0's wall is at −X of the tool, flank 1's at +X.  The material is on the right of a travel
    (dX, dY) where wall_x · dY > 0.
    """
    if not label.startswith("flank"):
        return "both"
    wall_x = -1.0 if label.startswith("flank 0") else 1.0
    dy = A_AXIS_SENSE[a_axis] * float(pts[-1, 1] - pts[0, 1])
    return "right" if wall_x * dy > 0 else "left"


def _check_fit_floor(cam, m: MachiningSpec, quantizer: Quantizer, least_mm: float, flank_err: float,
                     flanks: bool, groove: GrooveBudget = DEFAULT_GROOVE_BUDGET,
                     budget: FitBudget = DEFAULT_BUDGET) -> None:
    """Refuse, naming ``machining.tolerance`` and a value that works, a tolerance whose share for the passes'
    fits is below what the post's decimals allow (:meth:`FitBudget.floor_mm`).  The spec's own check holds the
    whole tolerance to that floor; a barrel's flank passes fit within max(δ − e, s·δ) (e: the flank plan's
    error, s: :attr:`GrooveBudget.flank_fit_share`), times k = :attr:`GrooveBudget.tilt_fit_share` where the
    roller's axis tilts, so the least δ that holds is min(F/k + e, F/(s·k)) with flanks, F/k without (issue 43:
    it said "use at least 0.0018 mm" to a user at 0.0023)."""
    k = groove.fit_factor(cam.follower.roller_axis_tilts)
    floor = budget.floor_mm(quantizer)
    if least_mm * k >= floor:
        return
    need = min(floor / k + flank_err, floor / k / groove.flank_fit_share) if flanks else floor / k
    need = math.ceil(need * 1e4 + 1e-9) / 1e4  # up to 0.0001 mm: the least tolerance that holds, as typed
    raise SpecError("machining.tolerance", f"{m.tolerance_mm:g} mm leaves the groove passes' fits "
                                           f"{least_mm * k:.2g} mm, below the {floor:.2g} mm the post's "
                                           f"{quantizer.decimals} decimals allow; expected at least {need:g} mm, "
                                           f"or a post with more decimals")


def corner_offset_mm(bottom_radius_mm: float, tool_radius_mm: float, pressure_angle_rad: float) -> float:
    """How far from the tool's axis plane a radial tool touches a wall of pressure angle α on the cylinder of the
    groove bottom: y = ρ sin β of the contact, mm.

    The tool's section on r = ρ is |x − X| ≤ √(r² − ρ² sin² β) at β off its axis plane, and it moves along the
    wall at dX/dθ = ρ tan α: the envelope touches where the two slopes meet, ρ² tan²α (r² − y²) = y² (ρ² − y²),
    whose smaller root is taken.  Flat (ρ → ∞) it is r sin α; on the curved bottom it is farther out: campaign
    case 43:54 (ρ 20.6, r 8 mm, α 48.06°) touches at 6.07 mm, not 5.95, and a tip placed for 5.95 left
    0.00035 mm more material along the wall corner than anywhere else on the wall (3-D check, 0.006 mm
    tolerance), with every tolerance the advice named.

    Examples
    --------
    >>> round(corner_offset_mm(20.6, 8.0, math.radians(48.06)), 2)
    6.07
    >>> round(corner_offset_mm(1e6, 8.0, math.radians(30.0)), 6)  # a flat bottom: r sin α
    4.0
    """
    rho, r, t2 = bottom_radius_mm, tool_radius_mm, math.tan(pressure_angle_rad) ** 2
    a, c = rho * rho * (1.0 + t2), rho * rho * t2 * r * r  # y⁴ − a y² + c = 0
    y2 = 2.0 * c / (a + math.sqrt(max(a * a - 4.0 * c, 0.0)))  # the smaller root, without cancellation
    return math.sqrt(min(y2, rho * rho))


def _corner_dip_mm(cam, r_t: float) -> float:
    """How far below the groove bottom the tip must go for the flat end to reach the wall corner (mm, exact:
    :func:`corner_offset_mm` at the largest pressure angle, which is at the groove bottom)."""
    th = np.linspace(0.0, 2 * math.pi, 2881)
    alpha = np.abs(cam.pressure_angle(th).value).max()  # at the groove bottom, where it is largest
    rb = cam.bottom_radius
    y = corner_offset_mm(rb, r_t, float(alpha))
    return rb - math.sqrt(rb * rb - y * y)


def _corner_depth_mm(cam, r_t: float, quantizer, depth_mm: float) -> float:
    """How far below ``depth_mm`` the tool tip goes so that its end clears the wall corner (mm), as printed.

    The wall contact at the groove bottom is y = r_t·sin α off the tool's axis plane (α the largest pressure
    angle), where the bottom lies ρ_b − √(ρ_b² − y²) under the tangent plane the tip would touch.  The tip's
    Z is printed on the post's grid: the last pass goes to the first grid value strictly below that, so the
    printed program clears the corner, not merely touches it.  A rounding up would leave the tip above it (at
    R 1000 mm the corner is 4e-5 mm deep and Z990 printed exactly at the bottom, where the tool's section on
    the bottom radius is a single line: the 3-D check found the groove uncut there, 16 mm).
    """
    top = cam.base_radius - depth_mm  # the tip at the stated depth
    target = top - _corner_dip_mm(cam, r_t)
    k = quantizer.count(target)
    while quantizer.value(k) >= target:
        k -= 1
    return top - quantizer.value(k)


def machine_cylindrical(built: BuiltCam, m: MachiningSpec, name: str, workers: int = 1,
                        groove: GrooveBudget = DEFAULT_GROOVE_BUDGET) -> MachiningResult:
    """The 4-axis program of a cylindrical cam and its 3-D measurement (see the module notes); ``groove``: how
    the tolerance is shared between the flank plan and the passes' fits (:class:`GrooveBudget`)."""
    cam, post = built.cam, m.post
    if not post.inverse_time:
        raise GeometryError(f"post {post.name}: has no inverse-time feed (G93) for a cylindrical cam's 4-axis program")
    rho_d = cam.base_radius
    turn = A_AXIS_SENSE[m.a_axis] * cam.sigma  # printed A = turn · θ
    r_t = m.tool_diameter_mm / 2
    # the title names the tolerance as a target; whether the cut holds it is the 3-D check's line below it
    title = (f"{name}: {built.spec.kind} cam, {cam.kind} follower, tool D{m.tool_diameter_mm:g} mm, lines, "
             f"tolerance {m.tolerance_mm:g} mm, post {post.name}")
    cs0 = m.cut_settings()
    corner = _corner_depth_mm(cam, r_t, post.quantizer, m.depth_mm) if m.depth_mm >= cam.groove_depth - 1e-9 else 0.0
    scale = (m.depth_mm + corner) / m.depth_mm
    cs = dataclasses.replace(cs0, depth_mm=m.depth_mm + corner, stepdown_mm=m.stepdown_mm * scale)
    plan, flank_err = _plan(cam, r_t, rho_d, m.tolerance_mm, groove)
    fit_tol = groove.flank_fit_mm(m.tolerance_mm, flank_err)
    _check_fit_floor(cam, m, post.quantizer, fit_tol if len(plan) > 1 else m.tolerance_mm, flank_err, len(plan) > 1,
                     groove)

    def printed(elements):
        return developed_printed(printed_axes(elements, post.quantizer, rho_d, turn), rho_d, turn)

    def job(item):
        """A pass's fit as printed, or (the last item) the smallest tool whose flank error holds
        :attr:`GrooveBudget.flank_share` of the tolerance."""
        if item is None:
            return 2 * smallest_tool_radius(cam, groove.flank_tool_mm(m.tolerance_mm), rho_d)
        label, curve = item[0], item[1]
        tol = fit_tol if label.startswith("flank") else m.tolerance_mm
        if cam.follower.roller_axis_tilts:
            tol *= groove.tilt_fit_share
        return fit_printed(curve, tol, "lines", post.quantizer, post.max_arc_sweep_deg, printed, f"{name} {label}")

    # the passes' fits and the smallest-tool search are independent: they share the workers (the same
    # results as one by one, camcam.workers.parallel_map); the search is only needed for a thinner tool.
    # The dearest first, so that the workers end together: the search, then the passes from the last (the
    # walls' finishing passes before the rough centre; cylindrical-translating-small-tool: 0.46, 0.31,
    # 0.32 and 0.18 CPU s, 0.64 s for each of two workers against 0.49 and 0.78 in plan order)
    thinner = not cam.follower.roller_axis_tilts and r_t < cam.roller_radius - SAME_TOOL_MM
    results = parallel_map(job, ([None] if thinner else []) + list(plan)[::-1], workers)
    # rounded up to a size one can buy and hold to (0.01 mm): the note, the advice and the report name this one
    smallest = math.ceil(results[0] * 100.0 - 1e-9) / 100.0 if thinner else None
    done = results[1 if thinner else 0:][::-1]
    contours, paths = [], []
    for k, ((label, curve, offset, kind), (fit, path, dev, segs)) in enumerate(zip(plan, done)):
        pts = np.array([fit.elements[0].start] + [e.end for e in fit.elements])
        pts = np.stack([pts[:, 1], turn * pts[:, 0]], axis=-1)  # (x, turn·u): A = turn·θ
        side = _wall_side(label, pts, m.a_axis)
        if side != "both" and side != material_side(m.direction):
            pts, side = pts[::-1], material_side(m.direction)  # the other way round the cam
        try:
            tp = rotary_toolpath(pts, cam.base_radius, cs, title, developed_radius_mm=rho_d,
                                 contour=k, kind=kind, rotary_rapid=post.rotary_rapid)
            paths.append(dataclasses.replace(tp, passes=tuple(dataclasses.replace(p, direction=direction_of(side))
                                                              for p in tp.passes)))
        except InputError as err:
            raise GeometryError(f"{name} {label}: {err}") from None
        contours.append(CutContour(label=label, curve=curve, fit=fit, printed=path, deviation=dev, offset_mm=offset,
                                   leads=False, segments=segs, stock_side="both"))
    comments = tuple(f"{c}" for c in machine_frame_lines(m.a_axis, rho_d))
    if corner > 0:
        comments += (f"last pass {corner:.{post.decimals}f} mm below the groove bottom: the tool end clears the wall "
                     f"corner",)
    joined = join_toolpaths(title, paths)
    # every pass opens with a comment naming it (pass 1/4: slot, groove centre, Z45.0), as a disc's do
    # A turns back to each pass's start in a G0 at the safe height, or counts on (the shortest way) where the
    # controller takes no rotary word in G0 (issue 47)
    passes = with_cutting_data(joined.passes if post.rotary_rapid else shortest_rotation(joined.passes), m)
    toolpath = dataclasses.replace(joined, comments=comments, spindle_rpm=passes[0].spindle_rpm or m.spindle_rpm,
                                   passes=with_markers(passes, [c.label for c in contours]))
    # printed without the 3-D check: camcam.verify.job_checks measures this program and adds its result to the
    # header (the same moves)
    program = post.write_program(toolpath, name, m.setup)
    # how deep the printed program has to go: the groove bottom, less the corner dip with a full-depth cut
    full = m.depth_mm >= cam.groove_depth - 1e-9
    needed = cam.bottom_radius - _corner_dip_mm(cam, r_t) if full else cam.base_radius - m.depth_mm
    plan = GroovePlan(axes=4, reach_radius_mm=needed,
                      reach_why="so that the flat end reaches the wall corner" if full else "",
                      flank_error_mm=float(flank_err))
    notes = (f"4-axis: X along the cam axis, A = {'+' if turn > 0 else '-'}cam angle (deg), developed at R{rho_d:g} mm",)
    if m.mode == "arcs":
        notes += ("mode arcs: a 4-axis G1 X A program has lines only",)
    if corner > 0:
        notes += (f"4-axis: the last pass runs {corner:.{post.decimals}f} mm below the groove bottom so the tool's "
                  f"flat end reaches the wall corner",)
    if flank_err > 0:
        notes += (f"4-axis: flank passes balanced over the depth; first-order flank error {flank_err:.4f} mm"
                  + (f", smallest tool holding half the tolerance D{smallest:.2f} mm" if smallest else ""),)
    return MachiningResult(name=name, cam_kind=built.spec.kind, follower_kind=cam.kind, post=post,
                           tool_diameter_mm=m.tool_diameter_mm, tolerance_mm=m.tolerance_mm, mode="lines",
                           contours=tuple(contours), toolpath=toolpath, program=program, reference_radius_mm=rho_d,
                           notes=notes,
                           checks=deviation_checks(contours, m.tolerance_mm), smallest_tool_mm=smallest,
                           groove_plan=plan)
