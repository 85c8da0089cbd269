"""`camcam reverse` on files at the row cap and on rows that are not a profile (issue 50 item 5).

Both ended in ``ValueError: Seems like the problem is ill-posed`` from SciPy's smoothing spline
(exit 1): 199 999 measured points (neighbours 1e-10 rad apart, 6e5 padded knots), and a disc's
(radians, radius) rows read as x, y (every point within 84°–90° of polar angle).  Now close
points are averaged and a large file is fitted on at most MAX_FIT_POINTS averaged points, and
rows that do not go round the cam axis are one exit-2 line saying so.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from camcam.cli import main
from camcam.reverse.design import MAX_FIT_POINTS, _polar_order
from camcam.reverse.points import MeasuredPoints
from camcam.reverse.synth import measure_cylindrical, measure_disc

from .conftest import ROOT, spec_cam

SAMPLES = ROOT / "samples" / "reverse"
DATA = ROOT / "tests" / "reverse" / "data"
N = 199_999  # one under the data files' 200 000-row cap, as in the issue


def _write(path, header: str, pts: np.ndarray) -> None:
    np.savetxt(path, pts, fmt="%.6f", delimiter=",", header=header, comments="")  # 1 nm, as a CMM export


def test_disc_at_the_row_cap(tmp_path, capsys):
    _, _, cam = spec_cam("reverse/disc.toml")
    _write(tmp_path / "p.csv", "x,y", measure_disc(cam, N, np.random.default_rng(1), noise_mm=0.002))
    rc = main(["reverse", str(tmp_path / "p.csv"), "--spec", str(SAMPLES / "disc.toml"), "-o", str(tmp_path / "o"), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["points"] == N and 0.99 * MAX_FIT_POINTS < out["points_fitted"] <= MAX_FIT_POINTS  # runs of 40 points
    # ±2 µm noise: measured 1.5e-4 mm, 1.8e-4 mm/deg, 3.8e-4 mm/deg² (the 240-point sample: 2.1e-3, 1.1e-3,
    # 9.5e-4); bound: the noise amplitude itself, which 200 000 points must beat
    assert out["max_lift_error"] < 0.002 and out["max_velocity_error"] < 0.002 and out["max_acceleration_error"] < 0.002


def test_cylinder_at_the_row_cap(tmp_path, capsys):
    _, _, cam = spec_cam("reverse/seed002.toml")
    _write(tmp_path / "p.csv", "x,y,z", measure_cylindrical(cam, N, np.random.default_rng(1), noise_mm=0.002))
    rc = main(["reverse", str(tmp_path / "p.csv"), "--spec", str(SAMPLES / "seed002.toml"), "-o", str(tmp_path / "o"), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["points"] == N and 0.99 * MAX_FIT_POINTS < out["points_fitted"] <= MAX_FIT_POINTS  # runs of 40 points
    # measured 7.0e-5 deg, 1.4e-4 deg/deg, 5.0e-4 deg/deg²; bound: seed 002's own figures (0.0023, 0.001, 0.018)
    assert out["max_lift_error"] < 0.0023 and out["max_velocity_error"] < 0.001 and out["max_acceleration_error"] < 0.018


def test_radians_written_as_x(tmp_path, capsys):
    """A disc's (polar angle in radians, radius) rows under an x, y header: one line saying what is wrong.

    ``data/radians-as-x.csv``: 240 points of samples/reverse/disc.toml's cam (±2 µm noise) as
    (atan2(y, x) mod 2π, √(x² + y²)); before, SciPy's GCV raised "the problem is ill-posed" (exit 1)."""
    rc = main(["reverse", str(DATA / "radians-as-x.csv"), "--spec", str(SAMPLES / "disc.toml"), "-o", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 2 and len(err.splitlines()) == 1 and not (tmp_path / "o").exists()
    assert err.startswith("camcam: error: radians-as-x.csv: the points do not go round the cam axis: their polar "
                          "angles about it all lie from 83.67° to 89.98° (no point in the other 353.68°; "
                          "x 0.0158 … 6.28 mm, y 40 … 59.93 mm)")
    assert "the x column holds values within ±2π only, like angles in radians" in err


def test_points_on_one_side_of_the_axis(tmp_path, capsys):
    """Half a measured profile (no point in 200° of polar angle): refused before any fit, no hint about radians."""
    pts = np.loadtxt(SAMPLES / "disc-points.csv", delimiter=",", skiprows=1)
    phi = np.degrees(np.mod(np.arctan2(pts[:, 1], pts[:, 0]), 2 * math.pi))
    _write(tmp_path / "half.csv", "x,y", pts[(phi < 100) | (phi > 300)])
    rc = main(["reverse", str(tmp_path / "half.csv"), "--spec", str(SAMPLES / "disc.toml"), "-o", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 2 and len(err.splitlines()) == 1
    assert "the points do not go round the cam axis" in err and "radians" not in err


@pytest.mark.parametrize("wrap", [False, True])
def test_close_points_are_averaged(wrap):
    """Two points 1e-10 rad apart (as in the 199 999-point file) become one, also across φ = 0."""
    if wrap:  # a point at φ = 0 and one 1e-10 below 2π
        phi = np.append(np.linspace(0.0, 2 * math.pi, 40, endpoint=False), 2 * math.pi - 1e-10)
    else:
        phi = np.linspace(0.0, 2 * math.pi, 40, endpoint=False) + 0.01
        phi = np.append(phi, phi[5] + 1e-10)
    r = 50.0 + np.arange(phi.size) * 0.001
    xy = np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1)
    pts = MeasuredPoints(xy, tuple(range(2, phi.size + 2)), "p.csv")
    order, got_phi, got = _polar_order(pts, xy, (0, 1), merge=True)
    assert got.shape == (40, 2) and np.all(np.diff(got_phi) > 0)
    j = 0 if wrap else 5
    k = int(np.argmin(np.abs(np.angle(np.exp(1j * (got_phi - phi[j]))))))
    # the merged point is the mean of the two (1e-12 mm: float rounding of coordinates near 50 mm)
    assert np.abs(got[k] - 0.5 * (xy[j] + xy[-1])).max() < 1e-12
    assert order[k] in (j, phi.size - 1)
    # without smoothing nothing is averaged: two points 1e-10 apart stay two
    assert _polar_order(pts, xy, (0, 1), merge=False)[2].shape == (41, 2)


def test_smoothing_falls_back_when_scipy_gives_up():
    """A dense probe dwell (40 points 1e-5 rad apart) among 120 even ones: SciPy's GCV raises "ill-posed";
    the profile fit takes the banded route instead and still follows the curve."""
    from scipy.interpolate import make_smoothing_spline

    from camcam.reverse.slopes import periodic_fit

    two_pi = 2 * math.pi
    phi = np.sort(np.concatenate([np.linspace(0, two_pi, 120, endpoint=False) + 0.01, 1.0 + 1e-5 * np.arange(1, 40)]))
    r = 50 + 5 * np.sin(phi) + np.random.default_rng(0).uniform(-0.002, 0.002, phi.size)
    with pytest.raises(ValueError, match="ill-posed"):
        make_smoothing_spline(np.concatenate([phi - two_pi, phi, phi + two_pi]), np.tile(r, 3))
    g = np.linspace(0, two_pi, 1000)
    # measured 2.2e-3 mm against the truth with ±2e-3 mm noise; bound: twice the noise amplitude
    assert np.abs(periodic_fit(phi, r, True)(g) - (50 + 5 * np.sin(g))).max() < 0.004
