"""``camcam run [SPEC] -o DIR``: the whole flow for one spec.

Motion (table, SVAJ plot); with ``[cam]`` and ``[follower]`` the cam
(``<name>.stl``, ``<name>-profile.png``, ``<name>-report.json``); with
``[machining]`` the NC program (``<name>.<post extension>``) and
``<name>.dxf`` (:func:`nc_step`); and the tolerance report
``<name>-report.html`` with its plots and inspection table.  Without SPEC
the bundled default job runs.  Everything is written at the end, all or
nothing.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from camcam.cli.output import print_json, to_json, warn
from camcam.cli.progress import step

__all__ = ["register", "nc_step", "job", "DEFAULT_SPEC"]

#: The bundled job `camcam run` runs without a spec.
DEFAULT_SPEC = "default.toml"


def nc_step(out, spec, built, report: dict):
    """The NC step: machine ``built`` per ``spec.machining``, add the program and DXF to ``out``
    and the figures to ``report``; returns the :class:`~camcam.nc.job.MachiningResult`."""
    from camcam.export.nc import machining_report, nc_files
    from camcam.nc.job import machine

    result = machine(built, spec.machining, spec.name)
    for name, data in nc_files(built, result).items():
        out.add(name, data)
    nc = machining_report(result)
    for key in ("tolerance_mm", "max_deviation_mm", "line_blocks", "arc_blocks", "lower_bound_blocks"):
        report[key] = nc[key]
    report["machining"] = nc
    for note in result.notes:
        warn(note)
    return result


def register(sub) -> None:
    p = sub.add_parser("run", help="run the whole flow for a spec (default: the bundled sample job)")
    p.add_argument("spec", nargs="?", help="spec file (TOML); omitted: the bundled default job")
    p.add_argument("-o", "--output", default="camcam-out", help="output directory (default ./camcam-out)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(func=run)


def _load(spec_arg):
    from camcam.spec import load_spec

    if spec_arg is not None:
        return load_spec(spec_arg)
    with resources.as_file(resources.files("camcam.data") / DEFAULT_SPEC) as path:
        return load_spec(path)


def job(spec, out) -> dict:
    """The whole flow for a loaded ``spec``: add every file to ``out`` (not committed) and return the summary.

    `camcam run` and each spec of `camcam batch` go through here.
    """
    from camcam.cli.motion import motion_outputs, motion_summary

    program = spec.need("motion", "run").program(spec.unit)
    for j in program.joins:
        warn(j.describe())
    with step("motion table and plot"):
        svaj = motion_outputs(out, spec.name, program, 0.5)
    summary = {"name": spec.name, "motion": motion_summary(program)}
    if spec.cam is not None:
        from camcam.export.cam_report import cam_report
        from camcam.export.stl import stl_bytes
        from camcam.geometry.build import build_cam
        from camcam.plots.profile import cam_png
        from camcam.report.job import job_report

        with step("cam geometry, analysis and mesh"):
            built = build_cam(spec.cam, spec.follower, program)
            report = cam_report(built)
        machining = None
        if spec.machining is not None:
            with step("NC second fitting and program"):
                machining = nc_step(out, spec, built, report)
        with step("drawing, model and report"):
            out.add(f"{spec.name}.stl", stl_bytes(built.mesh))
            profile_png = cam_png(built, f"{spec.name}: {spec.cam.kind} cam, {built.cam.kind} follower")
            out.add(f"{spec.name}-profile.png", profile_png)
            page = job_report(spec.name, spec, program, svaj, built, report, profile_png, machining,
                              spec.report.inspection_step_deg)
            for name, data in page.files.items():
                out.add(name, data)
            report.update(page.figures)
            out.add(f"{spec.name}-report.html", page.html)
            out.add(f"{spec.name}-report.json", to_json(report) + "\n")
        summary["cam"] = report
    return summary


def run(args) -> int:
    from camcam.cli.motion import print_summary
    from camcam.export.files import OutputSet

    spec = _load(args.spec)
    out = OutputSet(Path(args.output))
    summary = job(spec, out)
    with step("writing files"):
        written = out.commit()
    summary["files"] = [str(p) for p in written]
    if args.json:
        print_json(summary)
    else:
        print_summary(summary["motion"])
        if "cam" in summary:
            c = summary["cam"]
            print(f"max pressure angle {c['max_pressure_angle_deg']:.4f}° at {c['max_pressure_angle_at_deg']:.2f}°; "
                  f"min radius of curvature {c['min_curvature_radius_mm']:.4f} mm at {c['min_curvature_radius_at_deg']:.2f}°")
            if "machining" in c:
                print(f"NC: {c['line_blocks']} line + {c['arc_blocks']} arc blocks (lower bound {c['lower_bound_blocks']:.1f}), "
                      f"max deviation {c['max_deviation_mm']:.4f} mm of {c['tolerance_mm']:g} mm on the printed program")
        for p in written:
            print(f"wrote {p}")
    return 0
