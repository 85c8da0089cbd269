"""Design checks of a job: figures a designer should see before cutting, each held to a limit.

* pressure angle over ``[cam] max_pressure_angle_deg`` (default 30° for a
  translating follower, 35° for an oscillating one, the usual rules of thumb);
* the profile's smallest convex radius of curvature below ``[cam]
  min_curvature_radius_mm`` (default half the roller radius: the pitch curve
  bends at least 1.5 roller radii, the usual rule for contact stress; 0 for a
  flat face, whose cusp is refused as bad input anyway);
* a cut depth beyond the part: below a disc's bottom face (into the fixture)
  or below a face groove's floor (a barrel's is the job's check on its
  printed program, :mod:`camcam.verify.reach`);
* a finishing allowance larger than the stepdown (the finish pass would take
  more side stock than a roughing pass takes depth).

Each is a warning (``severity="warn"``: the verdict says WARN, the run exits
0); the two design limits (pressure angle and curvature) fail the run (exit 3)
with ``[cam] design_limits = "fail"``, every check with ``[report] strict =
true``.  A missed design limit's advice names the base radius that meets it
(:func:`base_radius_meeting`), measured on the cam rebuilt at that radius.

Examples
--------
>>> default_max_pressure_angle_deg("translating-roller"), default_max_pressure_angle_deg("oscillating-flat")
(30.0, 35.0)
"""

from __future__ import annotations

from camcam.geometry.analysis import analyse, analyse_cylindrical, max_pressure_angle
from camcam.geometry.followers import follower_kind
from camcam.geometry.resize import base_radius_advice, base_radius_meeting, is_barrel
from camcam.verdict import Check

__all__ = ["design_checks", "default_max_pressure_angle_deg", "default_min_curvature_radius_mm", "base_radius_meeting"]

#: The default least radius of curvature of a roller follower's profile, in roller radii (pitch curve: 1.5).
CURVATURE_ROLLERS = 0.5


def default_max_pressure_angle_deg(kind: str) -> float:
    """30° for translating followers, 35° for oscillating ones (the kind's ``default_max_pressure_angle_deg``)."""
    return follower_kind(kind).default_max_pressure_angle_deg


def default_min_curvature_radius_mm(roller_radius_mm: float) -> float:
    """Half the roller radius (the pitch curve then bends at least 1.5 roller radii); 0 for a flat face."""
    return CURVATURE_ROLLERS * roller_radius_mm


def _analysis(cam):

    return analyse_cylindrical(cam) if is_barrel(cam) else analyse(cam)


def _limit_advice(cam, margin, what: str, other: str, fails: bool, strict: bool) -> str:
    r = base_radius_meeting(cam, margin)
    fix = f"{base_radius_advice(cam, r)} {what}" if r is not None else f"a larger cam.base_radius {what}"
    text = f"{fix}; or {other}"
    if fails:
        text += (", or accept it as a warning with [cam] design_limits = \"warn\"" if not strict else
                 ", or accept it as a warning with [report] strict = false and [cam] design_limits = \"warn\"")
    return text


def design_checks(built, machining=None, strict: bool = False) -> tuple[Check, ...]:
    """The checks of a built cam and its ``[machining]`` table (None: the design limits only)."""
    severity = "fail" if strict else "warn"
    spec, cam = built.spec, built.cam
    limits = "fail" if strict or getattr(spec, "design_limits", "warn") == "fail" else "warn"
    pa = built.analysis.max_pressure_angle_deg
    limit = spec.max_pressure_angle_deg if spec.max_pressure_angle_deg is not None \
        else default_max_pressure_angle_deg(cam.kind)
    pa_ok = pa.value <= limit + 1e-9  # a limit met to the 9th digit (the fix is measured with the same figure)
    advice = "" if pa_ok else _limit_advice(
        built.cam, lambda c: limit + 1e-9 - max_pressure_angle(c).value, f"brings it within {limit:g}°",
        "lengthen the rise angle, or offset the follower", limits == "fail", strict)
    checks = [Check("pressure angle", pa.value, limit, "deg", ok=pa_ok, severity=limits,
                    where=f"program angle {pa.angle_deg:.2f}°, {cam.kind} follower", advice=advice)]
    rho = built.analysis.profile
    rho_min = getattr(spec, "min_curvature_radius_mm", None)
    roller = getattr(cam, "roller_radius", 0.0) or 0.0
    rho_limit = rho_min if rho_min is not None else default_min_curvature_radius_mm(roller)
    rho_ok = rho.min_radius_mm >= rho_limit - 1e-9
    advice = "" if rho_ok else _limit_advice(
        built.cam, lambda c: _analysis(c).profile.min_radius_mm - rho_limit + 1e-9, f"brings it to {rho_limit:g} mm",
        "a gentler motion law or a smaller roller" if roller else "a gentler motion law", limits == "fail", strict)
    where = (f"cam angle {rho.at_deg:.2f}°, " if rho.at_deg is not None else "") + \
        ("profile, convex side" if spec.kind != "cylindrical" else "developed flank at the groove bottom, convex side")
    checks.append(Check("radius of curvature", rho.min_radius_mm, rho_limit, "mm", ok=rho_ok, severity=limits,
                        where=where, advice=advice,
                        at_least=True))
    if machining is None:
        return tuple(checks)
    depth = machining.depth_mm
    if spec.kind == "disc":
        checks.append(Check("cut depth", depth, spec.thickness, "mm", ok=depth <= spec.thickness, severity=severity,
                            where=f"part thickness {spec.thickness:g} mm",
                            advice="the tool goes below the bottom face: set [machining] depth to the thickness, "
                            "or mount the blank over a sacrificial plate"))
    elif spec.kind != "cylindrical":
        checks.append(Check("cut depth", depth, spec.groove_depth, "mm", ok=depth <= spec.groove_depth,
                            severity=severity,
                            where=f"groove depth {spec.groove_depth:g} mm",
                            advice="the tool goes below the groove floor: set [machining] depth to the groove depth"))
    # a barrel's cut depth is the job's check, measured on the printed program (camcam.verify.reach): its tool goes
    # below the groove floor by design (4 axes: to the wall corner; 5 axes: the tilted flat end), which the
    # stated depth does not say ("8 mm / 8 mm within" where the flat end dipped 3.9 mm below the floor)
    if spec.kind == "disc":
        a, step = machining.finish_allowance_mm, machining.stepdown_mm
        checks.append(Check("finish allowance", a, step, "mm", ok=a <= step, severity=severity,
                            where=f"stepdown {step:g} mm",
                            advice="keep the finish allowance at most the stepdown (typically 0.2–0.5 mm)"))
    return tuple(checks)
