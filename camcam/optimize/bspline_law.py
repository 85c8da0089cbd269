"""A uniform B-spline cam curve (seed 000, eq. 3) as a motion law.

The law keeps its B-spline description (degree, segments, symmetry, control
points) and, for evaluation and extremes, the equivalent
:class:`~camcam.motion.law.PiecewiseLaw` of polynomial pieces (scipy's
``PPoly.from_spline``, mirrored about (0.5, 0.5) when symmetric), so that its
characteristic values come from polynomial roots exactly like every other law.

Continuity: inside [0, 0.5] and [0.5, 1] (or all of [0, 1] when asymmetric) a
degree-n uniform B-spline is C^(n−1).  The point mirror keeps V and J (odd
derivatives of S) continuous at T = 0.5 by construction and S, A by the end
conditions S(0.5) = 0.5, A(0.5) = 0; the fourth derivative changes sign there
(the paper imposes no S''''(0.5) = 0), so a symmetric law is C3 at T = 0.5 and
C^(n−1) elsewhere.
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass, field

import numpy as np

from camcam.motion.law import Extreme, MotionLaw, PiecewiseLaw
from camcam.motion.piece import TrigPoly
from camcam.optimize.space import BSplineSpace

__all__ = ["BSplineLaw"]


@dataclass(frozen=True, eq=False)
class BSplineLaw(MotionLaw):
    """Uniform B-spline rise law S(T), T ∈ [0, 1].

    Parameters
    ----------
    degree, segments, symmetric
        The :class:`~camcam.optimize.space.BSplineSpace`.
    control_points : tuple of float
        All N + n control points (of the half curve when symmetric).
    name : str
        Spec name (``"bspline"`` or the ``file:`` reference it was read from).
    space : BSplineSpace, optional
        The space, when the caller has it already (built otherwise).

    Examples
    --------
    >>> sp = BSplineSpace(5, 7, True)
    >>> law = BSplineLaw.from_free(sp, sp.initial_free())
    >>> float(law.evaluate(0.5)), round(float(law.evaluate(1.0)), 12)
    (0.5, 1.0)
    """

    degree: int
    segments: int
    symmetric: bool
    control_points: tuple[float, ...]
    _: KW_ONLY
    name: str = "bspline"
    rest_to_rest: bool = True
    space: BSplineSpace | None = field(default=None, repr=False)
    _law: PiecewiseLaw = field(init=False, repr=False)

    def __post_init__(self) -> None:
        space = self.space
        if space is None:
            space = BSplineSpace(self.degree, self.segments, self.symmetric)
            object.__setattr__(self, "space", space)
        elif (space.degree, space.segments, space.symmetric) != (self.degree, self.segments, self.symmetric):
            raise ValueError("space does not match degree, segments and symmetric")
        if len(self.control_points) != space.n_control:
            raise ValueError(
                f"a degree-{self.degree} B-spline over {self.segments} segments has "
                f"{space.n_control} control points, got {len(self.control_points)}"
            )
        C = space.pieces(np.asarray(self.control_points, dtype=float))
        b = space.breaks
        pieces = tuple(TrigPoly(tuple(c)) for c in C)
        object.__setattr__(self, "_law", PiecewiseLaw(self.name, (0.0, *map(float, b[1:-1]), 1.0), pieces, self.rest_to_rest))

    @classmethod
    def from_free(cls, space: BSplineSpace, x, name: str = "bspline") -> "BSplineLaw":
        """The law of the free control points ``x`` of ``space``."""
        P = space.control_points(x)
        return cls(space.degree, space.segments, space.symmetric, tuple(float(p) for p in P), name=name, space=space)

    @property
    def knots(self) -> np.ndarray:
        """The uniform knots of the (half) curve."""
        return self.space.knots

    @property
    def piecewise(self) -> PiecewiseLaw:
        """The equivalent polynomial pieces on [0, 1]."""
        return self._law

    def evaluate(self, T, order: int = 0) -> np.ndarray:
        return self._law.evaluate(T, order)

    def evaluate_orders(self, T, orders) -> list[np.ndarray]:
        return self._law.evaluate_orders(T, orders)

    def as_piecewise(self) -> PiecewiseLaw:
        return self._law

    def extreme(self, order: int, rest_ends: bool | None = None) -> tuple[Extreme, Extreme]:
        return self._law.extreme(order, self.rest_to_rest if rest_ends is None else rest_ends)

    def boundary_residual(self) -> float:
        """Largest |error| of the space's boundary conditions (S, V, A at the ends, and at 0.5)."""
        errs = [abs(float(self.evaluate(T, k)) - v) for T, k, v in self.space.conditions]
        errs += [abs(float(self.evaluate(1.0, k)) - v) for k, v in ((0, 1.0), (1, 0.0), (2, 0.0))]
        return max(errs)


