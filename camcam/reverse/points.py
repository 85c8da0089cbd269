"""Measured points: reading the CSV text and ordering the points about the cam axis.

A points file has two columns ``x, y`` (a disc cam's profile, mm, drawing
frame) or three ``x, y, z`` (a cylindrical cam's flank, mm, cam frame of
:mod:`camcam.geometry.cylindrical`; a disc cam ignores z).  A header line is
optional; values are separated by commas or whitespace; ``#`` starts a
comment line.  Every error is one :class:`~camcam.errors.InputError` line
naming the row (the line number in the file).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from camcam.errors import InputError
from camcam.inputs import data_rows, looks_numeric, parse_number, read_text

__all__ = ["MeasuredPoints", "parse_points", "load_points", "MIN_POINTS"]

#: Fewest points: the periodic fits and the three-point differences need a few per feature.
MIN_POINTS = 20



@dataclass(frozen=True)
class MeasuredPoints:
    """Points (n, 2 or 3) in file order, with the file line of each."""

    xyz: np.ndarray
    rows: tuple[int, ...]
    source: str = "points"

    @property
    def dims(self) -> int:
        return self.xyz.shape[1]

    def __len__(self) -> int:
        return self.xyz.shape[0]

    def describe(self, index: int) -> str:
        """"points.csv row 12" for the point at ``index`` (file order)."""
        return f"{self.source} row {self.rows[index]}"


def parse_points(text: str, source: str = "points") -> MeasuredPoints:
    """Validate the text of a points file (module docstring).

    Examples
    --------
    >>> p = parse_points("x, y, z\\n" + "\\n".join(f"{i}, 1, 2" for i in range(20)), "p.csv")
    >>> p.dims, len(p), p.rows[0]
    (3, 20, 2)
    >>> parse_points("x, y\\n1, 2\\n3, four\\n", "p.csv")
    Traceback (most recent call last):
    ...
    camcam.errors.InputError: p.csv row 3: y 'four' is not a number
    """
    rows: list[list[float]] = []
    lines: list[int] = []
    ncol = None
    seen = False
    for where, lineno, stripped, fields in data_rows(text, source):
        if not seen:
            seen = True
            if not looks_numeric(fields[0]):
                if len(fields) not in (2, 3):
                    raise InputError(f"{where}: a header needs 2 or 3 column names (x, y[, z]), got {len(fields)}") from None
                ncol = len(fields)
                continue
        if ncol is None:
            ncol = len(fields)
            if ncol not in (2, 3) or "" in fields:
                raise InputError(f"{where}: expected 2 or 3 values (x, y[, z]), got {stripped!r}")
        if len(fields) != ncol or "" in fields:
            names = "x, y, z" if ncol == 3 else "x, y"
            raise InputError(f"{where}: expected {ncol} values ({names}), got {stripped!r}")
        rows.append([parse_number(f, name, where) for name, f in zip("xyz", fields)])
        lines.append(lineno)
    if len(rows) < MIN_POINTS:
        raise InputError(f"{source}: {len(rows)} point(s); reverse design needs at least {MIN_POINTS}")
    return MeasuredPoints(np.array(rows), tuple(lines), source)


def load_points(path: str | Path) -> MeasuredPoints:
    """Read and validate the points file at ``path`` (named by its file name in messages)."""
    path = Path(path)
    text = read_text(path)
    return parse_points(text, path.name)
