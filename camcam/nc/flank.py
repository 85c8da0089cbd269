"""Flank passes of a translating barrel cam cut with a radial tool smaller than the roller.

Roller and tool are both radial cylinders, so on the cylinder r = ρ, in the
developed plane there (u = ρ·θ, x), each cuts the same convex section
translated along its path: K(r, ρ) = {(ρ·asin(r sin φ / ρ), r cos φ)}.  The
designed wall is the boundary of (roller centre path) ⊕ K(r_r, ρ), the cut
wall that of (tool path) ⊕ K(r_t, ρ); along the wall's outward normal n_ρ
their gap is, to first order in the tool's displacement from the centre path,

    e(ρ) = q·g(ρ) + h(K(r_t, ρ), n_ρ) − h(K(r_r, ρ), n_ρ),

h the support function, q the tool's displacement along the wall normal at
the development radius ρ_d, g(ρ) = (ρ·N_d)/(ρ_d·N_ρ) what that displacement
is along n_ρ (N_ρ = √(ρ² + s′²)).  The error changes with depth because n_ρ
and the section shapes do: one q cannot zero it at every radius.  Each
station's q is the one that minimises the largest |e(ρ)| over the flank
depth (times the 3-D factor √(1 − n_r²), see :mod:`camcam.verify.groove3d`):
all e(ρ) rise with q, so the optimum balances the largest overcut against
the largest material left (bisection).  q(θ) is interpolated per motion
segment by the Chebyshev series through its 49 stations (Chebyshev–Lobatto
points, numpy.polynomial), so the flank curve keeps exact derivatives for the
fit.  The true figure is the 3-D measurement of the printed program.

The series replaced scipy's quintic splines through the same stations (issue 49): on
cylindrical-translating-small-tool, against q balanced at 3000 points a segment, it is within 1e-14 mm
on the cycloidal rise (the splines 5e-9 mm) and 8.8e-7 mm on the modified-sine return, whose jerk jumps
inside the segment (the splines 6.8e-7 mm); its first derivative 4.7e-5 against 3.9e-5 mm/rad there.  A
barrel job with flank passes then imports no scipy (0.26 CPU s: the run, and the children that unpickle
the plan, need numpy alone).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from numpy.polynomial import chebyshev as C

from camcam.geometry.cylindrical import CylindricalCam
from camcam.geometry.jet import Jet
from camcam.toolpath.contours import OffsetCurve

__all__ = ["FlankPlan", "plan_flank", "flank_error_mm", "smallest_tool_radius"]

#: Radii across the flank depth at which a station's error is balanced.
DEPTH_RADII = 21

def _support(r: float, rho: np.ndarray, nu: np.ndarray, nx: np.ndarray) -> np.ndarray:
    """h(K(r, ρ), n) = max over φ of f(φ) = nu·ρ·asin(k sin φ) + nx·r·cos φ, k = r/ρ < 1, from its root.

    f′(φ) = r·(nu·cos φ / √(1 − k² sin²φ) − nx·sin φ) = 0; squared, with S = sin²φ:
    nx²k²·S² − (nu² + nx²)·S + nu² = 0, whose smaller root (the one in [0, 1]) is
    S = 2nu² / (B + √(B² − 4nx²k²nu²)), B = nu² + nx² (written so that it holds as k → 0,
    where K is the circle and S = nu²/B).  K is convex and symmetric in both axes, so the
    maximum has sin φ of nu's sign and cos φ of nx's.  The same figure as a 97-point grid
    refined by golden-section search, to 4e-15 mm on 200 000 random normals
    (``tests/nc/test_flank.py``), 15–70 × faster.
    """
    k = r / rho
    B = nu * nu + nx * nx
    root = np.sqrt(np.maximum(B * B - 4.0 * nx * nx * k * k * nu * nu, 0.0))
    S = 2.0 * nu * nu / np.where(B + root > 0, B + root, 1.0)
    sin_phi = np.copysign(np.sqrt(np.minimum(S, 1.0)), nu)
    cos_phi = np.copysign(np.sqrt(np.maximum(1.0 - sin_phi * sin_phi, 0.0)), nx)
    return nu * rho * np.arcsin(k * sin_phi) + nx * r * cos_phi


def _station_terms(cam: CylindricalCam, theta: np.ndarray, r_t: float, rho_d: float, radii: np.ndarray):
    """g(ρ), b(ρ) = h_t − h_r and the 3-D factor at each (station, radius): arrays (n, m)."""
    s1 = cam.lift(theta, 1).d[1][:, None]  # ds/dθ, mm/rad
    rho = radii[None, :]
    N_r = np.sqrt(rho**2 + s1**2)
    N_d = np.sqrt(rho_d**2 + s1**2)
    g = rho * N_d / (rho_d * N_r)
    # wall 1's outward normal in (u_ρ, x); the section shapes are symmetric, so wall 0 gives the same terms
    nu, nx = -s1 / N_r, rho / N_r
    b = _support(r_t, rho, nu, nx) - _support(cam.roller_radius, rho, nu, nx)
    sin2 = s1**2 / N_r**2
    f3 = np.sqrt(1.0 - (cam.roller_radius * sin2 / rho) ** 2)
    return g, b, f3


def _balance(g: np.ndarray, b: np.ndarray, f3: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per station (row) the q minimising max_ρ |f3·(q·g + b)| and that smallest largest error."""
    lo = np.min(-b / g, axis=1) - 1.0
    hi = np.max(-b / g, axis=1) + 1.0
    for _ in range(60):
        q = 0.5 * (lo + hi)
        e = f3 * (q[:, None] * g + b)
        up = e.max(axis=1) + e.min(axis=1) > 0
        hi, lo = np.where(up, q, hi), np.where(up, lo, q)
    q = 0.5 * (lo + hi)
    e = f3 * (q[:, None] * g + b)
    return q, np.abs(e).max(axis=1)


def _radii(cam: CylindricalCam) -> np.ndarray:
    return np.linspace(cam.bottom_radius, cam.base_radius, DEPTH_RADII)


def _stations(cam: CylindricalCam, per_degree: float = 1.0) -> np.ndarray:
    return np.linspace(0.0, 2 * math.pi, int(360 * per_degree) + 1)


def flank_error_mm(cam: CylindricalCam, tool_radius_mm: float, rho_d: float) -> float:
    """The largest balanced flank error over the revolution for a tool radius (first order, mm)."""
    th = _stations(cam)
    g, b, f3 = _station_terms(cam, th, tool_radius_mm, rho_d, _radii(cam))
    return float(_balance(g, b, f3)[1].max())


def smallest_tool_radius(cam: CylindricalCam, budget_mm: float, rho_d: float) -> float:
    """The smallest tool radius whose balanced flank error stays within ``budget_mm`` (bisection)."""
    lo, hi = cam.roller_radius / 3.0, cam.roller_radius
    if flank_error_mm(cam, lo, rho_d) <= budget_mm:
        return lo
    for _ in range(14):  # to 1e-4 of the roller radius
        mid = 0.5 * (lo + hi)
        if flank_error_mm(cam, mid, rho_d) <= budget_mm:
            hi = mid
        else:
            lo = mid
    return hi


@dataclass(frozen=True)
class FlankPlan:
    """Per-station displacements q(θ) of a flank pass and the error they leave: per motion segment
    [breaks[i], breaks[i + 1]] the Chebyshev coefficients ``series[i]`` of q in u = (θ − mid) / half ∈ [−1, 1]."""

    breaks: np.ndarray
    series: tuple
    error_mm: float

    def q(self, theta: np.ndarray, K: int, piece: int | None) -> Jet:
        theta = np.atleast_1d(np.asarray(theta, float))
        if piece is None:
            idx = np.clip(np.searchsorted(self.breaks, theta, side="right") - 1, 0, len(self.series) - 1)
        else:
            idx = np.full(theta.shape, piece)
        rows = np.zeros((K + 1, theta.size))
        for i in np.unique(idx):
            m = idx == i
            lo, hi = self.breaks[i], self.breaks[i + 1]
            half = 0.5 * (hi - lo)
            u = (theta[m] - 0.5 * (lo + hi)) / half
            c = self.series[i]
            for k in range(K + 1):
                rows[k, m] = C.chebval(u, c) / half**k  # d^k q / dθ^k: the series' k-th derivative in u
                c = C.chebder(c)
        return Jet(rows)


def plan_flank(cam: CylindricalCam, tool_radius_mm: float, rho_d: float, per_segment: int = 49) -> FlankPlan:
    """Balanced displacements q(θ) for a flank pass of a tool of ``tool_radius_mm`` (see the module notes)."""
    br = cam.breaks
    series, worst = [], 0.0
    radii = _radii(cam)
    u = -np.cos(np.linspace(0, math.pi, per_segment))  # Chebyshev–Lobatto points of [−1, 1]
    for lo, hi in zip(br[:-1], br[1:]):
        x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * u
        g, b, f3 = _station_terms(cam, x, tool_radius_mm, rho_d, radii)
        q, err = _balance(g, b, f3)
        series.append(C.chebfit(u, q, per_segment - 1))  # as many terms as stations: it interpolates them
        worst = max(worst, float(err.max()))
    return FlankPlan(np.asarray(br, float), tuple(series), worst)


@dataclass(frozen=True)
class DisplacedCurve(OffsetCurve):
    """``base`` moved along its unit normal by ``distance_mm`` (±1: left or right) × q(θ) of ``plan``."""

    plan: FlankPlan | None = None

    def distance(self, t: np.ndarray, order: int, piece: int | None) -> Jet:
        return self.plan.q(t, order, piece) * self.distance_mm
