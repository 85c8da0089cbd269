"""Forces, torque, Hertz stress, jump speed and spring sizing, each against a second method (issue 45)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from camcam.dynamics.cycle import analyse_dynamics, jump_speed
from camcam.dynamics.forces import coefficients, first_root, forces
from camcam.dynamics.spring import least_mean_spring, size_spring
from camcam.dynamics.train import MATERIALS, Material
from camcam.errors import SpecError
from camcam.geometry.analysis import convex_curvature, flat_radius
from tests.dynamics.cams import SAMPLES, built, train

THETA = np.radians(np.arange(0.0, 360.0, 0.05))


@pytest.mark.parametrize("name", SAMPLES)
def test_torque_is_the_power_balance(name):
    """T = F_n × (the normal's lever arm about the cam axis) equals Q·dq/dθ without friction."""
    cam, rpm = built(name)
    d = train(name, damping_n_s_per_m=40.0)
    f = forces(cam, d, rpm, THETA)
    scale = np.max(np.abs(f.torque_nm))
    assert scale > 0
    # 1e-9 relative (the bound): two routes through different geometry, both exact to rounding
    assert np.max(np.abs(f.torque_nm - f.torque_power_balance_nm)) <= 1e-9 * scale


def test_torque_with_friction_costs_power():
    """Guide friction takes power on the rise and the return alike: the mean torque is positive and the rise's torque larger."""
    cam, rpm = built("disc-translating-roller")
    d0, d1 = train("disc-translating-roller"), train("disc-translating-roller", friction=0.2)
    f0, f1 = forces(cam, d0, rpm, THETA), forces(cam, d1, rpm, THETA)
    rising = coefficients(cam, d0, THETA).rate > 0
    assert np.all(f1.contact_force_n[rising] >= f0.contact_force_n[rising])
    assert np.mean(f1.torque_nm) > 0 and abs(np.mean(f0.torque_nm)) < 1e-9 * np.max(np.abs(f0.torque_nm))
    # the translating roller's friction model by hand at one angle: F_n (cos φ − μ sgn(v)|sin φ|) = Q
    k = coefficients(cam, d1, THETA)
    i = int(np.argmax(np.abs(k.sin_phi) * rising))
    q = f1.generalised[i]
    by_hand = q / (k.cos_phi[i] - 0.2 * np.abs(k.sin_phi[i]))
    assert f1.contact_force_n[i] == pytest.approx(by_hand, rel=1e-12)  # the same formula: rounding only


def test_friction_that_locks_the_guide_is_bad_input():
    cam, rpm = built("disc-translating-roller")
    with pytest.raises(SpecError, match=r"^dynamics\.friction: 3 locks the follower in its guide at cam angle"):
        analyse_dynamics(cam, rpm, train("disc-translating-roller", friction=3.0))


@pytest.mark.parametrize("name", ["disc-translating-roller", "disc-oscillating-roller", "disc-groove"])
def test_hertz_by_hand(name):
    """p_max = √(F E*/(π L R′)) with 1/R′ = 1/r + 1/ρ, ρ the profile's own radius (not the pitch formula)."""
    cam, rpm = built(name)
    d = train(name, cam_material=MATERIALS["cast-iron"], follower_material=MATERIALS["steel"])
    t = np.radians(np.array([15.0, 60.0, 100.0, 200.0, 250.0]))
    f = forces(cam, d, rpm, t)
    profile = cam.cam.profile  # a face groove's inner flank
    kappa = convex_curvature(profile, cam.cam.sigma, t)[0]
    r = cam.cam.roller_radius
    e_star = 1.0 / ((1 - 0.26**2) / 103.4e3 + (1 - 0.28**2) / 206.8e3)  # MPa, the two presets by hand
    inner = f.contact_force_n >= 0
    p = np.sqrt(np.abs(f.contact_force_n) * e_star / (math.pi * 10.0) * (1.0 / r + kappa))
    # a groove's outer flank (F < 0): the pitch curve offset outwards, ρ = ρ_pitch + r on the concave side
    if not inner.all():
        kp = convex_curvature(cam.cam.pitch, cam.cam.sigma, t)[0]
        outer = np.sqrt(np.abs(f.contact_force_n) * e_star / (math.pi * 10.0) * (1.0 / r - kp / (1 + r * kp)))
        p = np.where(inner, p, outer)
    # 1e-9: two curvature routes (profile offset jets vs pitch-curve formula), equal to rounding
    assert np.allclose(f.contact_stress_mpa, p, rtol=1e-9, atol=0)


def test_hertz_flat_face_on_a_curve():
    cam, rpm = built("disc-translating-flat")
    d = train("disc-translating-flat")
    t = np.radians(np.array([30.0, 90.0, 210.0]))
    f = forces(cam, d, rpm, t)
    rho = flat_radius(cam.cam, t)[0]  # R_b + s + s″ for a translating flat face
    e_star = 0.5 * 206.8e3 / (1 - 0.28**2)
    p = np.sqrt(f.contact_force_n * e_star / (math.pi * 12.0 * rho))  # L: the cam's thickness, 12 mm
    assert np.allclose(f.contact_stress_mpa, p, rtol=1e-12, atol=0)  # the same formula: rounding only


@pytest.mark.parametrize("a, b, c", [(-1.0, 0.0, 4.0), (-1.0, 3.0, 4.0), (-1.0, -3.0, 4.0), (2.0, -9.0, 4.0),
                                     (2.0, -1.0, 4.0), (0.0, -2.0, 4.0), (1.0, 1.0, 1.0), (0.0, 0.0, 1.0),
                                     (-1e-12, 1e3, 1e-3), (1.0, -1e4, 1e-6)])
def test_first_root_is_the_smallest_positive_root(a, b, c):
    roots = np.roots([a, b, c]) if a else np.roots([b, c]) if b else np.array([])
    pos = sorted(r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and r.real > 0)
    want = pos[0] if pos else math.inf
    got = float(first_root(a, b, c))
    # 1e-9 relative: np.roots (companion eigenvalues) is the loose one of the two
    assert got == want if math.isinf(want) else got == pytest.approx(want, rel=1e-9)


def _min_contact(cam, d, rpm, theta):
    return float(np.min(forces(cam, d, rpm, theta).contact_force_n))


@pytest.mark.parametrize("name, damping", [("disc-translating-roller", 0.0), ("disc-translating-roller", 60.0),
                                           ("disc-oscillating-roller", 0.0), ("disc-oscillating-flat", 15.0),
                                           ("disc-translating-flat", 0.0)])
def test_jump_speed_against_a_brute_force_sweep(name, damping):
    """The root per angle against sweeping the rpm in 0.5 rpm steps with the force on a 0.02° grid."""
    cam, rpm = built(name)
    d = train(name, damping_n_s_per_m=damping)
    omega, theta = jump_speed(cam, d)
    jump = omega * 60 / (2 * math.pi)
    fine = np.radians(np.arange(0.0, 360.0, 0.02))
    sweep = np.arange(math.floor(jump) - 20, math.floor(jump) + 20, 0.5)
    first = next(r for r in sweep if _min_contact(cam, d, r, fine) < 0)
    # the sweep finds the first 0.5-rpm step past the jump; the 0.02° grid can miss the worst angle by
    # O(step²) of the force, far below what half an rpm moves it
    assert first - 0.5 < jump <= first + 1e-9
    # and at the jump angle itself the force is zero at the jump speed, positive a hair below
    at = np.array([theta])
    assert abs(forces(cam, d, jump, at).contact_force_n[0]) < 1e-9 * d.preload_n  # a root: rounding only
    assert _min_contact(cam, d, jump * (1 - 1e-6), fine) > 0


def test_grooved_cams_never_jump_and_load_both_flanks():
    for name in ("disc-groove", "cylindrical-translating", "cylindrical-oscillating"):
        cam, rpm = built(name)
        dy = analyse_dynamics(cam, rpm, train(name))
        assert dy.positive_drive and dy.jump_rpm is None
        assert dy.lift_flank_force_n.max() > 0 and dy.return_flank_force_n.max() > 0
        # each angle loads one flank: the signed contact force is the lift flank's minus the return flank's
        assert np.array_equal(dy.lift_flank_force_n - dy.return_flank_force_n, dy.contact_force_n)


@pytest.mark.parametrize("name", ["disc-translating-roller", "disc-oscillating-roller", "disc-translating-flat",
                                  "disc-oscillating-flat"])
@pytest.mark.parametrize("least", [0.0, 5.0])
def test_sized_spring_holds_to_overspeed_and_5_percent_less_does_not(name, least):
    cam, rpm = built(name)
    d = train(name, size_spring=True, spring_rate_n_per_mm=0.0, preload_n=0.0, min_contact_force_n=least,
              external_load_n=2.0)
    rate, preload = size_spring(cam, rpm, d)
    fine = np.radians(np.arange(0.0, 360.0, 0.02))
    over = rpm * d.overspeed
    held = d.with_spring(rate, preload)
    speeds = np.linspace(0.0, over, 11)
    # the sized spring keeps F_n ≥ F_min at every speed up to the overspeed (1e-9 N: rounding of the sums)
    assert min(_min_contact(cam, held, s, fine) for s in speeds) >= least - 1e-9
    weak = d.with_spring(0.95 * rate, 0.95 * preload)
    assert min(_min_contact(cam, weak, s, fine) for s in speeds) < least
    if least == 0.0:
        w, _ = jump_speed(cam, held)
        assert w * 60 / (2 * math.pi) >= over * (1 - 1e-12)  # the rounding up only raises it


def test_least_mean_spring_is_the_linear_program():
    """The hull walk against HiGHS on random constraint sets."""
    from scipy.optimize import linprog

    rng = np.random.default_rng(45)
    for _ in range(200):
        n = int(rng.integers(2, 40))
        x, r, xm = rng.uniform(0, 20, n), rng.normal(0, 10, n), float(rng.uniform(0, 20))
        k, p = least_mean_spring(x, r, xm)
        res = linprog([xm, 1], A_ub=-np.column_stack([x, np.ones(n)]), b_ub=-r, bounds=[(0, None), (0, None)],
                      method="highs")
        # HiGHS's optimality tolerance is 1e-7 relative; the hull walk is exact to rounding
        assert p + k * xm == pytest.approx(res.fun, rel=1e-7, abs=1e-9)
        assert np.all(p + k * x >= r - 1e-9 * max(1.0, np.abs(r).max()))  # feasible to rounding


def test_spring_that_cannot_hold_at_rest_is_bad_input():
    cam, rpm = built("disc-translating-roller")
    d = train("disc-translating-roller", preload_n=5.0, external_load_n=-10.0)  # the load pulls the follower off
    with pytest.raises(SpecError, match=r"^dynamics\.preload_n: 5 N: the spring cannot hold .* expected at least 10 N$"):
        analyse_dynamics(cam, rpm, d)


def test_figures_are_consistent():
    cam, rpm = built("disc-translating-roller")
    dy = analyse_dynamics(cam, rpm, train("disc-translating-roller", speed_fluctuation=0.02))
    fig = dy.figures()
    # the refined extremes bound the 0.5° arrays (1e-12: the refinement only improves on a sample)
    assert fig["max_contact_force_n"] >= dy.contact_force_n.max() - 1e-12
    assert fig["min_contact_force_n"] <= dy.contact_force_n.min() + 1e-12
    assert fig["max_torque_nm"] >= np.abs(dy.torque_nm).max() - 1e-12
    assert fig["max_contact_stress_mpa"] >= dy.contact_stress_mpa.max() - 1e-12
    # RMS and mean from Gauss–Legendre against a fine trapezoid (1e-6: the trapezoid's error at 0.01°)
    fine = np.radians(np.arange(0.0, 360.0 + 1e-9, 0.01))
    T = forces(cam, dy.spec, rpm, fine).torque_nm
    assert dy.rms_torque_nm == pytest.approx(math.sqrt(np.trapezoid(T * T, fine) / (2 * math.pi)), rel=1e-6)
    # the flywheel: ΔE from the cumulative trapezoid (1e-6 relative, the same reason)
    E = np.concatenate([[0.0], np.cumsum(0.5 * (T[1:] + T[:-1]) * np.diff(fine))])
    E -= fine * (E[-1] / (2 * math.pi))
    assert dy.energy_fluctuation_j == pytest.approx(E.max() - E.min(), rel=1e-6)
    omega = 4 * math.pi
    assert dy.flywheel_inertia_kgm2 == pytest.approx(dy.energy_fluctuation_j / (0.02 * omega**2), rel=1e-15)


def test_custom_material():
    m = Material("custom", 100.0, 0.25)
    cam, rpm = built("disc-translating-roller")
    dy = analyse_dynamics(cam, rpm, train("disc-translating-roller", cam_material=m, follower_material=m))
    assert dy.contact_modulus_mpa == pytest.approx(0.5 * 100e3 / (1 - 0.0625), rel=1e-15)  # rounding only
