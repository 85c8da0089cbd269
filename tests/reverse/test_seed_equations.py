"""Seed 002's equations against the forward geometry: eq. 3, eq. 13 (corrected), eqs. 14–18 via the solve."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.reverse.cylindrical import BarrelFollower, flank_tangents, solve_cylindrical
from camcam.reverse.slopes import central_difference
from camcam.reverse.synth import measure_cylindrical


@settings(max_examples=40, deadline=None)
@given(st.floats(0.1, 5.0), st.floats(0.1, 5.0), st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3))
def test_eq3_exact_for_quadratics(h1, h2, a, b, c):
    f = lambda x: a * x * x + b * x + c  # noqa: E731
    # eq. 3 is exact for quadratics: only float rounding remains (relative 1e-9 of the scale)
    assert abs(central_difference(f(-h1), f(0.0), f(h2), h1, h2) - b) < 1e-9 * (1 + abs(a) * 25 + abs(b))


def test_solve_recovers_forward_angles_and_seed_eq13(seed002):
    spec, prog, cam = seed002
    rng = np.random.default_rng(7)
    theta = np.sort(rng.uniform(0, 2 * math.pi, 150))
    P = cam.flank(0, cam.reference_radius).evaluate(theta)  # seed 002's measuring line: the cross-section r
    phi = np.mod(np.arctan2(P[:, 2], P[:, 1]), 2 * math.pi)
    o = np.argsort(phi)
    P, phi, theta = P[o], phi[o], theta[o]
    f = BarrelFollower(roller_radius=cam.roller_radius, length=cam.length, rotation=cam.rotation,
                       pivot_distance=cam.follower.pivot_distance, flank=0)
    sol = solve_cylindrical(f, P, flank_tangents(phi, P[:, 0], np.hypot(P[:, 1], P[:, 2])))
    lo, hi = prog.extremes(0)
    # cam angle and follower angle per point: with random (not jittered) spacing, gaps up to ~8°,
    # the quintic slope fit's error moves the solved point by up to ~1e-4 rad / 4e-5 deg
    assert np.abs(np.angle(np.exp(1j * (sol.cam_angle - theta)))).max() < 5e-4
    assert np.abs(np.degrees(sol.q) - (prog.lift(theta) - 0.5 * (lo.value + hi.value))).max() < 1e-4
    # the solved cross-section is the one measured (arm distance r = 170 mm), to 1 µm
    assert np.abs(sol.ell - cam.follower.arm_length).max() < 1e-3
    # eq. 13 as printed (tan φz = f′/cos θf) and with the projection the other way (f′·cos θf) both
    # miss the exact contact angle by ~1e-2 in tan α on the forward geometry (the roller offset moves
    # the contact off the mid-plane), i.e. a cam-angle error r_r·δα/R ≈ 0.1°: hence the exact condition
    printed = np.abs(np.abs(np.tan(sol.alpha)) - np.abs(sol.slope / np.cos(sol.q)))
    projected = np.abs(np.abs(np.tan(sol.alpha)) - np.abs(sol.slope * np.cos(sol.q)))
    assert printed.max() > 1e-2 and projected.max() > 1e-2


def test_per_point_velocity_matches_design(seed002):
    spec, prog, cam = seed002
    P = measure_cylindrical(cam, 180, np.random.default_rng(8))
    phi = np.mod(np.arctan2(P[:, 2], P[:, 1]), 2 * math.pi)
    f = BarrelFollower(roller_radius=cam.roller_radius, length=cam.length, rotation=cam.rotation,
                       pivot_distance=cam.follower.pivot_distance, flank=0)
    sol = solve_cylindrical(f, P, flank_tangents(phi, P[:, 0], np.hypot(P[:, 1], P[:, 2]), "central"))
    # eqs. 16–18 with the seed's three-point slopes: dθf/dθc within 2% of the peak 0.43
    assert np.abs(sol.dq - np.radians(prog.lift(sol.cam_angle, 1))).max() < 0.02 * 0.43
