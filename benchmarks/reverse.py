"""Reverse design against known designs: seed 002's Table 1 example and a disc-cam round trip.

Run from the repository root: ``PYTHONPATH=. python benchmarks/reverse.py``.  Reads the
samples in ``samples/reverse/`` (made by ``make_points.py`` from camcam's forward geometry)
and prints the largest errors of the recovered motion at 360 cam angles against the design:
per degree of cam angle (deg, deg/deg, deg/deg² or mm, mm/deg, mm/deg²), as a fraction of the
design's peak, and in time units at the spec's rpm; plus the run time.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from camcam.reverse import ReverseOptions, design_motion, load_points, reverse_design
from camcam.spec import load_spec

HERE = Path(__file__).resolve().parents[1] / "samples" / "reverse"
ANG = np.arange(360.0)


def run(points: str, spec_name: str, **opts) -> None:
    spec = load_spec(HERE / spec_name)
    prog = spec.motion.program(spec.unit)
    pts = load_points(HERE / points)
    t0 = time.perf_counter()
    res = reverse_design(pts, spec.cam, spec.follower, ReverseOptions(**opts))
    dt = time.perf_counter() - t0
    err = [np.abs(res.motion(ANG, k) - design_motion(prog, spec.cam.kind, ANG, k)).max() for k in range(3)]
    peak = [np.abs(design_motion(prog, spec.cam.kind, ANG, k)).max() for k in range(3)]
    phys = [abs(float(prog.to_physical(err[k] * (180 / math.pi) ** k, k))) for k in range(3)]
    u = res.unit
    label = f"{points} [{res.motion.fit}{', smoothed' if res.motion.smoothed else ''}, slopes {opts.get('slopes', 'spline')}]"
    print(label)
    print(f"  per degree : lift {err[0]:.2e} {u}   velocity {err[1]:.2e} {u}/deg   acceleration {err[2]:.2e} {u}/deg²")
    print(f"  of peak    : {err[0] / peak[0]:.1e}   {err[1] / peak[1]:.1e}   {err[2] / peak[2]:.1e}")
    print(f"  at {prog.rpm:g} rpm  : {phys[0]:.2e} {prog.units[0]}   {phys[1]:.2e} {prog.units[1]}   {phys[2]:.2e} {prog.units[2]}   ({dt:.2f} s)")


def main() -> None:
    print("seed 002 reports 0.0023 deg, 0.001, 0.018 (180 points → 360)\n")
    run("seed002-points.csv", "seed002.toml", smoothing=False, slopes="central")
    run("seed002-points.csv", "seed002.toml", smoothing=False)
    run("seed002-points.csv", "seed002.toml")
    run("seed002-noisy-points.csv", "seed002.toml", smoothing=False)
    run("seed002-noisy-points.csv", "seed002.toml")
    run("disc-points.csv", "disc.toml", smoothing=False)
    run("disc-points.csv", "disc.toml")


if __name__ == "__main__":
    main()
