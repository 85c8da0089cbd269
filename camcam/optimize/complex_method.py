"""Box's Complex method with restarts, as seed 000 §2.3 steps (a)–(f) describe it.

(a) From the start point Ŝ_1 make M − 1 more vertices Ŝ_m = Ŝ_1 + D·R
    (R uniform in [−0.5, 0.5] per coordinate), M = 2·(free points); K_L = 0.
(b) Evaluate I at every vertex; worst Ŝ^(m), best Ŝ^(l).  K_L += 1 whenever
    the best vertex changes.
(c) Stop when I^(m) − I^(l) ≤ ε.  Otherwise, when K_L reaches M_L, restart:
    Ŝ_1 := Ŝ^(l) and go to (a).
(d) Centroid Ŝ^(w) of all vertices but the worst; trial point
    Ŝ^(c) = Ŝ^(m) + α·(Ŝ^(w) − Ŝ^(m)).
(e) If I^(c) < I^(m), the trial point replaces the worst; back to (b).
(f) Otherwise α := α·β while α ≥ ε' (the paper's text says ε here; ε' is
    meant: ε = 1e-12 would take 40 halvings); once α < ε', α is reset and the
    centroid is replaced by the best vertex, then (d) again.

Why the plain algorithm stalls, and what is decided here
--------------------------------------------------------
I is a maximum of many smooth pieces (eq. 6, and eq. 5 for active limits).
With α = 1.3 a reflected vertex lands 0.3 of its distance beyond the
centroid, so the complex shrinks by about that factor per sweep: from a
box of size D it makes progress of order D, then collapses onto a kink of
I.  Restarting (step (c)) is what moves it on, and what matters is the size
D of the new box.  The paper's D = 1 spans the whole range of S; a box that
size is thousands of times too coarse near the optimum (J grows like D/ΔT³),
so every restart at D = 1 just collapses back onto its start.  Decided here:

* **Restart size.**  A cycle is steps (a)–(f) from one start.  It ends at
  (c) (I^(m) − I^(l) ≤ ε, or K_L = M_L), when the complex has collapsed to a
  spread below ``collapse``·D (it then only refines a kink), or when the move
  towards the best vertex also fails down to α < ε'.  The next cycle restarts
  from the best vertex with D·``grow`` if the cycle improved the best I, else
  with D/``shrink`` (the first cycle uses the paper's D).  When D falls below
  ``D_min`` it is reset to the paper's D for another sweep; the run ends when
  a whole sweep brings no improvement, or after ``max_evaluations``.
* **Penalty scaling and weights** (eq. 4, the paper's ref. 8 idea).  The
  constraint terms are made relative and put on the objective's scale:
  k_cp = w_p·I_r(Ŝ_1)/h*_p, so w_p = 1 charges a 100 % excess as much as the
  whole start objective.  Every w_p starts at 1; after a cycle whose best
  vertex violates a limit by more than ``violation_tol`` (relative), the
  weight of the first such limit in priority order is multiplied by
  ``weight_factor`` (at most ``weight_max``).  The penalty is linear (exact),
  so a weight above the limit's Lagrange multiplier makes the constrained
  optimum the penalised one.
* **Coordinates** (``symmetric``, ``scaled``).  Steps (a)–(f) run in the
  coordinates of :mod:`camcam.optimize.coordinates`: for an asymmetric space,
  the mirror-symmetric curves (which always hold an optimum, by convexity);
  optionally (``scaled``, off by default) scaled so that the random box of
  step (a) is round in the minimised quantity.  The subspace is what brings
  Table 4 from +4.27 % to +0.69 % of the paper with the default settings
  (figures in that module and the README).  M = 2·(search coordinates).
* The start point Ŝ_1 is the caller's (see :mod:`camcam.optimize.start`).
* If the budget runs out while the best vertex violates a limit, the best
  vertex of the last cycle that met every limit is returned instead.

A seeded :class:`numpy.random.Generator` makes runs reproducible.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from camcam.optimize.coordinates import search_coordinates
from camcam.optimize.evaluation import EvaluationFunction

__all__ = ["ComplexSettings", "ComplexResult", "complex_method"]


@dataclass(frozen=True, kw_only=True)
class ComplexSettings:
    """Parameters of the Complex method (α … M_L: the paper's values)."""

    alpha: float = 1.3
    beta: float = 0.5
    eps: float = 1e-12
    eps_prime: float = 1e-4
    D: float = 1.0
    restart_every: int = 50  # M_L
    max_evaluations: int = 40_000
    collapse: float = 1e-3
    grow: float = 2.0
    shrink: float = 3.0
    D_min: float = 1e-10
    weight_factor: float = 10.0
    weight_max: float = 1e3
    violation_tol: float = 1e-9
    scaled: bool = False  # measured: helps Table 4, costs Table 3 N=4, 5 (see camcam.optimize.coordinates)
    symmetric: bool = True


@dataclass(frozen=True, kw_only=True)
class ComplexResult:
    """The best vertex found and what it took."""

    x: np.ndarray
    value: float
    objective: float
    violations: tuple[float, ...]
    weights: tuple[float, ...]
    evaluations: int
    iterations: int
    restarts: int
    converged: bool
    seconds: float


def complex_method(
    f: EvaluationFunction,
    x1,
    seed: int = 1,
    settings: ComplexSettings = ComplexSettings(),
    progress: Callable[[int, float], None] | None = None,
) -> ComplexResult:
    """Minimise eq. 4 of ``f`` from the start point ``x1``.

    ``progress(evaluations, best objective)`` is called after every cycle.
    ``converged`` is true when the run ended because a whole sweep of D
    brought no improvement (rather than on the evaluation budget).

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> p = Problem(5, 4, True, "A", limits=(("V", 2.0), ("J", 61.4)))
    >>> f = EvaluationFunction(p)
    >>> a = complex_method(f, p.space.initial_free(), 3, ComplexSettings(max_evaluations=300))
    >>> b = complex_method(f, p.space.initial_free(), 3, ComplexSettings(max_evaluations=300))
    >>> a.value == b.value and a.evaluations == 300
    True
    """
    s = settings
    t0 = time.perf_counter()
    rng = np.random.default_rng(seed)
    coords = search_coordinates(f, x1, s.scaled, s.symmetric)
    x1 = coords.start
    nf = coords.size
    M = 2 * nf
    limits = np.array([lim for _, lim in f.problem.limits])
    weights = np.ones(len(limits))
    evals = 0

    def terms(x):
        nonlocal evals
        evals += 1
        return f.terms(coords.free(x))

    ic1, ir1 = terms(x1)
    scale = max(ir1, 1e-12) / limits if limits.size else limits

    def value(ic, ir) -> float:
        return float(ir + (weights * scale * ic).sum())

    budget_left = lambda: evals < s.max_evaluations  # noqa: E731
    best = (x1, ic1, ir1)
    feasible = best if not (ic1 / limits > settings.violation_tol).any() else None
    start, D = x1, s.D
    iterations = restarts = 0
    sweep_improved = converged = False
    while budget_left():
        # (a) the complex around the start point
        X = start + D * rng.uniform(-0.5, 0.5, size=(M, nf))
        X[0] = start
        T = [terms(x) for x in X[: min(M, s.max_evaluations - evals)]]
        if len(T) < M:
            break
        IC = np.array([t[0] for t in T]).reshape(M, -1)
        IR = np.array([t[1] for t in T])
        F = np.array([value(a, b) for a, b in zip(IC, IR)])
        F_start = F[0]
        l = int(np.argmin(F))
        KL = 0
        while budget_left():
            m = int(np.argmax(F))  # (b)
            if F[m] - F[l] <= s.eps or KL >= s.restart_every:  # (c)
                break
            if float(np.abs(X - X[l]).max()) <= s.collapse * D:
                break
            iterations += 1
            centroid = (X.sum(axis=0) - X[m]) / (M - 1)  # (d)
            target, alpha, towards_best, stuck = centroid, s.alpha, False, False
            while budget_left():
                xc = X[m] + alpha * (target - X[m])
                ic, ir = terms(xc)
                fc = value(ic, ir)
                if fc < F[m]:  # (e)
                    X[m], IC[m], IR[m], F[m] = xc, ic, ir, fc
                    if fc < F[l]:
                        l = m
                        KL += 1
                    break
                if alpha >= s.eps_prime:  # (f)
                    alpha *= s.beta
                elif not towards_best:
                    target, alpha, towards_best = X[l], s.alpha, True
                else:
                    stuck = True
                    break
            if stuck:
                break
        improved = F_start - F[l] > s.eps * max(1.0, abs(F[l]))
        start = X[l].copy()
        best = (start, IC[l].copy(), float(IR[l]))
        restarts += 1
        if progress is not None:
            progress(evals, best[2])
        violated = np.nonzero(IC[l] / limits > s.violation_tol)[0] if limits.size else []
        if not len(violated):
            feasible = best
        if len(violated):
            p = violated[0]
            weights[p] = min(s.weight_max, weights[p] * s.weight_factor)
            sweep_improved = True  # the weights changed: I values are not comparable
        sweep_improved |= improved
        D = D * s.grow if improved else D / s.shrink
        D = min(D, s.D)
        if D < s.D_min:
            if not sweep_improved:
                converged = True
                break
            D, sweep_improved = s.D, False
    if feasible is not None and (best[1] / limits > s.violation_tol).any():
        best = feasible  # the run ended on an infeasible vertex: the last feasible best instead
    x, ic, ir = best
    return ComplexResult(
        x=coords.free(x),
        value=value(ic, ir),
        objective=ir,
        violations=tuple(float(v) for v in f.relative_violation(ic)),
        weights=tuple(float(w) for w in weights),
        evaluations=evals,
        iterations=iterations,
        restarts=restarts,
        converged=converged,
        seconds=time.perf_counter() - t0,
    )
