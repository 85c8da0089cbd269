"""The oscillating roller follower: a roller at the end of an arm that swings about a pivot.

On a barrel cam it is seed 002's follower (:mod:`camcam.geometry.cylindrical`): the arm pivots
about an axis parallel to Y at (length/2, 0, d), the roller axis along the arm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.followers import closedform
from camcam.geometry.followers.base import Element, FollowerKind, reject
from camcam.geometry.jet import Jet

__all__ = ["OscillatingRoller", "BarrelOscillatingRoller"]


@dataclass(frozen=True)
class BarrelOscillatingRoller:
    """Seed 002's follower: pivot distance d, roller radius r_r; ``arm_length`` r names the
    cross-section of the paper's eqs. 10–12 (radius d − r); default: mid-depth of the groove."""

    roller_radius: float
    pivot_distance: float
    arm_length: float | None = None
    kind = "oscillating-roller"
    unit = "deg"
    roller_axis_tilts = True  # the roller axis tilts with the arm: only a 5-axis tool follows it
    plus_side = 0  # the flank whose contact is C + r_r·m

    def check_barrel(self, radius: float, groove_depth: float) -> None:
        """The pivot outside the cylinder, the arm's cross-section (if given) inside the groove."""
        R, h = radius, groove_depth
        if not self.pivot_distance > R:
            raise GeometryError(f"follower.pivot_distance {self.pivot_distance:g} mm must exceed the cylinder radius {R:g} mm")
        if self.arm_length is not None and not self.pivot_distance - R <= self.arm_length <= self.pivot_distance - R + h:
            raise GeometryError(
                f"follower.arm_length {self.arm_length:g} mm must reach into the groove: between "
                f"{self.pivot_distance - R:g} and {self.pivot_distance - R + h:g} mm (pivot_distance − radius)"
            )

    def reference_radius(self, radius: float, groove_depth: float) -> float | None:
        """Radius of seed 002's cross-section (d − r), or None (the cam takes mid-depth)."""
        if self.arm_length is not None:
            return self.pivot_distance - self.arm_length
        return None

    def axis_point(self, s: Jet, K: int, rho, length: float, one: Jet):
        """Roller-axis point C at radius ρ, motion direction n, speed v along n, distance R of C from the axis."""
        d = self.pivot_distance
        ell = d - rho
        th = s.truncate(K)
        c, sn = th.cos(), th.sin()
        C = (0.5 * length - sn * ell, one * 0.0, d - c * ell)
        return C, (-c, one * 0.0, sn), s.derivative() * ell, d - c * ell


@dataclass(frozen=True)
class OscillatingRoller(FollowerKind):
    """Roller at the end of an arm of ``arm_length`` pivoting at (``pivot_distance``, 0)."""

    roller_radius: float
    pivot_distance: float
    arm_length: float
    kind = "oscillating-roller"
    unit = "deg"
    is_roller = True
    lift_order_extra = 0
    spec_keys = ("roller_radius", "pivot_distance", "arm_length")
    barrel_optional_keys = ("arm_length",)
    default_max_pressure_angle_deg = 35.0
    barrel = BarrelOscillatingRoller
    barrel_axes = (5, 4)
    size_axes = ("base_radius", "pivot_distance", "arm_length", "roller_radius")

    @classmethod
    def from_spec(cls, f) -> "OscillatingRoller":
        return cls(f.roller_radius, f.pivot_distance, f.arm_length)

    @classmethod
    def barrel_from_spec(cls, f) -> BarrelOscillatingRoller:
        return BarrelOscillatingRoller(f.roller_radius, f.pivot_distance, f.arm_length)

    @classmethod
    def from_params(cls, params: dict[str, float]) -> "OscillatingRoller":
        return cls(params["roller_radius"], params["pivot_distance"], params["arm_length"])

    @staticmethod
    def size_figures(ps, sigma: int, params: dict, contact=None) -> dict:
        return OscillatingRoller.figures(ps, sigma, params["base_radius"], params["pivot_distance"], params["arm_length"],
                                         params["roller_radius"], contact)

    @staticmethod
    def figures(ps, sigma: int, base_radius, pivot_distance, arm_length, roller_radius, contact=None) -> dict:
        """Figures of oscillating-roller designs; the program's samples are the swing in radians; ``contact``:
        the sweep's dynamics (:class:`camcam.sizing.contact.SweepDynamics`), which adds ``max_contact_stress_mpa``."""
        rb, a, L, rr = (np.asarray(v, float) for v in (base_radius, pivot_distance, arm_length, roller_radius))
        rp = rb + rr
        valid = (np.abs(a - L) < rp) & (rp < a + L)
        x0 = (a * a + rp * rp - L * L) / (2 * a)
        y0 = np.sqrt(np.where(valid, rp * rp - x0 * x0, 1.0))
        beta0 = np.arctan2(y0, x0 - a)
        cb0, sb0 = np.cos(beta0)[:, None], np.sin(beta0)[:, None]
        cp, sp = np.cos(ps.s), np.sin(ps.s)
        cb = cb0 * cp + sb0 * sp  # β = β₀ − ψ
        sb = sb0 * cp - cb0 * sp
        L2 = L[:, None]
        b1, b2 = -ps.s1, -ps.s2
        px, py = a[:, None] + L2 * cb, L2 * sb
        p1x, p1y = -L2 * sb * b1, L2 * cb * b1
        p2x = L2 * (-sb * b2 - cb * b1 * b1)
        p2y = L2 * (cb * b2 - sb * b1 * b1)
        tx, ty = p1x + sigma * py, p1y - sigma * px
        t1x, t1y = p2x + sigma * p1y, p2y - sigma * p1x
        T2 = tx * tx + ty * ty
        kc = (T2 - sigma * (tx * t1y - ty * t1x)) / (T2 * np.sqrt(T2))
        # tan φ = (T·u)/(σ T×u), u = (sin β, −cos β); the denominator stays > 0 on a working cam
        ratio = (tx * sb - ty * cb) / (sigma * (-tx * cb - ty * sb))
        outer = np.sqrt(px * px + py * py).max(axis=1) - rr
        out = closedform.roller_figures(kc, ratio, rr, ps, outer, valid)
        if contact is not None:  # the outward normal n = σJT/|T| against u: cos φ = n·u, sin φ = n×u
            T = np.sqrt(T2)
            out["max_contact_stress_mpa"] = closedform.blank(contact.max_stress(
                ps, cos_phi=sigma * (-tx * cb - ty * sb) / T, sin_phi=sigma * (ty * cb - tx * sb) / T,
                relative_radius_mm=rr[:, None] * (1.0 - rr[:, None] * kc), roller=True, arm_length_mm=L), valid)
        return out

    def start_angle(self, base_radius: float) -> float:
        """Arm angle β₀ (from +X, about the pivot) at lift 0."""
        a, L, rp = self.pivot_distance, self.arm_length, base_radius + self.roller_radius
        if not abs(a - L) < rp < a + L:
            raise GeometryError(
                f"follower: an arm of {L:g} mm pivoting {a:g} mm from the cam centre cannot put the roller "
                f"on the base pitch circle of radius {rp:g} mm (needs |pivot_distance − arm_length| < {rp:g} < pivot_distance + arm_length)"
            )
        x0 = (a * a + rp * rp - L * L) / (2 * a)
        y0 = math.sqrt(rp * rp - x0 * x0)
        return math.atan2(y0, x0 - a)

    def check(self, base_radius: float) -> None:
        self.start_angle(base_radius)

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        beta = self.start_angle(base_radius) - s
        c, sn = beta.cos(), beta.sin()
        L = self.arm_length
        return Element(c * L + self.pivot_distance, sn * L, sn, -c)

    def invert(self, P, n, base_radius, sg):
        # the roller centre C on both the circle |C| = ρ and the arm's circle about the pivot (upper intersection)
        C = P + self.roller_radius * n
        rho, gamma = np.hypot(C[:, 0], C[:, 1]), np.arctan2(C[:, 1], C[:, 0])
        a, L = self.pivot_distance, self.arm_length
        x = (a * a + rho**2 - L * L) / (2 * a)
        reject(
            (rho <= abs(a - L)) | (rho >= a + L), P,
            f"the arm of {L:g} mm pivoting {a:g} mm from the cam centre cannot reach its roller centre",
        )
        y = np.sqrt(np.maximum(rho**2 - x**2, 0.0))
        beta = np.arctan2(y, x - a)
        lift = self.start_angle(base_radius) - beta
        theta = sg * (np.arctan2(y, x) - gamma)
        return theta, lift

    @classmethod
    def datum_note(cls, offset: float) -> str:
        return "the follower arm pivots on the +X axis"
