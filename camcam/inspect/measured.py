"""A measured part: the text of a CMM points file, a dial-indicator table or a bore file, validated.

Three kinds (issue 46), each a CSV-like text (header optional, values separated
by commas or white space, ``#`` starts a comment line, as every camcam table):

``cmm``
    ``x_mm, y_mm[, z_mm]``: points on a disc cam's profile in the part frame
    (drawing frame of DESIGN.md, cam axis +Z; z is ignored).
``dial``
    ``angle_deg, reading_mm``: a dial indicator (or the follower) on a dividing
    head, its probe of a stated tip radius moving radially; the reading's zero is
    arbitrary (it is fitted).
``barrel``
    ``x_mm, y_mm, z_mm``: points on the two walls of a barrel cam's groove, cam
    axis along X (the machine frame of DESIGN.md at A = 0).

Bore points (``x_mm, y_mm[, z_mm]``) locate the cam centre of a disc part
(:func:`bore_centre`).  Every error is one :class:`~camcam.errors.InputError`
line naming the file and row.  This module does no I/O: the command reads the
files and hands their text here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import InputError
from camcam.inputs import data_rows, looks_numeric, parse_number

__all__ = ["KINDS", "MeasuredPart", "parse_measured", "parse_bore", "bore_centre", "MIN_POINTS", "MAX_POINTS",
           "MIN_BORE_POINTS"]

KINDS = ("cmm", "dial", "barrel")
#: Fewest points of a part: the bad-point test needs 4 neighbours a point, the reverse fit a few per feature.
MIN_POINTS = 20
#: Most points of a part: each point is solved for its nearest point on the exact profile at every step
#: of the alignment (20 000 points take a few seconds; a CMM scan of a cam rarely has more than 5000).
MAX_POINTS = 20_000
#: Fewest bore points: a circle has three unknowns; a few more give its uncertainty.
MIN_BORE_POINTS = 5

_COLUMNS = {"cmm": ("x", "y", "z"), "dial": ("angle", "reading"), "barrel": ("x", "y", "z")}


@dataclass(frozen=True, kw_only=True)
class MeasuredPart:
    """Validated measurements in file order: ``values`` (n, 2) — x, y for ``cmm``, angle (deg), reading
    (mm) for ``dial`` — or (n, 3) x, y, z for ``barrel``; ``rows`` the file line of each."""

    kind: str
    values: np.ndarray
    rows: tuple[int, ...]
    source: str

    def __len__(self) -> int:
        return self.values.shape[0]

    def describe(self, index: int) -> str:
        """"part.csv row 12" for the point at ``index`` (file order)."""
        return f"{self.source} row {self.rows[index]}"


def _table(text: str, source: str, names: tuple[str, ...], optional_last: bool, what: str, fewest: int,
           most: int) -> tuple[np.ndarray, tuple[int, ...]]:
    """Rows of ``len(names)`` numbers (or one fewer when ``optional_last``), a header optional."""
    allowed = (len(names) - 1, len(names)) if optional_last else (len(names),)
    wanted = " or ".join(str(n) for n in allowed)
    rows: list[list[float]] = []
    lines: list[int] = []
    ncol = None
    for where, lineno, stripped, fields in data_rows(text, source):
        if ncol is None and not rows and not looks_numeric(fields[0]):
            if len(fields) not in allowed:
                raise InputError(f"{where}: a header needs {wanted} column names ({', '.join(names)}), got {len(fields)}")
            ncol = len(fields)
            continue
        if ncol is None:
            ncol = len(fields)
            if ncol not in allowed:
                raise InputError(f"{where}: expected {wanted} values ({', '.join(names)}), got {stripped!r}")
        if len(fields) != ncol or "" in fields:
            raise InputError(f"{where}: expected {ncol} values ({', '.join(names[:ncol])}), got {stripped!r}")
        if len(rows) >= most:
            raise InputError(f"{where}: more than {most} {what}; at most {most} are read")
        rows.append([parse_number(f, name, where) for name, f in zip(names, fields)])
        lines.append(lineno)
    if len(rows) < fewest:
        raise InputError(f"{source}: {len(rows)} {what}; inspection needs at least {fewest}")
    return np.array(rows, dtype=float), tuple(lines)


def parse_measured(text: str, kind: str, source: str = "measured") -> MeasuredPart:
    """Validate the text of a measured part of ``kind`` (module docstring).

    Examples
    --------
    >>> p = parse_measured("angle_deg, reading_mm\\n" + "\\n".join(f"{i * 10}, 0.5" for i in range(36)), "dial", "d.csv")
    >>> p.kind, len(p), p.rows[0]
    ('dial', 36, 2)
    >>> parse_measured("x, y\\n1, 2\\n", "cmm", "p.csv")
    Traceback (most recent call last):
    ...
    camcam.errors.InputError: p.csv: 1 points; inspection needs at least 20
    """
    if kind not in KINDS:
        raise ValueError(f"unknown measured kind {kind!r}; known: {', '.join(KINDS)}")
    names = _COLUMNS[kind]
    values, rows = _table(text, source, names, kind == "cmm", "points" if kind != "dial" else "readings",
                          MIN_POINTS, MAX_POINTS)
    if kind == "cmm":
        values = values[:, :2]
    if kind == "dial":
        values[:, 0] = np.mod(values[:, 0], 360.0)
        order = np.argsort(values[:, 0], kind="stable")
        same = np.flatnonzero(np.diff(values[order, 0]) <= 1e-9)
        if same.size:
            i, j = order[same[0]], order[same[0] + 1]
            raise InputError(f"{source} row {rows[j]}: angle {values[j, 0]:g}° was read already at row {rows[i]} "
                             "(one reading per angle; average repeats first)")
    return MeasuredPart(kind=kind, values=values, rows=rows, source=source)


def parse_bore(text: str, source: str = "bore") -> MeasuredPart:
    """Validate bore points (x, y[, z], mm); at least :data:`MIN_BORE_POINTS`."""
    values, rows = _table(text, source, ("x", "y", "z"), True, "bore points", MIN_BORE_POINTS, MAX_POINTS)
    return MeasuredPart(kind="cmm", values=values[:, :2], rows=rows, source=source)


@dataclass(frozen=True, kw_only=True)
class BoreCentre:
    """The fitted bore circle: centre (mm, part frame), radius and their standard uncertainties."""

    centre: np.ndarray
    radius: float
    centre_sigma: np.ndarray
    rms_mm: float


def bore_centre(bore: MeasuredPart) -> BoreCentre:
    """Least-squares circle through the bore points (geometric distance, uncertainty from the Jacobian).

    Examples
    --------
    >>> t = np.radians(np.arange(0, 360, 30))
    >>> pts = np.stack([1.0 + 6 * np.cos(t), -2.0 + 6 * np.sin(t)], axis=-1)
    >>> c = bore_centre(MeasuredPart(kind="cmm", values=pts, rows=tuple(range(12)), source="b"))
    >>> [round(float(v), 9) for v in (*c.centre, c.radius)]
    [1.0, -2.0, 6.0]
    """
    from scipy.optimize import least_squares

    P = bore.values
    phi = np.unwrap(np.arctan2(P[:, 1] - P[:, 1].mean(), P[:, 0] - P[:, 0].mean()))
    if np.ptp(phi) < math.radians(90.0):
        raise InputError(f"{bore.source}: the bore points span {math.degrees(np.ptp(phi)):.1f}° of the bore; "
                         "at least 90° are needed to find its centre")

    def res(u):
        return np.hypot(P[:, 0] - u[0], P[:, 1] - u[1]) - u[2]

    def jac(u):
        d = np.maximum(np.hypot(P[:, 0] - u[0], P[:, 1] - u[1]), 1e-300)
        return np.stack([-(P[:, 0] - u[0]) / d, -(P[:, 1] - u[1]) / d, -np.ones(len(P))], axis=-1)

    c0 = P.mean(axis=0)
    u0 = np.array([c0[0], c0[1], float(np.mean(np.hypot(*(P - c0).T)))])
    fit = least_squares(res, u0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
    r = fit.fun
    dof = max(len(P) - 3, 1)
    s2 = float(r @ r) / dof
    cov = s2 * np.linalg.pinv(fit.jac.T @ fit.jac)
    return BoreCentre(centre=fit.x[:2], radius=float(fit.x[2]), centre_sigma=np.sqrt(np.diag(cov)[:2]),
                      rms_mm=math.sqrt(float(r @ r) / len(P)))
