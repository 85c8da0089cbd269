"""Generate samples/lift/noisy-lift.csv: a known motion program measured badly.

Truth: the demo program (modified-sine rise of 10 mm over 0–120°, dwell to
180°, cycloidal return over 180–300°, dwell to 360°), sampled at every whole
degree, plus Gaussian noise of σ = 3 µm (numpy default_rng(20240611)) and
four spikes of 35–50 µm; lifts written with 5 decimals (0.01 µm).  Run from the repository
root: ``PYTHONPATH=. python samples/lift/make_noisy_lift.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell

SEED = 20240611
NOISE_MM = 0.003
#: (angle in degrees, spike in mm)
SPIKES = ((47.0, 0.040), (151.0, -0.035), (233.0, 0.050), (329.0, -0.035))


def truth_program(rise_mm: float = 10.0) -> MotionProgram:
    return MotionProgram(
        (
            Segment(make_law("modified-sine"), 0, 120, rise_mm, base=0.0),
            Segment(dwell(), 120, 180, 0.0, base=rise_mm),
            Segment(make_law("cycloidal"), 180, 300, -rise_mm, base=rise_mm),
            Segment(dwell(), 300, 360, 0.0, base=0.0),
        ),
        rpm=120,
    )


def noisy_table(seed: int = SEED, noise_mm: float = NOISE_MM, spikes=SPIKES) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(angles_deg, truth_mm, measured_mm) at 0, 1, …, 360°; the measurement closes at 360°."""
    ang = np.arange(0.0, 361.0, 1.0)
    truth = truth_program().lift(np.radians(ang))
    truth[-1] = truth[0]
    rng = np.random.default_rng(seed)
    meas = truth + rng.normal(0.0, noise_mm, ang.size)
    for a, s in spikes:
        meas[int(a)] += s
    meas[-1] = meas[0]
    return ang, truth, np.round(meas, 5)


def main(path: str) -> None:
    ang, _, meas = noisy_table()
    lines = ["angle_deg, lift_mm"] + [f"{a:g}, {h:.5f}" for a, h in zip(ang, meas)]
    Path(path).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else str(Path(__file__).with_name("noisy-lift.csv")))
