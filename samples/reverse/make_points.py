"""Generate the reverse-design samples' measured points from camcam's own forward geometry.

* ``seed002-points.csv``: seed 002's Table 1 cylindrical cam (``seed002.toml``), 180 points on
  flank 0 at uneven cam angles (2° steps, each moved by up to ±0.7°), on the cylinder of radius
  75 mm (the seed's cross-section d − r), written to 1 nm.
* ``seed002-noisy-points.csv``: the same points with every coordinate moved by up to ±2 µm
  (uniform).
* ``disc-points.csv``: the disc cam of ``disc.toml`` (offset translating roller), 240 profile
  points at uneven angles, ±2 µm noise, in random order.

numpy ``default_rng(SEED)``; run from the repository root:
``PYTHONPATH=. python samples/reverse/make_points.py``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from camcam.geometry.build import build_cam
from camcam.reverse.synth import measure_cylindrical, measure_disc
from camcam.spec import load_spec

SEED = 20020607
HERE = Path(__file__).resolve().parent
NOISE_MM = 0.002


def built(name: str):
    spec = load_spec(HERE / name)
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit)).cam


def seed002_points(noise_mm: float = 0.0, seed: int = SEED) -> np.ndarray:
    """The 180 flank points (the noise is drawn after the angles, so both files share them)."""
    rng = np.random.default_rng(seed)
    clean = measure_cylindrical(built("seed002.toml"), 180, rng, jitter=0.35)
    return clean + rng.uniform(-noise_mm, noise_mm, clean.shape) if noise_mm else clean


def disc_points(seed: int = SEED) -> np.ndarray:
    return measure_disc(built("disc.toml"), 240, np.random.default_rng(seed + 1), NOISE_MM, shuffle=True)


def write(path: Path, pts: np.ndarray) -> None:
    names = "x, y, z" if pts.shape[1] == 3 else "x, y"
    path.write_text(names + "\n" + "\n".join(", ".join(f"{v:.6f}" for v in p) for p in pts) + "\n")


def main() -> None:
    write(HERE / "seed002-points.csv", seed002_points())
    write(HERE / "seed002-noisy-points.csv", seed002_points(NOISE_MM))
    write(HERE / "disc-points.csv", disc_points())


if __name__ == "__main__":
    main()
