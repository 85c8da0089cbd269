"""Start points for the Complex method: known cam laws projected into the B-spline space.

Seed 000 §2.3 (a) sets the initial control-point vector Ŝ_1 "suitably".  Its
tables use the characteristic values of standard laws as limits (Table 1:
modified trapezoid, Table 2: modified sine, Table 4: Yu and Lee's law), so the
natural start is such a law itself: its displacement fitted by least squares
with the free control points (the fixed ones keep the boundary conditions).
``"auto"`` takes, among the laws of :data:`camcam.motion.catalog.LAWS` whose
projection exceeds no limit by more than :data:`AUTO_SLACK` (relative), the
one with the smallest objective; if none is that close, the smallest sum of
relative excesses.  (A projection slightly off the limits, e.g. Yu and Lee's
law for Table 4 at +1.9 % in J, is a far better start than a feasible but
much worse law.)
"""

from __future__ import annotations

import numpy as np

from camcam.motion.catalog import LAWS, make_law
from camcam.motion.law import MotionLaw
from camcam.optimize.evaluation import EvaluationFunction
from camcam.optimize.space import BSplineSpace

__all__ = ["AUTO_SLACK", "AUTO_STARTS", "project_law", "ranked_starts", "start_point"]

#: Largest relative limit excess of a projection ``"auto"`` ranks by its objective.
AUTO_SLACK = 0.05
#: How many of the best-ranked projections ``"auto"`` may run the Complex method from.
AUTO_STARTS = 3


def project_law(space: BSplineSpace, law: MotionLaw) -> np.ndarray:
    """Free control points whose curve is closest (least squares in S) to ``law``.

    Examples
    --------
    >>> sp = BSplineSpace(5, 7, True)
    >>> x = project_law(sp, make_law("modified-trapezoid"))
    >>> T = np.linspace(0, 0.5, 101)
    >>> float(np.abs(sp.spline(x)(T) - make_law("modified-trapezoid").evaluate(T, 0)).max()) < 1e-3
    True
    """
    T = np.linspace(0.0, space.span, 40 * space.segments + 1)
    basis = space.basis_matrix(T)
    p0 = space.control_points(np.zeros(space.n_free))
    E = np.stack([space.control_points(e) - p0 for e in np.eye(space.n_free)], axis=1)
    x, *_ = np.linalg.lstsq(basis @ E, law.evaluate(T, 0) - basis @ p0, rcond=None)
    return x


def ranked_starts(f: EvaluationFunction, count: int = AUTO_STARTS) -> list[tuple[np.ndarray, str]]:
    """Up to ``count`` projected catalog laws to start ``f``'s problem from, best first.

    The first is ``"auto"``'s choice (module docstring); the others follow by
    objective × (1 + sum of relative limit excesses), a rough penalised value
    that lets a law whose projection is fast but over a limit (the modified
    trapezoid for N = 5: J +31 %) take its turn.

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> f = EvaluationFunction(Problem(5, 5, True, "A", limits=(("V", 2.0), ("J", 61.4))))
    >>> [name for _, name in ranked_starts(f)]
    ['polynomial-345', 'cycloidal', 'modified-trapezoid']
    """
    limits = np.array([lim for _, lim in f.problem.limits])
    rows = []
    for law_name in LAWS:
        x = project_law(f.problem.space, make_law(law_name))
        ic, ir = f.terms(x)
        rel = ic / limits if limits.size else np.zeros(0)
        excess = float(rel.max()) if rel.size else 0.0
        first = (0, ir) if excess <= AUTO_SLACK else (1, float(rel.sum()))
        rows.append((first, ir * (1.0 + float(rel.sum())), x, law_name))
    head = min(rows, key=lambda r: r[0])
    rest = sorted((r for r in rows if r is not head), key=lambda r: r[1])
    return [(r[2], r[3]) for r in [head, *rest][:count]]


def start_point(f: EvaluationFunction, name: str = "auto") -> tuple[np.ndarray, str]:
    """(free control points, law name) of the start Ŝ_1 for ``f``'s problem.

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> f = EvaluationFunction(Problem(5, 7, True, "A", limits=(("V", 2.0), ("J", 61.4))))
    >>> start_point(f)[1]
    'modified-trapezoid'
    """
    if name != "auto":
        return project_law(f.problem.space, make_law(name)), name
    return ranked_starts(f, 1)[0]
