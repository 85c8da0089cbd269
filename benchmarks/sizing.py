"""Sizing sweep speed: a 10,000-design disc sweep on one core, and designs per second on Dask
with 1 and 2 workers.

    PYTHONPATH=. python benchmarks/sizing.py [--designs 10000] [--repeat 3]

The sweep is samples/size/translating-roller.toml's motion and constraints with
base radius × offset cut to the asked number of designs (3,600 cam-angle samples
a revolution).  "evaluate" is the closed-form evaluation of every design (the part
that scales with the sweep: sampling the motion once and the exact check of the
best design are reported apart); each figure is the best of ``--repeat`` runs
(the machine is shared: the load average is printed beside the figures, and the
in-process CPU time, which load inflates far less than the wall time).  The Dask runs start their LocalCluster first and warm it
up with one sweep, so the figures are the work, not the start-up.
"""

from __future__ import annotations

import argparse
import logging
import math
import os
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def sweep_spec(designs: int):
    from camcam.spec import load_spec
    from camcam.spec.size import SizeAxis

    spec = load_spec(ROOT / "samples" / "size" / "translating-roller.toml")
    side = int(math.ceil(math.sqrt(designs)))
    rb = tuple(round(10.0 + 0.5 * i, 9) for i in range(side))
    e = tuple(round(-10.0 + 20.0 * i / side, 9) for i in range(int(math.ceil(designs / side))))
    size = replace(spec.size, axes=(SizeAxis("base_radius", rb), SizeAxis("offset", e), SizeAxis("roller_radius", (10.0,))),
                   laws=())
    return replace(spec, size=size)


def timed(fn, repeat: int) -> tuple[float, float]:
    """(best wall seconds, CPU seconds of that run in this process)."""
    best = (math.inf, math.inf)
    for _ in range(repeat):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        best = min(best, (time.perf_counter() - t0, time.process_time() - c0))
    return best


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--designs", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()

    from camcam.geometry.disc import SIGMA
    from camcam.dask_batch.engine import DaskExecutor, InProcess
    from camcam.sizing.grid import DesignGrid
    from camcam.sizing.samples import sample_program
    from camcam.sizing.sweep import SweepContext, evaluate_chunk, run_sweep

    load0 = os.getloadavg()[0]
    spec = sweep_spec(a.designs)
    grid = DesignGrid.of(spec.size)
    n = len(grid)
    t0 = time.perf_counter()
    samples = (sample_program(spec.motion.program("mm"), spec.size.samples),)
    t_sample = time.perf_counter() - t0
    ctx = SweepContext(spec.follower.kind, SIGMA[spec.cam.rotation], grid, samples)
    chunks = grid.chunks()
    rows = []
    wall, cpu = timed(lambda: InProcess().map(evaluate_chunk, chunks, ctx=ctx), a.repeat)
    rows.append(("in-process (one core)", wall, n / wall))
    c0, t0 = time.process_time(), time.perf_counter()
    result = run_sweep(spec, InProcess())
    t_all, c_all = time.perf_counter() - t0, time.process_time() - c0
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        Client = None
    if Client is not None:
        for workers in (1, 2):
            with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                              silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
                ex = DaskExecutor(client, f"{workers}")
                ex.map(evaluate_chunk, chunks, ctx=ctx)  # warm-up: imports, first scatter
                w, _ = timed(lambda: ex.map(evaluate_chunk, chunks, ctx=ctx), a.repeat)
                rows.append((f"Dask LocalCluster, {workers} worker{'s' if workers > 1 else ''}", w, n / w))
    print(f"{n:,} designs ({spec.size.samples} cam-angle samples a revolution, {len(chunks)} chunks of up to 512); "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores (before: {load0:.1f})")
    print(f"motion sampled once: {t_sample * 1000:.0f} ms; whole in-process sweep with the exact check of the best: {t_all:.2f} s "
          f"wall, {c_all:.2f} s CPU ({len(result.checked)} exact check{'s' if len(result.checked) != 1 else ''})")
    print(f"in-process evaluate: {cpu:.2f} s of CPU ({n / cpu:,.0f} designs per CPU-second)")
    print()
    print("| engine | evaluate (s) | designs/s |")
    print("|---|---:|---:|")
    for label, w, rate in rows:
        print(f"| {label} | {w:.2f} | {rate:,.0f} |")
    dask = [r for r in rows if r[0].startswith("Dask")]
    if len(dask) == 2:
        print(f"\n2-worker speed-up over 1 worker: {dask[1][2] / dask[0][2]:.2f}×")


if __name__ == "__main__":
    main()
