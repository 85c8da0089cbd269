import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "samples" / "lift"))

from make_noisy_lift import noisy_table, truth_program  # noqa: E402

from camcam.lifttable.table import LiftTable  # noqa: E402


@pytest.fixture(scope="module")
def truth():
    return truth_program()


def make_table(seed, noise_mm=0.003, spikes=None):
    kw = {} if spikes is None else {"spikes": spikes}
    ang, tru, meas = noisy_table(seed=seed, noise_mm=noise_mm, **kw)
    return LiftTable(tuple(ang), tuple(meas), "t.csv", resolution=1e-5), tru
