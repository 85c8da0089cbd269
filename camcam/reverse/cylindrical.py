"""Cylindrical cams: measured flank points → follower motion (seed 002, section 4, corrected).

Frames and followers are those of :mod:`camcam.geometry.cylindrical` (cam axis
+X, follower above the cam on +Z, cam turning by σ about +X).  A measured point
P (cam frame) lies on one groove flank; its cylindrical coordinates about the
cam axis are the axial x_P, the radius ρ_P and the polar angle φ_P = atan2(z, y).
The flank's tangent there, from the neighbouring points, has cylindrical
components (t_x, t_r, t_φ).

The follower's roller-axis point C(q, ℓ) (q the follower coordinate – the
follower angle θf from the perpendicular, or the axial displacement from the
groove's mid-line – and ℓ the roller cross-section: the arm distance, or the
radius) and the contact

    p = C + k·r_r·m,   m = cos α·n + sin α·e_Y          (seed eqs. 10–12)

(n the direction C moves for increasing q, k = ±1 the flank) must match P up to
the cam's turn, which leaves three rotation-invariant conditions for the three
unknowns (q, α, ℓ):

1. axial position   p_x = x_P                            (seed eq. 14)
2. radius          |p_yz| = ρ_P                           (seed: ℓ = r fixed)
3. the flank normal m is normal to the measured tangent:
   m · (t_x e_x + t_r e_r(p) + t_φ e_φ(p)) = 0            (seed eq. 13)

solved per point by Newton's method from the seed's start (α = 0, ℓ from the
radius, q from eq. 14).  The cam angle is then θ = σ(φ_p − φ_P) (seed eq. 15,
which is the half-angle form of the same rotation), and the follower velocity
per unit cam angle follows from the relative-velocity condition of the forward
model, tan α = −σ v / R:  dq/dθ = −σ R tan α / ℓ (oscillating, v = ℓ θf′,
R = d − ℓ cos θf; seed eqs. 16–18) or −σ R tan α (translating, R = ℓ).

Corrections to the seed, checked against the forward geometry in the tests:

* eq. 11 writes (d − r)·cos θf for the arm's reach where the arm geometry needs
  d − r·cos θf (the paper's own eq. 16 uses the latter);
* eq. 13, tan φ_z = f′/cos θf, is a first-order projection of the flank
  slope that ignores the roller offset moving the contact off the mid-plane;
  on the forward geometry it (and the projection f′·cos θf) misses tan α by
  ~1e-2, a cam-angle error of r_r·δα/R ≈ 0.1° (tests), so condition 3 is used
  exactly instead;
* the seed takes every measured point on the roller cross-section r; here ℓ
  is solved per point, so points measured at any depth (e.g. on a cylinder of
  constant radius, as a probe scans) are recovered as well.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.reverse.slopes import central_difference, periodic_fit

__all__ = ["BarrelFollower", "CylinderSolution", "flank_tangents", "solve_cylindrical"]

SIGMA = {"ccw": 1, "cw": -1}
#: Newton stops when every residual is below this (mm, or the sine of an angle).
RESIDUAL_TOL = 1e-10
MAX_NEWTON = 40


@dataclass(frozen=True, kw_only=True)
class BarrelFollower:
    """What the inverse needs of a cylindrical cam and its follower.

    ``pivot_distance`` None means a translating roller.  ``flank`` 0 is the
    groove wall on the −X side, 1 the +X side (as :meth:`CylindricalCam.flank`).
    ``inner_radius``/``outer_radius``: the groove bottom and the cylinder; a solved
    roller cross-section must lie within a roller radius of them.
    """

    roller_radius: float
    length: float
    rotation: str = "ccw"
    pivot_distance: float | None = None
    flank: int = 0
    inner_radius: float = 0.0
    outer_radius: float = math.inf

    @property
    def oscillating(self) -> bool:
        return self.pivot_distance is not None

    @property
    def sigma(self) -> int:
        return SIGMA[self.rotation]

    @property
    def side(self) -> float:
        """k = ±1: which side of the roller touches the measured flank (as the forward model)."""
        plus = 0 if self.oscillating else 1
        return 1.0 if self.flank == plus else -1.0

    def axis(self, q, ell):
        """Roller-axis point C, motion direction n (x and z parts; y is 0) and R = C's distance from the axis."""
        half = 0.5 * self.length
        if not self.oscillating:
            one = np.ones_like(q)
            return (half + q, ell), (one, 0.0 * one), ell
        d = self.pivot_distance
        c, s = np.cos(q), np.sin(q)
        return (half - ell * s, d - ell * c), (-c, s), d - ell * c

    def contact(self, q, alpha, ell):
        """Fixed-frame contact point (x, y, z) and flank normal m (x, y, z)."""
        (cx, cz), (nx, nz), _ = self.axis(q, ell)
        ca, sa = np.cos(alpha), np.sin(alpha)
        m = (nx * ca, sa, nz * ca)
        k = self.side * self.roller_radius
        return (cx + k * m[0], k * m[1], cz + k * m[2]), m

    def velocity(self, q, alpha, ell):
        """dq/dθ from the relative-velocity condition tan α = −σ v / R."""
        _, _, R = self.axis(q, ell)
        v = -self.sigma * R * np.tan(alpha)
        return v / ell if self.oscillating else v


@dataclass(frozen=True, kw_only=True)
class CylinderSolution:
    """Per measured point: cam angle θ (rad, [0, 2π)), follower coordinate q (rad or mm from the
    swing's centre), dq/dθ, contact angle α (rad), cross-section ℓ (mm) and the flank slope
    tan ϕ = t_x / t_φ of seed eq. 4."""

    cam_angle: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    alpha: np.ndarray
    ell: np.ndarray
    slope: np.ndarray


def flank_tangents(phi, x, r, method: str = "spline", smoothing: bool = False) -> np.ndarray:
    """Cylindrical components (t_x, t_r, t_φ) of the flank's tangent at each point, shape (n, 3).

    ``phi`` (strictly increasing in [0, 2π)), ``x``, ``r``: the ordered points'
    polar angle, axial coordinate and radius.  ``method`` is ``"central"``
    (seed eqs. 1–4: each triple turned so that P_i lies on the radial axis, the
    neighbours' circumferential offsets are h₁, h₂) or ``"spline"`` (periodic
    fits of x(φ) and r(φ), see :mod:`camcam.reverse.slopes`).
    """
    phi, x, r = (np.asarray(v, dtype=float) for v in (phi, x, r))
    if method == "spline":
        fx, fr = periodic_fit(phi, x, smoothing), periodic_fit(phi, r, smoothing)
        return np.stack([fx(phi, 1), fr(phi, 1), fr(phi)], axis=-1)
    if method != "central":
        raise ValueError(f"unknown slope method {method!r}; known: central, spline")
    prev, nxt = np.roll(np.arange(phi.size), 1), np.roll(np.arange(phi.size), -1)
    d_prev, d_next = phi[prev] - phi, phi[nxt] - phi
    d_prev = np.where(d_prev > 0, d_prev - 2 * math.pi, d_prev)
    d_next = np.where(d_next < 0, d_next + 2 * math.pi, d_next)
    # turned so that P_i is on the radial axis: circumferential y'' = r sin Δ, radial z' = r cos Δ
    h1 = -r[prev] * np.sin(d_prev)
    h2 = r[nxt] * np.sin(d_next)
    tx = central_difference(x[prev], x, x[nxt], h1, h2)
    tr = central_difference(r[prev] * np.cos(d_prev), r, r[nxt] * np.cos(d_next), h1, h2)
    return np.stack([tx, tr, np.ones_like(tx)], axis=-1)


def _residuals(f: BarrelFollower, u, xP, rhoP, t):
    q, alpha, ell = u
    p, m = f.contact(q, alpha, ell)
    phip = np.arctan2(p[2], p[1])
    er = (0.0 * phip, np.cos(phip), np.sin(phip))
    ep = (0.0 * phip, -np.sin(phip), np.cos(phip))
    T = [t[:, 0] * (i == 0) + t[:, 1] * er[i] + t[:, 2] * ep[i] for i in range(3)]
    tn = np.sqrt(T[0] ** 2 + T[1] ** 2 + T[2] ** 2)
    dot = (m[0] * T[0] + m[1] * T[1] + m[2] * T[2]) / tn
    return np.stack([p[0] - xP, np.hypot(p[1], p[2]) - rhoP, dot]), p


def _start(f: BarrelFollower, xP, rhoP):
    """The seed's start: α = 0, ℓ from the radius, q from the axial position (eq. 14)."""
    k = f.side * f.roller_radius
    c = 0.5 * f.length - xP
    if not f.oscillating:
        return np.stack([xP - 0.5 * f.length - k, 0.0 * xP, rhoP])
    ell = f.pivot_distance - rhoP
    # ℓ sin q + k cos q = c  ⇒  q = asin(c / √(ℓ² + k²)) − atan2(k, ℓ)
    ratio = c / np.hypot(ell, k)
    return np.stack([np.arcsin(np.clip(ratio, -1, 1)) - np.arctan2(k, ell), 0.0 * xP, ell])


def solve_cylindrical(f: BarrelFollower, points: np.ndarray, tangents: np.ndarray, label=None) -> CylinderSolution:
    """Solve every point for (q, α, ℓ) and its cam angle (module docstring).

    ``points`` (n, 3) in the cam frame, ``tangents`` (n, 3) from :func:`flank_tangents`.
    Raises :class:`GeometryError` naming the first point the follower cannot
    touch, as ``label(index)`` (default "point <index + 1>").
    """
    P = np.asarray(points, dtype=float)
    xP, rhoP = P[:, 0], np.hypot(P[:, 1], P[:, 2])
    u = _start(f, xP, rhoP)
    steps = np.array([1e-7, 1e-7, 1e-6])
    for _ in range(MAX_NEWTON):
        res, _ = _residuals(f, u, xP, rhoP, tangents)
        if np.all(np.abs(res) < RESIDUAL_TOL):
            break
        J = np.empty((P.shape[0], 3, 3))
        for j in range(3):
            du = np.zeros((3, 1))
            du[j] = steps[j]
            rp, _ = _residuals(f, u + du, xP, rhoP, tangents)
            rm, _ = _residuals(f, u - du, xP, rhoP, tangents)
            J[:, :, j] = ((rp - rm) / (2 * steps[j])).T
        with np.errstate(all="ignore"):
            delta = np.linalg.solve(J, -res.T[:, :, None])[:, :, 0].T
        delta[1] = np.clip(delta[1], -0.3, 0.3)
        u = u + np.where(np.isfinite(delta), delta, 0.0)
    res, p = _residuals(f, u, xP, rhoP, tangents)
    q, alpha, ell = u
    R = f.axis(q, ell)[2]
    bad = (R < f.inner_radius - f.roller_radius) | (R > f.outer_radius + f.roller_radius)
    bad |= ~np.all(np.isfinite(res), axis=0) | np.any(np.abs(res) > 1e-6, axis=0) | (np.abs(alpha) >= 0.5 * math.pi * 0.95)
    if f.oscillating:
        bad |= (ell <= 0) | (np.abs(q) >= 0.5 * math.pi)
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        name = label(i) if label is not None else f"point {i + 1}"
        raise GeometryError(
            f"{name} ({P[i, 0]:.4f}, {P[i, 1]:.4f}, {P[i, 2]:.4f}) cannot be touched by this follower on flank "
            f"{f.flank} (no follower position puts the roller there); check the follower, cam and flank"
        )
    theta = np.mod(f.sigma * (np.arctan2(p[2], p[1]) - np.arctan2(P[:, 2], P[:, 1])), 2 * math.pi)
    slope = tangents[:, 0] / tangents[:, 2]
    return CylinderSolution(cam_angle=theta, q=q, dq=f.velocity(q, alpha, ell), alpha=alpha, ell=ell, slope=slope)
