"""Seed 000's Tables 1-4: paper value, Complex method, exact LP optimum, and times.

Run: PYTHONPATH=. python benchmarks/optimize_tables.py [--evaluations N]

Also prints the continuous optimum of the Table 1 problem and the N at which
the exact B-spline optimum gets within 0.25 % of it.

Continuous optimum (Table 1: minimise max|A| with |V| <= 2, |J| <= Jm = 61.4,
S(0)=0, S(1)=1, rest to rest).  Time-optimal control with bounded jerk is
bang-bang in J: A rises at +Jm for τ = a/Jm to a, holds a for c, falls at −Jm
for 2τ to −a, holds −a for c, returns to 0 in τ (4τ + 2c = 1, no cruise
phase: a cruise at constant V would need V > 2, see below).  The accelerating
half lasts D = 2τ + c = 1/2 and its V curve is point-symmetric about Vp/2,
so each half covers Vp·D/2 and S(1) = Vp·D = 1 → Vp = 2 exactly (the V limit
holds with equality but costs nothing); Vp = a(τ + c) = a(1/2 − a/Jm) = 2 gives
a² / Jm − a / 2 + 2 = 0, smallest root

    a* = Jm / 4 · (1 − sqrt(1 − 32 / Jm)) = 4.72821 for Jm = 61.4.

A cruise phase of length d > 0 gives D = (1 − d)/2 < 1/2 and
S(1) = Vp·(D + d) = 1, so Vp = 1/(1 − D) > 2: the V limit forbids it.
Every B-spline curve is a curve, so its optimum is >= a*; N → ∞ reaches it.
"""

from __future__ import annotations

import argparse
import math
import time

from camcam.optimize.complex_method import ComplexSettings
from camcam.optimize.evaluation import EvaluationFunction, Problem
from camcam.optimize.exact import exact_optimum
from camcam.optimize.multistart import multistart
from camcam.optimize.start import ranked_starts

T1 = (("V", 2.0), ("J", 61.4))
ROWS = [
    ("Table 1, N=7", Problem(5, 7, True, "A", limits=T1), 4.869),
    ("Table 2, N=7", Problem(5, 7, True, "J", limits=(("V", 1.76), ("A", 5.53))), 66.439),
    *[(f"Table 3, N={N}", Problem(5, N, True, "A", limits=T1), p) for N,
      p in zip(range(3, 11), (5.581, 5.177, 5.077, 4.893, 4.869, 4.867, 4.865, 4.864))],
    ("Table 4, N=18", Problem(5, 18, False, "A", limits=(("V", 1.91), ("J", 81.0))), 4.657),
]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--evaluations", type=int, default=40_000, help="Complex method budget per row")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--rows", help="comma-separated row numbers (0-based) to run; default all")
    ap.add_argument("--no-bound", action="store_true", help="skip the continuous-optimum study")
    args = ap.parse_args()
    chosen = range(len(ROWS)) if args.rows is None else [int(i) for i in args.rows.split(",")]
    print(f"| row | paper | start law | Complex (≤ {args.evaluations} eval.) | vs paper | evaluations | worst viol. | time s | exact | worst viol. | time s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for label, problem, paper in (ROWS[i] for i in chosen):
        f = EvaluationFunction(problem)
        c, law, ran = multistart(f, ranked_starts(f), args.seed, ComplexSettings(max_evaluations=args.evaluations))
        if len(ran) > 1:
            law = f"{law} (of {', '.join(ran)})"
        e = exact_optimum(problem)
        print(
            f"| {label} | {paper:.3f} | {law} | {c.objective:.4f} | {100 * (c.objective / paper - 1):+.2f} % | {c.evaluations} "
            f"| {max(c.violations):.1e} | {c.seconds:.1f} "
            f"| {e.objective:.4f} | {e.worst_violation:.1e} | {e.seconds:.3f} |",
            flush=True,
        )
    if args.no_bound:
        return
    jm = 61.4
    a_star = jm / 4 * (1 - math.sqrt(1 - 32 / jm))
    print(f"\ncontinuous optimum of Table 1: a* = {a_star:.5f}")
    within = None
    for N in (7, 10, 15, 20, 25, 30, 35, 40, 60, 80):
        t = time.perf_counter()
        e = exact_optimum(Problem(5, N, True, "A", limits=T1))
        gap = e.objective / a_star - 1
        print(f"N={N:3d}: exact {e.objective:.5f}  (+{100 * gap:.3f} %)  {time.perf_counter() - t:.2f} s", flush=True)
        if within is None and gap <= 0.0025:
            within = N
    print(f"first N in this list within 0.25 %: {within}")


if __name__ == "__main__":
    main()
