"""A job's checks of its printed program, in one call: :func:`check_job`, then :func:`with_checks`.

:mod:`camcam.nc` plans a job and prints its program; everything measured on
what it printed is taken here, from the program text the machine reads:

* a disc or face-groove job: the material-removal check against its blank
  (:mod:`camcam.verify.removal`), 2.5-D at every level;
* a barrel job: the tool poses read back (:func:`camcam.post.readback.read_poses`),
  the groove they cut measured in 3-D on both walls and every radius
  (:mod:`camcam.verify.groove3d`), held to the tolerance
  (:mod:`camcam.verify.groove_checks`), and how deep the tool reaches and how
  much flute it needs (:mod:`camcam.verify.reach`).  The 3-D figure is then
  printed in the program's header: the same moves, read back again to show it;
* every job: the cycle time of the moves as printed, feed-only (:mod:`camcam.verify.cycle_time`) and from
  the motion model with the post's accelerations (:mod:`camcam.verify.motion_time`), per pass.

:func:`check_job` does no I/O and returns a frozen :class:`JobChecks`; it may
run in another process (`camcam run` checks a disc's material in a child
while it writes the drawing).  :func:`checked` is both steps for a caller
that wants the finished job at once.

Examples
--------
>>> from camcam.spec import load_spec
>>> from camcam.geometry.build import build_cam
>>> from camcam.nc import machine_program
>>> from camcam.verify import check_job, with_checks
>>> spec = load_spec("samples/disc-translating-roller.toml")
>>> built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
>>> planned = machine_program(built, spec.machining, spec.name, spec.stock)
>>> planned.removal is None
True
>>> done = with_checks(planned, check_job(planned, built, spec.machining), spec.machining)
>>> done.removal is not None, [c.name for c in done.checks][len(planned.checks)]
(True, 'plunges into material')
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from camcam.errors import PostError
from camcam.nc.result import MachiningResult
from camcam.nc.settings import DEFAULT_STOCK, MachiningSpec, StockSpec
from camcam.post.readback import read_poses
from camcam.toolpath.poses import CylinderTool, ToolPoses
from camcam.verdict import Check
from camcam.verify.cycle_time import cycle_time
from camcam.verify.motion_time import motion_time
from camcam.verify.groove_checks import five_axis_check, groove_check
from camcam.verify.holder import check_holder
from camcam.verify.reach import ToolReach, flute_to_buy_mm, tool_reach

if TYPE_CHECKING:
    from camcam.geometry.build import BuiltCam
    from camcam.verify.groove3d import GrooveMeasurement
    from camcam.verify.removal import RemovalReport

__all__ = ["JobChecks", "check_job", "with_checks", "checked"]


@dataclass(frozen=True, kw_only=True)
class JobChecks:
    """What :func:`check_job` measured on a printed program.

    ``checks`` join the job's own (in this order); ``removal`` is a disc or
    face-groove job's material check, ``groove`` and ``reach`` a barrel
    job's 3-D figure and tool reach, measured on ``poses`` (read from the
    program); ``header`` the comment lines the program's header gains (the
    3-D check's result).
    """

    checks: tuple[Check, ...] = ()
    removal: RemovalReport | None = None
    groove: GrooveMeasurement | None = None
    reach: ToolReach | None = None
    poses: ToolPoses | None = None
    header: tuple[str, ...] = ()


def check_job(result: MachiningResult, built: BuiltCam, m: MachiningSpec, workers: int = 1) -> JobChecks:
    """Every figure of ``result``'s printed program (see the module notes), measured by ``workers`` processes
    where the work splits (the same figures for any count).

    Raises
    ------
    SpecError
        The spec's tool holder would hit the blank (:func:`camcam.verify.holder.check_holder`).
    """
    check_holder(result, built, m)
    if result.groove_plan is not None:
        return _barrel_checks(result, built, m, workers)
    if result.blank is not None:
        from camcam.verify.removal import check_program

        removal = check_program(result.program.text, result.post, result.blank, m, built, workers)
        return JobChecks(checks=removal.checks(), removal=removal)
    return JobChecks()


def _barrel_checks(result: MachiningResult, built: BuiltCam, m: MachiningSpec, workers: int) -> JobChecks:
    from camcam.verify.groove3d import measure_groove, pose_step_for

    cam, plan, post = built.cam, result.groove_plan, result.post
    r_t = m.tool_diameter_mm / 2
    poses = read_poses(result.program.text, post, m.a_axis)
    reach = tool_reach(poses, r_t, cam.base_radius, cam.bottom_radius, plan.reach_radius_mm, m.flute_length_mm,
                       post.quantizer.decimals, plan.reach_why)
    # the tool modelled: the spec's flute, or where it states none one as long as the printed cut needs
    m = replace(m, flute_length_mm=m.flute_for(flute_to_buy_mm(max(reach.flute_needed_mm, plan.cut_length_mm or 0.0))))
    reach = replace(reach, flute_length_mm=m.flute_length_mm)
    groove = measure_groove(cam, CylinderTool(r_t, m.flute_length_mm), poses, workers=workers,
                           pose_step_mm=pose_step_for(m.tolerance_mm, r_t))
    if plan.axes == 5:
        check = five_axis_check(m, groove, plan.cut_length_mm, reach.flute_needed_mm)
    else:
        check = groove_check(cam, m, groove, result.smallest_tool_mm, reach.flute_needed_mm,
                             flank_error_mm=plan.flank_error_mm)
    verdict = "within" if check.ok else "OUT OF TOLERANCE"
    header = (f"3-D groove check of this program: {groove.max_deviation_mm:.4f} mm, {verdict} {m.tolerance_mm:g} mm",)
    return JobChecks(checks=(check, reach.check()), groove=groove, reach=reach, poses=poses, header=header)


def with_checks(result: MachiningResult, checks: JobChecks, m: MachiningSpec) -> MachiningResult:
    """``result`` with what :func:`check_job` measured: its checks after the job's own, its figures, the
    program re-printed with the header lines (the same moves: read back again to show it) and its cycle time
    (:func:`camcam.verify.cycle_time.cycle_time`).

    Raises
    ------
    PostError
        The re-printed program's moves differ from the measured one's.
    """
    toolpath, program = result.toolpath, result.program
    if checks.header:
        toolpath = replace(toolpath, comments=toolpath.comments + checks.header)
        program = result.post.write_program(toolpath, result.name, m.setup)
        before = checks.poses  # what the checks measured, read from the program before the header
        again = read_poses(program.text, result.post, m.a_axis)
        if not (np.array_equal(again.tip_mm, before.tip_mm) and np.array_equal(again.a_deg, before.a_deg)
                and np.array_equal(again.b_deg, before.b_deg)):
            raise PostError("the program's moves changed with its header comment")
    program = replace(program, cycle_time=cycle_time(program.printed_moves, result.post.rapid_mm_min),
                      motion_time=motion_time(program.printed_moves, result.post))
    return replace(result, toolpath=toolpath, program=program, checks=result.checks + checks.checks,
                   removal=checks.removal if checks.removal is not None else result.removal,
                   groove=checks.groove if checks.groove is not None else result.groove,
                   reach=checks.reach if checks.reach is not None else result.reach)


def checked(built: BuiltCam, m: MachiningSpec, name: str, stock: StockSpec = DEFAULT_STOCK,
            workers: int = 1) -> MachiningResult:
    """The job planned and printed (:func:`camcam.nc.machine_program`) and its printed program checked
    (:func:`check_job`, :func:`with_checks`): what `camcam run` machines, in one call (no I/O).

    Raises
    ------
    GeometryError, SpecError, FitError, PostError
        As :func:`camcam.nc.machine_program`.
    """
    from camcam.nc.job import machine_program

    result = machine_program(built, m, name, stock, workers)
    return with_checks(result, check_job(result, built, m, workers), m)
