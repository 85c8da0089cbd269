"""``camcam fit TABLE.csv -o DIR``: bad points, fairing and fit of a lift table.

Writes ``DIR/faired.csv`` (``angle_deg, lift_mm, velocity, acceleration, jerk``
per degree, at ``--step``), ``DIR/curvature-comb.png`` (lift-curve comb before
and after), ``DIR/roughness.png`` (difference quotients before and after) and
``DIR/summary.json``; ``--json`` prints the summary.
"""

from __future__ import annotations


from camcam.cli.commands import help_of
from camcam.cli.output import add_output_arguments, output_set, publish, to_json
from camcam.errors import SpecError
from camcam.export.faired_table import faired_csv
from camcam.lifttable.fairing import DEFAULT_METHOD, DEFAULT_XI, METHODS
from camcam.lifttable.interpolate import FITS, default_fit
from camcam.lifttable.process import FairingOptions, FittedTable, fit_table
from camcam.lifttable.table import load_lift_table

__all__ = ["register", "fit_summary"]


def register(sub) -> None:
    p = sub.add_parser("fit", help=help_of("fit"))
    p.add_argument("table", help="lift table: angle_deg, lift_mm (CSV or whitespace)")
    add_output_arguments(p)
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.add_argument("--step", type=float, default=0.5, help="faired.csv step in degrees (default 0.5)")
    p.add_argument("--xi", type=float, default=DEFAULT_XI, help=f"mid-point stop: largest correction per round, mm (default {DEFAULT_XI:g})")
    p.add_argument("--method", choices=METHODS, default=DEFAULT_METHOD, help=f"fairing method (default {DEFAULT_METHOD})")
    p.add_argument("--fit", choices=FITS, default=None, help="interpolation (default periodic for a full revolution, else clamped)")
    p.add_argument("--threshold", type=float, default=FairingOptions.threshold, help="bad point: |deviation| > threshold × noise scale (default 5)")
    p.add_argument("--min-size", type=float, default=FairingOptions.min_size, help="bad point: |deviation| > this, mm (default 0.001)")
    p.add_argument("--no-bad-points", action="store_true", help="do not look for bad points")
    p.set_defaults(func=run)


def fit_summary(ft: FittedTable) -> dict:
    """The JSON summary: bad points, fairing figures, roughness before and after."""
    fr = ft.fairing
    bad = ft.bad.points if ft.bad else ()
    return {
        "table": ft.raw.source,
        "rows": len(ft.raw),
        "full_revolution": ft.raw.full_revolution,
        "fit": ft.fit,
        "method": fr.method if fr else None,
        "bad_points_deg": sorted(p.angle_deg for p in bad),
        "bad_points": [{"angle_deg": p.angle_deg, "row": p.row, "deviation_mm": p.deviation, "score": p.score} for p in bad],
        "noise_sigma_mm": ft.bad.noise_sigma if ft.bad else None,
        "iterations": fr.iterations if fr else 0,
        "converged": fr.converged if fr else True,
        "max_correction_mm": max(float(abs(ft.table.y - ft.raw.y).max()), 0.0),
        "fairing_max_correction_mm": fr.max_correction if fr else 0.0,
        "roughness_before": ft.roughness_before.max_abs_second,
        "roughness_after": ft.roughness_after.max_abs_second,
        "roughness_unit": "mm/deg²",
    }


def run(args) -> int:
    from camcam.plots.comb import lift_comb_png  # plotting is loaded only when a plot is drawn
    from camcam.plots.roughness_plot import roughness_png  # plotting is loaded only when a plot is drawn
    from camcam.cli.motion import check_step

    check_step(args.step)
    if not args.xi > 0:
        raise SpecError("--xi", f"expected a number > 0 mm, got {args.xi:g}")
    if not args.threshold > 0:
        raise SpecError("--threshold", f"expected a number > 0, got {args.threshold:g}")
    if not args.min_size >= 0:
        raise SpecError("--min-size", f"expected a number >= 0 mm, got {args.min_size:g}")
    raw = load_lift_table(args.table)
    out = output_set(args, "fit")
    fit = args.fit or default_fit(raw.full_revolution)
    if fit == "periodic" and not raw.full_revolution:
        raise SpecError("--fit", f'"periodic" needs a full revolution; {raw.source} covers {raw.angles_deg[0]:g}–{raw.angles_deg[-1]:g}°')
    opts = FairingOptions(method=args.method, xi=args.xi, bad_points=not args.no_bad_points, threshold=args.threshold,
                          min_size=args.min_size)
    ft = fit_table(raw, fit, opts)
    summary = fit_summary(ft)
    before, after = ft.interpolant("raw"), ft.interpolant("final")
    x0, x1 = raw.angles_deg[0], raw.angles_deg[-1]
    out.add("faired.csv", faired_csv(after, x0, x1, args.step))
    out.add("curvature-comb.png", lift_comb_png(before, after, x0, x1, title=f"{raw.source}: lift-curve curvature comb ({ft.fit} fit)"))
    out.add("roughness.png", roughness_png(ft.roughness_before, ft.roughness_after, summary["bad_points_deg"]))
    out.add("summary.json", to_json(summary) + "\n")
    publish(out, summary, args.json, _show)
    return 0


def _show(summary: dict) -> None:
    bad = ", ".join(f"{p['angle_deg']:g}° ({p['deviation_mm'] * 1000:+.1f} µm)" for p in summary["bad_points"]) or "none"
    print(f"bad points: {bad}")
    print(f"fairing: {summary['method']}, {summary['iterations']} iteration(s), largest correction {summary['max_correction_mm'] * 1000:.2f} µm")
    print(f"roughness (max |second difference|): {summary['roughness_before']:.4g} → {summary['roughness_after']:.4g} mm/deg²")
