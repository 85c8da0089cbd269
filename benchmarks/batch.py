"""`camcam batch` of the run samples: in this process against a local Dask cluster of 2 workers.

    PYTHONPATH=. python benchmarks/batch.py [--repeat 3] [--workers 2] [--dask-of OTHER_CHECKOUT]

The samples are the ``samples/*.toml`` with a ``[cam]`` and a ``[machining]`` table: the
six disc and three cylindrical cams `camcam run` turns into NC programs (``demo.toml``
is motion only, a table and a plot: no cam to machine, so it is left out).  Each repeat
runs, in fresh processes and alternately so that a change in the machine's load hits
both alike,

* ``camcam batch SPECS -o DIR --in-process``: one spec after the other, each job forking
  its plot server, drawing child and NC helpers as `camcam run` does;
* ``camcam batch SPECS -o DIR --workers N``: a local Dask cluster of N worker processes
  (each job run in its worker alone, :func:`camcam.workers.single_process`);
* with ``--dask-of DIR``, the same on the camcam of another checkout (``git archive COMMIT``
  unpacked there, say: a before/after of a change to the batch).

Printed: the medians of wall and CPU seconds (user + system of the batch process and
every process under it), the CPU seconds per cam (the total over the number of cams:
the batch's own start, imports and cluster included), the least wall time (see
:func:`timed`: a figure the load of other users does not move), and the cluster's wall
time over the in-process one against the issue's target (≤ 0.6).

How the CPU is counted.  ``resource.getrusage(RUSAGE_CHILDREN)`` of this script, before
and after each batch, which adds a process's CPU to its parent's once the parent has
waited for it, and so, recursively, every descendant's that was waited for: the Dask
worker processes are children of the batch process (the local cluster's nannies run in
it and start the workers with ``multiprocessing``; they are joined when the cluster
closes), and their own forked children are waited for by them.  As a check that nothing
escapes (a worker not reaped, a process handed to init), the script also reads the CPU
of every process under the batch from ``/proc`` every 0.1 s while it runs (Linux only;
the last tenth of a second of each process and a process that lives less than that are
missed, so it is a lower bound): "polled" must be below the getrusage figure and, for
the cluster, whose jobs fork nothing, close to it.

The output folders are compared file by file (every file under the folder, the
manifests included: a manifest holds names, sizes and SHA-256s, no times or ids, so
nothing is excluded), every repeat of both modes against the first in-process one.
No test asserts any of these figures.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TARGET_RATIO = 0.6
#: Files left out of the comparison: none (see the module notes).
EXCLUDED: tuple[str, ...] = ()


def run_samples() -> list[Path]:
    """The samples `camcam run` machines: a ``[cam]`` and a ``[machining]`` table."""
    out = []
    for spec in sorted((ROOT / "samples").glob("*.toml")):
        t = tomllib.loads(spec.read_text())
        if "cam" in t and "machining" in t:
            out.append(spec)
    return out


def _proc_cpu(root_pid: int) -> dict[tuple[int, int], float]:
    """{(pid, start tick): user + system CPU s} of ``root_pid`` and every process under it (Linux /proc)."""
    tick = os.sysconf("SC_CLK_TCK")
    parent, cpu = {}, {}
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            raw = Path(entry.path, "stat").read_text()
        except OSError:
            continue  # ended meanwhile
        fields = raw[raw.rindex(")") + 2:].split()  # after the command name, which may hold spaces
        pid = int(entry.name)
        parent[pid] = int(fields[1])
        cpu[(pid, int(fields[19]))] = (int(fields[11]) + int(fields[12])) / tick
    under = {root_pid}
    grew = True
    while grew:
        grew = False
        for pid, ppid in parent.items():
            if ppid in under and pid not in under:
                under.add(pid)
                grew = True
    return {key: s for key, s in cpu.items() if key[0] in under}


class Poll:
    """The largest CPU seen of every process under ``pid``, read every ``every_s`` seconds in a thread."""

    def __init__(self, pid: int, every_s: float = 0.1) -> None:
        self.seen: dict[tuple[int, int], float] = {}
        self._pid, self._every = pid, every_s
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, daemon=True)
        self._thread.start()

    def _loop(self) -> None:
        while not self._stop.wait(self._every):
            for key, s in _proc_cpu(self._pid).items():
                self.seen[key] = max(s, self.seen.get(key, 0.0))

    def stop(self) -> tuple[float, float]:
        """(CPU s of all the processes seen, CPU s of the busiest one)."""
        self._stop.set()
        self._thread.join()
        return sum(self.seen.values()), max(self.seen.values(), default=0.0)


def timed(argv: list[str], root: Path) -> tuple[float, float, float, float]:
    """(wall s, CPU s by getrusage, CPU s polled from /proc, least wall s) of one whole batch with ``root``'s
    camcam (its folder is the working directory too: ``python -m`` looks there first); raises if it fails.

    The least wall is the longest any scheduling on the machine's cores could make it end: the CPU over the
    cores, or the CPU of its busiest process (the batch process in-process, a worker on the cluster), which
    runs on one core at a time, whichever is more.  Unlike the wall time, it does not move with the load
    of other users' processes (the CPU seconds do, a little: caches and memory bandwidth are shared)."""
    env = {**os.environ, "PYTHONPATH": str(root)}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=root)
    poll = Poll(proc.pid) if Path("/proc/self/stat").exists() else None
    out, err = proc.communicate()
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    polled, busiest = poll.stop() if poll is not None else (float("nan"), 0.0)
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed ({proc.returncode}): {err.strip()[-500:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, polled, max(cpu / (os.cpu_count() or 1), busiest)


def tree(root: Path) -> dict[str, bytes]:
    """Every file under ``root`` by its relative path, but the excluded names."""
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*"))
            if p.is_file() and p.name not in EXCLUDED}


def differences(a: dict[str, bytes], b: dict[str, bytes]) -> list[str]:
    """The relative paths whose bytes differ or that only one side has."""
    return sorted(k for k in a.keys() | b.keys() if a.get(k) != b.get(k))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3, help="batches per mode (median), default 3")
    ap.add_argument("--workers", type=int, default=2, help="worker processes of the local cluster, default 2")
    ap.add_argument("--dask-of", type=Path, help="also the cluster batch on this checkout's camcam")
    args = ap.parse_args()
    roots = {"": ROOT} | ({f" ({args.dask_of})": args.dask_of.resolve()} if args.dask_of else {})
    for root in roots.values():
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(root / "camcam")], check=True)
    specs = run_samples()
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs, Python {sys.version.split()[0]}, "
          f"load average before {os.getloadavg()[0]:.2f}; {len(specs)} samples: {', '.join(s.stem for s in specs)}")
    modes = {"in-process": (ROOT, ["--in-process"])}
    for tag, root in roots.items():
        modes[f"Dask, {args.workers} workers{tag}"] = (root, ["--workers", str(args.workers)])
    figures: dict[str, list[tuple[float, float, float, float]]] = {m: [] for m in modes}
    with tempfile.TemporaryDirectory() as d:
        reference: dict[str, bytes] | None = None
        differing: dict[str, set[str]] = {m: set() for m in modes}
        for k in range(args.repeat):
            for m, (mode, (root, flags)) in enumerate(modes.items()):
                folder = Path(d) / f"{k}-{m}"
                argv = [sys.executable, "-m", "camcam", "batch", *map(str, specs), "-o", str(folder), *flags]
                figures[mode].append(timed(argv, root))
                w, c, p, least = figures[mode][-1]
                print(f"  repeat {k + 1} {mode}: {w:.2f} s wall, {c:.2f} CPU s (polled {p:.2f}), least wall {least:.2f} s, "
                      f"load {os.getloadavg()[0]:.2f}", flush=True)
                files = tree(folder)
                if reference is None:
                    reference = files
                differing[mode].update(differences(reference, files))
    n = len(specs)
    med = {m: tuple(statistics.median(f[i] for f in figs) for i in range(4)) for m, figs in figures.items()}
    base_wall, base_cpu, base_least = med["in-process"][0], med["in-process"][1], med["in-process"][3]
    print(f"\n| mode | wall s | CPU s | CPU s polled | CPU s per cam | least wall s | wall × in-process | "
          f"CPU × in-process | least wall × in-process | target wall ≤ {TARGET_RATIO} × | met | files differing from in-process |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for mode in modes:
        w, c, p, least = med[mode]
        ratio = w / base_wall
        target = f"≤ {TARGET_RATIO * base_wall:.2f} s" if mode != "in-process" else ""
        met = ("yes" if ratio <= TARGET_RATIO else "NO") if mode != "in-process" else ""
        diff = ", ".join(sorted(differing[mode])[:5]) or "none"
        print(f"| {mode} | {w:.2f} | {c:.2f} | {p:.2f} | {c / n:.2f} | {least:.2f} | {ratio:.2f} | {c / base_cpu:.2f} | "
              f"{least / base_least:.2f} | {target} | "
              f"{met} | {diff} |")
    print(f"\n{len(reference or {})} files compared in each of {args.repeat * len(modes)} output folders; "
          f"load average after {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
