"""Dynamics stage: follower force, contact force, camshaft torque, Hertz stress, jump speed and spring sizing.

It takes the geometry stage's built cam (pressure angle, curvature, ds/dθ) and a follower train
(:class:`DynamicsSpec`, the ``[dynamics]`` table) and returns a frozen :class:`Dynamics`.  The public names
load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("DynamicsSpec", "Material", "MATERIALS", "MATERIAL_SOURCE", "contact_modulus_mpa"),
                    "camcam.dynamics.train"),
    **dict.fromkeys(("Dynamics", "analyse_dynamics", "jump_speed"), "camcam.dynamics.cycle"),
    **dict.fromkeys(("forces", "coefficients", "first_root"), "camcam.dynamics.forces"),
    **dict.fromkeys(("size_spring", "SPRING_RULE"), "camcam.dynamics.spring"),
})
