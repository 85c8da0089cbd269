"""The files of `camcam size`: the whole table, the feasible set, the best design (JSON and a
ready-to-run spec), the chart and a short HTML page.

The table is Parquet when ``pyarrow`` is installed (``pip install 'camcam[parquet]'``),
CSV otherwise.  Nothing written depends on where the sweep ran.
"""

from __future__ import annotations

import io
import math

import numpy as np

from camcam.export.jsontext import to_json
from camcam.export.spec_toml import dumps, sized_spec_data
from camcam.sizing.chart import sizing_png
from camcam.report.html import DataTable, Figure, KeyValues, Paragraph, Section, render_html
from camcam.sizing.sweep import SizingResult, grid_bounds

__all__ = ["sizing_files", "table_bytes", "parquet_available", "TOP"]

#: Designs the HTML page lists.
TOP = 10


def parquet_available() -> bool:
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return False
    return True


def _cell(v) -> str:
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (float, np.floating)):
        v = float(v)
        return "nan" if math.isnan(v) else ("inf" if v == math.inf else repr(v))
    return str(v)


def _csv(cols: dict[str, np.ndarray], rows: np.ndarray) -> bytes:
    names = list(cols)
    lines = [",".join(names)]
    data = [cols[n][rows].tolist() for n in names]
    for r in zip(*data):
        lines.append(",".join(_cell(v) for v in r))
    return ("\n".join(lines) + "\n").encode()


def _parquet(cols: dict[str, np.ndarray], rows: np.ndarray) -> bytes:
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.table({n: pa.array(v[rows]) for n, v in cols.items()})
    buf = io.BytesIO()
    pq.write_table(table, buf, compression="zstd")
    return buf.getvalue()


def table_bytes(cols: dict[str, np.ndarray], rows: np.ndarray, fmt: str) -> bytes:
    """The rows ``rows`` of the table as ``fmt`` ("parquet" or "csv")."""
    return _parquet(cols, rows) if fmt == "parquet" else _csv(cols, rows)


def _design(result: SizingResult, number: int) -> dict:
    params, laws = result.grid.design(number)
    t = result.table
    extra = ("max_contact_stress_mpa", "jump_rpm") if _dynamic(result) else ()
    return {
        "design": number,
        **{f"{k}_mm": v for k, v in params.items()},
        "laws": {f"segment {k}": v for k, v in laws.items()},
        "grid": {c: t[c][number] for c in ("max_pressure_angle_deg", "min_curvature_radius_mm", "min_concave_radius_mm",
                                           "outer_radius_mm", "pressure_angle_bound_deg", "curvature_radius_bound_mm",
                                           *extra)},
    }


def _constraints(result: SizingResult) -> list[tuple[str, str]]:
    lim = result.limits
    rows = []
    if lim.max_pressure_angle_deg is not None:
        rows.append(("max pressure angle", f"≤ {lim.max_pressure_angle_deg:g}°"))
    if lim.min_curvature_radius_rollers is not None:
        rows.append(("min radius of curvature (convex profile)", f"≥ {lim.min_curvature_radius_rollers:g} × roller radius"))
    else:
        rows.append(("min radius of curvature (convex profile)", f"≥ {lim.min_curvature_radius_mm:g} mm"))
    rows.append(("undercut / cusp", "none"))
    if lim.bore_mm > 0:
        rows.append(("bore fits", f"Ø{lim.bore_mm:g} mm within the base circle minus the roller"))
    if lim.tool_radius_mm is not None:
        rows.append(("tool fits every concave part", f"concave radius ≥ tool radius {lim.tool_radius_mm:g} mm"))
    else:
        rows.append(("tool fits every concave part", "not checked ([machining] absent or [size] tool_check = false)"))
    if lim.max_contact_stress_mpa is not None:
        rows.append(("max contact stress", f"≤ {lim.max_contact_stress_mpa:g} MPa (Hertz, [dynamics] train at "
                                           f"{result.programs[0].rpm:g} rpm)"))
    if lim.min_jump_rpm is not None:
        rows.append(("min jump speed", f"≥ {lim.min_jump_rpm:g} rpm ([dynamics] train)"))
    rows.append(("objective", "smallest outer radius" if result.objective == "outer-radius" else "smallest max pressure angle"))
    return rows


def _dynamic(result: SizingResult) -> bool:
    return "jump_rpm" in result.table


def _fmt(v: float, unit: str, digits: int = 4) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    if v == math.inf:
        return "none"
    return f"{v:.{digits}f}{unit}"


def sizing_files(result: SizingResult, spec_data: dict, name: str, table_format: str) -> dict[str, bytes | str]:
    """Every file of a sizing run, by file name."""
    ext = "parquet" if table_format == "parquet" else "csv"
    cols = result.table
    n = len(result.grid)
    files: dict[str, bytes | str] = {}
    files[f"{name}-designs.{ext}"] = table_bytes(cols, np.arange(n), table_format)
    files[f"{name}-feasible.{ext}"] = table_bytes(cols, result.ranked, table_format)
    png = sizing_png(result, name)
    files[f"{name}-sizing.png"] = png
    pa_b, rho_b = grid_bounds(result)
    step_deg = 360.0 / result.samples_per_rev
    grid_note = (f"The sweep samples the cam angle every {step_deg:g}° (each segment on its own closed interval). "
                 f"A sampled maximum is never above the true one, so no design was rejected wrongly; the estimated "
                 f"grid error of the table's figures is at most {pa_b:.2e}° of pressure angle and {rho_b:.2e} mm of "
                 f"radius of curvature over the feasible set (2·max|Δ²f|/8 around each extreme). The best design's "
                 f"figures below are from the exact geometry (root-found extremes).")
    summary = {
        "name": name,
        "follower_kind": result.kind,
        "rotation": result.rotation,
        "designs": n,
        "feasible": int(result.ranked.size),
        "objective": result.objective,
        "constraints": dict(_constraints(result)),
        "axes": {a: {"from": min(v), "to": max(v), "values": len(v)} for a, v in result.grid.axes},
        "law_choices": {f"segment {k}": sorted({c[i] for c in result.grid.combos}) for i, k in enumerate(result.grid.segments)},
        "grid": {"samples_per_rev": result.samples_per_rev, "step_deg": step_deg,
                 "pressure_angle_bound_deg": pa_b, "curvature_radius_bound_mm": rho_b},
        "exact_checks": [{"design": d, "failures": result.limits.failures(ex, result.params(d).get("roller_radius", 0.0),
                                                                          result.params(d)["base_radius"])}
                         for d, ex in result.checked],
        "best": None,
    }
    if result.note:
        summary["note"] = result.note
    best_rows: list[tuple[str, str]] = []
    if result.best is not None:
        b, ex = result.best, result.best_exact
        d = _design(result, b)
        d["exact"] = {
            "max_pressure_angle_deg": ex.max_pressure_angle_deg, "max_pressure_angle_at_deg": ex.max_pressure_angle_at_deg,
            "min_curvature_radius_mm": ex.min_curvature_radius_mm, "min_curvature_radius_at_deg": ex.min_curvature_radius_at_deg,
            "min_concave_radius_mm": ex.min_concave_radius_mm, "outer_radius_mm": ex.outer_radius_mm,
        }
        if _dynamic(result):  # as `camcam run` computes them (camcam.dynamics.cycle.analyse_dynamics)
            d["exact"]["max_contact_stress_mpa"] = ex.max_contact_stress_mpa
            d["exact"]["jump_rpm"] = ex.jump_rpm
        d["spec"] = f"{name}-best.toml"
        summary["best"] = d
        params, laws = result.grid.design(b)
        data = sized_spec_data(spec_data, f"{name}-best", params, laws)
        header = (f"The best design of `camcam size` on {name} (design {b} of {n}): run it with\n"
                  f"  camcam run {name}-best.toml -o out\n"
                  f"outer radius {ex.outer_radius_mm:.4f} mm, max pressure angle {ex.max_pressure_angle_deg:.4f}°, "
                  f"min radius of curvature {ex.min_curvature_radius_mm:.4f} mm (exact geometry)")
        files[f"{name}-best.toml"] = dumps(data, header)
        best_rows = [(k.replace("_mm", "").replace("_", " "), f"{v:g} mm") for k, v in d.items() if k.endswith("_mm")]
        best_rows += [(k, v) for k, v in d["laws"].items()]
        best_rows += [
            ("outer radius", _fmt(ex.outer_radius_mm, " mm")),
            ("max pressure angle", f"{ex.max_pressure_angle_deg:.4f}° at cam angle {ex.max_pressure_angle_at_deg:.2f}°"),
            ("min radius of curvature", f"{ex.min_curvature_radius_mm:.4f} mm at cam angle {ex.min_curvature_radius_at_deg:.2f}°"),
            ("smallest concave radius", _fmt(ex.min_concave_radius_mm, " mm")),
            *((("max contact stress", _fmt(ex.max_contact_stress_mpa, " MPa", 2)),
               ("jump speed", "never separates" if ex.jump_rpm == math.inf else _fmt(ex.jump_rpm, " rpm", 1)))
              if _dynamic(result) else ()),
            ("spec", f"{name}-best.toml (camcam run takes it as is)"),
        ]
    files[f"{name}-best.json"] = to_json(summary) + "\n"
    header = ["#", "design", *[a.replace("_", " ") + " (mm)" for a, _ in result.grid.axes],
              *[f"law seg {k}" for k in result.grid.segments], "outer radius (mm)", "max pressure angle (°)",
              "min radius of curvature (mm)", "smallest concave radius (mm)"]
    if _dynamic(result):
        header += ["max contact stress (MPa)", "jump speed (rpm)"]
    rows = []
    for i, number in enumerate(result.ranked[:TOP]):
        params, laws = result.grid.design(int(number))
        rows.append((str(i + 1), str(int(number)), *[f"{params[a]:g}" for a, _ in result.grid.axes], *laws.values(),
                     _fmt(cols["outer_radius_mm"][number], ""), _fmt(cols["max_pressure_angle_deg"][number], ""),
                     _fmt(cols["min_curvature_radius_mm"][number], ""), _fmt(cols["min_concave_radius_mm"][number], ""),
                     *((_fmt(cols["max_contact_stress_mpa"][number], "", 2), _fmt(cols["jump_rpm"][number], "", 1))
                       if _dynamic(result) else ())))
    verdict = (f"{n:,} designs, {result.ranked.size:,} feasible on the grid; best: design {result.best}"
               if result.best is not None else f"{n:,} designs, none meets every constraint")
    sections = [
        Section("Best design" if result.best is not None else "No design meets every constraint",
                (KeyValues(tuple(best_rows)),) if best_rows else (Paragraph(
                    "Widen the ranges (a larger base radius, another roller) or relax a constraint; the chart shows where "
                    "each constraint bites."),)),
        Section("Constraints", (KeyValues(tuple(_constraints(result))),)),
        Section("Sizing chart", (Figure(png, "Pressure-angle (solid) and radius-of-curvature (dashed) contours over the two "
                                        "main sweep axes, feasible region shaded, best design starred"),)),
        Section(f"Top {TOP} designs", (DataTable(tuple(header), tuple(rows), "grid figures; ranked by the objective, "
                                                 "ties by pressure angle"),)),
        Section("Grid error", (Paragraph(grid_note),)),
    ]
    if result.note:
        sections.append(Section("Note", (Paragraph(result.note),)))
    files[f"{name}-sizing.html"] = render_html(f"{name}: sizing", verdict, sections)
    return files
