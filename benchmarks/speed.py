"""Wall time of camcam's commands against the time it takes to import its libraries.

    PYTHONPATH=. python benchmarks/speed.py [--repeat 3] [--only disc-translating-roller] [--busy 1]

Prints, from one run, side by side:

* the import floor: ``python -c "import numpy, scipy.interpolate, scipy.optimize,
  matplotlib.pyplot, ezdxf, trimesh"``, the libraries a run that writes every file needs;
* ``camcam --help``, ``camcam laws`` and ``camcam optimize`` (exact, Table 1), target ≤ 0.5 s;
* ``camcam run`` of every disc and cylindrical sample, and of every disc sample at
  ``tolerance = 0.001`` mm, targets ≤ 1.7 × the floor (disc) and ≤ 2.5 × (cylindrical).

Where the ``cad`` extra is installed a run writes the STEP too, and OpenCascade (OCP, about a CPU
second to import, as much as the five libraries together) is a library it needs: those runs are
judged against "import floor + OCP" (the five and OCP's modules camcam imports, in one process),
and each sample is timed once more with ``[report] step_file = false`` against the five-library
floor, the floor issue 49 states (it was written before the STEP), and once more with
``--single-process`` (every job in the run's own process: no forks, the fewest CPU seconds).

Every figure is the median of ``--repeat`` whole processes (a fresh interpreter each,
imports included), and the repeats are interleaved (commands, samples, then again) so
that a change in the machine's load hits them all alike.  Each command is timed right
after a floor of its own, and its "× floor" figures are the medians of its rounds'
ratios to that floor: on the shared machine the floor's CPU seconds read 1.17 to 2.19
within one run (2026-12-07), and a floor timed a minute earlier moved a ratio by as much
as the changes measured (``benchmarks/ab.py --floor`` pairs the same way).  Besides wall
seconds it prints CPU seconds (user + system of the process and its children): on a
shared, loaded machine the wall figures move with the load, the CPU figures much less;
a run that renders its plots concurrently uses more CPU than wall on an idle machine.
"least wall" is the CPU seconds over the machine's cores: no scheduling of that work
can end sooner, so a run whose least wall is over its target needs less CPU, not more
concurrency.  The load average is printed before and after.  No test asserts any of
these figures.

``--busy N`` runs N busy loops (Python processes spinning, each ending by itself after an hour at
most, and killed when the timing ends) beside every timed process, floor included: the shared
machine of issue 49, where a run's forked workers no longer have a core to themselves.  The
targets are then judged both ways: CPU seconds against the floor's CPU, and wall time against
the floor's wall time beside the same loops.

camcam's own bytecode is compiled first (``python -m compileall camcam``, into the
git-ignored ``__pycache__`` folders), as ``pip install`` does: with
``PYTHONDONTWRITEBYTECODE=1`` set (as on the project's machines) an editable install
would otherwise compile every camcam module again in every process.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib.util
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FLOOR = "import numpy, scipy.interpolate, scipy.optimize, matplotlib.pyplot, ezdxf, trimesh"
#: What a run that writes the STEP imports besides (the ``cad`` extra's OpenCascade, camcam/export/step*.py): one
#: shared library of about a CPU second, whichever of its modules comes first.
STEP_IMPORTS = "OCP.STEPControl, OCP.BRepAlgoAPI, OCP.BRepBuilderAPI, OCP.GeomAPI"
OPTIMIZE_FLOOR = "import numpy, highspy"
COMMAND_LIMIT_S = 0.5
RUN_LIMITS = {"disc": 1.7, "cylindrical": 2.5}
FINE_TOLERANCE_MM = 0.001


def timed(argv: list[str], env: dict, cwd: Path = ROOT) -> tuple[float, float]:
    """(wall s, CPU s) of one whole process run in ``cwd``; raises if it fails."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=cwd)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode not in (0, 3):  # 3: written but out of tolerance (the run still did all its work)
        raise SystemExit(f"{' '.join(argv)} failed ({r.returncode}): {r.stderr.strip()[-300:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


#: A busy loop's own limit (s): it ends by itself even if the benchmark is killed.
BUSY_LIMIT_S = 3600


@contextlib.contextmanager
def busy_loops(n: int):
    """``n`` processes spinning on a core each for the block's duration (killed at its end)."""
    code = f"import time\nend = time.monotonic() + {BUSY_LIMIT_S}\nwhile time.monotonic() < end:\n    pass\n"
    procs = [subprocess.Popen([sys.executable, "-c", code]) for _ in range(n)]
    try:
        yield
    finally:
        for p in procs:
            p.kill()
            p.wait()


def fine_spec(spec: Path, out_dir: Path, tolerance_mm: float = FINE_TOLERANCE_MM) -> Path:
    """A copy of ``spec`` in ``out_dir`` with ``[machining] tolerance = tolerance_mm`` (also used by ab.py)."""
    text = spec.read_text()
    fine, n = re.subn(r"(?m)^tolerance\s*=\s*[0-9.eE+-]+", f"tolerance = {tolerance_mm}", text)
    if n != 1:
        raise SystemExit(f"{spec}: expected one `tolerance = …` line, found {n}")
    path = out_dir / f"{spec.stem}-fine.toml"
    path.write_text(fine)
    return path


def no_step_spec(spec: Path, out_dir: Path) -> Path:
    """A copy of ``spec`` in ``out_dir`` with ``[report] step_file = false`` (no STEP, no OpenCascade import)."""
    text = spec.read_text()
    if re.search(r"(?m)^step_file\s*=", text):
        raise SystemExit(f"{spec}: already says step_file")
    text, n = re.subn(r"(?m)^\[report\]\s*$", "[report]\nstep_file = false", text)
    if n == 0:
        text += "\n[report]\nstep_file = false\n"
    path = out_dir / f"{spec.stem}-nostep.toml"
    path.write_text(text)
    return path


def writes_step() -> bool:
    """Whether a run writes the STEP by default here: the ``cad`` extra (OCP) is installed."""
    return importlib.util.find_spec("OCP") is not None


def _jobs(out_dir: Path, only: str | None) -> list[tuple[str, str, list[str], str]]:
    """(label, kind, argv, floor) of every timed command; kind names its target, floor the label of the import
    floor it is judged against: a run that writes the STEP needs OpenCascade's import besides the five libraries."""
    py = sys.executable
    cli = [py, "-m", "camcam"]
    jobs = [
        ("import floor", "floor", [py, "-c", FLOOR], "import floor"),
        # what `camcam optimize` cannot do without (numpy and the LP solver): its own floor
        ("import numpy, highspy", "info", [py, "-c", OPTIMIZE_FLOOR], "import floor"),
        ("camcam --help", "command", cli + ["--help"], "import floor"),
        ("camcam laws", "command", cli + ["laws"], "import floor"),
        ("camcam optimize table1 (exact)", "command", cli + ["optimize", "samples/optimize/table1.toml"], "import floor"),
    ]
    step = writes_step()
    run_floor = "import floor + OCP" if step else "import floor"
    if step:
        jobs.insert(1, ("import floor + OCP", "floor", [py, "-c", f"{FLOOR}, {STEP_IMPORTS}"], "import floor + OCP"))
    runs = []
    for spec in sorted((ROOT / "samples").glob("*.toml")):
        cam = tomllib.loads(spec.read_text()).get("cam")
        if cam is None or (only and only not in spec.stem):
            continue
        kind = "cylindrical" if cam.get("kind") == "cylindrical" else "disc"
        runs.append((f"run {spec.stem}", kind, spec, run_floor, []))
        fine = fine_spec(spec, out_dir) if kind == "disc" else spec
        at = f" @ {FINE_TOLERANCE_MM} mm" if kind == "disc" else ""
        if kind == "disc":
            runs.append((f"run {spec.stem}{at}", kind, fine, run_floor, []))
        bare = no_step_spec(fine, out_dir) if step else fine
        if step:
            runs.append((f"run {spec.stem}{at}, no STEP", kind, bare, "import floor", []))
        # every job in the run's own process (camcam run --single-process): the fewest CPU seconds
        runs.append((f"run {spec.stem}{at}{', no STEP' if step else ''}, --single-process", kind, bare, "import floor",
                     ["--single-process"]))
    for k, (label, kind, spec, floor, extra) in enumerate(runs):
        jobs.append((label, kind, cli + ["run", str(spec), "-o", str(out_dir / f"out{k}"), "--force", *extra], floor))
    return jobs


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3, help="processes per figure (median), default 3")
    ap.add_argument("--only", help="time only the samples whose name contains this")
    ap.add_argument("--busy", type=int, default=0, help="busy loops beside every timed process (default 0)")
    args = ap.parse_args()
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "camcam")], check=True)
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, Python {sys.version.split()[0]}, "
          f"load average before {os.getloadavg()[0]:.2f}, PYTHONDONTWRITEBYTECODE={os.environ.get('PYTHONDONTWRITEBYTECODE', '')!r}, "
          f"{args.busy} busy loop(s) beside")
    with tempfile.TemporaryDirectory() as d, busy_loops(args.busy):
        jobs = _jobs(Path(d), args.only)
        wall: dict[str, list[float]] = {label: [] for label, _, _, _ in jobs}
        cpu: dict[str, list[float]] = {label: [] for label, _, _, _ in jobs}
        # each run's figures over those of its floor timed just before it: (wall ratio, CPU ratio) per round
        ratios: dict[str, list[tuple[float, float]]] = {label: [] for label, _, _, _ in jobs}
        floors = {label: argv for label, kind, argv, _ in jobs if kind == "floor"}
        for _ in range(args.repeat):
            for label, kind, argv, floor_label in jobs:
                fw, fc = timed(floors[floor_label], env) if kind != "floor" else (None, None)
                w, c = timed(argv, env)
                wall[label].append(w)
                cpu[label].append(c)
                if fw is not None:
                    wall[floor_label].append(fw)
                    cpu[floor_label].append(fc)
                    ratios[label].append((w / fw, c / fc))
    med = {k: statistics.median(v) for k, v in wall.items()}
    medc = {k: statistics.median(v) for k, v in cpu.items()}
    cores = os.cpu_count() or 1
    print(f"\n| what | wall s | × floor | CPU s | CPU × floor CPU | least wall s (CPU / {cores}) | least × floor | target | "
          f"wall met | CPU met |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label, kind, _, floor_label in jobs:
        w, c = med[label], medc[label]
        floor = med[floor_label]
        # over the floor: the median of the rounds' ratios, each to the floor timed just before (a floor is 1)
        x_wall = statistics.median(r[0] for r in ratios[label]) if ratios[label] else 1.0
        x_cpu = statistics.median(r[1] for r in ratios[label]) if ratios[label] else 1.0
        if kind in ("floor", "info"):
            target, ok, ok_cpu = "", "", ""
        elif kind == "command":
            target, ok, ok_cpu = f"≤ {COMMAND_LIMIT_S} s", "yes" if w <= COMMAND_LIMIT_S else "NO", ""
        else:
            lim = RUN_LIMITS[kind]
            target = f"≤ {lim} × {floor_label}"
            ok, ok_cpu = ("yes" if x_wall <= lim else "NO"), ("yes" if x_cpu <= lim else "NO")
        print(f"| {label} | {w:.2f} | {x_wall:.2f} | {c:.2f} | {x_cpu:.2f} | {c / cores:.2f} | "
              f"{c / cores / floor:.2f} | {target} | {ok} | {ok_cpu} |")
    print(f"\nfloors: {len(cpu['import floor'])} timed, CPU s {min(cpu['import floor']):.2f} … {max(cpu['import floor']):.2f}")
    print(f"\nload average after {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
