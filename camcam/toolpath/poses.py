"""The tool a barrel-cam program cuts with, and its poses as printed.

:class:`CylinderTool` is the flat end mill (radius, cutting length);
:class:`ToolPoses` the tool tip X Y Z and the A and B angles of every
printed position, read back from the program text
(:func:`camcam.post.readback.read_poses`) or from rs274's canonical moves
(:func:`camcam.verify.rs274.poses_from_canon`).  :mod:`camcam.verify.groove3d`
measures the groove they cut.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ToolPoses", "CylinderTool", "A_AXIS_SENSE", "frozen_array"]

#: Sign of the part's turn for a positive A: Rx(sign·A).
A_AXIS_SENSE = {"right-hand": 1, "left-hand": -1}


def frozen_array(a) -> np.ndarray:
    """``a`` as a read-only float array."""
    arr = np.array(a, dtype=float)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class ToolPoses:
    """Tool poses as printed: tip X Y Z (mm), A and B (degrees), in program order.

    The tool moves linearly in every axis word from one pose to the next.

    Examples
    --------
    >>> p = ToolPoses([[0.0, 0.0, 60.0], [10.0, 0.0, 60.0]], [0.0, 90.0], [0.0, 0.0])
    >>> len(p), p.a_axis
    (2, 'right-hand')
    """

    tip_mm: np.ndarray
    a_deg: np.ndarray
    b_deg: np.ndarray
    a_axis: str = "right-hand"

    def __post_init__(self) -> None:
        tip = frozen_array(self.tip_mm)
        a = frozen_array(self.a_deg)
        b = frozen_array(self.b_deg)
        if tip.ndim != 2 or tip.shape[1] != 3 or len(tip) < 2:
            raise ValueError(f"tip_mm must be (n, 3) with n ≥ 2, got shape {tip.shape}")
        if a.shape != (len(tip),) or b.shape != (len(tip),):
            raise ValueError(f"a_deg and b_deg must have {len(tip)} values, got {a.shape} and {b.shape}")
        if not (np.all(np.isfinite(tip)) and np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            raise ValueError("tool poses must be finite")
        if np.any(np.abs(b) >= 90.0):
            raise ValueError("B must stay within ±90°")
        if self.a_axis not in A_AXIS_SENSE:
            raise ValueError(f'a_axis must be "right-hand" or "left-hand", got {self.a_axis!r}')
        object.__setattr__(self, "tip_mm", tip)
        object.__setattr__(self, "a_deg", a)
        object.__setattr__(self, "b_deg", b)

    def __len__(self) -> int:
        return len(self.a_deg)


@dataclass(frozen=True)
class CylinderTool:
    """A flat end mill: ``radius_mm``, cutting length ``length_mm`` from the tip."""

    radius_mm: float
    length_mm: float

    def __post_init__(self) -> None:
        if not (self.radius_mm > 0 and self.length_mm > 0):
            raise ValueError(f"tool radius and length must be > 0, got {self.radius_mm!r}, {self.length_mm!r}")
