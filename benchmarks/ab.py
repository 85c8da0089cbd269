"""Wall time and CPU seconds of `camcam run` on this tree against an earlier commit, the two alternated.

    PYTHONPATH=. python benchmarks/ab.py REV [--repeat 6] [--no-step] [--floor] [SAMPLE ...]

`benchmarks/speed.py` gives ratios to the import floor from one run; on a shared
machine those move by ±15 % from one run to the next (the floor itself was 2.38,
2.69 and 2.91 s within one hour here), so a change of 10 % is not visible in them.
This script checks REV out into a temporary git worktree and runs each sample
with the two trees alternately (old, new, old, new, …), so the machine's load
hits both alike, then prints the sorted wall seconds and the medians.  Both use
this tree's interpreter and libraries; each tree's bytecode is compiled first
(as in speed.py).  A SAMPLE written NAME@TOL runs at ``tolerance = TOL`` mm
(speed.py's copy of the spec); ``--no-step`` runs every spec with ``[report] step_file = false`` (speed.py's
copy).  CPU seconds are user + system of the run and every process it forked (the children's rusage), the
figure issue 49 judges on a shared machine; ``--floor`` times the import floor (speed.py's) before each pair
too and prints each tree's CPU over the floor's of its round, the median of the rounds.  SAMPLE defaults to the default disc, disc-groove and
cylindrical-translating-small-tool.  No test asserts any of these figures.
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
sys.path.insert(0, str(ROOT / "benchmarks"))
from speed import FLOOR, fine_spec, no_step_spec, timed  # noqa: E402  (a script beside this one)
SAMPLES = ("disc-translating-roller", "disc-groove", "cylindrical-translating-small-tool")


def _timed(tree: Path, spec: Path, out: Path) -> tuple[float, float]:
    """Wall and CPU seconds of one `camcam run` with ``tree``'s camcam (run from that folder: it comes first on
    sys.path); CPU is user + system of the run and all its children (speed.py's :func:`timed`)."""
    return timed([sys.executable, "-m", "camcam", "run", str(spec), "-o", str(out), "--force"], dict(os.environ), tree)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("rev", help="the earlier commit (anything git rev-parse takes)")
    ap.add_argument("samples", nargs="*", default=list(SAMPLES), help="sample names under samples/, NAME@TOL at tolerance TOL mm")
    ap.add_argument("--repeat", type=int, default=6, help="runs per tree and sample (default 6)")
    ap.add_argument("--no-step", action="store_true", help="run every spec with [report] step_file = false")
    ap.add_argument("--floor", action="store_true", help="time the import floor before each pair; print CPU over it")
    args = ap.parse_intermixed_args()
    rev = subprocess.run(["git", "rev-parse", "--short", args.rev], capture_output=True, text=True, cwd=ROOT,
                         check=True).stdout.strip()
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT,
                          check=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        old = Path(tmp) / "old"
        subprocess.run(["git", "worktree", "add", "--detach", str(old), rev], capture_output=True, cwd=ROOT, check=True)
        try:
            for tree in (old, ROOT):
                subprocess.run([sys.executable, "-m", "compileall", "-q", "camcam"], cwd=tree, check=True)
            print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {rev} against {head} (this tree's "
                  f"working files), {args.repeat} runs each, alternated\n")
            print(f"| sample | {rev} wall s (sorted) | now wall s (sorted) | median {rev} | median now | change | "
                  f"{rev} CPU s (sorted) | now CPU s (sorted) | median {rev} | median now | change |")
            print("|---|---|---|---|---|---|---|---|---|---|---|")
            for name in args.samples:
                stem, _, tol = name.partition("@")
                spec = ROOT / "samples" / f"{stem}.toml"
                if tol:
                    spec = fine_spec(spec, Path(tmp), float(tol))
                if args.no_step:
                    spec = no_step_spec(spec, Path(tmp))
                walls: dict[Path, list[float]] = {old: [], ROOT: []}
                cpus: dict[Path, list[float]] = {old: [], ROOT: []}
                floors: list[float] = []
                for _ in range(args.repeat):
                    if args.floor:
                        floors.append(timed([sys.executable, "-c", FLOOR], dict(os.environ))[1])
                    for tree in (old, ROOT):
                        wall, cpu = _timed(tree, spec, Path(tmp) / "out")
                        walls[tree].append(wall)
                        cpus[tree].append(cpu)
                cells = []
                for times in (walls, cpus):
                    a, b = statistics.median(times[old]), statistics.median(times[ROOT])
                    fmt = lambda xs: " ".join(f"{x:.2f}" for x in sorted(xs))  # noqa: E731
                    cells.append(f"{fmt(times[old])} | {fmt(times[ROOT])} | {a:.2f} | {b:.2f} | {100 * (b / a - 1):+.0f} %")
                print(f"| {name}{' (no STEP)' if args.no_step else ''} | {' | '.join(cells)} |", flush=True)
                if floors:
                    ratio = {t: statistics.median(c / f for c, f in zip(cpus[t], floors)) for t in (old, ROOT)}
                    print(f"\nimport floor {statistics.median(floors):.2f} CPU s (median of {len(floors)}); CPU over "
                          f"the floor of its round, median: {rev} {ratio[old]:.2f} x, now {ratio[ROOT]:.2f} x\n",
                          flush=True)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(old)], capture_output=True, cwd=ROOT)
    return 0


if __name__ == "__main__":
    sys.exit(main())
