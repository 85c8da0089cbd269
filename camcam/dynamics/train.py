"""The follower train the dynamics stage is given: masses, spring, damper, loads, materials (``[dynamics]``).

Units are SI at this edge, as the key names say (``mass_kg``, ``preload_n``,
``spring_rate_n_per_mm``, ``damping_n_s_per_m``); lengths stay mm as
everywhere in camcam.  :mod:`camcam.spec.dynamics` reads and validates the
table; :func:`camcam.dynamics.forces.analyse_dynamics` takes the value.

Material presets: Young's modulus and Poisson's ratio from R. L. Norton,
*Machine Design: An Integrated Approach*, Appendix C, Table C-1 ("Physical
properties of some engineering materials"), quoted in GPa; the polymer row
(nylon 6/6) from Beer, Johnston, DeWolf, Mazurek, *Mechanics of Materials*,
Appendix B.  Typical values: a specific alloy or heat treatment may differ by a
few per cent; give ``{ e_gpa = …, poisson = … }`` for your own.

Examples
--------
>>> m = MATERIALS["steel"]
>>> m.e_gpa, m.poisson
(206.8, 0.28)
>>> round(contact_modulus_mpa(m, m), 1)   # E* = 1 / ((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂)
112196.2
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Material", "MATERIALS", "MATERIAL_SOURCE", "DynamicsSpec", "contact_modulus_mpa", "DEFAULT_OVERSPEED",
           "DEFAULT_SPEED_FLUCTUATION"]

#: Where the presets' figures come from (the report prints it beside the stress).
MATERIAL_SOURCE = ("Norton, Machine Design, App. C Table C-1 (metals); Beer et al., Mechanics of Materials, "
                   "App. B (nylon 6/6)")

#: The speed margin the spring is sized to and the jump speed is held to, × rpm.
DEFAULT_OVERSPEED = 1.25

#: Default coefficient of speed fluctuation (ω_max − ω_min)/ω_mean the flywheel is sized for (Norton, Design of
#: Machinery, Table 11-3 gives 0.03–0.05 for machine tools and general machinery).
DEFAULT_SPEED_FLUCTUATION = 0.05


@dataclass(frozen=True)
class Material:
    """An elastic material: Young's modulus (GPa) and Poisson's ratio; ``name`` the preset or "custom"."""

    name: str
    e_gpa: float
    poisson: float

    def describe(self) -> str:
        return f"{self.name} (E {self.e_gpa:g} GPa, ν {self.poisson:g})"


#: Named presets (module notes for the source).
MATERIALS = {
    "steel": Material("steel", 206.8, 0.28),
    "stainless-steel": Material("stainless-steel", 189.6, 0.28),
    "cast-iron": Material("cast-iron", 103.4, 0.26),  # gray cast iron
    "ductile-iron": Material("ductile-iron", 168.9, 0.28),
    "bronze": Material("bronze", 110.3, 0.33),
    "aluminum": Material("aluminum", 71.7, 0.34),
    "titanium": Material("titanium", 113.8, 0.34),
    "nylon": Material("nylon", 2.76, 0.4),
}


def contact_modulus_mpa(a: Material, b: Material) -> float:
    """E* = 1/((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂) in MPa: Johnson's contact modulus (Norton's 1/(m₁ + m₂))."""
    return 1.0 / ((1.0 - a.poisson**2) / (a.e_gpa * 1e3) + (1.0 - b.poisson**2) / (b.e_gpa * 1e3))


@dataclass(frozen=True, kw_only=True)
class DynamicsSpec:
    """The follower train (``[dynamics]``).

    A translating follower has ``mass_kg``, an oscillating one ``inertia_kgm2`` about its pivot.  The spring,
    damper and external load act along the follower's axis (translating) or perpendicular to the arm at
    ``load_arm_mm`` from the pivot (oscillating), where the spring's deflection is the arc ``load_arm_mm·ψ``.
    The spring force is ``preload_n + spring_rate_n_per_mm · lift`` (lift 0: the follower on the base circle);
    ``size_spring`` asks for the least spring instead (:mod:`camcam.dynamics.spring`).  A grooved cam (face
    groove, barrel) drives the follower both ways and has no spring (rate and preload 0).

    ``external_load_n`` pushes the follower towards the cam (against the lift) when positive; a table
    ``external_load_table`` of (cam angle °, N) rows, linear between them and periodic, replaces it.
    ``friction`` is the coefficient at a translating follower's guide (the lateral force F_n·|sin φ| makes a
    friction force against the motion).
    """

    mass_kg: float | None = None
    inertia_kgm2: float | None = None
    spring_rate_n_per_mm: float = 0.0
    preload_n: float = 0.0
    size_spring: bool = False
    damping_ratio: float | None = None
    damping_n_s_per_m: float | None = None
    external_load_n: float = 0.0
    external_load_table: tuple[tuple[float, float], ...] | None = None
    friction: float = 0.0
    roller_width_mm: float | None = None
    cam_material: Material = MATERIALS["steel"]
    follower_material: Material = MATERIALS["steel"]
    allowable_contact_stress_mpa: float | None = None
    min_contact_force_n: float = 0.0
    overspeed: float = DEFAULT_OVERSPEED
    speed_fluctuation: float = DEFAULT_SPEED_FLUCTUATION
    load_arm_mm: float | None = None

    def with_spring(self, rate_n_per_mm: float, preload_n: float) -> "DynamicsSpec":
        """The same train with this spring (the sized one, or a test's)."""
        from dataclasses import replace

        return replace(self, spring_rate_n_per_mm=float(rate_n_per_mm), preload_n=float(preload_n), size_spring=False)
