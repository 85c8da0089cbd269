"""The translating flat-faced follower: a face perpendicular to +Y on a stem (disc cams only)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.geometry.followers import closedform
from camcam.geometry.followers.base import Element, FollowerKind
from camcam.geometry.jet import Jet

__all__ = ["TranslatingFlat"]


@dataclass(frozen=True)
class TranslatingFlat(FollowerKind):
    """Flat face perpendicular to +Y on a stem at x = ``offset``."""

    offset: float = 0.0
    roller_radius = 0.0
    kind = "translating-flat"
    unit = "mm"
    is_roller = False
    lift_order_extra = 1
    spec_keys = ("offset",)
    default_max_pressure_angle_deg = 30.0
    size_axes = ("base_radius",)

    @classmethod
    def from_spec(cls, f) -> "TranslatingFlat":
        return cls(f.offset)

    @classmethod
    def from_params(cls, params: dict[str, float]) -> "TranslatingFlat":
        return cls(0.0)  # the offset moves the contact along the face, not the profile

    @staticmethod
    def size_figures(ps, sigma: int, params: dict, contact=None) -> dict:
        return TranslatingFlat.figures(ps, sigma, params["base_radius"], contact)

    @staticmethod
    def figures(ps, sigma: int, base_radius, contact=None) -> dict:
        """Figures of translating flat-faced designs: ρ = R_b + s + s″, no pressure angle, no concave part;
        ``contact``: the sweep's dynamics (:class:`camcam.sizing.contact.SweepDynamics`), which adds
        ``max_contact_stress_mpa`` (flat on a curve: R′ = ρ)."""
        rb = np.asarray(base_radius, float)
        n = rb.size
        rho_prog = ps.s + ps.s2
        rho = rb + rho_prog.min()
        d_rho = closedform.grid_bound(rho_prog[None, :], ps.inner)[0]
        r = np.sqrt(ps.s1[None, :] ** 2 + (rb[:, None] + ps.s) ** 2)
        valid = np.ones(n, bool)
        out = {
            "valid": valid,
            "max_pressure_angle_deg": np.zeros(n),
            "min_curvature_radius_mm": rho,
            "min_concave_radius_mm": np.full(n, math.inf),
            "undercut": rho <= 0,
            "outer_radius_mm": r.max(axis=1),
            "pressure_angle_bound_deg": np.zeros(n),
            "curvature_radius_bound_mm": np.full(n, d_rho),
        }
        if contact is not None:
            one = np.ones((n, ps.theta.size))
            out["max_contact_stress_mpa"] = contact.max_stress(ps, cos_phi=one, sin_phi=0.0 * one,
                                                               relative_radius_mm=rb[:, None] + rho_prog, roller=False)
        return out

    def check(self, base_radius: float) -> None:
        return None

    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        # envelope: the profile tangent Q' − σJQ has no Y part ⇒ x_Q = σ s′
        ds = s.derivative()
        s0 = s.truncate(ds.K)
        xq = ds * sigma
        one = Jet.constant(1.0, s.d.shape[1], ds.K)
        return Element(xq, s0 + base_radius, nx=one * 0.0, ny=one, along=xq - self.offset)

    def invert(self, P, n, base_radius, sg):
        # the face normal is +Y: θ = σ(π/2 − ∠n), s = P·n − R_b (the support function)
        nu = np.arctan2(n[:, 1], n[:, 0])
        p = np.einsum("ij,ij->i", P, n)
        theta = sg * (0.5 * math.pi - nu)
        lift = p - base_radius
        return theta, lift

    @classmethod
    def datum_note(cls, offset: float) -> str:
        return f"the follower rides on the line X{offset:g}, moving along +Y"
