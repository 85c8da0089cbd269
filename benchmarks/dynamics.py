"""What the dynamics (issue 45) add to `camcam run`: each samples/dynamics spec with and without its [dynamics] table.

    PYTHONPATH=. python benchmarks/dynamics.py [--repeat 5]

For every spec in samples/dynamics/ it times whole `camcam run` processes of the spec as is and of a copy
without its [dynamics] table (the same cam, program and files but the dynamics' own), interleaved so that
the machine's load hits both alike, and prints the medians of wall and CPU seconds, the difference and its
share of the run without dynamics (the issue's target: under 10 %).  It also times analyse_dynamics itself
in this process (median of --repeat calls after one warm-up).  No test asserts these figures.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from speed import timed  # noqa: E402  (a script beside this one: one whole process's wall and CPU seconds)

TARGET = 0.10


def without_dynamics(spec: Path, out_dir: Path) -> Path:
    """A copy of ``spec`` without its [dynamics] table (the last table of every sample)."""
    text = spec.read_text()
    path = out_dir / f"{spec.stem}-plain.toml"
    path.write_text(text[:text.index("[dynamics]")])
    return path


def in_process(spec: Path, repeat: int) -> float:
    from camcam.dynamics.cycle import analyse_dynamics
    from camcam.geometry.build import build_cam
    from camcam.spec import load_spec

    s = load_spec(spec)
    program = s.motion.program(s.unit)
    built = build_cam(s.cam, s.follower, program)
    analyse_dynamics(built, program.rpm, s.dynamics)
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        analyse_dynamics(built, program.rpm, s.dynamics)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5, help="processes per figure (median), default 5")
    args = ap.parse_args()
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "camcam")], check=True)
    specs = sorted((ROOT / "samples" / "dynamics").glob("*.toml"))
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, Python "
          f"{sys.version.split()[0]}, load average before {os.getloadavg()[0]:.2f}")
    cli = [sys.executable, "-m", "camcam", "run"]
    with tempfile.TemporaryDirectory() as d:
        out = Path(d)
        pairs = [(spec, without_dynamics(spec, out)) for spec in specs]
        wall = {p: [] for pair in pairs for p in pair}
        cpu = {p: [] for pair in pairs for p in pair}
        for _ in range(args.repeat):
            for k, pair in enumerate(pairs):
                for j, p in enumerate(pair):
                    w, c = timed(cli + [str(p), "-o", str(out / f"o{k}-{j}"), "--force"], env)
                    wall[p].append(w)
                    cpu[p].append(c)
    print("\n| sample | run s | without [dynamics] s | added s | added share | CPU added s | analyse_dynamics s | met |")
    print("|---|---|---|---|---|---|---|---|")
    for spec, plain in pairs:
        w1, w0 = statistics.median(wall[spec]), statistics.median(wall[plain])
        c1, c0 = statistics.median(cpu[spec]), statistics.median(cpu[plain])
        share = (w1 - w0) / w0
        print(f"| dynamics/{spec.stem} | {w1:.2f} | {w0:.2f} | {w1 - w0:+.2f} | {share:+.1%} | {c1 - c0:+.2f} | "
              f"{in_process(spec, args.repeat):.3f} | {'yes' if share < TARGET else 'NO'} |")
    print(f"\nload average after {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
