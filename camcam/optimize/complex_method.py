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

Two details the paper leaves open, decided here:

* If the move towards the best vertex also fails down to α < ε', the complex
  is stuck; it restarts from the best vertex as in (c).  Without this the
  loop of (d)–(f) need not end.
* Constraint weights (eq. 4, the paper's ref. 8 idea): every k_cp starts at 1.
  At each restart and at convergence, if the best vertex violates a limit by
  more than ``violation_tol`` (relative), the weight of the first such limit in
  priority order is multiplied by ``weight_factor``; a converged run with a
  violated limit restarts instead of stopping.  The penalty is linear (eq. 5),
  so a finite weight makes the constrained optimum the penalised one.

A seeded :class:`numpy.random.Generator` makes runs reproducible; the run
also stops after ``max_evaluations`` evaluations of I.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from camcam.optimize.evaluation import EvaluationFunction

__all__ = ["ComplexSettings", "ComplexResult", "complex_method"]


@dataclass(frozen=True)
class ComplexSettings:
    """Parameters of the Complex method (defaults: the paper's values)."""

    alpha: float = 1.3
    beta: float = 0.5
    eps: float = 1e-12
    eps_prime: float = 1e-4
    D: float = 1.0
    restart_every: int = 50  # M_L
    max_evaluations: int = 400_000
    weight_factor: float = 10.0
    violation_tol: float = 1e-6
    restart_scale: float = 4.0
    restart_floor: float = 1e-4
    patience: int = 12


@dataclass(frozen=True)
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

    ``progress(evaluations, best I)`` is called about every 1000 evaluations.

    Examples
    --------
    >>> from camcam.optimize.evaluation import Problem
    >>> p = Problem(5, 4, True, "A", (("V", 2.0), ("J", 61.4)))
    >>> f = EvaluationFunction(p)
    >>> a = complex_method(f, p.space.initial_free(), 3, ComplexSettings(max_evaluations=300))
    >>> b = complex_method(f, p.space.initial_free(), 3, ComplexSettings(max_evaluations=300))
    >>> a.value == b.value and a.evaluations == 300
    True
    """
    s = settings
    t0 = time.perf_counter()
    rng = np.random.default_rng(seed)
    x1 = np.asarray(x1, dtype=float)
    nf = x1.size
    M = 2 * nf
    weights = np.ones(len(f.problem.limits))
    count = {"evals": 0}

    def terms(x):
        count["evals"] += 1
        if progress is not None and count["evals"] % 1000 == 0:
            progress(count["evals"], best_value)
        return f.terms(x)

    start, D = x1, s.D
    idle = 0
    iterations = restarts = 0
    converged = False
    best_value = np.inf
    best = (x1, *terms(x1))
    budget_left = lambda: count["evals"] < s.max_evaluations  # noqa: E731

    while budget_left():
        # (a) the complex around the start point
        X = start + D * rng.uniform(-0.5, 0.5, size=(M, nf))
        X[0] = start
        T = [terms(x) for x in X[: min(M, s.max_evaluations - count["evals"] + 1)]]
        if len(T) < M:
            break
        IC = np.array([t[0] for t in T]).reshape(M, -1)
        IR = np.array([t[1] for t in T])
        F = IC @ weights + IR
        l = int(np.argmin(F))
        best_value = cycle_start = F[l]
        KL = 0
        restart = False
        while budget_left() and not restart:
            # (b)
            m = int(np.argmax(F))
            # (c)
            if F[m] - F[l] <= s.eps:
                if _raise_weight(weights, f.relative_violation(IC[l]), s):
                    restart = True
                elif cycle_start - F[l] > s.eps:  # this cycle improved: look again around the best
                    restart, idle = True, 0
                elif idle + 1 < s.patience:  # no improvement: try a fresh complex
                    restart, idle = True, idle + 1
                else:
                    converged = True
                break
            if KL >= s.restart_every:
                _raise_weight(weights, f.relative_violation(IC[l]), s)
                restart = True
                break
            # (d)–(f)
            iterations += 1
            centroid = (X.sum(axis=0) - X[m]) / (M - 1)
            target, alpha, towards_best = centroid, s.alpha, False
            while budget_left():
                xc = X[m] + alpha * (target - X[m])
                ic, ir = terms(xc)
                fc = float(ic @ weights + ir)
                if fc < F[m]:  # (e)
                    X[m], IC[m], IR[m], F[m] = xc, ic, ir, fc
                    if fc < F[l]:
                        l = m
                        best_value = fc
                        KL += 1
                    break
                if alpha >= s.eps_prime:  # (f)
                    alpha *= s.beta
                elif not towards_best:
                    target, alpha, towards_best = X[l], s.alpha, True
                else:  # stuck: restart from the best vertex
                    _raise_weight(weights, f.relative_violation(IC[l]), s)
                    restart = True
                    break
        best = (X[l].copy(), IC[l].copy(), float(IR[l]))
        if converged:
            break
        restarts += 1
        start = X[l].copy()
        # Restart at the scale the complex had reached (at most D, at least D·restart_floor).
        spread = float(np.abs(X - X[l]).max())
        D = min(s.D, max(s.restart_scale * spread, s.D * s.restart_floor ** ((idle % 4) / 3)))
    x, ic, ir = best
    return ComplexResult(
        x=x,
        value=float(ic @ weights + ir),
        objective=ir,
        violations=tuple(float(v) for v in f.relative_violation(ic)),
        weights=tuple(float(w) for w in weights),
        evaluations=count["evals"],
        iterations=iterations,
        restarts=restarts,
        converged=converged,
        seconds=time.perf_counter() - t0,
    )


def _raise_weight(weights: np.ndarray, rel_violation: np.ndarray, s: ComplexSettings) -> bool:
    """Raise the weight of the first violated limit (priority order); True if one was raised."""
    for p, v in enumerate(rel_violation):
        if v > s.violation_tol:
            weights[p] *= s.weight_factor
            return True
    return False
