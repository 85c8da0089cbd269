"""Slopes of measured points: seed 002's central difference on uneven spacing, and periodic fits.

Measured points of a closed cam curve are ordered by their polar angle φ
about the cam axis.  A quantity g (an axial coordinate, a radius) known at
uneven φ_i is differentiated in one of two ways:

``central`` (seed 002, eqs. 1–4)
    The two Taylor expansions about P_i towards P_{i−1} and P_{i+1} at
    distances h₁, h₂ (eqs. 1–2) solved for f′ and f″ (eq. 3):

        f′ = (h₁²(f₊ − f₀) − h₂²(f₋ − f₀)) / (h₁h₂(h₁ + h₂))

    exact for quadratics, error O(h₁h₂).
``spline``
    A periodic spline of g(φ): a quintic periodic interpolating spline
    (``smoothing=False``; error O(h⁵) in g′) or a cubic smoothing spline whose
    penalty is chosen by generalised cross-validation on the data padded by one
    period each side (``smoothing=True``; for noisy points).  Above
    :data:`~camcam.lifttable.smoothing.GCV_MAX_POINTS` padded points, or where
    SciPy's GCV gives up ("the problem is ill-posed"), the smoothing spline is the
    lift-table stage's O(n) one: Reinsch's banded solve with λ by GCV on every
    k-th point (:mod:`camcam.lifttable.smoothing`), so a points file at the
    200 000-row cap is fitted in seconds.

Examples
--------
>>> import numpy as np
>>> h1, h2 = np.array([0.5]), np.array([1.5])
>>> f = lambda x: 3 * x**2 - 2 * x + 1
>>> float(central_difference(f(-h1), f(0.0 * h1), f(h2), h1, h2)[0])
-2.0
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import make_interp_spline, make_smoothing_spline

from camcam.lifttable.smoothing import GCV_MAX_POINTS, GCV_SUBSAMPLE, gcv_lambda, reinsch

__all__ = ["central_difference", "PeriodicFit", "periodic_fit"]

TWO_PI = 2.0 * math.pi


def central_difference(f_prev, f_0, f_next, h1, h2) -> np.ndarray:
    """f′ at the middle point from seed 002's eq. 3 (uneven spacing h₁ behind, h₂ ahead)."""
    f_prev, f_0, f_next, h1, h2 = (np.asarray(v, dtype=float) for v in (f_prev, f_0, f_next, h1, h2))
    return (h1**2 * (f_next - f_0) - h2**2 * (f_prev - f_0)) / (h1 * h2 * (h1 + h2))


class PeriodicFit:
    """A 2π-periodic fit g(φ) with derivatives: ``fit(phi, nu)``."""

    def __init__(self, spline, smoothing: bool) -> None:
        self._spline = spline
        self.smoothing = smoothing

    def __call__(self, phi, nu: int = 0) -> np.ndarray:
        phi = np.mod(np.asarray(phi, dtype=float), TWO_PI)
        return self._spline(phi, nu)


def periodic_fit(phi, g, smoothing: bool) -> PeriodicFit:
    """Fit g(φ) over one revolution; ``phi`` strictly increasing in [0, 2π).

    Examples
    --------
    >>> import numpy as np
    >>> phi = np.sort(np.random.default_rng(0).uniform(0, 2 * np.pi, 90))
    >>> fit = periodic_fit(phi, np.sin(phi), smoothing=False)
    >>> bool(abs(fit(1.0, 1) - np.cos(1.0)) < 1e-7)
    True
    """
    phi = np.asarray(phi, dtype=float)
    g = np.asarray(g, dtype=float)
    if smoothing:
        xs = np.concatenate([phi - TWO_PI, phi, phi + TWO_PI])
        ys = np.concatenate([g, g, g])
        if xs.size <= GCV_MAX_POINTS:
            try:
                return PeriodicFit(make_smoothing_spline(xs, ys), True)
            except ValueError:  # SciPy's GCV search gave up; the banded route below always answers
                pass
        return PeriodicFit(_large_smoothing(phi, g, xs, ys), True)
    xs = np.concatenate([phi, [phi[0] + TWO_PI]])
    ys = np.concatenate([g, [g[0]]])
    spl = make_interp_spline(xs, ys, k=5, bc_type="periodic")
    return _Shifted(spl, phi[0])


def _large_smoothing(phi: np.ndarray, g: np.ndarray, xs: np.ndarray, ys: np.ndarray):
    """The cubic smoothing spline through the padded (xs, ys) in O(n): λ by exact GCV on every k-th
    point of the revolution (padded the same way) scaled by k^{1/5}, values by Reinsch's banded solve
    (:mod:`camcam.lifttable.smoothing`), and the natural cubic spline through those values — which *is*
    the smoothing spline (it is the natural cubic spline with knots at the data)."""
    k = math.ceil(phi.size / GCV_SUBSAMPLE)
    sub = np.arange(0, phi.size, k)
    ps, gs = phi[sub], g[sub]
    lam = gcv_lambda(np.concatenate([ps - TWO_PI, ps, ps + TWO_PI]), np.concatenate([gs, gs, gs])) * k ** 0.2
    return make_interp_spline(xs, reinsch(xs, ys, lam), k=3, bc_type="natural")


class _Shifted(PeriodicFit):
    """A periodic spline defined on [φ₀, φ₀ + 2π)."""

    def __init__(self, spline, start: float) -> None:
        super().__init__(spline, False)
        self._start = start

    def __call__(self, phi, nu: int = 0) -> np.ndarray:
        phi = self._start + np.mod(np.asarray(phi, dtype=float) - self._start, TWO_PI)
        return self._spline(phi, nu)
