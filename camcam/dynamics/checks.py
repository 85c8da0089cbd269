"""The dynamics' checks for the verdict: contact stress, jump speed and the least contact force.

Each is a design limit: a WARN, or a FAIL with ``[cam] design_limits = "fail"`` (every check with ``[report]
strict = true``), as the pressure angle and curvature checks of :mod:`camcam.nc.design_checks`.
"""

from __future__ import annotations

from camcam.verdict import Check

__all__ = ["dynamics_checks"]


def dynamics_checks(dyn, cam_spec, strict: bool = False) -> tuple[Check, ...]:
    """The checks of a :class:`~camcam.dynamics.cycle.Dynamics` for the cam ``cam_spec`` (its ``design_limits``)."""
    d = dyn.spec
    fails = strict or getattr(cam_spec, "design_limits", "warn") == "fail"
    severity = "fail" if fails else "warn"
    tail = (', or accept it as a warning with [cam] design_limits = "warn"' if fails and not strict else
            ', or accept it as a warning with [report] strict = false and [cam] design_limits = "warn"' if fails else "")
    checks = []
    if d.allowable_contact_stress_mpa is not None:
        p, limit = dyn.max_contact_stress_mpa, d.allowable_contact_stress_mpa
        checks.append(Check("contact stress", p, limit, "MPa", ok=p <= limit, severity=severity,
                            where=f"cam angle {dyn.max_contact_stress_angle_deg:.2f}°, Hertz line contact",
                            advice="a wider or larger roller ([dynamics] roller_width_mm, [follower] roller_radius), "
                            "a larger cam.base_radius, a softer spring or a gentler law, or stronger materials" + tail))
    if dyn.positive_drive:
        return tuple(checks)
    need = d.overspeed * dyn.rpm
    if dyn.jump_rpm is not None:
        checks.append(Check("jump speed", dyn.jump_rpm, need, "rpm", ok=dyn.jump_rpm >= need * (1 - 1e-9),
                            severity=severity,
                            where=f"cam angle {dyn.jump_angle_deg:.2f}°, {d.overspeed:g} × {dyn.rpm:g} rpm",
                            advice='a stiffer spring or more preload ([dynamics] spring = "size" gives the least that '
                            "holds), a lighter follower or a gentler motion law" + tail, at_least=True))
    least = d.min_contact_force_n
    checks.append(Check("contact force", dyn.min_contact_force_n, least, "N",
                        ok=dyn.min_contact_force_n >= least - 1e-9 * max(1.0, dyn.max_contact_force_n),
                        severity=severity,
                        where=f"cam angle {dyn.min_contact_force_angle_deg:.2f}°, at {dyn.rpm:g} rpm",
                        advice="more preload or a stiffer spring" + tail, at_least=True))
    return tuple(checks)
