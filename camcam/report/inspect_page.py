"""The inspection report of `camcam inspect`: the verdict, the deviation plots, the worst points, the
alignment and the motion errors, as a self-contained HTML page and a JSON object."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.export.figures import fixed
from camcam.geometry.cylindrical import CylindricalCam
from camcam.plots.inspect_plots import deviation_along_png, exaggeration, motion_error_png, polar_deviation_png
from camcam.report.html import DataTable, Figure, KeyValues, Paragraph, Section, VerdictBlock, render_html
from camcam.verdict import Check, Verdict

__all__ = ["InspectionReport", "inspection_report"]

_KIND_TEXT = {"cmm": "CMM points on the profile", "dial": "dial-indicator readings",
              "barrel": "points on the groove walls"}


@dataclass(frozen=True, kw_only=True)
class InspectionReport:
    """The files (name → bytes or text) and the JSON summary."""

    files: dict
    summary: dict
    verdict: Verdict


def _outline(cam, n: int = 1440):
    """The nominal outline the polar plot draws around (cam frame, xy) with its outward normals, and the
    2-D foot and normal of a point at cam angle θ: the profile for a disc; the cylinder's circle seen along
    the cam axis for a barrel (cam angle as polar angle, deviation radial)."""
    th = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    if isinstance(cam, CylindricalCam):
        circle = np.stack([np.cos(th), np.sin(th)], axis=-1)

        def at(theta):
            c = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
            return cam.base_radius * c, c

        return cam.base_radius * circle, circle, at, 2 * cam.base_radius
    prof = cam.profile.evaluate(th)
    size = float(np.ptp(prof, axis=0).max())
    return prof, cam.normal(th), (lambda theta: (cam.profile.evaluate(theta), cam.normal(theta))), size


def _motion_summary(ins) -> list[dict]:
    return [dict({"wall": m.wall, "unit": m.unit}, **m.errors) for m in ins.motion]


def inspection_report(ins, cam, name: str, spec_name: str, predicted=None) -> InspectionReport:
    """Files ``report.html``, ``report.json`` and the plots for the :class:`~camcam.inspect.Inspection`
    ``ins`` of the built ``cam``; ``predicted`` (angles, deviation): the NC program's own deviation."""
    from camcam.export.jsontext import to_json

    al = ins.alignment
    w = ins.worst_index
    wall = ins.wall
    check = Check("measured deviation", float(abs(ins.deviation_mm[w])), ins.tolerance_mm, "mm", ok=ins.passed,
                  where=f"{ins.source} row {ins.rows[w]}, cam angle {ins.angle_deg[w]:.2f}°"
                        + (f", wall {int(wall[w])}" if wall is not None else ""),
                  advice="re-cut or re-measure the part there")
    verdict = Verdict((check,))
    worst = ins.worst(10)
    summary = {
        "verdict": ins.verdict,
        "kind": ins.kind,
        "points": int(len(ins.deviation_mm)),
        "points_kept": int(ins.kept.sum()),
        "tolerance_mm": ins.tolerance_mm,
        "max_deviation_mm": ins.max_deviation_mm,
        "min_deviation_mm": ins.min_deviation_mm,
        "worst_deviation_mm": float(ins.deviation_mm[w]),
        "worst_angle_deg": float(ins.angle_deg[w]),
        "worst_row": int(ins.rows[w]),
        "align": al.mode,
        "rotation_deg": al.rotation_deg,
        "rotation_sigma_deg": al.rotation_sigma_deg,
        "translation_mm": al.translation_mm,
        "translation_sigma_mm": al.translation_sigma_mm,
        "noise_sigma_mm": ins.noise_sigma_mm,
        "outliers": [{"row": o.row, "angle_deg": o.angle_deg, "deviation_mm": o.deviation_mm, "score": o.score}
                     for o in ins.outliers],
        "worst_points": [{"row": int(ins.rows[i]), "angle_deg": float(ins.angle_deg[i]),
                          "deviation_mm": float(ins.deviation_mm[i]),
                          **({"wall": int(wall[i])} if wall is not None else {})} for i in worst],
        "max_acceleration_error": ins.max_acceleration_error,
        "max_acceleration_error_unit": f"{ins.motion[0].unit}/deg²" if ins.motion else None,
        "motion": _motion_summary(ins),
    }
    if al.zero_mm is not None:
        summary["reading_zero_mm"] = al.zero_mm
    if ins.bore is not None:
        summary["bore"] = ins.bore
    if ins.motion_note is not None:
        summary["motion_note"] = ins.motion_note
    if predicted is not None:
        summary["program_deviation_mm"] = {"min": float(np.min(predicted[1])), "max": float(np.max(predicted[1]))}

    files: dict = {}
    title = f"{spec_name}: {ins.source}"
    files["deviation.png"] = deviation_along_png(ins.angle_deg, ins.deviation_mm, ins.outlier, ins.tolerance_mm, w,
                                                 wall, predicted, f"{title}: measured − design, normal to the surface")
    outline, outline_n, at, size = _outline(cam)
    foot, normal = at(np.radians(ins.angle_deg))
    kept_dev = np.abs(ins.deviation_mm[ins.kept])
    factor = exaggeration(size, max(float(kept_dev.max()), ins.tolerance_mm))
    labels = (("cam angle as polar angle, radius = cylinder [mm]", "") if wall is not None else ("x [mm]", "y [mm]"))
    files["polar.png"] = polar_deviation_png(outline, outline_n, foot, normal, ins.deviation_mm, ins.outlier,
                                             ins.tolerance_mm, factor, title, labels)
    summary["polar_exaggeration"] = factor
    if ins.motion:
        files["motion.png"] = motion_error_png(ins.motion, f"{title}: motion of the measured cam − design")

    def mm(v):
        return f"{fixed(v, 4)} mm"

    sections = [Section("Verdict", (VerdictBlock(verdict), Paragraph(ins.worst_line())))]
    sections.append(Section("Deviation", (
        Figure(files["deviation.png"], "Signed normal deviation of each measured point from the exact design surface "
               "along the cam angle (+ material left, − overcut), the tolerance band"
               + (" and the NC program's predicted deviation (printed tool path − exact tool-centre curve)"
                  if predicted is not None else "") + "."),
        Figure(files["polar.png"], f"The measured points around the part, their deviations drawn × {factor:g} "
               f"(1 mm on the drawing is {1000 / factor:g} µm of deviation); grey: the tolerance band at the same scale."
               + (" Barrel: the cylinder seen along the cam axis, each point at its cam angle." if wall is not None else "")),
        KeyValues((("measured", f"{len(ins.deviation_mm)} {_KIND_TEXT[ins.kind]} ({ins.source})"),
                   ("kept / outliers", f"{int(ins.kept.sum())} / {len(ins.outliers)}"),
                   ("largest deviation", mm(ins.max_deviation_mm)), ("smallest deviation", mm(ins.min_deviation_mm)),
                   ("tolerance", f"±{ins.tolerance_mm:g} mm"),
                   ("measuring noise (seed 004 estimate)", f"σ {fixed(ins.noise_sigma_mm, 5)} mm"))),
    )))
    head = ("row", "cam angle [deg]", "deviation [mm]") + (("wall",) if wall is not None else ())
    rows = tuple((str(ins.rows[i]), fixed(ins.angle_deg[i], 2), fixed(ins.deviation_mm[i], 4))
                 + ((str(int(wall[i])),) if wall is not None else ()) for i in worst)
    sections.append(Section("Worst 10 points", (DataTable(head, rows),)))
    orow = tuple((str(o.row), fixed(o.angle_deg, 2), fixed(o.deviation_mm, 4), fixed(o.score, 1)) for o in ins.outliers)
    sections.append(Section("Outliers", (
        Paragraph("Points seed 004's bad-point test flags against their neighbours (score: deviation from the cubic "
                  "through two neighbours each side, in units of the noise); listed here and left out of the alignment "
                  "and the verdict." if orow else "No outliers: every point is in the verdict."),)
        + ((DataTable(("row", "cam angle [deg]", "deviation [mm]", "score"), orow),) if orow else ())))
    names = {"cmm": "x, y", "dial": "dividing-head axis x, y", "barrel": "x, y, z"}[ins.kind]
    kv = [("mode", al.mode), ("rotation", f"{fixed(al.rotation_deg, 4)}° ± {fixed(al.rotation_sigma_deg, 4)}°"),
          (f"translation ({names})", ", ".join(fixed(v, 4) for v in al.translation_mm) + " mm ± "
           + ", ".join(fixed(v, 4) for v in al.translation_sigma_mm) + " mm"),
          ("points fitted", str(al.points_used))]
    if al.zero_mm is not None:
        kv.append(("reading zero", mm(al.zero_mm)))
    if ins.bore is not None:
        kv.append(("bore centre", ", ".join(fixed(v, 4) for v in ins.bore["centre_mm"]) + " mm ± "
                   + ", ".join(fixed(v, 4) for v in ins.bore["centre_sigma_mm"]) + f" mm (Ø{fixed(2 * ins.bore['radius_mm'], 4)} mm)"))
    sections.append(Section("Alignment", (
        Paragraph("Least squares on the normal deviations (robust soft-L1 loss, outliers left out); the uncertainty "
                  "is one standard deviation from the Jacobian. Rotation + by the right-hand rule about the cam axis, "
                  "applied to the measured points; a fitted rotation over --max-rotation is refused."),
        KeyValues(tuple(kv)))))
    blocks: list = []
    if ins.motion:
        blocks.append(Figure(files["motion.png"], "Lift, velocity and acceleration of the motion the measured cam "
                             "produces (seed 002's reverse fit of the aligned points) minus the design."))
        mrows = []
        for m in ins.motion:
            at_ = m.errors["max_error_at_deg"]
            for k, key in enumerate(("lift", "velocity", "acceleration")):
                unit = [m.unit, f"{m.unit}/deg", f"{m.unit}/deg²"][k]
                mrows.append(("—" if m.wall is None else str(m.wall), key,
                              f"{m.errors[f'max_{key}_error']:.4g} {unit}", fixed(at_[key], 1)))
        blocks.append(DataTable(("wall", "motion", "largest error", "at cam angle [deg]"), tuple(mrows)))
    if ins.motion_note:
        blocks.append(Paragraph(ins.motion_note))
    sections.append(Section("Motion errors", tuple(blocks)))
    files["report.html"] = render_html(f"{spec_name}: inspection {ins.verdict}",
                                       f"{ins.source}: {_KIND_TEXT[ins.kind]}, alignment {al.mode}", sections)
    files["report.json"] = to_json(summary) + "\n"
    return InspectionReport(files=files, summary=summary, verdict=verdict)
