"""``camcam size SPEC -o DIR``: sweep a spec's ``[size]`` table and write the best design.

Writes ``<name>-designs.parquet`` (or ``.csv`` without pyarrow: every design),
``<name>-feasible.*`` (the feasible ones, best first), ``<name>-best.json``,
``<name>-best.toml`` (the best design as a spec `camcam run` takes as is),
``<name>-sizing.png`` and ``<name>-sizing.html``, all or nothing.  Exit status
3 when no design meets every constraint (the table and chart are written).
"""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

from camcam.cli.output import add_output_arguments, output_set, print_json
from camcam.cli.commands import help_of
from camcam.cli.dask_options import add_scale_arguments, executor_from_args, tell_scale_note

__all__ = ["register"]

#: Exit status when the sweep ran but no design meets every constraint (files written).
NO_DESIGN = 3


def register(sub) -> None:
    p = sub.add_parser("size", help=help_of("size"))
    p.add_argument("spec", help="spec file (TOML) with a [size] table")
    add_output_arguments(p)
    p.add_argument("--table", choices=("auto", "parquet", "csv"), default="auto",
                   help="table format (auto: Parquet when pyarrow is installed, else CSV)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_scale_arguments(p)
    p.set_defaults(func=run)


def run(args) -> int:
    import json

    from camcam.errors import SpecError
    from camcam.sizing.outputs import parquet_available, sizing_files
    from camcam.sizing.sweep import run_sweep
    from camcam.spec import load_spec

    spec = load_spec(args.spec)
    spec.need("size", "size")
    if args.table == "parquet" and not parquet_available():
        raise SpecError("--table", "parquet needs pyarrow: pip install 'camcam[parquet]'")
    fmt = "parquet" if args.table == "parquet" or (args.table == "auto" and parquet_available()) else "csv"
    data = tomllib.loads(Path(args.spec).read_text(encoding="utf-8"))
    out = output_set(args, "size")
    with executor_from_args(args) as executor:
        result = run_sweep(spec, executor)
        note = executor.note
        tell_scale_note(executor)
    files = sizing_files(result, data, spec.name, fmt)
    for name, content in files.items():
        out.add(name, content)
    written = out.commit()
    summary = json.loads(files[f"{spec.name}-best.json"])
    if args.json:
        summary["files"] = [str(p) for p in written]
        if note:
            summary["note"] = note
        print_json(summary)
    else:
        print(f"{summary['designs']:,} designs, {summary['feasible']:,} feasible on the grid")
        b = summary["best"]
        if b is not None:
            e = b["exact"]
            axes = ", ".join(f"{k.removesuffix('_mm').replace('_', ' ')} {v:g} mm" for k, v in b.items() if k.endswith("_mm"))
            laws = "".join(f", {k}: {v}" for k, v in b["laws"].items())
            print(f"best: design {b['design']}: {axes}{laws}")
            print(f"  outer radius {e['outer_radius_mm']:.4f} mm, max pressure angle {e['max_pressure_angle_deg']:.4f}°, "
                  f"min radius of curvature {e['min_curvature_radius_mm']:.4f} mm (exact geometry)")
            if "jump_rpm" in e:
                jump = "never separates" if e["jump_rpm"] in ("inf", float("inf")) else f"jump speed {e['jump_rpm']:.1f} rpm"
                print(f"  max contact stress {e['max_contact_stress_mpa']:.2f} MPa, {jump} ([dynamics], as camcam run)")
        for p in written:
            print(f"wrote {p}")
    if result.best is None:
        print(f"camcam: FAIL: none of the {len(result.grid):,} designs meets every constraint; widen the ranges or relax a "
              f"constraint (see {spec.name}-sizing.png)", file=sys.stderr)
        return NO_DESIGN
    return 0
