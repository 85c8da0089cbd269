"""The ``[machining]`` table: post, tool, tolerance, feeds and depths of the NC program.

```toml
[machining]
post = "linuxcnc"          # a bundled post, or a path to your own post file
tool_diameter = 16.0       # mm
tolerance = 0.01           # mm, two-sided, on the printed program
mode = "arcs"              # or "lines"
feed = 400.0               # mm/min
spindle = 3000             # rev/min
depth = 12.0               # mm
stepdown = 4.0             # mm
```
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from camcam.errors import InputError
from camcam.post.post import Post, load_post
from camcam.spec.reader import Table
from camcam.toolpath.budget import DEFAULT_BUDGET
from camcam.toolpath.path import CutSettings

__all__ = ["MachiningSpec", "read_machining"]


@dataclass(frozen=True)
class MachiningSpec:
    """The validated ``[machining]`` table (lengths in mm, feeds in mm/min)."""

    post: Post
    tool_diameter_mm: float
    tolerance_mm: float
    mode: str
    feed_mm_min: float
    spindle_rpm: float
    depth_mm: float
    stepdown_mm: float
    plunge_feed_mm_min: float
    safe_z_mm: float
    clearance_z_mm: float
    lead_radius_mm: float
    finish_allowance_mm: float
    spring_pass: bool
    tool_number: int

    def cut_settings(self, stock_side: str = "right") -> CutSettings:
        """Settings for :func:`camcam.toolpath.path.contour_toolpath`."""
        return CutSettings(depth_mm=self.depth_mm, stepdown_mm=self.stepdown_mm, feed_mm_min=self.feed_mm_min,
                           spindle_rpm=self.spindle_rpm, plunge_feed_mm_min=self.plunge_feed_mm_min,
                           safe_z_mm=self.safe_z_mm, clearance_z_mm=self.clearance_z_mm,
                           lead_radius_mm=self.lead_radius_mm, stock_side=stock_side,
                           finish_allowance_mm=self.finish_allowance_mm, spring_pass=self.spring_pass,
                           tool_number=self.tool_number, tool_diameter_mm=self.tool_diameter_mm)


def read_machining(t: Table, base: Path) -> MachiningSpec:
    """Validate ``[machining]``; ``base`` anchors a relative post path."""
    name = t.string("post", "linuxcnc")
    try:
        post = load_post(name, base)
    except InputError as err:
        raise t.error("post", str(err)) from None
    tool = t.number("tool_diameter", minimum=0.0, inclusive=False, unit="mm")
    tol = t.number("tolerance", 0.01, minimum=0.0, inclusive=False, unit="mm")
    need = DEFAULT_BUDGET.floor_mm(post.quantizer)
    t.check("tolerance", tol >= need, f"{tol:g} mm is too fine for post {post.name}'s {post.decimals} decimals; "
            f"expected >= {need:.2g} mm")
    mode = t.string("mode", "arcs", choices=("arcs", "lines"))
    feed = t.number("feed", minimum=0.0, inclusive=False, unit="mm/min")
    spindle = t.number("spindle", minimum=0.0, inclusive=False, unit="rev/min")
    depth = t.number("depth", minimum=0.0, inclusive=False, unit="mm")
    stepdown = t.number("stepdown", depth, minimum=0.0, inclusive=False, unit="mm")
    plunge = t.number("plunge_feed", feed / 2, minimum=0.0, inclusive=False, unit="mm/min")
    clearance = t.number("clearance_z", 2.0, minimum=0.0, inclusive=False, unit="mm")
    safe = t.number("safe_z", 25.0, minimum=clearance, unit="mm")
    lead = t.number("lead_radius", max(tool / 2, 1.0), minimum=0.0, inclusive=False, unit="mm")
    allowance = t.number("finish_allowance", 0.0, minimum=0.0, unit="mm")
    spring = t.boolean("spring_pass", False)
    tool_number = t.integer("tool_number", 1, minimum=0, maximum=999)
    t.done()
    return MachiningSpec(post, tool, tol, mode, feed, spindle, depth, stepdown, plunge, safe, clearance, lead,
                         allowance, spring, tool_number)
