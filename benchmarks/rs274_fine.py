"""LinuxCNC's rs274 reads back the programs of the disc samples' contours fitted at fine tolerances.

For each case (sample @ tolerance) the disc sample is machined in arcs mode at that tolerance, its program
is written and interpreted by rs274 (Debian's linuxcnc-uspace; a program nobody here wrote), and every
finishing pass rs274 reports is measured against the exact tool-centre curve both ways
(:func:`camcam.toolpath.deviation.measure_deviation`), as ``tests/nc/test_job.py`` does for the samples at
their own tolerance.  The default cases are every disc sample with analytic motion at 0.1, 0.01, 0.002, 0.001
and 0.0005 mm (the 30 analytic cases of ``run_nc.py --arcs``): their closed contours are the seeded chain's
(:mod:`camcam.toolpath.arcseed`) where one of its counts fits, else the march's and its optimised chain's
(:mod:`camcam.toolpath.arcpolish`; until 2026-12-06 the defaults were the 12 cases of that chain).  Run from the
repository:

    PYTHONPATH=. python benchmarks/rs274_fine.py [SAMPLE@TOL ...]
"""

from __future__ import annotations

import sys
import tempfile
from dataclasses import replace
from pathlib import Path

from camcam.geometry.build import build_cam
from camcam.verify import checked
from camcam.spec import load_spec
from camcam.toolpath.deviation import measure_deviation
from camcam.verify.rs274 import feed_passes, print_margin_mm, rs274_available, run_rs274

ROOT = Path(__file__).resolve().parents[1]
CASES = tuple(f"{sample}@{tol}" for sample in ("disc-translating-roller", "disc-translating-flat",
                                                "disc-oscillating-roller", "disc-oscillating-flat", "disc-groove",
                                                "optimize/run-table1")
              for tol in ("0.1", "0.01", "0.002", "0.001", "0.0005"))


def check(case: str, folder: Path) -> bool:
    sample, tol = case.rsplit("@", 1)
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    result = checked(built, replace(spec.machining, tolerance_mm=float(tol), mode="arcs"), spec.name, spec.stock)
    path = folder / result.program_filename
    path.write_text(result.program.text)
    passes = feed_passes(run_rs274(path))
    margin = print_margin_mm(result.post.decimals)
    worst, ok = 0.0, len(passes) == len(result.passes)
    for (z, elements), p in zip(passes, result.passes):
        if not p.finishes:
            continue
        c = result.contours[p.contour]
        dev = measure_deviation(c.curve, elements[1:-1] if c.leads else elements, margin_mm=0.02 * float(tol))
        worst = max(worst, dev.max_deviation_mm)
        ok &= dev.max_deviation_mm <= float(tol) + margin
    arcs = sum(c.fit.arc_blocks + c.fit.line_blocks for c in result.contours)
    print(f"| {sample} | {tol} | {arcs} | {len(passes)} | {worst:.6f} | {'yes' if ok else 'NO'} |", flush=True)
    return ok


def main() -> int:
    if not rs274_available():
        print("rs274 (Debian linuxcnc-uspace) is not installed", file=sys.stderr)
        return 2
    print("| sample | δ mm | blocks | passes read | max deviation read back, mm | within δ |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as d:
        results = [check(case, Path(d)) for case in (sys.argv[1:] or CASES)]
    return 0 if all(results) else 1


if __name__ == "__main__":
    raise SystemExit(main())
