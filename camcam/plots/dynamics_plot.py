"""The report's dynamics plot: contact force, camshaft torque and contact stress over the cam angle."""

from __future__ import annotations

import numpy as np

from camcam.plots.render import png_bytes, subplots
from camcam.plots.stacked import angle_axis

__all__ = ["dynamics_png", "DYNAMICS_LAYOUT"]

#: Figure margins (fractions), fixed instead of tight_layout (module notes of camcam.plots.report_plots).
DYNAMICS_LAYOUT = dict(left=0.12, right=0.965, bottom=0.08, top=0.93, hspace=0.3)


def dynamics_png(angles_deg, contact_force_n, torque_nm, stress_mpa, title: str, *, return_flank_n=None,
                 allowable_mpa: float | None = None, jump_angle_deg: float | None = None) -> bytes:
    """Three stacked panels over the cam angle: contact force (a groove's two flanks), torque, Hertz stress."""
    fig, axes = subplots(3, 1, figsize=(8, 7.5))
    f = np.asarray(contact_force_n, float)
    if return_flank_n is not None:
        axes[0].plot(angles_deg, np.maximum(f, 0.0), color="C0", lw=1.1, label="lift flank")
        axes[0].plot(angles_deg, np.asarray(return_flank_n, float), color="C1", lw=1.1, label="return flank")
        axes[0].legend(loc="upper right", fontsize=8)
    else:
        axes[0].plot(angles_deg, f, color="C0", lw=1.1)
        axes[0].axhline(0, color="C3", lw=0.8)
    if jump_angle_deg is not None:
        axes[0].axvline(jump_angle_deg, color="C3", lw=0.8, ls="--", label="first to let go")
    axes[0].set_ylabel("contact force\n[N]")
    axes[1].plot(angles_deg, torque_nm, color="C2", lw=1.1)
    axes[1].axhline(0, color="0.3", lw=0.6)
    axes[1].set_ylabel("camshaft torque\n[N·m]")
    axes[2].plot(angles_deg, stress_mpa, color="C4", lw=1.1)
    if allowable_mpa is not None:
        axes[2].axhline(allowable_mpa, color="C3", lw=0.9, ls="--", label=f"allowable {allowable_mpa:g} MPa")
        axes[2].legend(loc="upper right", fontsize=8)
    axes[2].set_ylabel("Hertz contact\nstress [MPa]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    angle_axis(axes, grid_alpha=0.3)
    fig.suptitle(title)
    fig.subplots_adjust(**DYNAMICS_LAYOUT)
    return png_bytes(fig)
