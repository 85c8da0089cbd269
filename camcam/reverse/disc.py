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

Each is its kind's ``invert`` (:mod:`camcam.geometry.followers`) and raises
:class:`GeometryError` naming the first point the follower cannot reach.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.build import disc_follower
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


def solve_disc(follower, base_radius: float, rotation: str, points, normals) -> tuple[np.ndarray, np.ndarray]:
    """Cam angle θ (rad, in [0, 2π)) and lift (mm, or rad for an oscillating follower) of each profile point.

    ``points`` and ``normals`` (n, 2) are cam-frame profile points and outward unit normals.
    """
    P = np.asarray(points, dtype=float)
    n = np.asarray(normals, dtype=float)
    sg = SIGMA[rotation]
    follower.check(base_radius)
    theta, lift = follower.invert(P, n, base_radius, sg)
    return np.mod(theta, 2 * math.pi), lift
