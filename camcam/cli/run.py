"""``camcam run SPEC -o DIR``: the whole flow for one spec.

Motion stage (table, SVAJ plot, summary); with ``[cam]`` and ``[follower]``
tables also the cam geometry: ``<name>.stl``, ``<name>-profile.png`` and
``<name>-report.json``; with ``[machining]`` also the NC program
(``<name>.<post extension>``) and ``<name>.dxf`` (:func:`nc_step`).
"""

from __future__ import annotations

from pathlib import Path

from camcam.cli.motion import motion_outputs, motion_summary, print_summary
from camcam.cli.output import print_json, to_json, warn
from camcam.export.files import OutputSet
from camcam.spec import load_spec

__all__ = ["register", "nc_step"]


def nc_step(out: OutputSet, spec, built, report: dict):
    """The NC step: machine ``built`` per ``spec.machining``, add the program and DXF to ``out``
    and the figures to ``report``; returns the :class:`~camcam.toolpath.machining.MachiningResult`."""
    from camcam.export.nc import machining_report, nc_files
    from camcam.toolpath.machining import machine

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
    p = sub.add_parser("run", help="run the whole flow for a spec")
    p.add_argument("spec", help="spec file (TOML)")
    p.add_argument("-o", "--output", default="camcam-out", help="output directory (default ./camcam-out)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = load_spec(args.spec)
    program = spec.need("motion", "run").program(spec.unit)
    for j in program.joins:
        warn(j.describe())
    out = OutputSet(Path(args.output))
    motion_outputs(out, spec.name, program, 0.5)
    summary = {"name": spec.name, "motion": motion_summary(program)}
    if spec.cam is not None:
        from camcam.export.cam_report import cam_report
        from camcam.export.stl import stl_bytes
        from camcam.geometry.build import build_cam
        from camcam.plots.profile import cam_png

        built = build_cam(spec.cam, spec.follower, program)
        report = cam_report(built)
        if spec.machining is not None:
            nc_step(out, spec, built, report)
        out.add(f"{spec.name}.stl", stl_bytes(built.mesh))
        out.add(f"{spec.name}-profile.png", cam_png(built, f"{spec.name}: {spec.cam.kind} cam, {built.cam.kind} follower"))
        out.add(f"{spec.name}-report.json", to_json(report) + "\n")
        summary["cam"] = report
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
