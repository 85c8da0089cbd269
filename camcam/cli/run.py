"""``camcam run [SPEC] -o DIR``: the whole flow for one spec (:func:`camcam.flow.run_job`), written and printed.

The command parses its arguments, calls :func:`~camcam.flow.run_job`, writes
the :class:`~camcam.flow.Job`'s files into DIR all or nothing, and prints its
summary, warnings and notes (stdout) and, when it did not pass, one line on
stderr.  Without SPEC the bundled default job runs.
"""

from __future__ import annotations

import sys

from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, add_verbose_flag, output_set, publish, warn
from camcam.cli.progress import Progress, add_progress_flag

__all__ = ["register", "engagement_phrase"]


def register(sub) -> None:
    p = sub.add_parser("run", help=help_of("run"))
    p.add_argument("spec", nargs="?", help="spec file (TOML); omitted: the bundled default job")
    add_output_arguments(p)
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_progress_flag(p)
    add_verbose_flag(p)
    p.add_argument("--single-process", action="store_true",
                   help="do all the work in this one process: the fewest CPU seconds, for a shared or busy machine "
                        "(by default plots, drawing and checks run in child processes beside the fitting, which ends "
                        "sooner on an idle machine); the files are the same")
    p.set_defaults(func=run)


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
    """`camcam run`; with ``--single-process`` every job of :mod:`camcam.workers` runs in this process
    (:func:`camcam.workers.single_process`, as each spec of a batch on a Dask worker)."""
    from contextlib import nullcontext

    from camcam.workers.children import single_process

    with single_process() if getattr(args, "single_process", False) else nullcontext():
        return _run(args)


def _run(args) -> int:
    progress = Progress.from_args(args)
    # numpy first (the run needs it in any case): the plot server forked next inherits it instead of importing
    # it again (about 0.1 CPU s; default disc 2.32 -> 2.28 CPU s, disc-groove at 0.001 mm 3.29 -> 3.15, medians
    # of 8 alternated runs)
    import numpy  # noqa: F401

    from camcam.flow import load_job_spec, run_job, start_plot_workers

    plots = start_plot_workers()  # first of all: matplotlib's import runs on the other core while the flow's load
    from camcam.cli.motion import print_summary

    try:
        spec = load_job_spec(args.spec)
        out = output_set(args, "run")
        job = run_job(spec, progress=progress, plots=plots)
    finally:
        server, gate = plots
        gate.open()
        server.kill()  # a spec or folder refused: the server is stopped (after run_job it has ended already)
    summary, verdict = dict(job.summary), job.verdict
    for name, data in job.files.items():
        out.add(name, data)
    for text in job.warnings:
        warn(text)
    for text in job.notes:
        warn(text, "note")

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
                    from camcam.verify.cycle_time import CycleTime

                    ct = {k: v for k, v in c["machining"]["cycle_time"].items() if k != "total_s"}
                    print(f"cycle time {CycleTime(**ct).describe()}, rapids at "
                          f"{spec.machining.post.rapid_mm_min:g} mm/min, acceleration not counted")
                if "motion_time" in c["machining"]:
                    from camcam.verify.motion_time import MotionTime

                    print(f"cycle time {MotionTime.from_dict(c['machining']['motion_time']).describe()}")
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
