"""Curvature analysis: of the lift curve (fairness check), and of a cam profile.

The lift curve is the graph h(α) drawn with one degree of cam angle as one
unit of length, so its curvature κ = h''/(1 + h'²)^{3/2} (per mm with
h in mm) is what the comb of the plotted curve shows; a rough table shows up
as a ragged comb.  The cam profile's curvature comes from the geometry stage
through the :class:`~camcam.geometry.curve.PlanarCurve` protocol.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.geometry.curve import PlanarCurve, curvature

__all__ = ["lift_curvature", "ProfileCurvature", "profile_curvature"]


def lift_curvature(f, angles_deg) -> np.ndarray:
    """Curvature of the graph of interpolant ``f`` (``f(x, nu)``, x in degrees) at ``angles_deg``.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.interpolate import CubicSpline
    >>> x = np.linspace(-1, 1, 9); f = CubicSpline(x, x ** 2)     # parabola: κ(0) = 2
    >>> round(float(lift_curvature(f, [0.0])[0]), 9)
    2.0
    """
    a = np.asarray(angles_deg, dtype=float)
    d1, d2 = f(a, 1), f(a, 2)
    return d2 / (1.0 + d1**2) ** 1.5


@dataclass(frozen=True)
class ProfileCurvature:
    """Curvature of a profile sampled piece by piece (every break included)."""

    t: np.ndarray
    kappa: np.ndarray

    @property
    def min_radius(self) -> float:
        """Smallest |radius of curvature| over the samples (inf where straight)."""
        k = np.max(np.abs(self.kappa))
        return float(1.0 / k) if k > 0 else float("inf")


def profile_curvature(curve: PlanarCurve, per_piece: int = 64) -> ProfileCurvature:
    """κ of ``curve`` at ``per_piece`` points on each analytic piece, both ends of every piece included.

    Examples
    --------
    >>> import numpy as np
    >>> from camcam.geometry.curve import FunctionCurve
    >>> def ellipse(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return np.stack([[4 * c, 2 * s], [-4 * s, 2 * c], [-4 * c, -2 * s], [4 * s, -2 * c]][k], axis=-1)
    >>> pc = profile_curvature(FunctionCurve(ellipse, 0.0, 2 * np.pi, closed=True))
    >>> round(pc.min_radius, 12)                       # b²/a = 4/4 at the ends of the major axis
    1.0
    """
    b = np.asarray(curve.breaks, dtype=float)
    t = np.unique(np.concatenate([np.linspace(lo, hi, per_piece) for lo, hi in zip(b[:-1], b[1:])]))
    return ProfileCurvature(t, curvature(curve, t))
