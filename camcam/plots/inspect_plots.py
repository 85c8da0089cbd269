"""The plots of `camcam inspect`: deviation along the cam angle, a polar view exaggerated, motion errors."""

from __future__ import annotations

import math

import numpy as np

from camcam.plots.render import png_bytes, subplots
from camcam.plots.reverse import stacked_png

__all__ = ["deviation_along_png", "polar_deviation_png", "motion_error_png", "exaggeration"]

_WALL_COLOURS = ("C0", "C2")


def deviation_along_png(angle_deg, deviation_mm, outlier, tolerance_mm: float, worst: int, wall=None,
                        predicted=None, title: str = "") -> bytes:
    """Measured deviation (+ material left) against the cam angle with the ± tolerance band; outliers as
    crosses, the worst point ringed; ``predicted`` (angles, deviation) the NC program's own, when known."""
    angle_deg, dev, outlier = np.asarray(angle_deg), np.asarray(deviation_mm), np.asarray(outlier, dtype=bool)
    fig, ax = subplots(figsize=(9, 4.2))
    ax.axhspan(-tolerance_mm, tolerance_mm, color="0.9", label=f"tolerance ±{tolerance_mm:g} mm")
    ax.axhline(0.0, color="0.5", lw=0.8)
    groups = [(~outlier, "measured points", "C0")] if wall is None else [
        (~outlier & (np.asarray(wall) == w), f"wall {w} ({'−X' if w == 0 else '+X'} side)", _WALL_COLOURS[w]) for w in (0, 1)]
    for mask, label, colour in groups:
        order = np.argsort(angle_deg[mask])
        ax.plot(angle_deg[mask][order], dev[mask][order], ".", ms=3, color=colour, label=label)
    if predicted is not None:
        ax.plot(predicted[0], predicted[1], color="C1", lw=1.0, label="NC program, predicted (printed path − design)")
    kept = dev[~outlier]
    span = max(float(np.abs(kept).max()), tolerance_mm) * 1.3
    if outlier.any():  # off the scale: drawn at its edge
        ax.plot(angle_deg[outlier], np.clip(dev[outlier], -0.97 * span, 0.97 * span), "x", color="C3", ms=7,
                label="outliers (left out; at the edge when off the scale)")
    ax.plot([angle_deg[worst]], [dev[worst]], "o", mfc="none", mec="k", ms=11, label=f"worst {dev[worst]:+.4f} mm")
    ax.set_ylim(-span, span)
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 30))
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("normal deviation [mm] (+ material left)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=7, ncol=2)
    ax.set_title(title or "Deviation along the cam angle", fontsize=10)
    fig.tight_layout()
    return png_bytes(fig)


def exaggeration(size_mm: float, deviation_mm: float) -> float:
    """A round factor that draws ``deviation_mm`` as about 8 % of ``size_mm`` (1, 2 or 5 × a power of ten).

    Examples
    --------
    >>> exaggeration(100.0, 0.03)
    200.0
    """
    raw = 0.08 * size_mm / max(deviation_mm, 1e-9)
    p = 10.0 ** math.floor(math.log10(raw))
    return float(max(m * p for m in (1.0, 2.0, 5.0) if m * p <= raw))


def polar_deviation_png(nominal_xy, nominal_normal, foot_xy, normal_xy, deviation_mm, outlier, tolerance_mm: float,
                        factor: float, title: str = "", labels: tuple[str, str] = ("x [mm]", "y [mm]")) -> bytes:
    """The nominal outline (closed polyline) with its tolerance band and the measured points, both drawn
    ``factor`` × their deviation off it along the normal (the scale is in the title); ``labels`` of the axes."""
    nominal_xy, nominal_normal = np.asarray(nominal_xy), np.asarray(nominal_normal)
    foot_xy, normal_xy = np.asarray(foot_xy), np.asarray(normal_xy)
    dev, outlier = np.asarray(deviation_mm), np.asarray(outlier, dtype=bool)
    fig, ax = subplots(figsize=(6.4, 6.4))
    ring = np.vstack([nominal_xy, nominal_xy[:1]])
    nrm = np.vstack([nominal_normal, nominal_normal[:1]])
    hi, lo = ring + factor * tolerance_mm * nrm, ring - factor * tolerance_mm * nrm
    ax.fill(np.concatenate([hi[:, 0], lo[::-1, 0]]), np.concatenate([hi[:, 1], lo[::-1, 1]]), color="0.88", lw=0,
            label=f"tolerance ±{tolerance_mm:g} mm")
    ax.plot(ring[:, 0], ring[:, 1], color="0.35", lw=0.8, label="design")
    drawn = foot_xy + factor * dev[:, None] * normal_xy
    k = ~outlier
    ax.plot(drawn[k, 0], drawn[k, 1], ".", ms=2.5, color="C0", label="measured")
    if outlier.any():
        ax.plot(drawn[outlier, 0], drawn[outlier, 1], "x", ms=6, color="C3", label="outliers")
    ax.plot([0], [0], "+", color="k", ms=10)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.legend(loc="upper right", fontsize=7)
    ax.set_title((title + "\n" if title else "") + f"deviations drawn × {factor:g} (1 mm drawn = {1000 / factor:g} µm)",
                 fontsize=9)
    fig.tight_layout()
    return png_bytes(fig)


def motion_error_png(checks, title: str = "") -> bytes:
    """Recovered − design lift, velocity and acceleration along the cam angle, one line per check (wall)."""
    fig, axes = subplots(3, 1, figsize=(8, 7))
    names = ["lift", "velocity", "acceleration"]
    for m in checks:
        units = [m.unit, f"{m.unit}/deg", f"{m.unit}/deg²"]
        label = "measured cam − design" if m.wall is None else f"wall {m.wall}"
        for k, ax in enumerate(axes):
            ax.plot(m.angles_deg, m.recovered[:, k] - m.design[:, k], lw=1.0, label=label)
            ax.set_ylabel(f"{names[k]} error [{units[k]}]")
    for ax in axes:
        ax.axhline(0.0, color="0.5", lw=0.8)
    return stacked_png(fig, axes, title or "Motion of the measured cam against the design (seed 002 reverse fit)")
