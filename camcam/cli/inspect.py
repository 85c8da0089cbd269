"""``camcam inspect SPEC MEASURED -o DIR``: the part as measured against the design, with a verdict.

MEASURED is CMM points on a disc cam's profile (``x_mm, y_mm[, z_mm]``, with
``--bore FILE`` to find the centre from bore points), a dial-indicator table
(``angle_deg, reading_mm`` with ``--probe-radius``) or points on a barrel cam's
groove walls (``x_mm, y_mm, z_mm``, cam axis along X): :mod:`camcam.inspect`.
The kind follows the spec's cam and the file (``--kind`` to say it): a
cylindrical cam's file is wall points; a disc's is a dial table when its header
names an angle or ``--probe-radius`` is given, else CMM points.

Writes ``DIR/report.html``, ``DIR/report.json``, ``DIR/deviation.csv`` (every
point: row, cam angle, deviation, kept) and the plots, all or nothing; exit 3
with one stderr line naming the worst point when the part is out of tolerance.
With ``--program`` and a disc spec with ``[machining]``, the NC program is
planned too and its predicted deviation drawn on the same axes.
"""

from __future__ import annotations

import sys
from pathlib import Path

from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, output_set, publish
from camcam.errors import InputError, SpecError
from camcam.inputs import read_text
from camcam.verdict import OUT_OF_TOLERANCE

__all__ = ["register", "run", "guess_kind"]

KIND_CHOICES = ("cmm", "dial", "barrel")
ALIGN_CHOICES = ("none", "rotation", "rigid")


def register(sub) -> None:
    p = sub.add_parser("inspect", help=help_of("inspect"))
    p.add_argument("spec", help="the part's spec (TOML) with [motion], [cam], [follower]; tolerance from "
                                "[inspection] tolerance, else [machining] tolerance")
    p.add_argument("measured", help="CMM points x, y[, z]; a dial table angle_deg, reading_mm; or barrel wall points x, y, z")
    add_output_arguments(p)
    p.add_argument("--kind", choices=KIND_CHOICES, default=None, help="what MEASURED holds (default: from the spec's cam and the file)")
    p.add_argument("--bore", default=None, help="CMM bore points x, y[, z]: the part's centre is the bore's")
    p.add_argument("--probe-radius", type=float, default=None, help="dial indicator: the probe's tip radius, mm")
    p.add_argument("--align", choices=ALIGN_CHOICES, default="rotation", help="fit nothing, the rotation (default) or rotation and translation")
    p.add_argument("--max-rotation", type=float, default=2.0, help="refuse a fitted rotation above this, degrees (default 2)")
    p.add_argument("--no-motion", action="store_true", help="skip the reverse fit of the motion (deviation only)")
    p.add_argument("--program", action="store_true", help="plan the NC program ([machining], disc cams) and draw its predicted deviation")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.set_defaults(func=run)


def guess_kind(cam_kind: str, text: str, probe_radius) -> str:
    """The measured kind of a file (module docstring).

    Examples
    --------
    >>> guess_kind("disc", "angle_deg, reading_mm\\n0, 0.1\\n", None), guess_kind("disc", "1, 2\\n", None)
    ('dial', 'cmm')
    >>> guess_kind("cylindrical", "1, 2, 3\\n", None)
    'barrel'
    """
    if cam_kind == "cylindrical":
        return "barrel"
    if probe_radius is not None:
        return "dial"
    for line in text.splitlines():
        s = line.strip()
        if s and not s.startswith("#"):
            return "dial" if s.lower().startswith("angle") else "cmm"
    return "cmm"


def _tolerance(spec) -> float:
    if spec.inspection is not None and spec.inspection.tolerance_mm is not None:
        return spec.inspection.tolerance_mm
    if spec.machining is not None:
        return spec.machining.tolerance_mm
    raise SpecError("inspection.tolerance", "missing; `camcam inspect` needs [inspection] tolerance or a [machining] "
                                            "table whose tolerance it takes")


def _predicted(built, spec):
    """The NC program's deviation along the cam angle (as the run report draws it), or None."""
    import numpy as np

    from camcam.geometry.disc import DiscCam
    from camcam.nc import machine_program
    from camcam.report.deviation_along import signed_deviation

    if spec.machining is None or not isinstance(built.cam, DiscCam):
        return None
    m = machine_program(built, spec.machining, spec.name)
    ang = np.arange(0.0, 360.0, 0.25)
    th = np.radians(ang)
    c = m.contours[0]
    return ang, signed_deviation(c.curve, c.printed, th, built.cam.normal(th))


def _check_file(path: str, what: str) -> str:
    if Path(path).is_dir():
        raise InputError(f"{path}: a folder where the {what} file was expected")
    return read_text(path)


def run(args) -> int:
    from camcam.geometry.build import build_cam
    from camcam.inspect import InspectOptions, inspect_part, parse_bore, parse_measured
    from camcam.report.inspect_page import inspection_report
    from camcam.spec import load_spec

    if not 0 < args.max_rotation <= 180:
        raise SpecError("--max-rotation", f"expected degrees > 0 and <= 180, got {args.max_rotation:g}")
    if args.probe_radius is not None and not 0 <= args.probe_radius <= 1000:
        raise SpecError("--probe-radius", f"expected mm from 0 to 1000, got {args.probe_radius:g}")
    if Path(args.spec).is_dir():
        raise InputError(f"{args.spec}: a folder where the spec file was expected")
    spec = load_spec(args.spec)
    cam_spec = spec.need("cam", "inspect")
    follower = spec.need("follower", "inspect")
    motion = spec.need("motion", "inspect")
    tolerance = _tolerance(spec)
    text = _check_file(args.measured, "measured")
    kind = args.kind or guess_kind(cam_spec.kind, text, args.probe_radius)
    part = parse_measured(text, kind, Path(args.measured).name)
    bore = None
    if args.bore is not None:
        if kind != "cmm":
            raise InputError(f"--bore: bore points locate a CMM part's centre; {args.measured} is {kind} data")
        bore = parse_bore(_check_file(args.bore, "bore"), Path(args.bore).name)
    out = output_set(args, "inspect")
    program = motion.program(spec.unit)
    built = build_cam(cam_spec, follower, program)
    opts = InspectOptions(tolerance_mm=tolerance, align=args.align, max_rotation_deg=args.max_rotation,
                          probe_radius_mm=args.probe_radius, bore=bore, motion=not args.no_motion)
    ins = inspect_part(built, cam_spec, follower, program, part, opts)
    predicted = _predicted(built, spec) if args.program else None
    rep = inspection_report(ins, built.cam, part.source, spec.name, predicted)
    for name, data in rep.files.items():
        out.add(name, data)
    lines = ["row,cam_angle_deg,deviation_mm,kept" + (",wall" if ins.wall is not None else "")]
    for i in range(len(ins.deviation_mm)):
        wall = f",{int(ins.wall[i])}" if ins.wall is not None else ""
        lines.append(f"{ins.rows[i]},{ins.angle_deg[i]:.4f},{ins.deviation_mm[i]:.6f},{int(ins.kept[i])}{wall}")
    out.add("deviation.csv", "\n".join(lines) + "\n")
    summary = dict(rep.summary)

    def show(s: dict) -> None:
        al = ins.alignment
        print(f"{s['points']} points ({kind}), {len(ins.outliers)} outlier(s) left out; alignment {al.mode}: rotation "
              f"{al.rotation_deg:+.4f}° ± {al.rotation_sigma_deg:.4f}°, translation "
              + ", ".join(f"{v:+.4f}" for v in al.translation_mm) + " mm")
        print(f"deviation {s['min_deviation_mm']:+.4f} … {s['max_deviation_mm']:+.4f} mm (tolerance ±{tolerance:g} mm); "
              f"worst at {s['worst_angle_deg']:.2f}°")
        if ins.motion:
            print(f"motion of the measured cam: largest acceleration error {s['max_acceleration_error']:.4g} "
                  f"{ins.motion[0].unit}/deg²")
        if ins.motion_note:
            print(f"note: {ins.motion_note}")

    publish(out, summary, args.json, show, (ins.worst_line(),))
    if not ins.passed:
        print(f"camcam: {ins.worst_line()}", file=sys.stderr)
        return OUT_OF_TOLERANCE
    return 0
