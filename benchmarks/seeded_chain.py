"""A closed contour's arc chain seeded from the arc density, count by count, against the beam march.

The measurement behind :mod:`camcam.toolpath.arcseed`'s choices (which counts it tries, where the seed
starts, which curves it leaves to the march).  For every closed contour of the disc samples at δ = 0.1,
0.01, 0.002, 0.001 and 0.0005 mm (arcs mode, as ``benchmarks/run_nc.py --arcs``), the NC step is run with
the seed turned off and its beam march recorded (:func:`camcam.toolpath.arcspline.fit_arc_spline`: the
count it returns, the optimised chain included, and its CPU seconds); then, on the same curve and band,
chains of N arcs are seeded without a march, each as :func:`camcam.toolpath.arcseed.seeded_chain` seeds one
(:func:`~camcam.toolpath.arcseed.seeded_count`, its give-ups included), but every N from ⌈∫⌉ − 1 to ⌈∫⌉ + 2:
joints at equal steps of the optimal pattern's arc density (:func:`~camcam.toolpath.arcseed.seed_density`)
from the section's start, optimised in the largest error, printed on the grid and measured both ways; a
count fits if the printed chain is within the band.

Each cell says N, whether the printed chain keeps within the band ("ok") and the CPU seconds of that
try.  ``ratio``: the Chebyshev copy's N_lb over the exact curve's (above 1.01 only on the noisy curves,
where the march does far better than any seed).  Run from the repository (about a minute on two cores):

    PYTHONPATH=. python benchmarks/seeded_chain.py [SAMPLE ...]
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

import camcam.toolpath.arcfit as arcfit
from camcam.geometry.build import build_cam
from camcam.verify import checked
from camcam.spec import load_spec
from camcam.toolpath.arcchain import CurveTable
from camcam.toolpath.arcclose import quiet_stretches
from camcam.toolpath.budget import DEFAULT_BUDGET
from camcam.toolpath.arcseed import seed_density, seeded_count
from camcam.toolpath.arcspline import SplineBudget, fit_arc_spline

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ("disc-translating-roller", "disc-translating-flat", "disc-oscillating-roller", "disc-oscillating-flat",
           "disc-groove", "optimize/run-table1", "lift/noisy-lift", "reverse/recovered-disc")
TOLERANCES = (0.1, 0.01, 0.002, 0.001, 0.0005)


def main(samples) -> None:
    marches = []

    def recorded(curve, a, b, band, **kw):
        t0 = time.process_time()
        unseeded = replace(kw.get("budget", SplineBudget()), seeded=False)
        spline = fit_arc_spline(curve, a, b, band, **{**kw, "budget": unseeded})
        if kw.get("closed"):
            marches.append((curve, a, b, band, kw, len(spline.elements), time.process_time() - t0))
        return spline

    arcfit.fit_arc_spline = recorded  # a benchmark-only hook: the NC step itself is unchanged
    print("| sample | δ mm | march arcs | march s | ratio | tot | seeded N: ok?, s |")
    print("|---|---|---|---|---|---|---|")
    for sample in samples:
        spec = load_spec(ROOT / "samples" / f"{sample}.toml")
        built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
        for tol in TOLERANCES:
            marches.clear()
            checked(built, replace(spec.machining, tolerance_mm=tol, mode="arcs"), sample)
            for curve, a, b, band, kw, arcs, seconds in marches:
                _, integral = quiet_stretches(curve, a, b)
                ratio = integral / np.cbrt(192.0 * band) / kw["lower_bound"]
                tab = CurveTable(curve, a, b, 16384)
                q, max_sweep, sag = kw["quantizer"], kw["max_sweep"], kw["sag"]
                density = seed_density(curve, a, b, DEFAULT_BUDGET.chain_band_mm(band, q), max_sweep)
                total = float(density[1][-1])
                cells = []
                for n in range(math.ceil(total) - 1, math.ceil(total) + 3):
                    t0 = time.process_time()
                    got = seeded_count(curve, a, b, band, q, max_sweep, sag, n, density, tab)
                    cells.append(f"{n}: {'ok' if got else '–'} {time.process_time() - t0:.2f}")
                print(f"| {sample} | {tol:g} | {arcs} | {seconds:.2f} | {ratio:.4f} | {total:.2f} | "
                      f"{'; '.join(cells)} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or SAMPLES)
