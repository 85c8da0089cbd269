"""The ``[cam]`` table.

```toml
[cam]
kind = "disc"          # "disc", "disc-groove" or "cylindrical"
base_radius = 40.0     # disc: base circle of the profile; cylindrical: cylinder radius, mm
thickness = 12.0       # disc kinds, mm
bore = 12.0            # bore diameter, mm (0: none)
rotation = "ccw"       # "ccw" or "cw" (about +Z for discs, +X for cylinders)
groove_depth = 8.0     # disc-groove and cylindrical, mm
outer_radius = 90.0    # disc-groove: blank radius, mm (default: groove + one roller radius of wall)
length = 120.0         # cylindrical, mm
max_pressure_angle_deg = 30.0  # design check limit (default 30° translating, 35° oscillating followers)
min_curvature_radius_mm = 5.0  # design check limit: the profile's smallest convex radius (default half the
                               # roller radius, 0 for a flat face)
design_limits = "warn"         # a design limit missed: "warn" (WARN verdict, exit 0) or "fail" (FAIL, exit 3)
material = "C45 steel"        # the part's material, free text for the setup sheet (default: not stated)
keyway = { width = 4.0, depth = 1.8, angle = 90.0 }  # disc kinds: a keyway in the bore, mm; its centre line at
                               # angle degrees from +X in the drawing (default 90: +Y); the part's angular datum
dowel = { diameter = 6.0, radius = 20.0, angle = 90.0 }  # disc cams: or a dowel hole through the cam, its centre
                               # at radius mm from the cam centre on the line at angle degrees from +X
```
"""

from __future__ import annotations

import math

from camcam.advice import largest_below_mm
from camcam.geometry.params import CAM_KINDS, CamSpec, Dowel, Keyway
from camcam.spec.reader import Table

__all__ = ["CamSpec", "read_cam", "CAM_KINDS", "MIN_PART_MM", "DESIGN_LIMITS"]

#: What a missed design limit (pressure angle, radius of curvature) does: warn (exit 0) or fail (exit 3).
DESIGN_LIMITS = ("warn", "fail")

#: Smallest cam or follower dimension (mm): below it the mesh and the fit work at rounding level.
MIN_PART_MM = 0.1

def read_cam(t: Table) -> CamSpec:
    kind = t.string("kind", "disc", choices=CAM_KINDS)
    base = t.number("base_radius", minimum=MIN_PART_MM, unit="mm")
    bore = t.number("bore", 0.0, minimum=0, unit="mm")
    rotation = t.string("rotation", "ccw", choices=("ccw", "cw"))
    thickness = groove = outer = length = None
    if kind in ("disc", "disc-groove"):
        thickness = t.number("thickness", minimum=MIN_PART_MM, unit="mm")
    if kind in ("disc-groove", "cylindrical"):
        groove = t.number("groove_depth", minimum=MIN_PART_MM, unit="mm")
    if kind == "disc-groove":
        outer = t.number("outer_radius", None, minimum=MIN_PART_MM, unit="mm")
        t.check("groove_depth", groove < thickness, f"{groove:g} must be smaller than thickness = {thickness:g}")
    if kind == "cylindrical":
        length = t.number("length", minimum=MIN_PART_MM, unit="mm")
        t.check("groove_depth", groove < base, f"{groove:g} must be smaller than base_radius = {base:g}")
    t.check("bore", bore == 0 or bore >= MIN_PART_MM, f"{bore:g} mm: expected 0 (no bore) or at least {MIN_PART_MM:g} mm")
    if bore and kind == "cylindrical":  # a barrel's groove is radial: the bore must stay under its bottom
        t.check("bore", bore / 2 < base - groove, f"{bore:g} mm leaves no material under the groove, whose bottom "
                                                  f"is at radius {base - groove:g} mm; expected at most "
                                                  f"{largest_below_mm(2 * (base - groove)):g} mm")
    elif bore:
        # a face groove's depth is axial: the bore must fit inside its inner flank, which the cam's geometry
        # measures (camcam.geometry.mesh.groove_parts); the base radius bounds it here.  Campaign case 50:38 (a
        # 9.4 mm bore, base radius 22.6 mm, groove 19.8 mm deep) was refused by base − depth = 2.8 mm
        t.check("bore", bore / 2 < base, f"{bore:g} mm leaves no material around the bore; expected at most "
                                         f"{largest_below_mm(2 * base):g} mm (under twice the base radius)")
    max_pa = t.number("max_pressure_angle_deg", None, minimum=0.0, maximum=90.0, inclusive=False, unit="degrees")
    min_rho = t.number("min_curvature_radius_mm", None, minimum=0.0, unit="mm")
    limits = t.string("design_limits", "warn", choices=DESIGN_LIMITS)
    material = t.string("material", None)
    t.check("material", material is None or material.strip() != "", "expected the material's name, got an empty string")
    keyway = _keyway(t, kind, bore, base)
    dowel = _dowel(t, kind, bore, base, keyway)
    t.done()
    return CamSpec(kind=kind, base_radius=base, bore=bore, rotation=rotation, thickness=thickness, groove_depth=groove,
                   outer_radius=outer, length=length, max_pressure_angle_deg=max_pa, min_curvature_radius_mm=min_rho,
                   design_limits=limits, material=material.strip() if material else None, keyway=keyway,
                   dowel=dowel)


def _keyway(t: Table, kind: str, bore: float, base: float) -> Keyway | None:
    k = t.table("keyway", None)
    if k is None:
        return None
    if kind == "cylindrical":
        raise t.error("keyway", "applies to disc cams (a barrel cam's datum is its A0 line)")
    if bore <= 0:
        raise t.error("keyway", "needs a bore (cam.bore)")
    width = k.number("width", minimum=MIN_PART_MM, unit="mm")
    depth = k.number("depth", minimum=MIN_PART_MM, unit="mm")
    angle = k.number("angle", 90.0, minimum=-360.0, maximum=360.0, unit="degrees")
    k.done()
    k.check("width", width < bore, f"{width:g} mm must be narrower than the bore ({bore:g} mm)")
    corner = math.hypot(width / 2, bore / 2 + depth)
    k.check("depth", corner < base, f"{depth:g} mm puts the keyway's corners at radius {corner:.3g} mm, outside the "
                                    f"base circle ({base:g} mm)")
    return Keyway(width=width, depth=depth, angle_deg=angle)


def _dowel(t: Table, kind: str, bore: float, base: float, keyway: Keyway | None) -> Dowel | None:
    d = t.table("dowel", None)
    if d is None:
        return None
    if kind != "disc":
        raise t.error("dowel", f"applies to disc cams (kind = \"disc\"), not {kind}")
    diameter = d.number("diameter", minimum=MIN_PART_MM, unit="mm")
    radius = d.number("radius", minimum=0.0, inclusive=False, unit="mm")
    angle = d.number("angle", 90.0, minimum=-360.0, maximum=360.0, unit="degrees")
    d.done()
    inner = bore / 2 if keyway is None else math.hypot(keyway.width / 2, bore / 2 + keyway.depth)
    d.check("radius", radius - diameter / 2 > inner, f"{radius:g} mm puts the Ø{diameter:g} mm hole into the bore "
                                                     f"(it reaches radius {inner:.3g} mm)")
    d.check("radius", radius + diameter / 2 < base, f"{radius:g} mm puts the Ø{diameter:g} mm hole outside the base "
                                                    f"circle ({base:g} mm)")
    return Dowel(diameter=diameter, radius=radius, angle_deg=angle)
