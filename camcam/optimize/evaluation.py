"""The optimisation problem and the paper's evaluation function I (seed 000, eqs. 4–6).

A problem names the B-spline space, the quantity whose largest absolute value
is minimised (``"V"``, ``"A"`` or ``"J"``) and upper limits on the largest
absolute values of others, in priority order.  ``"AV"`` (the product A·V,
which eq. 5 also allows) may be limited too, by the Complex method only: it is
not linear in the control points.

Eq. 4:  I = Σ_p k_cp·I_cp + Σ_q k_rq·I_rq, with, for a limit |h| ≤ L,

    I_cp = (h_max − L)⁺ + (−L − h_min)⁺          (eq. 5, h_max* = L, h_min* = −L)

and the non-constraint term I_rq = max(|h_max|, |h_min|) (eq. 6) with
k_rq = 1.  The extremes h_max, h_min are exact: per-piece polynomial roots
(:mod:`camcam.optimize.extremes`).
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass, field

import numpy as np

from camcam.optimize.extremes import derivative_coefficients, piece_extremes
from camcam.optimize.space import BSplineSpace

__all__ = ["QUANTITIES", "LINEAR_QUANTITIES", "Problem", "CurveEvaluator", "EvaluationFunction"]

#: Quantity name → what it is.
QUANTITIES = {"V": "velocity dS/dT", "A": "acceleration d²S/dT²", "J": "jerk d³S/dT³", "AV": "product A·V"}
#: Quantities linear in the control points (the exact optimiser handles these).
LINEAR_QUANTITIES = ("V", "A", "J")
_ORDER = {"V": 1, "A": 2, "J": 3}


@dataclass(frozen=True)
class Problem:
    """What to optimise.

    Parameters
    ----------
    degree, segments, symmetric
        The B-spline space (see :class:`~camcam.optimize.space.BSplineSpace`).
    minimize : str
        ``"V"``, ``"A"`` or ``"J"``: its largest absolute value over the rise is minimised.
    limits : tuple of (str, float)
        Upper limits on largest absolute values, highest priority first.

    Examples
    --------
    >>> p = Problem(5, 7, True, "A", limits=(("V", 2.0), ("J", 61.4)))
    >>> p.space.n_free
    7
    """

    degree: int = 5
    segments: int = 7
    symmetric: bool = True
    minimize: str = "A"
    _: KW_ONLY
    limits: tuple[tuple[str, float], ...] = ()
    space: BSplineSpace = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.minimize not in LINEAR_QUANTITIES:
            raise ValueError(f"minimize must be one of {', '.join(LINEAR_QUANTITIES)}, got {self.minimize!r}")
        for q, lim in self.limits:
            if q not in QUANTITIES:
                raise ValueError(f"unknown limited quantity {q!r}; known: {', '.join(QUANTITIES)}")
            if not lim > 0:
                raise ValueError(f"limit on {q} must be > 0, got {lim!r}")
        object.__setattr__(self, "space", BSplineSpace(self.degree, self.segments, self.symmetric))

    @property
    def quantities(self) -> tuple[str, ...]:
        """Every quantity the problem looks at: the minimised one first."""
        out = [self.minimize]
        out += [q for q, _ in self.limits if q not in out]
        return tuple(out)


class CurveEvaluator:
    """Exact extremes of V, A, J (and A·V) of the curve of free points ``x``.

    Holds the affine maps from the free points to the piece coefficients of
    each derivative; evaluation is a matrix product and one batched root
    solve per quantity.
    """

    def __init__(self, space: BSplineSpace) -> None:
        self.space = space
        C0, K = space.affine_pieces()
        self._maps = {}
        for q, k in _ORDER.items():
            d0 = derivative_coefficients(C0, k)
            dK = np.moveaxis(derivative_coefficients(np.moveaxis(K, 2, 1), k), 1, 2)
            self._maps[q] = (d0, dK)

    def coefficients(self, q: str, x) -> np.ndarray:
        """Piece coefficients (pieces, deg + 1) of quantity ``q`` (lowest first, u = T − break)."""
        if q == "AV":
            A = self.coefficients("A", x)
            V = self.coefficients("V", x)
            return np.stack([np.convolve(a, v) for a, v in zip(A, V)])
        d0, dK = self._maps[q]
        return d0 + dK @ np.asarray(x, dtype=float)

    def extremes(self, q: str, x) -> tuple[float, float]:
        """(minimum, maximum) of ``q`` over T ∈ [0, 1]."""
        lo, _, hi, _ = piece_extremes(self.coefficients(q, x), self.space.h)
        return float(lo.min()), float(hi.max())

    def largest(self, q: str, x) -> float:
        """Largest |q| over T ∈ [0, 1]."""
        lo, hi = self.extremes(q, x)
        return max(-lo, hi)


@dataclass(frozen=True)
class EvaluationFunction:
    """Eq. 4 for ``problem``: ``terms(x)`` gives the constraint terms and the objective term.

    Examples
    --------
    >>> p = Problem(5, 7, True, "A", limits=(("V", 2.0), ("J", 30.0)))
    >>> f = EvaluationFunction(p)
    >>> ic, ir = f.terms(p.space.initial_free())
    >>> float(ic[0]) < 1e-4, round(float(ic[1]), 1), round(ir, 2)   # cycloidal-like: J ≈ ±39.5, 9.5 over on each side
    (True, 18.9, 6.28)
    """

    problem: Problem
    evaluator: CurveEvaluator = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "evaluator", CurveEvaluator(self.problem.space))

    def terms(self, x) -> tuple[np.ndarray, float]:
        """(I_cp for every limit in priority order, I_r) at ``x``."""
        ev = self.evaluator
        ic = np.empty(len(self.problem.limits))
        for p, (q, lim) in enumerate(self.problem.limits):
            lo, hi = ev.extremes(q, x)
            ic[p] = max(0.0, hi - lim) + max(0.0, -lim - lo)
        return ic, ev.largest(self.problem.minimize, x)

    def relative_violation(self, ic: np.ndarray) -> np.ndarray:
        """Constraint terms divided by their limits."""
        return ic / np.array([lim for _, lim in self.problem.limits]) if len(ic) else ic
