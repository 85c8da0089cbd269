"""Disc cams: measured profile points → follower lift, by the follower's inverse kinematics.

Frames and followers are those of :mod:`camcam.geometry.disc` and
:mod:`camcam.geometry.followers`: the points are the profile in the drawing
(cam angle 0), the cam turns by σ about +Z, a fixed-frame point at program
angle θ is R(σθ)·P.  The profile is fitted as a periodic function r(φ) of the
polar angle φ about the cam centre (:mod:`camcam.reverse.slopes`), which gives
each point's outward normal n = (r e_r − r′ e_φ)/√(r² + r′²).  Then, per point:

translating roller (offset e)
    the roller centre C = P + r_r n sits on the stem x = e above the cam:
    |C| = ρ, the fixed-frame angle of C is β = atan2(√(ρ² − e²), e), so
    θ = σ(β − ∠C) and s = √(ρ² − e²) − √((R_b + r_r)² − e²);
oscillating roller (pivot (a, 0), arm L)
    C on both the circle |C| = ρ and the arm's circle about the pivot (upper
    intersection): arm angle β, lift ψ = β₀ − β, θ = σ(∠C_fixed − ∠C);
translating flat
    the face normal is +Y: θ = σ(π/2 − ∠n) and s = P·n − R_b (the support
    function);
oscillating flat (face line through the pivot)
    with p = P·n the face's distance from the cam centre, sin β = p/a,
    β = π − asin(p/a) (the branch of the forward model), ψ = β₀ − β and
    θ = σ(β − π/2 − ∠n).

Each raises :class:`GeometryError` naming the first point the follower cannot
reach.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.build import disc_follower
from camcam.geometry.followers import OscillatingRoller, TranslatingFlat, TranslatingRoller
from camcam.geometry.disc import SIGMA

__all__ = ["disc_follower", "profile_normals", "solve_disc"]



def profile_normals(phi, r, dr) -> np.ndarray:
    """Outward unit normals (n, 2) of the polar curve r(φ) with r′ = ``dr``.

    Examples
    --------
    >>> import numpy as np
    >>> profile_normals(np.array([0.5]), np.array([3.0]), np.array([0.0])).round(6).tolist()
    [[0.877583, 0.479426]]
    """
    phi, r, dr = (np.asarray(v, dtype=float) for v in (phi, r, dr))
    c, s = np.cos(phi), np.sin(phi)
    nx = r * c + dr * s  # r e_r − r′ e_φ, e_φ = (−sin φ, cos φ)
    ny = r * s - dr * c
    h = np.hypot(nx, ny)
    return np.stack([nx / h, ny / h], axis=-1)


def _reject(mask, points, what: str) -> None:
    if np.any(mask):
        i = int(np.flatnonzero(mask)[0])
        raise GeometryError(f"point ({points[i, 0]:.4f}, {points[i, 1]:.4f}) does not fit the follower: {what}")


def solve_disc(follower, base_radius: float, rotation: str, points, normals) -> tuple[np.ndarray, np.ndarray]:
    """Cam angle θ (rad, in [0, 2π)) and lift (mm, or rad for an oscillating follower) of each profile point.

    ``points`` and ``normals`` (n, 2) are cam-frame profile points and outward unit normals.
    """
    P = np.asarray(points, dtype=float)
    n = np.asarray(normals, dtype=float)
    sg = SIGMA[rotation]
    follower.check(base_radius)
    if isinstance(follower, (TranslatingRoller, OscillatingRoller)):
        C = P + follower.roller_radius * n
        rho, gamma = np.hypot(C[:, 0], C[:, 1]), np.arctan2(C[:, 1], C[:, 0])
        if isinstance(follower, TranslatingRoller):
            e = follower.offset
            _reject(rho <= abs(e), P, f"its roller centre is {rho.min():.4f} mm from the cam centre, inside the offset {e:g} mm")
            y = np.sqrt(rho**2 - e**2)
            theta = sg * (np.arctan2(y, e) - gamma)
            lift = y - math.sqrt((base_radius + follower.roller_radius) ** 2 - e**2)
        else:
            a, L = follower.pivot_distance, follower.arm_length
            x = (a * a + rho**2 - L * L) / (2 * a)
            _reject(
                (rho <= abs(a - L)) | (rho >= a + L), P,
                f"the arm of {L:g} mm pivoting {a:g} mm from the cam centre cannot reach its roller centre",
            )
            y = np.sqrt(np.maximum(rho**2 - x**2, 0.0))
            beta = np.arctan2(y, x - a)
            lift = follower.start_angle(base_radius) - beta
            theta = sg * (np.arctan2(y, x) - gamma)
    else:
        nu = np.arctan2(n[:, 1], n[:, 0])
        p = np.einsum("ij,ij->i", P, n)
        if isinstance(follower, TranslatingFlat):
            theta = sg * (0.5 * math.pi - nu)
            lift = p - base_radius
        else:
            a = follower.pivot_distance
            _reject(p >= a, P, f"its tangent lies {p.max():.4f} mm from the cam centre, beyond the pivot at {a:g} mm")
            beta = math.pi - np.arcsin(p / a)
            lift = follower.start_angle(base_radius) - beta
            theta = sg * (beta - 0.5 * math.pi - nu)
    return np.mod(theta, 2 * math.pi), lift
