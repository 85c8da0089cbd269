"""The report's dynamics section: forces, torque, contact stress, jump speed and the spring (issue 45)."""

from __future__ import annotations

from dataclasses import replace

from camcam.dynamics.train import MATERIAL_SOURCE
from camcam.report.html import Figure, KeyValues, Paragraph, Section

__all__ = ["dynamics_section", "with_dynamics", "DYNAMICS_PLOT"]

#: The plot's function (drawn where matplotlib is imported: the plot server).
DYNAMICS_PLOT = "camcam.plots.dynamics_plot:dynamics_png"


def _at(value: float, unit: str, angle: float | None, fmt: str = ".4g") -> str:
    return f"{value:{fmt}} {unit}" + (f" at {angle:.2f}°" if angle is not None else "")


def dynamics_section(dyn, png) -> Section:
    """The section for a :class:`~camcam.dynamics.cycle.Dynamics` with its plot (PNG bytes or pending)."""
    d = dyn.spec
    rows = [("cam speed", f"{dyn.rpm:g} rev/min")]
    if dyn.positive_drive:
        rows.append(("drive", "positive (grooved cam): no spring, the follower cannot jump"))
        rows.append(("largest force, lift flank", f"{dyn.lift_flank_force_n.max():.4g} N"))
        rows.append(("largest force, return flank", f"{dyn.return_flank_force_n.max():.4g} N"))
    else:
        spring = f"{d.spring_rate_n_per_mm:g} N/mm, preload {d.preload_n:g} N"
        rows.append(("spring", spring + (" (sized)" if dyn.spring_sized else "")))
        if dyn.spring_sized:
            rows.append(("spring sizing rule", dyn.spring_rule))
        rows.append(("largest contact force", _at(dyn.max_contact_force_n, "N", dyn.max_contact_force_angle_deg)))
        rows.append(("least contact force", _at(dyn.min_contact_force_n, "N", dyn.min_contact_force_angle_deg)))
        jump = ("never (the contact force stays positive at every speed)" if dyn.jump_rpm is None else
                _at(dyn.jump_rpm, "rev/min", dyn.jump_angle_deg, ".5g") + f" ({dyn.jump_rpm / dyn.rpm:.3g} × the cam "
                f"speed; held to {d.overspeed:g} ×)")
        rows.append(("jump speed (the follower first leaves the cam)", jump))
    rows += [
        ("largest camshaft torque", _at(dyn.max_torque_nm, "N·m", dyn.max_torque_angle_deg)),
        ("RMS camshaft torque", f"{dyn.rms_torque_nm:.4g} N·m"),
        ("mean / peak power", f"{dyn.mean_power_w:.4g} W / {dyn.max_power_w:.4g} W"),
        ("flywheel for the speed fluctuation", f"{dyn.flywheel_inertia_kgm2:.4g} kg·m² for C_s = {d.speed_fluctuation:g} "
                                               f"(energy swing {dyn.energy_fluctuation_j:.4g} J)"),
        ("largest Hertz contact stress", _at(dyn.max_contact_stress_mpa, "MPa", dyn.max_contact_stress_angle_deg)
         + (f" (allowable {d.allowable_contact_stress_mpa:g} MPa)" if d.allowable_contact_stress_mpa else "")),
        ("contact", f"length {dyn.contact_length_mm:g} mm, E* {dyn.contact_modulus_mpa:.5g} MPa: cam "
                    f"{d.cam_material.describe()}, follower {d.follower_material.describe()}"),
        ("material data", MATERIAL_SOURCE),
    ]
    text = ("The follower train as one mass, spring and damper (Norton, Cam Design and Manufacturing Handbook): the "
            "force along the follower is m·a + c·v + k·(s + x₀) + F_ext (moments about the pivot for an oscillating "
            "follower), the contact force acts along the contact normal, the torque is its moment about the cam axis, "
            "and the contact stress is Hertz's line contact of the roller (or flat face) on the profile's curvature.")
    return Section("Dynamics", (Paragraph(text), Figure(png, "Contact force, camshaft torque and Hertz contact stress "
                                                             "over the cam angle."), KeyValues(tuple(rows))))


def with_dynamics(analysis, name: str, dyn, render):
    """The report analysis (:func:`camcam.report.job_page.report_analysis`'s value) with the dynamics section
    and its plot ``<name>-dynamics.png``, before the inspection table."""
    title = f"{name}: forces at {dyn.rpm:g} rpm"
    png = render(DYNAMICS_PLOT, dyn.cam_angle_deg, dyn.contact_force_n, dyn.torque_nm, dyn.contact_stress_mpa, title,
                 return_flank_n=dyn.return_flank_force_n if dyn.positive_drive else None,
                 allowable_mpa=dyn.spec.allowable_contact_stress_mpa,
                 jump_angle_deg=None if dyn.positive_drive or dyn.jump_rpm is None or dyn.jump_rpm > dyn.rpm
                 else dyn.jump_angle_deg)
    files = dict(analysis.files)
    files[f"{name}-dynamics.png"] = png
    section = dynamics_section(dyn, png)
    rest = [s for s in analysis.sections if not s.title.startswith("Inspection table")]
    last = [s for s in analysis.sections if s.title.startswith("Inspection table")]
    return replace(analysis, files=files, sections=tuple(rest) + (section,) + tuple(last))
