"""The sweep's dynamics constraints (``[size] max_contact_stress_mpa``, ``min_jump_rpm``), per design.

The follower train is the spec's ``[dynamics]`` table, at the spec's rpm; the model and its functions are
:mod:`camcam.dynamics` (used here, not copied):

* contact stress: the generalised force Q on the sweep's samples (:func:`~camcam.dynamics.forces.train_terms`),
  the contact force F_n = Q·gain with the kernel's pressure angle (a translating roller's guide friction
  included, an oscillating roller's arm L: gain 1/(L cos φ)), and Hertz line contact
  (:func:`~camcam.dynamics.forces.hertz_line_mpa`) with R′ = r(1 − r·κc) from the pitch curve's convex
  curvature κc the kernels have (a flat face: R′ the profile radius R_b + s + s″, L the cam's thickness).
  The largest sampled value of a row, like the kernels' other maxima, is never above the true one; the exact
  check (:func:`camcam.sizing.exact_check.exact_figures`) computes it as ``camcam run`` does.
  Where the guide friction would lock the follower (cos φ ≤ μ|sin φ|), and where the roller is as large as
  the pitch curve's radius (R′ ≤ 0: undercut), the stress is infinite.
* jump speed: exact per design (:func:`~camcam.dynamics.cycle.program_jump_speed`, the function ``camcam run``
  uses): it depends on the law combination and the lever w alone (the oscillating roller's arm when no
  ``load_arm_mm`` is given), so it is computed once per distinct (combination, w) and spread over the table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.dynamics.cycle import program_jump_speed
from camcam.dynamics.forces import hertz_line_mpa, train_terms
from camcam.dynamics.train import DynamicsSpec, contact_modulus_mpa
from camcam.errors import SpecError

__all__ = ["SweepDynamics", "COLUMNS"]

#: The table columns the dynamics constraints add (only when [size] gives one of them).
COLUMNS = ("max_contact_stress_mpa", "jump_rpm")


@dataclass(frozen=True, kw_only=True)
class SweepDynamics:
    """The follower train and what the per-design figures need besides the design's geometry."""

    spec: DynamicsSpec
    rpm: float
    oscillating: bool
    thickness_mm: float  # a flat face's contact length: the cam's thickness

    @classmethod
    def of(cls, spec) -> "SweepDynamics":
        d = spec.dynamics
        if d is None:  # read_size refuses this already; kept for a spec built in code
            raise SpecError("size", "max_contact_stress_mpa and min_jump_rpm need a [dynamics] table")
        program = spec.motion.program(spec.unit)
        return cls(spec=d, rpm=float(program.rpm), oscillating=program.unit == "deg",
                   thickness_mm=float(spec.cam.thickness))

    def lever_m(self, arm_length_mm=None):
        """w: 1 (translating), ``load_arm_mm`` in m, or each design's arm length in m (oscillating)."""
        if not self.oscillating:
            return 1.0
        if self.spec.load_arm_mm is not None:
            return self.spec.load_arm_mm / 1000.0
        return np.asarray(arm_length_mm, float) / 1000.0

    def _generalised(self, ps, lever) -> np.ndarray:
        """Q (rows: designs when ``lever`` is a column, else one row) on the sweep's samples at the spec's rpm."""
        scale = 1.0 if self.oscillating else 1e-3  # the samples are mm (or rad) per rad: the model's m (or rad)
        a, b, c, _, _ = train_terms(self.spec, self.oscillating, lever, ps.theta, ps.s * scale, ps.s1 * scale,
                                    ps.s2 * scale)
        omega = 2.0 * math.pi * self.rpm / 60.0
        return a * omega * omega + b * omega + c  # Coefficients.generalised_force

    def max_stress(self, ps, *, cos_phi, sin_phi, relative_radius_mm, roller: bool, arm_length_mm=None) -> np.ndarray:
        """The largest sampled contact stress of each design (MPa); arrays (designs, samples)."""
        d = self.spec
        n = relative_radius_mm.shape[0]
        lever = self.lever_m(arm_length_mm)
        Q = self._generalised(ps, np.reshape(lever, (-1, 1)) if np.ndim(lever) else lever)
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.oscillating:  # the normal's moment arm about the pivot: L·cos φ (no guide friction)
                denominator = np.asarray(arm_length_mm, float)[:, None] / 1000.0 * cos_phi
            else:
                denominator = cos_phi - d.friction * np.sign(ps.s1) * np.abs(sin_phi)
            fn = np.where(Q >= 0, Q / denominator, 0.0)
            length = d.roller_width_mm if roller else self.thickness_mm
            p = hertz_line_mpa(np.maximum(fn, 0.0), contact_modulus_mpa(d.cam_material, d.follower_material), length,
                               relative_radius_mm)
            locked = (cos_phi - d.friction * np.abs(sin_phi) <= 0) if not self.oscillating else (cos_phi <= 0)
            p = np.where(locked | ~(relative_radius_mm > 0) | np.isnan(p), np.inf, p)
        return np.broadcast_to(p, (n, p.shape[-1])).max(axis=1)

    def jump_rpm(self, program, arm_length_mm: float | None = None) -> float:
        """The exact jump speed of one design, rpm (inf: it never separates)."""
        omega, _ = program_jump_speed(program, self.spec, float(self.lever_m(arm_length_mm)))
        return omega * 60.0 / (2.0 * math.pi)
