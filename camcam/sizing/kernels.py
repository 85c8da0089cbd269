"""The sizing sweep's closed-form figures: each follower kind's kernel, for a block of designs at once.

Rows are designs, columns cam angles.  The kernels themselves belong to their
kinds (``size_figures`` of each class in :mod:`camcam.geometry.followers`, the
shared forms in :mod:`camcam.geometry.followers.closedform`); this module names
the figures they return and looks the kind up.  They are validated point by
point against :mod:`camcam.geometry.disc` in ``tests/sizing/test_kernels.py``.
"""

from __future__ import annotations

from camcam.geometry.followers import follower_kind
from camcam.sizing.samples import ProgramSamples

__all__ = ["FIGURES", "block_figures"]

#: The figure columns every kernel returns, in table order.
FIGURES = ("valid", "max_pressure_angle_deg", "min_curvature_radius_mm", "min_concave_radius_mm", "undercut",
           "outer_radius_mm", "pressure_angle_bound_deg", "curvature_radius_bound_mm")


def block_figures(kind: str, ps: ProgramSamples, sigma: int, params: dict, contact=None) -> dict:
    """The figures of one block of designs of follower ``kind``; ``params`` maps axis names to arrays;
    ``contact`` (:class:`camcam.sizing.contact.SweepDynamics`) adds ``max_contact_stress_mpa``."""
    cls = follower_kind(kind)
    if cls.size_axes is None:
        raise ValueError(f"no closed form for a {kind} follower")
    if contact is None:
        return cls.size_figures(ps, sigma, params)
    return cls.size_figures(ps, sigma, params, contact)
