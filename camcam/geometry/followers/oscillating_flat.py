"""The oscillating flat-faced follower: a face whose line passes through the pivot (disc cams only)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.advice import smallest_above_mm
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
        """The face keeps its contact on the pivot's side: ℓ > 0 and 1 + σψ′ > 0 all round.

        ℓ = −a cos β / (1 + σψ′) with β = β₀ − ψ and sin β₀ = R_b/a (:meth:`element`), so where the follower
        swings slower than the cam turns (1 + σψ′ > 0), ℓ > 0 ⇔ β > 90° ⇔ a > R_b / cos ψ: the pivot
        distance the largest swing ψ_max needs, which the error names.  Where it swings as fast as the cam
        turns, no pivot distance keeps the contact, and the error names the motion segment instead (campaign
        case 52:39: a 25° return over 40°, told to use a larger pivot distance).
        """
        t = np.linspace(0.0, 2 * math.pi, 3601)
        s1 = cam.lift(t, 1).d[1] * cam.sigma
        ell = cam.element(t, 0).along.value
        fast = np.flatnonzero(1.0 + s1 <= 0)
        if fast.size:
            at = float(t[fast[0]])
            field, seg = cam.program.spec_field(at)
            lo, hi = seg.law.extreme(1, rest_ends=False)  # the law's exact extremes of dS/dT
            rate = abs(seg.scale) * max(abs(lo.value), abs(hi.value)) / (seg.end_deg - seg.start_deg)
            raise GeometryError(
                f"{field}: the flat face loses contact at cam angle {math.degrees(at):.2f}°, where the follower "
                f"swings as fast as the cam turns (up to {rate:.3g} times as fast in its {seg.law.name} from "
                f"{seg.start_deg:g}° to {seg.end_deg:g}°, rise {seg.scale:g}°); expected a longer segment or a "
                f"smaller rise (no pivot distance keeps the contact)")
        bad = np.flatnonzero(ell <= 0)
        if bad.size:
            psi_max = math.radians(cam.program.extremes(0)[1].value)
            deg = math.degrees(t[bad[0]])
            where = f"the flat face loses contact at cam angle {deg:.2f}° (the contact point passes the pivot)"
            if psi_max >= math.pi / 2:
                field, seg = cam.program.spec_field(float(t[bad[0]]))
                raise GeometryError(f"{field}: {where}: a swing of {math.degrees(psi_max):g}° turns the face past "
                                    f"the pivot at any pivot distance; expected a largest swing under 90°")
            need = cam.base_radius / math.cos(psi_max)  # a > R_b / cos ψ_max
            advised = smallest_above_mm(need)
            raise GeometryError(f"follower.pivot_distance: at {self.pivot_distance:g} mm {where}; the largest "
                                f"swing {math.degrees(psi_max):g}° needs more than R_b / cos ψ = {need:.4g} mm; "
                                f"expected at least {advised:g} mm")

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
