"""``camcam motion SPEC -o DIR``: the motion program as a table, a plot and a summary."""

from __future__ import annotations


from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, add_verbose_flag, output_set, publish, warn
from camcam.export.files import OutputSet
from camcam.export.motion_table import motion_csv
from camcam.motion.program import MotionProgram
from camcam.spec import load_spec

__all__ = ["register", "motion_summary", "motion_outputs", "SVAJ_PLOT", "svaj_title"]


def register(sub) -> None:
    p = sub.add_parser("motion", help=help_of("motion"))
    p.add_argument("spec", help="spec file (TOML)")
    add_output_arguments(p)
    p.add_argument("--step", type=float, default=0.5, help="table step in degrees (default 0.5)")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_verbose_flag(p)
    p.set_defaults(func=run)


def motion_summary(program: MotionProgram) -> dict:
    """Extremes of s, v, a, j with the cam angles where they occur (rounding noise printed as 0:
    :func:`camcam.export.figures.clean`), and the joins."""
    from camcam.export.figures import clean

    names = ["lift", "velocity", "acceleration", "jerk"]
    out = {"rpm": program.rpm, "units": dict(zip(names, program.units)), "extremes": {}}
    for k, n in enumerate(names):
        lo, hi = program.extremes(k)
        scale = max(abs(lo.value), abs(hi.value))  # a lift of -3.55e-15 mm beside a 20 mm rise is 0 (issue 43)
        out["extremes"][n] = {"min": clean(lo.value, scale), "min_at_deg": lo.angle_deg, "max": clean(hi.value, scale),
                              "max_at_deg": hi.angle_deg}
    out["joins"] = [
        {"angle_deg": j.angle_deg, "quantity": {1: "velocity", 2: "acceleration"}[j.order], "jump": j.jump, "unit": j.unit}
        for j in program.joins
    ]
    return out


def motion_outputs(out: OutputSet, name: str, program: MotionProgram, step_deg: float, svaj=None):
    """Add the motion table and the SVAJ plot to ``out``; returns the plot (the report shows it too),
    a :class:`~camcam.forked.Pending` while it is drawn in a child process.

    ``svaj`` is the plot when a caller already has it being drawn (`camcam run`'s plot server);
    otherwise it is drawn in a forked child that imports matplotlib itself.
    """
    from camcam.forked import call_target, later

    out.add(f"{name}-motion.csv", motion_csv(program, step_deg))
    if svaj is None:
        svaj = later(call_target, SVAJ_PLOT, program, title=svaj_title(name, program))
    out.add(f"{name}-svaj.png", svaj)
    return svaj


#: The SVAJ plot's function (imported where it is drawn: matplotlib is loaded only there).
SVAJ_PLOT = "camcam.plots.svaj:svaj_png"


def svaj_title(name: str, program: MotionProgram) -> str:
    return f"{name}: motion at {program.rpm:g} rpm"


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
