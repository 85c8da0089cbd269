"""Reading a lift table: cam angle against follower lift.

A lift table is a CSV-like text with two columns, ``angle_deg, lift_mm`` (the
lift is in degrees for an oscillating follower).  A header line is optional;
a header naming more columns (``cam_angle_deg, lift, velocity, acceleration``,
as ``camcam reverse`` writes) makes every row carry that many values, of which
the first two are read;
values are separated by commas or whitespace with any spacing; ``#`` starts a
comment line.  The angles must rise strictly.  A table whose angles span
exactly 360° is a full revolution and must close (the last lift equals the
first); any shorter span is a rise-only table.

Every error is one :class:`~camcam.errors.InputError` line naming the row (the
line number in the file), e.g. ``lift.csv row 7: angle 12 is not above the
previous angle 12``.
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass
from pathlib import Path

import numpy as np

from camcam.errors import InputError
from camcam.inputs import data_rows, looks_numeric, parse_number, read_text

__all__ = ["LiftTable", "parse_lift_table", "load_lift_table", "CLOSE_ATOL", "MIN_ROWS"]

#: A full revolution must close within this much (mm or deg): half a unit of the
#: sixth decimal, the finest precision lift tables are printed with.
CLOSE_ATOL = 5e-7

#: Tolerance on "spans exactly 360°": decimal angles sum to 360 within rounding.
SPAN_ATOL_DEG = 1e-9

#: Fewest rows: a cubic needs 4 points, the bad-point test 4 neighbours + 1.
MIN_ROWS = 5



@dataclass(frozen=True)
class LiftTable:
    """A validated lift table.

    Parameters
    ----------
    angles_deg : tuple of float
        Strictly increasing cam angles in degrees.
    lift : tuple of float
        Follower lift at each angle (mm, or deg for an oscillating follower).
    source : str
        Name used in messages (the file name).
    rows : tuple of int
        Line number of each entry in the source file.
    resolution : float
        The smallest decimal step the lifts were written with (0 if unknown).

    Examples
    --------
    >>> t = parse_lift_table("angle_deg, lift_mm\\n0 0\\n90 1\\n180 2\\n270 1\\n360 0\\n", "x.csv")
    >>> t.full_revolution, t.span_deg, len(t)
    (True, 360.0, 5)
    """

    angles_deg: tuple[float, ...]
    lift: tuple[float, ...]
    source: str = "table"
    _: KW_ONLY
    rows: tuple[int, ...] = ()
    resolution: float = 0.0

    def __len__(self) -> int:
        return len(self.angles_deg)

    @property
    def x(self) -> np.ndarray:
        """Angles in degrees as an array."""
        return np.asarray(self.angles_deg, dtype=float)

    @property
    def y(self) -> np.ndarray:
        """Lifts as an array."""
        return np.asarray(self.lift, dtype=float)

    @property
    def span_deg(self) -> float:
        return self.angles_deg[-1] - self.angles_deg[0]

    @property
    def full_revolution(self) -> bool:
        """True when the angles span exactly one revolution (360°)."""
        return abs(self.span_deg - 360.0) <= SPAN_ATOL_DEG

    def with_lift(self, lift) -> "LiftTable":
        """The same angles with new lifts (a full revolution is closed exactly)."""
        lift = np.asarray(lift, dtype=float)
        if self.full_revolution:
            lift = lift.copy()
            lift[-1] = lift[0]
        return LiftTable(self.angles_deg, tuple(float(v) for v in lift), self.source, rows=self.rows,
                         resolution=self.resolution)

    def row_of(self, index: int) -> int:
        return self.rows[index] if self.rows else index + 1


def _decimals(text: str) -> int:
    mant = text.lower().split("e")[0]
    exp = int(text.lower().split("e")[1]) if "e" in text.lower() else 0
    dec = len(mant.split(".")[1]) if "." in mant else 0
    return dec - exp


def parse_lift_table(text: str, source: str = "table") -> LiftTable:
    """Validate the text of a lift table (see the module docstring).

    Examples
    --------
    >>> parse_lift_table("0 0\\n1 1\\n2 2\\n2 3\\n4 4\\n", "lift.csv")
    Traceback (most recent call last):
    ...
    camcam.errors.InputError: lift.csv row 4: angle 2 is not above the previous angle 2
    """
    angles: list[float] = []
    lifts: list[float] = []
    rows: list[int] = []
    decimals = 0
    ncol = 2
    seen_content = False
    for where, lineno, stripped, fields in data_rows(text, source):
        first_content = not seen_content
        seen_content = True
        if first_content and fields:
            if not looks_numeric(fields[0]):
                if len(fields) < 2:
                    raise InputError(f"{where}: a header needs 2 column names (angle_deg, lift_mm), got {len(fields)}") from None
                ncol = len(fields)
                continue  # a header line
        if len(fields) != ncol or "" in fields:
            raise InputError(f"{where}: expected {ncol} values (angle_deg, lift_mm{', …' if ncol > 2 else ''}), got {stripped!r}")
        angle = parse_number(fields[0], "angle", where)
        lift = parse_number(fields[1], "lift", where)
        if angles and angle <= angles[-1]:
            raise InputError(f"{where}: angle {angle:g} is not above the previous angle {angles[-1]:g}")
        if angles and angle - angles[0] > 360.0 + SPAN_ATOL_DEG:
            raise InputError(f"{where}: angle {angle:g} is more than 360° after the first angle {angles[0]:g}")
        decimals = max(decimals, _decimals(fields[1]))
        angles.append(angle)
        lifts.append(lift)
        rows.append(lineno)
    if len(angles) < MIN_ROWS:
        raise InputError(f"{source}: {len(angles)} data row(s); a lift table needs at least {MIN_ROWS}")
    table = LiftTable(tuple(angles), tuple(lifts), source, rows=tuple(rows), resolution=10.0 ** (-decimals))
    if table.full_revolution and abs(lifts[-1] - lifts[0]) > CLOSE_ATOL:
        raise InputError(
            f"{source} row {rows[-1]}: lift {lifts[-1]:g} at {angles[-1]:g}° differs from lift {lifts[0]:g} "
            f"at {angles[0]:g}° by {lifts[-1] - lifts[0]:+.6g}; a full revolution must close"
        )
    return table


def load_lift_table(path: str | Path) -> LiftTable:
    """Read and validate the lift table file at ``path`` (named by its file name in messages)."""
    path = Path(path)
    text = read_text(path)
    return parse_lift_table(text, path.name)
