"""Deviation of the printed tool path from the exact tool-centre curve, along the cam angle.

At each cam angle the exact tool-centre point is compared with the nearest
point of the printed path; the signed value is positive where the path lies
outside (away from the material, leaving stock) and negative where it cuts in.
This is the curve→path half of the two-sided measurement, drawn for the
machinist; the guaranteed maximum (both halves) comes from the fitting stage.
"""

from __future__ import annotations

import numpy as np

from camcam.geometry.curve import PlanarCurve
from camcam.toolpath.elements import Line

__all__ = ["signed_deviation"]


def _nearest_on(e, q: np.ndarray) -> np.ndarray:
    """Nearest points of element ``e`` to points ``q`` (n, 2)."""
    if isinstance(e, Line):
        a, b = np.asarray(e.start, float), np.asarray(e.end, float)
        d = b - a
        u = np.clip(((q - a) @ d) / (d @ d), 0.0, 1.0)
        return a + u[:, None] * d
    c = np.asarray(e.centre, float)
    v = q - c
    ang = np.arctan2(v[:, 1], v[:, 0])
    a0 = np.arctan2(e.start[1] - c[1], e.start[0] - c[0])
    sweep = e.sweep if e.ccw else -e.sweep
    rel = np.mod((ang - a0) * np.sign(sweep), 2 * np.pi)
    inside = rel <= abs(sweep)
    on_circle = c + e.radius * v / np.hypot(v[:, 0], v[:, 1])[:, None]
    ends = np.array([e.start, e.end], float)
    de = np.hypot(*(q[:, None, :] - ends[None, :, :]).transpose(2, 0, 1))
    nearest_end = ends[np.argmin(de, axis=1)]
    return np.where(inside[:, None], on_circle, nearest_end)


def signed_deviation(curve: PlanarCurve, elements, theta: np.ndarray, outward: np.ndarray | None) -> np.ndarray:
    """Signed distance (mm) from ``curve(theta)`` to the nearest printed element, + outward.

    ``outward`` (n, 2) are unit normals away from the material at ``theta``;
    ``None`` gives the unsigned distance.
    """
    q = curve.evaluate(theta, 0)
    best = np.full(len(q), np.inf)
    best_pt = np.zeros_like(q)
    for e in elements:
        p = _nearest_on(e, q)
        d = np.hypot(*(p - q).T)
        m = d < best
        best[m] = d[m]
        best_pt[m] = p[m]
    if outward is None:
        return best
    return np.sign(np.einsum("ij,ij->i", best_pt - q, outward)) * best
