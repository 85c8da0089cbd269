"""The 3-D deviation map of a barrel cam's groove walls: radius × cam angle, colour = deviation."""

from __future__ import annotations

import numpy as np

from camcam.plots.render import png_bytes, subplots
from camcam.plots.stacked import angle_axis

__all__ = ["groove_map_png"]


def groove_map_png(groove, tolerance_mm: float, title: str) -> bytes:
    """Both walls' signed deviation (+ overcut, − material left) over radius and cam angle.

    The colour scale is symmetric about 0 and spans at least ±2·tolerance; the
    black contour marks ±tolerance, the markers the refined extremes.
    """
    dev = np.asarray(groove.deviation_mm)
    finite = np.abs(dev[np.isfinite(dev)])
    span = max(2.0 * tolerance_mm, float(np.percentile(finite, 99.5)) if finite.size else tolerance_mm)
    fig, axes = subplots(2, 1, figsize=(8.5, 5.4))
    ang, rad = np.asarray(groove.cam_angle_deg), np.asarray(groove.radii_mm)
    mesh = None
    for w, ax in zip(groove.walls, axes):
        z = np.clip(dev[w.index], -span, span)
        mesh = ax.pcolormesh(ang, rad, z, cmap="RdBu_r", vmin=-span, vmax=span, shading="nearest")
        if len(rad) > 1:
            ax.contour(ang, rad, dev[w.index], levels=[-tolerance_mm, tolerance_mm], colors="k", linewidths=0.7)
        ax.plot([w.overcut.cam_angle_deg], [w.overcut.radius_mm], marker="^", color="k", ms=6, ls="none",
                label=f"largest overcut {w.overcut_mm:.4f} mm")
        ax.plot([w.material_left.cam_angle_deg], [w.material_left.radius_mm], marker="v", color="k", ms=6,
                mfc="w", ls="none", label=f"largest material left {w.material_left_mm:.4f} mm")
        ax.set_ylabel(f"{w.label}\nradius [mm]", fontsize=9)
        ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    angle_axis(axes)
    bar = fig.colorbar(mesh, ax=list(axes), shrink=0.9)
    bar.set_label(f"deviation normal to the wall [mm]\n(+ overcut, − material left; black: ±{tolerance_mm:g} mm)",
                  fontsize=8)
    fig.suptitle(title, fontsize=10)
    return png_bytes(fig)
