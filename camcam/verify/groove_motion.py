"""Posed cylinders and how they move: the section of a cylinder on r = ρ, the program's tool and the roller.

A cylinder (radius r, length L from its tip) posed at (X, Y, Z, a, B) in the
barrel-cam machine frame (:mod:`camcam.verify.groove3d` gives the frame and the
closed form) cuts the cylinder r = ρ of the part in an x-interval at each
part angle γ (:func:`section_interval`).  A :class:`Motion` is a continuous
family of such poses: the program's tool moving linearly between its printed
poses (:class:`ProgramMotion`), or the follower's roller at every program
angle (:class:`RollerMotion`, exact).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod

import numpy as np

from camcam.geometry.cylindrical import CylindricalCam
from camcam.toolpath.poses import A_AXIS_SENSE, CylinderTool, ToolPoses

__all__ = ["section_interval", "sincos_sum", "wall_extents", "side_extent", "Motion", "ProgramMotion", "RollerMotion",
           "follower_poses"]


def section_interval(X, Y, Z, a, B, r, L, rho, gamma, sincos_B=None, sincos_beta=None):
    """x-interval (lo, hi) of a posed cylinder on r = ρ at part angle γ; NaN where it misses.

    ``sincos_B`` is (sin B, cos B) when the caller has them (an envelope reuses
    a sample's for each of its angles); ``B`` is then not used (None will do).
    ``sincos_beta`` is (sin β, cos β) of β = γ + a when the caller has them (an
    envelope on a regular grid makes them from its angles' and its samples'
    sines and cosines by the angle-addition formulas, :func:`sincos_sum`);
    ``gamma`` and ``a`` are then not used (None will do).  The arithmetic is
    done in place: at tens of thousands of (pose, angle) pairs a call, fresh
    temporaries cost more than the arithmetic; sin and cos are most of the rest.
    """
    shape = np.broadcast_shapes(np.shape(gamma), np.shape(a), np.shape(X), np.shape(Y), np.shape(Z), np.shape(B),
                                *(np.shape(x) for x in (sincos_B or ()) + (sincos_beta or ())))
    sb, cb = (np.sin(B), np.cos(B)) if sincos_B is None else sincos_B
    if sincos_beta is None:
        beta = np.add(gamma, a, out=np.empty(shape))  # every result below is an array of this shape (0-d too)
        eta = np.sin(beta, out=np.empty(shape))
        zeta = np.cos(beta, out=beta)
    else:
        eta = np.array(np.broadcast_to(sincos_beta[0], shape), float)
        zeta = np.array(np.broadcast_to(sincos_beta[1], shape), float)
    eta *= rho
    eta += Y
    zeta *= rho
    zeta -= Z
    q2 = np.multiply(eta, eta, out=eta)
    np.subtract(r * r, q2, out=q2)
    q = np.maximum(q2, 0.0, out=np.empty(shape))
    np.sqrt(q, out=q)
    lo = np.multiply(zeta, sb, out=np.empty(shape))
    hi = np.add(lo, q, out=np.empty(shape))
    lo -= q
    lo /= cb
    hi /= cb
    tilted = np.abs(sb) > 1e-15
    every, some = bool(tilted.all()), bool(tilted.any())  # a 5-axis envelope's poses are all tilted, a 4-axis's none
    if some:
        # the tip plane (axial position 0) and the end (L) bound a tilted cylinder's section
        safe = sb if every else np.where(tilted, sb, 1.0)
        e0 = np.negative(zeta, out=np.empty(shape))
        e0 *= cb
        e0 /= safe
        e1 = np.multiply(zeta, cb, out=np.empty(shape))
        np.subtract(L, e1, out=e1)
        e1 /= safe
        up = sb > 0
        alo = np.where(up, e0, e1)
        ahi = np.where(up, e1, e0)
        np.maximum(lo, alo, out=alo)
        np.minimum(hi, ahi, out=ahi)
        lo = alo if every else np.where(tilted, alo, lo)
        hi = ahi if every else np.where(tilted, ahi, hi)
    miss = np.less(q2, 0, out=np.empty(shape, bool))  # the negation of the old q2 >= 0 & ...: NaN-free here
    miss |= lo > hi
    if not every:  # an untilted cylinder's section lies between its tip plane and its end
        miss |= ~(tilted | ((zeta >= 0) & (zeta <= L)))
    lo += X
    hi += X
    lo[miss] = np.nan
    hi[miss] = np.nan
    return lo, hi


def sincos_sum(s1, c1, s2, c2):
    """(sin(x + y), cos(x + y)) from sin and cos of x (``s1``, ``c1``) and of y (``s2``, ``c2``), arrays.

    The angle-addition formulas: four products and two sums instead of a sine and a cosine.  They differ
    from ``np.sin(x + y)`` by a few units in the last place (the sum x + y is not rounded first).

    Examples
    --------
    >>> x, y = np.array([0.3, 2.0]), np.array([1.1, -4.0])
    >>> s, c = sincos_sum(np.sin(x), np.cos(x), np.sin(y), np.cos(y))
    >>> bool(np.abs(s - np.sin(x + y)).max() < 1e-15), bool(np.abs(c - np.cos(x + y)).max() < 1e-15)
    (True, True)
    """
    s = np.multiply(s1, c2)
    s += c1 * s2
    c = np.multiply(c1, c2)
    c -= s1 * s2
    return s, c


def wall_extents(lo, hi):
    """Both walls' extents from a section's (lo, hi): (−lo, hi), both maximised; −inf where it misses.

    Computed in ``lo`` and ``hi`` themselves (a section's interval misses on both ends at once)."""
    miss = np.isnan(lo)
    side0 = np.negative(lo, out=lo)
    side0[miss] = -np.inf
    hi[miss] = -np.inf
    return side0, hi


def side_extent(X, Y, Z, a, B, r, L, rho, gamma, side):
    """The wall-side extent: hi for side 1, −lo for side 0 (both maximised); −inf where it misses.

    ``side`` is 0 or 1, or an array of them (one per pose and angle)."""
    side0, side1 = wall_extents(*section_interval(X, Y, Z, a, B, r, L, rho, gamma))
    return np.where(np.asarray(side) == 1, side1, side0)


class Motion(ABC):
    """A continuous motion p ↦ pose (X, Y, Z, a, B) of a cylinder (r, L)."""

    r: float
    L: float
    periodic: bool
    p_lo: float
    p_hi: float

    @abstractmethod
    def pose(self, p):
        """The cylinder's pose (X, Y, Z, a, B) at motion parameter ``p``."""

    @abstractmethod
    def samples(self, pose_step_mm: float, rho_max: float) -> np.ndarray:
        """Motion parameters no farther apart than ``pose_step_mm`` at radius ``rho_max``."""

    def clamp(self, p):
        return p if self.periodic else np.clip(p, self.p_lo, self.p_hi)


class ProgramMotion(Motion):
    periodic = False

    def __init__(self, poses: ToolPoses, tool: CylinderTool):
        self.r, self.L = tool.radius_mm, tool.length_mm
        s = A_AXIS_SENSE[poses.a_axis]
        self.q = np.column_stack([poses.tip_mm, s * np.radians(poses.a_deg), np.radians(poses.b_deg)])
        self.p_lo, self.p_hi = 0.0, float(len(self.q) - 1)

    def pose(self, p):
        p = np.asarray(p, float)
        k = np.clip(np.floor(p).astype(int), 0, len(self.q) - 2)
        t = (p - k)[..., None]
        v = self.q[k] * (1 - t) + self.q[k + 1] * t
        return tuple(v[..., i] for i in range(5))

    def samples(self, pose_step_mm, rho_max):
        d = np.abs(np.diff(self.q, axis=0))
        size = d[:, 0] + d[:, 1] + d[:, 2] + rho_max * d[:, 3] + (self.L + self.r) * d[:, 4]
        m = np.maximum(1, np.ceil(size / pose_step_mm)).astype(int)
        starts = np.repeat(np.arange(len(m)), m)
        frac = np.arange(m.sum()) - np.repeat(np.cumsum(m) - m, m)
        p = starts + frac / np.repeat(m, m)
        return np.append(p, self.p_hi)


class RollerMotion(Motion):
    """The roller at program angle θ = p (radians), exactly."""

    periodic = True

    def __init__(self, cam: CylindricalCam):
        self.cam = cam
        self.r = cam.roller_radius
        f = cam.follower
        self.osc = f.pivot_distance is not None  # an arm about a pivot
        self.d = f.pivot_distance if self.osc else 0.0
        self.L = 2.0 * self.d if self.osc else 2.0 * cam.base_radius
        self.p_lo, self.p_hi = 0.0, 2 * math.pi

    def pose(self, p):
        th = np.asarray(p, float)
        flat = np.mod(th.ravel(), 2 * math.pi)
        s = self.cam.lift(flat, 0).value.reshape(th.shape)
        a = self.cam.sigma * th
        half = 0.5 * self.cam.length
        zero = np.zeros_like(th)
        if not self.osc:
            return half + s, zero, zero, a, zero
        # axis through the pivot (half, 0, d) along (sin θf, 0, cos θf); tip at the pivot's depth d below it
        return half - self.d * np.sin(s), zero, self.d - self.d * np.cos(s), a, s

    def samples(self, pose_step_mm, rho_max):
        n = int(math.ceil(2 * math.pi * (rho_max + self._speed()) / pose_step_mm))
        return np.linspace(0.0, 2 * math.pi, n, endpoint=False)

    def _speed(self) -> float:
        """Largest |dx/dθ| of the roller axis (mm/rad), from a dense view (sets only the sample count)."""
        th = np.linspace(0, 2 * math.pi, 4001)
        v = np.abs(self.cam.lift(th, 1).d[1]).max()
        return float(v * (self.d + self.r if self.osc else 1.0))


def follower_poses(cam: CylindricalCam, theta) -> tuple:
    """The roller's pose (X, Y, Z, a, B) at program angles ``theta`` (rad) in the machine frame (a, B in rad)."""
    return RollerMotion(cam).pose(theta)
