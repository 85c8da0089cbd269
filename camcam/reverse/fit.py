"""From recovered (cam angle, lift) pairs at uneven angles to a periodic motion with derivatives.

The pairs are sorted, checked to cover the revolution, optionally smoothed by
the lift-table stage's GCV smoothing spline (periodic: padded by a period),
and fitted by

``periodic``
    the lift-table stage's periodic cubic spline through [θ₀, θ₀ + 360°];
``bspline``
    seed 002's chord-length cubic B-spline (:func:`camcam.lifttable.bspline.chord_bspline`).
    Its free ends (eq. 8) would put zero curvature at θ₀ and θ₀ + 360°; here
    the table is padded with a quarter of its points from each neighbouring
    revolution, so the free ends fall outside the revolution used.

Derivatives are per degree of cam angle (mm/deg, deg/deg, …).

Examples
--------
>>> import numpy as np
>>> ang = np.sort(np.random.default_rng(3).uniform(0, 360, 120))
>>> m = fit_motion(ang, 2 - 2 * np.cos(np.radians(ang)), "mm", "periodic", smoothing=False)
>>> round(float(m(np.array([180.0]))[0]), 5)
4.0
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.lifttable.bspline import chord_bspline
from camcam.lifttable.fairing import smoothing_fairing
from camcam.lifttable.interpolate import interpolate
from camcam.lifttable.table import LiftTable

__all__ = ["RecoveredMotion", "fit_motion", "check_coverage", "FITS", "DEFAULT_MAX_GAP_DEG"]

FITS = ("periodic", "bspline")
#: The largest gap between neighbouring recovered cam angles a point set may leave, degrees.
DEFAULT_MAX_GAP_DEG = 20.0


def check_coverage(angles_deg: np.ndarray, max_gap_deg: float = DEFAULT_MAX_GAP_DEG) -> None:
    """Raise :class:`GeometryError` when sorted ``angles_deg`` leave a gap above ``max_gap_deg`` (cyclically)."""
    a = np.asarray(angles_deg, dtype=float)
    gaps = np.diff(np.concatenate([a, [a[0] + 360.0]]))
    i = int(np.argmax(gaps))
    if gaps[i] > max_gap_deg:
        raise GeometryError(
            f"the points do not cover the revolution: no point between cam angles {a[i]:.2f}° and "
            f"{(a[(i + 1) % a.size]):.2f}° (a gap of {gaps[i]:.2f}°, at most {max_gap_deg:g}° allowed)"
        )
    if np.any(gaps <= 1e-9):
        j = int(np.flatnonzero(gaps <= 1e-9)[0])
        raise GeometryError(f"two points give the same cam angle {a[j]:.6f}°; remove the duplicate")


@dataclass(frozen=True, eq=False, kw_only=True)
class RecoveredMotion:
    """The recovered follower motion: ``motion(angle_deg, nu)`` is d^ν lift / dθ^ν (per degree).

    ``angles_deg``/``lift`` are the recovered points (sorted, lift smoothed when
    ``smoothed``), ``raw_lift`` before smoothing.
    """

    angles_deg: np.ndarray
    lift: np.ndarray
    raw_lift: np.ndarray
    unit: str
    fit: str
    smoothed: bool
    _f: object

    def __call__(self, angle_deg, nu: int = 0) -> np.ndarray:
        a0 = self.angles_deg[0]
        x = a0 + np.mod(np.asarray(angle_deg, dtype=float) - a0, 360.0)
        return np.asarray(self._f(x, nu), dtype=float)

    def table(self, points: int) -> tuple[np.ndarray, np.ndarray]:
        """``points`` cam angles 0, 360/points, … and the closing 360°, with (lift, velocity, acceleration) columns."""
        ang = np.arange(points + 1) * (360.0 / points)
        ang[-1] = 360.0
        cols = np.stack([self(ang, k) for k in range(3)], axis=-1)
        cols[-1] = cols[0]
        return ang, cols


def fit_motion(angles_deg, lift, unit: str, fit: str = "periodic", smoothing: bool = True,
               max_gap_deg: float = DEFAULT_MAX_GAP_DEG) -> RecoveredMotion:
    """Sort, check coverage, smooth (GCV) when asked, and fit (module docstring)."""
    if fit not in FITS:
        raise ValueError(f"unknown fit {fit!r}; known: {', '.join(FITS)}")
    order = np.argsort(angles_deg, kind="stable")
    x = np.asarray(angles_deg, dtype=float)[order]
    y = np.asarray(lift, dtype=float)[order]
    check_coverage(x, max_gap_deg)
    xc, yc = np.append(x, x[0] + 360.0), np.append(y, y[0])
    ys = yc
    if smoothing:
        ys = smoothing_fairing(LiftTable(tuple(xc), tuple(yc))).table.y
    if fit == "periodic":
        f = interpolate(xc, ys, "periodic")
    else:
        m = max(4, x.size // 4)
        xp = np.concatenate([x[-m:] - 360.0, xc, x[1:m + 1] + 360.0])
        yp = np.concatenate([ys[-m - 1:-1], ys, ys[1:m + 1]])
        f = chord_bspline(xp, yp)
    return RecoveredMotion(angles_deg=x, lift=ys[:-1], raw_lift=y, unit=unit, fit=fit, smoothed=smoothing, _f=f)
