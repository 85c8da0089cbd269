"""How deep a barrel cam's program takes the tool, and how much of the tool cuts: read from the printed poses.

A barrel program's tool is a flat end mill whose tip (the centre of its flat end) the program prints at
(X, Y, Z) with the axis tilted by B in the X–Z plane (B = 0 on 4 axes).  The flat end is a disc of the
tool's radius r_t about the tip, normal to the axis (sin B, 0, cos B); its point farthest toward the cam
axis lies r_t·|sin B| below the tip (for Y = 0 and |Z·sin B| > r_t·cos² B, as on every barrel program
camcam writes; on 4 axes the tip itself), so the deepest radius the tool reaches is
min(√(Y² + Z²) − r_t·|sin B|) over the printed poses.  The cut runs up the tool to where its side leaves
the cam's outer cylinder R: (R + r_t·|sin B| − Z)/cos B from the tip, which is the flute the program
needs (:meth:`camcam.nc.fiveaxis.ToolPose.cut_length` on the exact poses).

The ``cut depth`` check holds the program's deepest point below the top (R − that radius) to the depth
the walls need: the groove depth plus the dip the job plans below the groove floor (a 4-axis tool's
flat end reaching the wall corner, a tilted 5-axis flat end reaching both walls at the bottom).  It is a
warning, as the other design checks: a deeper cut goes into the groove floor, which no roller touches.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.toolpath.poses import ToolPoses
from camcam.verdict import Check

__all__ = ["ToolReach", "tool_reach", "flute_text", "flute_to_buy_mm"]


@dataclass(frozen=True, kw_only=True)
class ToolReach:
    """The printed program's reach (mm): its deepest radius, the flute it needs, and what the walls need."""

    top_radius_mm: float  # the cam's outer radius R
    bottom_radius_mm: float  # the groove floor
    deepest_radius_mm: float  # measured on the printed poses
    needed_radius_mm: float  # the deepest the plan has to go (the floor less the planned dip)
    flute_needed_mm: float  # measured on the printed poses
    flute_length_mm: float  # the spec's
    print_step_mm: float  # one unit of the post's last printed decimal
    why: str  # why the plan dips below the floor (or "")

    @property
    def depth_mm(self) -> float:
        """The deepest point below the top."""
        return self.top_radius_mm - self.deepest_radius_mm

    @property
    def needed_depth_mm(self) -> float:
        return self.top_radius_mm - self.needed_radius_mm

    @property
    def below_floor_mm(self) -> float:
        return self.bottom_radius_mm - self.deepest_radius_mm

    def check(self) -> Check:
        """The cut depth on the printed program against what the walls need (a warning when deeper).

        The limit carries one printed step: the plan's depth is printed on the post's grid (a 4-axis last pass
        goes to the first grid value below the corner depth, a 5-axis node rounds to the nearest)."""
        dip = self.below_floor_mm
        where = (f"the tool reaches R{self.deepest_radius_mm:.4g}, {dip:.4g} mm below the groove floor "
                 f"R{self.bottom_radius_mm:g}" + (f" ({self.why})" if self.why and dip > 0 else "")
                 if dip > 0 else f"the tool reaches R{self.deepest_radius_mm:.4g}, above the groove floor "
                 f"R{self.bottom_radius_mm:g}")
        return Check("cut depth", self.depth_mm, self.needed_depth_mm, "mm",
                     ok=self.depth_mm <= self.needed_depth_mm + self.print_step_mm, severity="warn", where=where,
                     advice="the tool goes deeper into the groove floor than the walls need: set [machining] depth "
                     "to the groove depth")

    def as_dict(self) -> dict:
        return {"depth_mm": self.depth_mm, "deepest_radius_mm": self.deepest_radius_mm,
                "below_groove_floor_mm": self.below_floor_mm, "needed_depth_mm": self.needed_depth_mm,
                "flute_needed_mm": self.flute_needed_mm, "flute_length_mm": self.flute_length_mm}


def tool_reach(poses: ToolPoses, tool_radius_mm: float, top_radius_mm: float, bottom_radius_mm: float,
               needed_radius_mm: float, flute_length_mm: float, decimals: int, why: str = "") -> ToolReach:
    """The reach of the printed ``poses`` (:func:`camcam.toolpath.poses.poses_from_program`)."""
    tip = np.asarray(poses.tip_mm, float)
    sin_b = np.abs(np.sin(np.radians(np.asarray(poses.b_deg, float))))
    cos_b = np.cos(np.radians(np.asarray(poses.b_deg, float)))
    rho = np.hypot(tip[:, 1], tip[:, 2])
    deepest = float((rho - tool_radius_mm * sin_b).min())
    flute = float(((top_radius_mm + tool_radius_mm * sin_b - rho) / cos_b).max())
    return ToolReach(top_radius_mm=top_radius_mm, bottom_radius_mm=bottom_radius_mm, deepest_radius_mm=deepest,
                     needed_radius_mm=needed_radius_mm, flute_needed_mm=max(flute, 0.0),
                     flute_length_mm=flute_length_mm,
                     print_step_mm=10.0 ** -decimals, why=why)


def flute_to_buy_mm(needed_mm: float) -> float:
    """The flute a cut reaching ``needed_mm`` up the tool asks for: rounded up to 0.01 mm, a length one can buy
    and hold to (the setup sheet, the advice and the tool an unstated flute is modelled as name this one).

    >>> flute_to_buy_mm(16.303), flute_to_buy_mm(10.3)
    (16.31, 10.3)
    """
    return math.ceil(needed_mm * 100 - 1e-9) / 100


def flute_text(reach: ToolReach) -> str:
    """The setup sheet's flute line for a barrel program."""
    return (f"flute length ≥ {flute_to_buy_mm(reach.flute_needed_mm):g} mm (the cut reaches "
            f"{reach.flute_needed_mm:.2f} mm up the tool from its tip; deepest point {reach.depth_mm:.2f} mm "
            f"below the top, R{reach.deepest_radius_mm:.2f})")
