"""Second-fitting benchmark: blocks and seconds at δ = 0.1, 0.01, 0.001 mm, lines and arcs, beside N_lb.

The curve is a cam-like closed curve r(θ) = 40 + s(θ) mm with the demo motion
(modified-sine rise 20 mm over 120°, dwell, cycloidal return over 120°, dwell);
exact derivatives come from ``MotionProgram.lift``.  Run from the repository:

    PYTHONPATH=. python benchmarks/fitting.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from camcam.toolpath.arcfit import fit_contour  # noqa: E402
from nc_curves import polar_cam  # noqa: E402


def main() -> None:
    curve = polar_cam()
    print(f"{'delta_mm':>9} {'mode':>5} {'blocks':>6} {'bound':>8} {'ratio':>6} {'max_dev_mm':>11} {'seconds':>8}  per piece (blocks / 1.5·N_lb+2)")
    for tol in (0.1, 0.01, 0.001):
        for mode in ("lines", "arcs"):
            t0 = time.perf_counter()
            fit = fit_contour(curve, tol, mode=mode, max_sweep_deg=120.0)
            dt = time.perf_counter() - t0
            n = len(fit.elements)
            per = " ".join(f"{b}/{1.5 * lb + 2:.1f}" for b, lb in zip(fit.piece_blocks, fit.piece_lower_bounds)) \
                if mode == "arcs" else ""
            print(f"{tol:>9g} {mode:>5} {n:>6d} {fit.lower_bound:>8.2f} {n / fit.lower_bound:>6.2f} "
                  f"{fit.max_deviation_mm:>11.6f} {dt:>8.2f}  {per}")
    print("bound: N_lb = ∫(|κ′|/192δ)^⅓ ds for arcs, ∫√(|κ|/8δ) ds for lines")


if __name__ == "__main__":
    main()
