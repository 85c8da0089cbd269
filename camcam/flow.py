"""The flow for one spec, as a Python call: ``run_job(spec) -> Job``, then ``job.write(folder)``.

:func:`run_job` designs the motion, builds the cam, plans and prints the NC
program, draws the DXF, STL and plots, measures the program, and assembles
the report; it writes nothing and returns a frozen :class:`Job` holding every
file's bytes, the summary `camcam run --json` prints, the verdict, and the
warnings and notes.  :meth:`Job.write` publishes the files as a folder, all or
nothing (:class:`~camcam.export.files.OutputSet`).  `camcam run` and each spec
of `camcam batch` are this call and a print.

How the work is shared out is an implementation detail behind it: plots are
drawn by a forked plot worker (:mod:`camcam.workers`), the drawing, STL and
material check by a prepared child, and the NC step splits independent work
with a second process (:func:`nc_step`).

Examples
--------
>>> from camcam.flow import run_job
>>> job = run_job("samples/demo.toml")
>>> job.verdict.status, sorted(job.files)[:2]
('PASS', ['demo-motion.csv', 'demo-svaj.png'])
>>> job.summary["motion"]["extremes"]["lift"]["max"]
20.0
"""

from __future__ import annotations

import importlib
import os
from dataclasses import dataclass
from contextlib import contextmanager
from importlib import resources
from pathlib import Path
from typing import Iterator, Mapping

from camcam.export.jsontext import to_json
from camcam.verdict import Verdict

__all__ = ["Job", "run_job", "start_plot_workers", "load_job_spec", "load_child_modules", "DEFAULT_SPEC", "nc_step",
           "model", "drawing", "drawing_and_check", "nc_figures", "job_verdict", "design_and_drawing_checks", "plot_server"]

#: The bundled job `camcam run` runs without a spec.
DEFAULT_SPEC = "default.toml"


def nc_step(spec, built):
    """The NC step's program (:func:`camcam.nc.machine_program`); a barrel program checked in 3-D at once
    (:func:`camcam.verify.check_job`), a disc's material check left to :func:`drawing_and_check`."""
    from camcam.nc import machine_program

    # work that splits into independent parts (a closed contour's further arc starts, a barrel cam's passes
    # and 3-D measurement) is shared with a second process: the same results
    workers = min(2, _cores())
    result = machine_program(built, spec.machining, spec.name, spec.stock, workers=workers)
    if result.groove_plan is None:
        return result
    from camcam.verify import check_job, with_checks

    return with_checks(result, check_job(result, built, spec.machining, workers), spec.machining)


def model(built, name: str) -> tuple[dict, dict]:
    """The STL and the mesh's figures: ({file: bytes}, figures).  The mesh is checked and written here (numpy,
    :mod:`camcam.export.stl`): `camcam run` calls this in a child process while the NC step runs (the drawing's
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
    """:func:`drawing` and the program's material check (:func:`camcam.verify.check_job`, None for a job
    without a blank): (files, part outline deviation, :class:`~camcam.verify.JobChecks` or None).

    `camcam run` calls this in a prepared child (:class:`camcam.workers.Prepared`) that imported ezdxf and
    scipy while the NC step ran, so the run's own process never imports scipy.  On three cores or more the
    check runs in a child of its own (which inherits them) beside the drawing; on fewer, where the plot
    server has the other core, in this process after it, without forks (each costs system CPU and the
    processes would only share the one core)."""
    from camcam.workers import ChildGroup, resolve
    from camcam.verify import check_job

    spare = _cores() >= 3
    with ChildGroup() as group:
        # the check's slabs are swept by two processes (camcam.verify.swept): the top slab, which every deeper
        # move cuts too, beside the others
        check = group.later(check_job, machining, built, machining_spec, 2) \
            if machining.blank is not None and spare else None
        files, part_deviation = drawing(built, machining)
        if machining.blank is not None and not spare:
            check = check_job(machining, built, machining_spec, 1)
        return files, part_deviation, resolve(check)


def nc_figures(report: dict, result, part_deviation_mm: float | None, said: list) -> None:
    """Add the NC step's figures to ``report``; its notes go to ``said`` as ("note", text)."""
    nc = result.figures()
    nc["dxf_part_deviation_mm"] = part_deviation_mm
    for key in ("tolerance_mm", "max_deviation_mm", "line_blocks", "arc_blocks", "lower_bound_blocks", "cycle_time_s",
                "motion_time_s"):
        report[key] = nc[key]
    report["machining"] = nc
    if "material" in nc:
        report["material"] = nc["material"]
    for note in result.notes:
        said.append(("note", note))


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
                            ok=part_deviation_mm <= machining.tolerance_mm, where="layer PART against the design",
                            advice="use a post with more decimals or a larger tolerance"))
    return tuple(checks) + design_checks(built, machining_spec, strict)


def _flow(spec, out, progress, plots, said: list) -> tuple[dict, Verdict, tuple]:
    """The whole flow for a loaded ``spec``: add every file to ``out``; (summary, verdict, (motion program,
    built cam or None, machining result or None)); warnings and notes go to ``said`` as (kind, text).

    :func:`run_job` (`camcam run`, and each spec of `camcam batch`) goes through here.  ``plots`` is a plot server and its gate
    (:func:`plot_server`) already started, which this call closes; without one, the call starts its own.

    On fewer than three cores the plot server draws its first plots (the SVAJ and the cam) only once the
    drawing's child has loaded its modules or the NC step has ended, whichever comes first
    (:class:`camcam.workers.Gate`): the fitting process, whose NC step everything else waits for, then has
    a core to itself while the two children load and draw one after the other on the other, instead of
    three processes sharing two.  Medians of 6
    alternated runs on the 2-core benchmark machine (2026-12-06, ``benchmarks/ab.py``): at 0.001 mm
    disc-oscillating-roller 1.70 → 1.56 s, disc-groove 1.57 → 1.47 s, disc-oscillating-flat 1.73 → 1.65 s;
    disc-oscillating-roller 1.29 → 1.29 s; but the default disc 1.14 → 1.24 s, whose short NC step ends
    before the drawing's child has loaded, so that all four of the plot server's plots come after it
    (still 1.3 × the import floor, within its 1.7 ×).
    """
    from camcam.export.motion_table import SVAJ_PLOT, motion_outputs, motion_summary, svaj_title
    from camcam.workers import ChildGroup, Prepared, freeze_start_up, resolve

    freeze_start_up()
    verdict = Verdict(())
    # one child process draws every plot, and only it imports matplotlib (camcam.workers.Server): the
    # plots' data goes to it pickled (a cam pickles in about a millisecond)
    plots, gate = plot_server() if plots is None else plots
    # the run's other child processes: stopped if the run fails before it collects them
    children = ChildGroup()
    drawings = None
    try:
        program = spec.need("motion", "run").program(spec.unit)
        for j in program.joins:
            said.append(("warning", j.describe()))
        svaj = plots.submit(SVAJ_PLOT, program, title=svaj_title(spec.name, program))
        if spec.cam is None or spec.machining is None:
            gate.open()  # no NC step: the plots are drawn at once
        if spec.cam is None:
            with progress.step("motion table and plot"):
                motion_outputs(out, spec.name, program, 0.5, svaj)
                resolve(svaj)
            plots.close()
            return {"name": spec.name, "motion": motion_summary(program)}, verdict, (program, None, None)
        from camcam.export.cam_report import cam_report
        from camcam.geometry.build import build_cam

        with progress.step("cam geometry and analysis"):
            built = build_cam(spec.cam, spec.follower, program)
        dynamics = None
        if spec.dynamics is not None:  # forces, torque, contact stress, jump speed (issue 45): bad input stops here
            from camcam.dynamics.cycle import analyse_dynamics

            with progress.step("dynamics"):
                dynamics = analyse_dynamics(built, program.rpm, spec.dynamics)
        profile_png = plots.submit(CAM_PLOT, built, f"{spec.name}: {spec.cam.kind} cam, {built.cam.kind} follower")
        with progress.step("motion table and plot"):
            motion_outputs(out, spec.name, program, 0.5, svaj, dynamics)
        summary = {"name": spec.name, "motion": motion_summary(program)}
        # the STEP in a child of its own, from now on (OCP's import is about a CPU second): nothing waits for it
        # until the report (camcam.export.step.step_files: nothing where OCP is not installed)
        from camcam.export.step import step_files

        step_file = children.later(step_files, built, spec.name) if spec.report.step_file else None
        if spec.machining is not None:
            # the drawing's child starts now, imports ezdxf and scipy's k-d tree (about a third of a second) and makes the
            # mesh's STL beside the NC step; the program goes to it pickled once it is printed, and it writes the
            # drawing and runs the material check (drawing_and_check)
            # the NC step's modules (and the material check's removal, which the run imports with its result):
            # the child unpickles the program to them, and inherits them instead of importing them again
            for name in NC_MODULES + (("camcam.verify.removal",) if has_material_check(built.spec.kind) else ()):
                importlib.import_module(name)
            drawings = Prepared(drawing_modules(built.spec.kind), first=[(model, (built, spec.name), {})], opens=gate)
            model_files = drawings.first[0]
        else:
            model_files = children.later(model, built, spec.name)  # the mesh and STL need no NC: made beside it
        report = cam_report(built, mesh=False)  # its "mesh" comes with the STL
        if dynamics is not None:
            report["dynamics"] = dynamics.figures()
        machining = drawn = None
        if spec.machining is not None:
            with progress.step("NC second fitting and program"):
                machining = nc_step(spec, built)
            gate.open()  # if the drawing's child has not
            drawn = drawings.submit(DRAWING, built, machining, spec.machining)
        with progress.step("report analysis"):
            from camcam.report.job_page import job_report, report_analysis

            analysis = report_analysis(spec.name, built, machining, spec.report.inspection_step_deg, plots.submit)
            if dynamics is not None:
                from camcam.report.dynamics_section import with_dynamics

                analysis = with_dynamics(analysis, spec.name, dynamics, plots.submit)
        with progress.step("drawing, model and material check"):
            files, report["mesh"] = resolve(model_files)
            if machining is not None:
                from camcam.verify import with_checks

                nc, part_deviation, checks = resolve(drawn)
                for name, data in nc.items():
                    out.add(name, data)
                if checks is not None:
                    machining = with_checks(machining, checks, spec.machining)
                nc_figures(report, machining, part_deviation, said)
        verdict = job_verdict(machining, spec.machining)
        verdict = Verdict(verdict.checks + design_and_drawing_checks(
            built, machining, spec.machining, spec.report.strict,
            report.get("machining", {}).get("dxf_part_deviation_mm")), verdict.accepted)
        if dynamics is not None:
            from camcam.dynamics.checks import dynamics_checks

            verdict = Verdict(verdict.checks + dynamics_checks(dynamics, built.spec, spec.report.strict), verdict.accepted)
        report["verdict"] = verdict.as_dict()
        with progress.step("report"):
            out.add(f"{spec.name}.stl", files.pop(f"{spec.name}.stl"))
            step, why_not = resolve(step_file) if step_file is not None else ({}, None)
            for name, data in step.items():
                out.add(name, data)
            if why_not is not None:
                from camcam.export.step import CAD_HINT

                said.append(("note" if why_not == CAD_HINT else "warning", why_not))
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
    return summary, verdict, (program, built, machining)


def plot_server():
    """The child process that draws a run's plots (:class:`camcam.workers.Server`), started at once, and the
    gate it waits at before its first plot (:class:`camcam.workers.Gate`, opened by :func:`job`): it
    imports matplotlib (about a second) while the run itself reads the spec and designs the cam."""
    from camcam.workers import Gate, Server

    for name in PLOT_INHERITS + CHILDREN_SHARE:
        importlib.import_module(name)
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


#: Loads modules in a server child before its first job (camcam.workers.preload).
PRELOAD = "camcam.workers:preload"
#: What the plot server imports before its first plot: matplotlib comes with them.
PLOT_MODULES = ("camcam.plots.svaj", "camcam.plots.profile")
#: What PLOT_MODULES need besides matplotlib, which a cam's run imports in any case: imported before the plot
#: server is forked, it inherits them instead of importing them again (0.02-0.03 CPU s of its preload,
#: medians of 5 alternated runs; a motion-only run pays them here instead of in the server).
PLOT_INHERITS = ("camcam.motion.program", "camcam.geometry.build", "camcam.geometry.analysis")
#: What matplotlib (the plot server's) and ezdxf (the drawing's child's) both import: numpy's masked arrays and
#: typing, pyparsing (and the unittest it brings), fontTools' helpers, uuid and socket, the expat XML parser, subprocess.
#: Imported before the plot server is forked, every child inherits them instead of each importing them
#: again: about 0.1 CPU s once instead of twice (benchmarks/ab.py figures in docs/benchmarks.md).
CHILDREN_SHARE = ("numpy.ma", "numpy.typing", "pyparsing", "fontTools.misc.loggingTools", "fontTools.misc.textTools",
                  "uuid", "socket", "pyexpat", "subprocess", "sysconfig", "calendar")
#: What the drawing's child imports while the NC step runs: ezdxf comes with them; the STL is numpy's (no trimesh)
#: and the DXF's splines too (camcam.export.dxf.HermiteSpline).
DRAWING_MODULES = ("camcam.export.nc",)
#: What the material check adds, for a job that has one (a disc or face-groove job, which starts from a blank; a
#: barrel's groove is checked in 3-D by the NC step): its k-d tree is scipy's loaded alone (camcam.verify.kdtree),
#: the child's only scipy (0.1 CPU s with scipy.sparse, which a barrel's drawing no longer imports).
CHECK_MODULES = ("camcam.verify.removal", "camcam.verify.job_checks", "camcam.verify.kdtree")


def drawing_modules(cam_kind: str) -> tuple[str, ...]:
    """What the drawing's child of a ``cam_kind`` job imports: :data:`DRAWING_MODULES`, and :data:`CHECK_MODULES`
    where the job has a material check (every kind but ``"cylindrical"``, whose job has no blank).

    >>> drawing_modules("cylindrical")
    ('camcam.export.nc',)
    >>> drawing_modules("disc")[-1]
    'camcam.verify.kdtree'
    """
    return DRAWING_MODULES + (CHECK_MODULES if has_material_check(cam_kind) else ())


def has_material_check(cam_kind: str) -> bool:
    """Whether a ``cam_kind`` job's program gets the material check (:func:`camcam.verify.check_job`): a disc's
    or face groove's, which starts from a blank; a barrel's groove is measured in 3-D by its NC step instead."""
    return cam_kind != "cylindrical"


#: What the NC step (:func:`nc_step`) and its material check's result (``with_checks``) import: the run imports them
#: before it forks the drawing's child, which needs them too (its machining result unpickles to them).
NC_MODULES = ("camcam.nc.job", "camcam.verify.job_checks")
#: The plot modules of the report's plots after the NC step (camcam.report.job_page) and of the dynamics section.
REPORT_PLOT_MODULES = ("camcam.plots.report_plots", "camcam.plots.groove_map", "camcam.plots.dynamics_plot")


def load_child_modules(spec) -> None:
    """Import in this process what the children of ``spec``'s job would import: matplotlib with the plot
    modules, ezdxf and the k-d tree with the drawing's (a job with machining), OpenCascade and the solids'
    builders when it writes a STEP (:func:`camcam.export.step.load_cad`; nothing where OCP is not installed).

    `camcam batch` in one process calls it before each job: every job's children, forked from this process,
    inherit them instead of importing them again, job after job (`camcam run` forks its children before
    their imports instead, so that they import beside the NC step).
    """
    for name in PLOT_MODULES + REPORT_PLOT_MODULES:
        importlib.import_module(name)
    if spec.machining is not None and spec.cam is not None:
        for name in drawing_modules(spec.cam.kind):
            importlib.import_module(name)
    if spec.report.step_file and spec.cam is not None:
        from camcam.export.step import load_cad

        load_cad(spec.cam.kind)


#: The drawing's and material check's function (run in its child, on the pickled cam and program).
DRAWING = "camcam.flow:drawing_and_check"


#: The cam profile plot's function (drawn in the plot server, camcam.workers).
CAM_PLOT = "camcam.plots.profile:cam_png"


@dataclass(frozen=True, kw_only=True)
class Job:
    """One spec's whole result, in memory: nothing is on disk until :meth:`write`.

    Attributes
    ----------
    name : str
        The spec's name (the files' stem).
    summary : Mapping
        What `camcam run --json` prints, but for the ``files`` it wrote: ``motion`` (extremes, joins)
        and, for a cam, ``cam`` (the report.json figures, the ``verdict`` among them).
    verdict : Verdict
        Every check of the job; ``verdict.exit_status`` is the status `camcam run` ends with.
    files : Mapping[str, bytes]
        Every output file by name: the program, DXF, STL, plots, report HTML and JSON, tables.
    warnings, notes : tuple of str
        What the user may want to change, and how the job was done (`camcam run` prints them on stdout).
    motion : MotionProgram
        The follower's motion program (:mod:`camcam.motion`): ``lift(θ)``, ``physical(θ, order)``, extremes, joins.
    cam : BuiltCam or None
        The cam built around the follower (:func:`camcam.geometry.build.build_cam`); None for a motion-only spec.
    machining : MachiningResult or None
        The NC step's result: contours, toolpath, printed program and checks; None without ``[machining]``.

    Examples
    --------
    >>> job = run_job("samples/demo.toml")
    >>> import numpy as np
    >>> job.cam is None, round(float(job.motion.lift(np.radians(60.0))), 9)  # mid-rise of the symmetric 20 mm rise
    (True, 10.0)
    """

    name: str
    summary: Mapping
    verdict: Verdict
    files: Mapping[str, bytes]
    warnings: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    motion: object = None
    cam: object = None
    machining: object = None

    def write(self, folder: str | Path, *, force: bool = False) -> tuple[Path, ...]:
        """Publish :attr:`files` as ``folder``, all or nothing, with its manifest
        (:class:`~camcam.export.files.OutputSet`: the folder must be new or empty, or, with ``force``,
        hold exactly an earlier run's files).  Returns the paths written."""
        from camcam.export.files import OutputSet

        out = OutputSet(Path(folder), force=force, command="run")
        for name, data in self.files.items():
            out.add(name, data)
        return tuple(out.commit())


class _Files:
    """The flow's output files while it runs: plots still being drawn are collected at the end."""

    def __init__(self) -> None:
        self._files: dict = {}

    def add(self, name: str, data) -> None:
        self._files[name] = data.encode("utf-8") if isinstance(data, str) else data

    def contents(self) -> dict[str, bytes]:
        from camcam.workers import resolve

        return {name: resolve(data) for name, data in self._files.items()}


class _Quiet:
    """No progress lines (the library's default; `camcam run` passes its own)."""

    @contextmanager
    def step(self, name: str) -> Iterator[None]:
        yield


def load_job_spec(spec):
    """A loaded spec from a path, a :class:`~camcam.spec.Spec` as it is, or ``None``: the bundled default job."""
    from camcam.spec import load_spec

    if spec is None:
        with resources.as_file(resources.files("camcam.data") / DEFAULT_SPEC) as path:
            return load_spec(path)
    if isinstance(spec, (str, os.PathLike)):
        return load_spec(spec)
    return spec


def start_plot_workers():
    """Start the plot worker now (it imports matplotlib, about a second, while the caller loads its spec);
    pass it to :func:`run_job` as ``plots``.  Optional: without it :func:`run_job` starts its own."""
    return plot_server()


def run_job(spec=None, *, progress=None, plots=None) -> Job:
    """Run the whole flow for ``spec`` (a path, a loaded spec, or ``None`` for the bundled default job) and
    return its :class:`Job`; nothing is written.

    Raises the spec's :class:`~camcam.errors.CamcamError` on bad input (exit 2 in `camcam run`).
    ``progress`` announces long steps (`camcam run`'s :class:`~camcam.cli.progress.Progress`); ``plots``
    is a plot worker from :func:`start_plot_workers`, which this call stops.
    """
    spec = load_job_spec(spec)
    said: list[tuple[str, str]] = []
    files = _Files()
    summary, verdict, (motion, cam, machining) = _flow(spec, files, progress if progress is not None else _Quiet(),
                                                      plots, said)
    return Job(name=spec.name, summary=summary, verdict=verdict, files=files.contents(),
               warnings=tuple(t for k, t in said if k == "warning"),
               notes=tuple(t for k, t in said if k == "note"), motion=motion, cam=cam, machining=machining)
