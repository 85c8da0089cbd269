"""Exact planar parametric curves: the contract between geometry and toolpath.

A cam's pitch curve, profile and tool-centre path are curves P(t) of one
parameter (the cam angle in radians for disc cams) with exact derivatives.
Stages downstream (fitting, export, report) use only this protocol; a dense
polyline is only ever a view.

Sign conventions: the left normal is the tangent turned +90°; the signed
curvature κ = (x′y″ − y′x″)/|P′|³ is positive where the curve turns left
(counter-clockwise), so a counter-clockwise convex profile has κ > 0.
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass
from typing import Callable, Protocol, runtime_checkable

import numpy as np

__all__ = [
    "PlanarCurve",
    "FunctionCurve",
    "unit_tangent",
    "left_normal",
    "curvature",
    "curvature_rate",
    "derivatives",
    "speed",
    "arc_length",
]


@runtime_checkable
class PlanarCurve(Protocol):
    """A C¹ planar curve P(t), t ∈ [t_start, t_end], with exact derivatives.

    ``evaluate(t, order)`` returns the ``order``-th derivative (0…3) with
    respect to t at each parameter, shape (n, 2) for t of shape (n,).
    ``breaks`` are the parameters (ends included, increasing) where a
    derivative of order 2 or higher may jump: between two breaks the curve is
    analytic.  ``closed`` curves have P(t_start) = P(t_end).
    """

    @property
    def t_start(self) -> float: ...

    @property
    def t_end(self) -> float: ...

    @property
    def closed(self) -> bool: ...

    @property
    def breaks(self) -> np.ndarray: ...

    def evaluate(self, t, order: int = 0) -> np.ndarray: ...


@dataclass(frozen=True)
class FunctionCurve:
    """A curve from a function ``f(t, order) -> (n, 2)`` (used for tests and simple shapes).

    Examples
    --------
    >>> import numpy as np
    >>> def circle(t, order):
    ...     t = np.atleast_1d(t); c, s = np.cos(t), np.sin(t)
    ...     return 5.0 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][order], axis=-1)
    >>> C = FunctionCurve(circle, 0.0, 2 * np.pi, closed=True)
    >>> float(curvature(C, [1.0])[0])
    0.2
    """

    func: Callable[[np.ndarray, int], np.ndarray]
    t_start: float
    t_end: float
    _: KW_ONLY
    closed: bool = False
    breaks_: tuple[float, ...] = ()

    @property
    def breaks(self) -> np.ndarray:
        inner = [b for b in self.breaks_ if self.t_start < b < self.t_end]
        return np.array([self.t_start, *inner, self.t_end])

    def evaluate(self, t, order: int = 0) -> np.ndarray:
        if not 0 <= order <= 3:
            raise ValueError(f"order must be 0..3, got {order!r}")
        return np.asarray(self.func(np.atleast_1d(np.asarray(t, dtype=float)), order), dtype=float)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def derivatives(curve: PlanarCurve, t, order: int, first: int = 1) -> list[np.ndarray]:
    """[P^(first), …, P^(order)] at ``t`` (by default from P′), each shape (n, 2): one evaluation of the
    jets when the curve has them (a jet of order k carries every lower derivative), else one
    ``evaluate`` per order."""
    jets = getattr(curve, "jets", None)
    if jets is None:
        return [curve.evaluate(t, k) for k in range(first, order + 1)]
    js = jets(t, order)
    return [np.stack([j.d[k] for j in js], axis=-1) for k in range(first, order + 1)]


def speed(curve: PlanarCurve, t) -> np.ndarray:
    """|dP/dt|, shape (n,)."""
    return np.hypot(*curve.evaluate(t, 1).T)


def unit_tangent(curve: PlanarCurve, t) -> np.ndarray:
    d = curve.evaluate(t, 1)
    return d / np.hypot(d[:, 0], d[:, 1])[:, None]


def left_normal(curve: PlanarCurve, t) -> np.ndarray:
    """Unit tangent turned +90° (shape (n, 2))."""
    tx, ty = unit_tangent(curve, t).T
    return np.stack([-ty, tx], axis=-1)


def curvature(curve: PlanarCurve, t) -> np.ndarray:
    """Signed curvature κ (1/mm), positive turning left."""
    d1, d2 = derivatives(curve, t, 2)
    return _cross(d1, d2) / np.hypot(d1[:, 0], d1[:, 1]) ** 3


def curvature_rate(curve: PlanarCurve, t) -> np.ndarray:
    """dκ/ds (1/mm²), exact from the third derivative."""
    d1, d2, d3 = derivatives(curve, t, 3)
    v = np.hypot(d1[:, 0], d1[:, 1])
    c = _cross(d1, d2)
    dc = _cross(d1, d3)  # d/dt (d1 × d2) = d1 × d3
    dv = np.einsum("ij,ij->i", d1, d2) / v
    dk_dt = dc / v**3 - 3 * c * dv / v**4
    return dk_dt / v


def arc_length(curve: PlanarCurve, a: float, b: float) -> float:
    """Length of the curve between parameters a and b (adaptive quadrature, per analytic piece)."""
    from scipy.integrate import quad  # imported here: the rest of this module needs only numpy

    edges = [a, *[x for x in curve.breaks if a < x < b], b]
    total = 0.0
    for lo, hi in zip(edges, edges[1:]):
        val, _ = quad(lambda u: float(speed(curve, [u])[0]), lo, hi, epsabs=1e-12, epsrel=1e-12, limit=200)
        total += val
    return total
