"""The SVAJ plot: displacement, velocity, acceleration and jerk over the revolution."""

from __future__ import annotations

import numpy as np

from camcam.motion.program import MotionProgram
from camcam.plots.render import png_bytes, subplots
from camcam.plots.stacked import angle_axis, vertical_lines

__all__ = ["svaj_png", "LAYOUT"]

#: Figure margins (fractions): room for two-line axis labels and 7-character tick labels.
LAYOUT = dict(left=0.14, right=0.965, bottom=0.07, top=0.945, hspace=0.15)


def svaj_png(program: MotionProgram, title: str = "", points_per_degree: int = 4) -> bytes:
    """Four stacked axes with units; segment boundaries dashed; jumps drawn as jumps."""
    fig, axes = subplots(4, 1, figsize=(8, 8.5))
    names = ["displacement", "velocity", "acceleration", "jerk"]
    # one line an axes, the segments apart (a NaN between them): a jump is drawn as a jump, not joined
    angles, values = [], [[] for _ in axes]
    for seg in program.segments:
        n = max(2, int((seg.end_deg - seg.start_deg) * points_per_degree) + 1)
        T = np.linspace(0.0, 1.0, n)
        angles += [seg.start_deg + T * (seg.end_deg - seg.start_deg), [np.nan]]
        for k in range(len(axes)):
            values[k] += [program.to_physical(seg.derivative(T, k) + (seg.base if k == 0 else 0.0), k), [np.nan]]
    boundaries = [seg.start_deg for seg in program.segments[1:]]
    for k, ax in enumerate(axes):
        ax.plot(np.concatenate(angles), np.concatenate(values[k]), color="C0", lw=1.4)
        ax.set_ylabel(f"{names[k]}\n[{program.units[k]}]")
        ax.grid(True, alpha=0.3)
        ax.add_collection(vertical_lines(ax, boundaries, color="0.5", ls="--", lw=0.8), autolim=False)
        ax.axhline(0.0, color="0.3", lw=0.6)
    angle_axis(axes, grid_alpha=0.3)
    fig.suptitle(title or f"Motion program at {program.rpm:g} rpm")
    # fixed margins, not tight_layout (a second draw: 0.1–0.3 s a plot); tests/plots check nothing is cut off
    fig.subplots_adjust(**LAYOUT)
    return png_bytes(fig)
