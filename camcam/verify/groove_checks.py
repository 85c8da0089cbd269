"""The 3-D groove check of a barrel program: its measured deviation held to the tolerance, with the way out of a
miss as values a spec takes.

:func:`groove_check` judges a 4-axis program (:mod:`camcam.nc.rotary`, a radial tool), :func:`five_axis_check`
a 5-axis one (:mod:`camcam.nc.fiveaxis`, the tool on the roller's axis).  Both take the figure
:func:`camcam.verify.groove3d.measure_groove` measured on the printed program.
"""

from __future__ import annotations

import math

from camcam.nc.settings import MachiningSpec
from camcam.nc.tools import SAME_TOOL_MM
from camcam.toolpath.budget import DEFAULT_GROOVE_BUDGET, GrooveBudget
from camcam.verdict import Check
from camcam.verify.groove3d import GrooveMeasurement
from camcam.verify.reach import flute_to_buy_mm

__all__ = ["groove_check", "five_axis_check"]


def groove_check(cam, m: MachiningSpec, groove: GrooveMeasurement, smallest_tool_mm: float | None,
                 flute_needed_mm: float | None = None, budget: GrooveBudget = DEFAULT_GROOVE_BUDGET,
                 flank_error_mm: float = 0.0) -> Check:
    """The 3-D groove deviation held to the tolerance, with the way out of a miss (``flute_needed_mm``: the
    flute the printed poses need, :func:`camcam.verify.reach.tool_reach`; ``budget``: the shares the plan was
    fitted with, whence the tolerance a tilting roller's plan holds, :meth:`GrooveBudget.tilt_tolerance_mm`, and
    a thinner tool's with flank error ``flank_error_mm``, :meth:`GrooveBudget.flank_tolerance_mm`)."""
    value, tol = groove.max_deviation_mm, m.tolerance_mm
    holds = math.ceil(value * 1e4) / 1e4
    r_r = cam.roller_radius
    if flute_needed_mm is not None and m.flute_length_mm < flute_needed_mm:
        # first: no tool diameter or tolerance cuts the top of the walls a short flute leaves (campaign case 43:34
        # of the translating barrels: "use a tool from D15.78 mm ..., or accept a tolerance of at least 23.203 mm")
        advice = f"the flute is shorter than the cut: [machining] flute_length = {flute_to_buy_mm(flute_needed_mm):g}"
    elif cam.follower.roller_axis_tilts:
        holds = math.ceil(budget.tilt_tolerance_mm(value, tol) * 1e4) / 1e4
        # keys and values as a spec writes them, each with its section, so that the advice applies as it reads
        # (issue 43: it said "a tool of the roller's diameter (D8 mm)"); the tool first: axes = 5 with another
        # tool is refused.  On a post with no 5-axis mode "axes = 5" ends in a refusal, so the tolerance comes first
        if m.post.five_axis:
            advice = ("the roller axis tilts with the arm and a radial tool cannot follow it: cut it with "
                      f"[machining] tool_diameter = {2 * r_r:g} (the roller's diameter) and [machining] axes = 5, "
                      f"or accept a tolerance of at least {holds:g} mm")
        else:
            advice = (f"the roller axis tilts with the arm and a radial tool cannot follow it, and post {m.post.name} "
                      f"has no 5-axis mode: accept a tolerance of at least {holds:g} mm, or cut it on a 5-axis "
                      f"machine (a post with tool-centre-point control, e.g. post = \"linuxcnc\", with axes = 5 and "
                      f"tool_diameter = {2 * r_r:g}, the roller's diameter)")
    elif m.tool_diameter_mm < 2 * r_r - 2 * SAME_TOOL_MM:
        # one diameter, one meaning: the smallest tool is the one whose balanced flank error holds half the
        # tolerance (the fit has the other half); where only the roller's own diameter does, it is named once
        least = math.ceil(smallest_tool_mm * 100.0 - 1e-9) / 100.0 if smallest_tool_mm is not None else None
        # as a spec writes it (campaign case 43:48: "use a tool from D30.69 mm" named no setting to follow)
        if least is not None and least < 2 * r_r - 0.01:
            tool = (f"[machining] tool_diameter = {least:g} (the thinnest tool whose flank error holds half of "
                    f"{tol:g} mm; any up to the roller's diameter, {2 * r_r:g} mm)")
        else:
            tool = (f"[machining] tool_diameter = {2 * r_r:g} (the roller's diameter: no thinner tool holds half of "
                    f"{tol:g} mm)")
        # a tolerance only where a plan at it is certain to hold it: the flank fit widens with the tolerance
        held = budget.flank_tolerance_mm(value, tol, flank_error_mm)
        advice = tool + (f", or accept a tolerance of at least {math.ceil(held * 1e4) / 1e4:g} mm"
                         if held is not None else "")
    elif m.depth_mm < cam.groove_depth - 1e-9:
        advice = (f"the cut stops above the groove bottom: [machining] depth = {cam.groove_depth:g} (the groove "
                  f"depth), or accept a tolerance of at least {holds:g} mm")
    else:
        advice = f"accept a tolerance of at least {holds:g} mm"
    return Check("3-D groove deviation", value, tol, "mm", ok=value <= tol, severity="fail", where=groove.where(),
                 advice=advice)


def five_axis_check(m: MachiningSpec, groove: GrooveMeasurement, cut_length_mm: float,
                    flute_needed_mm: float) -> Check:
    """A 5-axis program's 3-D groove deviation held to the tolerance; the way out of a miss is a longer flute
    where the flute is shorter than the cut (``cut_length_mm``: the plan's, ``flute_needed_mm``: the printed
    poses'), else a wider tolerance."""
    value, tol = groove.max_deviation_mm, m.tolerance_mm
    holds = math.ceil(value * 1e4) / 1e4
    # the flute the cut needs, as a value a spec takes (issue 43: "check flute_length (the cut needs 10.04 mm from
    # the tip) and depth" named no setting; a short flute leaves the top of the walls uncut, 10.48 mm on 43:404
    # with flute_length = 6, where no tolerance is the way out)
    flute = flute_to_buy_mm(max(cut_length_mm, flute_needed_mm))
    if m.flute_length_mm < flute:
        advice = (f"the flute is shorter than the cut: [machining] flute_length = {flute:g} (the cut reaches "
                  f"{cut_length_mm:.2f} mm up the tool from its tip)")
    else:
        advice = f"accept a tolerance of at least {holds:g} mm"
    return Check("3-D groove deviation", value, tol, "mm", ok=value <= tol, severity="fail", where=groove.where(),
                 advice=advice)
