"""What writing the STEP (issue 48) adds to `camcam run`: wall and CPU seconds, with and without OpenCascade.

    PYTHONPATH=. python benchmarks/step_cost.py [--repeat 5] [SAMPLE ...]

Each sample is run with the cad extra (the run writes ``<name>.step``) and with OCP's import blocked
(``sys.modules["OCP"] = None``: the run writes everything else and prints one note), alternately, so
that the shared machine's load hits both alike; the medians of the wall seconds and of the CPU
seconds of the run and its children (``RUSAGE_CHILDREN``) are printed, and their differences.  Then,
in this process, the parts of the STEP's cost: OCP's import, the solid, the file.  SAMPLE defaults
to the default disc and the face-groove cam.  No test asserts any of these figures.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ("disc-translating-roller", "disc-groove")
_RUN = """import runpy, sys
if sys.argv[1] == "blocked":
    sys.modules["OCP"] = None
sys.argv = ["camcam", "run", sys.argv[2], "-o", sys.argv[3], "--force"]
runpy.run_module("camcam", run_name="__main__")
"""


def _one(mode: str, spec: Path, out: Path) -> tuple[float, float]:
    """(wall s, CPU s) of one run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", _RUN, mode, str(spec), str(out)], capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode not in (0, 3):
        raise SystemExit(f"camcam run {spec.name} ({mode}) failed ({r.returncode}): {r.stderr.strip()[-300:]}")
    wrote = any(p.suffix == ".step" for p in out.iterdir())
    if wrote != (mode == "cad"):
        raise SystemExit(f"camcam run {spec.name} ({mode}) {'did not write' if mode == 'cad' else 'wrote'} a STEP")
    return wall, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def _parts(name: str) -> str:
    """OCP's import, the solid and the file, in this process (seconds)."""
    import importlib

    t0 = time.perf_counter()
    importlib.import_module("OCP.STEPControl")
    t1 = time.perf_counter()
    from camcam.export.step import step_bytes
    from camcam.export.step_solids import cam_solid
    from camcam.geometry.build import build_cam
    from camcam.spec import load_spec

    spec = load_spec(ROOT / "samples" / f"{name}.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    t2 = time.perf_counter()
    solid = cam_solid(built)
    t3 = time.perf_counter()
    data = step_bytes(solid, spec.name)
    t4 = time.perf_counter()
    return (f"{name}: import OCP {t1 - t0:.2f} s (first sample only), solid {t3 - t2:.2f} s, file {t4 - t3:.2f} s, "
            f"{len(data) / 1e3:.0f} kB")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("samples", nargs="*", default=list(SAMPLES), help="sample names under samples/")
    ap.add_argument("--repeat", type=int, default=5, help="runs per mode and sample (default 5)")
    args = ap.parse_args()
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {args.repeat} alternated runs per mode, medians")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.samples:
            spec = ROOT / "samples" / f"{name}.toml"
            got: dict[str, list[tuple[float, float]]] = {"blocked": [], "cad": []}
            for _ in range(args.repeat):
                for mode in ("blocked", "cad"):
                    got[mode].append(_one(mode, spec, Path(tmp) / f"{name}-{mode}"))
            med = {m: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for m, v in got.items()}
            (wb, cb), (wc, cc) = med["blocked"], med["cad"]
            print(f"{name}: without STEP {wb:.2f} s wall, {cb:.2f} s CPU; with STEP {wc:.2f} s wall, {cc:.2f} s CPU; "
                  f"added {wc - wb:+.2f} s wall, {cc - cb:+.2f} s CPU")
    for name in args.samples:
        print(_parts(name))
    return 0


if __name__ == "__main__":
    sys.exit(main())
