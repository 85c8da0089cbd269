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

* **Scaling** (``scaled``).  ``basis = M^(−1/2)`` with ``M = GᵀG / rows``,
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
evaluations, start Yu–Lee): free coordinates 4.8559 (+4.27 % over the paper's
4.657); scaled only 4.7743 (+2.52 %); symmetric subspace only (unscaled,
20 000 evaluations) 4.7429 (+1.85 %); both: see the README table.
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


def search_coordinates(f: EvaluationFunction, x1, scaled: bool = True, symmetric: bool = True) -> SearchCoordinates:
    """The coordinates to search ``f``'s problem in from the start point ``x1`` (module docstring).

    ``y = 0`` is ``x1`` (its symmetric part when the subspace is used).

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> f = EvaluationFunction(Problem(5, 18, False, "A", (("V", 1.91), ("J", 81.0))))
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
    return SearchCoordinates(origin=origin, basis=basis, symmetric=mirrored)
