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

import os
import sys
from importlib import resources

from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, add_verbose_flag, output_set, publish, to_json, warn
from camcam.cli.progress import Progress, add_progress_flag
from camcam.verdict import Verdict

__all__ = ["register", "nc_step", "model", "drawing", "drawing_and_check", "nc_figures", "job_verdict", "design_and_drawing_checks", "job",
           "plot_server", "engagement_phrase", "DEFAULT_SPEC"]

#: The bundled job `camcam run` runs without a spec.
DEFAULT_SPEC = "default.toml"


def nc_step(spec, built):
    """The NC step's program (:func:`camcam.nc.machine_program`), without its material check (see
    :func:`drawing_and_check`)."""
    from camcam.nc import machine_program

    # work that splits into independent parts (a closed contour's further arc starts, a barrel cam's passes
    # and 3-D measurement) is shared with a second process: the same results
    return machine_program(built, spec.machining, spec.name, spec.stock, workers=min(2, _cores()))


def model(built, name: str) -> tuple[dict, dict]:
    """The STL and the mesh's figures: ({file: bytes}, figures).  The mesh is made and trimesh
    imported here: `camcam run` calls this in a child process while the NC step runs (the drawing's
    prepared child when there is a program, see :func:`drawing_and_check`)."""
    from camcam.export.cam_report import mesh_figures
    from camcam.export.stl import program_frame, stl_bytes

    return {f"{name}.stl": stl_bytes(program_frame(built))}, mesh_figures(built)


def drawing(built, machining) -> tuple[dict, float | None]:
    """The program and the DXF with the part outline: ({file: bytes}, the part outline's deviation
    from the design or None).  ezdxf is imported here."""
    from camcam.export.nc import nc_files, part_of

    part = part_of(built, machining)
    return nc_files(built, machining, part), part.deviation_mm


def drawing_and_check(built, machining, machining_spec):
    """:func:`drawing` and the program's material check (:func:`camcam.nc.material_check`, None for a job
    without a blank): (files, part outline deviation, removal report or None).

    `camcam run` calls this in a prepared child (:class:`camcam.servers.Prepared`) that imported ezdxf and
    scipy while the NC step ran: the check runs in a child of its own (which inherits them) beside the
    drawing, so the run's own process never imports scipy."""
    from camcam.forked import ChildGroup, resolve
    from camcam.nc import material_check

    with ChildGroup() as group:
        # the check's slabs are swept by two processes (camcam.nc.sweep): the top slab, which every deeper
        # move cuts too, beside the others
        check = group.later(material_check, machining, built, machining_spec, min(2, _cores())) \
            if machining.blank is not None else None
        files, part_deviation = drawing(built, machining)
        return files, part_deviation, resolve(check)


def nc_figures(report: dict, result, part_deviation_mm: float | None) -> None:
    """Add the NC step's figures to ``report`` and pass its notes on as warnings (stdout; stderr with
    ``--verbose``: :func:`camcam.cli.output.warn`)."""
    nc = result.figures()
    nc["dxf_part_deviation_mm"] = part_deviation_mm
    for key in ("tolerance_mm", "max_deviation_mm", "line_blocks", "arc_blocks", "lower_bound_blocks", "cycle_time_s"):
        report[key] = nc[key]
    report["machining"] = nc
    if "material" in nc:
        report["material"] = nc["material"]
    for note in result.notes:
        warn(note, "note")


def job_verdict(machining, machining_spec) -> Verdict:
    """Every check of the job in one verdict; accepted when the spec accepts out-of-tolerance results."""
    checks = machining.checks if machining is not None else ()
    accepted = machining_spec.accept_out_of_tolerance if machining_spec is not None else False
    return Verdict(tuple(checks), accepted)


def design_and_drawing_checks(built, machining, machining_spec, strict: bool, part_deviation_mm: float | None):
    """The DXF part outline against the tolerance and the design checks (:mod:`camcam.nc.design_checks`:
    WARN, or FAIL with ``[cam] design_limits = "fail"`` for the design limits, ``[report] strict`` for all)."""
    from camcam.nc.design_checks import design_checks
    from camcam.verdict import Check

    checks = []
    if part_deviation_mm is not None:
        checks.append(Check("DXF part outline deviation", part_deviation_mm, machining.tolerance_mm, "mm",
                            part_deviation_mm <= machining.tolerance_mm, where="layer PART against the design",
                            advice="use a post with more decimals or a larger tolerance"))
    return tuple(checks) + design_checks(built, machining_spec, strict)


def register(sub) -> None:
    p = sub.add_parser("run", help=help_of("run"))
    p.add_argument("spec", nargs="?", help="spec file (TOML); omitted: the bundled default job")
    add_output_arguments(p)
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_progress_flag(p)
    add_verbose_flag(p)
    p.set_defaults(func=run)


def _load(spec_arg):
    from camcam.spec import load_spec

    if spec_arg is not None:
        return load_spec(spec_arg)
    with resources.as_file(resources.files("camcam.data") / DEFAULT_SPEC) as path:
        return load_spec(path)


def job(spec, out, progress: Progress, plots=None) -> tuple[dict, Verdict]:
    """The whole flow for a loaded ``spec``: add every file to ``out`` (not committed); (summary, verdict).

    `camcam run` and each spec of `camcam batch` go through here.  ``plots`` is a plot server and its gate
    (:func:`plot_server`) already started, which this call closes; without one, the call starts its own.

    On fewer than three cores the plot server draws its first plots (the SVAJ and the cam) only once the
    drawing's child has loaded its modules or the NC step has ended, whichever comes first
    (:class:`camcam.servers.Gate`): the fitting process, whose NC step everything else waits for, then has
    a core to itself while the two children load and draw one after the other on the other, instead of
    three processes sharing two.  Medians of 6
    alternated runs on the 2-core benchmark machine (2026-12-06, ``benchmarks/ab.py``): at 0.001 mm
    disc-oscillating-roller 1.70 → 1.56 s, disc-groove 1.57 → 1.47 s, disc-oscillating-flat 1.73 → 1.65 s;
    disc-oscillating-roller 1.29 → 1.29 s; but the default disc 1.14 → 1.24 s, whose short NC step ends
    before the drawing's child has loaded, so that all four of the plot server's plots come after it
    (still 1.3 × the import floor, within its 1.7 ×).
    """
    from camcam.cli.motion import SVAJ_PLOT, motion_outputs, motion_summary, svaj_title
    from camcam.forked import ChildGroup, freeze_start_up, resolve
    from camcam.servers import Prepared

    freeze_start_up()
    verdict = Verdict(())
    # one child process draws every plot, and only it imports matplotlib (camcam.servers.Server): the
    # plots' data goes to it pickled (a cam pickles in about a millisecond)
    plots, gate = plot_server() if plots is None else plots
    # the run's other child processes: stopped if the run fails before it collects them
    children = ChildGroup()
    drawings = None
    try:
        program = spec.need("motion", "run").program(spec.unit)
        for j in program.joins:
            warn(j.describe())
        svaj = plots.submit(SVAJ_PLOT, program, title=svaj_title(spec.name, program))
        if spec.cam is None or spec.machining is None:
            gate.open()  # no NC step: the plots are drawn at once
        if spec.cam is None:
            with progress.step("motion table and plot"):
                motion_outputs(out, spec.name, program, 0.5, svaj)
                resolve(svaj)
            plots.close()
            return {"name": spec.name, "motion": motion_summary(program)}, verdict
        from camcam.export.cam_report import cam_report
        from camcam.geometry.build import build_cam

        with progress.step("cam geometry and analysis"):
            built = build_cam(spec.cam, spec.follower, program)
        profile_png = plots.submit(CAM_PLOT, built, f"{spec.name}: {spec.cam.kind} cam, {built.cam.kind} follower")
        with progress.step("motion table and plot"):
            motion_outputs(out, spec.name, program, 0.5, svaj)
        summary = {"name": spec.name, "motion": motion_summary(program)}
        if spec.machining is not None:
            # the drawing's child starts now, imports ezdxf and scipy (about a second) and makes the mesh and
            # STL (trimesh, which imports scipy too: once for both) beside the NC step; the program goes to it
            # pickled once it is printed, and it writes the drawing while its own children run the material check
            drawings = Prepared(DRAWING_MODULES, first=[(model, (built, spec.name), {})], opens=gate)
            model_files = drawings.first[0]
        else:
            model_files = children.later(model, built, spec.name)  # the mesh and STL need no NC: made beside it
        report = cam_report(built, mesh=False)  # its "mesh" comes with the STL
        machining = drawn = None
        if spec.machining is not None:
            with progress.step("NC second fitting and program"):
                machining = nc_step(spec, built)
            gate.open()  # if the drawing's child has not
            drawn = drawings.submit(DRAWING, built, machining, spec.machining)
        with progress.step("report analysis"):
            from camcam.report.job import job_report, report_analysis

            analysis = report_analysis(spec.name, built, machining, spec.report.inspection_step_deg, plots.submit)
        with progress.step("drawing, model and material check"):
            files, report["mesh"] = resolve(model_files)
            if machining is not None:
                from camcam.nc import with_removal

                nc, part_deviation, removal = resolve(drawn)
                for name, data in nc.items():
                    out.add(name, data)
                if removal is not None:
                    machining = with_removal(machining, removal)
                nc_figures(report, machining, part_deviation)
        verdict = job_verdict(machining, spec.machining)
        verdict = Verdict(verdict.checks + design_and_drawing_checks(
            built, machining, spec.machining, spec.report.strict,
            report.get("machining", {}).get("dxf_part_deviation_mm")), verdict.accepted)
        report["verdict"] = verdict.as_dict()
        with progress.step("report"):
            out.add(f"{spec.name}.stl", files.pop(f"{spec.name}.stl"))
            out.add(f"{spec.name}-profile.png", profile_png)
            page = job_report(spec.name, spec, program, svaj, built, report, profile_png, machining,
                              spec.report.inspection_step_deg, verdict, render=plots.submit, analysis=analysis)
            for name, data in page.files.items():
                out.add(name, data)
            report.update(page.figures)
            out.add(f"{spec.name}-report.html", page.html)
            out.add(f"{spec.name}-report.json", to_json(report) + "\n")
        summary["cam"] = report
    except BaseException:
        gate.open()
        children.cancel()
        plots.kill()
        if drawings is not None:
            drawings.kill()
        raise
    plots.close()
    return summary, verdict


def plot_server():
    """The child process that draws a run's plots (:class:`camcam.servers.Server`), started at once, and the
    gate it waits at before its first plot (:class:`camcam.servers.Gate`, opened by :func:`job`): it
    imports matplotlib (about a second) while the run itself reads the spec and designs the cam."""
    from camcam.servers import Gate, Server

    gate = Gate()
    # on three cores or more the three processes each have one: nothing waits
    return Server([(PRELOAD, PLOT_MODULES, {})], gate=gate if _cores() < 3 else None), gate


def _cores() -> int:
    """The CPUs this process may run on (its affinity where the platform says it): the run's worker counts and
    whether the plot server waits at its gate."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


#: Loads modules in a server child before its first job (camcam.forked.preload).
PRELOAD = "camcam.forked:preload"
#: What the plot server imports before its first plot: matplotlib comes with them.
PLOT_MODULES = ("camcam.plots.svaj", "camcam.plots.profile")
#: What the drawing's child imports while the NC step runs: ezdxf, scipy.interpolate and the material
#: check's scipy.spatial come with them.
DRAWING_MODULES = ("camcam.export.nc", "camcam.nc.removal", "scipy.spatial")
#: The drawing's and material check's function (run in its child, on the pickled cam and program).
DRAWING = "camcam.cli.run:drawing_and_check"


#: The cam profile plot's function (drawn in the plot server, camcam.forked).
CAM_PLOT = "camcam.plots.profile:cam_png"


def engagement_phrase(material: dict) -> str:
    """The summary's engagement figures from a report's ``material`` dict: the radial engagement is measured
    on passes other than slots (:data:`camcam.nc.passes.SLOT_KINDS`), so a program of slots alone (a groove)
    says so instead of printing 0 over no moves; a slot's own width is added where there are slots.

    Examples
    --------
    >>> engagement_phrase({"passes": [{"kind": "slot"}], "max_engagement_mm": 0.0, "stepover_mm": 8.0,
    ...                    "max_slot_engagement_mm": 20.0})
    'every pass a slot (engagement 20.000 mm)'
    >>> engagement_phrase({"passes": [{"kind": "rough"}, {"kind": "finish"}], "max_engagement_mm": 5.5,
    ...                    "stepover_mm": 8.0, "max_slot_engagement_mm": 0.0})
    'largest engagement 5.500 mm of 8 mm'
    """
    from camcam.nc.passes import SLOT_KINDS

    kinds = [p["kind"] for p in material["passes"]]
    slots = f"engagement {material['max_slot_engagement_mm']:.3f} mm"
    if all(k in SLOT_KINDS for k in kinds):
        return f"every pass a slot ({slots})"
    radial = f"largest engagement {material['max_engagement_mm']:.3f} mm of {material['stepover_mm']:g} mm"
    return radial + (f" outside slots, slots {slots}" if any(k in SLOT_KINDS for k in kinds) else "")


def run(args) -> int:
    progress = Progress.from_args(args)
    # numpy first (the run needs it in any case): the plot server forked next inherits it instead of importing
    # it again (about 0.1 CPU s; default disc 2.32 -> 2.28 CPU s, disc-groove at 0.001 mm 3.29 -> 3.15, medians
    # of 8 alternated runs)
    import numpy  # noqa: F401

    plots, gate = plot_server()  # first of all: matplotlib's import runs on the other core while the flow's load
    from camcam.cli.motion import print_summary

    try:
        spec = _load(args.spec)
        out = output_set(args, "run")
        summary, verdict = job(spec, out, progress, (plots, gate))
    finally:
        gate.open()
        plots.kill()  # a spec or folder refused: the server is stopped (after job() it has ended already)

    def show(summary: dict) -> None:
        print_summary(summary["motion"])
        if "cam" in summary:
            from camcam.geometry.analysis import radius_text  # imported already by the geometry stage

            c = summary["cam"]
            print(f"max pressure angle {c['max_pressure_angle_deg']:.4f}° at {c['max_pressure_angle_at_deg']:.2f}°; "
                  f"min radius of curvature {radius_text(c['min_curvature_radius_mm'], c['min_curvature_radius_at_deg'], 4)}")
            if "machining" in c:
                what = ("3-D groove deviation" if "flank_deviation" in c["machining"] else "max deviation")
                where = (" (both walls, every radius)" if "flank_deviation" in c["machining"] else "")
                print(f"NC: {c['line_blocks']} line + {c['arc_blocks']} arc blocks (lower bound {c['lower_bound_blocks']:.1f}), "
                      f"{what} {c['max_deviation_mm']:.4f} mm of {c['tolerance_mm']:g} mm{where} on the printed program")
                if "cycle_time" in c["machining"]:
                    from camcam.nc.timing import CycleTime

                    ct = {k: v for k, v in c["machining"]["cycle_time"].items() if k != "total_s"}
                    print(f"cycle time {CycleTime(**ct).describe()}, rapids at "
                          f"{spec.machining.post.rapid_mm_min:g} mm/min, acceleration not counted")
            if "material" in c:
                mt = c["material"]
                print(f"material: {mt['blank']['description']}; {len(mt['passes'])} passes, {engagement_phrase(mt)}, "
                      f"{mt['plunges_into_material']} plunges into material, left {mt['material_left_mm']:.4f} mm, "
                      f"overcut {mt['overcut_mm']:.4f} mm")

    for c in verdict.warnings[1 if verdict.status == "WARN" else 0:]:  # a WARN verdict's line names the first
        warn(c.describe())
    with progress.step("writing files"):
        publish(out, summary, args.json, show, (verdict.line(),) if verdict.checks else ())
    if not verdict.passed:
        accepted = " (accepted: accept_out_of_tolerance = true)" if verdict.accepted else ""
        print(f"camcam: {verdict.line()}{accepted}", file=sys.stderr)
    return verdict.exit_status
