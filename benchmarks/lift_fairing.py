"""Compare the two fairing methods on samples/lift/noisy-lift.csv against its known truth.

Run from the repository root: ``PYTHONPATH=. python benchmarks/lift_fairing.py``.
Prints, per method, the lift error against the truth (RMS and max, µm), the
acceleration error of the periodic spline through the result (max, mm/deg², on
a 0.25° grid), the roughness and the run time.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "samples" / "lift"))

from make_noisy_lift import noisy_table, truth_program  # noqa: E402

from camcam.lifttable.badpoints import find_bad_points  # noqa: E402
from camcam.lifttable.fairing import midpoint_fairing, smoothing_fairing  # noqa: E402
from camcam.lifttable.interpolate import interpolate  # noqa: E402
from camcam.lifttable.roughness import difference_quotients  # noqa: E402
from camcam.lifttable.table import LiftTable  # noqa: E402


def main() -> None:
    ang, truth, meas = noisy_table()
    prog = truth_program()
    fine = np.arange(0.0, 360.0, 0.25)
    a_true = prog.lift(np.radians(fine), 2) * math.radians(1.0) ** 2
    raw = LiftTable(tuple(ang), tuple(meas), resolution=1e-5)
    t0 = time.perf_counter()
    rep = find_bad_points(raw)
    print(f"bad points: {rep.angles_deg}  σ̂ = {rep.noise_sigma * 1000:.2f} µm  ({time.perf_counter() - t0:.3f} s)")
    print(f"{'table':24s} {'rms µm':>8s} {'max µm':>8s} {'max |ΔA| mm/deg²':>17s} {'roughness':>10s} {'rounds':>6s} {'s':>6s}")

    def row(name, table, rounds="", dt=0.0):
        f = interpolate(table.x, table.y, "periodic")
        e = table.y - truth
        ea = np.max(np.abs(f(fine, 2) - a_true))
        print(f"{name:24s} {np.sqrt(np.mean(e**2)) * 1e3:8.2f} {np.max(np.abs(e)) * 1e3:8.2f} {ea:17.2e} "
              f"{difference_quotients(table).max_abs_second:10.2e} {rounds!s:>6s} {dt:6.3f}")

    row("as read", raw)
    row("bad points removed", rep.table)
    for xi in (1e-3, 1e-4, 1e-5):
        t0 = time.perf_counter()
        m = midpoint_fairing(rep.table, "periodic", xi)
        row(f"mid-point ξ={xi:g} mm", m.table, m.iterations, time.perf_counter() - t0)
    t0 = time.perf_counter()
    s = smoothing_fairing(rep.table)
    row("smoothing (GCV)", s.table, 1, time.perf_counter() - t0)
    print(f"truth: max |A| = {np.max(np.abs(a_true)):.2e} mm/deg²; noise σ = 3 µm")


if __name__ == "__main__":
    main()
