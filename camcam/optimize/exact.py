"""The exact optimum: a linear programme on the continuous curve.

Every piece coefficient of V, A, J is affine in the free control points x, so
"minimise the largest |Q| subject to |V| ≤ V*, |J| ≤ J* …" is a linear
programme in (x, t) with the epigraph variable t ≥ |Q(T)|:

    minimise t   subject to   ±Q(T_s) − t ≤ 0,   ±R(T_s) ≤ R*   at sample points T_s.

Sample points alone bound the curve only there.  The solver therefore
refines: after each HiGHS solve it computes the exact extremes of every piece
(roots of the next derivative), adds the points where a limit or the epigraph
is exceeded, and solves again, until the worst excess is at most ``rtol``
(relative).  The LP over the final sample set is a relaxation of the
continuous problem, so its optimum is a lower bound of the continuous optimum
and the returned curve, feasible to ``rtol``, attains it to the same accuracy.

The LP keeps its rows from round to round and each round adds only its new
samples' rows, so HiGHS's dual simplex restarts from the last optimal basis
(:class:`~camcam.optimize.lp.IncrementalLp`; Table 1: 73 simplex iterations in
13 rounds, against 521 when every round was solved from nothing).

So that the returned curve meets the limits literally (its exact extremes are
≤ the limits, not only within ``rtol``), the LP is solved against limits
tightened by the relative ``margin`` (default 2e-9 > the 1e-9 refinement
tolerance): the curve may exceed a tightened limit by ``rtol`` and still be
below the stated one.  ``worst_violation`` is measured against the stated
limits.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from camcam.optimize.evaluation import LINEAR_QUANTITIES, CurveEvaluator, Problem
from camcam.optimize.extremes import piece_extremes
from camcam.optimize.lp import IncrementalLp, solve_lp

__all__ = ["ExactResult", "InfeasibleProblem", "ProblemTooLarge", "exact_optimum", "lp_size", "MAX_LP_ENTRIES"]

#: HiGHS's feasibility tolerance on rows scaled to O(1): 1e-10 keeps the solver's own
#: slack below the 1e-9 relative limit check.
_TIGHT = 1e-10

#: The largest LP the exact method starts, in entries of its first constraint matrix (columns × rows,
#: :func:`lp_size`).  Seed 000's tables are 864–11 664 entries and the N = 80 row of
#: benchmarks/optimize_tables.py 466 560 (0.7 s); above, HiGHS's dual simplex can stall for minutes on
#: the refined rows (degree 7, 98 symmetric segments, minimise J: 712 656 entries, one round of 240 000
#: iterations, 41 s; degree 9, 200 segments: 1 468 800, 15 CPU-minutes in issue 50).
MAX_LP_ENTRIES = 500_000


class InfeasibleProblem(ValueError):
    """No curve of the problem's space meets its limits."""


class ProblemTooLarge(ValueError):
    """The problem's LP is over :data:`MAX_LP_ENTRIES`; the message says which sizes fit."""


def lp_size(problem: Problem, per_piece: int = 6) -> tuple[int, int]:
    """(columns, rows) of the exact method's first LP: the free control points and the epigraph variable;
    two rows (±) at ``per_piece`` samples of every piece for each bounded or minimised quantity.

    >>> lp_size(Problem(5, 7, True, "A", limits=(("V", 2.0), ("J", 61.4))))
    (8, 504)
    """
    quantities = len(set(dict(problem.limits)) | {problem.minimize})
    return problem.space.n_free + 1, 2 * per_piece * problem.space.n_pieces * quantities


def _check_size(problem: Problem, per_piece: int) -> None:
    cols, rows = lp_size(problem, per_piece)
    if cols * rows <= MAX_LP_ENTRIES:
        return
    sp = problem.space
    quantities = rows // (2 * per_piece * sp.n_pieces)
    fits = [n for n in range(sp.segments - 1, 0, -1)
            if (n + sp.degree - sp.n_conditions + 1) * 2 * per_piece * (2 * n if sp.symmetric else n) * quantities
            <= MAX_LP_ENTRIES and n + sp.degree - sp.n_conditions >= 1]
    advice = f"at most {fits[0]} segments at degree {sp.degree}" if fits else "a lower degree"
    raise ProblemTooLarge(
        f"the exact LP would start with {cols} columns × {rows} rows = {cols * rows:,} entries, over camcam's "
        f"limit of {MAX_LP_ENTRIES:,} (degree {sp.degree}, {sp.segments} segments, "
        f"{'symmetric' if sp.symmetric else 'asymmetric'}); use {advice}"
    )


@dataclass(frozen=True, kw_only=True)
class ExactResult:
    """The LP optimum and how it was reached."""

    x: np.ndarray
    objective: float  # exact largest |Q| of the returned curve
    lower_bound: float  # LP value over the final samples
    worst_violation: float  # largest relative excess of a limit (≤ rtol; 0 if none)
    rounds: int
    samples: int
    lp_iterations: int
    seconds: float


def _rows(ev: CurveEvaluator, q: str, piece: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q(T) = a·x + b at the points (piece, u): returns (a, b)."""
    d0, dK = ev._maps[q]
    powers = u[:, None] ** np.arange(d0.shape[1])
    return np.einsum("sk,skf->sf", powers, dK[piece]), np.einsum("sk,sk->s", powers, d0[piece])


def exact_optimum(
    problem: Problem, rtol: float = 1e-9, max_rounds: int = 60, per_piece: int = 6, margin: float = 2e-9
) -> ExactResult:
    """Globally optimal free control points of ``problem`` (limits V, A, J only).

    Examples
    --------
    >>> r = exact_optimum(Problem(5, 7, True, "A", limits=(("V", 2.0), ("J", 61.4))))
    >>> r.objective < 4.862 and r.worst_violation == 0.0
    True
    """
    t0 = time.perf_counter()
    for q, _ in problem.limits:
        if q not in LINEAR_QUANTITIES:
            raise ValueError(f"the exact optimiser handles limits on {', '.join(LINEAR_QUANTITIES)} only, got {q!r}")
    _check_size(problem, per_piece)
    space = problem.space
    ev = CurveEvaluator(space)
    nf, h = space.n_free, space.h
    pieces = np.arange(space.n_pieces)
    base_u = np.linspace(0.0, h, per_piece)
    # One sample set per quantity: (piece index, local u).
    stated = dict(problem.limits)
    limits = {q: lim * (1.0 - margin) for q, lim in stated.items()}
    samples = {q: (np.repeat(pieces, per_piece), np.tile(base_u, len(pieces))) for q in set(limits) | {problem.minimize}}
    rounds = lp_iters = 0
    t_scale = 1.0
    c = np.zeros(nf + 1)
    c[-1] = 1.0
    lower = np.r_[np.full(nf, -np.inf), 0.0]
    upper = np.full(nf + 1, np.inf)
    # The LP keeps its rows and basis from round to round: each round adds the rows of its new
    # samples only, and the dual simplex restarts from the last optimum.
    lp = IncrementalLp(c, lower, upper, primal_tolerance=_TIGHT, dual_tolerance=_TIGHT)
    new = dict(samples)
    rows_A, rows_b = [], []  # every row so far, for a solve from nothing if the warm one stalls
    while True:
        rounds += 1
        A_ub, b_ub = [], []
        for q, (pc, u) in new.items():
            a, b = _rows(ev, q, pc, u)
            # Rows are divided by their limit (or the last objective value) to keep
            # HiGHS well scaled: its feasibility tolerance then is relative.  (A row
            # added in an earlier round keeps that round's scale: the same constraint.)
            if q == problem.minimize:
                s = 1.0 / max(1e-3, t_scale)
                A_ub += [np.hstack([a * s, -s * np.ones((len(u), 1))]), np.hstack([-a * s, -s * np.ones((len(u), 1))])]
                b_ub += [-b * s, b * s]
            if q in limits:
                lim = limits[q]
                zero = np.zeros((len(u), 1))
                A_ub += [np.hstack([a / lim, zero]), np.hstack([-a / lim, zero])]
                b_ub += [(lim - b) / lim, (lim + b) / lim]
        rows_A += A_ub
        rows_b += b_ub
        lp.add_rows(np.vstack(A_ub), np.concatenate(b_ub))
        res = lp.solve()
        if res.status not in ("optimal", "infeasible"):  # tight tolerances can stall HiGHS: retry with its defaults
            res = solve_lp(c, np.vstack(rows_A), np.concatenate(rows_b), lower, upper, simplex=False)
        lp_iters += res.iterations
        if res.status == "infeasible":
            raise InfeasibleProblem("no curve of this degree and number of segments meets the limits")
        if res.status != "optimal":
            raise RuntimeError(f"HiGHS failed: {res.status}")
        x, t = res.x[:nf], float(res.x[-1])
        t_scale = t
        worst, obj_excess, added = 0.0, 0.0, 0
        new = {}
        for q in samples:
            lo, ulo, hi, uhi = piece_extremes(ev.coefficients(q, x), h)
            bound = limits.get(q)
            new_p, new_u = [], []
            if bound is not None:
                exc = np.maximum(hi - bound, -bound - lo) / bound
                worst = max(worst, float(exc.max()))
                for arr, uu in ((hi - bound, uhi), (-bound - lo, ulo)):
                    m = arr > rtol * bound * 0.1
                    new_p.append(pieces[m])
                    new_u.append(uu[m])
            if q == problem.minimize:
                largest = np.maximum(hi, -lo)
                obj_excess = max(obj_excess, (float(largest.max()) - t) / max(t, 1e-300))
                for arr, uu in ((hi - t, uhi), (-t - lo, ulo)):
                    m = arr > rtol * t * 0.1
                    new_p.append(pieces[m])
                    new_u.append(uu[m])
            pc = np.concatenate(new_p)
            if pc.size:
                new[q] = (pc, np.concatenate(new_u))
                samples[q] = (np.concatenate([samples[q][0], pc]), np.concatenate([samples[q][1], new[q][1]]))
                added += pc.size
        if (worst <= rtol and obj_excess <= rtol) or added == 0 or rounds >= max_rounds:
            break
    objective = ev.largest(problem.minimize, x)
    worst = max(max(ev.largest(q, x) - lim, 0.0) / lim for q, lim in stated.items()) if stated else 0.0
    return ExactResult(
        x=x,
        objective=objective,
        lower_bound=t,
        worst_violation=max(0.0, worst),
        rounds=rounds,
        samples=int(sum(len(p) for p, _ in samples.values())),
        lp_iterations=lp_iters,
        seconds=time.perf_counter() - t0,
    )
