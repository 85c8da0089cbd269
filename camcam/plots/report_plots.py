"""Plots of the tolerance report: deviation along the profile, design vs as-machined motion."""

from __future__ import annotations

import numpy as np

from camcam.plots.render import TITLE_Y, png_bytes, subplots
from camcam.plots.stacked import angle_axis

__all__ = ["deviation_png", "fitted_motion_png", "DEVIATION_LAYOUT", "FITTED_LAYOUT"]

#: Figure margins (fractions), fixed instead of tight_layout (a second draw: 0.1–0.3 s a plot);
#: tests/plots check that nothing is cut off or overlaps.
DEVIATION_LAYOUT = dict(left=0.15, right=0.965, bottom=0.185, top=0.89)
FITTED_LAYOUT = dict(left=0.14, right=0.965, bottom=0.07, top=0.94, hspace=0.3)


def deviation_png(angles_deg: np.ndarray, deviation_mm: np.ndarray, tolerance_mm: float, title: str) -> bytes:
    """Signed deviation against cam angle with the ±tolerance band."""
    fig, ax = subplots(figsize=(8, 3.2))
    ax.axhspan(-tolerance_mm, tolerance_mm, color="C2", alpha=0.12, label=f"±{tolerance_mm:g} mm tolerance")
    ax.plot(angles_deg, deviation_mm, color="C0", lw=1.0, label="printed path − exact")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 30))
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("deviation [mm]\n(+ leaves stock)")
    ax.set_ylim(-1.3 * tolerance_mm, 1.3 * tolerance_mm)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, alpha=0.3)
    ax.set_title(title, fontsize=10, y=TITLE_Y)
    fig.subplots_adjust(**DEVIATION_LAYOUT)
    return png_bytes(fig)


def fitted_motion_png(angles_deg: np.ndarray, design: np.ndarray, fitted: np.ndarray, units, title: str) -> bytes:
    """Design and as-machined lift, velocity, acceleration, jerk, stacked.

    ``design`` and ``fitted`` are (4, n) over ``angles_deg`` (n,), in ``units`` (4 strings).
    """
    names = ["lift", "velocity", "acceleration", "jerk"]
    fig, axes = subplots(4, 1, figsize=(8, 8.5))
    for k, ax in enumerate(axes):
        ax.plot(angles_deg, design[k], color="0.2", lw=1.6, label="design")
        style = dict(ls="none", marker=".", ms=2.5) if k == 3 else dict(lw=0.9)
        ax.plot(angles_deg, fitted[k], color="C3", label="as machined (fitted program)", **style)
        ax.set_ylabel(f"{names[k]}\n[{units[k]}]")
        ax.grid(True, alpha=0.3)
    err = np.abs(np.asarray(fitted) - np.asarray(design))
    i_a, i_j = int(np.argmax(err[2])), int(np.argmax(err[3]))
    axes[0].legend(loc="upper right", fontsize=8)
    axes[2].set_title(f"largest acceleration error {err[2][i_a]:.4g} {units[2]} at {angles_deg[i_a]:g}°", fontsize=9,
                      y=TITLE_Y)
    axes[3].set_title(f"largest jerk error {err[3][i_j]:.4g} {units[3]} at {angles_deg[i_j]:g}° "
                      f"(jerk is impulsive at every arc join)", fontsize=9, y=TITLE_Y)
    angle_axis(axes, grid_alpha=0.3)
    fig.suptitle(title)
    fig.subplots_adjust(**FITTED_LAYOUT)
    return png_bytes(fig)
