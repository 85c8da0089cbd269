"""The ``[motion]`` table: cam speed and the segments of the motion program.

```toml
[motion]
rpm = 120
strict = false            # true: a velocity or acceleration jump at a join is an error
segments = [
  { law = "modified-sine", from = 0, to = 120, rise = 20.0 },
  { law = "dwell", from = 120, to = 180 },
  { law = "cycloidal", from = 180, to = 300, rise = -20.0 },
  { law = "dwell", from = 300, to = 360 },
]
```

``rise`` is signed (negative = return) in mm for a translating follower or
degrees for an oscillating one.  ``law = "file:laws/x.json"`` uses a law
written by ``camcam optimize`` (path relative to the spec file).  Law parameters (``beta7`` … for ``yu-lee``)
sit beside ``law`` in the segment.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from camcam.errors import InputError, MotionError
from camcam.motion.catalog import LAWS, make_law
from camcam.motion.law import MotionLaw
from camcam.motion.program import TILE_ATOL_DEG, MotionProgram, Segment
from camcam.motion.standard import dwell
from camcam.spec.reader import Table, fmt

__all__ = ["SegmentSpec", "MotionSpec", "read_motion"]

#: Closure tolerance of a program's rises, mm or degrees: decimal rises in a spec
#: add up to exact zero within float rounding (~1e-12); a real mismatch is ≥ 1e-6.
CLOSURE_ATOL = 1e-9


@dataclass(frozen=True)
class SegmentSpec:
    """One segment as written in the spec, with its law resolved."""

    law_name: str
    law: MotionLaw
    from_deg: float
    to_deg: float
    rise: float


@dataclass(frozen=True)
class MotionSpec:
    """The validated ``[motion]`` table."""

    rpm: float
    strict: bool
    segments: tuple[SegmentSpec, ...]

    def program(self, unit: str = "mm") -> MotionProgram:
        """The motion program; with ``strict`` a jump at a join raises :class:`MotionError`."""
        segs = []
        lift = 0.0
        for s in self.segments:
            segs.append(Segment(s.law, s.from_deg, s.to_deg, s.rise, lift))
            lift = segs[-1].end_lift
        program = MotionProgram(tuple(segs), self.rpm, unit)
        if self.strict:
            program.check_strict()
        return program


def _read_law(t: Table, base_dir: Path) -> tuple[str, MotionLaw]:
    name = t.string("law")
    if name.startswith("file:"):
        return name, _read_law_file(t, name, base_dir)
    if name == "dwell":
        return name, dwell()
    if name not in LAWS:
        known = ", ".join([*sorted(LAWS), "dwell"])
        raise t.error("law", f"unknown law {fmt(name)}; known: {known}")
    params = {p: t.number(p, default) for p, default in LAWS[name].parameters.items()}
    return name, make_law(name, **params)


def _read_law_file(t: Table, name: str, base_dir: Path) -> MotionLaw:
    """``law = "file:laws/x.json"``: an optimised law, path relative to the spec."""
    from camcam.optimize.lawfile import read_law_file

    rel = name.removeprefix("file:")
    if not rel:
        raise t.error("law", '"file:" needs a path, e.g. "file:laws/table1.json"')
    try:
        return read_law_file(base_dir / rel, name)
    except InputError as err:
        msg = str(err).removeprefix(f"{base_dir / rel}: ")
        raise t.error("law", f"{fmt(name)}: {msg}") from None


def read_motion(t: Table, base_dir: Path, unit: str = "mm") -> MotionSpec:
    """Validate the ``[motion]`` table ``t``; law files are resolved against ``base_dir``."""
    rpm = t.number("rpm", minimum=0, inclusive=False, unit="rev/min")
    strict = t.boolean("strict", False)
    rows = t.tables("segments")
    segments = []
    prev_to = 0.0
    for i, row in enumerate(rows):
        name, law = _read_law(row, base_dir)
        a = row.number("from", unit="degrees")
        b = row.number("to", unit="degrees")
        if i == 0:
            row.check("from", abs(a) <= TILE_ATOL_DEG, f"{fmt(a)} must be 0: the segments tile 0–360°")
        elif a > prev_to + TILE_ATOL_DEG:
            raise row.error("from", f"{fmt(a)} leaves a gap after the previous segment, which ends at {fmt(prev_to)}")
        elif a < prev_to - TILE_ATOL_DEG:
            raise row.error("from", f"{fmt(a)} overlaps the previous segment, which ends at {fmt(prev_to)}")
        row.check("to", b <= 360 + TILE_ATOL_DEG, f"{fmt(b)} is past 360")
        row.check("to", b > a, f"{fmt(b)} is not after from = {fmt(a)}")
        if name == "dwell":
            rise = row.number("rise", 0.0)
            row.check("rise", rise == 0.0, f"{fmt(rise)}: a dwell has no rise")
        else:
            rise = row.number("rise", unit="mm" if unit == "mm" else "degrees")
        row.done()
        segments.append(SegmentSpec(name, law, a, b, rise))
        prev_to = b
    if abs(prev_to - 360.0) > TILE_ATOL_DEG:
        raise t.error(f"segments[{len(rows) - 1}].to", f"{fmt(prev_to)}: the last segment must end at 360")
    spec = MotionSpec(rpm, strict, tuple(segments))
    lift = 0.0
    for s in spec.segments:
        lift += s.rise * float(s.law.evaluate(1.0) - s.law.evaluate(0.0))
    if abs(lift) > CLOSURE_ATOL * max(1.0, max(abs(s.rise) for s in spec.segments)):
        raise t.error("segments", f"rises add up to {lift:+.6g} {unit}; the follower must return to its start over 360°")
    try:
        spec.program(unit)
    except MotionError as err:
        raise t.error("strict", str(err).removeprefix("motion: ")) from None
    return spec

