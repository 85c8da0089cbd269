"""Round trips: design → measured points (forward geometry, uneven, noisy, shuffled) → reverse → design."""

from __future__ import annotations

import numpy as np
import pytest

from camcam.errors import GeometryError
from camcam.reverse import MeasuredPoints, ReverseOptions, design_motion, reverse_design
from camcam.reverse.synth import measure_cylindrical, measure_disc

from .conftest import spec_cam

ANG = np.arange(360.0)


def errors(res, prog, kind):
    return [float(np.abs(res.motion(ANG, k) - design_motion(prog, kind, ANG, k)).max()) for k in range(3)]


def peaks(prog, kind):
    return [float(np.abs(design_motion(prog, kind, ANG, k)).max()) for k in range(3)]


def pts(xyz):
    return MeasuredPoints(np.round(xyz, 6), tuple(range(2, xyz.shape[0] + 2)), "p.csv")


DISC = ["disc-translating-roller.toml", "disc-oscillating-roller.toml", "disc-translating-flat.toml", "disc-oscillating-flat.toml"]


@pytest.mark.parametrize("name", DISC)
def test_disc_exact_points(name):
    spec, prog, cam = spec_cam(name)
    rng = np.random.default_rng(11)
    res = reverse_design(pts(measure_disc(cam, 360, rng, shuffle=True)), spec.cam, spec.follower, ReverseOptions(smoothing=False))
    e = errors(res, prog, "disc")
    # exact points (to 1 nm) at ~1° uneven spacing: the quintic profile fit and the periodic cubic
    # lift spline leave ~1e-5; bounds ~5x the worst measured (7e-6, 2.4e-5, 8.8e-5)
    assert e[0] < 4e-5 and e[1] < 1.2e-4 and e[2] < 5e-4, e


@pytest.mark.parametrize("name", DISC)
def test_disc_noisy_points(name):
    spec, prog, cam = spec_cam(name)
    rng = np.random.default_rng(12)
    res = reverse_design(pts(measure_disc(cam, 360, rng, noise_mm=0.002, shuffle=True)), spec.cam, spec.follower)
    e = errors(res, prog, "disc")
    # ±2 µm noise, GCV smoothing: worst measured over the four followers 1.8e-3, 1.1e-3, 1.1e-3; bounds ~2x
    assert e[0] < 4e-3 and e[1] < 2.5e-3 and e[2] < 2.5e-3, e


@pytest.mark.parametrize("name,flank,on_surface", [
    ("reverse/seed002.toml", 0, True), ("reverse/seed002.toml", 1, False),
    ("cylindrical-translating.toml", 0, True), ("cylindrical-translating.toml", 1, True),
])
def test_cylindrical_round_trip(name, flank, on_surface):
    spec, prog, cam = spec_cam(name)
    rng = np.random.default_rng(13)
    xyz = measure_cylindrical(cam, 180, rng, flank=flank, on_surface=on_surface, shuffle=True)
    res = reverse_design(pts(xyz), spec.cam, spec.follower, ReverseOptions(flank=flank, smoothing=False))
    e, pk = errors(res, prog, "cylindrical"), peaks(prog, "cylindrical")
    # 180 exact points at ~2° spacing: the B-spline's interpolation error dominates (seed cam:
    # 1.2e-4 deg, 1.6e-4 deg/deg, 5.7e-4 deg/deg² = 1e-5, 4e-4, 3e-2 of the peaks); bounds ~3x
    assert e[0] < 3e-5 * pk[0] and e[1] < 1.5e-3 * pk[1] and e[2] < 0.1 * pk[2], (e, pk)
    # seed 002's per-point velocity (eq. 18, corrected) against the design: within 1e-3 of the peak
    dv = res.point_velocity - design_motion(prog, "cylindrical", res.point_angles_deg, 1)
    assert np.abs(dv).max() < 1e-3 * pk[1]


def test_points_not_covering_the_revolution():
    spec, prog, cam = spec_cam("disc-translating-roller.toml")
    xy = cam.profile.evaluate(np.radians(np.arange(0.0, 300.0, 1.0)))
    with pytest.raises(GeometryError, match=r"do not cover the revolution: no point between cam angles 299\.\d\d° and 359\.\d\d° \(a gap of 6\d\.\d\d°, at most 20° allowed\)"):
        reverse_design(pts(xy), spec.cam, spec.follower)


def test_points_inside_the_base_circle():
    spec, prog, cam = spec_cam("disc-translating-roller.toml")
    xy = measure_disc(cam, 200, np.random.default_rng(1))
    bigger = type(spec.cam)(**{**spec.cam.__dict__, "base_radius": 42.0})
    with pytest.raises(GeometryError, match=r"inside the base circle .* do not fit cam.base_radius = 42 mm"):
        reverse_design(pts(xy), bigger, spec.follower)


def test_arm_cannot_reach():
    spec, prog, cam = spec_cam("disc-oscillating-roller.toml")
    xy = measure_disc(cam, 200, np.random.default_rng(2))
    f = spec.follower
    # the arm still reaches the base pitch circle (radius 50 mm) but not the top of the lift
    short = type(f)(**{**f.__dict__, "pivot_distance": 40.0, "arm_length": 15.0})
    with pytest.raises(GeometryError, match=r"does not fit the follower: the arm of 15 mm pivoting 40 mm .* cannot reach"):
        reverse_design(pts(xy), spec.cam, short)


def test_cylinder_points_the_follower_cannot_touch(seed002):
    spec, prog, cam = seed002
    xyz = measure_cylindrical(cam, 120, np.random.default_rng(3))
    xyz[:, 0] += 400.0  # far beyond the arm's reach along the axis
    with pytest.raises(GeometryError, match=r"^p\.csv row \d+ \(.*\) cannot be touched by this follower"):
        reverse_design(pts(xyz), spec.cam, spec.follower)
