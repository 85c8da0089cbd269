"""Where a `camcam run` spends its time: every process it forks, when it starts and ends, its CPU seconds.

    PYTHONPATH=. python benchmarks/timeline.py SPEC [--tolerance MM]

Runs ``camcam run SPEC`` once in this process's child (a fresh interpreter, as `camcam` itself runs)
with a benchmark-only hook: each forked process says what it runs (the function a
:func:`camcam.workers.later` job, a :func:`~camcam.workers.parallel_map` worker or a
:mod:`camcam.workers` child was given), when it was forked and when it left, its CPU seconds and
how many of them went to imports (the outermost ``importlib._bootstrap._find_and_load`` of each module not yet
loaded: a module the parent loaded before the fork costs its child nothing), to the kernel (system time: a
forked child's copy-on-write faults among it) and to its cyclic garbage collector (a ``gc.callbacks`` hook); the run's own steps
(``Progress.step``) and each job a server child ran (its plots, the drawing) are timed too.  Seconds count from the start of the timed
interpreter's first line (its own start-up, about 0.03 s, is before it).  ``--tolerance`` runs a copy of the spec at
that ``[machining] tolerance`` (speed.py's copy).  A child that is killed (a run's children when
it fails) has no end or CPU figure.

`benchmarks/speed.py` says whether a run meets its target; this says why not: a run whose CPU over
the two cores is over its target needs less work, and the table shows whose.  The hooks cost a few
milliseconds; no test asserts any of these figures.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from speed import fine_spec  # noqa: E402  (a script beside this one)

#: Runs in the timed child: installs the hooks, then `camcam run` (each event one line on stderr, "@@" first).
HOOKED_RUN = r"""
import gc, os, sys, time
T0 = time.time()
label = ["camcam run"]
collecting = [0.0, 0.0]  # this process's seconds in the cyclic collector; when the current collection began

def say(*words):
    os.write(2, ("@@ " + " ".join(str(w) for w in words) + "\n").encode())

def collector(phase, info):
    if phase == "start":
        collecting[1] = time.process_time()
    else:
        collecting[0] += time.process_time() - collecting[1]

gc.callbacks.append(collector)

import importlib._bootstrap as bootstrap
importing = [0.0, 0]  # this process's CPU seconds in imports (outermost only), and the depth of the current one
real_find_and_load = bootstrap._find_and_load

def find_and_load(*args, **kwargs):
    importing[1] += 1
    c = time.process_time() if importing[1] == 1 else 0.0
    try:
        return real_find_and_load(*args, **kwargs)
    finally:
        importing[1] -= 1
        if importing[1] == 0:
            importing[0] += time.process_time() - c

bootstrap._find_and_load = find_and_load

def after_fork():
    collecting[0] = 0.0
    importing[0] = 0.0
    say("fork", os.getpid(), os.getppid(), f"{time.time() - T0:.3f}", label[0])

os.register_at_fork(after_in_child=after_fork)
real_exit = os._exit

def bye():
    say("exit", os.getpid(), f"{time.time() - T0:.3f}", f"{time.process_time():.3f}", f"{collecting[0]:.3f}",
        f"{importing[0]:.3f}", f"{os.times().system:.3f}")

def leave(status):
    bye()
    real_exit(status)

os._exit = leave

import camcam.workers.children as forked
import camcam.workers.servers as servers
from camcam.cli import progress

def named(fn):
    return getattr(fn, "__qualname__", None) or type(fn).__name__

real_later = forked.later

def later(fn, *args, **kwargs):
    inner = args[0] if named(fn) == "_take" else fn
    label[0] = ("parallel_map worker " if named(fn) == "_take" else "") + named(inner)
    try:
        return real_later(fn, *args, **kwargs)
    finally:
        label[0] = "camcam run"

forked.later = later
real_call = servers.call_target

def call_target(target, *args, **kwargs):
    t, c = time.time() - T0, time.process_time()
    try:
        return real_call(target, *args, **kwargs)
    finally:
        say("job", os.getpid(), f"{t:.3f}", f"{time.time() - T0:.3f}", f"{time.process_time() - c:.3f}", target)

servers.call_target = call_target
for cls, what in ((servers.Server, "plot server"), (servers.Prepared, "drawing (prepared child)")):
    def init(self, *args, _real=cls.__init__, _what=what, **kwargs):
        label[0] = _what
        try:
            _real(self, *args, **kwargs)
        finally:
            label[0] = "camcam run"
    cls.__init__ = init

real_step = progress.Progress.step

def step(self, what, *args, **kwargs):
    from contextlib import contextmanager

    @contextmanager
    def timed():
        t = time.time() - T0
        with real_step(self, what, *args, **kwargs):
            yield
        say("step", f"{t:.3f}", f"{time.time() - T0:.3f}", what)
    return timed()

progress.Progress.step = step
from camcam.cli import main
status = main(sys.argv[1:])
bye()
sys.exit(status)
"""


def timeline(spec: Path) -> str:
    """The table of one run of ``spec`` (markdown)."""
    with tempfile.TemporaryDirectory() as out:
        r = subprocess.run([sys.executable, "-c", HOOKED_RUN, "run", str(spec), "-o", out, "--force"],
                           capture_output=True, text=True, cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
    if r.returncode not in (0, 3):
        raise SystemExit(f"camcam run {spec} failed ({r.returncode}): {r.stderr.strip()[-300:]}")
    procs: dict[int, dict] = {}
    steps = []
    jobs = []  # (pid, start, end, CPU, target) of each server job
    main_pid = None
    for line in r.stderr.splitlines():
        if not line.startswith("@@ "):
            continue
        kind, *rest = line[3:].split(" ", {"fork": 4, "job": 5, "exit": 6}.get(line[3:].split(" ", 1)[0], 3))
        if kind == "fork":
            pid, parent, at, what = int(rest[0]), int(rest[1]), float(rest[2]), rest[3]
            procs[pid] = {"what": what, "parent": parent, "start": at}
        elif kind == "exit":
            pid, at, cpu, gc_s, imp, system = (int(rest[0]), *map(float, rest[1:6]))
            if pid not in procs:  # the run's own process says only its exit
                main_pid = pid
                procs[pid] = {"what": "camcam run (the fitting process)", "parent": None, "start": 0.0}
            procs[pid].update(end=at, cpu=cpu, gc=gc_s, imports=imp, system=system)
        elif kind == "step":
            steps.append((float(rest[0]), float(rest[1]), rest[2]))
        elif kind == "job":
            jobs.append((int(rest[0]), float(rest[1]), float(rest[2]), float(rest[3]), rest[4]))
    names = {main_pid: "run"}
    for k, pid in enumerate(p for p in procs if p != main_pid):
        names[pid] = f"c{k + 1}"
    rows = ["| process | forked by | what it runs | start s | end s | CPU s | of it imports s | of it system s | of it GC s |",
            "|---|---|---|---|---|---|---|---|---|"]
    for pid, p in sorted(procs.items(), key=lambda kv: kv[1]["start"]):
        end = f"{p['end']:.2f}" if "end" in p else "killed"
        cpu = f"{p['cpu']:.2f}" if "cpu" in p else ""
        gc_s = f"{p['gc']:.3f}" if "gc" in p else ""
        imp = f"{p['imports']:.2f}" if "imports" in p else ""
        system = f"{p['system']:.2f}" if "system" in p else ""
        rows.append(f"| {names[pid]} | {names.get(p['parent'], '') if p['parent'] else ''} | {p['what']} | "
                    f"{p['start']:.2f} | {end} | {cpu} | {imp} | {system} | {gc_s} |")
    total = sum(p.get("cpu", 0.0) for p in procs.values())
    collected = sum(p.get("gc", 0.0) for p in procs.values())
    imported = sum(p.get("imports", 0.0) for p in procs.values())
    system = sum(p.get("system", 0.0) for p in procs.values())
    rows.append(f"\nCPU of the processes that ended: {total:.2f} s, of it imports {imported:.2f} s, the kernel (system time) "
                f"{system:.2f} s, the cyclic garbage collector {collected:.3f} s\n")
    rows += ["| the run's step | start s | end s |", "|---|---|---|"]
    rows += [f"| {what} | {a:.2f} | {b:.2f} |" for a, b, what in steps]
    rows += ["", "| server job | process | start s | end s | CPU s |", "|---|---|---|---|---|"]
    rows += [f"| {target} | {names.get(pid, pid)} | {a:.2f} | {b:.2f} | {cpu:.2f} |" for pid, a, b, cpu, target in jobs]
    return "\n".join(rows)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("spec", type=Path)
    ap.add_argument("--tolerance", type=float, help="run a copy of the spec at this [machining] tolerance (mm)")
    args = ap.parse_args()
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "camcam")], check=True)
    with tempfile.TemporaryDirectory() as d:
        spec = fine_spec(args.spec.resolve(), Path(d), args.tolerance) if args.tolerance else args.spec.resolve()
        print(timeline(spec))


if __name__ == "__main__":
    main()
