"""NC step on a real cam: blocks and seconds at δ = 0.1, 0.01, 0.001 mm, lines and arcs, beside the bounds;
then the whole ``camcam run`` time of every sample with ``[machining]``.

The first table machines ``samples/disc-translating-roller.toml`` (profile offset by the 8 mm tool
radius, linuxcnc post, 4 decimals) with the tolerance and mode replaced; ``max_dev`` is measured on the
printed program against the exact tool-centre curve.  Run from the repository:

    PYTHONPATH=. python benchmarks/run_nc.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from camcam.geometry.build import build_cam
from camcam.spec import load_spec
from camcam.toolpath.arcfit import line_estimate_blocks, lower_bound_blocks
from camcam.nc import machine

ROOT = Path(__file__).resolve().parents[1]


def blocks_table(sample: str = "disc-translating-roller") -> None:
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    curve = built.cam.offset_profile(spec.machining.tool_diameter_mm / 2)
    print(f"{sample}: tool-centre curve, post {spec.machining.post.name}")
    print("| δ mm | lines | ∫√(κ/8δ) | s | arcs | N_lb | 1.5·N_lb+2 per segment (blocks/target) | s | max dev lines, arcs mm |")
    print("|---|---|---|---|---|---|---|---|---|")
    for tol in (0.1, 0.01, 0.001):
        row = {}
        for mode in ("lines", "arcs"):
            m = replace(spec.machining, tolerance_mm=tol, mode=mode)
            t0 = time.perf_counter()
            r = machine(built, m, sample)
            row[mode] = (r, time.perf_counter() - t0)
        (rl, tl), (ra, ta) = row["lines"], row["arcs"]
        c = ra.contours[0]
        segs = ", ".join(f"{s.blocks}/{s.target:.1f}" for s in c.segments)
        print(f"| {tol:g} | {rl.line_blocks} | {line_estimate_blocks(curve, tol):.1f} | {tl:.1f} | "
              f"{ra.arc_blocks + ra.line_blocks} | {lower_bound_blocks(curve, tol):.2f} | {segs} | {ta:.1f} | "
              f"{rl.max_deviation_mm:.4f}, {ra.max_deviation_mm:.4f} |")


def run_times() -> None:
    specs = sorted(p for p in (ROOT / "samples").glob("*.toml") if "[machining]" in p.read_text())
    specs += sorted((ROOT / "samples" / "posts").glob("*.toml"))
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    print("\n| sample | camcam run s | NC figures |")
    print("|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for p in specs:
            t0 = time.perf_counter()
            out = subprocess.run([sys.executable, "-m", "camcam", "run", str(p), "-o", tmp], env=env,
                                 capture_output=True, text=True, check=True).stdout
            dt = time.perf_counter() - t0
            nc = next((line[4:] for line in out.splitlines() if line.startswith("NC: ")), "")
            print(f"| {p.relative_to(ROOT)} | {dt:.2f} | {nc} |")


if __name__ == "__main__":
    blocks_table()
    run_times()
