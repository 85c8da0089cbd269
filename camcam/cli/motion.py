"""``camcam motion SPEC -o DIR``: the motion program as a table, a plot and a summary."""

from __future__ import annotations


from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, add_verbose_flag, output_set, publish, warn
from camcam.export.motion_table import motion_outputs, motion_summary
from camcam.spec import load_spec

__all__ = ["register", "print_summary", "check_step"]


def register(sub) -> None:
    p = sub.add_parser("motion", help=help_of("motion"))
    p.add_argument("spec", help="spec file (TOML)")
    add_output_arguments(p)
    p.add_argument("--step", type=float, default=0.5, help="table step in degrees (default 0.5)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_verbose_flag(p)
    p.set_defaults(func=run)


def print_summary(summary: dict) -> None:
    for n, e in summary["extremes"].items():
        u = summary["units"][n]
        print(f"{n:13s} min {e['min']:+12.6g} {u:7s} at {e['min_at_deg']:7.2f}°   max {e['max']:+12.6g} {u:7s} at {e['max_at_deg']:7.2f}°")


#: Finest table step (degrees): 36 000 rows per revolution at most.
MIN_STEP_DEG = 0.01


def check_step(step_deg: float) -> None:
    """``--step`` of a table command: from :data:`MIN_STEP_DEG` to 360 degrees."""
    from camcam.errors import SpecError

    if not MIN_STEP_DEG <= step_deg <= 360:
        raise SpecError("--step", f"expected degrees from {MIN_STEP_DEG:g} (at most {round(360 / MIN_STEP_DEG)} rows) "
                                  f"to 360, got {step_deg:g}")


def run(args) -> int:
    check_step(args.step)
    spec = load_spec(args.spec)
    program = spec.need("motion", "motion").program(spec.unit)
    for j in program.joins:
        warn(j.describe())
    out = output_set(args, "motion")
    motion_outputs(out, spec.name, program, args.step)
    publish(out, motion_summary(program), args.json, print_summary)
    return 0
