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
flute_length = 32.0        # mm, the tool's cutting length (default: twice its diameter)
a_axis = "right-hand"      # barrel cams: a positive A turns the part by the right-hand rule about +X
accept_out_of_tolerance = false  # true: a FAIL verdict only warns (exit 0)
stepover = 0.4             # roughing: radial step, a fraction of the tool diameter
ramp_angle = 3.0           # deg, steepest descent into material (grooves: ramped entries)
bore = false               # true: cut the bore as a helical bore
```
"""

from __future__ import annotations

from pathlib import Path

from camcam.errors import InputError
from camcam.nc.settings import MachiningSpec
from camcam.post.post import load_post
from camcam.spec.reader import Table
from camcam.toolpath.budget import DEFAULT_BUDGET

__all__ = ["MachiningSpec", "read_machining"]


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
    accept = t.boolean("accept_out_of_tolerance", False)
    flute = t.number("flute_length", 2.0 * tool, minimum=0.0, inclusive=False, unit="mm")
    a_axis = t.string("a_axis", "right-hand", choices=("right-hand", "left-hand"))
    stepover = t.number("stepover", 0.4, minimum=0.0, maximum=1.0, inclusive=False)
    ramp = t.number("ramp_angle", 3.0, minimum=0.0, maximum=45.0, inclusive=False, unit="deg")
    bore = t.boolean("bore", False)
    t.done()
    return MachiningSpec(post, tool, tol, mode, feed, spindle, depth, stepdown, plunge, safe, clearance, lead,
                         allowance, spring, tool_number, accept, flute_length_mm=flute, a_axis=a_axis,
                         stepover=stepover, ramp_angle_deg=ramp, bore=bore)
