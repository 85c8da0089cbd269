"""Tool-size rules of a machining job: which tools can cut a profile or a groove, and how.

A disc profile's concave parts need a tool radius below their smallest
radius of curvature.  A groove (face groove or barrel cam) is as wide as the
roller: a tool of the roller's size cuts it in one centre pass; a narrower one
cuts a centre pass and then each flank; a tool below a third of the groove
width would leave a band between those passes.
"""

from __future__ import annotations

import math

from camcam.errors import GeometryError

__all__ = ["SAME_TOOL_MM", "check_profile_tool", "groove_passes", "job_title"]

#: A tool whose diameter is within this of the groove width counts as the roller's size (mm).
SAME_TOOL_MM = 1e-6


def check_profile_tool(tool_radius_mm: float, min_concave) -> None:
    """Refuse a tool too large for the profile's smallest concave radius (``min_concave``: an extreme or None).

    Examples
    --------
    >>> check_profile_tool(8.0, None)  # a convex profile takes any tool
    """
    if min_concave is not None and tool_radius_mm >= min_concave.value:
        raise GeometryError(f"machining.tool_diameter: {2 * tool_radius_mm:g} mm is too large: the profile's smallest "
                            f"concave radius is {min_concave.value:.3f} mm at cam angle {min_concave.angle_deg:.2f}°; "
                            f"expected a tool radius below it")


def groove_passes(tool_radius_mm: float, roller_radius_mm: float, thinnest_mm=None) -> str:
    """How a groove as wide as the roller is cut: ``"centre"`` or ``"centre+flanks"``.

    ``thinnest_mm``, optional: a callable giving the thinnest tool diameter (mm) that a rule of the caller's own
    holds (a barrel's flank error, :func:`camcam.nc.flank.smallest_tool_radius`), asked only to advise a tool
    below a third of the width: the advice names the larger of the two, so that following it does not end at
    the caller's rule (campaign case 47:1: "expected at least 8 mm", where the 3-D check then asked 15.58 mm).

    Raises
    ------
    GeometryError
        A tool wider than the groove, or below a third of its width.

    Examples
    --------
    >>> groove_passes(10.0, 10.0), groove_passes(6.0, 10.0)
    ('centre', 'centre+flanks')
    """
    r_t, r_r = tool_radius_mm, roller_radius_mm
    if r_t > r_r + SAME_TOOL_MM:
        raise GeometryError(f"machining.tool_diameter: {2 * r_t:g} mm is wider than the groove ({2 * r_r:g} mm, "
                            f"twice the roller radius); expected at most {2 * r_r:g} mm (the roller's diameter cuts "
                            f"the groove in one centre pass)")
    if abs(r_t - r_r) <= SAME_TOOL_MM:
        return "centre"
    if 3 * r_t < r_r - 1e-9:  # 1e-9 mm: a third typed as advised (10.2 of 30.6 mm: 3 x 5.1 = 15.299999999999999)
        smallest = math.ceil(2 * r_r / 3 * 100 - 1e-9) / 100  # a third of the width, rounded up to 0.01 mm
        why = ""
        if thinnest_mm is not None:
            held = math.ceil(thinnest_mm() * 100 - 1e-9) / 100  # as the 3-D check's note rounds it
            if held > smallest:
                smallest, why = held, "; a thinner tool's flank passes would miss half the tolerance"
        raise GeometryError(f"machining.tool_diameter: {2 * r_t:g} mm is below a third of the groove width "
                            f"{2 * r_r:g} mm: a centre pass and two flank passes would leave material between them; "
                            f"expected at least {smallest:g} mm (up to the roller's {2 * r_r:g} mm){why}")
    return "centre+flanks"


def job_title(name: str, cam_kind: str, follower_kind: str, tool_diameter_mm: float, mode: str,
              tolerance_mm: float, post_name: str) -> str:
    """The program's title line.

    Examples
    --------
    >>> job_title("c", "disc", "translating-roller", 16, "arcs", 0.01, "linuxcnc")
    'c: disc cam, translating-roller follower, tool D16 mm, arcs within 0.01 mm, post linuxcnc'
    """
    return (f"{name}: {cam_kind} cam, {follower_kind} follower, tool D{tool_diameter_mm:g} mm, "
            f"{mode} within {tolerance_mm:g} mm, post {post_name}")
