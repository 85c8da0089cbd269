"""Wall-clock time of `camcam run` on every run sample (a fresh process each, imports included).

    PYTHONPATH=. python benchmarks/samples.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    specs = sorted(p for p in (ROOT / "samples").rglob("*.toml") if "motion" in tomllib.loads(p.read_text()))
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    print(f"{'sample':42s} {'seconds':>8s}")
    for spec in specs:
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            r = subprocess.run([sys.executable, "-m", "camcam", "run", str(spec), "-o", d], capture_output=True, text=True, env=env)
            dt = time.perf_counter() - t0
        status = "" if r.returncode == 0 else f"  FAILED: {r.stderr.strip()[-120:]}"
        print(f"{str(spec.relative_to(ROOT / 'samples')):42s} {dt:8.2f}{status}")


if __name__ == "__main__":
    main()
