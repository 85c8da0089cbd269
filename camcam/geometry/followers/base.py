"""The four disc-cam followers, placed in the fixed frame.

Fixed frame (DESIGN.md): cam centre at the origin, drawing in the XY plane seen
from +Z.  A translating follower moves along +Y, its axis offset ``offset`` mm
along +X.  An oscillating follower pivots at (``pivot_distance``, 0) on the +X
axis; a lift turns it clockwise about the pivot, away from the cam.  At lift 0
the roller centre sits on the base pitch circle (radius R_b + r_r) above the
X axis, or the flat face is tangent to the base circle above the X axis.

Each follower turns the lift jet ``s`` (mm, or radians for an oscillating
follower) into the jets of its cam-touching element in the fixed frame for a
cam turning in direction σ (+1 counter-clockwise, −1 clockwise):

* roller followers: the roller centre ``P`` and the unit direction ``u`` in
  which it moves for increasing lift (for the pressure angle);
* flat-faced followers: the contact point ``Q`` on the face, the face's unit
  normal pointing away from the cam, and the contact's position along the face
  (from the stem axis or from the pivot), which sizes the face.

The flat-face contact follows from the envelope condition: the cam-frame
profile tangent Q′ − σJQ (J = +90° turn) is parallel to the face.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from camcam.errors import GeometryError
from camcam.geometry.jet import Jet

__all__ = ["TranslatingRoller", "OscillatingRoller", "TranslatingFlat", "OscillatingFlat", "Element", "FOLLOWER_KINDS"]

FOLLOWER_KINDS = ("translating-roller", "oscillating-roller", "translating-flat", "oscillating-flat")


@dataclass(frozen=True)
class Element:
    """Fixed-frame jets of a follower's cam-touching element."""

    x: Jet
    y: Jet
    ux: Jet | None = None  # roller: direction of motion for increasing lift
    uy: Jet | None = None
    nx: Jet | None = None  # flat face: unit normal away from the cam
    ny: Jet | None = None
    along: Jet | None = None  # flat face: contact position along the face, mm


@dataclass(frozen=True)
class TranslatingRoller:
    """Roller of radius ``roller_radius`` on a stem along +Y at x = ``offset``."""

    roller_radius: float
    offset: float = 0.0
    kind = "translating-roller"
    unit = "mm"
    lift_order_extra = 0

    def check(self, base_radius: float) -> None:
        rp = base_radius + self.roller_radius
        if abs(self.offset) >= rp:
            raise GeometryError(f"follower.offset {self.offset:g} mm must be smaller than the base pitch radius {rp:g} mm")

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        rp = base_radius + self.roller_radius
        y0 = math.sqrt(rp * rp - self.offset**2)
        one = Jet.constant(1.0, s.d.shape[1], s.K)
        return Element(one * self.offset, s + y0, one * 0.0, one)


@dataclass(frozen=True)
class OscillatingRoller:
    """Roller at the end of an arm of ``arm_length`` pivoting at (``pivot_distance``, 0)."""

    roller_radius: float
    pivot_distance: float
    arm_length: float
    kind = "oscillating-roller"
    unit = "deg"
    lift_order_extra = 0

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


@dataclass(frozen=True)
class TranslatingFlat:
    """Flat face perpendicular to +Y on a stem at x = ``offset``."""

    offset: float = 0.0
    roller_radius = 0.0
    kind = "translating-flat"
    unit = "mm"
    lift_order_extra = 1

    def check(self, base_radius: float) -> None:
        return None

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        # envelope: the profile tangent Q' − σJQ has no Y part ⇒ x_Q = σ s′
        ds = s.derivative()
        s0 = s.truncate(ds.K)
        xq = ds * sigma
        one = Jet.constant(1.0, s.d.shape[1], ds.K)
        return Element(xq, s0 + base_radius, nx=one * 0.0, ny=one, along=xq - self.offset)


@dataclass(frozen=True)
class OscillatingFlat:
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
    lift_order_extra = 1

    def start_angle(self, base_radius: float) -> float:
        a = self.pivot_distance
        if not a > base_radius:
            raise GeometryError(f"follower.pivot_distance {a:g} mm must exceed the base radius {base_radius:g} mm")
        return math.pi - math.asin(base_radius / a)

    def check(self, base_radius: float) -> None:
        self.start_angle(base_radius)

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        # contact Q = O + ℓ e_β; the envelope condition gives ℓ (σβ′ − 1) = a cos β, β′ = −ψ′
        a = self.pivot_distance
        ds = s.derivative()
        beta = (self.start_angle(base_radius) - s).truncate(ds.K)
        c, sn = beta.cos(), beta.sin()
        ell = -(c * a) / (ds * sigma + 1.0)
        return Element(c * ell + a, sn * ell, nx=sn, ny=-c, along=ell)
