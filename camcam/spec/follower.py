"""The ``[follower]`` table.

```toml
[follower]
kind = "translating-roller"   # "oscillating-roller", "translating-flat", "oscillating-flat"
roller_radius = 10.0          # roller kinds, mm
offset = 5.0                  # translating kinds, mm along +X (default 0)
pivot_distance = 100.0        # oscillating kinds, mm (cam centre/axis to pivot)
arm_length = 80.0             # oscillating-roller, mm (pivot to roller centre)
```

An oscillating follower makes the motion unit degrees.
"""

from __future__ import annotations

from camcam.geometry.params import FOLLOWER_KINDS, FollowerSpec
from camcam.spec.cam import MIN_PART_MM
from camcam.spec.reader import Table

__all__ = ["FollowerSpec", "read_follower", "FOLLOWER_KINDS"]

def read_follower(t: Table, cam_kind: str | None = None) -> FollowerSpec:
    kind = t.string("kind", choices=FOLLOWER_KINDS)
    rr = t.number("roller_radius", minimum=MIN_PART_MM, unit="mm") if kind.endswith("roller") else 0.0
    offset = t.number("offset", 0.0, unit="mm") if kind.startswith("translating") else 0.0
    pivot = arm = None
    if kind.startswith("oscillating"):
        pivot = t.number("pivot_distance", minimum=MIN_PART_MM, unit="mm")
        if kind == "oscillating-roller":
            need_arm = cam_kind != "cylindrical"
            arm = t.number("arm_length", *(() if need_arm else (None,)), minimum=MIN_PART_MM, unit="mm")
    if cam_kind == "cylindrical" and kind.startswith("translating"):
        t.check("offset", offset == 0.0, "a cylindrical cam's translating follower has no offset")
    t.done()
    return FollowerSpec(kind, rr, offset, pivot, arm)
