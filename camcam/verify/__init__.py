"""The verify stage: every figure measured on the printed program, and the independent checkers.

:mod:`camcam.nc` plans and prints; this stage reads what was printed (with the
dialect's reader, :mod:`camcam.post.readback`) and measures it: the material
removal of a disc or face-groove job (:mod:`camcam.verify.removal`, its swept
slabs :mod:`camcam.verify.swept`), a barrel's 3-D groove
(:mod:`camcam.verify.groove3d`, the follower's motion in it
:mod:`camcam.verify.groove_motion`, its checks
:mod:`camcam.verify.groove_checks`) and tool reach
(:mod:`camcam.verify.reach`), and the cycle time of the printed moves
(:mod:`camcam.verify.cycle_time`).  :func:`check_job` is the one call a job makes
(:mod:`camcam.verify.job_checks`).  :mod:`camcam.verify.rs274` runs LinuxCNC's
interpreter, a reader nobody on the project wrote.
"""

from camcam.lazy import lazy_exports

# lazy (camcam.lazy): the material check pulls in shapely and scipy, the 3-D check numpy only
__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("JobChecks", "check_job", "with_checks", "checked"), "camcam.verify.job_checks"),
    **dict.fromkeys(("RemovalReport", "check_moves", "check_program", "design_keep"), "camcam.verify.removal"),
    **dict.fromkeys(("GrooveMeasurement", "measure_groove", "pose_step_for"), "camcam.verify.groove3d"),
    **dict.fromkeys(("ToolReach", "tool_reach", "flute_text"), "camcam.verify.reach"),
    **dict.fromkeys(("groove_check", "five_axis_check"), "camcam.verify.groove_checks"),
    **dict.fromkeys(("CycleTime", "cycle_time"), "camcam.verify.cycle_time"),
    **dict.fromkeys(("CanonMove", "rs274_available", "run_rs274", "feed_passes", "poses_from_canon"),
                    "camcam.verify.rs274"),
})
