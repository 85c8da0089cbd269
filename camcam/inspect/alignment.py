"""Aligning the measured part on the design: least squares on the signed normal deviations.

``none`` fits nothing (a dial's reading zero is always fitted: an indicator has no
absolute zero), ``rotation`` the angular datum about the cam axis, ``rigid`` the
rotation and the translation (the centre in the plane of a disc; x, y, z for a
barrel).  The fit is :func:`scipy.optimize.least_squares` with the soft-L1 loss
of scale ``f_scale``: a local defect a few times the scale pulls the fit by about
(its share of the points) × the scale, where plain least squares would spread it
over the datum (the deviation is never absorbed).  The uncertainty is the
covariance s²·(JᵀJ)⁻¹ of the plain problem at the solution, J the Jacobian of
the deviations by the free parameters over the points kept, s² their mean square
over n − p: the defect stays in s, so the figure is on the safe side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from camcam.inspect.nominal import PARAMETERS

__all__ = ["MODES", "Alignment", "free_parameters", "fit_alignment"]

MODES = ("none", "rotation", "rigid")


def free_parameters(kind: str, mode: str) -> list[int]:
    """Indices into the model's alignment vector that ``mode`` fits.

    Examples
    --------
    >>> free_parameters("cmm", "rotation"), free_parameters("dial", "none"), free_parameters("barrel", "rigid")
    ([0], [3], [0, 1, 2, 3])
    """
    if mode not in MODES:
        raise ValueError(f"unknown alignment {mode!r}; known: {', '.join(MODES)}")
    names = PARAMETERS[kind]
    free = {"none": [], "rotation": [0], "rigid": list(range(len(names)))}[mode]
    if kind == "dial" and 3 not in free:
        free = free + [3]
    return free


@dataclass(frozen=True, kw_only=True)
class Alignment:
    """The fitted alignment: ``u`` the full vector (:data:`~camcam.inspect.nominal.PARAMETERS`), ``sigma``
    its standard uncertainty (0 where not fitted), ``points_used`` the points it was fitted on."""

    kind: str
    mode: str
    u: np.ndarray
    sigma: np.ndarray
    points_used: int

    @property
    def rotation_deg(self) -> float:
        return math.degrees(float(self.u[0]))

    @property
    def rotation_sigma_deg(self) -> float:
        return math.degrees(float(self.sigma[0]))

    @property
    def translation_mm(self) -> list[float]:
        """The shift applied to the measured points (cmm, barrel); for a dial, the cam centre's offset
        from the dividing head's axis (−c)."""
        if self.kind == "dial":
            return [-float(self.u[1]), -float(self.u[2])]
        return [float(v) for v in self.u[1:]]

    @property
    def translation_sigma_mm(self) -> list[float]:
        return [float(v) for v in self.sigma[1:3 if self.kind == "dial" else None]]

    @property
    def zero_mm(self) -> float | None:
        """A dial's fitted reading zero (added to every reading), else None."""
        return float(self.u[3]) if self.kind == "dial" else None


def fit_alignment(model, data: np.ndarray, mode: str, keep: np.ndarray, f_scale: float,
                  u0: np.ndarray) -> Alignment:
    """Fit ``mode``'s free parameters to the points ``data[keep]`` from ``u0`` (module docstring)."""
    free = free_parameters(model.kind, mode)
    u = np.array(u0, dtype=float)
    sigma = np.zeros_like(u)
    pts = data[keep]
    if not free:
        return Alignment(kind=model.kind, mode=mode, u=u, sigma=sigma, points_used=int(keep.sum()))

    def full(x):
        v = u.copy()
        v[free] = x
        return v

    cache: dict = {}

    def ev(x):
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = model.evaluate(full(x), pts)
        return cache[key]

    fit = least_squares(lambda x: ev(x).deviation, u[free], jac=lambda x: ev(x).jacobian[:, free],
                        loss="soft_l1", f_scale=f_scale, x_scale="jac", xtol=1e-12, ftol=1e-12, gtol=1e-12,
                        max_nfev=200)
    u = full(fit.x)
    u[0] = math.remainder(u[0], 2 * math.pi)  # a turn is a turn: the rotation in (−180°, 180°]
    e = model.evaluate(u, pts)
    J = e.jacobian[:, free]
    r = e.deviation
    dof = max(len(r) - len(free), 1)
    cov = float(r @ r) / dof * np.linalg.pinv(J.T @ J)
    sigma[free] = np.sqrt(np.maximum(np.diag(cov), 0.0))
    return Alignment(kind=model.kind, mode=mode, u=u, sigma=sigma, points_used=int(keep.sum()))
