"""``camcam reverse POINTS.csv --spec SPEC -o DIR``: measured cam points back to the follower motion.

SPEC holds ``[cam]`` and ``[follower]`` (and optionally a design ``[motion]``
to compare against).  Writes ``DIR/motion.csv`` (``cam_angle_deg, lift,
velocity, acceleration`` at ``--points`` angles plus the closing 360° row;
usable as a spec's ``lift_table``), ``DIR/reverse.png`` (recovered against
design) and ``DIR/summary.json``; ``--json`` prints the summary.
"""

from __future__ import annotations

import numpy as np

from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, output_set, publish, to_json
from camcam.errors import SpecError
from camcam.export.figures import fixed
from camcam.export.recovered_motion import motion_csv
from camcam.reverse.compare import motion_errors
from camcam.reverse.design import ReverseOptions, reverse_design
from camcam.reverse.fit import DEFAULT_MAX_GAP_DEG, FITS
from camcam.reverse.points import load_points
from camcam.spec import load_spec

__all__ = ["register", "compare"]


def register(sub) -> None:
    p = sub.add_parser("reverse", help=help_of("reverse"))
    p.add_argument("points", help="points: x, y (disc profile) or x, y, z (cylindrical flank), mm")
    p.add_argument("--spec", required=True, help="spec with [cam], [follower] and optionally the design [motion]")
    add_output_arguments(p)
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.add_argument("--points", dest="n_points", type=int, default=360, help="output cam angles per revolution (default 360)")
    p.add_argument("--fit", choices=FITS, default=None, help="motion fit (default: bspline, seed 002, for cylindrical cams; periodic for discs)")
    p.add_argument("--no-smoothing", action="store_true", help="interpolate exactly (points from a drawing, no measuring noise)")
    p.add_argument("--slopes", choices=("spline", "central"), default="spline", help="cylindrical flank slopes: periodic spline (default) or seed 002's central differences")
    p.add_argument("--flank", type=int, choices=(0, 1), default=0, help="cylindrical: groove wall measured, 0 = −X side (default), 1 = +X side")
    p.add_argument("--max-gap", type=float, default=DEFAULT_MAX_GAP_DEG, help=f"largest cam-angle gap between points, deg (default {DEFAULT_MAX_GAP_DEG:g})")
    p.set_defaults(func=run)


def compare(angles_deg, recovered, program, cam_kind: str) -> tuple[np.ndarray, dict]:
    """Design columns at ``angles_deg`` and the largest errors (:func:`camcam.reverse.compare.motion_errors`)."""
    return motion_errors(angles_deg, recovered, program, cam_kind)


def run(args) -> int:
    from camcam.plots.reverse import reverse_png  # plotting is loaded only when a plot is drawn
    if not 8 <= args.n_points <= 36000:
        raise SpecError("--points", f"expected a whole number of output angles from 8 to 36000, got {args.n_points}")
    if not 0 < args.max_gap <= 180:
        raise SpecError("--max-gap", f"expected degrees > 0 and <= 180, got {args.max_gap:g}")
    spec = load_spec(args.spec)
    cam = spec.need("cam", "reverse")
    follower = spec.need("follower", "reverse")
    points = load_points(args.points)
    out = output_set(args, "reverse")
    opts = ReverseOptions(fit=args.fit, smoothing=not args.no_smoothing, slopes=args.slopes, flank=args.flank,
                          max_gap_deg=args.max_gap)
    res = reverse_design(points, cam, follower, opts)
    angles, cols = res.motion.table(args.n_points)
    unit = res.unit
    summary = {
        "points": len(points),
        "points_fitted": int(res.point_lift.size),  # fewer where close points were averaged (MAX_FIT_POINTS)
        "cam": cam.kind,
        "follower": follower.kind,
        "fit": res.motion.fit,
        "smoothing": res.motion.smoothed,
        "output_points": args.n_points,
        "lift_unit": unit,
        "lift_reference": "swing centre" if cam.kind == "cylindrical" else "base circle",
        "velocity_unit": f"{unit}/deg",
        "acceleration_unit": f"{unit}/deg²",
        "max_lift": float(cols[:, 0].max()),
        "min_lift": float(cols[:, 0].min()),
    }
    design = None
    if spec.motion is not None:
        program = spec.motion.program(spec.unit)
        design, errors = compare(angles[:-1], cols[:-1], program, cam.kind)
        design = np.vstack([design, design[:1]])
        summary.update(errors)
    out.add("motion.csv", motion_csv(angles, cols))
    title = f"{points.source}: {cam.kind} cam, {follower.kind} follower ({len(points)} points)"
    out.add("reverse.png", reverse_png(angles, cols, unit, res.point_angles_deg, res.point_lift, design, title))
    out.add("summary.json", to_json(summary) + "\n")
    def show(summary: dict) -> None:
        fitted = "" if summary["points_fitted"] == len(points) else f" (averaged into {summary['points_fitted']} for the fits)"
        print(f"{len(points)} points{fitted} → {args.n_points} cam angles ({res.motion.fit} fit{', smoothed' if res.motion.smoothed else ''}); "
              f"lift {fixed(summary['min_lift'], 4)} … {fixed(summary['max_lift'], 4)} {unit} (from the {summary['lift_reference']})")
        if "max_lift_error" in summary:
            print(f"largest errors against the design: lift {summary['max_lift_error']:.3g} {unit}, velocity "
                  f"{summary['max_velocity_error']:.3g} {unit}/deg, acceleration {summary['max_acceleration_error']:.3g} {unit}/deg²")

    publish(out, summary, args.json, show)
    return 0
