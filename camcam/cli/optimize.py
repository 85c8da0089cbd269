"""``camcam optimize SPEC [-o LAW.json] [--json]``: an optimal B-spline cam curve."""

from __future__ import annotations

import sys
from pathlib import Path

from camcam.cli.commands import help_of
from camcam.cli.output import print_json, to_json
from camcam.cli.progress import Progress, add_progress_flag
from camcam.errors import SpecError
from camcam.export.files import atomic_write
from camcam.optimize.bspline_law import BSplineLaw
from camcam.optimize.lawfile import law_document
from camcam.spec import load_spec
from camcam.spec.optimize import OptimizeSpec

__all__ = ["register", "optimize", "LIMIT_NOT_MET"]

#: Exit status when the Complex method's law is written but exceeds a limit some law meets.
LIMIT_NOT_MET = 3


def register(sub) -> None:
    p = sub.add_parser("optimize", help=help_of("optimize"))
    p.add_argument("spec", help="spec file (TOML) with an [optimize] table")
    p.add_argument("-o", "--output", help="write the law as JSON to this file (replaced in one step if it exists)")
    p.add_argument("--json", action="store_true", help="print the law as one JSON object")
    add_progress_flag(p)
    p.set_defaults(func=run)


def optimize(opt: OptimizeSpec) -> tuple[BSplineLaw, dict]:
    """Run the spec's method; the law and the solver figures."""
    problem = opt.problem
    # each method imports its own modules: `camcam optimize` (exact) is meant to take at most 0.5 s
    if opt.method == "exact":
        r = _exact(problem)
        solver = {
            "method": "exact",
            "lp_rounds": r.rounds,
            "iterations": r.lp_iterations,
            "evaluations": r.rounds,
            "samples": r.samples,
            "lower_bound": r.lower_bound,
            "worst_violation": r.worst_violation,
            "seconds": r.seconds,
        }
        x = r.x
    else:
        from camcam.optimize.complex_method import ComplexSettings
        from camcam.optimize.evaluation import EvaluationFunction
        from camcam.optimize.multistart import multistart
        from camcam.optimize.start import ranked_starts, start_point

        settings = ComplexSettings(max_evaluations=opt.evaluations)
        f = EvaluationFunction(problem)
        starts = ranked_starts(f) if opt.start == "auto" else [start_point(f, opt.start)]
        r, start_law, ran = multistart(f, starts, opt.seed, settings)
        solver = {
            "method": "complex",
            "seed": opt.seed,
            "start": start_law,
            "starts_run": list(ran),
            "evaluations": r.evaluations,
            "iterations": r.iterations,
            "restarts": r.restarts,
            "converged": r.converged,
            "weights": list(r.weights),
            "worst_violation": max(r.violations, default=0.0),
            "seconds": r.seconds,
        }
        x = r.x
        law = BSplineLaw.from_free(problem.space, x)
        if solver["worst_violation"] > settings.violation_tol:
            solver["limits_met"] = False
            solver["fail"] = _complex_infeasible(problem, law, r)
        return law, solver
    return BSplineLaw.from_free(problem.space, x), solver


def _exact(problem):
    """The exact optimum; the spec's bad sizes and limits as one line naming the key (exit 2)."""
    from camcam.optimize.exact import InfeasibleProblem, ProblemTooLarge, exact_optimum

    try:
        return exact_optimum(problem)
    except InfeasibleProblem as err:
        raise SpecError("optimize.limits", f"{err} (degree {problem.degree}, {problem.segments} segments)") from None
    except ProblemTooLarge as err:
        raise SpecError("optimize.segments", str(err)) from None


def _complex_infeasible(problem, law: BSplineLaw, r) -> str:
    """The Complex method ended outside a limit: decided by the exact LP, as ``method = "exact"`` decides it.

    Raises :class:`SpecError` naming ``optimize.limits`` (exit 2, nothing written) when no curve of the
    space meets the limits; otherwise returns the FAIL line's text (the law is written and the command
    exits 3): the Complex method missed, within its budget, a law that meets them.
    """
    from camcam.optimize.exact import InfeasibleProblem, ProblemTooLarge, exact_optimum

    k = max(range(len(r.violations)), key=lambda i: r.violations[i])
    q, limit = problem.limits[k]
    found = getattr(law.characteristics(), f"{q}m")
    over = (f"the Complex method's best law has {q}m {found:.6g} over {q} = {limit:g} "
            f"(+{100.0 * r.violations[k]:.1f} %) after {r.evaluations} evaluations")
    try:
        exact = exact_optimum(problem)
    except InfeasibleProblem as err:
        raise SpecError("optimize.limits", f"{err} (degree {problem.degree}, {problem.segments} segments); {over}") from None
    except ProblemTooLarge:
        return f"{over}; whether any law meets the limits is not decided (the exact LP is over its size limit)"
    return (f"{over}; a law within the limits exists (method = \"exact\": {problem.minimize}m {exact.objective:.6g}): "
            f"raise optimize.evaluations or use method = \"exact\"")


def run(args) -> int:
    progress = Progress.from_args(args)
    spec = load_spec(args.spec)
    opt = spec.need("optimize", "optimize")
    with progress.step(f"optimize ({opt.method})"):
        law, solver = optimize(opt)
    doc = law_document(law, problem=opt.as_dict(), solver=solver)
    if args.output:
        atomic_write(Path(args.output), to_json(doc) + "\n", getattr(args, "disk_log", None))
    if args.json:
        print_json(doc)
    else:
        print(f"{opt.method}: degree {law.degree}, {law.segments} segments, {'symmetric' if law.symmetric else 'asymmetric'}")
        print(f"Vm {doc['Vm']:.6f}  Am {doc['Am']:.6f}  Jm {doc['Jm']:.6f}  (Jmax {doc['Jmax']:+.6f}, Jmin {doc['Jmin']:+.6f})")
        print(f"{solver['evaluations']} evaluations in {solver['seconds']:.3f} s, worst limit violation {solver['worst_violation']:.2e}")
        if args.output:
            print(f"wrote {args.output}")
    if "fail" in solver:  # the Complex method ended outside a limit that some law meets: written, exit 3
        print(f"camcam: FAIL: {solver['fail']}", file=sys.stderr)
        return LIMIT_NOT_MET
    return 0
