"""``camcam run SPEC -o DIR``: the whole flow for one spec.

Today: the motion stage (table, SVAJ plot, summary).  Later stages add the
geometry, the NC program, the drawing and the report to the same output set.
"""

from __future__ import annotations

from pathlib import Path

from camcam.cli.motion import motion_outputs, motion_summary, print_summary
from camcam.cli.output import print_json, warn
from camcam.export.files import OutputSet
from camcam.spec import load_spec

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("run", help="run the whole flow for a spec")
    p.add_argument("spec", help="spec file (TOML)")
    p.add_argument("-o", "--output", default="camcam-out", help="output directory (default ./camcam-out)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = load_spec(args.spec)
    program = spec.need("motion", "run").program()
    for j in program.joins:
        warn(j.describe())
    out = OutputSet(Path(args.output))
    motion_outputs(out, spec.name, program, 0.5)
    written = out.commit()
    summary = {"name": spec.name, "motion": motion_summary(program), "files": [str(p) for p in written]}
    if args.json:
        print_json(summary)
    else:
        print_summary(summary["motion"])
        for p in written:
            print(f"wrote {p}")
    return 0
