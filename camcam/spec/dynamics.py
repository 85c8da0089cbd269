"""The ``[dynamics]`` table: the follower train, for forces, torque, contact stress and jump speed.

```toml
[dynamics]
mass_kg = 0.8                  # translating follower: the moving mass (stem, roller, a third of the spring)
# inertia_kgm2 = 0.004         # oscillating follower: the arm's inertia about its pivot, kg·m²
spring_rate_n_per_mm = 2.5     # the spring: rate and preload (the force at lift 0)
preload_n = 60.0
# spring = "size"              # or: the least spring that holds to overspeed × rpm (camcam.dynamics.spring)
damping_ratio = 0.05           # or damping_n_s_per_m = 12.0 (optional; none: no damping)
external_load_n = 20.0         # pushing the follower onto the cam; or a table: [[0, 20.0], [120, 35.0], ...]
friction = 0.05                # at a translating follower's guide (default 0)
roller_width_mm = 12.0         # roller followers
materials = { cam = "steel", follower = "steel" }   # presets, or { e_gpa = 205, poisson = 0.29 }
allowable_contact_stress_mpa = 1200.0               # optional: the contact stress check
min_contact_force_n = 0.0      # the least contact force the checks and the sizing hold (default 0)
overspeed = 1.25               # the jump speed must exceed overspeed × rpm (default 1.25)
speed_fluctuation = 0.05       # (ω_max − ω_min)/ω for the flywheel (default 0.05)
# load_arm_mm = 60.0           # oscillating: where the spring, damper and load act (default: the arm length)
```

A grooved cam (``disc-groove``, ``cylindrical``) drives its follower both ways: it takes no spring.
Without ``[dynamics]`` a run computes no dynamics and its outputs do not change.
"""

from __future__ import annotations

from camcam.dynamics.train import (DEFAULT_OVERSPEED, DEFAULT_SPEED_FLUCTUATION, MATERIALS, DynamicsSpec, Material)
from camcam.errors import SpecError
from camcam.geometry.followers import follower_kind
from camcam.spec.reader import Table, fmt

__all__ = ["read_dynamics", "DynamicsSpec"]

_MASS = 1e4  # kg or kg·m²: a cap far beyond any cam follower, which keeps every force finite
_FORCE = 1e7  # N


def _material(t: Table, key: str) -> Material:
    value = t.raw(key, "steel", f"one of {', '.join(MATERIALS)}, or {{ e_gpa = …, poisson = … }}")
    if isinstance(value, str):
        t.check(key, value in MATERIALS, f"{fmt(value)}: expected one of {', '.join(f'{m!r}' for m in MATERIALS)}"
                .replace("'", '"') + ", or { e_gpa = …, poisson = … }")
        return MATERIALS[value]
    sub = t.table(key)
    e = sub.number("e_gpa", minimum=0.0, maximum=2000.0, inclusive=False, unit="GPa")
    nu = sub.raw("poisson", what="a number >= 0 and < 0.5")
    ok = isinstance(nu, (int, float)) and not isinstance(nu, bool) and 0.0 <= nu < 0.5
    sub.check("poisson", ok, f"expected a number >= 0 and < 0.5 (Poisson's ratio; 0.5 is incompressible), got {fmt(nu)}")
    nu = float(nu)
    sub.done()
    return Material("custom", e, nu)


def _load_table(t: Table, value) -> tuple[tuple[float, float], ...]:
    key = "external_load_n"
    rows = []
    for i, row in enumerate(value):
        ok = (isinstance(row, list) and len(row) == 2
              and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in row))
        t.check(f"{key}[{i}]", ok, f"expected [cam angle in degrees, force in N], got {fmt(row)}")
        a, f = float(row[0]), float(row[1])
        t.check(f"{key}[{i}]", 0.0 <= a < 360.0, f"angle {fmt(a)}: expected >= 0 and < 360 degrees")
        t.check(f"{key}[{i}]", abs(f) <= _FORCE, f"force {fmt(f)} N: expected at most {_FORCE:g} N in size")
        if rows:
            t.check(f"{key}[{i}]", a > rows[-1][0], f"angle {fmt(a)} must follow {fmt(rows[-1][0])} (increasing)")
        rows.append((a, f))
    t.check(key, bool(rows), "an empty table: expected a number, or rows [cam angle in degrees, force in N]")
    return tuple(rows)


def read_dynamics(t: Table, cam, follower) -> DynamicsSpec:
    """Validate ``[dynamics]`` against the validated ``[cam]`` and ``[follower]`` (both needed)."""
    if cam is None or follower is None:
        raise SpecError("dynamics", "needs [cam] and [follower] tables: the forces come from the cam's geometry")
    kind = follower_kind(follower.kind)
    oscillating = kind.unit == "deg"
    grooved = cam.kind != "disc"
    mass = inertia = None
    if oscillating:
        t.check("mass_kg", not t.has("mass_kg"), "an oscillating follower is given by inertia_kgm2 about its pivot")
        inertia = t.number("inertia_kgm2", minimum=0.0, maximum=_MASS, inclusive=False, unit="kg·m²")
    else:
        t.check("inertia_kgm2", not t.has("inertia_kgm2"), "a translating follower is given by mass_kg")
        mass = t.number("mass_kg", minimum=0.0, maximum=_MASS, inclusive=False, unit="kg")
    size = False
    rate = preload = 0.0
    if grooved:
        for key in ("spring", "spring_rate_n_per_mm", "preload_n", "damping_ratio"):
            t.check(key, not t.has(key), f"a {cam.kind} cam drives its follower both ways (positive drive): it takes "
                    "no spring" + ("; give damping_n_s_per_m" if key == "damping_ratio" else ""))
    else:
        if t.has("spring"):
            t.string("spring", choices=("size",))
            size = True
            for key in ("spring_rate_n_per_mm", "preload_n"):
                t.check(key, not t.has(key), 'spring = "size" sizes the rate and the preload: leave them out')
        elif not t.has("spring_rate_n_per_mm"):
            raise t.error("spring_rate_n_per_mm", 'missing; expected spring_rate_n_per_mm and preload_n, or spring = "size"')
        else:
            rate = t.number("spring_rate_n_per_mm", minimum=0.0, maximum=_FORCE, unit="N/mm")
            preload = t.number("preload_n", 0.0, minimum=0.0, maximum=_FORCE, unit="N")
    ratio = t.number("damping_ratio", None, minimum=0.0, maximum=10.0)
    damping = t.number("damping_n_s_per_m", None, minimum=0.0, maximum=_FORCE, unit="N·s/m")
    t.check("damping_ratio", ratio is None or damping is None, "give damping_ratio or damping_n_s_per_m, not both")
    t.check("damping_ratio", ratio is None or not size,
            'spring = "size" makes the rate unknown, and with it the damping a ratio gives: give damping_n_s_per_m')
    load = t.raw("external_load_n", 0.0, "a number (N), or rows [cam angle in degrees, force in N]")
    table = None
    if isinstance(load, list):
        table = _load_table(t, load)
        load = 0.0
    else:
        load = t.number("external_load_n", 0.0, minimum=-_FORCE, maximum=_FORCE, unit="N")
    friction = t.number("friction", 0.0, minimum=0.0, maximum=1.0)
    t.check("friction", friction == 0.0 or not oscillating,
            "guide friction applies to translating followers; an oscillating follower's pivot friction is not modelled")
    width = None
    if kind.is_roller:
        width = t.number("roller_width_mm", minimum=0.0, inclusive=False, unit="mm")
    else:
        t.check("roller_width_mm", not t.has("roller_width_mm"),
                "a flat face has no roller: its contact runs across the cam's thickness")
    mats = t.table("materials", None)
    cam_m = follower_m = MATERIALS["steel"]
    if mats is not None:
        cam_m, follower_m = _material(mats, "cam"), _material(mats, "follower")
        mats.done()
    allowable = t.number("allowable_contact_stress_mpa", None, minimum=0.0, maximum=1e5, inclusive=False, unit="MPa")
    least = t.number("min_contact_force_n", 0.0, minimum=0.0, maximum=_FORCE, unit="N")
    overspeed = t.number("overspeed", DEFAULT_OVERSPEED, minimum=1.0, maximum=10.0)
    fluctuation = t.number("speed_fluctuation", DEFAULT_SPEED_FLUCTUATION, minimum=0.0, maximum=1.0, inclusive=False)
    arm = None
    if oscillating:
        needs_arm = "arm_length" not in kind.spec_keys
        arm = t.number("load_arm_mm", *(() if needs_arm else (None,)), minimum=0.0, inclusive=False, unit="mm")
    else:
        t.check("load_arm_mm", not t.has("load_arm_mm"), "a translating follower's spring acts along its axis")
    t.done()
    return DynamicsSpec(mass_kg=mass, inertia_kgm2=inertia, spring_rate_n_per_mm=rate, preload_n=preload,
                        size_spring=size, damping_ratio=ratio, damping_n_s_per_m=damping, external_load_n=load,
                        external_load_table=table, friction=friction, roller_width_mm=width, cam_material=cam_m,
                        follower_material=follower_m, allowable_contact_stress_mpa=allowable, min_contact_force_n=least,
                        overspeed=overspeed, speed_fluctuation=fluctuation, load_arm_mm=arm)
