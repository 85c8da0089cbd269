"""Large inputs (issue 16): how long `camcam fit` takes on 10⁵- and 10⁶-row lift tables.

A full revolution of the demo-like lift 5·(1 − cos θ) mm with σ = 3 µm Gaussian noise
(fixed seed), written with 6 decimals; `camcam fit` is timed in process from reading
the file to the published folder (plots included).  The faired lift is compared with
the known truth.  Run: ``PYTHONPATH=. python benchmarks/hostile_sizes.py [ROWS ...]``.
"""

from __future__ import annotations

import contextlib
import io
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from camcam.cli import main


def table(n: int, path: Path) -> np.ndarray:
    a = np.linspace(0.0, 360.0, n + 1)
    truth = 5.0 * (1.0 - np.cos(np.radians(a)))
    y = truth + np.random.default_rng(1).normal(0.0, 0.003, a.size)
    y[-1] = y[0]
    np.savetxt(path, np.column_stack([a, y]), fmt="%.6f", delimiter=",", header="angle_deg,lift_mm", comments="")
    return truth


def main_(rows: list[int]) -> None:
    print("| rows | s (read, bad points, fairing, spline, plots, files) | max error vs truth µm | rms µm |")
    print("|---|---|---|---|")
    for n in rows:
        with tempfile.TemporaryDirectory() as d:
            src = Path(d) / "t.csv"
            truth = table(n, src)
            t0 = time.perf_counter()
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()) as err:
                code = main(["fit", str(src), "-o", str(Path(d) / "out"), "--step", "0.01"])
            dt = time.perf_counter() - t0
            if code != 0:
                print(f"| {n} | exit {code}: {err.getvalue().strip()} | | |")
                continue
            got = np.loadtxt(Path(d) / "out" / "faired.csv", delimiter=",", skiprows=1)
            want = 5.0 * (1.0 - np.cos(np.radians(got[:, 0])))
            e = (got[:, 1] - want) * 1000
            print(f"| {n} | {dt:.1f} | {np.max(np.abs(e)):.2f} | {np.sqrt(np.mean(e ** 2)):.2f} |")


if __name__ == "__main__":
    main_([int(a) for a in sys.argv[1:]] or [100_000, 1_000_000])
