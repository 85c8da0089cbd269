"""A closed contour's arc chain seeded from the arc density, count by count, against the beam march.

The measurement behind :mod:`camcam.toolpath.arcseed`'s choices (which counts it tries, where the seed
starts, which curves it leaves to the march).  For every closed contour of the disc samples at δ = 0.1,
0.01, 0.002, 0.001 and 0.0005 mm (arcs mode, as ``benchmarks/run_nc.py --arcs``), the NC step is run with
the seed turned off and its beam march recorded (:func:`camcam.toolpath.arcspline.fit_arc_spline`: the
count it returns, the optimised chain included, and its CPU seconds); then, on the same curve and band,
chains of N arcs are seeded without a march (as :func:`camcam.toolpath.arcseed.seeded_chain` does, but every
N from ⌈∫⌉ − 1 to ⌈∫⌉ + 2 and each judged only at the end):

* the N_lb integrand of the optimal pattern, (|κ′| / 124.7·δ′)^⅓ per unit length, δ′ the band less
  :data:`~camcam.toolpath.arcpolish.PRINT_ALLOWANCE_STEPS` grid steps (the error of a G1 arc spline whose
  error is the Bernoulli pattern, :mod:`camcam.toolpath.arcspline`), at least |κ| / (0.9·max sweep) (a
  dwell's circle needs arcs for its sweep alone), is integrated over the turn: ``tot`` arcs;
* N joints are put at equal steps of that integral from the section's start (``shift`` × a step on),
  on the curve, along its tangent;
* the chain is optimised in the largest error (:func:`camcam.toolpath.arcchain.minimax_chain`, as
  :func:`camcam.toolpath.arcpolish.fewer_arcs` calls it), printed on the grid and measured both ways
  (:mod:`camcam.toolpath.arcprint`); it counts if it is within the band.

Each cell says N, whether the printed chain keeps within the band ("ok") and the CPU seconds of that
try.  ``ratio``: the Chebyshev copy's N_lb over the exact curve's (above 1.01 only on the noisy curves,
where the march does far better than any seed).  Run from the repository (about 6 min on two cores):

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
from camcam.geometry.curve import curvature_rate, speed
from camcam.nc import machine
from camcam.spec import load_spec
from camcam.toolpath.arcchain import CurveTable, OnCurve, minimax_chain
from camcam.toolpath.arcclose import quiet_stretches
from camcam.toolpath.arcpolish import PRINT_ALLOWANCE_STEPS
from camcam.toolpath.arcprint import measured_deviation, printed_spline
from camcam.toolpath.arcspline import SplineBudget, fit_arc_spline

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ("disc-translating-roller", "disc-translating-flat", "disc-oscillating-roller", "disc-oscillating-flat",
           "disc-groove", "optimize/run-table1", "lift/noisy-lift", "reverse/recovered-disc")
TOLERANCES = (0.1, 0.01, 0.002, 0.001, 0.0005)


def density(curve, a: float, b: float, allowed: float, max_sweep: float, n: int = 4096):
    """(parameters (n,), cumulative seeded arcs (n + 1,)): the optimal pattern's arcs per parameter, integrated."""
    t = np.linspace(a, b, n, endpoint=False)
    sp = speed(curve, t)
    d1, d2 = curve.evaluate(t, 1), curve.evaluate(t, 2)
    kappa = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / sp ** 3
    dens = np.maximum(np.cbrt(np.abs(curvature_rate(curve, t)) / (124.7 * allowed)), kappa / (0.9 * max_sweep)) * sp
    return t, np.concatenate([[0.0], np.cumsum(dens) * (b - a) / n])


def seeded(curve, a, b, band, kw, tab, t, cum, n_arcs: int, shift: float = 0.0) -> int | None:
    """Arcs of the printed chain seeded with ``n_arcs`` joints, or None if it leaves the band."""
    q, max_sweep, sag = kw["quantizer"], kw["max_sweep"], kw["sag"]
    allowed = band - PRINT_ALLOWANCE_STEPS * q.step_mm
    tot = cum[-1]
    tj = np.interp(np.mod((np.arange(n_arcs) + shift) / n_arcs * tot, tot), cum, np.concatenate([t, [b]]))
    start = OnCurve(curve, a, b, tj, np.zeros(n_arcs), np.zeros(n_arcs), 1)
    chain, err, gap = minimax_chain(start, tab, max_sweep=max_sweep, per_arc=24, hopeless=1.05 * allowed,
                                    enough=0.97 * allowed)
    if not (err <= allowed and gap <= 1e-3 * band):
        return None
    elements, _ = printed_spline(chain, tab, q, sag, max_sweep, band)
    if not elements or measured_deviation(elements, chain, tab) > band:
        return None
    return len(elements)


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
            machine(built, replace(spec.machining, tolerance_mm=tol, mode="arcs"), sample)
            for curve, a, b, band, kw, arcs, seconds in marches:
                _, integral = quiet_stretches(curve, a, b)
                ratio = integral / np.cbrt(192.0 * band) / kw["lower_bound"]
                tab = CurveTable(curve, a, b, 16384)
                allowed = band - PRINT_ALLOWANCE_STEPS * kw["quantizer"].step_mm
                t, cum = density(curve, a, b, allowed, kw["max_sweep"])
                cells = []
                for n in range(math.ceil(cum[-1]) - 1, math.ceil(cum[-1]) + 3):
                    t0 = time.process_time()
                    got = seeded(curve, a, b, band, kw, tab, t, cum, n)
                    cells.append(f"{n}: {'ok' if got else '–'} {time.process_time() - t0:.2f}")
                print(f"| {sample} | {tol:g} | {arcs} | {seconds:.2f} | {ratio:.4f} | {cum[-1]:.2f} | "
                      f"{'; '.join(cells)} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or SAMPLES)
