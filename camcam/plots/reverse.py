"""The reverse-design plot: recovered lift, velocity, acceleration against the design."""

from __future__ import annotations

from camcam.plots.render import png_bytes, subplots
from camcam.plots.stacked import angle_axis

__all__ = ["reverse_png", "stacked_png"]


def reverse_png(angles_deg, recovered, unit: str, point_angles_deg, point_lift, design=None, title: str = "") -> bytes:
    """Three stacked axes; ``recovered`` and ``design`` are (n, 3) columns (lift, per-degree velocity, acceleration)."""
    fig, axes = subplots(3, 1, figsize=(8, 7.5))
    units = [unit, f"{unit}/deg", f"{unit}/deg²"]
    names = ["lift", "velocity", "acceleration"]
    for k, ax in enumerate(axes):
        if design is not None:
            ax.plot(angles_deg, design[:, k], color="0.55", lw=2.6, label="design")
        ax.plot(angles_deg, recovered[:, k], color="C0", lw=1.1, label="recovered")
        if k == 0:
            ax.plot(point_angles_deg, point_lift, ".", ms=2.5, color="C3", label="measured points")
        ax.set_ylabel(f"{names[k]} [{units[k]}]")
    return stacked_png(fig, axes, title or "Reverse design")


def stacked_png(fig, axes, title: str) -> bytes:
    """Finish stacked axes over one revolution of cam angle, made without ``sharex`` (grid, legend on the top
    one, 0-360° in 30° ticks: :func:`~camcam.plots.stacked.angle_axis`, the title) and render them."""
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[0].legend(loc="best", fontsize=8)
    angle_axis(axes, grid_alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    return png_bytes(fig)
