"""The ``[optimize]`` table: an optimal B-spline cam curve (seed 000).

```toml
[optimize]
degree = 5            # odd, 3 … 9
segments = 7          # N: knot intervals of [0, 0.5] (symmetric) or [0, 1]
symmetric = true
method = "exact"      # or "complex" (the paper's Box Complex method)
minimize = "A"        # "V", "A" or "J": the largest |.| over the rise
seed = 1              # random numbers of the Complex method
start = "auto"        # Complex start: a catalog law projected, or "auto" (best projection)
evaluations = 40000   # Complex method budget (evaluations of I)
[optimize.limits]     # upper bounds on the largest |V|, |A|, |J| (priority = order written)
V = 2.0
J = 61.4
```
"""

from __future__ import annotations

from dataclasses import dataclass

from camcam.errors import SpecError
from camcam.motion.catalog import LAWS
from camcam.optimize.evaluation import LINEAR_QUANTITIES, Problem
from camcam.optimize.space import MAX_DEGREE, MAX_SEGMENTS
from camcam.spec.reader import Table, fmt

__all__ = ["OptimizeSpec", "read_optimize", "METHODS"]

METHODS = ("exact", "complex")


@dataclass(frozen=True, kw_only=True)
class OptimizeSpec:
    """The validated ``[optimize]`` table."""

    problem: Problem
    method: str
    seed: int
    start: str = "auto"
    evaluations: int = 40_000

    def as_dict(self) -> dict:
        p = self.problem
        return {
            "degree": p.degree,
            "segments": p.segments,
            "symmetric": p.symmetric,
            "method": self.method,
            "minimize": p.minimize,
            "seed": self.seed,
            "start": self.start,
            "evaluations": self.evaluations,
            "limits": dict(p.limits),
        }


def read_optimize(t: Table) -> OptimizeSpec:
    """Validate the ``[optimize]`` table ``t``."""
    degree = t.integer("degree", 5, minimum=3, maximum=MAX_DEGREE)
    t.check("degree", degree % 2 == 1, f"expected an odd integer, got {degree}")
    segments = t.integer("segments", 7, minimum=1, maximum=MAX_SEGMENTS)
    symmetric = t.boolean("symmetric", True)
    method = t.string("method", "exact", choices=METHODS)
    minimize = t.string("minimize", "A", choices=LINEAR_QUANTITIES)
    seed = t.integer("seed", 1, minimum=0)
    start = t.string("start", "auto", choices=("auto", *LAWS))
    evaluations = t.integer("evaluations", 40_000, minimum=100, maximum=10_000_000)
    lt = t.table("limits", None)
    limits = []
    if lt is not None:
        for q in lt.data:
            if q not in LINEAR_QUANTITIES:
                continue  # reported by lt.done() as an unknown key
            limits.append((q, lt.number(q, minimum=0, inclusive=False)))
        lt.done()
    try:
        problem = Problem(degree, segments, symmetric, minimize, limits=tuple(limits))
    except ValueError as err:
        raise SpecError(t.key_path("segments"), f"{fmt(segments)}: {err}") from None
    return OptimizeSpec(problem=problem, method=method, seed=seed, start=start, evaluations=evaluations)
