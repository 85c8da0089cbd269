"""The pure eccentric (Norton, Design of Machinery, Problem 15-12) against its closed form (issue 45).

The spec and the source are in tests/dynamics/data/eccentric-p15-12.toml: an eccentric of e = 20 mm with a
flat-faced translating follower moves it by exactly s = e(1 − cos θ), so force, torque, jump speed, Hertz
stress, RMS torque, the flywheel's energy and the sized spring all have closed forms.  No printed worked
example was found; this is the check the issue allows in its place (see the data file's notes).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from camcam.dynamics.cycle import analyse_dynamics, jump_speed
from camcam.dynamics.forces import forces
from camcam.dynamics.spring import size_spring
from camcam.geometry.build import build_cam
from camcam.spec import load_spec

DATA = Path(__file__).parent / "data" / "eccentric-p15-12.toml"
E = 0.020  # m
M, K, P, ZETA = 1.0, 10.0, 0.2, 0.10  # kg, N/m, N, –
C = 2 * ZETA * math.sqrt(K * M)  # N·s/m
R_DISC = 0.050  # m: base radius 30 mm + e


@pytest.fixture(scope="module")
def eccentric():
    spec = load_spec(DATA)
    program = spec.motion.program(spec.unit)
    return build_cam(spec.cam, spec.follower, program), spec.dynamics, program.rpm


def closed_force(theta, omega, c=C, k=K, p=P):
    return M * E * omega**2 * np.cos(theta) + c * E * omega * np.sin(theta) + k * E * (1 - np.cos(theta)) + p


def test_the_cam_is_the_eccentric(eccentric):
    cam, _, _ = eccentric
    t = np.linspace(0, 2 * math.pi, 721)
    s = cam.cam.program.lifts(t, 2)
    # the harmonic law over 180° is the eccentric exactly (1e-12 mm: the law's sin/cos rounding)
    assert np.allclose(s[0], 20.0 * (1 - np.cos(t)), atol=1e-12, rtol=0)
    assert np.allclose(s[2], 20.0 * np.cos(t), atol=1e-12, rtol=0)


def test_force_and_torque_against_the_closed_form(eccentric):
    cam, d, rpm = eccentric
    omega = 2 * math.pi * rpm / 60
    t = np.radians(np.arange(0.0, 360.0, 0.25))
    f = forces(cam, d, rpm, t)
    F = closed_force(t, omega)
    scale = np.max(np.abs(F))
    # 1e-9 relative: the same physics by two routes (jets of the built cam vs the closed form)
    assert np.max(np.abs(f.contact_force_n - F)) <= 1e-9 * scale
    T = F * E * np.sin(t)
    assert np.max(np.abs(f.torque_nm - T)) <= 1e-9 * np.max(np.abs(T))


def test_jump_speed_against_the_closed_form(eccentric):
    """min over θ of A cos θ + B sin θ + (k e + P) is (k e + P) − √(A² + B²), A = m e ω² − k e, B = c e ω:
    zero where m²e²u² + (c²e² − 2 m k e²) u + k²e² − (k e + P)² = 0, u = ω², at θ = atan2(−B, −A)."""
    cam, d, rpm = eccentric
    a, b, c = M * M * E * E, C * C * E * E - 2 * M * K * E * E, K * K * E * E - (K * E + P) ** 2
    u = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
    omega = math.sqrt(u)
    theta = math.atan2(-C * E * omega, -(M * E * u - K * E)) % (2 * math.pi)
    got_w, got_t = jump_speed(cam, d)
    # 1e-9: a root by the per-angle quadratic, refined in angle to 1e-12 rad; the minimum is flat in θ
    assert got_w == pytest.approx(omega, rel=1e-9)
    assert got_t == pytest.approx(theta, abs=1e-5)  # the angle of a flat minimum: √(1e-9) of its curvature
    # undamped: ω_j = √((P + 2 k e)/(m e)), at θ = 180° (Norton's P15-12 spring lets go at 52.3 rpm, far below 200)
    undamped = d.__class__(**{**d.__dict__, "damping_ratio": None})
    w0, t0 = jump_speed(cam, undamped)
    assert w0 == pytest.approx(math.sqrt((P + 2 * K * E) / (M * E)), rel=1e-12)  # 1e-12: rounding of the root
    assert t0 == pytest.approx(math.pi, abs=1e-6)  # a flat minimum, as above
    assert w0 * 60 / (2 * math.pi) == pytest.approx(52.30, abs=0.005)  # printed to 0.01 rpm


def test_hertz_flat_on_the_eccentric_circle(eccentric):
    cam, d, rpm = eccentric
    strong = d.with_spring(2.0, 100.0)  # a spring that holds at 200 rpm: contact all round
    omega = 2 * math.pi * rpm / 60
    t = np.radians(np.arange(0.0, 360.0, 5.0))
    f = forces(cam, strong, rpm, t)
    F = closed_force(t, omega, c=2 * ZETA * math.sqrt(2000.0 * M), k=2000.0, p=100.0)  # ζ of the stiffer spring
    e_star = 1 / (2 * (1 - 0.28**2) / 206.8e9)  # Pa
    p = np.sqrt(F * e_star / (math.pi * 0.010 * R_DISC)) / 1e6  # MPa; L: the disc's 10 mm
    assert np.allclose(f.contact_stress_mpa, p, rtol=1e-9, atol=0)  # 1e-9: ρ = R_b + s + s″ from jets


def test_rms_torque_and_flywheel_against_the_closed_form(eccentric):
    """Undamped: T = (A e/2) sin 2θ + C₀ e sin θ with A = m e ω² − k e, C₀ = k e + P; RMS² = ((A e/2)² + (C₀ e)²)/2;
    E(θ) = −(A e/4) cos 2θ − C₀ e cos θ, its extremes at θ = 0, π and cos θ = −C₀/A."""
    cam, d, rpm = eccentric
    strong = d.__class__(**{**d.__dict__, "damping_ratio": None}).with_spring(2.0, 100.0)
    dy = analyse_dynamics(cam, rpm, strong)
    omega = 2 * math.pi * rpm / 60
    k = 2000.0
    A, C0 = M * E * omega**2 - k * E, k * E + 100.0
    rms = math.sqrt(((A * E / 2) ** 2 + (C0 * E) ** 2) / 2)
    assert dy.rms_torque_nm == pytest.approx(rms, rel=1e-12)  # Gauss–Legendre is exact on these trig terms
    cands = [0.0, math.pi] + ([math.acos(-C0 / A)] if abs(C0 / A) <= 1 else [])
    energy = [-(A * E / 4) * math.cos(2 * t) - C0 * E * math.cos(t) for t in cands]
    assert dy.energy_fluctuation_j == pytest.approx(max(energy) - min(energy), rel=1e-12)
    assert dy.flywheel_inertia_kgm2 == pytest.approx((max(energy) - min(energy)) / (0.05 * omega**2), rel=1e-12)
    assert abs(dy.mean_power_w) < 1e-12  # no damping, no friction: no work lost over a cycle


def test_sized_spring_against_the_closed_form(eccentric):
    """Undamped, F ≥ 0 to 250 rpm: P + k·e(1 − cos θ) ≥ −m e ω² cos θ binds at θ = 180° only
    (P + 2 k e ≥ m e ω²), and the least mean spring force P + k e puts it all in the rate: k = m ω²/2, P = 0."""
    cam, d, rpm = eccentric
    bare = d.__class__(**{**d.__dict__, "damping_ratio": None, "size_spring": True})
    rate, preload = size_spring(cam, rpm, bare)
    omega = 2 * math.pi * rpm * 1.25 / 60
    exact = M * omega**2 / 2 / 1000  # N/mm
    assert rate == math.ceil(exact * 1000) / 1000 and preload == 0.0
    assert rate == 0.343  # Norton's P15-12 "respecify the spring": 0.343 N/mm and no preload hold to 250 rpm
