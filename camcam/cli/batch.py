"""``camcam batch SPEC… -o DIR``: many cam specs, each into its own folder, one summary.

Each spec goes through the same library path as ``camcam run`` (:func:`camcam.flow.run_job`)
as one task, in this process or on Dask workers.  A spec that fails (bad input or an
internal fault) is a row of the summary with its one-line reason; the others still run.
Writes ``DIR/<spec file stem>/…`` (what ``camcam run`` writes), ``DIR/summary.csv``,
``DIR/summary.json`` and ``DIR/index.html``.  Exit 0 when every spec passes (PASS, or WARN: an
advisory design limit missed), 3 when any did not and was not accepted (its row says why; the
other folders are written).
"""

from __future__ import annotations

import sys
from pathlib import Path

from camcam.cli.output import add_output_arguments, output_set, print_json, to_json
from camcam.cli.commands import help_of
from camcam.cli.dask_options import add_scale_arguments, executor_from_args, tell_scale_note
from camcam.dask_batch.engine import InProcess

__all__ = ["register", "batch_task", "summary_row", "COLUMNS"]

#: Exit status when any spec did not pass (everything else written).
NOT_ALL_PASSED = 3

COLUMNS = ("spec", "folder", "name", "verdict", "accepted", "max_deviation_mm", "tolerance_mm", "line_blocks", "arc_blocks",
           "cycle_time_s", "motion_time_s", "max_pressure_angle_deg", "min_curvature_radius_mm", "warnings", "reason")


def register(sub) -> None:
    p = sub.add_parser("batch", help=help_of("batch"))
    p.add_argument("specs", nargs="+", metavar="SPEC", help="spec files (TOML)")
    add_output_arguments(p)
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_scale_arguments(p)
    p.set_defaults(func=run)


def summary_row(spec_arg: str, folder: str, summary: dict | None, verdict, warnings: list[str], error: str = "") -> dict:
    """One row of the summary table (empty cells: not applicable); ``verdict`` is the run's
    :class:`~camcam.verdict.Verdict` (``None`` when the spec did not run: ERROR)."""
    row = dict.fromkeys(COLUMNS, "")
    row.update(spec=spec_arg, folder=folder, warnings=len(warnings))
    if summary is None:
        row.update(verdict="ERROR", reason=error)
        return row
    cam = summary.get("cam") or {}
    reason = "" if verdict.status == "PASS" else verdict.line() + (" (accepted: accept_out_of_tolerance = true)" if verdict.accepted and not verdict.passed else "")
    row.update(name=summary.get("name", ""), verdict=verdict.status, accepted=verdict.accepted, reason=reason)
    for key in ("max_deviation_mm", "tolerance_mm", "line_blocks", "arc_blocks", "cycle_time_s", "motion_time_s",
                "max_pressure_angle_deg", "min_curvature_radius_mm"):
        if cam.get(key) is not None:
            row[key] = cam[key]
    return row


def batch_task(item: tuple[str, str], forks: bool = True) -> tuple[dict, dict[str, bytes]]:
    """Run one spec like `camcam run` (:func:`camcam.flow.run_job`) and return (summary row, files by name);
    never raises for a bad spec.

    ``forks=False`` runs the whole job in this process (:func:`camcam.workers.single_process`): what a Dask
    worker does, the cluster's workers being the batch's parallelism.  The same files either way."""
    from contextlib import nullcontext

    from camcam.errors import CamcamError
    from camcam.flow import load_child_modules, load_job_spec, run_job
    from camcam.workers import single_process

    spec_arg, folder = item
    job, error = None, ""
    try:
        spec = load_job_spec(spec_arg)
        if forks:  # the job's children inherit the libraries this process loaded for the jobs before it
            load_child_modules(spec)
        with nullcontext() if forks else single_process():
            job = run_job(spec)
    except CamcamError as e:
        error = " ".join(str(e).splitlines())
    except Exception as e:  # noqa: BLE001 - one spec's fault must not stop the batch; the row names it
        error = f"internal fault: {type(e).__name__}: {' '.join(str(e).splitlines())}"
    # the warnings `camcam run` prints: the job's own, then the verdict's advisory misses (design limits)
    warned = list(job.warnings) + [c.describe() for c in job.verdict.warnings] if job is not None else []
    row = summary_row(spec_arg, folder, dict(job.summary) if job else None, job.verdict if job else None, warned, error)
    row["warning_text"] = warned
    return row, (dict(job.files) if job is not None else {})


def _folders(specs: list[str]) -> list[str]:
    """One folder per spec: its file stem, with -2, -3 … on a repeated stem (input order)."""
    seen: dict[str, int] = {}
    out = []
    for s in specs:
        stem = Path(s).stem or "spec"
        seen[stem] = seen.get(stem, 0) + 1
        out.append(stem if seen[stem] == 1 else f"{stem}-{seen[stem]}")
    return out


def _csv(rows: list[dict]) -> str:
    def cell(v) -> str:
        text = ("true" if v else "false") if isinstance(v, bool) else repr(v) if isinstance(v, float) else str(v)
        return '"' + text.replace('"', '""') + '"' if any(c in text for c in ',"\n') else text

    return "\n".join([",".join(COLUMNS)] + [",".join(cell(r[c]) for c in COLUMNS) for r in rows]) + "\n"


def _index(rows: list[dict], files: list[dict[str, bytes]]) -> str:
    import html

    from camcam.report.html import DataTable, Paragraph, Section, render_html

    def num(v, digits):
        return f"{v:.{digits}f}" if isinstance(v, float) else str(v)

    table = DataTable(
        ("spec", "folder", "verdict", "max deviation (mm)", "tolerance (mm)", "blocks (line + arc)", "cycle time (s)",
         "with acceleration (s)", "max pressure angle (°)", "reason"),
        tuple((r["spec"], r["folder"], r["verdict"] + (" (accepted)" if r["accepted"] is True else ""), num(r["max_deviation_mm"], 4), num(r["tolerance_mm"], 4),
               f"{r['line_blocks']} + {r['arc_blocks']}" if r["line_blocks"] != "" else "", num(r["cycle_time_s"], 1),
               num(r["motion_time_s"], 1), num(r["max_pressure_angle_deg"], 3), r["reason"]) for r in rows))
    passed = sum(r["verdict"] == "PASS" for r in rows)
    warned = sum(r["verdict"] == "WARN" for r in rows)
    page = render_html("camcam batch", f"{len(rows)} specs: {passed} PASS, " + (f"{warned} WARN, " if warned else "")
                       + f"{len(rows) - passed - warned} not", [
        Section("Summary", (table, Paragraph("summary.csv holds the same table; each folder holds what `camcam run` writes."))),
    ])
    links = []
    for r, f in zip(rows, files):
        report = next((n for n in f if n.endswith("-report.html")), None)
        if report is not None:
            links.append(f'<li><a href="{html.escape(r["folder"])}/{html.escape(report)}">{html.escape(r["spec"])}</a></li>')
    if links:
        page = page.replace("</body></html>", "<section><h2>Reports</h2><ul>" + "".join(links) + "</ul></section>\n</body></html>")
    return page


def run(args) -> int:
    specs = list(args.specs)
    folders = _folders(specs)
    top = output_set(args, "batch")  # checked before the work: a folder it cannot use fails at once
    with executor_from_args(args) as executor:
        # in this process a job forks its plot server and drawing child onto the other cores, as `camcam run`
        # does; on a cluster, whose workers fill the cores already, each job runs in its worker alone
        results = executor.map(batch_task, list(zip(specs, folders)), what=f"{len(specs)} specs",
                               forks=isinstance(executor, InProcess))
        note = executor.note
        tell_scale_note(executor)
    root = Path(args.output)
    rows = [r for r, _ in results]
    contents = [f for _, f in results]
    # one output set: every spec's folder and the summary appear together or not at all
    for (row, files) in results:
        for name, data in files.items():
            top.add(f"{row['folder']}/{name}", data)
    table_rows = [{k: v for k, v in r.items() if k != "warning_text"} for r in rows]
    top.add("summary.csv", _csv(table_rows))
    top.add("summary.json", to_json({"specs": rows}) + "\n")
    top.add("index.html", _index(table_rows, contents))
    top.commit()
    bad = [r for r in rows if r["verdict"] not in ("PASS", "WARN") and r["accepted"] is not True]  # WARN exits 0
    if args.json:
        print_json({"specs": rows, "output": str(root), **({"note": note} if note else {})})
    else:
        for r in rows:
            print(f"{r['verdict']:5s} {r['spec']}" + (f": {r['reason']}" if r["reason"] else ""))
        print(f"wrote {root / 'summary.csv'}, {root / 'index.html'} and {len(specs) - sum(r['verdict'] == 'ERROR' for r in rows)} folders")
    if bad:
        first = bad[0]
        print(f"camcam: FAIL: {len(bad)} of {len(rows)} specs did not pass; first: {first['spec']}: {first['verdict']}"
              f"{': ' + first['reason'] if first['reason'] else ''} (see {root / 'summary.csv'})", file=sys.stderr)
        return NOT_ALL_PASSED
    return 0
