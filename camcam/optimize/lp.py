"""Linear programmes solved by HiGHS, through its own Python binding (``highspy``).

    minimise c·x   subject to   A_ub x ≤ b_ub,   lower ≤ x ≤ upper

This is the problem ``scipy.optimize.linprog(method="highs-ds")`` hands to the
same solver.  camcam calls HiGHS directly because ``import scipy.optimize``
(which ``linprog`` needs) costs 0.35–0.75 s of a 2-core machine's time, more
than the whole exact optimisation takes after it; ``import highspy`` costs a
few tens of milliseconds on top of numpy.  The options are linprog's for
``highs-ds``: presolve on, the dual simplex, no output.

A solve is answered by Ctrl-C, SIGTERM and SIGHUP within one simplex (or interior-point)
iteration: the signals are held (:func:`camcam.interrupts.deferred`) while HiGHS runs, its
interrupt callbacks — called every iteration — tell it to stop once one came, and the held
signal is delivered as the call returns (before, a stalled solve answered after 30–60 s).

Examples
--------
>>> sol = solve_lp(np.array([-1.0, -1.0]), np.array([[1.0, 2.0], [3.0, 1.0]]), np.array([4.0, 6.0]),
...                np.zeros(2), np.full(2, np.inf))
>>> sol.status, sol.x.round(12).tolist()
('optimal', [1.6, 1.2])
"""

from __future__ import annotations

from dataclasses import dataclass

import highspy
import numpy as np
from highspy._core import _Highs, cb

from camcam.interrupts import deferred

__all__ = ["IncrementalLp", "LpSolution", "solve_lp"]

_STATUS = {
    highspy.HighsModelStatus.kOptimal: "optimal",
    highspy.HighsModelStatus.kInfeasible: "infeasible",
    highspy.HighsModelStatus.kUnbounded: "unbounded",
}


@dataclass(frozen=True)
class LpSolution:
    """HiGHS's verdict: ``status`` is "optimal", "infeasible", "unbounded" or HiGHS's own words for anything else.

    ``x`` (n,) is the solution (meaningful only when optimal); ``iterations``
    the simplex iterations spent.
    """

    status: str
    x: np.ndarray
    iterations: int


class IncrementalLp:
    """``minimise c·x`` over rows added a batch at a time; each solve starts from the last one's basis.

    A cutting-plane loop (:func:`camcam.optimize.exact.exact_optimum`) adds a few
    violated rows per round; the dual simplex then needs a handful of iterations
    from the previous optimal basis instead of a solve from nothing (73 against
    521 iterations in 13 rounds on seed 000's Table 1).

    Parameters
    ----------
    c : array_like, shape (n,)
    lower, upper : array_like, shape (n,)
        Bounds of x (±inf for none).
    primal_tolerance, dual_tolerance : float, optional
        HiGHS's feasibility tolerances (its defaults, 1e-7, when None).
    simplex : bool
        The dual simplex (linprog's ``highs-ds``), or HiGHS's own choice of
        solver (linprog's ``highs``).
    presolve : bool
        HiGHS's presolve before each solve (its default).
    devex : bool
        Devex pricing in the dual simplex instead of HiGHS's choice (dual steepest edge): cheaper
        iterations, usually more of them.

    Examples
    --------
    >>> lp = IncrementalLp(np.array([-1.0, -1.0]), np.zeros(2), np.full(2, np.inf))
    >>> lp.add_rows(np.array([[1.0, 2.0]]), np.array([4.0]))
    >>> lp.add_rows(np.array([[3.0, 1.0]]), np.array([6.0]))
    >>> sol = lp.solve()
    >>> sol.status, sol.x.round(12).tolist()
    ('optimal', [1.6, 1.2])
    """

    def __init__(self, c, lower, upper, *, primal_tolerance: float | None = None,
                 dual_tolerance: float | None = None, simplex: bool = True, presolve: bool = True,
                 devex: bool = False) -> None:
        c = np.ascontiguousarray(c, dtype=float)
        # the binding's core class, as scipy's own HiGHS wrapper uses it: the public ``highspy.Highs`` writes
        # HiGHS's banner to the process's standard output (C level) when it is made, before any option can be set
        h = _Highs()
        h.setOptionValue("output_flag", False)
        h.setOptionValue("presolve", "on" if presolve else "off")
        if simplex:
            h.setOptionValue("solver", "simplex")
            h.setOptionValue("simplex_strategy", 1)  # dual
        if devex:
            h.setOptionValue("simplex_dual_edge_weight_strategy", 1)
        if primal_tolerance is not None:
            h.setOptionValue("primal_feasibility_tolerance", float(primal_tolerance))
        if dual_tolerance is not None:
            h.setOptionValue("dual_feasibility_tolerance", float(dual_tolerance))
        h.addVars(len(c), np.asarray(lower, dtype=float), np.asarray(upper, dtype=float))
        h.changeColsCost(len(c), np.arange(len(c), dtype=np.int32), c)
        self._highs, self._n = h, len(c)

    def add_rows(self, A_ub, b_ub) -> None:
        """Add the rows ``A_ub x ≤ b_ub`` (dense, shape (m, n) and (m,))."""
        A = np.ascontiguousarray(A_ub, dtype=float)
        if A.ndim != 2 or A.shape[1] != self._n:
            raise ValueError(f"rows must have {self._n} columns, got shape {A.shape}")
        nz = A != 0.0
        starts = np.concatenate([[0], np.cumsum(nz.sum(axis=1))[:-1]]).astype(np.int32)
        self._highs.addRows(len(A), np.full(len(A), -np.inf), np.asarray(b_ub, dtype=float), int(nz.sum()), starts,
                            np.nonzero(nz)[1].astype(np.int32), A[nz])

    def solve(self) -> LpSolution:
        """Solve over the rows added so far; a signal that comes meanwhile stops it and is raised after."""
        h = self._highs
        with deferred() as came:
            def poll(kind, message, data_out, data_in, user_data) -> None:
                if came and data_in is not None:
                    data_in.user_interrupt = True

            h.setCallback(poll, None)
            h.startCallback(cb.HighsCallbackType.kCallbackSimplexInterrupt)
            h.startCallback(cb.HighsCallbackType.kCallbackIpmInterrupt)
            try:
                h.run()
            finally:
                h.setCallback(None, None)  # stops the callbacks: none refers to this block's list afterwards
        model_status = h.getModelStatus()
        status = _STATUS.get(model_status, h.modelStatusToString(model_status))
        x = np.array(h.getSolution().col_value, dtype=float)
        return LpSolution(status, x, int(h.getInfo().simplex_iteration_count))


def solve_lp(c, A_ub, b_ub, lower, upper, *, primal_tolerance: float | None = None,
             dual_tolerance: float | None = None, simplex: bool = True) -> LpSolution:
    """Minimise ``c·x`` subject to ``A_ub x ≤ b_ub`` and ``lower ≤ x ≤ upper`` (±inf for no bound), from nothing.

    ``A_ub`` (m, n) is dense (camcam's LPs are small and dense); the other
    parameters are :class:`IncrementalLp`'s.
    """
    lp = IncrementalLp(c, lower, upper, primal_tolerance=primal_tolerance, dual_tolerance=dual_tolerance,
                       simplex=simplex)
    lp.add_rows(A_ub, b_ub)
    return lp.solve()
