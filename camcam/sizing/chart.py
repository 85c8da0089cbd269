"""The sizing chart: pressure-angle and curvature-radius contours over the two main sweep axes,
the feasible region shaded, the best design marked (the classic pressure-angle chart, for
this motion and every constraint at once).
"""

from __future__ import annotations

import numpy as np

from camcam.plots.render import Line2D, Rectangle, png_bytes, subplots

__all__ = ["sizing_png", "main_axes", "anchor_design"]

LABELS = {"base_radius": "base radius R_b (mm)", "offset": "offset e (mm)", "roller_radius": "roller radius r_r (mm)",
          "pivot_distance": "pivot distance (mm)", "arm_length": "arm length (mm)"}


def main_axes(result) -> list[int]:
    """Indices of the swept numeric axes (more than one value), in table order; the chart uses the first two."""
    return [i for i, (_, vals) in enumerate(result.grid.axes) if len(vals) > 1]


def anchor_design(result) -> int:
    """The design the chart's slice goes through: the best, else the first feasible, else the lowest pressure angle."""
    if result.best is not None:
        return result.best
    if result.ranked.size:
        return int(result.ranked[0])
    pa = np.where(result.table["valid"], result.table["max_pressure_angle_deg"], np.inf)
    return int(np.argmin(pa))


def _slice(result, anchor: int, free: list[int]) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    g = result.grid
    combo, k = divmod(anchor, g.per_combo)
    at = np.unravel_index(k, g.shape)
    index = tuple(slice(None) if i in free else at[i] for i in range(len(g.shape)))
    numbers = (np.arange(g.per_combo).reshape(g.shape)[index] + combo * g.per_combo)
    cols = {c: result.table[c][numbers] for c in ("max_pressure_angle_deg", "min_curvature_radius_mm", "feasible", "valid")}
    return numbers, cols


def _title(result, anchor: int, free: list[int]) -> str:
    params, laws = result.grid.design(anchor)
    fixed = [f"{n.replace('_', ' ')} {params[n]:g} mm" for i, (n, _) in enumerate(result.grid.axes) if i not in free]
    fixed += [f"segment {k}: {v}" for k, v in laws.items()]
    return ("at " + ", ".join(fixed)) if fixed else ""


def sizing_png(result, name: str) -> bytes:
    """The chart as PNG bytes (same result, same bytes)."""
    axes = main_axes(result)
    anchor = anchor_design(result)
    lim_pa = result.limits.max_pressure_angle_deg
    params = result.grid.design(anchor)[0]
    lim_rho = float(result.limits.curvature_limit(params.get("roller_radius", 0.0)))
    fig, ax = subplots(figsize=(8.4, 6.0))
    star = dict(marker="*", s=260, color="#d62728", edgecolor="black", zorder=5, label="best design")
    if len(axes) >= 2:
        ia, ib = axes[0], axes[1]
        _, cols = _slice(result, anchor, [ia, ib])
        x = np.asarray(result.grid.axes[ia][1])
        y = np.asarray(result.grid.axes[ib][1])
        # the slice is indexed [a, b]: transpose so rows run along y
        pa = np.where(cols["valid"], cols["max_pressure_angle_deg"], np.nan).T
        rho = np.where(cols["valid"], cols["min_curvature_radius_mm"], np.nan).T
        feas = cols["feasible"].T.astype(float)
        if feas.any():
            ax.contourf(x, y, feas, levels=[0.5, 1.5], colors=["#b7e4c7"], alpha=0.8)
        cs = ax.contour(x, y, pa, levels=10, colors="#1f5fa8", linewidths=0.8)
        ax.clabel(cs, fmt="%.0f°", fontsize=8)
        if lim_pa is not None and np.nanmin(pa) < lim_pa < np.nanmax(pa):
            ax.contour(x, y, pa, levels=[lim_pa], colors="#1f5fa8", linewidths=2.2)
        rho_f = np.where(np.isfinite(rho), rho, np.nan)
        if np.isfinite(rho_f).sum() > 3 and np.nanmax(rho_f) > np.nanmin(rho_f):
            cr = ax.contour(x, y, rho_f, levels=8, colors="#e07b00", linewidths=0.8, linestyles="--")
            ax.clabel(cr, fmt="%.0f mm", fontsize=8)
            if np.nanmin(rho_f) < lim_rho < np.nanmax(rho_f):
                ax.contour(x, y, rho_f, levels=[lim_rho], colors="#e07b00", linewidths=2.2, linestyles="--")
        if result.best is not None:
            ax.scatter([params[result.grid.axes[ia][0]]], [params[result.grid.axes[ib][0]]], **star)
        ax.set_xlabel(LABELS.get(result.grid.axes[ia][0], result.grid.axes[ia][0]))
        ax.set_ylabel(LABELS.get(result.grid.axes[ib][0], result.grid.axes[ib][0]))
        handles = [Line2D([], [], color="#1f5fa8", lw=1.2, label="max pressure angle (°)"),
                   Line2D([], [], color="#e07b00", lw=1.2, ls="--", label="min radius of curvature (mm)"),
                   Rectangle((0, 0), 1, 1, color="#b7e4c7", label="feasible")]
        if result.best is not None:
            handles.append(Line2D([], [], marker="*", color="#d62728", ls="", markersize=14, label="best design"))
        ax.legend(handles=handles, loc="upper right", fontsize=8, framealpha=0.9)
    elif len(axes) == 1:
        ia = axes[0]
        _, cols = _slice(result, anchor, [ia])
        x = np.asarray(result.grid.axes[ia][1])
        rho = np.where(cols["valid"], cols["min_curvature_radius_mm"], np.nan)
        ax.plot(x, rho, color="#e07b00", ls="--", label="min radius of curvature (mm)")
        ax.set_ylabel("min radius of curvature (mm)")
        ax.axhline(lim_rho, color="#e07b00", lw=0.8)
        feas = cols["feasible"]
        if feas.any():
            ax.fill_between(x, 0, 1, where=feas, color="#b7e4c7", alpha=0.8, transform=ax.get_xaxis_transform(), label="feasible")
        if lim_pa is not None:
            ax2 = ax.twinx()
            ax2.plot(x, np.where(cols["valid"], cols["max_pressure_angle_deg"], np.nan), color="#1f5fa8", label="max pressure angle (°)")
            ax2.axhline(lim_pa, color="#1f5fa8", lw=0.8)
            ax2.set_ylabel("max pressure angle (°)")
        if result.best is not None:
            ax.scatter([params[result.grid.axes[ia][0]]], [result.table["min_curvature_radius_mm"][result.best]], **star)
        ax.set_xlabel(LABELS.get(result.grid.axes[ia][0], result.grid.axes[ia][0]))
        ax.legend(loc="upper left", fontsize=8)
    else:
        obj = result.table[result.objective_column]
        colours = np.where(result.table["feasible"], "#2a9d55", "#bbbbbb")
        ax.bar(np.arange(obj.size), np.nan_to_num(obj), color=colours)
        if result.best is not None:
            ax.scatter([result.best], [obj[result.best]], **star)
        ax.set_xlabel("design")
        ax.set_ylabel(result.objective_column.replace("_", " "))
    ax.set_title(f"{name}: sizing chart {_title(result, anchor, axes[:2])}", fontsize=10)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return png_bytes(fig)
