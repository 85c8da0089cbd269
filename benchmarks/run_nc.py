"""NC step on real cams: arcs against the lower bound on every disc sample; lines and arcs on the default
sample; then the whole ``camcam run`` time of every sample with ``[machining]``.

The first table fits every contour of every disc sample in arcs mode at δ = 0.1, 0.01, 0.002, 0.001 and
0.0005 mm (each sample's own post and tool, its tolerance and mode replaced) and prints, per contour, the
arcs, the G1 lines among the blocks (nearly straight arcs print as lines), N_lb = ∫(|κ′|/192δ)^⅓ ds, the
ratio blocks / N_lb, the issue-13 target 1.2·N_lb + 4, the seconds of the contour fit (the arc-spline march
and the measurement of the printed path) and of the whole NC step.

The second table machines ``samples/disc-translating-roller.toml`` (profile offset by the 8 mm tool
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
from camcam.verify import checked

ROOT = Path(__file__).resolve().parents[1]


DISC_SAMPLES = ("disc-translating-roller", "disc-translating-flat", "disc-oscillating-roller",
                "disc-oscillating-flat", "disc-groove", "optimize/run-table1", "lift/noisy-lift",
                "reverse/recovered-disc")
TOLERANCES = (0.1, 0.01, 0.002, 0.001, 0.0005)


class _FitClock:
    """Seconds spent in the contour fit (the march and its measurement) during a ``with`` block.

    The NC step calls :func:`camcam.toolpath.contours.fit_contour` through that module's name; the clock
    wraps it there for the block and restores it after (a benchmark-only hook: nothing else changes).
    """

    def __enter__(self):
        import camcam.toolpath.contours as contours

        self.module, self.real, self.seconds = contours, contours.fit_contour, 0.0

        def timed(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return self.real(*args, **kwargs)
            finally:
                self.seconds += time.perf_counter() - t0

        contours.fit_contour = timed
        return self

    def __exit__(self, *exc):
        self.module.fit_contour = self.real


def arcs_table(samples=DISC_SAMPLES, tolerances=TOLERANCES) -> bool:
    """Print the arcs-vs-bound table; return whether every contour meets blocks ≤ 1.2·N_lb + 4."""
    print("| sample | contour | δ mm | arcs | lines | N_lb | blocks/N_lb | 1.2·N_lb+4 | ok | max dev mm | fit s | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    all_ok = True
    for sample in samples:
        spec = load_spec(ROOT / "samples" / f"{sample}.toml")
        built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
        for tol in tolerances:
            m = replace(spec.machining, tolerance_mm=tol, mode="arcs")
            t0 = time.perf_counter()
            with _FitClock() as clock:
                r = checked(built, m, sample)
            dt = time.perf_counter() - t0
            for c in r.contours:
                arcs, lines = c.fit.arc_blocks, c.fit.line_blocks
                nlb = c.lower_bound
                target = 1.2 * nlb + 4.0
                ok = arcs + lines <= target
                all_ok &= ok
                print(f"| {sample} | {c.label} | {tol:g} | {arcs} | {lines} | {nlb:.2f} | {(arcs + lines) / nlb:.3f} | "
                      f"{target:.1f} | {'yes' if ok else 'NO'} | {c.deviation.max_deviation_mm:.5f} | {clock.seconds:.2f} | "
                      f"{dt:.2f} |",
                      flush=True)
    print(f"\nevery contour within 1.2·N_lb + 4: {'yes' if all_ok else 'NO'}")
    return all_ok


def blocks_table(sample: str = "disc-translating-roller") -> None:
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    curve = built.cam.offset_profile(spec.machining.tool_diameter_mm / 2)
    print(f"{sample}: tool-centre curve, post {spec.machining.post.name}")
    print("| δ mm | lines | ∫√(κ/8δ) | s | arcs | N_lb | 1.2·N_lb+4 per segment (blocks/target) | s | max dev lines, arcs mm |")
    print("|---|---|---|---|---|---|---|---|---|")
    for tol in (0.1, 0.01, 0.001):
        row = {}
        for mode in ("lines", "arcs"):
            m = replace(spec.machining, tolerance_mm=tol, mode=mode)
            t0 = time.perf_counter()
            r = checked(built, m, sample)
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
            out = subprocess.run([sys.executable, "-m", "camcam", "run", str(p), "-o", tmp, "--force"], env=env,
                                 capture_output=True, text=True, check=True).stdout
            dt = time.perf_counter() - t0
            nc = next((line[4:] for line in out.splitlines() if line.startswith("NC: ")), "")
            print(f"| {p.relative_to(ROOT)} | {dt:.2f} | {nc} |")


if __name__ == "__main__":
    if "--arcs" in sys.argv[1:]:
        sys.exit(0 if arcs_table() else 1)
    arcs_table()
    print()
    blocks_table()
    run_times()
