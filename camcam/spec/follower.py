"""The ``[follower]`` table.

```toml
[follower]
kind = "translating-roller"   # "oscillating-roller", "translating-flat", "oscillating-flat"
roller_radius = 10.0          # roller kinds, mm
offset = 5.0                  # translating kinds, mm along +X (default 0)
pivot_distance = 100.0        # oscillating kinds, mm (cam centre/axis to pivot)
arm_length = 80.0             # oscillating-roller, mm (pivot to roller centre)
```

An oscillating follower makes the motion unit degrees.  The kinds and the keys each
takes are the follower registry's (:data:`camcam.geometry.followers.FOLLOWERS`, each
kind's ``spec_keys``).
"""

from __future__ import annotations

from camcam.geometry.followers import FOLLOWERS, follower_kind
from camcam.geometry.params import FOLLOWER_KINDS, FollowerSpec
from camcam.spec.cam import MIN_PART_MM
from camcam.spec.reader import Table

__all__ = ["FollowerSpec", "read_follower", "FOLLOWER_KINDS"]

def read_follower(t: Table, cam_kind: str | None = None) -> FollowerSpec:
    kind = t.string("kind", choices=tuple(FOLLOWERS))
    cls = follower_kind(kind)
    keys = cls.spec_keys
    optional = cls.barrel_optional_keys if cam_kind == "cylindrical" else ()
    rr = t.number("roller_radius", minimum=MIN_PART_MM, unit="mm") if "roller_radius" in keys else 0.0
    offset = t.number("offset", 0.0, unit="mm") if "offset" in keys else 0.0
    pivot = arm = None
    if "pivot_distance" in keys:
        pivot = t.number("pivot_distance", minimum=MIN_PART_MM, unit="mm")
    if "arm_length" in keys:
        arm = t.number("arm_length", *((None,) if "arm_length" in optional else ()), minimum=MIN_PART_MM, unit="mm")
    if cam_kind == "cylindrical" and "offset" in keys:
        t.check("offset", offset == 0.0, "a cylindrical cam's translating follower has no offset")
    t.done()
    return FollowerSpec(kind=kind, roller_radius=rr, offset=offset, pivot_distance=pivot, arm_length=arm)
