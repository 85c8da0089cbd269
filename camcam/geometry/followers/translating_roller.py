"""The translating roller follower: a roller on a stem moving along +Y (disc), or along the cam axis (barrel)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.followers import closedform
from camcam.geometry.followers.base import Element, FollowerKind, reject
from camcam.geometry.jet import Jet

__all__ = ["TranslatingRoller", "BarrelTranslatingRoller"]


@dataclass(frozen=True)
class BarrelTranslatingRoller:
    """A barrel cam's translating roller: roller axis along Z at x = length/2 + s(θ)."""

    roller_radius: float
    kind = "translating-roller"
    unit = "mm"
    pivot_distance = None  # no pivot (reverse design, design checks)
    roller_axis_tilts = False  # the roller axis stays radial: a radial tool follows it (4 axes)
    plus_side = 1  # the flank whose contact is C + r_r·m

    def check_barrel(self, radius: float, groove_depth: float) -> None:
        """Nothing to check: the roller's axis is radial at any radius."""

    def reference_radius(self, radius: float, groove_depth: float) -> float | None:
        """No cross-section of its own (the cam takes mid-depth)."""
        return None

    def axis_point(self, s: Jet, K: int, rho, length: float, one: Jet):
        """Roller-axis point C at radius ρ, motion direction n, speed v along n, distance R of C from the axis."""
        C = (s.truncate(K) + 0.5 * length, one * 0.0, one * rho)
        return C, (one, one * 0.0, one * 0.0), s.derivative(), one * rho


@dataclass(frozen=True)
class TranslatingRoller(FollowerKind):
    """Roller of radius ``roller_radius`` on a stem along +Y at x = ``offset``."""

    roller_radius: float
    offset: float = 0.0
    kind = "translating-roller"
    unit = "mm"
    is_roller = True
    lift_order_extra = 0
    spec_keys = ("roller_radius", "offset")
    default_max_pressure_angle_deg = 30.0
    barrel = BarrelTranslatingRoller
    barrel_axes = (4,)
    size_axes = ("base_radius", "offset", "roller_radius")

    @classmethod
    def from_spec(cls, f) -> "TranslatingRoller":
        return cls(f.roller_radius, f.offset)

    @classmethod
    def barrel_from_spec(cls, f) -> BarrelTranslatingRoller:
        return BarrelTranslatingRoller(f.roller_radius)

    @classmethod
    def from_params(cls, params: dict[str, float]) -> "TranslatingRoller":
        return cls(params["roller_radius"], params["offset"])

    @staticmethod
    def size_figures(ps, sigma: int, params: dict, contact=None) -> dict:
        return TranslatingRoller.figures(ps, sigma, params["base_radius"], params["offset"], params["roller_radius"],
                                         contact)

    @staticmethod
    def figures(ps, sigma: int, base_radius, offset, roller_radius, contact=None) -> dict:
        """Figures of translating-roller designs (arrays of equal length); ``contact``: the sweep's dynamics
        (:class:`camcam.sizing.contact.SweepDynamics`), which adds ``max_contact_stress_mpa``."""
        rb, e, rr = (np.asarray(a, float) for a in (base_radius, offset, roller_radius))
        rp = rb + rr
        valid = np.abs(e) < rp
        y0 = np.sqrt(np.where(valid, rp * rp - e * e, 1.0))
        valid &= (y0 + ps.lift_min) > 0
        Y = y0[:, None] + ps.s
        q = ps.s1 - sigma * e[:, None]
        T2 = Y * Y + q * q
        kc = (T2 + ps.s1 * q - Y * ps.s2) / (T2 * np.sqrt(T2))
        outer = np.sqrt(e * e + (y0 + ps.lift_max) ** 2) - rr
        out = closedform.roller_figures(kc, q / Y, rr, ps, outer, valid)
        if contact is not None:  # cos φ = Y/|T|, sin φ = −σq/|T| (the contact normal against the stem's +Y)
            T = np.sqrt(T2)
            out["max_contact_stress_mpa"] = closedform.blank(contact.max_stress(
                ps, cos_phi=Y / T, sin_phi=-sigma * q / T, relative_radius_mm=rr[:, None] * (1.0 - rr[:, None] * kc),
                roller=True), valid)
        return out

    def check(self, base_radius: float) -> None:
        rp = base_radius + self.roller_radius
        if abs(self.offset) >= rp:
            raise GeometryError(f"follower.offset {self.offset:g} mm must be smaller than the base pitch radius {rp:g} mm")

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        rp = base_radius + self.roller_radius
        y0 = math.sqrt(rp * rp - self.offset**2)
        one = Jet.constant(1.0, s.d.shape[1], s.K)
        return Element(one * self.offset, s + y0, one * 0.0, one)

    def invert(self, P, n, base_radius, sg):
        # the roller centre C = P + r_r n on the stem x = e above the cam
        C = P + self.roller_radius * n
        rho, gamma = np.hypot(C[:, 0], C[:, 1]), np.arctan2(C[:, 1], C[:, 0])
        e = self.offset
        reject(rho <= abs(e), P, f"its roller centre is {rho.min():.4f} mm from the cam centre, inside the offset {e:g} mm")
        y = np.sqrt(rho**2 - e**2)
        theta = sg * (np.arctan2(y, e) - gamma)
        lift = y - math.sqrt((base_radius + self.roller_radius) ** 2 - e**2)
        return theta, lift

    @classmethod
    def datum_note(cls, offset: float) -> str:
        return f"the follower rides on the line X{offset:g}, moving along +Y"
