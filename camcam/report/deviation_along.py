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
from camcam.toolpath.elements import element_nearest

__all__ = ["signed_deviation"]


def signed_deviation(curve: PlanarCurve, elements, theta: np.ndarray, outward: np.ndarray | None) -> np.ndarray:
    """Signed distance (mm) from ``curve(theta)`` to the nearest printed element, + outward.

    ``outward`` (n, 2) are unit normals away from the material at ``theta``;
    ``None`` gives the unsigned distance.
    """
    q = curve.evaluate(theta, 0)
    best = np.full(len(q), np.inf)
    best_pt = np.zeros_like(q)
    for e in elements:
        p = element_nearest(e, q)
        d = np.hypot(*(p - q).T)
        m = d < best
        best[m] = d[m]
        best_pt[m] = p[m]
    if outward is None:
        return best
    return np.sign(np.einsum("ij,ij->i", best_pt - q, outward)) * best
