"""The coordinates the Complex method searches in: scaled, and mirror-symmetric where that loses nothing.

The free control points ``x`` are a poor frame for a direct search.  A step
δ in one control point changes A by about δ·n(n−1)/ΔT² and J by δ·n(n−1)(n−2)/ΔT³,
and the smooth directions (which change the curve's shape broadly) change A
hundreds of times less than the rough ones.  A Box complex is generated as a
random box in its coordinates (step (a)) and its collapse is measured there, so
in ``x`` a box that is small enough for the rough directions hardly explores
the smooth ones.  Two changes of coordinates ``x = origin + basis @ y`` fix
this; the method's steps (b)–(f) are unchanged (reflections through centroids
are affine-invariant), only the box of step (a) and the collapse test see ``y``.

* **Scaling** (``scaled``, off by default, see below).  ``basis = M^(−1/2)`` with ``M = GᵀG / rows``,
  ``G`` the map from ``x`` to the minimised quantity sampled at 6 points of
  every piece (both ends and 4 inside).  A unit step in ``y`` in any direction
  changes that quantity by 1 in root mean square, so the random box of step (a)
  is round in the quantity that is minimised.
* **Mirror-symmetric subspace** (``symmetric``).  An asymmetric space
  (S, V, A fixed at both ends) is mapped onto itself by the point mirror
  S(T) → 1 − S(1 − T), and so are limits on |V|, |A|, |J| and the objective
  max |Q|.  The problem is convex (I's terms are maxima of affine functions of
  ``x``), so if ``x*`` is optimal so is its mirror, and so is their mean, which
  is symmetric: the symmetric subspace (8 of the 17 free points for degree 5,
  N = 18) always holds an optimum, and searching it loses nothing.  The start
  point is replaced by its symmetric part (x₁ + mirror(x₁))/2.  A limit on A·V
  (not convex) keeps the whole space.

Measured (seed 000 Table 4, degree 5, N = 18, asymmetric, seed 1, 40 000
evaluations, start Yu–Lee; the paper has Am = 4.657, the exact LP 4.6556):

=========================================================  ========  =========
coordinates                                                Am        vs paper
=========================================================  ========  =========
free points (before)                                       4.8559    +4.27 %
scaled only                                                4.7743    +2.52 %
scaled by every quantity over its limit (not kept)         4.7585    +2.18 %
symmetric subspace, 20 000 evaluations, then 20 000 free   4.7424    +1.83 %
symmetric subspace (the default)                           4.6893    +0.69 %
symmetric subspace and scaled                              4.6692    +0.26 %
=========================================================  ========  =========

Scaling is not the default: on the symmetric tables (whose space is already
symmetric, so scaling is the only change there) it moves Table 3 N = 4 from
+0.04 % to +0.57 % and N = 5 from +0.33 % to +1.47 % of the paper (the
polynomial 3-4-5 run no longer converges early, so the multi-start never
reaches the cycloidal start); elsewhere it changes little (scaled against
unscaled: Table 1 4.8697 / 4.8619, Table 2 61.449 / 60.256, Table 3 N = 3
5.5324 / 5.5325, N = 6 4.8938 / 4.8942, N = 7 4.8697 / 4.8619, N = 8
4.9052 / 4.9039, N = 9 4.9019 / 4.9043, N = 10 4.8721 / 4.8790).  Without scaling a search in the symmetric
space is exactly the former search in ``x`` (``y = x``), so Tables 1–3 keep
their figures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.optimize.evaluation import EvaluationFunction
from camcam.optimize.space import BSplineSpace

__all__ = ["SearchCoordinates", "search_coordinates", "mirror_map"]

#: Sample points per piece (fractions of ΔT) of the scaling metric.
_SAMPLES = np.linspace(0.0, 1.0, 6)


@dataclass(frozen=True)
class SearchCoordinates:
    """``x = origin + basis @ y``: free control points from search coordinates ``y``."""

    origin: np.ndarray
    basis: np.ndarray
    symmetric: bool
    start: np.ndarray  # y of the start point

    @property
    def size(self) -> int:
        """Number of search coordinates."""
        return self.basis.shape[1]

    def free(self, y) -> np.ndarray:
        """The free control points at ``y``."""
        return self.origin + self.basis @ np.asarray(y, dtype=float)


def mirror_map(space: BSplineSpace) -> tuple[np.ndarray, np.ndarray]:
    """``(R, r)`` with ``R @ x + r`` the free points of the curve 1 − S(1 − T).

    Examples
    --------
    >>> sp = BSplineSpace(5, 18, False)
    >>> R, r = mirror_map(sp)
    >>> x = sp.initial_free()
    >>> T = np.linspace(0, 1, 7)
    >>> bool(np.allclose(sp.spline(R @ x + r)(T), 1 - sp.spline(x)(1 - T)))
    True
    """
    def mirror(x):
        return space.free_points(1.0 - space.control_points(x)[::-1])

    r = mirror(np.zeros(space.n_free))
    R = np.stack([mirror(e) - r for e in np.eye(space.n_free)], axis=1)
    return R, r


def _metric(f: EvaluationFunction) -> np.ndarray:
    """``GᵀG / rows`` for the minimised quantity sampled on every piece."""
    space = f.problem.space
    _, dK = f.evaluator._maps[f.problem.minimize]
    powers = (_SAMPLES * space.h)[:, None] ** np.arange(dK.shape[1])[None, :]
    G = np.einsum("uk,pkf->puf", powers, dK).reshape(-1, space.n_free)
    return G.T @ G / G.shape[0]


def search_coordinates(f: EvaluationFunction, x1, scaled: bool = False, symmetric: bool = True) -> SearchCoordinates:
    """The coordinates to search ``f``'s problem in from the start point ``x1`` (module docstring).

    ``y = start`` is ``x1`` (its symmetric part when the subspace is used).  Without
    scaling or subspace the coordinates are the free points themselves (``y = x``,
    the same floating-point numbers as a search in ``x``).

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> f = EvaluationFunction(Problem(5, 18, False, "A", limits=(("V", 1.91), ("J", 81.0))))
    >>> c = search_coordinates(f, f.problem.space.initial_free())
    >>> c.size, c.symmetric
    (8, True)
    >>> R, r = mirror_map(f.problem.space)
    >>> x = c.free(np.linspace(-1, 1, c.size))
    >>> float(np.abs(R @ x + r - x).max()) < 1e-9     # every searched curve is point-symmetric
    True
    """
    space = f.problem.space
    x1 = np.asarray(x1, dtype=float)
    basis = np.eye(space.n_free)
    origin = x1
    mirrored = symmetric and not space.symmetric and all(q != "AV" for q, _ in f.problem.limits)
    if mirrored:
        R, r = mirror_map(space)
        P = np.eye(space.n_free) + R
        k = int(round(np.trace(P) / 2))  # dimension of the +1 eigenspace of the involution R
        basis = np.linalg.svd(P)[0][:, :k]
        origin = (x1 + R @ x1 + r) / 2
    if scaled:
        w, V = np.linalg.eigh(basis.T @ _metric(f) @ basis)
        basis = basis @ (V * w**-0.5) @ V.T
    if not (scaled or mirrored):
        return SearchCoordinates(origin=np.zeros(space.n_free), basis=basis, symmetric=False, start=x1)
    return SearchCoordinates(origin=origin, basis=basis, symmetric=mirrored, start=np.zeros(basis.shape[1]))
