"""The Complex method from several start laws within one evaluation budget.

Seed 000 restarts the Complex method from its best vertex (step (c)); the
start Ŝ_1 itself is left to the user.  ``start = "auto"`` runs
:func:`~camcam.optimize.complex_method.complex_method` from the best-ranked
projected catalog laws (:func:`~camcam.optimize.start.ranked_starts`) one
after the other: the first gets the whole budget, and only when its run ends
early (a whole sweep of restart sizes brought nothing, i.e. it converged) does
the next start get what is left.  A row whose first run uses the budget is
therefore exactly the single-start run; one that stalls early (Table 3, N = 5
from the polynomial 3-4-5 law) gets another start.  The result is the best run
that meets every limit (the lowest I when none does).  It is the paper's own
restart idea applied to the start point, within the same total budget.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Callable

from camcam.optimize.complex_method import ComplexResult, ComplexSettings, complex_method
from camcam.optimize.evaluation import EvaluationFunction

__all__ = ["multistart"]


def multistart(
    f: EvaluationFunction,
    starts,
    seed: int = 1,
    settings: ComplexSettings = ComplexSettings(),
    progress: Callable[[int, float], None] | None = None,
) -> tuple[ComplexResult, str, tuple[str, ...]]:
    """(best result, its start law, the start laws run) for ``starts`` = [(x1, name), ...].

    Run ``k`` (0-based) uses seed ``seed + k``; ``evaluations`` and
    ``seconds`` of the returned result are the totals over all runs.

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> from camcam.optimize.start import ranked_starts
    >>> f = EvaluationFunction(Problem(5, 4, True, "A", limits=(("V", 2.0), ("J", 61.4))))
    >>> r, law, run = multistart(f, ranked_starts(f), 1, ComplexSettings(max_evaluations=300))
    >>> r.evaluations, law, len(run)
    (300, 'polynomial-345', 1)
    """
    used, seconds, best, ran = 0, 0.0, None, []
    for k, (x1, name) in enumerate(starts):
        left = settings.max_evaluations - used
        if left <= 2 * len(x1):  # not even one complex
            break
        offset = used
        step = None if progress is None else (lambda e, o, offset=offset: progress(offset + e, o))
        r = complex_method(f, x1, seed + k, replace(settings, max_evaluations=left), step)
        used += r.evaluations
        seconds += r.seconds
        ran.append(name)
        key = (max(r.violations, default=0.0) > settings.violation_tol, r.value if r.violations and max(r.violations) > settings.violation_tol else r.objective)
        if best is None or key < best[0]:
            best = (key, r, name)
        if not r.converged:
            break
    _, r, name = best
    return replace(r, evaluations=used, seconds=seconds), name, tuple(ran)
