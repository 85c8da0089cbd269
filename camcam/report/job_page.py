"""The machinist's tolerance report: ``<name>-report.html`` and the figures of ``<name>-report.json``.

Assembled from the values the stages returned (no stage is re-run here except
the as-machined follower motion, which is the report's own analysis).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.geometry.analysis import radius_text
from camcam.geometry.build import BuiltCam
from camcam.geometry.disc import DiscCam
from camcam.geometry.groove import GrooveCam
from camcam.motion.program import MotionProgram
from camcam.workers import Pending, call_target, later
from camcam.report.deviation_along import signed_deviation
from camcam.report.fitted_motion import fitted_motion
from camcam.report.html import Code, DataTable, Figure, KeyValues, Paragraph, Section, VerdictBlock, render_html
from camcam.report.setup_sheet import setup_blocks
from camcam.verdict import Verdict
from camcam.report.inspection import inspection_table
from camcam.report.material import material_section
from camcam.nc.result import MachiningResult

__all__ = ["JobReport", "job_report", "ReportAnalysis", "report_analysis", "render_later", "GROOVE_MAP_PLOT", "DEVIATION_PLOT", "FITTED_MOTION_PLOT"]

#: The report's plots, as ``"module:function"`` names: they are drawn where matplotlib is imported (a
#: child process, camcam.workers), never in the process assembling the report.
GROOVE_MAP_PLOT = "camcam.plots.groove_map:groove_map_png"
DEVIATION_PLOT = "camcam.plots.report_plots:deviation_png"
FITTED_MOTION_PLOT = "camcam.plots.report_plots:fitted_motion_png"


def render_later(target: str, *args, **kwargs) -> Pending | bytes:
    """Draw the plot ``target`` (``"module:function"``) in a forked child (:func:`camcam.workers.later`)."""
    return later(call_target, target, *args, **kwargs)


@dataclass(frozen=True)
class JobReport:
    html: str
    figures: dict  # extra JSON keys
    files: dict  # name → bytes, or Pending for a plot being drawn (also shown in the HTML), and the inspection CSV


def _job_rows(name, spec, built: BuiltCam | None, m: MachiningResult | None):
    rows = [("job", name), ("cam speed", f"{spec.motion.rpm:g} rev/min")]
    if built is not None:
        c, cam = built.spec, built.cam
        rows += [("cam", f"{c.kind}, base radius {c.base_radius:g} mm, rotation {cam.rotation}"),
                 ("follower", f"{cam.kind}, roller radius {cam.roller_radius:g} mm" if cam.roller_radius else cam.kind)]
    if m is not None:
        ms = spec.machining
        rows += [
            ("post", f"{m.post.name} ({m.post.description})"), ("program", m.program_filename),
            ("tool", f"Ø{m.tool_diameter_mm:g} mm"), ("tolerance", f"±{m.tolerance_mm:g} mm, two-sided, on the printed program"),
            ("mode", m.mode),
            *((("feed", f"{ms.feed_mm_min:g} mm/min"), ("spindle", f"{ms.spindle_rpm:g} rev/min")) if not ms.cutting
              else (("feed and spindle", "per pass kind: the setup sheet's cutting data"),)),
            ("depth / stepdown", f"{ms.depth_mm:g} / {ms.stepdown_mm:g} mm"),
        ]
    return tuple(rows)


def _deviation_label(m: MachiningResult) -> str:
    if m.groove is None:
        return "measured deviation (two-sided, printed program)"
    return "3-D groove deviation (both walls, every radius, printed program)"


def _groove_rows(m: MachiningResult) -> tuple:
    if m.groove is None:
        return ()
    rows = []
    for w in m.groove.walls:
        rows.append((w.label, f"largest overcut {w.overcut_mm:.4f} mm at {w.overcut.describe()}; largest material "
                              f"left {w.material_left_mm:.4f} mm at {w.material_left.describe()}"))
    g = m.groove
    rows.append(("3-D measurement", f"radii {g.radii_mm[0]:g}-{g.radii_mm[-1]:g} mm ({len(g.radii_mm)} on the map, "
                                    f"extremes refined between), cam angle step {g.cam_angle_deg[1]:g}°, motion "
                                    f"sampling bound {g.sampling_bound_mm:.1e} mm (pose step {g.pose_step_mm:g} mm), "
                                    f"added to the walls' largest {g.measured_mm:.4f} mm in the deviation held to "
                                    f"the tolerance"))
    if m.smallest_tool_mm is not None:
        rows.append(("smallest tool holding half the tolerance on the flanks", f"Ø{m.smallest_tool_mm:.2f} mm"))
    return tuple(rows)


@dataclass(frozen=True)
class ReportAnalysis:
    """The report's own analyses of the printed program, with their plots and figures.

    They need the fitted contours and the program but not the material check,
    so `camcam run` computes them while the check runs in a child process.
    """

    files: dict  # name → bytes or Pending (plots being drawn), the inspection CSV
    figures: dict  # extra JSON keys
    tolerance_figures: tuple  # blocks of the Tolerance section: the groove map, the deviation along the profile
    sections: tuple  # the follower motion as machined, the inspection table


def report_analysis(name: str, built: BuiltCam | None, machining: MachiningResult | None,
                    inspection_step_deg: float = 10.0, render=render_later) -> ReportAnalysis:
    """The deviation along the profile, the follower motion as machined and the inspection table.

    ``render(target, *args)`` draws a plot (PNG bytes, or a :class:`~camcam.workers.Pending`): by
    default in a forked child of its own; `camcam run` passes its plot server's ``submit``.
    """
    files: dict = {}
    figures: dict = {}
    blocks, sections = [], []
    disc = built.cam if built is not None and isinstance(built.cam, (DiscCam, GrooveCam)) else None
    if machining is not None:
        m = machining
        if m.groove is not None:
            png = render(GROOVE_MAP_PLOT, m.groove, m.tolerance_mm,
                         f"{name}: cut groove − designed groove, normal to the walls")
            files[f"{name}-groove-map.png"] = png
            blocks.append(Figure(png, "3-D deviation of the cut groove walls from the designed walls (the roller's "
                                      "envelope), over radius and cam angle, measured on the printed program's axis "
                                      "words: + overcut, − material left."))
        if disc is not None:
            curve, elements = m.contours[0].curve, m.contours[0].printed
            ang = np.arange(0.0, 360.0, 0.25)
            th = np.radians(ang)
            # the sign (+ leaves stock) needs the material side: known for a disc's outside contour;
            # a groove's flanks are drawn unsigned
            normal = disc.normal(th) if isinstance(disc, DiscCam) else None
            dev = signed_deviation(curve, elements, th, normal)
            files[f"{name}-deviation.png"] = render(DEVIATION_PLOT, ang, dev, m.tolerance_mm,
                                                    f"{name}: printed tool path − exact tool-centre curve")
            blocks.append(Figure(files[f"{name}-deviation.png"], "Deviation of the printed tool path from the exact tool-centre curve along the cam angle (+ leaves stock)."))
            figures["deviation_along_profile_mm"] = {"min": float(dev.min()), "max": float(dev.max())}
        if isinstance(disc, DiscCam):
            c0 = m.contours[0]
            fm = fitted_motion(disc, c0.printed, c0.offset_mm, np.arange(0.0, 360.0, 0.5))
            png = render(FITTED_MOTION_PLOT, fm.angles_deg, fm.design, fm.fitted, fm.units,
                         f"{name}: follower motion the fitted program will produce")
            files[f"{name}-fitted-motion.png"] = png
            ea, aa = fm.max_error(2)
            ej, aj = fm.max_error(3)
            el, al = fm.max_error(0)
            figures["fitted_motion"] = {
                "max_lift_error": el, "max_lift_error_at_deg": al,
                "max_acceleration_error": ea, "max_acceleration_error_at_deg": aa,
                "max_jerk_error": ej, "max_jerk_error_at_deg": aj,
                "units": list(fm.units), "contact_changes": fm.contact_changes,
            }
            sections.append(Section("Follower motion as machined", (
                Paragraph("The motion the follower will actually make on the cam cut by this program: the kinematics "
                          "solved against every printed arc and line. An arc spline has piecewise-constant curvature, so the "
                          "acceleration is a staircase around the design and the jerk is impulsive at every join; a finer "
                          "tolerance makes the steps smaller."),
                Figure(png, "Design (black) and as-machined (red) lift, velocity, acceleration and jerk."),
                KeyValues((
                    ("largest lift error", f"{el:.5f} {fm.units[0]} at {al:g}°"),
                    ("largest acceleration error", f"{ea:.4g} {fm.units[2]} at {aa:g}°"),
                    ("largest jerk error", f"{ej:.4g} {fm.units[3]} at {aj:g}°"),
                    ("contact changes (acceleration steps) per revolution", str(fm.contact_changes)),
                )),
            )))
    if disc is not None:
        tol = machining.tolerance_mm if machining is not None else 0.0
        table = inspection_table(built.cam, tol, inspection_step_deg)
        files[f"{name}-inspection.csv"] = table.csv().encode()
        sections.append(Section(f"Inspection table (every {inspection_step_deg:g}°)", (
            Paragraph("Profile point in the cam frame (drawing at cam angle 0), its radius from the cam centre, the outward "
                      "normal direction, the roller centre, the nominal lift and the tolerance band along the normal. "
                      f"Also written as {name}-inspection.csv."),
            DataTable(table.header, tuple(table.rows())),
        )))
    return ReportAnalysis(files, figures, tuple(blocks), tuple(sections))


def job_report(name: str, spec, program: MotionProgram, svaj: bytes | Pending, built: BuiltCam | None, cam_figures: dict,
               cam_png: bytes | Pending | None, machining: MachiningResult | None, inspection_step_deg: float = 10.0,
               verdict: Verdict | None = None, render=render_later,
               analysis: ReportAnalysis | None = None) -> JobReport:
    """Build the HTML page, the report's extra JSON figures and its files; the verdict opens the page.

    ``analysis`` is :func:`report_analysis` of the same job when the caller has it already (computed
    with ``render``, and ``inspection_step_deg``, otherwise).
    """
    if analysis is None:
        analysis = report_analysis(name, built, machining, inspection_step_deg, render)
    files: dict = dict(analysis.files)
    figures: dict = dict(analysis.figures)
    # the verdict and the setup are the setup sheet: printed alone on page 1 (report/html.py)
    sections = [Section("Verdict", (VerdictBlock(verdict),), sheet=True)] if verdict is not None else []
    if machining is not None and built is not None:
        sections.append(Section("Setup", setup_blocks(built, machining, spec.machining), sheet=True))
    sections.append(Section("Job", (KeyValues(_job_rows(name, spec, built, machining)),)))
    sections.append(Section("Motion (design)", (Figure(svaj, "Displacement, velocity, acceleration and jerk over the revolution; dashed: segment boundaries."),)))
    if built is not None:
        blocks = []
        if cam_png is not None:
            blocks.append(Figure(cam_png, "The cam at cam angle 0 with pitch curve, base circle and roller; pressure angle and radius of curvature."))
        rows = [("largest pressure angle", f"{cam_figures['max_pressure_angle_deg']:.3f}° at {cam_figures['max_pressure_angle_at_deg']:.2f}°"),
                ("smallest convex radius of curvature", radius_text(cam_figures["min_curvature_radius_mm"], cam_figures["min_curvature_radius_at_deg"]))]
        blocks.append(KeyValues(tuple(rows)))
        sections.append(Section("Cam", tuple(blocks)))
    if machining is not None:
        m = machining
        verdict = "within" if m.max_deviation_mm <= m.tolerance_mm else "OUTSIDE"
        fit_kind = "fit deviation (developed plane)" if m.groove is not None else "deviation"
        blocks = [KeyValues((
            (_deviation_label(m), f"{m.max_deviation_mm:.5f} mm — {verdict} ±{m.tolerance_mm:g} mm"),
            *_groove_rows(m),
            ("blocks on the contour", f"{m.arc_blocks} arcs + {m.line_blocks} lines"),
            ("lower bound (N_lb; lines: ∫√(κ/8δ) ds)", f"{m.lower_bound_blocks:.1f}"),
            *((f"contour {c.label}", f"{c.fit.arc_blocks} arcs + {c.fit.line_blocks} lines, {fit_kind} "
               f"{c.deviation.max_deviation_mm:.5f} mm") for c in m.contours),
            *(("note", n) for n in m.notes),
        ))]
        blocks += analysis.tolerance_figures
        excerpt = m.program.text.splitlines()[:24]
        blocks.append(Code("\n".join(excerpt), f"The first {len(excerpt)} lines of {m.program_filename}."))
        sections.append(Section("Tolerance", tuple(blocks)))
        material = material_section(m)
        if material is not None:
            sections.append(material)
    sections += analysis.sections
    html = render_html(f"{name}: tolerance report", "camcam — cam, NC program and inspection data", sections)
    return JobReport(html, figures, files)
