"""The oscillating flat-faced follower: a face whose line passes through the pivot (disc cams only)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.followers.base import Element, FollowerKind, reject
from camcam.geometry.jet import Jet

__all__ = ["OscillatingFlat"]


@dataclass(frozen=True)
class OscillatingFlat(FollowerKind):
    """Flat face whose line passes through the pivot at (``pivot_distance``, 0).

    At lift 0 the face is tangent to the base circle; a lift turns it clockwise
    about the pivot (β = β₀ − ψ), away from the cam.  With the face through the
    pivot, the contact point moves along the face normal, so the pressure angle
    is zero throughout.
    """

    pivot_distance: float
    roller_radius = 0.0
    kind = "oscillating-flat"
    unit = "deg"
    is_roller = False
    lift_order_extra = 1
    spec_keys = ("pivot_distance",)
    default_max_pressure_angle_deg = 35.0

    @classmethod
    def from_spec(cls, f) -> "OscillatingFlat":
        return cls(f.pivot_distance)

    def start_angle(self, base_radius: float) -> float:
        a = self.pivot_distance
        if not a > base_radius:
            raise GeometryError(f"follower.pivot_distance {a:g} mm must exceed the base radius {base_radius:g} mm")
        return math.pi - math.asin(base_radius / a)

    def check(self, base_radius: float) -> None:
        self.start_angle(base_radius)

    def check_cam(self, cam) -> None:
        """The face keeps its contact on the pivot's side: ℓ > 0 and 1 + σψ′ > 0 all round."""
        t = np.linspace(0.0, 2 * math.pi, 3601)
        s1 = cam.lift(t, 1).d[1] * cam.sigma
        ell = cam.element(t, 0).along.value
        bad = np.flatnonzero((1.0 + s1 <= 0) | (ell <= 0))
        if bad.size:
            raise GeometryError(
                f"follower: the flat face loses contact at cam angle {math.degrees(t[bad[0]]):.2f}° "
                "(the contact point passes the pivot); use a larger pivot_distance or a slower swing"
            )

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        # contact Q = O + ℓ e_β; the envelope condition gives ℓ (σβ′ − 1) = a cos β, β′ = −ψ′
        a = self.pivot_distance
        ds = s.derivative()
        beta = (self.start_angle(base_radius) - s).truncate(ds.K)
        c, sn = beta.cos(), beta.sin()
        ell = -(c * a) / (ds * sigma + 1.0)
        return Element(c * ell + a, sn * ell, nx=sn, ny=-c, along=ell)

    def invert(self, P, n, base_radius, sg):
        # p = P·n the face's distance from the cam centre, sin β = p/a, β = π − asin(p/a) (the forward branch)
        nu = np.arctan2(n[:, 1], n[:, 0])
        p = np.einsum("ij,ij->i", P, n)
        a = self.pivot_distance
        reject(p >= a, P, f"its tangent lies {p.max():.4f} mm from the cam centre, beyond the pivot at {a:g} mm")
        beta = math.pi - np.arcsin(p / a)
        lift = self.start_angle(base_radius) - beta
        theta = sg * (beta - 0.5 * math.pi - nu)
        return theta, lift

    @classmethod
    def datum_note(cls, offset: float) -> str:
        return "the follower arm pivots on the +X axis"
