"""Interpolating a lift table: cubic splines with the seed's end conditions, or seed 002's B-spline.

Fits (``fit`` in the spec, ``--fit`` on the command line):

``periodic``
    Cubic spline, periodic ends (S, V, A continuous through 360°/0°); full revolutions only.
``clamped``
    Cubic spline with given end slopes y'_0, y'_N (seed 004, eqs. 5–6); the
    slopes default to 0 (from and to rest).
``natural``
    Cubic spline with zero second derivative at both ends.
``not-a-knot``
    Cubic spline whose third derivative is continuous at the second and last-but-one points.
``bspline``
    Seed 002's chord-length cubic B-spline with free ends (:mod:`camcam.lifttable.bspline`).

Every interpolant is called as ``f(angle_deg, nu)``: derivative ``nu`` of the
lift with respect to the angle in degrees.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline

from camcam.errors import InputError
from camcam.lifttable.bspline import chord_bspline

__all__ = ["FITS", "interpolate", "default_fit"]

FITS = ("periodic", "clamped", "natural", "not-a-knot", "bspline")


def default_fit(full_revolution: bool) -> str:
    """``periodic`` for a full revolution, ``clamped`` (from rest to rest) for a rise-only table."""
    return "periodic" if full_revolution else "clamped"


def interpolate(x, y, fit: str, end_slopes: tuple[float, float] = (0.0, 0.0)):
    """The interpolant of (x_i, y_i) for ``fit`` (see the module docstring).

    Parameters
    ----------
    x, y : array_like
        Strictly increasing angles (deg) and lifts.
    fit : str
        One of :data:`FITS`.
    end_slopes : (float, float)
        dy/dx at the first and last angle for ``clamped`` (lift per degree).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.arange(0.0, 361.0, 10.0); y = np.sin(np.radians(x))
    >>> f = interpolate(x, y, "periodic")
    >>> bool(abs(float(f(45.0)) - np.sin(np.radians(45.0))) < 1e-5)
    True
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if fit == "bspline":
        return chord_bspline(x, y)
    if fit == "periodic":
        if abs(x[-1] - x[0] - 360.0) > 1e-9:
            raise InputError(f"fit \"periodic\" needs a full revolution; the table covers {x[0]:g}–{x[-1]:g}°")
        y = y.copy()
        y[-1] = y[0]
        return CubicSpline(x, y, bc_type="periodic")
    if fit == "clamped":
        return CubicSpline(x, y, bc_type=((1, float(end_slopes[0])), (1, float(end_slopes[1]))))
    if fit in ("natural", "not-a-knot"):
        return CubicSpline(x, y, bc_type=fit)
    raise ValueError(f"unknown fit {fit!r}; known: {', '.join(FITS)}")
