"""Design checks of a job: figures a designer should see before cutting, each held to a limit.

* pressure angle over ``[cam] max_pressure_angle_deg`` (default 30° for a
  translating follower, 35° for an oscillating one, the usual rules of thumb);
* a cut depth beyond the part: below a disc's bottom face (into the fixture)
  or below a groove's floor;
* a finishing allowance larger than the stepdown (the finish pass would take
  more side stock than a roughing pass takes depth).

Each is a warning (``severity="warn"``); with ``[report] strict = true`` a
miss fails the run (exit 3).

Examples
--------
>>> default_max_pressure_angle_deg("translating-roller"), default_max_pressure_angle_deg("oscillating-flat")
(30.0, 35.0)
"""

from __future__ import annotations

from camcam.verdict import Check

__all__ = ["design_checks", "default_max_pressure_angle_deg"]


def default_max_pressure_angle_deg(follower_kind: str) -> float:
    """30° for translating followers, 35° for oscillating ones."""
    return 35.0 if follower_kind.startswith("oscillating") else 30.0


def design_checks(built, machining=None, strict: bool = False) -> tuple[Check, ...]:
    """The checks of a built cam and its ``[machining]`` table (None: the pressure angle only)."""
    severity = "fail" if strict else "warn"
    spec, cam = built.spec, built.cam
    pa = built.analysis.max_pressure_angle_deg
    limit = spec.max_pressure_angle_deg if spec.max_pressure_angle_deg is not None \
        else default_max_pressure_angle_deg(cam.kind)
    checks = [Check("pressure angle", pa.value, limit, "deg", pa.value <= limit, severity,
                    f"program angle {pa.angle_deg:.2f}°, {cam.kind} follower",
                    "raise the base radius, lengthen the rise angle, or offset the follower")]
    if machining is None:
        return tuple(checks)
    depth = machining.depth_mm
    if spec.kind == "disc":
        checks.append(Check("cut depth", depth, spec.thickness, "mm", depth <= spec.thickness, severity,
                            f"part thickness {spec.thickness:g} mm",
                            "the tool goes below the bottom face: set [machining] depth to the thickness, "
                            "or mount the blank over a sacrificial plate"))
    else:
        checks.append(Check("cut depth", depth, spec.groove_depth, "mm", depth <= spec.groove_depth, severity,
                            f"groove depth {spec.groove_depth:g} mm",
                            "the tool goes below the groove floor: set [machining] depth to the groove depth"))
    if spec.kind == "disc":
        a, step = machining.finish_allowance_mm, machining.stepdown_mm
        checks.append(Check("finish allowance", a, step, "mm", a <= step, severity,
                            f"stepdown {step:g} mm",
                            "keep the finish allowance at most the stepdown (typically 0.2–0.5 mm)"))
    return tuple(checks)
