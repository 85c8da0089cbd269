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

Instead of ``segments`` the motion may come from a full-revolution lift table
(exactly one of the two)::

    [motion]
    rpm = 120
    lift_table = "lift.csv"   # relative to the spec file; angles 0–360°
    fit = "periodic"          # periodic (default), clamped, natural, not-a-knot, bspline
    [motion.fairing]          # optional: remove bad points, then fair
    method = "smoothing"      # or "mid-point"
    xi = 1e-4                 # mid-point stop: largest correction per round, mm
    bad_points = true
    threshold = 5.0           # bad point: |deviation| > threshold × its noise scale
    min_size = 0.001          # … and > min_size mm

A rise-only table is a segment law: ``{ law = "lift-table", table = "rise.csv",
fit = "clamped", from = 0, to = 120 }`` (``rise`` defaults to the table's rise).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from camcam.errors import InputError, MotionError
from camcam.motion.catalog import LAWS, make_law
from camcam.motion.law import MotionLaw
from camcam.motion.program import TILE_ATOL_DEG, MotionProgram, Segment
from camcam.motion.standard import dwell
from camcam.spec.reader import MISSING, Table, fmt

if TYPE_CHECKING:
    from camcam.lifttable.process import FairingOptions, FittedTable
    from camcam.lifttable.table import LiftTable

# camcam.lifttable (scipy's splines and optimisers) is imported only by a spec that has a lift table

__all__ = ["SegmentSpec", "TableMotionSpec", "MotionSpec", "read_motion"]

#: Closure tolerance of a program's rises, mm or degrees: decimal rises in a spec
#: add up to exact zero within float rounding (~1e-12); a real mismatch is ≥ 1e-6.
CLOSURE_ATOL = 1e-9


@dataclass(frozen=True, kw_only=True)
class SegmentSpec:
    """One segment as written in the spec, with its law resolved."""

    law_name: str
    law: MotionLaw
    from_deg: float
    to_deg: float
    rise: float


@dataclass(frozen=True)
class TableMotionSpec:
    """``[motion] lift_table``: the table file, the fit, the fairing options and the fitted result."""

    path: Path
    fit: str
    fairing: FairingOptions | None
    fitted: FittedTable


@dataclass(frozen=True)
class MotionSpec:
    """The validated ``[motion]`` table: ``segments`` or (exclusively) ``lift_table``."""

    rpm: float
    strict: bool
    segments: tuple[SegmentSpec, ...]
    lift_table: TableMotionSpec | None = None

    def program(self, unit: str = "mm") -> MotionProgram:
        """The motion program; with ``strict`` a jump at a join raises :class:`MotionError`."""
        if self.lift_table is not None:
            from camcam.lifttable.table_motion import table_program

            program = table_program(self.lift_table.fitted.law, self.rpm, unit)
            if self.strict:
                program.check_strict()
            return program
        segs = []
        lift = 0.0
        for s in self.segments:
            segs.append(Segment(s.law, s.from_deg, s.to_deg, s.rise, base=lift))
            lift = segs[-1].end_lift
        program = MotionProgram(tuple(segs), self.rpm, unit)
        if self.strict:
            program.check_strict()
        return program


def _load_table(t: Table, key: str, base_dir: Path) -> tuple[Path, LiftTable]:
    from camcam.lifttable.table import load_lift_table

    rel = t.string(key)
    path = (base_dir / rel) if not Path(rel).is_absolute() else Path(rel)
    try:
        return path, load_lift_table(path)
    except InputError as err:
        raise t.error(key, str(err)) from None


def _read_table_law(t: Table, base_dir: Path) -> tuple[MotionLaw, float]:
    """A rise-only table as a segment law: (normalised law, the table's rise)."""
    from camcam.lifttable.interpolate import FITS
    from camcam.lifttable.table_motion import table_law

    _, table = _load_table(t, "table", base_dir)
    t.check("table", not table.full_revolution, "a full-revolution table goes in [motion] lift_table, not in a segment")
    fit = t.string("fit", "clamped", choices=[f for f in FITS if f != "periodic"])
    try:
        law = table_law(table, fit)
    except InputError as err:
        raise t.error("table", str(err)) from None
    return law, table.lift[-1] - table.lift[0]


def _read_fairing(t: Table) -> FairingOptions:
    from camcam.lifttable.fairing import DEFAULT_MAX_ITERATIONS, METHODS
    from camcam.lifttable.process import FairingOptions

    opts = FairingOptions(
        method=t.string("method", FairingOptions.method, choices=METHODS),
        xi=t.number("xi", FairingOptions.xi, minimum=0, inclusive=False, unit="mm"),
        bad_points=t.boolean("bad_points", True),
        threshold=t.number("threshold", FairingOptions.threshold, minimum=0, inclusive=False),
        min_size=t.number("min_size", FairingOptions.min_size, minimum=0, unit="mm"),
        max_iterations=t.integer("max_iterations", DEFAULT_MAX_ITERATIONS, minimum=1),
    )
    t.done()
    return opts


def _read_lift_table(t: Table, base_dir: Path) -> TableMotionSpec:
    from camcam.lifttable.interpolate import FITS, default_fit
    from camcam.lifttable.process import fit_table

    path, table = _load_table(t, "lift_table", base_dir)
    t.check(
        "lift_table",
        table.full_revolution and abs(table.angles_deg[0]) <= TILE_ATOL_DEG,
        f"{path.name} covers {table.angles_deg[0]:g}–{table.angles_deg[-1]:g}°; [motion] lift_table must run 0–360° "
        '(a rise-only table is a segment law: law = "lift-table")',
    )
    fit = t.string("fit", default_fit(True), choices=FITS)
    ft = t.table("fairing", None)
    fairing = _read_fairing(ft) if ft is not None else None
    try:
        fitted = fit_table(table, fit, fairing)
    except InputError as err:
        raise t.error("lift_table", str(err)) from None
    return TableMotionSpec(path, fit, fairing, fitted)


def _read_law(t: Table, base_dir: Path) -> tuple[str, MotionLaw]:
    name = t.string("law")
    if name.startswith("file:"):
        return name, _read_law_file(t, name, base_dir)
    if name == "dwell":
        return name, dwell()
    if name not in LAWS:
        known = ", ".join([*sorted(LAWS), "dwell", "lift-table"])
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
    if t.has("lift_table") and t.has("segments"):
        raise t.error("lift_table", "give either segments or lift_table, not both")
    if t.has("lift_table") or not t.has("segments"):
        if not t.has("lift_table"):
            raise t.error("segments", "missing; expected an array of tables (or lift_table = \"FILE.csv\")")
        spec = MotionSpec(rpm, strict, (), _read_lift_table(t, base_dir))
        try:
            spec.program(unit)
        except MotionError as err:
            raise t.error("strict", str(err).removeprefix("motion: ")) from None
        return spec
    rows = t.tables("segments")
    segments = []
    prev_to = 0.0
    for i, row in enumerate(rows):
        table_rise = None
        if row.has("law") and row.data["law"] == "lift-table":
            name = row.string("law")
            law, table_rise = _read_table_law(row, base_dir)
        else:
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
            rise = row.number("rise", table_rise if table_rise is not None else MISSING, unit="mm" if unit == "mm" else "degrees")
        row.done()
        segments.append(SegmentSpec(law_name=name, law=law, from_deg=a, to_deg=b, rise=rise))
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

