"""The ``[size]`` table: a sweep of disc-cam designs, its constraints and its objective.

```toml
[size]
base_radius = [30, 80, 0.5]        # [from, to, step] mm (or one number)
offset = [-10, 10, 0.5]            # translating-roller, [from, to, step] mm
roller_radius = [6, 8, 10]         # roller kinds: the roller sizes to try, mm
pivot_distance = [90, 110, 5]      # oscillating-roller, [from, to, step] mm
arm_length = [70, 90, 5]           # oscillating-roller, [from, to, step] mm
law = [{ segment = 0, choices = ["cycloidal", "modified-sine", "polynomial-345"] }]
max_pressure_angle_deg = 30        # roller kinds (default 30 translating, 35 oscillating)
min_curvature_radius_mm = 4.0      # smallest convex radius of the profile, mm ...
min_curvature_radius_rollers = 0.5 # ... or as a multiple of the roller radius (not both)
tool_check = true                  # the [machining] tool fits the smallest concave radius
objective = "outer-radius"         # or "pressure-angle"
samples = 3600                     # cam-angle samples per revolution for the sweep
max_contact_stress_mpa = 900       # optional: Hertz stress at [motion] rpm, with the [dynamics] train
min_jump_rpm = 500                 # optional: the follower stays on the cam up to this speed
```

The two dynamics constraints need a ``[dynamics]`` table with a given spring (not ``spring = "size"``);
the sweep evaluates them per design (:mod:`camcam.sizing.contact`) and the exact check as ``camcam run``
does.

An axis the table leaves out keeps the value of ``[cam]`` / ``[follower]``.
The axes of each kind are its ``size_axes`` in the follower registry
(:data:`camcam.geometry.followers.FOLLOWERS`), its default pressure-angle limit
its ``default_max_pressure_angle_deg``.
No undercut (roller) and no cusp (flat face) are always required.  The sweep
covers the translating roller, the oscillating roller and the translating
flat-faced follower on a plain disc cam (``[cam] kind = "disc"``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from camcam.errors import SpecError
from camcam.geometry.followers import FOLLOWERS, follower_kind
from camcam.motion.catalog import LAWS
from camcam.spec.reader import Table, fmt

__all__ = ["SizeAxis", "LawChoice", "SizeSpec", "read_size", "check_size_dynamics", "MAX_DESIGNS", "OBJECTIVES",
           "sized_followers"]

#: The largest sweep `camcam size` runs: about two minutes on one core at the default
#: samples; a larger one is almost always a step typed too small.
MAX_DESIGNS = 1_000_000


def sized_followers() -> dict[str, tuple[str, ...]]:
    """The swept geometry of each follower kind that can be sized, in table order (its ``size_axes``)."""
    return {kind: cls.size_axes for kind, cls in FOLLOWERS.items() if cls.size_axes is not None}


#: Axes given as lists of values (catalogue sizes); the others are [from, to, step] ranges.
LIST_AXES = ("roller_radius",)

OBJECTIVES = ("outer-radius", "pressure-angle")


@dataclass(frozen=True)
class SizeAxis:
    """One swept quantity (mm) and its values, in sweep order."""

    name: str
    values: tuple[float, ...]


@dataclass(frozen=True)
class LawChoice:
    """The laws to try on motion segment ``segment``."""

    segment: int
    laws: tuple[str, ...]


@dataclass(frozen=True, kw_only=True)
class SizeSpec:
    axes: tuple[SizeAxis, ...]
    laws: tuple[LawChoice, ...]
    max_pressure_angle_deg: float | None
    min_curvature_radius_mm: float
    min_curvature_radius_rollers: float | None
    tool_radius_mm: float | None
    objective: str
    samples: int
    max_contact_stress_mpa: float | None = None  # needs [dynamics] (camcam.sizing.contact)
    min_jump_rpm: float | None = None

    @property
    def dynamic(self) -> bool:
        """A dynamics constraint is given (the sweep needs the [dynamics] train)."""
        return self.max_contact_stress_mpa is not None or self.min_jump_rpm is not None

    @property
    def design_count(self) -> int:
        n = 1
        for a in self.axes:
            n *= len(a.values)
        for c in self.laws:
            n *= len(c.laws)
        return n


def _range(t: Table, key: str) -> tuple[float, ...]:
    raw = t.raw(key)
    if isinstance(raw, (int, float)) and not isinstance(raw, bool):
        return (t.number(key, unit="mm"),)
    if not (isinstance(raw, list) and len(raw) == 3 and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw)):
        raise t.error(key, f"expected [from, to, step] in mm or one number, got {fmt(raw)}")
    lo, hi, step = (float(v) for v in raw)
    if not all(math.isfinite(v) and abs(v) <= 1e4 for v in (lo, hi, step)):
        raise t.error(key, f"expected finite [from, to, step] within ±10000 mm, got {raw}")
    if not step > 0:
        raise t.error(key, f"step {fmt(step)} must be > 0")
    if hi < lo:
        raise t.error(key, f"to = {fmt(hi)} is below from = {fmt(lo)}: the range is empty")
    n = int(math.floor((hi - lo) / step + 1e-9)) + 1
    if n > MAX_DESIGNS:
        raise t.error(key, f"{n} values; a sweep is capped at {MAX_DESIGNS:,} designs")
    return tuple(round(lo + i * step, 9) for i in range(n))


def _values(t: Table, key: str) -> tuple[float, ...]:
    raw = t.raw(key)
    if isinstance(raw, (int, float)) and not isinstance(raw, bool):
        raw = [raw]
    if not isinstance(raw, list) or not raw:
        raise t.error(key, f"expected a non-empty list of sizes in mm, got {fmt(raw)}")
    out = []
    for i, v in enumerate(raw):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or not 0 < v <= 1e4:
            raise SpecError(f"{t.key_path(key)}[{i}]", f"expected a size > 0 and <= 10000 mm, got {fmt(v)}")
        out.append(float(v))
    if len(set(out)) != len(out):
        raise t.error(key, "lists a size twice")
    return tuple(out)


def _fixed(name: str, cam, follower) -> float:
    if name == "base_radius":
        return cam.base_radius
    return float(getattr(follower, name))


def read_size(t: Table, cam, follower, motion, machining) -> SizeSpec:
    """Validate ``[size]`` against the spec's ``[cam]``, ``[follower]``, ``[motion]`` and ``[machining]``."""
    if cam is None or follower is None or motion is None:
        raise SpecError("size", "a sizing sweep needs [motion], [cam] and [follower] tables")
    if cam.kind != "disc":
        raise SpecError("size", f'sizes plain disc cams; cam.kind is {fmt(cam.kind)}, expected "disc"')
    sized = sized_followers()
    if follower.kind not in sized:
        raise SpecError("size", f"sizes {', '.join(sized)} followers; follower.kind is {fmt(follower.kind)}")
    if motion.lift_table is not None:
        raise SpecError("size", "needs [motion] segments (a lift table has no law to swap); the sized spec must run from any folder")
    axes = []
    for name in sized[follower.kind]:
        if t.has(name):
            vals = _values(t, name) if name in LIST_AXES else _range(t, name)
            if name != "offset" and min(vals) <= 0:
                raise t.error(name, f"sizes must be > 0 mm, got {fmt(min(vals))}")
        else:
            vals = (_fixed(name, cam, follower),)
        axes.append(SizeAxis(name, vals))
    for name in ("offset", "roller_radius", "pivot_distance", "arm_length"):
        if name not in sized[follower.kind] and t.has(name):
            raise t.error(name, f"a {follower.kind} follower has no {name} to sweep")
    for i, seg in enumerate(motion.segments):
        if seg.law_name.startswith("file:") or seg.law_name == "lift-table":
            raise SpecError(f"motion.segments[{i}].law", f"{fmt(seg.law_name)}: a sized spec is written to another folder; "
                            "use a catalogue law (see `camcam laws`)")
    choices = []
    if t.has("law"):
        rows = t.tables("law")
        seen = set()
        for row in rows:
            k = row.integer("segment", minimum=0, maximum=len(motion.segments) - 1)
            row.check("segment", k not in seen, f"segment {k} is listed twice")
            row.check("segment", motion.segments[k].law_name != "dwell", f"segment {k} is a dwell; it has no law to choose")
            seen.add(k)
            raw = row.raw("choices", what="a list of law names")
            if not isinstance(raw, list) or not raw:
                raise row.error("choices", f"expected a non-empty list of law names, got {fmt(raw)}")
            for j, name in enumerate(raw):
                if not isinstance(name, str) or name not in LAWS:
                    raise SpecError(f"{row.key_path('choices')}[{j}]", f"unknown law {fmt(name)}; known: {', '.join(sorted(LAWS))}")
            row.check("choices", len(set(raw)) == len(raw), "lists a law twice")
            row.done()
            choices.append(LawChoice(k, tuple(raw)))
    roller = follower.is_roller
    if roller:
        pa = t.number("max_pressure_angle_deg", follower_kind(follower.kind).default_max_pressure_angle_deg, minimum=0, maximum=90, inclusive=False)
    else:
        t.check("max_pressure_angle_deg", not t.has("max_pressure_angle_deg"),
                "a flat face's pressure angle is zero throughout; there is nothing to limit")
        pa = None
    if t.has("min_curvature_radius_mm") and t.has("min_curvature_radius_rollers"):
        raise t.error("min_curvature_radius_rollers", "give min_curvature_radius_mm or min_curvature_radius_rollers, not both")
    rho = t.number("min_curvature_radius_mm", 0.0, minimum=0, unit="mm")
    rollers = None
    if t.has("min_curvature_radius_rollers"):
        t.check("min_curvature_radius_rollers", roller, "a flat-faced follower has no roller to scale by")
        rollers = t.number("min_curvature_radius_rollers", minimum=0)
    tool_check = t.boolean("tool_check", True)
    tool = None
    if tool_check and machining is not None:
        tool = machining.tool_diameter_mm / 2.0
    objective = t.string("objective", "outer-radius", choices=OBJECTIVES)
    t.check("objective", roller or objective != "pressure-angle", "a flat face's pressure angle is zero throughout")
    samples = t.integer("samples", 3600, minimum=360, maximum=100_000)
    stress = t.number("max_contact_stress_mpa", None, minimum=0.0, maximum=1e5, inclusive=False, unit="MPa")
    jump = t.number("min_jump_rpm", None, minimum=0.0, maximum=1e6, inclusive=False, unit="rpm")
    t.done()
    spec = SizeSpec(axes=tuple(axes), laws=tuple(sorted(choices, key=lambda c: c.segment)), max_pressure_angle_deg=pa,
                    min_curvature_radius_mm=rho, min_curvature_radius_rollers=rollers, tool_radius_mm=tool,
                    objective=objective, samples=samples, max_contact_stress_mpa=stress, min_jump_rpm=jump)
    if spec.design_count > MAX_DESIGNS:
        raise SpecError("size", f"the sweep has {spec.design_count:,} designs; it is capped at {MAX_DESIGNS:,}: use coarser steps")
    return spec


def check_size_dynamics(size: SizeSpec, dynamics) -> None:
    """The dynamics constraints need the ``[dynamics]`` train, with a spring given (one line, exit 2)."""
    if not size.dynamic:
        return
    key = "size.max_contact_stress_mpa" if size.max_contact_stress_mpa is not None else "size.min_jump_rpm"
    if dynamics is None:
        raise SpecError(key, "needs a [dynamics] table: the follower's mass or inertia, spring, roller_width_mm "
                        "and materials give the contact force and the jump speed")
    if dynamics.size_spring:
        raise SpecError(key, 'needs a given spring: [dynamics] spring = "size" sizes one per design to hold up to '
                        "overspeed × rpm; give spring_rate_n_per_mm and preload_n")
